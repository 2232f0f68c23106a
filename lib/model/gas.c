/* gas.c - see gas.h. */
#include "model/gas.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"
#include "model/scope.h"

#define NEWTON_MAX 30        /* iterations at most; 2-4 as a rule */
#define NEWTON_TOL_M3 1e-12  /* the volume matched within this */
#define BURST_LEAK_M3_PER_S_PA (1e-3 / 1000.0) /* a tear: 1 L/s per kPa */

/* kappa of a power-exponential LAW: v(nominal) = 1. */
static double law_kappa(const struct gas_law *law)
{
	double vc = law->collapsed * law->collapsed;
	double vm = law->max * law->max;

	return law->nominal_pa * pow(-log((1 - vc) / (vm - vc)),
				     1 / law->beta);
}

double gas_law_volume(const struct gas_law *law, double p, double *dv_dp)
{
	double vc = law->collapsed * law->collapsed, v, d;

	if (law->kind == GAS_LAW_LINEAR) {
		double slope = (1 - vc) / law->nominal_pa;

		if (p >= 0) {
			v = vc + slope * p;
			d = slope;
		} else {
			v = vc * exp(p * slope / vc);
			d = slope * v / vc;
		}
	} else if (p > 0) {
		double vm = law->max * law->max;
		double x = pow(law_kappa(law) / p, law->beta);
		double e = exp(-x);

		v = vc + (vm - vc) * e;
		d = (vm - vc) * e * x * law->beta / p;
	} else {
		v = vc * exp(p / law->collapse_pa);
		d = v / law->collapse_pa;
	}
	if (dv_dp) {
		*dv_dp = d;
	}
	return v;
}

/* Each segment's abdominal pressure under gravity DOWN: rho_g times its
 * depth below the highest segment's centre. */
static void abdominal(const struct gas *g, const double down[3],
		      double p_abd[GAS_SEGMENTS])
{
	double top = -INFINITY;

	for (int i = 0; i < g->segments; i++) {
		p_abd[i] = -vec3_dot(g->seg[i].centre, down); /* height */
		top = fmax(top, p_abd[i]);
	}
	for (int i = 0; i < g->segments; i++) {
		p_abd[i] = g->p.hydrostatic_pa_per_m * (top - p_abd[i]);
	}
}

/* The lumen volume at gas pressure P with abdominal pressures P_ABD, and
 * its derivative. */
static double lumen_volume(const struct gas *g, double p,
			   const double p_abd[GAS_SEGMENTS], double *dv_dp)
{
	double v = 0, d = 0;

	for (int i = 0; i < g->segments; i++) {
		const struct gas_segment *s = &g->seg[i];
		double di;

		v += s->volume0_m3 *
		     gas_law_volume(&s->law, p - p_abd[i], &di);
		d += s->volume0_m3 * di;
	}
	if (dv_dp) {
		*dv_dp = d;
	}
	return v;
}

double gas_lumen_volume(const struct gas *g, double p_pa,
			const struct gas_input *in)
{
	double p_abd[GAS_SEGMENTS];

	abdominal(g, in->down, p_abd);
	return lumen_volume(g, p_pa, p_abd, NULL);
}

/* The gas pressure at which the lumen holds TARGET (m^3): Newton from the
 * last pressure, kept inside a bracket that bisects when it overshoots. */
static double solve_pressure(const struct gas *g, double target,
			     const double p_abd[GAS_SEGMENTS])
{
	double lo = -INFINITY, hi = INFINITY, p = g->pressure_pa;

	for (int k = 0; k < NEWTON_MAX; k++) {
		double d, f = lumen_volume(g, p, p_abd, &d) - target, next;

		if (isnan(f)) {
			return NAN; /* a law or volume gone bad: no pressure
				       bursts a wall, the loop faults */
		}
		if (fabs(f) < NEWTON_TOL_M3) {
			break;
		}
		if (f > 0) {
			hi = p;
		} else {
			lo = p;
		}
		next = d > 0 ? p - f / d : NAN;
		if (!(next > lo && next < hi)) { /* outside: bisect */
			next = isfinite(lo) && isfinite(hi) ? (lo + hi) / 2 :
			       isfinite(lo) ? lo + fmax(1000, fabs(lo)) :
					      hi - fmax(1000, fabs(hi));
		}
		p = next;
	}
	return p;
}

/* Each segment's state at P. */
static void segments_at(struct gas *g, double p,
			const double p_abd[GAS_SEGMENTS])
{
	for (int i = 0; i < g->segments; i++) {
		struct gas_segment *s = &g->seg[i];
		double least = SCOPE_RADIUS_M / s->radius_m, f;

		s->transmural_pa = p - p_abd[i];
		/* the wall closes on the scope, not past it (a NaN stays one:
		   the loop's non-finite check must see it) */
		f = sqrt(gas_law_volume(&s->law, s->transmural_pa, NULL));
		s->factor = f < least ? least : f;
		s->tension_n_per_m = fmax(0, s->transmural_pa) * s->widest_m *
				     s->factor;
	}
}

static double fluid_total(const struct gas *g, const struct gas_input *in)
{
	double v = 0;

	for (int i = 0; i < g->segments; i++) {
		v += fmax(0, in->fluid_m3[i]);
	}
	return v;
}

void gas_set_volume(struct gas *g, double volume_m3,
		    const struct gas_input *in)
{
	double p_abd[GAS_SEGMENTS];

	abdominal(g, in->down, p_abd);
	g->volume_m3 = fmax(0, volume_m3);
	g->pressure_pa = solve_pressure(g, g->volume_m3 + fluid_total(g, in),
					p_abd);
	segments_at(g, g->pressure_pa, p_abd);
}

/* A segment's centre, length and lumen from COLON's region I. */
static void measure_segment(const struct colon *colon, int i,
			    struct gas_segment *s)
{
	const struct colon_region *r = colon_region(colon, i);
	const struct centreline *cl = colon_centreline(colon);
	double ds = centreline_step(cl), area = 0, c[3] = { 0, 0, 0 };
	size_t a = (size_t)lround(r->s0_m / ds), b = (size_t)lround(r->s1_m / ds);
	size_t n = centreline_count(cl);

	b = b < n ? b : n - 1;
	s->widest_m = 0;
	for (size_t k = a; k <= b; k++) {
		double rk = colon_tube_radius(colon, k);

		s->widest_m = fmax(s->widest_m, rk);
		area += M_PI * rk * rk;
		vec3_add(c, c, centreline_base(cl, k)->p);
	}
	s->length_m = r->s1_m - r->s0_m;
	s->volume0_m3 = area / (double)(b - a + 1) * s->length_m;
	s->radius_m = sqrt(s->volume0_m3 / (M_PI * s->length_m));
	vec3_scale(s->centre, c, 1.0 / (double)(b - a + 1));
}

struct gas_law gas_law_of(const struct anatomy *a, int i)
{
	const struct anatomy_segment *s = &a->seg[i];

	return (struct gas_law){ .kind = GAS_LAW_POWEXP,
				 .collapsed = s->wall_collapsed,
				 .max = s->wall_max,
				 .nominal_pa = s->wall_nominal_pa,
				 .beta = s->wall_beta,
				 .collapse_pa = GAS_COLLAPSE_PA };
}

void gas_attach(struct gas *g, const struct gas_params *p,
		const struct colon *colon, const struct gas_law *law,
		const double down[3])
{
	struct gas_input in = { .down = { down[0], down[1], down[2] } };
	double p_abd[GAS_SEGMENTS], most = 0;

	memset(g, 0, sizeof(*g));
	g->p = *p;
	g->burst_segment = -1;
	if (!colon_anatomy(colon) || colon_regions(colon) != GAS_SEGMENTS) {
		return;
	}
	g->segments = GAS_SEGMENTS;
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		measure_segment(colon, i, &g->seg[i]);
		g->seg[i].law = law ? law[i]
				    : gas_law_of(colon_anatomy(colon), i);
		g->seg[i].factor = 1;
	}
	/* as much gas as holds the uppermost segment at its nominal p */
	abdominal(g, in.down, p_abd);
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		if (p_abd[i] == 0) {
			most = fmax(most, g->seg[i].law.nominal_pa);
		}
	}
	g->pressure_pa = most;
	gas_set_volume(g, lumen_volume(g, most, p_abd, NULL), &in);
}

void gas_set_params(struct gas *g, const struct gas_params *p)
{
	g->p = *p;
}

/* The step's net flow into the colon, m^3/s, at the last pressure, and
 * in *G the conductance of what flows out by the pressure (m^3/s/Pa). */
static double net_flow(const struct gas *g, const struct gas_input *in,
		       double *cond)
{
	double p = g->pressure_pa, q = 0;
	double absorb = g->p.kind == GAS_CO2 ? g->p.absorb_co2_per_s :
					       g->p.absorb_air_per_s;

	if (in->air && !(g->p.relief_pa > 0 && p >= g->p.relief_pa)) {
		q += g->p.pump_m3_per_s;
	}
	if (in->suction) {
		q -= g->p.suction_m3_per_s;
	}
	*cond = 0;
	if (p > g->p.leak_pa) {
		q -= g->p.leak_m3_per_s_pa * (p - g->p.leak_pa);
		*cond += g->p.leak_m3_per_s_pa;
	}
	if (g->burst_segment >= 0 && p > 0) {
		q -= BURST_LEAK_M3_PER_S_PA * p;
		*cond += BURST_LEAK_M3_PER_S_PA;
	}
	return q - absorb * g->volume_m3;
}

int gas_step(struct gas *g, const struct gas_input *in, double dt_s)
{
	double p_abd[GAS_SEGMENTS], q, cond, c;
	int torn = -1;

	if (!g->segments) {
		return -1;
	}
	abdominal(g, in->down, p_abd);
	q = net_flow(g, in, &cond);
	if (in->air && !(g->p.relief_pa > 0 &&
			 g->pressure_pa >= g->p.relief_pa)) {
		g->flow_in_m3 += g->p.pump_m3_per_s * dt_s;
	}
	/* the outflows that grow with the pressure taken implicitly (the
	 * pressure's rise per volume is 1 / C): a stiff wall and a wide
	 * leak stay stable at any step */
	lumen_volume(g, g->pressure_pa, p_abd, &c);
	g->volume_m3 = fmax(0, g->volume_m3 +
				       q * dt_s / (1 + dt_s * cond / fmax(c, 1e-15)));
	g->pressure_pa = solve_pressure(g, g->volume_m3 + fluid_total(g, in),
					p_abd);
	segments_at(g, g->pressure_pa, p_abd);
	for (int i = 0; i < g->segments; i++) {
		struct gas_segment *s = &g->seg[i];

		if (!s->burst &&
		    s->tension_n_per_m > g->p.wall_strength_n_per_m) {
			s->burst = true;
			torn = torn < 0 ? i : torn;
			if (g->burst_segment < 0) {
				g->burst_segment = i;
			}
		}
	}
	return torn;
}

double gas_factor_in(const double factor[GAS_SEGMENTS], int i, double s0_m,
		     double s1_m, double s_m)
{
	double f = factor[i], w;

	if (i > 0 && s_m < s0_m + GAS_BLEND_M) {
		w = 0.5 + 0.5 * (s_m - s0_m) / GAS_BLEND_M; /* 0.5 .. 1 */
		return factor[i - 1] + (f - factor[i - 1]) * fmax(0.5, w);
	}
	if (i + 1 < GAS_SEGMENTS && s_m > s1_m - GAS_BLEND_M) {
		w = 0.5 + 0.5 * (s1_m - s_m) / GAS_BLEND_M;
		return factor[i + 1] + (f - factor[i + 1]) * fmax(0.5, w);
	}
	return f;
}

double gas_factor_at(const struct colon *colon,
		     const double factor[GAS_SEGMENTS], double s_m)
{
	int n = colon_anatomy(colon) ? colon_regions(colon) : 0, i;
	const struct colon_region *r;

	if (n != GAS_SEGMENTS) {
		return 1;
	}
	i = colon_region_at(colon, s_m);
	r = colon_region(colon, i);
	return gas_factor_in(factor, i, r->s0_m, r->s1_m, s_m);
}
