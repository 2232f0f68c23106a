/*
 * safety.h - the daemon's state machine and the last word on every force.
 *
 *   IDLE --enable--> ENABLED --disable--> IDLE
 *   any  --estop---> ESTOP (latched)     --reset--> IDLE
 *   any  --fault---> FAULT (latched)     --reset--> IDLE, once the cause is gone
 *
 * Torque is allowed only in ENABLED. The safety filter clamps each axis'
 * command to its configured limit and zeroes it in every other state; a
 * non-finite command is itself a fault. Faults latch their bit with the
 * axis, the backend's detail code and the time of the first one.
 *
 * Owned by the force loop: every function here is pure computation on the
 * loop's own struct (no locks, no allocation, no I/O).
 */
#ifndef ENDOSIM_SAFETY_H
#define ENDOSIM_SAFETY_H

#include <stdbool.h>
#include <stdint.h>

#include "config.h"
#include "rig.h"

enum safety_cmd {
	SAFETY_ENABLE = 1,
	SAFETY_DISABLE,
	SAFETY_ESTOP,
	SAFETY_RESET,
};

/* One cause per possible fault bit. */
#define SAFETY_CAUSES 32

/* Where a fault bit was first seen since the last reset. */
struct safety_cause {
	int axis;              /* -1: none or global */
	uint32_t detail;       /* the backend's code */
};

struct safety {
	uint32_t state;        /* enum endosim_state_id */
	uint32_t faults;       /* latched enum endosim_fault bits */
	uint32_t active;       /* causes seen in the last checked cycle */
	uint32_t seen;         /* causes seen so far in this cycle */
	uint32_t fault_bit;    /* first fault's bit */
	int fault_axis;        /* first fault's axis, -1: none or global */
	uint32_t fault_detail; /* first fault's backend code */
	uint64_t fault_ns;     /* first fault's time */
	struct safety_cause cause[SAFETY_CAUSES]; /* by bit number */
};

void safety_init(struct safety *s);

/*
 * Applies an operator's command. Returns 0, -EPERM (enable while in FAULT
 * or ESTOP) or -EBUSY (reset while a fault's cause is still present).
 */
int safety_command(struct safety *s, enum safety_cmd cmd);

/* Starts a cycle's checks: the causes seen last cycle become `active`. */
void safety_begin_cycle(struct safety *s);

/* A fault cause seen now: latches FAULT. AXIS -1 for a global cause. */
void safety_fault(struct safety *s, uint32_t bit, int axis, uint32_t detail,
		  uint64_t now_ns);

/*
 * Checks feedback: present, not faulted, no failed transaction, fresh (the
 * axis' bus' feedback_max_age_s), finite.
 */
void safety_check_feedback(struct safety *s, const struct config *cfg,
			   const struct rig_feedback *fb, uint64_t now_ns);

/* True when the drives may produce torque. */
bool safety_torque_on(const struct safety *s);

/*
 * LIMITED[a] = COMMAND[a] clamped to +-cfg->limits.max[a] and, from the
 * previous LIMITED[a], to cfg->limits.slew[a] per period DT_S; or 0 when
 * torque is off (at once, not slewed). A non-finite command faults and
 * gives 0 on every axis.
 */
void safety_filter(struct safety *s, const struct config *cfg,
		   const double command[ENDOSIM_AXES],
		   double limited[ENDOSIM_AXES], double dt_s, uint64_t now_ns);

#endif
