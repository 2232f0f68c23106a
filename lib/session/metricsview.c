/*
 * metricsview.c - the metrics' view (metricsview.h; for people:
 * docs/METRICS.md):
 *
 *   lumen lost       while inserted, the time of records where the
 *                    centreline point METRICS_LOOKAHEAD_M beyond tip_s (on
 *                    the bowed centreline, clamped to the cecum's pole) is
 *                    further than lumen_angle_rad off dir, or the tip
 *                    presses into a wall facing it (contact, normal . dir
 *                    < -cos 45 deg)
 *   mucosa seen      each vertex carries a third of the area of its
 *                    triangles; a vertex is in view at an evaluated pose
 *                    when it lies within view_distance_m of the tip,
 *                    within fov_rad / 2 of dir, its normal faces the tip
 *                    and no wall is in front of it (the depth test,
 *                    depthmap.h); it is seen once in view for
 *                    seen_dwell_s in all (each evaluation in view counts
 *                    1 / view_rate_hz); the share is the seen vertices'
 *                    area over the whole
 *   polyps seen      a polyp's centre (its wall point lifted by its radius
 *                    along the wall's normal) within view_distance_m plus
 *                    its radius, within fov_rad / 2 of dir, on the lumen's
 *                    side of the wall, not hidden by the wall (the depth
 *                    test), at an evaluated pose: in view; found
 *                    once in view for polyp_dwell_s in all
 *
 * Poses are evaluated (mucosa, polyps) at most view_rate_hz times a second
 * and only while inserted. The published tip is on the bowed centreline;
 * the mesh is kept as offsets in the frames of the undeformed one, so the
 * vertices near tip_s are placed here on a private centreline bowed by the
 * record's bow_m (the daemon's algorithm, centreline_bow()).
 */
#include "session/metricsview.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"
#include "session/depthmap.h"

#define REDOUT_COS 0.7071067811865476 /* the wall within 45 deg of head-on */
#define POLE_GAP_M 0.01 /* nearer the lumen point than this: at the pole */
#define BOW_STEP_M 1e-4 /* rebow the private centreline beyond this */

struct metricsview {
	struct metrics_params p;
	struct centreline *cl;    /* private: bowed by the records' bow_m */
	const struct mesh *mesh;  /* the colon's: offsets only */
	float *area;              /* per vertex: a third of its triangles' */
	unsigned char *seen;      /* per vertex */
	float *dwell;             /* per vertex: in view so long, s */
	double polyp_dwell[ANATOMY_MAX_POLYPS]; /* s in view */
	double total_area, seen_area;
	double reach_m;           /* samples this far from tip_s are tested */
	int polyps;
	uint32_t polyp_vertex[ANATOMY_MAX_POLYPS];
	double polyp_r[ANATOMY_MAX_POLYPS];
	double next_s;            /* time of the next evaluation */
	uint32_t found;           /* the polyps found: bit k the case's k */
	/* the occlusion test: the wall near the camera drawn into depth */
	struct depthmap *depth;
	float (*cam)[3];          /* per vertex: camera coordinates, ... */
	float (*img)[3];          /* ... their projection, ... */
	uint32_t *stamp;          /* ... valid when stamp == evaluation */
	unsigned char *candidate; /* ... not seen yet but in view */
	uint32_t evaluation;
	/* the unseen-mucosa map's cells (metrics_map()), kept as it goes */
	uint16_t *cell;           /* per vertex: i * METRICS_MAP_A + k */
	float cell_area[METRICS_MAP_S * METRICS_MAP_A];
	float cell_seen[METRICS_MAP_S * METRICS_MAP_A];
};


/* ---------------------------------------------------------------- view */

/* Vertex V's offset placed in the frame of CL's sample. */
static void vertex_place(const struct mesh *me, const struct centreline *cl,
			 uint32_t v, double p[3], double n[3])
{
	const struct centreline_point *c = centreline_sample(cl, me->sample[v]);

	vec3_copy(p, c->p);
	vec3_axpy(p, p, me->off[v][0], c->t);
	vec3_axpy(p, p, me->off[v][1], c->u);
	vec3_axpy(p, p, me->off[v][2], c->v);
	if (n) {
		vec3_scale(n, c->t, me->noff[v][0]);
		vec3_axpy(n, n, me->noff[v][1], c->u);
		vec3_axpy(n, n, me->noff[v][2], c->v);
	}
}

/* Each vertex' share of the area, on the undeformed colon; the reach. */
static void view_areas(struct metricsview *w)
{
	const struct mesh *me = w->mesh;
	double rho = 0;

	for (uint32_t k = 0; k < me->triangles; k++) {
		double a[3], b[3], c[3], x[3];

		vertex_place(me, w->cl, me->tri[k][0], a, NULL);
		vertex_place(me, w->cl, me->tri[k][1], b, NULL);
		vertex_place(me, w->cl, me->tri[k][2], c, NULL);
		vec3_sub(b, b, a);
		vec3_sub(c, c, a);
		vec3_cross(x, b, c);
		for (int j = 0; j < 3; j++) {
			w->area[me->tri[k][j]] += (float)(vec3_norm(x) / 6);
		}
		w->total_area += vec3_norm(x) / 2;
	}
	for (uint32_t v = 0; v < me->vertices; v++) {
		double o = hypot(hypot(me->off[v][0], me->off[v][1]),
				 me->off[v][2]);

		rho = fmax(rho, o);
	}
	w->reach_m = rho;
}

/* Each vertex' cell of the map (by its place along the colon and its
 * angle around the centreline from the frame's u, as the case's polyps
 * are placed) and each cell's area. */
static void view_cells(struct metricsview *w)
{
	const struct mesh *me = w->mesh;
	double step = centreline_step(w->cl);
	double length = (double)(me->samples - 1) * step;

	for (uint32_t v = 0; v < me->vertices; v++) {
		double a = atan2(me->off[v][2], me->off[v][1]);
		long i = lround(floor(me->sample[v] * step / length *
				      METRICS_MAP_S));
		long k = lround(floor((a < 0 ? a + 2 * M_PI : a) /
				      (2 * M_PI) * METRICS_MAP_A));

		i = i < 0 ? 0 : i >= METRICS_MAP_S ? METRICS_MAP_S - 1 : i;
		k = k < 0 ? 0 : k >= METRICS_MAP_A ? METRICS_MAP_A - 1 : k;
		w->cell[v] = (uint16_t)(i * METRICS_MAP_A + k);
		w->cell_area[w->cell[v]] += w->area[v];
	}
}

/* The ring vertex nearest the polyp's angle: where the viewer draws it. */
static uint32_t polyp_vertex(const struct mesh *me, double step,
			     const struct anatomy_polyp *p)
{
	size_t i = (size_t)lround(p->s_m / step);
	uint32_t ring;
	double k;

	i = i + 1 < me->samples ? i : me->samples - 2; /* the pole: no ring */
	ring = me->sample_first[i + 1] - me->sample_first[i];
	k = fmod(p->angle_rad / (2 * M_PI), 1.0);
	k = k < 0 ? k + 1 : k;
	return me->sample_first[i] + (uint32_t)lround(k * ring) % ring;
}

static int view_init(struct metricsview *w, const struct colon *c)
{
	const struct centreline *src = colon_centreline(c);
	const struct anatomy *a = colon_anatomy(c);
	size_t n = centreline_count(src);
	double (*pts)[3], range[CENTRELINE_MAX_SPANS][2];
	char err[128];

	pts = malloc(n * sizeof(*pts));
	if (!pts) {
		return -ENOMEM;
	}
	for (size_t i = 0; i < n; i++) {
		vec3_copy(pts[i], centreline_base(src, i)->p);
	}
	w->cl = centreline_create((const double(*)[3])pts, n,
				  centreline_step(src),
				  centreline_base(src, 0)->u, err, sizeof(err));
	free(pts);
	for (int k = 0; k < centreline_spans(src); k++) {
		centreline_span_range(src, k, &range[k][0], &range[k][1]);
	}
	if (!w->cl || centreline_set_spans(w->cl, (const double(*)[2])range,
					   centreline_spans(src))) {
		return -ENOMEM;
	}
	w->mesh = colon_mesh(c);
	w->area = calloc(w->mesh->vertices, sizeof(*w->area));
	w->seen = calloc(w->mesh->vertices, 1);
	w->dwell = calloc(w->mesh->vertices, sizeof(*w->dwell));
	w->depth = malloc(sizeof(*w->depth));
	w->cam = malloc(w->mesh->vertices * sizeof(*w->cam));
	w->img = malloc(w->mesh->vertices * sizeof(*w->img));
	w->stamp = calloc(w->mesh->vertices, sizeof(*w->stamp));
	w->candidate = malloc(w->mesh->vertices);
	w->cell = malloc(w->mesh->vertices * sizeof(*w->cell));
	if (!w->area || !w->seen || !w->dwell || !w->depth || !w->cam ||
	    !w->img || !w->stamp || !w->candidate || !w->cell) {
		return -ENOMEM;
	}
	view_areas(w);
	view_cells(w);
	for (int k = 0; a && k < a->polyps && k < ANATOMY_MAX_POLYPS; k++) {
		w->polyp_vertex[k] = polyp_vertex(w->mesh, centreline_step(src),
						  &a->polyp[k]);
		w->polyp_r[k] = a->polyp[k].diameter_m / 2;
		w->polyps = k + 1;
	}
	return 0;
}

struct metricsview *metricsview_create(const struct colon *colon,
				       const struct metrics_params *p)
{
	struct metricsview *w = calloc(1, sizeof(*w));

	if (!w) {
		return NULL;
	}
	w->p = *p;
	if (view_init(w, colon)) {
		metricsview_destroy(w);
		return NULL;
	}
	return w;
}

void metricsview_destroy(struct metricsview *w)
{
	if (!w) {
		return;
	}
	centreline_destroy(w->cl);
	free(w->area);
	free(w->seen);
	free(w->dwell);
	free(w->depth);
	free(w->cam);
	free(w->img);
	free(w->stamp);
	free(w->candidate);
	free(w->cell);
	free(w);
}

/* The private centreline bowed as in R. */
static void view_bow(struct metricsview *w, const struct session_record *r)
{
	int spans = centreline_spans(w->cl);

	for (int k = 0; k < spans && k < (int)r->spans &&
			k < ENDOSIM_SPANS; k++) {
		double b = r->bow_m[k];

		if (isfinite(b) &&
		    fabs(b - centreline_bow_amplitude(w->cl, k)) > BOW_STEP_M) {
			centreline_bow(w->cl, k, b);
		}
	}
}

struct pose {
	double tip[3], dir[3];
	double range_m, cos_half;
};

/* X (camera coordinates) in the camera's range and cone. */
static bool pose_sees(const struct pose *c, const float x[3], double range)
{
	double d = sqrt((double)x[0] * x[0] + (double)x[1] * x[1] +
			(double)x[2] * x[2]);

	return d <= range && x[2] >= c->cos_half * d;
}

/*
 * The samples whose rings may be in view at C (within the range of the
 * tip and not wholly behind it, by each ring's largest offset), *I0 to
 * *I1: their vertices in camera coordinates and projected, stamped with
 * this evaluation, and marked candidates when not yet seen, in range and
 * cone and facing the camera (and wanted in the depth buffer). Returns the
 * deepest candidate's z (m; 0: none).
 */
static double view_vertices(struct metricsview *w, const struct pose *c,
			    double tip_s, long *i0, long *i1)
{
	const struct mesh *me = w->mesh;
	double step = centreline_step(w->cl), reach = c->range_m + w->reach_m;
	double deepest = 0;
	long first = lround((tip_s - reach) / step);
	long last = lround((tip_s + reach) / step) + 1;

	first = first < 0 ? 0 : first;
	last = last > (long)me->samples ? (long)me->samples : last;
	*i0 = first;
	*i1 = last;
	w->evaluation++;
	for (long i = first; i < last; i++) {
		double x[3], rho = me->sample_rho[i] + step;

		vec3_sub(x, centreline_sample(w->cl, (size_t)i)->p, c->tip);
		if (vec3_norm(x) > c->range_m + rho ||
		    vec3_dot(x, c->dir) < -rho) {
			continue;
		}
		for (uint32_t v = me->sample_first[i];
		     v < me->sample_first[i + 1]; v++) {
			double p[3], n[3];
			float *cam = w->cam[v];

			vertex_place(me, w->cl, v, p, n);
			vec3_sub(x, p, c->tip);
			depthmap_camera(w->depth, p, cam);
			if (cam[2] >= DEPTHMAP_NEAR_M) {
				depthmap_project(w->depth, cam, w->img[v]);
			}
			w->stamp[v] = w->evaluation;
			w->candidate[v] = !w->seen[v] && vec3_dot(n, x) < 0 &&
					  pose_sees(c, cam, c->range_m);
			if (!w->candidate[v]) {
				continue;
			}
			deepest = fmax(deepest, cam[2]);
			if (cam[2] >= DEPTHMAP_NEAR_M) {
				depthmap_want(w->depth, w->img[v]);
			}
		}
	}
	return deepest;
}

/* The triangles of samples I0..I1 whose corners all have this
 * evaluation's coordinates and one nearer than DEEPEST_M (no other can
 * hide anything in question) into the depth buffer. */
static void view_draw(struct metricsview *w, long i0, long i1, double deepest_m)
{
	const struct mesh *me = w->mesh;
	double step = centreline_step(w->cl);
	float far = (float)(deepest_m * (1 + DEPTHMAP_SLACK));
	uint32_t t0, nt, stamp = w->evaluation;

	mesh_range(me, (double)i0 * step, (double)i1 * step, &t0, &nt);
	for (uint32_t k = t0; k < t0 + nt; k++) {
		const uint32_t *t = me->tri[k];
		const float *const x[3] = { w->cam[t[0]], w->cam[t[1]],
					    w->cam[t[2]] };
		const float *const q[3] = { w->img[t[0]], w->img[t[1]],
					    w->img[t[2]] };

		if (w->stamp[t[0]] == stamp && w->stamp[t[1]] == stamp &&
		    w->stamp[t[2]] == stamp &&
		    (x[0][2] < far || x[1][2] < far || x[2][2] < far)) {
			depthmap_triangle(w->depth, x, q);
		}
	}
}

/* The candidates of samples I0..I1 not hidden: DT_S more of dwell each;
 * seen past DWELL_S. */
static void view_mucosa(struct metricsview *w, long i0, long i1, double dt_s,
			double dwell_s)
{
	const struct mesh *me = w->mesh;

	for (uint32_t v = me->sample_first[i0]; v < me->sample_first[i1];
	     v++) {
		if (w->stamp[v] != w->evaluation || !w->candidate[v] ||
		    !depthmap_visible(w->depth, w->cam[v])) {
			continue;
		}
		if ((w->dwell[v] += (float)dt_s) >= dwell_s - 1e-6) {
			w->seen[v] = 1;
			w->seen_area += w->area[v];
			w->cell_seen[w->cell[v]] += w->area[v];
		}
	}
}

/* The polyps not yet found (MASK: those found) in range and cone at C,
 * on the lumen's side of the wall: their centres' camera coordinates
 * in CAM, their bits returned; *DEEPEST the deepest z. */
static uint32_t view_polyp_candidates(struct metricsview *w,
				      const struct pose *c, uint32_t found,
				      float cam[][3], double *deepest)
{
	uint32_t in_view = 0;

	for (int k = 0; k < w->polyps; k++) {
		double p[3], n[3], x[3];

		if (found & (1u << k)) {
			continue;
		}
		vertex_place(w->mesh, w->cl, w->polyp_vertex[k], p, n);
		vec3_normalize(n);
		vec3_sub(x, p, c->tip);
		if (vec3_dot(n, x) >= 0) {
			continue; /* behind the wall */
		}
		vec3_axpy(p, p, w->polyp_r[k], n);
		depthmap_camera(w->depth, p, cam[k]);
		if (pose_sees(c, cam[k], c->range_m + w->polyp_r[k])) {
			float img[3];

			in_view |= 1u << k;
			*deepest = fmax(*deepest, cam[k][2]);
			if (cam[k][2] >= DEPTHMAP_NEAR_M) {
				depthmap_project(w->depth, cam[k], img);
				depthmap_want(w->depth, img);
			}
		}
	}
	return in_view;
}

/* The polyps IN_VIEW not hidden: DT_S more of dwell each; the mask of
 * those found (in view DWELL_S in all). */
static uint32_t view_polyps(struct metricsview *w, uint32_t in_view,
			    const float cam[][3], double dt_s, double dwell_s)
{
	uint32_t mask = 0;

	for (int k = 0; k < w->polyps; k++) {
		if ((in_view & (1u << k)) &&
		    depthmap_visible(w->depth, cam[k]) &&
		    (w->polyp_dwell[k] += dt_s) >= dwell_s - 1e-6) {
			mask |= 1u << k;
		}
	}
	return mask;
}

static void view_pose(const struct metricsview *w,
		      const struct session_record *r, struct pose *c)
{
	for (int j = 0; j < 3; j++) {
		c->tip[j] = r->tip[j];
		c->dir[j] = r->dir[j];
	}
	vec3_normalize(c->dir);
	c->range_m = w->p.view_distance_m;
	c->cos_half = cos(w->p.fov_rad / 2);
}

void metricsview_record(struct metricsview *w, const struct session_record *r,
			double t)
{
	float polyp_cam[ANATOMY_MAX_POLYPS][3];
	double dt = 1 / w->p.view_rate_hz, deepest;
	uint32_t polyps;
	struct pose c;
	long i0, i1;

	if (t < w->next_s || !isfinite(r->tip_s_m) ||
	    !isfinite(r->tip[0] + r->tip[1] + r->tip[2]) ||
	    !isfinite(r->dir[0] + r->dir[1] + r->dir[2])) {
		return; /* not yet, or no pose to look from */
	}
	w->next_s = t + dt;
	view_bow(w, r);
	view_pose(w, r, &c);
	depthmap_begin(w->depth, c.tip, c.dir, w->p.fov_rad / 2);
	deepest = view_vertices(w, &c, r->tip_s_m, &i0, &i1);
	polyps = view_polyp_candidates(w, &c, w->found, polyp_cam, &deepest);
	if (deepest <= 0) {
		return; /* nothing new in view: nothing to draw */
	}
	view_draw(w, i0, i1, deepest);
	view_mucosa(w, i0, i1, dt, w->p.seen_dwell_s);
	w->found |= view_polyps(w, polyps, polyp_cam, dt, w->p.polyp_dwell_s);
}

/* --------------------------------------------------------------- lumen */

/* The bowed centreline's point at material S_M: the undeformed one moved
 * by each span's A sin^2(pi (s - s0) / (s1 - s0)) e (centreline.h). */
static void bowed_point(const struct metricsview *v,
			const struct session_record *r, double s_m,
			double out[3])
{
	const struct centreline *cl = v->cl;
	struct centreline_point q;

	centreline_at_s(cl, s_m, &q); /* the private copy; see below */
	vec3_copy(out, q.p);
	for (int k = 0; k < centreline_spans(cl) && k < (int)r->spans &&
			k < ENDOSIM_SPANS; k++) {
		double s0, s1, e[3], w, b = r->bow_m[k];

		centreline_span_range(cl, k, &s0, &s1);
		if (s_m <= s0 || s_m >= s1 || !isfinite(b)) {
			continue;
		}
		w = sin(M_PI * (s_m - s0) / (s1 - s0));
		centreline_bow_direction(cl, k, e);
		/* the private copy is bowed by its own amplitude: replace */
		vec3_axpy(out, out, (b - centreline_bow_amplitude(cl, k)) * w * w,
			  e);
	}
}

bool metricsview_lumen_lost(const struct metricsview *v,
			    const struct session_record *r)
{
	double s = fmin(r->tip_s_m + METRICS_LOOKAHEAD_M,
			centreline_length(v->cl));
	double a[3], x[3], dir[3], d;

	if (r->contact) {
		double n[3] = { r->normal[0], r->normal[1], r->normal[2] };

		for (int j = 0; j < 3; j++) {
			dir[j] = r->dir[j];
		}
		if (vec3_dot(n, dir) < -REDOUT_COS * vec3_norm(dir) * vec3_norm(n)) {
			return true;
		}
	}
	bowed_point(v, r, s, a);
	for (int j = 0; j < 3; j++) {
		x[j] = a[j] - r->tip[j];
		dir[j] = r->dir[j];
	}
	d = vec3_norm(x);
	if (d < POLE_GAP_M) {
		return false;
	}
	return vec3_dot(x, dir) < cos(v->p.lumen_angle_rad) * d * vec3_norm(dir);
}

/* -------------------------------------------------------------- results */

double metricsview_seen(const struct metricsview *w)
{
	return w && w->total_area > 0 ? w->seen_area / w->total_area : 0;
}

uint32_t metricsview_found(const struct metricsview *w)
{
	return w ? w->found : 0;
}

int metricsview_polyps(const struct metricsview *w)
{
	return w ? w->polyps : 0;
}

double metricsview_seen_in(const struct metricsview *w, double s0_m,
			   double s1_m, double a0_rad, double a1_rad)
{
	const struct mesh *me;
	bool all_around = a0_rad <= 0 && a1_rad >= 2 * M_PI;
	double step, seen = 0, all = 0;

	if (!w) {
		return 0;
	}
	me = w->mesh;
	step = centreline_step(w->cl);
	for (size_t i = 0; i < me->samples; i++) { /* vertices by sample */
		double s = (double)i * step;

		if (s < s0_m || s > s1_m) {
			continue;
		}
		for (uint32_t v = me->sample_first[i];
		     v < me->sample_first[i + 1]; v++) {
			double a = all_around ? 0 : atan2(me->off[v][2],
							  me->off[v][1]);

			a = a < 0 ? a + 2 * M_PI : a;
			if (a >= a0_rad && a <= a1_rad) {
				all += w->area[v];
				seen += w->seen[v] ? w->area[v] : 0;
			}
		}
	}
	return all > 0 ? seen / all : 0;
}

void metricsview_map(const struct metricsview *w, struct metrics_map *out)
{
	out->length_m = w ? (double)(w->mesh->samples - 1) *
			    centreline_step(w->cl) : 0;
	for (int i = 0; i < METRICS_MAP_S; i++) {
		for (int k = 0; k < METRICS_MAP_A; k++) {
			int c = i * METRICS_MAP_A + k;

			out->seen[i][k] = w && w->cell_area[c] > 0 ?
					  w->cell_seen[c] / w->cell_area[c] :
					  -1;
		}
	}
}
