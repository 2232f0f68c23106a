/*
 * vitals.h - the patient's vital signs on the monitor: the heart rate and
 * the oxygen saturation. Simple models, documented as such: no
 * physiology, the two behaviours an endoscopist watches for.
 *
 *  - The heart rate rises with pain (the sympathetic response): it
 *    follows rest_bpm + bpm_per_pain * pain (pain 0..10, pain.h) with
 *    time constant heart_s (a heart answers in seconds, and settles over
 *    tens of them);
 *  - the saturation falls with sedation (the respiratory depression of
 *    deep sedation; room air): it follows the sedation's level in
 *    spo2[] with time constant spo2_s (a minute: oxygen stores drain
 *    slowly).
 * Both are first-order responses, exact for inputs held over a step:
 *   x += (target - x) (1 - exp(-dt / tau)).
 *
 * The defaults: 72 bpm at rest, 3 bpm a point of pain (pain 10: 102 bpm),
 * 8 s; saturation 0.98 unsedated, 0.975 minimal, 0.965 moderate, 0.94
 * deep (below 0.95 the monitor's first alarm in many units), 60 s.
 *
 * Units: beats a minute, a share 0..1, seconds. Plain data, no
 * allocation, fixed work. One writer.
 */
#ifndef ENDOSIM_VITALS_H
#define ENDOSIM_VITALS_H

#include "proto/endosim_shm.h"

struct vitals_params {
	double rest_bpm;
	double bpm_per_pain;
	double heart_s;
	double spo2[ENDOSIM_SEDATIONS]; /* by enum endosim_sedation */
	double spo2_s;
};

#define VITALS_DEFAULT_REST_BPM 72.0
#define VITALS_DEFAULT_BPM_PER_PAIN 3.0
#define VITALS_DEFAULT_HEART_S 8.0
#define VITALS_DEFAULT_SPO2_S 60.0

#define VITALS_PARAMS_DEFAULT { .rest_bpm = VITALS_DEFAULT_REST_BPM, \
		.bpm_per_pain = VITALS_DEFAULT_BPM_PER_PAIN, \
		.heart_s = VITALS_DEFAULT_HEART_S, \
		.spo2 = { 0.98, 0.975, 0.965, 0.94 }, \
		.spo2_s = VITALS_DEFAULT_SPO2_S }

struct vitals {
	double heart_rate_bpm;
	double spo2;            /* 0..1 */
};

/* At rest without pain under SEDATION (enum endosim_sedation). */
void vitals_reset(struct vitals *v, const struct vitals_params *p,
		  int sedation);

/* One step of DT_S with PAIN (0..10) under SEDATION. */
void vitals_step(struct vitals *v, const struct vitals_params *p,
		 double pain, int sedation, double dt_s);

#endif
