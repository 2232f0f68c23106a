/* contact.c - see contact.h. */
#include "model/contact.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"

#define LEAF_TRIANGLES 4
#define STACK_DEPTH 64
#define BOX_SLACK 1e-6f /* m: boxes grown so tolerant hits stay inside */

struct node {
	float min[3], max[3];
	uint32_t first; /* leaf: into order[]; inner: the left child */
	uint32_t count; /* leaf: triangles; inner: 0 (right child first+1) */
};

struct segment {
	double s0, s1;
	uint32_t root;
	uint32_t first;     /* its triangles: order[first .. first + count) */
	uint32_t triangles;
};

/* A triangle's bounds and centroid, computed once for the tree's build. */
struct tri_box {
	float min[3], max[3], cen[3];
};

struct contact {
	uint32_t vertices, triangles, segments, nodes;
	float (*pos)[3];    /* vertices, m */
	float (*nrm)[3];    /* vertex normals */
	uint32_t (*tri)[3];
	uint32_t *order;    /* triangle indices in leaf order */
	float *key;         /* scratch while building */
	struct tri_box *tb; /* scratch while building, per triangle */
	struct node *node;
	struct segment *seg;
};

/* ------------------------------------------------------------ geometry */

static void vertex(const struct contact *c, uint32_t v, double out[3])
{
	vec3_set(out, c->pos[v][0], c->pos[v][1], c->pos[v][2]);
}

/* The plane of triangle T: unit normal into the lumen and offset. Returns
 * false for a degenerate triangle. */
static bool plane(const struct contact *c, uint32_t t, double n[3],
		  double *offset)
{
	double a[3], b[3], cc[3], e1[3], e2[3];

	vertex(c, c->tri[t][0], a);
	vertex(c, c->tri[t][1], b);
	vertex(c, c->tri[t][2], cc);
	vec3_sub(e1, b, a);
	vec3_sub(e2, cc, a);
	vec3_cross(n, e1, e2);
	if (vec3_normalize(n) < 1e-14) {
		return false;
	}
	*offset = vec3_dot(n, a);
	return true;
}

/* Barycentric coordinates of P (in the plane of T); true when inside,
 * within CONTACT_EDGE_TOLERANCE. */
static bool inside(const struct contact *c, uint32_t t, const double p[3],
		   double w[3])
{
	double a[3], b[3], cc[3], v0[3], v1[3], v2[3];
	double d00, d01, d11, d20, d21, den;

	vertex(c, c->tri[t][0], a);
	vertex(c, c->tri[t][1], b);
	vertex(c, c->tri[t][2], cc);
	vec3_sub(v0, b, a);
	vec3_sub(v1, cc, a);
	vec3_sub(v2, p, a);
	d00 = vec3_dot(v0, v0);
	d01 = vec3_dot(v0, v1);
	d11 = vec3_dot(v1, v1);
	d20 = vec3_dot(v2, v0);
	d21 = vec3_dot(v2, v1);
	den = d00 * d11 - d01 * d01;
	if (den <= 0) {
		return false;
	}
	w[1] = (d11 * d20 - d01 * d21) / den;
	w[2] = (d00 * d21 - d01 * d20) / den;
	w[0] = 1.0 - w[1] - w[2];
	return w[0] >= -CONTACT_EDGE_TOLERANCE &&
	       w[1] >= -CONTACT_EDGE_TOLERANCE &&
	       w[2] >= -CONTACT_EDGE_TOLERANCE;
}

/* ------------------------------------------------------------ building */

static float min2(float a, float b)
{
	return a < b ? a : b; /* fminf() is a call; the mesh is finite */
}

static float max2(float a, float b)
{
	return a > b ? a : b;
}

static void tri_boxes(struct contact *c)
{
	for (uint32_t t = 0; t < c->triangles; t++) {
		struct tri_box *b = &c->tb[t];

		for (int d = 0; d < 3; d++) {
			float p0 = c->pos[c->tri[t][0]][d];
			float p1 = c->pos[c->tri[t][1]][d];
			float p2 = c->pos[c->tri[t][2]][d];

			b->min[d] = min2(min2(p0, p1), p2);
			b->max[d] = max2(max2(p0, p1), p2);
			b->cen[d] = (p0 + p1 + p2) / 3.0f;
		}
	}
}

static void box_of(const struct contact *c, const uint32_t *tris, uint32_t n,
		   struct node *nd)
{
	for (int d = 0; d < 3; d++) {
		nd->min[d] = FLT_MAX;
		nd->max[d] = -FLT_MAX;
	}
	for (uint32_t i = 0; i < n; i++) {
		const struct tri_box *b = &c->tb[tris[i]];

		for (int d = 0; d < 3; d++) {
			nd->min[d] = min2(nd->min[d], b->min[d]);
			nd->max[d] = max2(nd->max[d], b->max[d]);
		}
	}
	for (int d = 0; d < 3; d++) {
		nd->min[d] -= BOX_SLACK;
		nd->max[d] += BOX_SLACK;
	}
}

static void swap_pair(float *key, uint32_t *tris, int64_t i, int64_t j)
{
	float k = key[i];
	uint32_t t = tris[i];

	key[i] = key[j];
	key[j] = k;
	tris[i] = tris[j];
	tris[j] = t;
}

static float median3(float a, float b, float c)
{
	return max2(min2(a, b), min2(max2(a, b), c));
}

/*
 * Reorders TRIS (with their KEYs) so that the N/2 smallest keys come first:
 * quickselect with a three-way partition, linear even when many keys are
 * equal (the triangles of a ring often are).
 */
static void split_median(float *key, uint32_t *tris, int64_t n)
{
	int64_t lo = 0, hi = n - 1, k = n / 2;

	while (lo < hi) {
		float pv = median3(key[lo], key[lo + (hi - lo) / 2], key[hi]);
		int64_t lt = lo, i = lo, gt = hi;

		while (i <= gt) {
			if (key[i] < pv) {
				swap_pair(key, tris, lt++, i++);
			} else if (key[i] > pv) {
				swap_pair(key, tris, i, gt--);
			} else {
				i++;
			}
		}
		if (k < lt) {
			hi = lt - 1;
		} else if (k > gt) {
			lo = gt + 1;
		} else {
			return;
		}
	}
}

static int longest_axis(const struct node *nd)
{
	float ext[3];

	for (int d = 0; d < 3; d++) {
		ext[d] = nd->max[d] - nd->min[d];
	}
	return ext[0] >= ext[1] && ext[0] >= ext[2] ? 0 : ext[1] >= ext[2] ? 1
									    : 2;
}

/* Builds the subtree over order[first .. first + n) at node I. */
static void build(struct contact *c, uint32_t i, uint32_t first, uint32_t n)
{
	struct node *nd = &c->node[i];

	box_of(c, c->order + first, n, nd);
	if (n <= LEAF_TRIANGLES) {
		nd->first = first;
		nd->count = n;
		return;
	}
	int axis = longest_axis(nd);

	for (uint32_t k = 0; k < n; k++) {
		c->key[k] = c->tb[c->order[first + k]].cen[axis];
	}
	split_median(c->key, c->order + first, n);
	nd->first = c->nodes;
	nd->count = 0;
	c->nodes += 2;
	build(c, nd->first, first, n / 2);
	build(c, c->node[i].first + 1, first + n / 2, n - n / 2);
}

static int copy_mesh(struct contact *c, const float (*pos)[3],
		     const float (*nrm)[3], const uint32_t (*tri)[3])
{
	c->pos = malloc(c->vertices * sizeof(*c->pos));
	c->nrm = malloc(c->vertices * sizeof(*c->nrm));
	c->tri = malloc(c->triangles * sizeof(*c->tri));
	c->order = malloc(c->triangles * sizeof(*c->order));
	/* a binary tree with leaves of >= 1 triangle: < 2 n nodes */
	c->node = malloc((2 * (size_t)c->triangles + c->segments) *
			 sizeof(*c->node));
	c->seg = malloc(c->segments * sizeof(*c->seg));
	c->key = malloc(c->triangles * sizeof(*c->key));
	c->tb = malloc(c->triangles * sizeof(*c->tb));
	if (!c->pos || !c->nrm || !c->tri || !c->order || !c->node ||
	    !c->seg || !c->key || !c->tb) {
		return -1;
	}
	memcpy(c->pos, pos, c->vertices * sizeof(*c->pos));
	memcpy(c->nrm, nrm, c->vertices * sizeof(*c->nrm));
	for (uint32_t t = 0; t < c->triangles; t++) {
		for (int k = 0; k < 3; k++) {
			if (tri[t][k] >= c->vertices) {
				return -1;
			}
			c->tri[t][k] = tri[t][k];
		}
		c->order[t] = t;
	}
	tri_boxes(c);
	return 0;
}

struct contact *contact_create(const float (*pos)[3], const float (*nrm)[3],
			       uint32_t vertices, const uint32_t (*tri)[3],
			       uint32_t triangles,
			       const struct mesh_segment *seg,
			       uint32_t segments)
{
	struct contact *c = calloc(1, sizeof(*c));

	if (!c) {
		return NULL;
	}
	c->vertices = vertices;
	c->triangles = triangles;
	c->segments = segments;
	if (copy_mesh(c, pos, nrm, tri)) {
		contact_destroy(c);
		return NULL;
	}
	for (uint32_t s = 0; s < segments; s++) {
		c->seg[s] = (struct segment){ .s0 = seg[s].s0_m,
					      .s1 = seg[s].s1_m,
					      .root = c->nodes,
					      .first = seg[s].first,
					      .triangles = seg[s].count };
		if (seg[s].first + (uint64_t)seg[s].count > triangles) {
			contact_destroy(c);
			return NULL;
		}
		c->nodes++;
		if (seg[s].count) {
			build(c, c->seg[s].root, seg[s].first, seg[s].count);
		}
	}
	free(c->key);
	free(c->tb);
	c->key = NULL;
	c->tb = NULL;
	return c;
}

void contact_destroy(struct contact *c)
{
	if (!c) {
		return;
	}
	free(c->pos);
	free(c->nrm);
	free(c->tri);
	free(c->order);
	free(c->key);
	free(c->tb);
	free(c->node);
	free(c->seg);
	free(c);
}

size_t contact_bytes(const struct contact *c)
{
	return sizeof(*c) +
	       c->vertices * (sizeof(*c->pos) + sizeof(*c->nrm)) +
	       c->triangles * (sizeof(*c->tri) + sizeof(*c->order)) +
	       (2 * (size_t)c->triangles + c->segments) * sizeof(*c->node) +
	       c->segments * sizeof(*c->seg);
}

/* ------------------------------------------------------------ queries */

/* Does the segment A + u D, u in [0, UMAX], meet the box? */
static bool segment_meets_box(const struct node *nd, const double a[3],
			      const double d[3], double umax)
{
	double lo = 0, hi = umax;

	for (int k = 0; k < 3; k++) {
		if (fabs(d[k]) < 1e-300) {
			if (a[k] < nd->min[k] || a[k] > nd->max[k]) {
				return false;
			}
			continue;
		}
		double t0 = (nd->min[k] - a[k]) / d[k];
		double t1 = (nd->max[k] - a[k]) / d[k];

		if (t0 > t1) {
			double t = t0;

			t0 = t1;
			t1 = t;
		}
		lo = fmax(lo, t0);
		hi = fmin(hi, t1);
		if (lo > hi) {
			return false;
		}
	}
	return true;
}

static bool skipped(uint32_t t, const uint32_t *skip, int n_skip)
{
	for (int i = 0; i < n_skip; i++) {
		if (skip[i] == t) {
			return true;
		}
	}
	return false;
}

/*
 * Tests triangle T against A -> B; keeps it in *HIT if it is the first. The
 * path crosses T when it starts in front of its plane (within the
 * tolerance), ends behind it (any amount: small penetrations must not pile
 * up over cycles) and meets the plane inside T. Where the path starts a
 * hair behind the plane, the meeting point is taken where the line meets
 * it, a hair before A.
 */
static void test_triangle(const struct contact *c, uint32_t t,
			  const double a[3], const double b[3],
			  struct contact_hit *hit)
{
	double n[3], off, da, db, u, p[3], w[3], d[3];

	if (!plane(c, t, n, &off)) {
		return;
	}
	da = vec3_dot(n, a) - off;
	db = vec3_dot(n, b) - off;
	if (da < -CONTACT_PLANE_TOLERANCE || db >= 0 || da <= db) {
		return;
	}
	u = da / (da - db);
	if (fmax(u, 0) >= hit->u) {
		return;
	}
	vec3_sub(d, b, a);
	vec3_axpy(p, a, u, d);
	if (!inside(c, t, p, w)) {
		return;
	}
	hit->triangle = t;
	hit->u = fmax(u, 0);
	vec3_axpy(hit->point, a, hit->u, d);
	vec3_copy(hit->normal, n);
	hit->offset = off;
	vec3_set(hit->shaded, 0, 0, 0);
	for (int k = 0; k < 3; k++) {
		const float *vn = c->nrm[c->tri[t][k]];
		double nk[3] = { vn[0], vn[1], vn[2] };

		vec3_axpy(hit->shaded, hit->shaded, w[k], nk);
	}
	if (vec3_normalize(hit->shaded) < 1e-9) {
		vec3_copy(hit->shaded, n);
	}
}

static void query_segment(const struct contact *c, const struct segment *sg,
			  const double a[3], const double b[3],
			  const uint32_t *skip, int n_skip,
			  struct contact_hit *hit)
{
	uint32_t stack[STACK_DEPTH];
	int top = 0;
	double d[3];

	vec3_sub(d, b, a);
	stack[top++] = sg->root;
	while (top) {
		const struct node *nd = &c->node[stack[--top]];

		if (!segment_meets_box(nd, a, d, fmin(hit->u, 1.0))) {
			continue;
		}
		if (nd->count) {
			for (uint32_t i = 0; i < nd->count; i++) {
				uint32_t t = c->order[nd->first + i];

				if (!skipped(t, skip, n_skip)) {
					test_triangle(c, t, a, b, hit);
				}
			}
		} else if (top + 2 <= STACK_DEPTH) {
			stack[top++] = nd->first;
			stack[top++] = nd->first + 1;
		}
	}
}

bool contact_first_hit(const struct contact *c, const double a[3],
		       const double b[3], double s0_m, double s1_m,
		       const uint32_t *skip, int n_skip,
		       struct contact_hit *hit)
{
	hit->u = INFINITY;
	for (uint32_t s = 0; s < c->segments; s++) {
		const struct segment *sg = &c->seg[s];

		if (sg->s1 < s0_m || sg->s0 > s1_m || !sg->triangles) {
			continue;
		}
		query_segment(c, sg, a, b, skip, n_skip, hit);
	}
	return isfinite(hit->u);
}

double contact_triangle_s(const struct contact *c, uint32_t t)
{
	uint32_t lo = 0, hi = c->segments;

	while (hi - lo > 1) { /* the last segment starting at or before t */
		uint32_t mid = (lo + hi) / 2;

		if (c->seg[mid].first <= t) {
			lo = mid;
		} else {
			hi = mid;
		}
	}
	return c->segments ? (c->seg[lo].s0 + c->seg[lo].s1) / 2 : 0;
}

void contact_triangle(const struct contact *c, uint32_t t, double out[3][3])
{
	for (int k = 0; k < 3; k++) {
		vertex(c, c->tri[t][k], out[k]);
	}
}

uint32_t contact_nearest(const struct contact *c, const double p[3],
			 double s0_m, double s1_m, double *dist_m)
{
	uint32_t best = UINT32_MAX;
	double best_abs = INFINITY;

	for (uint32_t s = 0; s < c->segments; s++) {
		const struct segment *sg = &c->seg[s];

		if (sg->s1 < s0_m || sg->s0 > s1_m || !sg->triangles) {
			continue;
		}
		for (uint32_t i = sg->first; i < sg->first + sg->triangles; i++) {
			double n[3], off, w[3], q[3], d;
			uint32_t t = c->order[i];

			if (!plane(c, t, n, &off)) {
				continue;
			}
			d = vec3_dot(n, p) - off;
			vec3_axpy(q, p, -d, n);
			if (fabs(d) < best_abs && inside(c, t, q, w)) {
				best_abs = fabs(d);
				best = t;
				*dist_m = d;
			}
		}
	}
	return best;
}
