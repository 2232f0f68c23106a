/*
 * rig_drives.c - the rig of drives: each axis on the backend its
 * [axis.NAME] section names. Real axes belong to a bus (one per EPOS4, one
 * for all Modbus drives), each with its own thread (bus.h); simulated axes
 * stay with the simulated rig (rig_sim.c), which this rig runs alongside.
 * The handle's valves likewise: those mapped to a drive's inputs come
 * from its bus (released when stale or lost), the rest from the simulated
 * hand; and the tool in the working channel's signals (stale or lost:
 * the tool and its handle still, the pedal up).
 *
 * The force loop's read and write touch only the buses' mailboxes and the
 * simulated rig: nothing here waits on a device.
 */
#include <errno.h>
#include <stdlib.h>

#include "rig/bus.h"
#include "base/log.h"
#include "rig/rig_drives.h"
#include "rig/rig_sim.h"

#define BUS_PRIORITY_BELOW_LOOP 10

struct rig_drives {
	struct rig rig;
	struct rig *sim;                /* the simulated axes */
	struct bus *bus[ENDOSIM_AXES];
	int buses;
};

static struct rig_drives *to_drives(struct rig *rig)
{
	return (struct rig_drives *)rig;
}

static int drives_start(struct rig *rig)
{
	struct rig_drives *r = to_drives(rig);
	int err = 0;

	for (int b = 0; !err && b < r->buses; b++) {
		err = bus_open(r->bus[b]);
	}
	for (int b = 0; !err && b < r->buses; b++) {
		err = bus_start(r->bus[b]);
	}
	return err;
}

static void drives_read(struct rig *rig, uint64_t now_ns,
			struct rig_feedback *fb)
{
	struct rig_drives *r = to_drives(rig);

	rig_read(r->sim, now_ns, fb);
	for (int b = 0; b < r->buses; b++) {
		bus_fetch(r->bus[b], now_ns, fb);
	}
}

static void drives_write(struct rig *rig, uint64_t now_ns,
			 const double setpoint[ENDOSIM_AXES], bool enable)
{
	struct rig_drives *r = to_drives(rig);

	rig_write(r->sim, now_ns, setpoint, enable);
	for (int b = 0; b < r->buses; b++) {
		bus_post(r->bus[b], now_ns, setpoint, enable);
	}
}

static void drives_stop(struct rig *rig)
{
	struct rig_drives *r = to_drives(rig);

	for (int b = 0; b < r->buses; b++) {
		bus_stop(r->bus[b]);
	}
	rig_stop(r->sim);
}

static int drives_bus_stats(struct rig *rig, int index,
			    struct rig_bus_stats *st)
{
	struct rig_drives *r = to_drives(rig);

	if (index < 0 || index >= r->buses) {
		return -ENOENT;
	}
	bus_get_stats(r->bus[index], st);
	return 0;
}

static void drives_describe(struct rig *rig, uint32_t fault_bit, int axis,
			    uint32_t detail, char *buf, size_t size)
{
	struct rig_drives *r = to_drives(rig);

	for (int b = 0; b < r->buses; b++) {
		if (bus_has_axis(r->bus[b], axis)) {
			bus_describe(r->bus[b], axis, fault_bit, detail, buf,
				     size);
			return;
		}
	}
	rig_describe(r->sim, fault_bit, axis, detail, buf, size);
}

static void drives_destroy(struct rig *rig)
{
	struct rig_drives *r = to_drives(rig);

	for (int b = 0; b < r->buses; b++) {
		bus_destroy(r->bus[b]);
	}
	rig_destroy(r->sim);
	free(r);
}

static const struct rig_ops drives_ops = {
	.name = "drives",
	.start = drives_start,
	.read = drives_read,
	.write = drives_write,
	.stop = drives_stop,
	.bus_stats = drives_bus_stats,
	.describe = drives_describe,
	.destroy = drives_destroy,
};

static int add_bus(struct rig_drives *r, const struct config *cfg,
		   struct drive *d, double rate_hz, double max_age_s)
{
	struct bus_params p = {
		.max_rate_hz = rate_hz,
		.feedback_max_age_s = max_age_s,
		.priority = cfg->loop.priority > BUS_PRIORITY_BELOW_LOOP
				    ? cfg->loop.priority -
					      BUS_PRIORITY_BELOW_LOOP
				    : 1,
	};

	struct bus *b = d ? bus_create(d, &p) : NULL;

	if (!b) {
		return -1;
	}
	r->bus[r->buses++] = b;
	return 0;
}

static int add_buses(struct rig_drives *r, const struct config *cfg)
{
	bool modbus = false;

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		int backend = config_axis_backend(cfg, a);

		if (backend == CONFIG_DRIVE_EPOS4_USB &&
		    add_bus(r, cfg, drive_epos4_create(cfg, a),
			    cfg->epos4[a].max_rate_hz,
			    cfg->epos4[a].feedback_max_age_s)) {
			return -1;
		}
		modbus |= backend == CONFIG_DRIVE_MODBUS;
	}
	if (modbus && add_bus(r, cfg, drive_modbus_create(cfg),
			      cfg->modbus.max_rate_hz,
			      cfg->modbus.feedback_max_age_s)) {
		return -1;
	}
	return 0;
}

struct rig *rig_drives_create(const struct config *cfg, struct hand *hand)
{
	struct rig_drives *r = calloc(1, sizeof(*r));

	if (!r) {
		log_err("rig: out of memory");
		return NULL;
	}
	r->rig.ops = &drives_ops;
	r->sim = rig_sim_create(cfg, hand);
	if (!r->sim || add_buses(r, cfg)) {
		drives_destroy(&r->rig);
		return NULL;
	}
	return &r->rig;
}
