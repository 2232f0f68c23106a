/*
 * haptics.h - the forces the trainee feels, by one of two models
 * ([haptics] model):
 *
 * `rod` (the default): the insertion tube is an elastic rod in a colon
 * that moves (rodscope.h: the rod, its feeding from the carriage, its
 * contact with the lumen, the mobile spans as chains of nodes). The tip's
 * god-object contact below enters the rod at its tip; the insertion force
 * is the rod's reaction at the carriage, the roll torque its twisting
 * moment there, each wheel the bending section's moment about its wire
 * plus the wire tension over the rod's shape; each wheel keeps its stop
 * and its spring-back (below). The passivity observer watches the wheels
 * only: the rod is passive by its making (implicit, damped, held by a
 * spring-damper). The kinematics are the rod's (haptics_rod_pose()).
 *
 * `paper`: Koerner and Maenner, section 5, generalised where the brief
 * says how. Every cycle of the force loop, from the scope's pose (scope.h)
 * on the colon's centreline (colon.h):
 *
 * Tip contact (5.1). A god-object proxy (godobject.h) against the colon's
 * wall inset by the tip's radius (contact.h), only the triangles of the
 * colon's stretch around the tip considered. The static force
 *   F_static = K (proxy - tip) - (b_wall / k_wall) K v_n
 * with the depth pushed along the constraint planes' interpolated normal
 * when force_shading is on, and never pulling the tip into the wall. Contact works in the colon's
 * material (undeformed) placement: the tip is mapped there through the
 * frame of the centreline sample nearest it, and the force mapped back, so
 * that a bowed segment needs no moving of triangles.
 *
 * Generalised forces by virtual work: with J the Jacobian of the tip
 * position in (d, phi, bend_ud, bend_lr) (scope.h), the contact part of
 * each axis is J^T F_static, and of a wheel that times d bend/d wheel. With
 * a straight tip this is the paper's n . F_static projection: d tip/d bend
 * = (Lb/2) n, n the wheel's bending direction.
 *
 * Insertion (5.2): the contact part, plus the friction
 *   F_dyn = -c_f v K,  K = sum_i |r(i) - 2 r(i+1) + r(i+2)| / ds
 * the total turning angle of the inserted tube: the centreline's up to the
 * bending section (precomputed, following the bows) plus the bending
 * section's own bend, over the share of it inserted (min(depth, Lb) / Lb,
 * as the kinematics bend it: nothing outside the patient rubs).
 *
 * Wheels (5.3): the contact part, plus the wire tension
 *   tau_k = k_t dL_k,  dL_k = dr sum_i [n_k(i+1) - n_k(i)] . t(i)
 * over the inserted tube up to the bending section, n_k the wheel's wire
 * direction (the centreline's rotation-minimising u, v turned by the roll:
 * up/down u', left/right v'), plus the bending section springing back,
 * -k_bend bend_k d bend_k/d wheel_k. A planar bend Theta in a wire's plane
 * gives |dL| = dr Theta; an S-curve cancels.
 *
 * The knobs' ends. Past the angle at which its tip reaches the angulation
 * limit (limit / gain), a wheel meets its stop: d rad past it at v rad/s,
 *   tau_stop = -k_stop d - b_stop v
 * only ever pushing the wheel back, at most the wheel's [limits] torque
 * beyond the tension pushing it on (so the tension cannot push through);
 * the bending section's spring-back stays at its value at the limit. Both
 * are published in wheel_elastic_nm.
 *
 * Tube roll: the contact part, and torsional friction -c_r omega K.
 *
 * Loops (end of 5.2). Each mobile segment (sigmoid, transverse) that the
 * tube fills entirely behind the bending section can bow by an amplitude A
 * (centreline.h); stored tube length dL(A) ~ c A^2 (c measured on the
 * segment). Its mesentery holds the bow with the energy
 *   U(A) = k A^2 (1 + (A/h)^2) / 2     (k: stiffness, h: its height)
 * which resists the tube with the axial force F_m(A) = U'(A) / dL'(A)
 *   = k/(2c) (1 + 2 (A/h)^2)
 * (a threshold, then stiffening). When the wall resists the tip with more
 * than that (the tip is held and the hand pushes), the excess tube goes
 * into the bow: A grows until the tip's axial resistance, which falls as
 * the stored length pulls the tip back, equals F_m(A). The tip does not
 * advance, the curvature integral grows (and with it friction and wire
 * tension), and the force rises with the loop; withdrawing releases it. A
 * follows that balance with the time constant loop_relax_s. The part of
 * the insertion force the loop carries is published as trans_loop_n.
 *
 * Every axis: a light virtual damping (the feel of a real scope's
 * inertia; a margin of stability), -b v.
 *
 * Stability: a passivity observer and controller (Hannaford and Ryu 2002)
 * on each axis: the energy the rendered environment took in, exactly as a
 * sampled device delivers it, E += -F(n-1) (x(n) - x(n-1)) with F(n-1) the
 * setpoint the drive held over the last period; when E goes negative (the
 * environment gave out energy it never got, as a stiff spring held over a
 * period does) damping on the contact part removes that much.
 *
 * A wheel behind a lag. A drive on a bus applies a torque computed from a
 * position some time ago: the period's hold (dt/2 on average) and
 * [haptics] wheel_delay_s (the feedback's age and the command's way to the
 * motor: 2-4 ms on Modbus TCP). A spring K rendered T = dt/2 + delay late
 * acts as K minus a damping K T; Colgate and Schenkel's condition for a
 * sampled wall (b > K dt/2) becomes b > K T, so with the wheel's virtual
 * damping b (its own friction is not known: counted as none)
 *   K_wheel <= b / T
 * for everything stiff on the wheel (the stop brings its own damping:
 * 0.5 N m/rad behind 3.5 ms needs 1.75e-3 of its 4e-3). The discrete closed loop of a light
 * wheel (2e-5 kg m^2) with a K, b command d periods late is unstable just
 * past b / (dt/2 + d dt) (within 1-7% for b = 2e-4..2e-3, d = 1..3).
 * The wall alone is ~1-2 N m/rad at a wheel (the bending section's side
 * spring through (Lb/2 gain)^2): ~30 Hz on that wheel, unstable behind 3 ms
 * whatever damping is added (a damping above ~J/T is itself unstable when
 * late). So on a wheel that a drive turns, the wall's part (spring and
 * damping together, the damping a share of it) is scaled down to the
 * stiffness left after the bending section's spring: (J_w . K n)(n . J_w)
 * <= b / T - k_bend (d bend/d wheel)^2, J_w the tip's way per wheel rad,
 * n the contact's normal. The defaults give ~0.01-0.03 N m/rad there; a
 * rig that wants a firmer wall raises the wheel's damping (below J / T).
 * The passivity observer is off on such a wheel: it does not know what the
 * drive held, and damping a deficit it only imagines kicks the wheel. The
 * simulated rig applies each command over the next period, which the
 * observer accounts for exactly: its wheels are left as they were.
 *
 * Units SI, SI names. The struct and its arrays are allocated by
 * haptics_create(); the rest never allocates, blocks or prints: force loop.
 */
#ifndef ENDOSIM_HAPTICS_H
#define ENDOSIM_HAPTICS_H

#include <stdbool.h>

#include "model/colon.h"
#include "model/patient.h"
#include "proto/endosim_shm.h"
#include "model/rodscope.h"
#include "model/scope.h"

/* [haptics] model: which model renders the forces. */
enum haptics_model {
	HAPTICS_MODEL_PAPER = 0, /* the paper's: the tube on the centreline */
	HAPTICS_MODEL_ROD = 1,   /* an elastic rod in a colon that moves */
};

/* The model's gains: the configuration's [haptics] (every key with its
 * unit and range in `endosimd --print-config`). Units in the names. */
struct haptics_gains {
	int model;                     /* enum haptics_model (not live) */
	double scope_radius_m;         /* the tip: the contact inset */
	double wall_stiffness_n_per_m;
	double wall_damping_n_s_per_m;
	double tip_lateral_stiffness_n_per_m; /* bending section */
	int force_shading;             /* 1: interpolated normals */
	double contact_reach_m;        /* colon searched around the tip */
	double entry_depth_m;          /* contact from this depth on */
	double friction_n_s_per_m_rad; /* c_f */
	double torsion_n_m_s_per_rad2; /* roll friction per turning */
	double wire_spacing_m;         /* dr */
	double wire_tension_n_m_per_m; /* k_t */
	double bending_stiffness_n_m_per_rad;
	double stop_stiffness_n_m_per_rad; /* each knob's end */
	double stop_damping_n_m_s_per_rad;
	double wheel_delay_s;          /* a drive's wheel: its lag */
	double loop_relax_s;           /* how fast a loop follows */
	double damping[ENDOSIM_AXES];  /* N s/m or N m s/rad */
	int passivity;                 /* 1: passivity observer on */
};

/* The gains' defaults, each written once (the configuration's table takes
 * them); the scope's radius and wire spacing are scope.h's. */
#define HAPTICS_DEFAULT_MODEL HAPTICS_MODEL_ROD
#define HAPTICS_DEFAULT_WALL_STIFFNESS_N_PER_M 2000
#define HAPTICS_DEFAULT_WALL_DAMPING_N_S_PER_M 15
#define HAPTICS_DEFAULT_TIP_LATERAL_STIFFNESS_N_PER_M 150
#define HAPTICS_DEFAULT_FORCE_SHADING 1
#define HAPTICS_DEFAULT_CONTACT_REACH_M 0.1
#define HAPTICS_DEFAULT_ENTRY_DEPTH_M 0.02
#define HAPTICS_DEFAULT_FRICTION_N_S_PER_M_RAD 8
#define HAPTICS_DEFAULT_TORSION_N_M_S_PER_RAD2 0.02
#define HAPTICS_DEFAULT_WIRE_TENSION_N_M_PER_M 0.5
#define HAPTICS_DEFAULT_BENDING_STIFFNESS_N_M_PER_RAD 0.01
#define HAPTICS_DEFAULT_STOP_STIFFNESS_N_M_PER_RAD 0.5
#define HAPTICS_DEFAULT_STOP_DAMPING_N_M_S_PER_RAD 4e-3
#define HAPTICS_DEFAULT_WHEEL_DELAY_S 0.003
#define HAPTICS_DEFAULT_LOOP_RELAX_S 0.1
#define HAPTICS_DEFAULT_INSERTION_DAMPING_N_S_PER_M 0.5
#define HAPTICS_DEFAULT_ROLL_DAMPING_N_M_S_PER_RAD 1e-3
#define HAPTICS_DEFAULT_WHEEL_DAMPING_N_M_S_PER_RAD 2e-4
#define HAPTICS_DEFAULT_PASSIVITY 1

#define HAPTICS_GAINS_DEFAULT { \
	.model = HAPTICS_DEFAULT_MODEL, \
	.scope_radius_m = SCOPE_RADIUS_M, \
	.wall_stiffness_n_per_m = HAPTICS_DEFAULT_WALL_STIFFNESS_N_PER_M, \
	.wall_damping_n_s_per_m = HAPTICS_DEFAULT_WALL_DAMPING_N_S_PER_M, \
	.tip_lateral_stiffness_n_per_m = \
		HAPTICS_DEFAULT_TIP_LATERAL_STIFFNESS_N_PER_M, \
	.force_shading = HAPTICS_DEFAULT_FORCE_SHADING, \
	.contact_reach_m = HAPTICS_DEFAULT_CONTACT_REACH_M, \
	.entry_depth_m = HAPTICS_DEFAULT_ENTRY_DEPTH_M, \
	.friction_n_s_per_m_rad = HAPTICS_DEFAULT_FRICTION_N_S_PER_M_RAD, \
	.torsion_n_m_s_per_rad2 = HAPTICS_DEFAULT_TORSION_N_M_S_PER_RAD2, \
	.wire_spacing_m = SCOPE_WIRE_SPACING_M, \
	.wire_tension_n_m_per_m = HAPTICS_DEFAULT_WIRE_TENSION_N_M_PER_M, \
	.bending_stiffness_n_m_per_rad = \
		HAPTICS_DEFAULT_BENDING_STIFFNESS_N_M_PER_RAD, \
	.stop_stiffness_n_m_per_rad = \
		HAPTICS_DEFAULT_STOP_STIFFNESS_N_M_PER_RAD, \
	.stop_damping_n_m_s_per_rad = \
		HAPTICS_DEFAULT_STOP_DAMPING_N_M_S_PER_RAD, \
	.wheel_delay_s = HAPTICS_DEFAULT_WHEEL_DELAY_S, \
	.loop_relax_s = HAPTICS_DEFAULT_LOOP_RELAX_S, \
	.damping = { \
		[ENDOSIM_AXIS_INSERTION] = \
			HAPTICS_DEFAULT_INSERTION_DAMPING_N_S_PER_M, \
		[ENDOSIM_AXIS_ROLL] = \
			HAPTICS_DEFAULT_ROLL_DAMPING_N_M_S_PER_RAD, \
		[ENDOSIM_AXIS_WHEEL_UD] = \
			HAPTICS_DEFAULT_WHEEL_DAMPING_N_M_S_PER_RAD, \
		[ENDOSIM_AXIS_WHEEL_LR] = \
			HAPTICS_DEFAULT_WHEEL_DAMPING_N_M_S_PER_RAD }, \
	.passivity = HAPTICS_DEFAULT_PASSIVITY }

struct haptics;

/*
 * The model's gains ([haptics] in the configuration, every one with its
 * unit in `endosimd --print-config`), and what it needs of the scope and
 * the rig: the service fills it from the configuration (cases.h).
 */
struct haptics_params {
	struct haptics_gains gains;    /* [haptics] */
	double bending_length_m;       /* the scope's (scope_params) */
	double wheel_gain[2];          /* tip rad per wheel rad: ud, lr */
	double wheel_limit_rad[2];     /* largest tip bend: ud, lr */
	double wheel_max_n_m[2];       /* each wheel's torque limit */
	bool driven[ENDOSIM_AXES];     /* a drive behind a bus, not simulated */
	struct rodscope_params rod;    /* the rod model's ([rod]) */
	struct patient_params patient; /* the patient's body ([patient]) */
};

struct haptics_input {
	const struct haptics_params *params;
	struct colon *colon;           /* its mobile spans are bowed here */
	const struct scope_pose *pose; /* this cycle's kinematics */
	const double *position;        /* per axis: m or rad */
	const double *velocity;        /* per axis: m/s or rad/s */
	double dt_s;                   /* the loop's period */
	bool torque_on;                /* the forces reach the hand */
	const double *applied;         /* N, N m per axis: the setpoints the
					  drives held over the last period */
	uint32_t valves;               /* the handle's (enum endosim_valve) */
};

/*
 * The rendering of P's model (gains.model; P NULL: the paper's): the rod
 * model's tube sized as P->rod says (haptics_rod()). NULL on ENOMEM or a
 * rod that cannot be made.
 */
struct haptics *haptics_create(const struct haptics_params *p);

/* NULL is fine. */
void haptics_destroy(struct haptics *h);

/*
 * A new colon (or the first): the proxy starts free at the next tip, the
 * loops straight; measures each mobile segment's stored length per
 * amplitude (bows and unbows it); the rod model's tube is laid anew at the
 * next haptics_rod_pose(). Force loop (no allocation).
 */
void haptics_reset(struct haptics *h, struct colon *colon);

/*
 * The rod model's published state (endosim_shm.h) and each mobile span's
 * loop size in BOW_M (the scope state's); the paper's model zeroes OUT and
 * leaves BOW_M alone. Force loop, after haptics_render().
 */
void haptics_publish_rod(const struct haptics *h, double roll_rad,
			 struct endosim_rod_state *out,
			 double bow_m[ENDOSIM_SPANS]);

/* The rod model's tip held by a spring of HOLD_N_PER_M where it is, or
 * let go (0): rodscope_hold_tip(); nothing in the paper's model. */
void haptics_hold_tip(struct haptics *h, double hold_n_per_m);

/*
 * The patient's body (patient.h), which haptics_render() steps each cycle
 * before the model renders: its commands (patient_turn(), patient_press(),
 * patient_release()) are the force loop's to give; its state to publish
 * (patient_publish()). Force loop.
 */
struct patient *haptics_patient(struct haptics *h);

/* The rod model renders (else the paper's). */
bool haptics_rod(const struct haptics *h);

/*
 * The rod model's kinematics: the scope's pose as the tube lies now (the
 * last step's; rodscope_pose()) for the axes at POSITION (m, rad), their
 * VELOCITY; lays the tube anew first after haptics_reset() or when it is
 * no longer finite (the non-finite fault has then been latched on the
 * cycle that broke it). In place of scope_update(). Force loop.
 */
void haptics_rod_pose(struct haptics *h, const struct haptics_params *par,
		      const double *position, const double *velocity,
		      struct scope_pose *pose);

/*
 * One cycle: COMMAND (N, N m per axis) and the published parts in OUT
 * (their sum per axis is COMMAND); bows the colon's mobile segments to
 * this cycle's loops (the kinematics of the next cycle see them).
 */
void haptics_render(struct haptics *h, const struct haptics_input *in,
		    double command[ENDOSIM_AXES],
		    struct endosim_haptics_state *out);

#endif
