/* emu.c - see emu.h. */
#include "emu.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define TRAVEL_RAD 1e7 /* the motor turns freely */

void emu_motor_init(struct emu_motor *m, const struct emu_motor_params *p)
{
	struct plant_params pp = {
		.inertia = p->inertia_kg_m2,
		.viscous = p->viscous_nm_s,
		.coulomb = p->coulomb_nm,
		.min = -TRAVEL_RAD,
		.max = TRAVEL_RAD,
	};

	memset(m, 0, sizeof(*m));
	plant_init(&m->plant, &pp, 0.0);
	m->hold_nm_per_rad = p->hold_nm_per_rad;
}

static void step(struct emu_motor *m, double dt_s)
{
	double hand = m->hand_nm - m->hold_nm_per_rad * m->plant.x;

	if (m->hand_hz > 0) {
		hand += m->hand_amp_nm * sin(2.0 * M_PI * m->hand_hz * m->t_s);
	}
	m->t_s += dt_s;
	if (m->moving) {
		m->plant.v = m->move_rad_s;
		m->plant.x += m->move_rad_s * dt_s;
		return;
	}
	plant_step(&m->plant, m->drive_nm + hand, dt_s);
}

void emu_motor_advance(struct emu_motor *m, double dt_s)
{
	if (!m->moving) {
		dt_s = fmin(dt_s, 0.05);
	}
	for (double t = 0; t < dt_s; t += 0.001) {
		step(m, fmin(0.001, dt_s - t));
	}
}

int emu_motor_hand(struct emu_motor *m, const char *args)
{
	double torque = 0, hz = 0;
	int n = sscanf(args, "%lf %lf", &torque, &hz);

	if (n < 1) {
		return -EINVAL;
	}
	m->moving = false;
	m->hand_hz = n == 2 ? hz : 0;
	m->hand_amp_nm = n == 2 ? torque : 0;
	m->hand_nm = n == 2 ? 0 : torque;
	return 0;
}

bool emu_motor_option(struct emu_motor_params *p, const char *arg)
{
	static const struct {
		const char *name;
		size_t offset;
	} opts[] = {
		{ "inertia=", offsetof(struct emu_motor_params, inertia_kg_m2) },
		{ "viscous=", offsetof(struct emu_motor_params, viscous_nm_s) },
		{ "coulomb=", offsetof(struct emu_motor_params, coulomb_nm) },
		{ "hold=", offsetof(struct emu_motor_params, hold_nm_per_rad) },
	};

	for (size_t i = 0; i < sizeof(opts) / sizeof(opts[0]); i++) {
		size_t len = strlen(opts[i].name);

		if (!strncmp(arg, opts[i].name, len)) {
			*(double *)((char *)p + opts[i].offset) =
				atof(arg + len);
			return true;
		}
	}
	return false;
}

double emu_now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

void emu_sleep_s(double s)
{
	struct timespec ts = { .tv_sec = (time_t)s,
			       .tv_nsec = (long)((s - floor(s)) * 1e9) };

	if (s > 0) {
		nanosleep(&ts, NULL);
	}
}

int emu_control_open(const char *path)
{
	if (mkfifo(path, 0600) < 0 && errno != EEXIST) {
		return -1;
	}
	/* read-write: the FIFO never reports end-of-file between writers */
	return open(path, O_RDWR | O_NONBLOCK | O_CLOEXEC);
}

void emu_control_poll(int fd, struct emu_lines *lb,
		      void (*fn)(void *ctx, char *line), void *ctx)
{
	ssize_t n;
	char *nl;

	if (fd < 0) {
		return;
	}
	while ((n = read(fd, lb->buf + lb->len,
			 sizeof(lb->buf) - 1 - lb->len)) > 0) {
		lb->len += (size_t)n;
		lb->buf[lb->len] = '\0';
		while ((nl = strchr(lb->buf, '\n'))) {
			*nl = '\0';
			fn(ctx, lb->buf);
			lb->len -= (size_t)(nl + 1 - lb->buf);
			memmove(lb->buf, nl + 1, lb->len + 1);
		}
		if (lb->len == sizeof(lb->buf) - 1) {
			lb->len = 0; /* a line too long: dropped */
		}
	}
}

/*
 * The state file is written by a thread of its own: a write (a new file
 * renamed over the old, 50 times a second) can wait on the disk's journal
 * for hundreds of milliseconds on a busy machine, and the emulator's loop,
 * which answers the bus, must never wait with it (33-wheel-stop once saw
 * a Modbus TCP request time out after 0.3 s so). The loop hands over the
 * newest text; the writer writes the newest it has.
 */
#define STATE_TEXT_MAX 65536

static struct {
	pthread_mutex_t lock;
	pthread_cond_t more;
	bool started, dirty;
	char path[4096];
	char text[STATE_TEXT_MAX];
} state = { .lock = PTHREAD_MUTEX_INITIALIZER,
	    .more = PTHREAD_COND_INITIALIZER };

/* PATH replaced by TEXT: a new file renamed over it. */
static void write_file(const char *path, const char *text)
{
	char tmp[4200];
	FILE *f;

	snprintf(tmp, sizeof(tmp), "%s.tmp", path);
	f = fopen(tmp, "w");
	if (!f) {
		return;
	}
	fputs(text, f);
	if (fclose(f) == 0) {
		rename(tmp, path);
	}
}

static void *state_writer(void *arg)
{
	static char path[4096], text[STATE_TEXT_MAX];

	(void)arg;
	for (;;) {
		pthread_mutex_lock(&state.lock);
		while (!state.dirty) {
			pthread_cond_wait(&state.more, &state.lock);
		}
		memcpy(path, state.path, sizeof(path));
		memcpy(text, state.text, sizeof(text));
		state.dirty = false;
		pthread_mutex_unlock(&state.lock);
		write_file(path, text);
	}
	return NULL;
}

void emu_state_write(const char *path, const char *text)
{
	pthread_t t;

	pthread_mutex_lock(&state.lock);
	if (!state.started) {
		state.started = pthread_create(&t, NULL, state_writer, NULL) == 0;
		if (!state.started) { /* no thread: written here, as before */
			pthread_mutex_unlock(&state.lock);
			write_file(path, text);
			return;
		}
		pthread_detach(t);
	}
	snprintf(state.path, sizeof(state.path), "%s", path);
	snprintf(state.text, sizeof(state.text), "%s", text);
	state.dirty = true;
	pthread_cond_signal(&state.more);
	pthread_mutex_unlock(&state.lock);
}

void emu_trace(FILE *f, const char *tag, const uint8_t *p, size_t n,
	       const char *note)
{
	if (!f) {
		return;
	}
	fprintf(f, "%.6f %s", emu_now_s(), tag);
	for (size_t i = 0; i < n; i++) {
		fprintf(f, " %02x", p[i]);
	}
	fprintf(f, "%s%s\n", note && *note ? "  ; " : "", note ? note : "");
	fflush(f);
}

int emu_words(char *line, char **word, int max)
{
	char *save = NULL;
	int n = 0;

	for (char *w = strtok_r(line, " \t", &save); w && n < max;
	     w = strtok_r(NULL, " \t", &save)) {
		word[n++] = w;
	}
	return n;
}
