/*
 * rig_drives.h - the rig of drives, a backend of rig.h: each axis on the
 * backend its [axis.NAME] section names, simulated axes (rig_sim.h) next to
 * real ones; one bus thread per physical bus (bus.h), started by start()
 * at a SCHED_FIFO priority below the force loop's. Main thread only.
 */
#ifndef ENDOSIM_RIG_DRIVES_H
#define ENDOSIM_RIG_DRIVES_H

#include "conf/config.h"
#include "rig/hand.h"
#include "rig/rig.h"

/*
 * The simulated axes take their hand from HAND (not owned). NULL on
 * failure, logged.
 */
struct rig *rig_drives_create(const struct config *cfg, struct hand *hand);

#endif
