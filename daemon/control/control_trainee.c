/*
 * control_trainee.c - the control thread's TraineeSessions: a trainee's
 * sessions from the rig's records (records.h), which the daemon keeps, as
 * the directory's owner (control_private.h).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "control/control_private.h"
#include "session/sessiondir.h"
#include "session/sessionpb.h"

struct control_trainees {
	Endosim__TraineeReply reply;
	Endosim__SessionInfo *infos;
	Endosim__SessionInfo **infos_p;
	struct sessionpb_scalars *metrics;
	char (*paths)[CONFIG_STR + 32];
	struct records_session *entries;
	char error[256];
};

struct control_trainees *control_trainees_create(void)
{
	return calloc(1, sizeof(struct control_trainees));
}

/* Frees the sessions the last reply was made of. */
static void free_trainee(struct control_trainees *rb)
{
	free(rb->infos);
	free(rb->infos_p);
	free(rb->metrics);
	free(rb->entries);
	free(rb->paths);
	rb->infos = NULL;
	rb->paths = NULL;
	rb->infos_p = NULL;
	rb->metrics = NULL;
	rb->entries = NULL;
}

void control_trainees_destroy(struct control_trainees *rb)
{
	if (!rb) {
		return;
	}
	free_trainee(rb);
	free(rb);
}

/* The reply's arrays for N sessions. */
static int alloc_reply(struct control_trainees *rb, size_t n)
{
	size_t k = n ? n : 1;

	rb->infos = calloc(k, sizeof(*rb->infos));
	rb->infos_p = calloc(k, sizeof(*rb->infos_p));
	rb->metrics = calloc(k, sizeof(*rb->metrics));
	rb->paths = calloc(k, sizeof(*rb->paths));
	return rb->infos && rb->infos_p && rb->metrics && rb->paths ? 0
								    : -ENOMEM;
}

/* Session E as the reply's S; the recorder's own one as recording. */
static void fill_trainee_session(struct control *c, Endosim__SessionInfo *s,
				 struct records_session *e,
				 struct sessionpb_scalars *pm, char *path,
				 const struct recorder_info *ri)
{
	sessionpb_from_entry(s, &e->e);
	sessiondir_path(c->cfg.session.directory, e->e.id, path,
			sizeof(*c->trainees->paths));
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

/* The N sessions of the records that are WHO's ("": everyone's) as the
 * reply's sessions; how many. */
static size_t fill_sessions(struct control *c, const char *who, size_t n)
{
	struct control_trainees *rb = c->trainees;
	struct recorder_info ri;
	size_t kept = 0;

	recorder_info(c->deps.recorder, &ri);
	for (size_t i = 0; i < n; i++) {
		struct records_session *e = &rb->entries[i];

		if (*who && strcmp(who, e->e.trainee)) {
			continue;
		}
		fill_trainee_session(c, &rb->infos[kept], e, &rb->metrics[kept],
				     rb->paths[kept], &ri);
		rb->infos_p[kept] = &rb->infos[kept];
		kept++;
	}
	return kept;
}

void control_on_trainee_sessions(struct control *c, struct client *cl,
				 const Endosim__Request *req,
				 Endosim__Reply *rep)
{
	struct control_trainees *rb = c->trainees;
	size_t n;
	int r;

	(void)cl;
	free_trainee(rb);
	r = control_records_list(c, &rb->entries, &n, rb->error,
				 sizeof(rb->error));
	if (!r && (r = alloc_reply(rb, n))) {
		snprintf(rb->error, sizeof(rb->error), "out of memory");
	}
	if (r) {
		free_trainee(rb);
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, rb->error);
		return;
	}
	endosim__trainee_reply__init(&rb->reply);
	rb->reply.n_sessions = fill_sessions(c, req->trainee_sessions->trainee,
					     n);
	rb->reply.sessions = rb->infos_p;
	rb->reply.directory = c->cfg.session.directory;
	rb->reply.course = c->cfg.session.course;
	rep->body_case = ENDOSIM__REPLY__BODY_TRAINEE;
	rep->trainee = &rb->reply;
}
