/*
 * test_guide.c - guided replay (daemon/rig/guide.h): the path a session
 * file gives, and the guidance in the force loop, in lockstep on
 * simulated time (tests/tools/offline.h), so that every answer is the same
 * on any machine.
 *
 * The recording: the paper model's demo course on the normal case
 * (config/scenarios/demo-paper.scn: a scripted hand inserting at 3 cm/s
 * to the cecum), every cycle written to a session file as endosimd's
 * recorder writes it. The guided runs: the same rig and colon with a
 * passive hand (no force: the scope moves only as the motors and the
 * colon push it), the guidance playing that file.
 *
 * What the gains promise ([guide] defaults): the insertion's spring of
 * 4000 N/m holds the colon's largest force on this course (about 13 N) at
 * 3.3 mm, so the RMS error stays under 5 mm; the roll's 2 N m/rad holds
 * its friction torque (under 0.05 N m) at 1.4 degrees, under 3.
 *
 * The patient plays along: a short session recorded with the patient (a
 * valve held, the assistant's press and release, a turn) replayed on a
 * rig with its own: each change at its recorded time, the trainee's own
 * valve joining the recording's.
 *
 * The expert's tool is shown, not played: a session on the polyps case in
 * which the expert's snare captures and cuts the pedunculated polyp,
 * guided on a rig where the trainee holds her forceps in the channel and
 * the same polyp stands under the expert's loop: the published expert's
 * tool is the recording's at the playhead, cycle for cycle, only while
 * guiding; hers stays hers, and the polyp is never cut.
 *
 * Under the sanitizers (sanitized.h) the course is followed at 2x alone:
 * the same path and guidance in half the cycles; the 1x run is the plain
 * build's.
 *
 * Run from the top of the source tree (tests/run.sh does).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>

#include "conf/cases.h"
#include "rig/guide.h"
#include "loop/loop.h"
#include "proto/names.h"
#include "offline.h"
#include "proto/session_file.h"
#include "sanitized.h"

#define PERIOD_S (OFFLINE_PERIOD_NS * ENDOSIM_S_PER_NS)
#define CECUM_S_M 1.46  /* normal.case: where the cecum's segment starts */
#define SOURCE_ID 7

static char dir[] = "/tmp/test_guide.XXXXXX";
static char file[256];
static struct guide_path *path;
static double rec_cecum_s; /* the recording's tip at the cecum, s of it */

/* SCN played on CASE_FILE with CFG, the paper's model. */
static struct offline *on_case(struct config *cfg, struct scenario *scn,
			       const char *case_file)
{
	char err[512];
	struct colon *c;
	struct offline *o;

	cfg->haptics.model = HAPTICS_MODEL_PAPER;
	snprintf(cfg->colon.file, sizeof(cfg->colon.file), "%s", case_file);
	c = cases_load(cfg, NULL, err, sizeof(err));
	if (!c) {
		fail_msg("%s", err);
	}
	o = offline_create_with(cfg, c, scn, err, sizeof(err));
	if (!o) {
		fail_msg("%s", err);
	}
	return o;
}

static struct offline *on_normal(struct config *cfg, struct scenario *scn)
{
	return on_case(cfg, scn, "config/cases/normal.case");
}

/* What a recording's every cycle is shown to: the loop O, its state ST
 * at T_S from the first enabled one (-1 before). */
typedef void each_fn(struct offline *o, const struct endosim_state *st,
		     double t_s);

/*
 * SCN played on CASE_FILE with CFG, every cycle written to NAME as
 * endosimd's recorder writes a session (its id SOURCE_ID) after EACH saw
 * it. -1 when NAME cannot be written.
 */
static int record_on(const char *name, const char *case_file,
		     struct config *cfg, struct scenario *scn, each_fn *each)
{
	struct session_header h = {
		.id = SOURCE_ID, .trainee = "expert", .case_name = "normal",
		.started = "2026-11-25T00:00:00Z", .start_ns = OFFLINE_START_NS,
		.period_ns = OFFLINE_PERIOD_NS, .version = "test",
		.step_m = 0.002, .ring_vertices = 24, .segment_m = 0.05,
	};
	char text[1024];
	struct offline *o;
	long cycles;
	double t0 = -1;
	int fd = open(name, O_WRONLY | O_CREAT | O_TRUNC, 0644);

	if (fd < 0) {
		scenario_destroy(scn);
		return -1;
	}
	o = on_case(cfg, scn, case_file);
	cycles = (long)(offline_length_s(o) / PERIOD_S);
	session_header_text(&h, text, sizeof(text));
	session_file_write_magic(fd);
	session_file_write_frame(fd, SESSION_FRAME_HEADER, text,
				 (uint32_t)strlen(text));
	for (long k = 0; k < cycles; k++) {
		const struct endosim_state *st = offline_step(o);
		struct session_record r;
		double t = (st->stamp_ns - OFFLINE_START_NS) * ENDOSIM_S_PER_NS;

		if (st->state == ENDOSIM_STATE_ENABLED && t0 < 0) {
			t0 = t;
		}
		each(o, st, t0 < 0 ? -1 : t - t0);
		session_record_from_state(st, &r);
		session_file_write_frame(fd, SESSION_FRAME_RECORD, &r,
					 sizeof(r));
	}
	offline_destroy(o);
	close(fd);
	return 0;
}

/* SCN on the normal case, recorded (record_on()). */
static int record(const char *name, struct config *cfg, struct scenario *scn,
		  each_fn *each)
{
	return record_on(name, "config/cases/normal.case", cfg, scn, each);
}

static void cecum_seen(struct offline *o, const struct endosim_state *st,
		       double t_s)
{
	(void)o;
	if (rec_cecum_s < 0 && t_s >= 0 && st->scope.tip_s_m >= CECUM_S_M) {
		rec_cecum_s = t_s;
	}
}

/* The demo course, recorded into FILE as endosimd records a session. */
static int record_course(void **unused)
{
	struct config cfg;
	char err[512];
	struct scenario *scn;

	(void)unused;
	if (!mkdtemp(dir)) {
		return -1;
	}
	snprintf(file, sizeof(file), "%s/7.endoses", dir);
	config_defaults(&cfg);
	scn = scenario_load("config/scenarios/demo-paper.scn", err,
			    sizeof(err));
	rec_cecum_s = -1;
	if (!scn || record(file, &cfg, scn, cecum_seen)) {
		return -1;
	}
	path = guide_path_load(file, err, sizeof(err));
	if (!path) {
		fprintf(stderr, "%s\n", err);
		return -1;
	}
	printf("# the recording: %.2f s guided, the tip at the cecum at "
	       "%.2f s\n", guide_path_length_s(path), rec_cecum_s);
	return rec_cecum_s > 0 ? 0 : -1;
}

static int remove_course(void **unused)
{
	(void)unused;
	guide_path_free(path);
	unlink(file);
	rmdir(dir);
	return 0;
}

/* The normal case with a passive hand: no force on any axis until a
 * test appends steps to its scenario (*SCN, if asked for). */
static struct offline *passive_with(struct config *cfg, struct scenario **scn)
{
	struct scenario *s = scenario_create();

	config_defaults(cfg);
	if (scn) {
		*scn = s;
	}
	return on_normal(cfg, s);
}

static struct offline *passive(struct config *cfg)
{
	return passive_with(cfg, NULL);
}

static const struct endosim_state *command(struct offline *o,
					   enum guide_action action,
					   double speed, double from_s)
{
	const struct guide_command c = {
		.action = action, .path = path, .speed = speed,
		.from_s = from_s,
	};
	const struct endosim_state *st;

	offline_guide(o, &c);
	st = offline_step(o);
	assert_int_equal(offline_guide_answer(o), 0);
	return st;
}

/* Steps until the guidance is in PHASE (at most MAX_S); the last state. */
static const struct endosim_state *until(struct offline *o, uint32_t phase,
					 double max_s)
{
	const struct endosim_state *st = NULL;

	for (long k = 0; k < (long)(max_s / PERIOD_S); k++) {
		st = offline_step(o);
		if (st->guide.phase == phase) {
			return st;
		}
	}
	fail_msg("the guidance never got to %s in %.1f s",
		 names_guide_phase(phase), max_s);
	return st;
}

/* --- the path ---------------------------------------------------------- */

/* The path through the records: its samples are the records' positions
 * 10 ms apart, its curve passes through them with their speeds. */
static void test_path(void **unused)
{
	struct session_file f = { 0 };
	double q[ENDOSIM_AXES], dq[ENDOSIM_AXES], jump = 0;
	size_t i = 0;

	(void)unused;
	assert_int_equal(session_file_read(file, &f), 0);
	assert_int_equal(path->source_id, SOURCE_ID);
	assert_string_equal(path->case_name, "normal");
	assert_null(path->tool); /* recorded without a tool */
	assert_true(fabs(guide_path_length_s(path) -
			 (f.n_records - 1) * PERIOD_S) < 0.011);
	for (size_t k = 0; k < f.n_records; k += 997) {
		double t = k * PERIOD_S;

		guide_path_at(path, floor(t * GUIDE_PATH_HZ) / GUIDE_PATH_HZ,
			      q, dq);
		i = (size_t)(floor(t * GUIDE_PATH_HZ) * 10);
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			assert_true(fabs(q[a] - f.records[i].position[a]) <
				    1e-6);
		}
	}
	/* the speed along the curve: continuous across a sample, near the
	   recorded speed */
	for (double t = 5.0; t < 60; t += 0.37) {
		double before[ENDOSIM_AXES], after[ENDOSIM_AXES];
		double ts = floor(t * GUIDE_PATH_HZ) / GUIDE_PATH_HZ;

		guide_path_at(path, ts - 1e-7, q, before);
		guide_path_at(path, ts + 1e-7, q, after);
		jump = fmax(jump, fabs(after[0] - before[0]));
		i = (size_t)(ts / PERIOD_S + 0.5);
		assert_true(fabs(after[0] - f.records[i].velocity[0]) < 0.01);
	}
	printf("# path: speed continuous within %.2g m/s across samples\n",
	       jump);
	assert_true(jump < 1e-3);
	/* the nearest sample to a recorded position is where it was */
	for (size_t k = 3000; k < f.n_records; k += 9001) {
		double at[ENDOSIM_AXES], t;

		for (int a = 0; a < ENDOSIM_AXES; a++) {
			at[a] = f.records[k].position[a];
		}
		t = guide_path_nearest(path, at);
		guide_path_at(path, t, q, dq);
		assert_true(fabs(q[0] - at[0]) < 0.002);
	}
	session_file_close(&f);
}

/* A scenario's targets as the path: where its hand would put the axes. */
static void test_path_scenario(void **unused)
{
	char err[512];
	struct guide_path *p = guide_path_load("config/scenarios/demo-paper.scn",
					       err, sizeof(err));
	struct scenario *scn = scenario_load("config/scenarios/demo-paper.scn",
					     err, sizeof(err));
	double q[ENDOSIM_AXES], dq[ENDOSIM_AXES];

	(void)unused;
	assert_non_null(p);
	assert_non_null(scn);
	assert_string_equal(p->case_name, "");
	assert_true(fabs(guide_path_length_s(p) - scenario_length(scn)) <
		    0.011);
	for (double t = 1; t < scenario_length(scn); t += 7.3) {
		struct scenario_cmd c[ENDOSIM_AXES];

		scenario_eval(scn, floor(t * GUIDE_PATH_HZ) / GUIDE_PATH_HZ, c);
		guide_path_at(p, floor(t * GUIDE_PATH_HZ) / GUIDE_PATH_HZ, q,
			      dq);
		assert_int_equal(c[0].mode, SCENARIO_TARGET);
		assert_true(fabs(q[0] - c[0].value) < 1e-6);
	}
	scenario_destroy(scn);
	guide_path_free(p);
}

/* A file that is not a session, and one without an enabled record. */
static void test_path_refused(void **unused)
{
	char err[512], bad[300];
	struct session_record r = { .state = ENDOSIM_STATE_IDLE };
	const char *h = "format=3\nid=8\ncase=normal\n";
	int fd;

	(void)unused;
	assert_null(guide_path_load("config/cases/normal.case", err,
				    sizeof(err)));
	assert_non_null(strstr(err, "not a session file, nor a scenario"));
	snprintf(bad, sizeof(bad), "%s/idle.endoses", dir);
	fd = open(bad, O_WRONLY | O_CREAT | O_TRUNC, 0644);
	session_file_write_magic(fd);
	session_file_write_frame(fd, SESSION_FRAME_HEADER, h,
				 (uint32_t)strlen(h));
	for (int k = 0; k < 100; k++) {
		session_file_write_frame(fd, SESSION_FRAME_RECORD, &r,
					 sizeof(r));
	}
	close(fd);
	assert_null(guide_path_load(bad, err, sizeof(err)));
	assert_non_null(strstr(err, "no record with the rig enabled"));
	unlink(bad);
}

/*
 * A recording faster than speed_max (the insertion at 0.3 m/s) played at
 * 1x on an ideal plant (the axes where the reference is): the reference
 * moves at speed_max (0.1 m/s), the playhead at a third of the clock.
 */
static void test_slowed(void **unused)
{
	static float q[201][ENDOSIM_AXES];
	struct guide_path p = { .n = 201, .q = q, .case_name = "normal" };
	struct config cfg;
	struct guide g;
	double at[ENDOSIM_AXES] = { 0 }, v[ENDOSIM_AXES] = { 0 };
	double f[ENDOSIM_AXES], zero[ENDOSIM_AXES] = { 0 }, t0 = 0;
	const struct guide_command c = {
		.action = GUIDE_START, .path = &p, .speed = 1,
	};

	(void)unused;
	config_defaults(&cfg);
	for (size_t i = 0; i < p.n; i++) {
		q[i][0] = (float)(0.3 * (double)i / GUIDE_PATH_HZ);
	}
	guide_init(&g);
	assert_int_equal(guide_command(&g, &cfg.guide, &c, at), 0);
	for (int k = 0; k < 1000; k++) {
		guide_step(&g, &cfg.guide, true, true, at, v, zero, PERIOD_S,
			   f);
		memcpy(at, g.ref, sizeof(at));
		memcpy(v, g.ref_v, sizeof(v));
		if (k == 100) {
			t0 = g.t_s;
		}
		if (g.phase == ENDOSIM_GUIDE_GUIDING) {
			assert_true(fabs(g.ref_v[0]) <=
				    cfg.guide.speed_max[0] + 1e-12);
		}
	}
	assert_int_equal(g.phase, ENDOSIM_GUIDE_GUIDING);
	printf("# a 0.3 m/s recording: the reference at %.4f m/s, the "
	       "playhead at %.4fx\n", g.ref_v[0], (g.t_s - t0) / 0.899);
	assert_true(fabs(g.rate - cfg.guide.speed_max[0] / 0.3) < 1e-6);
	assert_true(fabs(g.ref_v[0] - cfg.guide.speed_max[0]) < 1e-6);
}

/*
 * A scope that cannot follow (held fast where it is, the motors' push
 * balanced by what holds it, so no hand is felt): the guidance ends itself
 * error_s after the error passed error_max, naming the axis, and fades
 * out; it never takes over, never faults.
 */
static void test_lost(void **unused)
{
	static float q[1001][ENDOSIM_AXES];
	struct guide_path p = { .n = 1001, .q = q, .case_name = "normal" };
	struct config cfg;
	struct guide g;
	double at[ENDOSIM_AXES] = { 0 }, zero[ENDOSIM_AXES] = { 0 };
	double f[ENDOSIM_AXES], t = 0, t_beyond = -1;
	const struct guide_command c = {
		.action = GUIDE_START, .path = &p, .speed = 1,
	};

	(void)unused;
	config_defaults(&cfg);
	for (size_t i = 0; i < p.n; i++) { /* 5 cm/s on the insertion */
		q[i][0] = (float)(0.05 * (double)i / GUIDE_PATH_HZ);
	}
	guide_init(&g);
	assert_int_equal(guide_command(&g, &cfg.guide, &c, at), 0);
	while (g.phase != ENDOSIM_GUIDE_OFF && t < 10) {
		guide_step(&g, &cfg.guide, true, true, at, zero, zero, PERIOD_S,
			   f);
		t += PERIOD_S;
		if (t_beyond < 0 &&
		    fabs(g.ref[0]) > cfg.guide.error_max[0]) {
			t_beyond = t;
		}
		if (g.phase == ENDOSIM_GUIDE_FADING) {
			assert_int_equal(g.ended, ENDOSIM_GUIDE_END_LOST);
		}
	}
	printf("# held fast: the error past %.0f mm at %.3f s, the guidance "
	       "ended %.3f s later (error_s %.1f)\n",
	       cfg.guide.error_max[0] * 1e3, t_beyond,
	       t - cfg.guide.fade_s - t_beyond, cfg.guide.error_s);
	assert_int_equal(g.phase, ENDOSIM_GUIDE_OFF);
	assert_int_equal(g.ended, ENDOSIM_GUIDE_END_LOST);
	assert_int_equal(g.lost_axis, ENDOSIM_AXIS_INSERTION);
	assert_int_equal(g.takeovers, 0);
	assert_true(fabs(t - cfg.guide.fade_s - t_beyond - cfg.guide.error_s) <
		    2 * PERIOD_S + 1e-9);
}

/* --- following --------------------------------------------------------- */

/* The whole recording at SPEED with a passive hand: the positions within
 * the promised RMS error of the recording's, the cecum at its time. */
static void follow(double speed, double cecum_tolerance_s)
{
	struct config cfg;
	struct offline *o = passive(&cfg);
	const struct endosim_state *st;
	double e_ins = 0, e_roll = 0, hand_max = 0, t = 0, cecum = -1;
	long n = 0;

	command(o, GUIDE_START, speed, 0);
	until(o, ENDOSIM_GUIDE_GUIDING, 5);
	do {
		st = offline_step(o);
		if (st->guide.phase != ENDOSIM_GUIDE_GUIDING) {
			break;
		}
		t += PERIOD_S;
		e_ins += st->guide.error[0] * st->guide.error[0];
		e_roll += st->guide.error[1] * st->guide.error[1];
		hand_max = fmax(hand_max, fabs(st->guide.hand[0]));
		n++;
		if (cecum < 0 && st->scope.tip_s_m >= CECUM_S_M) {
			cecum = t;
		}
		assert_int_equal(st->fault_bits, 0);
		/* recorded without a tool: no expert's tool shown */
		assert_int_equal(st->guide.expert_kind, ENDOSIM_TOOL_NONE);
	} while (t < 2 * guide_path_length_s(path) / speed);
	e_ins = sqrt(e_ins / (double)n);
	e_roll = sqrt(e_roll / (double)n);
	printf("# %.1fx: %.2f s guided (the recording %.2f s), RMS error "
	       "insertion %.2f mm, roll %.2f deg; the cecum at %.2f s "
	       "(recorded %.2f s, scaled %.2f s); the hand's estimate at "
	       "most %.2f N\n", speed, t, guide_path_length_s(path),
	       e_ins * 1e3, e_roll * 180 / M_PI, cecum, rec_cecum_s,
	       rec_cecum_s / speed, hand_max);
	assert_int_equal(st->guide.ended, ENDOSIM_GUIDE_END_DONE);
	assert_int_equal(st->guide.takeovers, 0);
	assert_true(e_ins <= 0.005);
	assert_true(e_roll <= 3 * M_PI / 180);
	assert_true(cecum > 0);
	assert_true(fabs(cecum - rec_cecum_s / speed) <= cecum_tolerance_s);
	offline_destroy(o);
}

static void test_follow_1x(void **unused)
{
	(void)unused;
	if (SANITIZED) {
		printf("skip - test_follow_1x under the sanitizers: the 2x run "
		       "follows the same path in half the cycles; the plain "
		       "build runs both\n");
		skip();
	}
	follow(1.0, 1.0);
}

static void test_follow_2x(void **unused)
{
	(void)unused;
	follow(2.0, 2.0);
}

/* --- take-over, resume, reset ----------------------------------------- */

/*
 * A hand that resists 10 s into the guidance, gripping the scope where it
 * is for 1 s (the scenario's spring-damper grip): taken over after
 * takeover_s (plus the estimate's lag), the force zero fade_s later, the
 * phase in the records; then resumed from the path's point nearest the
 * scope, which the grip held back while the recording went on.
 */
static void test_takeover(void **unused)
{
	struct config cfg;
	struct scenario *scn;
	struct offline *o = passive_with(&cfg, &scn);
	const struct endosim_state *st;
	double t_push, t_over, t_zero = -1, q[ENDOSIM_AXES], dq[ENDOSIM_AXES];
	double playhead, nearest, t;
	struct session_record r;
	char line[128], err[256];

	(void)unused;
	command(o, GUIDE_START, 1.0, 0);
	until(o, ENDOSIM_GUIDE_GUIDING, 5);
	for (long k = 0; k < 10000; k++) {
		st = offline_step(o);
	}
	t = st->scenario_time_s + 0.01;
	snprintf(line, sizeof(line), "%.3f insertion target %.5f", t,
		 st->axis[0].position);
	assert_int_equal(scenario_append(scn, line, err, sizeof(err)), 0);
	snprintf(line, sizeof(line), "%.3f insertion free", t + 1.0);
	assert_int_equal(scenario_append(scn, line, err, sizeof(err)), 0);
	/* the hand's own force (the simulated hand's, published) beyond the
	   take-over's threshold from ... */
	do {
		st = offline_step(o);
	} while (fabs(st->axis[0].hand) <= cfg.guide.takeover[0]);
	t_push = st->stamp_ns * ENDOSIM_S_PER_NS;
	st = until(o, ENDOSIM_GUIDE_FADING, 2);
	t_over = st->stamp_ns * ENDOSIM_S_PER_NS;
	playhead = st->guide.time_s;
	session_record_from_state(st, &r);
	assert_int_equal(r.guide_phase, ENDOSIM_GUIDE_FADING);
	for (long k = 0; k < 2000; k++) {
		st = offline_step(o);
		if (t_zero < 0 && st->guide.force[0] == 0 &&
		    st->guide.force[1] == 0) {
			t_zero = st->stamp_ns * ENDOSIM_S_PER_NS;
		}
		if (t_zero >= 0) {
			for (int a = 0; a < ENDOSIM_AXES; a++) {
				assert_true(st->guide.force[a] == 0);
			}
		}
	}
	printf("# take-over %.3f s after the grip's force passed the "
	       "threshold, the guidance's "
	       "force zero %.3f s after that\n", t_over - t_push,
	       t_zero - t_over);
	/* the estimate is what the motors push against: it leads the hand's
	   own force by the carriage's inertia, a few cycles at most */
	assert_true(t_over - t_push >= cfg.guide.takeover_s - 0.02);
	assert_true(t_over - t_push <= cfg.guide.takeover_s + 0.2);
	assert_true(t_zero > t_over && t_zero - t_over <= 0.5 + 1e-9);
	assert_int_equal(st->guide.phase, ENDOSIM_GUIDE_FREE);
	assert_int_equal(st->guide.takeovers, 1);

	/* the grip held the scope back: the nearest point is where it was
	   held, before the playhead */
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		q[a] = st->axis[a].position;
	}
	nearest = guide_path_nearest(path, q);
	guide_path_at(path, nearest, dq, q);
	printf("# held at %.3f m: resumed at %.2f s of the recording "
	       "(%.3f m there), taken over at %.2f s\n",
	       st->axis[0].position, nearest, dq[0], playhead);
	assert_true(nearest > 5 && nearest <= playhead);
	assert_true(fabs(dq[0] - st->axis[0].position) < 0.005);
	command(o, GUIDE_RESUME, 1.0, nearest);
	st = until(o, ENDOSIM_GUIDE_GUIDING, 5);
	for (long k = 0; k < 2000; k++) {
		st = offline_step(o);
	}
	assert_int_equal(st->guide.phase, ENDOSIM_GUIDE_GUIDING);
	assert_true(fabs(st->guide.error[0]) < 0.005);
	offline_destroy(o);
}

/*
 * Reset to the path from 20 cm off: at the path's point 20 cm back from
 * where the scope is, no faster than speed_max, then held within 5 mm.
 */
static void test_reset(void **unused)
{
	struct config cfg;
	struct offline *o = passive(&cfg);
	const struct endosim_state *st;
	double q[ENDOSIM_AXES], dq[ENDOSIM_AXES], to = -1, v_max = 0, off;

	(void)unused;
	command(o, GUIDE_START, 1.0, 0);
	until(o, ENDOSIM_GUIDE_GUIDING, 5);
	for (long k = 0; k < 20000; k++) {
		st = offline_step(o);
	}
	for (double t = 0; t < guide_path_length_s(path); t += 0.01) {
		guide_path_at(path, t, q, dq);
		if (fabs(q[0] - (st->axis[0].position - 0.20)) < 0.002) {
			to = t;
			break;
		}
	}
	assert_true(to >= 0);
	off = st->axis[0].position - q[0];
	command(o, GUIDE_RESET, 1.0, to);
	do {
		st = offline_step(o);
		v_max = fmax(v_max, fabs(st->axis[0].velocity));
	} while (st->guide.phase == ENDOSIM_GUIDE_MOVING);
	assert_int_equal(st->guide.phase, ENDOSIM_GUIDE_HOLDING);
	for (long k = 0; k < 1000; k++) {
		st = offline_step(o);
		v_max = fmax(v_max, fabs(st->axis[0].velocity));
	}
	printf("# reset from %.3f m off: at most %.3f m/s (limit %.3f), "
	       "then %.2f mm from the path's point (the guide's error "
	       "%.2f mm)\n", off, v_max, cfg.guide.speed_max[0],
	       fabs(st->axis[0].position - q[0]) * 1e3,
	       fabs(st->guide.error[0]) * 1e3);
	/* held at the path's point asked for, not only at its reference */
	assert_true(fabs(st->axis[0].position - q[0]) <= 0.005);
	assert_true(v_max <= cfg.guide.speed_max[0] * 1.05);
	assert_true(fabs(st->guide.error[0]) <= 0.005);
	assert_int_equal(st->guide.phase, ENDOSIM_GUIDE_HOLDING);
	offline_destroy(o);
}

/* A disable ends the guidance at once, with no force; so does a stop,
 * fading out. Commands out of range are refused. */
static void test_ends(void **unused)
{
	struct config cfg;
	struct offline *o = passive(&cfg);
	const struct endosim_state *st;
	const struct guide_command fast = {
		.action = GUIDE_START, .path = path, .speed = 3,
	};
	const struct guide_command late = {
		.action = GUIDE_START, .path = path, .speed = 1,
		.from_s = guide_path_length_s(path) + 1,
	};

	(void)unused;
	offline_guide(o, &fast);
	offline_step(o);
	assert_int_equal(offline_guide_answer(o), -EINVAL);
	offline_guide(o, &late);
	offline_step(o);
	assert_int_equal(offline_guide_answer(o), -EINVAL);

	command(o, GUIDE_START, 1.0, 0);
	until(o, ENDOSIM_GUIDE_GUIDING, 5);
	command(o, GUIDE_STOP, 1.0, 0);
	st = until(o, ENDOSIM_GUIDE_OFF, 1);
	assert_int_equal(st->guide.ended, ENDOSIM_GUIDE_END_STOPPED);

	command(o, GUIDE_START, 1.0, 0);
	until(o, ENDOSIM_GUIDE_GUIDING, 5);
	offline_command(o, LOOP_CMD_DISABLE);
	st = offline_step(o);
	assert_int_equal(st->guide.phase, ENDOSIM_GUIDE_OFF);
	assert_int_equal(st->guide.ended, ENDOSIM_GUIDE_END_NOT_ENABLED);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		assert_true(st->guide.force[a] == 0);
		assert_true(st->axis[a].limited == 0);
	}
	offline_destroy(o);
}

/* --- the patient plays along ------------------------------------------ */

/* The moments the patient changed (s of the path; -1: not yet). */
struct patient_times {
	double air_on, air_off, press, turn, release, both;
};

static struct patient_times seen;

/* Notes the first time of each change in ST at T_S into SEEN. */
static void note(struct patient_times *pt, const struct endosim_state *st,
		 double t_s)
{
	const struct endosim_patient_state *p = &st->patient;

	if (t_s < 0) {
		return;
	}
	if (pt->air_on < 0 && (p->valves & ENDOSIM_VALVE_AIR)) {
		pt->air_on = t_s;
	}
	if (pt->air_on >= 0 && pt->air_off < 0 &&
	    !(p->valves & ENDOSIM_VALVE_AIR)) {
		pt->air_off = t_s;
	}
	if (pt->both < 0 && p->valves == (ENDOSIM_VALVE_AIR |
					  ENDOSIM_VALVE_SUCTION)) {
		pt->both = t_s;
	}
	if (pt->press < 0 && p->hand_site == 0 && p->hand_n == 30) {
		pt->press = t_s;
	}
	if (pt->turn < 0 && p->position == ENDOSIM_POSITION_SUPINE) {
		pt->turn = t_s;
	}
	if (pt->press >= 0 && pt->release < 0 && p->hand_site == -1) {
		pt->release = t_s;
	}
}

static void patient_seen(struct offline *o, const struct endosim_state *st,
			 double t_s)
{
	(void)o;
	note(&seen, st, t_s);
}

#define NOT_SEEN { -1, -1, -1, -1, -1, -1 }

/* The trainee's hand on the suction valve at T_S of her scenario S. */
static void suction(struct scenario *s, double t_s, const char *how)
{
	char line[64], err[256];

	snprintf(line, sizeof(line), "%.3f valve suction %s", t_s, how);
	assert_int_equal(scenario_append(s, line, err, sizeof(err)), 0);
}

/*
 * An expert's session with the patient: the insertion moving on (so that
 * there is a path), the air valve held from 0.5 to 1.0 s, the assistant
 * pressing llq with 30 N at 1.5 s, the patient turned supine at 2.0 s,
 * the hand let go at 2.5 s. Guided replay of it on a passive rig with
 * the patient: each change at its recorded time on the path's clock
 * (within 20 ms: two of the path's samples), the trainee's own suction
 * pressed meanwhile joining the recording's air; in the end the
 * trainee's patient lies as the expert's did. Without the patient in
 * the recording, its path has none.
 */
static void test_patient_plays(void **unused)
{
	static const char *const lines[] = {
		"0 insertion target 0.05 3", "0.5 valve air on",
		"1.0 valve air off", "1.5 patient press llq 30",
		"2.0 patient position supine", "2.5 patient release",
		"3.5 end", NULL,
	};
	struct patient_times rec = NOT_SEEN, got = NOT_SEEN;
	struct config cfg;
	struct scenario *scn = scenario_create(), *trainee;
	struct guide_path *p;
	struct offline *o;
	char name[300], err[512];
	const struct endosim_state *st;
	double t0 = -1;

	(void)unused;
	for (const char *const *l = lines; *l; l++) {
		assert_int_equal(scenario_append(scn, *l, err, sizeof(err)), 0);
	}
	snprintf(name, sizeof(name), "%s/patient.endoses", dir);
	config_defaults(&cfg);
	cfg.patient.enabled = true;
	seen = rec;
	assert_int_equal(record(name, &cfg, scn, patient_seen), 0);
	rec = seen;
	p = guide_path_load(name, err, sizeof(err));
	unlink(name);
	assert_non_null(p);
	assert_non_null(p->patient);
	assert_null(path->patient); /* the demo's: recorded without one */

	/* the trainee's rig: nobody's hand on the scope, her suction
	 * pressed from 0.65 to 0.75 s of the path */
	config_defaults(&cfg);
	cfg.patient.enabled = true;
	trainee = scenario_create();
	o = on_normal(&cfg, trainee);
	offline_guide(o, &(struct guide_command){
		.action = GUIDE_START, .path = p, .speed = 1 });
	do {
		st = offline_step(o);
		if (t0 < 0 && st->guide.phase == ENDOSIM_GUIDE_GUIDING) {
			t0 = st->scenario_time_s - st->guide.time_s;
			suction(trainee, t0 + 0.65, "on");
			suction(trainee, t0 + 0.75, "off");
		}
		note(&got, st, t0 < 0 ? -1 : st->guide.time_s);
	} while (st->guide.phase != ENDOSIM_GUIDE_OFF &&
		 st->scenario_time_s < 10);
	printf("# the expert's patient (s of the path): air %.3f-%.3f, "
	       "pressed %.3f, supine %.3f, let go %.3f; replayed: air "
	       "%.3f-%.3f, pressed %.3f, supine %.3f, let go %.3f; the "
	       "trainee's suction with the air at %.3f\n", rec.air_on,
	       rec.air_off, rec.press, rec.turn, rec.release, got.air_on,
	       got.air_off, got.press, got.turn, got.release, got.both);
	assert_int_equal(st->guide.ended, ENDOSIM_GUIDE_END_DONE);
	assert_true(rec.air_on > 0.4 && rec.release > 2.4);
	assert_true(fabs(got.air_on - rec.air_on) <= 0.02);
	assert_true(fabs(got.air_off - rec.air_off) <= 0.02);
	assert_true(fabs(got.press - rec.press) <= 0.02);
	assert_true(fabs(got.turn - rec.turn) <= 0.02);
	assert_true(fabs(got.release - rec.release) <= 0.02);
	assert_true(got.both > got.air_on && got.both < got.air_off);
	assert_int_equal(st->patient.position, ENDOSIM_POSITION_SUPINE);
	assert_int_equal(st->patient.hand_site, -1);
	assert_int_equal(st->fault_bits, 0);
	offline_destroy(o);
	guide_path_free(p);
}

/* --- the expert's tool shown ------------------------------------------ */

#define POLYPS_CASE "config/cases/polyps.case"
#define EXPERT_SNARE_M 0.020
#define EXPERT_DEPTH_M 0.010
#define EXPERT_SHUT 0.1     /* the handle closed on the stalk */
#define EXPERT_S 4.0        /* the recording's length, s */
#define EXPERT_RECORDS 4010 /* its records, at most */
#define TRAINEE_DEPTH_M -0.005 /* her forceps, in the channel */
#define TRAINEE_OPENING 0.3
#define RAMP_S 0.1          /* the rigs' enable ramp: short, not to wait */

/* The expert's snare and what became of it, recorded cycle by cycle. */
static struct expert_run {
	int ip;                /* the case's pedunculated polyp */
	double base[3], normal[3]; /* where it stood, under the loop */
	bool placed;
	double cut_s;          /* the polyp cut free (s of the path) */
	long first;            /* the first enabled record */
	long n;                /* records so far */
	float loop_m[EXPERT_RECORDS]; /* each record's loop, m */
} ex;

/* The case's pedunculated polyp in C. */
static int pedunculated(const struct colon *c)
{
	const struct anatomy *a = colon_anatomy(c);

	for (int i = 0; a && i < a->polyps; i++) {
		if (a->polyp[i].paris == ANATOMY_PARIS_IP) {
			return i;
		}
	}
	fail_msg("no pedunculated polyp in %s", POLYPS_CASE);
	return -1;
}

/* From A to B as T goes from T0 to T1. */
static double ramp(double t, double t0, double t1, double a, double b)
{
	double f = (t - t0) / (t1 - t0);

	return a + (b - a) * fmax(0, fmin(1, f));
}

/* The pedunculated polyp of O's tool stood under the open loop of ST:
 * its stalk through the loop's centre along the channel's radial
 * direction (test_tool_loop's placing; held there, off the wall). */
static void under_the_loop(struct offline *o, const struct endosim_state *st)
{
	struct tool_params par = TOOL_PARAMS_DEFAULT;
	struct tool_polyp *p = &offline_tool(o)->polyp[ex.ip];
	struct tool_pose pose;
	double h = tool_polyp_height(p, par.lift_m);

	tool_pose(&par, &st->scope, st->tool.depth_m, &pose);
	for (int k = 0; k < 3; k++) {
		p->base[k] = st->tool.loop_centre[k] + h / 2 * pose.radial[k];
		p->normal[k] = -pose.radial[k];
	}
	p->on_wall = false;
	memcpy(ex.base, p->base, sizeof(ex.base));
	memcpy(ex.normal, p->normal, sizeof(ex.normal));
	ex.placed = true;
}

/*
 * The expert's hand, each cycle of the recording: a 20 mm snare handed
 * over; its sheath out 10 mm (0 .. 0.3 s), the loop opened (.. 0.6 s),
 * the case's pedunculated polyp standing under it, the loop closed on
 * the stalk (0.7 .. 1.0 s), the pedal down from 1.2 s until it is cut,
 * the snare back in the channel (0.3 s after the cut, over 0.3 s).
 */
static void expert_hand(struct offline *o, const struct endosim_state *st,
			double t_s)
{
	double depth, opening;

	if (ex.n == 0) {
		ex.ip = pedunculated(offline_colon(o));
		offline_tool_select(o, TOOL_SNARE, EXPERT_SNARE_M);
	}
	if (t_s >= 0 && ex.first < 0) {
		ex.first = ex.n;
	}
	if (ex.n < (long)(sizeof(ex.loop_m) / sizeof(ex.loop_m[0]))) {
		ex.loop_m[ex.n] = (float)st->tool.loop_m;
	}
	ex.n++;
	if (st->tool.events & ENDOSIM_TOOL_CUT) {
		ex.cut_s = t_s;
	}
	if (t_s >= 0.65 && !ex.placed) {
		under_the_loop(o, st);
	}
	t_s = fmax(0, t_s);
	depth = ex.cut_s > 0 ? ramp(t_s, ex.cut_s + 0.3, ex.cut_s + 0.6,
				    EXPERT_DEPTH_M, -EXPERT_DEPTH_M)
			     : ramp(t_s, 0, 0.3, -EXPERT_DEPTH_M,
				    EXPERT_DEPTH_M);
	opening = t_s < 0.7 ? ramp(t_s, 0.3, 0.6, 0, 1)
			    : ramp(t_s, 0.7, 1.0, 1, EXPERT_SHUT);
	offline_tool_input(o, depth, opening, t_s >= 1.2 && ex.cut_s < 0,
			   0.003);
}

/* A cycle of the trainee's rig: her forceps held in the channel. */
static const struct endosim_state *trainee_step(struct offline *o)
{
	offline_tool_input(o, TRAINEE_DEPTH_M, TRAINEE_OPENING, false, 0.003);
	return offline_step(o);
}

/* The trainee's rig for the expert's recording: the polyps case, the
 * pedunculated polyp where the expert's stood, her forceps in the
 * channel; nobody's hand on the scope. */
static struct offline *trainee_rig(struct config *cfg)
{
	struct offline *o;
	struct tool *t;

	config_defaults(cfg);
	cfg->limits.enable_ramp_s = RAMP_S;
	o = on_case(cfg, scenario_create(), POLYPS_CASE);
	t = offline_tool(o);
	memcpy(t->polyp[ex.ip].base, ex.base, sizeof(ex.base));
	memcpy(t->polyp[ex.ip].normal, ex.normal, sizeof(ex.normal));
	t->polyp[ex.ip].on_wall = false;
	offline_tool_select(o, TOOL_FORCEPS, 0);
	while (trainee_step(o)->safety.ramp < 1) { /* enabled in full */
	}
	assert_int_equal(offline_tool_answer(o), 0);
	return o;
}

/* What the expert's tool and hers must be after a cycle (ST) of guided
 * replay of F (the expert's records), counted in *SHOWN and *PEDAL
 * while it shows the expert's. */
static void check_shown(const struct endosim_state *st,
			const struct session_file *f, long *shown,
			long *pedal)
{
	const struct endosim_guide_state *g = &st->guide;
	const struct session_record *r;
	struct tool_params par = TOOL_PARAMS_DEFAULT;
	struct tool_pose pose;
	long k;

	/* hers, as she holds it; the polyp uncut, nothing happening */
	assert_int_equal(st->tool.kind, ENDOSIM_TOOL_FORCEPS);
	assert_true(st->tool.depth_m == TRAINEE_DEPTH_M);
	assert_true(st->tool.opening == TRAINEE_OPENING);
	assert_int_equal(st->tool.pedal, 0);
	assert_int_equal(st->tool.events, 0);
	assert_int_equal(st->tool.polyp[ex.ip].state, ENDOSIM_POLYP_IN_PLACE);
	assert_true(st->tool.polyp[ex.ip].energy_j == 0);
	assert_true(st->tool.blood_m3 == 0);
	assert_int_equal(st->fault_bits, 0);
	if (g->phase != ENDOSIM_GUIDE_GUIDING) {
		assert_int_equal(g->expert_kind, ENDOSIM_TOOL_NONE);
		assert_true(g->expert_depth_m == 0 && g->expert_opening == 0 &&
			    g->expert_pedal == 0 && g->expert_loop_m == 0);
		return;
	}
	/* the record of the path's sample nearest the playhead */
	k = ex.first + (long)(g->time_s * GUIDE_PATH_HZ + 0.5) *
		       (long)(1 / (GUIDE_PATH_HZ * PERIOD_S) + 0.5);
	assert_true(k < (long)f->n_records && k < ex.n);
	r = &f->records[k];
	assert_int_equal(g->expert_kind, r->tool_kind);
	if (r->tool_kind == ENDOSIM_TOOL_NONE) {
		return;
	}
	assert_true(g->expert_snare_m == r->tool_snare_m);
	assert_true(g->expert_depth_m == r->tool_depth_m);
	assert_true(g->expert_opening == r->tool_opening);
	assert_int_equal(g->expert_pedal, r->tool_pedal);
	/* the loop the recording's model had; on the scope as it is now */
	assert_true(fabs(g->expert_loop_m - ex.loop_m[k]) < 1e-6);
	tool_pose(&par, &st->scope, r->tool_depth_m, &pose);
	for (int c = 0; c < 3; c++) {
		assert_true(fabs(g->expert_tip[c] - pose.tip[c]) < 1e-12);
		assert_true(fabs(g->expert_loop_centre[c] - pose.tip[c] -
				 g->expert_loop_m / 2 * pose.dir[c]) < 1e-12);
	}
	*shown += 1;
	*pedal += g->expert_pedal;
}

/* Steps O (guided replay of F) for MAX_S, or until the guidance is in
 * PHASE (-1: the whole time) and then fails if it never was, each cycle
 * checked; the last state. */
static const struct endosim_state *
checked(struct offline *o, const struct session_file *f, int phase,
	double max_s, long *shown, long *pedal)
{
	const struct endosim_state *st = NULL;

	for (long k = 0; k < (long)(max_s / PERIOD_S + 0.5); k++) {
		st = trainee_step(o);
		check_shown(st, f, shown, pedal);
		if (phase >= 0 && st->guide.phase == (uint32_t)phase) {
			return st;
		}
	}
	if (phase >= 0) {
		fail_msg("the guidance never got to %s in %.1f s",
			 names_guide_phase((uint32_t)phase), max_s);
	}
	return st;
}

/* The guidance command C on O, answered in its next (checked) cycle. */
static void checked_command(struct offline *o, const struct session_file *f,
			    struct guide_command c)
{
	long none = 0;

	offline_guide(o, &c);
	checked(o, f, -1, PERIOD_S, &none, &none);
	assert_int_equal(offline_guide_answer(o), 0);
}

/*
 * An expert's snare recorded on the polyps case (expert_hand(): the
 * pedunculated polyp captured and cut hot), guided on the trainee's rig
 * with her forceps in the channel. At every cycle: while GUIDING, the
 * published expert's tool is the recording's sample nearest the playhead
 * (its kind, size, depth, opening, pedal exactly; its loop the
 * recording's model's, the stalk held included; its tip and loop on the
 * scope as it is now, with the channel's place), at 1x and at 2x; in any
 * other phase (moving to the path, holding after a reset, fading and
 * free after a take-over, off) none; her forceps as she holds them, no
 * event, the polyp under the expert's loop in place, no energy into it,
 * no blood. The pedal shown down about as long as the expert held it,
 * over the speed.
 */
static void test_tool_shown(void **unused)
{
	struct config cfg;
	struct scenario *scn = scenario_create();
	struct session_file f = { 0 };
	struct guide_path *p;
	struct offline *o;
	char name[300], err[512];
	long shown, pedal, recorded_pedal = 0, none = 0;

	(void)unused;
	assert_int_equal(scenario_append(scn, "4 end", err, sizeof(err)), 0);
	snprintf(name, sizeof(name), "%s/tool.endoses", dir);
	memset(&ex, 0, sizeof(ex));
	ex.first = -1;
	ex.cut_s = -1;
	config_defaults(&cfg);
	cfg.limits.enable_ramp_s = RAMP_S;
	assert_int_equal(record_on(name, POLYPS_CASE, &cfg, scn, expert_hand),
			 0);
	printf("# the expert's recording: the stalk cut at %.3f s\n",
	       ex.cut_s);
	assert_true(ex.placed && ex.cut_s > 1.2 && ex.cut_s < 3.3);
	assert_int_equal(session_file_read(name, &f), 0);
	p = guide_path_load(name, err, sizeof(err));
	assert_non_null(p);
	assert_non_null(p->tool);
	for (size_t i = 0; i < f.n_records; i++) {
		recorded_pedal += f.records[i].tool_pedal;
	}

	o = trainee_rig(&cfg);
	for (int speed = 1; speed <= 2; speed++) {
		const struct endosim_state *st;

		checked_command(o, &f, (struct guide_command){
			.action = GUIDE_START, .path = p, .speed = speed });
		checked(o, &f, ENDOSIM_GUIDE_GUIDING, 1, &none, &none);
		shown = pedal = 0;
		st = checked(o, &f, ENDOSIM_GUIDE_OFF, EXPERT_S + 2, &shown,
			     &pedal);
		printf("# %dx: the expert's tool shown %ld cycles, its pedal "
		       "down %ld (recorded %ld cycles)\n", speed, shown,
		       pedal, recorded_pedal);
		assert_int_equal(st->guide.ended, ENDOSIM_GUIDE_END_DONE);
		assert_true(shown > (long)(3.0 / speed / PERIOD_S));
		assert_true(pedal > 0 &&
			    labs(pedal * speed - recorded_pedal) <= 20);
		if (speed > 1) {
			break;
		}
		/* reset: moving, then holding */
		checked_command(o, &f, (struct guide_command){
			.action = GUIDE_RESET, .from_s = 1.5 });
		checked(o, &f, ENDOSIM_GUIDE_HOLDING, 1, &none, &none);
		st = checked(o, &f, -1, 0.2, &none, &none);
		assert_int_equal(st->guide.phase, ENDOSIM_GUIDE_HOLDING);
		/* resumed: shown again; taken over: fading, then free */
		checked_command(o, &f, (struct guide_command){
			.action = GUIDE_RESUME, .from_s = 1.5 });
		checked(o, &f, ENDOSIM_GUIDE_GUIDING, 1, &none, &none);
		shown = 0;
		checked(o, &f, -1, 0.2, &shown, &none);
		assert_true(shown > 0);
		checked_command(o, &f, (struct guide_command){
			.action = GUIDE_TAKEOVER });
		checked(o, &f, ENDOSIM_GUIDE_FREE, 2, &none, &none);
		checked(o, &f, -1, 0.2, &none, &none);
	}
	offline_destroy(o);
	guide_path_free(p);
	session_file_close(&f);
	unlink(name);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_path),
		cmocka_unit_test(test_path_refused),
		cmocka_unit_test(test_path_scenario),
		cmocka_unit_test(test_slowed),
		cmocka_unit_test(test_lost),
		cmocka_unit_test(test_follow_1x),
		cmocka_unit_test(test_follow_2x),
		cmocka_unit_test(test_takeover),
		cmocka_unit_test(test_reset),
		cmocka_unit_test(test_ends),
		cmocka_unit_test(test_patient_plays),
		cmocka_unit_test(test_tool_shown),
	};

	return cmocka_run_group_tests(tests, record_course, remove_course);
}
