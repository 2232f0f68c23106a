/*
 * overview.h - the colon from outside, like a magnetic scope-position
 * display: the colon translucent (a ghost: its silhouette bright, the
 * walls facing the viewer nearly clear) where it is placed now, the mobile
 * segments turning amber as they bow or move, the scope's shape inside it
 * in green with its tip, and the contact point with the wall's normal
 * while the wall holds the tip. The scope's shape is the published tube
 * polyline in the paper's model; in the rod model the whole tube (struct
 * endosim_rod_state), from the carriage, its part outside the patient
 * dimmer, with a white line along it that its roll turns
 * (shapes_stripe()): a twist held in the tube winds the line round it.
 *
 * Seen from the patient's front by default (the patient's left on the
 * viewer's right, cranial up, as a frontal radiograph); the orbit turns
 * and zooms the view. The colon is drawn at a coarse level of detail
 * (lod.h) whatever the mesh's resolution.
 *
 * Main thread, with the GL context current.
 */
#ifndef ENDOVIEW_OVERVIEW_H
#define ENDOVIEW_OVERVIEW_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "viewer/draw2d.h"
#include "viewer/endo.h"
#include "proto/endosim_shm.h"
#include "viewer/gpumesh.h"
#include "viewer/lod.h"
#include "viewer/model.h"

#define OVERVIEW_SCOPE_RGB 0.20f, 0.95f, 0.30f /* the scope's green */

struct overview_orbit {
	double yaw_rad;   /* 0: from the front; about the cranial axis */
	double pitch_rad; /* up from the horizontal */
	double zoom;      /* 1: the whole colon fits */
};

struct overview;

/* NULL on failure (logged). */
struct overview *overview_create(void);

/* NULL is fine. */
void overview_destroy(struct overview *o);

/*
 * Draws the overview of M (placed as it is now) with the scope of ST into
 * R, clearing it first; returns the triangles drawn. ST may be NULL (the
 * colon alone).
 */
uint32_t overview_draw(struct overview *o, const struct model *m,
		       const struct lod *l, const struct gpumesh *g,
		       const struct endosim_state *st,
		       const struct overview_orbit *orbit, struct endo_rect r);

/*
 * Where the point P (m) lies in the last overview drawn, in a framebuffer
 * FB_H pixels high: XY in pixels from its top-left corner (it may lie
 * outside the overview). False when P is behind the camera.
 */
bool overview_project(const struct overview *o, const double p[3], int fb_h,
		      float xy[2]);

/*
 * Queues the names of the colon's regions at their places in the last
 * overview drawn, for a framebuffer FB_H pixels high.
 */
void overview_labels(const struct overview *o, const struct model *m,
		     struct draw2d *d, int fb_h);

/*
 * For tests, in the last overview drawn (of M with ST, in a framebuffer
 * FB_H pixels high; pixels from its top-left corner): in the rod model
 * the published tube's points inside the patient and outside,
 *   overview: rod_in=X,Y;X,Y;...
 *   overview: rod_out=X,Y;...
 * and the share of the points inside that lie within the colon as placed
 * (its wall pressed in by 5 mm at most),
 *   overview: rod_in_lumen=SHARE
 * and for each mobile span the sample that has moved most (model_moved()):
 * how far, where it is drawn, where it lies at rest, the lumen's radius
 * there,
 *   overview: span=K moved_m=M at=X,Y rest=X,Y lumen_px=R
 */
void overview_print(const struct overview *o, const struct model *m,
		    const struct endosim_state *st, int fb_h, FILE *f);

#endif
