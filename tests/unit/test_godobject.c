/*
 * test_godobject.c - the tip's god-object against analytic walls and the
 * real colon: a plane (the proxy is the projection of the tip, k delta
 * along the normal), an edge (it slides along the line of two planes), a
 * corner (it stops at the point of three), walls at oblique angles (a
 * 120 and a 30 deg crease, a corner of oblique faces: the proxy rests at
 * the point of the walls nearest the tip, on one plane, the crease or the
 * apex, as the planes' multipliers say), jumps of 5 cm through the
 * colon's wall and across its folds (it stays inside), and a long random
 * ride of the scope through every case (it never leaks out).
 *
 * Under the sanitizers (sanitized.h) a quarter of the jumps, and the ride
 * through the normal case alone; the other cases' rides are the plain
 * build's.
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
#include "model/contact.h"
#include "geom_assert.h"
#include "model/godobject.h"
#include "model/scope.h"
#include "base/vec3.h"
#include "sanitized.h"

#define SKIN 1e-6  /* godobject.c keeps the proxy this far off its planes */
#define NEAR 1e-5  /* m: "on" a plane, line or point */
#define JUMPS (SANITIZED ? 500 : 2000)

/* ------------------------------------------------------------ walls */

/* A parallelogram of sides 2 HALF E1 and 2 HALF E2 centred at C (a square
 * for unit, orthogonal E1, E2), lumen towards E1 x E2, as two triangles
 * appended to the arrays. */
struct walls {
	float pos[64][3], nrm[64][3];
	uint32_t tri[32][3];
	uint32_t v, t;
};

static void square(struct walls *w, const double c[3], const double e1[3],
		   const double e2[3], double half)
{
	double n[3];
	uint32_t v0 = w->v;

	vec3_cross(n, e1, e2);
	vec3_normalize(n); /* E1, E2 need not be orthogonal */
	for (int k = 0; k < 4; k++) {
		double a = (k == 1 || k == 2) ? half : -half;
		double b = k >= 2 ? half : -half;

		for (int d = 0; d < 3; d++) {
			w->pos[w->v][d] = (float)(c[d] + a * e1[d] + b * e2[d]);
			w->nrm[w->v][d] = (float)n[d];
		}
		w->v++;
	}
	w->tri[w->t][0] = v0;
	w->tri[w->t][1] = v0 + 1;
	w->tri[w->t++][2] = v0 + 2;
	w->tri[w->t][0] = v0;
	w->tri[w->t][1] = v0 + 2;
	w->tri[w->t++][2] = v0 + 3;
}

static struct contact *make_contact(const struct walls *w)
{
	const struct mesh_segment seg = {
		.s0_m = 0, .s1_m = 1, .first = 0, .count = w->t,
	};

	return contact_create(w->pos, w->nrm, w->v, w->tri, w->t, &seg, 1);
}

static const double X[3] = { 1, 0, 0 }, Y[3] = { 0, 1, 0 },
		    Z[3] = { 0, 0, 1 }, O[3] = { 0, 0, 0 };

static void assert_point(const double p[3], double x, double y, double z,
			 double tol)
{
	assert_float_equal(p[0], x, tol);
	assert_float_equal(p[1], y, tol);
	assert_float_equal(p[2], z, tol);
}

/* The floor z = 0, lumen above: the proxy is the tip's projection; free
 * above the floor. */
static void test_plane(void **state)
{
	struct walls w = { 0 };
	struct godobject g;
	struct contact *c;
	const double start[3] = { 0, 0, 0.01 };

	(void)state;
	square(&w, O, X, Y, 0.1);
	c = make_contact(&w);
	assert_non_null(c);
	godobject_reset(&g, start);
	godobject_update(&g, c, (double[3]){ 0.02, 0.01, 0.005 }, 0, 1);
	assert_false(godobject_contact(&g));
	assert_point(g.proxy, 0.02, 0.01, 0.005, 1e-12);
	godobject_update(&g, c, (double[3]){ 0.03, -0.02, -0.004 }, 0, 1);
	assert_true(godobject_contact(&g));
	assert_int_equal(g.planes, 1);
	assert_point(g.proxy, 0.03, -0.02, SKIN, NEAR);
	assert_point(g.normal[0], 0, 0, 1, 1e-12);
	/* sliding on the floor follows the tip */
	for (int i = 0; i < 50; i++) {
		double goal[3] = { 0.03 - 0.001 * i, -0.02 + 0.0005 * i, -0.004 };

		godobject_update(&g, c, goal, 0, 1);
		assert_point(g.proxy, goal[0], goal[1], SKIN, NEAR);
	}
	/* and lifting the tip releases it */
	godobject_update(&g, c, (double[3]){ 0, 0, 0.002 }, 0, 1);
	assert_false(godobject_contact(&g));
	assert_point(g.proxy, 0, 0, 0.002, 1e-12);
	contact_destroy(c);
}

/* The floor z = 0 and the wall x = 0 meet in a concave edge along y: a
 * tip behind both holds the proxy on the edge, and it slides along it. */
static void test_edge(void **state)
{
	const double wall_c[3] = { 0, 0, 0.1 }, floor_c[3] = { 0.1, 0, 0 };
	struct walls w = { 0 };
	struct godobject g;
	struct contact *c;

	(void)state;
	square(&w, floor_c, X, Y, 0.1);           /* normal +z */
	square(&w, wall_c, Y, X, 0.1);            /* normal -z: wrong side */
	w.v -= 4;                                 /* replace: the wall x = 0 */
	w.t -= 2;
	square(&w, wall_c, Y, Z, 0.1);            /* normal +x */
	c = make_contact(&w);
	assert_non_null(c);
	godobject_reset(&g, (double[3]){ 0.02, 0, 0.02 });
	godobject_update(&g, c, (double[3]){ -0.01, 0.03, -0.02 }, 0, 1);
	assert_int_equal(g.planes, 2);
	assert_point(g.proxy, SKIN, 0.03, SKIN, NEAR);
	for (int i = 1; i <= 40; i++) {
		double y = 0.03 - 0.002 * i;

		godobject_update(&g, c, (double[3]){ -0.005, y, -0.03 }, 0, 1);
		assert_int_equal(g.planes, 2);
		assert_point(g.proxy, SKIN, y, SKIN, NEAR);
	}
	/* a tip behind the floor only slides along the floor, off the edge */
	godobject_update(&g, c, (double[3]){ 0.04, 0, -0.01 }, 0, 1);
	assert_int_equal(g.planes, 1);
	assert_point(g.proxy, 0.04, 0, SKIN, NEAR);
	contact_destroy(c);
}

/* Three walls x = 0, y = 0, z = 0: the proxy stops in the corner. */
static void test_corner(void **state)
{
	struct walls w = { 0 };
	struct godobject g;
	struct contact *c;

	(void)state;
	square(&w, (double[3]){ 0.1, 0.1, 0 }, X, Y, 0.1);
	square(&w, (double[3]){ 0, 0.1, 0.1 }, Y, Z, 0.1);
	square(&w, (double[3]){ 0.1, 0, 0.1 }, Z, X, 0.1);
	c = make_contact(&w);
	assert_non_null(c);
	godobject_reset(&g, (double[3]){ 0.03, 0.02, 0.01 });
	godobject_update(&g, c, (double[3]){ -0.01, -0.02, -0.03 }, 0, 1);
	assert_int_equal(g.planes, 3);
	assert_point(g.proxy, SKIN, SKIN, SKIN, NEAR);
	/* deeper into the corner: still there */
	godobject_update(&g, c, (double[3]){ -0.05, -0.01, -0.02 }, 0, 1);
	assert_point(g.proxy, SKIN, SKIN, SKIN, NEAR);
	/* out of the corner along x: back to an edge, then a plane */
	godobject_update(&g, c, (double[3]){ 0.03, -0.01, -0.02 }, 0, 1);
	assert_int_equal(g.planes, 2);
	assert_point(g.proxy, 0.03, SKIN, SKIN, NEAR);
	godobject_update(&g, c, (double[3]){ 0.03, 0.02, -0.02 }, 0, 1);
	assert_int_equal(g.planes, 1);
	assert_point(g.proxy, 0.03, 0.02, SKIN, NEAR);
	contact_destroy(c);
}

/* ------------------------------------------------------ oblique walls */

/*
 * The floor z = 0 (x >= 0) and a ramp from the same crease, the y axis,
 * rising along d = (cos beta, 0, sin beta): a wedge of lumen with the
 * dihedral angle BETA between them. The ramp's normal into the lumen is
 * n = Y x d = (sin beta, 0, -cos beta); the floor's is Z; n . Z = -cos beta,
 * so only at 90 deg are the two constraints independent.
 */
struct wedge {
	struct walls w;
	struct contact *c;
	double d[3], n[3];
};

static void wedge_init(struct wedge *k, double beta)
{
	double mid[3];

	memset(&k->w, 0, sizeof(k->w));
	vec3_set(k->d, cos(beta), 0, sin(beta));
	vec3_set(k->n, sin(beta), 0, -cos(beta));
	square(&k->w, (double[3]){ 0.1, 0, 0 }, X, Y, 0.1);
	vec3_scale(mid, k->d, 0.1);
	square(&k->w, mid, Y, k->d, 0.1);
	k->c = make_contact(&k->w);
	assert_non_null(k->c);
}

/*
 * The nearest point of the wedge to G (the proxy's place at rest), in the
 * three ways it can lie: on the floor below G, on the ramp below G, or on
 * the crease. Which one holds is the caller's geometry (the multipliers of
 * the planes that hold it are positive), stated at each call.
 */
enum wedge_rest { ON_FLOOR, ON_RAMP, ON_CREASE };

static void wedge_expect(const struct wedge *k, enum wedge_rest where,
			 const double g[3], double out[3])
{
	switch (where) {
	case ON_FLOOR:
		vec3_set(out, g[0], g[1], 0);
		break;
	case ON_RAMP:
		vec3_axpy(out, g, -vec3_dot(k->n, g), k->n);
		break;
	case ON_CREASE:
		vec3_set(out, 0, g[1], 0);
		break;
	}
}

/* From START, the tip to GOAL: the proxy rests at the expected point, held
 * by PLANES planes. */
static void wedge_push(const struct wedge *k, const double start[3],
		       const double goal[3], enum wedge_rest where, int planes)
{
	struct godobject g;
	double want[3];

	godobject_reset(&g, start);
	godobject_update(&g, k->c, goal, 0, 1);
	wedge_expect(k, where, goal, want);
	assert_int_equal(g.planes, planes);
	assert_vec_near(g.proxy, want, NEAR);
}

/* -(a Z + b n): a goal the floor and the ramp push back with
 * multipliers a and b, displaced by Y_M along the crease. */
static void behind_both(const struct wedge *k, double a, double b, double y_m,
			double out[3])
{
	vec3_set(out, 0, y_m, 0);
	vec3_axpy(out, out, -a, Z);
	vec3_axpy(out, out, -b, k->n);
}

/* An obtuse crease (120 deg, n = (0.866, 0, 0.5)): each plane alone, the
 * crease, and a tip that slides off the floor over the crease onto the
 * ramp, where the floor's multiplier turns negative and it lets go. */
static void test_wedge_obtuse(void **state)
{
	const double start[3] = { 0.03, 0, 0.02 };
	struct godobject g;
	double goal[3];
	struct wedge k;

	(void)state;
	wedge_init(&k, 120 * M_PI / 180);
	/* below the floor, in front of the ramp's plane: the floor alone */
	wedge_push(&k, start, (double[3]){ 0.03, 0.01, -0.01 }, ON_FLOOR, 1);
	/* behind the ramp, 4 cm up it, 1 cm deep: the ramp alone */
	vec3_scale(goal, k.d, 0.04);
	vec3_axpy(goal, goal, -0.01, k.n);
	goal[1] = -0.02;
	wedge_push(&k, start, goal, ON_RAMP, 1);
	/* pushed into the crease by both: on the crease line */
	behind_both(&k, 0.01, 0.02, 0.015, goal);
	wedge_push(&k, start, goal, ON_CREASE, 2);
	behind_both(&k, 0.02, 0.003, -0.03, goal);
	wedge_push(&k, start, goal, ON_CREASE, 2);
	/* along the floor first (it is crossed at x = 1 cm), over the crease:
	 * on the crease the floor would have to pull (a = -1.6 cm), so the
	 * proxy rests on the ramp, 1.2 cm above the floor */
	vec3_set(goal, -0.03, 0.01, -0.001);
	wedge_push(&k, (double[3]){ 0.03, 0.01, 0.0005 }, goal, ON_RAMP, 1);
	/* the crease, then sliding along it */
	godobject_reset(&g, start);
	for (int i = 0; i <= 20; i++) {
		double want[3];

		behind_both(&k, 0.01, 0.01, 0.002 * i, goal);
		godobject_update(&g, k.c, goal, 0, 1);
		assert_int_equal(g.planes, 2);
		wedge_expect(&k, ON_CREASE, goal, want);
		assert_vec_near(g.proxy, want, NEAR);
	}
	contact_destroy(k.c);
}

/* An acute wedge (30 deg, n = (0.5, 0, -0.866)): the lumen narrows to the
 * crease; a tip behind the ramp is held on the ramp, or, where the ramp's
 * foot point would be below the floor, in the crease. */
static void test_wedge_acute(void **state)
{
	const double start[3] = { 0.05, 0, 0.01 };
	double goal[3];
	struct wedge k;

	(void)state;
	wedge_init(&k, 30 * M_PI / 180);
	assert_true(vec3_dot(k.n, start) > 0 && start[2] > 0);
	/* below the floor: the floor alone (the ramp's half-space holds the
	 * whole floor) */
	wedge_push(&k, start, (double[3]){ 0.06, 0.01, -0.01 }, ON_FLOOR, 1);
	/* behind the ramp, 5 cm up it, 1 cm deep: the ramp alone */
	vec3_scale(goal, k.d, 0.05);
	vec3_axpy(goal, goal, -0.01, k.n);
	wedge_push(&k, start, goal, ON_RAMP, 1);
	/* behind the ramp, 0.7 cm deep: its foot point (2.4, 1.4) cm */
	wedge_push(&k, start, (double[3]){ 0.02, 0, 0.02 }, ON_RAMP, 1);
	/* above the floor, behind the ramp, crossing it first (1.5 cm up
	 * it); its foot point there (-1.3, -0.74) cm is below the floor:
	 * then the floor too, both pushing (a = 3.0 cm, b = 4 cm): the
	 * crease */
	wedge_push(&k, start, (double[3]){ -0.02, 0.01, 0.005 }, ON_CREASE, 2);
	/* below the floor, its foot point on the floor behind the ramp
	 * (a, b > 0 by construction): the crease */
	behind_both(&k, 0.0373, 0.02, -0.01, goal);
	wedge_push(&k, start, goal, ON_CREASE, 2);
	/* above the floor, behind the ramp, its foot point below the
	 * floor: the crease */
	behind_both(&k, 0.005, 0.03, 0.02, goal);
	wedge_push(&k, start, goal, ON_CREASE, 2);
	contact_destroy(k.c);
}

/*
 * A corner of three faces at oblique angles: the cone spanned by the rays
 * r1 = (1, 0, 0), r2 = (cos 60, sin 60, 0), r3 = (0.5, 0.5, 1)/|.|, its
 * faces the sectors (r1, r2), (r2, r3), (r3, r1). A tip pushed back by all
 * three faces holds the proxy at the apex; pushed back by the two faces of
 * one edge, on that edge at the tip's place along it.
 */
static void sector(struct walls *w, const double a[3], const double b[3],
		   double len)
{
	double c[3];

	for (int d = 0; d < 3; d++) {
		c[d] = len / 2 * (a[d] + b[d]);
	}
	square(w, c, a, b, len / 2); /* corners 0, len a, len (a + b), len b */
}

static void test_corner_oblique(void **state)
{
	double r[3][3] = { { 1, 0, 0 }, { 0.5, sqrt(3) / 2, 0 },
			   { 0.5, 0.5, 1 } };
	double n[3][3], start[3] = { 0, 0, 0 }, goal[3], want[3];
	struct walls w = { 0 };
	struct godobject g;
	struct contact *c;

	(void)state;
	vec3_normalize(r[2]);
	for (int i = 0; i < 3; i++) { /* face i: (r_i, r_i+1), inwards */
		sector(&w, r[i], r[(i + 1) % 3], 0.1);
		vec3_cross(n[i], r[i], r[(i + 1) % 3]);
		vec3_normalize(n[i]);
		vec3_axpy(start, start, 0.02, r[i]);
	}
	c = make_contact(&w);
	assert_non_null(c);
	for (int i = 0; i < 3; i++) { /* no two faces at right angles */
		assert_true(fabs(vec3_dot(n[i], n[(i + 1) % 3])) > 0.15);
	}
	/* behind all three: the apex */
	vec3_set(goal, 0, 0, 0);
	for (int i = 0; i < 3; i++) {
		vec3_axpy(goal, goal, -0.01 * (i + 1), n[i]);
	}
	godobject_reset(&g, start);
	godobject_update(&g, c, goal, 0, 1);
	assert_int_equal(g.planes, 3);
	assert_vec_near(g.proxy, O, NEAR);
	/* behind the two faces of edge r_e (faces e and e - 1), 3 cm along
	 * it: on the edge there */
	for (int e = 0; e < 3; e++) {
		int fa = e, fb = (e + 2) % 3; /* the faces that hold r_e */

		vec3_scale(want, r[e], 0.03);
		vec3_axpy(goal, want, -0.004, n[fa]);
		vec3_axpy(goal, goal, -0.007, n[fb]);
		godobject_reset(&g, start);
		godobject_update(&g, c, goal, 0, 1);
		assert_int_equal(g.planes, 2);
		assert_vec_near(g.proxy, want, NEAR);
	}
	contact_destroy(c);
}

/* ------------------------------------------------------------ the colon */

/*
 * The loaded case's contact triangles with their bounds, read once: the
 * ground truth below tests thousands of points against them.
 */
static struct tri_box {
	double p[3][3];
	double lo[3], hi[3];
} *boxes;

static struct colon *load_case(const char *name)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	const char *dir = getenv("ENDOSIM_CASES");
	char path[512], err[256];
	struct anatomy a;
	struct colon *c;

	snprintf(path, sizeof(path), "%s/%s.case",
		 dir && *dir ? dir : "config/cases", name);
	assert_int_equal(anatomy_load(&a, path, err, sizeof(err)), 0);
	c = colon_create(&a, &p, err, sizeof(err));
	assert_non_null(c);
	boxes = malloc(colon_mesh(c)->triangles * sizeof(*boxes));
	assert_non_null(boxes);
	for (uint32_t t = 0; t < colon_mesh(c)->triangles; t++) {
		struct tri_box *b = &boxes[t];

		contact_triangle(colon_contact(c), t, b->p);
		for (int d = 0; d < 3; d++) {
			b->lo[d] = fmin(fmin(b->p[0][d], b->p[1][d]), b->p[2][d]);
			b->hi[d] = fmax(fmax(b->p[0][d], b->p[1][d]), b->p[2][d]);
		}
	}
	return c;
}

static void unload_case(struct colon *c)
{
	colon_destroy(c);
	free(boxes);
	boxes = NULL;
}

/* Moller-Trumbore: does the open segment A -> B cross triangle P? */
static bool crosses(const double a[3], const double b[3],
		    const double p[3][3])
{
	double e1[3], e2[3], d[3], h[3], s[3], q[3], det, u, v, t;

	vec3_sub(e1, p[1], p[0]);
	vec3_sub(e2, p[2], p[0]);
	vec3_sub(d, b, a);
	vec3_cross(h, d, e2);
	det = vec3_dot(e1, h);
	if (fabs(det) < 1e-20) {
		return false;
	}
	vec3_sub(s, a, p[0]);
	u = vec3_dot(s, h) / det;
	vec3_cross(q, s, e1);
	v = vec3_dot(d, q) / det;
	t = vec3_dot(e2, q) / det;
	return u >= 0 && v >= 0 && u + v <= 1 && t > 0 && t < 1;
}

/*
 * Ground truth, independent of the code under test: P is inside the
 * contact surface when a segment from the centreline sample nearest to it
 * (well inside the lumen) crosses the surface an even number of times.
 */
static bool inside_colon(const struct colon *c, const double p[3])
{
	const struct centreline *cl = colon_centreline(c);
	const struct mesh *m = colon_mesh(c);
	size_t n = centreline_count(cl), best = 0;
	double best_d = INFINITY, s, lo[3], hi[3];
	const double *a;
	int crossings = 0;

	/* not the last samples: the cecum's pole lies on the surface */
	for (size_t i = 5; i + 25 < n; i++) {
		double d = vec3_dist(centreline_sample(cl, i)->p, p);

		if (d < best_d) {
			best_d = d;
			best = i;
		}
	}
	s = (double)best * centreline_step(cl);
	a = centreline_sample(cl, best)->p;
	for (int d = 0; d < 3; d++) {
		lo[d] = fmin(a[d], p[d]);
		hi[d] = fmax(a[d], p[d]);
	}
	for (uint32_t k = 0; k < m->segments; k++) {
		if (m->seg[k].s1_m < s - 0.15 || m->seg[k].s0_m > s + 0.15) {
			continue;
		}
		for (uint32_t t = m->seg[k].first;
		     t < m->seg[k].first + m->seg[k].count; t++) {
			const struct tri_box *b = &boxes[t];

			if (b->hi[0] < lo[0] || b->lo[0] > hi[0] ||
			    b->hi[1] < lo[1] || b->lo[1] > hi[1] ||
			    b->hi[2] < lo[2] || b->lo[2] > hi[2]) {
				continue; /* the segment cannot cross it */
			}
			crossings += crosses(a, p, b->p);
		}
	}
	return !(crossings & 1);
}

static double uniform(double lo, double hi)
{
	return lo + (hi - lo) * rand() / (double)RAND_MAX;
}

/* From points near the wall, goals 5 cm away in every direction: through
 * the wall, across folds, along the lumen. The proxy ends inside. */
static void test_jumps_stay_inside(void **state)
{
	struct colon *c = load_case("normal");
	const struct centreline *cl = colon_centreline(c);
	const struct contact *ct = colon_contact(c);
	int held = 0;

	(void)state;
	srand(3);
	for (int k = 0; k < JUMPS; k++) {
		double s = uniform(0.08, 1.40), start[3], goal[3], dir[3];
		double r = uniform(0.0, 0.012);
		struct centreline_point q;
		struct godobject g;

		centreline_at_s(cl, s, &q);
		vec3_set(dir, uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
		vec3_normalize(dir);
		vec3_axpy(start, q.p, r, dir);
		assert_true(inside_colon(c, start));
		vec3_set(dir, uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
		vec3_normalize(dir);
		vec3_axpy(goal, start, 0.05, dir);
		godobject_reset(&g, start);
		godobject_update(&g, ct, goal, s - 0.1, s + 0.1);
		held += godobject_contact(&g);
		if (!inside_colon(c, g.proxy)) {
			fail_msg("jump %d from s %.3f: proxy outside", k, s);
		}
	}
	assert_true(held > JUMPS / 2); /* most 5 cm jumps meet the wall */
	unload_case(c);
}

/* The point at S, at angle THETA around the centreline from u, RHO from it. */
static void around(const struct centreline *cl, double s, double theta,
		   double rho, double out[3])
{
	struct centreline_point q;

	centreline_at_s(cl, s, &q);
	vec3_axpy(out, q.p, rho * cos(theta), q.u);
	vec3_axpy(out, out, rho * sin(theta), q.v);
}

/*
 * Along the lumen near the wall, 5 cm at a time, midway between two
 * taeniae where the haustral folds stand: from a valley between folds, at
 * a distance from the centreline that clears the valleys but not the
 * folds' crests. The proxy meets the first fold and stays inside (it may
 * slide over the crest, never through it).
 */
static void test_jump_across_folds(void **state)
{
	struct colon *c = load_case("normal");
	const struct centreline *cl = colon_centreline(c);
	double theta = M_PI / 3, inset = SCOPE_RADIUS_M; /* the colon's */
	int stopped = 0, jumps = 0;

	(void)state;
	for (double s0 = 0.90; s0 < 1.10; s0 += 0.013) {
		double lo = INFINITY, hi = 0, valley = s0, rho;
		double start[3], goal[3];
		struct godobject g;

		for (double s = s0; s <= s0 + 0.05; s += 0.0005) {
			double r = colon_lumen_radius(c, s, theta) - inset;

			lo = fmin(lo, r);
			if (s < s0 + 0.03 && r > hi) {
				hi = r;
				valley = s;
			}
		}
		rho = (lo + hi) / 2; /* below the valley, above the crests */
		if (hi - lo < 0.002) {
			continue;
		}
		jumps++;
		around(cl, valley, theta, rho, start);
		around(cl, valley + 0.05, theta, rho, goal);
		assert_true(inside_colon(c, start));
		godobject_reset(&g, start);
		godobject_update(&g, colon_contact(c), goal, valley - 0.1,
				 valley + 0.15);
		stopped += godobject_contact(&g);
		assert_true(inside_colon(c, g.proxy));
	}
	assert_true(jumps > 5);
	assert_int_equal(stopped, jumps);
	unload_case(c);
}

/* A long random ride in every case: insertion, withdrawal, roll and both
 * wheels to their limits, now and then a 5 cm jump; the proxy never
 * leaks. The window of s is what the haptics use: around the proxy, the
 * tip and the bending section. */
static void ride(const char *name, int steps)
{
	struct colon *c = load_case(name);
	const struct centreline *cl = colon_centreline(c);
	const struct contact *ct = colon_contact(c);
	const struct scope_params sp = SCOPE_PARAMS_DEFAULT;
	struct scope_input in = { .depth_m = 0.05 };
	struct scope_pose *pose = malloc(sizeof(*pose));
	double proxy_s = 0.05;
	struct godobject g;
	int held = 0;

	scope_update(&sp, cl, &in, pose);
	godobject_reset(&g, pose->tip);
	for (int k = 0; k < steps; k++) {
		double lo, hi;

		if (rand() % 100 == 0) {
			in.depth_m += uniform(-0.05, 0.05);
		} else {
			in.depth_m += uniform(-0.0018, 0.0022);
			in.roll_rad += uniform(-0.03, 0.03);
			in.wheel_ud_rad += uniform(-0.03, 0.03);
			in.wheel_lr_rad += uniform(-0.03, 0.03);
		}
		in.depth_m = fmin(fmax(in.depth_m, 0.03), 1.55);
		in.wheel_ud_rad = fmin(fmax(in.wheel_ud_rad, -1.75), 1.75);
		in.wheel_lr_rad = fmin(fmax(in.wheel_lr_rad, -1.75), 1.75);
		scope_update(&sp, cl, &in, pose);
		lo = fmin(fmin(proxy_s, pose->tip_s_m), pose->base_s_m) - 0.1;
		hi = fmax(fmax(proxy_s, pose->tip_s_m),
			  pose->base_s_m + sp.bending_length_m) + 0.1;
		godobject_update(&g, ct, pose->tip, lo, hi);
		proxy_s = g.planes ? contact_triangle_s(ct, g.tri[0])
				   : pose->tip_s_m;
		held += godobject_contact(&g);
		if (k % 5 == 0 && !inside_colon(c, g.proxy)) {
			fail_msg("%s: step %d, depth %.3f: proxy outside", name,
				 k, in.depth_m);
		}
	}
	printf("%s: %d steps, %d in contact\n", name, steps, held);
	assert_true(held > steps / 10);
	free(pose);
	unload_case(c);
}

static void test_random_ride(void **state)
{
	(void)state;
	srand(11);
	ride("normal", 6000);
	if (SANITIZED) {
		return;
	}
	ride("tight-flexures", 6000);
	ride("redundant-sigmoid", 6000);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_plane),
		cmocka_unit_test(test_edge),
		cmocka_unit_test(test_corner),
		cmocka_unit_test(test_wedge_obtuse),
		cmocka_unit_test(test_wedge_acute),
		cmocka_unit_test(test_corner_oblique),
		cmocka_unit_test(test_jumps_stay_inside),
		cmocka_unit_test(test_jump_across_folds),
		cmocka_unit_test(test_random_ride),
	};

	sanitized_leaves("a quarter of the jumps, the ride through the normal "
			 "case alone; the other cases' rides are the plain "
			 "build's");
	return cmocka_run_group_tests(tests, NULL, NULL);
}
