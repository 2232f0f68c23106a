/*
 * test_course.c - the force loop's behaviour on a course, in lockstep on
 * simulated time (tests/tools/offline.h: loop_step(), the loop's own
 * cycle on the simulated rig), so that every answer is the same on any
 * machine, however busy: the paper model's demo course on the normal case
 * (config/scenarios/demo-paper.scn, which is scenario_gen --model paper's
 * course at 3 cm/s, tests/system/70-session.sh checks that it still is)
 * with [haptics] model = paper, for the haptics,
 * the safety filter's clamp, the hand's top speed, a session's metrics,
 * and that a run repeats bit for bit; and a scenario's valves and
 * commands for the assistant carried out by the loop's cycle. (The rod
 * model's course, with the patient: test_rodcourse.c.)
 *
 * The course, from scenario_gen (all times on the scenario's clock, which
 * is the loop's: one period a cycle):
 *  - the tip meets the wall in the rectum and sigmoid; it reaches the
 *    splenic flexure (0.68 m) at 22.4 s, is pushed on straight to 0.78 m
 *    until 27.5 s (the tip held: the sigmoid bows into a loop), withdrawn
 *    to 0.62 m by 30.5 s (the loop reduced);
 *  - the cecum's segment starts at s = 1.46 m, the sum of the case's
 *    segments before it; the insertion target passes it at 59.32 s and
 *    rests at 1.48 m until 61.5 s, so the tip gets there in [59.2, 61.5] s;
 *  - the sigmoid's mesentery (600 N/m) holding a loop of 2 cm needs 12 N
 *    from the hand: with the episode threshold at 10 N the push at the
 *    flexure is one episode of excessive force peaking above 12 N, inside
 *    the loop's window; nowhere else does the course push on a held tip.
 *
 * Run from the top of the source tree (tests/run.sh does), or with
 * ENDOSIM_TOP naming it.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <math.h>
#include <stdbool.h>

#include "conf/cases.h"
#include "session/metrics.h"
#include "offline.h"
#include "proto/session_file.h"

#define PERIOD_S (OFFLINE_PERIOD_NS * ENDOSIM_S_PER_NS)
#define MESENTERY_N_PER_M 600.0 /* normal.case: the sigmoid's */

/* The normal case's colon as CFG sets it up (the caller owns it). */
static struct colon *normal_colon(struct config *cfg)
{
	char err[512];
	struct colon *c;

	snprintf(cfg->colon.file, sizeof(cfg->colon.file),
		 "config/cases/normal.case");
	c = cases_load(cfg, NULL, err, sizeof(err));
	if (!c) {
		fail_msg("%s", err);
	}
	return c;
}

/* The loop on the normal case playing the file SCENARIO, the paper's
 * model rendering. */
static struct offline *course(struct config *cfg, const char *scenario,
			      struct colon **colon)
{
	char err[512];
	struct offline *o;

	cfg->haptics.model = HAPTICS_MODEL_PAPER;
	*colon = normal_colon(cfg);
	o = offline_create(cfg, *colon, scenario, err, sizeof(err));
	if (!o) {
		fail_msg("%s", err);
	}
	return o;
}

/* What the demo's first 32 s show of the haptics (as 16-haptics did). */
struct haptics_seen {
	long contact;
	double f_static_max, friction_deep_max, curvature_max, tension_max;
	double bow_max, loop_min, bow_end;
	double sum_err_insertion, sum_err_wheels;
	uint32_t faults;
};

static double norm3(const double v[3])
{
	return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static void see_haptics(struct haptics_seen *s, const struct endosim_state *st)
{
	const struct endosim_haptics_state *h = &st->haptics;
	double ins = h->trans_contact_n + h->trans_friction_n + h->trans_loop_n +
		     h->damping[0];

	s->contact += h->contact != 0;
	s->f_static_max = fmax(s->f_static_max, norm3(h->f_static));
	if (st->scope.depth_m > 0.4) {
		s->friction_deep_max = fmax(s->friction_deep_max,
					    fabs(h->trans_friction_n));
	}
	s->curvature_max = fmax(s->curvature_max, h->curvature_rad);
	for (int w = 0; w < 2; w++) {
		double sum = h->wheel_contact_nm[w] + h->wheel_tension_nm[w] +
			     h->wheel_elastic_nm[w] + h->damping[2 + w];

		s->tension_max = fmax(s->tension_max,
				      fabs(h->wheel_tension_nm[w]));
		s->sum_err_wheels = fmax(s->sum_err_wheels,
					 fabs(st->axis[2 + w].command - sum));
	}
	s->bow_max = fmax(s->bow_max, st->scope.bow_m[0]);
	s->loop_min = fmin(s->loop_min, h->trans_loop_n);
	s->bow_end = st->scope.bow_m[0];
	s->sum_err_insertion = fmax(s->sum_err_insertion,
				    fabs(st->axis[0].command - ins));
	s->faults |= st->fault_bits;
}

/*
 * The demo's course, played once (group setup) for the tests that look
 * at it whole or at its start: its first 32 s' haptics, its records'
 * metrics, its first 26 s' hash (one of the two runs compared).
 */
#define HAPTICS_CYCLES 32000
#define REPEAT_CYCLES 26000
static struct demo {
	struct haptics_seen seen; /* its first HAPTICS_CYCLES */
	struct metrics_result r;  /* every record's */
	float *scen;              /* each record's scenario time */
	long cycles;
	uint64_t hash;            /* of its first REPEAT_CYCLES */
} demo;

/* The whole course recorded as the daemon records a session (70's). */
static int play_demo(void **unused)
{
	struct config cfg;
	struct colon *colon;
	struct offline *o;
	struct metrics_params p;
	struct metrics *m;
	struct session_record rec;

	(void)unused;
	config_defaults(&cfg);
	o = course(&cfg, "config/scenarios/demo-paper.scn", &colon);
	demo.cycles = lround(offline_length_s(o) / PERIOD_S);
	demo.hash = OFFLINE_HASH_START;
	metrics_params_default(&p);
	p.force_threshold_n = 10;
	m = metrics_create(colon, &p);
	demo.scen = calloc((size_t)demo.cycles, sizeof(*demo.scen));
	if (!m || !demo.scen) {
		return -1;
	}
	for (long k = 0; k < demo.cycles; k++) {
		const struct endosim_state *st = offline_step(o);

		if (k < HAPTICS_CYCLES) {
			see_haptics(&demo.seen, st);
		}
		if (k < REPEAT_CYCLES) {
			demo.hash = offline_hash(demo.hash, st);
		}
		session_record_from_state(st, &rec);
		metrics_record(m, &rec);
		demo.scen[k] = (float)st->scenario_time_s;
	}
	metrics_result(m, &demo.r);
	metrics_destroy(m);
	offline_destroy(o);
	return 0;
}

static int forget_demo(void **unused)
{
	(void)unused;
	free(demo.scen);
	return 0;
}

static void test_demo_haptics(void **unused)
{
	const struct haptics_seen s = demo.seen;

	(void)unused;
	printf("# 32 s: contact %ld cycles, F_static max %.2f N, friction "
	       "deep %.2f N, curvature %.2f rad, tension %.4f N m, bow %.4f m "
	       "(%.4f m at 32 s), loop force min %.2f N\n", s.contact,
	       s.f_static_max, s.friction_deep_max, s.curvature_max,
	       s.tension_max, s.bow_max, s.bow_end, s.loop_min);
	assert_true(s.contact > 10);             /* the tip touched the wall */
	assert_true(s.f_static_max > 1);         /* and the wall pushed back */
	assert_true(s.friction_deep_max > 0.5);  /* friction deep in */
	assert_true(s.curvature_max > 2);        /* the tube turned > 2 rad */
	assert_true(s.tension_max > 0.002);      /* wire tension on a wheel */
	assert_true(s.bow_max > 0.01);           /* a loop formed (> 1 cm) */
	assert_true(s.loop_min < -1);            /* it carried insertion force */
	assert_true(s.bow_end < 0.005);          /* withdrawing reduced it */
	assert_true(s.sum_err_insertion < 1e-9); /* the parts add up */
	assert_true(s.sum_err_wheels < 1e-9);
	assert_int_equal(s.faults, 0);
}

/*
 * The safety filter's clamp, driven past: the insertion limit set below
 * what the course commands at the flexure. What reaches the rig never
 * exceeds the limit, and sits on it while the command is beyond it.
 */
static void test_clamp(void **unused)
{
	const double limit_n = 6;
	struct config cfg;
	struct colon *colon;
	struct offline *o;
	double cmd_max = 0, lim_max = 0;
	long beyond = 0, held = 0;

	(void)unused;
	config_defaults(&cfg);
	cfg.limits.max[ENDOSIM_AXIS_INSERTION] = limit_n;
	cfg.limits.saturation_s = 60; /* the hold is what is looked at here */
	o = course(&cfg, "config/scenarios/demo-paper.scn", &colon);
	for (long k = 0; k < 32000; k++) {
		const struct endosim_state *st = offline_step(o);
		const struct endosim_axis_state *ax =
			&st->axis[ENDOSIM_AXIS_INSERTION];

		cmd_max = fmax(cmd_max, fabs(ax->command));
		lim_max = fmax(lim_max, fabs(ax->limited));
		if (fabs(ax->command) > limit_n * 1.05) {
			beyond++;
			held += fabs(fabs(ax->limited) - limit_n) < 1e-9;
		}
		assert_int_equal(st->fault_bits, 0);
	}
	offline_destroy(o);
	printf("# clamp at %.1f N: largest command %.2f N, largest written "
	       "%.6f N; %ld cycles beyond the limit, %ld of them at it\n",
	       limit_n, cmd_max, lim_max, beyond, held);
	assert_true(cmd_max > limit_n * 1.5);  /* driven well past it */
	assert_true(lim_max <= limit_n);       /* never beyond */
	assert_true(beyond > 100);
	assert_true(held > beyond * 9 / 10);   /* on it, bar the slew's steps */
}

/* A scenario file in /tmp: the hand holds the carriage at 0 until END_S. */
static void idle_scenario(char *buf, size_t size, double end_s)
{
	FILE *f;
	int fd;

	snprintf(buf, size, "/tmp/test_course.XXXXXX");
	fd = mkstemp(buf);
	assert_true(fd >= 0);
	f = fdopen(fd, "w");
	assert_non_null(f);
	fprintf(f, "0 insertion target 0 0.1\n%g end\n", end_s);
	fclose(f);
}

/*
 * The hand's top speed: the strongest push the socket allows, held, never
 * moves the carriage faster than sim.hand_insertion_max_speed_m_s (the
 * push fades to nothing there), and gets it well under way.
 */
static void test_hand_top_speed(void **unused)
{
	const double push[ENDOSIM_AXES] = { 1000, 0, 0, 0 };
	struct config cfg;
	struct colon *colon;
	struct offline *o;
	char scn[64], err[512];
	double top, fastest = 0, hand_max = 0;

	(void)unused;
	config_defaults(&cfg);
	top = cfg.sim.hand_max_speed[ENDOSIM_AXIS_INSERTION];
	idle_scenario(scn, sizeof(scn), 5);
	colon = normal_colon(&cfg);
	o = offline_create(&cfg, colon, scn, err, sizeof(err));
	unlink(scn);
	if (!o) {
		fail_msg("%s", err);
	}
	offline_step(o);
	offline_hand(o, push, 1.5);
	for (long k = 0; k < 1500; k++) {
		const struct endosim_state *st = offline_step(o);

		fastest = fmax(fastest, st->axis[0].velocity);
		hand_max = fmax(hand_max, st->axis[0].hand);
	}
	offline_destroy(o);
	printf("# pushed as hard as allowed: %.3f m/s (top speed %.2f m/s), "
	       "the hand's force at most %.1f N (its strength %.1f N)\n",
	       fastest, top, hand_max, cfg.sim.hand_max[0]);
	assert_true(fastest > 0.3);
	assert_true(fastest <= top);
	assert_true(hand_max <= cfg.sim.hand_max[0]);
	assert_true(hand_max > 0.9 * cfg.sim.hand_max[0]);
}

/* The loop on the normal case with the patient ENABLED or not, its hand
 * playing the scenario of LINES (the paper's model rendering). */
static struct offline *patient_course(bool enabled, const char *const *lines)
{
	struct scenario *scn = scenario_create();
	struct config cfg;
	struct offline *o;
	char err[512];

	assert_non_null(scn);
	for (; *lines; lines++) {
		assert_int_equal(scenario_append(scn, *lines, err,
						 sizeof(err)), 0);
	}
	config_defaults(&cfg);
	cfg.patient.enabled = enabled;
	o = offline_create_with(&cfg, normal_colon(&cfg), scn, err,
				sizeof(err));
	if (!o) {
		fail_msg("%s", err);
	}
	return o;
}

/* The state of the first cycle played at scenario time T_S or after. */
static const struct endosim_state *play_until(struct offline *o, double t_s)
{
	const struct endosim_state *st;

	do {
		st = offline_step(o);
	} while (st->scenario_time_s < t_s - 1e-9);
	return st;
}

/*
 * A scenario's valves and commands for the assistant reach the patient
 * through the loop's own cycle (what the daemon plays): the valves as the
 * scenario holds them, each command once, in order, one a cycle (two at
 * the same time both carried out), one the patient refuses (a site the
 * case does not have) changing nothing; with the patient disabled, only
 * the valves are published, nothing moves.
 */
static void test_scenario_patient(void **unused)
{
	static const char *const lines[] = {
		"0.10 valve air on", "0.20 patient press llq 30",
		"0.30 patient press nowhere", "0.40 valve air off",
		"0.40 patient release", "0.40 patient position supine",
		"0.50 valve water on", "1 end", NULL,
	};
	const struct endosim_state *st;
	struct offline *o = patient_course(true, lines);
	double gas_in;

	(void)unused;
	st = play_until(o, 0.09);
	assert_int_equal(st->patient.valves, 0);
	assert_true(st->patient.gas_in_m3 == 0);
	st = play_until(o, 0.15);
	assert_int_equal(st->patient.valves, ENDOSIM_VALVE_AIR);
	assert_true(st->patient.gas_in_m3 > 0);
	st = play_until(o, 0.25);
	assert_int_equal(st->patient.hand_site, 0); /* llq, the first */
	assert_float_equal(st->patient.hand_n, 30, 1e-12);
	st = play_until(o, 0.35);
	assert_int_equal(st->patient.hand_site, 0);
	st = play_until(o, 0.45);
	gas_in = st->patient.gas_in_m3;
	assert_int_equal(st->patient.valves, 0);
	assert_int_equal(st->patient.hand_site, -1);
	assert_int_equal(st->patient.position, ENDOSIM_POSITION_SUPINE);
	assert_int_equal(st->patient.turning, 1);
	st = play_until(o, 0.55);
	assert_int_equal(st->patient.valves, ENDOSIM_VALVE_WATER);
	assert_true(st->patient.gas_in_m3 == gas_in);
	offline_destroy(o);

	o = patient_course(false, lines);
	st = play_until(o, 0.45);
	assert_int_equal(st->patient.enabled, 0);
	assert_int_equal(st->patient.hand_site, -1);
	assert_int_equal(st->patient.turning, 0);
	assert_true(st->patient.gas_in_m3 == 0);
	st = play_until(o, 0.55);
	assert_int_equal(st->patient.valves, ENDOSIM_VALVE_WATER);
	offline_destroy(o);
}

/* SCEN's value at session time T: the record at or after it. */
static double scen_at(const float *scen, long n, double t)
{
	long k = (long)ceil(t / PERIOD_S - 1e-9);

	return scen[k < 0 ? 0 : k >= n ? n - 1 : k];
}

/* Each episode of EP within [LO, HI] s of the course; at least one. */
static void episodes_within(const struct metrics_episode *ep, uint32_t n,
			    const float *scen, long cycles, double lo,
			    double hi)
{
	assert_true(n >= 1);
	for (uint32_t i = 0; i < n; i++) {
		double a = scen_at(scen, cycles, ep[i].start_s);
		double b = scen_at(scen, cycles, ep[i].end_s);

		printf("#   episode %.2f-%.2f s of the course, peak %.4f\n", a,
		       b, ep[i].peak);
		assert_true(ep[i].end_s >= 0 && a >= lo && b <= hi);
	}
}

/* The whole course's metrics, as the daemon's session would give them
 * (play_demo()). */
static void test_session_metrics(void **unused)
{
	const struct metrics_result r = demo.r;
	const float *scen = demo.scen;
	long cycles = demo.cycles;

	(void)unused;
	printf("# %.1f s: cecum at %.3f s (%.3f s of the course), insertion "
	       "%.3f s, withdrawal %.3f s; %u loops, largest %.4f m; %u force "
	       "episodes; mucosa seen %.3f\n", r.duration_s, r.cecum_s,
	       scen_at(scen, cycles, r.cecum_s), r.insertion_s,
	       r.withdrawal_s, r.loop_episodes, r.largest_loop_m,
	       r.force_episodes, r.mucosa_seen);
	assert_int_equal(r.records, cycles);
	assert_true(r.cecum_s > 0);
	assert_true(scen_at(scen, cycles, r.cecum_s) >= 59.2);
	assert_true(scen_at(scen, cycles, r.cecum_s) <= 61.5);
	assert_true(r.insertion_s == r.cecum_s && r.withdrawal_s > 10);
	episodes_within(r.loop, r.n_loop, scen, cycles, 22.4, 31.0);
	assert_true(r.largest_loop_m > 0.01 && r.largest_loop_m < 0.06);
	episodes_within(r.force, r.n_force, scen, cycles, 22.4, 31.0);
	for (uint32_t i = 0; i < r.n_force; i++) {
		/* the mesentery holding the largest loop, and not less than
		 * the 12 N of a 2 cm one */
		assert_true(r.force[i].peak >
			    fmin(12, MESENTERY_N_PER_M * r.largest_loop_m));
	}
	assert_true(r.mucosa_seen > 0.5);
}

static uint64_t run_hash(long cycles)
{
	struct config cfg;
	struct colon *colon;
	struct offline *o;
	uint64_t h = OFFLINE_HASH_START;

	config_defaults(&cfg);
	o = course(&cfg, "config/scenarios/demo-paper.scn", &colon);
	for (long k = 0; k < cycles; k++) {
		h = offline_hash(h, offline_step(o));
	}
	offline_destroy(o);
	return h;
}

/* Same inputs, same outputs, bit for bit: the flexure's loop included
 * (the first run play_demo()'s). */
static void test_repeats_exactly(void **unused)
{
	uint64_t a = demo.hash, b;

	(void)unused;
	b = run_hash(REPEAT_CYCLES);
	printf("# two runs of 26 s: %016llx, %016llx\n",
	       (unsigned long long)a, (unsigned long long)b);
	assert_true(a == b);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_demo_haptics),
		cmocka_unit_test(test_clamp),
		cmocka_unit_test(test_hand_top_speed),
		cmocka_unit_test(test_scenario_patient),
		cmocka_unit_test(test_session_metrics),
		cmocka_unit_test(test_repeats_exactly),
	};
	const char *top = getenv("ENDOSIM_TOP");

	if (top && chdir(top)) {
		perror(top);
		return 1;
	}
	return cmocka_run_group_tests(tests, play_demo, forget_demo);
}
