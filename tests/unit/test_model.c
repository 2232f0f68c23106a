/*
 * test_model.c - the viewer's colon (viewer/model.h): rebuilt from what
 * GetScene serves, it is the daemon's colon vertex for vertex, also bowed
 * or moved by the rod model's nodes, and its lumen widened or narrowed by
 * the gas as the haptics scale theirs; it names the region of any s; it
 * keeps a camera inside the lumen, out of the cecum's closed end too; its
 * scope is the scene's.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "base/vec3.h"
#include "model/gas.h"
#include "viewer/lod.h"
#include "viewer_fixture.h"

#define SAME_M 1e-6

static void same_as_daemon(void **state)
{
	struct fixture f;
	const struct mesh *a, *b;

	(void)state;
	fixture_setup(&f, "config/cases", "polyps", 0.002, 192);
	a = f.model->mesh;
	b = colon_mesh(f.colon);
	assert_int_equal(a->vertices, b->vertices);
	assert_int_equal(a->triangles, b->triangles);
	assert_memory_equal(a->tri, b->tri, b->triangles * sizeof(*b->tri));
	assert_true(fixture_placed_error(&f) < SAME_M);
	assert_true(f.model->placed_error_m < SAME_M);
	assert_int_equal(f.model->ring, 192);
	assert_int_equal(f.model->scene_id, 42);
	assert_string_equal(f.model->name, "polyps");
	assert_int_equal(f.model->regions, 9);
	assert_int_equal(f.model->polyps, 5);
	assert_int_equal(f.model->polyp[1].shape, MODEL_POLYP_SESSILE);
	fixture_teardown(&f);
}

/* The vertices outside [FIRST, FIRST + COUNT) are those of BEFORE. */
static void only_range_moved(const struct mesh *me, const float (*before)[3],
			     uint32_t first, uint32_t count)
{
	for (uint32_t j = 0; j < me->vertices; j++) {
		if (j < first || j >= first + count) {
			assert_memory_equal(before[j], me->pos[j],
					    sizeof(before[j]));
		}
	}
}

/* A copy of ME's vertices as placed now (the caller frees it). */
static float (*positions(const struct mesh *me))[3]
{
	float (*pos)[3] = malloc(me->vertices * sizeof(*pos));

	assert_non_null(pos);
	memcpy(pos, me->pos, me->vertices * sizeof(*pos));
	return pos;
}

/* Bowed as the daemon bows: the same vertices, and every vertex that
 * moved lies in the range model_bow() reports. */
static void bows_as_daemon(void **state)
{
	struct fixture f;
	const struct mesh *me;
	float (*before)[3];
	double bow[2] = { 0.04, -0.03 };
	uint32_t first, count;

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.002, 192);
	me = f.model->mesh;
	before = positions(me);
	assert_int_equal(colon_bow(f.colon, 0, bow[0], true), 0);
	assert_int_equal(colon_bow(f.colon, 1, bow[1], true), 0);
	model_bow(f.model, bow, 2, &first, &count);
	assert_true(count > 0);
	assert_true(fixture_placed_error(&f) < SAME_M);
	only_range_moved(me, (const float(*)[3])before, first, count);
	bow[0] += MODEL_BOW_STEP_M / 2; /* too small a change to place */
	model_bow(f.model, bow, 2, &first, &count);
	assert_int_equal(count, 0);
	free(before);
	fixture_teardown(&f);
}

/*
 * Every vertex of ME lies where the daemon's (D, unscaled) lies with its
 * offset across the centreline scaled by gas_factor_at() on the daemon's
 * colon C (FACTOR; NULL: 1), the surface the haptics map the tip onto,
 * to within 10 um and the share REL of its offset.
 */
static void scaled_as_haptics(const struct mesh *me, const struct mesh *d,
			      const struct colon *c, const double *factor,
			      double rel)
{
	const struct centreline *cl = colon_centreline(c);
	double ds = centreline_step(cl), worst = 0;

	for (uint32_t j = 0; j < me->vertices; j++) {
		const struct centreline_point *p =
			centreline_sample(cl, me->sample[j]);
		double f = factor ? gas_factor_at(c, factor,
						  me->sample[j] * ds) : 1;
		double a[3], b[3], e;

		for (int k = 0; k < 3; k++) {
			a[k] = me->pos[j][k] - p->p[k];
			b[k] = d->pos[j][k] - p->p[k];
		}
		e = fabs(vec3_dot(a, p->t) - vec3_dot(b, p->t)) +
		    fabs(vec3_dot(a, p->u) - f * vec3_dot(b, p->u)) +
		    fabs(vec3_dot(a, p->v) - f * vec3_dot(b, p->v));
		e /= 1e-5 + rel * vec3_norm(a);
		worst = e > worst ? e : worst;
	}
	assert_true(worst < 1);
}

/* The gas's factors scale the lumen radially as the haptics scale it;
 * only what changed by MODEL_SCALE_STEP or more is placed again; a
 * factor that is not finite counts as 1; without factors the mesh is
 * the daemon's again. */
static void scales_as_the_gas(void **state)
{
	double factor[GAS_SEGMENTS] = { 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.1,
					1.2, 1.25 };
	double placed[GAS_SEGMENTS];
	struct fixture f;
	const struct mesh *me, *d;
	float (*before)[3];
	uint32_t first, count;

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.004, 32);
	me = f.model->mesh;
	d = colon_mesh(f.colon);
	before = positions(me);
	model_scale(f.model, factor, &first, &count);
	assert_true(count > 0.9 * me->vertices);
	only_range_moved(me, (const float(*)[3])before, first, count);
	scaled_as_haptics(me, d, f.colon, factor, 0);
	memcpy(placed, factor, sizeof(placed));
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		factor[i] *= 1 + MODEL_SCALE_STEP / 2; /* too small to place */
	}
	model_scale(f.model, factor, &first, &count);
	assert_int_equal(count, 0);
	factor[4] = NAN; /* the splenic flexure: as the case draws it */
	model_scale(f.model, factor, &first, &count);
	assert_true(count > 0 && count < me->vertices / 4);
	placed[4] = 1; /* its neighbours' blends to within the step */
	scaled_as_haptics(me, d, f.colon, placed, 2 * MODEL_SCALE_STEP);
	model_scale(f.model, NULL, &first, &count);
	assert_true(count > 0.9 * me->vertices);
	assert_true(fixture_placed_error(&f) == 0);
	free(before);
	fixture_teardown(&f);
}

/* The daemon's colon moved by span K's N nodes from NODE, its mesh placed
 * there. */
static void daemon_displace(struct colon *c, int k, const float (*node)[3],
			    int n)
{
	struct centreline *cl = colon_centreline(c);
	double y[ENDOSIM_COLON_NODES][3], s0, s1, ds = centreline_step(cl);

	for (int j = 0; j < n; j++) {
		for (int d = 0; d < 3; d++) {
			y[j][d] = node[j][d];
		}
	}
	assert_int_equal(centreline_displace(cl, k, (const double(*)[3])y, n),
			 0);
	centreline_span_range(cl, k, &s0, &s1);
	mesh_place(colon_mesh(c), cl, (size_t)lround(s0 / ds),
		   (size_t)lround(s1 / ds));
}

/* The rod model's nodes (floats a double holds exactly): three in the
 * sigmoid, the largest 6.25 cm from rest, two in the transverse. */
static void rod_nodes(struct endosim_rod_state *rod)
{
	static const float node[5][3] = {
		{ 0.015625f, 0, 0.0078125f }, { 0.0625f, 0, 0 },
		{ 0.0234375f, -0.0078125f, 0 },
		{ 0, 0.015625f, -0.03125f }, { 0, 0.0078125f, -0.015625f },
	};

	memset(rod, 0, sizeof(*rod));
	rod->model = ENDOSIM_MODEL_ROD;
	rod->nodes = 5;
	rod->span_nodes[0] = 3;
	rod->span_nodes[1] = 2;
	memcpy(rod->node, node, sizeof(node));
}

/* Moved by the nodes as the daemon's colon follows them: the same
 * vertices, only those in the range reported moved, the span's largest
 * displacement at least its largest node's; a node moved by less than
 * MODEL_BOW_STEP_M is not placed, one moved by more places its span
 * alone; nodes that do not add up move nothing; a bow of 0 afterwards
 * lays the span at rest again. */
static void moves_as_daemon(void **state)
{
	struct fixture f;
	struct endosim_rod_state rod;
	const struct mesh *me;
	float (*before)[3];
	uint32_t first, count, second;
	double bow[2] = { 0, 0 };
	size_t at;

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.002, 192);
	me = f.model->mesh;
	before = positions(me);
	rod_nodes(&rod);
	daemon_displace(f.colon, 0, (const float(*)[3])rod.node, 3);
	daemon_displace(f.colon, 1, (const float(*)[3])rod.node[3], 2);
	model_displace(f.model, &rod, &first, &count);
	assert_true(count > 0);
	assert_true(fixture_placed_error(&f) < SAME_M);
	only_range_moved(me, (const float(*)[3])before, first, count);
	assert_true(model_moved(f.model, 0, &at) >= 0.0625 - 1e-9);
	assert_true(model_moved(f.model, 0, NULL) < 0.07);
	assert_string_equal(model_region_at(f.model, at * 0.002)->name,
			    "sigmoid");
	assert_true(model_moved(f.model, 1, NULL) >= 0.034);

	rod.node[1][0] += (float)(MODEL_BOW_STEP_M / 2); /* too small */
	model_displace(f.model, &rod, &first, &count);
	assert_int_equal(count, 0);
	memcpy(before, me->pos, me->vertices * sizeof(*before));
	rod.node[4][2] += (float)(MODEL_BOW_STEP_M * 2); /* the transverse */
	daemon_displace(f.colon, 1, (const float(*)[3])rod.node[3], 2);
	model_displace(f.model, &rod, &second, &count);
	assert_true(count > 0 && second > first);
	only_range_moved(me, (const float(*)[3])before, second, count);
	assert_true(fixture_placed_error(&f) < SAME_M);

	rod.node[0][0] = NAN; /* with another node well moved */
	rod.node[2][0] += 0.01f;
	rod.node[3][0] += 0.01f;
	rod.span_nodes[1] = 3; /* more nodes than published */
	model_displace(f.model, &rod, &first, &count);
	assert_int_equal(count, 0);

	model_bow(f.model, bow, 2, &first, &count);
	assert_true(count > 0);
	assert_true(model_moved(f.model, 0, NULL) == 0);
	assert_true(model_moved(f.model, 1, NULL) == 0);
	free(before);
	fixture_teardown(&f);
}

/* Whether a sample's rings are held between their neighbours' planes
 * somewhere (the fold limits a kept-or-not vertex is placed with). */
static bool folds_held(const struct mesh *me)
{
	for (size_t i = 0; i < me->samples; i++) {
		if (me->near_lo[i] <= me->near_hi[i]) {
			return true;
		}
	}
	return false;
}

/* Segment K's box over every vertex as ME places them, vertex by vertex. */
static void box_of(const struct mesh *me, uint32_t k, float lo[3],
		   float hi[3])
{
	size_t a = (size_t)lround(me->seg[k].s0_m / me->step_m);
	size_t b = (size_t)lround(me->seg[k].s1_m / me->step_m) + me->tri_span;

	b = b < me->samples ? b : me->samples - 1;
	for (int d = 0; d < 3; d++) {
		lo[d] = INFINITY;
		hi[d] = -INFINITY;
	}
	for (uint32_t j = me->sample_first[a]; j < me->sample_first[b + 1];
	     j++) {
		for (int d = 0; d < 3; d++) {
			float x = me->pos[j][d];

			lo[d] = x < lo[d] ? x : lo[d];
			hi[d] = x > hi[d] ? x : hi[d];
		}
	}
}

/* Segment K's largest ring offset as ME scales it, m. */
static double widest_ring(const struct mesh *me, uint32_t k)
{
	size_t a = (size_t)lround(me->seg[k].s0_m / me->step_m);
	size_t b = (size_t)lround(me->seg[k].s1_m / me->step_m) + me->tri_span;
	double r = 0;

	b = b < me->samples ? b : me->samples - 1;
	for (size_t i = a; i <= b; i++) {
		r = fmax(r, (double)me->radial[i] * me->sample_rho[i]);
	}
	return r;
}

/* Keeping only the vertices the levels draw (model_keep()): moved as the
 * daemon moves, those are the daemon's to the bit, and so is every other
 * vertex where model_wall() and model_wall_gap() read it; the others are
 * not stored. Every segment's box holds all of the daemon's vertices
 * (the daemon's own box is theirs to the bit) and is larger by less than
 * its widest ring. */
static void keeps_what_is_drawn(void **state)
{
	struct fixture f, all;
	struct endosim_rod_state rod;
	const struct mesh *me, *dm;
	struct lod *l;
	uint32_t first, count, stale = 0;

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.002, 192);
	fixture_setup(&all, "config/cases", "normal", 0.002, 192);
	me = f.model->mesh;
	dm = colon_mesh(f.colon);
	l = lod_create(me, f.model->ring);
	assert_non_null(l);
	model_keep(f.model, l->drawn);
	rod_nodes(&rod);
	daemon_displace(f.colon, 0, (const float(*)[3])rod.node, 3);
	daemon_displace(f.colon, 1, (const float(*)[3])rod.node[3], 2);
	model_displace(f.model, &rod, &first, &count);
	model_displace(all.model, &rod, &first, &count);
	assert_true(folds_held(me));
	for (uint32_t j = 0; j < me->vertices; j++) {
		float p[3];

		mesh_vertex_at(me, f.model->cl, j, p);
		assert_memory_equal(p, dm->pos[j], sizeof(p));
		if (l->drawn[j]) {
			assert_memory_equal(me->pos[j], dm->pos[j], sizeof(p));
			assert_memory_equal(me->nrm[j], dm->nrm[j], sizeof(p));
		}
		stale += memcmp(me->pos[j], dm->pos[j], sizeof(p)) != 0;
	}
	print_message("%u of %u vertices not placed\n", stale, me->vertices);
	assert_true(stale > count / 2);
	for (uint32_t k = 0; k < me->segments; k++) {
		double slack = widest_ring(me, k);
		float lo[3], hi[3];

		box_of(dm, k, lo, hi);
		assert_memory_equal(dm->seg[k].min, lo, sizeof(lo));
		assert_memory_equal(dm->seg[k].max, hi, sizeof(hi));
		for (int d = 0; d < 3; d++) {
			assert_true(me->seg[k].min[d] <= lo[d]);
			assert_true(me->seg[k].max[d] >= hi[d]);
			assert_true(lo[d] - me->seg[k].min[d] < slack);
			assert_true(me->seg[k].max[d] - hi[d] < slack);
		}
	}
	for (size_t i = 0; i < me->samples; i += 7) {
		double p[3], n[3], q[3], m[3], x[3], d[3], e[3];
		size_t a = i, b = i;

		model_wall(f.model, i, 0.1 * (double)i, p, n);
		model_wall(all.model, i, 0.1 * (double)i, q, m);
		assert_memory_equal(p, q, sizeof(p));
		vec3_lerp(x, centreline_sample(f.model->cl, i)->p, p, 0.7);
		x[0] += 0.001;
		assert_true(model_wall_gap(f.model, &a, x, d) ==
			    model_wall_gap(all.model, &b, x, e));
		assert_int_equal(a, b);
	}
	lod_destroy(l);
	fixture_teardown(&all);
	fixture_teardown(&f);
}

/* The rig's pipe behind the anal verge is outside; the rectum inside. */
static void knows_outside(void **state)
{
	struct fixture f;
	const struct centreline_point *c;
	float p[3];

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.004, 32);
	c = centreline_base(f.model->cl, 0);
	for (int sign = -1; sign <= 1; sign += 2) {
		for (int d = 0; d < 3; d++) {
			p[d] = (float)(c->p[d] + sign * 0.01 * c->t[d]);
		}
		assert_true(model_outside(f.model, p) == (sign < 0));
	}
	fixture_teardown(&f);
}

static void names_regions(void **state)
{
	struct fixture f;

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.004, 32);
	assert_string_equal(model_region_at(f.model, -1)->name, "anal_canal");
	assert_string_equal(model_region_at(f.model, 0.30)->name, "sigmoid");
	assert_int_equal(model_region_at(f.model, 0.30)->span, 0);
	assert_string_equal(model_region_at(f.model, 0.90)->name,
			    "transverse");
	assert_string_equal(model_region_at(f.model, 99)->name, "cecum");
	assert_int_equal(model_sample_at(f.model, 0.30),
			 lround(0.30 / centreline_step(f.model->cl)));
	assert_int_equal(model_sample_at(f.model, 99),
			 centreline_count(f.model->cl) - 1);
	fixture_teardown(&f);
}

/* In the straight case the lumen is a tube along z: the wall's distance
 * from the centreline is the lumen radius there. */
static void keeps_inside(void **state)
{
	struct fixture f;
	size_t i;
	double p[3], d[3], c[3], r, gap, moved;

	(void)state;
	fixture_setup(&f, "tests/cases", "straight", 0.002, 192);
	i = model_sample_at(f.model, 0.70);
	memcpy(c, centreline_sample(f.model->cl, i)->p, sizeof(c));
	r = colon_lumen_radius(f.colon, 0.70, 0);
	memcpy(p, c, sizeof(p));
	gap = model_wall_gap(f.model, &i, p, d);
	assert_true(fabs(gap - r) < 0.001);
	assert_true(model_keep_inside(f.model, i, p, 0.003) == 0);
	p[0] += 0.1; /* 10 cm off the centreline: through the wall */
	p[1] += 0.1;
	gap = model_wall_gap(f.model, &i, p, d);
	assert_true(gap < -0.1);
	moved = model_keep_inside(f.model, i, p, 0.003);
	assert_true(fabs(moved + gap - 0.003) < 1e-9);
	gap = model_wall_gap(f.model, &i, p, d);
	assert_true(fabs(gap - 0.003) < 0.0005);
	/* at the cecum's pole: back to where the lumen is open */
	i = centreline_count(f.model->cl) - 1;
	memcpy(p, centreline_sample(f.model->cl, i)->p, sizeof(p));
	assert_true(model_keep_inside(f.model, i, p, 0.003) > 0);
	i = f.model->last_open;
	assert_true(i + 5 < centreline_count(f.model->cl));
	assert_true(p[2] <= centreline_sample(f.model->cl, i)->p[2] + 1e-9);
	fixture_teardown(&f);
}

/* Levels of detail need a tube laid out as colon_create() lays it: one
 * quad's diagonal the other way makes it any mesh. */
static void knows_a_tube(void **state)
{
	struct fixture f;
	uint32_t (*tri)[3];
	struct model *m;
	char err[256];

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.004, 24);
	assert_int_equal(f.model->ring, 24);
	tri = malloc(f.cs.triangles * sizeof(*tri));
	assert_non_null(tri);
	memcpy(tri, f.cs.indices, f.cs.triangles * sizeof(*tri));
	/* (a, b, c), (b, d, c) become (a, b, d), (a, d, c) */
	tri[0][2] = tri[1][1];
	tri[1][0] = tri[0][0];
	f.cs.indices = tri;
	m = model_create(&f.cs, err, sizeof(err));
	assert_non_null(m);
	assert_int_equal(m->ring, 0);
	model_destroy(m);
	free(tri);
	fixture_teardown(&f);
}

/* A scene that does not add up is refused, with a reason. */
static void refuses_bad_scene(void **state)
{
	struct fixture f;
	Endosim__SceneInfo info;
	char err[256] = "";

	(void)state;
	f.colon = fixture_colon("config/cases", "normal", 0.004, 32);
	fixture_scene(&f, 1);
	info = *f.cs.info;
	info.n_segments--;
	f.cs.info = &info;
	assert_null(model_create(&f.cs, err, sizeof(err)));
	assert_non_null(strstr(err, "segments"));
	f.model = NULL;
	fixture_teardown(&f);
}

/* The scope is the scene's; the shipped one when the scene has none; a
 * scene whose scope does not add up is refused. */
static void takes_the_scenes_scope(void **state)
{
	const struct scope_params shipped = SCOPE_PARAMS_DEFAULT;
	const struct scope_params p = {
		.bending_length_m = 0.1, .ud_gain = 2, .lr_gain = 1.5,
		.ud_limit_rad = 3, .lr_limit_rad = 2.5,
	};
	const struct scope_params bad = { .bending_length_m = 0 };
	struct fixture f;
	struct model *m;
	char err[256];

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.004, 32);
	assert_null(f.cs.scope);
	assert_true(f.model->scope.ud_limit_rad == shipped.ud_limit_rad);
	assert_true(f.model->scope.bending_length_m ==
		    shipped.bending_length_m);
	assert_true(f.model->scope_radius_m == SCOPE_RADIUS_M);
	scene_set_scope(f.scene, &p, 0.007);
	scene_client(f.scene, &f.cs);
	m = model_create(&f.cs, err, sizeof(err));
	assert_non_null(m);
	assert_true(m->scope.bending_length_m == 0.1);
	assert_true(m->scope.ud_gain == 2);
	assert_true(m->scope.lr_gain == 1.5);
	assert_true(m->scope.ud_limit_rad == 3);
	assert_true(m->scope.lr_limit_rad == 2.5);
	assert_true(m->scope_radius_m == 0.007);
	model_destroy(m);
	scene_set_scope(f.scene, &bad, 0.007);
	assert_null(model_create(&f.cs, err, sizeof(err)));
	assert_non_null(strstr(err, "scope"));
	fixture_teardown(&f);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(same_as_daemon),
		cmocka_unit_test(bows_as_daemon),
		cmocka_unit_test(moves_as_daemon),
		cmocka_unit_test(scales_as_the_gas),
		cmocka_unit_test(keeps_what_is_drawn),
		cmocka_unit_test(knows_outside),
		cmocka_unit_test(names_regions),
		cmocka_unit_test(keeps_inside),
		cmocka_unit_test(knows_a_tube),
		cmocka_unit_test(refuses_bad_scene),
		cmocka_unit_test(takes_the_scenes_scope),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
