/*
 * sessionindex.h - the index of a session directory (sessiondir.h): the
 * file DIR/index, one line per ID.endoses file with what its header says
 * (trainee, case, start), its size and modification time, and the
 * metrics of its END frame (the scalars, metricstext_fields(); no
 * episodes), so that a trainee's sessions are found and judged without
 * replaying files (endoctl trainee).
 *
 * The session files are the truth; the index only saves reading them. A
 * load checks it against the directory: a file added, one removed, or
 * one whose size or modification time changed (the session recording,
 * one rewritten) makes it stale, and only those files are read again; a
 * line that does not parse or whose CRC-32 does not match makes it
 * damaged, and its file is read again. A missing index is built from
 * every file. A changed index is written to a temporary file and renamed
 * over DIR/index, so a reader never sees half of one. The format, one
 * line each, fields separated by a tab (docs/SESSION_FORMAT.md):
 *
 *   endosim-session-index 1
 *   ID BYTES MTIME_NS KIND TRAINEE CASE STARTED METRICS CRC
 *
 * KIND "ended" (an END frame: METRICS its "key=value" pairs separated by
 * spaces), "cut" (none: METRICS "-") or "bad" (not a session file, kept so
 * that it is not read each time); control characters of the header's
 * texts become '?'; CRC the CRC-32 (session_crc32()) of the line before
 * its last tab, 8 hex digits.
 *
 * Reads the directory and the files' headers and tails, allocates: the
 * control thread or endoctl, never the force loop. One writer per
 * directory (endosimd, which owns it); a reader that may not write (a
 * directory endoctl reads) loads with WRITE false.
 */
#ifndef ENDOSIM_SESSIONINDEX_H
#define ENDOSIM_SESSIONINDEX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "session/metrics.h"
#include "session/sessiondir.h"

#define SESSIONINDEX_NAME "index"

enum sessionindex_state {
	SESSIONINDEX_FRESH,    /* it matched the directory */
	SESSIONINDEX_MISSING,  /* none: built from every file */
	SESSIONINDEX_STALE,    /* files added, removed or changed */
	SESSIONINDEX_DAMAGED,  /* lines that do not parse: read again */
};

struct sessionindex_entry {
	struct sessiondir_entry e;  /* id (its file's name), bytes, ended,
				       trainee, case, started */
	int64_t mtime_ns;           /* the file's modification time */
	bool has_metrics;           /* m is its END frame's */
	struct metrics_result m;    /* the scalars; n_force = n_loop = 0 */
};

struct sessionindex_info {
	enum sessionindex_state state;
	size_t reread;      /* files whose header (and END) were read */
	size_t bad_lines;   /* lines of the index that did not parse */
	int write_error;    /* 0, or -errno of writing the index */
};

/*
 * The sessions of DIR, sorted by ID, from DIR/index checked against the
 * directory (see above): a malloc'd array of *N in *OUT (free() it);
 * files that are not session files are left out. With WRITE the index is
 * written again when it was not fresh (a failure to do so is only said in
 * INFO->write_error: the entries are right all the same). 0 or -errno
 * (the directory unreadable, -ENOMEM).
 */
int sessionindex_load(const char *dir, bool write,
		      struct sessionindex_entry **out, size_t *n,
		      struct sessionindex_info *info);

/* "fresh", "missing", "stale", "damaged". */
const char *sessionindex_state_name(enum sessionindex_state s);

#endif
