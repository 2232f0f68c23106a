/*
 * inject.h - test-only sabotage of the force loop, for the fault-injection
 * tests (tests/system/4N-*.sh): `endoctl debug ...`, which the control
 * thread refuses unless [debug] test_commands = yes.
 *
 * Each injection acts on one axis (or every axis) at the stage where a real
 * failure would show: the rig's feedback (a drive that faults, vanishes,
 * stops being renewed, reports a failed transaction, a speed or a position
 * read wrong, a NaN), the force pipeline (a NaN in the scope's pose, in the
 * haptic parts or in the command; a constant command, to saturate). It
 * holds until cleared, so a test can show that reset is refused while the
 * cause persists. Stalling the loop and ending the control thread are
 * carried out by the loop and the control thread themselves.
 *
 * The force loop owns struct inject: pure computation, no allocation.
 */
#ifndef ENDOSIM_INJECT_H
#define ENDOSIM_INJECT_H

#include <stdbool.h>
#include <stdint.h>

#include "proto/endosim_shm.h"
#include "rig/rig.h"
#include "model/scope.h"

/* The same numbers as endosim.proto's DebugAction (their names:
 * names_debug_action()). */
enum inject_action {
	INJECT_CLEAR = 1,       /* every injection on the axis ends */
	INJECT_DRIVE_FAULT,     /* the drive reports fault code VALUE */
	INJECT_DRIVE_GONE,      /* the drive is not present */
	INJECT_STALE,           /* the feedback is no longer renewed */
	INJECT_BUS_ERROR,       /* a transaction failed */
	INJECT_SPEED,           /* the speed reads VALUE (m/s, rad/s) */
	INJECT_POSITION,        /* the position reads VALUE (m, rad) */
	INJECT_FORCE,           /* the rendered command is VALUE (N, N m) */
	INJECT_NAN,             /* a NaN at stage VALUE (enum endosim_stage) */
	INJECT_STALL,           /* the force loop sleeps VALUE s, once */
	INJECT_END_CONTROL,     /* the control thread ends */
	INJECT_ACTIONS,
};

struct inject_axis {
	uint32_t on;                   /* 1 << enum inject_action */
	double value[INJECT_ACTIONS];
	uint64_t stale_ns;             /* the feedback's time from then on */
};

struct inject {
	struct inject_axis axis[ENDOSIM_AXES];
	bool haptics_nan;      /* a haptic part holds a NaN of ours ... */
	double haptics_saved;  /* ... instead of this */
};

/*
 * Starts ACTION with VALUE on AXIS (-1: every axis) at NOW_NS. Returns 0,
 * or -EINVAL for an action this module does not carry out, an axis out of
 * range, or a NaN stage that does not exist.
 */
int inject_start(struct inject *in, int action, int axis, double value,
		 uint64_t now_ns);

/* The feedback as the injections make it read. */
void inject_feedback(const struct inject *in, struct rig_feedback *fb);

/*
 * The pose, the haptic parts and the command as the injections make them
 * (a haptic part poisoned with a NaN gets its value back when cleared).
 */
void inject_pipeline(struct inject *in, struct scope_pose *pose,
		     struct endosim_haptics_state *haptics,
		     double command[ENDOSIM_AXES]);

#endif
