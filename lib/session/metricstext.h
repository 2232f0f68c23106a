/*
 * metricstext.h - a session's metrics (struct metrics_result, metrics.h)
 * by their names: the table of its scalar measures, each with its key and
 * its kind (fields.h's), which the END frame, `session show`, the JSON,
 * the summary CSV, the trainee's page and the courses' conditions name
 * them by; and the END frame's text, "key=value\n" lines: the scalars in
 * the table's order, then each kept episode as
 * "force_episode.N=start,end,peak" or "loop_episode.N=...", and
 * "pain_episode.N=start,end,peak,cause,place" (cause: enum
 * endosim_pain_cause, place: the segment, -1 none); then each of the
 * therapy's polyps (therapy.h) as "polyp.N=fate,start,cut,cautery,bites"
 * (fate: enum metrics_fate; start and cut -1: none).
 *
 * Pure: any thread, no allocation, no shared state.
 */
#ifndef ENDOSIM_METRICSTEXT_H
#define ENDOSIM_METRICSTEXT_H

#include <stddef.h>

#include "proto/fields.h"
#include "session/metrics.h"

/* One scalar measure: its key, where it is in struct metrics_result, its
 * kind (FIELDS_DOUBLE: double, FIELDS_UINT: uint32_t, FIELDS_UINT64:
 * uint64_t). */
struct metricstext_field {
	const char *key;
	size_t offset;
	enum fields_kind kind;
};

/* The table of them, in the END frame's order; returns how many. */
size_t metricstext_fields(const struct metricstext_field **out);

/* F's value in R. */
double metricstext_field_value(const struct metrics_result *r,
			       const struct metricstext_field *f);

/*
 * RESULT as "key=value\n" lines (the END frame, `session show`); returns
 * the length written, or -ENOSPC when SIZE is too small.
 */
int metricstext_format(const struct metrics_result *result, char *buf,
		       size_t size);

/*
 * The inverse of metricstext_format(): 0, or -EINVAL naming nothing. A
 * key it does not know (a later version's) is skipped.
 */
int metricstext_parse(const char *text, struct metrics_result *out);

#endif
