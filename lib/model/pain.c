/* pain.c - the patient's pain from the mechanics (pain.h). */
#include "model/pain.h"

#include <math.h>
#include <stddef.h>

#include "base/lag.h"

/* gain and threshold factors, in enum endosim_sedation's order */
static const double sedation_gain[ENDOSIM_SEDATIONS] = {
	1, 0.9, 0.75, 0.3,
};
static const double sedation_threshold[ENDOSIM_SEDATIONS] = {
	1, 1.05, 1.15, 2,
};

void pain_sedation_factors(int s, double *gain, double *threshold)
{
	if (s < 0 || s >= ENDOSIM_SEDATIONS) {
		s = PAIN_DEFAULT_SEDATION;
	}
	*gain = sedation_gain[s];
	*threshold = sedation_threshold[s];
}

void pain_reset(struct pain *p)
{
	*p = (struct pain){ .cause = ENDOSIM_PAIN_NONE, .place = -1 };
}

/* gain (x - threshold) above the threshold; 0 below, and for NaN */
static double term(double x, double threshold, double gain)
{
	return x > threshold ? gain * (x - threshold) : 0;
}

/* The largest of N values (non-finite ones none) and its index (-1). */
static double largest(int n, const double *x, int *at)
{
	double most = 0;

	*at = -1;
	for (int i = 0; x && i < n; i++) {
		if (isfinite(x[i]) && x[i] > most) {
			most = x[i];
			*at = i;
		}
	}
	return most;
}

/* Stretch is looping while the tube goes in or stays, straightening
 * while it comes out or turns. */
static int stretch_cause(const struct pain_params *par,
			 const struct pain_input *in)
{
	if (in->insertion_m_s < -par->moving_m_s ||
	    fabs(in->roll_rad_s) > par->turning_rad_s) {
		return ENDOSIM_PAIN_STRAIGHTENING;
	}
	return ENDOSIM_PAIN_LOOPING;
}

void pain_step(struct pain *p, const struct pain_params *par,
	       const struct pain_input *in, double dt_s)
{
	double g, t, tau, stretch, wall;
	int span, seg;

	pain_sedation_factors(par->sedation, &g, &t);
	stretch = largest(in->spans, in->span_tension_n, &span);
	wall = largest(in->segments, in->wall_n_per_m, &seg);
	p->stretch = term(stretch, t * par->stretch_threshold_n,
			  g * par->stretch_gain_per_n);
	p->distension = term(wall, t * par->wall_threshold_n_per_m,
			     g * par->wall_gain_per_n_per_m);
	p->tip = term(in->tip_force_n, t * par->tip_threshold_n,
		      g * par->tip_gain_per_n);
	p->stimulus = fmin(PAIN_MAX, p->stretch + p->distension + p->tip);
	p->cause = ENDOSIM_PAIN_NONE;
	p->place = -1;
	if (p->stimulus > 0) {
		if (p->tip >= p->stretch && p->tip >= p->distension) {
			p->cause = ENDOSIM_PAIN_TIP;
			p->place = in->tip_segment;
		} else if (p->distension >= p->stretch) {
			p->cause = ENDOSIM_PAIN_INSUFFLATION;
			p->place = seg;
		} else {
			p->cause = stretch_cause(par, in);
			p->place = span >= 0 && in->span_segment ?
					   in->span_segment[span] : -1;
		}
	}
	tau = p->stimulus > p->level ? par->rise_s : par->fade_s;
	p->level = lag_follow(p->level, p->stimulus, tau, dt_s);
}
