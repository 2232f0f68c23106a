/* control.c - see control.h. */
#include "control.h"

#include <errno.h>
#include <grp.h>
#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "client.h"
#include "frame.h"
#include "names.h"
#include "version.h"
#include "cases.h"
#include "faults.h"
#include "inject.h"
#include "log.h"
#include "mono.h"
#include "scene.h"
#include "sessiondir.h"
#include "sessionpb.h"

#define MAX_EVENTS 32
#define MAX_PEER_GROUPS 256
#define COMMAND_TIMEOUT_MS 200
#define MAX_PUSH_HZ 1000.0
#define MAX_HOLD_S 10.0
#define SWAP_TIMEOUT_MS 500

enum { TAG_WAKE = 0, TAG_RO = 1, TAG_RW = 2, TAG_CLIENT = 3 };

struct client {
	int fd;               /* -1: free slot */
	bool rw;              /* connected to the read-write socket */
	bool may_command;     /* rw, and root or in the command group */
	uid_t uid;
	pid_t pid;
	uint64_t last_rx_ns;  /* last bytes received */
	uint64_t partial_ns;  /* since when part of a request waits, 0: none */
	struct frame_rx rx;
	uint8_t *out;         /* replies not yet sent */
	size_t out_len, out_cap;
	uint64_t push_period_ns; /* 0: not subscribed */
	uint64_t next_push_ns;
	uint32_t push_seq;
};

/* Storage for the reply being built: no allocation per reply. */
struct reply_buf {
	Endosim__StatusReply status;
	Endosim__AxisStatus axes[ENDOSIM_AXES];
	Endosim__AxisStatus *axes_p[ENDOSIM_AXES];
	Endosim__Fault faults[ENDOSIM_FAULT_BITS];
	Endosim__Fault *faults_p[ENDOSIM_FAULT_BITS];
	char fault_lines[ENDOSIM_FAULT_BITS][640];
	Endosim__StatsReply stats;
	Endosim__Histogram latency, compute;
	Endosim__BusStats buses[ENDOSIM_AXES];
	Endosim__BusStats *buses_p[ENDOSIM_AXES];
	Endosim__Histogram bus_histo[ENDOSIM_AXES][2];
	Endosim__ConfigReply config;
	Endosim__ConfigEntry *entries;
	Endosim__ConfigEntry **entries_p;
	char (*values)[CONFIG_STR + 32];
	char error[256];
	Endosim__ScopeStatus scope;
	struct endosim_scope_state scope_state; /* what scope points into */
	Endosim__HapticsStatus haptics;
	struct endosim_haptics_state haptics_state; /* haptics points in */
	Endosim__CaseListReply case_list;
	Endosim__CaseEntry *case_entries;
	Endosim__CaseEntry **case_entries_p;
	struct cases_entry *cases;
	char case_error[512];
	Endosim__SessionReply session_reply;
	Endosim__SessionInfo session;
	struct recorder_info rinfo;        /* what session points into */
	struct sessionpb_metrics metrics;
	Endosim__SessionListReply session_list;
	Endosim__SessionInfo *list_infos;
	Endosim__SessionInfo **list_infos_p;
	struct sessiondir_entry *list_entries;
	struct sessiondir_entry shown;     /* SessionShow's file */
};

struct control {
	struct config cfg;       /* the master copy */
	struct control_deps deps;
	char ro_path[sizeof(((struct sockaddr_un *)0)->sun_path)];
	char rw_path[sizeof(((struct sockaddr_un *)0)->sun_path)];
	int ro_fd, rw_fd, ep, wake_fd;
	struct client *clients;
	int max_clients;
	size_t max_request;
	size_t max_queued;
	gid_t command_gid;       /* who may command besides root */
	struct reply_buf rb;
	struct colon *colon;     /* the loop's now: read its mesh only */
	char case_path[2 * CONFIG_STR + 8]; /* the file it was built from */
	uint64_t scene_id;
	struct scene *scene;     /* GetScene's replies, made on demand */
	uint64_t rate_t0_ns, rate_cycle0;
	double loop_hz;
	pthread_t thread;
	bool running;
	_Atomic bool alive;
	_Atomic bool stop;
	bool end;                /* a test command: the thread ends */
};

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
	cl->may_command = rw && peer_may_command(c, fd, &cred);
	cl->uid = cred.uid;
	cl->pid = cred.pid;
	cl->last_rx_ns = mono_ns();
	cl->partial_ns = 0;
	if (epoll_add(c->ep, fd, TAG_CLIENT + (uint64_t)(cl - c->clients),
		      EPOLLIN)) {
		client_drop(c, cl);
	}
}

/* ---------------------------------------------------------------- replies */

/* One latched fault, bit number K, into the reply's slot N. */
static void fill_fault(struct control *c, const struct endosim_state *st,
		       int k, size_t n)
{
	const struct endosim_fault_cause *fc = &st->safety.cause[k];
	Endosim__Fault *f = &c->rb.faults[n];

	endosim__fault__init(f);
	faults_format(c->deps.rig, c->deps.start_ns, 1u << k, fc,
		      c->rb.fault_lines[n], sizeof(c->rb.fault_lines[n]));
	f->code = (uint32_t)k;
	f->name = (char *)names_fault(1u << k);
	f->axis = fc->axis >= 0 ? (char *)names_axis(fc->axis) : "";
	f->time_s = (double)(fc->first_ns - c->deps.start_ns) / 1e9;
	f->text = c->rb.fault_lines[n];
	f->active = st->safety.active & 1u << k;
	f->value = fc->value;
	f->limit = fc->limit;
	f->detail = fc->detail;
	c->rb.faults_p[n] = f;
}

/* Every latched fault, the first one first; its line is the fault text. */
static void fill_faults(struct control *c, const struct endosim_state *st,
			Endosim__StatusReply *s)
{
	size_t n = 0;

	if (st->fault_first) {
		fill_fault(c, st, __builtin_ctz(st->fault_first), n++);
	}
	for (int k = 0; k < ENDOSIM_FAULT_BITS; k++) {
		if ((st->fault_bits & 1u << k) && 1u << k != st->fault_first) {
			fill_fault(c, st, k, n++);
		}
	}
	s->n_faults = n;
	s->faults = c->rb.faults_p;
	s->fault_text = n ? c->rb.fault_lines[0] : "";
	s->active_faults = st->safety.active;
	s->ramp = st->safety.ramp;
}

static void update_loop_rate(struct control *c, uint64_t now)
{
	uint64_t cycles = loop_heartbeat(c->deps.loop);

	if (!c->rate_t0_ns) {
		c->rate_t0_ns = now;
		c->rate_cycle0 = cycles;
		return;
	}
	if (now - c->rate_t0_ns >= 1000000000ull) {
		c->loop_hz = (double)(cycles - c->rate_cycle0) * 1e9 /
			     (double)(now - c->rate_t0_ns);
		c->rate_t0_ns = now;
		c->rate_cycle0 = cycles;
	}
}

/* The protobuf view of the published scope: arrays point into SC. */
static void fill_scope(Endosim__ScopeStatus *p, struct endosim_scope_state *sc)
{
	endosim__scope_status__init(p);
	p->depth_m = sc->depth_m;
	p->tip_s_m = sc->tip_s_m;
	p->base_s_m = sc->base_s_m;
	p->n_bend_rad = 2;
	p->bend_rad = sc->bend_rad;
	p->n_tip = p->n_dir = p->n_up = 3;
	p->tip = sc->tip;
	p->dir = sc->dir;
	p->up = sc->up;
	p->turning_rad = sc->turning_rad;
	p->n_bow_m = sc->spans;
	p->bow_m = sc->bow_m;
	p->scene_id = sc->scene_id;
}

/* The protobuf view of the published haptics: arrays point into H. */
static void fill_haptics(Endosim__HapticsStatus *p,
			 struct endosim_haptics_state *h)
{
	endosim__haptics_status__init(p);
	p->n_proxy = p->n_normal = p->n_f_static = 3;
	p->proxy = h->proxy;
	p->normal = h->normal;
	p->f_static = h->f_static;
	p->penetration_m = h->penetration_m;
	p->contact = h->contact;
	p->constraints = h->constraints;
	p->curvature_rad = h->curvature_rad;
	p->trans_contact_n = h->trans_contact_n;
	p->trans_friction_n = h->trans_friction_n;
	p->trans_loop_n = h->trans_loop_n;
	p->n_wheel_contact_nm = p->n_wheel_tension_nm = 2;
	p->n_wheel_elastic_nm = p->n_wire_dl_m = 2;
	p->wheel_contact_nm = h->wheel_contact_nm;
	p->wheel_tension_nm = h->wheel_tension_nm;
	p->wheel_elastic_nm = h->wheel_elastic_nm;
	p->wire_dl_m = h->wire_dl_m;
	p->tube_contact_nm = h->tube_contact_nm;
	p->tube_friction_nm = h->tube_friction_nm;
	p->n_damping = ENDOSIM_AXES;
	p->damping = h->damping;
	p->passivity_energy_j = h->passivity_energy_j;
	p->passivity_damping = h->passivity_damping;
}

static void build_status(struct control *c, Endosim__Reply *rep)
{
	struct reply_buf *rb = &c->rb;
	const struct loop_info *info = loop_get_info(c->deps.loop);
	Endosim__StatusReply *s = &rb->status;
	struct endosim_state st;

	if (publish_read(c->deps.pub, &st)) {
		rep->status = ENDOSIM__STATUS__STATUS_INTERNAL;
		rep->error = "state busy, try again";
		return;
	}
	endosim__status_reply__init(s);
	s->state = (Endosim__DaemonState)st.state;
	s->fault_bits = st.fault_bits;
	fill_faults(c, &st, s);
	s->cycle = st.cycle;
	s->stamp_ns = st.stamp_ns;
	s->rt_policy = (char *)info->policy;
	s->rt_priority = info->priority;
	s->loop_hz = c->loop_hz ? c->loop_hz
				: (double)st.cycle * 1e9 /
					  (double)(st.stamp_ns - c->deps.start_ns + 1);
	s->loop_rate_hz = c->cfg.loop.rate_hz;
	s->overruns = st.overruns;
	s->rig = (char *)rig_name(c->deps.rig);
	s->version = ENDOSIM_VERSION;
	s->uptime_s = (double)(mono_ns() - c->deps.start_ns) / 1e9;
	s->scenario_time_s = st.scenario_time_s;
	s->scenario_done = st.scenario_done;
	s->case_name = (char *)colon_name(c->colon);
	rb->scope_state = st.scope;
	fill_scope(&rb->scope, &rb->scope_state);
	s->scope = &rb->scope;
	rb->haptics_state = st.haptics;
	fill_haptics(&rb->haptics, &rb->haptics_state);
	s->haptics = &rb->haptics;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		Endosim__AxisStatus *ax = &rb->axes[a];

		endosim__axis_status__init(ax);
		ax->name = (char *)names_axis(a);
		ax->position = st.axis[a].position;
		ax->velocity = st.axis[a].velocity;
		ax->hand = st.axis[a].hand;
		ax->command = st.axis[a].command;
		ax->limited = st.axis[a].limited;
		ax->position_unit = (char *)names_axis_position_unit(a);
		ax->force_unit = (char *)names_axis_force_unit(a);
		ax->drive_status = st.axis[a].drive_status;
		rb->axes_p[a] = ax;
	}
	s->n_axes = ENDOSIM_AXES;
	s->axes = rb->axes_p;
	rep->body_case = ENDOSIM__REPLY__BODY_STATUS_REPLY;
	rep->status_reply = s;
}

static void fill_histogram(Endosim__Histogram *h,
			   const struct histo_summary *s)
{
	endosim__histogram__init(h);
	h->p50_us = s->p50_us;
	h->p99_us = s->p99_us;
	h->p999_us = s->p999_us;
	h->max_us = s->max_us;
	h->mean_us = s->mean_us;
	h->count = s->count;
}

/* At most one bus per axis. */
static void fill_buses(struct control *c)
{
	struct reply_buf *rb = &c->rb;
	struct rig_bus_stats st;
	size_t n = 0;

	while (n < ENDOSIM_AXES && !rig_bus_stats(c->deps.rig, (int)n, &st)) {
		Endosim__BusStats *b = &rb->buses[n];

		endosim__bus_stats__init(b);
		b->name = (char *)st.name;
		b->rate_hz = st.rate_hz;
		b->exchanges = st.exchanges;
		fill_histogram(&rb->bus_histo[n][0], &st.exchange);
		fill_histogram(&rb->bus_histo[n][1], &st.txn);
		b->exchange = &rb->bus_histo[n][0];
		b->transaction = &rb->bus_histo[n][1];
		rb->buses_p[n++] = b;
	}
	rb->stats.n_buses = n;
	rb->stats.buses = rb->buses_p;
}

static void build_stats(struct control *c, Endosim__Reply *rep)
{
	struct reply_buf *rb = &c->rb;
	const struct loop_info *info = loop_get_info(c->deps.loop);
	struct loop_stats st;

	loop_get_stats(c->deps.loop, &st);
	endosim__stats_reply__init(&rb->stats);
	rb->stats.cycles = st.cycles;
	rb->stats.overruns = st.overruns;
	fill_histogram(&rb->latency, &st.latency);
	fill_histogram(&rb->compute, &st.compute);
	rb->stats.latency = &rb->latency;
	rb->stats.compute = &rb->compute;
	rb->stats.rt_policy = (char *)info->policy;
	rb->stats.rt_priority = info->priority;
	rb->stats.period_us = info->period_ns / 1000.0;
	fill_buses(c);
	rep->body_case = ENDOSIM__REPLY__BODY_STATS;
	rep->stats = &rb->stats;
}

/* ---------------------------------------------------------------- requests */

typedef void handler_fn(struct control *c, struct client *cl,
			const Endosim__Request *req, Endosim__Reply *rep);

static void refuse(Endosim__Reply *rep, Endosim__Status status,
		   const char *why)
{
	rep->status = status;
	rep->error = (char *)why;
}

static void on_get_status(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)cl;
	(void)req;
	build_status(c, rep);
}

static void on_get_stats(struct control *c, struct client *cl,
			 const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)cl;
	(void)req;
	build_stats(c, rep);
}

static void on_get_config(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	struct reply_buf *rb = &c->rb;
	const char *want = req->get_config->key;
	size_t n = 0;

	(void)cl;
	for (size_t i = 0; i < config_key_count(); i++) {
		const struct config_key *k = config_key_at(i);
		Endosim__ConfigEntry *e = &rb->entries[n];
		char *value = rb->values[n];
		int len = snprintf(value, sizeof(rb->values[n]), "%s.%s",
				   k->section, k->name);

		if (*want && strcmp(want, value)) {
			continue;
		}
		endosim__config_entry__init(e);
		e->key = value;
		config_format(&c->cfg, k, value + len + 1,
			      sizeof(rb->values[n]) - (size_t)len - 1);
		e->value = value + len + 1;
		e->unit = (char *)k->unit;
		e->live = k->flags & CONFIG_LIVE;
		e->help = (char *)k->help;
		rb->entries_p[n++] = e;
	}
	if (*want && !n) {
		refuse(rep, ENDOSIM__STATUS__STATUS_UNKNOWN_KEY, "no such key");
		return;
	}
	endosim__config_reply__init(&rb->config);
	rb->config.n_entries = n;
	rb->config.entries = rb->entries_p;
	rep->body_case = ENDOSIM__REPLY__BODY_CONFIG;
	rep->config = &rb->config;
}

static void on_set_param(struct control *c, struct client *cl,
			 const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__SetParam *sp = req->set_param;
	const struct config_key *k = config_key_find(sp->key);
	char before[CONFIG_STR + 32];
	int r;

	if (k) {
		config_format(&c->cfg, k, before, sizeof(before));
	}
	r = config_set(&c->cfg, sp->key, sp->value, true, c->rb.error,
		       sizeof(c->rb.error));
	if (r) {
		refuse(rep, r == -ENOENT   ? ENDOSIM__STATUS__STATUS_UNKNOWN_KEY
			    : r == -EPERM ? ENDOSIM__STATUS__STATUS_NOT_LIVE
					  : ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       c->rb.error);
		return;
	}
	loop_set_config(c->deps.loop, &c->cfg);
	atomic_store(&log_max_level, c->cfg.log.level);
	recorder_param(c->deps.recorder, sp->key, sp->value);
	log_notice("%s set from %s to %s (uid %d)", sp->key, before, sp->value,
		   (int)cl->uid);
}

static void on_command(struct control *c, struct client *cl,
		       enum loop_cmd cmd, const char *what,
		       Endosim__Reply *rep)
{
	int r = loop_command(c->deps.loop, cmd, COMMAND_TIMEOUT_MS);

	switch (r) {
	case 0:
		log_info("%s by uid %d", what, (int)cl->uid);
		return;
	case -EPERM:
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "latched in FAULT or ESTOP: reset first");
		return;
	case -EBUSY:
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "the fault's cause is still present");
		return;
	default:
		refuse(rep, ENDOSIM__STATUS__STATUS_TIMEOUT,
		       "the force loop did not take the command");
		return;
	}
}

static void on_enable(struct control *c, struct client *cl,
		      const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_ENABLE, "enable", rep);
}

static void on_disable(struct control *c, struct client *cl,
		       const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_DISABLE, "disable", rep);
}

static void on_estop(struct control *c, struct client *cl,
		     const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_ESTOP, "emergency stop", rep);
}

static void on_reset(struct control *c, struct client *cl,
		     const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_RESET, "reset", rep);
}

static void on_reset_stats(struct control *c, struct client *cl,
			   const Endosim__Request *req, Endosim__Reply *rep)
{
	(void)req;
	on_command(c, cl, LOOP_CMD_RESET_STATS, "statistics reset", rep);
}

static void on_hand_input(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__HandInput *hi = req->hand_input;
	double hold = hi->hold_ms ? hi->hold_ms / 1000.0 : c->cfg.sim.hand_hold_s;

	(void)cl;
	if (!c->deps.hand) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "the rig is not simulated");
		return;
	}
	if (hi->n_force != ENDOSIM_AXES || hold > MAX_HOLD_S) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "need 4 forces and a hold of at most 10 s");
		return;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		if (!isfinite(hi->force[a])) {
			refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
			       "forces must be finite");
			return;
		}
	}
	hand_set_live(c->deps.hand, hi->force, hold, mono_ns());
}

static void on_subscribe(struct control *c, struct client *cl,
			 const Endosim__Request *req, Endosim__Reply *rep)
{
	double hz = req->subscribe->rate_hz;

	if (!isfinite(hz) || hz < 0 || hz > MAX_PUSH_HZ) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "rate_hz must be in [0, 1000]");
		return;
	}
	cl->push_period_ns = hz > 0 ? (uint64_t)(1e9 / hz) : 0;
	cl->next_push_ns = mono_ns();
	cl->push_seq = req->seq;
	build_status(c, rep);
}

static void on_get_scene(struct control *c, struct client *cl,
			 const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__GetScene *g = req->get_scene;
	Endosim__SceneReply *sr;

	(void)cl;
	if (g->chunk && g->scene_id != c->scene_id) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "the case changed: start again from chunk 0");
		return;
	}
	if (!c->scene) {
		c->scene = scene_create(c->colon, c->scene_id);
		if (!c->scene) {
			log_err("GetScene: out of memory");
			refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL,
			       "out of memory");
			return;
		}
	}
	sr = scene_reply(c->scene, g->chunk);
	if (!sr) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, "no such chunk");
		return;
	}
	rep->body_case = ENDOSIM__REPLY__BODY_SCENE;
	rep->scene = sr;
}

static void free_case_list(struct reply_buf *rb)
{
	free(rb->cases);
	free(rb->case_entries);
	free(rb->case_entries_p);
	rb->cases = NULL;
	rb->case_entries = NULL;
	rb->case_entries_p = NULL;
}

static void on_list_cases(struct control *c, struct client *cl,
			  const Endosim__Request *req, Endosim__Reply *rep)
{
	struct reply_buf *rb = &c->rb;
	Endosim__CaseListReply *l = &rb->case_list;
	size_t n;

	(void)cl;
	(void)req;
	free_case_list(rb);
	if (cases_list(c->cfg.colon.directory, &rb->cases, &n, rb->case_error,
		       sizeof(rb->case_error))) {
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, rb->case_error);
		return;
	}
	rb->case_entries = calloc(n + 1, sizeof(*rb->case_entries));
	rb->case_entries_p = calloc(n + 1, sizeof(*rb->case_entries_p));
	if (!rb->case_entries || !rb->case_entries_p) {
		free_case_list(rb);
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, "out of memory");
		return;
	}
	for (size_t i = 0; i < n; i++) {
		Endosim__CaseEntry *e = &rb->case_entries[i];

		endosim__case_entry__init(e);
		e->name = rb->cases[i].name;
		e->description = rb->cases[i].description;
		e->loaded = !strcmp(e->name, colon_name(c->colon));
		rb->case_entries_p[i] = e;
	}
	endosim__case_list_reply__init(l);
	l->n_cases = n;
	l->cases = rb->case_entries_p;
	l->directory = c->cfg.colon.directory;
	l->error = rb->case_error;
	rep->body_case = ENDOSIM__REPLY__BODY_CASES;
	rep->cases = l;
}

/* Hands COLON to the loop; on success it is the one GetScene serves. */
static int swap_colon(struct control *c, struct colon *colon)
{
	struct colon *old = NULL;
	int r = loop_swap_colon(c->deps.loop, colon, c->scene_id + 1, &old,
				SWAP_TIMEOUT_MS);

	if (r) {
		colon_destroy(colon);
		return r;
	}
	scene_destroy(c->scene);
	c->scene = NULL;
	c->colon = colon;
	c->scene_id++;
	colon_destroy(old);
	return 0;
}

/* Loads case NAME (IDLE only, never during a session). 0, or -1 refused. */
static int load_case(struct control *c, struct client *cl, const char *name,
		     Endosim__Reply *rep)
{
	struct recorder_info ri;
	struct endosim_state st;
	struct colon *colon;
	int r;

	recorder_info(c->deps.recorder, &ri);
	if (ri.recording) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "a session is recording: 'session stop' first");
		return -1;
	}
	if (!publish_read(c->deps.pub, &st) &&
	    st.state != ENDOSIM_STATE_IDLE) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "a case loads only while IDLE: disable first");
		return -1;
	}
	colon = cases_load(&c->cfg, name, c->rb.error, sizeof(c->rb.error));
	if (!colon) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->rb.error);
		return -1;
	}
	r = swap_colon(c, colon);
	if (r == -EBUSY) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "a case loads only while IDLE: disable first");
		return -1;
	}
	if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_TIMEOUT,
		       "the force loop did not take the new case");
		return -1;
	}
	cases_path(&c->cfg, name, c->case_path, sizeof(c->case_path));
	log_notice("case %s loaded (uid %d): %u triangles", name,
		   (int)cl->uid, colon_mesh(colon)->triangles);
	return 0;
}

static void on_load_case(struct control *c, struct client *cl,
			 const Endosim__Request *req, Endosim__Reply *rep)
{
	load_case(c, cl, req->load_case->name, rep);
}

/* ---------------------------------------------------------------- sessions */

/* A trainee's name: shorter than SIZE, no control characters. */
static bool session_name_ok(const char *s, size_t size)
{
	if (strlen(s) >= size) {
		return false;
	}
	for (; *s; s++) {
		if ((unsigned char)*s < 0x20 || *s == 0x7f) {
			return false;
		}
	}
	return true;
}

/* The effective configuration as --print-config prints it (malloc'd). */
static char *config_text(const struct config *cfg)
{
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);

	if (!f) {
		return NULL;
	}
	config_print(cfg, f);
	if (fclose(f)) {
		free(text);
		return NULL;
	}
	return text;
}

/* The case file's text (malloc'd); an imported mesh: its paths. */
static char *case_text(const struct control *c)
{
	const char *path = c->case_path;
	size_t n = strlen(path);
	char *text = NULL;
	FILE *f;
	long len;

	if (n > 4 && !strcmp(path + n - 4, ".obj")) {
		return asprintf(&text, "# an imported mesh\nobj=%s\n"
				"centreline=%s\n", path,
				c->cfg.colon.centreline_file) < 0 ? NULL : text;
	}
	f = fopen(path, "re");
	if (!f || fseek(f, 0, SEEK_END) || (len = ftell(f)) < 0 ||
	    len > (long)SESSION_FRAME_MAX || fseek(f, 0, SEEK_SET) ||
	    !(text = calloc(1, (size_t)len + 1)) ||
	    fread(text, 1, (size_t)len, f) != (size_t)len) {
		free(text);
		text = NULL;
	}
	if (f) {
		fclose(f);
	}
	return text;
}

/* The reply's SessionInfo for the recorder's session IN. */
static Endosim__SessionInfo *fill_session(struct control *c,
					  const struct recorder_info *in)
{
	struct reply_buf *rb = &c->rb;
	Endosim__SessionInfo *s = &rb->session;

	rb->rinfo = *in;
	endosim__session_info__init(s);
	s->id = rb->rinfo.id;
	s->trainee = rb->rinfo.trainee;
	s->case_name = rb->rinfo.case_name;
	s->started = rb->rinfo.started;
	s->start_ns = rb->rinfo.start_ns;
	s->end_ns = rb->rinfo.end_ns;
	s->duration_s = (double)((rb->rinfo.end_ns ? rb->rinfo.end_ns
						   : mono_ns()) -
				 rb->rinfo.start_ns) / 1e9;
	s->records = rb->rinfo.records;
	s->drops = rb->rinfo.drops;
	s->bytes = rb->rinfo.bytes;
	s->path = rb->rinfo.path;
	s->recording = rb->rinfo.recording;
	s->ended = !rb->rinfo.recording;
	sessionpb_from_metrics(&rb->metrics, &rb->rinfo.metrics);
	s->metrics = &rb->metrics.msg;
	return s;
}

static void session_reply(struct control *c, Endosim__Reply *rep,
			  Endosim__SessionInfo *s)
{
	endosim__session_reply__init(&c->rb.session_reply);
	c->rb.session_reply.session = s;
	rep->body_case = ENDOSIM__REPLY__BODY_SESSION;
	rep->session = &c->rb.session_reply;
}

static int start_session(struct control *c, const char *trainee,
			 struct recorder_info *info)
{
	struct recorder_session s = {
		.colon = c->colon,
		.period_ns = loop_get_info(c->deps.loop)->period_ns,
		.step_m = c->cfg.colon.step_m,
		.segment_m = c->cfg.colon.segment_m,
		.ring_vertices = c->cfg.colon.ring_vertices,
	};
	char *cfg = config_text(&c->cfg), *cs = case_text(c);
	int r = -ENOMEM;

	snprintf(s.trainee, sizeof(s.trainee), "%s", trainee);
	snprintf(s.case_name, sizeof(s.case_name), "%s", colon_name(c->colon));
	if (cfg && cs) {
		s.config_text = cfg;
		s.case_text = cs;
		r = recorder_start(c->deps.recorder, &s, info);
	}
	free(cfg);
	free(cs);
	return r;
}

static void on_session_start(struct control *c, struct client *cl,
			     const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__SessionStart *ss = req->session_start;
	struct recorder_info info;
	int r;

	recorder_info(c->deps.recorder, &info);
	if (!session_name_ok(ss->trainee, RECORDER_NAME)) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "trainee: at most 63 bytes, no control characters");
		return;
	}
	if (*ss->case_name && !config_case_name_ok(ss->case_name)) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "case: letters, digits, '-' and '_'");
		return;
	}
	if (info.recording) {
		snprintf(c->rb.error, sizeof(c->rb.error), "session %" PRIu64
			 " is recording: 'session stop' first", info.id);
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED, c->rb.error);
		return;
	}
	if (*ss->case_name && load_case(c, cl, ss->case_name, rep)) {
		return;
	}
	r = start_session(c, ss->trainee, &info);
	if (r) {
		snprintf(c->rb.error, sizeof(c->rb.error), "cannot record in "
			 "%s: %s", c->cfg.session.directory, strerror(-r));
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, c->rb.error);
		return;
	}
	log_notice("session %" PRIu64 " started (uid %d): trainee '%s', case "
		   "%s, %s", info.id, (int)cl->uid, info.trainee,
		   info.case_name, info.path);
	session_reply(c, rep, fill_session(c, &info));
}

static void on_session_stop(struct control *c, struct client *cl,
			    const Endosim__Request *req, Endosim__Reply *rep)
{
	struct recorder_info info;
	int r = recorder_stop(c->deps.recorder, &info);

	(void)req;
	if (r == -ENOENT) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "no session is recording");
		return;
	}
	log_notice("session %" PRIu64 " stopped (uid %d): %" PRIu64
		   " records, %" PRIu64 " dropped, %s", info.id, (int)cl->uid,
		   info.records, info.drops, info.path);
	if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL,
		       "the session file could not be finished (see the log)");
		return;
	}
	session_reply(c, rep, fill_session(c, &info));
}

static void on_session_status(struct control *c, struct client *cl,
			      const Endosim__Request *req, Endosim__Reply *rep)
{
	struct recorder_info info;

	(void)cl;
	(void)req;
	recorder_info(c->deps.recorder, &info);
	session_reply(c, rep, info.active ? fill_session(c, &info) : NULL);
}

static void free_session_list(struct reply_buf *rb)
{
	free(rb->list_infos);
	free(rb->list_infos_p);
	free(rb->list_entries);
	rb->list_infos = NULL;
	rb->list_infos_p = NULL;
	rb->list_entries = NULL;
}

/* A listed session; the recorder's own one with what it knows. */
static void fill_entry(Endosim__SessionInfo *s, struct sessiondir_entry *e,
		       const struct recorder_info *ri)
{
	sessionpb_from_entry(s, e);
	if (ri->active && ri->id == e->id) {
		s->recording = ri->recording;
		s->records = ri->records;
		s->drops = ri->drops;
		s->start_ns = ri->start_ns;
		s->end_ns = ri->end_ns;
	}
}

static void on_session_list(struct control *c, struct client *cl,
			    const Endosim__Request *req, Endosim__Reply *rep)
{
	struct reply_buf *rb = &c->rb;
	struct recorder_info ri;
	size_t n;
	int r;

	(void)cl;
	(void)req;
	free_session_list(rb);
	recorder_info(c->deps.recorder, &ri);
	r = sessiondir_list(c->cfg.session.directory, &rb->list_entries, &n);
	rb->list_infos = r ? NULL : calloc(n + 1, sizeof(*rb->list_infos));
	rb->list_infos_p = r ? NULL : calloc(n + 1, sizeof(*rb->list_infos_p));
	if (r || !rb->list_infos || !rb->list_infos_p) {
		snprintf(rb->error, sizeof(rb->error), "%s: %s",
			 c->cfg.session.directory, strerror(r ? -r : ENOMEM));
		free_session_list(rb);
		refuse(rep, ENDOSIM__STATUS__STATUS_INTERNAL, rb->error);
		return;
	}
	for (size_t i = 0; i < n; i++) {
		fill_entry(&rb->list_infos[i], &rb->list_entries[i], &ri);
		rb->list_infos_p[i] = &rb->list_infos[i];
	}
	endosim__session_list_reply__init(&rb->session_list);
	rb->session_list.n_sessions = n;
	rb->session_list.sessions = rb->list_infos_p;
	rb->session_list.directory = c->cfg.session.directory;
	rep->body_case = ENDOSIM__REPLY__BODY_SESSION_LIST;
	rep->session_list = &rb->session_list;
}

static void on_session_show(struct control *c, struct client *cl,
			    const Endosim__Request *req, Endosim__Reply *rep)
{
	struct reply_buf *rb = &c->rb;
	uint64_t id = req->session_show->id;
	struct sessiondir_entry *e = &rb->shown;
	Endosim__SessionInfo *s;
	struct recorder_info ri;
	int r;

	(void)cl;
	recorder_info(c->deps.recorder, &ri);
	r = sessiondir_stat(c->cfg.session.directory, id, e);
	if (r) {
		snprintf(rb->error, sizeof(rb->error), "no session %" PRIu64
			 " in %s%s", id, c->cfg.session.directory,
			 r == -ENOENT ? "" : r == -EBADMSG ? ": not a session "
			 "file" : ": unreadable");
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, rb->error);
		return;
	}
	if (ri.active && ri.id == id) {
		s = fill_session(c, &ri);
	} else {
		memset(&rb->rinfo, 0, sizeof(rb->rinfo));
		fill_entry(&rb->session, e, &rb->rinfo);
		sessiondir_path(c->cfg.session.directory, id, rb->rinfo.path,
				sizeof(rb->rinfo.path));
		s = &rb->session;
		s->path = rb->rinfo.path;
	}
	s->ended = e->ended;
	s->bytes = s->recording ? s->bytes : e->bytes;
	s->trainee = s->trainee ? s->trainee : "";
	session_reply(c, rep, s);
}

static void on_debug(struct control *c, struct client *cl,
		     const Endosim__Request *req, Endosim__Reply *rep)
{
	const Endosim__DebugInject *d = req->debug_inject;
	const char *name = inject_name(d->action);
	int r;

	if (!c->cfg.debug.test_commands) {
		refuse(rep, ENDOSIM__STATUS__STATUS_REFUSED,
		       "test commands are off ([debug] test_commands = no)");
		return;
	}
	log_warn("test command %s on axis %d, value %g (uid %d)",
		 name ? name : "?", d->axis, d->value, (int)cl->uid);
	if (d->action == ENDOSIM__DEBUG_ACTION__DEBUG_ACTION_END_CONTROL) {
		c->end = true;
		return;
	}
	r = loop_debug(c->deps.loop, d->action, d->axis, d->value,
		       COMMAND_TIMEOUT_MS);
	if (r == -EINVAL) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "no such test command, axis or stage");
	} else if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_TIMEOUT,
		       "the force loop did not take the command");
	}
}

struct handler {
	Endosim__Request__BodyCase body;
	bool writes; /* refused on the read-only socket */
	handler_fn *fn;
};

static const struct handler handlers[] = {
	{ ENDOSIM__REQUEST__BODY_GET_STATUS, false, on_get_status },
	{ ENDOSIM__REQUEST__BODY_GET_STATS, false, on_get_stats },
	{ ENDOSIM__REQUEST__BODY_GET_CONFIG, false, on_get_config },
	{ ENDOSIM__REQUEST__BODY_SUBSCRIBE, false, on_subscribe },
	{ ENDOSIM__REQUEST__BODY_GET_SCENE, false, on_get_scene },
	{ ENDOSIM__REQUEST__BODY_LIST_CASES, false, on_list_cases },
	{ ENDOSIM__REQUEST__BODY_LOAD_CASE, true, on_load_case },
	{ ENDOSIM__REQUEST__BODY_SET_PARAM, true, on_set_param },
	{ ENDOSIM__REQUEST__BODY_ENABLE, true, on_enable },
	{ ENDOSIM__REQUEST__BODY_DISABLE, true, on_disable },
	{ ENDOSIM__REQUEST__BODY_ESTOP, true, on_estop },
	{ ENDOSIM__REQUEST__BODY_RESET_FAULT, true, on_reset },
	{ ENDOSIM__REQUEST__BODY_HAND_INPUT, true, on_hand_input },
	{ ENDOSIM__REQUEST__BODY_RESET_STATS, true, on_reset_stats },
	{ ENDOSIM__REQUEST__BODY_DEBUG_INJECT, true, on_debug },
	{ ENDOSIM__REQUEST__BODY_SESSION_START, true, on_session_start },
	{ ENDOSIM__REQUEST__BODY_SESSION_STOP, true, on_session_stop },
	{ ENDOSIM__REQUEST__BODY_SESSION_STATUS, false, on_session_status },
	{ ENDOSIM__REQUEST__BODY_SESSION_LIST, false, on_session_list },
	{ ENDOSIM__REQUEST__BODY_SESSION_SHOW, false, on_session_show },
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
	} else {
		h->fn(c, cl, req, &rep);
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
			build_status(c, &rep);
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
	uint64_t idle = (uint64_t)(c->cfg.socket.idle_timeout_s * 1e9);
	uint64_t partial = (uint64_t)(c->cfg.socket.partial_timeout_s * 1e9);

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
	size_t keys = config_key_count();

	c->clients = calloc((size_t)c->max_clients, sizeof(*c->clients));
	c->rb.entries = calloc(keys, sizeof(*c->rb.entries));
	c->rb.entries_p = calloc(keys, sizeof(*c->rb.entries_p));
	c->rb.values = calloc(keys, sizeof(*c->rb.values));
	if (!c->clients || !c->rb.entries || !c->rb.entries_p ||
	    !c->rb.values) {
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
	if (alloc_buffers(c) || open_sockets(c)) {
		control_destroy(c);
		return NULL;
	}
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
	free(c->rb.entries);
	free(c->rb.entries_p);
	free(c->rb.values);
	free_case_list(&c->rb);
	free_session_list(&c->rb);
	scene_destroy(c->scene);
	free(c);
}
