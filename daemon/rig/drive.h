/*
 * drive.h - the interface every drive backend implements: a table of
 * functions over one physical bus (one EPOS4 on USB; one Modbus line or
 * connection with its wheel drives), as libmodbus' modbus_backend_t.
 *
 * Who calls what: open() from the main thread at start-up (before the force
 * loop runs), then everything from that bus' own thread (bus.h) only. Every
 * function may block on the bus for up to its configured timeouts; none is
 * ever called from the force loop.
 *
 * Errors: 0 or a negative errno, with the reason in words in d->why
 * (naming the object, register or service and the device's own code):
 *   -ENODEV     the device is gone (unplugged, connection lost) or absent:
 *               the bus thread closes it and reopens it later
 *   -ETIMEDOUT  no reply in time
 *   -EBADMSG    a reply failed its CRC
 *   -EPROTO     a reply made no sense (framing, length, wrong answer)
 *   -EREMOTEIO  the device refused the request (SDO abort, Modbus exception)
 *   -ENXIO      open(): a device answered but is not what was configured
 *   -EIO        anything else the transport reported
 *
 * Units: SI at the axis (m, rad, N, N m) on this interface; each backend
 * converts from counts, per-mille and register values in one place, with
 * struct drive_units.
 */
#ifndef ENDOSIM_DRIVE_H
#define ENDOSIM_DRIVE_H

#include <stdbool.h>
#include <stdint.h>

#include "conf/config.h"
#include "base/histo.h"

/* Drives one bus can carry: every axis on one Modbus line at most. */
#define DRIVE_MAX ENDOSIM_AXES

/*
 * Converts between the motor shaft and the axis:
 *   axis position = counts * si_per_count          (m or rad)
 *   motor torque  = axis force * motor_nm_per_si   (N m, from N or N m)
 * from [axis.NAME] gear_ratio, counts_per_rev, direction and, for the
 * insertion, gear_radius_m (a lossless gear: power in equals power out).
 */
struct drive_units {
	double si_per_count;
	double motor_nm_per_si;
};

void drive_units_init(struct drive_units *u, const struct config *cfg,
		      int axis);

/*
 * The tool in the working channel as a drive's inputs read it: those of
 * its signals the drive reads (struct drive's tool); the others as they
 * were (unused).
 */
struct drive_tool {
	double depth_m;   /* its tip beyond the channel's exit, m */
	double opening;   /* its handle, 0 closed .. 1 open */
	bool pedal;       /* the cautery's foot pedal down */
};

/* One drive's state after an exchange, at the axis. */
struct drive_sample {
	double position;  /* m or rad */
	double velocity;  /* m/s or rad/s */
	bool enabled;     /* power stage on, following the setpoint */
	bool fault;       /* the drive reports a fault of its own */
	uint32_t code;    /* its fault code when FAULT */
	uint32_t valves;  /* enum endosim_valve bits: those of the drive's
			     valves (struct drive's) read pressed */
	struct drive_tool tool; /* the tool's signals the drive reads */
};

struct drive;

struct drive_ops {
	const char *kind; /* "epos4-usb", "modbus" */
	/*
	 * Opens the device and checks it is the configured one (identity,
	 * rated torque, each drive answering). Leaves every drive disabled.
	 */
	int (*open)(struct drive *d);
	/*
	 * One step of bringing drive I (0..n-1) into torque mode and enabling
	 * it (fault reset, mode, shutdown, switch on, enable operation).
	 * Returns 1 while under way (call again after the next exchange),
	 * 0 once it follows torque setpoints, or a negative errno.
	 */
	int (*bring_up)(struct drive *d, int i);
	/*
	 * One cycle: sends SETPOINT[i] (N or N m at the axis) to every
	 * enabled drive, reads every drive's position, velocity, status,
	 * the valves and the tool's signals on its inputs into SAMPLE[i].
	 */
	int (*exchange)(struct drive *d, const double *setpoint,
			struct drive_sample *sample);
	/* Drive I: torque zero, quick stop, disable. Best effort. */
	int (*bring_down)(struct drive *d, int i);
	/* Drive I, disabled and in fault: asks it to clear the fault. */
	int (*clear_fault)(struct drive *d, int i);
	/* Releases the device; the next open() starts afresh. */
	void (*close)(struct drive *d);
	/* Frees; closes first. */
	void (*destroy)(struct drive *d);
	/* The drive's fault CODE in words (never NULL). */
	const char *(*describe_fault)(uint32_t code);
};

/* Backends start their private struct with this. */
struct drive {
	const struct drive_ops *ops;
	int n;                       /* drives on this bus */
	int axis[DRIVE_MAX];         /* the rig axis of each */
	struct drive_units units[DRIVE_MAX];
	uint32_t valves[DRIVE_MAX];  /* the valves each reads (enum
					endosim_valve bits) */
	uint32_t tool[DRIVE_MAX];    /* the tool's signals each reads
					(enum config_tool_signal bits) */
	char name[200];              /* the bus: "epos4-usb 24e7:3b01 ..." */
	char unit[DRIVE_MAX][32];    /* each drive on it: "node 1", "slave 2" */
	char why[256];               /* the last error, in words */
	int why_drive;               /* the drive it concerns, -1: the bus */
	struct histo *txn;           /* when set: each transaction's duration */
};

/*
 * The backends. Each returns NULL on ENOMEM (logged); nothing is opened
 * before open().
 *  - epos4-usb: one bus for AXIS ([epos4.AXIS]).
 *  - modbus: one bus for every axis whose backend is modbus ([modbus],
 *    [modbus.AXIS]).
 */
struct drive *drive_epos4_create(const struct config *cfg, int axis);
struct drive *drive_modbus_create(const struct config *cfg);

/*
 * The valves (enum endosim_valve bits) pressed in a word of digital inputs
 * INPUTS (an EPOS4's 0x60FD) whose bit BIT[V] is set while valve V is
 * pressed (-1: valve V is not on these inputs). Pure.
 */
uint32_t drive_valves_of_inputs(uint32_t inputs,
				const int bit[CONFIG_VALVES]);

/*
 * The tool's handle's opening (0 closed .. 1 open, clamped) from an
 * analogue input reading VOLTAGE_MV that reads CLOSED_MV closed and
 * OPEN_MV open (not equal: config_check()). Pure.
 */
double drive_tool_opening(double voltage_mv, double closed_mv,
			  double open_mv);

/*
 * Records D's error text (printf-style) concerning drive I (-1: the whole
 * bus) and returns ERR.
 */
int drive_fail(struct drive *d, int i, int err, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

/* Adds one transaction that began at START_NS to D's histogram, if any. */
void drive_count_txn(struct drive *d, uint64_t start_ns);

#endif
