/*
 * viewstats.h - endoview's closing figures (--stats, and every run of
 * --frames N), two lines (three with --pass-times) on stdout that
 * tests/bench/viewer.sh and the system tests read:
 *
 *   endoview: frames=N seconds=S fps=F frame_ms_p50=.. frame_ms_p99=..
 *     age_ms_p50=.. age_ms_p99=.. triangles=N triangles_max=N
 *     gl_errors=N daemon=live|stale|none|replay colon=NAME|none
 *   endoview: layout endo=X,Y,W,H overview=.. panel=.. timeline=..
 *     map=X,Y,W,H
 *   endoview: passes_ms update=P50/P99 image=.. lens=.. scale=..
 *     overview=.. panel=.. swap=..   (only with --pass-times: each pass
 *     of a frame finished before the next, its ms; a pass not drawn
 *     counts 0; update: from the last swap to the drawing)
 *
 * (each on one line), the views' rectangles in pixels from the image's
 * top-left corner, as in its PNG (0,0,0,0: not shown). Main thread; no
 * allocation.
 */
#ifndef ENDOVIEW_VIEWSTATS_H
#define ENDOVIEW_VIEWSTATS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "viewer/hud.h"
#include "viewer/timing.h"

struct viewstats {
	long frames;                 /* drawn */
	double seconds;              /* from the start to the last swap */
	const struct timing *timing; /* the frame times and states' ages */
	uint32_t triangles;          /* in the last frame */
	uint32_t triangles_max;      /* in any frame */
	unsigned long gl_errors;
	const char *daemon;          /* live, stale, none or replay */
	const char *colon;           /* its name, or none */
	enum hud_view view;          /* the last frame's */
	int width, height;           /* the framebuffer's, px */
	bool map_shown;              /* the M key's overlay */
};

/* S's two lines into OUT. */
void viewstats_print(FILE *out, const struct viewstats *s);

#endif
