/*
 * test_lumen.c - the insertion tube against the lumen (lumen.h):
 *  - a rod on the centreline of a straight colon touches nothing; moved
 *    sideways by more than the free radius it is pushed back with
 *    k_wall l delta per segment, towards the centreline;
 *  - outside the anal verge the pipe holds it on the colon's first
 *    tangent, produced backwards;
 *  - the capstan through the colon: a soft rod pulled through a bend of
 *    90 deg (the sigmoid's, 10 cm radius) against a back tension needs
 *    F_out / F_in = exp(mu theta) (5 %), and without friction 1;
 *  - action = reaction: what the wall pushes on the tube, the mobile colon
 *    takes (the forces pushed onto the flex are the contacts' forces).
 *
 * Under the sanitizers (sanitized.h) the capstan with the first friction
 * alone; the others are the plain build's.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "model/anatomy.h"
#include "model/colon.h"
#include "model/flex.h"
#include "geom_assert.h"
#include "plain_anatomy.h"
#include "model/lumen.h"
#include "model/rod.h"
#include "base/vec3.h"
#include "sanitized.h"

#define DT 0.001

/* A round colon, WIDTH m wide, no folds; the sigmoid bends by BEND_DEG on
 * a radius of 10 cm (0 for a straight colon), mobile when MOBILE. */
static struct colon *smooth_colon(double width, double bend_deg, bool mobile)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	struct anatomy a;
	struct colon *c;
	char err[256];

	plain_anatomy(&a, width);
	if (bend_deg > 0) {
		a.seg[2].bend[0] = (struct anatomy_bend){
			.angle_rad = bend_deg * M_PI / 180, .radius_m = 0.1,
		};
		a.seg[2].bends = 1;
	}
	plain_mobile_sigmoid(&a, 600, 0.06);
	a.seg[2].mobile = mobile;
	p.ring_vertices = 64;
	c = colon_create(&a, &p, err, sizeof(err));
	assert_non_null(c);
	return c;
}

/* A rod of N segments of L m laid along COLON's centreline from material
 * S0 (negative: that much in the pipe). */
static struct rod *rod_along(const struct colon *c, int n, double len,
			     double s0, double ei)
{
	const struct centreline *cl = colon_centreline(c);
	const struct centreline_point *c0 = centreline_sample(cl, 0);
	struct rod_params p = ROD_PARAMS_DEFAULT;
	double (*ends)[3] = calloc((size_t)n + 1, sizeof(*ends));
	struct rod *r;

	p.segments = n;
	p.length_m = len;
	p.bending_n_m2 = ei;
	p.torsion_n_m2 = 10 * ei;
	p.drag_n_s_per_m2 = 0;
	r = rod_create(&p);
	assert_non_null(r);
	for (int i = 0; i <= n; i++) {
		double s = s0 + len * i / n;

		if (s < 0) {
			vec3_axpy(ends[i], c0->p, s, c0->t);
		} else {
			centreline_position_at_length(cl, s, ends[i], NULL);
		}
	}
	rod_lay(r, (const double(*)[3])ends, c0->u);
	free(ends);
	return r;
}

static struct lumen *lumen_for(const struct rod *r, double s0)
{
	int n = rod_segments(r);
	double l = rod_segment_length(r), *sigma = calloc((size_t)n,
							  sizeof(*sigma));
	struct lumen *lu = lumen_create(n);

	assert_non_null(lu);
	for (int i = 0; i < n; i++) {
		sigma[i] = s0 + (i + 0.5) * l;
	}
	lumen_reset(lu, sigma);
	free(sigma);
	return lu;
}

/* On the centreline: free; pushed aside: the wall's spring; the pipe. */
static void test_wall_and_pipe(void **state)
{
	const struct lumen_params p = LUMEN_PARAMS_DEFAULT;
	struct colon *c = smooth_colon(0.05, 0, false);
	struct rod *r = rod_along(c, 40, 0.4, -0.1, 0.03);
	struct lumen *lu = lumen_for(r, -0.1);
	struct lumen_totals t;
	double free_r, delta = 0.004;
	const double *u = centreline_sample(colon_centreline(c), 0)->u;
	double ends[41][3];

	(void)state;
	rod_clear_loads(r);
	lumen_load(lu, r, c, NULL, &p);
	rod_step(r, DT);
	lumen_react(lu, r, NULL, &t);
	assert_int_equal(t.contacts, 0);
	assert_near(t.wall_n, 0, 1e-12);
	/* the inside moved aside by the free radius and DELTA, the pipe's
	 * part by 1 cm */
	free_r = colon_tube_radius(c, 100) - p.tube_radius_m;
	for (int i = 0; i <= 40; i++) {
		double s = -0.1 + 0.01 * i, off = s < 0 ? 0.01 : free_r + delta;

		vec3_set(ends[i], 0, 0, 0);
		ends[i][2] = 0;
		centreline_position_at_length(colon_centreline(c), fmax(s, 0),
					      ends[i], NULL);
		if (s < 0) {
			vec3_axpy(ends[i], ends[i], s,
				  centreline_sample(colon_centreline(c), 0)->t);
		}
		vec3_axpy(ends[i], ends[i], off, u);
	}
	rod_lay(r, (const double(*)[3])ends, u);
	rod_clear_loads(r);
	lumen_load(lu, r, c, NULL, &p);
	/* the loads before the step: a segment well inside is pushed back
	 * along -u by k_wall l delta; one in the pipe towards its axis */
	{
		struct rod_load *in = rod_load(r, 25), *out = rod_load(r, 3);
		double k = p.wall_n_per_m2 * 0.01;

		assert_near(vec3_dot(in->f, u), -k * delta, 0.05 * k * delta);
		assert_true(vec3_dot(out->f, u) < 0);
	}
	rod_step(r, DT);
	lumen_react(lu, r, NULL, &t);
	/* every inside segment but the tip's (the god-object's) and those
	 * within the narrower anal canal's reach */
	assert_true(t.contacts >= 25 && t.contacts <= 30);
	for (int k = 0; k < 300; k++) {
		rod_clear_loads(r);
		lumen_load(lu, r, c, NULL, &p);
		rod_step(r, DT);
	}
	/* back within the lumen, the pipe's part on its axis */
	{
		const double *x = rod_centre(r, 3), *c0 = centreline_sample(
			colon_centreline(c), 0)->p;
		double d[3], t0[3];

		memcpy(t0, centreline_sample(colon_centreline(c), 0)->t,
		       sizeof(t0));
		vec3_sub(d, x, c0);
		vec3_axpy(d, d, -vec3_dot(d, t0), t0);
		assert_true(vec3_norm(d) < LUMEN_PIPE_CLEARANCE_M + 1e-3);
		assert_true(lumen_sample(lu, 3) == -1);
		assert_true(lumen_sample(lu, 25) > 0);
	}
	lumen_destroy(lu);
	rod_destroy(r);
	colon_destroy(c);
}

/*
 * Pulls a soft rod through the 90 deg bend at V against F_IN, friction
 * MU; returns F_out / F_in once steady (with MOBILE, the tube holds still
 * against F_IN, for the colon to come to rest). The lumen is narrow (2 cm, 3.5 mm
 * of play around the tube): a rope on a drum, as the capstan's law has it
 * (in a wide lumen a rod this soft buckles behind a stick). MOBILE: the
 * sigmoid moves; *PUSHED gets its largest displacement, *HELD the wall's
 * mean force on the rod.
 */
struct mobile_bend {
	double moved;      /* the sigmoid's largest displacement, m */
	double pushed[3];  /* what the tube pushed on it, N */
	double held[3];    /* what its mesentery holds, N */
	double inward;     /* the push along the exit less along the entry */
};

static double capstan(double mu, bool mobile, double *held,
		      struct mobile_bend *mb)
{
	struct lumen_params p = LUMEN_PARAMS_DEFAULT;
	const struct flex_params fp = FLEX_PARAMS_DEFAULT;
	struct colon *c = smooth_colon(0.02, 90, mobile);
	struct rod *r = rod_along(c, 70, 0.7, 0.05, 1e-3);
	struct lumen *lu = lumen_for(r, 0.05);
	struct flex *fx = mobile ? flex_create(&fp) : NULL;
	const struct centreline *cl = colon_centreline(c);
	struct rod_anchor pull = { .compliance = { 1e-4, 1e-4, 1e-4, 1, 1, 1 },
				   .damping_s = { 0.002, 0.002, 0.002 } };
	struct centreline_point out;
	double start[3], sum = 0, f_in = 10, v = mobile ? 0 : 0.05;
	int samples = 0;

	p.friction = mu;
	if (fx) {
		flex_attach(fx, c);
	}
	centreline_at_length(cl, 0.75, &out, NULL);
	rod_end_point(r, 69, ROD_TIP, start);
	memcpy(pull.q, rod_quat(r, 69), sizeof(pull.q));
	*held = 0;
	for (int k = 0; k < 3000; k++) {
		double back[3], off[3], d1[3], d2[3], d3[3], f[3], tau[3];
		struct lumen_totals t;

		vec3_axpy(pull.p, start, v * DT * (k + 1), out.t);
		rod_set_anchor(r, ROD_TIP, &pull);
		rod_clear_loads(r);
		lumen_load(lu, r, c, fx, &p);
		rod_frame(r, 0, d1, d2, d3);
		vec3_scale(off, d3, -rod_segment_length(r) / 2);
		/* the back tension rises over the first second */
		vec3_scale(back, d3, -f_in * fmin(1, k * DT));
		rod_load_point(rod_load(r, 0), off, back, NULL, NULL, NULL);
		rod_step(r, DT);
		if (fx) {
			flex_clear(fx);
		}
		lumen_react(lu, r, fx, &t);
		if (fx) {
			flex_step(fx, DT);
		}
		if (k >= 2000) {
			rod_anchor_wrench(r, ROD_TIP, f, tau);
			sum += vec3_dot(f, out.t);
			samples++;
			*held += t.wall_n;
			if (fx) { /* the colon's forces, averaged likewise */
				double pu[3], he[3];

				flex_span_forces(fx, 0, pu, he);
				vec3_add(mb->pushed, mb->pushed, pu);
				vec3_add(mb->held, mb->held, he);
			}
		}
	}
	if (fx) {
		mb->moved = flex_span_displacement(fx, 0);
		vec3_scale(mb->pushed, mb->pushed, 1.0 / samples);
		vec3_scale(mb->held, mb->held, 1.0 / samples);
		mb->inward = vec3_dot(mb->pushed, out.t) -
			     vec3_dot(mb->pushed, centreline_sample(cl, 50)->t);
	}
	*held /= samples;
	assert_true(rod_finite(r));
	flex_destroy(fx);
	lumen_destroy(lu);
	rod_destroy(r);
	colon_destroy(c);
	return sum / samples / f_in;
}

static void test_capstan(void **state)
{
	const double mus[] = { 0.3, 0.1, 0 };
	const size_t n = SANITIZED ? 1 : sizeof(mus) / sizeof(mus[0]);
	double held;

	(void)state;
	for (size_t i = 0; i < n; i++) {
		double got = capstan(mus[i], false, &held, NULL);
		double want = exp(mus[i] * M_PI / 2);

		print_message("capstan through the colon: mu %.1f: F_out/F_in "
			      "%.4f, exp(mu theta) %.4f; wall %.1f N\n", mus[i],
			      got, want, held);
		assert_near(got, want, 0.05 * want);
		/* the bend's wall holds the tension's turn: |sum F_n| ~ the
		 * two tensions' vector sum, T_in sqrt(2) without friction */
		assert_true(held > 0.9 * 10 * M_SQRT2);
	}
}

/* The mobile sigmoid takes what its wall holds: the bend is pulled in,
 * and at rest its mesentery holds what the tube pushes. */
static void test_colon_takes_it(void **state)
{
	struct mobile_bend mb = { 0 };
	double held;

	(void)state;
	capstan(0, true, &held, &mb);
	print_message("mobile bend: the wall held %.1f N on the tube, the "
		      "sigmoid moved %.2f cm; pushed %.2f N, held %.2f N\n",
		      held, mb.moved * 100, vec3_norm(mb.pushed),
		      vec3_norm(mb.held));
	assert_true(mb.moved > 0.01);
	assert_vec_near(mb.held, mb.pushed, 0.06 * vec3_norm(mb.pushed));
	/* towards the bend's inside, as the rope's pull t_out - t_in */
	assert_true(mb.inward > 0.5 * vec3_norm(mb.pushed));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_wall_and_pipe),
		cmocka_unit_test(test_capstan),
		cmocka_unit_test(test_colon_takes_it),
	};

	sanitized_leaves("the capstan with the first friction alone; the "
			 "others are the plain build's");
	return cmocka_run_group_tests(tests, NULL, NULL);
}
