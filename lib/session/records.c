/* records.c - see records.h. */
#include "session/records.h"
#include "session/coursefile.h"
#include "session/metricstext.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>

#include <sqlite3.h>


#define BUSY_MS 5000

/*
 * The migrations, in order: step I takes user_version I to I + 1. A
 * released step never changes; a new measure is a new step adding its
 * column ("ALTER TABLE measures ADD COLUMN name REAL;").
 */
static const char *const migrations[RECORDS_SCHEMA_VERSION] = {
	/* 1: the first schema */
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
	" REFERENCES sessions(id),"
	" duration_s REAL, records INTEGER, drops INTEGER, cecum_s REAL,"
	" insertion_s REAL, withdrawal_s REAL, max_tip_s_m REAL,"
	" peak_insertion_n REAL, mean_insertion_n REAL,"
	" force_episodes INTEGER, force_episode_s REAL,"
	" loop_episodes INTEGER, longest_loop_s REAL, largest_loop_m REAL,"
	" pain_share REAL, peak_pain REAL, pain_episodes INTEGER,"
	" pain_s_looping REAL, pain_s_straightening REAL,"
	" pain_s_insufflation REAL, pain_s_tip REAL, gloucester INTEGER,"
	" gas_used_l REAL, peak_gas_pressure_pa REAL,"
	" position_changes INTEGER, hand_uses INTEGER,"
	" perforations INTEGER, lumen_lost_s REAL, mucosa_seen REAL,"
	" polyps_seen INTEGER, polyps_total INTEGER,"
	" polyps_seen_mask INTEGER, shaft_in_m REAL, tip_in_m REAL,"
	" chase_efficiency REAL, shaft_idle_m REAL, loop_s REAL,"
	" retraction_m REAL, tip_retraction_m REAL,"
	" retraction_efficiency REAL, clear_view REAL, lost_views INTEGER,"
	" mucosa_per_min REAL, mucosa_seen_anal_canal REAL,"
	" mucosa_seen_rectum REAL, mucosa_seen_sigmoid REAL,"
	" mucosa_seen_descending REAL, mucosa_seen_splenic_flexure REAL,"
	" mucosa_seen_transverse REAL, mucosa_seen_hepatic_flexure REAL,"
	" mucosa_seen_ascending REAL, mucosa_seen_cecum REAL);",
	/* 2: a trainee's sessions found without reading them all */
	"CREATE INDEX sessions_by_trainee ON sessions(trainee_id, id);",
	/* 3: a centre's (records_set_centre()): each session's UUID, whether
	 * the centre has it, and the queue of those it waits for */
	"ALTER TABLE sessions ADD COLUMN uuid TEXT;"
	"ALTER TABLE sessions ADD COLUMN at_centre INTEGER NOT NULL DEFAULT 0;"
	"CREATE TABLE centre_queue (seq INTEGER PRIMARY KEY AUTOINCREMENT,"
	" session_id INTEGER NOT NULL UNIQUE);",
	/* 4: the therapy through the working channel (therapy.h) */
	"ALTER TABLE measures ADD COLUMN polyps_resected INTEGER;"
	"ALTER TABLE measures ADD COLUMN polyps_partly INTEGER;"
	"ALTER TABLE measures ADD COLUMN polyps_retrieved INTEGER;"
	"ALTER TABLE measures ADD COLUMN resection_s REAL;"
	"ALTER TABLE measures ADD COLUMN cautery_s REAL;"
	"ALTER TABLE measures ADD COLUMN tool_injuries INTEGER;"
	"ALTER TABLE measures ADD COLUMN biopsies INTEGER;"
	"ALTER TABLE measures ADD COLUMN clips INTEGER;",
	/* 5: the bleeding (format 7; therapy.h) */
	"ALTER TABLE measures ADD COLUMN bleeds INTEGER;"
	"ALTER TABLE measures ADD COLUMN bleeds_clipped INTEGER;"
	"ALTER TABLE measures ADD COLUMN bleed_control_s REAL;",
};

struct records {
	char path[4096];
	char dir[4096];
	char rig[64];
	char course[4096];      /* its file; "": none */
	bool centre;            /* each session written is queued */
	char *insert_measures;  /* INSERT INTO measures (...) VALUES (?...) */
	char *select_list;      /* the sessions joined with their measures,
				   without an ORDER BY */
	char *select_facts;     /* the sessions alone, likewise */
	char error[9216];       /* room for the path and SQLite's words */
};

/* ------------------------------------------------------------- create */

/* "PREFIX k1, k2, ... MIDDLE ?, ?, ... SUFFIX" over the measures' keys
 * (our own table's names, never a value): malloc'd. */
static char *field_sql(const char *prefix, const char *key_prefix,
		       const char *middle, const char *suffix)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);
	char *text = NULL;
	size_t len = 0;
	FILE *m = open_memstream(&text, &len);

	if (!m) {
		return NULL;
	}
	fputs(prefix, m);
	for (size_t i = 0; i < n; i++) {
		fprintf(m, "%s%s%s", i ? ", " : "", key_prefix, f[i].key);
	}
	fputs(middle, m);
	for (size_t i = 0; middle[0] && i < n; i++) {
		fputs(", ?", m);
	}
	fputs(suffix, m);
	if (fclose(m)) {
		free(text);
		return NULL;
	}
	return text;
}

/* The columns read_row() reads, with or without the measures after them
 * (m: the measures' table), and the names they need. */
#define FACTS_COLUMNS "SELECT s.id, t.name, c.name, s.started, s.ended, " \
	"s.bytes, s.checksum, s.rig, s.judgement, "
#define FACTS FACTS_COLUMNS "0, s.uuid"
#define FACTS_WITH_MEASURES FACTS_COLUMNS "m.session_id IS NOT NULL, s.uuid"
#define JOIN_NAMES " JOIN trainees t ON t.id = s.trainee_id" \
	" JOIN cases c ON c.id = s.case_id"

struct records *records_create(const char *database, const char *dir,
			       const char *rig, const char *course)
{
	struct records *r = calloc(1, sizeof(*r));

	if (!r) {
		return NULL;
	}
	snprintf(r->dir, sizeof(r->dir), "%s", dir);
	if (database[0] == '/') {
		snprintf(r->path, sizeof(r->path), "%s", database);
	} else {
		snprintf(r->path, sizeof(r->path), "%s/%s", dir, database);
	}
	snprintf(r->course, sizeof(r->course), "%s", course ? course : "");
	if (rig && *rig) {
		snprintf(r->rig, sizeof(r->rig), "%s", rig);
	} else if (gethostname(r->rig, sizeof(r->rig) - 1)) {
		snprintf(r->rig, sizeof(r->rig), "rig");
	}
	r->insert_measures = field_sql("INSERT INTO measures (session_id, ",
				       "", ") VALUES (?", ")");
	r->select_list = field_sql(FACTS_WITH_MEASURES ", ", "m.", "",
				   " FROM sessions s" JOIN_NAMES " LEFT JOIN "
				   "measures m ON m.session_id = s.id");
	r->select_facts = strdup(FACTS " FROM sessions s" JOIN_NAMES);
	if (!r->insert_measures || !r->select_list || !r->select_facts) {
		records_destroy(r);
		return NULL;
	}
	return r;
}

void records_destroy(struct records *r)
{
	if (!r) {
		return;
	}
	free(r->insert_measures);
	free(r->select_list);
	free(r->select_facts);
	free(r);
}

const char *records_path(const struct records *r)
{
	return r->path;
}

const char *records_rig(const struct records *r)
{
	return r->rig;
}

const char *records_error(const struct records *r)
{
	return r->error;
}

/* ------------------------------------------------------------ SQLite */

static bool is_damage(int code)
{
	code &= 0xff;
	return code == SQLITE_CORRUPT || code == SQLITE_NOTADB;
}

/* Says what failed in R's error: -EBADMSG (the database is damaged) or
 * -EIO. */
static int sql_fail(struct records *r, sqlite3 *db, const char *what)
{
	int code = db ? sqlite3_extended_errcode(db) : SQLITE_NOMEM;

	snprintf(r->error, sizeof(r->error), "records %s: %s: %s", r->path,
		 what, db ? sqlite3_errmsg(db) : "out of memory");
	return is_damage(code) ? -EBADMSG : -EIO;
}

static int exec(struct records *r, sqlite3 *db, const char *sql)
{
	return sqlite3_exec(db, sql, NULL, NULL, NULL) == SQLITE_OK ? 0
		: sql_fail(r, db, sql);
}

/* The database's PRAGMA user_version into *V. */
static int user_version(struct records *r, sqlite3 *db, int *v)
{
	sqlite3_stmt *st;
	int rc;

	if (sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &st, NULL)) {
		return sql_fail(r, db, "reading its schema version");
	}
	rc = sqlite3_step(st);
	*v = rc == SQLITE_ROW ? sqlite3_column_int(st, 0) : 0;
	sqlite3_finalize(st);
	return rc == SQLITE_ROW ? 0 : sql_fail(r, db, "reading its version");
}

/* The migrations from version FROM on, each in its transaction. */
static int migrate(struct records *r, sqlite3 *db, int from)
{
	char sql[64];
	int e = 0;

	for (int v = from; !e && v < RECORDS_SCHEMA_VERSION; v++) {
		snprintf(sql, sizeof(sql), "PRAGMA user_version = %d", v + 1);
		e = exec(r, db, "BEGIN IMMEDIATE");
		if (!e && ((e = exec(r, db, migrations[v])) ||
			   (e = exec(r, db, sql)) ||
			   (e = exec(r, db, "COMMIT")))) {
			sqlite3_exec(db, "ROLLBACK", NULL, NULL, NULL);
		}
	}
	return e;
}

/* How open_db() found the database. */
enum found { FOUND_OK, FOUND_NEW, FOUND_MISSING };

/*
 * The database PATH (R's, or the one a rebuild makes) opened into *DB,
 * migrated to this schema; with CREATE
 * made when missing (*HOW FOUND_NEW: empty), else FOUND_MISSING and *DB
 * NULL. 0; -EBADMSG (damaged); -EPROTO (newer); -EIO.
 */
static int open_db(struct records *r, const char *path, bool create,
		   sqlite3 **db, enum found *how)
{
	int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX;
	int v = 0, e;

	*db = NULL;
	*how = FOUND_OK;
	r->error[0] = '\0';
	if (access(path, F_OK)) {
		if (!create) {
			*how = FOUND_MISSING;
			return 0;
		}
		*how = FOUND_NEW;
	}
	if (sqlite3_open_v2(path, db, flags | (create ?
			    SQLITE_OPEN_CREATE : 0), NULL) != SQLITE_OK) {
		e = sql_fail(r, *db, "opening it");
		goto close;
	}
	sqlite3_busy_timeout(*db, BUSY_MS);
	if ((e = exec(r, *db, "PRAGMA journal_mode = WAL")) ||
	    (e = user_version(r, *db, &v))) {
		goto close;
	}
	if (v > RECORDS_SCHEMA_VERSION) {
		snprintf(r->error, sizeof(r->error), "records %s: its schema "
			 "is version %d, newer than this endosim's %d: run a "
			 "newer endosim, or move the database aside (the "
			 "session files rebuild it)", r->path, v,
			 RECORDS_SCHEMA_VERSION);
		e = -EPROTO;
		goto close;
	}
	if (!(e = migrate(r, *db, v)) &&
	    !(e = exec(r, *db, "PRAGMA foreign_keys = ON"))) {
		return 0;
	}
close:
	sqlite3_close(*db);
	*db = NULL;
	return e;
}

/* ------------------------------------------------------------ a file */

uint64_t records_checksum(uint64_t sum, const void *p, size_t n)
{
	const unsigned char *b = p;

	for (size_t i = 0; i < n; i++) {
		sum = (sum ^ b[i]) * 0x100000001b3ull;
	}
	return sum;
}

int records_file_checksum(const char *path, uint64_t *sum)
{
	unsigned char buf[65536];
	int fd = open(path, O_RDONLY | O_CLOEXEC);
	ssize_t got;

	if (fd < 0) {
		return -errno;
	}
	*sum = RECORDS_CHECKSUM_SEED;
	while ((got = read(fd, buf, sizeof(buf))) > 0) {
		*sum = records_checksum(*sum, buf, (size_t)got);
	}
	close(fd);
	return got < 0 ? -EIO : 0;
}

/* The file PATH as its row; its checksum SUM when known (NULL: read the
 * file whole for it). */
static int read_file(const char *path, const uint64_t *sum,
		     struct records_session *s)
{
	char *end = NULL;
	int e;

	memset(s, 0, sizeof(*s));
	if ((e = sessiondir_stat_file(path, &s->e))) {
		return e;
	}
	if (sum) {
		s->checksum = *sum;
	} else if ((e = records_file_checksum(path, &s->checksum))) {
		return e;
	}
	s->has_metrics = s->e.ended && !sessiondir_end_text(path, &end) &&
			 !metricstext_parse(end, &s->m);
	s->m.n_force = s->m.n_loop = s->m.n_pain = 0;
	free(end);
	return 0;
}

int records_read_file(const char *path, struct records_session *s)
{
	return read_file(path, NULL, s);
}

/* ------------------------------------------------------------ writing */

/* Binds the texts and numbers of a statement and steps it once. */
static int step_done(struct records *r, sqlite3 *db, sqlite3_stmt *st,
		     const char *what)
{
	int rc = sqlite3_step(st);

	sqlite3_finalize(st);
	return rc == SQLITE_DONE || rc == SQLITE_ROW ? 0
		: sql_fail(r, db, what);
}

/* The id of NAME in TABLE (trainees or cases), added when new. */
static int name_id(struct records *r, sqlite3 *db, const char *table,
		   const char *name, sqlite3_int64 *id)
{
	char sql[128];
	sqlite3_stmt *st;
	int rc;

	snprintf(sql, sizeof(sql), "INSERT INTO %s (name) VALUES (?) "
		 "ON CONFLICT (name) DO NOTHING", table);
	if (sqlite3_prepare_v2(db, sql, -1, &st, NULL)) {
		return sql_fail(r, db, sql);
	}
	sqlite3_bind_text(st, 1, name, -1, SQLITE_STATIC);
	if ((rc = step_done(r, db, st, sql))) {
		return rc;
	}
	snprintf(sql, sizeof(sql), "SELECT id FROM %s WHERE name = ?", table);
	if (sqlite3_prepare_v2(db, sql, -1, &st, NULL)) {
		return sql_fail(r, db, sql);
	}
	sqlite3_bind_text(st, 1, name, -1, SQLITE_STATIC);
	rc = sqlite3_step(st);
	*id = sqlite3_column_int64(st, 0);
	sqlite3_finalize(st);
	return rc == SQLITE_ROW ? 0 : sql_fail(r, db, sql);
}

/* The N statements SQL run in turn, each on session ID. */
static int each_on_id(struct records *r, sqlite3 *db,
		      const char *const *sql, size_t n, uint64_t id)
{
	sqlite3_stmt *st;
	int e = 0;

	for (size_t i = 0; !e && i < n; i++) {
		if (sqlite3_prepare_v2(db, sql[i], -1, &st, NULL)) {
			return sql_fail(r, db, sql[i]);
		}
		sqlite3_bind_int64(st, 1, (sqlite3_int64)id);
		e = step_done(r, db, st, sql[i]);
	}
	return e;
}

/* Session ID's rows deleted. */
static int delete_row(struct records *r, sqlite3 *db, uint64_t id)
{
	static const char *const sql[] = {
		"DELETE FROM measures WHERE session_id = ?",
		"DELETE FROM sessions WHERE id = ?",
	};

	return each_on_id(r, db, sql, 2, id);
}

/* The sessions that WHAT selects (VALUES (?): session ARG) queued for
 * the centre, after those queued already; one queued already stays where
 * it is. */
static int queue_ids(struct records *r, sqlite3 *db, const char *what,
		     uint64_t arg)
{
	char sql[256];
	sqlite3_stmt *st;

	snprintf(sql, sizeof(sql), "INSERT OR IGNORE INTO centre_queue "
		 "(session_id) %s", what);
	if (sqlite3_prepare_v2(db, sql, -1, &st, NULL)) {
		return sql_fail(r, db, sql);
	}
	if (sqlite3_bind_parameter_count(st)) {
		sqlite3_bind_int64(st, 1, (sqlite3_int64)arg);
	}
	return step_done(r, db, st, "queueing for the centre");
}

/* Session ID out of the centre's queue; with ARRIVED, marked as there. */
static int unqueue_as(struct records *r, sqlite3 *db, uint64_t id,
		      bool arrived)
{
	static const char *const sql[] = {
		"DELETE FROM centre_queue WHERE session_id = ?",
		"UPDATE sessions SET at_centre = 1 WHERE id = ?",
	};

	return each_on_id(r, db, sql, 1u + arrived, id);
}

static int unqueue(struct records *r, sqlite3 *db, uint64_t id)
{
	return unqueue_as(r, db, id, false);
}

static int insert_measures(struct records *r, sqlite3 *db,
			   const struct records_session *s)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);
	sqlite3_stmt *st;

	if (sqlite3_prepare_v2(db, r->insert_measures, -1, &st, NULL)) {
		return sql_fail(r, db, "preparing the measures' insert");
	}
	sqlite3_bind_int64(st, 1, (sqlite3_int64)s->e.id);
	for (size_t i = 0; i < n; i++) {
		double v = metricstext_field_value(&s->m, &f[i]);

		if (f[i].kind == FIELDS_DOUBLE) {
			sqlite3_bind_double(st, (int)i + 2, v);
		} else {
			sqlite3_bind_int64(st, (int)i + 2, (sqlite3_int64)v);
		}
	}
	return step_done(r, db, st, "inserting the measures");
}

/* S (read from PATH) as its rows, replacing any. */
static int insert_session(struct records *r, sqlite3 *db, const char *path,
			  const struct records_session *s)
{
	static const char sql[] = "INSERT INTO sessions (id, trainee_id, "
		"case_id, started, ended, path, bytes, checksum, rig, judgement, "
		"uuid) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)";
	struct records_session named = *s;
	sqlite3_int64 trainee, case_id;
	sqlite3_stmt *st;
	int e;

	if ((e = delete_row(r, db, s->e.id)) ||
	    (e = name_id(r, db, "trainees", s->e.trainee, &trainee)) ||
	    (e = name_id(r, db, "cases", s->e.case_name, &case_id))) {
		return e;
	}
	if (sqlite3_prepare_v2(db, sql, -1, &st, NULL)) {
		return sql_fail(r, db, sql);
	}
	sqlite3_bind_int64(st, 1, (sqlite3_int64)s->e.id);
	sqlite3_bind_int64(st, 2, trainee);
	sqlite3_bind_int64(st, 3, case_id);
	sqlite3_bind_text(st, 4, s->e.started, -1, SQLITE_STATIC);
	sqlite3_bind_int(st, 5, s->e.ended);
	sqlite3_bind_text(st, 6, path, -1, SQLITE_STATIC);
	sqlite3_bind_int64(st, 7, (sqlite3_int64)s->e.bytes);
	sqlite3_bind_int64(st, 8, (sqlite3_int64)s->checksum);
	sqlite3_bind_text(st, 9, r->rig, -1, SQLITE_STATIC);
	if (s->judgement[0]) {
		sqlite3_bind_text(st, 10, s->judgement, -1, SQLITE_STATIC);
	}
	snprintf(named.rig, sizeof(named.rig), "%s", r->rig);
	records_uuid(&named, named.uuid);
	sqlite3_bind_text(st, 11, named.uuid, -1, SQLITE_STATIC);
	if ((e = step_done(r, db, st, "inserting the session")) ||
	    (s->has_metrics && (e = insert_measures(r, db, s)))) {
		return e;
	}
	return r->centre ? queue_ids(r, db, "VALUES (?)", s->e.id) : 0;
}

/* S's judgement by R's course, when it names S's case. */
static void judge(const struct records *r, struct records_session *s)
{
	const struct coursefile_case *k;
	struct coursefile *c;
	char err[512];

	if (!r->course[0] || !s->has_metrics ||
	    !(c = malloc(sizeof(*c)))) {
		return;
	}
	if (!coursefile_load(c, r->course, err, sizeof(err)) &&
	    (k = coursefile_case(c, s->e.case_name))) {
		snprintf(s->judgement, sizeof(s->judgement), "%s: %s",
			 c->name, coursefile_passed(k, &s->m) ? "passed"
							      : "failed");
	}
	free(c);
}

/* Session ID's file as its row (SUM: its checksum when known), or its
 * row deleted when the file is gone; not a session file: left out. */
static int write_summed(struct records *r, sqlite3 *db, uint64_t id,
			const uint64_t *sum)
{
	struct records_session s;
	char path[4096];
	int e;

	if (sessiondir_path(r->dir, id, path, sizeof(path))) {
		return -ENAMETOOLONG;
	}
	e = read_file(path, sum, &s);
	if (e == -ENOENT || e == -EBADMSG) {
		int d = delete_row(r, db, id);

		d = d ? d : unqueue(r, db, id);
		return d ? d : e;
	}
	if (e) {
		snprintf(r->error, sizeof(r->error), "%s: %s", path,
			 strerror(-e));
		return e;
	}
	s.e.id = id; /* the file's name says it */
	judge(r, &s);
	return insert_session(r, db, path, &s);
}

static int write_file(struct records *r, sqlite3 *db, uint64_t id)
{
	return write_summed(r, db, id, NULL);
}

/* Every file's row written (but SKIP's), one transaction; how many. */
static int fill(struct records *r, sqlite3 *db, uint64_t skip,
		size_t *written)
{
	struct sessiondir_entry *files;
	size_t n;
	int e = sessiondir_list(r->dir, &files, &n);

	if (e) {
		snprintf(r->error, sizeof(r->error), "%s: %s", r->dir,
			 strerror(-e));
		return e;
	}
	if (!(e = exec(r, db, "BEGIN IMMEDIATE"))) {
		for (size_t i = 0; !e && i < n; i++) {
			if (files[i].id != skip) {
				e = write_file(r, db, files[i].id);
				e = e == -EBADMSG || e == -ENOENT ? 0 : e;
				*written += !e;
			}
		}
	}
	e = e ? e : exec(r, db, "COMMIT");
	if (e) {
		sqlite3_exec(db, "ROLLBACK", NULL, NULL, NULL);
	}
	free(files);
	return e;
}

/* PATH's write-ahead log and shared memory removed: never to be taken
 * for another database's. */
static void remove_sides(const char *path)
{
	char side[4300];

	snprintf(side, sizeof(side), "%s-wal", path);
	unlink(side);
	snprintf(side, sizeof(side), "%s-shm", path);
	unlink(side);
}

/* A damaged database moved aside, kept to be looked at. */
static void move_aside(struct records *r)
{
	char to[4200];

	snprintf(to, sizeof(to), "%s.damaged", r->path);
	rename(r->path, to);
	remove_sides(r->path);
}

/*
 * A new database of every file (but SKIP's) made beside R's and renamed
 * over it: nothing of the old one is trusted, not even its indexes.
 */
static int build_new(struct records *r, uint64_t skip, size_t *written)
{
	char tmp[4200];
	sqlite3 *db;
	enum found how;
	int e;

	snprintf(tmp, sizeof(tmp), "%s.new", r->path);
	unlink(tmp);
	remove_sides(tmp);
	if ((e = open_db(r, tmp, true, &db, &how))) {
		return e;
	}
	e = fill(r, db, skip, written);
	sqlite3_close(db);
	remove_sides(r->path);
	if (!e && rename(tmp, r->path)) {
		e = -errno;
		snprintf(r->error, sizeof(r->error), "records %s: %s",
			 r->path, strerror(errno));
	}
	if (e) {
		unlink(tmp);
	}
	return e;
}

/*
 * The database ready to use in *DB: opened, or made again from the files
 * when missing or damaged (*REBUILT then). 0 or as open_db().
 */
static int ready(struct records *r, sqlite3 **db, bool *rebuilt)
{
	enum found how;
	size_t written = 0;
	int e = open_db(r, r->path, false, db, &how);

	*rebuilt = false;
	if (e == -EBADMSG) {
		move_aside(r);
	}
	if (e == -EBADMSG || (!e && how == FOUND_MISSING)) {
		*rebuilt = true;
		e = build_new(r, 0, &written);
		e = e ? e : open_db(r, r->path, false, db, &how);
	}
	return e;
}

int records_add(struct records *r, uint64_t id)
{
	return records_add_summed(r, id, NULL);
}

int records_add_summed(struct records *r, uint64_t id, const uint64_t *sum)
{
	sqlite3 *db;
	bool rebuilt;
	int e = ready(r, &db, &rebuilt);

	if (e || rebuilt) {
		sqlite3_close(db); /* a rebuild wrote ID's row too */
		return e;
	}
	e = exec(r, db, "BEGIN IMMEDIATE");
	if (!e) {
		e = write_summed(r, db, id, sum);
		if (e && e != -ENOENT) {
			sqlite3_exec(db, "ROLLBACK", NULL, NULL, NULL);
		} else {
			int c = exec(r, db, "COMMIT");

			e = c ? c : e;
		}
	}
	sqlite3_close(db);
	return e;
}

/* ------------------------------------------------------------ reading */

static void column_text(sqlite3_stmt *st, int col, char *out, size_t size)
{
	const unsigned char *t = sqlite3_column_text(st, col);

	snprintf(out, size, "%s", t ? (const char *)t : "");
}

/* The measures a statement selects after the facts: N of them, the
 * metricstext_fields() index of each in IDX (NULL: every field, in
 * order). */
struct columns {
	const size_t *idx;
	size_t n;
};

/* The current row of the list's statement, selecting the measures C,
 * into S. */
static void read_row(sqlite3_stmt *st, const struct columns *c,
		     struct records_session *s)
{
	const struct metricstext_field *all;
	size_t n = metricstext_fields(&all);

	memset(s, 0, sizeof(*s));
	s->e.id = (uint64_t)sqlite3_column_int64(st, 0);
	column_text(st, 1, s->e.trainee, sizeof(s->e.trainee));
	column_text(st, 2, s->e.case_name, sizeof(s->e.case_name));
	column_text(st, 3, s->e.started, sizeof(s->e.started));
	s->e.ended = sqlite3_column_int(st, 4);
	s->e.bytes = (uint64_t)sqlite3_column_int64(st, 5);
	s->checksum = (uint64_t)sqlite3_column_int64(st, 6);
	column_text(st, 7, s->rig, sizeof(s->rig));
	column_text(st, 8, s->judgement, sizeof(s->judgement));
	s->has_metrics = sqlite3_column_int(st, 9);
	column_text(st, 10, s->uuid, sizeof(s->uuid));
	if (!s->uuid[0]) {
		records_uuid(s, s->uuid); /* a row older than the column */
	}
	for (size_t i = 0; s->has_metrics && i < (c->idx ? c->n : n); i++) {
		const struct metricstext_field *f = &all[c->idx ? c->idx[i] : i];
		char *at = (char *)&s->m + f->offset;
		int col = (int)i + 11;

		if (f->kind == FIELDS_DOUBLE) {
			/* SQLite keeps a NaN as NULL */
			*(double *)at = sqlite3_column_type(st, col) ==
					SQLITE_NULL ? NAN :
					sqlite3_column_double(st, col);
		} else if (f->kind == FIELDS_UINT64) {
			*(uint64_t *)at = (uint64_t)sqlite3_column_int64(st,
									 col);
		} else {
			*(uint32_t *)at = (uint32_t)sqlite3_column_int64(st,
									 col);
		}
	}
}

/* Each row of DB that SELECT and SUFFIX select (its one parameter, when
 * it has one, bound to ARG's text) read into one S and passed to FN. */
static int each_row(struct records *r, sqlite3 *db, const char *select,
		    const struct columns *c, const char *suffix,
		    const char *arg, records_fn *fn, void *fn_arg)
{
	struct records_session *s = malloc(sizeof(*s));
	sqlite3_stmt *st = NULL;
	char *sql = NULL;
	int rc, e = 0;

	if (!s || asprintf(&sql, "%s %s", select, suffix) < 0) {
		free(s);
		return -ENOMEM;
	}
	rc = sqlite3_prepare_v2(db, sql, -1, &st, NULL);
	free(sql);
	if (rc) {
		free(s);
		return sql_fail(r, db, "preparing the list");
	}
	if (arg) {
		sqlite3_bind_text(st, 1, arg, -1, SQLITE_STATIC);
	}
	while (!e && (rc = sqlite3_step(st)) == SQLITE_ROW) {
		read_row(st, c, s);
		e = fn(fn_arg, s);
	}
	if (!e && rc != SQLITE_DONE) {
		e = sql_fail(r, db, "listing the sessions");
	}
	sqlite3_finalize(st);
	free(s);
	return e;
}

/* A growing array of rows, for select_rows(). */
struct rows {
	struct records_session *s;
	size_t n, cap;
};

static int append_row(void *arg, const struct records_session *s)
{
	struct rows *a = arg;

	if (!s) {
		a->n = 0; /* read again from the start */
		return 0;
	}
	if (a->n == a->cap) {
		size_t cap = a->cap ? 2 * a->cap : 64;
		struct records_session *more = realloc(a->s, cap * sizeof(*more));

		if (!more) {
			return -ENOMEM;
		}
		a->s = more;
		a->cap = cap;
	}
	a->s[a->n++] = *s;
	return 0;
}

/* The rows of DB that the list's statement and SUFFIX select into *OUT,
 * *N. */
static int select_rows(struct records *r, sqlite3 *db, const char *suffix,
		       struct records_session **out, size_t *n)
{
	struct rows a = { 0 };
	int e = each_row(r, db, r->select_list, &(struct columns){ 0 },
			 suffix, NULL, append_row, &a);

	*out = a.s;
	*n = a.n;
	return e;
}

/* Every row of DB into *OUT, *N, by ID. */
static int select_all(struct records *r, sqlite3 *db,
		      struct records_session **out, size_t *n)
{
	return select_rows(r, db, "ORDER BY s.id", out, n);
}

int records_list(struct records *r, struct records_session **out, size_t *n)
{
	struct rows a = { 0 };
	int e = records_each(r, NULL, RECORDS_MEASURES, NULL, 0, append_row,
			     &a);

	if (e) {
		free(a.s);
		a = (struct rows){ 0 };
	}
	*out = a.s;
	*n = a.n;
	return e;
}

/*
 * The statement selecting the facts and the measures named by KEYS (N of
 * them) into *SQL (malloc'd), their columns into C (IDX: room for N). Our
 * table's names only: each key is checked against it. 0, -EINVAL (R's
 * error names the key), -ENOMEM.
 */
static int select_some(struct records *r, const char *const *keys, size_t n,
		       char **sql, size_t *idx, struct columns *c)
{
	const struct metricstext_field *f;
	size_t nf = metricstext_fields(&f), len = 0;
	FILE *m = open_memstream(sql, &len);

	if (!m) {
		return -ENOMEM;
	}
	fputs(FACTS_WITH_MEASURES, m);
	for (size_t i = 0; i < n; i++) {
		for (idx[i] = 0; idx[i] < nf && strcmp(f[idx[i]].key, keys[i]);
		     idx[i]++) {
		}
		if (idx[i] == nf) {
			fclose(m);
			free(*sql);
			snprintf(r->error, sizeof(r->error), "no measure '%.64s'",
				 keys[i]);
			return -EINVAL;
		}
		fprintf(m, ", m.%s", f[idx[i]].key);
	}
	fputs(" FROM sessions s" JOIN_NAMES " LEFT JOIN measures m ON "
	      "m.session_id = s.id", m);
	*c = (struct columns){ .idx = idx, .n = n };
	return fclose(m) ? -ENOMEM : 0;
}

int records_each(struct records *r, const char *trainee, unsigned what,
		 const char *const *keys, size_t n_keys, records_fn *fn,
		 void *arg)
{
	const char *select = what & RECORDS_MEASURES ? r->select_list
						     : r->select_facts;
	const char *suffix = trainee ? "WHERE t.name = ? ORDER BY s.id"
				     : "ORDER BY s.id";
	struct columns c = { 0 };
	char *some = NULL;
	size_t *idx = NULL;
	sqlite3 *db;
	bool rebuilt;
	int e = 0;

	r->error[0] = '\0';
	if ((what & RECORDS_MEASURES) && keys &&
	    (!(idx = calloc(n_keys + 1, sizeof(*idx))) ||
	     (e = select_some(r, keys, n_keys, &some, idx, &c)))) {
		free(idx);
		return e ? e : -ENOMEM;
	}
	for (int tries = 0; tries < 2; tries++) {
		if ((e = ready(r, &db, &rebuilt))) {
			break;
		}
		e = each_row(r, db, some ? some : select, &c, suffix, trainee,
			     fn, arg);
		sqlite3_close(db);
		if (e != -EBADMSG) {
			break;
		}
		fn(arg, NULL);
		move_aside(r); /* damage found only now: rebuild, once */
	}
	free(some);
	free(idx);
	return e;
}

/* ------------------------------------------------------- the centre */

void records_set_centre(struct records *r, bool on)
{
	r->centre = on;
}

void records_uuid(const struct records_session *s, char out[37])
{
	const char *const parts[] = { s->rig, s->e.trainee, s->e.case_name,
				      s->e.started };
	uint64_t h[2] = { 0xcbf29ce484222325ull, 0x6c62272e07bb0142ull };
	unsigned char b[16];

	for (int k = 0; k < 2; k++) {
		for (int i = 0; i < 8; i++) { /* the ID, little-endian */
			h[k] = (h[k] ^ ((s->e.id >> (8 * i)) & 0xff)) *
			       0x100000001b3ull;
		}
		for (size_t p = 0; p < 4; p++) {
			for (const char *c = parts[p]; ; c++) {
				h[k] = (h[k] ^ (unsigned char)*c) *
				       0x100000001b3ull;
				if (!*c) {
					break; /* the NUL keeps parts apart */
				}
			}
		}
	}
	for (int i = 0; i < 16; i++) {
		b[i] = (unsigned char)(h[i / 8] >> (8 * (i % 8)));
	}
	b[6] = (unsigned char)((b[6] & 0x0f) | 0x80); /* version 8 */
	b[8] = (unsigned char)((b[8] & 0x3f) | 0x80); /* RFC 9562 */
	snprintf(out, 37, "%02x%02x%02x%02x-%02x%02x-%02x%02x-%02x%02x-"
		 "%02x%02x%02x%02x%02x%02x", b[0], b[1], b[2], b[3], b[4],
		 b[5], b[6], b[7], b[8], b[9], b[10], b[11], b[12], b[13],
		 b[14], b[15]);
}

/* The one number SQL (a COUNT) gives, into *N; WHAT names it. */
static int count(struct records *r, sqlite3 *db, const char *sql,
		 const char *what, size_t *n)
{
	sqlite3_stmt *st;
	int rc;

	if (sqlite3_prepare_v2(db, sql, -1, &st, NULL)) {
		return sql_fail(r, db, what);
	}
	rc = sqlite3_step(st);
	*n = rc == SQLITE_ROW ? (size_t)sqlite3_column_int64(st, 0) : 0;
	sqlite3_finalize(st);
	return rc == SQLITE_ROW ? 0 : sql_fail(r, db, what);
}

/* How many sessions wait for the centre, into *N. */
static int queue_length(struct records *r, sqlite3 *db, size_t *n)
{
	return count(r, db, "SELECT COUNT(*) FROM centre_queue q JOIN "
		     "sessions s ON s.id = q.session_id",
		     "counting the centre's queue", n);
}

int records_queue_unsent(struct records *r, size_t *waiting)
{
	sqlite3 *db;
	bool rebuilt;
	int e = ready(r, &db, &rebuilt);

	*waiting = 0;
	if (!e && !(e = queue_ids(r, db, "SELECT id FROM sessions WHERE "
				  "at_centre = 0 ORDER BY id", 0))) {
		e = queue_length(r, db, waiting);
	}
	sqlite3_close(db);
	return e;
}

/* The database as it is in *DB, NULL when missing: never built again
 * here, so that a second thread's call cannot race its writer's rebuild. */
static int existing(struct records *r, sqlite3 **db)
{
	enum found how;

	return open_db(r, r->path, false, db, &how);
}

int records_queue_head(struct records *r, struct records_session *s,
		       size_t *waiting)
{
	struct records_session *rows = NULL;
	size_t n = 0;
	sqlite3 *db;
	int e = existing(r, &db);

	*waiting = 0;
	if (!e && db && !(e = queue_length(r, db, waiting))) {
		e = select_rows(r, db, "JOIN centre_queue q ON q.session_id "
				"= s.id ORDER BY q.seq LIMIT 1", &rows, &n);
	}
	if (!e && n) {
		*s = rows[0];
	}
	free(rows);
	sqlite3_close(db);
	return e ? e : n ? 0 : -ENOENT;
}

int records_queue_arrived(struct records *r, uint64_t id)
{
	sqlite3 *db;
	int e = existing(r, &db);

	if (!e && db) {
		e = unqueue_as(r, db, id, true);
	}
	sqlite3_close(db);
	return e;
}

/* ------------------------------------------------------------ checking */

struct check {
	struct records *r;
	sqlite3 *db;
	unsigned flags;
	FILE *text;
	struct records_report *rep;
};

/* The names of what differs between row A and file B into WHAT. */
static void differences(const struct records_session *a,
			const struct records_session *b, bool deep,
			char *what, size_t size)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f), at = 0;

#define DIFF(cond, name)                                                      \
	do {                                                                  \
		if ((cond) && at < size) {                                    \
			at += (size_t)snprintf(what + at, size - at, "%s%s",  \
					       at ? ", " : "", name);         \
		}                                                             \
	} while (0)
	what[0] = '\0';
	DIFF(a->e.bytes != b->e.bytes, "size");
	DIFF(a->e.ended != b->e.ended, "ended");
	if (!deep) {
		return;
	}
	DIFF(a->checksum != b->checksum, "checksum");
	DIFF(strcmp(a->e.trainee, b->e.trainee), "trainee");
	DIFF(strcmp(a->e.case_name, b->e.case_name), "case");
	DIFF(strcmp(a->e.started, b->e.started), "started");
	DIFF(a->has_metrics != b->has_metrics, "measures");
	for (size_t i = 0; a->has_metrics && b->has_metrics && i < n; i++) {
		double x = metricstext_field_value(&a->m, &f[i]);
		double y = metricstext_field_value(&b->m, &f[i]);

		DIFF(x != y && !(isnan(x) && isnan(y)), f[i].key);
	}
#undef DIFF
}

/* One session: its file FILE (NULL: none) against its row ROW (NULL:
 * none); said and, with RECORDS_FIX, written. */
static int check_one(struct check *c, uint64_t id,
		     const struct sessiondir_entry *file,
		     const struct records_session *row)
{
	struct records_session s = { .e = file ? *file : (struct
							  sessiondir_entry){ 0 } };
	char path[4096], what[512] = "";
	bool deep = c->flags & RECORDS_DEEP;
	int e = 0;

	if (file && row && deep) {
		sessiondir_path(c->r->dir, id, path, sizeof(path));
		e = records_read_file(path, &s);
		s.checksum = e ? ~row->checksum : s.checksum;
	}
	if (file && row) {
		differences(row, &s, deep, what, sizeof(what));
		if (!what[0]) {
			return 0;
		}
		fprintf(c->text, "session %" PRIu64 ": the database's row "
			"differs from its file: %s\n", id, what);
	} else if (file) {
		fprintf(c->text, "session %" PRIu64 ": not in the database\n",
			id);
	} else {
		fprintf(c->text, "session %" PRIu64 ": in the database, but "
			"its file is gone\n", id);
	}
	c->rep->differ++;
	if (c->flags & RECORDS_FIX) {
		e = write_file(c->r, c->db, id);
		e = e == -ENOENT || e == -EBADMSG ? 0 : e;
		c->rep->written += !e;
	}
	return e;
}

/* The rows against the files, merged by id. */
static int check_rows(struct check *c, const struct sessiondir_entry *files,
		      size_t nf, const struct records_session *rows, size_t nr,
		      uint64_t skip)
{
	size_t i = 0, j = 0;
	int e = 0;

	while (!e && (i < nf || j < nr)) {
		uint64_t fid = i < nf ? files[i].id : UINT64_MAX;
		uint64_t rid = j < nr ? rows[j].e.id : UINT64_MAX;
		uint64_t id = fid < rid ? fid : rid;

		if (id != skip) {
			e = check_one(c, id, fid == id ? &files[i] : NULL,
				      rid == id ? &rows[j] : NULL);
		}
		i += fid == id;
		j += rid == id;
	}
	return e;
}

/* SQLite's own check of the file: 0 when it says "ok". */
static int integrity(struct records *r, sqlite3 *db)
{
	sqlite3_stmt *st;
	int rc, ok;

	if (sqlite3_prepare_v2(db, "PRAGMA integrity_check", -1, &st, NULL)) {
		return sql_fail(r, db, "checking it");
	}
	rc = sqlite3_step(st);
	ok = rc == SQLITE_ROW && sqlite3_column_text(st, 0) &&
	     !strcmp((const char *)sqlite3_column_text(st, 0), "ok");
	if (!ok && rc == SQLITE_ROW) {
		snprintf(r->error, sizeof(r->error), "records %s: %s",
			 r->path, (const char *)sqlite3_column_text(st, 0));
	}
	sqlite3_finalize(st);
	return ok ? 0 : rc == SQLITE_ROW ? -EBADMSG : sql_fail(r, db, "check");
}

/* Opens the database for a check; says when it is missing or damaged. */
static int check_open(struct check *c, enum found *how)
{
	struct records *r = c->r;
	int e = open_db(r, r->path, c->flags & RECORDS_FIX, &c->db, how);

	if (!e && *how != FOUND_OK) {
		c->rep->missing = true;
		fprintf(c->text, "the database %s is missing\n", r->path);
	}
	if (!e && c->db && (c->flags & RECORDS_DEEP)) {
		e = integrity(r, c->db);
		if (e) {
			sqlite3_close(c->db);
			c->db = NULL;
		}
	}
	if (e == -EBADMSG) {
		c->rep->damaged = true;
		fprintf(c->text, "the database is damaged: %s\n", r->error);
	}
	return e;
}

static int close_text(struct check *c, int e)
{
	if (fclose(c->text) && !e) {
		e = -ENOMEM;
	}
	if (!c->rep->text) {
		c->rep->text = strdup("");
	}
	return e;
}

int records_check(struct records *r, unsigned flags, uint64_t skip,
		  struct records_report *rep)
{
	struct check c = { .r = r, .flags = flags, .rep = rep };
	struct sessiondir_entry *files = NULL;
	struct records_session *rows = NULL;
	size_t nf = 0, nr = 0, len = 0;
	enum found how;
	int e;

	memset(rep, 0, sizeof(*rep));
	c.text = open_memstream(&rep->text, &len);
	if (!c.text) {
		return -ENOMEM;
	}
	if ((e = sessiondir_list(r->dir, &files, &nf))) {
		snprintf(r->error, sizeof(r->error), "%s: %s", r->dir,
			 strerror(-e));
		return close_text(&c, e);
	}
	rep->files = nf - (skip && nf && files[nf - 1].id == skip);
	e = check_open(&c, &how);
	if (!e && c.db) {
		e = select_all(r, c.db, &rows, &nr);
		rep->rows = nr;
		if (!e && (flags & RECORDS_FIX) &&
		    !(e = exec(r, c.db, "BEGIN IMMEDIATE"))) {
			e = check_rows(&c, files, nf, rows, nr, skip);
			e = e ? e : exec(r, c.db, "COMMIT");
			if (e) {
				sqlite3_exec(c.db, "ROLLBACK", NULL, NULL,
					     NULL);
			}
		} else if (!e) {
			e = check_rows(&c, files, nf, rows, nr, skip);
		}
	} else if (!e) {
		rep->differ = rep->files;
	}
	if (e == -EBADMSG && rep->damaged) {
		rep->differ = rep->files;
		e = 0; /* what was found: the report says it */
		if (flags & RECORDS_FIX) {
			move_aside(r);
			e = build_new(r, skip, &rep->written);
		}
	}
	sqlite3_close(c.db);
	free(files);
	free(rows);
	return close_text(&c, e);
}

int records_rebuild(struct records *r, uint64_t skip,
		    struct records_report *rep)
{
	int e = records_check(r, RECORDS_DEEP, skip, rep);

	if (e) {
		return e; /* a newer schema's database is left alone */
	}
	if (rep->damaged) {
		move_aside(r);
	}
	rep->written = 0;
	return build_new(r, skip, &rep->written);
}

/* ------------------------------------------------- backup and restore */

/* Every page of FROM into TO (SQLite's online backup), waiting out a
 * writer's lock for up to BUSY_MS. */
static int copy_pages(struct records *r, sqlite3 *to, sqlite3 *from,
		      const char *what)
{
	sqlite3_backup *b = sqlite3_backup_init(to, "main", from, "main");
	int rc, waited = 0;

	if (!b) {
		return sql_fail(r, to, what);
	}
	while ((rc = sqlite3_backup_step(b, -1)) == SQLITE_BUSY ||
	       rc == SQLITE_LOCKED) {
		if ((waited += 50) > BUSY_MS) {
			break;
		}
		sqlite3_sleep(50);
	}
	sqlite3_backup_finish(b);
	return rc == SQLITE_DONE ? 0 : sql_fail(r, to, what);
}

int records_backup(struct records *r, const char *path, size_t *rows)
{
	sqlite3 *db = NULL, *to = NULL;
	bool made = false;
	struct stat sb;
	enum found how;
	int e;

	*rows = 0;
	r->error[0] = '\0';
	if (!lstat(path, &sb)) { /* a link, even dangling, counts */
		snprintf(r->error, sizeof(r->error), "backup %s: it exists "
			 "(a backup replaces nothing)", path);
		return -EEXIST;
	}
	e = open_db(r, r->path, false, &db, &how);
	if (!e && how == FOUND_MISSING) {
		snprintf(r->error, sizeof(r->error), "records %s: missing, "
			 "nothing to back up ('endoctl records rebuild' makes "
			 "it from the files)", r->path);
		return -ENOENT;
	}
	if (!e && sqlite3_open_v2(path, &to, SQLITE_OPEN_READWRITE |
				  SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX,
				  NULL) != SQLITE_OK) {
		e = sql_fail(r, to, "creating the backup");
		snprintf(r->error, sizeof(r->error), "backup %s: %s", path,
			 to ? sqlite3_errmsg(to) : "out of memory");
	} else if (!e) {
		made = true;
	}
	e = e ? e : copy_pages(r, to, db, "copying it");
	e = e ? e : exec(r, to, "PRAGMA journal_mode = DELETE");
	e = e ? e : count(r, to, "SELECT COUNT(*) FROM sessions",
			  "counting the backup's sessions", rows);
	sqlite3_close(to);
	sqlite3_close(db);
	if (e && made) {
		unlink(path); /* made here: no half copy left */
		remove_sides(path);
	}
	return e;
}

/* Whether PATH is a sound records database this program reads, opened
 * into *FROM: 0, -errno (it cannot be read), -EBADMSG, -EPROTO (R's
 * error says why). */
static int sound_backup(struct records *r, const char *path, sqlite3 **from)
{
	const char *why = NULL;
	size_t n;
	int v = 0;

	if (access(path, R_OK)) {
		int e = errno;

		snprintf(r->error, sizeof(r->error), "restore %s: %s", path,
			 strerror(e));
		return -e;
	}
	if (sqlite3_open_v2(path, from, SQLITE_OPEN_READONLY |
			    SQLITE_OPEN_NOMUTEX, NULL) != SQLITE_OK ||
	    user_version(r, *from, &v)) {
		why = "SQLite cannot read it";
	} else if (v > RECORDS_SCHEMA_VERSION) {
		snprintf(r->error, sizeof(r->error), "restore %s: its schema "
			 "is version %d, newer than this endosim's %d", path,
			 v, RECORDS_SCHEMA_VERSION);
		return -EPROTO;
	} else if (v < 1) {
		why = "no records schema";
	} else if (integrity(r, *from)) {
		why = "SQLite's check fails";
	} else if (count(r, *from, "SELECT COUNT(*) FROM sessions",
			 "reading its sessions", &n)) {
		why = "no sessions";
	}
	if (why) {
		snprintf(r->error, sizeof(r->error), "restore %s: not a sound "
			 "records database: %s", path, why);
		return -EBADMSG;
	}
	return 0;
}

int records_restore(struct records *r, const char *path, uint64_t skip,
		    struct records_report *rep)
{
	sqlite3 *from = NULL, *db = NULL;
	enum found how;
	int e;

	memset(rep, 0, sizeof(*rep));
	r->error[0] = '\0';
	e = sound_backup(r, path, &from);
	if (!e && (e = open_db(r, r->path, true, &db, &how)) == -EBADMSG) {
		move_aside(r); /* a damaged one: kept beside, as a rebuild */
		e = open_db(r, r->path, true, &db, &how);
	}
	e = e ? e : copy_pages(r, db, from, "restoring it");
	sqlite3_close(db);
	sqlite3_close(from);
	return e ? e : records_check(r, RECORDS_DEEP | RECORDS_FIX, skip, rep);
}

void records_report_free(struct records_report *rep)
{
	free(rep->text);
	rep->text = NULL;
}
