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
#include "session/coursefile.h"

/* The measures a listing judged by a course is sent besides the course's:
 * what the reply says of each session. */
static const char *const always[] = { "duration_s", "records", "drops" };
#define MAX_KEYS (COURSEFILE_MAX_CASES * COURSEFILE_MAX_REQS + 3)

struct control_trainees {
	Endosim__TraineeReply reply;
	struct control_rows rows;  /* what the reply points into */
	struct control_courses courses; /* the groups', likewise */
	struct coursefile course;  /* the daemon's, for its keys */
	const char *keys[MAX_KEYS];
	size_t n_keys;             /* the groups' courses' */
	char error[1024];
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
	control_courses_free(&rb->courses);
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

/*
 * What Q asks of each session into ROWS: the facts alone (no course to
 * judge by), the measures Q names, those the daemon's courses judge by
 * (the groups' courses' keys are rb->keys' first rb->n_keys), or (the
 * daemon's [session] course does not load: the listing says so) every
 * measure.
 */
static void what_asked(struct control *c, const Endosim__TraineeSessions *q,
		       struct control_rows *rows)
{
	struct control_trainees *rb = c->trainees;
	size_t n = rb->n_keys;
	char err[256];

	rows->what = RECORDS_MEASURES;
	rows->keys = NULL;
	if (q->n_measures) {
		rows->keys = (const char *const *)q->measures;
		rows->n_keys = q->n_measures;
		return;
	}
	if (!q->facts_unless_course) {
		return;
	}
	if (!c->cfg.session.course[0] && !n) {
		rows->what = RECORDS_FACTS;
		return;
	}
	if (c->cfg.session.course[0]) {
		const char *mine[MAX_KEYS];
		size_t m;

		if (coursefile_load(&rb->course, c->cfg.session.course, err,
				    sizeof(err))) {
			return;
		}
		m = coursefile_keys(&rb->course, mine, MAX_KEYS);
		for (size_t i = 0; i < m; i++) {
			control_key_add(rb->keys, &n, MAX_KEYS, mine[i]);
		}
	}
	for (size_t i = 0; i < sizeof(always) / sizeof(always[0]); i++) {
		control_key_add(rb->keys, &n, MAX_KEYS, always[i]);
	}
	rows->keys = rb->keys;
	rows->n_keys = n;
}

void control_on_trainee_sessions(struct control *c, struct client *cl,
				 const Endosim__Request *req,
				 Endosim__Reply *rep)
{
	const Endosim__TraineeSessions *q = req->trainee_sessions;
	struct control_trainees *rb = c->trainees;
	struct control_rows *rows = &rb->rows;
	struct recorder_info ri;
	int r;

	control_rows_free(rows);
	control_courses_free(&rb->courses);
	rb->n_keys = 0;
	if (!q->course_given &&
	    (r = control_courses_build(c, cl, q->trainee, &rb->courses,
				       rb->keys, &rb->n_keys, MAX_KEYS - 3,
				       rb->error, sizeof(rb->error)))) {
		refuse(rep, r == -EIO || r == -ENOMEM ?
		       ENDOSIM__STATUS__STATUS_INTERNAL :
		       ENDOSIM__STATUS__STATUS_BAD_VALUE, rb->error);
		return;
	}
	what_asked(c, q, rows);
	rows->paths = true;
	r = control_records_rows(c, *q->trainee ? q->trainee : NULL, rows,
				 rb->error, sizeof(rb->error));
	if (r) {
		refuse(rep, r == -EINVAL ? ENDOSIM__STATUS__STATUS_BAD_VALUE
					 : ENDOSIM__STATUS__STATUS_INTERNAL,
		       rb->error);
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
	rb->reply.n_courses = rb->courses.n;
	rb->reply.courses = rb->courses.entries_p;
	rep->body_case = ENDOSIM__REPLY__BODY_TRAINEE;
	rep->trainee = &rb->reply;
}
