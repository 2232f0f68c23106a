/* painview.c - see painview.h. */
#include "viewer/painview.h"

#include <math.h>

#define ROUND 32 /* an ellipse's triangles */

static const float skin[4] = { 0.93f, 0.76f, 0.62f, 1 };
static const float flush[4] = { 0.95f, 0.45f, 0.38f, 1 };
static const float rim[4] = { 0.45f, 0.30f, 0.26f, 1 };
static const float ink[4] = { 0.22f, 0.13f, 0.12f, 1 };
static const float mouth[4] = { 0.40f, 0.08f, 0.10f, 1 };
static const float teeth[4] = { 0.97f, 0.96f, 0.92f, 1 };
static const float tear[4] = { 0.55f, 0.80f, 1.00f, 0.9f };
static const float track[4] = { 1, 1, 1, 0.15f };
static const float white[4] = { 0.90f, 0.92f, 0.95f, 1 };
static const float green[4] = { 0.30f, 0.90f, 0.42f, 1 };
static const float amber[4] = { 1.00f, 0.70f, 0.15f, 1 };
static const float red[4] = { 1.00f, 0.27f, 0.22f, 1 };

enum painview_mood painview_mood(double level)
{
	if (!(level >= PAINVIEW_UNEASY_AT)) {
		return PAINVIEW_CALM;
	}
	if (level < PAINVIEW_GRIMACE_AT) {
		return PAINVIEW_UNEASY;
	}
	return level < PAINVIEW_CRYING_AT ? PAINVIEW_GRIMACE : PAINVIEW_CRYING;
}

const char *painview_mood_name(enum painview_mood m)
{
	static const char *const name[] = {
		[PAINVIEW_CALM] = "calm", [PAINVIEW_UNEASY] = "uneasy",
		[PAINVIEW_GRIMACE] = "grimace",
		[PAINVIEW_CRYING] = "crying out",
	};

	return m >= PAINVIEW_CALM && m <= PAINVIEW_CRYING ? name[m] : "?";
}

const float *painview_rgb(double level)
{
	if (!(level >= PAINVIEW_GRIMACE_AT)) {
		return green;
	}
	return level < PAINVIEW_CRYING_AT ? amber : red;
}

/* 0..1: how far LEVEL is from A to B. */
static float ramp(double level, double a, double b)
{
	double f = (level - a) / (b - a);

	return (float)(isfinite(f) ? fmax(0, fmin(1, f)) : 0);
}

static void ellipse(struct draw2d *d, float cx, float cy, float a, float b,
		    const float rgba[4])
{
	float v[6];

	for (int k = 0; k < ROUND; k++) {
		float t0 = 2 * (float)M_PI * k / ROUND;
		float t1 = 2 * (float)M_PI * (k + 1) / ROUND;

		v[0] = cx;
		v[1] = cy;
		v[2] = cx + a * cosf(t0);
		v[3] = cy + b * sinf(t0);
		v[4] = cx + a * cosf(t1);
		v[5] = cy + b * sinf(t1);
		draw2d_triangle(d, v, rgba);
	}
}

/* One side's brow and eye (SIDE -1 the patient's right, on the left of
 * the picture; +1 the other), shutting as PAIN (0..1) rises. */
static void eye(struct draw2d *d, float cx, float cy, float r, float side,
		float pain)
{
	float ex = cx + side * 0.36f * r, ey = cy - 0.10f * r;
	float open = 1 - ramp(pain * PAINVIEW_MAX, 1.5, 5.0);
	float w = fmaxf(1.5f, r * 0.07f);
	float drop = pain * 0.16f * r; /* the brow's inner end drawn down */

	draw2d_line(d, ex + side * 0.2f * r, ey - 0.26f * r + drop * 0.2f,
		    ex - side * 0.18f * r, ey - 0.24f * r + drop, w, ink);
	if (open > 0.35f) {
		ellipse(d, ex, ey, 0.09f * r, 0.11f * r * open, ink);
		return;
	}
	/* squeezed shut: a chevron pointing in */
	draw2d_line(d, ex + side * 0.12f * r, ey - 0.08f * r,
		    ex - side * 0.10f * r, ey, w, ink);
	draw2d_line(d, ex - side * 0.10f * r, ey, ex + side * 0.12f * r,
		    ey + 0.08f * r, w, ink);
	if (pain * PAINVIEW_MAX >= PAINVIEW_CRYING_AT) {
		ellipse(d, ex + side * 0.08f * r, ey + 0.26f * r, 0.05f * r,
			0.09f * r, tear);
	}
}

/* The mouth: a curve from a smile to a frown, else a grimace, else open. */
static void face_mouth(struct draw2d *d, float cx, float cy, float r,
		       double level)
{
	float my = cy + 0.42f * r, w = fmaxf(1.5f, r * 0.07f);
	float bend = 0.10f * r * (1 - 2 * ramp(level, 0, PAINVIEW_GRIMACE_AT));
	float x0 = cx - 0.3f * r, y0 = my - bend;

	if (level >= PAINVIEW_CRYING_AT) {
		ellipse(d, cx, my + 0.02f * r, 0.2f * r,
			(0.16f + 0.08f * ramp(level, 7, 10)) * r, mouth);
		draw2d_rect(d, cx - 0.13f * r, my - 0.12f * r, 0.26f * r,
			    0.05f * r, teeth);
		return;
	}
	if (level >= PAINVIEW_GRIMACE_AT) {
		draw2d_rect(d, cx - 0.34f * r, my - 0.09f * r, 0.68f * r,
			    0.18f * r, mouth);
		draw2d_rect(d, cx - 0.3f * r, my - 0.05f * r, 0.6f * r,
			    0.1f * r, teeth);
		draw2d_line(d, cx - 0.3f * r, my, cx + 0.3f * r, my, 1, rim);
		return;
	}
	for (int k = 1; k <= 8; k++) {
		float u = -1 + 2 * k / 8.0f;
		float x1 = cx + 0.3f * r * u, y1 = my - bend * u * u;

		draw2d_line(d, x0, y0, x1, y1, w, ink);
		x0 = x1;
		y0 = y1;
	}
}

void painview_face(struct draw2d *d, float cx, float cy, float r,
		   double level)
{
	float s = ramp(level, 0, PAINVIEW_MAX), f = 0.55f * s;
	float head[4];

	for (int k = 0; k < 3; k++) {
		head[k] = skin[k] + (flush[k] - skin[k]) * f;
	}
	head[3] = 1;
	ellipse(d, cx, cy, r * 1.04f, r * 1.1f, rim);
	ellipse(d, cx, cy, r, r * 1.06f, head);
	eye(d, cx, cy, r, -1, s);
	eye(d, cx, cy, r, 1, s);
	face_mouth(d, cx, cy, r, isfinite(level) ? level : 0);
}

void painview_bar(struct draw2d *d, float x, float y, float w, float h,
		  double level)
{
	float f = ramp(level, 0, PAINVIEW_MAX);
	float mark = x + w * (float)(PAINVIEW_GRIMACE_AT / PAINVIEW_MAX);

	draw2d_rect(d, x, y, w, h, track);
	draw2d_rect(d, x, y, f * w, h, painview_rgb(level));
	for (int k = 1; k < 10; k++) {
		draw2d_rect(d, x + w * k / 10.0f, y + h * 0.7f, 1, h * 0.3f,
			    track);
	}
	draw2d_rect(d, mark - 1, y - 3, 2, h + 6, white);
}
