/*
 * test_lensfx.c - what the lens lets the endoscopic image be drawn at
 * (viewer/lensfx.h, lensfx_image_factor()): the image at half its side
 * only where the lens hides the sharp image everywhere, by the shader's
 * own rule: the least smeared pixel's blur, 1.6 x 0.45 smear + 1.2 murk,
 * at least one half (from there a pixel takes only the blurred copies);
 * at its full scale for a clean lens, a light smear or haze, a red-out or
 * the water jet alone, and an amount not finite.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "viewer/lensfx.h"

static double factor(double smear, double murk, double redout,
		     uint32_t valves)
{
	struct endosim_patient_state p = { .enabled = 1 };

	p.lens_smear = smear;
	p.lens_murk = murk;
	p.lens_redout = redout;
	p.valves = valves;
	return lensfx_image_factor(&p);
}

static void hidden(void **state)
{
	(void)state;
	assert_true(factor(1, 1, 0, 0) == LENSFX_HIDDEN_FACTOR);
	assert_true(factor(0, 0.42, 0, 0) == LENSFX_HIDDEN_FACTOR);
	assert_true(factor(0.70, 0, 0, 0) == LENSFX_HIDDEN_FACTOR);
	assert_true(factor(0.4, 0.2, 0, ENDOSIM_VALVE_WATER) ==
		    LENSFX_HIDDEN_FACTOR); /* 0.288 + 0.24 */
}

static void sharp_shows(void **state)
{
	(void)state;
	/* the least smeared pixel's blur just under one half */
	assert_true(factor(0.69, 0, 0, 0) == 1);
	assert_true(factor(0, 0.41, 0, 0) == 1);
	assert_true(factor(0.4, 0.17, 0, 0) == 1); /* 0.288 + 0.204 */
	assert_true(factor(0, 0, 0, 0) == 1);
	assert_true(factor(0, 0, 1, 0) == 1);  /* red-out alone */
	assert_true(factor(0, 0, 0, ENDOSIM_VALVE_WATER) == 1); /* the jet */
	/* not finite: none of it (the murk alone hides it here) */
	assert_true(factor(NAN, 1, 0, 0) == LENSFX_HIDDEN_FACTOR);
	assert_true(factor(INFINITY, 0, 0, 0) == 1);
	assert_true(factor(NAN, 0, 0, 0) == 1);
}

static void patient_off(void **state)
{
	struct endosim_patient_state p = { .enabled = 0, .lens_smear = 1,
					   .lens_murk = 1 };

	(void)state;
	assert_true(lensfx_image_factor(&p) == 1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(hidden),
		cmocka_unit_test(sharp_shows),
		cmocka_unit_test(patient_off),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
