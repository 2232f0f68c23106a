/*
 * lod.h - levels of detail of the colon's mesh, so that what endoview
 * draws stays in the thousands of triangles whatever the mesh's
 * resolution (the default ~290 000 triangles, or 2 million).
 *
 * A generated tube (model.h: RING vertices per ring, one ring per
 * centreline sample) is drawn at level L from every ring_stride[L]-th ring
 * and every vertex_stride[L]-th vertex of those rings, aiming at the rings
 * and vertices per ring of lod_step_m[L] and lod_ring[L]. The endoscopic
 * view's levels (0 .. LOD_OVERVIEW - 1) keep the same vertices around and
 * thin out the rings only (the lumen's shape, taeniae and folds, varies
 * slowly around; the folds, a few mm wide, need the rings close along the
 * colon near the lens): neighbouring segments at different levels then
 * share their boundary ring exactly, without cracks. LOD_OVERVIEW is
 * coarser all round, for the colon seen whole from outside.
 *
 * Each segment's triangles at each level are one contiguous run of
 * indices, the runs of one level in segment order; strips end on each
 * segment's first ring. The triangles wind as the mesh's
 * (counter-clockwise from the lumen).
 *
 * The indices address the vertices as gpumesh.h lays them out, and that
 * layout holds only what some level draws: for a generated tube, the rings
 * some level draws, one row each (in order), and of each every column-th
 * vertex (column: the largest stride all levels' vertex strides are
 * multiples of), ring i's vertex j at lod_vertex(l, i, j), every row
 * carrying its first vertex again at j = ring (where the texture wraps),
 * the cecum's pole last, alone on its row; drawn marks those vertices of
 * the mesh. Any other mesh (an import) is laid out as the mesh is, with
 * one level: its own triangles.
 *
 * lod_create() allocates; the rest does not. Any thread, read-only.
 */
#ifndef ENDOVIEW_LOD_H
#define ENDOVIEW_LOD_H

#include <stdint.h>

#include "model/mesh.h"

#define LOD_LEVELS 5
#define LOD_OVERVIEW 4 /* the level for the overview */

struct lod_range {
	uint32_t first; /* first index */
	uint32_t count; /* indices, 3 per triangle */
};

struct lod {
	int levels;
	uint32_t segments;
	uint32_t ring;                      /* of the tube, 0: not one */
	uint32_t ring_stride[LOD_LEVELS];   /* samples from ring to ring */
	uint32_t vertex_stride[LOD_LEVELS]; /* vertices around a ring */
	uint32_t *index;
	uint32_t indices;
	struct lod_range *range; /* [level * segments + segment] */
	/* the GPU's vertices (a tube's; an import's are the mesh's) */
	uint32_t vertices;
	uint32_t column;    /* every column-th vertex round a ring */
	uint32_t rows;
	uint32_t *row;      /* per sample: its row, LOD_NO_ROW if not drawn */
	uint32_t *row_sample; /* per row: its sample */
	uint8_t *drawn;     /* per vertex of the mesh: on the GPU (non-zero) */
};

#define LOD_NO_ROW UINT32_MAX

/* Ring spacing (m) and vertices per ring each level aims at. */
extern const double lod_step_m[LOD_LEVELS];
extern const uint32_t lod_ring[LOD_LEVELS];

/* Where vertex J (0..ring, a multiple of column) of ring I of a tube
 * (a ring some level draws) lies in the GPU's arrays. */
static inline uint32_t lod_vertex(const struct lod *l, uint32_t i, uint32_t j)
{
	return l->row[i] * (l->ring / l->column + 1) + j / l->column;
}

/* The mesh's vertex that GPU vertex K shows; *J (may be NULL): a tube's
 * vertex' place round its ring, 0..ring (ring: the seam's copy), else 0. */
uint32_t lod_source(const struct lod *l, uint32_t k, uint32_t *j);

/* The GPU's vertices [*K0, *K1) that show any of the mesh's vertices
 * [FIRST, FIRST + COUNT) (COUNT > 0); *K0 == *K1 if none. */
void lod_gpu_range(const struct lod *l, uint32_t first, uint32_t count,
		   uint32_t *k0, uint32_t *k1);

/* The levels of mesh M, a generated tube of RING vertices per ring (0 if it
 * is not one). NULL on ENOMEM or a mesh of more than 2^32 indices. */
struct lod *lod_create(const struct mesh *m, uint32_t ring);

/* NULL is fine. */
void lod_destroy(struct lod *l);

/* Segment K at LEVEL (clamped to the levels there are). */
struct lod_range lod_segment(const struct lod *l, int level, uint32_t k);

/* Segments K0..K1 (inclusive) at LEVEL: one run. */
struct lod_range lod_span(const struct lod *l, int level, uint32_t k0,
			  uint32_t k1);

#endif
