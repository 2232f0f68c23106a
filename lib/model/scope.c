/* scope.c - see scope.h. */
#include "model/scope.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"

#define SERIES_BELOW 0.05 /* rad: the arc's functions by their series */

/*
 * The arc's functions of its angle th, smooth through th = 0:
 * F = sin th / th, G = (1 - cos th) / th^2, F1 = F' / th, G1 = G' / th.
 */
struct arcfn {
	double f, g, f1, g1;
};

static void arc_functions(double th, struct arcfn *a)
{
	double t2 = th * th, t4 = t2 * t2, t6 = t4 * t2;

	if (th < SERIES_BELOW) {
		a->f = 1 - t2 / 6 + t4 / 120 - t6 / 5040;
		a->g = 0.5 - t2 / 24 + t4 / 720 - t6 / 40320;
		a->f1 = -1.0 / 3 + t2 / 30 - t4 / 840 + t6 / 45360;
		a->g1 = -1.0 / 12 + t2 / 180 - t4 / 6720 + t6 / 453600;
		return;
	}
	a->f = sin(th) / th;
	a->g = (1 - cos(th)) / t2;
	a->f1 = (th * cos(th) - sin(th)) / (t2 * th);
	a->g1 = (th * sin(th) - 2 * (1 - cos(th))) / t4;
}

/* Where the bending section starts, and its frame turned by the roll. */
struct base {
	struct centreline_point c; /* t, u' and v' after the roll */
	double s_m;                /* material s */
	double len_m;              /* inserted length of the bending section */
	double a[2];               /* its angles: (ud, lr) len / Lb, rad */
	double avec[3];            /* a[0] u' + a[1] v' */
	double th;                 /* |a| */
};

static void find_base(const struct scope_params *p,
		      const struct centreline *cl, double depth, double roll,
		      const double bend[2], struct base *b)
{
	double u[3];

	b->len_m = fmin(depth, p->bending_length_m);
	b->s_m = centreline_at_length(cl, depth - b->len_m, &b->c, NULL);
	vec3_scale(u, b->c.u, cos(roll));
	vec3_axpy(u, u, sin(roll), b->c.v);
	vec3_copy(b->c.u, u);
	vec3_cross(b->c.v, b->c.t, b->c.u);
	b->a[0] = bend[0] * b->len_m / p->bending_length_m;
	b->a[1] = bend[1] * b->len_m / p->bending_length_m;
	vec3_scale(b->avec, b->c.u, b->a[0]);
	vec3_axpy(b->avec, b->avec, b->a[1], b->c.v);
	b->th = hypot(b->a[0], b->a[1]);
}

/* The point X along the bending section (0 <= X <= len). */
static void arc_point(const struct base *b, double x, double out[3])
{
	double f = b->len_m > 0 ? x / b->len_m : 0;
	struct arcfn fn;

	arc_functions(b->th * f, &fn);
	vec3_axpy(out, b->c.p, x * fn.f, b->c.t);
	vec3_axpy(out, out, x * f * fn.g, b->avec);
}

static void tip_position(const struct scope_params *p,
			 const struct centreline *cl, double depth,
			 double roll, const double bend[2], double out[3])
{
	struct base b;

	find_base(p, cl, depth, roll, bend, &b);
	arc_point(&b, b.len_m, out);
}

/* dir = R t, up = R u' with R the rotation by w = t x avec. */
static void tip_frame(const struct base *b, const struct arcfn *fn,
		      struct scope_pose *out)
{
	double w[3], wu[3], wwu[3];

	vec3_scale(out->dir, b->c.t, cos(b->th));
	vec3_axpy(out->dir, out->dir, fn->f, b->avec);
	vec3_cross(w, b->c.t, b->avec);
	vec3_cross(wu, w, b->c.u);
	vec3_cross(wwu, w, wu);
	vec3_axpy(out->up, b->c.u, fn->f, wu);
	vec3_axpy(out->up, out->up, fn->g, wwu);
}

static void jacobian(const struct scope_params *p, const struct centreline *cl,
		     const struct base *b, const struct arcfn *fn,
		     struct scope_pose *out)
{
	double h = centreline_step(cl), most = scope_max_depth(p, cl);
	double lo = fmax(0, out->depth_m - h), hi = fmin(most, out->depth_m + h);
	double plo[3], phi[3], rel[3], col[3];
	double k = b->len_m / p->bending_length_m;

	tip_position(p, cl, lo, out->roll_rad, out->bend_rad, plo);
	tip_position(p, cl, hi, out->roll_rad, out->bend_rad, phi);
	for (int d = 0; d < 3; d++) {
		out->jacobian[d][0] = hi > lo ? (phi[d] - plo[d]) / (hi - lo) : 0;
	}
	vec3_sub(rel, out->tip, b->c.p);
	vec3_cross(col, b->c.t, rel);
	for (int d = 0; d < 3; d++) {
		out->jacobian[d][1] = col[d];
	}
	for (int j = 0; j < 2; j++) {
		const double *axis = j ? b->c.v : b->c.u;

		vec3_scale(col, b->c.t, fn->f1 * b->a[j]);
		vec3_axpy(col, col, fn->g1 * b->a[j], b->avec);
		vec3_axpy(col, col, fn->g, axis);
		for (int d = 0; d < 3; d++) {
			out->jacobian[d][2 + j] = b->len_m * k * col[d];
		}
	}
}

/* The sample nearest the tip, among those of the bending section. */
static double nearest_s(const struct centreline *cl, const struct base *b,
			const double tip[3])
{
	double ds = centreline_step(cl), best = INFINITY, s = b->s_m;
	size_t n = centreline_count(cl);
	size_t i = (size_t)floor(b->s_m / ds);
	size_t last = (size_t)ceil((b->s_m + 1.5 * b->len_m) / ds) + 1;

	for (; i < n && i <= last; i++) {
		double d = vec3_dist(centreline_sample(cl, i)->p, tip);

		if (d < best) {
			best = d;
			s = (double)i * ds;
		}
	}
	return s;
}

static void tube(const struct centreline *cl, const struct base *b,
		 double depth, struct scope_pose *out)
{
	double along = depth - b->len_m;
	size_t hint = 0;

	for (int i = 0; i < SCOPE_TUBE_POINTS; i++) {
		double x = depth * i / (SCOPE_TUBE_POINTS - 1);

		if (x <= along) {
			centreline_position_at_length(cl, x, out->tube[i],
						      &hint);
		} else {
			arc_point(b, x - along, out->tube[i]);
		}
	}
}

void scope_bend(const struct scope_params *p, double wheel_ud_rad,
		double wheel_lr_rad, double bend_rad[2],
		double dbend_dwheel[2])
{
	const double gain[2] = { p->ud_gain, p->lr_gain };
	const double limit[2] = { p->ud_limit_rad, p->lr_limit_rad };
	const double wheel[2] = { wheel_ud_rad, wheel_lr_rad };

	for (int j = 0; j < 2; j++) {
		double b = gain[j] * wheel[j];

		dbend_dwheel[j] = fabs(b) < limit[j] ? gain[j] : 0;
		bend_rad[j] = fmax(-limit[j], fmin(limit[j], b));
	}
}

double scope_max_depth(const struct scope_params *p,
		       const struct centreline *cl)
{
	return centreline_total_arclength(cl) + p->bending_length_m;
}

void scope_update(const struct scope_params *p, const struct centreline *cl,
		  const struct scope_input *in, struct scope_pose *out)
{
	struct base b;
	struct arcfn fn;

	out->depth_m = fmax(0, fmin(in->depth_m, scope_max_depth(p, cl)));
	out->roll_rad = in->roll_rad;
	scope_bend(p, in->wheel_ud_rad, in->wheel_lr_rad, out->bend_rad,
		   out->dbend_dwheel);
	find_base(p, cl, out->depth_m, out->roll_rad, out->bend_rad, &b);
	arc_functions(b.th, &fn);
	out->base_s_m = b.s_m;
	arc_point(&b, b.len_m, out->tip);
	tip_frame(&b, &fn, out);
	jacobian(p, cl, &b, &fn, out);
	out->tip_s_m = nearest_s(cl, &b, out->tip);
	tube(cl, &b, out->depth_m, out);
}

_Static_assert(SCOPE_TUBE_POINTS == ENDOSIM_TUBE_POINTS,
	       "the published tube is the kinematics' tube");

void scope_publish(const struct scope_pose *p, const struct centreline *cl,
		   struct endosim_scope_state *out)
{
	double base = p->base_s_m / centreline_step(cl);

	out->depth_m = p->depth_m;
	out->roll_rad = p->roll_rad;
	memcpy(out->bend_rad, p->bend_rad, sizeof(out->bend_rad));
	out->base_s_m = p->base_s_m;
	out->tip_s_m = p->tip_s_m;
	out->turning_rad = centreline_turning(cl, (size_t)(base + 0.5));
	memcpy(out->tip, p->tip, sizeof(out->tip));
	memcpy(out->dir, p->dir, sizeof(out->dir));
	memcpy(out->up, p->up, sizeof(out->up));
	out->spans = (uint32_t)centreline_spans(cl);
	for (int k = 0; k < ENDOSIM_SPANS; k++) {
		out->bow_m[k] = k < (int)out->spans ?
					centreline_bow_amplitude(cl, k) : 0;
	}
	for (int i = 0; i < ENDOSIM_TUBE_POINTS; i++) {
		for (int d = 0; d < 3; d++) {
			out->tube[i][d] = (float)p->tube[i][d];
		}
	}
}
