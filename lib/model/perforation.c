/* perforation.c - the tip pushed through the wall (perforation.h). */
#include "model/perforation.h"

#include <math.h>

void perforation_reset(struct perforation *p)
{
	*p = (struct perforation){ .segment = -1 };
}

double perforation_threshold_n(const struct perforation_params *par,
			       double bend_rad)
{
	double f = fmin(fabs(bend_rad), M_PI / 2) / (M_PI / 2);

	return par->straight_n + (par->bent_n - par->straight_n) * f;
}

bool perforation_step(struct perforation *p,
		      const struct perforation_params *par, double force_n,
		      double bend_rad, int segment, double dt_s)
{
	if (p->torn) {
		return false;
	}
	if (isfinite(force_n) && isfinite(bend_rad) &&
	    force_n > perforation_threshold_n(par, bend_rad)) {
		p->over_s += dt_s;
	} else {
		p->over_s = 0;
	}
	if (p->over_s < par->hold_s - dt_s / 2) { /* within half a step */
		return false;
	}
	p->torn = true;
	p->segment = segment;
	return true;
}
