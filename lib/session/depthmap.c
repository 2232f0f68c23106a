/*
 * depthmap.c - the software depth buffer (depthmap.h).
 *
 * 1 / z is affine in the image (perspective-correct depth), so it is
 * interpolated linearly over a projected triangle. A pixel is covered when
 * its centre lies inside the triangle or within EDGE_PX of an edge: the
 * small overlap leaves no crack between neighbours through which a hidden
 * point would show.
 */
#include <math.h>
#include <string.h>

#include "session/depthmap.h"
#include "base/vec3.h"

#define EDGE_PX 0.05f

void depthmap_begin(struct depthmap *d, const double eye[3],
		    const double dir[3], double half_fov_rad)
{
	double *right = d->axis[0], *up = d->axis[1], *fwd = d->axis[2];
	double other[3] = { 1, 0, 0 };

	vec3_copy(d->eye, eye);
	vec3_copy(fwd, dir);
	vec3_normalize(fwd);
	if (fabs(fwd[0]) > 0.6) {
		vec3_set(other, 0, 1, 0);
	}
	vec3_cross(right, other, fwd);
	vec3_normalize(right);
	vec3_cross(up, fwd, right);
	d->scale = DEPTHMAP_N / 2.0 /
		   tan(fmin(half_fov_rad, DEPTHMAP_MAX_HALF_RAD));
	d->x0 = d->y0 = DEPTHMAP_N;
	d->x1 = d->y1 = 0;
	memset(d->w, 0, sizeof(d->w));
}

void depthmap_want(struct depthmap *d, const float p[3])
{
	/* depthmap_visible()'s pixels i, i + 1 and j, j + 1 */
	int i = (int)floorf(p[0] - 0.5f), j = (int)floorf(p[1] - 0.5f);

	i = i < 0 ? 0 : i > DEPTHMAP_N - 2 ? DEPTHMAP_N - 2 : i;
	j = j < 0 ? 0 : j > DEPTHMAP_N - 2 ? DEPTHMAP_N - 2 : j;
	d->x0 = i < d->x0 ? i : d->x0;
	d->y0 = j < d->y0 ? j : d->y0;
	d->x1 = i + 2 > d->x1 ? i + 2 : d->x1;
	d->y1 = j + 2 > d->y1 ? j + 2 : d->y1;
}

void depthmap_camera(const struct depthmap *d, const double p[3],
		     float out[3])
{
	double x[3];

	vec3_sub(x, p, d->eye);
	for (int j = 0; j < 3; j++) {
		out[j] = (float)vec3_dot(d->axis[j], x);
	}
}

void depthmap_project(const struct depthmap *d, const float x[3],
		      float out[3])
{
	float k = (float)d->scale / x[2];

	out[0] = x[0] * k + DEPTHMAP_N / 2.0f;
	out[1] = x[1] * k + DEPTHMAP_N / 2.0f;
	out[2] = 1.0f / x[2];
}

/* Plain comparisons: fminf() and fmaxf() are calls into libm here. */
static inline float min3(float a, float b, float c)
{
	float m = a < b ? a : b;

	return m < c ? m : c;
}

static inline float max3(float a, float b, float c)
{
	float m = a > b ? a : b;

	return m > c ? m : c;
}

static float edge(const float a[3], const float b[3], float x, float y)
{
	return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
}

/*
 * A projected triangle into the buffer, counter-clockwise in the image
 * (AREA, twice its area in pixels, > 0). Row by row: each edge function
 * e_j = ex_j x + ey_j y + e0_j is linear, so the pixels of a row inside
 * all three form one span, found without testing the pixels outside it
 * (a thin triangle at the edge of the view has a large bounding box);
 * 1 / z is linear too.
 */
static void fill(struct depthmap *d, const float *const p[3], float area)
{
	float ex[3], ey[3], e0[3], inv[3], slack[3], wx = 0, wy = 0, w0 = 0;
	int y0, y1;

	for (int j = 0; j < 3; j++) {
		const float *a = p[(j + 1) % 3], *b = p[(j + 2) % 3];

		ex[j] = -(b[1] - a[1]);
		ey[j] = b[0] - a[0];
		e0[j] = -ey[j] * a[1] - ex[j] * a[0];
		slack[j] = -EDGE_PX * (fabsf(ex[j]) + fabsf(ey[j]));
		inv[j] = ex[j] != 0 ? 1 / ex[j] : 0;
		wx += ex[j] * p[j][2] / area;
		wy += ey[j] * p[j][2] / area;
		w0 += e0[j] * p[j][2] / area;
	}
	y0 = (int)floorf(min3(p[0][1], p[1][1], p[2][1]));
	y1 = (int)ceilf(max3(p[0][1], p[1][1], p[2][1]));
	y0 = y0 < d->y0 ? d->y0 : y0;
	y1 = y1 > d->y1 ? d->y1 : y1;
	for (int y = y0; y < y1; y++) {
		float py = (float)y + 0.5f, lo = (float)d->x0 + 0.5f;
		float hi = (float)d->x1 - 0.5f;
		float *row = d->w[y];

		for (int j = 0; j < 3; j++) {
			float r = slack[j] - ey[j] * py - e0[j];

			if (ex[j] > 0) {
				float x = r * inv[j];

				lo = x > lo ? x : lo;
			} else if (ex[j] < 0) {
				float x = r * inv[j];

				hi = x < hi ? x : hi;
			} else if (r > 0) {
				hi = -1;
			}
		}
		if (!(lo <= hi)) {
			continue;
		}
		/* pixel x's centre x + 0.5 within [lo, hi] */
		for (int x = (int)ceilf(lo - 0.5f); x <= (int)floorf(hi - 0.5f);
		     x++) {
			float w = wx * ((float)x + 0.5f) + wy * py + w0;

			if (w > row[x]) {
				row[x] = w;
			}
		}
	}
}

/* A projected triangle facing the camera: clockwise in the image (x
 * right, y up), which the fill wants the other way round. */
static void fill_facing(struct depthmap *d, const float *p0, const float *p1,
			const float *p2)
{
	const float *const q[3] = { p0, p2, p1 };
	float area = -edge(p0, p1, p2[0], p2[1]);
	float x0 = min3(p0[0], p1[0], p2[0]), x1 = max3(p0[0], p1[0], p2[0]);
	float y0 = min3(p0[1], p1[1], p2[1]), y1 = max3(p0[1], p1[1], p2[1]);

	/* most triangles far down the lumen cover no pixel's centre */
	if (area > 1e-9f &&
	    floorf(x1 - 0.5f + EDGE_PX) >= ceilf(x0 - 0.5f - EDGE_PX) &&
	    floorf(y1 - 0.5f + EDGE_PX) >= ceilf(y0 - 0.5f - EDGE_PX) &&
	    x1 > (float)d->x0 && y1 > (float)d->y0 && x0 < (float)d->x1 &&
	    y0 < (float)d->y1) {
		fill(d, q, area);
	}
}

/* The point where the edge A B crosses the near plane. */
static void near_cut(const float a[3], const float b[3], float out[3])
{
	float k = (DEPTHMAP_NEAR_M - a[2]) / (b[2] - a[2]);

	for (int j = 0; j < 3; j++) {
		out[j] = a[j] + k * (b[j] - a[j]);
	}
}

/* A triangle with a corner nearer than DEPTHMAP_NEAR_M: culled in space,
 * clipped (Sutherland-Hodgman, up to 4 corners), projected, drawn. */
static void clipped(struct depthmap *d, const float *const x[3])
{
	float e1[3], e2[3], n[3], poly[4][3], img[4][3];
	int k = 0;

	for (int j = 0; j < 3; j++) {
		e1[j] = x[1][j] - x[0][j];
		e2[j] = x[2][j] - x[0][j];
	}
	n[0] = e1[1] * e2[2] - e1[2] * e2[1];
	n[1] = e1[2] * e2[0] - e1[0] * e2[2];
	n[2] = e1[0] * e2[1] - e1[1] * e2[0];
	if (n[0] * x[0][0] + n[1] * x[0][1] + n[2] * x[0][2] >= 0) {
		return; /* faces away: the wall's outside */
	}
	for (int j = 0; j < 3; j++) {
		const float *p = x[j], *q = x[(j + 1) % 3];
		bool p_in = p[2] >= DEPTHMAP_NEAR_M;
		bool q_in = q[2] >= DEPTHMAP_NEAR_M;

		if (p_in) {
			memcpy(poly[k++], p, sizeof(poly[0]));
		}
		if (p_in != q_in) {
			near_cut(p, q, poly[k++]);
		}
	}
	if (k < 3) {
		return;
	}
	for (int j = 0; j < k; j++) {
		depthmap_project(d, poly[j], img[j]);
	}
	fill_facing(d, img[0], img[1], img[2]);
	if (k == 4) {
		fill_facing(d, img[0], img[2], img[3]);
	}
}

/*
 * With every corner in front, perspective keeps the winding: the image's
 * (P1 - P0) x (P2 - P0) has the sign of X0 . (X1 - X0) x (X2 - X0), so
 * the image alone says which way the triangle faces.
 */
void depthmap_triangle(struct depthmap *d, const float *const x[3],
		       const float *const p[3])
{
	if (x[0][2] < DEPTHMAP_NEAR_M || x[1][2] < DEPTHMAP_NEAR_M ||
	    x[2][2] < DEPTHMAP_NEAR_M) {
		clipped(d, x);
		return;
	}
	fill_facing(d, p[0], p[1], p[2]);
}

bool depthmap_visible(const struct depthmap *d, const float x[3])
{
	float p[3], deepest = INFINITY;
	int i, j;

	if (x[2] < DEPTHMAP_NEAR_M) {
		return true; /* not in the buffer's view */
	}
	depthmap_project(d, x, p);
	i = (int)floorf(p[0] - 0.5f);
	j = (int)floorf(p[1] - 0.5f);
	if (i < 0 || j < 0 || i + 1 >= DEPTHMAP_N || j + 1 >= DEPTHMAP_N) {
		return true;
	}
	for (int y = j; y <= j + 1; y++) {
		for (int xx = i; xx <= i + 1; xx++) {
			deepest = fminf(deepest, d->w[y][xx]);
		}
	}
	return p[2] * (1 + DEPTHMAP_SLACK) >= deepest;
}
