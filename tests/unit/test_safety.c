/* test_safety.c - the state machine, the fault latch, the safety filter and
 * the placeholder forces. */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "haptics.h"
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
	double out[ENDOSIM_AXES];
	struct safety s;

	(void)state;
	safety_init(&s);
	safety_filter(&s, &cfg, cmd, out, 0);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_true(out[a] == 0.0); /* IDLE: nothing gets through */
	}
	safety_command(&s, SAFETY_ENABLE);
	safety_filter(&s, &cfg, cmd, out, 0);
	assert_true(out[0] == cfg.limits.max[0]);
	assert_true(out[1] == -0.5);
	assert_true(out[2] == 0.05);
	assert_true(out[3] == -cfg.limits.max[3]);
	cmd[2] = INFINITY;
	safety_filter(&s, &cfg, cmd, out, 0);
	assert_int_equal(s.state, ENDOSIM_STATE_FAULT);
	assert_int_equal(s.faults, ENDOSIM_FAULT_NONFINITE);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_true(out[a] == 0.0);
	}
}

/* The placeholder end brakes only ever take energy out (F v <= 0), do not
 * push an axis at rest, and reach the limit at the end stop. */
static void test_placeholder_is_passive(void **state)
{
	struct rig_feedback fb;
	double cmd[ENDOSIM_AXES];

	(void)state;
	healthy_feedback(&fb, 0);
	for (double x = 0; x <= 1.8; x += 0.01) {
		for (double v = -1; v <= 1; v += 0.05) {
			fb.axis[0].position = x;
			fb.axis[0].velocity = v;
			haptics_render(&cfg, &fb, cmd);
			assert_true(cmd[0] * v <= 0);
		}
	}
	fb.axis[0].position = 0.0;
	fb.axis[0].velocity = 0.0;
	haptics_render(&cfg, &fb, cmd);
	assert_true(cmd[0] == 0.0);
	fb.axis[0].position = cfg.rig.travel_max[0];
	fb.axis[0].velocity = 1.0;
	cfg.haptics.damping[0] = 0;
	haptics_render(&cfg, &fb, cmd);
	assert_float_equal(cmd[0], -cfg.limits.max[0], 1e-9);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_transitions),
		cmocka_unit_test(test_fault_latches_until_cause_gone),
		cmocka_unit_test(test_feedback_checks),
		cmocka_unit_test(test_filter),
		cmocka_unit_test(test_placeholder_is_passive),
	};

	return cmocka_run_group_tests(tests, setup, NULL);
}
