/*
 * control_courses.c - the courses assigned to the trainees' groups
 * (accounts.h), which judge their sessions (control_private.h): a course
 * as assigned named to its file, checked when it is assigned, and the
 * courses of a TraineeSessions reply's trainees gathered, each file
 * loaded (coursefile.h) for what its requirements measure. endoctl judges
 * by them as it judges by [session] course; a course that does not load
 * refuses the request in words rather than judge a trainee by less.
 */
#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "control/control_private.h"
#include "session/coursefile.h"

int control_course_file(const struct control *c, const char *course,
			char *path, size_t size)
{
	char cases[CONFIG_STR];
	size_t n = strlen(course);
	const char *ext = n > 7 && !strcmp(course + n - 7, ".course") ? "" :
			  ".course";
	int len;

	if (strchr(course, '/')) {
		len = snprintf(path, size, "%s", course);
	} else {
		snprintf(cases, sizeof(cases), "%s", c->cfg.colon.directory);
		len = snprintf(path, size, "%s/courses/%s%s", dirname(cases),
			       course, ext);
	}
	return len < 0 || (size_t)len >= size ? -ENAMETOOLONG : 0;
}

/* COURSE of GROUP loaded into K (its file into PATH): 0, or -errno with
 * why in WHY. */
static int load(const struct control *c, const char *group,
		const char *course, struct coursefile *k, char *path,
		size_t size, char *why, size_t why_size)
{
	char err[512];
	int e = control_course_file(c, course, path, size);

	if (e) {
		snprintf(why, why_size, "group %.63s's course %.96s: too long "
			 "a path", group, course);
		return e;
	}
	e = coursefile_load(k, path, err, sizeof(err));
	if (e) {
		snprintf(why, why_size, "group %.63s's course %.96s: %.320s",
			 group, course, err);
	}
	return e;
}

bool control_course_refused(struct control *c, const Endosim__Accounts *m,
			    Endosim__Reply *rep)
{
	struct coursefile *k;
	char path[PATH_MAX];

	if (m->op != ENDOSIM__ACCOUNTS__OP__OP_GROUP_ASSIGN || !*m->course) {
		return false;
	}
	if (!(k = malloc(sizeof(*k)))) {
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, "out of memory");
		return true;
	}
	if (load(c, m->group, m->course, k, path, sizeof(path), c->refusal,
		 sizeof(c->refusal))) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->refusal);
		free(k);
		return true;
	}
	free(k);
	return false;
}

void control_courses_free(struct control_courses *cc)
{
	for (size_t i = 0; i < cc->n; i++) {
		free(cc->entries[i].file);
		free(cc->entries[i].trainee);
		free(cc->entries[i].course);
	}
	free(cc->entries);
	free(cc->entries_p);
	accounts_groups_free(cc->groups, cc->n_groups);
	memset(cc, 0, sizeof(*cc));
}

/* The lines of TEXT, one at a time: the next into LINE (SIZE), *AT past
 * it; false after the last. */
static bool next_line(const char **at, char *line, size_t size)
{
	size_t n;

	if (!**at) {
		return false;
	}
	n = strcspn(*at, "\n");
	snprintf(line, size, "%.*s", (int)n, *at);
	*at += n + ((*at)[n] == '\n');
	return true;
}

void control_key_add(const char **keys, size_t *n, size_t max,
		     const char *key)
{
	for (size_t i = 0; i < *n; i++) {
		if (!strcmp(keys[i], key)) {
			return;
		}
	}
	if (*n < max) {
		keys[(*n)++] = key;
	}
}

/* Group G's course COURSE for TRAINEE as CC's next entry, its file
 * loaded into K (scratch) and its measures added to the keys. */
static int add_entry(struct control *c, struct control_courses *cc,
		     const struct accounts_group *g, const char *trainee,
		     const char *course, struct coursefile *k,
		     const char **keys, size_t *n, size_t max, char *why,
		     size_t size)
{
	const char *mine[COURSEFILE_MAX_CASES * COURSEFILE_MAX_REQS];
	Endosim__TraineeCourse *e = &cc->entries[cc->n];
	char path[PATH_MAX];
	size_t m;
	int r = load(c, g->name, course, k, path, sizeof(path), why, size);

	if (r) {
		return r;
	}
	endosim__trainee_course__init(e);
	if (!(e->file = strdup(path)) || !(e->trainee = strdup(trainee)) ||
	    !(e->course = strdup(course))) {
		free(e->file);
		free(e->trainee);
		free(e->course);
		endosim__trainee_course__init(e);
		snprintf(why, size, "out of memory");
		return -ENOMEM;
	}
	e->group = (char *)g->name;
	cc->entries_p[cc->n++] = e;
	m = coursefile_keys(k, mine, sizeof(mine) / sizeof(mine[0]));
	for (size_t i = 0; i < m; i++) {
		control_key_add(keys, n, max, mine[i]);
	}
	return 0;
}

/* Each (trainee, course) of group G whom NAMES sees (NULL: all) and, when
 * TRAINEE is not "", is TRAINEE. */
static int add_group(struct control *c, struct control_courses *cc,
		     const struct accounts_group *g, const char *names,
		     const char *trainee, struct coursefile *k,
		     const char **keys, size_t *n, size_t max, char *why,
		     size_t size)
{
	char who[ACCOUNTS_NAME_MAX + 1], course[PATH_MAX];
	int r = 0;

	for (const char *t = g->trainees; !r && next_line(&t, who,
							  sizeof(who));) {
		if ((*trainee && strcmp(who, trainee)) ||
		    (names && !accounts_among(names, who))) {
			continue;
		}
		for (const char *k2 = g->courses; !r &&
		     next_line(&k2, course, sizeof(course));) {
			r = add_entry(c, cc, g, who, course, k, keys, n, max,
				      why, size);
		}
	}
	return r;
}

/* How many (trainee, course) pairs the groups hold: room for them. */
static size_t pairs(const struct accounts_group *g, size_t n)
{
	size_t total = 0;

	for (size_t i = 0; i < n; i++) {
		size_t t = *g[i].trainees != '\0', k = *g[i].courses != '\0';

		for (const char *p = g[i].trainees; *p; p++) {
			t += *p == '\n';
		}
		for (const char *p = g[i].courses; *p; p++) {
			k += *p == '\n';
		}
		total += t * k;
	}
	return total;
}

int control_courses_build(struct control *c, const struct client *cl,
			  const char *trainee, struct control_courses *cc,
			  const char **keys, size_t *n, size_t max, char *why,
			  size_t size)
{
	struct accounts *db = control_accounts_db(c);
	struct coursefile *k = malloc(sizeof(*k));
	char *names = NULL;
	size_t room;
	int r = k ? 0 : -ENOMEM;

	r = r ? r : control_accounts_seen(c, cl, &names);
	r = r ? r : accounts_groups(db, NULL, &cc->groups, &cc->n_groups);
	if (r) {
		snprintf(why, size, "%s", r == -ENOMEM ? "out of memory" :
			 accounts_error(db));
		free(k);
		free(names);
		return r;
	}
	room = pairs(cc->groups, cc->n_groups) + 1;
	cc->entries = calloc(room, sizeof(*cc->entries));
	cc->entries_p = calloc(room, sizeof(*cc->entries_p));
	r = cc->entries && cc->entries_p ? 0 : -ENOMEM;
	if (r) {
		snprintf(why, size, "out of memory");
	}
	for (size_t i = 0; !r && i < cc->n_groups; i++) {
		r = add_group(c, cc, &cc->groups[i], names, trainee, k, keys, n,
			      max, why, size);
	}
	free(k);
	free(names);
	return r;
}
