/* flex.c - see flex.h. */
#include "model/flex.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"

struct chain {
	int span;          /* the centreline's */
	int first, count;  /* its nodes */
	double s0, s1;     /* m, material */
	double k;          /* mesentery per node, N/m */
	double mass;       /* per node, kg */
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
	double along[FLEX_MAX_NODES][3];   /* the course's tangent at rest */
	double rest[FLEX_MAX_NODES][3];    /* the node's place at rest */
	double g[3];                       /* gravity, m/s^2 */
	struct flex_pad pad;
	double pad_n;                      /* what the pad held, N */
	bool held[FLEX_MAX_NODES];         /* under the pad: in its grip */
	double anchor[FLEX_MAX_NODES][3];  /* where it holds it, m */
	double grip[FLEX_MAX_NODES][3];    /* the pad's force on it, N */
	double z[FLEX_MAX_NODES][3];       /* the step's new displacement */
};

static bool params_ok(const struct flex_params *p)
{
	return p->node_spacing_m >= 0.005 && p->node_spacing_m <= 0.2 &&
	       p->mass_per_m_kg >= 0 && p->mass_per_m_kg < 100 &&
	       p->damping_n_s_per_m > 0 && p->damping_n_s_per_m < 1e6 &&
	       p->chain_n_per_m >= 0 && p->chain_n_per_m < 1e6 &&
	       p->bending_n_per_m >= 0 && p->bending_n_per_m < 1e7;
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
		c->mass = f->par.mass_per_m_kg * (c->s1 - c->s0) / (count + 1);
		c->h = r->max_bow_m;
		for (int k = 0; k < count; k++) {
			double s_m = c->s0 + (c->s1 - c->s0) * (k + 1) /
					       (count + 1);
			size_t at = (size_t)lround(s_m / centreline_step(cl));

			vec3_copy(f->along[f->nodes + k],
				  centreline_base(cl, at)->t);
			vec3_copy(f->rest[f->nodes + k],
				  centreline_base(cl, at)->p);
		}
		f->nodes += count;
		f->chains++;
	}
	flex_reset(f);
}

void flex_destroy(struct flex *f)
{
	free(f);
}

static bool pad_on(const struct flex *f)
{
	return f->pad.on && f->pad.force_n > 0;
}

/* Whether node N's place at rest lies within the pad's reach (within its
 * radius of its axis, at any depth); its depth beyond the pad's face into
 * DEPTH (m, < 0 on the abdominal wall's side). */
static bool pad_reach(const struct flex *f, int n, double *depth)
{
	const struct flex_pad *p = &f->pad;
	double r[3];

	vec3_sub(r, f->rest[n], p->point);
	*depth = vec3_dot(r, p->in);
	vec3_axpy(r, r, -*depth, p->in);         /* off the pad's axis */
	return vec3_norm(r) <= p->radius_m;
}

/* Node N's displacement Y, DEPTH in front of the pad's face, put back onto
 * it across the course (as the mesentery lets it move); left where the
 * course runs along the press (it cannot be). */
static void pad_onto_face(const struct flex *f, int n, double y[3],
			  double depth)
{
	double across[3], a;

	vec3_axpy(across, f->pad.in, -vec3_dot(f->pad.in, f->along[n]),
		  f->along[n]);
	a = vec3_dot(across, f->pad.in);         /* 1 - (in . t)^2 */
	if (a >= 0.1) {
		vec3_axpy(y, y, -depth / a, across);
	}
}

/* The nodes the pad holds: those whose course at rest lies within its
 * reach, each towards its place at rest, put back onto the pad's face
 * where that lies in front of it. */
static void pad_place(struct flex *f)
{
	double depth;

	for (int n = 0; n < f->nodes; n++) {
		f->held[n] = pad_on(f) && pad_reach(f, n, &depth);
		vec3_set(f->anchor[n], 0, 0, 0);
		if (f->held[n] && depth < 0) {
			pad_onto_face(f, n, f->anchor[n], depth);
		}
	}
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
	pad_place(f);
	f->pad_n = 0;
	for (int i = 0; i < f->chains; i++) {
		lay(f, &f->chain[i]);
	}
}

void flex_set_params(struct flex *f, const struct flex_params *p)
{
	if (params_ok(p)) {
		f->par.damping_n_s_per_m = p->damping_n_s_per_m;
		f->par.chain_n_per_m = p->chain_n_per_m;
		f->par.bending_n_per_m = p->bending_n_per_m;
		for (int i = 0; i < f->chains; i++) {
			struct chain *c = &f->chain[i];

			c->mass = p->mass_per_m_kg * (c->s1 - c->s0) /
				  (c->count + 1);
		}
		f->par.mass_per_m_kg = p->mass_per_m_kg;
	}
}

void flex_set_gravity(struct flex *f, const double g[3])
{
	vec3_copy(f->g, g);
}

/* Whether two pads press alike: where, which way, how wide, how hard. */
static bool same_pad(const struct flex_pad *a, const struct flex_pad *b)
{
	return a->on == b->on && a->radius_m == b->radius_m &&
	       a->force_n == b->force_n &&
	       !memcmp(a->point, b->point, sizeof(a->point)) &&
	       !memcmp(a->in, b->in, sizeof(a->in));
}

void flex_set_pad(struct flex *f, const struct flex_pad *pad)
{
	if (same_pad(&f->pad, pad)) {
		return;
	}
	f->pad = *pad;
	pad_place(f);
	f->pad_n = 0;
}

double flex_pad_force(const struct flex *f)
{
	return f->pad_n;
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

/* The grip's stiffness on each node held, N/m. */
static double pad_stiffness(const struct flex *f)
{
	return f->pad.force_n / FLEX_PAD_GIVE_M;
}

/*
 * One implicit step of chain C into f->z, per coordinate:
 *   (b/h + k_t + k_m + k_p) y' - k_c D2 y' + k_b D4 y'
 *       = (b/h + k_t) y + F + m g + k_p a + G
 * D2 and D4 the second and fourth differences along the chain with the
 * fixed colon beyond both ends (zero displacement and slope there), the
 * mesentery's stiffening taken at the step's start, k_t the pushes'
 * stiffness (the push F - k_t (y' - y) as the wall yields), and on a node
 * the pad holds either its grip's spring k_p towards the anchor a
 * (SPRING) or the force G it holds with (f->grip): a symmetric
 * pentadiagonal system, solved by its banded LDL^T. Each node's result is
 * put across the course (the mesentery keeps the colon on it).
 */
static void step_chain(struct flex *f, const struct chain *c, double h,
		       bool spring)
{
	double bh = f->par.damping_n_s_per_m / h, kc = f->par.chain_n_per_m;
	double kb = f->par.bending_n_per_m, kp = pad_stiffness(f);
	double l1[FLEX_MAX_NODES], l2[FLEX_MAX_NODES], dd[FLEX_MAX_NODES];
	double (*z)[3] = &f->z[c->first];
	int m = c->count;

	for (int i = 0; i < m; i++) {
		int n = c->first + i;
		double q = vec3_norm(f->y[n]) / c->h, kt = f->stiff[n];
		double k = f->held[n] && spring ? kp : 0;
		double a0 = bh + kt + c->k * (1 + q * q) + 2 * kc + 6 * kb + k;
		double a1 = -kc - 4 * kb, a2 = kb;

		l2[i] = i >= 2 ? a2 / dd[i - 2] : 0;
		l1[i] = i >= 1 ? (a1 - (i >= 2 ? l2[i] * l1[i - 1] *
							 dd[i - 2] : 0)) /
					 dd[i - 1] : 0;
		dd[i] = a0 - (i >= 1 ? l1[i] * l1[i] * dd[i - 1] : 0) -
			(i >= 2 ? l2[i] * l2[i] * dd[i - 2] : 0);
		for (int d = 0; d < 3; d++) {
			double pad = !f->held[n] ? 0 : spring ?
				     k * f->anchor[n][d] : f->grip[n][d];

			z[i][d] = (bh + kt) * f->y[n][d] + f->force[n][d] +
				  c->mass * f->g[d] + pad -
				  (i >= 1 ? l1[i] * z[i - 1][d] : 0) -
				  (i >= 2 ? l2[i] * z[i - 2][d] : 0);
		}
	}
	for (int i = m - 1; i >= 0; i--) {
		for (int d = 0; d < 3; d++) {
			z[i][d] = z[i][d] / dd[i] -
				  (i + 1 < m ? l1[i + 1] * z[i + 1][d] : 0) -
				  (i + 2 < m ? l2[i + 2] * z[i + 2][d] : 0);
		}
	}
	for (int i = 0; i < m; i++) {
		const double *t = f->along[c->first + i];

		vec3_axpy(z[i], z[i], -vec3_dot(z[i], t), t);
	}
}

/* The held nodes' grip forces added up into NET; returns how many. */
static int pad_net(const struct flex *f, double net[3])
{
	int held = 0;

	vec3_set(net, 0, 0, 0);
	for (int n = 0; n < f->nodes; n++) {
		if (f->held[n]) {
			vec3_add(net, net, f->grip[n]);
			held++;
		}
	}
	return held;
}

/*
 * The grip's forces bounded by the hand's, F: beyond it in all, the
 * excess taken off every node held alike (the pressed mass shifts as a
 * whole; the forces that press the colon's parts against each other and
 * cancel in the sum stay); then no node above F, and the sum again within
 * F (scaled down). Returns whether it changed any.
 */
static bool pad_bound(struct flex *f)
{
	double net[3], most = f->pad.force_n, sum;
	int held = pad_net(f, net);
	bool changed = false;

	sum = vec3_norm(net);
	if (sum > most) {
		vec3_scale(net, net, (1 - most / sum) / held);
		for (int n = 0; n < f->nodes; n++) {
			if (f->held[n]) {
				vec3_sub(f->grip[n], f->grip[n], net);
			}
		}
		changed = true;
	}
	for (int n = 0; n < f->nodes; n++) {
		double g = vec3_norm(f->grip[n]);

		if (f->held[n] && g > most) {
			vec3_scale(f->grip[n], f->grip[n], most / g);
			changed = true;
		}
	}
	pad_net(f, net);
	sum = vec3_norm(net);
	if (sum > most) {
		for (int n = 0; n < f->nodes; n++) {
			vec3_scale(f->grip[n], f->grip[n], most / sum);
		}
		changed = true;
	}
	return changed;
}

/*
 * After the chains' step with the grip's springs: each held node's force
 * from the pad; bounded (pad_bound()), the chains with a node held stepped
 * again under the forces as bounded. The pad's force: their sum.
 */
static void pad_grip(struct flex *f, double h)
{
	double kp = pad_stiffness(f), net[3];

	for (int n = 0; n < f->nodes; n++) {
		if (f->held[n]) {
			vec3_sub(f->grip[n], f->anchor[n], f->z[n]);
			vec3_scale(f->grip[n], f->grip[n], kp);
		}
	}
	if (pad_bound(f)) {
		for (int i = 0; i < f->chains; i++) {
			const struct chain *c = &f->chain[i];
			bool held = false;

			for (int n = c->first; n < c->first + c->count; n++) {
				held = held || f->held[n];
			}
			if (held) {
				step_chain(f, c, h, false);
			}
		}
	}
	pad_net(f, net);
	f->pad_n = vec3_norm(net);
}

void flex_step(struct flex *f, double dt_s)
{
	for (int i = 0; i < f->chains; i++) {
		step_chain(f, &f->chain[i], dt_s, true);
	}
	f->pad_n = 0;
	if (pad_on(f)) {
		pad_grip(f, dt_s);
	}
	for (int i = 0; i < f->chains; i++) {
		const struct chain *c = &f->chain[i];
		bool moved = false;

		for (int n = c->first; n < c->first + c->count; n++) {
			for (int d = 0; d < 3; d++) {
				f->v[n][d] = (f->z[n][d] - f->y[n][d]) / dt_s;
				f->y[n][d] = f->z[n][d];
			}
			moved = moved ||
				vec3_dist(f->y[n], f->applied[n]) > FLEX_APPLY_M;
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

/* Chain C's node K's displacement, 0 beyond its ends (the fixed colon). */
static const double *at(const struct flex *f, const struct chain *c, int k)
{
	static const double zero[3] = { 0, 0, 0 };

	return k < 0 || k >= c->count ? zero : f->y[c->first + k];
}

void flex_span_forces(const struct flex *f, int span, double pushed[3],
		      double held[3])
{
	double kc = f->par.chain_n_per_m, kb = f->par.bending_n_per_m;

	vec3_set(pushed, 0, 0, 0);
	vec3_set(held, 0, 0, 0);
	for (int i = 0; i < f->chains; i++) {
		const struct chain *c = &f->chain[i];

		if (c->span != span) {
			continue;
		}
		/* every node's elastic force: the mesentery's, the chain's
		 * and the wall's (D2, D4 with the fixed colon beyond), and
		 * along the course all of the push */
		for (int k = 0; k < c->count; k++) {
			int n = c->first + k;
			double q = vec3_norm(f->y[n]) / c->h, e[3];

			vec3_add(pushed, pushed, f->force[n]);
			vec3_axpy(pushed, pushed, c->mass, f->g);
			vec3_scale(e, f->y[n], c->k * (1 + q * q));
			for (int d = 0; d < 3; d++) {
				double d2 = at(f, c, k - 1)[d] -
					    2 * at(f, c, k)[d] +
					    at(f, c, k + 1)[d];
				double d4 = at(f, c, k - 2)[d] -
					    4 * at(f, c, k - 1)[d] +
					    6 * at(f, c, k)[d] -
					    4 * at(f, c, k + 1)[d] +
					    at(f, c, k + 2)[d];

				e[d] += -kc * d2 + kb * d4;
			}
			/* across the course the elastic force, along it the
			 * mesentery takes the push */
			vec3_axpy(e, e, -vec3_dot(e, f->along[n]), f->along[n]);
			vec3_add(held, held, e);
			vec3_axpy(held, held,
				  vec3_dot(f->force[n], f->along[n]) +
					  c->mass * vec3_dot(f->g, f->along[n]),
				  f->along[n]);
		}
	}
}

/* Span SPAN's largest node displacement (*MOST, m) and its mesentery's
 * pulls summed (*TENSION, N). */
static void span_stretch(const struct flex *f, int span, double *most,
			 double *tension)
{
	*most = 0;
	*tension = 0;
	for (int i = 0; i < f->chains; i++) {
		const struct chain *c = &f->chain[i];

		if (c->span != span) {
			continue;
		}
		for (int k = c->first; k < c->first + c->count; k++) {
			double y = vec3_norm(f->y[k]), q = y / c->h;

			*most = fmax(*most, y);
			*tension += c->k * (1 + q * q) * y;
		}
	}
}

double flex_span_tension(const struct flex *f, int span)
{
	double most, tension;

	span_stretch(f, span, &most, &tension);
	return tension;
}

double flex_span_displacement(const struct flex *f, int span)
{
	double most, tension;

	span_stretch(f, span, &most, &tension);
	return most;
}
