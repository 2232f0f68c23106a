/*
 * shapes.h - small meshes the views build: a unit sphere (polyps, the
 * tip, the contact point), a tube along a polyline (the scope in the
 * overview) and the line that marks a tube's roll. Vertices are 9 floats:
 * position, normal, and the vessel texture's coordinates as the colon's
 * (gpumesh.h) and a 0. Triangles wind counter-clockwise seen from outside.
 * Pure computation.
 */
#ifndef ENDOVIEW_SHAPES_H
#define ENDOVIEW_SHAPES_H

#include <stddef.h>
#include <stdint.h>

#define SHAPES_STACKS 12
#define SHAPES_SLICES 24
#define SHAPES_SPHERE_VERTICES ((SHAPES_STACKS + 1) * (SHAPES_SLICES + 1))
#define SHAPES_SPHERE_INDICES (6 * SHAPES_STACKS * SHAPES_SLICES)

#define SHAPES_TUBE_SIDES 10

/* The unit sphere into V (SHAPES_SPHERE_VERTICES) and IDX. */
void shapes_sphere(float (*v)[9], uint32_t *idx);

/* Vertices and indices of a tube through N points. */
size_t shapes_tube_vertices(size_t n);
size_t shapes_tube_indices(size_t n);

/*
 * The vertices V of a tube of RADIUS (m) through the N points P, its
 * rings carried along without twist; points that coincide repeat the
 * previous ring.
 */
void shapes_tube(const float (*p)[3], size_t n, float radius, float (*v)[9]);

/* The triangles of any tube through N points: segment i (points i to
 * i + 1) is indices [6 i SHAPES_TUBE_SIDES, 6 (i + 1) SHAPES_TUBE_SIDES). */
void shapes_tube_index(size_t n, uint32_t *idx);

/*
 * The line along a tube through the N points P that marks its roll, into
 * OUT (N points): each point moved OFFSET (m) towards the tube's material
 * d1 there, which is U0 (made normal to the tube at P[0]) carried along
 * the tube without twist and turned by ROLL[i] (rad) about the tangent,
 * towards t x d1 (a positive roll turns u0 towards the first frame's v).
 */
void shapes_stripe(const float (*p)[3], const float *roll, size_t n,
		   const double u0[3], float offset, float (*out)[3]);

#endif
