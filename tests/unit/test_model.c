/*
 * test_model.c - the viewer's colon (viewer/model.h): rebuilt from what
 * GetScene serves, it is the daemon's colon vertex for vertex, also bowed;
 * it names the region of any s; it keeps a camera inside the lumen, out of
 * the cecum's closed end too.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

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
	before = malloc(me->vertices * sizeof(*before));
	assert_non_null(before);
	memcpy(before, me->pos, me->vertices * sizeof(*before));
	assert_int_equal(colon_bow(f.colon, 0, bow[0], true), 0);
	assert_int_equal(colon_bow(f.colon, 1, bow[1], true), 0);
	model_bow(f.model, bow, 2, &first, &count);
	assert_true(count > 0);
	assert_true(fixture_placed_error(&f) < SAME_M);
	for (uint32_t j = 0; j < me->vertices; j++) {
		if (j < first || j >= first + count) {
			assert_memory_equal(before[j], me->pos[j],
					    sizeof(before[j]));
		}
	}
	bow[0] += MODEL_BOW_STEP_M / 2; /* too small a change to place */
	model_bow(f.model, bow, 2, &first, &count);
	assert_int_equal(count, 0);
	free(before);
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

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(same_as_daemon),
		cmocka_unit_test(bows_as_daemon),
		cmocka_unit_test(names_regions),
		cmocka_unit_test(keeps_inside),
		cmocka_unit_test(knows_a_tube),
		cmocka_unit_test(refuses_bad_scene),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
