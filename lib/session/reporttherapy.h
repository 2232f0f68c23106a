/*
 * reporttherapy.h - the report's therapy through the working channel
 * (report.h; the measures: therapy.h): a section "Therapy" with the
 * session's measures (the polyps resected, partly, left and retrieved of
 * the case's, the mean time per resection next to the published times,
 * the cautery, the wall injured, the biopsies and clips), then a table of
 * the case's polyps, one row each (id "polyp-N", N from 1; the row
 * marked good when resected, warn when partly, bad when left): its fate,
 * where it stands (the segment, its distance from the anal verge, its
 * size and Paris class, when the case is known), the first tool's touch,
 * the time to its resection, its cautery, its bites. The rows of
 * measures and their marks are the report's (htmlpage_row_begin()).
 *
 * The section's id "therapy", the table's "polyp-fates". A session
 * without a tool in hand (n_polyp 0) writes nothing.
 *
 * Not for the force loop: writes. Any thread; no allocation.
 */
#ifndef ENDOSIM_REPORTTHERAPY_H
#define ENDOSIM_REPORTTHERAPY_H

#include <stdio.h>

#include "model/anatomy.h"
#include "session/metrics.h"

/* The published resection times (s; docs/METRICS.md, "The therapy"):
 * a rotary snare's 24 +/- 18 s, a standard snare's 30 +/- 26 s. */
#define REPORTTHERAPY_ROTARY_S 24.0
#define REPORTTHERAPY_ROTARY_SD_S 18.0
#define REPORTTHERAPY_STANDARD_S 30.0
#define REPORTTHERAPY_STANDARD_SD_S 26.0

/* M's therapy into O; A: the case's anatomy, or NULL. */
void reporttherapy_write(FILE *o, const struct metrics_result *m,
			 const struct anatomy *a);

#endif
