/* flex.c - see flex.h. */
#include "flex.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vec3.h"

struct chain {
	int span;          /* the centreline's */
	int first, count;  /* its nodes */
	double s0, s1;     /* m, material */
	double k;          /* mesentery per node, N/m */
	double h;          /* mesentery height, m */
};

struct flex {
	struct colon *colon;
	struct flex_params par;
	struct chain chain[CENTRELINE_MAX_SPANS];
	int chains;
	int nodes;
	double y[FLEX_MAX_NODES][3];       /* displacement now */
	double v[FLEX_MAX_NODES][3];       /* its rate over the last step */
	double force[FLEX_MAX_NODES][3];   /* pushed this step */
	double stiff[FLEX_MAX_NODES];      /* and how it eases, N/m */
	double applied[FLEX_MAX_NODES][3]; /* what the centreline has */
};

static bool params_ok(const struct flex_params *p)
{
	return p->node_spacing_m >= 0.005 && p->node_spacing_m <= 0.2 &&
	       p->damping_n_s_per_m > 0 && p->damping_n_s_per_m < 1e6 &&
	       p->chain_n_per_m >= 0 && p->chain_n_per_m < 1e6;
}

struct flex *flex_create(const struct flex_params *p)
{
	struct flex *f;

	if (!params_ok(p)) {
		return NULL;
	}
	f = calloc(1, sizeof(*f));
	if (f) {
		f->par = *p;
	}
	return f;
}

void flex_attach(struct flex *f, struct colon *colon)
{
	struct centreline *cl = colon_centreline(colon);

	f->colon = colon;
	f->chains = 0;
	f->nodes = 0;
	for (int i = 0; i < colon_regions(colon); i++) {
		const struct colon_region *r = colon_region(colon, i);
		struct chain *c = &f->chain[f->chains];
		int count;

		if (r->span < 0 || !(r->mesentery_n_per_m > 0) ||
		    !(r->max_bow_m > 0)) {
			continue;
		}
		centreline_span_range(cl, r->span, &c->s0, &c->s1);
		count = (int)lround((c->s1 - c->s0) / f->par.node_spacing_m) -
			1;
		count = count < 1 ? 1 : count;
		if (f->nodes + count > FLEX_MAX_NODES) {
			count = FLEX_MAX_NODES - f->nodes;
		}
		if (count < 1) {
			break;
		}
		c->span = r->span;
		c->first = f->nodes;
		c->count = count;
		c->k = r->mesentery_n_per_m / count;
		c->h = r->max_bow_m;
		f->nodes += count;
		f->chains++;
	}
	flex_reset(f);
}

void flex_destroy(struct flex *f)
{
	free(f);
}

static void lay(struct flex *f, const struct chain *c)
{
	centreline_displace(colon_centreline(f->colon), c->span,
			    (const double(*)[3])f->y[c->first], c->count);
	memcpy(f->applied[c->first], f->y[c->first],
	       (size_t)c->count * sizeof(f->y[0]));
}

void flex_reset(struct flex *f)
{
	memset(f->y, 0, sizeof(f->y));
	memset(f->v, 0, sizeof(f->v));
	memset(f->force, 0, sizeof(f->force));
	memset(f->stiff, 0, sizeof(f->stiff));
	for (int i = 0; i < f->chains; i++) {
		lay(f, &f->chain[i]);
	}
}

void flex_set_params(struct flex *f, const struct flex_params *p)
{
	if (params_ok(p)) {
		f->par.damping_n_s_per_m = p->damping_n_s_per_m;
		f->par.chain_n_per_m = p->chain_n_per_m;
	}
}

void flex_clear(struct flex *f)
{
	memset(f->force, 0, sizeof(f->force));
	memset(f->stiff, 0, sizeof(f->stiff));
}

/* The chain holding material S_M, and where in it (0..1); NULL: fixed. */
static const struct chain *chain_at(const struct flex *f, double s_m,
				    double *x)
{
	for (int i = 0; i < f->chains; i++) {
		const struct chain *c = &f->chain[i];

		if (s_m > c->s0 && s_m < c->s1) {
			*x = (s_m - c->s0) / (c->s1 - c->s0);
			return c;
		}
	}
	return NULL;
}

void flex_push(struct flex *f, double s_m, const double force[3],
	       double stiffness_n_per_m)
{
	double x, w[2];
	const struct chain *c = chain_at(f, s_m, &x);
	int j;

	if (!c) {
		return;
	}
	centreline_knot_weights(x, c->count, &j, w);
	/* knots j, j + 1; knot k >= 1 is node k - 1, 0 and count + 1 are
	 * the fixed ends */
	for (int e = 0; e < 2; e++) {
		int k = j + e;

		if (k >= 1 && k <= c->count) {
			vec3_axpy(f->force[c->first + k - 1],
				  f->force[c->first + k - 1], w[e], force);
			f->stiff[c->first + k - 1] +=
				w[e] * fmax(stiffness_n_per_m, 0);
		}
	}
}

/*
 * One implicit step of chain C: (b/h + k_m + k_t + 2 k_c) y' - k_c
 * (y'_prev + y'_next) = (b/h + k_t) y + F per coordinate, the mesentery's
 * stiffening taken at the step's start, k_t the pushes' stiffness (the
 * push F - k_t (y' - y) as the wall yields); a tridiagonal solve
 * (Thomas).
 */
static void step_chain(struct flex *f, const struct chain *c, double h)
{
	double bh = f->par.damping_n_s_per_m / h, kc = f->par.chain_n_per_m;
	double cp[FLEX_MAX_NODES], dp[FLEX_MAX_NODES][3];

	for (int i = 0; i < c->count; i++) {
		int n = c->first + i;
		double q = vec3_norm(f->y[n]) / c->h;
		double kt = f->stiff[n];
		double diag = bh + kt + c->k * (1 + q * q) + 2 * kc;
		double denom = diag - (i > 0 ? kc * cp[i - 1] : 0);

		cp[i] = kc / denom; /* minus Thomas' c', the couplings -kc */
		for (int d = 0; d < 3; d++) {
			double rhs = (bh + kt) * f->y[n][d] + f->force[n][d];

			dp[i][d] = (rhs + (i > 0 ? kc * dp[i - 1][d] : 0)) /
				   denom;
		}
	}
	for (int i = c->count - 1; i >= 0; i--) {
		int n = c->first + i;

		for (int d = 0; d < 3; d++) {
			double y = dp[i][d] +
				   (i + 1 < c->count ?
					    cp[i] * f->y[n + 1][d] : 0);

			f->v[n][d] = (y - f->y[n][d]) / h;
			f->y[n][d] = y;
		}
	}
}

void flex_step(struct flex *f, double dt_s)
{
	for (int i = 0; i < f->chains; i++) {
		const struct chain *c = &f->chain[i];
		bool moved = false;

		step_chain(f, c, dt_s);
		for (int k = c->first; k < c->first + c->count && !moved; k++) {
			moved = vec3_dist(f->y[k], f->applied[k]) > FLEX_APPLY_M;
		}
		if (moved) {
			lay(f, c);
		}
	}
}

void flex_velocity(const struct flex *f, double s_m, double v[3])
{
	double x, w[2];
	const struct chain *c = chain_at(f, s_m, &x);
	int j;

	vec3_set(v, 0, 0, 0);
	if (!c) {
		return;
	}
	centreline_knot_weights(x, c->count, &j, w);
	for (int e = 0; e < 2; e++) {
		int k = j + e;

		if (k >= 1 && k <= c->count) {
			vec3_axpy(v, v, w[e], f->v[c->first + k - 1]);
		}
	}
}

int flex_nodes(const struct flex *f)
{
	return f->nodes;
}

int flex_span_nodes(const struct flex *f, int span)
{
	for (int i = 0; i < f->chains; i++) {
		if (f->chain[i].span == span) {
			return f->chain[i].count;
		}
	}
	return 0;
}

const double *flex_node(const struct flex *f, int i)
{
	return f->y[i];
}

void flex_span_forces(const struct flex *f, int span, double pushed[3],
		      double held[3])
{
	vec3_set(pushed, 0, 0, 0);
	vec3_set(held, 0, 0, 0);
	for (int i = 0; i < f->chains; i++) {
		const struct chain *c = &f->chain[i];
		int last = c->first + c->count - 1;

		if (c->span != span) {
			continue;
		}
		for (int k = c->first; k <= last; k++) {
			double q = vec3_norm(f->y[k]) / c->h;

			vec3_add(pushed, pushed, f->force[k]);
			vec3_axpy(held, held, c->k * (1 + q * q), f->y[k]);
		}
		/* the chain's pull on the fixed ends: k_c y at each */
		vec3_axpy(held, held, f->par.chain_n_per_m, f->y[c->first]);
		vec3_axpy(held, held, f->par.chain_n_per_m, f->y[last]);
	}
}

double flex_span_displacement(const struct flex *f, int span)
{
	double most = 0;

	for (int i = 0; i < f->chains; i++) {
		const struct chain *c = &f->chain[i];

		if (c->span != span) {
			continue;
		}
		for (int k = c->first; k < c->first + c->count; k++) {
			most = fmax(most, vec3_norm(f->y[k]));
		}
	}
	return most;
}
