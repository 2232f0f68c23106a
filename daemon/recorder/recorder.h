/*
 * recorder.h - training sessions: the recorder thread that writes every
 * force-loop cycle of a session into a session file (proto/session_file.h,
 * docs/SESSION_FORMAT.md) and computes the session's metrics (metrics.h)
 * live, outside the force loop.
 *
 * Data flow:
 *
 *   force loop --session_tap_push()--> record ring (SPSC, [session]
 *   ring_s of cycles) --> recorder thread: metrics, events, frames
 *   gathered in a buffer, write(2) every ~100 ms or when full
 *              (rod model) --> shape ring (as many seconds, a shape every
 *   session_shape_every() cycles) --> recorder thread: SHAPE frames after
 *   the records of the same drain
 *
 * The force loop's only part is the tap (sessiontap.h): while a session is
 * recording it converts the published state into a record and pushes it
 * (and the rod's shape when one is due); a full ring (a slow disk) drops
 * the record or the shape and counts it. It never waits, allocates or
 * writes. The recorder writes a DROPS event whenever the records' count
 * grows, so a file says where it has gaps (a shape's gap shows in the
 * SHAPE frames' cycles).
 *
 * The recorder derives STATE and FAULT events from the records' state and
 * fault bits, the guidance's NOTE events from its phase, the patient's
 * POSITION, HAND, VALVE and PERFORATION events from its fields (the
 * site's name from the session's colon), the tool's TOOL events (a tool
 * handed over, each of its event bits), takes PARAM events from the
 * control thread
 * (recorder_param()), and at stop writes the END frame (the final
 * metrics), fsyncs and closes. One session at a time.
 *
 * While recording, the recorder also keeps the unseen-mucosa map
 * (metrics_map(), quantised by livemap.h) for endoview's overlay and
 * `endoctl session map` (recorder_map()): renewed every RECORDER_MAP_S
 * (the metrics keep each cell's seen area as they go: a map is ~4000
 * cells, microseconds). It is made outside the lock and copied in under
 * it (4 kB), so a reader holds the recorder up for a copy at most.
 *
 * Threads: the tap is the force loop's; recorder_start(),
 * recorder_stop(), recorder_param(), recorder_info() and recorder_map()
 * the control thread's (they may block briefly on the recorder's mutex;
 * start writes the file's first frames, stop waits for the last ones and
 * the fsync); create, run and destroy the main thread's.
 */
#ifndef ENDOSIM_RECORDER_H
#define ENDOSIM_RECORDER_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "proto/endosim_shm.h"
#include "proto/session_file.h"
#include "model/colon.h"
#include "conf/config.h"
#include "session/metrics.h"
#include "loop/publish.h"
#include "rig/rig.h"
#include "loop/sessiontap.h"
#include "session/livemap.h"

#define RECORDER_NAME 64 /* trainee and case names, bytes with the NUL */
#define RECORDER_PATH 256

/* What a session starts with (the control thread fills it). */
struct recorder_session {
	char trainee[RECORDER_NAME];
	char case_name[RECORDER_NAME];
	const char *config_text;     /* as --print-config prints it */
	const char *case_text;       /* the case file's text */
	const struct colon *colon;   /* the metrics' colon: must stay until
					recorder_stop() (no case loads during
					a session) */
	uint32_t period_ns;
	double step_m, segment_m;    /* the colon's resolution */
	int ring_vertices;
};

/* A session, running or just ended, as endoctl shows it. */
struct recorder_info {
	bool active;                 /* false: no session since start-up */
	bool recording;
	uint64_t id;
	char trainee[RECORDER_NAME];
	char case_name[RECORDER_NAME];
	char started[32];            /* UTC, ISO 8601 */
	char path[RECORDER_PATH];
	uint64_t start_ns, end_ns;   /* CLOCK_MONOTONIC; end 0 while running */
	uint64_t records;            /* written so far */
	uint64_t drops;
	uint64_t bytes;              /* file size so far */
	uint64_t checksum;           /* once ended: records_checksum() of the
					file as written */
	bool checksum_known;         /* checksum is the whole file's (false:
					a write failed, or it records) */
	struct metrics_result metrics; /* live: refreshed every ~100 ms */
};

#define RECORDER_MAP_S 0.25         /* the live map renewed this often, s */

/* The recording session's unseen-mucosa map, as last renewed. */
struct recorder_map {
	uint64_t id;                 /* the session */
	double time_s;               /* into the session (its first record) */
	double length_m;             /* the colon's; 0: no colon geometry */
	double mucosa_seen;          /* 0..1 of the mesh's area */
	double tip_s_m;              /* the tip along the colon then */
	uint32_t polyps_found_mask;  /* bit k: the case's polyp k found */
	uint8_t cells[LIVEMAP_CELLS]; /* livemap.h */
};

struct recorder;

/*
 * Allocates the ring ([session] ring_s at the loop's rate) and the write
 * buffer; creates [session] directory if it is missing. A new fault's
 * cause is read from PUB and put into words with RIG, its time counted
 * from START_NS (the daemon's start), as in the journal. NULL on failure
 * (logged).
 */
struct recorder *recorder_create(const struct config *cfg, struct rig *rig,
				 struct publish *pub, uint64_t start_ns);

/* The tap for loop_set_tap(). */
struct session_tap *recorder_tap(struct recorder *r);

/*
 * Starts the recorder thread (SCHED_OTHER); a stop waits for the tap's
 * next two passes (at most 100 ms). 0/-errno.
 */
int recorder_run(struct recorder *r);

/*
 * Opens the next session file (ID = largest existing + 1), writes HEADER,
 * CONFIG and CASE, and starts recording from the next cycle. 0; -EBUSY (a
 * session is recording); -errno from the file (logged). *INFO: the session.
 */
int recorder_start(struct recorder *r, const struct recorder_session *s,
		   struct recorder_info *info);

/*
 * Stops recording: the ring drained into the file, the END frame with the
 * final metrics, fsync, close. Waits for it (bounded by the disk). 0;
 * -ENOENT when no session is recording; -EIO when the file could not be
 * finished (logged). *INFO: the session as it ended.
 */
int recorder_stop(struct recorder *r, struct recorder_info *info);

/* The current or last session; INFO->active false if none yet. */
void recorder_info(struct recorder *r, struct recorder_info *info);

/*
 * The recording session's map into *OUT. 0; -ENOENT when no session is
 * recording; -EAGAIN before its first map (the first drain of a session).
 * Never allocates; holds the recorder's mutex for a copy.
 */
int recorder_map(struct recorder *r, struct recorder_map *out);

/* A live parameter changed (SetParam): a PARAM event while recording. */
void recorder_param(struct recorder *r, const char *key, const char *value);

/* Stops a running session (as recorder_stop()) and the thread; frees. */
void recorder_destroy(struct recorder *r);

#endif
