/*
 * font.h - text for the HUD: a TrueType font (DejaVu Sans from Debian's
 * fonts-dejavu-core by default) baked with stb_truetype into one 8-bit
 * alpha atlas at two pixel sizes, printable ASCII only.
 *
 * The atlas also holds a small opaque block (font_white()) so that one
 * texture serves text and solid shapes in a single batch (draw2d.h).
 * Pure CPU; font_create() reads the file and allocates.
 */
#ifndef ENDOVIEW_FONT_H
#define ENDOVIEW_FONT_H

#define FONT_DEFAULT_PATH "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#define FONT_FIRST 32
#define FONT_CHARS 95

enum font_size {
	FONT_SMALL = 0,
	FONT_LARGE = 1,
	FONT_SIZES = 2,
};

/* A glyph to draw: screen rectangle (pixels, y down) and atlas texcoords. */
struct font_quad {
	float x0, y0, x1, y1;
	float s0, t0, s1, t1;
};

struct font;

/*
 * Bakes PATH at SMALL_PX and LARGE_PX (pixel heights, 6..128). NULL with
 * errno set when the file cannot be read or is not a font (EINVAL).
 */
struct font *font_create(const char *path, float small_px, float large_px);

/* NULL is fine. */
void font_destroy(struct font *f);

/* The atlas: W x H bytes of coverage, rows top first. */
const unsigned char *font_atlas(const struct font *f, int *w, int *h);

/* Texcoords of the centre of the atlas' opaque block. */
void font_white(const struct font *f, float *s, float *t);

/*
 * The quad of character C with its baseline at Y and pen at *X (pixels),
 * advancing *X. Returns 0, or -1 for a character outside the atlas (the
 * pen then advances as for '?').
 */
int font_quad(const struct font *f, enum font_size size, int c, float *x,
	      float y, struct font_quad *q);

/* Width of TEXT (pixels). */
float font_width(const struct font *f, enum font_size size,
		 const char *text);

/* Pixel height the size was baked at (~ line spacing / 1.2). */
float font_px(const struct font *f, enum font_size size);

#endif
