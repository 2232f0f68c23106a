/*
 * test_rod.c - the elastic rod against mechanics (rod.h): the cantilever's
 * tip deflection P L^3 / (3 EI) and, bent far, the elastica's; a
 * clamped rod rolled into a circle of radius EI / M by an end couple M,
 * a tube twisted at its surface held with the torques' sum, all the same
 * whatever the step (1 or 2 ms); Euler's buckling load pi^2 EI / (4 L^2)
 * of a clamped-free rod, the twist T L / GJ of a rod turned at its base
 * with its tip held, the capstan F_out / F_in = exp(mu theta) of a rod
 * pulled through a bend, a rest bend taken exactly, the anchor's reaction
 * equal to the load it holds, and a free rod that keeps still.
 *
 * Under the sanitizers (sanitized.h) the capstan's first case alone (a
 * quarter turn with friction); the others are the plain build's.
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
#include "sanitized.h"

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

/* Loads the rod for the next step with what ARG says. */
typedef void load_fn(struct rod *r, const void *arg);

/* A force F (N, double[3]) at the tip's end point. */
static void load_tip(struct rod *r, const void *f)
{
	int n = rod_segments(r);
	double d1[3], d2[3], d3[3], off[3];

	rod_frame(r, n - 1, d1, d2, d3);
	vec3_scale(off, d3, rod_segment_length(r) / 2);
	rod_load_point(rod_load(r, n - 1), off, f, NULL, NULL, NULL);
}

/* A couple M (N m, double[3]) on the tip's segment. */
static void load_couple(struct rod *r, const void *m)
{
	struct rod_load *l = rod_load(r, rod_segments(r) - 1);

	vec3_add(l->tau, l->tau, m);
}

/* Each segment twisted about its axis by a tangential force F (N,
 * double) at either side of its surface, as a wall's friction is put. */
static void load_twist(struct rod *r, const void *f)
{
	double radius = rod_params(r)->radius_m;

	for (int i = 0; i < rod_segments(r); i++) {
		double d1[3], d2[3], d3[3], off[3], push[3];

		rod_frame(r, i, d1, d2, d3);
		for (int side = -1; side <= 1; side += 2) {
			vec3_scale(off, d1, side * radius);
			vec3_scale(push, d2, side * *(const double *)f);
			rod_load_point(rod_load(r, i), off, push, NULL, NULL,
				       NULL);
		}
	}
}

/* Steps of DT_S with LOAD (may be NULL) until the rod has been at rest for
 * 0.5 s (or STEPS ran): an oscillation passes through rest at its turning
 * points. Returns the widest gap the joints had after a step. */
static double settle_at(struct rod *r, double dt_s, load_fn *load,
			const void *arg, int steps)
{
	int still = 0, rest = (int)lround(0.5 / dt_s);
	double gap = 0;

	for (int k = 0; k < steps && still < rest; k++) {
		rod_clear_loads(r);
		if (load) {
			load(r, arg);
		}
		rod_step(r, dt_s);
		gap = fmax(gap, rod_joint_gap(r));
		still = rod_kinetic_energy(r) < 1e-16 ? still + 1 : 0;
	}
	assert_true(rod_finite(r));
	return gap;
}

/* Steps with a tip force F (may be NULL) at DT, as settle_at(). */
static void settle(struct rod *r, const double f[3], int steps)
{
	settle_at(r, DT, f ? load_tip : NULL, f, steps);
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

/* The loop's steps: the settled shape must not depend on which. */
static const double steps_s[] = { 0.001, 0.002 };

/*
 * The elastica: a clamped rod under a dead tip load P normal to it, P L^2
 * / EI = 2, bends far: its tip deflects 0.49346 L and comes 0.16064 L
 * nearer the clamp (theta'' = -(P / EI) cos theta, theta(0) = 0,
 * theta'(L) = 0, integrated). Within 0.1 % at each of the loop's steps,
 * and the same shape at both: the light segment at the tip, turned by
 * the load, does not move its rest with the step. 100 segments: the
 * discretisation's error 1 / N^2 is 0.01 % of each.
 */
static void test_elastica(void **state)
{
	const double L = 0.3, EI = 0.03, P = 2 * EI / (L * L);
	const double deflection = 0.49346, shortening = 0.16064;
	const double f[3] = { 0, 0, -P };
	double tip[2][3];

	(void)state;
	for (int k = 0; k < 2; k++) {
		struct rod *r = straight_rod(100, L, EI, 0.45);

		clamp_at_origin(r, 0);
		settle_at(r, steps_s[k], load_tip, f, 20000);
		tip_point(r, tip[k]);
		print_message("elastica at %.0f ms: tip deflection %.6f L, "
			      "shortening %.6f L (%.5f, %.5f)\n",
			      steps_s[k] * 1e3, -tip[k][2] / L,
			      1 - tip[k][0] / L, deflection, shortening);
		assert_near(-tip[k][2] / L, deflection, 1e-3 * deflection);
		assert_near(1 - tip[k][0] / L, shortening, 1e-3 * shortening);
		rod_destroy(r);
	}
	assert_vec_near(tip[0], tip[1], 1e-6 * L);
}

/*
 * An end couple M rolls a clamped rod into a circular arc of radius R =
 * EI / M: here half a circle, its tip over the clamp at 2 R. A couple on
 * the tip's light segment alone, h^2 M / I far above a radian at either
 * step: its joints stay closed as it rolls up. The chain settles as a
 * polygon whose joints each hold (EI / l) sin(phi) = M: its ends within
 * (M l / EI)^2 R of the arc (1e-3 R at 100 segments).
 */
static void test_end_couple(void **state)
{
	const double L = 0.3, EI = 0.03, M = M_PI * EI / L, R = EI / M;
	const double centre[3] = { 0, 0, R }, top[3] = { 0, 0, 2 * R };
	const double couple[3] = { 0, -M, 0 }; /* rolls +x towards +z */
	const int n = 100;
	double tol = (M * L / n / EI) * (M * L / n / EI) * R;

	(void)state;
	for (int k = 0; k < 2; k++) {
		struct rod *r = straight_rod(n, L, EI, 0.45);
		double gap, off = 0, tip[3];

		clamp_at_origin(r, 0);
		gap = settle_at(r, steps_s[k], load_couple, couple, 20000);
		for (int i = 0; i < n; i++) {
			double e[3];

			rod_end_point(r, i, ROD_TIP, e);
			off = fmax(off, fabs(vec3_dist(e, centre) - R));
		}
		tip_point(r, tip);
		print_message("end couple at %.0f ms: the ends off the circle "
			      "%.2e R at most, the tip %.2e R off its top; "
			      "joints open %.1e m at most\n", steps_s[k] * 1e3,
			      off / R, vec3_dist(tip, top) / R, gap);
		assert_true(gap < 1e-6);
		assert_true(off < tol);
		assert_vec_near(tip, top, tol);
		rod_destroy(r);
	}
}

/*
 * The wall's friction twists the tube at its surface: 160 segments of
 * the scope, each turned by a couple T = 2 r F of tangential forces, are
 * held by the clamp with their sum N T (the roll the hand feels) at
 * either step; the twist up to the tip is the sum of T (N - 1 - j) l / GJ
 * over the joints j.
 */
static void test_twist_load(void **state)
{
	const double F = 0.5, L = 0.5, GJ = 0.45;
	const int n = 160;

	(void)state;
	for (int k = 0; k < 2; k++) {
		struct rod *r = straight_rod(n, L, 0.03, GJ);
		double t = 2 * rod_params(r)->radius_m * F, f[3], tau[3];
		double twist = 0, want = 0;

		clamp_at_origin(r, 0);
		settle_at(r, steps_s[k], load_twist, &F, 20000);
		rod_anchor_wrench(r, ROD_BASE, f, tau);
		for (int j = 0; j < n - 1; j++) {
			double th[3];

			rod_joint_rotation(r, j, th);
			twist += 2 * asin(th[2] / 2);
			want += t * (n - 1 - j) * (L / n) / GJ;
		}
		print_message("twist load at %.0f ms: the clamp holds %.6f N m "
			      "(N T %.6f N m); twisted %.6f rad (%.6f rad)\n",
			      steps_s[k] * 1e3, -tau[0], n * t, twist, want);
		assert_near(-tau[0], n * t, 1e-3 * n * t);
		assert_near(twist, want, 1e-3 * want);
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
	const size_t n = SANITIZED ? 1 : sizeof(cases) / sizeof(cases[0]);

	(void)state;
	for (size_t i = 0; i < n; i++) {
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
		cmocka_unit_test(test_elastica),
		cmocka_unit_test(test_end_couple),
		cmocka_unit_test(test_twist_load),
		cmocka_unit_test(test_torsion),
		cmocka_unit_test(test_euler_buckling),
		cmocka_unit_test(test_capstan),
	};

	sanitized_leaves("the capstan's first case alone; the others are the "
			 "plain build's");
	return cmocka_run_group_tests(tests, NULL, NULL);
}
