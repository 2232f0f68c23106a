/* test_safety.c - the state machine, the fault latch, the safety filter
 * (slew, enable ramp), the fault monitors (motion, overruns, saturation,
 * non-finite values: the patient's body's through the force loop, in
 * lockstep, under either model) and the test commands' injections. */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "proto/names.h"
#include "loop/inject.h"
#include "loop/safety.h"
#include "model/haptics.h"
#include "rig_loop.h"

static struct config cfg;

static int setup(void **state)
{
	(void)state;
	config_defaults(&cfg);
	return 0;
}

#define MS ENDOSIM_NS_PER_MS
#define S ENDOSIM_NS_PER_S

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
	assert_int_equal(safety_command(&s, SAFETY_ENABLE, 0), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_ENABLED);
	assert_true(safety_torque_on(&s));
	assert_int_equal(safety_command(&s, SAFETY_DISABLE, 0), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_IDLE);
	assert_int_equal(safety_command(&s, SAFETY_ENABLE, 0), 0);
	assert_int_equal(safety_command(&s, SAFETY_ESTOP, 7 * S), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_ESTOP);
	/* the emergency stop is latched with its time, never "present" */
	assert_int_equal(s.faults, ENDOSIM_FAULT_ESTOP);
	assert_int_equal(safety_first(&s)->first_ns, 7 * S);
	safety_begin_cycle(&s);
	assert_int_equal(s.active, 0);
	assert_false(safety_torque_on(&s));
	assert_int_equal(safety_command(&s, SAFETY_ENABLE, 0), -EPERM);
	assert_int_equal(safety_command(&s, SAFETY_DISABLE, 0), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_ESTOP);
	assert_int_equal(safety_command(&s, SAFETY_RESET, 0), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_IDLE);
	assert_int_equal(s.faults, 0);
	assert_null(safety_first(&s));
}

static void test_fault_latches_until_cause_gone(void **state)
{
	struct rig_feedback fb;
	struct safety s;
	uint64_t now = 10000000000ull;

	(void)state;
	safety_init(&s);
	safety_command(&s, SAFETY_ENABLE, 0);
	/* cycle 1: the up/down wheel's drive vanishes */
	safety_begin_cycle(&s);
	healthy_feedback(&fb, now);
	fb.axis[ENDOSIM_AXIS_WHEEL_UD].status = 0;
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.state, ENDOSIM_STATE_FAULT);
	assert_int_equal(s.faults, ENDOSIM_FAULT_DRIVE_GONE);
	assert_int_equal(safety_first(&s)->axis, ENDOSIM_AXIS_WHEEL_UD);
	assert_int_equal(safety_first(&s)->first_ns, now);
	assert_false(safety_torque_on(&s));
	/* cycle 2: still gone; reset is refused, enable too */
	safety_begin_cycle(&s);
	safety_check_feedback(&s, &cfg, &fb, now + 1000000);
	safety_begin_cycle(&s);
	assert_int_equal(safety_command(&s, SAFETY_RESET, 0), -EBUSY);
	assert_int_equal(safety_command(&s, SAFETY_ENABLE, 0), -EPERM);
	/* cycle 3: back; the fault stays latched until reset */
	healthy_feedback(&fb, now + 2000000);
	safety_check_feedback(&s, &cfg, &fb, now + 2000000);
	assert_int_equal(s.state, ENDOSIM_STATE_FAULT);
	safety_begin_cycle(&s);
	assert_int_equal(safety_command(&s, SAFETY_RESET, 0), 0);
	assert_int_equal(s.state, ENDOSIM_STATE_IDLE);
	assert_int_equal(s.faults, 0);
	assert_null(safety_first(&s));
	assert_int_equal(s.latched, 1);
}

static void test_feedback_checks(void **state)
{
	struct rig_feedback fb;
	struct safety s;
	uint64_t now = 5000000000ull;
	uint64_t age =
		(uint64_t)(cfg.rig.feedback_max_age_s * ENDOSIM_NS_PER_S);

	(void)state;
	safety_init(&s);
	healthy_feedback(&fb, now - age);
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.faults, 0);
	fb.axis[ENDOSIM_AXIS_ROLL].stamp_ns = now - age - 1;
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.faults, ENDOSIM_FAULT_STALE);
	assert_int_equal(safety_first(&s)->axis, ENDOSIM_AXIS_ROLL);
	safety_init(&s);
	healthy_feedback(&fb, now);
	fb.axis[ENDOSIM_AXIS_INSERTION].status |= ENDOSIM_DRIVE_FAULT;
	fb.axis[ENDOSIM_AXIS_INSERTION].fault_detail = 0x3210;
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.faults, ENDOSIM_FAULT_DRIVE);
	assert_int_equal(safety_first(&s)->detail, 0x3210);
	safety_init(&s);
	healthy_feedback(&fb, now);
	fb.axis[ENDOSIM_AXIS_WHEEL_LR].velocity = NAN;
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.faults, ENDOSIM_FAULT_NONFINITE);
	assert_int_equal(safety_first(&s)->detail, ENDOSIM_STAGE_FEEDBACK);
	assert_int_equal(safety_first(&s)->axis, ENDOSIM_AXIS_WHEEL_LR);
	/* the simulated hand's force is feedback too */
	safety_init(&s);
	healthy_feedback(&fb, now);
	fb.axis[ENDOSIM_AXIS_ROLL].hand = -INFINITY;
	safety_check_feedback(&s, &cfg, &fb, now);
	assert_int_equal(s.faults, ENDOSIM_FAULT_NONFINITE);
}

static void test_filter(void **state)
{
	double cmd[ENDOSIM_AXES] = { 100, -0.5, 0.05, -7 };
	double out[ENDOSIM_AXES] = { 0 };
	struct safety s;

	(void)state;
	cfg.limits.enable_ramp_s = 0; /* no ramp: full force at once */
	safety_init(&s);
	safety_filter(&s, &cfg, cmd, out, 1.0, 0);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_true(out[a] == 0.0); /* IDLE: nothing gets through */
	}
	safety_command(&s, SAFETY_ENABLE, 0);
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
	config_defaults(&cfg);
}

/*
 * After enable a constant command comes through as command * t / T over
 * the ramp time T, then in full; disabling drops it at once, and the next
 * enable ramps again from nothing.
 */
static void test_enable_ramp(void **state)
{
	double cmd[ENDOSIM_AXES] = { 10, 0.5, -0.05, 0 };
	double out[ENDOSIM_AXES];
	double ramp_s = cfg.limits.enable_ramp_s;
	uint64_t t0 = 3 * S;
	struct safety s;

	(void)state;
	assert_true(ramp_s > 0);
	safety_init(&s);
	safety_command(&s, SAFETY_ENABLE, t0);
	for (int k = 0; k <= 12; k++) {
		double t = ramp_s * k / 10.0, scale = fmin(t / ramp_s, 1.0);

		safety_filter(&s, &cfg, cmd, out, 0.1,
			      t0 + (uint64_t)(t * ENDOSIM_NS_PER_S));
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			assert_float_equal(out[a], cmd[a] * scale, 1e-9);
		}
	}
	assert_int_equal(s.enabled_ns, t0);
	safety_command(&s, SAFETY_DISABLE, 0);
	safety_filter(&s, &cfg, cmd, out, 0.1, t0 + 5 * S);
	assert_true(out[0] == 0.0);
	safety_command(&s, SAFETY_ENABLE, 0);
	safety_filter(&s, &cfg, cmd, out, 0.1, t0 + 6 * S);
	assert_true(out[0] == 0.0); /* the first cycle of a new ramp */
	safety_filter(&s, &cfg, cmd, out, 0.1,
		      t0 + 6 * S + (uint64_t)(ramp_s * 0.5e9));
	assert_float_equal(out[0], cmd[0] * 0.5, 1e-9);
	assert_int_equal(s.faults, 0);
}

/*
 * A force held beyond its limit while torque is on faults once it has been
 * held longer than saturation_s, in that cycle with zero on every axis;
 * dropping below the limit or torque off restarts the clock.
 */
static void test_saturation(void **state)
{
	double cmd[ENDOSIM_AXES] = { 0, 0, 0.5, 0 }; /* 5 x the wheel's */
	double out[ENDOSIM_AXES];
	uint64_t hold = (uint64_t)(cfg.limits.saturation_s * ENDOSIM_NS_PER_S),
		 t;
	struct safety s;

	(void)state;
	cfg.limits.enable_ramp_s = 0;
	cfg.limits.saturation_fault = CONFIG_OVERRUN_FAULT;
	safety_init(&s);
	safety_command(&s, SAFETY_ENABLE, 0);
	for (t = S; t <= S + hold; t += 100 * MS) {
		safety_filter(&s, &cfg, cmd, out, 0.1, t);
		assert_int_equal(s.state, ENDOSIM_STATE_ENABLED);
		assert_true(out[2] == cfg.limits.max[2]);
	}
	/* below the limit for one cycle: the clock starts again */
	cmd[2] = 0.05;
	safety_filter(&s, &cfg, cmd, out, 0.1, t);
	cmd[2] = -0.5;
	for (t += MS; t <= 2 * S + 2 * hold; t += 100 * MS) {
		safety_filter(&s, &cfg, cmd, out, 0.1, t);
		if (s.state == ENDOSIM_STATE_FAULT) {
			break;
		}
	}
	assert_int_equal(s.faults, ENDOSIM_FAULT_SATURATION);
	assert_true(t > S + 2 * hold);
	assert_int_equal(safety_first(&s)->axis, ENDOSIM_AXIS_WHEEL_UD);
	assert_float_equal(safety_first(&s)->value, -0.5, 1e-12);
	assert_float_equal(safety_first(&s)->limit, cfg.limits.max[2], 1e-12);
	assert_true(safety_first(&s)->detail > hold / MS);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_true(out[a] == 0.0);
	}
	/* torque off: the clock stops, the cause is gone, reset works */
	safety_begin_cycle(&s);
	safety_filter(&s, &cfg, cmd, out, 0.1, t + MS);
	safety_begin_cycle(&s);
	assert_int_equal(safety_command(&s, SAFETY_RESET, 0), 0);
	config_defaults(&cfg);
}

/*
 * saturation_fault = auto: on a simulated axis (no motor to protect) a
 * hold past saturation_s only warns (published among the active causes,
 * nothing latched); on an axis a drive turns it is the fault.
 */
static void test_saturation_auto(void **state)
{
	double cmd[ENDOSIM_AXES] = { 0, 0, 0.5, 0 };
	double out[ENDOSIM_AXES];
	struct endosim_safety_state pub;
	uint64_t t;
	struct safety s;

	(void)state;
	cfg.limits.enable_ramp_s = 0;
	cfg.limits.saturation_fault = CONFIG_OVERRUN_AUTO;
	safety_init(&s);
	safety_command(&s, SAFETY_ENABLE, 0);
	for (t = S; t <= 3 * S + 2 * (uint64_t)(cfg.limits.saturation_s *
						ENDOSIM_NS_PER_S);
	     t += 100 * MS) {
		safety_begin_cycle(&s);
		safety_filter(&s, &cfg, cmd, out, 0.1, t);
	}
	assert_int_equal(s.state, ENDOSIM_STATE_ENABLED);
	assert_int_equal(s.faults, 0);
	safety_publish(&s, t, &pub);
	assert_int_equal(pub.active & ENDOSIM_FAULT_SATURATION,
			 ENDOSIM_FAULT_SATURATION);
	/* the same axis on a drive: a fault */
	cfg.rig.backend = CONFIG_BACKEND_DRIVES;
	cfg.axis[ENDOSIM_AXIS_WHEEL_UD].backend = CONFIG_DRIVE_MODBUS;
	safety_begin_cycle(&s);
	safety_filter(&s, &cfg, cmd, out, 0.1, t + MS);
	assert_int_equal(s.state, ENDOSIM_STATE_FAULT);
	assert_int_equal(s.faults, ENDOSIM_FAULT_SATURATION);
	config_defaults(&cfg);
}

/* Outside the travel by more than the margin; faster than the limit. */
static void test_motion(void **state)
{
	double span = cfg.rig.travel_max[0] - cfg.rig.travel_min[0];
	double margin = cfg.limits.travel_margin * span;
	struct rig_feedback fb;
	struct safety s;

	(void)state;
	safety_init(&s);
	healthy_feedback(&fb, 0);
	fb.axis[0].position = cfg.rig.travel_max[0] + margin * 0.99;
	fb.axis[1].velocity = -cfg.limits.max_speed[1] * 0.99;
	safety_check_motion(&s, &cfg, &fb, 0);
	assert_int_equal(s.faults, 0);
	fb.axis[0].position = cfg.rig.travel_min[0] - margin * 1.01;
	safety_check_motion(&s, &cfg, &fb, 1);
	assert_int_equal(s.faults, ENDOSIM_FAULT_TRAVEL);
	assert_int_equal(safety_first(&s)->axis, 0);
	assert_float_equal(safety_first(&s)->limit,
			   cfg.rig.travel_min[0] - margin, 1e-12);
	fb.axis[1].velocity = -cfg.limits.max_speed[1] * 1.01;
	safety_check_motion(&s, &cfg, &fb, 2);
	assert_int_equal(s.faults,
			 ENDOSIM_FAULT_TRAVEL | ENDOSIM_FAULT_RUNAWAY);
	assert_int_equal(s.cause[__builtin_ctz(ENDOSIM_FAULT_RUNAWAY)].axis, 1);
	assert_int_equal(s.cause[__builtin_ctz(ENDOSIM_FAULT_RUNAWAY)].first_ns,
			 2);
	/* the first fault stays the first */
	assert_int_equal(s.fault_bit, ENDOSIM_FAULT_TRAVEL);
}

/*
 * The budget, where a miss is a fault: N periods skipped within the window
 * are allowed, N + 1 are a fault, present until the window has moved past
 * them.
 */
static void test_overrun_budget(void **state)
{
	struct config c = cfg;
	int budget = c.loop.overrun_budget;
	uint64_t window =
		(uint64_t)(c.loop.overrun_window_s * ENDOSIM_NS_PER_S);
	uint64_t t = 10 * S;
	struct safety s;

	(void)state;
	c.loop.overrun_fault = CONFIG_OVERRUN_FAULT;
	safety_init(&s);
	/* the budget, one period at a time, well inside the window */
	for (int i = 0; i < budget; i++) {
		safety_check_overruns(&s, &c, 1, t + (uint64_t)i * MS);
	}
	assert_int_equal(s.faults, 0);
	assert_int_equal(s.overrun_window, budget);
	/* spread out over more than the window: never a fault */
	safety_init(&s);
	for (int i = 0; i < 4 * budget; i++) {
		t += window / (uint64_t)budget + MS;
		safety_check_overruns(&s, &c, 1, t);
	}
	assert_int_equal(s.faults, 0);
	/* one period past the budget */
	safety_init(&s);
	for (int i = 0; i <= budget; i++) {
		assert_int_equal(s.faults, 0);
		safety_check_overruns(&s, &c, 1, t + (uint64_t)i * MS);
	}
	assert_int_equal(s.faults, ENDOSIM_FAULT_OVERRUN);
	assert_float_equal(safety_first(&s)->value, budget + 1, 0);
	assert_float_equal(safety_first(&s)->limit, budget, 0);
	/* a single long stall; present until the window passes */
	safety_init(&s);
	safety_begin_cycle(&s);
	safety_check_overruns(&s, &c, 2000, t);
	assert_int_equal(s.faults, ENDOSIM_FAULT_OVERRUN);
	safety_begin_cycle(&s);
	safety_check_overruns(&s, &c, 0, t + window);
	safety_begin_cycle(&s);
	assert_int_equal(safety_command(&s, SAFETY_RESET, 0), -EBUSY);
	safety_check_overruns(&s, &c, 0, t + window + MS);
	safety_begin_cycle(&s);
	assert_int_equal(safety_command(&s, SAFETY_RESET, 0), 0);
}

/* One stall of 2 budgets: is it a fault under C? */
static bool stall_faults(const struct config *c, struct safety *s)
{
	uint64_t t = 10 * S;
	int missed;

	safety_init(s);
	assert_int_equal(safety_command(s, SAFETY_ENABLE, t), 0);
	safety_begin_cycle(s);
	missed = safety_check_overruns(s, c, 2 * c->loop.overrun_budget, t);
	safety_begin_cycle(s);
	/* still over the budget: the same miss, no new warning */
	assert_false(safety_check_overruns(s, c, 1, t + MS));
	assert_int_equal(s->overrun_misses, 1);
	assert_int_equal(missed, !(s->faults & ENDOSIM_FAULT_OVERRUN));
	return s->state == ENDOSIM_STATE_FAULT;
}

/*
 * [loop] overrun_fault: auto warns where every axis is simulated and
 * faults where one is a real drive; yes faults on the simulated rig, no
 * warns beside a real drive. A warning keeps torque on, is published as
 * present but not latched, is counted once per miss and lets a reset by.
 */
static void test_overrun_fault_setting(void **state)
{
	struct config c = cfg;
	struct endosim_safety_state pub;
	struct safety s;
	uint64_t t = 10 * S;

	(void)state;
	assert_int_equal(c.loop.overrun_fault, CONFIG_OVERRUN_AUTO);
	assert_false(stall_faults(&c, &s));
	assert_true(safety_torque_on(&s));
	assert_int_equal(s.faults, 0);
	safety_publish(&s, t, &pub);
	assert_int_equal(pub.active, ENDOSIM_FAULT_OVERRUN);
	assert_int_equal(safety_command(&s, SAFETY_RESET, t), 0);
	/* the window passes, then a second miss: counted again */
	assert_false(safety_check_overruns(&s, &c, 0, t + 2 * S));
	safety_publish(&s, t + 2 * S, &pub);
	assert_int_equal(pub.active, 0);
	assert_true(safety_check_overruns(&s, &c, 2 * c.loop.overrun_budget,
					  t + 3 * S));
	assert_int_equal(s.overrun_misses, 2);
	assert_int_equal(s.faults, 0);

	c.loop.overrun_fault = CONFIG_OVERRUN_FAULT;
	assert_true(stall_faults(&c, &s));
	assert_int_equal(s.faults, ENDOSIM_FAULT_OVERRUN);
	assert_false(safety_torque_on(&s));

	c.loop.overrun_fault = CONFIG_OVERRUN_AUTO;
	c.rig.backend = CONFIG_BACKEND_DRIVES;
	assert_false(stall_faults(&c, &s)); /* [axis.*] backend = sim */
	c.axis[ENDOSIM_AXIS_WHEEL_LR].backend = CONFIG_DRIVE_MODBUS;
	assert_true(stall_faults(&c, &s));
	assert_float_equal(safety_first(&s)->value, 2 * c.loop.overrun_budget,
			   0);

	c.loop.overrun_fault = CONFIG_OVERRUN_WARN;
	assert_false(stall_faults(&c, &s));
	assert_true(safety_torque_on(&s));
}

/* A NaN or infinity anywhere: its stage and axis are kept. */
static void test_finite(void **state)
{
	double pose[4] = { 0.1, 0.2, NAN, 0.4 };
	struct safety s;

	(void)state;
	safety_init(&s);
	safety_check_finite(&s, pose, 2, -1, ENDOSIM_STAGE_KINEMATICS, 5);
	assert_int_equal(s.faults, 0);
	safety_check_finite(&s, pose, 4, -1, ENDOSIM_STAGE_KINEMATICS, 5);
	assert_int_equal(s.state, ENDOSIM_STATE_FAULT);
	assert_int_equal(s.faults, ENDOSIM_FAULT_NONFINITE);
	assert_int_equal(safety_first(&s)->detail, ENDOSIM_STAGE_KINEMATICS);
	assert_int_equal(safety_first(&s)->axis, -1);
	assert_true(isnan(safety_first(&s)->value));
}

/* Cycles until the rig is enabled with its forces in full. */
static const struct endosim_state *enabled(struct rig_loop *r)
{
	const struct endosim_state *st;

	loop_post(r->loop, LOOP_CMD_ENABLE);
	for (int k = 0; k < 5000; k++) {
		st = rig_loop_step(r);
		if (st->state == ENDOSIM_STATE_ENABLED &&
		    st->safety.ramp >= 1) {
			return st;
		}
	}
	fail_msg("not enabled");
	return NULL;
}

/*
 * A wall law gone NaN makes the gas's pressure and every radius factor
 * NaN in the patient's step (FLUID: the fluid's surface gone NaN, its
 * level alone, which no force reads): the cycle that computes them faults
 * (non-finite, the haptic rendering's stage) with every axis' torque off,
 * under either model, and nothing crashes; the next cycle lays the body
 * anew lying where it lies, so that reset is taken.
 */
static void patient_goes_nonfinite(int model, bool fluid)
{
	const struct endosim_state *st;
	struct rig_loop r;
	struct patient *pt;

	rig_loop_create(&r, true, model);
	loop_patient_post(r.loop, &(struct loop_patient_command){
		LOOP_PATIENT_TURN, POSTURE_SUPINE, 0 });
	enabled(&r);
	pt = loop_patient(r.loop);
	assert_true(patient_finite(pt));
	if (fluid) {
		pt->fluid.up[2] = NAN;
	} else {
		pt->gas.seg[ANATOMY_CECUM].law.nominal_pa = NAN;
	}
	st = rig_loop_step(&r);
	assert_true(fluid || isnan(st->patient.pressure_pa));
	assert_true(fluid || isnan(st->patient.factor[ANATOMY_SIGMOID]));
	assert_int_equal(st->patient.burst_segment, -1);
	assert_int_equal(st->state, ENDOSIM_STATE_FAULT);
	assert_int_equal(st->fault_bits, ENDOSIM_FAULT_NONFINITE);
	assert_int_equal(st->fault_detail, ENDOSIM_STAGE_HAPTICS);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_true(st->axis[a].limited == 0);
	}
	for (int k = 0; k < 100; k++) {
		st = rig_loop_step(&r);
	}
	assert_true(patient_finite(pt));
	assert_int_equal(st->patient.position, ENDOSIM_POSITION_SUPINE);
	assert_true(st->patient.pressure_pa > 10 * GAS_PA_PER_MMHG &&
		    st->patient.pressure_pa < 20 * GAS_PA_PER_MMHG);
	loop_post(r.loop, LOOP_CMD_RESET);
	st = rig_loop_step(&r);
	assert_int_equal(st->state, ENDOSIM_STATE_IDLE);
	enabled(&r);
	rig_loop_destroy(&r);
}

/* Each watched part of the body (the gas, a factor, the fluid, the lens,
 * the pad) not finite is seen, and laid anew by the next step. */
static void patient_watches_each_part(void)
{
	struct rig_loop r;
	struct patient *pt;
	double *part[8];

	rig_loop_create(&r, true, HAPTICS_MODEL_PAPER);
	pt = loop_patient(r.loop);
	part[0] = &pt->gas.volume_m3;
	part[1] = &pt->gas.pressure_pa;
	part[2] = &pt->factor[ANATOMY_TRANSVERSE];
	part[3] = &pt->fluid.seg[ANATOMY_CECUM].volume_m3;
	part[4] = &pt->fluid.seg[ANATOMY_SIGMOID].level_m;
	part[5] = &pt->lens.smear;
	part[6] = &pt->lens.redout;
	part[7] = &pt->pad_n;
	for (int i = 0; i < 8; i++) {
		rig_loop_step(&r);
		assert_true(patient_finite(pt));
		*part[i] = i % 2 ? NAN : -INFINITY;
		assert_false(patient_finite(pt));
		assert_int_equal(rig_loop_step(&r)->fault_bits, 0);
		assert_true(patient_finite(pt));
	}
	rig_loop_destroy(&r);
}

static void test_patient_nonfinite(void **state)
{
	(void)state;
	for (int fluid = 0; fluid < 2; fluid++) {
		patient_goes_nonfinite(HAPTICS_MODEL_PAPER, fluid);
		patient_goes_nonfinite(HAPTICS_MODEL_ROD, fluid);
	}
	patient_watches_each_part();
}

/* The test commands alter the feedback and the pipeline, until cleared. */
static void test_inject(void **state)
{
	double cmd[ENDOSIM_AXES] = { 1, 2, 3, 4 };
	struct endosim_haptics_state h = { 0 };
	struct scope_pose pose = { 0 };
	struct rig_feedback fb;
	struct inject in = { 0 };

	(void)state;
	assert_int_equal(inject_start(&in, INJECT_DRIVE_GONE, 1, 0, 0), 0);
	assert_int_equal(inject_start(&in, INJECT_STALE, 2, 0, 5 * S), 0);
	assert_int_equal(inject_start(&in, INJECT_FORCE, -1, 9, 0), 0);
	assert_int_equal(inject_start(&in, INJECT_NAN, 3,
				      ENDOSIM_STAGE_KINEMATICS, 0), 0);
	assert_int_equal(inject_start(&in, INJECT_NAN, 3, 7, 0), -EINVAL);
	assert_int_equal(inject_start(&in, INJECT_STALL, 0, 1, 0), -EINVAL);
	assert_int_equal(inject_start(&in, INJECT_SPEED, 4, 1, 0), -EINVAL);
	healthy_feedback(&fb, 9 * S);
	inject_feedback(&in, &fb);
	assert_int_equal(fb.axis[1].status & ENDOSIM_DRIVE_PRESENT, 0);
	assert_int_equal(fb.axis[2].stamp_ns, 5 * S);
	assert_int_equal(fb.axis[0].stamp_ns, 9 * S);
	inject_pipeline(&in, &pose, &h, cmd);
	assert_true(cmd[0] == 9 && cmd[3] == 9);
	assert_true(isnan(pose.tip[0]));
	/* a haptic part poisoned gets its value back once cleared */
	h.f_static[0] = 2.5;
	assert_int_equal(inject_start(&in, INJECT_NAN, 0,
				      ENDOSIM_STAGE_HAPTICS, 0), 0);
	inject_pipeline(&in, &pose, &h, cmd);
	assert_true(isnan(h.f_static[0]));
	assert_int_equal(inject_start(&in, INJECT_CLEAR, -1, 0, 0), 0);
	inject_pipeline(&in, &pose, &h, cmd);
	assert_true(h.f_static[0] == 2.5);
	healthy_feedback(&fb, 9 * S);
	inject_feedback(&in, &fb);
	assert_int_equal(fb.axis[1].status, ENDOSIM_DRIVE_PRESENT);
	assert_int_equal(fb.axis[2].stamp_ns, 9 * S);
	assert_int_equal(names_debug_action_find("drive-gone"),
			 INJECT_DRIVE_GONE);
	assert_string_equal(names_debug_action(INJECT_END_CONTROL),
			    "end-control");
	assert_int_equal(names_debug_action_find("nonsense"), -1);
}

/*
 * The speed fade: torque that drives an axis the way it moves fades from
 * full at SAFETY_FADE_START of its max speed to nothing at SAFETY_FADE_END;
 * torque against the motion is never faded.
 */
static void test_speed_fade(void **state)
{
	double cmd[ENDOSIM_AXES] = { 0, 0, 0.08, 0 };
	double out[ENDOSIM_AXES] = { 0 };
	double vmax = cfg.limits.max_speed[2];
	double mid = (SAFETY_FADE_START + SAFETY_FADE_END) / 2;
	struct rig_feedback fb;
	struct safety s;

	(void)state;
	cfg.limits.enable_ramp_s = 0;
	safety_init(&s);
	safety_command(&s, SAFETY_ENABLE, 0);
	healthy_feedback(&fb, 0);
	const struct {
		double v_share;   /* speed as a share of the max, signed */
		double expect;    /* the share of the command let through */
	} cases[] = {
		{ 0.0, 1.0 }, { SAFETY_FADE_START, 1.0 }, { mid, 0.5 },
		{ SAFETY_FADE_END, 0.0 }, { 0.99, 0.0 },
		{ -mid, 1.0 }, { -0.99, 1.0 }, /* braking: never faded */
	};
	for (size_t k = 0; k < sizeof(cases) / sizeof(cases[0]); k++) {
		fb.axis[2].velocity = cases[k].v_share * vmax;
		safety_check_motion(&s, &cfg, &fb, 0);
		/* a second of slew: the filter's steady value */
		safety_filter(&s, &cfg, cmd, out, 1.0, 0);
		assert_float_equal(out[2], 0.08 * cases[k].expect, 1e-12);
	}
	assert_int_equal(s.faults, 0);
	config_defaults(&cfg);
}

/* A step of command reaches the drive at the slew rate, no faster. */
static void test_slew(void **state)
{
	double cmd[ENDOSIM_AXES] = { 30, 0.5, -0.08, 0 };
	double out[ENDOSIM_AXES] = { 0 };
	double dt = 0.001;
	struct safety s;

	(void)state;
	cfg.limits.enable_ramp_s = 0; /* the slew alone */
	safety_init(&s);
	safety_command(&s, SAFETY_ENABLE, 0);
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
	config_defaults(&cfg);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_transitions),
		cmocka_unit_test(test_fault_latches_until_cause_gone),
		cmocka_unit_test(test_feedback_checks),
		cmocka_unit_test(test_filter),
		cmocka_unit_test(test_slew),
		cmocka_unit_test(test_speed_fade),
		cmocka_unit_test(test_enable_ramp),
		cmocka_unit_test(test_saturation),
		cmocka_unit_test(test_saturation_auto),
		cmocka_unit_test(test_motion),
		cmocka_unit_test(test_overrun_budget),
		cmocka_unit_test(test_overrun_fault_setting),
		cmocka_unit_test(test_finite),
		cmocka_unit_test(test_patient_nonfinite),
		cmocka_unit_test(test_inject),
	};

	return cmocka_run_group_tests(tests, setup, NULL);
}
