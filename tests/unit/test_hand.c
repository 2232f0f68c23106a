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
 * Every push begins with the same insertion to the sigmoid's end: it is
 * played once, and each push is a branch of it (branch.h), the same run
 * bit for bit as one played from the start.
 *
 * Under the sanitizers (sanitized.h; three times slower) each push is two
 * steps, with the assistant over the sigmoid and without, the hand at
 * twice the pace (6 cm/s): a run for memory errors; the plain build
 * checks the hand's effect.
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
#include "branch.h"
#include "sanitized.h"
#include "trainee.h"

#define CASE "config/cases/normal.case"
#define HOLD_N_PER_M 5000  /* the tip impacted in the junction's fold */
#define PUSH_STEP_M 0.02
#define PUSH_MOST_M 0.30
#define LOOP_M 0.05        /* the clinic's loop */
#define SAMPLES 4096       /* the centreline's, at most */
#define PACE_M_PER_S (SANITIZED ? 0.06 : 0.03) /* the hand's, in and on */

struct push {
	double loop_m;     /* the sigmoid's growth under the push */
	double advance_m;  /* the tip's */
	double pushed_m;   /* the carriage's */
	double force_n;    /* the hand's at the end */
	int steps;         /* of PUSH_STEP_M */
	int hand_site;     /* the published one, once pressed */
	uint32_t faults;   /* the fault bits at the end */
};

/* The trainee at the sigmoid's end, where every push begins. */
struct start {
	struct trainee *t;
	size_t i0, i1;     /* the sigmoid's samples */
};

/* One push from START: the assistant pressing at SITE (NULL: nobody),
 * STEPS steps of PUSH_STEP_M (0: until the clinic's loop). */
struct push_of {
	const struct start *start;
	const char *site;
	int steps;
};

/* The sigmoid's samples: where they lie now into AT, or how far they are
 * from AT (the largest). */
static double sigmoid(const struct start *s, double (*at)[3], int keep)
{
	const struct centreline *cl = colon_centreline(trainee_colon(s->t));
	double most = 0;

	for (size_t i = s->i0; i <= s->i1; i++) {
		const double *p = centreline_sample(cl, i)->p;

		if (keep) {
			vec3_copy(at[i], p);
		} else {
			most = fmax(most, vec3_dist(p, at[i]));
		}
	}
	return most;
}

/* The trainee steered to the sigmoid's end (the same for every push:
 * played once, each push a branch of it, branch.h). */
static void to_junction(struct start *s)
{
	struct config cfg;
	struct anatomy a;
	char err[512];
	double ds;

	trainee_demo_config(&cfg);
	assert_int_equal(anatomy_load(&a, CASE, err, sizeof(err)), 0);
	s->t = trainee_create(&cfg, CASE, NULL, err, sizeof(err));
	if (!s->t) {
		fail_msg("%s", err);
	}
	ds = centreline_step(colon_centreline(trainee_colon(s->t)));
	s->i0 = (size_t)ceil(anatomy_segment_start(&a, ANATOMY_SIGMOID) / ds);
	s->i1 = (size_t)floor(anatomy_segment_start(&a, ANATOMY_DESCENDING) /
			      ds);
	assert_true(s->i1 < SAMPLES);
	assert_true(trainee_insert(s->t, anatomy_segment_start(&a,
					ANATOMY_DESCENDING) - 0.01, PACE_M_PER_S, 8));
}

/* The held-tip push of ARG (struct push_of) into OUT (struct push), in
 * the child of branch_run(): no assertion here. */
static void held_push(void *arg, void *out)
{
	static double at[SAMPLES][3];
	const struct push_of *p = arg;
	struct trainee *t = p->start->t;
	struct push *r = out;
	double tip0[3], d0;

	memset(r, 0, sizeof(*r));
	if (p->site) {
		trainee_press(t, p->site, 0);
	}
	trainee_relax(t, 1.0);
	r->hand_site = trainee_state(t)->patient.hand_site;
	sigmoid(p->start, at, 1);
	vec3_copy(tip0, trainee_state(t)->scope.tip);
	d0 = trainee_state(t)->scope.depth_m;
	trainee_hold_tip(t, HOLD_N_PER_M);
	while (p->steps ? r->steps < p->steps :
			  r->steps * PUSH_STEP_M < PUSH_MOST_M &&
				  sigmoid(p->start, at, 0) < LOOP_M) {
		trainee_push(t, PUSH_STEP_M, PACE_M_PER_S);
		r->steps++;
	}
	r->loop_m = sigmoid(p->start, at, 0);
	r->advance_m = vec3_dist(trainee_state(t)->scope.tip, tip0);
	r->pushed_m = trainee_state(t)->scope.depth_m - d0;
	r->force_n = -trainee_state(t)->axis[ENDOSIM_AXIS_INSERTION].command;
	r->faults = trainee_state(t)->fault_bits;
	trainee_destroy(t);
}

/* The push of held_push() from START, checked to have run clean. */
static struct push push(const struct start *start, const char *site,
			int steps)
{
	struct push_of p = { start, site, steps };
	struct push r;
	struct anatomy a;
	char err[512];

	assert_int_equal(anatomy_load(&a, CASE, err, sizeof(err)), 0);
	branch_run(held_push, &p, &r, sizeof(r));
	assert_int_equal(r.hand_site, site ? anatomy_site_find(&a, site) : -1);
	assert_int_equal(r.faults, 0);
	print_message("%-9s pushed %.1f cm (%d steps): the loop %.2f cm, the "
		      "tip %.2f mm, %.1f N\n", site ? site : "no hand",
		      r.pushed_m * 100, r.steps, r.loop_m * 100,
		      r.advance_m * 1e3, r.force_n);
	return r;
}

static void test_hand_over_the_loop(void **unused)
{
	struct push none, near, far;
	struct start start;

	(void)unused;
	to_junction(&start);
	if (SANITIZED) {
		none = push(&start, NULL, 2);
		near = push(&start, "llq", 2);
		trainee_destroy(start.t);
		assert_true(near.steps == 2 && none.steps == 2);
		sanitized_leaves("at 6 cm/s, two steps each, with the "
				 "assistant over the sigmoid and without; the "
				 "hand's effect, and far from the loop, are the "
				 "plain build's");
		return;
	}
	none = push(&start, NULL, 0);
	near = push(&start, "llq", none.steps);
	far = push(&start, "umbilical", none.steps);
	trainee_destroy(start.t);
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
