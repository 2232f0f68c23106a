/* centreline.c - see centreline.h. */
#include "model/centreline.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"

#define MAX_PIECES (2 * CENTRELINE_MAX_SPANS + 1)
#define SPAN_MIN_STEPS 8

struct span {
	size_t a, b;      /* first and last sample of the span */
	double amplitude; /* m */
	double e[3];      /* bow direction */
	double u_end[3];  /* the undeformed frame's u at b */
};

/*
 * The turning angle and arc length are summed within pieces: the spans and
 * the fixed stretches between them. A bow recomputes its own piece and the
 * few prefix sums, never the samples of other pieces.
 */
struct piece {
	size_t first, last;
	double turn_before; /* rad, sum over earlier pieces */
	double len_before;  /* m */
};

struct centreline {
	size_t n;
	double ds;
	struct centreline_point *cur;
	struct centreline_point *base;
	double *turn_local; /* rad, within the sample's piece, up to it */
	double *len_local;  /* m, within the sample's piece, up to it */
	uint8_t *piece_of;
	struct piece piece[MAX_PIECES];
	int pieces;
	struct span span[CENTRELINE_MAX_SPANS];
	int spans;
};

/* ---------------------------------------------------------------- frames */

static void tangent(struct centreline_point *c, size_t i, size_t n)
{
	size_t lo = i ? i - 1 : 0, hi = i + 1 < n ? i + 1 : n - 1;

	vec3_sub(c[i].t, c[hi].p, c[lo].p);
	vec3_normalize(c[i].t);
}

static void curvature(struct centreline_point *c, size_t i, size_t n,
		      double ds)
{
	if (i == 0 || i + 1 >= n) {
		vec3_set(c[i].k, 0, 0, 0);
		return;
	}
	for (int d = 0; d < 3; d++) {
		c[i].k[d] = (c[i + 1].p[d] - 2 * c[i].p[d] + c[i - 1].p[d]) /
			    (ds * ds);
	}
}

/* Carries the frame of sample I to sample I + 1 (double reflection). */
static void reflect(struct centreline_point *c, size_t i)
{
	const struct centreline_point *a = &c[i];
	struct centreline_point *b = &c[i + 1];
	double v1[3], rl[3], tl[3], v2[3], c1, c2;

	vec3_sub(v1, b->p, a->p);
	c1 = vec3_dot(v1, v1);
	vec3_axpy(rl, a->u, -2 / c1 * vec3_dot(v1, a->u), v1);
	vec3_axpy(tl, a->t, -2 / c1 * vec3_dot(v1, a->t), v1);
	vec3_sub(v2, b->t, tl);
	c2 = vec3_dot(v2, v2);
	if (c2 > 1e-300) {
		vec3_axpy(b->u, rl, -2 / c2 * vec3_dot(v2, rl), v2);
	} else {
		vec3_copy(b->u, rl);
	}
	/* keep it exactly normal to t against rounding */
	vec3_axpy(b->u, b->u, -vec3_dot(b->u, b->t), b->t);
	vec3_normalize(b->u);
	vec3_cross(b->v, b->t, b->u);
}

static void first_frame(struct centreline_point *c, const double u0[3])
{
	double guess[3] = { 1, 0, 0 };

	if (u0) {
		vec3_copy(guess, u0);
	}
	vec3_axpy(c->u, guess, -vec3_dot(guess, c->t), c->t);
	if (vec3_normalize(c->u) < 1e-6) {
		/* U0 along the tangent, or the default was: take another */
		vec3_set(guess, fabs(c->t[0]) < 0.9 ? 1 : 0,
			 fabs(c->t[0]) < 0.9 ? 0 : 1, 0);
		vec3_axpy(c->u, guess, -vec3_dot(guess, c->t), c->t);
		vec3_normalize(c->u);
	}
	vec3_cross(c->v, c->t, c->u);
}

/* ---------------------------------------------------------------- pieces */

static double vertex_turn(const struct centreline *cl, size_t i)
{
	return vec3_norm(cl->cur[i].k) * cl->ds;
}

static double chord(const struct centreline *cl, size_t i)
{
	return i ? vec3_dist(cl->cur[i].p, cl->cur[i - 1].p) : 0;
}

/* Sums piece P's samples, then every piece's prefix. */
static void sum_piece(struct centreline *cl, int p)
{
	const struct piece *pc = &cl->piece[p];
	double turn = 0, len = 0;

	for (size_t i = pc->first; i <= pc->last; i++) {
		turn += vertex_turn(cl, i);
		len += chord(cl, i);
		cl->turn_local[i] = turn;
		cl->len_local[i] = len;
	}
	for (int q = 1; q < cl->pieces; q++) {
		const struct piece *prev = &cl->piece[q - 1];

		cl->piece[q].turn_before = prev->turn_before +
					   cl->turn_local[prev->last];
		cl->piece[q].len_before = prev->len_before +
					  cl->len_local[prev->last];
	}
}

static void add_piece(struct centreline *cl, size_t first, size_t last)
{
	struct piece *pc = &cl->piece[cl->pieces];

	*pc = (struct piece){ .first = first, .last = last };
	for (size_t i = first; i <= last; i++) {
		cl->piece_of[i] = (uint8_t)cl->pieces;
	}
	cl->pieces++;
}

/* Splits the samples into pieces around the spans and sums them all. */
static void build_pieces(struct centreline *cl)
{
	size_t next = 0;

	cl->pieces = 0;
	for (int k = 0; k < cl->spans; k++) {
		add_piece(cl, next, cl->span[k].a - 1);
		add_piece(cl, cl->span[k].a, cl->span[k].b);
		next = cl->span[k].b + 1;
	}
	add_piece(cl, next, cl->n - 1);
	for (int p = 0; p < cl->pieces; p++) {
		sum_piece(cl, p);
	}
}

/* ---------------------------------------------------------------- life */

static int check_points(const double (*pts)[3], size_t n, char *err,
			size_t errsize)
{
	if (n < CENTRELINE_MIN_SAMPLES) {
		snprintf(err, errsize, "centreline: %zu points, need at least "
			 "%d", n, CENTRELINE_MIN_SAMPLES);
		return -EINVAL;
	}
	for (size_t i = 0; i < n; i++) {
		if (!isfinite(pts[i][0]) || !isfinite(pts[i][1]) ||
		    !isfinite(pts[i][2])) {
			snprintf(err, errsize, "centreline: point %zu is not "
				 "finite", i + 1);
			return -EINVAL;
		}
		if (i && vec3_dist(pts[i], pts[i - 1]) <= 0) {
			snprintf(err, errsize, "centreline: point %zu repeats "
				 "point %zu", i + 1, i);
			return -EINVAL;
		}
	}
	return 0;
}

struct centreline *centreline_create(const double (*pts)[3], size_t n,
				     double step_m, const double u0[3],
				     char *err, size_t errsize)
{
	struct centreline *cl;

	if (check_points(pts, n, err, errsize)) {
		return NULL;
	}
	cl = calloc(1, sizeof(*cl));
	if (!cl) {
		goto nomem;
	}
	cl->n = n;
	cl->ds = step_m;
	cl->cur = calloc(n, sizeof(*cl->cur));
	cl->base = calloc(n, sizeof(*cl->base));
	cl->turn_local = calloc(n, sizeof(*cl->turn_local));
	cl->len_local = calloc(n, sizeof(*cl->len_local));
	cl->piece_of = calloc(n, sizeof(*cl->piece_of));
	if (!cl->cur || !cl->base || !cl->turn_local || !cl->len_local ||
	    !cl->piece_of) {
		goto free_cl;
	}
	for (size_t i = 0; i < n; i++) {
		vec3_copy(cl->cur[i].p, pts[i]);
	}
	for (size_t i = 0; i < n; i++) {
		tangent(cl->cur, i, n);
		curvature(cl->cur, i, n, step_m);
	}
	first_frame(&cl->cur[0], u0);
	for (size_t i = 0; i + 1 < n; i++) {
		reflect(cl->cur, i);
	}
	memcpy(cl->base, cl->cur, n * sizeof(*cl->cur));
	build_pieces(cl);
	return cl;

free_cl:
	centreline_destroy(cl);
nomem:
	snprintf(err, errsize, "centreline: out of memory (%zu samples)", n);
	return NULL;
}

void centreline_destroy(struct centreline *cl)
{
	if (!cl) {
		return;
	}
	free(cl->cur);
	free(cl->base);
	free(cl->turn_local);
	free(cl->len_local);
	free(cl->piece_of);
	free(cl);
}

double (*centreline_resample(const double (*pts)[3], size_t n, double step_m,
			     size_t *out_n, double *out_step_m))[3]
{
	double total = 0, walked = 0, (*out)[3];
	size_t steps, j = 0;

	for (size_t i = 1; i < n; i++) {
		total += vec3_dist(pts[i], pts[i - 1]);
	}
	steps = (size_t)ceil(total / step_m - 1e-9);
	if (n < 2 || !(step_m > 0) || steps + 1 < CENTRELINE_MIN_SAMPLES) {
		errno = EINVAL;
		return NULL;
	}
	out = malloc((steps + 1) * sizeof(*out));
	if (!out) {
		return NULL;
	}
	*out_step_m = total / (double)steps;
	for (size_t k = 0; k <= steps; k++) {
		double want = k == steps ? total : (double)k * *out_step_m;
		double len = vec3_dist(pts[j + 1], pts[j]);

		while (j + 2 < n && walked + len < want) {
			walked += len;
			j++;
			len = vec3_dist(pts[j + 1], pts[j]);
		}
		vec3_lerp(out[k], pts[j], pts[j + 1],
			  len > 0 ? fmin(1, (want - walked) / len) : 0);
	}
	*out_n = steps + 1;
	return out;
}

/* ---------------------------------------------------------------- spans */

/* Across the span, away from its chord; the frame's u if it is straight. */
static void bow_direction(const struct centreline *cl, struct span *sp)
{
	const double *pa = cl->base[sp->a].p, *pb = cl->base[sp->b].p;
	const struct centreline_point *mid = &cl->base[(sp->a + sp->b) / 2];
	double c[3], m[3];

	vec3_sub(c, pb, pa);
	vec3_normalize(c);
	vec3_lerp(m, pa, pb, 0.5);
	vec3_sub(sp->e, mid->p, m);
	vec3_axpy(sp->e, sp->e, -vec3_dot(sp->e, c), c);
	if (vec3_norm(sp->e) < 1e-3 * cl->ds) {
		vec3_axpy(sp->e, mid->u, -vec3_dot(mid->u, c), c);
	}
	vec3_normalize(sp->e);
}

int centreline_set_spans(struct centreline *cl, const double (*range)[2],
			 int count)
{
	size_t prev_b = 1;

	if (count < 0 || count > CENTRELINE_MAX_SPANS) {
		return -EINVAL;
	}
	for (int k = 0; k < count; k++) {
		double a = round(range[k][0] / cl->ds);
		double b = round(range[k][1] / cl->ds);

		if (!(a >= (double)prev_b + 2) || !(b <= (double)cl->n - 3) ||
		    b - a < SPAN_MIN_STEPS) {
			return -EINVAL;
		}
		prev_b = (size_t)b;
	}
	memcpy(cl->cur, cl->base, cl->n * sizeof(*cl->cur));
	cl->spans = count;
	for (int k = 0; k < count; k++) {
		struct span *sp = &cl->span[k];

		sp->a = (size_t)round(range[k][0] / cl->ds);
		sp->b = (size_t)round(range[k][1] / cl->ds);
		sp->amplitude = 0;
		vec3_copy(sp->u_end, cl->base[sp->b].u);
		bow_direction(cl, sp);
	}
	build_pieces(cl);
	return 0;
}

/* Rotates the frames of [A, B] about their tangents so that u at B is the
 * undeformed one again, the twist growing evenly along the span. */
static void untwist(struct centreline_point *c, const struct span *sp)
{
	const struct centreline_point *end = &c[sp->b];
	double want[3], x[3], twist;

	vec3_axpy(want, sp->u_end, -vec3_dot(sp->u_end, end->t), end->t);
	vec3_normalize(want);
	vec3_cross(x, end->u, want);
	twist = atan2(vec3_dot(x, end->t), vec3_dot(end->u, want));
	for (size_t i = sp->a; i <= sp->b; i++) {
		double f = (double)(i - sp->a + 1) / (double)(sp->b - sp->a + 1);

		vec3_rotate(c[i].u, c[i].u, c[i].t, twist * f);
		vec3_cross(c[i].v, c[i].t, c[i].u);
	}
}

/* The frames, curvatures and sums of span SP after its samples moved. */
static void reframe(struct centreline *cl, const struct span *sp)
{
	for (size_t i = sp->a; i <= sp->b; i++) {
		tangent(cl->cur, i, cl->n);
		curvature(cl->cur, i, cl->n, cl->ds);
	}
	for (size_t i = sp->a - 1; i < sp->b; i++) {
		reflect(cl->cur, i);
	}
	untwist(cl->cur, sp);
	sum_piece(cl, cl->piece_of[sp->a]);
}

int centreline_bow(struct centreline *cl, int k, double amplitude_m)
{
	struct span *sp;
	size_t len;

	if (k < 0 || k >= cl->spans || !isfinite(amplitude_m)) {
		return -EINVAL;
	}
	sp = &cl->span[k];
	sp->amplitude = amplitude_m;
	len = sp->b - sp->a;
	for (size_t i = sp->a + 1; i < sp->b; i++) {
		double w = sin(M_PI * (double)(i - sp->a) / (double)len);

		vec3_axpy(cl->cur[i].p, cl->base[i].p, amplitude_m * w * w,
			  sp->e);
	}
	reframe(cl, sp);
	return 0;
}

/* Knot J's displacement: NODE[J - 1] inside, 0 at both ends. */
static const double *knot(const double (*node)[3], int count, int j)
{
	static const double zero[3] = { 0, 0, 0 };

	return j < 1 || j > count ? zero : node[j - 1];
}

void centreline_knot_weights(double x, int count, int *j, double w[2])
{
	double f = x * (count + 1);

	*j = (int)floor(f);
	if (*j < 0) {
		*j = 0;
	} else if (*j > count) {
		*j = count;
	}
	w[1] = fmin(fmax(f - *j, 0), 1);
	w[0] = 1 - w[1];
}

int centreline_displace(struct centreline *cl, int k,
			const double (*node)[3], int count)
{
	struct span *sp;
	size_t len;

	if (k < 0 || k >= cl->spans || count < 1) {
		return -EINVAL;
	}
	for (int j = 0; j < count; j++) {
		if (!isfinite(node[j][0]) || !isfinite(node[j][1]) ||
		    !isfinite(node[j][2])) {
			return -EINVAL;
		}
	}
	sp = &cl->span[k];
	sp->amplitude = 0;
	len = sp->b - sp->a;
	for (size_t i = sp->a + 1; i < sp->b; i++) {
		double w[2], t, t2, t3, h[4], m0[3], m1[3], d[3];
		int j;

		centreline_knot_weights((double)(i - sp->a) / (double)len,
					count, &j, w);
		t = w[1];
		t2 = t * t;
		t3 = t2 * t;
		h[0] = 2 * t3 - 3 * t2 + 1;
		h[1] = t3 - 2 * t2 + t;
		h[2] = -2 * t3 + 3 * t2;
		h[3] = t3 - t2;
		/* Catmull-Rom tangents inside, none at the fixed ends */
		vec3_set(m0, 0, 0, 0);
		vec3_set(m1, 0, 0, 0);
		if (j >= 1) {
			vec3_sub(m0, knot(node, count, j + 1),
				 knot(node, count, j - 1));
			vec3_scale(m0, m0, 0.5);
		}
		if (j + 1 <= count) {
			vec3_sub(m1, knot(node, count, j + 2),
				 knot(node, count, j));
			vec3_scale(m1, m1, 0.5);
		}
		vec3_scale(d, knot(node, count, j), h[0]);
		vec3_axpy(d, d, h[1], m0);
		vec3_axpy(d, d, h[2], knot(node, count, j + 1));
		vec3_axpy(d, d, h[3], m1);
		vec3_add(cl->cur[i].p, cl->base[i].p, d);
	}
	reframe(cl, sp);
	return 0;
}

int centreline_spans(const struct centreline *cl)
{
	return cl->spans;
}

void centreline_span_range(const struct centreline *cl, int k, double *s0_m,
			   double *s1_m)
{
	*s0_m = (double)cl->span[k].a * cl->ds;
	*s1_m = (double)cl->span[k].b * cl->ds;
}

double centreline_bow_amplitude(const struct centreline *cl, int k)
{
	return cl->span[k].amplitude;
}

void centreline_bow_direction(const struct centreline *cl, int k, double e[3])
{
	vec3_copy(e, cl->span[k].e);
}

/* ---------------------------------------------------------------- queries */

size_t centreline_bytes(const struct centreline *cl)
{
	return sizeof(*cl) + cl->n * (2 * sizeof(*cl->cur) +
				      2 * sizeof(double) + sizeof(uint8_t));
}

size_t centreline_count(const struct centreline *cl)
{
	return cl->n;
}

double centreline_step(const struct centreline *cl)
{
	return cl->ds;
}

double centreline_length(const struct centreline *cl)
{
	return (double)(cl->n - 1) * cl->ds;
}

const struct centreline_point *centreline_sample(const struct centreline *cl,
						 size_t i)
{
	return &cl->cur[i];
}

const struct centreline_point *centreline_base(const struct centreline *cl,
					       size_t i)
{
	return &cl->base[i];
}

double centreline_turning(const struct centreline *cl, size_t i)
{
	return cl->piece[cl->piece_of[i]].turn_before + cl->turn_local[i];
}

double centreline_arclength(const struct centreline *cl, size_t i)
{
	return cl->piece[cl->piece_of[i]].len_before + cl->len_local[i];
}

double centreline_total_arclength(const struct centreline *cl)
{
	return centreline_arclength(cl, cl->n - 1);
}

/* Sample I's point and the one after, mixed by F, frame made orthonormal. */
static void interpolate(const struct centreline *cl, size_t i, double f,
			struct centreline_point *out)
{
	const struct centreline_point *a = &cl->cur[i];
	const struct centreline_point *b = &cl->cur[i + 1 < cl->n ? i + 1 : i];

	vec3_lerp(out->p, a->p, b->p, f);
	vec3_lerp(out->t, a->t, b->t, f);
	vec3_lerp(out->u, a->u, b->u, f);
	vec3_lerp(out->k, a->k, b->k, f);
	vec3_normalize(out->t);
	vec3_axpy(out->u, out->u, -vec3_dot(out->u, out->t), out->t);
	vec3_normalize(out->u);
	vec3_cross(out->v, out->t, out->u);
}

/* The last sample whose arc length is at most LEN_M (bisection). */
static size_t find_length(const struct centreline *cl, double len_m)
{
	size_t lo = 0, hi = cl->n - 1;

	while (hi - lo > 1) {
		size_t mid = lo + (hi - lo) / 2;

		if (centreline_arclength(cl, mid) <= len_m) {
			lo = mid;
		} else {
			hi = mid;
		}
	}
	return lo;
}

/* The sample I and fraction F at arc length LEN_M (clamped); HINT as in
 * the header. */
static size_t locate_length(const struct centreline *cl, double len_m,
			    double *f, size_t *hint)
{
	size_t i = hint && *hint < cl->n ? *hint : find_length(cl, len_m);
	double lo, hi;

	len_m = fmax(0, fmin(len_m, centreline_total_arclength(cl)));
	while (i > 0 && centreline_arclength(cl, i) > len_m) {
		i--;
	}
	while (i + 2 < cl->n && centreline_arclength(cl, i + 1) <= len_m) {
		i++;
	}
	if (i + 1 >= cl->n) {
		i = cl->n - 2;
	}
	lo = centreline_arclength(cl, i);
	hi = centreline_arclength(cl, i + 1);
	*f = hi > lo ? fmin(1, (len_m - lo) / (hi - lo)) : 0;
	if (hint) {
		*hint = i;
	}
	return i;
}

double centreline_at_length(const struct centreline *cl, double len_m,
			    struct centreline_point *out, size_t *hint)
{
	double f;
	size_t i = locate_length(cl, len_m, &f, hint);

	interpolate(cl, i, f, out);
	return ((double)i + f) * cl->ds;
}

void centreline_position_at_length(const struct centreline *cl, double len_m,
				   double out[3], size_t *hint)
{
	double f;
	size_t i = locate_length(cl, len_m, &f, hint);

	vec3_lerp(out, cl->cur[i].p, cl->cur[i + 1].p, f);
}

double centreline_at_s(const struct centreline *cl, double s_m,
		       struct centreline_point *out)
{
	double x = fmax(0, fmin(s_m / cl->ds, (double)(cl->n - 1)));
	size_t i = (size_t)x;
	double f;

	if (i + 1 >= cl->n) {
		i = cl->n - 2;
	}
	f = x - (double)i;
	interpolate(cl, i, f, out);
	return centreline_arclength(cl, i) +
	       f * (centreline_arclength(cl, i + 1) -
		    centreline_arclength(cl, i));
}
