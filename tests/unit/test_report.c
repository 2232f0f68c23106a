/*
 * test_report.c - the instructor's report from a synthetic session in
 * memory: the page holds its four plots, the episodes as bands, the
 * events, the segments' names, the figure and table along the colon (the
 * force and the loop in the segment the tip was in); text from the file
 * is escaped; a spike of one record in 20 000 survives the decimation;
 * the metrics recomputed from the file (sessionmetrics_compute()) find
 * what the records hold.
 *
 * Reads tests/cases/straight.case: run from the source tree. Writes to
 * $TMPDIR.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "geom_assert.h"
#include "session/report.h"
#include "session/sessioninputs.h"
#include "session/sessionmetrics.h"

#define N_REC 20000 /* 20 s at 1 kHz */

static char case_text[1 << 16];
static char header[] =
	"format=1\nid=7\ntrainee=<script>alert(1)</script> & O'Neil\n"
	"case=straight\nstarted=2026-11-20T10:00:00Z\nstep_m=0.002\n"
	"ring_vertices=48\nsegment_m=0.04\nversion=test\n";
static struct session_record records[N_REC];
static struct session_file_event events[2];

static void load_case(void)
{
	FILE *f = fopen("tests/cases/straight.case", "r");
	size_t n;

	assert_non_null(f);
	n = fread(case_text, 1, sizeof(case_text) - 1, f);
	case_text[n] = '\0';
	fclose(f);
}

/* 5 N, 20 N from 5 to 8 s, one record of 40 N at 12.345 s; the sigmoid
 * bowed 2 cm from 14 to 16 s; the tip at 1 cm/s along the axis. */
static void make_session(struct session_file *f)
{
	load_case();
	for (int k = 0; k < N_REC; k++) {
		struct session_record *r = &records[k];
		double t = k * 1e-3;

		memset(r, 0, sizeof(*r));
		r->stamp_ns =
			ENDOSIM_NS_PER_S + (uint64_t)k * ENDOSIM_NS_PER_MS;
		r->depth_m = r->tip_s_m = (float)(0.01 * t + 0.05);
		r->tip[2] = r->tip_s_m;
		r->dir[2] = 1;
		r->limited[0] = (float)(k == 12345 ? 40 : t >= 5 && t < 8 ? 20 : 5);
		r->limited[1] = (float)(0.01 * sin(t));
		r->spans = 2;
		r->bow_m[0] = (float)(t >= 14 && t < 16 ? 0.02 : 0);
	}
	events[0] = (struct session_file_event){
		.ev = {.stamp_ns = ENDOSIM_NS_PER_S,
		       .kind = SESSION_EVENT_STATE,
		       .axis = -1,
		       .value = 1},
		.text = "",
	};
	events[1] = (struct session_file_event){
		.ev = { .stamp_ns = ENDOSIM_NS_PER_S + 9000000000ull,
			.kind = SESSION_EVENT_FAULT, .axis = 0, .detail = 7 },
		.text = "<evil> note",
	};
	*f = (struct session_file){
		.header = header, .case_text = case_text, .records = records,
		.n_records = N_REC, .events = events, .n_events = 2,
	};
}

static char *slurp(const char *path)
{
	FILE *f = fopen(path, "r");
	static char buf[1 << 22];
	size_t n;

	assert_non_null(f);
	n = fread(buf, 1, sizeof(buf) - 1, f);
	buf[n] = '\0';
	fclose(f);
	return buf;
}

static int count(const char *hay, const char *needle)
{
	int n = 0;

	for (const char *p = strstr(hay, needle); p; p = strstr(p + 1, needle)) {
		n++;
	}
	return n;
}

static void test_recomputed_metrics(void **state)
{
	struct session_file f;
	struct metrics_params p;
	struct metrics_result m;
	char err[256];

	(void)state;
	make_session(&f);
	metrics_params_default(&p);
	assert_int_equal(sessionmetrics_compute(&f, &p, &m, err, sizeof(err)),
			 0);
	assert_string_equal(err, "");
	assert_int_equal(m.records, N_REC);
	assert_int_equal(m.force_episodes, 1);
	assert_near(m.force[0].start_s, 5.0, 1.001e-3);
	assert_near(m.force[0].end_s, 8.0, 1.001e-3);
	assert_near(m.peak_insertion_n, 40, 1e-6);
	assert_int_equal(m.loop_episodes, 1);
	assert_near(m.longest_loop_s, 2.0, 1.001e-3);
	assert_true(m.cecum_s < 0);
}

static void test_report_page(void **state)
{
	struct session_file f;
	struct metrics_params p;
	struct metrics_result m;
	char dir[256], path[300], err[256], cmd[320];
	const char *tmp = getenv("TMPDIR");
	const char *html, *force, *path_end;
	static char series[1 << 16];

	(void)state;
	make_session(&f);
	metrics_params_default(&p);
	assert_int_equal(sessionmetrics_compute(&f, &p, &m, err, sizeof(err)),
			 0);
	snprintf(dir, sizeof(dir), "%s/endosim-report-%d",
		 tmp && *tmp ? tmp : "/tmp", (int)getpid());
	assert_int_equal(report_write(&f, &m, NULL, dir), 0); /* creates DIR */
	snprintf(path, sizeof(path), "%s/index.html", dir);
	html = slurp(path);
	assert_int_equal(count(html, "<svg class=\"plot\""), 6);
	assert_non_null(strstr(html, "id=\"mucosa-map\""));
	assert_non_null(strstr(html, "id=\"pain-along\""));
	assert_non_null(strstr(html, "id=\"plot-force\""));
	assert_non_null(strstr(html, "id=\"plot-torque\""));
	assert_non_null(strstr(html, "id=\"plot-tip\""));
	assert_non_null(strstr(html, "id=\"plot-bow\""));
	/* one force and one loop episode, a band on each of the 4 plots */
	assert_int_equal(count(html, "<rect class=\"band force\" x="), 4);
	assert_int_equal(count(html, "<rect class=\"band loop\" x="), 4);
	assert_int_equal(count(html, "class=\"event fault\""), 4);
	assert_non_null(strstr(html, ">sigmoid</text>"));
	assert_non_null(strstr(html, "&lt;script&gt;alert(1)&lt;/script&gt; "
				     "&amp; O&#39;Neil"));
	assert_null(strstr(html, "<script"));
	assert_null(strstr(html, "<evil>"));
	assert_non_null(strstr(html, "&lt;evil&gt; note"));
	assert_null(strstr(html, "src="));
	/* along the colon, no patient: the rectum pushed at 20 N, the
	 * sigmoid's spike of 40 N and its loop of 2 s (the tip there) */
	assert_non_null(strstr(html, "<th>rectum</th><td>&ndash;</td><td>"
				     "&ndash;</td><td>11.0 s</td><td>none</td>"
				     "<td>20.0 N</td>"));
	assert_non_null(strstr(html, "<td>2.0 s</td><td>40.0 N</td>"));
	/* the spike's pixel: 40 N on the axis 0..40 N is the plot's top */
	force = strstr(html, "id=\"plot-force\"");
	force = strstr(force, "<path class=\"series\"");
	assert_non_null(force);
	path_end = strstr(force, "\"/>");
	assert_non_null(path_end);
	snprintf(series, sizeof(series), "%.*s", (int)(path_end - force), force);
	assert_non_null(strstr(series, ",34.0"));
	assert_true(count(series, " L") <= 2 * 951);
	snprintf(cmd, sizeof(cmd), "rm -r '%s'", dir);
	assert_int_equal(system(cmd), 0);
}

static void test_report_unwritable(void **state)
{
	struct session_file f;
	struct metrics_result m = { 0 };

	(void)state;
	make_session(&f);
	assert_true(report_write(&f, &m, NULL, "/proc/no/such/dir") < 0);
}

/* A session moving the tip at SPEED m/s for N records, its insertion
 * force 100 N per metre along the colon and its sigmoid bowed 1 cm beyond
 * 0.15 m: what it does at a place does not depend on when it got there. */
static void along_session(struct session_file *f, struct session_record *r,
			  size_t n, double speed, char *head)
{
	for (size_t k = 0; k < n; k++) {
		double s = 0.05 + speed * (double)k * 1e-3;

		memset(&r[k], 0, sizeof(r[k]));
		r[k].stamp_ns =
			ENDOSIM_NS_PER_S + (uint64_t)k * ENDOSIM_NS_PER_MS;
		r[k].depth_m = r[k].tip_s_m = (float)s;
		r[k].dir[2] = 1;
		r[k].limited[0] = (float)(100 * s);
		r[k].spans = 2;
		r[k].bow_m[0] = (float)(s > 0.15 ? 0.01 : 0);
	}
	*f = (struct session_file){
		.header = head, .case_text = case_text, .records = r,
		.n_records = n,
	};
}

/* The path strings (d="...") of the Nth and N+1st series after figure ID
 * in PAGE, into A and B. */
static void two_paths(const char *page, const char *id, char *a, char *b,
		      size_t size)
{
	const char *at = strstr(page, id);
	char *out[2] = { a, b };

	assert_non_null(at);
	for (int k = 0; k < 2; k++) {
		const char *d, *end;

		at = strstr(at, "class=\"series\"");
		assert_non_null(at);
		d = strstr(at, " d=\"") + 4;
		end = strchr(d, '"');
		assert_true((size_t)(end - d) < size);
		memcpy(out[k], d, (size_t)(end - d));
		out[k][end - d] = '\0';
		at = end;
	}
}

/* The largest difference between the points of two SVG paths of as many
 * points ("M x,y L x,y ..."), px; INFINITY if their points differ in
 * number. */
static double path_gap(const char *a, const char *b)
{
	double gap = 0;

	while (*a && *b) {
		char *ea, *eb;
		double va, vb;

		while (*a && !(*a == '-' || *a == '.' || (*a >= '0' && *a <= '9'))) {
			a++;
		}
		while (*b && !(*b == '-' || *b == '.' || (*b >= '0' && *b <= '9'))) {
			b++;
		}
		if (!*a || !*b) {
			break;
		}
		va = strtod(a, &ea);
		vb = strtod(b, &eb);
		gap = fmax(gap, fabs(va - vb));
		a = ea;
		b = eb;
	}
	return *a || *b ? INFINITY : gap;
}

/*
 * --reference: a trainee twice as fast as the reference over the same
 * colon with the same force at each place: their force and loop curves
 * along the colon are the same curve (aligned on the colon position, not
 * on time); their tip over time is not; both sessions' measures side by
 * side.
 */
static void test_report_reference(void **state)
{
	static struct session_record mine[10000], theirs[20000];
	static char a[1 << 16], b[1 << 16];
	static char head_mine[] = "format=3\nid=12\ntrainee=novice\n"
				  "case=straight\nversion=test\n";
	static char head_ref[] = "format=3\nid=9\ntrainee=expert\n"
				 "case=straight\nversion=test\n";
	struct session_file f, rf;
	struct metrics_params p;
	struct metrics_result m, rm;
	struct report_reference ref = { &rf, &rm };
	char dir[] = "/tmp/test_report_ref.XXXXXX", path[64], err[256];
	const char *page;

	(void)state;
	load_case();
	along_session(&f, mine, 10000, 0.02, head_mine);
	along_session(&rf, theirs, 20000, 0.01, head_ref);
	metrics_params_default(&p);
	assert_int_equal(sessionmetrics_compute(&f, &p, &m, err, sizeof(err)),
			 0);
	assert_int_equal(sessionmetrics_compute(&rf, &p, &rm, err,
						sizeof(err)), 0);
	assert_non_null(mkdtemp(dir));
	assert_int_equal(report_write(&f, &m, &ref, dir), 0);
	snprintf(path, sizeof(path), "%s/index.html", dir);
	page = slurp(path);
	assert_non_null(strstr(page, "Compared with the reference: session 9 "
				     "(expert)"));
	assert_non_null(strstr(page, "<th>duration (s)</th><td>10.0</td>"
				     "<td>20.0</td>"));
	/* the same curve to a tenth of a pixel (the largest force within each
	   centimetre: the faster session's last sample in it is 0.2 mm, the
	   slower's 0.1 mm, short of its end) */
	two_paths(page, "id=\"compare-force\"", a, b, sizeof(a));
	assert_true(strlen(a) > 100);
	assert_true(path_gap(a, b) <= 0.1 + 1e-9);
	two_paths(page, "id=\"compare-loop\"", a, b, sizeof(a));
	assert_true(path_gap(a, b) <= 0.1 + 1e-9);
	two_paths(page, "id=\"compare-tip\"", a, b, sizeof(a));
	assert_true(path_gap(a, b) > 10);
	/* without a reference, no such section */
	assert_int_equal(report_write(&f, &m, NULL, dir), 0);
	assert_null(strstr(slurp(path), "id=\"compare"));
	unlink(path);
	rmdir(dir);
}

/* The number after the last y1=" in PAGE before AT. */
static double y1_before(const char *page, const char *at)
{
	while (at > page && strncmp(at, "y1=\"", 4)) {
		at--;
	}
	assert_true(at > page);
	return strtod(at + 4, NULL);
}

/*
 * The loop row and the bow plot's threshold line give the threshold the
 * metrics counted from: the session's (sessioninputs.h), 1 cm in the
 * paper model, 3 cm in the rod's (its records' model).
 */
static void test_report_loop_threshold(void **state)
{
	static const struct { uint32_t model; const char *row, *tick; } m_of[] = {
		{ ENDOSIM_MODEL_PAPER, "bowed more than 1 cm", ">0.01</text>" },
		{ ENDOSIM_MODEL_ROD, "bowed more than 3 cm", ">0.03</text>" },
	};
	char dir[] = "/tmp/test_report_loop.XXXXXX", path[64], err[256];
	struct session_file f;
	struct metrics_params p;
	struct metrics_result m;

	(void)state;
	assert_non_null(mkdtemp(dir));
	snprintf(path, sizeof(path), "%s/index.html", dir);
	for (size_t i = 0; i < sizeof(m_of) / sizeof(m_of[0]); i++) {
		const char *page, *bow, *tick, *line;

		make_session(&f);
		for (size_t k = 0; k < f.n_records; k++) {
			records[k].model = m_of[i].model;
		}
		sessioninputs_file_metrics_params(&f, &p);
		assert_int_equal(sessionmetrics_compute(&f, &p, &m, err,
							sizeof(err)), 0);
		assert_int_equal(report_write(&f, &m, NULL, dir), 0);
		page = slurp(path);
		assert_non_null(strstr(page, m_of[i].row));
		/* the line at the height of the axis' grid line for it */
		bow = strstr(page, "id=\"plot-bow\"");
		assert_non_null(bow);
		tick = strstr(bow, m_of[i].tick);
		line = strstr(bow, "<line class=\"threshold\"");
		assert_non_null(tick);
		assert_non_null(line);
		assert_near(y1_before(bow, strchr(line, '>')),
			    y1_before(bow, tick), 0.05);
	}
	unlink(path);
	rmdir(dir);
}

/* The force plot's threshold line is the session's [session]
 * force_threshold_n, the one its metrics counted from. */
static void test_report_force_threshold(void **state)
{
	char dir[] = "/tmp/test_report_force.XXXXXX", path[64], err[256];
	struct session_file f;
	struct metrics_params p;
	struct metrics_result m;
	const char *page;

	(void)state;
	assert_non_null(mkdtemp(dir));
	snprintf(path, sizeof(path), "%s/index.html", dir);
	make_session(&f);
	f.config = "[session]\nforce_threshold_n = 12\n";
	sessioninputs_file_metrics_params(&f, &p);
	assert_near(p.force_threshold_n, 12, 1e-12);
	assert_int_equal(sessionmetrics_compute(&f, &p, &m, err, sizeof(err)),
			 0);
	assert_int_equal(report_write(&f, &m, NULL, dir), 0);
	page = slurp(path);
	assert_non_null(strstr(page, "threshold 12 N"));
	assert_null(strstr(page, "threshold 15 N"));
	unlink(path);
	rmdir(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_recomputed_metrics),
		cmocka_unit_test(test_report_page),
		cmocka_unit_test(test_report_unwritable),
		cmocka_unit_test(test_report_reference),
		cmocka_unit_test(test_report_loop_threshold),
		cmocka_unit_test(test_report_force_threshold),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
