/* haptics.c - see haptics.h. */
#include "model/haptics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model/godobject.h"
#include "base/vec3.h"

#define MIN_BOW_M 1e-4     /* a loop smaller than this is no loop */
#define MAX_BOW_HEIGHTS 1.5 /* a bow never exceeds this many mesentery heights */
#define BOW_STEP_M 1e-4    /* smaller changes are not applied */
#define PO_MIN_SPEED 1e-6  /* m/s or rad/s: below, no damping is added */
#define LOST_LUMENS 1.5    /* a free proxy this many widest radii from the
			      centreline is outside the colon */

struct span {
	int index;         /* the centreline's span */
	double s0, s1;     /* m, material */
	double k;          /* mesentery, N/m */
	double h;          /* mesentery height, m */
	double c;          /* stored tube length per amplitude^2, 1/m */
	double amplitude;  /* m: the loop */
	double applied;    /* m: the bow the centreline has (within
			      BOW_STEP_M of the loop) */
};

struct haptics {
	struct godobject go;
	struct rodscope *rs;  /* the rod model's tube; NULL: the paper's */
	struct colon *colon;  /* the rod model's: its tube is laid in it */
	bool rod_fresh;       /* lay the tube at the next pose */
	struct lumen_totals wall; /* the rod model's last step's contacts */
	double tip_v[3];      /* the rod model's tip velocity, m/s */
	bool fresh;          /* place the proxy at the next tip */
	double proxy_s;      /* m: where along the colon the proxy is */
	struct span span[CENTRELINE_MAX_SPANS];
	int spans;
	double energy[ENDOSIM_AXES]; /* passivity observers, J */
	double last_x[ENDOSIM_AXES]; /* axis positions last cycle */
};

/* The contact this cycle, in the colon's coordinates now. */
struct touch {
	bool on;
	int planes;
	double proxy[3];
	double normal[3];
	double force[3];    /* F_static, N */
	double spring[3];   /* its spring alone (the rod takes it on) */
	double depth;       /* m */
};

struct haptics *haptics_create(const struct haptics_params *p)
{
	struct haptics *h = calloc(1, sizeof(*h));

	if (!h) {
		return NULL;
	}
	h->fresh = true;
	if (p && p->gains.model == HAPTICS_MODEL_ROD) {
		h->rs = rodscope_create(&p->rod);
		if (!h->rs) {
			free(h);
			return NULL;
		}
	}
	return h;
}

void haptics_destroy(struct haptics *h)
{
	if (h) {
		rodscope_destroy(h->rs);
		free(h);
	}
}

void haptics_publish_rod(const struct haptics *h, double roll_rad,
			 struct endosim_rod_state *out,
			 double bow_m[ENDOSIM_SPANS])
{
	memset(out, 0, sizeof(*out));
	if (h->rs) {
		rodscope_publish(h->rs, roll_rad, &h->wall, out, bow_m);
	}
}

void haptics_hold_tip(struct haptics *h, double hold_n_per_m)
{
	if (h->rs) {
		rodscope_hold_tip(h->rs, hold_n_per_m);
	}
}

bool haptics_rod(const struct haptics *h)
{
	return h->rs != NULL;
}

/* ---------------------------------------------------------------- frames */

/* The centreline's frame at one sample, now and before any bow. */
struct frame_map {
	const struct centreline_point *now, *base;
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

/* V from frame A's coordinates into frame B's: sum_e e_B (e_A . v). */
static void turn(const struct centreline_point *a,
		 const struct centreline_point *b, const double v[3],
		 double out[3])
{
	double r[3] = { 0, 0, 0 };

	vec3_axpy(r, r, vec3_dot(a->t, v), b->t);
	vec3_axpy(r, r, vec3_dot(a->u, v), b->u);
	vec3_axpy(r, r, vec3_dot(a->v, v), b->v);
	vec3_copy(out, r);
}

/* A point from the colon now into its material placement, and back. */
static void point_to_base(const struct frame_map *m, const double x[3],
			  double out[3])
{
	double d[3];

	vec3_sub(d, x, m->now->p);
	turn(m->now, m->base, d, d);
	vec3_add(out, m->base->p, d);
}

static void point_to_now(const struct frame_map *m, const double x[3],
			 double out[3])
{
	double d[3];

	vec3_sub(d, x, m->base->p);
	turn(m->base, m->now, d, d);
	vec3_add(out, m->now->p, d);
}

/* ---------------------------------------------------------------- loops */

static void setup_span(struct span *sp, struct centreline *cl,
		       const struct colon_region *r)
{
	double l0 = centreline_total_arclength(cl);
	double a = r->max_bow_m / 2;

	sp->index = r->span;
	centreline_span_range(cl, r->span, &sp->s0, &sp->s1);
	sp->k = r->mesentery_n_per_m;
	sp->h = r->max_bow_m;
	sp->amplitude = sp->applied = 0;
	centreline_bow(cl, r->span, a);
	sp->c = (centreline_total_arclength(cl) - l0) / (a * a);
	centreline_bow(cl, r->span, 0);
	if (!(sp->c > 1e-6)) {
		/* a straight span's sin^2 bump: dL = pi^2 A^2 / (4 length) */
		sp->c = M_PI * M_PI / (4 * (sp->s1 - sp->s0));
	}
}

void haptics_reset(struct haptics *h, struct colon *colon)
{
	struct centreline *cl = colon_centreline(colon);

	h->fresh = true;
	h->colon = colon;
	h->rod_fresh = true;
	h->spans = 0;
	memset(h->energy, 0, sizeof(h->energy));
	memset(h->last_x, 0, sizeof(h->last_x));
	for (int i = 0; i < colon_regions(colon); i++) {
		const struct colon_region *r = colon_region(colon, i);

		if (r->span >= 0 && r->span < CENTRELINE_MAX_SPANS &&
		    r->mesentery_n_per_m > 0 && r->max_bow_m > 0) {
			setup_span(&h->span[h->spans++], cl, r);
		}
	}
}

/* The axial force with which a loop's mesentery holds it, N. */
static double mesentery_force(const struct span *sp, double a)
{
	double q = a / sp->h;

	return sp->k / (2 * sp->c) * (1 + 2 * q * q);
}

/*
 * The amplitude at which span SP balances the tip's axial resistance
 * F_TIP (N), given that storing more tube pulls the tip back against the
 * wall's axial stiffness K_AX (N/m):
 *   F_tip - K_AX c (A'^2 - A^2) = F_m(A')
 */
static double balanced_bow(const struct span *sp, double f_tip, double k_ax)
{
	double f0 = sp->k / (2 * sp->c);
	double a = sp->amplitude;
	double num = f_tip + k_ax * sp->c * a * a - f0;
	double den = k_ax * sp->c + 2 * f0 / (sp->h * sp->h);

	return num > 0 ? sqrt(num / den) : 0;
}

/*
 * Moves each loop towards its balance and bows the colon to it. Returns the
 * share of the insertion force the loops carry (N, <= 0: pushing out).
 */
static double update_loops(struct haptics *h, const struct haptics_input *in,
			   double f_tip, double k_ax)
{
	struct centreline *cl = colon_centreline(in->colon);
	double gain = fmin(1.0, in->dt_s / in->params->gains.loop_relax_s);
	double carried = 0;

	for (int i = 0; i < h->spans; i++) {
		struct span *sp = &h->span[i];
		bool filled = sp->s1 < in->pose->base_s_m;
		double target = filled ? balanced_bow(sp, f_tip, k_ax) : 0;
		double a = sp->amplitude + (target - sp->amplitude) * gain;

		a = fmin(fmax(a, 0), MAX_BOW_HEIGHTS * sp->h);
		if (a < MIN_BOW_M && target == 0) {
			a = 0;
		}
		sp->amplitude = a;
		/* re-bowing costs ~0.1 us a sample: only for a visible change */
		if (fabs(a - sp->applied) > BOW_STEP_M ||
		    (a == 0 && sp->applied != 0)) {
			sp->applied = a;
			centreline_bow(cl, sp->index, a);
		}
		if (sp->amplitude > MIN_BOW_M) {
			carried = fmax(carried, fmin(f_tip,
				       mesentery_force(sp, sp->amplitude)));
		}
	}
	return -carried;
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

/*
 * The spring between proxy and tip: the wall's stiffness along the tip's
 * view direction DIR, and across it the wall in series with the bending
 * section's own lateral compliance (a real bending section gives way when
 * its side meets the wall; head-on, the tube does not). K = k_wall D D^T +
 * k_side (I - D D^T), k_side = k_wall k_lat / (k_wall + k_lat).
 */
static void spring(const struct haptics_params *par, const double dir[3],
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
			 const double vel_b[3], struct touch *t)
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
	spring(par, dir_b, delta, t->force);
	vec3_copy(t->spring, t->force);
	/* damping of the penetration rate, as anisotropic as the spring:
	 * B = (b_wall / k_wall) K (the bending section damps across no more
	 * than it gives way across) */
	vec3_scale(rate, t->normal, vec3_dot(vel_b, t->normal));
	spring(par, dir_b, rate, damp);
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

static void touch_wall(struct haptics *h, const struct haptics_input *in,
		       struct touch *t)
{
	const struct haptics_params *par = in->params;
	const struct scope_pose *p = in->pose;
	const struct contact *c = colon_contact(in->colon);
	double tip_b[3], dir_b[3], vel[3], vel_b[3], s0, s1;
	struct frame_map m;

	memset(t, 0, sizeof(*t));
	frame_at(colon_centreline(in->colon), p->tip_s_m, &m);
	point_to_base(&m, p->tip, tip_b);
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
	if (h->rs) {
		vec3_copy(vel, h->tip_v);
	} else {
		tip_velocity(in, vel);
	}
	turn(m.now, m.base, vel, vel_b);
	turn(m.now, m.base, p->dir, dir_b);
	static_force(h, par, tip_b, dir_b, vel_b, t);
	turn(m.base, m.now, t->force, t->force);
	turn(m.base, m.now, t->spring, t->spring);
	turn(m.base, m.now, t->normal, t->normal);
}

/* ---------------------------------------------------------------- tube */

/*
 * The wire length differences of the two wheels (m): dr sum over the
 * samples up to the bending section of [n(i+1) - n(i)] . t(i), n = u' or v'.
 */
static void wire_lengths(const struct haptics_input *in, double dl[2])
{
	const struct centreline *cl = colon_centreline(in->colon);
	const struct scope_pose *p = in->pose;
	double su = 0, sv = 0, dr = in->params->gains.wire_spacing_m;
	double last = floor(p->base_s_m / centreline_step(cl));
	size_t n = last < 1 ? 0 : (size_t)last;

	if (n >= centreline_count(cl)) {
		n = centreline_count(cl) - 1;
	}
	for (size_t i = 0; i < n; i++) {
		const struct centreline_point *a = centreline_sample(cl, i);
		const struct centreline_point *b = centreline_sample(cl, i + 1);
		double du[3], dv[3];

		vec3_sub(du, b->u, a->u);
		vec3_sub(dv, b->v, a->v);
		su += vec3_dot(du, a->t);
		sv += vec3_dot(dv, a->t);
	}
	dl[0] = dr * (cos(p->roll_rad) * su + sin(p->roll_rad) * sv);
	dl[1] = dr * (-sin(p->roll_rad) * su + cos(p->roll_rad) * sv);
}

/* Total turning angle of the inserted tube: the centreline's up to the
 * bending section, and the section's own bend as far as it is inserted. */
static double tube_turning(const struct haptics_input *in)
{
	const struct centreline *cl = colon_centreline(in->colon);
	const struct scope_pose *p = in->pose;
	double i = floor(p->base_s_m / centreline_step(cl) + 0.5);
	size_t n = centreline_count(cl);
	size_t k = i < 0 ? 0 : i >= (double)n ? n - 1 : (size_t)i;
	double inserted = fmin(fmax(p->depth_m, 0) /
			       in->params->bending_length_m, 1);

	return (p->depth_m > 0 ? centreline_turning(cl, k) : 0) +
	       hypot(p->bend_rad[0], p->bend_rad[1]) * inserted;
}

/* ---------------------------------------------------------------- forces */

/* Wheel axis A is turned by a drive behind a bus: its torque lags. */
static bool wheel_lags(const struct haptics_params *par, int a)
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
 * limited instead (wheel_lag_limit). Axes before FIRST are left alone.
 * Returns the damping added on the insertion axis (N s/m).
 */
static double passivity(struct haptics *h, const struct haptics_input *in,
			double contact[ENDOSIM_AXES], int first)
{
	double added = 0;

	for (int a = first; a < ENDOSIM_AXES; a++) {
		double x = in->position[a];
		double v = in->velocity[a];
		double held = in->applied ? in->applied[a] : 0;

		if (in->torque_on && in->params->gains.passivity &&
		    !wheel_lags(in->params, a)) {
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
	return added;
}

/* The contact force's virtual work on each axis (J^T F, wheels through
 * their gains). */
static void generalised(const struct scope_pose *p, const double f[3],
			double out[ENDOSIM_AXES])
{
	double g[4];

	for (int k = 0; k < 4; k++) {
		g[k] = p->jacobian[0][k] * f[0] + p->jacobian[1][k] * f[1] +
		       p->jacobian[2][k] * f[2];
	}
	out[ENDOSIM_AXIS_INSERTION] = g[0];
	out[ENDOSIM_AXIS_ROLL] = g[1];
	out[ENDOSIM_AXIS_WHEEL_UD] = g[2] * p->dbend_dwheel[0];
	out[ENDOSIM_AXIS_WHEEL_LR] = g[3] * p->dbend_dwheel[1];
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

/*
 * The wall's stiffness against wheel W's turning, N m/rad, J_w the tip's
 * way per wheel rad: the spring along the contact's normal n, (J_w . K n)
 * (n . J_w), or where planes meet (the spring holds the tip every way),
 * J_w . K J_w if that is more.
 */
static double wheel_wall_stiffness(const struct haptics_input *in,
				   const struct touch *t, int w)
{
	const struct scope_pose *p = in->pose;
	double jw[3], kn[3], kj[3];

	for (int d = 0; d < 3; d++) {
		jw[d] = p->jacobian[d][2 + w] * p->dbend_dwheel[w];
	}
	spring(in->params, p->dir, t->normal, kn);
	spring(in->params, p->dir, jw, kj);
	return fmax(fabs(vec3_dot(jw, kn) * vec3_dot(t->normal, jw)),
		    vec3_dot(jw, kj));
}

/*
 * The stiffness wheel W can render behind its drive's lag, N m/rad: its
 * virtual damping over the lag (the period's hold and wheel_delay_s),
 * less what the bending section's spring already takes (haptics.h).
 */
static double wheel_stiffness_budget(const struct haptics_input *in, int w)
{
	const struct haptics_params *par = in->params;
	double g = in->pose->dbend_dwheel[w];
	double lag = in->dt_s / 2 + par->gains.wheel_delay_s;

	return fmax(0, par->gains.damping[ENDOSIM_AXIS_WHEEL_UD + w] / lag -
			       par->gains.bending_stiffness_n_m_per_rad *
				       g * g);
}

/*
 * The wall on a wheel that a drive turns: spring and damping scaled
 * together down to the stiffness its lag allows. The simulated rig's
 * wheels are left alone (no lag beyond the period's hold, which the
 * passivity observer accounts for exactly).
 */
static void wheel_lag_limit(const struct haptics_input *in,
			    const struct touch *t, double contact[ENDOSIM_AXES])
{
	for (int w = 0; w < 2 && t->on; w++) {
		int a = ENDOSIM_AXIS_WHEEL_UD + w;
		double k = wheel_wall_stiffness(in, t, w);
		double most = wheel_stiffness_budget(in, w);

		if (wheel_lags(in->params, a) && k > most) {
			contact[a] *= most / k;
		}
	}
}

/* The contact's stiffness against insertion, J_d^T K J_d, N/m. */
static double axial_stiffness(const struct haptics_input *in,
			      const struct touch *t)
{
	const struct scope_pose *p = in->pose;
	double jd[3] = { p->jacobian[0][0], p->jacobian[1][0],
			 p->jacobian[2][0] };
	double kj[3];

	if (!t->on) {
		return 0;
	}
	spring(in->params, p->dir, jd, kj);
	return vec3_dot(jd, kj);
}

static void publish(const struct touch *t, struct endosim_haptics_state *o)
{
	vec3_copy(o->proxy, t->proxy);
	vec3_copy(o->normal, t->normal);
	vec3_copy(o->f_static, t->force);
	o->penetration_m = t->depth;
	o->contact = t->on;
	o->constraints = (uint32_t)t->planes;
}

/*
 * Both models' last parts: each wheel's (the contact's CONTACT, the wire
 * tension from OUT's wire_dl_m, the spring-back and the stop) and every
 * axis' damping, into OUT; the wheels' COMMAND, and the damping added to
 * every axis' (insertion's and roll's set before).
 */
static void wheels_and_damping(const struct haptics_input *in,
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

/* ---------------------------------------------------------------- rod */

/* The rig's axes as the rod model takes them. */
static void rod_axes(const struct haptics_params *par, const double *position,
		     const double *velocity, struct rodscope_axes *a)
{
	const struct scope_params sp = {
		.bending_length_m = par->bending_length_m,
		.ud_gain = par->wheel_gain[0], .lr_gain = par->wheel_gain[1],
		.ud_limit_rad = par->wheel_limit_rad[0],
		.lr_limit_rad = par->wheel_limit_rad[1],
	};

	a->depth_m = position[ENDOSIM_AXIS_INSERTION];
	a->depth_m_s = velocity[ENDOSIM_AXIS_INSERTION];
	a->roll_rad = position[ENDOSIM_AXIS_ROLL];
	a->roll_rad_s = velocity[ENDOSIM_AXIS_ROLL];
	scope_bend(&sp, position[ENDOSIM_AXIS_WHEEL_UD],
		   position[ENDOSIM_AXIS_WHEEL_LR], a->bend_rad,
		   a->dbend_dwheel);
}

void haptics_rod_pose(struct haptics *h, const struct haptics_params *par,
		      const double *position, const double *velocity,
		      struct scope_pose *pose)
{
	struct rodscope_axes a;

	rod_axes(par, position, velocity, &a);
	rodscope_set_params(h->rs, &par->rod);
	if (h->rod_fresh || !rodscope_finite(h->rs)) {
		rodscope_reset(h->rs, h->colon, &a);
		h->rod_fresh = false;
		h->fresh = true;
	}
	rodscope_pose(h->rs, &a, pose, h->tip_v);
}

/*
 * The tip's contact as the rod takes it: the god-object's spring K (along
 * the view direction the wall's, across it in series with the bending
 * section's side: spring()) with the force it has now, never pulling, and
 * the damping of the penetration rate, B = (b_wall / k_wall) (n . K n) n
 * n^T, both implicit in the rod's step.
 */
static void rod_tip(const struct haptics_input *in, const struct touch *t,
		    struct rodscope_tip *tip)
{
	const struct haptics_params *par = in->params;
	double kn[3], knn, bk;

	memset(tip, 0, sizeof(*tip));
	if (!t->on) {
		return;
	}
	tip->on = true;
	if (vec3_dot(t->spring, t->normal) > 0) {
		vec3_copy(tip->force, t->spring);
	}
	for (int c = 0; c < 3; c++) {
		double e[3] = { c == 0, c == 1, c == 2 }, col[3];

		spring(par, in->pose->dir, e, col);
		for (int r = 0; r < 3; r++) {
			tip->k[r][c] = col[r];
		}
	}
	spring(par, in->pose->dir, t->normal, kn);
	knn = vec3_dot(t->normal, kn);
	bk = par->gains.wall_damping_n_s_per_m /
	     fmax(par->gains.wall_stiffness_n_per_m, 1e-9);
	for (int r = 0; r < 3; r++) {
		for (int c = 0; c < 3; c++) {
			tip->b[r][c] = bk * knn * t->normal[r] * t->normal[c];
		}
	}
}

/*
 * The bending section's stiffness at wheel W with the tip held, EI_b g^2 /
 * Lb: a drive's wheel takes the moment scaled down to what its lag allows
 * (as the paper's wall, wheel_lag_limit()).
 */
static double rod_wheel_scale(const struct haptics_input *in, int w)
{
	const struct haptics_params *par = in->params;
	double g = in->pose->dbend_dwheel[w];
	double k = par->rod.tip_bending_n_m2 * g * g / par->bending_length_m;
	double most = wheel_stiffness_budget(in, w);

	if (!wheel_lags(par, ENDOSIM_AXIS_WHEEL_UD + w) || k <= most) {
		return 1;
	}
	return most / k;
}

static void render_rod(struct haptics *h, const struct haptics_input *in,
		       double command[ENDOSIM_AXES],
		       struct endosim_haptics_state *out)
{
	const struct haptics_params *par = in->params;
	double contact[ENDOSIM_AXES] = { 0 };
	struct rodscope_axes a;
	struct rodscope_tip tip;
	struct rodscope_out ro;
	struct touch t;

	memset(out, 0, sizeof(*out));
	rod_axes(par, in->position, in->velocity, &a);
	touch_wall(h, in, &t);
	publish(&t, out);
	rod_tip(in, &t, &tip);
	rodscope_step(h->rs, &a, &tip, in->dt_s, &ro);
	for (int w = 0; w < 2; w++) {
		contact[ENDOSIM_AXIS_WHEEL_UD + w] = ro.wheel_nm[w] *
						     rod_wheel_scale(in, w);
	}
	/* the rod is passive by its own making (implicit, damped, coupled
	 * by a spring-damper): the observer watches the wheels only */
	out->passivity_damping = passivity(h, in, contact,
					   ENDOSIM_AXIS_WHEEL_UD);
	for (int ax = 0; ax < ENDOSIM_AXES; ax++) {
		out->passivity_energy_j += h->energy[ax];
	}
	out->curvature_rad = ro.turning_rad;
	out->trans_rod_n = ro.insertion_n;
	out->tube_rod_nm = ro.roll_nm;
	memcpy(out->wire_dl_m, ro.wire_dl_m, sizeof(out->wire_dl_m));
	command[ENDOSIM_AXIS_INSERTION] = out->trans_rod_n;
	command[ENDOSIM_AXIS_ROLL] = out->tube_rod_nm;
	wheels_and_damping(in, contact, out, command);
	h->wall = ro.wall;
}

void haptics_render(struct haptics *h, const struct haptics_input *in,
		    double command[ENDOSIM_AXES],
		    struct endosim_haptics_state *out)
{
	const struct haptics_params *par = in->params;

	if (h->rs) {
		render_rod(h, in, command, out);
		return;
	}
	const struct scope_pose *p = in->pose;
	double contact[ENDOSIM_AXES], k = tube_turning(in), f_tip;
	struct touch t;

	memset(out, 0, sizeof(*out));
	touch_wall(h, in, &t);
	publish(&t, out);
	generalised(p, t.force, contact);
	f_tip = fmax(0, -contact[ENDOSIM_AXIS_INSERTION]);
	wheel_lag_limit(in, &t, contact);
	out->passivity_damping = passivity(h, in, contact, 0);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		out->passivity_energy_j += h->energy[a];
	}
	out->curvature_rad = k;
	out->trans_loop_n = update_loops(h, in, f_tip, axial_stiffness(in, &t));
	out->trans_contact_n = contact[ENDOSIM_AXIS_INSERTION] -
			       out->trans_loop_n;
	out->trans_friction_n = -par->gains.friction_n_s_per_m_rad * k *
				in->velocity[ENDOSIM_AXIS_INSERTION];
	out->tube_contact_nm = contact[ENDOSIM_AXIS_ROLL];
	out->tube_friction_nm = -par->gains.torsion_n_m_s_per_rad2 * k *
				in->velocity[ENDOSIM_AXIS_ROLL];
	wire_lengths(in, out->wire_dl_m);
	command[ENDOSIM_AXIS_INSERTION] = out->trans_contact_n +
					  out->trans_loop_n +
					  out->trans_friction_n;
	command[ENDOSIM_AXIS_ROLL] = out->tube_contact_nm +
				     out->tube_friction_nm;
	wheels_and_damping(in, contact, out, command);
}
