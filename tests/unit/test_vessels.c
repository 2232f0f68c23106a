/*
 * test_vessels.c - the mucosa's texture (viewer/vessels.h): the same seed
 * makes the same image; it tiles (its edges meet as smoothly as any two
 * neighbouring columns); it has vessels (darker, redder lines) on a
 * salmon-pink mucosa; and vessels_around() has no seam.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "viewer/vessels.h"

#define N 1024 /* as endoview makes it */

/* Mean absolute difference between columns A and B. */
static double column_step(const uint8_t *img, int a, int b)
{
	double sum = 0;

	for (int y = 0; y < N; y++) {
		for (int c = 0; c < 4; c++) {
			sum += abs(img[4 * (y * N + a) + c] -
				   img[4 * (y * N + b) + c]);
		}
	}
	return sum / (4 * N);
}

static void tiles_and_repeats(void **state)
{
	uint8_t *a = vessels_create(N, 7), *b = vessels_create(N, 7);
	double inner = 0;

	(void)state;
	assert_non_null(a);
	assert_non_null(b);
	assert_memory_equal(a, b, 4 * N * N);
	for (int x = 0; x + 1 < N; x++) {
		inner += column_step(a, x, x + 1) / (N - 1);
	}
	assert_true(column_step(a, N - 1, 0) < 2 * inner);
	assert_null(vessels_create(100, 7));
	free(a);
	free(b);
}

static void mucosa_and_vessels(void **state)
{
	uint8_t *img = vessels_create(N, 3);
	int dark = 0;
	double r = 0, g = 0, bl = 0;

	(void)state;
	assert_non_null(img);
	for (int k = 0; k < N * N; k++) {
		r += img[4 * k];
		g += img[4 * k + 1];
		bl += img[4 * k + 2];
		dark += img[4 * k + 1] < 0.75 * 0.36 * 255; /* a vessel */
	}
	assert_true(r > 1.5 * g && g > bl); /* salmon pink */
	assert_true(dark > N * N / 100 && dark < N * N / 3);
	free(img);
}

static void no_seam_around(void **state)
{
	(void)state;
	assert_true(fabs(vessels_around(1e-9) - vessels_around(-1e-9)) < 1e-6);
	assert_true(fabs(vessels_around(2 * M_PI - 1e-9) -
			 vessels_around(1e-9)) < 1e-6);
	assert_true(fabs(vessels_around(M_PI) - VESSELS_AROUND / 2) < 1e-9);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(tiles_and_repeats),
		cmocka_unit_test(mucosa_and_vessels),
		cmocka_unit_test(no_seam_around),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
