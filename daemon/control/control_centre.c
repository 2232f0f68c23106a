/*
 * control_centre.c - the rig's sessions sent to a training centre's
 * PostgreSQL (centre.h, control_private.h), and the rig's accounts kept
 * with the centre's people, by a worker thread of the records: the
 * sessions and the changes of the accounts wait in the rig's own
 * databases (records.h, accounts.h: their queues), so that an unreachable
 * centre loses nothing, and the worker sends them in the order they were
 * queued, each once; then, when the centre's people changed and none of
 * the rig's changes wait, it copies them down.
 */
#include <errno.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "base/log.h"
#include "control/control_private.h"
#include "session/accounts.h"
#include "session/centre.h"
#include "session/records.h"

struct control_centre {
	pthread_t thread;
	pthread_mutex_t lock;
	pthread_cond_t wake;   /* on CLOCK_MONOTONIC */
	bool poked;            /* something was queued since the last round */
	bool stop;
	bool down;             /* the last round failed, and was said */
	bool people;           /* the rig's accounts are kept with the centre */
	char version[32];      /* of the centre's people last copied to them */
	atomic_uint copies;    /* of the people made so far */
	int wake_fd;           /* the control thread's eventfd; -1: none */
	double retry_s;
	struct records *db;    /* the worker's own */
	struct accounts *accounts; /* the worker's own */
	struct centre *centre;
	char url[CONFIG_STR];
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

/* Says that the centre failed, WHY (once until it answers again). */
static void went_down(struct control_centre *cc, const char *why)
{
	struct records_session s;
	struct accounts_queued q;
	size_t sessions = 0, changes = 0;
	char words[1024];

	if (cc->down) {
		return;
	}
	cc->down = true;
	snprintf(words, sizeof(words), "%s", why); /* the calls below reset
						      their errors */
	records_queue_head(cc->db, &s, &sessions);
	if (cc->people) {
		accounts_queue_head(cc->accounts, &q, &changes);
	}
	log_warn("%s; %zu sessions wait in the rig's records %s, %zu changes "
		 "in its accounts; tried again every %g s", words, sessions,
		 records_path(cc->db), changes, cc->retry_s);
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

/* The sessions queued sent, in order, *SENT of them: NULL, or why one
 * cannot be sent now (try again later). */
static const char *send_sessions(struct control_centre *cc, size_t *sent)
{
	struct records_session s;
	size_t waiting = 0;
	int e;

	while (!stopping(cc)) {
		e = records_queue_head(cc->db, &s, &waiting);
		if (e == -ENOENT) {
			break;
		}
		if (e) {
			return records_error(cc->db);
		}
		if ((e = send_one(cc, &s)) && e != -EBADMSG) {
			return centre_error(cc->centre);
		}
		if ((e = sent_or_refused(cc, &s, e))) {
			return records_error(cc->db);
		}
		(*sent)++;
	}
	return NULL;
}

/* What the centre made of the change Q, said where it is not what the
 * rig made (the centre's people stand: the next copy brings them). */
static void said(struct control_centre *cc, const struct accounts_queued *q,
		 enum centre_outcome out)
{
	static struct log_ratelimit rl = LOG_RATELIMIT_INIT(10, 5);
	const struct accounts_change *ch = &q->ch;
	bool add = ch->op == ACCOUNTS_USER_ADD || ch->op == ACCOUNTS_GROUP_ADD;
	const char *name = ch->op == ACCOUNTS_GROUP_ADD ? ch->group : ch->name;

	if (out == CENTRE_REFUSED) {
		log_ratelimited(&rl, LOG_NOTICE, "centre: %s %s%s%s: not "
				"applied, the centre's people stand: %s",
				accounts_op_name(ch->op), name, *ch->group &&
				!add ? " in " : "", add ? "" : ch->group,
				centre_error(cc->centre));
	} else if (out == CENTRE_UNCHANGED && add) {
		log_ratelimited(&rl, LOG_NOTICE, "centre: %s %s: the centre "
				"has one of that name already, and keeps it",
				accounts_op_name(ch->op), name);
	}
}

/* The changes of the rig's accounts queued sent, in order, *SENT of
 * them: NULL, or why one cannot be sent now. */
static const char *send_changes(struct control_centre *cc, size_t *sent)
{
	struct accounts_queued q;
	enum centre_outcome out;
	size_t waiting;
	int e;

	while (!stopping(cc)) {
		e = accounts_queue_head(cc->accounts, &q, &waiting);
		if (e == -ENOENT) {
			break;
		}
		if (e) {
			return accounts_error(cc->accounts);
		}
		if (centre_change(cc->centre, records_rig(cc->db), &q, &out)) {
			return centre_error(cc->centre);
		}
		said(cc, &q, out);
		if (accounts_queue_arrived(cc->accounts, q.id)) {
			return accounts_error(cc->accounts);
		}
		(*sent)++;
	}
	return NULL;
}

/* The centre's people copied to the rig's accounts when they changed
 * since the last copy: NULL, or why not now. Changes of the rig queued
 * meanwhile put it off (-EBUSY) until they arrive. */
static const char *copy_people(struct control_centre *cc)
{
	struct centre_people p;
	size_t people = 0;
	char now[32];
	int e;

	if (centre_people_version(cc->centre, now, sizeof(now))) {
		return centre_error(cc->centre);
	}
	if (!strcmp(cc->version, now)) {
		return NULL;
	}
	if (centre_people(cc->centre, &p)) {
		return centre_error(cc->centre);
	}
	for (size_t i = 0; i < p.n; i++) {
		people += p.ch[i].op == ACCOUNTS_USER_ADD;
	}
	e = accounts_replace(cc->accounts, p.version, p.ch, p.n);
	if (!e) {
		uint64_t one = 1;

		snprintf(cc->version, sizeof(cc->version), "%s", p.version);
		log_info("centre: the rig's accounts are the centre's people "
			 "now: %zu people (version %s)", people, p.version);
		atomic_fetch_add(&cc->copies, 1);
		if (cc->wake_fd >= 0 &&
		    write(cc->wake_fd, &one, sizeof(one)) < 0) {
			/* full: the control thread is woken already */
		}
	}
	centre_people_free(&p);
	return e && e != -EBUSY ? accounts_error(cc->accounts) : NULL;
}

/* With QUEUES the sessions and the changes sent (counted); the people
 * copied: NULL, or why not now. */
static const char *try_round(struct control_centre *cc, bool queues,
			     size_t *sessions, size_t *changes)
{
	const char *why = queues ? send_sessions(cc, sessions) : NULL;

	if (!why && cc->people && queues) {
		why = send_changes(cc, changes);
	}
	if (!why && cc->people) {
		why = copy_people(cc);
	}
	return why;
}

/*
 * One round: the queues looked at when something was queued (POKED),
 * and after a failure; the people every time (a quiet round is one
 * question to the centre). When it fails on the connection of an earlier
 * round (one the server may have closed since, a restart), once more at
 * once on a new one, so that the log says how the centre is now.
 */
static void one_round(struct control_centre *cc, bool poked)
{
	size_t sessions = 0, changes = 0;
	bool held = centre_connected(cc->centre), queues = poked || cc->down;
	const char *why = try_round(cc, queues, &sessions, &changes);

	if (why && held) {
		centre_disconnect(cc->centre);
		why = try_round(cc, true, &sessions, &changes);
	}
	if (why) {
		went_down(cc, why);
		return;
	}
	if (cc->down) {
		log_notice("centre reachable again: %zu sessions sent, %zu "
			   "changes of the accounts", sessions, changes);
	}
	cc->down = false;
}

/* Waits until poked or stopped, at most retry_s. Locked. */
static void await(struct control_centre *cc)
{
	struct timespec until;
	double s = cc->retry_s;

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

	/* before any copy: a copy of a centre that lacks the rig's own
	 * accounts would remove them */
	cc->people = !accounts_centre(cc->accounts, cc->url) &&
		     !accounts_copy_version(cc->accounts, cc->version,
					    sizeof(cc->version));
	if (!cc->people) {
		log_err("centre: the rig's accounts: %s; they are not kept "
			"with the centre's people",
			accounts_error(cc->accounts));
	}
	pthread_mutex_lock(&cc->lock);
	while (!cc->stop) {
		bool poked = cc->poked;

		cc->poked = false;
		pthread_mutex_unlock(&cc->lock);
		one_round(cc, poked);
		pthread_mutex_lock(&cc->lock);
		if (!cc->stop && !cc->poked) {
			await(cc);
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

/* What the worker holds, freed (NULL fine). */
static void free_worker(struct control_centre *cc)
{
	if (cc) {
		centre_destroy(cc->centre);
		accounts_destroy(cc->accounts);
		records_destroy(cc->db);
		free(cc);
	}
}

struct control_centre *control_centre_create(const struct config *cfg,
					     int wake_fd)
{
	struct control_centre *cc = calloc(1, sizeof(*cc));
	char path[3 * CONFIG_STR];
	int e;

	control_accounts_path(cfg, path, sizeof(path));
	if (!cc || init_sync(cc) ||
	    !(cc->db = records_create(cfg->records.database,
				      cfg->session.directory, cfg->records.rig,
				      cfg->session.course)) ||
	    !(cc->accounts = accounts_create(path)) ||
	    !(cc->centre = centre_create(cfg->records.centre, "endosimd"))) {
		log_err("control: out of memory, or libsodium cannot start");
		free_worker(cc);
		return NULL;
	}
	snprintf(cc->dir, sizeof(cc->dir), "%s", cfg->session.directory);
	snprintf(cc->url, sizeof(cc->url), "%s", cfg->records.centre);
	cc->retry_s = cfg->records.centre_retry_s;
	cc->wake_fd = wake_fd;
	cc->poked = true;
	if ((e = pthread_create(&cc->thread, NULL, centre_main, cc))) {
		log_err("centre: no thread: %s", strerror(e));
		free_worker(cc);
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
	pthread_cond_destroy(&cc->wake);
	pthread_mutex_destroy(&cc->lock);
	free_worker(cc);
}

unsigned control_centre_copies(struct control_centre *cc)
{
	return atomic_load(&cc->copies);
}

void control_centre_poke(struct control_centre *cc)
{
	pthread_mutex_lock(&cc->lock);
	cc->poked = true;
	pthread_cond_signal(&cc->wake);
	pthread_mutex_unlock(&cc->lock);
}
