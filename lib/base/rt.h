/*
 * rt.h - starting a real-time thread the way cyclictest does: SCHED_FIFO at
 * a given priority when the process may (root, or CAP_SYS_NICE with an
 * RLIMIT_RTPRIO that allows it), otherwise SCHED_OTHER; optionally pinned to
 * one CPU, with a stack of a given size. The force loop and the bus threads
 * use it.
 *
 * Main thread only (it creates threads; it may allocate).
 */
#ifndef ENDOSIM_RT_H
#define ENDOSIM_RT_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>

#define RT_PREFAULT_BYTES (256 * 1024) /* rt_prefault_stack()'s */

struct rt_thread_params {
	const char *name;    /* at most 15 characters */
	int priority;        /* SCHED_FIFO priority, 1..99 */
	int cpu;             /* -1: any */
	size_t stack_bytes;  /* 0: the default */
};

/*
 * Main thread only (it creates a thread; it may allocate): starts FN(ARG)
 * with P. *FIFO tells whether it got SCHED_FIFO (false when
 * the process may not: the caller warns once). Returns 0 or a negative errno.
 */
int rt_thread_start(pthread_t *thread, const struct rt_thread_params *p,
		    void *(*fn)(void *), void *arg, bool *fifo);

/*
 * Main thread, before the real-time threads start: locks the process'
 * memory, now and to come (mlockall), when it may (root, or an unlimited
 * RLIMIT_MEMLOCK: LimitMEMLOCK=infinity); otherwise, or in a build with
 * AddressSanitizer (whose shadow memory cannot be locked), logs why not.
 * Returns whether it is locked.
 */
bool rt_lock_memory(void);

/*
 * A real-time thread, first thing: touches RT_PREFAULT_BYTES of its own
 * stack (which must be larger: rt_thread_params.stack_bytes), so that
 * with the memory locked those pages stay. Never blocks or allocates.
 */
void rt_prefault_stack(void);

#endif
