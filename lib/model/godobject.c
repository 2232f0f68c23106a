/* godobject.c - see godobject.h. */
#include "model/godobject.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"

#define MAX_MOVES 16       /* crossings handled per update */
#define PARALLEL 1e-10     /* Gram determinant below which planes coincide */

/*
 * The proxy rests this far (m) in front of its planes. On a plane exactly,
 * rounding may leave it a hair behind; sliding on, a path a hair behind
 * plane A crosses a neighbour B that is almost coplanar far from their
 * shared edge, on A's side of it, where B's triangle is not: the crossing
 * would be missed and the proxy would leak. A path in front of A crosses B
 * on B's side, inside B.
 */
#define SKIN_M 1e-6

/* The active planes while an update runs. */
struct planes {
	int n;
	uint32_t tri[GODOBJECT_MAX_PLANES];
	double normal[GODOBJECT_MAX_PLANES][3];
	double offset[GODOBJECT_MAX_PLANES];
	double shaded[GODOBJECT_MAX_PLANES][3];
};

void godobject_reset(struct godobject *g, const double p[3])
{
	memset(g, 0, sizeof(*g));
	vec3_copy(g->proxy, p);
}

static void drop(struct planes *ps, int k)
{
	ps->n--;
	for (int i = k; i < ps->n; i++) {
		ps->tri[i] = ps->tri[i + 1];
		vec3_copy(ps->normal[i], ps->normal[i + 1]);
		ps->offset[i] = ps->offset[i + 1];
		vec3_copy(ps->shaded[i], ps->shaded[i + 1]);
	}
}

static double det3(const double m[3][3])
{
	return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
	       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
	       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/*
 * Solves G lambda = R for the N (1..3) active planes, G the Gram matrix of
 * their normals, by Cramer's rule. Returns false when G is singular (two
 * planes coincide).
 */
static bool multipliers(const struct planes *ps, const double r[3],
			double lambda[3])
{
	double g[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
	double d;

	for (int i = 0; i < ps->n; i++) {
		for (int j = 0; j < ps->n; j++) {
			g[i][j] = vec3_dot(ps->normal[i], ps->normal[j]);
		}
	}
	d = det3(g);
	if (fabs(d) < PARALLEL) {
		return false;
	}
	for (int k = 0; k < ps->n; k++) {
		double gk[3][3];

		memcpy(gk, g, sizeof(gk));
		for (int i = 0; i < 3; i++) {
			gk[i][k] = i < ps->n ? r[i] : (i == k);
		}
		lambda[k] = det3(gk) / d;
	}
	return true;
}

/*
 * The point nearest GOAL on the active planes (moved SKIN_M into the lumen),
 * x = goal + sum lambda_i n_i.
 * Planes that would have to pull (lambda < 0) are dropped, and so is the
 * older of two that coincide.
 */
static void target(struct planes *ps, const double goal[3], double out[3])
{
	double lambda[3], r[3];

	for (;;) {
		int worst = -1;

		for (int i = 0; i < ps->n; i++) {
			r[i] = ps->offset[i] + SKIN_M -
			       vec3_dot(ps->normal[i], goal);
		}
		if (ps->n && !multipliers(ps, r, lambda)) {
			drop(ps, 0);
			continue;
		}
		for (int i = 0; i < ps->n; i++) {
			if (lambda[i] < 0 && (worst < 0 || lambda[i] < lambda[worst])) {
				worst = i;
			}
		}
		if (worst < 0) {
			break;
		}
		drop(ps, worst);
	}
	vec3_copy(out, goal);
	for (int i = 0; i < ps->n; i++) {
		vec3_axpy(out, out, lambda[i], ps->normal[i]);
	}
}

static void add(struct planes *ps, const struct contact_hit *h)
{
	int i = ps->n++;

	ps->tri[i] = h->triangle;
	vec3_copy(ps->normal[i], h->normal);
	ps->offset[i] = h->offset;
	vec3_copy(ps->shaded[i], h->shaded);
}

void godobject_update(struct godobject *g, const struct contact *c,
		      const double goal[3], double s0_m, double s1_m)
{
	struct planes ps = { 0 };
	struct contact_hit hit;
	double cur[3], next[3];

	vec3_copy(cur, g->proxy);
	for (int move = 0;; move++) {
		target(&ps, goal, next);
		if (!contact_first_hit(c, cur, next, s0_m, s1_m, ps.tri, ps.n,
				       &hit)) {
			vec3_copy(cur, next);
			break;
		}
		/* stop at the crossing, off its plane, when held in a corner
		 * or out of moves */
		vec3_copy(cur, hit.point);
		if (ps.n == GODOBJECT_MAX_PLANES || move + 1 == MAX_MOVES) {
			vec3_axpy(cur, cur, SKIN_M, hit.normal);
			break;
		}
		add(&ps, &hit);
	}
	vec3_copy(g->proxy, cur);
	g->planes = ps.n;
	for (int i = 0; i < ps.n; i++) {
		g->tri[i] = ps.tri[i];
		vec3_copy(g->normal[i], ps.normal[i]);
		g->offset[i] = ps.offset[i];
	}
	/* the planes' interpolated normals, averaged: at an edge they meet
	 * (the vertex normals are shared), so the shaded push does not jump
	 * as a second plane takes hold or lets go */
	vec3_set(g->shaded, 0, 0, 0);
	for (int i = 0; i < ps.n; i++) {
		vec3_add(g->shaded, g->shaded, ps.shaded[i]);
	}
	if (ps.n && vec3_normalize(g->shaded) < 1e-9) {
		vec3_copy(g->shaded, ps.normal[0]);
	}
}
