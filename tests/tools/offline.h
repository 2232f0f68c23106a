/*
 * offline.h - endosimd's force loop off line, for the tools and the
 * benchmarks that want its motion without a daemon (bench_haptics,
 * session_synth): the simulated rig (the plants and the scripted hand of a
 * scenario, rig_sim.c) advances one period of OFFLINE_PERIOD_NS per step;
 * the scope's kinematics (scope_update()) and the haptics
 * (haptics_render()) run on the colon as the loop runs them; the command
 * is clamped to the configured limits and written back with the torque on
 * (there is no safety filter, no enable ramp, no fault). Every run sees
 * the same motion.
 *
 * Not for the force loop: offline_create() allocates and reads the
 * scenario file. One thread.
 */
#ifndef ENDOSIM_OFFLINE_H
#define ENDOSIM_OFFLINE_H

#include <stddef.h>
#include <stdint.h>

#include "colon.h"
#include "config.h"
#include "endosim_shm.h"
#include "rig.h"
#include "scope.h"

#define OFFLINE_PERIOD_NS 1000000ull   /* 1 ms, as the daemon's default */
#define OFFLINE_START_NS 1000000000ull /* the first cycle's stamp */

/* One cycle, as the force loop saw it. */
struct offline_cycle {
	uint64_t cycle;              /* 1, 2, ... */
	uint64_t stamp_ns;           /* OFFLINE_START_NS, then a period more */
	struct rig_feedback fb;      /* read at stamp_ns */
	struct scope_pose pose;      /* on the colon as last cycle bowed it */
	struct endosim_haptics_state haptics;
	double command[ENDOSIM_AXES]; /* N, N m: rendered */
	double limited[ENDOSIM_AXES]; /* clamped to cfg->limits, written */
	uint64_t step_ns;            /* wall time of kinematics + haptics */
};

struct offline;

/*
 * The loop's parts with CFG (copied) on COLON (not owned; the haptics bow
 * its mobile spans), the hand playing the scenario file SCENARIO. NULL
 * with one line in ERR.
 */
struct offline *offline_create(const struct config *cfg, struct colon *colon,
			       const char *scenario, char *err,
			       size_t errsize);

/* NULL is fine. */
void offline_destroy(struct offline *o);

/* The scenario's length (s): how long a run of it lasts. */
double offline_length_s(const struct offline *o);

/* Runs one cycle; the result stays valid until the next call. */
const struct offline_cycle *offline_step(struct offline *o);

/*
 * The last cycle as the daemon would have published it (struct
 * endosim_state, loop.c's fill_state() and fill_scope()): ENABLED, no
 * fault, the ramp at 1, scene SCENE_ID; compute_ns the step's time.
 */
void offline_state(const struct offline *o, uint64_t scene_id,
		   struct endosim_state *st);

#endif
