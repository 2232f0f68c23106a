/*
 * rig_sim.h - the simulated rig: four plants (plant.h) moved by the motor
 * setpoints and the simulated hand (hand.h), one loop period per cycle, a
 * backend of rig.h. Main thread (or a test's) only.
 */
#ifndef ENDOSIM_RIG_SIM_H
#define ENDOSIM_RIG_SIM_H

#include "conf/config.h"
#include "rig/hand.h"
#include "rig/rig.h"

/* The simulated rig, its hand HAND (not owned). NULL on failure, logged. */
struct rig *rig_sim_create(const struct config *cfg, struct hand *hand);

#endif
