/*
 * pain.h - the patient's pain from the mechanics, on the clinical 0-10
 * numeric rating scale, every cycle from what the model computes:
 *
 *  - stretch: the mesentery's tension where a mobile span is pushed off
 *    its course (flex_span_tension(): the nodes' mesentery springs,
 *    stiffening as they stretch), N, the largest span's;
 *  - distension: the wall's tension by Laplace's law, the transmural
 *    pressure times the lumen's radius (N/m), the largest segment's;
 *  - the tip: its force on the wall, N.
 *
 * Each term is gain * (x - threshold) above its threshold and 0 below;
 * the stimulus is their sum, at most 10. Sedation scales every gain by
 * its factor and every threshold by its own (the sedated patient feels
 * less and later). The level follows the stimulus as a first-order
 * response: it rises with time constant rise_s and fades with fade_s,
 *   level += (stimulus - level) (1 - exp(-dt / tau)),
 * exact for a stimulus held over the step, so that a step of stimulus S
 * from 0 gives S (1 - exp(-t / rise_s)) and its end S0 exp(-t / fade_s).
 *
 * Each moment's pain has a cause, the term that gives most of the
 * stimulus: the tip's pressure; over-insufflation (distension); or the
 * stretch, which is looping while the tube is pushed in (or held still)
 * and straightening while it is withdrawn or turned (faster than
 * moving_m_s, turning_rad_s). And a place: the segment (anatomy.h's
 * index) of the largest stretch, the largest wall tension, or the tip.
 *
 * The defaults and why (docs/PATIENT.md, "Pain"), calibrated on the
 * scripted trainee's demo course on the normal case (tests/tools/
 * trainee.h), whose sigmoid (600 N/m, a 6 cm mesentery) holds 10 N
 * pulled 2 cm off its course, 20 N at 4 cm and 40 N at 6 cm:
 *  - stretch from 8 N, 0.2 a newton: a 2 cm bow is painless, a 4 cm loop
 *    an ache (2.4), the 6 cm loop of the course's mistake 6.4, the pain
 *    that makes patients ask for more analgesia (Shah et al. 2002: 79 %
 *    of the requests during looping);
 *  - distension from 120 N/m, 0.04 per N/m: 30 mmHg in a 3 cm lumen,
 *    where barostat studies find the first discomfort in the colon;
 *    60 mmHg in a 3.5 cm lumen (280 N/m) gives 6.4;
 *  - the tip from 5 N, 0.5 a newton: the few newtons of steering past a
 *    fold do not hurt; 14 N, where a straight tip perforates porcine
 *    colon, gives 4.5 (with the loop that such a push makes, more);
 *  - rising in 0.3 s (a reflex), fading in 5 s (the ache that lingers).
 *
 * Sedation (the instructor's choice per session), gain and threshold
 * factors: none 1 and 1; minimal 0.9 and 1.05; moderate (the default)
 * 0.75 and 1.15; deep 0.3 and 2. Simple scalings, documented as such:
 * no pharmacology. Moderate ("conscious") sedation leaves a loop's pain
 * felt, as Shah's sedated patients did; deep sedation leaves little.
 *
 * Units SI. Plain data, no allocation; fixed work per cycle (one pass
 * over the spans and segments given). One writer.
 */
#ifndef ENDOSIM_PAIN_H
#define ENDOSIM_PAIN_H

#include <stdbool.h>

#include "proto/endosim_shm.h"

#define PAIN_MAX 10.0

struct pain_params {
	double stretch_threshold_n;
	double stretch_gain_per_n;
	double wall_threshold_n_per_m;
	double wall_gain_per_n_per_m;
	double tip_threshold_n;
	double tip_gain_per_n;
	double rise_s;
	double fade_s;
	double moving_m_s;    /* the tube pushed or withdrawn faster */
	double turning_rad_s; /* the tube turned faster */
	int sedation;         /* enum endosim_sedation */
};

#define PAIN_DEFAULT_STRETCH_THRESHOLD_N 8.0
#define PAIN_DEFAULT_STRETCH_GAIN_PER_N 0.2
#define PAIN_DEFAULT_WALL_THRESHOLD_N_PER_M 120.0
#define PAIN_DEFAULT_WALL_GAIN_PER_N_PER_M 0.04
#define PAIN_DEFAULT_TIP_THRESHOLD_N 5.0
#define PAIN_DEFAULT_TIP_GAIN_PER_N 0.5
#define PAIN_DEFAULT_RISE_S 0.3
#define PAIN_DEFAULT_FADE_S 5.0
#define PAIN_DEFAULT_MOVING_M_S 0.002
#define PAIN_DEFAULT_TURNING_RAD_S 0.2
#define PAIN_DEFAULT_SEDATION ENDOSIM_SEDATION_MODERATE

#define PAIN_PARAMS_DEFAULT { \
		.stretch_threshold_n = PAIN_DEFAULT_STRETCH_THRESHOLD_N, \
		.stretch_gain_per_n = PAIN_DEFAULT_STRETCH_GAIN_PER_N, \
		.wall_threshold_n_per_m = PAIN_DEFAULT_WALL_THRESHOLD_N_PER_M, \
		.wall_gain_per_n_per_m = PAIN_DEFAULT_WALL_GAIN_PER_N_PER_M, \
		.tip_threshold_n = PAIN_DEFAULT_TIP_THRESHOLD_N, \
		.tip_gain_per_n = PAIN_DEFAULT_TIP_GAIN_PER_N, \
		.rise_s = PAIN_DEFAULT_RISE_S, .fade_s = PAIN_DEFAULT_FADE_S, \
		.moving_m_s = PAIN_DEFAULT_MOVING_M_S, \
		.turning_rad_s = PAIN_DEFAULT_TURNING_RAD_S, \
		.sedation = PAIN_DEFAULT_SEDATION }

/* This cycle's mechanics. Arrays of SPANS and SEGMENTS entries. */
struct pain_input {
	int spans;
	const double *span_tension_n; /* flex_span_tension() */
	const int *span_segment;      /* the segment each span lies in */
	int segments;
	const double *wall_n_per_m;   /* transmural pressure x radius */
	double tip_force_n;           /* the tip's on the wall */
	int tip_segment;
	double insertion_m_s;         /* > 0: pushed in */
	double roll_rad_s;
};

struct pain {
	double level;       /* 0..PAIN_MAX, the patient's */
	double stimulus;    /* what it follows now */
	double stretch;     /* each term's part of the stimulus */
	double distension;
	double tip;
	int cause;          /* enum endosim_pain_cause: the largest part's */
	int place;          /* its segment; -1 with no cause */
};

/* The factors sedation S puts on every gain and threshold. */
void pain_sedation_factors(int s, double *gain, double *threshold);

/* Without pain, nothing felt yet. */
void pain_reset(struct pain *p);

/* One step of DT_S seconds. Non-finite inputs count as none. */
void pain_step(struct pain *p, const struct pain_params *par,
	       const struct pain_input *in, double dt_s);

#endif
