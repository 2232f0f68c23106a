/*
 * offline.h - endosimd's force loop off line, in lockstep on simulated
 * time (loop_step()), for the tools, tests and benchmarks that want its
 * behaviour cycle for cycle whatever the machine does (session_synth,
 * bench_haptics, test_course): the loop's own cycle (safety checks and
 * filter with its enable ramp and clamps, kinematics, haptics) on the
 * simulated rig (the plants and the scripted hand of a scenario,
 * rig_sim.c), one period of OFFLINE_PERIOD_NS a step. The loop is enabled
 * at the first step. Same configuration, colon and scenario: the same
 * states, bit for bit.
 *
 * Not for the force loop: offline_create() allocates and reads the
 * scenario file. One thread.
 */
#ifndef ENDOSIM_OFFLINE_H
#define ENDOSIM_OFFLINE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "model/colon.h"
#include "conf/config.h"
#include "proto/endosim_shm.h"
#include "rig/guide.h"
#include "model/haptics.h"
#include "rig/scenario.h"

#define OFFLINE_PERIOD_NS ENDOSIM_NS_PER_MS /* 1 ms, as the daemon's default */
#define OFFLINE_START_NS ENDOSIM_NS_PER_S /* the first cycle's stamp */
#define OFFLINE_SCENE_ID 1             /* the colon's scene_id */

struct offline;

/*
 * The loop with CFG (copied; its [loop] rate_hz must give
 * OFFLINE_PERIOD_NS) on COLON (owned from here on, freed with the loop,
 * also on failure), the hand playing the scenario file SCENARIO. NULL
 * with one line in ERR.
 */
struct offline *offline_create(const struct config *cfg, struct colon *colon,
			       const char *scenario, char *err,
			       size_t errsize);

/*
 * The same with the scenario SCN (taken, also on failure), which the
 * caller may go on appending to (scenario_append()) for times not yet
 * played: a scripted trainee that decides as it goes.
 */
struct offline *offline_create_with(const struct config *cfg,
				    struct colon *colon, struct scenario *scn,
				    char *err, size_t errsize);

/* NULL is fine. */
void offline_destroy(struct offline *o);

/* The scenario's length (s): how long a run of it lasts. */
double offline_length_s(const struct offline *o);

/*
 * Runs one cycle; returns the state it published (as struct endosim_state
 * in shared memory: cycle 0, 1, ..., as the daemon counts them, stamped
 * OFFLINE_START_NS and a period more each cycle; compute_ns the cycle's
 * wall time), valid until the next call.
 */
const struct endosim_state *offline_step(struct offline *o);

/*
 * H and the bytes of ST (FNV-1a), its wall-clock field (compute_ns)
 * zeroed: runs that repeat bit for bit hash the same. Start from
 * OFFLINE_HASH_START.
 */
#define OFFLINE_HASH_START 0xcbf29ce484222325ull
uint64_t offline_hash(uint64_t h, const struct endosim_state *st);

/* The loop's colon (loop_colon()): where its mobile spans are now. */
const struct colon *offline_colon(const struct offline *o);

/* The rod model's tip held where it is, or let go (loop_hold_tip()). */
void offline_hold_tip(struct offline *o, double hold_n_per_m);

/*
 * Live hand input, as `endoctl hand` gives it: FORCE (N, N m, N m, N m)
 * from the next cycle on, for HOLD_S seconds of simulated time.
 */
void offline_hand(struct offline *o, const double force[ENDOSIM_AXES],
		  double hold_s);

/* Hands off: the hand lets go of every axis (hand_release()). */
void offline_hands_off(struct offline *o);

/* A safety command (enable, disable, ...) for the next cycle. */
void offline_command(struct offline *o, int cmd);

/*
 * A guidance command for the next cycle (loop_guide_post()); its answer,
 * once that cycle ran, is offline_guide_answer()'s.
 */
void offline_guide(struct offline *o, const struct guide_command *c);
int offline_guide_answer(const struct offline *o);

/*
 * The tool in the working channel as the hand holds it (hand_set_tool():
 * DEPTH_M beyond the channel's exit, the handle's OPENING, the PEDAL)
 * from the next cycle on, for HOLD_S seconds of simulated time.
 */
void offline_tool_input(struct offline *o, double depth_m, double opening,
			bool pedal, double hold_s);

/*
 * The tool KIND (enum tool_kind) of size SNARE_M handed over for the next
 * cycle (loop_tool_post()); its answer, once that cycle ran, is
 * offline_tool_answer()'s.
 */
void offline_tool_select(struct offline *o, int kind, double snare_m);
int offline_tool_answer(const struct offline *o);

/* The loop's tool (loop_tool()), for the tests that look inside it. */
struct tool *offline_tool(struct offline *o);

#endif
