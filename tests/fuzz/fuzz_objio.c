/*
 * fuzz_objio - libFuzzer target: the OBJ importer on arbitrary file
 * contents, as `[case] file = colon.obj` meets it: objio.c's reader, then
 * colon_import() making a colon of the mesh and its polyline (resampled,
 * indexed in segments); and the same bytes as a centreline point file.
 */
#include <stdint.h>
#include <stdlib.h>

#include "model/colon.h"
#include "fuzz_file.h"
#include "model/objio.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const struct colon_params p = { .step_m = 0.005, .ring_vertices = 8,
					.segment_m = 0.1 };
	const char *path = fuzz_file(data, size);
	double(*pts)[3] = NULL;
	struct colon *c;
	char err[512];
	size_t n;

	c = colon_import(path, NULL, &p, err, sizeof(err));
	colon_destroy(c);
	if (!objio_read_points(path, &pts, &n, err, sizeof(err))) {
		free(pts);
	}
	return 0;
}
