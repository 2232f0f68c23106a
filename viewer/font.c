/* font.c - see font.h. */
#include "viewer/font.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_truetype.h>

#define ATLAS_W 1024
#define WHITE_PX 4 /* the opaque block's side */

struct font {
	int w, h;
	unsigned char *atlas;
	stbtt_bakedchar glyph[FONT_SIZES][FONT_CHARS];
	float px[FONT_SIZES];
	int white_y; /* the opaque block's top row */
};

static unsigned char *read_file(const char *path, size_t *len)
{
	FILE *f = fopen(path, "rb");
	unsigned char *buf = NULL;
	long n;

	if (!f) {
		return NULL;
	}
	if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) > 0 &&
	    fseek(f, 0, SEEK_SET) == 0) {
		buf = malloc((size_t)n);
		if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
			free(buf);
			buf = NULL;
			errno = EIO;
		}
		*len = (size_t)n;
	}
	fclose(f);
	return buf;
}

/* Bakes one size below row *Y of the atlas; moves *Y past it. */
static int bake(struct font *f, const unsigned char *ttf, int size, int *y)
{
	int rows = f->h - *y;
	int used = stbtt_BakeFontBitmap(ttf, 0, f->px[size],
					f->atlas + (size_t)*y * f->w, f->w,
					rows, FONT_FIRST, FONT_CHARS,
					f->glyph[size]);

	if (used <= 0) {
		return -EINVAL;
	}
	for (int c = 0; c < FONT_CHARS; c++) {
		f->glyph[size][c].y0 += (unsigned short)*y;
		f->glyph[size][c].y1 += (unsigned short)*y;
	}
	*y += used + 1;
	return 0;
}

static int bake_all(struct font *f, const unsigned char *ttf)
{
	int y = 0;

	for (int s = 0; s < FONT_SIZES; s++) {
		if (bake(f, ttf, s, &y)) {
			return -EINVAL;
		}
	}
	if (y + WHITE_PX > f->h) {
		return -EINVAL;
	}
	f->white_y = y;
	for (int r = 0; r < WHITE_PX; r++) {
		memset(f->atlas + (size_t)(y + r) * f->w, 255, WHITE_PX);
	}
	return 0;
}

struct font *font_create(const char *path, float small_px, float large_px)
{
	size_t len = 0;
	unsigned char *ttf = read_file(path, &len);
	struct font *f = NULL;

	if (!ttf) {
		return NULL;
	}
	if (!(small_px >= 6 && small_px <= 128 && large_px >= 6 &&
	      large_px <= 128) || stbtt_GetFontOffsetForIndex(ttf, 0) < 0) {
		errno = EINVAL;
		goto free_ttf;
	}
	f = calloc(1, sizeof(*f));
	if (!f) {
		goto free_ttf;
	}
	f->w = ATLAS_W;
	f->h = ATLAS_W / 2;
	f->px[FONT_SMALL] = small_px;
	f->px[FONT_LARGE] = large_px;
	f->atlas = calloc((size_t)f->w * f->h, 1);
	if (!f->atlas || bake_all(f, ttf)) {
		int err = f->atlas ? EINVAL : ENOMEM;

		font_destroy(f);
		f = NULL;
		errno = err;
	}
free_ttf:
	free(ttf);
	return f;
}

void font_destroy(struct font *f)
{
	if (!f) {
		return;
	}
	free(f->atlas);
	free(f);
}

const unsigned char *font_atlas(const struct font *f, int *w, int *h)
{
	*w = f->w;
	*h = f->h;
	return f->atlas;
}

void font_white(const struct font *f, float *s, float *t)
{
	*s = (WHITE_PX / 2.0f) / (float)f->w;
	*t = ((float)f->white_y + WHITE_PX / 2.0f) / (float)f->h;
}

int font_quad(const struct font *f, enum font_size size, int c, float *x,
	      float y, struct font_quad *q)
{
	stbtt_aligned_quad a;
	int r = 0;

	if (c < FONT_FIRST || c >= FONT_FIRST + FONT_CHARS) {
		c = '?';
		r = -1;
	}
	stbtt_GetBakedQuad(f->glyph[size], f->w, f->h, c - FONT_FIRST, x, &y,
			   &a, 1);
	*q = (struct font_quad){ a.x0, a.y0, a.x1, a.y1,
				 a.s0, a.t0, a.s1, a.t1 };
	return r;
}

float font_width(const struct font *f, enum font_size size, const char *text)
{
	float x = 0;
	struct font_quad q;

	for (const char *p = text; *p; p++) {
		font_quad(f, size, (unsigned char)*p, &x, 0, &q);
	}
	return x;
}

float font_px(const struct font *f, enum font_size size)
{
	return f->px[size];
}
