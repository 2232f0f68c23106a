/*
 * sessiontap.h - the force loop's end of a training session's recording:
 * after publishing each cycle the loop hands its state to the tap, which
 * counts the pass and, while a session records, converts the state into a
 * session record (proto/session_file.h) and pushes it into a preallocated
 * SPSC ring for the recorder thread (recorder.h). A full ring (a slow
 * disk) drops the record and counts it.
 *
 * Threads: session_tap_push() is the force loop's and never blocks,
 * allocates or writes; the recorder sets `recording`, pops the ring, reads
 * `drops` and `passes`. The ring is set up (and touched, so that the
 * loop's first pushes fault no pages) before the loop starts.
 */
#ifndef ENDOSIM_SESSIONTAP_H
#define ENDOSIM_SESSIONTAP_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "endosim_shm.h"
#include "spsc.h"

struct session_tap {
	struct spsc ring;            /* struct session_record */
	_Atomic bool recording;
	_Atomic uint64_t drops;      /* records the ring had no room for */
	_Atomic uint64_t passes;     /* cycles that went through the tap */
};

/*
 * Force loop, after publishing ST: counts the pass and pushes ST's record
 * while a session is recording.
 */
void session_tap_push(struct session_tap *t, const struct endosim_state *st);

#endif
