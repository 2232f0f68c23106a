/*
 * spsc.h - a bounded single-producer/single-consumer ring of fixed-size
 * records, lock-free (C11 acquire/release). The buffer is allocated once by
 * spsc_init(); push and pop never allocate, block or fail except on a full
 * or empty ring. The force loop uses it to hand events and samples to other
 * threads.
 *
 * Exactly one thread may push and exactly one may pop.
 */
#ifndef ENDOSIM_SPSC_H
#define ENDOSIM_SPSC_H

#include <stdalign.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>

struct spsc {
	alignas(64) _Atomic size_t head; /* next slot to write (producer) */
	alignas(64) _Atomic size_t tail; /* next slot to read (consumer) */
	alignas(64) size_t mask;
	size_t record_size;
	unsigned char *records;
};

/* CAPACITY is rounded up to a power of two. Returns 0 or -ENOMEM. */
int spsc_init(struct spsc *r, size_t capacity, size_t record_size);

/* Frees the buffer; safe on a zeroed ring. */
void spsc_free(struct spsc *r);

/* Producer: copies RECORD in. False (nothing copied) when full. */
bool spsc_push(struct spsc *r, const void *record);

/* Consumer: copies the oldest record out. False when empty. */
bool spsc_pop(struct spsc *r, void *record);

/* Records waiting; exact for the consumer, a snapshot for anyone else. */
size_t spsc_count(struct spsc *r);

#endif
