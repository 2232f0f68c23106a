/* rodscope.c - see rodscope.h. */
#include "model/rodscope.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"

struct rodscope {
	struct rodscope_params par;
	struct rod *rod;
	struct lumen *lumen;
	struct flex *flex;
	struct colon *colon;
	int n;              /* segments */
	int nb;             /* of them the bending section's */
	double *sigma;      /* per segment: where it would be on the course */
	double (*ends)[3];  /* room for a laid tube's joint points */
	double hold;        /* N/m: the tip held (0: free) */
	double g[3];        /* gravity, m/s^2 */
};

static int bending_segments(const struct rodscope_params *p, double l)
{
	int nb = (int)lround(p->bending_length_m / l);

	return nb < 1 ? 1 : nb >= p->rod.segments ? p->rod.segments - 1 : nb;
}

/* The bending section's joints: its n_b segments' and the one before. */
static void set_stiffness(struct rodscope *rs)
{
	for (int j = 0; j < rs->n - 1; j++) {
		bool tip = j >= rs->n - 1 - rs->nb;

		rod_set_stiffness(rs->rod, j,
				  tip ? rs->par.tip_bending_n_m2
				      : rs->par.rod.bending_n_m2,
				  rs->par.rod.torsion_n_m2);
	}
}

struct rodscope *rodscope_create(const struct rodscope_params *p)
{
	struct rodscope *rs = calloc(1, sizeof(*rs));

	if (!rs || !(p->tip_bending_n_m2 > 0) || !(p->bending_length_m > 0)) {
		free(rs);
		return NULL;
	}
	rs->par = *p;
	rs->n = p->rod.segments;
	rs->rod = rod_create(&p->rod);
	rs->lumen = lumen_create(rs->n);
	rs->flex = flex_create(&p->flex);
	rs->sigma = calloc((size_t)rs->n, sizeof(*rs->sigma));
	rs->ends = calloc((size_t)rs->n + 1, sizeof(*rs->ends));
	if (!rs->rod || !rs->lumen || !rs->flex || !rs->sigma || !rs->ends) {
		rodscope_destroy(rs);
		return NULL;
	}
	rs->nb = bending_segments(p, rod_segment_length(rs->rod));
	set_stiffness(rs);
	return rs;
}

void rodscope_destroy(struct rodscope *rs)
{
	if (!rs) {
		return;
	}
	rod_destroy(rs->rod);
	lumen_destroy(rs->lumen);
	flex_destroy(rs->flex);
	free(rs->sigma);
	free(rs->ends);
	free(rs);
}

void rodscope_set_params(struct rodscope *rs, const struct rodscope_params *p)
{
	struct rod_params keep = rs->par.rod;

	rs->par = *p;
	/* the rod's own parameters are fixed at creation */
	rs->par.rod = keep;
	rs->par.rod.bending_n_m2 = p->rod.bending_n_m2;
	rs->par.rod.torsion_n_m2 = p->rod.torsion_n_m2;
	rs->nb = bending_segments(&rs->par, rod_segment_length(rs->rod));
	set_stiffness(rs);
	flex_set_params(rs->flex, &p->flex);
}

/* The carriage's depth, the tube's length at most. */
static double carried(const struct rodscope *rs, const struct rodscope_axes *a)
{
	return fmin(fmax(a->depth_m, 0), rs->par.rod.length_m);
}

/* The pipe's frame turned by the roll: d1 (up) and the pipe's axis. */
static void carriage_frame(const struct rodscope *rs, double roll,
			   double up[3], const double **axis)
{
	const struct centreline_point *c0 =
		centreline_sample(colon_centreline(rs->colon), 0);

	vec3_scale(up, c0->u, cos(roll));
	vec3_axpy(up, up, sin(roll), c0->v);
	*axis = c0->t;
}

/* Where rod arc length U (from the base) lies on the course: the pipe,
 * then the colon's centreline, then on past the cecum. */
static void course_point(const struct rodscope *rs, double depth, double u,
			 double out[3])
{
	const struct centreline *cl = colon_centreline(rs->colon);
	const struct centreline_point *c0 = centreline_sample(cl, 0);
	double s = depth - rs->par.rod.length_m + u;
	double total = centreline_total_arclength(cl);

	if (s < 0) {
		vec3_axpy(out, c0->p, s, c0->t);
	} else if (s <= total) {
		centreline_position_at_length(cl, s, out, NULL);
	} else {
		const struct centreline_point *end =
			centreline_sample(cl, centreline_count(cl) - 1);

		vec3_axpy(out, end->p, s - total, end->t);
	}
}

static void set_anchor(struct rodscope *rs, const struct rodscope_axes *a)
{
	const struct rodscope_params *p = &rs->par;
	double l = rod_segment_length(rs->rod), up[3], clamp[6];
	const double *axis;
	struct rod_anchor an;

	memset(&an, 0, sizeof(an));
	carriage_frame(rs, a->roll_rad, up, &axis);
	course_point(rs, carried(rs, a), 0, an.p);
	rod_frame_quat(axis, up, an.q);
	rod_clamp_compliance(rs->rod, clamp);
	/* rigid across the pipe and against bending; a spring-damper along
	 * it and about it */
	an.compliance[2] = 1 / p->coupling_n_per_m;
	an.damping_s[2] = p->coupling_n_s_per_m / p->coupling_n_per_m;
	an.compliance[3] = clamp[3];
	an.compliance[4] = clamp[4];
	an.compliance[5] = 1 / p->roll_n_m_per_rad +
			   l / (2 * p->rod.torsion_n_m2);
	an.damping_s[5] = p->roll_n_m_s_per_rad / p->roll_n_m_per_rad;
	rod_set_anchor(rs->rod, ROD_BASE, &an);
}

/* The bending section's rest: the bend v = (-lr, ud, 0) / n_b per joint,
 * theta0 = 2 sin(|v| / 2) v / |v|. */
static void set_rest(struct rodscope *rs, const struct rodscope_axes *a)
{
	double v[3] = { -a->bend_rad[1] / rs->nb, a->bend_rad[0] / rs->nb, 0 };
	double angle = vec3_norm(v), axis[3], th[3] = { 0, 0, 0 };

	if (angle > 0) {
		vec3_scale(axis, v, 1 / angle);
		rod_rest_for_angle(angle, axis, th);
	}
	for (int j = rs->n - 1 - rs->nb; j < rs->n - 1; j++) {
		rod_set_rest(rs->rod, j, th);
	}
}

void rodscope_reset(struct rodscope *rs, struct colon *colon,
		    const struct rodscope_axes *a)
{
	double l = rod_segment_length(rs->rod), d = carried(rs, a), up[3];
	const double *axis;

	rs->colon = colon;
	flex_attach(rs->flex, colon);
	carriage_frame(rs, a->roll_rad, up, &axis);
	for (int j = 0; j <= rs->n; j++) {
		course_point(rs, d, j * l, rs->ends[j]);
	}
	rod_lay(rs->rod, (const double(*)[3])rs->ends, up);
	for (int i = 0; i < rs->n; i++) {
		rs->sigma[i] = d - rs->par.rod.length_m + (i + 0.5) * l;
	}
	lumen_reset(rs->lumen, rs->sigma);
	rod_set_anchor(rs->rod, ROD_BASE, NULL);
	set_anchor(rs, a);
	set_rest(rs, a);
}

/* The point at rod arc length U from the base, between its joints. */
static void rod_point(const struct rodscope *rs, double u, double out[3])
{
	double l = rod_segment_length(rs->rod), f = u / l;
	int i = (int)floor(f);
	double a[3], b[3];

	if (i < 0) {
		i = 0;
	} else if (i >= rs->n) {
		i = rs->n - 1;
	}
	rod_end_point(rs->rod, i, ROD_BASE, a);
	rod_end_point(rs->rod, i, ROD_TIP, b);
	f = fmin(fmax(f - i, 0), 1);
	vec3_lerp(out, a, b, f);
}

/* A segment's material s on the colon, from its nearest sample (0 in the
 * pipe). */
static double segment_s(const struct rodscope *rs, int i)
{
	long k = lumen_sample(rs->lumen, i);

	return k < 0 ? 0 : (double)k * centreline_step(colon_centreline(
						     rs->colon));
}

void rodscope_pose(const struct rodscope *rs, const struct rodscope_axes *a,
		   struct scope_pose *pose, double tip_velocity[3])
{
	double l = rod_segment_length(rs->rod), d = carried(rs, a);
	double len = rs->par.rod.length_m, d1[3], d2[3], d3[3], w[3], arm[3];
	int last = rs->n - 1;

	memset(pose, 0, sizeof(*pose));
	pose->depth_m = d;
	pose->roll_rad = a->roll_rad;
	memcpy(pose->bend_rad, a->bend_rad, sizeof(pose->bend_rad));
	memcpy(pose->dbend_dwheel, a->dbend_dwheel,
	       sizeof(pose->dbend_dwheel));
	pose->base_s_m = segment_s(rs, rs->n - rs->nb);
	pose->tip_s_m = segment_s(rs, last);
	rod_end_point(rs->rod, last, ROD_TIP, pose->tip);
	rod_frame(rs->rod, last, d1, d2, d3);
	vec3_copy(pose->dir, d3);
	vec3_copy(pose->up, d1);
	for (int k = 0; k < SCOPE_TUBE_POINTS; k++) {
		rod_point(rs, len - d + d * k / (SCOPE_TUBE_POINTS - 1),
			  pose->tube[k]);
	}
	vec3_scale(arm, d3, l / 2);
	vec3_cross(w, rod_spin(rs->rod, last), arm);
	vec3_add(tip_velocity, rod_velocity(rs->rod, last), w);
}

void rodscope_hold_tip(struct rodscope *rs, double hold_n_per_m)
{
	struct rod_anchor an = { .compliance = { 0, 0, 0, 1e6, 1e6, 1e6 } };
	int last = rs->n - 1;

	rs->hold = hold_n_per_m > 0 ? hold_n_per_m : 0;
	if (!rs->hold) {
		rod_set_anchor(rs->rod, ROD_TIP, NULL);
		return;
	}
	rod_end_point(rs->rod, last, ROD_TIP, an.p);
	memcpy(an.q, rod_quat(rs->rod, last), sizeof(an.q));
	for (int i = 0; i < 3; i++) {
		an.compliance[i] = 1 / rs->hold;
	}
	rod_set_anchor(rs->rod, ROD_TIP, &an);
}

/* d theta0 / d bend (the wheel's, per rad) at joint rest v (rodscope.h). */
static void rest_slope(const double v[3], const double dv[3], double out[3])
{
	double x = vec3_norm(v), g, gx;

	if (x < 1e-4) {
		g = 1 - x * x / 24;
		gx = -1.0 / 12;
	} else {
		g = 2 * sin(x / 2) / x;
		gx = (x * cos(x / 2) - 2 * sin(x / 2)) / (x * x * x);
	}
	/* d (g(|v|) v) = g dv + g'(|v|) / |v| (v . dv) v */
	vec3_scale(out, dv, g);
	vec3_axpy(out, out, gx * vec3_dot(v, dv), v);
}

/* The bending section's moments on the wheels, N m. */
static void wheel_moments(const struct rodscope *rs,
			  const struct rodscope_axes *a, double out[2])
{
	double v[3] = { -a->bend_rad[1] / rs->nb, a->bend_rad[0] / rs->nb, 0 };
	const double dv[2][3] = { { 0, 1.0 / rs->nb, 0 },
				  { -1.0 / rs->nb, 0, 0 } };

	for (int w = 0; w < 2; w++) {
		double slope[3];

		out[w] = 0;
		rest_slope(v, dv[w], slope);
		for (int j = rs->n - 1 - rs->nb; j < rs->n - 1; j++) {
			double m[3];

			rod_joint_moment(rs->rod, j, m);
			out[w] += vec3_dot(m, slope);
		}
		out[w] *= a->dbend_dwheel[w];
	}
}

/* The wires' length differences and the inserted tube's turning before
 * the bending section, over the segments inside. */
static void wires(const struct rodscope *rs, double dl[2], double *turning)
{
	double su = 0, sv = 0, turn = 0;
	int first = rs->n - rs->nb;

	for (int i = 0; i + 1 < rs->n; i++) {
		double a1[3], a2[3], a3[3], b1[3], b2[3], b3[3], d[3], th[3];

		if (lumen_sample(rs->lumen, i) < 0) {
			continue;
		}
		rod_joint_rotation(rs->rod, i, th);
		turn += hypot(th[0], th[1]);
		if (i + 1 >= first) {
			continue;
		}
		rod_frame(rs->rod, i, a1, a2, a3);
		rod_frame(rs->rod, i + 1, b1, b2, b3);
		vec3_sub(d, b1, a1);
		su += vec3_dot(d, a3);
		vec3_sub(d, b2, a2);
		sv += vec3_dot(d, a3);
	}
	dl[0] = rs->par.wire_spacing_m * su;
	dl[1] = rs->par.wire_spacing_m * sv;
	*turning = turn;
}

void rodscope_set_patient(struct rodscope *rs, const double *factor,
			  const double g[3], const struct flex_pad *pad)
{
	struct flex_pad none = { .on = false };

	vec3_copy(rs->g, g);
	lumen_set_factors(rs->lumen, factor);
	flex_set_gravity(rs->flex, g);
	flex_set_pad(rs->flex, pad ? pad : &none);
}

double rodscope_pad_force(const struct rodscope *rs)
{
	return flex_pad_force(rs->flex);
}

double rodscope_span_tension(const struct rodscope *rs, int span)
{
	return flex_span_tension(rs->flex, span);
}

void rodscope_step(struct rodscope *rs, const struct rodscope_axes *a,
		   const struct rodscope_tip *tip, double dt_s,
		   struct rodscope_out *out)
{
	const struct rodscope_params *p = &rs->par;
	int last = rs->n - 1;
	double f[3], tau[3], up[3];
	const double *axis;

	memset(out, 0, sizeof(*out));
	rod_clear_loads(rs->rod);
	set_anchor(rs, a);
	set_rest(rs, a);
	if (rs->g[0] || rs->g[1] || rs->g[2]) { /* the tube's weight */
		double m = p->rod.mass_per_m_kg * rod_segment_length(rs->rod);

		for (int i = 0; i < rs->n; i++) {
			struct rod_load *ld = rod_load(rs->rod, i);

			vec3_axpy(ld->f, ld->f, m, rs->g);
		}
	}
	if (tip && tip->on) {
		double d1[3], d2[3], d3[3], off[3];

		rod_frame(rs->rod, last, d1, d2, d3);
		vec3_scale(off, d3, rod_segment_length(rs->rod) / 2);
		rod_load_point(rod_load(rs->rod, last), off, tip->force,
			       tip->k, tip->b, NULL);
	}
	lumen_load(rs->lumen, rs->rod, rs->colon, rs->flex, &p->lumen);
	rod_step(rs->rod, dt_s);
	flex_clear(rs->flex);
	lumen_react(rs->lumen, rs->rod, rs->flex, &out->wall);
	flex_step(rs->flex, dt_s);

	rod_anchor_wrench(rs->rod, ROD_BASE, f, tau);
	carriage_frame(rs, a->roll_rad, up, &axis);
	out->insertion_n = -vec3_dot(f, axis);
	out->roll_nm = -vec3_dot(tau, axis);
	if (a->depth_m > p->rod.length_m) {
		out->insertion_n -= p->stop_n_per_m *
					    (a->depth_m - p->rod.length_m) +
				    p->coupling_n_s_per_m * fmax(a->depth_m_s, 0);
	}
	wheel_moments(rs, a, out->wheel_nm);
	wires(rs, out->wire_dl_m, &out->turning_rad);
}

void rodscope_publish(const struct rodscope *rs, double roll_rad,
		      const struct lumen_totals *wall,
		      struct endosim_rod_state *out,
		      double bow_m[ENDOSIM_SPANS])
{
	const struct centreline *cl = colon_centreline(rs->colon);
	int every = (rs->n + ENDOSIM_ROD_POINTS - 2) / (ENDOSIM_ROD_POINTS - 1);
	double roll = roll_rad;
	int k = 0;

	out->model = ENDOSIM_MODEL_ROD;
	out->contacts = (uint32_t)wall->contacts;
	out->wall_n = wall->wall_n;
	out->friction_n = wall->friction_n;
	for (int j = 0; j <= rs->n; j++) {
		double p[3], th[3];

		if (j % every == 0 || j == rs->n) {
			rod_end_point(rs->rod, j < rs->n ? j : j - 1,
				      j < rs->n ? ROD_BASE : ROD_TIP, p);
			for (int d = 0; d < 3; d++) {
				out->point[k][d] = (float)p[d];
			}
			out->roll[k++] = (float)roll;
		}
		if (j + 1 < rs->n) {
			rod_joint_rotation(rs->rod, j, th);
			roll += th[2];
		}
	}
	out->points = (uint32_t)k;
	out->nodes = (uint32_t)flex_nodes(rs->flex);
	for (int i = 0; i < (int)out->nodes && i < ENDOSIM_COLON_NODES; i++) {
		const double *y = flex_node(rs->flex, i);

		for (int d = 0; d < 3; d++) {
			out->node[i][d] = (float)y[d];
		}
	}
	for (int sp = 0; sp < ENDOSIM_SPANS; sp++) {
		bool has = sp < centreline_spans(cl);

		out->span_nodes[sp] =
			has ? (uint32_t)flex_span_nodes(rs->flex, sp) : 0;
		bow_m[sp] = has ? flex_span_displacement(rs->flex, sp) : 0;
	}
}

bool rodscope_finite(const struct rodscope *rs)
{
	return rod_finite(rs->rod);
}
