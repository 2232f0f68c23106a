/* parse.c - see parse.h. */
#include "base/parse.h"

#include <errno.h>
#include <ini.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/text.h"

#define NO_ERROR INT_MAX /* the first error's line, while there is none */

struct parse_file {
	const struct parse_table *t;
	FILE *f;
	const char *name;
	void *base, *user;
	void *sbase;         /* where the current section's keys land */
	char *err;
	size_t errsize;
	int line;            /* lines read */
	int err_line;        /* the first error's, NO_ERROR */
	int section_line;    /* the current section's header, 0: none yet */
	char section[PARSE_MAX_LINE + 2]; /* its header's text, "[" "]" off */
	char kind[PARSE_MAX_LINE + 2];    /* whose keys it holds */
	int *set_on;         /* per key: the line it was set on, 0 */
	int keys_set;
	char raw[PARSE_MAX_LINE + 2]; /* the line being read */
};

int parse_double(const char *text, double *out)
{
	char *end;

	errno = 0;
	*out = strtod(text, &end);
	return end == text || *end || errno || !isfinite(*out) ? -EINVAL : 0;
}

int parse_long(const char *text, int base, long *out)
{
	char *end;

	errno = 0;
	*out = strtol(text, &end, base);
	return end == text || *end || errno ? -EINVAL : 0;
}

static int in_range(const char *text, double v, double min, double max,
		    const char *unit, char *why, size_t size)
{
	if (v < min || v > max) {
		unit = unit ? unit : "";
		snprintf(why, size, "%s is out of range [%g, %g]%s%s", text,
			 min, max, *unit ? " " : "", unit);
		return -EINVAL;
	}
	return 0;
}

int parse_number(const char *text, double min, double max, const char *unit,
		 double *out, char *why, size_t size)
{
	if (parse_double(text, out)) {
		snprintf(why, size, "'%s' is not a number", text);
		return -EINVAL;
	}
	return in_range(text, *out, min, max, unit, why, size);
}

int parse_verror(char *buf, size_t size, const char *file, int line,
		 const char *what, const char *fmt, va_list ap)
{
	char msg[256], at[16] = "";

	vsnprintf(msg, sizeof(msg), fmt, ap);
	if (line > 0) {
		snprintf(at, sizeof(at), ":%d", line);
	}
	snprintf(buf, size, "%s%s: %s%s%s", file, at, what ? what : "",
		 what ? ": " : "", msg);
	return -EINVAL;
}

int parse_error(char *buf, size_t size, const char *file, int line,
		const char *what, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	parse_verror(buf, size, file, line, what, fmt, ap);
	va_end(ap);
	return -EINVAL;
}

/* ------------------------------------------------------------ a key */

const struct parse_key *parse_find(const struct parse_table *t,
				   const char *section, const char *name)
{
	for (size_t i = 0; i < t->n; i++) {
		if (!strcmp(t->keys[i].section, section) &&
		    !strcmp(t->keys[i].name, name)) {
			return &t->keys[i];
		}
	}
	return NULL;
}

static void *field(void *base, const struct parse_key *k)
{
	return (char *)base + k->offset;
}

static int parse_int(const struct parse_key *k, const char *text, int *out,
		     char *why, size_t size)
{
	long v;

	if (parse_long(text, k->flags & PARSE_HEX ? 16 : 10, &v)) {
		snprintf(why, size, "'%s' is not an integer", text);
		return -EINVAL;
	}
	if (in_range(text, (double)v, k->min, k->max, k->unit, why, size)) {
		return -EINVAL;
	}
	*out = (int)v;
	return 0;
}

static int parse_choice(const struct parse_key *k, const char *text,
			int *out, char *why, size_t size)
{
	for (int i = 0; k->choices[i]; i++) {
		if (!strcmp(text, k->choices[i])) {
			*out = i;
			return 0;
		}
	}
	snprintf(why, size, "'%s' is not a known choice", text);
	return -EINVAL;
}

int parse_apply(const struct parse_key *k, void *base, const char *text,
		struct parse_file *pf, char *why, size_t size)
{
	void *f = field(base, k);
	double v;

	switch (k->type) {
	case PARSE_INT:
		return parse_int(k, text, f, why, size);
	case PARSE_DOUBLE:
		if (parse_number(text, k->min, k->max, k->unit, &v, why,
				 size)) {
			return -EINVAL;
		}
		*(double *)f = v;
		return 0;
	case PARSE_STRING:
		if (strlen(text) >= k->size) {
			snprintf(why, size, "longer than %zu characters",
				 k->size - 1);
			return -EINVAL;
		}
		strcpy(f, text);
		return 0;
	case PARSE_CHOICE:
		return parse_choice(k, text, f, why, size);
	case PARSE_CUSTOM:
		return k->ops->parse(k, text, f, pf, why, size);
	}
	return -EINVAL;
}

void parse_defaults(const struct parse_table *t, void *base)
{
	for (size_t i = 0; i < t->n; i++) {
		const struct parse_key *k = &t->keys[i];
		const char *text = k->def_str ? k->def_str : "";
		void *f = field(base, k);

		switch (k->type) {
		case PARSE_INT:
		case PARSE_CHOICE:
			*(int *)f = (int)k->def;
			break;
		case PARSE_DOUBLE:
			*(double *)f = k->def;
			break;
		case PARSE_STRING:
			snprintf(f, k->size, "%s", text);
			break;
		case PARSE_CUSTOM:
			k->ops->parse(k, text, f, NULL, NULL, 0);
			break;
		}
	}
}

static const char *choice_name(const struct parse_key *k, int choice)
{
	for (int i = 0; k->choices[i]; i++) {
		if (i == choice) {
			return k->choices[i];
		}
	}
	return "?";
}

void parse_format(const struct parse_key *k, const void *base, char *buf,
		  size_t size)
{
	const void *f = (const char *)base + k->offset;

	switch (k->type) {
	case PARSE_INT:
		snprintf(buf, size, k->flags & PARSE_HEX ? "0x%04x" : "%d",
			 *(const int *)f);
		break;
	case PARSE_DOUBLE:
		snprintf(buf, size, "%.9g", *(const double *)f);
		break;
	case PARSE_STRING:
		snprintf(buf, size, "%s", (const char *)f);
		break;
	case PARSE_CHOICE:
		snprintf(buf, size, "%s", choice_name(k, *(const int *)f));
		break;
	case PARSE_CUSTOM:
		if (k->ops->format) {
			k->ops->format(k, f, buf, size);
		} else if (size) {
			*buf = '\0';
		}
		break;
	}
}

/* ------------------------------------------------------------ a file */

void *parse_file_user(const struct parse_file *pf)
{
	return pf->user;
}

int parse_file_line(const struct parse_file *pf)
{
	return pf->line;
}

static int fail(struct parse_file *pf, int line, const char *what,
		const char *fmt, ...) __attribute__((format(printf, 4, 5)));

/* Keeps the first error, at LINE; always returns -EINVAL. */
static int fail(struct parse_file *pf, int line, const char *what,
		const char *fmt, ...)
{
	va_list ap;

	if (pf->err_line == NO_ERROR) {
		va_start(ap, fmt);
		parse_verror(pf->err, pf->errsize, pf->name, line, what, fmt,
			     ap);
		va_end(ap);
		pf->err_line = line;
	}
	return -EINVAL;
}

/* "[SECTION]" for messages. */
static const char *section_what(const struct parse_file *pf, char *buf,
				size_t size)
{
	snprintf(buf, size, "[%s]", pf->section);
	return buf;
}

/* The current section ends: its required keys, the table's end(). */
static int end_section(struct parse_file *pf)
{
	const struct parse_table *t = pf->t;
	char what[sizeof(pf->section) + 2];

	if (!pf->section_line) {
		return 0;
	}
	for (size_t i = 0; i < t->n; i++) {
		if ((t->keys[i].flags & PARSE_REQUIRED) && !pf->set_on[i] &&
		    !strcmp(t->keys[i].section, pf->kind)) {
			return fail(pf, pf->section_line,
				    section_what(pf, what, sizeof(what)),
				    "%s is missing", t->keys[i].name);
		}
	}
	if (t->end) {
		t->end(pf, pf->set_on);
	}
	return 0;
}

/* HEADER ("[...]...", trimmed) ends the current section, begins one. */
static int begin_section(struct parse_file *pf, const char *header)
{
	const struct parse_table *t = pf->t;
	const char *close = strchr(header, ']');
	char *name, *arg = NULL, why[256], what[sizeof(pf->section) + 2];

	if (!close) {
		return fail(pf, pf->line, header, "syntax error: expected "
			    "'[section]'");
	}
	if (end_section(pf)) {
		return -EINVAL;
	}
	memcpy(pf->kind, header + 1, (size_t)(close - header - 1));
	pf->kind[close - header - 1] = '\0';
	name = text_trim(pf->kind);
	memmove(pf->section, name, strlen(name) + 1);
	strcpy(pf->kind, pf->section);
	if ((t->flags & PARSE_KIND_ARG) && (arg = strpbrk(pf->kind, " \t"))) {
		*arg = '\0';
		arg = text_trim(arg + 1);
	}
	pf->section_line = pf->line;
	pf->sbase = pf->base;
	if (t->flags & PARSE_PER_SECTION) {
		memset(pf->set_on, 0, t->n * sizeof(*pf->set_on));
	}
	if (t->begin && t->begin(pf, pf->kind, arg, &pf->sbase, why,
				 sizeof(why))) {
		return fail(pf, pf->line, section_what(pf, what, sizeof(what)),
			    "%s", why);
	}
	return 0;
}

/* libinih's reader: the next line with the kit's rules (parse.h); NULL at
 * the end or after an error. */
static char *read_line(char *str, int num, void *stream)
{
	struct parse_file *pf = stream;
	char *line = pf->raw;
	size_t n;

	if (pf->err_line != NO_ERROR || !fgets(pf->raw, sizeof(pf->raw),
						pf->f)) {
		return NULL;
	}
	pf->line++;
	if (!strchr(pf->raw, '\n') && !feof(pf->f)) {
		fail(pf, pf->line, "line", "longer than %d characters",
		     PARSE_MAX_LINE);
		return NULL;
	}
	if (pf->line == 1 && !strncmp(line, "\xEF\xBB\xBF", 3)) {
		line += 3;
	}
	if (pf->t->flags & PARSE_HASH_COMMENTS) {
		line[strcspn(line, "#")] = '\0';
	}
	line = text_trim(line);
	if (*line == ';' || *line == '#') {
		*line = '\0';
	}
	n = strlen(line);
	if (n + 2 > (size_t)num) {
		fail(pf, pf->line, "line", "longer than %d characters",
		     num - 2);
		return NULL;
	}
	if (*line == '[') {
		if (begin_section(pf, line)) {
			return NULL;
		}
	} else if (*line && !strpbrk(line, "=:")) {
		fail(pf, pf->line, line,
		     "syntax error: expected 'key = value'");
		return NULL;
	}
	memcpy(str, line, n);
	str[n] = '\n';
	str[n + 1] = '\0';
	return str;
}

/* What is wrong with NAME = VALUE of the current section, in WHAT and WHY;
 * 0 when it is set. */
static int set_key(struct parse_file *pf, const char *name, const char *value,
		   char *what, size_t wsize, char *why, size_t size)
{
	const struct parse_key *k;
	size_t i;

	if (!pf->section_line) {
		snprintf(what, wsize, "%s", name);
		snprintf(why, size, "before any [section]");
		return -EINVAL;
	}
	snprintf(what, wsize, "[%s] %s", pf->section, name);
	k = parse_find(pf->t, pf->kind, name);
	if (!k) {
		snprintf(why, size, "unknown key");
		return -EINVAL;
	}
	i = (size_t)(k - pf->t->keys);
	if (pf->set_on[i] && !(k->flags & PARSE_REPEATS)) {
		snprintf(why, size, "duplicate key (first set on line %d)",
			 pf->set_on[i]);
		return -EINVAL;
	}
	if (parse_apply(k, pf->sbase, value, pf, why, size)) {
		return -EINVAL;
	}
	pf->set_on[i] = pf->line;
	pf->keys_set++;
	return 0;
}

/* libinih's handler: one "name = value" (libinih's section is not used:
 * the kit keeps its own, read_line()). 0 ends the reading. */
static int on_key(void *user, const char *section, const char *name,
		  const char *value)
{
	struct parse_file *pf = user;
	char what[2 * sizeof(pf->section)], why[256];

	(void)section;
	if (set_key(pf, name, value, what, sizeof(what), why, sizeof(why))) {
		fail(pf, pf->line, what, "%s", why);
		return 0;
	}
	return 1;
}

int parse_ini(const struct parse_table *t, FILE *f, const char *name,
	      void *base, void *user, char *err, size_t errsize)
{
	int *set_on = calloc(t->n + 1, sizeof(*set_on));
	struct parse_file *pf = calloc(1, sizeof(*pf));
	int r;

	if (!set_on || !pf) {
		free(set_on);
		free(pf);
		snprintf(err, errsize, "%s: out of memory", name);
		return -ENOMEM;
	}
	*pf = (struct parse_file){
		.t = t, .f = f, .name = name, .base = base, .user = user,
		.sbase = base, .err = err, .errsize = errsize,
		.err_line = NO_ERROR, .set_on = set_on,
	};
	err[0] = '\0';
	r = ini_parse_stream(read_line, pf, on_key, pf);
	if (r > 0 && r < pf->err_line) {
		/* what read_line() leaves to libinih: an inline comment
		 * before the '=' */
		pf->err_line = NO_ERROR;
		fail(pf, r, NULL, "syntax error: expected 'key = value'");
	} else if (r < 0 && pf->err_line == NO_ERROR) {
		fail(pf, 0, NULL, "out of memory");
	}
	if (pf->err_line == NO_ERROR) {
		end_section(pf);
	}
	r = pf->err_line == NO_ERROR ? pf->keys_set : -EINVAL;
	free(set_on);
	free(pf);
	return r;
}
