/*
 * shm_reader.h - read endosimd's shared-memory state from any process.
 *
 * Never blocks the daemon: reads are lock-free copies under the seqlock in
 * endosim_shm.h. Not thread-safe per reader object; open one per thread.
 */
#ifndef ENDOSIM_SHM_READER_H
#define ENDOSIM_SHM_READER_H

#include <stdbool.h>

#include "proto/endosim_shm.h"

struct shm_reader;

/*
 * Maps the shm object NAME (e.g. "/endosim") read-only and checks its header
 * (magic, version, size). Returns NULL and sets errno on failure: ENOENT (no
 * daemon), EPROTO (a different layout version or size), or the error of
 * shm_open/mmap.
 */
struct shm_reader *shm_reader_open(const char *name);

/* Unmaps; NULL is fine. */
void shm_reader_close(struct shm_reader *r);

/*
 * Copies a consistent state into *out. Tries up to TRIES times (at least
 * once) while the writer is mid-update. Returns 0, or -EAGAIN when every try
 * was torn (*out is then unspecified).
 */
int shm_reader_read(struct shm_reader *r, struct endosim_state *out,
		    unsigned int tries);

/* The header as mapped (period, writer pid, start time). */
const struct endosim_shm *shm_reader_header(const struct shm_reader *r);

/* True while the process that wrote the header is still alive. */
bool shm_reader_writer_alive(const struct shm_reader *r);

#endif
