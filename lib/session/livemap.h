/*
 * livemap.h - the unseen-mucosa map on the wire: metrics_map()'s shares
 * (float, < 0: no wall) quantised to a byte per cell for the SessionMap
 * reply (proto/endosim.proto MapReply) and back for endoview's overlay
 * and endoctl. The cells are along-major: cell (i, k), i along the colon
 * (0 .. METRICS_MAP_S-1), k around it (0 .. METRICS_MAP_A-1), at byte
 * i * METRICS_MAP_A + k.
 *
 * Pure functions: any thread, no allocation.
 */
#ifndef ENDOSIM_LIVEMAP_H
#define ENDOSIM_LIVEMAP_H

#include <stddef.h>
#include <stdint.h>

#include "session/metrics.h"

#define LIVEMAP_CELLS (METRICS_MAP_S * METRICS_MAP_A)
#define LIVEMAP_FULL 254   /* a cell's wall all seen */
#define LIVEMAP_NO_WALL 255

/* MAP's shares as bytes: round(share x LIVEMAP_FULL), clamped to 0..254;
 * a cell without wall (or a share that is not a number) LIVEMAP_NO_WALL. */
void livemap_quantise(const struct metrics_map *map,
		      uint8_t cells[LIVEMAP_CELLS]);

/* A byte's share 0..1 of its wall seen; -1 for LIVEMAP_NO_WALL. */
double livemap_share(uint8_t cell);

/*
 * The map's colour ramp, the one the report (report.h) and endoview's
 * overlay (viewer/mapview.h) paint a cell with: its share seen 0..1 as a
 * colour from unseen, red, to seen, green, each channel linear in the
 * share, 0..255 (sRGB). Its ends are the background's: on the report's
 * white page a pale green reads as seen; on endoview's dark overlay a
 * deeper green (and a brighter red) does.
 */
enum livemap_background {
	LIVEMAP_ON_PAGE,   /* the report's: 214,60,60 to 154,230,180 */
	LIVEMAP_ON_SCREEN, /* endoview's */
};

/* SHARE's colour on BG into RGB (0..255 each). */
void livemap_colour(enum livemap_background bg, double share,
		    double rgb[3]);

/*
 * The mean share seen over the N cells with wall (each cell counted
 * alike, not by its area: metrics_result's mucosa_seen weighs by area);
 * 0 when none has wall.
 */
double livemap_mean_seen(const uint8_t *cells, size_t n);

#endif
