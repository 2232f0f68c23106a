/*
 * scene.h - the colon as GetScene serves it (proto/endosim.proto): chunk 0
 * the case's metadata and centreline, chunks 1.. the mesh, vertices first
 * (SCENE_VERTICES_PER_CHUNK, ~1.7 MB each) then triangles
 * (SCENE_TRIANGLES_PER_CHUNK, ~1.5 MB each), so that no reply passes a
 * few MiB whatever the resolution.
 *
 * Chunk 0 also says which scope the colon is rendered with (the scope's
 * parameters, scene_set_scope()) and where the assistant may press on
 * the abdomen (the case's sites, by name). The replies point into the
 * colon's anatomy (the sites), its undeformed centreline and mesh, which
 * nobody writes once built (the force loop bows the centreline's current
 * samples only), so the control thread may serve them while the loop
 * runs. Any one thread that is not the force loop (endosimd's control
 * thread, the viewer's replay); a scene is not shared between threads;
 * scene_create() allocates.
 */
#ifndef ENDOSIM_SCENE_H
#define ENDOSIM_SCENE_H

#include <stdint.h>

#include "proto/client.h"
#include "model/colon.h"
#include "model/scope.h"
#include "proto/endosim.pb-c.h"

#define SCENE_VERTICES_PER_CHUNK 32768u
#define SCENE_TRIANGLES_PER_CHUNK 131072u

struct scene;

/* The replies for colon C (not owned; it must outlive the scene), known
 * to clients as SCENE_ID. NULL on ENOMEM. */
struct scene *scene_create(const struct colon *c, uint64_t scene_id);

/* NULL is fine. */
void scene_destroy(struct scene *s);

uint64_t scene_id(const struct scene *s);
uint32_t scene_chunks(const struct scene *s);

/*
 * The scope chunk 0 describes from now on (SceneInfo's scope): P and the
 * tip's and tube's RADIUS_M. Until it is set, chunk 0 has none.
 */
void scene_set_scope(struct scene *s, const struct scope_params *p,
		     double radius_m);

/*
 * The reply for chunk CHUNK: valid until the next call on S. Returns NULL
 * when there is no such chunk.
 */
Endosim__SceneReply *scene_reply(struct scene *s, uint32_t chunk);

/*
 * What client_get_scene() would gather from S's replies (proto/client.h),
 * without a socket: for a viewer that builds the colon itself (endoview
 * --replay) and for tests. OUT points into S and its colon: valid while
 * both live, never for client_scene_free().
 */
void scene_client(struct scene *s, struct client_scene *out);

#endif
