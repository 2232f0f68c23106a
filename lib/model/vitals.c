/* vitals.c - the patient's heart rate and saturation (vitals.h). */
#include "model/vitals.h"

#include "base/lag.h"

static double spo2_of(const struct vitals_params *p, int sedation)
{
	if (sedation < 0 || sedation >= ENDOSIM_SEDATIONS) {
		sedation = ENDOSIM_SEDATION_NONE;
	}
	return p->spo2[sedation];
}

void vitals_reset(struct vitals *v, const struct vitals_params *p,
		  int sedation)
{
	v->heart_rate_bpm = p->rest_bpm;
	v->spo2 = spo2_of(p, sedation);
}

void vitals_step(struct vitals *v, const struct vitals_params *p,
		 double pain, int sedation, double dt_s)
{
	v->heart_rate_bpm = lag_follow(v->heart_rate_bpm,
				       p->rest_bpm + p->bpm_per_pain * pain,
				       p->heart_s, dt_s);
	v->spo2 = lag_follow(v->spo2, spo2_of(p, sedation), p->spo2_s, dt_s);
}
