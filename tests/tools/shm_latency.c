/*
 * shm_latency - publish-to-read latency of endosimd's shared memory as a
 * reader process sees it: polls the seqlock and, for each new cycle,
 * records now - publish_ns (CLOCK_MONOTONIC). For `make bench`.
 *
 *   shm_latency NAME SECONDS [--json]
 *
 * It polls without sleeping (a reader that wants the lowest latency would),
 * so it keeps one CPU busy while it runs.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/histo.h"
#include "proto/shm_reader.h"

static uint64_t now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * ENDOSIM_NS_PER_S + (uint64_t)ts.tv_nsec;
}

int main(int argc, char **argv)
{
	static struct histo h;
	struct histo_summary s;
	struct endosim_state st;
	struct shm_reader *r;
	uint64_t last = 0, end;
	bool json;

	if (argc < 3) {
		fprintf(stderr, "usage: shm_latency NAME SECONDS [--json]\n");
		return 2;
	}
	json = argc > 3 && !strcmp(argv[3], "--json");
	r = shm_reader_open(argv[1]);
	if (!r) {
		fprintf(stderr, "shm_latency: %s: %s\n", argv[1], strerror(errno));
		return 1;
	}
	end = now_ns() + (uint64_t)(atof(argv[2]) * ENDOSIM_NS_PER_S);
	while (now_ns() < end) {
		if (shm_reader_read(r, &st, 1) || st.cycle == last) {
			continue;
		}
		uint64_t t = now_ns();

		if (last) {
			histo_add(&h, t > st.publish_ns ? t - st.publish_ns : 0);
		}
		last = st.cycle;
	}
	histo_summarize(&h, &s);
	if (json) {
		printf("{\"count\":%llu,\"p50_us\":%.0f,\"p99_us\":%.0f,"
		       "\"p999_us\":%.0f,\"max_us\":%.1f,\"mean_us\":%.2f}\n",
		       (unsigned long long)s.count, s.p50_us, s.p99_us,
		       s.p999_us, s.max_us, s.mean_us);
	} else {
		printf("shm publish-to-read: %llu samples, p50 %.0f us, p99 %.0f "
		       "us, p99.9 %.0f us, max %.1f us\n",
		       (unsigned long long)s.count, s.p50_us, s.p99_us,
		       s.p999_us, s.max_us);
	}
	shm_reader_close(r);
	return s.count ? 0 : 1;
}
