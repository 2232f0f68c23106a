/* sessiontap.c - see sessiontap.h. */
#include "loop/sessiontap.h"

/* ITEM into RING, or counted in DROPS. */
static void push(struct spsc *ring, const void *item, _Atomic uint64_t *drops)
{
	if (!spsc_push(ring, item)) {
		atomic_fetch_add_explicit(drops, 1, memory_order_relaxed);
	}
}

void session_tap_push(struct session_tap *t, const struct endosim_state *st)
{
	struct session_record rec;

	if (atomic_load_explicit(&t->recording, memory_order_acquire)) {
		session_record_from_state(st, &rec);
		push(&t->ring, &rec, &t->drops);
		if (session_shape_due(st, t->shape_every)) {
			session_shape_from_state(st, &t->shape);
			push(&t->shapes, &t->shape, &t->shape_drops);
		}
	}
	/* after the push: a recorder that saw this count is past it */
	atomic_fetch_add_explicit(&t->passes, 1, memory_order_release);
}
