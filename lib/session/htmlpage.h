/*
 * htmlpage.h - what the instructor's pages share (report.h: a session's;
 * traineepage.h: a trainee's course): one self-contained HTML page (inline
 * CSS and SVG, no scripts, no external assets) written to a temporary
 * name and renamed, its style, escaped text, durations, and plots drawn
 * as inline SVG with axes, ticks, units, threshold lines and colours.
 *
 * A plot is HTMLPAGE_SVG_W x HTMLPAGE_SVG_H px, its area inside at
 * HTMLPAGE_PLOT_X, _Y of HTMLPAGE_PLOT_W x _H px. Values outside an axis
 * are drawn at its end.
 *
 * Not for the force loop: writes files. Any thread; no shared state.
 */
#ifndef ENDOSIM_HTMLPAGE_H
#define ENDOSIM_HTMLPAGE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define HTMLPAGE_SVG_W 1040
#define HTMLPAGE_SVG_H 250
#define HTMLPAGE_PLOT_X 70.0 /* the plot area inside the svg, px */
#define HTMLPAGE_PLOT_Y 34.0
#define HTMLPAGE_PLOT_W 950.0
#define HTMLPAGE_PLOT_H 176.0

/* The page's style sheet: sections, tables (rows of class good, bad,
 * warn), figures, the plots' classes (grid, frame, tick, label, legend,
 * series, key, threshold, thlabel, band force/loop, segment, event). */
extern const char htmlpage_style[];

/*
 * Creates DIR if missing and opens DIR/index.html's temporary file; its
 * name into TMP (SIZE bytes). The stream, or NULL with errno set.
 */
FILE *htmlpage_create(const char *dir, char *tmp, size_t size);

/*
 * Closes O (htmlpage_create()'s, on TMP) and renames it to DIR/index.html;
 * on any error the temporary file is removed. 0 or -errno (-EIO: a write
 * failed).
 */
int htmlpage_commit(FILE *o, const char *tmp, const char *dir);

/* Writes TEXT to OUT with & < > " ' escaped (NULL: nothing). */
void htmlpage_escape(FILE *out, const char *text);

/* S seconds as "12 min 05 s" or "42.5 s"; a dash when < 0 or not finite. */
void htmlpage_duration(FILE *out, double s);

/* A row of a table of measures (class "metrics"): WHAT, the row marked
 * MARK ("good", "bad", "warn" or ""), then the caller's value, then NOTE
 * (HTML) with htmlpage_row_end(). */
void htmlpage_row_begin(FILE *o, const char *what, const char *mark);
void htmlpage_row_end(FILE *o, const char *note);

/* One of six distinct colours, for the I-th series. */
const char *htmlpage_color(int i);

struct htmlpage_axis {
	double lo, hi, step;
};

/* An axis over LO .. HI with about TICKS round steps (1, 2, 5 x 10^k). */
struct htmlpage_axis htmlpage_axis(double lo, double hi, int ticks);

struct htmlpage_plot {
	FILE *out;
	struct htmlpage_axis x, y;
	double xscale;       /* x values per unit of the x axis (s per min) */
	uint64_t t0_ns;      /* a time axis' zero: the caller's clock */
};

/* The x, y pixel of a value X (before xscale) and Y. */
double htmlpage_px_x(const struct htmlpage_plot *p, double x);
double htmlpage_px_y(const struct htmlpage_plot *p, double y);

/*
 * A y axis over a band of the plot's width from TOP px down HEIGHT px (a
 * plot's: HTMLPAGE_PLOT_Y, _H; a figure of several strips: each strip's):
 * the pixel of V on axis Y, and Y's grid lines and tick labels into O.
 */
double htmlpage_px_band(const struct htmlpage_axis *y, double v, double top,
			double height);
void htmlpage_yticks(FILE *o, const struct htmlpage_axis *y, double top,
		     double height);

/*
 * Opens a figure ID with TITLE (both as HTML, not escaped here) and its
 * svg; sets P's y axis over YLO .. YHI and draws both axes (P->x set by
 * the caller) with their labels.
 */
void htmlpage_plot_begin(struct htmlpage_plot *p, const char *id,
			 const char *title, double ylo, double yhi,
			 const char *xlabel, const char *ylabel);
void htmlpage_plot_end(struct htmlpage_plot *p);

/* A dashed horizontal line at Y with LABEL (HTML) at its right end. */
void htmlpage_plot_hline(const struct htmlpage_plot *p, double y,
			 const char *label);

#endif
