/*
 * posture.h - the patient's position on the table and gravity in the
 * body's frame.
 *
 * The body's frame is the case's (anatomy.h): x to the patient's left, y
 * posterior, z cranial. The patient lies in one of four positions, each a
 * turn about the body's long axis (z), with gravity's direction:
 *   left lateral   (+1, 0, 0)   on the left side: where a colonoscopy
 *                               starts
 *   supine         (0, +1, 0)   on the back
 *   right lateral  (-1, 0, 0)   on the right side
 *   prone          (0, -1, 0)   on the belly
 * A change of position takes turn_s (the shorter way round; from one
 * lateral position to the other over the back, through supine; between
 * supine and prone through the left lateral): gravity turns smoothly
 * about z, its angle
 * eased in and out (3 u^2 - 2 u^3 of the time's share u), so that the
 * colon, the scope and the fluid feel no jolt.
 *
 * Pure computation, no allocation: the force loop steps it. One writer.
 */
#ifndef ENDOSIM_POSTURE_H
#define ENDOSIM_POSTURE_H

#include <stdbool.h>

enum posture_position {
	POSTURE_LEFT_LATERAL = 0,
	POSTURE_SUPINE = 1,
	POSTURE_RIGHT_LATERAL = 2,
	POSTURE_PRONE = 3,
	POSTURE_POSITIONS,
};

struct posture {
	int position;       /* where it is, or where it is turning to */
	int from;           /* where a turn began */
	double from_rad;    /* gravity's angle about z from +x at the start */
	double to_rad;      /* ... at the end (the way the turn goes) */
	double turn_s;      /* the turn's duration */
	double elapsed_s;   /* into the turn; >= turn_s: settled */
	double down[3];     /* gravity's direction now (unit) */
};

/* Settled in POSITION. */
void posture_reset(struct posture *p, int position);

/*
 * Starts turning to POSITION over TURN_S seconds (0: at once) from where
 * gravity points now (a turn may start during another). Returns 0, or
 * -EINVAL for no such position.
 */
int posture_turn(struct posture *p, int position, double turn_s);

/* Advances DT_S seconds. */
void posture_step(struct posture *p, double dt_s);

/* Turning (not settled). */
bool posture_turning(const struct posture *p);

/* The turn's progress 0..1 (1: settled). */
double posture_progress(const struct posture *p);

/* "left-lateral", "supine", "right-lateral", "prone"; "?" otherwise. */
const char *posture_name(int position);

/* The position called NAME, or -1. */
int posture_find(const char *name);

#endif
