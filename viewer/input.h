/*
 * input.h - the trainee's hand on the simulated rig, from the keyboard,
 * the mouse and a gamepad: the force (N) or torque (N m) it puts on each
 * axis, sent to endosimd as HandInput.
 *
 * The hand is a grip, like the daemon's scripted hand (scenario.h): a
 * spring-damper pulling each axis towards a target that the controls
 * move,
 *   F = k (target - position) - c velocity, clamped to the hand's strength,
 * so that a key held pushes the scope along at a steady pace where the
 * colon lets it and with the hand's full strength where it does not.
 * Rates (keys, sticks; -1..1, or up to INPUT_FAST for a hurried hand)
 * move the target at input_rate per axis; a drag sets an axis' target to
 * where it was when the drag began plus the drag's offset; a step nudges
 * it once (the scroll wheel). The target never leads its axis by more
 * than the strength over the stiffness, so it does not run away from a
 * blocked scope.
 *
 * The grip takes hold at the axes' current positions on the first
 * control and lets go INPUT_RELEASE_S after the last: endosimd's hand
 * then holds each axis where it was left (rig/hand.h) until hands off
 * (the key Z), or a scenario takes it. Pure computation.
 */
#ifndef ENDOVIEW_INPUT_H
#define ENDOVIEW_INPUT_H

#include <stdbool.h>
#include <stdint.h>

#include "proto/endosim_shm.h"

#define INPUT_RELEASE_S 0.6
#define INPUT_FAST 3.0

/* Per axis: insertion (m), roll, up/down wheel, left/right wheel (rad). */
extern const double input_rate[ENDOSIM_AXES];      /* per second */
extern const double input_stiffness[ENDOSIM_AXES]; /* N/m, N m/rad */
extern const double input_damping[ENDOSIM_AXES];   /* N s/m, N m s/rad */
extern const double input_strength[ENDOSIM_AXES];  /* N, N m */

/* What the trainee does this frame. */
struct input_controls {
	double rate[ENDOSIM_AXES];   /* -INPUT_FAST..INPUT_FAST */
	bool drag[ENDOSIM_AXES];     /* a drag holds this axis */
	double drag_by[ENDOSIM_AXES]; /* the drag's offset, m or rad */
	double step[ENDOSIM_AXES];   /* a nudge of the target, m or rad */
	uint32_t valves;             /* the handle's valves held (enum
					endosim_valve bits): no part of the
					grip (input_active(), input_step()) */
};

struct input_hand {
	bool engaged;
	double target[ENDOSIM_AXES];
	bool dragging[ENDOSIM_AXES];
	double drag_from[ENDOSIM_AXES]; /* the target when the drag began */
	uint64_t last_used_ns;
};

/* True when C does anything at all. */
bool input_active(const struct input_controls *c);

/*
 * One frame of DT_S seconds at NOW_NS: moves the targets by C and writes
 * the hand's FORCE from the axes in ST. Returns true while the grip holds
 * (FORCE is to be sent), false once it let go (FORCE is zero).
 */
bool input_step(struct input_hand *h, const struct input_controls *c,
		const struct endosim_state *st, double dt_s, uint64_t now_ns,
		double force[ENDOSIM_AXES]);

#endif
