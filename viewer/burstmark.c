/* burstmark.c - see burstmark.h. */
#include "viewer/burstmark.h"

#include <math.h>

double burstmark_pa(const struct endosim_patient_state *p,
		    double strength_n_per_m)
{
	double least = NAN;

	for (int i = 0; strength_n_per_m > 0 && i < ENDOSIM_SEGMENTS; i++) {
		double pi = p->transmural_pa[i], t = p->tension_n_per_m[i];
		double at;

		if (!(pi > 0 && t > 0) || !isfinite(pi) || !isfinite(t)) {
			continue;
		}
		at = strength_n_per_m * pi / t + (p->pressure_pa - pi);
		if (isnan(least) || at < least) {
			least = at;
		}
	}
	return least;
}
