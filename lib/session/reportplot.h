/*
 * reportplot.h - a session's records plotted over its time, for the
 * instructor's report (report.h) and its comparison with a reference
 * (reportcompare.h): the time axis (s, or min past 5 min: the plot's
 * xscale) from the first record (the plot's t0_ns), and each series
 * decimated to the minimum and maximum of each pixel column, in the order
 * they came, so that every peak survives. Inline SVG into the plot's
 * stream (htmlpage.h).
 *
 * Not for the force loop: writes. Any thread; no allocation.
 */
#ifndef ENDOSIM_REPORTPLOT_H
#define ENDOSIM_REPORTPLOT_H

#include "proto/session_file.h"
#include "session/htmlpage.h"

/* A series: its NAME (HTML) and its value at a record, GET(R, ARG), NaN
 * where it has none. */
struct reportplot_series {
	const char *name;
	double (*get)(const struct session_record *r, int arg);
	int arg;
};

/* A plot over the session's time, its y axis over YLO .. YHI with
 * YLABEL (htmlpage_plot_begin(); P's x axis set by the caller). */
void reportplot_begin(struct htmlpage_plot *p, const char *id,
		      const char *title, double ylo, double yhi,
		      const char *ylabel);

/* S over F's records, in COLOR, from P's t0_ns. */
void reportplot_series(const struct htmlpage_plot *p,
		       const struct session_file *f,
		       const struct reportplot_series *s, const char *color);

/* *LO and *HI widened to every finite value of the N series S over F. */
void reportplot_range(const struct session_file *f,
		      const struct reportplot_series *s, int n, double *lo,
		      double *hi);

/* A series' GET: the tip's place along the colon (m) while inserted. */
double reportplot_tip_s(const struct session_record *r, int arg);

#endif
