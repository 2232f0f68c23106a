/*
 * gpumesh.h - the colon's mesh on the GPU: one vertex array with the
 * placed positions, the normals (their tilt from the smooth tube deepened,
 * so that the folds read clearly), the vessel texture's coordinates
 * (vessels.h), in the layout lod.h describes, and the levels of detail's
 * index buffer. Both views draw from it.
 *
 * Main thread, with the GL context current.
 */
#ifndef ENDOVIEW_GPUMESH_H
#define ENDOVIEW_GPUMESH_H

#include <stdint.h>

#include "viewer/lod.h"
#include "viewer/model.h"

struct gpumesh;

/* Uploads M (placed as it is now: the vertices L draws, lod.h) and L,
 * which must outlive G. NULL on failure (logged). */
struct gpumesh *gpumesh_create(const struct model *m, const struct lod *l);

/* NULL is fine. */
void gpumesh_destroy(struct gpumesh *g);

/* Uploads the positions and normals of M's vertices [FIRST, FIRST +
 * COUNT) that the levels draw (the rows that hold them). */
void gpumesh_update(struct gpumesh *g, const struct model *m, uint32_t first,
		    uint32_t count);

/* Binds the vertex array for gpumesh_draw(). */
void gpumesh_bind(const struct gpumesh *g);

/* Draws the triangles of R (bound first). Returns their number. */
uint32_t gpumesh_draw(const struct gpumesh *g, struct lod_range r);

#endif
