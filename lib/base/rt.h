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

struct rt_thread_params {
	const char *name;    /* at most 15 characters */
	int priority;        /* SCHED_FIFO priority, 1..99 */
	int cpu;             /* -1: any */
	size_t stack_bytes;  /* 0: the default */
};

/*
 * Starts FN(ARG) with P. *FIFO tells whether it got SCHED_FIFO (false when
 * the process may not: the caller warns once). Returns 0 or a negative errno.
 */
int rt_thread_start(pthread_t *thread, const struct rt_thread_params *p,
		    void *(*fn)(void *), void *arg, bool *fifo);

#endif
