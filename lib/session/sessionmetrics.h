/*
 * sessionmetrics.h - a session file's metrics recomputed from its records
 * (metrics.h): the colon rebuilt from its CASE frame, its configuration
 * and its header's resolution (sessioninputs.h), the records fed in with
 * its events in time order. For a file whose END frame is missing (a
 * recording cut short), for the report's map and measures along the
 * colon, and for other thresholds than those it was recorded with.
 *
 * Not for the force loop: allocates (the colon, ~50 ms), reads nothing
 * but F. Any thread.
 */
#ifndef ENDOSIM_SESSIONMETRICS_H
#define ENDOSIM_SESSIONMETRICS_H

#include <stddef.h>

#include "proto/session_file.h"
#include "session/metrics.h"

/*
 * The metrics of F with P into OUT (without a case, those that need no
 * colon). 0, or -ENOMEM with one line in ERR. A case that does not load
 * leaves the colon out, as its line in ERR says; ERR is empty otherwise.
 */
int sessionmetrics_compute(const struct session_file *f,
			   const struct metrics_params *p,
			   struct metrics_result *out, char *err,
			   size_t errsize);

/*
 * F's unseen-mucosa map (metrics_map()) into MAP and its measures along
 * the colon (metrics_along()) into ALONG (either NULL: not wanted), with
 * the metrics' parameters F was recorded with: what the END frame does
 * not hold. 0 or -ENOMEM. The report draws them under its plots.
 */
int sessionmetrics_map(const struct session_file *f, struct metrics_map *map,
		       struct metrics_along *along);

#endif
