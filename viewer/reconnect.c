/* reconnect.c - see reconnect.h. */
#include "viewer/reconnect.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "proto/endosim_shm.h"

struct reconnect {
	char *socket;          /* as given, NULL: the default */
	bool write;
	uint64_t retry_ns;
	int level;
	const char *prefix;
	struct client *c;
	uint64_t next_try_ns;  /* earliest time for the next attempt */
	char path[108];
	char problem[RECONNECT_PROBLEM];
};

struct reconnect *reconnect_create(const char *socket, bool write,
				   double retry_s, int level,
				   const char *prefix)
{
	struct reconnect *r = calloc(1, sizeof(*r));

	if (!r) {
		return NULL;
	}
	r->socket = socket ? strdup(socket) : NULL;
	if (socket && !r->socket) {
		free(r);
		return NULL;
	}
	r->write = write;
	r->retry_ns = (uint64_t)(retry_s * ENDOSIM_NS_PER_S);
	r->level = level;
	r->prefix = prefix;
	return r;
}

void reconnect_destroy(struct reconnect *r)
{
	if (!r) {
		return;
	}
	client_close(r->c);
	free(r->socket);
	free(r);
}

int reconnect_connect(struct reconnect *r, uint64_t now_ns)
{
	int err;

	if (r->c) {
		return 0;
	}
	if (!reconnect_due(r, now_ns)) {
		return -EAGAIN;
	}
	r->next_try_ns = now_ns + r->retry_ns;
	err = client_socket_path(r->socket, r->write, r->path,
				 sizeof(r->path));
	r->c = err ? NULL : client_connect(r->path);
	if (!r->c) {
		return err ? err : -errno;
	}
	return 1;
}

struct client *reconnect_client(const struct reconnect *r)
{
	return r->c;
}

int reconnect_request(struct reconnect *r, Endosim__Request *req,
		      Endosim__Reply **reply, int timeout_ms)
{
	int err;

	if (!r->c) {
		return -ENOTCONN;
	}
	err = client_request(r->c, req, reply, timeout_ms);
	if (err) {
		reconnect_close(r);
	}
	return err;
}

void reconnect_close(struct reconnect *r)
{
	client_close(r->c);
	r->c = NULL;
}

void reconnect_now(struct reconnect *r)
{
	r->next_try_ns = 0;
}

bool reconnect_due(const struct reconnect *r, uint64_t now_ns)
{
	return now_ns >= r->next_try_ns;
}

const char *reconnect_path(const struct reconnect *r)
{
	return r->path;
}

void reconnect_say(struct reconnect *r, const char *fmt, ...)
{
	char why[RECONNECT_PROBLEM];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(why, sizeof(why), fmt, ap);
	va_end(ap);
	if (strcmp(r->problem, why)) {
		log_at(r->level, "%s%s", r->prefix, why);
	}
	memcpy(r->problem, why, sizeof(why));
}

void reconnect_clear(struct reconnect *r)
{
	r->problem[0] = '\0';
}

const char *reconnect_problem(const struct reconnect *r)
{
	return r->problem;
}
