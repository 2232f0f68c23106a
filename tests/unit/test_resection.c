/*
 * test_resection.c - the therapy's assessment (issue 25; therapy.h) on a
 * scripted resection of the polyps case (config/cases/polyps.case): the
 * scripted trainee (trainee.h) on the force loop in lockstep on
 * simulated time (offline.h), the paper's model (the scope stands still
 * when nothing pushes it) with the patient, her every cycle recorded as
 * the daemon records it (session_record_from_state()) into the metrics
 * (metrics_record()), the tool's inputs added to hers:
 *  - the scripted expert, polyp by polyp in the case's order: she finds
 *    it (in, steering, until the tip is 2 cm short of its place along the
 *    colon); where its base is flat, or sessile and too thick for a cold
 *    snare, the needle lifts it first; then the snare (15 mm; 20 mm for
 *    a head of 15 mm or more) is opened around it and closed, and the
 *    polyp cut: cold (closing the handle all the way) below the cold
 *    snare's 10 mm, hot otherwise (the pedal down until it is free, her
 *    foot off as it comes free); the pedunculated polyp's stump is
 *    clipped after (the clip pushed on to the wall ahead and closed: one
 *    clip counted). She aims each tool herself (trainee_aim(); the
 *    polyps stay where the case put them): the polyp's wall rolled to
 *    the channel's 5 o'clock, the tip swung with the wheels and the tool
 *    or the scope moved in until the needle's point is in the wall under
 *    the base, or the open loop's centre at the middle of the polyp's
 *    axis (the loop hangs forward from the sheath's tip in the model, so
 *    that the sheath's tip stays short of the polyp: she does not push
 *    it beyond), then she closes; at most AIM_S a tool. A cut polyp the
 *    channel takes (retrieve_max_m, tool.h: the case's 4 and 6 mm ones)
 *    she sucks out: the snare back in, the channel's exit brought to
 *    where it lies with the scope (trainee_approach()): fallen to the
 *    lowest wall of its ring, that wall where the gas holds it (tool.h;
 *    the 6 mm one lies where the lumen is collapsed to 0.6 of the
 *    case's radius), then the suction valve pressed: it is retrieved in
 *    the first cycle the valve is, the exit within retrieve_reach_m of
 *    its surface (and not before: no suction, no retrieval); a larger
 *    one she leaves lying. Every
 *    polyp of the case comes out complete (retrieved where it can be),
 *    the wall uninjured, no perforation;
 *    her times per polyp (found, aimed, lifted, cut: found to free; the
 *    retrieval from the cut) are printed next to the published ones,
 *    and each resection's time as the metrics count it (the first
 *    tool's touch to the polyp free) with the clip's; the session
 *    passes the polypectomy course (config/courses/polypectomy.course);
 *  - the careless trainee: the same session going on, the snare open
 *    and pushed against the mucosa with the pedal held: the wall
 *    injured, the patient perforated, and the course fails the session
 *    on exactly its two requirements of the wall (tool_injuries,
 *    perforations);
 *  - the fates in the END frame (metricstext_format(), parsed back
 *    alike) and in the report's table of polyps (reporttherapy.h), the
 *    retrieved ones among them;
 *  - the rules on records made for them: a polyp left, one bitten and
 *    left in place (partly), one the forceps took whole (complete, in no
 *    time), one burnt in the loop and let go uncut (partly; its
 *    cautery), one lifted and cut (its time from the lift); a bite of the
 *    mucosa, an injury, a clip counted; the same through the wire
 *    (sessionpb.h); no polyps listed without a tool in hand.
 *
 * Run from the top of the source tree (tests/run.sh does), or with
 * ENDOSIM_TOP naming it.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "base/vec3.h"
#include "conf/cases.h"
#include "model/centreline.h"
#include "model/colon.h"
#include "model/tool.h"
#include "proto/session_file.h"
#include "session/coursefile.h"
#include "session/metrics.h"
#include "session/metricstext.h"
#include "session/reporttherapy.h"
#include "session/sessionpb.h"
#include "session/therapy.h"
#include "offline.h"
#include "trainee.h"

#define CASE "config/cases/polyps.case"
#define COURSE "config/courses/polypectomy.course"
#define DT (OFFLINE_PERIOD_NS * ENDOSIM_S_PER_NS)
#define HOLD_S 0.003     /* the hand's input renewed each cycle */
#define SHEATH_M 0.010   /* the snare's sheath out of the channel */
#define NEEDLE_M 0.005   /* the needle's catheter out */
#define SHUT 0.1         /* the loop closed on a polyp, not yet cut */
#define FIND_BEFORE_M 0.02 /* the tip short of a polyp: she sees it */
#define FIND_SPEED 0.03  /* m/s: her pace */
#define FIND_STUCK_S 4.0
#define VIEW_RATE_HZ 1.0 /* the polyps and the mucosa seen: not judged
			    here, evaluated seldom (the cost) */
#define PUSH_M 0.0025    /* the tool pushed on towards the wall a step */
#define UNDER_M 0.002    /* the needle's point under a base */
#define AIM_S 20.0       /* her time to aim a tool, at most */
#define LOOP_TOL_M 0.002 /* the loop's centre off a polyp's axis' middle */
#define NEEDLE_TOL_M 0.001 /* the needle's point off its place */
#define FLAT_DEG 30.0    /* the loop over a polyp, flat to its wall within */
#define RETRIEVE_S 10.0  /* her time to suck a cut polyp out, at most */
#define OVER_M 0.0005    /* the tip's side clear of the wall by, sucking */
#define NEARER_M 0.0002  /* less nearer a waypoint: no nearer */
#define STALLED 4        /* waypoints running no nearer: as near as it comes
			    (rolling the scope to a polyp fallen to the
			    other side takes her further first) */
#define NEAR 0.6         /* of the retrieval's reach: near enough to suck */
#define SUCK_BEFORE_M 0.01 /* the tip short of a cut polyp, to suck it */

struct run {
	struct config cfg;
	struct tool_params par;
	struct trainee *tr;
	struct offline *o;  /* hers */
	struct metrics *m;
	const struct endosim_state *st;
	double depth_m, opening; /* the hand's tool now */
	double from_d, from_o, to_d, to_o, t0, t1; /* ... its move */
	bool pedal;
	unsigned events;    /* since the last look */
	int event_polyp;    /* the last event's polyp */
	double event_s;     /* ... and its time */
	int sucking;        /* the cut polyp she sucks at, -1: none */
	double gap_m;       /* the channel's exit from its body's surface */
	int sucked;         /* cycles with the suction pressed, up to its
			       retrieval */
	double retrieved_gap_m; /* the gap at its retrieval */
	int aiming;         /* the polyp she aims at (aim_polyp()), -1: none */
	double aim_along_m; /* ... the point along its axis */
	double aim_at[3];   /* ... where that point is now, m */
};

static double now_s(const struct endosim_state *s)
{
	return (double)s->stamp_ns * ENDOSIM_S_PER_NS;
}

/* The channel's exit on the scope of S from polyp I's body's surface
 * (tool.h's retrieval reach), m. */
static double exit_gap(const struct run *r, const struct endosim_state *s,
		       int i)
{
	const struct tool_polyp *p = &offline_tool(r->o)->polyp[i];
	struct tool_pose q;
	double body[3];

	tool_pose(&r->par, &s->scope, 0, &q);
	if (p->state == TOOL_POLYP_CUT || p->state == TOOL_POLYP_RETRIEVED) {
		vec3_copy(body, p->at); /* where it fell (and was sucked) */
	} else {
		tool_polyp_body(p, &r->par, body);
	}
	return vec3_dist(q.exit, body) - p->size_m / 2;
}

/* While she goes for a cut polyp: the exit's gap from it each cycle;
 * the cycles with the suction pressed up to its retrieval, and the gap
 * then. */
static void watch_retrieval(struct run *r, const struct endosim_state *s)
{
	if (r->sucking < 0) {
		return;
	}
	r->gap_m = exit_gap(r, s, r->sucking);
	if (r->retrieved_gap_m < INFINITY) {
		return;
	}
	r->sucked += (s->patient.valves & ENDOSIM_VALVE_SUCTION) != 0;
	if ((s->tool.events & ENDOSIM_TOOL_RETRIEVE) &&
	    s->tool.event_polyp == r->sucking) {
		r->retrieved_gap_m = r->gap_m;
	}
}

/*
 * After each cycle she plays: the cycle recorded; the tool's input for
 * the next, along its move (the foot off the pedal as soon as the polyp
 * comes free).
 */
static void watch(const struct endosim_state *s, void *arg)
{
	struct run *r = arg;
	struct session_record rec;
	double f = r->t1 > r->t0 ? (now_s(s) + DT - r->t0) / (r->t1 - r->t0)
				 : 1;

	r->st = s;
	if (r->aiming >= 0) {
		const struct tool_polyp *p = &offline_tool(r->o)->polyp[r->aiming];

		vec3_axpy(r->aim_at, p->base, r->aim_along_m, p->normal);
	}
	session_record_from_state(s, &rec);
	metrics_record(r->m, &rec);
	watch_retrieval(r, s);
	r->events |= s->tool.events;
	if (s->tool.events) {
		r->event_polyp = s->tool.event_polyp;
		r->event_s = now_s(s);
	}
	r->pedal &= !(s->tool.events & ENDOSIM_TOOL_CUT);
	f = fmax(0, fmin(1, f));
	r->depth_m = r->from_d + (r->to_d - r->from_d) * f;
	r->opening = r->from_o + (r->to_o - r->from_o) * f;
	offline_tool_input(r->o, r->depth_m, r->opening, r->pedal, HOLD_S);
}

/* The scripted trainee on the polyps case, the paper's model, the
 * patient; her every cycle recorded. */
static void start(struct run *r)
{
	struct metrics_params mp;
	char err[512];

	memset(r, 0, sizeof(*r));
	config_defaults(&r->cfg);
	r->cfg.haptics.model = HAPTICS_MODEL_PAPER;
	r->cfg.patient.enabled = true;
	cases_tool_params(&r->cfg, &r->par);
	r->tr = trainee_create(&r->cfg, CASE, NULL, err, sizeof(err));
	if (!r->tr) {
		fail_msg("%s", err);
	}
	r->o = trainee_offline(r->tr);
	r->st = trainee_state(r->tr);
	metrics_params_default(&mp);
	mp.view_rate_hz = VIEW_RATE_HZ;
	r->m = metrics_create(trainee_colon(r->tr), &mp);
	assert_non_null(r->m);
	r->depth_m = r->from_d = r->to_d = -SHEATH_M; /* in the channel */
	r->sucking = -1;
	r->aiming = -1;
	trainee_watch(r->tr, watch, r);
}

static void stop(struct run *r, struct metrics_result *out)
{
	metrics_result(r->m, out);
	metrics_destroy(r->m);
	trainee_destroy(r->tr);
}

/* The tool moved linearly to DEPTH_M and OPENING over S seconds, as long
 * as she holds the scope still (her waypoints': TRAINEE_STEP_S, at least
 * one). */
static void move(struct run *r, double s, double depth_m, double opening)
{
	r->from_d = r->depth_m;
	r->from_o = r->opening;
	r->to_d = depth_m;
	r->to_o = opening;
	r->t0 = now_s(r->st);
	r->t1 = r->t0 + s;
	trainee_hold(r->tr, fmax(TRAINEE_STEP_S, s));
}

static void hold(struct run *r, double s)
{
	move(r, s, r->depth_m, r->opening);
}

/* Holds until EVENT (at most S seconds); whether it came. */
static bool until(struct run *r, unsigned event, double s)
{
	r->events = 0;
	for (double t = 0; t < s && !(r->events & event);
	     t += TRAINEE_STEP_S) {
		trainee_hold(r->tr, TRAINEE_STEP_S);
	}
	return r->events & event;
}

/* The nurse hands KIND over (SNARE_M for a snare). */
static void hand_over(struct run *r, int kind, double snare_m)
{
	offline_tool_select(r->o, kind, snare_m);
	hold(r, TRAINEE_STEP_S);
	assert_int_equal(offline_tool_answer(r->o), 0);
}

/* She finds polyp I: in, steering, until the tip is FIND_BEFORE_M short
 * of it; she lets the tube settle. The seconds it took. */
static double find(struct run *r, int i)
{
	const struct anatomy *a = colon_anatomy(trainee_colon(r->tr));
	double t0 = now_s(r->st);

	assert_true(trainee_insert(r->tr, a->polyp[i].s_m - FIND_BEFORE_M,
				   FIND_SPEED, FIND_STUCK_S));
	trainee_relax(r->tr, TRAINEE_STEP_S);
	return now_s(r->st) - t0;
}

/* The tool's pose at the hand's depth now. */
static void pose(const struct run *r, struct tool_pose *out)
{
	tool_pose(&r->par, &r->st->scope, r->st->tool.depth_m, out);
}

/* She aims the point BEYOND_M ahead of the tool's tip at TARGET, on or
 * by the wall whose normal is NORMAL, within TOL_M, in at most AIM_S (the
 * tool's depth hers meanwhile); the seconds it took. */
static double aim(struct run *r, const double target[3],
		  const double normal[3], double beyond_m, double tol_m)
{
	double t0 = now_s(r->st);

	assert_true(trainee_aim(r->tr, &r->par, target, normal, &r->to_d,
				beyond_m, tol_m, AIM_S));
	return now_s(r->st) - t0;
}

/*
 * She aims the point BEYOND_M ahead of the tool's tip ALONG_M along
 * polyp I's axis from its base, within TOL_M (aim()), following it as
 * the wall moves, and the base with it (tool_follow_wall(): the
 * point kept where it is now by watch()). The seconds it took.
 */
static double aim_polyp(struct run *r, int i, double along_m,
			double beyond_m, double tol_m)
{
	const struct tool_polyp *p = &offline_tool(r->o)->polyp[i];
	double s;

	r->aiming = i;
	r->aim_along_m = along_m;
	vec3_axpy(r->aim_at, p->base, along_m, p->normal);
	s = aim(r, r->aim_at, p->normal, beyond_m, tol_m);
	r->aiming = -1;
	return s;
}

/* She brings polyp I under the open loop: its axis' middle at the loop's
 * centre, the loop lying flat over it (the polyp at the channel's clock:
 * its wall's normal within FLAT_DEG of the loop's). The seconds it
 * took. */
static double under_loop(struct run *r, int i)
{
	const struct tool_polyp *p = &offline_tool(r->o)->polyp[i];
	double h = tool_polyp_height(p, r->par.lift_m), s;
	struct tool_pose q;

	s = aim_polyp(r, i, h / 2, r->st->tool.loop_m / 2,
		      fmin(LOOP_TOL_M, h / 3));
	pose(r, &q);
	assert_true(-vec3_dot(p->normal, q.radial) >=
		    cos(FLAT_DEG * TOOL_RAD_PER_DEG));
	return s;
}

/* She brings the needle's point into the wall UNDER_M under polyp I's
 * base. The seconds it took. */
static double over_needle(struct run *r, int i)
{
	return aim_polyp(r, i, -UNDER_M, r->par.needle_m, NEEDLE_TOL_M);
}

/* The scripted times of a resection, s. */
struct times {
	double needle_s;  /* the needle aimed */
	double lift_s;    /* ... and the base lifted, from its aiming */
	double loop_s;    /* the loop aimed */
	double cut_s;     /* ... and the polyp cut, from its closing */
	double total_s;   /* from found to free */
	double retrieve_s; /* sucked out, from the cut; -1: left lying */
	double cut_at_s;  /* when it was cut (the clock's) */
};

/* The needle lifts polyp I's base: out, aimed into the wall under it,
 * the nurse injecting (as soon as its point is there: the lift may come
 * while she aims) until it lifts; back in. */
static void lift(struct run *r, int i, struct times *tm)
{
	double t0;

	hand_over(r, TOOL_NEEDLE, 0);
	move(r, 0.5, NEEDLE_M, 0);
	move(r, 0.2, NEEDLE_M, 1);
	t0 = now_s(r->st);
	r->events = 0;
	tm->needle_s = over_needle(r, i);
	assert_true((r->events & ENDOSIM_TOOL_LIFT) ||
		    until(r, ENDOSIM_TOOL_LIFT, 10));
	assert_int_equal(r->event_polyp, i);
	tm->lift_s = r->event_s - t0;
	move(r, 0.2, r->depth_m, 0);
	move(r, 0.5, -SHEATH_M, 0);
}

/* Polyp I, found, resected by the scripted expert: TM her times. */
static void resect(struct run *r, int i, struct times *tm)
{
	const struct tool_polyp *p = &offline_tool(r->o)->polyp[i];
	double th = tool_polyp_thickness(p), t0 = now_s(r->st), t1;
	bool hot = p->paris == ANATOMY_PARIS_IP || th >= r->par.cold_max_m;
	bool flat = p->paris == ANATOMY_PARIS_IIA ||
		    p->paris == ANATOMY_PARIS_IIB;

	*tm = (struct times){ .needle_s = -1, .lift_s = -1 };
	if (flat || (hot && p->paris != ANATOMY_PARIS_IP)) {
		lift(r, i, tm);
	}
	hand_over(r, TOOL_SNARE, p->size_m >= 0.015 ? 0.020 : 0.015);
	move(r, 0.5, SHEATH_M, 0);
	move(r, 0.5, SHEATH_M, 1);
	tm->loop_s = under_loop(r, i);
	hold(r, 0.05);
	t1 = now_s(r->st);
	r->events = 0;
	move(r, 0.5, r->depth_m, SHUT);
	assert_true(r->events & ENDOSIM_TOOL_CAPTURE);
	assert_int_equal(r->st->tool.captured, i);
	if (hot) {
		r->pedal = true;
		assert_true(until(r, ENDOSIM_TOOL_CUT, 20));
		r->pedal = false;
	} else {
		r->events = 0;
		move(r, 0.3, r->depth_m, 0);
		assert_true(r->events & ENDOSIM_TOOL_CUT);
	}
	assert_int_equal(r->event_polyp, i);
	assert_int_equal(r->st->tool.polyp[i].state, ENDOSIM_POLYP_CUT);
	tm->cut_s = r->event_s - t1;
	tm->total_s = r->event_s - t0;
	tm->cut_at_s = r->event_s;
	move(r, 0.5, -SHEATH_M, 0);
}

/* Where she brings the channel's exit to suck cut polyp P out: its body
 * where it fell (tool.h: on the lowest wall of its ring where the gas
 * holds it, its radius in),
 * raised towards the lumen's centre as far as the tip's side needs to
 * come clear of the wall there (the exit is the channel's offset from
 * the tip's axis, towards the wall), into X; the wall's normal there
 * into the lumen into N. */
static void suck_at(const struct run *r, const struct tool_polyp *p,
		    double x[3], double n[3])
{
	double clear = r->cfg.haptics.scope_radius_m -
		       r->par.channel_offset_m + OVER_M;
	struct centreline_point c;

	centreline_at_s(colon_centreline(trainee_colon(r->tr)), p->s_m, &c);
	vec3_sub(n, c.p, p->at);
	vec3_normalize(n);
	vec3_axpy(x, p->at, fmax(0, clear - p->size_m / 2), n);
}

/*
 * Cut polyp I sucked out through the channel where it can be (no larger
 * than the channel takes, retrieve_max_m): the tool back in, she moves
 * in, steering, until the tip is SUCK_BEFORE_M short of it along the
 * colon, then brings the channel's exit to where it lies with the scope
 * (suck_at()) until it is near (NEAR of the reach) or comes no nearer;
 * she presses the suction valve until it is gone (at most a second) and
 * lets go. A larger one she leaves lying. TM's retrieve_s: from the cut
 * to out, or -1.
 */
static void retrieve(struct run *r, int i, struct times *tm)
{
	const struct tool_polyp *p = &offline_tool(r->o)->polyp[i];
	double at[3], wall[3], was = INFINITY;
	int stalled = 0;

	tm->retrieve_s = -1;
	if (p->size_m > r->par.retrieve_max_m) {
		return;
	}
	r->events = 0;
	r->sucking = i;
	r->sucked = 0;
	r->retrieved_gap_m = INFINITY;
	r->gap_m = exit_gap(r, r->st, i);
	if (r->st->scope.tip_s_m < p->s_m - SUCK_BEFORE_M) {
		assert_true(trainee_insert(r->tr, p->s_m - SUCK_BEFORE_M,
					   FIND_SPEED, FIND_STUCK_S));
	}
	for (double s = 0; s < RETRIEVE_S &&
			   r->gap_m > NEAR * r->par.retrieve_reach_m;
	     s += TRAINEE_STEP_S) {
		suck_at(r, p, at, wall);
		trainee_approach(r->tr, &r->par, at, wall, 0,
				 TRAINEE_STEP_S);
		if (r->gap_m > was - NEARER_M) {
			if (++stalled >= STALLED) {
				break; /* as near as it comes */
			}
			continue;
		}
		stalled = 0;
		was = r->gap_m;
	}
	assert_false(r->events & ENDOSIM_TOOL_RETRIEVE); /* not unasked */
	trainee_suction(r->tr, true);
	until(r, ENDOSIM_TOOL_RETRIEVE, 1);
	trainee_suction(r->tr, false);
	hold(r, TRAINEE_STEP_S);
	r->sucking = -1;
	assert_true(r->events & ENDOSIM_TOOL_RETRIEVE);
	assert_int_equal(r->event_polyp, i);
	assert_int_equal(r->st->tool.polyp[i].state, ENDOSIM_POLYP_RETRIEVED);
	/* in the first cycle the valve was pressed, the exit within reach */
	assert_int_equal(r->sucked, 1);
	assert_true(r->retrieved_gap_m <= r->par.retrieve_reach_m);
	tm->retrieve_s = r->event_s - tm->cut_at_s;
}

/* Polyp I's scripted times, found FOUND_S after the last. */
static void print_times(int i, double found_s, const struct times *tm)
{
	char needle[160] = "no needle";
	char out[96] = "left lying (larger than the channel takes)";

	if (tm->needle_s >= 0) {
		snprintf(needle, sizeof(needle), "needle aimed %.2f s, lifted "
			 "at %.2f s (the hemostasis trainer's injection: "
			 "experts 36 s, beginners 92 s, the whole task)",
			 tm->needle_s, tm->lift_s);
	}
	if (tm->retrieve_s >= 0) {
		snprintf(out, sizeof(out), "retrieved by suction %.2f s after "
			 "the cut", tm->retrieve_s);
	}
	print_message("polyp %d: found in %.2f s; %s; loop aimed %.2f s, "
		      "cut %.2f s later: resected %.2f s after found "
		      "(published: %.0f s rotary, %.0f s standard); %s\n",
		      i + 1, found_s, needle, tm->loop_s, tm->cut_s,
		      tm->total_s, REPORTTHERAPY_ROTARY_S,
		      REPORTTHERAPY_STANDARD_S, out);
}

/* The clip's jaws' distance from the wall ahead (as the loop sees the
 * wall: tool_wall()), m. */
static double jaws_to_wall(const struct run *r)
{
	struct tool_input in = { 0 };
	struct tool_pose q;
	double jaws[3], d[3];

	pose(r, &q);
	vec3_axpy(jaws, q.tip, r->par.clip_m, q.dir);
	tool_wall(offline_colon(r->o), r->st->scope.tip_s_m + r->depth_m,
		  q.tip, r->st->patient.factor, &in);
	assert_true(in.wall);
	vec3_sub(d, jaws, in.wall_point);
	return vec3_dot(d, in.wall_normal);
}

/* A clip closed on the wall ahead (the stalk's stump, a large polyp's):
 * out, open, pushed on until its jaws are half their length from the
 * wall, closed. Returns the seconds from its handing over to placed. */
static double clip_wall(struct run *r)
{
	double t0 = now_s(r->st);
	int k;

	hand_over(r, TOOL_CLIP, 0);
	move(r, 0.5, SHEATH_M, 0);
	move(r, 0.3, SHEATH_M, 1);
	for (k = 0; k < 80 && jaws_to_wall(r) > r->par.clip_m / 2; k++) {
		move(r, TRAINEE_STEP_S, r->depth_m + PUSH_M, 1);
	}
	r->events = 0;
	move(r, 0.3, r->depth_m, 0);
	assert_true(r->events & ENDOSIM_TOOL_CLIP_PLACED);
	t0 = r->event_s - t0;
	move(r, 0.5, -SHEATH_M, 0);
	return t0;
}

/* The careless trainee's pedal held with the open snare pushed against
 * the mucosa: until the wall is injured (at most 20 cm of sheath, 1 cm a
 * second). */
static bool pedal_on_wall(struct run *r)
{
	hand_over(r, TOOL_SNARE, 0.020);
	move(r, 0.5, SHEATH_M, 1);
	r->pedal = true;
	r->events = 0;
	for (int k = 0; k < 80 && !(r->events & ENDOSIM_TOOL_INJURY); k++) {
		move(r, TRAINEE_STEP_S, r->depth_m + PUSH_M, 1);
	}
	r->pedal = false;
	hold(r, 0.5);
	return r->events & ENDOSIM_TOOL_INJURY;
}

static bool retrievable[ANATOMY_MAX_POLYPS]; /* small enough to suck out */
static double retrieve_max_m;

/*
 * The whole script on the polyps case: the expert's session into EXPERT;
 * then, the same session going on, the careless pedal on the wall, the
 * whole into CARELESS.
 */
static void script(struct metrics_result *expert_out,
		   struct metrics_result *careless_out)
{
	struct run r;
	double clip_s = -1;
	int n;

	start(&r);
	hold(&r, TRAINEE_STEP_S);
	n = (int)r.st->tool.polyps;
	assert_int_equal(n, 5);
	retrieve_max_m = r.par.retrieve_max_m;
	for (int i = 0; i < n; i++) {
		retrievable[i] = offline_tool(r.o)->polyp[i].size_m <=
				 r.par.retrieve_max_m;
	}
	for (int i = 0; i < n; i++) {
		double found_s = find(&r, i);
		struct times tm;

		resect(&r, i, &tm);
		retrieve(&r, i, &tm);
		print_times(i, found_s, &tm);
		if (offline_tool(r.o)->polyp[i].paris == ANATOMY_PARIS_IP) {
			clip_s = clip_wall(&r);
		}
	}
	print_message("the stalk's stump clipped %.2f s after the clip was "
		      "handed over (the hemostasis trainer's clip: experts "
		      "20 s, beginners 73 s)\n", clip_s);
	metrics_result(r.m, expert_out);
	assert_true(pedal_on_wall(&r));
	assert_true(r.st->patient.torn_segment >= 0);
	stop(&r, careless_out);
}

static struct metrics_result expert, careless;

static int play(void **unused)
{
	(void)unused;
	script(&expert, &careless);
	return 0;
}

/* The course's section of the polyps case. */
static const struct coursefile_case *polyps_section(struct coursefile *c)
{
	char err[256];
	const struct coursefile_case *k;

	if (coursefile_load(c, COURSE, err, sizeof(err))) {
		fail_msg("%s", err);
	}
	k = coursefile_case(c, "polyps");
	assert_non_null(k);
	return k;
}

static void test_expert_resects_all(void **unused)
{
	const struct metrics_result *m = &expert;
	struct coursefile c;
	const struct coursefile_case *k = polyps_section(&c);

	(void)unused;
	uint32_t small = 0;

	for (uint32_t i = 0; i < m->n_polyp; i++) {
		const struct metrics_polyp *p = &m->polyp[i];

		print_message("polyp %u: %s, touched at %.2f s, free %.2f s "
			      "later, cautery %.2f s\n", i + 1,
			      therapy_fate_name(p->fate), p->start_s,
			      p->cut_s - p->start_s, p->cautery_s);
		assert_int_equal(p->fate, retrievable[i] ?
				 METRICS_FATE_RETRIEVED :
				 METRICS_FATE_COMPLETE);
		assert_true(p->start_s >= 0 && p->cut_s > p->start_s);
		small += retrievable[i];
	}
	print_message("the channel takes up to %.0f mm: %u of the case's "
		      "polyps retrieved, the rest left lying\n",
		      retrieve_max_m * 1e3, small);
	assert_int_equal(small, 2); /* the case's 4 and 6 mm ones */
	assert_int_equal(m->polyps_retrieved, small);
	print_message("the expert: %u of %u resected, %.2f s a resection "
		      "(published: %.0f s rotary, %.0f s standard), cautery "
		      "%.2f s, %u injuries, %u perforations\n",
		      m->polyps_resected, m->n_polyp, m->resection_s,
		      REPORTTHERAPY_ROTARY_S, REPORTTHERAPY_STANDARD_S,
		      m->cautery_s, m->tool_injuries, m->perforations);
	assert_int_equal(m->n_polyp, 5);
	assert_int_equal(m->polyps_resected, 5);
	assert_int_equal(m->polyps_partly, 0);
	assert_int_equal(m->tool_injuries, 0);
	assert_int_equal(m->perforations, 0);
	assert_true(m->cautery_s > 0);
	assert_int_equal(m->clips, 1);
	assert_int_equal(m->biopsies, 0);
	assert_true(coursefile_passed(k, m));
}

static void test_careless_perforates(void **unused)
{
	const struct metrics_result *m = &careless;
	struct coursefile c;
	const struct coursefile_case *k = polyps_section(&c);
	char text[128];

	(void)unused;
	assert_int_equal(m->polyps_resected, 5);
	assert_int_equal(m->tool_injuries, 1);
	assert_int_equal(m->perforations, 1);
	assert_false(coursefile_passed(k, m));
	for (size_t q = 0; q < k->n_reqs; q++) {
		const char *key = k->req[q].field->key;
		bool wall = !strcmp(key, "tool_injuries") ||
			    !strcmp(key, "perforations");

		coursefile_req_text(&k->req[q], text, sizeof(text));
		print_message("careless: %s %s\n", text,
			      coursefile_met(&k->req[q], m) ? "met" : "failed");
		assert_true(coursefile_met(&k->req[q], m) == !wall);
	}
}

/* The fates through the END frame's text and back, and in the report. */
static void test_end_frame_and_report(void **unused)
{
	static char text[65536];
	struct metrics_result back;
	char *page = NULL, row[64];
	size_t size = 0;
	FILE *o;
	int n;

	(void)unused;
	n = metricstext_format(&careless, text, sizeof(text));
	assert_true(n > 0);
	assert_non_null(strstr(text, "\npolyps_resected=5\n"));
	assert_non_null(strstr(text, "\ntool_injuries=1\n"));
	assert_non_null(strstr(text, "\npolyp.4=2,"));   /* complete */
	assert_non_null(strstr(text, "\npolyp.0=3,"));   /* retrieved */
	assert_non_null(strstr(text, "\npolyps_retrieved=2\n"));
	assert_int_equal(metricstext_parse(text, &back), 0);
	assert_int_equal(back.n_polyp, careless.n_polyp);
	for (uint32_t i = 0; i < back.n_polyp; i++) {
		assert_int_equal(back.polyp[i].fate, careless.polyp[i].fate);
		assert_true(fabs(back.polyp[i].cut_s - careless.polyp[i].cut_s)
			    < 1e-6);
	}
	assert_true(fabs(back.resection_s - careless.resection_s) < 1e-6);
	o = open_memstream(&page, &size);
	assert_non_null(o);
	reporttherapy_write(o, &careless, NULL);
	fclose(o);
	for (uint32_t i = 0; i < careless.n_polyp; i++) {
		snprintf(row, sizeof(row),
			 "<tr id=\"polyp-%u\" class=\"good\">", i + 1);
		assert_non_null(strstr(page, row));
	}
	assert_non_null(strstr(page, "<tr id=\"polyp-4\" class=\"good\">"
				   "<th>4</th><td>complete</td>"));
	assert_non_null(strstr(page, "<tr id=\"polyp-1\" class=\"good\">"
				   "<th>1</th><td>retrieved</td>"));
	assert_non_null(strstr(page, "<tr id=\"polyp-3\" class=\"good\">"
				   "<th>3</th><td>retrieved</td>"));
	assert_non_null(strstr(page, "2 retrieved"));
	assert_null(strstr(page, ">left</td>"));
	assert_non_null(strstr(page, "5 of 5"));
	free(page);
}

/* A record at T s with the tool's KIND, the pedal, the polyp held and
 * EVENTS concerning POLYP. */
static void record(struct metrics *m, double t, unsigned events, int polyp,
		   int captured, bool pedal)
{
	struct session_record r = {
		.stamp_ns = OFFLINE_START_NS + (uint64_t)llround(t * 1e9),
		.tool_kind = ENDOSIM_TOOL_SNARE, .tool_pedal = pedal,
		.tool_captured = captured, .tool_events = events,
		.tool_event_polyp = polyp,
	};

	metrics_record(m, &r);
}

/*
 * The rules on records made for them (no colon: the polyps listed are
 * those the events name): polyp 0 bitten, left in place (partly); 1
 * taken whole by a bite (complete, in no time); 2 captured, burnt for
 * 0.5 s and let go (partly); 3 captured and cut a second later; 4 never
 * touched (left); 5 lifted, captured, cut a second after the lift. A bite
 * of the mucosa, an injury, a clip. Then the same through the wire.
 */
static void test_fates(void **unused)
{
	struct metrics_params mp;
	struct metrics *m;
	struct metrics_result r, back;
	static const uint32_t want[] = {
		METRICS_FATE_PARTLY, METRICS_FATE_COMPLETE,
		METRICS_FATE_PARTLY, METRICS_FATE_COMPLETE,
		METRICS_FATE_LEFT, METRICS_FATE_COMPLETE,
	};
	struct sessionpb_metrics pb;
	Endosim__SessionMetrics *un;
	uint8_t wire[8192];
	size_t len;

	(void)unused;
	metrics_params_default(&mp);
	m = metrics_create(NULL, &mp);
	assert_non_null(m);
	record(m, 0.0, 0, -1, -1, false);
	record(m, 0.2, ENDOSIM_TOOL_BITE, 0, -1, false);
	record(m, 0.4, ENDOSIM_TOOL_BITE | ENDOSIM_TOOL_CUT, 1, -1, false);
	record(m, 1.0, ENDOSIM_TOOL_CAPTURE, 2, 2, true);
	record(m, 1.5, ENDOSIM_TOOL_RELEASE, 2, -1, false);
	record(m, 2.0, ENDOSIM_TOOL_CAPTURE, 3, 3, false);
	record(m, 3.0, ENDOSIM_TOOL_CUT, 3, -1, false);
	record(m, 3.5, ENDOSIM_TOOL_BITE, -1, -1, false);
	record(m, 3.6, ENDOSIM_TOOL_INJURY, -1, -1, false);
	record(m, 3.7, ENDOSIM_TOOL_CLIP_PLACED, -1, -1, false);
	record(m, 4.0, ENDOSIM_TOOL_LIFT, 5, -1, false);
	record(m, 4.5, ENDOSIM_TOOL_CAPTURE, 5, 5, false);
	record(m, 5.0, ENDOSIM_TOOL_CUT, 5, -1, false);
	metrics_result(m, &r);
	metrics_destroy(m);
	assert_int_equal(r.n_polyp, 6);
	for (uint32_t i = 0; i < r.n_polyp; i++) {
		assert_int_equal(r.polyp[i].fate, want[i]);
	}
	assert_int_equal(r.polyps_resected, 3);
	assert_int_equal(r.polyps_partly, 2);
	assert_int_equal(r.polyps_retrieved, 0);
	assert_true(fabs(r.resection_s - 2.0 / 3) < 1e-9);
	assert_true(fabs(r.polyp[2].cautery_s - 0.5) < 1e-9);
	assert_true(fabs(r.cautery_s - 0.5) < 1e-9);
	assert_true(r.polyp[4].start_s < 0 && r.polyp[4].cut_s < 0);
	assert_true(fabs(r.polyp[5].start_s - 4.0) < 1e-9);
	assert_int_equal(r.polyp[0].bites, 1);
	assert_int_equal(r.biopsies, 3);
	assert_int_equal(r.tool_injuries, 1);
	assert_int_equal(r.clips, 1);

	sessionpb_from_metrics(&pb, &r);
	len = endosim__session_metrics__get_packed_size(&pb.msg);
	assert_true(len <= sizeof(wire));
	endosim__session_metrics__pack(&pb.msg, wire);
	un = endosim__session_metrics__unpack(NULL, len, wire);
	assert_non_null(un);
	sessionpb_to_metrics(un, &back);
	endosim__session_metrics__free_unpacked(un, NULL);
	assert_int_equal(back.n_polyp, r.n_polyp);
	assert_int_equal(back.polyps_partly, 2);
	assert_int_equal(back.tool_injuries, 1);
	assert_true(back.resection_s == r.resection_s);
	for (uint32_t i = 0; i < r.n_polyp; i++) {
		assert_int_equal(back.polyp[i].fate, want[i]);
		assert_true(back.polyp[i].cautery_s == r.polyp[i].cautery_s);
	}
}

/* Without a tool in hand, no polyps are listed (their fates would be
 * "left" for a session that never meant to resect). */
static void test_no_tool_no_fates(void **unused)
{
	struct metrics_params mp;
	struct metrics *m;
	struct metrics_result r;
	struct session_record rec = { .tool_captured = -1,
				      .tool_event_polyp = -1 };

	(void)unused;
	metrics_params_default(&mp);
	m = metrics_create(NULL, &mp);
	assert_non_null(m);
	metrics_record(m, &rec);
	rec.stamp_ns += ENDOSIM_NS_PER_S;
	metrics_record(m, &rec);
	metrics_result(m, &r);
	metrics_destroy(m);
	assert_int_equal(r.n_polyp, 0);
	assert_int_equal(r.polyps_resected, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_fates),
		cmocka_unit_test(test_no_tool_no_fates),
		cmocka_unit_test(test_expert_resects_all),
		cmocka_unit_test(test_careless_perforates),
		cmocka_unit_test(test_end_frame_and_report),
	};
	const char *top = getenv("ENDOSIM_TOP");

	if (top && chdir(top)) {
		perror(top);
		return 1;
	}
	return cmocka_run_group_tests(tests, play, NULL);
}
