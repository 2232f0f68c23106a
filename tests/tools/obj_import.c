/*
 * obj_import - imports a Wavefront OBJ colon (with its centreline as the
 * OBJ's polyline, as endosimd exports it) the way endosimd does, and
 * prints what it found. Used by the system tests.
 *
 *   obj_import FILE.obj [CENTRELINE.txt]
 *
 * Prints name=, vertices=, triangles=, samples=, segments= lines; exit 0,
 * or 1 with endosimd's error message.
 */
#include <stdio.h>

#include "model/colon.h"

int main(int argc, char **argv)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	struct colon *c;
	char err[512];

	if (argc < 2 || argc > 3) {
		fprintf(stderr, "usage: obj_import FILE.obj [CENTRELINE]\n");
		return 2;
	}
	c = colon_import(argv[1], argc == 3 ? argv[2] : NULL, &p, err,
			 sizeof(err));
	if (!c) {
		fprintf(stderr, "%s\n", err);
		return 1;
	}
	printf("name=%s\nvertices=%u\ntriangles=%u\nsamples=%zu\n"
	       "segments=%u\nlength_m=%.4f\n", colon_name(c),
	       colon_mesh(c)->vertices, colon_mesh(c)->triangles,
	       centreline_count(colon_centreline(c)), colon_mesh(c)->segments,
	       centreline_length(colon_centreline(c)));
	colon_destroy(c);
	return 0;
}
