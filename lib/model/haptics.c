/* haptics.c - see haptics.h; inside: haptics_private.h. */
#include "model/haptics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"
#include "model/haptics_private.h"

#define PO_MIN_SPEED 1e-6  /* m/s or rad/s: below, no damping is added */
#define LOST_LUMENS 1.5    /* a free proxy this many widest radii from the
			      centreline is outside the colon */

struct haptics *haptics_create(const struct haptics_params *p)
{
	struct haptics *h = calloc(1, sizeof(*h));

	if (!h) {
		return NULL;
	}
	h->fresh = true;
	h->model = p ? p->gains.model : HAPTICS_MODEL_PAPER;
	if (p) {
		patient_init(&h->patient, &p->patient);
	} else {
		struct patient_params none = PATIENT_PARAMS_DEFAULT;

		none.enabled = false;
		patient_init(&h->patient, &none);
	}
	if (h->model == HAPTICS_MODEL_ROD && haptics_rod_create(h, &p->rod)) {
		free(h);
		return NULL;
	}
	return h;
}

void haptics_destroy(struct haptics *h)
{
	if (h) {
		haptics_rod_destroy(h);
		free(h);
	}
}

void haptics_publish_rod(const struct haptics *h, double roll_rad,
			 struct endosim_rod_state *out,
			 double bow_m[ENDOSIM_SPANS])
{
	memset(out, 0, sizeof(*out));
	if (h->model == HAPTICS_MODEL_ROD) {
		haptics_rod_publish(h, roll_rad, out, bow_m);
	}
}

void haptics_hold_tip(struct haptics *h, double hold_n_per_m)
{
	if (h->model == HAPTICS_MODEL_ROD) {
		haptics_rod_hold_tip(h, hold_n_per_m);
	}
}

bool haptics_rod(const struct haptics *h)
{
	return h->model == HAPTICS_MODEL_ROD;
}

void haptics_reset(struct haptics *h, struct colon *colon)
{
	h->fresh = true;
	memset(h->energy, 0, sizeof(h->energy));
	memset(h->last_x, 0, sizeof(h->last_x));
	haptics_rod_reset(h, colon);
	haptics_paper_reset(h, colon);
	patient_attach(&h->patient, colon);
	h->tip_force_n = 0;
	h->tip_gap_m = INFINITY;
	memset(h->span_tension_n, 0, sizeof(h->span_tension_n));
}

struct patient *haptics_patient(struct haptics *h)
{
	return &h->patient;
}

/* The patient's cycle, from the tip as it is and its contact's and the
 * mesentery's last. */
static void step_patient(struct haptics *h, const struct haptics_input *in)
{
	struct patient_input pi = {
		.valves = in->valves,
		.tip_s_m = in->pose->tip_s_m,
		.tip_force_n = h->tip_force_n,
		.wall_gap_m = h->tip_gap_m,
		.tip_bend_rad = hypot(in->pose->bend_rad[0],
				      in->pose->bend_rad[1]),
		.insertion_m_s = in->velocity[ENDOSIM_AXIS_INSERTION],
		.roll_rad_s = in->velocity[ENDOSIM_AXIS_ROLL],
		.span_tension_n = h->span_tension_n,
	};

	patient_set_params(&h->patient, &in->params->patient);
	vec3_copy(pi.tip, in->pose->tip);
	patient_step(&h->patient, &pi, in->dt_s);
}

void haptics_render(struct haptics *h, const struct haptics_input *in,
		    double command[ENDOSIM_AXES],
		    struct endosim_haptics_state *out)
{
	step_patient(h, in);
	if (h->model == HAPTICS_MODEL_ROD) {
		haptics_rod_render(h, in, command, out);
	} else {
		haptics_paper_render(h, in, command, out);
	}
}

/* ---------------------------------------------------------------- frames */

/* The centreline's frame at one sample, now and before any bow, and the
 * lumen's radius factor there (the gas's: 1 as the case drew it). */
struct frame_map {
	const struct centreline_point *now, *base;
	double f;
};

static void frame_at(const struct centreline *cl, double s_m,
		     struct frame_map *m)
{
	double i = floor(s_m / centreline_step(cl) + 0.5);
	size_t n = centreline_count(cl);
	size_t k = i < 0 ? 0 : i >= (double)n ? n - 1 : (size_t)i;

	m->now = centreline_sample(cl, k);
	m->base = centreline_base(cl, k);
}

/* V from frame A's coordinates into frame B's, its parts across the
 * course (u, v) scaled by K: sum_e e_B (e_A . v) k_e. */
static void turn_scaled(const struct centreline_point *a,
			const struct centreline_point *b, const double v[3],
			double k, double out[3])
{
	double r[3] = { 0, 0, 0 };

	vec3_axpy(r, r, vec3_dot(a->t, v), b->t);
	vec3_axpy(r, r, k * vec3_dot(a->u, v), b->u);
	vec3_axpy(r, r, k * vec3_dot(a->v, v), b->v);
	vec3_copy(out, r);
}

/*
 * A point from the colon now into its material placement, and back: the
 * lumen as the gas holds it is the material's scaled about the centreline
 * by f, so the part across the course scales by 1 / f into the material
 * and by f out of it (f = 1: the frames' turn alone). A displacement or a
 * force goes as a point does; a velocity or a direction into the
 * material as a point; a normal out of it by the inverse transpose (1 /
 * f across, then made unit).
 */
static void point_to_base(const struct frame_map *m, const double x[3],
			  double out[3])
{
	double d[3];

	vec3_sub(d, x, m->now->p);
	turn_scaled(m->now, m->base, d, 1 / m->f, d);
	vec3_add(out, m->base->p, d);
}

static void point_to_now(const struct frame_map *m, const double x[3],
			 double out[3])
{
	double d[3];

	vec3_sub(d, x, m->base->p);
	turn_scaled(m->base, m->now, d, m->f, d);
	vec3_add(out, m->now->p, d);
}

/* ---------------------------------------------------------------- contact */

/* The tip's velocity from the axes' velocities through the Jacobian. */
static void tip_velocity(const struct haptics_input *in, double v[3])
{
	const struct scope_pose *p = in->pose;
	double qd[4] = {
		in->velocity[ENDOSIM_AXIS_INSERTION],
		in->velocity[ENDOSIM_AXIS_ROLL],
		in->velocity[ENDOSIM_AXIS_WHEEL_UD] *
			p->dbend_dwheel[0],
		in->velocity[ENDOSIM_AXIS_WHEEL_LR] *
			p->dbend_dwheel[1],
	};

	for (int d = 0; d < 3; d++) {
		v[d] = 0;
		for (int k = 0; k < 4; k++) {
			v[d] += p->jacobian[d][k] * qd[k];
		}
	}
}

void haptics_spring(const struct haptics_params *par, const double dir[3],
		    const double delta[3], double out[3])
{
	double kw = par->gains.wall_stiffness_n_per_m;
	double kl = par->gains.tip_lateral_stiffness_n_per_m;
	double ks = kw * kl / (kw + kl);
	double along = vec3_dot(delta, dir);

	vec3_scale(out, delta, ks);
	vec3_axpy(out, out, (kw - ks) * along, dir);
}

/*
 * F_static in the material placement: the spring to the proxy (with
 * shading on, the depth pushed along the planes' shaded normal, which
 * stays continuous as the proxy slides onto an edge or off it) and
 * damping of the penetration rate, never pulling.
 */
static void static_force(const struct haptics *h,
			 const struct haptics_params *par,
			 const double tip_b[3], const double dir_b[3],
			 const double vel_b[3], struct haptics_touch *t)
{
	const struct godobject *g = &h->go;
	double delta[3], rate[3], damp[3];

	vec3_sub(delta, g->proxy, tip_b);
	if (g->planes == 1) {
		vec3_copy(t->normal, g->normal[0]);
		t->depth = fmax(0, vec3_dot(delta, t->normal));
	} else {
		vec3_copy(t->normal, delta);
		t->depth = vec3_normalize(t->normal);
	}
	if (par->gains.force_shading) {
		/* the depth (along the plane's normal, or the whole way to
		 * an edge or corner) pushed along the interpolated normal */
		vec3_scale(delta, g->shaded, t->depth);
	}
	haptics_spring(par, dir_b, delta, t->force);
	vec3_copy(t->spring, t->force);
	/* damping of the penetration rate, as anisotropic as the spring:
	 * B = (b_wall / k_wall) K (the bending section damps across no more
	 * than it gives way across) */
	vec3_scale(rate, t->normal, vec3_dot(vel_b, t->normal));
	haptics_spring(par, dir_b, rate, damp);
	vec3_axpy(t->force, t->force,
		  -par->gains.wall_damping_n_s_per_m /
			  fmax(par->gains.wall_stiffness_n_per_m, 1e-9),
		  damp);
	double push = vec3_dot(t->force, t->normal);

	if (push < 0) { /* a wall pushes, it never pulls */
		vec3_axpy(t->force, t->force, -push, t->normal);
	}
}

/*
 * The stretch of colon whose triangles the proxy may meet on its way to the
 * tip: around the proxy, the tip, and the bending section (which a
 * strongly bent tip may leave far from its own nearest sample).
 */
static void search_window(const struct haptics *h,
			  const struct haptics_input *in, double *s0,
			  double *s1)
{
	const struct scope_pose *p = in->pose;
	double reach = in->params->gains.contact_reach_m;
	double lo = fmin(fmin(h->proxy_s, p->tip_s_m), p->base_s_m);
	double hi = fmax(fmax(h->proxy_s, p->tip_s_m),
			 p->base_s_m + in->params->bending_length_m);

	*s0 = lo - reach;
	*s1 = hi + reach;
}

/*
 * A free proxy farther from the centreline than the widest lumen around it
 * cannot be in the colon: it was lost (a path that no query could follow).
 * It starts again from the centreline, from where the next update finds
 * the wall between it and the tip.
 */
static bool lost(const struct haptics *h, const struct haptics_input *in,
		 const struct frame_map *m)
{
	const struct colon *c = in->colon;
	double widest = 0;

	if (h->go.planes || !colon_anatomy(c)) {
		return false;
	}
	for (int i = 0; i < colon_regions(c); i++) {
		widest = fmax(widest, colon_region(c, i)->diameter_m / 2);
	}
	return vec3_dist(h->go.proxy, m->base->p) > LOST_LUMENS * widest;
}

/* The tip's clearance to the wall as the gas holds it (TIP_B: its place
 * in the material, M its frame): the lumen's radius there less the tip's
 * distance from the centreline, both scaled by f, less the tip's own
 * radius. */
static double tip_gap(const struct haptics_input *in,
		      const struct frame_map *m, const double tip_b[3])
{
	const struct centreline *cl = colon_centreline(in->colon);
	double d[3], along, r, k = floor(in->pose->tip_s_m /
					      centreline_step(cl) + 0.5);
	size_t n = centreline_count(cl);
	size_t i = k < 0 ? 0 : k >= (double)n ? n - 1 : (size_t)k;

	vec3_sub(d, tip_b, m->base->p);
	along = vec3_dot(d, m->base->t);
	vec3_axpy(d, d, -along, m->base->t);
	r = colon_tube_radius(in->colon, i) - vec3_norm(d);
	return fmax(0, m->f * r - in->params->gains.scope_radius_m);
}

void haptics_touch_wall(struct haptics *h, const struct haptics_input *in,
			const double tip_v[3], struct haptics_touch *t)
{
	const struct haptics_params *par = in->params;
	const struct scope_pose *p = in->pose;
	const struct contact *c = colon_contact(in->colon);
	double tip_b[3], dir_b[3], vel[3], vel_b[3], s0, s1;
	struct frame_map m;

	memset(t, 0, sizeof(*t));
	frame_at(colon_centreline(in->colon), p->tip_s_m, &m);
	m.f = patient_factor_at(&h->patient, p->tip_s_m);
	point_to_base(&m, p->tip, tip_b);
	h->tip_gap_m = tip_gap(in, &m, tip_b);
	h->tip_force_n = 0;
	if (h->fresh || p->depth_m < par->gains.entry_depth_m) {
		godobject_reset(&h->go, tip_b);
		h->fresh = false;
	} else {
		if (lost(h, in, &m)) {
			godobject_reset(&h->go, m.base->p);
		}
		search_window(h, in, &s0, &s1);
		godobject_update(&h->go, c, tip_b, s0, s1);
	}
	h->proxy_s = h->go.planes ? contact_triangle_s(c, h->go.tri[0])
				  : p->tip_s_m;
	point_to_now(&m, h->go.proxy, t->proxy);
	t->planes = h->go.planes;
	t->on = godobject_contact(&h->go);
	if (!t->on) {
		return;
	}
	if (tip_v) {
		vec3_copy(vel, tip_v);
	} else {
		tip_velocity(in, vel);
	}
	turn_scaled(m.now, m.base, vel, 1 / m.f, vel_b);
	turn_scaled(m.now, m.base, p->dir, 1 / m.f, dir_b);
	if (m.f != 1) {
		vec3_normalize(dir_b);
	}
	static_force(h, par, tip_b, dir_b, vel_b, t);
	turn_scaled(m.base, m.now, t->force, m.f, t->force);
	turn_scaled(m.base, m.now, t->spring, m.f, t->spring);
	turn_scaled(m.base, m.now, t->normal, 1 / m.f, t->normal);
	if (m.f != 1) {
		vec3_normalize(t->normal);
	}
	h->tip_force_n = vec3_norm(t->force);
	h->tip_gap_m = 0;
}

void haptics_publish_touch(const struct haptics_touch *t,
			   struct endosim_haptics_state *o)
{
	vec3_copy(o->proxy, t->proxy);
	vec3_copy(o->normal, t->normal);
	vec3_copy(o->f_static, t->force);
	o->penetration_m = t->depth;
	o->contact = t->on;
	o->constraints = (uint32_t)t->planes;
}

/* ---------------------------------------------------------------- forces */

bool haptics_wheel_lags(const struct haptics_params *par, int a)
{
	return (a == ENDOSIM_AXIS_WHEEL_UD || a == ENDOSIM_AXIS_WHEEL_LR) &&
	       par->driven[a];
}

/*
 * Hannaford and Ryu: the energy each axis' rendering took in over the last
 * period (the setpoint held times the way the axis went); when the sum
 * would go negative, damping on the contact part removes the deficit.
 * Not on a wheel whose drive lags: the setpoint held is not known there,
 * and damping on a phantom deficit kicks the light wheel; its stiffness is
 * limited instead (the paper's wall: haptics_paper.c; the rod's bending
 * section: haptics_rod.c). Axes before FIRST are left alone.
 */
void haptics_passivity(struct haptics *h, const struct haptics_input *in,
		       double contact[ENDOSIM_AXES], int first,
		       struct endosim_haptics_state *out)
{
	double added = 0;

	for (int a = first; a < ENDOSIM_AXES; a++) {
		double x = in->position[a];
		double v = in->velocity[a];
		double held = in->applied ? in->applied[a] : 0;

		if (in->torque_on && in->params->gains.passivity &&
		    !haptics_wheel_lags(in->params, a)) {
			h->energy[a] -= held * (x - h->last_x[a]);
		} else {
			h->energy[a] = 0;
		}
		h->last_x[a] = x;
		/* the damping's work shows in the next period's measure; it
		 * is never stronger than the contact force itself (a tiny
		 * speed would ask for a huge one, and a speed that turns
		 * within the period would make it push) */
		if (h->energy[a] < 0 && fabs(v) > PO_MIN_SPEED) {
			double alpha = -h->energy[a] / (v * v * in->dt_s);
			double f = fmin(fabs(alpha * v), fabs(contact[a]));

			contact[a] -= copysign(f, v);
			if (a == ENDOSIM_AXIS_INSERTION) {
				added = alpha;
			}
		}
	}
	out->passivity_damping = added;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		out->passivity_energy_j += h->energy[a];
	}
}

/*
 * How far wheel W (0: up/down, 1: left/right) at WHEEL_RAD is past the
 * angle at which its bend reaches the limit, rad, signed as the wheel; 0
 * within it (scope_bend()'s test).
 */
static double wheel_beyond(const struct haptics_params *par, int w,
			   double wheel_rad)
{
	double gain = par->wheel_gain[w], limit = par->wheel_limit_rad[w];
	double bend = gain * wheel_rad;

	if (!(gain > 0) || fabs(bend) < limit) {
		return 0;
	}
	return (bend - copysign(limit, bend)) / gain;
}

/*
 * The knob's end, D rad past the limit at V rad/s: -k d - b v, only ever
 * pushing the wheel back; at most the wheel's torque limit beyond the part
 * of TENSION (N m) that pushes it on, so the tension never pushes through.
 */
static double wheel_stop(const struct haptics_params *par, int w, double d,
			 double v, double tension)
{
	double out = copysign(1, d);
	double push = par->gains.stop_stiffness_n_m_per_rad * fabs(d) +
		      par->gains.stop_damping_n_m_s_per_rad * v * out;
	double most = par->wheel_max_n_m[w] +
		      fmax(0, tension * out);

	return -out * fmin(fmax(push, 0), most);
}

/*
 * The bending section springing back, -k_bend bend d bend/d wheel; past
 * the limit, where the bend stays, its spring-back at the limit (the wires
 * still carry it) and the knob's end.
 */
static double wheel_elastic(const struct haptics_input *in, int w,
			    double tension)
{
	const struct haptics_params *par = in->params;
	const struct scope_pose *p = in->pose;
	double x = in->position[ENDOSIM_AXIS_WHEEL_UD + w];
	double v = in->velocity[ENDOSIM_AXIS_WHEEL_UD + w];
	double k = par->gains.bending_stiffness_n_m_per_rad;
	double d = wheel_beyond(par, w, x);

	if (d == 0) {
		return -k * p->bend_rad[w] * p->dbend_dwheel[w];
	}
	return -k * p->bend_rad[w] * par->wheel_gain[w] +
	       wheel_stop(par, w, d, v, tension);
}

double haptics_wheel_budget(const struct haptics_input *in, int w)
{
	const struct haptics_params *par = in->params;
	double g = in->pose->dbend_dwheel[w];
	double lag = in->dt_s / 2 + par->gains.wheel_delay_s;

	return fmax(0, par->gains.damping[ENDOSIM_AXIS_WHEEL_UD + w] / lag -
			       par->gains.bending_stiffness_n_m_per_rad *
				       g * g);
}

void haptics_wheels_and_damping(const struct haptics_input *in,
				const double contact[ENDOSIM_AXES],
				struct endosim_haptics_state *out,
				double command[ENDOSIM_AXES])
{
	const struct haptics_params *par = in->params;

	for (int w = 0; w < 2; w++) {
		out->wheel_contact_nm[w] = contact[ENDOSIM_AXIS_WHEEL_UD + w];
		out->wheel_tension_nm[w] = par->gains.wire_tension_n_m_per_m *
					   out->wire_dl_m[w];
		out->wheel_elastic_nm[w] =
			wheel_elastic(in, w, out->wheel_tension_nm[w]);
		command[ENDOSIM_AXIS_WHEEL_UD + w] = out->wheel_contact_nm[w] +
						     out->wheel_tension_nm[w] +
						     out->wheel_elastic_nm[w];
	}
	for (int ax = 0; ax < ENDOSIM_AXES; ax++) {
		out->damping[ax] = -par->gains.damping[ax] * in->velocity[ax];
		command[ax] += out->damping[ax];
	}
}
