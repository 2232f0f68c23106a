/*
 * guide.h - guided replay: the rig plays a recorded session back through
 * its motors, the trainee's hands riding along on the scope (Rieger 2008).
 *
 * Per axis a spring-damper pulls the axis towards a reference,
 *
 *   F_g = fade * clamp(k (q_ref - q) + b (qdot_ref - qdot), +-force_max)
 *
 * added to the haptic model's force before the safety filter, which then
 * limits the sum as it limits any command. The reference is a recorded
 * session's axis positions (a guide_path: 100 samples a second, a cubic
 * Hermite curve through them), played from a chosen time at a chosen speed
 * on the loop's clock; where the recording moved an axis faster than
 * [guide] speed_max, the playhead slows down so that it never does.
 *
 * What the controller does, by phase (enum endosim_guide_phase):
 *   MOVING   the reference goes from where the scope is to a point of the
 *            path in a straight, smooth line, no axis faster than its
 *            speed_max (start, resume and reset begin here), then GUIDING
 *            or HOLDING;
 *   GUIDING  the reference plays the path;
 *   HOLDING  the reference stays at a point of the path;
 *   FADING   the trainee took over: the force fades out over fade_s, then
 *   FREE     no force until resumed.
 * Take-over: while GUIDING, the hand's force on an axis, estimated as what
 * the motors push against (the applied command, low-passed: at a guided
 * scope's speeds the rig's own inertia and friction take under 0.5 N),
 * stays beyond takeover_force for takeover_s. A reference the axis cannot
 * follow (tracking error beyond error_max for error_s, with no take-over:
 * the scope stuck) ends the guidance with why; so do the path's end, a
 * stop, and the rig leaving ENABLED (at once: no fade; the safety filter
 * zeroes the torque anyway).
 *
 * The patient plays along: a session recorded with the patient keeps, per
 * sample of its path, the handle's valves, the position the patient lay
 * in (or was being turned to) and the assistant's hand (site and force).
 * While GUIDING, guide_patient_now() gives them at the playhead, so that
 * the force loop presses the recording's valves with the trainee's (an OR:
 * the trainee's own presses still work, and neither can release the
 * other's) and has the patient turned and the abdomen pressed or let go
 * as the recording's changed, at their times on the path's clock (loop.h).
 *
 * The expert's tool is shown, not played: the tool in the working channel
 * is sensed, never driven (no motor moves it), and only the trainee's own
 * acts on the model. A session recorded with a tool keeps, per sample of
 * its path, the tool as the rig sensed it then (its kind, the snare's
 * size, its depth, the handle's opening, the pedal) and the polyp its
 * loop held. While GUIDING, guide_publish_tool() publishes it at the
 * playhead (the sample nearest it, as the patient's), drawn on the scope
 * as it is now: tool.h's pose with this rig's channel, the snare's loop
 * tool_loop_diameter()'s, or the held polyp's thickness while the
 * recording's loop held one (its place is this rig's case's: a guided
 * session is of the same case). The viewer draws it as a ghost beside
 * the trainee's own tool, with a line of the HUD saying what the expert
 * does (viewer/toolview.h, docs/TRAINEE.md). It cuts, injects, bites,
 * clips and pours nothing; the trainee's tool stays the trainee's, as
 * sensed. In any other phase (moving to the path, holding, taken over,
 * off), for a path recorded without a tool (none held at any sample: a
 * scenario's, a session before format 6) and at a sample without one,
 * no expert's tool is published (kind none, the rest zero). The
 * recording's suction valve is the handle's, and plays along as above.
 *
 * Threads: guide_path_*() allocate (the control thread); the rest is the
 * force loop's: no allocation, fixed work a cycle.
 */
#ifndef ENDOSIM_GUIDE_H
#define ENDOSIM_GUIDE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "conf/config.h"
#include "model/tool.h"
#include "proto/endosim_shm.h"

#define GUIDE_PATH_HZ 100.0 /* samples a second of a path */

/* What the recording's patient was doing at one sample of its path. */
struct guide_patient {
	uint32_t valves;         /* enum endosim_valve bits */
	int32_t position;        /* enum endosim_position, or turning to */
	int32_t hand_site;       /* the case's site pressed, -1: none */
	float hand_n;            /* the assistant's press, N */
};

/* What the recording's tool was at one sample of its path (tool.h). */
struct guide_tool {
	int32_t kind;            /* enum tool_kind; TOOL_NONE: none */
	int32_t captured;        /* the polyp its loop held, -1: none */
	float snare_m;           /* the snare's size, m */
	float depth_m;           /* beyond the channel's exit, m */
	float opening;           /* the handle, 0 closed .. 1 open */
	uint32_t pedal;          /* 1: the pedal down */
};

/* A recorded session's axis positions, GUIDE_PATH_HZ samples a second. */
struct guide_path {
	uint64_t source_id;      /* the session's id */
	char case_name[64];      /* the case it was recorded on; "": any (a
				    scenario's) */
	size_t n;                /* samples, >= 2 */
	float (*q)[ENDOSIM_AXES]; /* m, rad */
	float *tip_s_m;          /* where the tip was along the colon */
	struct guide_patient *patient; /* each sample's; NULL: none (a
					  scenario's path, a session
					  recorded without the patient) */
	struct guide_tool *tool; /* each sample's; NULL: none held at any
				    (a scenario's path, a session recorded
				    without a tool) */
};

/*
 * The path of the session file FILE: every record's axis positions (and
 * its patient's and its tool's, if it had them) from
 * the first record with torque on (the session's enabled part) to the
 * last, resampled: each sample the last record at or before its time. Or, for a file that is not a session, of a scenario
 * (scenario.h): its hand's targets (an axis pushed or let go keeps its
 * last target), of no case (case_name empty, source_id 0). NULL with one
 * line in ERR (cannot read, neither a session nor a scenario, too short,
 * no enabled record, no target).
 */
struct guide_path *guide_path_load(const char *file, char *err,
				   size_t errsize);

/* NULL is fine. */
void guide_path_free(struct guide_path *p);

/* The path's length, s of its recording. */
double guide_path_length_s(const struct guide_path *p);

/*
 * The path at T_S (clamped into it): positions Q and their rate of
 * change DQ (per second of the recording).
 */
void guide_path_at(const struct guide_path *p, double t_s,
		   double q[ENDOSIM_AXES], double dq[ENDOSIM_AXES]);

/*
 * The time of the path's sample nearest the axes' positions Q (a radian
 * of a rotary axis weighs as a centimetre of insertion). Any thread: the
 * control thread's, from the published state.
 */
double guide_path_nearest(const struct guide_path *p,
			  const double q[ENDOSIM_AXES]);

enum guide_action {
	GUIDE_START = 1,  /* PATH from FROM_S at SPEED (moving there first) */
	GUIDE_STOP,       /* fade out and end */
	GUIDE_RESUME,     /* from FROM_S of the path in use, at its speed */
	GUIDE_RESET,      /* move to FROM_S of the path in use and hold */
	GUIDE_TAKEOVER,   /* the trainee takes over (a key): fade out, then
			     free until resumed */
};

struct guide_command {
	enum guide_action action;
	const struct guide_path *path; /* GUIDE_START; the loop's until the
					  next start (loop.h) */
	double speed;                  /* GUIDE_START: 0.25 .. 2 */
	double from_s;                 /* time on the path */
};

struct guide {
	const struct guide_path *path;
	uint32_t phase;          /* enum endosim_guide_phase */
	uint32_t after_move;     /* the phase that follows MOVING */
	uint32_t ended;          /* enum endosim_guide_end: why it last ended */
	uint32_t takeovers;      /* since the start */
	double speed;            /* the playhead's, x recording */
	double rate;             /* this cycle's: speed, slowed where fast */
	double t_s;              /* the playhead, s of the path */
	double fade;             /* 1 .. 0 */
	double move_t_s, move_len_s; /* MOVING: time in, its length */
	double from[ENDOSIM_AXES], to[ENDOSIM_AXES]; /* MOVING's ends */
	double over_s;           /* the hand beyond takeover_force so long */
	double lost_s;           /* the error beyond error_max so long */
	double hand[ENDOSIM_AXES];  /* the hand's force, estimated */
	double ref[ENDOSIM_AXES], ref_v[ENDOSIM_AXES];
	double force[ENDOSIM_AXES]; /* this cycle's F_g */
	int lost_axis;           /* the axis that could not follow */
};

/* Nothing to guide: OFF. */
void guide_init(struct guide *g);

/*
 * A command, with the axes at Q (P: the moves' speeds). 0, or -EINVAL
 * (RESUME or RESET without a path; a speed or time out of range). Force
 * loop.
 */
int guide_command(struct guide *g, const struct config_guide *p,
		  const struct guide_command *c, const double q[ENDOSIM_AXES]);

/*
 * One cycle of DT_S: the guidance force FORCE per axis, from the axes'
 * positions Q and speeds V and the command APPLIED to them last cycle.
 * ENABLED: the rig is (else the guidance ends at once, no force); RAMPED:
 * its enable ramp is done (until then the guidance waits, no force).
 * Force loop.
 */
void guide_step(struct guide *g, const struct config_guide *p, bool enabled,
		bool ramped,
		const double q[ENDOSIM_AXES], const double v[ENDOSIM_AXES],
		const double applied[ENDOSIM_AXES], double dt_s,
		double force[ENDOSIM_AXES]);

/*
 * The recording's patient at the playhead (its sample nearest it)
 * into OUT while GUIDING: true; false in any other phase (moving to the
 * path, holding, taken over, off) or on a path without the patient.
 * Force loop.
 */
bool guide_patient_now(const struct guide *g, struct guide_patient *out);

/*
 * The expert's tool into ST's expert_* fields (endosim_shm.h): while
 * GUIDING a path with a tool, the recording's at the playhead (its sample
 * nearest it) on the scope SC as it is now, with PAR's channel (tool.h's
 * pose), the snare's loop held at the thickness of T's polyp that the
 * recording's loop held; otherwise none (kind none, the rest zero). T is
 * read only: the expert's tool acts on nothing. Force loop, after the
 * scope is published.
 */
void guide_publish_tool(const struct guide *g, const struct tool_params *par,
			const struct endosim_scope_state *sc,
			const struct tool *t, struct endosim_guide_state *st);

/* What the guidance does, for the published state. */
void guide_publish(const struct guide *g, const double q[ENDOSIM_AXES],
		   struct endosim_guide_state *st);

#endif
