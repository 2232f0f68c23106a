/*
 * names.h - the printable names of the shared enumerations in
 * endosim_shm.h, so that the daemon, endoctl and the viewer say the same.
 * All functions are pure and thread-safe; unknown values give "?".
 */
#ifndef ENDOSIM_NAMES_H
#define ENDOSIM_NAMES_H

#include <stddef.h>
#include <stdint.h>

/* "IDLE", "ENABLED", "ESTOP", "FAULT". */
const char *names_state(uint32_t state);

/* "insertion", "roll", "wheel_ud", "wheel_lr". */
const char *names_axis(int axis);

/* The unit of an axis' position ("m" or "rad") and of its force ("N" or "N m"). */
const char *names_axis_position_unit(int axis);
const char *names_axis_force_unit(int axis);

/* Index of the axis called NAME, or -1. */
int names_axis_find(const char *name);

/* "paper", "rod": [haptics] model's words (enum endosim_model). */
const char *names_model(uint32_t model);

/* Guided replay: "off", "moving", "guiding", "holding", "fading",
 * "taken-over" (enum endosim_guide_phase). */
const char *names_guide_phase(uint32_t phase);

/* Why it ended: "", "stopped", "done", "not-enabled", "lost" (enum
 * endosim_guide_end). */
const char *names_guide_end(uint32_t end);

/* An axis' name, or "" for ENDOSIM_AXES and beyond (none). */
const char *names_guide_axis(uint32_t axis);

/*
 * Where the patient lies (enum endosim_position): "left-lateral",
 * "supine", "right-lateral", "prone"; NAMES_POSITIONS lists them, NULL
 * after the last (the configuration's words for [patient] position).
 */
extern const char *const names_positions[];
const char *names_position(uint32_t position);

/* The position called NAME, or -1. */
int names_position_find(const char *name);

/*
 * The handle's valves (enum endosim_valve bits), as one word: "none",
 * "air", "water", "suction" or several joined by ',' ("air,suction");
 * "?" for bits beyond them.
 */
const char *names_valves(uint32_t valves);

/* The valve bit called NAME ("air", "water", "suction"), or 0. */
uint32_t names_valve_find(const char *name);

/* What hurts (enum endosim_pain_cause): "none", "looping",
 * "straightening", "insufflation", "tip". */
const char *names_pain_cause(uint32_t cause);

/*
 * The patient's sedation (enum endosim_sedation): "none", "minimal",
 * "moderate", "deep"; NAMES_SEDATIONS lists them, NULL after the last.
 */
extern const char *const names_sedations[];
const char *names_sedation(uint32_t sedation);

/* The sedation called NAME, or -1. */
int names_sedation_find(const char *name);

/*
 * The tool in the working channel (enum endosim_tool): "none",
 * "forceps", "snare", "needle", "clip"; NAMES_TOOLS lists them, NULL
 * after the last.
 */
extern const char *const names_tools[];
const char *names_tool(uint32_t tool);

/* The tool called NAME, or -1. */
int names_tool_find(const char *name);

/* A polyp as the tools left it (enum endosim_polyp_state): "in-place",
 * "captured", "cut", "retrieved". */
const char *names_polyp_state(uint32_t state);

/* A polyp's bleeding point (enum endosim_bleed): "none", "bleeding",
 * "clipped", "stopped"; "?" for another. */
const char *names_bleed(uint32_t bleed);

/* One tool event's bit (enum endosim_tool_event): "capture", "release",
 * "cut", "injury", "lift", "bite", "clip", "bleed", "clipped",
 * "stopped", "retrieve"; "?" for another. */
const char *names_tool_event(uint32_t bit);

/*
 * A session event's kind (session_file.h enum session_event_kind) as the
 * CSV says it: "state", "fault", "param", "drops", "note", "position",
 * "hand", "valve", "perforation", "tear", "sedation", "tool"; "unknown" for
 * another.
 */
const char *names_event(uint32_t kind);

/*
 * One word for an axis' drive status bits (enum endosim_drive_status), the
 * worst first: "gone", "fault", "bus-error", "on" (enabled), "off".
 */
const char *names_drive_status(uint32_t status);

/* The short name of one fault bit ("drive", "stale", ...). */
const char *names_fault(uint32_t bit);

/*
 * Writes the names of every bit in FAULT_BITS, comma-separated, into BUF
 * ("none" when zero). Returns BUF.
 */
char *names_faults(uint32_t fault_bits, char *buf, size_t size);

/*
 * A test command's name in endoctl ("clear", "drive-fault", "stale", ...)
 * by its number in endosim.proto's DebugAction (inject.h's enum), or NULL.
 */
const char *names_debug_action(int action);

/* The DebugAction called NAME, or -1. */
int names_debug_action_find(const char *name);

#endif
