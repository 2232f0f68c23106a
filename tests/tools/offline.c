/* offline.c - see offline.h. */
#include "offline.h"

#include <stdio.h>
#include <stdlib.h>

#include "rig/hand.h"
#include "loop/loop.h"
#include "rig/rig_sim.h"
#include "rig/scenario.h"

struct offline {
	struct hand *hand;
	struct rig *rig;
	struct loop *loop;
	uint64_t stamp_ns; /* the last cycle's */
};

struct offline *offline_create(const struct config *cfg, struct colon *colon,
			       const char *scenario, char *err,
			       size_t errsize)
{
	struct scenario *scn = scenario_load(scenario, err, errsize);

	if (!scn) {
		colon_destroy(colon);
		return NULL;
	}
	return offline_create_with(cfg, colon, scn, err, errsize);
}

struct offline *offline_create_with(const struct config *cfg,
				    struct colon *colon, struct scenario *scn,
				    char *err, size_t errsize)
{
	struct offline *o = calloc(1, sizeof(*o));

	if (!o) {
		snprintf(err, errsize, "out of memory");
		scenario_destroy(scn);
		colon_destroy(colon);
		return NULL;
	}
	o->hand = hand_create(cfg, scn);
	if (!o->hand) {
		scenario_destroy(scn); /* not taken */
	}
	o->rig = o->hand ? rig_sim_create(cfg, o->hand) : NULL;
	o->loop = o->rig ? loop_create(cfg, o->rig, NULL, colon,
				       OFFLINE_SCENE_ID) : NULL;
	if (!o->loop) {
		snprintf(err, errsize, "out of memory");
		colon_destroy(colon);
		offline_destroy(o);
		return NULL;
	}
	loop_post(o->loop, LOOP_CMD_ENABLE);
	o->stamp_ns = OFFLINE_START_NS - OFFLINE_PERIOD_NS;
	return o;
}

void offline_destroy(struct offline *o)
{
	if (!o) {
		return;
	}
	loop_destroy(o->loop);
	if (o->rig) {
		o->rig->ops->destroy(o->rig); /* rig.c would bring every backend */
	}
	hand_destroy(o->hand);
	free(o);
}

double offline_length_s(const struct offline *o)
{
	return scenario_length(hand_scenario(o->hand));
}

const struct endosim_state *offline_step(struct offline *o)
{
	o->stamp_ns += OFFLINE_PERIOD_NS;
	loop_step(o->loop, o->stamp_ns);
	return loop_state(o->loop);
}

void offline_hand(struct offline *o, const double force[ENDOSIM_AXES],
		  double hold_s)
{
	hand_set_live(o->hand, force, 0, hold_s, o->stamp_ns);
}

void offline_hands_off(struct offline *o)
{
	hand_release(o->hand);
}

uint64_t offline_hash(uint64_t h, const struct endosim_state *st)
{
	struct endosim_state s = *st;
	const unsigned char *b = (const unsigned char *)&s;

	s.compute_ns = 0;
	for (size_t i = 0; i < sizeof(s); i++) {
		h = (h ^ b[i]) * 0x100000001b3ull;
	}
	return h;
}

const struct colon *offline_colon(const struct offline *o)
{
	return loop_colon(o->loop);
}

void offline_hold_tip(struct offline *o, double hold_n_per_m)
{
	loop_hold_tip(o->loop, hold_n_per_m);
}

void offline_guide(struct offline *o, const struct guide_command *c)
{
	loop_guide_post(o->loop, c);
}

int offline_guide_answer(const struct offline *o)
{
	return loop_guide_answer(o->loop);
}

void offline_command(struct offline *o, int cmd)
{
	loop_post(o->loop, (enum loop_cmd)cmd);
}

void offline_tool_input(struct offline *o, double depth_m, double opening,
			bool pedal, double hold_s)
{
	hand_set_tool(o->hand, depth_m, opening, pedal, hold_s, o->stamp_ns);
}

void offline_tool_select(struct offline *o, int kind, double snare_m)
{
	loop_tool_post(o->loop, &(struct loop_tool_command){ kind, snare_m });
}

int offline_tool_answer(const struct offline *o)
{
	return loop_tool_answer(o->loop);
}

struct tool *offline_tool(struct offline *o)
{
	return loop_tool(o->loop);
}
