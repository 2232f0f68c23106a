/*
 * test_coursefile.c - a course's file (coursefile.h): the shipped one
 * parses; each mistake is named with its file and line; a session's
 * metrics meet a requirement or not (at its bound, a cecum never
 * reached); a case is complete after `consecutive` passing sessions in a
 * row and a failing one starts the count again; the shipped course fails
 * a session that perforated (counted from its records) or was in pain
 * more than 10 % of the time. Hostile files: quotes and semicolons
 * kept as given, a NUL byte or a 10 kB line refused with FILE:LINE.
 *
 * Reads config/courses/basic.course: run from the source tree.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "session/coursefile.h"

static struct coursefile course;
static char err[256];

static const char good[] =
	"# a comment\n"
	"[course]\nname = t\nconsecutive = 2\n"
	"[case normal]\ncecum_s <= 480\nwithdrawal_s>=360 # inline\n"
	"mucosa_seen >= 0.9\nforce_episodes == 0\n"
	"[case polyps]\npolyps_seen > 4\n";

static void test_shipped(void **state)
{
	(void)state;
	assert_int_equal(coursefile_load(&course,
					 "config/courses/basic.course", err,
					 sizeof(err)), 0);
	assert_string_equal(course.name, "basic");
	assert_int_equal(course.consecutive, 3);
	assert_int_equal(course.n_cases, 2);
	assert_non_null(coursefile_case(&course, "polyps"));
	assert_null(coursefile_case(&course, "tight-flexures"));
}

static void test_parse(void **state)
{
	char text[64];

	(void)state;
	assert_int_equal(coursefile_parse(&course, good, "g", err,
					  sizeof(err)), 0);
	assert_int_equal(course.cases[0].n_reqs, 4);
	assert_int_equal(course.cases[0].req[1].op, COURSEFILE_GE);
	assert_string_equal(course.cases[0].req[1].field->key,
			    "withdrawal_s");
	coursefile_req_text(&course.cases[0].req[2], text, sizeof(text));
	assert_string_equal(text, "mucosa_seen >= 0.9");
}

/* TEXT fails with an error that says WANT. */
static void fails(const char *text, const char *want)
{
	assert_int_equal(coursefile_parse(&course, text, "c.course", err,
					  sizeof(err)), -EINVAL);
	if (!strstr(err, want)) {
		fail_msg("'%s' does not say '%s'", err, want);
	}
}

static void test_errors(void **state)
{
	const char *head = "[course]\nname = t\nconsecutive = 2\n[case n]\n";
	char text[256];

	(void)state;
	snprintf(text, sizeof(text), "%scecum_time <= 3\n", head);
	fails(text, "c.course:5: unknown metric 'cecum_time'");
	snprintf(text, sizeof(text), "%spolyps_seen_mask == 31\n", head);
	fails(text, "c.course:5: polyps_seen_mask: a set of polyps");
	snprintf(text, sizeof(text), "%scecum_s => 3\n", head);
	fails(text, "c.course:5: cecum_s: bad operator '=>'");
	snprintf(text, sizeof(text), "%scecum_s <= 8min\n", head);
	fails(text, "c.course:5: cecum_s: bad number '8min'");
	snprintf(text, sizeof(text), "%scecum_s <= 1\n[case n]\n", head);
	fails(text, "c.course:6: [case n] again");
	fails("[course]\nname = t\nconsecutive = 0\n", "c.course:3: "
	      "consecutive");
	fails("[course]\nnmae = t\n", "c.course:2: unknown key 'nmae'");
	fails("[lesson]\n", "c.course:1: unknown section [lesson]");
	fails("cecum_s <= 1\n", "c.course:1: outside a section");
	fails("[course]\nname = t\nconsecutive = 1\n", "no [case NAME]");
	fails("[course]\nname = t\nconsecutive = 1\n[case n]\n",
	      "[case n] has no requirement");
	fails("[case n]\ncecum_s < 1\n", "c.course: no [course] section");
}

static void test_met(void **state)
{
	const struct coursefile_case *k;
	struct metrics_result m = { .cecum_s = 480, .withdrawal_s = 360,
				    .mucosa_seen = 0.9 };

	(void)state;
	assert_int_equal(coursefile_parse(&course, good, "g", err,
					  sizeof(err)), 0);
	k = coursefile_case(&course, "normal");
	assert_true(coursefile_passed(k, &m)); /* every bound is inclusive */
	m.force_episodes = 1;
	assert_false(coursefile_met(&k->req[3], &m));
	assert_true(coursefile_met(&k->req[0], &m));
	assert_false(coursefile_passed(k, &m));
	m.force_episodes = 0;
	m.withdrawal_s = 359.9;
	assert_false(coursefile_passed(k, &m));
	m.withdrawal_s = 400;
	m.cecum_s = -1; /* never reached: not "within 480 s" */
	assert_false(coursefile_met(&k->req[0], &m));
	m.cecum_s = 480.001;
	assert_false(coursefile_met(&k->req[0], &m));
	m.polyps_seen = 4;
	assert_false(coursefile_passed(coursefile_case(&course, "polyps"),
				       &m));
}

/*
 * The shipped course fails a session that perforated, by a burst or by
 * the tip's tear, counted from its records, though it met every other
 * requirement; and one in pain more than 10 % of the time.
 */
static void test_perforation_fails(void **state)
{
	const struct coursefile_case *k;
	struct metrics_result good_m = { .cecum_s = 300, .withdrawal_s = 400,
					 .mucosa_seen = 0.95,
					 .pain_share = 0.10,
					 .polyps_seen = 5 }, m;
	struct metrics_params p;

	(void)state;
	assert_int_equal(coursefile_load(&course,
					 "config/courses/basic.course", err,
					 sizeof(err)), 0);
	k = coursefile_case(&course, "normal");
	assert_non_null(k);
	assert_true(coursefile_passed(k, &good_m));
	assert_true(coursefile_passed(coursefile_case(&course, "polyps"),
				      &good_m));
	metrics_params_default(&p);
	for (int torn = 0; torn < 2; torn++) {
		struct metrics *mt = metrics_create(NULL, &p);

		assert_non_null(mt);
		for (uint64_t i = 0; i < 10; i++) {
			struct session_record r = {
				.stamp_ns = i * 100000000ull, .patient = 1,
				.hand_site = -1, .burst_segment = -1,
				.torn_segment = -1, .pain_place = -1,
			};

			if (i >= 5) {
				*(torn ? &r.torn_segment : &r.burst_segment) =
					2;
			}
			metrics_record(mt, &r);
		}
		metrics_result(mt, &m);
		metrics_destroy(mt);
		assert_int_equal(m.perforations, 1);
		good_m.perforations = m.perforations;
		assert_false(coursefile_passed(k, &good_m));
		assert_false(coursefile_passed(coursefile_case(&course,
							       "polyps"),
					       &good_m));
		good_m.perforations = 0;
	}
	good_m.pain_share = 0.1001;
	assert_false(coursefile_passed(k, &good_m));
}

/* Judged one by one (a listing's way): the same progress as P's, of the
 * N sessions CASES[i] with measures M[i]. */
static void judged_alike(const char **cases,
			 const struct metrics_result **m, size_t n,
			 const struct coursefile_progress *p)
{
	struct coursefile_progress q[COURSEFILE_MAX_CASES];
	signed char passed[16];

	for (size_t i = 0; i < n; i++) {
		passed[i] = (signed char)coursefile_judge(&course, cases[i],
							  m[i]);
	}
	coursefile_progress_judged(&course, cases, passed, n, q);
	assert_memory_equal(p, q, sizeof(q));
}

static void test_progress(void **state)
{
	struct metrics_result pass = { .cecum_s = 300, .withdrawal_s = 400,
				       .mucosa_seen = 0.95, .polyps_seen = 5 };
	struct metrics_result miss = pass;
	const char *cases[] = { "normal", "normal", "polyps", "other",
				"normal", "polyps", "normal" };
	const struct metrics_result *m[] = { &pass, &miss, &pass, &miss,
					     &pass, NULL, &pass };
	struct coursefile_progress p[COURSEFILE_MAX_CASES];

	(void)state;
	miss.force_episodes = 2;
	assert_int_equal(coursefile_parse(&course, good, "g", err,
					  sizeof(err)), 0);
	coursefile_progress(&course, cases, m, 6, p);
	assert_int_equal(p[0].sessions, 3); /* "other" and NULL not judged */
	assert_int_equal(p[0].run, 1);      /* the miss restarted it */
	assert_int_equal(p[0].completed, 0);
	assert_int_equal(p[1].sessions, 1);
	assert_int_equal(p[1].completed, 0); /* one of two */
	assert_false(coursefile_complete(&course, p));
	coursefile_progress(&course, cases, m, 7, p);
	assert_int_equal(p[0].run, 2);
	assert_int_equal(p[0].completed, 7);
	assert_false(coursefile_complete(&course, p));
	assert_int_equal(coursefile_judge(&course, "normal", &miss), 0);
	assert_int_equal(coursefile_judge(&course, "other", &pass), -1);
	assert_int_equal(coursefile_judge(&course, "polyps", NULL), -1);
	assert_int_equal(coursefile_judge(&course, "normal", &pass), 1);
	judged_alike(cases, m, 7, p);
	cases[5] = "polyps";
	m[5] = &pass;
	coursefile_progress(&course, cases, m, 7, p);
	assert_int_equal(p[1].completed, 6);
	assert_true(coursefile_complete(&course, p));
	judged_alike(cases, m, 7, p);
}

/* The file PATH written with the N bytes TEXT. */
static void write_file(const char *path, const char *text, size_t n)
{
	FILE *f = fopen(path, "we");

	assert_non_null(f);
	assert_int_equal(fwrite(text, 1, n, f), n);
	assert_int_equal(fclose(f), 0);
}

/* Names as given whatever they hold; what a parser reading C strings
 * would take wrongly refused, with its file and line. */
static void test_hostile_files(void **state)
{
	static const char quotes[] =
		"[course]\nname = it's \"a\"; DROP TABLE x;--\n"
		"description = ';--\nconsecutive = 1\n"
		"[case normal]\ncecum_s <= 480\n";
	static const char nul[] = "[course]\nname = t\0evil\n"
				  "consecutive = 1\n[case normal]\n"
				  "cecum_s <= 480\n";
	const char *tmp = getenv("TMPDIR");
	char path[256], *big = malloc(12000);
	size_t n;

	(void)state;
	assert_non_null(big);
	snprintf(path, sizeof(path), "%s/test_coursefile.%d.course",
		 tmp ? tmp : "/tmp", (int)getpid());
	write_file(path, quotes, sizeof(quotes) - 1);
	assert_int_equal(coursefile_load(&course, path, err, sizeof(err)), 0);
	assert_string_equal(course.name, "it's \"a\"; DROP TABLE x;--");
	assert_string_equal(course.description, "';--");
	write_file(path, nul, sizeof(nul) - 1);
	assert_int_equal(coursefile_load(&course, path, err, sizeof(err)),
			 -EINVAL);
	assert_non_null(strstr(err, ":2: a NUL byte"));
	assert_non_null(strstr(err, path));
	n = (size_t)snprintf(big, 12000, "[course]\nname = ");
	memset(big + n, 'x', 10240);
	n += 10240;
	n += (size_t)snprintf(big + n, 12000 - n, "\nconsecutive = 1\n");
	write_file(path, big, n);
	assert_int_equal(coursefile_load(&course, path, err, sizeof(err)),
			 -EINVAL);
	assert_non_null(strstr(err, ":2: line longer than"));
	unlink(path);
	free(big);
}


int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_shipped),
		cmocka_unit_test(test_parse),
		cmocka_unit_test(test_errors),
		cmocka_unit_test(test_met),
		cmocka_unit_test(test_perforation_fails),
		cmocka_unit_test(test_progress),
		cmocka_unit_test(test_hostile_files),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
