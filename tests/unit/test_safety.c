/* test_safety.c - the state machine, the fault latch and the safety
 * filter. */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "safety.h"

static struct config cfg;

static int setup(void **state)
{
	(void)state;
	config_defaults(&cfg);
	return 0;
}

static void healthy_feedback(struct rig_feedback *fb, uint64_t now)
{
	memset(fb, 0, sizeof(*fb));
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		fb->axis[a].status = ENDOSIM_DRIVE_PRESENT;
		fb->axis[a].stamp_ns = now;
		fb->axis[a].position = 0.1;
	}
}

static void test_transitions(void **state)
{
	struct safety s;

	(void)state;
	safety_init(&s);
	assert_int_equal(s.state, ENDOSIM_STATE_IDLE);
	assert_false(safety_torque_on(&s));
	assert_int_equal(safety_command(&s, SAFETY_ENABLE), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_ENABLED);
	assert_true(safety_torque_on(&s));
	assert_int_equal(safety_command(&s, SAFETY_DISABLE), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_IDLE);
	assert_int_equal(safety_command(&s, SAFETY_ENABLE), 0);
	assert_int_equal(safety_command(&s, SAFETY_ESTOP), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_ESTOP);
	assert_false(safety_torque_on(&s));
	assert_int_equal(safety_command(&s, SAFETY_ENABLE), -EPERM);
	assert_int_equal(safety_command(&s, SAFETY_DISABLE), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_ESTOP);
	assert_int_equal(safety_command(&s, SAFETY_RESET), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_IDLE);
}

static void test_fault_latches_until_cause_gone(void **state)
{
	struct rig_feedback fb;
	struct safety s;
	uint64_t now = 10000000000ull;

	(void)state;
	safety_init(&s);
	safety_command(&s, SAFETY_ENABLE);
	/* cycle 1: the up/down wheel's drive vanishes */
	safety_begin_cycle(&s);
	healthy_feedback(&fb, now);
	fb.axis[ENDOSIM_AXIS_WHEEL_UD].status = 0;
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.state, ENDOSIM_STATE_FAULT);
	assert_int_equal(s.faults, ENDOSIM_FAULT_DRIVE_GONE);
	assert_int_equal(s.fault_axis, ENDOSIM_AXIS_WHEEL_UD);
	assert_int_equal(s.fault_ns, now);
	assert_false(safety_torque_on(&s));
	/* cycle 2: still gone; reset is refused, enable too */
	safety_begin_cycle(&s);
	safety_check_feedback(&s, &cfg, &fb, now + 1000000);
	safety_begin_cycle(&s);
	assert_int_equal(safety_command(&s, SAFETY_RESET), -EBUSY);
	assert_int_equal(safety_command(&s, SAFETY_ENABLE), -EPERM);
	/* cycle 3: back; the fault stays latched until reset */
	healthy_feedback(&fb, now + 2000000);
	safety_check_feedback(&s, &cfg, &fb, now + 2000000);
	assert_int_equal(s.state, ENDOSIM_STATE_FAULT);
	safety_begin_cycle(&s);
	assert_int_equal(safety_command(&s, SAFETY_RESET), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_IDLE);
	assert_int_equal(s.faults, 0);
	assert_int_equal(s.fault_axis, -1);
}

static void test_feedback_checks(void **state)
{
	struct rig_feedback fb;
	struct safety s;
	uint64_t now = 5000000000ull;
	uint64_t age = (uint64_t)(cfg.rig.feedback_max_age_s * 1e9);

	(void)state;
	safety_init(&s);
	healthy_feedback(&fb, now - age);
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.faults, 0);
	fb.axis[ENDOSIM_AXIS_ROLL].stamp_ns = now - age - 1;
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.faults, ENDOSIM_FAULT_STALE);
	assert_int_equal(s.fault_axis, ENDOSIM_AXIS_ROLL);
	safety_init(&s);
	healthy_feedback(&fb, now);
	fb.axis[ENDOSIM_AXIS_INSERTION].status |= ENDOSIM_DRIVE_FAULT;
	fb.axis[ENDOSIM_AXIS_INSERTION].fault_detail = 0x3210;
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.faults, ENDOSIM_FAULT_DRIVE);
	assert_int_equal(s.fault_detail, 0x3210);
	safety_init(&s);
	healthy_feedback(&fb, now);
	fb.axis[ENDOSIM_AXIS_WHEEL_LR].velocity = NAN;
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.faults, ENDOSIM_FAULT_NONFINITE);
}

static void test_filter(void **state)
{
	double cmd[ENDOSIM_AXES] = { 100, -0.5, 0.05, -7 };
	double out[ENDOSIM_AXES] = { 0 };
	struct safety s;

	(void)state;
	safety_init(&s);
	safety_filter(&s, &cfg, cmd, out, 1.0, 0);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_true(out[a] == 0.0); /* IDLE: nothing gets through */
	}
	safety_command(&s, SAFETY_ENABLE);
	/* a second of slew is enough for any default limit */
	safety_filter(&s, &cfg, cmd, out, 1.0, 0);
	assert_true(out[0] == cfg.limits.max[0]);
	assert_true(out[1] == -0.5);
	assert_true(out[2] == 0.05);
	assert_true(out[3] == -cfg.limits.max[3]);
	cmd[2] = INFINITY;
	safety_filter(&s, &cfg, cmd, out, 1.0, 0);
	assert_int_equal(s.state, ENDOSIM_STATE_FAULT);
	assert_int_equal(s.faults, ENDOSIM_FAULT_NONFINITE);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_true(out[a] == 0.0); /* at once, not slewed */
	}
}

/* A step of command reaches the drive at the slew rate, no faster. */
static void test_slew(void **state)
{
	double cmd[ENDOSIM_AXES] = { 30, 0.5, -0.08, 0 };
	double out[ENDOSIM_AXES] = { 0 };
	double dt = 0.001;
	struct safety s;

	(void)state;
	safety_init(&s);
	safety_command(&s, SAFETY_ENABLE);
	for (int k = 1; k <= 3; k++) {
		safety_filter(&s, &cfg, cmd, out, dt, 0);
		assert_float_equal(out[0], k * cfg.limits.slew[0] * dt, 1e-9);
		assert_float_equal(out[2], -k * cfg.limits.slew[2] * dt, 1e-12);
	}
	for (int k = 0; k < 1000; k++) {
		safety_filter(&s, &cfg, cmd, out, dt, 0);
	}
	assert_float_equal(out[0], 30, 1e-9);
	assert_float_equal(out[1], 0.5, 1e-12);
	assert_float_equal(out[2], -0.08, 1e-12);
	cmd[0] = -30;
	safety_filter(&s, &cfg, cmd, out, dt, 0);
	assert_float_equal(out[0], 30 - cfg.limits.slew[0] * dt, 1e-9);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_transitions),
		cmocka_unit_test(test_fault_latches_until_cause_gone),
		cmocka_unit_test(test_feedback_checks),
		cmocka_unit_test(test_filter),
		cmocka_unit_test(test_slew),
	};

	return cmocka_run_group_tests(tests, setup, NULL);
}
