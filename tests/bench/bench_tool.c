/*
 * bench_tool - what the tools' model (tool.h) costs the force loop per
 * cycle, next to the 10 us issue 25 allows at p99. For `make bench`.
 *
 *   bench_tool [SECONDS] CASE_FILE
 *
 * Each tool_step() call timed on CLOCK_MONOTONIC (the clock's own ~20 ns
 * included), as bench_haptics times the patient's response: p50, p99 and
 * the largest over SECONDS (60) of 1 kHz cycles, twice:
 *  - the case's polyps placed on its colon's wall (tool_place_polyps()),
 *    a 20 mm snare 2 cm out, its handle opened and closed every 2 s with
 *    the pedal down while it closes, on a tip withdrawn along the
 *    centreline from the cecum to the rectum and back (dir its tangent,
 *    up its frame's u);
 *  - the most a step does: ANATOMY_MAX_POLYPS stalks, every axis
 *    crossing the loop's plane inside it, the handle cycling as above on
 *    a still tip, the polyps put back in place at each opening, so that
 *    every step computes every crossing and captures, cuts and injures
 *    as they come, every one bleeding from the start of each cycle and
 *    the suction valve held (each step sheds every point's blood and
 *    looks for a cut one to retrieve), and gravity turning all the
 *    while (1 rad/s about the body's long axis: each step seeks a cut
 *    polyp's rest again and moves every cut one towards its own), the
 *    gas opening and collapsing the lumen (every segment's radius
 *    factor 0.8 +- 0.2 at 1 rad/s: a polyp lying is carried with the
 *    wall each step).
 * tool_follow_wall() comes before each tool_step() and tool_fall() after
 * it, timed with it (the case's polyps: gravity still, lying on the left
 * side, the gas's factors 0.8; the stalks, placed by hand in the loop,
 * are not on the wall: the wall moves the case's five only).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/vec3.h"
#include "model/anatomy.h"
#include "model/centreline.h"
#include "model/colon.h"
#include "model/gas.h"
#include "model/tool.h"

#define DT 0.001
#define CYCLE_S 2.0   /* the handle opened and closed */
#define SNARE_M 0.020

struct series {
	double *v;
	long n;
};

static double now_us(void)
{
	struct timespec t;

	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec * 1e6 + (double)t.tv_nsec / 1e3;
}

static int by_value(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

/* The Q quantile of S (sorted here), nearest rank. */
static double quantile(struct series *s, double q)
{
	long k = (long)ceil(q * (double)s->n) - 1;

	qsort(s->v, (size_t)s->n, sizeof(double), by_value);
	return s->v[k < 0 ? 0 : k];
}

/* The handle at time T_S: open for the first half of each cycle, closing
 * over the second, the pedal down while it closes. */
static void handle_at(double t_s, struct tool_input *in)
{
	double x = fmod(t_s, CYCLE_S) / CYCLE_S;

	in->opening = x < 0.5 ? 1 : 1 - 2 * (x - 0.5);
	in->pedal = x >= 0.5;
}

/* The tip at time T_S withdrawn along CL between 0.3 m and its end. */
static void tip_at(const struct centreline *cl, double t_s, double span_s,
		   struct endosim_scope_state *sc)
{
	double len = centreline_length(cl), x = fmod(t_s, span_s) / span_s;
	struct centreline_point q;

	x = x < 0.5 ? 2 * x : 2 - 2 * x;
	centreline_at_s(cl, 0.3 + x * (len - 0.35), &q);
	vec3_copy(sc->tip, q.p);
	vec3_copy(sc->dir, q.t);
	vec3_copy(sc->up, q.u);
}

/* ANATOMY_MAX_POLYPS stalks under the open loop of T, crossing its plane
 * inside it, around its centre. */
static void stalks(struct tool *t)
{
	const struct tool_pose *po = &t->pose;
	struct anatomy_polyp ap = {
		.diameter_m = 0.012, .paris = ANATOMY_PARIS_IP,
		.stalk_length_m = 0.008, .stalk_diameter_m = 0.003,
	};
	double n[3];

	vec3_scale(n, po->radial, -1);
	for (int i = 0; i < ANATOMY_MAX_POLYPS; i++) {
		double a = 2 * M_PI * i / ANATOMY_MAX_POLYPS, base[3];
		double r = 0.002 + 0.006 * (i % 4) / 3;

		vec3_axpy(base, t->loop_centre, r * cos(a), po->dir);
		vec3_axpy(base, base, r * sin(a), po->side);
		vec3_axpy(base, base, 0.004, po->radial);
		tool_add_polyp(t, &ap, base, n);
	}
}

/* Times N cycles of T on colon C; WORST: the still tip, the stalks put
 * back, gravity turning. */
static void run(struct tool *t, const struct colon *c, long n, bool worst,
		const char *what)
{
	const struct centreline *cl = colon_centreline(c);
	static const struct tool_params par = TOOL_PARAMS_DEFAULT;
	struct series us = { calloc((size_t)n, sizeof(double)), 0 };
	struct endosim_scope_state sc;
	struct tool_input in = { .depth_m = 0.02, .opening = 1,
				 .suction = worst };
	double g[3] = { 9.81, 0, 0 }, factor[GAS_SEGMENTS];
	long events = 0;

	if (!us.v) {
		fprintf(stderr, "bench_tool: out of memory\n");
		exit(1);
	}
	memset(us.v, 0, (size_t)n * sizeof(double)); /* prefaulted */
	memset(&sc, 0, sizeof(sc));
	tip_at(cl, 0, 1, &sc);
	for (long k = 0; k < n; k++) {
		double t0, t_s = (double)k * DT;

		handle_at(t_s, &in);
		if (!worst) {
			tip_at(cl, t_s, 40, &sc);
		} else if (k % lround(CYCLE_S / DT) == 0) {
			for (int i = 0; i < t->polyps; i++) {
				t->polyp[i].state = TOOL_POLYP_IN_PLACE;
				t->polyp[i].energy_j = 0;
				t->polyp[i].bleed = TOOL_BLEED_BLEEDING;
				t->polyp[i].bleed_m3_s = 2e-8;
				t->polyp[i].bleed_s = 0;
			}
		}
		for (int i = 0; i < GAS_SEGMENTS; i++) {
			factor[i] = 0.8 + (worst ? 0.2 * sin(t_s) : 0);
		}
		if (worst) {
			vec3_set(g, 9.81 * cos(t_s), 9.81 * sin(t_s), 0);
		}
		t0 = now_us();
		tool_follow_wall(t, c, factor);
		events += tool_step(t, &par, &sc, &in, DT, NULL) != 0;
		tool_fall(t, &par, c, g, factor, DT);
		us.v[us.n++] = now_us() - t0;
	}
	printf("  %s: tool_follow_wall(), tool_step() and tool_fall() per "
	       "cycle p50 %.3f us, "
	       "p99 %.3f us, max "
	       "%.2f us over %ld cycles, %ld with events (limit: p99 <= 10 "
	       "us)\n", what, quantile(&us, 0.5), quantile(&us, 0.99),
	       quantile(&us, 1), n, events);
	free(us.v);
}

int main(int argc, char **argv)
{
	static const struct tool_params par = TOOL_PARAMS_DEFAULT;
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct endosim_scope_state sc;
	struct tool_input in = { .depth_m = 0.02, .opening = 1 };
	double seconds = argc == 3 ? atof(argv[1]) : 60;
	struct colon *colon;
	struct anatomy a;
	struct tool t;
	char err[256], what[64];
	long n;

	if (argc < 2 || argc > 3 || !(seconds > 0)) {
		fprintf(stderr, "usage: bench_tool [SECONDS] CASE_FILE\n");
		return 2;
	}
	if (anatomy_load(&a, argv[argc - 1], err, sizeof(err)) ||
	    !(colon = colon_create(&a, &cp, err, sizeof(err)))) {
		fprintf(stderr, "bench_tool: %s\n", err);
		return 1;
	}
	n = lround(seconds / DT);
	printf("the tools' model (a %.0f mm snare, 1 kHz, %.0f s):\n",
	       SNARE_M * 1e3, seconds);
	tool_reset(&t);
	tool_select(&t, TOOL_SNARE, SNARE_M);
	tool_place_polyps(&t, colon);
	run(&t, colon, n, false, "the case's polyps");
	tool_reset(&t);
	tool_select(&t, TOOL_SNARE, SNARE_M);
	memset(&sc, 0, sizeof(sc));
	tip_at(colon_centreline(colon), 0, 1, &sc);
	tool_step(&t, &par, &sc, &in, DT, NULL);
	stalks(&t);
	snprintf(what, sizeof(what), "%d stalks in the loop", t.polyps);
	run(&t, colon, n, true, what);
	colon_destroy(colon);
	return 0;
}
