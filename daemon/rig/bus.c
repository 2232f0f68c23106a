/* bus.c - see bus.h. */
#include "rig/bus.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "proto/names.h"
#include "proto/seqlock.h"
#include "base/log.h"
#include "base/mono.h"
#include "base/rt.h"

#define DISCONNECTED_TICK_NS 20000000ull /* publish while a device is away */
#define CLEAR_FAULT_EVERY_NS 500000000ull
#define START_WAIT_NS 2000000000ull
#define CMD_TRIES 100
#define STACK_BYTES (256 * 1024) /* locked with the rest: keep it small */

/* Loop to bus: the newest command. */
struct bus_cmd {
	uint64_t stamp_ns;             /* the loop's cycle that posted it */
	double setpoint[ENDOSIM_AXES]; /* N or N m, by rig axis */
	bool enable;
	uint32_t enable_gen;           /* rising edges of enable so far */
	uint32_t fault_ack;            /* the newest fault_seq the loop read */
};

/* Bus to loop: the newest feedback. */
struct bus_fb {
	struct rig_axis_feedback drive[DRIVE_MAX]; /* by drive index */
	uint32_t valves[DRIVE_MAX]; /* pressed, read at drive[i].stamp_ns */
	struct drive_tool tool[DRIVE_MAX]; /* the tool, read then */
	uint32_t fault_seq;                        /* latched faults so far */
};

/* What can be latched on a drive, each with its own words. */
enum latch_kind {
	LATCH_GONE,   /* the device vanished: PRESENT cleared */
	LATCH_BUS,    /* a transaction failed: ENDOSIM_DRIVE_BUS_ERROR */
	LATCH_FAULT,  /* the drive faulted: ENDOSIM_DRIVE_FAULT */
	LATCHES,
};

/* What the bus thread keeps of each drive. */
struct bus_drive {
	bool up;             /* bring_up() completed: torque follows */
	bool rising;         /* bring_up() under way */
	uint32_t latched;    /* 1 << enum latch_kind */
	uint32_t detail[LATCHES]; /* errno, drive code */
	struct drive_sample sample;
};

struct bus {
	struct drive *d;
	struct bus_params p;
	pthread_t thread;
	bool running;
	bool fifo;
	_Atomic bool stop;

	/* loop -> bus, and the loop's own bookkeeping */
	seqlock_t cmd_lock;
	struct bus_cmd cmd_box;
	bool loop_enable;
	uint32_t loop_gen;
	uint32_t loop_seen_seq;
	struct bus_fb loop_fb;      /* the loop's last good copy */

	/* bus -> loop */
	seqlock_t fb_lock;
	struct bus_fb fb_box;

	/* bus -> other threads: each latched cause in words */
	seqlock_t note_lock;
	char note[DRIVE_MAX][LATCHES][384];

	/* the bus thread's own */
	struct bus_cmd cmd;
	struct bus_drive dr[DRIVE_MAX];
	bool connected;
	bool sample_ok;             /* the last exchange succeeded */
	uint64_t stamp_ns;          /* when the newest feedback was taken */
	uint64_t next_open_ns;
	uint64_t next_clear_ns;
	uint32_t fault_seq;
	uint32_t blocked_gen;       /* no bring-up before enable rises anew */

	/* statistics (bus thread writes) */
	struct histo exchange_h;
	struct histo txn_h;
	_Atomic uint64_t exchanges;
	uint64_t start_ns;
};

struct bus *bus_create(struct drive *d, const struct bus_params *p)
{
	struct bus *b = calloc(1, sizeof(*b));

	if (!b) {
		log_err("%s: out of memory", d->name);
		d->ops->destroy(d);
		return NULL;
	}
	b->d = d;
	b->p = *p;
	d->txn = &b->txn_h;
	seqlock_init(&b->cmd_lock);
	seqlock_init(&b->fb_lock);
	seqlock_init(&b->note_lock);
	return b;
}

void bus_destroy(struct bus *b)
{
	if (!b) {
		return;
	}
	bus_stop(b);
	b->d->ops->destroy(b->d);
	free(b);
}

const char *bus_name(const struct bus *b)
{
	return b->d->name;
}

bool bus_has_axis(const struct bus *b, int axis)
{
	for (int i = 0; i < b->d->n; i++) {
		if (b->d->axis[i] == axis) {
			return true;
		}
	}
	return false;
}

int bus_open(struct bus *b)
{
	int r = b->d->ops->open(b->d);

	if (r) {
		log_err("%s: %s", b->d->name, b->d->why);
		return r;
	}
	b->connected = true;
	return 0;
}

/* --- the bus thread ------------------------------------------------- */

static void take_command(struct bus *b)
{
	for (int tries = 0; tries < CMD_TRIES; tries++) {
		uint64_t seq = seqlock_read_begin(&b->cmd_lock);
		struct bus_cmd copy = b->cmd_box;

		if (!seqlock_read_retry(&b->cmd_lock, seq)) {
			b->cmd = copy;
			return;
		}
	}
}

static bool any_latch(const struct bus *b)
{
	for (int i = 0; i < b->d->n; i++) {
		if (b->dr[i].latched) {
			return true;
		}
	}
	return false;
}

/* Drives may produce torque: enabled anew since the last fault. */
static bool may_run(const struct bus *b)
{
	return b->cmd.enable && b->cmd.enable_gen != b->blocked_gen &&
	       !any_latch(b);
}

static void publish(struct bus *b);

static void write_note(struct bus *b, int i, int kind, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

static void write_note(struct bus *b, int i, int kind, const char *fmt, ...)
{
	char text[sizeof(b->note[0][0])];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(text, sizeof(text), fmt, ap);
	va_end(ap);
	seqlock_write_begin(&b->note_lock);
	memcpy(b->note[i][kind], text, sizeof(text));
	seqlock_write_end(&b->note_lock);
}

/*
 * Latches a fault of KIND on drive I (-1: every drive of the bus) with its
 * DETAIL and WHY in words (the first of each kind is kept), and tells the
 * loop at once.
 */
static void latch(struct bus *b, int i, enum latch_kind kind, uint32_t detail,
		  const char *why)
{
	for (int j = 0; j < b->d->n; j++) {
		struct bus_drive *dr = &b->dr[j];

		if ((i >= 0 && j != i) || (dr->latched & 1u << kind)) {
			continue;
		}
		write_note(b, j, kind, "%s %s: %s%s", b->d->name, b->d->unit[j],
			   kind == LATCH_GONE ? "device gone: " : "", why);
		dr->detail[kind] = detail;
		dr->latched |= 1u << kind;
	}
	b->fault_seq++;
	b->blocked_gen = b->cmd.enable_gen;
	/* the loop learns of it now, not after the drives are down */
	publish(b);
}

static void take_down(struct bus *b, int i)
{
	if (b->connected) {
		b->d->ops->bring_down(b->d, i);
	}
	b->dr[i].up = false;
	b->dr[i].rising = false;
}

/* Brings every drive down but SKIP (-1: none). */
static void take_all_down(struct bus *b, int skip)
{
	for (int i = 0; i < b->d->n; i++) {
		if (i == skip) {
			b->dr[i].up = false;
			b->dr[i].rising = false;
		} else {
			take_down(b, i);
		}
	}
}

/*
 * A failed operation: latch it, stop every drive, drop a lost device. A
 * drive that did not answer is not asked again: the bus would wait on it
 * while the others' feedback grows old (its own watchdog stops it).
 */
static void failed(struct bus *b, int err)
{
	int i = b->d->why_drive;

	if (err == -ENODEV) {
		latch(b, -1, LATCH_GONE, 0, b->d->why);
		b->d->ops->close(b->d);
		b->connected = false;
		b->sample_ok = false;
		b->next_open_ns =
			mono_ns() + (uint64_t)(BUS_REOPEN_S * ENDOSIM_NS_PER_S);
	} else {
		latch(b, i, LATCH_BUS, (uint32_t)-err, b->d->why);
	}
	take_all_down(b, err == -ETIMEDOUT ? i : -1);
}

static void step_up(struct bus *b, int i)
{
	int r = b->d->ops->bring_up(b->d, i);

	b->dr[i].rising = r > 0;
	b->dr[i].up = r == 0;
	if (r < 0) {
		failed(b, r);
	}
}

static void clear_faults(struct bus *b, int i)
{
	uint64_t now = mono_ns();

	if (now < b->next_clear_ns) {
		return;
	}
	b->next_clear_ns = now + CLEAR_FAULT_EVERY_NS;
	if (b->d->ops->clear_fault(b->d, i) == -ENODEV) {
		failed(b, -ENODEV);
	}
}

/* Brings drives up or down as the command says; clears drive faults. */
static void steer(struct bus *b)
{
	bool run = may_run(b);

	for (int i = 0; i < b->d->n && b->connected; i++) {
		struct bus_drive *dr = &b->dr[i];

		if (run && !dr->up) {
			step_up(b, i);
		} else if (!run && (dr->up || dr->rising)) {
			take_down(b, i);
		} else if (!run && b->sample_ok && dr->sample.fault) {
			clear_faults(b, i);
		}
	}
}

/* Latches what the drives report about themselves. */
static void check_drives(struct bus *b)
{
	char why[160];

	for (int i = 0; i < b->d->n; i++) {
		struct bus_drive *dr = &b->dr[i];

		if (dr->sample.fault && !(dr->latched & 1u << LATCH_FAULT)) {
			snprintf(why, sizeof(why), "drive fault 0x%04x (%s)",
				 dr->sample.code,
				 b->d->ops->describe_fault(dr->sample.code));
			latch(b, i, LATCH_FAULT, dr->sample.code, why);
			take_all_down(b, -1);
		} else if (dr->up && !dr->sample.enabled && !dr->sample.fault) {
			latch(b, i, LATCH_FAULT, 0,
			      "the drive stopped following torque by itself");
			take_all_down(b, -1);
		}
	}
}

/*
 * Commands the force loop stopped renewing (a stalled or dead loop) are
 * not followed: a bus error latched, every drive brought down at once.
 */
static void check_command_age(struct bus *b)
{
	uint64_t now = mono_ns();
	uint64_t max_age =
		(uint64_t)(b->p.feedback_max_age_s * ENDOSIM_NS_PER_S);
	char why[160];

	if (!b->cmd.enable || any_latch(b) || now <= b->cmd.stamp_ns ||
	    now - b->cmd.stamp_ns <= max_age) {
		return;
	}
	snprintf(why, sizeof(why), "no command from the force loop for %.0f "
		 "ms (limit %.0f ms): drives stopped",
		 (double)(now - b->cmd.stamp_ns) / ENDOSIM_NS_PER_MS,
		 (double)max_age / ENDOSIM_NS_PER_MS);
	latch(b, -1, LATCH_BUS, ETIME, why);
	take_all_down(b, -1);
}

static void exchange(struct bus *b)
{
	struct drive_sample sample[DRIVE_MAX];
	double setpoint[DRIVE_MAX];
	bool run = may_run(b);
	uint64_t t0 = mono_ns();
	int r;

	for (int i = 0; i < b->d->n; i++) {
		setpoint[i] = run && b->dr[i].up ? b->cmd.setpoint[b->d->axis[i]]
						 : 0.0;
	}
	r = b->d->ops->exchange(b->d, setpoint, sample);
	b->stamp_ns = mono_ns();
	histo_add(&b->exchange_h, b->stamp_ns - t0);
	atomic_fetch_add_explicit(&b->exchanges, 1, memory_order_relaxed);
	b->sample_ok = r == 0;
	if (r) {
		failed(b, r);
		return;
	}
	for (int i = 0; i < b->d->n; i++) {
		b->dr[i].sample = sample[i];
	}
	check_drives(b);
}

/* Releases latches the loop has seen, with torque off and the cause gone. */
static void settle(struct bus *b)
{
	if (b->cmd.fault_ack != b->fault_seq || b->cmd.enable ||
	    !b->connected || !b->sample_ok) {
		return;
	}
	for (int i = 0; i < b->d->n; i++) {
		if (!b->dr[i].sample.fault) {
			b->dr[i].latched = 0;
		}
	}
}

static void reopen(struct bus *b)
{
	uint64_t now = mono_ns();

	b->stamp_ns = now;
	if (now < b->next_open_ns) {
		return;
	}
	b->next_open_ns = now + (uint64_t)(BUS_REOPEN_S * ENDOSIM_NS_PER_S);
	if (b->d->ops->open(b->d) == 0) {
		b->connected = true;
		log_notice("%s: back; 'endoctl reset' clears the fault",
			   b->d->name);
	}
}

static bool has(const struct bus_drive *dr, enum latch_kind kind)
{
	return dr->latched & 1u << kind;
}

static uint32_t status_of(const struct bus *b, int i)
{
	const struct bus_drive *dr = &b->dr[i];
	uint32_t st = 0;

	if (b->connected && !has(dr, LATCH_GONE)) {
		st |= ENDOSIM_DRIVE_PRESENT;
	}
	if (b->sample_ok && dr->up && dr->sample.enabled) {
		st |= ENDOSIM_DRIVE_ENABLED;
	}
	if (has(dr, LATCH_FAULT) || (b->sample_ok && dr->sample.fault)) {
		st |= ENDOSIM_DRIVE_FAULT;
	}
	if (has(dr, LATCH_BUS)) {
		st |= ENDOSIM_DRIVE_BUS_ERROR;
	}
	return st;
}

/* The detail of what the status shows first, as safety.h checks it. */
static uint32_t detail_of(const struct bus *b, int i, uint32_t status)
{
	const struct bus_drive *dr = &b->dr[i];

	if (!(status & ENDOSIM_DRIVE_PRESENT)) {
		return dr->detail[LATCH_GONE];
	}
	if (status & ENDOSIM_DRIVE_FAULT) {
		return has(dr, LATCH_FAULT) ? dr->detail[LATCH_FAULT]
					    : dr->sample.code;
	}
	return status & ENDOSIM_DRIVE_BUS_ERROR ? dr->detail[LATCH_BUS] : 0;
}

static void publish(struct bus *b)
{
	const struct drive_tool still = { NAN, NAN, false };
	struct bus_fb fb = b->fb_box;

	for (int i = 0; i < b->d->n; i++) {
		struct rig_axis_feedback *f = &fb.drive[i];
		const struct bus_drive *dr = &b->dr[i];

		if (b->sample_ok) {
			f->position = dr->sample.position;
			f->velocity = dr->sample.velocity;
		}
		f->hand = 0.0;
		f->stamp_ns = b->stamp_ns;
		f->status = status_of(b, i);
		f->fault_detail = detail_of(b, i, f->status);
		/* what a failed exchange did not read is not pressed, the
		 * tool not moved */
		fb.valves[i] = b->sample_ok ? dr->sample.valves : 0;
		fb.tool[i] = b->sample_ok ? dr->sample.tool : still;
	}
	fb.fault_seq = b->fault_seq;
	seqlock_write_begin(&b->fb_lock);
	b->fb_box = fb;
	seqlock_write_end(&b->fb_lock);
}

/* Sleeps until the next period (or the next tick while disconnected). */
static uint64_t pace(struct bus *b, uint64_t next)
{
	uint64_t period =
		b->connected ? (uint64_t)(ENDOSIM_NS_PER_S / b->p.max_rate_hz)
			     : DISCONNECTED_TICK_NS;
	uint64_t now = mono_ns();
	struct timespec ts;

	next += period;
	if (next <= now) {
		return now; /* the bus is the limit: no debt carried */
	}
	ts.tv_sec = (time_t)(next / ENDOSIM_NS_PER_S);
	ts.tv_nsec = (long)(next % ENDOSIM_NS_PER_S);
	while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) ==
	       EINTR) {
	}
	return next;
}

static void *bus_main(void *arg)
{
	struct bus *b = arg;
	uint64_t next = mono_ns();

	while (!atomic_load_explicit(&b->stop, memory_order_acquire)) {
		take_command(b);
		check_command_age(b);
		if (b->connected) {
			steer(b);
		}
		if (b->connected) {
			exchange(b);
			settle(b);
		} else {
			reopen(b);
		}
		publish(b);
		next = pace(b, next);
	}
	take_all_down(b, -1);
	if (b->connected) {
		b->d->ops->close(b->d);
		b->connected = false;
	}
	return NULL;
}

/* --- the main thread ------------------------------------------------ */

static bool published(struct bus *b)
{
	return seqlock_read_begin(&b->fb_lock) >= 2;
}

int bus_start(struct bus *b)
{
	struct rt_thread_params p = {
		.name = "endosim-bus",
		.priority = b->p.priority,
		.cpu = -1,
		.stack_bytes = STACK_BYTES,
	};
	struct timespec nap = { .tv_nsec = 1000000 };
	uint64_t deadline;
	int r;

	b->start_ns = mono_ns();
	r = rt_thread_start(&b->thread, &p, bus_main, b, &b->fifo);
	if (r) {
		log_err("%s: cannot start the bus thread: %s", b->d->name,
			strerror(-r));
		return r;
	}
	b->running = true;
	deadline = mono_ns() + START_WAIT_NS;
	while (!published(b)) {
		if (mono_ns() > deadline) {
			log_err("%s: no feedback within %.0f s of start",
				b->d->name,
				(double)START_WAIT_NS / ENDOSIM_NS_PER_S);
			return -ETIMEDOUT;
		}
		nanosleep(&nap, NULL);
	}
	log_info("%s: bus thread %s priority %d, up to %g exchanges/s",
		 b->d->name, b->fifo ? "SCHED_FIFO" : "SCHED_OTHER",
		 b->fifo ? b->p.priority : 0, b->p.max_rate_hz);
	return 0;
}

void bus_stop(struct bus *b)
{
	struct rig_bus_stats st;

	if (!b->running) {
		if (b->connected) {
			b->d->ops->close(b->d);
			b->connected = false;
		}
		return;
	}
	atomic_store_explicit(&b->stop, true, memory_order_release);
	pthread_join(b->thread, NULL);
	b->running = false;
	bus_get_stats(b, &st);
	log_info("%s: %llu exchanges, %.0f/s; exchange p50 %.0f us, p99 %.0f "
		 "us", b->d->name, (unsigned long long)st.exchanges,
		 st.rate_hz, st.exchange.p50_us, st.exchange.p99_us);
}

/* --- the force loop ------------------------------------------------- */

/* What a drive read in the exchange that gave F counts at NOW_NS: F at
 * most MAX_AGE_NS old, its drive present, without a fault or a bus
 * error. */
static bool reading_fresh(const struct rig_axis_feedback *f, uint64_t now_ns,
			  uint64_t max_age_ns)
{
	const uint32_t bad = ENDOSIM_DRIVE_FAULT | ENDOSIM_DRIVE_BUS_ERROR;
	bool stale = now_ns > f->stamp_ns && now_ns - f->stamp_ns > max_age_ns;
	bool lost = !(f->status & ENDOSIM_DRIVE_PRESENT) || (f->status & bad);

	return !stale && !lost;
}

uint32_t bus_valves(uint32_t valves, uint32_t mapped, uint32_t pressed,
		    const struct rig_axis_feedback *f, uint64_t now_ns,
		    uint64_t max_age_ns)
{
	valves &= ~mapped;
	return reading_fresh(f, now_ns, max_age_ns)
		       ? valves | (pressed & mapped) : valves;
}

void bus_tool(struct rig_feedback *fb, uint32_t mapped,
	      const struct drive_tool *read,
	      const struct rig_axis_feedback *f, uint64_t now_ns,
	      uint64_t max_age_ns)
{
	bool fresh = reading_fresh(f, now_ns, max_age_ns);

	if (mapped & CONFIG_TOOL_DEPTH) {
		fb->tool_depth_m = fresh ? read->depth_m : NAN;
	}
	if (mapped & CONFIG_TOOL_OPENING) {
		fb->tool_opening = fresh ? read->opening : NAN;
	}
	if (mapped & CONFIG_TOOL_PEDAL) {
		fb->tool_pedal = fresh && read->pedal;
	}
}

void bus_fetch(struct bus *b, uint64_t now_ns, struct rig_feedback *fb)
{
	uint64_t seq = seqlock_read_begin(&b->fb_lock);
	struct bus_fb copy = b->fb_box;
	uint64_t max_age =
		(uint64_t)(b->p.feedback_max_age_s * ENDOSIM_NS_PER_S);

	if (!seqlock_read_retry(&b->fb_lock, seq)) {
		b->loop_fb = copy;
		b->loop_seen_seq = copy.fault_seq;
	}
	for (int i = 0; i < b->d->n; i++) {
		fb->axis[b->d->axis[i]] = b->loop_fb.drive[i];
		fb->valves = bus_valves(fb->valves, b->d->valves[i],
					b->loop_fb.valves[i],
					&b->loop_fb.drive[i], now_ns, max_age);
		bus_tool(fb, b->d->tool[i], &b->loop_fb.tool[i],
			 &b->loop_fb.drive[i], now_ns, max_age);
	}
}

void bus_post(struct bus *b, uint64_t now_ns,
	      const double setpoint[ENDOSIM_AXES], bool enable)
{
	struct bus_cmd cmd;

	if (enable && !b->loop_enable) {
		b->loop_gen++;
	}
	b->loop_enable = enable;
	memcpy(cmd.setpoint, setpoint, sizeof(cmd.setpoint));
	cmd.stamp_ns = now_ns;
	cmd.enable = enable;
	cmd.enable_gen = b->loop_gen;
	cmd.fault_ack = b->loop_seen_seq;
	seqlock_write_begin(&b->cmd_lock);
	b->cmd_box = cmd;
	seqlock_write_end(&b->cmd_lock);
}

/* --- any thread ----------------------------------------------------- */

static int drive_index(const struct bus *b, int axis)
{
	for (int i = 0; i < b->d->n; i++) {
		if (b->d->axis[i] == axis) {
			return i;
		}
	}
	return -1;
}

/* The latch whose words explain FAULT_BIT, or -1. */
static int kind_of(uint32_t fault_bit)
{
	switch (fault_bit) {
	case ENDOSIM_FAULT_DRIVE_GONE:
		return LATCH_GONE;
	case ENDOSIM_FAULT_BUS:
		return LATCH_BUS;
	case ENDOSIM_FAULT_DRIVE:
		return LATCH_FAULT;
	default:
		return -1;
	}
}

void bus_describe(struct bus *b, int axis, uint32_t fault_bit,
		  uint32_t detail, char *buf, size_t size)
{
	int i = drive_index(b, axis), kind = kind_of(fault_bit);
	uint64_t seq;

	if (fault_bit == ENDOSIM_FAULT_STALE && i >= 0) {
		snprintf(buf, size, "%s %s: no feedback for %u ms (limit %.0f "
			 "ms)", b->d->name, b->d->unit[i], detail,
			 b->p.feedback_max_age_s * 1e3);
		return;
	}
	if (i < 0 || kind < 0) {
		snprintf(buf, size, "%s%s%s", b->d->name, i < 0 ? "" : " ",
			 i < 0 ? "" : b->d->unit[i]);
		return;
	}
	do {
		seq = seqlock_read_begin(&b->note_lock);
		snprintf(buf, size, "%s", b->note[i][kind]);
	} while (seqlock_read_retry(&b->note_lock, seq));
}

void bus_get_stats(struct bus *b, struct rig_bus_stats *st)
{
	uint64_t now = mono_ns();

	memset(st, 0, sizeof(*st));
	st->name = b->d->name;
	st->exchanges = atomic_load_explicit(&b->exchanges,
					     memory_order_relaxed);
	if (b->start_ns && now > b->start_ns) {
		st->rate_hz = (double)st->exchanges * ENDOSIM_NS_PER_S /
			      (double)(now - b->start_ns);
	}
	histo_summarize(&b->exchange_h, &st->exchange);
	histo_summarize(&b->txn_h, &st->txn);
	st->fifo = b->fifo;
}
