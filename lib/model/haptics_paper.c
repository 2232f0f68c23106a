/* haptics_paper.c - see haptics_paper.h. */
#include "model/haptics_paper.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"
#include "model/haptics_private.h"

#define MIN_BOW_M 1e-4     /* a loop smaller than this is no loop */
#define MAX_BOW_HEIGHTS 1.5 /* a bow never exceeds this many mesentery heights */
#define BOW_STEP_M 1e-4    /* smaller changes are not applied */

/* ---------------------------------------------------------------- loops */

static void setup_span(struct haptics_paper_span *sp, struct centreline *cl,
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

void haptics_paper_reset(struct haptics *h, struct colon *colon)
{
	struct centreline *cl = colon_centreline(colon);
	struct haptics_paper_loops *lp = &h->loops;

	lp->spans = 0;
	for (int i = 0; i < colon_regions(colon); i++) {
		const struct colon_region *r = colon_region(colon, i);

		if (r->span >= 0 && r->span < CENTRELINE_MAX_SPANS &&
		    r->mesentery_n_per_m > 0 && r->max_bow_m > 0) {
			setup_span(&lp->span[lp->spans++], cl, r);
		}
	}
}

/* The axial force with which a loop's mesentery holds it, N. */
static double mesentery_force(const struct haptics_paper_span *sp, double a)
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
static double balanced_bow(const struct haptics_paper_span *sp, double f_tip,
			   double k_ax)
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

	for (int i = 0; i < h->loops.spans; i++) {
		struct haptics_paper_span *sp = &h->loops.span[i];
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
		if (sp->index < ENDOSIM_SPANS) { /* the pain's: as flex's node */
			double q = a / sp->h;

			h->span_tension_n[sp->index] = sp->k * (1 + q * q) * a;
		}
	}
	return -carried;
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
 * The wall's stiffness against wheel W's turning, N m/rad, J_w the tip's
 * way per wheel rad: the spring along the contact's normal n, (J_w . K n)
 * (n . J_w), or where planes meet (the spring holds the tip every way),
 * J_w . K J_w if that is more.
 */
static double wheel_wall_stiffness(const struct haptics_input *in,
				   const struct haptics_touch *t, int w)
{
	const struct scope_pose *p = in->pose;
	double jw[3], kn[3], kj[3];

	for (int d = 0; d < 3; d++) {
		jw[d] = p->jacobian[d][2 + w] * p->dbend_dwheel[w];
	}
	haptics_spring(in->params, p->dir, t->normal, kn);
	haptics_spring(in->params, p->dir, jw, kj);
	return fmax(fabs(vec3_dot(jw, kn) * vec3_dot(t->normal, jw)),
		    vec3_dot(jw, kj));
}

/*
 * The wall on a wheel that a drive turns: spring and damping scaled
 * together down to the stiffness its lag allows. The simulated rig's
 * wheels are left alone (no lag beyond the period's hold, which the
 * passivity observer accounts for exactly).
 */
static void wheel_lag_limit(const struct haptics_input *in,
			    const struct haptics_touch *t,
			    double contact[ENDOSIM_AXES])
{
	for (int w = 0; w < 2 && t->on; w++) {
		int a = ENDOSIM_AXIS_WHEEL_UD + w;
		double k = wheel_wall_stiffness(in, t, w);
		double most = haptics_wheel_budget(in, w);

		if (haptics_wheel_lags(in->params, a) && k > most) {
			contact[a] *= most / k;
		}
	}
}

/* The contact's stiffness against insertion, J_d^T K J_d, N/m. */
static double axial_stiffness(const struct haptics_input *in,
			      const struct haptics_touch *t)
{
	const struct scope_pose *p = in->pose;
	double jd[3] = { p->jacobian[0][0], p->jacobian[1][0],
			 p->jacobian[2][0] };
	double kj[3];

	if (!t->on) {
		return 0;
	}
	haptics_spring(in->params, p->dir, jd, kj);
	return vec3_dot(jd, kj);
}

void haptics_paper_render(struct haptics *h, const struct haptics_input *in,
			  double command[ENDOSIM_AXES],
			  struct endosim_haptics_state *out)
{
	const struct haptics_params *par = in->params;
	const struct scope_pose *p = in->pose;
	double contact[ENDOSIM_AXES], k = tube_turning(in), f_tip;
	struct haptics_touch t;

	memset(out, 0, sizeof(*out));
	haptics_touch_wall(h, in, NULL, &t);
	haptics_publish_touch(&t, out);
	generalised(p, t.force, contact);
	f_tip = fmax(0, -contact[ENDOSIM_AXIS_INSERTION]);
	wheel_lag_limit(in, &t, contact);
	haptics_passivity(h, in, contact, 0, out);
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
	haptics_wheels_and_damping(in, contact, out, command);
}
