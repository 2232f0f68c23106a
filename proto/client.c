/* client.c - see client.h. */
#include "proto/client.h"

#include <errno.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include "proto/frame.h"

struct client {
	int fd;
	uint32_t seq;
	struct frame_rx rx;
};

int client_socket_path(const char *path, bool write, char *out, size_t size)
{
	struct stat st;
	int n;

	if (!path) {
		path = getenv(CLIENT_ENV);
	}
	if (!path || !*path) {
		path = CLIENT_DEFAULT_DIR;
	}
	if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
		n = snprintf(out, size, "%s/%s", path,
			     write ? CLIENT_RW_SOCKET : CLIENT_RO_SOCKET);
	} else {
		n = snprintf(out, size, "%s", path);
	}
	return n < 0 || (size_t)n >= size ? -ENAMETOOLONG : 0;
}

struct client *client_connect(const char *path)
{
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	struct client *c;
	int err;

	if (strlen(path) >= sizeof(addr.sun_path)) {
		errno = ENAMETOOLONG;
		return NULL;
	}
	strcpy(addr.sun_path, path);
	c = calloc(1, sizeof(*c));
	if (!c) {
		return NULL;
	}
	err = frame_rx_init(&c->rx, CLIENT_MAX_REPLY);
	if (err) {
		goto free_client;
	}
	c->fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (c->fd < 0) {
		err = -errno;
		goto free_rx;
	}
	if (connect(c->fd, (struct sockaddr *)&addr, sizeof(addr)) < 0) {
		err = -errno;
		goto close_fd;
	}
	return c;

close_fd:
	close(c->fd);
free_rx:
	frame_rx_free(&c->rx);
free_client:
	free(c);
	errno = -err;
	return NULL;
}

void client_close(struct client *c)
{
	if (!c) {
		return;
	}
	close(c->fd);
	frame_rx_free(&c->rx);
	free(c);
}

int client_fd(const struct client *c)
{
	return c->fd;
}

static int write_all(int fd, const uint8_t *p, size_t len)
{
	while (len) {
		ssize_t n = send(fd, p, len, MSG_NOSIGNAL);

		if (n < 0) {
			if (errno == EINTR) {
				continue;
			}
			return -errno;
		}
		p += n;
		len -= (size_t)n;
	}
	return 0;
}

static int send_request(struct client *c, Endosim__Request *req)
{
	size_t len = endosim__request__get_packed_size(req);
	uint8_t *buf = malloc(FRAME_HEADER_BYTES + len);
	int err;

	if (!buf) {
		return -ENOMEM;
	}
	frame_put_header(buf, (uint32_t)len);
	endosim__request__pack(req, buf + FRAME_HEADER_BYTES);
	err = write_all(c->fd, buf, FRAME_HEADER_BYTES + len);
	free(buf);
	return err;
}

static int64_t now_ms(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* Reads until one message is complete or the deadline passes. */
static int read_message(struct client *c, Endosim__Reply **reply,
			int64_t deadline_ms)
{
	const uint8_t *msg;
	size_t len, room;
	int r;

	for (;;) {
		r = frame_rx_next(&c->rx, &msg, &len);
		if (r < 0) {
			return -EPROTO;
		}
		if (r == 1) {
			*reply = endosim__reply__unpack(NULL, len, msg);
			return *reply ? 0 : -EPROTO;
		}
		int wait = (int)(deadline_ms - now_ms());
		struct pollfd pfd = { .fd = c->fd, .events = POLLIN };

		if (wait <= 0) {
			return -ETIMEDOUT;
		}
		r = poll(&pfd, 1, wait);
		if (r < 0 && errno != EINTR) {
			return -errno;
		}
		if (r <= 0) {
			continue;
		}
		uint8_t *dst = frame_rx_space(&c->rx, &room);
		ssize_t n = recv(c->fd, dst, room, 0);

		if (n == 0) {
			return -ECONNRESET;
		}
		if (n < 0 && errno != EINTR && errno != EAGAIN) {
			return -errno;
		}
		if (n > 0) {
			frame_rx_commit(&c->rx, (size_t)n);
		}
	}
}

int client_request(struct client *c, Endosim__Request *req,
		   Endosim__Reply **reply, int timeout_ms)
{
	int64_t deadline = now_ms() + timeout_ms;
	int err;

	req->version = ENDOSIM__PROTOCOL_VERSION__PROTOCOL_VERSION_CURRENT;
	req->seq = ++c->seq;
	err = send_request(c, req);
	if (err) {
		return err;
	}
	for (;;) {
		err = read_message(c, reply, deadline);
		if (err) {
			return err;
		}
		if ((*reply)->seq == req->seq) {
			return 0;
		}
		endosim__reply__free_unpacked(*reply, NULL);
	}
}

int client_receive(struct client *c, Endosim__Reply **reply, int timeout_ms)
{
	return read_message(c, reply, now_ms() + timeout_ms);
}

void client_scene_free(struct client_scene *s)
{
	if (!s) {
		return;
	}
	if (s->info_reply) {
		endosim__reply__free_unpacked(s->info_reply, NULL);
	}
	free(s->positions);
	free(s->normals);
	free(s->vertex_sample);
	free(s->vertex_offset);
	free(s->normal_offset);
	free(s->indices);
	free(s);
}

/* One chunk of scene ID (0: the first); *REP holds an OK scene reply. */
static int scene_chunk(struct client *c, uint32_t chunk, uint64_t id,
		       Endosim__Reply **rep, int timeout_ms,
		       Endosim__Status *status)
{
	Endosim__GetScene body = ENDOSIM__GET_SCENE__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	int r;

	body.chunk = chunk;
	body.scene_id = id;
	req.body_case = ENDOSIM__REQUEST__BODY_GET_SCENE;
	req.get_scene = &body;
	r = client_request(c, &req, rep, timeout_ms);
	if (r) {
		return r;
	}
	if ((*rep)->status != ENDOSIM__STATUS__STATUS_OK) {
		if (status) {
			*status = (*rep)->status;
		}
		r = (*rep)->status == ENDOSIM__STATUS__STATUS_REFUSED ? -EAGAIN
								     : -EACCES;
	} else if ((*rep)->body_case != ENDOSIM__REPLY__BODY_SCENE ||
		   (*rep)->scene->chunk != chunk ||
		   (chunk && !(*rep)->scene->mesh) ||
		   (!chunk && !(*rep)->scene->info)) {
		r = -EPROTO;
	}
	if (r) {
		endosim__reply__free_unpacked(*rep, NULL);
		*rep = NULL;
	}
	return r;
}

static int add_vertices(struct client_scene *s, const Endosim__SceneChunk *m)
{
	size_t n = m->n_vertex_sample, first = m->first_vertex;

	if (!n || first + n > s->vertices || m->n_positions != 3 * n ||
	    m->n_normals != 3 * n || m->n_vertex_offset != 3 * n ||
	    m->n_normal_offset != 3 * n) {
		return -EPROTO;
	}
	memcpy(s->positions[first], m->positions, 3 * n * sizeof(float));
	memcpy(s->normals[first], m->normals, 3 * n * sizeof(float));
	memcpy(s->vertex_offset[first], m->vertex_offset,
	       3 * n * sizeof(float));
	memcpy(s->normal_offset[first], m->normal_offset,
	       3 * n * sizeof(float));
	memcpy(&s->vertex_sample[first], m->vertex_sample,
	       n * sizeof(uint32_t));
	return 0;
}

static int add_triangles(struct client_scene *s, const Endosim__SceneChunk *m)
{
	size_t n = m->n_indices / 3, first = m->first_triangle;

	if (!n || m->n_indices % 3 || first + n > s->triangles) {
		return -EPROTO;
	}
	for (size_t i = 0; i < 3 * n; i++) {
		if (m->indices[i] >= s->vertices) {
			return -EPROTO;
		}
	}
	memcpy(s->indices[first], m->indices, 3 * n * sizeof(uint32_t));
	return 0;
}

static int scene_alloc(struct client_scene *s)
{
	size_t v = s->vertices, t = s->triangles;

	s->positions = malloc(v * sizeof(*s->positions));
	s->normals = malloc(v * sizeof(*s->normals));
	s->vertex_sample = malloc(v * sizeof(*s->vertex_sample));
	s->vertex_offset = malloc(v * sizeof(*s->vertex_offset));
	s->normal_offset = malloc(v * sizeof(*s->normal_offset));
	s->indices = malloc(t * sizeof(*s->indices));
	return s->positions && s->normals && s->vertex_sample &&
			       s->vertex_offset && s->normal_offset &&
			       s->indices ? 0 : -ENOMEM;
}

/* Chunk 0, then the rest; -EAGAIN when the case changed meanwhile. */
static int fetch_scene(struct client *c, struct client_scene *s,
		       int timeout_ms, Endosim__Status *status)
{
	Endosim__Reply *rep;
	uint32_t chunks;
	size_t got_v = 0, got_t = 0;
	int r = scene_chunk(c, 0, 0, &s->info_reply, timeout_ms, status);

	if (r) {
		return r;
	}
	s->scene_id = s->info_reply->scene->scene_id;
	s->info = s->info_reply->scene->info;
	s->scope = s->info->scope;
	s->vertices = s->info->vertices;
	s->triangles = s->info->triangles;
	chunks = s->info_reply->scene->chunks;
	r = scene_alloc(s);
	for (uint32_t k = 1; !r && k < chunks; k++) {
		const Endosim__SceneChunk *m;

		r = scene_chunk(c, k, s->scene_id, &rep, timeout_ms, status);
		if (r) {
			break;
		}
		m = rep->scene->mesh;
		r = m->n_indices ? add_triangles(s, m) : add_vertices(s, m);
		got_v += m->n_vertex_sample;
		got_t += m->n_indices / 3;
		endosim__reply__free_unpacked(rep, NULL);
	}
	if (!r && (got_v != s->vertices || got_t != s->triangles)) {
		r = -EPROTO; /* chunks missing or repeated */
	}
	return r;
}

int client_get_scene(struct client *c, struct client_scene **out,
		     int timeout_ms, Endosim__Status *status)
{
	int r = -EAGAIN;

	for (int attempt = 0; attempt < 3 && r == -EAGAIN; attempt++) {
		struct client_scene *s = calloc(1, sizeof(*s));

		if (!s) {
			return -ENOMEM;
		}
		r = fetch_scene(c, s, timeout_ms, status);
		if (!r) {
			*out = s;
			return 0;
		}
		client_scene_free(s);
	}
	return r;
}

const char *client_status_text(Endosim__Status status)
{
	static const char *const text[] = {
		[ENDOSIM__STATUS__STATUS_OK] = "ok",
		[ENDOSIM__STATUS__STATUS_BAD_VERSION] = "protocol version not supported",
		[ENDOSIM__STATUS__STATUS_MALFORMED] = "malformed request",
		[ENDOSIM__STATUS__STATUS_TOO_LARGE] = "request too large",
		[ENDOSIM__STATUS__STATUS_READ_ONLY] = "refused on the read-only socket",
		[ENDOSIM__STATUS__STATUS_REFUSED] = "refused in the current state",
		[ENDOSIM__STATUS__STATUS_UNKNOWN_KEY] = "unknown key",
		[ENDOSIM__STATUS__STATUS_NOT_LIVE] = "key not changeable while running",
		[ENDOSIM__STATUS__STATUS_BAD_VALUE] = "bad value",
		[ENDOSIM__STATUS__STATUS_TIMEOUT] = "force loop did not answer",
		[ENDOSIM__STATUS__STATUS_UNSUPPORTED] = "request not supported",
		[ENDOSIM__STATUS__STATUS_INTERNAL] = "internal error",
		[ENDOSIM__STATUS__STATUS_PERMISSION] = "permission denied",
	};

	if ((unsigned int)status < sizeof(text) / sizeof(text[0]) &&
	    text[status]) {
		return text[status];
	}
	return "unknown status";
}
