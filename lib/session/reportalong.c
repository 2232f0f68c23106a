/* reportalong.c - see reportalong.h. */
#include "session/reportalong.h"

#include <math.h>

#include "model/anatomy.h"
#include "session/htmlpage.h"

#define STRIPS 3
#define STRIP_TOP 30.0 /* the first strip's plot area, px */
#define STRIP_H 84.0
#define STRIP_GAP 34.0 /* above each strip: its title */
#define FOOT_H 40.0    /* under the last: the names, the times there */
#define COL_W (HTMLPAGE_PLOT_W / ANATOMY_SEGMENTS)
#define HEADROOM 1.2   /* an axis this far above its highest bar: its value
			  is written above it */
#define PAIN_COLOR "#c62828"
#define LOOP_COLOR "#fb8c00"
#define FORCE_COLOR "#1f5fa8"

static const double svg_h = STRIP_TOP + STRIPS * STRIP_H +
			    (STRIPS - 1) * STRIP_GAP + FOOT_H;

/* One strip of bars: its top (px) and its y axis. */
struct strip {
	FILE *o;
	double y0;
	struct htmlpage_axis y;
};

static double strip_y(const struct strip *s, double v)
{
	return htmlpage_px_band(&s->y, v, s->y0, STRIP_H);
}

/* Segment I's column's middle, px. */
static double col_x(int i)
{
	return HTMLPAGE_PLOT_X + (i + 0.5) * COL_W;
}

/* Strip K over 0 .. HI, the segments' columns shaded as the tip's plot's
 * bands. */
static void strip_begin(struct strip *s, FILE *o, int k, double hi)
{
	s->o = o;
	s->y0 = STRIP_TOP + k * (STRIP_H + STRIP_GAP);
	s->y = htmlpage_axis(0, hi, 3);
	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		fprintf(o, "<rect class=\"segment s%d\" x=\"%.1f\" y=\"%.1f\" "
			"width=\"%.1f\" height=\"%.1f\"/>\n", i % 2,
			col_x(i) - COL_W / 2, s->y0, COL_W, STRIP_H);
	}
	htmlpage_yticks(o, &s->y, s->y0, STRIP_H);
	fprintf(o, "<rect class=\"frame\" x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" "
		"height=\"%.1f\"/>\n", HTMLPAGE_PLOT_X, s->y0, HTMLPAGE_PLOT_W,
		STRIP_H);
}

/* The strip's title (HTML) at its top left, its end's x returned: TITLE
 * of about 7 px a character. */
static double strip_title(const struct strip *s, const char *title, int len)
{
	fprintf(s->o, "<text class=\"label\" x=\"%.1f\" y=\"%.1f\">%s</text>\n",
		HTMLPAGE_PLOT_X, s->y0 - 8, title);
	return HTMLPAGE_PLOT_X + 7.0 * len;
}

/* A swatch of COLOR with its NAME at X on S's title line; the next x. */
static double strip_key(const struct strip *s, double x, const char *color,
			const char *name, int len)
{
	fprintf(s->o, "<rect x=\"%.1f\" y=\"%.1f\" width=\"12\" height=\"10\" "
		"fill=\"%s\"/><text class=\"legend\" x=\"%.1f\" y=\"%.1f\">%s"
		"</text>\n", x, s->y0 - 17, color, x + 16, s->y0 - 8, name);
	return x + 26 + 6.5 * len;
}

/* A bar of V in segment I's column, OFF px off its middle, W wide, with
 * its value VALUE written above it and WHAT in its tooltip. */
static void strip_bar(const struct strip *s, int i, double off, double w,
		      double v, const char *color, const char *value,
		      const char *what)
{
	double x = col_x(i) + off, y = strip_y(s, v);

	if (!(v > 0)) {
		return;
	}
	fprintf(s->o, "<rect class=\"bar\" x=\"%.1f\" y=\"%.1f\" "
		"width=\"%.1f\" height=\"%.1f\" fill=\"%s\" "
		"fill-opacity=\".85\"><title>%s: %s %s</title></rect>\n"
		"<text class=\"tick\" x=\"%.1f\" y=\"%.1f\" "
		"text-anchor=\"middle\" stroke=\"#fff\" stroke-width=\"3\" "
		"paint-order=\"stroke\">%s</text>\n", x - w / 2, y, w,
		s->y0 + STRIP_H - y, color, anatomy_segment_name(i), what,
		value, x, y - 3, value);
}

/* A dashed line at V (under the bars, seen through them), keyed with
 * LABEL at the right of the title line. */
static void strip_level(const struct strip *s, double v, const char *label)
{
	const double right = HTMLPAGE_PLOT_X + HTMLPAGE_PLOT_W;

	fprintf(s->o, "<line class=\"threshold\" x1=\"%.1f\" y1=\"%.1f\" "
		"x2=\"%.1f\" y2=\"%.1f\"/><line class=\"threshold\" "
		"x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/><text "
		"class=\"thlabel\" x=\"%.1f\" y=\"%.1f\" "
		"text-anchor=\"end\">%s</text>\n", HTMLPAGE_PLOT_X,
		strip_y(s, v), right, strip_y(s, v), right - 22, s->y0 - 12,
		right, s->y0 - 12, right - 28, s->y0 - 8, label);
}

/* S seconds, short: "0.4 s", "12 s", "305 s". */
static void short_s(char *buf, size_t size, double s)
{
	snprintf(buf, size, s < 10 ? "%.1f s" : "%.0f s", s);
}

/* A bar of each segment's PEAK (one decimal written above it) in COLOR,
 * WHAT in their tooltips. */
static void strip_peaks(const struct strip *s, const double *peak,
			const char *color, const char *what)
{
	char v[32];

	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		snprintf(v, sizeof(v), "%.1f", peak[i]);
		strip_bar(s, i, 0, COL_W * 0.4, peak[i], color, v, what);
	}
}

static void strip_pain(FILE *o, const struct metrics_along *al,
		       const struct metrics_params *p, bool patient)
{
	double peak[ANATOMY_SEGMENTS];
	struct strip s;
	char v[32];

	strip_begin(&s, o, 0, 10);
	strip_title(&s, "Peak pain (0-10)", 16);
	if (!patient) {
		fprintf(o, "<text class=\"label\" x=\"%.1f\" y=\"%.1f\" "
			"text-anchor=\"middle\">no patient: the session ran "
			"without the patient's model</text>\n",
			HTMLPAGE_PLOT_X + HTMLPAGE_PLOT_W / 2,
			s.y0 + STRIP_H / 2 + 4);
		return;
	}
	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		peak[i] = al->seg[i].peak_pain;
	}
	snprintf(v, sizeof(v), "in pain from %g", p->pain_level);
	strip_level(&s, p->pain_level, v);
	strip_peaks(&s, peak, PAIN_COLOR, "peak pain");
}

static void strip_times(FILE *o, const struct metrics_along *al,
			bool patient)
{
	struct strip s;
	double x, hi = 1;
	char v[32];

	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		hi = fmax(hi, fmax(al->seg[i].pain_s, al->seg[i].loop_s));
	}
	strip_begin(&s, o, 1, hi * HEADROOM);
	x = strip_title(&s, "Time (s):", 9) + 8;
	if (patient) {
		x = strip_key(&s, x, PAIN_COLOR, "in pain", 7);
	}
	strip_key(&s, x, LOOP_COLOR, "looped (a bow beyond the loop "
		  "threshold)", 40);
	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		const struct metrics_segment *g = &al->seg[i];

		short_s(v, sizeof(v), g->pain_s);
		strip_bar(&s, i, -COL_W * 0.17, COL_W * 0.3, g->pain_s,
			  PAIN_COLOR, v, "in pain");
		short_s(v, sizeof(v), g->loop_s);
		strip_bar(&s, i, COL_W * 0.17, COL_W * 0.3, g->loop_s,
			  LOOP_COLOR, v, "looped");
	}
}

static void strip_force(FILE *o, const struct metrics_along *al,
			const struct metrics_params *p)
{
	double hi = p->force_threshold_n, peak[ANATOMY_SEGMENTS];
	struct strip s;
	char v[48];

	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		peak[i] = al->seg[i].peak_force_n;
		hi = fmax(hi, peak[i]);
	}
	strip_begin(&s, o, 2, hi * HEADROOM);
	strip_title(&s, "Peak insertion force (N)", 24);
	snprintf(v, sizeof(v), "excessive from %g N", p->force_threshold_n);
	strip_level(&s, p->force_threshold_n, v);
	strip_peaks(&s, peak, FORCE_COLOR, "peak insertion force (N)");
}

/* Under the columns: each segment's name and the time the tip was there. */
static void columns_foot(FILE *o, const struct metrics_along *al)
{
	double y = svg_h - FOOT_H + 16;

	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		fprintf(o, "<text class=\"label\" x=\"%.1f\" y=\"%.1f\" "
			"text-anchor=\"middle\">%s</text><text class=\"tick\" "
			"x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">",
			col_x(i), y, anatomy_segment_name(i), col_x(i), y + 15);
		if (al->seg[i].time_s > 0) {
			htmlpage_duration(o, al->seg[i].time_s);
			fputs(" there", o);
		} else {
			fputs("not reached", o);
		}
		fputs("</text>\n", o);
	}
}

static void along_figure(FILE *o, const struct metrics_along *al,
			 const struct metrics_params *p, bool patient)
{
	fprintf(o, "<figure id=\"pain-along\"><figcaption>Pain along the "
		"colon, next to the force and the loop</figcaption>\n"
		"<svg class=\"plot\" "
		"xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 %d %.0f\" "
		"width=\"%d\" height=\"%.0f\" role=\"img\" aria-label=\"Pain "
		"along the colon\">\n", HTMLPAGE_SVG_W, svg_h, HTMLPAGE_SVG_W,
		svg_h);
	strip_pain(o, al, p, patient);
	strip_times(o, al, patient);
	strip_force(o, al, p);
	columns_foot(o, al);
	fputs("</svg></figure>\n", o);
	if (patient) {
		fputs("<p class=\"none\" style=\"font-size:13px\">Each "
		      "segment: while the tip was in it. A loop hurts where it "
		      "stretches, often behind the tip: the pain episodes "
		      "below name that place.</p>\n", o);
	}
}

/* A row's mark: bad from a severe peak, warn in pain at all. */
static const char *row_mark(const struct metrics_segment *g)
{
	return g->peak_pain >= METRICS_GLOUCESTER_SEVERE_PAIN ? "bad" :
	       g->pain_s > 0 ? "warn" : "";
}

/* S seconds as htmlpage_duration() writes them, "none" for 0. */
static void put_time(FILE *o, double s)
{
	if (s > 0) {
		htmlpage_duration(o, s);
	} else {
		fputs("none", o);
	}
}

static void along_row(FILE *o, int i, const struct metrics_segment *g,
		      bool patient)
{
	fprintf(o, "<tr class=\"%s\"><th>%s</th><td>", row_mark(g),
		anatomy_segment_name(i));
	if (!(g->time_s > 0)) {
		fputs("&ndash;</td><td>&ndash;</td><td>not reached</td>"
		      "<td>&ndash;</td><td>&ndash;</td></tr>\n", o);
		return;
	}
	if (patient) {
		put_time(o, g->pain_s);
		if (g->pain_s > 0) {
			fprintf(o, " (%.0f %%)", 100 * g->pain_s / g->time_s);
		}
		fprintf(o, "</td><td>%.1f", g->peak_pain);
	} else {
		fputs("&ndash;</td><td>&ndash;", o);
	}
	fputs("</td><td>", o);
	htmlpage_duration(o, g->time_s);
	fputs("</td><td>", o);
	put_time(o, g->loop_s);
	fprintf(o, "</td><td>%.1f N</td></tr>\n", g->peak_force_n);
}

static void along_table(FILE *o, const struct metrics_along *al,
			bool patient)
{
	fputs("<table class=\"episodes\" id=\"pain-along-table\"><tr>"
	      "<th>segment</th><th>in pain (share of the time there)</th>"
	      "<th>peak pain (0-10)</th><th>time there</th><th>looped</th>"
	      "<th>peak insertion force</th></tr>\n", o);
	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		along_row(o, i, &al->seg[i], patient);
	}
	fputs("</table>\n", o);
}

void reportalong_write(FILE *o, const struct metrics_along *al,
		       const struct metrics_params *p, bool patient)
{
	if (!al->segments) {
		fputs("<p class=\"none\">no case's anatomy: the segments are "
		      "not known</p>\n", o);
		return;
	}
	along_figure(o, al, p, patient);
	along_table(o, al, patient);
}
