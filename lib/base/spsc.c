/* spsc.c - see spsc.h. */
#include "base/spsc.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

int spsc_init(struct spsc *r, size_t capacity, size_t record_size)
{
	size_t n = 1;

	while (n < capacity) {
		n <<= 1;
	}
	r->records = calloc(n, record_size);
	if (!r->records) {
		return -ENOMEM;
	}
	atomic_init(&r->head, 0);
	atomic_init(&r->tail, 0);
	r->mask = n - 1;
	r->record_size = record_size;
	return 0;
}

void spsc_free(struct spsc *r)
{
	free(r->records);
	r->records = NULL;
}

bool spsc_push(struct spsc *r, const void *record)
{
	size_t head = atomic_load_explicit(&r->head, memory_order_relaxed);
	size_t tail = atomic_load_explicit(&r->tail, memory_order_acquire);

	if (head - tail > r->mask) {
		return false;
	}
	memcpy(r->records + (head & r->mask) * r->record_size, record,
	       r->record_size);
	atomic_store_explicit(&r->head, head + 1, memory_order_release);
	return true;
}

bool spsc_pop(struct spsc *r, void *record)
{
	size_t tail = atomic_load_explicit(&r->tail, memory_order_relaxed);
	size_t head = atomic_load_explicit(&r->head, memory_order_acquire);

	if (head == tail) {
		return false;
	}
	memcpy(record, r->records + (tail & r->mask) * r->record_size,
	       r->record_size);
	atomic_store_explicit(&r->tail, tail + 1, memory_order_release);
	return true;
}

size_t spsc_count(struct spsc *r)
{
	return atomic_load_explicit(&r->head, memory_order_acquire) -
	       atomic_load_explicit(&r->tail, memory_order_acquire);
}
