/*
 * painview.h - the patient's pain in the patient panel (the HUD's,
 * hud.h; issue 23): a drawn face whose expression follows the level,
 * and the level as a bar.
 *
 * The face is flat, in the HUD's colours: a head that flushes as the
 * level rises, brows drawn down and in, eyes that narrow and shut, and a
 * mouth that goes from a smile to a flat line, to a grimace (teeth shown)
 * and, crying out, open; tears when crying out. The moods, by the level
 * (0..10, the clinical scale the daemon publishes):
 *
 *   below PAINVIEW_UNEASY_AT  2  calm
 *   below PAINVIEW_GRIMACE_AT 4  uneasy
 *   below PAINVIEW_CRYING_AT  7  grimace (in pain: the assessment's 4)
 *   from 7                       crying out
 *
 * The bar runs from 0 to 10, green below PAINVIEW_GRIMACE_AT, amber
 * below PAINVIEW_CRYING_AT, red above, with the threshold of pain (4)
 * marked.
 *
 * Main thread; the drawing functions queue into D (draw2d.h) between
 * draw2d_begin() and draw2d_end(). painview_mood() is pure.
 */
#ifndef ENDOVIEW_PAINVIEW_H
#define ENDOVIEW_PAINVIEW_H

#include "viewer/draw2d.h"

#define PAINVIEW_UNEASY_AT 2.0
#define PAINVIEW_GRIMACE_AT 4.0 /* the assessment's "in pain" */
#define PAINVIEW_CRYING_AT 7.0
#define PAINVIEW_MAX 10.0

enum painview_mood {
	PAINVIEW_CALM = 0,
	PAINVIEW_UNEASY,
	PAINVIEW_GRIMACE,
	PAINVIEW_CRYING,
};

/* The mood at LEVEL (NaN: calm). */
enum painview_mood painview_mood(double level);

/* "calm", "uneasy", "grimace", "crying out". */
const char *painview_mood_name(enum painview_mood m);

/* The level's colour: green, amber, red as the bar's. */
const float *painview_rgb(double level);

/* The face at LEVEL centred at (CX, CY), R pixels its head's radius. */
void painview_face(struct draw2d *d, float cx, float cy, float r,
		   double level);

/* The bar of LEVEL in the rectangle at (X, Y), W x H pixels. */
void painview_bar(struct draw2d *d, float x, float y, float w, float h,
		  double level);

#endif
