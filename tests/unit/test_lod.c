/*
 * test_lod.c - the levels of detail (viewer/lod.h): at full detail they
 * are the mesh's own triangles; every level's triangles face the lumen and
 * address real vertices; what a segment costs at a level does not depend
 * on the mesh's resolution (the default ~290 000 triangles or 2 million).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "viewer/lod.h"
#include "base/vec3.h"
#include "viewer_fixture.h"

/* The model's vertex behind index V of a tube's levels (gpumesh.h). */
static uint32_t vertex_of(uint32_t ring, uint32_t v)
{
	uint32_t i = v / (ring + 1), j = v % (ring + 1);

	return i * ring + (j == ring ? 0 : j);
}

static int by_triangle(const void *a, const void *b)
{
	return memcmp(a, b, 3 * sizeof(uint32_t));
}

/* Rotated to start at its smallest vertex, winding kept. */
static void canonical(uint32_t t[3])
{
	while (t[0] > t[1] || t[0] > t[2]) {
		uint32_t x = t[0];

		t[0] = t[1];
		t[1] = t[2];
		t[2] = x;
	}
}

/* A tube of 32 vertices a ring, 2 mm apart: level 0 is the mesh itself. */
static void full_detail_is_the_mesh(void **state)
{
	struct fixture f;
	const struct mesh *me;
	struct lod *l;
	uint32_t (*a)[3], (*b)[3];

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.002, 32);
	me = f.model->mesh;
	l = lod_create(me, f.model->ring);
	assert_non_null(l);
	assert_int_equal(l->ring_stride[0], 1);
	assert_int_equal(l->vertex_stride[0], 1);
	assert_int_equal(lod_span(l, 0, 0, me->segments - 1).count,
			 3 * me->triangles);
	a = malloc(me->triangles * sizeof(*a));
	b = malloc(me->triangles * sizeof(*b));
	assert_non_null(a);
	assert_non_null(b);
	for (uint32_t k = 0; k < me->triangles; k++) {
		for (int c = 0; c < 3; c++) {
			a[k][c] = vertex_of(32, l->index[3 * k + c]);
			b[k][c] = me->tri[k][c];
		}
		canonical(a[k]);
		canonical(b[k]);
	}
	qsort(a, me->triangles, sizeof(*a), by_triangle);
	qsort(b, me->triangles, sizeof(*b), by_triangle);
	assert_memory_equal(a, b, me->triangles * sizeof(*a));
	free(a);
	free(b);
	lod_destroy(l);
	fixture_teardown(&f);
}

/* Each triangle of each level faces the centreline of its first vertex. */
static void levels_face_the_lumen(void **state)
{
	struct fixture f;
	const struct mesh *me;
	struct lod *l;

	(void)state;
	fixture_setup(&f, "config/cases", "normal", 0.002, 192);
	me = f.model->mesh;
	l = lod_create(me, f.model->ring);
	assert_non_null(l);
	assert_int_equal(l->levels, LOD_LEVELS);
	for (int lv = 0; lv < l->levels; lv++) {
		struct lod_range r = lod_span(l, lv, 0, me->segments - 1);

		assert_int_equal(r.count % 3, 0);
		for (uint32_t k = r.first; k < r.first + r.count; k += 3) {
			double p[3][3], ab[3], ac[3], n[3], in[3];

			for (int c = 0; c < 3; c++) {
				uint32_t v = vertex_of(192, l->index[k + c]);

				assert_true(v < me->vertices);
				for (int x = 0; x < 3; x++) {
					p[c][x] = me->pos[v][x];
				}
			}
			vec3_sub(ab, p[1], p[0]);
			vec3_sub(ac, p[2], p[0]);
			vec3_cross(n, ab, ac);
			vec3_sub(in, centreline_sample(f.model->cl,
				 me->sample[vertex_of(192, l->index[k])])->p,
				 p[0]);
			assert_true(vec3_dot(n, in) > 0);
		}
	}
	lod_destroy(l);
	fixture_teardown(&f);
}

/* Triangles of segment K at each level, for a colon at STEP_M and RING. */
static void segment_costs(double step_m, uint32_t ring, uint32_t k,
			  uint32_t tris[LOD_LEVELS])
{
	struct fixture f;
	struct lod *l;

	fixture_setup(&f, "config/cases", "normal", step_m, ring);
	l = lod_create(f.model->mesh, f.model->ring);
	assert_non_null(l);
	for (int lv = 0; lv < LOD_LEVELS; lv++) {
		tris[lv] = lod_segment(l, lv, k).count / 3;
	}
	lod_destroy(l);
	fixture_teardown(&f);
}

static void cost_independent_of_resolution(void **state)
{
	uint32_t fine[LOD_LEVELS], dflt[LOD_LEVELS];

	(void)state;
	segment_costs(0.002, 192, 10, dflt);
	segment_costs(0.001, 672, 10, fine);
	for (int lv = 0; lv < LOD_LEVELS; lv++) {
		print_message("level %d: %u and %u triangles a segment\n", lv,
			      dflt[lv], fine[lv]);
		assert_true(dflt[lv] > 0);
		assert_true(fabs((double)fine[lv] - dflt[lv]) <=
			    0.1 * dflt[lv]);
	}
	/* level 0: 4 cm of rings 2 mm apart, 32 vertices round */
	assert_int_equal(dflt[0], 20 * 32 * 2);
}

/* An imported mesh has one level: its own triangles, segment by segment. */
static void import_has_one_level(void **state)
{
	struct colon *c = fixture_colon("config/cases", "normal", 0.004, 24);
	struct mesh *me = colon_mesh(c);
	struct lod *l = lod_create(me, 0);

	(void)state;
	assert_non_null(l);
	assert_int_equal(l->levels, 1);
	assert_memory_equal(l->index, me->tri,
			    me->triangles * sizeof(*me->tri));
	for (uint32_t k = 0; k < me->segments; k++) {
		struct lod_range r = lod_segment(l, 3, k);

		assert_int_equal(r.first, 3 * me->seg[k].first);
		assert_int_equal(r.count, 3 * me->seg[k].count);
	}
	lod_destroy(l);
	colon_destroy(c);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(full_detail_is_the_mesh),
		cmocka_unit_test(levels_face_the_lumen),
		cmocka_unit_test(cost_independent_of_resolution),
		cmocka_unit_test(import_has_one_level),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
