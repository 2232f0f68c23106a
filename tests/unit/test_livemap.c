/* test_livemap.c - the unseen-mucosa map on the wire (livemap.h): each
 * share to its byte and back within half a step, the cells' order, the
 * cells without wall, the mean over the walls only; the map's colour
 * ramp. */
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

/*
 * The map's colour ramp: each channel from the unseen end to the seen one
 * and straight between; on the page the report's colours, on the screen
 * what 77-live-map's pixel statistics count as red and as green
 * (png_stats.c).
 */
static void test_colour_ramp(void **state)
{
	static const double page[2][3] = { { 214, 60, 60 },
					   { 154, 230, 180 } };
	double end[2][3], c[3];

	(void)state;
	for (int bg = LIVEMAP_ON_PAGE; bg <= LIVEMAP_ON_SCREEN; bg++) {
		livemap_colour(bg, 0, end[0]);
		livemap_colour(bg, 1, end[1]);
		for (int k = 0; k <= 10; k++) {
			livemap_colour(bg, k / 10.0, c);
			for (int ch = 0; ch < 3; ch++) {
				double want = end[0][ch] +
					      k / 10.0 * (end[1][ch] -
							  end[0][ch]);

				assert_true(fabs(c[ch] - want) < 1e-9);
				assert_true(c[ch] >= 0 && c[ch] <= 255);
			}
		}
		if (bg == LIVEMAP_ON_PAGE) {
			for (int ch = 0; ch < 3; ch++) {
				assert_true(fabs(end[0][ch] - page[0][ch]) <
					    1e-9);
				assert_true(fabs(end[1][ch] - page[1][ch]) <
					    1e-9);
			}
			continue;
		}
		assert_true(end[0][0] > 200 && end[0][1] < 100 &&
			    end[0][2] < 100);
		assert_true(end[1][1] > 120 && end[1][1] > end[1][0] + 50 &&
			    end[1][1] > end[1][2] + 50);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ends_and_no_wall),
		cmocka_unit_test(test_order_and_precision),
		cmocka_unit_test(test_round_trip),
		cmocka_unit_test(test_mean_over_walls),
		cmocka_unit_test(test_colour_ramp),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
