/*
 * scope.h - the endoscope's kinematics: from the rig's axes to the shape of
 * the inserted tube and the pose of its tip.
 *
 * Inputs: the insertion depth d (m of tube past the anal verge), the roll
 * phi (rad), and the two wheel angles (rad), which turn into the tip's
 * bending angles by a gain each, clamped to their limits (defaults: 180 deg
 * up/down, 160 deg left/right).
 *
 * Shape: the tube follows the centreline as it is now (bowed or not) up to
 * the arc length d - Lb, where the bending section (length Lb) starts; the
 * bending section is one circular arc with the curvature vector
 *   kappa = (bend_ud u' + bend_lr v') / Lb
 * where (u', v') is the centreline frame there turned by the roll:
 * u' = cos(phi) u + sin(phi) v, v' = t x u'. Up bends towards u' (the
 * camera's up), right towards v' (the camera's right). When d < Lb, only
 * the inserted part exists: an arc of length d with the same curvature.
 * d is clamped to [0, scope_max_depth()]: the centreline's arc length and
 * the bending section beyond it, which leaves the colon's end straight on
 * (into the cecum's wall, where the haptics push it back).
 *
 * The tip: position, view direction (the arc's end tangent) and up vector
 * (u' carried along the arc), all in the colon's coordinates (m).
 *
 * Jacobian of the tip position with respect to (d, phi, bend_ud, bend_lr):
 * analytic for phi and the bending angles (exact for the arc); by central
 * differences for d, with h = the centreline's step, so its error is that
 * of the sampled centreline, about h^2 |r'''| / 6 plus the interpolation
 * between samples (well under 1% on bends of radius >= 20 step).
 *
 * Pure computation on caller-owned structures: no allocation, no I/O,
 * never blocks; safe in the force loop (~1-2 us with the tube polyline).
 */
#ifndef ENDOSIM_SCOPE_H
#define ENDOSIM_SCOPE_H

#include <math.h>

#include "model/centreline.h"
#include "proto/endosim_shm.h"

#define SCOPE_TUBE_POINTS 128

struct scope_params {
	double bending_length_m; /* Lb, > 0 */
	double ud_gain;          /* tip rad per wheel rad, up/down */
	double lr_gain;          /* tip rad per wheel rad, left/right */
	double ud_limit_rad;     /* |bend_ud| at most, 0..pi */
	double lr_limit_rad;     /* |bend_lr| at most, 0..pi */
};

/*
 * The shipped scope, each of its defaults written here once: the model's
 * *_PARAMS_DEFAULT and the configuration's keys ([scope], [haptics]
 * scope_radius_m and wire_spacing_m, [rod]) take them. The gains take the
 * rig's default wheel travel (+-1.75 rad) to the limits, which are 180 and
 * 160 deg as `endosimd --print-config` writes them (%.9g).
 */
#define SCOPE_RADIUS_M 0.0065            /* the tip and the tube: 13 mm */
#define SCOPE_WIRE_SPACING_M 0.008       /* dr: a wheel's two wires apart */
#define SCOPE_DEFAULT_BENDING_LENGTH_M 0.09
#define SCOPE_DEFAULT_UD_GAIN 1.8
#define SCOPE_DEFAULT_LR_GAIN 1.6
#define SCOPE_DEFAULT_UD_LIMIT_RAD 3.14159
#define SCOPE_DEFAULT_LR_LIMIT_RAD 2.79253

#define SCOPE_PARAMS_DEFAULT { \
	.bending_length_m = SCOPE_DEFAULT_BENDING_LENGTH_M, \
	.ud_gain = SCOPE_DEFAULT_UD_GAIN, .lr_gain = SCOPE_DEFAULT_LR_GAIN, \
	.ud_limit_rad = SCOPE_DEFAULT_UD_LIMIT_RAD, \
	.lr_limit_rad = SCOPE_DEFAULT_LR_LIMIT_RAD }

struct scope_input {
	double depth_m;      /* insertion axis, m */
	double roll_rad;     /* roll axis */
	double wheel_ud_rad; /* up/down wheel */
	double wheel_lr_rad; /* left/right wheel */
};

struct scope_pose {
	double depth_m;         /* d as used (clamped) */
	double roll_rad;
	double bend_rad[2];     /* up/down, left/right: after gain and limits */
	double dbend_dwheel[2]; /* the gain, or 0 at a limit */
	double base_s_m;        /* material s where the bending section starts */
	double tip_s_m;         /* material s of the sample nearest the tip */
	double tip[3];          /* m */
	double dir[3];          /* unit view direction */
	double up[3];           /* unit, normal to dir */
	double jacobian[3][4];  /* d tip / d (d, phi, bend_ud, bend_lr):
				   m/m, m/rad, m/rad, m/rad */
	double tube[SCOPE_TUBE_POINTS][3]; /* anal verge to tip, equal arcs */
};

/* The tip's bending angles (rad) for wheel angles (rad): gain, limits. */
void scope_bend(const struct scope_params *p, double wheel_ud_rad,
		double wheel_lr_rad, double bend_rad[2],
		double dbend_dwheel[2]);

/* The deepest insertion the kinematics follow (m): the centreline's arc
 * length plus the bending section. */
double scope_max_depth(const struct scope_params *p,
		       const struct centreline *cl);

/* Computes OUT for IN along CL. */
void scope_update(const struct scope_params *p, const struct centreline *cl,
		  const struct scope_input *in, struct scope_pose *out);

/*
 * The published form of pose P on CL (endosim_shm.h): depth, roll, bends,
 * base and tip s, the centreline's turning at the base, the tip's frame,
 * each mobile span's bow as CL holds it now, and the tube. Leaves
 * OUT->scene_id alone. The force loop calls it after the haptics, so the
 * bows are this cycle's while the pose was made on last cycle's.
 */
void scope_publish(const struct scope_pose *p, const struct centreline *cl,
		   struct endosim_scope_state *out);

#endif
