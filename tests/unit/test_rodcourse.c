/*
 * test_rodcourse.c - the rod model's demo course (config/scenarios/
 * demo.scn) in lockstep on simulated time: it is the trainee's course
 * (tests/tools/trainee.h, scenario_gen's: the file holds what she wrote
 * while she played it, byte for byte), and played on the normal case with
 * the demo's configuration (trainee_demo_config(): the patient enabled):
 *  - the tip reaches the cecum;
 *  - the patient: she insufflates, washes the lens, has the assistant
 *    press and the patient turned, each at least once and each to its
 *    effect, never insufflating beyond her 25 mmHg, the gas's pressure
 *    within Kozarek et al.'s 9-57 mmHg (the tip free); the gas used a
 *    minute printed beside Bretthauer et al.'s 0.25 L/min;
 *  - a loop forms on the way (the sigmoid pushed more than 2.5 cm off its
 *    course while the hand pushes on at the sigmoid's end) and is reduced
 *    (back under 2.5 cm after the withdrawal that follows);
 *  - each axis' published parts add up to its command;
 *  - the forces stay in a real colonoscopy's ranges (Appleyard et al.,
 *    GIE 2000, 21 colonoscopies: the insertion force above 10 N at most
 *    ~5-10 % of the time, its peak between 15 and 45 N; the roll's torque
 *    within 1 N m), nothing faults;
 *  - played again from the file she wrote, as endosimd plays it
 *    (offline.h), it repeats her run bit for bit (the first 30 s
 *    compared: her valves and the assistant's first press among them);
 *  - last, the shipped demo is her course, step for step: a change of
 *    the physics fails here after the checks above have judged it (and
 *    the demo is then written anew, docs/INSTRUCTOR.md says how).
 *
 * Under the sanitizers (sanitized.h) she plays the same course at twice
 * her pace (every check above but the last holds there too), and the
 * repeat compares its first 5 s; the demo, her course at her own pace, is
 * compared in the plain build.
 *
 * Run from the top of the source tree (tests/run.sh does), or with
 * ENDOSIM_TOP naming it.
 */
#include <math.h>
#include <stdbool.h>
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
#include "conf/cases.h"
#include "model/gas.h"
#include "offline.h"
#include "sanitized.h"
#include "trainee.h"

#define CASE "config/cases/normal.case"
#define DEMO "config/scenarios/demo.scn"

struct seen {
	double cecum;         /* where it starts + 2 cm, m */
	double cecum_at_s;    /* -1: not reached */
	double junction;      /* the sigmoid's end, m */
	double loop_max;      /* the sigmoid's largest loop, m */
	double loop_after;    /* the smallest loop after it, m */
	long cycles, over_10n;
	double peak_n, roll_peak_nm;
	uint32_t faults;
	double sum_err;       /* each axis' command less its parts' sum */
	uint64_t hash;        /* of the first REPEAT_CYCLES states */
	/* the patient's care */
	struct trainee_actions did; /* what she asked for */
	double length_s;      /* the course's */
	double gas_in_m3;     /* pumped in over it */
	double p_min_pa, p_max_pa; /* the gas's pressure */
	double p_air_max_pa;  /* ... while the air valve was covered */
	bool washing;         /* the jet on a dirty lens ... */
	int cleared;          /* ... that left it clear */
	double pad_n_s;       /* what the assistant's hand held, N s ... */
	double pressed_s;     /* ... over the time she pressed */
	uint32_t positions;   /* the positions the patient lay in (bits) */
};

/* The bound she keeps the pressure under while insufflating (trainee.c),
 * and Kozarek et al.'s range with the tip free (mmHg). */
#define PRESSURE_MAX_MMHG 25.0
#define KOZAREK_MIN_MMHG 9.0
#define KOZAREK_MAX_MMHG 57.0
#define MMHG (1 / GAS_PA_PER_MMHG)

#define REPEAT_CYCLES (SANITIZED ? 5000 : 30000)
#define PACE_M_PER_S (SANITIZED ? 0.06 : 0.03) /* her pace in: 3 cm/s */

/* The published parts of each axis' force against its command: the rod's
 * reaction at the carriage and the damping on insertion and roll; the
 * bending section's moment, the wires, the spring-back and the damping on
 * each wheel. */
static double parts_error(const struct endosim_state *s)
{
	const struct endosim_haptics_state *h = &s->haptics;
	double e = fabs(s->axis[0].command - h->trans_rod_n - h->damping[0]);

	e = fmax(e, fabs(s->axis[1].command - h->tube_rod_nm - h->damping[1]));
	for (int w = 0; w < 2; w++) {
		e = fmax(e, fabs(s->axis[2 + w].command -
				 h->wheel_contact_nm[w] -
				 h->wheel_tension_nm[w] -
				 h->wheel_elastic_nm[w] - h->damping[2 + w]));
	}
	return e;
}

/* The patient as the course leaves it: the gas, the lens, the hand. */
static void watch_patient(struct seen *w, const struct endosim_patient_state *p)
{
	double dirt = fmax(p->lens_smear, p->lens_murk);

	w->p_min_pa = fmin(w->p_min_pa, p->pressure_pa);
	w->p_max_pa = fmax(w->p_max_pa, p->pressure_pa);
	if (p->valves & ENDOSIM_VALVE_AIR) {
		w->p_air_max_pa = fmax(w->p_air_max_pa, p->pressure_pa);
	}
	w->washing = (p->valves & ENDOSIM_VALVE_WATER) &&
		     (w->washing || dirt > 0.3);
	if (w->washing && dirt < 0.05) {
		w->cleared++;
		w->washing = false;
	}
	if (p->hand_site >= 0) {
		w->pad_n_s += p->pad_n * OFFLINE_PERIOD_NS * ENDOSIM_S_PER_NS;
		w->pressed_s += OFFLINE_PERIOD_NS * ENDOSIM_S_PER_NS;
	}
	if (!p->turning) {
		w->positions |= 1u << p->position;
	}
	w->gas_in_m3 = p->gas_in_m3;
}

static void watch(const struct endosim_state *s, void *arg)
{
	struct seen *w = arg;
	double f = fabs(s->axis[ENDOSIM_AXIS_INSERTION].limited);
	double loop = s->scope.bow_m[0];

	w->cycles++;
	w->over_10n += f > 10;
	w->peak_n = fmax(w->peak_n, f);
	w->roll_peak_nm = fmax(w->roll_peak_nm,
			       fabs(s->axis[ENDOSIM_AXIS_ROLL].limited));
	if (w->cecum_at_s < 0 && s->scope.tip_s_m >= w->cecum) {
		w->cecum_at_s = s->scenario_time_s;
	}
	if (s->scope.depth_m > w->junction - 0.1 && w->cecum_at_s < 0) {
		if (loop > w->loop_max) {
			w->loop_max = loop;
			w->loop_after = loop;
		}
		w->loop_after = fmin(w->loop_after, loop);
	}
	w->faults |= s->fault_bits;
	w->sum_err = fmax(w->sum_err, parts_error(s));
	if (w->cycles <= REPEAT_CYCLES) {
		w->hash = offline_hash(w->hash, s);
	}
	watch_patient(w, &s->patient);
	w->length_s = s->scenario_time_s;
}

/* Plays the trainee's course, her script into SCRIPT (may be NULL). */
static void play(struct seen *w, FILE *script)
{
	struct config cfg;
	struct anatomy a;
	struct trainee *t;
	char err[512];

	memset(w, 0, sizeof(*w));
	w->cecum_at_s = -1;
	w->p_min_pa = INFINITY;
	w->hash = OFFLINE_HASH_START;
	trainee_demo_config(&cfg);
	assert_int_equal(anatomy_load(&a, CASE, err, sizeof(err)), 0);
	w->cecum = anatomy_segment_start(&a, ANATOMY_CECUM) + 0.02;
	w->junction = anatomy_segment_start(&a, ANATOMY_DESCENDING);
	t = trainee_create(&cfg, CASE, script, err, sizeof(err));
	if (!t) {
		fail_msg("%s", err);
	}
	trainee_watch(t, watch, w);
	assert_true(trainee_course(t, &a, PACE_M_PER_S));
	w->did = *trainee_did(t);
	trainee_destroy(t);
}

/* The lines of FILE that are not comments, joined. */
static char *steps_of(FILE *f)
{
	char *out = NULL, line[256];
	size_t size = 0;
	FILE *o = open_memstream(&out, &size);

	assert_non_null(o);
	rewind(f);
	while (fgets(line, sizeof(line), f)) {
		if (line[0] != '#') {
			fputs(line, o);
		}
	}
	fclose(o);
	return out;
}

/* Her course, played once for the tests: what she saw and wrote (a file,
 * as the daemon reads a scenario). */
static struct seen course;
static char course_file[] = "/tmp/test_rodcourse.XXXXXX";
static FILE *course_script;

static int play_course(void **unused)
{
	int fd = mkstemp(course_file);

	(void)unused;
	course_script = fd < 0 ? NULL : fdopen(fd, "w+");
	if (!course_script) {
		return -1;
	}
	play(&course, course_script);
	fflush(course_script);
	return 0;
}

static int forget_course(void **unused)
{
	(void)unused;
	if (course_script) {
		fclose(course_script);
		unlink(course_file);
	}
	return 0;
}

static void test_course(void **unused)
{
	const struct seen w = course;

	(void)unused;
	print_message("the course: cecum at %.2f s; the sigmoid's loop %.1f "
		      "cm, reduced to %.1f cm; insertion force above 10 N "
		      "%.1f %% of the time, peak %.1f N; roll torque peak "
		      "%.3f N m\n", w.cecum_at_s, w.loop_max * 100,
		      w.loop_after * 100, 100.0 * w.over_10n / w.cycles,
		      w.peak_n, w.roll_peak_nm);
	assert_true(w.cecum_at_s > 0);
	assert_true(w.loop_max > 0.025);
	assert_true(w.loop_after < 0.025);
	assert_true(w.over_10n <= 0.10 * w.cycles);
	assert_true(w.peak_n >= 15 && w.peak_n <= 45);
	assert_true(w.roll_peak_nm <= 1.0);
	assert_true(w.sum_err < 1e-9); /* the parts add up */
	assert_int_equal(w.faults, 0);
}

/*
 * The patient in the course: she used each of her means at least once and
 * each did what it is for (the gas pumped in, a wash that left the lens
 * clear, the assistant's hand holding the colon, the patient lying in
 * another position), never insufflated beyond her bound, and the gas's
 * pressure (the free tip's: the model has one) stayed within what Kozarek
 * et al. measured with the tip free. The gas used a minute is printed
 * against Bretthauer et al.'s (a short course: the first filling weighs
 * more than in a half-hour colonoscopy).
 */
static void test_patient_care(void **unused)
{
	const struct seen w = course;
	const struct trainee_actions *d = &w.did;

	(void)unused;
	print_message("the patient: %d insufflations, %.2f L in %.0f s: %.2f "
		      "L/min (Bretthauer et al.: about 0.25); the gas at "
		      "%.1f-%.1f mmHg (Kozarek et al., tip free: %.0f-%.0f), "
		      "at most %.1f while she insufflated; %d washes, %d "
		      "leaving the lens clear; the hand %d time(s), %.0f s, "
		      "holding %.1f N on average; %d turns, positions seen "
		      "0x%x\n",
		      d->insufflations, w.gas_in_m3 * 1e3, w.length_s,
		      w.gas_in_m3 * 1e3 / (w.length_s / 60), w.p_min_pa * MMHG,
		      w.p_max_pa * MMHG, KOZAREK_MIN_MMHG, KOZAREK_MAX_MMHG,
		      w.p_air_max_pa * MMHG, d->washes, w.cleared, d->hands,
		      w.pressed_s, w.pad_n_s / fmax(w.pressed_s, 1e-9),
		      d->turns, w.positions);
	assert_true(w.cecum_at_s > 0);
	assert_int_equal(w.faults, 0);
	assert_true(d->insufflations >= 1 && w.gas_in_m3 > 0);
	assert_true(d->washes >= 1 && w.cleared >= 1);
	assert_true(d->hands >= 1 && w.pad_n_s > 0);
	assert_true(d->turns >= 1 && (w.positions & (w.positions - 1)));
	assert_true(w.p_air_max_pa * MMHG < PRESSURE_MAX_MMHG + 0.5);
	assert_true(w.p_min_pa * MMHG >= KOZAREK_MIN_MMHG);
	assert_true(w.p_max_pa * MMHG <= KOZAREK_MAX_MMHG);
}

/*
 * Same inputs, same outputs, bit for bit: the file she wrote, played as
 * the daemon plays a scenario, repeats her run (its states from the first
 * cycle she acted in).
 */
static void test_repeats_exactly(void **unused)
{
	struct config cfg;
	struct colon *colon;
	struct offline *o;
	char err[512];
	uint64_t h = OFFLINE_HASH_START;

	(void)unused;
	trainee_demo_config(&cfg);
	snprintf(cfg.colon.file, sizeof(cfg.colon.file), CASE);
	colon = cases_load(&cfg, NULL, err, sizeof(err));
	assert_non_null(colon);
	o = offline_create(&cfg, colon, course_file, err, sizeof(err));
	if (!o) {
		fail_msg("%s", err);
	}
	offline_step(o); /* cycle 0: before she acted */
	for (long k = 0; k < REPEAT_CYCLES; k++) {
		h = offline_hash(h, offline_step(o));
	}
	offline_destroy(o);
	print_message("%d s: her run %016llx, the file played %016llx\n",
		      REPEAT_CYCLES / 1000, (unsigned long long)course.hash,
		      (unsigned long long)h);
	assert_true(course.hash == h);
}

/* Where the first line in which A and B differ starts (-1: none). */
static long first_difference(const char *a, const char *b)
{
	long k = 0, line = 0;

	for (; a[k] && a[k] == b[k]; k++) {
		if (a[k] == '\n') {
			line = k + 1;
		}
	}
	return a[k] == b[k] ? -1 : line;
}

/* The shipped demo is her course, step for step (with the two tests above
 * passing, the demo played is her run). */
static void test_demo_is_her_course(void **unused)
{
	FILE *shipped;
	char *a, *b;
	long at;

	(void)unused;
	if (SANITIZED) {
		printf("skip - test_demo_is_her_course under the sanitizers: "
		       "she played at twice her pace; the plain build compares "
		       "the demo\n");
		skip();
	}
	shipped = fopen(DEMO, "r");
	assert_non_null(shipped);
	a = steps_of(course_script);
	b = steps_of(shipped);
	at = first_difference(a, b);
	if (at >= 0) {
		fail_msg("%s is not her course on this model (write it anew: "
			 "docs/INSTRUCTOR.md, the demo): hers '%.*s', the file's "
			 "'%.*s'", DEMO, (int)strcspn(a + at, "\n"), a + at,
			 (int)strcspn(b + at, "\n"), b + at);
	}
	free(a);
	free(b);
	fclose(shipped);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_course),
		cmocka_unit_test(test_patient_care),
		cmocka_unit_test(test_repeats_exactly),
		cmocka_unit_test(test_demo_is_her_course),
	};
	const char *top = getenv("ENDOSIM_TOP");

	if (top && chdir(top)) {
		perror(top);
		return 1;
	}
	sanitized_leaves("her course at twice her pace (6 cm/s), the repeat "
			 "over its first 5 s; the demo as her course is the "
			 "plain build's");
	return cmocka_run_group_tests(tests, play_course, forget_course);
}
