/*
 * godobject.h - the god-object (Zilles and Salisbury 1995) of the
 * endoscope's tip: a proxy point that follows the tip but never passes
 * through the contact surface (contact.h), so that the spring between them
 * renders the wall (Koerner and Maenner, section 5.1).
 *
 * Each update starts from the previous proxy, which is in the lumen, and
 * moves it towards the goal (the tip as the kinematics put it):
 *  1. the first triangle the path crosses becomes a constraint plane;
 *  2. the proxy stops there, and its next target is the point nearest to
 *     the goal on the active planes: one plane (slide on it), two (slide
 *     along their line: an edge), three (their point: a corner), found as
 *     the minimum of |x - goal|^2 with the planes as equalities; a plane
 *     whose Lagrange multiplier is negative (the goal pulls away from it)
 *     is dropped and the rest solved again;
 *  3. repeated towards that target until nothing more is crossed or three
 *     planes hold the proxy.
 * Since every move starts inside and every crossing of the closed surface
 * is caught, a goal that jumps far (through a fold, out of the colon) leaves
 * the proxy inside: no pop-through.
 *
 * Units: m. Pure computation on the caller's struct: no allocation, never
 * blocks; safe in the force loop.
 */
#ifndef ENDOSIM_GODOBJECT_H
#define ENDOSIM_GODOBJECT_H

#include <stdbool.h>
#include <stdint.h>

#include "model/contact.h"

#define GODOBJECT_MAX_PLANES 3

struct godobject {
	double proxy[3];   /* m */
	int planes;        /* active constraints now, 0..3 */
	uint32_t tri[GODOBJECT_MAX_PLANES];
	double normal[GODOBJECT_MAX_PLANES][3]; /* unit, into the lumen */
	double offset[GODOBJECT_MAX_PLANES];    /* normal . x = offset */
	double shaded[3];  /* the planes' interpolated normals, averaged */
};

/* Puts the proxy at P (which must be in the lumen), free. */
void godobject_reset(struct godobject *g, const double p[3]);

/*
 * Moves the proxy towards GOAL against the surface C, considering the
 * triangles of the colon's stretch [S0_M, S1_M] (it must hold the proxy,
 * the goal and the path between them).
 */
void godobject_update(struct godobject *g, const struct contact *c,
		      const double goal[3], double s0_m, double s1_m);

/* True while a constraint holds the proxy (the tip touches the wall). */
static inline bool godobject_contact(const struct godobject *g)
{
	return g->planes > 0;
}

#endif
