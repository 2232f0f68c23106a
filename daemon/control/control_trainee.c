/*
 * control_trainee.c - the control thread's TraineeSessions: a trainee's
 * sessions through the session directory's index (sessionindex.h), which
 * the daemon keeps, as the directory's owner (control_private.h).
 */
#include "control/control_private.h"

void control_free_trainee(struct reply_buf *rb)
{
	free(rb->trainee_infos);
	free(rb->trainee_infos_p);
	free(rb->trainee_metrics);
	free(rb->trainee_entries);
	free(rb->trainee_paths);
	rb->trainee_infos = NULL;
	rb->trainee_paths = NULL;
	rb->trainee_infos_p = NULL;
	rb->trainee_metrics = NULL;
	rb->trainee_entries = NULL;
}

/* Says how the index was found when it had to be brought up to date. */
static void log_index(const char *dir, const struct sessionindex_info *in)
{
	if (in->state != SESSIONINDEX_FRESH) {
		log_info("session index of %s %s: %zu session files read, %zu "
			 "bad lines", dir, sessionindex_state_name(in->state),
			 in->reread, in->bad_lines);
	}
	if (in->write_error) {
		log_warn("session index of %s: cannot write it: %s", dir,
			    strerror(-in->write_error));
	}
}

/* The reply's arrays for N sessions. */
static int alloc_reply(struct reply_buf *rb, size_t n)
{
	size_t k = n ? n : 1;

	rb->trainee_infos = calloc(k, sizeof(*rb->trainee_infos));
	rb->trainee_infos_p = calloc(k, sizeof(*rb->trainee_infos_p));
	rb->trainee_metrics = calloc(k, sizeof(*rb->trainee_metrics));
	rb->trainee_paths = calloc(k, sizeof(*rb->trainee_paths));
	return rb->trainee_infos && rb->trainee_infos_p &&
		       rb->trainee_metrics && rb->trainee_paths ? 0 : -ENOMEM;
}

/* Session E as the reply's S; the recorder's own one as recording. */
static void fill_trainee_session(struct control *c, Endosim__SessionInfo *s,
				 struct sessionindex_entry *e,
				 struct sessionpb_scalars *pm, char *path,
				 const struct recorder_info *ri)
{
	sessionpb_from_entry(s, &e->e);
	sessiondir_path(c->cfg.session.directory, e->e.id, path,
			sizeof(*c->rb.trainee_paths));
	s->path = path;
	s->recording = ri->active && ri->recording && ri->id == e->e.id;
	if (e->has_metrics && !s->recording) {
		sessionpb_from_scalars(pm, &e->m);
		s->metrics = &pm->msg;
		s->duration_s = e->m.duration_s;
		s->records = e->m.records;
		s->drops = e->m.drops;
	}
}

/* The N entries of the index that are WHO's ("": everyone's) as the
 * reply's sessions; how many. */
static size_t fill_sessions(struct control *c, const char *who, size_t n)
{
	struct reply_buf *rb = &c->rb;
	struct recorder_info ri;
	size_t kept = 0;

	recorder_info(c->deps.recorder, &ri);
	for (size_t i = 0; i < n; i++) {
		struct sessionindex_entry *e = &rb->trainee_entries[i];

		if (*who && strcmp(who, e->e.trainee)) {
			continue;
		}
		fill_trainee_session(c, &rb->trainee_infos[kept], e,
				     &rb->trainee_metrics[kept],
				     rb->trainee_paths[kept], &ri);
		rb->trainee_infos_p[kept] = &rb->trainee_infos[kept];
		kept++;
	}
	return kept;
}

void control_on_trainee_sessions(struct control *c, struct client *cl,
				 const Endosim__Request *req,
				 Endosim__Reply *rep)
{
	struct reply_buf *rb = &c->rb;
	char *dir = c->cfg.session.directory;
	struct sessionindex_info info;
	size_t n;
	int r;

	(void)cl;
	control_free_trainee(rb);
	r = sessionindex_load(dir, true, &rb->trainee_entries, &n, &info);
	if (!r) {
		log_index(dir, &info);
		r = alloc_reply(rb, n);
	}
	if (r) {
		snprintf(rb->error, sizeof(rb->error), "%s: %s", dir,
			 strerror(-r));
		control_free_trainee(rb);
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, rb->error);
		return;
	}
	endosim__trainee_reply__init(&rb->trainee);
	rb->trainee.n_sessions = fill_sessions(c, req->trainee_sessions->trainee,
					       n);
	rb->trainee.sessions = rb->trainee_infos_p;
	rb->trainee.directory = dir;
	rb->trainee.course = c->cfg.session.course;
	rb->trainee.index = (char *)sessionindex_state_name(info.state);
	rb->trainee.index_reread = info.reread;
	rb->trainee.index_error = (char *)(info.write_error ?
					   strerror(-info.write_error) : "");
	rep->body_case = ENDOSIM__REPLY__BODY_TRAINEE;
	rep->trainee = &rb->trainee;
}
