/* fluid.c - see fluid.h. */
#include "model/fluid.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"

#define NEWTON_ITERATIONS 3  /* a step's, from the last level */
#define SETTLE_ITERATIONS 60 /* from nothing: bisection's worst case */

/* A unit disc's area below the chord at height X (-1..1). */
static double disc_below(double x)
{
	x = fmax(-1, fmin(1, x));
	return acos(-x) + x * sqrt(1 - x * x);
}

/* The lumen's radius at sample K with the gas's FACTOR. */
static double ring_radius(const struct fluid *f, size_t k,
			  const double *factor)
{
	const struct centreline *cl = colon_centreline(f->colon);
	double r = colon_tube_radius(f->colon, k);

	return factor ? r * gas_factor_at(f->colon, factor,
					   (double)k * centreline_step(cl))
		      : r;
}

/* The rings of segment S: every STRIDE-th sample. */
static size_t stride_of(const struct fluid *f, const struct fluid_segment *s)
{
	double ds = centreline_step(colon_centreline(f->colon));
	size_t stride = (size_t)fmax(1, lround(FLUID_RING_M / ds));

	while (s->count / stride > FLUID_MAX_RINGS) {
		stride++;
	}
	return stride;
}

/* Segment S's fluid below level H, and its derivative in H; its lowest
 * and highest points' heights in *LOW and *HIGH. */
static double volume_below(const struct fluid *f,
			   const struct fluid_segment *s, const double *factor,
			   double h, double *dv_dh, double *low, double *high)
{
	const struct centreline *cl = colon_centreline(f->colon);
	size_t stride = stride_of(f, s);
	size_t end = s->first + s->count;
	double step = centreline_step(cl), v = 0, d = 0;

	*low = INFINITY;
	*high = -INFINITY;
	/* each ring stands for its chunk of samples [k0, k0 + n) */
	for (size_t k0 = s->first; k0 < end; k0 += stride) {
		size_t n = end - k0 < stride ? end - k0 : stride;
		size_t k = k0 + n / 2;
		const struct centreline_point *c = centreline_sample(cl, k);
		double r = ring_radius(f, k, factor), tn = vec3_dot(c->t, f->up);
		double ds = step * (double)n;
		double e = r * sqrt(fmax(0, 1 - tn * tn)) + ds * fabs(tn) / 2;
		double x = (h - vec3_dot(c->p, f->up)) / e;

		*low = fmin(*low, vec3_dot(c->p, f->up) - e);
		*high = fmax(*high, vec3_dot(c->p, f->up) + e);
		v += ds * r * r * disc_below(x);
		if (fabs(x) < 1) {
			d += ds * r * r * 2 * sqrt(1 - x * x) / e;
		}
	}
	*dv_dh = d;
	return v;
}

/* Segment I's level for its volume: Newton from the last level, within
 * the bracket [lowest, highest] that bisects a step leaving it; at most
 * ITERATIONS. */
static void solve_level(struct fluid *f, int i, const double *factor,
			int iterations)
{
	struct fluid_segment *s = &f->seg[i];
	double h = s->level_m, lo, hi, d, v;

	volume_below(f, s, factor, h, &d, &lo, &hi);
	if (s->volume_m3 <= 0) {
		s->level_m = lo;
		s->depth_m = 0;
		return;
	}
	if (!(h > lo && h < hi)) {
		h = (lo + hi) / 2;
	}
	for (int it = 0; it < iterations; it++) {
		double a, b, next;

		v = volume_below(f, s, factor, h, &d, &a, &b);
		if (fabs(v - s->volume_m3) < 1e-9 * s->volume_m3) {
			break;
		}
		if (v > s->volume_m3) {
			hi = h;
		} else {
			lo = h;
		}
		next = d > 0 ? h - (v - s->volume_m3) / d : NAN;
		h = next > lo && next < hi ? next : (lo + hi) / 2;
	}
	s->level_m = h;
	volume_below(f, s, factor, h, &d, &lo, &hi);
	s->depth_m = h - lo;
}

void fluid_attach(struct fluid *f, const struct fluid_params *p,
		  const struct colon *colon, const double *volume_m3,
		  const double down[3], const double *factor)
{
	const struct centreline *cl = colon_centreline(colon);
	double ds = centreline_step(cl);

	memset(f, 0, sizeof(*f));
	f->p = *p;
	f->colon = colon;
	vec3_scale(f->up, down, -1);
	if (!colon_anatomy(colon) || colon_regions(colon) != FLUID_SEGMENTS ||
	    vec3_normalize(f->up) <= 0) {
		vec3_set(f->up, 0, -1, 0);
		if (!colon_anatomy(colon) ||
		    colon_regions(colon) != FLUID_SEGMENTS) {
			return;
		}
	}
	f->segments = FLUID_SEGMENTS;
	for (int i = 0; i < FLUID_SEGMENTS; i++) {
		const struct colon_region *r = colon_region(colon, i);
		size_t a = (size_t)lround(r->s0_m / ds);
		size_t b = (size_t)lround(r->s1_m / ds);

		b = b < centreline_count(cl) ? b : centreline_count(cl);
		f->seg[i].first = a;
		f->seg[i].count = b > a ? b - a : 1;
		f->seg[i].volume_m3 = volume_m3 ? fmax(0, volume_m3[i]) : 0;
		f->seg[i].level_m = NAN;
	}
	fluid_settle(f, factor);
}

void fluid_set_params(struct fluid *f, const struct fluid_params *p)
{
	f->p = *p;
}

void fluid_settle(struct fluid *f, const double *factor)
{
	for (int i = 0; i < f->segments; i++) {
		f->seg[i].level_m = NAN;
		solve_level(f, i, factor, SETTLE_ITERATIONS);
	}
}

bool fluid_under(const struct fluid *f, int i, const double p[3])
{
	return i >= 0 && i < f->segments && f->seg[i].volume_m3 > 0 &&
	       vec3_dot(p, f->up) < f->seg[i].level_m;
}

bool fluid_step(struct fluid *f, const double down[3], const double *factor,
		bool suction, const double tip[3], int tip_segment,
		double dt_s)
{
	double want[3], k;
	bool under;

	if (!f->segments) {
		return false;
	}
	vec3_scale(want, down, -1);
	if (vec3_normalize(want) > 0) {
		k = f->p.settle_s > 0 ? fmin(1, dt_s / f->p.settle_s) : 1;
		vec3_lerp(f->up, f->up, want, k);
		vec3_normalize(f->up);
	}
	under = fluid_under(f, tip_segment, tip);
	if (suction && under) {
		struct fluid_segment *s = &f->seg[tip_segment];
		double take = fmin(s->volume_m3, f->p.suction_m3_per_s * dt_s);

		s->volume_m3 -= take;
		f->sucked_m3 += take;
	}
	solve_level(f, f->next, factor, NEWTON_ITERATIONS);
	f->next = (f->next + 1) % f->segments;
	return under;
}

void fluid_add(struct fluid *f, int i, double volume_m3)
{
	if (i >= 0 && i < f->segments && volume_m3 > 0) {
		f->seg[i].volume_m3 += volume_m3;
	}
}

void fluid_volumes(const struct fluid *f, double out[FLUID_SEGMENTS])
{
	for (int i = 0; i < FLUID_SEGMENTS; i++) {
		out[i] = i < f->segments ? f->seg[i].volume_m3 : 0;
	}
}

int fluid_segment_at(const struct fluid *f, double s_m)
{
	return f->segments ? colon_region_at(f->colon, s_m) : -1;
}
