/*
 * loop.h - the force loop: a dedicated real-time thread that, every period,
 * reads the rig, renders forces, applies the safety filter, writes the
 * setpoints and publishes the state.
 *
 * Real time after cyclictest: SCHED_FIFO at [loop] priority when permitted
 * (root, or CAP_SYS_NICE with an RLIMIT_RTPRIO that allows it; otherwise one
 * warning and SCHED_OTHER), memory locked when permitted, a prefaulted stack,
 * everything allocated before the thread starts, absolute-time
 * clock_nanosleep on CLOCK_MONOTONIC; after an overrun whole periods are
 * skipped and counted. Inside the loop: no allocation, no stdio or syslog,
 * no blocking lock, no bus I/O.
 *
 * Every cycle it also works out the endoscope's kinematics (scope.h) on
 * the colon model it owns and publishes them (endosim_shm.h, scope).
 *
 * Talking to the loop, lock-free (mailbox.h):
 *  - commands (enable, disable, estop, reset): loop_command(), the control
 *    thread only, one at a time, answered within a cycle or two;
 *  - live configuration: loop_set_config(), the control thread only;
 *  - a new colon model: loop_swap_colon(), the control thread only;
 *  - events out (state changes, faults, overruns): loop_pop_event(), the main
 *    thread only, which logs them;
 *  - a fault from outside (a daemon thread died): loop_fail(), the main
 *    thread;
 *  - test commands (inject.h): loop_debug(), the control thread only;
 *  - the patient's commands (patient.h: a turn, the hand):
 *    loop_patient_command(), the control thread only;
 *  - the tool in the working channel (tool.h): the one selected,
 *    loop_tool_command(), the control thread only; the case's polyps are
 *    placed for it off the loop, by loop_create() and loop_swap_colon()
 *    (published by the swap's hand-over), and it is stepped each cycle
 *    after the scope's state is filled, on the rig's sensing (rig.h:
 *    a stale reading holds the tool still, the pedal up); its injury of
 *    the wall is the patient's perforation (patient_perforate()) where
 *    there is a patient;
 *  - records out to the recorder (recorder.h) while a session records:
 *    loop_set_tap() before the loop starts;
 *  - a scenario's commands for the assistant (scenario.h: turn, press,
 *    release) come with the rig's feedback (rig.h, .patient: the simulated
 *    hand hands out one new number a cycle at most), and the loop carries
 *    each number out once, before the patient's step of that cycle
 *    (patient_turn(), patient_press() at the case's site of that name,
 *    patient_release()); the scenario's valves come as the handle's
 *    (.valves). The daemon and the lockstep tools take the same path;
 *  - guided replay's patient (guide.h): while the guidance plays, the
 *    recording's valves are pressed with the handle's (an OR), and each
 *    change of its patient (a turn, the hand's press or release) carried
 *    out the same way, before the patient's step;
 *  - statistics and heartbeat: any thread.
 */
#ifndef ENDOSIM_LOOP_H
#define ENDOSIM_LOOP_H

#include <stdbool.h>
#include <stdint.h>

#include "model/colon.h"
#include "conf/config.h"
#include "rig/guide.h"
#include "base/histo.h"
#include "loop/publish.h"
#include "loop/sessiontap.h"
#include "rig/rig.h"
#include "loop/safety.h"

enum loop_event_code {
	LOOP_EV_STATE = 1,    /* arg: new state, prev: old state, cmd */
	LOOP_EV_FAULT,        /* arg: a new fault bit, its axis and detail */
	LOOP_EV_OVERRUN,      /* arg: periods skipped */
	LOOP_EV_SCENARIO_END, /* the scripted hand's scenario ended */
	LOOP_EV_OVER_BUDGET,  /* arg: periods skipped within the window, over
				 the budget: a warning (safety.h) */
	LOOP_EV_GUIDE,        /* arg: the guidance's new phase, prev: its old
				 one, detail: why it ended, axis: the one
				 that could not follow, value: the playhead
				 (enum endosim_guide_phase, _end) */
};

/* Commands for loop_command(): the safety commands, and one of the loop's. */
enum loop_cmd {
	LOOP_CMD_ENABLE = SAFETY_ENABLE,
	LOOP_CMD_DISABLE = SAFETY_DISABLE,
	LOOP_CMD_ESTOP = SAFETY_ESTOP,
	LOOP_CMD_RESET = SAFETY_RESET,
	LOOP_CMD_RESET_STATS = 16, /* zero the latency/compute histograms */
};

struct loop_event {
	uint64_t stamp_ns; /* CLOCK_MONOTONIC */
	uint32_t code;     /* enum loop_event_code */
	uint32_t arg;
	uint32_t prev;
	uint32_t cmd;      /* enum loop_cmd that caused it, 0: none */
	int32_t axis;      /* -1: none or global */
	uint32_t detail;
	double value;      /* a fault's: what tripped it (endosim_shm.h) */
	double limit;
};

/* A test command for the loop (inject.h). */
struct loop_debug {
	uint32_t seq;
	int action;        /* enum inject_action */
	int axis;          /* -1: every axis */
	double value;
};

/* What the patient's mailbox carries (patient.h). */
enum loop_patient_op {
	LOOP_PATIENT_TURN = 1,    /* to position ARG (enum endosim_position) */
	LOOP_PATIENT_PRESS = 2,   /* at site ARG (the case's) with FORCE_N */
	LOOP_PATIENT_RELEASE = 3, /* the hand lets go */
	LOOP_PATIENT_SEDATE = 4,  /* to ARG (enum endosim_sedation) */
};

struct loop_patient_command {
	int op;            /* enum loop_patient_op */
	int arg;
	double force_n;    /* PRESS: N, <= 0: [patient] hand_n */
};

/* What the tool's mailbox carries (tool.h): the tool the nurse hands
 * over. */
struct loop_tool_command {
	int kind;          /* enum tool_kind */
	double snare_m;    /* a snare's size, TOOL_SNARE_MIN_M..MAX_M */
};

struct loop_info {
	const char *policy;  /* "SCHED_FIFO" or "SCHED_OTHER" */
	int priority;        /* 0 under SCHED_OTHER */
	bool memory_locked;
	uint32_t period_ns;
};

struct loop_stats {
	uint64_t cycles;
	uint64_t overruns;
	struct histo_summary latency; /* wake-up latency */
	struct histo_summary compute; /* wake-up to publish */
};

struct loop;

/*
 * Allocates everything the loop will use. The loop owns COLON (built
 * before, never NULL), known to clients as SCENE_ID, and frees it in
 * loop_destroy(). PUB may be NULL (lockstep: nothing published). NULL on
 * ENOMEM (logged).
 */
struct loop *loop_create(const struct config *cfg, struct rig *rig,
			 struct publish *pub, struct colon *colon,
			 uint64_t scene_id);

/*
 * Main thread, before loop_start(): after publishing each cycle the loop
 * hands its state to TAP (session_tap_push()). NULL: no recorder.
 */
void loop_set_tap(struct loop *l, struct session_tap *tap);

/* Locks memory and starts the thread. Returns 0 or a negative errno. */
int loop_start(struct loop *l);

/*
 * Stops the thread (its last act: zero setpoints, drives disabled) and
 * joins it, then brings the rig down. Idempotent.
 */
void loop_stop(struct loop *l);

/* NULL is fine; stops first. */
void loop_destroy(struct loop *l);

/*
 * Control thread: carries out CMD in the loop and waits up to TIMEOUT_MS.
 * Returns 0, what safety_command() refused with (-EPERM, -EBUSY), or
 * -ETIMEDOUT when the loop did not take it (it is then withdrawn, never
 * applied).
 */
int loop_command(struct loop *l, enum loop_cmd cmd, int timeout_ms);

/* Control thread: the loop uses CFG's live keys from its next cycle on. */
void loop_set_config(struct loop *l, const struct config *cfg);

/*
 * Control thread, loop running: hands COLON (SCENE_ID) to the loop, which
 * takes it at the start of its next cycle if the state is IDLE. Waits up
 * to TIMEOUT_MS (the loop never waits). Returns 0 with *OLD the colon it
 * replaced (now the caller's to free); -EBUSY when not IDLE (COLON is the
 * caller's again); -ETIMEDOUT when the loop did not take it (withdrawn,
 * the caller's again). The loop only reads its colon's mesh, never writes
 * it, so the caller may keep reading the mesh of the colon it handed over
 * until it swaps it out.
 */
int loop_swap_colon(struct loop *l, struct colon *colon, uint64_t scene_id,
		    struct colon **old, int timeout_ms);

/*
 * Control thread, only when [debug] test_commands allows it: hands the
 * loop one injection (enum inject_action; INJECT_STALL sleeps the loop
 * VALUE s after answering) and waits up to TIMEOUT_MS for its answer.
 * Returns 0, -EINVAL (inject_start() refused it) or -ETIMEDOUT.
 */
int loop_debug(struct loop *l, int action, int axis, double value,
	       int timeout_ms);

/*
 * Control thread: hands the loop a guidance command (guide.h) and waits up
 * to TIMEOUT_MS for its answer: 0, -EINVAL (guide_command() refused it) or
 * -ETIMEDOUT (no answer yet: the loop may still take it). A GUIDE_START's
 * path is the loop's from the post on (unless answered -EINVAL) until a
 * later start is answered 0: only then may the caller free it.
 */
int loop_guide(struct loop *l, const struct guide_command *c, int timeout_ms);

/*
 * Control thread: hands the loop a patient command and waits up to
 * TIMEOUT_MS for its answer: 0, -EINVAL (patient_turn() or
 * patient_press() refused it: no such position or site, a force above
 * hand_max_n, the patient disabled; nothing changed) or -ETIMEDOUT (no
 * answer yet: the loop may still take it).
 */
int loop_patient_command(struct loop *l, const struct loop_patient_command *c,
			 int timeout_ms);

/*
 * Control thread: hands the loop a tool (tool_select()) and waits up to
 * TIMEOUT_MS for its answer: 0, -EINVAL (no such tool, a snare's size
 * out of range; nothing changed) or -ETIMEDOUT (no answer yet: the loop
 * may still take it).
 */
int loop_tool_command(struct loop *l, const struct loop_tool_command *c,
		      int timeout_ms);

/*
 * Main thread: latches fault BIT (ENDOSIM_FAULT_INTERNAL: a daemon thread
 * died) with DETAIL from the next cycle on, for good: torque off.
 */
void loop_fail(struct loop *l, uint32_t bit, uint32_t detail);

/* Main thread: the next event, false when there is none. */
bool loop_pop_event(struct loop *l, struct loop_event *ev);

/* Any thread: cycles completed so far (the watchdog's heartbeat). */
uint64_t loop_heartbeat(const struct loop *l);

/* Any thread. */
void loop_get_stats(const struct loop *l, struct loop_stats *st);
const struct loop_info *loop_get_info(const struct loop *l);

/*
 * Lockstep: the force loop without its thread, on simulated time, for the
 * tools and tests that need its behaviour cycle for cycle whatever the
 * machine does (tests/tools/offline.h). Never together with loop_start().
 *
 * loop_step() runs one cycle, exactly as the thread does, at NOW_NS (the
 * caller's clock: a period after the last call's), with no period
 * skipped; the state it fills is stamped and published at NOW_NS. Same
 * inputs, same outputs, bit for bit. loop_post() leaves CMD for the next
 * cycle without waiting for the answer; loop_state() is the state the last
 * cycle filled.
 */
void loop_step(struct loop *l, uint64_t now_ns);

/* In lockstep (never while the loop's thread runs): the colon the loop
 * renders on, for the tools and tests that look inside it. */
const struct colon *loop_colon(const struct loop *l);

/* In lockstep: the rod model's tip held where it is by a spring of
 * HOLD_N_PER_M, or let go (0) (haptics_hold_tip()), for the clinic's
 * tests. */
void loop_hold_tip(struct loop *l, double hold_n_per_m);

/* In lockstep: the patient's body (patient.h), for the tools and tests
 * that turn the patient, press the abdomen or look inside; the daemon's
 * control thread goes through the loop's patient mailbox instead. */
struct patient *loop_patient(struct loop *l);
/* In lockstep: the tool in the working channel (tool.h), for the tests
 * that look inside it or place a polyp where the scope is. */
struct tool *loop_tool(struct loop *l);
void loop_post(struct loop *l, enum loop_cmd cmd);
/* In lockstep: a guidance command for the next cycle; its answer is
 * loop_guide_answer()'s after that cycle (-EINPROGRESS before). */
void loop_guide_post(struct loop *l, const struct guide_command *c);
int loop_guide_answer(const struct loop *l);
/* In lockstep: a patient command for the next cycle, through the
 * mailbox the daemon uses; its answer is loop_patient_answer()'s after
 * that cycle (-EINPROGRESS before). */
void loop_patient_post(struct loop *l, const struct loop_patient_command *c);
int loop_patient_answer(const struct loop *l);
/* In lockstep: a tool for the next cycle, through the daemon's mailbox;
 * its answer is loop_tool_answer()'s after that cycle. */
void loop_tool_post(struct loop *l, const struct loop_tool_command *c);
int loop_tool_answer(const struct loop *l);
const struct endosim_state *loop_state(const struct loop *l);

#endif
