/*
 * sessionview.h - what endoctl makes of a session file (session_file.h):
 * its metrics (from the END frame, or recomputed over its records when the
 * file was cut short and has none), the metrics as text and JSON, and the
 * records as CSV.
 *
 * Reads files and allocates: endoctl's, never the daemon's force loop.
 */
#ifndef ENDOSIM_SESSIONVIEW_H
#define ENDOSIM_SESSIONVIEW_H

#include <stdbool.h>
#include <stdio.h>

#include "proto/session_file.h"
#include "base/json.h"
#include "session/metrics.h"

/*
 * The metrics of the session in F: parsed from its END frame, or, for a
 * file without one (a crash), computed again over its records and events
 * (*RECOMPUTED true, sessionmetrics_compute()) with the thresholds of its
 * CONFIG frame's [session], on the colon rebuilt from its CASE frame and
 * header (without a colon when that fails: no mucosa or polyps then). 0
 * or -errno.
 */
int sessionview_metrics(const struct session_file *f,
			struct metrics_result *out, bool *recomputed);

/* The metrics as lines "name  value unit" for people (the therapy a
 * line and a line a polyp, when a tool was in hand: therapy.h). */
void sessionview_print(FILE *out, const struct metrics_result *m);

/* The metrics as the JSON object KEY (NULL: a value in an array); the
 * therapy's polyps as the array "polyps" when a tool was in hand. */
void sessionview_json(struct json *j, const char *key,
		      const struct metrics_result *m);

/* The session's start (CLOCK_MONOTONIC ns), which its CSV's t_s and its
 * events' times count from: the header's start_ns, else its first
 * record's. */
uint64_t sessionview_start_ns(const struct session_file *f);

/*
 * The records of F as CSV: a header row naming every field with its unit
 * (t_s, cycle, state, ..., insertion_m, ...), one row per record, t_s in s
 * from the session's start. 0 or -EIO.
 */
int sessionview_csv(FILE *out, const struct session_file *f);

/*
 * The events of F as CSV: t_s (from the session's start), kind (state,
 * fault, param, drops, note, position, hand, valve, perforation: names.h),
 * axis, detail, value, text (quoted). 0 or -EIO.
 */
int sessionview_events_csv(FILE *out, const struct session_file *f);

/*
 * The summary CSV (`endoctl session export ID... --summary`): a header of
 * id, trainee, case, started and every measure (metricstext_fields()'
 * keys), then one row per session of F with its metrics M. 0 or -EIO.
 */
int sessionview_summary_header(FILE *out);
int sessionview_summary_row(FILE *out, const struct session_file *f,
			    const struct metrics_result *m);

#endif
