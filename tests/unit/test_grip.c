/*
 * test_grip.c - the simulated hand's grip (rig/hand.h), in lockstep on
 * simulated time:
 *  - one axis (the simulated rig's insertion plant, without dry
 *    friction so that the load alone acts, with a tube's drag of 40 N
 *    s/m) held where live input
 *    left it, under a known load L: it settles L / k from there (k the
 *    hand's stiffness), within 2 %, the hand pulling back with L; beyond
 *    the grip's strength it slips: the axis runs on and the hand holds no
 *    more than its strength; hands off: the hand lets go, no force;
 *  - the whole rig on the normal case (rod model): the tube pushed into
 *    the colon by live input, then the input lapses: held, the carriage
 *    and the roll stay within the hand's stiffness answer to the forces
 *    the tube pushes back with; let go (hands off), the same tube springs
 *    back centimetres. Both printed side by side.
 *
 * Run from the top of the source tree (tests/run.sh does), or with
 * ENDOSIM_TOP naming it.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "conf/cases.h"
#include "conf/config.h"
#include "model/plant.h"
#include "offline.h"
#include "rig/hand.h"
#include "branch.h"

#define DT 0.001
#define NS(s) ((uint64_t)llround((s) * ENDOSIM_NS_PER_S))

/* The insertion plant under LOAD_N and the hand for SECONDS from T (s),
 * the hand's last force in *HAND_N. */
static double run_axis(struct hand *h, struct plant *pl, double load_n,
		       double *t, double seconds, double *hand_n)
{
	double pos[ENDOSIM_AXES] = { 0 }, vel[ENDOSIM_AXES] = { 0 };
	double f[ENDOSIM_AXES];

	for (long k = 0; k < lround(seconds / DT); k++) {
		pos[0] = pl->x;
		vel[0] = pl->v;
		hand_forces(h, *t, NS(*t), pos, vel, f);
		plant_step(pl, load_n + f[0], DT);
		*t += DT;
	}
	*hand_n = f[0];
	return pl->x;
}

static void axis_held(void **unused)
{
	const double push[ENDOSIM_AXES] = { 5, 0, 0, 0 };
	struct config cfg;
	struct plant_params pp;
	struct plant pl;
	struct hand *h;
	double t = 0, k, at, x, f, load, v0;

	(void)unused;
	config_defaults(&cfg);
	k = cfg.sim.hand_stiffness[ENDOSIM_AXIS_INSERTION];
	pp = (struct plant_params){ .inertia = cfg.sim.inertia[0],
				    .viscous = 40, /* a tube's drag */
				    .coulomb = 0, /* the load alone */
				    .min = -10, .max = 10 };
	plant_init(&pl, &pp, 0);
	h = hand_create(&cfg, NULL);
	assert_non_null(h);

	/* the trainee pushes 0.2 s, then the input lapses: held there */
	hand_set_live(h, push, 0, 0.2, NS(t));
	run_axis(h, &pl, 0, &t, 0.2, &f);
	at = pl.x;
	run_axis(h, &pl, 0, &t, 1.0, &f);
	print_message("pushed to %.4f m; held 1 s unloaded: %.4f m\n", at,
		      pl.x);
	/* the push's momentum carries it a little past: within 5 mm */
	assert_true(fabs(pl.x - at) < 0.005);
	at = pl.x;

	/* a known load, below the grip's strength: L / k back */
	load = 0.5 * cfg.sim.grip_max[0];
	x = run_axis(h, &pl, load, &t, 3.0, &f);
	print_message("load %.1f N: moved %.2f mm (L / k = %.2f mm), the "
		      "hand %.2f N\n", load, (x - at) * 1e3, load / k * 1e3, f);
	assert_true(fabs((x - at) - load / k) <= 0.02 * load / k);
	assert_true(fabs(f + load) <= 0.02 * load);

	/* beyond it: the axis slips on, the hand at its strength */
	load = 1.5 * cfg.sim.grip_max[0];
	run_axis(h, &pl, load, &t, 0.5, &f);
	v0 = pl.v;
	x = pl.x;
	run_axis(h, &pl, load, &t, 0.2, &f);
	print_message("load %.1f N: slipping at %.3f m/s, the hand %.2f N "
		      "(strength %.1f N)\n", load, pl.v, f,
		      cfg.sim.grip_max[0]);
	assert_true(v0 > 0.05 && pl.x > x + 0.01);
	assert_true(fabs(f) <= cfg.sim.grip_max[0] + 1e-9);
	assert_true(fabs(f) > 0.8 * cfg.sim.grip_max[0]);
	/* the load gone, the hand's spring gives back at most its reach
	 * (strength / stiffness): it holds the axis where it slipped to,
	 * not where the input left it */
	x = pl.x;
	run_axis(h, &pl, 0, &t, 3.0, &f);
	print_message("the load gone: back %.1f mm from where it slipped to "
		      "(the grip's reach %.1f mm), %.0f mm on from where the "
		      "input left it\n", (x - pl.x) * 1e3,
		      cfg.sim.grip_max[0] / k * 1e3, (pl.x - at) * 1e3);
	assert_true(x - pl.x <= 1.02 * cfg.sim.grip_max[0] / k);
	assert_true(pl.x - at > 0.05);

	/* hands off: no force at all */
	hand_release(h);
	run_axis(h, &pl, 0, &t, 0.1, &f);
	assert_true(f == 0);
	hand_destroy(h);
}

/* The normal case, rod model, no scenario to speak of (one ended at
 * once): the tube pushed in 3 s at 15 N (the same for the tube held and
 * let go: played once, each a branch of it, branch.h). */
static struct offline *rig_pushed(void)
{
	const double push[ENDOSIM_AXES] = { 15, 0, 0, 0 };
	struct config cfg;
	struct colon *colon;
	struct offline *o;
	char scn[] = "/tmp/test_grip.XXXXXX", err[512];
	int fd = mkstemp(scn);
	FILE *f = fdopen(fd, "w");

	assert_non_null(f);
	fprintf(f, "0 insertion target 0 0.1\n0.001 end\n");
	fclose(f);
	config_defaults(&cfg);
	cfg.haptics.model = HAPTICS_MODEL_ROD;
	snprintf(cfg.colon.file, sizeof(cfg.colon.file),
		 "config/cases/normal.case");
	colon = cases_load(&cfg, NULL, err, sizeof(err));
	if (!colon) {
		fail_msg("%s", err);
	}
	o = offline_create(&cfg, colon, scn, err, sizeof(err));
	unlink(scn);
	if (!o) {
		fail_msg("%s", err);
	}
	offline_step(o);
	offline_hand(o, push, 3.0);
	for (int k = 0; k < 2999; k++) {
		offline_step(o);
	}
	return o;
}

/* After the push: the carriage's and the roll's moves over the next 2 s,
 * and the insertion and roll forces the tube pushed back with when the
 * input lapsed. */
struct after {
	double moved[2], back[2];
	bool enabled; /* throughout */
};

/* What the pushed rig ARG (its last cycle of the push to play) does
 * after the input lapses, into OUT (struct after); released (hands off)
 * where RELEASE. In branch_run()'s child: no assertion here. */
static void rig_after(struct offline *o, bool release, struct after *a)
{
	const struct endosim_state *st = offline_step(o);
	double d0, r0;

	a->back[0] = st->axis[ENDOSIM_AXIS_INSERTION].command;
	a->back[1] = st->axis[ENDOSIM_AXIS_ROLL].command;
	d0 = st->axis[ENDOSIM_AXIS_INSERTION].position;
	r0 = st->axis[ENDOSIM_AXIS_ROLL].position;
	if (release) {
		offline_hands_off(o);
	}
	a->enabled = true;
	for (int k = 0; k < 2000; k++) {
		st = offline_step(o);
		a->enabled = a->enabled && st->state == ENDOSIM_STATE_ENABLED;
	}
	a->moved[0] = st->axis[ENDOSIM_AXIS_INSERTION].position - d0;
	a->moved[1] = st->axis[ENDOSIM_AXIS_ROLL].position - r0;
	offline_destroy(o);
}

static void held(void *o, void *out)
{
	rig_after(o, false, out);
}

static void let_go(void *o, void *out)
{
	rig_after(o, true, out);
}

static void rig_held_and_let_go(void **unused)
{
	struct config cfg;
	struct offline *o = rig_pushed();
	struct after h, f;
	double k_ins, k_roll;

	(void)unused;
	config_defaults(&cfg);
	k_ins = cfg.sim.hand_stiffness[ENDOSIM_AXIS_INSERTION];
	k_roll = cfg.sim.hand_stiffness[ENDOSIM_AXIS_ROLL];
	branch_run(held, o, &h, sizeof(h));
	branch_run(let_go, o, &f, sizeof(f));
	offline_destroy(o);
	assert_true(h.enabled && f.enabled);
	print_message("the tube pushed back %.2f N, %.4f N m when the input "
		      "lapsed\n", h.back[0], h.back[1]);
	print_message("held: carriage %+.2f cm, roll %+.1f deg (stiffness "
		      "answer %.2f cm, %.1f deg); let go: carriage %+.2f cm, "
		      "roll %+.1f deg\n", h.moved[0] * 100,
		      h.moved[1] * 180 / M_PI, fabs(h.back[0]) / k_ins * 100,
		      fabs(h.back[1]) / k_roll * 180 / M_PI, f.moved[0] * 100,
		      f.moved[1] * 180 / M_PI);
	assert_true(fabs(h.back[0]) > 1); /* the tube is loaded */
	assert_true(fabs(h.moved[0]) <= 1.1 * fabs(h.back[0]) / k_ins + 0.002);
	assert_true(fabs(h.moved[1]) <=
		    1.1 * fabs(h.back[1]) / k_roll + 0.02);
	assert_true(fabs(f.moved[0]) > 2 * fabs(h.moved[0]) + 0.01);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(axis_held),
		cmocka_unit_test(rig_held_and_let_go),
	};
	const char *top = getenv("ENDOSIM_TOP");

	if (top && chdir(top)) {
		perror(top);
		return 1;
	}
	return cmocka_run_group_tests(tests, NULL, NULL);
}
