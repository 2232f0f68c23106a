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
 * The patient's fluid (struct endosim_patient_state) pools in each
 * segment under a plane (normal fluid_up, at its level): a wall point of
 * a segment below its segment's surface, seen from above it, is seen
 * through the surface where the ray meets it, each fragment's plane
 * found analytically: the surface (a murky brown liquid, the lens's light
 * glinting off it, a wet line where it meets the wall), the wall under it
 * dimmed and tinted by the depth of liquid the ray crosses; with the eye
 * under its segment's surface everything is seen through the liquid (the
 * lens's murk, lensfx.h, blurs it). Each segment is drawn by the program
 * it needs: dry (no surface in reach of its walls), pools, or under (the
 * eye under its surface): llvmpipe runs both sides of a branch, so the
 * pools' shading would otherwise cost every wall.
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
#include <stdbool.h>
#include <stdint.h>

#include "proto/endosim_shm.h"
#include "viewer/gpumesh.h"
#include "viewer/lod.h"
#include "viewer/model.h"
#include "viewer/toolview.h"

#define ENDO_FOV_DEG 140.0
#define ENDO_FAR_M 0.30        /* darker than a pixel's step beyond */
#define ENDO_WALL_MARGIN_M 0.003
#define ENDO_LEVEL_M 0.03, 0.06, 0.12 /* where levels 1, 2, 3 begin */
#define ENDO_MASK_RADIUS 1.06 /* image circle, in half-sides of its square */
/* GLSL: the image circle's mask (1 inside, 0 outside, a pixel's edge;
 * endo_mask_px(): PX pixels') at this fragment of the viewport VP (x, y,
 * w, h) for a circle of R half-sides; the endoscopic view's and the
 * lens's (lensfx.h) */
#define ENDO_MASK_GLSL \
	"float endo_mask_px(vec4 vp, float r, float px) {\n" \
	"	vec2 hs = 0.5 * vp.zw;\n" \
	"	vec2 q = (gl_FragCoord.xy - vp.xy - hs) / hs.y;\n" \
	"	return 1.0 - smoothstep(r - 2.0 * px / vp.w, r, length(q));\n" \
	"}\n" \
	"float endo_mask(vec4 vp, float r) {\n" \
	"	return endo_mask_px(vp, r, 1.0);\n" \
	"}\n"
/* the widest angle from the view direction the image shows */
#define ENDO_HALF_ANGLE_RAD (ENDO_FOV_DEG / 2 * M_PI / 180 * ENDO_MASK_RADIUS)
#define ENDO_ALC_REF_M 0.025
#define ENDO_ALC_MIN 0.02
#define ENDO_DRY_M (-10.0) /* a segment without a pool: its level */
#define ENDO_AXIS_AHEAD_M 0.03 /* the lumen's way on, taken this far on */
#define ENDO_LUMEN_SHARE 0.85  /* its radius: of the widest ring's */
#define ENDO_WET_M 0.001 /* a wall this far above a surface glistens */

/* The pools as the camera sees them; all in the colon's frame. */
struct endo_liquid {
	bool on;                /* a pool anywhere */
	double up[3];           /* the surfaces' normal (unit) */
	double level_m[ENDOSIM_SEGMENTS]; /* each segment's surface along up
					     (ENDO_DRY_M: none) */
	double eye_level_m;     /* the surface of the eye's segment */
	bool under;             /* the eye under it */
	/* the lumen around the eye as a straight tube, which the surfaces
	   mirror: a point on its axis, the axis (unit), its radius */
	double axis_p[3], axis[3], lumen_m;
};

struct endo_camera {
	double eye[3]; /* m */
	double dir[3]; /* unit */
	double up[3];  /* unit, normal to dir */
	double s_m;    /* material position the camera is near */
	double pulled_in_m; /* how far it was moved to stay in the lumen */
	double wall_m; /* how far the walls in the middle of the view are */
	double exposure; /* the light's automatic level, 0..1 */
	struct endo_liquid liquid;
	struct toolview tool; /* the working channel's, with the lens */
	struct toolview expert; /* guided replay's expert's, a ghost */
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

/* The camera for state ST on model M (its pools: a patient's, on a colon
 * of the nine segments). */
void endo_camera(const struct model *m, const struct endosim_state *st,
		 struct endo_camera *cam);

/*
 * Where endo_draw() puts point X (colon frame, m) of CAM's view into R:
 * its pixel PX (x right, y up from R's bottom-left, GL's way), as the
 * vertex shader maps it (the angle from the view's axis over the image's
 * half angle, in the direction about the axis). False for a point at the
 * lens or behind it. No GL: for tests and the closing lines.
 */
bool endo_project(const struct endo_camera *cam, struct endo_rect r,
		  const double x[3], double px[2]);

/*
 * Draws the view from CAM into R (a square is best: the image circle
 * fills its height), clearing it first. Fills ST.
 */
void endo_draw(struct endo *e, const struct model *m, const struct lod *l,
	       const struct gpumesh *g, const struct endo_camera *cam,
	       struct endo_rect r, struct endo_stats *st);

#endif
