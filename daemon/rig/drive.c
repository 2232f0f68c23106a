/* drive.c - see drive.h. */
#include "rig/drive.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "base/mono.h"

void drive_units_init(struct drive_units *u, const struct config *cfg,
		      int axis)
{
	const struct config_axis *ax = &cfg->axis[axis];
	double sign = ax->reversed ? -1.0 : 1.0;
	double radius = axis == ENDOSIM_AXIS_INSERTION ? ax->gear_radius_m
						       : 1.0;

	/* a count turns the motor 2 pi / cpr, the output 1 / gear as much */
	u->si_per_count = sign * 2.0 * M_PI * radius /
			  ((double)ax->counts_per_rev * ax->gear_ratio);
	/* power: F v = T_motor w_motor, w_motor = gear v / radius */
	u->motor_nm_per_si = sign * radius / ax->gear_ratio;
}

uint32_t drive_valves_of_inputs(uint32_t inputs,
				const int bit[CONFIG_VALVES])
{
	uint32_t valves = 0;

	for (int v = 0; v < CONFIG_VALVES; v++) {
		if (bit[v] >= 0 && ((inputs >> bit[v]) & 1u)) {
			valves |= 1u << v;
		}
	}
	return valves;
}

double drive_tool_opening(double voltage_mv, double closed_mv,
			  double open_mv)
{
	double x = (voltage_mv - closed_mv) / (open_mv - closed_mv);

	return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
}

int drive_fail(struct drive *d, int i, int err, const char *fmt, ...)
{
	va_list ap;

	d->why_drive = i;
	va_start(ap, fmt);
	vsnprintf(d->why, sizeof(d->why), fmt, ap);
	va_end(ap);
	return err;
}

void drive_count_txn(struct drive *d, uint64_t start_ns)
{
	if (d->txn) {
		histo_add(d->txn, mono_ns() - start_ns);
	}
}
