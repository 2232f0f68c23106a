/*
 * publish.h - the writer side of the shared-memory state (endosim_shm.h).
 *
 * publish_create() makes the POSIX shm object (mode 0644: any local user may
 * read it), sizes it, maps it and writes the header. publish_state() is the
 * force loop's one write per cycle under the seqlock: a memcpy, no system
 * call. publish_read() gives other daemon threads a consistent copy.
 */
#ifndef ENDOSIM_PUBLISH_H
#define ENDOSIM_PUBLISH_H

#include <stdint.h>

#include "proto/endosim_shm.h"

struct publish;

/*
 * Creates NAME, replacing a stale object a dead daemon left behind. Returns
 * NULL on failure, logged.
 */
struct publish *publish_create(const char *name, uint32_t period_ns,
			       uint64_t start_ns);

/* Unmaps and unlinks; NULL is fine. */
void publish_destroy(struct publish *p);

/* Force loop: publishes STATE. Never blocks. */
void publish_state(struct publish *p, const struct endosim_state *state);

/* Any other thread: a consistent copy. Returns 0 or -EAGAIN. */
int publish_read(const struct publish *p, struct endosim_state *out);

#endif
