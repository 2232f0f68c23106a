/* control.c - see control.h; the parts share control_private.h. */
#include <errno.h>
#include <grp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/log.h"
#include "base/mono.h"
#include "conf/cases.h"
#include "control/control_private.h"
#include "proto/client.h"

#define MAX_EVENTS 32
#define MAX_PEER_GROUPS 256

enum { TAG_WAKE = 0, TAG_RO = 1, TAG_RW = 2, TAG_CLIENT = 3 };

/* ---------------------------------------------------------------- sockets */

/* Another daemon answering on PATH? */
static bool socket_in_use(const char *path)
{
	struct client *probe = client_connect(path);

	client_close(probe);
	return probe != NULL;
}

static int listen_on(const char *path, mode_t mode, gid_t gid)
{
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	int fd;

	if (socket_in_use(path)) {
		log_err("%s: another endosimd is running", path);
		return -EADDRINUSE;
	}
	unlink(path);
	strcpy(addr.sun_path, path);
	fd = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
	if (fd < 0) {
		log_err("%s: socket: %m", path);
		return -errno;
	}
	if (bind(fd, (struct sockaddr *)&addr, sizeof(addr)) < 0 ||
	    chmod(path, mode) < 0 ||
	    (gid != (gid_t)-1 && chown(path, (uid_t)-1, gid) < 0) ||
	    listen(fd, 16) < 0) {
		log_err("%s: cannot listen: %m", path);
		close(fd);
		unlink(path);
		return -errno;
	}
	return fd;
}

static int socket_paths(struct control *c)
{
	const char *dir = c->cfg.socket.directory;
	int n1 = snprintf(c->ro_path, sizeof(c->ro_path), "%s/%s", dir,
			  CLIENT_RO_SOCKET);
	int n2 = snprintf(c->rw_path, sizeof(c->rw_path), "%s/%s", dir,
			  CLIENT_RW_SOCKET);

	if (n1 < 0 || n2 < 0 || (size_t)n1 >= sizeof(c->ro_path) ||
	    (size_t)n2 >= sizeof(c->rw_path)) {
		log_err("[socket] directory '%s' is too long for a socket path",
			dir);
		return -ENAMETOOLONG;
	}
	if (mkdir(dir, 0755) < 0 && errno != EEXIST) {
		log_err("%s: cannot create: %m", dir);
		return -errno;
	}
	return 0;
}

static int resolve_group(const char *name, gid_t *gid)
{
	struct group *gr;

	*gid = (gid_t)-1;
	if (!*name) {
		return 0;
	}
	gr = getgrnam(name);
	if (!gr) {
		log_err("[socket] group '%s' does not exist", name);
		return -ENOENT;
	}
	*gid = gr->gr_gid;
	return 0;
}

static int epoll_add(int ep, int fd, uint64_t tag, uint32_t events)
{
	struct epoll_event ev = { .events = events, .data.u64 = tag };

	return epoll_ctl(ep, EPOLL_CTL_ADD, fd, &ev) < 0 ? -errno : 0;
}

/* ---------------------------------------------------------------- clients */

static void client_drop(struct control *c, struct client *cl)
{
	epoll_ctl(c->ep, EPOLL_CTL_DEL, cl->fd, NULL);
	close(cl->fd);
	cl->fd = -1;
	frame_rx_free(&cl->rx);
	free(cl->out);
	cl->out = NULL;
	cl->out_len = cl->out_cap = 0;
	cl->push_period_ns = 0;
}

static void watch_output(struct control *c, struct client *cl, bool on)
{
	struct epoll_event ev = {
		.events = EPOLLIN | (on ? EPOLLOUT : 0u),
		.data.u64 = TAG_CLIENT + (uint64_t)(cl - c->clients),
	};

	epoll_ctl(c->ep, EPOLL_CTL_MOD, cl->fd, &ev);
}

/* Sends what is queued; returns -1 when the client is gone. */
static int client_flush(struct control *c, struct client *cl)
{
	while (cl->out_len) {
		ssize_t n = send(cl->fd, cl->out, cl->out_len,
				 MSG_NOSIGNAL | MSG_DONTWAIT);

		if (n < 0 && errno == EINTR) {
			continue;
		}
		if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
			watch_output(c, cl, true);
			return 0;
		}
		if (n < 0) {
			client_drop(c, cl);
			return -1;
		}
		memmove(cl->out, cl->out + n, cl->out_len - (size_t)n);
		cl->out_len -= (size_t)n;
	}
	watch_output(c, cl, false);
	return 0;
}

static int queue_bytes(struct client *cl, size_t len, size_t max,
		       uint8_t **at)
{
	if (cl->out_len + len > max) {
		return -ENOBUFS;
	}
	if (cl->out_len + len > cl->out_cap) {
		size_t cap = cl->out_cap ? cl->out_cap : 4096;
		uint8_t *grown;

		while (cap < cl->out_len + len) {
			cap *= 2;
		}
		grown = realloc(cl->out, cap);
		if (!grown) {
			return -ENOMEM;
		}
		cl->out = grown;
		cl->out_cap = cap;
	}
	*at = cl->out + cl->out_len;
	cl->out_len += len;
	return 0;
}

/* Queues and sends a reply; a client that cannot keep up is dropped. */
static int client_reply(struct control *c, struct client *cl,
			Endosim__Reply *rep)
{
	size_t len;
	uint8_t *at;

	rep->version = ENDOSIM__PROTOCOL_VERSION__PROTOCOL_VERSION_CURRENT;
	len = endosim__reply__get_packed_size(rep);
	if (queue_bytes(cl, FRAME_HEADER_BYTES + len, c->max_queued, &at)) {
		log_notice("client pid %d: %zu bytes of replies unread, "
			   "disconnected", (int)cl->pid, cl->out_len);
		client_drop(c, cl);
		return -1;
	}
	frame_put_header(at, (uint32_t)len);
	endosim__reply__pack(rep, at + FRAME_HEADER_BYTES);
	return client_flush(c, cl);
}

/* Root, the daemon's own user, or a member of the command group. */
static bool peer_may_command(const struct control *c, int fd,
			     const struct ucred *cred)
{
	gid_t groups[MAX_PEER_GROUPS];
	socklen_t len = sizeof(groups);

	if (cred->uid == 0 || cred->uid == geteuid() ||
	    cred->gid == c->command_gid) {
		return true;
	}
	if (getsockopt(fd, SOL_SOCKET, SO_PEERGROUPS, groups, &len) < 0) {
		return false;
	}
	for (size_t i = 0; i < len / sizeof(groups[0]); i++) {
		if (groups[i] == c->command_gid) {
			return true;
		}
	}
	return false;
}

static void accept_client(struct control *c, int lfd, bool rw)
{
	struct ucred cred;
	socklen_t len = sizeof(cred);
	struct client *cl = NULL;
	int fd = accept4(lfd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);

	if (fd < 0) {
		return;
	}
	for (int i = 0; i < c->max_clients && !cl; i++) {
		cl = c->clients[i].fd < 0 ? &c->clients[i] : NULL;
	}
	if (!cl || frame_rx_init(&cl->rx, c->max_request)) {
		static struct log_ratelimit rl = LOG_RATELIMIT_INIT(10, 1);

		log_ratelimited(&rl, LOG_WARNING,
				cl ? "out of memory: connection refused"
				   : "too many clients (%d): connection refused",
				c->max_clients);
		close(fd);
		return;
	}
	cred = (struct ucred){ .pid = 0, .uid = (uid_t)-1, .gid = (gid_t)-1 };
	getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len);
	cl->fd = fd;
	cl->rw = rw;
	cl->staff = peer_may_command(c, fd, &cred);
	cl->may_command = rw && cl->staff;
	cl->logged_in = false;
	cl->uid = cred.uid;
	cl->pid = cred.pid;
	cl->last_rx_ns = mono_ns();
	cl->partial_ns = 0;
	if (epoll_add(c->ep, fd, TAG_CLIENT + (uint64_t)(cl - c->clients),
		      EPOLLIN)) {
		client_drop(c, cl);
	}
}

/* ---------------------------------------------------------------- requests */

struct handler {
	Endosim__Request__BodyCase body;
	bool writes; /* refused on the read-only socket */
	handler_fn *fn;
};

static const struct handler handlers[] = {
	{ ENDOSIM__REQUEST__BODY_GET_STATUS, false, control_on_get_status },
	{ ENDOSIM__REQUEST__BODY_GET_STATS, false, control_on_get_stats },
	{ ENDOSIM__REQUEST__BODY_GET_CONFIG, false, control_on_get_config },
	{ ENDOSIM__REQUEST__BODY_SUBSCRIBE, false, control_on_subscribe },
	{ ENDOSIM__REQUEST__BODY_GET_SCENE, false, control_on_get_scene },
	{ ENDOSIM__REQUEST__BODY_LIST_CASES, false, control_on_list_cases },
	{ ENDOSIM__REQUEST__BODY_LOAD_CASE, true, control_on_load_case },
	{ ENDOSIM__REQUEST__BODY_SET_PARAM, true, control_on_set_param },
	{ ENDOSIM__REQUEST__BODY_ENABLE, true, control_on_enable },
	{ ENDOSIM__REQUEST__BODY_DISABLE, true, control_on_disable },
	{ ENDOSIM__REQUEST__BODY_ESTOP, true, control_on_estop },
	{ ENDOSIM__REQUEST__BODY_RESET_FAULT, true, control_on_reset },
	{ ENDOSIM__REQUEST__BODY_HAND_INPUT, true, control_on_hand_input },
	{ ENDOSIM__REQUEST__BODY_RESET_STATS, true, control_on_reset_stats },
	{ ENDOSIM__REQUEST__BODY_DEBUG_INJECT, true, control_on_debug },
	{ ENDOSIM__REQUEST__BODY_SESSION_START, true,
	  control_on_session_start },
	{ ENDOSIM__REQUEST__BODY_SESSION_STOP, true, control_on_session_stop },
	{ ENDOSIM__REQUEST__BODY_SESSION_STATUS, false,
	  control_on_session_status },
	{ ENDOSIM__REQUEST__BODY_SESSION_LIST, false, control_on_session_list },
	{ ENDOSIM__REQUEST__BODY_SESSION_SHOW, false, control_on_session_show },
	{ ENDOSIM__REQUEST__BODY_SESSION_MAP, false, control_on_session_map },
	{ ENDOSIM__REQUEST__BODY_TRAINEE_SESSIONS, false,
	  control_on_trainee_sessions },
	{ ENDOSIM__REQUEST__BODY_GUIDE, true, control_on_guide },
	{ ENDOSIM__REQUEST__BODY_PATIENT, true, control_on_patient },
	{ ENDOSIM__REQUEST__BODY_TOOL, true, control_on_tool },
	{ ENDOSIM__REQUEST__BODY_RECORDS_CHECK, false,
	  control_on_records_check },
	{ ENDOSIM__REQUEST__BODY_RECORDS_REBUILD, true,
	  control_on_records_rebuild },
	{ ENDOSIM__REQUEST__BODY_RECORDS_BACKUP, true,
	  control_on_records_backup },
	{ ENDOSIM__REQUEST__BODY_RECORDS_RESTORE, true,
	  control_on_records_restore },
	{ ENDOSIM__REQUEST__BODY_LOGIN, false, control_on_login },
	{ ENDOSIM__REQUEST__BODY_ACCOUNTS, false, control_on_accounts },
	{ ENDOSIM__REQUEST__BODY_LOGOUT, true, control_on_logout },
};

static const struct handler *find_handler(Endosim__Request__BodyCase body)
{
	for (size_t i = 0; i < sizeof(handlers) / sizeof(handlers[0]); i++) {
		if (handlers[i].body == body) {
			return &handlers[i];
		}
	}
	return NULL;
}

/* The varint at *P (before END) into *V, *P past it; false cut short. */
static bool wire_varint(const uint8_t **p, const uint8_t *end, uint64_t *v)
{
	*v = 0;
	for (int shift = 0; *p < end && shift < 64; shift += 7) {
		uint8_t b = *(*p)++;

		*v |= (uint64_t)(b & 0x7f) << shift;
		if (!(b & 0x80)) {
			return true;
		}
	}
	return false;
}

/*
 * Calls FN(ARG, FIELD, BYTES, LEN) on each length-delimited field of the
 * protobuf message MSG (LEN bytes); stops at FN's true and returns it.
 * false, too, for what is not well formed (the unpack said so already).
 */
static bool wire_each(const uint8_t *msg, size_t len,
		      bool (*fn)(void *arg, uint64_t field, const uint8_t *b,
				 size_t n),
		      void *arg)
{
	const uint8_t *p = msg, *end = msg + len;
	uint64_t key, n;

	while (p < end && wire_varint(&p, end, &key)) {
		switch (key & 7) {
		case 0:
			if (!wire_varint(&p, end, &n)) {
				return false;
			}
			break;
		case 1:
		case 5:
			p += (key & 7) == 1 ? 8 : 4;
			break;
		case 2:
			if (!wire_varint(&p, end, &n) ||
			    n > (uint64_t)(end - p)) {
				return false;
			}
			if (fn(arg, key >> 3, p, n)) {
				return true;
			}
			p += n;
			break;
		default:
			return false;
		}
	}
	return false;
}

static bool has_nul(void *arg, uint64_t field, const uint8_t *b, size_t n)
{
	(void)arg;
	(void)field;
	return memchr(b, '\0', n) != NULL;
}

/* Whether a name the request carries holds a NUL byte: protobuf-c's C
 * string ends there and would be taken silently cut short. Only the
 * requests whose every length-delimited field is a string (names). */
static bool names_nul(void *arg, uint64_t field, const uint8_t *b, size_t n)
{
	(void)arg;
	return (field == ENDOSIM__REQUEST__BODY_SESSION_START ||
		field == ENDOSIM__REQUEST__BODY_TRAINEE_SESSIONS) &&
	       wire_each(b, n, has_nul, NULL);
}

static int dispatch(struct control *c, struct client *cl, const uint8_t *msg,
		    size_t len)
{
	Endosim__Request *req = endosim__request__unpack(NULL, len, msg);
	Endosim__Reply rep = ENDOSIM__REPLY__INIT;
	const struct handler *h;
	int r;

	if (!req) {
		refuse(&rep, ENDOSIM__STATUS__STATUS_MALFORMED,
		       "undecodable request");
		return client_reply(c, cl, &rep);
	}
	rep.seq = req->seq;
	h = find_handler(req->body_case);
	if (req->version !=
	    ENDOSIM__PROTOCOL_VERSION__PROTOCOL_VERSION_CURRENT) {
		refuse(&rep, ENDOSIM__STATUS__STATUS_BAD_VERSION,
		       "protocol version not supported");
	} else if (req->body_case == ENDOSIM__REQUEST__BODY__NOT_SET) {
		refuse(&rep, ENDOSIM__STATUS__STATUS_MALFORMED,
		       "no request in the message");
	} else if (wire_each(msg, len, names_nul, NULL)) {
		refuse(&rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "a name holds a NUL byte");
	} else if (!h) {
		refuse(&rep, ENDOSIM__STATUS__STATUS_UNSUPPORTED,
		       "request not supported by this daemon");
	} else if (h->writes && !cl->rw) {
		refuse(&rep, ENDOSIM__STATUS__STATUS_READ_ONLY,
		       "read-only socket: use the control socket");
	} else if (h->writes && !cl->may_command) {
		static struct log_ratelimit rl = LOG_RATELIMIT_INIT(10, 3);

		log_ratelimited(&rl, LOG_NOTICE, "command from uid %d (pid %d) "
				"refused: not root or in the command group",
				(int)cl->uid, (int)cl->pid);
		refuse(&rep, ENDOSIM__STATUS__STATUS_PERMISSION,
		       "only root and the endosim group may command");
	} else if (!control_accounts_refuse(c, cl, req, &rep)) {
		h->fn(c, cl, req, &rep);
		control_accounts_filter(c, cl, req, &rep);
	}
	r = client_reply(c, cl, &rep);
	endosim__request__free_unpacked(req, NULL);
	return r;
}

static void client_read(struct control *c, struct client *cl)
{
	const uint8_t *msg;
	size_t room, len;
	uint8_t *dst = frame_rx_space(&cl->rx, &room);
	ssize_t n = recv(cl->fd, dst, room, 0);
	int r;

	if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
		return;
	}
	if (n <= 0) {
		client_drop(c, cl); /* EOF; a truncated message dies with it */
		return;
	}
	frame_rx_commit(&cl->rx, (size_t)n);
	cl->last_rx_ns = mono_ns();
	while ((r = frame_rx_next(&cl->rx, &msg, &len)) == 1) {
		if (dispatch(c, cl, msg, len)) {
			return; /* dropped */
		}
	}
	if (!frame_rx_pending(&cl->rx)) {
		cl->partial_ns = 0;
	} else if (!cl->partial_ns) {
		cl->partial_ns = cl->last_rx_ns;
	}
	if (r < 0) {
		Endosim__Reply rep = ENDOSIM__REPLY__INIT;

		refuse(&rep, ENDOSIM__STATUS__STATUS_TOO_LARGE,
		       "request larger than max_request_bytes");
		if (!client_reply(c, cl, &rep)) {
			client_drop(c, cl);
		}
	}
}

/* ---------------------------------------------------------------- thread */

static void update_loop_rate(struct control *c, uint64_t now)
{
	uint64_t cycles = loop_heartbeat(c->deps.loop);

	if (!c->rate_t0_ns) {
		c->rate_t0_ns = now;
		c->rate_cycle0 = cycles;
		return;
	}
	if (now - c->rate_t0_ns >= ENDOSIM_NS_PER_S) {
		c->loop_hz = (double)(cycles - c->rate_cycle0) *
			     ENDOSIM_NS_PER_S / (double)(now - c->rate_t0_ns);
		c->rate_t0_ns = now;
		c->rate_cycle0 = cycles;
	}
}

static int push_subscriptions(struct control *c, uint64_t now)
{
	uint64_t next = UINT64_MAX;

	for (int i = 0; i < c->max_clients; i++) {
		struct client *cl = &c->clients[i];

		if (cl->fd < 0 || !cl->push_period_ns) {
			continue;
		}
		if (now >= cl->next_push_ns) {
			Endosim__Reply rep = ENDOSIM__REPLY__INIT;

			rep.seq = cl->push_seq;
			control_build_status(c, &rep);
			cl->next_push_ns += cl->push_period_ns;
			if (cl->next_push_ns < now) {
				cl->next_push_ns = now + cl->push_period_ns;
			}
			if (client_reply(c, cl, &rep)) {
				continue;
			}
		}
		if (cl->next_push_ns < next) {
			next = cl->next_push_ns;
		}
	}
	if (next == UINT64_MAX) {
		return 100;
	}
	return next <= now ? 0 : (int)((next - now + 999999) / 1000000);
}

/* Closes silent clients (subscribers excepted) and half-sent requests. */
static void sweep_clients(struct control *c, uint64_t now)
{
	uint64_t idle =
		(uint64_t)(c->cfg.socket.idle_timeout_s * ENDOSIM_NS_PER_S);
	uint64_t partial =
		(uint64_t)(c->cfg.socket.partial_timeout_s * ENDOSIM_NS_PER_S);

	for (int i = 0; i < c->max_clients; i++) {
		struct client *cl = &c->clients[i];
		const char *why = NULL;

		if (cl->fd < 0) {
			continue;
		}
		if (cl->partial_ns && now - cl->partial_ns > partial) {
			why = "unfinished request";
		} else if (!cl->push_period_ns && now - cl->last_rx_ns > idle) {
			why = "idle";
		}
		if (why) {
			log_info("client pid %d: %s, disconnected", (int)cl->pid,
				 why);
			client_drop(c, cl);
		}
	}
}

static void handle_event(struct control *c, const struct epoll_event *ev)
{
	uint64_t tag = ev->data.u64;
	uint64_t junk;
	struct client *cl;

	switch (tag) {
	case TAG_WAKE:
		if (read(c->wake_fd, &junk, sizeof(junk)) < 0) {
			/* nothing to drain */
		}
		return;
	case TAG_RO:
		accept_client(c, c->ro_fd, false);
		return;
	case TAG_RW:
		accept_client(c, c->rw_fd, true);
		return;
	}
	cl = &c->clients[tag - TAG_CLIENT];
	if (cl->fd < 0) {
		return;
	}
	if ((ev->events & EPOLLOUT) && client_flush(c, cl)) {
		return;
	}
	if (ev->events & (EPOLLIN | EPOLLHUP | EPOLLERR)) {
		client_read(c, cl);
	}
}

static void *control_main(void *arg)
{
	struct control *c = arg;
	struct epoll_event evs[MAX_EVENTS];
	int timeout = 0;

	while (!atomic_load(&c->stop) && !c->end) {
		int n = epoll_wait(c->ep, evs, MAX_EVENTS, timeout);

		for (int i = 0; i < n; i++) {
			handle_event(c, &evs[i]);
		}
		if (control_records_people_copied(c)) {
			control_accounts_refresh(c);
		}
		uint64_t now = mono_ns();

		update_loop_rate(c, now);
		sweep_clients(c, now);
		timeout = push_subscriptions(c, now);
	}
	atomic_store(&c->alive, false);
	return NULL;
}

/* ---------------------------------------------------------------- life */

static int alloc_buffers(struct control *c)
{
	c->clients = calloc((size_t)c->max_clients, sizeof(*c->clients));
	c->replies = control_replies_create();
	c->cases = control_cases_create();
	c->sessions = control_sessions_create();
	c->trainees = control_trainees_create();
	c->guide = control_guide_create();
	if (!c->clients || !c->replies || !c->cases || !c->sessions ||
	    !c->trainees || !c->guide) {
		log_err("control: out of memory");
		return -ENOMEM;
	}
	for (int i = 0; i < c->max_clients; i++) {
		c->clients[i].fd = -1;
	}
	return 0;
}

static int open_sockets(struct control *c)
{
	gid_t gid;
	int r;

	r = socket_paths(c);
	if (r || (r = resolve_group(c->cfg.socket.group, &gid))) {
		return r;
	}
	c->command_gid = gid != (gid_t)-1 ? gid : getegid();
	c->ro_fd = listen_on(c->ro_path, 0666, (gid_t)-1);
	if (c->ro_fd < 0) {
		return c->ro_fd;
	}
	c->rw_fd = listen_on(c->rw_path, 0660, gid);
	if (c->rw_fd < 0) {
		return c->rw_fd;
	}
	c->ep = epoll_create1(EPOLL_CLOEXEC);
	c->wake_fd = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
	if (c->ep < 0 || c->wake_fd < 0 ||
	    epoll_add(c->ep, c->wake_fd, TAG_WAKE, EPOLLIN) ||
	    epoll_add(c->ep, c->ro_fd, TAG_RO, EPOLLIN) ||
	    epoll_add(c->ep, c->rw_fd, TAG_RW, EPOLLIN)) {
		log_err("control: epoll: %m");
		return -errno;
	}
	return 0;
}

struct control *control_create(const struct config *cfg,
			       const struct control_deps *deps)
{
	struct control *c = calloc(1, sizeof(*c));

	if (!c) {
		log_err("control: out of memory");
		return NULL;
	}
	c->cfg = *cfg;
	c->deps = *deps;
	c->colon = deps->colon;
	c->scene_id = deps->scene_id;
	cases_path(cfg, NULL, c->case_path, sizeof(c->case_path));
	c->ro_fd = c->rw_fd = c->ep = c->wake_fd = -1;
	c->max_clients = cfg->socket.max_clients;
	c->max_request = (size_t)cfg->socket.max_request_bytes;
	c->max_queued = (size_t)cfg->socket.max_queued_bytes;
	if (alloc_buffers(c) || open_sockets(c) ||
	    !(c->records = control_records_create(cfg, c->wake_fd)) ||
	    !(c->accounts = control_accounts_create(cfg))) {
		control_destroy(c);
		return NULL;
	}
	control_accounts_refresh(c);
	if (cfg->debug.test_commands) {
		log_warn("[debug] test_commands = yes: clients may inject "
			 "faults and stall the force loop; never on a rig a "
			 "person touches");
	}
	log_info("listening on %s (read-only) and %s (read-write)", c->ro_path,
		 c->rw_path);
	return c;
}

int control_start(struct control *c)
{
	int r;

	atomic_store(&c->alive, true);
	r = pthread_create(&c->thread, NULL, control_main, c);
	if (r) {
		atomic_store(&c->alive, false);
		log_err("control: cannot start thread: %s", strerror(r));
		return -r;
	}
	pthread_setname_np(c->thread, "endosim-ctl");
	c->running = true;
	return 0;
}

void control_stop(struct control *c)
{
	uint64_t one = 1;

	if (!c->running) {
		return;
	}
	atomic_store(&c->stop, true);
	if (write(c->wake_fd, &one, sizeof(one)) < 0) {
		log_warn("control: cannot wake thread: %m");
	}
	pthread_join(c->thread, NULL);
	c->running = false;
}

bool control_alive(const struct control *c)
{
	return atomic_load(&((struct control *)c)->alive);
}

static void close_fd(int fd)
{
	if (fd >= 0) {
		close(fd);
	}
}

void control_destroy(struct control *c)
{
	if (!c) {
		return;
	}
	control_stop(c);
	for (int i = 0; c->clients && i < c->max_clients; i++) {
		if (c->clients[i].fd >= 0) {
			client_drop(c, &c->clients[i]);
		}
	}
	if (c->ro_fd >= 0) {
		unlink(c->ro_path);
	}
	if (c->rw_fd >= 0) {
		unlink(c->rw_path);
	}
	close_fd(c->ro_fd);
	close_fd(c->rw_fd);
	close_fd(c->ep);
	close_fd(c->wake_fd);
	free(c->clients);
	control_replies_destroy(c->replies);
	control_cases_destroy(c->cases);
	control_sessions_destroy(c->sessions);
	control_trainees_destroy(c->trainees);
	control_guide_destroy(c->guide);
	control_records_destroy(c->records);
	control_accounts_destroy(c->accounts);
	free(c);
}
