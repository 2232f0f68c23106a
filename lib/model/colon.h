/*
 * colon.h - the colon model: a case's anatomy (anatomy.h) turned into a
 * centreline (centreline.h) and a triangle mesh around it (mesh.h), or an
 * imported mesh with its centreline; the one geometry that haptics and
 * graphics share.
 *
 * Generated cases: the course is laid segment by segment from the anal
 * verge (straights and circular arcs, anatomy.h), sampled every step_m
 * (shortened so that the length fits exactly); a ring of ring_vertices
 * vertices at every sample; the cecum closes in a dome, so the tube's
 * only open end is the anal verge. The lumen radius at (s, theta), theta
 * around the centreline from the frame's u:
 *   R(s) (1 - td (1 + cos 3 phi) / 2) (1 - fd g(s, phi) (1 - cos 3 phi) / 2)
 * with phi = theta - taenia angle: the three taeniae pull the wall in by
 * the fraction td (a rounded triangle); haustral folds (Gaussian ridges of
 * half-width fold_width_m every fold_spacing_m, staggered by a third of
 * the spacing between the three sectors) narrow it by up to fd midway
 * between the taeniae. R, td and fd blend smoothly over ~3 cm at segment
 * boundaries; the cecum's last radius-length rounds off as a hemisphere.
 *
 * Triangles: about 2 x (length / step_m) x ring_vertices (defaults: 0.002
 * m and 192, ~290 000 triangles for 1.5 m; 0.001 m and 672 give ~2 million).
 *
 * Mobile segments are the centreline's spans, in order (colon_bow()).
 *
 * Contact: each model also carries the contact surface of the haptics
 * (contact.h), built from its mesh before any bow.
 *
 * Allocation: colon_create() and colon_import() allocate everything; the
 * rest does not. colon_bow() is safe in the force loop (no allocation, no
 * I/O): ~0.1 us per span sample (the sigmoid: ~20 us); moving the span's
 * mesh too costs ~20-50 ns per vertex (the sigmoid at the default
 * resolution: 1-2 ms), so the loop should bow the centreline only and
 * place just the segments it needs (mesh_place()). Building a case takes
 * ~50 ms at the default resolution, ~0.5 s at 2 million triangles. One
 * writer; readers on other threads need their own copy.
 */
#ifndef ENDOSIM_COLON_H
#define ENDOSIM_COLON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "model/anatomy.h"
#include "model/centreline.h"
#include "model/contact.h"
#include "model/mesh.h"
#include "model/scope.h"

#define COLON_MAX_REGIONS ANATOMY_SEGMENTS

struct colon_params {
	double step_m;          /* centreline and ring spacing, 0.0002..0.01 */
	uint32_t ring_vertices; /* per ring, 8..4096 */
	double segment_m;       /* mesh segment length, 0.01..0.5 */
	double contact_radius_m; /* the scope tip's radius: the contact
				    surface's inset (contact.h), 0..0.02 */
};

/* The default resolution ([case] in the configuration); the contact
 * radius is the scope's (scope.h). */
#define COLON_DEFAULT_STEP_M 0.002
#define COLON_DEFAULT_RING_VERTICES 192
#define COLON_DEFAULT_SEGMENT_M 0.04

#define COLON_PARAMS_DEFAULT { .step_m = COLON_DEFAULT_STEP_M, \
			       .ring_vertices = COLON_DEFAULT_RING_VERTICES, \
			       .segment_m = COLON_DEFAULT_SEGMENT_M, \
			       .contact_radius_m = SCOPE_RADIUS_M }

/* A named stretch of the colon: an anatomical segment, or the whole of an
 * imported colon. */
struct colon_region {
	char name[ANATOMY_NAME];
	double s0_m, s1_m;
	double diameter_m;         /* nominal; 0 when imported */
	int span;                  /* its mobile span, -1 if fixed */
	double mesentery_n_per_m;  /* mobile only */
	double max_bow_m;          /* mobile only: the mesentery's height */
};

struct colon;

/* Builds case A. NULL with one line in ERR (bad parameters, ENOMEM). */
struct colon *colon_create(const struct anatomy *a,
			   const struct colon_params *p, char *err,
			   size_t errsize);

/*
 * Imports the Wavefront OBJ mesh OBJ_PATH with the centreline in
 * CENTRELINE_PATH (objio.h), or, when that is NULL, the OBJ's own polyline
 * ('l' elements, as colon_export() writes). The centreline is resampled at
 * p->step_m; p->ring_vertices is unused. NULL with "FILE:LINE: what" (or
 * "FILE: what") in ERR.
 */
struct colon *colon_import(const char *obj_path, const char *centreline_path,
			   const struct colon_params *p, char *err,
			   size_t errsize);

/* NULL is fine. */
void colon_destroy(struct colon *c);

/* Writes the mesh as placed now, with the centreline (objio.h). */
int colon_export(const struct colon *c, const char *path, char *err,
		 size_t errsize);

const char *colon_name(const struct colon *c);
const struct anatomy *colon_anatomy(const struct colon *c); /* NULL: import */
struct centreline *colon_centreline(const struct colon *c);
struct mesh *colon_mesh(const struct colon *c);

/* The surface the tip's centre touches: the mesh as it was built (the
 * undeformed placement), inset by contact_radius_m (contact.h). */
const struct contact *colon_contact(const struct colon *c);

int colon_regions(const struct colon *c);
const struct colon_region *colon_region(const struct colon *c, int i);
/* The region arc length S_M (m) lies in: the first whose far end is
 * beyond it, the last past them all (the first before them, and for a
 * NaN). */
int colon_region_at(const struct colon *c, double s_m);

/* Where the cecum starts (m), the whole length for an imported colon. */
double colon_cecum_s(const struct colon *c);

/*
 * Bows mobile span SPAN (0..spans-1) by AMPLITUDE_M and, with PLACE_MESH,
 * moves its mesh vertices too. Returns 0 or -EINVAL.
 */
int colon_bow(struct colon *c, int span, double amplitude_m, bool place_mesh);

/* Bytes held by the model. */
size_t colon_bytes(const struct colon *c);

/*
 * The lumen's radius the insertion tube meets at centreline sample SAMPLE
 * (clamped), m: the mean of the mesh's ring there (folds and taeniae
 * included), averaged over 1.5 cm either way; any colon, imported too.
 */
double colon_tube_radius(const struct colon *c, size_t sample);

/* Lumen radius (m) of a generated case at S_M, THETA_RAD (for tests). */
double colon_lumen_radius(const struct colon *c, double s_m, double theta_rad);

/*
 * The same round one ring: what the radius takes from S_M alone (the
 * segments' diameters, taeniae and folds blended, the cecum's dome),
 * found once by colon_ring_at() (~0.5 us), then colon_ring_radius() of
 * it at THETA_RAD (a few tens of ns) is colon_lumen_radius(C, S_M,
 * THETA_RAD) exactly. Fixed work, no allocation: the force loop may.
 */
struct colon_ring {
	double s_m;
	double r_m;    /* the round lumen's radius, with the cecum's dome */
	double taenia; /* the taeniae's depth, 0..1 */
	double fold;   /* the folds' depth, 0..1 */
};

void colon_ring_at(const struct colon *c, double s_m, struct colon_ring *out);
double colon_ring_radius(const struct colon *c, const struct colon_ring *ring,
			 double theta_rad);

#endif
