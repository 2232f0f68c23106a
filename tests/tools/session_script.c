/*
 * session_script - writes a session file (session_file.h) of a scripted,
 * plausible colonoscopy, for the report's tests without the daemon:
 *
 *   session_script [--rate HZ] [--ring N] CASE_FILE OUT.endoses [TRAINEE]
 *
 * Records at HZ (default 100; the daemon's are 1000) on the colon at N
 * vertices a ring (default 96; the daemon's 192): idle for 2 s, enabled; insertion at ~3 cm/s along the
 * centreline (stop and go), a sigmoid loop pushed to 3.5 cm with the
 * insertion force above 15 N, then reduced; a small transverse loop; a
 * fault with a re-enable at the splenic flexure; 10 s at the cecum; a
 * withdrawal of ~6.5 min looking around the wall (the view 35 deg off the
 * lumen, circling); an END frame with the metrics computed on the way.
 * The tip's pose is on the centreline bowed as recorded, like the daemon's.
 */
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "model/colon.h"
#include "session/metrics.h"
#include "session/metricstext.h"
#include "proto/session_file.h"
#include "base/vec3.h"

#define START_NS 1000000000000ull

static uint64_t period_ns = 10000000ull; /* --rate */
static uint32_t ring = 96;                /* --ring */

struct synth {
	int fd;
	struct colon *colon;
	struct metrics *metrics;
	uint64_t k;
	double s, bow[2];
	uint32_t state;
};

static double ramp(double t, double t0, double t1)
{
	return fmin(1, fmax(0, (t - t0) / (t1 - t0)));
}

static int put_event(struct synth *y, uint32_t kind, int axis,
		     uint32_t detail, double value, const char *text)
{
	unsigned char buf[256];
	struct session_event ev = {
		.stamp_ns = START_NS + y->k * period_ns, .kind = kind,
		.axis = axis, .detail = detail, .value = value,
	};
	size_t n = strlen(text);

	memcpy(buf, &ev, sizeof(ev));
	memcpy(buf + sizeof(ev), text, n);
	metrics_event(y->metrics, &ev, text);
	return session_file_write_frame(y->fd, SESSION_FRAME_EVENT, buf,
					(uint32_t)(sizeof(ev) + n));
}

/* The pose at S, looking LOOK rad off the lumen, circling at PHASE. */
static void pose(struct synth *y, struct session_record *r, double look,
		 double phase)
{
	const struct centreline *cl = colon_centreline(y->colon);
	struct centreline_point q;
	double axis[3], d[3];

	colon_bow(y->colon, 0, y->bow[0], false);
	colon_bow(y->colon, 1, y->bow[1], false);
	centreline_at_s(cl, y->s, &q);
	vec3_scale(axis, q.u, cos(phase));
	vec3_axpy(axis, axis, sin(phase), q.v);
	vec3_rotate(d, q.t, axis, look);
	for (int j = 0; j < 3; j++) {
		r->tip[j] = (float)q.p[j];
		r->dir[j] = (float)d[j];
		r->up[j] = (float)q.u[j];
	}
	r->depth_m = (float)(y->s + fabs(y->bow[0]) + fabs(y->bow[1]));
	r->tip_s_m = (float)y->s;
	r->base_s_m = (float)fmax(0, y->s - 0.09);
	r->bow_m[0] = (float)y->bow[0];
	r->bow_m[1] = (float)y->bow[1];
	r->spans = 2;
}

/* Forces: friction with depth, the loops' mesentery, wall contact. */
static void forces(struct synth *y, struct session_record *r, double t,
		   double v)
{
	double f = 2 + 3 * y->s + 400 * (y->bow[0] + y->bow[1]) +
		   0.8 * sin(t * 2.1);

	f = v >= 0 ? f : -0.6 * f;
	r->limited[0] = r->command[0] = (float)(y->state == 1 ? f : 0);
	r->limited[1] = (float)(y->state == 1 ? 0.02 * sin(t * 0.13) +
				0.01 * sin(t * 0.9) : 0);
	r->limited[2] = (float)(y->state == 1 ? 0.05 * sin(t * 0.05) * (0.2 + y->s) : 0);
	r->limited[3] = (float)(y->state == 1 ? 0.03 * cos(t * 0.07) * (0.2 + y->s) : 0);
	r->contact = fmod(t, 23) < 1.5;
	r->f_static[0] = r->contact ? 2.5f : 0;
	r->normal[2] = 1;
	r->velocity[0] = (float)v;
	r->state = y->state;
	r->ramp = y->state == 1;
}

static int put_record(struct synth *y, double t, double v, double look,
		      double phase)
{
	struct session_record r;

	memset(&r, 0, sizeof(r));
	r.tool_captured = -1; /* no tool, as the daemon records it */
	r.tool_event_polyp = -1;
	r.cycle = y->k;
	r.stamp_ns = START_NS + y->k * period_ns;
	pose(y, &r, look, phase);
	forces(y, &r, t, v);
	r.scenario_time_s = (float)t;
	metrics_record(y->metrics, &r);
	y->k++;
	return session_file_write_frame(y->fd, SESSION_FRAME_RECORD, &r,
					sizeof(r));
}

static int set_state(struct synth *y, uint32_t state)
{
	y->state = state;
	return put_event(y, SESSION_EVENT_STATE, -1, 0, state, "");
}

/* Insertion to the cecum, with the loops and the fault on the way. */
static int insert(struct synth *y, double cecum_s)
{
	double t0 = (double)y->k * period_ns * ENDOSIM_S_PER_NS, t = t0, v;
	int r = 0;
	bool faulted = false;

	while (!r && y->s < cecum_s + 0.02) {
		t = (double)y->k * period_ns * ENDOSIM_S_PER_NS;
		v = 0.03 * (1 + 0.6 * sin((t - t0) / 3));
		/* the sigmoid loop: the tip held at 0.40 m while pushing */
		y->bow[0] = 0.035 * ramp(t, t0 + 12, t0 + 20) *
			    (1 - ramp(t, t0 + 26, t0 + 32));
		y->bow[1] = 0.013 * ramp(t, t0 + 52, t0 + 55) *
			    (1 - ramp(t, t0 + 60, t0 + 63));
		if (t > t0 + 12 && t < t0 + 32) {
			v = t < t0 + 26 ? 0.002 : -0.01;
		}
		if (!faulted && y->s > 0.65) {
			faulted = true;
			r = put_event(y, SESSION_EVENT_FAULT, 0, 7,
				      0, "insertion force saturated 0.5 s");
			r = r ? r : set_state(y, 3);
		}
		if (y->state == 3 && t > t0 + 40) {
			r = set_state(y, 0);
			r = r ? r : set_state(y, 1);
		}
		v = y->state == 1 ? v : 0;
		y->s += v * period_ns * ENDOSIM_S_PER_NS;
		r = r ? r : put_record(y, t, v, 0.15 * sin(t), t);
	}
	return r;
}

static int withdraw(struct synth *y, double cecum_s)
{
	double t0 = (double)y->k * period_ns * ENDOSIM_S_PER_NS, t;
	int r = 0;

	while (!r && y->s > 0.01) {
		t = (double)y->k * period_ns * ENDOSIM_S_PER_NS - t0;
		if (t < 10) { /* looking around the cecum */
			r = put_record(y, t + t0, 0, 0.6, t * 1.3);
			continue;
		}
		y->s -= (cecum_s / 390) * period_ns * ENDOSIM_S_PER_NS;
		r = put_record(y, t + t0, -cecum_s / 390, 0.6, t * 2.6);
	}
	for (uint64_t i = 0; !r && i < 3000000000ull / period_ns; i++) {
		/* out */
		y->s = 0;
		r = put_record(y, (double)y->k * period_ns * ENDOSIM_S_PER_NS,
			       0, 0, 0);
	}
	return r;
}

static int write_head(struct synth *y, const char *case_path,
		      const char *trainee, char *case_text, size_t n)
{
	char head[1024];
	FILE *f = fopen(case_path, "r");
	size_t got;

	if (!f) {
		return -errno;
	}
	got = fread(case_text, 1, n - 1, f);
	fclose(f);
	case_text[got] = '\0';
	session_header_text(&(struct session_header){
				    .id = 42, .trainee = trainee,
				    .case_name = colon_name(y->colon),
				    .started = "2026-11-20T09:30:00Z",
				    .start_ns = START_NS, .period_ns = period_ns,
				    .version = "synth", .step_m = 0.002,
				    .ring_vertices = ring, .segment_m = 0.04 },
			    head, sizeof(head));
	if (session_file_write_magic(y->fd) ||
	    session_file_write_frame(y->fd, SESSION_FRAME_HEADER, head,
				     (uint32_t)strlen(head)) ||
	    session_file_write_frame(y->fd, SESSION_FRAME_CONFIG, "[loop]\n",
				     7) ||
	    session_file_write_frame(y->fd, SESSION_FRAME_CASE, case_text,
				     (uint32_t)got)) {
		return -EIO;
	}
	return 0;
}

static int run(struct synth *y, const char *case_path, const char *trainee)
{
	static char case_text[1 << 16], end[1 << 14];
	struct metrics_result res;
	double cecum_s = colon_cecum_s(y->colon);
	int r = write_head(y, case_path, trainee, case_text, sizeof(case_text));

	for (uint64_t i = 0; !r && i < 2000000000ull / period_ns; i++) {
		r = put_record(y, (double)y->k * period_ns * ENDOSIM_S_PER_NS,
			       0, 0, 0);
	}
	r = r ? r : set_state(y, 1);
	r = r ? r : put_event(y, SESSION_EVENT_PARAM, -1, 0, 0,
			      "haptics.friction_n_s_per_m_rad=0.8");
	r = r ? r : insert(y, cecum_s);
	r = r ? r : withdraw(y, cecum_s);
	r = r ? r : set_state(y, 0);
	if (r) {
		return r;
	}
	metrics_result(y->metrics, &res);
	r = metricstext_format(&res, end, sizeof(end));
	if (r < 0) {
		return r;
	}
	fputs(end, stdout);
	return session_file_write_frame(y->fd, SESSION_FRAME_END, end,
					(uint32_t)r);
}

int main(int argc, char **argv)
{
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct metrics_params mp;
	struct synth y = { .fd = -1 };
	struct anatomy a;
	char err[256];
	int r;

	for (int o; (o = getopt_long(argc, argv, "", (const struct option[]){
			{ "rate", required_argument, NULL, 'r' },
			{ "ring", required_argument, NULL, 'n' },
			{ 0 } }, NULL)) != -1;) {
		double v = o == '?' ? 0 : atof(optarg);

		if (o == 'r' && v >= 1 && v <= 10000) {
			period_ns = (uint64_t)llround(ENDOSIM_NS_PER_S / v);
		} else if (o == 'n' && v >= 8 && v <= 4096) {
			ring = (uint32_t)v;
		} else {
			argc = 0; /* usage */
			break;
		}
	}
	argc -= optind;
	argv += optind - 1;
	if (argc < 2) {
		fprintf(stderr, "usage: session_script [--rate HZ] [--ring N] "
			"CASE OUT [TRAINEE]\n");
		return 2;
	}
	cp.ring_vertices = ring;
	if (anatomy_load(&a, argv[1], err, sizeof(err)) ||
	    !(y.colon = colon_create(&a, &cp, err, sizeof(err)))) {
		fprintf(stderr, "session_script: %s\n", err);
		return 1;
	}
	metrics_params_default(&mp);
	y.metrics = metrics_create(y.colon, &mp);
	y.fd = open(argv[2], O_WRONLY | O_CREAT | O_TRUNC, 0644);
	r = y.fd < 0 || !y.metrics ? -errno :
	    run(&y, argv[1], argc > 2 ? argv[3] : "");
	if (r) {
		fprintf(stderr, "session_script: %s: %s\n", argv[2], strerror(-r));
	}
	if (y.fd >= 0) {
		close(y.fd);
	}
	metrics_destroy(y.metrics);
	colon_destroy(y.colon);
	return r ? 1 : 0;
}
