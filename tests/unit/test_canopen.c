/*
 * test_canopen.c - CiA 402 statusword decoding for every state (with the
 * bits that do not identify a state set or not), the controlwords that walk
 * a drive to "operation enabled", and the CiA 301 abort code texts.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "rig/canopen.h"

/* The CiA 402 table (DRIVES.md): state = (sw & mask) == value. */
static const struct {
	uint16_t mask, value;
	enum canopen_state state;
} table[] = {
	{ 0x4F, 0x00, CANOPEN_NOT_READY },
	{ 0x4F, 0x40, CANOPEN_SWITCH_ON_DISABLED },
	{ 0x6F, 0x21, CANOPEN_READY_TO_SWITCH_ON },
	{ 0x6F, 0x23, CANOPEN_SWITCHED_ON },
	{ 0x6F, 0x27, CANOPEN_OPERATION_ENABLED },
	{ 0x6F, 0x07, CANOPEN_QUICK_STOP_ACTIVE },
	{ 0x4F, 0x0F, CANOPEN_FAULT_REACTION_ACTIVE },
	{ 0x4F, 0x08, CANOPEN_FAULT },
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

static void test_every_state_with_any_other_bits(void **state)
{
	(void)state;
	for (size_t i = 0; i < COUNT(table); i++) {
		/* every combination of the bits outside the mask */
		for (uint32_t other = 0; other < 0x10000; other++) {
			uint16_t sw;

			if (other & table[i].mask) {
				continue;
			}
			sw = (uint16_t)(other | table[i].value);
			assert_int_equal(canopen_state(sw), table[i].state);
		}
	}
}

static void test_typical_statuswords(void **state)
{
	(void)state;
	/* as EPOS4 drives report them: remote, voltage enabled set */
	assert_int_equal(canopen_state(0x0240), CANOPEN_SWITCH_ON_DISABLED);
	assert_int_equal(canopen_state(0x0231), CANOPEN_READY_TO_SWITCH_ON);
	assert_int_equal(canopen_state(0x0233), CANOPEN_SWITCHED_ON);
	assert_int_equal(canopen_state(0x0237), CANOPEN_OPERATION_ENABLED);
	assert_int_equal(canopen_state(0x0217), CANOPEN_QUICK_STOP_ACTIVE);
	assert_int_equal(canopen_state(0x021F), CANOPEN_FAULT_REACTION_ACTIVE);
	assert_int_equal(canopen_state(0x0218), CANOPEN_FAULT);
	assert_int_equal(canopen_state(0x0000), CANOPEN_NOT_READY);
}

static void test_unknown_patterns(void **state)
{
	(void)state;
	/* ready-to-switch-on bits with quick stop cleared: no state */
	assert_int_equal(canopen_state(0x0001), CANOPEN_UNKNOWN);
	assert_int_equal(canopen_state(0x0003), CANOPEN_UNKNOWN);
	assert_int_equal(canopen_state(0x0061), CANOPEN_UNKNOWN);
	assert_string_equal(canopen_state_name(CANOPEN_UNKNOWN), "unknown");
}

static void test_canonical_statusword_roundtrip(void **state)
{
	(void)state;
	for (int s = 0; s < CANOPEN_STATES; s++) {
		assert_int_equal(canopen_state(canopen_statusword(s)), s);
	}
}

static void test_walk_to_enabled(void **state)
{
	static const struct {
		enum canopen_state from;
		int r;
		uint16_t cw;
	} steps[] = {
		{ CANOPEN_FAULT, 1, 0x0080 },
		{ CANOPEN_SWITCH_ON_DISABLED, 1, 0x0006 },
		{ CANOPEN_READY_TO_SWITCH_ON, 1, 0x0007 },
		{ CANOPEN_SWITCHED_ON, 1, 0x000F },
		{ CANOPEN_QUICK_STOP_ACTIVE, 1, 0x0000 },
		{ CANOPEN_OPERATION_ENABLED, 0, 0 },
		{ CANOPEN_NOT_READY, -EAGAIN, 0 },
		{ CANOPEN_FAULT_REACTION_ACTIVE, -EAGAIN, 0 },
		{ CANOPEN_UNKNOWN, -EAGAIN, 0 },
	};

	(void)state;
	for (size_t i = 0; i < COUNT(steps); i++) {
		uint16_t cw = 0xFFFF;
		int r = canopen_step_to_enabled(steps[i].from, &cw);

		assert_int_equal(r, steps[i].r);
		if (r == 1) {
			assert_int_equal(cw, steps[i].cw);
		}
	}
}

static void test_abort_texts(void **state)
{
	(void)state;
	assert_string_equal(canopen_abort_text(0x06020000),
			    "object does not exist in the object dictionary");
	assert_string_equal(canopen_abort_text(0x06090030),
			    "value range of parameter exceeded");
	assert_string_equal(canopen_abort_text(0x05040004), "CRC error");
	assert_null(canopen_abort_text(0x12345678));
	assert_null(canopen_abort_text(0));
}

static void test_error_texts(void **state)
{
	(void)state;
	assert_string_equal(canopen_error_text(0x2310),
			    "continuous overcurrent");
	assert_string_equal(canopen_error_text(0x2399), "current");
	assert_string_equal(canopen_error_text(0x4201), "temperature");
	assert_string_equal(canopen_error_text(0xFF01), "device specific");
	assert_string_equal(canopen_error_text(0xF001),
			    "additional functions");
	assert_string_equal(canopen_error_text(0x0000), "no error");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_every_state_with_any_other_bits),
		cmocka_unit_test(test_typical_statuswords),
		cmocka_unit_test(test_unknown_patterns),
		cmocka_unit_test(test_canonical_statusword_roundtrip),
		cmocka_unit_test(test_walk_to_enabled),
		cmocka_unit_test(test_abort_texts),
		cmocka_unit_test(test_error_texts),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
