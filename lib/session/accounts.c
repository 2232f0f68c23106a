/* accounts.c - see accounts.h. */
#include "session/accounts.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>

#include <sodium.h>
#include <sqlite3.h>

#define BUSY_MS 5000

static const char schema[] =
	"CREATE TABLE users (name TEXT PRIMARY KEY,"
	" role TEXT NOT NULL CHECK (role IN ('trainee', 'instructor',"
	" 'administrator')),"
	" pin TEXT NOT NULL,"
	" failures INTEGER NOT NULL DEFAULT 0,"
	" wait_until REAL NOT NULL DEFAULT 0);"
	"CREATE TABLE groups (name TEXT PRIMARY KEY,"
	" instructor TEXT NOT NULL REFERENCES users(name));"
	"CREATE TABLE members (group_name TEXT NOT NULL"
	" REFERENCES groups(name) ON DELETE CASCADE,"
	" trainee TEXT NOT NULL REFERENCES users(name) ON DELETE CASCADE,"
	" PRIMARY KEY (group_name, trainee));"
	"CREATE TABLE courses (group_name TEXT NOT NULL"
	" REFERENCES groups(name) ON DELETE CASCADE,"
	" course TEXT NOT NULL, PRIMARY KEY (group_name, course));"
	"PRAGMA user_version = 1;";

/*
 * Version 2: a centre's copy (accounts.h). The triggers queue each change
 * while centre.queue is set; a member or course gone with its user or
 * group (a cascade) is not queued apart: the centre's cascade does it.
 */
#define QUEUED(when) " WHEN (SELECT queue FROM centre)" when " BEGIN" \
	" INSERT INTO centre_queue (op, name, role, pin, group_name, course)"
static const char schema_v2[] =
	"CREATE TABLE centre (one INTEGER PRIMARY KEY CHECK (one = 1),"
	" url TEXT, version TEXT, queue INTEGER NOT NULL DEFAULT 0);"
	"INSERT INTO centre (one) VALUES (1);"
	"CREATE TABLE centre_queue (seq INTEGER PRIMARY KEY AUTOINCREMENT,"
	" id TEXT NOT NULL UNIQUE DEFAULT (lower(hex(randomblob(16)))),"
	" op TEXT NOT NULL, name TEXT NOT NULL, role TEXT NOT NULL,"
	" pin TEXT NOT NULL, group_name TEXT NOT NULL, course TEXT NOT NULL);"
	"CREATE TRIGGER user_added AFTER INSERT ON users" QUEUED("")
	" VALUES ('user_add', NEW.name, NEW.role, NEW.pin, '', ''); END;"
	"CREATE TRIGGER user_pin AFTER UPDATE OF pin ON users" QUEUED("")
	" VALUES ('user_pin', NEW.name, '', NEW.pin, '', ''); END;"
	"CREATE TRIGGER user_removed AFTER DELETE ON users" QUEUED("")
	" VALUES ('user_remove', OLD.name, '', '', '', ''); END;"
	"CREATE TRIGGER group_added AFTER INSERT ON groups" QUEUED("")
	" VALUES ('group_add', NEW.instructor, '', '', NEW.name, ''); END;"
	"CREATE TRIGGER group_removed AFTER DELETE ON groups" QUEUED("")
	" VALUES ('group_remove', '', '', '', OLD.name, ''); END;"
	"CREATE TRIGGER member_joined AFTER INSERT ON members" QUEUED("")
	" VALUES ('group_join', NEW.trainee, '', '', NEW.group_name, ''); END;"
	"CREATE TRIGGER member_left AFTER DELETE ON members"
	QUEUED(" AND EXISTS (SELECT 1 FROM users WHERE name = OLD.trainee)"
	       " AND EXISTS (SELECT 1 FROM groups WHERE name = OLD.group_name)")
	" VALUES ('group_leave', OLD.trainee, '', '', OLD.group_name, ''); END;"
	"CREATE TRIGGER course_assigned AFTER INSERT ON courses" QUEUED("")
	" VALUES ('group_assign', '', '', '', NEW.group_name, NEW.course); END;"
	"CREATE TRIGGER course_unassigned AFTER DELETE ON courses"
	QUEUED(" AND EXISTS (SELECT 1 FROM groups WHERE name = OLD.group_name)")
	" VALUES ('group_unassign', '', '', '', OLD.group_name, OLD.course);"
	" END;"
	"PRAGMA user_version = 2;";

/* migrations[V] takes a database of version V to V + 1. */
static const char *const migrations[ACCOUNTS_SCHEMA_VERSION] = {
	schema, schema_v2,
};

struct accounts {
	char path[4096];
	char dummy[crypto_pwhash_STRBYTES]; /* an unknown name's hash */
	char error[1024];
};

struct accounts *accounts_create(const char *path)
{
	struct accounts *a;

	if (sodium_init() < 0 || !(a = calloc(1, sizeof(*a)))) {
		return NULL;
	}
	snprintf(a->path, sizeof(a->path), "%s", path);
	return a;
}

void accounts_destroy(struct accounts *a)
{
	if (a) {
		sodium_memzero(a, sizeof(*a));
		free(a);
	}
}

const char *accounts_path(const struct accounts *a)
{
	return a->path;
}

const char *accounts_error(const struct accounts *a)
{
	return a->error;
}

/* Says in A's error why; returns E. */
static int fail(struct accounts *a, int e, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));
static int fail(struct accounts *a, int e, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(a->error, sizeof(a->error), fmt, ap);
	va_end(ap);
	return e;
}

static int sql_fail(struct accounts *a, sqlite3 *db, const char *what)
{
	return fail(a, -EIO, "accounts %s: %s: %s", a->path, what,
		    db ? sqlite3_errmsg(db) : "out of memory");
}

/* ---------------------------------------------------------- the file */

static int schema_version(sqlite3 *db)
{
	sqlite3_stmt *st;
	int v = 0;

	if (sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &st, NULL) ==
	    SQLITE_OK && sqlite3_step(st) == SQLITE_ROW) {
		v = sqlite3_column_int(st, 0);
	}
	sqlite3_finalize(st);
	return v;
}

/* DB brought to this schema by its migrations, in one transaction. */
static int migrate(struct accounts *a, sqlite3 *db)
{
	int rc = sqlite3_exec(db, "BEGIN IMMEDIATE", NULL, NULL, NULL), e;

	/* read under the lock: the other thread may have done it since */
	for (int v = schema_version(db); !rc && v < ACCOUNTS_SCHEMA_VERSION;
	     v++) {
		rc = sqlite3_exec(db, migrations[v], NULL, NULL, NULL);
	}
	if (!rc && !sqlite3_exec(db, "COMMIT", NULL, NULL, NULL)) {
		return 0;
	}
	e = sql_fail(a, db, "making its schema");
	sqlite3_exec(db, "ROLLBACK", NULL, NULL, NULL);
	return e;
}

/* The database opened into *DB, made (0600) when missing and CREATE;
 * else *DB NULL when missing. 0 or -EIO (-EPROTO: a newer schema). */
static int open_db(struct accounts *a, bool create, sqlite3 **db)
{
	int v, fd;

	*db = NULL;
	a->error[0] = '\0';
	if (access(a->path, F_OK)) {
		if (!create) {
			return 0;
		}
		fd = open(a->path, O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
		if (fd < 0) {
			return fail(a, -errno, "accounts %s: %s", a->path,
				    strerror(errno));
		}
		close(fd);
	}
	if (sqlite3_open_v2(a->path, db, SQLITE_OPEN_READWRITE |
			    SQLITE_OPEN_NOMUTEX, NULL) != SQLITE_OK) {
		int e = sql_fail(a, *db, "opening it");

		sqlite3_close(*db);
		*db = NULL;
		return e;
	}
	sqlite3_busy_timeout(*db, BUSY_MS);
	v = schema_version(*db);
	if (v > ACCOUNTS_SCHEMA_VERSION) {
		sqlite3_close(*db);
		*db = NULL;
		return fail(a, -EPROTO, "accounts %s: its schema is version "
			    "%d, newer than this endosim's %d", a->path, v,
			    ACCOUNTS_SCHEMA_VERSION);
	}
	if ((v < ACCOUNTS_SCHEMA_VERSION && migrate(a, *db)) ||
	    sqlite3_exec(*db, "PRAGMA foreign_keys = ON", NULL, NULL, NULL)) {
		int e = a->error[0] ? -EIO : sql_fail(a, *db, "making its "
						      "schema");

		sqlite3_close(*db);
		*db = NULL;
		return e;
	}
	return 0;
}

/* SQL prepared with its texts bound (NULL ends them) into *ST. */
static int prepare(struct accounts *a, sqlite3 *db, sqlite3_stmt **st,
		   const char *sql, ...)
{
	const char *text;
	va_list ap;
	int i = 1;

	if (sqlite3_prepare_v2(db, sql, -1, st, NULL) != SQLITE_OK) {
		return sql_fail(a, db, sql);
	}
	va_start(ap, sql);
	while ((text = va_arg(ap, const char *))) {
		sqlite3_bind_text(*st, i++, text, -1, SQLITE_TRANSIENT);
	}
	va_end(ap);
	return 0;
}

/* ST stepped to its end and finalized: 0, -ENOENT (it changed nothing
 * where CHANGE), -EEXIST or -EBUSY (a constraint: unique, or a key
 * still used), -EIO. */
static int run(struct accounts *a, sqlite3 *db, sqlite3_stmt *st,
	       bool change)
{
	int rc = sqlite3_step(st);
	int ext = sqlite3_extended_errcode(db);

	sqlite3_finalize(st);
	if (rc == SQLITE_DONE) {
		return change && !sqlite3_changes(db) ? -ENOENT : 0;
	}
	if (ext == SQLITE_CONSTRAINT_PRIMARYKEY ||
	    ext == SQLITE_CONSTRAINT_UNIQUE) {
		return -EEXIST;
	}
	if (ext == SQLITE_CONSTRAINT_FOREIGNKEY) {
		return -EBUSY;
	}
	return sql_fail(a, db, "writing");
}

/* ------------------------------------------------------------ rules */

static bool bad_text(const char *s, size_t min, size_t max)
{
	size_t n = strlen(s);

	for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
		if (*p < 0x20 || *p == 0x7f) {
			return true;
		}
	}
	return n < min || n > max;
}

static int check_name(struct accounts *a, const char *what, const char *n)
{
	return bad_text(n, 1, ACCOUNTS_NAME_MAX) ? fail(a, -EINVAL, "%s: "
		"1 to %d bytes, no control characters", what,
		ACCOUNTS_NAME_MAX) : 0;
}

/* PIN hashed into OUT. */
static int hash_pin(struct accounts *a, const char *pin,
		    char out[crypto_pwhash_STRBYTES])
{
	if (bad_text(pin, ACCOUNTS_PIN_MIN, ACCOUNTS_PIN_MAX)) {
		return fail(a, -EINVAL, "a PIN: %d to %d characters, no "
			    "control characters", ACCOUNTS_PIN_MIN,
			    ACCOUNTS_PIN_MAX);
	}
	if (crypto_pwhash_str_alg(out, pin, strlen(pin), ACCOUNTS_PIN_OPS,
				  ACCOUNTS_PIN_MEM,
				  crypto_pwhash_ALG_ARGON2ID13)) {
		return fail(a, -ENOMEM, "hashing a PIN: out of memory");
	}
	return 0;
}

/* ------------------------------------------------------------ users */

/* SQL (its texts the rest, NULL-ended) run on the database made if
 * need be; what run() returns, in words for -ENOENT, -EEXIST, -EBUSY. */
static int change(struct accounts *a, const char *why_missing,
		  const char *why_exists, const char *sql, const char *t1,
		  const char *t2, const char *t3)
{
	sqlite3_stmt *st;
	sqlite3 *db;
	int e = open_db(a, true, &db);

	if (!e && !(e = prepare(a, db, &st, sql, t1, t2, t3, NULL))) {
		e = run(a, db, st, why_missing != NULL);
	}
	sqlite3_close(db);
	if (e == -ENOENT && why_missing) {
		fail(a, e, "%s", why_missing);
	} else if ((e == -EEXIST || e == -EBUSY) && why_exists) {
		fail(a, e, "%s", why_exists);
	}
	return e;
}

int accounts_user_add(struct accounts *a, const char *name,
		      enum accounts_role role, const char *pin)
{
	char hash[crypto_pwhash_STRBYTES], exists[128];
	int e;

	if ((e = check_name(a, "a user's name", name)) ||
	    (e = hash_pin(a, pin, hash))) {
		return e;
	}
	snprintf(exists, sizeof(exists), "there is a user %s already", name);
	return change(a, NULL, exists, "INSERT INTO users (name, role, pin) "
		      "VALUES (?, ?, ?)", name, accounts_role_name(role),
		      hash);
}

int accounts_user_pin(struct accounts *a, const char *name, const char *pin)
{
	char hash[crypto_pwhash_STRBYTES], missing[128];
	int e = hash_pin(a, pin, hash);

	snprintf(missing, sizeof(missing), "no user %s", name);
	return e ? e : change(a, missing, NULL, "UPDATE users SET pin = ?, "
			      "failures = 0, wait_until = 0 WHERE name = ?",
			      hash, name, NULL);
}

int accounts_user_remove(struct accounts *a, const char *name)
{
	char missing[128], busy[160];

	snprintf(missing, sizeof(missing), "no user %s", name);
	snprintf(busy, sizeof(busy), "%s manages a group: give it another "
		 "instructor or remove it first", name);
	return change(a, missing, busy, "DELETE FROM users WHERE name = ?",
		      name, NULL, NULL);
}

/* The wait a user's FAILURES wrong PINs in a row earn, in seconds. */
static double wait_for(long failures)
{
	long over = failures - ACCOUNTS_FREE_TRIES;

	return over < 0 ? 0 : fmin(ldexp(1.0, (int)fmin(over, 30)),
				   ACCOUNTS_WAIT_MAX_S);
}

/* A wrong PIN of NAME counted; the wait it earns into *WAIT_S. */
static int count_failure(struct accounts *a, sqlite3 *db, const char *name,
			 long failures, double now_s, double *wait_s)
{
	char until[32], n[24];
	sqlite3_stmt *st;
	int e;

	*wait_s = wait_for(failures + 1);
	snprintf(until, sizeof(until), "%.3f", *wait_s ? now_s + *wait_s : 0);
	snprintf(n, sizeof(n), "%ld", failures + 1);
	e = prepare(a, db, &st, "UPDATE users SET failures = ?, wait_until = "
		    "? WHERE name = ?", n, until, name, NULL);
	return e ? e : run(a, db, st, false);
}

int accounts_login(struct accounts *a, const char *name, const char *pin,
		   double now_s, struct accounts_user *u, double *wait_s)
{
	char kept[crypto_pwhash_STRBYTES];
	const char *hash = NULL;
	sqlite3_stmt *st = NULL;
	long failures = 0;
	double until = 0;
	sqlite3 *db;
	bool right;
	int e = open_db(a, false, &db);

	*wait_s = 0;
	memset(u, 0, sizeof(*u));
	if (!e && db && !(e = prepare(a, db, &st, "SELECT role, pin, "
				      "failures, wait_until FROM users WHERE "
				      "name = ?", name, NULL)) &&
	    sqlite3_step(st) == SQLITE_ROW) {
		accounts_role_parse((const char *)sqlite3_column_text(st, 0),
				    &u->role);
		snprintf(kept, sizeof(kept), "%s",
			 (const char *)sqlite3_column_text(st, 1));
		hash = kept;
		failures = (long)sqlite3_column_int64(st, 2);
		until = sqlite3_column_double(st, 3);
	}
	/* the read ended before the hash and any write: a wrong PIN counted
	 * while the read held on would meet a writer beside us (the
	 * centre's worker) waiting for it to end, and SQLite refuses the
	 * one that would deadlock */
	sqlite3_finalize(st);
	if (!e && hash && until > now_s) {
		*wait_s = until - now_s;
		e = fail(a, -EAGAIN, "too many wrong PINs for %s: try again "
			 "in %.0f s", name, ceil(*wait_s));
	} else if (!e) {
		if (!hash && !a->dummy[0]) {
			hash_pin(a, "0000", a->dummy);
		}
		/* an unknown name costs the same hash as a known one */
		right = !crypto_pwhash_str_verify(hash ? hash : a->dummy, pin,
						  strlen(pin)) && hash;
		snprintf(u->name, sizeof(u->name), "%s", name);
		if (!right) {
			e = hash ? count_failure(a, db, name, failures, now_s,
						 wait_s) : 0;
			e = e ? e : fail(a, -EACCES, "wrong name or PIN");
		} else if (failures) {
			e = count_failure(a, db, name, -1, now_s, wait_s);
		}
	}
	sqlite3_close(db);
	return e;
}

int accounts_users(struct accounts *a, struct accounts_user **out,
		   size_t *n)
{
	sqlite3_stmt *st;
	sqlite3 *db;
	int e = open_db(a, false, &db), rc;

	*n = 0;
	*out = NULL;
	if (e || !db) {
		return e;
	}
	if (!(e = prepare(a, db, &st, "SELECT name, role FROM users ORDER "
			  "BY name", NULL))) {
		while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
			struct accounts_user *more = realloc(*out, (*n + 1) *
							     sizeof(*more));

			if (!more) {
				e = -ENOMEM;
				break;
			}
			*out = more;
			snprintf(more[*n].name, sizeof(more[*n].name), "%s",
				 (const char *)sqlite3_column_text(st, 0));
			accounts_role_parse((const char *)
					    sqlite3_column_text(st, 1),
					    &more[(*n)++].role);
		}
		e = e ? e : rc == SQLITE_DONE ? 0 : sql_fail(a, db, "users");
		sqlite3_finalize(st);
	}
	sqlite3_close(db);
	return e;
}

/* ----------------------------------------------------------- groups */

/* Whether NAME is a user of ROLE: 0, -ENOENT (in words), -EIO. */
static int has_role(struct accounts *a, const char *name,
		    enum accounts_role role)
{
	struct accounts_user *u;
	size_t n;
	int e = accounts_users(a, &u, &n);
	bool found = false;

	for (size_t i = 0; !e && i < n; i++) {
		found |= !strcmp(u[i].name, name) && u[i].role == role;
	}
	free(u);
	return e ? e : found ? 0 : fail(a, -ENOENT, "no %s %s",
					accounts_role_name(role), name);
}

int accounts_group_add(struct accounts *a, const char *name,
		       const char *instructor)
{
	char exists[128];
	int e;

	if ((e = check_name(a, "a group's name", name)) ||
	    (e = has_role(a, instructor, ACCOUNTS_INSTRUCTOR))) {
		return e;
	}
	snprintf(exists, sizeof(exists), "there is a group %s already", name);
	return change(a, NULL, exists, "INSERT INTO groups (name, instructor)"
		      " VALUES (?, ?)", name, instructor, NULL);
}

int accounts_group_remove(struct accounts *a, const char *name)
{
	char missing[128];

	snprintf(missing, sizeof(missing), "no group %s", name);
	return change(a, missing, NULL, "DELETE FROM groups WHERE name = ?",
		      name, NULL, NULL);
}

/* Whether group NAME exists: 0, -ENOENT (in words), -EIO. */
static int has_group(struct accounts *a, const char *name)
{
	struct accounts_group *g;
	size_t n;
	int e = accounts_groups(a, NULL, &g, &n);
	bool found = false;

	for (size_t i = 0; !e && i < n; i++) {
		found |= !strcmp(g[i].name, name);
	}
	accounts_groups_free(g, n);
	return e ? e : found ? 0 : fail(a, -ENOENT, "no group %s", name);
}

int accounts_group_member(struct accounts *a, const char *name,
			  const char *trainee, bool join)
{
	int e;

	if ((e = has_group(a, name)) ||
	    (join && (e = has_role(a, trainee, ACCOUNTS_TRAINEE)))) {
		return e;
	}
	return change(a, NULL, NULL, join ? "INSERT OR IGNORE INTO members "
		      "(group_name, trainee) VALUES (?, ?)" : "DELETE FROM "
		      "members WHERE group_name = ? AND trainee = ?", name,
		      trainee, NULL);
}

int accounts_group_course(struct accounts *a, const char *name,
			  const char *course, bool assign)
{
	int e;

	if (bad_text(course, 1, ACCOUNTS_COURSE_MAX)) {
		return fail(a, -EINVAL, "a course: 1 to %d bytes, no control "
			    "characters", ACCOUNTS_COURSE_MAX);
	}
	if ((e = has_group(a, name))) {
		return e;
	}
	return change(a, NULL, NULL, assign ? "INSERT OR IGNORE INTO courses "
		      "(group_name, course) VALUES (?, ?)" : "DELETE FROM "
		      "courses WHERE group_name = ? AND course = ?", name,
		      course, NULL);
}

/* A text column of ST as a malloc'd string ("" for NULL). */
static char *dup_column(sqlite3_stmt *st, int col)
{
	const unsigned char *t = sqlite3_column_text(st, col);

	return strdup(t ? (const char *)t : "");
}

int accounts_groups(struct accounts *a, const char *instructor,
		    struct accounts_group **out, size_t *n)
{
	sqlite3_stmt *st;
	sqlite3 *db;
	int e = open_db(a, false, &db), rc;

	*n = 0;
	*out = NULL;
	if (e || !db) {
		return e;
	}
	e = prepare(a, db, &st, "SELECT g.name, g.instructor, (SELECT "
		    "group_concat(trainee, char(10)) FROM (SELECT trainee FROM "
		    "members WHERE group_name = g.name ORDER BY trainee)), "
		    "(SELECT group_concat(course, char(10)) FROM (SELECT course "
		    "FROM courses WHERE group_name = g.name ORDER BY course)) "
		    "FROM groups g WHERE ?1 IS NULL OR g.instructor = ?1 "
		    "ORDER BY g.name", instructor, NULL);
	while (!e && (rc = sqlite3_step(st)) == SQLITE_ROW) {
		struct accounts_group *more = realloc(*out, (*n + 1) *
						      sizeof(*more));

		if (!more) {
			e = -ENOMEM;
			break;
		}
		*out = more;
		more += (*n)++;
		snprintf(more->name, sizeof(more->name), "%s",
			 (const char *)sqlite3_column_text(st, 0));
		snprintf(more->instructor, sizeof(more->instructor), "%s",
			 (const char *)sqlite3_column_text(st, 1));
		more->trainees = dup_column(st, 2);
		more->courses = dup_column(st, 3);
		e = more->trainees && more->courses ? 0 : -ENOMEM;
	}
	if (!e && rc != SQLITE_DONE) {
		e = sql_fail(a, db, "groups");
	}
	sqlite3_finalize(st);
	sqlite3_close(db);
	if (e) {
		accounts_groups_free(*out, *n);
		*out = NULL;
		*n = 0;
	}
	return e;
}

void accounts_groups_free(struct accounts_group *g, size_t n)
{
	for (size_t i = 0; g && i < n; i++) {
		free(g[i].trainees);
		free(g[i].courses);
	}
	free(g);
}

/* ------------------------------------------------------- who sees */

int accounts_seen(struct accounts *a, const struct accounts_user *u,
		  char **names, bool *all)
{
	struct accounts_group *g = NULL;
	size_t n = 0, len = 0;
	FILE *m;
	int e = 0;

	*all = u->role == ACCOUNTS_ADMINISTRATOR;
	if (!(m = open_memstream(names, &len))) {
		return -ENOMEM;
	}
	if (u->role == ACCOUNTS_TRAINEE) {
		fputs(u->name, m);
	} else if (u->role == ACCOUNTS_INSTRUCTOR &&
		   !(e = accounts_groups(a, u->name, &g, &n))) {
		for (size_t i = 0; i < n; i++) {
			fprintf(m, "%s%s", i && g[i].trainees[0] ? "\n" : "",
				g[i].trainees);
		}
	}
	accounts_groups_free(g, n);
	if (fclose(m) && !e) {
		e = -ENOMEM;
	}
	if (e) {
		free(*names);
		*names = NULL;
	}
	return e;
}

bool accounts_among(const char *names, const char *trainee)
{
	size_t len = strlen(trainee);

	for (const char *p = names; p && *p;) {
		const char *end = strchr(p, '\n');
		size_t n = end ? (size_t)(end - p) : strlen(p);

		if (n == len && !memcmp(p, trainee, n)) {
			return true;
		}
		p = end ? end + 1 : p + n;
	}
	return false;
}

/* ------------------------------------------------- who changes what */

/* Whether instructor ME may make CH, given every group G (N). */
static int groups_may(struct accounts *a, const char *me,
		      const struct accounts_change *ch,
		      const struct accounts_group *g, size_t n)
{
	const struct accounts_group *to = NULL;

	for (size_t i = 0; i < n; i++) {
		bool mine = !strcmp(g[i].instructor, me);

		if (ch->op == ACCOUNTS_USER_PIN && mine &&
		    accounts_among(g[i].trainees, ch->name)) {
			return 0;
		}
		if (ch->op == ACCOUNTS_GROUP_JOIN && !mine &&
		    accounts_among(g[i].trainees, ch->name)) {
			return fail(a, -EPERM, "%s is a trainee of group %s, "
				    "%s's: an administrator moves a trainee "
				    "to another instructor", ch->name,
				    g[i].name, g[i].instructor);
		}
		to = strcmp(g[i].name, ch->group) ? to : &g[i];
	}
	if (ch->op == ACCOUNTS_USER_PIN) {
		return fail(a, -EPERM, "%s's PIN: an instructor sets the PINs "
			    "of their groups' trainees only", ch->name);
	}
	if (to && strcmp(to->instructor, me)) {
		return fail(a, -EPERM, "group %s is %s's: an instructor "
			    "changes only the groups they manage", to->name,
			    to->instructor);
	}
	return 0; /* no such group: the change itself says so */
}

static int instructor_may(struct accounts *a, const char *me,
			  const struct accounts_change *ch)
{
	struct accounts_group *g;
	size_t n;
	int e;

	switch (ch->op) {
	case ACCOUNTS_USER_ADD:
		return ch->role == ACCOUNTS_TRAINEE ? 0 : fail(a, -EPERM,
			"an instructor adds trainees only: an administrator "
			"adds instructors and administrators");
	case ACCOUNTS_USER_REMOVE:
		return fail(a, -EPERM, "only an administrator removes a user");
	case ACCOUNTS_GROUP_ADD:
	case ACCOUNTS_GROUP_REMOVE:
		return fail(a, -EPERM, "only an administrator makes or removes "
			    "a group");
	default:
		break;
	}
	if ((e = accounts_groups(a, NULL, &g, &n))) {
		return e;
	}
	e = groups_may(a, me, ch, g, n);
	accounts_groups_free(g, n);
	return e;
}

int accounts_may(struct accounts *a, const struct accounts_user *u,
		 const struct accounts_change *ch)
{
	a->error[0] = '\0';
	if (u->role == ACCOUNTS_ADMINISTRATOR ||
	    (ch->op == ACCOUNTS_USER_PIN && !strcmp(ch->name, u->name))) {
		return 0;
	}
	if (u->role == ACCOUNTS_INSTRUCTOR) {
		return instructor_may(a, u->name, ch);
	}
	return fail(a, -EPERM, "only an administrator, or an instructor in the "
		    "groups they manage, changes the accounts");
}

/* ------------------------------------------------- a centre's copy */

/* SQL (statements without texts) run on DB. */
static int exec(struct accounts *a, sqlite3 *db, const char *sql)
{
	return sqlite3_exec(db, sql, NULL, NULL, NULL) ?
	       sql_fail(a, db, "writing") : 0;
}

/* SQL with up to three texts (the first NULL ends them) run on DB; as
 * run(). */
static int step(struct accounts *a, sqlite3 *db, const char *sql,
		const char *t1, const char *t2, const char *t3)
{
	sqlite3_stmt *st;
	int e = prepare(a, db, &st, sql, t1, t2, t3, NULL);

	return e ? e : run(a, db, st, false);
}

/* The transaction begun on DB committed when E is 0, else rolled back;
 * E or COMMIT's failure. */
static int finish(struct accounts *a, sqlite3 *db, int e)
{
	if (!e && !(e = exec(a, db, "COMMIT"))) {
		return 0;
	}
	sqlite3_exec(db, "ROLLBACK", NULL, NULL, NULL);
	return e;
}

/* Everything the accounts hold, queued for a centre that has none of
 * it; the queue before it forgotten (this replaces it). */
#define QUEUE_ALL "INSERT INTO centre_queue (op, name, role, pin," \
	" group_name, course) SELECT "
static const char queue_all[] =
	"DELETE FROM centre_queue;"
	QUEUE_ALL "'user_add', name, role, pin, '', '' FROM users"
	" ORDER BY name;"
	QUEUE_ALL "'group_add', instructor, '', '', name, '' FROM groups"
	" ORDER BY name;"
	QUEUE_ALL "'group_join', trainee, '', '', group_name, '' FROM members"
	" ORDER BY group_name, trainee;"
	QUEUE_ALL "'group_assign', '', '', '', group_name, course FROM courses"
	" ORDER BY group_name, course;";

/* Queueing on, for the centre URL (everything queued when new). */
static int keep_with(struct accounts *a, sqlite3 *db, const char *url)
{
	sqlite3_stmt *st;
	bool same;
	int e = prepare(a, db, &st, "SELECT url IS ? FROM centre", url, NULL);

	if (e) {
		return e;
	}
	same = sqlite3_step(st) == SQLITE_ROW && sqlite3_column_int(st, 0);
	sqlite3_finalize(st);
	if (same) {
		return exec(a, db, "UPDATE centre SET queue = 1");
	}
	return (e = exec(a, db, queue_all)) ? e : step(a, db, "UPDATE centre "
		"SET queue = 1, url = ?, version = NULL", url, NULL, NULL);
}

int accounts_centre(struct accounts *a, const char *url)
{
	bool on = url && *url;
	sqlite3 *db;
	int e = open_db(a, on, &db);

	if (e || !db) {
		return e;
	}
	e = exec(a, db, "BEGIN IMMEDIATE");
	if (!e) {
		e = on ? keep_with(a, db, url) : exec(a, db, "UPDATE centre "
			"SET url = NULL, version = NULL, queue = 0;"
			"DELETE FROM centre_queue");
	}
	e = finish(a, db, e);
	sqlite3_close(db);
	return e;
}

/* A text column of ST ("" for NULL) into OUT. */
static void column_into(sqlite3_stmt *st, int col, char *out, size_t size)
{
	const unsigned char *t = sqlite3_column_text(st, col);

	snprintf(out, size, "%s", t ? (const char *)t : "");
}

/* The row of ST (accounts_queue_head()'s columns) into Q. */
static int queued_row(struct accounts *a, sqlite3_stmt *st,
		      struct accounts_queued *q, size_t *waiting)
{
	char op[32], role[32];

	column_into(st, 0, q->id, sizeof(q->id));
	column_into(st, 1, op, sizeof(op));
	column_into(st, 2, q->name, sizeof(q->name));
	column_into(st, 3, role, sizeof(role));
	column_into(st, 4, q->pin, sizeof(q->pin));
	column_into(st, 5, q->group, sizeof(q->group));
	column_into(st, 6, q->course, sizeof(q->course));
	*waiting = (size_t)sqlite3_column_int64(st, 7);
	q->ch = (struct accounts_change){ .name = q->name, .pin = q->pin,
					  .group = q->group,
					  .course = q->course };
	if (*role) {
		accounts_role_parse(role, &q->ch.role);
	}
	return accounts_op_parse(op, &q->ch.op) ? fail(a, -EIO, "accounts "
		"%s: a change %s in the centre's queue", a->path, op) : 0;
}

int accounts_queue_head(struct accounts *a, struct accounts_queued *q,
			size_t *waiting)
{
	sqlite3_stmt *st;
	sqlite3 *db;
	int e = open_db(a, false, &db), rc;

	*waiting = 0;
	if (e || !db) {
		return e ? e : -ENOENT;
	}
	if (!(e = prepare(a, db, &st, "SELECT id, op, name, role, pin, "
			  "group_name, course, (SELECT count(*) FROM "
			  "centre_queue) FROM centre_queue ORDER BY seq "
			  "LIMIT 1", NULL))) {
		rc = sqlite3_step(st);
		e = rc == SQLITE_ROW ? queued_row(a, st, q, waiting) :
		    rc == SQLITE_DONE ? -ENOENT : sql_fail(a, db, "its queue");
		sqlite3_finalize(st);
	}
	sqlite3_close(db);
	return e;
}

int accounts_queue_arrived(struct accounts *a, const char *id)
{
	sqlite3 *db;
	int e = open_db(a, false, &db);

	if (!e && db) {
		e = step(a, db, "DELETE FROM centre_queue WHERE id = ?", id,
			 NULL, NULL);
	}
	sqlite3_close(db);
	return e;
}

int accounts_copy_version(struct accounts *a, char *out, size_t size)
{
	sqlite3_stmt *st;
	sqlite3 *db;
	int e = open_db(a, false, &db);

	*out = '\0';
	if (e || !db) {
		return e;
	}
	if (!(e = prepare(a, db, &st, "SELECT version FROM centre", NULL))) {
		if (sqlite3_step(st) == SQLITE_ROW) {
			column_into(st, 0, out, size);
		}
		sqlite3_finalize(st);
	}
	sqlite3_close(db);
	return e;
}

/* -EBUSY, in words, while changes of the rig are queued. */
static int queue_empty(struct accounts *a, sqlite3 *db)
{
	sqlite3_stmt *st;
	long n = 0;
	int e = prepare(a, db, &st, "SELECT count(*) FROM centre_queue", NULL);

	if (e) {
		return e;
	}
	if (sqlite3_step(st) == SQLITE_ROW) {
		n = (long)sqlite3_column_int64(st, 0);
	}
	sqlite3_finalize(st);
	return n ? fail(a, -EBUSY, "%ld changes of the rig's accounts wait "
			"for the centre", n) : 0;
}

/* CH's names and texts within the rules. */
static int copy_checked(struct accounts *a, const struct accounts_change *ch)
{
	int e = 0;

	if (ch->op == ACCOUNTS_USER_ADD &&
	    (strncmp(ch->pin, "$argon2id$", 10) ||
	     strlen(ch->pin) > ACCOUNTS_HASH_MAX)) {
		return fail(a, -EINVAL, "%s's PIN: not an Argon2id string",
			    ch->name);
	}
	if (ch->op != ACCOUNTS_GROUP_ASSIGN) {
		e = check_name(a, "a user's name", ch->name);
	}
	if (!e && ch->op != ACCOUNTS_USER_ADD) {
		e = check_name(a, "a group's name", ch->group);
	}
	if (!e && ch->op == ACCOUNTS_GROUP_ASSIGN &&
	    bad_text(ch->course, 1, ACCOUNTS_COURSE_MAX)) {
		e = fail(a, -EINVAL, "a course: 1 to %d bytes, no control "
			 "characters", ACCOUNTS_COURSE_MAX);
	}
	return e;
}

/* One change of the centre's copy made on DB (a user noted in kept). */
static int copy_one(struct accounts *a, sqlite3 *db,
		    const struct accounts_change *ch)
{
	int e = copy_checked(a, ch);

	if (e) {
		return e;
	}
	switch (ch->op) {
	case ACCOUNTS_USER_ADD:
		/* a wrong PINs' count kept while the PIN is the same */
		e = step(a, db, "INSERT INTO users (name, role, pin) VALUES "
			 "(?1, ?2, ?3) ON CONFLICT (name) DO UPDATE SET "
			 "role = excluded.role, failures = CASE WHEN "
			 "pin = excluded.pin THEN failures ELSE 0 END, "
			 "wait_until = CASE WHEN pin = excluded.pin THEN "
			 "wait_until ELSE 0 END, pin = excluded.pin", ch->name,
			 accounts_role_name(ch->role), ch->pin);
		return e ? e : step(a, db, "INSERT INTO temp.kept VALUES (?)",
				    ch->name, NULL, NULL);
	case ACCOUNTS_GROUP_ADD:
		return step(a, db, "INSERT INTO groups (name, instructor) "
			    "VALUES (?, ?)", ch->group, ch->name, NULL);
	case ACCOUNTS_GROUP_JOIN:
		return step(a, db, "INSERT INTO members (group_name, trainee) "
			    "VALUES (?, ?)", ch->group, ch->name, NULL);
	case ACCOUNTS_GROUP_ASSIGN:
		return step(a, db, "INSERT INTO courses (group_name, course) "
			    "VALUES (?, ?)", ch->group, ch->course, NULL);
	default:
		return fail(a, -EINVAL, "a %s in the centre's accounts",
			    accounts_op_name(ch->op));
	}
}

int accounts_replace(struct accounts *a, const char *version,
		     const struct accounts_change *ch, size_t n)
{
	sqlite3 *db;
	int e = open_db(a, true, &db);

	if (e) {
		return e;
	}
	if (!(e = exec(a, db, "BEGIN IMMEDIATE")) &&
	    !(e = queue_empty(a, db))) {
		e = exec(a, db, "UPDATE centre SET queue = 0;"
			 "DELETE FROM courses; DELETE FROM members;"
			 "DELETE FROM groups;"
			 "CREATE TEMP TABLE kept (name TEXT PRIMARY KEY)");
	}
	for (size_t i = 0; !e && i < n; i++) {
		if ((e = copy_one(a, db, &ch[i])) == -EEXIST || e == -EBUSY) {
			e = fail(a, -EINVAL, "the centre's accounts: %s %s%s%s "
				 "twice, or without its user or group",
				 accounts_op_name(ch[i].op), ch[i].name,
				 *ch[i].group ? " in " : "", ch[i].group);
		}
	}
	if (!e && !(e = exec(a, db, "DELETE FROM users WHERE name NOT IN "
			     "(SELECT name FROM temp.kept)"))) {
		e = step(a, db, "UPDATE centre SET queue = 1, version = ?",
			 version, NULL, NULL);
	}
	e = finish(a, db, e);
	sqlite3_close(db);
	return e;
}
