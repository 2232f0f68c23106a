/*
 * test_clinic.c - the rod model against what happens in a colonoscopy
 * (issue 14's clinic), on the normal and the redundant-sigmoid cases, in
 * lockstep on simulated time with the simulated hand (tests/tools/
 * trainee.h: a trainee driving the rig through a scenario she writes as
 * she goes):
 *
 *  - the loop: the tip steered to the sigmoid's end and held there (a
 *    spring of 5000 N/m where it is: impacted in the junction's fold),
 *    the hand pushing on with a straight tip: the sigmoid (mobile) lifts
 *    into a loop of at least 5 cm while the tip advances less than 2 cm
 *    per 10 cm inserted, and the hand's force rises;
 *  - the reduction: withdrawing 20 cm turning the tube clockwise, then
 *    letting the tube settle, brings the sigmoid back within 1 cm of where
 *    it lay with the tip at the junction before the loop (a stiff scope
 *    through the sigmoid's tight bends holds it a little off its empty
 *    course: that is its rest with the scope in it);
 *  - after it, let go, the tip advances at least 0.8 cm per cm inserted;
 *  - the descending colon (fixed) moves less than 2 mm throughout.
 *
 * Under the sanitizers (sanitized.h) the redundant sigmoid's clinic alone
 * (the normal case's held-tip push runs there in test_hand; the normal
 * case skipped, not passed), the hand at twice the pace, 6 cm/s (every
 * check above holds there too).
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

#include "model/anatomy.h"
#include "model/centreline.h"
#include "sanitized.h"
#include "trainee.h"
#include "base/vec3.h"

#define HOLD_N_PER_M 5000  /* the tip impacted in the junction's fold */
#define PUSH_STEP_M 0.02
#define PUSH_MOST_M 0.30
#define PACE_M_PER_S (SANITIZED ? 0.06 : 0.03) /* the hand's, in and out */

/* The descending colon's largest displacement from its course, m. */
static double descending_moved(const struct trainee *t,
			       const struct anatomy *a)
{
	const struct centreline *cl = colon_centreline(trainee_colon(t));
	double ds = centreline_step(cl), most = 0;
	size_t i0 = (size_t)ceil(anatomy_segment_start(a, ANATOMY_DESCENDING) /
				 ds);
	size_t i1 = (size_t)floor(anatomy_segment_start(
				a, ANATOMY_SPLENIC_FLEXURE) / ds);

	for (size_t i = i0; i <= i1; i++) {
		most = fmax(most, vec3_dist(centreline_sample(cl, i)->p,
					    centreline_base(cl, i)->p));
	}
	return most;
}

static double loop_m(const struct trainee *t)
{
	return trainee_state(t)->scope.bow_m[0]; /* the sigmoid: span 0 */
}

static void clinic(const char *case_path)
{
	struct config cfg;
	struct anatomy a;
	struct trainee *t;
	char err[512];
	double junction, before, f0, d0, tip0, pushed, advanced, moved = 0;

	config_defaults(&cfg);
	cfg.haptics.model = HAPTICS_MODEL_ROD;
	assert_int_equal(anatomy_load(&a, case_path, err, sizeof(err)), 0);
	t = trainee_create(&cfg, case_path, NULL, err, sizeof(err));
	if (!t) {
		fail_msg("%s", err);
	}
	junction = anatomy_segment_start(&a, ANATOMY_DESCENDING);
	assert_true(trainee_insert(t, junction - 0.01, PACE_M_PER_S, 8));
	trainee_relax(t, 1.0);
	before = loop_m(t);
	f0 = -trainee_state(t)->axis[ENDOSIM_AXIS_INSERTION].command;
	d0 = trainee_state(t)->scope.depth_m;
	tip0 = trainee_state(t)->scope.tip_s_m;

	/* the loop */
	trainee_hold_tip(t, HOLD_N_PER_M);
	for (pushed = 0; pushed < PUSH_MOST_M && loop_m(t) < 0.05;
	     pushed += PUSH_STEP_M) {
		trainee_push(t, PUSH_STEP_M, PACE_M_PER_S);
		moved = fmax(moved, descending_moved(t, &a));
	}
	pushed = trainee_state(t)->scope.depth_m - d0;
	advanced = trainee_state(t)->scope.tip_s_m - tip0;
	print_message("%s: at the junction (tip %.3f m, depth %.3f m) the "
		      "sigmoid %.1f cm off its course, %.1f N; pushed %.1f "
		      "cm on: loop %.1f cm, tip %+.1f cm, %.1f N\n", a.name,
		      tip0, d0, before * 100, f0, pushed * 100,
		      loop_m(t) * 100, advanced * 100,
		      -trainee_state(t)->axis[0].command);
	assert_true(loop_m(t) >= 0.05);
	assert_true(advanced < 0.2 * pushed);
	assert_true(-trainee_state(t)->axis[0].command > f0 + 1);

	/* the reduction */
	trainee_withdraw(t, 0.20, PACE_M_PER_S, 0.5);
	trainee_relax(t, 2.0);
	moved = fmax(moved, descending_moved(t, &a));
	print_message("%s: withdrawn 20 cm turning clockwise: loop %.1f cm "
		      "(%.1f cm before it)\n", a.name, loop_m(t) * 100,
		      before * 100);
	assert_true(loop_m(t) <= before + 0.01);

	/* on again */
	trainee_hold_tip(t, 0);
	trainee_relax(t, 1.0);
	d0 = trainee_state(t)->scope.depth_m;
	tip0 = trainee_state(t)->scope.tip_s_m;
	trainee_insert(t, tip0 + 0.10, PACE_M_PER_S, 4);
	moved = fmax(moved, descending_moved(t, &a));
	print_message("%s: inserted again %.1f cm: the tip %+.1f cm; the "
		      "descending colon moved %.2f mm at most\n", a.name,
		      (trainee_state(t)->scope.depth_m - d0) * 100,
		      (trainee_state(t)->scope.tip_s_m - tip0) * 100,
		      moved * 1e3);
	assert_true(trainee_state(t)->scope.tip_s_m - tip0 >=
		    0.8 * (trainee_state(t)->scope.depth_m - d0));
	assert_true(moved < 0.002);
	assert_int_equal(trainee_state(t)->fault_bits, 0);
	trainee_destroy(t);
}

static void test_normal(void **unused)
{
	(void)unused;
	if (SANITIZED) {
		printf("skip - test_normal under the sanitizers: the plain "
		       "build runs it, test_hand the same case's push\n");
		skip();
	}
	clinic("config/cases/normal.case");
}

static void test_redundant_sigmoid(void **unused)
{
	(void)unused;
	clinic("config/cases/redundant-sigmoid.case");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_normal),
		cmocka_unit_test(test_redundant_sigmoid),
	};
	const char *top = getenv("ENDOSIM_TOP");

	if (top && chdir(top)) {
		perror(top);
		return 1;
	}
	sanitized_leaves("the redundant sigmoid's clinic at twice the pace "
			 "(6 cm/s); the normal case's is the plain build's");
	return cmocka_run_group_tests(tests, NULL, NULL);
}
