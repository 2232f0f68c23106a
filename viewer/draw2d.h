/*
 * draw2d.h - flat shapes and text in pixels over the 3-D views (the HUD,
 * banners, the endoscopic image's mask): one batch, one texture (the
 * font's atlas, font.h), drawn with alpha blending in call order.
 *
 * Coordinates are framebuffer pixels, origin top-left, y down. Colours are
 * RGBA in 0..1. Main thread, with the GL context current.
 */
#ifndef ENDOVIEW_DRAW2D_H
#define ENDOVIEW_DRAW2D_H

#include "viewer/font.h"

struct draw2d;

/* F may be NULL: shapes only, text is skipped. NULL on failure (logged). */
struct draw2d *draw2d_create(const struct font *f);

/* NULL is fine. */
void draw2d_destroy(struct draw2d *d);

/* Starts a batch over the whole framebuffer of W x H pixels. */
void draw2d_begin(struct draw2d *d, int w, int h);

void draw2d_rect(struct draw2d *d, float x, float y, float w, float h,
		 const float rgba[4]);

void draw2d_triangle(struct draw2d *d, const float xy[6],
		     const float rgba[4]);

/* A disc of radius R pixels centred at (X, Y), 16 triangles round. */
void draw2d_disc(struct draw2d *d, float x, float y, float r,
		 const float rgba[4]);

/* A segment WIDTH pixels wide. */
void draw2d_line(struct draw2d *d, float x0, float y0, float x1, float y1,
		 float width, const float rgba[4]);

/* TEXT with its baseline at Y from X; returns the pen's advance. */
float draw2d_text(struct draw2d *d, enum font_size size, float x, float y,
		  const float rgba[4], const char *text);

/* The same, formatted (at most 255 characters). */
float draw2d_printf(struct draw2d *d, enum font_size size, float x, float y,
		    const float rgba[4], const char *fmt, ...)
	__attribute__((format(printf, 6, 7)));

/* Width of TEXT at SIZE (0 without a font). */
float draw2d_text_width(const struct draw2d *d, enum font_size size,
			const char *text);

/* The font's pixel height at SIZE (a fallback without a font). */
float draw2d_px(const struct draw2d *d, enum font_size size);

/* Draws what the batch holds. */
void draw2d_end(struct draw2d *d);

#endif
