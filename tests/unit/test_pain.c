/*
 * test_pain.c - the pain model (pain.h) against its definitions:
 *  - each term alone: a held loop of known stretch (the sigmoid pushed
 *    evenly on its mesentery until at rest: its tension is the pushes'
 *    sum), a known transmural pressure in a known lumen (Laplace's p r), a
 *    known tip force each give gain (x - threshold), within 2 %;
 *  - the level's rise and fade follow the first-order response's curves
 *    S (1 - exp(-t / rise_s)) and S exp(-t / fade_s) within 2 %, at any
 *    step;
 *  - sedation scales gains and thresholds by its documented factors;
 *  - the cause and the place: stretch while pushing is looping, while
 *    withdrawing or turning straightening; distension over-insufflation;
 *    the tip's pressure the tip; each in its segment;
 *  - non-finite inputs count as none.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "model/anatomy.h"
#include "model/centreline.h"
#include "model/colon.h"
#include "model/flex.h"
#include "model/gas.h"
#include "model/pain.h"
#include "plain_anatomy.h"
#include "proto/names.h"

#define DT 0.001
#define NONE_SEDATED(par) ((par).sedation = ENDOSIM_SEDATION_NONE)

static int near(double got, double want, double rel)
{
	return fabs(got - want) <= rel * fabs(want);
}

/* The stimulus of one step with IN under PAR, from rest. */
static struct pain one_step(const struct pain_params *par,
			    const struct pain_input *in)
{
	struct pain p;

	pain_reset(&p);
	pain_step(&p, par, in, DT);
	return p;
}

/* The sigmoid of a straight colon (0.16..0.53 m), on a mesentery of 600
 * N/m, 6 cm high, pushed with F newtons on each node until at rest: its
 * tension. */
static double held_loop_tension(double force_n, int *nodes)
{
	const struct flex_params fp = { .node_spacing_m = 0.02,
					.damping_n_s_per_m = 2 };
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct anatomy a;
	struct colon *c;
	struct flex *f;
	char err[256];
	double s0, s1, push[3] = { 0, force_n, 0 }, tension;

	plain_anatomy(&a, 0.05);
	plain_mobile_sigmoid(&a, 600, 0.06);
	cp.ring_vertices = 32;
	c = colon_create(&a, &cp, err, sizeof(err));
	assert_non_null(c);
	f = flex_create(&fp);
	assert_non_null(f);
	flex_attach(f, c);
	*nodes = flex_span_nodes(f, 0);
	centreline_span_range(colon_centreline(c), 0, &s0, &s1);
	for (int k = 0; k < 3000; k++) {
		flex_clear(f);
		for (int i = 0; i < *nodes; i++) {
			flex_push(f, s0 + (s1 - s0) * (i + 1) / (*nodes + 1),
				  push, 0);
		}
		flex_step(f, DT);
	}
	print_message("the sigmoid pushed %.1f N a node: %.2f cm off its "
		      "course\n", force_n, flex_span_displacement(f, 0) * 100);
	tension = flex_span_tension(f, 0);
	flex_destroy(f);
	colon_destroy(c);
	return tension;
}

static void test_stretch(void **unused)
{
	struct pain_params par = PAIN_PARAMS_DEFAULT;
	int seg = 2, nodes;

	(void)unused;
	NONE_SEDATED(par);
	for (double fn = 1; fn <= 3; fn += 1) {
		double t = held_loop_tension(fn, &nodes);
		double want = par.stretch_gain_per_n *
			      (nodes * fn - par.stretch_threshold_n);
		struct pain_input in = { .spans = 1, .span_tension_n = &t,
					 .span_segment = &seg };
		struct pain p = one_step(&par, &in);

		print_message("stretch: %d nodes at %.1f N hold %.1f N: pain "
			      "%.2f (documented %.2f)\n", nodes, fn, t,
			      p.stimulus, want);
		assert_true(want > 0);
		assert_true(near(p.stimulus, want, 0.02));
		assert_true(near(p.stretch, p.stimulus, 1e-12));
		assert_int_equal(p.cause, ENDOSIM_PAIN_LOOPING);
		assert_int_equal(p.place, seg);
	}
	/* below the threshold: nothing */
	{
		double t = 0.9 * par.stretch_threshold_n;
		struct pain_input in = { .spans = 1, .span_tension_n = &t,
					 .span_segment = &seg };
		struct pain p = one_step(&par, &in);

		assert_true(p.stimulus == 0 && p.level == 0);
		assert_int_equal(p.cause, ENDOSIM_PAIN_NONE);
		assert_int_equal(p.place, -1);
	}
}

static void test_distension(void **unused)
{
	struct pain_params par = PAIN_PARAMS_DEFAULT;
	const double mmhg = GAS_PA_PER_MMHG;
	/* 60 mmHg in a 3.5 cm lumen (the cecum), 20 in the sigmoid */
	double wall[3] = { 20 * mmhg * 0.0225, 60 * mmhg * 0.035, 0 };
	struct pain_input in = { .segments = 3, .wall_n_per_m = wall };
	struct pain p;
	double want;

	(void)unused;
	NONE_SEDATED(par);
	p = one_step(&par, &in);
	want = par.wall_gain_per_n_per_m *
	       (60 * mmhg * 0.035 - par.wall_threshold_n_per_m);
	print_message("distension: 60 mmHg in a 3.5 cm lumen, %.0f N/m: pain "
		      "%.2f (documented %.2f)\n", wall[1], p.stimulus, want);
	assert_true(near(p.stimulus, want, 0.02));
	assert_true(near(p.distension, p.stimulus, 1e-12));
	assert_int_equal(p.cause, ENDOSIM_PAIN_INSUFFLATION);
	assert_int_equal(p.place, 1);
	/* 30 mmHg in a 3 cm lumen is the threshold itself */
	wall[1] = 30 * mmhg * 0.03 * 0.99;
	assert_true(one_step(&par, &in).stimulus == 0);
}

static void test_tip(void **unused)
{
	struct pain_params par = PAIN_PARAMS_DEFAULT;
	struct pain_input in = { .tip_force_n = 14.1, .tip_segment = 4 };
	struct pain p;
	double want;

	(void)unused;
	NONE_SEDATED(par);
	p = one_step(&par, &in);
	want = par.tip_gain_per_n * (14.1 - par.tip_threshold_n);
	print_message("tip: 14.1 N on the wall: pain %.2f (documented %.2f)\n",
		      p.stimulus, want);
	assert_true(near(p.stimulus, want, 0.02));
	assert_int_equal(p.cause, ENDOSIM_PAIN_TIP);
	assert_int_equal(p.place, 4);
	/* the scale ends at 10 */
	in.tip_force_n = 100;
	assert_true(one_step(&par, &in).stimulus == PAIN_MAX);
}

/* The level after T_S of stimulus held, from LEVEL0, in steps of DT_S. */
static double after(const struct pain_params *par, double tip_n, double t_s,
		    double dt_s, double level0)
{
	struct pain_input in = { .tip_force_n = tip_n, .tip_segment = 0 };
	struct pain p;

	pain_reset(&p);
	p.level = level0;
	for (long k = 0; k < lround(t_s / dt_s); k++) {
		pain_step(&p, par, &in, dt_s);
	}
	return p.level;
}

static void test_rise_and_fade(void **unused)
{
	struct pain_params par = PAIN_PARAMS_DEFAULT;
	const double dts[] = { 0.001, 0.002, 0.01 };
	double s;

	(void)unused;
	NONE_SEDATED(par);
	s = par.tip_gain_per_n * (12 - par.tip_threshold_n);
	for (int i = 0; i < 3; i++) {
		for (double t = 0.1; t <= 1.0; t += 0.3) {
			double rise = after(&par, 12, t, dts[i], 0);
			double want = s * (1 - exp(-t / par.rise_s));

			assert_true(near(rise, want, 0.02));
		}
		for (double t = 1; t <= 10; t += 3) {
			double fade = after(&par, 0, t, dts[i], s);
			double want = s * exp(-t / par.fade_s);

			assert_true(near(fade, want, 0.02));
		}
	}
	print_message("rise: %.2f of %.2f after %.1f s (%.2f analytic); fade: "
		      "%.2f after %.0f s (%.2f)\n", after(&par, 12, 0.3, DT, 0),
		      s, par.rise_s, s * (1 - exp(-1.0)),
		      after(&par, 0, 5, DT, s), par.fade_s, s * exp(-1.0));
}

static void test_sedation(void **unused)
{
	const double want_gain[] = { 1, 0.9, 0.75, 0.3 };
	const double want_thr[] = { 1, 1.05, 1.15, 2 };
	double last = INFINITY;

	(void)unused;
	for (int s = 0; s < ENDOSIM_SEDATIONS; s++) {
		struct pain_params par = PAIN_PARAMS_DEFAULT;
		struct pain_input in = { .tip_force_n = 12 };
		double g, t, want;
		struct pain p;

		par.sedation = s;
		pain_sedation_factors(s, &g, &t);
		assert_true(g == want_gain[s] && t == want_thr[s]);
		p = one_step(&par, &in);
		want = g * par.tip_gain_per_n * (12 - t * par.tip_threshold_n);
		print_message("sedation %-8s: 12 N on the wall, pain %.2f\n",
			      names_sedation((uint32_t)s), p.stimulus);
		assert_true(near(p.stimulus, want, 1e-12));
		assert_true(p.stimulus < last); /* the deeper, the less */
		last = p.stimulus;
	}
	{
		const struct pain_params d = PAIN_PARAMS_DEFAULT;

		assert_int_equal(d.sedation, ENDOSIM_SEDATION_MODERATE);
	}
}

static void test_causes(void **unused)
{
	struct pain_params par = PAIN_PARAMS_DEFAULT;
	double t[2] = { 12, 30 }, wall = 150;
	int segs[2] = { 2, 5 };
	struct pain_input in = { .spans = 2, .span_tension_n = t,
				 .span_segment = segs, .segments = 1,
				 .wall_n_per_m = &wall, .tip_force_n = 5,
				 .tip_segment = 3 };
	struct pain p;

	(void)unused;
	NONE_SEDATED(par);
	in.insertion_m_s = 0.02;
	p = one_step(&par, &in);
	assert_int_equal(p.cause, ENDOSIM_PAIN_LOOPING);
	assert_int_equal(p.place, 5); /* the transverse: the larger */
	assert_true(near(p.stimulus, p.stretch + p.distension + p.tip, 1e-12));
	in.insertion_m_s = 0; /* held still against the loop */
	assert_int_equal(one_step(&par, &in).cause, ENDOSIM_PAIN_LOOPING);
	in.insertion_m_s = -0.02;
	assert_int_equal(one_step(&par, &in).cause, ENDOSIM_PAIN_STRAIGHTENING);
	in.insertion_m_s = 0;
	in.roll_rad_s = -1;
	assert_int_equal(one_step(&par, &in).cause, ENDOSIM_PAIN_STRAIGHTENING);
	wall = 500;
	p = one_step(&par, &in);
	assert_int_equal(p.cause, ENDOSIM_PAIN_INSUFFLATION);
	assert_int_equal(p.place, 0);
	in.tip_force_n = 40;
	p = one_step(&par, &in);
	assert_int_equal(p.cause, ENDOSIM_PAIN_TIP);
	assert_int_equal(p.place, 3);
	assert_string_equal(names_pain_cause((uint32_t)p.cause), "tip");
	assert_string_equal(names_pain_cause(ENDOSIM_PAIN_CAUSES), "?");
}

static void test_not_finite(void **unused)
{
	const struct pain_params par = PAIN_PARAMS_DEFAULT;
	double t = NAN, wall = INFINITY;
	int seg = 2;
	struct pain_input in = { .spans = 1, .span_tension_n = &t,
				 .span_segment = &seg, .segments = 1,
				 .wall_n_per_m = &wall, .tip_force_n = NAN };
	struct pain p = one_step(&par, &in);

	(void)unused;
	assert_true(p.stimulus == 0 && p.level == 0);
	assert_int_equal(p.cause, ENDOSIM_PAIN_NONE);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_stretch),
		cmocka_unit_test(test_distension),
		cmocka_unit_test(test_tip),
		cmocka_unit_test(test_rise_and_fade),
		cmocka_unit_test(test_sedation),
		cmocka_unit_test(test_causes),
		cmocka_unit_test(test_not_finite),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
