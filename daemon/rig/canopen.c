/* canopen.c - see canopen.h. */
#include "rig/canopen.h"

#include <errno.h>
#include <stddef.h>

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

static const struct {
	uint16_t mask, value;
	const char *name;
} states[CANOPEN_STATES] = {
	[CANOPEN_NOT_READY] = { 0x4F, 0x00, "not ready to switch on" },
	[CANOPEN_SWITCH_ON_DISABLED] = { 0x4F, 0x40, "switch on disabled" },
	[CANOPEN_READY_TO_SWITCH_ON] = { 0x6F, 0x21, "ready to switch on" },
	[CANOPEN_SWITCHED_ON] = { 0x6F, 0x23, "switched on" },
	[CANOPEN_OPERATION_ENABLED] = { 0x6F, 0x27, "operation enabled" },
	[CANOPEN_QUICK_STOP_ACTIVE] = { 0x6F, 0x07, "quick stop active" },
	[CANOPEN_FAULT_REACTION_ACTIVE] = { 0x4F, 0x0F,
					    "fault reaction active" },
	[CANOPEN_FAULT] = { 0x4F, 0x08, "fault" },
};

enum canopen_state canopen_state(uint16_t statusword)
{
	for (int s = 0; s < CANOPEN_STATES; s++) {
		if ((statusword & states[s].mask) == states[s].value) {
			return (enum canopen_state)s;
		}
	}
	return CANOPEN_UNKNOWN;
}

uint16_t canopen_statusword(enum canopen_state state)
{
	return state < CANOPEN_STATES ? states[state].value : 0;
}

const char *canopen_state_name(enum canopen_state state)
{
	return state < CANOPEN_STATES ? states[state].name : "unknown";
}

int canopen_step_to_enabled(enum canopen_state state, uint16_t *cw)
{
	switch (state) {
	case CANOPEN_OPERATION_ENABLED:
		return 0;
	case CANOPEN_FAULT:
		*cw = CANOPEN_CW_FAULT_RESET;
		return 1;
	case CANOPEN_SWITCH_ON_DISABLED:
		*cw = CANOPEN_CW_SHUTDOWN;
		return 1;
	case CANOPEN_READY_TO_SWITCH_ON:
		*cw = CANOPEN_CW_SWITCH_ON;
		return 1;
	case CANOPEN_SWITCHED_ON:
		*cw = CANOPEN_CW_ENABLE_OPERATION;
		return 1;
	case CANOPEN_QUICK_STOP_ACTIVE:
		/* back through switch on disabled: quick stop is not undone */
		*cw = CANOPEN_CW_DISABLE_VOLTAGE;
		return 1;
	default:
		return -EAGAIN;
	}
}

static const struct {
	uint32_t code;
	const char *text;
} aborts[] = {
	{ 0x05030000, "toggle bit not alternated" },
	{ 0x05040000, "SDO protocol timed out" },
	{ 0x05040001, "command specifier not valid or unknown" },
	{ 0x05040002, "invalid block size" },
	{ 0x05040003, "invalid sequence number" },
	{ 0x05040004, "CRC error" },
	{ 0x05040005, "out of memory" },
	{ 0x06010000, "unsupported access to an object" },
	{ 0x06010001, "attempt to read a write-only object" },
	{ 0x06010002, "attempt to write a read-only object" },
	{ 0x06020000, "object does not exist in the object dictionary" },
	{ 0x06040041, "object cannot be mapped to the PDO" },
	{ 0x06040042, "PDO length exceeded" },
	{ 0x06040043, "general parameter incompatibility" },
	{ 0x06040047, "general internal incompatibility in the device" },
	{ 0x06060000, "access failed due to a hardware error" },
	{ 0x06070010, "data type does not match, length does not match" },
	{ 0x06070012, "data type does not match, length too high" },
	{ 0x06070013, "data type does not match, length too low" },
	{ 0x06090011, "subindex does not exist" },
	{ 0x06090030, "value range of parameter exceeded" },
	{ 0x06090031, "value of parameter written too high" },
	{ 0x06090032, "value of parameter written too low" },
	{ 0x06090036, "maximum value is less than minimum value" },
	{ 0x060A0023, "resource not available: SDO connection" },
	{ 0x08000000, "general error" },
	{ 0x08000020, "data cannot be transferred or stored" },
	{ 0x08000021, "data cannot be transferred: local control" },
	{ 0x08000022, "data cannot be transferred: present device state" },
	{ 0x08000023, "no object dictionary present" },
	{ 0x08000024, "no data available" },
};

const char *canopen_abort_text(uint32_t code)
{
	for (size_t i = 0; i < COUNT(aborts); i++) {
		if (aborts[i].code == code) {
			return aborts[i].text;
		}
	}
	return NULL;
}

static const struct {
	uint16_t code, mask;
	const char *text;
} errors[] = {
	{ 0x0000, 0xFFFF, "no error" },
	{ 0x2310, 0xFFFF, "continuous overcurrent" },
	{ 0x2320, 0xFFFF, "short circuit at the motor side" },
	{ 0x3210, 0xFFFF, "DC link overvoltage" },
	{ 0x3220, 0xFFFF, "DC link undervoltage" },
	{ 0x4210, 0xFFFF, "excess temperature, device" },
	{ 0x4310, 0xFFFF, "excess temperature, drive" },
	{ 0x5113, 0xFFFF, "supply voltage too low" },
	{ 0x7121, 0xFFFF, "motor blocked" },
	{ 0x7300, 0xFFFF, "sensor error" },
	{ 0x8110, 0xFFFF, "CAN overrun" },
	{ 0x8130, 0xFFFF, "life guard or heartbeat error" },
	{ 0x8611, 0xFFFF, "following error" },
	{ 0x1000, 0xF000, "generic error" },
	{ 0x2000, 0xF000, "current" },
	{ 0x3000, 0xF000, "voltage" },
	{ 0x4000, 0xF000, "temperature" },
	{ 0x5000, 0xF000, "device hardware" },
	{ 0x6000, 0xF000, "device software" },
	{ 0x7000, 0xF000, "additional modules (motor, sensor)" },
	{ 0x8000, 0xF000, "monitoring (communication, control)" },
	{ 0x9000, 0xF000, "external error" },
	{ 0xFF00, 0xFF00, "device specific" },
	{ 0xF000, 0xF000, "additional functions" },
};

const char *canopen_error_text(uint16_t code)
{
	for (size_t i = 0; i < COUNT(errors); i++) {
		if ((code & errors[i].mask) == errors[i].code) {
			return errors[i].text;
		}
	}
	return "unknown error class";
}
