/* regmap.c - see regmap.h. */
#include "conf/regmap.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

static const char *const signal_names[REGMAP_SIGNALS] = {
	"torque", "enable", "position", "velocity", "fault", "fault_reset",
	"watchdog",
};

static const char *const table_names[] = {
	[REGMAP_NONE] = "none", [REGMAP_COIL] = "coil",
	[REGMAP_DISCRETE] = "discrete", [REGMAP_INPUT] = "input",
	[REGMAP_HOLDING] = "holding",
};

static const char *const type_names[] = {
	[REGMAP_U16] = "u16", [REGMAP_I16] = "i16", [REGMAP_U32] = "u32",
	[REGMAP_I32] = "i32", [REGMAP_F32] = "f32",
};

static const struct {
	const char *name;
	enum regmap_order order;
} order_names[] = {
	{ "abcd", REGMAP_ABCD }, { "cdab", REGMAP_CDAB },
	{ "badc", REGMAP_BADC }, { "dcba", REGMAP_DCBA },
	{ "ab", REGMAP_ABCD },   { "ba", REGMAP_BADC },
};

const char *regmap_signal_name(enum regmap_signal s)
{
	return s < REGMAP_SIGNALS ? signal_names[s] : "?";
}

static bool is_bit(const struct regmap_reg *r)
{
	return r->table == REGMAP_COIL || r->table == REGMAP_DISCRETE;
}

int regmap_words(const struct regmap_reg *r)
{
	if (r->table == REGMAP_NONE) {
		return 0;
	}
	return r->type == REGMAP_U16 || r->type == REGMAP_I16 ? 1 : 2;
}

bool regmap_writable(const struct regmap_reg *r)
{
	return r->table == REGMAP_COIL || r->table == REGMAP_HOLDING;
}

static uint16_t swap16(uint16_t w)
{
	return (uint16_t)(w << 8 | w >> 8);
}

static bool bytes_swapped(const struct regmap_reg *r)
{
	return r->order == REGMAP_BADC || r->order == REGMAP_DCBA;
}

static bool low_word_first(const struct regmap_reg *r)
{
	return r->order == REGMAP_CDAB || r->order == REGMAP_DCBA;
}

/* The raw bits, most significant byte first (ABCD), from the registers. */
static uint32_t gather(const struct regmap_reg *r, const uint16_t *words)
{
	uint16_t w0 = bytes_swapped(r) ? swap16(words[0]) : words[0];
	uint16_t w1;

	if (regmap_words(r) == 1) {
		return w0;
	}
	w1 = bytes_swapped(r) ? swap16(words[1]) : words[1];
	return low_word_first(r) ? (uint32_t)w1 << 16 | w0
				 : (uint32_t)w0 << 16 | w1;
}

static void scatter(const struct regmap_reg *r, uint32_t raw, uint16_t *words)
{
	uint16_t hi = (uint16_t)(raw >> 16), lo = (uint16_t)raw;

	if (regmap_words(r) == 1) {
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

static double raw_value(const struct regmap_reg *r, uint32_t raw)
{
	float f;

	switch (r->type) {
	case REGMAP_I16:
		return (int16_t)raw;
	case REGMAP_U32:
		return raw;
	case REGMAP_I32:
		return (int32_t)raw;
	case REGMAP_F32:
		memcpy(&f, &raw, sizeof(f));
		return f;
	default:
		return (uint16_t)raw;
	}
}

double regmap_decode(const struct regmap_reg *r, const uint16_t *words)
{
	uint32_t raw = is_bit(r) ? (words[0] != 0) : gather(r, words);

	return raw_value(r, raw) * r->scale + r->offset;
}

/* Integer limits of R's type (f32 not included). */
static void type_range(const struct regmap_reg *r, double *lo, double *hi)
{
	static const double ranges[][2] = {
		[REGMAP_U16] = { 0, 65535.0 },
		[REGMAP_I16] = { -32768.0, 32767.0 },
		[REGMAP_U32] = { 0, 4294967295.0 },
		[REGMAP_I32] = { -2147483648.0, 2147483647.0 },
		[REGMAP_F32] = { -3.4e38, 3.4e38 },
	};

	*lo = is_bit(r) ? 0 : ranges[r->type][0];
	*hi = is_bit(r) ? 1 : ranges[r->type][1];
}

static uint32_t to_raw(const struct regmap_reg *r, double x)
{
	float f = (float)x;
	uint32_t u;

	if (r->type == REGMAP_F32) {
		memcpy(&u, &f, sizeof(u));
		return u;
	}
	if (r->type == REGMAP_I16 || r->type == REGMAP_I32) {
		return (uint32_t)(int32_t)x;
	}
	return (uint32_t)x;
}

int regmap_encode(const struct regmap_reg *r, double value, uint16_t *words)
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
	if (r->type != REGMAP_F32) {
		x = round(x);
	}
	if (is_bit(r)) {
		words[0] = x != 0;
	} else {
		scatter(r, to_raw(r, x), words);
	}
	return err;
}

/* --- the text form ---------------------------------------------------- */

static int find_name(const char *const *names, size_t n, const char *word)
{
	for (size_t i = 0; i < n; i++) {
		if (names[i] && !strcmp(names[i], word)) {
			return (int)i;
		}
	}
	return -1;
}

static int parse_double(const char *text, double *out)
{
	char *end;

	errno = 0;
	*out = strtod(text, &end);
	return !*text || *end || errno || !isfinite(*out) ? -EINVAL : 0;
}

/* One optional word after the address: a type, an order, scale=, offset=. */
static int parse_option(const char *word, struct regmap_reg *r, char *why,
			size_t size)
{
	int i = find_name(type_names, COUNT(type_names), word);

	if (i >= 0) {
		r->type = (uint8_t)i;
		return 0;
	}
	for (size_t k = 0; k < COUNT(order_names); k++) {
		if (!strcmp(word, order_names[k].name)) {
			r->order = (uint8_t)order_names[k].order;
			return 0;
		}
	}
	if (!strncmp(word, "scale=", 6)) {
		if (parse_double(word + 6, &r->scale) || r->scale == 0) {
			snprintf(why, size, "scale '%s' is not a number other "
				 "than 0", word + 6);
			return -EINVAL;
		}
		return 0;
	}
	if (!strncmp(word, "offset=", 7)) {
		if (parse_double(word + 7, &r->offset)) {
			snprintf(why, size, "offset '%s' is not a number",
				 word + 7);
			return -EINVAL;
		}
		return 0;
	}
	snprintf(why, size, "'%s' is not a type (u16, i16, u32, i32, f32), "
		 "an order (abcd, cdab, badc, dcba), scale= or offset=", word);
	return -EINVAL;
}

static int parse_address(const char *word, struct regmap_reg *r, char *why,
			 size_t size)
{
	char *end;
	unsigned long a;

	errno = 0;
	a = word ? strtoul(word, &end, 0) : 0;
	if (!word || !*word || *end || errno || a > 0xFFFF) {
		snprintf(why, size, "expected an address 0..65535 after the "
			 "table");
		return -EINVAL;
	}
	r->address = (uint16_t)a;
	return 0;
}

/* Parses the words of TEXT into R. */
static int parse_words(char *text, struct regmap_reg *r, char *why,
		       size_t size)
{
	char *save = NULL;
	char *word = strtok_r(text, " \t", &save);
	int t = word ? find_name(table_names, COUNT(table_names), word) : -1;

	if (t < 0) {
		snprintf(why, size, "expected none, coil, discrete, input or "
			 "holding, not '%s'", word ? word : "");
		return -EINVAL;
	}
	r->table = (uint8_t)t;
	if (t == REGMAP_NONE) {
		word = strtok_r(NULL, " \t", &save);
		if (word) {
			snprintf(why, size, "nothing may follow none");
			return -EINVAL;
		}
		return 0;
	}
	if (parse_address(strtok_r(NULL, " \t", &save), r, why, size)) {
		return -EINVAL;
	}
	while ((word = strtok_r(NULL, " \t", &save))) {
		if (parse_option(word, r, why, size)) {
			return -EINVAL;
		}
	}
	if (is_bit(r) && r->type != REGMAP_U16) {
		snprintf(why, size, "a %s holds one bit: its type is u16",
			 table_names[t]);
		return -EINVAL;
	}
	return 0;
}

int regmap_parse(const char *text, struct regmap_reg *r, char *why,
		 size_t size)
{
	struct regmap_reg tmp = { .type = REGMAP_U16, .scale = 1.0 };
	char copy[160];

	if (strlen(text) >= sizeof(copy)) {
		snprintf(why, size, "longer than %zu characters",
			 sizeof(copy) - 1);
		return -EINVAL;
	}
	strcpy(copy, text);
	if (parse_words(copy, &tmp, why, size)) {
		return -EINVAL;
	}
	*r = tmp;
	return 0;
}

static const char *order_name(const struct regmap_reg *r)
{
	if (regmap_words(r) == 1) {
		return bytes_swapped(r) ? " ba" : "";
	}
	return r->order == REGMAP_ABCD ? "" : r->order == REGMAP_CDAB ? " cdab"
		: r->order == REGMAP_BADC ? " badc" : " dcba";
}

void regmap_format(const struct regmap_reg *r, char *buf, size_t size)
{
	char scale[40] = "", offset[40] = "";

	if (r->table == REGMAP_NONE || r->table >= COUNT(table_names)) {
		snprintf(buf, size, "none");
		return;
	}
	if (r->scale != 1.0) {
		snprintf(scale, sizeof(scale), " scale=%.9g", r->scale);
	}
	if (r->offset != 0.0) {
		snprintf(offset, sizeof(offset), " offset=%.9g", r->offset);
	}
	snprintf(buf, size, "%s 0x%04x %s%s%s%s", table_names[r->table],
		 r->address, type_names[r->type], order_name(r), scale,
		 offset);
}
