/* lumen.c - see lumen.h. */
#include "model/lumen.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"

#define ONSET_M 0.0005     /* the wall's push sets in over this (lumen.h) */
#define ONSET_WIDTHS 8     /* nothing worth the name farther out */

/* What one segment met this step. */
struct touch {
	long sample;        /* nearest sample, -1: in the pipe */
	bool fresh;         /* s_m says where it is (lumen_reset()) */
	bool on;            /* the wall (not the pipe) presses it */
	double s_m;         /* the sample's material s */
	double n[3];        /* into the lumen */
	double fn;          /* the wall's push at the step's start, N */
	double k;           /* its stiffness along n now, N/m */
	double c;           /* friction's damping, N s/m */
	double b;           /* the wall's own damping, N s/m */
	double x0[3];       /* the segment's centre at the step's start */
	double wall_v[3];   /* the wall's velocity */
};

struct lumen {
	int n;
	struct touch *t;
	const double *factor; /* the gas's, or NULL */
};

struct lumen *lumen_create(int segments)
{
	struct lumen *l = calloc(1, sizeof(*l));

	if (!l) {
		return NULL;
	}
	l->n = segments;
	l->t = calloc((size_t)segments, sizeof(*l->t));
	if (!l->t) {
		free(l);
		return NULL;
	}
	return l;
}

void lumen_destroy(struct lumen *l)
{
	if (l) {
		free(l->t);
		free(l);
	}
}

void lumen_reset(struct lumen *l, const double *sigma_m)
{
	for (int i = 0; i < l->n; i++) {
		l->t[i].sample = -1;
		l->t[i].fresh = true;
		l->t[i].s_m = sigma_m[i];
		l->t[i].on = false;
	}
}

static double dist2(const struct centreline *cl, long k, const double p[3])
{
	double d[3];

	vec3_sub(d, p, centreline_sample(cl, (size_t)k)->p);
	return vec3_dot(d, d);
}

/* The sample nearest P, walking from HINT while the distance falls. */
static long walk(const struct centreline *cl, long hint, const double p[3])
{
	long n = (long)centreline_count(cl), k = hint;
	double best = dist2(cl, k, p);

	for (int step = 0; step < LUMEN_WALK; step++) {
		double lo = k > 0 ? dist2(cl, k - 1, p) : INFINITY;
		double hi = k + 1 < n ? dist2(cl, k + 1, p) : INFINITY;

		if (lo < best && lo <= hi) {
			best = lo;
			k--;
		} else if (hi < best) {
			best = hi;
			k++;
		} else {
			break;
		}
	}
	return k;
}

/*
 * The wall's push on a segment DELTA (m) beyond the free radius, and its
 * stiffness: K ONSET softplus(delta / ONSET), K sigma(delta / ONSET) -- K
 * delta once well in, nothing well out, and in between a smooth onset over
 * ONSET_M, so that a segment grazing the wall meets a stiffness that grows
 * as it comes in rather than one that switches on a step late (which makes
 * a tube pushed into a bend chatter between two shapes).
 */
static void wall_law(double k, double delta, double *force, double *stiff)
{
	double z = delta / ONSET_M;

	if (z > 30) {
		*force = k * delta;
		*stiff = k;
		return;
	}
	*force = k * ONSET_M * log1p(exp(z));
	*stiff = k / (1 + exp(-z));
}

/* A spring K and a damper B along N, a damper C across it, as 3x3
 * matrices. */
static void spring_damper(const double n[3], double k, double b, double c,
			  double km[3][3], double bm[3][3])
{
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++) {
			km[i][j] = k * n[i] * n[j];
			bm[i][j] = c * ((i == j) - n[i] * n[j]) +
				   b * n[i] * n[j];
		}
	}
}

/* Segment I in the rig's pipe: held on the axis through C0 along T0. */
static void load_pipe(struct rod *rod, int i, const double c0[3],
		      const double t0[3], const struct lumen_params *p)
{
	const double *x = rod_centre(rod, i);
	double d[3], rho, n[3], k, km[3][3], bm[3][3], f[3];
	const double zero[3] = { 0, 0, 0 };

	vec3_sub(d, x, c0);
	vec3_axpy(d, d, -vec3_dot(d, t0), t0);
	rho = vec3_norm(d);
	if (rho <= LUMEN_PIPE_CLEARANCE_M) {
		return;
	}
	vec3_scale(n, d, -1 / rho);
	k = p->pipe_n_per_m2 * rod_segment_length(rod);
	spring_damper(n, k, 0, 0, km, bm);
	vec3_scale(f, n, k * (rho - LUMEN_PIPE_CLEARANCE_M));
	rod_load_point(rod_load(rod, i), zero, f, (const double(*)[3])km,
		       NULL, NULL);
}

/* The radial offset of X from sample K (beyond the last: all of it). */
static void radial(const struct centreline *cl, long k, const double x[3],
		   double out[3])
{
	const struct centreline_point *c = centreline_sample(cl, (size_t)k);
	double along;

	vec3_sub(out, x, c->p);
	along = vec3_dot(out, c->t);
	if (k + 1 < (long)centreline_count(cl) || along < 0) {
		vec3_axpy(out, out, -along, c->t);
	}
}

/*
 * Segment I against the lumen; false when it has left through the anal
 * verge (its nearest sample the first, behind it).
 */
static bool load_wall(struct lumen *l, struct rod *rod, int i,
		      const struct colon *colon, const struct flex *flex,
		      const struct lumen_params *p)
{
	const struct centreline *cl = colon_centreline(colon);
	struct touch *t = &l->t[i];
	const double *x = rod_centre(rod, i), *v = rod_velocity(rod, i);
	double rho[3], r, free_r, off[3], f[3], vt[3], slip, km[3][3], bm[3][3];
	double ds = centreline_step(cl), behind[3];
	long n = (long)centreline_count(cl);

	if (t->sample < 0) {
		double k = floor(t->s_m / ds + 0.5);

		t->sample = k < 0 ? 0 : k >= (double)n ? n - 1 : (long)k;
	}
	t->sample = walk(cl, t->sample, x);
	vec3_sub(behind, x, centreline_sample(cl, 0)->p);
	if (t->sample == 0 &&
	    vec3_dot(behind, centreline_sample(cl, 0)->t) < 0) {
		return false;
	}
	t->s_m = (double)t->sample * ds;
	radial(cl, t->sample, x, rho);
	r = vec3_norm(rho);
	free_r = colon_tube_radius(colon, (size_t)t->sample);
	if (l->factor) {
		free_r *= gas_factor_at(colon, l->factor, t->s_m);
	}
	free_r = fmax(free_r - p->tube_radius_m, 0);
	t->on = r > free_r - ONSET_WIDTHS * ONSET_M && r > 0 && i + 1 < l->n;
	if (!t->on) {
		return true;
	}
	vec3_scale(t->n, rho, -1 / r);
	wall_law(p->wall_n_per_m2 * rod_segment_length(rod), r - free_r,
		 &t->fn, &t->k);
	vec3_copy(t->x0, x);
	if (flex) {
		/* the wall carries the tube along it (friction), not across:
		 * the damping across takes the tube's speed alone (the
		 * wall's, a step old, would feed back) */
		flex_velocity(flex, t->s_m, t->wall_v);
		vec3_axpy(t->wall_v, t->wall_v, -vec3_dot(t->wall_v, t->n),
			  t->n);
	} else {
		vec3_set(t->wall_v, 0, 0, 0);
	}
	vec3_sub(vt, v, t->wall_v);
	vec3_axpy(vt, vt, -vec3_dot(vt, t->n), t->n);
	slip = vec3_norm(vt);
	t->c = p->friction * t->fn / fmax(slip, p->slip_m_per_s);
	t->b = t->k * p->wall_damping_s;
	spring_damper(t->n, t->k, t->b, t->c, km, bm);
	vec3_scale(f, t->n, t->fn);
	vec3_scale(off, t->n, -p->tube_radius_m);
	rod_load_point(rod_load(rod, i), off, f, (const double(*)[3])km,
		       (const double(*)[3])bm, t->wall_v);
	return true;
}

/* Segment I was in the pipe (or placed anew): has it come in? Only
 * through the anal verge: in front of it, near the pipe's axis. */
static bool comes_in(const struct touch *t, const struct colon *colon,
		     const double x[3])
{
	const struct centreline_point *c0 =
		centreline_sample(colon_centreline(colon), 0);
	double d[3], along;

	if (t->fresh) {
		return t->s_m >= 0;
	}
	vec3_sub(d, x, c0->p);
	along = vec3_dot(d, c0->t);
	vec3_axpy(d, d, -along, c0->t);
	return along >= 0 && vec3_norm(d) < colon_tube_radius(colon, 0);
}

void lumen_set_factors(struct lumen *l, const double *factor)
{
	l->factor = factor;
}

void lumen_load(struct lumen *l, struct rod *rod, const struct colon *colon,
		const struct flex *flex, const struct lumen_params *p)
{
	const struct centreline_point *c0 =
		centreline_sample(colon_centreline(colon), 0);

	for (int i = 0; i < l->n; i++) {
		struct touch *t = &l->t[i];
		bool inside = t->sample >= 0 ||
			      comes_in(t, colon, rod_centre(rod, i));

		if (!inside || t->fresh) {
			t->sample = -1;
		}
		t->fresh = false;
		t->on = false;
		if (inside && load_wall(l, rod, i, colon, flex, p)) {
			continue;
		}
		t->sample = -1;
		t->s_m = 0;
		load_pipe(rod, i, c0->p, c0->t, p);
	}
}

void lumen_react(struct lumen *l, const struct rod *rod, struct flex *flex,
		 struct lumen_totals *out)
{
	memset(out, 0, sizeof(*out));
	for (int i = 0; i < l->n; i++) {
		const struct touch *t = &l->t[i];
		const double *v = rod_velocity(rod, i);
		double vt[3], f[3], fn, moved[3];

		if (!t->on) {
			continue;
		}
		/* the spring as the step ended, linear as the step took it,
		 * and the damper on the step's sliding */
		vec3_sub(moved, rod_centre(rod, i), t->x0);
		vec3_sub(vt, v, t->wall_v);
		fn = fmax(0, t->fn - t->k * vec3_dot(t->n, moved) -
				     t->b * vec3_dot(t->n, vt));
		vec3_axpy(vt, vt, -vec3_dot(vt, t->n), t->n);
		vec3_scale(f, t->n, fn);
		vec3_axpy(f, f, -t->c, vt);
		out->contacts++;
		out->wall_n += fn;
		out->friction_n += t->c * vec3_norm(vt);
		if (flex) {
			vec3_scale(f, f, -1);
			flex_push(flex, t->s_m, f, 0);
		}
	}
}

long lumen_sample(const struct lumen *l, int i)
{
	return l->t[i].sample;
}
