/*
 * fuzz_anatomy - libFuzzer target: the case-file parser (anatomy.c) on
 * arbitrary file contents, then building the colon of whatever it accepts
 * (at a coarse resolution: the checks must keep the geometry buildable).
 */
#include <stdint.h>

#include "model/colon.h"
#include "fuzz_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const struct colon_params p = { .step_m = 0.01, .ring_vertices = 8,
					.segment_m = 0.2 };
	struct anatomy a;
	struct colon *c;
	char err[512];

	if (anatomy_load(&a, fuzz_file(data, size), err, sizeof(err))) {
		return 0;
	}
	c = colon_create(&a, &p, err, sizeof(err));
	colon_destroy(c);
	return 0;
}
