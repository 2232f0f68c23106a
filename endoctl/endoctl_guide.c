/*
 * endoctl_guide.c - `endoctl guide ...`: guided replay of a recorded
 * session through the rig's motors (proto's Guide request). Every action
 * answers with the status; `guide status` reads it on the read-only
 * socket.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "endoctl/endoctl.h"
#include "proto/names.h"

#define GUIDE_USAGE                                                          \
	"endoctl guide start ID|FILE [--speed X] [--from S] | stop | " \
	"takeover | resume | reset [--to S] | status\n"

/* The expert's tool shown while guiding, if any: "; expert: ...". */
static void print_expert(const Endosim__GuideStatus *g)
{
	if (g->expert_kind == ENDOSIM_TOOL_NONE) {
		return;
	}
	printf("; expert: %s", names_tool(g->expert_kind));
	if (g->expert_kind == ENDOSIM_TOOL_SNARE) {
		printf(" %.0f mm", g->expert_snare_m * 1e3);
	}
	printf(g->expert_depth_m > 0 ? ", %.1f mm out" : ", in the channel",
	       g->expert_depth_m * 1e3);
	printf(", handle %.0f %% open, pedal %s", g->expert_opening * 100,
	       g->expert_pedal ? "down" : "up");
}

/* The guidance in one line. */
static void print_guide(const Endosim__GuideStatus *g)
{
	static const char *const unit[] = { "mm", "deg", "deg", "deg" };
	static const double scale[] = { 1e3, 57.29577951308232,
					57.29577951308232, 57.29577951308232 };

	if (!g) {
		printf("guide: not known to this endosimd\n");
		return;
	}
	printf("guide: %s", names_guide_phase(g->phase));
	if (g->source_id) {
		printf(", session %llu at %.2f of %.2f s, %.2fx",
		       (unsigned long long)g->source_id, g->time_s,
		       g->length_s, g->speed);
	}
	if (g->phase == ENDOSIM_GUIDE_OFF && g->ended) {
		printf(" (ended: %s%s%s)", names_guide_end(g->ended),
		       g->ended == ENDOSIM_GUIDE_END_LOST ? ", " : "",
		       g->ended == ENDOSIM_GUIDE_END_LOST ?
		       names_guide_axis(g->lost_axis) : "");
	}
	printf(", taken over %u time%s", g->takeovers,
	       g->takeovers == 1 ? "" : "s");
	if (g->n_error == ENDOSIM_AXES && g->phase != ENDOSIM_GUIDE_OFF) {
		printf("; error");
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			printf(" %s %+.1f %s", names_axis(a),
			       g->error[a] * scale[a], unit[a]);
		}
	}
	print_expert(g);
	printf("\n");
}

/* Reads "--NAME VALUE" at ARGV[*I] into *V; false on a bad value. */
static bool option(int argc, char **argv, int *i, const char *name,
		   double *v, bool *given)
{
	char *end;

	if (strcmp(argv[*i], name) || *i + 1 >= argc) {
		return false;
	}
	*v = strtod(argv[++*i], &end);
	*given = true;
	return *argv[*i] && !*end;
}

static int guide_request(struct ctl *ctl, Endosim__Guide *g, bool write)
{
	Endosim__GetStatus get = ENDOSIM__GET_STATUS__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int r;

	if (write) {
		req.body_case = ENDOSIM__REQUEST__BODY_GUIDE;
		req.guide = g;
	} else {
		req.body_case = ENDOSIM__REQUEST__BODY_GET_STATUS;
		req.get_status = &get;
	}
	r = ctl_transact(ctl, write, &req, &rep);
	if (r) {
		return r;
	}
	if (ctl->json) {
		ctl_json_status(rep->status_reply);
	} else if (rep->status_reply) {
		print_guide(rep->status_reply->guide);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

int ctl_cmd_guide(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Guide g = ENDOSIM__GUIDE__INIT;
	const char *what = argc >= 2 ? argv[1] : "";
	bool speed_given = false, from_given = false, ok = true;
	char *end;
	int first = 2;

	if (!strcmp(what, "status") && argc == 2) {
		return guide_request(ctl, &g, false);
	}
	if (!strcmp(what, "start") && argc >= 3) {
		g.action = ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_START;
		g.session_id = strtoull(argv[2], &end, 10);
		if (*end || !*argv[2]) {
			g.session_id = 0;
			g.file = argv[2];
		}
		first = 3;
	} else if (!strcmp(what, "stop")) {
		g.action = ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_STOP;
	} else if (!strcmp(what, "takeover")) {
		g.action = ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_TAKEOVER;
	} else if (!strcmp(what, "resume")) {
		g.action = ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_RESUME;
	} else if (!strcmp(what, "reset")) {
		g.action = ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_RESET;
	} else {
		ok = false;
	}
	for (int i = first; ok && i < argc; i++) {
		bool start = g.action == ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_START;
		bool reset = g.action == ENDOSIM__GUIDE_ACTION__GUIDE_ACTION_RESET;

		ok = (start && option(argc, argv, &i, "--speed", &g.speed,
				      &speed_given)) ||
		     (start && option(argc, argv, &i, "--from", &g.from_s,
				      &from_given)) ||
		     (reset && option(argc, argv, &i, "--to", &g.from_s,
				      &from_given));
	}
	if (!ok) {
		fprintf(stderr, "%s", GUIDE_USAGE);
		return EXIT_USAGE;
	}
	g.from_given = from_given;
	return guide_request(ctl, &g, true);
}
