/*
 * test_hand.c - the assistant's hand against a loop (issue 22), on the
 * clinic's held-tip push (test_clinic.c) on the normal case with the
 * patient enabled, in lockstep on simulated time: the tip steered to the
 * sigmoid's end and held there (a spring of 5000 N/m), the hand pushing
 * on 2 cm at a time, straight, until the sigmoid has looped 5 cm (at most
 * 30 cm), then the same push with the assistant pressing (the default
 * 20 N) first over the sigmoid (the case's llq), then far from it (its
 * umbilical site, over the transverse colon):
 *  - over the sigmoid the loop is at least 40 % smaller for the same
 *    push, or the tip advances at least twice as far;
 *  - far from it both change by less than 10 %.
 * The loop is the sigmoid's growth under the push: its centreline's
 * largest move from where it lay when the push began (the pad itself
 * moves the colon from its rest before the push: that is not the loop);
 * the tip's advance is how far its point moved.
 *
 * Under AddressSanitizer (three times slower) each push is two steps,
 * with the assistant over the sigmoid and without: a run for memory
 * errors; the plain build checks the hand's effect.
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
#include "model/anatomy.h"
#include "model/centreline.h"
#include "trainee.h"

#define CASE "config/cases/normal.case"
#define HOLD_N_PER_M 5000  /* the tip impacted in the junction's fold */
#define PUSH_STEP_M 0.02
#define PUSH_MOST_M 0.30
#define LOOP_M 0.05        /* the clinic's loop */
#define SAMPLES 4096       /* the centreline's, at most */
#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

struct push {
	double loop_m;     /* the sigmoid's growth under the push */
	double advance_m;  /* the tip's */
	double pushed_m;   /* the carriage's */
	double force_n;    /* the hand's at the end */
	int steps;         /* of PUSH_STEP_M */
};

/* The sigmoid's samples: where they lie now into AT, or how far they are
 * from AT (the largest). */
static double sigmoid(const struct trainee *t, const struct anatomy *a,
		      double (*at)[3], int keep)
{
	const struct centreline *cl = colon_centreline(trainee_colon(t));
	double ds = centreline_step(cl), most = 0;
	size_t i0 = (size_t)ceil(anatomy_segment_start(a, ANATOMY_SIGMOID) /
				 ds);
	size_t i1 = (size_t)floor(anatomy_segment_start(a, ANATOMY_DESCENDING) /
				  ds);

	assert_true(i1 < SAMPLES);
	for (size_t i = i0; i <= i1; i++) {
		const double *p = centreline_sample(cl, i)->p;

		if (keep) {
			vec3_copy(at[i], p);
		} else {
			most = fmax(most, vec3_dist(p, at[i]));
		}
	}
	return most;
}

/*
 * The held-tip push with the assistant pressing at SITE (NULL: nobody),
 * STEPS steps of PUSH_STEP_M (0: until the clinic's loop).
 */
static struct push held_push(const char *site, int steps)
{
	static double at[SAMPLES][3];
	struct push r = { 0 };
	struct config cfg;
	struct anatomy a;
	struct trainee *t;
	char err[512];
	double tip0[3], d0;

	trainee_demo_config(&cfg);
	assert_int_equal(anatomy_load(&a, CASE, err, sizeof(err)), 0);
	t = trainee_create(&cfg, CASE, NULL, err, sizeof(err));
	if (!t) {
		fail_msg("%s", err);
	}
	assert_true(trainee_insert(t, anatomy_segment_start(&a,
					ANATOMY_DESCENDING) - 0.01, 0.03, 8));
	if (site) {
		trainee_press(t, site, 0);
	}
	trainee_relax(t, 1.0);
	assert_int_equal(trainee_state(t)->patient.hand_site,
			 site ? anatomy_site_find(&a, site) : -1);
	sigmoid(t, &a, at, 1);
	vec3_copy(tip0, trainee_state(t)->scope.tip);
	d0 = trainee_state(t)->scope.depth_m;
	trainee_hold_tip(t, HOLD_N_PER_M);
	while (steps ? r.steps < steps : r.steps * PUSH_STEP_M < PUSH_MOST_M &&
				    sigmoid(t, &a, at, 0) < LOOP_M) {
		trainee_push(t, PUSH_STEP_M, 0.03);
		r.steps++;
	}
	r.loop_m = sigmoid(t, &a, at, 0);
	r.advance_m = vec3_dist(trainee_state(t)->scope.tip, tip0);
	r.pushed_m = trainee_state(t)->scope.depth_m - d0;
	r.force_n = -trainee_state(t)->axis[ENDOSIM_AXIS_INSERTION].command;
	assert_int_equal(trainee_state(t)->fault_bits, 0);
	trainee_destroy(t);
	print_message("%-9s pushed %.1f cm (%d steps): the loop %.2f cm, the "
		      "tip %.2f mm, %.1f N\n", site ? site : "no hand",
		      r.pushed_m * 100, r.steps, r.loop_m * 100,
		      r.advance_m * 1e3, r.force_n);
	return r;
}

static void test_hand_over_the_loop(void **unused)
{
	struct push none, near, far;

	(void)unused;
	if (SANITIZED) {
		none = held_push(NULL, 2);
		near = held_push("llq", 2);
		assert_true(near.steps == 2 && none.steps == 2);
		print_message("sanitized build: two steps each; the hand's "
			      "effect is checked in the plain build\n");
		return;
	}
	none = held_push(NULL, 0);
	near = held_push("llq", none.steps);
	far = held_push("umbilical", none.steps);
	print_message("over the sigmoid: the loop %+.0f %%, the tip's advance "
		      "x%.2f; far from it: %+.0f %%, x%.2f\n",
		      100 * (near.loop_m / none.loop_m - 1),
		      near.advance_m / none.advance_m,
		      100 * (far.loop_m / none.loop_m - 1),
		      far.advance_m / none.advance_m);
	assert_true(fabs(far.loop_m - none.loop_m) < 0.1 * none.loop_m);
	assert_true(fabs(far.advance_m - none.advance_m) <
		    0.1 * none.advance_m);
	assert_true(near.loop_m <= 0.6 * none.loop_m ||
		    near.advance_m >= 2 * none.advance_m);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_hand_over_the_loop),
	};
	const char *top = getenv("ENDOSIM_TOP");

	if (top && chdir(top)) {
		perror(top);
		return 1;
	}
	return cmocka_run_group_tests(tests, NULL, NULL);
}
