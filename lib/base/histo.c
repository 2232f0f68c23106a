/* histo.c - see histo.h. */
#include "base/histo.h"

#include <string.h>

#define LOAD(x) atomic_load_explicit(&(x), memory_order_relaxed)
#define STORE(x, v) atomic_store_explicit(&(x), (v), memory_order_relaxed)

void histo_reset(struct histo *h)
{
	memset(h, 0, sizeof(*h));
}

void histo_add(struct histo *h, uint64_t ns)
{
	uint64_t us = ns / 1000;
	unsigned int bin = us < HISTO_BINS ? (unsigned int)us : HISTO_BINS - 1;

	STORE(h->bins[bin], LOAD(h->bins[bin]) + 1);
	STORE(h->sum_ns, LOAD(h->sum_ns) + ns);
	if (ns > LOAD(h->max_ns)) {
		STORE(h->max_ns, ns);
	}
	/* count last: a reader never sees more samples counted than binned */
	atomic_store_explicit(&h->count, LOAD(h->count) + 1,
			      memory_order_release);
}

/* The first bin at which the cumulative count reaches Q of TOTAL. */
static double quantile(const struct histo *h, uint64_t total, double q)
{
	uint64_t need = (uint64_t)((double)total * q + 0.5);
	uint64_t seen = 0;

	if (need == 0) {
		need = 1;
	}
	for (unsigned int i = 0; i < HISTO_BINS; i++) {
		seen += LOAD(h->bins[i]);
		if (seen >= need) {
			return (double)i;
		}
	}
	return HISTO_BINS - 1;
}

void histo_summarize(const struct histo *h, struct histo_summary *s)
{
	uint64_t total = atomic_load_explicit(&h->count, memory_order_acquire);

	memset(s, 0, sizeof(*s));
	s->count = total;
	if (!total) {
		return;
	}
	s->p50_us = quantile(h, total, 0.50);
	s->p99_us = quantile(h, total, 0.99);
	s->p999_us = quantile(h, total, 0.999);
	s->max_us = (double)LOAD(h->max_ns) / 1000.0;
	s->mean_us = (double)LOAD(h->sum_ns) / (double)total / 1000.0;
}
