/*
 * gas.h - the gas in the colon: how much there is, its pressure, and how
 * wide it holds each anatomical segment open.
 *
 * The colon holds a gas volume V (m^3). Each segment i (anatomy.h's nine)
 * is a tube of length L_i whose lumen volume follows the transmural
 * pressure across its wall, p_i = P - P_abd,i, through its wall's law:
 *   V_i(p) = V0_i v_i(p),  the lumen radius r_i = R_i sqrt(v_i(p))
 * with V0_i and R_i the segment as the case draws it (its mesh's rings,
 * folds and taeniae included) and v_i its volume factor:
 *   power-exponential (GAS_LAW_POWEXP; the shape barostat studies fit to
 *   the colon's quasi-static pressure-volume curve, Bharucha et al., Am J
 *   Physiol GI 2001):
 *     v(p) = vc + (vm - vc) exp(-(kappa / p)^beta)        p > 0
 *     v(p) = vc exp(p / p_c)                             p <= 0
 *   vc = collapsed^2 the lumen with its folds meeting (no gas pressure
 *   holds it open), vm = max^2 the size the wall stiffens towards, beta
 *   the curve's shape, and kappa set so that v(nominal_pa) = 1: the case's
 *   radius at the nominal pressure. Below zero (suction) the collapsed
 *   lumen empties further, e-fold every collapse_pa. Compliant from
 *   collapsed (the curve's steep middle), stiffening beyond. The radius
 *   the contact and the picture take never falls below the scope's
 *   (SCOPE_RADIUS_M): the wall closes on the tube, not past it.
 *   linear (GAS_LAW_LINEAR, for analytic tests): v(p) = vc + (1 - vc) p /
 *   nominal_pa for p >= 0, vc exp(p (1 - vc) / (vc nominal_pa)) below
 *   (the same slope at 0).
 * The abdomen's contents press on the colon like a fluid: P_abd,i =
 * rho_g (h_top - h_i), h_i the height of segment i's centroid against
 * gravity and h_top the highest segment's (rho_g = hydrostatic_pa_per_m,
 * about 0.74 mmHg per cm): a segment lying low is less distended than one
 * lying high at the same gas pressure.
 *
 * P follows from V: sum_i (V_i(P - P_abd,i)) = V + the fluid's volume
 * (fluid.h keeps its own share of each lumen), solved each step by a
 * safeguarded Newton iteration from the last P (each V_i is increasing in
 * p, so the sum is: one root). Flows change V each step of dt:
 *   + pump      while the air valve is covered, unless P >= relief_pa
 *               (an insufflator's relief; 0: none)
 *   - suction   while the suction valve is pressed and the tip is in gas
 *   - leak      through the anus around the tube: leak_m3_per_s_pa
 *               (P - leak_pa) above leak_pa
 *   - absorbed  through the wall: absorb_per_s V (CO2 ~150 times air's)
 * and a burst: the wall's tension (Laplace: p_i r_i per length of wall,
 * r_i at the segment's widest ring) above wall_strength_n_per_m tears
 * segment i (one strength for the whole
 * colon: the widest segment, the cecum, fails first, as Kozarek et al.
 * found, Gastroenterology 1980); its gas escapes and it stays torn.
 *
 * Units SI (Pa, m^3, m); GAS_PA_PER_MMHG converts. gas_create() allocates
 * nothing beyond itself; gas_attach() and the rest neither allocate,
 * block nor print: the force loop steps it (fixed work: ~20 exp/pow per
 * Newton iteration, 2-4 iterations). One writer.
 */
#ifndef ENDOSIM_GAS_H
#define ENDOSIM_GAS_H

#include <stdbool.h>

#include "model/anatomy.h"
#include "model/colon.h"

#define GAS_SEGMENTS ANATOMY_SEGMENTS
#define GAS_PA_PER_MMHG 133.322387415
#define GAS_M3_PER_L 1e-3

enum gas_kind { GAS_AIR = 0, GAS_CO2 = 1 };
enum gas_law_kind { GAS_LAW_POWEXP = 0, GAS_LAW_LINEAR = 1 };

/* One segment's wall: a case's [segment] keys (anatomy.h). */
struct gas_law {
	int kind;            /* enum gas_law_kind */
	double collapsed;    /* radius factor at zero transmural pressure */
	double max;          /* radius factor the wall stiffens towards */
	double nominal_pa;   /* the case's radius at this transmural p */
	double beta;         /* the power exponential's shape */
	double collapse_pa;  /* under suction: e-fold of the volume, Pa */
};

/* The case's defaults (anatomy.h); under suction the collapsed lumen
 * empties e-fold every 2 mmHg. */
#define GAS_COLLAPSE_PA (2 * GAS_PA_PER_MMHG)
#define GAS_LAW_DEFAULT { .kind = GAS_LAW_POWEXP, \
			  .collapsed = ANATOMY_DEFAULT_WALL_COLLAPSED, \
			  .max = ANATOMY_DEFAULT_WALL_MAX, \
			  .nominal_pa = ANATOMY_DEFAULT_WALL_NOMINAL_PA, \
			  .beta = ANATOMY_DEFAULT_WALL_BETA, \
			  .collapse_pa = GAS_COLLAPSE_PA }

struct gas_params {
	int kind;                   /* enum gas_kind */
	double pump_m3_per_s;       /* the air valve covered */
	double suction_m3_per_s;    /* the suction valve pressed, tip in gas */
	double leak_m3_per_s_pa;    /* the anus, per Pa above leak_pa */
	double leak_pa;             /* the anus holds the gas below this */
	double absorb_air_per_s;    /* share of the volume absorbed a second */
	double absorb_co2_per_s;
	double relief_pa;           /* the pump stops at this; 0: never */
	double wall_strength_n_per_m; /* Laplace's p r at which a wall tears */
	double hydrostatic_pa_per_m;  /* the abdomen's contents, rho g */
};

/* Defaults (their reasons in docs/PATIENT.md): an endoscope's air pump
 * (~2 L/min), suction 3 L/min, the anus leaking above 20 mmHg at 1 L/min
 * per 10 mmHg more, air absorbed over hours and CO2 in minutes (150
 * times faster), no relief (an endoscope's own pump reaches > 300 mmHg;
 * an insufflator's stops at 50), a wall strength that tears the normal
 * case's cecum at ~81 mmHg, 0.74 mmHg per cm of depth. */
#define GAS_DEFAULT_PUMP_M3_PER_S 3.3e-5      /* 2.0 L/min */
#define GAS_DEFAULT_SUCTION_M3_PER_S 5e-5      /* 3.0 L/min */
#define GAS_DEFAULT_LEAK_M3_PER_S_PA 1.25e-8   /* 1 L/min per 10 mmHg */
#define GAS_DEFAULT_LEAK_PA 2670.0             /* 20 mmHg */
#define GAS_DEFAULT_ABSORB_AIR_PER_S 2e-5
#define GAS_DEFAULT_ABSORB_CO2_PER_S 3e-3
#define GAS_DEFAULT_RELIEF_PA 0.0
#define GAS_DEFAULT_WALL_STRENGTH_N_PER_M 540.0
#define GAS_DEFAULT_HYDROSTATIC_PA_PER_M 9866.0 /* 0.74 mmHg per cm */

#define GAS_PARAMS_DEFAULT { .kind = GAS_AIR, \
	.pump_m3_per_s = GAS_DEFAULT_PUMP_M3_PER_S, \
	.suction_m3_per_s = GAS_DEFAULT_SUCTION_M3_PER_S, \
	.leak_m3_per_s_pa = GAS_DEFAULT_LEAK_M3_PER_S_PA, \
	.leak_pa = GAS_DEFAULT_LEAK_PA, \
	.absorb_air_per_s = GAS_DEFAULT_ABSORB_AIR_PER_S, \
	.absorb_co2_per_s = GAS_DEFAULT_ABSORB_CO2_PER_S, \
	.relief_pa = GAS_DEFAULT_RELIEF_PA, \
	.wall_strength_n_per_m = GAS_DEFAULT_WALL_STRENGTH_N_PER_M, \
	.hydrostatic_pa_per_m = GAS_DEFAULT_HYDROSTATIC_PA_PER_M }

/* This step's inputs. */
struct gas_input {
	bool air;               /* the air/water valve covered (air in) */
	bool suction;           /* the suction valve pressed, tip in gas */
	double down[3];         /* gravity's direction in the body's frame
				   (unit; zeros: no hydrostatic pressure) */
	double fluid_m3[GAS_SEGMENTS]; /* fluid held in each segment */
};

struct gas_segment {
	double length_m;        /* along the centreline */
	double radius_m;        /* R: the case's mean lumen radius */
	double widest_m;        /* its widest ring's mean radius (Laplace's
				   r: the widest part tears first) */
	double volume0_m3;      /* V0: its lumen at the case's radius */
	double centre[3];       /* its centreline's mean point, body frame */
	struct gas_law law;
	/* the state, as of the last step */
	double transmural_pa;   /* p */
	double factor;          /* r / R, never below the scope's radius
				   (the wall closes on the tube, not past
				   it; the volume follows the law) */
	double tension_n_per_m; /* p r at its widest, 0 when p <= 0 */
	bool burst;
};

struct gas {
	struct gas_params p;
	int segments;           /* 0 until attached: no gas model */
	struct gas_segment seg[GAS_SEGMENTS];
	double volume_m3;       /* the gas */
	double pressure_pa;     /* P, above the atmosphere */
	double flow_in_m3;      /* gas pumped in so far (the pump's total) */
	int burst_segment;      /* the first torn, -1: none */
};

/*
 * Sets P and the segments of a generated COLON (an imported one has no
 * segments: the gas stays detached, every factor 1) with the wall LAW
 * of each segment (NULL: its case's, anatomy.h), filled with
 * as much gas as holds the uppermost segment at its nominal pressure
 * under gravity DOWN (zeros: none). No allocation.
 */
void gas_attach(struct gas *g, const struct gas_params *p,
		const struct colon *colon, const struct gas_law *law,
		const double down[3]);

/* Segment I's wall law as case A gives it. */
struct gas_law gas_law_of(const struct anatomy *a, int i);

/* Live parameters (the kind of gas, flows, strength). */
void gas_set_params(struct gas *g, const struct gas_params *p);

/* The volume factor v(P_TRANSMURAL) of LAW, and its derivative (1/Pa). */
double gas_law_volume(const struct gas_law *law, double p_transmural,
		      double *dv_dp);

/* One step of DT_S seconds: the flows, then P and each segment's state.
 * Returns the segment that tore in this step, or -1. */
int gas_step(struct gas *g, const struct gas_input *in, double dt_s);

/* Sets the gas volume (m^3) and solves P for it, the inputs as IN says
 * (tests, a session's start). */
void gas_set_volume(struct gas *g, double volume_m3,
		    const struct gas_input *in);

/* The lumen's volume (gas and fluid) when the gas is at P_PA with the
 * inputs of IN: the sum the step solves, m^3. */
double gas_lumen_volume(const struct gas *g, double p_pa,
			const struct gas_input *in);

/*
 * The radius factor at material S_M (m) of COLON: its segment's, blended
 * linearly with the neighbour's over GAS_BLEND_M either side of their
 * boundary (the case's radii blend alike): one surface for the rod's
 * contact, the tip's and the picture. FACTOR: the nine factors (as
 * published); 1 for an imported colon. Any thread.
 */
#define GAS_BLEND_M 0.015
double gas_factor_at(const struct colon *colon,
		     const double factor[GAS_SEGMENTS], double s_m);

/* The same at S_M in segment I (0 .. GAS_SEGMENTS - 1), which runs from
 * S0_M to S1_M: for a reader that knows the segments but has no colon
 * (endoview: the scene's regions). Any thread. */
double gas_factor_in(const double factor[GAS_SEGMENTS], int i, double s0_m,
		     double s1_m, double s_m);

#endif
