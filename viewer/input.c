/* input.c - see input.h. */
#include "viewer/input.h"

#include <math.h>
#include <string.h>

/* The scripted hand's grip (endosimd --print-config, [sim] hand_*). */
const double input_rate[ENDOSIM_AXES] = { 0.05, 1.5, 1.5, 1.5 };
const double input_stiffness[ENDOSIM_AXES] = { 400, 0.5, 0.05, 0.05 };
const double input_damping[ENDOSIM_AXES] = { 40, 0.02, 0.002, 0.002 };
const double input_strength[ENDOSIM_AXES] = { 40, 1.0, 0.15, 0.15 };


bool input_active(const struct input_controls *c)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		if (c->rate[a] != 0 || c->drag[a] || c->step[a] != 0) {
			return true;
		}
	}
	return false;
}

static double clamp(double x, double lo, double hi)
{
	return x < lo ? lo : x > hi ? hi : x;
}

static void take_hold(struct input_hand *h, const struct endosim_state *st)
{
	memset(h, 0, sizeof(*h));
	h->engaged = true;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		h->target[a] = st->axis[a].position;
	}
}

/* Moves axis A's target by the controls; keeps it within reach. */
static void move_target(struct input_hand *h, const struct input_controls *c,
			const struct endosim_state *st, double dt_s, int a)
{
	double lead = input_strength[a] / input_stiffness[a];
	double rate = clamp(c->rate[a], -INPUT_FAST, INPUT_FAST);

	if (c->drag[a] && !h->dragging[a]) {
		h->drag_from[a] = h->target[a];
	}
	h->dragging[a] = c->drag[a];
	if (c->drag[a]) {
		h->target[a] = h->drag_from[a] + c->drag_by[a];
	}
	h->target[a] += rate * input_rate[a] * dt_s + c->step[a];
	h->target[a] = clamp(h->target[a], st->axis[a].position - lead,
			     st->axis[a].position + lead);
}

bool input_step(struct input_hand *h, const struct input_controls *c,
		const struct endosim_state *st, double dt_s, uint64_t now_ns,
		double force[ENDOSIM_AXES])
{
	bool active = input_active(c);

	memset(force, 0, ENDOSIM_AXES * sizeof(*force));
	if (active) {
		if (!h->engaged) {
			take_hold(h, st);
		}
		h->last_used_ns = now_ns;
	} else if (h->engaged && (double)(now_ns - h->last_used_ns) >
					 INPUT_RELEASE_S * ENDOSIM_NS_PER_S) {
		h->engaged = false;
	}
	if (!h->engaged) {
		return false;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		const struct endosim_axis_state *ax = &st->axis[a];

		double pull;

		move_target(h, c, st, dt_s, a);
		pull = input_stiffness[a] * (h->target[a] - ax->position) -
		       input_damping[a] * ax->velocity;
		force[a] = clamp(pull, -input_strength[a], input_strength[a]);
	}
	return true;
}
