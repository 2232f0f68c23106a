/*
 * traineepage.h - a trainee's courses for the instructor: one
 * self-contained HTML page (htmlpage.h: inline CSS and SVG, no scripts)
 * with
 *   - each course's status: "course complete", or per case how many
 *     sessions in a row have met its requirements and how many remain
 *     (coursefile.h); one course: in the section "course", its status
 *     "course-status", as the page always had them; more: the second's
 *     "course-2", "course-status-2", and so on;
 *   - the sessions table: id, date, case, duration, the main measures
 *     (time to the cecum, withdrawal time, mucosa seen, excessive-force
 *     and loop episodes, peak insertion force, time in pain,
 *     perforations, polyps found)
 *     and each of its case's requirements met or not (with several
 *     courses, each course that names the case: passed or failed, its
 *     requirements after its name);
 *   - the learning curves: per case, one plot per main measure across the
 *     trainee's sessions on it (the session's number on that case along
 *     x), each point marked by whether it met the courses' requirements
 *     on that measure (grey: none), each course's bounds on it as
 *     threshold lines.
 * Every text from the files (trainee, case, date) is HTML-escaped.
 *
 * Not for the force loop: writes files. Any thread; no shared state.
 */
#ifndef ENDOSIM_TRAINEEPAGE_H
#define ENDOSIM_TRAINEEPAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "session/coursefile.h"
#include "session/metrics.h"

/* One of the trainee's sessions, in the order they were recorded. */
struct traineepage_session {
	uint64_t id;
	const char *case_name;
	const char *started;            /* UTC, ISO 8601 */
	const struct metrics_result *m; /* NULL: not known (recording) */
	bool recomputed;                /* m recomputed: the file was cut */
	const char *rig;                /* the rig that recorded it (a
					   centre's, centre.h); NULL: no Rig
					   column */
	const char *href;               /* its own report page, linked from
					   its ID; NULL: none */
};

#define TRAINEEPAGE_MAX_COURSES 16

/*
 * Writes DIR/index.html (DIR created if missing; written to a temporary
 * name and renamed) for TRAINEE's N sessions S, judged by the N_COURSES
 * COURSES (none: no requirements, no status). 0, -EINVAL (more than
 * TRAINEEPAGE_MAX_COURSES courses), or -errno.
 */
int traineepage_write(const char *trainee,
		      const struct traineepage_session *s, size_t n,
		      const struct coursefile *const *courses,
		      size_t n_courses, const char *dir);

#endif
