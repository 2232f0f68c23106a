/*
 * vessels.h - the colon's mucosa as a procedural texture: a tileable RGBA
 * image whose colour is the mucosa's albedo (salmon pink, mottled, with
 * the branching submucosal vessels: deep ones broad and bluish-purple,
 * superficial ones fine and red) and whose alpha is the surface's
 * moisture (fine grain, higher along the vessels), which scales the
 * specular highlight so that the moist mucosa breaks it into glints.
 *
 * The image repeats in both directions: endoview maps it along the colon
 * once every VESSELS_TILE_M, and around a generated tube VESSELS_AROUND
 * times (its rings carry their first vertex again where it wraps), around
 * anything else with vessels_around(). Same seed, same image. Pure
 * computation; allocates the image.
 */
#ifndef ENDOVIEW_VESSELS_H
#define ENDOVIEW_VESSELS_H

#include <math.h>
#include <stdint.h>

#define VESSELS_TILE_M 0.04 /* along the colon, one repeat */
#define VESSELS_AROUND 4.0  /* repeats around the lumen */

/*
 * The texture coordinate around the lumen at ANGLE_RAD from the frame's u:
 * up to VESSELS_AROUND / 2 and back, mirrored where it turns (at 0 and pi)
 * so that it has no seam to interpolate across.
 */
static inline double vessels_around(double angle_rad)
{
	double x = fabs(remainder(angle_rad, 2 * M_PI)) / M_PI; /* 0..1 */

	return x * VESSELS_AROUND / 2;
}

/* A SIZE x SIZE RGBA image (SIZE a power of two, 64..4096), rows top
 * first; NULL on a bad size or ENOMEM. Free with free(). */
uint8_t *vessels_create(int size, uint32_t seed);

#endif
