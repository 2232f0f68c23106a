/*
 * test_scenario.c - the scripted hand's scenario files: the axes' steps,
 * the handle's valves and the assistant's commands (scenario.h), and the
 * simulated hand that plays them (hand.h: live input over the scenario
 * while it holds, the valves alone held beside the scenario's forces,
 * the patient's commands handed out one a cycle).
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "conf/config.h"
#include "rig/hand.h"
#include "rig/scenario.h"

static char path[64];
static char err[256];

static struct scenario *load(const char *text)
{
	FILE *f;

	snprintf(path, sizeof(path), "/tmp/test_scenario.%d.scn", (int)getpid());
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(text, f);
	fclose(f);
	err[0] = '\0';
	return scenario_load(path, err, sizeof(err));
}

static void assert_error(int line, const char *what)
{
	char where[96];

	snprintf(where, sizeof(where), "%s:%d:", path, line);
	assert_non_null(strstr(err, where));
	assert_non_null(strstr(err, what));
}

static void test_ramps_and_modes(void **state)
{
	struct scenario_cmd c[ENDOSIM_AXES];
	struct scenario *s = load("# comment\n"
				  "1.0 insertion target 0.4 2.0\n"
				  "0.0 insertion target 0.1\n"
				  "2.0 roll force 0.3   # push\n"
				  "4.0 roll free\n"
				  "5.0 end\n");

	(void)state;
	assert_non_null(s);
	scenario_eval(s, 0.5, c);
	assert_int_equal(c[ENDOSIM_AXIS_INSERTION].mode, SCENARIO_TARGET);
	assert_float_equal(c[ENDOSIM_AXIS_INSERTION].value, 0.1, 1e-12);
	assert_int_equal(c[ENDOSIM_AXIS_ROLL].mode, SCENARIO_FREE);
	scenario_eval(s, 2.0, c);
	/* halfway along the ramp from 0.1 to 0.4 */
	assert_float_equal(c[ENDOSIM_AXIS_INSERTION].value, 0.25, 1e-12);
	assert_int_equal(c[ENDOSIM_AXIS_ROLL].mode, SCENARIO_FORCE);
	assert_float_equal(c[ENDOSIM_AXIS_ROLL].value, 0.3, 1e-12);
	scenario_eval(s, 4.5, c);
	assert_float_equal(c[ENDOSIM_AXIS_INSERTION].value, 0.4, 1e-12);
	assert_int_equal(c[ENDOSIM_AXIS_ROLL].mode, SCENARIO_FREE);
	assert_int_equal(c[ENDOSIM_AXIS_WHEEL_UD].mode, SCENARIO_FREE);
	assert_false(scenario_done(s, 4.99));
	assert_true(scenario_done(s, 5.0));
	assert_float_equal(scenario_length(s), 5.0, 1e-12);
	scenario_destroy(s);
}

static void test_repeat(void **state)
{
	struct scenario_cmd c[ENDOSIM_AXES];
	struct scenario *s = load("0 wheel_ud target 1.0 2\n3 repeat\n");

	(void)state;
	assert_non_null(s);
	scenario_eval(s, 1.0, c);
	assert_float_equal(c[ENDOSIM_AXIS_WHEEL_UD].value, 0.5, 1e-12);
	scenario_eval(s, 4.0, c);
	assert_float_equal(c[ENDOSIM_AXIS_WHEEL_UD].value, 0.5, 1e-12);
	assert_false(scenario_done(s, 100));
	scenario_destroy(s);
}

static void test_without_end(void **state)
{
	struct scenario *s = load("1 insertion target 0.5 4\n2 roll free\n");

	(void)state;
	assert_non_null(s);
	assert_float_equal(scenario_length(s), 5.0, 1e-12);
	assert_false(scenario_done(s, 1e6));
	scenario_destroy(s);
}

static void test_valves(void **state)
{
	struct scenario *s = load("0 insertion target 0.1\n"
				  "1 valve air on\n"
				  "2 valve water on   # pressed as well\n"
				  "3 valve air off\n"
				  "4 valve water off\n"
				  "4 valve suction on\n"
				  "6 valve suction off\n"
				  "7 end\n");

	(void)state;
	assert_non_null(s);
	assert_int_equal(scenario_valves(s, 0.99), 0);
	assert_int_equal(scenario_valves(s, 1.0), ENDOSIM_VALVE_AIR);
	assert_int_equal(scenario_valves(s, 2.5),
			 ENDOSIM_VALVE_AIR | ENDOSIM_VALVE_WATER);
	assert_int_equal(scenario_valves(s, 3.5), ENDOSIM_VALVE_WATER);
	assert_int_equal(scenario_valves(s, 5), ENDOSIM_VALVE_SUCTION);
	assert_int_equal(scenario_valves(s, 6.5), 0);
	assert_float_equal(scenario_length(s), 7.0, 1e-12);
	scenario_destroy(s);
}

static void assert_command(const struct scenario *s, uint32_t seq,
			   int action)
{
	struct scenario_patient c;

	scenario_patient_get(s, seq, &c);
	assert_int_equal(c.action, action);
	assert_int_equal(c.seq, action ? seq : 0);
}

static void test_patient_commands(void **state)
{
	struct scenario_patient c;
	struct scenario *s = load("0 roll free\n"
				  "2 patient press llq 30\n"
				  "1 patient position supine\n"
				  "2 patient press umbilical\n"
				  "3 patient release\n"
				  "4 repeat\n");

	(void)state;
	assert_non_null(s);
	assert_int_equal(scenario_patient_due(s, 0.5), 0);
	assert_int_equal(scenario_patient_due(s, 1), 1);
	assert_int_equal(scenario_patient_due(s, 2), 3);
	assert_int_equal(scenario_patient_due(s, 3.5), 4);
	/* the second round goes on counting */
	assert_int_equal(scenario_patient_due(s, 4.5), 4);
	assert_int_equal(scenario_patient_due(s, 5.0), 5);
	assert_int_equal(scenario_patient_due(s, 11.0), 12);
	scenario_patient_get(s, 1, &c);
	assert_int_equal(c.action, SCENARIO_PATIENT_TURN);
	assert_int_equal(c.position, 1); /* supine */
	scenario_patient_get(s, 2, &c); /* equal times: the file's order */
	assert_string_equal(c.site, "llq");
	assert_float_equal(c.force_n, 30, 0);
	scenario_patient_get(s, 3, &c);
	assert_int_equal(c.action, SCENARIO_PATIENT_PRESS);
	assert_string_equal(c.site, "umbilical");
	assert_float_equal(c.force_n, 0, 0);
	assert_command(s, 4, SCENARIO_PATIENT_RELEASE);
	assert_command(s, 5, SCENARIO_PATIENT_TURN);
	assert_command(s, 0, SCENARIO_PATIENT_NONE);
	scenario_destroy(s);
	s = load("1 patient release\n");
	assert_non_null(s);
	assert_command(s, 1, SCENARIO_PATIENT_RELEASE);
	assert_command(s, 2, SCENARIO_PATIENT_NONE); /* no repeat */
	assert_int_equal(scenario_patient_due(s, 100), 1);
	scenario_destroy(s);
}

/* The hand hands out the commands one a cycle, each with its number,
 * however many fall due at once; the valves are the scenario's unless
 * live input holds. */
static void test_hand(void **state)
{
	const double none[ENDOSIM_AXES] = { 0 };
	struct scenario *s = scenario_create();
	struct scenario_patient c;
	struct config cfg;
	struct hand *h;

	(void)state;
	config_defaults(&cfg);
	assert_int_equal(scenario_append(s, "1 patient position prone", err,
					 sizeof(err)), 0);
	assert_int_equal(scenario_append(s, "1 patient release", err,
					 sizeof(err)), 0);
	assert_int_equal(scenario_append(s, "1 valve suction on", err,
					 sizeof(err)), 0);
	assert_int_equal(scenario_append(s, "0.5 valve air on", err,
					 sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "before the last step"));
	h = hand_create(&cfg, s);
	assert_non_null(h);
	hand_patient(h, 0.5, &c);
	assert_int_equal(c.seq, 0);
	assert_int_equal(hand_valves(h, 0.5, 0), 0);
	hand_patient(h, 1.0, &c);
	assert_int_equal(c.seq, 1);
	assert_int_equal(c.action, SCENARIO_PATIENT_TURN);
	hand_patient(h, 1.001, &c);
	assert_int_equal(c.seq, 2);
	assert_int_equal(c.action, SCENARIO_PATIENT_RELEASE);
	hand_patient(h, 1.002, &c);
	assert_int_equal(c.seq, 2); /* the last again */
	assert_int_equal(hand_valves(h, 1.0, 0), ENDOSIM_VALVE_SUCTION);
	/* live input's valves while it holds (taken with the forces) */
	hand_set_live(h, none, ENDOSIM_VALVE_AIR, 1.0, 0);
	hand_forces(h, 1.0, 1, none, none, (double[ENDOSIM_AXES]){ 0 });
	assert_int_equal(hand_valves(h, 1.0, 1), ENDOSIM_VALVE_AIR);
	assert_int_equal(hand_valves(h, 1.0, 2 * ENDOSIM_NS_PER_S),
			 ENDOSIM_VALVE_SUCTION);
	hand_destroy(h);
}

static void test_errors(void **state)
{
	(void)state;
	assert_null(load("0 insertion target 0.1\n1 elbow target 2\n"));
	assert_error(2, "unknown axis 'elbow'");
	assert_null(load("0 insertion push 3\n"));
	assert_error(1, "expected");
	assert_null(load("\n\nx insertion free\n"));
	assert_error(3, "'x' is not a time");
	assert_null(load("0 insertion target abc\n"));
	assert_error(1, "'abc' is not a number");
	assert_null(load("0 insertion target 0.2 -1\n"));
	assert_error(1, "ramp");
	assert_null(load("0 insertion force 1 2\n"));
	assert_error(1, "expected");
	assert_null(load("1 end\n2 roll free\n"));
	assert_error(2, "after the end/repeat on line 1");
	assert_null(load("5 roll free\n1 end\n"));
	assert_non_null(strstr(err, "after the end/repeat"));
	assert_null(load("# nothing\n"));
	assert_non_null(strstr(err, "no steps"));
	assert_null(load("0 valve foot on\n"));
	assert_error(1, "unknown valve 'foot'");
	assert_null(load("0 valve air half\n"));
	assert_error(1, "expected 'valve");
	assert_null(load("0 patient position upside-down\n"));
	assert_error(1, "unknown position 'upside-down'");
	assert_null(load("0 patient press llq -3\n"));
	assert_error(1, "'-3' is not a force");
	assert_null(load("0 patient release now\n"));
	assert_error(1, "expected 'patient position NAME'");
	assert_null(load("0 patient\n"));
	assert_error(1, "expected");
	assert_null(load("0 roll free\n2 valve air on\n1 end\n"));
	assert_non_null(strstr(err, "after the end/repeat"));
	assert_null(scenario_load("/nonexistent.scn", err, sizeof(err)));
	assert_non_null(strstr(err, "cannot open"));
	unlink(path);
}

static void test_shipped_demo(void **state)
{
	struct scenario *s = scenario_load("config/scenarios/demo.scn", err,
					   sizeof(err));

	(void)state;
	assert_non_null(s);
	assert_true(scenario_length(s) > 10);
	scenario_destroy(s);
}

/*
 * The valves alone (endoctl patient valve): held for their time while
 * the scenario pushes on as before; live forces with valves override the
 * scenario and hold both; valves alone then leave the live forces.
 */
static void test_valves_alone(void **state)
{
	const double pos[ENDOSIM_AXES] = { 0 }, vel[ENDOSIM_AXES] = { 0 };
	const double live[ENDOSIM_AXES] = { 5, 0, 0, 0 };
	const uint64_t s = ENDOSIM_NS_PER_S;
	double f[ENDOSIM_AXES];
	struct config cfg;
	struct hand *h;

	(void)state;
	config_defaults(&cfg);
	h = hand_create(&cfg, load("0.0 roll force 0.3\n"));
	assert_non_null(h);
	hand_forces(h, 0.5, s, pos, vel, f);
	assert_true(f[ENDOSIM_AXIS_ROLL] == 0.3);
	assert_int_equal(hand_valves(h, 0.5, s), 0);

	hand_set_live(h, NULL, ENDOSIM_VALVE_AIR, 1.0, s);
	hand_forces(h, 1.0, s + s / 2, pos, vel, f);
	assert_true(f[ENDOSIM_AXIS_ROLL] == 0.3);
	assert_true(f[ENDOSIM_AXIS_INSERTION] == 0);
	assert_int_equal(hand_valves(h, 1.0, s + s / 2), ENDOSIM_VALVE_AIR);
	hand_forces(h, 1.5, 2 * s, pos, vel, f);
	assert_int_equal(hand_valves(h, 1.5, 2 * s), 0); /* sprung back */
	assert_true(f[ENDOSIM_AXIS_ROLL] == 0.3);

	hand_set_live(h, live, ENDOSIM_VALVE_WATER, 1.0, 3 * s);
	hand_forces(h, 3.0, 3 * s + 1, pos, vel, f);
	assert_true(f[ENDOSIM_AXIS_INSERTION] == 5);
	assert_true(f[ENDOSIM_AXIS_ROLL] == 0);
	assert_int_equal(hand_valves(h, 3.0, 3 * s + 1), ENDOSIM_VALVE_WATER);
	hand_set_live(h, NULL, ENDOSIM_VALVE_SUCTION, 5.0, 3 * s + s / 2);
	hand_forces(h, 3.5, 3 * s + s / 2 + 1, pos, vel, f);
	assert_true(f[ENDOSIM_AXIS_INSERTION] == 5);
	assert_int_equal(hand_valves(h, 3.5, 3 * s + s / 2 + 1),
			 ENDOSIM_VALVE_SUCTION);
	/* the live forces lapse at their own time, the valves hold on */
	hand_forces(h, 4.5, 4 * s + s / 2, pos, vel, f);
	assert_true(f[ENDOSIM_AXIS_INSERTION] == 0);
	assert_true(f[ENDOSIM_AXIS_ROLL] == 0.3);
	assert_int_equal(hand_valves(h, 4.5, 4 * s + s / 2),
			 ENDOSIM_VALVE_SUCTION);
	hand_destroy(h);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ramps_and_modes),
		cmocka_unit_test(test_repeat),
		cmocka_unit_test(test_without_end),
		cmocka_unit_test(test_valves),
		cmocka_unit_test(test_patient_commands),
		cmocka_unit_test(test_hand),
		cmocka_unit_test(test_errors),
		cmocka_unit_test(test_shipped_demo),
		cmocka_unit_test(test_valves_alone),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
