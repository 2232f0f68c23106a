/* trainee.c - see trainee.h. */
#include "trainee.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "conf/cases.h"
#include "model/gas.h"
#include "model/tool.h"
#include "model/posture.h"
#include "rig/scenario.h"
#include "base/vec3.h"

#define STEER_AHEAD_M 0.04   /* she looks this far down the lumen */
#define STEER_GAIN 0.5       /* rad of bend per waypoint per unit error */
#define WHEEL_EASE_NM 0.06   /* a wheel this hard on her thumb: ease it */
#define WHEEL_EASE 0.8       /* ... by this much a waypoint */
#define PUSH_MAX_N 16        /* she does not push harder to go on */
/* The patient's care (trainee.h) */
#define VIEW_AHEAD_M STEER_AHEAD_M /* she judges the lumen where she steers */
#define VIEW_CLOSED 0.6      /* the lumen's radius factor there: closed */
#define VIEW_OPEN 0.8        /* open enough: she stops insufflating */
#define PRESSURE_MAX_PA (25 * GAS_PA_PER_MMHG) /* she never goes beyond */
#define LENS_DIRTY 0.3       /* smear or murk: she washes the lens ... */
#define LENS_CLEAN 0.05      /* ... until it is clear */
#define LOOP_HELP_M 0.03     /* a mobile span bowed this far ... */
#define LOOP_HELP_N 10       /* ... and her push this hard: a loop, help */
#define EASE_PAIN 3.0        /* the patient's face this pained: she eases */
#define CALM_PAIN 1.5        /* ... until it is back under this ... */
#define EASE_MAX_S 8.0       /* ... or this long has passed */
/* Aiming the tool (trainee_aim()) */
#define AIM_GAIN 0.5         /* of the error corrected a waypoint */
#define AIM_ROLL_MAX 0.3     /* rad a waypoint, at most */
#define AIM_BEND_MAX 0.1     /* ... of bend */
#define AIM_IN_MAX 0.005     /* m a waypoint, in or out, at most */
#define AIM_BEND_AHEAD 0.3   /* rad her wheels ask beyond the tip's bend */
#define AIM_IN_AHEAD 0.01    /* m her insertion asks beyond the carriage */
#define AIM_ROLL_AHEAD 0.3   /* rad her roll asks beyond the tube's */
#define AIM_TOOL_MIN_M 0.003 /* the tool out of the channel, at least */
#define AIM_TOOL_MAX_M 0.050 /* ... at most: then the scope moves in */
#define AIM_TOOL_M 0.030     /* ... where she likes it (shorter, the
				scope nearer the wall and bent more) */
#define AIM_BACK 0.2         /* ... of the difference a waypoint */
#define AIM_SETTLED 2        /* waypoints within the tolerance: there */

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
	double bending_m;         /* the bending section's length */
	double roll_min, roll_max; /* rad, within the rig's travel */
	uint32_t valves;          /* the valves she holds */
	uint32_t holding;         /* ... of them, by her own decision (the
				     suction: trainee_suction()), whatever
				     the view asks for */
	int pressing;             /* the site the assistant presses, -1 */
	bool turned;              /* she had the patient turned for a loop */
	bool examining;           /* withdrawing: the segment seen uppermost */
	bool mindful;             /* she eases off when the patient hurts */
	struct trainee_actions did;
	void (*watch)(const struct endosim_state *s, void *arg);
	void *watch_arg;
};

void trainee_demo_config(struct config *cfg)
{
	config_defaults(cfg);
	cfg->haptics.model = HAPTICS_MODEL_ROD;
	cfg->patient.enabled = true;
}

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
	t->pressing = -1;
	for (int w = 0; w < 2; w++) {
		t->gain[w] = cfg->scope.gain[w];
		t->bend_max[w] = cfg->scope.limit_rad[w];
	}
	t->bending_m = cfg->scope.bending_length_m;
	t->roll_min = 0.9 * cfg->rig.travel_min[ENDOSIM_AXIS_ROLL];
	t->roll_max = 0.9 * cfg->rig.travel_max[ENDOSIM_AXIS_ROLL];
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

struct offline *trainee_offline(struct trainee *t)
{
	return t->off;
}

const struct colon *trainee_colon(const struct trainee *t)
{
	return offline_colon(t->off);
}

const struct trainee_actions *trainee_did(const struct trainee *t)
{
	return &t->did;
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

/* One line of the script at the next waypoint's time (FMT: what follows
 * the time), played as written. */
static void say(struct trainee *t, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

static void say(struct trainee *t, const char *fmt, ...)
{
	char line[128], err[256];
	va_list ap;
	int n = snprintf(line, sizeof(line), "%7.2f ", t->t);

	va_start(ap, fmt);
	vsnprintf(line + n, sizeof(line) - (size_t)n, fmt, ap);
	va_end(ap);
	if (scenario_append(t->scn, line, err, sizeof(err))) {
		fprintf(stderr, "trainee: %s\n", err); /* a bug of hers */
		abort();
	}
	if (t->script) {
		fprintf(t->script, "%s\n", line);
	}
}

/*
 * Whether the next waypoint's time is still to be played: not before her
 * first waypoint (trainee_create() played cycle 0, at time 0, before she
 * said anything). A target said then changes nothing (it ramps from where
 * the axis is), a valve or the assistant would: the file would hold a
 * line at a time the loop played without it.
 */
static bool to_play(const struct trainee *t)
{
	return t->t > t->s->scenario_time_s;
}

/* A line for the valves or the assistant, from the next waypoint on. */
static void say_patient(struct trainee *t, const char *what)
{
	if (!to_play(t)) {
		fprintf(stderr, "trainee: '%s' before her first waypoint\n",
			what); /* a bug of the caller's */
		abort();
	}
	say(t, "%s", what);
}

/* The hand's target on AXIS, reached over a waypoint's time. */
static void say_target(struct trainee *t, const char *axis, double value)
{
	say(t, "%-9s target %.4f %.2f", axis, value, TRAINEE_STEP_S);
}

/* Holds the valves WANT from the next waypoint on, a line for each that
 * changes. */
static void valves(struct trainee *t, uint32_t want)
{
	static const char *const name[] = { "air", "water", "suction" };

	for (int v = 0; v < 3; v++) {
		uint32_t bit = 1u << v;

		if ((want ^ t->valves) & bit) {
			char line[32];

			snprintf(line, sizeof(line), "valve %s %s", name[v],
				 want & bit ? "on" : "off");
			say_patient(t, line);
		}
	}
	t->did.insufflations += (want & ~t->valves & ENDOSIM_VALVE_AIR) != 0;
	t->did.washes += (want & ~t->valves & ENDOSIM_VALVE_WATER) != 0;
	t->valves = want;
}

/* The lumen's radius factor where she looks ahead of the tip. */
static double view_ahead(const struct trainee *t)
{
	const struct colon *c = trainee_colon(t);

	return gas_factor_at(c, t->s->patient.factor,
			     fmin(t->s->scope.tip_s_m + VIEW_AHEAD_M,
				  centreline_length(colon_centreline(c))));
}

/*
 * What she does for the view, each waypoint, from what the screen shows:
 * the lens smeared or murky, she presses the air/water valve (the jet)
 * until it is clear; else the lumen ahead closed, she covers it
 * (insufflates) until it is open, never beyond PRESSURE_MAX_PA.
 */
static void care(struct trainee *t)
{
	const struct endosim_patient_state *p = &t->s->patient;
	double dirt = fmax(p->lens_smear, p->lens_murk), view;
	bool air = t->valves & ENDOSIM_VALVE_AIR;

	if (!p->enabled || !to_play(t)) {
		return;
	}
	if (dirt > LENS_DIRTY ||
	    (t->valves & ENDOSIM_VALVE_WATER && dirt > LENS_CLEAN)) {
		valves(t, ENDOSIM_VALVE_WATER | t->holding);
		return;
	}
	view = view_ahead(t);
	if (p->pressure_pa >= PRESSURE_MAX_PA || view >= VIEW_OPEN) {
		air = false;
	} else if (view < VIEW_CLOSED) {
		air = true;
	}
	valves(t, (air ? ENDOSIM_VALVE_AIR : 0) | t->holding);
}

void trainee_suction(struct trainee *t, bool on)
{
	uint32_t bit = ENDOSIM_VALVE_SUCTION;

	t->holding = on ? t->holding | bit : t->holding & ~bit;
	valves(t, on ? t->valves | bit : t->valves & ~bit);
}

/*
 * The position that lays the segment at material S_M uppermost, where the
 * gas opens it most (East et al.'s positions for the withdrawal): left
 * lateral for the right colon (the cecum to the hepatic flexure), supine
 * for the transverse, right lateral for the left colon (the splenic
 * flexure to the sigmoid); -1 below (the rectum: as it is).
 */
static int uppermost(const struct anatomy *a, double s_m)
{
	if (s_m >= anatomy_segment_start(a, ANATOMY_HEPATIC_FLEXURE)) {
		return POSTURE_LEFT_LATERAL;
	}
	if (s_m >= anatomy_segment_start(a, ANATOMY_TRANSVERSE)) {
		return POSTURE_SUPINE;
	}
	if (s_m >= anatomy_segment_start(a, ANATOMY_SIGMOID)) {
		return POSTURE_RIGHT_LATERAL;
	}
	return -1;
}

/* Examining on the way out: the segment the tip is in turned uppermost. */
static void examine(struct trainee *t)
{
	const struct anatomy *a = colon_anatomy(trainee_colon(t));
	int want;

	if (!t->examining || !t->s->patient.enabled || !a || !to_play(t)) {
		return;
	}
	want = uppermost(a, t->s->scope.tip_s_m);
	if (want >= 0 && want != (int)t->s->patient.position) {
		trainee_turn(t, want);
	}
}

/* The waypoint of now, then the cycles up to the next. */
static void waypoint(struct trainee *t)
{
	static const char *const wheel[2] = { "wheel_ud", "wheel_lr" };

	care(t);
	examine(t);

	say_target(t, "insertion", t->depth);
	say_target(t, "roll", t->roll);
	for (int w = 0; w < 2; w++) {
		double v = t->gain[w] > 0 ? t->bend[w] / t->gain[w] : 0;

		say_target(t, wheel[w],
			   fmax(-t->wheel_max, fmin(t->wheel_max, v)));
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

void trainee_mind_patient(struct trainee *t, bool mindful)
{
	t->mindful = mindful;
}

/* Minding the patient: while the patient hurts she neither pushes nor
 * pulls, letting the tube settle where it wants, until the pain has
 * eased. Whether she did. */
static bool mind(struct trainee *t)
{
	double since = trainee_time(t);

	if (!t->mindful || t->s->patient.pain < EASE_PAIN) {
		return false;
	}
	while (t->s->patient.pain >= CALM_PAIN &&
	       trainee_time(t) - since < EASE_MAX_S) {
		t->depth = t->s->axis[ENDOSIM_AXIS_INSERTION].position;
		t->roll = t->s->axis[ENDOSIM_AXIS_ROLL].position;
		waypoint(t);
	}
	return true;
}

static void ask_help(struct trainee *t);

bool trainee_insert(struct trainee *t, double tip_s_m, double speed,
		    double stuck_s)
{
	double best = t->s->scope.tip_s_m, since = trainee_time(t);

	while (t->s->scope.tip_s_m < tip_s_m) {
		if (mind(t)) {
			continue; /* the stuck clock ran on meanwhile */
		}
		if (t->s->patient.turning) { /* she waits, easing off */
			t->depth = t->s->axis[ENDOSIM_AXIS_INSERTION].position;
			since = trainee_time(t);
		} else if (t->s->axis[ENDOSIM_AXIS_INSERTION].hand < PUSH_MAX_N) {
			t->depth += speed * TRAINEE_STEP_S;
		}
		steer(t);
		waypoint(t);
		if (t->s->axis[ENDOSIM_AXIS_INSERTION].hand > LOOP_HELP_N) {
			ask_help(t);
		}
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
		mind(t);
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

void trainee_press(struct trainee *t, const char *site, double force_n)
{
	char line[96];

	if (force_n > 0) {
		snprintf(line, sizeof(line), "patient press %s %.0f", site,
			 force_n);
	} else {
		snprintf(line, sizeof(line), "patient press %s", site);
	}
	say_patient(t, line);
	t->did.hands++;
}

void trainee_release(struct trainee *t)
{
	say_patient(t, "patient release");
}

void trainee_turn(struct trainee *t, int position)
{
	char line[64];

	snprintf(line, sizeof(line), "patient position %s",
		 posture_name(position));
	say_patient(t, line);
	t->did.turns++;
}

void trainee_hold_tip(struct trainee *t, double hold_n_per_m)
{
	offline_hold_tip(t->off, hold_n_per_m);
}

/* The case's site nearest to where mobile span SPAN has moved furthest
 * from its rest: over the loop. -1: the case has none. */
static int site_over(const struct trainee *t, int span)
{
	const struct colon *c = trainee_colon(t);
	const struct anatomy *a = colon_anatomy(c);
	const struct centreline *cl = colon_centreline(c);
	double ds = centreline_step(cl), s0, s1, most = -1, best = INFINITY;
	size_t at = 0;
	int site = -1;

	centreline_span_range(cl, span, &s0, &s1);
	for (size_t i = (size_t)ceil(s0 / ds); i * ds <= s1; i++) {
		double d = vec3_dist(centreline_sample(cl, i)->p,
				     centreline_base(cl, i)->p);

		if (d > most) {
			most = d;
			at = i;
		}
	}
	for (int k = 0; a && k < a->sites; k++) {
		double d = vec3_dist(a->site[k].position_m,
				     centreline_sample(cl, at)->p);

		if (d < best) {
			best = d;
			site = k;
		}
	}
	return site;
}

/*
 * Stuck with a loop (a mobile span bowed LOOP_HELP_M or more), she asks
 * for help, once each: the assistant's hand over the loop; the hand
 * there already, a turn of the patient.
 */
static void ask_help(struct trainee *t)
{
	const struct endosim_scope_state *sc = &t->s->scope;
	const struct anatomy *a = colon_anatomy(trainee_colon(t));
	int span = 0, site;

	if (!t->s->patient.enabled || !sc->spans) {
		return;
	}
	for (int k = 1; k < (int)sc->spans; k++) {
		span = sc->bow_m[k] > sc->bow_m[span] ? k : span;
	}
	if (sc->bow_m[span] < LOOP_HELP_M) {
		return;
	}
	site = site_over(t, span);
	if (site >= 0 && site != t->pressing) {
		trainee_press(t, a->site[site].name, 0);
		t->pressing = site;
	} else if (!t->turned) {
		trainee_turn(t, t->s->patient.position == POSTURE_SUPINE
					? POSTURE_LEFT_LATERAL : POSTURE_SUPINE);
		t->turned = true;
	}
}

/* Past the loop: the assistant lets go, ready to help again. */
static void help_done(struct trainee *t)
{
	if (t->pressing >= 0) {
		trainee_release(t);
		t->pressing = -1;
	}
	t->turned = false;
}

bool trainee_reach(struct trainee *t, double tip_s_m, double speed,
		   double push_m)
{
	for (int tries = 0; tries < 6; tries++) {
		if (trainee_insert(t, tip_s_m, speed, 4)) {
			help_done(t);
			return true;
		}
		if (push_m > 0) {
			trainee_push(t, push_m, speed);
		}
		ask_help(t);
		trainee_withdraw(t, 0.10, speed, 0.5);
		trainee_relax(t, 0.5);
		if (t->s->scope.tip_s_m >= tip_s_m) {
			help_done(t);
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
	ask_help(t);
	trainee_withdraw(t, 0.15, speed, 0.5);
	trainee_relax(t, 1.0);
	there = trainee_reach(t, cecum, speed, 0);
	t->examining = true;
	trainee_relax(t, 2.0);
	trainee_withdraw(t, t->s->scope.depth_m - 0.10, 2 * speed, 0);
	t->examining = false;
	return there;
}

static double clampd(double x, double lim)
{
	return fmax(-lim, fmin(lim, x));
}

/* X, at most AHEAD from where the axis is, AT. */
static double near(double x, double at, double ahead)
{
	return at + clampd(x - at, ahead);
}

/* Rolls on by DROLL_RAD, turning the wheels against it so that the bent
 * tip keeps its way (the bends are the roll's frame's: (ud, lr) turned
 * by -DROLL_RAD bends the same way after it); the image turns. */
static void turn(struct trainee *t, double droll_rad)
{
	double c = cos(droll_rad), s = sin(droll_rad), ud = t->bend[0];

	t->roll += droll_rad;
	t->bend[0] = ud * c + t->bend[1] * s;
	t->bend[1] = -ud * s + t->bend[1] * c;
}

/* The roll (rad) that turns the image by ERR_RAD: the shorter way, unless
 * that runs the tube's roll out of the rig's travel. */
static double roll_to(const struct trainee *t, double err_rad)
{
	double d = remainder(err_rad, 2 * M_PI);
	double other = d - copysign(2 * M_PI, d);

	return t->roll + d > t->roll_max || t->roll + d < t->roll_min ? other
								      : d;
}

/* She turns the polyp's wall (WALL: its normal into the lumen) to the
 * channel's clock in the image: the clock of the way out to it, in the
 * camera's up and right (a point at angle psi round the tip's axis shows
 * at psi less the roll: rolling on by the clock's error brings it
 * there), the wheels turned against the roll. */
static void aim_turn(struct trainee *t, const struct tool_params *par,
		     const double wall[3])
{
	const struct endosim_scope_state *sc = &t->s->scope;
	double right[3], clock;

	vec3_cross(right, sc->dir, sc->up);
	clock = atan2(-vec3_dot(wall, right), -vec3_dot(wall, sc->up));
	turn(t, clampd(AIM_GAIN * roll_to(t, clock - par->channel_angle_rad),
		       AIM_ROLL_MAX));
	t->roll = near(t->roll, t->s->axis[ENDOSIM_AXIS_ROLL].position,
		       AIM_ROLL_AHEAD);
}

/* She swings the tip to move the aimed point, REACH_M ahead of the
 * bending section's end, by E (m) across the view: a bend of b moves it
 * by about (Lb / 2 + REACH_M) b. */
static void aim_swing(struct trainee *t, const double e[3], double reach_m)
{
	const struct endosim_scope_state *sc = &t->s->scope;
	double right[3], lever = t->bending_m / 2 + reach_m;

	vec3_cross(right, sc->dir, sc->up);
	t->bend[0] += clampd(AIM_GAIN * vec3_dot(e, sc->up) / lever,
			     AIM_BEND_MAX);
	t->bend[1] += clampd(AIM_GAIN * vec3_dot(e, right) / lever,
			     AIM_BEND_MAX);
	for (int w = 0; w < 2; w++) {
		t->bend[w] = near(t->bend[w], sc->bend_rad[w], AIM_BEND_AHEAD);
		t->bend[w] = clampd(t->bend[w], t->bend_max[w]);
	}
}

/* She moves the aimed point by E (m) along the view: the tool's depth
 * *DEPTH_M first; the scope in or out for what the tool cannot, and to
 * bring the tool back to the depth she likes (AIM_TOOL_M). DEPTH_M NULL:
 * the scope alone (the tool in the channel). */
static void aim_reach(struct trainee *t, const double e[3], double *depth_m)
{
	double fw = AIM_GAIN * vec3_dot(e, t->s->scope.dir), tool = 0, back = 0;

	if (depth_m) {
		double was = *depth_m;

		*depth_m = fmax(AIM_TOOL_MIN_M, fmin(AIM_TOOL_MAX_M, was + fw));
		tool = *depth_m - was;
		back = AIM_BACK * (*depth_m - AIM_TOOL_M);
	}
	t->depth += clampd(fw - tool + back, AIM_IN_MAX);
	t->depth = near(t->depth, t->s->axis[ENDOSIM_AXIS_INSERTION].position,
			AIM_IN_AHEAD);
}

/*
 * One waypoint's aim from what she sees (the published scope: where it
 * is, not where she asked it to be, so that nothing winds up against the
 * wall): the turn, the swing, the reach. Returns the aimed point's
 * distance from TARGET (m) before it.
 */
static double aim_step(struct trainee *t, const struct tool_params *par,
		       const double target[3], const double wall[3],
		       double *depth_m, double beyond_m)
{
	double reach_m = (depth_m ? *depth_m : 0) + beyond_m, e[3], x[3];
	struct tool_pose q;

	tool_pose(par, &t->s->scope, 0, &q);
	vec3_axpy(x, q.exit, reach_m, q.dir);
	vec3_sub(e, target, x);
	aim_turn(t, par, wall);
	aim_swing(t, e, reach_m);
	aim_reach(t, e, depth_m);
	return vec3_norm(e);
}

/* trainee_aim(), or with DEPTH_M NULL trainee_approach(). */
static bool aim(struct trainee *t, const struct tool_params *par,
		const double target[3], const double wall[3], double *depth_m,
		double beyond_m, double tol_m, double max_s)
{
	double since = trainee_time(t);
	int settled = 0;

	while (trainee_time(t) - since < max_s) {
		double e = aim_step(t, par, target, wall, depth_m, beyond_m);

		settled = e <= tol_m ? settled + 1 : 0;
		if (settled >= AIM_SETTLED) {
			return true;
		}
		waypoint(t);
	}
	return false;
}

bool trainee_aim(struct trainee *t, const struct tool_params *par,
		 const double target[3], const double wall[3],
		 double *depth_m, double beyond_m, double tol_m, double max_s)
{
	return aim(t, par, target, wall, depth_m, beyond_m, tol_m, max_s);
}

bool trainee_approach(struct trainee *t, const struct tool_params *par,
		      const double target[3], const double wall[3],
		      double tol_m, double max_s)
{
	return aim(t, par, target, wall, NULL, 0, tol_m, max_s);
}
