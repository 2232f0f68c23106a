/*
 * mapview.h - endoview's unseen-mucosa overlay (the M key): the recording
 * session's map as endosimd's recorder keeps it (SessionMap over the
 * read-only socket; the cells as livemap.h quantises them), drawn across
 * the bottom of the window: the colon unrolled from the anal verge (left)
 * to the cecum (right), around it from the centreline frame's u (top) to
 * a full turn (bottom); each cell red while its wall is unseen, green
 * once seen (mixed in between); the segments' starts with their names (or
 * initials where the name does not fit); the tip where it is now (from
 * the shared memory, every frame); the polyps found so far (the daemon
 * sends no others). Without a recording session, without a daemon or in
 * a replay, the overlay says so instead.
 *
 * The map is asked for every MAPVIEW_POLL_S only while shown, on a
 * connection of its own (reconnect.h; why there is no map logged once),
 * each request waiting MAPVIEW_TIMEOUT_MS at most
 * (the control thread answers within a millisecond or two; rigctl's
 * requests wait up to 200 ms); hidden, the connection is closed.
 *
 * Main thread only; drawing with the GL context current (draw2d.h).
 */
#ifndef ENDOVIEW_MAPVIEW_H
#define ENDOVIEW_MAPVIEW_H

#include <stdbool.h>
#include <stdint.h>

#include "viewer/draw2d.h"
#include "proto/endosim_shm.h"

#define MAPVIEW_POLL_S 0.5
#define MAPVIEW_TIMEOUT_MS 100

/* Framebuffer pixels, top-left origin. */
struct mapview_rect {
	float x, y, w, h;
};

struct mapview;

/* SOCKET: as client_socket_path() takes it (NULL: the default); OFFLINE:
 * a replay, no daemon to ask. NULL on ENOMEM. */
struct mapview *mapview_create(const char *socket, bool offline);

/* NULL is fine. */
void mapview_destroy(struct mapview *v);

/* Shown (asks for the map when due: blocks up to MAPVIEW_TIMEOUT_MS) or
 * hidden (closes the connection, forgets the map). NOW_NS: monotonic. */
void mapview_update(struct mapview *v, bool shown, uint64_t now_ns);

/* Where the overlay lies in a W x H framebuffer. */
struct mapview_rect mapview_box(int w, int h);

/* Queues the overlay into D (between draw2d_begin() and draw2d_end());
 * ST: the newest state, for the tip (NULL: the map's own). */
void mapview_draw(const struct mapview *v, struct draw2d *d, int w, int h,
		  const struct endosim_state *st);

/* What the overlay says, one line ("session 3 at 12.0 s: 23.5 % seen,
 * 160 x 24 cells, 1 polyp found" or why there is no map), for tests. */
const char *mapview_said(const struct mapview *v);

#endif
