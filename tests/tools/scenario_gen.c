/*
 * scenario_gen - writes a scenario for the simulated hand (scenario.h) that
 * drives the scope through a case the way a trainee would: inserting at a
 * steady pace while steering the tip into the lumen ahead, with one
 * mistake on the way (pushing on with a straight tip, which forms a loop
 * behind it), the loop reduced by withdrawing, the cecum reached, and the
 * withdrawal.
 *
 *   scenario_gen [--model rod|paper] CASE_FILE [SPEED_M_PER_S] > FILE.scn
 *
 * The rod model (the default, as endosimd's): the course is played as it
 * is written, on endosimd's own force loop in lockstep with the demo's
 * configuration (trainee_demo_config(): the defaults, the rod model and
 * the patient; tests/tools/trainee.h: she steers by what the tip sees,
 * insufflates when the lumen ahead closes, washes a smeared lens, waits
 * when the scope is stuck, reduces a loop when it stops her with the
 * assistant's hand or a turn of the patient, and turns the segment she
 * examines uppermost on the way out); the daemon on the same case and
 * configuration plays it back exactly so.
 *
 * The paper model: written ahead, on the centreline (the tube follows it),
 * with a quarter twist in the transverse colon:
 * for a depth d the bending section (length Lb, scope.h) starts
 * at s = d - Lb on the centreline; the tip should sit on the centreline at
 * s = d. An arc from the base with the base's tangent t reaches the point
 * D ahead when it bends by theta = 2 atan2(b, a), a = D . t, b = |D - a t|,
 * towards n = (D - a t) / b; its up/down and left/right parts are theta
 * times n along the rolled frame (u', v'), and the wheels turn them by the
 * configured gains.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <string.h>

#include "model/anatomy.h"
#include "model/colon.h"
#include "conf/config.h"
#include "model/scope.h"
#include "trainee.h"
#include "base/vec3.h"

#define STEP_S 0.5 /* a waypoint every half second */

struct gen {
	struct colon *colon;
	struct scope_params sp;
	double wheel_max;   /* rad */
	double t;           /* s, the script's clock */
	double d, roll;     /* where the hand is now */
	double ud, lr;      /* wheels, rad */
};

/* The wheel angles that point the tip at the centreline D ahead. */
static void steer(const struct gen *g, double d, double roll, double *ud,
		  double *lr)
{
	const struct centreline *cl = colon_centreline(g->colon);
	double lb = g->sp.bending_length_m;
	struct centreline_point b, t;
	double dd[3], a, n[3], len, theta, up[3], right[3];

	if (d <= lb) {
		*ud = *lr = 0;
		return;
	}
	centreline_at_s(cl, d - lb, &b);
	centreline_at_s(cl, d, &t);
	vec3_sub(dd, t.p, b.p);
	a = vec3_dot(dd, b.t);
	vec3_axpy(n, dd, -a, b.t);
	len = vec3_normalize(n);
	theta = 2 * atan2(len, a);
	for (int k = 0; k < 3; k++) {
		up[k] = cos(roll) * b.u[k] + sin(roll) * b.v[k];
	}
	vec3_cross(right, b.t, up);
	*ud = fmax(-g->wheel_max, fmin(g->wheel_max,
		   theta * vec3_dot(n, up) / g->sp.ud_gain));
	*lr = fmax(-g->wheel_max, fmin(g->wheel_max,
		   theta * vec3_dot(n, right) / g->sp.lr_gain));
}

static void waypoint(struct gen *g, double ud, double lr)
{
	printf("%7.2f insertion target %.4f %.2f\n", g->t, g->d, STEP_S);
	printf("%7.2f roll      target %.4f %.2f\n", g->t, g->roll, STEP_S);
	printf("%7.2f wheel_ud  target %.4f %.2f\n", g->t, ud, STEP_S);
	printf("%7.2f wheel_lr  target %.4f %.2f\n", g->t, lr, STEP_S);
	g->ud = ud;
	g->lr = lr;
	g->t += STEP_S;
}

/* Moves the hand to depth TO (and roll ROLL_TO) at SPEED, steering along
 * when STEERING, else holding the tip straight. */
static void move(struct gen *g, double to, double roll_to, double speed,
		 int steering)
{
	int steps = (int)ceil(fabs(to - g->d) / (speed * STEP_S));
	double d0 = g->d, r0 = g->roll, ud = 0, lr = 0;

	for (int i = 1; i <= steps; i++) {
		g->d = d0 + (to - d0) * i / steps;
		g->roll = r0 + (roll_to - r0) * i / steps;
		if (steering) {
			steer(g, g->d, g->roll, &ud, &lr);
		}
		waypoint(g, ud, lr);
	}
}

static void hold(struct gen *g, double seconds)
{
	for (double s = 0; s < seconds; s += STEP_S) {
		waypoint(g, g->ud, g->lr);
	}
}

/* The paper model's course, written ahead on the centreline. */
static int paper_course(const struct anatomy *a, double speed)
{
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct gen g = { .sp = SCOPE_PARAMS_DEFAULT };
	struct config cfg;
	char err[256];
	double flexure, cecum;

	config_defaults(&cfg);
	g.sp.ud_gain = cfg.scope.gain[0];
	g.sp.lr_gain = cfg.scope.gain[1];
	g.sp.bending_length_m = cfg.scope.bending_length_m;
	g.wheel_max = cfg.rig.travel_max[ENDOSIM_AXIS_WHEEL_UD] * 0.95;
	g.colon = colon_create(a, &cp, err, sizeof(err));
	if (!g.colon) {
		fprintf(stderr, "scenario_gen: %s\n", err);
		return 1;
	}
	flexure = anatomy_segment_start(a, ANATOMY_SPLENIC_FLEXURE);
	cecum = anatomy_segment_start(a, ANATOMY_CECUM) + 0.02;
	printf("# endosim scenario for case '%s', written by scenario_gen "
	       "--model paper:\n"
	       "# a trainee inserting at %.0f mm/s, steering into the lumen;\n"
	       "# at the splenic flexure (%.2f m) pushing on with a straight "
	       "tip\n# (the tip is held, a loop forms behind it), withdrawing "
	       "to reduce it,\n# then steering through with a quarter twist in "
	       "the transverse colon\n# to the cecum (%.2f m), and withdrawing."
	       "\n# TIME AXIS target VALUE RAMP (daemon/rig/scenario.h)\n",
	       a->name, speed * 1000, flexure, cecum);
	g.d = 0.03;
	hold(&g, 1.0);
	move(&g, flexure - 0.04, 0, speed, 1);
	move(&g, flexure + 0.10, 0, speed, 0);  /* the mistake */
	hold(&g, 1.5);
	move(&g, flexure - 0.06, 0, speed * 2, 1);
	move(&g, flexure + 0.30, M_PI / 2, speed, 1);
	move(&g, cecum, 0, speed, 1);
	hold(&g, 2.0);
	move(&g, 0.10, 0, speed * 2, 1);
	printf("%7.2f end\n", g.t + 1);
	colon_destroy(g.colon);
	return 0;
}

/* The rod model's course, played as it is written. */
static int rod_course(const char *case_path, const struct anatomy *a,
		      double speed)
{
	struct config cfg;
	struct trainee *t;
	char err[256];
	bool there;

	trainee_demo_config(&cfg);
	printf("# endosim scenario for case '%s', written by scenario_gen "
	       "(the rod model,\n"
	       "# the patient enabled: endosimd --set patient.enabled=yes "
	       "plays it as it\n"
	       "# was written): a trainee inserting at %.0f mm/s, steering "
	       "into the lumen\n"
	       "# ahead of the tip, insufflating when it closes and washing "
	       "the lens when it\n"
	       "# smears; at the sigmoid's end pushing on 15 cm with a "
	       "straight tip (a loop\n"
	       "# forms: she asks for the assistant's hand over it), "
	       "withdrawing 15 cm with a\n"
	       "# clockwise twist to reduce it, on to the cecum (reducing "
	       "again whenever the\n"
	       "# scope is stuck, the hand on, then the patient turned), and "
	       "withdrawing with\n"
	       "# the segment examined turned uppermost. Played on endosimd's "
	       "force loop as it\n"
	       "# was written (tests/tools/trainee.h).\n"
	       "# TIME AXIS target VALUE RAMP, TIME valve ..., TIME patient "
	       "... (scenario.h)\n",
	       a->name, speed * 1000);
	t = trainee_create(&cfg, case_path, stdout, err, sizeof(err));
	if (!t) {
		fprintf(stderr, "scenario_gen: %s\n", err);
		return 1;
	}
	there = trainee_course(t, a, speed);
	trainee_destroy(t);
	if (!there) {
		fprintf(stderr, "scenario_gen: the course did not reach the "
			"cecum\n");
		return 1;
	}
	return 0;
}

int main(int argc, char **argv)
{
	bool paper = false;
	struct anatomy a;
	char err[256];
	double speed;
	int arg = 1;

	if (argc > 2 && !strcmp(argv[1], "--model")) {
		paper = !strcmp(argv[2], "paper");
		if (!paper && strcmp(argv[2], "rod")) {
			arg = argc; /* usage */
		}
		arg += 2;
	}
	if (arg >= argc || anatomy_load(&a, argv[arg], err, sizeof(err))) {
		fprintf(stderr, "usage: scenario_gen [--model rod|paper] "
			"CASE_FILE [SPEED_M_PER_S]%s%s\n",
			arg >= argc ? "" : ": ", arg >= argc ? "" : err);
		return 2;
	}
	speed = arg + 1 < argc ? atof(argv[arg + 1]) : paper ? 0.04 : 0.03;
	return paper ? paper_course(&a, speed)
		     : rod_course(argv[arg], &a, speed);
}
