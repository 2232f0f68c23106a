/* objio.c - see objio.h. */
#include "model/objio.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LINE_MAX_BYTES 4096
#define LINE_POINTS 16 /* per 'l' element written */

struct reader {
	const char *path;
	int line;
	char *err;
	size_t errsize;
	size_t vcap, tcap, lcap;
};

static int fail(struct reader *r, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

static int fail(struct reader *r, const char *fmt, ...)
{
	char msg[200];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(msg, sizeof(msg), fmt, ap);
	va_end(ap);
	snprintf(r->err, r->errsize, "%s:%d: %s", r->path, r->line, msg);
	return -EINVAL;
}

/* Makes room for one more element of SIZE bytes in *ARR. */
static int grow(void **arr, size_t n, size_t *cap, size_t size)
{
	void *bigger;
	size_t c;

	if (n < *cap) {
		return 0;
	}
	c = *cap ? *cap * 2 : 1024;
	bigger = realloc(*arr, c * size);
	if (!bigger) {
		return -ENOMEM;
	}
	*arr = bigger;
	*cap = c;
	return 0;
}

/* Three finite numbers, the only tokens of TEXT. */
static int parse_xyz(struct reader *r, char *text, double out[3])
{
	char *tok, *end, *save = NULL;
	int n = 0;

	for (tok = strtok_r(text, " \t\r\n", &save); tok;
	     tok = strtok_r(NULL, " \t\r\n", &save)) {
		if (n == 3) {
			return fail(r, "expected 3 coordinates");
		}
		errno = 0;
		out[n] = strtod(tok, &end);
		if (*end || errno || !isfinite(out[n])) {
			return fail(r, "'%s' is not a finite number", tok);
		}
		n++;
	}
	return n == 3 ? 0 : fail(r, "expected 3 coordinates");
}

/* An OBJ index (1-based or negative) into the NV vertices read so far. */
static int parse_index(struct reader *r, const char *tok, size_t nv,
		       uint32_t *out)
{
	char *end;
	long i;

	errno = 0;
	i = strtol(tok, &end, 10);
	if (end == tok || (*end && *end != '/') || errno || i == 0) {
		return fail(r, "'%s' is not a vertex index", tok);
	}
	if (i < 0) {
		i += (long)nv + 1;
	}
	if (i < 1 || (size_t)i > nv) {
		return fail(r, "vertex index %s is out of range (1..%zu)", tok,
			    nv);
	}
	*out = (uint32_t)(i - 1);
	return 0;
}

static int add_face(struct reader *r, struct objio_data *d, char *save)
{
	uint32_t corner[2];
	char *tok;
	int n = 0;

	while ((tok = strtok_r(NULL, " \t\r\n", &save))) {
		uint32_t i;

		if (parse_index(r, tok, d->nv, &i)) {
			return -EINVAL;
		}
		if ((n >= 1 && i == corner[0]) || (n >= 2 && i == corner[1])) {
			return fail(r, "face repeats vertex %u", i + 1);
		}
		if (n < 2) {
			corner[n++] = i;
			continue;
		}
		if (grow((void **)&d->tri, d->ntri, &r->tcap, sizeof(*d->tri))) {
			return fail(r, "out of memory");
		}
		d->tri[d->ntri][0] = corner[0];
		d->tri[d->ntri][1] = corner[1];
		d->tri[d->ntri++][2] = i;
		corner[1] = i; /* the fan's next triangle */
		n++;
	}
	return n < 3 ? fail(r, "a face needs at least 3 vertices") : 0;
}

static int add_line(struct reader *r, struct objio_data *d, char *save)
{
	char *tok;

	while ((tok = strtok_r(NULL, " \t\r\n", &save))) {
		uint32_t i;

		if (parse_index(r, tok, d->nv, &i)) {
			return -EINVAL;
		}
		if (d->nline && d->line[d->nline - 1] == i) {
			continue; /* a polyline joined to the previous one */
		}
		if (grow((void **)&d->line, d->nline, &r->lcap,
			 sizeof(*d->line))) {
			return fail(r, "out of memory");
		}
		d->line[d->nline++] = i;
	}
	return 0;
}

static bool skipped(const char *kw)
{
	static const char *const skip[] = { "vt", "vn", "vp", "o", "g", "s",
					    "mtllib", "usemtl", NULL };

	for (int i = 0; skip[i]; i++) {
		if (!strcmp(kw, skip[i])) {
			return true;
		}
	}
	return false;
}

static int read_statement(struct reader *r, struct objio_data *d, char *buf)
{
	char *save = NULL, *kw = strtok_r(buf, " \t\r\n", &save);

	if (!kw || *kw == '#' || skipped(kw)) {
		return 0;
	}
	if (!strcmp(kw, "v")) {
		if (grow((void **)&d->v, d->nv, &r->vcap, sizeof(*d->v))) {
			return fail(r, "out of memory");
		}
		if (parse_xyz(r, save, d->v[d->nv])) {
			return -EINVAL;
		}
		d->nv++;
		return 0;
	}
	if (!strcmp(kw, "f")) {
		return add_face(r, d, save);
	}
	if (!strcmp(kw, "l")) {
		return add_line(r, d, save);
	}
	return fail(r, "unknown statement '%s'", kw);
}

/* Feeds each line of PATH to FN; FILE:LINE errors. */
static int read_lines(struct reader *r, void *ctx,
		      int (*fn)(struct reader *, void *, char *))
{
	char buf[LINE_MAX_BYTES];
	FILE *f = fopen(r->path, "r");
	int ret = 0;

	if (!f) {
		ret = -errno;
		snprintf(r->err, r->errsize, "%s: cannot open: %s", r->path,
			 strerror(-ret));
		return ret;
	}
	while (!ret && fgets(buf, sizeof(buf), f)) {
		r->line++;
		if (!strchr(buf, '\n') && !feof(f)) {
			ret = fail(r, "line longer than %d bytes",
				   LINE_MAX_BYTES - 2);
			break;
		}
		ret = fn(r, ctx, buf);
	}
	if (!ret && ferror(f)) {
		ret = -EIO;
		snprintf(r->err, r->errsize, "%s: read error", r->path);
	}
	fclose(f);
	return ret;
}

static int obj_line(struct reader *r, void *ctx, char *buf)
{
	return read_statement(r, ctx, buf);
}

int objio_read(const char *path, struct objio_data *d, char *err,
	       size_t errsize)
{
	struct reader r = { .path = path, .err = err, .errsize = errsize };
	int ret;

	memset(d, 0, sizeof(*d));
	ret = read_lines(&r, d, obj_line);
	if (!ret && !d->ntri) {
		snprintf(err, errsize, "%s: no faces", path);
		ret = -EINVAL;
	}
	if (ret) {
		objio_free(d);
	}
	return ret;
}

void objio_free(struct objio_data *d)
{
	free(d->v);
	free(d->tri);
	free(d->line);
	memset(d, 0, sizeof(*d));
}

struct points {
	double (*p)[3];
	size_t n;
};

static int point_line(struct reader *r, void *ctx, char *buf)
{
	struct points *pts = ctx;

	buf[strcspn(buf, "#")] = '\0';
	if (strspn(buf, " \t\r\n") == strlen(buf)) {
		return 0;
	}
	if (grow((void **)&pts->p, pts->n, &r->vcap, sizeof(*pts->p))) {
		return fail(r, "out of memory");
	}
	return parse_xyz(r, buf, pts->p[pts->n++]);
}

int objio_read_points(const char *path, double (**out)[3], size_t *n,
		      char *err, size_t errsize)
{
	struct reader r = { .path = path, .err = err, .errsize = errsize };
	struct points pts = { 0 };
	int ret = read_lines(&r, &pts, point_line);

	if (!ret && pts.n < CENTRELINE_MIN_SAMPLES) {
		snprintf(err, errsize, "%s: %zu points, need at least %d",
			 path, pts.n, CENTRELINE_MIN_SAMPLES);
		ret = -EINVAL;
	}
	if (ret) {
		free(pts.p);
		return ret;
	}
	*out = pts.p;
	*n = pts.n;
	return 0;
}

int objio_write(const char *path, const struct objio_mesh *m, char *err,
		size_t errsize)
{
	FILE *f = fopen(path, "w");
	int ret = 0;

	if (!f) {
		ret = -errno;
		snprintf(err, errsize, "%s: cannot create: %s", path,
			 strerror(-ret));
		return ret;
	}
	fprintf(f, "# endosim colon '%s': %u vertices, %u triangles, "
		"centreline of %zu points every %.9g m\no colon\n", m->name,
		m->vertices, m->triangles, m->samples, m->step_m);
	for (uint32_t j = 0; j < m->vertices; j++) {
		fprintf(f, "v %.9g %.9g %.9g\n", m->pos[j][0], m->pos[j][1],
			m->pos[j][2]);
	}
	for (uint32_t j = 0; j < m->vertices; j++) {
		fprintf(f, "vn %.9g %.9g %.9g\n", m->nrm[j][0], m->nrm[j][1],
			m->nrm[j][2]);
	}
	for (uint32_t k = 0; k < m->triangles; k++) {
		const uint32_t *t = m->tri[k];

		fprintf(f, "f %u//%u %u//%u %u//%u\n", t[0] + 1, t[0] + 1,
			t[1] + 1, t[1] + 1, t[2] + 1, t[2] + 1);
	}
	fprintf(f, "o centreline\n");
	for (size_t i = 0; i < m->samples; i++) {
		const double *p = m->centreline[i];

		fprintf(f, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
	}
	/* polylines of LINE_POINTS, each starting where the last ended */
	for (size_t i = 0; i + 1 < m->samples; i += LINE_POINTS - 1) {
		fprintf(f, "l");
		for (size_t k = i; k < i + LINE_POINTS && k < m->samples; k++) {
			fprintf(f, " %zu", m->vertices + k + 1);
		}
		fprintf(f, "\n");
	}
	if (ferror(f)) {
		ret = -EIO;
	}
	if (fclose(f) && !ret) {
		ret = -errno;
	}
	if (ret) {
		snprintf(err, errsize, "%s: write error: %s", path,
			 strerror(-ret));
	}
	return ret;
}
