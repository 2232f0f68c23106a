/* offline.c - see offline.h. */
#include "offline.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hand.h"
#include "haptics.h"
#include "scenario.h"

struct offline {
	struct config cfg;
	struct colon *colon;
	struct scope_params sp;
	struct hand *hand;
	struct rig *rig;
	struct haptics *haptics;
	struct offline_cycle c;
};

static uint64_t now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

struct offline *offline_create(const struct config *cfg, struct colon *colon,
			       const char *scenario, char *err,
			       size_t errsize)
{
	struct offline *o = calloc(1, sizeof(*o));
	struct scenario *scn;

	if (!o) {
		snprintf(err, errsize, "out of memory");
		return NULL;
	}
	o->cfg = *cfg;
	o->colon = colon;
	scope_params_config(cfg, &o->sp);
	scn = scenario_load(scenario, err, errsize);
	o->hand = scn ? hand_create(&o->cfg, scn) : NULL;
	o->rig = o->hand ? rig_sim_create(&o->cfg, o->hand) : NULL;
	o->haptics = haptics_create();
	if (!o->rig || !o->haptics) {
		if (scn) {
			snprintf(err, errsize, "out of memory");
		}
		offline_destroy(o);
		return NULL;
	}
	haptics_reset(o->haptics, colon);
	o->c.stamp_ns = OFFLINE_START_NS - OFFLINE_PERIOD_NS;
	return o;
}

void offline_destroy(struct offline *o)
{
	if (!o) {
		return;
	}
	haptics_destroy(o->haptics);
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

const struct offline_cycle *offline_step(struct offline *o)
{
	struct offline_cycle *c = &o->c;
	const struct haptics_input in = {
		.cfg = &o->cfg, .colon = o->colon, .pose = &c->pose,
		.fb = &c->fb, .dt_s = OFFLINE_PERIOD_NS * 1e-9,
		.torque_on = true, .applied = c->limited,
	};
	struct scope_input si;
	uint64_t t0;

	c->cycle++;
	c->stamp_ns += OFFLINE_PERIOD_NS;
	rig_read(o->rig, c->stamp_ns, &c->fb);
	si = (struct scope_input){
		c->fb.axis[0].position, c->fb.axis[1].position,
		c->fb.axis[2].position, c->fb.axis[3].position,
	};
	t0 = now_ns();
	scope_update(&o->sp, colon_centreline(o->colon), &si, &c->pose);
	haptics_render(o->haptics, &in, c->command, &c->haptics);
	c->step_ns = now_ns() - t0;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		c->limited[a] = fmin(fmax(c->command[a], -o->cfg.limits.max[a]),
				     o->cfg.limits.max[a]);
	}
	rig_write(o->rig, c->stamp_ns, c->limited, true);
	return c;
}

void offline_state(const struct offline *o, uint64_t scene_id,
		   struct endosim_state *st)
{
	const struct offline_cycle *c = &o->c;

	memset(st, 0, sizeof(*st));
	st->cycle = c->cycle;
	st->stamp_ns = st->publish_ns = c->stamp_ns;
	st->state = ENDOSIM_STATE_ENABLED;
	st->fault_axis = -1;
	st->compute_ns = (uint32_t)(c->step_ns < UINT32_MAX ? c->step_ns :
							      UINT32_MAX);
	st->scenario_time_s = c->fb.hand_time_s;
	st->scenario_done = c->fb.hand_done;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		struct endosim_axis_state *ax = &st->axis[a];

		ax->position = c->fb.axis[a].position;
		ax->velocity = c->fb.axis[a].velocity;
		ax->hand = c->fb.axis[a].hand;
		ax->command = c->command[a];
		ax->limited = c->limited[a];
		ax->feedback_ns = c->fb.axis[a].stamp_ns;
		ax->drive_status = c->fb.axis[a].status;
	}
	st->scope.scene_id = scene_id;
	scope_publish(&c->pose, colon_centreline(o->colon), &st->scope);
	st->haptics = c->haptics;
	st->safety.ramp = 1;
}
