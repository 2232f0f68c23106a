/*
 * coursefile.h - a training course (config/courses/NAME.course): the
 * pass/fail requirements per case on a session's metrics (metrics.h), and
 * how many sessions in a row must meet all of them for the course to be
 * complete.
 *
 * The file ("key = value" under [course], one requirement a line under
 * [case NAME]; '#' starts a comment):
 *
 *   [course]
 *   name = basic                 up to 63 bytes
 *   description = ...            optional, up to 159 bytes
 *   consecutive = 3              sessions in a row, 1 .. 100
 *
 *   [case normal]                a case's name (config/cases/NAME.case)
 *   cecum_s <= 480               KEY OP NUMBER: KEY one of
 *   withdrawal_s >= 360          metricstext_fields()' keys (the END
 *   mucosa_seen >= 0.90          frame's, in its units: s, m, N, shares
 *   force_episodes == 0          0..1) but polyps_seen_mask (a set, not a
 *                                measure), OP one of <= >= < > ==
 *
 * A session that never reached the cecum (cecum_s < 0) meets no
 * requirement on cecum_s. A case is complete when `consecutive` of the
 * trainee's sessions on it, one after the other, met every requirement of
 * its section; the course when every case of it is. Sessions of a case
 * the course does not name are not judged.
 *
 * No allocation, no shared state: any thread but the force loop.
 */
#ifndef ENDOSIM_COURSEFILE_H
#define ENDOSIM_COURSEFILE_H

#include <stdbool.h>
#include <stddef.h>

#include "session/metrics.h"
#include "session/metricstext.h"

#define COURSEFILE_MAX_CASES 16
#define COURSEFILE_MAX_REQS 16
#define COURSEFILE_MAX_RUN 100 /* `consecutive` at most */

enum coursefile_op {
	COURSEFILE_LE,
	COURSEFILE_GE,
	COURSEFILE_LT,
	COURSEFILE_GT,
	COURSEFILE_EQ,
};

struct coursefile_req {
	const struct metricstext_field *field; /* metricstext_fields()' */
	enum coursefile_op op;
	double value;                      /* in the field's unit */
};

struct coursefile_case {
	char name[64];
	size_t n_reqs;
	struct coursefile_req req[COURSEFILE_MAX_REQS];
};

struct coursefile {
	char name[64];
	char description[160];
	unsigned consecutive;
	size_t n_cases;
	struct coursefile_case cases[COURSEFILE_MAX_CASES];
};

/*
 * Parses TEXT (NAME: the file's name in messages) into C. 0, or -EINVAL
 * with one line "NAME:LINE: what is wrong" in ERR (an unknown key or
 * metric, a bad operator or number, a section twice, a missing name,
 * consecutive or case).
 */
int coursefile_parse(struct coursefile *c, const char *text, const char *name,
		     char *err, size_t errsize);

/* Reads and parses the file PATH: 0, -errno when it cannot be read (with
 * ERR saying so), or -EINVAL as coursefile_parse() (and "PATH:LINE: a NUL
 * byte" for a file holding one). */
int coursefile_load(struct coursefile *c, const char *path, char *err,
		    size_t errsize);

/* The section of CASE_NAME, or NULL when the course does not name it. */
const struct coursefile_case *coursefile_case(const struct coursefile *c,
					      const char *case_name);

/* Whether M meets Q. */
bool coursefile_met(const struct coursefile_req *q,
		    const struct metrics_result *m);

/* Whether M meets every requirement of K. */
bool coursefile_passed(const struct coursefile_case *k,
		       const struct metrics_result *m);

/* Q as "cecum_s <= 480" into BUF. */
void coursefile_req_text(const struct coursefile_req *q, char *buf,
			 size_t size);

/* A trainee's way through one case of the course. */
struct coursefile_progress {
	unsigned sessions;  /* judged: on this case, with metrics */
	unsigned run;       /* the last ones in a row that passed */
	size_t completed;   /* the index + 1 (into the caller's array) of the
			       session that completed the case; 0: not yet */
};

/*
 * Judges the sessions CASE_NAMES[i] with metrics M[i] (NULL: not known,
 * not judged), I = 0 .. N-1 in the order they were recorded, against C:
 * OUT[k] for C's case k.
 */
void coursefile_progress(const struct coursefile *c,
			 const char *const *case_names,
			 const struct metrics_result *const *m, size_t n,
			 struct coursefile_progress out[COURSEFILE_MAX_CASES]);

/*
 * Session M (NULL: its measures not known) of the case CASE_NAME judged
 * by C: 1 it met every requirement of its case, 0 it did not, -1 not
 * judged (M not known, or a case C does not name).
 */
int coursefile_judge(const struct coursefile *c, const char *case_name,
		     const struct metrics_result *m);

/*
 * As coursefile_progress(), each session judged already: PASSED[i] as
 * coursefile_judge() said (a listing of many sessions judges each as it
 * reads it and keeps no measures).
 */
void coursefile_progress_judged(const struct coursefile *c,
				const char *const *case_names,
				const signed char *passed, size_t n,
				struct coursefile_progress
				out[COURSEFILE_MAX_CASES]);

/* The keys of the measures C's requirements name, each once, into KEYS
 * (room for MAX); how many. */
size_t coursefile_keys(const struct coursefile *c, const char **keys,
		       size_t max);

/* Whether every case of C is complete in P (coursefile_progress()). */
bool coursefile_complete(const struct coursefile *c,
			 const struct coursefile_progress *p);

#endif
