/*
 * control_records.c - the control thread's records (control_private.h):
 * the rig's database (records.h) brought up to date with the session
 * files at start-up, a session's row written when it ends (and queued
 * for a centre's database, control_centre.c), and RecordsCheck and
 * RecordsRebuild.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "control/control_private.h"
#include "session/records.h"
#include "session/sessionpb.h"

struct control_records {
	struct records *db;
	struct control_centre *centre;  /* NULL: none */
	unsigned copies_seen;           /* control_centre_copies() so far */
	struct records_report report;   /* what the last reply points into */
	Endosim__RecordsReply reply;
};

/* The records' own words when they have some, else errno's. */
static const char *why(const struct control_records *cr, int e)
{
	const char *text = records_error(cr->db);

	return *text ? text : strerror(-e);
}

/* With a centre: the sessions it has not had queued, and its worker. */
static int start_centre(struct control_records *cr, const struct config *cfg,
			int wake_fd)
{
	size_t waiting = 0;
	int e;

	if (!cfg->records.centre[0]) {
		return 0;
	}
	records_set_centre(cr->db, true);
	if ((e = records_queue_unsent(cr->db, &waiting))) {
		log_warn("records: the centre's queue: %s", why(cr, e));
	} else if (waiting) {
		log_notice("records: %zu sessions wait for the centre", waiting);
	}
	cr->centre = control_centre_create(cfg, wake_fd);
	return cr->centre ? 0 : -EINVAL;
}

/* The sessions the files had and the database had not, at start-up. */
static int bring_up_to_date(struct control_records *cr)
{
	struct records_report *rep = &cr->report;
	int e = records_check(cr->db, RECORDS_FIX, 0, rep);

	if (e == -EPROTO) {
		log_err("%s", records_error(cr->db));
		return e;
	}
	if (e) {
		log_warn("records: cannot bring them up to date: %s",
			 why(cr, e));
	} else if (rep->missing || rep->damaged || rep->differ) {
		log_notice("records %s: %s%zu of %zu sessions written from "
			   "their files", records_path(cr->db), rep->missing ?
			   "made: " : rep->damaged ? "damaged: " : "",
			   rep->written, rep->files);
	}
	records_report_free(rep);
	return 0;
}

struct control_records *control_records_create(const struct config *cfg,
					       int wake_fd)
{
	struct control_records *cr = calloc(1, sizeof(*cr));

	if (!cr || !(cr->db = records_create(cfg->records.database,
					     cfg->session.directory,
					     cfg->records.rig,
					     cfg->session.course))) {
		log_err("control: out of memory");
		control_records_destroy(cr);
		return NULL;
	}
	if (bring_up_to_date(cr) || start_centre(cr, cfg, wake_fd)) {
		control_records_destroy(cr);
		return NULL;
	}
	return cr;
}

void control_records_destroy(struct control_records *cr)
{
	if (!cr) {
		return;
	}
	control_centre_destroy(cr->centre);
	records_report_free(&cr->report);
	records_destroy(cr->db);
	free(cr);
}

void control_records_ended(struct control *c, const struct recorder_info *ri)
{
	uint64_t id = ri->id;
	int e = records_add_summed(c->records->db, id, ri->checksum_known ?
				   &ri->checksum : NULL);

	if (e) {
		log_warn("records: session %llu not written: %s (the next "
			 "start-up or 'endoctl records rebuild' writes it)",
			 (unsigned long long)id, why(c->records, e));
	} else if (c->records->centre) {
		control_centre_poke(c->records->centre);
	}
}

void control_records_poke_centre(struct control *c)
{
	if (c->records->centre) {
		control_centre_poke(c->records->centre);
	}
}

bool control_records_people_copied(struct control *c)
{
	struct control_records *cr = c->records;
	unsigned now;

	if (!cr->centre) {
		return false;
	}
	now = control_centre_copies(cr->centre);
	if (now == cr->copies_seen) {
		return false;
	}
	cr->copies_seen = now;
	return true;
}

/* One row of control_records_rows(): what its info points into. */
struct control_row {
	Endosim__SessionInfo info;  /* first: free() of its address frees all */
	struct sessiondir_entry e;
	struct sessionpb_scalars pm;
	char path[];
};

static int add_row(void *arg, const struct records_session *s)
{
	struct control_rows *rows = arg;
	size_t len = rows->paths ? strlen(rows->dir) + 32 : 0;
	struct control_row *row;

	if (!s) {
		control_rows_free(rows); /* read again from the start */
		return 0;
	}
	if (rows->n == rows->cap) {
		size_t cap = rows->cap ? 2 * rows->cap : 64;
		Endosim__SessionInfo **more = realloc(rows->infos,
						      cap * sizeof(*more));

		if (!more) {
			return -ENOMEM;
		}
		rows->infos = more;
		rows->cap = cap;
	}
	if (!(row = malloc(sizeof(*row) + len))) {
		return -ENOMEM;
	}
	row->e = s->e;
	sessionpb_from_entry(&row->info, &row->e);
	if (len) {
		sessiondir_path(rows->dir, s->e.id, row->path, len);
		row->info.path = row->path;
	}
	if (s->has_metrics) {
		sessionpb_from_scalars(&row->pm, &s->m);
		row->info.metrics = &row->pm.msg;
	}
	rows->infos[rows->n++] = &row->info;
	return 0;
}

int control_records_rows(struct control *c, const char *trainee,
			 struct control_rows *rows, char *error, size_t size)
{
	int e;

	rows->dir = c->cfg.session.directory;
	e = records_each(c->records->db, trainee, rows->what, rows->keys,
			 rows->n_keys, add_row, rows);
	if (e) {
		snprintf(error, size, "%s", e == -ENOMEM ? "out of memory"
			 : why(c->records, e));
		if (e != -EINVAL) { /* a client's unknown key is not ours */
			log_warn("%s", error);
		}
		control_rows_free(rows);
	}
	return e;
}

void control_rows_free(struct control_rows *rows)
{
	for (size_t i = 0; i < rows->n; i++) {
		free(rows->infos[i]);
	}
	free(rows->infos);
	rows->infos = NULL;
	rows->n = rows->cap = 0;
}

/* The session recording (0: none), which the files and rows leave out. */
static uint64_t recording_id(struct control *c)
{
	struct recorder_info ri;

	recorder_info(c->deps.recorder, &ri);
	return ri.active && ri.recording ? ri.id : 0;
}

/* The reply of what *REP found (E: what failed). */
static void records_reply(struct control *c, Endosim__Reply *rep, int e)
{
	struct control_records *cr = c->records;
	Endosim__RecordsReply *m = &cr->reply;

	if (e) {
		snprintf(c->refusal, sizeof(c->refusal), "%s", why(cr, e));
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, c->refusal);
		return;
	}
	endosim__records_reply__init(m);
	m->database = (char *)records_path(cr->db);
	m->missing = cr->report.missing;
	m->damaged = cr->report.damaged;
	m->files = cr->report.files;
	m->rows = cr->report.rows;
	m->differ = cr->report.differ;
	m->written = cr->report.written;
	m->text = cr->report.text ? cr->report.text : "";
	rep->body_case = ENDOSIM__REPLY__BODY_RECORDS;
	rep->records = m;
}

void control_on_records_check(struct control *c, struct client *cl,
			      const Endosim__Request *req, Endosim__Reply *rep)
{
	struct control_records *cr = c->records;

	(void)cl;
	(void)req;
	records_report_free(&cr->report);
	records_reply(c, rep, records_check(cr->db, RECORDS_DEEP,
					    recording_id(c), &cr->report));
}

void control_on_records_rebuild(struct control *c, struct client *cl,
				const Endosim__Request *req,
				Endosim__Reply *rep)
{
	struct control_records *cr = c->records;
	int e;

	(void)req;
	records_report_free(&cr->report);
	e = records_rebuild(cr->db, recording_id(c), &cr->report);
	if (!e && cr->centre) {
		control_centre_poke(cr->centre); /* all queued again */
	}
	if (!e) {
		log_notice("records %s rebuilt (uid %d): %zu sessions written, "
			   "%zu differed", records_path(cr->db), (int)cl->uid,
			   cr->report.written, cr->report.differ);
	}
	records_reply(c, rep, e);
}

/* Refuses WHAT's PATH unless it is absolute and of a sane length: the
 * daemon's working directory is not the client's. True: refused. */
static bool bad_path(const char *what, const char *path, Endosim__Reply *rep)
{
	if (path && path[0] == '/' && strlen(path) < 4096) {
		return false;
	}
	refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
	       !strcmp(what, "backup") ?
		       "backup: the file's path must be absolute" :
		       "restore: the file's path must be absolute");
	return true;
}

/* Refuses with what a backup or a restore's E means (the file's fault:
 * refused; the daemon's: internal). True: E was an error. */
static bool failed(struct control *c, int e, Endosim__Reply *rep)
{
	if (!e) {
		return false;
	}
	snprintf(c->refusal, sizeof(c->refusal), "%s", why(c->records, e));
	refuse(rep, e == -EEXIST || e == -EBADMSG || e == -EPROTO ||
			    e == -ENOENT || e == -EACCES ?
			    ENDOSIM__STATUS__STATUS_REFUSED :
			    ENDOSIM__STATUS__STATUS_INTERNAL,
	       c->refusal);
	return true;
}

void control_on_records_backup(struct control *c, struct client *cl,
			       const Endosim__Request *req,
			       Endosim__Reply *rep)
{
	struct control_records *cr = c->records;
	const char *path = req->records_backup->path;
	size_t rows;

	records_report_free(&cr->report);
	if (bad_path("backup", path, rep) ||
	    failed(c, records_backup(cr->db, path, &rows), rep)) {
		return;
	}
	log_notice("records %s backed up into %s (uid %d): %zu sessions",
		   records_path(cr->db), path, (int)cl->uid, rows);
	cr->report.rows = rows;
	cr->report.written = rows;
	if (asprintf(&cr->report.text, "backed up %zu sessions into %s\n",
		     rows, path) < 0) {
		cr->report.text = NULL;
	}
	records_reply(c, rep, 0);
}

void control_on_records_restore(struct control *c, struct client *cl,
				const Endosim__Request *req,
				Endosim__Reply *rep)
{
	struct control_records *cr = c->records;
	const char *path = req->records_restore->path;

	records_report_free(&cr->report);
	if (bad_path("restore", path, rep)) {
		return;
	}
	if (recording_id(c)) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "restore: a session is recording; stop it first "
		       "(endoctl session stop)");
		return;
	}
	if (failed(c, records_restore(cr->db, path, 0, &cr->report), rep)) {
		return;
	}
	if (cr->centre) {
		control_centre_poke(cr->centre); /* its queue as restored */
	}
	log_notice("records %s restored from %s (uid %d): %zu sessions "
		   "written from their files", records_path(cr->db), path,
		   (int)cl->uid, cr->report.written);
	records_reply(c, rep, 0);
}
