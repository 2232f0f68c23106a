/* replay.c - see replay.h. */
#include "viewer/replay.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/colon.h"
#include "base/log.h"
#include "model/scene.h"
#include "model/scope.h"
#include "model/tool.h"
#include "base/vec3.h"
#include "proto/session_file.h"
#include "session/sessioninputs.h"


/* A record whose cycle had tool events, and where a clip it placed went. */
struct tool_mark {
	size_t rec;
	uint32_t events;       /* enum endosim_tool_event bits */
	int32_t polyp;         /* the polyp they concern, -1 none */
	double clip_at[3];     /* a clip placed: its jaws' point */
};

/* A cut polyp's place as a record told it, when it changed. */
struct place {
	size_t rec;
	float at[3];
};

struct replay {
	struct session_file f;
	struct scope_params scope; /* recorded with */
	double scope_radius_m;
	struct colon *colon;
	struct scene *scene;
	struct client_scene cs;
	char trainee[64], case_name[64];
	double t_s, speed;
	bool paused;
	size_t shown;     /* the record in st, SIZE_MAX: none yet */
	struct endosim_state st;
	struct scope_pose pose;
	struct session_shape shape; /* the rod model's, at or before st */
	double loop_threshold_m;    /* the session's metrics' */
	double relief_pa, strength_n_per_m; /* its [patient] */
	struct tool_params tool_par; /* its [tool] */
	struct tool tool;            /* its case's polyps placed for it */
	struct tool_mark *marks;     /* the records with tool events */
	size_t n_marks;
	struct place *places;        /* each polyp's changes of place, */
	size_t place_first[ENDOSIM_POLYPS], place_n[ENDOSIM_POLYPS]; /* its */
	struct endosim_state scratch;
};

static const char *read_error(int r)
{
	switch (r) {
	case -EBADMSG:
		return "not a session file";
	case -EPROTO:
		return "a session file of a format or record size this viewer "
		       "does not know";
	default:
		return strerror(-r);
	}
}

/* The scope's parameters and radius, from CONFIG. */
static void read_scope(struct replay *r, const char *path)
{
	struct metrics_params mp;
	char err[256];

	if (sessioninputs_scope(&r->f, &r->scope, &r->scope_radius_m, err,
				sizeof(err))) {
		log_warn("%s: its configuration: %s: the scope's defaults "
			 "instead", path, err);
	}
	sessioninputs_file_metrics_params(&r->f, &mp);
	r->loop_threshold_m = mp.loop_threshold_m;
}

/* The pressure gauge's marks, from the recorded configuration (its
 * defaults where it has none). */
static void read_patient(struct replay *r)
{
	struct config cfg;
	char err[256];

	sessioninputs_config(&r->f, &cfg, err, sizeof(err));
	r->relief_pa = cfg.patient.relief_pa;
	r->strength_n_per_m = cfg.patient.wall_strength_n_per_m;
}

static int build_colon(struct replay *r, const char *path, char *err,
		       size_t errsize)
{
	char why[256];

	if (!r->f.case_text || !*r->f.case_text) {
		snprintf(err, errsize, "%s: no case recorded", path);
		return -EINVAL;
	}
	r->colon = sessioninputs_file_colon(&r->f, why, sizeof(why));
	if (!r->colon) {
		snprintf(err, errsize, "%s: its colon: %s", path, why);
		return -EINVAL;
	}
	r->scene = scene_create(r->colon, REPLAY_SCENE_ID);
	if (!r->scene) {
		snprintf(err, errsize, "%s: out of memory", path);
		return -ENOMEM;
	}
	scene_set_scope(r->scene, &r->scope, r->scope_radius_m);
	scene_client(r->scene, &r->cs);
	return 0;
}

/* Where the clip placed in record REC went: its jaws' point on the pose
 * the record's tip and tool depth give (tool.h), into AT. */
static void clip_place(struct replay *r, size_t rec, double at[3])
{
	struct tool_pose pose;

	session_record_to_state(&r->f.records[rec], &r->scratch);
	tool_pose(&r->tool_par, &r->scratch.scope, r->scratch.tool.depth_m,
		  &pose);
	vec3_axpy(at, pose.tip, r->tool_par.clip_m, pose.dir);
}

/* The records with tool events, in order, the clips' places with them:
 * 0, or -ENOMEM. */
static int read_marks(struct replay *r)
{
	size_t n = 0;

	for (size_t i = 0; i < r->f.n_records; i++) {
		n += r->f.records[i].tool_events != 0;
	}
	r->marks = calloc(n ? n : 1, sizeof(*r->marks));
	if (!r->marks) {
		return -ENOMEM;
	}
	for (size_t i = 0; i < r->f.n_records; i++) {
		const struct session_record *rec = &r->f.records[i];
		struct tool_mark *m = &r->marks[r->n_marks];

		if (!rec->tool_events) {
			continue;
		}
		*m = (struct tool_mark){ .rec = i, .events = rec->tool_events,
					 .polyp = rec->tool_event_polyp };
		if (rec->tool_events & ENDOSIM_TOOL_CLIP_PLACED) {
			clip_place(r, i, m->clip_at);
		}
		r->n_marks++;
	}
	return 0;
}

/* The polyp record REC tells the place of, or -1. */
static int told(const struct replay *r, const struct session_record *rec)
{
	int k = rec->tool_lying_polyp;

	return k >= 0 && k < r->tool.polyps ? k : -1;
}

/* Walks the places the records tell, each polyp's changes only: counts
 * them into R's place_n, or, with AT (each polyp's next slot), writes
 * them into its places. */
static void walk_places(struct replay *r, size_t *at)
{
	bool had[ENDOSIM_POLYPS] = { false };
	float last[ENDOSIM_POLYPS][3];

	for (size_t i = 0; i < r->f.n_records; i++) {
		const struct session_record *rec = &r->f.records[i];
		int k = told(r, rec);

		if (k < 0 || (had[k] && !memcmp(last[k], rec->tool_lying_at,
						sizeof(last[k])))) {
			continue;
		}
		had[k] = true;
		memcpy(last[k], rec->tool_lying_at, sizeof(last[k]));
		if (!at) {
			r->place_n[k]++;
			continue;
		}
		r->places[at[k]++] = (struct place){
			.rec = i, .at = { last[k][0], last[k][1], last[k][2] } };
	}
}

/* Each polyp's changes of place as the records tell them, grouped by
 * polyp in the records' order: 0, or -ENOMEM. */
static int read_places(struct replay *r)
{
	size_t n = 0, at[ENDOSIM_POLYPS];

	walk_places(r, NULL);
	for (int k = 0; k < ENDOSIM_POLYPS; k++) {
		r->place_first[k] = at[k] = n;
		n += r->place_n[k];
	}
	r->places = calloc(n ? n : 1, sizeof(*r->places));
	if (!r->places) {
		return -ENOMEM;
	}
	walk_places(r, at);
	return 0;
}

struct replay *replay_open(const char *path, char *err, size_t errsize)
{
	struct replay *r = calloc(1, sizeof(*r));
	int e;

	if (!r) {
		snprintf(err, errsize, "%s: out of memory", path);
		return NULL;
	}
	r->speed = 1;
	r->shown = SIZE_MAX;
	e = session_file_read(path, &r->f);
	if (e) {
		snprintf(err, errsize, "%s: %s", path, read_error(e));
		goto fail;
	}
	if (!r->f.n_records) {
		snprintf(err, errsize, "%s: no record to replay", path);
		goto fail;
	}
	session_text_get(r->f.header, "trainee", r->trainee,
			 sizeof(r->trainee));
	session_text_get(r->f.header, "case", r->case_name,
			 sizeof(r->case_name));
	read_scope(r, path);
	read_patient(r);
	if (build_colon(r, path, err, errsize)) {
		goto fail;
	}
	sessioninputs_tool(&r->f, &r->tool_par);
	tool_reset(&r->tool);
	(void)tool_place_polyps(&r->tool, r->colon);
	if (read_marks(r) || read_places(r)) {
		snprintf(err, errsize, "%s: out of memory", path);
		goto fail;
	}
	return r;
fail:
	replay_destroy(r);
	return NULL;
}

void replay_destroy(struct replay *r)
{
	if (!r) {
		return;
	}
	free(r->marks);
	free(r->places);
	scene_destroy(r->scene);
	colon_destroy(r->colon);
	session_file_close(&r->f);
	free(r);
}

const struct client_scene *replay_scene(struct replay *r)
{
	return &r->cs;
}

const char *replay_trainee(const struct replay *r)
{
	return r->trainee;
}

const char *replay_case(const struct replay *r)
{
	return r->case_name;
}

size_t replay_records(const struct replay *r)
{
	return r->f.n_records;
}

size_t replay_bytes_ignored(const struct replay *r)
{
	return r->f.bytes_ignored;
}

void replay_patient_limits(const struct replay *r, double *relief_pa,
			   double *strength_n_per_m)
{
	*relief_pa = r->relief_pa;
	*strength_n_per_m = r->strength_n_per_m;
}

double replay_loop_threshold_m(const struct replay *r)
{
	return r->loop_threshold_m;
}

double replay_duration(const struct replay *r)
{
	const struct session_record *rec = r->f.records;

	return (double)(rec[r->f.n_records - 1].stamp_ns - rec[0].stamp_ns) /
	       ENDOSIM_NS_PER_S;
}

double replay_time(const struct replay *r)
{
	return r->t_s;
}

void replay_seek(struct replay *r, double t_s)
{
	r->t_s = fmax(0, fmin(t_s, replay_duration(r)));
}

void replay_advance(struct replay *r, double dt_s)
{
	if (!r->paused) {
		replay_seek(r, r->t_s + dt_s * r->speed);
	}
}

void replay_set_paused(struct replay *r, bool paused)
{
	r->paused = paused;
}

bool replay_paused(const struct replay *r)
{
	return r->paused;
}

void replay_set_speed(struct replay *r, double speed)
{
	r->speed = fmax(REPLAY_SPEED_MIN, fmin(REPLAY_SPEED_MAX, speed));
}

double replay_speed(const struct replay *r)
{
	return r->speed;
}

/* The record shown at T_S. */
static size_t index_at(const struct replay *r, double t_s)
{
	return session_file_seek(
		&r->f,
		r->f.records[0].stamp_ns +
			(uint64_t)llround(fmax(0, t_s) * ENDOSIM_NS_PER_S));
}

void replay_record_at(const struct replay *r, double t_s,
		      struct endosim_state *out)
{
	session_record_to_state(&r->f.records[index_at(r, t_s)], out);
	out->scope.scene_id = REPLAY_SCENE_ID;
}

/* The tube of record I: its pose on the colon bowed as the cycle before
 * left it (the record before, when it is that cycle's). */
static void rebuild_tube(struct replay *r, size_t i)
{
	const struct session_record *rec = &r->f.records[i];
	const struct session_record *bows =
		i > 0 && rec[-1].cycle + 1 == rec->cycle ? &rec[-1] : rec;
	const struct scope_input in = {
		rec->position[0], rec->position[1], rec->position[2],
		rec->position[3],
	};
	const struct centreline *cl = colon_centreline(r->colon);

	for (int k = 0; k < centreline_spans(cl) && k < ENDOSIM_SPANS; k++) {
		colon_bow(r->colon, k, bows->bow_m[k], false);
	}
	scope_update(&r->scope, cl, &in, &r->pose);
	for (int p = 0; p < ENDOSIM_TUBE_POINTS; p++) {
		for (int d = 0; d < 3; d++) {
			r->st.scope.tube[p][d] = (float)r->pose.tube[p][d];
		}
	}
}

static double distance(const float a[3], const float b[3])
{
	double d[3] = { (double)b[0] - a[0], (double)b[1] - a[1],
			(double)b[2] - a[2] };

	return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/*
 * The scope's tube as the rod model makes it: DEPTH_M of the rod's end
 * (its points, base to tip) in equal arcs, from the anal verge to the tip.
 */
static void tube_from_rod(struct endosim_state *st, double depth_m)
{
	const struct endosim_rod_state *rod = &st->rod;
	double len = 0, along = 0;
	uint32_t j = 0;

	if (rod->points < 2) {
		return;
	}
	for (uint32_t i = 1; i < rod->points; i++) {
		len += distance(rod->point[i - 1], rod->point[i]);
	}
	for (int k = 0; k < ENDOSIM_TUBE_POINTS; k++) {
		double at = len - depth_m +
			    depth_m * k / (ENDOSIM_TUBE_POINTS - 1);
		double seg = distance(rod->point[j], rod->point[j + 1]);
		double f;

		while (j + 2 < rod->points && along + seg < at) {
			along += seg;
			j++;
			seg = distance(rod->point[j], rod->point[j + 1]);
		}
		f = seg > 0 ? fmin(fmax((at - along) / seg, 0), 1) : 0;
		for (int d = 0; d < 3; d++) {
			st->scope.tube[k][d] =
				(float)((1 - f) * rod->point[j][d] +
					f * rod->point[j + 1][d]);
		}
	}
}

/*
 * The rod model's shape: the SHAPE at or before the record shown (none
 * when the file has none), and the tube, the inserted depth of its cycle,
 * from it.
 */
static void show_rod(struct replay *r)
{
	const struct session_record *rec;

	if (!r->f.n_shapes) {
		return;
	}
	session_file_shape(&r->f, session_file_seek_shape(&r->f,
							  r->st.stamp_ns),
			   &r->shape);
	session_shape_to_state(&r->shape, &r->st);
	rec = &r->f.records[session_file_seek(&r->f, r->shape.stamp_ns)];
	tube_from_rod(&r->st, rec->depth_m);
}

/*
 * The tool in the working channel where the record's sensing put it: the
 * file records what the rig sensed (its depth, the handle, the snare's
 * size, the polyp held), the model says where that puts the tool on the
 * recorded tip (tool.h): its tip, and a snare's loop, held open at the
 * thickness of the polyp it holds.
 */
static void show_tool(struct replay *r)
{
	struct endosim_tool_state *t = &r->st.tool;
	struct tool_pose pose;
	double loop_m;

	if (t->kind == ENDOSIM_TOOL_NONE) {
		return;
	}
	tool_pose(&r->tool_par, &r->st.scope, t->depth_m, &pose);
	vec3_copy(t->tip, pose.tip);
	if (t->kind != ENDOSIM_TOOL_SNARE) {
		return;
	}
	loop_m = tool_loop_diameter(t->snare_m, t->opening, t->depth_m);
	if (t->captured >= 0 && t->captured < r->tool.polyps) {
		loop_m = fmax(loop_m, tool_polyp_thickness(
					      &r->tool.polyp[t->captured]));
	}
	t->loop_m = loop_m;
	vec3_axpy(t->loop_centre, pose.tip, loop_m / 2, pose.dir);
}

/* Of polyp K's places, the last told at or before record I; NULL none. */
static const struct place *place_at(const struct replay *r, int k, size_t i)
{
	const struct place *p = &r->places[r->place_first[k]];
	size_t lo = 0, hi = r->place_n[k]; /* the first told after I: lo */

	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;

		if (p[mid].rec <= i) {
			lo = mid + 1;
		} else {
			hi = mid;
		}
	}
	return lo ? &p[lo - 1] : NULL;
}

/* The marks at or before record I. */
static size_t marks_by(const struct replay *r, size_t i)
{
	size_t lo = 0, hi = r->n_marks;

	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;

		if (r->marks[mid].rec <= i) {
			lo = mid + 1;
		} else {
			hi = mid;
		}
	}
	return lo;
}

/* The polyps, the bleeding points and the clips as record I's cycle had
 * them, from the events up to it: each polyp held (the record's), cut,
 * retrieved, bleeding and stopped by a clip or by itself as they said;
 * the last clip where its jaws were; each cut polyp where the records
 * last told it lay (where it was cut, before they do). */
static void show_left(struct replay *r, size_t i)
{
	struct endosim_tool_state *t = &r->st.tool;
	size_t n = marks_by(r, i);
	double most = 0;

	t->polyps = (uint32_t)r->tool.polyps;
	for (size_t m = 0; m < n; m++) {
		const struct tool_mark *mk = &r->marks[m];
		struct endosim_tool_polyp *p = mk->polyp >= 0 &&
			mk->polyp < r->tool.polyps ? &t->polyp[mk->polyp] : NULL;

		if (mk->events & ENDOSIM_TOOL_CLIP_PLACED) {
			t->clips++;
			vec3_copy(t->clip_at, mk->clip_at);
		}
		if (!p) {
			continue;
		}
		if (mk->events & ENDOSIM_TOOL_CUT) {
			p->state = ENDOSIM_POLYP_CUT;
			tool_polyp_body(&r->tool.polyp[mk->polyp],
					&r->tool_par, p->at);
		}
		if (mk->events & ENDOSIM_TOOL_RETRIEVE) {
			p->state = ENDOSIM_POLYP_RETRIEVED;
		}
		if (mk->events & ENDOSIM_TOOL_BLEED) {
			p->bleed = ENDOSIM_BLEED_BLEEDING;
			p->bleed_m3_s = tool_polyp_flow(
				&r->tool.polyp[mk->polyp], &r->tool_par);
		}
		if (mk->events & (ENDOSIM_TOOL_CLIPPED | ENDOSIM_TOOL_STOPPED)) {
			p->bleed = mk->events & ENDOSIM_TOOL_CLIPPED ?
					   ENDOSIM_BLEED_CLIPPED :
					   ENDOSIM_BLEED_STOPPED;
			p->bleed_m3_s = 0;
		}
	}
	for (int k = 0; k < r->tool.polyps; k++) {
		struct endosim_tool_polyp *p = &t->polyp[k];
		const struct place *at = place_at(r, k, i);

		if (k == t->captured && p->state == ENDOSIM_POLYP_IN_PLACE) {
			p->state = ENDOSIM_POLYP_CAPTURED;
		}
		if (at && p->state != ENDOSIM_POLYP_RETRIEVED) {
			p->state = ENDOSIM_POLYP_CUT;
			for (int d = 0; d < 3; d++) {
				p->at[d] = at->at[d];
			}
		}
		if (p->bleed_m3_s > most) {
			most = p->bleed_m3_s;
			vec3_copy(t->bleed_at, r->tool.polyp[k].base);
		}
		t->bleeding += p->bleed_m3_s > 0;
	}
}

const struct endosim_state *replay_state(struct replay *r)
{
	size_t i = index_at(r, r->t_s);

	if (i != r->shown) {
		replay_record_at(r, r->t_s, &r->st);
		if (r->st.rod.model == ENDOSIM_MODEL_ROD) {
			show_rod(r);
		} else {
			rebuild_tube(r, i);
		}
		show_tool(r);
		show_left(r, i);
		r->shown = i;
	}
	return &r->st;
}
