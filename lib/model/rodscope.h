/*
 * rodscope.h - the endoscope's insertion tube as an elastic rod (rod.h) in
 * the rig and in a colon that moves (lumen.h, flex.h): the haptics' `rod`
 * model (haptics.h).
 *
 * Feeding. The whole tube, L long (1.6 m), always exists: the part outside
 * the patient lies in the rig's straight slitted pipe, which is the
 * colon's first tangent produced back from the anal verge, and the
 * carriage holds the tube's proximal end. With the insertion axis at d
 * (m) and the roll axis at phi (rad), the carriage is at material s =
 * min(d, L) - L on the pipe's axis, its frame the pipe's (u0, v0, t0, the
 * colon's first frame) turned by phi about t0. It holds the tube's end
 * point by a virtual coupling (Colgate 1995): a spring-damper of
 * coupling_n_per_m along the pipe and roll_n_m_per_rad about it, rigid
 * across and against bending (the half segment at the rod's end,
 * rod_clamp_compliance()). The insertion force the trainee feels is the
 * coupling's pull, the rod's axial reaction there; the roll torque its
 * twisting moment there. Pushed past d = L (the handle at the anus) the
 * carriage meets a stiff stop.
 *
 * The bending section, the tube's last Lb (n_b segments), has the rest
 * bend the wheels set (scope_bend(): gains and limits), spread evenly over
 * its n_b joints: a bend up (towards the camera's up, d1) turns about d2,
 * right (towards d2) about -d1. Its stiffness is tip_bending_n_m2: the
 * wires that hold it. Each wheel feels the bending section's moment about
 * its wire: by virtual work, tau_w = sum_j m_j . d theta0_j / d wheel,
 * m_j the joint's moment beyond rest (rod_joint_moment()), which is how
 * the tip's contact and the wall reach the wheels (a tip force F on a stiff
 * section gives J^T F, the paper's), and the paper's wire tension over the
 * rod's real shape: dL_w = dr sum_i [n_w(i+1) - n_w(i)] . d3(i) over the
 * inserted segments before the bending section, n_ud = d1, n_lr = d2 (the
 * material frame: the roll is in it).
 *
 * The tip. The camera is the last segment's end: position, view direction
 * d3, up d1. The tip's god-object contact (haptics.h) enters the rod
 * there as a spring and a damper on the step (rod_load_point()).
 *
 * Each step, in the force loop: the carriage's coupling from the axes, the
 * bending section's rest from the wheels, the tip's contact, every
 * segment's contact with the pipe or the lumen (lumen.h), one rod step,
 * the contacts' reactions onto the colon and one step of the colon
 * (flex.h). Fixed work per step (O(segments)), no allocation; runs repeat
 * bit for bit.
 */
#ifndef ENDOSIM_RODSCOPE_H
#define ENDOSIM_RODSCOPE_H

#include <stdbool.h>

#include "model/colon.h"
#include "proto/endosim_shm.h"
#include "model/flex.h"
#include "model/lumen.h"
#include "model/rod.h"
#include "model/scope.h"

struct rodscope_params {
	struct rod_params rod;            /* the tube (ROD_PARAMS_DEFAULT) */
	double bending_length_m;          /* Lb: the scope's bending section */
	double tip_bending_n_m2;          /* the bending section's EI */
	struct lumen_params lumen;        /* the wall and the pipe */
	struct flex_params flex;          /* the colon that moves */
	double coupling_n_per_m;          /* carriage: along the pipe */
	double coupling_n_s_per_m;
	double roll_n_m_per_rad;          /* carriage: about the pipe */
	double roll_n_m_s_per_rad;
	double stop_n_per_m;              /* the handle at the anus */
	double wire_spacing_m;            /* dr: the wires from the axis */
};

#define RODSCOPE_DEFAULT_TIP_BENDING_N_M2 0.01
#define RODSCOPE_DEFAULT_COUPLING_N_PER_M 3000
#define RODSCOPE_DEFAULT_COUPLING_N_S_PER_M 20
#define RODSCOPE_DEFAULT_ROLL_N_M_PER_RAD 2
#define RODSCOPE_DEFAULT_ROLL_N_M_S_PER_RAD 0.005
#define RODSCOPE_DEFAULT_STOP_N_PER_M 5000

#define RODSCOPE_PARAMS_DEFAULT { \
	.rod = ROD_PARAMS_DEFAULT, \
	.bending_length_m = SCOPE_DEFAULT_BENDING_LENGTH_M, \
	.tip_bending_n_m2 = RODSCOPE_DEFAULT_TIP_BENDING_N_M2, \
	.lumen = LUMEN_PARAMS_DEFAULT, \
	.flex = FLEX_PARAMS_DEFAULT, \
	.coupling_n_per_m = RODSCOPE_DEFAULT_COUPLING_N_PER_M, \
	.coupling_n_s_per_m = RODSCOPE_DEFAULT_COUPLING_N_S_PER_M, \
	.roll_n_m_per_rad = RODSCOPE_DEFAULT_ROLL_N_M_PER_RAD, \
	.roll_n_m_s_per_rad = RODSCOPE_DEFAULT_ROLL_N_M_S_PER_RAD, \
	.stop_n_per_m = RODSCOPE_DEFAULT_STOP_N_PER_M, \
	.wire_spacing_m = SCOPE_WIRE_SPACING_M }

/* What the rig's axes are this step. */
struct rodscope_axes {
	double depth_m, depth_m_s;        /* insertion and its speed */
	double roll_rad, roll_rad_s;
	double bend_rad[2];               /* the wheels' rest bends: ud, lr */
	double dbend_dwheel[2];           /* their gains, 0 at a limit */
};

/* The tip's contact for this step: a spring K (N/m) towards where the
 * force F (N, world) acts now, and a damper B (N s/m). */
struct rodscope_tip {
	bool on;
	double force[3];
	double k[3][3];
	double b[3][3];
};

/* What the step gives the axes and the world. */
struct rodscope_out {
	double insertion_n;     /* on the carriage, + inserts */
	double roll_nm;         /* on the roll axis, + turns as phi */
	double wheel_nm[2];     /* the bending section's moment on each wheel */
	double wire_dl_m[2];    /* the wire length differences */
	double turning_rad;     /* total turning of the inserted tube */
	struct lumen_totals wall; /* the lumen's contacts */
};

struct rodscope;

/* The tube, its contacts and the colon's chains. NULL on bad parameters
 * or ENOMEM. */
struct rodscope *rodscope_create(const struct rodscope_params *p);

/* NULL is fine. */
void rodscope_destroy(struct rodscope *rs);

/*
 * COLON (the first, or a new one: attached, no allocation) and the tube
 * laid anew at rest as the axes A have it: along the pipe and, the part
 * inserted, along the colon's centreline, its frame turned by the roll.
 */
void rodscope_reset(struct rodscope *rs, struct colon *colon,
		    const struct rodscope_axes *a);

/* Live parameters: all but the rod's segments, length and iterations. */
void rodscope_set_params(struct rodscope *rs, const struct rodscope_params *p);

/*
 * The scope's pose as the tube is now (scope.h: depth and roll from A,
 * bends, base and tip s, tip, dir, up, the 128-point tube from the anal
 * verge to the tip); the Jacobian is not filled (the rod model needs
 * none). Also the tip's velocity (m/s).
 */
void rodscope_pose(const struct rodscope *rs, const struct rodscope_axes *a,
		   struct scope_pose *pose, double tip_velocity[3]);

/*
 * A tip held where it is, by a spring of HOLD_N_PER_M (N/m, its direction
 * free), from the next step on, or let go (0): a tip impacted in a fold or
 * caught in a spasm, as the clinic's tests and an instructor's
 * demonstration of a loop want it.
 */
void rodscope_hold_tip(struct rodscope *rs, double hold_n_per_m);

/* One step of DT_S: the tube, its contacts, the colon. */
/*
 * The patient around the tube for the next steps: the lumen's radius
 * FACTOR per segment (gas.h; NULL: the case's, held by pointer), gravity
 * G (m/s^2, body frame: on every segment of the tube and the mobile
 * colon's nodes; zeros: none) and the assistant's PAD (NULL: none).
 */
void rodscope_set_patient(struct rodscope *rs, const double *factor,
			  const double g[3], const struct flex_pad *pad);

/* The force the pad held on the colon in the last step, N. */
double rodscope_pad_force(const struct rodscope *rs);

/* Mobile span SPAN's mesentery tension after the last step, N
 * (flex_span_tension()). */
double rodscope_span_tension(const struct rodscope *rs, int span);

void rodscope_step(struct rodscope *rs, const struct rodscope_axes *a,
		   const struct rodscope_tip *tip, double dt_s,
		   struct rodscope_out *out);

/*
 * The published rod state (endosim_shm.h) after the last step: the tube's
 * points and roll (ROLL_RAD: the carriage's), the colon's nodes, the
 * wall's contacts (WALL: the last step's); and each mobile span's largest
 * displacement in BOW_M (the loop's size).
 */
void rodscope_publish(const struct rodscope *rs, double roll_rad,
		      const struct lumen_totals *wall,
		      struct endosim_rod_state *out,
		      double bow_m[ENDOSIM_SPANS]);

/* Every segment finite. */
bool rodscope_finite(const struct rodscope *rs);

#endif
