/* rt.c - see rt.h. */
#include "base/rt.h"

#include <errno.h>
#include <sched.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include "base/log.h"

#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif

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

bool rt_lock_memory(void)
{
	struct rlimit rl;

#ifdef UNDER_ASAN
	log_info("memory not locked: built with AddressSanitizer, whose "
		 "shadow memory cannot be locked");
	return false;
#endif
	getrlimit(RLIMIT_MEMLOCK, &rl);
	if (geteuid() != 0 && rl.rlim_cur != RLIM_INFINITY) {
		log_warn("memory not locked: RLIMIT_MEMLOCK is %llu KiB "
			 "(set LimitMEMLOCK=infinity); page faults may "
			 "delay the force loop",
			 (unsigned long long)rl.rlim_cur / 1024);
		return false;
	}
	if (mlockall(MCL_CURRENT | MCL_FUTURE) < 0) {
		log_warn("memory not locked: mlockall: %m");
		return false;
	}
	return true;
}

void rt_prefault_stack(void)
{
	unsigned char buf[RT_PREFAULT_BYTES];

	memset(buf, 0, sizeof(buf));
	__asm__ volatile("" : : "r"(buf) : "memory");
}
