/* names.c - see names.h. */
#include "proto/names.h"

#include <stdio.h>
#include <string.h>

#include "proto/endosim_shm.h"
#include "proto/session_file.h"

static const char *const state_names[] = {
	[ENDOSIM_STATE_IDLE] = "IDLE",
	[ENDOSIM_STATE_ENABLED] = "ENABLED",
	[ENDOSIM_STATE_ESTOP] = "ESTOP",
	[ENDOSIM_STATE_FAULT] = "FAULT",
};

static const char *const axis_names[ENDOSIM_AXES] = {
	"insertion", "roll", "wheel_ud", "wheel_lr",
};

static const char *const model_names[] = {
	[ENDOSIM_MODEL_PAPER] = "paper",
	[ENDOSIM_MODEL_ROD] = "rod",
};

static const char *const guide_phase_names[] = {
	[ENDOSIM_GUIDE_OFF] = "off",
	[ENDOSIM_GUIDE_MOVING] = "moving",
	[ENDOSIM_GUIDE_GUIDING] = "guiding",
	[ENDOSIM_GUIDE_HOLDING] = "holding",
	[ENDOSIM_GUIDE_FADING] = "fading",
	[ENDOSIM_GUIDE_FREE] = "taken-over",
};

static const char *const guide_end_names[] = {
	[ENDOSIM_GUIDE_END_NONE] = "",
	[ENDOSIM_GUIDE_END_STOPPED] = "stopped",
	[ENDOSIM_GUIDE_END_DONE] = "done",
	[ENDOSIM_GUIDE_END_NOT_ENABLED] = "not-enabled",
	[ENDOSIM_GUIDE_END_LOST] = "lost",
};

const char *const names_positions[] = {
	[ENDOSIM_POSITION_LEFT_LATERAL] = "left-lateral",
	[ENDOSIM_POSITION_SUPINE] = "supine",
	[ENDOSIM_POSITION_RIGHT_LATERAL] = "right-lateral",
	[ENDOSIM_POSITION_PRONE] = "prone",
	NULL,
};

const char *const names_tools[] = {
	[ENDOSIM_TOOL_NONE] = "none",
	[ENDOSIM_TOOL_FORCEPS] = "forceps",
	[ENDOSIM_TOOL_SNARE] = "snare",
	[ENDOSIM_TOOL_NEEDLE] = "needle",
	[ENDOSIM_TOOL_CLIP] = "clip",
	NULL,
};

static const char *const polyp_state_names[] = {
	[ENDOSIM_POLYP_IN_PLACE] = "in-place",
	[ENDOSIM_POLYP_CAPTURED] = "captured",
	[ENDOSIM_POLYP_CUT] = "cut",
	[ENDOSIM_POLYP_RETRIEVED] = "retrieved",
};

static const char *const bleed_names[] = {
	[ENDOSIM_BLEED_NONE] = "none",
	[ENDOSIM_BLEED_BLEEDING] = "bleeding",
	[ENDOSIM_BLEED_CLIPPED] = "clipped",
	[ENDOSIM_BLEED_STOPPED] = "stopped",
};

/* By the bit's number (enum endosim_tool_event). */
static const char *const tool_event_names[] = {
	"capture", "release", "cut", "injury", "lift", "bite", "clip",
	"bleed", "clipped", "stopped", "retrieve",
};

static const char *const pain_cause_names[] = {
	[ENDOSIM_PAIN_NONE] = "none",
	[ENDOSIM_PAIN_LOOPING] = "looping",
	[ENDOSIM_PAIN_STRAIGHTENING] = "straightening",
	[ENDOSIM_PAIN_INSUFFLATION] = "insufflation",
	[ENDOSIM_PAIN_TIP] = "tip",
};

const char *const names_sedations[] = {
	[ENDOSIM_SEDATION_NONE] = "none",
	[ENDOSIM_SEDATION_MINIMAL] = "minimal",
	[ENDOSIM_SEDATION_MODERATE] = "moderate",
	[ENDOSIM_SEDATION_DEEP] = "deep",
	NULL,
};

_Static_assert(ENDOSIM_VALVE_AIR == 1 && ENDOSIM_VALVE_WATER == 2 &&
	       ENDOSIM_VALVE_SUCTION == 4, "names: the valves' bits");

/* every combination of the three valves' bits */
static const char *const valves_names[] = {
	"none", "air", "water", "air,water", "suction", "air,suction",
	"water,suction", "air,water,suction",
};

static const char *const event_names[] = {
	[SESSION_EVENT_STATE] = "state",
	[SESSION_EVENT_FAULT] = "fault",
	[SESSION_EVENT_PARAM] = "param",
	[SESSION_EVENT_DROPS] = "drops",
	[SESSION_EVENT_NOTE] = "note",
	[SESSION_EVENT_POSITION] = "position",
	[SESSION_EVENT_HAND] = "hand",
	[SESSION_EVENT_VALVE] = "valve",
	[SESSION_EVENT_PERFORATION] = "perforation",
	[SESSION_EVENT_TEAR] = "tear",
	[SESSION_EVENT_SEDATION] = "sedation",
	[SESSION_EVENT_TOOL] = "tool",
};

/* endosim.proto's DebugAction, by number */
static const char *const debug_action_names[] = {
	NULL, "clear", "drive-fault", "drive-gone", "stale", "bus-error",
	"speed", "position", "force", "nan", "stall", "end-control",
};

static const char *const fault_names[] = {
	"drive", "drive-gone", "stale-feedback", "bus-error",
	"overrun-budget", "travel", "runaway", "saturation",
	"non-finite", "internal", "estop",
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

const char *names_state(uint32_t state)
{
	return state < COUNT(state_names) ? state_names[state] : "?";
}

const char *names_guide_phase(uint32_t phase)
{
	return phase < COUNT(guide_phase_names) ? guide_phase_names[phase]
						 : "?";
}

const char *names_guide_end(uint32_t end)
{
	return end < COUNT(guide_end_names) ? guide_end_names[end] : "?";
}

const char *names_guide_axis(uint32_t axis)
{
	return axis < ENDOSIM_AXES ? axis_names[axis] : "";
}

const char *names_axis(int axis)
{
	return axis >= 0 && axis < ENDOSIM_AXES ? axis_names[axis] : "?";
}

const char *names_axis_position_unit(int axis)
{
	return axis == ENDOSIM_AXIS_INSERTION ? "m" : "rad";
}

const char *names_axis_force_unit(int axis)
{
	return axis == ENDOSIM_AXIS_INSERTION ? "N" : "N m";
}

int names_axis_find(const char *name)
{
	for (int i = 0; i < ENDOSIM_AXES; i++) {
		if (!strcmp(name, axis_names[i])) {
			return i;
		}
	}
	return -1;
}

const char *names_model(uint32_t model)
{
	return model < COUNT(model_names) ? model_names[model] : "?";
}

const char *names_position(uint32_t position)
{
	return position < COUNT(names_positions) - 1 ? names_positions[position]
						     : "?";
}

/* NAME's index in LIST (NULL after its last), or -1. */
static int find_in(const char *const *list, const char *name)
{
	for (int i = 0; list[i]; i++) {
		if (!strcmp(name, list[i])) {
			return i;
		}
	}
	return -1;
}

int names_position_find(const char *name)
{
	return find_in(names_positions, name);
}

const char *names_tool(uint32_t tool)
{
	return tool < COUNT(names_tools) - 1 ? names_tools[tool] : "?";
}

int names_tool_find(const char *name)
{
	return find_in(names_tools, name);
}

const char *names_polyp_state(uint32_t state)
{
	return state < COUNT(polyp_state_names) ? polyp_state_names[state]
						: "?";
}

const char *names_bleed(uint32_t bleed)
{
	return bleed < COUNT(bleed_names) ? bleed_names[bleed] : "?";
}

const char *names_tool_event(uint32_t bit)
{
	for (size_t i = 0; i < COUNT(tool_event_names); i++) {
		if (bit == 1u << i) {
			return tool_event_names[i];
		}
	}
	return "?";
}

const char *names_pain_cause(uint32_t cause)
{
	return cause < COUNT(pain_cause_names) ? pain_cause_names[cause] : "?";
}

const char *names_sedation(uint32_t sedation)
{
	return sedation < COUNT(names_sedations) - 1 ? names_sedations[sedation]
						     : "?";
}

int names_sedation_find(const char *name)
{
	return find_in(names_sedations, name);
}

const char *names_valves(uint32_t valves)
{
	return valves < COUNT(valves_names) ? valves_names[valves] : "?";
}

uint32_t names_valve_find(const char *name)
{
	for (uint32_t bit = 1; bit < COUNT(valves_names); bit <<= 1) {
		if (!strcmp(name, valves_names[bit])) {
			return bit;
		}
	}
	return 0;
}

const char *names_event(uint32_t kind)
{
	return kind < COUNT(event_names) && event_names[kind] ?
		       event_names[kind] : "unknown";
}

const char *names_drive_status(uint32_t status)
{
	if (!(status & ENDOSIM_DRIVE_PRESENT)) {
		return "gone";
	}
	if (status & ENDOSIM_DRIVE_FAULT) {
		return "fault";
	}
	if (status & ENDOSIM_DRIVE_BUS_ERROR) {
		return "bus-error";
	}
	return status & ENDOSIM_DRIVE_ENABLED ? "on" : "off";
}

const char *names_fault(uint32_t bit)
{
	for (unsigned int i = 0; i < COUNT(fault_names); i++) {
		if (bit == 1u << i) {
			return fault_names[i];
		}
	}
	return "?";
}

char *names_faults(uint32_t fault_bits, char *buf, size_t size)
{
	size_t len = 0;

	buf[0] = '\0';
	for (unsigned int i = 0; i < 32 && len < size; i++) {
		if (fault_bits & (1u << i)) {
			len += (size_t)snprintf(buf + len, size - len, "%s%s",
						len ? "," : "",
						names_fault(1u << i));
		}
	}
	if (!fault_bits) {
		snprintf(buf, size, "none");
	}
	return buf;
}

const char *names_debug_action(int action)
{
	return action > 0 && action < (int)COUNT(debug_action_names)
		       ? debug_action_names[action]
		       : NULL;
}

int names_debug_action_find(const char *name)
{
	for (int i = 1; i < (int)COUNT(debug_action_names); i++) {
		if (!strcmp(name, debug_action_names[i])) {
			return i;
		}
	}
	return -1;
}
