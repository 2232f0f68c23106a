/* mesh.c - see mesh.h. */
#include "model/mesh.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"

#define BIND_MAX_M 0.15    /* farthest a wall vertex may be from its sample */
#define BIND_SPAN_M 0.05   /* a triangle's corners lie this close along s */
#define GRID_CELL_M 0.01
#define GRID_MAX_CELLS (1u << 21)

struct mesh *mesh_create(uint32_t vertices, uint32_t triangles,
			 size_t samples)
{
	struct mesh *m = calloc(1, sizeof(*m));

	if (!m) {
		return NULL;
	}
	m->vertices = vertices;
	m->triangles = triangles;
	m->samples = samples;
	m->pos = calloc(vertices, sizeof(*m->pos));
	m->nrm = calloc(vertices, sizeof(*m->nrm));
	m->off = calloc(vertices, sizeof(*m->off));
	m->noff = calloc(vertices, sizeof(*m->noff));
	m->sample_rho = calloc(samples, sizeof(*m->sample_rho));
	m->sample_axial = calloc(samples, sizeof(*m->sample_axial));
	m->near_lo = calloc(samples, sizeof(*m->near_lo));
	m->near_hi = calloc(samples, sizeof(*m->near_hi));
	m->sample_min = calloc(samples, sizeof(*m->sample_min));
	m->sample_max = calloc(samples, sizeof(*m->sample_max));
	m->radial = malloc(samples * sizeof(*m->radial));
	m->sample = calloc(vertices, sizeof(*m->sample));
	m->tri = calloc(triangles, sizeof(*m->tri));
	m->sample_first = calloc(samples + 1, sizeof(*m->sample_first));
	if (!m->pos || !m->nrm || !m->off || !m->noff || !m->sample_rho ||
	    !m->sample_axial || !m->near_lo || !m->near_hi || !m->sample_min || !m->sample_max ||
	    !m->sample || !m->tri || !m->sample_first || !m->radial) {
		mesh_destroy(m);
		return NULL;
	}
	for (size_t i = 0; i < samples; i++) {
		m->radial[i] = 1;
	}
	return m;
}

void mesh_destroy(struct mesh *m)
{
	if (!m) {
		return;
	}
	free(m->pos);
	free(m->nrm);
	free(m->off);
	free(m->noff);
	free(m->sample_rho);
	free(m->sample_axial);
	free(m->near_lo);
	free(m->near_hi);
	free(m->sample_min);
	free(m->sample_max);
	free(m->radial);
	free(m->sample);
	free(m->tri);
	free(m->sample_first);
	free(m->seg);
	free(m);
}

size_t mesh_bytes(const struct mesh *m)
{
	return sizeof(*m) +
	       (size_t)m->vertices * (4 * sizeof(*m->pos) + sizeof(uint32_t)) +
	       (size_t)m->triangles * sizeof(*m->tri) +
	       (4 * m->samples + 1) * sizeof(uint32_t) +
	       m->samples * (sizeof(*m->sample_min) + sizeof(*m->sample_max) +
			     sizeof(*m->radial)) +
	       m->segments * sizeof(*m->seg);
}

static uint32_t sample_segment(const struct mesh *m, double i);

/* ---------------------------------------------------------------- placing */

/*
 * The planes of samples J near I that a vertex of I could reach: those
 * whose plane comes within I's largest offset rho of r(I), i.e. where
 * (r(J) - r(I)).t(J) < rho |t(J) - (t(J).t(I)) t(I)|, turned less than a
 * right angle from t(I). Inside a bend of radius R < rho every such plane
 * up to pi R / 2 away passes within R: look as far.
 */
static void find_near(struct mesh *m, const struct centreline *cl, size_t i)
{
	const struct centreline_point *ci = centreline_sample(cl, i);
	double rho = m->sample_rho[i];
	size_t w = (size_t)ceil(M_PI_2 * rho / centreline_step(cl)) + 1;
	size_t lo = i > w ? i - w : 0;
	size_t hi = i + w < m->samples ? i + w : m->samples - 1;

	m->near_lo[i] = (uint32_t)i + 1;
	m->near_hi[i] = (uint32_t)i;
	for (size_t j = lo; j <= hi; j++) {
		const struct centreline_point *cj = centreline_sample(cl, j);
		double x[3], side[3], gap;

		if (j == i || vec3_dot(cj->t, ci->t) <= 0) {
			continue; /* turned a right angle or more away */
		}
		vec3_sub(x, cj->p, ci->p);
		gap = fabs(vec3_dot(x, cj->t));
		vec3_axpy(side, cj->t, -vec3_dot(cj->t, ci->t), ci->t);
		if (gap < rho * vec3_norm(side)) {
			m->near_lo[i] = j < m->near_lo[i] ? (uint32_t)j
							  : m->near_lo[i];
			m->near_hi[i] = (uint32_t)j;
		}
	}
}

/* The longest offset along D (unit, normal to t(I)) from BASE that keeps
 * the vertex MESH_FOLD_MARGIN of the way to each near plane. */
static double fold_reach(const struct mesh *m, const struct centreline *cl,
			 size_t i, const double base[3], const double d[3],
			 double rho)
{
	const double *ti = centreline_sample(cl, i)->t;

	for (size_t j = m->near_lo[i]; j <= m->near_hi[i]; j++) {
		const struct centreline_point *cj = centreline_sample(cl, j);
		double x[3], dt = vec3_dot(d, cj->t), gap;

		if (j == i || (j > i ? dt <= 0 : dt >= 0) ||
		    vec3_dot(cj->t, ti) <= 0) {
			continue; /* moving away from that plane */
		}
		vec3_sub(x, cj->p, base);
		gap = vec3_dot(x, cj->t);
		rho = fmin(rho, fmax(0, MESH_FOLD_MARGIN * gap / dt));
	}
	return rho;
}

/* Whether sample I's vertices are held between near planes. */
static bool holds_folds(const struct mesh *m, size_t i)
{
	return m->hold_folds && m->near_lo[i] <= m->near_hi[i];
}

/* Coordinate X of the point at (A, B, CC) in C's frame (t, u, v). */
static inline float frame_coord(const struct centreline_point *c, int x,
				double a, double b, double cc)
{
	return (float)(c->p[x] + a * c->t[x] + b * c->u[x] + cc * c->v[x]);
}

/* The point at (A, B, CC) in C's frame, as a float (written out: -O2
 * leaves a loop of three rolled, and the viewer places ~350 000 points at
 * a time). */
static inline void frame_point(const struct centreline_point *c, double a,
			       double b, double cc, float out[3])
{
	out[0] = frame_coord(c, 0, a, b, cc);
	out[1] = frame_coord(c, 1, a, b, cc);
	out[2] = frame_coord(c, 2, a, b, cc);
}

/* How much the near planes shorten offset O (not on the axis) of a
 * vertex of sample I (at C). */
static double fold_factor(const struct mesh *m, const struct centreline *cl,
			  size_t i, const struct centreline_point *c,
			  const float o[3])
{
	double b = o[1], cc = o[2], rho = sqrt(b * b + cc * cc);
	double base[3], d[3];

	vec3_axpy(base, c->p, o[0], c->t);
	vec3_scale(d, c->u, b / rho);
	vec3_axpy(d, d, cc / rho, c->v);
	return fold_reach(m, cl, i, base, d, rho) / rho;
}

/* Vertex J of sample I (at C) where mesh_place() puts it; FOLDS:
 * holds_folds(M, I). */
static inline void vertex_position(const struct mesh *m,
				   const struct centreline *cl, size_t i,
				   const struct centreline_point *c,
				   bool folds, uint32_t j, float out[3])
{
	const float *o = m->off[j];
	double b = o[1], cc = o[2], k = m->radial[i];

	if (folds && (b != 0 || cc != 0)) {
		k *= fold_factor(m, cl, i, c, o);
	}
	frame_point(c, o[0], b * k, cc * k, out);
}

static inline float least(float a, float b)
{
	return a < b ? a : b;
}

static inline float most(float a, float b)
{
	return a > b ? a : b;
}

/* Widens the box [LO, HI] to hold P; a NaN widens nothing. */
static inline void widen_box(float lo[3], float hi[3], const float p[3])
{
	lo[0] = least(p[0], lo[0]);
	lo[1] = least(p[1], lo[1]);
	lo[2] = least(p[2], lo[2]);
	hi[0] = most(p[0], hi[0]);
	hi[1] = most(p[1], hi[1]);
	hi[2] = most(p[2], hi[2]);
}

static void empty_box(float lo[3], float hi[3])
{
	for (int d = 0; d < 3; d++) {
		lo[d] = INFINITY;
		hi[d] = -INFINITY;
	}
}

/* X as a float no greater (DOWN) or no less than X. */
static float rounded(double x, bool down)
{
	float f = (float)x;

	if (down ? (double)f > x : (double)f < x) {
		f = nextafterf(f, down ? -INFINITY : INFINITY);
	}
	return f;
}

/*
 * Sample I's box (at C) from its ring rather than vertex by vertex: each
 * vertex lies at p + a t + k (b u + c v) with a within the sample's axial
 * offsets, |(b, c)| at most its largest offset and 0 <= k <= radial
 * (fold_factor() only shortens), so along axis x within
 * a t_x +/- radial rho |(u_x, v_x)| of p. Never smaller than the box of
 * the vertices as placed; larger by what held folds pull in.
 */
static void ring_box(const struct mesh *m, size_t i,
		     const struct centreline_point *c, float lo[3], float hi[3])
{
	double r = (double)m->radial[i] * m->sample_rho[i];
	double a0 = m->sample_axial[i][0], a1 = m->sample_axial[i][1];

	for (int x = 0; x < 3; x++) {
		double e = r * hypot(c->u[x], c->v[x]);
		double l = c->p[x] + fmin(a0 * c->t[x], a1 * c->t[x]) - e;
		double h = c->p[x] + fmax(a0 * c->t[x], a1 * c->t[x]) + e;

		if (!isfinite(l) || !isfinite(h)) {
			empty_box(lo, hi); /* as a NaN widens nothing */
			return;
		}
		lo[x] = rounded(l, true);
		hi[x] = rounded(h, false);
	}
}

/* Places sample I's vertices that KEEP marks (all without KEEP) and
 * bounds them: without KEEP every vertex as placed, with it the ring
 * (ring_box()), so that an unkept vertex costs nothing. */
static void place_sample(struct mesh *m, const struct centreline *cl,
			 size_t i, const uint8_t *keep)
{
	const struct centreline_point *c = centreline_sample(cl, i);
	bool folds = holds_folds(m, i);
	float lo[3], hi[3];

	empty_box(lo, hi);
	for (uint32_t j = m->sample_first[i]; j < m->sample_first[i + 1];
	     j++) {
		const float *n = m->noff[j];
		float p[3];

		if (keep && !keep[j]) {
			continue;
		}
		vertex_position(m, cl, i, c, folds, j, p);
		widen_box(lo, hi, p);
		for (int x = 0; x < 3; x++) {
			m->pos[j][x] = p[x];
			m->nrm[j][x] = (float)(n[0] * c->t[x] + n[1] * c->u[x] +
					       n[2] * c->v[x]);
		}
	}
	if (keep) {
		ring_box(m, i, c, lo, hi);
	}
	memcpy(m->sample_min[i], lo, sizeof(lo));
	memcpy(m->sample_max[i], hi, sizeof(hi));
}

/* Sample I's box from the positions as they are (an import at rest). */
static void sample_bounds(struct mesh *m, size_t i)
{
	empty_box(m->sample_min[i], m->sample_max[i]);
	for (uint32_t j = m->sample_first[i]; j < m->sample_first[i + 1];
	     j++) {
		widen_box(m->sample_min[i], m->sample_max[i], m->pos[j]);
	}
}

/* Segment K's box: its samples' and those of the next tri_span. */
static void segment_bounds(struct mesh *m, uint32_t k, double ds)
{
	struct mesh_segment *sg = &m->seg[k];
	size_t first = (size_t)lround(sg->s0_m / ds);
	size_t last = (size_t)lround(sg->s1_m / ds) + m->tri_span;

	if (last >= m->samples) {
		last = m->samples - 1;
	}
	empty_box(sg->min, sg->max);
	for (size_t i = first; i <= last; i++) {
		const float *lo = m->sample_min[i], *hi = m->sample_max[i];

		for (int d = 0; d < 3; d++) {
			sg->min[d] = least(lo[d], sg->min[d]);
			sg->max[d] = most(hi[d], sg->max[d]);
		}
	}
}

static void place_samples(struct mesh *m, const struct centreline *cl,
			  size_t first, size_t last, const uint8_t *keep)
{
	for (size_t i = first; m->hold_folds && i <= last; i++) {
		find_near(m, cl, i);
	}
	for (size_t i = first; i <= last; i++) {
		place_sample(m, cl, i, keep);
	}
}

void mesh_place_kept(struct mesh *m, const struct centreline *cl,
		     size_t first, size_t last, const uint8_t *keep)
{
	double ds = centreline_step(cl);
	uint32_t k0, k1;

	first = first > m->reach ? first - m->reach : 0;
	last += m->reach;
	if (last >= m->samples) {
		last = m->samples - 1;
	}
	place_samples(m, cl, first, last, keep);
	k0 = mesh_segment_at(m, ((double)first - (double)m->tri_span) * ds);
	k1 = mesh_segment_at(m, (double)last * ds);
	for (uint32_t k = k0; k <= k1; k++) {
		segment_bounds(m, k, ds);
	}
}

void mesh_place(struct mesh *m, const struct centreline *cl, size_t first,
		size_t last)
{
	mesh_place_kept(m, cl, first, last, NULL);
}

void mesh_vertex_at(const struct mesh *m, const struct centreline *cl,
		    uint32_t j, float p[3])
{
	size_t i = m->sample[j];

	vertex_position(m, cl, i, centreline_sample(cl, i), holds_folds(m, i),
			j, p);
}

uint32_t mesh_segment_at(const struct mesh *m, double s_m)
{
	return sample_segment(m, round(s_m / m->step_m));
}

void mesh_range(const struct mesh *m, double s0_m, double s1_m,
		uint32_t *first, uint32_t *count)
{
	uint32_t k0 = mesh_segment_at(m, s0_m), k1 = mesh_segment_at(m, s1_m);

	if (k1 < k0) {
		uint32_t k = k0;

		k0 = k1;
		k1 = k;
	}
	*first = m->seg[k0].first;
	*count = m->seg[k1].first + m->seg[k1].count - *first;
}

/* ---------------------------------------------------------------- binding */

/* Centreline samples bucketed in cubes of side h, for nearest searches. */
struct grid {
	double lo[3], h;
	int dim[3];
	uint32_t *start; /* cell c: items[start[c] .. start[c + 1]) */
	uint32_t *items;
};

static int grid_cell(const struct grid *g, const double p[3], int c[3])
{
	for (int d = 0; d < 3; d++) {
		/* clamped as a double: a point far out (an imported mesh's
		 * 1e300) or not finite has no int cell */
		double x = floor((p[d] - g->lo[d]) / g->h);

		c[d] = !(x >= 0) ? 0 : x >= g->dim[d] ? g->dim[d] - 1 : (int)x;
	}
	return (c[2] * g->dim[1] + c[1]) * g->dim[0] + c[0];
}

static void grid_free(struct grid *g)
{
	free(g->start);
	free(g->items);
}

static int grid_build(struct grid *g, const struct centreline *cl)
{
	size_t n = centreline_count(cl), cells;
	double hi[3];
	int c[3];

	vec3_copy(g->lo, centreline_base(cl, 0)->p);
	vec3_copy(hi, g->lo);
	for (size_t i = 1; i < n; i++) {
		for (int d = 0; d < 3; d++) {
			g->lo[d] = fmin(g->lo[d], centreline_base(cl, i)->p[d]);
			hi[d] = fmax(hi[d], centreline_base(cl, i)->p[d]);
		}
	}
	g->h = GRID_CELL_M;
	while ((hi[0] - g->lo[0] + g->h) * (hi[1] - g->lo[1] + g->h) *
		       (hi[2] - g->lo[2] + g->h) / (g->h * g->h * g->h) >
	       GRID_MAX_CELLS) {
		g->h *= 2;
	}
	cells = 1;
	for (int d = 0; d < 3; d++) {
		g->dim[d] = (int)((hi[d] - g->lo[d]) / g->h) + 1;
		cells *= (size_t)g->dim[d];
	}
	g->start = calloc(cells + 1, sizeof(*g->start));
	g->items = malloc(n * sizeof(*g->items));
	if (!g->start || !g->items) {
		grid_free(g);
		return -ENOMEM;
	}
	for (size_t i = 0; i < n; i++) {
		g->start[grid_cell(g, centreline_base(cl, i)->p, c) + 1]++;
	}
	for (size_t k = 0; k < cells; k++) {
		g->start[k + 1] += g->start[k];
	}
	for (size_t i = 0; i < n; i++) {
		int k = grid_cell(g, centreline_base(cl, i)->p, c);

		g->items[g->start[k]++] = (uint32_t)i;
	}
	memmove(g->start + 1, g->start, cells * sizeof(*g->start));
	g->start[0] = 0;
	return 0;
}

/* Visits the cells at Chebyshev distance R from cell C, updating BEST. */
static void grid_shell(const struct grid *g, const struct centreline *cl,
		       const double p[3], const int c[3], int r,
		       uint32_t *best, double *best_d2)
{
	for (int z = c[2] - r; z <= c[2] + r; z++) {
		for (int y = c[1] - r; y <= c[1] + r; y++) {
			for (int x = c[0] - r; x <= c[0] + r; x++) {
				int k;

				if (x < 0 || y < 0 || z < 0 || x >= g->dim[0] ||
				    y >= g->dim[1] || z >= g->dim[2] ||
				    (abs(x - c[0]) < r && abs(y - c[1]) < r &&
				     abs(z - c[2]) < r)) {
					continue;
				}
				k = (z * g->dim[1] + y) * g->dim[0] + x;
				for (uint32_t j = g->start[k];
				     j < g->start[k + 1]; j++) {
					double d[3], d2;

					vec3_sub(d, p, centreline_base(
						cl, g->items[j])->p);
					d2 = vec3_dot(d, d);
					if (d2 < *best_d2) {
						*best_d2 = d2;
						*best = g->items[j];
					}
				}
			}
		}
	}
}

/*
 * The nearest sample to P within BIND_MAX_M: after shell r, every sample
 * not yet seen is farther than r h from P's (clamped) cell, and clamping
 * P into the grid only brings it closer to any sample.
 */
static int grid_nearest(const struct grid *g, const struct centreline *cl,
			const double p[3], uint32_t *best)
{
	double best_d2 = INFINITY;
	int c[3], rmax = (int)ceil(BIND_MAX_M / g->h) + 1;

	grid_cell(g, p, c);
	for (int r = 0; r <= rmax; r++) {
		grid_shell(g, cl, p, c, r, best, &best_d2);
		if (sqrt(best_d2) <= r * g->h) {
			break;
		}
	}
	return sqrt(best_d2) <= BIND_MAX_M ? 0 : -ERANGE;
}

static void to_local(const struct centreline_point *c, const double x[3],
		     float out[3])
{
	out[0] = (float)vec3_dot(x, c->t);
	out[1] = (float)vec3_dot(x, c->u);
	out[2] = (float)vec3_dot(x, c->v);
}

/* The tangential offset of P from sample I, in steps. */
static double along(const struct centreline *cl, size_t i, const double p[3])
{
	const struct centreline_point *c = centreline_base(cl, i);
	double x[3];

	vec3_sub(x, p, c->p);
	return vec3_dot(x, c->t) / centreline_step(cl);
}

/* From sample I, walks to the sample whose normal plane is nearest P. */
static uint32_t normal_plane(const struct centreline *cl, uint32_t i,
			     const double p[3])
{
	size_t n = centreline_count(cl);
	double a = along(cl, i, p);
	int dir = a > 0 ? 1 : -1;

	while (fabs(a) > 0.5 && (dir > 0 ? i + 1 < n : i > 0)) {
		double next = along(cl, (size_t)((int64_t)i + dir), p);

		if (fabs(next) >= fabs(a)) {
			break;
		}
		i = (uint32_t)((int64_t)i + dir);
		a = next;
	}
	return i;
}

/* Gives every vertex its nearest sample and its offset from it. */
/* The sample nearest P among [LO, HI]. */
static uint32_t nearest_in(const struct centreline *cl, size_t lo, size_t hi,
			   const double p[3])
{
	size_t best = lo;

	for (size_t i = lo + 1; i <= hi; i++) {
		if (vec3_dist(centreline_base(cl, i)->p, p) <
		    vec3_dist(centreline_base(cl, best)->p, p)) {
			best = i;
		}
	}
	return (uint32_t)best;
}

static uint32_t median3(uint32_t a, uint32_t b, uint32_t c)
{
	return a < b ? (b < c ? b : a < c ? c : a) : (a < c ? a : b < c ? c : b);
}

/*
 * Where a wider lumen passes close to a narrower one, a wall vertex can be
 * nearer the other's centreline. Its triangle's other corners say where
 * it belongs: a corner far (in samples) from the triangle's median is
 * bound again near the median.
 */
static void rebind_strays(struct mesh *m, const struct centreline *cl)
{
	size_t w = (size_t)ceil(BIND_SPAN_M / centreline_step(cl));

	for (int pass = 0; pass < 4; pass++) {
		size_t changed = 0;

		for (uint32_t k = 0; k < m->triangles; k++) {
			const uint32_t *t = m->tri[k];
			size_t med = median3(m->sample[t[0]], m->sample[t[1]],
					     m->sample[t[2]]);

			for (int j = 0; j < 3; j++) {
				uint32_t *sj = &m->sample[t[j]];
				double p[3] = { m->pos[t[j]][0], m->pos[t[j]][1],
						m->pos[t[j]][2] };

				if (*sj + w >= med && *sj <= med + w) {
					continue;
				}
				*sj = nearest_in(cl, med > w ? med - w : 0,
						 med + w < m->samples ?
							 med + w :
							 m->samples - 1, p);
				*sj = normal_plane(cl, *sj, p);
				changed++;
			}
		}
		if (!changed) {
			return;
		}
	}
}

/* Gives every vertex its nearest sample and its offset from it. */
static int bind(struct mesh *m, const struct centreline *cl, char *err,
		size_t errsize)
{
	struct grid g;
	int r = grid_build(&g, cl);

	if (r) {
		return r;
	}
	for (uint32_t j = 0; j < m->vertices; j++) {
		double p[3] = { m->pos[j][0], m->pos[j][1], m->pos[j][2] };

		if (grid_nearest(&g, cl, p, &m->sample[j])) {
			snprintf(err, errsize, "vertex %u (%g, %g, %g) is more "
				 "than %g m from the centreline", j + 1, p[0],
				 p[1], p[2], BIND_MAX_M);
			grid_free(&g);
			return -EINVAL;
		}
		m->sample[j] = normal_plane(cl, m->sample[j], p);
	}
	grid_free(&g);
	rebind_strays(m, cl);
	for (uint32_t j = 0; j < m->vertices; j++) {
		const struct centreline_point *c = centreline_base(cl,
								  m->sample[j]);
		double x[3] = { m->pos[j][0] - c->p[0], m->pos[j][1] - c->p[1],
				m->pos[j][2] - c->p[2] };

		to_local(c, x, m->off[j]);
	}
	return 0;
}

static void face_normal(const struct mesh *m, uint32_t k, double n[3])
{
	const uint32_t *t = m->tri[k];
	double a[3], b[3], c[3], ab[3], ac[3];

	for (int d = 0; d < 3; d++) {
		a[d] = m->pos[t[0]][d];
		b[d] = m->pos[t[1]][d];
		c[d] = m->pos[t[2]][d];
	}
	vec3_sub(ab, b, a);
	vec3_sub(ac, c, a);
	vec3_cross(n, ab, ac);
}

/* Winds every triangle to face the centreline, as most already do. */
static void orient(struct mesh *m, const struct centreline *cl)
{
	size_t inward = 0;

	for (uint32_t k = 0; k < m->triangles; k++) {
		const uint32_t *t = m->tri[k];
		double n[3], x[3];

		face_normal(m, k, n);
		for (int d = 0; d < 3; d++) {
			x[d] = centreline_base(cl, m->sample[t[0]])->p[d] -
			       m->pos[t[0]][d];
		}
		inward += vec3_dot(n, x) > 0;
	}
	if (2 * inward >= m->triangles) {
		return;
	}
	for (uint32_t k = 0; k < m->triangles; k++) {
		uint32_t v = m->tri[k][1];

		m->tri[k][1] = m->tri[k][2];
		m->tri[k][2] = v;
	}
}

/* ---------------------------------------------------------------- order */

/* Orders the vertices by sample (stable) and fills sample_first. */
static int sort_vertices(struct mesh *m)
{
	uint32_t n = m->vertices, *at = malloc(n * sizeof(*at));
	float (*pos)[3] = malloc(n * sizeof(*pos));
	float (*off)[3] = malloc(n * sizeof(*off));
	uint32_t *sf = m->sample_first;

	if (!at || !pos || !off) {
		free(at);
		free(pos);
		free(off);
		return -ENOMEM;
	}
	memset(sf, 0, (m->samples + 1) * sizeof(*sf));
	for (uint32_t j = 0; j < n; j++) {
		sf[m->sample[j] + 1]++;
	}
	for (size_t i = 0; i < m->samples; i++) {
		sf[i + 1] += sf[i];
	}
	for (uint32_t j = 0; j < n; j++) {
		at[j] = sf[m->sample[j]]++;
		memcpy(pos[at[j]], m->pos[j], sizeof(*pos));
		memcpy(off[at[j]], m->off[j], sizeof(*off));
	}
	memmove(sf + 1, sf, m->samples * sizeof(*sf));
	sf[0] = 0;
	for (size_t i = 0; i < m->samples; i++) {
		for (uint32_t j = sf[i]; j < sf[i + 1]; j++) {
			m->sample[j] = (uint32_t)i;
		}
	}
	for (uint32_t k = 0; k < m->triangles; k++) {
		for (int c = 0; c < 3; c++) {
			m->tri[k][c] = at[m->tri[k][c]];
		}
	}
	memcpy(m->pos, pos, n * sizeof(*pos));
	memcpy(m->off, off, n * sizeof(*off));
	free(at);
	free(pos);
	free(off);
	return 0;
}

static uint32_t tri_low_sample(struct mesh *m, uint32_t k)
{
	const uint32_t *t = m->tri[k];
	uint32_t a = m->sample[t[0]], b = m->sample[t[1]], c = m->sample[t[2]];
	uint32_t lo = a < b ? a : b, hi = a < b ? b : a;

	lo = c < lo ? c : lo;
	hi = c > hi ? c : hi;
	if (hi - lo > m->tri_span) {
		m->tri_span = hi - lo;
	}
	return lo;
}

/* Orders the triangles by segment (stable) and fills the segment table. */
static int sort_triangles(struct mesh *m)
{
	uint32_t (*tri)[3] = malloc(m->triangles * sizeof(*tri));
	uint32_t *key = malloc(m->triangles * sizeof(*key));

	if (!tri || !key) {
		free(tri);
		free(key);
		return -ENOMEM;
	}
	for (uint32_t k = 0; k < m->triangles; k++) {
		key[k] = sample_segment(m, tri_low_sample(m, k));
		m->seg[key[k]].count++;
	}
	for (uint32_t s = 1; s < m->segments; s++) {
		m->seg[s].first = m->seg[s - 1].first + m->seg[s - 1].count;
	}
	for (uint32_t s = 0; s < m->segments; s++) {
		m->seg[s].count = 0;
	}
	for (uint32_t k = 0; k < m->triangles; k++) {
		struct mesh_segment *sg = &m->seg[key[k]];

		memcpy(tri[sg->first + sg->count++], m->tri[k], sizeof(*tri));
	}
	memcpy(m->tri, tri, m->triangles * sizeof(*tri));
	free(tri);
	free(key);
	return 0;
}

/*
 * Segments as runs of samples: sample I belongs to the segment holding
 * (I + 1/2) step, so a boundary never falls on a sample and a centreline
 * resampled a hair differently (an import) cuts the same runs. The last
 * segment is 0.5 to 1.5 segment_m long.
 */
static uint32_t sample_segment(const struct mesh *m, double i)
{
	double k = floor((i + 0.5) * m->step_m / m->segment_m);

	if (!(k > 0)) {
		return 0;
	}
	return k >= m->segments ? m->segments - 1 : (uint32_t)k;
}

static int make_segments(struct mesh *m, const struct centreline *cl,
			 double segment_m)
{
	double len = centreline_length(cl);

	m->segment_m = segment_m;
	m->step_m = centreline_step(cl);
	m->segments = (uint32_t)fmax(1, round(len / segment_m));
	m->seg = calloc(m->segments, sizeof(*m->seg));
	if (!m->seg) {
		return -ENOMEM;
	}
	for (size_t i = m->samples; i-- > 0;) {
		m->seg[sample_segment(m, (double)i)].s0_m = (double)i * m->step_m;
	}
	for (uint32_t k = 0; k < m->segments; k++) {
		m->seg[k].s1_m = k + 1 < m->segments ? m->seg[k + 1].s0_m : len;
	}
	return 0;
}

/* Area-weighted vertex normals, kept in the frames of their samples. */
static int normals(struct mesh *m, const struct centreline *cl)
{
	double (*acc)[3] = calloc(m->vertices, sizeof(*acc));

	if (!acc) {
		return -ENOMEM;
	}
	for (uint32_t k = 0; k < m->triangles; k++) {
		double n[3];

		face_normal(m, k, n);
		for (int c = 0; c < 3; c++) {
			vec3_add(acc[m->tri[k][c]], acc[m->tri[k][c]], n);
		}
	}
	for (uint32_t j = 0; j < m->vertices; j++) {
		vec3_normalize(acc[j]);
		to_local(centreline_base(cl, m->sample[j]), acc[j], m->noff[j]);
	}
	free(acc);
	return 0;
}

/* Each sample's largest offset and its axial offsets' range, and how
 * many samples the largest spans: the fold check's reach. */
static void set_reach(struct mesh *m, const struct centreline *cl,
		      enum mesh_finish_from from)
{
	float rho = 0;

	for (size_t i = 0; i < m->samples; i++) {
		float *ax = m->sample_axial[i];

		m->sample_rho[i] = 0;
		ax[0] = ax[1] = 0;
		for (uint32_t j = m->sample_first[i]; j < m->sample_first[i + 1];
		     j++) {
			m->sample_rho[i] = fmaxf(m->sample_rho[i],
						 hypotf(m->off[j][1],
							m->off[j][2]));
			ax[0] = fminf(ax[0], m->off[j][0]);
			ax[1] = fmaxf(ax[1], m->off[j][0]);
		}
		rho = fmaxf(rho, m->sample_rho[i]);
	}
	m->hold_folds = from == MESH_FROM_OFFSETS;
	m->reach = (uint32_t)ceil(M_PI_2 * rho / centreline_step(cl)) + 1;
}

int mesh_finish(struct mesh *m, const struct centreline *cl,
		double segment_m, enum mesh_finish_from from, char *err,
		size_t errsize)
{
	int r;

	if (m->vertices < 3 || !m->triangles) {
		snprintf(err, errsize, "mesh: no triangles");
		return -EINVAL;
	}
	if (from == MESH_FROM_POSITIONS) {
		r = bind(m, cl, err, errsize);
		if (r) {
			return r;
		}
		orient(m, cl);
	}
	r = sort_vertices(m);
	if (!r) {
		r = make_segments(m, cl, segment_m);
	}
	if (!r) {
		r = sort_triangles(m);
	}
	if (r) {
		snprintf(err, errsize, "mesh: out of memory");
		return r;
	}
	set_reach(m, cl, from);
	if (from == MESH_FROM_OFFSETS) {
		place_samples(m, cl, 0, m->samples - 1, NULL);
	}
	r = normals(m, cl);
	if (r) {
		snprintf(err, errsize, "mesh: out of memory");
		return r;
	}
	if (from == MESH_FROM_OFFSETS) {
		mesh_place(m, cl, 0, m->samples - 1);
	} else {
		/* at rest an import keeps the file's positions to the bit */
		for (size_t i = 0; i < m->samples; i++) {
			sample_bounds(m, i);
		}
		for (uint32_t k = 0; k < m->segments; k++) {
			segment_bounds(m, k, centreline_step(cl));
		}
	}
	return 0;
}
