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
	" (trainee, started);";
#define SCHEMA_COLUMNS 13 /* the table's before the measures' */

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

/* SQL with the N texts V (NULL: SQL's NULL) run: its result in *RES
 * (NULL: not wanted), or as failed(). Without texts SQL may be several
 * statements (PQexec()'s). */
static int run(struct centre *c, const char *sql, int n,
	       const char *const *v, PGresult **res, const char *what)
{
	PGresult *r = n ? PQexecParams(c->pg, sql, n, NULL, v, NULL, NULL, 0)
			: PQexec(c->pg, sql);
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
	if (c->pg && PQstatus(c->pg) == CONNECTION_OK) {
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
