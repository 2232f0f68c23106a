/*
 * control_reply.c - the control thread's replies: status, stats,
 * configuration, commands, the hand, subscriptions, test commands
 * (control_private.h).
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/log.h"
#include "base/mono.h"
#include "control/control_private.h"
#include "loop/faults.h"
#include "proto/fields.h"
#include "proto/names.h"
#include "proto/version.h"

#define MAX_PUSH_HZ 1000.0
#define MAX_HOLD_S 10.0
#define ALL_VALVES                                                           \
	(ENDOSIM_VALVE_AIR | ENDOSIM_VALVE_WATER | ENDOSIM_VALVE_SUCTION)

/* Storage for the reply being built: no allocation per reply. */
struct control_replies {
	Endosim__StatusReply status;
	Endosim__AxisStatus axes[ENDOSIM_AXES];
	Endosim__AxisStatus *axes_p[ENDOSIM_AXES];
	Endosim__Fault faults[ENDOSIM_FAULT_BITS];
	Endosim__Fault *faults_p[ENDOSIM_FAULT_BITS];
	char fault_lines[ENDOSIM_FAULT_BITS][640];
	Endosim__ScopeStatus scope;
	Endosim__HapticsStatus haptics;
	Endosim__RodStatus rod;
	Endosim__GuideStatus guide;
	Endosim__PatientStatus patient;
	Endosim__ToolStatus tool;
	Endosim__ToolPolyp tool_polyps[ENDOSIM_POLYPS];
	Endosim__ToolPolyp *tool_polyps_p[ENDOSIM_POLYPS];
	struct endosim_state state; /* what the status reply points into */
	Endosim__StatsReply stats;
	Endosim__Histogram latency, compute;
	Endosim__BusStats buses[ENDOSIM_AXES];
	Endosim__BusStats *buses_p[ENDOSIM_AXES];
	Endosim__Histogram bus_histo[ENDOSIM_AXES][2];
	Endosim__ConfigReply config;
	Endosim__ConfigEntry *entries;     /* one per key */
	Endosim__ConfigEntry **entries_p;
	char (*values)[CONFIG_STR + 32];
	char error[256];                   /* SetParam's refusal */
};

struct control_replies *control_replies_create(void)
{
	struct control_replies *rb = calloc(1, sizeof(*rb));
	size_t keys = config_key_count();

	if (!rb) {
		return NULL;
	}
	rb->entries = calloc(keys, sizeof(*rb->entries));
	rb->entries_p = calloc(keys, sizeof(*rb->entries_p));
	rb->values = calloc(keys, sizeof(*rb->values));
	if (!rb->entries || !rb->entries_p || !rb->values) {
		control_replies_destroy(rb);
		return NULL;
	}
	return rb;
}

void control_replies_destroy(struct control_replies *rb)
{
	if (!rb) {
		return;
	}
	free(rb->entries);
	free(rb->entries_p);
	free(rb->values);
	free(rb);
}

/* ---------------------------------------------------------------- replies */

/* One latched fault, bit number K, into the reply's slot N. */
static void fill_fault(struct control *c, const struct endosim_state *st,
		       int k, size_t n)
{
	const struct endosim_fault_cause *fc = &st->safety.cause[k];
	struct control_replies *rb = c->replies;
	Endosim__Fault *f = &rb->faults[n];

	fields_to_pb(&fields_fault, f, fc);
	faults_format(c->deps.rig, c->deps.start_ns, 1u << k, fc,
		      rb->fault_lines[n], sizeof(rb->fault_lines[n]));
	f->code = (uint32_t)k;
	f->name = (char *)names_fault(1u << k);
	f->axis = fc->axis >= 0 ? (char *)names_axis(fc->axis) : "";
	f->time_s =
		(double)(fc->first_ns - c->deps.start_ns) / ENDOSIM_NS_PER_S;
	f->text = rb->fault_lines[n];
	f->active = st->safety.active & 1u << k;
	rb->faults_p[n] = f;
}

/* Every latched fault, the first one first; its line is the fault text. */
static void fill_faults(struct control *c, const struct endosim_state *st,
			Endosim__StatusReply *s)
{
	size_t n = 0;

	if (st->fault_first) {
		fill_fault(c, st, __builtin_ctz(st->fault_first), n++);
	}
	for (int k = 0; k < ENDOSIM_FAULT_BITS; k++) {
		if ((st->fault_bits & 1u << k) && 1u << k != st->fault_first) {
			fill_fault(c, st, k, n++);
		}
	}
	s->n_faults = n;
	s->faults = c->replies->faults_p;
	s->fault_text = n ? c->replies->fault_lines[0] : "";
}

/* The axes: their values (fields.h) with their names and units. */
static void fill_axes(struct control_replies *rb, Endosim__StatusReply *s)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		Endosim__AxisStatus *ax = &rb->axes[a];

		fields_to_pb(&fields_axis, ax, &rb->state.axis[a]);
		ax->name = (char *)names_axis(a);
		ax->position_unit = (char *)names_axis_position_unit(a);
		ax->force_unit = (char *)names_axis_force_unit(a);
		rb->axes_p[a] = ax;
	}
	s->n_axes = ENDOSIM_AXES;
	s->axes = rb->axes_p;
}

/* The patient's values (fields.h) with the name of the site pressed. */
static void fill_patient(struct control *c, Endosim__StatusReply *s)
{
	struct control_replies *rb = c->replies;
	const struct anatomy *a = colon_anatomy(c->colon);
	int site = rb->state.patient.hand_site;

	fields_to_pb(&fields_patient, &rb->patient, &rb->state.patient);
	rb->patient.site = a && site >= 0 && site < a->sites ?
				   (char *)a->site[site].name : "";
	s->patient = &rb->patient;
}

/* The tool's values (fields.h) with each of the case's polyps'. */
static void fill_tool(struct control_replies *rb, Endosim__StatusReply *s)
{
	const struct endosim_tool_state *t = &rb->state.tool;
	size_t n = t->polyps < ENDOSIM_POLYPS ? t->polyps : ENDOSIM_POLYPS;

	fields_to_pb(&fields_tool, &rb->tool, t);
	for (size_t i = 0; i < n; i++) {
		fields_to_pb(&fields_tool_polyp, &rb->tool_polyps[i],
			     &t->polyp[i]);
		rb->tool_polyps_p[i] = &rb->tool_polyps[i];
	}
	rb->tool.n_polyp = n;
	rb->tool.polyp = rb->tool_polyps_p;
	s->tool = &rb->tool;
}

/* The state's values by fields.h's tables; the rest is the daemon's. */
void control_build_status(struct control *c, Endosim__Reply *rep)
{
	struct control_replies *rb = c->replies;
	const struct loop_info *info = loop_get_info(c->deps.loop);
	Endosim__StatusReply *s = &rb->status;
	const struct endosim_state *st = &rb->state;

	if (publish_read(c->deps.pub, &rb->state)) {
		rep->status = ENDOSIM__STATUS__STATUS_INTERNAL;
		rep->error = "state busy, try again";
		return;
	}
	fields_to_pb(&fields_status, s, st);
	fill_faults(c, st, s);
	s->rt_policy = (char *)info->policy;
	s->rt_priority = info->priority;
	s->loop_hz = c->loop_hz ? c->loop_hz
				: (double)st->cycle * ENDOSIM_NS_PER_S /
					  (double)(st->stamp_ns - c->deps.start_ns + 1);
	s->loop_rate_hz = c->cfg.loop.rate_hz;
	s->rig = (char *)rig_name(c->deps.rig);
	s->version = ENDOSIM_VERSION;
	s->uptime_s = (double)(mono_ns() - c->deps.start_ns) / ENDOSIM_NS_PER_S;
	s->case_name = (char *)colon_name(c->colon);
	s->trainee = c->training.trainee;
	s->asks_trainee = c->training.asks;
	fields_to_pb(&fields_scope, &rb->scope, &st->scope);
	s->scope = &rb->scope;
	fields_to_pb(&fields_haptics, &rb->haptics, &st->haptics);
	s->haptics = &rb->haptics;
	fields_to_pb(&fields_rod, &rb->rod, &st->rod);
	s->rod = &rb->rod;
	fields_to_pb(&fields_guide, &rb->guide, &st->guide);
	s->guide = &rb->guide;
	fill_patient(c, s);
	fill_tool(rb, s);
	fill_axes(rb, s);
	rep->body_case = ENDOSIM__REPLY__BODY_STATUS_REPLY;
	rep->status_reply = s;
}

void control_await_state(struct control *c)
{
	struct endosim_state st;
	uint64_t seen, deadline = mono_ns() + 100000000ull;
	struct timespec nap = { .tv_nsec = 100000 };

	if (publish_read(c->deps.pub, &st)) {
		return;
	}
	seen = st.cycle;
	while (mono_ns() < deadline && !publish_read(c->deps.pub, &st) &&
	       st.cycle <= seen) {
		nanosleep(&nap, NULL);
	}
}

static void fill_histogram(Endosim__Histogram *h,
			   const struct histo_summary *s)
{
	endosim__histogram__init(h);
	h->p50_us = s->p50_us;
	h->p99_us = s->p99_us;
	h->p999_us = s->p999_us;
	h->max_us = s->max_us;
	h->mean_us = s->mean_us;
	h->count = s->count;
}

/* At most one bus per axis. */
static void fill_buses(struct control *c)
{
	struct control_replies *rb = c->replies;
	struct rig_bus_stats st;
	size_t n = 0;

	while (n < ENDOSIM_AXES && !rig_bus_stats(c->deps.rig, (int)n, &st)) {
		Endosim__BusStats *b = &rb->buses[n];

		endosim__bus_stats__init(b);
		b->name = (char *)st.name;
		b->rate_hz = st.rate_hz;
		b->exchanges = st.exchanges;
		fill_histogram(&rb->bus_histo[n][0], &st.exchange);
		fill_histogram(&rb->bus_histo[n][1], &st.txn);
		b->exchange = &rb->bus_histo[n][0];
		b->transaction = &rb->bus_histo[n][1];
		rb->buses_p[n++] = b;
	}
	rb->stats.n_buses = n;
	rb->stats.buses = rb->buses_p;
}

static void build_stats(struct control *c, Endosim__Reply *rep)
{
	struct control_replies *rb = c->replies;
	const struct loop_info *info = loop_get_info(c->deps.loop);
	struct loop_stats st;

	loop_get_stats(c->deps.loop, &st);
	endosim__stats_reply__init(&rb->stats);
	rb->stats.cycles = st.cycles;
	rb->stats.overruns = st.overruns;
	fill_histogram(&rb->latency, &st.latency);
	fill_histogram(&rb->compute, &st.compute);
	rb->stats.latency = &rb->latency;
	rb->stats.compute = &rb->compute;
	rb->stats.rt_policy = (char *)info->policy;
	rb->stats.rt_priority = info->priority;
	rb->stats.period_us = info->period_ns / 1000.0;
	fill_buses(c);
	rep->body_case = ENDOSIM__REPLY__BODY_STATS;
	rep->stats = &rb->stats;
}

void control_on_get_status(struct control *c, struct client *cl,
			   const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)cl;
	(void)req;
	control_build_status(c, rep);
}

void control_on_get_stats(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)cl;
	(void)req;
	build_stats(c, rep);
}

void control_on_get_config(struct control *c, struct client *cl,
			   const Endosim__Request *req, Endosim__Reply *rep)
{
	struct control_replies *rb = c->replies;
	const char *want = req->get_config->key;
	size_t n = 0;

	(void)cl;
	for (size_t i = 0; i < config_key_count(); i++) {
		const struct parse_key *k = config_key_at(i);
		Endosim__ConfigEntry *e = &rb->entries[n];
		char *value = rb->values[n];
		int len = snprintf(value, sizeof(rb->values[n]), "%s.%s",
				   k->section, k->name);

		if (*want && strcmp(want, value)) {
			continue;
		}
		endosim__config_entry__init(e);
		e->key = value;
		config_format(&c->cfg, k, value + len + 1,
			      sizeof(rb->values[n]) - (size_t)len - 1);
		e->value = value + len + 1;
		e->unit = (char *)k->unit;
		e->live = k->flags & CONFIG_LIVE;
		e->help = (char *)k->help;
		rb->entries_p[n++] = e;
	}
	if (*want && !n) {
		refuse(rep, ENDOSIM__STATUS__STATUS_UNKNOWN_KEY, "no such key");
		return;
	}
	endosim__config_reply__init(&rb->config);
	rb->config.n_entries = n;
	rb->config.entries = rb->entries_p;
	rep->body_case = ENDOSIM__REPLY__BODY_CONFIG;
	rep->config = &rb->config;
}

void control_on_set_param(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__SetParam *sp = req->set_param;
	const struct parse_key *k = config_key_find(sp->key);
	char before[CONFIG_STR + 32];
	int r;

	if (k) {
		config_format(&c->cfg, k, before, sizeof(before));
	}
	r = config_set(&c->cfg, sp->key, sp->value, true, c->replies->error,
		       sizeof(c->replies->error));
	if (r) {
		refuse(rep, r == -ENOENT   ? ENDOSIM__STATUS__STATUS_UNKNOWN_KEY
		       : r == -EPERM ? ENDOSIM__STATUS__STATUS_NOT_LIVE
		       : ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       c->replies->error);
		return;
	}
	loop_set_config(c->deps.loop, &c->cfg);
	atomic_store(&log_max_level, c->cfg.log.level);
	recorder_param(c->deps.recorder, sp->key, sp->value);
	log_notice("%s set from %s to %s (uid %d)", sp->key, before, sp->value,
		   (int)cl->uid);
}

static void on_command(struct control *c, struct client *cl,
		       enum loop_cmd cmd, const char *what,
		       Endosim__Reply *rep)
{
	int r = loop_command(c->deps.loop, cmd, COMMAND_TIMEOUT_MS);

	switch (r) {
	case 0:
		log_info("%s by uid %d", what, (int)cl->uid);
		return;
	case -EPERM:
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "latched in FAULT or ESTOP: reset first");
		return;
	case -EBUSY:
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "the fault's cause is still present");
		return;
	default:
		refuse(rep, ENDOSIM__STATUS__STATUS_TIMEOUT,
		       "the force loop did not take the command");
		return;
	}
}

void control_on_enable(struct control *c, struct client *cl,
		       const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_ENABLE, "enable", rep);
}

void control_on_disable(struct control *c, struct client *cl,
			const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_DISABLE, "disable", rep);
}

void control_on_estop(struct control *c, struct client *cl,
		      const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_ESTOP, "emergency stop", rep);
}

void control_on_reset(struct control *c, struct client *cl,
		      const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_RESET, "reset", rep);
}

void control_on_reset_stats(struct control *c, struct client *cl,
			    const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_RESET_STATS, "statistics reset", rep);
}

void control_on_hand_input(struct control *c, struct client *cl,
			   const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__HandInput *hi = req->hand_input;
	double hold = hi->hold_ms ? hi->hold_ms / 1000.0 : c->cfg.sim.hand_hold_s;

	(void)cl;
	if (!c->deps.hand) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "the rig is not simulated");
		return;
	}
	if ((hi->n_force != ENDOSIM_AXES && hi->n_force) || hold > MAX_HOLD_S) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "need 4 forces (or none: the valves alone) and a hold "
		       "of at most 10 s");
		return;
	}
	if (hi->valves & ~ALL_VALVES) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "valves: 1 air, 2 water, 4 suction");
		return;
	}
	for (size_t a = 0; a < hi->n_force; a++) {
		if (!isfinite(hi->force[a])) {
			refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
			       "forces must be finite");
			return;
		}
	}
	if (hi->tool && (!isfinite(hi->tool_depth_m) ||
			 !isfinite(hi->tool_opening) || hi->tool_opening < 0 ||
			 hi->tool_opening > 1)) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "tool: a finite depth, an opening 0..1");
		return;
	}
	if (hi->tool) {
		hand_set_tool(c->deps.hand, hi->tool_depth_m, hi->tool_opening,
			      hi->tool_pedal, hold, mono_ns());
	}
	if (hi->hands_off) {
		hand_release(c->deps.hand);
	}
	if ((hi->hands_off || hi->tool) && !hi->n_force && !hi->valves) {
		return; /* the valves held stay held */
	}
	hand_set_live(c->deps.hand, hi->n_force ? hi->force : NULL, hi->valves,
		      hold, mono_ns());
}

void control_on_subscribe(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	double hz = req->subscribe->rate_hz;

	if (!isfinite(hz) || hz < 0 || hz > MAX_PUSH_HZ) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "rate_hz must be in [0, 1000]");
		return;
	}
	cl->push_period_ns = hz > 0 ? (uint64_t)(ENDOSIM_NS_PER_S / hz) : 0;
	cl->next_push_ns = mono_ns();
	cl->push_seq = req->seq;
	control_build_status(c, rep);
}

void control_on_debug(struct control *c, struct client *cl,
		      const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__DebugInject *d = req->debug_inject;
	const char *name = names_debug_action(d->action);
	int r;

	if (!c->cfg.debug.test_commands) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "test commands are off ([debug] test_commands = no)");
		return;
	}
	log_warn("test command %s on axis %d, value %g (uid %d)",
		 name ? name : "?", d->axis, d->value, (int)cl->uid);
	if (d->action == ENDOSIM__DEBUG_ACTION__DEBUG_ACTION_END_CONTROL) {
		c->end = true;
		return;
	}
	r = loop_debug(c->deps.loop, d->action, d->axis, d->value,
		       COMMAND_TIMEOUT_MS);
	if (r == -EINVAL) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "no such test command, axis or stage");
	} else if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_TIMEOUT,
		       "the force loop did not take the command");
	}
}
