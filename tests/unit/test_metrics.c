/*
 * test_metrics.c - the training metrics against synthetic record streams
 * whose answers follow from the geometry and the timing alone:
 *   - a tip moving at constant speed v reaches the cecum at s_c / v and is
 *     out again (s below the rectum's start s_x) (s_c - s_x) / v later;
 *     with a loop's slack the depth gets there first, the tip decides;
 *   - force plateaus above the threshold at known times: count, start,
 *     end, peak; a dip within the hysteresis does not split one, a spike
 *     shorter than min_episode_s is no episode;
 *   - a bow ramp: loop count, longest, largest;
 *   - the patient: a pain trace of known steps gives its time in pain,
 *     peak, episodes (a dip within the hysteresis does not split one, a
 *     drop below it does; a pulse shorter than min_episode_s is none)
 *     with the cause and place at each one's peak (or, with a stimulus
 *     recorded, of its provocation: the largest stimulus), the time in pain by
 *     cause (a fade counts for the cause before it); the Gloucester
 *     estimate's every step; the gas, turns, presses and perforations of
 *     known changes; a file of format 4 (no pain) still computes;
 *   - along the colon: a session file whose tip dwells in the sigmoid in
 *     pain and a loop and in the descending without: each segment's times
 *     and peaks to the nanosecond, the pain with the tip out in none;
 *   - the lumen on a straight colon: lost when dir points at the wall or
 *     presses head-on into it, kept down the lumen or 30 deg off it;
 *   - the mucosa seen on a straight colon (geometry in each test);
 *   - the polyps of the polyps case: seen when looked at from 3 cm, not
 *     when behind the camera or beyond view_distance_m;
 *   - metricstext_format() and metricstext_parse() round trip.
 * Times are to one record (1 ms at 1 kHz).
 *
 * Case files are read from $ENDOSIM_CASES (default config/cases) and
 * tests/cases: run from the source tree.
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

#include "model/anatomy.h"
#include "model/colon.h"
#include "conf/config.h"
#include "geom_assert.h"
#include "session/metrics.h"
#include "session/metricstext.h"
#include "session/sessioninputs.h"
#include "session/sessionmetrics.h"
#include "base/vec3.h"

#define RATE_HZ 1000
#define REC_TOL (1.0001 / RATE_HZ) /* one record */

/* Case NAME of DIR with rings of 96 vertices every STEP_M. */
static struct colon *build_step(const char *dir, const char *name,
				double step_m)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	const char *env = getenv("ENDOSIM_CASES");
	struct anatomy a;
	struct colon *c;
	char path[512], err[256];

	if (!strcmp(dir, "config/cases") && env && *env) {
		dir = env;
	}
	snprintf(path, sizeof(path), "%s/%s.case", dir, name);
	if (anatomy_load(&a, path, err, sizeof(err))) {
		print_error("%s\n", err);
		fail();
	}
	p.ring_vertices = 96;
	p.step_m = step_m;
	c = colon_create(&a, &p, err, sizeof(err));
	if (!c) {
		print_error("%s\n", err);
		fail();
	}
	return c;
}

static struct colon *build(const char *dir, const char *name)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;

	return build_step(dir, name, p.step_m);
}

/* Record K (at K / RATE_HZ s), inserted, at rest. */
static struct session_record rec(uint64_t k)
{
	return (struct session_record){
		.cycle = k,
		.stamp_ns = 5000000000ull + k * (ENDOSIM_NS_PER_S / RATE_HZ),
		.state = 1,
		.depth_m = 0.1f,
		.spans = 2,
		.dir = { 0, 0, 1 },
	};
}

static double t_of(uint64_t k)
{
	return (double)k / RATE_HZ;
}

/* The tip on CL's centreline at S, looking along the tangent rotated by
 * ANGLE about u (0: down the lumen). */
static void place(struct session_record *r, const struct centreline *cl,
		  double s, double angle)
{
	struct centreline_point q;
	double d[3];

	centreline_at_s(cl, s, &q);
	vec3_rotate(d, q.t, q.u, angle);
	for (int j = 0; j < 3; j++) {
		r->tip[j] = (float)q.p[j];
		r->dir[j] = (float)d[j];
		r->up[j] = (float)q.u[j];
	}
	r->tip_s_m = (float)s;
	r->depth_m = (float)s;
}

/* The metrics evaluating the view RATE_HZ times a second, with no dwell:
 * the view's geometry alone (the dwell: test_dwell_*, metrics_dwell). */
static struct metrics *metrics_at(const struct colon *c, double rate_hz)
{
	struct metrics_params p;
	struct metrics *m;

	metrics_params_default(&p);
	p.view_rate_hz = rate_hz;
	p.seen_dwell_s = p.polyp_dwell_s = 0;
	m = metrics_create(c, &p);
	assert_non_null(m);
	return m;
}

/* --------------------------------------------------------- the cecum */

static void test_cecum_insertion_withdrawal(void **state)
{
	struct colon *c = build("config/cases", "normal");
	const struct centreline *cl = colon_centreline(c);
	struct metrics *m = metrics_at(c, 20);
	struct metrics_result res;
	double v = 0.0937, sc = colon_cecum_s(c);
	double sx = anatomy_segment_start(colon_anatomy(c), ANATOMY_RECTUM);
	double deep = sc + 0.03, t_turn = deep / v;
	uint64_t k = 0, n_in = (uint64_t)(t_turn * RATE_HZ);

	(void)state;
	for (; k <= n_in; k++) {
		struct session_record r = rec(k);

		place(&r, cl, v * t_of(k), 0);
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_near(res.cecum_s, sc / v, REC_TOL);
	assert_near(res.insertion_s, sc / v, REC_TOL);
	/* not out yet: the withdrawal counts up to now */
	assert_near(res.withdrawal_s, t_of(n_in) - res.cecum_s, 1e-9);
	for (; v * (t_of(k) - t_turn) < deep; k++) {
		struct session_record r = rec(k);

		place(&r, cl, deep - v * (t_of(k) - t_turn), 0);
		metrics_record(m, &r);
	}
	for (uint64_t j = 0; j < RATE_HZ; j++, k++) { /* a second outside */
		struct session_record r = rec(k);

		r.depth_m = 0;
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_near(res.withdrawal_s, t_turn + (deep - sx) / v - sc / v,
		    2 * REC_TOL);
	assert_near(res.duration_s, t_of(k - 1), 1e-9);
	assert_int_equal(res.records, k);
	assert_near(res.max_tip_s_m, deep, 1e-4);
	metrics_destroy(m);
	colon_destroy(c);
}

static void test_cecum_not_reached(void **state)
{
	struct colon *c = build("config/cases", "normal");
	struct metrics *m = metrics_at(c, 20);
	struct metrics_result res;

	(void)state;
	for (uint64_t k = 0; k < 2000; k++) {
		struct session_record r = rec(k);

		place(&r, colon_centreline(c), 0.5, 0);
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_true(res.cecum_s < 0);
	assert_near(res.insertion_s, t_of(1999), 1e-9);
	assert_near(res.withdrawal_s, 0, 0);
	metrics_destroy(m);
	colon_destroy(c);
}

/*
 * A loop stores tube: the insertion depth runs 12 cm ahead of the tip's
 * place along the colon. The depth passes the cecum's start at
 * (s_c - 0.12) / v, the tip at s_c / v: the cecum is the tip's.
 */
static void test_cecum_is_the_tips_not_the_depth(void **state)
{
	struct colon *c = build("config/cases", "normal");
	const struct centreline *cl = colon_centreline(c);
	struct metrics *m = metrics_at(c, 20);
	struct metrics_result res;
	const double v = 0.0937, slack = 0.12, sc = colon_cecum_s(c);
	bool deep_before = false;

	(void)state;
	for (uint64_t k = 0; v * t_of(k) <= sc + 0.02; k++) {
		struct session_record r = rec(k);

		place(&r, cl, v * t_of(k), 0);
		r.depth_m = (float)(v * t_of(k) + slack);
		r.bow_m[0] = 0.04f;
		metrics_record(m, &r);
		if (r.tip_s_m < sc && r.depth_m >= sc) {
			deep_before = true;
			metrics_result(m, &res);
			assert_true(res.cecum_s < 0);
		}
	}
	assert_true(deep_before);
	metrics_result(m, &res);
	assert_near(res.cecum_s, sc / v, REC_TOL);
	assert_near(res.insertion_s, sc / v, REC_TOL);
	metrics_destroy(m);
	colon_destroy(c);
}

/* ---------------------------------------------------------- episodes */

/* 5 N, with plateaus of 20 N (2.0-3.5 s, a dip to 14 N at 2.5 s inside
 * the hysteresis) and 25 N (6.0-7.0 s, 30 N at 6.2-6.3 s), a 40 N spike
 * of 0.1 s at 8 s (shorter than min_episode_s), 10 s in all. */
static double force_at(double t)
{
	if (t >= 2.0 && t < 3.5) {
		return t >= 2.5 && t < 2.55 ? 14 : 20;
	}
	if (t >= 6.0 && t < 7.0) {
		return t >= 6.2 && t < 6.3 ? 30 : 25;
	}
	return t >= 8.0 && t < 8.1 ? 40 : 5;
}

static void test_force_episodes(void **state)
{
	struct metrics *m = metrics_at(NULL, 20);
	struct metrics_result res;
	double sum = 0;

	(void)state;
	for (uint64_t k = 0; k < 10 * RATE_HZ; k++) {
		struct session_record r = rec(k);

		/* the sign does not matter: |limited[0]| */
		r.limited[0] = (float)(k % 2 ? force_at(t_of(k)) :
					       -force_at(t_of(k)));
		sum += force_at(t_of(k));
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_int_equal(res.force_episodes, 2);
	assert_int_equal(res.n_force, 2);
	assert_near(res.force[0].start_s, 2.0, REC_TOL);
	assert_near(res.force[0].end_s, 3.5, REC_TOL);
	assert_near(res.force[0].peak, 20, 1e-6);
	assert_near(res.force[1].start_s, 6.0, REC_TOL);
	assert_near(res.force[1].end_s, 7.0, REC_TOL);
	assert_near(res.force[1].peak, 30, 1e-6);
	assert_near(res.force_episode_s, 2.5, 2 * REC_TOL);
	assert_near(res.peak_insertion_n, 40, 1e-6);
	/* 5 N x 10 s + 15 x 1.5 - 6 x 0.05 + 20 x 1 + 5 x 0.1 + 35 x 0.1 */
	assert_near(res.mean_insertion_n, sum / (10 * RATE_HZ), 1e-9);
	assert_near(res.mean_insertion_n, (50 + 22.5 - 0.3 + 20 + 0.5 + 3.5) /
				  10, 0.01);
	metrics_destroy(m);
}

static void test_force_episode_running(void **state)
{
	struct metrics *m = metrics_at(NULL, 20);
	struct metrics_result res;

	(void)state;
	for (uint64_t k = 0; k < 3 * RATE_HZ; k++) {
		struct session_record r = rec(k);

		r.limited[0] = t_of(k) >= 1.0 ? 18.0f : 0.0f;
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_int_equal(res.force_episodes, 1);
	assert_true(res.force[0].end_s < 0);
	assert_near(res.force_episode_s, t_of(3 * RATE_HZ - 1) - 1.0,
		    REC_TOL);
	metrics_destroy(m);
}

/* Span 0 ramps 0 -> 4 cm over 4 s and back over 4 s; span 1 holds 5 mm,
 * then 2 cm from 9 to 9.5 s. Threshold 1 cm, off below 9 mm. */
/* [session] loop_threshold_m 0: the model's threshold (the rod's tube
 * moves the sigmoid on any insertion, the paper's bow does not); a value
 * set overrides it. */
static void test_loop_threshold_by_model(void **state)
{
	struct config cfg;
	struct metrics_params p;

	(void)state;
	config_defaults(&cfg);
	cfg.haptics.model = HAPTICS_MODEL_ROD;
	sessioninputs_metrics_params(&cfg, &p);
	assert_true(p.loop_threshold_m == SESSION_LOOP_THRESHOLD_ROD_M);
	cfg.haptics.model = HAPTICS_MODEL_PAPER;
	sessioninputs_metrics_params(&cfg, &p);
	assert_true(p.loop_threshold_m == SESSION_LOOP_THRESHOLD_PAPER_M);
	cfg.session.loop_threshold_m = 0.02;
	sessioninputs_metrics_params(&cfg, &p);
	assert_true(p.loop_threshold_m == 0.02);
}

/* A session file's threshold, which the report and the replay's HUD
 * take: by the model its records say ran, whatever model its CONFIG
 * names (a tool's file may name none: the default, the rod); its CONFIG's
 * value overrides it; without records, its CONFIG's model. */
static void test_loop_threshold_of_file(void **state)
{
	struct session_record rec = { .model = ENDOSIM_MODEL_PAPER };
	struct session_file f = { .config = "[loop]\n" };
	struct metrics_params p;

	(void)state;
	sessioninputs_file_metrics_params(&f, &p);
	assert_true(p.loop_threshold_m == SESSION_LOOP_THRESHOLD_ROD_M);
	f.records = &rec;
	f.n_records = 1;
	sessioninputs_file_metrics_params(&f, &p);
	assert_true(p.loop_threshold_m == SESSION_LOOP_THRESHOLD_PAPER_M);
	rec.model = ENDOSIM_MODEL_ROD;
	f.config = "[haptics]\nmodel = paper\n";
	sessioninputs_file_metrics_params(&f, &p);
	assert_true(p.loop_threshold_m == SESSION_LOOP_THRESHOLD_ROD_M);
	f.config = "[session]\nloop_threshold_m = 0.05\n";
	sessioninputs_file_metrics_params(&f, &p);
	assert_true(p.loop_threshold_m == 0.05);
	assert_true(sessioninputs_loop_threshold_m(0, true) ==
		    SESSION_LOOP_THRESHOLD_ROD_M);
	assert_true(sessioninputs_loop_threshold_m(0, false) ==
		    SESSION_LOOP_THRESHOLD_PAPER_M);
	assert_true(sessioninputs_loop_threshold_m(0.04, false) == 0.04);
}

static void test_loop_episodes(void **state)
{
	struct metrics *m = metrics_at(NULL, 20);
	struct metrics_result res;

	(void)state;
	for (uint64_t k = 0; k < 10 * RATE_HZ; k++) {
		struct session_record r = rec(k);
		double t = t_of(k);

		r.bow_m[0] = (float)(t < 4 ? 0.01 * t :
				     t < 8 ? 0.04 - 0.01 * (t - 4) : 0);
		r.bow_m[1] = t >= 9 && t < 9.5 ? 0.02f : 0.005f;
		r.bow_m[2] = 0.5f; /* beyond spans: ignored */
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_int_equal(res.loop_episodes, 2);
	assert_near(res.loop[0].start_s, 1.0, 2 * REC_TOL);
	assert_near(res.loop[0].end_s, 8 - 0.9, 2 * REC_TOL);
	assert_near(res.loop[0].peak, 0.04, 1e-6);
	assert_near(res.loop[1].start_s, 9.0, REC_TOL);
	assert_near(res.loop[1].end_s, 9.5, REC_TOL);
	assert_near(res.loop[1].peak, 0.02, 1e-6);
	assert_near(res.longest_loop_s, 6.1, 3 * REC_TOL);
	assert_near(res.largest_loop_m, 0.04, 1e-6);
	metrics_destroy(m);
}

static void test_episodes_beyond_the_list(void **state)
{
	struct metrics *m = metrics_at(NULL, 20);
	struct metrics_result res;
	uint32_t n = METRICS_MAX_EPISODES + 6;

	(void)state;
	/* N pulses of 0.5 s above 15 N, 0.5 s apart */
	for (uint64_t k = 0; k < n * RATE_HZ; k++) {
		struct session_record r = rec(k);

		r.limited[0] = (k % RATE_HZ) < RATE_HZ / 2 ? 20.0f : 0.0f;
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_int_equal(res.force_episodes, n);
	assert_int_equal(res.n_force, METRICS_MAX_EPISODES);
	assert_near(res.force_episode_s, 0.5 * n, n * REC_TOL);
	metrics_destroy(m);
}

/* ------------------------------------------------------------ the pain */

/* A stretch of a pain trace: from FROM_S on, PAIN with CAUSE at PLACE,
 * the stimulus STIMULUS (0: none recorded). */
struct pain_step {
	double from_s;
	float pain;
	uint32_t cause;
	int32_t place;
	float stimulus;
};

/* Records at RATE_HZ for DURATION_S with the patient enabled (a heart
 * rate: it responds) and the pain of the N steps S (in time order). */
static void pain_trace(struct metrics_result *res, const struct pain_step *s,
		       size_t n, double duration_s, double rate_hz)
{
	struct metrics_params p;
	struct metrics *m;
	uint64_t records = (uint64_t)llround(duration_s * rate_hz);
	size_t j = 0;

	metrics_params_default(&p);
	m = metrics_create(NULL, &p);
	assert_non_null(m);
	for (uint64_t k = 0; k < records; k++) {
		struct session_record r = rec(0);
		double t = (double)k / rate_hz;

		r.stamp_ns += (uint64_t)llround(t * ENDOSIM_NS_PER_S);
		while (j + 1 < n && t >= s[j + 1].from_s - 1e-9) {
			j++;
		}
		r.patient = 1;
		r.heart_rate_bpm = 70;
		r.hand_site = r.burst_segment = r.torn_segment = -1;
		r.pain = t >= s[j].from_s - 1e-9 ? s[j].pain : 0;
		r.pain_cause = s[j].cause;
		r.pain_place = s[j].place;
		r.pain_stimulus = s[j].stimulus;
		metrics_record(m, &r);
	}
	metrics_result(m, res);
	metrics_destroy(m);
}

#define LOOP ENDOSIM_PAIN_LOOPING
#define STRAIGHT ENDOSIM_PAIN_STRAIGHTENING
#define GAS ENDOSIM_PAIN_INSUFFLATION
#define TIP ENDOSIM_PAIN_TIP
#define NONE ENDOSIM_PAIN_NONE

/*
 * 12 s at 1 kHz, the level 4 (off below 3.6), episodes of 0.2 s or more:
 *   0-2 s    1, looping in the sigmoid                     not in pain
 *   2-5 s    5 looping (sigmoid), 8 straightening at 2.5-3.5 s (the
 *            transverse), 5 looping, a dip to 3.8 at 4-4.05 s (not in pain
 *            but within the hysteresis), 5 insufflation (splenic flexure):
 *            one episode, 2-5 s, peak 8, straightening in the transverse
 *   5-6 s    2, no cause (fading)
 *   6-6.1 s  9, the tip in the cecum: in pain, too short for an episode
 *   6.1-7 s  1, no cause
 *   7-8 s    4.0 exactly, no cause: an episode (at the level counts), its
 *            cause the last one seen: the tip's, in the cecum
 *   8-9 s    3, no cause
 *   9-10 s   6 looping (sigmoid) with a drop to 3 at 9.5-9.6 s: two
 *            episodes, 9-9.5 and 9.6-10
 *   10-12 s  0
 * In pain 2.95 + 0.1 + 1 + 0.9 = 4.95 s: looping 0.5 + 0.5 + 0.9 = 1.9,
 * straightening 1, insufflation 0.95, the tip 0.1 + 1 (the fade after it).
 * No stimulus is recorded: each cause and place is the one at the peak.
 */
static const struct pain_step trace[] = {
	{ 0, 1, LOOP, 2, 0 },     { 2, 5, LOOP, 2, 0 },
	{ 2.5, 8, STRAIGHT, 5, 0 }, { 3.5, 5, LOOP, 2, 0 },
	{ 4, 3.8f, LOOP, 2, 0 },  { 4.05, 5, GAS, 4, 0 },
	{ 5, 2, NONE, -1, 0 },    { 6, 9, TIP, 8, 0 },
	{ 6.1, 1, NONE, -1, 0 },  { 7, 4, NONE, -1, 0 },
	{ 8, 3, NONE, -1, 0 },    { 9, 6, LOOP, 2, 0 },
	{ 9.5, 3, LOOP, 2, 0 },   { 9.6, 6, LOOP, 2, 0 },
	{ 10, 0, NONE, -1, 0 },
};

static void assert_pain_episode(const struct metrics_episode *e,
				double start_s, double end_s, double peak,
				uint32_t cause, int32_t place)
{
	assert_near(e->start_s, start_s, REC_TOL);
	assert_near(e->end_s, end_s, REC_TOL);
	assert_near(e->peak, peak, 1e-6);
	assert_int_equal(e->cause, cause);
	assert_int_equal(e->place, place);
}

static void test_pain_trace(void **state)
{
	struct metrics_result res;

	(void)state;
	pain_trace(&res, trace, sizeof(trace) / sizeof(trace[0]), 12,
		   RATE_HZ);
	assert_near(res.duration_s, 12 - 1.0 / RATE_HZ, 1e-9);
	assert_near(res.peak_pain, 9, 1e-6);
	assert_int_equal(res.pain_episodes, 4);
	assert_int_equal(res.n_pain, 4);
	assert_pain_episode(&res.pain[0], 2, 5, 8, STRAIGHT, 5);
	assert_pain_episode(&res.pain[1], 7, 8, 4, TIP, 8);
	assert_pain_episode(&res.pain[2], 9, 9.5, 6, LOOP, 2);
	assert_pain_episode(&res.pain[3], 9.6, 10, 6, LOOP, 2);
	assert_near(res.pain_share * res.duration_s, 4.95, 4 * REC_TOL);
	assert_near(res.pain_cause_s[LOOP], 1.9, 3 * REC_TOL);
	assert_near(res.pain_cause_s[STRAIGHT], 1.0, 2 * REC_TOL);
	assert_near(res.pain_cause_s[GAS], 0.95, 2 * REC_TOL);
	assert_near(res.pain_cause_s[TIP], 1.1, 2 * REC_TOL);
	assert_near(res.pain_cause_s[NONE], 0, 1e-12);
	/* in pain 41 % of the time: "severe, frequent and prolonged" */
	assert_int_equal(res.gloucester, 5);
}

/*
 * An episode's cause and place are its provocation's: a loop pushed in
 * (stimulus 8, looping in the sigmoid) and reduced at once, the level
 * crossing 4 and peaking while the tube is withdrawn (straightening, a
 * stimulus of 3 and then 1): looping in the sigmoid, not straightening;
 * then the tip in the cecum, alone; then a loop in the transverse colon
 * (stimulus 5) that brings the pain on, the tip pushed harder into the
 * wall while it lasts (stimulus 9): what brought it on, the loop.
 */
static void test_pain_provocation(void **state)
{
	static const struct pain_step s[] = {
		{ 0, 0, LOOP, 2, 2 },
		{ 1.0, 2, LOOP, 2, 8 },
		{ 1.5, 5, STRAIGHT, 2, 3 },
		{ 2.0, 7, STRAIGHT, 2, 1 },
		{ 3.0, 0, NONE, -1, 0 },
		{ 4.0, 5, TIP, 8, 6 },
		{ 4.5, 0, NONE, -1, 0 },
		{ 6.0, 2, LOOP, 5, 5 },
		{ 6.5, 4.5, LOOP, 5, 5 },
		{ 7.0, 6, TIP, 6, 9 },
		{ 7.5, 0, NONE, -1, 0 },
	};
	struct metrics_result res;

	(void)state;
	pain_trace(&res, s, sizeof(s) / sizeof(s[0]), 8, RATE_HZ);
	assert_int_equal(res.n_pain, 3);
	assert_pain_episode(&res.pain[0], 1.5, 3, 7, LOOP, 2);
	assert_pain_episode(&res.pain[1], 4, 4.5, 5, TIP, 8);
	assert_pain_episode(&res.pain[2], 6.5, 7.5, 6, LOOP, 5);
	/* the time by cause is each record's own */
	assert_near(res.pain_cause_s[STRAIGHT], 1.5, 2 * REC_TOL);
}

/* PULSES pulses of PAIN for HOLD_S each, 5 s apart, in 100 s: the
 * Gloucester estimate. */
static uint32_t gloucester_of(int pulses, float pain, double hold_s)
{
	struct pain_step s[2 * 8 + 1];
	struct metrics_result res;
	size_t n = 0;

	s[n++] = (struct pain_step){ 0, 0, NONE, -1, 0 };
	for (int i = 0; i < pulses; i++) {
		double t0 = 1 + i * (hold_s + 5);

		s[n++] = (struct pain_step){ t0, pain, LOOP, 2, 0 };
		s[n++] = (struct pain_step){ t0 + hold_s, 0, NONE, -1,
					     0 };
	}
	pain_trace(&res, s, n, 100, 100);
	assert_int_equal(res.pain_episodes, pulses);
	return res.gloucester;
}

/* The mapping (metrics.c): none 1, 1-2 mild episodes 2, more 3 (or one
 * severe), two severe or 10 % of the time 4, 25 % 5; the patient
 * disabled (or not responding: a format-4 file) 0. */
static void test_gloucester(void **state)
{
	struct metrics_params p;
	struct metrics *m;
	struct metrics_result res;
	struct session_record r = rec(0);

	(void)state;
	assert_int_equal(gloucester_of(0, 0, 1), 1);
	assert_int_equal(gloucester_of(1, 5, 1), 2);
	assert_int_equal(gloucester_of(2, 5, 1), 2);
	assert_int_equal(gloucester_of(3, 5, 1), 3);
	assert_int_equal(gloucester_of(1, 8, 1), 3);
	assert_int_equal(gloucester_of(2, 8, 1), 4);
	assert_int_equal(gloucester_of(1, 5, 11), 4);   /* 11 % */
	assert_int_equal(gloucester_of(2, 5, 13), 5);   /* 26 % */
	metrics_params_default(&p);
	m = metrics_create(NULL, &p);
	metrics_record(m, &r);
	metrics_result(m, &res);
	assert_int_equal(res.gloucester, 0);
	assert_false(metrics_has_patient(&res)); /* shown as none */
	r.patient = 1;  /* enabled, but no vitals: format 4 */
	metrics_record(m, &r);
	metrics_result(m, &res);
	assert_int_equal(res.gloucester, 0);
	metrics_destroy(m);
}

/* [session] pain_level: a level of 6 sees only the stronger pain. */
static void test_pain_level(void **state)
{
	struct metrics_params p;
	struct metrics *m;
	struct metrics_result res;

	(void)state;
	metrics_params_default(&p);
	assert_true(p.pain_level == 4);
	p.pain_level = 6;
	m = metrics_create(NULL, &p);
	for (uint64_t k = 0; k < 10 * RATE_HZ; k++) {
		struct session_record r = rec(k);

		r.patient = 1;
		r.pain = t_of(k) < 5 ? 5.0f : 7.0f;
		r.pain_cause = TIP;
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_int_equal(res.pain_episodes, 1);
	assert_near(res.pain[0].start_s, 5, REC_TOL);
	assert_near(res.pain_share * res.duration_s, 5 - 1.0 / RATE_HZ,
		    REC_TOL);
	metrics_destroy(m);
}

/* The patient's other measures, from records at 10 Hz over 10 s: the gas
 * in rises 0.5 L, drops to 0 (a case loaded) and rises 0.2 L; the
 * pressure peaks at 4000 Pa; turned twice; pressed by the hand twice
 * (once held over 1 s); a burst and a tear; records with the patient
 * disabled count nothing. */
static void test_patient_counts(void **state)
{
	struct metrics_params p;
	struct metrics *m;
	struct metrics_result res;

	(void)state;
	metrics_params_default(&p);
	m = metrics_create(NULL, &p);
	for (uint64_t k = 0; k < 100; k++) {
		struct session_record r = rec(k * (RATE_HZ / 10));
		double t = k / 10.0;

		r.patient = t < 9;  /* then disabled: a zeroed record's */
		r.gas_in_m3 = (float)(t < 1 ? 0.5e-3 * t : t < 2 ? 0.5e-3 :
				      t < 3 ? 0 : t < 4 ? 0.2e-3 * (t - 3)
						    : 0.2e-3);
		r.gas_pressure_pa = t >= 5 && t < 5.1 ? 4000 : 1000;
		r.patient_position = t < 2 ? 0 : t < 3 ? 1 : 2;
		r.hand_site = (t >= 1 && t < 2) || (t >= 4 && t < 4.5) ? 3 :
			      -1;
		r.burst_segment = t >= 5 ? 2 : -1;
		r.torn_segment = t >= 6 ? 3 : -1;
		if (!r.patient) {
			r.hand_site = r.burst_segment = r.torn_segment = 0;
			r.patient_position = 0;
			r.gas_in_m3 = 1;
		}
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_near(res.gas_used_l, 0.5 + 0.2, 1e-5);
	assert_near(res.peak_gas_pressure_pa, 4000, 1e-3);
	assert_int_equal(res.position_changes, 2);
	assert_int_equal(res.hand_uses, 2);
	assert_int_equal(res.perforations, 2);
	assert_true(res.peak_pain == 0);
	assert_int_equal(res.pain_episodes, 0);
	metrics_destroy(m);
}

/*
 * A session file of format 4 (488-byte records: the patient's body, no
 * pain): the pain reads as none (0, not assessed), the body's measures
 * count; an END frame of format 4 with its discomfort index reads, the
 * index ignored.
 */
static void test_format_4_file(void **state)
{
	static const char head[] = "format=4\nrecord_size=488\n";
	static const char end[] = "duration_s=2\ndiscomfort=12.5\n"
				  "force_episodes=1\n";
	char path[] = "/tmp/test_metrics_XXXXXX";
	struct metrics_params p;
	struct metrics_result res;
	struct session_file f;
	char err[256];
	int fd = mkstemp(path);

	(void)state;
	assert_true(fd >= 0);
	assert_int_equal(session_file_write_magic(fd), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_HEADER,
						  head, strlen(head)), 0);
	for (uint64_t k = 0; k < 20; k++) {
		struct session_record r = rec(k * (RATE_HZ / 10));

		r.patient = 1;
		r.hand_site = -1;
		r.burst_segment = k >= 10 ? 1 : -1;
		r.gas_in_m3 = (float)(k * 1e-4);
		r.gas_pressure_pa = 2000;
		/* format 5's: not in a format-4 record */
		r.pain = 8;
		r.pain_cause = TIP;
		r.heart_rate_bpm = 90;
		r.torn_segment = 2;
		assert_int_equal(session_file_write_frame(
					 fd, SESSION_FRAME_RECORD, &r,
					 SESSION_RECORD_SIZE_4), 0);
	}
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_END, end,
						  strlen(end)), 0);
	close(fd);
	assert_int_equal(session_file_read(path, &f), 0);
	unlink(path);
	metrics_params_default(&p);
	assert_int_equal(sessionmetrics_compute(&f, &p, &res, err,
						sizeof(err)), 0);
	assert_true(res.peak_pain == 0 && res.pain_share == 0);
	assert_int_equal(res.pain_episodes, 0);
	assert_int_equal(res.gloucester, 0);
	assert_true(metrics_has_patient(&res)); /* the body's measures */
	assert_int_equal(res.perforations, 1);
	assert_near(res.gas_used_l, 19 * 0.1, 1e-4);
	assert_near(res.peak_gas_pressure_pa, 2000, 1e-3);
	assert_near(res.duration_s, 1.9, 1e-9);
	assert_int_equal(metricstext_parse(f.end, &res), 0);
	assert_near(res.duration_s, 2, 1e-12);
	assert_int_equal(res.force_episodes, 1);
	assert_int_equal(res.gloucester, 0);
	session_file_close(&f);
}

/* ------------------------------------------------- along the colon */

/* The text of the file PATH into BUF (SIZE bytes), NUL-terminated. */
static void read_text(const char *path, char *buf, size_t size)
{
	FILE *f = fopen(path, "r");
	size_t n;

	assert_non_null(f);
	n = fread(buf, 1, size - 1, f);
	buf[n] = '\0';
	fclose(f);
}

/*
 * The straight case's segments (tests/cases/straight.case: the anal canal
 * to 0.04 m, the rectum to 0.16, the sigmoid to 0.53, the descending to
 * 0.68), records at 100 Hz for 9 s, the patient enabled:
 *   0-1 s  the tip at 0.10 (rectum), no pain, 2 N
 *   1-5 s  at 0.30 (sigmoid), pain 6 (looping, there), 8 N with one
 *          record of 16 N at 3 s; the sigmoid bowed 5 cm at 2-4 s
 *   5-8 s  at 0.60 (descending), no pain, 5 N, the sigmoid bowed just
 *          below the loop threshold (the paper model's: the records')
 *   8-9 s  out (depth 0), pain 5, looping in the sigmoid: in pain, but
 *          in no segment (they are the tip's, not the pain's place)
 * Each record's state holds until the next: exact to the nanosecond.
 */
static void write_along_session(const char *path)
{
	static const char head[] = "format=8\nrecord_size=572\nid=9\n"
				   "case=straight\nstep_m=0.002\n"
				   "ring_vertices=48\nsegment_m=0.04\n";
	static char case_text[1 << 16];
	int fd = open(path, O_WRONLY | O_TRUNC);

	assert_true(fd >= 0);
	read_text("tests/cases/straight.case", case_text, sizeof(case_text));
	assert_int_equal(session_file_write_magic(fd), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_HEADER,
						  head, strlen(head)), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_CASE,
						  case_text,
						  strlen(case_text)), 0);
	for (uint64_t k = 0; k < 900; k++) {
		struct session_record r = rec(k * (RATE_HZ / 100));
		double t = k / 100.0;
		bool sigmoid = t >= 1 && t < 5;

		r.tip_s_m = t < 1 ? 0.10f : sigmoid ? 0.30f : t < 8 ? 0.60f : 0;
		r.depth_m = t < 8 ? r.tip_s_m : 0;
		r.limited[0] = t < 1 ? -2 : !sigmoid ? -5 : k == 300 ? -16 : -8;
		r.bow_m[0] = t >= 2 && t < 4 ? 0.05f :
			     t >= 5 && t < 8 ?
			     (float)(0.95 * SESSION_LOOP_THRESHOLD_PAPER_M) : 0;
		r.patient = 1;
		r.heart_rate_bpm = 70;
		r.hand_site = r.burst_segment = r.torn_segment = -1;
		r.pain = sigmoid ? 6 : t >= 8 ? 5 : 0;
		r.pain_cause = r.pain > 0 ? LOOP : NONE;
		r.pain_place = r.pain > 0 ? ANATOMY_SIGMOID : -1;
		assert_int_equal(session_file_write_frame(
					 fd, SESSION_FRAME_RECORD, &r,
					 sizeof(r)), 0);
	}
	close(fd);
}

static void assert_segment(const struct metrics_segment *g, double time_s,
			   double pain_s, double loop_s, double peak_pain,
			   double peak_force_n)
{
	assert_near(g->time_s, time_s, 1e-9);
	assert_near(g->pain_s, pain_s, 1e-9);
	assert_near(g->loop_s, loop_s, 1e-9);
	assert_near(g->peak_pain, peak_pain, 1e-6);
	assert_near(g->peak_force_n, peak_force_n, 1e-6);
}

/* The session file above, as the report recomputes it: each segment's
 * time, time in pain and looped, peaks; the pain with the tip out in
 * none; none without a case. */
static void test_along_the_colon(void **state)
{
	char path[] = "/tmp/test_metrics_XXXXXX";
	struct metrics_along al;
	struct metrics_result res;
	struct metrics_params p;
	struct session_file f;
	char err[256];
	int fd = mkstemp(path);

	(void)state;
	assert_true(fd >= 0);
	close(fd);
	write_along_session(path);
	assert_int_equal(session_file_read(path, &f), 0);
	unlink(path);
	assert_int_equal(sessionmetrics_map(&f, NULL, &al), 0);
	assert_true(al.segments);
	assert_segment(&al.seg[ANATOMY_ANAL_CANAL], 0, 0, 0, 0, 0);
	assert_segment(&al.seg[ANATOMY_RECTUM], 1, 0, 0, 0, 2);
	assert_segment(&al.seg[ANATOMY_SIGMOID], 4, 4, 2, 6, 16);
	assert_segment(&al.seg[ANATOMY_DESCENDING], 3, 0, 0, 0, 5);
	for (int i = ANATOMY_SPLENIC_FLEXURE; i < ANATOMY_SEGMENTS; i++) {
		assert_segment(&al.seg[i], 0, 0, 0, 0, 0);
	}
	/* in pain 4 s with the tip in, 0.99 s out (the last record's none) */
	sessioninputs_file_metrics_params(&f, &p);
	assert_true(p.loop_threshold_m == SESSION_LOOP_THRESHOLD_PAPER_M);
	assert_int_equal(sessionmetrics_compute(&f, &p, &res, err,
						sizeof(err)), 0);
	assert_near(res.pain_share * res.duration_s, 4.99, 1e-9);
	f.case_text = NULL; /* no case: no segments */
	assert_int_equal(sessionmetrics_map(&f, NULL, &al), 0);
	assert_false(al.segments);
	assert_segment(&al.seg[ANATOMY_SIGMOID], 0, 0, 0, 0, 0);
	session_file_close(&f);
}

/* ------------------------------------------------------------- lumen */

static void test_lumen_lost_straight(void **state)
{
	struct colon *c = build("tests/cases", "straight");
	const struct centreline *cl = colon_centreline(c);
	struct metrics *m = metrics_at(c, 20);
	struct metrics_result res;
	uint64_t k = 0;

	(void)state;
	/* 1 s down the lumen, 1 s 30 deg off it: kept */
	for (; k < 2 * RATE_HZ; k++) {
		struct session_record r = rec(k);

		place(&r, cl, 0.3 + 0.02 * t_of(k), k < RATE_HZ ? 0 : M_PI / 6);
		metrics_record(m, &r);
	}
	/* 0.5 s at the wall (90 deg) and 0.25 s at 75 deg: lost */
	for (; k < 2.75 * RATE_HZ; k++) {
		struct session_record r = rec(k);

		place(&r, cl, 0.3 + 0.02 * t_of(k),
		      k < 2.5 * RATE_HZ ? M_PI / 2 : 75 * M_PI / 180);
		metrics_record(m, &r);
	}
	/* 0.25 s down the lumen but pressing head-on into a wall: lost */
	for (; k < 3 * RATE_HZ; k++) {
		struct session_record r = rec(k);

		place(&r, cl, 0.3 + 0.02 * t_of(k), 0);
		r.contact = 1;
		for (int j = 0; j < 3; j++) {
			r.normal[j] = -r.dir[j];
		}
		metrics_record(m, &r);
	}
	/* 0.5 s outside, looking anywhere: not counted; then 0.5 s kept */
	for (; k < 4 * RATE_HZ; k++) {
		struct session_record r = rec(k);

		place(&r, cl, 0.01, M_PI / 2);
		if (k < 3.5 * RATE_HZ) {
			r.depth_m = 0;
		} else {
			place(&r, cl, 0.05, 0);
		}
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_near(res.lumen_lost_s, 1.0, 2 * REC_TOL);
	/* lost once (2 to 3 s), in view the rest of the 3.5 s inserted */
	assert_int_equal(res.lost_views, 1);
	assert_near(res.clear_view, 1 - 1.0 / 3.5, 3 * REC_TOL);
	metrics_destroy(m);
	colon_destroy(c);
}

/* ------------------------------------------------------------ mucosa */

/*
 * A camera on the axis looking forward sees a wall point at radius R and
 * axial distance x ahead when x >= R / tan(70 deg) = 0.36 R (the cone) and
 * x^2 + R^2 <= (6 cm)^2; the backs of the haustral folds (slope < 0.7)
 * face it once x < 1.4 R. Moved from the anal verge to 1 cm before the
 * cecum's pole in 2 mm steps it sees everything but the first 0.36 R of
 * the anal canal (R = 12.5 mm: 3.5 cm^2 of ~2400 cm^2): > 99 %.
 */
static void test_mucosa_forward_sweep(void **state)
{
	struct colon *c = build("tests/cases", "straight");
	const struct centreline *cl = colon_centreline(c);
	struct metrics *m = metrics_at(c, 2 * RATE_HZ);
	struct metrics_result res;
	double len = centreline_length(cl);
	uint64_t k = 0;

	(void)state;
	for (double s = 0.001; s <= len - 0.01; s += 0.002, k++) {
		struct session_record r = rec(k);

		place(&r, cl, s, 0);
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	assert_true(res.mucosa_seen > 0.99);
	assert_true(res.mucosa_seen <= 1.0 + 1e-9);
	assert_near(metrics_mucosa_seen_between(m, 0.1, len), 1.0, 1e-3);
	/* the map: every cell beyond 0.1 m seen in full */
	{
		static struct metrics_map map;

		metrics_map(m, &map);
		assert_near(map.length_m, len, 0.01);
		for (int i = 0; i < METRICS_MAP_S; i++) {
			for (int a = 0; a < METRICS_MAP_A; a++) {
				if ((i + 0.0) / METRICS_MAP_S * len > 0.1) {
					assert_true(map.seen[i][a] > 0.99);
				}
			}
		}
	}
	/* each segment beyond the anal canal: all of it; the canal's first
	   0.36 R is behind the first pose's cone */
	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		printf("# %s %.4f\n", anatomy_segment_name(i),
		       res.mucosa_segment[i]);
		assert_true(res.mucosa_segment[i] > (i ? 0.999 : 0.5));
	}
	metrics_destroy(m);
	colon_destroy(c);
}

/*
 * One pose at s = 0.3 m (the sigmoid, R = 22.5 mm nominal, 16.6 mm at the
 * folds' and taeniae's deepest) looking back: nothing ahead of it is seen;
 * behind it the band 0.36 R <= x <= sqrt(0.06^2 - R^2), 0.79 to 0.86 of the
 * 6 cm from 0.24 to 0.3 m. Looking forward instead, the mirror image.
 */
static void test_mucosa_backward_sees_nothing_ahead(void **state)
{
	struct colon *c = build("tests/cases", "straight");
	const struct centreline *cl = colon_centreline(c);
	struct metrics *m = metrics_at(c, 20);
	double band;

	(void)state;
	for (uint64_t k = 0; k < 10; k++) {
		struct session_record r = rec(k);

		place(&r, cl, 0.3, M_PI);
		metrics_record(m, &r);
	}
	assert_near(metrics_mucosa_seen_between(m, 0.3 + 0.001, 2), 0, 0);
	band = metrics_mucosa_seen_between(m, 0.24, 0.3);
	assert_true(band > 0.74 && band < 0.90);
	metrics_destroy(m);

	m = metrics_at(c, 20);
	for (uint64_t k = 0; k < 10; k++) {
		struct session_record r = rec(k);

		place(&r, cl, 0.3, 0);
		metrics_record(m, &r);
	}
	assert_near(metrics_mucosa_seen_between(m, 0, 0.3 - 0.001), 0, 0);
	band = metrics_mucosa_seen_between(m, 0.3, 0.36);
	assert_true(band > 0.74 && band < 0.90);
	metrics_destroy(m);
	colon_destroy(c);
}

/*
 * The sigmoid bowed 4 cm: a camera on the bowed centreline (where the
 * daemon publishes it) sees what it sees unbowed; one left on the
 * undeformed centreline is 4 cm off the bowed axis, outside the lumen
 * (R = 22.5 mm), facing the wall's outside, and sees almost nothing.
 */
static double seen_at(struct colon *c, double bow, bool on_bowed)
{
	struct metrics *m = metrics_at(c, 20);
	double share;

	colon_bow(c, 0, on_bowed ? bow : 0, false);
	for (uint64_t k = 0; k < 4; k++) {
		struct session_record r = rec(k);

		place(&r, colon_centreline(c), 0.35, 0);
		r.bow_m[0] = (float)bow;
		metrics_record(m, &r);
	}
	colon_bow(c, 0, 0, false);
	share = metrics_mucosa_seen_between(m, 0.35, 0.41);
	metrics_destroy(m);
	return share;
}

static void test_mucosa_follows_the_bow(void **state)
{
	struct colon *c = build("tests/cases", "straight");
	double straight = seen_at(c, 0, true);

	(void)state;
	assert_true(straight > 0.74);
	assert_near(seen_at(c, 0.04, true), straight, 0.05);
	assert_true(seen_at(c, 0.04, false) < 0.2);
	colon_destroy(c);
}

/* ------------------------------------------------------------ polyps */

/* Where the polyps case's polyp K sits on the undeformed wall. */
/* ------------------------------------------------------------ occlusion */

/*
 * deep-fold.case: a straight colon whose folds are half the radius deep
 * (R = 22.5 mm in the sigmoid: a ridge at 11.3 mm from the axis), 2.5 mm
 * thin, on a mesh of 0.5 mm steps. The
 * folds of the sector around 90 deg stand at s = 0.03 k; a line of sight
 * from the axis to a wall point at 90 deg stays in that angle's plane and
 * meets only those. The oracle below decides each vertex by the case's
 * analytic wall, independently of the depth buffer.
 */
#define FOLD_S 0.30
#define DEG (M_PI / 180)

/* Whether the straight line from E to P stays in the lumen (inside
 * colon_lumen_radius(), the wall the mesh samples, with 0.5 mm for the
 * mesh's chords) up to 1 mm short of P. On a colon without bends a
 * point's place along it is its distance along the axis. */
static bool line_of_sight(const struct colon *c, const double e[3],
			  const double p[3])
{
	const struct centreline *cl = colon_centreline(c);
	const struct centreline_point *o = centreline_sample(cl, 0);
	double x[3], len;

	vec3_sub(x, p, e);
	len = vec3_norm(x);
	for (double d = 0.00025; d < len - 0.001; d += 0.00025) {
		struct centreline_point f;
		double q[3], r[3], s, a, rho;

		vec3_axpy(q, e, d / len, x);
		vec3_sub(r, q, o->p);
		s = vec3_dot(r, o->t);
		centreline_at_s(cl, s, &f);
		vec3_sub(r, q, f.p);
		a = atan2(vec3_dot(r, f.v), vec3_dot(r, f.u));
		rho = hypot(vec3_dot(r, f.u), vec3_dot(r, f.v));
		if (rho > colon_lumen_radius(c, s, a) + 0.0005) {
			return false;
		}
	}
	return true;
}

/*
 * The oracle: of the wall between S0 and S1 and at angles A0 to A1 (each
 * vertex a third of its triangles' area, as metrics.c counts), the share
 * a camera at E looking along DIR has in view: within view_distance_m
 * and half the field of view, the wall facing it and, when CLEAR, nothing
 * of the wall on the line of sight.
 */
static double oracle_seen(const struct colon *c, const double e[3],
			  const double dir[3], double s0, double s1,
			  double a0, double a1, bool clear)
{
	const struct mesh *me = colon_mesh(c);
	struct metrics_params p;
	double *area = calloc(me->vertices, sizeof(*area));
	double step = centreline_step(colon_centreline(c)), all = 0, seen = 0;

	assert_non_null(area);
	metrics_params_default(&p);
	for (uint32_t k = 0; k < me->triangles; k++) {
		double v[3][3], x[3];

		for (int j = 0; j < 3; j++) {
			vec3_set(v[j], me->pos[me->tri[k][j]][0],
				 me->pos[me->tri[k][j]][1],
				 me->pos[me->tri[k][j]][2]);
		}
		vec3_sub(v[1], v[1], v[0]);
		vec3_sub(v[2], v[2], v[0]);
		vec3_cross(x, v[1], v[2]);
		for (int j = 0; j < 3; j++) {
			area[me->tri[k][j]] += vec3_norm(x) / 6;
		}
	}
	for (uint32_t i = 0; i < me->vertices; i++) {
		double s = me->sample[i] * step, pt[3], n[3], x[3], d;
		double a = atan2(me->off[i][2], me->off[i][1]);

		a = a < 0 ? a + 2 * M_PI : a;
		if (s < s0 || s > s1 || a < a0 || a > a1) {
			continue;
		}
		all += area[i];
		vec3_set(pt, me->pos[i][0], me->pos[i][1], me->pos[i][2]);
		vec3_set(n, me->nrm[i][0], me->nrm[i][1], me->nrm[i][2]);
		vec3_sub(x, pt, e);
		d = vec3_norm(x);
		if (d <= p.view_distance_m &&
		    vec3_dot(x, dir) >= cos(p.fov_rad / 2) * d &&
		    vec3_dot(n, x) < 0 && (!clear || line_of_sight(c, e, pt))) {
			seen += area[i];
		}
	}
	free(area);
	return seen / all;
}

/* One pose on the axis at S looking forward (ANGLE 0) or back (pi): the
 * metrics' share of the wall around FOLD_S seen, against the oracle's. */
static void one_pose(struct colon *c, double s, double angle)
{
	const struct centreline *cl = colon_centreline(c);
	struct metrics *m = metrics_at(c, 20);
	struct session_record r = rec(0);
	double e[3], dir[3], got, want, open;

	place(&r, cl, s, angle);
	metrics_record(m, &r);
	vec3_set(e, r.tip[0], r.tip[1], r.tip[2]);
	vec3_set(dir, r.dir[0], r.dir[1], r.dir[2]);
	got = metrics_mucosa_seen_between(m, FOLD_S - 0.01, FOLD_S + 0.04);
	want = oracle_seen(c, e, dir, FOLD_S - 0.01, FOLD_S + 0.04, 0,
			   2 * M_PI, true);
	open = oracle_seen(c, e, dir, FOLD_S - 0.01, FOLD_S + 0.04, 0,
			   2 * M_PI, false);
	printf("# camera at %.2f m looking %s: seen %.4f, oracle %.4f "
	       "(%.4f in view without the folds' shadow)\n", s,
	       angle ? "back" : "ahead", got, want, open);
	/* the depth test sees 0.010 and 0.011 more than the oracle at these
	 * poses (the buffer's pixels); a buffer of half the resolution, or a
	 * depth slack 20 times its own, errs by 0.019 and 0.020 */
	assert_true(fabs(got - want) < 0.013);
	assert_true(open - want > 0.1); /* the folds hide a good part */
	metrics_destroy(m);
}

static void test_occlusion_one_pose(void **state)
{
	struct colon *c = build_step("tests/cases", "deep-fold", 0.0005);

	(void)state;
	one_pose(c, FOLD_S - 0.04, 0);
	one_pose(c, FOLD_S + 0.06, M_PI);
	colon_destroy(c);
}

/*
 * The fold's back (the 6 mm beyond its ridge, +-15 deg around its deepest
 * angle): a camera sweeping past it looking ahead sees little of it, the
 * ridge in front of it; sweeping back over it from beyond, looking back,
 * it sees it all.
 */
static void test_occlusion_fold_back(void **state)
{
	struct colon *c = build_step("tests/cases", "deep-fold", 0.0005);
	const struct centreline *cl = colon_centreline(c);
	struct metrics *ahead = metrics_at(c, RATE_HZ);
	struct metrics *back = metrics_at(c, RATE_HZ);
	double got_ahead, got_back, a0 = 75 * DEG, a1 = 105 * DEG;
	uint64_t k = 0;

	(void)state;
	for (double s = FOLD_S - 0.1; s <= FOLD_S + 0.1; s += 0.001, k++) {
		struct session_record r = rec(k), b = rec(k);

		place(&r, cl, s, 0);
		metrics_record(ahead, &r);
		place(&b, cl, 2 * FOLD_S + 0.01 - s, M_PI);
		metrics_record(back, &b);
	}
	got_ahead = metrics_mucosa_seen_in(ahead, FOLD_S, FOLD_S + 0.006,
					   a0, a1);
	got_back = metrics_mucosa_seen_in(back, FOLD_S, FOLD_S + 0.006, a0,
					  a1);
	printf("# the fold's back: seen %.4f sweeping ahead, %.4f looking "
	       "back\n", got_ahead, got_back);
	assert_true(got_ahead < 0.5);
	assert_true(got_back > 0.99);
	metrics_destroy(ahead);
	metrics_destroy(back);
	colon_destroy(c);
}

/* The polyp in the valley beyond the fold: hidden by the ridge from 3 cm
 * before it (in range and within the field of view), found looking back
 * from 2 cm beyond it. */
static void test_occlusion_polyp(void **state)
{
	struct colon *c = build_step("tests/cases", "deep-fold", 0.0005);
	const struct centreline *cl = colon_centreline(c);
	struct metrics_result res;
	struct metrics *m;

	(void)state;
	for (int look = 0; look < 2; look++) {
		struct session_record r = rec(0);

		m = metrics_at(c, 20);
		place(&r, cl, look ? 0.33 : 0.278, look ? M_PI : 0);
		metrics_record(m, &r);
		metrics_result(m, &res);
		assert_int_equal(res.polyps_total, 1);
		assert_int_equal(res.polyps_seen, look ? 1 : 0);
		metrics_destroy(m);
	}
	colon_destroy(c);
}

static void polyp_at(const struct colon *c, int k, double out[3])
{
	const struct anatomy_polyp *p = &colon_anatomy(c)->polyp[k];
	struct centreline_point q;
	double r = colon_lumen_radius(c, p->s_m, p->angle_rad);

	centreline_at_s(colon_centreline(c), p->s_m, &q);
	vec3_copy(out, q.p);
	vec3_axpy(out, out, r * cos(p->angle_rad), q.u);
	vec3_axpy(out, out, r * sin(p->angle_rad), q.v);
}

static void test_polyps_seen(void **state)
{
	struct colon *c = build("config/cases", "polyps");
	const struct centreline *cl = colon_centreline(c);
	struct metrics *m = metrics_at(c, 20);
	struct metrics_result res;
	uint64_t k = 0;

	(void)state;
	assert_int_equal(colon_anatomy(c)->polyps, 5);
	for (int i = 0; i < 5; i++) {
		double s = colon_anatomy(c)->polyp[i].s_m, at[3], d[3];
		struct session_record r = rec(k);

		/* 0, 2, 4: looked at from 3 cm; 1: behind the camera; 3:
		 * looked at from 10 cm, beyond view_distance_m */
		place(&r, cl, s - (i == 3 ? 0.10 : 0.03), i == 1 ? M_PI : 0);
		polyp_at(c, i, at);
		if (i != 1) {
			for (int j = 0; j < 3; j++) {
				d[j] = at[j] - r.tip[j];
			}
			vec3_normalize(d);
			for (int j = 0; j < 3; j++) {
				r.dir[j] = (float)d[j];
			}
		}
		for (int j = 0; j < 100; j++, k++) {
			r.stamp_ns = rec(k).stamp_ns;
			metrics_record(m, &r);
		}
		metrics_result(m, &res);
		assert_int_equal(res.polyps_seen_mask >> i & 1,
				 i == 0 || i == 2 || i == 4);
	}
	assert_int_equal(res.polyps_seen, 3);
	assert_int_equal(res.polyps_total, 5);
	assert_int_equal(res.polyps_seen_mask, 0x15);
	metrics_destroy(m);
	colon_destroy(c);
}

/* ------------------------------------------------------------- dwell */

/* The default metrics (dwell included) with polyp I of the polyps case
 * looked at from 3 cm for HOLD_S, then the camera turned away (1 s). */
static struct metrics_result looked_at(struct colon *c, int i, double hold_s)
{
	const struct centreline *cl = colon_centreline(c);
	struct metrics_params p;
	struct metrics *m;
	struct metrics_result res;
	double s = colon_anatomy(c)->polyp[i].s_m, at[3], d[3];
	struct session_record r = rec(0);
	uint64_t k = 0;

	metrics_params_default(&p);
	m = metrics_create(c, &p);
	place(&r, cl, s - 0.03, 0);
	polyp_at(c, i, at);
	vec3_sub(d, at, (double[3]){ r.tip[0], r.tip[1], r.tip[2] });
	vec3_normalize(d);
	for (int j = 0; j < 3; j++) {
		r.dir[j] = (float)d[j];
	}
	for (; t_of(k) < hold_s; k++) {
		r.stamp_ns = rec(k).stamp_ns;
		metrics_record(m, &r);
	}
	place(&r, cl, s - 0.03, M_PI); /* looking back the way it came */
	for (uint64_t j = 0; j < RATE_HZ; j++, k++) {
		r.stamp_ns = rec(k).stamp_ns;
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	metrics_destroy(m);
	return res;
}

/* A polyp in view for 2.4 s is not found, for 2.6 s it is. */
static void test_dwell_polyp(void **state)
{
	struct colon *c = build("config/cases", "polyps");
	struct metrics_result a = looked_at(c, 0, 2.4), b = looked_at(c, 0, 2.6);

	(void)state;
	assert_int_equal(a.polyps_seen, 0);
	assert_int_equal(b.polyps_seen, 1);
	assert_int_equal(b.polyps_seen_mask, 1);
	colon_destroy(c);
}

/* The default metrics' mucosa seen with the camera down a straight colon's
 * lumen at 0.35 m for HOLD_S. */
static double held_for(struct colon *c, double hold_s)
{
	struct metrics_params p;
	struct metrics *m;
	struct metrics_result res;

	metrics_params_default(&p);
	m = metrics_create(c, &p);
	for (uint64_t k = 0; t_of(k) < hold_s; k++) {
		struct session_record r = rec(k);

		place(&r, colon_centreline(c), 0.35, 0);
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	metrics_destroy(m);
	return res.mucosa_seen;
}

/* The map of a camera held down the lumen at 0.35 m: seen only ahead of
 * it within the view's 6 cm, all around. */
static void test_map_held(void **state)
{
	struct colon *c = build("tests/cases", "straight");
	static struct metrics_map map;
	struct metrics_params p;
	struct metrics *m;
	int ahead = 0;

	(void)state;
	metrics_params_default(&p);
	m = metrics_create(c, &p);
	for (uint64_t k = 0; t_of(k) < 1; k++) {
		struct session_record r = rec(k);

		place(&r, colon_centreline(c), 0.35, 0);
		metrics_record(m, &r);
	}
	metrics_map(m, &map);
	for (int i = 0; i < METRICS_MAP_S; i++) {
		double s0 = (double)i / METRICS_MAP_S * map.length_m;
		double s1 = (double)(i + 1) / METRICS_MAP_S * map.length_m;

		for (int a = 0; a < METRICS_MAP_A; a++) {
			if (s1 < 0.35 || s0 > 0.35 + 0.06) {
				assert_true(map.seen[i][a] == 0);
			} else if (s0 > 0.37 && s1 < 0.40) {
				assert_true(map.seen[i][a] > 0.5);
				ahead++;
			}
		}
	}
	assert_true(ahead >= 2 * METRICS_MAP_A);
	metrics_destroy(m);
	colon_destroy(c);
}

/* Mucosa in view for 0.4 s is not seen; for 0.6 s it is. */
static void test_dwell_mucosa(void **state)
{
	struct colon *c = build("tests/cases", "straight");
	double a = held_for(c, 0.4), b = held_for(c, 0.6);

	(void)state;
	printf("# mucosa seen: %.4f after 0.4 s in view, %.4f after 0.6 s\n",
	       a, b);
	assert_true(a == 0);
	assert_true(b > 0.01);
	colon_destroy(c);
}

/* ------------------------------------------------------- drops, text */

static void test_drops(void **state)
{
	struct metrics *m = metrics_at(NULL, 20);
	struct session_event ev = { .kind = SESSION_EVENT_DROPS, .value = 12 };
	struct metrics_result res;

	(void)state;
	metrics_event(m, &ev, "");
	ev.value = 40;
	metrics_event(m, &ev, "");
	ev.kind = SESSION_EVENT_NOTE;
	ev.value = 99;
	metrics_event(m, &ev, "a note");
	metrics_result(m, &res);
	assert_int_equal(res.drops, 40);
	metrics_destroy(m);
}

static void assert_rel(double a, double b)
{
	assert_near(a, b, 1e-8 * fmax(1, fabs(b)));
}

static void test_format_parse(void **state)
{
	struct metrics_result in = {
		.duration_s = 1234.5678, .records = 1234568, .drops = 3,
		.cecum_s = 456.25, .insertion_s = 456.25,
		.withdrawal_s = 401.001, .max_tip_s_m = 1.4812,
		.peak_insertion_n = 23.75, .mean_insertion_n = 4.321,
		.force_episodes = 70, .force_episode_s = 12.5,
		.loop_episodes = 2, .longest_loop_s = 6.1,
		.largest_loop_m = 0.0412, .pain_share = 0.123456789,
		.peak_pain = 8.5, .pain_episodes = 3, .gloucester = 4,
		.pain_cause_s = { 0, 1.5, 2.25, 3.125, 4.0625 },
		.gas_used_l = 3.75, .peak_gas_pressure_pa = 5432.1,
		.position_changes = 2, .hand_uses = 5, .perforations = 1,
		.lumen_lost_s = 77.7, .mucosa_seen = 0.873456789,
		.polyps_seen = 3, .polyps_total = 5, .polyps_seen_mask = 0x15,
		.n_force = METRICS_MAX_EPISODES, .n_loop = 2, .n_pain = 2,
		.pain = { { 1.5, 3.25, 7.5, TIP, 8 },
			  { 10, -1, 4.5, LOOP, -1 } },
	}, out;
	static char buf[16384];
	int n;

	(void)state;
	for (uint32_t i = 0; i < in.n_force; i++) {
		in.force[i] = (struct metrics_episode){ 10.0 * i + 0.125,
							10.0 * i + 1.5,
							15.5 + i / 3.0, 0,
							-1 };
	}
	in.loop[0] = (struct metrics_episode){ 1.001, 7.1, 0.04, 0, -1 };
	in.loop[1] = (struct metrics_episode){ 9, -1, 0.02, 0, -1 };
	n = metricstext_format(&in, buf, sizeof(buf));
	assert_true(n > 0 && (size_t)n == strlen(buf));
	assert_non_null(strstr(buf, "withdrawal_s=401.001\n"));
	assert_non_null(strstr(buf, "loop_episode.1=9,-1,0.02\n"));
	assert_int_equal(metricstext_parse(buf, &out), 0);
	assert_rel(out.duration_s, in.duration_s);
	assert_int_equal(out.records, in.records);
	assert_int_equal(out.drops, in.drops);
	assert_rel(out.withdrawal_s, in.withdrawal_s);
	assert_rel(out.pain_share, in.pain_share);
	assert_rel(out.peak_pain, in.peak_pain);
	assert_int_equal(out.pain_episodes, 3);
	assert_int_equal(out.gloucester, 4);
	for (int c = 1; c < ENDOSIM_PAIN_CAUSES; c++) {
		assert_rel(out.pain_cause_s[c], in.pain_cause_s[c]);
	}
	assert_rel(out.gas_used_l, in.gas_used_l);
	assert_rel(out.peak_gas_pressure_pa, in.peak_gas_pressure_pa);
	assert_int_equal(out.position_changes, 2);
	assert_int_equal(out.hand_uses, 5);
	assert_int_equal(out.perforations, 1);
	assert_non_null(strstr(buf, "pain_episode.0=1.5,3.25,7.5,4,8\n"));
	assert_int_equal(out.n_pain, 2);
	assert_rel(out.pain[0].peak, 7.5);
	assert_int_equal(out.pain[0].cause, TIP);
	assert_int_equal(out.pain[0].place, 8);
	assert_rel(out.pain[1].end_s, -1);
	assert_int_equal(out.pain[1].cause, LOOP);
	assert_int_equal(out.pain[1].place, -1);
	assert_rel(out.mucosa_seen, in.mucosa_seen);
	assert_int_equal(out.force_episodes, 70);
	assert_int_equal(out.polyps_seen_mask, 0x15);
	assert_int_equal(out.n_force, in.n_force);
	assert_int_equal(out.n_loop, 2);
	for (uint32_t i = 0; i < in.n_force; i++) {
		assert_rel(out.force[i].start_s, in.force[i].start_s);
		assert_rel(out.force[i].end_s, in.force[i].end_s);
		assert_rel(out.force[i].peak, in.force[i].peak);
	}
	assert_rel(out.loop[1].end_s, -1);
	/* too small a buffer, malformed text, a later version's key */
	assert_int_equal(metricstext_format(&in, buf, 100), -ENOSPC);
	assert_int_equal(metricstext_parse("records=12\nnonsense\n", &out),
			 -EINVAL);
	assert_int_equal(metricstext_parse("records=twelve\n", &out), -EINVAL);
	assert_int_equal(metricstext_parse("force_episode.64=1,2,3\n", &out),
			 -EINVAL);
	assert_int_equal(metricstext_parse("force_episode.0=1,2\n", &out),
			 -EINVAL);
	/* a pain episode without its cause and place, or a cause unknown */
	assert_int_equal(metricstext_parse("pain_episode.0=1,2,3\n", &out),
			 -EINVAL);
	assert_int_equal(metricstext_parse("pain_episode.0=1,2,3,9,1\n",
					   &out), -EINVAL);
	assert_int_equal(metricstext_parse("records=12\nfuture_key=x\n", &out),
			 0);
	assert_int_equal(out.records, 12);
	assert_true(out.cecum_s < 0);
}

/* ------------------------------------------ the scope's handling */

/* Records K0..K1 (exclusive) with the depth and the tip's place given by
 * DEPTH(t) and TIP(t) (t since K0), no colon. */
static void drive(struct metrics *m, uint64_t k0, uint64_t k1, double d0,
		  double dv, double s0, double sv)
{
	for (uint64_t k = k0; k < k1; k++) {
		struct session_record r = rec(k);
		double t = t_of(k - k0);

		r.depth_m = (float)(d0 + dv * t);
		r.tip_s_m = (float)(s0 + sv * t);
		metrics_record(m, &r);
	}
}

/* A straight push: the tip advances with the shaft, 1:1. */
static void test_handling_straight(void **state)
{
	struct metrics *m = metrics_at(NULL, 20);
	struct metrics_result res;

	(void)state;
	drive(m, 0, 10 * RATE_HZ, 0.05, 0.02, 0.05, 0.02);
	metrics_result(m, &res);
	assert_near(res.shaft_in_m, 0.2, 0.0021);
	assert_near(res.tip_in_m, 0.2, 0.0021);
	assert_near(res.chase_efficiency, 1.0, 1e-4);
	assert_near(res.shaft_idle_m, 0, 1e-9);
	assert_near(res.retraction_m, 0, 1e-9);
	metrics_destroy(m);
}

/* A loop: 5 s straight (0.1 m), then 5 s the shaft goes on 0.1 m while
 * the tip stays: half the push idle, the chase efficiency 0.5. */
static void test_handling_loop(void **state)
{
	struct metrics *m = metrics_at(NULL, 20);
	struct metrics_result res;

	(void)state;
	drive(m, 0, 5 * RATE_HZ, 0.05, 0.02, 0.05, 0.02);
	drive(m, 5 * RATE_HZ, 10 * RATE_HZ, 0.15, 0.02, 0.15, 0);
	metrics_result(m, &res);
	printf("# loop: shaft %.4f m, tip %.4f m, efficiency %.3f, idle "
	       "%.4f m\n", res.shaft_in_m, res.tip_in_m, res.chase_efficiency,
	       res.shaft_idle_m);
	assert_near(res.shaft_in_m, 0.2, 0.0041);
	assert_near(res.tip_in_m, 0.1, 0.0021);
	assert_near(res.chase_efficiency, 0.5, 0.02);
	assert_near(res.shaft_idle_m, 0.1, 0.0021);
	metrics_destroy(m);
}

/*
 * A withdrawal at constant speed from beyond the cecum (the normal case):
 * the shaft and the tip retreat together until the tip leaves the rectum
 * (1:1), and nothing of the way in counts as withdrawn.
 */
static void test_handling_withdrawal(void **state)
{
	struct colon *c = build("config/cases", "normal");
	const struct centreline *cl = colon_centreline(c);
	struct metrics *m = metrics_at(c, 20);
	struct metrics_result res;
	double v = 0.05, sc = colon_cecum_s(c);
	double sx = anatomy_segment_start(colon_anatomy(c), ANATOMY_RECTUM);
	double deep = sc + 0.03, t_turn = deep / v;
	uint64_t k = 0;

	(void)state;
	for (; t_of(k) <= t_turn; k++) {
		struct session_record r = rec(k);

		place(&r, cl, v * t_of(k), 0);
		metrics_record(m, &r);
	}
	for (; v * (t_of(k) - t_turn) < deep; k++) {
		struct session_record r = rec(k);

		place(&r, cl, deep - v * (t_of(k) - t_turn), 0);
		metrics_record(m, &r);
	}
	metrics_result(m, &res);
	printf("# withdrawal from %.3f m to the rectum's %.3f m: shaft %.4f "
	       "m, tip %.4f m, efficiency %.3f; on the way in %.4f m\n", deep,
	       sx, res.retraction_m, res.tip_retraction_m,
	       res.retraction_efficiency, res.shaft_in_m);
	assert_near(res.retraction_m, deep - sx, 2 * v * METRICS_SHAPE_STEP_S);
	assert_near(res.tip_retraction_m, res.retraction_m, 1e-4);
	assert_near(res.retraction_efficiency, 1.0, 1e-3);
	assert_near(res.shaft_in_m, sc, v * METRICS_SHAPE_STEP_S + 1e-3);
	assert_near(res.chase_efficiency, 1.0, 1e-3);
	metrics_destroy(m);
	colon_destroy(c);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cecum_insertion_withdrawal),
		cmocka_unit_test(test_cecum_not_reached),
		cmocka_unit_test(test_cecum_is_the_tips_not_the_depth),
		cmocka_unit_test(test_force_episodes),
		cmocka_unit_test(test_force_episode_running),
		cmocka_unit_test(test_loop_episodes),
		cmocka_unit_test(test_loop_threshold_by_model),
		cmocka_unit_test(test_loop_threshold_of_file),
		cmocka_unit_test(test_episodes_beyond_the_list),
		cmocka_unit_test(test_pain_trace),
		cmocka_unit_test(test_pain_provocation),
		cmocka_unit_test(test_gloucester),
		cmocka_unit_test(test_pain_level),
		cmocka_unit_test(test_patient_counts),
		cmocka_unit_test(test_format_4_file),
		cmocka_unit_test(test_along_the_colon),
		cmocka_unit_test(test_lumen_lost_straight),
		cmocka_unit_test(test_mucosa_forward_sweep),
		cmocka_unit_test(test_mucosa_backward_sees_nothing_ahead),
		cmocka_unit_test(test_mucosa_follows_the_bow),
		cmocka_unit_test(test_polyps_seen),
		cmocka_unit_test(test_occlusion_one_pose),
		cmocka_unit_test(test_occlusion_fold_back),
		cmocka_unit_test(test_occlusion_polyp),
		cmocka_unit_test(test_drops),
		cmocka_unit_test(test_format_parse),
		cmocka_unit_test(test_dwell_polyp),
		cmocka_unit_test(test_dwell_mucosa),
		cmocka_unit_test(test_map_held),
		cmocka_unit_test(test_handling_straight),
		cmocka_unit_test(test_handling_loop),
		cmocka_unit_test(test_handling_withdrawal),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
