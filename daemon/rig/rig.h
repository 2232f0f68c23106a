/*
 * rig.h - the force loop's view of the rig: four axes, each with feedback
 * in and a force or torque setpoint out, behind a table of functions that
 * every backend implements (the simulated rig; the drive backends).
 *
 * Contract of the table:
 *  - start: opens and checks the devices; may block; called once from the
 *    main thread before the force loop runs. Returns 0 or a negative errno,
 *    having logged what it looked for and why it failed.
 *  - read, write: called by the force loop every cycle; never block,
 *    allocate, print or do bus I/O themselves (bus backends exchange through
 *    mailboxes with their bus threads).
 *  - stop: torque to zero and drives disabled; called once after the force
 *    loop has ended; may block.
 *  - bus_stats: any thread: the exchange rate and latencies of bus INDEX
 *    (0, 1, ...); -ENOENT past the last (the simulated rig has none).
 *  - describe: any thread but the force loop: which device a fault (its
 *    bit, axis and detail as the loop reported them) concerns and why, in
 *    words, for the log line and `endoctl status`.
 *  - destroy: frees; NULL-safe through rig_destroy().
 *
 * Units: SI (m, rad, N, N m); backends convert counts and per-mille in one
 * place each.
 */
#ifndef ENDOSIM_RIG_H
#define ENDOSIM_RIG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "conf/config.h"
#include "rig/hand.h"
#include "base/histo.h"

struct rig_axis_feedback {
	double position;       /* m or rad */
	double velocity;       /* m/s or rad/s */
	double hand;           /* N or N m: simulated hand, 0 on real drives */
	uint64_t stamp_ns;     /* CLOCK_MONOTONIC of the sample */
	uint32_t status;       /* enum endosim_drive_status bits */
	uint32_t fault_detail; /* backend's code when status has FAULT */
};

struct rig_feedback {
	struct rig_axis_feedback axis[ENDOSIM_AXES];
	double hand_time_s;    /* simulated hand: time into the scenario */
	bool hand_done;        /* simulated hand: scenario ended */
	uint32_t valves;       /* the handle's (enum endosim_valve): pressed
				  or covered; a stale or lost input reads
				  released (0) */
	double tool_depth_m;   /* the tool in the working channel (tool.h):
				  its depth beyond the exit, m; */
	double tool_opening;   /* its handle, 0 closed .. 1 open; a stale
				  or lost input reads non-finite (the tool
				  and the handle still) */
	bool tool_pedal;       /* the cautery's pedal; stale or lost: up */
	struct scenario_patient patient; /* simulated hand: the scenario's
				  latest command for the assistant, a new
				  number at most once a cycle (hand_patient());
				  seq 0: none */
};

/* What one bus thread achieves (bus.h). */
struct rig_bus_stats {
	const char *name;              /* the bus, as in the log */
	uint64_t exchanges;            /* cycles: setpoints out, feedback in */
	double rate_hz;                /* exchanges per second since start */
	struct histo_summary exchange; /* one exchange, all its transactions */
	struct histo_summary txn;      /* one request and its reply */
	bool fifo;                     /* the thread runs SCHED_FIFO */
};

struct rig;

struct rig_ops {
	const char *name;
	int (*start)(struct rig *rig);
	void (*read)(struct rig *rig, uint64_t now_ns, struct rig_feedback *fb);
	void (*write)(struct rig *rig, uint64_t now_ns,
		      const double setpoint[ENDOSIM_AXES], bool enable);
	void (*stop)(struct rig *rig);
	int (*bus_stats)(struct rig *rig, int index, struct rig_bus_stats *st);
	void (*describe)(struct rig *rig, uint32_t fault_bit, int axis,
			 uint32_t detail, char *buf, size_t size);
	void (*destroy)(struct rig *rig);
};

/* Backends start their private struct with this. */
struct rig {
	const struct rig_ops *ops;
};

/* The backends, each created by its own header: rig_sim.h, rig_drives.h. */

static inline int rig_start(struct rig *rig)
{
	return rig->ops->start(rig);
}

static inline void rig_read(struct rig *rig, uint64_t now_ns,
			    struct rig_feedback *fb)
{
	rig->ops->read(rig, now_ns, fb);
}

static inline void rig_write(struct rig *rig, uint64_t now_ns,
			     const double setpoint[ENDOSIM_AXES], bool enable)
{
	rig->ops->write(rig, now_ns, setpoint, enable);
}

static inline void rig_stop(struct rig *rig)
{
	rig->ops->stop(rig);
}

static inline const char *rig_name(const struct rig *rig)
{
	return rig->ops->name;
}

static inline int rig_bus_stats(struct rig *rig, int index,
				struct rig_bus_stats *st)
{
	return rig->ops->bus_stats(rig, index, st);
}

static inline void rig_describe(struct rig *rig, uint32_t fault_bit,
				int axis, uint32_t detail, char *buf,
				size_t size)
{
	rig->ops->describe(rig, fault_bit, axis, detail, buf, size);
}

void rig_destroy(struct rig *rig);

#endif
