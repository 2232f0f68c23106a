/*
 * perforation.h - the tip pushed through the wall: a perforation by force
 * (the gas's burst, gas.h, is the other kind).
 *
 * The tip's force on the wall tears it when it stays above a threshold
 * for hold_s: a tissue fails under a load held, not under a knock. The
 * threshold depends on how the tip meets the wall: Johnson et al. (2019,
 * porcine colon) measured 14.1 N with a straight tip, which meets the
 * wall with its face, and 46.5 N with the tip bent 90 degrees, which
 * meets it with its side, the load spread over a longer contact. Between
 * them it is taken linear in the bend's angle (the simplest curve through
 * the two measurements; none was measured between), and 46.5 N beyond
 * 90 degrees:
 *   F_tear(b) = straight_n + (bent_n - straight_n) min(|b|, pi/2) / (pi/2)
 * The hold, 0.5 s by default, is a choice, not a measurement: long enough
 * that a knock does not tear, short next to the seconds a trainee leans
 * on a wall. Once torn it stays torn (until perforation_reset()).
 *
 * Units SI. Plain data, no allocation, fixed work. One writer.
 */
#ifndef ENDOSIM_PERFORATION_H
#define ENDOSIM_PERFORATION_H

#include <stdbool.h>

struct perforation_params {
	double straight_n; /* the threshold with the tip straight */
	double bent_n;     /* with it bent 90 degrees or more */
	double hold_s;     /* above it this long tears */
};

#define PERFORATION_DEFAULT_STRAIGHT_N 14.1
#define PERFORATION_DEFAULT_BENT_N 46.5
#define PERFORATION_DEFAULT_HOLD_S 0.5

#define PERFORATION_PARAMS_DEFAULT { \
		.straight_n = PERFORATION_DEFAULT_STRAIGHT_N, \
		.bent_n = PERFORATION_DEFAULT_BENT_N, \
		.hold_s = PERFORATION_DEFAULT_HOLD_S }

struct perforation {
	double over_s; /* how long the force has been above the threshold */
	bool torn;
	int segment;   /* where it tore; -1: not torn */
};

/* Not torn, nothing held. */
void perforation_reset(struct perforation *p);

/* The threshold (N) for a tip bent BEND_RAD (either way). */
double perforation_threshold_n(const struct perforation_params *par,
			       double bend_rad);

/*
 * One step of DT_S: the tip presses FORCE_N on the wall of SEGMENT, bent
 * BEND_RAD. True in the step in which it tears (once). A non-finite force
 * or bend counts as no force.
 */
bool perforation_step(struct perforation *p,
		      const struct perforation_params *par, double force_n,
		      double bend_rad, int segment, double dt_s);

#endif
