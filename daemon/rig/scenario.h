/*
 * scenario.h - a scripted trainee's hand for the simulated rig.
 *
 * A scenario file is a list of timed steps, one per line ('#' starts a
 * comment), times in seconds from the start, in any order (steps at the
 * same time apply in file order); end or repeat, if present, is the last
 * line:
 *
 *   TIME AXIS target VALUE [RAMP]  the hand follows a target position (m or
 *                                  rad) that moves linearly from the previous
 *                                  target to VALUE over RAMP seconds (0 if
 *                                  omitted); the hand is a spring-damper
 *   TIME AXIS force VALUE          the hand pushes with VALUE (N or N m)
 *   TIME AXIS free                 the hand lets go
 *   TIME end                       the scenario ends; the hand keeps its last
 *                                  step
 *   TIME repeat                    the scenario starts again at time 0
 *
 * AXIS is insertion, roll, wheel_ud or wheel_lr. Until its first step an
 * axis is free; the first target ramps from 0.
 *
 * Loading allocates; evaluating does not (safe in the force loop).
 */
#ifndef ENDOSIM_SCENARIO_H
#define ENDOSIM_SCENARIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "proto/endosim_shm.h"

enum scenario_mode {
	SCENARIO_FREE = 0,
	SCENARIO_TARGET,
	SCENARIO_FORCE,
};

struct scenario_cmd {
	enum scenario_mode mode;
	double value; /* target (m or rad) or force (N or N m) */
};

struct scenario;

/*
 * Reads PATH. Returns NULL with one line "FILE:LINE: what" in ERR when the
 * file cannot be read or a line is wrong.
 */
struct scenario *scenario_load(const char *path, char *err, size_t errsize);

/* The same for an open stream; NAME stands for the file in messages. */
struct scenario *scenario_load_stream(FILE *f, const char *name, char *err,
				      size_t errsize);

/*
 * A scenario built step by step (a scripted trainee that decides as it
 * goes, in lockstep): none yet; scenario_append() adds them. NULL on
 * ENOMEM.
 */
struct scenario *scenario_create(void);

/*
 * Appends one line of the file format (a step, or end/repeat), parsed as
 * the file's are, at or after the last step's time: what evaluates before
 * it does not change. 0, or -EINVAL (a bad line, too early, after the
 * end) / -ENOMEM with one line in ERR. Allocates: not in the force loop
 * (nor while a force loop's thread evaluates it).
 */
int scenario_append(struct scenario *s, const char *line, char *err,
		    size_t errsize);

/* NULL is fine. */
void scenario_destroy(struct scenario *s);

/* What the hand does on each axis T seconds after the start. */
void scenario_eval(const struct scenario *s, double t,
		   struct scenario_cmd out[ENDOSIM_AXES]);

/* True once a scenario that ends (not one that repeats) is past its end. */
bool scenario_done(const struct scenario *s, double t);

/* Seconds until the end or the repeat; for a scenario without either, the
 * time its last step is complete. */
double scenario_length(const struct scenario *s);

#endif
