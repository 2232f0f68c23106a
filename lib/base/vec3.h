/*
 * vec3.h - three-vectors of doubles for the colon and scope geometry.
 *
 * Plain arrays (double[3]) so that the geometry's tables stay flat arrays;
 * every function writes through OUT, which may alias an input. Pure and
 * inline: safe anywhere, the force loop included.
 */
#ifndef ENDOSIM_VEC3_H
#define ENDOSIM_VEC3_H

#include <math.h>

static inline void vec3_set(double out[3], double x, double y, double z)
{
	out[0] = x;
	out[1] = y;
	out[2] = z;
}

static inline void vec3_copy(double out[3], const double a[3])
{
	vec3_set(out, a[0], a[1], a[2]);
}

static inline void vec3_add(double out[3], const double a[3],
			    const double b[3])
{
	vec3_set(out, a[0] + b[0], a[1] + b[1], a[2] + b[2]);
}

static inline void vec3_sub(double out[3], const double a[3],
			    const double b[3])
{
	vec3_set(out, a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

static inline void vec3_scale(double out[3], const double a[3], double k)
{
	vec3_set(out, a[0] * k, a[1] * k, a[2] * k);
}

/* OUT = A + K B */
static inline void vec3_axpy(double out[3], const double a[3], double k,
			     const double b[3])
{
	vec3_set(out, a[0] + k * b[0], a[1] + k * b[1], a[2] + k * b[2]);
}

static inline double vec3_dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void vec3_cross(double out[3], const double a[3],
			      const double b[3])
{
	vec3_set(out, a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
		 a[0] * b[1] - a[1] * b[0]);
}

static inline double vec3_norm(const double a[3])
{
	return sqrt(vec3_dot(a, a));
}

static inline double vec3_dist(const double a[3], const double b[3])
{
	double d[3];

	vec3_sub(d, a, b);
	return vec3_norm(d);
}

/* Scales A to unit length; returns its former length (0: left as is). */
static inline double vec3_normalize(double a[3])
{
	double n = vec3_norm(a);

	if (n > 0) {
		vec3_scale(a, a, 1.0 / n);
	}
	return n;
}

/* OUT = A + F (B - A) */
static inline void vec3_lerp(double out[3], const double a[3],
			     const double b[3], double f)
{
	vec3_set(out, a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]),
		 a[2] + f * (b[2] - a[2]));
}

/* OUT = A rotated by ANGLE (rad) about the unit AXIS (Rodrigues). */
static inline void vec3_rotate(double out[3], const double a[3],
			       const double axis[3], double angle)
{
	double c = cos(angle), s = sin(angle), kxa[3], r[3];
	double kda = vec3_dot(axis, a);

	vec3_cross(kxa, axis, a);
	vec3_scale(r, a, c);
	vec3_axpy(r, r, s, kxa);
	vec3_axpy(out, r, kda * (1 - c), axis);
}

#endif
