/*
 * haptics_paper.h - the haptics' `paper` model (haptics.h: Koerner and
 * Maenner, section 5): the tip's contact through the scope's Jacobian,
 * the insertion's friction over the tube's turning, the wires' tension
 * along the centreline, and the loops that the mobile segments bow into
 * when the tip is held and the hand pushes on. haptics.c dispatches to
 * it; its struct is haptics_private.h's.
 *
 * Force loop: nothing allocates, blocks or prints. Units SI.
 */
#ifndef ENDOSIM_HAPTICS_PAPER_H
#define ENDOSIM_HAPTICS_PAPER_H

#include "model/centreline.h"
#include "model/colon.h"
#include "proto/endosim_shm.h"

struct haptics;
struct haptics_input;
struct endosim_haptics_state;

/* A mobile segment that can loop. */
struct haptics_paper_span {
	int index;         /* the centreline's span */
	double s0, s1;     /* m, material */
	double k;          /* mesentery, N/m */
	double h;          /* mesentery height, m */
	double c;          /* stored tube length per amplitude^2, 1/m */
	double amplitude;  /* m: the loop */
	double applied;    /* m: the bow the centreline has (within
			      BOW_STEP_M of the loop) */
};

struct haptics_paper_loops {
	struct haptics_paper_span span[CENTRELINE_MAX_SPANS];
	int spans;
};

/*
 * COLON's mobile segments (a mesentery and a largest bow) as loops, each
 * straight, its stored tube length per amplitude measured by bowing the
 * span and laying it straight again. haptics_reset() measures them in
 * either model, as it always has: the rod's model never bows them, but a
 * colon's spans straightened here on a reset are what its runs started
 * from (the golden outputs are the same without: a change for its own
 * commit).
 */
void haptics_paper_reset(struct haptics *h, struct colon *colon);

/* One cycle of the paper's model (haptics_render()). */
void haptics_paper_render(struct haptics *h, const struct haptics_input *in,
			  double command[ENDOSIM_AXES],
			  struct endosim_haptics_state *out);

#endif
