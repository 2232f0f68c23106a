/*
 * lag.h - a first-order lag: a value following its target with a time
 * constant, exact for a target held over the step,
 *   x += (target - x) (1 - exp(-dt / tau)),
 * so that a step of the target is followed as 1 - exp(-t / tau) whatever
 * the step. Pure computation; any thread, the force loop included.
 */
#ifndef ENDOSIM_LAG_H
#define ENDOSIM_LAG_H

#include <math.h>

/* X after DT_S seconds following TARGET with time constant TAU_S (<= 0:
 * at once). A step that is not positive, or a target that is not finite,
 * leaves X as it is. */
static inline double lag_follow(double x, double target, double tau_s,
				double dt_s)
{
	if (!(dt_s > 0) || !isfinite(target)) {
		return x;
	}
	return tau_s > 0 ? x + (target - x) * -expm1(-dt_s / tau_s) : target;
}

#endif
