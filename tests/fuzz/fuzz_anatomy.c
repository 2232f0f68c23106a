/*
 * fuzz_anatomy - libFuzzer target: the case-file parser (anatomy.c) on
 * arbitrary file contents, then building the colon of whatever it accepts
 * (at a coarse resolution: the checks must keep the geometry buildable),
 * and the patient's body in it (issue 22): each segment's wall law and
 * fluid, the case's sites; the gas pumped in, sucked out and the patient
 * turned, the assistant pressing at each site: a case that loads must
 * give a body that stays finite.
 */
#include <stdint.h>
#include <stdlib.h>

#include "model/colon.h"
#include "model/patient.h"
#include "fuzz_file.h"

/* A few cycles of the patient in COLON: insufflated, turned supine, the
 * hand at each site, the suction. */
static void patient_in(const struct colon *colon)
{
	static struct patient pt;
	struct patient_params p = PATIENT_PARAMS_DEFAULT;
	struct patient_input in = { .valves = ENDOSIM_VALVE_AIR };
	struct flex_pad pad;

	p.enabled = true;
	p.turn_s = 0.01;
	patient_init(&pt, &p);
	patient_attach(&pt, colon);
	patient_turn(&pt, POSTURE_SUPINE);
	for (int k = 0; k < 40; k++) {
		if (k % 10 == 0) {
			patient_press(&pt, k / 10, 0);
		}
		in.valves = k < 20 ? ENDOSIM_VALVE_AIR : ENDOSIM_VALVE_SUCTION;
		patient_step(&pt, &in, 0.002);
		patient_pad(&pt, &pad);
		if (!patient_finite(&pt)) {
			abort(); /* a case that loads keeps the body finite */
		}
	}
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const struct colon_params p = { .step_m = 0.01, .ring_vertices = 8,
					.segment_m = 0.2 };
	struct anatomy a;
	struct colon *c;
	char err[512];

	if (anatomy_load(&a, fuzz_file(data, size), err, sizeof(err))) {
		return 0;
	}
	c = colon_create(&a, &p, err, sizeof(err));
	if (c) {
		patient_in(c);
	}
	colon_destroy(c);
	return 0;
}
