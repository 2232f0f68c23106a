/*
 * tool.h - the tools a trainee passes through the scope's working channel
 * (issue 25): biopsy forceps, a snare, an injection needle, a clip; the
 * snare's capture of a polyp and its cut. This is the model alone: the
 * loop steps it (loop.c), the simulated hand senses it (rig/hand.h), the
 * viewer draws it from what the loop publishes (viewer/toolview.h).
 *
 * The tool, one at a time as the nurse hands it over (tool_select()),
 * lies in the channel; what the rig senses of it each cycle
 * (struct tool_input): its depth beyond the channel's exit (m, negative
 * while still inside), its handle's opening (0 closed .. 1 open) and the
 * cautery's foot pedal.
 *
 * The pose. The channel leaves the tip's face channel_offset_m from its
 * axis at channel_angle_rad, clockwise from 12 o'clock in the endoscopic
 * image (the scope state's up is 12 o'clock, dir x up 3 o'clock): by
 * default 5 o'clock (150 degrees), where a colonoscope's 3.2-3.8 mm
 * channel (the numbers gathered for issue 25) opens, 4 mm from the axis
 * of a 13 mm tip (a guess from those sizes). The tool leaves it along the tip's
 * dir: its tip is exit + depth dir.
 *
 * The snare. A wire loop of size D (its diameter fully open, 10..30 mm:
 * mini snares below 11 mm, standard loops 15 to 45 mm, issue 25's
 * numbers) is pushed out of its sheath by the handle: opening x pi D / 2
 * of each of its two strands, the part beyond the channel's exit free to
 * open (the sheath's tip at depth: the loop's wire beyond the exit is
 * that length plus the depth, when the depth is negative). Those l
 * metres of wire make a loop of perimeter 2 l, a circle of diameter
 *   d = min(D, 2 l / pi),
 * so that it opens as it leaves the sheath and closes as the handle
 * closes (tool_loop_diameter()). The loop hangs from the sheath's tip
 * forward, its centre d / 2 along dir, and lies flat towards the
 * channel's side of the image: its plane holds dir and dir x the
 * channel's radial direction, its normal is that radial direction (a
 * polyp brought to 5 o'clock stands on the wall under the loop, as
 * endoscopists turn the scope to bring it there).
 *
 * Capture. Each polyp of the case (tool_add_polyp(), tool_place_polyps())
 * has an axis from its base on the wall along the wall's normal: a
 * pedunculated (Ip) polyp's stalk, its length and thickness the case's;
 * a sessile (Is) polyp's base, half its size high and its size thick; a
 * flat one's, IIa a quarter of its size high and at most 2.5 mm (Paris'
 * limit), IIb level with the mucosa (nothing a loop can close around);
 * a base lifted by an injection stands lift_m higher. In a cycle in
 * which the loop closes (its diameter smaller than in the cycle
 * before), it captures the first
 * polyp in place whose axis passed inside the loop at the loop's plane
 * in the cycle before (the axis crossing the plane within its height, at
 * less than d / 2 from the loop's centre) and which the wire now reaches
 * (the crossing at d / 2 - t / 2 or more from the centre, t the axis'
 * thickness). An axis outside the loop is not captured, however near:
 * a stalk a stalk's width outside is pushed aside. The captured polyp
 * holds the loop at its thickness; opening the handle again releases it.
 *
 * The cut, hot. With the pedal down the generator puts hot_power_w into
 * the tissue the loop holds; it is cut through when the energy reaches
 *   E = cut_j_per_m2 x pi t^2 / 4
 * (the cross-section held). cut_j_per_m2 = 2.5e6 J/m^2 (2.5 J/mm^2),
 * reasoned, not measured: the wire (0.4 mm, snares' 0.3-0.5 mm) cuts by
 * vaporising a kerf its width; tissue ~75 % water at ~1050 kg/m^3 takes
 * 4.18 kJ/kg/K x 63 K to boil from 37 C and 2.26 MJ/kg to vaporise,
 * ~2.0 GJ/m^3, 0.8 MJ/m^2 over the kerf; the coagulation either side and
 * conduction away take about twice as much again (a guess). At 30 W (a
 * common polypectomy setting, 20-40 W; the power the tissue takes is a
 * guess) a 5 mm stalk takes 49 J, 1.6 s; a 10 mm base 196 J, 6.5 s: a
 * few seconds of the 24-30 s a resection takes (24 +/- 18 s with a
 * rotary snare, 30 +/- 26 s with a standard one). The energy stays in a polyp
 * across presses of the pedal (no cooling).
 *
 * The cut, cold. Without the pedal, the handle closed (opening at most
 * closed_opening) cuts what the loop holds by its force when the held
 * thickness is below cold_max_m, 10 mm: the ESGE (Ferlitsch et al.,
 * Endoscopy 2017;49:270 and its 2024 update) recommends cold snaring for
 * diminutive and small polyps, up to 9 mm, and cold snares are used for
 * polyps of 10 mm and less (Giri et al., Clin Endosc 2022); a
 * thicker one holds the loop shut, captured and uncut. The rig senses the
 * handle's travel, not its force: closing it all the way stands for the
 * force a nurse closes a cold snare with.
 *
 * The wall. With the pedal down and the snare out, the loop on the
 * mucosa (the caller's nearest wall point and normal: the loop's circle
 * reaches the wall's plane, within half the wire) with nothing captured,
 * or the loop holding an unlifted sessile or flat base (Is, IIa: current
 * through the whole wall beneath it), injures the wall: one
 * TOOL_EVENT_INJURY per press of the pedal, for the patient's side to
 * turn into a perforation.
 *
 * The needle. The handle pushes the needle needle_m out of its
 * catheter (opening above one half); out, with its point in the wall
 * under a sessile or flat polyp's base (at most needle_m below the
 * surface, within the base's radius and margin_m more of its centre),
 * the nurse injects at inject_m3_per_s; lift_m3 under a base lifts it
 * (TOOL_EVENT_LIFT), so that a snare can close around it. 1 mL/s and
 * 3 mL are guesses (EMR injects a few mL a site; the hemostasis
 * trainer's experts inject in 36 s, beginners in 92 s: the whole task,
 * not the flow).
 *
 * The forceps and the clip close their jaws when the handle, opened past
 * one half since their last closing, closes (to closed_opening), the
 * tool out of the channel; the jaws' point is jaw_m (the forceps' cups)
 * or clip_m (a clip's jaws) beyond the tool's tip. The forceps bite a
 * polyp in place within their cups' length of its body (a sphere of its
 * size at half its height) or, failing one, the mucosa within a cup's
 * length of the wall: TOOL_EVENT_BITE, the polyp's bites counted. A bite
 * takes a polyp of forceps_max_m (3 mm) or less whole (TOOL_EVENT_CUT,
 * and TOOL_EVENT_RETRIEVE: it leaves in the cups through the channel):
 * cold forceps resected adenomas of 4 mm or less about as completely as
 * a cold snare (96.9 against 100 %; Kim et al., GIE 2015), larger ones
 * less so, and the ESGE's 2024 update recommends against them for what
 * they leave: whether a bite removed a polyp completely is the
 * assessment's question (a later slice). A clip closing within its
 * jaws' length of the wall is placed there (TOOL_EVENT_CLIP, clip_at):
 * what stops a bleeding point is the bleeding's slice. Cups 2.5 mm and
 * clip jaws 5 mm long: the sizes of common models, rounded (guesses).
 *
 * Bleeding. A stalk's artery bleeds when it is cut before it is
 * coagulated: at the cut (hot or cold) an Ip stalk t thick, t at least
 * bleed_min_m, bleeds when the energy the generator put into it is below
 *   E_coag = coag_j_per_m3 x pi t^2 / 4 x t,
 * the stalk heated through over a collar as long as it is thick.
 * coag_j_per_m3 = 2.5e8 J/m^3 is heating tissue (about water, ~4 MJ/m^3/K)
 * from 37 C by ~63 K to coagulate it (reasoned, the collar a guess).
 * "Too fast", physically: the wire parts the stalk (E_cut, which grows as
 * its section t^2) before the heat has coagulated its bulk (E_coag, as
 * t^3): a cold cut (no energy), a cut closed cold after too short a press
 * of the pedal, or a hot cut of a stalk thicker than cut_j_per_m2 /
 * coag_j_per_m3 = 10 mm, where E_cut < E_coag whatever the power (the
 * generator's power sets how long, not how much): the ESGE's threshold
 * for prophylaxis before cutting a stalk (10 mm or more; Ferlitsch et
 * al., Endoscopy 2017). A sessile or flat base's vessels are not
 * modelled (it never bleeds). The bleeding point is the stalk's foot on
 * the wall (the polyp's base); its flow is
 *   Q = bleed_m_per_s x pi t^2 / 4
 * (m^3/s; 1 mm/s over the stalk's section, a guess: 1.2 mL/min from a
 * 5 mm stalk, 6.8 mL/min from 12 mm: an oozing to a spurting immediate
 * post-polypectomy bleed). The blood shed each step is Q dt (the loop
 * pours it into the patient's pool there: patient_bleed()), until a clip
 * is placed with the point within half its jaws' length clip_m / 2 of
 * the clip's point (it closes the point that step: TOOL_EVENT_CLIPPED,
 * nothing shed in it), or bleed_stop_s (300 s, a guess: the normal
 * bleeding time is 2 to 9 minutes) after the cut, when it stops by
 * itself (TOOL_EVENT_STOPPED, in the step after the one that sheds its
 * last). A point sheds in a step exactly when its flow after the step is
 * above zero: the loop pours bleed_m3_s x dt of each into the pool.
 *
 * The fall. A cut polyp comes free where it was cut, its body's centre
 * (at) the head's atop its stalk (Ip) or half its height over its base,
 * and falls under gravity to the dependent wall of the lumen there
 * (tool_fall(), the loop's step after tool_step()): on the ring of the
 * centreline's frame at its place s_m (colon C's wall as the case draws
 * it, where the polyps are placed), the wall point lowest along
 * gravity, g's direction in the colon's frame (the patient's posture,
 * posture.h: +x lying on the left side, +y on the back; found among
 * TOOL_REST_COARSE points round the ring, then by golden section to
 * TOOL_REST_FINE steps), taken where the gas holds the wall (patient.h:
 * the lumen's radius factor f at its place scales the ring's radius r
 * about the centreline, as for the tip's contact and the picture: the
 * same lowest point round the ring), its body's radius (size / 2) in
 * along the ring's radius, f r - size / 2 from the centreline, is where
 * it comes to rest; lying there, it is carried with the wall as the gas
 * opens or collapses the lumen. (Where the polyps case's 6 mm polyp is
 * cut, in its descending colon collapsed to f 0.6, the case's own wall
 * lies 9 mm beyond the wall the scope touches and the picture shows.)
 * It goes to its rest along the straight line from where it is, as a
 * body of the full weight slowed by a linear drag: its speed v along the
 * line follows dv/dt = |g| - v / fall_drag_s, from rest at the cut, so
 * that the distance L takes t with
 *   L = |g| tau (t - tau (1 - exp(-t / tau))),   tau = fall_drag_s
 * (integrated exactly each step; it stops at its rest, v 0). The drag's
 * 0.1 s (terminal speed ~1 m/s; a 25 mm fall in 0.08 s, against 0.071
 * s free) stands for the mucus and the wall it slides along: a guess,
 * the fall a matter of a tenth of a second either way. A turn of the
 * patient (gravity turning) moves each rest to the new dependent side,
 * and the polyp follows it there. Each step finds one rest, in turn, of
 * the polyps whose gravity changed (or just cut: until its first rest is
 * found a cut polyp stays where it was cut, a step or a few). Without
 * gravity (g zero) or a case (an imported mesh) nothing falls.
 *
 * Retrieval. With the suction valve pressed and the channel's exit
 * within retrieve_reach_m (5 mm) of its body's surface where it lies, a
 * cut polyp no larger than retrieve_max_m (6 mm, a guess: soft tissue
 * squeezed through the 3.2-3.8 mm channel into the trap; larger ones
 * need a net) is sucked through the channel (TOOL_EVENT_RETRIEVE):
 * retrieved. A larger one stays where it lies.
 *
 * The bleeding's constants and retrieval's, like the channel's place,
 * the hot cut's and the cold snare's, are [tool] keys of the same names
 * (lib/conf/config.c, their defaults the TOOL_DEFAULT_* below); the
 * others are these defaults.
 *
 * Published: each cut polyp's place (at), and, for a session's record
 * (which keeps one place a cycle, not the 32), one cut polyp's a step in
 * turn (lying): the next one after the last, in the case's order, that
 * moved since it was last the one (a cut, a fall), or, none moving, the
 * next one lying; -1 with none cut.
 *
 * Each polyp's fate: in place, captured, cut (lying in the lumen) or
 * retrieved (its state); partly resected where the forceps bit one in
 * place too big to take whole (in place with bites, tool_polyp_fate()).
 *
 * At most one polyp's event a step (the *POLYP of tool_step()): a stop
 * by itself or a retrieval waits a step while another polyp's event
 * takes this one.
 *
 * Units SI. Plain data (copy it freely), no allocation, no logging; a
 * step's work is fixed: one pass over at most ANATOMY_MAX_POLYPS polyps
 * (p99 under 0.5 us with 32 in the loop on this project's VM:
 * bench_tool in `make bench`; with tool_fall() after it, every polyp
 * cut, gravity turning and the gas moving the wall, under 5 us). One
 * writer (the force loop); any thread may read a copy.
 */
#ifndef ENDOSIM_TOOL_H
#define ENDOSIM_TOOL_H

#include <stdbool.h>

#include "model/anatomy.h"
#include "proto/endosim_shm.h"

struct colon;

/* The published kinds and bits (endosim_shm.h), the model's. */
enum tool_kind {
	TOOL_NONE = ENDOSIM_TOOL_NONE,
	TOOL_FORCEPS = ENDOSIM_TOOL_FORCEPS,
	TOOL_SNARE = ENDOSIM_TOOL_SNARE,
	TOOL_NEEDLE = ENDOSIM_TOOL_NEEDLE,
	TOOL_CLIP = ENDOSIM_TOOL_CLIP,
};

/* A snare's sizes, its loop's diameter fully open, m; the one the nurse
 * hands over unless told (a standard loop's smallest). */
#define TOOL_SNARE_MIN_M 0.010
#define TOOL_SNARE_MAX_M 0.030
#define TOOL_DEFAULT_SNARE_M 0.015

enum tool_polyp_state {
	TOOL_POLYP_IN_PLACE = ENDOSIM_POLYP_IN_PLACE,
	TOOL_POLYP_CAPTURED = ENDOSIM_POLYP_CAPTURED, /* held in the loop */
	TOOL_POLYP_CUT = ENDOSIM_POLYP_CUT, /* cut free: lies in the lumen */
	TOOL_POLYP_RETRIEVED = ENDOSIM_POLYP_RETRIEVED, /* sucked out */
};

/* A polyp's fate, as the assessment asks: its state, or partly resected
 * (in place, bitten, too big for a bite to take whole). */
enum tool_polyp_fate {
	TOOL_FATE_IN_PLACE = TOOL_POLYP_IN_PLACE,
	TOOL_FATE_CAPTURED = TOOL_POLYP_CAPTURED,
	TOOL_FATE_CUT = TOOL_POLYP_CUT,
	TOOL_FATE_RETRIEVED = TOOL_POLYP_RETRIEVED,
	TOOL_FATE_PARTLY, /* bitten in place, too big for one bite */
};

/* A polyp's bleeding (enum endosim_bleed). */
enum tool_bleed {
	TOOL_BLEED_NONE = ENDOSIM_BLEED_NONE,
	TOOL_BLEED_BLEEDING = ENDOSIM_BLEED_BLEEDING,
	TOOL_BLEED_CLIPPED = ENDOSIM_BLEED_CLIPPED, /* a clip closed it */
	TOOL_BLEED_STOPPED = ENDOSIM_BLEED_STOPPED, /* by itself */
};

/* What happened in a step: tool_step()'s bits. */
#define TOOL_EVENT_CAPTURE ENDOSIM_TOOL_CAPTURE /* the loop closed on one */
#define TOOL_EVENT_RELEASE ENDOSIM_TOOL_RELEASE /* the handle opened */
#define TOOL_EVENT_CUT ENDOSIM_TOOL_CUT         /* a polyp cut free */
#define TOOL_EVENT_INJURY ENDOSIM_TOOL_INJURY   /* current into the wall */
#define TOOL_EVENT_LIFT ENDOSIM_TOOL_LIFT       /* an injection lifted one */
#define TOOL_EVENT_BITE ENDOSIM_TOOL_BITE       /* the forceps' sample */
#define TOOL_EVENT_CLIP ENDOSIM_TOOL_CLIP_PLACED /* a clip on the wall */
#define TOOL_EVENT_BLEED ENDOSIM_TOOL_BLEED     /* a cut stalk bleeds */
#define TOOL_EVENT_CLIPPED ENDOSIM_TOOL_CLIPPED /* a clip closed a point */
#define TOOL_EVENT_STOPPED ENDOSIM_TOOL_STOPPED /* one stopped by itself */
#define TOOL_EVENT_RETRIEVE ENDOSIM_TOOL_RETRIEVE /* a cut one sucked out */

struct tool_params {
	double channel_angle_rad; /* clockwise from 12 o'clock, image */
	double channel_offset_m;  /* the exit from the tip's axis */
	double cut_j_per_m2;      /* the hot cut's energy per area held */
	double hot_power_w;       /* into the tissue, pedal down */
	double cold_max_m;        /* thickness a cold snare cuts, below */
	double closed_opening;    /* the handle closed, at and below */
	double wire_m;            /* the snare wire's diameter */
	double lift_m;            /* what an injection lifts a base by */
	double needle_m;          /* the needle out of its catheter */
	double margin_m;          /* beyond a base's radius, still its */
	double inject_m3_per_s;   /* the injection's flow */
	double lift_m3;           /* what lifts a base */
	double jaw_m;             /* the forceps' cups, long */
	double forceps_max_m;     /* a polyp a bite takes whole, at most */
	double clip_m;            /* a clip's jaws, long */
	double coag_j_per_m3;     /* what coagulates a stalk, per volume */
	double bleed_min_m;       /* a stalk this thick or more bleeds */
	double bleed_m_per_s;     /* the flow per area of its section */
	double bleed_stop_s;      /* a bleed stops by itself after */
	double retrieve_max_m;    /* the largest the channel sucks out */
	double retrieve_reach_m;  /* the exit from its surface, at most */
	double fall_drag_s;       /* a cut one's fall: the drag's tau */
};

#define TOOL_DEFAULT_CHANNEL_ANGLE_DEG 150.0
#define TOOL_DEFAULT_CHANNEL_ANGLE_RAD (TOOL_DEFAULT_CHANNEL_ANGLE_DEG * \
					TOOL_RAD_PER_DEG)
#define TOOL_RAD_PER_DEG (3.14159265358979323846 / 180)
#define TOOL_DEFAULT_CHANNEL_OFFSET_M 0.004
#define TOOL_DEFAULT_CUT_J_PER_M2 2.5e6
#define TOOL_DEFAULT_HOT_POWER_W 30.0
#define TOOL_DEFAULT_COLD_MAX_M 0.010
#define TOOL_DEFAULT_CLOSED_OPENING 0.02
#define TOOL_DEFAULT_WIRE_M 0.0004
#define TOOL_DEFAULT_LIFT_M 0.004
#define TOOL_DEFAULT_NEEDLE_M 0.004
#define TOOL_DEFAULT_MARGIN_M 0.005
#define TOOL_DEFAULT_INJECT_M3_PER_S 1e-6
#define TOOL_DEFAULT_LIFT_M3 3e-6
#define TOOL_DEFAULT_JAW_M 0.0025
#define TOOL_DEFAULT_FORCEPS_MAX_M 0.003
#define TOOL_DEFAULT_CLIP_M 0.005
#define TOOL_DEFAULT_COAG_J_PER_M3 2.5e8
#define TOOL_DEFAULT_BLEED_MIN_M 0.003
#define TOOL_DEFAULT_BLEED_M_PER_S 1e-3
#define TOOL_DEFAULT_BLEED_STOP_S 300.0
#define TOOL_DEFAULT_RETRIEVE_MAX_M 0.006
#define TOOL_DEFAULT_RETRIEVE_REACH_M 0.005
#define TOOL_DEFAULT_FALL_DRAG_S 0.1
/* A rest's search round its ring: coarse points, then golden steps. */
#define TOOL_REST_COARSE 24
#define TOOL_REST_FINE 12

#define TOOL_PARAMS_DEFAULT { \
		.channel_angle_rad = TOOL_DEFAULT_CHANNEL_ANGLE_RAD, \
		.channel_offset_m = TOOL_DEFAULT_CHANNEL_OFFSET_M, \
		.cut_j_per_m2 = TOOL_DEFAULT_CUT_J_PER_M2, \
		.hot_power_w = TOOL_DEFAULT_HOT_POWER_W, \
		.cold_max_m = TOOL_DEFAULT_COLD_MAX_M, \
		.closed_opening = TOOL_DEFAULT_CLOSED_OPENING, \
		.wire_m = TOOL_DEFAULT_WIRE_M, .lift_m = TOOL_DEFAULT_LIFT_M, \
		.needle_m = TOOL_DEFAULT_NEEDLE_M, \
		.margin_m = TOOL_DEFAULT_MARGIN_M, \
		.inject_m3_per_s = TOOL_DEFAULT_INJECT_M3_PER_S, \
		.lift_m3 = TOOL_DEFAULT_LIFT_M3, .jaw_m = TOOL_DEFAULT_JAW_M, \
		.forceps_max_m = TOOL_DEFAULT_FORCEPS_MAX_M, \
		.clip_m = TOOL_DEFAULT_CLIP_M, \
		.coag_j_per_m3 = TOOL_DEFAULT_COAG_J_PER_M3, \
		.bleed_min_m = TOOL_DEFAULT_BLEED_MIN_M, \
		.bleed_m_per_s = TOOL_DEFAULT_BLEED_M_PER_S, \
		.bleed_stop_s = TOOL_DEFAULT_BLEED_STOP_S, \
		.retrieve_max_m = TOOL_DEFAULT_RETRIEVE_MAX_M, \
		.retrieve_reach_m = TOOL_DEFAULT_RETRIEVE_REACH_M, \
		.fall_drag_s = TOOL_DEFAULT_FALL_DRAG_S }

/* What the rig senses of the tool this cycle. */
struct tool_input {
	double depth_m;        /* its tip beyond the channel's exit */
	double opening;        /* the handle, 0 closed .. 1 open */
	bool pedal;            /* the cautery's, down */
	bool suction;          /* the suction valve pressed */
	bool wall;             /* whether wall_point and wall_normal hold */
	double wall_point[3];  /* the wall nearest the tool's tip, m */
	double wall_normal[3]; /* unit, into the lumen */
};

/* Where the tool is: in the colon's frame, as the scope's tip. */
struct tool_pose {
	double exit[3];   /* the channel's exit on the tip's face, m */
	double tip[3];    /* the tool's tip (the snare's sheath's), m */
	double dir[3];    /* unit, the tool's (the tip's) direction */
	double radial[3]; /* unit, from the tip's axis to the exit */
	double side[3];   /* unit, dir x radial: the loop's width */
};

/* A polyp as the snare sees it. */
struct tool_polyp {
	double base[3];      /* on the wall, m */
	double normal[3];    /* the wall's there, unit, into the lumen */
	bool on_wall;        /* placed on a colon (tool_place_polyps()): its
				base follows the wall (tool_follow_wall()) */
	double angle_rad;    /* ... round the lumen from the frame's u */
	double wall_r_m;     /* ... the case's lumen radius there */
	double size_m;       /* anatomy's diameter_m */
	double stalk_m;      /* Ip: the stalk's length; 0 otherwise */
	double stalk_diameter_m; /* Ip: its thickness; 0 otherwise */
	int paris;           /* enum anatomy_paris */
	double injected_m3;  /* under its base so far */
	int bites;           /* the forceps' on it */
	bool lifted;         /* by an injection */
	int state;           /* enum tool_polyp_state */
	bool inside;         /* its axis inside the loop, last step */
	double energy_j;     /* the cautery's into it so far */
	double s_m;          /* its place along the centreline (the case's) */
	int bleed;           /* enum tool_bleed */
	double bleed_m3_s;   /* its flow now */
	double bleed_s;      /* how long it has bled */
	double blood_m3;     /* shed so far */
	double at[3];        /* cut: its body's centre, where it lies, m */
	double rest[3];      /* cut: where it comes to rest, m (by the
				undeformed wall) */
	double rest_wall[3]; /* ... the ring's radius out to that wall, m:
				the gas's factor f moves the wall, and the
				rest, by (f - 1) times it */
	bool rest_ok;        /* rest is for the gravity of t->down */
	bool lies;           /* at its rest: carried with the wall */
	double fall_v;       /* cut: its speed towards rest, m/s */
	bool moved;          /* since it was last the published lying one */
};

struct tool {
	int kind;            /* enum tool_kind */
	double snare_m;      /* the snare's size, D */
	double depth_m;      /* the last finite input's */
	double opening;
	bool pedal;          /* the last step's (up while the input is stale) */
	struct tool_pose pose;
	double command_m;    /* the loop's diameter the handle asks for */
	double loop_m;       /* the loop's: command_m, or a held thickness */
	double loop_centre[3]; /* the snare's loop, m */
	double needle[3];    /* the needle's point, out or not, m */
	double jaws[3];      /* the forceps' or the clip's point, m */
	bool armed;          /* their handle opened since they closed */
	double injury_at[3]; /* the last TOOL_EVENT_INJURY's place, m */
	double bite_at[3];   /* the last bite's, m */
	double clip_at[3];   /* the last clip's, m */
	int clips;           /* placed */
	double blood_m3;     /* every point's shed since the case loaded */
	int captured;        /* the polyp the loop holds; -1 none */
	int lying;           /* the cut one published this step; -1 none */
	int next_rest;       /* whose rest is sought first next step */
	double down[3];      /* gravity's direction the rests are for */
	bool injured;        /* this press of the pedal has injured */
	int polyps;
	struct tool_polyp polyp[ANATOMY_MAX_POLYPS];
};

/* No tool, no polyps. */
void tool_reset(struct tool *t);

/*
 * The tool the nurse hands over: KIND (enum tool_kind) and, for a snare,
 * its size SNARE_M (TOOL_SNARE_MIN_M..TOOL_SNARE_MAX_M). Lets go of a
 * captured polyp. Returns 0 or -EINVAL (T unchanged).
 */
int tool_select(struct tool *t, int kind, double snare_m);

/*
 * A polyp of the case, AP, standing at BASE (m) on the wall whose normal
 * into the lumen is NORMAL (made unit). Returns its index, or -ENOSPC
 * past ANATOMY_MAX_POLYPS, -EINVAL for a zero normal.
 */
int tool_add_polyp(struct tool *t, const struct anatomy_polyp *ap,
		   const double base[3], const double normal[3]);

/*
 * The case's polyps on colon C's undeformed wall (colon_lumen_radius() at
 * each polyp's place; tool_follow_wall() moves them with the wall), after
 * any added before. Returns the number added,
 * or a negative errno; 0 for an imported mesh (no case, no polyps).
 * Not for the force loop (it reads the centreline).
 */
int tool_place_polyps(struct tool *t, const struct colon *c);

/*
 * The wall nearest the tool's tip into IN (wall, wall_point, wall_normal):
 * colon C's wall where the gas holds it (the undeformed wall's radius
 * times the gas's factor at S_M, gas_factor_at() of FACTOR; NULL: 1, no
 * patient), the surface the scope's contact and the picture have, on the
 * ring of the centreline's frame at the material S_M nearest the tip, in
 * the tip's direction from the centreline. No wall for an imported mesh
 * (no case). Fixed work, no allocation: the force loop's.
 */
void tool_wall(const struct colon *c, double s_m, const double tip[3],
	       const double *factor, struct tool_input *in);

/*
 * The polyps placed on colon C (tool_place_polyps()) moved with its wall
 * as it is now: each one's base (and so its axis, its stump and its
 * bleeding point) on the ring of C's centreline as the scope has moved
 * it (a bowed or displaced segment) at its s_m, at its angle, the case's
 * radius there times the gas's factor (gas_factor_at() of FACTOR; NULL:
 * 1), its normal that ring's, into the lumen. Before tool_step(), each
 * cycle. Fixed work, no allocation: the force loop's.
 */
void tool_follow_wall(struct tool *t, const struct colon *c,
		      const double *factor);

/* Polyp P's body's centre standing where it is (where a cut frees it,
 * tool.h's fall) with PAR's lift, into AT (m). */
void tool_polyp_body(const struct tool_polyp *p, const struct tool_params *par,
		     double at[3]);

/* Polyp P's bleeding point's flow (m^3/s) when it bleeds, with PAR's
 * bleed_m_per_s: Q = bleed_m_per_s x pi t^2 / 4 of its stalk. */
double tool_polyp_flow(const struct tool_polyp *p,
		       const struct tool_params *par);

/* The thickness (m) and the height (m) of polyp P's axis, which the loop
 * must close around, with lift LIFT_M (tool_params' lift_m). */
double tool_polyp_thickness(const struct tool_polyp *p);
double tool_polyp_height(const struct tool_polyp *p, double lift_m);


/*
 * The loop's diameter (m) of a snare of size SNARE_M with its handle at
 * OPENING (clamped to 0..1) and its sheath's tip at DEPTH_M beyond the
 * channel's exit (above: min(D, 2 l / pi)).
 */
double tool_loop_diameter(double snare_m, double opening, double depth_m);

/* Polyp P's fate (enum tool_polyp_fate) with PAR's forceps_max_m. */
int tool_polyp_fate(const struct tool_polyp *p, const struct tool_params *par);

/*
 * The cut polyps' fall (above), a step of DT_S seconds after tool_step():
 * on colon C's rings (NULL, or an imported mesh: none falls) under
 * gravity G (m/s^2, colon frame; zero: none falls), the wall where the
 * gas holds it (FACTOR: the lumen's GAS_SEGMENTS radius factors,
 * gas_factor_at()'s; NULL: the undeformed wall); and the cut polyp
 * published this step (T->lying). Fixed work, no allocation: at most one
 * rest found (TOOL_REST_COARSE + TOOL_REST_FINE of the lumen's radius), a
 * pass or two over the polyps, a factor each cut one. The force loop's.
 */
void tool_fall(struct tool *t, const struct tool_params *par,
	       const struct colon *c, const double g[3],
	       const double *factor, double dt_s);

/* T as published, with this step's EVENTS and the POLYP they concern. */
void tool_publish(const struct tool *t, unsigned events, int polyp,
		  struct endosim_tool_state *out);

/* The tool's pose at DEPTH_M on the scope's tip in SC (tip, dir, up). */
void tool_pose(const struct tool_params *par,
	       const struct endosim_scope_state *sc, double depth_m,
	       struct tool_pose *out);

/*
 * The depth (m) tool_step() takes from IN: its own, or T's last while IN
 * is still (a depth or an opening not finite: a stale reading). The
 * caller finds the wall at the tool's tip with it before the step.
 */
double tool_input_depth(const struct tool *t, const struct tool_input *in);

/*
 * One step of DT_S seconds: the pose, the snare's loop, capture, the
 * cut, the wall; the needle's injection. Returns the TOOL_EVENT_* bits
 * of what happened; the polyp concerned is T->captured for a capture,
 * the one just released, cut, lifted or bitten otherwise (*POLYP, -1 if none;
 * POLYP may be NULL). Non-finite inputs count as the tool still: depth
 * and opening as in the step before, the pedal up.
 */
unsigned tool_step(struct tool *t, const struct tool_params *par,
		   const struct endosim_scope_state *sc,
		   const struct tool_input *in, double dt_s, int *polyp);

#endif
