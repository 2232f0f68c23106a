/* sessiontap.c - see sessiontap.h. */
#include "sessiontap.h"

#include "session_file.h"

void session_tap_push(struct session_tap *t, const struct endosim_state *st)
{
	struct session_record rec;

	if (atomic_load_explicit(&t->recording, memory_order_acquire)) {
		session_record_from_state(st, &rec);
		if (!spsc_push(&t->ring, &rec)) {
			atomic_fetch_add_explicit(&t->drops, 1,
						  memory_order_relaxed);
		}
	}
	/* after the push: a recorder that saw this count is past it */
	atomic_fetch_add_explicit(&t->passes, 1, memory_order_release);
}
