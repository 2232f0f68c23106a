/* portal.c - see portal.h. */
#include "viewer/portal.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "base/vec3.h"

int portal_sphere_visible(const struct portal_view *v, const double c[3],
			  double r)
{
	double x[3], d, angle;

	vec3_sub(x, c, v->eye);
	d = vec3_norm(x);
	if (d <= r) {
		return 1;
	}
	if (d - r > v->far_m) {
		return 0;
	}
	angle = acos(fmax(-1, fmin(1, vec3_dot(x, v->dir) / d)));
	return angle - asin(r / d) <= v->half_angle;
}

/* Distance from P to segment K's bounding box (0 inside). */
static double box_distance(const struct mesh *me, uint32_t k,
			   const double p[3])
{
	const struct mesh_segment *sg = &me->seg[k];
	double d2 = 0;

	for (int x = 0; x < 3; x++) {
		double e = fmax(0, fmax(sg->min[x] - p[x], p[x] - sg->max[x]));

		d2 += e * e;
	}
	return sqrt(d2);
}

/* The portal where segment K starts: its ring's centre and radius. */
static int portal_visible(const struct model *m, const struct portal_view *v,
			  uint32_t k)
{
	const struct mesh *me = m->mesh;
	size_t i = model_sample_at(m, me->seg[k].s0_m);

	return portal_sphere_visible(v, centreline_sample(m->cl, i)->p,
				     me->sample_rho[i]);
}

static int level_at(const struct portal_view *v, double d)
{
	int level = 0;

	while (level < 3 && d >= v->level_m[level]) {
		level++;
	}
	return level;
}

/* Segment K's bounding box as a sphere: can the camera see into it? */
static int box_visible(const struct mesh *me, const struct portal_view *v,
		       uint32_t k)
{
	const struct mesh_segment *sg = &me->seg[k];
	double c[3], lo[3], hi[3];

	for (int x = 0; x < 3; x++) {
		lo[x] = sg->min[x];
		hi[x] = sg->max[x];
	}
	vec3_lerp(c, lo, hi, 0.5);
	return portal_sphere_visible(v, c, 0.5 * vec3_dist(lo, hi));
}

/* Adds segment K if V may see it (or ALWAYS: the camera's own). */
static int add(const struct model *m, const struct portal_view *v,
	       uint32_t k, bool always, struct portal_item *out, int n)
{
	double d = box_distance(m->mesh, k, v->eye);

	if (n >= PORTAL_MAX ||
	    (!always && (d > v->far_m || !box_visible(m->mesh, v, k)))) {
		return n;
	}
	out[n] = (struct portal_item){ .segment = k, .level = level_at(v, d),
				       .distance_m = d };
	return n + 1;
}

static int nearer(const void *a, const void *b)
{
	double da = ((const struct portal_item *)a)->distance_m;
	double db = ((const struct portal_item *)b)->distance_m;

	return (da > db) - (da < db);
}

int portal_find(const struct model *m, const struct portal_view *v,
		double s_m, struct portal_item out[PORTAL_MAX])
{
	const struct mesh *me = m->mesh;
	uint32_t kc = mesh_segment_at(me, s_m);
	int n = add(m, v, kc, true, out, 0);

	if (kc > 0) {
		n = add(m, v, kc - 1, false, out, n);
	}
	/* towards the cecum: through the portal at each segment's start */
	for (uint32_t k = kc + 1; k < me->segments && n < PORTAL_MAX; k++) {
		if (k > kc + 1 && !portal_visible(m, v, k)) {
			break;
		}
		n = add(m, v, k, false, out, n);
	}
	/* towards the anus: through the portal where the one after starts */
	for (uint32_t k = kc > 1 ? kc - 2 : 0; kc > 1 && n < PORTAL_MAX;
	     k--) {
		if (!portal_visible(m, v, k + 1)) {
			break;
		}
		n = add(m, v, k, false, out, n);
		if (k == 0) {
			break;
		}
	}
	qsort(out, (size_t)n, sizeof(*out), nearer);
	return n;
}
