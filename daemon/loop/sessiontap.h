/*
 * sessiontap.h - the force loop's end of a training session's recording:
 * after publishing each cycle the loop hands its state to the tap, which
 * counts the pass and, while a session records, converts the state into a
 * session record (proto/session_file.h) and pushes it into a preallocated
 * SPSC ring for the recorder thread (recorder.h); in the rod model, every
 * shape_every-th cycle (session_shape_due()), also the rod's shape into a
 * second ring. A full ring (a slow disk) drops the record or the shape
 * and counts it.
 *
 * Threads: session_tap_push() is the force loop's and never blocks,
 * allocates or writes; the recorder sets `recording`, pops the rings,
 * reads `drops`, `shape_drops` and `passes`. The rings and shape_every are
 * set up (the rings touched, so that the loop's first pushes fault no
 * pages) before the loop starts.
 */
#ifndef ENDOSIM_SESSIONTAP_H
#define ENDOSIM_SESSIONTAP_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "proto/endosim_shm.h"
#include "proto/session_file.h"
#include "base/spsc.h"

struct session_tap {
	struct spsc ring;            /* struct session_record */
	struct spsc shapes;          /* struct session_shape */
	uint32_t shape_every;        /* session_shape_every() of the loop's */
	struct session_shape shape;  /* the loop's: the one being made */
	_Atomic bool recording;
	_Atomic uint64_t drops;      /* records the ring had no room for */
	_Atomic uint64_t shape_drops; /* shapes the ring had no room for */
	_Atomic uint64_t passes;     /* cycles that went through the tap */
};

/*
 * Force loop, after publishing ST: counts the pass and pushes ST's record,
 * and its shape when one is due, while a session is recording.
 */
void session_tap_push(struct session_tap *t, const struct endosim_state *st);

#endif
