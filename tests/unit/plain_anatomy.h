/*
 * plain_anatomy.h - a case built in code for the model's tests and fuzz
 * targets: the nine segments at the normal case's lengths (m), one lumen
 * diameter, no bends, nothing mobile, folds 3 cm apart, each wall's law
 * a case file's default. A test adds the bends, the mobility and the
 * sites it is about.
 */
#ifndef ENDOSIM_PLAIN_ANATOMY_H
#define ENDOSIM_PLAIN_ANATOMY_H

#include <stdio.h>
#include <string.h>

#include "model/anatomy.h"

static inline void plain_anatomy(struct anatomy *a, double diameter_m)
{
	static const double len[ANATOMY_SEGMENTS] = {
		0.04, 0.12, 0.37, 0.15, 0.07, 0.45, 0.06, 0.20, 0.06,
	};

	memset(a, 0, sizeof(*a));
	snprintf(a->name, sizeof(a->name), "test");
	a->fold_spacing_m = 0.03;
	a->fold_width_m = 0.005;
	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		a->seg[i].length_m = len[i];
		a->seg[i].diameter_m = diameter_m;
		a->seg[i].wall_collapsed = ANATOMY_DEFAULT_WALL_COLLAPSED;
		a->seg[i].wall_max = ANATOMY_DEFAULT_WALL_MAX;
		a->seg[i].wall_nominal_pa = ANATOMY_DEFAULT_WALL_NOMINAL_PA;
		a->seg[i].wall_beta = ANATOMY_DEFAULT_WALL_BETA;
	}
}

/* The sigmoid (segment 2) mobile on a mesentery of K_N_PER_M (N/m), H_M
 * (m) high. */
static inline void plain_mobile_sigmoid(struct anatomy *a, double k_n_per_m,
					double h_m)
{
	a->seg[2].mobile = true;
	a->seg[2].mesentery_n_per_m = k_n_per_m;
	a->seg[2].mesentery_height_m = h_m;
}

#endif
