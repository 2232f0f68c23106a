/*
 * parse.h - one kit for the text files people write: the configuration
 * (config.c), case files (anatomy.c), scenarios (scenario.c), course files
 * (coursefile.c) and a Modbus register's description (regspec.c).
 *
 * Numbers. parse_double() and parse_long() take the whole text or nothing
 * (strtod's and strtol's leading blanks allowed): an empty or blank text,
 * anything after the number, a value beyond the type (ERANGE, underflow
 * included) and, for a double, inf or nan are not numbers. parse_number()
 * adds an inclusive range and says in words what is wrong.
 *
 * Errors. One line, "FILE:LINE: WHAT: message" (parse_error()), in the
 * caller's buffer.
 *
 * Key tables. A table declares each key once: its section and name, its
 * type, where its value lands (an offset into the section's struct), its
 * default, range and unit, flags and one line of help. The same table reads
 * a file (parse_ini(), over Debian's libinih), one value as text
 * (parse_apply()), sets every default (parse_defaults()) and writes a value
 * as the file would say it (parse_format()). A type of the caller's own
 * (PARSE_CUSTOM) brings its parse and format functions (struct parse_ops).
 *
 * The file: libinih's INI grammar ("[section]", "name = value" or
 * "name: value", ';' starting a comment at a line's start or after a
 * blank, '#' at a line's start), with the kit's own rules:
 *   - a line's leading and trailing blanks do not count (there are no
 *     continuation lines), nor a UTF-8 byte order mark;
 *   - with PARSE_HASH_COMMENTS, '#' starts a comment anywhere;
 *   - a line holds at most PARSE_MAX_LINE characters, and without its
 *     comments at most what libinih's line buffer takes (198 characters
 *     with Debian's);
 *   - a section is whatever "[...]" holds, trimmed; with PARSE_KIND_ARG a
 *     header is "[KIND ARG]": the keys are KIND's, ARG is for the table's
 *     begin() (a case file's "[segment rectum]");
 *   - a key is set once (PARSE_REPEATS: any number of times) in a file or,
 *     with PARSE_PER_SECTION, in each section;
 *   - the first error ends the reading, and is the one reported:
 *       FILE:LINE: NAME: before any [section]
 *       FILE:LINE: [SECTION] NAME: unknown key
 *       FILE:LINE: [SECTION] NAME: duplicate key (first set on line N)
 *       FILE:LINE: [SECTION] NAME: WHY (the value: parse_apply()'s WHY)
 *       FILE:LINE: [SECTION]: NAME is missing (LINE: the section's header)
 *       FILE:LINE: [SECTION]: WHY (the table's begin() refused it)
 *       FILE:LINE: TEXT: syntax error: expected 'key = value' (or
 *                  '[section]'; the TEXT is the line's)
 *       FILE:LINE: line: longer than N characters
 *
 * parse_ini() allocates its bookkeeping (an int per key) and reads the
 * stream; nothing else allocates or keeps state: any thread but the force
 * loop.
 */
#ifndef ENDOSIM_PARSE_H
#define ENDOSIM_PARSE_H

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#define PARSE_MAX_LINE 4094 /* characters of a line, comments included */

/* TEXT as a number, whole: 0, or -EINVAL (*OUT then undefined). */
int parse_double(const char *text, double *out);
int parse_long(const char *text, int base, long *out);

/*
 * TEXT as a number in [MIN, MAX] (UNIT, "" for none, for the message):
 * 0, or -EINVAL with "'TEXT' is not a number" or "TEXT is out of range
 * [MIN, MAX] UNIT" in WHY.
 */
int parse_number(const char *text, double min, double max, const char *unit,
		 double *out, char *why, size_t size);

/*
 * "FILE:LINE: WHAT: message" into BUF; LINE 0 leaves ":LINE" out, WHAT
 * NULL leaves "WHAT: " out. Returns -EINVAL, for the caller to return.
 */
int parse_error(char *buf, size_t size, const char *file, int line,
		const char *what, const char *fmt, ...)
	__attribute__((format(printf, 6, 7)));
int parse_verror(char *buf, size_t size, const char *file, int line,
		 const char *what, const char *fmt, va_list ap)
	__attribute__((format(printf, 6, 0)));

enum parse_type {
	PARSE_INT,    /* int: decimal, or hexadecimal with PARSE_HEX */
	PARSE_DOUBLE, /* double */
	PARSE_STRING, /* char[size], NUL-terminated */
	PARSE_CHOICE, /* int: the index of one of choices */
	PARSE_CUSTOM, /* ops' */
};

enum parse_flags {
	PARSE_HEX = 1u << 0,      /* PARSE_INT: read and written in hex */
	PARSE_REQUIRED = 1u << 1, /* its section must set it */
	PARSE_REPEATS = 1u << 2,  /* may be set more than once */
	PARSE_USER = 1u << 8,     /* the table's owner's flags from here */
};

/* What a table reads a file with (struct parse_table flags). */
enum parse_table_flags {
	PARSE_HASH_COMMENTS = 1u << 0, /* '#' starts a comment anywhere */
	PARSE_KIND_ARG = 1u << 1,      /* "[KIND ARG]" headers */
	PARSE_PER_SECTION = 1u << 2,   /* a key once per section, not file */
};

struct parse_key;
struct parse_file;

/* A type of the table's owner's (PARSE_CUSTOM). */
struct parse_ops {
	/*
	 * TEXT into FIELD (the key's, in its section's struct): 0, or
	 * -EINVAL with why in WHY (SIZE may be 0: say nothing), FIELD
	 * unchanged. PF: the file being read (parse_file_user(),
	 * parse_file_line()), NULL outside one.
	 */
	int (*parse)(const struct parse_key *k, const char *text, void *field,
		     struct parse_file *pf, char *why, size_t size);
	/* FIELD as parse() reads it; NULL: the type is never written. */
	void (*format)(const struct parse_key *k, const void *field,
		       char *buf, size_t size);
};

struct parse_key {
	const char *section;         /* or the KIND of "[KIND ARG]" */
	const char *name;
	enum parse_type type;
	size_t offset;               /* into its section's struct */
	size_t size;                 /* PARSE_STRING: bytes with the NUL */
	double def;                  /* numbers and choices */
	const char *def_str;         /* strings, custom types (NULL: "") */
	double min, max;             /* numbers, inclusive */
	const char *const *choices;  /* PARSE_CHOICE: NULL-terminated */
	const struct parse_ops *ops; /* PARSE_CUSTOM */
	const char *unit;            /* "" for none */
	unsigned int flags;          /* enum parse_flags */
	const char *help;            /* one line; NULL for none */
};

struct parse_table {
	const struct parse_key *keys;
	size_t n;
	unsigned int flags; /* enum parse_table_flags */
	/*
	 * A section begins (its header's line: parse_file_line()): KIND and
	 * ARG (NULL without PARSE_KIND_ARG or an argument); its keys land in
	 * *BASE, which is parse_ini()'s BASE unless begin() says otherwise.
	 * 0, or -EINVAL with why in WHY. NULL: every section is accepted.
	 */
	int (*begin)(struct parse_file *pf, const char *kind, const char *arg,
		     void **base, char *why, size_t size);
	/*
	 * The section ends (at the next header or the end of the file), its
	 * required keys there: SET_ON[i] the line keys[i] was set on in it
	 * (in the file, without PARSE_PER_SECTION), 0 when not. May be NULL.
	 */
	void (*end)(struct parse_file *pf, const int *set_on);
};

/*
 * Reads the INI stream F (NAME: the file in messages) by table T, every
 * section's keys into BASE unless T's begin() chooses; USER is for T's
 * functions (parse_file_user()). Returns the number of keys set, or
 * -EINVAL with one line in ERR (the first error; see above), or -ENOMEM.
 * What was set before the error stays set.
 */
int parse_ini(const struct parse_table *t, FILE *f, const char *name,
	      void *base, void *user, char *err, size_t errsize);

/* For T's functions while parse_ini() reads: its USER, the line. */
void *parse_file_user(const struct parse_file *pf);
int parse_file_line(const struct parse_file *pf);

/* The key SECTION NAME of T, or NULL. */
const struct parse_key *parse_find(const struct parse_table *t,
				   const char *section, const char *name);

/* Every key's default into BASE (a table whose sections share one). */
void parse_defaults(const struct parse_table *t, void *base);

/*
 * TEXT into K's field in BASE: 0, or -EINVAL with why in WHY and the
 * field unchanged. PF as in struct parse_ops (NULL: no file).
 */
int parse_apply(const struct parse_key *k, void *base, const char *text,
		struct parse_file *pf, char *why, size_t size);

/* K's value in BASE as the file would say it. */
void parse_format(const struct parse_key *k, const void *base, char *buf,
		  size_t size);

#endif
