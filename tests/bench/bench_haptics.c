/*
 * bench_haptics - the cost of the force loop's cycle (safety, kinematics,
 * the haptic model) over a scenario on a case, the forces the hand feels
 * over it, and how smooth the tip's contact force is while the tip slides
 * along the wall. For `make bench`.
 *
 *   bench_haptics [--model rod|paper] [--segments N] [--no-shading]
 *                 [--patient] [--ring VERTICES --step M] CASE_FILE SCENARIO
 *
 * --patient: the patient's body around the colon ([patient] enabled:
 * the gas, gravity, the fluid, the lens, the assistant's pad), played as
 * the scenario's valves and commands ask. Then also the patient's
 * response alone, per cycle, over the run's own mechanics: pain_step()
 * (4 mobile spans, 9 segments), and with it vitals_step() and
 * perforation_step() as patient.c's respond() calls them, each call timed
 * on CLOCK_MONOTONIC (the clock's own ~20 ns included): p50, p99 and the
 * largest next to the 5 us the issue allows (issue 23).
 * The inputs each cycle: the wall's Laplace tension per segment, the
 * tip's force F_static, its bend, the tube's insertion and roll speed,
 * as the run published them; each span's mesentery tension, which the
 * state does not publish, from its published displacement bow_m as the
 * normal case's sigmoid holds it (600 N/m, stiffening as
 * 1 + (bow / 6 cm)^2: 2 cm ~13 N, 6 cm ~70 N, pain.h's figures).
 *
 * The force loop's own parts run as in the daemon, off line
 * (tests/tools/offline.h): the simulated rig (plants and the scripted
 * hand) advances one 1 ms period per step, so every run sees the same
 * motion; the cycle's compute time is the loop's own clock around it
 * (compute_ns), as the daemon publishes it.
 * Forces: the insertion force and the roll torque the drives were asked
 * for (after the limits), over every cycle: p50, p95, the peak and the
 * share of the time above 10 N (Appleyard et al. 2000 measured 21
 * colonoscopies: above 10 N about 5 % of the time, peak push 43 N, roll
 * torque within 1 N m).
 * Smoothness: the change of the tip's contact force F_static between two
 * consecutive cycles while the tip touches and slides (moves more than 1
 * mm/s along the wall): p50, p99 and the largest.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "model/anatomy.h"
#include "model/colon.h"
#include "model/pain.h"
#include "model/perforation.h"
#include "model/vitals.h"
#include "conf/config.h"
#include "offline.h"
#include "base/vec3.h"

/* a series of samples, for its percentiles */
struct series {
	double *v;
	long n;
};

/* what the patient's response takes in, one cycle's */
struct respond_in {
	double span_n[ENDOSIM_SPANS];
	double wall_n_per_m[ENDOSIM_SEGMENTS];
	double tip_n;
	double bend_rad;
	double insertion_m_s;
	double roll_rad_s;
};

struct run {
	struct series step_us;   /* the cycle's compute time */
	struct respond_in *in;   /* each cycle's, with --patient */
	struct series df_n;      /* |dF_static| per cycle while sliding */
	struct series push_n;    /* |insertion force| every cycle */
	double roll_peak_nm;
	double max_f;            /* N, largest F_static */
	long contact;
	double seconds;
};

static void add(struct series *s, double v)
{
	s->v[s->n++] = v;
}

static int by_value(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

/* mesentery stiffness and the stretch at which it doubles (the normal
 * case's sigmoid) */
#define BENCH_MESENTERY_N_PER_M 600.0
#define BENCH_MESENTERY_M 0.06

/* What the patient's response takes in from the state ST. */
static void respond_input(const struct endosim_state *st,
			  struct respond_in *in)
{
	const struct endosim_scope_state *sc = &st->scope;

	for (int i = 0; i < ENDOSIM_SPANS; i++) {
		double q = sc->bow_m[i] / BENCH_MESENTERY_M;

		in->span_n[i] = BENCH_MESENTERY_N_PER_M * (1 + q * q) *
				fabs(sc->bow_m[i]);
	}
	memcpy(in->wall_n_per_m, st->patient.tension_n_per_m,
	       sizeof(in->wall_n_per_m));
	in->tip_n = vec3_norm(st->haptics.f_static);
	in->bend_rad = hypot(sc->bend_rad[0], sc->bend_rad[1]);
	in->insertion_m_s = st->axis[ENDOSIM_AXIS_INSERTION].velocity;
	in->roll_rad_s = st->axis[ENDOSIM_AXIS_ROLL].velocity;
}

/* The Q quantile of S (sorted here), nearest rank; 0 when empty. */
static double quantile(struct series *s, double q)
{
	long k;

	if (!s->n) {
		return 0;
	}
	qsort(s->v, (size_t)s->n, sizeof(*s->v), by_value);
	k = (long)ceil(q * (double)s->n) - 1;
	return s->v[k < 0 ? 0 : k >= s->n ? s->n - 1 : k];
}

static double share_above(const struct series *s, double limit)
{
	long over = 0;

	for (long i = 0; i < s->n; i++) {
		over += s->v[i] > limit;
	}
	return s->n ? (double)over / (double)s->n : 0;
}

/* Runs SCENARIO_PATH on COLON (consumed) with CFG into R. */
static void simulate(const struct config *cfg, struct colon *colon,
		     const char *scenario_path, struct run *r)
{
	char err[256];
	struct offline *o = offline_create(cfg, colon, scenario_path, err,
					   sizeof(err));
	struct endosim_haptics_state prev = { 0 };
	long cycles;

	if (!o) {
		fprintf(stderr, "bench_haptics: %s\n", err);
		exit(1);
	}
	r->seconds = offline_length_s(o);
	cycles = (long)(r->seconds * 1000);
	r->step_us.v = calloc((size_t)cycles + 1, sizeof(double));
	r->df_n.v = calloc((size_t)cycles + 1, sizeof(double));
	r->push_n.v = calloc((size_t)cycles + 1, sizeof(double));
	r->in = calloc((size_t)cycles + 1, sizeof(*r->in));
	if (!r->step_us.v || !r->df_n.v || !r->push_n.v || !r->in) {
		fprintf(stderr, "bench_haptics: out of memory\n");
		exit(1);
	}
	for (long i = 0; i < cycles; i++) {
		const struct endosim_state *st = offline_step(o);
		const struct endosim_haptics_state *out = &st->haptics;

		add(&r->step_us, st->compute_ns / 1e3);
		respond_input(st, &r->in[i]);
		add(&r->push_n,
		    fabs(st->axis[ENDOSIM_AXIS_INSERTION].limited));
		r->roll_peak_nm = fmax(r->roll_peak_nm,
				       fabs(st->axis[ENDOSIM_AXIS_ROLL].limited));
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
				add(&r->df_n, vec3_norm(df));
			}
		}
		prev = *out;
	}
	offline_destroy(o);
}

static double now_us(void)
{
	struct timespec t;

	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec * 1e6 + (double)t.tv_nsec / 1e3;
}

/* One cycle of the patient's response on IN; with WHOLE, the vital signs
 * and the tear after the pain, as respond() (patient.c) steps them. */
static void respond_once(struct pain *p, struct vitals *v,
			 struct perforation *perf, const struct respond_in *in,
			 bool whole)
{
	static const int span_segment[ENDOSIM_SPANS] = { 2, 3, 5, 7 };
	static const struct pain_params par = PAIN_PARAMS_DEFAULT;
	static const struct vitals_params vp = VITALS_PARAMS_DEFAULT;
	static const struct perforation_params pp =
		PERFORATION_PARAMS_DEFAULT;
	struct pain_input pi = {
		.spans = ENDOSIM_SPANS, .span_tension_n = in->span_n,
		.span_segment = span_segment, .segments = ENDOSIM_SEGMENTS,
		.wall_n_per_m = in->wall_n_per_m, .tip_force_n = in->tip_n,
		.tip_segment = 2, .insertion_m_s = in->insertion_m_s,
		.roll_rad_s = in->roll_rad_s,
	};
	double dt_s = OFFLINE_PERIOD_NS / 1e9;

	pain_step(p, &par, &pi, dt_s);
	if (whole) {
		vitals_step(v, &vp, p->level, par.sedation, dt_s);
		perforation_step(perf, &pp, in->tip_n, in->bend_rad, 2, dt_s);
	}
}

/* Times the patient's response over the run's N cycles of inputs IN. */
static void time_response(const struct respond_in *in, long n, bool whole)
{
	static const struct vitals_params vp = VITALS_PARAMS_DEFAULT;
	struct series us = { calloc((size_t)n + 1, sizeof(double)), 0 };
	struct pain p;
	struct vitals v;
	struct perforation perf;
	double peak = 0;

	if (!us.v) {
		fprintf(stderr, "bench_haptics: out of memory\n");
		exit(1);
	}
	memset(us.v, 0, ((size_t)n + 1) * sizeof(double)); /* prefaulted */
	pain_reset(&p);
	vitals_reset(&v, &vp, PAIN_DEFAULT_SEDATION);
	perforation_reset(&perf);
	for (long i = 0; i < n; i++) {
		double t0 = now_us();

		respond_once(&p, &v, &perf, &in[i], whole);
		add(&us, now_us() - t0);
		peak = fmax(peak, p.level);
	}
	printf("  %s per cycle: p50 %.3f us, p99 %.3f us, max %.2f us over "
	       "%ld cycles (limit: p99 <= 5 us); peak pain %.1f\n",
	       whole ? "the response (pain, vitals, tear)" : "pain_step()",
	       quantile(&us, 0.5), quantile(&us, 0.99), quantile(&us, 1), n,
	       peak);
	free(us.v);
}

static void usage(void)
{
	fprintf(stderr, "usage: bench_haptics [--model rod|paper] "
		"[--segments N] [--no-shading] [--patient] "
		"[--ring VERTICES --step M] CASE_FILE SCENARIO\n");
	exit(2);
}

int main(int argc, char **argv)
{
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct config cfg;
	struct anatomy a;
	struct colon *colon;
	struct run r;
	char err[256];
	int i;

	config_defaults(&cfg);
	for (i = 1; i < argc && !strncmp(argv[i], "--", 2); i++) {
		const char *opt = argv[i];

		if (!strcmp(opt, "--no-shading")) {
			cfg.haptics.force_shading = 0;
			continue;
		}
		if (!strcmp(opt, "--patient")) {
			cfg.patient.enabled = 1;
			continue;
		}
		if (++i >= argc) {
			usage();
		}
		if (!strcmp(opt, "--model") && !strcmp(argv[i], "rod")) {
			cfg.haptics.model = HAPTICS_MODEL_ROD;
		} else if (!strcmp(opt, "--model") &&
			   !strcmp(argv[i], "paper")) {
			cfg.haptics.model = HAPTICS_MODEL_PAPER;
		} else if (!strcmp(opt, "--segments")) {
			cfg.rod.segments = atoi(argv[i]);
		} else if (!strcmp(opt, "--ring")) {
			cp.ring_vertices = (uint32_t)atoi(argv[i]);
		} else if (!strcmp(opt, "--step")) {
			cp.step_m = atof(argv[i]);
		} else {
			usage();
		}
	}
	if (argc - i != 2) {
		usage();
	}
	if (anatomy_load(&a, argv[i], err, sizeof(err)) ||
	    !(colon = colon_create(&a, &cp, err, sizeof(err)))) {
		fprintf(stderr, "bench_haptics: %s\n", err);
		return 1;
	}
	printf("%s, %u triangles, %s model", a.name,
	       colon_mesh(colon)->triangles,
	       cfg.haptics.model == HAPTICS_MODEL_ROD ? "rod" : "paper");
	if (cfg.haptics.model == HAPTICS_MODEL_ROD) {
		printf(" (%d segments)", cfg.rod.segments);
	}
	printf(", force shading %s%s:\n",
	       cfg.haptics.force_shading ? "on" : "off",
	       cfg.patient.enabled ? ", the patient's body" : "");
	memset(&r, 0, sizeof(r));
	simulate(&cfg, colon, argv[i + 1], &r);
	printf("  one force-loop cycle (safety, kinematics, haptics): p50 "
	       "%.0f us, p99 %.0f us, max %.0f us over %.0f s\n",
	       quantile(&r.step_us, 0.5), quantile(&r.step_us, 0.99),
	       quantile(&r.step_us, 1), r.seconds);
	printf("  insertion force: p50 %.1f N, p95 %.1f N, peak %.1f N, "
	       "above 10 N %.1f %% of the time; roll torque peak %.2f N m "
	       "(Appleyard 2000: above 10 N ~5 %%, peak push 43 N, torque "
	       "<= 1 N m)\n",
	       quantile(&r.push_n, 0.5), quantile(&r.push_n, 0.95),
	       quantile(&r.push_n, 1), 100 * share_above(&r.push_n, 10),
	       r.roll_peak_nm);
	printf("  the tip sliding on the wall (%ld of %ld cycles in contact): "
	       "change of F_static per cycle p50 %.3f N, p99 %.3f N, max "
	       "%.2f N; largest F_static %.1f N\n", r.df_n.n, r.contact,
	       quantile(&r.df_n, 0.5), quantile(&r.df_n, 0.99),
	       quantile(&r.df_n, 1), r.max_f);
	if (cfg.patient.enabled) {
		time_response(r.in, r.step_us.n, false);
		time_response(r.in, r.step_us.n, true);
	}
	free(r.in);
	free(r.step_us.v);
	free(r.df_n.v);
	free(r.push_n.v);
	return 0;
}
