/*
 * test_gas.c - the gas in the colon (gas.h) against its definitions and
 * the literature:
 *  - a closed colon (no leak, no absorption) insufflated at flow Q for t
 *    holds V0 + Q t within 0.5 %, and its pressure is the law's: the
 *    segments' volumes at that pressure add up to the gas;
 *  - a linear wall law and a leak: the pressure decays as P0 exp(-t / tau)
 *    with tau = C / G (C the colon's compliance, G the leak's
 *    conductance) within 2 %;
 *  - one wall strength for every segment tears the cecum first, at Kozarek
 *    et al.'s 81 mmHg within 20 %, and would tear the sigmoid at their 169
 *    mmHg within 20 %; torn, it lets its gas go;
 *  - the normal colon distended at 15 mmHg holds 1.3-3.5 L (CT
 *    colonography's volumetry);
 *  - gravity: two segments 10 cm apart along it differ in transmural
 *    pressure by 7.4 mmHg within 2 %; at the same gas volume left lateral
 *    distends the ascending colon more than the descending, right lateral
 *    the reverse, and supine the transverse colon most;
 *  - the blend across a boundary is continuous and reaches each
 *    segment's own factor.
 * All on simulated time.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "model/anatomy.h"
#include "model/colon.h"
#include "model/gas.h"
#include "model/scope.h"

#define DT 0.001
#define MMHG GAS_PA_PER_MMHG
#define L GAS_M3_PER_L

static struct colon *normal;

static int setup(void **state)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	struct anatomy a;
	char err[256];

	(void)state;
	if (anatomy_load(&a, "config/cases/normal.case", err, sizeof(err))) {
		fprintf(stderr, "%s\n", err);
		return -1;
	}
	p.ring_vertices = 64;
	normal = colon_create(&a, &p, err, sizeof(err));
	return normal ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	colon_destroy(normal);
	return 0;
}

/* A closed colon: no leak, no absorption, no gravity. */
static struct gas_params closed(void)
{
	struct gas_params p = GAS_PARAMS_DEFAULT;

	p.leak_m3_per_s_pa = 0;
	p.absorb_air_per_s = 0;
	p.absorb_co2_per_s = 0;
	p.wall_strength_n_per_m = 1e9;
	return p;
}

static const double none[3] = { 0, 0, 0 };

static void closed_insufflation(void **state)
{
	struct gas_params p = closed();
	struct gas_input in = { .air = true };
	struct gas g;
	double v0, want, sum = 0;
	const double t = 30;

	(void)state;
	gas_attach(&g, &p, normal, NULL, none);
	v0 = g.volume_m3;
	for (int k = 0; k < (int)lround(t / DT); k++) {
		gas_step(&g, &in, DT);
	}
	want = v0 + p.pump_m3_per_s * t;
	printf("# closed: %.4f L + %.3f L/min x %.0f s = %.4f L, held %.4f L "
	       "at %.2f mmHg\n", v0 / L, p.pump_m3_per_s / L * 60, t,
	       want / L, g.volume_m3 / L, g.pressure_pa / MMHG);
	assert_true(fabs(g.volume_m3 - want) < 0.005 * want);
	assert_true(fabs(g.flow_in_m3 - p.pump_m3_per_s * t) <
		    1e-6 * p.pump_m3_per_s * t);
	/* the law: each segment's volume at the pressure, summed */
	for (int i = 0; i < g.segments; i++) {
		double v = gas_law_volume(&g.seg[i].law, g.pressure_pa, NULL);

		assert_true(fabs(g.seg[i].factor - sqrt(v)) < 1e-12);
		sum += g.seg[i].volume0_m3 * v;
	}
	assert_true(fabs(sum - g.volume_m3) < 1e-6 * g.volume_m3);
	assert_true(g.pressure_pa > 15 * MMHG);
}

static void linear_leak(void **state)
{
	struct gas_params p = closed();
	struct gas_law law[GAS_SEGMENTS];
	struct gas_input in = { .air = false };
	struct gas g;
	double c = 0, tau, p0, t = 0;

	(void)state;
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		law[i] = (struct gas_law)GAS_LAW_DEFAULT;
		law[i].kind = GAS_LAW_LINEAR;
	}
	p.leak_pa = 0;
	p.leak_m3_per_s_pa = 1e-3 / 60 / (10 * MMHG);
	gas_attach(&g, &p, normal, law, none);
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		c += g.seg[i].volume0_m3 * (1 - law[i].collapsed *
						     law[i].collapsed) /
		     law[i].nominal_pa;
	}
	tau = c / p.leak_m3_per_s_pa;
	gas_set_volume(&g, g.volume_m3 + c * 10 * MMHG, &in);
	p0 = g.pressure_pa;
	while (t < tau - DT / 2) {
		gas_step(&g, &in, DT);
		t += DT;
	}
	printf("# linear law, leak: tau %.2f s; P %.3f -> %.3f mmHg at tau "
	       "(analytic %.3f)\n", tau, p0 / MMHG, g.pressure_pa / MMHG,
	       p0 * exp(-t / tau) / MMHG);
	assert_true(fabs(g.pressure_pa - p0 * exp(-t / tau)) <
		    0.02 * p0 * exp(-t / tau));
}

/* The transmural pressure at which segment I tears: p R f(p) = S. */
static double burst_pa(const struct gas *g, int i)
{
	double lo = 0, hi = 1e6;

	for (int k = 0; k < 200; k++) {
		double p = (lo + hi) / 2;
		double f = sqrt(gas_law_volume(&g->seg[i].law, p, NULL));

		if (p * g->seg[i].widest_m * f > g->p.wall_strength_n_per_m) {
			hi = p;
		} else {
			lo = p;
		}
	}
	return lo;
}

static void burst(void **state)
{
	struct gas_params p = GAS_PARAMS_DEFAULT;
	struct gas_input in = { .air = true };
	struct gas g;
	double cecum, sigmoid;
	int torn = -1;

	(void)state;
	p.leak_m3_per_s_pa = 0;
	p.absorb_air_per_s = 0;
	p.pump_m3_per_s = 20 * L / 60; /* fast: the tear within seconds */
	gas_attach(&g, &p, normal, NULL, none);
	for (int k = 0; k < 600000 && torn < 0; k++) {
		torn = gas_step(&g, &in, DT);
	}
	cecum = burst_pa(&g, ANATOMY_CECUM);
	sigmoid = burst_pa(&g, ANATOMY_SIGMOID);
	printf("# one wall strength %.0f N/m: the %s tears first, at %.1f "
	       "mmHg; the cecum at %.1f (Kozarek 81), the sigmoid at %.1f "
	       "(169)\n", p.wall_strength_n_per_m, anatomy_segment_name(torn),
	       g.pressure_pa / MMHG, cecum / MMHG, sigmoid / MMHG);
	assert_int_equal(torn, ANATOMY_CECUM);
	assert_int_equal(g.burst_segment, ANATOMY_CECUM);
	assert_true(fabs(g.pressure_pa / MMHG - 81) < 0.2 * 81);
	assert_true(fabs(cecum / MMHG - 81) < 0.2 * 81);
	assert_true(fabs(sigmoid / MMHG - 169) < 0.2 * 169);
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		assert_true(i == ANATOMY_CECUM || burst_pa(&g, i) > cecum);
	}
	/* torn, it does not hold its gas */
	in.air = false;
	for (int k = 0; k < 10000; k++) {
		gas_step(&g, &in, DT);
	}
	printf("# torn: %.2f mmHg, %.3f L after 10 s\n", g.pressure_pa / MMHG,
	       g.volume_m3 / L);
	assert_true(g.pressure_pa < 2 * MMHG);
}

static void distended_volume(void **state)
{
	struct gas_params p = closed();
	struct gas_input in = { .air = false };
	struct gas g;
	double v;

	(void)state;
	gas_attach(&g, &p, normal, NULL, none);
	v = gas_lumen_volume(&g, 15 * MMHG, &in);
	printf("# the normal colon at 15 mmHg: %.2f L (CT colonography "
	       "1.3-3.5 L)\n", v / L);
	assert_true(v > 1.3 * L && v < 3.5 * L);
}

/* The segment whose factor is largest. */
static int most_open(const struct gas *g)
{
	int best = 0;

	for (int i = 1; i < g->segments; i++) {
		best = g->seg[i].factor > g->seg[best].factor ? i : best;
	}
	return best;
}

static void gravity(void **state)
{
	struct gas_params p = closed();
	struct gas_input in = { .down = { 0, 0, -1 } }; /* upright */
	struct gas g;
	const double left[3] = { 1, 0, 0 }, right[3] = { -1, 0, 0 };
	const double supine[3] = { 0, 1, 0 }; /* y posterior */
	double dz, dp, want, v;
	int a = ANATOMY_RECTUM, b = ANATOMY_TRANSVERSE;

	(void)state;
	gas_attach(&g, &p, normal, NULL, in.down);
	dz = g.seg[b].centre[2] - g.seg[a].centre[2];
	dp = g.seg[b].transmural_pa - g.seg[a].transmural_pa;
	want = 7.4 * MMHG * dz / 0.10;
	printf("# upright: the %s %.1f cm above the %s: %.2f mmHg more "
	       "(7.4 mmHg per 10 cm: %.2f)\n", anatomy_segment_name(b),
	       dz * 100, anatomy_segment_name(a), dp / MMHG, want / MMHG);
	assert_true(dz > 0.1);
	assert_true(fabs(dp - want) < 0.02 * want);

	/* the same gas, three positions */
	v = g.volume_m3;
	memcpy(in.down, left, sizeof(left));
	gas_set_volume(&g, v, &in);
	printf("# left lateral: ascending %.3f, descending %.3f\n",
	       g.seg[ANATOMY_ASCENDING].factor,
	       g.seg[ANATOMY_DESCENDING].factor);
	assert_true(g.seg[ANATOMY_ASCENDING].factor >
		    g.seg[ANATOMY_DESCENDING].factor);
	memcpy(in.down, right, sizeof(right));
	gas_set_volume(&g, v, &in);
	printf("# right lateral: ascending %.3f, descending %.3f\n",
	       g.seg[ANATOMY_ASCENDING].factor,
	       g.seg[ANATOMY_DESCENDING].factor);
	assert_true(g.seg[ANATOMY_DESCENDING].factor >
		    g.seg[ANATOMY_ASCENDING].factor);
	memcpy(in.down, supine, sizeof(supine));
	gas_set_volume(&g, v, &in);
	printf("# supine: the most open is the %s (%.3f)\n",
	       anatomy_segment_name(most_open(&g)),
	       g.seg[most_open(&g)].factor);
	assert_int_equal(most_open(&g), ANATOMY_TRANSVERSE);
}

static void blend(void **state)
{
	double f[GAS_SEGMENTS];
	const struct colon_region *r;
	double s1, below, above;

	(void)state;
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		f[i] = 0.5 + 0.1 * i;
	}
	r = colon_region(normal, ANATOMY_SIGMOID);
	s1 = r->s1_m;
	below = gas_factor_at(normal, f, s1 - 1e-9);
	above = gas_factor_at(normal, f, s1 + 1e-9);
	assert_true(fabs(below - above) < 1e-6);
	assert_true(fabs(below - (f[2] + f[3]) / 2) < 1e-6);
	assert_true(fabs(gas_factor_at(normal, f, (r->s0_m + r->s1_m) / 2) -
			 f[2]) < 1e-12);
	assert_true(fabs(gas_factor_at(normal, f, s1 - GAS_BLEND_M) - f[2]) <
		    1e-9);
	assert_true(fabs(gas_factor_at(normal, f, s1 + GAS_BLEND_M) - f[3]) <
		    1e-9);
}

/*
 * Suction with the tip in gas empties the colon towards a vacuum: each
 * segment's radius follows its law down to the scope's and no further
 * (the wall closes on the tube, not past it), while the volume keeps
 * the law's own.
 */
static void suction_closes_on_the_scope(void **state)
{
	struct gas_params p = closed();
	struct gas_input in = { .suction = true };
	struct gas g;
	int floored = 0;

	(void)state;
	gas_attach(&g, &p, normal, NULL, none);
	for (int k = 0; k < (int)lround(120 / DT); k++) {
		gas_step(&g, &in, DT);
	}
	printf("# suction 120 s: %.4f L at %.1f mmHg\n", g.volume_m3 / L,
	       g.pressure_pa / MMHG);
	assert_true(g.pressure_pa < 0);
	for (int i = 0; i < g.segments; i++) {
		double v = gas_law_volume(&g.seg[i].law, g.pressure_pa, NULL);
		double floor = SCOPE_RADIUS_M / g.seg[i].radius_m;

		assert_true(g.seg[i].factor >= floor - 1e-12);
		assert_true(fabs(g.seg[i].factor - fmax(sqrt(v), floor)) <
			    1e-12);
		floored += sqrt(v) < floor;
	}
	assert_true(floored > 0); /* the vacuum reached below the scope */
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(closed_insufflation),
		cmocka_unit_test(linear_leak),
		cmocka_unit_test(burst),
		cmocka_unit_test(distended_volume),
		cmocka_unit_test(gravity),
		cmocka_unit_test(blend),
		cmocka_unit_test(suction_closes_on_the_scope),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
