/* loginview.c - see loginview.h. */
#include "viewer/loginview.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const float veil[4] = { 0, 0, 0, 0.78f };
static const float box_rgb[4] = { 0.10f, 0.12f, 0.16f, 0.96f };
static const float field_rgb[4] = { 0.02f, 0.03f, 0.05f, 1 };
static const float focus_rgb[4] = { 0.30f, 0.90f, 0.42f, 1 };
static const float edge_rgb[4] = { 0.35f, 0.38f, 0.45f, 1 };
static const float white[4] = { 0.90f, 0.92f, 0.95f, 1 };
static const float dim[4] = { 0.55f, 0.58f, 0.66f, 1 };
static const float red[4] = { 1.00f, 0.35f, 0.30f, 1 };

/* Where things go: the box and its text's sizes. */
struct form {
	struct draw2d *d;
	float x, y, w;   /* the box's left, the pen's top, its width */
	float small, large, pad;
};

/* A rectangle's outline, WIDTH pixels. */
static void outline(struct draw2d *d, float x, float y, float w, float h,
		    float width, const float rgb[4])
{
	draw2d_rect(d, x, y, w, width, rgb);
	draw2d_rect(d, x, y + h - width, w, width, rgb);
	draw2d_rect(d, x, y, width, h, rgb);
	draw2d_rect(d, x + w - width, y, width, h, rgb);
}

/* TEXT in SIZE at the pen, cut to the box; the pen moves down. */
static void text_line(struct form *f, enum font_size size, const float rgb[4],
		      const char *text)
{
	float px = size == FONT_LARGE ? f->large : f->small;
	char cut[256];
	size_t n = (size_t)snprintf(cut, sizeof(cut), "%s", text);

	while (n > 1 &&
	       draw2d_text_width(f->d, size, cut) > f->w - 2 * f->pad) {
		cut[--n] = '\0';
	}
	draw2d_text(f->d, size, f->x + f->pad, f->y + px, rgb, cut);
	f->y += px * 1.5f;
}

/* TEXT (UTF-8) as the font draws it into OUT: each character beyond
 * ASCII one '?' (not one a byte). */
static void ascii(const char *text, char *out, size_t size)
{
	size_t n = 0;

	for (; *text && n + 1 < size; text++) {
		unsigned char c = (unsigned char)*text;

		if ((c & 0xc0) != 0x80) {
			out[n++] = c < 0x80 ? (char)c : '?';
		}
	}
	out[n] = '\0';
}

/* The field LABEL holding TEXT (or, with DOTS >= 0, that many dots). */
static void field(struct form *f, const char *label, const char *text,
		  long dots, bool focus, bool caret)
{
	float fx = f->x + f->pad, fw = f->w - 2 * f->pad;
	float fh = f->large * 1.6f, tx = fx + f->pad * 0.6f;
	float base = f->y + f->small * 1.2f + fh * 0.5f + f->large * 0.4f;
	float end = tx;
	char shown[ACCOUNTS_NAME_MAX + 1];

	draw2d_text(f->d, FONT_SMALL, fx, f->y + f->small, dim, label);
	f->y += f->small * 1.4f;
	draw2d_rect(f->d, fx, f->y, fw, fh, field_rgb);
	outline(f->d, fx, f->y, fw, fh, focus ? 2 : 1,
		focus ? focus_rgb : edge_rgb);
	if (dots < 0) {
		ascii(text, shown, sizeof(shown));
		end += draw2d_text(f->d, FONT_LARGE, tx, base - f->small * 0.2f,
				   white, shown);
	}
	for (long k = 0; k < dots; k++) {
		draw2d_disc(f->d, end + f->large * 0.35f, f->y + fh / 2,
			    f->large * 0.22f, white);
		end += f->large * 0.75f;
	}
	if (focus && caret) {
		draw2d_rect(f->d, end + 2, f->y + fh * 0.2f, 2, fh * 0.6f,
			    focus_rgb);
	}
	f->y += fh + f->small;
}

void loginview_draw(struct draw2d *d, const struct login *l, int w, int h,
		    double t_s)
{
	struct form f = { .d = d };
	bool caret = fmod(t_s, 1.0) < 0.6;
	float bh;

	if (l->stage != LOGIN_ASK) {
		return;
	}
	f.small = draw2d_px(d, FONT_SMALL);
	f.large = draw2d_px(d, FONT_LARGE);
	f.pad = f.small;
	f.w = fminf((float)w * 0.9f, f.small * 34);
	bh = f.large * 4.7f + f.small * 7.8f + f.pad * 1.2f; /* as below */
	f.x = ((float)w - f.w) / 2;
	f.y = fmaxf(0, ((float)h - bh) / 2);
	draw2d_rect(d, 0, 0, (float)w, (float)h, veil);
	draw2d_rect(d, f.x, f.y, f.w, bh, box_rgb);
	outline(d, f.x, f.y, f.w, bh, 1, edge_rgb);
	f.y += f.pad * 0.6f;
	text_line(&f, FONT_LARGE, white, "Who is training?");
	field(&f, "Name", l->name, -1, l->focus == LOGIN_NAME, caret);
	field(&f, "PIN", "", (long)login_pin_chars(l),
	      l->focus == LOGIN_PIN, caret);
	text_line(&f, FONT_SMALL, red, *l->error ? l->error : "");
	text_line(&f, FONT_SMALL, dim, "Enter: next, then log in   Tab: the "
		  "other field   Esc: empty");
}
