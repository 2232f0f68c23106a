/*
 * regmap.h - a Modbus drive's registers turned into values and back, by
 * the register's description in the configuration (conf/regspec.h: its
 * table, type, byte order, scale and offset):
 *
 *   value = raw * scale + offset
 *
 * raw being the type's value of the registers' bytes in their order (a
 * bit: 0 or 1). The Modbus backend (drive_modbus.c) and its emulator
 * (tests/emulators/modbus_emu.c) use it.
 *
 * Pure computation: safe in any thread, the bus threads included.
 */
#ifndef ENDOSIM_REGMAP_H
#define ENDOSIM_REGMAP_H

#include <stdint.h>

#include "conf/regspec.h"

/* The physical value of the raw registers WORDS (regspec_words() of them). */
double regmap_decode(const struct regspec *r, const uint16_t *words);

/*
 * The raw registers for VALUE, rounded to the nearest count. Returns 0, or
 * -ERANGE when VALUE is beyond the type (WORDS then hold the nearest end) or
 * not a number (WORDS then hold raw 0).
 */
int regmap_encode(const struct regspec *r, double value, uint16_t *words);

#endif
