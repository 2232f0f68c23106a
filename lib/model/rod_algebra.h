/*
 * rod_algebra.h - the rod's algebra (rod.c): unit quaternions (w, x, y, z)
 * for the segments' frames, and the 3x3 and 6x6 blocks of its
 * block-tridiagonal solve (a 6x6's Cholesky factor and its triangular
 * solves).
 *
 * Static inline: each function compiles into its caller, so that the
 * rod's solver keeps the -O3 of rod.c's own rule in the Makefile (the
 * blocks vectorised, a third fewer instructions than -O2) and a test may
 * call them as they are. Plain arrays of doubles; every function writes
 * through its last arguments only, none allocates, blocks or keeps state:
 * the force loop may call them, any thread.
 */
#ifndef ENDOSIM_ROD_ALGEBRA_H
#define ENDOSIM_ROD_ALGEBRA_H

#include <math.h>
#include <string.h>

#include "base/vec3.h"

/* A pivot or a determinant below this: not definite, the system broken. */
#define ROD_ALGEBRA_FLOOR 1e-300

/* ------------------------------------------------------------ quaternions */

/* OUT = A B (OUT may be A or B). */
static inline void rod_algebra_quat_mul(const double a[4],
					const double b[4], double out[4])
{
	double r[4] = {
		a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
		a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
		a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
		a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
	};

	memcpy(out, r, sizeof(r));
}

static inline void rod_algebra_quat_conj(const double a[4],
					 double out[4])
{
	out[0] = a[0];
	out[1] = -a[1];
	out[2] = -a[2];
	out[3] = -a[3];
}

static inline void rod_algebra_quat_normalize(double q[4])
{
	double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);

	for (int i = 0; i < 4; i++) {
		q[i] /= n;
	}
}

/* Q turned by the small rotation vector W (world): (1 + w/2) q. */
static inline void rod_algebra_quat_turn(double q[4], const double w[3])
{
	double dq[4] = { 0, w[0] / 2, w[1] / 2, w[2] / 2 }, t[4];

	rod_algebra_quat_mul(dq, q, t);
	for (int i = 0; i < 4; i++) {
		q[i] += t[i];
	}
	rod_algebra_quat_normalize(q);
}

/* The world rotation that took Q0 to Q: 2 Im(q conj(q0)), short way. */
static inline void rod_algebra_rotation_since(const double q[4],
					      const double q0[4],
					      double out[3])
{
	double c[4], d[4];

	rod_algebra_quat_conj(q0, c);
	rod_algebra_quat_mul(q, c, d);
	if (d[0] < 0) {
		vec3_set(out, -2 * d[1], -2 * d[2], -2 * d[3]);
	} else {
		vec3_set(out, 2 * d[1], 2 * d[2], 2 * d[3]);
	}
}

/* The rotation matrix of unit Q: columns d1, d2, d3. */
static inline void rod_algebra_quat_matrix(const double q[4],
					   double m[3][3])
{
	double w = q[0], x = q[1], y = q[2], z = q[3];

	m[0][0] = 1 - 2 * (y * y + z * z);
	m[0][1] = 2 * (x * y - w * z);
	m[0][2] = 2 * (x * z + w * y);
	m[1][0] = 2 * (x * y + w * z);
	m[1][1] = 1 - 2 * (x * x + z * z);
	m[1][2] = 2 * (y * z - w * x);
	m[2][0] = 2 * (x * z - w * y);
	m[2][1] = 2 * (y * z + w * x);
	m[2][2] = 1 - 2 * (x * x + y * y);
}

/* The unit quaternion of rotation matrix M (columns orthonormal). */
static inline void rod_algebra_quat_from_matrix(const double m[3][3],
						double q[4])
{
	double tr = m[0][0] + m[1][1] + m[2][2];

	if (tr > 0) {
		double s = 2 * sqrt(tr + 1);

		q[0] = s / 4;
		q[1] = (m[2][1] - m[1][2]) / s;
		q[2] = (m[0][2] - m[2][0]) / s;
		q[3] = (m[1][0] - m[0][1]) / s;
	} else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
		double s = 2 * sqrt(1 + m[0][0] - m[1][1] - m[2][2]);

		q[0] = (m[2][1] - m[1][2]) / s;
		q[1] = s / 4;
		q[2] = (m[0][1] + m[1][0]) / s;
		q[3] = (m[0][2] + m[2][0]) / s;
	} else if (m[1][1] > m[2][2]) {
		double s = 2 * sqrt(1 + m[1][1] - m[0][0] - m[2][2]);

		q[0] = (m[0][2] - m[2][0]) / s;
		q[1] = (m[0][1] + m[1][0]) / s;
		q[2] = s / 4;
		q[3] = (m[1][2] + m[2][1]) / s;
	} else {
		double s = 2 * sqrt(1 + m[2][2] - m[0][0] - m[1][1]);

		q[0] = (m[1][0] - m[0][1]) / s;
		q[1] = (m[0][2] + m[2][0]) / s;
		q[2] = (m[1][2] + m[2][1]) / s;
		q[3] = s / 4;
	}
	rod_algebra_quat_normalize(q);
}

/* D1 of unit Q's frame. */
static inline void rod_algebra_quat_axis_d1(const double q[4],
					    double d1[3])
{
	double m[3][3];

	rod_algebra_quat_matrix(q, m);
	vec3_set(d1, m[0][0], m[1][0], m[2][0]);
}

/*
 * R = conj(A) B taken the short way (R0 >= 0), and G = (r0 I - [rv]x)
 * M^T, M = R(A): d (2 Im R) = G (dtheta_b - dtheta_a) for world
 * rotations.
 */
static inline void rod_algebra_relative(const double a[4], const double b[4],
					const double m[3][3], double r[4],
					double g[3][3])
{
	double ca[4], k[3][3];

	rod_algebra_quat_conj(a, ca);
	rod_algebra_quat_mul(ca, b, r);
	if (r[0] < 0) {
		for (int i = 0; i < 4; i++) {
			r[i] = -r[i];
		}
	}
	k[0][0] = r[0];
	k[0][1] = r[3];
	k[0][2] = -r[2];
	k[1][0] = -r[3];
	k[1][1] = r[0];
	k[1][2] = r[1];
	k[2][0] = r[2];
	k[2][1] = -r[1];
	k[2][2] = r[0];
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++) {
			g[i][j] = k[i][0] * m[j][0] + k[i][1] * m[j][1] +
				  k[i][2] * m[j][2];
		}
	}
}

/* ------------------------------------------------- 3x3 and 6x6 blocks */

/* OUT = A B^T (3x3). */
static inline void rod_algebra_m3_abt(const double a[3][3],
				      const double b[3][3], double out[3][3])
{
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++) {
			out[i][j] = a[i][0] * b[j][0] + a[i][1] * b[j][1] +
				    a[i][2] * b[j][2];
		}
	}
}

/* OUT += A B (3x3), into the block at (R0, C0) of a 6x6. */
static inline void rod_algebra_m6_add_ab(double out[6][6], int r0, int c0,
					 const double a[3][3],
					 const double b[3][3])
{
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++) {
			out[r0 + i][c0 + j] += a[i][0] * b[0][j] +
					       a[i][1] * b[1][j] +
					       a[i][2] * b[2][j];
		}
	}
}

/* OUT = A X (3x3 times 3), added with SIGN. */
static inline void rod_algebra_m3_mv_acc(const double a[3][3],
					 const double x[3], double sign,
					 double out[3])
{
	for (int i = 0; i < 3; i++) {
		out[i] += sign * (a[i][0] * x[0] + a[i][1] * x[1] +
				  a[i][2] * x[2]);
	}
}

/* OUT += A^T X. */
static inline void rod_algebra_m3_mtv_acc(const double a[3][3],
					  const double x[3], double out[3])
{
	for (int i = 0; i < 3; i++) {
		out[i] += a[0][i] * x[0] + a[1][i] * x[1] + a[2][i] * x[2];
	}
}

/* [e]x times SIGN. */
static inline void rod_algebra_m3_cross(double m[3][3], const double e[3],
					double sign)
{
	m[0][0] = 0;
	m[0][1] = -sign * e[2];
	m[0][2] = sign * e[1];
	m[1][0] = sign * e[2];
	m[1][1] = 0;
	m[1][2] = -sign * e[0];
	m[2][0] = -sign * e[1];
	m[2][1] = sign * e[0];
	m[2][2] = 0;
}

static inline void rod_algebra_m3_identity(double m[3][3], double k)
{
	memset(m, 0, sizeof(double[3][3]));
	m[0][0] = m[1][1] = m[2][2] = k;
}

/* The inverse of the symmetric positive definite A; -1 when it is not. */
static inline int rod_algebra_m3_inverse(const double a[3][3],
					 double out[3][3])
{
	double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
	double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
	double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
	double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;

	if (!(det > ROD_ALGEBRA_FLOOR) || !(a[0][0] > 0)) {
		return -1;
	}
	out[0][0] = c00 / det;
	out[1][0] = c01 / det;
	out[2][0] = c02 / det;
	out[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det;
	out[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
	out[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det;
	out[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det;
	out[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det;
	out[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det;
	return 0;
}

/*
 * In place Cholesky of the SPD 6x6 A: its lower triangle becomes L with
 * the reciprocal of each diagonal element on the diagonal (the solves
 * multiply). -1 when not definite.
 */
static inline int rod_algebra_chol6(double a[6][6])
{
	for (int j = 0; j < 6; j++) {
		double d = a[j][j];

		for (int k = 0; k < j; k++) {
			d -= a[j][k] * a[j][k];
		}
		if (!(d > ROD_ALGEBRA_FLOOR)) {
			return -1;
		}
		d = 1 / sqrt(d);
		a[j][j] = d;
		for (int i = j + 1; i < 6; i++) {
			double s = a[i][j];

			for (int k = 0; k < j; k++) {
				s -= a[i][k] * a[j][k];
			}
			a[i][j] = s * d;
		}
	}
	return 0;
}

/* X = L^-1 X (rod_algebra_chol6()'s factor). */
static inline void rod_algebra_lower_solve(const double l[6][6],
					   double x[6])
{
	for (int i = 0; i < 6; i++) {
		double s = x[i];

		for (int k = 0; k < i; k++) {
			s -= l[i][k] * x[k];
		}
		x[i] = s * l[i][i];
	}
}

/* X = L^-T X. */
static inline void rod_algebra_upper_solve(const double l[6][6],
					   double x[6])
{
	for (int i = 5; i >= 0; i--) {
		double s = x[i];

		for (int k = i + 1; k < 6; k++) {
			s -= l[k][i] * x[k];
		}
		x[i] = s * l[i][i];
	}
}

/* B = L^-1 B, all six columns at once. */
static inline void rod_algebra_lower_solve6(const double l[6][6],
					    double b[6][6])
{
	for (int i = 0; i < 6; i++) {
		for (int k = 0; k < i; k++) {
			for (int j = 0; j < 6; j++) {
				b[i][j] -= l[i][k] * b[k][j];
			}
		}
		for (int j = 0; j < 6; j++) {
			b[i][j] *= l[i][i];
		}
	}
}

#endif
