/*
 * control.h - the control thread: endosimd's two Unix sockets, served with
 * epoll, speaking proto/endosim.proto in length-prefixed frames (frame.h).
 *
 *   DIR/status.sock   mode 0666: GetStatus, GetStats, GetConfig, Subscribe,
 *                     GetScene, ListCases; anything else is answered
 *                     STATUS_READ_ONLY
 *   DIR/control.sock  mode 0660, group [socket] group: every request
 *
 * Hostile or broken clients cannot hurt the daemon: a request over
 * [socket] max_request_bytes gets STATUS_TOO_LARGE and the connection is
 * closed (the stream cannot be resynchronised), an undecodable one gets
 * STATUS_MALFORMED, a client whose unsent replies pile up beyond a bound is
 * disconnected, and at most [socket] max_clients are served at once.
 *
 * The control thread never runs in the force loop's place: it talks to it
 * through loop.h's lock-free calls and reads the state from shared memory.
 * It owns the master copy of the configuration. LoadCase builds the new
 * colon here (tens of ms, other clients wait) and hands it to the loop
 * (loop_swap_colon()); the old one is freed here once the loop let go.
 */
#ifndef ENDOSIM_CONTROL_H
#define ENDOSIM_CONTROL_H

#include <stdint.h>

#include "model/colon.h"
#include "conf/config.h"
#include "rig/hand.h"
#include "loop/loop.h"
#include "loop/publish.h"
#include "recorder/recorder.h"
#include "rig/rig.h"

struct control_deps {
	struct loop *loop;
	struct hand *hand;       /* simulated rig's hand; NULL on real drives */
	struct publish *pub;
	struct rig *rig;         /* its name, and faults in words */
	uint64_t start_ns;       /* CLOCK_MONOTONIC at daemon start */
	struct colon *colon;     /* the loop's colon at start (loop owns it) */
	uint64_t scene_id;       /* its GetScene id */
	struct recorder *recorder; /* training sessions */
};

struct control;

/*
 * Creates both sockets in cfg->socket.directory (creating the directory if
 * it is missing), refusing to start when another daemon answers on them.
 * NULL on failure, logged.
 */
struct control *control_create(const struct config *cfg,
			       const struct control_deps *deps);

/* Starts the control thread. Returns 0 or a negative errno. */
int control_start(struct control *c);

/* Stops and joins the thread, closing every connection. Idempotent. */
void control_stop(struct control *c);

/* Stops, removes the sockets and frees; NULL is fine. */
void control_destroy(struct control *c);

/* True while the control thread runs (false if it ended by itself). */
bool control_alive(const struct control *c);

#endif
