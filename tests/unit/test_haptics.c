/*
 * test_haptics.c - the haptic rendering against analytic cases:
 *  - friction: a straight tube gives 0, an arc of angle Theta gives
 *    c_f v Theta (1%), the sign follows v;
 *  - wire tension: a planar bend Theta in a wire's plane gives dr Theta
 *    (1%), an S-curve ~0, a bend across a wire ~0, a roll of 90 deg swaps
 *    the wheels;
 *  - contact torques by the Jacobian equal the paper's n . F_static
 *    projection ((Lb/2) n . F per rad of bend) with a straight tip;
 *  - loops: with the tip held, pushing grows the loop while the tip stays,
 *    the axial force rises monotonically, and withdrawing straightens it;
 *  - stability: pressing and holding against the wall puts no energy into
 *    the hand, and where a stiff wall sampled at 1 kHz would (no damping),
 *    the passivity observer keeps it bounded.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "anatomy.h"
#include "colon.h"
#include "config.h"
#include "haptics.h"
#include "plant.h"
#include "scope.h"
#include "vec3.h"

#define DT 0.001

/* ------------------------------------------------------------ fixtures */

struct world {
	double applied[ENDOSIM_AXES]; /* what the "drive" held last period */
	struct config cfg;
	struct colon *colon;
	struct haptics *h;
	struct scope_pose pose;
	struct rig_feedback fb;
	struct endosim_haptics_state out;
	double cmd[ENDOSIM_AXES];
};

/* A round colon, 5 cm wide, nine segments, no folds, nothing mobile. */
static void smooth_anatomy(struct anatomy *a)
{
	static const double len[ANATOMY_SEGMENTS] = {
		0.04, 0.12, 0.37, 0.15, 0.07, 0.45, 0.06, 0.20, 0.06,
	};

	memset(a, 0, sizeof(*a));
	snprintf(a->name, sizeof(a->name), "test");
	a->fold_spacing_m = 0.03;
	a->fold_width_m = 0.005;
	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		a->seg[i].length_m = len[i];
		a->seg[i].diameter_m = 0.05;
	}
}

static void add_bend(struct anatomy *a, int seg, double deg, double radius,
		     double plane_deg)
{
	struct anatomy_segment *s = &a->seg[seg];

	s->bend[s->bends++] = (struct anatomy_bend){
		.angle_rad = deg * M_PI / 180, .radius_m = radius,
		.plane_rad = plane_deg * M_PI / 180,
	};
}

static void world_init(struct world *w, const struct anatomy *a)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	char err[256];

	memset(w, 0, sizeof(*w));
	config_defaults(&w->cfg);
	/* the physics alone: no virtual damping of the axes */
	memset(w->cfg.haptics.damping, 0, sizeof(w->cfg.haptics.damping));
	p.ring_vertices = 96;
	w->colon = colon_create(a, &p, err, sizeof(err));
	assert_non_null(w->colon);
	w->h = haptics_create();
	assert_non_null(w->h);
	haptics_reset(w->h, w->colon);
}

static void world_free(struct world *w)
{
	haptics_destroy(w->h);
	colon_destroy(w->colon);
}

/* One cycle at the axes' positions Q and velocities QD. */
static void step(struct world *w, const double q[ENDOSIM_AXES],
		 const double qd[ENDOSIM_AXES])
{
	const struct scope_params sp = {
		.bending_length_m = w->cfg.scope.bending_length_m,
		.ud_gain = w->cfg.scope.gain[0],
		.lr_gain = w->cfg.scope.gain[1],
		.ud_limit_rad = w->cfg.scope.limit_rad[0],
		.lr_limit_rad = w->cfg.scope.limit_rad[1],
	};
	const struct scope_input in = { q[0], q[1], q[2], q[3] };
	const struct haptics_input hi = {
		.cfg = &w->cfg, .colon = w->colon, .pose = &w->pose,
		.fb = &w->fb, .dt_s = DT, .torque_on = true,
		.applied = w->applied,
	};

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		w->fb.axis[a].position = q[a];
		w->fb.axis[a].velocity = qd[a];
	}
	scope_update(&sp, colon_centreline(w->colon), &in, &w->pose);
	haptics_render(w->h, &hi, w->cmd, &w->out);
}

/* The roll that turns the up/down wire's direction into the plane of the
 * colon's bend at material S (its curvature vector in the frame). */
static double roll_into_bend(const struct world *w, double s)
{
	struct centreline_point q;

	centreline_at_s(colon_centreline(w->colon), s, &q);
	return atan2(vec3_dot(q.k, q.v), vec3_dot(q.k, q.u));
}

/* ------------------------------------------------------------ friction */

static void test_friction_straight_is_zero(void **state)
{
	const double q[4] = { 0.8, 0, 0, 0 }, qd[4] = { 0.05, 0, 0, 0 };
	struct anatomy a;
	struct world w;

	(void)state;
	smooth_anatomy(&a);
	world_init(&w, &a);
	step(&w, q, qd);
	assert_false(w.out.contact);
	assert_float_equal(w.out.curvature_rad, 0, 1e-9);
	assert_float_equal(w.out.trans_friction_n, 0, 1e-9);
	assert_float_equal(w.out.tube_friction_nm, 0, 1e-9);
	world_free(&w);
}

static void test_friction_arc(void **state)
{
	const double theta = M_PI / 2, v = 0.05;
	double q[4] = { 0.8, 0, 0, 0 }, qd[4] = { v, 0, 0, 0 };
	struct anatomy a;
	struct world w;
	double want;

	(void)state;
	smooth_anatomy(&a);
	add_bend(&a, ANATOMY_DESCENDING, 90, 0.06, 0);
	world_init(&w, &a);
	step(&w, q, qd);
	assert_false(w.out.contact);
	want = -w.cfg.haptics.friction_n_s_per_m_rad * v * theta;
	assert_float_equal(w.out.curvature_rad, theta, 0.01 * theta);
	assert_float_equal(w.out.trans_friction_n, want, 0.01 * fabs(want));
	assert_float_equal(w.cmd[ENDOSIM_AXIS_INSERTION], want,
			   0.01 * fabs(want));
	qd[0] = -v;
	step(&w, q, qd);
	assert_float_equal(w.out.trans_friction_n, -want, 0.01 * fabs(want));
	/* torsion: the same integral, the roll velocity */
	qd[0] = 0;
	qd[1] = 2;
	step(&w, q, qd);
	assert_float_equal(w.out.tube_friction_nm,
			   -w.cfg.haptics.torsion_n_m_s_per_rad2 * 2 * theta,
			   0.01 * w.cfg.haptics.torsion_n_m_s_per_rad2 * 2 *
				   theta);
	world_free(&w);
}

/* ------------------------------------------------------------ tension */

static void test_tension_planar_bend(void **state)
{
	const double theta = M_PI / 2, zero[4] = { 0 };
	struct anatomy a;
	struct world w;
	double q[4] = { 0.8, 0, 0, 0 }, dr, roll;

	(void)state;
	smooth_anatomy(&a);
	add_bend(&a, ANATOMY_DESCENDING, 90, 0.06, 0);
	world_init(&w, &a);
	dr = w.cfg.haptics.wire_spacing_m;
	roll = roll_into_bend(&w, 0.53 + 0.075);
	/* the bend in the up/down wire's plane */
	q[1] = roll;
	step(&w, q, zero);
	assert_float_equal(fabs(w.out.wire_dl_m[0]), dr * theta,
			   0.01 * dr * theta);
	assert_true(fabs(w.out.wire_dl_m[1]) < 0.01 * dr * theta);
	assert_float_equal(w.out.wheel_tension_nm[0],
			   w.cfg.haptics.wire_tension_n_m_per_m *
				   w.out.wire_dl_m[0], 1e-12);
	/* a quarter turn of the tube: the left/right wire has it, the
	 * up/down wire lies across the bend and has none */
	q[1] = roll + M_PI / 2;
	step(&w, q, zero);
	assert_float_equal(fabs(w.out.wire_dl_m[1]), dr * theta,
			   0.01 * dr * theta);
	assert_true(fabs(w.out.wire_dl_m[0]) < 0.01 * dr * theta);
	world_free(&w);
}

static void test_tension_s_curve_cancels(void **state)
{
	const double theta = M_PI / 3, zero[4] = { 0 };
	struct anatomy a;
	struct world w;
	double q[4] = { 0.8, 0, 0, 0 }, dr;

	(void)state;
	smooth_anatomy(&a);
	add_bend(&a, ANATOMY_DESCENDING, 60, 0.06, 0);
	add_bend(&a, ANATOMY_DESCENDING, 60, 0.06, 180);
	world_init(&w, &a);
	dr = w.cfg.haptics.wire_spacing_m;
	for (double roll = 0; roll < 2 * M_PI; roll += M_PI / 8) {
		q[1] = roll;
		step(&w, q, zero);
		assert_true(fabs(w.out.wire_dl_m[0]) < 0.02 * dr * theta);
		assert_true(fabs(w.out.wire_dl_m[1]) < 0.02 * dr * theta);
	}
	/* while the tube has turned through both bends */
	assert_float_equal(w.out.curvature_rad, 2 * theta, 0.02 * theta);
	world_free(&w);
}

/* ------------------------------------------------------------ contact */

/* With a straight tip the wheels' contact torques are the paper's
 * projection: the bending direction of each wheel dotted with F_static,
 * times Lb/2 (d tip / d bend at zero bend) and the wheel's gain. */
static void test_contact_torque_is_projection(void **state)
{
	const double zero[4] = { 0 };
	struct anatomy a;
	struct world w;
	double q[4] = { 0.5, 0.3, 0, 0 }, right[3], lb;
	int touched = 0;

	(void)state;
	smooth_anatomy(&a);
	add_bend(&a, ANATOMY_DESCENDING, 90, 0.06, 0);
	world_init(&w, &a);
	lb = w.cfg.scope.bending_length_m;
	for (; q[0] < 0.7 && touched < 20; q[0] += 0.0005) {
		step(&w, q, zero);
		if (!w.out.contact) {
			continue;
		}
		touched++;
		vec3_cross(right, w.pose.dir, w.pose.up);
		double ud = w.cfg.scope.gain[0] * lb / 2 *
			    vec3_dot(w.pose.up, w.out.f_static);
		double lr = w.cfg.scope.gain[1] * lb / 2 *
			    vec3_dot(right, w.out.f_static);
		double tol = 1e-6 + 0.01 * hypot(ud, lr);

		assert_float_equal(w.out.wheel_contact_nm[0], ud, tol);
		assert_float_equal(w.out.wheel_contact_nm[1], lr, tol);
		/* and the carriage feels the force's axial part */
		assert_float_equal(w.out.trans_contact_n,
				   vec3_dot(w.pose.dir, w.out.f_static),
				   1e-6 + 0.01 * vec3_norm(w.out.f_static));
	}
	assert_int_equal(touched, 20);
	world_free(&w);
}

/* Pushing into the wall head-on (the cecum's end, along the colon):
 * F_static = k_wall * depth along the normal, however many planes hold the
 * proxy (the cap's pole is a vertex). */
static void test_head_on_is_k_delta(void **state)
{
	const double zero[4] = { 0 };
	double q[4] = { 1.40, 0, 0, 0 };
	struct anatomy a;
	struct world w;
	int checked = 0;

	(void)state;
	smooth_anatomy(&a);
	world_init(&w, &a);
	w.cfg.haptics.wall_damping_n_s_per_m = 0;
	for (; q[0] < 1.6; q[0] += 0.0005) {
		step(&w, q, zero);
		if (!w.out.contact || w.out.penetration_m < 0.002) {
			continue;
		}
		double f = vec3_norm(w.out.f_static);
		double along = vec3_dot(w.out.f_static, w.out.normal);

		/* the cecum's dome, hit along the colon's axis */
		assert_true(fabs(vec3_dot(w.pose.dir, w.out.normal)) > 0.99);
		assert_float_equal(along, w.cfg.haptics.wall_stiffness_n_per_m *
				   w.out.penetration_m, 0.02 * along);
		assert_true(along > 0.99 * f);
		checked++;
	}
	assert_true(checked > 10);
	world_free(&w);
}

/* ------------------------------------------------------------ loops */

static void settle(struct world *w, const double q[4], int cycles)
{
	const double zero[4] = { 0 };

	for (int i = 0; i < cycles; i++) {
		step(w, q, zero);
	}
}

/*
 * A straight colon with a mobile transverse, the tip pushed head-on into
 * the cecum: the tip is held, the transverse behind it bows; its amplitude
 * grows while the tip's place along the colon stays, the force on the
 * carriage rises monotonically, and withdrawing straightens the loop.
 */
static void test_loop_grows_and_returns(void **state)
{
	struct anatomy a;
	struct world w;
	struct centreline *cl;
	double q[4] = { 1.46, 0, 0, 0 }, tip0 = 0, last_bow = 0, last_f = 0;
	double f0 = 0;
	bool looping = false;

	(void)state;
	smooth_anatomy(&a);
	a.seg[ANATOMY_TRANSVERSE].mobile = true;
	a.seg[ANATOMY_TRANSVERSE].mesentery_n_per_m = 500;
	a.seg[ANATOMY_TRANSVERSE].mesentery_height_m = 0.07;
	world_init(&w, &a);
	cl = colon_centreline(w.colon);
	for (; q[0] <= 1.62; q[0] += 0.002) {
		settle(&w, q, 300);
		double bow = centreline_bow_amplitude(cl, 0);
		double f = -w.cmd[ENDOSIM_AXIS_INSERTION];

		if (!looping && bow > 0.002) {
			looping = true;
			tip0 = w.pose.tip_s_m;
			last_bow = bow;
			f0 = last_f = f;
			continue;
		}
		if (looping) {
			assert_true(bow >= last_bow - 1e-5);
			assert_true(f >= last_f - 1e-3);
			assert_float_equal(w.pose.tip_s_m, tip0, 0.005);
			assert_true(w.out.trans_loop_n < 0);
			last_bow = bow;
			last_f = f;
		}
	}
	assert_true(looping);
	printf("loop: %.1f mm at the end, carriage force %.1f N (from %.1f N), "
	       "tip at %.3f m (from %.3f m)\n", last_bow * 1e3, last_f, f0,
	       w.pose.tip_s_m, tip0);
	assert_true(last_bow > 0.03);
	assert_true(last_f > 1.5 * f0);
	for (; q[0] >= 1.40; q[0] -= 0.002) {
		settle(&w, q, 300);
	}
	assert_true(centreline_bow_amplitude(cl, 0) < 0.001);
	world_free(&w);
}

/* ------------------------------------------------------------ stability */

/* The insertion axis as a plant pushed by a hand against the cecum, from
 * just before the wall: the work the wall does on the hand's side over the
 * press and the hold (the force held over each period times the way the
 * carriage went meanwhile, exactly). */
struct press {
	double work_max;  /* J: most energy the wall ever gave back */
	double speed_end; /* m/s: largest speed in the last 0.5 s */
	double force_end; /* N: the wall's push at the end */
};

#define WALL_M 1.513 /* the smooth colon's cecum, less the tip's radius */

static void press_and_hold(struct world *w, double mass_kg, double hand_n,
			   struct press *r)
{
	const struct plant_params pp = {
		.inertia = mass_kg, .min = 0, .max = 1.8,
	};
	double q[4] = { 0 }, qd[4] = { 0 }, work = 0;
	struct plant pl;

	plant_init(&pl, &pp, WALL_M);
	memset(r, 0, sizeof(*r));
	for (int i = 0; i < 3000; i++) {
		double f;

		q[0] = pl.x;
		qd[0] = pl.v;
		step(w, q, qd);
		f = fmin(fmax(w->cmd[0], -w->cfg.limits.max[0]),
			 w->cfg.limits.max[0]);
		w->applied[0] = f;
		double x0 = pl.x;

		plant_step(&pl, hand_n + f, DT);
		work += f * (pl.x - x0);
		r->work_max = fmax(r->work_max, work);
		if (i >= 2500) {
			r->speed_end = fmax(r->speed_end, fabs(pl.v));
		}
		r->force_end = -f;
	}
}

static void test_press_and_hold_is_passive(void **state)
{
	struct anatomy a;
	struct world w;
	struct press r;

	(void)state;
	smooth_anatomy(&a);
	for (int po = 0; po <= 1; po++) {
		world_init(&w, &a);
		w.cfg.haptics.passivity = po;
		press_and_hold(&w, 0.5, 15, &r);
		printf("press 15 N, passivity %s: wall gave back at most %.4f "
		       "J, end speed %.5f m/s, wall force %.2f N\n",
		       po ? "on" : "off", r.work_max, r.speed_end,
		       r.force_end);
		assert_true(r.work_max < 0.005);
		assert_true(r.speed_end < 0.001);
		assert_float_equal(r.force_end, 15, 0.5);
		world_free(&w);
	}
}

/*
 * Without its damping a wall sampled at 1 kHz gives out energy it never
 * took in (each period the drive holds the force of the deeper position
 * it was computed at): the carriage is pumped harder at every bounce. The
 * passivity observer sees it and damps exactly that much: the wall then
 * gives back no more than it took. Both at the default stiffness and at
 * ten times it on a lighter carriage.
 */
static void active_wall(double k, double mass_kg, double hand_n)
{
	struct press off, on;
	struct anatomy a;
	struct world w;

	smooth_anatomy(&a);
	for (int po = 0; po <= 1; po++) {
		world_init(&w, &a);
		w.cfg.haptics.wall_stiffness_n_per_m = k;
		w.cfg.haptics.wall_damping_n_s_per_m = 0;
		w.cfg.haptics.passivity = po;
		press_and_hold(&w, mass_kg, hand_n, po ? &on : &off);
		world_free(&w);
	}
	printf("undamped wall %g N/m, %g kg: without the observer %.3f J "
	       "given back, end speed %.2f m/s; with it %.4f J, %.2f m/s\n",
	       k, mass_kg, off.work_max, off.speed_end, on.work_max,
	       on.speed_end);
	assert_true(off.work_max > 0.5);
	assert_true(on.work_max < 0.05);
	assert_true(on.speed_end < off.speed_end / 2);
}

static void test_passivity_observer_bounds_active_wall(void **state)
{
	(void)state;
	active_wall(2000, 0.5, 15);
	active_wall(20000, 0.1, 10);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_friction_straight_is_zero),
		cmocka_unit_test(test_friction_arc),
		cmocka_unit_test(test_tension_planar_bend),
		cmocka_unit_test(test_tension_s_curve_cancels),
		cmocka_unit_test(test_contact_torque_is_projection),
		cmocka_unit_test(test_head_on_is_k_delta),
		cmocka_unit_test(test_loop_grows_and_returns),
		cmocka_unit_test(test_press_and_hold_is_passive),
		cmocka_unit_test(test_passivity_observer_bounds_active_wall),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
