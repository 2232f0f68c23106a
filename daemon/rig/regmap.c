/* regmap.c - see regmap.h. */
#include "rig/regmap.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <string.h>

static uint16_t swap16(uint16_t w)
{
	return (uint16_t)(w << 8 | w >> 8);
}

static bool bytes_swapped(const struct regspec *r)
{
	return r->order == REGSPEC_BADC || r->order == REGSPEC_DCBA;
}

static bool low_word_first(const struct regspec *r)
{
	return r->order == REGSPEC_CDAB || r->order == REGSPEC_DCBA;
}

/* The raw bits, most significant byte first (ABCD), from the registers. */
static uint32_t gather(const struct regspec *r, const uint16_t *words)
{
	uint16_t w0 = bytes_swapped(r) ? swap16(words[0]) : words[0];
	uint16_t w1;

	if (regspec_words(r) == 1) {
		return w0;
	}
	w1 = bytes_swapped(r) ? swap16(words[1]) : words[1];
	return low_word_first(r) ? (uint32_t)w1 << 16 | w0
				 : (uint32_t)w0 << 16 | w1;
}

static void scatter(const struct regspec *r, uint32_t raw, uint16_t *words)
{
	uint16_t hi = (uint16_t)(raw >> 16), lo = (uint16_t)raw;

	if (regspec_words(r) == 1) {
		words[0] = bytes_swapped(r) ? swap16(lo) : lo;
		return;
	}
	words[0] = low_word_first(r) ? lo : hi;
	words[1] = low_word_first(r) ? hi : lo;
	if (bytes_swapped(r)) {
		words[0] = swap16(words[0]);
		words[1] = swap16(words[1]);
	}
}

static double raw_value(const struct regspec *r, uint32_t raw)
{
	float f;

	switch (r->type) {
	case REGSPEC_I16:
		return (int16_t)raw;
	case REGSPEC_U32:
		return raw;
	case REGSPEC_I32:
		return (int32_t)raw;
	case REGSPEC_F32:
		memcpy(&f, &raw, sizeof(f));
		return f;
	default:
		return (uint16_t)raw;
	}
}

double regmap_decode(const struct regspec *r, const uint16_t *words)
{
	uint32_t raw = regspec_bit(r) ? (words[0] != 0) : gather(r, words);

	return raw_value(r, raw) * r->scale + r->offset;
}

/* Integer limits of R's type (f32 not included). */
static void type_range(const struct regspec *r, double *lo, double *hi)
{
	static const double ranges[][2] = {
		[REGSPEC_U16] = { 0, 65535.0 },
		[REGSPEC_I16] = { -32768.0, 32767.0 },
		[REGSPEC_U32] = { 0, 4294967295.0 },
		[REGSPEC_I32] = { -2147483648.0, 2147483647.0 },
		[REGSPEC_F32] = { -3.4e38, 3.4e38 },
	};

	*lo = regspec_bit(r) ? 0 : ranges[r->type][0];
	*hi = regspec_bit(r) ? 1 : ranges[r->type][1];
}

static uint32_t to_raw(const struct regspec *r, double x)
{
	float f = (float)x;
	uint32_t u;

	if (r->type == REGSPEC_F32) {
		memcpy(&u, &f, sizeof(u));
		return u;
	}
	if (r->type == REGSPEC_I16 || r->type == REGSPEC_I32) {
		return (uint32_t)(int32_t)x;
	}
	return (uint32_t)x;
}

int regmap_encode(const struct regspec *r, double value, uint16_t *words)
{
	double x = (value - r->offset) / r->scale;
	double lo, hi;
	int err = 0;

	type_range(r, &lo, &hi);
	if (isnan(x)) {
		x = 0;
		err = -ERANGE;
	} else if (x < lo || x > hi) {
		x = x < lo ? lo : hi;
		err = -ERANGE;
	}
	if (r->type != REGSPEC_F32) {
		x = round(x);
	}
	if (regspec_bit(r)) {
		words[0] = x != 0;
	} else {
		scatter(r, to_raw(r, x), words);
	}
	return err;
}
