/*
 * portal.h - which segments of the colon the endoscope's camera can see,
 * and at what level of detail (lod.h): the paper's portal technique.
 *
 * From inside a tube the camera sees the walls of the segment it is in
 * and, beyond them, only what the lumen's cross-sections (the portals
 * between segments) let through. So the walk starts at the camera's
 * segment (drawn whatever the view) and its two neighbours and goes on
 * towards the cecum and towards the anus while the next portal (its
 * centre on the bowed centreline, the radius of its ring) lies within the
 * view cone and nearer than far_m, where the light at the tip no longer
 * shows anything.
 * What it returns therefore depends on the camera's surroundings only,
 * never on the colon's length or the mesh's resolution.
 *
 * Each segment found gets a level from the distance between the camera and
 * its bounding box: finer near, coarser far. The list is sorted near to
 * far (front-to-back drawing lets the depth test skip hidden fragments).
 *
 * Pure computation on the model; no allocation.
 */
#ifndef ENDOVIEW_PORTAL_H
#define ENDOVIEW_PORTAL_H

#include <stdint.h>

#include "viewer/model.h"

#define PORTAL_MAX 48

struct portal_view {
	double eye[3];      /* camera position, m */
	double dir[3];      /* unit view direction */
	double half_angle;  /* rad: widest angle from dir that shows */
	double far_m;       /* nothing beyond is drawn */
	double level_m[3];  /* distances where levels 1, 2, 3 begin */
};

struct portal_item {
	uint32_t segment;
	int level;
	double distance_m;  /* camera to the segment's bounding box */
};

/*
 * The segments V sees, the camera being near material position S_M.
 * Returns how many were written to OUT (at most PORTAL_MAX).
 */
int portal_find(const struct model *m, const struct portal_view *v,
		double s_m, struct portal_item out[PORTAL_MAX]);

/* True when the sphere (C, R) reaches into V's cone. */
int portal_sphere_visible(const struct portal_view *v, const double c[3],
			  double r);

#endif
