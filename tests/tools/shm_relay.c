/*
 * shm_relay - republishes endosimd's shared-memory state under another
 * name, with some of its fields set by hand: what the viewer's tests (and
 * the README's pictures) need to show a loop, a contact or the force's
 * parts before the force model makes them. The scene stays the daemon's:
 * point endoview's --socket at the daemon and its --shm-name at TO.
 *
 *   shm_relay FROM TO [--bow SPAN=METRES]... [--contact]
 *
 *   --bow K=M    mobile span K bowed M metres (scope.bow_m[K])
 *   --contact    the wall holds the tip: the proxy 2 mm behind the tip
 *                along its view direction, the normal facing the tip
 *
 * Relays every millisecond until SIGTERM or SIGINT. Exit 0, 1 when either
 * object cannot be opened, 2 on usage.
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "log.h"
#include "publish.h"
#include "shm_reader.h"

#define PROXY_BACK_M 0.002

struct edits {
	double bow[ENDOSIM_SPANS];
	int has_bow[ENDOSIM_SPANS];
	int contact;
};

static volatile sig_atomic_t stop;

static void on_signal(int sig)
{
	(void)sig;
	stop = 1;
}

static int parse(int argc, char **argv, struct edits *e)
{
	for (int k = 3; k < argc; k++) {
		int span;
		double m;

		if (!strcmp(argv[k], "--contact")) {
			e->contact = 1;
		} else if (!strcmp(argv[k], "--bow") && k + 1 < argc &&
			   sscanf(argv[++k], "%d=%lf", &span, &m) == 2 &&
			   span >= 0 && span < ENDOSIM_SPANS) {
			e->bow[span] = m;
			e->has_bow[span] = 1;
		} else {
			return -1;
		}
	}
	return 0;
}

static void edit(struct endosim_state *st, const struct edits *e)
{
	struct endosim_haptics_state *h = &st->haptics;

	for (int k = 0; k < ENDOSIM_SPANS; k++) {
		if (e->has_bow[k]) {
			st->scope.bow_m[k] = e->bow[k];
		}
	}
	if (!e->contact) {
		return;
	}
	h->contact = 1;
	h->constraints = 1;
	h->penetration_m = PROXY_BACK_M;
	for (int d = 0; d < 3; d++) {
		h->proxy[d] = st->scope.tip[d] -
			      PROXY_BACK_M * st->scope.dir[d];
		h->normal[d] = -st->scope.dir[d];
	}
}

static void relay(struct shm_reader *from, struct publish *to,
		  const struct edits *e)
{
	const struct timespec ms = { .tv_nsec = 1000000 };
	struct endosim_state st;

	while (!stop && shm_reader_writer_alive(from)) {
		if (shm_reader_read(from, &st, 8) == 0) {
			edit(&st, e);
			publish_state(to, &st);
		}
		nanosleep(&ms, NULL);
	}
}

int main(int argc, char **argv)
{
	struct edits e = { 0 };
	const struct endosim_shm *hdr;
	struct shm_reader *from;
	struct publish *to;

	if (argc < 3 || parse(argc, argv, &e)) {
		fprintf(stderr, "usage: shm_relay FROM TO "
			"[--bow SPAN=METRES]... [--contact]\n");
		return 2;
	}
	log_init("shm_relay", LOG_NOTICE);
	from = shm_reader_open(argv[1]);
	if (!from) {
		fprintf(stderr, "shm_relay: %s: %s\n", argv[1],
			strerror(errno));
		return 1;
	}
	hdr = shm_reader_header(from);
	to = publish_create(argv[2], hdr->period_ns, hdr->start_ns);
	if (!to) {
		shm_reader_close(from);
		return 1;
	}
	signal(SIGTERM, on_signal);
	signal(SIGINT, on_signal);
	relay(from, to, &e);
	publish_destroy(to);
	shm_reader_close(from);
	return 0;
}
