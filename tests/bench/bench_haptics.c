/*
 * bench_haptics - the cost of one haptic step (kinematics, contact, forces)
 * over the shipped scenario on a case, and how smooth the force is while
 * the tip slides along the wall. For `make bench`.
 *
 *   bench_haptics CASE_FILE SCENARIO [RING_VERTICES STEP_M]
 *
 * The force loop's own parts run as in the daemon, off line
 * (tests/tools/offline.h): the simulated rig (plants and the scripted
 * hand) advances one 1 ms period per step, so every run sees the same
 * motion; only the haptic step is timed (CLOCK_MONOTONIC around
 * scope_update() and haptics_render()).
 * Smoothness: the change of the contact force F_static between two
 * consecutive cycles while the tip touches and slides (moves more than 1
 * mm/s along the wall): p50, p99 and the largest, with force shading on
 * and off.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "anatomy.h"
#include "colon.h"
#include "config.h"
#include "histo.h"
#include "offline.h"
#include "vec3.h"

struct run {
	struct histo step;
	struct histo df;    /* |dF_static| per cycle while sliding, mN */
	double max_df;      /* N per cycle, sliding contact */
	double max_f;       /* N, largest F_static */
	long contact, sliding;
	double seconds;
};

/* p50, p99 (in the histogram's whole-us bins) or the exact max (q = 1). */
static double percentile_ns(const struct histo *h, double q)
{
	struct histo_summary s;

	histo_summarize(h, &s);
	return q < 0.6 ? s.p50_us : q < 0.995 ? s.p99_us : s.max_us;
}

/* Runs SCENARIO_PATH on COLON (consumed) with CFG into R. */
static void simulate(const struct config *cfg, struct colon *colon,
		     const char *scenario_path, struct run *r)
{
	char err[256];
	struct offline *o = offline_create(cfg, colon, scenario_path, err,
					   sizeof(err));
	struct endosim_haptics_state prev = { 0 };
	double len;

	if (!o) {
		fprintf(stderr, "bench_haptics: %s\n", err);
		exit(1);
	}
	len = offline_length_s(o);
	memset(r, 0, sizeof(*r));
	for (long i = 0; i < (long)(len * 1000); i++) {
		const struct endosim_state *st = offline_step(o);
		const struct endosim_haptics_state *out = &st->haptics;

		histo_add(&r->step, st->compute_ns);
		if (out->contact) {
			double df[3], sliding[3], v = st->axis[0].velocity;

			r->contact++;
			r->max_f = fmax(r->max_f, vec3_norm(out->f_static));
			/* the tip's motion along the wall, from the carriage */
			vec3_axpy(sliding, st->scope.dir,
				  -vec3_dot(st->scope.dir, out->normal),
				  out->normal);
			if (prev.contact &&
			    fabs(v) * vec3_norm(sliding) > 0.001) {
				vec3_sub(df, out->f_static, prev.f_static);
				r->max_df = fmax(r->max_df, vec3_norm(df));
				/* the histogram's "us" bins hold mN here */
				histo_add(&r->df, (uint64_t)(vec3_norm(df) * 1e6));
				r->sliding++;
			}
		}
		prev = *out;
	}
	r->seconds = len;
	offline_destroy(o);
}

int main(int argc, char **argv)
{
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct config cfg;
	struct anatomy a;
	struct colon *colon;
	struct run *shaded = calloc(1, sizeof(*shaded));
	struct run *flat = calloc(1, sizeof(*flat));
	char err[256];
	uint32_t triangles;

	if (argc < 3 || !shaded || !flat) {
		fprintf(stderr, "usage: bench_haptics CASE_FILE SCENARIO "
			"[RING_VERTICES STEP_M]\n");
		return 2;
	}
	if (argc > 4) {
		cp.ring_vertices = (uint32_t)atoi(argv[3]);
		cp.step_m = atof(argv[4]);
	}
	config_defaults(&cfg);
	if (anatomy_load(&a, argv[1], err, sizeof(err)) ||
	    !(colon = colon_create(&a, &cp, err, sizeof(err)))) {
		fprintf(stderr, "bench_haptics: %s\n", err);
		return 1;
	}
	triangles = colon_mesh(colon)->triangles;
	simulate(&cfg, colon, argv[2], shaded);
	cfg.haptics.force_shading = 0;
	colon = colon_create(&a, &cp, err, sizeof(err));
	if (!colon) {
		fprintf(stderr, "bench_haptics: %s\n", err);
		return 1;
	}
	simulate(&cfg, colon, argv[2], flat);
	printf("%s, %u triangles: one force-loop cycle (safety, kinematics, "
	       "haptics) p50 %.0f us, p99 %.0f us, max %.1f us over %.0f s "
	       "(%ld cycles in contact)\n", a.name,
	       triangles, percentile_ns(&shaded->step, 0.5),
	       percentile_ns(&shaded->step, 0.99),
	       percentile_ns(&shaded->step, 1), shaded->seconds,
	       shaded->contact);
	printf("  sliding on the wall (%ld cycles): change of F_static per "
	       "cycle p50 %.3f N, p99 %.3f N, max %.2f N with force shading; "
	       "p50 %.3f N, p99 %.3f N, max %.2f N without; largest F_static "
	       "%.1f N\n", shaded->sliding,
	       percentile_ns(&shaded->df, 0.5) / 1e3,
	       percentile_ns(&shaded->df, 0.99) / 1e3, shaded->max_df,
	       percentile_ns(&flat->df, 0.5) / 1e3,
	       percentile_ns(&flat->df, 0.99) / 1e3, flat->max_df,
	       shaded->max_f);
	free(shaded);
	free(flat);
	return 0;
}
