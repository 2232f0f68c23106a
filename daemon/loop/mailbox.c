/* mailbox.c - see mailbox.h. */
#include "loop/mailbox.h"

#include <errno.h>
#include <string.h>
#include <time.h>

#include "base/mono.h"

#define CMD_SHIFT 8
#define GRACE_NS 100000000u /* taken just at the deadline: a cycle away */

static uint64_t deadline_ns(int timeout_ms)
{
	return mono_ns() + (uint64_t)timeout_ms * 1000000u;
}

/* An answer word's result, if it answers SEQ. */
static bool answers(uint64_t done, uint32_t seq, int *result)
{
	if ((uint32_t)(done >> 32) != seq) {
		return false;
	}
	*result = (int32_t)(uint32_t)done;
	return true;
}

uint32_t mailbox_answer_next(struct mailbox_answer *a)
{
	return ++a->seq;
}

void mailbox_answer_set(struct mailbox_answer *a, uint32_t seq, int result)
{
	atomic_store_explicit(&a->done, (uint64_t)seq << 32 | (uint32_t)result,
			      memory_order_release);
}

int mailbox_answer_wait(const struct mailbox_answer *a, uint32_t seq,
			int timeout_ms)
{
	uint64_t deadline = deadline_ns(timeout_ms);
	struct timespec nap = { .tv_nsec = 100000 };
	int r;

	for (;;) {
		uint64_t d = atomic_load_explicit(&a->done,
						  memory_order_acquire);

		if (answers(d, seq, &r)) {
			return r;
		}
		if (mono_ns() > deadline) {
			return -ETIMEDOUT;
		}
		nanosleep(&nap, NULL);
	}
}

int mailbox_answer_last(const struct mailbox_answer *a)
{
	uint64_t done = atomic_load_explicit(&a->done, memory_order_acquire);
	int r;

	return answers(done, a->seq, &r) ? r : -EINPROGRESS;
}

uint64_t mailbox_slot_post(struct mailbox_slot *s, uint32_t cmd)
{
	uint32_t seq = mailbox_answer_next(&s->answer) & MAILBOX_SLOT_SEQ_MASK;
	uint64_t slot = (uint64_t)seq << CMD_SHIFT | (uint64_t)cmd;

	atomic_store_explicit(&s->slot, slot, memory_order_release);
	return slot;
}

int mailbox_slot_wait(struct mailbox_slot *s, uint64_t slot, int timeout_ms)
{
	uint32_t seq = (uint32_t)(slot >> CMD_SHIFT);
	uint64_t deadline = deadline_ns(timeout_ms);
	struct timespec nap = { .tv_nsec = 100000 };
	int r;

	for (;;) {
		uint64_t done = atomic_load_explicit(&s->answer.done,
						     memory_order_acquire);

		if (answers(done, seq, &r)) {
			return r;
		}
		if (mono_ns() > deadline) {
			uint64_t expected = slot;

			if (atomic_compare_exchange_strong(&s->slot,
							   &expected, 0)) {
				return -ETIMEDOUT; /* withdrawn */
			}
			deadline += GRACE_NS;
		}
		nanosleep(&nap, NULL);
	}
}

uint32_t mailbox_slot_take(struct mailbox_slot *s, uint32_t *seq)
{
	uint64_t slot = atomic_load_explicit(&s->slot, memory_order_acquire);

	if (!slot || !atomic_compare_exchange_strong(&s->slot, &slot, 0)) {
		return 0;
	}
	*seq = (uint32_t)(slot >> CMD_SHIFT);
	return (uint32_t)(slot & ((1u << CMD_SHIFT) - 1));
}

void mailbox_box_init(struct mailbox_box *b, void *data, size_t size)
{
	seqlock_init(&b->lock);
	b->data = data;
	b->size = size;
	b->seen = seqlock_read_begin(&b->lock);
}

void mailbox_box_put(struct mailbox_box *b, const void *src)
{
	seqlock_write_begin(&b->lock);
	memcpy(b->data, src, b->size);
	seqlock_write_end(&b->lock);
}

bool mailbox_box_take(struct mailbox_box *b, void *dst)
{
	uint64_t seq = seqlock_read_begin(&b->lock);

	if (seq == b->seen) {
		return false;
	}
	memcpy(dst, b->data, b->size);
	if (seqlock_read_retry(&b->lock, seq)) {
		return false; /* torn: next cycle */
	}
	b->seen = seq;
	return true;
}

int mailbox_swap_hand(struct mailbox_swap *s, void *p, void **back,
		      int timeout_ms)
{
	uint64_t deadline = deadline_ns(timeout_ms);
	struct timespec nap = { .tv_nsec = 200000 };

	atomic_store_explicit(&s->in, p, memory_order_release);
	while (!(*back = atomic_exchange_explicit(&s->out, NULL,
						  memory_order_acq_rel))) {
		if (mono_ns() > deadline) {
			void *expected = p;

			if (atomic_compare_exchange_strong(&s->in, &expected,
							   NULL)) {
				return -ETIMEDOUT; /* withdrawn */
			}
			deadline += GRACE_NS;
		}
		nanosleep(&nap, NULL);
	}
	return 0;
}

void *mailbox_swap_take(struct mailbox_swap *s)
{
	return atomic_exchange_explicit(&s->in, NULL, memory_order_acq_rel);
}

void mailbox_swap_give_back(struct mailbox_swap *s, void *p)
{
	atomic_store_explicit(&s->out, p, memory_order_release);
}
