/*
 * test_centre.c - a centre's records (centre.h) without a server: the URL
 * checked as libpq reads it (a malformed one and one holding a password
 * refused, saying why; libpq's forms taken), a centre that cannot be
 * reached said in words without waiting (the sessions' calls and the
 * people's: a change taken nowhere, no copy of the people), and a
 * session's report page made from its file (a missing file: its errno).
 * The server itself: tests/system/80-centre.sh, 83-centre-roles.sh.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "session/centre.h"

static void url_refused(const char *url, const char *why)
{
	char err[512] = "";

	assert_int_equal(centre_check_url(url, err, sizeof(err)), -EINVAL);
	if (!strstr(err, why)) {
		print_message("%s: %s\n", url, err);
	}
	assert_non_null(strstr(err, why));
}

static void test_url(void **state)
{
	char err[512];

	(void)state;
	assert_int_equal(centre_check_url("postgresql://centre.example.org/"
					  "endosim?user=rig&sslmode=verify-full",
					  err, sizeof(err)), 0);
	assert_int_equal(centre_check_url("postgresql:///endosim?host=/run/pg",
					  err, sizeof(err)), 0);
	assert_int_equal(centre_check_url("service=centre", err, sizeof(err)),
			 0);
	url_refused("endosim", "not a PostgreSQL connection URL (endosim)");
	url_refused("postgresql://[bad", "not a PostgreSQL connection URL");
	url_refused("postgresql://rig:secret@centre/endosim", "holds a password");
	url_refused("host=centre password=secret", "holds a password");
}

static void test_unreachable(void **state)
{
	struct centre *c = centre_create("postgresql:///endosim?host="
					 "/nonexistent/socket&user=rig",
					 "test_centre");
	struct records_session *s;
	struct timespec t0, t1;
	size_t n;

	(void)state;
	assert_non_null(c);
	clock_gettime(CLOCK_MONOTONIC, &t0);
	assert_int_equal(centre_list(c, "Ann", &s, &n), -ENOTCONN);
	clock_gettime(CLOCK_MONOTONIC, &t1);
	assert_null(s);
	assert_int_equal(n, 0);
	assert_non_null(strstr(centre_error(c), "centre: cannot connect: "));
	assert_null(strchr(centre_error(c), '\n')); /* one log line */
	assert_true(t1.tv_sec - t0.tv_sec < CENTRE_CONNECT_TIMEOUT_S);
	assert_int_equal(centre_has(c, "00000000-0000-8000-8000-000000000000"),
			 -ENOTCONN);
	assert_false(centre_connected(c));
	centre_destroy(c);
	centre_destroy(NULL);

	c = centre_create("postgresql://rig:pw@centre/endosim", "test_centre");
	assert_int_equal(centre_connect(c, false), -EINVAL); /* not tried */
	assert_non_null(strstr(centre_error(c), "holds a password"));
	centre_destroy(c);
}

static void test_people_unreachable(void **state)
{
	struct centre *c = centre_create("postgresql:///endosim?host="
					 "/nonexistent/socket&user=rig",
					 "test_centre");
	struct accounts_queued q = { .id = "0123456789abcdef0123456789abcdef",
				     .name = "Ann" };
	enum centre_outcome out = CENTRE_APPLIED;
	struct centre_people p;
	char version[32] = "untouched";

	(void)state;
	q.ch = (struct accounts_change){ .op = ACCOUNTS_GROUP_JOIN,
					 .name = q.name, .pin = "",
					 .group = "2026", .course = "" };
	assert_int_equal(centre_change(c, "rig-a", &q, &out), -ENOTCONN);
	assert_int_equal(out, CENTRE_TAKEN); /* not said applied */
	assert_non_null(strstr(centre_error(c), "centre: cannot connect: "));
	assert_int_equal(centre_people_version(c, version, sizeof(version)),
			 -ENOTCONN);
	assert_string_equal(version, "untouched");
	memset(&p, 0xff, sizeof(p));
	assert_int_equal(centre_people(c, &p), -ENOTCONN);
	assert_null(p.ch);
	assert_int_equal(p.n, 0);
	centre_people_free(&p); /* as it was left: fine */
	centre_destroy(c);
}

static void test_report_page(void **state)
{
	char *html = (char *)"untouched";

	(void)state;
	assert_int_equal(centre_report_page("/nonexistent/1.endoses", &html),
			 -ENOENT);
	assert_null(html);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_url),
		cmocka_unit_test(test_unreachable),
		cmocka_unit_test(test_people_unreachable),
		cmocka_unit_test(test_report_page),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
