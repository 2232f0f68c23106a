/* loop.c - see loop.h. */
#include "loop/loop.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "conf/cases.h"
#include "model/haptics.h"
#include "loop/inject.h"
#include "loop/mailbox.h"
#include "base/log.h"
#include "base/mono.h"
#include "base/rt.h"
#include "model/scope.h"
#include "model/tool.h"
#include "base/spsc.h"

#define LOOP_STACK_BYTES (512 * 1024) /* more than RT_PREFAULT_BYTES */
#define LOOP_EVENTS 256

/* A guidance command and its request's number, in their box. */
struct guide_post {
	struct guide_command c;
	uint32_t seq;
};

/* A patient command and its request's number, in their box. */
struct patient_post {
	struct loop_patient_command c;
	uint32_t seq;
};

/* A tool command and its request's number, in their box. */
struct tool_post {
	struct loop_tool_command c;
	uint32_t seq;
};

struct loop {
	/* owned by the loop thread */
	struct config cfg;
	struct config cfg_incoming; /* scratch for a torn-free copy */
	struct safety safety;
	struct rig_feedback fb;
	double command[ENDOSIM_AXES];
	double limited[ENDOSIM_AXES];
	struct endosim_state state;
	bool scenario_was_done;
	struct colon *colon;
	uint64_t scene_id;
	struct scope_pose pose;
	struct haptics *haptics;
	uint64_t skipped;          /* periods skipped before this cycle */
	uint64_t stall_ns;         /* a test command: sleep after the cycle */
	struct inject inject;      /* test commands' sabotage */
	struct guide guide;        /* guided replay (guide.h) */
	bool lockstep;             /* loop_step(): stamps on the caller's clock */
	uint32_t patient_seq;      /* the scenario's last patient command done */
	bool guide_playing;        /* the recording's patient plays along */
	struct guide_patient guide_was; /* what it last asked of the patient */
	uint32_t guide_valves;     /* the recording's, pressed this cycle */
	struct tool tool;          /* the working channel's (tool.h) */

	/* shared */
	struct rig *rig;
	struct publish *pub;
	struct session_tap *tap;   /* NULL: no recorder */
	pthread_t thread;
	bool running;
	int pm_qos_fd;             /* /dev/cpu_dma_latency, held open */
	_Atomic bool stop;
	_Atomic uint64_t heartbeat;
	_Atomic uint64_t overruns;
	struct histo latency;
	struct histo compute;
	struct loop_info info;
	struct spsc events;        /* loop -> main */
	/* control -> loop (mailbox.h) */
	struct mailbox_box cfg_box;
	struct config cfg_mailbox;
	struct mailbox_slot cmd;
	struct mailbox_swap colon_swap; /* struct colon * */
	uint64_t scene_id_in;      /* published by the swap's hand-over */
	struct tool tool_in;       /* its polyps placed, the same way */
	struct mailbox_box debug_box; /* a test command */
	struct loop_debug debug_mailbox;
	struct mailbox_answer debug_answer;
	struct mailbox_box guide_box; /* a guidance command */
	struct guide_post guide_mailbox;
	struct mailbox_answer guide_answer;
	struct mailbox_box patient_box; /* a patient command */
	struct patient_post patient_mailbox;
	struct mailbox_answer patient_answer;
	struct mailbox_box tool_box; /* a tool command */
	struct tool_post tool_mailbox;
	struct mailbox_answer tool_answer;
	_Atomic uint32_t fail_bits; /* main -> loop: a thread died */
	_Atomic uint32_t fail_detail;
};

static struct timespec to_timespec(uint64_t ns)
{
	return (struct timespec){ .tv_sec = (time_t)(ns / ENDOSIM_NS_PER_S),
				  .tv_nsec = (long)(ns % ENDOSIM_NS_PER_S) };
}

struct loop *loop_create(const struct config *cfg, struct rig *rig,
			 struct publish *pub, struct colon *colon,
			 uint64_t scene_id)
{
	struct loop *l = calloc(1, sizeof(*l));

	if (!l) {
		log_err("force loop: out of memory");
		return NULL;
	}
	guide_init(&l->guide);
	if (spsc_init(&l->events, LOOP_EVENTS, sizeof(struct loop_event))) {
		log_err("force loop: out of memory");
		free(l);
		return NULL;
	}
	{
		struct haptics_params hp;

		cases_haptics_params(cfg, &hp);
		l->haptics = haptics_create(&hp);
	}
	if (!l->haptics) {
		log_err("force loop: out of memory for the haptics' model");
		spsc_free(&l->events);
		free(l);
		return NULL;
	}
	l->cfg = *cfg;
	l->cfg_mailbox = *cfg;
	mailbox_box_init(&l->cfg_box, &l->cfg_mailbox, sizeof(l->cfg_mailbox));
	mailbox_box_init(&l->debug_box, &l->debug_mailbox,
			 sizeof(l->debug_mailbox));
	mailbox_box_init(&l->guide_box, &l->guide_mailbox,
			 sizeof(l->guide_mailbox));
	mailbox_box_init(&l->patient_box, &l->patient_mailbox,
			 sizeof(l->patient_mailbox));
	mailbox_box_init(&l->tool_box, &l->tool_mailbox,
			 sizeof(l->tool_mailbox));
	tool_reset(&l->tool);
	(void)tool_place_polyps(&l->tool, colon);
	l->rig = rig;
	l->pub = pub;
	l->colon = colon;
	l->scene_id = scene_id;
	haptics_reset(l->haptics, colon);
	safety_init(&l->safety);
	l->pm_qos_fd = -1;
	l->info.policy = "none";
	l->info.period_ns = (uint32_t)(1000000000u / (unsigned)cfg->loop.rate_hz);
	return l;
}

/* --- inside the loop thread: nothing below may block or allocate --- */

static void post(struct loop *l, const struct loop_event *ev)
{
	/* a full ring drops the event: the state in shm still tells */
	(void)spsc_push(&l->events, ev);
}

static void fetch_config(struct loop *l)
{
	if (mailbox_box_take(&l->cfg_box, &l->cfg_incoming)) {
		memcpy(&l->cfg, &l->cfg_incoming, sizeof(l->cfg));
	}
}

/* Takes a posted command, if any, and answers it. Returns the command. */
static uint32_t take_command(struct loop *l, uint64_t now)
{
	uint32_t seq, cmd = mailbox_slot_take(&l->cmd, &seq);
	int r;

	if (!cmd) {
		return 0;
	}
	if (cmd == LOOP_CMD_RESET_STATS) {
		histo_reset(&l->latency);
		histo_reset(&l->compute);
		r = 0;
	} else {
		r = safety_command(&l->safety, (enum safety_cmd)cmd, now);
	}
	mailbox_answer_set(&l->cmd.answer, seq, r);
	return cmd;
}

static void post_changes(struct loop *l, uint32_t old_state,
			 uint32_t old_faults, uint32_t cmd, uint64_t now)
{
	const struct safety *s = &l->safety;
	uint32_t added = s->faults & ~old_faults;

	for (uint32_t k = 0; added; k++) {
		uint32_t bit = 1u << k;

		if (added & bit) {
			struct loop_event ev = {
				.stamp_ns = now, .code = LOOP_EV_FAULT,
				.arg = bit, .axis = s->cause[k].axis,
				.detail = s->cause[k].detail,
				.value = s->cause[k].value,
				.limit = s->cause[k].limit,
			};
			post(l, &ev);
			added &= ~bit;
		}
	}
	if (s->state != old_state) {
		struct loop_event ev = {
			.stamp_ns = now, .code = LOOP_EV_STATE,
			.arg = s->state, .prev = old_state, .cmd = cmd,
			.axis = -1,
		};
		post(l, &ev);
	}
}

static void fill_state(struct loop *l, uint64_t now, uint64_t latency)
{
	struct endosim_state *st = &l->state;
	const struct safety *s = &l->safety;
	const struct endosim_fault_cause *first = safety_first(s);

	st->cycle = atomic_load_explicit(&l->heartbeat, memory_order_relaxed);
	st->stamp_ns = now;
	st->state = s->state;
	st->fault_bits = s->faults;
	st->fault_first = s->fault_bit;
	st->fault_axis = first ? first->axis : -1;
	st->fault_detail = first ? first->detail : 0;
	st->fault_ns = first ? first->first_ns : 0;
	safety_publish(s, now, &st->safety);
	st->overruns = atomic_load_explicit(&l->overruns, memory_order_relaxed);
	st->latency_ns = (uint32_t)(latency < UINT32_MAX ? latency : UINT32_MAX);
	st->scenario_time_s = l->fb.hand_time_s;
	st->scenario_done = l->fb.hand_done;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		struct endosim_axis_state *ax = &st->axis[a];
		const struct rig_axis_feedback *f = &l->fb.axis[a];

		ax->position = f->position;
		ax->velocity = f->velocity;
		ax->hand = f->hand;
		ax->command = l->command[a];
		ax->limited = l->limited[a];
		ax->feedback_ns = f->stamp_ns;
		ax->drive_status = f->status;
	}
}

/* Takes a new colon from the control thread, only while IDLE. */
static void take_colon(struct loop *l)
{
	struct colon *in = mailbox_swap_take(&l->colon_swap);

	if (!in) {
		return;
	}
	if (l->safety.state != ENDOSIM_STATE_IDLE) {
		mailbox_swap_give_back(&l->colon_swap, in);
		return;
	}
	/* the new case's polyps, the tool in hand kept: before the give
	 * back, which frees tool_in for the control thread */
	(void)tool_select(&l->tool_in, l->tool.kind, l->tool.snare_m);
	l->tool = l->tool_in;
	mailbox_swap_give_back(&l->colon_swap, l->colon);
	l->colon = in;
	l->scene_id = l->scene_id_in;
	haptics_reset(l->haptics, in);
}

/* Carries out C on the patient: 0, or -EINVAL (patient_turn() or
 * patient_press() refused it; nothing changed). */
static int patient_do(struct loop *l, const struct loop_patient_command *c)
{
	struct patient *pt = haptics_patient(l->haptics);

	switch (c->op) {
	case LOOP_PATIENT_TURN:
		return patient_turn(pt, c->arg);
	case LOOP_PATIENT_PRESS:
		return patient_press(pt, c->arg, c->force_n);
	case LOOP_PATIENT_RELEASE:
		patient_release(pt);
		return 0;
	case LOOP_PATIENT_SEDATE:
		return patient_sedate(pt, c->arg);
	default:
		return -EINVAL;
	}
}

/*
 * The scenario's command for the assistant (the rig's feedback: the
 * simulated hand's scenario), carried out once per new number, before the
 * patient's step of this cycle, as the control thread's would be (its
 * site by name in the case). One the patient refuses changes nothing.
 */
static void scenario_patient(struct loop *l)
{
	const struct scenario_patient *c = &l->fb.patient;
	const struct anatomy *a = colon_anatomy(l->colon);
	struct loop_patient_command cmd = { LOOP_PATIENT_RELEASE, 0, 0 };

	if (c->seq == l->patient_seq) {
		return;
	}
	l->patient_seq = c->seq;
	if (c->action == SCENARIO_PATIENT_TURN) {
		cmd = (struct loop_patient_command){ LOOP_PATIENT_TURN,
						     c->position, 0 };
	} else if (c->action == SCENARIO_PATIENT_PRESS) {
		cmd = (struct loop_patient_command){ LOOP_PATIENT_PRESS,
			a ? anatomy_site_find(a, c->site) : -1, c->force_n };
	} else if (c->action != SCENARIO_PATIENT_RELEASE) {
		return;
	}
	(void)patient_do(l, &cmd);
}

/* The patient as it lies now, in the recording's terms. */
static void patient_now(struct loop *l, struct guide_patient *out)
{
	const struct patient *pt = haptics_patient(l->haptics);

	*out = (struct guide_patient){
		.position = pt->posture.position, .hand_site = pt->site,
		.hand_n = pt->site >= 0 ? (float)pt->hand_n : 0,
	};
}

/*
 * Guided replay's patient (guide.h): while the guidance plays, the
 * recording's valves join the handle's this cycle, and each change of
 * its patient (a turn, the assistant's press or release) is carried out
 * as the scenario's are; at the start of play, whatever differs from the
 * patient as it lies. One the patient refuses changes nothing.
 */
static void guide_patient(struct loop *l)
{
	struct guide_patient now, *was = &l->guide_was;
	struct loop_patient_command cmd = { LOOP_PATIENT_RELEASE, 0, 0 };

	l->guide_valves = 0;
	if (!guide_patient_now(&l->guide, &now)) {
		l->guide_playing = false;
		return;
	}
	if (!l->guide_playing) {
		patient_now(l, was);
		l->guide_playing = true;
	}
	l->guide_valves = now.valves;
	if (now.position != was->position) {
		(void)patient_do(l, &(struct loop_patient_command){
			LOOP_PATIENT_TURN, now.position, 0 });
	}
	if (now.hand_site != was->hand_site || now.hand_n != was->hand_n) {
		if (now.hand_site >= 0) {
			cmd = (struct loop_patient_command){
				LOOP_PATIENT_PRESS, now.hand_site, now.hand_n };
		}
		(void)patient_do(l, &cmd);
	}
	*was = now;
}

/* The scope's pose: the paper's kinematics on the centreline, or the rod
 * model's tube as its last step left it. */
static void kinematics(struct loop *l)
{
	const struct scope_input in = {
		.depth_m = l->fb.axis[ENDOSIM_AXIS_INSERTION].position,
		.roll_rad = l->fb.axis[ENDOSIM_AXIS_ROLL].position,
		.wheel_ud_rad = l->fb.axis[ENDOSIM_AXIS_WHEEL_UD].position,
		.wheel_lr_rad = l->fb.axis[ENDOSIM_AXIS_WHEEL_LR].position,
	};
	struct scope_params p;

	if (haptics_rod(l->haptics)) {
		struct haptics_params par;
		double position[ENDOSIM_AXES], velocity[ENDOSIM_AXES];

		cases_haptics_params(&l->cfg, &par);
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			position[a] = l->fb.axis[a].position;
			velocity[a] = l->fb.axis[a].velocity;
		}
		haptics_rod_pose(l->haptics, &par, position, velocity,
				 &l->pose);
		return;
	}
	cases_scope_params(&l->cfg, &p);
	scope_update(&p, colon_centreline(l->colon), &in, &l->pose);
}

static void render(struct loop *l)
{
	struct haptics_params par;
	double position[ENDOSIM_AXES], velocity[ENDOSIM_AXES];
	const struct haptics_input in = {
		.params = &par,
		.colon = l->colon,
		.pose = &l->pose,
		.position = position,
		.velocity = velocity,
		.dt_s = l->info.period_ns * ENDOSIM_S_PER_NS,
		.torque_on = safety_torque_on(&l->safety),
		.applied = l->limited, /* last cycle's, not yet filtered */
		.valves = l->fb.valves | l->guide_valves,
	};

	cases_haptics_params(&l->cfg, &par);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		position[a] = l->fb.axis[a].position;
		velocity[a] = l->fb.axis[a].velocity;
	}
	haptics_render(l->haptics, &in, l->command, &l->state.haptics);
}

static void fill_scope(struct loop *l)
{
	l->state.scope.scene_id = l->scene_id;
	scope_publish(&l->pose, colon_centreline(l->colon), &l->state.scope);
	haptics_publish_rod(l->haptics, l->pose.roll_rad, &l->state.rod,
			    l->state.scope.bow_m);
}

/* The bleeding points' blood this cycle of DT_S into the patient's pools. */
static void pour_blood(struct loop *l, double dt_s)
{
	for (int i = 0; i < l->tool.polyps; i++) {
		const struct tool_polyp *p = &l->tool.polyp[i];

		if (p->bleed_m3_s > 0) {
			patient_bleed(haptics_patient(l->haptics), p->s_m,
				      p->bleed_m3_s * dt_s);
		}
	}
}

/*
 * The tool in the working channel this cycle, on the scope's published
 * state: the rig's sensing; the wall at the tool's tip and the polyps on
 * it where the gas holds it and the scope has bowed it (the surface the
 * scope touches and the picture shows); its injury of the wall the patient's perforation where
 * there is a patient; the cut polyps falling where the patient lies.
 * Then guided replay's expert's tool on the same scope, shown only
 * (guide.h).
 */
static void step_tool(struct loop *l)
{
	const struct endosim_scope_state *sc = &l->state.scope;
	struct tool_params par;
	struct tool_input in = {
		.depth_m = l->fb.tool_depth_m,
		.opening = l->fb.tool_opening,
		.pedal = l->fb.tool_pedal,
		.suction = (l->fb.valves | l->guide_valves) &
			   ENDOSIM_VALVE_SUCTION,
	};
	double dt = l->info.period_ns * ENDOSIM_S_PER_NS;
	double depth = tool_input_depth(&l->tool, &in), g[3];
	const double *factor = patient_factors(haptics_patient(l->haptics));
	struct tool_pose pose;
	unsigned ev;
	int polyp;

	cases_tool_params(&l->cfg, &par);
	tool_pose(&par, sc, depth, &pose);
	tool_follow_wall(&l->tool, l->colon, factor);
	tool_wall(l->colon, sc->tip_s_m + depth, pose.tip, factor, &in);
	ev = tool_step(&l->tool, &par, sc, &in, dt, &polyp);
	if (ev & TOOL_EVENT_INJURY) {
		(void)patient_perforate(haptics_patient(l->haptics),
					sc->tip_s_m);
	}
	patient_loose_gravity(haptics_patient(l->haptics), g);
	tool_fall(&l->tool, &par, l->colon, g, factor, dt);
	pour_blood(l, dt);
	tool_publish(&l->tool, ev, polyp, &l->state.tool);
	guide_publish_tool(&l->guide, &par, sc, &l->tool, &l->state.guide);
}

/* Takes a tool command, if any, applies it and answers it. */
static void take_tool(struct loop *l)
{
	struct tool_post p;

	if (mailbox_box_take(&l->tool_box, &p)) {
		mailbox_answer_set(&l->tool_answer, p.seq,
				   tool_select(&l->tool, p.c.kind,
					       p.c.snare_m));
	}
}

/* Takes a test command, if any (the control thread checked it is allowed). */
static void take_debug(struct loop *l, uint64_t now)
{
	struct loop_debug d;
	int r = 0;

	if (!mailbox_box_take(&l->debug_box, &d)) {
		return;
	}
	if (d.action == INJECT_STALL) {
		l->stall_ns = d.value > 0
				      ? (uint64_t)(d.value * ENDOSIM_NS_PER_S)
				      : 0;
	} else {
		r = inject_start(&l->inject, d.action, d.axis, d.value, now);
	}
	mailbox_answer_set(&l->debug_answer, d.seq, r);
}

/* Takes a guidance command, if any, and answers it. */
static void take_guide(struct loop *l)
{
	struct guide_post g;
	double q[ENDOSIM_AXES];
	int r;

	if (!mailbox_box_take(&l->guide_box, &g)) {
		return;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		q[a] = l->fb.axis[a].position;
	}
	r = guide_command(&l->guide, &l->cfg.guide, &g.c, q);
	mailbox_answer_set(&l->guide_answer, g.seq, r);
}

/* Takes a patient command, if any, applies it and answers it. */
static void take_patient(struct loop *l)
{
	struct patient_post p;

	if (mailbox_box_take(&l->patient_box, &p)) {
		mailbox_answer_set(&l->patient_answer, p.seq,
				   patient_do(l, &p.c));
	}
}

/*
 * The guidance's force, added to the rendered command: only while
 * ENABLED with the enable ramp done (last cycle's), the sum then filtered
 * as any command is. A change of its phase is an event.
 */
static void guide(struct loop *l, uint64_t now)
{
	uint32_t old_phase = l->guide.phase;
	double q[ENDOSIM_AXES], v[ENDOSIM_AXES], f[ENDOSIM_AXES];
	bool enabled = l->safety.state == ENDOSIM_STATE_ENABLED;

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		q[a] = l->fb.axis[a].position;
		v[a] = l->fb.axis[a].velocity;
	}
	guide_step(&l->guide, &l->cfg.guide, enabled,
		   enabled && l->safety.ramp >= 1.0, q, v, l->limited,
		   l->info.period_ns * ENDOSIM_S_PER_NS, f);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		l->command[a] += f[a];
	}
	if (l->guide.phase != old_phase) {
		post(l, &(struct loop_event){
			.stamp_ns = now, .code = LOOP_EV_GUIDE,
			.arg = l->guide.phase, .prev = old_phase,
			.detail = l->guide.ended, .axis = l->guide.lost_axis,
			.value = l->guide.t_s });
	}
	guide_publish(&l->guide, q, &l->state.guide);
}

/* A test command's stall, once this cycle is published. */
static void stall(struct loop *l)
{
	struct timespec ts = to_timespec(l->stall_ns);

	l->stall_ns = 0;
	while (clock_nanosleep(CLOCK_MONOTONIC, 0, &ts, &ts) == EINTR) {
	}
}

/* The loop's own causes: its overruns, a daemon thread that died. */
static void check_loop(struct loop *l, uint64_t now)
{
	uint32_t bits = atomic_load_explicit(&l->fail_bits,
					     memory_order_acquire);

	if (safety_check_overruns(&l->safety, &l->cfg, l->skipped, now)) {
		post(l, &(struct loop_event){ .stamp_ns = now, .axis = -1,
			.code = LOOP_EV_OVER_BUDGET,
			.arg = (uint32_t)l->safety.overrun_window });
	}
	l->skipped = 0;
	if (bits) {
		struct endosim_fault_cause c = {
			.first_ns = now, .axis = -1,
			.detail = atomic_load(&l->fail_detail),
		};

		safety_fault(&l->safety, bits, &c);
	}
}

/* A non-finite value in the scope's pose, the haptic parts or the
 * patient's body (the gas, the fluid, the lens: the rendering's) is a
 * fault. */
static void check_pipeline(struct loop *l, uint64_t now)
{
	const struct scope_pose *p = &l->pose;
	const struct endosim_haptics_state *h = &l->state.haptics;
	double body[PATIENT_WATCHED];
	const double pose[] = {
		p->depth_m, p->roll_rad, p->bend_rad[0], p->bend_rad[1],
		p->base_s_m, p->tip_s_m, p->tip[0], p->tip[1], p->tip[2],
		p->dir[0], p->dir[1], p->dir[2], p->up[0], p->up[1], p->up[2],
	};
	const double parts[] = {
		h->proxy[0], h->proxy[1], h->proxy[2], h->f_static[0],
		h->f_static[1], h->f_static[2], h->penetration_m,
		h->curvature_rad, h->trans_contact_n, h->trans_friction_n,
		h->trans_loop_n, h->wheel_contact_nm[0], h->wheel_contact_nm[1],
		h->wheel_tension_nm[0], h->wheel_tension_nm[1],
		h->wheel_elastic_nm[0], h->wheel_elastic_nm[1],
		h->tube_contact_nm, h->tube_friction_nm, h->passivity_energy_j,
		h->passivity_damping,
	};

	safety_check_finite(&l->safety, pose, sizeof(pose) / sizeof(pose[0]),
			    -1, ENDOSIM_STAGE_KINEMATICS, now);
	safety_check_finite(&l->safety, parts, sizeof(parts) / sizeof(parts[0]),
			    -1, ENDOSIM_STAGE_HAPTICS, now);
	patient_watched(haptics_patient(l->haptics), body);
	safety_check_finite(&l->safety, body, PATIENT_WATCHED, -1,
			    ENDOSIM_STAGE_HAPTICS, now);
}

static void cycle(struct loop *l, uint64_t now, uint64_t latency)
{
	uint32_t old_state = l->safety.state;
	uint32_t old_faults = l->safety.faults;
	uint32_t cmd;

	fetch_config(l);
	cmd = take_command(l, now);
	take_debug(l, now);
	take_guide(l);
	take_colon(l);
	take_patient(l);
	take_tool(l);
	safety_begin_cycle(&l->safety);
	check_loop(l, now);
	rig_read(l->rig, now, &l->fb);
	inject_feedback(&l->inject, &l->fb);
	safety_check_feedback(&l->safety, &l->cfg, &l->fb, now);
	safety_check_motion(&l->safety, &l->cfg, &l->fb, now);
	kinematics(l);
	scenario_patient(l);
	guide_patient(l);
	render(l);
	guide(l, now);
	inject_pipeline(&l->inject, &l->pose, &l->state.haptics, l->command);
	check_pipeline(l, now);
	safety_filter(&l->safety, &l->cfg, l->command, l->limited,
		      l->info.period_ns * ENDOSIM_S_PER_NS, now);
	rig_write(l->rig, now, l->limited, safety_torque_on(&l->safety));

	post_changes(l, old_state, old_faults, cmd, now);
	if (l->fb.hand_done && !l->scenario_was_done) {
		struct loop_event ev = { .stamp_ns = now,
					 .code = LOOP_EV_SCENARIO_END,
					 .axis = -1 };
		post(l, &ev);
	}
	l->scenario_was_done = l->fb.hand_done;
	fill_state(l, now, latency);
	fill_scope(l);
	step_tool(l); /* on the scope's state; its injury tears the patient */
	patient_publish(haptics_patient(l->haptics), &l->state.patient);
	l->state.publish_ns = l->lockstep ? now : mono_ns();
	if (l->pub) {
		publish_state(l->pub, &l->state);
	}
	if (l->tap) {
		session_tap_push(l->tap, &l->state);
	}
}

/* Skips whole periods after an overrun; returns how many. */
static uint64_t skip_overrun(uint64_t *next, uint64_t now, uint64_t period)
{
	uint64_t skipped;

	if (now < *next + period) {
		return 0;
	}
	skipped = (now - *next) / period;
	*next += skipped * period;
	return skipped;
}

/* After a cycle: its compute time (ns) in the histogram, the heartbeat. */
static void count_cycle(struct loop *l, uint64_t compute)
{
	histo_add(&l->compute, compute);
	l->state.compute_ns = (uint32_t)(compute < UINT32_MAX ? compute :
								UINT32_MAX);
	atomic_fetch_add_explicit(&l->heartbeat, 1, memory_order_release);
}

static void *loop_main(void *arg)
{
	struct loop *l = arg;
	uint64_t period = l->info.period_ns;
	uint64_t next, now, skipped;
	struct timespec ts;

	rt_prefault_stack();
	next = mono_ns();
	while (!atomic_load_explicit(&l->stop, memory_order_acquire)) {
		next += period;
		ts = to_timespec(next);
		while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts,
				       NULL) == EINTR) {
		}
		now = mono_ns();
		uint64_t latency = now > next ? now - next : 0;

		skipped = skip_overrun(&next, now, period);
		l->skipped = skipped;
		if (skipped) {
			struct loop_event ev = { .stamp_ns = now,
						 .code = LOOP_EV_OVERRUN,
						 .arg = (uint32_t)skipped,
						 .axis = -1 };
			atomic_fetch_add_explicit(&l->overruns, skipped,
						  memory_order_relaxed);
			post(l, &ev);
		}
		histo_add(&l->latency, latency);
		cycle(l, now, latency);
		count_cycle(l, mono_ns() - now);
		if (l->stall_ns) {
			stall(l);
		}
	}
	/* last act: nothing energised */
	memset(l->limited, 0, sizeof(l->limited));
	rig_write(l->rig, mono_ns(), l->limited, false);
	return NULL;
}

/* --- setup, from the main thread --- */

/*
 * Holds the PM QoS request cyclictest makes: while the file stays open the
 * CPUs do not enter idle states slower to leave than the value.
 */
static void hold_cpu_latency(struct loop *l)
{
	int32_t us = l->cfg.loop.cpu_dma_latency_us;
	int fd;

	if (us < 0) {
		return;
	}
	fd = open("/dev/cpu_dma_latency", O_WRONLY | O_CLOEXEC);
	if (fd < 0 || write(fd, &us, sizeof(us)) != sizeof(us)) {
		log_warn("cannot hold /dev/cpu_dma_latency at %d us: %m; deep "
			 "CPU idle states may delay the force loop", (int)us);
		if (fd >= 0) {
			close(fd);
		}
		return;
	}
	l->pm_qos_fd = fd;
}

void loop_set_tap(struct loop *l, struct session_tap *tap)
{
	l->tap = tap;
}

int loop_start(struct loop *l)
{
	struct rt_thread_params p = {
		.name = "endosim-loop",
		.priority = l->cfg.loop.priority,
		.cpu = l->cfg.loop.cpu,
		.stack_bytes = LOOP_STACK_BYTES,
	};
	bool fifo;
	int r;

	l->info.memory_locked = rt_lock_memory();
	hold_cpu_latency(l);
	r = rt_thread_start(&l->thread, &p, loop_main, l, &fifo);
	if (r) {
		log_err("force loop: cannot start thread: %s", strerror(-r));
		return r;
	}
	if (!fifo) {
		log_warn("force loop: no permission for SCHED_FIFO priority %d "
			 "(needs root or CAP_SYS_NICE with LimitRTPRIO); "
			 "running as SCHED_OTHER without latency guarantees",
			 l->cfg.loop.priority);
	}
	l->running = true;
	l->info.policy = fifo ? "SCHED_FIFO" : "SCHED_OTHER";
	l->info.priority = fifo ? l->cfg.loop.priority : 0;
	log_info("force loop: %d Hz, %s priority %d, memory %slocked%s%s",
		 l->cfg.loop.rate_hz, l->info.policy, l->info.priority,
		 l->info.memory_locked ? "" : "not ",
		 l->cfg.loop.cpu >= 0 ? ", pinned" : "",
		 l->pm_qos_fd >= 0 ? ", CPU idle latency held" : "");
	return 0;
}

void loop_stop(struct loop *l)
{
	if (!l->running) {
		return;
	}
	atomic_store_explicit(&l->stop, true, memory_order_release);
	pthread_join(l->thread, NULL);
	l->running = false;
	rig_stop(l->rig);
}

void loop_destroy(struct loop *l)
{
	if (!l) {
		return;
	}
	loop_stop(l);
	colon_destroy(l->colon);
	haptics_destroy(l->haptics);
	if (l->pm_qos_fd >= 0) {
		close(l->pm_qos_fd);
	}
	spsc_free(&l->events);
	free(l);
}

int loop_command(struct loop *l, enum loop_cmd cmd, int timeout_ms)
{
	return mailbox_slot_wait(&l->cmd, mailbox_slot_post(&l->cmd, cmd),
				 timeout_ms);
}

const struct colon *loop_colon(const struct loop *l)
{
	return l->colon;
}

void loop_hold_tip(struct loop *l, double hold_n_per_m)
{
	haptics_hold_tip(l->haptics, hold_n_per_m);
}

struct patient *loop_patient(struct loop *l)
{
	return haptics_patient(l->haptics);
}

struct tool *loop_tool(struct loop *l)
{
	return &l->tool;
}

int loop_swap_colon(struct loop *l, struct colon *colon, uint64_t scene_id,
		    struct colon **old, int timeout_ms)
{
	void *back;
	int r;

	l->scene_id_in = scene_id;
	tool_reset(&l->tool_in);
	(void)tool_place_polyps(&l->tool_in, colon);
	r = mailbox_swap_hand(&l->colon_swap, colon, &back, timeout_ms);
	if (r) {
		return r;
	}
	if (back == colon) {
		return -EBUSY;
	}
	*old = back;
	return 0;
}

void loop_set_config(struct loop *l, const struct config *cfg)
{
	mailbox_box_put(&l->cfg_box, cfg);
}

int loop_debug(struct loop *l, int action, int axis, double value,
	       int timeout_ms)
{
	struct loop_debug d = { mailbox_answer_next(&l->debug_answer), action,
				axis, value };

	mailbox_box_put(&l->debug_box, &d);
	return mailbox_answer_wait(&l->debug_answer, d.seq, timeout_ms);
}

/* Leaves C in the guidance's box; returns its sequence number. */
static uint32_t post_guide(struct loop *l, const struct guide_command *c)
{
	struct guide_post g = { *c, mailbox_answer_next(&l->guide_answer) };

	mailbox_box_put(&l->guide_box, &g);
	return g.seq;
}

int loop_guide(struct loop *l, const struct guide_command *c, int timeout_ms)
{
	return mailbox_answer_wait(&l->guide_answer, post_guide(l, c),
				   timeout_ms);
}

/* Leaves C in the patient's box; returns its sequence number. */
static uint32_t post_patient(struct loop *l,
			     const struct loop_patient_command *c)
{
	struct patient_post p = { *c, mailbox_answer_next(&l->patient_answer) };

	mailbox_box_put(&l->patient_box, &p);
	return p.seq;
}

int loop_patient_command(struct loop *l, const struct loop_patient_command *c,
			 int timeout_ms)
{
	return mailbox_answer_wait(&l->patient_answer, post_patient(l, c),
				   timeout_ms);
}

/* Leaves C in the tool's box; returns its sequence number. */
static uint32_t post_tool(struct loop *l, const struct loop_tool_command *c)
{
	struct tool_post p = { *c, mailbox_answer_next(&l->tool_answer) };

	mailbox_box_put(&l->tool_box, &p);
	return p.seq;
}

int loop_tool_command(struct loop *l, const struct loop_tool_command *c,
		      int timeout_ms)
{
	return mailbox_answer_wait(&l->tool_answer, post_tool(l, c),
				   timeout_ms);
}

void loop_fail(struct loop *l, uint32_t bit, uint32_t detail)
{
	atomic_store(&l->fail_detail, detail);
	atomic_fetch_or_explicit(&l->fail_bits, bit, memory_order_release);
}

bool loop_pop_event(struct loop *l, struct loop_event *ev)
{
	return spsc_pop(&l->events, ev);
}

uint64_t loop_heartbeat(const struct loop *l)
{
	return atomic_load_explicit(&l->heartbeat, memory_order_acquire);
}

void loop_get_stats(const struct loop *l, struct loop_stats *st)
{
	st->cycles = loop_heartbeat(l);
	st->overruns = atomic_load_explicit(&l->overruns, memory_order_relaxed);
	histo_summarize(&l->latency, &st->latency);
	histo_summarize(&l->compute, &st->compute);
}

const struct loop_info *loop_get_info(const struct loop *l)
{
	return &l->info;
}

/* --- lockstep --- */

void loop_step(struct loop *l, uint64_t now_ns)
{
	uint64_t t0 = mono_ns();

	l->lockstep = true;
	l->skipped = 0;
	cycle(l, now_ns, 0);
	count_cycle(l, mono_ns() - t0);
}

void loop_post(struct loop *l, enum loop_cmd cmd)
{
	(void)mailbox_slot_post(&l->cmd, cmd);
}

void loop_guide_post(struct loop *l, const struct guide_command *c)
{
	(void)post_guide(l, c);
}

int loop_guide_answer(const struct loop *l)
{
	return mailbox_answer_last(&l->guide_answer);
}

void loop_patient_post(struct loop *l, const struct loop_patient_command *c)
{
	(void)post_patient(l, c);
}

int loop_patient_answer(const struct loop *l)
{
	return mailbox_answer_last(&l->patient_answer);
}

void loop_tool_post(struct loop *l, const struct loop_tool_command *c)
{
	(void)post_tool(l, c);
}

int loop_tool_answer(const struct loop *l)
{
	return mailbox_answer_last(&l->tool_answer);
}

const struct endosim_state *loop_state(const struct loop *l)
{
	return &l->state;
}
