/* plant.c - see plant.h. */
#include "model/plant.h"

#include <math.h>

/* Below this b / m (1/s) the viscous term is negligible: use uniform
 * acceleration (avoids 0/0 in the exponential solution). */
#define VISCOUS_EPS 1e-9

static double sign(double v)
{
	return (v > 0) - (v < 0);
}

/* State after T seconds under the constant net force FNET with viscous
 * damping only. */
static void advance(const struct plant_params *p, double *x, double *v,
		    double fnet, double t)
{
	double a = p->viscous / p->inertia;

	if (a < VISCOUS_EPS) {
		*x += *v * t + 0.5 * fnet / p->inertia * t * t;
		*v += fnet / p->inertia * t;
		return;
	}
	double vinf = fnet / p->viscous;
	double e = exp(-a * t);

	*x += vinf * t + (*v - vinf) * (1.0 - e) / a;
	*v = vinf + (*v - vinf) * e;
}

/* Time until a moving axis under the net force FNET comes to rest, or
 * INFINITY when FNET does not oppose the motion. */
static double time_to_rest(const struct plant_params *p, double v, double fnet)
{
	double a = p->viscous / p->inertia;

	if (sign(fnet) != -sign(v)) {
		return INFINITY;
	}
	if (a < VISCOUS_EPS) {
		return -v * p->inertia / fnet;
	}
	double vinf = fnet / p->viscous;

	return -log(-vinf / (v - vinf)) / a;
}

void plant_init(struct plant *pl, const struct plant_params *p, double x0)
{
	pl->p = *p;
	pl->x = fmin(fmax(x0, p->min), p->max);
	pl->v = 0;
}

static void end_stops(struct plant *pl)
{
	if (pl->x > pl->p.max) {
		pl->x = pl->p.max;
		pl->v = fmin(pl->v, 0);
	} else if (pl->x < pl->p.min) {
		pl->x = pl->p.min;
		pl->v = fmax(pl->v, 0);
	}
}

void plant_step(struct plant *pl, double force, double dt)
{
	const struct plant_params *p = &pl->p;
	double t = dt;

	if (pl->v != 0) {
		double fnet = force - p->coulomb * sign(pl->v);
		double t0 = time_to_rest(p, pl->v, fnet);

		if (t0 >= t) {
			advance(p, &pl->x, &pl->v, fnet, t);
			end_stops(pl);
			return;
		}
		advance(p, &pl->x, &pl->v, fnet, t0);
		pl->v = 0;
		t -= t0;
	}
	/* at rest: static friction holds unless the force overcomes it */
	if (fabs(force) > p->coulomb) {
		advance(p, &pl->x, &pl->v, force - p->coulomb * sign(force), t);
	}
	end_stops(pl);
}
