/*
 * endoctl_trainee.c - endoctl's trainees (endoctl.h): their sessions found
 * by name from endosimd (TraineeSessions: the rig's records, which the
 * daemon keeps) or read from a session directory's files without it
 * (--dir: every file's header and END frame), or from a training
 * centre's database, every rig's (--centre: centre.h, read here with
 * libpq), judged by course files (coursefile.h), listed or written as a
 * page (traineepage.h). Which courses judge a trainee: --course FILE,
 * everyone's; else the courses assigned to the trainee's groups (the
 * daemon's TraineeReply says which; none with --dir or --centre); else
 * the daemon's [session] course; else none.
 */
#include "endoctl/endoctl.h"
#include "session/centre.h"
#include "session/coursefile.h"
#include "session/metricstext.h"
#include "session/traineepage.h"

#define TLIST_MAX_COURSES TRAINEEPAGE_MAX_COURSES /* of one listing, at most */

/* One session, whichever way it was found. */
struct tsession {
	uint64_t id;
	char trainee[64];
	char case_name[64];
	char started[32];
	bool recording;
	bool recomputed;    /* the file was cut short */
	signed char passed[TLIST_MAX_COURSES]; /* by each course of the
						  list's (coursefile_judge()),
						  -1 not judged by it */
	struct metrics_result *m; /* a report's (malloc'd): the END frame's,
				     or recomputed; NULL not known, and in a
				     list, which judges each as it reads it */
	char rig[64];       /* a centre's: the rig that recorded it */
	char uuid[37];      /* a centre's: its key there */
};

/* A course that judges some of the list's trainees. */
struct tcourse {
	struct coursefile c;
	char file[4096];
	char group[64];     /* the group it is assigned to; "": the rig's
			       (--course, [session] course) */
};

/* The courses of one trainee of the list's groups, by index. */
struct tjudged {
	char trainee[64];
	size_t k[TLIST_MAX_COURSES];
	size_t n;
};

struct tlist {
	struct tsession *s;
	size_t n;
	bool keep_m;        /* a report: each session's measures kept */
	const char *course_file; /* --course FILE; NULL: the daemon's */
	struct tcourse *courses; /* loaded, TLIST_MAX_COURSES room */
	size_t n_courses;
	int rig;            /* the rig's course (--course, else [session]
			       course): its index; -1: none */
	struct tjudged *judged; /* the trainees of groups with courses */
	size_t n_judged;
	struct centre *centre; /* read from a centre's database; NULL not */
	char directory[4096];
};

/* The course of FILE (of GROUP, "" the rig's) loaded into L once: its
 * index, or -1 (said on stderr). */
static int add_course(struct tlist *l, const char *file, const char *group)
{
	char err[512];
	struct tcourse *t;

	for (size_t k = 0; k < l->n_courses; k++) {
		if (!strcmp(l->courses[k].file, file) &&
		    !strcmp(l->courses[k].group, group)) {
			return (int)k;
		}
	}
	if (!l->courses &&
	    !(l->courses = calloc(TLIST_MAX_COURSES, sizeof(*l->courses)))) {
		fprintf(stderr, "endoctl: out of memory\n");
		return -1;
	}
	if (l->n_courses == TLIST_MAX_COURSES) {
		fprintf(stderr, "endoctl: course: more than %d courses judge "
			"these trainees: name one (--course FILE)\n",
			TLIST_MAX_COURSES);
		return -1;
	}
	t = &l->courses[l->n_courses];
	if (coursefile_load(&t->c, file, err, sizeof(err))) {
		fprintf(stderr, "endoctl: course%s%s: %s\n", *group ?
			" of group " : "", group, err);
		return -1;
	}
	snprintf(t->file, sizeof(t->file), "%s", file);
	snprintf(t->group, sizeof(t->group), "%s", group);
	return (int)l->n_courses++;
}

/* The course named by --course (FILE), else the daemon's DAEMONS (NULL
 * or "": none), into L as the rig's. */
static int load_course(struct tlist *l, const char *daemons)
{
	const char *path = l->course_file ? l->course_file : daemons;

	l->rig = -1;
	if (!path || !*path) {
		return 0;
	}
	l->rig = add_course(l, path, "");
	return l->rig < 0 ? EXIT_REFUSED : 0;
}

/* TRAINEE's courses in L, added (with none) if not there yet; NULL:
 * ENOMEM. */
static struct tjudged *judged_of(struct tlist *l, const char *trainee)
{
	struct tjudged *j;

	for (size_t m = 0; m < l->n_judged; m++) {
		if (!strcmp(l->judged[m].trainee, trainee)) {
			return &l->judged[m];
		}
	}
	j = reallocarray(l->judged, l->n_judged + 1, sizeof(*j));
	if (!j) {
		return NULL;
	}
	l->judged = j;
	j = &l->judged[l->n_judged++];
	memset(j, 0, sizeof(*j));
	snprintf(j->trainee, sizeof(j->trainee), "%s", trainee);
	return j;
}

/* The courses of the trainees' groups that the reply T names into L
 * (--course given: none asked for); a trainee in two groups of one
 * course file is judged by it once. */
static int load_group_courses(struct tlist *l, const Endosim__TraineeReply *t)
{
	for (size_t i = 0; i < t->n_courses; i++) {
		const Endosim__TraineeCourse *e = t->courses[i];
		int k = add_course(l, e->file, e->group);
		struct tjudged *j;

		if (k < 0) {
			return EXIT_REFUSED; /* said */
		}
		if (!(j = judged_of(l, e->trainee))) {
			fprintf(stderr, "endoctl: out of memory\n");
			return EXIT_REFUSED;
		}
		for (size_t m = 0; m < j->n && k >= 0; m++) {
			k = strcmp(l->courses[j->k[m]].file, e->file) ? k : -1;
		}
		if (k >= 0) { /* fewer than the list's: room */
			j->k[j->n++] = (size_t)k;
		}
	}
	return 0;
}

/* The indices of the courses that judge TRAINEE into K: how many. */
static size_t courses_of(const struct tlist *l, const char *trainee,
			 size_t k[TLIST_MAX_COURSES])
{
	for (size_t m = 0; !l->course_file && m < l->n_judged; m++) {
		const struct tjudged *j = &l->judged[m];

		if (!strcmp(j->trainee, trainee)) {
			memcpy(k, j->k, sizeof(j->k));
			return j->n;
		}
	}
	k[0] = (size_t)l->rig;
	return l->rig >= 0;
}

/* L's next session (L->s has room), its facts in; M its measures (NULL:
 * not known), judged by L's course and kept for a report. */
static struct tsession *add_session(struct tlist *l, uint64_t id,
				    const char *trainee, const char *case_name,
				    const char *started,
				    const struct metrics_result *m)
{
	struct tsession *t = &l->s[l->n++];
	size_t k[TLIST_MAX_COURSES], n = courses_of(l, trainee, k);

	memset(t, 0, sizeof(*t));
	t->id = id;
	snprintf(t->trainee, sizeof(t->trainee), "%s", trainee);
	snprintf(t->case_name, sizeof(t->case_name), "%s", case_name);
	snprintf(t->started, sizeof(t->started), "%s", started);
	memset(t->passed, -1, sizeof(t->passed));
	for (size_t i = 0; i < n; i++) {
		t->passed[k[i]] = (signed char)coursefile_judge(
			&l->courses[k[i]].c, case_name, m);
	}
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
	free(l->courses);
	free(l->judged);
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
		} else if (!s->recording && (l->keep_m || l->n_courses)) {
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
	body.course_given = l->course_file != NULL;
	if (!l->keep_m && l->course_file) {
		if ((r = load_course(l, NULL))) {
			return r;
		}
		body.n_measures = coursefile_keys(&l->courses[l->rig].c, keys,
						  sizeof(keys) /
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
	r = l->course_file && !l->keep_m ? 0 : load_course(l, t->course);
	r = r ? r : load_group_courses(l, t);
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
	size_t n_courses;     /* that judge them */
	struct {
		size_t k;         /* the course: its index in the list */
		size_t cases_done; /* of its cases */
		bool complete;
	} course[TLIST_MAX_COURSES];
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

/* ST's standing in its course J, its N sessions' CASES judged PASSED[i *
 * TLIST_MAX_COURSES + course]. */
static void stand_in(const struct tlist *l, struct standing *st, size_t j,
		     const char **cases, const signed char *passed, size_t n)
{
	const struct coursefile *c = &l->courses[st->course[j].k].c;
	struct coursefile_progress p[COURSEFILE_MAX_CASES];
	signed char *mine = malloc(n ? n : 1);

	if (!mine) {
		return;
	}
	for (size_t i = 0; i < n; i++) {
		mine[i] = passed[i * TLIST_MAX_COURSES + st->course[j].k];
	}
	coursefile_progress_judged(c, cases, mine, n, p);
	for (size_t i = 0; i < c->n_cases; i++) {
		st->course[j].cases_done += p[i].completed != 0;
	}
	st->course[j].complete = coursefile_complete(c, p);
	free(mine);
}

static void stand(const struct tlist *l, size_t first, struct standing *st)
{
	size_t room = l->n ? l->n : 1, k = 0, ks[TLIST_MAX_COURSES];
	const char **cases = malloc(room * sizeof(*cases));
	signed char *passed = malloc(room * TLIST_MAX_COURSES);

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
			memcpy(passed + k++ * TLIST_MAX_COURSES, s->passed,
			       TLIST_MAX_COURSES);
		}
	}
	st->n_courses = cases && passed ? courses_of(l, st->trainee, ks) : 0;
	for (size_t j = 0; j < st->n_courses; j++) {
		st->course[j].k = ks[j];
		stand_in(l, st, j, cases, passed, k);
	}
	free(cases);
	free(passed);
}

/* Whether ST is judged by the courses of their groups (each named), not
 * by the rig's one course (as it always was). */
static bool by_groups(const struct tlist *l, const struct standing *st)
{
	return st->n_courses &&
	       (st->n_courses > 1 || (int)st->course[0].k != l->rig);
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

/* The standing in course J into OUT at AT: "complete" or "N of M
 * cases", after the course's name when NAMED. */
static size_t course_words(const struct tlist *l, const struct standing *st,
			   size_t j, bool named, char *out, size_t at,
			   size_t size)
{
	const struct coursefile *c = &l->courses[st->course[j].k].c;
	const char *sep = at ? ", " : "", *name = named ? c->name : "";
	int n;

	if (at >= size) {
		return at;
	}
	if (st->course[j].complete) {
		n = snprintf(out + at, size - at, "%s%s%scomplete", sep, name,
			     named ? " " : "");
	} else {
		n = snprintf(out + at, size - at, "%s%s%s%zu of %zu cases", sep,
			     name, named ? " " : "", st->course[j].cases_done,
			     c->n_cases);
	}
	return n < 0 ? size : at + (size_t)n;
}

static void print_standing(const struct tlist *l, const struct standing *st)
{
	char course[512] = "-";
	size_t at = 0;

	for (size_t j = 0; j < st->n_courses; j++) {
		at = course_words(l, st, j, by_groups(l, st), course, at,
				  sizeof(course));
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

/* The courses of their groups that judge ST, each with its standing. */
static void json_courses(struct json *j, const struct tlist *l,
			 const struct standing *st)
{
	json_array_begin(j, "courses");
	for (size_t i = 0; i < st->n_courses; i++) {
		const struct tcourse *t = &l->courses[st->course[i].k];

		json_object_begin(j, NULL);
		json_string(j, "name", t->c.name);
		json_string(j, "group", t->group);
		json_string(j, "file", t->file);
		json_uint(j, "cases", t->c.n_cases);
		json_uint(j, "cases_complete", st->course[i].cases_done);
		json_bool(j, "complete", st->course[i].complete);
		json_object_end(j);
	}
	json_array_end(j);
}

static void json_standing(struct json *j, const struct tlist *l,
			  const struct standing *st)
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
	if (st->n_courses == 1) {
		json_uint(j, "cases_complete", st->course[0].cases_done);
		json_bool(j, "course_complete", st->course[0].complete);
	}
	if (by_groups(l, st)) {
		json_courses(j, l, st);
	}
	json_object_end(j);
}

static void print_list(const struct ctl *ctl, const struct tlist *l)
{
	const struct coursefile *c = l->rig >= 0 ? &l->courses[l->rig].c
						 : NULL;
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
		stand(l, i, &st);
		if (ctl->json) {
			json_standing(&j, l, &st);
		} else {
			print_standing(l, &st);
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

/* The line after writing the page: TRAINEE's courses' standing (ST). */
static void print_written(const struct tlist *l, const struct standing *st,
			  const char *out)
{
	printf("wrote %s/index.html: %zu sessions", out, l->n);
	if (st->n_courses == 1) {
		printf(st->course[0].complete ? ", course complete" :
		       ", course not complete");
	}
	for (size_t j = 0; st->n_courses > 1 && j < st->n_courses; j++) {
		printf("%s%s %scomplete", j ? ", " : ", courses: ",
		       l->courses[st->course[j].k].c.name,
		       st->course[j].complete ? "" : "not ");
	}
	printf("\n");
}

static int write_report(const char *trainee, const struct tlist *l,
			const char *out)
{
	struct traineepage_session *p = calloc(l->n ? l->n : 1, sizeof(*p));
	char (*href)[48] = calloc(l->n ? l->n : 1, sizeof(*href));
	const struct coursefile *c[TLIST_MAX_COURSES];
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
	stand(l, 0, &st);
	for (size_t j = 0; j < st.n_courses; j++) {
		c[j] = &l->courses[st.course[j].k].c;
	}
	r = traineepage_write(trainee, p, l->n, c, st.n_courses, out);
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
	print_written(l, &st, out);
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
			   .course_file = a->course, .rig = -1 };
	int r = a->centre ? from_centre(a->centre, a->name, &l)
		: a->dir  ? from_dir(a->dir, a->name, &l)
			  : from_daemon(ctl, a->name, &l);

	if (!r && a->name && !l.n) {
		fprintf(stderr, "endoctl: no session of trainee '%s' in %s\n",
			a->name, l.directory);
		r = EXIT_REFUSED;
	}
	if (!r) {
		r = a->name ? write_report(a->name, &l, a->out)
			    : (print_list(ctl, &l), 0);
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
