/*
 * test_scene.c - GetScene's replies: chunk 0 carries the case and its
 * centreline, the other chunks cover every vertex and triangle exactly
 * once, in order, each packed reply within a few MiB even at 2 million
 * triangles, and what they carry is the colon itself; chunk 0 says which
 * scope the colon is rendered with.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "conf/cases.h"
#include "conf/config.h"
#include "model/scene.h"

#define MAX_REPLY_BYTES (4u << 20)

static struct colon *load(const char *name, double step, int ring)
{
	struct config cfg;
	char err[512];
	struct colon *c;

	config_defaults(&cfg);
	snprintf(cfg.colon.directory, sizeof(cfg.colon.directory), "%s",
		 "config/cases");
	cfg.colon.step_m = step;
	cfg.colon.ring_vertices = ring;
	c = cases_load(&cfg, name, err, sizeof(err));
	if (!c) {
		print_error("%s\n", err);
		fail();
	}
	return c;
}

static void check_chunks(const struct colon *c)
{
	const struct mesh *m = colon_mesh(c);
	struct scene *s = scene_create(c, 7);
	uint32_t next_v = 0, next_t = 0;
	Endosim__SceneReply *r;

	assert_non_null(s);
	r = scene_reply(s, 0);
	assert_non_null(r);
	assert_int_equal(r->scene_id, 7);
	assert_int_equal(r->chunks, scene_chunks(s));
	assert_string_equal(r->info->name, colon_name(c));
	assert_int_equal(r->info->vertices, m->vertices);
	assert_int_equal(r->info->triangles, m->triangles);
	assert_int_equal(r->info->n_centreline,
			 3 * centreline_count(colon_centreline(c)));
	assert_memory_equal(&r->info->centreline[3 * 5],
			    centreline_base(colon_centreline(c), 5)->p,
			    3 * sizeof(double));
	assert_int_equal(r->info->n_segments, m->segments);
	assert_int_equal(r->info->n_span_s, 4);
	assert_true(endosim__scene_reply__get_packed_size(r) < MAX_REPLY_BYTES);
	for (uint32_t k = 1; k < scene_chunks(s); k++) {
		const Endosim__SceneChunk *ch;

		r = scene_reply(s, k);
		assert_non_null(r);
		ch = r->mesh;
		assert_true(endosim__scene_reply__get_packed_size(r) <
			    MAX_REPLY_BYTES);
		if (ch->n_indices) {
			assert_int_equal(next_v, m->vertices);
			assert_int_equal(ch->first_triangle, next_t);
			assert_memory_equal(ch->indices, m->tri[next_t],
					    ch->n_indices * sizeof(uint32_t));
			next_t += (uint32_t)ch->n_indices / 3;
			continue;
		}
		assert_int_equal(ch->first_vertex, next_v);
		assert_int_equal(ch->n_positions, 3 * ch->n_vertex_sample);
		assert_memory_equal(ch->positions, m->pos[next_v],
				    ch->n_positions * sizeof(float));
		assert_memory_equal(ch->vertex_sample, &m->sample[next_v],
				    ch->n_vertex_sample * sizeof(uint32_t));
		next_v += (uint32_t)ch->n_vertex_sample;
	}
	assert_int_equal(next_v, m->vertices);
	assert_int_equal(next_t, m->triangles);
	assert_null(scene_reply(s, scene_chunks(s)));
	scene_destroy(s);
}

static void test_chunks_cover_default_mesh(void **state)
{
	struct colon *c = load("polyps", 0.002, 192);
	struct scene *s = scene_create(c, 1);
	Endosim__SceneReply *r = scene_reply(s, 0);

	(void)state;
	assert_int_equal(r->info->n_polyps, 5);
	assert_int_equal(r->info->n_regions, 9);
	assert_string_equal(r->info->regions[8]->name, "cecum");
	assert_true(r->info->cecum_s_m > 1.3);
	/* the assistant's sites, by name, as the case places them */
	assert_int_equal(r->info->n_sites, 2);
	assert_string_equal(r->info->sites[0]->name, "llq");
	assert_string_equal(r->info->sites[1]->name, "umbilical");
	assert_int_equal(r->info->sites[1]->n_position_m, 3);
	assert_true(r->info->sites[1]->position_m[1] == -0.199);
	assert_int_equal(r->info->sites[0]->n_direction, 3);
	assert_true(r->info->sites[0]->direction[1] == 1);
	assert_true(r->info->sites[0]->radius_m == 0.08);
	assert_true(protobuf_c_message_check(&r->base));
	scene_destroy(s);
	check_chunks(c);
	colon_destroy(c);
}

static void test_chunks_stay_small_at_two_million(void **state)
{
	struct colon *c = load("normal", 0.001, 672);

	(void)state;
	assert_true(colon_mesh(c)->triangles > 2000000);
	check_chunks(c);
	colon_destroy(c);
}

static void test_bad_case_name_refused(void **state)
{
	struct config cfg;
	char err[512];

	(void)state;
	config_defaults(&cfg);
	snprintf(cfg.colon.directory, sizeof(cfg.colon.directory), "%s",
		 "config/cases");
	assert_null(cases_load(&cfg, "../cases/normal", err, sizeof(err)));
	assert_non_null(strstr(err, "not a case name"));
	assert_null(cases_load(&cfg, "nope", err, sizeof(err)));
	assert_non_null(strstr(err, "config/cases/nope.case: cannot open"));
}

/* The scope set is the one chunk 0 carries, packed and read back. */
static void test_scope_on_the_wire(void **state)
{
	const struct scope_params p = {
		.bending_length_m = 0.1, .ud_gain = 2, .lr_gain = 1.5,
		.ud_limit_rad = 3, .lr_limit_rad = 2.5,
	};
	struct colon *c = load("normal", 0.004, 32);
	struct scene *s = scene_create(c, 3);
	struct client_scene cs;
	Endosim__SceneReply *r = scene_reply(s, 0), *back;
	uint8_t *buf;
	size_t n;

	(void)state;
	assert_null(r->info->scope);
	scene_set_scope(s, &p, 0.007);
	r = scene_reply(s, 0);
	n = endosim__scene_reply__get_packed_size(r);
	buf = malloc(n);
	assert_non_null(buf);
	endosim__scene_reply__pack(r, buf);
	back = endosim__scene_reply__unpack(NULL, n, buf);
	assert_non_null(back);
	assert_non_null(back->info->scope);
	assert_true(back->info->scope->bending_length_m == 0.1);
	assert_true(back->info->scope->ud_gain == 2);
	assert_true(back->info->scope->lr_gain == 1.5);
	assert_true(back->info->scope->ud_limit_rad == 3);
	assert_true(back->info->scope->lr_limit_rad == 2.5);
	assert_true(back->info->scope->radius_m == 0.007);
	endosim__scene_reply__free_unpacked(back, NULL);
	free(buf);
	scene_client(s, &cs);
	assert_ptr_equal(cs.scope, r->info->scope);
	scene_destroy(s);
	colon_destroy(c);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_chunks_cover_default_mesh),
		cmocka_unit_test(test_chunks_stay_small_at_two_million),
		cmocka_unit_test(test_bad_case_name_refused),
		cmocka_unit_test(test_scope_on_the_wire),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
