/*
 * test_input.c - the trainee's hand on the simulated rig (viewer/input.h):
 * a grip that takes hold on the first control and lets go after the last,
 * pushes with its spring towards a target the controls move, never harder
 * than a hand, and does not wind its target up against a blocked scope.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "viewer/input.h"

#define MS ENDOSIM_NS_PER_MS

static void idle_hand_does_nothing(void **state)
{
	struct input_hand h = { 0 };
	struct input_controls c = { 0 };
	struct endosim_state st = { 0 };
	double f[ENDOSIM_AXES] = { 1, 1, 1, 1 };

	(void)state;
	assert_false(input_active(&c));
	assert_false(input_step(&h, &c, &st, 0.016, 100 * MS, f));
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_true(f[a] == 0);
	}
}

/* A held key: the target runs ahead at the axis' rate; a scope that does
 * not follow is pushed up to the hand's strength and no more. */
static void key_pushes_up_to_strength(void **state)
{
	struct input_hand h = { 0 };
	struct input_controls c = { 0 };
	struct endosim_state st = { 0 };
	double f[ENDOSIM_AXES];
	const int a = ENDOSIM_AXIS_INSERTION;

	(void)state;
	st.axis[a].position = 0.2;
	c.rate[a] = 1;
	assert_true(input_step(&h, &c, &st, 0.1, 0, f));
	assert_true(fabs(h.target[a] - (0.2 + 0.1 * input_rate[a])) < 1e-12);
	assert_true(fabs(f[a] - input_stiffness[a] * 0.1 * input_rate[a]) <
		    1e-9);
	assert_true(f[ENDOSIM_AXIS_ROLL] == 0); /* held where it is */
	for (int k = 1; k < 1000; k++) {
		input_step(&h, &c, &st, 0.1, (uint64_t)k * 100 * MS, f);
	}
	assert_true(fabs(f[a] - input_strength[a]) < 1e-9);
	assert_true(h.target[a] - st.axis[a].position <=
		    input_strength[a] / input_stiffness[a] + 1e-12);
	/* the scope gives way: the pull falls at once */
	st.axis[a].position = h.target[a];
	c.rate[a] = 0;
	input_step(&h, &c, &st, 0.1, 100000 * MS, f);
	assert_true(fabs(f[a]) < 1e-9);
}

static void damps_motion(void **state)
{
	struct input_hand h = { 0 };
	struct input_controls c = { 0 };
	struct endosim_state st = { 0 };
	double f[ENDOSIM_AXES];
	const int a = ENDOSIM_AXIS_WHEEL_UD;

	(void)state;
	c.step[ENDOSIM_AXIS_INSERTION] = 1e-9; /* anything, to take hold */
	st.axis[a].velocity = 2.0;
	input_step(&h, &c, &st, 0.0, 0, f);
	assert_true(fabs(f[a] + input_damping[a] * 2.0) < 1e-12);
}

/* A drag sets the target from where it was when the drag began. */
static void drag_steers_from_its_start(void **state)
{
	struct input_hand h = { 0 };
	struct input_controls c = { 0 };
	struct endosim_state st = { 0 };
	double f[ENDOSIM_AXES];
	const int a = ENDOSIM_AXIS_WHEEL_LR;

	(void)state;
	st.axis[a].position = 0.5;
	c.drag[a] = true;
	c.drag_by[a] = 0.0;
	input_step(&h, &c, &st, 0.016, 0, f);
	c.drag_by[a] = 0.3;
	input_step(&h, &c, &st, 0.016, 16 * MS, f);
	assert_true(fabs(h.target[a] - 0.8) < 1e-12);
	c.drag_by[a] = -0.2;
	input_step(&h, &c, &st, 0.016, 32 * MS, f);
	assert_true(fabs(h.target[a] - 0.3) < 1e-12);
	assert_true(f[a] < 0);
}

/* Let go INPUT_RELEASE_S after the last control, not before. */
static void lets_go(void **state)
{
	struct input_hand h = { 0 };
	struct input_controls c = { 0 }, none = { 0 };
	struct endosim_state st = { 0 };
	double f[ENDOSIM_AXES];
	uint64_t release = (uint64_t)(INPUT_RELEASE_S * 1000) * MS;

	(void)state;
	c.rate[ENDOSIM_AXIS_ROLL] = -1;
	assert_true(input_step(&h, &c, &st, 0.016, 1000 * MS, f));
	assert_true(input_step(&h, &none, &st, 0.016,
			       1000 * MS + release - MS, f));
	assert_false(input_step(&h, &none, &st, 0.016,
				1000 * MS + release + MS, f));
	assert_true(f[ENDOSIM_AXIS_ROLL] == 0);
	assert_false(h.engaged);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(idle_hand_does_nothing),
		cmocka_unit_test(key_pushes_up_to_strength),
		cmocka_unit_test(damps_motion),
		cmocka_unit_test(drag_steers_from_its_start),
		cmocka_unit_test(lets_go),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
