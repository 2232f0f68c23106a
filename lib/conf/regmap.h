/*
 * regmap.h - a Modbus drive's register map: where each signal lives and how
 * its raw register value turns into a physical value.
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
 *
 * Pure computation: safe in any thread.
 */
#ifndef ENDOSIM_REGMAP_H
#define ENDOSIM_REGMAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

enum regmap_table {
	REGMAP_NONE = 0, /* the signal is not used */
	REGMAP_COIL,
	REGMAP_DISCRETE,
	REGMAP_INPUT,
	REGMAP_HOLDING,
};

enum regmap_type { REGMAP_U16, REGMAP_I16, REGMAP_U32, REGMAP_I32, REGMAP_F32 };

enum regmap_order { REGMAP_ABCD, REGMAP_CDAB, REGMAP_BADC, REGMAP_DCBA };

enum regmap_signal {
	REGMAP_TORQUE,
	REGMAP_ENABLE,
	REGMAP_POSITION,
	REGMAP_VELOCITY,
	REGMAP_FAULT,
	REGMAP_FAULT_RESET,
	REGMAP_WATCHDOG,
	REGMAP_SIGNALS,
};

/* Registers (or bits) one value takes: at most 2. */
#define REGMAP_MAX_WORDS 2

struct regmap_reg {
	uint8_t table;    /* enum regmap_table */
	uint8_t type;     /* enum regmap_type */
	uint8_t order;    /* enum regmap_order */
	uint16_t address;
	double scale;     /* value per raw unit, not 0 */
	double offset;    /* value at raw 0 */
};

/* "torque", "enable", ... */
const char *regmap_signal_name(enum regmap_signal s);

/* Registers (bits, for coil and discrete) R spans: 1 or 2; 0 when unused. */
int regmap_words(const struct regmap_reg *r);

/* True when R can be written (coil or holding). */
bool regmap_writable(const struct regmap_reg *r);

/* The physical value of the raw registers WORDS (regmap_words() of them). */
double regmap_decode(const struct regmap_reg *r, const uint16_t *words);

/*
 * The raw registers for VALUE, rounded to the nearest count. Returns 0, or
 * -ERANGE when VALUE is beyond the type (WORDS then hold the nearest end) or
 * not a number (WORDS then hold raw 0).
 */
int regmap_encode(const struct regmap_reg *r, double value, uint16_t *words);

/*
 * Parses TEXT (the syntax above). Returns 0, or -EINVAL with the reason in
 * WHY. R is unchanged on error.
 */
int regmap_parse(const char *text, struct regmap_reg *r, char *why,
		 size_t size);

/* Writes R in the syntax regmap_parse() reads, defaults left out. */
void regmap_format(const struct regmap_reg *r, char *buf, size_t size);

#endif
