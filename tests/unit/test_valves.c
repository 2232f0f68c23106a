/*
 * test_valves.c - the handle's valves and the tool in the working channel
 * on a real rig, without emulators: an EPOS4's digital inputs word to
 * valves, a Modbus input's description to pressed or not, an analogue
 * input's voltage to the tool's opening, the rules by which the force
 * loop takes a drive's valves and tool (bus_valves(), bus_tool()), and a
 * bus thread (bus.h) over a scripted drive backend: pressed (the tool as
 * read) while its exchanges succeed, released (the tool still, the pedal
 * up) when its feedback grows old, a transaction fails (its own or the
 * other drive's on its bus), the drive faults or vanishes.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "base/mono.h"
#include "conf/regspec.h"
#include "rig/bus.h"
#include "rig/drive.h"
#include "rig/regmap.h"

#define AIR ENDOSIM_VALVE_AIR
#define WATER ENDOSIM_VALVE_WATER
#define SUCTION ENDOSIM_VALVE_SUCTION
#define PRESENT ENDOSIM_DRIVE_PRESENT
#define MS 1000000ull

static void test_inputs_word(void **state)
{
	const int bit[CONFIG_VALVES] = { 16, -1, 31 };
	const int none[CONFIG_VALVES] = { -1, -1, -1 };

	(void)state;
	assert_int_equal(drive_valves_of_inputs(0, bit), 0);
	assert_int_equal(drive_valves_of_inputs(1u << 16, bit), AIR);
	assert_int_equal(drive_valves_of_inputs(1u << 31, bit), SUCTION);
	/* the limit switches and the other inputs are no valve */
	assert_int_equal(drive_valves_of_inputs(0x7FFEFFFFu, bit), 0);
	assert_int_equal(drive_valves_of_inputs(0xFFFFFFFFu, bit),
			 AIR | SUCTION);
	assert_int_equal(drive_valves_of_inputs(0xFFFFFFFFu, none), 0);
}

/* A Modbus valve: a discrete input, or one that opens when pressed. */
static void test_modbus_input(void **state)
{
	struct regspec plain, inverted;
	uint16_t raw;
	char why[128];

	(void)state;
	assert_int_equal(regspec_parse("discrete 0x0010", &plain, why,
				       sizeof(why)), 0);
	assert_int_equal(regspec_parse("discrete 0x0010 u16 scale=-1 offset=1",
				       &inverted, why, sizeof(why)), 0);
	assert_true(regspec_bit(&plain));
	raw = 1;
	assert_true(regmap_decode(&plain, &raw) != 0.0);
	assert_true(regmap_decode(&inverted, &raw) == 0.0);
	raw = 0;
	assert_true(regmap_decode(&plain, &raw) == 0.0);
	assert_true(regmap_decode(&inverted, &raw) != 0.0);
}

/* The loop's rule, case by case. */
static void test_taking_rule(void **state)
{
	const uint64_t now = 10000 * MS, age = 50 * MS;
	struct rig_axis_feedback f = { .stamp_ns = now - 10 * MS,
				       .status = PRESENT };

	(void)state;
	/* fresh: the drive's valves as read, the hand's others kept, the
	 * hand's press of a mapped valve not */
	assert_int_equal(bus_valves(0, AIR, AIR, &f, now, age), AIR);
	assert_int_equal(bus_valves(WATER | SUCTION, AIR | SUCTION, AIR, &f,
				    now, age), WATER | AIR);
	assert_int_equal(bus_valves(WATER, AIR, SUCTION, &f, now, age),
			 WATER);
	/* stamped after the cycle began (the bus thread's clock): fresh */
	f.stamp_ns = now + 2 * MS;
	assert_int_equal(bus_valves(0, AIR, AIR, &f, now, age), AIR);
	/* exactly as old as allowed, then older */
	f.stamp_ns = now - age;
	assert_int_equal(bus_valves(0, AIR, AIR, &f, now, age), AIR);
	f.stamp_ns = now - age - 1;
	assert_int_equal(bus_valves(WATER, AIR, AIR, &f, now, age), WATER);
	/* lost: gone, faulted, a failed transaction */
	f.stamp_ns = now;
	f.status = 0;
	assert_int_equal(bus_valves(WATER, AIR, AIR, &f, now, age), WATER);
	f.status = PRESENT | ENDOSIM_DRIVE_FAULT;
	assert_int_equal(bus_valves(0, AIR, AIR, &f, now, age), 0);
	f.status = PRESENT | ENDOSIM_DRIVE_BUS_ERROR;
	assert_int_equal(bus_valves(0, AIR, AIR, &f, now, age), 0);
	/* nothing mapped: the hand's alone, whatever the drive */
	assert_int_equal(bus_valves(AIR | WATER, 0, AIR, &f, now, age),
			 AIR | WATER);
}

/* The handle's opening from an analogue input, either way round. */
static void test_tool_opening(void **state)
{
	(void)state;
	assert_true(drive_tool_opening(0, 0, 5000) == 0.0);
	assert_true(fabs(drive_tool_opening(1250, 0, 5000) - 0.25) < 1e-12);
	assert_true(drive_tool_opening(5000, 0, 5000) == 1.0);
	/* beyond the travel (a noisy wire): clamped */
	assert_true(drive_tool_opening(-300, 0, 5000) == 0.0);
	assert_true(drive_tool_opening(9000, 0, 5000) == 1.0);
	/* a potentiometer wired the other way */
	assert_true(fabs(drive_tool_opening(1000, 5000, 0) - 0.8) < 1e-12);
}

#define DEPTH CONFIG_TOOL_DEPTH
#define OPENING CONFIG_TOOL_OPENING
#define PEDAL CONFIG_TOOL_PEDAL

/* The hand's tool: the simulated rig's reading before the buses'. */
static void hands_tool(struct rig_feedback *fb)
{
	fb->tool_depth_m = 0.25;
	fb->tool_opening = 0.5;
	fb->tool_pedal = true;
}

/* The loop's rule for the tool, case by case. */
static void test_tool_rule(void **state)
{
	const uint64_t now = 10000 * MS, age = 50 * MS;
	const struct drive_tool read = { 0.012, 0.75, false };
	struct rig_axis_feedback f = { .stamp_ns = now - 10 * MS,
				       .status = PRESENT };
	struct rig_feedback fb;

	(void)state;
	/* fresh: as read, the pedal up as read */
	hands_tool(&fb);
	bus_tool(&fb, DEPTH | OPENING | PEDAL, &read, &f, now, age);
	assert_true(fb.tool_depth_m == 0.012 && fb.tool_opening == 0.75);
	assert_false(fb.tool_pedal);
	/* the pedal on no drive: the hand's */
	hands_tool(&fb);
	bus_tool(&fb, DEPTH | OPENING, &read, &f, now, age);
	assert_true(fb.tool_depth_m == 0.012 && fb.tool_pedal);
	/* nothing mapped: the hand's alone, whatever the drive */
	hands_tool(&fb);
	bus_tool(&fb, 0, &read, &f, now, age);
	assert_true(fb.tool_depth_m == 0.25 && fb.tool_opening == 0.5);
	/* stale, gone, faulted, a failed transaction: still, pedal up */
	for (int k = 0; k < 4; k++) {
		f.stamp_ns = k == 0 ? now - age - 1 : now;
		f.status = k == 1 ? 0
			   : k == 2 ? PRESENT | ENDOSIM_DRIVE_FAULT
			   : k == 3 ? PRESENT | ENDOSIM_DRIVE_BUS_ERROR
				    : PRESENT;
		hands_tool(&fb);
		bus_tool(&fb, DEPTH | OPENING | PEDAL, &read, &f, now, age);
		assert_true(isnan(fb.tool_depth_m) && isnan(fb.tool_opening));
		assert_false(fb.tool_pedal);
	}
}

/* --- a bus over a scripted drive -------------------------------------- */

enum fake_mode {
	FAKE_OK,
	FAKE_SLOW,       /* an exchange hangs while the mode is so */
	FAKE_LATE,       /* drive 0 does not answer */
	FAKE_LATE_OTHER, /* drive 1 does not answer */
	FAKE_FAULT,      /* drive 0 faults */
	FAKE_GONE,       /* the device is unplugged */
};

struct fake {
	struct drive d;
	_Atomic int mode;
	_Atomic uint32_t pressed; /* what its inputs read */
	_Atomic int tool_mm;      /* the tool's depth, mm */
	_Atomic int opening_pc;   /* its handle, % open */
	_Atomic bool pedal;
};

static void nap_ms(long ms)
{
	struct timespec ts = { .tv_sec = ms / 1000,
			       .tv_nsec = (ms % 1000) * 1000000 };

	nanosleep(&ts, NULL);
}

static int fake_open(struct drive *d)
{
	struct fake *f = (struct fake *)d;

	return atomic_load(&f->mode) == FAKE_GONE
		       ? drive_fail(d, -1, -ENODEV, "not there") : 0;
}

static int fake_step(struct drive *d, int i)
{
	(void)d;
	(void)i;
	return 0;
}

static int fake_exchange(struct drive *d, const double *setpoint,
			 struct drive_sample *s)
{
	struct fake *f = (struct fake *)d;
	int mode = atomic_load(&f->mode);

	(void)setpoint;
	memset(s, 0, sizeof(*s) * (size_t)d->n);
	switch (mode) {
	case FAKE_SLOW:
		while (atomic_load(&f->mode) == FAKE_SLOW) {
			nap_ms(10);
		}
		break;
	case FAKE_LATE:
		return drive_fail(d, 0, -ETIMEDOUT, "no reply");
	case FAKE_LATE_OTHER:
		return drive_fail(d, 1, -ETIMEDOUT, "no reply");
	case FAKE_FAULT:
		s->fault = true;
		s->code = 0x1234;
		break;
	case FAKE_GONE:
		return drive_fail(d, -1, -ENODEV, "unplugged");
	default:
		break;
	}
	s->valves = atomic_load(&f->pressed) & d->valves[0];
	s->tool.depth_m = atomic_load(&f->tool_mm) * 1e-3;
	s->tool.opening = atomic_load(&f->opening_pc) * 1e-2;
	s->tool.pedal = atomic_load(&f->pedal);
	return 0;
}

static void fake_close(struct drive *d)
{
	(void)d;
}

static void fake_destroy(struct drive *d)
{
	free(d);
}

static const char *fake_describe(uint32_t code)
{
	(void)code;
	return "scripted";
}

static const struct drive_ops fake_ops = {
	.kind = "fake",
	.open = fake_open,
	.bring_up = fake_step,
	.exchange = fake_exchange,
	.bring_down = fake_step,
	.clear_fault = fake_step,
	.close = fake_close,
	.destroy = fake_destroy,
	.describe_fault = fake_describe,
};

struct rig_valves {
	struct bus *b;
	struct fake *f;
	struct rig_feedback fb;
};

/* The loop's cycle now, the hand pressing WATER and SUCTION. */
static uint32_t fetch(struct rig_valves *r)
{
	r->fb.valves = WATER | SUCTION;
	bus_fetch(r->b, mono_ns(), &r->fb);
	return r->fb.valves;
}

/* The tool as the loop's cycle now reads it: depth mm, opening %, pedal
 * (-1, -1: still), as "MM PC PEDAL". */
static void tool_now(struct rig_valves *r, char *buf, size_t size)
{
	fetch(r);
	if (isnan(r->fb.tool_depth_m) || isnan(r->fb.tool_opening)) {
		snprintf(buf, size, "-1 -1 %d", r->fb.tool_pedal);
		return;
	}
	snprintf(buf, size, "%.0f %.0f %d", r->fb.tool_depth_m * 1e3,
		 r->fb.tool_opening * 1e2, r->fb.tool_pedal);
}

/*
 * The loop's command this cycle, torque off: with ACK, it acknowledges
 * the faults it has seen, as the loop does each cycle until they clear.
 */
static void post(struct rig_valves *r, bool ack)
{
	const double zero[ENDOSIM_AXES] = { 0 };

	if (ack) {
		bus_post(r->b, mono_ns(), zero, false);
	}
}

/* Polls (as the loop does, acknowledging with ACK) until the tool reads
 * WANT, up to 3 s. */
static bool tool_reads(struct rig_valves *r, const char *want, bool ack)
{
	uint64_t end = mono_ns() + 3000 * MS;
	char now[64];

	while (mono_ns() < end) {
		post(r, ack);
		tool_now(r, now, sizeof(now));
		if (!strcmp(now, want)) {
			return true;
		}
		nap_ms(1);
	}
	fail_msg("the tool reads '%s', not '%s'", now, want);
	return false;
}

/* Polls (as the loop does, acknowledging with ACK) until the valves
 * read WANT, up to 3 s. */
static bool reads(struct rig_valves *r, uint32_t want, bool ack)
{
	uint64_t end = mono_ns() + 3000 * MS;

	while (mono_ns() < end) {
		post(r, ack);
		if (fetch(r) == want) {
			return true;
		}
		nap_ms(1);
	}
	return false;
}

static int bus_setup(void **state)
{
	const struct bus_params p = { .max_rate_hz = 1000,
				      .feedback_max_age_s = 0.05,
				      .priority = 1 };
	struct rig_valves *r = calloc(1, sizeof(*r));

	r->f = calloc(1, sizeof(*r->f));
	r->f->d.ops = &fake_ops;
	r->f->d.n = 2; /* drive 0 reads the valves, drive 1 none */
	r->f->d.axis[0] = ENDOSIM_AXIS_WHEEL_UD;
	r->f->d.axis[1] = ENDOSIM_AXIS_WHEEL_LR;
	r->f->d.valves[0] = AIR | SUCTION;
	r->f->d.tool[0] = DEPTH | OPENING | PEDAL;
	strcpy(r->f->d.name, "fake");
	strcpy(r->f->d.unit[0], "drive 1");
	strcpy(r->f->d.unit[1], "drive 2");
	r->b = bus_create(&r->f->d, &p);
	assert_non_null(r->b);
	assert_int_equal(bus_open(r->b), 0);
	assert_int_equal(bus_start(r->b), 0);
	*state = r;
	return 0;
}

static int bus_teardown(void **state)
{
	struct rig_valves *r = *state;

	atomic_store(&r->f->mode, FAKE_OK); /* a failed test's hang ends */
	bus_destroy(r->b);
	free(r);
	return 0;
}

#define WANT(r, v) assert_true(reads(r, v, false))

/*
 * What the drive reads replaces the hand's mapped valves (SUCTION, not
 * pressed on the drive, reads released), the hand keeps WATER.
 */
static void test_bus_pressed(void **state)
{
	struct rig_valves *r = *state;

	atomic_store(&r->f->pressed, AIR | WATER);
	WANT(r, AIR | WATER);
	atomic_store(&r->f->pressed, SUCTION);
	WANT(r, WATER | SUCTION);
	atomic_store(&r->f->pressed, 0);
	WANT(r, WATER);
}

/* An exchange that hangs: released once the feedback is too old. */
static void test_bus_stale(void **state)
{
	struct rig_valves *r = *state;

	atomic_store(&r->f->pressed, AIR);
	WANT(r, AIR | WATER);
	atomic_store(&r->f->mode, FAKE_SLOW);
	WANT(r, WATER);
	assert_true(r->fb.axis[ENDOSIM_AXIS_WHEEL_UD].status & PRESENT);
	atomic_store(&r->f->mode, FAKE_OK);
	WANT(r, AIR | WATER);
}

/*
 * A failed transaction, with the drive or with the other drive on its bus
 * (whose failure ends the exchange before the valves' reading counts), a
 * drive fault, a vanished drive: released until the cause is gone and
 * the loop has seen it.
 */
static void test_bus_lost(void **state)
{
	static const int causes[] = { FAKE_LATE, FAKE_LATE_OTHER, FAKE_FAULT,
				      FAKE_GONE };
	struct rig_valves *r = *state;

	atomic_store(&r->f->pressed, AIR);
	for (size_t i = 0; i < sizeof(causes) / sizeof(causes[0]); i++) {
		WANT(r, AIR | WATER);
		atomic_store(&r->f->mode, causes[i]);
		WANT(r, WATER);
		nap_ms(100); /* and stays so */
		assert_int_equal(fetch(r), WATER);
		atomic_store(&r->f->mode, FAKE_OK);
		assert_true(reads(r, AIR | WATER, true));
	}
}

/*
 * The tool through a bus: as read while the exchanges succeed; still with
 * the pedal up while they hang, fail (its own or the other drive's), the
 * drive faults or vanishes; as read again once the cause is gone.
 */
static void test_bus_tool(void **state)
{
	static const int causes[] = { FAKE_SLOW, FAKE_LATE, FAKE_LATE_OTHER,
				      FAKE_FAULT, FAKE_GONE };
	struct rig_valves *r = *state;
	char now[64];

	atomic_store(&r->f->tool_mm, 12);
	atomic_store(&r->f->opening_pc, 75);
	atomic_store(&r->f->pedal, true);
	assert_true(tool_reads(r, "12 75 1", false));
	atomic_store(&r->f->tool_mm, -3);
	atomic_store(&r->f->pedal, false);
	assert_true(tool_reads(r, "-3 75 0", false));
	atomic_store(&r->f->pedal, true);
	assert_true(tool_reads(r, "-3 75 1", false));
	for (size_t i = 0; i < sizeof(causes) / sizeof(causes[0]); i++) {
		atomic_store(&r->f->mode, causes[i]);
		assert_true(tool_reads(r, "-1 -1 0", false));
		nap_ms(100); /* and stays so */
		tool_now(r, now, sizeof(now));
		assert_string_equal(now, "-1 -1 0");
		atomic_store(&r->f->mode, FAKE_OK);
		/* back once the loop has acknowledged what it last saw (a
		 * valve, unpressed, cannot tell: the hand's WATER reads
		 * either way) */
		assert_true(tool_reads(r, "-3 75 1", true));
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_inputs_word),
		cmocka_unit_test(test_modbus_input),
		cmocka_unit_test(test_taking_rule),
		cmocka_unit_test(test_tool_opening),
		cmocka_unit_test(test_tool_rule),
		cmocka_unit_test_setup_teardown(test_bus_pressed, bus_setup,
						bus_teardown),
		cmocka_unit_test_setup_teardown(test_bus_stale, bus_setup,
						bus_teardown),
		cmocka_unit_test_setup_teardown(test_bus_lost, bus_setup,
						bus_teardown),
		cmocka_unit_test_setup_teardown(test_bus_tool, bus_setup,
						bus_teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
