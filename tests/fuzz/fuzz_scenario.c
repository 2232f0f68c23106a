/*
 * fuzz_scenario - libFuzzer target: the simulated hand's scenario parser,
 * and evaluating what it accepted (the axes, the valves, the patient's
 * commands).
 */
#include <stdint.h>
#include <stdio.h>

#include "rig/scenario.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct scenario_cmd cmd[ENDOSIM_AXES];
	struct scenario_patient pc;
	struct scenario *s;
	char err[256];
	FILE *f = fmemopen((void *)data, size, "r");

	if (!f) {
		return 0;
	}
	s = scenario_load_stream(f, "fuzz.scn", err, sizeof(err));
	fclose(f);
	if (s) {
		double len = scenario_length(s);

		for (int i = 0; i <= 10; i++) {
			scenario_eval(s, len * i / 8.0, cmd);
			(void)scenario_done(s, len * i / 8.0);
			(void)scenario_valves(s, len * i / 8.0);
			scenario_patient_get(s, scenario_patient_due(
					     s, len * i / 8.0), &pc);
		}
		scenario_destroy(s);
	}
	return 0;
}
