/*
 * test_records.c - the rig's records (records.h) on small session files
 * written here (a HEADER, an END frame or none): each added session comes
 * back as its file says, a trainee named like an SQL injection among
 * them, each judged by a course when one is given; a deleted or damaged
 * database is said by a check and built again from the files; a file
 * changed under it is told apart field by field and fixed; a database made by the first schema opens migrated with its
 * measures intact; one of a newer schema is refused, saying so. A reader
 * listing while a writer commits a session midway (in lockstep, 100
 * times) sees the sessions of its start whole, never an error. For a
 * centre: each session written is queued in the order written, once,
 * leaves the queue when it arrived, and keeps its UUID when the database
 * is built again (and is queued again then, the centre's copy telling).
 * A backup restored after the database was lost: the files' sessions,
 * the backup's marks; junk, a newer schema or nothing refused.
 *
 * Writes to $TMPDIR.
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <sqlite3.h>

#include "proto/session_file.h"
#include "session/metricstext.h"
#include "session/records.h"

#define BOBBY "Robert'); DROP TABLE sessions;--"

static char dir[256], db_path[300];

/* Session ID of TRAINEE on CASE_NAME; with END metrics (cecum_s = ID s,
 * withdrawal_s WITHDRAWAL) when ENDED. */
static void write_session(uint64_t id, const char *trainee, int ended,
			  double withdrawal)
{
	char path[300], header[256], end[4096];
	struct metrics_result m = { .cecum_s = (double)id,
				    .withdrawal_s = withdrawal,
				    .mucosa_seen = 0.5, .records = 1ull << 40,
				    .polyps_seen_mask = 0xffffffffu,
				    .force_episodes = (uint32_t)id,
				    .chase_efficiency = id == 10 ? NAN : 0.25 };
	int fd, n;

	snprintf(path, sizeof(path), "%s/%llu.endoses", dir,
		 (unsigned long long)id);
	n = snprintf(header, sizeof(header), "format=1\nid=%llu\ntrainee=%s\n"
		     "case=normal\nstarted=2026-11-2%lluT10:00:00Z\n",
		     (unsigned long long)id, trainee,
		     (unsigned long long)id % 10);
	fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
	assert_true(fd >= 0);
	assert_int_equal(session_file_write_magic(fd), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_HEADER,
						  header, (uint32_t)n), 0);
	if (ended) {
		n = metricstext_format(&m, end, sizeof(end));
		assert_true(n > 0);
		assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_END,
							  end, (uint32_t)n), 0);
	}
	close(fd);
}

/* The sessions listed equal their files, every field and measure. */
static void check_list(struct records *r, size_t want)
{
	const struct metricstext_field *f;
	size_t nf = metricstext_fields(&f);
	struct records_session *s, file;
	char path[300];
	size_t n;

	assert_int_equal(records_list(r, &s, &n), 0);
	assert_int_equal(n, want);
	for (size_t i = 0; i < n; i++) {
		snprintf(path, sizeof(path), "%s/%llu.endoses", dir,
			 (unsigned long long)s[i].e.id);
		assert_int_equal(records_read_file(path, &file), 0);
		assert_string_equal(s[i].e.trainee, file.e.trainee);
		assert_string_equal(s[i].e.case_name, file.e.case_name);
		assert_string_equal(s[i].e.started, file.e.started);
		assert_int_equal(s[i].e.bytes, file.e.bytes);
		assert_int_equal(s[i].e.ended, file.e.ended);
		assert_int_equal(s[i].checksum, file.checksum);
		assert_string_equal(s[i].rig, "rig-1");
		assert_int_equal(s[i].has_metrics, file.has_metrics);
		for (size_t k = 0; k < nf; k++) {
			double x = metricstext_field_value(&s[i].m, &f[k]);
			double y = metricstext_field_value(&file.m, &f[k]);

			assert_true(x == y || (isnan(x) && isnan(y)));
		}
	}
	free(s);
}

static int setup(void **state)
{
	const char *tmp = getenv("TMPDIR");
	struct records *r;

	snprintf(dir, sizeof(dir), "%s/test_records.XXXXXX",
		 tmp ? tmp : "/tmp");
	assert_non_null(mkdtemp(dir));
	snprintf(db_path, sizeof(db_path), "%s/records.sqlite", dir);
	write_session(1, "Ann Smith", 1, 400);
	write_session(2, "Ann Smith", 0, 0);
	write_session(10, BOBBY, 1, 300);
	r = records_create("records.sqlite", dir, "rig-1", NULL);
	assert_non_null(r);
	*state = r;
	return 0;
}

static int teardown(void **state)
{
	char cmd[400];

	records_destroy(*state);
	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
	return system(cmd);
}

static void test_add_and_list(void **state)
{
	struct records *r = *state;
	struct records_session *s;
	size_t n;

	assert_string_equal(records_path(r), db_path);
	assert_int_equal(records_add(r, 1), 0); /* made: every file in it */
	check_list(r, 3);
	write_session(11, BOBBY, 1, 200);
	assert_int_equal(records_add(r, 11), 0);
	assert_int_equal(records_add(r, 11), 0); /* once, replaced */
	check_list(r, 4);
	assert_int_equal(records_list(r, &s, &n), 0);
	assert_string_equal(s[2].e.trainee, BOBBY); /* as given */
	assert_true(s[2].m.withdrawal_s == 300);
	assert_true(isnan(s[2].m.chase_efficiency)); /* kept as NULL */
	assert_int_equal(s[2].m.records, 1ull << 40);
	assert_int_equal(s[2].m.polyps_seen_mask, 0xffffffffu);
	assert_false(s[1].has_metrics); /* cut short */
	free(s);
	assert_int_equal(records_add(r, 99), -ENOENT);
	check_list(r, 4);
}

/* What records_each() passed: its IDs in order, the measures seen. */
struct seen {
	uint64_t id[8];
	size_t n, with_measures, restarts;
	char trainee[8][64];
};

static int see(void *arg, const struct records_session *s)
{
	struct seen *w = arg;

	if (!s) {
		w->n = 0;
		w->restarts++;
		return 0;
	}
	assert_true(w->n < 8);
	snprintf(w->trainee[w->n], sizeof(w->trainee[0]), "%s", s->e.trainee);
	w->with_measures += s->has_metrics && s->m.withdrawal_s > 0;
	w->id[w->n++] = s->e.id;
	return 0;
}

static int stop_at_two(void *arg, const struct records_session *s)
{
	return see(arg, s) ? -1 : ((struct seen *)arg)->n == 2 ? -EINTR : 0;
}

/* A trainee's sessions alone, by ID; the facts without the measures; a
 * damaged database read again from the start, built from the files. */
static void test_each(void **state)
{
	struct records *r = *state;
	struct seen w = { 0 };

	assert_int_equal(records_each(r, "Ann Smith", RECORDS_MEASURES, NULL,
				      0, see, &w), 0);
	assert_int_equal(w.n, 2);
	assert_int_equal(w.id[0], 1);
	assert_int_equal(w.id[1], 2);
	assert_int_equal(w.with_measures, 1); /* 2 was cut short */
	memset(&w, 0, sizeof(w));
	assert_int_equal(records_each(r, BOBBY, RECORDS_FACTS, NULL, 0, see,
				      &w), 0);
	assert_int_equal(w.n, 1);
	assert_int_equal(w.id[0], 10);
	assert_string_equal(w.trainee[0], BOBBY);
	assert_int_equal(w.with_measures, 0); /* facts alone */
	memset(&w, 0, sizeof(w));
	assert_int_equal(records_each(r, "Ann", RECORDS_FACTS, NULL, 0, see,
				      &w), 0);
	assert_int_equal(w.n, 0); /* exactly the name */
	assert_int_equal(records_each(r, NULL, RECORDS_MEASURES, NULL, 0, see,
				      &w), 0);
	assert_int_equal(w.n, 3);
	assert_int_equal(w.with_measures, 2);
	memset(&w, 0, sizeof(w));
	assert_int_equal(records_each(r, NULL, RECORDS_FACTS, NULL, 0,
				      stop_at_two, &w), -EINTR);
	assert_int_equal(w.n, 2);
	assert_int_equal(w.restarts, 0);
}

/* The measures named alone, the others 0; a key naming none refused. */
static int see_some(void *arg, const struct records_session *s)
{
	struct seen *w = arg;

	assert_non_null(s);
	if (s->has_metrics) {
		assert_true(s->m.withdrawal_s == (s->e.id == 1 ? 400 : 300));
		assert_true(s->m.cecum_s == 0);   /* not asked */
		assert_true(s->m.mucosa_seen == 0.5);
		w->with_measures++;
	}
	w->id[w->n++] = s->e.id;
	return 0;
}

static void test_each_some(void **state)
{
	static const char *const keys[] = { "withdrawal_s", "mucosa_seen" };
	static const char *const bad[] = { "withdrawal_s",
					   "x FROM trainees; --" };
	struct records *r = *state;
	struct seen w = { 0 };

	assert_int_equal(records_each(r, NULL, RECORDS_MEASURES, keys, 2,
				      see_some, &w), 0);
	assert_int_equal(w.n, 3);
	assert_int_equal(w.with_measures, 2);
	assert_int_equal(records_each(r, NULL, RECORDS_MEASURES, bad, 2,
				      see_some, &w), -EINVAL);
	assert_non_null(strstr(records_error(r), "no measure 'x FROM"));
}

/*
 * Concurrency in lockstep: a writer (a second struct records on the same
 * database, as endosimd beside a reader) adds session N + 1 while a
 * reader is midway through its list of N, at its first row: each pass
 * must see the N sessions of its start whole (every row once, in order,
 * with its own measures: cecum_s is the ID), never the one committed
 * meanwhile nor an error. Each step waits for the other, not for time.
 */
struct lockstep {
	pthread_mutex_t lock;
	pthread_cond_t cond;
	uint64_t want;     /* the session the writer is to add; 0: none */
	uint64_t added;    /* the last it added */
	int error;         /* its records_add()'s */
	bool done;
	struct records *writer;
};

static void *writer_thread(void *arg)
{
	struct lockstep *ls = arg;

	pthread_mutex_lock(&ls->lock);
	while (!ls->done) {
		uint64_t id = ls->want;

		if (!id || id == ls->added) {
			pthread_cond_wait(&ls->cond, &ls->lock);
			continue;
		}
		pthread_mutex_unlock(&ls->lock);
		write_session(id, id % 2 ? "Ann Smith" : BOBBY, 1, 400);
		ls->error = records_add(ls->writer, id);
		pthread_mutex_lock(&ls->lock);
		ls->added = id;
		pthread_cond_broadcast(&ls->cond);
	}
	pthread_mutex_unlock(&ls->lock);
	return NULL;
}

struct pass {
	struct lockstep *ls;
	uint64_t next;     /* the ID the next row must have */
	bool poked;
};

static int read_row_checked(void *arg, const struct records_session *s)
{
	struct pass *p = arg;
	struct lockstep *ls = p->ls;

	assert_non_null(s); /* no damage: never read again */
	assert_int_equal(s->e.id, p->next++);
	assert_true(s->has_metrics);
	assert_true(s->m.cecum_s == (double)s->e.id);
	assert_string_equal(s->e.trainee, s->e.id % 2 ? "Ann Smith" : BOBBY);
	if (!p->poked) { /* midway: the writer commits the next one now */
		p->poked = true;
		pthread_mutex_lock(&ls->lock);
		ls->want = ls->added + 1;
		pthread_cond_broadcast(&ls->cond);
		while (ls->added != ls->want) {
			pthread_cond_wait(&ls->cond, &ls->lock);
		}
		pthread_mutex_unlock(&ls->lock);
		assert_int_equal(ls->error, 0);
	}
	return 0;
}

static void test_concurrent_reads(void **state)
{
	struct records *r = *state;
	struct lockstep ls = { .added = 1 };
	pthread_t t;
	char cmd[400];

	snprintf(cmd, sizeof(cmd), "rm -f '%s'/*.endoses", dir);
	assert_int_equal(system(cmd), 0);
	write_session(1, "Ann Smith", 1, 400);
	assert_int_equal(records_add(r, 1), 0);
	ls.writer = records_create("records.sqlite", dir, "rig-1", NULL);
	assert_non_null(ls.writer);
	pthread_mutex_init(&ls.lock, NULL);
	pthread_cond_init(&ls.cond, NULL);
	assert_int_equal(pthread_create(&t, NULL, writer_thread, &ls), 0);
	for (uint64_t n = 1; n <= 100; n++) {
		struct pass p = { .ls = &ls, .next = 1 };

		assert_int_equal(records_each(r, NULL, RECORDS_MEASURES,
					      NULL, 0, read_row_checked,
					      &p), 0);
		assert_int_equal(p.next, n + 1); /* the N of its start */
		assert_int_equal(ls.added, n + 1); /* one more committed */
	}
	pthread_mutex_lock(&ls.lock);
	ls.done = true;
	pthread_cond_broadcast(&ls.cond);
	pthread_mutex_unlock(&ls.lock);
	pthread_join(t, NULL);
	records_destroy(ls.writer);
	check_list(r, 101);
}

/* A session added with its writer's checksum: the file not read for it;
 * the right one agrees with a deep check, a wrong one is found by it. */
static void test_add_summed(void **state)
{
	struct records *r = *state;
	struct records_report rep;
	char path[300];
	uint64_t sum, whole;

	assert_int_equal(records_add(r, 1), 0);
	write_session(11, "Ann Smith", 1, 200);
	snprintf(path, sizeof(path), "%s/11.endoses", dir);
	assert_int_equal(records_file_checksum(path, &whole), 0);
	sum = records_checksum(RECORDS_CHECKSUM_SEED, "", 0);
	assert_true(sum == RECORDS_CHECKSUM_SEED);
	sum = whole;
	assert_int_equal(records_add_summed(r, 11, &sum), 0);
	assert_int_equal(records_check(r, RECORDS_DEEP, 0, &rep), 0);
	assert_int_equal(rep.differ, 0);
	records_report_free(&rep);
	sum = whole ^ 1;
	assert_int_equal(records_add_summed(r, 11, &sum), 0);
	assert_int_equal(records_check(r, RECORDS_DEEP, 0, &rep), 0);
	assert_int_equal(rep.differ, 1);
	assert_non_null(strstr(rep.text, "session 11: the database's row "
			       "differs from its file: checksum"));
	records_report_free(&rep);
}

static void test_judgement(void **state)
{
	struct records_report rep;
	struct records *r;
	struct records_session *s;
	char course[300];
	FILE *f;
	size_t n;

	(void)state;
	snprintf(course, sizeof(course), "%s/t.course", dir);
	f = fopen(course, "w");
	assert_non_null(f);
	fputs("[course]\nname = t\nconsecutive = 1\n[case normal]\n"
	      "withdrawal_s >= 360\n", f);
	fclose(f);
	r = records_create("records.sqlite", dir, "rig-1", course);
	assert_non_null(r);
	assert_int_equal(records_list(r, &s, &n), 0);
	assert_int_equal(n, 3);
	assert_string_equal(s[0].judgement, "t: passed"); /* 400 s */
	assert_string_equal(s[1].judgement, "");          /* no END */
	assert_string_equal(s[2].judgement, "t: failed"); /* 300 s */
	free(s);
	records_destroy(r);
	r = *state; /* no course: a rebuild judges none */
	assert_int_equal(records_rebuild(r, 0, &rep), 0);
	records_report_free(&rep);
	assert_int_equal(records_list(r, &s, &n), 0);
	assert_string_equal(s[0].judgement, "");
	free(s);
}

/* A check that finds DIFFER things, the first line holding WHAT. */
static void check_finds(struct records *r, unsigned flags, size_t differ,
			const char *what)
{
	struct records_report rep;

	assert_int_equal(records_check(r, flags, 0, &rep), 0);
	if (!strstr(rep.text, what) || rep.differ != differ) {
		print_message("found: %s", rep.text);
	}
	assert_int_equal(rep.differ, differ);
	assert_non_null(strstr(rep.text, what));
	records_report_free(&rep);
}

static void test_check_and_fix(void **state)
{
	struct records *r = *state;
	char path[300];

	check_finds(r, RECORDS_DEEP, 3, "is missing"); /* not made */
	assert_int_equal(access(db_path, F_OK), -1);
	check_finds(r, RECORDS_FIX, 3, "is missing");
	check_finds(r, RECORDS_DEEP, 0, "");
	write_session(1, "Ann Smith", 1, 401); /* same size, one measure */
	check_finds(r, 0, 0, ""); /* the size alone does not tell */
	check_finds(r, RECORDS_DEEP, 1, "checksum, withdrawal_s");
	write_session(12, "Cy", 0, 0);
	snprintf(path, sizeof(path), "%s/10.endoses", dir);
	assert_int_equal(unlink(path), 0);
	check_finds(r, RECORDS_DEEP | RECORDS_FIX, 3, "session 10: in the "
		    "database, but its file is gone");
	check_finds(r, RECORDS_DEEP, 0, "");
	check_list(r, 3);
}

/* Overwrites the database at OFF with TEXT. */
static void damage(long off, const char *text)
{
	int fd = open(db_path, O_WRONLY);

	assert_true(fd >= 0);
	assert_true(pwrite(fd, text, strlen(text), off) ==
		    (ssize_t)strlen(text));
	close(fd);
}

static void test_missing_and_damaged(void **state)
{
	struct records *r = *state;
	struct records_report rep;

	check_list(r, 3);
	assert_int_equal(unlink(db_path), 0);
	check_list(r, 3); /* built again */
	damage(0, "SQLite fermat 3");
	check_finds(r, RECORDS_DEEP, 3, "damaged");
	assert_int_equal(records_rebuild(r, 0, &rep), 0);
	assert_true(rep.damaged);
	assert_int_equal(rep.written, 3);
	records_report_free(&rep);
	assert_int_equal(access(db_path, F_OK), 0);
	check_finds(r, RECORDS_DEEP, 0, "");
	damage(0, "garbage garbage");
	check_list(r, 3); /* a listing rebuilds it too */
	check_finds(r, RECORDS_DEEP, 0, "");
	damage(0, "garbage garbage");
	check_finds(r, RECORDS_FIX, 3, "damaged"); /* start-up's: made again */
	check_finds(r, RECORDS_DEEP, 0, "");
	/* the recording session left out */
	assert_int_equal(records_rebuild(r, 10, &rep), 0);
	assert_int_equal(rep.written, 2);
	records_report_free(&rep);
	check_finds(r, RECORDS_DEEP, 1, "session 10: not in the database");
}

/* The first schema as endosim 1 made it, frozen here. */
static const char first_schema[] =
	"CREATE TABLE trainees (id INTEGER PRIMARY KEY,"
	" name TEXT NOT NULL UNIQUE);"
	"CREATE TABLE cases (id INTEGER PRIMARY KEY,"
	" name TEXT NOT NULL UNIQUE);"
	"CREATE TABLE sessions (id INTEGER PRIMARY KEY,"
	" trainee_id INTEGER NOT NULL REFERENCES trainees(id),"
	" case_id INTEGER NOT NULL REFERENCES cases(id),"
	" started TEXT NOT NULL, ended INTEGER NOT NULL,"
	" path TEXT NOT NULL, bytes INTEGER NOT NULL,"
	" checksum INTEGER NOT NULL, rig TEXT NOT NULL, judgement TEXT);"
	"CREATE TABLE measures (session_id INTEGER PRIMARY KEY"
	" REFERENCES sessions(id), duration_s REAL, records INTEGER,"
	" drops INTEGER, cecum_s REAL, insertion_s REAL, withdrawal_s REAL,"
	" max_tip_s_m REAL, peak_insertion_n REAL, mean_insertion_n REAL,"
	" force_episodes INTEGER, force_episode_s REAL, loop_episodes INTEGER,"
	" longest_loop_s REAL, largest_loop_m REAL, pain_share REAL,"
	" peak_pain REAL, pain_episodes INTEGER, pain_s_looping REAL,"
	" pain_s_straightening REAL, pain_s_insufflation REAL,"
	" pain_s_tip REAL, gloucester INTEGER, gas_used_l REAL,"
	" peak_gas_pressure_pa REAL, position_changes INTEGER,"
	" hand_uses INTEGER, perforations INTEGER, lumen_lost_s REAL,"
	" mucosa_seen REAL, polyps_seen INTEGER, polyps_total INTEGER,"
	" polyps_seen_mask INTEGER, shaft_in_m REAL, tip_in_m REAL,"
	" chase_efficiency REAL, shaft_idle_m REAL, loop_s REAL,"
	" retraction_m REAL, tip_retraction_m REAL,"
	" retraction_efficiency REAL, clear_view REAL, lost_views INTEGER,"
	" mucosa_per_min REAL, mucosa_seen_anal_canal REAL,"
	" mucosa_seen_rectum REAL, mucosa_seen_sigmoid REAL,"
	" mucosa_seen_descending REAL, mucosa_seen_splenic_flexure REAL,"
	" mucosa_seen_transverse REAL, mucosa_seen_hepatic_flexure REAL,"
	" mucosa_seen_ascending REAL, mucosa_seen_cecum REAL);"
	"INSERT INTO trainees VALUES (1, 'Old Timer');"
	"INSERT INTO cases VALUES (1, 'normal');"
	"INSERT INTO sessions VALUES (5, 1, 1, '2025-01-01T10:00:00Z', 1,"
	" 'x/5.endoses', 1234, 99, 'rig-0', NULL);"
	"INSERT INTO measures (session_id, cecum_s, withdrawal_s,"
	" polyps_seen) VALUES (5, 321.5, 410.25, 3);"
	"PRAGMA user_version = 1;";

/* Runs SQL on the database file, outside records.h. */
static void run_sql(const char *sql)
{
	sqlite3 *db;

	assert_int_equal(sqlite3_open(db_path, &db), SQLITE_OK);
	assert_int_equal(sqlite3_exec(db, sql, NULL, NULL, NULL), SQLITE_OK);
	sqlite3_close(db);
}

static int version(void)
{
	sqlite3_stmt *st;
	sqlite3 *db;
	int v;

	assert_int_equal(sqlite3_open(db_path, &db), SQLITE_OK);
	assert_int_equal(sqlite3_prepare_v2(db, "PRAGMA user_version", -1,
					    &st, NULL), SQLITE_OK);
	assert_int_equal(sqlite3_step(st), SQLITE_ROW);
	v = sqlite3_column_int(st, 0);
	sqlite3_finalize(st);
	sqlite3_close(db);
	return v;
}

static void test_migrate(void **state)
{
	struct records *r = *state;
	struct records_session *s;
	size_t n;

	run_sql(first_schema);
	assert_int_equal(records_list(r, &s, &n), 0);
	assert_int_equal(version(), RECORDS_SCHEMA_VERSION);
	assert_int_equal(n, 1); /* a listing is the database's */
	assert_int_equal(s[0].e.id, 5);
	assert_string_equal(s[0].e.trainee, "Old Timer");
	assert_string_equal(s[0].rig, "rig-0");
	assert_int_equal(s[0].e.bytes, 1234);
	assert_true(s[0].has_metrics);
	assert_true(s[0].m.cecum_s == 321.5);
	assert_true(s[0].m.withdrawal_s == 410.25);
	assert_int_equal(s[0].m.polyps_seen, 3);
	assert_int_equal(strlen(s[0].uuid), 36); /* made for an old row */
	free(s);
	run_sql("SELECT * FROM sessions INDEXED BY sessions_by_trainee;");
	assert_int_equal(records_add(r, 1), 0); /* the new schema's rows */
	assert_int_equal(records_list(r, &s, &n), 0);
	assert_int_equal(n, 2);
	free(s);
}

static void test_newer_refused(void **state)
{
	struct records *r = *state;
	struct records_session *s;
	struct records_report rep;
	size_t n;

	check_list(r, 3);
	run_sql("PRAGMA user_version = 99;");
	assert_int_equal(records_list(r, &s, &n), -EPROTO);
	assert_non_null(strstr(records_error(r), "version 99, newer than"));
	assert_int_equal(records_add(r, 1), -EPROTO);
	assert_int_equal(records_check(r, RECORDS_FIX, 0, &rep), -EPROTO);
	records_report_free(&rep);
	assert_int_equal(version(), 99); /* left as it was */
}

/* The session at the queue's head is ID, WAITING of them wait. */
static void head_is(struct records *r, uint64_t id, size_t waiting)
{
	struct records_session s;
	size_t n;

	assert_int_equal(records_queue_head(r, &s, &n), 0);
	assert_int_equal(s.e.id, id);
	assert_int_equal(n, waiting);
}

static void test_centre_queue(void **state)
{
	struct records *r = *state;
	struct records_session s, *all;
	char uuid[3][37];
	size_t n;

	assert_int_equal(records_add(r, 1), 0); /* made: no centre, no queue */
	assert_int_equal(records_queue_head(r, &s, &n), -ENOENT);
	assert_int_equal(n, 0);
	records_set_centre(r, true);
	assert_int_equal(records_add(r, 10), 0);
	assert_int_equal(records_add(r, 1), 0);
	assert_int_equal(records_add(r, 10), 0); /* keeps its place */
	head_is(r, 10, 2);
	assert_int_equal(records_queue_arrived(r, 10), 0);
	head_is(r, 1, 1);
	assert_int_equal(records_queue_unsent(r, &n), 0); /* 2 too */
	assert_int_equal(n, 2);
	head_is(r, 1, 2);
	assert_int_equal(records_queue_arrived(r, 1), 0);
	assert_int_equal(records_queue_arrived(r, 2), 0);
	assert_int_equal(records_queue_unsent(r, &n), 0);
	assert_int_equal(n, 0); /* every one arrived */

	assert_int_equal(records_list(r, &all, &n), 0);
	assert_int_equal(n, 3);
	for (size_t i = 0; i < n; i++) {
		memcpy(uuid[i], all[i].uuid, sizeof(uuid[i]));
		assert_int_equal(strlen(uuid[i]), 36);
		assert_int_equal(uuid[i][14], '8');
		records_uuid(&all[i], s.uuid);
		assert_string_equal(s.uuid, uuid[i]);
	}
	assert_string_not_equal(uuid[0], uuid[1]);
	snprintf(all[0].rig, sizeof(all[0].rig), "rig-2");
	records_uuid(&all[0], s.uuid);
	assert_string_not_equal(s.uuid, uuid[0]); /* another rig's */
	free(all);

	assert_int_equal(unlink(db_path), 0);
	assert_int_equal(records_queue_head(r, &s, &n), -ENOENT);
	assert_int_equal(records_queue_arrived(r, 1), 0);
	assert_int_equal(access(db_path, F_OK), -1); /* nor made it again */
	assert_int_equal(records_list(r, &all, &n), 0); /* built again: */
	head_is(r, 1, 3);                               /* all queued, */
	for (size_t i = 0; i < n; i++) { /* with the UUIDs they had */
		assert_string_equal(all[i].uuid, uuid[i]);
	}
	free(all);
	assert_int_equal(unlink(db_path), 0);
	records_set_centre(r, false);
	assert_int_equal(records_list(r, &all, &n), 0); /* no centre: */
	free(all);
	assert_int_equal(records_queue_head(r, &s, &n), -ENOENT); /* none */
}

/* A file of TEXT at PATH. */
static void write_text(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");

	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

/*
 * A backup, online, into a new file of its own (one file: in rollback
 * journal mode, no WAL), never over a file or a link; restored after the database was lost,
 * a session recorded since and one whose file went: the sessions are the
 * files' again, and what only the database held (the centre's marks and
 * queue) is the backup's. A file that is not a records database, one of a
 * newer schema, or none: refused, the database as it was.
 */
static void test_backup_restore(void **state)
{
	struct records *r = *state;
	struct records_report rep;
	char backup[320], other[400], link[320];
	size_t n;

	records_set_centre(r, true);
	assert_int_equal(records_add(r, 1), 0);
	assert_int_equal(records_add(r, 2), 0);
	assert_int_equal(records_add(r, 10), 0);
	assert_int_equal(records_queue_arrived(r, 10), 0); /* the db's alone */
	snprintf(backup, sizeof(backup), "%s/backup.sqlite", dir);
	assert_int_equal(records_backup(r, backup, &n), 0);
	assert_int_equal(n, 3);
	{
		sqlite3_stmt *st;
		sqlite3 *db;

		assert_int_equal(sqlite3_open(backup, &db), SQLITE_OK);
		assert_int_equal(sqlite3_prepare_v2(db, "PRAGMA journal_mode",
						    -1, &st, NULL), SQLITE_OK);
		assert_int_equal(sqlite3_step(st), SQLITE_ROW);
		assert_string_equal(sqlite3_column_text(st, 0), "delete");
		sqlite3_finalize(st);
		sqlite3_close(db);
	}
	assert_int_equal(records_backup(r, backup, &n), -EEXIST);
	snprintf(link, sizeof(link), "%s/link.sqlite", dir);
	assert_int_equal(symlink("/nonexistent/x.sqlite", link), 0);
	assert_int_equal(records_backup(r, link, &n), -EEXIST);

	assert_int_equal(unlink(db_path), 0); /* lost */
	write_session(11, "Ann Smith", 1, 200); /* recorded since */
	snprintf(other, sizeof(other), "%s/2.endoses", dir);
	assert_int_equal(unlink(other), 0); /* gone since */
	assert_int_equal(records_restore(r, backup, 0, &rep), 0);
	assert_int_equal(rep.written, 2);
	records_report_free(&rep);
	check_list(r, 3);
	head_is(r, 1, 2); /* 1 as backed up, 11 after; 10 had arrived */
	assert_int_equal(records_queue_arrived(r, 1), 0);
	head_is(r, 11, 1);

	snprintf(other, sizeof(other), "%s/junk.sqlite", dir);
	write_text(other, "not a database, though named like one\n");
	assert_int_equal(records_restore(r, other, 0, &rep), -EBADMSG);
	assert_non_null(strstr(records_error(r), "not a sound records"));
	records_report_free(&rep);
	snprintf(other, sizeof(other), "%s/none.sqlite", dir);
	assert_int_equal(records_restore(r, other, 0, &rep), -ENOENT);
	records_report_free(&rep);
	assert_int_equal(records_backup(r, other, &n), 0);
	{
		sqlite3 *db;

		assert_int_equal(sqlite3_open(other, &db), SQLITE_OK);
		assert_int_equal(sqlite3_exec(db, "PRAGMA user_version = 99",
					      NULL, NULL, NULL), SQLITE_OK);
		sqlite3_close(db);
	}
	assert_int_equal(records_restore(r, other, 0, &rep), -EPROTO);
	records_report_free(&rep);
	check_list(r, 3); /* as it was */
	head_is(r, 11, 1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_add_and_list, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_each, setup, teardown),
		cmocka_unit_test_setup_teardown(test_each_some, setup, teardown),
		cmocka_unit_test_setup_teardown(test_add_summed, setup, teardown),
		cmocka_unit_test_setup_teardown(test_concurrent_reads, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_judgement, setup, teardown),
		cmocka_unit_test_setup_teardown(test_check_and_fix, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_missing_and_damaged, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_migrate, setup, teardown),
		cmocka_unit_test_setup_teardown(test_newer_refused, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_centre_queue, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_backup_restore, setup,
						teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
