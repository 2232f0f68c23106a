/*
 * lensfx.h - what covers the scope's lens, drawn over the endoscopic
 * image (endo.h) as a post effect: the daemon's lens state (struct
 * endosim_patient_state lens_smear, lens_murk, lens_redout; lens.h in the
 * model has how each grows and clears) and the water jet (the air/water
 * valve pressed, ENDOSIM_VALVE_WATER).
 *
 * The image as drawn is copied into a texture, and into two blurred
 * copies a quarter and a sixteenth as wide; each pixel then mixes the
 * sharp image with the blurred ones and a veil:
 *   smear    the mucosa smeared on the lens: the image blurred in
 *            patches fixed to the lens (a noise texture), under a red veil
 *            (the light the walls return, scattered in the smear), more
 *            of both as the amount grows;
 *   murk     the fluid on the lens: an even blur under a brown-yellow
 *            haze;
 *   red-out  the mucosa sucked onto the lens: the image gives way to an
 *            even, dark red;
 *   water    while the jet runs: the image ripples as the water sheets
 *            across the lens.
 * The image circle's mask is kept. Nothing is drawn (no copy, no pass)
 * while the lens is clean and the jet off: a clean lens costs nothing.
 *
 * Main thread, with the GL context current.
 */
#ifndef ENDOVIEW_LENSFX_H
#define ENDOVIEW_LENSFX_H

#include <stdbool.h>

#include "proto/endosim_shm.h"
#include "viewer/endo.h"

#define LENSFX_CLEAN 0.002 /* an amount below this is not drawn */

struct lensfx;

/* The program, the noise texture. NULL on failure (logged). */
struct lensfx *lensfx_create(void);

/* NULL is fine. */
void lensfx_destroy(struct lensfx *fx);

/* True when P's lens (or its jet) has anything to draw. */
bool lensfx_visible(const struct endosim_patient_state *p);

/*
 * Draws P's lens over the endoscopic image in R (drawn by endo_draw() in
 * this frame, in the framebuffer bound: the back buffer, or
 * imagescale.h's target), at time T_S (s; the jet's ripples).
 */
void lensfx_draw(struct lensfx *fx, const struct endosim_patient_state *p,
		 struct endo_rect r, double t_s);

#endif
