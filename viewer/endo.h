/*
 * endo.h - the endoscopic view: what the colonoscope's camera sees.
 *
 * The camera sits at the tip (at the god-object proxy while the wall holds
 * the tip, and never closer to the wall than ENDO_WALL_MARGIN_M: a tip the
 * kinematics put outside the lumen shows the wall it pressed into, not the
 * colon from outside), looks along the tip's view direction with its up
 * vector, so roll and steering turn the image as on a real monitor.
 *
 * Like a real video processor the light is set automatically: full while
 * the walls in the middle of the view (rays cast through the lumen,
 * weighed by the light they would return) are ENDO_ALC_REF_M away or
 * more, down to ENDO_ALC_MIN as they come closer (the square of the
 * distance), so that a wall at the lens is red, not white.
 *
 * Projection: equidistant fisheye (image radius proportional to the angle
 * from the view direction), ENDO_FOV_DEG across the image circle, done per
 * vertex; the image is the circle cut by its square, as on a colonoscopy
 * monitor. Light: one point source at the lens, falling off with the
 * square of the distance, so that the lumen ahead is a dark hole; diffuse
 * with a little wrap for the red light scattered in tissue, a sharp
 * specular term for the moist mucosa, its strength the vessel texture's
 * moisture (vessels.h) so the highlights break into glints. The haustral
 * folds and the taeniae are the mesh's own relief, lit.
 *
 * Only the segments the portal walk finds (portal.h) are drawn, each at its
 * level of detail (lod.h), nearest first; polyps of the case as small
 * spheres (sessile), heads on stalks (pedunculated) or plaques (flat).
 *
 * Main thread, with the GL context current.
 */
#ifndef ENDOVIEW_ENDO_H
#define ENDOVIEW_ENDO_H

#include <math.h>
#include <stdint.h>

#include "proto/endosim_shm.h"
#include "viewer/gpumesh.h"
#include "viewer/lod.h"
#include "viewer/model.h"

#define ENDO_FOV_DEG 140.0
#define ENDO_FAR_M 0.30        /* darker than a pixel's step beyond */
#define ENDO_WALL_MARGIN_M 0.003
#define ENDO_LEVEL_M 0.03, 0.06, 0.12 /* where levels 1, 2, 3 begin */
#define ENDO_MASK_RADIUS 1.06 /* image circle, in half-sides of its square */
/* the widest angle from the view direction the image shows */
#define ENDO_HALF_ANGLE_RAD (ENDO_FOV_DEG / 2 * M_PI / 180 * ENDO_MASK_RADIUS)
#define ENDO_ALC_REF_M 0.025
#define ENDO_ALC_MIN 0.02

struct endo_camera {
	double eye[3]; /* m */
	double dir[3]; /* unit */
	double up[3];  /* unit, normal to dir */
	double s_m;    /* material position the camera is near */
	double pulled_in_m; /* how far it was moved to stay in the lumen */
	double wall_m; /* how far the walls in the middle of the view are */
	double exposure; /* the light's automatic level, 0..1 */
};

struct endo_stats {
	uint32_t triangles; /* drawn this frame */
	uint32_t segments;
};

/* A viewport in framebuffer pixels, GL's origin (bottom-left). */
struct endo_rect {
	int x, y, w, h;
};

struct endo;

/* Shaders, the vessel texture, the polyp mesh. NULL on failure (logged). */
struct endo *endo_create(void);

/* NULL is fine. */
void endo_destroy(struct endo *e);

/* The camera for state ST on model M. */
void endo_camera(const struct model *m, const struct endosim_state *st,
		 struct endo_camera *cam);

/*
 * Draws the view from CAM into R (a square is best: the image circle
 * fills its height), clearing it first. Fills ST.
 */
void endo_draw(struct endo *e, const struct model *m, const struct lod *l,
	       const struct gpumesh *g, const struct endo_camera *cam,
	       struct endo_rect r, struct endo_stats *st);

#endif
