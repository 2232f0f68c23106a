/*
 * safety.h - the daemon's state machine, its fault monitors and the last
 * word on every force.
 *
 *   IDLE --enable--> ENABLED --disable--> IDLE
 *   any  --estop---> ESTOP (latched)     --reset--> IDLE
 *   any  --fault---> FAULT (latched)     --reset--> IDLE, once the cause is gone
 *
 * Torque is allowed only in ENABLED. The safety filter scales each axis'
 * command by the enable ramp (0 to 1 over [limits] enable_ramp_s after
 * each enable), clamps it to the axis' force limit and zeroes it in every
 * other state, in the cycle that latched a fault included.
 *
 * Fault causes (enum endosim_fault), each checked every cycle by one of
 * the functions below: the rig's feedback (a drive gone, faulted, a failed
 * transaction, stale, non-finite); the motion (position outside the travel
 * by more than [limits] travel_margin_fraction of it, speed above the
 * axis' [limits] max speed); the force loop's overruns (more than [loop]
 * overrun_budget periods skipped within overrun_window_s, when [loop]
 * overrun_fault makes that a fault, see safety_check_overruns); the force
 * pipeline (a non-finite value anywhere: pose, haptic parts and the
 * patient's body, command, output); the command held beyond the force
 * limit for longer than [limits] saturation_s while torque is on; a
 * daemon thread that died.
 * A cause latches its bit with where and when it was first seen and what
 * tripped it (endosim_shm.h struct endosim_fault_cause); reset is refused
 * while any cause is still present. The emergency stop latches its bit
 * too, in state ESTOP.
 *
 * Owned by the force loop: every function here is pure computation on the
 * loop's own struct (no locks, no allocation, no I/O).
 */
#ifndef ENDOSIM_SAFETY_H
#define ENDOSIM_SAFETY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "conf/config.h"
#include "rig/rig.h"

enum safety_cmd {
	SAFETY_ENABLE = 1,
	SAFETY_DISABLE,
	SAFETY_ESTOP,
	SAFETY_RESET,
};

/* The ring of overruns holds one more than the largest budget. */
#define SAFETY_OVERRUN_MAX CONFIG_OVERRUN_BUDGET_MAX

struct safety {
	uint32_t state;        /* enum endosim_state_id */
	uint32_t faults;       /* latched enum endosim_fault bits */
	uint32_t active;       /* causes seen in the last checked cycle */
	uint32_t seen;         /* causes seen so far in this cycle */
	uint32_t fault_bit;    /* the first latched bit since reset, 0: none */
	uint64_t latched;      /* causes latched since start */
	struct endosim_fault_cause cause[ENDOSIM_FAULT_BITS]; /* by bit number */
	/* the monitors */
	bool torque_was_on;
	uint64_t enabled_ns;   /* start of the enable ramp */
	double ramp;           /* 0..1 this cycle */
	uint64_t saturated_since[ENDOSIM_AXES]; /* 0: not saturated */
	bool saturation_warning;  /* an axis past saturation_s that only
				     warns ([limits] saturation_fault) */
	double speed[ENDOSIM_AXES]; /* m/s, rad/s: the last checked motion */
	struct {
		uint64_t ns;   /* when */
		uint64_t n;    /* periods skipped then */
	} overrun[SAFETY_OVERRUN_MAX + 1]; /* the newest overruns, a ring */
	uint32_t overrun_next; /* next slot of the ring */
	uint32_t overrun_size; /* the ring's length: budget + 1 */
	uint64_t overrun_window; /* periods skipped within the window */
	uint64_t overrun_misses; /* times the window went over the budget */
	bool overrun_warning;  /* over the budget now, and only a warning */
};

/* The speed fade: shares of [limits] *_max_speed_* (see safety_filter). */
#define SAFETY_FADE_START 0.5
#define SAFETY_FADE_END 0.8

void safety_init(struct safety *s);

/*
 * Applies an operator's command at NOW_NS. Returns 0, -EPERM (enable while
 * in FAULT or ESTOP) or -EBUSY (reset while a fault's cause is present).
 */
int safety_command(struct safety *s, enum safety_cmd cmd, uint64_t now_ns);

/* Starts a cycle's checks: the causes seen last cycle become `active`. */
void safety_begin_cycle(struct safety *s);

/*
 * A fault cause seen now: latches BIT (its first sighting since reset keeps
 * C, whose first_ns is the time) and FAULT.
 */
void safety_fault(struct safety *s, uint32_t bit,
		  const struct endosim_fault_cause *c);

/* The cause of the first fault since reset, or NULL. */
const struct endosim_fault_cause *safety_first(const struct safety *s);

/*
 * Checks feedback: present, not faulted, no failed transaction, fresh (the
 * axis' bus' feedback_max_age_s), finite (position, speed, hand).
 */
void safety_check_feedback(struct safety *s, const struct config *cfg,
			   const struct rig_feedback *fb, uint64_t now_ns);

/* Checks the motion: each axis inside its travel and below its speed. */
void safety_check_motion(struct safety *s, const struct config *cfg,
			 const struct rig_feedback *fb, uint64_t now_ns);

/*
 * Counts SKIPPED periods at NOW_NS (0 too: the window moves on) against
 * [loop] overrun_budget within overrun_window_s. Over the budget is a miss,
 * counted once each time the window goes over it (overrun_misses). Where
 * config_overrun_faults() says so (a real drive, or [loop] overrun_fault =
 * yes) a miss latches ENDOSIM_FAULT_OVERRUN; otherwise (the simulated rig)
 * it is a warning: torque stays on, the cause is published as present
 * (endosim_safety_state.active) while the window is over the budget, and
 * it does not hold up a reset. Returns true in the cycle a warning begins,
 * for the caller to log it; false otherwise (a fault logs itself).
 */
bool safety_check_overruns(struct safety *s, const struct config *cfg,
			   uint64_t skipped, uint64_t now_ns);

/* N values at STAGE (enum endosim_stage) for AXIS (-1: none) are finite. */
void safety_check_finite(struct safety *s, const double *v, size_t n,
			 int axis, uint32_t stage, uint64_t now_ns);

/* True when the drives may produce torque. */
bool safety_torque_on(const struct safety *s);

/*
 * LIMITED[a] = COMMAND[a] times the enable ramp, clamped to
 * +-cfg->limits.max[a], faded out when it would drive the axis faster
 * (in the direction it moves: from SAFETY_FADE_START to SAFETY_FADE_END of
 * [limits] max speed, as last seen by safety_check_motion(), so that the
 * rig's own torque never makes a runaway of an axis a hand let go) and,
 * from the previous LIMITED[a], to
 * cfg->limits.slew[a] per period DT_S; or 0 when torque is off (at once,
 * not slewed). A non-finite command faults and gives 0 on every axis; so
 * does a command held beyond the limit for longer than [limits]
 * saturation_s.
 */
void safety_filter(struct safety *s, const struct config *cfg,
		   const double command[ENDOSIM_AXES],
		   double limited[ENDOSIM_AXES], double dt_s, uint64_t now_ns);

/*
 * What the monitors publish (endosim_shm.h), into OUT: `active` holds the
 * causes present this cycle, a missed overrun budget that only warns
 * included (it is then not in the latched fault bits).
 */
void safety_publish(const struct safety *s, uint64_t now_ns,
		    struct endosim_safety_state *out);

#endif
