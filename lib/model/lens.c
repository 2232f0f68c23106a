/* lens.c - see lens.h. */
#include "model/lens.h"

#include <math.h>
#include <string.h>

#include "base/lag.h"

static double unit(double x)
{
	return fmax(0, fmin(1, x));
}

void lens_reset(struct lens *l)
{
	memset(l, 0, sizeof(*l));
}

void lens_step(struct lens *l, const struct lens_params *p,
	       const struct lens_input *in, double dt_s)
{
	double pressed = fmax(0, in->tip_force_n - p->contact_n);
	double target = in->suction && in->wall_gap_m < p->redout_gap_m;

	if (p->smear_n_s > 0) {
		l->smear = unit(l->smear + dt_s * pressed / p->smear_n_s);
	}
	if (in->under_fluid && p->dip_s > 0) {
		l->murk = unit(l->murk + dt_s / p->dip_s);
	}
	if (in->water && p->wash_s > 0) {
		l->smear = unit(l->smear - dt_s / p->wash_s);
		l->murk = unit(l->murk - dt_s / p->wash_s);
	}
	l->redout = lag_follow(l->redout, target, p->redout_s, dt_s);
}
