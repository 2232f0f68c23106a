/*
 * faults.h - a latched fault in words, the same in the journal (main) and
 * in `endoctl status` (control): its name, the axis, when, and what
 * happened: the device's own words for the drive causes (rig.h describe),
 * what was measured against which limit for the causes the force loop
 * finds itself.
 *
 * Any thread but the force loop.
 */
#ifndef ENDOSIM_FAULTS_H
#define ENDOSIM_FAULTS_H

#include <stddef.h>
#include <stdint.h>

#include "proto/endosim_shm.h"
#include "rig/rig.h"

/*
 * What cause C of fault BIT means, into BUF: for the drive causes what RIG
 * says of it, for the others the value against the limit.
 */
void faults_describe(struct rig *rig, uint32_t bit,
		     const struct endosim_fault_cause *c, char *buf,
		     size_t size);

/*
 * The whole line, "NAME[ on AXIS] (detail D) at T s: WHAT", T counted from
 * START_NS (the daemon's start), into BUF.
 */
void faults_format(struct rig *rig, uint64_t start_ns, uint32_t bit,
		   const struct endosim_fault_cause *c, char *buf,
		   size_t size);

/* "feedback", "kinematics", ...: a stage of the force pipeline. */
const char *faults_stage_name(uint32_t stage);

#endif
