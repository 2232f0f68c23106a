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

struct control_trainees {
	Endosim__TraineeReply reply;
	struct control_rows rows;  /* what the reply points into */
	char error[256];
};

struct control_trainees *control_trainees_create(void)
{
	return calloc(1, sizeof(struct control_trainees));
}

void control_trainees_destroy(struct control_trainees *rb)
{
	if (!rb) {
		return;
	}
	control_rows_free(&rb->rows);
	free(rb);
}

/* Session S of the reply as the recorder knows it: recording, its
 * measures not yet known; else the END frame's duration and counts. */
static void fill_trainee_session(Endosim__SessionInfo *s,
				 const struct recorder_info *ri)
{
	s->recording = ri->active && ri->recording && ri->id == s->id;
	if (s->recording) {
		s->metrics = NULL;
	} else if (s->metrics) {
		s->duration_s = s->metrics->duration_s;
		s->records = s->metrics->records;
		s->drops = s->metrics->drops;
	}
}

void control_on_trainee_sessions(struct control *c, struct client *cl,
				 const Endosim__Request *req,
				 Endosim__Reply *rep)
{
	const Endosim__TraineeSessions *q = req->trainee_sessions;
	struct control_trainees *rb = c->trainees;
	struct control_rows *rows = &rb->rows;
	struct recorder_info ri;

	(void)cl;
	control_rows_free(rows);
	rows->what = q->facts_unless_course && !c->cfg.session.course[0]
		     ? RECORDS_FACTS : RECORDS_MEASURES;
	rows->paths = true;
	if (control_records_rows(c, *q->trainee ? q->trainee : NULL, rows,
				 rb->error, sizeof(rb->error))) {
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, rb->error);
		return;
	}
	recorder_info(c->deps.recorder, &ri);
	for (size_t i = 0; i < rows->n; i++) {
		fill_trainee_session(rows->infos[i], &ri);
	}
	endosim__trainee_reply__init(&rb->reply);
	rb->reply.n_sessions = rows->n;
	rb->reply.sessions = rows->infos;
	rb->reply.directory = c->cfg.session.directory;
	rb->reply.course = c->cfg.session.course;
	rep->body_case = ENDOSIM__REPLY__BODY_TRAINEE;
	rep->trainee = &rb->reply;
}
