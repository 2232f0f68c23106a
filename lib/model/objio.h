/*
 * objio.h - the colon's mesh in and out of Wavefront OBJ, and centreline
 * point files, so that meshes from elsewhere (segmented CT colonography)
 * can replace a generated case and ours open in MeshLab or Blender.
 *
 * Reading OBJ: 'v x y z' (metres; a fourth weight is refused), faces 'f'
 * with 3 or more corners written 'i', 'i/t', 'i//n' or 'i/t/n' (1-based,
 * or negative: relative to the last vertex; polygons are split into fans),
 * and polylines 'l i j ...' (joined in file order: the centreline). 'vt',
 * 'vn', 'vp', 'o', 'g', 's', 'mtllib', 'usemtl' are skipped; any other
 * statement, a number that is not finite, an index out of range or a face
 * that repeats a corner is refused with "FILE:LINE: what".
 *
 * Centreline point files: one point "x y z" (metres) per line, '#' starts
 * a comment, blank lines are skipped.
 *
 * Writing: "o colon" with 'v', 'vn' and 'f i//i' (triangles counter-
 * clockwise seen from the lumen), then "o centreline" with its points and
 * 'l' polylines of 16 points, each starting at the last one's end; numbers
 * with 9 significant digits (floats exactly).
 *
 * All functions do file I/O and allocate: never in the force loop. The
 * module depends on nothing but libc, so clients (endoctl) link it too.
 */
#ifndef ENDOSIM_OBJIO_H
#define ENDOSIM_OBJIO_H

#include <stddef.h>
#include <stdint.h>

#include "model/centreline.h"

struct objio_data {
	double (*v)[3];      /* every 'v', m */
	size_t nv;
	uint32_t (*tri)[3];  /* faces as triangles, 0-based into v */
	size_t ntri;
	uint32_t *line;      /* the polylines' corners in order, into v */
	size_t nline;
};

/* Reads PATH into D. Returns 0, or a negative errno with one line in ERR. */
int objio_read(const char *path, struct objio_data *d, char *err,
	       size_t errsize);

/* Frees what objio_read() allocated; D is zeroed. */
void objio_free(struct objio_data *d);

/*
 * Reads a centreline point file: *PTS (malloc'd) and *N. Returns 0, or a
 * negative errno with one line in ERR.
 */
int objio_read_points(const char *path, double (**pts)[3], size_t *n,
		      char *err, size_t errsize);

/* What objio_write() writes: plain arrays, so any client can. */
struct objio_mesh {
	const char *name;
	const float (*pos)[3];         /* m */
	const float (*nrm)[3];         /* unit, into the lumen */
	uint32_t vertices;
	const uint32_t (*tri)[3];      /* 0-based */
	uint32_t triangles;
	const double (*centreline)[3]; /* m */
	size_t samples;
	double step_m;                 /* for the header comment */
};

/* Writes M to PATH. Returns 0, or a negative errno with one line in ERR. */
int objio_write(const char *path, const struct objio_mesh *m, char *err,
		size_t errsize);

#endif
