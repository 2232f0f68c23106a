/*
 * test_sessionindex.c - a session directory's index (sessionindex.h) on
 * small session files written here (a HEADER, an END frame or none): it
 * is built when missing, fresh when nothing changed, stale after a file
 * is deleted, added or grows (only those read again), damaged after a
 * byte of a number or of a name changed (which only the line's CRC
 * tells), a line cut, or the whole file garbage, and each time the
 * sessions come back the same as the files say; a directory it may not
 * write is read all the same.
 *
 * Writes to $TMPDIR.
 */
#include <errno.h>
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "proto/session_file.h"
#include "session/sessionindex.h"
#include "session/metricstext.h"

static char dir[256], index_path[300];

/* Session ID of TRAINEE on CASE_NAME; with END metrics (cecum_s = ID s)
 * when ENDED. */
static void write_session(uint64_t id, const char *trainee,
			  const char *case_name, int ended)
{
	char path[300], header[256], end[4096];
	struct metrics_result m = { .cecum_s = (double)id,
				    .withdrawal_s = 400, .mucosa_seen = 0.5,
				    .force_episodes = (uint32_t)id };
	int fd, n;

	snprintf(path, sizeof(path), "%s/%llu.endoses", dir,
		 (unsigned long long)id);
	n = snprintf(header, sizeof(header), "format=1\nid=%llu\ntrainee=%s\n"
		     "case=%s\nstarted=2026-11-2%lluT10:00:00Z\n",
		     (unsigned long long)id, trainee, case_name,
		     (unsigned long long)id % 10);
	fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
	assert_true(fd >= 0);
	assert_int_equal(session_file_write_magic(fd), 0);
	assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_HEADER,
						  header, (uint32_t)n), 0);
	if (ended) {
		n = metricstext_format(&m, end, sizeof(end));
		assert_true(n > 0);
		assert_int_equal(session_file_write_frame(fd, SESSION_FRAME_END,
							  end, (uint32_t)n), 0);
	}
	close(fd);
}

static int load(struct sessionindex_entry **e, size_t *n,
		struct sessionindex_info *info)
{
	return sessionindex_load(dir, true, e, n, info);
}

/* The three sessions as the files say, whatever the index was. */
static void check_sessions(const struct sessionindex_entry *e, size_t n)
{
	assert_int_equal(n, 3);
	assert_int_equal(e[0].e.id, 1);
	assert_string_equal(e[0].e.trainee, "Ann Smith");
	assert_string_equal(e[0].e.case_name, "normal");
	assert_string_equal(e[0].e.started, "2026-11-21T10:00:00Z");
	assert_true(e[0].has_metrics);
	assert_true(e[0].m.cecum_s == 1);
	assert_true(e[0].m.withdrawal_s == 400);
	assert_int_equal(e[0].m.force_episodes, 1);
	assert_int_equal(e[1].e.id, 2);
	assert_false(e[1].has_metrics); /* cut short */
	assert_false(e[1].e.ended);
	assert_int_equal(e[2].e.id, 10);
	assert_string_equal(e[2].e.trainee, "Bo");
	assert_true(e[2].m.cecum_s == 10);
}

static int setup(void **state)
{
	const char *tmp = getenv("TMPDIR");
	FILE *f;

	(void)state;
	snprintf(dir, sizeof(dir), "%s/test_sessionindex.XXXXXX",
		 tmp ? tmp : "/tmp");
	assert_non_null(mkdtemp(dir));
	snprintf(index_path, sizeof(index_path), "%s/index", dir);
	write_session(1, "Ann Smith", "normal", 1);
	write_session(2, "Ann Smith", "polyps", 0);
	write_session(10, "Bo", "normal", 1);
	snprintf(index_path, sizeof(index_path), "%s/junk.txt", dir);
	f = fopen(index_path, "w"); /* not a session's name: ignored */
	fputs("junk", f);
	fclose(f);
	snprintf(index_path, sizeof(index_path), "%s/7.endoses", dir);
	f = fopen(index_path, "w"); /* a session's name, not one */
	fputs("not a session", f);
	fclose(f);
	snprintf(index_path, sizeof(index_path), "%s/index", dir);
	return 0;
}

static int teardown(void **state)
{
	char cmd[400];

	(void)state;
	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
	return system(cmd);
}

static void test_build_and_fresh(void **state)
{
	struct sessionindex_entry *e;
	struct sessionindex_info info;
	size_t n;

	(void)state;
	unlink(index_path);
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_MISSING);
	assert_int_equal(info.reread, 4); /* 7.endoses too, as "bad" */
	assert_int_equal(info.write_error, 0);
	check_sessions(e, n);
	free(e);
	assert_int_equal(access(index_path, R_OK), 0);
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_FRESH);
	assert_int_equal(info.reread, 0); /* not one file opened */
	check_sessions(e, n);
	free(e);
}

static void test_stale(void **state)
{
	struct sessionindex_entry *e;
	struct sessionindex_info info;
	char path[300];
	size_t n;

	(void)state;
	assert_int_equal(load(&e, &n, &info), 0);
	free(e);
	write_session(11, "Bo", "normal", 1); /* added */
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_STALE);
	assert_int_equal(info.reread, 1);
	assert_int_equal(n, 4);
	free(e);
	snprintf(path, sizeof(path), "%s/11.endoses", dir);
	assert_int_equal(unlink(path), 0); /* deleted */
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_STALE);
	assert_int_equal(info.reread, 0);
	check_sessions(e, n);
	free(e);
	write_session(2, "Ann Smith", "polyps", 1); /* it ended after all */
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_STALE);
	assert_int_equal(info.reread, 1);
	assert_true(e[1].has_metrics);
	assert_true(e[1].m.cecum_s == 2);
	free(e);
	write_session(2, "Ann Smith", "polyps", 0);
	assert_int_equal(load(&e, &n, &info), 0);
	check_sessions(e, n);
	free(e);
}

/* Overwrites the index at OFF with TEXT, or cuts it there (TEXT NULL). */
static void damage(long off, const char *text)
{
	int fd = open(index_path, O_WRONLY);

	assert_true(fd >= 0);
	if (text) {
		assert_true(pwrite(fd, text, strlen(text), off) ==
			    (ssize_t)strlen(text));
	} else {
		assert_int_equal(ftruncate(fd, off), 0);
	}
	close(fd);
}

/* The offset of the first TEXT in the index. */
static long find_in_index(const char *text)
{
	static char buf[1 << 16];
	FILE *f = fopen(index_path, "r");
	size_t n;
	char *at;

	assert_non_null(f);
	n = fread(buf, 1, sizeof(buf) - 1, f);
	fclose(f);
	buf[n] = '\0';
	at = strstr(buf, text);
	assert_non_null(at);
	return at - buf;
}

static void test_damaged(void **state)
{
	struct sessionindex_entry *e;
	struct sessionindex_info info;
	struct stat st;
	size_t n;

	(void)state;
	assert_int_equal(load(&e, &n, &info), 0);
	free(e);
	assert_int_equal(stat(index_path, &st), 0);
	damage(40, "Z"); /* one byte of the first line: its CRC fails */
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_DAMAGED);
	assert_int_equal(info.bad_lines, 1);
	assert_int_equal(info.reread, 1);
	check_sessions(e, n);
	free(e);
	/* a flipped letter: the line parses, only its CRC tells */
	damage(find_in_index("Ann Smith") + 8, "x");
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_DAMAGED);
	assert_int_equal(info.bad_lines, 1);
	check_sessions(e, n); /* "Ann Smith" again, from its file */
	free(e);
	damage(st.st_size - 30, NULL); /* the last line cut */
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_DAMAGED);
	check_sessions(e, n);
	free(e);
	damage(0, "garbage garbage garbage\n\n\t\t\t"); /* its first line */
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_DAMAGED);
	assert_int_equal(info.reread, 4);
	check_sessions(e, n);
	free(e);
	assert_int_equal(load(&e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_FRESH); /* written again */
	check_sessions(e, n);
	free(e);
}

static void test_read_only(void **state)
{
	struct sessionindex_entry *e;
	struct sessionindex_info info;
	size_t n;

	(void)state;
	unlink(index_path);
	assert_int_equal(sessionindex_load(dir, false, &e, &n, &info), 0);
	assert_int_equal(info.state, SESSIONINDEX_MISSING);
	check_sessions(e, n);
	free(e);
	assert_int_equal(access(index_path, F_OK), -1); /* not written */
	assert_int_equal(sessionindex_load("/nonexistent/dir", true, &e, &n,
					   &info), -ENOENT);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_build_and_fresh),
		cmocka_unit_test(test_stale),
		cmocka_unit_test(test_damaged),
		cmocka_unit_test(test_read_only),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
