/* timing.c - see timing.h. */
#include "viewer/timing.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct timing {
	double *ms[TIMING_KINDS];
	size_t next[TIMING_KINDS], count[TIMING_KINDS];
	double fps;
};

struct timing *timing_create(void)
{
	struct timing *t = calloc(1, sizeof(*t));

	for (int k = 0; t && k < TIMING_KINDS; k++) {
		t->ms[k] = calloc(TIMING_SAMPLES, sizeof(double));
		if (!t->ms[k]) {
			timing_destroy(t);
			return NULL;
		}
	}
	return t;
}

void timing_destroy(struct timing *t)
{
	if (!t) {
		return;
	}
	for (int k = 0; k < TIMING_KINDS; k++) {
		free(t->ms[k]);
	}
	free(t);
}

void timing_add(struct timing *t, enum timing_kind k, double ms)
{
	t->ms[k][t->next[k]] = ms;
	t->next[k] = (t->next[k] + 1) % TIMING_SAMPLES;
	t->count[k] += t->count[k] < TIMING_SAMPLES;
	if (k == TIMING_FRAME && ms > 0) {
		/* a one-second exponential average of the rate */
		double a = fmin(1, ms / 1000);

		t->fps = t->fps ? (1 - a) * t->fps + a * 1000 / ms : 1000 / ms;
	}
}

size_t timing_count(const struct timing *t, enum timing_kind k)
{
	return t->count[k];
}

static int ascending(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

double timing_quantile(const struct timing *t, enum timing_kind k, double q)
{
	size_t n = t->count[k], rank;
	double *sorted, v;

	if (!n) {
		return 0;
	}
	sorted = malloc(n * sizeof(*sorted));
	if (!sorted) {
		return NAN;
	}
	memcpy(sorted, t->ms[k], n * sizeof(*sorted));
	qsort(sorted, n, sizeof(*sorted), ascending);
	rank = (size_t)ceil(q * (double)n);
	v = sorted[rank ? rank - 1 : 0];
	free(sorted);
	return v;
}

double timing_fps(const struct timing *t)
{
	return t->fps;
}
