/*
 * fluid.h - residual fluid pooled in the colon: each segment's volume,
 * its surface level with gravity, and the suction that takes it away.
 *
 * Each anatomical segment i holds a fluid volume V_i (a case's
 * fluid_m3), which stays in its segment (it does not run over into the
 * next). It pools in the segment's dependent part: its surface is a plane
 * of normal n (up, against gravity) at height h_i, the level at which the
 * lumen below it holds V_i:
 *   V_i = sum_k ds_k r_k^2 A((h_i - c_k . n) / e_k),
 *   A(x) = acos(-x) + x sqrt(1 - x^2)   (a unit disc's area below x)
 * over the segment's rings k every FLUID_RING_M (centre c_k on the
 * centreline as it lies now, radius r_k the lumen's there as the gas
 * holds it, e_k = r_k sqrt(1 - (t_k . n)^2) + ds |t_k . n| / 2 the
 * half-height of the slab of tube the ring stands for, ds long: a tilted
 * disc's area below a plane divides as its projection's does, and a
 * slab standing upright fills evenly up its length),
 * solved by Newton from the last level. The surface settles towards the
 * horizontal with the time constant settle_s after the patient turns (the
 * pool sloshes; at rest it lies perpendicular to gravity).
 *
 * The suction valve pressed with the tip under its segment's surface
 * takes suction_m3_per_s of fluid out of that segment.
 *
 * Fixed work: one segment's level a step, in turn (each segment's every
 * FLUID_SEGMENTS steps), at most 3 Newton iterations over its rings; no
 * allocation, no blocking: the force loop steps it. One writer.
 */
#ifndef ENDOSIM_FLUID_H
#define ENDOSIM_FLUID_H

#include <stdbool.h>

#include "model/colon.h"
#include "model/gas.h"

#define FLUID_SEGMENTS GAS_SEGMENTS
#define FLUID_RING_M 0.004     /* the rings' spacing along a segment */
#define FLUID_MAX_RINGS 160    /* per segment, at most */

struct fluid_params {
	double suction_m3_per_s;   /* fluid sucked while under the surface */
	double settle_s;           /* the surface's time to follow gravity */
};

/* Suction through a 3.7 mm channel empties ~0.5 L/min of fluid; the
 * surface settles within about a second of a turn. */
#define FLUID_DEFAULT_SUCTION_M3_PER_S 8.3e-6 /* 0.5 L/min */
#define FLUID_DEFAULT_SETTLE_S 0.3
#define FLUID_PARAMS_DEFAULT { \
	.suction_m3_per_s = FLUID_DEFAULT_SUCTION_M3_PER_S, \
	.settle_s = FLUID_DEFAULT_SETTLE_S }

struct fluid_segment {
	double volume_m3;       /* V_i */
	double level_m;         /* h_i: the surface's height along n */
	double depth_m;         /* the pool's depth: h_i less its lowest
				   point's height (0: dry) */
	size_t first, count;    /* its centreline samples */
};

struct fluid {
	struct fluid_params p;
	const struct colon *colon;
	int segments;            /* 0: detached (an imported colon) */
	struct fluid_segment seg[FLUID_SEGMENTS];
	double up[3];            /* the surface's normal n (unit) */
	int next;                /* the segment whose level is due */
	double sucked_m3;        /* taken out so far */
};

/* COLON's segments (the generated case's nine; none for an import) with
 * VOLUME_M3[i] each (NULL: dry), level under gravity DOWN with the lumen
 * FACTOR (gas.h; NULL: 1). No allocation. */
void fluid_attach(struct fluid *f, const struct fluid_params *p,
		  const struct colon *colon, const double *volume_m3,
		  const double down[3], const double *factor);

void fluid_set_params(struct fluid *f, const struct fluid_params *p);

/*
 * One step of DT_S: the surface turns towards -DOWN; with SUCTION (the
 * valve pressed) and the tip at TIP (body frame) in segment TIP_SEGMENT
 * under its surface, fluid is taken out of it; one segment's level is
 * solved again with the lumen FACTOR (NULL: 1). Returns whether the tip
 * is under the surface.
 */
bool fluid_step(struct fluid *f, const double down[3], const double *factor,
		bool suction, const double tip[3], int tip_segment,
		double dt_s);

/* VOLUME_M3 (>= 0) of fluid more in segment I (blood from a bleeding
 * point, tool.h); its level follows in its turn. Nothing for a segment
 * not attached. Fixed work. */
void fluid_add(struct fluid *f, int i, double volume_m3);

/* Every segment's level solved again now (a start, a test). */
void fluid_settle(struct fluid *f, const double *factor);

/* Whether the point P (body frame) in segment I lies under its surface. */
bool fluid_under(const struct fluid *f, int i, const double p[3]);

/* The segments' volumes, for the gas (gas_input.fluid_m3). */
void fluid_volumes(const struct fluid *f, double out[FLUID_SEGMENTS]);

/* The segment holding material S_M, or -1. */
int fluid_segment_at(const struct fluid *f, double s_m);

#endif
