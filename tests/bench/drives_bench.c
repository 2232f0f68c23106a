/*
 * drives_bench.c - how fast each bus thread of a drive configuration
 * exchanges with its drives: exchanges per second, and the time of one
 * exchange and of one transaction (request and reply), p50 and p99.
 *
 * It runs endosimd's own rig of drives (rig_drives.h: the bus threads, the
 * backends, libusb, libmodbus) for a few seconds, enabled with zero torque,
 * posting commands and reading feedback at 1 kHz as the force loop does,
 * with each bus' rate cap lifted (--set keys as endosimd takes them). Run
 * it against the emulators (tests/bench/drives.sh does): what it measures
 * then is the emulators' speed, not hardware's.
 *
 *   drives-bench -c CONFIG [--set KEY=VALUE]... [--seconds S] [--label TEXT]
 *
 * Prints one line per bus; exits 1 when a drive faulted meanwhile.
 */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "conf/config.h"
#include "rig/hand.h"
#include "base/log.h"
#include "rig/rig_drives.h"

#define TICK_NS ENDOSIM_NS_PER_MS /* the force loop's default period */

struct options {
	const char *config, *label;
	double seconds;
};

static uint64_t now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * ENDOSIM_NS_PER_S + (uint64_t)ts.tv_nsec;
}

static int load(int argc, char **argv, struct options *o, struct config *cfg)
{
	static const struct option opts[] = {
		{ "config", required_argument, NULL, 'c' },
		{ "set", required_argument, NULL, 's' },
		{ "seconds", required_argument, NULL, 't' },
		{ "label", required_argument, NULL, 'l' },
		{ NULL, 0, NULL, 0 },
	};
	char err[512], key[128];
	const char *eq;
	int c;

	config_defaults(cfg);
	while ((c = getopt_long(argc, argv, "c:", opts, NULL)) != -1) {
		switch (c) {
		case 'c':
			o->config = optarg;
			if (config_load(cfg, optarg, err, sizeof(err))) {
				fprintf(stderr, "drives-bench: %s\n", err);
				return -1;
			}
			break;
		case 's':
			eq = strchr(optarg, '=');
			if (!eq || (size_t)(eq - optarg) >= sizeof(key)) {
				return -1;
			}
			snprintf(key, sizeof(key), "%.*s", (int)(eq - optarg),
				 optarg);
			if (config_set(cfg, key, eq + 1, false, err,
				       sizeof(err))) {
				fprintf(stderr, "drives-bench: %s\n", err);
				return -1;
			}
			break;
		case 't': o->seconds = atof(optarg); break;
		case 'l': o->label = optarg; break;
		default: return -1;
		}
	}
	return o->config && o->seconds > 0 ? 0 : -1;
}

/* As the force loop does for SECONDS: read, write zero torque, enabled. */
static bool exercise(struct rig *rig, double seconds)
{
	static const double zero[ENDOSIM_AXES];
	struct rig_feedback fb;
	uint64_t next = now_ns(),
		 end = next + (uint64_t)(seconds * ENDOSIM_NS_PER_S);
	uint32_t bad = 0;
	struct timespec ts;

	while (next < end) {
		uint64_t t = now_ns();

		rig_read(rig, t, &fb);
		rig_write(rig, t, zero, true);
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			bad |= (fb.axis[a].status &
				(ENDOSIM_DRIVE_FAULT | ENDOSIM_DRIVE_BUS_ERROR)) |
			       (~fb.axis[a].status & ENDOSIM_DRIVE_PRESENT);
		}
		next += TICK_NS;
		ts.tv_sec = (time_t)(next / ENDOSIM_NS_PER_S);
		ts.tv_nsec = (long)(next % ENDOSIM_NS_PER_S);
		clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL);
	}
	rig_write(rig, now_ns(), zero, false);
	return bad == 0;
}

/* A percentile in us; the histogram's last bin holds everything longer. */
static const char *us(double v, char *buf, size_t size)
{
	if (v >= HISTO_BINS - 1) {
		snprintf(buf, size, ">%d", HISTO_BINS - 1);
	} else {
		snprintf(buf, size, "%.0f", v);
	}
	return buf;
}

static void report(struct rig *rig, const char *label, bool clean)
{
	char a[16], b[16], c[16], d[16];
	struct rig_bus_stats st;

	for (int i = 0; !rig_bus_stats(rig, i, &st); i++) {
		printf("%-46s %6.0f Hz %7s %7s us %7s %7s us%s%s\n",
		       label ? label : st.name, st.rate_hz,
		       us(st.exchange.p50_us, a, sizeof(a)),
		       us(st.exchange.p99_us, b, sizeof(b)),
		       us(st.txn.p50_us, c, sizeof(c)),
		       us(st.txn.p99_us, d, sizeof(d)),
		       st.fifo ? "" : "  (not SCHED_FIFO)",
		       clean ? "" : "  (a drive faulted: see above)");
	}
}

int main(int argc, char **argv)
{
	struct options o = { .seconds = 3.0 };
	struct config cfg;
	struct hand *hand;
	struct rig *rig;
	bool clean;

	if (load(argc, argv, &o, &cfg)) {
		fprintf(stderr, "usage: drives-bench -c CONFIG [--set KEY=VALUE]"
			"... [--seconds S] [--label TEXT]\n");
		return 2;
	}
	log_init("drives-bench", LOG_WARNING);
	hand = hand_create(&cfg, NULL);
	rig = hand ? rig_drives_create(&cfg, hand) : NULL;
	if (!rig || rig_start(rig)) {
		return 1;
	}
	clean = exercise(rig, o.seconds);
	report(rig, o.label, clean);
	rig_stop(rig);
	rig_destroy(rig);
	hand_destroy(hand);
	return clean ? 0 : 1;
}
