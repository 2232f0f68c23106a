/*
 * test_shapes.c - the line that marks a tube's roll (viewer/shapes.h,
 * shapes_stripe()): on a straight tube it stands where the roll turns it
 * about the axis; round a planar bend its frame is carried without twist
 * (a line started on the bend's inside stays on the inside, one started
 * normal to the plane stays normal to it); a first direction along the
 * tube is made normal to it.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "viewer/shapes.h"

#define N 91
#define OFFSET 0.0065f
#define TOL 1e-6
#define STEP_RAD (M_PI / 2 / (N - 1)) /* round the quarter circle */

static float p[N][3], roll[N], out[N][3];

/*
 * OUT[I] - P[I] against OFFSET times D; at either end, where the tangent
 * is the chord to the next point, within the angle of half a step of the
 * quarter circle.
 */
static void assert_at(int i, double dx, double dy, double dz)
{
	double d[3] = { dx, dy, dz };
	double tol = i > 0 && i < N - 1 ? TOL : OFFSET * STEP_RAD / 2 + TOL;

	for (int k = 0; k < 3; k++) {
		assert_true(fabs(out[i][k] - p[i][k] - OFFSET * d[k]) < tol);
	}
}

/* Along z, u0 = x: the line at the angle of each point's roll from x
 * towards y (t x u = z x x = y). */
static void straight(void **state)
{
	static const double u0[3] = { 1, 0, 0 };

	(void)state;
	for (int i = 0; i < N; i++) {
		p[i][0] = p[i][1] = 0;
		p[i][2] = 0.01f * (float)i;
		roll[i] = (float)(M_PI * i / (N - 1)); /* half a turn held */
	}
	shapes_stripe((const float(*)[3])p, roll, N, u0, OFFSET, out);
	for (int i = 0; i < N; i++) {
		assert_at(i, cos(roll[i]), sin(roll[i]), 0);
	}
	assert_at(N / 2, 0, 1, 0);
	assert_at(N - 1, -1, 0, 0);
}

/* A quarter circle of radius R in the xz plane, centre at x = R: no roll. */
static void quarter(void)
{
	const double r = 0.2;

	for (int i = 0; i < N; i++) {
		double a = M_PI / 2 * i / (N - 1);

		p[i][0] = (float)(r - r * cos(a));
		p[i][1] = 0;
		p[i][2] = (float)(r * sin(a));
		roll[i] = 0;
	}
}

/* Started towards the bend's centre, it stays on the inside all round;
 * started normal to the plane, it stays so. */
static void planar_bend(void **state)
{
	static const double inside[3] = { 1, 0, 0 }, normal[3] = { 0, 1, 0 };

	(void)state;
	quarter();
	shapes_stripe((const float(*)[3])p, roll, N, inside, OFFSET, out);
	for (int i = 0; i < N; i++) {
		double a = M_PI / 2 * i / (N - 1);

		assert_at(i, cos(a), 0, -sin(a));
	}
	shapes_stripe((const float(*)[3])p, roll, N, normal, OFFSET, out);
	for (int i = 0; i < N; i++) {
		assert_at(i, 0, 1, 0);
	}
}

/* u0 partly along the tube: only its part normal to the tube counts. */
static void made_normal(void **state)
{
	static const double slanted[3] = { 0.6, 0, 0.8 };

	(void)state;
	quarter();
	shapes_stripe((const float(*)[3])p, roll, N, slanted, OFFSET, out);
	assert_at(0, 1, 0, 0);
	assert_at(N - 1, 0, 0, -1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(straight),
		cmocka_unit_test(planar_bend),
		cmocka_unit_test(made_normal),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
