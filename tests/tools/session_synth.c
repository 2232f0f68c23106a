/*
 * session_synth - a session file (docs/SESSION_FORMAT.md) without a
 * daemon: a scenario played on a case by endosimd's own force-loop parts
 * off line (offline.h: the simulated rig and hand, the kinematics, the
 * haptics), one RECORD per 1 ms cycle as the daemon publishes it, and in
 * the rod model a SHAPE every 33rd cycle as the daemon's recorder writes
 * them, for the replay's and the metrics' tests.
 *
 *   session_synth [--at T]... [--trainee NAME] [--set SECTION.KEY=VALUE]...
 *                 [--pain T:LEVEL]... [--tear T:SEGMENT] [--sedation NAME]
 *                 CASE SCENARIO OUT [SECONDS]
 *
 * CASE: a case file (the colon at the default resolution); SCENARIO: the
 * simulated hand's script; OUT: the file written; SECONDS: how much of the
 * scenario (default: all of it); --set: a configuration key, as endosimd's
 * (haptics.model=rod). --pain (repeatable, in increasing T): the
 * patient's pain level recorded instead of the model's, LEVEL at T
 * seconds after the first record, linear between two, held before the
 * first and after the last; the patient then shows as enabled (sedation
 * NAME, default moderate), the cause looping, in the sigmoid (segment
 * 2), the heart at 70 + 4 LEVEL beats a minute, SpO2 0.97; --tear:
 * the wall torn by the tip in SEGMENT from T seconds on (the viewer's
 * voice and panel tests). The file holds HEADER (every key of the
 * format), CONFIG (the defaults with [case] file = CASE and the keys set, as
 * endosimd --print-config prints them), CASE (the file's text), a STATE
 * event (ENABLED) at the first record, the RECORDs (and SHAPEs), and END
 * (cycles, duration_s).
 *
 * --at T (repeatable): the truth at T seconds after the first record,
 * printed to stdout as state_text.h's lines each prefixed "T: ": the
 * record's fields as the file holds them (through
 * session_record_from_state() and back) with, in the rod model, the
 * SHAPE at or before it as the file holds it, and the tube the daemon
 * would have published for that cycle (not in the file).
 *
 * Exit status: 0, 1 on a failure (said on stderr), 2 usage.
 */
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "conf/cases.h"
#include "offline.h"
#include "proto/names.h"
#include "proto/session_file.h"
#include "proto/state_text.h"
#include "proto/version.h"

#define MAX_AT 32
#define MAX_PAIN 32
#define BATCH (64u << 10)
#define SCENE_ID 1

struct synth {
	const char *case_path, *scenario, *out, *trainee;
	double seconds;
	double at[MAX_AT];
	int n_at;
	double pain_s[MAX_PAIN], pain[MAX_PAIN]; /* --pain */
	int n_pain;
	double tear_s;      /* --tear, or INFINITY */
	int tear_segment;
	int sedation;
	struct config cfg;
	struct colon *colon;
	int fd;
	unsigned char *buf;
	size_t used;
	struct session_shape shape; /* the last written */
	unsigned char payload[sizeof(struct session_shape)];
};

static void usage(void)
{
	fprintf(stderr, "usage: session_synth [--at T]... [--trainee NAME] "
		"[--set SECTION.KEY=VALUE]...\n"
		"                     [--pain T:LEVEL]... [--tear T:SEGMENT] "
		"[--sedation NAME]\n"
		"                     CASE SCENARIO OUT [SECONDS]\n");
	exit(2);
}

/* --set SECTION.KEY=VALUE into S's configuration, or usage. */
static void set_key(struct synth *s, char *arg)
{
	char *eq = strchr(arg, '=');
	char err[256];

	if (!eq) {
		usage();
	}
	*eq = '\0';
	if (config_set(&s->cfg, arg, eq + 1, false, err, sizeof(err))) {
		fprintf(stderr, "session_synth: --set %s: %s\n", arg, err);
		exit(2);
	}
}

/* --pain T:LEVEL, --tear T:SEGMENT and --sedation NAME into S, or
 * usage. */
static void patient_option(struct synth *s, int c, const char *arg)
{
	double t, v;

	if (c == 'S') {
		s->sedation = names_sedation_find(arg);
		if (s->sedation < 0) {
			usage();
		}
		return;
	}
	if (sscanf(arg, "%lf:%lf", &t, &v) != 2 ||
	    (c == 'p' && (s->n_pain == MAX_PAIN ||
			  (s->n_pain && t < s->pain_s[s->n_pain - 1])))) {
		usage();
	}
	if (c == 'p') {
		s->pain_s[s->n_pain] = t;
		s->pain[s->n_pain++] = v;
	} else {
		s->tear_s = t;
		s->tear_segment = (int)v;
	}
}

/* The options into S, whose configuration has its defaults. */
static void parse(int argc, char **argv, struct synth *s)
{
	static const struct option longs[] = {
		{ "at", required_argument, NULL, 'a' },
		{ "trainee", required_argument, NULL, 't' },
		{ "set", required_argument, NULL, 's' },
		{ "pain", required_argument, NULL, 'p' },
		{ "tear", required_argument, NULL, 'T' },
		{ "sedation", required_argument, NULL, 'S' },
		{ 0 },
	};
	int c;

	s->trainee = "synth";
	s->seconds = -1;
	s->tear_s = INFINITY;
	s->sedation = ENDOSIM_SEDATION_MODERATE;
	while ((c = getopt_long(argc, argv, "", longs, NULL)) != -1) {
		if (c == 'a' && s->n_at < MAX_AT) {
			s->at[s->n_at++] = atof(optarg);
		} else if (c == 'p' || c == 'T' || c == 'S') {
			patient_option(s, c, optarg);
		} else if (c == 't') {
			s->trainee = optarg;
		} else if (c == 's') {
			set_key(s, optarg);
		} else {
			usage();
		}
	}
	if (argc - optind < 3 || argc - optind > 4) {
		usage();
	}
	s->case_path = argv[optind];
	s->scenario = argv[optind + 1];
	s->out = argv[optind + 2];
	if (argc - optind == 4) {
		s->seconds = atof(argv[optind + 3]);
	}
}

/* The whole of PATH, NUL-terminated (free() it); NULL with errno. */
static char *slurp(const char *path)
{
	FILE *f = fopen(path, "r");
	char *text = NULL;
	size_t size = 0;
	FILE *m = f ? open_memstream(&text, &size) : NULL;
	char chunk[4096];
	size_t n;

	while (m && (n = fread(chunk, 1, sizeof(chunk), f)) > 0) {
		fwrite(chunk, 1, n, m);
	}
	if (m) {
		fclose(m);
	}
	if (f) {
		fclose(f);
	}
	return text;
}

static int put(struct synth *s, uint32_t type, const void *p, uint32_t n)
{
	if (s->used + n + 12 > BATCH) {
		if (write(s->fd, s->buf, s->used) != (ssize_t)s->used) {
			return -EIO;
		}
		s->used = 0;
	}
	if (n + 12 > BATCH) {
		return session_file_write_frame(s->fd, type, p, n);
	}
	s->used += session_frame_put(s->buf, BATCH, s->used, type, p, n);
	return 0;
}

static int put_text(struct synth *s, uint32_t type, const char *text)
{
	return put(s, type, text, (uint32_t)strlen(text));
}

static int write_head(struct synth *s)
{
	const struct config *c = &s->cfg;
	char header[1024], started[32], *config = NULL, *text;
	struct session_header h;
	size_t size = 0;
	time_t now = time(NULL);
	struct tm tm;
	FILE *m = open_memstream(&config, &size);
	int r;

	if (!m) {
		return -ENOMEM;
	}
	config_print(c, m);
	fclose(m);
	gmtime_r(&now, &tm);
	strftime(started, sizeof(started), "%Y-%m-%dT%H:%M:%SZ", &tm);
	h = (struct session_header){
		.id = 1, .trainee = s->trainee,
		.case_name = colon_name(s->colon), .started = started,
		.start_ns = OFFLINE_START_NS, .period_ns = OFFLINE_PERIOD_NS,
		.version = ENDOSIM_VERSION, .step_m = c->colon.step_m,
		.ring_vertices = (int)c->colon.ring_vertices,
		.segment_m = c->colon.segment_m,
	};
	session_header_text(&h, header, sizeof(header));
	text = slurp(s->case_path);
	r = session_file_write_magic(s->fd);
	r = r ? r : put_text(s, SESSION_FRAME_HEADER, header);
	r = r ? r : put_text(s, SESSION_FRAME_CONFIG, config);
	r = r ? r : !text ? -errno : put_text(s, SESSION_FRAME_CASE, text);
	free(text);
	free(config);
	return r;
}

static int put_event(struct synth *s, uint64_t stamp_ns, uint32_t kind,
		     double value)
{
	struct session_event ev = { .stamp_ns = stamp_ns, .kind = kind,
				    .axis = -1, .value = value };

	return put(s, SESSION_FRAME_EVENT, &ev, sizeof(ev));
}

/* --pain's level at T_S. */
static double pain_at(const struct synth *s, double t_s)
{
	int i = 0;

	while (i < s->n_pain && s->pain_s[i] <= t_s) {
		i++;
	}
	if (i == 0 || i == s->n_pain) {
		return s->pain[i ? i - 1 : 0];
	}
	return s->pain[i - 1] + (s->pain[i] - s->pain[i - 1]) *
		(t_s - s->pain_s[i - 1]) / (s->pain_s[i] - s->pain_s[i - 1]);
}

/* --pain and --tear at cycle K into ST (nothing without --pain). */
static void patient_schedule(const struct synth *s, long k,
			     struct endosim_state *st)
{
	struct endosim_patient_state *p = &st->patient;
	double t_s = (double)k * OFFLINE_PERIOD_NS * ENDOSIM_S_PER_NS;

	if (!s->n_pain) {
		return;
	}
	p->enabled = 1;
	p->sedation = (uint32_t)s->sedation;
	p->pain = pain_at(s, t_s);
	p->pain_stimulus = p->pain;
	p->pain_cause = p->pain > 0 ? ENDOSIM_PAIN_LOOPING :
				      ENDOSIM_PAIN_NONE;
	p->pain_place = p->pain > 0 ? 2 : -1;
	p->heart_rate_bpm = 70 + 4 * p->pain; /* a stand-in, not vitals.h */
	p->spo2 = 0.97;
	p->torn_segment = t_s >= s->tear_s ? s->tear_segment : -1;
}

/* The truth at cycle K (from 0), if one was asked for then. */
static void truth(const struct synth *s, long k, const struct endosim_state *st)
{
	struct session_record rec;
	struct endosim_state back;
	char prefix[32];

	for (int i = 0; i < s->n_at; i++) {
		if (llround(s->at[i] * ENDOSIM_NS_PER_S / OFFLINE_PERIOD_NS) !=
		    k) {
			continue;
		}
		session_record_from_state(st, &rec);
		session_record_to_state(&rec, &back);
		if (back.rod.model == ENDOSIM_MODEL_ROD) {
			session_shape_to_state(&s->shape, &back);
		}
		memcpy(back.scope.tube, st->scope.tube, sizeof(back.scope.tube));
		snprintf(prefix, sizeof(prefix), "%g: ", s->at[i]);
		state_text_print(stdout, prefix, &back);
	}
}

static int run(struct synth *s, struct offline *o, long cycles)
{
	uint32_t every = session_shape_every(OFFLINE_PERIOD_NS);
	struct endosim_state st;
	struct session_record rec;
	char end[128];
	int r = write_head(s);

	for (long k = 0; !r && k < cycles; k++) {
		st = *offline_step(o);
		patient_schedule(s, k, &st);
		if (k == 0) {
			r = put_event(s, st.stamp_ns, SESSION_EVENT_STATE,
				      ENDOSIM_STATE_ENABLED);
		}
		session_record_from_state(&st, &rec);
		r = r ? r : put(s, SESSION_FRAME_RECORD, &rec, sizeof(rec));
		if (!r && session_shape_due(&st, every)) {
			session_shape_from_state(&st, &s->shape);
			r = put(s, SESSION_FRAME_SHAPE, s->payload,
				session_shape_pack(&s->shape, s->payload));
		}
		truth(s, k, &st);
	}
	snprintf(end, sizeof(end), "cycles=%ld\nduration_s=%.3f\n", cycles,
		 cycles > 0 ? (double)(cycles - 1) * OFFLINE_PERIOD_NS *
				      ENDOSIM_S_PER_NS
			    : 0.0);
	r = r ? r : put_text(s, SESSION_FRAME_END, end);
	if (!r && write(s->fd, s->buf, s->used) != (ssize_t)s->used) {
		r = -EIO;
	}
	return r;
}

int main(int argc, char **argv)
{
	struct synth s = { .fd = -1 };
	struct offline *o = NULL;
	char err[512];
	int r = 1;

	config_defaults(&s.cfg);
	parse(argc, argv, &s);
	snprintf(s.cfg.colon.file, sizeof(s.cfg.colon.file), "%s",
		 s.case_path);
	s.colon = cases_load(&s.cfg, NULL, err, sizeof(err));
	o = s.colon ? offline_create(&s.cfg, s.colon, s.scenario, err,
				     sizeof(err)) : NULL; /* it owns the colon */
	if (!o) {
		fprintf(stderr, "session_synth: %s\n", err);
		goto out;
	}
	if (s.seconds < 0) {
		s.seconds = offline_length_s(o);
	}
	s.buf = malloc(BATCH);
	s.fd = open(s.out, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
	if (!s.buf || s.fd < 0) {
		fprintf(stderr, "session_synth: %s: %s\n", s.out,
			strerror(errno));
		goto out;
	}
	r = run(&s, o,
		lround(s.seconds * ENDOSIM_NS_PER_S / OFFLINE_PERIOD_NS) + 1);
	if (r) {
		fprintf(stderr, "session_synth: %s: %s\n", s.out,
			strerror(-r));
	}
	r = r ? 1 : 0;
out:
	if (s.fd >= 0) {
		close(s.fd);
	}
	free(s.buf);
	offline_destroy(o);
	return r;
}
