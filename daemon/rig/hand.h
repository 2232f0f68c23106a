/*
 * hand.h - the simulated trainee's hand: the force it puts on each axis of
 * the simulated rig, from a scenario (a spring-damper grip following timed
 * targets, or timed pushes) or from live input through the socket (the
 * viewer's keyboard or gamepad). Live input, while it holds, overrides the
 * scenario on every axis; live input of the valves alone (endoctl patient
 * valve) holds the valves and leaves the forces as they are; the tool in
 * the working channel (its depth, the handle, the pedal) holds on its own
 * too.
 *
 * Every force is clamped to the configured strongest push of a hand, and
 * fades along the motion to nothing at the hand's top speed, as a
 * muscle's does: a hand alone never moves an axis faster than that.
 *
 * The grip: a trainee's right hand holds the shaft and the left the
 * wheels between moves. Once live input has pushed an axis, the hand holds
 * it where the input left it when the input lapses (no scenario playing,
 * or the scenario done): a spring of the hand's stiffness and damping
 * ([sim] hand_*_stiffness, hand_*_damping) to that place, up to the
 * grip's strength ([sim] grip_*_max); a load beyond it makes the axis slip
 * (the place follows the axis, so that the spring holds the strength), as
 * a shaft slides through fingers. hand_release() ("hands off") lets every
 * axis go until live input takes hold again.
 */
#ifndef ENDOSIM_HAND_H
#define ENDOSIM_HAND_H

#include <stdbool.h>
#include <stdint.h>

#include "conf/config.h"
#include "rig/scenario.h"

struct hand;

/* Takes ownership of SCN (may be NULL: no scenario). NULL on ENOMEM. */
struct hand *hand_create(const struct config *cfg, struct scenario *scn);

/* NULL is fine. */
void hand_destroy(struct hand *h);

/* The scenario, or NULL. */
const struct scenario *hand_scenario(const struct hand *h);

/*
 * Control thread (one writer): live forces (N, N m, N m, N m) and the
 * handle's valves (enum endosim_valve bits) that hold for HOLD_S seconds
 * after NOW_NS (CLOCK_MONOTONIC). FORCE NULL: the valves alone, the
 * forces as they were (a scenario's, or earlier live ones while they
 * hold). Lock-free.
 */
void hand_set_live(struct hand *h, const double force[ENDOSIM_AXES],
		   uint32_t valves, double hold_s, uint64_t now_ns);

/*
 * Control thread (one writer): the tool in the working channel as the
 * hand holds it (tool.h: its depth beyond the channel's exit, m, the
 * handle's opening 0..1, the pedal down), for HOLD_S seconds after
 * NOW_NS; the forces and the valves as they were. Lock-free.
 */
void hand_set_tool(struct hand *h, double depth_m, double opening, bool pedal,
		   double hold_s, uint64_t now_ns);

/* Control thread: hands off, every axis let go (lock-free). */
void hand_release(struct hand *h);

/*
 * Force loop: the hand's force on each axis at scenario time T_S given the
 * axes' positions and velocities. Never blocks or allocates.
 */
void hand_forces(struct hand *h, double t_s, uint64_t now_ns,
		 const double pos[ENDOSIM_AXES], const double vel[ENDOSIM_AXES],
		 double force[ENDOSIM_AXES]);

/*
 * Force loop, after hand_forces() of a cycle: the valves the hand holds
 * (enum endosim_valve bits) at scenario time T_S: the live input's while
 * it holds, else the scenario's (none without one). Never blocks.
 */
uint32_t hand_valves(const struct hand *h, double t_s, uint64_t now_ns);

/*
 * Force loop, after hand_forces() of a cycle: the tool as the live input
 * holds it into *DEPTH_M, *OPENING and *PEDAL; once the input lapses (a
 * client that stops sending), the tool still and the handle still
 * (non-finite: tool.h's rule) and the pedal up. Never blocks.
 */
void hand_tool(const struct hand *h, uint64_t now_ns, double *depth_m,
	       double *opening, bool *pedal);

/*
 * Force loop, once a cycle: the scenario's commands for the assistant
 * (scenario.h), handed out one a cycle in order: the next one due at
 * scenario time T_S that was not handed out yet, else the last one again
 * (OUT->seq 0: none yet, or no scenario). The loop carries out each number
 * once; live input does not hold them back (they are the assistant's, not
 * the trainee's hand). Never blocks or allocates.
 */
void hand_patient(struct hand *h, double t_s, struct scenario_patient *out);

#endif
