/*
 * toolview.h - the tool in the working channel as the endoscopic view
 * draws it: a few tubes (polylines with a radius and a colour) built from
 * the published tool (proto/endosim_shm.h's endosim_tool_state) and the
 * scope's tip.
 *
 * The tool leaves the channel's exit along the tip's direction: the exit
 * is the published tool tip less its depth along dir (lib/model/tool.h),
 * the channel's side (radial) the exit's offset from the tip's axis. Each
 * tool shows once its tip is out of the channel (depth > 0):
 *  - a sheath or catheter from the exit to its tip, in the tool's colour
 *    (TOOLVIEW_SHEATH_M thick);
 *  - the snare: its wire loop, a circle of the published loop diameter
 *    round the published centre, in the plane of dir and dir x radial
 *    (tool.h's plane), TOOLVIEW_WIRE_M thick;
 *  - the forceps: two cups (the model's jaw length) opening with the
 *    handle up to TOOLVIEW_JAWS_RAD each side;
 *  - the needle: out of its catheter (the model's needle length) while
 *    the handle is past half open (tool.h);
 *  - the clip: two prongs (the model's clip length) opening with the
 *    handle up to TOOLVIEW_PRONGS_RAD each side.
 * What the tools left on the wall, tool in hand or not: a bleeding
 * point (the published bleed_at while any bleeds), a dark red welling
 * TOOLVIEW_WELL_M high, wider as the flow grows; the last clip placed
 * (clip_at), a steel stub TOOLVIEW_CLIP_M long; each stands from the wall
 * towards the scope's tip. And the view's reddening, toolview_redness()
 * of the published flow: the blood in the lumen before the lens; the
 * polyps retrieved, which the view no longer draws; the polyps cut,
 * which it draws where they lie (each one's published at: fallen to the
 * wall, tool.h), not on the wall where they stood.
 * The lengths are the model's defaults (tool.h): what the view draws, not
 * what the daemon computes with (the loop, the tip and the events are
 * the daemon's).
 *
 * Guided replay's expert's tool (the published guide state's expert_*:
 * the recording's, drawn by the daemon on the scope as it is now;
 * daemon/rig/guide.h) is a ghost beside the trainee's own
 * (toolview_build_ghost()): the same parts as a tool of its kind at its
 * depth and opening, every one in the light blue of the overview's
 * reference scope (guided replay's other ghost), the snare's wire amber
 * while the expert's pedal is down; the view draws a ghost's parts
 * translucent, TOOLVIEW_GHOST_ALPHA over what lies behind, writing no
 * depth (endo.c), so that the trainee's own tool and the polyp show
 * through it. It leaves nothing on the wall and reddens nothing.
 *
 * Everything is moved by SHIFT: the camera may stand where the scope's
 * tip is not (the god-object's proxy, the lumen's margin: endo.h), and the
 * tool goes with the lens. Pure computation, no allocation; colon frame,
 * m.
 */
#ifndef ENDOVIEW_TOOLVIEW_H
#define ENDOVIEW_TOOLVIEW_H

#include <stdbool.h>
#include <stdint.h>

#include "proto/endosim_shm.h"

#define TOOLVIEW_PARTS 5           /* a tool's 3, a bleeding point, a clip */
#define TOOLVIEW_POINTS 41       /* the loop's ring, closed */
#define TOOLVIEW_SHEATH_M 0.0024 /* a 2.8 mm channel's tools */
#define TOOLVIEW_WIRE_M 0.0004   /* the snare's wire (tool.h's wire_m) */
#define TOOLVIEW_JAWS_RAD 0.6    /* the forceps' cups, open */
#define TOOLVIEW_PRONGS_RAD 0.45 /* the clip's prongs, open */
#define TOOLVIEW_WELL_M 0.002    /* the blood welling from a point */
#define TOOLVIEW_CLIP_M 0.004    /* a clip placed, standing out */
#define TOOLVIEW_GHOST_ALPHA 0.55f /* a ghost's share of its pixels */
/* The flow that reddens the view half-way: a 5 mm stalk's (tool.h), a
 * guess at what fills the view with blood. */
#define TOOLVIEW_BLOOD_M3_S 2e-8

struct toolview_part {
	int points;                  /* of p in use, 2 or more */
	float p[TOOLVIEW_POINTS][3]; /* m */
	float radius_m;
	float rgb[3];                /* the tint, 0..1 */
	bool metal;                  /* glossy */
};

struct toolview {
	bool ghost;                  /* the expert's: drawn translucent */
	float blood;                 /* the view's reddening, 0..1 */
	uint32_t gone;               /* bit k: the case's polyp k retrieved
					(sucked out: not drawn) */
	uint32_t lying;              /* bit k: polyp k cut, lying at lie[k] */
	float lie[ENDOSIM_POLYPS][3]; /* its body's centre, m (not moved by
					 the shift: it is the colon's) */
	int parts;
	struct toolview_part part[TOOLVIEW_PARTS];
};

/*
 * The parts that draw TOOL on the scope SC, moved by SHIFT (m), into OUT
 * (no tool's parts for no tool, the tool inside the channel, or a state not
 * finite).
 */
void toolview_build(const struct endosim_tool_state *tool,
		    const struct endosim_scope_state *sc,
		    const double shift[3], struct toolview *out);

/*
 * The parts that draw the expert's tool of guided replay G (its expert_*
 * fields) on the scope SC as a ghost, moved by SHIFT (m), into OUT
 * (ghost set; no parts for no expert's tool, one inside the channel, or
 * a state not finite; no blood, nothing gone).
 */
void toolview_build_ghost(const struct endosim_guide_state *g,
			  const struct endosim_scope_state *sc,
			  const double shift[3], struct toolview *out);

/* The expert's tool of G as a tool's published state (its kind, pedal,
 * size, depth, opening, loop and tip; nothing held, no polyps), for the
 * views that show a tool: OUT. */
void toolview_expert(const struct endosim_guide_state *g,
		     struct endosim_tool_state *out);

/* The view's reddening for the bleeding points' flow BLEED_M3_S (m^3/s):
 * Q / (Q + TOOLVIEW_BLOOD_M3_S), 0..1; 0 for none or not finite. */
double toolview_redness(double bleed_m3_s);

#endif
