/*
 * imagescale.h - the 3-D views drawn offscreen and copied into the
 * window, the endoscopic image at a fraction of its size and scaled up.
 * Where the drawing is done in software (Mesa's llvmpipe, softpipe,
 * swrast), shading the image's pixels is most of a
 * frame: at 1280x720 (a 720 x 720 image) it took 11.5 of a 16 ms frame
 * on the 2-CPU VM, the panel 2, and the fluid and the lens (lensfx.h)
 * shade each pixel again. Drawn at IMAGESCALE_SOFTWARE of each side (a
 * quarter of the pixels) and scaled up with a linear filter (2.4 ms at
 * that size), the frame took 11; the picture is softer, as an
 * endoscope's video is, and keeps its vessels and folds. On a GPU it is
 * drawn at full size; --image-scale chooses.
 *
 * In the endoscopic view the window has neither a depth nor a stencil
 * buffer (endoview.c), so its clear has no depth to clear, and the
 * image, always drawn offscreen there, is copied in as a plain textured
 * rectangle rather than by glBlitFramebuffer(): together a 2 M
 * triangles' 1280x720 endoscopic frame took ~3 ms of CPU less of ~21
 * (docs/ENGINEER.md; llvmpipe's linear path for such rectangles is not
 * what gave it: Mesa 22.3 does not take it here). The overview's window
 * keeps its depth buffer: copying a view at full size cost as much as
 * that gained.
 *
 * imagescale_begin() binds an offscreen target (a colour texture and a
 * depth buffer) and gives the rectangle to draw the view of R in there
 * (endo_draw(), then lensfx_draw(): the mask and the lens follow it): at
 * SCALE < 1 the target is SCALE times R's size and the rectangle its
 * whole; at SCALE 1 in a window without depth the target reaches R's far
 * corner and the rectangle is R itself (the overview keeps its window
 * coordinates for its labels). imagescale_end() copies it into R in the
 * window's back buffer, as a textured rectangle (scaled up with a linear
 * filter, or texel for texel), and binds that again. At SCALE 1 in a
 * window with depth both do nothing and the view is drawn in R itself.
 *
 * Main thread, with the GL context current; the copy's program is made
 * once (imagescale_create()), the target anew when its size changes.
 */
#ifndef ENDOVIEW_IMAGESCALE_H
#define ENDOVIEW_IMAGESCALE_H

#include "viewer/endo.h"

#define IMAGESCALE_SOFTWARE 0.5 /* of each side: a quarter of the pixels */
#define IMAGESCALE_MIN 0.25

struct imagescale;

/* NULL when out of memory. Looks whether the window has a depth buffer
 * (its framebuffer is bound after) and compiles the copy's program (one
 * that does not compile: the views drawn in the window, logged). */
struct imagescale *imagescale_create(void);

/* NULL is fine. */
void imagescale_destroy(struct imagescale *s);

/* The scale for a context whose GL_RENDERER is RENDERER (NULL: 1). */
double imagescale_for(const char *renderer);

/*
 * Where to draw the view of R at SCALE (IMAGESCALE_MIN..1): a rectangle in
 * the target it binds, or R in the window (a target that cannot be made:
 * logged once; drawn there without a depth test).
 */
struct endo_rect imagescale_begin(struct imagescale *s, struct endo_rect r,
				  double scale);

/* The view drawn since imagescale_begin() into R of the back buffer; the
 * window's framebuffer bound, blending off. */
void imagescale_end(struct imagescale *s, struct endo_rect r);

#endif
