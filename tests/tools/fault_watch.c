/*
 * fault_watch - watches endosimd's shared memory, as fast as it can, until
 * a fault appears, and tells what the published states show about it: the
 * fault tests' witness (tests/system/4N-*.sh).
 *
 *   fault_watch NAME BITS TIMEOUT_S [--ready FILE] [--after S]
 *
 * BITS: the enum endosim_fault bits to wait for (any of them), in hex or
 * decimal. --ready FILE is created once the first state is read (inject
 * after that). After the fault it keeps watching for --after S (default
 * 0.3) and prints key=value lines:
 *
 *   watch_ns          the first state's CLOCK_MONOTONIC stamp
 *   before_cycle      the last state seen without the fault
 *   before_limited    its largest |limited| over the axes
 *   fault_cycle       the first state seen with the fault
 *   fault_bit, fault_axis, fault_detail, fault_value, fault_limit
 *   fault_ns          when the loop latched it (the cause's first_ns)
 *   publish_delay_ns  that state's stamp - fault_ns: 0 when the watcher saw
 *                     the very cycle that found the fault
 *   fault_limited     the largest |limited| in that first state
 *   state             its state
 *   torque_violations states seen (before and after) with a fault latched
 *                     or not ENABLED, yet some |limited| > 0
 *   states            distinct states seen
 *
 * It reads every 50 us, at SCHED_FIFO priority 1 where it may (below the
 * daemon's threads, above ordinary processes), so as to see every cycle.
 *
 * SIGTERM or SIGINT end the watch early, with the report.
 *
 * Exit 0 when the fault appeared, 1 otherwise, 2 on usage or no shm.
 */
#include <errno.h>
#include <math.h>
#include <sched.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "proto/names.h"
#include "proto/shm_reader.h"

struct watch {
	struct endosim_state st, before, first;
	unsigned long states, violations;
	uint64_t watch_ns;
	bool have_before, faulted;
};

static volatile sig_atomic_t stop;

static void on_signal(int sig)
{
	(void)sig;
	stop = 1;
}

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + (double)ts.tv_nsec / ENDOSIM_NS_PER_S;
}

static double largest_limited(const struct endosim_state *st)
{
	double m = 0;

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		m = fmax(m, fabs(st->axis[a].limited));
	}
	return m;
}

/* Torque must be off in every state but ENABLED without a fault. */
static bool violates(const struct endosim_state *st)
{
	bool off = st->fault_bits || st->state != ENDOSIM_STATE_ENABLED;

	return off && largest_limited(st) > 0;
}

/* A new state: counted, checked, and the fault looked for. */
static void take(struct watch *w, uint32_t bits)
{
	w->states++;
	w->violations += violates(&w->st);
	if (!w->watch_ns) {
		w->watch_ns = w->st.stamp_ns;
	}
	if (w->faulted) {
		return;
	}
	if (w->st.fault_bits & bits) {
		w->first = w->st;
		w->faulted = true;
	} else {
		w->before = w->st;
		w->have_before = true;
	}
}

static void report(const struct watch *w, uint32_t bits)
{
	const struct endosim_state *f = &w->first;
	uint32_t seen = f->fault_bits & bits;
	uint32_t bit = seen & (~seen + 1); /* the lowest one */
	const struct endosim_fault_cause *c =
		&f->safety.cause[__builtin_ctz(bit)];

	printf("watch_ns=%llu\n", (unsigned long long)w->watch_ns);
	printf("before_cycle=%llu\nbefore_limited=%.9g\n",
	       w->have_before ? (unsigned long long)w->before.cycle : 0ull,
	       w->have_before ? largest_limited(&w->before) : 0.0);
	printf("fault_cycle=%llu\nfault_bit=%s\nfault_axis=%s\n",
	       (unsigned long long)f->cycle, names_fault(bit),
	       c->axis >= 0 ? names_axis(c->axis) : "none");
	printf("fault_detail=%u\nfault_value=%.9g\nfault_limit=%.9g\n",
	       c->detail, c->value, c->limit);
	printf("fault_ns=%llu\npublish_delay_ns=%lld\n",
	       (unsigned long long)c->first_ns,
	       (long long)(f->stamp_ns - c->first_ns));
	printf("fault_limited=%.9g\nstate=%s\n", largest_limited(f),
	       names_state(f->state));
}

int main(int argc, char **argv)
{
	const char *ready = NULL;
	double after = 0.3, timeout, t_end, t_fault = 0;
	struct watch w = { 0 };
	struct shm_reader *r;
	uint64_t last = UINT64_MAX;
	uint32_t bits;

	if (argc < 4) {
		fprintf(stderr, "usage: fault_watch NAME BITS TIMEOUT_S "
			"[--ready FILE] [--after S]\n");
		return 2;
	}
	bits = (uint32_t)strtoul(argv[2], NULL, 0);
	timeout = atof(argv[3]);
	for (int i = 4; i + 1 < argc; i += 2) {
		if (!strcmp(argv[i], "--ready")) {
			ready = argv[i + 1];
		} else if (!strcmp(argv[i], "--after")) {
			after = atof(argv[i + 1]);
		}
	}
	r = shm_reader_open(argv[1]);
	if (!r) {
		fprintf(stderr, "fault_watch: %s: %s\n", argv[1],
			strerror(errno));
		return 2;
	}
	signal(SIGTERM, on_signal);
	signal(SIGINT, on_signal);
	sched_setscheduler(0, SCHED_FIFO, &(struct sched_param){ 1 });
	t_end = now_s() + timeout;
	while (!stop && now_s() < (w.faulted ? t_fault + after : t_end)) {
		nanosleep(&(struct timespec){ .tv_nsec = 50000 }, NULL);
		if (shm_reader_read(r, &w.st, 100) || w.st.cycle == last) {
			continue;
		}
		last = w.st.cycle;
		take(&w, bits);
		if (w.faulted && !t_fault) {
			t_fault = now_s();
		}
		if (ready && w.states == 1) {
			FILE *f = fopen(ready, "w");

			if (f) {
				fclose(f);
			}
		}
	}
	printf("states=%lu\ntorque_violations=%lu\n", w.states, w.violations);
	if (w.faulted) {
		report(&w, bits);
	}
	shm_reader_close(r);
	return w.faulted ? 0 : 1;
}
