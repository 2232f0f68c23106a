/*
 * control_centre.c - the rig's sessions sent to a training centre's
 * PostgreSQL (centre.h, control_private.h), by a worker thread of the
 * records: the sessions wait in the rig's own records (records.h, its
 * queue), so that an unreachable centre loses nothing, and the worker
 * sends them in the order they were queued, each once.
 */
#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/log.h"
#include "control/control_private.h"
#include "session/centre.h"
#include "session/records.h"

struct control_centre {
	pthread_t thread;
	pthread_mutex_t lock;
	pthread_cond_t wake;   /* on CLOCK_MONOTONIC */
	bool poked;            /* a session was queued since the last drain */
	bool stop;
	bool down;             /* the last try failed, and was said */
	double retry_s;
	struct records *db;    /* the worker's own */
	struct centre *centre;
	char dir[CONFIG_STR];  /* the session files */
};

/* The report page of S's file, NULL when it cannot be made (said). */
static char *page_of(const struct control_centre *cc,
		     const struct records_session *s)
{
	char path[4096], *html = NULL;
	int e = sessiondir_path(cc->dir, s->e.id, path, sizeof(path));

	if (!e) {
		e = centre_report_page(path, &html);
	}
	if (e) {
		log_warn("centre: session %llu sent without its report: %s",
			 (unsigned long long)s->e.id, strerror(-e));
	}
	return html;
}

/* S written to the centre unless it has it already (its report made only
 * then). 0 or as centre_put(). */
static int send_one(struct control_centre *cc, const struct records_session *s)
{
	char *html;
	int e = centre_has(cc->centre, s->uuid);

	if (e) {
		return e < 0 ? e : 0;
	}
	html = page_of(cc, s);
	e = centre_put(cc->centre, s, html);
	free(html);
	return e;
}

static bool stopping(struct control_centre *cc)
{
	bool stop;

	pthread_mutex_lock(&cc->lock);
	stop = cc->stop;
	pthread_mutex_unlock(&cc->lock);
	return stop;
}

/* Says that the centre failed (once until it answers again). */
static void went_down(struct control_centre *cc, const char *why,
		      size_t waiting)
{
	if (!cc->down) {
		log_warn("%s; %zu sessions wait in the rig's records %s, tried "
			 "again every %g s", why, waiting, records_path(cc->db),
			 cc->retry_s);
	}
	cc->down = true;
}

/* The session at the queue's head, sent or refused for good. */
static int sent_or_refused(struct control_centre *cc,
			   const struct records_session *s, int e)
{
	if (e == -EBADMSG) {
		log_err("centre refused session %llu (%s): %s; it stays in "
			"the rig's records only", (unsigned long long)s->e.id,
			s->uuid, centre_error(cc->centre));
	}
	return records_queue_arrived(cc->db, s->e.id);
}

/* The queue sent, in order, until it is empty (false) or a session
 * cannot be sent now (true: try again later). */
static bool drain(struct control_centre *cc)
{
	struct records_session s;
	size_t waiting = 0, sent = 0;
	int e;

	while (!stopping(cc)) {
		e = records_queue_head(cc->db, &s, &waiting);
		if (e == -ENOENT) {
			break;
		}
		if (e) {
			went_down(cc, records_error(cc->db), waiting);
			return true;
		}
		if ((e = send_one(cc, &s)) && e != -EBADMSG) {
			went_down(cc, centre_error(cc->centre), waiting);
			return true;
		}
		if ((e = sent_or_refused(cc, &s, e))) {
			went_down(cc, records_error(cc->db), waiting);
			return true;
		}
		sent++;
	}
	centre_disconnect(cc->centre);
	if (sent && cc->down) {
		log_notice("centre reachable again: %zu sessions sent", sent);
	}
	cc->down = false;
	return false;
}

/* Waits until poked or stopped; with RETRY, at most retry_s. Locked. */
static void await(struct control_centre *cc, bool retry)
{
	struct timespec until;
	double s = cc->retry_s;

	if (!retry) {
		pthread_cond_wait(&cc->wake, &cc->lock);
		return;
	}
	clock_gettime(CLOCK_MONOTONIC, &until);
	until.tv_sec += (time_t)s;
	until.tv_nsec += (long)((s - (double)(time_t)s) * 1e9);
	if (until.tv_nsec >= 1000000000L) {
		until.tv_sec++;
		until.tv_nsec -= 1000000000L;
	}
	pthread_cond_timedwait(&cc->wake, &cc->lock, &until);
}

static void *centre_main(void *arg)
{
	struct control_centre *cc = arg;
	bool retry;

	pthread_mutex_lock(&cc->lock);
	while (!cc->stop) {
		cc->poked = false;
		pthread_mutex_unlock(&cc->lock);
		retry = drain(cc);
		pthread_mutex_lock(&cc->lock);
		while (!cc->stop && !cc->poked) {
			await(cc, retry);
			if (retry) {
				break;
			}
		}
	}
	pthread_mutex_unlock(&cc->lock);
	return NULL;
}

/* The lock and the condition, its clock the monotonic one. */
static int init_sync(struct control_centre *cc)
{
	pthread_condattr_t attr;
	int e = pthread_condattr_init(&attr);

	if (!e && !(e = pthread_condattr_setclock(&attr, CLOCK_MONOTONIC))) {
		e = pthread_cond_init(&cc->wake, &attr);
	}
	pthread_condattr_destroy(&attr);
	return e ? e : pthread_mutex_init(&cc->lock, NULL);
}

struct control_centre *control_centre_create(const struct config *cfg)
{
	struct control_centre *cc = calloc(1, sizeof(*cc));
	int e;

	if (!cc || init_sync(cc) ||
	    !(cc->db = records_create(cfg->records.database,
				      cfg->session.directory, cfg->records.rig,
				      cfg->session.course)) ||
	    !(cc->centre = centre_create(cfg->records.centre, "endosimd"))) {
		log_err("control: out of memory");
		records_destroy(cc ? cc->db : NULL);
		free(cc);
		return NULL;
	}
	snprintf(cc->dir, sizeof(cc->dir), "%s", cfg->session.directory);
	cc->retry_s = cfg->records.centre_retry_s;
	cc->poked = true;
	if ((e = pthread_create(&cc->thread, NULL, centre_main, cc))) {
		log_err("centre: no thread: %s", strerror(e));
		centre_destroy(cc->centre);
		records_destroy(cc->db);
		free(cc);
		return NULL;
	}
	return cc;
}

void control_centre_destroy(struct control_centre *cc)
{
	if (!cc) {
		return;
	}
	pthread_mutex_lock(&cc->lock);
	cc->stop = true;
	pthread_cond_signal(&cc->wake);
	pthread_mutex_unlock(&cc->lock);
	pthread_join(cc->thread, NULL);
	centre_destroy(cc->centre);
	records_destroy(cc->db);
	pthread_cond_destroy(&cc->wake);
	pthread_mutex_destroy(&cc->lock);
	free(cc);
}

void control_centre_poke(struct control_centre *cc)
{
	pthread_mutex_lock(&cc->lock);
	cc->poked = true;
	pthread_cond_signal(&cc->wake);
	pthread_mutex_unlock(&cc->lock);
}
