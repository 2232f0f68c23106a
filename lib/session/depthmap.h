/*
 * depthmap.h - what a camera can see past what is in front: a small
 * software depth buffer (a z-buffer, as a GPU keeps one) for the metrics'
 * occlusion test (metrics.c): the colon's wall near the camera drawn as
 * triangles, then a point is visible when nothing drawn lies in front of
 * it.
 *
 * The camera sits at EYE looking along DIR; camera coordinates (x, y, z)
 * are metres along right, up and DIR (a right-handed frame), z the depth.
 * The buffer is DEPTHMAP_N x DEPTHMAP_N pixels of a perspective view
 * spanning tan(half) either side of DIR, half the smaller of the half
 * field of view and DEPTHMAP_MAX_HALF_RAD (a perspective view cannot
 * reach 90 deg); each pixel keeps the largest 1 / z drawn there (0:
 * nothing). Surfaces nearer than DEPTHMAP_NEAR_M are clipped.
 *
 * Visibility: a point is visible when its depth is at most the deepest of
 * the four pixel centres around it (times 1 + DEPTHMAP_SLACK): on a
 * surface drawn into the buffer a point's depth lies between those of the
 * pixel centres around it, so the surface never hides itself, while a
 * point behind a nearer surface that covers all four is hidden. A point
 * outside the buffer's view is not tested (visible): with the default
 * 140 deg field of view the buffer covers all of it.
 *
 * No allocation, no blocking; one struct belongs to one thread. A
 * triangle costs ~20-50 ns plus ~5 ns per pixel it covers.
 */
#ifndef ENDOSIM_DEPTHMAP_H
#define ENDOSIM_DEPTHMAP_H

#include <stdbool.h>

#define DEPTHMAP_N 128
#define DEPTHMAP_NEAR_M 0.0005      /* nearer than this: clipped */
#define DEPTHMAP_MAX_HALF_RAD 1.309 /* 75 deg */
#define DEPTHMAP_SLACK 0.01         /* relative depth tolerance */

struct depthmap {
	double eye[3];
	double axis[3][3];       /* rows: right, up, dir */
	double scale;            /* pixels per unit of x / z */
	int x0, y0, x1, y1;      /* drawn only in x0 <= x < x1, y0 <= y < y1 */
	float w[DEPTHMAP_N][DEPTHMAP_N]; /* 1 / z, 1/m; 0: nothing */
};

/* An empty buffer for the camera at EYE looking along DIR (need not be
 * unit) with a field of view of HALF_FOV_RAD either side, wanting
 * nothing drawn yet (depthmap_want()). */
void depthmap_begin(struct depthmap *d, const double eye[3],
		    const double dir[3], double half_fov_rad);

/*
 * The point whose projection is P (depthmap_project()) will be tested:
 * the pixels its test reads are drawn from here on. Triangles are drawn
 * only within the rectangle around the points wanted (a scissor, as a
 * GPU's): the rest of the buffer, which no test reads, stays empty.
 */
void depthmap_want(struct depthmap *d, const float p[3]);

/* World point P in camera coordinates. */
void depthmap_camera(const struct depthmap *d, const double p[3],
		     float out[3]);

/* X (camera coordinates, x[2] >= DEPTHMAP_NEAR_M) in the image: pixel
 * coordinates (0 .. DEPTHMAP_N across the view) and 1 / z. */
void depthmap_project(const struct depthmap *d, const float x[3],
		      float out[3]);

/*
 * Draws the triangle of corners X[0..2] (camera coordinates; P[0..2]:
 * their depthmap_project(), read only when every corner is at least
 * DEPTHMAP_NEAR_M deep) when it faces the camera: counter-clockwise seen
 * from it, (X1 - X0) x (X2 - X0) towards it (a wall seen from inside the
 * lumen: mesh.h's winding). Clipped at DEPTHMAP_NEAR_M and to the buffer.
 * A mesh's corners are shared by several triangles: projected once each.
 */
void depthmap_triangle(struct depthmap *d, const float *const x[3],
		       const float *const p[3]);

/* Whether the point X (camera coordinates) is hidden by nothing drawn. */
bool depthmap_visible(const struct depthmap *d, const float x[3]);

#endif
