/* patientview.c - see patientview.h. */
#include "viewer/patientview.h"

#include "viewer/burstmark.h"

#include <math.h>
#include <stdio.h>

#define ROUND 28               /* a disc's triangles */
#define DIAL_FROM_RAD (-1.25 * M_PI) /* 0 mmHg: lower left */
#define DIAL_SWEEP_RAD (1.5 * M_PI)  /* clockwise over the top */
#define DIAL_TICK_MMHG 20.0

static const float skin[4] = { 0.86f, 0.66f, 0.55f, 1 };
static const float belly[4] = { 0.93f, 0.74f, 0.62f, 1 };
static const float spine[4] = { 0.45f, 0.30f, 0.26f, 1 };
static const float table[4] = { 0.55f, 0.58f, 0.66f, 1 };
static const float hand[4] = { 1.00f, 0.70f, 0.15f, 1 };
static const float white[4] = { 0.90f, 0.92f, 0.95f, 1 };
static const float track[4] = { 1, 1, 1, 0.15f };
static const float green[4] = { 0.30f, 0.90f, 0.42f, 1 };
static const float amber[4] = { 1.00f, 0.70f, 0.15f, 1 };
static const float red[4] = { 1.00f, 0.27f, 0.22f, 1 };

/* The figure's turn: the angle that takes gravity DOWN (body frame) to the
 * screen's down, and where body point (X, Y) m lands. */
struct pose {
	float cx, cy, px_per_m, c, s;
};

static void place(const struct pose *o, double x, double y, float *sx,
		  float *sy)
{
	double bx = x, by = y - PATIENTVIEW_BODY_Y_M;

	*sx = o->cx + o->px_per_m * (float)(bx * o->c - by * o->s);
	*sy = o->cy + o->px_per_m * (float)(bx * o->s + by * o->c);
}

/* An ellipse of half-axes A, B (m, along the body's x, y) about (X, Y). */
static void ellipse(struct draw2d *d, const struct pose *o, double x,
		    double y, double a, double b, const float rgba[4])
{
	float c[2], v[6];

	place(o, x, y, &c[0], &c[1]);
	for (int k = 0; k < ROUND; k++) {
		double t0 = 2 * M_PI * k / ROUND, t1 = 2 * M_PI * (k + 1) /
						      ROUND;

		v[0] = c[0];
		v[1] = c[1];
		place(o, x + a * cos(t0), y + b * sin(t0), &v[2], &v[3]);
		place(o, x + a * cos(t1), y + b * sin(t1), &v[4], &v[5]);
		draw2d_triangle(d, v, rgba);
	}
}

/* The pressing hand: an arrow ending at SITE's pad, along its push. */
static void draw_hand(struct draw2d *d, const struct pose *o,
		      const struct model_site *site)
{
	const double *at = site->position_m, *dir = site->direction;
	double n = hypot(dir[0], dir[1]), len = 0.11, ux, uy;
	float tip[2], tail[2], head[6], w = o->px_per_m * 0.02f;

	if (!(n > 0.1)) {
		return; /* pushed along the body's length: not in this view */
	}
	ux = dir[0] / n;
	uy = dir[1] / n;
	place(o, at[0], at[1], &tip[0], &tip[1]);
	place(o, at[0] - len * ux, at[1] - len * uy, &tail[0], &tail[1]);
	draw2d_line(d, tail[0], tail[1], tip[0], tip[1], fmaxf(2, w * 0.6f),
		    hand);
	place(o, at[0] + 0.01 * ux, at[1] + 0.01 * uy, &head[0], &head[1]);
	place(o, at[0] - 0.035 * ux - 0.025 * uy,
	      at[1] - 0.035 * uy + 0.025 * ux, &head[2], &head[3]);
	place(o, at[0] - 0.035 * ux + 0.025 * uy,
	      at[1] - 0.035 * uy - 0.025 * ux, &head[4], &head[5]);
	draw2d_triangle(d, head, hand);
}

/* The patient's left and right flanks, lettered. */
static void sides(struct draw2d *d, const struct pose *o, double a)
{
	static const char *const letter[2] = { "L", "R" };
	float px = draw2d_px(d, FONT_SMALL), x, y;

	for (int k = 0; k < 2; k++) {
		place(o, (k ? -0.62 : 0.62) * a, PATIENTVIEW_BODY_Y_M, &x, &y);
		draw2d_text(d, FONT_SMALL,
			    x - draw2d_text_width(d, FONT_SMALL, letter[k]) / 2,
			    y + px * 0.35f, spine, letter[k]);
	}
}

void patientview_figure(struct draw2d *d, float cx, float cy, float size,
			const struct endosim_patient_state *p,
			const struct model *m)
{
	double a = PATIENTVIEW_BODY_W_M / 2, b = PATIENTVIEW_BODY_D_M / 2;
	double phi = atan2(p->down[1], p->down[0]);
	double turn = M_PI / 2 - phi;
	struct pose o = {
		.cx = cx, .px_per_m = size / (float)(2.3 * a),
		.c = (float)cos(turn), .s = (float)sin(turn),
	};
	/* the lowest point of the turned torso rests on the table */
	float reach = o.px_per_m * (float)hypot(a * o.s, b * o.c);

	if (!(hypot(p->down[0], p->down[1]) > 0.5)) {
		o.c = 1; /* no gravity in the cross-section: drawn supine */
		o.s = 0;
		reach = o.px_per_m * (float)b;
	}
	o.cy = cy + size * 0.42f - reach;
	draw2d_rect(d, cx - size / 2, o.cy + reach, size, fmaxf(2, size / 30),
		    table);
	ellipse(d, &o, 0, PATIENTVIEW_BODY_Y_M, a, b, skin);
	ellipse(d, &o, 0, PATIENTVIEW_BODY_Y_M - 0.55 * b, 0.55 * a, 0.5 * b,
		belly);
	ellipse(d, &o, 0, PATIENTVIEW_BODY_Y_M + 0.75 * b, 0.1 * a, 0.12 * b,
		spine);
	sides(d, &o, a);
	if (m && p->hand_site >= 0 && p->hand_site < m->sites) {
		draw_hand(d, &o, &m->site[p->hand_site]);
	}
}

/* A point of the dial at MMHG, R pixels from its centre. */
static void dial_at(float cx, float cy, float r, double mmhg, float *x,
		    float *y)
{
	double f = fmax(0, fmin(1, mmhg / PATIENTVIEW_GAUGE_MMHG));
	double t = DIAL_FROM_RAD + f * DIAL_SWEEP_RAD;

	*x = cx + r * (float)cos(t);
	*y = cy + r * (float)sin(t);
}

/* The arc from A to B mmHg, W pixels wide. */
static void arc(struct draw2d *d, float cx, float cy, float r, double a,
		double b, float w, const float rgba[4])
{
	int n = (int)ceil(48 * fabs(b - a) / PATIENTVIEW_GAUGE_MMHG) + 1;
	float x0, y0, x1, y1;

	dial_at(cx, cy, r, a, &x0, &y0);
	for (int k = 1; k <= n; k++) {
		dial_at(cx, cy, r, a + (b - a) * k / n, &x1, &y1);
		draw2d_line(d, x0, y0, x1, y1, w, rgba);
		x0 = x1;
		y0 = y1;
	}
}

/* A mark across the dial at MMHG, out to R1 from R0. */
static void mark(struct draw2d *d, float cx, float cy, float r0, float r1,
		 double mmhg, float w, const float rgba[4])
{
	float x0, y0, x1, y1;

	dial_at(cx, cy, r0, mmhg, &x0, &y0);
	dial_at(cx, cy, r1, mmhg, &x1, &y1);
	draw2d_line(d, x0, y0, x1, y1, w, rgba);
}

static const float *level_rgb(double mmhg, double relief, double burst)
{
	if (!isnan(burst) && mmhg >= burst) {
		return red;
	}
	return mmhg > PATIENTVIEW_HIGH_MMHG || (relief > 0 && mmhg >= relief) ?
		       amber : green;
}

void patientview_gauge(struct draw2d *d, float cx, float cy, float radius,
		       double pressure_pa, double relief_pa, double burst_pa)
{
	double p = pressure_pa / BURSTMARK_PA_PER_MMHG;
	double relief = relief_pa / BURSTMARK_PA_PER_MMHG;
	double burst = burst_pa / BURSTMARK_PA_PER_MMHG;
	float w = fmaxf(2, radius / 7), x, y, tw;
	char text[32];

	p = isfinite(p) ? p : 0;
	arc(d, cx, cy, radius, 0, PATIENTVIEW_GAUGE_MMHG, w, track);
	if (!isnan(burst) && burst < PATIENTVIEW_GAUGE_MMHG) {
		arc(d, cx, cy, radius, burst, PATIENTVIEW_GAUGE_MMHG, w * 0.5f,
		    red);
	}
	arc(d, cx, cy, radius, 0, fmax(0, p), w,
	    level_rgb(p, relief, burst));
	for (double t = 0; t <= PATIENTVIEW_GAUGE_MMHG; t += DIAL_TICK_MMHG) {
		mark(d, cx, cy, radius - w, radius - 2 * w, t, 1, track);
	}
	if (relief > 0) {
		mark(d, cx, cy, radius - 2.2f * w, radius + w, relief, 3,
		     white);
	}
	if (!isnan(burst) && burst < PATIENTVIEW_GAUGE_MMHG) {
		mark(d, cx, cy, radius - 2.2f * w, radius + w, burst, 3, red);
	}
	dial_at(cx, cy, radius - 1.5f * w, fmax(0, p), &x, &y);
	draw2d_line(d, cx, cy, x, y, 2, white);
	snprintf(text, sizeof(text), "%.0f", p);
	tw = draw2d_text_width(d, FONT_SMALL, text);
	draw2d_text(d, FONT_SMALL, cx - tw / 2, cy + radius * 0.6f, white,
		    text);
	tw = draw2d_text_width(d, FONT_SMALL, "mmHg");
	draw2d_text(d, FONT_SMALL, cx - tw / 2,
		    cy + radius * 0.6f + draw2d_px(d, FONT_SMALL), white,
		    "mmHg");
}
