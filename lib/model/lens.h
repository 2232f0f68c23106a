/*
 * lens.h - what covers the scope's lens: the mucosa's smear when the tip
 * is pressed into the wall, the fluid's murk when it is dipped into a
 * pool, the red-out of suction close to the wall, and the water jet that
 * washes them off.
 *
 * Each cycle:
 *   smear  += dt (F - F_c)+ / smear_n_s    the tip pressed into the wall
 *                                          with F above F_c: stronger
 *                                          with force and time
 *   murk   += dt / dip_s                   while under the fluid
 *   both   -= dt / wash_s                  while the water jet runs (the
 *                                          air/water valve pressed): about
 *                                          a second to clear
 *   redout -> 1 with time constant redout_s while suction runs with the
 *             tip within redout_gap_m of the wall (the mucosa sucked onto
 *             the lens), -> 0 as fast when it stops
 * each held within 0..1. Nothing else clears the lens: a smeared lens
 * stays smeared until washed, as on a real scope.
 *
 * Pure computation, no allocation: the force loop steps it.
 */
#ifndef ENDOSIM_LENS_H
#define ENDOSIM_LENS_H

#include <stdbool.h>

struct lens_params {
	double contact_n;      /* F_c: the tip's force that touches the lens */
	double smear_n_s;      /* force above F_c times seconds: smeared */
	double dip_s;          /* under the fluid this long: murky */
	double wash_s;         /* the water jet clears a smeared lens in */
	double redout_gap_m;   /* suction this close to the wall: red-out */
	double redout_s;       /* red-out's time constant */
};

/* A guess, documented as such (docs/PATIENT.md): pressed at 1.5 N the
 * lens smears over about 4 s, a second in a pool clouds it, the jet
 * clears it in a second, suction within 3 mm of the wall reds out within
 * a fifth of a second. */
#define LENS_DEFAULT_CONTACT_N 0.5
#define LENS_DEFAULT_SMEAR_N_S 4.0
#define LENS_DEFAULT_DIP_S 1.0
#define LENS_DEFAULT_WASH_S 1.0
#define LENS_DEFAULT_REDOUT_GAP_M 0.003
#define LENS_DEFAULT_REDOUT_S 0.2
#define LENS_PARAMS_DEFAULT { .contact_n = LENS_DEFAULT_CONTACT_N, \
			      .smear_n_s = LENS_DEFAULT_SMEAR_N_S, \
			      .dip_s = LENS_DEFAULT_DIP_S, \
			      .wash_s = LENS_DEFAULT_WASH_S, \
			      .redout_gap_m = LENS_DEFAULT_REDOUT_GAP_M, \
			      .redout_s = LENS_DEFAULT_REDOUT_S }

struct lens {
	double smear;   /* 0..1: red, the mucosa's */
	double murk;    /* 0..1: brown-green, the fluid's */
	double redout;  /* 0..1: the mucosa on the lens */
};

/* This cycle's inputs. */
struct lens_input {
	double tip_force_n;   /* the wall's force on the tip */
	bool under_fluid;
	bool water;           /* the jet (the air/water valve pressed) */
	bool suction;         /* the suction valve pressed */
	double wall_gap_m;    /* the tip's clearance to the wall */
};

void lens_reset(struct lens *l);

void lens_step(struct lens *l, const struct lens_params *p,
	       const struct lens_input *in, double dt_s);

#endif
