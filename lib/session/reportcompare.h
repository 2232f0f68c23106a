/*
 * reportcompare.h - the report's comparison of a session with a
 * reference (an expert's: `endoctl session report --reference`): both
 * sessions' main measures side by side in one table, the tip's progress
 * over time of both on one axis, and the insertion force and the largest
 * loop along the colon, over where the tip was on its way in (until the
 * cecum), so that the two are compared at the same place however fast
 * each went. The reference dashed.
 *
 * Not for the force loop: writes. Any thread; no allocation; not
 * reentrant (its two profiles along the colon are static).
 */
#ifndef ENDOSIM_REPORTCOMPARE_H
#define ENDOSIM_REPORTCOMPARE_H

#include <stdio.h>

#include "model/anatomy.h"
#include "session/report.h"

/* The comparison of F (its metrics M) with REF into the section O is in,
 * the segments' places from A (NULL: none). */
void reportcompare_write(FILE *o, const struct session_file *f,
			 const struct metrics_result *m,
			 const struct report_reference *ref,
			 const struct anatomy *a);

#endif
