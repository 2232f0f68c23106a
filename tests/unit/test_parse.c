/* test_parse.c - the parsing kit (lib/base/parse.h): numbers whole or not
 * at all, the error line, and a key table read over libinih with each of
 * the kit's rules and each of its errors at its line. */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "base/parse.h"

static char err[512];

static void test_numbers(void **state)
{
	static const char *const bad[] = {
		"", " ", "1 ", "1x", "x1", "nan", "inf", "-inf", "1e999",
		"1e-400", "0x", "--1",
	};
	double d;
	long l;

	(void)state;
	assert_int_equal(parse_double("2.5", &d), 0);
	assert_true(d == 2.5);
	assert_int_equal(parse_double(" -1e3", &d), 0);
	assert_true(d == -1000);
	for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		if (parse_double(bad[i], &d) != -EINVAL) {
			print_error("'%s' taken for %g\n", bad[i], d);
			fail();
		}
	}
	assert_int_equal(parse_long("0x24E7", 16, &l), 0);
	assert_int_equal(l, 0x24E7);
	assert_int_equal(parse_long("12", 10, &l), 0);
	assert_int_equal(parse_long("1.5", 10, &l), -EINVAL);
	assert_int_equal(parse_long("", 10, &l), -EINVAL);
	assert_int_equal(parse_long("0x10", 10, &l), -EINVAL);
	assert_int_equal(parse_long("99999999999999999999", 10, &l), -EINVAL);
}

static void test_number_in_range(void **state)
{
	char why[128];
	double v;

	(void)state;
	assert_int_equal(parse_number("3", 1, 5, "m", &v, why, sizeof(why)),
			 0);
	assert_true(v == 3);
	assert_int_equal(parse_number("9", 1, 5, "m", &v, why, sizeof(why)),
			 -EINVAL);
	assert_string_equal(why, "9 is out of range [1, 5] m");
	assert_int_equal(parse_number("0.5", 1, 5, "", &v, why, sizeof(why)),
			 -EINVAL);
	assert_string_equal(why, "0.5 is out of range [1, 5]");
	assert_int_equal(parse_number("abc", 1, 5, "m", &v, why, sizeof(why)),
			 -EINVAL);
	assert_string_equal(why, "'abc' is not a number");
}

static void test_error_line(void **state)
{
	(void)state;
	assert_int_equal(parse_error(err, sizeof(err), "f.conf", 3,
				     "[loop] rate_hz", "%d is odd", 5),
			 -EINVAL);
	assert_string_equal(err, "f.conf:3: [loop] rate_hz: 5 is odd");
	parse_error(err, sizeof(err), "f.conf", 0, NULL, "empty");
	assert_string_equal(err, "f.conf: empty");
	parse_error(err, sizeof(err), "f.conf", 7, NULL, "no steps");
	assert_string_equal(err, "f.conf:7: no steps");
}

/* ------------------------------------------------------------- a table */

struct thing {
	int count;
	double length_m;
	char label[8];
	int colour;
	int marks[4];
	int n_marks;
};

struct doc {
	struct thing a;          /* [a] */
	struct thing item[4];    /* [item NAME], in order */
	int items;
	int ended[4];            /* per item: the line length_m was set on */
	int item_line[4];
};

static const char *const colours[] = { "red", "green", NULL };

/* A mark: a whole number 0..9, appended (repeatable). */
static int mark_parse(const struct parse_key *k, const char *text,
		      void *field, struct parse_file *pf, char *why,
		      size_t size)
{
	struct thing *t = field;
	long v;

	(void)k;
	(void)pf;
	if (parse_long(text, 10, &v) || v < 0 || v > 9 || t->n_marks == 4) {
		snprintf(why, size, "'%s': a mark is 0..9, four at most",
			 text);
		return -EINVAL;
	}
	t->marks[t->n_marks++] = (int)v;
	return 0;
}

static const struct parse_ops mark_ops = { mark_parse, NULL };

#define T(f) offsetof(struct thing, f)

static const struct parse_key keys[] = {
	{ .section = "a", .name = "count", .type = PARSE_INT,
	  .offset = T(count), .def = 2, .min = 0, .max = 0xFFFF,
	  .flags = PARSE_HEX, .unit = "" },
	{ .section = "a", .name = "label", .type = PARSE_STRING,
	  .offset = T(label), .size = sizeof(((struct thing *)0)->label),
	  .def_str = "none", .unit = "" },
	{ .section = "item", .name = "length_m", .type = PARSE_DOUBLE,
	  .offset = T(length_m), .min = 0.1, .max = 2, .unit = "m",
	  .flags = PARSE_REQUIRED },
	{ .section = "item", .name = "colour", .type = PARSE_CHOICE,
	  .offset = T(colour), .choices = colours, .unit = "" },
	{ .section = "item", .name = "mark", .type = PARSE_CUSTOM,
	  .offset = 0, .ops = &mark_ops, .unit = "",
	  .flags = PARSE_REPEATS },
};

static int begin(struct parse_file *pf, const char *kind, const char *arg,
		 void **base, char *why, size_t size)
{
	struct doc *d = parse_file_user(pf);

	if (!strcmp(kind, "a") && !arg) {
		*base = &d->a;
		return 0;
	}
	if (!strcmp(kind, "item") && arg && d->items < 4) {
		d->item_line[d->items] = parse_file_line(pf);
		*base = &d->item[d->items++];
		return 0;
	}
	snprintf(why, size, "unknown section");
	return -EINVAL;
}

static void end(struct parse_file *pf, const int *set_on)
{
	struct doc *d = parse_file_user(pf);

	if (d->items) {
		d->ended[d->items - 1] = set_on[2];
	}
}

static const struct parse_table table = {
	.keys = keys,
	.n = sizeof(keys) / sizeof(keys[0]),
	.flags = PARSE_HASH_COMMENTS | PARSE_KIND_ARG | PARSE_PER_SECTION,
	.begin = begin,
	.end = end,
};

/* TEXT read by TABLE_ into D (zeroed first). */
static int read_doc(const struct parse_table *table_, const char *text,
		    struct doc *d)
{
	FILE *f = fmemopen((void *)text, strlen(text), "r");
	int r;

	assert_non_null(f);
	memset(d, 0, sizeof(*d));
	r = parse_ini(table_, f, "t.ini", d, d, err, sizeof(err));
	fclose(f);
	return r;
}

static void test_table_reads(void **state)
{
	struct doc d;

	(void)state;
	assert_int_equal(read_doc(&table,
				  "\xEF\xBB\xBF# a comment\n"
				  "[a]\n"
				  "  count = 0x1F   # '#' anywhere\n"
				  "label: x y ; libinih's inline comment\n"
				  "[ item  first ]\n"
				  "length_m = 0.5\n"
				  "mark = 3\n"
				  "\tmark = 4\n"
				  "[item second]\n"
				  "colour = green\n"
				  "length_m = 1\n", &d),
			 7);
	assert_int_equal(d.a.count, 0x1F);
	assert_string_equal(d.a.label, "x y");
	assert_int_equal(d.items, 2);
	assert_true(d.item[0].length_m == 0.5);
	assert_int_equal(d.item[0].n_marks, 2);
	assert_int_equal(d.item[0].marks[1], 4);
	assert_int_equal(d.item[1].colour, 1);
	assert_int_equal(d.item_line[0], 5);
	assert_int_equal(d.ended[0], 6);
	assert_int_equal(d.ended[1], 11);
}

struct bad {
	const char *text;
	const char *want; /* the whole message */
};

static void test_table_errors(void **state)
{
	static const struct bad bad[] = {
		{ "count = 1\n", "t.ini:1: count: before any [section]" },
		{ "[a]\ncont = 1\n", "t.ini:2: [a] cont: unknown key" },
		{ "[a]\ncount = 1\ncount = 2\n",
		  "t.ini:3: [a] count: duplicate key (first set on line 2)" },
		{ "[a]\ncount = 0x10000\n",
		  "t.ini:2: [a] count: 0x10000 is out of range [0, 65535]" },
		{ "[a]\ncount = 12q\n",
		  "t.ini:2: [a] count: '12q' is not an integer" },
		{ "[a]\nlabel = 12345678\n",
		  "t.ini:2: [a] label: longer than 7 characters" },
		{ "[item x]\nlength_m = 3\n",
		  "t.ini:2: [item x] length_m: 3 is out of range [0.1, 2] m" },
		{ "[item x]\nlength_m = 1\ncolour = blue\n",
		  "t.ini:3: [item x] colour: 'blue' is not a known choice" },
		{ "[item x]\nlength_m = 1\nmark = 12\n",
		  "t.ini:3: [item x] mark: '12': a mark is 0..9, four at "
		  "most" },
		{ "[a]\n\n[item x]\ncolour = red\n[a]\n",
		  "t.ini:3: [item x]: length_m is missing" },
		{ "[item x]\ncolour = red\n",
		  "t.ini:1: [item x]: length_m is missing" },
		{ "[b]\n", "t.ini:1: [b]: unknown section" },
		{ "[a\n", "t.ini:1: [a: syntax error: expected '[section]'" },
		{ "[a]\ncount 5\n", "t.ini:2: count 5: syntax error: expected "
				    "'key = value'" },
		{ "[a]\ncount ; = 5\n", "t.ini:2: syntax error: expected "
					"'key = value'" },
		/* the first error in the file, not the first found */
		{ "[a]\ncount 5\ncont = 1\n", "t.ini:2: count 5: syntax "
		  "error: expected 'key = value'" },
	};
	struct doc d;

	(void)state;
	for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		assert_int_equal(read_doc(&table, bad[i].text, &d), -EINVAL);
		if (strcmp(err, bad[i].want)) {
			print_error("case %zu: got '%s', want '%s'\n", i, err,
				    bad[i].want);
			fail();
		}
	}
}

static void test_long_lines(void **state)
{
	static char text[2 * PARSE_MAX_LINE];
	struct doc d;

	(void)state;
	/* a long comment is fine; a long value is not */
	snprintf(text, sizeof(text), "[a]\n# %0*d\ncount = 1\n", 1000, 0);
	assert_int_equal(read_doc(&table, text, &d), 1);
	snprintf(text, sizeof(text), "[a]\nlabel = %0*d\n", 200, 0);
	assert_int_equal(read_doc(&table, text, &d), -EINVAL);
	assert_string_equal(err, "t.ini:2: line: longer than 198 characters");
	snprintf(text, sizeof(text), "[a]\n# %0*d\n", PARSE_MAX_LINE, 0);
	assert_int_equal(read_doc(&table, text, &d), -EINVAL);
	assert_string_equal(err, "t.ini:2: line: longer than 4094 "
			    "characters");
}

/* Without PARSE_HASH_COMMENTS and PARSE_PER_SECTION: '#' is text after a
 * line's start, a key is set once in the file, a section is its name. */
static void test_plain_table(void **state)
{
	static const struct parse_table plain = {
		.keys = keys,
		.n = sizeof(keys) / sizeof(keys[0]),
	};
	struct doc d;

	(void)state;
	assert_int_equal(read_doc(&plain, "# c\n[a]\nlabel = a#b\n", &d), 1);
	assert_string_equal(d.a.label, "a#b");
	assert_int_equal(read_doc(&plain, "[a]\ncount = 1\n[b]\n[a]\n"
				  "count = 2\n", &d), -EINVAL);
	assert_string_equal(err, "t.ini:5: [a] count: duplicate key (first "
			    "set on line 2)");
	assert_int_equal(read_doc(&plain, "[item x]\nlength_m = 1\n", &d),
			 -EINVAL);
	assert_string_equal(err, "t.ini:2: [item x] length_m: unknown key");
}

static void test_defaults_apply_format(void **state)
{
	struct thing t;
	char buf[64], why[128];

	(void)state;
	memset(&t, 0, sizeof(t));
	parse_defaults(&(struct parse_table){ .keys = keys, .n = 2 }, &t);
	assert_int_equal(t.count, 2);
	assert_string_equal(t.label, "none");
	parse_format(&keys[0], &t, buf, sizeof(buf));
	assert_string_equal(buf, "0x0002");
	assert_int_equal(parse_apply(&keys[0], &t, "0x00ff", NULL, why,
				     sizeof(why)), 0);
	assert_int_equal(t.count, 255);
	assert_int_equal(parse_apply(&keys[0], &t, "-1", NULL, why,
				     sizeof(why)), -EINVAL);
	assert_int_equal(t.count, 255);
	t.colour = 1;
	parse_format(&keys[3], &t, buf, sizeof(buf));
	assert_string_equal(buf, "green");
	t.colour = 7;
	parse_format(&keys[3], &t, buf, sizeof(buf));
	assert_string_equal(buf, "?");
	parse_format(&keys[4], &t, buf, sizeof(buf));
	assert_string_equal(buf, "");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_numbers),
		cmocka_unit_test(test_number_in_range),
		cmocka_unit_test(test_error_line),
		cmocka_unit_test(test_table_reads),
		cmocka_unit_test(test_table_errors),
		cmocka_unit_test(test_long_lines),
		cmocka_unit_test(test_plain_table),
		cmocka_unit_test(test_defaults_apply_format),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
