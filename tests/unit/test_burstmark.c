/*
 * test_burstmark.c - the pressure gauge's burst mark (viewer/burstmark.h)
 * against the gas model that tears the walls (model/gas.h): on the normal
 * case, pumped fast with no leak, the mark at 15 mmHg lies above the
 * pressure at which the cecum tears (the walls widen on the way) but not
 * far; a step before the tear it is that pressure within 1 %; with no
 * wall distended, or the strength not known, there is no mark.
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
#include "viewer/burstmark.h"
#include "viewer_fixture.h"

#define DT 0.001
#define MMHG GAS_PA_PER_MMHG

static struct colon *normal;

static int setup(void **state)
{
	(void)state;
	normal = fixture_colon("config/cases", "normal", COLON_DEFAULT_STEP_M,
			       64);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	colon_destroy(normal);
	return 0;
}

/* What the daemon publishes of G (patient.c's, the fields the mark
 * reads). */
static struct endosim_patient_state published(const struct gas *g)
{
	struct endosim_patient_state p = { .enabled = 1 };

	p.pressure_pa = g->pressure_pa;
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		p.transmural_pa[i] = g->seg[i].transmural_pa;
		p.tension_n_per_m[i] = g->seg[i].tension_n_per_m;
	}
	return p;
}

static void comes_down_to_the_tear(void **state)
{
	static const double none[3] = { 0, 0, 0 };
	struct gas_params gp = GAS_PARAMS_DEFAULT;
	struct gas_input in = { .air = true };
	struct endosim_patient_state p;
	struct gas g, before;
	double p15, at15, last, tear;
	int torn = -1;

	(void)state;
	gp.leak_m3_per_s_pa = 0;
	gp.absorb_air_per_s = 0;
	gp.pump_m3_per_s = 20 * GAS_M3_PER_L / 60;
	gas_attach(&g, &gp, normal, NULL, none);
	p = published(&g);
	p15 = g.pressure_pa;
	at15 = burstmark_pa(&p, gp.wall_strength_n_per_m);
	for (int k = 0; k < 600000 && torn < 0; k++) {
		before = g;
		torn = gas_step(&g, &in, DT);
	}
	assert_int_equal(torn, ANATOMY_CECUM);
	tear = g.pressure_pa;
	p = published(&before);
	last = burstmark_pa(&p, gp.wall_strength_n_per_m);
	printf("# the mark at %.1f mmHg: %.1f; a step before the tear at "
	       "%.1f mmHg: %.1f\n", p15 / MMHG, at15 / MMHG,
	       tear / MMHG, last / MMHG);
	assert_true(at15 > tear && at15 < 1.5 * tear);
	assert_true(fabs(last - tear) < 0.01 * tear);
}

static void no_mark(void **state)
{
	struct endosim_patient_state p = { .enabled = 1 };

	(void)state;
	p.pressure_pa = 1000;
	for (int i = 0; i < ENDOSIM_SEGMENTS; i++) {
		p.transmural_pa[i] = -100; /* the abdomen's heavier */
	}
	assert_true(isnan(burstmark_pa(&p, 540)));
	p.transmural_pa[3] = 1000;
	p.tension_n_per_m[3] = 20; /* r = 2 cm */
	assert_true(fabs(burstmark_pa(&p, 540) - 27000) < 1e-6);
	assert_true(isnan(burstmark_pa(&p, 0)));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(comes_down_to_the_tear),
		cmocka_unit_test(no_mark),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
