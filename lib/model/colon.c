/* colon.c - see colon.h. */
#include "model/colon.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/objio.h"
#include "base/vec3.h"

#define BLEND_M 0.015 /* half-width of the blend between segments */
#define MAX_PIECES (ANATOMY_SEGMENTS * (2 * ANATOMY_MAX_BENDS + 1))

struct colon {
	char name[ANATOMY_NAME];
	struct anatomy anatomy;
	bool generated;
	struct centreline *cl;
	struct mesh *mesh;
	struct contact *contact;
	float *tube;     /* per sample: the lumen's radius for the tube, m */
	struct colon_region region[COLON_MAX_REGIONS];
	int regions;
	double cecum_s;
};

/* ---------------------------------------------------------------- course */

/* A straight or a circular arc of the course, laid by a turtle. */
struct piece {
	double s0, len;  /* m */
	double p[3];     /* start */
	double t[3];     /* start tangent */
	double n[3];     /* towards the arc's centre */
	double radius;   /* m, 0 for a straight */
};

struct turtle {
	double p[3], t[3], u[3]; /* u: the last bend's direction */
	double s;
	struct piece piece[MAX_PIECES];
	int pieces;
};

static void straight(struct turtle *tu, double len)
{
	struct piece *pc = &tu->piece[tu->pieces++];

	*pc = (struct piece){ .s0 = tu->s, .len = len };
	vec3_copy(pc->p, tu->p);
	vec3_copy(pc->t, tu->t);
	vec3_axpy(tu->p, tu->p, len, tu->t);
	tu->s += len;
}

static void arc(struct turtle *tu, const struct anatomy_bend *b)
{
	struct piece *pc = &tu->piece[tu->pieces++];
	double a = b->angle_rad, r = b->radius_m, t[3];

	vec3_rotate(tu->u, tu->u, tu->t, b->plane_rad);
	*pc = (struct piece){ .s0 = tu->s, .len = a * r, .radius = r };
	vec3_copy(pc->p, tu->p);
	vec3_copy(pc->t, tu->t);
	vec3_copy(pc->n, tu->u);
	vec3_axpy(tu->p, tu->p, r * sin(a), tu->t);
	vec3_axpy(tu->p, tu->p, r * (1 - cos(a)), tu->u);
	vec3_scale(t, tu->t, cos(a));
	vec3_axpy(t, t, sin(a), tu->u);
	vec3_scale(tu->u, tu->u, cos(a));
	vec3_axpy(tu->u, tu->u, -sin(a), tu->t);
	vec3_copy(tu->t, t);
	tu->s += a * r;
}

/* Lays the course: per segment its bends, straights shared around them. */
static void lay_course(const struct anatomy *a, struct turtle *tu)
{
	memset(tu, 0, sizeof(*tu));
	vec3_set(tu->t, 0, 0, 1); /* cranial */
	vec3_set(tu->u, 0, 1, 0); /* anterior */
	for (int k = 0; k < ANATOMY_SEGMENTS; k++) {
		const struct anatomy_segment *sg = &a->seg[k];
		double rest = sg->length_m;

		for (int b = 0; b < sg->bends; b++) {
			rest -= sg->bend[b].angle_rad * sg->bend[b].radius_m;
		}
		rest /= sg->bends + 1;
		for (int b = 0; b < sg->bends; b++) {
			straight(tu, rest);
			arc(tu, &sg->bend[b]);
		}
		straight(tu, rest);
	}
}

static void course_point(const struct turtle *tu, double s, double out[3])
{
	int k = 0;
	const struct piece *pc;
	double x;

	while (k + 1 < tu->pieces && tu->piece[k + 1].s0 <= s) {
		k++;
	}
	pc = &tu->piece[k];
	x = s - pc->s0;
	if (pc->radius == 0) {
		vec3_axpy(out, pc->p, x, pc->t);
		return;
	}
	vec3_axpy(out, pc->p, pc->radius * sin(x / pc->radius), pc->t);
	vec3_axpy(out, out, pc->radius * (1 - cos(x / pc->radius)), pc->n);
}

/* ---------------------------------------------------------------- lumen */

static double smoothstep(double x)
{
	x = fmax(0, fmin(1, x));
	return x * x * (3 - 2 * x);
}

/* A per-segment value blended across the segment boundaries. */
static double blend(const struct anatomy *a, double s, size_t off)
{
	double start = 0;
	double v = *(const double *)((const char *)&a->seg[0] + off);

	for (int k = 1; k < ANATOMY_SEGMENTS; k++) {
		double prev = *(const double *)((const char *)&a->seg[k - 1] +
						off);
		double cur = *(const double *)((const char *)&a->seg[k] + off);
		double w = fmin(BLEND_M, 0.5 * fmin(a->seg[k - 1].length_m,
						    a->seg[k].length_m));

		start += a->seg[k - 1].length_m;
		v += (cur - prev) * smoothstep((s - start + w) / (2 * w));
	}
	return v;
}

/* Distance from S to the nearest fold of sector SECTOR (0..2). */
static double fold_distance(const struct anatomy *a, double s, int sector)
{
	double sp = a->fold_spacing_m;
	double x = fmod(s - sp * sector / 3.0, sp);

	if (x < 0) {
		x += sp;
	}
	return fmin(x, sp - x);
}

/* The cecum's end rounds off as a hemisphere: the radius' factor. */
static double dome(const struct anatomy *a, double s, double radius)
{
	double len = anatomy_length(a);
	double depth = fmin(radius, 0.8 * a->seg[ANATOMY_CECUM].length_m);
	double x = (s - (len - depth)) / depth;

	return x <= 0 ? 1 : sqrt(fmax(0, 1 - x * x));
}

/* What the lumen radius takes from s alone, computed once per ring. */
static void section_at(const struct anatomy *a, double s,
		       struct colon_ring *x)
{
	double r = 0.5 * blend(a, s, offsetof(struct anatomy_segment,
					      diameter_m));

	x->s_m = s;
	x->r_m = r * dome(a, s, r);
	x->taenia = blend(a, s, offsetof(struct anatomy_segment,
					  taenia_depth));
	x->fold = blend(a, s, offsetof(struct anatomy_segment, fold_depth));
}

static double lumen(const struct anatomy *a, const struct colon_ring *x,
		    double s, double theta)
{
	double phi = fmod(theta - a->taenia_angle_rad, 2 * M_PI);
	double c3, g;

	if (phi < 0) {
		phi += 2 * M_PI;
	}
	c3 = cos(3 * phi);
	g = fold_distance(a, s, (int)(phi / (2 * M_PI / 3)) % 3) /
	    a->fold_width_m;
	return x->r_m * (1 - x->taenia * (1 + c3) / 2) *
	       (1 - x->fold * exp(-g * g) * (1 - c3) / 2);
}

double colon_tube_radius(const struct colon *c, size_t sample)
{
	size_t n = centreline_count(c->cl);

	return c->tube[sample < n ? sample : n - 1];
}

double colon_lumen_radius(const struct colon *c, double s_m, double theta_rad)
{
	struct colon_ring x;

	section_at(&c->anatomy, s_m, &x);
	return lumen(&c->anatomy, &x, s_m, theta_rad);
}

void colon_ring_at(const struct colon *c, double s_m, struct colon_ring *out)
{
	section_at(&c->anatomy, s_m, out);
}

double colon_ring_radius(const struct colon *c, const struct colon_ring *ring,
			 double theta_rad)
{
	return lumen(&c->anatomy, ring, ring->s_m, theta_rad);
}

/* ---------------------------------------------------------------- build */

static int check_params(const struct colon_params *p, char *err,
			size_t errsize)
{
	if (!(p->step_m >= 0.0002 && p->step_m <= 0.01) ||
	    p->ring_vertices < 8 || p->ring_vertices > 4096 ||
	    !(p->segment_m >= 0.01 && p->segment_m <= 0.5) ||
	    !(p->contact_radius_m >= 0 && p->contact_radius_m <= 0.02)) {
		snprintf(err, errsize, "colon: step %g m (0.0002..0.01), "
			 "ring of %u vertices (8..4096), segments of %g m "
			 "(0.01..0.5), contact radius %g m (0..0.02): out of "
			 "range", p->step_m, p->ring_vertices, p->segment_m,
			 p->contact_radius_m);
		return -EINVAL;
	}
	return 0;
}

/*
 * The haptics' surface: the mesh as built (before any bow) moved into the
 * lumen by the tip's radius. Where the wall runs along the colon (the
 * tube, its folds, the inside of tight flexures) each ring shrinks towards
 * its centreline sample within the sample's normal plane: rings stay in
 * their planes, so the surface keeps the mesh's guarantee that no two
 * rings cross (mesh.h), which an inset along the vertex normals would break
 * in creases sharper than the radius. In the cecum's cap (the last lumen
 * radius of a generated colon), where the wall faces along the colon, the
 * vertex moves along its normal instead; the two blend where the normal is
 * between 30 and 45 deg from the tangent. The radial part never exceeds
 * CONTACT_INSET_SHARE of the vertex' distance from the centreline.
 */
#define CONTACT_INSET_SHARE 0.8
#define CAP_FROM 0.5 /* |normal . tangent| where the cap blend starts */
#define CAP_TO 0.7   /* and where it is all normal */

/* The cecum's cap: the last lumen radius of a generated colon. */
static bool in_cap(const struct colon *c, uint32_t sample)
{
	double s = (double)sample * centreline_step(c->cl);
	double r = c->anatomy.seg[ANATOMY_CECUM].diameter_m / 2;

	return c->generated && s > centreline_length(c->cl) - r;
}

static void inset_vertex(const struct colon *c, uint32_t v, double radius_m,
			 float out[3])
{
	const struct mesh *m = c->mesh;
	const struct centreline_point *q = centreline_base(c->cl, m->sample[v]);
	double d[3], w[3], n[3], rho, cap = 0;

	vec3_set(d, m->pos[v][0] - q->p[0], m->pos[v][1] - q->p[1],
		 m->pos[v][2] - q->p[2]);
	vec3_set(n, m->nrm[v][0], m->nrm[v][1], m->nrm[v][2]);
	vec3_axpy(w, d, -vec3_dot(d, q->t), q->t);
	rho = vec3_normalize(w);
	if (in_cap(c, m->sample[v])) {
		cap = fmin(fmax((fabs(vec3_dot(n, q->t)) - CAP_FROM) /
				(CAP_TO - CAP_FROM), 0), 1);
	}
	vec3_axpy(d, d, -(1 - cap) * fmin(radius_m, CONTACT_INSET_SHARE * rho),
		  w);
	vec3_axpy(d, d, cap * radius_m, n);
	for (int k = 0; k < 3; k++) {
		out[k] = (float)(q->p[k] + d[k]);
	}
}

/*
 * The lumen's radius that the insertion tube meets along the colon: per
 * sample, the mean distance of its vertices from the centreline in the
 * sample's normal plane (a ring's mean, folds and taeniae included),
 * samples without vertices taking their neighbour's, then averaged over
 * TUBE_WINDOW_M either way (a tube slides over the folds, it does not
 * ride each one).
 */
#define TUBE_WINDOW_M 0.015

static int make_tube(struct colon *c, char *err, size_t errsize)
{
	const struct mesh *m = c->mesh;
	size_t n = centreline_count(c->cl), w;
	double *r = calloc(n, sizeof(*r)), last = NAN;

	c->tube = malloc(n * sizeof(*c->tube));
	if (!r || !c->tube) {
		free(r);
		snprintf(err, errsize, "%s: out of memory", c->name);
		return -ENOMEM;
	}
	for (size_t i = 0; i < n; i++) {
		uint32_t a = m->sample_first[i], b = m->sample_first[i + 1];

		r[i] = NAN;
		for (uint32_t v = a; v < b; v++) {
			r[i] = (v == a ? 0 : r[i]) +
			       hypot(m->off[v][1], m->off[v][2]) / (b - a);
		}
	}
	for (size_t i = 0; i < n; i++) { /* gaps: the last radius seen */
		r[i] = isnan(r[i]) ? last : r[i];
		last = r[i];
	}
	for (size_t i = n; i-- > 0;) { /* a gap at the start: the next */
		r[i] = isnan(r[i]) ? last : r[i];
		last = r[i];
	}
	w = (size_t)(TUBE_WINDOW_M / centreline_step(c->cl));
	for (size_t i = 0; i < n; i++) {
		size_t lo = i > w ? i - w : 0, hi = i + w < n ? i + w : n - 1;
		double sum = 0;

		for (size_t k = lo; k <= hi; k++) {
			sum += r[k];
		}
		c->tube[i] = (float)(isfinite(sum) ? sum / (double)(hi - lo + 1)
						   : 0.01);
	}
	free(r);
	return 0;
}

static int make_contact(struct colon *c, double radius_m, char *err,
			size_t errsize)
{
	const struct mesh *m = c->mesh;
	float (*pos)[3] = malloc(m->vertices * sizeof(*pos));

	if (pos) {
		for (uint32_t v = 0; v < m->vertices; v++) {
			inset_vertex(c, v, radius_m, pos[v]);
		}
		c->contact = contact_create((const float(*)[3])pos,
					    (const float(*)[3])m->nrm,
					    m->vertices,
					    (const uint32_t(*)[3])m->tri,
					    m->triangles, m->seg, m->segments);
		free(pos);
	}
	if (!c->contact) {
		snprintf(err, errsize, "%s: out of memory for the contact "
			 "surface", c->name);
		return -ENOMEM;
	}
	return 0;
}

/* The samples of the course, every length / steps. */
static double (*sample_course(const struct anatomy *a, double step_m,
			      size_t *n, double *ds))[3]
{
	struct turtle *tu = malloc(sizeof(*tu));
	double len = anatomy_length(a), (*pts)[3];
	size_t steps = (size_t)fmax(CENTRELINE_MIN_SAMPLES, round(len / step_m));

	pts = tu ? malloc((steps + 1) * sizeof(*pts)) : NULL;
	if (!pts) {
		free(tu);
		return NULL;
	}
	lay_course(a, tu);
	*ds = len / (double)steps;
	*n = steps + 1;
	for (size_t i = 0; i <= steps; i++) {
		course_point(tu, (double)i * *ds, pts[i]);
	}
	free(tu);
	return pts;
}

/* Rings at every sample but the last, which is the cecum's pole. */
static void make_rings(struct colon *c, uint32_t ring)
{
	struct mesh *m = c->mesh;
	size_t n = m->samples;
	double ds = centreline_step(c->cl);
	uint32_t v = 0, k = 0;

	for (size_t i = 0; i + 1 < n; i++) {
		struct colon_ring x;

		section_at(&c->anatomy, (double)i * ds, &x);
		for (uint32_t j = 0; j < ring; j++, v++) {
			double th = 2 * M_PI * j / ring;
			double r = lumen(&c->anatomy, &x, (double)i * ds, th);

			m->sample[v] = (uint32_t)i;
			m->off[v][0] = 0;
			m->off[v][1] = (float)(r * cos(th));
			m->off[v][2] = (float)(r * sin(th));
		}
	}
	m->sample[v] = (uint32_t)(n - 1); /* the pole, on the centreline */
	for (uint32_t i = 0; i + 2 < n; i++) {
		for (uint32_t j = 0; j < ring; j++) {
			uint32_t a = i * ring + j, b = a + ring;
			uint32_t cc = i * ring + (j + 1) % ring, d = cc + ring;

			memcpy(m->tri[k++], (uint32_t[3]){ a, b, cc },
			       sizeof(*m->tri));
			memcpy(m->tri[k++], (uint32_t[3]){ b, d, cc },
			       sizeof(*m->tri));
		}
	}
	for (uint32_t j = 0; j < ring; j++) {
		uint32_t base = (uint32_t)(n - 2) * ring;

		memcpy(m->tri[k++],
		       (uint32_t[3]){ base + j, v, base + (j + 1) % ring },
		       sizeof(*m->tri));
	}
}

/* The anatomy's segments as regions; the mobile ones become spans. */
static int make_regions(struct colon *c, char *err, size_t errsize)
{
	double range[CENTRELINE_MAX_SPANS][2];
	int spans = 0;

	for (int k = 0; k < ANATOMY_SEGMENTS; k++) {
		const struct anatomy_segment *sg = &c->anatomy.seg[k];
		struct colon_region *rg = &c->region[k];

		snprintf(rg->name, sizeof(rg->name), "%s",
			 anatomy_segment_name(k));
		rg->s0_m = anatomy_segment_start(&c->anatomy, k);
		rg->s1_m = rg->s0_m + sg->length_m;
		rg->diameter_m = sg->diameter_m;
		rg->span = -1;
		if (sg->mobile && spans < CENTRELINE_MAX_SPANS) {
			rg->span = spans;
			rg->mesentery_n_per_m = sg->mesentery_n_per_m;
			rg->max_bow_m = sg->mesentery_height_m;
			range[spans][0] = rg->s0_m;
			range[spans++][1] = rg->s1_m;
		}
	}
	c->regions = ANATOMY_SEGMENTS;
	c->cecum_s = c->region[ANATOMY_CECUM].s0_m;
	if (centreline_set_spans(c->cl, range, spans)) {
		snprintf(err, errsize, "%s: mobile segments too short or too "
			 "close for a step of %g m", c->name,
			 centreline_step(c->cl));
		return -EINVAL;
	}
	return 0;
}

struct colon *colon_create(const struct anatomy *a,
			   const struct colon_params *p, char *err,
			   size_t errsize)
{
	const double anterior[3] = { 0, 1, 0 };
	double (*pts)[3], ds;
	struct colon *c;
	size_t n;
	double tris;

	if (check_params(p, err, errsize)) {
		return NULL;
	}
	c = calloc(1, sizeof(*c));
	pts = c ? sample_course(a, p->step_m, &n, &ds) : NULL;
	if (!pts) {
		snprintf(err, errsize, "%s: out of memory", a->name);
		free(c);
		return NULL;
	}
	c->anatomy = *a;
	c->generated = true;
	snprintf(c->name, sizeof(c->name), "%s", a->name);
	tris = (2.0 * (double)(n - 2) + 1) * p->ring_vertices;
	c->cl = centreline_create((const double(*)[3])pts, n, ds, anterior,
				  err, errsize);
	free(pts);
	if (!c->cl || make_regions(c, err, errsize)) {
		goto fail;
	}
	if (tris >= UINT32_MAX / 2) {
		snprintf(err, errsize, "%s: %.0f triangles are too many",
			 c->name, tris);
		goto fail;
	}
	c->mesh = mesh_create((uint32_t)(n - 1) * p->ring_vertices + 1,
			      (uint32_t)tris, n);
	if (!c->mesh) {
		snprintf(err, errsize, "%s: out of memory for %.0f triangles",
			 c->name, tris);
		goto fail;
	}
	make_rings(c, p->ring_vertices);
	if (mesh_finish(c->mesh, c->cl, p->segment_m, MESH_FROM_OFFSETS, err,
			errsize) ||
	    make_contact(c, p->contact_radius_m, err, errsize) ||
	    make_tube(c, err, errsize)) {
		goto fail;
	}
	return c;

fail:
	colon_destroy(c);
	return NULL;
}

void colon_destroy(struct colon *c)
{
	if (!c) {
		return;
	}
	contact_destroy(c->contact);
	free(c->tube);
	mesh_destroy(c->mesh);
	centreline_destroy(c->cl);
	free(c);
}

/* ---------------------------------------------------------------- import */

/* The import's centreline: from its own file, or the OBJ's polyline. */
static int import_points(const char *obj_path, const char *cl_path,
			 const struct objio_data *d, double (**pts)[3],
			 size_t *n, char *err, size_t errsize)
{
	if (cl_path) {
		return objio_read_points(cl_path, pts, n, err, errsize);
	}
	if (d->nline < CENTRELINE_MIN_SAMPLES) {
		snprintf(err, errsize, "%s: no centreline: %zu polyline points "
			 "('l'), need %d or a centreline file", obj_path,
			 d->nline, CENTRELINE_MIN_SAMPLES);
		return -EINVAL;
	}
	*pts = malloc(d->nline * sizeof(**pts));
	if (!*pts) {
		snprintf(err, errsize, "%s: out of memory", obj_path);
		return -ENOMEM;
	}
	for (size_t i = 0; i < d->nline; i++) {
		vec3_copy((*pts)[i], d->v[d->line[i]]);
	}
	*n = d->nline;
	return 0;
}

static int make_centreline(struct colon *c, double (*pts)[3], size_t n,
			   const char *where, double step_m, char *err,
			   size_t errsize)
{
	double (*even)[3], ds;
	size_t m;
	char why[160];

	for (size_t i = 0; i < n; i++) {
		if (fabs(pts[i][0]) > 10 || fabs(pts[i][1]) > 10 ||
		    fabs(pts[i][2]) > 10) {
			snprintf(err, errsize, "%s: point %zu lies %g m away: "
				 "coordinates must be in metres", where, i + 1,
				 vec3_norm(pts[i]));
			return -EINVAL;
		}
	}
	even = centreline_resample((const double(*)[3])pts, n, step_m, &m, &ds);
	if (!even) {
		snprintf(err, errsize, "%s: centreline shorter than %d steps "
			 "of %g m", where, CENTRELINE_MIN_SAMPLES, step_m);
		return -EINVAL;
	}
	c->cl = centreline_create((const double(*)[3])even, m, ds, NULL, why,
				  sizeof(why));
	free(even);
	if (!c->cl) {
		snprintf(err, errsize, "%s: %s", where, why);
		return -EINVAL;
	}
	return 0;
}

/* The faces' vertices only (the polyline's stay out), renumbered. */
static int make_import_mesh(struct colon *c, const struct objio_data *d,
			    const char *path, double segment_m, char *err,
			    size_t errsize)
{
	uint32_t *map = malloc(d->nv * sizeof(*map)), used = 0;
	char why[160];
	int r;

	if (!map) {
		snprintf(err, errsize, "%s: out of memory", path);
		return -ENOMEM;
	}
	memset(map, 0xff, d->nv * sizeof(*map));
	for (size_t k = 0; k < d->ntri; k++) {
		for (int j = 0; j < 3; j++) {
			uint32_t *v = &map[d->tri[k][j]];

			*v = *v == UINT32_MAX ? used++ : *v;
		}
	}
	c->mesh = mesh_create(used, (uint32_t)d->ntri, centreline_count(c->cl));
	if (!c->mesh) {
		free(map);
		snprintf(err, errsize, "%s: out of memory", path);
		return -ENOMEM;
	}
	for (size_t i = 0; i < d->nv; i++) {
		for (int j = 0; map[i] != UINT32_MAX && j < 3; j++) {
			c->mesh->pos[map[i]][j] = (float)d->v[i][j];
		}
	}
	for (size_t k = 0; k < d->ntri; k++) {
		for (int j = 0; j < 3; j++) {
			c->mesh->tri[k][j] = map[d->tri[k][j]];
		}
	}
	free(map);
	r = mesh_finish(c->mesh, c->cl, segment_m, MESH_FROM_POSITIONS, why,
			sizeof(why));
	if (r) {
		snprintf(err, errsize, "%s: %s", path, why);
	}
	return r;
}

static void import_name(struct colon *c, const char *path)
{
	const char *base = strrchr(path, '/');
	size_t len;

	base = base ? base + 1 : path;
	len = strcspn(base, ".");
	snprintf(c->name, sizeof(c->name), "%.*s", (int)len, base);
}

struct colon *colon_import(const char *obj_path, const char *centreline_path,
			   const struct colon_params *p, char *err,
			   size_t errsize)
{
	struct objio_data d;
	double (*pts)[3] = NULL;
	struct colon *c;
	size_t n;

	if (check_params(p, err, errsize) ||
	    objio_read(obj_path, &d, err, errsize)) {
		return NULL;
	}
	c = calloc(1, sizeof(*c));
	if (!c) {
		snprintf(err, errsize, "%s: out of memory", obj_path);
		goto free_data;
	}
	import_name(c, obj_path);
	if (import_points(obj_path, centreline_path, &d, &pts, &n, err,
			  errsize) ||
	    make_centreline(c, pts, n, centreline_path ? centreline_path
						       : obj_path,
			    p->step_m, err, errsize) ||
	    make_import_mesh(c, &d, obj_path, p->segment_m, err, errsize) ||
	    make_contact(c, p->contact_radius_m, err, errsize) ||
	    make_tube(c, err, errsize)) {
		goto free_colon;
	}
	free(pts);
	objio_free(&d);
	c->regions = 1;
	snprintf(c->region[0].name, sizeof(c->region[0].name), "colon");
	c->region[0].s1_m = c->cecum_s = centreline_length(c->cl);
	c->region[0].span = -1;
	return c;

free_colon:
	free(pts);
	colon_destroy(c);
free_data:
	objio_free(&d);
	return NULL;
}

/* ---------------------------------------------------------------- use */

int colon_export(const struct colon *c, const char *path, char *err,
		 size_t errsize)
{
	size_t n = centreline_count(c->cl);
	double (*line)[3] = malloc(n * sizeof(*line));
	struct objio_mesh m = {
		.name = c->name, .pos = (const float(*)[3])c->mesh->pos,
		.nrm = (const float(*)[3])c->mesh->nrm,
		.vertices = c->mesh->vertices,
		.tri = (const uint32_t(*)[3])c->mesh->tri,
		.triangles = c->mesh->triangles, .samples = n,
		.step_m = centreline_step(c->cl),
	};
	int r;

	if (!line) {
		snprintf(err, errsize, "%s: out of memory", path);
		return -ENOMEM;
	}
	for (size_t i = 0; i < n; i++) {
		vec3_copy(line[i], centreline_sample(c->cl, i)->p);
	}
	m.centreline = (const double(*)[3])line;
	r = objio_write(path, &m, err, errsize);
	free(line);
	return r;
}

const char *colon_name(const struct colon *c)
{
	return c->name;
}

const struct anatomy *colon_anatomy(const struct colon *c)
{
	return c->generated ? &c->anatomy : NULL;
}

struct centreline *colon_centreline(const struct colon *c)
{
	return c->cl;
}

const struct contact *colon_contact(const struct colon *c)
{
	return c->contact;
}

struct mesh *colon_mesh(const struct colon *c)
{
	return c->mesh;
}

int colon_regions(const struct colon *c)
{
	return c->regions;
}

const struct colon_region *colon_region(const struct colon *c, int i)
{
	return &c->region[i];
}

int colon_region_at(const struct colon *c, double s_m)
{
	int i = 0;

	while (i + 1 < c->regions && s_m >= c->region[i].s1_m) {
		i++;
	}
	return i;
}

double colon_cecum_s(const struct colon *c)
{
	return c->cecum_s;
}

int colon_bow(struct colon *c, int span, double amplitude_m, bool place_mesh)
{
	double s0, s1, ds = centreline_step(c->cl);
	int r = centreline_bow(c->cl, span, amplitude_m);

	if (r || !place_mesh) {
		return r;
	}
	centreline_span_range(c->cl, span, &s0, &s1);
	mesh_place(c->mesh, c->cl, (size_t)lround(s0 / ds),
		   (size_t)lround(s1 / ds));
	return 0;
}

size_t colon_bytes(const struct colon *c)
{
	return sizeof(*c) + mesh_bytes(c->mesh) + centreline_bytes(c->cl) +
	       contact_bytes(c->contact);
}
