/*
 * control_session.c - the control thread's training sessions
 * (control_private.h).
 */
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "base/mono.h"
#include "control/control_private.h"
#include "session/sessiondir.h"
#include "session/sessionpb.h"

struct control_sessions {
	Endosim__SessionReply session_reply;
	Endosim__SessionInfo session;
	struct recorder_info rinfo;        /* what session points into */
	struct sessionpb_metrics metrics;
	Endosim__SessionListReply session_list;
	struct control_rows list_rows;     /* the records' sessions */
	Endosim__SessionInfo **list_infos_p; /* they and the recording one */
	Endosim__SessionInfo list_recording; /* the list's recording session */
	struct sessiondir_entry recording;
	struct sessiondir_entry shown;     /* SessionShow's file */
	Endosim__MapReply map;             /* SessionMap's */
	Endosim__MapRegion map_regions[COLON_MAX_REGIONS];
	Endosim__MapRegion *map_regions_p[COLON_MAX_REGIONS];
	Endosim__MapPolyp map_found[ANATOMY_MAX_POLYPS];
	Endosim__MapPolyp *map_found_p[ANATOMY_MAX_POLYPS];
	struct recorder_map rmap;          /* what map points into */
	char error[256];
};

struct control_sessions *control_sessions_create(void)
{
	return calloc(1, sizeof(struct control_sessions));
}

/* Frees the session list the last reply was made of. */
static void free_session_list(struct control_sessions *rb)
{
	control_rows_free(&rb->list_rows);
	free(rb->list_infos_p);
	rb->list_infos_p = NULL;
}

void control_sessions_destroy(struct control_sessions *rb)
{
	if (!rb) {
		return;
	}
	free_session_list(rb);
	free(rb);
}

/* ---------------------------------------------------------------- sessions */

/* A trainee's name: shorter than SIZE, no control characters. */
static bool session_name_ok(const char *s, size_t size)
{
	if (strlen(s) >= size) {
		return false;
	}
	for (; *s; s++) {
		if ((unsigned char)*s < 0x20 || *s == 0x7f) {
			return false;
		}
	}
	return true;
}

/* The effective configuration as --print-config prints it (malloc'd). */
static char *config_text(const struct config *cfg)
{
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);

	if (!f) {
		return NULL;
	}
	config_print(cfg, f);
	if (fclose(f)) {
		free(text);
		return NULL;
	}
	return text;
}

/* The case file's text (malloc'd); an imported mesh: its paths. */
static char *case_text(const struct control *c)
{
	const char *path = c->case_path;
	size_t n = strlen(path);
	char *text = NULL;
	FILE *f;
	long len;

	if (n > 4 && !strcmp(path + n - 4, ".obj")) {
		return asprintf(&text, "# an imported mesh\nobj=%s\n"
				"centreline=%s\n", path,
				c->cfg.colon.centreline_file) < 0 ? NULL : text;
	}
	f = fopen(path, "re");
	if (!f || fseek(f, 0, SEEK_END) || (len = ftell(f)) < 0 ||
	    len > (long)SESSION_FRAME_MAX || fseek(f, 0, SEEK_SET) ||
	    !(text = calloc(1, (size_t)len + 1)) ||
	    fread(text, 1, (size_t)len, f) != (size_t)len) {
		free(text);
		text = NULL;
	}
	if (f) {
		fclose(f);
	}
	return text;
}

/* The reply's SessionInfo for the recorder's session IN. */
static Endosim__SessionInfo *fill_session(struct control *c,
					  const struct recorder_info *in)
{
	struct control_sessions *rb = c->sessions;
	Endosim__SessionInfo *s = &rb->session;

	rb->rinfo = *in;
	endosim__session_info__init(s);
	s->id = rb->rinfo.id;
	s->trainee = rb->rinfo.trainee;
	s->case_name = rb->rinfo.case_name;
	s->started = rb->rinfo.started;
	s->start_ns = rb->rinfo.start_ns;
	s->end_ns = rb->rinfo.end_ns;
	s->duration_s = (double)((rb->rinfo.end_ns ? rb->rinfo.end_ns
						   : mono_ns()) -
				 rb->rinfo.start_ns) / ENDOSIM_NS_PER_S;
	s->records = rb->rinfo.records;
	s->drops = rb->rinfo.drops;
	s->bytes = rb->rinfo.bytes;
	s->path = rb->rinfo.path;
	s->recording = rb->rinfo.recording;
	s->ended = !rb->rinfo.recording;
	sessionpb_from_metrics(&rb->metrics, &rb->rinfo.metrics);
	s->metrics = &rb->metrics.msg;
	return s;
}

static void session_reply(struct control *c, Endosim__Reply *rep,
			  Endosim__SessionInfo *s)
{
	struct control_sessions *rb = c->sessions;

	endosim__session_reply__init(&rb->session_reply);
	rb->session_reply.session = s;
	rep->body_case = ENDOSIM__REPLY__BODY_SESSION;
	rep->session = &rb->session_reply;
}

static int start_session(struct control *c, const char *trainee,
			 struct recorder_info *info)
{
	struct recorder_session s = {
		.colon = c->colon,
		.period_ns = loop_get_info(c->deps.loop)->period_ns,
		.step_m = c->cfg.colon.step_m,
		.segment_m = c->cfg.colon.segment_m,
		.ring_vertices = c->cfg.colon.ring_vertices,
	};
	char *cfg = config_text(&c->cfg), *cs = case_text(c);
	int r = -ENOMEM;

	snprintf(s.trainee, sizeof(s.trainee), "%s", trainee);
	snprintf(s.case_name, sizeof(s.case_name), "%s", colon_name(c->colon));
	if (cfg && cs) {
		s.config_text = cfg;
		s.case_text = cs;
		r = recorder_start(c->deps.recorder, &s, info);
	}
	free(cfg);
	free(cs);
	return r;
}

void control_on_session_start(struct control *c, struct client *cl,
			      const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__SessionStart *ss = req->session_start;
	char *why = c->sessions->error, trainee[RECORDER_NAME];
	size_t size = sizeof(c->sessions->error);
	struct recorder_info info;
	int r;

	recorder_info(c->deps.recorder, &info);
	if (!session_name_ok(ss->trainee, RECORDER_NAME)) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "trainee: at most 63 bytes, no control characters");
		return;
	}
	if (*ss->case_name && !config_case_name_ok(ss->case_name)) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "case: letters, digits, '-' and '_'");
		return;
	}
	if (info.recording) {
		snprintf(why, size, "session %" PRIu64 " is recording: "
			 "'session stop' first", info.id);
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED, why);
		return;
	}
	if (control_training_session(c, cl, ss->trainee, trainee,
				     sizeof(trainee), rep)) {
		return;
	}
	if (*ss->case_name && control_load_case(c, cl, ss->case_name, rep)) {
		return;
	}
	if (control_sedate(c, cl, ss->sedation, rep)) {
		return;
	}
	control_await_state(c); /* the first record has it */
	r = start_session(c, trainee, &info);
	if (r) {
		snprintf(why, size, "cannot record in %s: %s",
			 c->cfg.session.directory, strerror(-r));
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, why);
		return;
	}
	log_notice("session %" PRIu64 " started (uid %d): trainee '%s', case "
		   "%s, %s", info.id, (int)cl->uid, info.trainee,
		   info.case_name, info.path);
	session_reply(c, rep, fill_session(c, &info));
}

void control_on_session_stop(struct control *c, struct client *cl,
			     const Endosim__Request *req, Endosim__Reply *rep)
{
	struct recorder_info info;
	int r = recorder_stop(c->deps.recorder, &info);

	(void)req;
	if (r == -ENOENT) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "no session is recording");
		return;
	}
	log_notice("session %" PRIu64 " stopped (uid %d): %" PRIu64
		   " records, %" PRIu64 " dropped, %s", info.id, (int)cl->uid,
		   info.records, info.drops, info.path);
	control_records_ended(c, &info); /* finished or cut, as the file */
	if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL,
		       "the session file could not be finished (see the log)");
		return;
	}
	session_reply(c, rep, fill_session(c, &info));
}

void control_on_session_status(struct control *c, struct client *cl,
			       const Endosim__Request *req, Endosim__Reply *rep)
{
	struct recorder_info info;

	(void)cl;
	(void)req;
	recorder_info(c->deps.recorder, &info);
	session_reply(c, rep, info.active ? fill_session(c, &info) : NULL);
}

/* A listed session; the recorder's own one with what it knows. */
static void fill_entry(Endosim__SessionInfo *s, const struct recorder_info *ri)
{
	if (ri->active && ri->id == s->id) {
		s->recording = ri->recording;
		s->records = ri->records;
		s->drops = ri->drops;
		s->start_ns = ri->start_ns;
		s->end_ns = ri->end_ns;
	}
}

/* The recording session, which the records hold only once it ends, as
 * the list's last (its ID the highest); how many that adds. */
static size_t list_recording(struct control *c, const struct recorder_info *ri,
			     size_t n)
{
	struct control_sessions *rb = c->sessions;
	Endosim__SessionInfo *s = &rb->list_recording;

	if (!ri->active || !ri->recording ||
	    (n && rb->list_infos_p[n - 1]->id >= ri->id) ||
	    sessiondir_stat(c->cfg.session.directory, ri->id, &rb->recording)) {
		return 0;
	}
	sessionpb_from_entry(s, &rb->recording);
	fill_entry(s, ri);
	rb->list_infos_p[n] = s;
	return 1;
}

void control_on_session_list(struct control *c, struct client *cl,
			     const Endosim__Request *req, Endosim__Reply *rep)
{
	struct control_sessions *rb = c->sessions;
	struct control_rows *rows = &rb->list_rows;
	struct recorder_info ri;
	size_t n;
	int r;

	(void)cl;
	(void)req;
	free_session_list(rb);
	recorder_info(c->deps.recorder, &ri);
	rows->what = RECORDS_FACTS;
	r = control_records_rows(c, NULL, rows, rb->error, sizeof(rb->error));
	n = rows->n;
	if (!r && !(rb->list_infos_p = calloc(n + 1, sizeof(*rows->infos)))) {
		snprintf(rb->error, sizeof(rb->error), "out of memory");
		r = -ENOMEM;
	}
	if (r) {
		free_session_list(rb);
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, rb->error);
		return;
	}
	for (size_t i = 0; i < n; i++) {
		fill_entry(rows->infos[i], &ri);
		rb->list_infos_p[i] = rows->infos[i];
	}
	endosim__session_list_reply__init(&rb->session_list);
	rb->session_list.n_sessions = n + list_recording(c, &ri, n);
	rb->session_list.sessions = rb->list_infos_p;
	rb->session_list.directory = c->cfg.session.directory;
	rep->body_case = ENDOSIM__REPLY__BODY_SESSION_LIST;
	rep->session_list = &rb->session_list;
}

void control_on_session_show(struct control *c, struct client *cl,
			     const Endosim__Request *req, Endosim__Reply *rep)
{
	struct control_sessions *rb = c->sessions;
	uint64_t id = req->session_show->id;
	struct sessiondir_entry *e = &rb->shown;
	Endosim__SessionInfo *s;
	struct recorder_info ri;
	int r;

	(void)cl;
	recorder_info(c->deps.recorder, &ri);
	r = sessiondir_stat(c->cfg.session.directory, id, e);
	if (r) {
		snprintf(rb->error, sizeof(rb->error), "no session %" PRIu64
			 " in %s%s", id, c->cfg.session.directory,
			 r == -ENOENT ? "" : r == -EBADMSG ? ": not a session "
			 "file" : ": unreadable");
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, rb->error);
		return;
	}
	if (ri.active && ri.id == id) {
		s = fill_session(c, &ri);
	} else {
		memset(&rb->rinfo, 0, sizeof(rb->rinfo));
		sessionpb_from_entry(&rb->session, e);
		sessiondir_path(c->cfg.session.directory, id, rb->rinfo.path,
				sizeof(rb->rinfo.path));
		s = &rb->session;
		s->path = rb->rinfo.path;
	}
	s->ended = e->ended;
	s->bytes = s->recording ? s->bytes : e->bytes;
	s->trainee = s->trainee ? s->trainee : "";
	session_reply(c, rep, s);
}

/* ------------------------------------------------------------ live map */

/* The map's regions: the colon's (no case loads while a session records,
 * so it is the session's). */
static void map_regions(struct control *c, Endosim__MapReply *m)
{
	struct control_sessions *rb = c->sessions;
	int n = colon_regions(c->colon);

	for (int i = 0; i < n && i < COLON_MAX_REGIONS; i++) {
		const struct colon_region *cr = colon_region(c->colon, i);
		Endosim__MapRegion *g = &rb->map_regions[i];

		endosim__map_region__init(g);
		g->name = (char *)cr->name;
		g->s0_m = cr->s0_m;
		g->s1_m = cr->s1_m;
		rb->map_regions_p[i] = g;
		m->n_regions++;
	}
	m->regions = rb->map_regions_p;
}

/* The polyps found so far, never those still to find. */
static void map_found(struct control *c, Endosim__MapReply *m)
{
	struct control_sessions *rb = c->sessions;
	const struct anatomy *a = colon_anatomy(c->colon);

	for (int k = 0; a && k < a->polyps && k < ANATOMY_MAX_POLYPS; k++) {
		Endosim__MapPolyp *p = &rb->map_found[m->n_found];

		if (!(rb->rmap.polyps_found_mask >> k & 1)) {
			continue;
		}
		endosim__map_polyp__init(p);
		p->index = (uint32_t)k;
		p->s_m = a->polyp[k].s_m;
		p->angle_rad = a->polyp[k].angle_rad;
		rb->map_found_p[m->n_found++] = p;
	}
	m->found = rb->map_found_p;
}

void control_on_session_map(struct control *c, struct client *cl,
			    const Endosim__Request *req, Endosim__Reply *rep)
{
	struct control_sessions *rb = c->sessions;
	Endosim__MapReply *m = &rb->map;
	int r = recorder_map(c->deps.recorder, &rb->rmap);

	(void)cl;
	(void)req;
	if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED, r == -ENOENT ?
		       "no session is recording" :
		       "the session's map is not made yet: ask again");
		return;
	}
	endosim__map_reply__init(m);
	m->session_id = rb->rmap.id;
	m->time_s = rb->rmap.time_s;
	m->length_m = rb->rmap.length_m;
	m->along = METRICS_MAP_S;
	m->around = METRICS_MAP_A;
	m->cells.data = rb->rmap.cells;
	m->cells.len = sizeof(rb->rmap.cells);
	m->mucosa_seen = rb->rmap.mucosa_seen;
	m->tip_s_m = rb->rmap.tip_s_m;
	map_regions(c, m);
	map_found(c, m);
	rep->body_case = ENDOSIM__REPLY__BODY_MAP;
	rep->map = m;
}
