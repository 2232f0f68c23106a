/*
 * lensfx_rules.c - see lensfx.h: what the lens shows and hides, without
 * the GL (the unit tests link it).
 */
#include "viewer/lensfx.h"

#include <math.h>

/* The blur the lens gives its least smeared pixel: the shader's
 * 1.6 smear (0.45 + 0.55 patch) + 1.2 murk, at patch 0 (lensfx.c). */
#define LEAST_SMEAR (1.6 * 0.45)
#define MURK_BLUR 1.2
#define SHARP_GONE 0.5 /* a blur from which no sharp image shows */

bool lensfx_visible(const struct endosim_patient_state *p)
{
	return p->enabled &&
	       (p->lens_smear > LENSFX_CLEAN || p->lens_murk > LENSFX_CLEAN ||
		p->lens_redout > LENSFX_CLEAN ||
		(p->valves & ENDOSIM_VALVE_WATER));
}

float lensfx_amount(double v)
{
	return isfinite(v) ? (float)fmax(0, fmin(1, v)) : 0;
}

double lensfx_image_factor(const struct endosim_patient_state *p)
{
	if (!lensfx_visible(p)) {
		return 1;
	}
	return LEAST_SMEAR * lensfx_amount(p->lens_smear) +
			       MURK_BLUR * lensfx_amount(p->lens_murk) >=
		       SHARP_GONE
		       ? LENSFX_HIDDEN_FACTOR
		       : 1;
}
