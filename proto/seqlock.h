/*
 * seqlock.h - one writer, any number of lock-free readers.
 *
 * The writer never waits. A reader copies the data and retries if the writer
 * was inside its critical section (odd sequence) or finished one meanwhile
 * (sequence changed). Works across processes on shared memory: the sequence
 * is the only synchronisation, a C11 atomic with acquire/release ordering.
 *
 * The protected data is copied with memcpy. A copy that raced with the
 * writer is thrown away because the sequence check fails, so the torn bytes
 * are never used.
 *
 * Who may call what:
 *  - seqlock_write_begin/end: exactly one writer (thread or process).
 *  - seqlock_read_begin/retry: any reader, never blocks; the caller bounds the
 *    number of retries (a real-time thread must not spin on a writer that
 *    may have been preempted on the same CPU: try once and keep old data).
 */
#ifndef ENDOSIM_SEQLOCK_H
#define ENDOSIM_SEQLOCK_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

typedef struct {
	_Atomic uint64_t seq;
} seqlock_t;

static inline void seqlock_init(seqlock_t *l)
{
	atomic_store_explicit(&l->seq, 0, memory_order_relaxed);
}

/* Writer: enter the critical section. */
static inline void seqlock_write_begin(seqlock_t *l)
{
	uint64_t s = atomic_load_explicit(&l->seq, memory_order_relaxed);

	atomic_store_explicit(&l->seq, s + 1, memory_order_relaxed);
	atomic_thread_fence(memory_order_release);
}

/* Writer: leave the critical section; readers may now use the new data. */
static inline void seqlock_write_end(seqlock_t *l)
{
	uint64_t s = atomic_load_explicit(&l->seq, memory_order_relaxed);

	atomic_store_explicit(&l->seq, s + 1, memory_order_release);
}

/*
 * Reader: returns the sequence to hand to seqlock_read_retry(). An odd value
 * means a write is in progress; the copy that follows will be refused.
 */
static inline uint64_t seqlock_read_begin(const seqlock_t *l)
{
	return atomic_load_explicit((_Atomic uint64_t *)&l->seq,
				    memory_order_acquire);
}

/* Reader: true when the copy made since seqlock_read_begin() is torn. */
static inline bool seqlock_read_retry(const seqlock_t *l, uint64_t start)
{
	atomic_thread_fence(memory_order_acquire);
	return (start & 1) ||
	       atomic_load_explicit((_Atomic uint64_t *)&l->seq,
				    memory_order_relaxed) != start;
}

#endif
