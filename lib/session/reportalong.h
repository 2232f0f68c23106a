/*
 * reportalong.h - the report's pain along the colon (report.h): where the
 * patient hurt, next to the force and the loop, so that an instructor sees
 * at a glance whether the pain went with a pushed tip or a loop. Per
 * anatomical segment (struct metrics_along, metrics.h), in their order
 * from the anal verge, one column each, three strips of bars:
 *   - the peak pain there (0-10), the level of "in pain" marked;
 *   - the time in pain there next to the time looped there (s);
 *   - the peak insertion force there (N), the excessive force marked;
 * under the columns each segment's name and the time the tip spent there;
 * then the same as a table (segment, in pain, peak pain, time there,
 * looped, peak force), a row in pain marked warn (bad from a peak of
 * METRICS_GLOUCESTER_SEVERE_PAIN). A session without the patient shows
 * the force and the loop and says so.
 *
 * The figure's id "pain-along", the table's "pain-along-table".
 *
 * Not for the force loop: writes. Any thread; no allocation.
 */
#ifndef ENDOSIM_REPORTALONG_H
#define ENDOSIM_REPORTALONG_H

#include <stdbool.h>
#include <stdio.h>

#include "session/metrics.h"

/* The figure and the table of AL into O, with the thresholds of P (the
 * session's: pain_level, force_threshold_n); PATIENT: the session had
 * the patient's model (metrics_has_patient()). AL without segments
 * writes one line saying so. */
void reportalong_write(FILE *o, const struct metrics_along *al,
		       const struct metrics_params *p, bool patient);

#endif
