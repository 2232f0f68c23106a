/*
 * timing.h - endoview's figures: the time from one frame's swap to the
 * next (frame time) and the age of the state each frame shows (the swap's
 * time less the state's publish_ns), kept sample by sample for their
 * percentiles, and a running frame rate for the HUD.
 *
 * Keeps the last TIMING_SAMPLES of each. Main thread; allocates once.
 */
#ifndef ENDOVIEW_TIMING_H
#define ENDOVIEW_TIMING_H

#include <stddef.h>

#define TIMING_SAMPLES 65536

enum timing_kind {
	TIMING_FRAME = 0, /* ms from swap to swap */
	TIMING_AGE,       /* ms from the state's publishing to the swap */
	/* --pass-times: each pass of a frame, finished (glFinish), ms */
	TIMING_PASS_UPDATE,   /* from the last swap: events, the state, the
				 colon's moved spans laid again */
	TIMING_PASS_IMAGE,    /* the window cleared, the endoscopic image
				 (endo.h) */
	TIMING_PASS_LENS,     /* what covers the lens (lensfx.h) */
	TIMING_PASS_SCALE,    /* the image scaled up (imagescale.h) */
	TIMING_PASS_OVERVIEW, /* the overview (overview.h) */
	TIMING_PASS_PANEL,    /* the panel and labels (hud.h, draw2d.h) */
	TIMING_PASS_SWAP,     /* the swap to the screen */
	TIMING_KINDS,
};

struct timing;

/* NULL on ENOMEM. */
struct timing *timing_create(void);

/* NULL is fine. */
void timing_destroy(struct timing *t);

void timing_add(struct timing *t, enum timing_kind k, double ms);

/* Samples of K kept. */
size_t timing_count(const struct timing *t, enum timing_kind k);

/* The Q-quantile (0..1) of K's samples, nearest rank; 0 without any. */
double timing_quantile(const struct timing *t, enum timing_kind k, double q);

/* Frames per second over the last second or so of frame times. */
double timing_fps(const struct timing *t);

#endif
