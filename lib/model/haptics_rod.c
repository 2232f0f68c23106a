/* haptics_rod.c - see haptics_rod.h. */
#include "model/haptics_rod.h"

#include <errno.h>
#include <string.h>

#include "base/vec3.h"
#include "model/haptics_private.h"

int haptics_rod_create(struct haptics *h, const struct rodscope_params *p)
{
	h->rod.rs = rodscope_create(p);
	return h->rod.rs ? 0 : -ENOMEM;
}

void haptics_rod_destroy(struct haptics *h)
{
	rodscope_destroy(h->rod.rs);
}

void haptics_rod_reset(struct haptics *h, struct colon *colon)
{
	h->rod.colon = colon;
	h->rod.fresh = true;
}

void haptics_rod_publish(const struct haptics *h, double roll_rad,
			 struct endosim_rod_state *out,
			 double bow_m[ENDOSIM_SPANS])
{
	rodscope_publish(h->rod.rs, roll_rad, &h->rod.wall, out, bow_m);
}

void haptics_rod_hold_tip(struct haptics *h, double hold_n_per_m)
{
	rodscope_hold_tip(h->rod.rs, hold_n_per_m);
}

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
	rodscope_set_params(h->rod.rs, &par->rod);
	if (h->rod.fresh || !rodscope_finite(h->rod.rs)) {
		rodscope_reset(h->rod.rs, h->rod.colon, &a);
		h->rod.fresh = false;
		h->fresh = true;
	}
	rodscope_pose(h->rod.rs, &a, pose, h->rod.tip_v);
}

/*
 * The tip's contact as the rod takes it: the god-object's spring K (along
 * the view direction the wall's, across it in series with the bending
 * section's side: haptics_spring()) with the force it has now, never
 * pulling, and the damping of the penetration rate, B = (b_wall / k_wall)
 * (n . K n) n n^T, both implicit in the rod's step.
 */
static void rod_tip(const struct haptics_input *in,
		    const struct haptics_touch *t, struct rodscope_tip *tip)
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

		haptics_spring(par, in->pose->dir, e, col);
		for (int r = 0; r < 3; r++) {
			tip->k[r][c] = col[r];
		}
	}
	haptics_spring(par, in->pose->dir, t->normal, kn);
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
 * (as the paper's wall: haptics_paper.c).
 */
static double rod_wheel_scale(const struct haptics_input *in, int w)
{
	const struct haptics_params *par = in->params;
	double g = in->pose->dbend_dwheel[w];
	double k = par->rod.tip_bending_n_m2 * g * g / par->bending_length_m;
	double most = haptics_wheel_budget(in, w);

	if (!haptics_wheel_lags(par, ENDOSIM_AXIS_WHEEL_UD + w) || k <= most) {
		return 1;
	}
	return most / k;
}

/* The patient's gas, gravity and hand on the tube and the colon. */
static void rod_patient(struct haptics *h)
{
	struct flex_pad pad;
	double g[3];

	patient_gravity(&h->patient, g);
	patient_pad(&h->patient, &pad);
	rodscope_set_patient(h->rod.rs, h->patient.p.enabled ?
					  h->patient.factor : NULL, g, &pad);
}

void haptics_rod_render(struct haptics *h, const struct haptics_input *in,
			double command[ENDOSIM_AXES],
			struct endosim_haptics_state *out)
{
	const struct haptics_params *par = in->params;
	double contact[ENDOSIM_AXES] = { 0 };
	struct rodscope_axes a;
	struct rodscope_tip tip;
	struct rodscope_out ro;
	struct haptics_touch t;

	memset(out, 0, sizeof(*out));
	rod_axes(par, in->position, in->velocity, &a);
	haptics_touch_wall(h, in, h->rod.tip_v, &t);
	haptics_publish_touch(&t, out);
	rod_tip(in, &t, &tip);
	rod_patient(h);
	rodscope_step(h->rod.rs, &a, &tip, in->dt_s, &ro);
	h->patient.pad_n = rodscope_pad_force(h->rod.rs);
	for (int sp = 0; sp < ENDOSIM_SPANS; sp++) {
		h->span_tension_n[sp] = rodscope_span_tension(h->rod.rs, sp);
	}
	for (int w = 0; w < 2; w++) {
		contact[ENDOSIM_AXIS_WHEEL_UD + w] = ro.wheel_nm[w] *
						     rod_wheel_scale(in, w);
	}
	/* the rod is passive by its own making (implicit, damped, coupled
	 * by a spring-damper): the observer watches the wheels only */
	haptics_passivity(h, in, contact, ENDOSIM_AXIS_WHEEL_UD, out);
	out->curvature_rad = ro.turning_rad;
	out->trans_rod_n = ro.insertion_n;
	out->tube_rod_nm = ro.roll_nm;
	memcpy(out->wire_dl_m, ro.wire_dl_m, sizeof(out->wire_dl_m));
	command[ENDOSIM_AXIS_INSERTION] = out->trans_rod_n;
	command[ENDOSIM_AXIS_ROLL] = out->tube_rod_nm;
	haptics_wheels_and_damping(in, contact, out, command);
	h->rod.wall = ro.wall;
}
