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
#include <errno.h>
#include <getopt.h>
#include <inttypes.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "client.h"
#include "endosim_shm.h"
#include "names.h"
#include "version.h"
#include "inject.h"
#include "json.h"
#include "objio.h"
#include "report.h"
#include "sessiondir.h"
#include "sessionpb.h"
#include "sessionview.h"

enum {
	EXIT_REFUSED = 1,
	EXIT_USAGE = 2,
	EXIT_NO_DAEMON = 3,
	EXIT_COMM = 4,
};

struct ctl {
	const char *socket; /* --socket, or NULL */
	bool json;
	int timeout_ms;
	struct client *client;
};

typedef int command_fn(struct ctl *ctl, int argc, char **argv);

/* ------------------------------------------------------------ plumbing */

static int connect_daemon(struct ctl *ctl, bool write)
{
	char path[256];

	if (client_socket_path(ctl->socket, write, path, sizeof(path))) {
		fprintf(stderr, "endoctl: socket path too long\n");
		return EXIT_USAGE;
	}
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

/* Sends REQ; on success *REP holds an OK reply. */
static int transact(struct ctl *ctl, bool write, Endosim__Request *req,
		    Endosim__Reply **rep)
{
	int r = connect_daemon(ctl, write);

	if (r) {
		return r;
	}
	r = client_request(ctl->client, req, rep, ctl->timeout_ms);
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

/* ------------------------------------------------------------ printing */

static void json_vector(struct json *j, const char *key, const double *v,
			size_t n)
{
	json_array_begin(j, key);
	for (size_t i = 0; i < n; i++) {
		json_double(j, NULL, v[i]);
	}
	json_array_end(j);
}

static void json_scope(struct json *j, const Endosim__ScopeStatus *sc)
{
	json_object_begin(j, "scope");
	json_double(j, "depth_m", sc->depth_m);
	json_double(j, "tip_s_m", sc->tip_s_m);
	json_double(j, "base_s_m", sc->base_s_m);
	json_double(j, "turning_rad", sc->turning_rad);
	json_vector(j, "bend_rad", sc->bend_rad, sc->n_bend_rad);
	json_vector(j, "tip", sc->tip, sc->n_tip);
	json_vector(j, "dir", sc->dir, sc->n_dir);
	json_vector(j, "up", sc->up, sc->n_up);
	json_vector(j, "bow_m", sc->bow_m, sc->n_bow_m);
	json_uint(j, "scene_id", sc->scene_id);
	json_object_end(j);
}

static void json_haptics(struct json *j, const Endosim__HapticsStatus *h)
{
	json_object_begin(j, "haptics");
	json_bool(j, "contact", h->contact);
	json_uint(j, "constraints", h->constraints);
	json_vector(j, "proxy", h->proxy, h->n_proxy);
	json_vector(j, "normal", h->normal, h->n_normal);
	json_vector(j, "f_static", h->f_static, h->n_f_static);
	json_double(j, "penetration_m", h->penetration_m);
	json_double(j, "curvature_rad", h->curvature_rad);
	json_double(j, "trans_contact_n", h->trans_contact_n);
	json_double(j, "trans_friction_n", h->trans_friction_n);
	json_double(j, "trans_loop_n", h->trans_loop_n);
	json_vector(j, "wheel_contact_nm", h->wheel_contact_nm,
		    h->n_wheel_contact_nm);
	json_vector(j, "wheel_tension_nm", h->wheel_tension_nm,
		    h->n_wheel_tension_nm);
	json_vector(j, "wheel_elastic_nm", h->wheel_elastic_nm,
		    h->n_wheel_elastic_nm);
	json_vector(j, "wire_dl_m", h->wire_dl_m, h->n_wire_dl_m);
	json_double(j, "tube_contact_nm", h->tube_contact_nm);
	json_double(j, "tube_friction_nm", h->tube_friction_nm);
	json_vector(j, "damping", h->damping, h->n_damping);
	json_double(j, "passivity_energy_j", h->passivity_energy_j);
	json_double(j, "passivity_damping", h->passivity_damping);
	json_object_end(j);
}

static void json_faults(struct json *j, const Endosim__StatusReply *s)
{
	json_array_begin(j, "faults");
	for (size_t i = 0; i < s->n_faults; i++) {
		const Endosim__Fault *f = s->faults[i];

		json_object_begin(j, NULL);
		json_uint(j, "code", f->code);
		json_string(j, "name", f->name);
		json_string(j, "axis", f->axis);
		json_double(j, "time_s", f->time_s);
		json_string(j, "text", f->text);
		json_bool(j, "active", f->active);
		json_double(j, "value", f->value);
		json_double(j, "limit", f->limit);
		json_uint(j, "detail", f->detail);
		json_object_end(j);
	}
	json_array_end(j);
}

static void json_status(const Endosim__StatusReply *s)
{
	struct json j;

	json_init(&j, stdout);
	json_object_begin(&j, NULL);
	json_string(&j, "state", names_state((uint32_t)s->state));
	json_uint(&j, "fault_bits", s->fault_bits);
	json_string(&j, "fault", s->fault_text);
	json_faults(&j, s);
	json_uint(&j, "active_faults", s->active_faults);
	json_double(&j, "ramp", s->ramp);
	json_uint(&j, "cycle", s->cycle);
	json_uint(&j, "stamp_ns", s->stamp_ns);
	json_string(&j, "rt_policy", s->rt_policy);
	json_int(&j, "rt_priority", s->rt_priority);
	json_double(&j, "loop_hz", s->loop_hz);
	json_double(&j, "loop_rate_hz", s->loop_rate_hz);
	json_uint(&j, "overruns", s->overruns);
	json_string(&j, "rig", s->rig);
	json_string(&j, "version", s->version);
	json_double(&j, "uptime_s", s->uptime_s);
	json_double(&j, "scenario_time_s", s->scenario_time_s);
	json_bool(&j, "scenario_done", s->scenario_done);
	json_string(&j, "case", s->case_name);
	if (s->scope) {
		json_scope(&j, s->scope);
	}
	if (s->haptics) {
		json_haptics(&j, s->haptics);
	}
	json_object_begin(&j, "axes");
	for (size_t i = 0; i < s->n_axes; i++) {
		const Endosim__AxisStatus *a = s->axes[i];

		json_object_begin(&j, a->name);
		json_double(&j, "position", a->position);
		json_double(&j, "velocity", a->velocity);
		json_double(&j, "hand", a->hand);
		json_double(&j, "command", a->command);
		json_double(&j, "limited", a->limited);
		json_string(&j, "position_unit", a->position_unit);
		json_string(&j, "force_unit", a->force_unit);
		json_uint(&j, "drive_status", a->drive_status);
		json_string(&j, "drive", names_drive_status(a->drive_status));
		json_object_end(&j);
	}
	json_object_end(&j);
	json_object_end(&j);
}

static void print_haptics(const Endosim__HapticsStatus *h,
			  const Endosim__ScopeStatus *sc)
{
	printf("contact   %s, %.1f mm into the wall, %u plane(s); tube turning "
	       "%.2f rad\n", h->contact ? "yes" : "no",
	       h->penetration_m * 1e3, h->constraints, h->curvature_rad);
	printf("insertion contact %+.2f N, friction %+.2f N, loop %+.2f N\n",
	       h->trans_contact_n, h->trans_friction_n, h->trans_loop_n);
	printf("wheels    contact %+.3f/%+.3f, tension %+.3f/%+.3f, elastic "
	       "%+.3f/%+.3f N m\n", h->wheel_contact_nm[0],
	       h->wheel_contact_nm[1], h->wheel_tension_nm[0],
	       h->wheel_tension_nm[1], h->wheel_elastic_nm[0],
	       h->wheel_elastic_nm[1]);
	printf("tube      contact %+.3f N m, friction %+.3f N m; loops",
	       h->tube_contact_nm, h->tube_friction_nm);
	for (size_t i = 0; i < sc->n_bow_m; i++) {
		printf(" %.1f mm", sc->bow_m[i] * 1e3);
	}
	printf("\n");
}

static void print_status(const Endosim__StatusReply *s)
{
	printf("state     %s\n", names_state((uint32_t)s->state));
	printf("fault     %s\n", *s->fault_text ? s->fault_text : "none");
	for (size_t i = 0; i < s->n_faults; i++) {
		const Endosim__Fault *f = s->faults[i];

		printf("%s %s%s\n", i ? "          " : "  latched",
		       f->text, f->active ? "  [still present]" : "");
	}
	if (s->active_faults & ~s->fault_bits & ENDOSIM_FAULT_OVERRUN) {
		printf("warning   %s: more periods skipped than the budget "
		       "allows, not a fault here ([loop] overrun_fault)\n",
		       names_fault(ENDOSIM_FAULT_OVERRUN));
	}
	if (s->state == ENDOSIM__DAEMON_STATE__DAEMON_STATE_ENABLED &&
	    s->ramp < 1.0) {
		printf("ramp      forces at %.0f%% (rising after enable)\n",
		       s->ramp * 100.0);
	}
	printf("rig       %s, %s priority %d, %.1f Hz (configured %.0f), "
	       "overruns %llu\n", s->rig, s->rt_policy, s->rt_priority,
	       s->loop_hz, s->loop_rate_hz, (unsigned long long)s->overruns);
	printf("cycle     %llu, uptime %.1f s, scenario %.1f s%s\n",
	       (unsigned long long)s->cycle, s->uptime_s, s->scenario_time_s,
	       s->scenario_done ? " (ended)" : "");
	if (s->scope && s->scope->n_tip == 3 && s->scope->n_bend_rad == 2) {
		const Endosim__ScopeStatus *sc = s->scope;

		printf("case      %s\n", s->case_name);
		printf("scope     inserted %.3f m, tip at s %.3f m "
		       "(%.3f %.3f %.3f) m, bent %+.2f/%+.2f rad, turning "
		       "%.2f rad\n", sc->depth_m, sc->tip_s_m, sc->tip[0],
		       sc->tip[1], sc->tip[2], sc->bend_rad[0], sc->bend_rad[1],
		       sc->turning_rad);
	}
	if (s->haptics && s->haptics->n_wheel_contact_nm == 2 &&
	    s->haptics->n_wheel_tension_nm == 2 && s->scope &&
	    s->scope->n_bow_m <= 4) {
		print_haptics(s->haptics, s->scope);
	}
	printf("%-10s %16s %16s %12s %12s %12s  %s\n", "axis", "position",
	       "velocity", "hand", "command", "limited", "drive");
	for (size_t i = 0; i < s->n_axes; i++) {
		const Endosim__AxisStatus *a = s->axes[i];
		char pos[32], vel[32], hand[32], cmd[32], lim[32];

		snprintf(pos, sizeof(pos), "%+.4f %s", a->position,
			 a->position_unit);
		snprintf(vel, sizeof(vel), "%+.4f %s/s", a->velocity,
			 a->position_unit);
		snprintf(hand, sizeof(hand), "%+.3f %s", a->hand, a->force_unit);
		snprintf(cmd, sizeof(cmd), "%+.3f %s", a->command,
			 a->force_unit);
		snprintf(lim, sizeof(lim), "%+.3f %s", a->limited,
			 a->force_unit);
		printf("%-10s %16s %16s %12s %12s %12s  %s\n", a->name, pos,
		       vel, hand, cmd, lim,
		       names_drive_status(a->drive_status));
	}
}

static void json_histogram(struct json *j, const char *key,
			   const Endosim__Histogram *h)
{
	json_object_begin(j, key);
	json_double(j, "p50_us", h->p50_us);
	json_double(j, "p99_us", h->p99_us);
	json_double(j, "p999_us", h->p999_us);
	json_double(j, "max_us", h->max_us);
	json_double(j, "mean_us", h->mean_us);
	json_uint(j, "count", h->count);
	json_object_end(j);
}

static void json_buses(struct json *j, const Endosim__StatsReply *s)
{
	json_array_begin(j, "buses");
	for (size_t i = 0; i < s->n_buses; i++) {
		const Endosim__BusStats *b = s->buses[i];

		json_object_begin(j, NULL);
		json_string(j, "name", b->name);
		json_double(j, "rate_hz", b->rate_hz);
		json_uint(j, "exchanges", b->exchanges);
		json_histogram(j, "exchange", b->exchange);
		json_histogram(j, "transaction", b->transaction);
		json_object_end(j);
	}
	json_array_end(j);
}

static void print_buses(const Endosim__StatsReply *s)
{
	for (size_t i = 0; i < s->n_buses; i++) {
		const Endosim__BusStats *b = s->buses[i];

		printf("bus       %s: %.0f exchanges/s; exchange p50 %.0f p99 "
		       "%.0f us; transaction p50 %.0f p99 %.0f us\n", b->name,
		       b->rate_hz, b->exchange->p50_us, b->exchange->p99_us,
		       b->transaction->p50_us, b->transaction->p99_us);
	}
}

static void print_stats(const Endosim__StatsReply *s, bool json)
{
	if (json) {
		struct json j;

		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_uint(&j, "cycles", s->cycles);
		json_uint(&j, "overruns", s->overruns);
		json_string(&j, "rt_policy", s->rt_policy);
		json_int(&j, "rt_priority", s->rt_priority);
		json_double(&j, "period_us", s->period_us);
		json_histogram(&j, "latency", s->latency);
		json_histogram(&j, "compute", s->compute);
		json_buses(&j, s);
		json_object_end(&j);
		return;
	}
	printf("cycles %llu, overruns %llu, %s priority %d, period %.0f us\n",
	       (unsigned long long)s->cycles, (unsigned long long)s->overruns,
	       s->rt_policy, s->rt_priority, s->period_us);
	printf("%-9s %8s %8s %8s %8s %8s   (us)\n", "", "p50", "p99",
	       "p99.9", "max", "mean");
	printf("%-9s %8.0f %8.0f %8.0f %8.1f %8.1f\n", "latency",
	       s->latency->p50_us, s->latency->p99_us, s->latency->p999_us,
	       s->latency->max_us, s->latency->mean_us);
	printf("%-9s %8.0f %8.0f %8.0f %8.1f %8.1f\n", "compute",
	       s->compute->p50_us, s->compute->p99_us, s->compute->p999_us,
	       s->compute->max_us, s->compute->mean_us);
	print_buses(s);
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
	r = transact(ctl, false, &req, &rep);
	if (r) {
		return r;
	}
	if (ctl->json) {
		json_status(rep->status_reply);
	} else {
		print_status(rep->status_reply);
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
	r = transact(ctl, false, &req, &rep);
	if (r) {
		return r;
	}
	print_stats(rep->stats, ctl->json);
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
				json_status(rep->status_reply);
			} else {
				watch_line(rep->status_reply, tty);
			}
		}
		endosim__reply__free_unpacked(rep, NULL);
		clock_gettime(CLOCK_MONOTONIC, &now);
		if (duration_s > 0 && (double)(now.tv_sec - t0.tv_sec) +
		    (double)(now.tv_nsec - t0.tv_nsec) / 1e9 >= duration_s) {
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
	r = transact(ctl, false, &req, &rep);
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
	r = transact(ctl, true, &req, &rep);
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
	r = transact(ctl, false, &req, &rep);
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
	r = transact(ctl, true, &req, &rep);
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

static int cmd_hand(struct ctl *ctl, int argc, char **argv)
{
	Endosim__HandInput body = ENDOSIM__HAND_INPUT__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	double force[ENDOSIM_AXES];
	Endosim__Reply *rep;
	int r, n = 0;

	for (int i = 1; i < argc; i++) {
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
			"F_LR_NM [--hold-ms MS]\n");
		return EXIT_USAGE;
	}
	body.n_force = ENDOSIM_AXES;
	body.force = force;
	req.body_case = ENDOSIM__REQUEST__BODY_HAND_INPUT;
	req.hand_input = &body;
	r = transact(ctl, true, &req, &rep);
	if (!r) {
		endosim__reply__free_unpacked(rep, NULL);
	}
	return r;
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
	r = transact(ctl, false, &req, &rep);
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
	int action = argc >= 2 ? inject_find(argv[1]) : -1;
	bool axisless = action == INJECT_STALL || action == INJECT_END_CONTROL;
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
	    (!axisless && argc < 3 && action != INJECT_CLEAR)) {
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
	r = transact(ctl, false, &req, &rep);
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

/* ------------------------------------------------------------ sessions */

/* A session request; *REP is its OK reply. */
static int session_request(struct ctl *ctl, bool write,
			   Endosim__Request__BodyCase body, void *msg,
			   Endosim__Reply **rep)
{
	Endosim__Request req = ENDOSIM__REQUEST__INIT;

	req.body_case = body;
	req.enable = msg; /* one member of the oneof's union */
	return transact(ctl, write, &req, rep);
}

static const char *session_state(const Endosim__SessionInfo *s)
{
	return s->recording ? "recording" : s->ended ? "ended" : "cut short";
}

/*
 * When an ended session ended, UTC like its start (its start plus its
 * duration), into OUT; "" while it records, when its length is not known
 * (a listing does not read the records) or the start is unreadable.
 */
static void session_ended_at(const Endosim__SessionInfo *s, char *out,
			     size_t size)
{
	struct tm tm = { 0 };
	const char *rest = strptime(s->started, "%Y-%m-%dT%H:%M:%SZ", &tm);
	time_t t;

	out[0] = '\0';
	if (s->recording || !s->records || !rest || *rest ||
	    !isfinite(s->duration_s)) {
		return;
	}
	t = timegm(&tm) + (time_t)llround(s->duration_s);
	gmtime_r(&t, &tm);
	strftime(out, size, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* The session's facts as JSON members (the object is the caller's). */
static void json_session_facts(struct json *j, const Endosim__SessionInfo *s)
{
	char ended[32];

	session_ended_at(s, ended, sizeof(ended));
	json_uint(j, "id", s->id);
	json_string(j, "trainee", s->trainee);
	json_string(j, "case", s->case_name);
	json_string(j, "started", s->started);
	json_string(j, "ended_at", ended);
	json_string(j, "state", session_state(s));
	json_bool(j, "recording", s->recording);
	json_bool(j, "ended", s->ended);
	json_double(j, "duration_s", s->duration_s);
	json_uint(j, "records", s->records);
	json_uint(j, "drops", s->drops);
	json_uint(j, "bytes", s->bytes);
	json_string(j, "path", s->path);
}

static void print_session_facts(const Endosim__SessionInfo *s)
{
	char ended[32];

	session_ended_at(s, ended, sizeof(ended));
	printf("session %" PRIu64 " (%s): trainee '%s', case %s, started %s%s%s\n"
	       "file %s, %" PRIu64 " bytes\n", s->id, session_state(s),
	       s->trainee, s->case_name, s->started, *ended ? ", ended " : "",
	       ended, s->path, s->bytes);
	if (s->recording || s->records) {
		printf("%.1f s, %" PRIu64 " records, %" PRIu64 " dropped\n",
		       s->duration_s, s->records, s->drops);
	}
}

/* The session and the metrics M (NULL: none) on stdout. */
static void print_session(const struct ctl *ctl, const Endosim__SessionInfo *s,
			  const struct metrics_result *m, const char *note)
{
	struct json j;

	if (!ctl->json) {
		print_session_facts(s);
		if (note) {
			printf("%s\n", note);
		}
		if (m) {
			sessionview_print(stdout, m);
		}
		return;
	}
	json_init(&j, stdout);
	json_object_begin(&j, NULL);
	json_session_facts(&j, s);
	if (note) {
		json_string(&j, "note", note);
	}
	if (m) {
		sessionview_json(&j, "metrics", m);
	}
	json_object_end(&j);
}

static int session_start(struct ctl *ctl, int argc, char **argv)
{
	Endosim__SessionStart body = ENDOSIM__SESSION_START__INIT;
	Endosim__Reply *rep;
	int r;

	for (int i = 2; i < argc; i += 2) {
		if (i + 1 < argc && !strcmp(argv[i], "--trainee")) {
			body.trainee = argv[i + 1];
		} else if (i + 1 < argc && !strcmp(argv[i], "--case")) {
			body.case_name = argv[i + 1];
		} else {
			fprintf(stderr, "endoctl: session start [--trainee "
				"NAME] [--case NAME]\n");
			return EXIT_USAGE;
		}
	}
	r = session_request(ctl, true, ENDOSIM__REQUEST__BODY_SESSION_START,
			    &body, &rep);
	if (r) {
		return r;
	}
	print_session(ctl, rep->session->session, NULL, NULL);
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

/* Stop, status: the recorder's session with its live or final metrics. */
static int session_current(struct ctl *ctl, bool stop)
{
	Endosim__SessionStop stop_body = ENDOSIM__SESSION_STOP__INIT;
	Endosim__SessionStatus status_body = ENDOSIM__SESSION_STATUS__INIT;
	const Endosim__SessionInfo *s;
	struct metrics_result m;
	Endosim__Reply *rep;
	int r;

	r = stop ? session_request(ctl, true,
				   ENDOSIM__REQUEST__BODY_SESSION_STOP,
				   &stop_body, &rep)
		 : session_request(ctl, false,
				   ENDOSIM__REQUEST__BODY_SESSION_STATUS,
				   &status_body, &rep);
	if (r) {
		return r;
	}
	s = rep->session->session;
	if (!s) {
		printf(ctl->json ? "{\"recording\":false,\"id\":0}\n"
				 : "no session since endosimd started\n");
	} else {
		if (s->metrics) {
			sessionpb_to_metrics(s->metrics, &m);
		}
		print_session(ctl, s, s->metrics ? &m : NULL, NULL);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

static void print_session_list(const struct ctl *ctl,
			       const Endosim__SessionListReply *l)
{
	struct json j;

	if (!ctl->json) {
		printf("%6s  %-20s  %-10s  %-18s  %10s  %s\n", "ID", "STARTED",
		       "STATE", "CASE", "BYTES", "TRAINEE");
		for (size_t i = 0; i < l->n_sessions; i++) {
			const Endosim__SessionInfo *s = l->sessions[i];

			printf("%6" PRIu64 "  %-20s  %-10s  %-18s  %10" PRIu64
			       "  %s\n", s->id, s->started, session_state(s),
			       s->case_name, s->bytes, s->trainee);
		}
		return;
	}
	json_init(&j, stdout);
	json_object_begin(&j, NULL);
	json_string(&j, "directory", l->directory);
	json_array_begin(&j, "sessions");
	for (size_t i = 0; i < l->n_sessions; i++) {
		json_object_begin(&j, NULL);
		json_session_facts(&j, l->sessions[i]);
		json_object_end(&j);
	}
	json_array_end(&j);
	json_object_end(&j);
}

static int session_list(struct ctl *ctl)
{
	Endosim__SessionList body = ENDOSIM__SESSION_LIST__INIT;
	Endosim__Reply *rep;
	int r = session_request(ctl, false, ENDOSIM__REQUEST__BODY_SESSION_LIST,
				&body, &rep);

	if (r) {
		return r;
	}
	print_session_list(ctl, rep->session_list);
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

/*
 * A session named on the command line, its file read: by ID, with its facts
 * from endosimd; or by the path of its file (it has a '/': ./3.endoses),
 * with endosimd not asked (it may be stopped), its facts from the file as
 * endosimd would give them (sessiondir.h, sessionpb.h).
 */
struct shown {
	struct session_file f;
	const Endosim__SessionInfo *s;
	Endosim__Reply *rep;           /* by ID */
	struct sessiondir_entry entry; /* by path */
	Endosim__SessionInfo local;
};

/* R of reading the session file PATH, said on stderr; the exit status. */
static int session_file_error(const char *path, int r)
{
	fprintf(stderr, "endoctl: %s: %s\n", path, r == -EBADMSG ?
		"not a session file" : r == -EPROTO ?
		"a format this endoctl does not know" : strerror(-r));
	return EXIT_REFUSED;
}

static int session_open(struct ctl *ctl, const char *id_text, struct shown *sh)
{
	Endosim__SessionShow body = ENDOSIM__SESSION_SHOW__INIT;
	char *end;
	int r;

	if (strchr(id_text, '/')) {
		r = sessiondir_stat_file(id_text, &sh->entry);
		if (!r) {
			r = session_file_read(id_text, &sh->f);
		}
		if (r) {
			return session_file_error(id_text, r);
		}
		sessionpb_from_entry(&sh->local, &sh->entry);
		sh->local.path = (char *)id_text;
		sh->s = &sh->local;
		return 0;
	}
	body.id = strtoull(id_text, &end, 10);
	if (*end || !body.id) {
		fprintf(stderr, "endoctl: '%s' is neither a session id nor a "
			"session file's path (with a '/')\n", id_text);
		return EXIT_USAGE;
	}
	r = session_request(ctl, false, ENDOSIM__REQUEST__BODY_SESSION_SHOW,
			    &body, &sh->rep);
	if (r) {
		return r;
	}
	sh->s = sh->rep->session->session;
	r = session_file_read(sh->s->path, &sh->f);
	if (r) {
		r = session_file_error(sh->s->path, r);
		endosim__reply__free_unpacked(sh->rep, NULL);
		sh->rep = NULL;
	}
	return r;
}

static void session_close(struct shown *sh)
{
	session_file_close(&sh->f);
	if (sh->rep) {
		endosim__reply__free_unpacked(sh->rep, NULL);
	}
}

static int session_show(struct ctl *ctl, const char *id)
{
	struct shown sh = { 0 };
	Endosim__SessionInfo s;
	struct metrics_result m;
	char note[160] = "";
	bool recomputed;
	int r = session_open(ctl, id, &sh);

	if (r) {
		return r;
	}
	s = *sh.s;
	if (s.recording && s.metrics) {
		sessionpb_to_metrics(s.metrics, &m); /* live */
	} else if (sessionview_metrics(&sh.f, &m, &recomputed)) {
		fprintf(stderr, "endoctl: out of memory\n");
		r = EXIT_REFUSED;
		goto out;
	} else if (recomputed) {
		snprintf(note, sizeof(note), "no END frame (cut short, %zu "
			 "bytes after the last complete record ignored): "
			 "metrics recomputed from %zu records",
			 sh.f.bytes_ignored, sh.f.n_records);
	}
	if (!s.recording) { /* its length: the file's, as in its metrics */
		s.duration_s = m.duration_s;
		s.records = m.records;
		s.drops = m.drops;
	}
	print_session(ctl, &s, &m, *note ? note : NULL);
out:
	session_close(&sh);
	return r;
}

static int session_export(struct ctl *ctl, int argc, char **argv)
{
	const char *out_path = NULL;
	struct shown sh = { 0 };
	bool csv = false, events = false;
	FILE *out = stdout;
	int r;

	for (int i = 3; i < argc; i++) {
		if (!strcmp(argv[i], "--csv")) {
			csv = true;
		} else if (!strcmp(argv[i], "--events")) {
			events = true;
		} else if (!strcmp(argv[i], "--out") && i + 1 < argc) {
			out_path = argv[++i];
		} else {
			csv = false;
			break;
		}
	}
	if (!csv) {
		fprintf(stderr, "endoctl: session export ID|FILE --csv [--events] "
			"[--out FILE]\n");
		return EXIT_USAGE;
	}
	r = session_open(ctl, argv[2], &sh);
	if (r) {
		return r;
	}
	if (out_path && !(out = fopen(out_path, "we"))) {
		fprintf(stderr, "endoctl: %s: %s\n", out_path, strerror(errno));
		r = EXIT_REFUSED;
	}
	if (out && ((events ? sessionview_events_csv(out, &sh.f)
			    : sessionview_csv(out, &sh.f)) ||
		    (out_path && fclose(out)))) {
		fprintf(stderr, "endoctl: %s: write error\n",
			out_path ? out_path : "stdout");
		r = EXIT_REFUSED;
	}
	session_close(&sh);
	return r;
}

/* The instructor's HTML report (report.h) of session ID (or FILE) into DIR. */
static int session_report(struct ctl *ctl, const char *id, const char *dir)
{
	struct shown sh = { 0 };
	struct metrics_result m;
	bool recomputed;
	int r = session_open(ctl, id, &sh);

	if (r) {
		return r;
	}
	r = sessionview_metrics(&sh.f, &m, &recomputed);
	if (!r) {
		r = report_write(&sh.f, &m, dir);
	}
	if (r) {
		fprintf(stderr, "endoctl: report in %s: %s\n", dir,
			strerror(-r));
		r = EXIT_REFUSED;
	} else {
		printf("wrote %s/index.html%s\n", dir, recomputed ?
		       " (metrics recomputed: the file was cut short)" : "");
	}
	session_close(&sh);
	return r;
}

static int cmd_session(struct ctl *ctl, int argc, char **argv)
{
	const char *sub = argc >= 2 ? argv[1] : "";

	if (!strcmp(sub, "start")) {
		return session_start(ctl, argc, argv);
	}
	if (argc == 2 && (!strcmp(sub, "stop") || !strcmp(sub, "status"))) {
		return session_current(ctl, !strcmp(sub, "stop"));
	}
	if (argc == 2 && !strcmp(sub, "list")) {
		return session_list(ctl);
	}
	if (argc == 3 && !strcmp(sub, "show")) {
		return session_show(ctl, argv[2]);
	}
	if (argc >= 3 && !strcmp(sub, "export")) {
		return session_export(ctl, argc, argv);
	}
	if (argc == 5 && !strcmp(sub, "report") && !strcmp(argv[3], "--out")) {
		return session_report(ctl, argv[2], argv[4]);
	}
	fprintf(stderr, "endoctl: session start [--trainee NAME] [--case NAME]"
		" | stop | status | list | show ID | export ID --csv [--events] "
		"[--out FILE] | report ID --out DIR (ID: or a session file's "
		"path, read without endosimd)\n");
	return EXIT_USAGE;
}

/* ------------------------------------------------------------ main */

static const struct {
	const char *name;
	command_fn *fn;
	const char *help;
} commands[] = {
	{ "status", cmd_status, "state, faults, loop and axes" },
	{ "stats", cmd_stats, "force-loop latency and compute time [--reset]" },
	{ "watch", cmd_watch, "live status line [--rate HZ] [--duration S]" },
	{ "enable", cmd_enable, "IDLE -> ENABLED: render forces" },
	{ "disable", cmd_disable, "ENABLED -> IDLE: torque off" },
	{ "estop", cmd_estop, "emergency stop (latched)" },
	{ "reset", cmd_reset, "clear ESTOP or a FAULT whose cause is gone" },
	{ "get", cmd_get, "[SECTION.KEY]: configuration" },
	{ "set", cmd_set, "SECTION.KEY VALUE: change a live key" },
	{ "hand", cmd_hand, "F_INS F_ROLL F_UD F_LR [--hold-ms MS]: push the "
			    "simulated hand (N, N m)" },
	{ "case", cmd_case, "list | load NAME: the anatomy cases (load: IDLE "
			    "only)" },
	{ "scene", cmd_scene, "info | export FILE.obj: the colon the daemon "
			      "renders" },
	{ "session", cmd_session, "start [--trainee NAME] [--case NAME] | stop "
				  "| status | list | show ID | export ID "
				  "--csv [--events] [--out FILE] | report "
				  "ID --out DIR: training sessions (ID: or "
				  "./N.endoses, without endosimd)" },
	{ "version", cmd_version, "endoctl's and endosimd's versions" },
	{ "debug", cmd_debug, "ACTION [AXIS] [VALUE]: fault injection, for "
			      "tests only" },
};

static void usage(FILE *out)
{
	fprintf(out, "usage: endoctl [--socket PATH] [--json] [--timeout MS] "
		"COMMAND [ARGS]\n\nPATH is a socket or the directory holding "
		"both (default $%s or %s).\n\ncommands:\n", CLIENT_ENV,
		CLIENT_DEFAULT_DIR);
	for (size_t i = 0; i < sizeof(commands) / sizeof(commands[0]); i++) {
		fprintf(out, "  %-8s %s\n", commands[i].name, commands[i].help);
	}
	fprintf(out, "\nexit status: 0 ok, 1 refused by endosimd, 2 usage, "
		"3 endosimd not running, 4 communication error\n");
}

int main(int argc, char **argv)
{
	static const struct option opts[] = {
		{ "socket", required_argument, NULL, 's' },
		{ "json", no_argument, NULL, 'j' },
		{ "timeout", required_argument, NULL, 't' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 },
	};
	struct ctl ctl = { .timeout_ms = 2000 };
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
	for (size_t i = 0; i < sizeof(commands) / sizeof(commands[0]); i++) {
		if (!strcmp(argv[optind], commands[i].name)) {
			r = commands[i].fn(&ctl, argc - optind, argv + optind);
			client_close(ctl.client);
			return r;
		}
	}
	fprintf(stderr, "endoctl: unknown command '%s'\n", argv[optind]);
	usage(stderr);
	return EXIT_USAGE;
}
