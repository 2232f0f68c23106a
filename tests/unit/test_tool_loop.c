/*
 * test_tool_loop.c - the tool in the running force loop (issue 25), in
 * lockstep (offline.h), on the polyps case (config/cases/polyps.case),
 * the paper's model (a scope that stands still when nothing pushes it):
 *  - the case's polyps are placed for the tool when the loop is made,
 *    every one published, nothing captured;
 *  - a tool reaches the loop through its mailbox: a snare of 20 mm; one
 *    of 35 mm or an unknown kind is refused there and changes nothing;
 *  - the hand's sensing reaches the loop: the sheath pushed out of the
 *    channel and the handle opened, the published loop's diameter is
 *    tool_loop_diameter()'s, d = min(D, 2 l / pi), at every cycle;
 *  - the case's pedunculated polyp, moved to stand under the open loop
 *    where the scope is (its stalk along the channel's radial direction,
 *    through the loop's centre), is captured as the handle closes, the
 *    loop then held at the stalk's thickness, published;
 *  - the pedal down, it is cut after the documented energy over the
 *    power, E = cut_j_per_m2 pi t^2 / 4 at hot_power_w, within 2 %, its
 *    energy published;
 *  - a stale input (the client stops sending) holds the tool and the
 *    handle still and the pedal up: no energy goes in while it lasts;
 *  - the stalk cut cold bleeds its documented flow, published; the blood
 *    shed is the flow times the time, all of it in the polyp's
 *    segment's pool when there is a patient; [tool] bleed_stop_s set
 *    shorter stops it by itself that long after the cut;
 *  - the stalked polyp cut falls to the lowest wall of its ring, in the
 *    time the fall's law gives, and stays; with the patient turned onto
 *    the back it lies on the new dependent wall;
 *  - the hand's suction valve reaches the tool: a 6 mm polyp cut and
 *    lying before the channel's exit is retrieved with it pressed, left
 *    lying without;
 *  - the snare closed on the case's sessile polyp, unlifted, the pedal
 *    down: an injury of the wall, the patient's perforation in the same
 *    cycle (torn_segment; with no patient, the tool's event alone).
 */
#include <errno.h>
#include <fcntl.h>
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
#include "model/gas.h"
#include "model/patient.h"
#include "model/tool.h"
#include "offline.h"
#include "proto/names.h"
#include "proto/session_file.h"
#include "viewer/replay.h"

#define DT (OFFLINE_PERIOD_NS * ENDOSIM_S_PER_NS)
#define SNARE_M 0.020
#define DEPTH_M 0.010
#define HOLD_S 0.003 /* three cycles: stale unless renewed */
#define SHUT 0.1      /* the handle closed on the stalk, not cold-cut */

struct run {
	struct config cfg;
	struct offline *o;
	const struct endosim_state *st;
	double depth_m, opening;
	bool pedal;
	double was_depth_m, was_opening; /* sent before the last cycle: the
					    simulated hand's reading lags a
					    cycle (rig_sim.c) */
	unsigned events;   /* since the last look */
	int ip;            /* the case's (last) pedunculated polyp */
	int is;            /* and its first sessile one */
	int fd;            /* a session's file the cycles are recorded in, or
			      0: none */
};

/* The loop on R's case (the polyps case unless its configuration names
 * one) with R's configuration, the patient there or not, the hand's
 * scenario LINES ('\n' between them; NULL: none). */
static void launch(struct run *r, bool patient, const char *lines)
{
	char err[512], text[512];
	struct colon *c;
	const struct anatomy *a;
	struct scenario *scn = NULL;
	bool polyps = !r->cfg.colon.file[0];

	r->cfg.haptics.model = HAPTICS_MODEL_PAPER;
	r->cfg.patient.enabled = patient;
	if (polyps) {
		snprintf(r->cfg.colon.file, sizeof(r->cfg.colon.file),
			 "config/cases/polyps.case");
	}
	c = cases_load(&r->cfg, NULL, err, sizeof(err));
	if (!c) {
		fail_msg("%s", err);
	}
	a = colon_anatomy(c);
	r->ip = r->is = -1;
	for (int i = 0; a && i < a->polyps; i++) {
		if (a->polyp[i].paris == ANATOMY_PARIS_IP) {
			r->ip = i;
		}
		if (a->polyp[i].paris == ANATOMY_PARIS_IS && r->is < 0) {
			r->is = i;
		}
	}
	assert_true(r->ip >= 0 && (r->is >= 0 || !polyps));
	if (lines) {
		scn = scenario_create();
		assert_non_null(scn);
		snprintf(text, sizeof(text), "%s", lines);
		for (char *save, *ln = strtok_r(text, "\n", &save); ln;
		     ln = strtok_r(NULL, "\n", &save)) {
			assert_int_equal(scenario_append(scn, ln, err,
							 sizeof(err)), 0);
		}
	}
	r->o = offline_create_with(&r->cfg, c, scn, err, sizeof(err));
	if (!r->o) {
		fail_msg("%s", err);
	}
	r->depth_m = -DEPTH_M; /* in the channel */
}

/* The same with the defaults. */
static void start_with(struct run *r, bool patient, const char *line)
{
	memset(r, 0, sizeof(*r));
	config_defaults(&r->cfg);
	launch(r, patient, line);
}

static void start(struct run *r, bool patient)
{
	start_with(r, patient, NULL);
}

/* One cycle, the hand's input renewed unless STALE. */
static void step(struct run *r, bool stale)
{
	if (!stale) {
		offline_tool_input(r->o, r->depth_m, r->opening, r->pedal,
				   HOLD_S);
	}
	r->st = offline_step(r->o);
	if (r->fd > 0) {
		struct session_record rec;

		session_record_from_state(r->st, &rec);
		assert_int_equal(session_file_write_frame(r->fd,
				 SESSION_FRAME_RECORD, &rec, sizeof(rec)), 0);
	}
	r->was_depth_m = r->depth_m;
	r->was_opening = r->opening;
	r->events |= r->st->tool.events;
}

/* N cycles moving the depth and the handle linearly to DEPTH_M and
 * OPENING, a snare's published loop checked against the formula each
 * cycle. */
static void move(struct run *r, long n, double depth_m, double opening)
{
	double d0 = r->depth_m, o0 = r->opening;

	for (long k = 1; k <= n; k++) {
		double depth = r->was_depth_m, open = r->was_opening;

		r->depth_m = d0 + (depth_m - d0) * (double)k / (double)n;
		r->opening = o0 + (opening - o0) * (double)k / (double)n;
		step(r, false);
		if (r->st->tool.kind == ENDOSIM_TOOL_SNARE &&
		    r->st->tool.captured < 0) {
			assert_true(r->st->tool.loop_m ==
				    tool_loop_diameter(SNARE_M, open, depth));
		}
		assert_true(r->st->tool.depth_m == depth);
		assert_true(r->st->tool.opening == open);
	}
}

/* The case's polyp I moved under the open loop: its axis' middle at the
 * loop's centre, along the channel's radial direction (held there: not
 * on the wall the gas moves). */
static void polyp_under_loop(struct run *r, int i)
{
	struct tool *t = offline_tool(r->o);
	struct tool_polyp *p = &t->polyp[i];
	struct tool_params par;
	struct tool_pose pose;
	double centre[3];

	cases_tool_params(&r->cfg, &par);
	tool_pose(&par, &r->st->scope, r->depth_m, &pose);
	vec3_axpy(centre, pose.tip, SNARE_M / 2, pose.dir);
	assert_true(vec3_dist(centre, r->st->tool.loop_centre) < 1e-12);
	vec3_axpy(p->base, centre, tool_polyp_height(p, par.lift_m) / 2,
		  pose.radial);
	vec3_scale(p->normal, pose.radial, -1);
	p->s_m = r->st->scope.tip_s_m + r->depth_m + SNARE_M / 2; /* its ring */
	p->on_wall = false;
}

static void test_polyps_placed(void **state)
{
	struct run r;

	(void)state;
	start(&r, false);
	step(&r, false);
	assert_int_equal(r.st->tool.polyps, 5);
	assert_int_equal(r.st->tool.kind, ENDOSIM_TOOL_NONE);
	assert_int_equal(r.st->tool.captured, -1);
	assert_int_equal(r.st->tool.polyp[r.ip].state, ENDOSIM_POLYP_IN_PLACE);
	offline_destroy(r.o);
}

static void test_select_refused(void **state)
{
	struct run r;

	(void)state;
	start(&r, false);
	offline_tool_select(r.o, TOOL_SNARE, SNARE_M);
	step(&r, false);
	assert_int_equal(offline_tool_answer(r.o), 0);
	assert_int_equal(r.st->tool.kind, ENDOSIM_TOOL_SNARE);
	assert_true(r.st->tool.snare_m == SNARE_M);
	offline_tool_select(r.o, TOOL_SNARE, 0.035);
	step(&r, false);
	assert_int_equal(offline_tool_answer(r.o), -EINVAL);
	offline_tool_select(r.o, 9, 0);
	step(&r, false);
	assert_int_equal(offline_tool_answer(r.o), -EINVAL);
	assert_int_equal(r.st->tool.kind, ENDOSIM_TOOL_SNARE);
	assert_true(r.st->tool.snare_m == SNARE_M);
	offline_destroy(r.o);
}

/* Cycles the loop saw the pedal down until the cut, the input going
 * stale for STALE cycles after the first FIRST: the pedal then reads up,
 * the tool and the handle still, and the energy stands still. */
static long pedal_until_cut(struct run *r, long first, long stale)
{
	const struct endosim_tool_state *t = &r->st->tool;
	long down = 0;
	double held;

	r->pedal = true;
	r->events = 0;
	for (long k = 0; k < 100000 && !(r->events & ENDOSIM_TOOL_CUT); k++) {
		step(r, k >= first && k < first + stale);
		t = &r->st->tool;
		down += t->pedal;
		if (k == first + stale / 2) {
			held = t->polyp[r->ip].energy_j;
		}
		if (k != first + stale - 1) {
			continue;
		}
		/* stale since mid-way at least: pedal up, still */
		assert_int_equal(t->pedal, 0);
		assert_true(t->opening == SHUT);
		assert_true(t->depth_m == DEPTH_M);
		assert_int_equal(t->captured, r->ip);
		assert_true(t->polyp[r->ip].energy_j == held);
	}
	assert_true(r->events & ENDOSIM_TOOL_CUT);
	assert_int_equal(t->event_polyp, r->ip);
	assert_int_equal(t->polyp[r->ip].state, ENDOSIM_POLYP_CUT);
	return down;
}

/* The snare selected, out and open, the case's stalk moved under it. */
static void snare_over_stalk(struct run *r)
{
	offline_tool_select(r->o, TOOL_SNARE, SNARE_M);
	step(r, false);
	move(r, 100, DEPTH_M, 0);          /* the sheath out, closed */
	move(r, 1, DEPTH_M, 0);
	assert_true(r->st->tool.loop_m == 0);
	move(r, 200, DEPTH_M, 1);          /* open: d = D */
	move(r, 1, DEPTH_M, 1);
	assert_true(r->st->tool.loop_m == SNARE_M);
	polyp_under_loop(r, r->ip);
	move(r, 5, DEPTH_M, 1);            /* inside the open loop */
	assert_int_equal(r->st->tool.captured, -1);
}

static void test_capture_and_cut(void **state)
{
	struct run r;
	struct tool_polyp held;
	double t_m, e_j, want_s, got_s;
	long n;

	(void)state;
	start(&r, false);
	snare_over_stalk(&r);
	r.events = 0;
	move(&r, 300, DEPTH_M, SHUT);       /* close around the stalk */
	move(&r, 1, DEPTH_M, SHUT);
	held = offline_tool(r.o)->polyp[r.ip];
	t_m = tool_polyp_thickness(&held);
	assert_true(r.events & ENDOSIM_TOOL_CAPTURE);
	assert_int_equal(r.st->tool.captured, r.ip);
	assert_int_equal(r.st->tool.polyp[r.ip].state, ENDOSIM_POLYP_CAPTURED);
	assert_true(r.st->tool.loop_m == t_m);
	assert_false(r.events & ENDOSIM_TOOL_CUT); /* not cold: still open */

	e_j = r.cfg.tool.cut_j_per_m2 * M_PI * t_m * t_m / 4;
	want_s = e_j / r.cfg.tool.hot_power_w;
	n = pedal_until_cut(&r, 200, 50);
	got_s = (double)n * DT;
	print_message("stalk %.1f mm: cut after %.3f s of pedal, E/P %.3f s\n",
		      t_m * 1e3, got_s, want_s);
	assert_true(fabs(got_s - want_s) <= 0.02 * want_s);
	assert_true(fabs(r.st->tool.polyp[r.ip].energy_j - e_j) <=
		    0.02 * e_j);
	assert_int_equal(r.st->tool.captured, -1);
	offline_destroy(r.o);
}

/* The snare closed on the sessile polyp's unlifted base and the pedal
 * down: an injury of the wall, the patient's perforation (torn_segment)
 * in the cycle it happens; without the patient, the tool's event alone. */
/*
 * The stalk cut cold (the handle closed all the way, no pedal): it
 * bleeds Q = bleed_m_per_s pi t^2 / 4, published; N cycles later the
 * blood shed is Q N dt, and with the patient, all of it in the pool of
 * one segment, the polyp's.
 */
static void test_cold_cut_bleeds_into_pool(void **state)
{
	struct run r;
	struct tool_params par;
	double t_m, q, before[ENDOSIM_SEGMENTS], added = 0;
	int changed = 0;

	(void)state;
	start(&r, true);
	cases_tool_params(&r.cfg, &par);
	snare_over_stalk(&r);
	move(&r, 300, DEPTH_M, SHUT);
	assert_int_equal(r.st->tool.captured, r.ip);
	t_m = tool_polyp_thickness(&offline_tool(r.o)->polyp[r.ip]);
	q = par.bleed_m_per_s * M_PI * t_m * t_m / 4;
	memcpy(before, r.st->patient.fluid_m3, sizeof(before));
	r.events = 0;
	move(&r, 10, DEPTH_M, 0);
	for (long k = 0; k < 1000; k++) {
		step(&r, false);
	}
	assert_true(r.events & ENDOSIM_TOOL_CUT);
	assert_true(r.events & ENDOSIM_TOOL_BLEED);
	assert_int_equal(r.st->tool.bleeding, 1);
	assert_int_equal(r.st->tool.polyp[r.ip].bleed, ENDOSIM_BLEED_BLEEDING);
	assert_true(fabs(r.st->tool.bleed_m3_s - q) <= 1e-12 * q);
	print_message("stalk %.1f mm: %.2f mL/min, %.4f mL shed\n", t_m * 1e3,
		      q * 6e7, r.st->tool.blood_m3 * 1e6);
	/* the cut came in one of the 10 closing cycles */
	assert_true(r.st->tool.blood_m3 >= q * 1001 * DT * (1 - 1e-9) &&
		    r.st->tool.blood_m3 <= q * 1010 * DT * (1 + 1e-9));
	for (int i = 0; i < ENDOSIM_SEGMENTS; i++) {
		double d = r.st->patient.fluid_m3[i] - before[i];

		changed += d != 0;
		added += d;
	}
	assert_int_equal(changed, 1);
	assert_true(fabs(added - r.st->tool.blood_m3) <= 1e-9 * added);
	offline_destroy(r.o);
}

/*
 * [tool] bleed_stop_s reaches the loop: at 0.5 s (the default 300 s) the
 * stalk cut cold stops bleeding by itself 0.5 s after the cut (the step
 * after the 500th that shed, tool.h), having shed Q x 0.5 s.
 */
static void test_bleed_stop_key(void **state)
{
	struct run r;
	double t_m, q;
	long cut = -1, stop = -1;

	(void)state;
	memset(&r, 0, sizeof(r));
	config_defaults(&r.cfg);
	r.cfg.tool.bleed_stop_s = 0.5;
	launch(&r, false, NULL);
	snare_over_stalk(&r);
	move(&r, 300, DEPTH_M, SHUT);
	assert_int_equal(r.st->tool.captured, r.ip);
	t_m = tool_polyp_thickness(&offline_tool(r.o)->polyp[r.ip]);
	q = r.cfg.tool.bleed_m_per_s * M_PI * t_m * t_m / 4;
	r.opening = 0;
	for (long k = 0; k < 2000 && stop < 0; k++) {
		step(&r, false);
		if (r.st->tool.events & ENDOSIM_TOOL_BLEED) {
			cut = k;
		}
		if (r.st->tool.events & ENDOSIM_TOOL_STOPPED) {
			stop = k;
		}
	}
	print_message("bleed_stop_s 0.5: cut at %ld, stopped at %ld\n", cut,
		      stop);
	assert_true(cut >= 0);
	assert_int_equal(stop - cut, 500);
	assert_int_equal(r.st->tool.polyp[r.ip].bleed, ENDOSIM_BLEED_STOPPED);
	assert_int_equal(r.st->tool.bleeding, 0);
	assert_true(fabs(r.st->tool.blood_m3 - q * 0.5) <= 1e-9 * q);
	offline_destroy(r.o);
}

/*
 * Where a cut polyp of SIZE_M at ring S_M rests under gravity DOWN on
 * colon C, the lumen's radius factors FACTOR (as published), into OUT:
 * the lowest of 3600 wall points round the ring along DOWN, the wall
 * where the gas holds it, its radius in along the ring's radius.
 */
static void rest_by_search(const struct colon *c, double s_m, double size_m,
			   const double down[3], const double *factor,
			   double out[3])
{
	struct centreline_point q;
	double best = -INFINITY, f = gas_factor_at(c, factor, s_m);

	centreline_at_s(colon_centreline(c), s_m, &q);
	for (int k = 0; k < 3600; k++) {
		double th = 2 * M_PI * k / 3600, x[3];
		double r = f * colon_lumen_radius(c, s_m, th);

		vec3_scale(x, q.u, cos(th));
		vec3_axpy(x, x, sin(th), q.v);
		if (r * vec3_dot(x, down) > best) {
			best = r * vec3_dot(x, down);
			vec3_axpy(out, q.p, r - size_m / 2, x);
		}
	}
}

/* The time (s) from rest over L_M pulled by G_M_S2 against a drag of
 * TAU_S (tool.h): L = g tau (t - tau (1 - exp(-t / tau))). */
static double fall_time(double l_m, double g_m_s2, double tau_s)
{
	double lo = 0, hi = 10;

	for (int k = 0; k < 200; k++) {
		double t = (lo + hi) / 2;

		if (g_m_s2 * tau_s * (t - tau_s * (1 - exp(-t / tau_s))) <
		    l_m) {
			lo = t;
		} else {
			hi = t;
		}
	}
	return lo;
}

/*
 * The stalked polyp cut cold in the loop falls to the lowest wall of its
 * ring (within 0.05 mm of a search of 3600 points round it) in the time
 * the drag's law gives for the way from where it was cut (to two
 * cycles), published where it lies (each cycle's lying polyp while it
 * falls), and stays there: with no patient modelled, lying on the left
 * side, still; with the patient, on the wall where the gas holds it
 * (its radius factor scaling the ring), carried with it, and turned
 * onto the back (2 s), it lies on the dependent wall again.
 */
static void falls_in_loop(bool patient)
{
	const double left[3] = { 1, 0, 0 }, back[3] = { 0, 1, 0 };
	struct run r;
	double from[3], want[3], l, t_s;
	long n = -1, k;
	const struct tool_polyp *p;

	memset(&r, 0, sizeof(r));
	config_defaults(&r.cfg);
	r.cfg.patient.turn_s = 2;
	launch(&r, patient, patient ? "1.5 patient position supine" : NULL);
	snare_over_stalk(&r);
	move(&r, 300, DEPTH_M, SHUT);
	r.opening = 0;
	p = &offline_tool(r.o)->polyp[r.ip];
	for (k = 0; k < 1000 && !(r.st->tool.events & ENDOSIM_TOOL_CUT); k++) {
		step(&r, false);
	}
	assert_true(r.st->tool.events & ENDOSIM_TOOL_CUT);
	vec3_copy(from, r.st->tool.polyp[r.ip].at);
	rest_by_search(offline_colon(r.o), p->s_m, p->size_m, left,
		       r.st->patient.factor, want);
	l = vec3_dist(from, want);
	t_s = fall_time(l, PATIENT_GRAVITY_M_S2, r.cfg.tool.fall_drag_s);
	for (k = 1; k < 1000 && n < 0; k++) {
		assert_int_equal(r.st->tool.lying_polyp, r.ip);
		assert_true(vec3_dist(r.st->tool.lying_at,
				      r.st->tool.polyp[r.ip].at) == 0);
		if (vec3_dist(r.st->tool.polyp[r.ip].at, want) < 5e-5 &&
		    p->fall_v == 0) {
			n = k;
		}
		step(&r, false);
	}
	print_message("%s: fell %.1f mm in %ld cycles, the law's %.4f s; "
		      "%.3f mm from the lowest wall's rest\n",
		      patient ? "the patient" : "no patient", l * 1e3, n, t_s,
		      vec3_dist(r.st->tool.polyp[r.ip].at, want) * 1e3);
	assert_true(n > 0 && fabs((double)n - t_s / DT) <= 2);
	vec3_copy(from, r.st->tool.polyp[r.ip].at);
	for (k = 0; k < 200; k++) {
		step(&r, false);
	}
	/* still, or with the patient carried with the wall as the gas
	 * moves it: at the rest for the factor now */
	rest_by_search(offline_colon(r.o), p->s_m, p->size_m, left,
		       r.st->patient.factor, want);
	print_message("%s: %.4f mm on in 200 cycles, %.4f mm from the rest "
		      "with the gas now\n", patient ? "the patient" :
		      "no patient", vec3_dist(r.st->tool.polyp[r.ip].at, from) *
		      1e3, vec3_dist(r.st->tool.polyp[r.ip].at, want) * 1e3);
	assert_true(vec3_dist(r.st->tool.polyp[r.ip].at, want) < 5e-5);
	assert_true(patient ||
		    vec3_dist(r.st->tool.polyp[r.ip].at, from) == 0);
	if (patient) {
		while (r.st->scenario_time_s < 4.5) {
			step(&r, false);
		}
		assert_int_equal(r.st->patient.position,
				 ENDOSIM_POSITION_SUPINE);
		assert_int_equal(r.st->patient.turning, 0);
		rest_by_search(offline_colon(r.o), p->s_m, p->size_m, back,
			       r.st->patient.factor, want);
		print_message("turned onto the back: %.3f mm from its rest\n",
			      vec3_dist(r.st->tool.polyp[r.ip].at, want) * 1e3);
		assert_true(vec3_dist(r.st->tool.polyp[r.ip].at, want) < 5e-5);
	}
	assert_int_equal(r.st->tool.polyp[r.ip].state, ENDOSIM_POLYP_CUT);
	offline_destroy(r.o);
}

static void test_cut_polyp_falls(void **state)
{
	(void)state;
	falls_in_loop(false);
	falls_in_loop(true);
}

/* ------------------------------------------------- a session, replayed */

/* 46-viewer-bleed's case: the straight colon and a stalked polyp at 5
 * o'clock 12 cm in (a 5 mm stalk 25 mm long), and its scope: 9.6 cm in,
 * then (at 3 s) 11.3 cm in, bent towards the polyp's foot. */
static const char bleed_polyp[] =
	"\n[polyp]\ns_m = 0.120\nangle_deg = 150\ndiameter_m = 0.009\n"
	"shape = pedunculated\nstalk_length_m = 0.025\n"
	"stalk_diameter_m = 0.005\n";
static const char bleed_scope[] =
	"0 insertion target 0.096 1.5\n3 insertion target 0.113 1.5\n"
	"3 wheel_ud target -0.18 1.5\n3 wheel_lr target 0.10 1.5\n"
	"60 end";

/* The text of file PATH, with MORE after it, into OUT (SIZE bytes). */
static void read_case(const char *path, const char *more, char *out,
		      size_t size)
{
	FILE *f = fopen(path, "r");
	size_t n;

	assert_non_null(f);
	n = fread(out, 1, size - 1, f);
	fclose(f);
	snprintf(out + n, size - n, "%s", more);
}

/* The session file PATH begun for R's loop on the case CASE_TEXT: its
 * head as the recorder writes it (the configuration as --print-config
 * prints it); each cycle's record then follows (step()). */
static void record(struct run *r, const char *path, const char *case_text)
{
	struct session_header h = {
		.id = 1, .trainee = "test", .case_name = "bleed",
		.started = "2026-11-30T10:00:00Z",
		.start_ns = OFFLINE_START_NS, .period_ns = OFFLINE_PERIOD_NS,
		.version = "test", .step_m = r->cfg.colon.step_m,
		.ring_vertices = (int)r->cfg.colon.ring_vertices,
		.segment_m = r->cfg.colon.segment_m,
	};
	char head[1024], *config = NULL;
	size_t size = 0;
	FILE *m = open_memstream(&config, &size);

	assert_non_null(m);
	config_print(&r->cfg, m);
	fclose(m);
	assert_true(session_header_text(&h, head, sizeof(head)) > 0);
	r->fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
	assert_true(r->fd > 0);
	assert_int_equal(session_file_write_magic(r->fd), 0);
	assert_int_equal(session_file_write_frame(r->fd, SESSION_FRAME_HEADER,
						  head, strlen(head)), 0);
	assert_int_equal(session_file_write_frame(r->fd, SESSION_FRAME_CONFIG,
						  config, strlen(config)), 0);
	assert_int_equal(session_file_write_frame(r->fd, SESSION_FRAME_CASE,
						  case_text,
						  strlen(case_text)), 0);
	free(config);
}

/* What the loop published at one cycle, to hold the replay against. */
struct truth {
	uint64_t cycle;
	struct endosim_tool_state tool;
};

/* Steps until COND holds (at most N cycles); fails otherwise. */
#define STEP_UNTIL(r, cond, n)                                               \
	do {                                                                 \
		long k_ = 0;                                                 \
		while (!(cond) && k_++ < (n)) {                              \
			step((r), false);                                    \
		}                                                            \
		assert_true(cond);                                           \
	} while (0)

/*
 * The replay of a recorded session (viewer/replay.h) against what the
 * loop published at the same cycle: POLYP's state and where it lay,
 * whether it bled and from where, the clips and the last one's place
 * (within a float's rounding of the recorded tip: 1e-6 m).
 */
static void replay_matches(struct replay *rp, const struct truth *tr,
			   int polyp)
{
	const struct endosim_tool_state *want = &tr->tool, *got;

	replay_seek(rp, (double)tr->cycle * OFFLINE_PERIOD_NS *
				ENDOSIM_S_PER_NS);
	got = &replay_state(rp)->tool;
	print_message("cycle %llu: polyp %s, lying %.3f mm off, %u bleeding "
		      "%.3g mm off, %u clips %.3g mm off\n",
		      (unsigned long long)tr->cycle,
		      names_polyp_state(got->polyp[polyp].state),
		      vec3_dist(got->polyp[polyp].at,
				want->polyp[polyp].at) * 1e3, got->bleeding,
		      vec3_dist(got->bleed_at, want->bleed_at) * 1e3,
		      got->clips, vec3_dist(got->clip_at, want->clip_at) * 1e3);
	assert_int_equal(replay_state(rp)->cycle, tr->cycle);
	assert_int_equal(got->polyps, want->polyps);
	assert_int_equal(got->polyp[polyp].state, want->polyp[polyp].state);
	assert_true(vec3_dist(got->polyp[polyp].at, want->polyp[polyp].at) <
		    1e-6);
	assert_int_equal(got->polyp[polyp].bleed, want->polyp[polyp].bleed);
	assert_int_equal(got->bleeding, want->bleeding);
	assert_true(vec3_dist(got->bleed_at, want->bleed_at) < 1e-9);
	assert_int_equal(got->clips, want->clips);
	assert_true(vec3_dist(got->clip_at, want->clip_at) < 1e-6);
}

/*
 * 46-viewer-bleed's session in lockstep, recorded: the stalk snared 15
 * mm out, cut cold, bleeding; its head falling to the wall; the scope
 * moved to the stalk's foot and a clip put on the point, which stops it.
 * Its replay shows at each of those cycles what the loop published: the
 * polyp standing, falling, lying; the bleeding point; the clip.
 */
static void test_replay_bleed_and_clip(void **state)
{
	char path[] = "/tmp/test_tool_loop_XXXXXX", err[256];
	static char text[1 << 16];
	struct truth tr[5];
	struct replay *rp;
	struct run r;
	int fd, nt = 0, p;
	double exit[3], depth;

	(void)state;
	fd = mkstemp(path);
	assert_true(fd >= 0);
	close(fd);
	read_case("tests/cases/straight.case", bleed_polyp, text, sizeof(text));
	memset(&r, 0, sizeof(r));
	config_defaults(&r.cfg);
	snprintf(r.cfg.colon.file, sizeof(r.cfg.colon.file), "%s.case", path);
	fd = open(r.cfg.colon.file, O_WRONLY | O_CREAT | O_TRUNC, 0600);
	assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
	close(fd);
	launch(&r, false, bleed_scope);
	unlink(r.cfg.colon.file);
	record(&r, path, text);
	p = r.ip;
	step(&r, false);
	STEP_UNTIL(&r, r.st->axis[0].position > 0.094, 3000);
	offline_tool_select(r.o, TOOL_SNARE, SNARE_M);
	step(&r, false);
	move(&r, 300, 0.015, 1);
	move(&r, 300, 0.015, 0.1);
	assert_int_equal(r.st->tool.captured, p);
	tr[nt++] = (struct truth){ r.st->cycle, r.st->tool }; /* standing */
	r.events = 0;
	move(&r, 20, 0.015, 0);
	STEP_UNTIL(&r, r.events & ENDOSIM_TOOL_BLEED, 100);
	step(&r, false);
	tr[nt++] = (struct truth){ r.st->cycle, r.st->tool }; /* falling */
	assert_true(offline_tool(r.o)->polyp[p].fall_v > 0);
	move(&r, 500, 0.015, 0);
	tr[nt++] = (struct truth){ r.st->cycle, r.st->tool }; /* lying */
	assert_true(offline_tool(r.o)->polyp[p].fall_v == 0);
	assert_int_equal(r.st->tool.bleeding, 1);
	/* the scope at the foot, then the clip's jaws onto the point */
	STEP_UNTIL(&r, r.st->scenario_time_s > 5.5, 6000);
	offline_tool_select(r.o, TOOL_CLIP, 0);
	step(&r, false);
	move(&r, 200, 0.005, 0);
	vec3_axpy(exit, r.st->tool.tip, -r.st->tool.depth_m, r.st->scope.dir);
	vec3_sub(exit, r.st->tool.bleed_at, exit);
	depth = vec3_dot(exit, r.st->scope.dir) - 0.005;
	move(&r, 200, depth, 1);
	tr[nt++] = (struct truth){ r.st->cycle, r.st->tool }; /* clip open */
	r.events = 0;
	move(&r, 200, depth, 0);
	assert_true(r.events & ENDOSIM_TOOL_CLIP_PLACED);
	assert_true(r.events & ENDOSIM_TOOL_CLIPPED);
	move(&r, 100, depth, 0);
	tr[nt++] = (struct truth){ r.st->cycle, r.st->tool }; /* clipped */
	assert_int_equal(r.st->tool.bleeding, 0);
	close(r.fd);
	offline_destroy(r.o);

	rp = replay_open(path, err, sizeof(err));
	if (!rp) {
		fail_msg("%s", err);
	}
	for (int k = 0; k < nt; k++) {
		replay_matches(rp, &tr[k], p);
	}
	/* and back: a seek to an earlier time shows it as it was then */
	replay_matches(rp, &tr[1], p);
	replay_destroy(rp);
	unlink(path);
}

/*
 * The case's 6 mm sessile polyp cut cold under the loop, then laid
 * (where it lies: tool.h, at rest) 6 mm from the channel's exit, the
 * hand holding the suction valve (SUCTION) or not: retrieved through
 * the channel, or left lying.
 */
static int retrieved(bool suction)
{
	struct run r;
	struct tool_polyp *p;
	struct tool_params par;
	struct tool_pose pose;
	int i = 2, state;

	start_with(&r, false, suction ? "0 valve suction on" : NULL);
	cases_tool_params(&r.cfg, &par);
	assert_true(offline_tool(r.o)->polyp[i].size_m == 0.006);
	offline_tool_select(r.o, TOOL_SNARE, SNARE_M);
	step(&r, false);
	move(&r, 100, DEPTH_M, 1);
	move(&r, 1, DEPTH_M, 1);
	polyp_under_loop(&r, i);
	move(&r, 5, DEPTH_M, 1);
	r.events = 0;
	move(&r, 300, DEPTH_M, 0);
	assert_true(r.events & ENDOSIM_TOOL_CUT);
	assert_int_equal(r.st->tool.polyp[i].state, ENDOSIM_POLYP_CUT);
	/* where it lies: 6 mm ahead of the exit, at rest there */
	p = &offline_tool(r.o)->polyp[i];
	tool_pose(&par, &r.st->scope, r.depth_m, &pose);
	vec3_axpy(p->at, pose.exit, 0.006, pose.dir);
	vec3_copy(p->rest, p->at);
	p->rest_ok = true;
	p->fall_v = 0;
	r.events = 0;
	move(&r, 20, DEPTH_M, 0);
	state = (int)r.st->tool.polyp[i].state;
	assert_int_equal((r.events & ENDOSIM_TOOL_RETRIEVE) != 0,
			 state == ENDOSIM_POLYP_RETRIEVED);
	offline_destroy(r.o);
	return state;
}

static void test_retrieve_by_suction(void **state)
{
	(void)state;
	assert_int_equal(retrieved(true), ENDOSIM_POLYP_RETRIEVED);
	assert_int_equal(retrieved(false), ENDOSIM_POLYP_CUT);
}

static void injury(bool patient)
{
	struct run r;

	start(&r, patient);
	offline_tool_select(r.o, TOOL_SNARE, SNARE_M);
	step(&r, false);
	move(&r, 100, DEPTH_M, 1);
	move(&r, 1, DEPTH_M, 1);
	polyp_under_loop(&r, r.is);
	move(&r, 5, DEPTH_M, 1);
	r.events = 0;
	move(&r, 300, DEPTH_M, SHUT);
	assert_int_equal(r.st->tool.captured, r.is);
	assert_int_equal(r.st->patient.torn_segment, -1);
	r.pedal = true;
	for (int k = 0; k < 10 && !(r.events & ENDOSIM_TOOL_INJURY); k++) {
		step(&r, false);
	}
	assert_true(r.events & ENDOSIM_TOOL_INJURY);
	assert_true(r.st->tool.events & ENDOSIM_TOOL_INJURY);
	assert_int_equal(r.st->tool.event_polyp, r.is);
	if (patient) {
		assert_true(r.st->patient.torn_segment >= 0);
	} else {
		assert_int_equal(r.st->patient.torn_segment, -1);
	}
	offline_destroy(r.o);
}

static void test_injury_perforates(void **state)
{
	(void)state;
	injury(true);
	injury(false);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_polyps_placed),
		cmocka_unit_test(test_select_refused),
		cmocka_unit_test(test_capture_and_cut),
		cmocka_unit_test(test_injury_perforates),
		cmocka_unit_test(test_cold_cut_bleeds_into_pool),
		cmocka_unit_test(test_bleed_stop_key),
		cmocka_unit_test(test_cut_polyp_falls),
		cmocka_unit_test(test_replay_bleed_and_clip),
		cmocka_unit_test(test_retrieve_by_suction),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
