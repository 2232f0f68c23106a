/*
 * test_separation.c - whether the metrics tell an expert from a novice the
 * way the papers do (docs/METRICS.md, "Which measures discriminate"): two
 * scripted trainees (tests/tools/trainee.h) through the polyps case on the
 * rod model as endosimd runs it, in lockstep on simulated time, every
 * published state recorded into the metrics as the daemon's recorder does:
 *
 *  - both insert at 4 cm/s steering into the lumen to the sigmoid's end,
 *    where the tip catches in the junction's fold (held by a spring of
 *    5000 N/m, as in test_clinic); the expert takes it out (withdrawing
 *    5 cm turning the tube clockwise), the novice pushes on 15 cm with a
 *    straight tip into the loop; then both steer on to the cecum, and
 *    whenever the scope is stuck the novice first pushes 10 cm more into
 *    the loop, then both reduce it (withdrawing 10 cm turning clockwise);
 *  - the expert withdraws at 3 cm/s looking around the folds (the tip bent
 *    0.4 rad, circling every 2 s), the novice at 6 cm/s looking ahead.
 *
 * Every measure that claims to discriminate and that these scripts
 * exercise must differ in the papers' direction: on the way in (3D-CoPS,
 * GI Mentor's excessive pressure) the expert's chase efficiency is higher,
 * her idle push, time looped, peak force and time above the force
 * threshold lower; on the way out (CoRS) her tip retraction and
 * retraction efficiency higher; her withdrawal longer (the quality mark);
 * she sees more of the mucosa and finds more polyps (GI Mentor, the
 * virtual-withdrawal study). The measures this pair does not separate,
 * and why, are in docs/METRICS.md. Deterministic: the loop runs bit for
 * bit the same on every machine.
 *
 * Under AddressSanitizer (three times slower; or built with
 * -DSEPARATION_SHORT) both sessions end 10 cm past
 * the junction, the mistake's immediate effect: there the expert's chase
 * efficiency is higher, her idle push, time looped and peak force lower;
 * the rest is checked in the plain build.
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
#include "session/metrics.h"
#include "session/metricstext.h"
#include "proto/session_file.h"
#include "trainee.h"

#define CASE "config/cases/polyps.case"
#define SPEED 0.04 /* m/s: both trainees' pace in */
#define IMPACTED_N_PER_M 5000 /* the tip caught in the junction's fold */
#define LOOP_M 0.03 /* the rod model's loop threshold */
#if defined(__SANITIZE_ADDRESS__) || defined(SEPARATION_SHORT)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

static void record(const struct endosim_state *s, void *arg)
{
	struct session_record r;

	session_record_from_state(s, &r);
	metrics_record(arg, &r);
}

/* One trainee's session: EXPERT or not; the result into OUT. */
static void session(bool expert, struct metrics_result *out)
{
	struct config cfg;
	struct metrics_params p;
	struct anatomy a;
	struct trainee *t;
	struct metrics *m;
	double junction, cecum, out_m;
	char err[512];

	config_defaults(&cfg);
	cfg.haptics.model = HAPTICS_MODEL_ROD;
	assert_int_equal(anatomy_load(&a, CASE, err, sizeof(err)), 0);
	junction = anatomy_segment_start(&a, ANATOMY_DESCENDING);
	cecum = anatomy_segment_start(&a, ANATOMY_CECUM) + 0.02;
	t = trainee_create(&cfg, CASE, NULL, err, sizeof(err));
	if (!t) {
		fail_msg("%s", err);
	}
	metrics_params_default(&p);
	p.loop_threshold_m = LOOP_M;
	m = metrics_create(trainee_colon(t), &p);
	assert_non_null(m);
	trainee_watch(t, record, m);
	trainee_hold(t, 1.0);
	trainee_insert(t, junction - 0.01, SPEED, 6);
	trainee_hold_tip(t, IMPACTED_N_PER_M);
	if (expert) {
		trainee_withdraw(t, 0.05, SPEED, 0.5);
	} else {
		trainee_push(t, 0.15, SPEED);
	}
	trainee_hold_tip(t, 0);
	trainee_relax(t, 1.0);
	if (SANITIZED) { /* on 10 cm past the junction, and no further */
		trainee_insert(t, junction + 0.10, SPEED, 4);
		goto done;
	}
	/* when stuck the novice first pushes on 10 cm into the loop */
	assert_true(trainee_reach(t, cecum, SPEED, expert ? 0 : 0.10));
	trainee_hold(t, 2.0);
	out_m = trainee_state(t)->scope.depth_m - 0.10;
	if (expert) {
		trainee_withdraw_looking(t, out_m, 0.03, 0.4, 2.0);
	} else {
		trainee_withdraw(t, out_m, 0.06, 0);
	}
done:
	metrics_result(m, out);
	metrics_destroy(m);
	trainee_destroy(t);
}

static void test_expert_and_novice(void **state)
{
	static struct metrics_result e, n;
	const struct metricstext_field *f;
	size_t nf = metricstext_fields(&f);

	(void)state;
	session(true, &e);
	session(false, &n);
	printf("# %-28s %12s %12s\n", "measure", "expert", "novice");
	for (size_t i = 0; i < nf; i++) {
		printf("# %-28s %12.4f %12.4f\n", f[i].key,
		       metricstext_field_value(&e, &f[i]),
		       metricstext_field_value(&n, &f[i]));
	}
	/* the way in (3D-CoPS, GI Mentor's excessive pressure) */
	assert_true(e.chase_efficiency > n.chase_efficiency);
	assert_true(e.shaft_idle_m < n.shaft_idle_m);
	assert_true(e.loop_s < n.loop_s);
	assert_true(e.peak_insertion_n < n.peak_insertion_n);
	if (SANITIZED) {
		printf("# sanitized build: the sessions end 10 cm past the "
		       "junction; the rest is checked in the plain build\n");
		return;
	}
	assert_true(e.force_episode_s < n.force_episode_s);
	/* the way out (CoRS, the quality mark) and what was seen (GI Mentor,
	 * the virtual-withdrawal study) */
	assert_true(e.tip_retraction_m > n.tip_retraction_m);
	assert_true(e.retraction_efficiency > n.retraction_efficiency);
	assert_true(e.withdrawal_s > n.withdrawal_s);
	assert_true(e.mucosa_seen > n.mucosa_seen);
	assert_true(e.polyps_seen > n.polyps_seen);
}

int main(void)
{
	const char *top = getenv("ENDOSIM_TOP");
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_expert_and_novice),
	};

	if (top && chdir(top)) {
		perror(top);
		return 1;
	}
	return cmocka_run_group_tests(tests, NULL, NULL);
}
