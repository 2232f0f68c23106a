/*
 * contact.h - the surface the endoscope's tip touches, as the god-object
 * (godobject.h) sees it: a closed triangle surface, and the first of its
 * triangles that a straight path from the lumen into the wall crosses.
 * For the colon it is the mesh inset by the tip's radius (colon.h), so that
 * the tip's centre can be treated as a point.
 *
 * Locality: the triangles are grouped by the mesh's segments along the
 * colon (mesh.h: contiguous triangle ranges with their material s range);
 * each segment has a bounding-volume hierarchy of its own. A query names
 * the stretch of s it may touch and visits only those segments, so its cost
 * does not grow with the colon's length or, beyond a logarithm, with the
 * mesh's resolution.
 *
 * Allocation: contact_create() allocates everything; the queries do not,
 * never block and are safe in the force loop. Read-only after creation:
 * any number of threads may query.
 */
#ifndef ENDOSIM_CONTACT_H
#define ENDOSIM_CONTACT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "model/mesh.h"

/* How far past a triangle's edges a crossing still counts, as a share of
 * the edge: closes the hairline cracks of floating point between
 * neighbouring triangles, so that a segment through a shared edge or
 * vertex hits one of them. */
#define CONTACT_EDGE_TOLERANCE 1e-3

/* A point this far (m) behind a plane still counts as in front of it:
 * absorbs the rounding of a proxy that sits on the plane. */
#define CONTACT_PLANE_TOLERANCE 1e-6


struct contact_hit {
	uint32_t triangle;  /* index into the mesh's triangles */
	double u;           /* where along the segment, 0..1 */
	double point[3];    /* the crossing, m */
	double normal[3];   /* the triangle's unit normal, into the lumen */
	double offset;      /* the plane: normal . x = offset */
	double shaded[3];   /* the normal interpolated from the vertex
			       normals at the crossing (unit) */
};

struct contact;

/*
 * The surface of VERTICES positions POS (m) with unit normals NRM (into the
 * lumen, for shading), TRIANGLES triangles TRI (counter-clockwise seen from
 * the lumen), grouped in SEGMENTS segments SEG (their s ranges and triangle
 * ranges). The arrays are copied. Returns NULL on ENOMEM or bad arguments
 * (a vertex index or triangle range out of range).
 */
struct contact *contact_create(const float (*pos)[3], const float (*nrm)[3],
			       uint32_t vertices, const uint32_t (*tri)[3],
			       uint32_t triangles,
			       const struct mesh_segment *seg,
			       uint32_t segments);

/* NULL is fine. */
void contact_destroy(struct contact *c);

/* Bytes held. */
size_t contact_bytes(const struct contact *c);

/*
 * The first triangle that the segment A -> B crosses from the lumen side
 * into the wall (A in front of its plane within CONTACT_PLANE_TOLERANCE, B
 * behind it by any amount), among the segments of the mesh that overlap
 * [S0_M, S1_M].
 * Triangles whose index is among the N_SKIP in SKIP are not considered.
 * Returns true with *HIT filled, false when the segment crosses nothing.
 */
bool contact_first_hit(const struct contact *c, const double a[3],
		       const double b[3], double s0_m, double s1_m,
		       const uint32_t *skip, int n_skip,
		       struct contact_hit *hit);

/* The material s (m, the middle of its segment) where triangle T is. */
double contact_triangle_s(const struct contact *c, uint32_t t);

/* The corners of triangle T (m): for tests and diagnostics. */
void contact_triangle(const struct contact *c, uint32_t t, double out[3][3]);

/*
 * The triangle nearest to P (m) among the segments overlapping [S0_M,
 * S1_M], and the signed distance of P from its plane (positive in the
 * lumen), through *DIST_M. Returns the triangle, or UINT32_MAX when the
 * stretch holds no triangle. For tests and diagnostics: it visits every
 * triangle of the stretch.
 */
uint32_t contact_nearest(const struct contact *c, const double p[3],
			 double s0_m, double s1_m, double *dist_m);

#endif
