/*
 * imagescale.h - the endoscopic image drawn at a fraction of its size
 * and scaled up to it. Where the drawing is done in software (Mesa's
 * llvmpipe, softpipe, swrast), shading the image's pixels is most of a
 * frame: at 1280x720 (a 720 x 720 image) it took 11.5 of a 16 ms frame
 * on the 2-CPU VM, the panel 2, and the fluid and the lens (lensfx.h)
 * shade each pixel again. Drawn at IMAGESCALE_SOFTWARE of each side (a
 * quarter of the pixels) and scaled up with a linear filter (2.4 ms at
 * that size), the frame took 11; the picture is softer, as an
 * endoscope's video is, and keeps its vessels and folds. On a GPU it is
 * drawn at full size; --image-scale chooses.
 *
 * imagescale_begin() binds an offscreen target (a colour texture and a
 * depth buffer) of SCALE times R's size and gives the rectangle to draw
 * the image in there (endo_draw(), then lensfx_draw(): the mask and the
 * lens follow it); imagescale_end() scales it up into R in the window's
 * back buffer and binds that again. With SCALE 1 both do nothing and the
 * image is drawn in R itself.
 *
 * Main thread, with the GL context current; the target is made anew when
 * its size changes.
 */
#ifndef ENDOVIEW_IMAGESCALE_H
#define ENDOVIEW_IMAGESCALE_H

#include "viewer/endo.h"

#define IMAGESCALE_SOFTWARE 0.5 /* of each side: a quarter of the pixels */
#define IMAGESCALE_MIN 0.25

struct imagescale;

/* NULL when out of memory. */
struct imagescale *imagescale_create(void);

/* NULL is fine. */
void imagescale_destroy(struct imagescale *s);

/* The scale for a context whose GL_RENDERER is RENDERER (NULL: 1). */
double imagescale_for(const char *renderer);

/*
 * Where to draw the image of R at SCALE (IMAGESCALE_MIN..1): a rectangle
 * in the target it binds, or R itself (SCALE 1, or a target that cannot
 * be made: logged once).
 */
struct endo_rect imagescale_begin(struct imagescale *s, struct endo_rect r,
				  double scale);

/* The image drawn since imagescale_begin() into R of the back buffer. */
void imagescale_end(struct imagescale *s, struct endo_rect r);

#endif
