/*
 * regspec.h - a Modbus drive's register map as the configuration describes
 * it: where each signal lives, its type, byte order, scale and offset, and
 * the text the configuration writes it in. The rig turns raw registers
 * into values by it (rig/regmap.h); the configuration only reads, checks
 * and prints it, so endoctl and endoview need no rig.
 *
 * Every vendor's map differs, so each signal of a wheel drive is one line
 * of the configuration:
 *
 *   SIGNAL = TABLE ADDRESS TYPE [ORDER] [scale=S] [offset=O]    or   none
 *
 *   TABLE    coil, discrete (read-only bits), input (read-only registers),
 *            holding; the function codes follow: reads 0x01/0x02/0x04/0x03,
 *            writes 0x05 (coil), 0x06 (one register), 0x10 (two registers)
 *   ADDRESS  0..65535, decimal or 0x hex, as on the wire (0-based)
 *   TYPE     u16, i16, u32, i32, f32 (bits are u16: 0 or 1)
 *   ORDER    of the bytes A (most significant) to D across the registers:
 *            abcd (high word first: the Modbus default), cdab (low word
 *            first), badc, dcba (bytes swapped in each word); 16-bit types
 *            take ab (= abcd, cdab) or ba (= badc, dcba)
 *   value = raw * scale + offset  (defaults 1 and 0)
 *
 * The values a signal carries, at the motor shaft:
 *   torque    motor torque setpoint, N m (a current-mode drive: scale is the
 *             torque constant times amperes per count)
 *   enable    written 1 to enable the power stage, 0 to disable it
 *   position  encoder counts
 *   velocity  encoder counts per second
 *   fault     the drive's fault code; anything but 0 is a fault
 *   fault_reset  written 1, then 0, to clear a fault
 *   watchdog  written at enable with [modbus.AXIS] watchdog_s: the drive
 *             stops by itself when it hears nothing for that long
 *   valve_air, valve_water, valve_suction
 *             the handle's valves on the drive's digital inputs (a
 *             discrete input, function 0x02, is the usual place): pressed
 *             while the value is not 0 (scale=-1 offset=1 reads an input
 *             that opens when pressed); read with the feedback
 *   tool_depth   the tool's depth beyond the working channel's exit, m
 *             (an encoder's count on an input register, function 0x04:
 *             scale is metres per count, offset the depth at count 0)
 *   tool_opening the tool's handle, 0 closed .. 1 open (an analogue
 *             input register: scale and offset map its raw value there)
 *   tool_pedal   the cautery's foot pedal, down while not 0 (a discrete
 *             input, as a valve)
 *
 * Pure computation: safe in any thread.
 */
#ifndef ENDOSIM_REGSPEC_H
#define ENDOSIM_REGSPEC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

enum regspec_table {
	REGSPEC_NONE = 0, /* the signal is not used */
	REGSPEC_COIL,
	REGSPEC_DISCRETE,
	REGSPEC_INPUT,
	REGSPEC_HOLDING,
};

enum regspec_type {
	REGSPEC_U16,
	REGSPEC_I16,
	REGSPEC_U32,
	REGSPEC_I32,
	REGSPEC_F32,
};

enum regspec_order { REGSPEC_ABCD, REGSPEC_CDAB, REGSPEC_BADC, REGSPEC_DCBA };

enum regspec_signal {
	REGSPEC_TORQUE,
	REGSPEC_ENABLE,
	REGSPEC_POSITION,
	REGSPEC_VELOCITY,
	REGSPEC_FAULT,
	REGSPEC_FAULT_RESET,
	REGSPEC_WATCHDOG,
	REGSPEC_VALVE_AIR,     /* in enum endosim_valve's order: air, */
	REGSPEC_VALVE_WATER,   /* water, */
	REGSPEC_VALVE_SUCTION, /* suction */
	REGSPEC_TOOL_DEPTH,    /* the tool in the working channel: */
	REGSPEC_TOOL_OPENING,
	REGSPEC_TOOL_PEDAL,
	REGSPEC_SIGNALS,
};

/* Registers (or bits) one value takes: at most 2. */
#define REGSPEC_MAX_WORDS 2

struct regspec {
	uint8_t table;    /* enum regspec_table */
	uint8_t type;     /* enum regspec_type */
	uint8_t order;    /* enum regspec_order */
	uint16_t address;
	double scale;     /* value per raw unit, not 0 */
	double offset;    /* value at raw 0 */
};

/* "torque", "enable", ... */
const char *regspec_signal_name(enum regspec_signal s);

/* Registers (bits, for coil and discrete) R spans: 1 or 2; 0 when unused. */
int regspec_words(const struct regspec *r);

/* True when R is a bit (coil or discrete). */
bool regspec_bit(const struct regspec *r);

/* True when R can be written (coil or holding). */
bool regspec_writable(const struct regspec *r);

/*
 * Parses TEXT (the syntax above). Returns 0, or -EINVAL with the reason in
 * WHY. R is unchanged on error.
 */
int regspec_parse(const char *text, struct regspec *r, char *why,
		  size_t size);

/* Writes R in the syntax regspec_parse() reads, defaults left out. */
void regspec_format(const struct regspec *r, char *buf, size_t size);

#endif
