/*
 * trainee.h - a scripted trainee who decides as she goes: the simulated
 * hand on endosimd's force loop in lockstep (offline.h), driven by a
 * scenario that the trainee writes while it plays (scenario_append()),
 * one waypoint per axis every TRAINEE_STEP_S. The script she leaves behind
 * is an ordinary scenario file: played by the daemon on the same case and
 * configuration, it moves the rig exactly as it moved here (the loop runs
 * bit for bit the same).
 *
 * What she does, each waypoint, from the published state (as a trainee
 * reads the screen and feels the handle):
 *  - steering: the lumen ahead is the centreline STEER_AHEAD_M beyond the
 *    sample nearest the tip; she turns the wheels to bend the tip towards
 *    it (the direction's parts along the camera's up and right), and eases
 *    them back towards straight when a wheel pushes her thumb hard;
 *  - inserting: the carriage's target moves on at her pace, but waits
 *    while the hand already pushes harder than she would (the scope is
 *    stuck: she does not shove), until she gives up on it;
 *  - pushing on (the classic mistake), withdrawing with a twist (the
 *    classic reduction), holding still;
 *  - aiming a tool in the working channel at a polyp (trainee_aim()),
 *    bringing the channel's exit to a cut one and sucking it out
 *    (trainee_approach(), trainee_suction()).
 *
 * With the patient enabled ([patient] enabled, struct endosim_state
 * .patient) she also looks after the view and the patient, each action a
 * line of her script (a valve, or the assistant: scenario.h), said from
 * her second waypoint on (the first one's time was played before she
 * could act):
 *  - the view closes: the lumen's radius factor 4 cm ahead of the tip
 *    (where she steers; gas_factor_at() on the published factors) below
 *    0.6 (the folds nearly meeting; collapsed is 0.4 in the cases), she
 *    covers the air/water valve, and lets go once it is 0.8 or more, or
 *    the gas reaches 25 mmHg: she never insufflates beyond (Kozarek et
 *    al. measured 9-57 mmHg with the tip free);
 *  - the lens smears: smear or murk above 0.3, she presses the valve
 *    (the jet; no air meanwhile) until both are under 0.05;
 *  - a loop: a mobile span bowed 3 cm or more while she pushes harder
 *    than 10 N, or stops her (trainee_reach()), or after her mistake in
 *    the course: she asks for the assistant's hand on the case's site
 *    nearest where that span has moved furthest (llq over the sigmoid,
 *    umbilical over the transverse colon); if the hand is there
 *    already, she has the patient turned (supine from a lateral
 *    position, left lateral from supine or prone; once), and while the
 *    patient is turned she waits, easing off; once she has got where she
 *    was going the assistant lets go (and she may ask again);
 *  - on the way out (trainee_course()): the segment the tip is in turned
 *    uppermost (East et al.): left lateral for the right colon, supine
 *    for the transverse, right lateral for the left colon.
 * With the patient disabled she says none of these lines and does as
 * before the patient.
 *
 * Not for the force loop (allocates, writes the script). One thread.
 */
#ifndef ENDOSIM_TRAINEE_H
#define ENDOSIM_TRAINEE_H

#include <stdbool.h>
#include <stdio.h>

#include "model/anatomy.h"
#include "model/colon.h"
#include "conf/config.h"
#include "proto/endosim_shm.h"
#include "offline.h"

#define TRAINEE_STEP_S 0.25 /* a waypoint this often */

/* What she asked for so far: each a line of her script. */
struct trainee_actions {
	int insufflations;  /* the air/water valve covered */
	int washes;         /* ... pressed: the jet */
	int hands;          /* the assistant's press */
	int turns;          /* the patient turned */
};

struct trainee;
struct tool_params;

/*
 * The demo's configuration (scenario_gen's, config/scenarios/demo.scn's):
 * the defaults with the rod model and the patient (tests/demo.sh runs
 * the daemon so).
 */
void trainee_demo_config(struct config *cfg);

/*
 * The trainee on CASE (a case file) with CFG, writing her script to
 * SCRIPT (may be NULL). NULL with one line in ERR.
 */
struct trainee *trainee_create(const struct config *cfg, const char *case_path,
			       FILE *script, char *err, size_t errsize);

/* Ends the script ("TIME end"). NULL is fine. */
void trainee_destroy(struct trainee *t);

/*
 * Whether she minds the patient (the expert does; not at first): when
 * the patient's pain reaches 3 of 10 (the face and the voice tell her)
 * she stops pushing or pulling, the hand's targets where the carriage and
 * the roll are, and waits until the pain is under 1.5 or 8 s have
 * passed, then goes on (inserting, the wait counts towards being stuck,
 * so that a loop that hurts each time she pushes is reduced).
 */
void trainee_mind_patient(struct trainee *t, bool mindful);

/* The loop she plays on (offline.h), for a caller who adds inputs of
 * its own to hers (the tool in the working channel, from a
 * trainee_watch() callback: offline_tool_input()). */
struct offline *trainee_offline(struct trainee *t);

/* The loop's latest state, its colon. */
const struct endosim_state *trainee_state(const struct trainee *t);
const struct colon *trainee_colon(const struct trainee *t);
double trainee_time(const struct trainee *t); /* s, the scenario's clock */
const struct trainee_actions *trainee_did(const struct trainee *t);

/* Called after every cycle while she acts (may be NULL): a test's eyes. */
void trainee_watch(struct trainee *t,
		   void (*fn)(const struct endosim_state *s, void *arg),
		   void *arg);

/*
 * Inserts at SPEED (m/s) while steering until the tip is past material
 * TIP_S_M (m), or until she has waited STUCK_S seconds without the tip
 * advancing. Returns true when the tip got there.
 */
bool trainee_insert(struct trainee *t, double tip_s_m, double speed,
		    double stuck_s);

/* Pushes the carriage on by DISTANCE (m) at SPEED with a straight tip,
 * whatever it meets (up to the hand's strength). */
void trainee_push(struct trainee *t, double distance, double speed);

/* Withdraws by DISTANCE (m) at SPEED, turning the tube by TWIST_RAD
 * (clockwise seen from the trainee: positive roll) on the way, tip
 * straight. */
void trainee_withdraw(struct trainee *t, double distance, double speed,
		      double twist_rad);

/* Withdraws by DISTANCE (m) at SPEED looking around the wall: the tip
 * bent LOOK_RAD off straight, the bend going round once every CIRCLE_S
 * seconds (up, right, down, left), straight again at the end. */
void trainee_withdraw_looking(struct trainee *t, double distance,
			      double speed, double look_rad, double circle_s);

/* Lets the tube find its rest: the hand's targets moved to where the
 * carriage and the roll are, so she neither pushes nor pulls; holds for
 * SECONDS. */
void trainee_relax(struct trainee *t, double seconds);

/*
 * The assistant, from the next waypoint on (a line of the script each):
 * presses the abdomen at SITE (the case's [site NAME]) with FORCE_N (0:
 * [patient] hand_n), lets go, or turns the patient to POSITION (enum
 * posture_position; the turn takes [patient] turn_s). With the patient
 * disabled they change nothing.
 */
void trainee_press(struct trainee *t, const char *site, double force_n);
void trainee_release(struct trainee *t);
void trainee_turn(struct trainee *t, int position);

/* The tip held where it is (a spring of HOLD_N_PER_M), or let go (0). */
void trainee_hold_tip(struct trainee *t, double hold_n_per_m);

/* Holds everything still for SECONDS. */
void trainee_hold(struct trainee *t, double seconds);

/*
 * Aims the tool in the working channel as an endoscopist does, from what
 * she sees (the published scope; TARGET and WALL, a polyp's, as the
 * test's eyes give them, read at each waypoint: a caller may move TARGET
 * with the polyp, the gas moving the wall): she turns the polyp's wall (WALL, its normal
 * into the lumen) to the channel's clock in the image (PAR's
 * channel_angle_rad: 5 o'clock) by rolling the tube, the wheels turned
 * against the roll so that the tip keeps its way; swings the tip with
 * the wheels to bring the aimed point across the view onto TARGET (m);
 * and reaches it along the view with the tool, *DEPTH_M (m beyond the
 * channel's exit, kept within 3..50 mm and brought back towards 30 mm),
 * the scope in or out for the rest. The aimed point is BEYOND_M ahead of
 * the tool's tip along the tip's direction: the open loop's centre (half
 * the loop), the needle's point (needle_m). Each waypoint corrects half
 * of the error she sees, within what a hand does in a waypoint; she is
 * there when the aimed point is within TOL_M of TARGET at two waypoints
 * running. At most MAX_S seconds. Returns whether she got there. The
 * caller passes *DEPTH_M on to the rig each cycle (a trainee_watch()
 * callback: offline_tool_input()); the handle and the pedal are its.
 */
bool trainee_aim(struct trainee *t, const struct tool_params *par,
		 const double target[3], const double wall[3],
		 double *depth_m, double beyond_m, double tol_m, double max_s);

/*
 * Brings the channel's exit to TARGET (m) with the scope alone, the tool
 * back in the channel: as trainee_aim() aims, with no tool to reach
 * with (the wall WALL turned to the channel's clock, the tip swung, the
 * scope in or out). At most MAX_S seconds; whether the exit was within
 * TOL_M of TARGET at two waypoints running.
 */
bool trainee_approach(struct trainee *t, const struct tool_params *par,
		      const double target[3], const double wall[3],
		      double tol_m, double max_s);

/*
 * She presses the suction valve (ON) or lets it go, from the next
 * waypoint on (a line of her script), and holds it so through her care
 * of the view (the air or the jet joining it). Not before her first
 * waypoint.
 */
void trainee_suction(struct trainee *t, bool on);

/*
 * On to material TIP_S_M (m) at SPEED, steering; each time the scope is
 * stuck (4 s without the tip advancing) she pushes on PUSH_M (m; 0: not
 * at all, the novice's mistake otherwise), then (with the patient) asks
 * for help with the loop, then reduces the loop: withdraws 10 cm turning
 * the tube clockwise (0.5 rad) and lets it settle for 0.5 s; up to 6
 * tries. There, the assistant lets go. Returns true when the tip got
 * there.
 */
bool trainee_reach(struct trainee *t, double tip_s_m, double speed,
		   double push_m);

/*
 * The demo's course on case A (the trainee's, on the case she was made
 * with): inserting at SPEED (m/s; 3 cm/s is a trainee's pace) steering
 * into the lumen up to the sigmoid's
 * end; there the mistake, pushing on 15 cm with a straight tip (the tip
 * held by the junction, a loop forms behind it: with the patient she
 * asks for the assistant's hand over it); the reduction,
 * withdrawing 15 cm turning the tube clockwise, then letting the tube
 * settle; on, steering, to the cecum (trainee_reach(), no push on), and
 * each time the scope is stuck (the tube runs out or the tip stops while
 * she pushes) the same reduction with 10 cm; two seconds at the cecum,
 * easing off; the withdrawal at 6 cm/s with a straight tip (with the
 * patient, the segment examined turned uppermost). Returns true when the
 * tip reached the cecum.
 */
bool trainee_course(struct trainee *t, const struct anatomy *a, double speed);

#endif
