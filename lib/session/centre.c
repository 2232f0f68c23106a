/* centre.c - see centre.h. */
#include "session/centre.h"
#include "session/metricstext.h"
#include "session/report.h"
#include "session/sessionview.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libpq-fe.h>

/* The columns before the measures', in the order of the statements. */
#define HEAD_COLUMNS "uuid, rig, rig_session, trainee, case_name, " \
		     "started, ended, bytes, judgement, has_measures"
#define HEAD_N 10

/* Held while a writer makes or completes the schema ("endo"). */
#define SCHEMA_LOCK "1701733487"

static const char schema[] =
	"CREATE TABLE IF NOT EXISTS sessions ("
	" uuid uuid PRIMARY KEY,"
	" arrival bigserial NOT NULL,"
	" rig text NOT NULL,"
	" rig_session bigint NOT NULL,"
	" trainee text NOT NULL,"
	" case_name text NOT NULL,"
	" started text NOT NULL,"
	" ended boolean NOT NULL,"
	" bytes bigint NOT NULL,"
	" judgement text,"
	" has_measures boolean NOT NULL,"
	" report text,"
	" received timestamptz NOT NULL DEFAULT now());"
	"CREATE INDEX IF NOT EXISTS sessions_by_trainee ON sessions"
	" (trainee, started);"
	"CREATE TABLE IF NOT EXISTS endosim_people ("
	" name text PRIMARY KEY,"
	" role text NOT NULL"
	"  CHECK (role IN ('trainee', 'instructor', 'administrator')),"
	" pin text NOT NULL);"
	"CREATE TABLE IF NOT EXISTS endosim_groups ("
	" name text PRIMARY KEY,"
	" instructor text NOT NULL REFERENCES endosim_people (name));"
	"CREATE TABLE IF NOT EXISTS endosim_members ("
	" group_name text NOT NULL"
	"  REFERENCES endosim_groups (name) ON DELETE CASCADE,"
	" trainee text NOT NULL"
	"  REFERENCES endosim_people (name) ON DELETE CASCADE,"
	" PRIMARY KEY (group_name, trainee));"
	"CREATE TABLE IF NOT EXISTS endosim_courses ("
	" group_name text NOT NULL"
	"  REFERENCES endosim_groups (name) ON DELETE CASCADE,"
	" course text NOT NULL,"
	" PRIMARY KEY (group_name, course));"
	"CREATE TABLE IF NOT EXISTS endosim_changes ("
	" id uuid PRIMARY KEY,"
	" arrival bigserial NOT NULL,"
	" rig text NOT NULL,"
	" op text NOT NULL,"
	" name text NOT NULL,"
	" group_name text NOT NULL,"
	" course text NOT NULL,"
	" applied boolean NOT NULL DEFAULT false,"
	" received timestamptz NOT NULL DEFAULT now());";
#define SCHEMA_COLUMNS 13 /* the table's before the measures' */

/* Held while a change of the people is taken ("peop"). */
#define PEOPLE_LOCK "1885695856"

struct centre {
	char *url;
	char app[32];
	PGconn *pg;
	char error[1024];
};

/* ------------------------------------------------------------ the URL */

int centre_check_url(const char *url, char *err, size_t size)
{
	char *why = NULL;
	PQconninfoOption *o = PQconninfoParse(url, &why);
	bool password = false;

	if (!o) {
		snprintf(err, size, "not a PostgreSQL connection URL (%s): %s",
			 url, why ? why : "out of memory");
		PQfreemem(why);
		return -EINVAL;
	}
	for (PQconninfoOption *p = o; p->keyword; p++) {
		password |= !strcmp(p->keyword, "password") && p->val &&
			    *p->val;
	}
	PQconninfoFree(o);
	if (password) {
		snprintf(err, size, "the centre's URL holds a password: put it "
			 "in libpq's password file (~/.pgpass, or PGPASSFILE) "
			 "or service file instead");
		return -EINVAL;
	}
	return 0;
}

struct centre *centre_create(const char *url, const char *app)
{
	struct centre *c = calloc(1, sizeof(*c));

	if (!c || !(c->url = strdup(url))) {
		free(c);
		return NULL;
	}
	snprintf(c->app, sizeof(c->app), "%s", app);
	return c;
}

void centre_destroy(struct centre *c)
{
	if (!c) {
		return;
	}
	centre_disconnect(c);
	free(c->url);
	free(c);
}

const char *centre_error(const struct centre *c)
{
	return c->error;
}

bool centre_connected(const struct centre *c)
{
	return c->pg && PQstatus(c->pg) == CONNECTION_OK;
}

void centre_disconnect(struct centre *c)
{
	PQfinish(c->pg);
	c->pg = NULL;
}

/* ------------------------------------------------------- statements */

/* libpq's words on one line (its lines joined by "; ", without the last
 * newline) into C's error after WHAT. */
static void say(struct centre *c, const char *what, const char *words)
{
	int at = snprintf(c->error, sizeof(c->error), "centre: %s: ", what);

	for (const char *w = words; *w && at < (int)sizeof(c->error) - 3;
	     w++) {
		if (*w == '\n' && w[1]) {
			at += snprintf(c->error + at, 3, "; ");
		} else if (*w != '\n' && *w != '\t') {
			c->error[at++] = *w;
		}
	}
	c->error[at] = '\0';
}

/*
 * What a failed statement's RES means: -ENOTCONN (the connection is
 * gone), -EBADMSG (the data were refused: SQLSTATE classes 22 and 23), or
 * -EIO. Clears RES.
 */
static int failed(struct centre *c, PGresult *res, const char *what)
{
	const char *state = res ? PQresultErrorField(res, PG_DIAG_SQLSTATE)
				: NULL;
	int e = -EIO;

	say(c, what, res ? PQresultErrorMessage(res) : PQerrorMessage(c->pg));
	if (PQstatus(c->pg) != CONNECTION_OK) {
		e = -ENOTCONN;
		centre_disconnect(c);
	} else if (state && (!strncmp(state, "22", 2) ||
			     !strncmp(state, "23", 2))) {
		e = -EBADMSG;
	}
	PQclear(res);
	return e;
}

/* SQL with the N texts V (NULL: SQL's NULL; of TYPES, NULL: as the
 * server infers them) run: its result in *RES (NULL: not wanted), or as
 * failed(). Without texts SQL may be several statements (PQexec()'s). */
static int run_typed(struct centre *c, const char *sql, int n,
		     const char *const *v, const Oid *types, PGresult **res,
		     const char *what)
{
	PGresult *r = n ? PQexecParams(c->pg, sql, n, types, v, NULL, NULL,
				       0) : PQexec(c->pg, sql);
	ExecStatusType st = PQresultStatus(r);

	if (st != PGRES_COMMAND_OK && st != PGRES_TUPLES_OK) {
		return failed(c, r, what);
	}
	if (res) {
		*res = r;
	} else {
		PQclear(r);
	}
	return 0;
}

static int run(struct centre *c, const char *sql, int n,
	       const char *const *v, PGresult **res, const char *what)
{
	return run_typed(c, sql, n, v, NULL, res, what);
}

/* ----------------------------------------------------------- schema */

/* The measures' columns the table lacks added. */
static int complete_columns(struct centre *c)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);
	PGresult *res;
	char sql[256];
	int e = run(c, "SELECT count(*) FROM information_schema.columns "
		    "WHERE table_schema = current_schema() AND table_name = "
		    "'sessions'", 0, NULL, &res, "reading the schema");
	long have;

	if (e) {
		return e;
	}
	have = strtol(PQgetvalue(res, 0, 0), NULL, 10);
	PQclear(res);
	for (size_t i = 0; !e && have < (long)(SCHEMA_COLUMNS + n) && i < n;
	     i++) {
		snprintf(sql, sizeof(sql), "ALTER TABLE sessions ADD COLUMN "
			 "IF NOT EXISTS \"%s\" %s", f[i].key,
			 f[i].kind == FIELDS_DOUBLE ? "double precision"
						    : "bigint");
		e = run(c, sql, 0, NULL, NULL, "adding a measure's column");
	}
	return e;
}

/* The table made or completed, in one transaction under the lock. */
static int make_schema(struct centre *c)
{
	int e = run(c, "BEGIN", 0, NULL, NULL, "BEGIN");

	if (!e && !(e = run(c, "SELECT pg_advisory_xact_lock(" SCHEMA_LOCK
			    ")", 0, NULL, NULL, "locking the schema")) &&
	    !(e = run(c, schema, 0, NULL, NULL, "making the schema")) &&
	    !(e = complete_columns(c))) {
		return run(c, "COMMIT", 0, NULL, NULL, "COMMIT");
	}
	if (c->pg) {
		PQclear(PQexec(c->pg, "ROLLBACK"));
	}
	return e;
}

int centre_connect(struct centre *c, bool write)
{
	char timeout[16];
	const char *const keys[] = { "connect_timeout", "application_name",
				     "dbname", NULL };
	const char *values[] = { timeout, c->app, c->url, NULL };
	int e;

	c->error[0] = '\0';
	if (centre_connected(c)) {
		return 0;
	}
	centre_disconnect(c);
	if ((e = centre_check_url(c->url, c->error, sizeof(c->error)))) {
		return e;
	}
	/* the URL's own connect_timeout, when it has one, comes later and
	 * wins (libpq: the last of a keyword is kept) */
	snprintf(timeout, sizeof(timeout), "%d", CENTRE_CONNECT_TIMEOUT_S);
	c->pg = PQconnectdbParams(keys, values, 1);
	if (!c->pg || PQstatus(c->pg) != CONNECTION_OK) {
		say(c, "cannot connect", c->pg ? PQerrorMessage(c->pg)
					       : "out of memory");
		centre_disconnect(c);
		return -ENOTCONN;
	}
	return write ? make_schema(c) : 0;
}

/* ----------------------------------------------------------- writing */

/*
 * "HEAD, "k1", "k2", ..." over the measures' keys (our own table's names,
 * never a value), then with VALUES ") VALUES ($1, ... $N)" for the head's
 * columns, the report's and the measures', then TAIL: malloc'd.
 */
static char *measures_sql(const char *head, bool values, const char *tail)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f), len = 0;
	char *text = NULL;
	FILE *m = open_memstream(&text, &len);

	if (!m) {
		return NULL;
	}
	fputs(head, m);
	for (size_t i = 0; i < n; i++) {
		fprintf(m, ", \"%s\"", f[i].key);
	}
	for (size_t i = 0; values && i < HEAD_N + 1 + n; i++) {
		fprintf(m, "%s$%zu", i ? ", " : ") VALUES (", i + 1);
	}
	fprintf(m, "%s%s", values ? ")" : "", tail);
	if (fclose(m)) {
		free(text);
		return NULL;
	}
	return text;
}

/* The texts of S's columns into V (NULL: SQL's NULL), their numbers'
 * digits in BUF (room for HEAD_N + n of 32 each). */
static void values_of(const struct records_session *s, const char *report,
		      const char **v, char (*buf)[32])
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);

	snprintf(buf[0], 32, "%" PRIu64, s->e.id);
	snprintf(buf[1], 32, "%" PRIu64, s->e.bytes);
	v[0] = s->uuid;
	v[1] = s->rig;
	v[2] = buf[0];
	v[3] = s->e.trainee;
	v[4] = s->e.case_name;
	v[5] = s->e.started;
	v[6] = s->e.ended ? "true" : "false";
	v[7] = buf[1];
	v[8] = s->judgement[0] ? s->judgement : NULL;
	v[9] = s->has_metrics ? "true" : "false";
	v[10] = report;
	for (size_t i = 0; i < n; i++) {
		double x = metricstext_field_value(&s->m, &f[i]);

		v[HEAD_N + 1 + i] = buf[2 + i];
		if (!s->has_metrics || isnan(x)) {
			v[HEAD_N + 1 + i] = NULL; /* as the rig's records */
		} else if (f[i].kind == FIELDS_DOUBLE) {
			snprintf(buf[2 + i], 32, "%.17g", x);
		} else {
			snprintf(buf[2 + i], 32, "%" PRId64, (int64_t)x);
		}
	}
}

int centre_put(struct centre *c, const struct records_session *s,
	       const char *report)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);
	const char **v = calloc(HEAD_N + 1 + n, sizeof(*v));
	char (*buf)[32] = calloc(2 + n, sizeof(*buf));
	char *sql = measures_sql("INSERT INTO sessions (" HEAD_COLUMNS
				 ", report", true,
				 " ON CONFLICT (uuid) DO NOTHING");
	int e = -ENOMEM;

	if (v && buf && sql && !(e = centre_connect(c, true))) {
		values_of(s, report, v, buf);
		e = run(c, sql, (int)(HEAD_N + 1 + n), v, NULL,
			"writing a session");
	}
	free(v);
	free(buf);
	free(sql);
	return e;
}

int centre_has(struct centre *c, const char *uuid)
{
	const char *v[] = { uuid };
	PGresult *res;
	int e = centre_connect(c, true);

	if (e || (e = run(c, "SELECT 1 FROM sessions WHERE uuid = $1", 1, v,
			  &res, "looking for a session"))) {
		return e;
	}
	e = PQntuples(res) > 0;
	PQclear(res);
	return e;
}

/* ----------------------------------------------------------- reading */

/* Row I of RES (the list's columns) into S. */
static void read_row(PGresult *res, int i, struct records_session *s)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);

	memset(s, 0, sizeof(*s));
	snprintf(s->uuid, sizeof(s->uuid), "%s", PQgetvalue(res, i, 0));
	snprintf(s->rig, sizeof(s->rig), "%s", PQgetvalue(res, i, 1));
	s->e.id = strtoull(PQgetvalue(res, i, 2), NULL, 10);
	snprintf(s->e.trainee, sizeof(s->e.trainee), "%s",
		 PQgetvalue(res, i, 3));
	snprintf(s->e.case_name, sizeof(s->e.case_name), "%s",
		 PQgetvalue(res, i, 4));
	snprintf(s->e.started, sizeof(s->e.started), "%s",
		 PQgetvalue(res, i, 5));
	s->e.ended = PQgetvalue(res, i, 6)[0] == 't';
	s->e.bytes = strtoull(PQgetvalue(res, i, 7), NULL, 10);
	snprintf(s->judgement, sizeof(s->judgement), "%s",
		 PQgetvalue(res, i, 8));
	s->has_metrics = PQgetvalue(res, i, 9)[0] == 't';
	for (size_t k = 0; s->has_metrics && k < n; k++) {
		char *at = (char *)&s->m + f[k].offset;
		const char *t = PQgetvalue(res, i, HEAD_N + (int)k);
		bool null = PQgetisnull(res, i, HEAD_N + (int)k);

		if (f[k].kind == FIELDS_DOUBLE) {
			*(double *)at = null ? NAN : strtod(t, NULL);
		} else if (f[k].kind == FIELDS_UINT64) {
			*(uint64_t *)at = (uint64_t)strtoll(t, NULL, 10);
		} else {
			*(uint32_t *)at = (uint32_t)strtoll(t, NULL, 10);
		}
	}
}

int centre_list(struct centre *c, const char *trainee,
		struct records_session **out, size_t *n)
{
	const char *v[] = { trainee };
	char *sql = measures_sql("SELECT " HEAD_COLUMNS, false, trainee ?
				 " FROM sessions WHERE trainee = $1 ORDER BY "
				 "started, rig, rig_session" : " FROM sessions "
				 "ORDER BY started, rig, rig_session");
	PGresult *res;
	int e = sql ? centre_connect(c, false) : -ENOMEM;

	*out = NULL;
	*n = 0;
	if (e || (e = run(c, sql, trainee ? 1 : 0, v, &res,
			  "listing the sessions"))) {
		free(sql);
		return e;
	}
	free(sql);
	*n = (size_t)PQntuples(res);
	*out = calloc(*n ? *n : 1, sizeof(**out));
	for (size_t i = 0; *out && i < *n; i++) {
		read_row(res, (int)i, &(*out)[i]);
	}
	PQclear(res);
	if (!*out) {
		*n = 0;
		return -ENOMEM;
	}
	return 0;
}

int centre_report(struct centre *c, const char *uuid, char **html)
{
	const char *v[] = { uuid };
	PGresult *res;
	int e = centre_connect(c, false);

	*html = NULL;
	if (e || (e = run(c, "SELECT coalesce(report, '') FROM sessions "
			  "WHERE uuid = $1", 1, v, &res,
			  "reading a report"))) {
		return e;
	}
	if (PQntuples(res) == 1) {
		*html = strdup(PQgetvalue(res, 0, 0));
		e = *html ? 0 : -ENOMEM;
	} else {
		snprintf(c->error, sizeof(c->error), "centre: no session %s",
			 uuid);
		e = -ENOENT;
	}
	PQclear(res);
	return e;
}

/* ------------------------------------------------------------ a page */

int centre_report_page(const char *path, char **html)
{
	struct metrics_result *m = malloc(sizeof(*m)); /* large */
	struct session_file f;
	size_t len = 0;
	bool recomputed;
	FILE *o = NULL;
	int e = m ? session_file_read(path, &f) : -ENOMEM;

	*html = NULL;
	if (e) {
		free(m);
		return e;
	}
	if (!(e = sessionview_metrics(&f, m, &recomputed)) &&
	    !(o = open_memstream(html, &len))) {
		e = -ENOMEM;
	}
	if (o) {
		report_print(o, &f, m, NULL);
		e = ferror(o) ? -EIO : 0;
		if (fclose(o) && !e) {
			e = -ENOMEM;
		}
	}
	session_file_close(&f);
	free(m);
	if (e) {
		free(*html);
		*html = NULL;
	}
	return e;
}

/* ------------------------------------------------------------ people */

#define TEXT_OID 25 /* PostgreSQL's text type (pg_type.h) */

/* Each change's statement, its texts $1 name, $2 role, $3 pin, $4 group,
 * $5 course (accounts.h's struct accounts_change). */
static const char *const change_sql[] = {
	[ACCOUNTS_USER_ADD] = "INSERT INTO endosim_people (name, role, pin) "
		"VALUES ($1, $2, $3) ON CONFLICT (name) DO NOTHING",
	[ACCOUNTS_USER_REMOVE] = "DELETE FROM endosim_people WHERE name = $1",
	[ACCOUNTS_USER_PIN] = "UPDATE endosim_people SET pin = $3 "
		"WHERE name = $1",
	[ACCOUNTS_GROUP_ADD] = "INSERT INTO endosim_groups (name, instructor) "
		"VALUES ($4, $1) ON CONFLICT (name) DO NOTHING",
	[ACCOUNTS_GROUP_REMOVE] = "DELETE FROM endosim_groups WHERE name = $4",
	[ACCOUNTS_GROUP_JOIN] = "INSERT INTO endosim_members (group_name, "
		"trainee) VALUES ($4, $1) ON CONFLICT DO NOTHING",
	[ACCOUNTS_GROUP_LEAVE] = "DELETE FROM endosim_members "
		"WHERE group_name = $4 AND trainee = $1",
	[ACCOUNTS_GROUP_ASSIGN] = "INSERT INTO endosim_courses (group_name, "
		"course) VALUES ($4, $5) ON CONFLICT DO NOTHING",
	[ACCOUNTS_GROUP_UNASSIGN] = "DELETE FROM endosim_courses "
		"WHERE group_name = $4 AND course = $5",
};

/* CH applied within the transaction (a savepoint round it: a change the
 * centre refuses leaves the rest of it). */
static int apply(struct centre *c, const struct accounts_change *ch,
		 enum centre_outcome *out)
{
	static const Oid types[5] = { TEXT_OID, TEXT_OID, TEXT_OID, TEXT_OID,
				      TEXT_OID };
	const char *const v[5] = { ch->name, accounts_role_name(ch->role),
				   ch->pin, ch->group, ch->course };
	PGresult *res;
	int e = run(c, "SAVEPOINT change", 0, NULL, NULL, "SAVEPOINT");

	if (e) {
		return e;
	}
	e = run_typed(c, change_sql[ch->op], 5, v, types, &res,
		      accounts_op_name(ch->op));
	if (e == -EBADMSG) {
		*out = CENTRE_REFUSED; /* its words kept in c->error */
		return run(c, "ROLLBACK TO SAVEPOINT change", 0, NULL, NULL,
			   "ROLLBACK TO SAVEPOINT");
	}
	if (!e) {
		*out = strcmp(PQcmdTuples(res), "0") ? CENTRE_APPLIED
						     : CENTRE_UNCHANGED;
		PQclear(res);
	}
	return e;
}

/* Q noted in endosim_changes, and applied unless noted before. */
static int take(struct centre *c, const char *rig,
		const struct accounts_queued *q, enum centre_outcome *out)
{
	const char *const note[] = { q->id, rig, accounts_op_name(q->ch.op),
				     q->ch.name, q->ch.group, q->ch.course };
	const char *done[] = { q->id, NULL };
	PGresult *res;
	int e = run(c, "SELECT pg_advisory_xact_lock(" PEOPLE_LOCK ")", 0,
		    NULL, NULL, "locking the people");

	if (e || (e = run(c, "INSERT INTO endosim_changes (id, rig, op, "
			  "name, group_name, course) VALUES ($1, $2, $3, $4, "
			  "$5, $6) ON CONFLICT (id) DO NOTHING", 6, note, &res,
			  "noting a change"))) {
		return e;
	}
	*out = CENTRE_TAKEN;
	if (!strcmp(PQcmdTuples(res), "0")) {
		PQclear(res);
		return 0;
	}
	PQclear(res);
	if ((e = apply(c, &q->ch, out)) || *out != CENTRE_APPLIED) {
		return e;
	}
	done[1] = "true";
	return run(c, "UPDATE endosim_changes SET applied = $2 WHERE id = $1",
		   2, done, NULL, "noting a change applied");
}

int centre_change(struct centre *c, const char *rig,
		  const struct accounts_queued *q, enum centre_outcome *out)
{
	char refused[sizeof(c->error)] = "";
	int e = centre_connect(c, true);

	*out = CENTRE_TAKEN;
	if (e || (e = run(c, "BEGIN", 0, NULL, NULL, "BEGIN"))) {
		return e;
	}
	if (!(e = take(c, rig, q, out))) {
		snprintf(refused, sizeof(refused), "%s", c->error);
		e = run(c, "COMMIT", 0, NULL, NULL, "COMMIT");
	}
	if (e && c->pg) {
		PQclear(PQexec(c->pg, "ROLLBACK"));
	}
	if (!e && *out == CENTRE_REFUSED) {
		snprintf(c->error, sizeof(c->error), "%s", refused);
	}
	return e;
}

int centre_people_version(struct centre *c, char *out, size_t size)
{
	PGresult *res;
	int e = centre_connect(c, true);

	if (e || (e = run(c, "SELECT coalesce(max(arrival), 0) FROM "
			  "endosim_changes", 0, NULL, &res,
			  "reading the people's version"))) {
		return e;
	}
	snprintf(out, size, "%s", PQgetvalue(res, 0, 0));
	PQclear(res);
	return 0;
}

/* The people's rows of P's results made changes (P->ch, P->n). */
static int people_rows(struct centre_people *p)
{
	size_t n = 0;
	PGresult **r = p->res;

	for (int k = 1; k < 5; k++) {
		n += (size_t)PQntuples(r[k]);
	}
	if (!(p->ch = calloc(n ? n : 1, sizeof(*p->ch)))) {
		return -ENOMEM;
	}
	for (int k = 1; k < 5; k++) {
		for (int i = 0; i < PQntuples(r[k]); i++) {
			struct accounts_change *ch = &p->ch[p->n++];
			const char *a = PQgetvalue(r[k], i, 0);
			const char *b = PQgetvalue(r[k], i, 1);

			*ch = (struct accounts_change){ .name = "", .pin = "",
							.group = "",
							.course = "" };
			if (k == 1) {
				ch->op = ACCOUNTS_USER_ADD;
				ch->name = a;
				ch->pin = PQgetvalue(r[k], i, 2);
				accounts_role_parse(b, &ch->role);
			} else {
				ch->op = k == 2 ? ACCOUNTS_GROUP_ADD : k == 3 ?
					 ACCOUNTS_GROUP_JOIN :
					 ACCOUNTS_GROUP_ASSIGN;
				ch->group = a;
				*(k == 4 ? &ch->course : &ch->name) = b;
			}
		}
	}
	return 0;
}

int centre_people(struct centre *c, struct centre_people *p)
{
	static const char *const sql[5] = {
		"SELECT coalesce(max(arrival), 0) FROM endosim_changes",
		"SELECT name, role, pin FROM endosim_people ORDER BY name",
		"SELECT name, instructor FROM endosim_groups ORDER BY name",
		"SELECT group_name, trainee FROM endosim_members "
		"ORDER BY group_name, trainee",
		"SELECT group_name, course FROM endosim_courses "
		"ORDER BY group_name, course",
	};
	int e = centre_connect(c, true);

	memset(p, 0, sizeof(*p));
	if (e || (e = run(c, "BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY",
			  0, NULL, NULL, "BEGIN"))) {
		return e;
	}
	for (int k = 0; !e && k < 5; k++) {
		e = run(c, sql[k], 0, NULL, &p->res[k], "reading the people");
	}
	e = e ? e : run(c, "COMMIT", 0, NULL, NULL, "COMMIT");
	if (e && c->pg) {
		PQclear(PQexec(c->pg, "ROLLBACK"));
	}
	if (!e) {
		snprintf(p->version, sizeof(p->version), "%s",
			 PQgetvalue(p->res[0], 0, 0));
		e = people_rows(p);
	}
	if (e) {
		centre_people_free(p);
	}
	return e;
}

void centre_people_free(struct centre_people *p)
{
	for (int k = 0; k < 5; k++) {
		PQclear(p->res[k]);
	}
	free(p->ch);
	memset(p, 0, sizeof(*p));
}
