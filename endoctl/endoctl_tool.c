/*
 * endoctl_tool.c - `endoctl tool ...`: the tool the nurse hands over
 * through the working channel, and the hand holding it on the simulated
 * rig, over the sockets (endoctl.h).
 */
#include "endoctl/endoctl.h"

#define TOOL_HOLD_S 2.0      /* `hand` holds the tool this long ... */
#define TOOL_HOLD_MAX_S 10.0 /* ... or as long as --for says, at most */

static const char usage_text[] =
	"endoctl: tool status | select none|forceps|snare|needle|clip "
	"[--size MM] | hand DEPTH_MM OPENING [--pedal] [--for S]\n";

static void print_polyps(const Endosim__ToolStatus *t)
{
	for (size_t i = 0; i < t->n_polyp; i++) {
		const Endosim__ToolPolyp *p = t->polyp[i];

		printf("polyp %-3zu %-9s energy %.1f J%s", i,
		       names_polyp_state(p->state), p->energy_j,
		       p->lifted ? ", lifted" : "");
		if (p->bites) {
			printf(", %u bite%s", p->bites,
			       p->bites > 1 ? "s" : "");
		}
		if (p->bleed != ENDOSIM_BLEED_NONE) {
			printf(", %s %.1f mL/min, %.2f mL shed",
			       names_bleed(p->bleed),
			       p->bleed_m3_s * ENDOSIM_ML_PER_MIN_PER_M3_S,
			       p->blood_m3 * ENDOSIM_ML_PER_M3);
		}
		printf("\n");
	}
}

static void print_tool(const Endosim__ToolStatus *t)
{
	printf("tool      %s", names_tool(t->kind));
	if (t->kind == ENDOSIM_TOOL_SNARE) {
		printf(" of %.0f mm", t->snare_m * 1e3);
	}
	printf("\nhand      %.1f mm out of the channel, handle %.0f %% open, "
	       "pedal %s\n", t->depth_m * 1e3, t->opening * 100,
	       t->pedal ? "down" : "up");
	if (t->kind == ENDOSIM_TOOL_SNARE) {
		printf("loop      %.1f mm", t->loop_m * 1e3);
		if (t->captured >= 0) {
			printf(", holding polyp %d", t->captured);
		}
		printf("\n");
	}
	printf("clips     %u\n", t->clips);
	if (t->blood_m3 > 0) {
		printf("blood     %.2f mL shed, %u point%s bleeding %.1f "
		       "mL/min\n", t->blood_m3 * ENDOSIM_ML_PER_M3, t->bleeding,
		       t->bleeding == 1 ? "" : "s",
		       t->bleed_m3_s * ENDOSIM_ML_PER_MIN_PER_M3_S);
	}
	print_polyps(t);
}

/* The tool in REP's status, as text or JSON; 0 or the exit status. */
static int show(struct ctl *ctl, const Endosim__Reply *rep)
{
	const Endosim__ToolStatus *t =
		rep->body_case == ENDOSIM__REPLY__BODY_STATUS_REPLY ?
			rep->status_reply->tool : NULL;

	if (!t) {
		fprintf(stderr, "endoctl: endosimd says nothing of a tool (an "
			"older daemon)\n");
		return EXIT_REFUSED;
	}
	if (ctl->json) {
		ctl_json_part(&fields_tool, t);
	} else {
		print_tool(t);
	}
	return 0;
}

/* Sends REQ (WRITE: on the read-write socket); shows the tool after it. */
static int tool_request(struct ctl *ctl, bool write, Endosim__Request *req)
{
	Endosim__Reply *rep;
	int r = ctl_transact(ctl, write, req, &rep);

	if (r) {
		return r;
	}
	r = show(ctl, rep);
	endosim__reply__free_unpacked(rep, NULL);
	return r;
}

/* select KIND [--size MM] */
static int tool_select(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Tool body = ENDOSIM__TOOL__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	char *end = NULL;

	if (argc == 5 && !strcmp(argv[3], "--size")) {
		body.snare_m = strtod(argv[4], &end) * 1e-3;
	}
	if ((argc != 3 && argc != 5) || (end && (*end || end == argv[4])) ||
	    (end && !(body.snare_m > 0))) {
		fputs(usage_text, stderr);
		return EXIT_USAGE;
	}
	body.select = argv[2];
	req.body_case = ENDOSIM__REQUEST__BODY_TOOL;
	req.tool = &body;
	return tool_request(ctl, true, &req);
}

/* The number at ARG into *OUT: false unless it is all a number. */
static bool number(const char *arg, double *out)
{
	char *end;

	*out = strtod(arg, &end);
	return end != arg && !*end && isfinite(*out);
}

/*
 * hand DEPTH_MM OPENING [--pedal] [--for S]: the hand holds the tool
 * DEPTH_MM beyond the channel's exit, its handle at OPENING (0..1), the
 * pedal down or up, for S s (default 2, at most 10); then the reading
 * lapses (the tool still, the pedal up). The valves and the forces stay
 * as they are.
 */
static int tool_hand(struct ctl *ctl, int argc, char **argv)
{
	Endosim__HandInput body = ENDOSIM__HAND_INPUT__INIT;
	double depth_mm = 0, hold_s = TOOL_HOLD_S;
	bool ok = argc >= 4 && number(argv[2], &depth_mm) &&
		  number(argv[3], &body.tool_opening);
	int r;

	for (int i = 4; ok && i < argc; i++) {
		if (!strcmp(argv[i], "--pedal")) {
			body.tool_pedal = true;
		} else if (!strcmp(argv[i], "--for") && i + 1 < argc) {
			ok = number(argv[++i], &hold_s);
		} else {
			ok = false;
		}
	}
	if (!ok || !(hold_s > 0 && hold_s <= TOOL_HOLD_MAX_S)) {
		fputs(usage_text, stderr);
		return EXIT_USAGE;
	}
	body.tool = true;
	body.tool_depth_m = depth_mm * 1e-3;
	body.hold_ms = (uint32_t)lround(hold_s * 1e3);
	r = ctl_hand_input(ctl, &body);
	if (!r && !ctl->json) {
		printf("tool held %.1f mm out, handle %.0f %% open, pedal %s, "
		       "for %.1f s\n", depth_mm, body.tool_opening * 100,
		       body.tool_pedal ? "down" : "up", hold_s);
	}
	return r;
}

int ctl_cmd_tool(struct ctl *ctl, int argc, char **argv)
{
	const char *sub = argc >= 2 ? argv[1] : "";

	if (argc == 2 && !strcmp(sub, "status")) {
		Endosim__GetStatus body = ENDOSIM__GET_STATUS__INIT;
		Endosim__Request req = ENDOSIM__REQUEST__INIT;

		req.body_case = ENDOSIM__REQUEST__BODY_GET_STATUS;
		req.get_status = &body;
		return tool_request(ctl, false, &req);
	}
	if (argc >= 3 && !strcmp(sub, "select")) {
		return tool_select(ctl, argc, argv);
	}
	if (argc >= 4 && !strcmp(sub, "hand")) {
		return tool_hand(ctl, argc, argv);
	}
	fputs(usage_text, stderr);
	return EXIT_USAGE;
}
