/*
 * bus.h - one bus thread per physical bus: it owns a drive backend
 * (drive.h) and runs its transactions, as fast as the bus allows and at most
 * at the configured rate, SCHED_FIFO below the force loop.
 *
 * The force loop and the bus thread share only two lock-free mailboxes
 * (seqlocks, proto/seqlock.h): the newest command (setpoints, enable) goes
 * one way, the newest feedback (position, velocity, status, with the
 * CLOCK_MONOTONIC time it was read) the other. The loop never waits on a
 * bus: a torn read keeps the previous copy, and a bus that stops answering
 * shows as feedback growing old.
 *
 * The handle's valves on the drives' inputs (drive.h, struct drive's
 * valves) travel with the feedback: each drive's as its last exchange
 * read them, with that exchange's time; released when the exchange
 * failed. The loop takes them by bus_valves() below. The tool in the
 * working channel (struct drive's tool) likewise, by bus_tool().
 *
 * Faults. A failed transaction (ENDOSIM_DRIVE_BUS_ERROR), a drive fault
 * (ENDOSIM_DRIVE_FAULT), a vanished device (ENDOSIM_DRIVE_PRESENT cleared) or
 * a drive that leaves torque mode by itself is latched in the feedback of
 * the bus' axes, with the reason in words (bus_describe()), and the bus
 * thread brings its drives down at once. The latch holds until the loop has
 * seen it, torque is off (enable false) and the cause is gone: a device that
 * went away is reopened every BUS_REOPEN_S, and a drive fault is asked to
 * clear while disabled. A bus brings drives up only on a new rising edge of
 * enable after its last fault: nothing restarts into torque by itself.
 */
#ifndef ENDOSIM_BUS_H
#define ENDOSIM_BUS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rig/drive.h"
#include "base/histo.h"
#include "rig/rig.h"

#define BUS_REOPEN_S 0.25 /* between attempts to reopen a vanished device */

struct bus_params {
	double max_rate_hz;         /* exchanges per second at most */
	double feedback_max_age_s;  /* to describe a stale-feedback fault */
	int priority;               /* SCHED_FIFO priority of the thread */
};

struct bus;

/* Takes ownership of D (destroyed with the bus). NULL on ENOMEM, logged. */
struct bus *bus_create(struct drive *d, const struct bus_params *p);

/* NULL is fine; stops first. */
void bus_destroy(struct bus *b);

/*
 * Main thread, before the force loop runs: opens the device and checks it.
 * Returns 0, or a negative errno after logging what was looked for and why
 * it failed.
 */
int bus_open(struct bus *b);

/*
 * Main thread: starts the bus thread and waits (up to 2 s) for its first
 * feedback, so the force loop starts on fresh data. Returns 0 or a negative
 * errno, logged.
 */
int bus_start(struct bus *b);

/* Main thread: drives brought down, thread joined, device closed. */
void bus_stop(struct bus *b);

/*
 * Force loop, its cycle at NOW_NS: the newest feedback of the bus' axes
 * into FB, the valves its drives read into FB's valves (bus_valves(),
 * with the bus' feedback_max_age_s), the tool's signals into FB's tool
 * (bus_tool()). Never blocks.
 */
void bus_fetch(struct bus *b, uint64_t now_ns, struct rig_feedback *fb);

/*
 * Any thread (pure): the handle's VALVES (enum endosim_valve bits) with
 * those a drive reads (MAPPED) replaced by what it read (PRESSED) in the
 * exchange that gave its feedback F: as read while F is at most
 * MAX_AGE_NS old at NOW_NS and its drive present, without a fault or a
 * bus error; released otherwise (no gas flows on a dead wire). The
 * valves not MAPPED stay as they are (the simulated hand's).
 */
uint32_t bus_valves(uint32_t valves, uint32_t mapped, uint32_t pressed,
		    const struct rig_axis_feedback *f, uint64_t now_ns,
		    uint64_t max_age_ns);

/*
 * Any thread (pure): FB's tool in the working channel (its depth, its
 * handle's opening, the pedal) with the signals a drive reads (MAPPED,
 * enum config_tool_signal bits) replaced by what it read (READ) in the
 * exchange that gave its feedback F, under bus_valves()' rule: as read
 * while fresh; stale or lost, the tool still and the handle still (NaN:
 * model/tool.h's rule) and the pedal up. The signals not MAPPED stay as
 * they are (the simulated hand's).
 */
void bus_tool(struct rig_feedback *fb, uint32_t mapped,
	      const struct drive_tool *read,
	      const struct rig_axis_feedback *f, uint64_t now_ns,
	      uint64_t max_age_ns);

/*
 * Force loop: the newest command of its cycle at NOW_NS: SETPOINT per rig
 * axis (N or N m), and whether the drives may produce torque. Never
 * blocks. A command older than the bus' feedback_max_age_s while enabled
 * (the loop stalled) is a bus error: the bus brings its drives down.
 */
void bus_post(struct bus *b, uint64_t now_ns,
	      const double setpoint[ENDOSIM_AXES], bool enable);

/* True when rig axis AXIS is on this bus. Any thread. */
bool bus_has_axis(const struct bus *b, int axis);

/*
 * Any thread but the force loop: the device and its drive of AXIS and, for
 * FAULT_BIT with DETAIL, the cause in words, into BUF.
 */
void bus_describe(struct bus *b, int axis, uint32_t fault_bit,
		  uint32_t detail, char *buf, size_t size);

/* Any thread: exchange rate and latencies so far. */
void bus_get_stats(struct bus *b, struct rig_bus_stats *st);

/* Any thread: the bus' name ("epos4-usb 24e7:3b01 serial ..."). */
const char *bus_name(const struct bus *b);

#endif
