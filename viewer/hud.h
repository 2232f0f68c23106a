/*
 * hud.h - endoview's window layout and its head-up display: the panel
 * beside the endoscopic image with the daemon's state (IDLE, ENABLED,
 * FAULT with its cause, ESTOP), the insertion depth and where the tip is
 * (the colon's segment), the force on each axis as bars (what the force
 * model asks for, what the safety filter lets through), the parts of the
 * force (contact, friction, loop; the wheels' contact, wire tension,
 * elastic return), a strip chart of the last seconds, a loop warning
 * (a mobile segment bowed beyond the threshold the session's metrics
 * count a loop from), the frame rate, and the keys; banners over the image when the daemon is
 * missing or stale, or the colon is loading. In the rod model (struct
 * endosim_rod_state) the first line names it, a line gives how far each
 * mobile segment has moved (its loop, published in bow_m), and the parts
 * of the force are the tube's pull at the carriage and the wall's
 * contacts along the tube, their force and friction.
 *
 * With the patient enabled (struct endosim_patient_state) the patient
 * panel takes the place of the force's parts and the chart: the position
 * as a small figure, the gas's pressure as a gauge (patientview.h) and
 * the patient's face, whose expression follows the pain level (issue
 * 23), side by side, under them the level as a bar from 0 to 10 with the
 * threshold of pain (4) marked (painview.h), and lines for the level
 * (the mood, the cause, the place), the vital signs (heart rate, oxygen
 * saturation, sedation), the position (and the turn in progress), the
 * gas, the assistant's hand, the valves, the lens and the voice's state
 * (hud_info voice); PERFORATED in red once a wall tore. A
 * perforation (by the gas or by the tip) is also a red banner across
 * the top of the image, "PERFORATION: sigmoid". A compact panel has
 * the lines without the pictures, the patient's before the force's
 * bars, the position and the gas on one line where it fits.
 *
 * A replay (endoview --replay) shows the recorded state, fault and forces
 * the same way, with the replay's lines in place of the state's hint
 * (REPLAY, the trainee and the case; the time, the duration, the speed,
 * PAUSED) and under them the timeline, a bar to click along; the chart
 * is the record's last seconds; the footer gives the replay's keys.
 *
 * Layout: the image is a square as high as the window (less room for the
 * panel in a narrow window) on the right, the panel on the left; with
 * both views, the overview is an inset at the bottom of the panel and the
 * panel above it compact (no parts of the force, no chart). The footer
 * (the keys or the rig's last word, the frame rate) keeps the panel's
 * bottom; what does not fit above it is left out from the first thing
 * that does not, the rest with it (the panel's order puts the least
 * needed last: the voice, the lens, the valves), and a line says how
 * many ("+ 3 more lines: no room here") rather than writing over the
 * overview. The keys (hud_info help) take the overview's inset too: the
 * panel then reaches the window's bottom.
 *
 * Main thread, with the GL context current (it draws through draw2d.h).
 */
#ifndef ENDOVIEW_HUD_H
#define ENDOVIEW_HUD_H

#include <stdbool.h>
#include <stdint.h>

#include "viewer/draw2d.h"
#include "viewer/endo.h"
#include "proto/endosim_shm.h"
#include "viewer/link.h"
#include "viewer/model.h"

#define HUD_CHART_S 6.0      /* seconds in the strip chart */
#define HUD_LINES 32         /* lines of text a panel keeps (hud_said()) */
#define HUD_LINE 256         /* characters a line, its NUL included */

enum hud_view {
	HUD_VIEW_ENDO = 0, /* the endoscopic image and the panel */
	HUD_VIEW_OVERVIEW, /* the overview in the image's place */
	HUD_VIEW_BOTH,     /* the image, the overview inset in the panel */
	HUD_VIEWS,
};

/* Rectangles in framebuffer pixels, GL's origin; w = 0: not shown. */
struct hud_layout {
	struct endo_rect endo;
	struct endo_rect overview;
	struct endo_rect panel;
	struct endo_rect timeline; /* a replay's, in the panel under its lines */
};

/* A replay's clock and what it plays. */
struct hud_replay {
	const char *trainee, *case_name;
	double t_s, duration_s;  /* from the first record */
	double speed;
	bool paused;
	size_t records;
};

/* What the frame knows, for the display. */
struct hud_info {
	enum link_status link;
	const char *link_problem;  /* why there is no daemon */
	double stale_s;
	const struct endosim_state *st; /* NULL: none yet */
	double loop_threshold_m;   /* a loop, as the metrics count one (the
				      link's or the replay's) */
	const struct model *m;     /* NULL: no colon yet */
	bool loading;              /* the colon is being fetched */
	const char *rig_problem;   /* why the viewer cannot command */
	const char *rig_said;      /* the last command's outcome */
	bool driving;              /* hand input goes through */
	double fps;
	uint32_t triangles;
	double age_ms;             /* of the state shown */
	bool help;                 /* the keys in place of the forces */
	bool compact;              /* no room for the force's parts, chart */
	const struct hud_replay *replay; /* NULL: live */
	/* the patient's gauge: [patient] relief_pa (<= 0: none) and
	   wall_strength_n_per_m (<= 0: not known, no burst mark) */
	double relief_pa, strength_n_per_m;
	const char *voice;         /* the patient's voice: on, muted, or why
				      there is none (NULL: not said) */
	const char *trainee;       /* who trains at the rig (login.h); NULL
				      or "": nobody, no line */
};

struct hud;

/* The layout of VIEW in a W x H framebuffer. */
void hud_layout(enum hud_view view, int w, int h, struct hud_layout *out);

/* Font sizes (pixels) that suit an H pixels high framebuffer. */
void hud_font_px(int h, float *small_px, float *large_px);

/* NULL on ENOMEM. */
struct hud *hud_create(void);

/* NULL is fine. */
void hud_destroy(struct hud *h);

/* Adds the state to the strip chart at time T_S (s, monotonic). */
void hud_record(struct hud *h, const struct endosim_state *st, double t_s);

/* Empties the strip chart (a replay's seek). */
void hud_chart_clear(struct hud *h);

/* Queues the HUD for the framebuffer of W x H into D (between
 * draw2d_begin() and draw2d_end()). */
void hud_draw(struct hud *h, struct draw2d *d, const struct hud_layout *lay,
	      const struct hud_info *in, int w, int hgt, double t_s);

/* Line I of the panel's text as the last hud_draw() drew it (cut where
 * the panel ends), NULL past the last: what the panel says, for tests. */
const char *hud_said(const struct hud *h, int i);

/* How many of the last panel's lines (a row of bars, the chart, the
 * patient's pictures: one each) found no room and were not drawn. */
int hud_hidden(const struct hud *h);

/* Where the last panel's text (its footer the last) ended: px from the
 * framebuffer's top, within the panel's rectangle. */
float hud_end_px(const struct hud *h);

/* The key help, one line per key, NULL-terminated: live, replay. */
extern const char *const hud_keys[];
extern const char *const hud_replay_keys[];

#endif
