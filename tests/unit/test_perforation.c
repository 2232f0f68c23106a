/*
 * test_perforation.c - the tip pushed through the wall (perforation.h):
 *  - the threshold: Johnson's 14.1 N straight and 46.5 N bent 90 degrees,
 *    linear between, 46.5 N beyond, either way of bending;
 *  - a force above it tears after hold_s held, to the step, in the
 *    segment it pressed, once; held a step less, or let go between, it
 *    does not;
 *  - 46 N on a tip bent 90 degrees never tears; non-finite inputs count as
 *    no force.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "model/perforation.h"

#define DT 0.001

static const struct perforation_params par = PERFORATION_PARAMS_DEFAULT;

/* Steps of F_N on a tip bent BEND_RAD for T_S; the step it tore in
 * (from 1), 0: it did not. */
static long press(struct perforation *p, double f_n, double bend_rad,
		  double t_s)
{
	long tore = 0;

	for (long k = 1; k <= lround(t_s / DT); k++) {
		if (perforation_step(p, &par, f_n, bend_rad, 3, DT)) {
			assert_int_equal(tore, 0); /* once */
			tore = k;
		}
	}
	return tore;
}

static void test_threshold(void **unused)
{
	(void)unused;
	assert_true(perforation_threshold_n(&par, 0) == 14.1);
	assert_true(fabs(perforation_threshold_n(&par, M_PI / 2) - 46.5) <
		    1e-12);
	assert_true(fabs(perforation_threshold_n(&par, -M_PI / 4) -
			 (14.1 + 46.5) / 2) < 1e-12);
	assert_true(perforation_threshold_n(&par, 2.5) == 46.5);
}

static void test_hold(void **unused)
{
	struct perforation p;
	long steps = lround(par.hold_s / DT);

	(void)unused;
	perforation_reset(&p);
	assert_int_equal(press(&p, 14.5, 0, par.hold_s - DT), 0);
	assert_false(p.torn);
	assert_int_equal(p.segment, -1);
	/* let go for a step: the hold starts again */
	assert_int_equal(press(&p, 0, 0, DT), 0);
	assert_int_equal(press(&p, 14.5, 0, par.hold_s - DT), 0);
	assert_int_equal(press(&p, 14.5, 0, 2 * DT), 1);
	assert_true(p.torn);
	assert_int_equal(p.segment, 3);
	/* from rest, to the step */
	perforation_reset(&p);
	assert_int_equal(press(&p, 25, 0.3, 1.0), steps); /* 20.3 N at 0.3 rad */
	print_message("perforation: 14.1 N straight, 46.5 N bent 90 deg; "
		      "torn after %ld steps of %.0f ms held\n", steps, DT * 1e3);
}

static void test_bent_tip_holds(void **unused)
{
	struct perforation p;

	(void)unused;
	perforation_reset(&p);
	assert_int_equal(press(&p, 46, M_PI / 2, 5), 0);
	assert_int_equal(press(&p, 30, M_PI / 2, 5), 0);
	assert_int_equal(press(&p, 30, 0, 1), lround(par.hold_s / DT));
	perforation_reset(&p);
	assert_int_equal(press(&p, NAN, 0, 1), 0);
	assert_int_equal(press(&p, 30, NAN, 1), 0);
	assert_int_equal(press(&p, INFINITY, 0, 1), 0);
	assert_false(p.torn);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_threshold),
		cmocka_unit_test(test_hold),
		cmocka_unit_test(test_bent_tip_holds),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
