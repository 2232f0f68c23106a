/*
 * test_regmap.c - Modbus register map conversions (rig/regmap.h): every
 * type in every byte and word order against raw words written out by
 * hand, scale and offset both ways, rounding and clamping, bits; and the
 * register's description in its text form (conf/regspec.h).
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "conf/regspec.h"
#include "rig/regmap.h"

static struct regspec reg(uint8_t table, uint8_t type, uint8_t order)
{
	return (struct regspec){ .table = table, .type = type,
				    .order = order, .address = 0x10,
				    .scale = 1.0 };
}

/* Bytes A B C D = 0x11 0x22 0x33 0x44, as each order puts them. */
static const struct {
	uint8_t order;
	uint16_t w[2];
} orders32[] = {
	{ REGSPEC_ABCD, { 0x1122, 0x3344 } },
	{ REGSPEC_CDAB, { 0x3344, 0x1122 } },
	{ REGSPEC_BADC, { 0x2211, 0x4433 } },
	{ REGSPEC_DCBA, { 0x4433, 0x2211 } },
};

static void test_u32_i32_orders(void **state)
{
	(void)state;
	for (size_t i = 0; i < 4; i++) {
		struct regspec u = reg(REGSPEC_INPUT, REGSPEC_U32,
					  orders32[i].order);
		struct regspec s = reg(REGSPEC_INPUT, REGSPEC_I32,
					  orders32[i].order);
		uint16_t w[2];

		assert_int_equal(regspec_words(&u), 2);
		assert_true(regmap_decode(&u, orders32[i].w) == 0x11223344);
		assert_true(regmap_decode(&s, orders32[i].w) == 0x11223344);
		assert_int_equal(regmap_encode(&u, 0x11223344, w), 0);
		assert_memory_equal(w, orders32[i].w, sizeof(w));
	}
}

static void test_negative_i32(void **state)
{
	/* -2 = 0xFFFFFFFE: bytes FF FF FF FE */
	static const uint16_t abcd[] = { 0xFFFF, 0xFFFE };
	static const uint16_t cdab[] = { 0xFFFE, 0xFFFF };
	static const uint16_t badc[] = { 0xFFFF, 0xFEFF };
	struct regspec r = reg(REGSPEC_HOLDING, REGSPEC_I32, REGSPEC_ABCD);
	uint16_t w[2];

	(void)state;
	assert_true(regmap_decode(&r, abcd) == -2.0);
	r.order = REGSPEC_CDAB;
	assert_true(regmap_decode(&r, cdab) == -2.0);
	regmap_encode(&r, -2.0, w);
	assert_memory_equal(w, cdab, sizeof(w));
	r.order = REGSPEC_BADC;
	assert_true(regmap_decode(&r, badc) == -2.0);
	r.type = REGSPEC_U32;
	assert_true(regmap_decode(&r, badc) == 4294967294.0);
}

static void test_f32_orders(void **state)
{
	/* -1.5f = 0xBFC00000 */
	static const struct {
		uint8_t order;
		uint16_t w[2];
	} f[] = {
		{ REGSPEC_ABCD, { 0xBFC0, 0x0000 } },
		{ REGSPEC_CDAB, { 0x0000, 0xBFC0 } },
		{ REGSPEC_BADC, { 0xC0BF, 0x0000 } },
		{ REGSPEC_DCBA, { 0x0000, 0xC0BF } },
	};

	(void)state;
	for (size_t i = 0; i < 4; i++) {
		struct regspec r = reg(REGSPEC_INPUT, REGSPEC_F32, f[i].order);
		uint16_t w[2];

		assert_true(regmap_decode(&r, f[i].w) == -1.5);
		assert_int_equal(regmap_encode(&r, -1.5, w), 0);
		assert_memory_equal(w, f[i].w, sizeof(w));
	}
}

static void test_16_bit_orders(void **state)
{
	static const uint16_t ab[] = { 0x1234 }, ba[] = { 0x3412 };
	static const uint16_t neg[] = { 0xFFFE }, neg_ba[] = { 0xFEFF };
	struct regspec r = reg(REGSPEC_HOLDING, REGSPEC_U16, REGSPEC_ABCD);
	uint16_t w[1];

	(void)state;
	assert_int_equal(regspec_words(&r), 1);
	assert_true(regmap_decode(&r, ab) == 0x1234);
	r.order = REGSPEC_CDAB; /* word order means nothing to one word */
	assert_true(regmap_decode(&r, ab) == 0x1234);
	r.order = REGSPEC_BADC;
	assert_true(regmap_decode(&r, ba) == 0x1234);
	regmap_encode(&r, 0x1234, w);
	assert_int_equal(w[0], 0x3412);
	r.order = REGSPEC_DCBA;
	assert_true(regmap_decode(&r, ba) == 0x1234);
	r = reg(REGSPEC_HOLDING, REGSPEC_I16, REGSPEC_ABCD);
	assert_true(regmap_decode(&r, neg) == -2.0);
	r.order = REGSPEC_BADC;
	assert_true(regmap_decode(&r, neg_ba) == -2.0);
}

static void test_scale_offset(void **state)
{
	static const uint16_t raw[] = { 0xFF9C }; /* -100 */
	struct regspec r = reg(REGSPEC_HOLDING, REGSPEC_I16, REGSPEC_ABCD);
	uint16_t w[1];

	(void)state;
	r.scale = 1e-3;
	r.offset = 0.5;
	assert_true(fabs(regmap_decode(&r, raw) - 0.4) < 1e-12);
	assert_int_equal(regmap_encode(&r, 0.4, w), 0);
	assert_int_equal(w[0], 0xFF9C);
	/* rounded to the nearest count */
	assert_int_equal(regmap_encode(&r, 0.40049, w), 0);
	assert_int_equal(w[0], 0xFF9C);
	assert_int_equal(regmap_encode(&r, 0.4006, w), 0);
	assert_int_equal(w[0], 0xFF9D);
}

static void test_clamped(void **state)
{
	struct regspec r = reg(REGSPEC_HOLDING, REGSPEC_I16, REGSPEC_ABCD);
	uint16_t w[2];

	(void)state;
	assert_int_equal(regmap_encode(&r, 40000, w), -ERANGE);
	assert_int_equal(w[0], 0x7FFF);
	assert_int_equal(regmap_encode(&r, -40000, w), -ERANGE);
	assert_int_equal(w[0], 0x8000);
	assert_int_equal(regmap_encode(&r, NAN, w), -ERANGE);
	assert_int_equal(w[0], 0);
	r.type = REGSPEC_U16;
	assert_int_equal(regmap_encode(&r, -1, w), -ERANGE);
	assert_int_equal(w[0], 0);
	r.type = REGSPEC_U32;
	assert_int_equal(regmap_encode(&r, 5e9, w), -ERANGE);
	assert_int_equal(w[0], 0xFFFF);
	assert_int_equal(w[1], 0xFFFF);
	r.type = REGSPEC_I32;
	assert_int_equal(regmap_encode(&r, -3e9, w), -ERANGE);
	assert_int_equal(w[0], 0x8000);
	assert_int_equal(w[1], 0x0000);
}

static void test_bits(void **state)
{
	static const uint16_t on[] = { 1 }, off[] = { 0 };
	struct regspec r = reg(REGSPEC_COIL, REGSPEC_U16, REGSPEC_ABCD);
	uint16_t w[1];

	(void)state;
	assert_true(regspec_writable(&r));
	assert_true(regmap_decode(&r, on) == 1.0);
	assert_true(regmap_decode(&r, off) == 0.0);
	regmap_encode(&r, 1.0, w);
	assert_int_equal(w[0], 1);
	assert_int_equal(regmap_encode(&r, 2.0, w), -ERANGE);
	assert_int_equal(w[0], 1);
	r.table = REGSPEC_DISCRETE;
	assert_false(regspec_writable(&r));
	r.table = REGSPEC_INPUT;
	assert_false(regspec_writable(&r));
	r.table = REGSPEC_NONE;
	assert_int_equal(regspec_words(&r), 0);
}

static void test_parse(void **state)
{
	struct regspec r;
	char why[200];

	(void)state;
	assert_int_equal(regspec_parse("input 0x0002 i32 cdab scale=0.001 "
				      "offset=-2", &r, why, sizeof(why)), 0);
	assert_int_equal(r.table, REGSPEC_INPUT);
	assert_int_equal(r.address, 2);
	assert_int_equal(r.type, REGSPEC_I32);
	assert_int_equal(r.order, REGSPEC_CDAB);
	assert_true(r.scale == 0.001 && r.offset == -2);
	assert_int_equal(regspec_parse("coil 17", &r, why, sizeof(why)), 0);
	assert_int_equal(r.table, REGSPEC_COIL);
	assert_int_equal(r.address, 17);
	assert_int_equal(r.type, REGSPEC_U16);
	assert_true(r.scale == 1.0 && r.offset == 0.0);
	assert_int_equal(regspec_parse("none", &r, why, sizeof(why)), 0);
	assert_int_equal(r.table, REGSPEC_NONE);
	assert_int_equal(regspec_parse("holding 65535 ba", &r, why,
				      sizeof(why)), 0);
	assert_int_equal(r.order, REGSPEC_BADC);
}

static void test_parse_errors(void **state)
{
	static const char *const bad[] = {
		"", "register 1 u16", "holding", "holding x", "holding 65536",
		"holding 1 i23", "holding 1 scale=0", "holding 1 scale=abc",
		"holding 1 offset=", "coil 1 i32", "none 1",
	};
	struct regspec r = reg(REGSPEC_INPUT, REGSPEC_F32, REGSPEC_DCBA);
	char why[200];

	(void)state;
	for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		why[0] = '\0';
		assert_int_equal(regspec_parse(bad[i], &r, why, sizeof(why)),
				 -EINVAL);
		assert_true(why[0] != '\0');
		/* unchanged on error */
		assert_int_equal(r.table, REGSPEC_INPUT);
		assert_int_equal(r.type, REGSPEC_F32);
	}
}

static void test_format_roundtrip(void **state)
{
	static const char *const texts[] = {
		"holding 0x0010 i16 scale=1e-05",
		"input 0x0000 i32 cdab",
		"input 0x0002 f32 dcba scale=0.5 offset=-1",
		"coil 0x0001 u16",
		"holding 0x0003 u16 ba",
		"none",
	};
	char buf[160], why[200];
	struct regspec r;

	(void)state;
	for (size_t i = 0; i < sizeof(texts) / sizeof(texts[0]); i++) {
		assert_int_equal(regspec_parse(texts[i], &r, why, sizeof(why)),
				 0);
		regspec_format(&r, buf, sizeof(buf));
		assert_string_equal(buf, texts[i]);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_u32_i32_orders),
		cmocka_unit_test(test_negative_i32),
		cmocka_unit_test(test_f32_orders),
		cmocka_unit_test(test_16_bit_orders),
		cmocka_unit_test(test_scale_offset),
		cmocka_unit_test(test_clamped),
		cmocka_unit_test(test_bits),
		cmocka_unit_test(test_parse),
		cmocka_unit_test(test_parse_errors),
		cmocka_unit_test(test_format_roundtrip),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
