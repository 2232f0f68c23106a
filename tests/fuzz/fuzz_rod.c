/*
 * fuzz_rod - libFuzzer target: the rod model's step with random inputs and
 * parameters (issue 14: any hand input, case or parameter within its range
 * leaves the rod finite, or its non-finite state is reported, never a
 * crash or undefined behaviour).
 *
 * The input's bytes, read as a stream of numbers each mapped into its
 * key's range: the tube's parameters (segments 8..40 to keep an input
 * quick, length, EI, GJ, the bending section's EI, damping, drag, mass,
 * iterations), the wall's and the colon's (stiffness, damping, friction,
 * slip speed, the couplings, node spacing), then up to 60 steps, each the
 * rig's four axes (position and speed, anywhere in and beyond their
 * travel) and the tip's contact (on or off, a force up to 200 N, a
 * spring up to 1e5 N/m and a damper). The colon: a case built in code
 * once (a bent, mobile sigmoid and transverse colon, residual fluid in
 * the sigmoid and the cecum, the assistant's sites over the middle of
 * each mobile segment).
 *
 * The patient (issue 22) around it, as the haptics drive it: after the
 * tube's parameters, the patient's (each key's [patient] range: the
 * flows, the leak, absorption, relief, wall strength, hydrostatic
 * pressure, the fluid's, the hand's, the lens', air or CO2); each step
 * the handle's valves, now and then a turn to any position, a press at
 * any site with any force (refused ones included) or a release, then the
 * patient's step from the tip as the rod lies, its gravity, radius
 * factors and pad on the rod and the colon. The body must stay finite
 * while the rod does (its parameters within their keys' ranges), and the
 * pad never holds the colon with more than the hand's force.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/anatomy.h"
#include "model/colon.h"
#include "model/patient.h"
#include "plain_anatomy.h"
#include "model/rodscope.h"
#include "base/vec3.h"

struct bytes {
	const uint8_t *p;
	size_t n;
};

/* The next 16 bits as a number in [LO, HI] (LO once the input is over). */
static double take(struct bytes *b, double lo, double hi)
{
	unsigned v = 0;

	for (int i = 0; i < 2 && b->n; i++, b->p++, b->n--) {
		v = v << 8 | *b->p;
	}
	return lo + (hi - lo) * v / 65535.0;
}

/* A site 3 cm in front of the middle of COLON's segment I, pressing
 * towards the back. */
static void site_over(const struct colon *colon, int i, const char *name,
		      struct anatomy_site *t)
{
	const struct centreline *cl = colon_centreline(colon);
	const struct colon_region *r = colon_region(colon, i);
	size_t k = (size_t)((r->s0_m + r->s1_m) / 2 / centreline_step(cl));
	const double *p = centreline_sample(cl, k)->p;

	snprintf(t->name, sizeof(t->name), "%s", name);
	t->position_m[0] = p[0];
	t->position_m[1] = p[1] - 0.03;
	t->position_m[2] = p[2];
	t->direction[1] = 1;
	t->radius_m = 0.06;
}

static struct colon *test_colon(void)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	struct anatomy a;
	struct colon *c;
	char err[256];

	plain_anatomy(&a, 0.05);
	a.seg[2].bend[0] = (struct anatomy_bend){ .angle_rad = 2.5,
						   .radius_m = 0.05 };
	a.seg[2].bends = 1;
	a.seg[4].bend[0] = (struct anatomy_bend){ .angle_rad = 2.3,
						   .radius_m = 0.03,
						   .plane_rad = 1.0 };
	a.seg[4].bends = 1;
	for (int i = 2; i <= 5; i += 3) {
		a.seg[i].mobile = true;
		a.seg[i].mesentery_n_per_m = 600;
		a.seg[i].mesentery_height_m = 0.06;
	}
	a.seg[ANATOMY_SIGMOID].fluid_m3 = 1e-4;
	a.seg[ANATOMY_CECUM].fluid_m3 = 3e-5;
	p.ring_vertices = 32;
	c = colon_create(&a, &p, err, sizeof(err));
	if (!c) {
		return NULL;
	}
	site_over(c, ANATOMY_SIGMOID, "llq", &a.site[0]);
	site_over(c, ANATOMY_TRANSVERSE, "umbilical", &a.site[1]);
	a.sites = 2;
	colon_destroy(c);
	return colon_create(&a, &p, err, sizeof(err));
}

/* The patient's parameters, each within its [patient] key's range. */
static void patient_params(struct bytes *b, struct patient_params *p)
{
	*p = (struct patient_params)PATIENT_PARAMS_DEFAULT;
	p->enabled = true;
	p->gas.kind = take(b, 0, 1) > 0.5 ? GAS_CO2 : GAS_AIR;
	p->gas.pump_m3_per_s = take(b, 0, 1e-3);
	p->gas.suction_m3_per_s = take(b, 0, 1e-3);
	p->gas.leak_pa = take(b, 0, 2e4);
	p->gas.leak_m3_per_s_pa = take(b, 0, 1e-5);
	p->gas.absorb_air_per_s = take(b, 0, 1);
	p->gas.absorb_co2_per_s = take(b, 0, 1);
	p->gas.relief_pa = take(b, 0, 1e5);
	p->gas.wall_strength_n_per_m = take(b, 10, 1e5);
	p->gas.hydrostatic_pa_per_m = take(b, 0, 1e5);
	p->fluid.suction_m3_per_s = take(b, 0, 1e-3);
	p->fluid.settle_s = take(b, 0, 10);
	p->start_position = (int)take(b, 0, 3.99);
	p->turn_s = take(b, 0, 60);
	p->hand_max_n = take(b, 1, 100);
	p->hand_n = take(b, 1, p->hand_max_n);
	p->abdomen_n_per_m = take(b, 10, 1e5);
	p->lens.contact_n = take(b, 0, 50);
	p->lens.smear_n_s = take(b, 0.01, 1000);
	p->lens.dip_s = take(b, 0.01, 100);
	p->lens.wash_s = take(b, 0.01, 100);
	p->lens.redout_gap_m = take(b, 0, 0.05);
	p->lens.redout_s = take(b, 0.001, 10);
}

/* This step's commands to the patient: the valves held, now and then a
 * turn, a press or a release (any position, site and force). */
static void patient_commands(struct bytes *b, struct patient *pt,
			     uint32_t *valves)
{
	int what = (int)take(b, 0, 15.99);

	*valves = (uint32_t)take(b, 0, 7.99);
	if (what == 0) {
		patient_turn(pt, (int)take(b, -1, 4.99));
	} else if (what == 1) {
		patient_press(pt, (int)take(b, -1, 2.99), take(b, -10, 150));
	} else if (what == 2) {
		patient_release(pt);
	}
}

/* The patient's step from the tube as it lies and the tip's contact T
 * (its gap to the wall GAP_M), as the haptics take it; its gravity,
 * factors and pad on the tube and the colon. */
static void patient_cycle(struct patient *pt, struct rodscope *rs,
			  const struct scope_pose *pose,
			  const struct rodscope_tip *t, double gap_m,
			  uint32_t valves, double dt_s)
{
	struct patient_input in = {
		.valves = valves, .tip_s_m = pose->tip_s_m,
		.tip_force_n = t->on ? sqrt(t->force[0] * t->force[0] +
					    t->force[1] * t->force[1] +
					    t->force[2] * t->force[2]) : 0,
		.wall_gap_m = gap_m,
	};
	struct flex_pad pad;
	double g[3];

	memcpy(in.tip, pose->tip, sizeof(in.tip));
	patient_step(pt, &in, dt_s);
	patient_gravity(pt, g);
	patient_pad(pt, &pad);
	rodscope_set_patient(rs, pt->factor, g, &pad);
}

static void params(struct bytes *b, struct rodscope_params *p)
{
	*p = (struct rodscope_params)RODSCOPE_PARAMS_DEFAULT;
	p->rod.segments = (int)take(b, 8, 40);
	p->rod.length_m = take(b, 0.5, 3);
	p->rod.bending_n_m2 = take(b, 1e-4, 10);
	p->rod.torsion_n_m2 = take(b, 1e-4, 100);
	p->rod.mass_per_m_kg = take(b, 0.01, 10);
	p->rod.damping_s = take(b, 0, 1);
	p->rod.drag_n_s_per_m2 = take(b, 0, 1000);
	p->rod.iterations = (int)take(b, 2, 3);
	p->tip_bending_n_m2 = take(b, 1e-4, 10);
	p->bending_length_m = take(b, 0.01, 0.3);
	p->lumen.wall_n_per_m2 = take(b, 1e3, 1e7);
	p->lumen.wall_damping_s = take(b, 0, 1);
	p->lumen.friction = take(b, 0, 2);
	p->lumen.slip_m_per_s = take(b, 1e-5, 1);
	p->lumen.pipe_n_per_m2 = take(b, 1e3, 1e8);
	p->flex.node_spacing_m = take(b, 0.005, 0.2);
	p->flex.damping_n_s_per_m = take(b, 0.1, 1e5);
	p->flex.chain_n_per_m = take(b, 0, 1e5);
	p->flex.bending_n_per_m = take(b, 0, 1e6);
	p->coupling_n_per_m = take(b, 10, 1e6);
	p->coupling_n_s_per_m = take(b, 0, 1e4);
	p->roll_n_m_per_rad = take(b, 0.01, 1e3);
	p->roll_n_m_s_per_rad = take(b, 0, 10);
	p->stop_n_per_m = take(b, 0, 1e6);
}

static void axes(struct bytes *b, struct rodscope_axes *a)
{
	a->depth_m = take(b, -1, 3);
	a->depth_m_s = take(b, -3, 3);
	a->roll_rad = take(b, -100, 100);
	a->roll_rad_s = take(b, -30, 30);
	for (int w = 0; w < 2; w++) {
		a->bend_rad[w] = take(b, -M_PI, M_PI);
		a->dbend_dwheel[w] = take(b, 0, 20);
	}
}

static void tip(struct bytes *b, struct rodscope_tip *t)
{
	memset(t, 0, sizeof(*t));
	t->on = take(b, 0, 1) > 0.5;
	for (int i = 0; i < 3; i++) {
		t->force[i] = take(b, -200, 200);
		t->k[i][i] = take(b, 0, 1e5);   /* diagonal: PSD */
		t->b[i][i] = take(b, 0, 1e3);
	}
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct colon *colon;
	static struct patient pt;
	struct bytes b = { data, size };
	struct rodscope_params p;
	struct patient_params pp;
	struct rodscope_axes a;
	struct rodscope_tip t;
	struct rodscope_out out;
	struct scope_pose pose;
	struct endosim_rod_state pub;
	struct endosim_patient_state ppub;
	double tip_v[3], bows[ENDOSIM_SPANS], dt;
	struct rodscope *rs;
	uint32_t valves;

	if (!colon && !(colon = test_colon())) {
		abort(); /* a fixed case that must build */
	}
	params(&b, &p);
	rs = rodscope_create(&p);
	if (!rs) {
		return 0;
	}
	patient_params(&b, &pp);
	patient_init(&pt, &pp);
	patient_attach(&pt, colon);
	axes(&b, &a);
	rodscope_reset(rs, colon, &a);
	for (int step = 0; step < 60 && b.n; step++) {
		axes(&b, &a);
		tip(&b, &t);
		patient_commands(&b, &pt, &valves);
		if (step == 20) {
			rodscope_hold_tip(rs, take(&b, 0, 1e4));
		}
		dt = take(&b, 1e-4, 2e-3);
		rodscope_pose(rs, &a, &pose, tip_v);
		patient_cycle(&pt, rs, &pose, &t, take(&b, 0, 0.02), valves,
			      dt);
		rodscope_step(rs, &a, &t, dt, &out);
		pt.pad_n = rodscope_pad_force(rs);
		if (!rodscope_finite(rs)) {
			break; /* the loop's non-finite fault would latch */
		}
		if (!patient_finite(&pt)) {
			abort(); /* within its keys' ranges the body is */
		}
		if (!(pt.pad_n <= pt.hand_n * (1 + 1e-9))) {
			abort(); /* the hand holds more than it presses with */
		}
	}
	patient_publish(&pt, &ppub);
	memset(&pub, 0, sizeof(pub));
	rodscope_publish(rs, a.roll_rad, &out.wall, &pub, bows);
	rodscope_destroy(rs);
	return 0;
}
