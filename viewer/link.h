/*
 * link.h - endoview's read-only link to endosimd: the newest state from the
 * shared memory every frame, and the scene (the colon, GetScene over the
 * read-only socket) whenever the state names a scene the viewer does not
 * hold.
 *
 * Reading the state never blocks the daemon (the seqlock: a torn copy is
 * retried a few times, then the previous state stays). The link notices a
 * daemon that is not there (no shared memory, its writer gone), one that
 * stopped publishing (stale: its newest state is older than LINK_STALE_S
 * on CLOCK_MONOTONIC, the daemon's stamp), and one that came back (a new
 * shared-memory object, a new start time): it reopens the shared memory
 * and, since scene ids start again with a new daemon, fetches the scene
 * again.
 *
 * With the scene the link asks the daemon's [session] loop_threshold_m:
 * a loop as the daemon's metrics count one (link_loop_threshold_m()),
 * and its [patient] relief_pa and wall_strength_n_per_m, the pressure
 * gauge's marks (link_patient_limits()); values changed live after that
 * are seen with the next scene.
 *
 * Fetching the scene is the one call that blocks (up to
 * LINK_SCENE_TIMEOUT_MS per chunk), on a connection made for it
 * (reconnect.h); link_update() never does. What is wrong is said in
 * link_problem() and logged once. Main thread only.
 */
#ifndef ENDOVIEW_LINK_H
#define ENDOVIEW_LINK_H

#include <stdbool.h>
#include <stdint.h>

#include "proto/client.h"
#include "proto/endosim_shm.h"

#define LINK_STALE_S 0.5          /* a state this old: stale */
#define LINK_RETRY_S 0.5          /* between attempts to (re)open */
#define LINK_SCENE_TIMEOUT_MS 3000

enum link_status {
	LINK_NO_DAEMON = 0, /* no state yet, or its writer died */
	LINK_STALE,         /* the writer lives but publishes no more */
	LINK_LIVE,
};

struct link;

/* SOCKET: as client_socket_path() takes it (NULL: the default); SHM_NAME:
 * the shared-memory object (NULL: ENDOSIM_SHM_DEFAULT_NAME). */
struct link *link_create(const char *socket, const char *shm_name);

/* NULL is fine. */
void link_destroy(struct link *l);

/* Reads the newest state; reopens what needs reopening. NOW_NS: monotonic. */
enum link_status link_update(struct link *l, uint64_t now_ns);

/* The newest good state, or NULL before the first. */
const struct endosim_state *link_state(const struct link *l);

/* Age of the newest state in seconds: now less its publish_ns. */
double link_stale_s(const struct link *l, uint64_t now_ns);

/* Why there is no daemon, in words (empty when there is one). */
const char *link_problem(const struct link *l);

/*
 * True when the state names a scene other than HELD_ID (0: none held) and
 * no fetch failed in the last LINK_RETRY_S.
 */
bool link_scene_wanted(const struct link *l, uint64_t held_id,
		       uint64_t now_ns);

/* Fetches the scene, and the daemon's loop threshold with it (blocks).
 * Returns 0 with *OUT, or a negative errno with the reason in
 * link_problem(). */
int link_fetch_scene(struct link *l, struct client_scene **out,
		     uint64_t now_ns);

/*
 * The bow (m) beyond which the daemon's metrics count a loop: its
 * [session] loop_threshold_m as last fetched, or where that is 0 (or was
 * not told) the model's the state names (sessioninputs_loop_threshold_m()).
 */
double link_loop_threshold_m(const struct link *l);

/* The daemon's [patient] relief_pa (0: none) and wall_strength_n_per_m
 * as fetched with the scene (0: not told). */
void link_patient_limits(const struct link *l, double *relief_pa,
			 double *strength_n_per_m);

/* True once after the daemon was replaced (the held scene is void). */
bool link_daemon_changed(struct link *l);

#endif
