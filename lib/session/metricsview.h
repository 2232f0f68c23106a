/*
 * metricsview.h - what the metrics (metrics.h) make of the camera's view
 * of a colon: whether the lumen is in view at a record, the mucosa seen
 * (its share of the mesh's area, by segment, on the unrolled map) and the
 * polyps found, from the records' poses (definitions in metricsview.c and
 * docs/METRICS.md).
 *
 * The colon is read, never written: only what never changes after
 * colon_create() (the undeformed centreline, the mesh's offsets, normals
 * and triangles), so that the force loop may bow it meanwhile; the view
 * bows a private copy of the centreline as the records say.
 *
 * A NULL view (no colon) sees nothing: no lumen lost, nothing seen, no
 * polyps, a map of no wall. One thread at a time. metricsview_create()
 * allocates; metricsview_record() does not, and costs about a millisecond
 * at the records it evaluates (at most view_rate_hz a second).
 */
#ifndef ENDOSIM_METRICSVIEW_H
#define ENDOSIM_METRICSVIEW_H

#include <stdbool.h>
#include <stdint.h>

#include "model/colon.h"
#include "proto/session_file.h"
#include "session/metrics.h"

struct metricsview;

/* The view of COLON (kept: it must outlive the view) with P's
 * view_distance_m, fov_rad, view_rate_hz, seen_dwell_s, polyp_dwell_s
 * and lumen_angle_rad. NULL on ENOMEM. */
struct metricsview *metricsview_create(const struct colon *colon,
				       const struct metrics_params *p);

/* NULL is fine. */
void metricsview_destroy(struct metricsview *v);

/*
 * R, at T_S (s since the session's first record), with the tube inserted:
 * the mucosa and the polyps in view, when view_rate_hz allows (the first
 * time, then every 1 / view_rate_hz s) and R has a pose to look from.
 */
void metricsview_record(struct metricsview *v, const struct session_record *r,
			double t_s);

/* At R, inserted: the lumen out of view (R facing away from it, or
 * pressed into a wall that faces it). */
bool metricsview_lumen_lost(const struct metricsview *v,
			    const struct session_record *r);

/* The share 0..1 of the mesh's area seen so far. */
double metricsview_seen(const struct metricsview *v);

/* metrics_mucosa_seen_in()'s (metrics.h). */
double metricsview_seen_in(const struct metricsview *v, double s0_m,
			   double s1_m, double a0_rad, double a1_rad);

/* The case's polyps found so far: bit k its polyp k. */
uint32_t metricsview_found(const struct metricsview *v);

/* How many polyps the case has (at most ANATOMY_MAX_POLYPS). */
int metricsview_polyps(const struct metricsview *v);

/* metrics_map()'s (metrics.h). */
void metricsview_map(const struct metricsview *v, struct metrics_map *out);

#endif
