/*
 * test_tool.c - the tools through the working channel (tool.h), against
 * the geometry and the numbers its header states:
 *  - the pose: the channel's exit at its clock angle in the image (5
 *    o'clock: down and right) and offset on a known tip pose, the tool
 *    along dir at its depth;
 *  - the loop's diameter as it leaves the sheath: min(D, 2 l / pi) with
 *    l = opening pi D / 2 plus a negative depth, in the step as alone;
 *  - capture: a closing loop of known size captures a stalk whose axis
 *    crosses its plane inside it (half a stalk's width inside the wire),
 *    not one touching the wire from outside nor one a stalk's width
 *    away; an unlifted IIb base never, a lifted one yes; opening the
 *    handle lets go;
 *  - the hot cut after cut_j_per_m2 x pi t^2 / 4, which the pedal's power
 *    x time reaches within 2 %, nothing counted with the pedal up;
 *  - the cold cut of a 6 mm base and not of a 15 mm one;
 *  - the needle out under a flat base lifts it after lift_m3 injected,
 *    not a needle beyond the base's margin or one left in its catheter;
 *  - the forceps bite the mucosa within a cup's length, take a 3 mm
 *    polyp whole and sample a 6 mm one, once per closing; a clip closes
 *    on a wall within its jaws' length and not beyond;
 *  - the wall: the pedal on mucosa with nothing captured, or on a held
 *    unlifted sessile base, injures once per press; a loop off the wall
 *    or a lifted base does not;
 *  - bleeding: a stalk cut before coagulated (cold, or closed cold after
 *    0.9 of E_coag / P; hot above 10 mm) bleeds Q = bleed_m_per_s x its
 *    section, not after 1.1 of E_coag, nor a thin stalk, an 8 mm one cut
 *    hot or a sessile base; the blood shed is Q t at every step; it
 *    stops by itself bleed_stop_s after the cut, to a step; a clip on the
 *    point (or within half its jaws) stops it in its step, one a clip's
 *    width away does not;
 *  - retrieval: a cut polyp of 6 mm or less is sucked out with the valve
 *    pressed and the channel's exit within reach, not a 7 mm one, one
 *    beyond reach or without suction; a bitten large polyp's fate is
 *    partly resected;
 *  - the fall of a cut polyp to the lowest wall of its ring, in the
 *    drag's time, following a turn, onto the wall where the gas holds
 *    it and carried with that wall (each test below says how);
 *  - the case's polyps on the colon's wall (the polyps case).
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "geom_assert.h"
#include "model/anatomy.h"
#include "model/centreline.h"
#include "model/colon.h"
#include "model/gas.h"
#include "model/posture.h"
#include "model/tool.h"
#include "base/vec3.h"
#include "plain_anatomy.h"

#define DT 0.001
#define SNARE 0.020 /* a 20 mm snare */
#define DEPTH 0.020 /* its sheath 2 cm out */

static const struct tool_params par = TOOL_PARAMS_DEFAULT;

/* A tool on a tip at (0.1, 0.2, 0.3) looking along x, 12 o'clock z: the
 * image's right is dir x up = -y. */
struct bench {
	struct tool t;
	struct endosim_scope_state sc;
	struct tool_input in;
	unsigned events;  /* every step's, or'ed */
	int polyp;        /* the last event's */
	long cut_step;    /* the step a cut came in (from 1), 0: none */
	int injuries;
};

static void bench_init(struct bench *b)
{
	memset(b, 0, sizeof(*b));
	tool_reset(&b->t);
	vec3_set(b->sc.tip, 0.1, 0.2, 0.3);
	vec3_set(b->sc.dir, 1, 0, 0);
	vec3_set(b->sc.up, 0, 0, 1);
	b->in.depth_m = DEPTH;
	b->in.opening = 1;
	b->polyp = -1;
}

/* N steps with the handle moving linearly from where it is to OPENING. */
static void run(struct bench *b, long n, double opening)
{
	double from = b->in.opening;

	for (long k = 1; k <= n; k++) {
		unsigned ev;
		int p;

		b->in.opening = from + (opening - from) * (double)k / n;
		ev = tool_step(&b->t, &par, &b->sc, &b->in, DT, &p);
		if (ev) {
			b->polyp = p;
		}
		if (ev & TOOL_EVENT_CUT) {
			assert_int_equal(b->cut_step, 0); /* once */
			b->cut_step = k;
		}
		b->injuries += (ev & TOOL_EVENT_INJURY) != 0;
		b->events |= ev;
	}
}

/* The snare open at its full size, its loop placed. */
static void open_snare(struct bench *b, double snare_m)
{
	assert_int_equal(tool_select(&b->t, TOOL_SNARE, snare_m), 0);
	run(b, 10, 1);
	assert_near(b->t.loop_m, snare_m, 1e-12);
}

/*
 * A polyp of class PARIS, SIZE_M, its stalk T_M thick (Ip), whose axis
 * (the wall's normal, towards the tip's axis) crosses the open loop's
 * plane at OFF_M from the loop's centre along the loop's width: its base
 * half its height below the plane. Returns its index.
 */
static int polyp_at(struct bench *b, int paris, double size_m, double t_m,
		    double off_m, bool lifted)
{
	struct anatomy_polyp ap = {
		.diameter_m = size_m, .paris = paris,
		.stalk_length_m = paris == ANATOMY_PARIS_IP ? 0.008 : 0,
		.stalk_diameter_m = paris == ANATOMY_PARIS_IP ? t_m : 0,
	};
	const struct tool_pose *po = &b->t.pose;
	double base[3], n[3], h;
	int i;

	vec3_scale(n, po->radial, -1);
	vec3_axpy(base, b->t.loop_centre, off_m, po->side);
	i = tool_add_polyp(&b->t, &ap, base, n);
	assert_true(i >= 0);
	b->t.polyp[i].lifted = lifted;
	h = tool_polyp_height(&b->t.polyp[i], par.lift_m);
	assert_true(h > 0 || paris == ANATOMY_PARIS_IIB);
	vec3_axpy(b->t.polyp[i].base, base, h / 2, po->radial);
	return i;
}

/* ------------------------------------------------------------ the pose */

static void test_pose_at_channel_angle(void **unused)
{
	struct tool_params p = par;
	struct bench b;
	double right[3] = { 0, -1, 0 }, want[3];
	const double a = 150 * M_PI / 180, r = par.channel_offset_m;

	(void)unused;
	bench_init(&b);
	tool_pose(&p, &b.sc, 0.015, &b.t.pose);
	/* 5 o'clock: down (-up) and to the right */
	assert_true(vec3_dot(b.t.pose.radial, b.sc.up) < -0.8);
	assert_true(vec3_dot(b.t.pose.radial, right) > 0.45);
	vec3_set(want, 0.1, 0.2 - r * sin(a), 0.3 + r * cos(a));
	assert_vec_near(b.t.pose.exit, want, 1e-12);
	want[0] += 0.015;
	assert_vec_near(b.t.pose.tip, want, 1e-12);
	assert_vec_near(b.t.pose.dir, b.sc.dir, 1e-12);
	assert_near(vec3_dot(b.t.pose.side, b.t.pose.radial), 0, 1e-12);
	assert_near(vec3_dot(b.t.pose.side, b.t.pose.dir), 0, 1e-12);
	/* 3 o'clock: straight right; 12 o'clock: straight up */
	p.channel_angle_rad = M_PI / 2;
	tool_pose(&p, &b.sc, -0.01, &b.t.pose);
	vec3_set(want, 0.1 - 0.01, 0.2 - r, 0.3);
	assert_vec_near(b.t.pose.tip, want, 1e-12);
	p.channel_angle_rad = 0;
	tool_pose(&p, &b.sc, 0, &b.t.pose);
	vec3_set(want, 0.1, 0.2, 0.3 + r);
	assert_vec_near(b.t.pose.exit, want, 1e-12);
}

/* ---------------------------------------------------- the loop's size */

static void test_loop_diameter_formula(void **unused)
{
	static const struct {
		double snare, opening, depth;
	} at[] = {
		{ 0.020, 0, 0.02 }, { 0.020, 0.25, 0.02 }, { 0.020, 0.5, 0 },
		{ 0.020, 1, 0.01 }, { 0.010, 0.7, 0.03 }, { 0.030, 1, -0.005 },
		{ 0.030, 0.5, -0.01 }, { 0.020, 1, -0.04 }, { 0.020, 1.5, 0.02 },
	};
	struct bench b;

	(void)unused;
	for (size_t i = 0; i < sizeof(at) / sizeof(at[0]); i++) {
		double o = fmin(1, at[i].opening), l, want;

		l = o * M_PI * at[i].snare / 2 + fmin(0, at[i].depth);
		want = fmin(at[i].snare, 2 * fmax(0, l) / M_PI);
		assert_near(tool_loop_diameter(at[i].snare, at[i].opening,
					       at[i].depth), want, 1e-12);
		bench_init(&b);
		assert_int_equal(tool_select(&b.t, TOOL_SNARE, at[i].snare), 0);
		b.in.depth_m = at[i].depth;
		b.in.opening = at[i].opening;
		run(&b, 1, at[i].opening);
		assert_near(b.t.loop_m, want, 1e-12);
	}
	/* at full opening and depth, the snare's size; half open, half */
	assert_near(tool_loop_diameter(0.02, 1, 0.02), 0.02, 1e-12);
	assert_near(tool_loop_diameter(0.02, 0.5, 0.02), 0.01, 1e-12);
	/* the loop's centre half its diameter beyond the sheath's tip */
	bench_init(&b);
	open_snare(&b, SNARE);
	assert_near(vec3_dist(b.t.loop_centre, b.t.pose.tip), SNARE / 2,
		    1e-12);
	assert_int_equal(tool_select(&b.t, TOOL_SNARE, 0.035), -EINVAL);
	assert_int_equal(tool_select(&b.t, 7, 0), -EINVAL);
}

/* --------------------------------------------------------------- capture */

/* A 20 mm loop closing in 0.5 s on a 4 mm stalk OFF_M from its centre:
 * whether it captured it. */
static bool closes_on(double off_m)
{
	struct bench b;
	int i;

	bench_init(&b);
	open_snare(&b, SNARE);
	i = polyp_at(&b, ANATOMY_PARIS_IP, 0.012, 0.004, off_m, false);
	run(&b, 5, 1);
	run(&b, 500, 0.1);
	if (b.events & TOOL_EVENT_CAPTURE) {
		assert_int_equal(b.t.captured, i);
		assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_CAPTURED);
		assert_int_equal(b.polyp, i);
		assert_near(b.t.loop_m, 0.004, 1e-12); /* held at its width */
		return true;
	}
	assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_IN_PLACE);
	return false;
}

static void test_capture_inside_not_outside(void **unused)
{
	const double r = SNARE / 2, t = 0.004;

	(void)unused;
	assert_true(closes_on(0));
	assert_true(closes_on(r / 2));
	assert_true(closes_on(-(r - t / 2)));  /* half its width inside */
	assert_true(closes_on(r - 0.1 * t));   /* the axis just inside */
	assert_false(closes_on(r + 0.1 * t));  /* the axis just outside */
	assert_false(closes_on(r + t / 2));    /* touching from outside */
	assert_false(closes_on(-(r + t)));     /* a stalk's width away */
	assert_false(closes_on(2 * r));
}

/* The loop held still, its wire against a stalk inside it, does not
 * capture it; closing does; opening it lets go. */
static void test_capture_needs_closing(void **unused)
{
	struct bench b;
	int i;

	(void)unused;
	bench_init(&b);
	open_snare(&b, SNARE);
	i = polyp_at(&b, ANATOMY_PARIS_IP, 0.012, 0.004,
		     SNARE / 2 - 0.001, false);
	run(&b, 500, 1);
	assert_int_equal(b.events, 0);
	run(&b, 500, 0.1);
	assert_int_equal(b.t.captured, i);
	run(&b, 100, 0.8);
	assert_true(b.events & TOOL_EVENT_RELEASE);
	assert_int_equal(b.t.captured, -1);
	assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_IN_PLACE);
	assert_near(b.t.loop_m, 0.8 * SNARE, 1e-12);
}

/* A flat IIb base: nothing to close around unless lifted. */
static void test_flat_base_needs_lift(void **unused)
{
	struct bench b;

	(void)unused;
	bench_init(&b);
	open_snare(&b, SNARE);
	polyp_at(&b, ANATOMY_PARIS_IIB, 0.008, 0, 0, false);
	run(&b, 500, 0);
	assert_false(b.events & TOOL_EVENT_CAPTURE);
	bench_init(&b);
	open_snare(&b, SNARE);
	polyp_at(&b, ANATOMY_PARIS_IIB, 0.008, 0, 0, true);
	run(&b, 500, 0.1);
	assert_true(b.events & TOOL_EVENT_CAPTURE);
	assert_near(b.t.loop_m, 0.008, 1e-12);
}

/* ------------------------------------------------------------------ cuts */

/* A stalk T_M thick captured and held (the handle not closed enough for
 * a cold cut). */
static int held_stalk(struct bench *b, double t_m)
{
	int i;

	bench_init(b);
	open_snare(b, SNARE);
	i = polyp_at(b, ANATOMY_PARIS_IP, 0.015, t_m, 0, false);
	run(b, 500, 0.1);
	assert_int_equal(b->t.captured, i);
	return i;
}

static void test_hot_cut_energy(void **unused)
{
	static const double stalk[] = { 0.003, 0.005, 0.008 };

	(void)unused;
	for (size_t k = 0; k < sizeof(stalk) / sizeof(stalk[0]); k++) {
		double t = stalk[k], need_j, got_j;
		struct bench b;
		int i = held_stalk(&b, t);

		need_j = par.cut_j_per_m2 * M_PI * t * t / 4;
		/* pedal up for a second: nothing counted, nothing cut */
		run(&b, 1000, 0.1);
		assert_near(b.t.polyp[i].energy_j, 0, 0);
		assert_int_equal(b.cut_step, 0);
		b.in.pedal = true;
		run(&b, lround(2 * need_j / par.hot_power_w / DT), 0.1);
		assert_true(b.cut_step > 0);
		got_j = par.hot_power_w * b.cut_step * DT;
		assert_near(got_j, need_j, 0.02 * need_j);
		assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_CUT);
		assert_int_equal(b.t.captured, -1);
		assert_int_equal(b.polyp, i);
		assert_int_equal(b.injuries, 0); /* a stalk: no wall */
	}
}

/* A sessile base SIZE_M across, the snare closed all the way without the
 * pedal: whether it was cut. */
static bool cold_cuts(double size_m)
{
	struct bench b;
	int i;

	bench_init(&b);
	open_snare(&b, 0.025);
	i = polyp_at(&b, ANATOMY_PARIS_IS, size_m, 0, 0, false);
	run(&b, 500, 0.2);
	assert_int_equal(b.t.captured, i);
	run(&b, 500, 0);
	run(&b, 500, 0);
	assert_int_equal(b.injuries, 0);
	assert_int_equal(b.events & TOOL_EVENT_BLEED, 0); /* no stalk */
	assert_int_equal(b.t.polyp[i].state, b.cut_step ? TOOL_POLYP_CUT :
				      TOOL_POLYP_CAPTURED);
	return b.cut_step > 0;
}

static void test_cold_cut_small_only(void **unused)
{
	(void)unused;
	assert_true(cold_cuts(0.004));
	assert_true(cold_cuts(0.006));
	assert_true(cold_cuts(0.0095));
	assert_false(cold_cuts(0.0105));
	assert_false(cold_cuts(0.015));
}

/* -------------------------------------------------------------- the wall */

/* The pedal on mucosa with nothing captured: one injury per press; the
 * loop 5 mm off the wall: none. */
static void test_pedal_on_mucosa_injures(void **unused)
{
	struct bench b;

	(void)unused;
	for (int off = 0; off < 2; off++) {
		bench_init(&b);
		open_snare(&b, SNARE);
		b.in.wall = true;
		vec3_axpy(b.in.wall_point, b.t.loop_centre, off * 0.005,
			  b.t.pose.radial);
		vec3_scale(b.in.wall_normal, b.t.pose.radial, -1);
		b.in.pedal = true;
		run(&b, 300, 0.2);
		assert_int_equal(b.injuries, off ? 0 : 1);
		b.in.pedal = false;
		run(&b, 10, 0.2);
		b.in.pedal = true;
		run(&b, 10, 0.2);
		assert_int_equal(b.injuries, off ? 0 : 2);
		assert_int_equal(b.polyp, -1);
		if (!off) {
			assert_vec_near(b.t.injury_at, b.in.wall_point, 0);
		}
	}
}

/* Hot current through a held sessile base: an injury unless lifted; the
 * lifted one is cut clean. */
static void test_hot_unlifted_base_injures(void **unused)
{
	for (int lifted = 0; lifted < 2; lifted++) {
		struct bench b;
		int i;

		(void)unused;
		bench_init(&b);
		open_snare(&b, SNARE);
		i = polyp_at(&b, ANATOMY_PARIS_IIA, 0.008, 0, 0, lifted);
		run(&b, 500, 0.2);
		assert_int_equal(b.t.captured, i);
		b.in.pedal = true;
		run(&b, 10000, 0.2);
		assert_int_equal(b.injuries, lifted ? 0 : 1);
		assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_CUT);
		if (!lifted) {
			assert_vec_near(b.t.injury_at, b.t.polyp[i].base, 0);
		}
	}
}

/* The needle out, its point 2 mm under a flat base OFF_M aside from its
 * centre, for 5 s: the step it lifted in (from 1), 0: not. */
static long lifts_after(double off_m, double opening)
{
	struct anatomy_polyp ap = { .diameter_m = 0.008,
				    .paris = ANATOMY_PARIS_IIB };
	struct bench b;
	double base[3], n[3];
	int i;

	bench_init(&b);
	assert_int_equal(tool_select(&b.t, TOOL_NEEDLE, 0), 0);
	b.in.opening = opening;
	run(&b, 1, opening);
	vec3_scale(n, b.t.pose.radial, -1);
	vec3_copy(base, b.t.pose.tip);
	vec3_axpy(base, base, par.needle_m, b.t.pose.dir);
	vec3_axpy(base, base, 0.002, n);
	vec3_axpy(base, base, off_m, b.t.pose.side);
	i = tool_add_polyp(&b.t, &ap, base, n);
	for (long k = 1; k <= 5000; k++) {
		int p;

		if (tool_step(&b.t, &par, &b.sc, &b.in, DT, &p) &
		    TOOL_EVENT_LIFT) {
			assert_int_equal(p, i);
			assert_true(b.t.polyp[i].lifted);
			return k;
		}
	}
	assert_false(b.t.polyp[i].lifted);
	return 0;
}

static void test_needle_lifts_base(void **unused)
{
	long want = lround(par.lift_m3 / par.inject_m3_per_s / DT);

	(void)unused;
	assert_true(labs(lifts_after(0, 1) - want) <= 1);
	assert_true(labs(lifts_after(0.008, 1) - want) <= 1);
	assert_int_equal(lifts_after(0.010, 1), 0); /* beyond its margin */
	assert_int_equal(lifts_after(0, 0.3), 0);   /* the needle in */
}

/* TOOL (forceps or clip) out, the wall WALL_M beyond its jaws' point
 * (-1: none), a sessile polyp of SIZE_M centred on that point (0: none);
 * the handle opened and closed twice over: the events of the first
 * closing; the second, without opening again, has none. */
static unsigned jaws_on(struct bench *b, int kind, double wall_m,
			double size_m)
{
	unsigned first;

	bench_init(b);
	assert_int_equal(tool_select(&b->t, kind, 0), 0);
	b->in.opening = 0;
	run(b, 1, 0);
	if (wall_m >= 0) {
		b->in.wall = true;
		vec3_axpy(b->in.wall_point, b->t.jaws, wall_m, b->t.pose.radial);
		vec3_scale(b->in.wall_normal, b->t.pose.radial, -1);
	}
	if (size_m > 0) {
		struct anatomy_polyp ap = { .diameter_m = size_m,
					    .paris = ANATOMY_PARIS_IS };
		double base[3], n[3];

		vec3_scale(n, b->t.pose.radial, -1);
		vec3_axpy(base, b->t.jaws, -size_m / 4, n);
		assert_int_equal(tool_add_polyp(&b->t, &ap, base, n), 0);
	}
	run(b, 100, 1);
	assert_int_equal(b->events, 0);
	run(b, 100, 0);
	first = b->events;
	b->events = 0;
	run(b, 100, 0.3);
	run(b, 100, 0);
	assert_int_equal(b->events, 0);
	return first;
}

static void test_forceps_bite(void **unused)
{
	struct bench b;

	(void)unused;
	assert_int_equal(jaws_on(&b, TOOL_FORCEPS, 0.001, 0), TOOL_EVENT_BITE);
	assert_int_equal(b.polyp, -1);
	assert_vec_near(b.t.bite_at, b.t.jaws, 0);
	assert_int_equal(jaws_on(&b, TOOL_FORCEPS, 0.004, 0), 0);
	assert_int_equal(jaws_on(&b, TOOL_FORCEPS, -1, 0), 0);
	/* a diminutive polyp taken whole; a larger one sampled */
	assert_int_equal(jaws_on(&b, TOOL_FORCEPS, -1, 0.003),
			 TOOL_EVENT_BITE | TOOL_EVENT_CUT |
				 TOOL_EVENT_RETRIEVE);
	assert_int_equal(b.t.polyp[0].state, TOOL_POLYP_RETRIEVED);
	assert_int_equal(jaws_on(&b, TOOL_FORCEPS, -1, 0.006),
			 TOOL_EVENT_BITE);
	assert_int_equal(b.t.polyp[0].state, TOOL_POLYP_IN_PLACE);
	assert_int_equal(b.t.polyp[0].bites, 1);
	assert_int_equal(b.polyp, 0);
	/* still in the channel, on the wall: no bite */
	bench_init(&b);
	assert_int_equal(tool_select(&b.t, TOOL_FORCEPS, 0), 0);
	b.in.depth_m = -0.001;
	run(&b, 1, 0);
	b.in.wall = true;
	vec3_copy(b.in.wall_point, b.t.jaws);
	vec3_scale(b.in.wall_normal, b.t.pose.radial, -1);
	run(&b, 100, 1);
	run(&b, 100, 0);
	assert_int_equal(b.events, 0);
}

static void test_clip_on_wall(void **unused)
{
	struct bench b;
	double want[3];

	(void)unused;
	assert_int_equal(jaws_on(&b, TOOL_CLIP, 0.003, 0), TOOL_EVENT_CLIP);
	assert_int_equal(b.t.clips, 1);
	vec3_axpy(want, b.t.pose.tip, par.clip_m, b.t.pose.dir);
	assert_vec_near(b.t.clip_at, want, 1e-15);
	assert_int_equal(jaws_on(&b, TOOL_CLIP, 0.008, 0), 0);
	assert_int_equal(b.t.clips, 0);
}

/* Non-finite readings hold the tool still with the pedal up; another
 * tool than the snare has a pose and nothing else. */
static void test_still_and_other_tools(void **unused)
{
	struct bench b;
	double tip[3];

	(void)unused;
	held_stalk(&b, 0.004);
	vec3_copy(tip, b.t.pose.tip);
	b.in.depth_m = NAN;
	b.in.pedal = true;
	run(&b, 100, 0.1);
	assert_vec_near(b.t.pose.tip, tip, 0);
	assert_near(b.t.polyp[b.t.captured].energy_j, 0, 0);
	b.in.depth_m = DEPTH;
	b.in.opening = INFINITY;
	run(&b, 1, INFINITY);
	assert_near(b.t.polyp[b.t.captured].energy_j, 0, 0);
	assert_int_equal(tool_select(&b.t, TOOL_FORCEPS, 0), 0);
	assert_int_equal(b.t.captured, -1);
	b.in.opening = 0;
	b.events = 0;
	run(&b, 100, 1);
	assert_int_equal(b.events, 0);
	assert_near(b.t.loop_m, 0, 0);
}

/* ------------------------------------------------------------ bleeding */

/* Q = bleed_m_per_s x pi t^2 / 4 and E_coag = coag_j_per_m3 x pi t^2/4 t */
static double flow(double t_m)
{
	return par.bleed_m_per_s * M_PI * t_m * t_m / 4;
}

static double coag_j(double t_m)
{
	return par.coag_j_per_m3 * M_PI * t_m * t_m / 4 * t_m;
}

/* A stalk T_M thick held, PEDAL_S of the pedal, then (the pedal up) the
 * handle closed all the way: whether the cut bled (and its flow then). */
static bool cut_bleeds(double t_m, double pedal_s, struct bench *b)
{
	int i = held_stalk(b, t_m);

	b->in.pedal = true;
	run(b, lround(pedal_s / DT), 0.1);
	b->in.pedal = false;
	run(b, 500, 0);
	assert_true(b->cut_step > 0);
	assert_int_equal(b->t.polyp[i].state, TOOL_POLYP_CUT);
	if (!(b->events & TOOL_EVENT_BLEED)) {
		assert_int_equal(b->t.polyp[i].bleed, TOOL_BLEED_NONE);
		assert_near(b->t.polyp[i].bleed_m3_s, 0, 0);
		return false;
	}
	assert_int_equal(b->t.polyp[i].bleed, TOOL_BLEED_BLEEDING);
	assert_near(b->t.polyp[i].bleed_m3_s, flow(t_m), 1e-18);
	return true;
}

/*
 * A stalk cut before it is coagulated bleeds: cold (5 and 8 mm), or
 * closed cold after 0.9 of E_coag / P; not after 1.1 of it, nor a 2.5 mm
 * stalk (below bleed_min_m), nor a hot cut of 8 mm (E_cut > E_coag);
 * a hot cut of 12 mm does (E_cut < E_coag: above 10 mm); a sessile base
 * cut cold never.
 */
static void test_bleed_uncoagulated_stalk(void **unused)
{
	struct bench b;
	double t = 0.005;

	(void)unused;
	assert_true(cut_bleeds(t, 0, &b));
	assert_int_equal(b.polyp, 0);
	assert_true(cut_bleeds(0.008, 0, &b));
	assert_false(cut_bleeds(0.0025, 0, &b));
	assert_true(cut_bleeds(t, 0.9 * coag_j(t) / par.hot_power_w, &b));
	assert_false(cut_bleeds(t, 1.1 * coag_j(t) / par.hot_power_w, &b));
	/* hot through: E_cut = cut_j_per_m2 pi t^2 / 4 */
	for (int k = 0; k < 2; k++) {
		double th = k ? 0.012 : 0.008;
		double cut_s = par.cut_j_per_m2 * M_PI * th * th / 4 /
			       par.hot_power_w;
		int i = held_stalk(&b, th);

		b.in.pedal = true;
		run(&b, lround(1.1 * cut_s / DT), 0.1);
		assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_CUT);
		assert_int_equal((b.events & TOOL_EVENT_BLEED) != 0, k);
	}
	assert_true(cold_cuts(0.006)); /* a base: it checks no bleed */
}

/* The cut 5 mm stalk's bleed: V = Q t at every step, and it stops by
 * itself bleed_stop_s after the cut (to a step), not before. */
static void test_bleed_volume_and_stop(void **unused)
{
	const double dt = 0.01;
	struct bench b;
	double q = flow(0.005), bled_s;
	bool stopped = false;

	(void)unused;
	assert_true(cut_bleeds(0.005, 0, &b));
	bled_s = (double)(500 - b.cut_step + 1) * DT; /* from the cut's */
	assert_near(b.t.blood_m3, q * bled_s, 1e-9 * q * bled_s);
	assert_near(b.t.polyp[0].blood_m3, b.t.blood_m3, 0);
	while (bled_s < 2 * par.bleed_stop_s) {
		unsigned ev = tool_step(&b.t, &par, &b.sc, &b.in, dt, NULL);

		if (ev & TOOL_EVENT_STOPPED) {
			stopped = true;
			break;
		}
		assert_int_equal(ev, 0);
		bled_s += dt;
		assert_near(b.t.blood_m3, q * bled_s, 1e-9 * q * bled_s);
	}
	assert_true(stopped);
	assert_true(bled_s >= par.bleed_stop_s - dt &&
		    bled_s <= par.bleed_stop_s + dt);
	assert_int_equal(b.t.polyp[0].bleed, TOOL_BLEED_STOPPED);
	assert_near(b.t.polyp[0].bleed_m3_s, 0, 0);
	run(&b, 100, 0);
	assert_near(b.t.blood_m3, q * bled_s, 1e-9 * q * bled_s);
}

/* The scope moved so that the clip's point lands OFF_M along the loop's
 * width from polyp I's base, on the wall there; the clip closed. */
static unsigned clip_at_point(struct bench *b, int i, double off_m)
{
	const struct tool_polyp *p = &b->t.polyp[i];
	double jaws[3];
	unsigned ev = 0;

	assert_int_equal(tool_select(&b->t, TOOL_CLIP, 0), 0);
	vec3_axpy(jaws, p->base, off_m, b->t.pose.side);
	vec3_axpy(b->sc.tip, jaws, -(par.clip_m + DEPTH), b->t.pose.dir);
	vec3_axpy(b->sc.tip, b->sc.tip, -par.channel_offset_m,
		  b->t.pose.radial);
	b->in.depth_m = DEPTH;
	b->in.wall = true;
	vec3_copy(b->in.wall_point, jaws);
	vec3_copy(b->in.wall_normal, p->normal);
	b->events = 0;
	run(b, 100, 1);
	assert_vec_near(b->t.jaws, jaws, 1e-12);
	run(b, 100, 0);
	ev = b->events;
	assert_true(ev & TOOL_EVENT_CLIP);
	return ev;
}

/* A clip on the point stops the bleed in its step (nothing shed after);
 * one at 0.45 clip_m too; one a clip's width (clip_m) away does not. */
static void test_clip_stops_bleed(void **unused)
{
	static const double off[] = { 0, 0.45 * TOOL_DEFAULT_CLIP_M,
				       TOOL_DEFAULT_CLIP_M };

	(void)unused;
	for (size_t k = 0; k < sizeof(off) / sizeof(off[0]); k++) {
		bool stops = off[k] <= par.clip_m / 2;
		struct bench b;
		double shed, q = flow(0.005);
		unsigned ev;

		assert_true(cut_bleeds(0.005, 0, &b));
		ev = clip_at_point(&b, 0, off[k]);
		assert_int_equal((ev & TOOL_EVENT_CLIPPED) != 0, stops);
		shed = b.t.blood_m3;
		run(&b, 1000, 0);
		assert_int_equal(b.t.polyp[0].bleed, stops ?
				 TOOL_BLEED_CLIPPED : TOOL_BLEED_BLEEDING);
		assert_near(b.t.blood_m3 - shed, stops ? 0 : q * 1000 * DT,
			    1e-9 * q);
	}
}

/* ----------------------------------------------------------- retrieval */

/* A sessile SIZE_M polyp cut cold; the channel's exit then moved to
 * REACH_M off its body's surface (radially), with the suction SUCTION:
 * its state after 10 steps. */
static int retrieved(double size_m, double reach_m, bool suction)
{
	struct bench b;
	double body[3], exit[3];
	int i;

	bench_init(&b);
	open_snare(&b, 0.025);
	i = polyp_at(&b, ANATOMY_PARIS_IS, size_m, 0, 0, false);
	run(&b, 500, 0.2);
	run(&b, 500, 0);
	assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_CUT);
	assert_int_equal(b.events & TOOL_EVENT_RETRIEVE, 0);
	vec3_axpy(body, b.t.polyp[i].base, size_m / 4, b.t.polyp[i].normal);
	vec3_axpy(exit, body, size_m / 2 + reach_m, b.t.pose.side);
	vec3_axpy(b.sc.tip, exit, -par.channel_offset_m, b.t.pose.radial);
	b.in.suction = suction;
	b.events = 0;
	run(&b, 10, 0);
	assert_vec_near(b.t.pose.exit, exit, 1e-12);
	assert_int_equal((b.events & TOOL_EVENT_RETRIEVE) != 0,
			 b.t.polyp[i].state == TOOL_POLYP_RETRIEVED);
	return b.t.polyp[i].state;
}

/* Sucked out when small, the exit within reach and the valve pressed;
 * left lying otherwise. */
static void test_retrieve_small_only(void **unused)
{
	const double r = TOOL_DEFAULT_RETRIEVE_REACH_M;

	(void)unused;
	assert_int_equal(retrieved(0.005, 0.9 * r, true),
			 TOOL_POLYP_RETRIEVED);
	assert_int_equal(retrieved(0.006, 0, true), TOOL_POLYP_RETRIEVED);
	assert_int_equal(retrieved(0.007, 0, true), TOOL_POLYP_CUT);
	assert_int_equal(retrieved(0.005, 1.1 * r, true), TOOL_POLYP_CUT);
	assert_int_equal(retrieved(0.005, 0, false), TOOL_POLYP_CUT);
}

/* --------------------------------------------------------------- the fall */

#define FALL_S_M 0.30   /* the cut polyp's ring: the sigmoid */
#define FALL_SIZE 0.006 /* a 6 mm sessile polyp */
#define G_M_S2 9.81

/* A 6 mm sessile polyp cut cold by the bench's snare, its ring at
 * FALL_S_M, then put (as if it came free there) at AT; *I its index. */
static void cut_free(struct bench *b, const double at[3], int *i)
{
	bench_init(b);
	open_snare(b, 0.025);
	*i = polyp_at(b, ANATOMY_PARIS_IS, FALL_SIZE, 0, 0, false);
	run(b, 500, 0.2);
	run(b, 500, 0);
	assert_int_equal(b->t.polyp[*i].state, TOOL_POLYP_CUT);
	assert_false(b->t.polyp[*i].rest_ok);
	b->t.polyp[*i].s_m = FALL_S_M;
	vec3_copy(b->t.polyp[*i].at, at);
	vec3_copy(b->t.polyp[*i].rest, at);
}

/* A colon of the plain anatomy (a round lumen DIAMETER_M wide, no folds,
 * no taeniae) or, with PATH, that case's. */
static struct colon *fall_colon(const char *path, double diameter_m)
{
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct anatomy a;
	struct colon *c;
	char err[256];

	if (path) {
		assert_int_equal(anatomy_load(&a, path, err, sizeof(err)), 0);
	} else {
		plain_anatomy(&a, diameter_m);
	}
	c = colon_create(&a, &cp, err, sizeof(err));
	assert_non_null(c);
	return c;
}

/* The time (s) a body from rest takes over L_M pulled by G_M_S2 against a
 * drag of TAU_S (tool.h): L = g tau (t - tau (1 - exp(-t / tau))). */
static double fall_time(double l_m, double g_m_s2, double tau_s)
{
	double lo = 0, hi = 10;

	for (int k = 0; k < 200; k++) {
		double t = (lo + hi) / 2;
		double x = g_m_s2 * tau_s * (t - tau_s * (1 - exp(-t / tau_s)));

		if (x < l_m) {
			lo = t;
		} else {
			hi = t;
		}
	}
	return (lo + hi) / 2;
}

/* Steps of tool_fall() with gravity G until polyp I arrives where it
 * rests (at most MAX); the steps taken. */
static long fall_until_rest(struct bench *b, const struct colon *c,
			    const double g[3], int i, long max)
{
	const struct tool_polyp *p = &b->t.polyp[i];
	long n = 0;

	do {
		tool_fall(&b->t, &par, c, g, NULL, DT);
		n++;
	} while (n < max && !(p->rest_ok && vec3_dist(p->at, p->rest) == 0));
	return n;
}

/*
 * From the lumen's axis in a round lumen 50 mm across, the cut polyp
 * falls to the wall point lowest along gravity, its radius in: supine
 * (gravity +y) and lying on the left (+x), gravity's part across the
 * ring, R - size/2 from the axis. It gets there in the time the drag's
 * law gives for that distance (to a step), and stays at rest after.
 */
static void falls_to(const double down[3])
{
	struct colon *c = fall_colon(NULL, 0.05);
	struct centreline_point q;
	double g[3], across[3], want[3], l, t_s;
	struct bench b;
	long n;
	int i;

	centreline_at_s(colon_centreline(c), FALL_S_M, &q);
	cut_free(&b, q.p, &i);
	vec3_scale(g, down, G_M_S2);
	vec3_axpy(across, down, -vec3_dot(down, q.t), q.t);
	assert_true(vec3_normalize(across) > 0.9);
	l = 0.025 - FALL_SIZE / 2;
	vec3_axpy(want, q.p, l, across);
	t_s = fall_time(l, G_M_S2, par.fall_drag_s);
	n = fall_until_rest(&b, c, g, i, 10000);
	print_message("down (%g, %g, %g): %.1f mm in %ld steps, the law's "
		      "%.4f s\n", down[0], down[1], down[2], l * 1e3, n, t_s);
	assert_vec_near(b.t.polyp[i].at, want, 1e-9);
	assert_true(fabs((double)n - t_s / DT) <= 1);
	for (int k = 0; k < 100; k++) {
		tool_fall(&b.t, &par, c, g, NULL, DT);
	}
	assert_vec_near(b.t.polyp[i].at, want, 1e-9);
	assert_true(b.t.polyp[i].fall_v == 0);
	assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_CUT);
	colon_destroy(c);
}

static void test_fall_supine_and_left(void **unused)
{
	const double supine[3] = { 0, 1, 0 }, left[3] = { 1, 0, 0 };

	(void)unused;
	falls_to(supine);
	falls_to(left);
}

/*
 * In the polyps case's sigmoid (taeniae and folds: a ring not round) the
 * rest is the lowest of 3600 points round the ring to 0.01 mm along
 * gravity, its body's radius in along the ring's radius there.
 */
static void test_fall_lowest_of_ring(void **unused)
{
	struct colon *c = fall_colon("config/cases/polyps.case", 0);
	const double down[3] = { 0.6, 0.8, 0 };
	struct centreline_point q;
	double g[3], x[3], best = -1, got;
	struct bench b;
	int i;

	(void)unused;
	centreline_at_s(colon_centreline(c), FALL_S_M, &q);
	cut_free(&b, q.p, &i);
	for (int k = 0; k < 3600; k++) {
		double th = 2 * M_PI * k / 3600;
		double r = colon_lumen_radius(c, FALL_S_M, th);

		vec3_scale(x, q.u, r * cos(th));
		vec3_axpy(x, x, r * sin(th), q.v);
		best = fmax(best, vec3_dot(x, down));
	}
	vec3_scale(g, down, G_M_S2);
	fall_until_rest(&b, c, g, i, 10000);
	/* the wall behind the body: its radius on along the ring's radius */
	vec3_sub(x, b.t.polyp[i].at, q.p);
	got = vec3_dot(x, down);
	vec3_normalize(x);
	got += FALL_SIZE / 2 * vec3_dot(x, down);
	print_message("lowest wall along gravity %.4f mm, the rest's %.4f mm\n",
		      best * 1e3, got * 1e3);
	assert_near(got, best, 1e-5);
	colon_destroy(c);
}

/*
 * The patient turned from the back onto the left side over 2 s (the
 * posture's eased turn): the polyp lying on the dependent wall follows it
 * round, within 1 mm of the wall all the way, and lies at the left
 * side's rest once the turn is over. Without gravity it lies still.
 */
static void test_fall_follows_turn(void **unused)
{
	struct colon *c = fall_colon(NULL, 0.05);
	struct centreline_point q;
	double g[3], want[3], across[3], worst = 0;
	struct posture pos;
	struct bench b;
	int i;

	(void)unused;
	centreline_at_s(colon_centreline(c), FALL_S_M, &q);
	cut_free(&b, q.p, &i);
	posture_reset(&pos, POSTURE_SUPINE);
	vec3_scale(g, pos.down, G_M_S2);
	fall_until_rest(&b, c, g, i, 10000);
	assert_int_equal(posture_turn(&pos, POSTURE_LEFT_LATERAL, 2), 0);
	for (int k = 0; k < 2500; k++) {
		double x[3], off;

		posture_step(&pos, DT);
		vec3_scale(g, pos.down, G_M_S2);
		tool_fall(&b.t, &par, c, g, NULL, DT);
		vec3_sub(x, b.t.polyp[i].at, q.p);
		off = 0.025 - FALL_SIZE / 2 - vec3_norm(x);
		worst = fmax(worst, off);
	}
	vec3_axpy(across, pos.down, -vec3_dot(pos.down, q.t), q.t);
	vec3_normalize(across);
	vec3_axpy(want, q.p, 0.025 - FALL_SIZE / 2, across);
	print_message("turned supine to left lateral: at most %.3f mm off the "
		      "wall\n", worst * 1e3);
	assert_true(worst < 0.001);
	assert_vec_near(b.t.polyp[i].at, want, 1e-9);
	memset(g, 0, sizeof(g));
	vec3_copy(want, b.t.polyp[i].at);
	for (int k = 0; k < 100; k++) {
		tool_fall(&b.t, &par, c, g, NULL, DT);
	}
	assert_vec_near(b.t.polyp[i].at, want, 0);
	colon_destroy(c);
}

/* Every segment's radius factor F, into FACTOR. */
static void factors(double factor[GAS_SEGMENTS], double f)
{
	for (int k = 0; k < GAS_SEGMENTS; k++) {
		factor[k] = f;
	}
}

/* Polyp P's distance from the ring's centre Q less F times R (its
 * centre's on the wall of radius R at factor 1, the body's radius in:
 * f R - size / 2 from the axis): 0 on the wall the gas holds. */
static double off_gas_wall(const struct tool_polyp *p,
			   const struct centreline_point *q, double f, double r)
{
	return vec3_dist(p->at, q->p) - (f * r - p->size_m / 2);
}

/*
 * The wall where the gas holds it. In the polyps case's sigmoid
 * collapsed to a radius factor of 0.6, the cut polyp falls to the lowest
 * of 3600 points round the ring scaled by 0.6, its radius in (not to the
 * case's wall, 40 % further out), in the time the drag's law gives for
 * that way. Lying there it is carried with the wall: the lumen opened
 * to 1.2 over a second, on the wall at every step (f R - size / 2 from
 * the axis, along the same radius), never falling (its speed 0);
 * collapsed to 0.4 in a step, on the wall in that step; at 1, at its rest
 * by the case's wall exactly.
 */
static void test_fall_onto_gas_wall(void **unused)
{
	struct colon *c = fall_colon("config/cases/polyps.case", 0);
	const double down[3] = { 0, 1, 0 };
	double factor[GAS_SEGMENTS], g[3], x[3], u[3], best = -1, got, l, t_s;
	double r, worst = 0, turned = 0;
	struct centreline_point q;
	const struct tool_polyp *p;
	struct bench b;
	long n = 0;
	int i;

	(void)unused;
	centreline_at_s(colon_centreline(c), FALL_S_M, &q);
	cut_free(&b, q.p, &i);
	p = &b.t.polyp[i];
	factors(factor, 0.6);
	assert_near(gas_factor_at(c, factor, FALL_S_M), 0.6, 1e-12);
	for (int k = 0; k < 3600; k++) {
		double th = 2 * M_PI * k / 3600;
		double rk = 0.6 * colon_lumen_radius(c, FALL_S_M, th);

		vec3_scale(x, q.u, rk * cos(th));
		vec3_axpy(x, x, rk * sin(th), q.v);
		best = fmax(best, vec3_dot(x, down));
	}
	vec3_scale(g, down, G_M_S2);
	do {
		tool_fall(&b.t, &par, c, g, factor, DT);
	} while (++n < 10000 && !p->lies);
	vec3_sub(u, p->at, q.p);
	l = vec3_normalize(u);
	got = vec3_dot(u, down) * (l + FALL_SIZE / 2);
	t_s = fall_time(l, G_M_S2, par.fall_drag_s);
	print_message("collapsed to 0.6: the lowest wall along gravity %.4f "
		      "mm, the rest's %.4f mm; %.1f mm in %ld steps, the law's "
		      "%.4f s\n", best * 1e3, got * 1e3, l * 1e3, n, t_s);
	assert_near(got, best, 1e-5);
	assert_true(fabs((double)n - t_s / DT) <= 1);
	r = (l + FALL_SIZE / 2) / 0.6;
	for (int k = 1; k <= 1000; k++) {
		double f = 0.6 + 0.6 * k / 1000;

		factors(factor, f);
		tool_fall(&b.t, &par, c, g, factor, DT);
		vec3_sub(x, p->at, q.p);
		vec3_normalize(x);
		worst = fmax(worst, fabs(off_gas_wall(p, &q, f, r)));
		turned = fmax(turned, 1 - vec3_dot(x, u));
		assert_true(p->fall_v == 0);
	}
	print_message("opened to 1.2 over 1 s: at most %.2g m off the wall, "
		      "%.2g off its radius\n", worst, turned);
	assert_true(worst < 1e-12 && turned < 1e-12);
	factors(factor, 0.4);
	tool_fall(&b.t, &par, c, g, factor, DT);
	assert_near(off_gas_wall(p, &q, 0.4, r), 0, 1e-12);
	factors(factor, 1);
	tool_fall(&b.t, &par, c, g, factor, DT);
	assert_vec_near(p->at, p->rest, 0);
	assert_near(off_gas_wall(p, &q, 1, r), 0, 1e-12);
	colon_destroy(c);
}

/*
 * Retrieval where it lies: fallen to the wall, the suction takes it with
 * the channel's exit at its body there, not at the place it was cut.
 */
static void test_retrieve_where_it_lies(void **unused)
{
	const double g[3] = { G_M_S2, 0, 0 };
	struct colon *c = fall_colon(NULL, 0.05);
	struct centreline_point q;
	double exit[3];
	struct bench b;
	int i;

	(void)unused;
	centreline_at_s(colon_centreline(c), FALL_S_M, &q);
	cut_free(&b, q.p, &i);
	fall_until_rest(&b, c, g, i, 10000);
	b.in.suction = true;
	/* the exit where it was cut (the lumen's axis): not in reach */
	vec3_copy(exit, q.p);
	vec3_axpy(b.sc.tip, exit, -par.channel_offset_m, b.t.pose.radial);
	b.events = 0;
	run(&b, 5, 0);
	assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_CUT);
	/* at its body where it lies: taken */
	vec3_copy(exit, b.t.polyp[i].at);
	vec3_axpy(b.sc.tip, exit, -par.channel_offset_m, b.t.pose.radial);
	run(&b, 5, 0);
	assert_true(b.events & TOOL_EVENT_RETRIEVE);
	assert_int_equal(b.t.polyp[i].state, TOOL_POLYP_RETRIEVED);
	colon_destroy(c);
}

/*
 * Published in turn: of two cut polyps, the one falling each step while
 * it falls; both at rest, one and the other; none cut, none.
 */
static void test_lying_in_turn(void **unused)
{
	const double g[3] = { 0, G_M_S2, 0 };
	struct colon *c = fall_colon(NULL, 0.05);
	struct centreline_point q;
	struct endosim_tool_state pub;
	struct bench b;
	int i, j, seen[2] = { 0, 0 };

	(void)unused;
	centreline_at_s(colon_centreline(c), FALL_S_M, &q);
	cut_free(&b, q.p, &i);
	tool_fall(&b.t, &par, c, g, NULL, DT);
	tool_publish(&b.t, 0, -1, &pub);
	assert_int_equal(pub.lying_polyp, i);
	assert_vec_near(pub.lying_at, b.t.polyp[i].at, 0);
	assert_vec_near(pub.polyp[i].at, b.t.polyp[i].at, 0);
	fall_until_rest(&b, c, g, i, 10000);
	/* a second one cut, falling: told every step till it rests */
	j = 1 - i;
	b.t.polyps = 2;
	b.t.polyp[j] = b.t.polyp[i];
	vec3_copy(b.t.polyp[j].at, q.p);
	b.t.polyp[j].rest_ok = false;
	b.t.polyp[j].moved = true;
	for (int k = 0; k < 20; k++) {
		tool_fall(&b.t, &par, c, g, NULL, DT);
		assert_int_equal(b.t.lying, j);
	}
	fall_until_rest(&b, c, g, j, 10000);
	for (int k = 0; k < 10; k++) {
		tool_fall(&b.t, &par, c, g, NULL, DT);
		seen[b.t.lying]++;
	}
	assert_int_equal(seen[0], 5);
	assert_int_equal(seen[1], 5);
	b.t.polyp[i].state = b.t.polyp[j].state = TOOL_POLYP_RETRIEVED;
	tool_fall(&b.t, &par, c, g, NULL, DT);
	assert_int_equal(b.t.lying, -1);
	colon_destroy(c);
}

/* Each fate: a 6 mm polyp bitten in place is partly resected. */
static void test_fates(void **unused)
{
	struct tool_polyp p = { .size_m = 0.006 };

	(void)unused;
	assert_int_equal(tool_polyp_fate(&p, &par), TOOL_FATE_IN_PLACE);
	p.bites = 1;
	assert_int_equal(tool_polyp_fate(&p, &par), TOOL_FATE_PARTLY);
	p.size_m = 0.003;
	assert_int_equal(tool_polyp_fate(&p, &par), TOOL_FATE_IN_PLACE);
	p.state = TOOL_POLYP_CUT;
	assert_int_equal(tool_polyp_fate(&p, &par), TOOL_FATE_CUT);
	p.state = TOOL_POLYP_RETRIEVED;
	assert_int_equal(tool_polyp_fate(&p, &par), TOOL_FATE_RETRIEVED);
}

/* -------------------------------------------------------- on the colon */

/* The polyps case into A, its colon (returned), its polyps placed on its
 * wall in T. */
static struct colon *polyps_placed(struct anatomy *a, struct tool *t)
{
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct colon *c;
	char err[256];

	assert_int_equal(anatomy_load(a, "config/cases/polyps.case", err,
				      sizeof(err)), 0);
	c = colon_create(a, &cp, err, sizeof(err));
	assert_non_null(c);
	tool_reset(t);
	assert_int_equal(tool_place_polyps(t, c), a->polyps);
	return c;
}

static void test_place_polyps_on_wall(void **unused)
{
	struct anatomy a;
	struct tool t;
	struct colon *c = polyps_placed(&a, &t);

	(void)unused;
	for (int i = 0; i < a.polyps; i++) {
		const struct tool_polyp *p = &t.polyp[i];
		struct centreline_point q;
		double x[3], r;

		centreline_at_s(colon_centreline(c), a.polyp[i].s_m, &q);
		r = colon_lumen_radius(c, a.polyp[i].s_m, a.polyp[i].angle_rad);
		vec3_sub(x, p->base, q.p);
		assert_near(vec3_norm(x), r, 1e-9);
		assert_near(vec3_dot(x, q.t), 0, 1e-9);
		vec3_normalize(x);
		assert_near(vec3_dot(x, p->normal), -1, 1e-9);
		assert_int_equal(p->paris, a.polyp[i].paris);
		assert_near(p->size_m, a.polyp[i].diameter_m, 0);
	}
	colon_destroy(c);
}

/* Polyp I of A on T, and the wall at a tool's tip halfway out to it, on
 * C's centreline as it is now, with the gas's FACTOR (NULL: none): on the
 * ring at its angle, the case's radius scaled by the factor at its
 * place, the normal that ring's. Its base, into BASE. */
static void on_the_ring(const struct anatomy *a, const struct tool *t,
			const struct colon *c, int i, const double *factor,
			double base[3])
{
	const struct tool_polyp *p = &t->polyp[i];
	double s = a->polyp[i].s_m, f = factor ? gas_factor_at(c, factor, s) : 1;
	double r = colon_lumen_radius(c, s, a->polyp[i].angle_rad);
	struct centreline_point q;
	struct tool_input in;
	double x[3], tip[3];

	centreline_at_s(colon_centreline(c), s, &q);
	vec3_sub(x, p->base, q.p);
	assert_near(vec3_norm(x), f * r, 1e-9);
	assert_near(vec3_dot(x, q.t), 0, 1e-9);
	assert_near(atan2(vec3_dot(x, q.v), vec3_dot(x, q.u)),
		    remainder(a->polyp[i].angle_rad, 2 * M_PI), 1e-9);
	vec3_normalize(x);
	assert_near(vec3_dot(x, p->normal), -1, 1e-9);
	vec3_axpy(tip, q.p, f * r / 2, x);
	tool_wall(c, s, tip, factor, &in);
	assert_true(in.wall);
	assert_near(vec3_dist(in.wall_point, p->base), 0, 1e-9);
	assert_near(vec3_dot(in.wall_normal, p->normal), 1, 1e-9);
	vec3_copy(base, p->base);
}

/* The polyps on the wall follow it, and the wall at the tool's tip is
 * the same: where the gas holds it (a factor each segment), without a
 * patient (NULL) the case's, and with the mobile segments bowed 3 cm
 * (the polyps in the sigmoid and the transverse colon carried along); a
 * polyp placed by hand (tool_add_polyp()) left where it is. */
static void test_polyps_and_wall_follow(void **unused)
{
	static const double factor[GAS_SEGMENTS] = { 0.6, 0.7, 0.8, 0.9, 1.0,
						     1.1, 1.2, 1.3, 1.4 };
	double hand[3] = { 0.01, 0.02, 0.03 }, up[3] = { 0, 0, 1 };
	double straight[ANATOMY_MAX_POLYPS][3], base[3];
	struct anatomy a;
	struct tool t;
	struct colon *c = polyps_placed(&a, &t);
	int scaled = 0, carried = 0;

	(void)unused;
	assert_int_equal(tool_add_polyp(&t, &a.polyp[0], hand, up), a.polyps);
	tool_follow_wall(&t, c, NULL);
	for (int i = 0; i < a.polyps; i++) {
		on_the_ring(&a, &t, c, i, NULL, straight[i]);
	}
	tool_follow_wall(&t, c, factor);
	for (int i = 0; i < a.polyps; i++) {
		on_the_ring(&a, &t, c, i, factor, base);
		scaled += vec3_dist(base, straight[i]) > 0.002;
	}
	for (int k = 0; k < centreline_spans(colon_centreline(c)); k++) {
		assert_int_equal(colon_bow(c, k, 0.03, false), 0);
	}
	tool_follow_wall(&t, c, NULL);
	for (int i = 0; i < a.polyps; i++) {
		on_the_ring(&a, &t, c, i, NULL, base);
		carried += vec3_dist(base, straight[i]) > 0.01;
	}
	assert_near(vec3_dist(t.polyp[a.polyps].base, hand), 0, 0);
	assert_true(scaled >= 3);  /* the factors moved most of them */
	assert_int_equal(carried, 2); /* the sigmoid's and the transverse's */
	colon_destroy(c);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_pose_at_channel_angle),
		cmocka_unit_test(test_loop_diameter_formula),
		cmocka_unit_test(test_capture_inside_not_outside),
		cmocka_unit_test(test_capture_needs_closing),
		cmocka_unit_test(test_flat_base_needs_lift),
		cmocka_unit_test(test_hot_cut_energy),
		cmocka_unit_test(test_cold_cut_small_only),
		cmocka_unit_test(test_pedal_on_mucosa_injures),
		cmocka_unit_test(test_hot_unlifted_base_injures),
		cmocka_unit_test(test_needle_lifts_base),
		cmocka_unit_test(test_forceps_bite),
		cmocka_unit_test(test_clip_on_wall),
		cmocka_unit_test(test_still_and_other_tools),
		cmocka_unit_test(test_bleed_uncoagulated_stalk),
		cmocka_unit_test(test_bleed_volume_and_stop),
		cmocka_unit_test(test_clip_stops_bleed),
		cmocka_unit_test(test_retrieve_small_only),
		cmocka_unit_test(test_fall_supine_and_left),
		cmocka_unit_test(test_fall_lowest_of_ring),
		cmocka_unit_test(test_fall_follows_turn),
		cmocka_unit_test(test_fall_onto_gas_wall),
		cmocka_unit_test(test_retrieve_where_it_lies),
		cmocka_unit_test(test_lying_in_turn),
		cmocka_unit_test(test_fates),
		cmocka_unit_test(test_place_polyps_on_wall),
		cmocka_unit_test(test_polyps_and_wall_follow),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
