/*
 * endoctl_trainee.c - endoctl's trainees (endoctl.h): their sessions found
 * by name from endosimd (TraineeSessions: the rig's records, which the
 * daemon keeps) or read from a session directory's files without it
 * (--dir: every file's header and END frame), or from a training
 * centre's database, every rig's (--centre: centre.h, read here with
 * libpq), judged by a course file (coursefile.h), listed or written as a
 * page (traineepage.h).
 */
#include "endoctl/endoctl.h"
#include "session/centre.h"
#include "session/coursefile.h"
#include "session/metricstext.h"
#include "session/traineepage.h"

/* One session, whichever way it was found. */
struct tsession {
	uint64_t id;
	char trainee[64];
	char case_name[64];
	char started[32];
	bool recording;
	bool recomputed;    /* the file was cut short */
	signed char passed; /* by the course: coursefile_judge() */
	struct metrics_result *m; /* a report's (malloc'd): the END frame's,
				     or recomputed; NULL not known, and in a
				     list, which judges each as it reads it */
	char rig[64];       /* a centre's: the rig that recorded it */
	char uuid[37];      /* a centre's: its key there */
};

struct tlist {
	struct tsession *s;
	size_t n;
	bool keep_m;        /* a report: each session's measures kept */
	const char *course_file; /* --course FILE; NULL: the daemon's */
	const struct coursefile *c; /* the course (load_course()); NULL: none */
	struct centre *centre; /* read from a centre's database; NULL not */
	char directory[4096];
};

/* The course named by --course (FILE), else the daemon's DAEMONS (NULL
 * or "": none), into L. */
static int load_course(struct tlist *l, const char *daemons)
{
	static struct coursefile buf;
	const char *path = l->course_file ? l->course_file : daemons;
	char err[512];

	l->c = NULL;
	if (!path || !*path) {
		return 0;
	}
	if (coursefile_load(&buf, path, err, sizeof(err))) {
		fprintf(stderr, "endoctl: course: %s\n", err);
		return EXIT_REFUSED;
	}
	l->c = &buf;
	return 0;
}

/* L's next session (L->s has room), its facts in; M its measures (NULL:
 * not known), judged by L's course and kept for a report. */
static struct tsession *add_session(struct tlist *l, uint64_t id,
				    const char *trainee, const char *case_name,
				    const char *started,
				    const struct metrics_result *m)
{
	struct tsession *t = &l->s[l->n++];

	memset(t, 0, sizeof(*t));
	t->id = id;
	snprintf(t->trainee, sizeof(t->trainee), "%s", trainee);
	snprintf(t->case_name, sizeof(t->case_name), "%s", case_name);
	snprintf(t->started, sizeof(t->started), "%s", started);
	t->passed = l->c ? (signed char)coursefile_judge(l->c, case_name, m)
			 : -1;
	if (m && l->keep_m && (t->m = malloc(sizeof(*t->m)))) {
		*t->m = *m;
	}
	return t;
}

/* The measures of the session file PATH cut short, recomputed into *M
 * (scratch); NULL when it cannot be read. */
static const struct metrics_result *recompute(const char *path,
					      struct metrics_result *m,
					      bool *recomputed)
{
	struct session_file f;
	int e;

	if (session_file_read(path, &f)) {
		fprintf(stderr, "endoctl: %s: unreadable: left out of the "
			"curves\n", path);
		return NULL;
	}
	e = sessionview_metrics(&f, m, recomputed);
	session_file_close(&f);
	return e ? NULL : m;
}

static void tlist_free(struct tlist *l)
{
	for (size_t i = 0; l->s && i < l->n; i++) {
		free(l->s[i].m);
	}
	free(l->s);
	centre_destroy(l->centre);
}

/* The sessions of the reply T into L, judged by L's course. */
static void add_replied(struct tlist *l, const Endosim__TraineeReply *t)
{
	static struct metrics_result m; /* scratch: 7 kB */

	for (size_t i = 0; i < t->n_sessions; i++) {
		const Endosim__SessionInfo *s = t->sessions[i];
		const struct metrics_result *got = NULL;
		bool recomputed = false;

		if (s->metrics) {
			sessionpb_to_metrics(s->metrics, &m);
			got = &m;
		} else if (!s->recording && (l->keep_m || l->c)) {
			got = recompute(s->path, &m, &recomputed);
		}
		add_session(l, s->id, s->trainee, s->case_name, s->started,
			    got)->recording = s->recording;
		l->s[l->n - 1].recomputed = recomputed;
	}
}

/*
 * TRAINEE's sessions (NULL: everyone's) from endosimd. A list asks only
 * for what it judges by: by --course, the measures the course names; else
 * what the daemon's course needs (its facts alone when it has none).
 */
static int from_daemon(struct ctl *ctl, const char *trainee, struct tlist *l)
{
	Endosim__TraineeSessions body = ENDOSIM__TRAINEE_SESSIONS__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	const char *keys[COURSEFILE_MAX_CASES * COURSEFILE_MAX_REQS];
	const Endosim__TraineeReply *t;
	Endosim__Reply *rep;
	int r;

	body.trainee = (char *)(trainee ? trainee : "");
	body.facts_unless_course = !l->keep_m && !l->course_file;
	if (!l->keep_m && l->course_file) {
		if ((r = load_course(l, NULL))) {
			return r;
		}
		body.n_measures = coursefile_keys(l->c, keys, sizeof(keys) /
						  sizeof(keys[0]));
		body.measures = (char **)keys;
	}
	req.body_case = ENDOSIM__REQUEST__BODY_TRAINEE_SESSIONS;
	req.trainee_sessions = &body;
	if ((r = ctl_transact(ctl, false, &req, &rep))) {
		return r;
	}
	t = rep->trainee;
	snprintf(l->directory, sizeof(l->directory), "%s", t->directory);
	r = l->c ? 0 : load_course(l, t->course);
	if (!r && !(l->s = calloc(t->n_sessions ? t->n_sessions : 1,
				  sizeof(*l->s)))) {
		fprintf(stderr, "endoctl: out of memory\n");
		r = EXIT_REFUSED;
	}
	if (!r) {
		add_replied(l, t);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return r;
}

/* The END frame's measures of the session file PATH into *M (scratch);
 * NULL when it has none (cut short). */
static const struct metrics_result *end_metrics(const char *path,
						struct metrics_result *m)
{
	char *end = NULL;
	bool ok = !sessiondir_end_text(path, &end) &&
		  !metricstext_parse(end, m);

	free(end);
	m->n_force = m->n_loop = m->n_pain = 0; /* the scalars only */
	return ok ? m : NULL;
}

/* TRAINEE's sessions (NULL: everyone's) read from the directory DIR. */
static int from_dir(const char *dir, const char *trainee, struct tlist *l)
{
	static struct metrics_result m; /* scratch: 7 kB */
	struct sessiondir_entry *e;
	char path[4096];
	size_t n;
	int r = sessiondir_list(dir, &e, &n);

	if (r || !(l->s = calloc(n ? n : 1, sizeof(*l->s)))) {
		fprintf(stderr, "endoctl: %s: %s\n", dir,
			strerror(r ? -r : ENOMEM));
		free(r ? NULL : e);
		return EXIT_REFUSED;
	}
	if ((r = load_course(l, NULL))) {
		free(e);
		return r;
	}
	snprintf(l->directory, sizeof(l->directory), "%s", dir);
	for (size_t i = 0; i < n; i++) {
		const struct metrics_result *got = NULL;
		bool recomputed = false;

		if ((trainee && strcmp(trainee, e[i].trainee)) ||
		    sessiondir_path(dir, e[i].id, path, sizeof(path))) {
			continue;
		}
		if (e[i].ended) {
			got = end_metrics(path, &m);
		}
		if (!got) {
			got = recompute(path, &m, &recomputed);
		}
		add_session(l, e[i].id, e[i].trainee, e[i].case_name,
			    e[i].started, got)->recomputed = recomputed;
	}
	free(e);
	return 0;
}

/* TRAINEE's sessions (NULL: everyone's) from the centre at URL, every
 * rig's; the connection kept in L for the reports. */
static int from_centre(const char *url, const char *trainee, struct tlist *l)
{
	struct records_session *rows;
	size_t n;
	int e;

	snprintf(l->directory, sizeof(l->directory), "the centre's records");
	if (!(l->centre = centre_create(url, "endoctl"))) {
		fprintf(stderr, "endoctl: out of memory\n");
		return EXIT_REFUSED;
	}
	if ((e = centre_list(l->centre, trainee, &rows, &n))) {
		fprintf(stderr, "endoctl: %s\n", centre_error(l->centre));
		return e == -EINVAL ? EXIT_USAGE : EXIT_COMM;
	}
	if ((e = load_course(l, NULL))) {
		free(rows);
		return e;
	}
	l->s = calloc(n ? n : 1, sizeof(*l->s));
	for (size_t i = 0; l->s && i < n; i++) {
		struct tsession *x = add_session(l, rows[i].e.id,
						 rows[i].e.trainee,
						 rows[i].e.case_name,
						 rows[i].e.started,
						 rows[i].has_metrics ?
						 &rows[i].m : NULL);

		snprintf(x->rig, sizeof(x->rig), "%s", rows[i].rig);
		snprintf(x->uuid, sizeof(x->uuid), "%s", rows[i].uuid);
	}
	free(rows);
	if (!l->s) {
		fprintf(stderr, "endoctl: out of memory\n");
		return EXIT_REFUSED;
	}
	return 0;
}

/* ---------------------------------------------------------------- list */

/* How trainee I (first seen at session I) stands. */
struct standing {
	const char *trainee;
	size_t sessions;
	char cases[256];      /* "normal, polyps" */
	char rigs[256];       /* a centre's: "rig-a, rig-b" */
	const struct tsession *last;
	size_t cases_done;    /* of the course's */
	bool complete;
};

/* NAME added to the list NAMES ("a, b") unless it is there. */
static void add_name(char *names, size_t size, const char *name)
{
	size_t len = strlen(name), at = strlen(names);

	for (const char *p = strstr(names, name); p; p = strstr(p + 1, name)) {
		if ((p == names || p[-1] == ' ') &&
		    (p[len] == ',' || !p[len])) {
			return;
		}
	}
	snprintf(names + at, size - at, "%s%s", at ? ", " : "", name);
}

static void stand(const struct tlist *l, size_t first,
		  const struct coursefile *c, struct standing *st)
{
	const char **cases = malloc((l->n ? l->n : 1) * sizeof(*cases));
	signed char *passed = malloc(l->n ? l->n : 1);
	struct coursefile_progress p[COURSEFILE_MAX_CASES];
	size_t k = 0;

	memset(st, 0, sizeof(*st));
	st->trainee = l->s[first].trainee;
	for (size_t i = first; i < l->n; i++) {
		const struct tsession *s = &l->s[i];

		if (strcmp(s->trainee, st->trainee)) {
			continue;
		}
		st->sessions++;
		st->last = s;
		add_name(st->cases, sizeof(st->cases), s->case_name);
		if (s->rig[0]) {
			add_name(st->rigs, sizeof(st->rigs), s->rig);
		}
		if (cases && passed) {
			cases[k] = s->case_name;
			passed[k++] = s->passed;
		}
	}
	if (c && cases && passed) {
		coursefile_progress_judged(c, cases, passed, k, p);
		for (size_t i = 0; i < c->n_cases; i++) {
			st->cases_done += p[i].completed != 0;
		}
		st->complete = coursefile_complete(c, p);
	}
	free(cases);
	free(passed);
}

/* Whether session I's trainee came earlier. */
static bool trainee_seen_before(const struct tlist *l, size_t i)
{
	for (size_t j = 0; j < i; j++) {
		if (!strcmp(l->s[j].trainee, l->s[i].trainee)) {
			return true;
		}
	}
	return false;
}

static void print_standing(const struct tlist *l, const struct standing *st,
			   const struct coursefile *c)
{
	char course[64] = "-";

	if (c && st->complete) {
		snprintf(course, sizeof(course), "complete");
	} else if (c) {
		snprintf(course, sizeof(course), "%zu of %zu cases", st->cases_done,
			 c->n_cases);
	}
	printf("%-24s  %8zu  %-20s  %6" PRIu64 "  %-20s  %-14s%s%s\n",
	       st->trainee, st->sessions, st->cases, st->last->id,
	       st->last->started, course, l->centre ? "  " : "", st->rigs);
}

/* The list NAMES ("a, b") as the JSON array KEY. */
static void json_names(struct json *j, const char *key, const char *names)
{
	json_array_begin(j, key);
	for (const char *at = names; *at;) {
		size_t n = strcspn(at, ",");
		char name[64];

		snprintf(name, sizeof(name), "%.*s", (int)n, at);
		json_string(j, NULL, name);
		at += n + (at[n] ? 2 : 0); /* ", " */
	}
	json_array_end(j);
}

static void json_standing(struct json *j, const struct tlist *l,
			  const struct standing *st, const struct coursefile *c)
{
	json_object_begin(j, NULL);
	json_string(j, "trainee", st->trainee);
	json_uint(j, "sessions", st->sessions);
	json_names(j, "cases", st->cases);
	json_uint(j, "last_session", st->last->id);
	json_string(j, "last_started", st->last->started);
	if (l->centre) {
		json_names(j, "rigs", st->rigs);
		json_string(j, "last_rig", st->last->rig);
	}
	if (c) {
		json_uint(j, "cases_complete", st->cases_done);
		json_bool(j, "course_complete", st->complete);
	}
	json_object_end(j);
}

static void print_list(const struct ctl *ctl, const struct tlist *l,
		       const struct coursefile *c)
{
	struct standing st;
	struct json j;

	if (ctl->json) {
		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_string(&j, "directory", l->directory);
		json_string(&j, "course", c ? c->name : "");
		json_array_begin(&j, "trainees");
	} else {
		printf("%-24s  %8s  %-20s  %6s  %-20s  %-14s%s\n", "TRAINEE",
		       "SESSIONS", "CASES", "LAST", "STARTED", "COURSE",
		       l->centre ? "  RIGS" : "");
	}
	for (size_t i = 0; i < l->n; i++) {
		if (trainee_seen_before(l, i)) {
			continue;
		}
		stand(l, i, c, &st);
		if (ctl->json) {
			json_standing(&j, l, &st, c);
		} else {
			print_standing(l, &st, c);
		}
	}
	if (ctl->json) {
		json_array_end(&j);
		json_object_end(&j);
	}
}

/* -------------------------------------------------------------- report */

/* Each session's report page from the centre, as OUT/UUID.html. */
static int write_pages(const struct tlist *l, const char *out)
{
	char path[4200], *html;
	FILE *f;
	int e;

	for (size_t i = 0; i < l->n; i++) {
		if ((e = centre_report(l->centre, l->s[i].uuid, &html))) {
			fprintf(stderr, "endoctl: %s\n", centre_error(l->centre));
			return EXIT_COMM;
		}
		snprintf(path, sizeof(path), "%s/%s.html", out, l->s[i].uuid);
		f = fopen(path, "we");
		e = !f || fputs(html, f) < 0;
		e |= f && fclose(f);
		free(html);
		if (e) {
			fprintf(stderr, "endoctl: %s: %s\n", path,
				strerror(errno));
			return EXIT_REFUSED;
		}
	}
	return 0;
}

static int write_report(const char *trainee, const struct tlist *l,
			const struct coursefile *c, const char *out)
{
	struct traineepage_session *p = calloc(l->n ? l->n : 1, sizeof(*p));
	char (*href)[48] = calloc(l->n ? l->n : 1, sizeof(*href));
	struct standing st;
	int r;

	if (!p || !href) {
		free(p);
		free(href);
		fprintf(stderr, "endoctl: out of memory\n");
		return EXIT_REFUSED;
	}
	for (size_t i = 0; i < l->n; i++) {
		snprintf(href[i], sizeof(href[i]), "%s.html", l->s[i].uuid);
		p[i] = (struct traineepage_session){
			.id = l->s[i].id, .case_name = l->s[i].case_name,
			.started = l->s[i].started,
			.m = l->s[i].m,
			.recomputed = l->s[i].recomputed,
			.rig = l->centre ? l->s[i].rig : NULL,
			.href = l->centre ? href[i] : NULL,
		};
	}
	r = traineepage_write(trainee, p, l->n, c, out);
	free(p);
	free(href);
	if (r) {
		fprintf(stderr, "endoctl: trainee report in %s: %s\n", out,
			strerror(-r));
		return EXIT_REFUSED;
	}
	if (l->centre && (r = write_pages(l, out))) {
		return r;
	}
	stand(l, 0, c, &st);
	printf("wrote %s/index.html: %zu sessions%s\n", out, l->n, !c ? "" :
	       st.complete ? ", course complete" : ", course not complete");
	return 0;
}

/* ------------------------------------------------------------ commands */

struct targs {
	const char *name;   /* report: the trainee */
	const char *out;    /* report: --out DIR */
	const char *course; /* --course FILE */
	const char *dir;    /* --dir DIR: without endosimd */
	const char *centre; /* --centre URL: a centre's, every rig's */
};

/* The options after ARGV[FIRST]; false on anything else. */
static bool parse_args(int argc, char **argv, int first, struct targs *a)
{
	for (int i = first; i < argc; i += 2) {
		const char **to = !strcmp(argv[i], "--out")      ? &a->out
				  : !strcmp(argv[i], "--course") ? &a->course
				  : !strcmp(argv[i], "--dir")    ? &a->dir
				  : !strcmp(argv[i], "--centre") ? &a->centre
								 : NULL;

		if (!to || i + 1 >= argc) {
			return false;
		}
		*to = argv[i + 1];
	}
	return true;
}

static int trainee_run(struct ctl *ctl, const struct targs *a)
{
	struct tlist l = { .keep_m = a->name != NULL,
			   .course_file = a->course };
	int r = a->centre ? from_centre(a->centre, a->name, &l)
		: a->dir  ? from_dir(a->dir, a->name, &l)
			  : from_daemon(ctl, a->name, &l);

	if (!r && a->name && !l.n) {
		fprintf(stderr, "endoctl: no session of trainee '%s' in %s\n",
			a->name, l.directory);
		r = EXIT_REFUSED;
	}
	if (!r) {
		r = a->name ? write_report(a->name, &l, l.c, a->out)
			    : (print_list(ctl, &l, l.c), 0);
	}
	tlist_free(&l);
	return r;
}

int ctl_cmd_trainee(struct ctl *ctl, int argc, char **argv)
{
	const char *sub = argc >= 2 ? argv[1] : "";
	struct targs a = { 0 };

	if (!strcmp(sub, "list") && parse_args(argc, argv, 2, &a) && !a.out &&
	    !(a.dir && a.centre)) {
		return trainee_run(ctl, &a);
	}
	if (!strcmp(sub, "report") && argc >= 3 &&
	    parse_args(argc, argv, 3, &a) && a.out && !(a.dir && a.centre)) {
		a.name = argv[2];
		return trainee_run(ctl, &a);
	}
	fprintf(stderr, "endoctl: trainee list [--course FILE] [--dir DIR | "
		"--centre URL] | report NAME --out DIR [--course FILE] [--dir "
		"DIR | --centre URL] (--dir: a session directory read without "
		"endosimd; --centre: a centre's PostgreSQL, every rig's)\n");
	return EXIT_USAGE;
}
