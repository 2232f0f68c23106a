/*
 * histo.h - a lock-free histogram of durations in 1 us bins, as cyclictest
 * keeps them: one writer (the force loop) adds samples without atomics
 * read-modify-write; any thread may summarise it at any time (the summary of
 * a histogram being written is off by the few samples in flight).
 */
#ifndef ENDOSIM_HISTO_H
#define ENDOSIM_HISTO_H

#include <stdatomic.h>
#include <stdint.h>

#define HISTO_BINS 10000 /* 0..9999 us; longer samples land in the last bin */

struct histo {
	_Atomic uint32_t bins[HISTO_BINS];
	_Atomic uint64_t count;
	_Atomic uint64_t sum_ns;
	_Atomic uint64_t max_ns;
};

struct histo_summary {
	double p50_us, p99_us, p999_us; /* bin (whole us) holding the quantile */
	double max_us, mean_us;         /* exact */
	uint64_t count;
};

/* Zeroes H; only the writer may (a reader meanwhile sees a partial sum). */
void histo_reset(struct histo *h);

/* The single writer: one sample of NS nanoseconds. Never blocks. */
void histo_add(struct histo *h, uint64_t ns);

/* Any thread: percentiles, mean and maximum. */
void histo_summarize(const struct histo *h, struct histo_summary *s);

#endif
