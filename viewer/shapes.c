/* shapes.c - see shapes.h. */
#include "viewer/shapes.h"

#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "base/vec3.h"
#include "viewer/vessels.h"

static void put(float *v, const double p[3], const double n[3], double s,
		double angle)
{
	for (int k = 0; k < 3; k++) {
		v[k] = (float)p[k];
		v[3 + k] = (float)n[k];
	}
	v[6] = (float)s;
	v[7] = (float)vessels_around(angle);
	v[8] = 0;
}

/* Quads between rows of W + 1 vertices, row I to row I + 1; FLIP turns
 * their winding round. */
static uint32_t *grid(uint32_t *idx, size_t rows, size_t w, bool flip)
{
	for (size_t i = 0; i < rows; i++) {
		for (size_t j = 0; j < w; j++) {
			uint32_t a = (uint32_t)(i * (w + 1) + j);
			uint32_t b = a + (uint32_t)(w + 1);
			uint32_t q[6] = { a, b, a + 1, a + 1, b, b + 1 };

			if (flip) {
				q[1] = a + 1;
				q[2] = b;
				q[4] = b + 1;
				q[5] = b;
			}
			memcpy(idx, q, sizeof(q));
			idx += 6;
		}
	}
	return idx;
}

void shapes_sphere(float (*v)[9], uint32_t *idx)
{
	int w = SHAPES_SLICES + 1;

	for (int i = 0; i <= SHAPES_STACKS; i++) {
		double lat = M_PI * i / SHAPES_STACKS;

		for (int j = 0; j <= SHAPES_SLICES; j++) {
			double lon = 2 * M_PI * j / SHAPES_SLICES, p[3];

			vec3_set(p, sin(lat) * cos(lon), sin(lat) * sin(lon),
				 cos(lat));
			put(v[i * w + j], p, p, lat / M_PI * 0.1, lon);
		}
	}
	grid(idx, SHAPES_STACKS, SHAPES_SLICES, false);
}

size_t shapes_tube_vertices(size_t n)
{
	return n * (SHAPES_TUBE_SIDES + 1);
}

size_t shapes_tube_indices(size_t n)
{
	return n > 1 ? 6 * (n - 1) * SHAPES_TUBE_SIDES : 0;
}

/* The tangent at point I, or T as it was when the points coincide. */
static void tangent(const float (*p)[3], size_t n, size_t i, double t[3])
{
	size_t lo = i ? i - 1 : 0, hi = i + 1 < n ? i + 1 : n - 1;
	double d[3] = { p[hi][0] - p[lo][0], p[hi][1] - p[lo][1],
			p[hi][2] - p[lo][2] };

	if (vec3_normalize(d) > 0) {
		vec3_copy(t, d);
	}
}

/* Turns U to stay normal to T (parallel transport, approximately). */
static void carry(double u[3], const double t[3])
{
	double w[3];

	vec3_axpy(u, u, -vec3_dot(u, t), t);
	if (vec3_normalize(u) == 0) {
		vec3_set(w, t[1], -t[0], 0);
		if (vec3_normalize(w) == 0) {
			vec3_set(w, 1, 0, 0);
		}
		vec3_copy(u, w);
	}
}

void shapes_tube(const float (*p)[3], size_t n, float radius, float (*v)[9])
{
	double t[3] = { 0, 0, 1 }, u[3] = { 1, 0, 0 }, w[3], s = 0;

	for (size_t i = 0; i < n; i++) {
		double c[3] = { p[i][0], p[i][1], p[i][2] };

		tangent(p, n, i, t);
		carry(u, t);
		vec3_cross(w, t, u);
		if (i) {
			s += sqrt(pow(p[i][0] - p[i - 1][0], 2) +
				  pow(p[i][1] - p[i - 1][1], 2) +
				  pow(p[i][2] - p[i - 1][2], 2));
		}
		for (int j = 0; j <= SHAPES_TUBE_SIDES; j++) {
			double a = 2 * M_PI * j / SHAPES_TUBE_SIDES;
			double nn[3], q[3];

			vec3_scale(nn, u, cos(a));
			vec3_axpy(nn, nn, sin(a), w);
			vec3_axpy(q, c, radius, nn);
			put(v[i * (SHAPES_TUBE_SIDES + 1) + (size_t)j], q, nn,
			    s, a);
		}
	}
}

void shapes_tube_index(size_t n, uint32_t *idx)
{
	if (n > 1) {
		grid(idx, n - 1, SHAPES_TUBE_SIDES, true);
	}
}

void shapes_stripe(const float (*p)[3], const float *roll, size_t n,
		   const double u0[3], float offset, float (*out)[3])
{
	double t[3] = { 0, 0, 1 }, u[3], w[3], d[3];

	vec3_copy(u, u0);
	for (size_t i = 0; i < n; i++) {
		tangent(p, n, i, t);
		carry(u, t);
		vec3_cross(w, t, u);
		vec3_scale(d, u, cos(roll[i]));
		vec3_axpy(d, d, sin(roll[i]), w);
		for (int k = 0; k < 3; k++) {
			out[i][k] = (float)(p[i][k] + offset * d[k]);
		}
	}
}
