/*
 * mailbox.h - how the control thread talks to the force loop without a
 * lock (loop.h): the loop only ever looks and takes, once a cycle, and
 * never waits; the control thread posts and may wait for the answer.
 *
 *  - a slot (mailbox_slot): one command at a time, a small number, which
 *    the loop takes whole or the poster withdraws whole after a timeout;
 *    never both (the enable, disable, estop and reset commands);
 *  - a box (mailbox_box): the latest copy of a struct, written by one
 *    thread and taken whole (a seqlock, seqlock.h) by the other when it
 *    changed; a torn copy is left for the next cycle (the live
 *    configuration, a test command, a guidance command);
 *  - an answer (mailbox_answer): the loop's result to the poster's
 *    numbered request, polled or waited for;
 *  - a swap (mailbox_swap): a pointer handed to the loop, which hands
 *    back the one it replaced, or the same when it refuses it (a new
 *    colon).
 *
 * C11 acquire/release atomics. Each side's functions are for its one
 * thread: "poster" the control thread (or a lockstep caller), "loop" the
 * force loop. The loop's never block, allocate or print; the poster's
 * waits sleep 0.1 or 0.2 ms between looks. Nothing allocates.
 */
#ifndef ENDOSIM_MAILBOX_H
#define ENDOSIM_MAILBOX_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "proto/seqlock.h"

#define MAILBOX_SLOT_SEQ_MASK 0xffffffu /* a slot's request numbers */

/* The loop's answer to the poster's request SEQ: seq << 32 | result. */
struct mailbox_answer {
	_Atomic uint64_t done; /* loop -> poster */
	uint32_t seq;          /* the poster's count of requests */
};

/* Poster: the next request's number. */
uint32_t mailbox_answer_next(struct mailbox_answer *a);

/* Loop: RESULT (0 or a negative errno) is the answer to request SEQ. */
void mailbox_answer_set(struct mailbox_answer *a, uint32_t seq, int result);

/* Poster: the answer to SEQ, waited for up to TIMEOUT_MS; -ETIMEDOUT
 * without one. */
int mailbox_answer_wait(const struct mailbox_answer *a, uint32_t seq,
			int timeout_ms);

/* Poster: the answer to the last request, -EINPROGRESS before it. */
int mailbox_answer_last(const struct mailbox_answer *a);

/* A command slot: 0 empty, else seq << 8 | command (1..255). */
struct mailbox_slot {
	_Atomic uint64_t slot;         /* poster -> loop */
	struct mailbox_answer answer;  /* its request numbers masked by
					  MAILBOX_SLOT_SEQ_MASK */
};

/* Poster: leaves CMD (1..255) in the slot, over any left there;
 * returns the slot's word, for mailbox_slot_wait(). */
uint64_t mailbox_slot_post(struct mailbox_slot *s, uint32_t cmd);

/*
 * Poster: waits up to TIMEOUT_MS for the answer to SLOT (what
 * mailbox_slot_post() returned). Past it the command is withdrawn if the
 * loop did not take it (-ETIMEDOUT); one taken just then is waited for
 * 100 ms more at a time: its answer is a cycle away.
 */
int mailbox_slot_wait(struct mailbox_slot *s, uint64_t slot, int timeout_ms);

/* Loop: takes the command left in the slot: its number, 0 when none, and
 * its request's in *SEQ for mailbox_answer_set(&S->answer, ...). */
uint32_t mailbox_slot_take(struct mailbox_slot *s, uint32_t *seq);

/* A box of SIZE bytes at DATA (the owner's, outliving the box). */
struct mailbox_box {
	seqlock_t lock;
	void *data;
	size_t size;
	uint64_t seen;  /* the loop's: the version it took last */
};

/* Before either side uses it: nothing to take until the first put. */
void mailbox_box_init(struct mailbox_box *b, void *data, size_t size);

/* Poster: copies SRC (SIZE bytes) into the box. */
void mailbox_box_put(struct mailbox_box *b, const void *src);

/* Loop: copies the box into DST when it changed since the last take and
 * the copy is whole; false (DST's bytes unspecified) otherwise. */
bool mailbox_box_take(struct mailbox_box *b, void *dst);

/* A pointer handed over: in the loop's way, and back. */
struct mailbox_swap {
	_Atomic(void *) in;  /* poster -> loop */
	_Atomic(void *) out; /* loop -> poster: replaced, or refused */
};

/*
 * Poster: hands P to the loop and waits up to TIMEOUT_MS for what it
 * hands back (*BACK: P refused, or the one P replaced). Past it, P is
 * withdrawn if the loop did not take it (-ETIMEDOUT: P is the caller's
 * again); one taken just then is waited for 100 ms more at a time. A
 * value the poster writes before the call is the loop's after its take.
 */
int mailbox_swap_hand(struct mailbox_swap *s, void *p, void **back,
		      int timeout_ms);

/* Loop: what was handed over, NULL when nothing was. */
void *mailbox_swap_take(struct mailbox_swap *s);

/* Loop: hands P back (the pointer taken, refused, or the one replaced). */
void mailbox_swap_give_back(struct mailbox_swap *s, void *p);

#endif
