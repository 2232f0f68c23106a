/* regspec.c - see regspec.h. */
#include "conf/regspec.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "base/parse.h"

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

static const char *const signal_names[REGSPEC_SIGNALS] = {
	"torque", "enable", "position", "velocity", "fault", "fault_reset",
	"watchdog", "valve_air", "valve_water", "valve_suction",
	"tool_depth", "tool_opening", "tool_pedal",
};

static const char *const table_names[] = {
	[REGSPEC_NONE] = "none", [REGSPEC_COIL] = "coil",
	[REGSPEC_DISCRETE] = "discrete", [REGSPEC_INPUT] = "input",
	[REGSPEC_HOLDING] = "holding",
};

static const char *const type_names[] = {
	[REGSPEC_U16] = "u16", [REGSPEC_I16] = "i16", [REGSPEC_U32] = "u32",
	[REGSPEC_I32] = "i32", [REGSPEC_F32] = "f32",
};

static const struct {
	const char *name;
	enum regspec_order order;
} order_names[] = {
	{ "abcd", REGSPEC_ABCD }, { "cdab", REGSPEC_CDAB },
	{ "badc", REGSPEC_BADC }, { "dcba", REGSPEC_DCBA },
	{ "ab", REGSPEC_ABCD },   { "ba", REGSPEC_BADC },
};

const char *regspec_signal_name(enum regspec_signal s)
{
	return s < REGSPEC_SIGNALS ? signal_names[s] : "?";
}

bool regspec_bit(const struct regspec *r)
{
	return r->table == REGSPEC_COIL || r->table == REGSPEC_DISCRETE;
}

int regspec_words(const struct regspec *r)
{
	if (r->table == REGSPEC_NONE) {
		return 0;
	}
	return r->type == REGSPEC_U16 || r->type == REGSPEC_I16 ? 1 : 2;
}

bool regspec_writable(const struct regspec *r)
{
	return r->table == REGSPEC_COIL || r->table == REGSPEC_HOLDING;
}

static int find_name(const char *const *names, size_t n, const char *word)
{
	for (size_t i = 0; i < n; i++) {
		if (names[i] && !strcmp(names[i], word)) {
			return (int)i;
		}
	}
	return -1;
}

/* One optional word after the address: a type, an order, scale=, offset=. */
static int parse_option(const char *word, struct regspec *r, char *why,
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

static int parse_address(const char *word, struct regspec *r, char *why,
			 size_t size)
{
	long a;

	if (!word || parse_long(word, 0, &a) || a < 0 || a > 0xFFFF) {
		snprintf(why, size, "expected an address 0..65535 after the "
			 "table");
		return -EINVAL;
	}
	r->address = (uint16_t)a;
	return 0;
}

/* Parses the words of TEXT into R. */
static int parse_words(char *text, struct regspec *r, char *why, size_t size)
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
	if (t == REGSPEC_NONE) {
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
	if (regspec_bit(r) && r->type != REGSPEC_U16) {
		snprintf(why, size, "a %s holds one bit: its type is u16",
			 table_names[t]);
		return -EINVAL;
	}
	return 0;
}

int regspec_parse(const char *text, struct regspec *r, char *why,
		  size_t size)
{
	struct regspec tmp = { .type = REGSPEC_U16, .scale = 1.0 };
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

static const char *order_name(const struct regspec *r)
{
	bool swapped = r->order == REGSPEC_BADC || r->order == REGSPEC_DCBA;

	if (regspec_words(r) == 1) {
		return swapped ? " ba" : "";
	}
	return r->order == REGSPEC_ABCD   ? ""
	       : r->order == REGSPEC_CDAB ? " cdab"
	       : r->order == REGSPEC_BADC ? " badc"
					  : " dcba";
}

void regspec_format(const struct regspec *r, char *buf, size_t size)
{
	char scale[40] = "", offset[40] = "";

	if (r->table == REGSPEC_NONE || r->table >= COUNT(table_names)) {
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
