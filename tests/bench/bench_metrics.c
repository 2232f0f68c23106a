/*
 * bench_metrics.c - what the training metrics cost, the occlusion-aware
 * coverage above all (metrics.h, depthmap.h).
 *
 *   build/tests/bench_metrics [CASE_FILE]     (default config/cases/normal.case)
 *
 * The case at the default resolution (as endosimd builds it), and a
 * 10-minute session at 1 kHz played into the metrics as the recorder
 * thread plays a live one: the tip on the centreline, inserted to the
 * cecum in 4 minutes looking about the lumen (the view swaying 20 deg),
 * 10 s at the cecum, withdrawn in the rest looking around the wall (the
 * view 35 deg off the lumen, circling every 3 s). Timed: each period of
 * the view's evaluation (1 / view_rate_hz: one evaluated pose and the
 * records between), p50 / p99 / max; the whole replay (what a report of
 * such a session spends on its metrics, once per pass over the records)
 * and its share of a CPU live. At 10 Hz (the default) and 20 Hz.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "model/colon.h"
#include "session/depthmap.h"
#include "base/histo.h"
#include "session/metrics.h"
#include "base/mono.h"
#include "base/vec3.h"

#define RATE_HZ 1000
#define SESSION_S 600.0
#define INSERT_S 240.0
#define HOLD_S 10.0

/* Record K of the session: where the tip is and where it looks. */
static void pose(const struct centreline *cl, double s_in, double s_out,
		 uint64_t k, struct session_record *r)
{
	double t = (double)k / RATE_HZ, s, d[3], axis[3];
	struct centreline_point q;

	if (t < INSERT_S) {
		s = s_out + (s_in - s_out) * t / INSERT_S;
	} else if (t < INSERT_S + HOLD_S) {
		s = s_in;
	} else {
		s = s_in - (s_in - s_out) * (t - INSERT_S - HOLD_S) /
			       (SESSION_S - INSERT_S - HOLD_S);
	}
	centreline_at_s(cl, s, &q);
	if (t < INSERT_S + HOLD_S) {
		vec3_rotate(d, q.t, q.u, 20 * M_PI / 180 * sin(t));
	} else {
		double phi = 2 * M_PI * t / 3;

		vec3_scale(axis, q.u, cos(phi));
		vec3_axpy(axis, axis, sin(phi), q.v);
		vec3_rotate(d, q.t, axis, 35 * M_PI / 180);
	}
	*r = (struct session_record){
		.cycle = k,
		.stamp_ns = ENDOSIM_NS_PER_S + k * (ENDOSIM_NS_PER_S / RATE_HZ),
		.state = 1,
		.depth_m = (float)s,
		.tip_s_m = (float)s,
	};
	for (int j = 0; j < 3; j++) {
		r->tip[j] = (float)q.p[j];
		r->dir[j] = (float)d[j];
		r->up[j] = (float)q.u[j];
	}
}

static int run(const struct colon *c, double view_rate_hz)
{
	size_t n = (size_t)(SESSION_S * RATE_HZ);
	size_t per = (size_t)lround(RATE_HZ / view_rate_hz);
	const struct centreline *cl = colon_centreline(c);
	static struct histo period; /* 1 us bins */
	struct histo_summary h;
	struct metrics_params p;
	struct metrics_result res;
	struct metrics *m;
	uint64_t total = 0, in_period = 0;

	metrics_params_default(&p);
	p.view_rate_hz = view_rate_hz;
	m = metrics_create(c, &p);
	if (!m) {
		fprintf(stderr, "bench_metrics: out of memory\n");
		return 1;
	}
	histo_reset(&period);
	for (size_t k = 0; k < n; k++) {
		struct session_record r;
		uint64_t a;

		pose(cl, colon_cecum_s(c) + 0.02, 0.05, k, &r);
		a = mono_ns();
		metrics_record(m, &r);
		a = mono_ns() - a;
		total += a;
		in_period += a;
		if ((k + 1) % per == 0) {
			histo_add(&period, in_period);
			in_period = 0;
		}
	}
	metrics_result(m, &res);
	histo_summarize(&period, &h);
	printf("view evaluated at %.0f Hz: %.0f s of session at 1 kHz in %.2f s"
	       " (%.1f ms of CPU a second of session, %.2f %% of a CPU live); "
	       "mucosa seen %.1f %%\n",
	       view_rate_hz, SESSION_S, (double)total / ENDOSIM_NS_PER_S,
	       (double)total / ENDOSIM_NS_PER_MS / SESSION_S,
	       (double)total / ENDOSIM_NS_PER_S / SESSION_S * 100,
	       res.mucosa_seen * 100);
	printf("  an evaluation and the records to the next (%llu): p50 %.0f us,"
	       " p99 %.0f us, p99.9 %.0f us, max %.0f us, mean %.0f us\n",
	       (unsigned long long)h.count, h.p50_us, h.p99_us, h.p999_us,
	       h.max_us, h.mean_us);
	metrics_destroy(m);
	return 0;
}

int main(int argc, char **argv)
{
	const char *path = argc > 1 ? argv[1] : "config/cases/normal.case";
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct anatomy a;
	struct colon *c;
	char err[256];
	int r;

	if (anatomy_load(&a, path, err, sizeof(err)) ||
	    !(c = colon_create(&a, &cp, err, sizeof(err)))) {
		fprintf(stderr, "bench_metrics: %s\n", err);
		return 1;
	}
	printf("%s at the default resolution: %u vertices, %u triangles; "
	       "the depth buffer %d x %d\n", path, colon_mesh(c)->vertices,
	       colon_mesh(c)->triangles, DEPTHMAP_N, DEPTHMAP_N);
	r = run(c, 10) || run(c, 20);
	colon_destroy(c);
	return r;
}
