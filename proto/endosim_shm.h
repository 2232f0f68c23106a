/*
 * endosim_shm.h - the layout of endosimd's shared-memory state.
 *
 * This header is the contract between the daemon (the one writer) and every
 * reader (endoview, endoctl, tests). It is plain C11 with fixed-size types so
 * that any process on the rig can map it.
 *
 * The object is a POSIX shm object (default name "/endosim") holding one
 * struct endosim_shm: a header written once at start-up, then a seqlock and
 * the state that the force loop publishes every cycle.
 *
 * Compatibility: a reader checks magic, version and size before using the
 * state. Any change to struct endosim_state that moves or retypes a field
 * bumps ENDOSIM_SHM_VERSION.
 *
 * Units are SI throughout: m, rad, s, N, N m; time stamps in nanoseconds of
 * CLOCK_MONOTONIC.
 */
#ifndef ENDOSIM_SHM_H
#define ENDOSIM_SHM_H

#include <stdint.h>

#include "proto/seqlock.h"

#define ENDOSIM_SHM_MAGIC 0x314d49534f444e45ULL /* "ENDOSIM1", little-endian */
#define ENDOSIM_SHM_VERSION 12u /* 2: the scope and the colon's bows;
				  3: the haptic rendering's forces;
				  4: the safety monitors and every latched
				     fault with its time, axis and values;
				  5: the rod model: the tube's shape, the
				     colon's nodes, the wall's contacts;
				  6: guided replay;
				  7: the patient's body;
				  8: the patient's pain, sedation, vital
				     signs and a perforation by the tip;
				  9: the tool in the working channel;
				  10: bleeding, clips on it, retrieval;
				  11: guided replay's expert tool;
				  12: where each cut polyp lies */
#define ENDOSIM_SHM_DEFAULT_NAME "/endosim"

/* The unit of every *_ns stamp and period, here and in session files:
 * CLOCK_MONOTONIC nanoseconds (base/mono.h). The one home of these
 * factors. */
#define ENDOSIM_NS_PER_S 1000000000ull
#define ENDOSIM_NS_PER_MS 1000000ull
#define ENDOSIM_S_PER_NS 1e-9
/* A flow's and a volume's units for people (a bleeding's: mL/min, mL). */
#define ENDOSIM_ML_PER_M3 1e6
#define ENDOSIM_ML_PER_MIN_PER_M3_S 6e7

/* The rig's four axes, in this order everywhere (shm, sockets, config). */
enum endosim_axis {
	ENDOSIM_AXIS_INSERTION = 0, /* carriage: position m, force N */
	ENDOSIM_AXIS_ROLL = 1,      /* tube roll: angle rad, torque N m */
	ENDOSIM_AXIS_WHEEL_UD = 2,  /* up/down wheel: angle rad, torque N m */
	ENDOSIM_AXIS_WHEEL_LR = 3,  /* left/right wheel: angle rad, torque N m */
	ENDOSIM_AXES = 4,
};

/* The daemon's state machine. Motors are energised only in ENABLED. */
enum endosim_state_id {
	ENDOSIM_STATE_IDLE = 0,    /* torque off, waiting for enable */
	ENDOSIM_STATE_ENABLED = 1, /* forces rendered */
	ENDOSIM_STATE_ESTOP = 2,   /* latched emergency stop, torque off */
	ENDOSIM_STATE_FAULT = 3,   /* latched fault, torque off */
};

/*
 * Fault causes: bits of endosim_state.fault_bits (all faults latched since
 * the last reset). Bit numbers never change meaning.
 */
enum endosim_fault {
	ENDOSIM_FAULT_DRIVE = 1u << 0,       /* a drive reports a fault */
	ENDOSIM_FAULT_DRIVE_GONE = 1u << 1,  /* a drive or bus vanished */
	ENDOSIM_FAULT_STALE = 1u << 2,       /* feedback older than allowed */
	ENDOSIM_FAULT_BUS = 1u << 3,         /* a bus transaction failed */
	ENDOSIM_FAULT_OVERRUN = 1u << 4,     /* loop overrun budget exceeded */
	ENDOSIM_FAULT_TRAVEL = 1u << 5,      /* position outside travel */
	ENDOSIM_FAULT_RUNAWAY = 1u << 6,     /* velocity above its limit */
	ENDOSIM_FAULT_SATURATION = 1u << 7,  /* command saturated too long */
	ENDOSIM_FAULT_NONFINITE = 1u << 8,   /* NaN or inf in the pipeline */
	ENDOSIM_FAULT_INTERNAL = 1u << 9,    /* a daemon thread died */
	ENDOSIM_FAULT_ESTOP = 1u << 10,      /* emergency stop (state ESTOP) */
};

#define ENDOSIM_FAULT_BITS 16 /* room for the causes above and to come */

/* Per-axis drive status bits (endosim_axis_state.drive_status). */
enum endosim_drive_status {
	ENDOSIM_DRIVE_PRESENT = 1u << 0, /* the device answers */
	ENDOSIM_DRIVE_ENABLED = 1u << 1, /* power stage on, following torque */
	ENDOSIM_DRIVE_FAULT = 1u << 2,   /* the drive itself reports a fault */
	ENDOSIM_DRIVE_BUS_ERROR = 1u << 3, /* a transaction with it failed */
};

struct endosim_axis_state {
	double position;   /* m (insertion) or rad */
	double velocity;   /* m/s or rad/s */
	double hand;       /* N or N m: the hand's force (simulated rig only) */
	double command;    /* N or N m: rendered force before the safety filter */
	double limited;    /* N or N m: after limits, sent to the drive */
	uint64_t feedback_ns; /* CLOCK_MONOTONIC time of the feedback sample */
	uint32_t drive_status; /* enum endosim_drive_status bits */
	uint32_t reserved;
};

#define ENDOSIM_TUBE_POINTS 128 /* the scope's shape, anal verge to tip */
#define ENDOSIM_SPANS 4         /* mobile colon segments published */

/*
 * The endoscope as the force loop sees it this cycle, in the colon's
 * coordinates (m; x to the patient's left, y posterior, z cranial), and
 * the colon's deformation. s is the material arc length from the anal
 * verge on the undeformed colon (GetScene's centreline). The paper's
 * model bows the mobile segments: a viewer bows its copy of the
 * centreline by bow_m with the daemon's algorithm (centreline_bow()) to
 * draw exactly what the haptics use. The rod model moves them node by
 * node (struct endosim_rod_state: centreline_displace()); bow_m is then
 * each mobile segment's largest displacement from rest, the loop's size.
 */
struct endosim_scope_state {
	uint64_t scene_id;    /* GetScene's scene_id of the colon in use */
	double depth_m;       /* inserted length of tube, clamped */
	double roll_rad;
	double bend_rad[2];   /* tip bending: up/down, left/right */
	double base_s_m;      /* where the bending section starts */
	double tip_s_m;       /* centreline sample nearest the tip */
	double turning_rad;   /* integrated curvature up to base_s_m */
	double tip[3];        /* m */
	double dir[3];        /* unit view direction */
	double up[3];         /* unit camera up, normal to dir */
	uint32_t spans;       /* mobile segments in bow_m */
	uint32_t reserved;
	double bow_m[ENDOSIM_SPANS]; /* each mobile segment's bow amplitude
					(rod model: largest displacement) */
	float tube[ENDOSIM_TUBE_POINTS][3]; /* m, evenly along the tube */
};

/*
 * The haptic rendering this cycle (Koerner and Maenner, section 5): the
 * god-object contact of the tip, the translational force on the tube, the
 * torques on the tube and the wheels, each by its part. Forces in N,
 * torques in N m, along or about the axes of struct endosim_axis_state.
 * The sum of the parts of an axis is that axis' `command`.
 */
struct endosim_haptics_state {
	double proxy[3];          /* god-object: where the tip may be, m */
	double normal[3];         /* unit contact normal, into the lumen */
	double f_static[3];       /* k_wall (proxy - tip) + damping, N */
	double penetration_m;     /* |proxy - tip| */
	uint32_t contact;         /* 1 while the wall holds the tip */
	uint32_t constraints;     /* active constraint planes, 0..3 */
	double curvature_rad;     /* total turning angle of the inserted tube */
	/* insertion axis, N */
	double trans_contact_n;   /* the contact force's virtual work on d */
	double trans_friction_n;  /* -c_f v sum |r(i) - 2 r(i+1) + r(i+2)|/ds */
	double trans_loop_n;      /* the mesenteries of bowed segments */
	double trans_rod_n;       /* the rod model: the tube's reaction at
				     the carriage (its parts inseparable) */
	/* wheels (up/down, left/right), N m */
	double wheel_contact_nm[2]; /* the contact force's virtual work */
	double wheel_tension_nm[2]; /* wire tension from the tube's bends */
	double wheel_elastic_nm[2]; /* the bending section springing back */
	double wire_dl_m[2];      /* wire length differences, m */
	/* roll axis, N m */
	double tube_contact_nm;   /* the contact force's virtual work */
	double tube_friction_nm;  /* torsional friction */
	double tube_rod_nm;       /* the rod model: the tube's twisting
				     moment at the carriage */
	/* every axis */
	double damping[ENDOSIM_AXES]; /* light virtual damping, N or N m */
	/* stability */
	double passivity_energy_j; /* the passivity observer's energy */
	double passivity_damping;  /* damping it added this cycle, N s/m */
};

#define ENDOSIM_ROD_POINTS 321   /* the tube's points published, at most */
#define ENDOSIM_COLON_NODES 64   /* the mobile colon's nodes, at most */

/* [haptics] model: which model rendered this cycle. */
enum endosim_model {
	ENDOSIM_MODEL_PAPER = 0,   /* the tube on the centreline */
	ENDOSIM_MODEL_ROD = 1,     /* an elastic rod in a colon that moves */
};

/*
 * The rod model this cycle (lib/model/rodscope.h): the whole insertion
 * tube, base (the carriage) to tip, as POINTS points evenly along it (its
 * segments' ends, every k-th when it has more than ENDOSIM_ROD_POINTS - 1
 * segments), with its material frame's roll at each (rad: the carriage's
 * roll plus the twist the tube holds up to there); the wall's contacts;
 * and the mobile colon's nodes: each mobile span's SPAN_NODES[k] nodes in
 * order (span 0's first), each node's displacement from rest (m), which
 * centreline_displace() turns into the centreline the haptics use. All
 * zero in the paper's model.
 */
struct endosim_rod_state {
	uint32_t model;           /* enum endosim_model */
	uint32_t points;          /* of point[] in use */
	uint32_t contacts;        /* tube segments the wall presses */
	uint32_t nodes;           /* of node[] in use */
	uint32_t span_nodes[ENDOSIM_SPANS]; /* nodes per mobile span */
	double wall_n;            /* the wall's normal forces on the tube, N */
	double friction_n;        /* the friction's forces, N (sizes summed) */
	float point[ENDOSIM_ROD_POINTS][3]; /* m */
	float roll[ENDOSIM_ROD_POINTS];     /* rad */
	float node[ENDOSIM_COLON_NODES][3]; /* m, from rest */
};

/*
 * One latched fault cause: endosim_safety_state.cause[k] describes bit
 * 1 << k of fault_bits, as first seen since the last reset (first_ns 0:
 * not latched). VALUE and LIMIT are what tripped it, in the units of the
 * cause: position (m, rad) and the travel end it passed; speed (m/s, rad/s)
 * and its limit; command (N, N m) and the force limit; periods skipped
 * within the window (at least that many) and the budget. DETAIL is the backend's code for drive causes, the window or
 * time in ms for the overrun and saturation causes, the stage of the force
 * pipeline (enum endosim_stage) for a non-finite value.
 */
struct endosim_fault_cause {
	uint64_t first_ns;    /* CLOCK_MONOTONIC when it latched; 0: never */
	int32_t axis;         /* -1: global, or a device of no single axis */
	uint32_t detail;
	double value;
	double limit;
};

/* Where in the force pipeline a non-finite value was found. */
enum endosim_stage {
	ENDOSIM_STAGE_FEEDBACK = 1,   /* the rig's positions, speeds, hand */
	ENDOSIM_STAGE_KINEMATICS = 2, /* the scope's pose */
	ENDOSIM_STAGE_HAPTICS = 3,    /* the haptic rendering's parts, the
					 patient's body among them */
	ENDOSIM_STAGE_COMMAND = 4,    /* the force to render per axis */
	ENDOSIM_STAGE_OUTPUT = 5,     /* the setpoint after the safety filter */
};

/*
 * The safety monitors this cycle (daemon/loop/safety.h) and every latched
 * fault.
 * Torque on an axis is, while ENABLED, its command times RAMP, clamped to
 * the axis' force limit: RAMP rises from 0 to 1 over [limits]
 * enable_ramp_s after each enable, so a session never starts with a step.
 */
struct endosim_safety_state {
	uint32_t active;          /* fault causes present this cycle */
	uint32_t overrun_periods; /* periods skipped within the window */
	uint64_t enabled_ns;      /* CLOCK_MONOTONIC of the last enable */
	double ramp;              /* 0..1, 0 unless ENABLED */
	double saturated_s[ENDOSIM_AXES]; /* time each axis has been held at
					     its force limit, s */
	uint64_t faults_latched;  /* fault causes latched since start */
	struct endosim_fault_cause cause[ENDOSIM_FAULT_BITS];
};

/* Guided replay (daemon/rig/guide.h): what the guidance does. */
enum endosim_guide_phase {
	ENDOSIM_GUIDE_OFF = 0,
	ENDOSIM_GUIDE_MOVING = 1,  /* to a point of the path, at a safe speed */
	ENDOSIM_GUIDE_GUIDING = 2, /* playing the path */
	ENDOSIM_GUIDE_HOLDING = 3, /* at a point of the path */
	ENDOSIM_GUIDE_FADING = 4,  /* taken over: the force fading out */
	ENDOSIM_GUIDE_FREE = 5,    /* taken over: no force until resumed */
};

/* Why the guidance last ended. */
enum endosim_guide_end {
	ENDOSIM_GUIDE_END_NONE = 0,
	ENDOSIM_GUIDE_END_STOPPED = 1,     /* a stop command */
	ENDOSIM_GUIDE_END_DONE = 2,        /* the path's end */
	ENDOSIM_GUIDE_END_NOT_ENABLED = 3, /* disabled, a fault, an estop */
	ENDOSIM_GUIDE_END_LOST = 4,        /* an axis could not follow */
};

struct endosim_guide_state {
	uint32_t phase;           /* enum endosim_guide_phase */
	uint32_t ended;           /* enum endosim_guide_end: the last end */
	uint64_t source_id;       /* the guiding session's id */
	double time_s;            /* the playhead, s of the recording */
	double length_s;          /* the recording's guided length, s */
	double speed;             /* x the recording's */
	double fade;              /* the force's share, 1 .. 0 */
	uint32_t takeovers;       /* since the start */
	uint32_t lost_axis;       /* ended lost: the axis; else ENDOSIM_AXES */
	double reference[ENDOSIM_AXES]; /* m, rad (taken over: where it left) */
	double force[ENDOSIM_AXES];     /* N, N m: in the command */
	double error[ENDOSIM_AXES];     /* reference - position */
	double hand[ENDOSIM_AXES];      /* N, N m: the hand's, estimated */
	/* 11: the expert's tool, while GUIDING a session recorded with one
	   (daemon/rig/guide.h): the recording's at the playhead, drawn on
	   the scope as it is now; a tool that acts on nothing (kind NONE in
	   any other phase, and the rest zero) */
	uint32_t expert_kind;     /* enum endosim_tool; NONE: no ghost */
	uint32_t expert_pedal;    /* 1: the expert's pedal down */
	double expert_snare_m;    /* the snare's size */
	double expert_depth_m;    /* beyond the channel's exit */
	double expert_opening;    /* the handle, 0 closed .. 1 open */
	double expert_loop_m;     /* the snare's loop's diameter */
	double expert_tip[3];     /* the tool's tip, colon frame, m */
	double expert_loop_centre[3]; /* the snare's loop's centre, m */
};

/* The patient's body (lib/model/patient.h). */
#define ENDOSIM_SEGMENTS 9 /* anal canal, rectum, sigmoid, descending,
			      splenic flexure, transverse, hepatic flexure,
			      ascending, cecum */

/* Where the patient lies (gravity in the body's frame: +x, +y, -x, -y). */
enum endosim_position {
	ENDOSIM_POSITION_LEFT_LATERAL = 0,
	ENDOSIM_POSITION_SUPINE = 1,
	ENDOSIM_POSITION_RIGHT_LATERAL = 2,
	ENDOSIM_POSITION_PRONE = 3,
};

/* The handle's valves, as the force loop took them this cycle. */
enum endosim_valve {
	ENDOSIM_VALVE_AIR = 1u << 0,     /* the air/water valve covered: air */
	ENDOSIM_VALVE_WATER = 1u << 1,   /* pressed: water onto the lens */
	ENDOSIM_VALVE_SUCTION = 1u << 2, /* the suction valve pressed */
};

/* What hurts most now (lib/model/pain.h). */
enum endosim_pain_cause {
	ENDOSIM_PAIN_NONE = 0,
	ENDOSIM_PAIN_LOOPING = 1,       /* stretch while pushed in or held */
	ENDOSIM_PAIN_STRAIGHTENING = 2, /* stretch while withdrawn or turned */
	ENDOSIM_PAIN_INSUFFLATION = 3,  /* the wall distended */
	ENDOSIM_PAIN_TIP = 4,           /* the tip pressed into the wall */
	ENDOSIM_PAIN_CAUSES
};

/* The patient's sedation, the instructor's choice per session. */
enum endosim_sedation {
	ENDOSIM_SEDATION_NONE = 0,
	ENDOSIM_SEDATION_MINIMAL = 1,
	ENDOSIM_SEDATION_MODERATE = 2,
	ENDOSIM_SEDATION_DEEP = 3,
	ENDOSIM_SEDATIONS
};

/*
 * The gas that holds the colon open, the patient's position and gravity,
 * the fluid, the assistant's hand and the lens. Body frame (x to the
 * patient's left, y posterior, z cranial); each segment's lumen radius is
 * its factor times the case's (a viewer places the mesh so:
 * gas_factor_at()); a pool's surface is the plane of normal fluid_up at
 * height fluid_level_m along it.
 */
struct endosim_patient_state {
	uint32_t enabled;        /* 0: none (the case's lumen, no gravity) */
	uint32_t valves;         /* enum endosim_valve bits */
	uint32_t position;       /* enum endosim_position, or turning to */
	uint32_t turning;        /* 1 while being turned */
	double turn;             /* the turn's progress 0..1 */
	double down[3];          /* gravity's direction (unit) */
	double gas_m3;           /* gas in the colon */
	double pressure_pa;      /* its pressure above the atmosphere */
	double gas_in_m3;        /* pumped in since the case was loaded */
	double factor[ENDOSIM_SEGMENTS];        /* lumen radius / the case's */
	double transmural_pa[ENDOSIM_SEGMENTS]; /* across each wall */
	double tension_n_per_m[ENDOSIM_SEGMENTS]; /* Laplace's p r */
	double fluid_m3[ENDOSIM_SEGMENTS];      /* pooled in each segment */
	double fluid_level_m[ENDOSIM_SEGMENTS]; /* its surface along fluid_up */
	double fluid_up[3];      /* the surfaces' normal (unit) */
	int32_t hand_site;       /* the site pressed (the scene's), -1: none */
	uint32_t tip_in_fluid;   /* 1: the tip under a surface */
	double hand_n;           /* the assistant's press, N */
	double pad_n;            /* what the pad holds of the colon, N */
	double lens_smear;       /* 0..1: the mucosa's smear on the lens */
	double lens_murk;        /* 0..1: the fluid's */
	double lens_redout;      /* 0..1: the mucosa sucked onto it */
	int32_t burst_segment;   /* the first segment torn, -1: none */
	uint32_t sedation;       /* enum endosim_sedation */
	/* 8: the patient responds (pain.h, vitals.h, perforation.h) */
	double pain;             /* 0..10, the clinical rating scale */
	double pain_stimulus;    /* what the level follows now, 0..10 */
	uint32_t pain_cause;     /* enum endosim_pain_cause */
	int32_t pain_place;      /* the cause's segment, -1: none */
	double heart_rate_bpm;   /* beats a minute */
	double spo2;             /* oxygen saturation, 0..1 */
	int32_t torn_segment;    /* where the tip tore the wall, -1: none */
	uint32_t reserved;
};

/* The tool in the working channel (lib/model/tool.h), one at a time. */
enum endosim_tool {
	ENDOSIM_TOOL_NONE = 0,
	ENDOSIM_TOOL_FORCEPS = 1,
	ENDOSIM_TOOL_SNARE = 2,
	ENDOSIM_TOOL_NEEDLE = 3,
	ENDOSIM_TOOL_CLIP = 4,
	ENDOSIM_TOOLS
};

/* What happened to the tool in a cycle (its events' bits). */
enum endosim_tool_event {
	ENDOSIM_TOOL_CAPTURE = 1u << 0, /* the loop closed on a polyp */
	ENDOSIM_TOOL_RELEASE = 1u << 1, /* it let go (the handle opened) */
	ENDOSIM_TOOL_CUT = 1u << 2,     /* a polyp cut free */
	ENDOSIM_TOOL_INJURY = 1u << 3,  /* current into the wall */
	ENDOSIM_TOOL_LIFT = 1u << 4,    /* an injection lifted a base */
	ENDOSIM_TOOL_BITE = 1u << 5,    /* the forceps took a sample */
	ENDOSIM_TOOL_CLIP_PLACED = 1u << 6, /* a clip closed on the wall */
	/* 10 */
	ENDOSIM_TOOL_BLEED = 1u << 7,   /* a cut stalk bleeds */
	ENDOSIM_TOOL_CLIPPED = 1u << 8, /* a clip closed a bleeding point */
	ENDOSIM_TOOL_STOPPED = 1u << 9, /* a bleeding stopped by itself */
	ENDOSIM_TOOL_RETRIEVE = 1u << 10, /* a cut polyp sucked out */
};

/* A polyp's bleeding point (its stalk's foot) (enum endosim_bleed). */
enum endosim_bleed {
	ENDOSIM_BLEED_NONE = 0,
	ENDOSIM_BLEED_BLEEDING = 1,
	ENDOSIM_BLEED_CLIPPED = 2, /* stopped by a clip */
	ENDOSIM_BLEED_STOPPED = 3, /* stopped by itself */
};

/* A polyp as the tool left it (enum endosim_polyp_state). */
enum endosim_polyp_state {
	ENDOSIM_POLYP_IN_PLACE = 0,
	ENDOSIM_POLYP_CAPTURED = 1, /* held in the snare's loop */
	ENDOSIM_POLYP_CUT = 2,      /* cut free: lies in the lumen */
	ENDOSIM_POLYP_RETRIEVED = 3, /* sucked out through the channel */
};

#define ENDOSIM_POLYPS 32 /* a case's most (anatomy.h) */

struct endosim_tool_polyp {
	uint32_t state;          /* enum endosim_polyp_state */
	uint32_t lifted;         /* 1: lifted by an injection */
	double energy_j;         /* the cautery's into it so far */
	uint32_t bites;          /* the forceps' on it */
	uint32_t bleed;          /* 10: enum endosim_bleed */
	double bleed_m3_s;       /* its flow now, m^3/s */
	double blood_m3;         /* shed from it so far */
	double at[3];            /* 11: cut, its body's centre: where it
				    falls and lies (retrieved: where it lay;
				    before its cut 0) */
};

/*
 * The tool: which, as sensed (depth beyond the channel's exit, the
 * handle's opening, the pedal), the snare's loop, this cycle's events and
 * each of the case's polyps (in the case's order) as the tools left them.
 * Colon frame (as the scope's), m.
 */
struct endosim_tool_state {
	uint32_t kind;           /* enum endosim_tool */
	uint32_t pedal;          /* 1: the pedal down */
	double snare_m;          /* the snare's size (its loop fully open) */
	double depth_m;          /* the tool's tip beyond the channel's exit */
	double opening;          /* the handle, 0 closed .. 1 open */
	double loop_m;           /* the snare's loop's diameter now */
	double tip[3];           /* the tool's tip */
	double loop_centre[3];   /* the snare's loop's centre */
	int32_t captured;        /* the polyp the loop holds, -1: none */
	uint32_t events;         /* this cycle's enum endosim_tool_event bits */
	int32_t event_polyp;     /* the polyp they concern, -1: none */
	uint32_t clips;          /* clips placed since the case was loaded */
	uint32_t polyps;         /* of polyp[] in use */
	uint32_t bleeding;       /* 10: the points bleeding now */
	struct endosim_tool_polyp polyp[ENDOSIM_POLYPS];
	double bleed_m3_s;       /* 10: their flow, all together, m^3/s */
	double blood_m3;         /* shed since the case was loaded */
	double bleed_at[3];      /* the point bleeding most (none: 0) */
	double clip_at[3];       /* the last clip's place (clips > 0) */
	/* 11: one cut polyp's place a cycle, in turn (tool.h), which a
	   session's record keeps: the polyp, -1 none, and its at */
	double lying_at[3];
	int32_t lying_polyp;
	uint32_t reserved;
};

struct endosim_state {
	uint64_t cycle;       /* force-loop cycles since start */
	uint64_t stamp_ns;    /* CLOCK_MONOTONIC: this cycle's wake-up */
	uint64_t publish_ns;  /* CLOCK_MONOTONIC: just before publishing */
	uint32_t state;       /* enum endosim_state_id */
	uint32_t fault_bits;  /* enum endosim_fault bits, latched */
	int32_t fault_axis;   /* axis of the first fault, -1 if none or global */
	uint32_t fault_detail; /* backend-specific code of the first fault */
	uint64_t fault_ns;    /* CLOCK_MONOTONIC time of the first fault */
	uint64_t overruns;    /* periods skipped since start */
	uint32_t latency_ns;  /* this cycle's wake-up latency */
	uint32_t compute_ns;  /* the previous cycle's compute time */
	double scenario_time_s; /* simulated hand: time into the scenario */
	uint32_t scenario_done; /* 1 once a scenario without repeat ended */
	uint32_t fault_first; /* the enum endosim_fault bit of the first fault */
	struct endosim_axis_state axis[ENDOSIM_AXES];
	struct endosim_scope_state scope;
	struct endosim_haptics_state haptics;
	struct endosim_safety_state safety;
	struct endosim_rod_state rod;
	struct endosim_guide_state guide;
	struct endosim_patient_state patient;
	struct endosim_tool_state tool;   /* 9 */
};

struct endosim_shm {
	/* Header: written once before the loop starts. */
	uint64_t magic;       /* ENDOSIM_SHM_MAGIC */
	uint32_t version;     /* ENDOSIM_SHM_VERSION */
	uint32_t size;        /* sizeof(struct endosim_shm) of the writer */
	int32_t writer_pid;
	uint32_t period_ns;   /* force-loop period */
	uint64_t start_ns;    /* CLOCK_MONOTONIC at daemon start */
	/* Published every cycle. */
	seqlock_t lock;
	struct endosim_state state;
};

#endif
