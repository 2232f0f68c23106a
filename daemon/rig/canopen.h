/*
 * canopen.h - what the EPOS4 backend and its emulator share of CANopen:
 * the CiA 402 drive state machine (statusword decoding, the controlwords
 * that walk a drive into "operation enabled"), the CiA 301 SDO abort codes
 * and the CiA 301/402 error codes, in words.
 *
 * Pure functions and constant tables: safe in any thread.
 */
#ifndef ENDOSIM_CANOPEN_H
#define ENDOSIM_CANOPEN_H

#include <stdint.h>

/* Object dictionary entries the drive layer uses (index; subindex 0). */
enum {
	CANOPEN_DEVICE_TYPE = 0x1000,    /* UNSIGNED32; low word 402: a drive */
	CANOPEN_HEARTBEAT_CONSUMER = 0x1016, /* :01 UNSIGNED32: producer node
						 << 16 | time in ms */
	CANOPEN_ERROR_CODE = 0x603F,     /* UNSIGNED16: the drive's fault */
	CANOPEN_CONTROLWORD = 0x6040,    /* UNSIGNED16 */
	CANOPEN_STATUSWORD = 0x6041,     /* UNSIGNED16 */
	CANOPEN_QUICK_STOP_OPTION = 0x605A,
	CANOPEN_MODE = 0x6060,           /* INTEGER8: modes of operation */
	CANOPEN_MODE_DISPLAY = 0x6061,   /* INTEGER8 */
	CANOPEN_POSITION_ACTUAL = 0x6064, /* INTEGER32, encoder increments */
	CANOPEN_VELOCITY_ACTUAL = 0x606C, /* INTEGER32, velocity units */
	CANOPEN_TARGET_TORQUE = 0x6071,  /* INTEGER16, per mille of 0x6076 */
	CANOPEN_MAX_TORQUE = 0x6072,     /* UNSIGNED16, per mille of 0x6076 */
	CANOPEN_RATED_TORQUE = 0x6076,   /* UNSIGNED32, the drive's unit */
	CANOPEN_TORQUE_ACTUAL = 0x6077,  /* INTEGER16, per mille of 0x6076 */
	CANOPEN_SI_UNIT_VELOCITY = 0x60A9, /* UNSIGNED32: prefix, unit, per */
	CANOPEN_ADDITIONAL_POSITION = 0x60E4, /* :01-03 INTEGER32: the
					    counts of each sensor (EPOS4:
					    sensor 1, 2, 3) */
	CANOPEN_DIGITAL_INPUTS = 0x60FD, /* UNSIGNED32: 0-2 the limit and
					    home switches, 16-31 the
					    maker's (EPOS4: its inputs) */
	EPOS4_ANALOG_INPUT_VOLTAGE = 0x3160, /* maxon's: :01-02 INTEGER16,
						each analogue input, mV */
};

#define CANOPEN_DEVICE_PROFILE_DRIVE 402
#define CANOPEN_MODE_CST 10 /* cyclic synchronous torque */
#define CANOPEN_MASTER_NODE 0x7F /* the producer the drive listens for */
#define CANOPEN_ERROR_HEARTBEAT 0x8130 /* life guard or heartbeat error */

/* SI unit velocity 0x60A9 without its prefix byte: revolutions per minute. */
#define CANOPEN_SI_UNIT_RPM 0x00B44700u

/* Controlwords (0x6040). Fault reset acts on the rising edge of bit 7. */
enum {
	CANOPEN_CW_DISABLE_VOLTAGE = 0x0000,
	CANOPEN_CW_QUICK_STOP = 0x0002,
	CANOPEN_CW_SHUTDOWN = 0x0006,
	CANOPEN_CW_SWITCH_ON = 0x0007,
	CANOPEN_CW_ENABLE_OPERATION = 0x000F,
	CANOPEN_CW_FAULT_RESET = 0x0080,
};

/* Statusword bits used directly. */
#define CANOPEN_SW_FAULT 0x0008

enum canopen_state {
	CANOPEN_NOT_READY = 0,          /* not ready to switch on */
	CANOPEN_SWITCH_ON_DISABLED,
	CANOPEN_READY_TO_SWITCH_ON,
	CANOPEN_SWITCHED_ON,
	CANOPEN_OPERATION_ENABLED,
	CANOPEN_QUICK_STOP_ACTIVE,
	CANOPEN_FAULT_REACTION_ACTIVE,
	CANOPEN_FAULT,
	CANOPEN_STATES,
	CANOPEN_UNKNOWN = CANOPEN_STATES, /* no pattern matches */
};

/* The state a statusword reports: (sw & mask) == value, per CiA 402. */
enum canopen_state canopen_state(uint16_t statusword);

/* The bits of the statusword that identify STATE (for emulators). */
uint16_t canopen_statusword(enum canopen_state state);

/* "switch on disabled", "operation enabled", ...; "unknown" otherwise. */
const char *canopen_state_name(enum canopen_state state);

/*
 * The controlword that moves a drive in STATE one step towards operation
 * enabled, in *CW. Returns 1 (send *CW), 0 (already operation enabled) or
 * -EAGAIN (not ready to switch on or fault reaction active: the drive moves
 * on by itself; wait).
 */
int canopen_step_to_enabled(enum canopen_state state, uint16_t *cw);

/* The meaning of a CiA 301 SDO abort code, or NULL when it is not known. */
const char *canopen_abort_text(uint32_t code);

/*
 * The meaning of a CiA 301/402 error code (0x603F), as precise as this
 * table knows it: a specific code, else its class ("current", "voltage",
 * ...). Never NULL.
 */
const char *canopen_error_text(uint16_t code);

#endif
