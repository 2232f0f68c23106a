/* scene.c - see scene.h. */
#include "model/scene.h"

#include <stdlib.h>
#include <string.h>

struct scene {
	const struct colon *colon;
	uint64_t id;
	uint32_t vchunks, tchunks;
	Endosim__SceneReply reply;
	Endosim__SceneInfo info;
	Endosim__SceneChunk chunk;
	double *centreline;        /* x, y, z per sample */
	double frame_u0[3];
	double span_s[2 * CENTRELINE_MAX_SPANS];
	Endosim__SceneRegion region[COLON_MAX_REGIONS];
	Endosim__SceneRegion *region_p[COLON_MAX_REGIONS];
	Endosim__ScenePolyp polyp[ANATOMY_MAX_POLYPS];
	Endosim__ScenePolyp *polyp_p[ANATOMY_MAX_POLYPS];
	Endosim__SceneSite site[ANATOMY_MAX_SITES];
	Endosim__SceneSite *site_p[ANATOMY_MAX_SITES];
	Endosim__SceneSegment *segment;
	Endosim__SceneSegment **segment_p;
	Endosim__SceneScope scope;
};

static void fill_regions(struct scene *s)
{
	const struct colon *c = s->colon;

	for (int i = 0; i < colon_regions(c); i++) {
		const struct colon_region *r = colon_region(c, i);
		Endosim__SceneRegion *x = &s->region[i];

		endosim__scene_region__init(x);
		x->name = (char *)r->name;
		x->s0_m = r->s0_m;
		x->s1_m = r->s1_m;
		x->diameter_m = r->diameter_m;
		x->span = r->span;
		x->mesentery_n_per_m = r->mesentery_n_per_m;
		x->max_bow_m = r->max_bow_m;
		s->region_p[i] = x;
	}
	s->info.n_regions = (size_t)colon_regions(c);
	s->info.regions = s->region_p;
}

static void fill_polyps(struct scene *s, const struct anatomy *a)
{
	for (int i = 0; a && i < a->polyps; i++) {
		Endosim__ScenePolyp *x = &s->polyp[i];

		endosim__scene_polyp__init(x);
		x->s_m = a->polyp[i].s_m;
		x->angle_rad = a->polyp[i].angle_rad;
		x->diameter_m = a->polyp[i].diameter_m;
		x->shape = (char *)anatomy_polyp_shape_name(a->polyp[i].shape);
		s->polyp_p[i] = x;
	}
	s->info.n_polyps = a ? (size_t)a->polyps : 0;
	s->info.polyps = s->polyp_p;
}

/* The assistant's sites: their vectors point into the colon's anatomy. */
static void fill_sites(struct scene *s, const struct anatomy *a)
{
	for (int i = 0; a && i < a->sites; i++) {
		const struct anatomy_site *in = &a->site[i];
		Endosim__SceneSite *x = &s->site[i];

		endosim__scene_site__init(x);
		x->name = (char *)in->name;
		x->n_position_m = x->n_direction = 3;
		x->position_m = (double *)in->position_m;
		x->direction = (double *)in->direction;
		x->radius_m = in->radius_m;
		s->site_p[i] = x;
	}
	s->info.n_sites = a ? (size_t)a->sites : 0;
	s->info.sites = s->site_p;
}

static void fill_segments(struct scene *s, const struct mesh *m)
{
	for (uint32_t k = 0; k < m->segments; k++) {
		Endosim__SceneSegment *x = &s->segment[k];

		endosim__scene_segment__init(x);
		x->s0_m = m->seg[k].s0_m;
		x->s1_m = m->seg[k].s1_m;
		x->first_triangle = m->seg[k].first;
		x->triangles = m->seg[k].count;
		x->n_min = x->n_max = 3;
		x->min = (float *)m->seg[k].min;
		x->max = (float *)m->seg[k].max;
		s->segment_p[k] = x;
	}
	s->info.n_segments = m->segments;
	s->info.segments = s->segment_p;
	s->info.segment_m = m->segment_m;
}

static void fill_centreline(struct scene *s, const struct centreline *cl)
{
	size_t n = centreline_count(cl);

	for (size_t i = 0; i < n; i++) {
		memcpy(&s->centreline[3 * i], centreline_base(cl, i)->p,
		       3 * sizeof(double));
	}
	memcpy(s->frame_u0, centreline_base(cl, 0)->u, sizeof(s->frame_u0));
	for (int k = 0; k < centreline_spans(cl); k++) {
		centreline_span_range(cl, k, &s->span_s[2 * k],
				      &s->span_s[2 * k + 1]);
	}
	s->info.n_centreline = 3 * n;
	s->info.centreline = s->centreline;
	s->info.n_frame_u0 = 3;
	s->info.frame_u0 = s->frame_u0;
	s->info.n_span_s = 2 * (size_t)centreline_spans(cl);
	s->info.span_s = s->span_s;
	s->info.step_m = centreline_step(cl);
	s->info.length_m = centreline_length(cl);
}

static void fill_info(struct scene *s)
{
	const struct colon *c = s->colon;
	const struct anatomy *a = colon_anatomy(c);
	const struct mesh *m = colon_mesh(c);

	endosim__scene_info__init(&s->info);
	s->info.name = (char *)colon_name(c);
	s->info.description = a ? (char *)a->description : "imported mesh";
	s->info.cecum_s_m = colon_cecum_s(c);
	s->info.vertices = m->vertices;
	s->info.triangles = m->triangles;
	fill_centreline(s, colon_centreline(c));
	fill_regions(s);
	fill_polyps(s, a);
	fill_sites(s, a);
	fill_segments(s, m);
}

struct scene *scene_create(const struct colon *c, uint64_t scene_id)
{
	const struct mesh *m = colon_mesh(c);
	struct scene *s = calloc(1, sizeof(*s));

	if (!s) {
		return NULL;
	}
	s->colon = c;
	s->id = scene_id;
	s->vchunks = (m->vertices + SCENE_VERTICES_PER_CHUNK - 1) /
		     SCENE_VERTICES_PER_CHUNK;
	s->tchunks = (m->triangles + SCENE_TRIANGLES_PER_CHUNK - 1) /
		     SCENE_TRIANGLES_PER_CHUNK;
	s->centreline = calloc(3 * centreline_count(colon_centreline(c)),
			       sizeof(double));
	s->segment = calloc(m->segments, sizeof(*s->segment));
	s->segment_p = calloc(m->segments, sizeof(*s->segment_p));
	if (!s->centreline || !s->segment || !s->segment_p) {
		scene_destroy(s);
		return NULL;
	}
	fill_info(s);
	return s;
}

void scene_destroy(struct scene *s)
{
	if (!s) {
		return;
	}
	free(s->centreline);
	free(s->segment);
	free(s->segment_p);
	free(s);
}

uint64_t scene_id(const struct scene *s)
{
	return s->id;
}

uint32_t scene_chunks(const struct scene *s)
{
	return 1 + s->vchunks + s->tchunks;
}

/* Chunk K of TOTAL items PER chunk: its first item and its size. */
static uint32_t chunk_range(uint32_t total, uint32_t per, uint32_t k,
			    uint32_t *first)
{
	*first = k * per;
	return total - *first < per ? total - *first : per;
}

static void vertex_chunk(struct scene *s, uint32_t k)
{
	const struct mesh *m = colon_mesh(s->colon);
	uint32_t first, n = chunk_range(m->vertices, SCENE_VERTICES_PER_CHUNK,
					k, &first);

	s->chunk.first_vertex = first;
	s->chunk.n_positions = s->chunk.n_normals = 3 * (size_t)n;
	s->chunk.positions = &m->pos[first][0];
	s->chunk.normals = &m->nrm[first][0];
	s->chunk.n_vertex_sample = n;
	s->chunk.vertex_sample = &m->sample[first];
	s->chunk.n_vertex_offset = s->chunk.n_normal_offset = 3 * (size_t)n;
	s->chunk.vertex_offset = &m->off[first][0];
	s->chunk.normal_offset = &m->noff[first][0];
}

static void triangle_chunk(struct scene *s, uint32_t k)
{
	const struct mesh *m = colon_mesh(s->colon);
	uint32_t first, n = chunk_range(m->triangles,
					SCENE_TRIANGLES_PER_CHUNK, k, &first);

	s->chunk.first_triangle = first;
	s->chunk.n_indices = 3 * (size_t)n;
	s->chunk.indices = &m->tri[first][0];
}

void scene_set_scope(struct scene *s, const struct scope_params *p,
		     double radius_m)
{
	endosim__scene_scope__init(&s->scope);
	s->scope.bending_length_m = p->bending_length_m;
	s->scope.ud_gain = p->ud_gain;
	s->scope.lr_gain = p->lr_gain;
	s->scope.ud_limit_rad = p->ud_limit_rad;
	s->scope.lr_limit_rad = p->lr_limit_rad;
	s->scope.radius_m = radius_m;
	s->info.scope = &s->scope;
}

Endosim__SceneReply *scene_reply(struct scene *s, uint32_t chunk)
{
	if (chunk >= scene_chunks(s)) {
		return NULL;
	}
	endosim__scene_reply__init(&s->reply);
	s->reply.scene_id = s->id;
	s->reply.chunk = chunk;
	s->reply.chunks = scene_chunks(s);
	if (chunk == 0) {
		s->reply.info = &s->info;
		return &s->reply;
	}
	endosim__scene_chunk__init(&s->chunk);
	if (chunk <= s->vchunks) {
		vertex_chunk(s, chunk - 1);
	} else {
		triangle_chunk(s, chunk - 1 - s->vchunks);
	}
	s->reply.mesh = &s->chunk;
	return &s->reply;
}

void scene_client(struct scene *s, struct client_scene *out)
{
	const struct mesh *m = colon_mesh(s->colon);

	memset(out, 0, sizeof(*out));
	out->scene_id = s->id;
	out->info = &s->info;
	out->scope = s->info.scope;
	out->vertices = m->vertices;
	out->triangles = m->triangles;
	out->positions = m->pos;
	out->normals = m->nrm;
	out->vertex_sample = m->sample;
	out->vertex_offset = m->off;
	out->normal_offset = m->noff;
	out->indices = m->tri;
}
