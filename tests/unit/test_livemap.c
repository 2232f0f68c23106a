/* test_livemap.c - the unseen-mucosa map on the wire (livemap.h): each
 * share to its byte and back within half a step, the cells' order, the
 * cells without wall, the mean over the walls only. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "session/livemap.h"

static struct metrics_map map;
static uint8_t cells[LIVEMAP_CELLS];

/* A map whose cell (i, k) says where it is: i and k in one share. */
static void place_map(void)
{
	for (int i = 0; i < METRICS_MAP_S; i++) {
		for (int k = 0; k < METRICS_MAP_A; k++) {
			map.seen[i][k] = (float)(i * METRICS_MAP_A + k) /
					 (LIVEMAP_CELLS - 1);
		}
	}
}

static void test_ends_and_no_wall(void **state)
{
	(void)state;
	place_map();
	map.seen[0][0] = 0;
	map.seen[0][1] = 1;
	map.seen[0][2] = -1;         /* no wall */
	map.seen[0][3] = NAN;        /* no number: no wall either */
	map.seen[0][4] = 1.5f;       /* more than all: all */
	map.seen[0][5] = 0.5f;
	livemap_quantise(&map, cells);
	assert_int_equal(cells[0], 0);
	assert_int_equal(cells[1], LIVEMAP_FULL);
	assert_int_equal(cells[2], LIVEMAP_NO_WALL);
	assert_int_equal(cells[3], LIVEMAP_NO_WALL);
	assert_int_equal(cells[4], LIVEMAP_FULL);
	assert_int_equal(cells[5], 127);
	assert_true(livemap_share(LIVEMAP_NO_WALL) < 0);
	assert_true(livemap_share(0) == 0);
	assert_true(livemap_share(LIVEMAP_FULL) == 1);
}

/* Cell (i, k) at byte i * around + k: the shares rise along the bytes. */
static void test_order_and_precision(void **state)
{
	(void)state;
	place_map();
	livemap_quantise(&map, cells);
	for (int i = 0; i < METRICS_MAP_S; i++) {
		for (int k = 0; k < METRICS_MAP_A; k++) {
			size_t b = (size_t)i * METRICS_MAP_A + k;
			double back = livemap_share(cells[b]);

			assert_true(fabs(back - map.seen[i][k]) <=
				    0.5 / LIVEMAP_FULL + 1e-9);
			if (b) {
				assert_true(cells[b] >= cells[b - 1]);
			}
		}
	}
	assert_int_equal(cells[0], 0);
	assert_int_equal(cells[LIVEMAP_CELLS - 1], LIVEMAP_FULL);
}

/* Every byte but the wall-less one is a share that quantises to itself. */
static void test_round_trip(void **state)
{
	(void)state;
	for (int b = 0; b <= LIVEMAP_FULL; b++) {
		memset(&map, 0, sizeof(map));
		map.seen[3][7] = (float)livemap_share((uint8_t)b);
		livemap_quantise(&map, cells);
		assert_int_equal(cells[3 * METRICS_MAP_A + 7], b);
	}
}

static void test_mean_over_walls(void **state)
{
	uint8_t some[6] = { 0, LIVEMAP_FULL, LIVEMAP_NO_WALL, LIVEMAP_FULL,
			    LIVEMAP_NO_WALL, 0 };
	uint8_t none[3] = { LIVEMAP_NO_WALL, LIVEMAP_NO_WALL,
			    LIVEMAP_NO_WALL };

	(void)state;
	assert_true(fabs(livemap_mean_seen(some, 6) - 0.5) < 1e-12);
	assert_true(fabs(livemap_mean_seen(some, 2) - 0.5) < 1e-12);
	assert_true(livemap_mean_seen(some, 1) == 0);
	assert_true(livemap_mean_seen(none, 3) == 0);
	assert_true(livemap_mean_seen(none, 0) == 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ends_and_no_wall),
		cmocka_unit_test(test_order_and_precision),
		cmocka_unit_test(test_round_trip),
		cmocka_unit_test(test_mean_over_walls),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
