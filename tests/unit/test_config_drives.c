/*
 * test_config_drives.c - the drive sections of the configuration: keys in
 * dotted sections, hexadecimal ids, register keys, the cross-key checks
 * that refuse an unusable drive setup, the feedback age per bus, and the
 * unit conversion derived from an axis' mechanics, the valves' inputs,
 * the tool's (issue 25).
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "conf/config.h"
#include "rig/drive.h"

static char err[512];

static void set(struct config *c, const char *key, const char *value)
{
	if (config_set(c, key, value, false, err, sizeof(err))) {
		fail_msg("%s=%s: %s", key, value, err);
	}
}

/*
 * Two modbus wheels with a usable map. (config_set() checks across keys
 * after each key: the order keeps every step valid.)
 */
static void modbus_wheels(struct config *c)
{
	config_defaults(c);
	set(c, "modbus.wheel_ud.torque", "holding 0 i16 scale=1e-5");
	set(c, "modbus.wheel_ud.position", "input 0 i32");
	set(c, "modbus.wheel_lr.torque", "holding 0 i16 scale=1e-5");
	set(c, "modbus.wheel_lr.position", "input 0 i32");
	set(c, "modbus.wheel_lr.slave", "2");
	set(c, "axis.wheel_ud.backend", "modbus");
	set(c, "axis.wheel_lr.backend", "modbus");
	set(c, "rig.backend", "drives");
}

#define UD ENDOSIM_AXIS_WHEEL_UD
#define LR ENDOSIM_AXIS_WHEEL_LR

/* Sets register SIG of axis A directly (no cross-key check), then checks. */
static int try_reg(struct config *c, int a, int sig, const char *text)
{
	assert_int_equal(regspec_parse(text, &c->modbus_drive[a].reg[sig], err,
				      sizeof(err)), 0);
	return config_check(c, err, sizeof(err));
}

static void test_dotted_sections_and_hex(void **state)
{
	const struct parse_key *k = config_key_find("epos4.roll.vid");
	struct config c;
	char buf[64];

	(void)state;
	assert_non_null(k);
	config_defaults(&c);
	assert_int_equal(c.epos4[ENDOSIM_AXIS_ROLL].vid, 0x24E7);
	assert_int_equal(c.epos4[ENDOSIM_AXIS_ROLL].pid, 0x3B01);
	set(&c, "epos4.roll.vid", "0x1234");
	assert_int_equal(c.epos4[ENDOSIM_AXIS_ROLL].vid, 0x1234);
	config_format(&c, k, buf, sizeof(buf));
	assert_string_equal(buf, "0x1234");
	assert_int_equal(config_set(&c, "epos4.roll.vid", "0x10000", false,
				    err, sizeof(err)), -EINVAL);
	assert_null(config_key_find("axis.roll.gear_radius_m"));
	assert_non_null(config_key_find("axis.insertion.gear_radius_m"));
}

static void test_register_key(void **state)
{
	const struct parse_key *k =
		config_key_find("modbus.wheel_lr.velocity");
	struct config c;
	char buf[160];

	(void)state;
	config_defaults(&c);
	config_format(&c, k, buf, sizeof(buf));
	assert_string_equal(buf, "none");
	set(&c, "modbus.wheel_lr.velocity", "input 0x0002 f32 cdab");
	config_format(&c, k, buf, sizeof(buf));
	assert_string_equal(buf, "input 0x0002 f32 cdab");
	assert_int_equal(config_set(&c, "modbus.wheel_lr.velocity",
				    "input 2 f33", false, err, sizeof(err)),
			 -EINVAL);
	assert_non_null(strstr(err, "modbus.wheel_lr.velocity"));
}

static void test_file_errors_name_line(void **state)
{
	char path[] = "/tmp/test_config_drives.XXXXXX";
	int fd = mkstemp(path);
	FILE *f = fdopen(fd, "w");
	struct config c;

	(void)state;
	fprintf(f, "[rig]\nbackend = drives\n[modbus.wheel_ud]\n"
		   "slave = 3\nposition = input 1 i33\n");
	fclose(f);
	config_defaults(&c);
	assert_int_equal(config_load(&c, path, err, sizeof(err)), -EINVAL);
	unlink(path);
	assert_non_null(strstr(err, ":5: [modbus.wheel_ud] position: "));
}

static void test_modbus_checks(void **state)
{
	struct config c;

	(void)state;
	modbus_wheels(&c);
	assert_int_equal(config_check(&c, err, sizeof(err)), 0);

	c.modbus_drive[LR].slave = 1;
	assert_int_equal(config_check(&c, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "[modbus.wheel_lr] slave"));

	modbus_wheels(&c);
	assert_int_equal(try_reg(&c, UD, REGSPEC_TORQUE, "none"), -EINVAL);
	assert_non_null(strstr(err, "[modbus.wheel_ud] torque"));

	modbus_wheels(&c);
	assert_int_equal(try_reg(&c, UD, REGSPEC_ENABLE, "discrete 3"),
			 -EINVAL);
	assert_non_null(strstr(err, "[modbus.wheel_ud] enable"));

	modbus_wheels(&c);
	c.modbus_drive[UD].combined_0x17 = 1;
	assert_int_equal(config_check(&c, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "position: 0x17 reads holding"));
	assert_int_equal(try_reg(&c, UD, REGSPEC_POSITION, "holding 0x10 i32"),
			 0);
	assert_int_equal(try_reg(&c, UD, REGSPEC_FAULT, "holding 0x200"),
			 -EINVAL);
	assert_non_null(strstr(err, "span"));
	assert_int_equal(try_reg(&c, UD, REGSPEC_FAULT, "holding 0x20"), 0);

	modbus_wheels(&c);
	c.modbus.baud = 100000;
	assert_int_equal(config_check(&c, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "[modbus] baud"));
	/* a modbus map is not checked while every axis is simulated */
	c.rig.backend = CONFIG_BACKEND_SIM;
	assert_int_equal(config_check(&c, err, sizeof(err)), 0);
}

static void test_epos4_checks(void **state)
{
	struct config c;

	(void)state;
	config_defaults(&c);
	set(&c, "axis.insertion.backend", "epos4-usb");
	set(&c, "axis.roll.backend", "epos4-usb");
	c.rig.backend = CONFIG_BACKEND_DRIVES;
	assert_int_equal(config_check(&c, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "[epos4.roll] serial"));
	set(&c, "epos4.insertion.serial", "A");
	set(&c, "epos4.roll.serial", "B");
	assert_int_equal(config_check(&c, err, sizeof(err)), 0);
	set(&c, "epos4.roll.pid", "0x3b02");
	set(&c, "epos4.roll.serial", "A");
	assert_int_equal(config_check(&c, err, sizeof(err)), 0);
	c.epos4[ENDOSIM_AXIS_ROLL].pid = 0x3B01;
	assert_int_equal(config_check(&c, err, sizeof(err)), -EINVAL);
}

static void test_feedback_age_per_bus(void **state)
{
	struct config c;

	(void)state;
	modbus_wheels(&c);
	set(&c, "axis.insertion.backend", "epos4-usb");
	set(&c, "rig.feedback_max_age_s", "0.01");
	set(&c, "epos4.insertion.feedback_max_age_s", "0.2");
	set(&c, "modbus.feedback_max_age_s", "0.03");
	assert_true(config_feedback_max_age_s(&c, ENDOSIM_AXIS_INSERTION) ==
		    0.2);
	assert_true(config_feedback_max_age_s(&c, ENDOSIM_AXIS_ROLL) == 0.01);
	assert_true(config_feedback_max_age_s(&c, ENDOSIM_AXIS_WHEEL_UD) ==
		    0.03);
	set(&c, "rig.backend", "sim");
	assert_true(config_feedback_max_age_s(&c, ENDOSIM_AXIS_WHEEL_UD) ==
		    0.01);
}

/* Loads TEXT as a file: config_load()'s result, its message in ERR. */
static int load_text(struct config *c, const char *text)
{
	char path[] = "/tmp/test_config_drives.XXXXXX";
	int fd = mkstemp(path);
	FILE *f = fdopen(fd, "w");
	int r;

	fputs(text, f);
	fclose(f);
	config_defaults(c);
	r = config_load(c, path, err, sizeof(err));
	unlink(path);
	return r;
}

/* A configuration file's text and what its refusal must say. */
struct bad_file {
	const char *text, *where;
};

/* Each of the N files BAD refused, saying its WHERE, the configuration
 * left as it was. */
static void refused(const struct bad_file *bad, size_t n)
{
	struct config c, before;

	config_defaults(&before);
	for (size_t i = 0; i < n; i++) {
		if (load_text(&c, bad[i].text) != -EINVAL ||
		    !strstr(err, bad[i].where)) {
			fail_msg("'%s': got '%s'", bad[i].text, err);
		}
		assert_memory_equal(&c, &before, sizeof(c));
	}
}

/*
 * The valves: a bit of 0x60FD on an EPOS4, a register on a Modbus drive;
 * what each drive reads; a bad bit or register refused with its line; a
 * valve on two inputs refused naming both.
 */
static void test_valve_keys(void **state)
{
	struct config c;

	(void)state;
	modbus_wheels(&c);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_int_equal(config_axis_valves(&c, a), 0);
	}
	set(&c, "axis.insertion.backend", "epos4-usb");
	set(&c, "epos4.insertion.valve_air_bit", "16");
	set(&c, "epos4.insertion.valve_suction_bit", "18");
	set(&c, "modbus.wheel_lr.valve_water", "discrete 0x0010");
	assert_int_equal(c.epos4[ENDOSIM_AXIS_INSERTION].valve_bit[0], 16);
	assert_int_equal(c.epos4[ENDOSIM_AXIS_INSERTION].valve_bit[1], -1);
	assert_int_equal(config_axis_valves(&c, ENDOSIM_AXIS_INSERTION),
			 ENDOSIM_VALVE_AIR | ENDOSIM_VALVE_SUCTION);
	assert_int_equal(config_axis_valves(&c, LR), ENDOSIM_VALVE_WATER);
	assert_int_equal(config_axis_valves(&c, UD), 0);

	/* a simulated axis' drive section reads nothing */
	set(&c, "epos4.roll.valve_water_bit", "3");
	assert_int_equal(config_axis_valves(&c, ENDOSIM_AXIS_ROLL), 0);

	/* one input per valve */
	assert_int_equal(config_set(&c, "modbus.wheel_ud.valve_air",
				    "input 0x0008 u16", false, err,
				    sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "[modbus.wheel_ud] valve_air: "
				    "[epos4.insertion] valve_air_bit reads"));
	assert_int_equal(config_set(&c, "epos4.insertion.valve_water_bit", "17",
				    false, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "[modbus.wheel_lr] valve_water: "
				    "[epos4.insertion] valve_water_bit"));
	set(&c, "modbus.wheel_ud.valve_air", "none");
	assert_int_equal(config_check(&c, err, sizeof(err)), 0);

	assert_int_equal(config_set(&c, "epos4.insertion.valve_air_bit", "32",
				    false, err, sizeof(err)), -EINVAL);
	assert_int_equal(load_text(&c, "[epos4.roll]\nnode_id = 2\n"
				   "valve_water_bit = -2\n"), -EINVAL);
	assert_non_null(strstr(err, ":3: [epos4.roll] valve_water_bit: "));
	assert_int_equal(load_text(&c, "[modbus.wheel_ud]\nslave = 3\n\n"
				   "valve_suction = discrete 0x10 q16\n"),
			 -EINVAL);
	assert_non_null(strstr(err, ":4: [modbus.wheel_ud] valve_suction: "));
}

/* Every valve key's bad values refused with the file's line and the key
 * (issue 22); two valves on one input of a drive, or one valve on two
 * drives, refused at the line of the key that came second. */
static void test_valve_keys_bad_input(void **state)
{
	static const struct bad_file bad[] = {
		{ "[epos4.roll]\nvalve_air_bit = 32\n",
		  ":2: [epos4.roll] valve_air_bit: 32 is out of range" },
		{ "[epos4.roll]\nvalve_water_bit = sixteen\n",
		  ":2: [epos4.roll] valve_water_bit: 'sixteen' is not an" },
		{ "[epos4.roll]\nvalve_suction_bit = 16.5\n",
		  ":2: [epos4.roll] valve_suction_bit: '16.5' is not an" },
		{ "[epos4.roll]\nvalve_suction_bit = 0x10\n",
		  ":2: [epos4.roll] valve_suction_bit: '0x10' is not an" },
		{ "[modbus.wheel_lr]\nvalve_air = discrete\n",
		  ":2: [modbus.wheel_lr] valve_air: " },
		{ "[modbus.wheel_lr]\nvalve_water = input 0x10000\n",
		  ":2: [modbus.wheel_lr] valve_water: " },
		{ "[modbus.wheel_lr]\nvalve_suction = lamp 0x10\n",
		  ":2: [modbus.wheel_lr] valve_suction: " },
		{ "[rig]\nbackend = drives\n[axis.insertion]\n"
		  "backend = epos4-usb\n[epos4.insertion]\n"
		  "valve_air_bit = 16\nvalve_suction_bit = 16\n",
		  ":7: [epos4.insertion] valve_suction_bit: the input of "
		  "[epos4.insertion] valve_air_bit (one input per valve)" },
		{ "[rig]\nbackend = drives\n[axis.wheel_ud]\n"
		  "backend = modbus\n[modbus.wheel_ud]\n"
		  "torque = holding 0 i16\nposition = input 0 i32\n"
		  "valve_water = discrete 0x10\n"
		  "valve_suction = discrete 16\n",
		  ":9: [modbus.wheel_ud] valve_suction: the input of "
		  "[modbus.wheel_ud] valve_water (one input per valve)" },
		{ "[rig]\nbackend = drives\n[axis.insertion]\n"
		  "backend = epos4-usb\n[axis.roll]\nbackend = epos4-usb\n"
		  "[epos4.insertion]\nserial = A\nvalve_air_bit = 16\n"
		  "[epos4.roll]\nserial = B\nvalve_air_bit = 17\n",
		  ":12: [epos4.roll] valve_air_bit: [epos4.insertion] "
		  "valve_air_bit reads that valve already" },
	};
	struct config c;

	(void)state;
	refused(bad, sizeof(bad) / sizeof(bad[0]));
	/* the same bit on a simulated axis' drive is never read */
	assert_int_equal(load_text(&c, "[epos4.roll]\nvalve_air_bit = 16\n"
				   "valve_water_bit = 16\n"), 0);
}

/*
 * The tool in the working channel: an EPOS4's auxiliary sensor, analogue
 * input and input bit, a Modbus drive's registers; what each drive reads;
 * its depth and opening on drives together, each signal on one drive, the
 * pedal on an input of its own, refused at the line of the key that came
 * second with both keys named.
 */
static void test_tool_keys(void **state)
{
	static const struct bad_file bad[] = {
		{ "[epos4.roll]\ntool_depth_sensor = 4\n",
		  ":2: [epos4.roll] tool_depth_sensor: 4 is out of range" },
		{ "[epos4.roll]\ntool_opening_input = 3\n",
		  ":2: [epos4.roll] tool_opening_input: 3 is out of range" },
		{ "[epos4.roll]\ntool_pedal_bit = 32\n",
		  ":2: [epos4.roll] tool_pedal_bit: 32 is out of range" },
		{ "[modbus.wheel_lr]\ntool_depth = input\n",
		  ":2: [modbus.wheel_lr] tool_depth: " },
		{ "[rig]\nbackend = drives\n[axis.insertion]\n"
		  "backend = epos4-usb\n[epos4.insertion]\n"
		  "tool_depth_sensor = 2\n",
		  "[epos4.insertion] tool_depth_sensor: the tool's opening is "
		  "on no drive" },
		{ "[rig]\nbackend = drives\n[axis.insertion]\n"
		  "backend = epos4-usb\n[epos4.insertion]\n"
		  "valve_suction_bit = 16\ntool_pedal_bit = 16\n",
		  ":7: [epos4.insertion] tool_pedal_bit: the input of "
		  "[epos4.insertion] valve_suction_bit (one input per switch)" },
		{ "[rig]\nbackend = drives\n[axis.insertion]\n"
		  "backend = epos4-usb\n[epos4.insertion]\n"
		  "tool_depth_sensor = 2\ntool_opening_input = 1\n"
		  "tool_open_mv = 0\n",
		  ":8: [epos4.insertion] tool_open_mv: 0 mV, the same as "
		  "tool_closed_mv" },
		{ "[rig]\nbackend = drives\n[axis.insertion]\n"
		  "backend = epos4-usb\n[axis.roll]\nbackend = epos4-usb\n"
		  "[epos4.insertion]\nserial = A\ntool_pedal_bit = 16\n"
		  "[epos4.roll]\nserial = B\ntool_pedal_bit = 17\n",
		  ":12: [epos4.roll] tool_pedal_bit: [epos4.insertion] "
		  "tool_pedal_bit reads it already (one drive per signal)" },
	};
	struct config c;

	(void)state;
	assert_int_equal(load_text(&c, "[rig]\nbackend = drives\n"
				   "[axis.insertion]\nbackend = epos4-usb\n"
				   "[axis.wheel_lr]\nbackend = modbus\n"
				   "[epos4.insertion]\ntool_depth_sensor = 2\n"
				   "tool_opening_input = 1\n"
				   "[modbus.wheel_lr]\n"
				   "torque = holding 0 i16\n"
				   "position = input 0 i32\n"
				   "tool_pedal = discrete 0x13\n"), 0);
	assert_int_equal(config_axis_tool(&c, ENDOSIM_AXIS_INSERTION),
			 CONFIG_TOOL_DEPTH | CONFIG_TOOL_OPENING);
	assert_int_equal(config_axis_tool(&c, LR), CONFIG_TOOL_PEDAL);
	assert_int_equal(config_axis_tool(&c, UD), 0);
	assert_true(c.epos4[ENDOSIM_AXIS_INSERTION].tool_m_per_count == 1e-5);
	assert_true(c.epos4[ENDOSIM_AXIS_INSERTION].tool_open_mv == 5000);
	/* one key at a time (--set): the depth alone passes each key's
	 * check, not the whole configuration's */
	set(&c, "epos4.insertion.tool_opening_input", "0");
	assert_int_equal(config_check_whole(&c, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "[epos4.insertion] tool_depth_sensor: "
				    "the tool's opening is on no drive"));
	set(&c, "epos4.insertion.tool_depth_sensor", "0");
	assert_int_equal(config_check_whole(&c, err, sizeof(err)), 0);
	/* a simulated axis' drive section reads nothing */
	assert_int_equal(load_text(&c, "[epos4.roll]\ntool_pedal_bit = 3\n"
				   "tool_depth_sensor = 2\n"), 0);
	assert_int_equal(config_axis_tool(&c, ENDOSIM_AXIS_ROLL), 0);

	refused(bad, sizeof(bad) / sizeof(bad[0]));
}

static void test_units(void **state)
{
	struct drive_units u;
	struct config c;

	(void)state;
	config_defaults(&c);
	set(&c, "axis.insertion.counts_per_rev", "2000");
	set(&c, "axis.insertion.gear_ratio", "2");
	set(&c, "axis.insertion.gear_radius_m", "0.015");
	drive_units_init(&u, &c, ENDOSIM_AXIS_INSERTION);
	/* 4000 counts: one pinion turn: 2 pi r of belt */
	assert_true(fabs(4000 * u.si_per_count - 2 * M_PI * 0.015) < 1e-12);
	/* 20 N on the carriage: 0.3 N m at the pinion, 0.15 at the motor */
	assert_true(fabs(20 * u.motor_nm_per_si - 0.15) < 1e-12);

	set(&c, "axis.wheel_lr.counts_per_rev", "4096");
	set(&c, "axis.wheel_lr.gear_ratio", "3.5");
	set(&c, "axis.wheel_lr.direction", "reversed");
	drive_units_init(&u, &c, ENDOSIM_AXIS_WHEEL_LR);
	assert_true(fabs(4096 * 3.5 * u.si_per_count + 2 * M_PI) < 1e-12);
	assert_true(fabs(0.07 * u.motor_nm_per_si + 0.02) < 1e-12);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_dotted_sections_and_hex),
		cmocka_unit_test(test_register_key),
		cmocka_unit_test(test_file_errors_name_line),
		cmocka_unit_test(test_modbus_checks),
		cmocka_unit_test(test_epos4_checks),
		cmocka_unit_test(test_feedback_age_per_bus),
		cmocka_unit_test(test_valve_keys),
		cmocka_unit_test(test_valve_keys_bad_input),
		cmocka_unit_test(test_tool_keys),
		cmocka_unit_test(test_units),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
