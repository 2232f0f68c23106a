/*
 * viewer_fixture.h - for the viewer's unit tests: a daemon's colon (a case
 * from config/cases or tests/cases, at a given resolution) and the scene
 * a viewer would gather from GetScene for it (proto/client.h), built from
 * the daemon's own reply (scene.h) and mesh arrays, without a socket.
 */
#ifndef VIEWER_FIXTURE_H
#define VIEWER_FIXTURE_H

#include <stdio.h>
#include <string.h>

#include "conf/cases.h"
#include "conf/config.h"
#include "viewer/model.h"
#include "model/scene.h"

struct fixture {
	struct colon *colon;
	struct scene *scene;
	struct client_scene cs; /* points into colon and scene */
	struct model *model;
};

static inline struct colon *fixture_colon(const char *dir, const char *name,
				   double step_m, uint32_t ring)
{
	struct config cfg;
	char err[512];
	struct colon *c;

	config_defaults(&cfg);
	snprintf(cfg.colon.directory, sizeof(cfg.colon.directory), "%s", dir);
	cfg.colon.step_m = step_m;
	cfg.colon.ring_vertices = ring;
	c = cases_load(&cfg, name, err, sizeof(err));
	if (!c) {
		print_error("%s\n", err);
		fail();
	}
	return c;
}

/* What client_get_scene() would have gathered for F's colon. */
static inline void fixture_scene(struct fixture *f, uint64_t id)
{
	f->scene = scene_create(f->colon, id);
	assert_non_null(f->scene);
	scene_client(f->scene, &f->cs);
}

/* The case NAME from DIR at STEP_M, RING, and the viewer's model of it. */
static inline void fixture_setup(struct fixture *f, const char *dir,
			  const char *name, double step_m, uint32_t ring)
{
	char err[256];

	f->colon = fixture_colon(dir, name, step_m, ring);
	fixture_scene(f, 42);
	f->model = model_create(&f->cs, err, sizeof(err));
	if (!f->model) {
		print_error("%s\n", err);
		fail();
	}
}

static inline void fixture_teardown(struct fixture *f)
{
	model_destroy(f->model);
	scene_destroy(f->scene);
	colon_destroy(f->colon);
	memset(f, 0, sizeof(*f));
}

/* Largest distance between the vertices of the viewer's and the daemon's
 * meshes. */
static inline double fixture_placed_error(const struct fixture *f)
{
	const struct mesh *a = f->model->mesh, *b = colon_mesh(f->colon);
	double worst = 0;

	for (uint32_t j = 0; j < a->vertices; j++) {
		for (int k = 0; k < 3; k++) {
			double d = (double)a->pos[j][k] - b->pos[j][k];

			worst = d > worst ? d : -d > worst ? -d : worst;
		}
	}
	return worst;
}

#endif
