/*
 * report.h - a training session's report for the instructor: one
 * self-contained HTML page (inline CSS and SVG drawn here, no scripts, no
 * external assets) that any browser shows.
 *
 * The page holds the session's header (trainee, case, date, duration), the
 * metrics (metrics.h) with the clinical marks (withdrawal of at least
 * 6 minutes, the cecum reached, all polyps seen), and plots over time with
 * axes, ticks, units and legends:
 *   - the insertion force (N) with the threshold of excessive force;
 *   - the roll and wheel torques (N m);
 *   - the tip's position along the colon (m) over the segments' bands;
 *   - each mobile segment's bow (m) with the loop threshold;
 *   - the unseen-mucosa map: the colon unrolled (along, around), each
 *     cell's share seen, the segments, the polyps found and missed;
 *   - the pain along the colon, next to the force and the loop: per
 *     anatomical segment (metrics_along(), recomputed from F's records)
 *     the peak pain, the time in pain and looped, the peak insertion
 *     force, and a table of them (reportalong.h);
 * force episodes and loop episodes as shaded bands on every plot over
 * time, faults and state changes as vertical marks, and the lists of
 * episodes and events. Long sessions are decimated to the minimum and
 * maximum of each pixel column, so that every peak survives. Every text
 * that comes from the file (trainee, case, event texts) is HTML-escaped.
 *
 * The page's parts shared with the trainee's page: htmlpage.h; its plots
 * over time: reportplot.h; the comparison with a reference:
 * reportcompare.h; the metrics recomputed from a file: sessionmetrics.h.
 *
 * Not for the force loop: allocates, writes files. Any thread.
 */
#ifndef ENDOSIM_REPORT_H
#define ENDOSIM_REPORT_H

#include <stdio.h>

#include "model/anatomy.h"
#include "session/metrics.h"
#include "proto/session_file.h"

/* The session a report compares with (an expert's: `--reference`). */
struct report_reference {
	const struct session_file *f;
	const struct metrics_result *m;
};

/*
 * Writes DIR/index.html (DIR is created if missing; the page is written to
 * a temporary name and renamed, so a reader never sees half of it) from
 * the session F and its metrics M; with REF (NULL: none) a section that
 * sets both side by side: their metrics in one table, the tip's progress
 * over time, and the insertion force and the largest loop along the
 * colon (over where the tip was on its way in, so that the two are
 * compared at the same place, however fast each went). 0 or -errno; logs
 * nothing.
 */
int report_write(const struct session_file *f, const struct metrics_result *m,
		 const struct report_reference *ref, const char *dir);

/* The same page written to O (the centre's copy: centre.h); O's error
 * flag says whether it was all written. */
void report_print(FILE *o, const struct session_file *f,
		  const struct metrics_result *m,
		  const struct report_reference *ref);

#endif
