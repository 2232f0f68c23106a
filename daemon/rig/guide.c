/* guide.c - see guide.h. */
#include "rig/guide.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rig/scenario.h"
#include "proto/session_file.h"

#define GUIDE_ROTARY_M 0.01   /* nearest point: a radian counts as 1 cm */
#define GUIDE_MOVE_MIN_S 0.05 /* the shortest move */
#define GUIDE_SPEED_MIN 0.25  /* x the recording */
#define GUIDE_SPEED_MAX 2.0

/* --- the path ---------------------------------------------------------- */

static struct guide_path *path_alloc(size_t n)
{
	struct guide_path *p = calloc(1, sizeof(*p));

	if (!p) {
		return NULL;
	}
	p->n = n;
	p->q = calloc(n, sizeof(*p->q));
	p->tip_s_m = calloc(n, sizeof(*p->tip_s_m));
	p->patient = calloc(n, sizeof(*p->patient));
	p->tool = calloc(n, sizeof(*p->tool));
	if (!p->q || !p->tip_s_m || !p->patient || !p->tool) {
		guide_path_free(p);
		return NULL;
	}
	return p;
}

/* The session's enabled part, [*first, *last] of its records: false if
 * it has none. */
static bool enabled_part(const struct session_file *f, size_t *first,
			 size_t *last)
{
	bool any = false;

	for (size_t i = 0; i < f->n_records; i++) {
		if (f->records[i].state != ENDOSIM_STATE_ENABLED) {
			continue;
		}
		if (!any) {
			*first = i;
			any = true;
		}
		*last = i;
	}
	return any;
}

/*
 * The path of a scenario (scenario.h): where its hand's targets put each
 * axis, sampled; an axis the hand pushes or lets go keeps its last
 * target. NULL with ERR when it is not one, or has no target.
 */
static struct guide_path *scenario_path(const char *file, char *err,
					size_t errsize)
{
	char why[256];
	struct scenario *scn = scenario_load(file, why, sizeof(why));
	struct guide_path *p = NULL;
	double len, q[ENDOSIM_AXES] = { 0 };
	bool any = false;
	size_t n;

	if (!scn) {
		snprintf(err, errsize, "%s: not a session file, nor a scenario "
			 "(%s)", file, why);
		return NULL;
	}
	len = scenario_length(scn);
	n = (size_t)(len * GUIDE_PATH_HZ) + 1;
	if (n < 2 || !(p = path_alloc(n))) {
		snprintf(err, errsize, "%s: %s", file, n < 2 ?
			 "a scenario too short to guide along" :
			 "out of memory");
		scenario_destroy(scn);
		return NULL;
	}
	for (size_t k = 0; k < n; k++) {
		struct scenario_cmd c[ENDOSIM_AXES];

		scenario_eval(scn, (double)k / GUIDE_PATH_HZ, c);
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			if (c[a].mode == SCENARIO_TARGET) {
				q[a] = c[a].value;
				any = true;
			}
			p->q[k][a] = (float)q[a];
		}
	}
	scenario_destroy(scn);
	free(p->patient); /* a scenario's commands stay its own */
	p->patient = NULL;
	free(p->tool);    /* ... and it holds no tool */
	p->tool = NULL;
	if (!any) {
		snprintf(err, errsize, "%s: a scenario without a target: "
			 "nothing to guide along", file);
		guide_path_free(p);
		return NULL;
	}
	return p;
}

/* Record R's patient as a path's sample holds it; whether it had one. */
static bool patient_of(const struct session_record *r,
		       struct guide_patient *out)
{
	*out = (struct guide_patient){
		.valves = r->valves, .position = (int32_t)r->patient_position,
		.hand_site = r->hand_site, .hand_n = r->hand_n,
	};
	return r->patient;
}

/* Record R's tool as a path's sample holds it; whether it had one. */
static bool tool_of(const struct session_record *r, struct guide_tool *out)
{
	*out = (struct guide_tool){
		.kind = (int32_t)r->tool_kind, .captured = r->tool_captured,
		.snare_m = r->tool_snare_m, .depth_m = r->tool_depth_m,
		.opening = r->tool_opening, .pedal = r->tool_pedal,
	};
	return r->tool_kind != ENDOSIM_TOOL_NONE;
}

/* A session file begins with its magic; anything else may be a
 * scenario. */
static bool is_session(const char *file)
{
	char magic[sizeof(SESSION_FILE_MAGIC) - 1];
	FILE *f = fopen(file, "rb");
	bool yes = f && fread(magic, 1, sizeof(magic), f) == sizeof(magic) &&
		   !memcmp(magic, SESSION_FILE_MAGIC, sizeof(magic));

	if (f) {
		fclose(f);
	}
	return yes;
}

struct guide_path *guide_path_load(const char *file, char *err,
				   size_t errsize)
{
	struct session_file f = { 0 };
	struct guide_path *p = NULL;
	char id[32] = "";
	size_t first = 0, last = 0, n, r;
	uint64_t t0, span, step = (uint64_t)(ENDOSIM_NS_PER_S / GUIDE_PATH_HZ);
	bool patient = false, tool = false;
	int e;

	if (!is_session(file) && access(file, R_OK) == 0) {
		return scenario_path(file, err, errsize);
	}
	e = session_file_read(file, &f);
	if (e) {
		snprintf(err, errsize, "%s: %s", file,
			 e == -EBADMSG ? "not a session file" :
			 e == -EPROTO ? "its records are damaged" :
			 strerror(-e));
		return NULL;
	}
	if (!enabled_part(&f, &first, &last)) {
		snprintf(err, errsize, "%s: no record with the rig enabled: "
			 "nothing to guide along", file);
		goto out;
	}
	t0 = f.records[first].stamp_ns;
	span = f.records[last].stamp_ns - t0;
	n = (size_t)(span / step) + 1;
	if (n < 2) {
		snprintf(err, errsize, "%s: its enabled part is too short to "
			 "guide along (%.3f s)", file, span * ENDOSIM_S_PER_NS);
		goto out;
	}
	p = path_alloc(n);
	if (!p) {
		snprintf(err, errsize, "%s: out of memory", file);
		goto out;
	}
	r = first;
	for (size_t k = 0; k < n; k++) {
		uint64_t t = t0 + k * step;

		while (r < last && f.records[r + 1].stamp_ns <= t) {
			r++;
		}
		memcpy(p->q[k], f.records[r].position, sizeof(p->q[k]));
		p->tip_s_m[k] = f.records[r].tip_s_m;
		patient |= patient_of(&f.records[r], &p->patient[k]);
		tool |= tool_of(&f.records[r], &p->tool[k]);
	}
	if (!patient) {
		free(p->patient);
		p->patient = NULL;
	}
	if (!tool) {
		free(p->tool);
		p->tool = NULL;
	}
	session_text_get(f.header, "id", id, sizeof(id));
	p->source_id = strtoull(id, NULL, 10);
	session_text_get(f.header, "case", p->case_name,
			 sizeof(p->case_name));
out:
	session_file_close(&f);
	return p;
}

void guide_path_free(struct guide_path *p)
{
	if (!p) {
		return;
	}
	free(p->q);
	free(p->tip_s_m);
	free(p->patient);
	free(p->tool);
	free(p);
}

double guide_path_length_s(const struct guide_path *p)
{
	return (double)(p->n - 1) / GUIDE_PATH_HZ;
}

/* Sample I's tangent (per sample): central, one-sided at the ends. */
static double tangent(const struct guide_path *p, size_t i, int a)
{
	size_t lo = i > 0 ? i - 1 : i, hi = i + 1 < p->n ? i + 1 : i;

	return ((double)p->q[hi][a] - p->q[lo][a]) / (double)(hi - lo);
}

void guide_path_at(const struct guide_path *p, double t_s,
		   double q[ENDOSIM_AXES], double dq[ENDOSIM_AXES])
{
	double x = t_s * GUIDE_PATH_HZ, u;
	size_t i;

	if (!(x > 0)) {
		x = 0;
	}
	if (x >= (double)(p->n - 1)) {
		x = (double)(p->n - 1);
	}
	i = (size_t)x;
	if (i >= p->n - 1) {
		i = p->n - 2;
	}
	u = x - (double)i;
	/* a cubic Hermite segment: positions and speeds continuous */
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		double p0 = p->q[i][a], p1 = p->q[i + 1][a];
		double m0 = tangent(p, i, a), m1 = tangent(p, i + 1, a);
		double u2 = u * u, u3 = u2 * u;

		q[a] = (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 +
		       (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1;
		dq[a] = ((6 * u2 - 6 * u) * p0 + (3 * u2 - 4 * u + 1) * m0 +
			 (-6 * u2 + 6 * u) * p1 + (3 * u2 - 2 * u) * m1) *
			GUIDE_PATH_HZ;
	}
}

/* An axis' difference in metres: rotary ones by GUIDE_ROTARY_M a rad. */
static double metres(int a, double d)
{
	return a == ENDOSIM_AXIS_INSERTION ? d : d * GUIDE_ROTARY_M;
}

double guide_path_nearest(const struct guide_path *p,
			  const double q[ENDOSIM_AXES])
{
	double best = INFINITY;
	size_t at = 0;

	for (size_t i = 0; i < p->n; i++) {
		double d2 = 0;

		for (int a = 0; a < ENDOSIM_AXES; a++) {
			double d = metres(a, q[a] - p->q[i][a]);

			d2 += d * d;
		}
		if (d2 < best) {
			best = d2;
			at = i;
		}
	}
	return (double)at / GUIDE_PATH_HZ;
}

/* --- the controller ---------------------------------------------------- */

void guide_init(struct guide *g)
{
	memset(g, 0, sizeof(*g));
	g->phase = ENDOSIM_GUIDE_OFF;
	g->lost_axis = -1;
}

/* From Q to the path at T_S, then NEXT. */
static void begin_move(struct guide *g, const struct config_guide *p,
		       const double q[ENDOSIM_AXES], double t_s, uint32_t next)
{
	double dq[ENDOSIM_AXES], len = GUIDE_MOVE_MIN_S;

	guide_path_at(g->path, t_s, g->to, dq);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		/* a smoothstep's top speed is 1.5 times its mean */
		double t = 1.5 * fabs(g->to[a] - q[a]) / p->speed_max[a];

		g->from[a] = q[a];
		len = t > len ? t : len;
	}
	g->t_s = t_s;
	g->move_t_s = 0;
	g->move_len_s = len;
	g->phase = ENDOSIM_GUIDE_MOVING;
	g->after_move = next;
	g->fade = 1;
	g->over_s = 0;
	g->lost_s = 0;
	g->lost_axis = -1;
	g->ended = ENDOSIM_GUIDE_END_NONE;
}

/* Ends with WHY: fading out unless WHY is the rig's leaving ENABLED. */
static void end(struct guide *g, uint32_t why)
{
	g->ended = why;
	if (why == ENDOSIM_GUIDE_END_NOT_ENABLED ||
	    g->phase == ENDOSIM_GUIDE_FREE) {
		g->phase = ENDOSIM_GUIDE_OFF;
		g->fade = 0;
		return;
	}
	g->phase = ENDOSIM_GUIDE_FADING;
	g->after_move = ENDOSIM_GUIDE_OFF;
}

/* The trainee takes over: fading out, then FREE until resumed. */
static void take_over(struct guide *g)
{
	g->takeovers++;
	g->phase = ENDOSIM_GUIDE_FADING;
	g->after_move = ENDOSIM_GUIDE_FREE;
	g->over_s = 0;
	g->lost_s = 0;
}

int guide_command(struct guide *g, const struct config_guide *p,
		  const struct guide_command *c, const double q[ENDOSIM_AXES])
{
	const struct guide_path *path =
		c->action == GUIDE_START ? c->path : g->path;

	if (c->action == GUIDE_STOP) {
		if (g->phase != ENDOSIM_GUIDE_OFF) {
			end(g, ENDOSIM_GUIDE_END_STOPPED);
		}
		return 0;
	}
	if (c->action == GUIDE_TAKEOVER) {
		if (g->phase == ENDOSIM_GUIDE_OFF ||
		    g->phase == ENDOSIM_GUIDE_FREE ||
		    g->phase == ENDOSIM_GUIDE_FADING) {
			return -EINVAL;
		}
		take_over(g);
		return 0;
	}
	if (!path || !(c->from_s >= 0) ||
	    c->from_s > guide_path_length_s(path)) {
		return -EINVAL;
	}
	switch (c->action) {
	case GUIDE_START:
		if (!(c->speed >= GUIDE_SPEED_MIN &&
		      c->speed <= GUIDE_SPEED_MAX)) {
			return -EINVAL;
		}
		g->path = path;
		g->speed = c->speed;
		g->takeovers = 0;
		begin_move(g, p, q, c->from_s, ENDOSIM_GUIDE_GUIDING);
		return 0;
	case GUIDE_RESUME:
		begin_move(g, p, q, c->from_s, ENDOSIM_GUIDE_GUIDING);
		return 0;
	case GUIDE_RESET:
		begin_move(g, p, q, c->from_s, ENDOSIM_GUIDE_HOLDING);
		return 0;
	default:
		return -EINVAL;
	}
}

/* MOVING: a smoothstep from FROM to TO. */
static void move_reference(struct guide *g, double dt_s)
{
	double u, s, ds;

	g->move_t_s += dt_s;
	u = g->move_t_s / g->move_len_s;
	u = u < 1 ? u : 1;
	s = u * u * (3 - 2 * u);
	ds = 6 * u * (1 - u) / g->move_len_s;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		g->ref[a] = g->from[a] + (g->to[a] - g->from[a]) * s;
		g->ref_v[a] = (g->to[a] - g->from[a]) * ds;
	}
	if (u >= 1) {
		g->phase = g->after_move;
		g->rate = g->speed;
	}
}

/* GUIDING: the path at the playhead, slowed where it moves too fast. */
static void play_reference(struct guide *g, const struct config_guide *p,
			   double dt_s)
{
	double dq[ENDOSIM_AXES];

	guide_path_at(g->path, g->t_s, g->ref, dq);
	g->rate = g->speed;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		double fast = fabs(g->rate * dq[a]);

		if (fast > p->speed_max[a]) {
			g->rate *= p->speed_max[a] / fast;
		}
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		g->ref_v[a] = g->rate * dq[a];
	}
	g->t_s += g->rate * dt_s;
	if (g->t_s >= guide_path_length_s(g->path)) {
		g->t_s = guide_path_length_s(g->path);
		end(g, ENDOSIM_GUIDE_END_DONE);
	}
}

/* Take-over and losing the path: how long each has held. */
static void watch(struct guide *g, const struct config_guide *p,
		  const double q[ENDOSIM_AXES], double dt_s)
{
	bool pushed = false;
	int lost = -1;

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		pushed |= fabs(g->hand[a]) > p->takeover[a];
		if (lost < 0 && fabs(g->ref[a] - q[a]) > p->error_max[a]) {
			lost = a;
		}
	}
	g->over_s = pushed && g->phase == ENDOSIM_GUIDE_GUIDING ?
		    g->over_s + dt_s : 0;
	g->lost_s = lost >= 0 ? g->lost_s + dt_s : 0;
	if (g->over_s >= p->takeover_s) {
		take_over(g);
	} else if (g->lost_s >= p->error_s) {
		g->lost_axis = lost;
		end(g, ENDOSIM_GUIDE_END_LOST);
	}
}

void guide_step(struct guide *g, const struct config_guide *p, bool enabled,
		bool ramped,
		const double q[ENDOSIM_AXES], const double v[ENDOSIM_AXES],
		const double applied[ENDOSIM_AXES], double dt_s,
		double force[ENDOSIM_AXES])
{
	double alpha = 1 - exp(-2 * M_PI * p->hand_filter_hz * dt_s);

	/* what the motors push against, low-passed: the hand's push */
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		g->hand[a] += alpha * (-applied[a] - g->hand[a]);
		g->force[a] = 0;
		force[a] = 0;
	}
	if (g->phase == ENDOSIM_GUIDE_OFF) {
		return;
	}
	if (!enabled) {
		end(g, ENDOSIM_GUIDE_END_NOT_ENABLED);
		return;
	}
	if (!ramped) {
		return;
	}
	switch (g->phase) {
	case ENDOSIM_GUIDE_MOVING:
		move_reference(g, dt_s);
		break;
	case ENDOSIM_GUIDE_GUIDING:
		play_reference(g, p, dt_s);
		break;
	case ENDOSIM_GUIDE_HOLDING:
		memcpy(g->ref, g->to, sizeof(g->ref));
		memset(g->ref_v, 0, sizeof(g->ref_v));
		break;
	case ENDOSIM_GUIDE_FADING:
		/* the reference stays where the take-over found it */
		memset(g->ref_v, 0, sizeof(g->ref_v));
		g->fade -= dt_s / p->fade_s;
		if (g->fade <= 0) {
			g->fade = 0;
			g->phase = g->after_move;
			return;
		}
		break;
	default: /* FREE */
		return;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		double f = p->stiffness[a] * (g->ref[a] - q[a]) +
			   p->damping[a] * (g->ref_v[a] - v[a]);

		f = f > p->force_max[a] ? p->force_max[a] :
		    f < -p->force_max[a] ? -p->force_max[a] : f;
		g->force[a] = g->fade * f;
		force[a] = g->force[a];
	}
	if (g->phase != ENDOSIM_GUIDE_FADING) {
		watch(g, p, q, dt_s);
	}
}

/* The path's sample nearest the playhead. */
static size_t playhead_sample(const struct guide *g)
{
	double x = g->t_s * GUIDE_PATH_HZ + 0.5;
	size_t i = x > 0 ? (size_t)x : 0;

	return i < g->path->n ? i : g->path->n - 1;
}

bool guide_patient_now(const struct guide *g, struct guide_patient *out)
{
	if (g->phase != ENDOSIM_GUIDE_GUIDING || !g->path->patient) {
		return false;
	}
	*out = g->path->patient[playhead_sample(g)];
	return true;
}

/* The snare's loop of the recording's tool W (m): as its handle asks, or
 * held at the thickness of T's polyp that its loop held. */
static double expert_loop(const struct guide_tool *w, const struct tool *t)
{
	double d = tool_loop_diameter(w->snare_m, w->opening, w->depth_m);

	if (w->captured >= 0 && w->captured < t->polyps) {
		d = fmax(d, tool_polyp_thickness(&t->polyp[w->captured]));
	}
	return d;
}

void guide_publish_tool(const struct guide *g, const struct tool_params *par,
			const struct endosim_scope_state *sc,
			const struct tool *t, struct endosim_guide_state *st)
{
	const struct guide_tool *w;
	struct tool_pose pose;
	double loop = 0;

	st->expert_kind = ENDOSIM_TOOL_NONE;
	st->expert_pedal = 0;
	st->expert_snare_m = st->expert_depth_m = st->expert_opening = 0;
	st->expert_loop_m = 0;
	memset(st->expert_tip, 0, sizeof(st->expert_tip));
	memset(st->expert_loop_centre, 0, sizeof(st->expert_loop_centre));
	if (g->phase != ENDOSIM_GUIDE_GUIDING || !g->path->tool) {
		return;
	}
	w = &g->path->tool[playhead_sample(g)];
	if (w->kind <= TOOL_NONE || w->kind >= ENDOSIM_TOOLS ||
	    !isfinite(w->depth_m) || !isfinite(w->opening) ||
	    !isfinite(w->snare_m)) {
		return; /* none, or a damaged file's */
	}
	tool_pose(par, sc, w->depth_m, &pose);
	if (w->kind == TOOL_SNARE) {
		loop = expert_loop(w, t);
	}
	st->expert_kind = (uint32_t)w->kind;
	st->expert_pedal = w->pedal != 0;
	st->expert_snare_m = w->snare_m;
	st->expert_depth_m = w->depth_m;
	st->expert_opening = w->opening;
	st->expert_loop_m = loop;
	for (int k = 0; k < 3; k++) {
		st->expert_tip[k] = pose.tip[k];
		st->expert_loop_centre[k] = pose.tip[k] +
					    loop / 2 * pose.dir[k];
	}
}

void guide_publish(const struct guide *g, const double q[ENDOSIM_AXES],
		   struct endosim_guide_state *st)
{
	bool on = g->phase != ENDOSIM_GUIDE_OFF; /* taken over: where it left */

	st->phase = g->phase;
	st->ended = g->ended;
	st->source_id = g->path ? g->path->source_id : 0;
	st->time_s = g->t_s;
	st->length_s = g->path ? guide_path_length_s(g->path) : 0;
	st->speed = g->speed;
	st->fade = g->fade;
	st->takeovers = g->takeovers;
	st->lost_axis = g->lost_axis >= 0 ? (uint32_t)g->lost_axis
					  : ENDOSIM_AXES;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		st->reference[a] = on ? g->ref[a] : 0;
		st->force[a] = g->force[a];
		st->error[a] = on ? g->ref[a] - q[a] : 0;
		st->hand[a] = g->hand[a];
	}
}
