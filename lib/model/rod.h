/*
 * rod.h - an elastic rod that bends and twists (Cosserat, inextensible),
 * stepped implicitly at a haptic rate with a direct solver.
 *
 * The rod is a chain of N rigid segments of length l = L / N, each with
 * its centre p and a unit quaternion q: its material frame (d1, d2, d3) =
 * R(q) (e1, e2, e3), d3 along the segment, from the base (segment 0) to
 * the tip (segment N - 1). Neighbours meet at a joint:
 *   position, 3 rows: p_a + (l/2) d3_a - (p_b - (l/2) d3_b) = 0 (hard: the
 *     rod neither stretches nor shears);
 *   bending and twist, 3 rows: the joint's rotation
 *     theta = 2 Im(conj(q_a) q_b)   (rad, in segment a's frame; the
 *     discrete Darboux vector times l) less its rest value theta0, with the
 *     energy (1 / 2l) (theta - theta0)^T diag(EI, EI, GJ) (theta - theta0):
 *     theta_1, theta_2 bend about d1, d2, theta_3 twists. A rest bend by
 *     an angle a about a unit axis is theta0 = 2 sin(a / 2) axis
 *     (rod_rest_for_angle()); its conjugate force is the joint's moment,
 *     (EI / l) (theta - theta0) (N m).
 * Either end may be held by an anchor: a frame given each step (a rig's
 * carriage, a clamp) with a compliance and a damping per row (position in
 * the anchor's frame, then rotation), so that it is a clamp (0) or a
 * virtual coupling (a spring-damper whose force is the rod's reaction).
 *
 * Why this formulation: the force the trainee feels is a constraint force
 * at the rod's end after it has travelled through 160 stiff segments, so
 * the constraints must be solved, not relaxed: Gauss-Seidel (PBD, XPBD)
 * needs hundreds of sweeps on a long stiff rod before the end feels the
 * far end. The joints of a chain make a block-tridiagonal system (6x6
 * blocks, one per joint), which a block LDL^T solves exactly in O(N)
 * (Deul, Kugelstadt, Weiler, Bender, "Direct position-based solver for
 * stiff rods", CGF 2018): each step is an implicit Euler step of the
 * whole rod with the XPBD compliance form (Macklin, Mueller, Chentanez
 * 2016: compliance in SI units, the stiffness independent of the step),
 * and damping as a Kelvin-Voigt retardation time per row. The step's
 * first iteration linearises the joints where the segments are at its
 * start, with the loads' motion over the step in the solve (not made
 * first and linearised after: a torque on a light segment would turn it
 * by h^2 tau / I, far beyond the linearisation, before its joints held
 * it). A rod at rest in equilibrium is then left where it is, so statics
 * are exact when the rod comes to rest, whatever the step and the
 * segments' inertia (the analytic tests: cantilever, elastica, an end
 * couple's circle, Euler buckling, torsion, capstan, at 1 and 2 ms); a
 * fixed number of iterations keeps the work per step bounded: the force
 * loop can run it.
 *
 * Loads: before each step the caller may load any segment with a force
 * and a torque linear in its motion over the step,
 *   f = f0 - Kt dp - Bt (v - v_ref),  tau = tau0 - Kr dtheta - Br (w - w_ref)
 * with dp, dtheta the step's displacement (m, rad), v, w the new
 * velocities, every K and B symmetric and positive semi-definite
 * (rod_load_point() builds them for a spring and a damper at a point of
 * the segment: a wall's contact, a proxy's spring, friction; the coupling
 * of a point's offset between the two is dropped, which keeps each
 * segment's effective mass block-diagonal and the solve cheap). They are
 * integrated implicitly (the segment's effective mass M + h B + h^2 K), so
 * a stiff wall or a friction that sticks neither explodes nor lags.
 *
 * Units SI. rod_create() allocates; nothing else allocates, blocks or
 * prints: safe in the force loop. Cost per step ~O(N) (make bench). One
 * thread at a time.
 */
#ifndef ENDOSIM_ROD_H
#define ENDOSIM_ROD_H

#include <stdbool.h>
#include <stddef.h>

#include "model/scope.h"

#define ROD_MIN_SEGMENTS 2
#define ROD_MAX_SEGMENTS 1024

struct rod_params {
	int segments;            /* N, ROD_MIN_SEGMENTS..ROD_MAX_SEGMENTS */
	double length_m;         /* L */
	double radius_m;         /* outer radius (the inertia about d3) */
	double mass_per_m_kg;    /* linear density, kg/m */
	double bending_n_m2;     /* EI, N m^2 (every joint until set) */
	double torsion_n_m2;     /* GJ, N m^2 */
	double damping_s;        /* Kelvin-Voigt retardation time of the
				    bending and twist rows, s */
	double drag_n_s_per_m2;  /* viscous drag per length and speed */
	int iterations;          /* Newton iterations per step, 1..8 (the
				    system is factored once per step) */
};

/* A colonoscope's insertion tube (docs/ARCHITECTURE.md, SCOPE-MECHANICS):
 * 1.6 m in 160 segments, EI 0.03 N m^2, GJ 0.45 N m^2 (78 N cm^2/deg),
 * 0.2 kg/m. */
#define ROD_DEFAULT_SEGMENTS 160
#define ROD_DEFAULT_LENGTH_M 1.6
#define ROD_DEFAULT_MASS_PER_M_KG 0.2
#define ROD_DEFAULT_BENDING_N_M2 0.03
#define ROD_DEFAULT_TORSION_N_M2 0.45
#define ROD_DEFAULT_DAMPING_S 0.002
#define ROD_DEFAULT_DRAG_N_S_PER_M2 0.5
#define ROD_DEFAULT_ITERATIONS 2

#define ROD_PARAMS_DEFAULT { .segments = ROD_DEFAULT_SEGMENTS, \
			     .length_m = ROD_DEFAULT_LENGTH_M, \
			     .radius_m = SCOPE_RADIUS_M, \
			     .mass_per_m_kg = ROD_DEFAULT_MASS_PER_M_KG, \
			     .bending_n_m2 = ROD_DEFAULT_BENDING_N_M2, \
			     .torsion_n_m2 = ROD_DEFAULT_TORSION_N_M2, \
			     .damping_s = ROD_DEFAULT_DAMPING_S, \
			     .drag_n_s_per_m2 = ROD_DEFAULT_DRAG_N_S_PER_M2, \
			     .iterations = ROD_DEFAULT_ITERATIONS }

/* A segment's load, linear in its motion over the step (above). */
struct rod_load {
	double f[3], tau[3];    /* N, N m; world, about the segment's centre */
	double kt[3][3];        /* N/m: symmetric PSD */
	double kr[3][3];        /* N m/rad */
	double bt[3][3];        /* N s/m */
	double br[3][3];        /* N m s/rad */
	double btv[3], brw[3];  /* Bt v_ref, Br w_ref */
};

enum rod_end { ROD_BASE = 0, ROD_TIP = 1 };

/*
 * An end held by a frame: its point (the rod's end, p_0 - (l/2) d3 at the
 * base, p + (l/2) d3 at the tip) and orientation are pulled to P and Q
 * (w, x, y, z). Rows 0-2: the position error in the anchor's frame (m);
 * rows 3-5: the rotation error 2 Im(conj(Q) q) in the anchor's frame (rad).
 * compliance (m/N, rad/(N m)) 0 holds it; damping_s is the Kelvin-Voigt
 * time of each row (a coupling of stiffness k and damping b: b / k).
 */
struct rod_anchor {
	double p[3];
	double q[4];
	double compliance[6];
	double damping_s[6];
};

struct rod;

/* Checks P; 0, or -EINVAL with one line in ERR. */
int rod_params_check(const struct rod_params *p, char *err, size_t errsize);

/* A straight rod along +z from the origin, at rest. NULL on bad
 * parameters or ENOMEM. */
struct rod *rod_create(const struct rod_params *p);

/* NULL is fine. */
void rod_destroy(struct rod *r);

int rod_segments(const struct rod *r);
double rod_segment_length(const struct rod *r); /* l, m */
const struct rod_params *rod_params(const struct rod *r);

/*
 * Lays the rod at rest along the polyline ENDS of N + 1 points (the
 * segments' ends, base to tip, each l apart is best), the first
 * segment's d1 along D1 (made normal to it), the next frames carried
 * along without twist (parallel transport). Velocities and loads zero.
 */
void rod_lay(struct rod *r, const double (*ends)[3], const double d1[3]);

/* Joint J's (0..N-2, between segments J and J+1) rest rotation theta0
 * (rad, in segment J's frame) and stiffness (EI, GJ: N m^2). */
void rod_set_rest(struct rod *r, int joint, const double theta0[3]);
void rod_set_stiffness(struct rod *r, int joint, double ei_n_m2,
		       double gj_n_m2);

/* The rest rotation of a bend by ANGLE (rad) about the unit AXIS. */
void rod_rest_for_angle(double angle_rad, const double axis[3],
			double theta0[3]);

/*
 * A clamp's compliance (m/N, rad/(N m)): a rigid segment cannot bend, so a
 * clamp at the rod's end takes the half segment between the end and the
 * first joint: l / (2 EI) in bending, l / (2 GJ) in twist, none in
 * position. The cantilever's deflection is then exact to 1 / (2 N^2).
 */
void rod_clamp_compliance(const struct rod *r, double compliance[6]);

/* Holds END by A from the next step on; NULL lets it go. */
void rod_set_anchor(struct rod *r, enum rod_end end,
		    const struct rod_anchor *a);

/* The unit quaternion (w, x, y, z) of the frame with d3 along the unit T
 * and d1 along U (made normal to T): an anchor's, a laid rod's. */
void rod_frame_quat(const double t[3], const double u[3], double q[4]);

/* Zeroes every load set since the last clear. */
void rod_clear_loads(struct rod *r);

/* Segment I's load for the next step (zeroed by rod_clear_loads()). */
struct rod_load *rod_load(struct rod *r, int i);

/*
 * Adds to L a force at the point OFF (m, world, from the segment's
 * centre): F (N), a spring K (N/m, 3x3 symmetric PSD, may be NULL) on
 * the point's displacement, and a damper B (N s/m, may be NULL) on its
 * velocity relative to V_REF (m/s, may be NULL: at rest). The point's
 * offset gives the torque OFF x F, and the spring and damper their
 * rotational parts [off]x^T K [off]x (the cross terms are dropped).
 */
void rod_load_point(struct rod_load *l, const double off[3],
		    const double f[3], const double k[3][3],
		    const double b[3][3], const double v_ref[3]);

/* One implicit step of DT_S seconds (> 0). */
void rod_step(struct rod *r, double dt_s);

/* Segment I: centre (m), orientation (w, x, y, z), velocity (m/s) and
 * angular velocity (rad/s, world). */
const double *rod_centre(const struct rod *r, int i);
const double *rod_quat(const struct rod *r, int i);
const double *rod_velocity(const struct rod *r, int i);
const double *rod_spin(const struct rod *r, int i);

/* Segment I's material frame. */
void rod_frame(const struct rod *r, int i, double d1[3], double d2[3],
	       double d3[3]);

/* The end point of segment I at its base (END = ROD_BASE) or tip side. */
void rod_end_point(const struct rod *r, int i, enum rod_end end,
		   double out[3]);

/*
 * The wrench the anchor at END exerted on the rod over the last step:
 * force F (N) and torque TAU (N m, about the rod's end point), world.
 * Zero when END is free.
 */
void rod_anchor_wrench(const struct rod *r, enum rod_end end, double f[3],
		       double tau[3]);

/* Joint J's rotation theta now (rad, segment J's frame). */
void rod_joint_rotation(const struct rod *r, int joint, double theta[3]);

/*
 * Joint J's moment over the last step (N m, segment J's frame): what the
 * rod's elasticity and damping hold against its bend and twist beyond
 * rest, (EI / l) (theta - theta0) at rest; the derivative of the rod's
 * energy with respect to theta0 is its negative.
 */
void rod_joint_moment(const struct rod *r, int joint, double m[3]);

/* The largest gap between neighbours' ends now (m): how far the solve left
 * the joints from closed (a check: the tube neither stretches nor
 * shears). */
double rod_joint_gap(const struct rod *r);

/* Every position and orientation finite. */
bool rod_finite(const struct rod *r);

/* Kinetic energy (J), for tests. */
double rod_kinetic_energy(const struct rod *r);

#endif
