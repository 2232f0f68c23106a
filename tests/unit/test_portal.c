/*
 * test_portal.c - the portal walk (viewer/portal.h): from wherever the
 * scope's kinematics put the camera, it finds the camera's segment and
 * what lies ahead within reach, never more than the colon near the camera,
 * and draws the same number of triangles whatever the mesh's resolution.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "viewer/endo.h"
#include "viewer/lod.h"
#include "viewer/portal.h"
#include "model/scope.h"
#include "base/vec3.h"
#include "viewer_fixture.h"

#define MAX_TRIANGLES 16000 /* llvmpipe draws 1-2 million a second */

static struct portal_view camera(const struct model *m, double depth_m,
				 double *s_m)
{
	const struct scope_params p = SCOPE_PARAMS_DEFAULT;
	const struct scope_input in = { .depth_m = depth_m };
	struct scope_pose pose;
	struct portal_view v = {
		.half_angle = ENDO_HALF_ANGLE_RAD, .far_m = ENDO_FAR_M,
		.level_m = { ENDO_LEVEL_M },
	};

	scope_update(&p, m->cl, &in, &pose);
	vec3_copy(v.eye, pose.tip);
	model_keep_inside(m, model_sample_at(m, pose.tip_s_m), v.eye,
			  ENDO_WALL_MARGIN_M); /* as endo_camera() */
	vec3_copy(v.dir, pose.dir);
	*s_m = pose.tip_s_m;
	return v;
}

/* Triangles the walk draws from depth D_M; checks the camera's segment
 * is among them. */
static uint32_t drawn(const struct fixture *f, const struct lod *l,
		      double depth_m)
{
	struct portal_item seen[PORTAL_MAX];
	double s;
	struct portal_view v = camera(f->model, depth_m, &s);
	uint32_t kc = mesh_segment_at(f->model->mesh, s), tris = 0;
	int n = portal_find(f->model, &v, s, seen), found = 0;

	assert_true(n > 0 && n <= PORTAL_MAX);
	for (int k = 0; k < n; k++) {
		assert_true(seen[k].distance_m <= v.far_m);
		assert_true(k == 0 ||
			    seen[k].distance_m >= seen[k - 1].distance_m);
		found |= seen[k].segment == kc;
		tris += lod_segment(l, seen[k].level, seen[k].segment).count /
			3;
	}
	assert_true(found);
	return tris;
}

static void bounded_and_independent_of_resolution(void **state)
{
	struct fixture dflt, fine;
	struct lod *ld, *lf;

	(void)state;
	fixture_setup(&dflt, "config/cases", "normal", 0.002, 192);
	fixture_setup(&fine, "config/cases", "normal", 0.001, 672);
	ld = lod_create(dflt.model->mesh, dflt.model->ring);
	lf = lod_create(fine.model->mesh, fine.model->ring);
	assert_true(fine.model->mesh->triangles > 1900000);
	for (double d = 0.05; d < 1.5; d += 0.05) {
		uint32_t a = drawn(&dflt, ld, d), b = drawn(&fine, lf, d);

		assert_true(a <= MAX_TRIANGLES);
		assert_true(fabs((double)a - b) <= 0.1 * a);
	}
	lod_destroy(ld);
	lod_destroy(lf);
	fixture_teardown(&dflt);
	fixture_teardown(&fine);
}

/* The farthest and nearest material position among the segments found. */
static void reach(const struct model *m, const struct portal_view *v,
		  double s, double *lo, double *hi)
{
	struct portal_item seen[PORTAL_MAX];
	int n = portal_find(m, v, s, seen);

	*lo = INFINITY;
	*hi = -INFINITY;
	for (int k = 0; k < n; k++) {
		const struct mesh_segment *sg = &m->mesh->seg[seen[k].segment];

		*lo = fmin(*lo, sg->s0_m);
		*hi = fmax(*hi, sg->s1_m);
	}
}

/* Down a straight lumen: as far as the light reaches, and no farther;
 * looking back: behind, not ahead. */
static void sees_down_the_lumen(void **state)
{
	struct fixture f;
	struct portal_view v;
	double s, lo, hi;

	(void)state;
	fixture_setup(&f, "tests/cases", "straight", 0.002, 192);
	v = camera(f.model, 0.60, &s);
	reach(f.model, &v, s, &lo, &hi);
	assert_true(hi >= s + v.far_m - 0.04);
	assert_true(hi <= s + v.far_m + 0.08);
	assert_true(lo >= s - 0.08);
	vec3_scale(v.dir, v.dir, -1);
	reach(f.model, &v, s, &lo, &hi);
	assert_true(hi <= s + 0.08);
	assert_true(lo <= s - 0.2);
	fixture_teardown(&f);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(bounded_and_independent_of_resolution),
		cmocka_unit_test(sees_down_the_lumen),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
