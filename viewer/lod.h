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
 * The indices address the vertices as gpumesh.h lays them out: for a
 * generated tube, ring i's vertex j at lod_vertex(ring, i, j), every ring
 * carrying its first vertex again at j = ring (where the texture wraps),
 * the cecum's pole last; any other mesh (an import) as the mesh does, with
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
};

/* Ring spacing (m) and vertices per ring each level aims at. */
extern const double lod_step_m[LOD_LEVELS];
extern const uint32_t lod_ring[LOD_LEVELS];

/* Where vertex J (0..RING) of ring I of a tube lies in the GPU's arrays. */
static inline uint32_t lod_vertex(uint32_t ring, uint32_t i, uint32_t j)
{
	return i * (ring + 1) + j;
}

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
