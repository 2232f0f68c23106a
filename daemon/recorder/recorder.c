/* recorder.c - see recorder.h. */
#include "recorder/recorder.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "model/anatomy.h"
#include "model/gas.h"
#include "proto/names.h"
#include "proto/version.h"
#include "loop/faults.h"
#include "base/log.h"
#include "base/mono.h"
#include "session/sessiondir.h"
#include "session/sessioninputs.h"
#include "session/metricstext.h"
#include "session/records.h"

#define BUF_BYTES (256 * 1024)   /* gathered frames, written in one go */
#define FLUSH_BYTES (BUF_BYTES / 2)
#define FLUSH_NS 100000000ull    /* write at least every 100 ms */
#define SNAPSHOT_NS 100000000ull /* live metrics for the control thread */
#define IDLE_NAP_NS 10000000L    /* the thread's pace between batches */
#define PARAMS 32                /* PARAM events queued between batches */
#define PARAM_TEXT 192
#define EVENT_TEXT 512
#define HEADER_BYTES 1024

enum phase { PHASE_IDLE, PHASE_RECORDING, PHASE_STOPPING };

struct param {
	uint64_t stamp_ns;
	char text[PARAM_TEXT];
};

struct recorder {
	struct session_tap tap;
	char dir[CONFIG_STR];
	double write_limit;          /* bytes/s, 0: none */
	struct metrics_params mp;
	struct rig *rig;
	struct publish *pub;
	uint64_t daemon_start_ns;
	uint32_t period_ns;
	pthread_t thread;
	bool running;

	pthread_mutex_t lock;        /* guards what follows up to "thread" */
	pthread_cond_t changed;
	bool quit;
	enum phase phase;
	struct recorder_info info;   /* what the control thread sees */
	struct recorder_map map;     /* the live map the control thread sees */
	bool map_ready;              /* map is this session's */
	struct param params[PARAMS];
	size_t n_params;
	int stop_result;

	/* the recorder thread's while recording (set up by start) */
	int fd;
	const struct colon *colon;   /* the session's: its sites' names */
	struct metrics *metrics;
	unsigned char *buf;
	size_t used;
	uint64_t last_write_ns, last_snapshot_ns, last_map_ns;
	uint64_t first_stamp_ns;     /* the session's first record */
	struct session_record last;  /* the newest record drained */
	struct metrics_map floats;   /* metrics_map(), before quantising */
	struct recorder_map next;    /* the map being made */
	uint64_t records, bytes, drops_written;
	uint64_t sum;                /* records_checksum() of what is written */
	bool sum_ok;                 /* every byte of the file went into sum */
	uint64_t throttle_t0_ns, throttle_bytes;
	uint32_t last_state, last_faults;
	uint32_t last_guide;       /* enum endosim_guide_phase */
	bool seen_record;
	struct param batch[PARAMS];
	struct session_shape shape;  /* popped, then packed into payload */
	unsigned char payload[sizeof(struct session_shape)];
};

/* ------------------------------------------------------------ writing */

static void nap_ns(uint64_t ns)
{
	struct timespec ts = { .tv_sec = (time_t)(ns / ENDOSIM_NS_PER_S),
			       .tv_nsec = (long)(ns % ENDOSIM_NS_PER_S) };

	while (nanosleep(&ts, &ts) < 0 && errno == EINTR) {
	}
}

static bool stopping(struct recorder *r)
{
	bool s;

	pthread_mutex_lock(&r->lock);
	s = r->phase != PHASE_RECORDING || r->quit;
	pthread_mutex_unlock(&r->lock);
	return s;
}

/*
 * The test-only slow disk: waits until N more bytes keep the writer under
 * [session] write_limit_bytes_per_s. Not once the session is stopping.
 */
static void throttle(struct recorder *r, size_t n)
{
	uint64_t due, now;

	if (r->write_limit <= 0) {
		return;
	}
	r->throttle_bytes += n;
	due = r->throttle_t0_ns + (uint64_t)((double)r->throttle_bytes /
					     r->write_limit * ENDOSIM_NS_PER_S);
	while ((now = mono_ns()) < due && !stopping(r)) {
		nap_ns(due - now < 20000000u ? due - now : 20000000u);
	}
}

static int write_all(int fd, const unsigned char *p, size_t n)
{
	while (n) {
		ssize_t w = write(fd, p, n);

		if (w < 0 && errno == EINTR) {
			continue;
		}
		if (w <= 0) {
			return w < 0 ? -errno : -EIO;
		}
		p += w;
		n -= (size_t)w;
	}
	return 0;
}

/* Writes the gathered frames. A failed write is logged once per session. */
static void flush(struct recorder *r)
{
	int e;

	r->last_write_ns = mono_ns();
	if (!r->used) {
		return;
	}
	throttle(r, r->used);
	e = r->fd >= 0 ? write_all(r->fd, r->buf, r->used) : -EBADF;
	if (e && r->fd >= 0) {
		log_err("session %" PRIu64 ": %s: %s; the rest of the session "
			"is not recorded", r->info.id, r->info.path,
			strerror(-e));
		close(r->fd);
		r->fd = -1;
	}
	if (!e) {
		r->bytes += r->used;
		r->sum = records_checksum(r->sum, r->buf, r->used);
	} else {
		r->sum_ok = false; /* part of it may be in the file */
	}
	r->used = 0;
}

static void put_frame(struct recorder *r, uint32_t type, const void *payload,
		      uint32_t length)
{
	size_t n = session_frame_put(r->buf, BUF_BYTES, r->used, type, payload,
				     length);

	if (!n) {
		flush(r);
		n = session_frame_put(r->buf, BUF_BYTES, 0, type, payload,
				      length);
	}
	r->used += n;
}

/* One event into the file and the metrics. */
static void put_event(struct recorder *r, const struct session_event *ev,
		      const char *text)
{
	unsigned char payload[sizeof(*ev) + EVENT_TEXT];
	size_t n = strnlen(text, EVENT_TEXT);

	memcpy(payload, ev, sizeof(*ev));
	memcpy(payload + sizeof(*ev), text, n);
	put_frame(r, SESSION_FRAME_EVENT, payload,
		  (uint32_t)(sizeof(*ev) + n));
	metrics_event(r->metrics, ev, text);
}

static void state_event(struct recorder *r, const struct session_record *rec)
{
	struct session_event ev = {
		.stamp_ns = rec->stamp_ns, .kind = SESSION_EVENT_STATE,
		.axis = -1, .value = rec->state,
	};

	put_event(r, &ev, names_state(rec->state));
}

/* A newly latched fault: its cause from the published state, in words. */
static void fault_event(struct recorder *r, const struct session_record *rec,
			uint32_t bit)
{
	struct session_event ev = {
		.stamp_ns = rec->stamp_ns, .kind = SESSION_EVENT_FAULT,
		.axis = -1, .detail = (uint32_t)__builtin_ctz(bit),
	};
	char text[EVENT_TEXT];
	struct endosim_state st;

	snprintf(text, sizeof(text), "%s", names_fault(bit));
	if (!publish_read(r->pub, &st) && (st.fault_bits & bit)) {
		const struct endosim_fault_cause *c =
			&st.safety.cause[ev.detail];

		ev.axis = c->axis;
		ev.value = c->value;
		faults_format(r->rig, r->daemon_start_ns, bit, c, text,
			      sizeof(text));
	}
	put_event(r, &ev, text);
}

/* The guidance's new phase, as a NOTE: "guide: fading at 12.34 s of the
 * recording", then "guide: taken-over at ..." (or "off": it ended). */
static void guide_event(struct recorder *r, const struct session_record *rec)
{
	struct session_event ev = {
		.stamp_ns = rec->stamp_ns, .kind = SESSION_EVENT_NOTE,
		.axis = -1, .value = rec->guide_phase,
	};
	char text[EVENT_TEXT];

	snprintf(text, sizeof(text), "guide: %s at %.2f s of the recording",
		 names_guide_phase(rec->guide_phase),
		 (double)rec->guide_time_s);
	put_event(r, &ev, text);
}

/* The patient before a session's first record: none, nothing held. */
static const struct session_record no_patient = {
	.hand_site = -1, .burst_segment = -1, .torn_segment = -1,
	.sedation = UINT32_MAX,
};

static void patient_event(struct recorder *r, const struct session_record *rec,
			  struct session_event ev, const char *text)
{
	ev.stamp_ns = rec->stamp_ns;
	put_event(r, &ev, text);
}

/* A turn started, or the patient settled (or first seen settled). */
static void position_event(struct recorder *r,
			   const struct session_record *rec,
			   const struct session_record *was)
{
	bool moved = rec->patient_position != was->patient_position;
	bool started = rec->patient_turning &&
		       (!was->patient_turning || moved);
	bool settled = !rec->patient_turning &&
		       (was->patient_turning || moved || !was->patient);
	char text[EVENT_TEXT];

	if (!rec->patient || (!started && !settled)) {
		return;
	}
	snprintf(text, sizeof(text), "%s %s", started ? "turning to" :
		 "settled", names_position(rec->patient_position));
	patient_event(r, rec, (struct session_event){
		.kind = SESSION_EVENT_POSITION, .axis = -1,
		.detail = started, .value = rec->patient_position }, text);
}

/* The assistant pressed (at another site, with another force) or let go. */
static void hand_event(struct recorder *r, const struct session_record *rec,
		       const struct session_record *was)
{
	const struct anatomy *a = r->colon ? colon_anatomy(r->colon) : NULL;
	int site = rec->hand_site;
	char text[EVENT_TEXT];

	if (site == was->hand_site &&
	    (site < 0 || rec->hand_n == was->hand_n)) {
		return;
	}
	if (site < 0) {
		snprintf(text, sizeof(text), "released");
	} else if (a && site < a->sites) {
		snprintf(text, sizeof(text), "pressed at %s, %.0f N",
			 a->site[site].name, (double)rec->hand_n);
	} else {
		snprintf(text, sizeof(text), "pressed at site %d, %.0f N", site,
			 (double)rec->hand_n);
	}
	patient_event(r, rec, (struct session_event){
		.kind = SESSION_EVENT_HAND, .axis = site < 0 ? -1 : site,
		.detail = site >= 0, .value = site < 0 ? 0 : rec->hand_n },
		text);
}

/* Each valve pressed or let go. */
static void valve_events(struct recorder *r, const struct session_record *rec,
			 const struct session_record *was)
{
	uint32_t changed = rec->valves ^ was->valves;
	char text[EVENT_TEXT];

	for (uint32_t bit = 1; changed; bit <<= 1) {
		bool on = rec->valves & bit;

		if (!(changed & bit)) {
			continue;
		}
		changed &= ~bit;
		snprintf(text, sizeof(text), "%s %s", names_valves(bit),
			 on ? "on" : "off");
		patient_event(r, rec, (struct session_event){
			.kind = SESSION_EVENT_VALVE, .axis = -1, .detail = bit,
			.value = on }, text);
	}
}

/* A segment torn: the perforation, with the pressure that tore it. */
static void burst_event(struct recorder *r, const struct session_record *rec,
			const struct session_record *was)
{
	char text[EVENT_TEXT];

	if (rec->burst_segment < 0 || rec->burst_segment == was->burst_segment) {
		return;
	}
	snprintf(text, sizeof(text), "%s torn at %.1f mmHg",
		 anatomy_segment_name(rec->burst_segment),
		 rec->gas_pressure_pa / GAS_PA_PER_MMHG);
	patient_event(r, rec, (struct session_event){
		.kind = SESSION_EVENT_PERFORATION, .axis = -1,
		.detail = (uint32_t)rec->burst_segment,
		.value = rec->gas_pressure_pa }, text);
}

/* The tip tore the wall, pressing as hard as the wall's contact says. */
static void tear_event(struct recorder *r, const struct session_record *rec,
		       const struct session_record *was)
{
	double f = hypot(hypot(rec->f_static[0], rec->f_static[1]),
			 rec->f_static[2]);
	char text[EVENT_TEXT];

	if (rec->torn_segment < 0 || rec->torn_segment == was->torn_segment) {
		return;
	}
	if (rec->tool_events & ENDOSIM_TOOL_INJURY) {
		snprintf(text, sizeof(text), "%s torn by the snare's current",
			 anatomy_segment_name(rec->torn_segment));
	} else {
		snprintf(text, sizeof(text), "%s torn by the tip at %.1f N",
			 anatomy_segment_name(rec->torn_segment), f);
	}
	patient_event(r, rec, (struct session_event){
		.kind = SESSION_EVENT_TEAR, .axis = -1,
		.detail = (uint32_t)rec->torn_segment, .value = f }, text);
}

/* The patient sedated anew (or first seen). */
static void sedation_event(struct recorder *r,
			   const struct session_record *rec,
			   const struct session_record *was)
{
	char text[EVENT_TEXT];

	if (!rec->patient || rec->sedation == was->sedation) {
		return;
	}
	snprintf(text, sizeof(text), "sedation %s",
		 names_sedation(rec->sedation));
	patient_event(r, rec, (struct session_event){
		.kind = SESSION_EVENT_SEDATION, .axis = -1,
		.value = rec->sedation }, text);
}

/* A tool handed over (or first seen in hand). */
static void select_event(struct recorder *r, const struct session_record *rec,
			 const struct session_record *was)
{
	char text[EVENT_TEXT];

	if (rec->tool_kind == was->tool_kind &&
	    rec->tool_snare_m == was->tool_snare_m) {
		return;
	}
	if (rec->tool_kind == ENDOSIM_TOOL_SNARE) {
		snprintf(text, sizeof(text), "a %.0f mm snare handed over",
			 rec->tool_snare_m * 1e3);
	} else {
		snprintf(text, sizeof(text), "%s handed over",
			 names_tool(rec->tool_kind));
	}
	patient_event(r, rec, (struct session_event){
		.kind = SESSION_EVENT_TOOL, .axis = (int32_t)rec->tool_kind,
		.value = rec->tool_snare_m }, text);
}

#define BLEED_BITS (ENDOSIM_TOOL_BLEED | ENDOSIM_TOOL_CLIPPED | \
		    ENDOSIM_TOOL_STOPPED)

/* Each of the tool's events in this record's cycle: a bleeding's with
 * the points' flow after it, the others with the handle's opening. */
static void tool_events(struct recorder *r, const struct session_record *rec)
{
	int polyp = rec->tool_event_polyp;
	char text[EVENT_TEXT], flow[32] = "";

	for (uint32_t bit = 1, left = rec->tool_events; left; bit <<= 1) {
		bool bleed = bit & BLEED_BITS;

		if (!(left & bit)) {
			continue;
		}
		left &= ~bit;
		if (bleed) {
			snprintf(flow, sizeof(flow), " (%.1f mL/min bleeding)",
				 rec->tool_bleed_m3_s *
					 ENDOSIM_ML_PER_MIN_PER_M3_S);
		}
		if (polyp >= 0) {
			snprintf(text, sizeof(text), "%s, polyp %d%s",
				 names_tool_event(bit), polyp,
				 bleed ? flow : "");
		} else {
			snprintf(text, sizeof(text), "%s",
				 names_tool_event(bit));
		}
		patient_event(r, rec, (struct session_event){
			.kind = SESSION_EVENT_TOOL, .axis = polyp,
			.detail = bit,
			.value = bleed ? rec->tool_bleed_m3_s
				       : rec->tool_opening }, text);
	}
}

/* The patient's and the tool's events from the change since the last
 * record. */
static void patient_events(struct recorder *r, const struct session_record *rec)
{
	const struct session_record *was = r->seen_record ? &r->last
							  : &no_patient;

	position_event(r, rec, was);
	hand_event(r, rec, was);
	valve_events(r, rec, was);
	burst_event(r, rec, was);
	tear_event(r, rec, was);
	sedation_event(r, rec, was);
	select_event(r, rec, was);
	tool_events(r, rec);
}

/* STATE, FAULT, guidance and the patient's events from the change between
 * records. */
static void derive_events(struct recorder *r, const struct session_record *rec)
{
	uint32_t added = rec->fault_bits & ~r->last_faults;

	if (!r->seen_record || rec->state != r->last_state) {
		state_event(r, rec);
	}
	for (uint32_t k = 0; added; k++) {
		if (added & 1u << k) {
			fault_event(r, rec, 1u << k);
			added &= ~(1u << k);
		}
	}
	if (r->seen_record && rec->guide_phase != r->last_guide) {
		guide_event(r, rec);
	}
	patient_events(r, rec);
	r->seen_record = true;
	r->last_guide = rec->guide_phase;
	r->last_state = rec->state;
	r->last_faults = rec->fault_bits;
}

static void drops_event(struct recorder *r)
{
	uint64_t d = atomic_load_explicit(&r->tap.drops, memory_order_relaxed);
	uint64_t shapes = atomic_load_explicit(&r->tap.shape_drops,
					       memory_order_relaxed);
	struct session_event ev = {
		.stamp_ns = mono_ns(), .kind = SESSION_EVENT_DROPS,
		.axis = -1, .value = (double)d,
	};
	static struct log_ratelimit rl = LOG_RATELIMIT_INIT(10, 1);

	if (d == r->drops_written) {
		return;
	}
	log_ratelimited(&rl, LOG_WARNING, "session %" PRIu64 ": the disk is "
			"too slow: %" PRIu64 " records (and %" PRIu64
			" shapes) dropped so far", r->info.id, d, shapes);
	r->drops_written = d;
	put_event(r, &ev, "");
}

static void param_events(struct recorder *r)
{
	size_t n;

	pthread_mutex_lock(&r->lock);
	n = r->n_params;
	memcpy(r->batch, r->params, n * sizeof(r->params[0]));
	r->n_params = 0;
	pthread_mutex_unlock(&r->lock);
	for (size_t i = 0; i < n; i++) {
		struct session_event ev = {
			.stamp_ns = r->batch[i].stamp_ns,
			.kind = SESSION_EVENT_PARAM, .axis = -1,
		};

		put_event(r, &ev, r->batch[i].text);
	}
}

static void snapshot(struct recorder *r)
{
	pthread_mutex_lock(&r->lock);
	metrics_result(r->metrics, &r->info.metrics);
	r->info.records = r->records;
	r->info.drops = atomic_load(&r->tap.drops);
	r->info.bytes = r->bytes + 8;
	pthread_mutex_unlock(&r->lock);
	r->last_snapshot_ns = mono_ns();
}

/* The live map: made outside the lock, copied in under it. */
static void map_snapshot(struct recorder *r, uint64_t now)
{
	struct recorder_map *m = &r->next;

	metrics_map(r->metrics, &r->floats);
	livemap_quantise(&r->floats, m->cells);
	m->id = r->info.id;
	m->length_m = r->floats.length_m;
	m->tip_s_m = r->seen_record ? r->last.tip_s_m : 0;
	m->time_s = r->seen_record
			    ? (double)(r->last.stamp_ns - r->first_stamp_ns) /
				      ENDOSIM_NS_PER_S
			    : 0;
	pthread_mutex_lock(&r->lock);
	/* the share and the polyps as snapshot() last put them (100 ms) */
	m->mucosa_seen = r->info.metrics.mucosa_seen;
	m->polyps_found_mask = r->info.metrics.polyps_seen_mask;
	r->map = *m;
	r->map_ready = true;
	pthread_mutex_unlock(&r->lock);
	r->last_map_ns = now;
}

/* The map's first of a session, or its next. */
static bool map_due(const struct recorder *r, uint64_t now)
{
	return !r->last_map_ns ||
	       now - r->last_map_ns >=
		       (uint64_t)(RECORDER_MAP_S * ENDOSIM_NS_PER_S);
}

/*
 * What the ring holds, into the buffer; written when due. At most a
 * ring's worth a call: on a disk slower than the loop the ring fills
 * again while a full buffer is written, and the live status (snapshot())
 * must not wait for a drain that never ends.
 */
static void drain(struct recorder *r)
{
	size_t left = r->tap.ring.mask + 1;
	struct session_record rec;
	uint64_t now;

	param_events(r);
	while (left-- && spsc_pop(&r->tap.ring, &rec)) {
		if (!r->seen_record) {
			r->first_stamp_ns = rec.stamp_ns;
		}
		derive_events(r, &rec);
		metrics_record(r->metrics, &rec);
		put_frame(r, SESSION_FRAME_RECORD, &rec, sizeof(rec));
		r->records++;
		r->last = rec;
	}
	/* after their records, or those of the next drain */
	while (spsc_pop(&r->tap.shapes, &r->shape)) {
		put_frame(r, SESSION_FRAME_SHAPE, r->payload,
			  session_shape_pack(&r->shape, r->payload));
	}
	drops_event(r);
	now = mono_ns();
	if (r->used >= FLUSH_BYTES || now - r->last_write_ns >= FLUSH_NS) {
		flush(r);
	}
	if (now - r->last_snapshot_ns >= SNAPSHOT_NS) {
		snapshot(r);
	}
	if (map_due(r, now)) {
		map_snapshot(r, now);
	}
}

/* ------------------------------------------------------------ stopping */

/* Waits until the loop is past any push begun before recording fell. */
static void quiesce(struct recorder *r)
{
	uint64_t pass = atomic_load_explicit(&r->tap.passes,
					     memory_order_acquire);
	uint64_t deadline = mono_ns() + 100000000ull;

	while (atomic_load_explicit(&r->tap.passes, memory_order_acquire) <
		       pass + 2 && mono_ns() < deadline) {
		nap_ns(r->period_ns);
	}
}

/* The END frame, fsync, close. Returns 0 or -EIO. */
static int finish(struct recorder *r)
{
	struct metrics_result *res = &r->info.metrics;
	char *text = malloc(65536);
	int n, e = 0;

	atomic_store_explicit(&r->tap.recording, false, memory_order_release);
	quiesce(r);
	drain(r);
	metrics_result(r->metrics, res);
	n = text ? metricstext_format(res, text, 65536) : -ENOMEM;
	if (n >= 0) {
		put_frame(r, SESSION_FRAME_END, text, (uint32_t)n);
	}
	flush(r);
	if (r->fd < 0 || n < 0 || fsync(r->fd) < 0) {
		log_err("session %" PRIu64 ": %s could not be finished",
			r->info.id, r->info.path);
		e = -EIO;
	}
	if (r->fd >= 0) {
		close(r->fd);
		r->fd = -1;
	}
	free(text);
	metrics_destroy(r->metrics);
	r->metrics = NULL;
	return e;
}

/* Under the lock: the session as it ended, for the control thread. */
static void ended(struct recorder *r, int result)
{
	r->info.recording = false;
	r->info.end_ns = mono_ns();
	r->info.records = r->records;
	r->info.drops = atomic_load(&r->tap.drops);
	r->info.bytes = r->bytes + 8;
	r->info.checksum = r->sum;
	r->info.checksum_known = r->sum_ok && !result;
	r->stop_result = result;
	r->phase = PHASE_IDLE;
	pthread_cond_broadcast(&r->changed);
}

static void *recorder_main(void *arg)
{
	struct recorder *r = arg;

	pthread_mutex_lock(&r->lock);
	while (!r->quit) {
		enum phase p = r->phase;

		pthread_mutex_unlock(&r->lock);
		if (p == PHASE_RECORDING) {
			drain(r);
		}
		if (p == PHASE_STOPPING) {
			int e = finish(r);

			pthread_mutex_lock(&r->lock);
			ended(r, e);
			continue;
		}
		nap_ns(IDLE_NAP_NS);
		pthread_mutex_lock(&r->lock);
	}
	pthread_mutex_unlock(&r->lock);
	return NULL;
}

/* ------------------------------------------------------------ starting */

static void utc_now(char *buf, size_t size)
{
	time_t t = time(NULL);
	struct tm tm;

	gmtime_r(&t, &tm);
	strftime(buf, size, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* Creates DIR/ID.endoses for the next free ID. Returns the fd or -errno. */
static int create_file(struct recorder *r, struct recorder_info *info)
{
	int fd = -EEXIST, e;

	for (int tries = 0; tries < 16 && fd == -EEXIST; tries++) {
		e = sessiondir_next_id(r->dir, &info->id);
		if (!e) {
			e = sessiondir_path(r->dir, info->id, info->path,
					    sizeof(info->path));
		}
		if (e) {
			return e;
		}
		fd = open(info->path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC,
			  0640);
		fd = fd < 0 ? -errno : fd;
	}
	if (fd >= 0 && fchmod(fd, 0640) < 0) {
		log_warn("%s: chmod 0640: %m", info->path);
	}
	return fd;
}

static int header_text(const struct recorder_session *s,
		       const struct recorder_info *info, char *buf,
		       size_t size)
{
	const struct session_header h = {
		.id = info->id, .trainee = s->trainee,
		.case_name = s->case_name, .started = info->started,
		.start_ns = info->start_ns, .period_ns = s->period_ns,
		.version = ENDOSIM_VERSION, .step_m = s->step_m,
		.ring_vertices = s->ring_vertices, .segment_m = s->segment_m,
	};

	return session_header_text(&h, buf, size);
}

/* The first frames, straight to the file. */
static int write_head(int fd, const struct recorder_session *s,
		      const struct recorder_info *info)
{
	char header[HEADER_BYTES];
	int n = header_text(s, info, header, sizeof(header));
	int e = n < 0 ? n : session_file_write_magic(fd);

	if (!e) {
		e = session_file_write_frame(fd, SESSION_FRAME_HEADER, header,
					     (uint32_t)n);
	}
	if (!e) {
		e = session_file_write_frame(fd, SESSION_FRAME_CONFIG,
					     s->config_text,
					     (uint32_t)strlen(s->config_text));
	}
	if (!e) {
		e = session_file_write_frame(fd, SESSION_FRAME_CASE,
					     s->case_text,
					     (uint32_t)strlen(s->case_text));
	}
	return e;
}

/* The recorder thread's state for a new session (it is idle now). */
static int arm(struct recorder *r, int fd, const struct recorder_session *s,
	       uint64_t head_bytes, uint64_t head_sum)
{
	r->metrics = metrics_create(s->colon, &r->mp);
	if (!r->metrics) {
		return -ENOMEM;
	}
	r->fd = fd;
	r->colon = s->colon;
	r->used = 0;
	r->records = 0;
	r->bytes = head_bytes - 8; /* info.bytes adds the magic back */
	r->sum = head_sum;
	r->sum_ok = true;
	r->drops_written = 0;
	r->seen_record = false;
	r->last_faults = 0;
	r->throttle_t0_ns = r->last_write_ns = r->last_snapshot_ns =
		mono_ns();
	r->throttle_bytes = 0;
	r->last_map_ns = 0; /* the first drain makes the first map */
	r->n_params = 0;
	atomic_store(&r->tap.drops, 0);
	atomic_store(&r->tap.shape_drops, 0);
	return 0;
}

int recorder_start(struct recorder *r, const struct recorder_session *s,
		   struct recorder_info *info)
{
	struct recorder_info in = { .active = true, .recording = true };
	struct stat st;
	uint64_t head_sum = 0;
	int fd, e;

	pthread_mutex_lock(&r->lock);
	e = r->phase != PHASE_IDLE ? -EBUSY : 0;
	pthread_mutex_unlock(&r->lock);
	if (e) {
		return e;
	}
	fd = sessiondir_prepare(r->dir);
	if (fd == 0) {
		fd = create_file(r, &in);
	}
	if (fd < 0) {
		log_err("session: cannot create a file in %s: %s", r->dir,
			strerror(-fd));
		return fd;
	}
	snprintf(in.trainee, sizeof(in.trainee), "%s", s->trainee);
	snprintf(in.case_name, sizeof(in.case_name), "%s", s->case_name);
	utc_now(in.started, sizeof(in.started));
	in.start_ns = mono_ns();
	e = write_head(fd, s, &in);
	if (!e && fstat(fd, &st) < 0) {
		e = -errno;
	}
	if (!e) { /* the head, small, read back: the file's sum starts there */
		e = records_file_checksum(in.path, &head_sum);
	}
	if (!e) {
		e = arm(r, fd, s, (uint64_t)st.st_size, head_sum);
	}
	if (e) {
		log_err("session %" PRIu64 ": %s: %s", in.id, in.path,
			strerror(-e));
		close(fd);
		unlink(in.path);
		return e;
	}
	pthread_mutex_lock(&r->lock);
	r->info = in;
	r->map_ready = false;
	r->info.bytes = (uint64_t)st.st_size;
	r->phase = PHASE_RECORDING;
	atomic_store_explicit(&r->tap.recording, true, memory_order_release);
	*info = r->info;
	pthread_mutex_unlock(&r->lock);
	return 0;
}

int recorder_stop(struct recorder *r, struct recorder_info *info)
{
	int e;

	pthread_mutex_lock(&r->lock);
	if (r->phase != PHASE_RECORDING) {
		pthread_mutex_unlock(&r->lock);
		return -ENOENT;
	}
	r->phase = PHASE_STOPPING;
	while (r->phase != PHASE_IDLE) {
		pthread_cond_wait(&r->changed, &r->lock);
	}
	e = r->stop_result;
	*info = r->info;
	pthread_mutex_unlock(&r->lock);
	return e;
}

void recorder_info(struct recorder *r, struct recorder_info *info)
{
	pthread_mutex_lock(&r->lock);
	*info = r->info;
	info->drops = r->phase == PHASE_RECORDING ?
			      atomic_load(&r->tap.drops) : r->info.drops;
	pthread_mutex_unlock(&r->lock);
}

int recorder_map(struct recorder *r, struct recorder_map *out)
{
	int e;

	pthread_mutex_lock(&r->lock);
	e = r->phase != PHASE_RECORDING ? -ENOENT :
	    !r->map_ready ? -EAGAIN : 0;
	if (!e) {
		*out = r->map;
	}
	pthread_mutex_unlock(&r->lock);
	return e;
}

void recorder_param(struct recorder *r, const char *key, const char *value)
{
	pthread_mutex_lock(&r->lock);
	if (r->phase == PHASE_RECORDING && r->n_params < PARAMS) {
		struct param *p = &r->params[r->n_params++];

		p->stamp_ns = mono_ns();
		snprintf(p->text, sizeof(p->text), "%s=%s", key, value);
	}
	pthread_mutex_unlock(&r->lock);
}

/* ------------------------------------------------------------ life */

struct recorder *recorder_create(const struct config *cfg, struct rig *rig,
				 struct publish *pub, uint64_t start_ns)
{
	struct recorder *r = calloc(1, sizeof(*r));
	size_t cycles = (size_t)ceil(cfg->session.ring_s * cfg->loop.rate_hz);
	uint32_t period = 1000000000u / (unsigned)cfg->loop.rate_hz;
	uint32_t every = session_shape_every(period);
	int e;

	if (!r || !(r->buf = malloc(BUF_BYTES)) ||
	    spsc_init(&r->tap.ring, cycles, sizeof(struct session_record)) ||
	    spsc_init(&r->tap.shapes, cycles / every + 1,
		      sizeof(struct session_shape))) {
		log_err("recorder: out of memory");
		recorder_destroy(r);
		return NULL;
	}
	r->tap.shape_every = every;
	/* touched now, so that the loop's first pushes do not fault pages */
	memset(r->tap.ring.records, 0, (r->tap.ring.mask + 1) *
	       sizeof(struct session_record));
	memset(r->tap.shapes.records, 0, (r->tap.shapes.mask + 1) *
	       sizeof(struct session_shape));
	memset(&r->tap.shape, 0, sizeof(r->tap.shape));
	/* the rig works without it: only `session start` will be refused */
	e = sessiondir_prepare(cfg->session.directory);
	if (e) {
		log_warn("[session] directory %s: cannot create: %s: no "
			 "session can be recorded until it can",
			 cfg->session.directory, strerror(-e));
	}
	snprintf(r->dir, sizeof(r->dir), "%s", cfg->session.directory);
	r->write_limit = cfg->session.write_limit_bytes_per_s;
	sessioninputs_metrics_params(cfg, &r->mp);
	r->rig = rig;
	r->pub = pub;
	r->daemon_start_ns = start_ns;
	r->period_ns = period;
	r->fd = -1;
	pthread_mutex_init(&r->lock, NULL);
	pthread_cond_init(&r->changed, NULL);
	if (r->write_limit > 0) {
		log_warn("[session] write_limit_bytes_per_s = %g: sessions are "
			 "written as if to a slow disk (a test setting)",
			 r->write_limit);
	}
	return r;
}

struct session_tap *recorder_tap(struct recorder *r)
{
	return &r->tap;
}

int recorder_run(struct recorder *r)
{
	int e;

	e = pthread_create(&r->thread, NULL, recorder_main, r);
	if (e) {
		log_err("recorder: cannot start thread: %s", strerror(e));
		return -e;
	}
	pthread_setname_np(r->thread, "endosim-rec");
	r->running = true;
	return 0;
}

void recorder_destroy(struct recorder *r)
{
	struct recorder_info info;

	if (!r) {
		return;
	}
	if (r->running) {
		if (!recorder_stop(r, &info)) {
			log_notice("session %" PRIu64 " stopped: %s, %" PRIu64
				   " records", info.id, info.path,
				   info.records);
		}
		pthread_mutex_lock(&r->lock);
		r->quit = true;
		pthread_mutex_unlock(&r->lock);
		pthread_join(r->thread, NULL);
		pthread_mutex_destroy(&r->lock);
		pthread_cond_destroy(&r->changed);
	}
	spsc_free(&r->tap.ring);
	spsc_free(&r->tap.shapes);
	free(r->buf);
	free(r);
}
