/* lod.c - see lod.h. */
#include "viewer/lod.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const double lod_step_m[LOD_LEVELS] = { 0.002, 0.004, 0.008, 0.016, 0.008 };
const uint32_t lod_ring[LOD_LEVELS] = { 32, 32, 32, 32, 16 };

/* The smallest divisor of RING that leaves at most TARGET vertices. */
static uint32_t vertex_stride(uint32_t ring, uint32_t target)
{
	for (uint32_t s = 1; s < ring; s++) {
		if (ring % s == 0 && ring / s <= target) {
			return s;
		}
	}
	return ring / 3 ? ring / 3 : 1;
}

static uint32_t gcd(uint32_t a, uint32_t b)
{
	while (b) {
		uint32_t r = a % b;

		a = b;
		b = r;
	}
	return a;
}

static void strides(struct lod *l, const struct mesh *m, uint32_t ring)
{
	l->column = 0;
	for (int k = 0; k < l->levels; k++) {
		double step = lod_step_m[k] / m->step_m;

		l->ring_stride[k] = step > 1 ? (uint32_t)lround(step) : 1;
		l->vertex_stride[k] = vertex_stride(ring, lod_ring[k]);
		l->column = gcd(l->vertex_stride[k], l->column);
	}
}

/* Where the levels are first made: every ring of the tube on the GPU. */
static uint32_t full_vertex(uint32_t ring, uint32_t i, uint32_t j)
{
	return i * (ring + 1) + j;
}

/* The first ring of segment K and the ring it runs to. */
static void segment_rings(const struct mesh *m, uint32_t k, uint32_t *a,
			  uint32_t *b)
{
	uint32_t last = (uint32_t)m->samples - 2; /* the last ring */

	*a = (uint32_t)lround(m->seg[k].s0_m / m->step_m);
	*b = k + 1 < m->segments ?
		     (uint32_t)lround(m->seg[k + 1].s0_m / m->step_m) : last;
	*b = *b < last ? *b : last;
}

static uint32_t *put_tri(uint32_t *out, uint32_t a, uint32_t b, uint32_t c)
{
	out[0] = a;
	out[1] = b;
	out[2] = c;
	return out + 3;
}

/* The strip from ring P to ring Q at vertex stride SV. */
static uint32_t *strip(uint32_t *out, uint32_t ring, uint32_t p, uint32_t q,
		       uint32_t sv)
{
	for (uint32_t j = 0; j < ring; j += sv) {
		uint32_t a = full_vertex(ring, p, j);
		uint32_t b = full_vertex(ring, q, j);
		uint32_t c = full_vertex(ring, p, j + sv);
		uint32_t d = full_vertex(ring, q, j + sv);

		out = put_tri(out, a, b, c);
		out = put_tri(out, b, d, c);
	}
	return out;
}

/* The cecum's dome: the last ring to the pole. */
static uint32_t *fan(uint32_t *out, const struct mesh *m, uint32_t ring,
		     uint32_t sv)
{
	uint32_t last = (uint32_t)m->samples - 2;
	uint32_t pole = full_vertex(ring, last + 1, 0);

	for (uint32_t j = 0; j < ring; j += sv) {
		out = put_tri(out, full_vertex(ring, last, j), pole,
			      full_vertex(ring, last, j + sv));
	}
	return out;
}

static uint32_t *tube_segment(uint32_t *out, const struct mesh *m,
			      uint32_t ring, uint32_t k, uint32_t sr,
			      uint32_t sv)
{
	uint32_t a, b;

	segment_rings(m, k, &a, &b);
	for (uint32_t p = a; p < b;) {
		uint32_t q = p + sr < b ? p + sr : b;

		out = strip(out, ring, p, q, sv);
		p = q;
	}
	if (k + 1 == m->segments) {
		out = fan(out, m, ring, sv);
	}
	return out;
}

/* Indices of every level, counted as tube_segment() writes them. */
static uint64_t tube_indices(const struct lod *l, const struct mesh *m,
			     uint32_t ring)
{
	uint64_t n = 0;

	for (int k = 0; k < l->levels; k++) {
		uint64_t per_ring = 6 * (uint64_t)(ring / l->vertex_stride[k]);

		for (uint32_t g = 0; g < m->segments; g++) {
			uint32_t a, b;

			segment_rings(m, g, &a, &b);
			n += per_ring * ((b - a + l->ring_stride[k] - 1) /
					 l->ring_stride[k]);
		}
		n += per_ring / 2; /* the fan */
	}
	return n;
}

static void fill_tube(struct lod *l, const struct mesh *m, uint32_t ring)
{
	uint32_t *out = l->index;

	for (int k = 0; k < l->levels; k++) {
		for (uint32_t g = 0; g < m->segments; g++) {
			struct lod_range *r = &l->range[k * l->segments + g];

			r->first = (uint32_t)(out - l->index);
			out = tube_segment(out, m, ring, g, l->ring_stride[k],
					   l->vertex_stride[k]);
			r->count = (uint32_t)(out - l->index) - r->first;
		}
	}
}

/* A row for each ring the indices use, in order. */
static void assign_rows(struct lod *l, const struct mesh *m)
{
	for (size_t i = 0; i < m->samples; i++) {
		l->row[i] = LOD_NO_ROW;
	}
	for (uint32_t k = 0; k < l->indices; k++) {
		l->row[l->index[k] / (l->ring + 1)] = 0;
	}
	l->rows = 0;
	for (size_t i = 0; i < m->samples; i++) {
		if (l->row[i] != LOD_NO_ROW) {
			l->row_sample[l->rows] = (uint32_t)i;
			l->row[i] = l->rows++;
		}
	}
}

/* The GPU's vertices: the rows' every column-th vertex and the pole; the
 * indices moved onto them. */
static void lay_out(struct lod *l, const struct mesh *m)
{
	uint32_t ring = l->ring;

	assign_rows(l, m);
	for (uint32_t k = 0; k < l->indices; k++) {
		uint32_t v = l->index[k];

		l->index[k] = lod_vertex(l, v / (ring + 1), v % (ring + 1));
	}
	l->vertices = (l->rows - 1) * (ring / l->column + 1) + 1; /* the pole
								     alone */
	for (uint32_t r = 0; r + 1 < l->rows; r++) {
		uint32_t first = l->row_sample[r] * ring;

		for (uint32_t j = 0; j < ring; j += l->column) {
			l->drawn[first + j] = 1;
		}
	}
	l->drawn[m->vertices - 1] = 1; /* the pole */
}

static void fill_mesh(struct lod *l, const struct mesh *m)
{
	memcpy(l->index, m->tri, (size_t)m->triangles * sizeof(*m->tri));
	for (uint32_t g = 0; g < m->segments; g++) {
		l->range[g].first = 3 * m->seg[g].first;
		l->range[g].count = 3 * m->seg[g].count;
	}
}

static int make_layout(struct lod *l, const struct mesh *m)
{
	l->row = malloc(m->samples * sizeof(*l->row));
	l->row_sample = malloc(m->samples * sizeof(*l->row_sample));
	l->drawn = calloc(m->vertices, sizeof(*l->drawn));
	return l->row && l->row_sample && l->drawn ? 0 : -ENOMEM;
}

struct lod *lod_create(const struct mesh *m, uint32_t ring)
{
	struct lod *l = calloc(1, sizeof(*l));
	uint64_t n;

	if (!l) {
		return NULL;
	}
	l->segments = m->segments;
	l->ring = ring;
	l->levels = ring ? LOD_LEVELS : 1;
	if (ring) {
		strides(l, m, ring);
	}
	n = ring ? tube_indices(l, m, ring) : 3 * (uint64_t)m->triangles;
	if (n >= UINT32_MAX) {
		goto fail;
	}
	l->indices = (uint32_t)n;
	l->index = malloc(n * sizeof(*l->index));
	l->range = calloc((size_t)l->levels * m->segments, sizeof(*l->range));
	if (!l->index || !l->range || (ring && make_layout(l, m))) {
		goto fail;
	}
	if (ring) {
		fill_tube(l, m, ring);
		lay_out(l, m);
	} else {
		fill_mesh(l, m);
		l->vertices = m->vertices;
	}
	return l;

fail:
	lod_destroy(l);
	return NULL;
}

void lod_destroy(struct lod *l)
{
	if (!l) {
		return;
	}
	free(l->index);
	free(l->range);
	free(l->row);
	free(l->row_sample);
	free(l->drawn);
	free(l);
}

uint32_t lod_source(const struct lod *l, uint32_t k, uint32_t *j)
{
	uint32_t per_row = l->ring / l->column + 1, around;

	if (!l->ring) {
		if (j) {
			*j = 0;
		}
		return k;
	}
	around = k % per_row * l->column;
	if (j) {
		*j = around;
	}
	return l->row_sample[k / per_row] * l->ring +
	       (around == l->ring ? 0 : around);
}

void lod_gpu_range(const struct lod *l, uint32_t first, uint32_t count,
		   uint32_t *k0, uint32_t *k1)
{
	uint32_t per_row = l->ring / l->column + 1, i0, i1;

	if (!l->ring) {
		*k0 = first;
		*k1 = first + count;
		return;
	}
	i0 = first / l->ring;
	i1 = (first + count - 1) / l->ring;
	while (i0 <= i1 && l->row[i0] == LOD_NO_ROW) {
		i0++;
	}
	while (i1 > i0 && l->row[i1] == LOD_NO_ROW) {
		i1--;
	}
	if (i0 > i1) {
		*k0 = *k1 = 0;
		return;
	}
	*k0 = l->row[i0] * per_row;
	*k1 = (l->row[i1] + 1) * per_row;
	*k1 = *k1 < l->vertices ? *k1 : l->vertices;
}

struct lod_range lod_segment(const struct lod *l, int level, uint32_t k)
{
	level = level < 0 ? 0 : level >= l->levels ? l->levels - 1 : level;
	return l->range[level * l->segments + k];
}

struct lod_range lod_span(const struct lod *l, int level, uint32_t k0,
			  uint32_t k1)
{
	struct lod_range a = lod_segment(l, level, k0);
	struct lod_range b = lod_segment(l, level, k1);

	return (struct lod_range){ .first = a.first,
				   .count = b.first + b.count - a.first };
}
