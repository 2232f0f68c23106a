/*
 * haptics.h - the forces the trainee feels.
 *
 * PLACEHOLDER until the haptic-rendering issue: no colon yet, only the rig's
 * own safety brakes near each end of travel and a light viscous damping on
 * every axis. The brakes resist motion towards an end over the last
 * [haptics] end_zone_fraction of the travel, growing to the axis' force
 * limit at the end stop; they never push an axis that rests or moves away
 * from the end (so they cannot kick a carriage that starts at its end), and
 * they only take energy out.
 *
 * Called by the force loop: pure computation, no allocation, no I/O.
 */
#ifndef ENDOSIM_HAPTICS_H
#define ENDOSIM_HAPTICS_H

#include "config.h"
#include "rig.h"

/* COMMAND[a]: the force (N) or torque (N m) to render on each axis. */
void haptics_render(const struct config *cfg, const struct rig_feedback *fb,
		    double command[ENDOSIM_AXES]);

#endif
