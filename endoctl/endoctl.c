/*
 * endoctl.c - the command-line client of endosimd's control sockets, for the
 * instructor, the technician and scripts (also over ssh).
 *
 * Read-only commands go to status.sock, commands that change the daemon to
 * control.sock (which needs the endosim group). --json prints one JSON
 * object per reply.
 *
 * Exit status: 0 done; 1 the daemon refused or failed (its reason on
 * stderr); 2 bad usage; 3 the daemon is not running (cannot connect);
 * 4 the conversation failed (timeout, closed, undecodable reply).
 */
#include "endoctl/endoctl.h"

#include <ctype.h>
#include <sys/param.h>

/* ------------------------------------------------------------ plumbing */

static int connect_daemon(struct ctl *ctl, bool write)
{
	char path[256];

	if (client_socket_path(ctl->socket, write, path, sizeof(path))) {
		fprintf(stderr, "endoctl: socket path too long\n");
		return EXIT_USAGE;
	}
	client_close(ctl->client); /* a command's earlier request's */
	ctl->client = client_connect(path);
	if (!ctl->client) {
		fprintf(stderr, "endoctl: cannot connect to %s: %s (is "
			"endosimd running?)\n", path, strerror(errno));
		return EXIT_NO_DAEMON;
	}
	return 0;
}

static int comm_error(int err)
{
	fprintf(stderr, "endoctl: %s\n",
		err == -ETIMEDOUT ? "no reply from endosimd (timeout)"
		: err == -ECONNRESET ? "endosimd closed the connection"
		: err == -EPROTO ? "undecodable reply" : strerror(-err));
	return EXIT_COMM;
}

int ctl_request(struct ctl *ctl, Endosim__Request *req,
		Endosim__Reply **rep)
{
	int r = client_request(ctl->client, req, rep, ctl->timeout_ms);

	if (r) {
		return comm_error(r);
	}
	if ((*rep)->status != ENDOSIM__STATUS__STATUS_OK) {
		if (ctl->json) {
			struct json j;

			json_init(&j, stdout);
			json_object_begin(&j, NULL);
			json_uint(&j, "status", (uint64_t)(*rep)->status);
			json_string(&j, "error", (*rep)->error);
			json_object_end(&j);
		}
		fprintf(stderr, "endoctl: %s: %s\n",
			client_status_text((*rep)->status), (*rep)->error);
		endosim__reply__free_unpacked(*rep, NULL);
		*rep = NULL;
		return EXIT_REFUSED;
	}
	return 0;
}

/* Sends REQ (logged in first with --as); on success *REP holds an OK
 * reply. */
int ctl_transact(struct ctl *ctl, bool write, Endosim__Request *req,
		 Endosim__Reply **rep)
{
	int r = connect_daemon(ctl, write);

	if (!r && ctl->as && req->body_case != ENDOSIM__REQUEST__BODY_LOGIN) {
		r = ctl_login(ctl);
	}
	return r ? r : ctl_request(ctl, req, rep);
}

/* ------------------------------------------------------------ commands */

static int cmd_status(struct ctl *ctl, int argc, char **argv)
{
	Endosim__GetStatus body = ENDOSIM__GET_STATUS__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int r;

	(void)argc;
	(void)argv;
	req.body_case = ENDOSIM__REQUEST__BODY_GET_STATUS;
	req.get_status = &body;
	r = ctl_transact(ctl, false, &req, &rep);
	if (r) {
		return r;
	}
	if (ctl->json) {
		ctl_json_status(rep->status_reply);
	} else {
		ctl_print_status(rep->status_reply);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

static int simple_command(struct ctl *ctl, Endosim__Request__BodyCase body,
			  void *msg, const char *done);

static int cmd_stats(struct ctl *ctl, int argc, char **argv)
{
	Endosim__GetStats body = ENDOSIM__GET_STATS__INIT;
	Endosim__ResetStats reset = ENDOSIM__RESET_STATS__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int r;

	if (argc == 2 && !strcmp(argv[1], "--reset")) {
		return simple_command(ctl, ENDOSIM__REQUEST__BODY_RESET_STATS,
				      &reset, "statistics reset");
	}
	if (argc != 1) {
		fprintf(stderr, "endoctl: stats [--reset]\n");
		return EXIT_USAGE;
	}
	req.body_case = ENDOSIM__REQUEST__BODY_GET_STATS;
	req.get_stats = &body;
	r = ctl_transact(ctl, false, &req, &rep);
	if (r) {
		return r;
	}
	ctl_print_stats(rep->stats, ctl->json);
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

static void watch_line(const Endosim__StatusReply *s, bool tty)
{
	const char *sep = tty ? "\r\033[K" : "";

	printf("%s%-7s %s%s cyc %-9llu ins %+.3f m %+6.2f N  roll %+6.2f rad "
	       "%+5.2f N m  ud %+5.2f rad %+6.3f N m  lr %+5.2f rad %+6.3f "
	       "N m  ovr %llu%s", sep, names_state((uint32_t)s->state),
	       *s->fault_text ? s->fault_text : "", *s->fault_text ? " " : "",
	       (unsigned long long)s->cycle, s->axes[0]->position,
	       s->axes[0]->limited, s->axes[1]->position, s->axes[1]->limited,
	       s->axes[2]->position, s->axes[2]->limited, s->axes[3]->position,
	       s->axes[3]->limited, (unsigned long long)s->overruns,
	       tty ? "" : "\n");
	fflush(stdout);
}

static volatile sig_atomic_t interrupted;

static void on_interrupt(int sig)
{
	(void)sig;
	interrupted = 1;
}

/* Runs until interrupted, the duration passes or the daemon leaves. */
static int watch_loop(struct ctl *ctl, double duration_s, bool tty)
{
	struct timespec t0, now;
	Endosim__Reply *rep;
	int r;

	clock_gettime(CLOCK_MONOTONIC, &t0);
	while (!interrupted) {
		r = client_receive(ctl->client, &rep, 2000);
		if (r) {
			if (tty) {
				putchar('\n');
			}
			return r == -EINTR ? 0 : comm_error(r);
		}
		if (rep->body_case == ENDOSIM__REPLY__BODY_STATUS_REPLY) {
			if (ctl->json) {
				/* a line at a time down a pipe, as the
				 * text's */
				ctl_json_status(rep->status_reply);
				fflush(stdout);
			} else {
				watch_line(rep->status_reply, tty);
			}
		}
		endosim__reply__free_unpacked(rep, NULL);
		clock_gettime(CLOCK_MONOTONIC, &now);
		if (duration_s > 0 &&
		    (double)(now.tv_sec - t0.tv_sec) +
				    (double)(now.tv_nsec - t0.tv_nsec) /
					    ENDOSIM_NS_PER_S >=
			    duration_s) {
			break;
		}
	}
	if (tty && !ctl->json) {
		putchar('\n');
	}
	return 0;
}

static int cmd_watch(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Subscribe body = ENDOSIM__SUBSCRIBE__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	bool tty = isatty(STDOUT_FILENO) && !ctl->json;
	double duration = 0;
	Endosim__Reply *rep;
	int r;

	body.rate_hz = tty ? 10 : 1;
	for (int i = 1; i < argc; i++) {
		char *end;

		if (!strcmp(argv[i], "--rate") && i + 1 < argc) {
			body.rate_hz = strtod(argv[++i], &end);
		} else if (!strcmp(argv[i], "--duration") && i + 1 < argc) {
			duration = strtod(argv[++i], &end);
		} else {
			fprintf(stderr, "endoctl: watch [--rate HZ] "
				"[--duration S]\n");
			return EXIT_USAGE;
		}
	}
	signal(SIGINT, on_interrupt);
	signal(SIGTERM, on_interrupt);
	req.body_case = ENDOSIM__REQUEST__BODY_SUBSCRIBE;
	req.subscribe = &body;
	r = ctl_transact(ctl, false, &req, &rep);
	if (r) {
		return r;
	}
	endosim__reply__free_unpacked(rep, NULL);
	return watch_loop(ctl, duration, tty);
}

/* enable, disable, estop, reset: a body-less request on control.sock. */
static int simple_command(struct ctl *ctl, Endosim__Request__BodyCase body,
			  void *msg, const char *done)
{
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int r;

	req.body_case = body;
	req.enable = msg; /* one member of the oneof's union */
	r = ctl_transact(ctl, true, &req, &rep);
	if (r) {
		return r;
	}
	if (ctl->json) {
		struct json j;

		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_uint(&j, "status", 0);
		json_string(&j, "result", done);
		json_object_end(&j);
	} else {
		printf("%s\n", done);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

static int cmd_enable(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Enable m = ENDOSIM__ENABLE__INIT;

	(void)argc;
	(void)argv;
	return simple_command(ctl, ENDOSIM__REQUEST__BODY_ENABLE, &m,
			      "enabled: forces on");
}

static int cmd_disable(struct ctl *ctl, int argc, char **argv)
{
	Endosim__Disable m = ENDOSIM__DISABLE__INIT;

	(void)argc;
	(void)argv;
	return simple_command(ctl, ENDOSIM__REQUEST__BODY_DISABLE, &m,
			      "disabled: torque off");
}

static int cmd_estop(struct ctl *ctl, int argc, char **argv)
{
	Endosim__EStop m = ENDOSIM__ESTOP__INIT;

	(void)argc;
	(void)argv;
	return simple_command(ctl, ENDOSIM__REQUEST__BODY_ESTOP, &m,
			      "EMERGENCY STOP: torque off, latched until reset");
}

static int cmd_reset(struct ctl *ctl, int argc, char **argv)
{
	Endosim__ResetFault m = ENDOSIM__RESET_FAULT__INIT;

	(void)argc;
	(void)argv;
	return simple_command(ctl, ENDOSIM__REQUEST__BODY_RESET_FAULT, &m,
			      "reset: IDLE");
}

static int cmd_get(struct ctl *ctl, int argc, char **argv)
{
	Endosim__GetConfig body = ENDOSIM__GET_CONFIG__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	struct json j;
	int r;

	if (argc > 2) {
		fprintf(stderr, "endoctl: get [SECTION.KEY]\n");
		return EXIT_USAGE;
	}
	body.key = argc == 2 ? argv[1] : "";
	req.body_case = ENDOSIM__REQUEST__BODY_GET_CONFIG;
	req.get_config = &body;
	r = ctl_transact(ctl, false, &req, &rep);
	if (r) {
		return r;
	}
	json_init(&j, stdout);
	if (ctl->json) {
		json_object_begin(&j, NULL);
	}
	for (size_t i = 0; i < rep->config->n_entries; i++) {
		const Endosim__ConfigEntry *e = rep->config->entries[i];

		if (ctl->json) {
			json_object_begin(&j, e->key);
			json_string(&j, "value", e->value);
			json_string(&j, "unit", e->unit);
			json_bool(&j, "live", e->live);
			json_string(&j, "help", e->help);
			json_object_end(&j);
		} else if (argc == 2) {
			printf("%s\n", e->value);
		} else {
			printf("%s = %s%s%s%s\n", e->key, e->value,
			       *e->unit ? " " : "", e->unit,
			       e->live ? "  (live)" : "");
		}
	}
	if (ctl->json) {
		json_object_end(&j);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

static int cmd_set(struct ctl *ctl, int argc, char **argv)
{
	Endosim__SetParam body = ENDOSIM__SET_PARAM__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int r;

	if (argc != 3) {
		fprintf(stderr, "endoctl: set SECTION.KEY VALUE\n");
		return EXIT_USAGE;
	}
	body.key = argv[1];
	body.value = argv[2];
	req.body_case = ENDOSIM__REQUEST__BODY_SET_PARAM;
	req.set_param = &body;
	r = ctl_transact(ctl, true, &req, &rep);
	if (r) {
		return r;
	}
	if (ctl->json) {
		struct json j;

		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_uint(&j, "status", 0);
		json_string(&j, "key", argv[1]);
		json_string(&j, "value", argv[2]);
		json_object_end(&j);
	} else {
		printf("%s = %s\n", argv[1], argv[2]);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

int ctl_hand_input(struct ctl *ctl, Endosim__HandInput *body)
{
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int r;

	req.body_case = ENDOSIM__REQUEST__BODY_HAND_INPUT;
	req.hand_input = body;
	r = ctl_transact(ctl, true, &req, &rep);
	if (!r) {
		endosim__reply__free_unpacked(rep, NULL);
	}
	return r;
}

static int cmd_hand(struct ctl *ctl, int argc, char **argv)
{
	Endosim__HandInput body = ENDOSIM__HAND_INPUT__INIT;
	double force[ENDOSIM_AXES];
	int n = 0;

	if (argc == 2 && !strcmp(argv[1], "off")) {
		body.hands_off = true; /* the grip lets go */
		n = ENDOSIM_AXES;
	}
	for (int i = 1; !body.hands_off && i < argc; i++) {
		char *end;

		if (!strcmp(argv[i], "--hold-ms") && i + 1 < argc) {
			body.hold_ms = (uint32_t)strtoul(argv[++i], &end, 10);
			continue;
		}
		if (n == ENDOSIM_AXES) {
			n++;
			break;
		}
		force[n++] = strtod(argv[i], &end);
		if (*end) {
			n = -1;
			break;
		}
	}
	if (n != ENDOSIM_AXES) {
		fprintf(stderr, "endoctl: hand F_INSERTION_N F_ROLL_NM F_UD_NM "
			"F_LR_NM [--hold-ms MS] | hand off\n");
		return EXIT_USAGE;
	}
	if (!body.hands_off) {
		body.n_force = ENDOSIM_AXES;
		body.force = force;
	}
	return ctl_hand_input(ctl, &body);
}

static void print_cases(const Endosim__CaseListReply *l, bool json)
{
	struct json j;

	if (json) {
		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_string(&j, "directory", l->directory);
		json_string(&j, "error", l->error);
		json_array_begin(&j, "cases");
		for (size_t i = 0; i < l->n_cases; i++) {
			json_object_begin(&j, NULL);
			json_string(&j, "name", l->cases[i]->name);
			json_string(&j, "description", l->cases[i]->description);
			json_bool(&j, "loaded", l->cases[i]->loaded);
			json_object_end(&j);
		}
		json_array_end(&j);
		json_object_end(&j);
		return;
	}
	for (size_t i = 0; i < l->n_cases; i++) {
		printf("%c %-20s %s\n", l->cases[i]->loaded ? '*' : ' ',
		       l->cases[i]->name, l->cases[i]->description);
	}
	if (*l->error) {
		fprintf(stderr, "endoctl: left out: %s\n", l->error);
	}
}

static int case_list(struct ctl *ctl)
{
	Endosim__ListCases body = ENDOSIM__LIST_CASES__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int r;

	req.body_case = ENDOSIM__REQUEST__BODY_LIST_CASES;
	req.list_cases = &body;
	r = ctl_transact(ctl, false, &req, &rep);
	if (r) {
		return r;
	}
	print_cases(rep->cases, ctl->json);
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

static int cmd_case(struct ctl *ctl, int argc, char **argv)
{
	Endosim__LoadCase body = ENDOSIM__LOAD_CASE__INIT;
	char done[160];

	if (argc == 2 && !strcmp(argv[1], "list")) {
		return case_list(ctl);
	}
	if (argc != 3 || strcmp(argv[1], "load")) {
		fprintf(stderr, "endoctl: case list | case load NAME\n");
		return EXIT_USAGE;
	}
	body.name = argv[2];
	snprintf(done, sizeof(done), "case %s loaded", argv[2]);
	return simple_command(ctl, ENDOSIM__REQUEST__BODY_LOAD_CASE, &body,
			      done);
}

static void print_scene_info(const struct client_scene *s, bool json)
{
	const Endosim__SceneInfo *in = s->info;

	if (json) {
		struct json j;

		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_string(&j, "name", in->name);
		json_uint(&j, "scene_id", s->scene_id);
		json_double(&j, "length_m", in->length_m);
		json_double(&j, "cecum_s_m", in->cecum_s_m);
		json_uint(&j, "vertices", s->vertices);
		json_uint(&j, "triangles", s->triangles);
		json_uint(&j, "samples", in->n_centreline / 3);
		json_uint(&j, "segments", in->n_segments);
		json_uint(&j, "polyps", in->n_polyps);
		json_array_begin(&j, "sites");
		for (size_t i = 0; i < in->n_sites; i++) {
			json_string(&j, NULL, in->sites[i]->name);
		}
		json_array_end(&j);
		json_object_end(&j);
		return;
	}
	printf("%s: %s\n%.3f m, cecum at %.3f m, %zu centreline samples, "
	       "%u vertices, %u triangles, %zu segments, %zu polyps\n",
	       in->name, in->description, in->length_m, in->cecum_s_m,
	       in->n_centreline / 3, s->vertices, s->triangles,
	       in->n_segments, in->n_polyps);
	for (size_t i = 0; i < in->n_regions; i++) {
		const Endosim__SceneRegion *r = in->regions[i];

		printf("  %-16s %6.3f .. %6.3f m%s\n", r->name, r->s0_m,
		       r->s1_m, r->span >= 0 ? "  mobile" : "");
	}
	for (size_t i = 0; i < in->n_sites; i++) {
		const Endosim__SceneSite *x = in->sites[i];

		if (x->n_position_m == 3 && x->n_direction == 3) {
			printf("  site %-11s at %.3f %.3f %.3f m, in along "
			       "%.2f %.2f %.2f, reach %.3f m\n", x->name,
			       x->position_m[0], x->position_m[1],
			       x->position_m[2], x->direction[0],
			       x->direction[1], x->direction[2], x->radius_m);
		}
	}
}

/* Writes the scene as an OBJ that MeshLab, Blender or endosimd read. */
static int export_scene(const struct client_scene *s, const char *path)
{
	struct objio_mesh m = {
		.name = s->info->name,
		.pos = (const float(*)[3])s->positions,
		.nrm = (const float(*)[3])s->normals,
		.vertices = s->vertices,
		.tri = (const uint32_t(*)[3])s->indices,
		.triangles = s->triangles,
		.centreline = (const double(*)[3])s->info->centreline,
		.samples = s->info->n_centreline / 3,
		.step_m = s->info->step_m,
	};
	char err[512];

	if (objio_write(path, &m, err, sizeof(err))) {
		fprintf(stderr, "endoctl: %s\n", err);
		return EXIT_REFUSED;
	}
	printf("wrote %s: %s, %u vertices, %u triangles, %zu centreline "
	       "points\n", path, m.name, m.vertices, m.triangles, m.samples);
	return 0;
}

static int cmd_scene(struct ctl *ctl, int argc, char **argv)
{
	struct client_scene *s;
	Endosim__Status status = ENDOSIM__STATUS__STATUS_OK;
	int r;

	if (!(argc == 2 && !strcmp(argv[1], "info")) &&
	    !(argc == 3 && !strcmp(argv[1], "export"))) {
		fprintf(stderr, "endoctl: scene info | scene export FILE.obj\n");
		return EXIT_USAGE;
	}
	r = connect_daemon(ctl, false);
	if (r) {
		return r;
	}
	r = client_get_scene(ctl->client, &s, ctl->timeout_ms, &status);
	if (r == -EACCES || r == -EAGAIN) {
		fprintf(stderr, "endoctl: %s\n", r == -EAGAIN ?
			"the case kept changing" : client_status_text(status));
		return EXIT_REFUSED;
	}
	if (r) {
		return comm_error(r);
	}
	if (argc == 2) {
		print_scene_info(s, ctl->json);
	} else {
		r = export_scene(s, argv[2]);
	}
	client_scene_free(s);
	return r;
}

/* The axis called NAME, "all" (-1), or -2. */
static int debug_axis(const char *name)
{
	return !strcmp(name, "all") ? -1
	       : names_axis_find(name) >= 0 ? names_axis_find(name) : -2;
}

static int cmd_debug(struct ctl *ctl, int argc, char **argv)
{
	Endosim__DebugInject body = ENDOSIM__DEBUG_INJECT__INIT;
	int action = argc >= 2 ? names_debug_action_find(argv[1]) : -1;
	bool axisless = action == ENDOSIM__DEBUG_ACTION__DEBUG_ACTION_STALL ||
			action ==
				ENDOSIM__DEBUG_ACTION__DEBUG_ACTION_END_CONTROL;
	int ai = 2, vi = axisless ? 2 : 3;
	char done[160], *end = NULL;

	body.axis = -1;
	if (!axisless && argc > ai) {
		body.axis = debug_axis(argv[ai]);
	}
	if (argc > vi) {
		body.value = strtod(argv[vi], &end);
	}
	if (action < 0 || argc > vi + 1 || body.axis < -1 || (end && *end) ||
	    (!axisless && argc < 3 &&
	     action != ENDOSIM__DEBUG_ACTION__DEBUG_ACTION_CLEAR)) {
		fprintf(stderr, "endoctl: debug ACTION [AXIS|all] [VALUE], with "
			"[debug] test_commands = yes in endosimd; ACTION: clear, "
			"drive-fault, drive-gone, stale, bus-error, speed, "
			"position, force, nan (VALUE: 1 feedback, 2 pose, "
			"3 haptics, 4 command), stall SECONDS, end-control\n");
		return EXIT_USAGE;
	}
	body.action = (Endosim__DebugAction)action;
	snprintf(done, sizeof(done), "test command %s done", argv[1]);
	return simple_command(ctl, ENDOSIM__REQUEST__BODY_DEBUG_INJECT, &body,
			      done);
}

static int cmd_version(struct ctl *ctl, int argc, char **argv)
{
	Endosim__GetStatus body = ENDOSIM__GET_STATUS__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	int r;

	(void)argc;
	(void)argv;
	req.body_case = ENDOSIM__REQUEST__BODY_GET_STATUS;
	req.get_status = &body;
	r = ctl_transact(ctl, false, &req, &rep);
	if (ctl->json) {
		struct json j;

		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_string(&j, "endoctl", ENDOSIM_VERSION);
		json_string(&j, "endosimd", r ? "" : rep->status_reply->version);
		json_uint(&j, "protocol",
			  ENDOSIM__PROTOCOL_VERSION__PROTOCOL_VERSION_CURRENT);
		json_object_end(&j);
	} else {
		printf("endoctl %s, protocol %d\n", ENDOSIM_VERSION,
		       ENDOSIM__PROTOCOL_VERSION__PROTOCOL_VERSION_CURRENT);
		if (!r) {
			printf("endosimd %s\n", rep->status_reply->version);
		}
	}
	if (!r) {
		endosim__reply__free_unpacked(rep, NULL);
	}
	return r;
}

/* ------------------------------------------------------------ main */

/* Each command: its one line, its usage (its forms, " | " between
 * them), notes and an example. */
static const struct command {
	const char *name;
	command_fn *fn;
	const char *line;
	const char *usage;
	const char *example;
	const char *notes;
} commands[] = {
	{ "status", cmd_status, "state, faults, loop, axes, scope, patient",
	  "status", "endoctl --json status | jq .patient.pain", NULL },
	{ "stats", cmd_stats, "force-loop latency and compute time",
	  "stats [--reset]", "endoctl stats", "percentiles since the start "
	  "(or the last reset); --reset starts them anew" },
	{ "watch", cmd_watch, "a live status line",
	  "watch [--rate HZ] [--duration S]",
	  "endoctl watch --rate 5 --duration 10", "one line a 1/HZ s "
	  "(default 10), for S s (default: until interrupted)" },
	{ "enable", cmd_enable, "IDLE -> ENABLED: render forces", "enable",
	  "endoctl enable", NULL },
	{ "disable", cmd_disable, "ENABLED -> IDLE: torque off", "disable",
	  "endoctl disable", NULL },
	{ "estop", cmd_estop, "emergency stop (latched)", "estop",
	  "endoctl estop", NULL },
	{ "reset", cmd_reset, "clear ESTOP or a FAULT whose cause is gone",
	  "reset", "endoctl reset", NULL },
	{ "get", cmd_get, "the configuration", "get [SECTION.KEY]",
	  "endoctl get pain.sedation", "every key, or one" },
	{ "set", cmd_set, "change a live configuration key",
	  "set SECTION.KEY VALUE",
	  "endoctl set haptics.wall_stiffness_n_per_m 800",
	  "the keys endosimd --print-config marks live" },
	{ "hand", cmd_hand, "push the simulated hand (N, N m), or let go",
	  "hand F_INS F_ROLL F_UD F_LR [--hold-ms MS] | off",
	  "endoctl hand 5 0 0 0 --hold-ms 500",
	  "the four axes' forces for MS ms (simulated rig); then the hand "
	  "holds each axis where it left it ([sim] grip_*_max: it slips "
	  "beyond) until `hand off`" },
	{ "case", cmd_case, "the anatomy cases", "case list | load NAME",
	  "endoctl case load tight-flexures",
	  "load: IDLE only, never in a session" },
	{ "scene", cmd_scene, "the colon the daemon renders",
	  "scene info | export FILE.obj", "endoctl scene info", NULL },
	{ "session", ctl_cmd_session, "training sessions",
	  "session start [--trainee NAME] [--case NAME] [--sedation "
	  "none|minimal|moderate|deep] | stop | status | map | list | show ID "
	  "| export ID --csv [--events] [--out FILE] | export ID... --summary "
	  "[--out FILE] | report ID --out DIR [--reference REF_ID]",
	  "endoctl session start --trainee ana --sedation moderate",
	  "ID: a session's number, or a file (./N.endoses) read without "
	  "endosimd" },
	{ "trainee", ctl_cmd_trainee, "trainees, their sessions and course",
	  "trainee list [--course FILE] [--dir DIR | --centre URL] | report "
	  "NAME --out DIR [--course FILE] [--dir DIR | --centre URL]",
	  "endoctl trainee report ana --out /tmp/ana",
	  "--dir: a session directory, read without endosimd; --centre: a "
	  "training centre's PostgreSQL (every rig's sessions)" },
	{ "records", ctl_cmd_records, "the rig's records against its session "
	  "files, their backup", "records check | rebuild | backup FILE | "
	  "restore FILE", "endoctl records backup /srv/records-monday.sqlite",
	  "check: what differs between the database and the files (the "
	  "truth); rebuild: the database written again from the files; "
	  "backup: an online copy into the new FILE (endosimd writes it); "
	  "restore: the database made again from FILE, then brought up to "
	  "date with the files (refused while a session records)" },
	{ "user", ctl_cmd_user, "the rig's users: trainees, instructors, "
	  "administrators", "user list | add NAME --role "
	  "trainee|instructor|administrator | remove NAME | pin NAME",
	  "ENDOSIM_NEW_PIN=4821 endoctl user add Ann --role trainee",
	  "who sees what of the records: a trainee their own sessions, an "
	  "instructor their groups' trainees', an administrator all; the PIN "
	  "of add and pin from $ENDOSIM_NEW_PIN, else asked twice on the "
	  "terminal (4 to 64 characters, kept only as a salted Argon2id "
	  "hash); add, remove and another's pin: an administrator on the "
	  "control socket (root or the endosim group are one while not "
	  "logged in), or an instructor logged in there adding a trainee or "
	  "setting the PIN of a trainee of their groups; anyone logged in "
	  "may change their own PIN" },
	{ "group", ctl_cmd_group, "groups of trainees and their courses",
	  "group list | add GROUP --instructor NAME | remove GROUP | join "
	  "GROUP TRAINEE... | leave GROUP TRAINEE... | assign GROUP COURSE | "
	  "unassign GROUP COURSE", "endoctl group join 2026 Ann Bo",
	  "a group (a year's intake) is managed by one instructor, who sees "
	  "the sessions of its trainees; its courses are the course files "
	  "assigned to it; changes: an administrator on the control socket, "
	  "or its instructor logged in there joining and leaving trainees "
	  "(one in no group, or in theirs) and assigning courses" },
	{ "whoami", ctl_cmd_whoami, "who this connection is to endosimd",
	  "whoami", "ENDOSIM_PIN=4821 endoctl --as Ann whoami",
	  "with --as NAME the name and role the PIN logged in as; without, "
	  "whether root or the endosim group make you an administrator" },
	{ "login", ctl_cmd_login, "who trains at the rig: a trainee logs in",
	  "login NAME", "ENDOSIM_PIN=4821 endoctl login Ann",
	  "what endoview's login screen does: from now on a session started "
	  "without --trainee is NAME's, until logout; the PIN from "
	  "$ENDOSIM_PIN, else asked on the terminal; a trainee's login only, "
	  "on the control socket, refused while a session of another "
	  "records" },
	{ "logout", ctl_cmd_logout, "nobody trains at the rig any more",
	  "logout", "endoctl logout", "endoview's C key; refused while a "
	  "session records, and to a trainee logged in (--as) as another" },
	{ "guide", ctl_cmd_guide, "guided replay of a session through the "
	  "motors",
	  "guide start ID|FILE [--speed X] [--from S] | stop | takeover | "
	  "resume | reset [--to S] | status", "endoctl guide start 12", NULL },
	{ "patient", ctl_cmd_patient, "the patient ([patient] enabled)",
	  "patient status | position left-lateral|supine|right-lateral|prone "
	  "| press SITE [--force N] | release | valve air|water|suction on "
	  "[--for S] | valve air|water|suction off | sedation "
	  "none|minimal|moderate|deep", "endoctl patient press llq --force 30",
	  "a turn takes [patient] turn_s; SITE is one of the case's (scene "
	  "info), N up to [patient] hand_max_n (default hand_n); a valve is "
	  "spring-loaded as on a real handle: `on` holds it S s (default 2, "
	  "at most 10), then it springs back, `off` lets go at once; the "
	  "other valves held stay held with it (simulated rig only)" },
	{ "tool", ctl_cmd_tool, "the tool through the working channel",
	  "tool status | select none|forceps|snare|needle|clip [--size MM] "
	  "| hand DEPTH_MM OPENING [--pedal] [--for S]",
	  "endoctl tool select snare --size 20",
	  "select: the tool the nurse hands over, one at a time; a snare of "
	  "MM mm, 10 to 30 (default [tool] snare_size_m); hand (simulated "
	  "rig): the hand holds the tool DEPTH_MM beyond the channel's exit "
	  "(negative: in it), its handle at OPENING (0 closed .. 1 open), "
	  "the cautery's pedal down with --pedal, for S s (default 2, at "
	  "most 10); then the reading lapses: the tool still, the pedal up" },
	{ "version", cmd_version, "endoctl's and endosimd's versions",
	  "version", "endoctl version", NULL },
	{ "debug", cmd_debug, "fault injection, for tests only",
	  "debug ACTION [AXIS] [VALUE]", "endoctl debug stall-loop", NULL },
	{ "help", NULL, "this list, or one command's options and an example",
	  "help [COMMAND]", "endoctl help session", NULL },
};

#define COMMANDS (sizeof(commands) / sizeof(commands[0]))

static void usage(FILE *out)
{
	fprintf(out, "usage: endoctl [--socket PATH] [--json] [--timeout MS] "
		"[--as NAME] COMMAND [ARGS]\n\nPATH is a socket or the "
		"directory holding both (default $%s or %s).\n--as NAME: "
		"logged in as NAME, the PIN from $ENDOSIM_PIN or the "
		"terminal.\n\ncommands:\n", CLIENT_ENV, CLIENT_DEFAULT_DIR);
	for (size_t i = 0; i < COMMANDS; i++) {
		fprintf(out, "  %-8s %s\n", commands[i].name, commands[i].line);
	}
	fprintf(out, "\n'endoctl help COMMAND' gives its options and an "
		"example.\nexit status: 0 ok, 1 refused by endosimd, 2 usage, "
		"3 endosimd not running, 4 communication error\n");
}

static const struct command *command_named(const char *name)
{
	for (size_t i = 0; i < COMMANDS; i++) {
		if (!strcmp(name, commands[i].name)) {
			return &commands[i];
		}
	}
	return NULL;
}

/* The edit distance between A and B (insertions, deletions, changes and
 * two neighbours swapped), at most 32 characters of each counted. */
static int distance(const char *a, const char *b)
{
	int d[33][33];
	int n = (int)strnlen(a, 32), m = (int)strnlen(b, 32);

	for (int i = 0; i <= n; i++) {
		for (int j = 0; j <= m; j++) {
			int best = i + j;

			if (i && j) {
				best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
				best = MIN(best, d[i - 1][j] + 1);
				best = MIN(best, d[i][j - 1] + 1);
				if (i > 1 && j > 1 && a[i - 1] == b[j - 2] &&
				    a[i - 2] == b[j - 1]) {
					best = MIN(best, d[i - 2][j - 2] + 1);
				}
			}
			d[i][j] = best;
		}
	}
	return d[n][m];
}

/* The command nearest NAME, when near enough to be a slip (at most two
 * edits, fewer than half its letters), else NULL. */
static const char *nearest(const char *name)
{
	const char *best = NULL;
	int most = 3;

	for (size_t i = 0; i < COMMANDS; i++) {
		int d = distance(name, commands[i].name);

		if (d < most && 2 * d < (int)strlen(commands[i].name)) {
			most = d;
			best = commands[i].name;
		}
	}
	return best;
}

static int unknown(const char *name)
{
	const char *near = nearest(name);

	fprintf(stderr, "endoctl: unknown command '%s'", name);
	if (near) {
		fprintf(stderr, "; did you mean '%s'?\n", near);
	} else {
		fprintf(stderr, "; 'endoctl help' lists them\n");
	}
	return EXIT_USAGE;
}

/* TEXT as a sentence (its first letter upper case, a full stop), in
 * lines of at most 72 columns broken between words. */
static void print_wrapped(const char *text)
{
	size_t col = 0;

	for (const char *w = text; *w;) {
		size_t n = strcspn(w, " ");

		if (col && col + 1 + n > 72) {
			putchar('\n');
			col = 0;
		} else if (col) {
			putchar(' ');
			col++;
		}
		printf("%c%.*s", w == text ? toupper((unsigned char)*w) : *w,
		       (int)n - 1, w + 1);
		col += n;
		w += n;
		w += *w == ' ';
	}
	puts(".");
}

/* help [COMMAND] */
static int help(int argc, char **argv)
{
	const struct command *c;

	if (argc == 1) {
		usage(stdout);
		return 0;
	}
	if (argc != 2) {
		fputs("endoctl: help [COMMAND]\n", stderr);
		return EXIT_USAGE;
	}
	c = command_named(argv[1]);
	if (!c) {
		return unknown(argv[1]);
	}
	printf("endoctl %s: %s\n\nusage:\n", c->name, c->line);
	if (!strcmp(c->usage, c->name)) {
		printf("  endoctl %s\n", c->name);
	}
	for (const char *u = c->usage + strlen(c->name), *bar; *u;
	     u = bar ? bar + 3 : u + strlen(u)) {
		u += *u == ' ';
		bar = strstr(u, " | ");
		printf("  endoctl %s %.*s\n", c->name,
		       bar ? (int)(bar - u) : (int)strlen(u), u);
	}
	if (c->notes) {
		putchar('\n');
		print_wrapped(c->notes);
	}
	printf("\nexample:\n  %s\n", c->example);
	return 0;
}

int main(int argc, char **argv)
{
	static const struct option opts[] = {
		{ "socket", required_argument, NULL, 's' },
		{ "json", no_argument, NULL, 'j' },
		{ "timeout", required_argument, NULL, 't' },
		{ "as", required_argument, NULL, 'a' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 },
	};
	struct ctl ctl = { .timeout_ms = 2000 };
	const struct command *cmd;
	int c, r;

	while ((c = getopt_long(argc, argv, "+s:jt:h", opts, NULL)) != -1) {
		switch (c) {
		case 's':
			ctl.socket = optarg;
			break;
		case 'j':
			ctl.json = true;
			break;
		case 't':
			ctl.timeout_ms = atoi(optarg);
			break;
		case 'a':
			ctl.as = optarg;
			break;
		case 'h':
			usage(stdout);
			return 0;
		default:
			usage(stderr);
			return EXIT_USAGE;
		}
	}
	if (optind >= argc || ctl.timeout_ms <= 0) {
		usage(stderr);
		return EXIT_USAGE;
	}
	if (!strcmp(argv[optind], "help")) {
		return help(argc - optind, argv + optind);
	}
	cmd = command_named(argv[optind]);
	if (!cmd) {
		return unknown(argv[optind]);
	}
	r = cmd->fn(&ctl, argc - optind, argv + optind);
	client_close(ctl.client);
	return r;
}
