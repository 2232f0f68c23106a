/* test_plant.c - the simulated axis against analytic solutions. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "model/plant.h"

#define DT 0.001

static const struct plant_params free_axis = {
	.inertia = 0.5, .viscous = 2.0, .coulomb = 0.0,
	.min = -100, .max = 100,
};

static void run(struct plant *pl, double force, double seconds)
{
	long steps = lround(seconds / DT);

	for (long i = 0; i < steps; i++) {
		plant_step(pl, force, DT);
	}
}

/* m v' = -b v: v = v0 e^(-bt/m), x = x0 + v0 m/b (1 - e^(-bt/m)). */
static void test_viscous_free_deceleration(void **state)
{
	struct plant pl;
	double m = free_axis.inertia, b = free_axis.viscous, v0 = 0.8;

	(void)state;
	plant_init(&pl, &free_axis, 0.1);
	pl.v = v0;
	for (int k = 1; k <= 5; k++) {
		double t = 0.3 * k;

		run(&pl, 0, 0.3);
		assert_float_equal(pl.v, v0 * exp(-b * t / m), 1e-9);
		assert_float_equal(pl.x, 0.1 + v0 * m / b * (1 - exp(-b * t / m)),
				   1e-9);
	}
}

/* A constant force from rest: v = F/b (1 - e^(-bt/m)), terminal F/b. */
static void test_constant_force(void **state)
{
	struct plant pl;
	double m = free_axis.inertia, b = free_axis.viscous, f = 3.0;
	double t = 1.7;

	(void)state;
	plant_init(&pl, &free_axis, 0);
	run(&pl, f, t);
	assert_float_equal(pl.v, f / b * (1 - exp(-b * t / m)), 1e-9);
	assert_float_equal(pl.x, f / b * t - f * m / (b * b) * (1 - exp(-b * t / m)),
			   1e-9);
	run(&pl, f, 20);
	assert_float_equal(pl.v, f / b, 1e-6);
}

/* Coulomb friction alone: uniform deceleration Fc/m, stopping distance
 * v0^2 m / (2 Fc), then it stays put. */
static void test_coulomb_stop(void **state)
{
	const struct plant_params p = {
		.inertia = 0.5, .coulomb = 0.4, .min = -10, .max = 10,
	};
	struct plant pl;
	double v0 = 0.6;

	(void)state;
	plant_init(&pl, &p, 0);
	pl.v = v0;
	run(&pl, 0, 0.5);
	assert_float_equal(pl.v, v0 - p.coulomb / p.inertia * 0.5, 1e-9);
	run(&pl, 0, 2.0);
	assert_true(pl.v == 0.0);
	assert_float_equal(pl.x, v0 * v0 * p.inertia / (2 * p.coulomb), 1e-9);
}

/* Coulomb with viscous: the stop happens exactly where the exponential
 * solution with net force -Fc reaches v = 0. */
static void test_coulomb_and_viscous_stop(void **state)
{
	const struct plant_params p = {
		.inertia = 0.5, .viscous = 2.0, .coulomb = 0.4,
		.min = -10, .max = 10,
	};
	struct plant pl;
	double v0 = 0.6, a = p.viscous / p.inertia, vinf = -p.coulomb / p.viscous;
	double t0 = -log(-vinf / (v0 - vinf)) / a;
	double x0 = vinf * t0 + (v0 - vinf) * (1 - exp(-a * t0)) / a;

	(void)state;
	plant_init(&pl, &p, 0);
	pl.v = v0;
	run(&pl, 0, 2.0);
	assert_true(pl.v == 0.0);
	assert_float_equal(pl.x, x0, 1e-9);
}

/* Static friction holds a force below it; above it the axis moves. */
static void test_stiction(void **state)
{
	const struct plant_params p = {
		.inertia = 0.5, .viscous = 1.0, .coulomb = 0.4,
		.min = -10, .max = 10,
	};
	struct plant pl;

	(void)state;
	plant_init(&pl, &p, 1.0);
	run(&pl, 0.39, 1.0);
	assert_true(pl.v == 0.0 && pl.x == 1.0);
	run(&pl, -0.39, 1.0);
	assert_true(pl.v == 0.0 && pl.x == 1.0);
	run(&pl, 0.5, 1.0);
	assert_true(pl.v > 0 && pl.x > 1.0);
	/* terminal velocity (F - Fc) / b */
	run(&pl, 0.5, 20.0);
	assert_float_equal(pl.v, 0.1, 1e-6);
}

/* Hard end stops: position clamped, velocity into the stop removed. */
static void test_end_stops(void **state)
{
	const struct plant_params p = {
		.inertia = 0.5, .viscous = 2.0, .min = 0.0, .max = 0.2,
	};
	struct plant pl;

	(void)state;
	plant_init(&pl, &p, -5);
	assert_true(pl.x == 0.0);
	run(&pl, 10, 2.0);
	assert_true(pl.x == 0.2 && pl.v == 0.0);
	run(&pl, -10, 0.001);
	assert_true(pl.x < 0.2 && pl.v < 0);
	run(&pl, -10, 2.0);
	assert_true(pl.x == 0.0 && pl.v == 0.0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_viscous_free_deceleration),
		cmocka_unit_test(test_constant_force),
		cmocka_unit_test(test_coulomb_stop),
		cmocka_unit_test(test_coulomb_and_viscous_stop),
		cmocka_unit_test(test_stiction),
		cmocka_unit_test(test_end_stops),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
