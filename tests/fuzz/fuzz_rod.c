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
 * spring up to 1e5 N/m and a damper); from step 10 on the patient
 * around it: gravity up to 20 m/s^2 and the assistant's pad anywhere
 * near the colon, pressing any way with up to 60 N over a reach up to
 * 20 cm (the pad never holds the colon with more than its force: abort
 * if it does). The colon: a case built in code once (a bent, mobile
 * sigmoid and transverse colon).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/anatomy.h"
#include "model/colon.h"
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

static struct colon *test_colon(void)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	struct anatomy a;
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
	p.ring_vertices = 32;
	return colon_create(&a, &p, err, sizeof(err));
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

/* Gravity and the assistant's pad, anywhere about the colon. */
static void patient(struct bytes *b, double g[3], struct flex_pad *pad)
{
	memset(pad, 0, sizeof(*pad));
	for (int i = 0; i < 3; i++) {
		g[i] = take(b, -20, 20);
		pad->point[i] = take(b, -0.3, 0.6);
		pad->in[i] = take(b, -1, 1);
	}
	pad->on = vec3_norm(pad->in) > 1e-3;
	if (pad->on) {
		vec3_scale(pad->in, pad->in, 1 / vec3_norm(pad->in));
	}
	pad->radius_m = take(b, 0, 0.2);
	pad->force_n = take(b, 0, 60);
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
	struct bytes b = { data, size };
	struct rodscope_params p;
	struct rodscope_axes a;
	struct rodscope_tip t;
	struct rodscope_out out;
	struct scope_pose pose;
	struct endosim_rod_state pub;
	double tip_v[3], bows[ENDOSIM_SPANS], g[3];
	struct flex_pad pad = { .on = false };
	struct rodscope *rs;

	if (!colon && !(colon = test_colon())) {
		abort(); /* a fixed case that must build */
	}
	params(&b, &p);
	rs = rodscope_create(&p);
	if (!rs) {
		return 0;
	}
	axes(&b, &a);
	rodscope_reset(rs, colon, &a);
	for (int step = 0; step < 60 && b.n; step++) {
		axes(&b, &a);
		tip(&b, &t);
		if (step == 10) {
			patient(&b, g, &pad);
			rodscope_set_patient(rs, NULL, g, &pad);
		}
		if (step == 20) {
			rodscope_hold_tip(rs, take(&b, 0, 1e4));
		}
		rodscope_pose(rs, &a, &pose, tip_v);
		rodscope_step(rs, &a, &t, take(&b, 1e-4, 2e-3), &out);
		if (!rodscope_finite(rs)) {
			break; /* the loop's non-finite fault would latch */
		}
		if (!(rodscope_pad_force(rs) <= pad.force_n * (1 + 1e-9))) {
			abort(); /* the hand holds more than it presses with */
		}
	}
	memset(&pub, 0, sizeof(pub));
	rodscope_publish(rs, a.roll_rad, &out.wall, &pub, bows);
	rodscope_destroy(rs);
	return 0;
}
