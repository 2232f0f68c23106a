/*
 * metrics.h - how a trainee did: the training session's metrics, computed
 * from the recorded states (struct session_record) one by one, the same
 * way live in endosimd's recorder thread and afterwards from a session
 * file (endoctl session show/report on a file cut short).
 *
 * What is measured (definitions, thresholds and units in metrics.c's
 * comments and in docs/SESSION_FORMAT.md):
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
 *   - the patient-discomfort index: the time integral of loop stretch and
 *     wall-contact force (see metrics.c for the formula);
 *   - time with the lumen lost from view: the tip facing a wall;
 *   - the share of the mucosa seen: the mesh's area that came into the
 *     camera's view (field of view, within view_distance_m) at some pose;
 *   - polyps seen (those of the case that came into view).
 *
 * Threads: one struct metrics belongs to one thread. metrics_create()
 * allocates (the colon's per-vertex bookkeeping); metrics_record() does
 * not allocate or block and costs microseconds (the mucosa and polyps are
 * evaluated at most view_rate_hz times a second).
 */
#ifndef ENDOSIM_METRICS_H
#define ENDOSIM_METRICS_H

#include <stddef.h>
#include <stdint.h>

#include "colon.h"
#include "session_file.h"

#define METRICS_MAX_EPISODES 64 /* kept per kind; more are counted only */

struct metrics_params {
	double force_threshold_n;  /* excessive insertion force, N */
	double loop_threshold_m;   /* a loop: bow amplitude above this, m */
	double view_distance_m;    /* mucosa nearer than this can be seen */
	double fov_rad;            /* the camera's full field of view */
	double view_rate_hz;       /* mucosa and polyps evaluated this often */
};

/* Defaults: 15 N, 0.01 m, 0.06 m, 140 deg, 20 Hz. */
void metrics_params_default(struct metrics_params *p);

struct metrics_episode {
	double start_s;            /* since the session's first record */
	double end_s;              /* < 0: still going */
	double peak;               /* N for force, m for loops */
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
	double discomfort;         /* the index, see metrics.c */
	double lumen_lost_s;
	double mucosa_seen;        /* share 0..1 of the mesh's area */
	uint32_t polyps_seen;
	uint32_t polyps_total;
	uint32_t n_force;          /* episodes kept below */
	uint32_t n_loop;
	struct metrics_episode force[METRICS_MAX_EPISODES];
	struct metrics_episode loop[METRICS_MAX_EPISODES];
};

struct metrics;

/*
 * COLON: the colon the session is on (kept, not copied: it must outlive
 * the metrics); NULL computes everything but the mucosa and polyps.
 * Returns NULL on allocation failure.
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

/*
 * RESULT as "key=value\n" lines (the END frame, `session show`); returns
 * the length written, or -ENOSPC when SIZE is too small.
 */
int metrics_format(const struct metrics_result *result, char *buf,
		   size_t size);

/* The inverse of metrics_format(): 0, or -EINVAL naming nothing. */
int metrics_parse(const char *text, struct metrics_result *out);

#endif
