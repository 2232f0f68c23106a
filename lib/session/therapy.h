/*
 * therapy.h - the assessment of the therapy through the working channel
 * (issue 25): each polyp's fate, the time each resection took, the
 * cautery, the wall injured, the biopsies and clips, computed from the
 * recorded states (struct session_record, format 6's tool fields: the tool
 * in hand, the pedal, the polyp the loop holds, each cycle's events and
 * the polyp they concern) one by one, as the other metrics (metrics.h:
 * metrics_record() calls therapy_record(), metrics_result() fills its
 * measures with therapy_result()). For people: docs/METRICS.md, "The
 * therapy".
 *
 *   fate         of each of the case's polyps, at the end:
 *                  retrieved  cut free and retrieved (format 7's retrieval
 *                             by suction; none before it)
 *                  complete   cut free whole: a snare's cut, or a bite of
 *                             the forceps that took it whole (tool.h:
 *                             3 mm or less, as completely as a cold snare
 *                             at 4 mm or less, Kim et al., GIE 2015)
 *                  partly     in place, but bitten or burnt: the forceps
 *                             took samples of it, or the pedal was down
 *                             while the loop held it (it let go uncut)
 *                  left       in place, untouched
 *   start_s      the first of the tools' events on it (a lift by the
 *                needle, a capture by the loop, a bite): s since the
 *                session's first record; -1: none
 *   cut_s        its CUT event; -1: not cut
 *   resection    cut_s - start_s: from the first touch of a tool (for
 *                a lifted base its lift, at the injection's end: the
 *                records name the polyp injected only then) to the polyp
 *                free; resection_s, their mean over the polyps cut
 *   cautery      the time with the pedal down (a record's pedal held
 *                until the next record): cautery_s over the session, a
 *                polyp's while the loop held it
 *   tool_injuries the INJURY events: current into the wall (the loop on
 *                the mucosa, or holding an unlifted sessile or flat base,
 *                the pedal down; one a press of the pedal); with the
 *                patient each is also a perforation (metrics' perforations)
 *   biopsies     the BITE events (on a polyp or the mucosa)
 *   clips        the CLIP_PLACED events
 *   bleeds       the BLEED events: a cut stalk bleeding (format 7)
 *   bleeds_clipped those stopped by a clip (CLIPPED)
 *   bleed_control_s the mean time from a BLEED to its stop, by a clip
 *                (CLIPPED) or by itself (STOPPED), over those stopped; a
 *                bleeding still running at the end is counted in bleeds
 *                only
 *
 * The polyps listed: the case's (polyps_total) when a tool was in hand in
 * any record, none otherwise (a session without the tools has no therapy
 * to assess); one a tool's event names beyond them is listed too.
 *
 * Format 7's events (the bleeding, its stop, the retrieval) give the
 * bleeding's measures and the fate retrieved; older files have none.
 *
 * Plain data, no allocation; one thread (the metrics').
 */
#ifndef ENDOSIM_THERAPY_H
#define ENDOSIM_THERAPY_H

#include <stdbool.h>
#include <stdint.h>

#include "proto/session_file.h"
#include "session/metrics.h"

struct therapy {
	bool tooled;              /* a tool in hand in some record */
	bool have_prev;
	bool pedal;               /* the previous record's */
	int32_t captured;         /* ... polyp held, -1: none */
	double pedal_s;
	uint32_t injuries, bites, clips;
	uint32_t bleeds, clipped, controlled;
	double control_s;         /* the stopped bleedings' times, summed */
	double bleed_s[METRICS_MAX_POLYPS]; /* its bleeding's start; -1 none */
	bool retrieved[METRICS_MAX_POLYPS];
	uint32_t polyps;          /* 1 + the highest polyp an event named */
	struct metrics_polyp polyp[METRICS_MAX_POLYPS];
};

/* No records yet. */
void therapy_init(struct therapy *th);

/* The record R at T (s since the first record), the previous record's
 * state held for DT (s; 0 at the first). */
void therapy_record(struct therapy *th, const struct session_record *r,
		    double t, double dt);

/* The measures so far into OUT (its therapy's fields and polyp[],
 * n_polyp), the case having POLYPS_TOTAL polyps. */
void therapy_result(const struct therapy *th, uint32_t polyps_total,
		    struct metrics_result *out);

/* FATE's name ("left", "partly", "complete", "retrieved"), "?" beyond. */
const char *therapy_fate_name(uint32_t fate);

#endif
