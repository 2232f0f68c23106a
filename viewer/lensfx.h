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
 * A lens smeared and murky enough hides the sharp image everywhere (the
 * pixel least smeared still takes only the blurred copies): then the
 * image need only be as fine as the first blurred copy, and the caller
 * draws it, and the lens over it, at LENSFX_HIDDEN_FACTOR of its side
 * (lensfx_image_factor()): a quarter of the pixels of the image and of
 * the lens's pass, the blurred copies the same as at full size, and the
 * picture the same but for the image circle's edge (scaled up further).
 * In software that takes the patient's worst frame (the tip in a pool,
 * the lens smeared and murky) from 12 to 8 ms (p50).
 *
 * Main thread, with the GL context current (lensfx_visible(),
 * lensfx_amount() and lensfx_image_factor() need none: lensfx_rules.c).
 */
#ifndef ENDOVIEW_LENSFX_H
#define ENDOVIEW_LENSFX_H

#include <stdbool.h>

#include "proto/endosim_shm.h"
#include "viewer/endo.h"

#define LENSFX_CLEAN 0.002 /* an amount below this is not drawn */
#define LENSFX_HIDDEN_FACTOR 0.5 /* the image's side, sharp image hidden */

struct lensfx;

/* The program, the noise texture. NULL on failure (logged). */
struct lensfx *lensfx_create(void);

/* NULL is fine. */
void lensfx_destroy(struct lensfx *fx);

/* True when P's lens (or its jet) has anything to draw. */
bool lensfx_visible(const struct endosim_patient_state *p);

/* An amount of the lens (smear, murk, red-out) as drawn: V within
 * 0..1, 0 when not finite. */
float lensfx_amount(double v);

/*
 * What P's lens lets the image be drawn at, of its side: 1, or
 * LENSFX_HIDDEN_FACTOR where it hides the sharp image everywhere.
 */
double lensfx_image_factor(const struct endosim_patient_state *p);

/*
 * Draws P's lens over the endoscopic image in R (drawn by endo_draw() in
 * this frame, in the framebuffer bound: the back buffer, or
 * imagescale.h's target), the image drawn at FACTOR of its side
 * (lensfx_image_factor()'s, or 1), at time T_S (s; the jet's ripples).
 * Where the driver will not have its offscreen targets it says so once
 * and draws nothing from then on: the image as it is.
 */
void lensfx_draw(struct lensfx *fx, const struct endosim_patient_state *p,
		 struct endo_rect r, double factor, double t_s);

#endif
