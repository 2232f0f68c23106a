/* model.c - see model.h. */
#include "viewer/model.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"
#include "model/gas.h"

#define PLACE_TOLERANCE_M 1e-4 /* the viewer's mesh against the daemon's */
#define PLANE_SEARCH 16        /* samples either side for a normal plane */

static int make_centreline(struct model *m, const Endosim__SceneInfo *in,
			   char *err, size_t errsize)
{
	double range[CENTRELINE_MAX_SPANS][2];
	size_t n = in->n_centreline / 3;
	int spans = (int)(in->n_span_s / 2);

	if (in->n_centreline % 3 || in->n_frame_u0 != 3 || in->n_span_s % 2 ||
	    spans > CENTRELINE_MAX_SPANS) {
		snprintf(err, errsize, "scene: malformed centreline");
		return -EPROTO;
	}
	m->cl = centreline_create((const double(*)[3])in->centreline, n,
				  in->step_m, in->frame_u0, err, errsize);
	if (!m->cl) {
		return -EPROTO;
	}
	for (int k = 0; k < spans; k++) {
		range[k][0] = in->span_s[2 * k];
		range[k][1] = in->span_s[2 * k + 1];
	}
	if (centreline_set_spans(m->cl, range, spans)) {
		snprintf(err, errsize, "scene: bad mobile spans");
		return -EPROTO;
	}
	return 0;
}

/* Every vertex' sample and offset, and the triangles, from the scene. */
static int fill_mesh(struct model *m, const struct client_scene *s,
		     char *err, size_t errsize)
{
	size_t samples = centreline_count(m->cl);

	m->mesh = mesh_create(s->vertices, s->triangles, samples);
	if (!m->mesh) {
		snprintf(err, errsize, "scene: out of memory for %u triangles",
			 s->triangles);
		return -ENOMEM;
	}
	for (uint32_t j = 0; j < s->vertices; j++) {
		if (s->vertex_sample[j] >= samples) {
			snprintf(err, errsize, "scene: vertex %u on sample %u "
				 "of %zu", j, s->vertex_sample[j], samples);
			return -EPROTO;
		}
	}
	memcpy(m->mesh->sample, s->vertex_sample,
	       s->vertices * sizeof(*m->mesh->sample));
	memcpy(m->mesh->off, s->vertex_offset,
	       s->vertices * sizeof(*m->mesh->off));
	memcpy(m->mesh->tri, s->indices, s->triangles * sizeof(*m->mesh->tri));
	return 0;
}

/* The daemon's segment table, and its triangle order, must be ours. */
static int check_segments(const struct model *m, const Endosim__SceneInfo *in,
			  char *err, size_t errsize)
{
	const struct mesh *me = m->mesh;

	if (in->n_segments != me->segments) {
		snprintf(err, errsize, "scene: %zu segments, the mesh makes %u",
			 in->n_segments, me->segments);
		return -EPROTO;
	}
	for (uint32_t k = 0; k < me->segments; k++) {
		if (in->segments[k]->first_triangle != me->seg[k].first ||
		    in->segments[k]->triangles != me->seg[k].count) {
			snprintf(err, errsize, "scene: segment %u differs from "
				 "the mesh made of it", k);
			return -EPROTO;
		}
	}
	return 0;
}

/* Triangle K of a tube of RING vertices a ring, as colon_create() makes
 * them: two per quad, ring by ring, then the fan to the cecum's pole. */
static void tube_triangle(uint32_t ring, uint32_t rings, uint32_t k,
			  uint32_t t[3])
{
	uint32_t q = k / 2, i = q / ring, j = q % ring;
	uint32_t a = i * ring + j, c = i * ring + (j + 1) % ring;

	if (i + 1 >= rings) { /* the fan */
		j = k - 2 * (rings - 1) * ring;
		t[0] = (rings - 1) * ring + j;
		t[1] = rings * ring;
		t[2] = (rings - 1) * ring + (j + 1) % ring;
	} else if (k % 2 == 0) {
		t[0] = a;
		t[1] = a + ring;
		t[2] = c;
	} else {
		t[0] = a + ring;
		t[1] = c + ring;
		t[2] = c;
	}
}

/* Every vertex at its place round the ring (j at 2 pi j / RING from u, to
 * within half a step) and every triangle where colon_create() puts it. */
static bool tube_laid_out(const struct mesh *me, uint32_t ring)
{
	uint32_t t[3];

	for (uint32_t v = 0; v + 1 < me->vertices; v++) {
		double a = atan2(me->off[v][2], me->off[v][1]) * ring /
			   (2 * M_PI);
		double step = remainder(a - v % ring, ring);

		if (fabs(step) > 0.5) {
			return false;
		}
	}
	for (uint32_t k = 0; k < me->triangles; k++) {
		tube_triangle(ring, (uint32_t)me->samples - 1, k, t);
		if (memcmp(t, me->tri[k], sizeof(t))) {
			return false;
		}
	}
	return true;
}

/*
 * A tube made by colon_create() (an import of one too): R vertices per
 * sample but the last (the cecum's pole), in ring order, and its
 * triangles. 0 for any other mesh.
 */
static uint32_t ring_size(const struct mesh *me)
{
	uint32_t ring = me->samples > 2 ? me->sample_first[1] : 0;

	if (ring < 3 || me->vertices != (me->samples - 1) * ring + 1 ||
	    me->triangles != (2 * (me->samples - 2) + 1) * ring) {
		return 0;
	}
	for (size_t i = 0; i + 1 < me->samples; i++) {
		if (me->sample_first[i] != i * ring) {
			return 0;
		}
	}
	return tube_laid_out(me, ring) ? ring : 0;
}

/*
 * The scene's normals stand (an import's come from the file's positions);
 * an import keeps its shape, a generated tube holds its folds (mesh.h).
 */
static void place_as_daemon(struct model *m, const struct client_scene *s,
			    const Endosim__SceneInfo *in)
{
	struct mesh *me = m->mesh;
	bool imported = in->n_regions == 1 && in->regions[0]->diameter_m == 0;

	memcpy(me->noff, s->normal_offset, s->vertices * sizeof(*me->noff));
	me->hold_folds = !imported;
	mesh_place(me, m->cl, 0, me->samples - 1);
	m->placed_error_m = 0;
	for (uint32_t j = 0; j < me->vertices; j++) {
		double a[3] = { me->pos[j][0], me->pos[j][1], me->pos[j][2] };
		double b[3] = { s->positions[j][0], s->positions[j][1],
				s->positions[j][2] };

		m->placed_error_m = fmax(m->placed_error_m, vec3_dist(a, b));
	}
}

/* The last sample whose ring is MODEL_OPEN of the widest near the end. */
static size_t last_open(const struct mesh *me, double step_m)
{
	size_t n = me->samples, near = (size_t)(MODEL_END_M / step_m);
	size_t i = n - 1;
	float widest = 0;

	for (size_t k = n > near ? n - near : 0; k < n; k++) {
		widest = fmaxf(widest, me->sample_rho[k]);
	}
	while (i > 0 && me->sample_rho[i] < MODEL_OPEN * widest) {
		i--;
	}
	return i;
}

static int make_mesh(struct model *m, const struct client_scene *s,
		     char *err, size_t errsize)
{
	const Endosim__SceneInfo *in = s->info;
	int r = fill_mesh(m, s, err, errsize);

	if (r) {
		return r;
	}
	r = mesh_finish(m->mesh, m->cl, in->segment_m, MESH_FROM_OFFSETS, err,
			errsize);
	if (!r) {
		r = check_segments(m, in, err, errsize);
	}
	if (r) {
		return r;
	}
	place_as_daemon(m, s, in);
	if (m->placed_error_m > PLACE_TOLERANCE_M) {
		snprintf(err, errsize, "scene: the mesh placed here lies "
			 "%.3g m from the daemon's", m->placed_error_m);
		return -EPROTO;
	}
	m->ring = ring_size(m->mesh);
	m->last_open = last_open(m->mesh, centreline_step(m->cl));
	return 0;
}

static int shape_of(const char *name)
{
	if (!strcmp(name, "pedunculated")) {
		return MODEL_POLYP_PEDUNCULATED;
	}
	return strcmp(name, "flat") ? MODEL_POLYP_SESSILE : MODEL_POLYP_FLAT;
}

/* The assistant's sites; one whose vectors do not add up is named with
 * none (the hand is still shown by its name). */
static void copy_sites(struct model *m, const Endosim__SceneInfo *in)
{
	m->sites = (int)(in->n_sites < MODEL_MAX_SITES ? in->n_sites :
							  MODEL_MAX_SITES);
	for (int i = 0; i < m->sites; i++) {
		const Endosim__SceneSite *x = in->sites[i];
		struct model_site *o = &m->site[i];

		memset(o, 0, sizeof(*o));
		snprintf(o->name, sizeof(o->name), "%s", x->name);
		if (x->n_position_m != 3 || x->n_direction != 3) {
			continue;
		}
		for (int k = 0; k < 3; k++) {
			o->position_m[k] = x->position_m[k];
			o->direction[k] = x->direction[k];
		}
		o->radius_m = x->radius_m;
	}
}

static void copy_anatomy(struct model *m, const Endosim__SceneInfo *in)
{
	snprintf(m->name, sizeof(m->name), "%s", in->name);
	m->regions = (int)(in->n_regions < MODEL_MAX_REGIONS ?
				   in->n_regions : MODEL_MAX_REGIONS);
	for (int i = 0; i < m->regions; i++) {
		const Endosim__SceneRegion *r = in->regions[i];
		struct model_region *x = &m->region[i];

		snprintf(x->name, sizeof(x->name), "%s", r->name);
		x->s0_m = r->s0_m;
		x->s1_m = r->s1_m;
		x->span = r->span;
		x->max_bow_m = r->max_bow_m;
	}
	m->polyps = (int)(in->n_polyps < MODEL_MAX_POLYPS ? in->n_polyps :
							     MODEL_MAX_POLYPS);
	for (int i = 0; i < m->polyps; i++) {
		const Endosim__ScenePolyp *p = in->polyps[i];

		m->polyp[i] = (struct model_polyp){
			.s_m = p->s_m, .angle_rad = p->angle_rad,
			.diameter_m = p->diameter_m, .shape = shape_of(p->shape)
		};
	}
	copy_sites(m, in);
}

/* The scope the scene is rendered with; the shipped one when it does not
 * say (an older daemon). */
static int copy_scope(struct model *m, const Endosim__SceneScope *sc,
		      char *err, size_t errsize)
{
	const struct scope_params shipped = SCOPE_PARAMS_DEFAULT;

	m->scope = shipped;
	m->scope_radius_m = SCOPE_RADIUS_M;
	if (!sc) {
		return 0;
	}
	if (!(sc->bending_length_m > 0) || !isfinite(sc->bending_length_m) ||
	    !isfinite(sc->ud_gain) || !isfinite(sc->lr_gain) ||
	    !(sc->ud_limit_rad >= 0 && sc->ud_limit_rad <= M_PI) ||
	    !(sc->lr_limit_rad >= 0 && sc->lr_limit_rad <= M_PI) ||
	    !(sc->radius_m >= 0) || !isfinite(sc->radius_m)) {
		snprintf(err, errsize, "scene: its scope does not add up");
		return -EPROTO;
	}
	m->scope = (struct scope_params){
		.bending_length_m = sc->bending_length_m,
		.ud_gain = sc->ud_gain, .lr_gain = sc->lr_gain,
		.ud_limit_rad = sc->ud_limit_rad,
		.lr_limit_rad = sc->lr_limit_rad,
	};
	m->scope_radius_m = sc->radius_m;
	return 0;
}

struct model *model_create(const struct client_scene *s, char *err,
			   size_t errsize)
{
	struct model *m = calloc(1, sizeof(*m));

	if (!m) {
		snprintf(err, errsize, "scene: out of memory");
		return NULL;
	}
	m->scene_id = s->scene_id;
	copy_anatomy(m, s->info);
	if (copy_scope(m, s->scope, err, errsize) ||
	    make_centreline(m, s->info, err, errsize) ||
	    make_mesh(m, s, err, errsize)) {
		model_destroy(m);
		return NULL;
	}
	return m;
}

void model_destroy(struct model *m)
{
	if (!m) {
		return;
	}
	mesh_destroy(m->mesh);
	centreline_destroy(m->cl);
	free(m);
}

void model_keep(struct model *m, const uint8_t *keep)
{
	m->keep = keep;
}

/* Vertex J as placed now, kept or not. */
static void vertex_at(const struct model *m, uint32_t j, double p[3])
{
	float f[3];

	if (m->keep && !m->keep[j]) {
		mesh_vertex_at(m->mesh, m->cl, j, f);
	} else {
		memcpy(f, m->mesh->pos[j], sizeof(f));
	}
	for (int x = 0; x < 3; x++) {
		p[x] = f[x];
	}
}

/* Widens [*LO, *HI) to hold [A, B). */
static void widen(uint32_t *lo, uint32_t *hi, uint32_t a, uint32_t b)
{
	if (*lo >= *hi) {
		*lo = a;
		*hi = b;
		return;
	}
	*lo = a < *lo ? a : *lo;
	*hi = b > *hi ? b : *hi;
}

/* Places samples A..B as the centreline lies now, widening [*LO, *HI)
 * by the vertices that moved. */
static void place_run(struct model *m, size_t a, size_t b, uint32_t *lo,
		      uint32_t *hi)
{
	struct mesh *me = m->mesh;

	mesh_place_kept(me, m->cl, a, b, m->keep);
	a = a > me->reach ? a - me->reach : 0;
	b = b + me->reach + 1 < me->samples ? b + me->reach + 1 : me->samples;
	widen(lo, hi, me->sample_first[a], me->sample_first[b]);
}

/* Places the mesh of span K as its centreline lies now, widening
 * [*LO, *HI) by the vertices that moved. */
static void place_span(struct model *m, int k, uint32_t *lo, uint32_t *hi)
{
	double ds = centreline_step(m->cl), s0, s1;

	centreline_span_range(m->cl, k, &s0, &s1);
	place_run(m, (size_t)lround(s0 / ds), (size_t)lround(s1 / ds), lo, hi);
}

void model_bow(struct model *m, const double *bow_m, int spans,
	       uint32_t *first, uint32_t *count)
{
	uint32_t lo = 0, hi = 0;

	for (int k = 0; k < spans && k < centreline_spans(m->cl); k++) {
		if (!isfinite(bow_m[k]) ||
		    (!m->node_count[k] &&
		     fabs(bow_m[k] - centreline_bow_amplitude(m->cl, k)) <
			     MODEL_BOW_STEP_M)) {
			continue;
		}
		centreline_bow(m->cl, k, bow_m[k]);
		m->node_count[k] = 0;
		place_span(m, k, &lo, &hi);
	}
	*first = lo;
	*count = hi - lo;
}

/* Span K's N nodes, published from AT, differ from those placed. */
static bool nodes_moved(const struct model *m, int k, int at,
			const double (*node)[3], int n)
{
	if (m->node_count[k] != n || m->node_first[k] != at) {
		return true;
	}
	for (int j = 0; j < n; j++) {
		if (vec3_dist(node[j], m->node[at + j]) >= MODEL_BOW_STEP_M) {
			return true;
		}
	}
	return false;
}

void model_displace(struct model *m, const struct endosim_rod_state *rod,
		    uint32_t *first, uint32_t *count)
{
	double node[ENDOSIM_COLON_NODES][3];
	uint32_t lo = 0, hi = 0, at = 0;
	uint32_t all = rod->nodes < ENDOSIM_COLON_NODES ? rod->nodes :
							  ENDOSIM_COLON_NODES;

	for (int k = 0; k < ENDOSIM_SPANS && k < centreline_spans(m->cl);
	     k++) {
		uint32_t n = rod->span_nodes[k];

		if (n > all - at) {
			break;
		}
		for (uint32_t j = 0; j < n; j++) {
			for (int d = 0; d < 3; d++) {
				node[j][d] = rod->node[at + j][d];
			}
		}
		if (n && nodes_moved(m, k, (int)at, (const double(*)[3])node,
				     (int)n) &&
		    !centreline_displace(m->cl, k, (const double(*)[3])node,
					 (int)n)) {
			memcpy(m->node[at], node, n * sizeof(node[0]));
			m->node_first[k] = (int)at;
			m->node_count[k] = (int)n;
			place_span(m, k, &lo, &hi);
		}
		at += n;
	}
	*first = lo;
	*count = hi - lo;
}

/* FACTOR's lumen factor at S_M, from region *R on (moved on to the
 * region holding S_M). */
static double factor_at(const struct model *m, const double *factor,
			int *r, double s_m)
{
	const struct model_region *rg;

	while (*r + 1 < m->regions && s_m >= m->region[*r].s1_m) {
		(*r)++;
	}
	rg = &m->region[*r];
	return gas_factor_in(factor, *r, rg->s0_m, rg->s1_m, s_m);
}

void model_scale(struct model *m, const double *factor, uint32_t *first,
		 uint32_t *count)
{
	struct mesh *me = m->mesh;
	double ds = centreline_step(m->cl), sane[GAS_SEGMENTS];
	uint32_t lo = 0, hi = 0;
	size_t run = SIZE_MAX; /* the first sample of a run to place */
	int r = 0;

	for (int k = 0; k < GAS_SEGMENTS; k++) {
		double f = factor ? factor[k] : 1;

		sane[k] = isfinite(f) && f > 0 ? f : 1;
	}
	for (size_t i = 0; m->regions == GAS_SEGMENTS && i < me->samples;
	     i++) {
		double f = factor_at(m, sane, &r, (double)i * ds);

		if (fabs(f - me->radial[i]) >= MODEL_SCALE_STEP *
						    me->radial[i] ||
		    (f == 1 && me->radial[i] != 1)) {
			me->radial[i] = (float)f;
			run = run == SIZE_MAX ? i : run;
		} else if (run != SIZE_MAX) {
			place_run(m, run, i - 1, &lo, &hi);
			run = SIZE_MAX;
		}
	}
	if (run != SIZE_MAX) {
		place_run(m, run, me->samples - 1, &lo, &hi);
	}
	*first = lo;
	*count = hi - lo;
}

double model_moved(const struct model *m, int span, size_t *at)
{
	double ds = centreline_step(m->cl), s0, s1, most = 0;
	size_t a, b;

	centreline_span_range(m->cl, span, &s0, &s1);
	a = (size_t)lround(s0 / ds);
	b = (size_t)lround(s1 / ds);
	if (at) {
		*at = a;
	}
	for (size_t i = a; i <= b; i++) {
		double d = vec3_dist(centreline_sample(m->cl, i)->p,
				     centreline_base(m->cl, i)->p);

		if (d > most) {
			most = d;
			if (at) {
				*at = i;
			}
		}
	}
	return most;
}

bool model_outside(const struct model *m, const float p[3])
{
	const struct centreline_point *c = centreline_base(m->cl, 0);
	double x[3] = { p[0] - c->p[0], p[1] - c->p[1], p[2] - c->p[2] };

	return vec3_dot(x, c->t) < 0;
}

const struct model_region *model_region_at(const struct model *m,
					   double s_m)
{
	int i = 0;

	while (i + 1 < m->regions && m->region[i + 1].s0_m <= s_m) {
		i++;
	}
	return &m->region[i];
}

size_t model_sample_at(const struct model *m, double s_m)
{
	double i = round(s_m / centreline_step(m->cl));
	size_t n = centreline_count(m->cl);

	if (!(i > 0)) {
		return 0;
	}
	return i >= (double)n ? n - 1 : (size_t)i;
}

/* Sample I's vertex farthest towards the unit direction D (the plane's):
 * for a generated tube the one at D's angle around the frame. */
static uint32_t ring_vertex(const struct model *m, size_t i, const double d[3])
{
	const struct mesh *me = m->mesh;
	const struct centreline_point *c = centreline_sample(m->cl, i);
	uint32_t best = me->sample_first[i];
	double best_dot = -INFINITY;

	if (m->ring) {
		double k = atan2(vec3_dot(d, c->v), vec3_dot(d, c->u)) /
			   (2 * M_PI);
		long j = lround((k < 0 ? k + 1 : k) * m->ring);

		return best + (uint32_t)(j % (long)m->ring);
	}
	for (uint32_t j = me->sample_first[i]; j < me->sample_first[i + 1];
	     j++) {
		double x[3], dot;

		vertex_at(m, j, x);
		vec3_sub(x, x, c->p);
		dot = vec3_dot(x, d) / fmax(vec3_norm(x), 1e-9);

		if (dot > best_dot) {
			best_dot = dot;
			best = j;
		}
	}
	return best;
}

/* The unit direction at ANGLE around sample I's frame. */
static void around(const struct centreline_point *c, double angle,
		   double d[3])
{
	vec3_scale(d, c->u, cos(angle));
	vec3_axpy(d, d, sin(angle), c->v);
}

void model_wall(const struct model *m, size_t i, double angle_rad,
		double p[3], double n[3])
{
	const struct mesh *me = m->mesh;
	size_t last = me->samples - 1;
	const struct centreline_point *c;
	double d[3];
	uint32_t j;

	i = i < last ? i : last - 1; /* the pole has no ring */
	c = centreline_sample(m->cl, i);
	around(c, angle_rad, d);
	if (m->ring) {
		double k = fmod(angle_rad / (2 * M_PI), 1.0);

		j = me->sample_first[i] +
		    (uint32_t)lround((k < 0 ? k + 1 : k) * m->ring) % m->ring;
	} else {
		j = ring_vertex(m, i, d);
	}
	vertex_at(m, j, p);
	for (int x = 0; x < 3; x++) {
		n[x] = -d[x];
	}
}

/* Near sample I, the sample whose normal plane passes nearest P. */
static size_t plane_of(const struct model *m, size_t i, const double p[3])
{
	size_t n = centreline_count(m->cl), best = i;
	size_t lo = i > PLANE_SEARCH ? i - PLANE_SEARCH : 0;
	size_t hi = i + PLANE_SEARCH < n ? i + PLANE_SEARCH : n - 1;
	double best_gap = INFINITY;

	for (size_t j = lo; j <= hi; j++) {
		const struct centreline_point *c = centreline_sample(m->cl, j);
		double x[3], gap;

		vec3_sub(x, p, c->p);
		gap = fabs(vec3_dot(x, c->t)) + 0.1 * vec3_norm(x);
		if (gap < best_gap) {
			best_gap = gap;
			best = j;
		}
	}
	return best;
}

double model_wall_gap(const struct model *m, size_t *i, const double p[3],
		      double d[3])
{
	const struct centreline_point *c;
	double x[3], wall[3], rho;
	uint32_t j;

	*i = plane_of(m, *i, p);
	*i = *i + 1 < m->mesh->samples ? *i : *i - 1; /* the pole: no ring */
	c = centreline_sample(m->cl, *i);
	vec3_sub(x, p, c->p);
	vec3_axpy(d, x, -vec3_dot(x, c->t), c->t);
	rho = vec3_normalize(d);
	if (rho == 0) {
		vec3_copy(d, c->u);
	}
	j = ring_vertex(m, *i, d);
	vertex_at(m, j, wall);
	vec3_sub(wall, wall, c->p);
	return vec3_dot(wall, d) - rho;
}

/* Back onto the plane of sample last_open from beyond it. */
static double keep_open(const struct model *m, double p[3])
{
	const struct centreline_point *c = centreline_sample(m->cl,
							    m->last_open);
	double x[3], past;

	vec3_sub(x, p, c->p);
	past = vec3_dot(x, c->t);
	if (past <= 0) {
		return 0;
	}
	vec3_axpy(p, p, -past, c->t);
	return past;
}

double model_keep_inside(const struct model *m, size_t i, double p[3],
			 double margin_m)
{
	double d[3], moved = keep_open(m, p);
	double gap = model_wall_gap(m, &i, p, d) - margin_m;

	if (gap < 0) {
		vec3_axpy(p, p, gap, d);
		moved -= gap;
	}
	return moved;
}
