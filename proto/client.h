/*
 * client.h - the client side of endosimd's control protocol, shared by
 * endoctl and endoview: connect, request/reply, subscription pushes.
 *
 * Calls block for at most the timeout they are given. Not thread-safe per
 * connection. Replies are protobuf-c messages; free them with
 * endosim__reply__free_unpacked(reply, NULL).
 */
#ifndef ENDOSIM_CLIENT_H
#define ENDOSIM_CLIENT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "proto/endosim.pb-c.h"

#define CLIENT_DEFAULT_DIR "/run/endosim"
#define CLIENT_RO_SOCKET "status.sock"  /* read-only, mode 0666 */
#define CLIENT_RW_SOCKET "control.sock" /* read-write, mode 0660 */
#define CLIENT_ENV "ENDOSIM_SOCKET"
#define CLIENT_MAX_REPLY (16u << 20)     /* bytes */

struct client;

/*
 * Resolves the socket to talk to. PATH (or, when NULL, $ENDOSIM_SOCKET, or
 * else CLIENT_DEFAULT_DIR) is either a socket or a directory holding both;
 * for a directory, WRITE picks the read-write socket. Returns 0, or
 * -ENAMETOOLONG.
 */
int client_socket_path(const char *path, bool write, char *out, size_t size);

/* Connects to the socket at PATH. Returns NULL and sets errno on failure. */
struct client *client_connect(const char *path);

/* Closes; NULL is fine. */
void client_close(struct client *c);

/* The socket, for poll(). */
int client_fd(const struct client *c);

/*
 * Sends REQ (its version and seq are filled in here) and waits up to
 * TIMEOUT_MS for the reply with the same seq; pushes for other requests that
 * arrive meanwhile are dropped. Returns 0 with *REPLY set, or -ETIMEDOUT,
 * -ECONNRESET (the daemon closed the connection), -EPROTO (undecodable
 * reply) or another negative errno.
 */
int client_request(struct client *c, Endosim__Request *req,
		   Endosim__Reply **reply, int timeout_ms);

/* Waits up to TIMEOUT_MS for the next message (e.g. a push). Same returns. */
int client_receive(struct client *c, Endosim__Reply **reply, int timeout_ms);

/*
 * A whole scene (GetScene, every chunk), the arrays gathered: the colon
 * the daemon renders, as the viewer draws it. info points into the reply
 * of chunk 0 (regions, polyps, segments, centreline); the mesh arrays are
 * malloc'd. Free with client_scene_free().
 */
struct client_scene {
	uint64_t scene_id;
	const Endosim__SceneInfo *info;
	const Endosim__SceneScope *scope; /* info's: the scope it is rendered
					     with; NULL from an older daemon */
	uint32_t vertices;
	uint32_t triangles;
	float (*positions)[3];     /* m, undeformed */
	float (*normals)[3];       /* into the lumen */
	uint32_t *vertex_sample;   /* centreline sample of each vertex */
	float (*vertex_offset)[3]; /* in that sample's frame (t, u, v), m */
	float (*normal_offset)[3];
	uint32_t (*indices)[3];
	Endosim__Reply *info_reply; /* owns info */
};

/*
 * Fetches the scene chunk by chunk, each within TIMEOUT_MS; starts again
 * (up to 3 times) when the daemon changes case meanwhile. Returns 0 with
 * *OUT, or a negative errno: client_request()'s, -EPROTO for a reply that
 * does not add up (sizes, indices out of range), -EAGAIN when the case
 * kept changing, -ENOMEM. On a refusal, -EACCES with the status in
 * *STATUS (may be NULL).
 */
int client_get_scene(struct client *c, struct client_scene **out,
		     int timeout_ms, Endosim__Status *status);

/* NULL is fine. */
void client_scene_free(struct client_scene *s);

/* "ok", "read-only socket", ...: the meaning of a reply's status. */
const char *client_status_text(Endosim__Status status);

#endif
