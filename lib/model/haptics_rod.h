/*
 * haptics_rod.h - the haptics' `rod` model (haptics.h): the insertion
 * tube an elastic rod in a colon that moves (rodscope.h), fed from the
 * rig's axes, the tip's god-object contact entering it at its tip; the
 * forces the rod's reactions at the carriage and along its bending
 * section. haptics.c dispatches to it; its struct is haptics_private.h's.
 *
 * haptics_rod_create() allocates (the rod); the rest never allocates,
 * blocks or prints: force loop. Units SI.
 */
#ifndef ENDOSIM_HAPTICS_ROD_H
#define ENDOSIM_HAPTICS_ROD_H

#include <stdbool.h>

#include "model/colon.h"
#include "proto/endosim_shm.h"
#include "model/lumen.h"
#include "model/rodscope.h"

struct haptics;
struct haptics_input;
struct endosim_haptics_state;

/* The rod model's own. */
struct haptics_rod_tube {
	struct rodscope *rs;       /* the tube */
	struct colon *colon;       /* it is laid in */
	bool fresh;                /* lay the tube at the next pose */
	struct lumen_totals wall;  /* the last step's contacts */
	double tip_v[3];           /* the tip's velocity, m/s */
};

/* The tube sized as P says into H; 0 or -ENOMEM (or bad parameters). */
int haptics_rod_create(struct haptics *h, const struct rodscope_params *p);

/* NULL's tube is fine. */
void haptics_rod_destroy(struct haptics *h);

/* COLON (a new one) to lay the tube in at the next haptics_rod_pose(). */
void haptics_rod_reset(struct haptics *h, struct colon *colon);

/* haptics_publish_rod()'s, OUT zeroed before. */
void haptics_rod_publish(const struct haptics *h, double roll_rad,
			 struct endosim_rod_state *out,
			 double bow_m[ENDOSIM_SPANS]);

/* haptics_hold_tip()'s. */
void haptics_rod_hold_tip(struct haptics *h, double hold_n_per_m);

/* One cycle of the rod's model (haptics_render()). */
void haptics_rod_render(struct haptics *h, const struct haptics_input *in,
			double command[ENDOSIM_AXES],
			struct endosim_haptics_state *out);

#endif
