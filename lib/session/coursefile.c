/* coursefile.c - see coursefile.h. */
#include "session/coursefile.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/parse.h"
#include "base/text.h"

#define COURSEFILE_MAX_BYTES (1 << 20)

struct parser {
	struct coursefile *c;
	const char *name;
	char *err;
	size_t errsize;
	int line;
	struct coursefile_case *in_case; /* NULL: in [course] or none yet */
	bool in_course;
	int course_line;                 /* where [course] began (0: none) */
};

static const struct {
	const char *text;
	enum coursefile_op op;
} ops[] = {
	{ "<=", COURSEFILE_LE }, { ">=", COURSEFILE_GE },
	{ "==", COURSEFILE_EQ }, { "<", COURSEFILE_LT },
	{ ">", COURSEFILE_GT },
};

#define NOPS (sizeof(ops) / sizeof(ops[0]))

static int fail(struct parser *p, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* "NAME:LINE: message"; always returns -EINVAL. */
static int fail(struct parser *p, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	parse_verror(p->err, p->errsize, p->name, p->line, NULL, fmt, ap);
	va_end(ap);
	return -EINVAL;
}

static const struct metricstext_field *find_field(const char *key)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);

	for (size_t i = 0; i < n; i++) {
		if (!strcmp(f[i].key, key)) {
			return &f[i];
		}
	}
	return NULL;
}

/* "[course]" or "[case NAME]". */
static int open_section(struct parser *p, char *line)
{
	char *end = strchr(line, ']'), *name;

	if (!end || end[1]) {
		return fail(p, "a section is [course] or [case NAME]");
	}
	*end = '\0';
	name = text_trim(line + 1);
	p->in_case = NULL;
	p->in_course = !strcmp(name, "course");
	if (p->in_course) {
		if (p->course_line) {
			return fail(p, "[course] again (line %d)",
				    p->course_line);
		}
		p->course_line = p->line;
		return 0;
	}
	if (strncmp(name, "case", 4) || !isspace((unsigned char)name[4])) {
		return fail(p, "unknown section [%s]: [course] or [case NAME]",
			    name);
	}
	name = text_trim(name + 4);
	if (!*name || strlen(name) >= sizeof(p->c->cases[0].name)) {
		return fail(p, "[case NAME]: a name of 1 to 63 bytes");
	}
	if (coursefile_case(p->c, name)) {
		return fail(p, "[case %s] again", name);
	}
	if (p->c->n_cases == COURSEFILE_MAX_CASES) {
		return fail(p, "more than %d cases", COURSEFILE_MAX_CASES);
	}
	p->in_case = &p->c->cases[p->c->n_cases++];
	snprintf(p->in_case->name, sizeof(p->in_case->name), "%s", name);
	return 0;
}

/* "key = value" under [course]. */
static int course_key(struct parser *p, char *line)
{
	char *eq = strchr(line, '='), *key, *value;
	double n;

	if (!eq) {
		return fail(p, "expected key = value");
	}
	*eq = '\0';
	key = text_trim(line);
	value = text_trim(eq + 1);
	if (!strcmp(key, "name") || !strcmp(key, "description")) {
		char *to = *key == 'n' ? p->c->name : p->c->description;
		size_t size = *key == 'n' ? sizeof(p->c->name)
					  : sizeof(p->c->description);

		if (strlen(value) >= size) {
			return fail(p, "%s: at most %zu bytes", key, size - 1);
		}
		memcpy(to, value, strlen(value) + 1);
		return 0;
	}
	if (strcmp(key, "consecutive")) {
		return fail(p, "unknown key '%s' in [course] (name, "
			    "description, consecutive)", key);
	}
	if (parse_double(value, &n) || n < 1 || n > COURSEFILE_MAX_RUN ||
	    n != floor(n)) {
		return fail(p, "consecutive: a whole number of sessions, 1 .. "
			    "%d, not '%s'", COURSEFILE_MAX_RUN, value);
	}
	p->c->consecutive = (unsigned)n;
	return 0;
}

/* "KEY OP NUMBER" under [case NAME]. */
static int case_req(struct parser *p, char *line)
{
	struct coursefile_case *k = p->in_case;
	size_t klen = strcspn(line, "<>=! \t");
	struct coursefile_req q;
	char key[64], *rest;
	size_t i;

	if (!klen || klen >= sizeof(key)) {
		return fail(p, "expected METRIC OP NUMBER (cecum_s <= 480)");
	}
	memcpy(key, line, klen);
	key[klen] = '\0';
	if (!(q.field = find_field(key))) {
		return fail(p, "unknown metric '%s' (the END frame's keys: "
			    "docs/METRICS.md)", key);
	}
	if (!strcmp(key, "polyps_seen_mask")) { /* nor on the wire */
		return fail(p, "%s: a set of polyps, not a measure "
			    "(polyps_seen counts them)", key);
	}
	rest = text_trim(line + klen);
	for (i = 0; i < NOPS; i++) {
		if (!strncmp(rest, ops[i].text, strlen(ops[i].text))) {
			break;
		}
	}
	if (i == NOPS) {
		return fail(p, "%s: bad operator '%.2s' (<= >= < > ==)", key,
			    rest);
	}
	q.op = ops[i].op;
	rest = text_trim(rest + strlen(ops[i].text));
	if (parse_double(rest, &q.value)) {
		return fail(p, "%s: bad number '%s'", key, rest);
	}
	if (k->n_reqs == COURSEFILE_MAX_REQS) {
		return fail(p, "more than %d requirements in [case %s]",
			    COURSEFILE_MAX_REQS, k->name);
	}
	k->req[k->n_reqs++] = q;
	return 0;
}

static int parse_line(struct parser *p, char *line)
{
	line[strcspn(line, "#")] = '\0';
	line = text_trim(line);
	if (!*line) {
		return 0;
	}
	if (*line == '[') {
		return open_section(p, line);
	}
	if (p->in_course) {
		return course_key(p, line);
	}
	if (p->in_case) {
		return case_req(p, line);
	}
	return fail(p, "outside a section: [course] or [case NAME] first");
}

/* What a whole file must have; LINE 0 names the file alone. */
static int finish(struct parser *p)
{
	const char *missing = !p->course_line    ? "no [course] section"
			      : !p->c->name[0]     ? "[course] has no name"
			      : !p->c->consecutive ? "[course] has no "
						     "consecutive"
			      : !p->c->n_cases     ? "no [case NAME] section"
						   : NULL;

	p->line = 0;
	for (size_t i = 0; !missing && i < p->c->n_cases; i++) {
		if (!p->c->cases[i].n_reqs) {
			return fail(p, "[case %s] has no requirement",
				    p->c->cases[i].name);
		}
	}
	return missing ? fail(p, "%s", missing) : 0;
}

int coursefile_parse(struct coursefile *c, const char *text, const char *name,
		     char *err, size_t errsize)
{
	struct parser p = { .c = c, .name = name, .err = err,
			    .errsize = errsize };
	char line[512];

	memset(c, 0, sizeof(*c));
	while (*text) {
		size_t n = strcspn(text, "\n");

		p.line++;
		if (n >= sizeof(line)) {
			return fail(&p, "line longer than %zu bytes",
				    sizeof(line) - 1);
		}
		memcpy(line, text, n);
		line[n] = '\0';
		text += n + (text[n] == '\n');
		if (parse_line(&p, line)) {
			return -EINVAL;
		}
	}
	return finish(&p);
}

/* TEXT (N bytes, a NUL among them) refused at its first NUL: the parser
 * reads C strings and would take the file as cut there. */
static int nul_byte(const char *path, const char *text, size_t n, char *err,
		    size_t errsize)
{
	struct parser p = { .name = path, .err = err, .errsize = errsize,
			    .line = 1 };
	const char *nul = memchr(text, '\0', n);

	for (const char *at = text; at < nul; at++) {
		p.line += *at == '\n';
	}
	return fail(&p, "a NUL byte: a course file is text");
}

int coursefile_load(struct coursefile *c, const char *path, char *err,
		    size_t errsize)
{
	FILE *f = fopen(path, "re");
	char *text = NULL;
	size_t n = 0;
	int r = 0;

	if (!f) {
		r = -errno;
		snprintf(err, errsize, "%s: %s", path, strerror(-r));
		return r;
	}
	text = malloc(COURSEFILE_MAX_BYTES + 1);
	if (!text) {
		r = -ENOMEM;
	} else if ((n = fread(text, 1, COURSEFILE_MAX_BYTES + 1, f)) >
		   COURSEFILE_MAX_BYTES || ferror(f)) {
		r = ferror(f) ? -EIO : -EFBIG;
	}
	fclose(f);
	if (r) {
		snprintf(err, errsize, "%s: %s", path, strerror(-r));
	} else if (memchr(text, '\0', n)) {
		r = nul_byte(path, text, n, err, errsize);
	} else {
		text[n] = '\0';
		r = coursefile_parse(c, text, path, err, errsize);
	}
	free(text);
	return r;
}

const struct coursefile_case *coursefile_case(const struct coursefile *c,
					      const char *case_name)
{
	for (size_t i = 0; i < c->n_cases; i++) {
		if (!strcmp(c->cases[i].name, case_name)) {
			return &c->cases[i];
		}
	}
	return NULL;
}

bool coursefile_met(const struct coursefile_req *q,
		    const struct metrics_result *m)
{
	double v = metricstext_field_value(m, q->field);

	if (!strcmp(q->field->key, "cecum_s") && v < 0) {
		return false; /* never reached */
	}
	switch (q->op) {
	case COURSEFILE_LE:
		return v <= q->value;
	case COURSEFILE_GE:
		return v >= q->value;
	case COURSEFILE_LT:
		return v < q->value;
	case COURSEFILE_GT:
		return v > q->value;
	default:
		return v == q->value;
	}
}

bool coursefile_passed(const struct coursefile_case *k,
		       const struct metrics_result *m)
{
	for (size_t i = 0; i < k->n_reqs; i++) {
		if (!coursefile_met(&k->req[i], m)) {
			return false;
		}
	}
	return true;
}

void coursefile_req_text(const struct coursefile_req *q, char *buf,
			 size_t size)
{
	const char *op = "?";

	for (size_t i = 0; i < NOPS; i++) {
		op = ops[i].op == q->op ? ops[i].text : op;
	}
	snprintf(buf, size, "%s %s %g", q->field->key, op, q->value);
}

int coursefile_judge(const struct coursefile *c, const char *case_name,
		     const struct metrics_result *m)
{
	const struct coursefile_case *k = coursefile_case(c, case_name);

	return !k || !m ? -1 : coursefile_passed(k, m);
}

/* Session I of case CASE_NAME, judged PASSED (coursefile_judge()), into
 * OUT. */
static void progress_step(const struct coursefile *c, const char *case_name,
			  int passed, size_t i,
			  struct coursefile_progress out[COURSEFILE_MAX_CASES])
{
	const struct coursefile_case *k = coursefile_case(c, case_name);
	struct coursefile_progress *p;

	if (!k || passed < 0) {
		return;
	}
	p = &out[k - c->cases];
	p->sessions++;
	p->run = passed ? p->run + 1 : 0;
	if (!p->completed && p->run >= c->consecutive) {
		p->completed = i + 1;
	}
}

void coursefile_progress_judged(const struct coursefile *c,
				const char *const *case_names,
				const signed char *passed, size_t n,
				struct coursefile_progress
				out[COURSEFILE_MAX_CASES])
{
	memset(out, 0, COURSEFILE_MAX_CASES * sizeof(*out));
	for (size_t i = 0; i < n; i++) {
		progress_step(c, case_names[i], passed[i], i, out);
	}
}

void coursefile_progress(const struct coursefile *c,
			 const char *const *case_names,
			 const struct metrics_result *const *m, size_t n,
			 struct coursefile_progress out[COURSEFILE_MAX_CASES])
{
	memset(out, 0, COURSEFILE_MAX_CASES * sizeof(*out));
	for (size_t i = 0; i < n; i++) {
		progress_step(c, case_names[i],
			      coursefile_judge(c, case_names[i], m[i]), i, out);
	}
}

size_t coursefile_keys(const struct coursefile *c, const char **keys,
		       size_t max)
{
	size_t n = 0, k;

	for (size_t i = 0; i < c->n_cases; i++) {
		for (size_t j = 0; j < c->cases[i].n_reqs; j++) {
			const char *key = c->cases[i].req[j].field->key;

			for (k = 0; k < n && strcmp(keys[k], key); k++) {
			}
			if (k == n && n < max) {
				keys[n++] = key;
			}
		}
	}
	return n;
}

bool coursefile_complete(const struct coursefile *c,
			 const struct coursefile_progress *p)
{
	for (size_t i = 0; i < c->n_cases; i++) {
		if (!p[i].completed) {
			return false;
		}
	}
	return true;
}
