/*
 * mesh.h - the colon's triangle mesh, shared by haptics and graphics, tied
 * to the centreline so that it follows the centreline's deformation.
 *
 * Every vertex belongs to one centreline sample and keeps its offset from
 * that sample in the sample's frame (t, u, v); its world position is
 *   p = r(i) + a t(i) + b u(i) + c v(i)
 * (mesh_place()). A generated tube has a = 0 (rings in the normal planes);
 * an imported vertex belongs to the sample nearest to it, moved to the
 * neighbour whose normal plane is nearest; a vertex that so lands on
 * another part of the colon (a wider lumen passing close) is bound again
 * near its triangle's other corners.
 *
 * A reader may scale the lumen radially (endoview: the gas's lumen factor,
 * gas.h): mesh_place() multiplies each vertex' offset across the
 * centreline (b, c) by its sample's radial[i] (1 as created), after the
 * folds are held as below: the haptics scale the same placed surface by
 * the same factor (haptics.c), so the picture and the contact are one
 * surface.
 *
 * Folds: inside a bend tighter than the lumen the normal planes of nearby
 * samples cross within the wall, and rings placed at full radius would
 * cross too. For a generated tube, mesh_place() therefore shortens a
 * vertex' offset (b, c) so that it stays MESH_FOLD_MARGIN of the way from
 * its own plane to the plane of every sample within the largest radius
 * (behind those ahead, in front of those behind). Each ring then lies
 * strictly between its neighbours' planes, so no two strips of triangles
 * within that reach can cross. Where the planes do not come within the
 * wall (bends wider than the lumen) nothing changes. An imported mesh is
 * placed as it is: it keeps its own shape.
 *
 * Triangles wind counter-clockwise seen from inside the lumen: the face
 * normal (B - A) x (C - A) faces the lumen, like the vertex normals.
 *
 * Segments cut the colon along the material arc length s into runs of
 * samples segment_m long (a few cm; the last one 0.5 to 1.5 times that);
 * triangle k belongs to the segment of its lowest sample, and the
 * triangles are stored segment by segment, so the triangles near any
 * stretch of s are one contiguous index range found in O(1)
 * (mesh_range()). Each segment has an axis-aligned bounding box.
 *
 * Allocation: mesh_create() and mesh_finish() allocate. mesh_place()
 * and its variants, mesh_range() and the accessors do not, never block,
 * and are safe in the force loop (mesh_place() costs ~20-50 ns per
 * vertex, more inside bends tighter than the lumen; mesh_range() ~10-20
 * ns). One writer.
 */
#ifndef ENDOSIM_MESH_H
#define ENDOSIM_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "model/centreline.h"

#define MESH_FOLD_MARGIN 0.8 /* share of the way to a neighbour's plane */

struct mesh_segment {
	double s0_m, s1_m;    /* material range */
	uint32_t first;       /* first triangle */
	uint32_t count;       /* triangles */
	float min[3], max[3]; /* bounding box of its triangles, m */
};

struct mesh {
	uint32_t vertices;
	uint32_t triangles;
	float (*pos)[3];       /* world position, m (mesh_place()) */
	float (*nrm)[3];       /* unit normal into the lumen */
	uint32_t (*tri)[3];    /* vertex indices */
	uint32_t *sample;      /* the vertex' centreline sample */
	float (*off)[3];       /* offset (a, b, c) in that sample's frame, m */
	float (*noff)[3];      /* normal in that sample's frame */
	size_t samples;        /* of the centreline */
	uint32_t *sample_first; /* vertices of sample i: [sf[i], sf[i + 1]) */
	uint32_t tri_span;     /* most samples between a triangle's vertices */
	int hold_folds;        /* generated: keep rings between planes */
	uint32_t reach;        /* samples within the largest offset */
	float *sample_rho;     /* per sample: its largest offset, m */
	float (*sample_axial)[2]; /* per sample: its offsets' least and
				     largest a (along t), m */
	uint32_t *near_lo, *near_hi; /* per sample: planes that may cut in */
	float (*sample_min)[3], (*sample_max)[3]; /* per sample: the box of
						    its vertices as placed */
	float *radial;         /* per sample: the scale of its vertices'
				  offsets across the centreline (1: as the
				  offsets say; mesh_place() applies it) */
	double segment_m;
	double step_m;         /* the centreline's */
	uint32_t segments;
	struct mesh_segment *seg;
};

/*
 * Room for VERTICES and TRIANGLES on a centreline of SAMPLES samples. The
 * caller fills tri and either sample/off (generated) or pos (imported),
 * then calls mesh_finish(). NULL on ENOMEM.
 */
struct mesh *mesh_create(uint32_t vertices, uint32_t triangles,
			 size_t samples);

/* NULL is fine. */
void mesh_destroy(struct mesh *m);

enum mesh_finish_from {
	MESH_FROM_OFFSETS,   /* sample and off are set: place them */
	MESH_FROM_POSITIONS, /* pos is set: bind each vertex to its nearest
				sample, orient the triangles to face the
				centreline */
};

/*
 * Completes the mesh on CL: orders vertices by sample and triangles by
 * segment (SEGMENT_M long), computes the vertex normals, places every
 * vertex and the bounding boxes. Returns 0, -ENOMEM, or -EINVAL with one
 * line in ERR (a vertex with no sample within reach, a degenerate mesh).
 */
int mesh_finish(struct mesh *m, const struct centreline *cl,
		double segment_m, enum mesh_finish_from from, char *err,
		size_t errsize);

/*
 * Places the vertices of samples FIRST..LAST (inclusive), and those within
 * reach of them whose fold limits depend on them, from CL's current
 * samples, and refreshes the bounding boxes of the segments they touch.
 */
void mesh_place(struct mesh *m, const struct centreline *cl, size_t first,
		size_t last);

/*
 * mesh_place() for a reader that uses only some vertices (endoview draws
 * a few of a fine mesh's): of the vertices it places, only those KEEP
 * marks (one byte per vertex, non-zero: kept; NULL: all) get pos and nrm;
 * the others keep their old ones (mesh_vertex_at() gives where they lie)
 * and cost nothing. The bounding boxes hold every vertex, kept or not, as
 * mesh_place() puts it, but are made from each sample's ring (its centre,
 * frame, largest offset and radial scale), not vertex by vertex: never
 * smaller than mesh_place()'s, larger where held folds pull a ring in
 * (by at most the ring's largest offset). For culling, which they keep
 * conservative; the daemon's mesh_place() boxes stay exact.
 */
void mesh_place_kept(struct mesh *m, const struct centreline *cl,
		     size_t first, size_t last, const uint8_t *keep);

/*
 * Where mesh_place() puts vertex J on CL as it is now: P (m), to the bit.
 * For a vertex mesh_place_kept() did not keep; CL must be the one the
 * mesh was last placed on, the vertex' sample's fold limits (near_lo,
 * near_hi) as that placement left them. Does not write the mesh.
 */
void mesh_vertex_at(const struct mesh *m, const struct centreline *cl,
		    uint32_t j, float p[3]);

/* The segment holding material position S_M (clamped to the mesh). */
uint32_t mesh_segment_at(const struct mesh *m, double s_m);

/*
 * The triangles of every segment that overlaps [S0_M, S1_M]: *FIRST and
 * *COUNT (one contiguous range). O(1).
 */
void mesh_range(const struct mesh *m, double s0_m, double s1_m,
		uint32_t *first, uint32_t *count);

/* Bytes held by the mesh. */
size_t mesh_bytes(const struct mesh *m);

#endif
