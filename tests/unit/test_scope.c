/*
 * test_scope.c - the endoscope's kinematics against the arc formulas: a
 * straight tube, 90 deg bends in both planes, the roll that swaps them, a
 * bending section only partly inserted, the Jacobian against finite
 * differences and against the rigid motion along a circle, the tube
 * polyline, the wheel limits, and a tube in a bowed colon.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "model/centreline.h"
#include "model/colon.h"
#include "geom_assert.h"
#include "model/scope.h"
#include "base/vec3.h"

#define STEP 0.002
#define LB 0.09

static const struct scope_params params = {
	.bending_length_m = LB, .ud_gain = 1, .lr_gain = 1,
	.ud_limit_rad = M_PI, .lr_limit_rad = 160 * M_PI / 180,
};

/* A straight centreline along z from the origin, 1 m, u along x. */
static struct centreline *straight_line(void)
{
	const double x[3] = { 1, 0, 0 };
	size_t n = 501;
	double (*p)[3] = malloc(n * sizeof(*p));
	char err[128];
	struct centreline *cl;

	for (size_t i = 0; i < n; i++) {
		vec3_set(p[i], 0, 0, (double)i * STEP);
	}
	cl = centreline_create((const double(*)[3])p, n, STEP, x, err,
			       sizeof(err));
	free(p);
	assert_non_null(cl);
	return cl;
}

/* A circle of radius R in the xy plane, from the origin along +x,
 * turning towards +y (its centre at (0, R, 0)). */
static struct centreline *circle(double r)
{
	const double z[3] = { 0, 0, 1 };
	size_t n = (size_t)(1.5 * M_PI * r / STEP) + 1;
	double (*p)[3] = malloc(n * sizeof(*p));
	char err[128];
	struct centreline *cl;

	for (size_t i = 0; i < n; i++) {
		double a = (double)i * STEP / r;

		vec3_set(p[i], r * sin(a), r * (1 - cos(a)), 0);
	}
	cl = centreline_create((const double(*)[3])p, n, STEP, z, err,
			       sizeof(err));
	free(p);
	assert_non_null(cl);
	return cl;
}

static void pose(const struct centreline *cl, double d, double roll,
		 double ud, double lr, struct scope_pose *out)
{
	const struct scope_input in = { d, roll, ud, lr };

	scope_update(&params, cl, &in, out);
}

static void test_straight_tip_is_centreline_point(void **state)
{
	struct centreline *cl = straight_line();
	struct scope_pose *p = malloc(sizeof(*p));
	const double want[3] = { 0, 0, 0.5 }, z[3] = { 0, 0, 1 };
	const double up[3] = { 0, 1, 0 }, o[3] = { 0, 0, 0 };

	(void)state;
	pose(cl, 0.5, M_PI / 2, 0, 0, p);
	assert_vec_near(p->tip, want, 1e-12);
	assert_vec_near(p->dir, z, 1e-12);
	/* the roll turned the camera's up from x to y */
	assert_vec_near(p->up, up, 1e-12);
	assert_near(p->tip_s_m, 0.5, STEP);
	assert_near(p->base_s_m, 0.5 - LB, 1e-9);
	/* the tube: anal verge to tip, evenly along */
	assert_vec_near(p->tube[0], o, 1e-12);
	assert_vec_near(p->tube[SCOPE_TUBE_POINTS - 1], want, 1e-12);
	assert_near(p->tube[64][2], 0.5 * 64 / (SCOPE_TUBE_POINTS - 1), 1e-9);
	free(p);
	centreline_destroy(cl);
}

/* A bend of TH over LB from P0 along T towards N: the arc formula. */
static void arc_tip(const double p0[3], const double t[3], const double n[3],
		    double th, double len, double out[3])
{
	vec3_axpy(out, p0, len / th * sin(th), t);
	vec3_axpy(out, out, len / th * (1 - cos(th)), n);
}

static void test_ninety_degree_bends_and_roll(void **state)
{
	struct centreline *cl = straight_line();
	struct scope_pose *p = malloc(sizeof(*p));
	const double p0[3] = { 0, 0, 0.4 - LB }, z[3] = { 0, 0, 1 };
	const double x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 };
	const double mx[3] = { -1, 0, 0 }, mz[3] = { 0, 0, -1 };
	double want[3];

	(void)state;
	/* up: towards u = x; the view turns to x, up turns to -z */
	pose(cl, 0.4, 0, M_PI / 2, 0, p);
	arc_tip(p0, z, x, M_PI / 2, LB, want);
	assert_vec_near(p->tip, want, 1e-12);
	assert_vec_near(p->dir, x, 1e-12);
	assert_vec_near(p->up, mz, 1e-12);
	/* right: towards v = z x x = y; up stays x */
	pose(cl, 0.4, 0, 0, M_PI / 2, p);
	arc_tip(p0, z, y, M_PI / 2, LB, want);
	assert_vec_near(p->tip, want, 1e-12);
	assert_vec_near(p->dir, y, 1e-12);
	assert_vec_near(p->up, x, 1e-12);
	/* a roll of 90 deg swaps the planes: up now bends towards y ... */
	pose(cl, 0.4, M_PI / 2, M_PI / 2, 0, p);
	arc_tip(p0, z, y, M_PI / 2, LB, want);
	assert_vec_near(p->tip, want, 1e-12);
	/* ... and right towards -x */
	pose(cl, 0.4, M_PI / 2, 0, M_PI / 2, p);
	arc_tip(p0, z, mx, M_PI / 2, LB, want);
	assert_vec_near(p->tip, want, 1e-12);
	/* both at once: one arc in the diagonal plane, angle sqrt(2) 90 deg */
	pose(cl, 0.4, 0, M_PI / 2, M_PI / 2, p);
	{
		double n[3] = { M_SQRT1_2, M_SQRT1_2, 0 };

		arc_tip(p0, z, n, M_SQRT2 * M_PI / 2, LB, want);
		assert_vec_near(p->tip, want, 1e-12);
	}
	assert_near(vec3_dot(p->up, p->dir), 0, 1e-12);
	assert_near(vec3_norm(p->up), 1, 1e-12);
	free(p);
	centreline_destroy(cl);
}

static void test_partly_inserted_bending_section(void **state)
{
	struct centreline *cl = straight_line();
	struct scope_pose *p = malloc(sizeof(*p));
	const double o[3] = { 0, 0, 0 }, z[3] = { 0, 0, 1 };
	const double x[3] = { 1, 0, 0 };
	double want[3], d = LB / 3;

	(void)state;
	/* a third inside: the inserted third bends a third of the angle */
	pose(cl, d, 0, M_PI / 2, 0, p);
	arc_tip(o, z, x, M_PI / 6, d, want);
	assert_vec_near(p->tip, want, 1e-12);
	assert_near(p->base_s_m, 0, 1e-12);
	/* nothing inside: the tip is at the anal verge, looking in */
	pose(cl, -0.1, 0, M_PI / 2, 0, p);
	assert_near(p->depth_m, 0, 0);
	assert_vec_near(p->tip, o, 1e-12);
	assert_vec_near(p->dir, z, 1e-12);
	/* past the end: the bending section leaves the end straight on, as
	 * far as its own length */
	pose(cl, 1.05, 0, 0, 0, p);
	assert_near(p->depth_m, 1.05, 1e-9);
	vec3_set(want, 0, 0, 1.05);
	assert_vec_near(p->tip, want, 1e-9);
	pose(cl, 5, 0, 0, 0, p);
	assert_near(p->depth_m, 1.0 + LB, 1e-9);
	free(p);
	centreline_destroy(cl);
}

static void test_wheel_gain_and_limits(void **state)
{
	struct scope_params q = params;
	double bend[2], db[2];

	(void)state;
	q.ud_gain = 2;
	q.lr_gain = 1.5;
	scope_bend(&q, 0.5, -0.5, bend, db);
	assert_near(bend[0], 1.0, 1e-15);
	assert_near(bend[1], -0.75, 1e-15);
	assert_near(db[0], 2, 0);
	assert_near(db[1], 1.5, 0);
	scope_bend(&q, 3, -3, bend, db);
	assert_near(bend[0], M_PI, 1e-15);
	assert_near(bend[1], -160 * M_PI / 180, 1e-15);
	assert_near(db[0], 0, 0);
	assert_near(db[1], 0, 0);
}

/* Columns 1..3 against central differences of the tip position. */
static void test_jacobian_matches_differences(void **state)
{
	struct centreline *cl = circle(0.2);
	struct scope_pose *p = malloc(sizeof(*p)), *q = malloc(sizeof(*q));
	const double in[][4] = {
		{ 0.4, 0.3, 0.7, -0.4 }, { 0.6, -1.2, 2.5, 0.2 },
		{ 0.05, 0.5, 1.0, 1.0 }, { 0.3, 2.0, 0, 0 },
		{ 0.5, 0.1, 1e-4, -2e-4 },
	};
	const double h = 1e-6;

	(void)state;
	for (size_t k = 0; k < sizeof(in) / sizeof(in[0]); k++) {
		pose(cl, in[k][0], in[k][1], in[k][2], in[k][3], p);
		for (int c = 1; c < 4; c++) {
			double x[4], lo[3], hi[3];

			memcpy(x, in[k], sizeof(x));
			x[c] -= h;
			pose(cl, x[0], x[1], x[2], x[3], q);
			vec3_copy(lo, q->tip);
			x[c] += 2 * h;
			pose(cl, x[0], x[1], x[2], x[3], q);
			vec3_copy(hi, q->tip);
			for (int d = 0; d < 3; d++) {
				assert_near(p->jacobian[d][c],
					    (hi[d] - lo[d]) / (2 * h), 1e-7);
			}
		}
	}
	free(p);
	free(q);
	centreline_destroy(cl);
}

/*
 * Along a circle of radius R the bending section moves rigidly: its base
 * advances along t at unit speed while turning at 1/R about the circle's
 * axis z, so d tip / d d = t0 + (z / R) x (tip - base).
 */
static void test_insertion_column_is_rigid_motion(void **state)
{
	const double r = 0.2, z[3] = { 0, 0, 1 };
	struct centreline *cl = circle(r);
	struct scope_pose *p = malloc(sizeof(*p));
	const double in[][4] = { { 0.4, 0.3, 0.7, -0.4 },
				 { 0.6, -1.2, 2.5, 0.2 },
				 { 0.3, 2.0, 0, 0 } };

	(void)state;
	for (size_t k = 0; k < sizeof(in) / sizeof(in[0]); k++) {
		struct centreline_point base;
		double rel[3], w[3], want[3];

		pose(cl, in[k][0], in[k][1], in[k][2], in[k][3], p);
		centreline_at_s(cl, p->base_s_m, &base);
		vec3_sub(rel, p->tip, base.p);
		vec3_scale(w, z, 1 / r);
		vec3_cross(want, w, rel);
		vec3_add(want, want, base.t);
		for (int d = 0; d < 3; d++) {
			/* the stated error: sampled circle, h = step */
			assert_near(p->jacobian[d][0], want[d], 0.005);
		}
	}
	free(p);
	centreline_destroy(cl);
}

/* The sample nearest P, by brute force: what tip_s_m must be. */
static double nearest_sample_s(const struct centreline *cl, const double p[3])
{
	size_t best = 0;

	for (size_t i = 1; i < centreline_count(cl); i++) {
		if (vec3_dist(centreline_sample(cl, i)->p, p) <
		    vec3_dist(centreline_sample(cl, best)->p, p)) {
			best = i;
		}
	}
	return (double)best * centreline_step(cl);
}

/* In a bowed colon the tube follows the bow: pushing the same depth gets
 * the bending section less far along the colon (the loop). */
static void test_tube_follows_bowed_colon(void **state)
{
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct scope_pose *p = malloc(sizeof(*p));
	struct anatomy a;
	struct colon *c;
	struct centreline *cl;
	struct centreline_point base;
	char err[256], path[512];
	double base_straight, s0, s1, d, want[3];
	const char *dir = getenv("ENDOSIM_CASES");

	(void)state;
	snprintf(path, sizeof(path), "%s/normal.case",
		 dir && *dir ? dir : "config/cases");
	assert_int_equal(anatomy_load(&a, path, err, sizeof(err)), 0);
	cp.ring_vertices = 16;
	c = colon_create(&a, &cp, err, sizeof(err));
	assert_non_null(c);
	cl = colon_centreline(c);
	centreline_span_range(cl, 0, &s0, &s1);
	d = s1 + 0.05;
	pose(cl, d, 0, 0, 0, p);
	base_straight = p->base_s_m;
	assert_near(base_straight, d - LB, STEP);
	assert_near(p->tip_s_m, nearest_sample_s(cl, p->tip), 1e-12);
	assert_int_equal(colon_bow(c, 0, 0.06, false), 0);
	pose(cl, d, 0, 0, 0, p);
	assert_true(p->base_s_m < base_straight - 0.01);
	/* the unbent bending section runs straight on from the bowed
	 * centreline at arc length d - Lb */
	centreline_at_length(cl, d - LB, &base, NULL);
	vec3_axpy(want, base.p, LB, base.t);
	assert_vec_near(p->tip, want, 1e-9);
	assert_near(p->tip_s_m, nearest_sample_s(cl, p->tip), 1e-12);
	/* and the tube up to there runs along the bowed sigmoid */
	for (int i = 0; i < SCOPE_TUBE_POINTS; i++) {
		struct centreline_point on;
		double along = p->depth_m * i / (SCOPE_TUBE_POINTS - 1);

		if (along > d - LB) {
			break;
		}
		centreline_at_length(cl, along, &on, NULL);
		assert_vec_near(p->tube[i], on.p, 1e-9);
	}
	free(p);
	colon_destroy(c);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_straight_tip_is_centreline_point),
		cmocka_unit_test(test_ninety_degree_bends_and_roll),
		cmocka_unit_test(test_partly_inserted_bending_section),
		cmocka_unit_test(test_wheel_gain_and_limits),
		cmocka_unit_test(test_jacobian_matches_differences),
		cmocka_unit_test(test_insertion_column_is_rigid_motion),
		cmocka_unit_test(test_tube_follows_bowed_colon),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
