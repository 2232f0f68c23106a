/* gpumesh.c - see gpumesh.h. */
#include "viewer/gpumesh.h"

#include <math.h>
#include <stdlib.h>

#include "viewer/gfx.h"
#include "base/log.h"
#include "base/vec3.h"
#include "viewer/vessels.h"

#define RELIEF 2.0 /* how much the folds' normals are deepened */

enum { POS, NRM, TEX, IDX, BUFFERS };

struct gpumesh {
	GLuint vao;
	GLuint buf[BUFFERS];
	const struct lod *lod; /* the layout */
	float (*pos)[3];   /* staging, as the GPU lays them out */
	float (*nrm)[3];
};

/*
 * Vertex V's normal for shading: its tilt along the colon (a fold's
 * flanks) deepened by RELIEF, so that folds read as clearly as in a real
 * lumen lit from the lens; the more a normal already faces along the
 * colon (the cecum's dome), the less.
 */
static void relief(const struct model *m, uint32_t v, float out[3])
{
	const struct mesh *me = m->mesh;
	const double *t = centreline_sample(m->cl, me->sample[v])->t;
	double n[3] = { me->nrm[v][0], me->nrm[v][1], me->nrm[v][2] };
	double tilt = vec3_dot(n, t);

	vec3_axpy(n, n, RELIEF * tilt * (1 - fabs(tilt)), t);
	vec3_normalize(n);
	for (int k = 0; k < 3; k++) {
		out[k] = (float)n[k];
	}
}

static void stage(struct gpumesh *g, const struct model *m, uint32_t k0,
		  uint32_t k1)
{
	for (uint32_t k = k0; k < k1; k++) {
		uint32_t v = lod_source(g->lod, k, NULL);

		for (int x = 0; x < 3; x++) {
			g->pos[k][x] = m->mesh->pos[v][x];
		}
		relief(m, v, g->nrm[k]);
	}
}

/* The vessel texture's coordinates: along s; around, a tube's ring once
 * round to VESSELS_AROUND (its seam vertex carries the end), any other
 * mesh mirrored (vessels_around()). */
static float (*texcoords(const struct gpumesh *g, const struct model *m))[2]
{
	const struct mesh *me = m->mesh;
	uint32_t ring = g->lod->ring;
	float (*uv)[2] = malloc((size_t)g->lod->vertices * sizeof(*uv));
	double ds = centreline_step(m->cl);

	for (uint32_t k = 0; uv && k < g->lod->vertices; k++) {
		uint32_t j, v = lod_source(g->lod, k, &j);

		uv[k][0] = (float)(me->sample[v] * ds / VESSELS_TILE_M);
		if (ring) {
			uv[k][1] = (float)j / (float)ring *
				   (float)VESSELS_AROUND;
		} else {
			uv[k][1] = (float)vessels_around(atan2(me->off[v][2],
							       me->off[v][1]));
		}
	}
	return uv;
}

static void attribute(GLuint buf, int attr, int size, GLsizeiptr bytes,
		      const void *data, GLenum usage)
{
	glBindBuffer(GL_ARRAY_BUFFER, buf);
	glBufferData(GL_ARRAY_BUFFER, bytes, data, usage);
	glEnableVertexAttribArray((GLuint)attr);
	glVertexAttribPointer((GLuint)attr, size, GL_FLOAT, GL_FALSE, 0, NULL);
}

static int upload_all(struct gpumesh *g, const struct model *m,
		      const struct lod *l)
{
	GLsizeiptr vbytes = (GLsizeiptr)l->vertices * 3 * sizeof(float);
	float (*uv)[2] = texcoords(g, m);

	if (!uv) {
		return -1;
	}
	stage(g, m, 0, l->vertices);
	glGenVertexArrays(1, &g->vao);
	glBindVertexArray(g->vao);
	glGenBuffers(BUFFERS, g->buf);
	attribute(g->buf[POS], GFX_ATTR_POSITION, 3, vbytes, g->pos,
		  GL_DYNAMIC_DRAW);
	attribute(g->buf[NRM], GFX_ATTR_NORMAL, 3, vbytes, g->nrm,
		  GL_DYNAMIC_DRAW);
	attribute(g->buf[TEX], GFX_ATTR_TEXCOORD, 2, vbytes / 3 * 2, uv,
		  GL_STATIC_DRAW);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->buf[IDX]);
	glBufferData(GL_ELEMENT_ARRAY_BUFFER,
		     (GLsizeiptr)l->indices * sizeof(uint32_t), l->index,
		     GL_STATIC_DRAW);
	glBindVertexArray(0);
	free(uv);
	return gfx_check("colon mesh upload") ? -1 : 0;
}

struct gpumesh *gpumesh_create(const struct model *m, const struct lod *l)
{
	struct gpumesh *g = calloc(1, sizeof(*g));

	if (!g) {
		return NULL;
	}
	g->lod = l;
	g->pos = malloc((size_t)l->vertices * sizeof(*g->pos));
	g->nrm = malloc((size_t)l->vertices * sizeof(*g->nrm));
	if (!g->pos || !g->nrm || upload_all(g, m, l)) {
		log_err("colon mesh: cannot upload %u vertices", l->vertices);
		gpumesh_destroy(g);
		return NULL;
	}
	return g;
}

void gpumesh_destroy(struct gpumesh *g)
{
	if (!g) {
		return;
	}
	glDeleteBuffers(BUFFERS, g->buf);
	glDeleteVertexArrays(1, &g->vao);
	free(g->pos);
	free(g->nrm);
	free(g);
}

void gpumesh_update(struct gpumesh *g, const struct model *m, uint32_t first,
		    uint32_t count)
{
	GLintptr at;
	GLsizeiptr bytes;
	uint32_t k0, k1;

	if (!count) {
		return;
	}
	lod_gpu_range(g->lod, first, count, &k0, &k1);
	if (k0 == k1) {
		return;
	}
	stage(g, m, k0, k1);
	at = (GLintptr)k0 * 3 * sizeof(float);
	bytes = (GLsizeiptr)(k1 - k0) * 3 * sizeof(float);
	glBindBuffer(GL_ARRAY_BUFFER, g->buf[POS]);
	glBufferSubData(GL_ARRAY_BUFFER, at, bytes, g->pos[k0]);
	glBindBuffer(GL_ARRAY_BUFFER, g->buf[NRM]);
	glBufferSubData(GL_ARRAY_BUFFER, at, bytes, g->nrm[k0]);
	glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void gpumesh_bind(const struct gpumesh *g)
{
	glBindVertexArray(g->vao);
}

uint32_t gpumesh_draw(const struct gpumesh *g, struct lod_range r)
{
	(void)g;
	if (!r.count) {
		return 0;
	}
	glDrawElements(GL_TRIANGLES, (GLsizei)r.count, GL_UNSIGNED_INT,
		       (void *)((uintptr_t)r.first * sizeof(uint32_t)));
	return r.count / 3;
}
