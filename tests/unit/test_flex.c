/*
 * test_flex.c - the colon that moves (flex.h, centreline_displace()):
 *  - the centreline through the nodes: a sample at a node's place moves by
 *    the node's displacement, the span's ends and the fixed colon stay, the
 *    tangent stays continuous at the ends (C1), and all nodes moved alike
 *    move the span's inside alike;
 *  - the mesentery's law: a uniform push F per node holds each node at y
 *    with F = k_m y (1 + (y / h)^2) (k_m the segment's mesentery shared
 *    among its nodes), and the segment's mesentery takes the whole push
 *    (action = reaction: the forces pushed are the forces held);
 *  - a push between two knots is shared by their weights; the fixed colon
 *    takes a push without moving; the chain carries a point push to the
 *    neighbours, less than to the node pushed;
 *  - released, the colon returns to rest;
 *  - its weight: a span across gravity sags in its middle by the
 *    mesentery law's answer, m g / k in the linear regime, within 2 %;
 *    along its course gravity moves nothing;
 *  - the assistant's pad (its grip, flex.h), on nodes free of each
 *    other: within its reach a node pushed sideways is held by the
 *    grip's spring towards its rest besides its mesentery
 *    (F = (k_m (1 + (y/h)^2) + k_p) y), one outside it by its mesentery
 *    alone; a pad pressed beyond the course puts the colon under it back
 *    onto its face and holds it there; the pad's force is what its
 *    springs hold, and no more than the hand's force: a weak hand's pad
 *    holds its force, shared by its nodes, which go on past the face as
 *    far as the rest of the push takes them; lifted, nothing holds them.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "model/anatomy.h"
#include "model/colon.h"
#include "model/flex.h"
#include "geom_assert.h"
#include "plain_anatomy.h"
#include "base/vec3.h"

#define DT 0.001

/* A round colon, 5 cm wide, straight along z, the sigmoid (0.16..0.53 m)
 * mobile on a mesentery K (N/m) of height H (m). */
static struct colon *straight_colon(double k, double h)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	struct anatomy a;
	struct colon *c;
	char err[256];

	plain_anatomy(&a, 0.05);
	plain_mobile_sigmoid(&a, k, h);
	p.ring_vertices = 32;
	c = colon_create(&a, &p, err, sizeof(err));
	assert_non_null(c);
	return c;
}

/* The material s of node I of span 0 with COUNT nodes. */
static double node_s(const struct colon *c, int i, int count)
{
	double s0, s1;

	centreline_span_range(colon_centreline(c), 0, &s0, &s1);
	return s0 + (s1 - s0) * (i + 1) / (count + 1);
}

static const double *sample_at(const struct colon *c, double s)
{
	const struct centreline *cl = colon_centreline(c);

	return centreline_sample(cl, (size_t)lround(s / centreline_step(cl)))
		->p;
}

static const double *base_at(const struct colon *c, double s)
{
	const struct centreline *cl = colon_centreline(c);

	return centreline_base(cl, (size_t)lround(s / centreline_step(cl)))->p;
}

/* The centreline through the nodes: knots, ends, C1, a uniform move. */
static void test_displace(void **state)
{
	struct colon *c = straight_colon(600, 0.06);
	struct centreline *cl = colon_centreline(c);
	double node[4][3] = { { 0.01, 0, 0 }, { 0.02, 0.01, 0 },
			      { -0.01, 0.005, 0 }, { 0.004, 0, 0 } };
	double s0, s1, ds = centreline_step(cl), d[3];
	size_t a, b;

	(void)state;
	centreline_span_range(cl, 0, &s0, &s1);
	assert_int_equal(centreline_displace(cl, 0,
					     (const double(*)[3])node, 4), 0);
	for (int i = 0; i < 4; i++) {
		double s = node_s(c, i, 4);

		/* a node's place is a sample's only to within half a step */
		vec3_sub(d, sample_at(c, s), base_at(c, s));
		assert_vec_near(d, node[i], 2e-4);
	}
	a = (size_t)lround(s0 / ds);
	b = (size_t)lround(s1 / ds);
	assert_vec_near(centreline_sample(cl, a)->p, centreline_base(cl, a)->p,
			1e-12);
	assert_vec_near(centreline_sample(cl, b)->p, centreline_base(cl, b)->p,
			1e-12);
	assert_vec_near(centreline_sample(cl, a - 5)->p,
			centreline_base(cl, a - 5)->p, 1e-12);
	/* C1: at the ends the tangent stays the fixed colon's (within the
	 * central difference over a step into the moved span) */
	assert_true(vec3_dot(centreline_sample(cl, a)->t,
			     centreline_base(cl, a)->t) > cos(0.01));
	assert_true(vec3_dot(centreline_sample(cl, b)->t,
			     centreline_base(cl, b)->t) > cos(0.01));
	/* every node alike: alike between the inner nodes (the outer
	 * intervals bend towards the fixed ends) */
	for (int i = 0; i < 4; i++) {
		vec3_set(node[i], 0.02, 0, 0);
	}
	centreline_displace(cl, 0, (const double(*)[3])node, 4);
	for (double s = node_s(c, 1, 4); s <= node_s(c, 2, 4); s += 0.01) {
		vec3_sub(d, sample_at(c, s), base_at(c, s));
		assert_near(d[0], 0.02, 1e-9);
	}
	node[0][0] = NAN;
	assert_int_equal(centreline_displace(cl, 0,
					     (const double(*)[3])node, 4),
			 -EINVAL);
	colon_destroy(c);
}

/* Pushes each node of span 0 with F for T seconds. */
static void push_nodes(struct flex *f, const struct colon *c,
		       const double force[3], double t)
{
	int count = flex_span_nodes(f, 0);

	for (int k = 0; k < (int)(t / DT); k++) {
		flex_clear(f);
		for (int i = 0; force && i < count; i++) {
			flex_push(f, node_s(c, i, count), force, 0);
		}
		flex_step(f, DT);
	}
}

/* The mesentery's law under a uniform push: F = k_m y (1 + (y/h)^2). */
static void test_mesentery_law(void **state)
{
	const double k = 600, h = 0.06;
	const struct flex_params p = { .node_spacing_m = 0.02,
				       .damping_n_s_per_m = 2,
				       .chain_n_per_m = 0 };
	struct colon *c = straight_colon(k, h);
	struct flex *f = flex_create(&p);
	int count;

	(void)state;
	assert_non_null(f);
	flex_attach(f, c);
	count = flex_span_nodes(f, 0);
	assert_int_equal(count, (int)lround(0.37 / 0.02) - 1);
	for (int trial = 0; trial < 3; trial++) {
		const double fn[] = { 0.5, 2, 6 };
		double km = k / count, force[3] = { 0, fn[trial], 0 }, y, want;

		flex_reset(f);
		push_nodes(f, c, force, 3.0);
		y = flex_node(f, count / 2)[1];
		want = km * y * (1 + (y / h) * (y / h));
		print_message("mesentery: push %.1f N per node holds %.2f cm "
			      "(k y (1 + (y/h)^2) = %.4f N)\n", fn[trial],
			      y * 100, want);
		assert_near(want, fn[trial], 0.01 * fn[trial]);
		assert_near(flex_span_displacement(f, 0), y, 1e-9);
		/* its tension: every node's push, held */
		assert_near(flex_span_tension(f, 0), count * fn[trial],
			    0.01 * count * fn[trial]);
		/* at rest the mesentery holds what was pushed, at every node */
		for (int i = 0; i < count; i++) {
			assert_near(flex_node(f, i)[1], y, 1e-6);
		}
	}
	/* released: back to rest */
	push_nodes(f, c, NULL, 3.0);
	assert_near(flex_span_displacement(f, 0), 0, 1e-5);
	flex_destroy(f);
	colon_destroy(c);
}

/* Shared pushes, the fixed colon, the chain's reach. */
static void test_pushes(void **state)
{
	const struct flex_params p = FLEX_PARAMS_DEFAULT;
	struct colon *c = straight_colon(600, 0.06);
	struct flex *f = flex_create(&p);
	const double push[3] = { 1, 0, 0 };
	int count, mid;
	double s, v[3];

	(void)state;
	assert_non_null(f);
	flex_attach(f, c);
	count = flex_span_nodes(f, 0);
	mid = count / 2;
	/* the fixed colon (the descending) takes a push, nothing moves */
	for (int k = 0; k < 1000; k++) {
		flex_clear(f);
		flex_push(f, 0.6, push, 0);
		flex_step(f, DT);
	}
	assert_near(flex_span_displacement(f, 0), 0, 1e-12);
	flex_velocity(f, 0.6, v);
	assert_vec_near(v, ((double[3]){ 0, 0, 0 }), 1e-12);
	/* a point push at one node: it moves most, its neighbours along */
	s = node_s(c, mid, count);
	for (int k = 0; k < 3000; k++) {
		flex_clear(f);
		flex_push(f, s, push, 0);
		flex_step(f, DT);
	}
	assert_true(flex_node(f, mid)[0] > flex_node(f, mid + 1)[0]);
	assert_true(flex_node(f, mid + 1)[0] > flex_node(f, mid + 3)[0]);
	assert_true(flex_node(f, mid + 3)[0] > 0);
	/* halfway between two nodes: both take half */
	flex_reset(f);
	s = (node_s(c, mid, count) + node_s(c, mid + 1, count)) / 2;
	for (int k = 0; k < 50; k++) {
		flex_clear(f);
		flex_push(f, s, push, 0);
		flex_step(f, DT);
	}
	assert_near(flex_node(f, mid)[0], flex_node(f, mid + 1)[0],
		    0.01 * flex_node(f, mid)[0]);
	flex_destroy(f);
	colon_destroy(c);
}

/* A span across gravity sags by m g / k per node (linear regime). */
static void test_gravity_sag(void **state)
{
	const double k = 600, h = 0.06;
	struct flex_params p = FLEX_PARAMS_DEFAULT;
	struct colon *c = straight_colon(k, h);
	struct flex *f;
	const double g[3] = { 0, 9.81, 0 }, along[3] = { 0, 0, -9.81 };
	double s0, s1, m, km, y, want;
	int count;

	(void)state;
	p.mass_per_m_kg = 0.3;
	f = flex_create(&p);
	assert_non_null(f);
	flex_attach(f, c);
	count = flex_span_nodes(f, 0);
	centreline_span_range(colon_centreline(c), 0, &s0, &s1);
	m = p.mass_per_m_kg * (s1 - s0) / (count + 1);
	km = k / count;
	flex_set_gravity(f, g);
	push_nodes(f, c, NULL, 5.0);
	y = flex_node(f, count / 2)[1];
	want = m * g[1] / km;
	print_message("its weight: %.4f kg a node on %.1f N/m sags %.3f mm "
		      "(m g / k = %.3f mm, h = %.0f mm)\n", m, km, y * 1e3,
		      want * 1e3, h * 1e3);
	assert_near(y, want, 0.02 * want);
	/* gravity along the course: the mesentery holds it, nothing moves */
	flex_reset(f);
	flex_set_gravity(f, along);
	push_nodes(f, c, NULL, 2.0);
	assert_near(flex_span_displacement(f, 0), 0, 1e-9);
	flex_destroy(f);
	colon_destroy(c);
}

/* Independent nodes (no chain, no wall, no weight): each obeys its own
 * forces, as the analytic checks want. */
static const struct flex_params lone = { .node_spacing_m = 0.02,
					 .damping_n_s_per_m = 2 };

/* The pad pressed with FORCE_N towards +y, reach 5 cm, its face FACE_M
 * from the course at the span's middle along y (< 0: in front of it). */
static struct flex_pad pad_at_middle(const struct colon *c, int count,
				     double force_n, double face_m)
{
	struct flex_pad pad = { .on = true, .in = { 0, 1, 0 },
				.radius_m = 0.05, .force_n = force_n };

	vec3_copy(pad.point, base_at(c, node_s(c, count / 2, count)));
	pad.point[1] += face_m;
	return pad;
}

/* The pad's tests' colon: its sigmoid's mesentery (N/m) and height (m). */
#define PAD_K 600
#define PAD_H 0.06

/* A flex of independent nodes on C, the pad pressed at its middle with
 * FORCE_N, its face FACE_M off the course (pad_at_middle()), each node
 * pushed with PUSH (NULL: none) for 3 s; its mesentery per node into
 * *KM, how many nodes it has into *COUNT. */
static struct flex *pressed(struct colon *c, double force_n, double face_m,
			    const double push[3], double *km, int *count)
{
	struct flex *f = flex_create(&lone);
	struct flex_pad pad;

	assert_non_null(f);
	flex_attach(f, c);
	*count = flex_span_nodes(f, 0);
	*km = PAD_K / (double)*count;
	pad = pad_at_middle(c, *count, force_n, face_m);
	flex_set_pad(f, &pad);
	push_nodes(f, c, push, 3.0);
	return f;
}

/* Whether node I lies within the pad's reach (the course runs along z,
 * across the press). */
static bool in_reach(const struct colon *c, int i, int count)
{
	return fabs(node_s(c, i, count) - node_s(c, count / 2, count)) <= 0.05;
}

/* The mesentery's force on a node displaced by Y (along one axis). */
static double mesentery_n(double km, double h, double y)
{
	return km * y * (1 + (y / h) * (y / h));
}

/*
 * The grip across the press: each node within the pad's reach, pushed
 * sideways with P, is held at y with P = k_m y (1 + (y/h)^2) + k_p y
 * (k_p = F / FLEX_PAD_GIVE_M), one outside it as by its mesentery alone;
 * the pad's force is the held nodes' k_p y added up; lifted, nothing
 * holds them.
 */
static void test_pad_grip(void **state)
{
	const double h = PAD_H, fn = 20, kp = fn / FLEX_PAD_GIVE_M;
	const double push[3] = { 0.5, 0, 0 };
	struct colon *c = straight_colon(PAD_K, h);
	double km, sum = 0, y;
	int count, held = 0;
	struct flex *f = pressed(c, fn, -0.01, push, &km, &count);

	(void)state;
	for (int i = 0; i < count; i++) {
		y = flex_node(f, i)[0];
		if (in_reach(c, i, count)) {
			assert_near(mesentery_n(km, h, y) + kp * y, push[0],
				    1e-3 * push[0]);
			sum += kp * y;
			held++;
		} else {
			assert_near(mesentery_n(km, h, y), push[0],
				    1e-2 * push[0]);
		}
	}
	print_message("grip: %d nodes held at %.3f mm (free %.2f cm); the "
		      "pad holds %.3f N\n", held,
		      flex_node(f, count / 2)[0] * 1e3,
		      flex_node(f, 0)[0] * 100, flex_pad_force(f));
	assert_int_equal(held, 5);
	assert_near(flex_pad_force(f), sum, 1e-3 * sum);
	flex_set_pad(f, &(struct flex_pad){ .on = false });
	push_nodes(f, c, push, 3.0);
	assert_near(mesentery_n(km, h, flex_node(f, count / 2)[0]), push[0],
		    1e-2 * push[0]);
	assert_near(flex_pad_force(f), 0, 1e-12);
	flex_destroy(f);
	colon_destroy(c);
}

/*
 * The pad's face: pressed 1 cm beyond the course (y_f = +1 cm), it puts
 * the colon under it back onto its face and holds it there: pushed with P
 * towards the wall, a node within the reach sits at y with
 * P = k_p (y_f - y) - k_m y (1 + (y/h)^2); one outside it as by its
 * mesentery alone.
 */
static void test_pad_face(void **state)
{
	const double h = PAD_H, fn = 20, kp = fn / FLEX_PAD_GIVE_M;
	const double push[3] = { 0, -2, 0 }, face = 0.01;
	struct colon *c = straight_colon(PAD_K, h);
	double km, sum = 0;
	int count;
	struct flex *f = pressed(c, fn, face, NULL, &km, &count);

	(void)state;
	assert_near(flex_node(f, count / 2)[1], face * kp / (kp + km),
		    1e-3 * face);
	push_nodes(f, c, push, 3.0);
	for (int i = 0; i < count; i++) {
		double y = flex_node(f, i)[1];

		if (in_reach(c, i, count)) {
			assert_near(kp * (face - y) - mesentery_n(km, h, y),
				    -push[1], 1e-3 * -push[1]);
			sum += kp * (face - y);
		} else {
			assert_near(mesentery_n(km, h, -y), -push[1],
				    1e-2 * -push[1]);
		}
	}
	print_message("face: the middle %.2f cm (the face %.0f cm); the pad "
		      "holds %.2f N\n", flex_node(f, count / 2)[1] * 100,
		      face * 100, flex_pad_force(f));
	assert_near(flex_pad_force(f), sum, 1e-3 * sum);
	assert_true(flex_pad_force(f) < fn);
	flex_destroy(f);
	colon_destroy(c);
}

/*
 * A hand weaker than the push: the pad holds with the hand's force F, no
 * more, shared by the nodes it holds (alike here: n of them), which go
 * on past its face until P - F / n = k_m |y| (1 + (y/h)^2).
 */
static void test_pad_bound(void **state)
{
	const double fn = 2, push[3] = { 0, -2, 0 };
	struct colon *c = straight_colon(PAD_K, PAD_H);
	double km;
	int count, held = 0;
	struct flex *f = pressed(c, fn, -0.01, push, &km, &count);

	(void)state;
	for (int i = 0; i < count; i++) {
		held += in_reach(c, i, count);
	}
	print_message("bound: a %.0f N hand holds %.4f N over %d nodes, the "
		      "middle at %.2f cm\n", fn, flex_pad_force(f), held,
		      flex_node(f, count / 2)[1] * 100);
	assert_near(flex_pad_force(f), fn, 1e-9);
	for (int i = 0; i < count; i++) {
		if (in_reach(c, i, count)) {
			assert_near(mesentery_n(km, PAD_H, -flex_node(f, i)[1]),
				    -push[1] - fn / held, 1e-3 * -push[1]);
		}
	}
	flex_destroy(f);
	colon_destroy(c);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_displace),
		cmocka_unit_test(test_mesentery_law),
		cmocka_unit_test(test_pushes),
		cmocka_unit_test(test_gravity_sag),
		cmocka_unit_test(test_pad_grip),
		cmocka_unit_test(test_pad_face),
		cmocka_unit_test(test_pad_bound),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
