/*
 * reconnect.h - one of endoview's connections to endosimd's sockets,
 * made when needed and made again after a delay when it failed, and its
 * problem said once: the link's scene (the read-only socket, a connection
 * for each fetch), the unseen-mucosa map's (read-only, held while the map
 * is shown) and rigctl's commands (read-write, held) each have one.
 *
 * The delay: an attempt to connect is made at most every RETRY_S (each
 * attempt, failed or not, starts it), unless reconnect_now() says the next
 * one may be made at once. A request that fails closes the connection.
 *
 * The problem: one line, said by its owner in its own words (why there is
 * no connection, or what the daemon refused); it is logged only when it
 * differs from the one said before, so a loss repeated every frame is
 * logged once, and it stays for the screen until cleared.
 *
 * Main thread only; requests block up to the timeout they are given.
 */
#ifndef ENDOVIEW_RECONNECT_H
#define ENDOVIEW_RECONNECT_H

#include <stdbool.h>
#include <stdint.h>

#include "proto/client.h"

#define RECONNECT_PROBLEM 192 /* a problem's characters, its NUL included */

struct reconnect;

/*
 * SOCKET: as client_socket_path() takes it (NULL: the default); WRITE:
 * the read-write socket. Problems are logged at syslog LEVEL, after
 * PREFIX (a constant string, "" for none). NULL on ENOMEM.
 */
struct reconnect *reconnect_create(const char *socket, bool write,
				   double retry_s, int level,
				   const char *prefix);

/* Closes the connection; NULL is fine. */
void reconnect_destroy(struct reconnect *r);

/*
 * Connects unless a connection is held. 1: connected now; 0: one is held;
 * -EAGAIN: the delay since the last attempt is not over; or the attempt's
 * negative errno (-EACCES: no permission; -ENAMETOOLONG: the socket's path
 * does not fit), the socket tried in reconnect_path(). NOW_NS: monotonic.
 */
int reconnect_connect(struct reconnect *r, uint64_t now_ns);

/* The connection held, or NULL. */
struct client *reconnect_client(const struct reconnect *r);

/*
 * REQ on the connection held (reconnect_connect() first: -ENOTCONN
 * without one) and its reply within TIMEOUT_MS: client_request()'s
 * returns; a failure closes the connection.
 */
int reconnect_request(struct reconnect *r, Endosim__Request *req,
		      Endosim__Reply **reply, int timeout_ms);

/* Closes the connection held, if any; the delay stays as it was. */
void reconnect_close(struct reconnect *r);

/* The next attempt may be made at once (someone asked). */
void reconnect_now(struct reconnect *r);

/* True when an attempt may be made at NOW_NS. */
bool reconnect_due(const struct reconnect *r, uint64_t now_ns);

/* The socket's path as last resolved ("" before the first attempt). */
const char *reconnect_path(const struct reconnect *r);

/* Says the problem (printf's FMT), logged if it differs from the last. */
void reconnect_say(struct reconnect *r, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* No problem (nothing logged). */
void reconnect_clear(struct reconnect *r);

/* The problem, "" when there is none. */
const char *reconnect_problem(const struct reconnect *r);

#endif
