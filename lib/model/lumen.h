/*
 * lumen.h - the insertion tube (a rod, rod.h) against the colon's lumen
 * and the rig's guide: every segment's contact, with Coulomb friction, and
 * its reaction on the colon that moves (flex.h).
 *
 * Inside the patient, segment i (its centre p, radius r) is held within
 * the lumen: with c(k), t(k) the centreline sample nearest p (found from
 * the segment's previous nearest sample by walking while the distance
 * falls: O(1) per step, at most LUMEN_WALK samples) and R(k) the lumen's
 * radius for the tube there (colon_tube_radius(), times the gas's
 * factor there: lumen_set_factors()), the radial offset
 *   rho = (p - c) - ((p - c) . t) t     (beyond the cecum's end: p - c)
 * may be at most R - r; beyond it by delta the wall pushes back along
 * n = -rho / |rho| with
 *   F_n = k_wall l delta + b_wall l (the rate delta grows)
 * (k_wall, b_wall per length of tube, l the segment's; the wall is
 * viscoelastic tissue: b_wall = k_wall times its Kelvin-Voigt time) and
 * rubs with regularised Coulomb friction at the tube's surface (the
 * point p - r n): a damper c (I - n n^T) on the sliding velocity relative
 * to the wall's own (flex_velocity()), c = mu F_n / max(|v_slip|, v_s):
 * viscous below the slip speed v_s (the tube sticks), Coulomb's mu F_n
 * above it; at the surface it resists rolling as well (the roll's
 * friction). Both are loads of the rod's next step, linear in its motion
 * (rod_load_point()), so a stiff wall and a sticking tube stay stable.
 * After the step each contact's force, as the step ended, goes back onto
 * the colon at the sample's material s (action = reaction): a mobile
 * segment moves, the fixed colon holds.
 *
 * Outside (behind the anal verge, where the colon's first tangent points
 * in), the segments lie in the rig's slitted pipe: held within
 * LUMEN_PIPE_CLEARANCE_M of its axis (the colon's first tangent produced
 * backwards) by pipe_stiffness per length, without friction.
 *
 * The tube's last segment is left to the tip's god-object (haptics.h):
 * it alone meets the mesh's folds and edges.
 *
 * lumen_create() allocates; the rest does not, never blocks or prints:
 * the force loop runs it. One writer.
 */
#ifndef ENDOSIM_LUMEN_H
#define ENDOSIM_LUMEN_H

#include <stddef.h>

#include "model/colon.h"
#include "model/flex.h"
#include "model/gas.h"
#include "model/rod.h"
#include "model/scope.h"

#define LUMEN_WALK 64                 /* samples walked per step, at most */
#define LUMEN_PIPE_CLEARANCE_M 0.001  /* the guide's play around the tube */

struct lumen_params {
	double wall_n_per_m2;    /* k_wall: N/m of depth per m of tube */
	double wall_damping_s;   /* b_wall / k_wall, s */
	double friction;         /* mu, 0..2 */
	double slip_m_per_s;     /* v_s, > 0 */
	double pipe_n_per_m2;    /* the guide's stiffness per m of tube */
	double tube_radius_m;    /* r: the insertion tube's outer radius */
};

#define LUMEN_DEFAULT_WALL_N_PER_M2 1.5e5
#define LUMEN_DEFAULT_WALL_DAMPING_S 0.01
#define LUMEN_DEFAULT_FRICTION 0.05
#define LUMEN_DEFAULT_SLIP_M_PER_S 0.002
#define LUMEN_DEFAULT_PIPE_N_PER_M2 1e6

#define LUMEN_PARAMS_DEFAULT { .wall_n_per_m2 = LUMEN_DEFAULT_WALL_N_PER_M2, \
			       .wall_damping_s = LUMEN_DEFAULT_WALL_DAMPING_S, \
			       .friction = LUMEN_DEFAULT_FRICTION, \
			       .slip_m_per_s = LUMEN_DEFAULT_SLIP_M_PER_S, \
			       .pipe_n_per_m2 = LUMEN_DEFAULT_PIPE_N_PER_M2, \
			       .tube_radius_m = SCOPE_RADIUS_M }

/* This step's totals. */
struct lumen_totals {
	int contacts;         /* segments pressed by the wall (not the pipe) */
	double wall_n;        /* sum of the wall's normal forces, N */
	double friction_n;    /* sum of the friction forces' sizes, N */
};

struct lumen;

/* For a rod of SEGMENTS segments. NULL on ENOMEM. */
struct lumen *lumen_create(int segments);

/* NULL is fine. */
void lumen_destroy(struct lumen *l);

/*
 * Forgets every segment's nearest sample: the next lumen_load() finds each
 * from SIGMA_M (m): the material s where the rod's segment I should be if
 * it followed the centreline (segment i of a rod inserted d deep: d - L +
 * (i + 1/2) l).
 */
void lumen_reset(struct lumen *l, const double *sigma_m);

/*
 * Loads ROD's segments for its next step (rod_clear_loads() first): the
 * pipe outside, the lumen of COLON inside, the wall moving as FLEX says
 * (may be NULL: a colon that does not move). Remembers each contact for
 * lumen_react().
 */
void lumen_load(struct lumen *l, struct rod *rod, const struct colon *colon,
		const struct flex *flex, const struct lumen_params *p);

/*
 * After ROD's step: each contact's force as the step ended, pushed onto
 * FLEX (may be NULL; flex_clear() first) at its material s, and the
 * totals in OUT.
 */
void lumen_react(struct lumen *l, const struct rod *rod, struct flex *flex,
		 struct lumen_totals *out);

/*
 * The lumen's radius factors the gas holds each segment at (gas.h: nine,
 * as published; NULL, the default: the case's radii); the tube meets the
 * wall at colon_tube_radius() times gas_factor_at(). FACTOR must outlive
 * its use.
 */
void lumen_set_factors(struct lumen *l, const double *factor);

/* Segment I's nearest centreline sample (after lumen_load()), or -1 in
 * the pipe. */
long lumen_sample(const struct lumen *l, int i);

#endif
