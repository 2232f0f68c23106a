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
 *   TIME valve VALVE on|off        the hand covers or presses a valve of the
 *                                  handle, or lets it go: air (the air/water
 *                                  valve covered: the pump's gas in), water
 *                                  (pressed: the jet onto the lens) or
 *                                  suction
 *   TIME patient position POSITION the assistant turns the patient to
 *                                  left-lateral, supine, right-lateral or
 *                                  prone (names.h; the turn takes
 *                                  [patient] turn_s)
 *   TIME patient press SITE [N]    the assistant presses the abdomen at the
 *                                  case's site SITE ([site NAME]) with N
 *                                  newtons ([patient] hand_n if omitted)
 *   TIME patient release           she lets go
 *   TIME end                       the scenario ends; the hand keeps its last
 *                                  step
 *   TIME repeat                    the scenario starts again at time 0
 *
 * AXIS is insertion, roll, wheel_ud or wheel_lr. Until its first step an
 * axis is free; the first target ramps from 0. Each valve is released
 * until its first line (and again at each repeat's start).
 *
 * The patient's commands are carried out by the force loop, each once, in
 * the file's order (the simulated rig hands them out one a cycle,
 * hand_patient()), as the control thread's would be: one the patient
 * cannot take (the patient disabled, a site the case does not have, a
 * force beyond [patient] hand_max_n) changes nothing. A file is checked
 * here for its words, not against a case.
 *
 * Loading allocates; evaluating does not (safe in the force loop).
 */
#ifndef ENDOSIM_SCENARIO_H
#define ENDOSIM_SCENARIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "model/anatomy.h"
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

/* A command for the assistant, as a scenario gives it. */
enum scenario_patient_action {
	SCENARIO_PATIENT_NONE = 0,
	SCENARIO_PATIENT_TURN,     /* to .position */
	SCENARIO_PATIENT_PRESS,    /* at .site with .force_n */
	SCENARIO_PATIENT_RELEASE,
};

struct scenario_patient {
	uint32_t seq;              /* its number, 1, 2, ... as played (a
				      repeat goes on counting); 0: none */
	int action;                /* enum scenario_patient_action */
	int position;              /* TURN: enum endosim_position */
	char site[ANATOMY_NAME];   /* PRESS: the case's site's name */
	double force_n;            /* PRESS: N; 0: [patient] hand_n */
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

/* The valves the scenario holds at T (enum endosim_valve bits). */
uint32_t scenario_valves(const struct scenario *s, double t);

/*
 * The patient's commands due by T: how many, a repeating scenario's
 * earlier rounds included (the last one's number). Fixed work for the
 * force loop: the scenario's patient lines, not all its lines.
 */
uint32_t scenario_patient_due(const struct scenario *s, double t);

/* The patient's command numbered SEQ (1 ..), a repeat's too, into OUT;
 * OUT->action NONE when there is no such command. */
void scenario_patient_get(const struct scenario *s, uint32_t seq,
			  struct scenario_patient *out);

/* True once a scenario that ends (not one that repeats) is past its end. */
bool scenario_done(const struct scenario *s, double t);

/* Seconds until the end or the repeat; for a scenario without either, the
 * time its last step is complete. */
double scenario_length(const struct scenario *s);

#endif
