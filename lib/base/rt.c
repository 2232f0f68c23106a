/* rt.c - see rt.h. */
#include "base/rt.h"

#include <errno.h>
#include <sched.h>

static int create(pthread_t *thread, const struct rt_thread_params *p,
		  bool fifo, void *(*fn)(void *), void *arg)
{
	struct sched_param sp = { .sched_priority = p->priority };
	pthread_attr_t attr;
	cpu_set_t cpus;
	int r;

	pthread_attr_init(&attr);
	if (p->stack_bytes) {
		pthread_attr_setstacksize(&attr, p->stack_bytes);
	}
	if (fifo) {
		pthread_attr_setinheritsched(&attr, PTHREAD_EXPLICIT_SCHED);
		pthread_attr_setschedpolicy(&attr, SCHED_FIFO);
		pthread_attr_setschedparam(&attr, &sp);
	}
	if (p->cpu >= 0) {
		CPU_ZERO(&cpus);
		CPU_SET(p->cpu, &cpus);
		pthread_attr_setaffinity_np(&attr, sizeof(cpus), &cpus);
	}
	r = pthread_create(thread, &attr, fn, arg);
	pthread_attr_destroy(&attr);
	return -r;
}

int rt_thread_start(pthread_t *thread, const struct rt_thread_params *p,
		    void *(*fn)(void *), void *arg, bool *fifo)
{
	int r = create(thread, p, true, fn, arg);

	*fifo = r == 0;
	if (r == -EPERM) {
		r = create(thread, p, false, fn, arg);
	}
	if (!r) {
		pthread_setname_np(*thread, p->name);
	}
	return r;
}
