/*
 * test_lod.c - the levels of detail (viewer/lod.h): at full detail they
 * are the mesh's own triangles; every level's triangles face the lumen and
 * address real vertices; what a segment costs at a level does not depend
 * on the mesh's resolution (the default ~290 000 triangles or 2 million);
 * the GPU holds only the vertices the levels draw. The default colon
 * and the 2 million triangles' are built once for the tests that look at
 * them (group setup).
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

/* The normal colon at the default resolution (rings 2 mm apart, 192
 * vertices round: ~290 000 triangles) and at 2 million triangles (1 mm,
 * 672), each with the viewer's model of it and its levels. */
struct built {
	struct fixture f;
	struct lod *l;
};
static struct built dflt, fine;

static void build(struct built *b, double step_m, uint32_t ring)
{
	fixture_setup(&b->f, "config/cases", "normal", step_m, ring);
	b->l = lod_create(b->f.model->mesh, b->f.model->ring);
	assert_non_null(b->l);
}

static int build_both(void **unused)
{
	(void)unused;
	build(&dflt, 0.002, 192);
	build(&fine, 0.001, 672);
	return 0;
}

static void unbuild(struct built *b)
{
	lod_destroy(b->l);
	fixture_teardown(&b->f);
}

static int free_both(void **unused)
{
	(void)unused;
	unbuild(&dflt);
	unbuild(&fine);
	return 0;
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
			a[k][c] = lod_source(l, l->index[3 * k + c], NULL);
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
	const struct fixture *f = &dflt.f;
	const struct mesh *me = f->model->mesh;
	const struct lod *l = dflt.l;

	(void)state;
	assert_int_equal(l->levels, LOD_LEVELS);
	for (int lv = 0; lv < l->levels; lv++) {
		struct lod_range r = lod_span(l, lv, 0, me->segments - 1);

		assert_int_equal(r.count % 3, 0);
		for (uint32_t k = r.first; k < r.first + r.count; k += 3) {
			double p[3][3], ab[3], ac[3], n[3], in[3];

			for (int c = 0; c < 3; c++) {
				uint32_t v = lod_source(l, l->index[k + c],
							NULL);

				assert_true(v < me->vertices);
				for (int x = 0; x < 3; x++) {
					p[c][x] = me->pos[v][x];
				}
			}
			vec3_sub(ab, p[1], p[0]);
			vec3_sub(ac, p[2], p[0]);
			vec3_cross(n, ab, ac);
			vec3_sub(in, centreline_sample(f->model->cl,
				 me->sample[lod_source(l, l->index[k],
						      NULL)])->p,
				 p[0]);
			assert_true(vec3_dot(n, in) > 0);
		}
	}
}

/* Triangles of segment K at each level, for the colon B. */
static void segment_costs(const struct built *b, uint32_t k,
			  uint32_t tris[LOD_LEVELS])
{
	for (int lv = 0; lv < LOD_LEVELS; lv++) {
		tris[lv] = lod_segment(b->l, lv, k).count / 3;
	}
}

static void cost_independent_of_resolution(void **state)
{
	uint32_t high[LOD_LEVELS], low[LOD_LEVELS];

	(void)state;
	segment_costs(&dflt, 10, low);
	segment_costs(&fine, 10, high);
	for (int lv = 0; lv < LOD_LEVELS; lv++) {
		print_message("level %d: %u and %u triangles a segment\n", lv,
			      low[lv], high[lv]);
		assert_true(low[lv] > 0);
		assert_true(fabs((double)high[lv] - low[lv]) <=
			    0.1 * low[lv]);
	}
	/* level 0: 4 cm of rings 2 mm apart, 32 vertices round */
	assert_int_equal(low[0], 20 * 32 * 2);
}

/* The GPU's vertices [K0, K1) are those of rings I0..I1 that it holds. */
static void range_is_rows(const struct lod *l, const struct mesh *me,
			  uint32_t i0, uint32_t i1)
{
	uint32_t k0, k1, first = me->sample_first[i0];

	lod_gpu_range(l, first, me->sample_first[i1 + 1] - first, &k0, &k1);
	assert_true(k0 < k1);
	assert_true(me->sample[lod_source(l, k0, NULL)] >= i0);
	assert_true(me->sample[lod_source(l, k1 - 1, NULL)] <= i1);
	if (k0 > 0) {
		assert_true(me->sample[lod_source(l, k0 - 1, NULL)] < i0);
	}
	if (k1 < l->vertices) {
		assert_true(me->sample[lod_source(l, k1, NULL)] > i1);
	}
}

/* At 2 million triangles (672 vertices a ring, 1 mm apart) the GPU holds
 * what the levels draw and no more than a grid of it: every row is drawn,
 * every 21st vertex round it (the endoscopic levels' stride), a fortieth
 * of the mesh; drawn marks just those vertices of the mesh; the vertices
 * of any stretch of rings are one run. */
static void holds_what_is_drawn(void **state)
{
	const struct mesh *me = fine.f.model->mesh;
	const struct lod *l = fine.l;
	uint8_t *used, *shown;
	uint32_t per_row;

	(void)state;
	assert_int_equal(l->column, 21);
	per_row = 672 / 21 + 1;
	assert_int_equal(l->vertices, (l->rows - 1) * per_row + 1);
	print_message("%u of %u vertices on the GPU\n", l->vertices,
		      me->vertices);
	assert_true(l->vertices < me->vertices / 40);
	used = calloc(l->rows, 1);
	shown = calloc(me->vertices, 1);
	assert_non_null(used);
	assert_non_null(shown);
	for (uint32_t k = 0; k < l->indices; k++) {
		assert_true(l->index[k] < l->vertices);
		used[l->index[k] / per_row] = 1;
	}
	for (uint32_t r = 0; r < l->rows; r++) {
		uint32_t i = l->row_sample[r], j;

		assert_true(used[r]);
		assert_int_equal(l->row[i], r);
		assert_int_equal(lod_source(l, lod_vertex(l, i, 0), &j),
				 me->sample_first[i]);
		assert_int_equal(j, 0);
	}
	for (uint32_t k = 0; k < l->vertices; k++) {
		shown[lod_source(l, k, NULL)] = 1;
	}
	assert_memory_equal(shown, l->drawn, me->vertices);
	range_is_rows(l, me, 0, 0);
	range_is_rows(l, me, 301, 302);
	range_is_rows(l, me, 300, 900);
	range_is_rows(l, me, 1000, (uint32_t)me->samples - 1);
	free(used);
	free(shown);
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
		cmocka_unit_test(holds_what_is_drawn),
		cmocka_unit_test(import_has_one_level),
	};

	return cmocka_run_group_tests(tests, build_both, free_both);
}
