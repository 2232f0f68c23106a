/*
 * metrics.h - how a trainee did: the training session's metrics, computed
 * from the recorded states (struct session_record) one by one, the same
 * way live in endosimd's recorder thread and afterwards from a session
 * file (endoctl session show/report on a file cut short).
 *
 * What is measured (definitions, thresholds, units and the limits of each
 * method in docs/METRICS.md; the formulas also in metrics.c and, for
 * what the camera sees, metricsview.c):
 *   - time to the cecum: from the first record to the first with the tip
 *     in the cecum segment; insertion time (to the cecum) and withdrawal
 *     time (from the cecum until the tip leaves the rectum or the session
 *     ends); withdrawal of at least 6 minutes is a clinical quality mark;
 *   - the insertion force (the insertion axis' force sent to the drive,
 *     N): peak and mean while inserted; episodes above force_threshold_n
 *     ("excessive pressure"): count, total time, each with its start,
 *     end and peak;
 *   - loop episodes: a mobile segment bowed more than loop_threshold_m;
 *     count, longest, largest amplitude, each with start, end, peak;
 *   - the patient (the records' pain, lib/model/pain.h): the share of the
 *     time in pain (at or above pain_level), the peak, pain episodes each
 *     with its cause and place, the time in pain by cause, an estimated
 *     Gloucester comfort score; the gas pumped in and its largest
 *     pressure; the patient's turns, the assistant's presses and the
 *     perforations (bursts and tears);
 *   - time with the lumen lost from view: the tip facing a wall; how
 *     often it was lost; the share of the time with it in view;
 *   - the scope's handling (3D-CoPS, CoRS): the shaft pushed in and the
 *     tip's advance, their ratio (chase efficiency), the shaft pushed
 *     without the tip following, the time looped; on the way out the
 *     shaft withdrawn, the tip's retreat, their ratio;
 *   - the share of the mucosa seen: the mesh's area in the camera's view
 *     (field of view, within view_distance_m, not hidden behind a fold:
 *     a depth test on the CPU, depthmap.h) for seen_dwell_s in all;
 *   - polyps found: those of the case in view for polyp_dwell_s in all;
 *   - the therapy through the working channel (therapy.h): each polyp's
 *     fate, the time per resection, the cautery, the wall injured, the
 *     biopsies and the clips;
 *   - along the colon (metrics_along(), not in the result: the report
 *     recomputes it): per anatomical segment of the case, the time the
 *     tip spent there, in pain, looped, and the peak pain and force there.
 *
 * Threads: one struct metrics belongs to one thread. metrics_create()
 * allocates (the colon's per-vertex bookkeeping); metrics_record() does
 * not allocate or block and costs microseconds, and about a millisecond at
 * the records where the mucosa and polyps are evaluated (at most
 * view_rate_hz times a second; `make bench`).
 */
#ifndef ENDOSIM_METRICS_H
#define ENDOSIM_METRICS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "model/colon.h"
#include "proto/session_file.h"

#define METRICS_MAX_EPISODES 64 /* kept per kind; more are counted only */

struct metrics_params {
	double force_threshold_n;  /* excessive insertion force, N */
	double loop_threshold_m;   /* a loop: bow amplitude above this, m */
	double view_distance_m;    /* mucosa nearer than this can be seen */
	double fov_rad;            /* the camera's full field of view */
	double view_rate_hz;       /* mucosa and polyps evaluated this often */
	/* episodes: above the threshold for at least min_episode_s; one
	 * ends when the value falls below METRICS_HYSTERESIS x threshold */
	double min_episode_s;
	/* the lumen is lost when its direction 3 cm ahead is further than
	 * this from the view direction (default: half the field of view) */
	double lumen_angle_rad;
	/* the patient is in pain at a pain (0..10) at or above this; a
	 * pain episode starts there (and ends as the others do) */
	double pain_level;
	/* in view so long in all before a wall point counts as seen, a
	 * polyp as found (the virtual-withdrawal study, BMC Med Educ 2017) */
	double seen_dwell_s;
	double polyp_dwell_s;
};

#define METRICS_HYSTERESIS 0.9      /* an episode ends below 0.9 x threshold */
#define METRICS_LOOKAHEAD_M 0.03    /* the lumen ahead: this far beyond tip_s */
#define METRICS_SHAPE_STEP_S 0.1  /* the handling's sampling: 10 Hz */
#define METRICS_IDLE_SHARE 0.2    /* the tip advancing less than this share
				     of the shaft's push: an idle push */
#define METRICS_PA_PER_MMHG 133.322387 /* the gas pressure shown in mmHg */
#define METRICS_EXIT_S_M 0.04       /* out: the tip below this s (an imported
				       colon; a case: the rectum's start) */

/* The defaults of the thresholds that the configuration's [session] sets
 * (the configuration, a wing below this one, writes them again; test_config
 * holds the two together). The loop threshold is the paper model's. */
#define METRICS_DEFAULT_FORCE_THRESHOLD_N 15
#define METRICS_DEFAULT_LOOP_THRESHOLD_M 0.01
#define METRICS_DEFAULT_VIEW_DISTANCE_M 0.06
#define METRICS_DEFAULT_FOV_DEG 140
#define METRICS_DEFAULT_VIEW_RATE_HZ 10
#define METRICS_DEFAULT_PAIN_LEVEL 4 /* the numeric rating scale's
					moderate pain: 4..6 */

/* The estimated Gloucester comfort score (metrics.c has the mapping): a
 * pain episode peaking at or above this is severe (the rating scale's
 * 7..10); in pain this share of the time or more is frequent (4), this
 * share or more prolonged (5). */
#define METRICS_GLOUCESTER_SEVERE_PAIN 7.0
#define METRICS_GLOUCESTER_FREQUENT_SHARE 0.10
#define METRICS_GLOUCESTER_PROLONGED_SHARE 0.25

/* Defaults: the above, and 0.2 s, 70 deg, 0.5 s, 2.5 s. */
void metrics_params_default(struct metrics_params *p);

struct metrics_episode {
	double start_s;            /* since the session's first record */
	double end_s;              /* < 0: still going */
	double peak;               /* N for force, m for loops, pain 0..10 */
	/* pain episodes only (0 and -1 for the others): the cause (enum
	 * endosim_pain_cause) and the place (anatomy segment, -1: none) of
	 * its provocation, the record with the largest stimulus from when the
	 * pain was last below an episode's end to the episode's first record:
	 * what brought it on (without a recorded stimulus:
	 * at the episode's peak, the first record at its peak; a record
	 * with no cause, the pain fading, takes the last cause before it) */
	uint32_t cause;
	int32_t place;
};

/* A polyp's fate at the end (therapy.h has the rules). */
enum metrics_fate {
	METRICS_FATE_LEFT = 0,      /* in place, untouched */
	METRICS_FATE_PARTLY = 1,    /* in place, bitten or burnt */
	METRICS_FATE_COMPLETE = 2,  /* cut free whole */
	METRICS_FATE_RETRIEVED = 3, /* ... and retrieved (format 7) */
	METRICS_FATES
};

#define METRICS_MAX_POLYPS ANATOMY_MAX_POLYPS

/* One of the case's polyps as the therapy left it (therapy.h). */
struct metrics_polyp {
	uint32_t fate;             /* enum metrics_fate */
	uint32_t bites;            /* the forceps' on it */
	double start_s;            /* the first tool's event on it; -1 none */
	double cut_s;              /* cut free; -1: not */
	double cautery_s;          /* the pedal down while the loop held it */
};

struct metrics_result {
	double duration_s;         /* first to last record */
	uint64_t records;
	uint64_t drops;            /* records the recorder could not keep */
	double cecum_s;            /* time to the cecum; < 0: not reached */
	double insertion_s;        /* to the cecum (or so far) */
	double withdrawal_s;       /* from the cecum out; 0 if not reached */
	double max_tip_s_m;        /* deepest the tip got along the colon */
	double peak_insertion_n;   /* |force| on the insertion axis */
	double mean_insertion_n;   /* while inserted (depth > 0) */
	uint32_t force_episodes;
	double force_episode_s;    /* their total time */
	uint32_t loop_episodes;
	double longest_loop_s;
	double largest_loop_m;
	double lumen_lost_s;
	double mucosa_seen;        /* share 0..1 of the mesh's area */
	uint32_t polyps_seen;
	uint32_t polyps_total;
	uint32_t polyps_seen_mask; /* bit k: the case's polyp k was seen */
	/* the scope's handling, from the tube's depth and the tip's place
	 * along the colon sampled every METRICS_SHAPE_STEP_S (3D-CoPS and
	 * CoRS in spirit; docs/METRICS.md): on the way in (to the cecum, or
	 * all of it when never reached) ... */
	double shaft_in_m;         /* the shaft pushed in, summed */
	double tip_in_m;           /* the tip's advance along the colon */
	double chase_efficiency;   /* tip_in_m / shaft_in_m (0: none) */
	double shaft_idle_m;       /* pushed in while the tip advanced less
				      than METRICS_IDLE_SHARE of it */
	double loop_s;             /* time with a loop (a mobile segment
				      bowed beyond loop_threshold_m), sampled
				      as the handling */
	/* ... and on the way out (from the cecum) */
	double retraction_m;       /* the shaft withdrawn, summed */
	double tip_retraction_m;   /* the tip's retreat along the colon */
	double retraction_efficiency; /* tip_retraction_m / retraction_m */
	/* the view */
	double clear_view;         /* share 0..1 of the inserted time with
				      the lumen in view */
	uint32_t lost_views;       /* times the lumen was lost */
	double mucosa_per_min;     /* mucosa_seen in % a minute: efficiency */
	double mucosa_segment[ANATOMY_SEGMENTS]; /* seen, each segment's
					   share (anal canal .. cecum); 0
					   without a case */
	/* the patient (records with it enabled; 0 without) */
	double pain_share;         /* 0..1 of duration_s with pain at or
				      above pain_level */
	double peak_pain;          /* 0..10 */
	uint32_t pain_episodes;    /* at or above pain_level */
	double pain_cause_s[ENDOSIM_PAIN_CAUSES]; /* s in pain by cause (enum
					   endosim_pain_cause; none: the
					   pain before any cause) */
	uint32_t gloucester;       /* estimated comfort score 1..5; 0: no
				      responding patient (disabled, or a
				      file of format 4 or older) */
	double gas_used_l;         /* gas pumped in (gas_in_m3's rises), L */
	double peak_gas_pressure_pa; /* the largest gas pressure, Pa */
	uint32_t position_changes; /* the patient turned (a turn started) */
	uint32_t hand_uses;        /* the assistant pressed (a site taken) */
	uint32_t perforations;     /* bursts by pressure and tears by the
				      tip (each segment torn, each time) */
	/* the therapy through the working channel (therapy.h) */
	uint32_t polyps_resected;  /* cut free whole (retrieved or not) */
	uint32_t polyps_partly;    /* in place, bitten or burnt */
	uint32_t polyps_retrieved; /* cut and retrieved (format 7) */
	double resection_s;        /* the mean time per resection; 0: none */
	double cautery_s;          /* the pedal down */
	uint32_t tool_injuries;    /* current into the wall */
	uint32_t biopsies;         /* the forceps' bites */
	uint32_t clips;            /* placed */
	uint32_t bleeds;           /* bleeding points (format 7) */
	uint32_t bleeds_clipped;   /* ... stopped by a clip */
	double bleed_control_s;    /* the mean time from a bleeding's start to
				      its stop, by a clip or by itself, over
				      those stopped; 0: none */
	uint32_t n_polyp;          /* of polyp[]: 0 without a tool in hand */
	struct metrics_polyp polyp[METRICS_MAX_POLYPS];
	uint32_t n_force;          /* episodes kept below */
	uint32_t n_loop;
	uint32_t n_pain;
	struct metrics_episode force[METRICS_MAX_EPISODES];
	struct metrics_episode loop[METRICS_MAX_EPISODES];
	struct metrics_episode pain[METRICS_MAX_EPISODES];
};

/*
 * Along the colon: each anatomical segment's share of the session, over
 * the records with the tip in it (inserted, depth_m > 0, and tip_s_m
 * within the segment's bounds of the case's anatomy; before the anal
 * canal counts for it, past the cecum's end for the cecum). A record's
 * state holds until the next record, as for pain_share, so the times sum
 * to the time the tip was in; the peaks are the records' own.
 */
struct metrics_segment {
	double time_s;             /* the tip there */
	double pain_s;             /* ... the pain at or above pain_level */
	double loop_s;             /* ... looped: any bow above
				      loop_threshold_m (as the loop episodes) */
	double peak_pain;          /* 0..10 (records with the patient) */
	double peak_force_n;       /* |insertion force| (as the force
				      episodes' F), N */
};

struct metrics_along {
	bool segments;             /* false: no case's anatomy (no colon, or
				      an imported one): all below 0 */
	struct metrics_segment seg[ANATOMY_SEGMENTS]; /* anal canal .. cecum */
};

struct metrics;

/*
 * COLON: the colon the session is on (kept, not copied: it must outlive
 * the metrics). Only what never changes after colon_create() is read (the
 * undeformed centreline, the mesh's offsets, normals and triangles), never
 * the bowed state, so the force loop may bow COLON meanwhile: the metrics
 * bow a private copy of the centreline. NULL computes everything but what
 * needs the colon's geometry: the cecum (and so the insertion and
 * withdrawal times), the lumen, the mucosa and the polyps. Returns NULL
 * on allocation failure.
 */
struct metrics *metrics_create(const struct colon *colon,
			       const struct metrics_params *p);
void metrics_destroy(struct metrics *m);

/* The next record, in time order. */
void metrics_record(struct metrics *m, const struct session_record *r);

/* An event of the session (drops are counted from SESSION_EVENT_DROPS). */
void metrics_event(struct metrics *m, const struct session_event *ev,
		   const char *text);

/* The metrics so far (at the end: the session's). */
void metrics_result(const struct metrics *m, struct metrics_result *out);

/* Whether R has any of the patient's measures: a responding patient, or
 * the body's gas, turns, presses or perforations (a file of format 4);
 * false for a session without the patient or older. */
bool metrics_has_patient(const struct metrics_result *r);

/* The measures along the colon so far (struct metrics_along). */
void metrics_along(const struct metrics *m, struct metrics_along *out);

/* The share 0..1 of the mesh's area between material S0_M and S1_M (by
 * each vertex' centreline sample) seen so far; 0 without a colon. */
double metrics_mucosa_seen_between(const struct metrics *m, double s0_m,
				   double s1_m);

/* The same of the wall between S0_M and S1_M and at angles A0_RAD to
 * A1_RAD (0 <= A0_RAD <= A1_RAD <= 2 pi) around the centreline from its
 * frame's u towards v, as metrics_map() and the case's polyps count them. */
double metrics_mucosa_seen_in(const struct metrics *m, double s0_m,
			      double s1_m, double a0_rad, double a1_rad);

/* The colon unrolled: METRICS_MAP_S cells along it, METRICS_MAP_A around. */
#define METRICS_MAP_S 160
#define METRICS_MAP_A 24

struct metrics_map {
	double length_m;          /* the colon's, along its centreline */
	/* each cell's share 0..1 of its wall's area seen; < 0: no wall there
	 * (a cell of the pole, past the end) */
	float seen[METRICS_MAP_S][METRICS_MAP_A];
};

/*
 * The unseen-mucosa map so far: each vertex (by its place along the
 * colon and its angle around the centreline from the frame's u, as the
 * case's polyps are placed) into its cell, the seen area over the area.
 * Without a colon every cell < 0. The cells are kept as vertices are
 * seen: a map costs a pass over the cells, not the mesh.
 */
void metrics_map(const struct metrics *m, struct metrics_map *out);

#endif
