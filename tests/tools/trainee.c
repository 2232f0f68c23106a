/* trainee.c - see trainee.h. */
#include "trainee.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "conf/cases.h"
#include "rig/scenario.h"
#include "base/vec3.h"

#define STEER_AHEAD_M 0.04   /* she looks this far down the lumen */
#define STEER_GAIN 0.5       /* rad of bend per waypoint per unit error */
#define WHEEL_EASE_NM 0.06   /* a wheel this hard on her thumb: ease it */
#define WHEEL_EASE 0.8       /* ... by this much a waypoint */
#define PUSH_MAX_N 16        /* she does not push harder to go on */

struct trainee {
	struct offline *off;
	struct scenario *scn;     /* the offline hand's: appended to */
	FILE *script;
	const struct endosim_state *s;
	double t;                 /* the next waypoint's time, s */
	double depth, roll;       /* the hand's targets */
	double bend[2];           /* the tip's bends she wants: ud, lr */
	double gain[2];           /* tip rad per wheel rad */
	double wheel_max;         /* rad */
	double bend_max[2];
	void (*watch)(const struct endosim_state *s, void *arg);
	void *watch_arg;
};

struct trainee *trainee_create(const struct config *cfg, const char *case_path,
			       FILE *script, char *err, size_t errsize)
{
	struct trainee *t = calloc(1, sizeof(*t));
	struct config c = *cfg;
	struct colon *colon;

	if (!t) {
		snprintf(err, errsize, "out of memory");
		return NULL;
	}
	snprintf(c.colon.file, sizeof(c.colon.file), "%s", case_path);
	colon = cases_load(&c, NULL, err, errsize);
	t->scn = colon ? scenario_create() : NULL;
	if (!t->scn) {
		if (colon) {
			snprintf(err, errsize, "out of memory");
		}
		colon_destroy(colon);
		free(t);
		return NULL;
	}
	t->off = offline_create_with(&c, colon, t->scn, err, errsize);
	if (!t->off) {
		free(t);
		return NULL;
	}
	t->script = script;
	for (int w = 0; w < 2; w++) {
		t->gain[w] = cfg->scope.gain[w];
		t->bend_max[w] = cfg->scope.limit_rad[w];
	}
	t->wheel_max = 0.95 * cfg->rig.travel_max[ENDOSIM_AXIS_WHEEL_UD];
	t->s = offline_step(t->off); /* cycle 0: the state before she acts */
	return t;
}

void trainee_destroy(struct trainee *t)
{
	if (!t) {
		return;
	}
	if (t->script) {
		fprintf(t->script, "%7.2f end\n", t->t + 1);
	}
	offline_destroy(t->off);
	free(t);
}

const struct endosim_state *trainee_state(const struct trainee *t)
{
	return t->s;
}

const struct colon *trainee_colon(const struct trainee *t)
{
	return offline_colon(t->off);
}

double trainee_time(const struct trainee *t)
{
	return t->s->scenario_time_s;
}

void trainee_watch(struct trainee *t,
		   void (*fn)(const struct endosim_state *s, void *arg),
		   void *arg)
{
	t->watch = fn;
	t->watch_arg = arg;
}

/* One line of the script, played as written. */
static void say(struct trainee *t, const char *axis, double value)
{
	char line[128], err[256];

	snprintf(line, sizeof(line), "%7.2f %-9s target %.4f %.2f", t->t, axis,
		 value, TRAINEE_STEP_S);
	if (scenario_append(t->scn, line, err, sizeof(err))) {
		fprintf(stderr, "trainee: %s\n", err); /* a bug of hers */
		abort();
	}
	if (t->script) {
		fprintf(t->script, "%s\n", line);
	}
}

/* The waypoint of now, then the cycles up to the next. */
static void waypoint(struct trainee *t)
{
	static const char *const wheel[2] = { "wheel_ud", "wheel_lr" };

	say(t, "insertion", t->depth);
	say(t, "roll", t->roll);
	for (int w = 0; w < 2; w++) {
		double v = t->gain[w] > 0 ? t->bend[w] / t->gain[w] : 0;

		say(t, wheel[w], fmax(-t->wheel_max, fmin(t->wheel_max, v)));
	}
	t->t += TRAINEE_STEP_S;
	/* up to the cycle before the next waypoint's: hers are in the
	 * script before that cycle plays, as a file's would be */
	while (t->s->scenario_time_s + OFFLINE_PERIOD_NS * ENDOSIM_S_PER_NS <
	       t->t - 1e-9) {
		t->s = offline_step(t->off);
		if (t->watch) {
			t->watch(t->s, t->watch_arg);
		}
	}
}

/* Bends the tip towards the lumen ahead; eases a wheel that pushes
 * back hard. */
static void steer(struct trainee *t)
{
	const struct centreline *cl = colon_centreline(trainee_colon(t));
	const struct endosim_scope_state *sc = &t->s->scope;
	struct centreline_point ahead;
	double e[3], right[3];

	centreline_at_s(cl, fmin(sc->tip_s_m + STEER_AHEAD_M,
				 centreline_length(cl)), &ahead);
	vec3_sub(e, ahead.p, sc->tip);
	if (vec3_normalize(e) == 0) {
		return;
	}
	vec3_cross(right, sc->dir, sc->up);
	t->bend[0] += STEER_GAIN * vec3_dot(e, sc->up);
	t->bend[1] += STEER_GAIN * vec3_dot(e, right);
	for (int w = 0; w < 2; w++) {
		double torque = t->s->axis[ENDOSIM_AXIS_WHEEL_UD + w].command;

		if (fabs(torque) > WHEEL_EASE_NM) {
			t->bend[w] *= WHEEL_EASE;
		}
		t->bend[w] = fmax(-t->bend_max[w], fmin(t->bend_max[w],
							 t->bend[w]));
	}
}

bool trainee_insert(struct trainee *t, double tip_s_m, double speed,
		    double stuck_s)
{
	double best = t->s->scope.tip_s_m, since = trainee_time(t);

	while (t->s->scope.tip_s_m < tip_s_m) {
		if (t->s->axis[ENDOSIM_AXIS_INSERTION].hand < PUSH_MAX_N) {
			t->depth += speed * TRAINEE_STEP_S;
		}
		steer(t);
		waypoint(t);
		if (t->s->scope.tip_s_m > best + 0.005) {
			best = t->s->scope.tip_s_m;
			since = trainee_time(t);
		} else if (trainee_time(t) - since > stuck_s) {
			return false;
		}
	}
	return true;
}

/* Moves the targets by DDEPTH and DROLL over the time DDEPTH takes at
 * SPEED, the tip straightening. */
static void move(struct trainee *t, double ddepth, double droll, double speed)
{
	int steps = (int)ceil(fabs(ddepth) / (speed * TRAINEE_STEP_S));

	for (int i = 0; i < steps; i++) {
		t->depth += ddepth / steps;
		t->roll += droll / steps;
		t->bend[0] *= 0.5;
		t->bend[1] *= 0.5;
		waypoint(t);
	}
}

void trainee_push(struct trainee *t, double distance, double speed)
{
	move(t, distance, 0, speed);
}

void trainee_withdraw(struct trainee *t, double distance, double speed,
		      double twist_rad)
{
	move(t, -distance, twist_rad, speed);
}

void trainee_withdraw_looking(struct trainee *t, double distance,
			      double speed, double look_rad, double circle_s)
{
	int steps = (int)ceil(distance / (speed * TRAINEE_STEP_S));

	for (int i = 0; i < steps; i++) {
		double phi = 2 * M_PI * (i + 1) * TRAINEE_STEP_S / circle_s;

		t->depth -= distance / steps;
		t->bend[0] = look_rad * cos(phi);
		t->bend[1] = look_rad * sin(phi);
		waypoint(t);
	}
	t->bend[0] = t->bend[1] = 0;
}

void trainee_hold(struct trainee *t, double seconds)
{
	for (double s = 0; s < seconds - 1e-9; s += TRAINEE_STEP_S) {
		waypoint(t);
	}
}

void trainee_relax(struct trainee *t, double seconds)
{
	t->depth = t->s->axis[ENDOSIM_AXIS_INSERTION].position;
	t->roll = t->s->axis[ENDOSIM_AXIS_ROLL].position;
	trainee_hold(t, seconds);
}

void trainee_hold_tip(struct trainee *t, double hold_n_per_m)
{
	offline_hold_tip(t->off, hold_n_per_m);
}

bool trainee_reach(struct trainee *t, double tip_s_m, double speed,
		   double push_m)
{
	for (int tries = 0; tries < 6; tries++) {
		if (trainee_insert(t, tip_s_m, speed, 4)) {
			return true;
		}
		if (push_m > 0) {
			trainee_push(t, push_m, speed);
		}
		trainee_withdraw(t, 0.10, speed, 0.5);
		trainee_relax(t, 0.5);
		if (t->s->scope.tip_s_m >= tip_s_m) {
			return true;
		}
	}
	return false;
}

bool trainee_course(struct trainee *t, const struct anatomy *a, double speed)
{
	double junction = anatomy_segment_start(a, ANATOMY_DESCENDING);
	double cecum = anatomy_segment_start(a, ANATOMY_CECUM) + 0.02;
	bool there;

	trainee_hold(t, 1.0);
	trainee_insert(t, junction - 0.01, speed, 6);
	trainee_push(t, 0.15, speed);
	trainee_withdraw(t, 0.15, speed, 0.5);
	trainee_relax(t, 1.0);
	there = trainee_reach(t, cecum, speed, 0);
	trainee_hold(t, 2.0);
	trainee_withdraw(t, t->s->scope.depth_m - 0.10, 2 * speed, 0);
	return there;
}
