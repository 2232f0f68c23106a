/*
 * test_timing.c - endoview's figures (viewer/timing.h): nearest-rank
 * percentiles of what was added, the last TIMING_SAMPLES only, and a
 * frame rate that follows the frame times.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "viewer/timing.h"

static void percentiles(void **state)
{
	struct timing *t = timing_create();

	(void)state;
	assert_non_null(t);
	assert_true(timing_quantile(t, TIMING_FRAME, 0.5) == 0);
	for (int k = 100; k >= 1; k--) {
		timing_add(t, TIMING_FRAME, k); /* 1 .. 100 ms, any order */
	}
	timing_add(t, TIMING_AGE, 7);
	assert_int_equal(timing_count(t, TIMING_FRAME), 100);
	assert_true(timing_quantile(t, TIMING_FRAME, 0.5) == 50);
	assert_true(timing_quantile(t, TIMING_FRAME, 0.99) == 99);
	assert_true(timing_quantile(t, TIMING_FRAME, 1.0) == 100);
	assert_true(timing_quantile(t, TIMING_AGE, 0.99) == 7);
	timing_destroy(t);
}

static void keeps_the_last(void **state)
{
	struct timing *t = timing_create();

	(void)state;
	assert_non_null(t);
	for (int k = 0; k < TIMING_SAMPLES; k++) {
		timing_add(t, TIMING_FRAME, 1000);
	}
	for (int k = 0; k < TIMING_SAMPLES; k++) {
		timing_add(t, TIMING_FRAME, 10);
	}
	assert_int_equal(timing_count(t, TIMING_FRAME), TIMING_SAMPLES);
	assert_true(timing_quantile(t, TIMING_FRAME, 1.0) == 10);
	assert_true(fabs(timing_fps(t) - 100) < 0.5);
	timing_destroy(t);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(percentiles),
		cmocka_unit_test(keeps_the_last),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
