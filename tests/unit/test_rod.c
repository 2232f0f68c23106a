/*
 * test_rod.c - the elastic rod against mechanics (rod.h): the cantilever's
 * tip deflection P L^3 / (3 EI), Euler's buckling load pi^2 EI / (4 L^2)
 * of a clamped-free rod, the twist T L / GJ of a rod turned at its base
 * with its tip held, the capstan F_out / F_in = exp(mu theta) of a rod
 * pulled through a bend, a rest bend taken exactly, the anchor's reaction
 * equal to the load it holds, and a free rod that keeps still.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "geom_assert.h"
#include "model/rod.h"
#include "base/vec3.h"

#define DT 0.001

/* A rod of N segments along +x from the origin, d1 along +z. */
static struct rod *straight_rod(int n, double length, double ei, double gj)
{
	struct rod_params p = ROD_PARAMS_DEFAULT;
	double (*ends)[3] = calloc((size_t)n + 1, sizeof(*ends));
	const double up[3] = { 0, 0, 1 };
	struct rod *r;

	p.segments = n;
	p.length_m = length;
	p.bending_n_m2 = ei;
	p.torsion_n_m2 = gj;
	p.damping_s = 0.01;
	p.drag_n_s_per_m2 = 2;
	r = rod_create(&p);
	assert_non_null(r);
	for (int i = 0; i <= n; i++) {
		vec3_set(ends[i], length * i / n, 0, 0);
	}
	rod_lay(r, (const double(*)[3])ends, up);
	free(ends);
	return r;
}

/* The anchor frame at the origin with e3 along +x, e1 along +z. */
static void clamp_at_origin(struct rod *r, double angle_about_x)
{
	struct rod_anchor a = { .p = { 0, 0, 0 } };
	/* e3 -> x, e1 -> z, e2 -> -y: the rotation (x, y, z) <- (z, -y, x)
	 * is 180 deg about (1, 0, 1)/sqrt2; then turned about x */
	double base[4] = { 0, M_SQRT1_2, 0, M_SQRT1_2 };
	double turn[4] = { cos(angle_about_x / 2), sin(angle_about_x / 2), 0,
			   0 };

	a.q[0] = turn[0] * base[0] - turn[1] * base[1];
	a.q[1] = turn[0] * base[1] + turn[1] * base[0];
	a.q[2] = turn[0] * base[2] - turn[1] * base[3];
	a.q[3] = turn[0] * base[3] + turn[1] * base[2];
	rod_clamp_compliance(r, a.compliance);
	rod_set_anchor(r, ROD_BASE, &a);
}

/* A force F at the tip's end point, for the next step. */
static void load_tip(struct rod *r, const double f[3])
{
	int n = rod_segments(r);
	double d1[3], d2[3], d3[3], off[3];

	rod_frame(r, n - 1, d1, d2, d3);
	vec3_scale(off, d3, rod_segment_length(r) / 2);
	rod_load_point(rod_load(r, n - 1), off, f, NULL, NULL, NULL);
}

/* Steps with a tip force F until the rod has been at rest for 0.5 s (or
 * STEPS ran): an oscillation passes through rest at its turning points. */
static void settle(struct rod *r, const double f[3], int steps)
{
	int still = 0;

	for (int k = 0; k < steps && still < 500; k++) {
		rod_clear_loads(r);
		if (f) {
			load_tip(r, f);
		}
		rod_step(r, DT);
		still = rod_kinetic_energy(r) < 1e-16 ? still + 1 : 0;
	}
	assert_true(rod_finite(r));
}

static void tip_point(const struct rod *r, double out[3])
{
	rod_end_point(r, rod_segments(r) - 1, ROD_TIP, out);
}

/* Cantilever: delta = P L^3 / (3 EI) within 2 % (the discretisation's
 * error is 1 / (2 N^2)) in both bending planes; the clamp holds the load
 * and its moment. */
static void test_cantilever(void **state)
{
	const double L = 0.3, EI = 0.03, P = 0.01;
	double want = P * L * L * L / (3 * EI);

	(void)state;
	for (int plane = 0; plane < 2; plane++) {
		struct rod *r = straight_rod(20, L, EI, 0.45);
		double f[3] = { 0, plane ? -P : 0, plane ? 0 : -P };
		double tip[3], rf[3], rt[3], moment[3];

		clamp_at_origin(r, 0);
		settle(r, f, 20000);
		tip_point(r, tip);
		print_message("cantilever: deflection %.6f mm, P L^3/3EI "
			      "%.6f mm\n", -tip[2 - plane] * 1e3, want * 1e3);
		assert_near(-tip[2 - plane], want, 0.02 * want);
		/* the tube neither stretches nor shears: its joints closed */
		assert_true(rod_joint_gap(r) < 1e-6);
		/* the clamp's reaction: the force, and its moment P L */
		rod_anchor_wrench(r, ROD_BASE, rf, rt);
		vec3_set(moment, 0, plane ? 0 : -P * L, plane ? P * L : 0);
		assert_near(rf[2 - plane], P, 1e-3 * P);
		assert_vec_near(rt, moment, 0.01 * P * L);
		rod_destroy(r);
	}
}

/* The tip's largest excursion from the axis after a nudge, under a
 * compressive tip load of FACTOR times Euler's. */
static double buckled(double factor)
{
	const double L = 0.2, EI = 0.03;
	double pcr = M_PI * M_PI * EI / (4 * L * L), tip[3];
	struct rod *r = straight_rod(20, L, EI, 0.45);
	double push[3] = { -factor * pcr, 0, 0 };
	double nudge[3] = { -factor * pcr, 0, 1e-3 * pcr };

	clamp_at_origin(r, 0);
	settle(r, nudge, 200);
	settle(r, push, 30000);
	tip_point(r, tip);
	rod_destroy(r);
	return hypot(tip[1], tip[2]) / L;
}

/* Euler: a clamped-free rod stands at 0.95 P_cr and buckles at 1.05. */
static void test_euler_buckling(void **state)
{
	double below = buckled(0.95), above = buckled(1.05);

	(void)state;
	print_message("buckling: tip off axis %.2e L at 0.95 P_cr, %.3f L "
		      "at 1.05 P_cr\n", below, above);
	assert_true(below < 1e-3);
	assert_true(above > 0.1);
}

/* Torsion: the base turned by phi, the tip held: phi = T L / GJ. */
static void test_torsion(void **state)
{
	const double L = 0.5, GJ = 0.45, phi = 0.2;
	struct rod *r = straight_rod(25, L, 0.03, GJ);
	struct rod_anchor tip = { .p = { L, 0, 0 } };
	double f[3], t[3];

	(void)state;
	/* the tip's frame as laid: the rod's own last frame */
	memcpy(tip.q, rod_quat(r, 24), sizeof(tip.q));
	rod_clamp_compliance(r, tip.compliance);
	rod_set_anchor(r, ROD_TIP, &tip);
	clamp_at_origin(r, phi);
	settle(r, NULL, 20000);
	rod_anchor_wrench(r, ROD_BASE, f, t);
	print_message("torsion: torque %.6f N m, GJ phi / L %.6f N m\n",
		      -t[0], GJ * phi / L);
	/* the base's anchor turns the rod by phi about +x: it holds -T */
	assert_near(fabs(t[0]), GJ * phi / L, 0.01 * GJ * phi / L);
	assert_true(t[0] * phi > 0);
	rod_destroy(r);
}

/* ------------------------------------------------------------- capstan */

/* A channel: along -x to the origin, an arc of radius R turning towards
 * +y by THETA, then straight on. The point of the channel's centreline
 * nearest X, and its tangent. */
struct channel {
	double radius, theta;
};

static void channel_nearest(const struct channel *c, const double x[3],
			    double p[3], double t[3])
{
	double ang = atan2(x[0], c->radius - x[1]);

	if (ang < -M_PI / 2) {
		ang += 2 * M_PI; /* past half a turn */
	}
	if (ang <= 0) {
		vec3_set(p, x[0] < 0 ? x[0] : 0, 0, 0);
		vec3_set(t, 1, 0, 0);
	} else if (ang >= c->theta) {
		double e[3] = { c->radius * sin(c->theta),
				c->radius * (1 - cos(c->theta)), 0 };
		double d[3];

		vec3_set(t, cos(c->theta), sin(c->theta), 0);
		vec3_sub(d, x, e);
		vec3_axpy(p, e, vec3_dot(d, t), t);
	} else {
		vec3_set(p, c->radius * sin(ang), c->radius * (1 - cos(ang)), 0);
		vec3_set(t, cos(ang), sin(ang), 0);
	}
}

/*
 * Each segment against the channel's wall (clearance CLEAR around its
 * centreline): a spring K_WALL on the penetration and regularised Coulomb
 * friction MU, both implicit.
 */
static void load_channel(struct rod *r, const struct channel *c, double mu,
			 double clear)
{
	const double k_wall = 2e4, v_reg = 1e-3;

	for (int i = 0; i < rod_segments(r); i++) {
		const double *x = rod_centre(r, i), *v = rod_velocity(r, i);
		double p[3], t[3], d[3], n[3], k[3][3], b[3][3], vt[3];
		double along, depth, fn, slip, cf;

		channel_nearest(c, x, p, t);
		vec3_sub(d, x, p);
		along = vec3_dot(d, t);
		vec3_axpy(d, d, -along, t);
		depth = vec3_norm(d) - clear;
		if (depth <= 0) {
			continue;
		}
		vec3_scale(n, d, -1 / vec3_norm(d)); /* into the channel */
		fn = k_wall * depth;
		vec3_axpy(vt, v, -vec3_dot(v, n), n);
		slip = vec3_norm(vt);
		cf = mu * fn / fmax(slip, v_reg);
		for (int a = 0; a < 3; a++) {
			for (int e = 0; e < 3; e++) {
				k[a][e] = k_wall * n[a] * n[e];
				b[a][e] = cf * ((a == e) - n[a] * n[e]);
			}
		}
		vec3_scale(n, n, fn);
		rod_load_point(rod_load(r, i), (double[3]){ 0, 0, 0 }, n,
			       (const double(*)[3])k, (const double(*)[3])b,
			       NULL);
	}
}

/* Pulls a soft rod through a bend of THETA with friction MU against a
 * back tension F_IN; returns the pull at the far end over F_IN. */
static double capstan_ratio(double theta, double mu, double f_in)
{
	const double R = 0.1, L = 0.8, V = 0.05;
	struct channel c = { R, theta };
	struct rod_params p = ROD_PARAMS_DEFAULT;
	struct rod_anchor pull = { .compliance = { 1e-4, 1e-4, 1e-4, 1, 1, 1 },
				   .damping_s = { 0.002, 0.002, 0.002 } };
	double ends[81][3], t_out[3], f[3], tau[3], sum = 0;
	const double up[3] = { 0, 0, 1 };
	int n = 80, samples = 0;
	struct rod *r;

	p.segments = n;
	p.length_m = L;
	p.bending_n_m2 = 1e-4;
	p.torsion_n_m2 = 1e-3;
	p.drag_n_s_per_m2 = 0;
	r = rod_create(&p);
	assert_non_null(r);
	/* laid along the channel, from 0.4 m before the bend */
	for (int i = 0; i <= n; i++) {
		double s = -0.4 + L * i / n, t[3];

		if (s <= 0) {
			vec3_set(ends[i], s, 0, 0);
		} else if (s <= R * theta) {
			vec3_set(ends[i], R * sin(s / R), R * (1 - cos(s / R)),
				 0);
		} else {
			double e = s - R * theta;

			vec3_set(t, cos(theta), sin(theta), 0);
			vec3_set(ends[i], R * sin(theta) + e * t[0],
				 R * (1 - cos(theta)) + e * t[1], 0);
		}
	}
	rod_lay(r, (const double(*)[3])ends, up);
	vec3_set(t_out, cos(theta), sin(theta), 0);
	memcpy(pull.q, rod_quat(r, n - 1), sizeof(pull.q));
	for (int k = 0; k < 4000; k++) {
		double back[3], d1[3], d2[3], d3[3], off[3];

		/* the far end's anchor moves out at V, the near end is
		 * held back by F_IN */
		vec3_axpy(pull.p, ends[n], V * DT * (k + 1), t_out);
		rod_set_anchor(r, ROD_TIP, &pull);
		rod_clear_loads(r);
		load_channel(r, &c, mu, 0.002);
		rod_frame(r, 0, d1, d2, d3);
		vec3_scale(off, d3, -rod_segment_length(r) / 2);
		vec3_set(back, -f_in, 0, 0);
		rod_load_point(rod_load(r, 0), off, back, NULL, NULL, NULL);
		rod_step(r, DT);
		if (k >= 3000) {
			rod_anchor_wrench(r, ROD_TIP, f, tau);
			sum += vec3_dot(f, t_out);
			samples++;
		}
	}
	assert_true(rod_finite(r));
	rod_destroy(r);
	return sum / samples / f_in;
}

/* Capstan: F_out / F_in = exp(mu theta) within 5 %, and no friction,
 * no gain. */
static void test_capstan(void **state)
{
	const double cases[][2] = { { M_PI / 2, 0.3 }, { M_PI, 0.2 },
				    { M_PI / 2, 0 } };

	(void)state;
	for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		double th = cases[i][0], mu = cases[i][1];
		double got = capstan_ratio(th, mu, 5.0);
		double want = exp(mu * th);

		print_message("capstan: theta %.2f rad, mu %.2f: F_out/F_in "
			      "%.4f, exp(mu theta) %.4f\n", th, mu, got, want);
		assert_near(got, want, 0.05 * want);
	}
}

/* A rest bend: a free rod with a rest rotation at one joint takes it,
 * with no moment left. */
static void test_rest_bend(void **state)
{
	struct rod *r = straight_rod(10, 0.1, 0.03, 0.45);
	const double axis[3] = { 0, 1, 0 };
	double th0[3], th[3], m[3];

	(void)state;
	rod_rest_for_angle(M_PI / 2, axis, th0);
	rod_set_rest(r, 4, th0);
	settle(r, NULL, 20000);
	rod_joint_rotation(r, 4, th);
	rod_joint_moment(r, 4, m);
	assert_vec_near(th, th0, 1e-6);
	assert_near(vec3_norm(m), 0, 1e-9);
	rod_destroy(r);
}

/* A free rod at rest stays at rest, and its energy never grows. */
static void test_still(void **state)
{
	struct rod *r = straight_rod(30, 0.5, 0.03, 0.45);
	double before[3], after[3];

	(void)state;
	memcpy(before, rod_centre(r, 29), sizeof(before));
	settle(r, NULL, 500);
	memcpy(after, rod_centre(r, 29), sizeof(after));
	assert_vec_near(after, before, 1e-9);
	rod_destroy(r);
}

static void test_params(void **state)
{
	struct rod_params p = ROD_PARAMS_DEFAULT;
	char err[128];

	(void)state;
	assert_int_equal(rod_params_check(&p, err, sizeof(err)), 0);
	p.segments = 1;
	assert_int_equal(rod_params_check(&p, err, sizeof(err)), -EINVAL);
	assert_null(rod_create(&p));
	p = (struct rod_params)ROD_PARAMS_DEFAULT;
	p.bending_n_m2 = NAN;
	assert_int_equal(rod_params_check(&p, err, sizeof(err)), -EINVAL);
	rod_destroy(NULL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_params),
		cmocka_unit_test(test_still),
		cmocka_unit_test(test_rest_bend),
		cmocka_unit_test(test_cantilever),
		cmocka_unit_test(test_torsion),
		cmocka_unit_test(test_euler_buckling),
		cmocka_unit_test(test_capstan),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
