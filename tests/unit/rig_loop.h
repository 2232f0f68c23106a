/*
 * rig_loop.h - for the tests that drive the force loop in lockstep: the
 * simulated rig (its hand) and the loop on the normal case (its sites llq
 * and umbilical) with either haptic model, the patient enabled or not and
 * its turns taking 0.5 s; a cycle of 1 ms at a time. Include after
 * cmocka.h.
 */
#ifndef ENDOSIM_RIG_LOOP_H
#define ENDOSIM_RIG_LOOP_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "conf/cases.h"
#include "conf/config.h"
#include "loop/loop.h"
#include "rig/hand.h"
#include "rig/rig_sim.h"

#define RIG_LOOP_PERIOD_NS 1000000ull

struct rig_loop {
	struct config cfg;
	struct hand *hand;
	struct rig *rig;
	struct loop *loop;
	uint64_t now_ns;
};

/* MODEL: enum haptics_model. */
static inline void rig_loop_create(struct rig_loop *r, bool patient,
				   int model)
{
	char err[512];
	struct colon *c;

	memset(r, 0, sizeof(*r));
	config_defaults(&r->cfg);
	r->cfg.haptics.model = model;
	r->cfg.patient.enabled = patient;
	r->cfg.patient.turn_s = 0.5;
	snprintf(r->cfg.colon.file, sizeof(r->cfg.colon.file),
		 "config/cases/normal.case");
	c = cases_load(&r->cfg, NULL, err, sizeof(err));
	if (!c) {
		fail_msg("%s", err);
	}
	r->hand = hand_create(&r->cfg, NULL);
	r->rig = r->hand ? rig_sim_create(&r->cfg, r->hand) : NULL;
	r->loop = r->rig ? loop_create(&r->cfg, r->rig, NULL, c, 1) : NULL;
	assert_non_null(r->loop);
	r->now_ns = ENDOSIM_NS_PER_S;
}

static inline void rig_loop_destroy(struct rig_loop *r)
{
	loop_destroy(r->loop);
	r->rig->ops->destroy(r->rig);
	hand_destroy(r->hand);
}

/* One cycle; the state it published. */
static inline const struct endosim_state *rig_loop_step(struct rig_loop *r)
{
	r->now_ns += RIG_LOOP_PERIOD_NS;
	loop_step(r->loop, r->now_ns);
	return loop_state(r->loop);
}

#endif
