/* config.c - see config.h. */
#include "conf/config.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "proto/names.h"
#include "base/log.h"

static const char *const backend_names[] = { "sim", "drives", NULL };
static const char *const drive_names[] = { "sim", "epos4-usb", "modbus",
					   NULL };
static const char *const direction_names[] = { "normal", "reversed", NULL };
static const char *const transport_names[] = { "rtu", "tcp", NULL };
static const char *const parity_names[] = { "none", "even", "odd", NULL };
static const char *const yes_no[] = { "no", "yes", NULL };
static const char *const model_names[] = { "paper", "rod", NULL };
static const char *const gas_names[] = { "air", "co2", NULL };
static const char *const overrun_fault_names[] = { "no", "yes", "auto",
						   NULL };

/* [log] level: a syslog level by name. */
static int level_parse(const struct parse_key *k, const char *text,
		       void *field, struct parse_file *pf, char *why,
		       size_t size)
{
	int level = log_level_parse(text);

	(void)k;
	(void)pf;
	if (level < 0) {
		snprintf(why, size, "'%s' is not one of err, warning, notice, "
			 "info, debug", text);
		return -EINVAL;
	}
	*(int *)field = level;
	return 0;
}

static void level_format(const struct parse_key *k, const void *field,
			 char *buf, size_t size)
{
	(void)k;
	snprintf(buf, size, "%s", log_level_name(*(const int *)field));
}

static const struct parse_ops level_ops = { level_parse, level_format };

/* [modbus.NAME] SIGNAL: a register's description (regspec.h). */
static int register_parse(const struct parse_key *k, const char *text,
			  void *field, struct parse_file *pf, char *why,
			  size_t size)
{
	(void)k;
	(void)pf;
	return regspec_parse(text, field, why, size);
}

static void register_format(const struct parse_key *k, const void *field,
			    char *buf, size_t size)
{
	(void)k;
	regspec_format(field, buf, size);
}

static const struct parse_ops register_ops = { register_parse,
					       register_format };

#define OFF(field) offsetof(struct config, field)
#define KI(sec, key, field, d, lo, hi, u, fl, h) \
	{ .section = sec, .name = key, .type = PARSE_INT, \
	  .offset = OFF(field), .def = d, .min = lo, .max = hi, .unit = u, \
	  .flags = fl, .help = h }
#define KD(sec, key, field, d, lo, hi, u, fl, h) \
	{ .section = sec, .name = key, .type = PARSE_DOUBLE, \
	  .offset = OFF(field), .def = d, .min = lo, .max = hi, .unit = u, \
	  .flags = fl, .help = h }
#define KS(sec, key, field, d, fl, h) \
	{ .section = sec, .name = key, .type = PARSE_STRING, \
	  .offset = OFF(field), .size = CONFIG_STR, .def_str = d, .unit = "", \
	  .flags = fl, .help = h }
#define KE(sec, key, field, d, ch, fl, h) \
	{ .section = sec, .name = key, .type = PARSE_CHOICE, \
	  .offset = OFF(field), .def = d, .choices = ch, .unit = "", \
	  .flags = fl, .help = h }
#define KL(sec, key, field, d, fl, h) \
	{ .section = sec, .name = key, .type = PARSE_CUSTOM, \
	  .offset = OFF(field), .def_str = d, .ops = &level_ops, .unit = "", \
	  .flags = fl, .help = h }
#define KR(sec, key, field, h) \
	{ .section = sec, .name = key, .type = PARSE_CUSTOM, \
	  .offset = OFF(field), .def_str = "none", .ops = &register_ops, \
	  .unit = "", .help = h }

#define I_INS ENDOSIM_AXIS_INSERTION
#define I_ROLL ENDOSIM_AXIS_ROLL
#define I_UD ENDOSIM_AXIS_WHEEL_UD
#define I_LR ENDOSIM_AXIS_WHEEL_LR
#define LIVE CONFIG_LIVE

/* [axis.NAME]: how motor turns and encoder counts map to axis I. */
#define AXIS_KEYS(sec, i)                                                    \
	KE(sec, "backend", axis[i].backend, CONFIG_DRIVE_SIM, drive_names, 0, \
	   "sim, epos4-usb or modbus (when [rig] backend = drives)"),        \
	KD(sec, "gear_ratio", axis[i].gear_ratio, 1.0, 0.001, 1000, "", 0,   \
	   "motor turns per turn of the output"),                            \
	KI(sec, "counts_per_rev", axis[i].counts_per_rev, 2048, 1, 1 << 30,  \
	   "counts", 0, "encoder counts per motor turn (quadrature counted)"), \
	KE(sec, "direction", axis[i].reversed, 0, direction_names, 0,        \
	   "normal, or reversed: motor positive is axis negative")

/* [guide]: one axis' guidance; AX its key's name, F and Q its force and
 * position units in key names (n, n_m; m, rad) and in words */
#define GUIDE_KEYS(ax, i, f, q, fw, qw, k, b, fmax, vmax, push, err)          \
	KD("guide", ax "_stiffness_" f "_per_" q, guide.stiffness[i], k, 0, \
	   1e6, fw "/" qw, LIVE, "k: the pull towards the reference"),     \
	KD("guide", ax "_damping_" f "_s_per_" q, guide.damping[i], b, 0,  \
	   1e4, fw " s/" qw, LIVE, "b: on the speed's difference from "    \
	   "the reference's"),                                              \
	KD("guide", ax "_force_max_" f, guide.force_max[i], fmax, 0, 100,  \
	   fw, LIVE, "the guidance's force at most (within [limits])"),    \
	KD("guide", ax "_speed_max_" q "_s", guide.speed_max[i], vmax,      \
	   1e-4, 100, qw "/s", LIVE, "the reference never moves faster: "  \
	   "a faster recording is slowed"),                                 \
	KD("guide", ax "_takeover_" f, guide.takeover[i], push, 0, 100, fw, \
	   LIVE, "a hand pushing so hard against the guidance takes over"), \
	KD("guide", ax "_error_max_" q, guide.error_max[i], err, 1e-4, 10, \
	   qw, LIVE, "tracking error beyond this for error_s: the guidance " \
	   "cannot follow and ends")

/* [epos4.NAME]: the maxon EPOS4 on USB that drives axis I. */
#define EPOS4_KEYS(sec, i)                                                   \
	KI(sec, "vid", epos4[i].vid, 0x24E7, 0, 0xFFFF, "", PARSE_HEX,     \
	   "USB vendor id"),                                                 \
	KI(sec, "pid", epos4[i].pid, 0x3B01, 0, 0xFFFF, "", PARSE_HEX,     \
	   "USB product id"),                                                \
	KS(sec, "serial", epos4[i].serial, "", 0,                            \
	   "USB serial number; empty: the only drive with that id"),          \
	KI(sec, "node_id", epos4[i].node_id, 1, 0, 127, "", 0,               \
	   "the drive's node-ID"),                                           \
	KD(sec, "timeout_s", epos4[i].timeout_s, 0.1, 0.001, 5, "s", 0,      \
	   "longest wait for one USB transfer"),                             \
	KD(sec, "feedback_max_age_s", epos4[i].feedback_max_age_s, 0.1,     \
	   0.001, 2, "s", 0, "feedback older than this is a fault"),         \
	KD(sec, "max_rate_hz", epos4[i].max_rate_hz, 1000, 1, 1e5, "Hz", 0, \
	   "exchanges per second at most (the bus may allow fewer)"),         \
	KD(sec, "rated_torque_unit_n_m", epos4[i].rated_torque_unit_n_m,     \
	   1e-6, 1e-9, 1, "N m", 0,                                          \
	   "what one unit of the rated torque 0x6076 is (EPOS4: 1 uN m)"),   \
	KD(sec, "watchdog_s", epos4[i].watchdog_s, 0.1, 0, 65.535, "s", 0,   \
	   "heartbeat consumer time 0x1016:01 written at enable: the drive " \
	   "faults when the daemon falls silent this long; 0: off"),         \
	KI(sec, "valve_air_bit", epos4[i].valve_bit[0], -1, -1, 31, "", 0,  \
	   "the bit of digital inputs 0x60FD set while the air/water valve " \
	   "is covered (air); -1: not on this drive"),                        \
	KI(sec, "valve_water_bit", epos4[i].valve_bit[1], -1, -1, 31, "", 0, \
	   "the bit of 0x60FD set while the air/water valve is pressed "      \
	   "(water); -1: not on this drive"),                                 \
	KI(sec, "valve_suction_bit", epos4[i].valve_bit[2], -1, -1, 31, "",  \
	   0, "the bit of 0x60FD set while the suction valve is pressed; "   \
	   "-1: not on this drive"),                                          \
	KI(sec, "tool_depth_sensor", epos4[i].tool_depth_sensor, 0, 0, 3, "", \
	   0, "the subindex of 0x60E4 (the drive's sensor 1..3) counting "   \
	   "the tool's depth; 0: not on this drive"),                        \
	KD(sec, "tool_m_per_count", epos4[i].tool_m_per_count, 1e-5, -1, 1,  \
	   "m", 0, "the tool's depth per count of that sensor (negative: "   \
	   "counting down as the tool goes in)"),                            \
	KD(sec, "tool_depth_offset_m", epos4[i].tool_depth_offset_m, 0, -2,  \
	   2, "m", 0, "the tool's depth beyond the channel's exit at count " \
	   "0"),                                                             \
	KI(sec, "tool_opening_input", epos4[i].tool_opening_input, 0, 0, 2,  \
	   "", 0, "the analogue input (0x3160:N, mV) wired to the tool's "   \
	   "handle, 1 or 2; 0: not on this drive"),                          \
	KD(sec, "tool_closed_mv", epos4[i].tool_closed_mv, 0, -10000, 10000, \
	   "mV", 0, "that input with the tool's handle closed"),             \
	KD(sec, "tool_open_mv", epos4[i].tool_open_mv, 5000, -10000, 10000,  \
	   "mV", 0, "that input with the tool's handle open"),               \
	KI(sec, "tool_pedal_bit", epos4[i].tool_pedal_bit, -1, -1, 31, "", 0, \
	   "the bit of 0x60FD set while the cautery's foot pedal is down; "  \
	   "-1: not on this drive")

/* [modbus.NAME]: the Modbus wheel drive of axis I and its register map. */
#define MODBUS_DRIVE_KEYS(sec, i)                                            \
	KI(sec, "slave", modbus_drive[i].slave, 1, 0, 255, "", 0,            \
	   "slave id (RTU 1..247; TCP unit id)"),                            \
	KE(sec, "combined_0x17", modbus_drive[i].combined_0x17, 0, yes_no, 0, \
	   "write torque and read feedback in one transaction (function 0x17)"), \
	KD(sec, "watchdog_s", modbus_drive[i].watchdog_s, 0.1, 0, 60, "s", 0, \
	   "written to the watchdog register at enable"),                    \
	KR(sec, "torque", modbus_drive[i].reg[REGSPEC_TORQUE],                \
	   "motor torque setpoint, N m (required)"),                         \
	KR(sec, "enable", modbus_drive[i].reg[REGSPEC_ENABLE],                \
	   "written 1 to enable, 0 to disable"),                             \
	KR(sec, "position", modbus_drive[i].reg[REGSPEC_POSITION],            \
	   "encoder counts (required)"),                                     \
	KR(sec, "velocity", modbus_drive[i].reg[REGSPEC_VELOCITY],            \
	   "encoder counts per second"),                                     \
	KR(sec, "fault", modbus_drive[i].reg[REGSPEC_FAULT],                  \
	   "the drive's fault code, 0: none"),                               \
	KR(sec, "fault_reset", modbus_drive[i].reg[REGSPEC_FAULT_RESET],      \
	   "written 1 then 0 to clear a fault"),                             \
	KR(sec, "watchdog", modbus_drive[i].reg[REGSPEC_WATCHDOG],            \
	   "communication watchdog, s (gets watchdog_s)"),                   \
	KR(sec, "valve_air", modbus_drive[i].reg[REGSPEC_VALVE_AIR],          \
	   "not 0 while the air/water valve is covered (air): an input, "    \
	   "e.g. discrete 0x0010"),                                          \
	KR(sec, "valve_water", modbus_drive[i].reg[REGSPEC_VALVE_WATER],      \
	   "not 0 while the air/water valve is pressed (water)"),            \
	KR(sec, "valve_suction", modbus_drive[i].reg[REGSPEC_VALVE_SUCTION],  \
	   "not 0 while the suction valve is pressed"),                      \
	KR(sec, "tool_depth", modbus_drive[i].reg[REGSPEC_TOOL_DEPTH],        \
	   "the tool's depth beyond the working channel's exit, m: an "     \
	   "encoder's count, e.g. input 0x0020 i32 scale=1e-5"),            \
	KR(sec, "tool_opening", modbus_drive[i].reg[REGSPEC_TOOL_OPENING],    \
	   "the tool's handle, 0 closed .. 1 open: an analogue input, e.g. " \
	   "input 0x0022 u16 scale=0.0002"),                                 \
	KR(sec, "tool_pedal", modbus_drive[i].reg[REGSPEC_TOOL_PEDAL],        \
	   "not 0 while the cautery's foot pedal is down, e.g. discrete "    \
	   "0x0013")

static const struct parse_key keys[] = {
	KI("loop", "rate_hz", loop.rate_hz, 1000, 100, 10000, "Hz", 0,
	   "force-loop rate"),
	KI("loop", "priority", loop.priority, 80, 1, 99, "", 0,
	   "SCHED_FIFO priority of the force loop"),
	KI("loop", "cpu", loop.cpu, -1, -1, 1023, "", 0,
	   "CPU the force loop is pinned to; -1: not pinned"),
	KI("loop", "cpu_dma_latency_us", loop.cpu_dma_latency_us, 0, -1, 100000,
	   "us", 0, "hold /dev/cpu_dma_latency at this while running (keeps "
	   "CPUs out of deep idle states); -1: leave alone"),
	KI("loop", "overrun_budget", loop.overrun_budget, 50, 1,
	   CONFIG_OVERRUN_BUDGET_MAX, "periods", 0, "more periods skipped than this "
	   "within overrun_window_s misses the budget (see overrun_fault)"),
	KD("loop", "overrun_window_s", loop.overrun_window_s, 1.0, 0.01, 60,
	   "s", 0, "the window of overrun_budget"),
	KE("loop", "overrun_fault", loop.overrun_fault, CONFIG_OVERRUN_AUTO,
	   overrun_fault_names, 0, "a missed overrun budget is a fault (yes), "
	   "a warning (no), or auto: a fault when any axis is a real drive"),

	KE("rig", "backend", rig.backend, CONFIG_BACKEND_SIM, backend_names, 0,
	   "sim: every axis simulated; drives: as each [axis.*] says"),
	KD("rig", "insertion_min_m", rig.travel_min[I_INS], 0.0, -1, 3, "m", 0,
	   "carriage travel, withdrawn end"),
	KD("rig", "insertion_max_m", rig.travel_max[I_INS], 1.8, -1, 3, "m", 0,
	   "carriage travel, inserted end"),
	KD("rig", "roll_min_rad", rig.travel_min[I_ROLL], -6.2832, -100, 100,
	   "rad", 0, "tube roll travel, counter-clockwise end"),
	KD("rig", "roll_max_rad", rig.travel_max[I_ROLL], 6.2832, -100, 100,
	   "rad", 0, "tube roll travel, clockwise end"),
	KD("rig", "wheel_ud_min_rad", rig.travel_min[I_UD], -1.75, -10, 10,
	   "rad", 0, "up/down wheel travel, one end"),
	KD("rig", "wheel_ud_max_rad", rig.travel_max[I_UD], 1.75, -10, 10,
	   "rad", 0, "up/down wheel travel, other end"),
	KD("rig", "wheel_lr_min_rad", rig.travel_min[I_LR], -1.75, -10, 10,
	   "rad", 0, "left/right wheel travel, one end"),
	KD("rig", "wheel_lr_max_rad", rig.travel_max[I_LR], 1.75, -10, 10,
	   "rad", 0, "left/right wheel travel, other end"),
	KD("rig", "feedback_max_age_s", rig.feedback_max_age_s, 0.05, 0.001,
	   1.0, "s", 0, "feedback older than this is a fault"),

	KD("sim", "insertion_mass_kg", sim.inertia[I_INS], 0.5, 0.01, 100,
	   "kg", 0, "moving mass of carriage and tube"),
	KD("sim", "roll_inertia_kg_m2", sim.inertia[I_ROLL], 2e-4, 1e-7, 1,
	   "kg m^2", 0, "inertia of the tube in roll"),
	KD("sim", "wheel_ud_inertia_kg_m2", sim.inertia[I_UD], 2e-5, 1e-8, 1,
	   "kg m^2", 0, "inertia of the up/down wheel"),
	KD("sim", "wheel_lr_inertia_kg_m2", sim.inertia[I_LR], 2e-5, 1e-8, 1,
	   "kg m^2", 0, "inertia of the left/right wheel"),
	KD("sim", "insertion_viscous_n_s_per_m", sim.viscous[I_INS], 2.0, 0,
	   1000, "N s/m", 0, "viscous friction of the carriage"),
	KD("sim", "roll_viscous_n_m_s_per_rad", sim.viscous[I_ROLL], 2e-3, 0,
	   10, "N m s/rad", 0, "viscous friction in roll"),
	KD("sim", "wheel_ud_viscous_n_m_s_per_rad", sim.viscous[I_UD], 1e-4, 0,
	   10, "N m s/rad", 0, "viscous friction of the up/down wheel"),
	KD("sim", "wheel_lr_viscous_n_m_s_per_rad", sim.viscous[I_LR], 1e-4, 0,
	   10, "N m s/rad", 0, "viscous friction of the left/right wheel"),
	KD("sim", "insertion_coulomb_n", sim.coulomb[I_INS], 0.3, 0, 100, "N",
	   0, "dry friction of the carriage"),
	KD("sim", "roll_coulomb_n_m", sim.coulomb[I_ROLL], 2e-3, 0, 10, "N m",
	   0, "dry friction in roll"),
	KD("sim", "wheel_ud_coulomb_n_m", sim.coulomb[I_UD], 5e-4, 0, 10, "N m",
	   0, "dry friction of the up/down wheel"),
	KD("sim", "wheel_lr_coulomb_n_m", sim.coulomb[I_LR], 5e-4, 0, 10, "N m",
	   0, "dry friction of the left/right wheel"),
	KD("sim", "hand_insertion_stiffness_n_per_m", sim.hand_stiffness[I_INS],
	   400, 0, 1e5, "N/m", 0, "scripted hand: grip stiffness, insertion"),
	KD("sim", "hand_roll_stiffness_n_m_per_rad", sim.hand_stiffness[I_ROLL],
	   0.5, 0, 100, "N m/rad", 0, "scripted hand: grip stiffness, roll"),
	KD("sim", "hand_wheel_ud_stiffness_n_m_per_rad",
	   sim.hand_stiffness[I_UD], 1.0, 0, 10, "N m/rad", 0,
	   "scripted hand: thumb stiffness, up/down wheel"),
	KD("sim", "hand_wheel_lr_stiffness_n_m_per_rad",
	   sim.hand_stiffness[I_LR], 1.0, 0, 10, "N m/rad", 0,
	   "scripted hand: thumb stiffness, left/right wheel"),
	KD("sim", "hand_insertion_damping_n_s_per_m", sim.hand_damping[I_INS],
	   40, 0, 1e4, "N s/m", 0, "scripted hand: damping, insertion"),
	KD("sim", "hand_roll_damping_n_m_s_per_rad", sim.hand_damping[I_ROLL],
	   0.02, 0, 100, "N m s/rad", 0, "scripted hand: damping, roll"),
	KD("sim", "hand_wheel_ud_damping_n_m_s_per_rad", sim.hand_damping[I_UD],
	   0.01, 0, 10, "N m s/rad", 0, "scripted hand: damping, up/down wheel"),
	KD("sim", "hand_wheel_lr_damping_n_m_s_per_rad", sim.hand_damping[I_LR],
	   0.01, 0, 10, "N m s/rad", 0,
	   "scripted hand: damping, left/right wheel"),
	KD("sim", "hand_insertion_max_n", sim.hand_max[I_INS], 40, 0, 200, "N",
	   0, "strongest push or pull of the hand"),
	KD("sim", "hand_roll_max_n_m", sim.hand_max[I_ROLL], 1.0, 0, 10, "N m",
	   0, "strongest twist of the hand"),
	KD("sim", "hand_wheel_ud_max_n_m", sim.hand_max[I_UD], 0.3, 0, 10,
	   "N m", 0, "strongest thumb torque on the up/down wheel"),
	KD("sim", "hand_wheel_lr_max_n_m", sim.hand_max[I_LR], 0.3, 0, 10,
	   "N m", 0, "strongest thumb torque on the left/right wheel"),
	KD("sim", "hand_insertion_max_speed_m_s", sim.hand_max_speed[I_INS],
	   1.5, 0.01, 100, "m/s", 0, "the hand's push fades to nothing at "
	   "this speed (a muscle's force-velocity limit)"),
	KD("sim", "hand_roll_max_speed_rad_s", sim.hand_max_speed[I_ROLL], 15,
	   0.01, 1000, "rad/s", 0, "the hand's twist fades to nothing at "
	   "this speed"),
	KD("sim", "hand_wheel_ud_max_speed_rad_s", sim.hand_max_speed[I_UD],
	   15, 0.01, 1000, "rad/s", 0, "the thumb fades to nothing at this "
	   "speed, up/down wheel"),
	KD("sim", "hand_wheel_lr_max_speed_rad_s", sim.hand_max_speed[I_LR],
	   15, 0.01, 1000, "rad/s", 0, "the thumb fades to nothing at this "
	   "speed, left/right wheel"),
	KD("sim", "hand_hold_s", sim.hand_hold_s, 0.25, 0.01, 10, "s", 0,
	   "live hand input holds this long unless refreshed"),
	KD("sim", "grip_insertion_max_n", sim.grip_max[I_INS], 20, 0, 200, "N",
	   0, "the hand holds the shaft where the trainee left it (the "
	   "hand's stiffness) up to this force, then it slips"),
	KD("sim", "grip_roll_max_n_m", sim.grip_max[I_ROLL], 0.5, 0, 10, "N m",
	   0, "the same for the shaft's roll"),
	KD("sim", "grip_wheel_ud_max_n_m", sim.grip_max[I_UD], 0.3, 0, 10,
	   "N m", 0, "the thumb's hold on the up/down wheel"),
	KD("sim", "grip_wheel_lr_max_n_m", sim.grip_max[I_LR], 0.3, 0, 10,
	   "N m", 0, "the thumb's hold on the left/right wheel"),

	KS("socket", "directory", socket.directory, "/run/endosim", 0,
	   "where status.sock (read-only) and control.sock live"),
	KS("socket", "group", socket.group, "", 0,
	   "group owning control.sock; empty: the daemon's group"),
	KI("socket", "max_request_bytes", socket.max_request_bytes, 65536, 256,
	   1 << 24, "bytes", 0, "largest request accepted"),
	KI("socket", "max_clients", socket.max_clients, 32, 1, 1024, "", 0,
	   "connections served at once"),
	KI("socket", "max_queued_bytes", socket.max_queued_bytes, 4 << 20,
	   1 << 16, 1 << 26, "bytes", 0,
	   "unsent replies held per client before it is disconnected"),
	KD("socket", "idle_timeout_s", socket.idle_timeout_s, 60, 1, 86400, "s",
	   0, "a client that sends nothing this long is disconnected "
	   "(subscribers excepted)"),
	KD("socket", "partial_timeout_s", socket.partial_timeout_s, 5, 0.1,
	   3600, "s", 0, "a request begun but not finished within this is "
	   "dropped with its connection"),

	KS("shm", "name", shm.name, ENDOSIM_SHM_DEFAULT_NAME, 0,
	   "POSIX shared-memory object holding the published state"),

	KD("limits", "insertion_max_force_n", limits.max[I_INS], 45, 0, 100,
	   "N", LIVE, "largest force on the carriage, either way"),
	KD("limits", "roll_max_torque_n_m", limits.max[I_ROLL], 1.0, 0, 5,
	   "N m", LIVE, "largest torque on the tube, either way"),
	KD("limits", "wheel_ud_max_torque_n_m", limits.max[I_UD], 0.1, 0, 1,
	   "N m", LIVE, "largest torque on the up/down wheel"),
	KD("limits", "wheel_lr_max_torque_n_m", limits.max[I_LR], 0.1, 0, 1,
	   "N m", LIVE, "largest torque on the left/right wheel"),
	KD("limits", "enable_ramp_s", limits.enable_ramp_s, 1.0, 0, 10, "s",
	   LIVE, "after enable, forces rise from nothing to full over this"),
	KD("limits", "insertion_max_speed_m_s", limits.max_speed[I_INS], 2.0,
	   0.01, 100, "m/s", 0, "a faster carriage is a runaway: a fault"),
	KD("limits", "roll_max_speed_rad_s", limits.max_speed[I_ROLL], 30,
	   0.01, 1000, "rad/s", 0, "a faster roll is a runaway: a fault"),
	KD("limits", "wheel_ud_max_speed_rad_s", limits.max_speed[I_UD], 30,
	   0.01, 1000, "rad/s", 0, "a faster up/down wheel is a runaway"),
	KD("limits", "wheel_lr_max_speed_rad_s", limits.max_speed[I_LR], 30,
	   0.01, 1000, "rad/s", 0, "a faster left/right wheel is a runaway"),
	KD("limits", "travel_margin_fraction", limits.travel_margin, 0.02, 0,
	   100, "", 0, "a position beyond either end of [rig] travel by more "
	   "than this share of it is a fault"),
	KD("limits", "saturation_s", limits.saturation_s, 5, 0.01, 3600, "s",
	   0, "a force held beyond its limit longer than this, torque on, is "
	   "a fault (see saturation_fault)"),
	KE("limits", "saturation_fault", limits.saturation_fault,
	   CONFIG_OVERRUN_AUTO, overrun_fault_names, 0, "a force held beyond "
	   "its limit too long: a fault (yes), a warning (no); auto: a fault "
	   "where a real drive turns the axis"),

	KD("limits", "insertion_slew_n_per_s", limits.slew[I_INS], 4000, 1,
	   1e6, "N/s", LIVE, "fastest change of the carriage force"),
	KD("limits", "roll_slew_n_m_per_s", limits.slew[I_ROLL], 100, 0.01,
	   1e5, "N m/s", LIVE, "fastest change of the tube torque"),
	KD("limits", "wheel_ud_slew_n_m_per_s", limits.slew[I_UD], 20, 0.01,
	   1e5, "N m/s", LIVE, "fastest change of the up/down wheel torque"),
	KD("limits", "wheel_lr_slew_n_m_per_s", limits.slew[I_LR], 20, 0.01,
	   1e5, "N m/s", LIVE, "fastest change of the left/right wheel torque"),

	KE("haptics", "model", haptics.model, HAPTICS_DEFAULT_MODEL,
	   model_names, 0,
	   "rod: the insertion tube an elastic rod in a colon that moves "
	   "([rod]); paper: the tube on the centreline (Koerner and Maenner)"),
	KD("haptics", "scope_radius_m", haptics.scope_radius_m, SCOPE_RADIUS_M,
	   0, 0.02, "m", 0, "radius of the scope's tip and tube: how far from "
	   "the wall its centre stays"),
	KD("haptics", "wall_stiffness_n_per_m", haptics.wall_stiffness_n_per_m,
	   HAPTICS_DEFAULT_WALL_STIFFNESS_N_PER_M, 0, 20000, "N/m", LIVE,
	   "k_wall: the colon wall's spring against the tip"),
	KD("haptics", "wall_damping_n_s_per_m", haptics.wall_damping_n_s_per_m,
	   HAPTICS_DEFAULT_WALL_DAMPING_N_S_PER_M, 0, 500, "N s/m", LIVE,
	   "damping of the tip's penetration velocity while in contact"),
	KD("haptics", "tip_lateral_stiffness_n_per_m",
	   haptics.tip_lateral_stiffness_n_per_m,
	   HAPTICS_DEFAULT_TIP_LATERAL_STIFFNESS_N_PER_M, 1, 100000, "N/m",
	   LIVE, "how hard the bending section resists the wall pushing its "
	   "side"),
	KE("haptics", "force_shading", haptics.force_shading,
	   HAPTICS_DEFAULT_FORCE_SHADING, yes_no, LIVE,
	   "contact force along interpolated normals (no facet buzz)"),
	KD("haptics", "contact_reach_m", haptics.contact_reach_m,
	   HAPTICS_DEFAULT_CONTACT_REACH_M, 0.01, 0.5, "m", LIVE,
	   "the stretch of colon around the tip whose triangles are contact "
	   "candidates"),
	KD("haptics", "entry_depth_m", haptics.entry_depth_m,
	   HAPTICS_DEFAULT_ENTRY_DEPTH_M, 0, 0.5, "m", LIVE,
	   "the tip touches the wall from this insertion on"),
	KD("haptics", "friction_n_s_per_m_rad", haptics.friction_n_s_per_m_rad,
	   HAPTICS_DEFAULT_FRICTION_N_S_PER_M_RAD, 0, 1000, "N s/(m rad)",
	   LIVE, "c_f: insertion friction per speed and per rad of the tube's "
	   "turning"),
	KD("haptics", "torsion_n_m_s_per_rad2", haptics.torsion_n_m_s_per_rad2,
	   HAPTICS_DEFAULT_TORSION_N_M_S_PER_RAD2, 0, 10, "N m s/rad^2", LIVE,
	   "roll friction per roll speed and per rad of the tube's turning"),
	KD("haptics", "wire_spacing_m", haptics.wire_spacing_m,
	   SCOPE_WIRE_SPACING_M, 0, 0.05, "m", LIVE,
	   "dr: distance between a wheel's two Bowden wires"),
	KD("haptics", "wire_tension_n_m_per_m", haptics.wire_tension_n_m_per_m,
	   HAPTICS_DEFAULT_WIRE_TENSION_N_M_PER_M, 0, 1000, "N m/m", LIVE,
	   "k_t: wheel torque per metre of wire length difference"),
	KD("haptics", "bending_stiffness_n_m_per_rad",
	   haptics.bending_stiffness_n_m_per_rad,
	   HAPTICS_DEFAULT_BENDING_STIFFNESS_N_M_PER_RAD, 0, 10, "N m/rad",
	   LIVE, "the bending section springing back straight, per rad of "
	   "tip bend"),
	KD("haptics", "wheel_stop_stiffness_n_m_per_rad",
	   haptics.stop_stiffness_n_m_per_rad,
	   HAPTICS_DEFAULT_STOP_STIFFNESS_N_M_PER_RAD, 0, 100, "N m/rad", LIVE,
	   "each knob's end at the tip's angulation limit: its spring per rad "
	   "of wheel past the limit"),
	KD("haptics", "wheel_stop_damping_n_m_s_per_rad",
	   haptics.stop_damping_n_m_s_per_rad,
	   HAPTICS_DEFAULT_STOP_DAMPING_N_M_S_PER_RAD, 0, 1, "N m s/rad", LIVE,
	   "each knob's end: its damping while the wheel is past the limit"),
	KD("haptics", "wheel_delay_s", haptics.wheel_delay_s,
	   HAPTICS_DEFAULT_WHEEL_DELAY_S, 0, 0.05, "s", LIVE,
	   "a wheel on a drive: the lag of its torque (feedback age, the "
	   "command's way); limits the wall on it"),
	KD("haptics", "loop_relax_s", haptics.loop_relax_s,
	   HAPTICS_DEFAULT_LOOP_RELAX_S, 0.001, 10, "s", LIVE,
	   "time constant with which a loop follows its force balance"),
	KD("haptics", "insertion_damping_n_s_per_m", haptics.damping[I_INS],
	   HAPTICS_DEFAULT_INSERTION_DAMPING_N_S_PER_M, 0, 100, "N s/m", LIVE,
	   "light virtual damping of the carriage"),
	KD("haptics", "roll_damping_n_m_s_per_rad", haptics.damping[I_ROLL],
	   HAPTICS_DEFAULT_ROLL_DAMPING_N_M_S_PER_RAD, 0, 1, "N m s/rad", LIVE,
	   "light virtual damping in roll"),
	KD("haptics", "wheel_ud_damping_n_m_s_per_rad", haptics.damping[I_UD],
	   HAPTICS_DEFAULT_WHEEL_DAMPING_N_M_S_PER_RAD, 0, 1, "N m s/rad",
	   LIVE, "light virtual damping of the up/down wheel"),
	KD("haptics", "wheel_lr_damping_n_m_s_per_rad", haptics.damping[I_LR],
	   HAPTICS_DEFAULT_WHEEL_DAMPING_N_M_S_PER_RAD, 0, 1, "N m s/rad",
	   LIVE, "light virtual damping of the left/right wheel"),
	KE("haptics", "passivity", haptics.passivity, HAPTICS_DEFAULT_PASSIVITY,
	   yes_no, LIVE,
	   "passivity observer and controller on the contact forces"),

	KI("rod", "segments", rod.segments, ROD_DEFAULT_SEGMENTS, 8, 1024, "",
	   0, "rigid segments of the insertion tube (cost grows linearly)"),
	KD("rod", "length_m", rod.length_m, ROD_DEFAULT_LENGTH_M, 0.5, 3, "m",
	   0, "the insertion tube's length: the deepest insertion"),
	KD("rod", "mass_per_m_kg", rod.mass_per_m_kg, ROD_DEFAULT_MASS_PER_M_KG,
	   0.01, 10, "kg/m", 0, "the insertion tube's mass per length"),
	KD("rod", "bending_n_m2", rod.bending_n_m2, ROD_DEFAULT_BENDING_N_M2,
	   1e-4, 10, "N m^2", LIVE,
	   "EI of the insertion tube (colonoscopes 0.026-0.040)"),
	KD("rod", "torsion_n_m2", rod.torsion_n_m2, ROD_DEFAULT_TORSION_N_M2,
	   1e-4, 100, "N m^2", LIVE,
	   "GJ of the insertion tube (68-88 N cm^2/deg: 0.39-0.50)"),
	KD("rod", "tip_bending_n_m2", rod.tip_bending_n_m2,
	   RODSCOPE_DEFAULT_TIP_BENDING_N_M2, 1e-4, 10, "N m^2", LIVE,
	   "EI of the bending section, its wires held"),
	KD("rod", "damping_s", rod.damping_s, ROD_DEFAULT_DAMPING_S, 0, 1, "s",
	   0, "the tube's internal damping: Kelvin-Voigt time of its bending "
	   "and twist"),
	KD("rod", "drag_n_s_per_m2", rod.drag_n_s_per_m2,
	   ROD_DEFAULT_DRAG_N_S_PER_M2, 0, 1000, "N s/m^2", 0,
	   "viscous drag on the tube per length and speed"),
	KI("rod", "iterations", rod.iterations, ROD_DEFAULT_ITERATIONS, 2, 8,
	   "", 0, "Newton iterations of the rod's solve per step"),
	KD("rod", "wall_n_per_m2", rod.wall_n_per_m2,
	   LUMEN_DEFAULT_WALL_N_PER_M2, 1e3, 1e7, "N/m^2", LIVE,
	   "the colon wall's stiffness against the tube, per metre of tube"),
	KD("rod", "wall_damping_s", rod.wall_damping_s,
	   LUMEN_DEFAULT_WALL_DAMPING_S, 0, 1, "s", LIVE,
	   "the wall's damping: its Kelvin-Voigt time"),
	KD("rod", "friction", rod.friction, LUMEN_DEFAULT_FRICTION, 0, 2, "",
	   LIVE, "mu: Coulomb friction of the tube on the mucosa"),
	KD("rod", "slip_m_per_s", rod.slip_m_per_s, LUMEN_DEFAULT_SLIP_M_PER_S,
	   1e-5, 1, "m/s", LIVE, "below this sliding speed the tube sticks "
	   "(friction regularised)"),
	KD("rod", "pipe_n_per_m2", rod.pipe_n_per_m2,
	   LUMEN_DEFAULT_PIPE_N_PER_M2, 1e3, 1e8, "N/m^2", LIVE,
	   "the rig's slitted pipe holding the tube outside, per metre"),
	KD("rod", "coupling_n_per_m", rod.coupling_n_per_m,
	   RODSCOPE_DEFAULT_COUPLING_N_PER_M, 10, 1e6, "N/m", LIVE,
	   "the carriage's hold on the tube's end along the pipe"),
	KD("rod", "coupling_n_s_per_m", rod.coupling_n_s_per_m,
	   RODSCOPE_DEFAULT_COUPLING_N_S_PER_M, 0, 1e4, "N s/m", LIVE,
	   "its damping"),
	KD("rod", "roll_n_m_per_rad", rod.roll_n_m_per_rad,
	   RODSCOPE_DEFAULT_ROLL_N_M_PER_RAD, 0.01, 1e3, "N m/rad", LIVE,
	   "the carriage's hold on the tube's end in roll"),
	KD("rod", "roll_n_m_s_per_rad", rod.roll_n_m_s_per_rad,
	   RODSCOPE_DEFAULT_ROLL_N_M_S_PER_RAD, 0, 10, "N m s/rad", LIVE,
	   "its damping"),
	KD("rod", "stop_n_per_m", rod.stop_n_per_m,
	   RODSCOPE_DEFAULT_STOP_N_PER_M, 0, 1e6, "N/m", LIVE,
	   "the handle at the anus: inserted past the tube's length"),
	KD("rod", "colon_node_spacing_m", rod.colon_node_spacing_m,
	   FLEX_DEFAULT_NODE_SPACING_M, 0.005, 0.2, "m", 0,
	   "the mobile colon's nodes, this far apart"),
	KD("rod", "colon_damping_n_s_per_m", rod.colon_damping_n_s_per_m,
	   FLEX_DEFAULT_DAMPING_N_S_PER_M, 0.1, 1e5, "N s/m", LIVE,
	   "the tissue's damping per node"),
	KD("rod", "colon_chain_n_per_m", rod.colon_chain_n_per_m,
	   FLEX_DEFAULT_CHAIN_N_PER_M, 0, 1e5, "N/m", LIVE,
	   "the colon's continuity between its nodes"),
	KD("rod", "colon_bending_n_per_m", rod.colon_bending_n_per_m,
	   FLEX_DEFAULT_BENDING_N_PER_M, 0, 1e6, "N/m", LIVE,
	   "the colon wall's resistance to crumpling between its nodes"),
	KD("rod", "colon_mass_per_m_kg", rod.colon_mass_per_m_kg,
	   FLEX_DEFAULT_MASS_PER_M_KG, 0, 10, "kg/m", LIVE,
	   "the mobile colon's mass with its contents, per metre: gravity "
	   "sags it on its mesentery"),

	KE("patient", "enabled", patient.enabled, PATIENT_DEFAULT_ENABLED,
	   yes_no, 0,
	   "yes: a patient around the colon (gas, gravity, fluid, the "
	   "assistant's hand, the lens); no: the case's lumen, always open"),
	KE("patient", "gas", patient.gas, GAS_AIR, gas_names, LIVE,
	   "what the pump blows in: air, or co2 (absorbed far faster)"),
	KE("patient", "position", patient.position, POSTURE_LEFT_LATERAL,
	   names_positions, 0, "where the patient lies at the start: "
	   "left-lateral, supine, right-lateral or prone"),
	KD("patient", "turn_s", patient.turn_s, PATIENT_DEFAULT_TURN_S, 0, 60,
	   "s", LIVE, "a change of position takes this long"),
	KD("patient", "pump_m3_per_s", patient.pump_m3_per_s,
	   GAS_DEFAULT_PUMP_M3_PER_S, 0, 1e-3, "m^3/s", LIVE,
	   "the pump's flow while the air/water valve is covered (2 L/min: "
	   "3.33e-5)"),
	KD("patient", "suction_m3_per_s", patient.suction_m3_per_s,
	   GAS_DEFAULT_SUCTION_M3_PER_S, 0, 1e-3, "m^3/s", LIVE,
	   "gas the suction valve takes out, the tip in gas"),
	KD("patient", "suction_fluid_m3_per_s", patient.suction_fluid_m3_per_s,
	   FLUID_DEFAULT_SUCTION_M3_PER_S, 0, 1e-3, "m^3/s", LIVE,
	   "fluid it takes out, the tip under a pool's surface"),
	KD("patient", "leak_pa", patient.leak_pa, GAS_DEFAULT_LEAK_PA, 0, 2e4,
	   "Pa", LIVE, "the anus holds the gas below this pressure"),
	KD("patient", "leak_m3_per_s_pa", patient.leak_m3_per_s_pa,
	   GAS_DEFAULT_LEAK_M3_PER_S_PA, 0, 1e-5, "m^3/(s Pa)", LIVE,
	   "and leaks this much above it, per Pa"),
	KD("patient", "absorb_air_per_s", patient.absorb_air_per_s,
	   GAS_DEFAULT_ABSORB_AIR_PER_S, 0, 1, "1/s", LIVE,
	   "the share of the gas absorbed through the wall a second: air"),
	KD("patient", "absorb_co2_per_s", patient.absorb_co2_per_s,
	   GAS_DEFAULT_ABSORB_CO2_PER_S, 0, 1, "1/s", LIVE,
	   "the same for CO2 (~150 times air's)"),
	KD("patient", "relief_pa", patient.relief_pa, GAS_DEFAULT_RELIEF_PA, 0,
	   1e5, "Pa", LIVE, "the pump stops at this pressure (an "
	   "insufflator's 50 mmHg: 6666); 0: never"),
	KD("patient", "wall_strength_n_per_m", patient.wall_strength_n_per_m,
	   GAS_DEFAULT_WALL_STRENGTH_N_PER_M, 10, 1e5, "N/m", LIVE,
	   "a wall tears when its tension (pressure times radius) passes "
	   "this: a perforation"),
	KD("patient", "hydrostatic_pa_per_m", patient.hydrostatic_pa_per_m,
	   GAS_DEFAULT_HYDROSTATIC_PA_PER_M, 0, 1e5, "Pa/m", LIVE,
	   "the abdomen's contents' pressure per metre of depth (0.74 mmHg "
	   "per cm)"),
	KD("patient", "fluid_settle_s", patient.fluid_settle_s,
	   FLUID_DEFAULT_SETTLE_S, 0, 10, "s", LIVE,
	   "a pool's surface follows gravity with this time constant"),
	KD("patient", "hand_n", patient.hand_n, PATIENT_DEFAULT_HAND_N, 1, 100,
	   "N", LIVE, "the assistant presses with this unless told"),
	KD("patient", "hand_max_n", patient.hand_max_n,
	   PATIENT_DEFAULT_HAND_MAX_N, 1, 100, "N", LIVE,
	   "and never harder than this"),
	KD("patient", "abdomen_n_per_m", patient.abdomen_n_per_m,
	   PATIENT_DEFAULT_ABDOMEN_N_PER_M, 10, 1e5, "N/m", LIVE,
	   "how far the belly gives under the pad: force over this"),
	KD("patient", "lens_contact_n", patient.lens_contact_n,
	   LENS_DEFAULT_CONTACT_N, 0, 50, "N", LIVE,
	   "the tip pressed harder than this smears the lens"),
	KD("patient", "lens_smear_n_s", patient.lens_smear_n_s,
	   LENS_DEFAULT_SMEAR_N_S, 0.01, 1000, "N s", LIVE,
	   "force above contact times seconds that smears it fully"),
	KD("patient", "lens_dip_s", patient.lens_dip_s, LENS_DEFAULT_DIP_S,
	   0.01, 100, "s", LIVE, "under a pool this long clouds it fully"),
	KD("patient", "lens_wash_s", patient.lens_wash_s, LENS_DEFAULT_WASH_S,
	   0.01, 100, "s", LIVE, "the water jet clears it in this"),
	KD("patient", "lens_redout_gap_m", patient.lens_redout_gap_m,
	   LENS_DEFAULT_REDOUT_GAP_M, 0, 0.05, "m", LIVE,
	   "suction this close to the wall pulls the mucosa onto the lens"),
	KD("patient", "lens_redout_s", patient.lens_redout_s,
	   LENS_DEFAULT_REDOUT_S, 0.001, 10, "s", LIVE,
	   "the red-out's time constant"),
	KD("patient", "perforation_straight_n", patient.perforation_straight_n,
	   PERFORATION_DEFAULT_STRAIGHT_N, 1, 500, "N", LIVE,
	   "the tip pushed straight into the wall this hard tears it "
	   "(porcine colon: 14.1 N)"),
	KD("patient", "perforation_bent_n", patient.perforation_bent_n,
	   PERFORATION_DEFAULT_BENT_N, 1, 500, "N", LIVE,
	   "the same with the tip bent 90 degrees (46.5 N); linear between"),
	KD("patient", "perforation_hold_s", patient.perforation_hold_s,
	   PERFORATION_DEFAULT_HOLD_S, 0, 10, "s", LIVE,
	   "for this long"),

	KE("pain", "sedation", pain.sedation, PAIN_DEFAULT_SEDATION,
	   names_sedations, LIVE, "a session's sedation unless it says: "
	   "none, minimal, moderate or deep"),
	KD("pain", "stretch_threshold_n", pain.stretch_threshold_n,
	   PAIN_DEFAULT_STRETCH_THRESHOLD_N, 0, 1000, "N", LIVE,
	   "the mesentery's tension that starts to hurt"),
	KD("pain", "stretch_gain_per_n", pain.stretch_gain_per_n,
	   PAIN_DEFAULT_STRETCH_GAIN_PER_N, 0, 10, "1/N",
	   LIVE, "pain a newton of tension above it"),
	KD("pain", "wall_threshold_n_per_m", pain.wall_threshold_n_per_m,
	   PAIN_DEFAULT_WALL_THRESHOLD_N_PER_M, 0, 1e4, "N/m", LIVE,
	   "the wall's tension (pressure times radius) that starts to hurt"),
	KD("pain", "wall_gain_per_n_per_m", pain.wall_gain_per_n_per_m,
	   PAIN_DEFAULT_WALL_GAIN_PER_N_PER_M, 0, 10, "m/N", LIVE,
	   "pain a N/m above it"),
	KD("pain", "tip_threshold_n", pain.tip_threshold_n,
	   PAIN_DEFAULT_TIP_THRESHOLD_N, 0, 100, "N", LIVE,
	   "the tip's force on the wall that starts to hurt"),
	KD("pain", "tip_gain_per_n", pain.tip_gain_per_n,
	   PAIN_DEFAULT_TIP_GAIN_PER_N, 0, 10, "1/N", LIVE,
	   "pain a newton above it"),
	KD("pain", "rise_s", pain.rise_s, PAIN_DEFAULT_RISE_S, 0.001, 60, "s",
	   LIVE, "the pain rises with this time constant"),
	KD("pain", "fade_s", pain.fade_s, PAIN_DEFAULT_FADE_S, 0.001, 600, "s",
	   LIVE, "and fades with this one"),
	KD("pain", "moving_m_s", pain.moving_m_s, PAIN_DEFAULT_MOVING_M_S, 0,
	   1, "m/s", LIVE, "the stretch while the tube is withdrawn faster "
	   "than this is straightening's (else looping's)"),
	KD("pain", "turning_rad_s", pain.turning_rad_s,
	   PAIN_DEFAULT_TURNING_RAD_S, 0, 100, "rad/s", LIVE,
	   "or while it is turned faster than this"),

	KL("log", "level", log.level, "info", LIVE,
	   "err, warning, notice, info or debug"),

	GUIDE_KEYS("insertion", I_INS, "n", "m", "N", "m", 4000, 40, 25, 0.1,
		   6, 0.03),
	GUIDE_KEYS("roll", I_ROLL, "n_m", "rad", "N m", "rad", 2, 0.02, 0.5,
		   2, 0.1, 0.5),
	GUIDE_KEYS("wheel_ud", I_UD, "n_m", "rad", "N m", "rad", 0.5, 0.002,
		   0.08, 2, 0.04, 0.5),
	GUIDE_KEYS("wheel_lr", I_LR, "n_m", "rad", "N m", "rad", 0.5, 0.002,
		   0.08, 2, 0.04, 0.5),
	KD("guide", "takeover_s", guide.takeover_s, 0.3, 0.01, 10, "s", LIVE,
	   "a push held this long takes over from the guidance"),
	KD("guide", "fade_s", guide.fade_s, 0.5, 0.001, 10, "s", LIVE,
	   "taken over or stopped, the guidance fades out over this"),
	KD("guide", "error_s", guide.error_s, 1.0, 0.01, 60, "s", LIVE,
	   "an error beyond error_max this long: cannot follow, ends"),
	KD("guide", "hand_filter_hz", guide.hand_filter_hz, 5, 0.1, 100, "Hz",
	   LIVE, "low pass of the hand's estimated force"),
	AXIS_KEYS("axis.insertion", I_INS),
	KD("axis.insertion", "gear_radius_m", axis[I_INS].gear_radius_m, 0.015,
	   0.001, 1, "m", 0, "radius of the pinion that drives the carriage"),
	AXIS_KEYS("axis.roll", I_ROLL),
	AXIS_KEYS("axis.wheel_ud", I_UD),
	AXIS_KEYS("axis.wheel_lr", I_LR),

	EPOS4_KEYS("epos4.insertion", I_INS),
	EPOS4_KEYS("epos4.roll", I_ROLL),
	EPOS4_KEYS("epos4.wheel_ud", I_UD),
	EPOS4_KEYS("epos4.wheel_lr", I_LR),

	KE("modbus", "transport", modbus.transport, CONFIG_MODBUS_RTU,
	   transport_names, 0, "rtu (serial line) or tcp"),
	KS("modbus", "device", modbus.device, "/dev/ttyUSB0", 0,
	   "rtu: the serial device"),
	KI("modbus", "baud", modbus.baud, 115200, 1200, 4000000, "Bd", 0,
	   "rtu: line speed"),
	KE("modbus", "parity", modbus.parity, CONFIG_PARITY_NONE, parity_names,
	   0, "rtu: none, even or odd"),
	KI("modbus", "data_bits", modbus.data_bits, 8, 5, 8, "", 0,
	   "rtu: data bits"),
	KI("modbus", "stop_bits", modbus.stop_bits, 1, 1, 2, "", 0,
	   "rtu: stop bits"),
	KE("modbus", "rs485", modbus.rs485, 0, yes_no, 0,
	   "rtu: switch the port to RS-485 mode (TIOCSRS485)"),
	KS("modbus", "host", modbus.host, "127.0.0.1", 0,
	   "tcp: host name or address"),
	KI("modbus", "port", modbus.port, 502, 1, 65535, "", 0, "tcp: port"),
	KD("modbus", "response_timeout_s", modbus.response_timeout_s, 0.02,
	   0.001, 5, "s", 0, "longest wait for a reply to begin"),
	KD("modbus", "byte_timeout_s", modbus.byte_timeout_s, 0.005, 0.0001, 1,
	   "s", 0, "longest gap inside a reply"),
	KD("modbus", "feedback_max_age_s", modbus.feedback_max_age_s, 0.05,
	   0.001, 2, "s", 0, "feedback older than this is a fault"),
	KD("modbus", "max_rate_hz", modbus.max_rate_hz, 1000, 1, 1e5, "Hz", 0,
	   "bus cycles per second at most (the line may allow fewer)"),

	MODBUS_DRIVE_KEYS("modbus.insertion", I_INS),
	MODBUS_DRIVE_KEYS("modbus.roll", I_ROLL),
	MODBUS_DRIVE_KEYS("modbus.wheel_ud", I_UD),
	MODBUS_DRIVE_KEYS("modbus.wheel_lr", I_LR),
	KS("case", "directory", colon.directory, CONFIG_CASE_DIR, 0,
	   "where the case files NAME.case live (endoctl case list)"),
	KS("case", "name", colon.name, "normal", 0,
	   "the case loaded at start-up: DIRECTORY/NAME.case"),
	KS("case", "file", colon.file, "", 0,
	   "instead of NAME: a .case file, or a Wavefront .obj colon mesh"),
	KS("case", "centreline_file", colon.centreline_file, "", 0,
	   "with an .obj: its centreline, 'x y z' per line; empty: the "
	   "OBJ's own polyline"),
	KD("case", "step_m", colon.step_m, COLON_DEFAULT_STEP_M, 0.0002, 0.01,
	   "m", 0, "centreline sample and mesh ring spacing"),
	KI("case", "ring_vertices", colon.ring_vertices,
	   COLON_DEFAULT_RING_VERTICES, 8, 4096, "", 0,
	   "vertices around each ring (triangles ~ 2 x length / step_m x "
	   "this)"),
	KD("case", "segment_m", colon.segment_m, COLON_DEFAULT_SEGMENT_M, 0.01,
	   0.5, "m", 0,
	   "length of the mesh segments that index triangles along the colon"),

	KE("debug", "test_commands", debug.test_commands, 0, yes_no, 0,
	   "accept the test-only fault injections (endoctl debug): never on "
	   "a rig a person touches"),

	KS("session", "directory", session.directory, CONFIG_SESSION_DIR, 0,
	   "where training sessions are recorded (ID.endoses), created if "
	   "missing"),
	KD("session", "ring_s", session.ring_s, 4.0, 0.1, 60, "s", 0,
	   "the ring between the force loop and the recorder, in seconds of "
	   "cycles: how long a stalled disk is ridden out before records drop"),
	KD("session", "write_limit_bytes_per_s", session.write_limit_bytes_per_s,
	   0, 0, 1e9, "B/s", 0,
	   "for tests only: the recorder writes at most this fast (a slow "
	   "disk); 0: unlimited"),
	/* the metrics' thresholds: metrics.h's METRICS_DEFAULT_*, which this
	 * wing, below the session's, cannot name (test_config holds them to
	 * each other) */
	KD("session", "force_threshold_n", session.force_threshold_n, 15, 0.1,
	   1000, "N", 0, "metrics: insertion force above this is an episode of "
	   "excessive pressure"),
	KD("session", "loop_threshold_m", session.loop_threshold_m, 0, 0, 1,
	   "m", 0, "metrics: a mobile segment bowed (moved) more than this is "
	   "a loop; 0: by the model (0.01 paper, 0.03 rod)"),
	KD("session", "view_distance_m", session.view_distance_m, 0.06, 0.001,
	   1, "m", 0, "metrics: mucosa nearer the camera than this is seen"),
	KD("session", "fov_deg", session.fov_deg, 140, 1, 359, "deg", 0,
	   "metrics: the camera's full field of view"),
	KD("session", "view_rate_hz", session.view_rate_hz, 10, 0.1, 1000, "Hz",
	   0, "metrics: how often the mucosa and polyps seen are evaluated"),
	KD("session", "pain_level", session.pain_level, 4, 0.1, 10, "", 0,
	   "metrics: the patient is in pain at this pain (0-10) or above: "
	   "the time in pain, the pain episodes"),
	KS("session", "course", session.course, "", 0,
	   "the course file (config/courses/NAME.course) endoctl trainee "
	   "judges by, for trainees whose groups have no course assigned; "
	   "empty: none"),

	/* records.h's RECORDS_DEFAULT_NAME, which this wing cannot name
	 * (test_config holds them to each other) */
	KS("records", "database", records.database, "records.sqlite", 0,
	   "the rig's records, a SQLite database of its sessions, rebuilt "
	   "from the session files when missing; a relative path is under "
	   "[session] directory"),
	KS("records", "rig", records.rig, "", 0,
	   "this rig's name in the records; empty: the host's name"),
	KS("records", "centre", records.centre, "", 0,
	   "a centre's PostgreSQL (postgresql://HOST/DBNAME?...; its "
	   "password in libpq's password file) each session goes to as "
	   "well; empty: none"),
	KD("records", "centre_retry_s", records.centre_retry_s, 30, 0.05,
	   3600, "s", 0, "an unreachable centre is tried again after this; "
	   "the centre's people are looked at for changes this often"),

	KD("scope", "bending_length_m", scope.bending_length_m,
	   SCOPE_DEFAULT_BENDING_LENGTH_M, 0.01, 0.3, "m", LIVE,
	   "length of the bending section behind the tip"),
	KD("scope", "ud_gain_rad_per_rad", scope.gain[0], SCOPE_DEFAULT_UD_GAIN,
	   0, 20, "rad/rad", LIVE, "tip bend per up/down wheel angle"),
	KD("scope", "lr_gain_rad_per_rad", scope.gain[1], SCOPE_DEFAULT_LR_GAIN,
	   0, 20, "rad/rad", LIVE, "tip bend per left/right wheel angle"),
	KD("scope", "ud_limit_rad", scope.limit_rad[0],
	   SCOPE_DEFAULT_UD_LIMIT_RAD, 0, 3.1416, "rad", LIVE,
	   "largest tip bend up or down (180 deg)"),
	KD("scope", "lr_limit_rad", scope.limit_rad[1],
	   SCOPE_DEFAULT_LR_LIMIT_RAD, 0, 3.1416, "rad", LIVE,
	   "largest tip bend left or right (160 deg)"),

	KD("tool", "channel_angle_deg", tool.channel_angle_deg,
	   TOOL_DEFAULT_CHANNEL_ANGLE_DEG, 0, 360, "deg", LIVE,
	   "where the working channel opens on the tip's face: clockwise "
	   "from 12 o'clock in the image (150: 5 o'clock)"),
	KD("tool", "channel_offset_m", tool.channel_offset_m,
	   TOOL_DEFAULT_CHANNEL_OFFSET_M, 0, 0.01, "m", LIVE,
	   "the channel's exit from the tip's axis"),
	KD("tool", "snare_size_m", tool.snare_size_m, TOOL_DEFAULT_SNARE_M,
	   TOOL_SNARE_MIN_M, TOOL_SNARE_MAX_M, "m", LIVE,
	   "a snare's loop fully open, when endoctl tool select snare gives "
	   "no size"),
	KD("tool", "hot_power_w", tool.hot_power_w, TOOL_DEFAULT_HOT_POWER_W,
	   1, 200, "W", LIVE,
	   "the generator's power into the tissue, the pedal down"),
	KD("tool", "cut_j_per_m2", tool.cut_j_per_m2, TOOL_DEFAULT_CUT_J_PER_M2,
	   1e4, 1e8, "J/m^2", LIVE,
	   "the hot cut's energy per area of the cross-section the snare "
	   "holds"),
	KD("tool", "cold_max_m", tool.cold_max_m, TOOL_DEFAULT_COLD_MAX_M, 0,
	   0.03, "m", LIVE,
	   "a cold snare cuts what it holds thinner than this"),
	KD("tool", "coag_j_per_m3", tool.coag_j_per_m3,
	   TOOL_DEFAULT_COAG_J_PER_M3, 1e6, 1e10, "J/m^3", LIVE,
	   "what coagulates a stalk t thick, per volume of a collar as long "
	   "as it is thick: cut with less, it bleeds"),
	KD("tool", "bleed_min_m", tool.bleed_min_m, TOOL_DEFAULT_BLEED_MIN_M,
	   0, 0.03, "m", LIVE,
	   "a stalk this thick or more bleeds when cut before it is "
	   "coagulated"),
	KD("tool", "bleed_m_per_s", tool.bleed_m_per_s,
	   TOOL_DEFAULT_BLEED_M_PER_S, 0, 0.1, "m/s", LIVE,
	   "a bleeding point's flow per area of its stalk's section"),
	KD("tool", "bleed_stop_s", tool.bleed_stop_s, TOOL_DEFAULT_BLEED_STOP_S,
	   0.1, 3600, "s", LIVE,
	   "an unclipped bleeding stops by itself after this"),
	KD("tool", "retrieve_max_m", tool.retrieve_max_m,
	   TOOL_DEFAULT_RETRIEVE_MAX_M, 0, 0.03, "m", LIVE,
	   "the largest cut polyp the suction takes through the channel"),
	KD("tool", "retrieve_reach_m", tool.retrieve_reach_m,
	   TOOL_DEFAULT_RETRIEVE_REACH_M, 0, 0.05, "m", LIVE,
	   "the channel's exit from a cut polyp's surface, at most, for the "
	   "suction to take it"),
	KD("tool", "fall_drag_s", tool.fall_drag_s, TOOL_DEFAULT_FALL_DRAG_S,
	   0.001, 10, "s", LIVE,
	   "a cut polyp falling to the wall: its drag's time constant (its "
	   "speed tends to g x this)"),
};

#define KEYS (sizeof(keys) / sizeof(keys[0]))

/* A section ends: the lines every key was set on in the file so far, into
 * the reader's int[KEYS] (config_load_stream()). */
static void remember_lines(struct parse_file *pf, const int *set_on)
{
	memcpy(parse_file_user(pf), set_on, KEYS * sizeof(*set_on));
}

static const struct parse_table table = {
	.keys = keys,
	.n = KEYS,
	.end = remember_lines,
};

size_t config_key_count(void)
{
	return table.n;
}

const struct parse_key *config_key_at(size_t i)
{
	return i < table.n ? &keys[i] : NULL;
}

const struct parse_key *config_key_find(const char *key)
{
	char section[64];
	const char *dot = strrchr(key, '.');

	if (!dot || (size_t)(dot - key) >= sizeof(section)) {
		return NULL;
	}
	memcpy(section, key, (size_t)(dot - key));
	section[dot - key] = '\0';
	return parse_find(&table, section, dot + 1);
}

void config_defaults(struct config *cfg)
{
	memset(cfg, 0, sizeof(*cfg));
	parse_defaults(&table, cfg);
}

/* The line LINES (each key's in the file) gives the key that a check's
 * message WHY names first ("[SECTION] NAME: ..."), 0 when none. */
static int line_of(const char *why, const int lines[KEYS])
{
	char section[64], name[64];
	const struct parse_key *k;

	if (sscanf(why, "[%63[^]]] %63[^: ]:", section, name) != 2) {
		return 0;
	}
	k = parse_find(&table, section, name);
	return k ? lines[k - keys] : 0;
}

/* F read over NEW (CFG's copy); 0, or -EINVAL with one line in ERR. */
static int load_over(struct config *new, FILE *f, const char *name,
		     char *err, size_t errsize)
{
	int lines[KEYS] = { 0 };
	int n = parse_ini(&table, f, name, new, lines, err, errsize);
	char why[512];

	if (n < 0) {
		return n;
	}
	if (!n) {
		snprintf(err, errsize, "%s: empty configuration (no keys)",
			 name);
		return -EINVAL;
	}
	if (config_check_whole(new, why, sizeof(why))) {
		return parse_error(err, errsize, name, line_of(why, lines),
				   NULL, "%s", why);
	}
	return 0;
}

int config_load_stream(struct config *cfg, FILE *f, const char *name,
		       char *err, size_t errsize)
{
	struct config *new = malloc(sizeof(*new));
	int r;

	if (!new) {
		snprintf(err, errsize, "%s: out of memory", name);
		return -ENOMEM;
	}
	*new = *cfg;
	r = load_over(new, f, name, err, errsize);
	if (!r) {
		*cfg = *new;
	}
	free(new);
	return r;
}

int config_load(struct config *cfg, const char *path, char *err,
		size_t errsize)
{
	FILE *f = fopen(path, "r");
	int r;

	if (!f) {
		r = -errno;
		snprintf(err, errsize, "%s: cannot open: %s", path,
			 strerror(-r));
		return r;
	}
	r = config_load_stream(cfg, f, path, err, errsize);
	fclose(f);
	return r;
}

int config_set(struct config *cfg, const char *key, const char *value,
	       bool live_only, char *err, size_t errsize)
{
	const struct parse_key *k = config_key_find(key);
	struct config tmp = *cfg;
	char why[160];
	int r;

	if (!k) {
		snprintf(err, errsize, "%s: unknown key", key);
		return -ENOENT;
	}
	if (live_only && !(k->flags & CONFIG_LIVE)) {
		snprintf(err, errsize,
			 "%s: cannot change while running (restart needed)",
			 key);
		return -EPERM;
	}
	if (parse_apply(k, &tmp, value, NULL, why, sizeof(why))) {
		snprintf(err, errsize, "%s: %s", key, why);
		return -EINVAL;
	}
	r = config_check(&tmp, err, errsize);
	if (r) {
		return r;
	}
	*cfg = tmp;
	return 0;
}

int config_axis_backend(const struct config *cfg, int axis)
{
	return cfg->rig.backend == CONFIG_BACKEND_DRIVES
		       ? cfg->axis[axis].backend
		       : CONFIG_DRIVE_SIM;
}

bool config_saturation_faults(const struct config *cfg, int axis)
{
	if (cfg->limits.saturation_fault != CONFIG_OVERRUN_AUTO) {
		return cfg->limits.saturation_fault == CONFIG_OVERRUN_FAULT;
	}
	return config_axis_backend(cfg, axis) != CONFIG_DRIVE_SIM;
}

bool config_overrun_faults(const struct config *cfg)
{
	if (cfg->loop.overrun_fault != CONFIG_OVERRUN_AUTO) {
		return cfg->loop.overrun_fault == CONFIG_OVERRUN_FAULT;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		if (config_axis_backend(cfg, a) != CONFIG_DRIVE_SIM) {
			return true;
		}
	}
	return false;
}

double config_feedback_max_age_s(const struct config *cfg, int axis)
{
	switch (config_axis_backend(cfg, axis)) {
	case CONFIG_DRIVE_EPOS4_USB:
		return cfg->epos4[axis].feedback_max_age_s;
	case CONFIG_DRIVE_MODBUS:
		return cfg->modbus.feedback_max_age_s;
	default:
		return cfg->rig.feedback_max_age_s;
	}
}

uint32_t config_axis_valves(const struct config *cfg, int axis)
{
	uint32_t valves = 0;

	for (int v = 0; v < CONFIG_VALVES; v++) {
		switch (config_axis_backend(cfg, axis)) {
		case CONFIG_DRIVE_EPOS4_USB:
			valves |= cfg->epos4[axis].valve_bit[v] >= 0 ? 1u << v
								     : 0;
			break;
		case CONFIG_DRIVE_MODBUS:
			valves |= cfg->modbus_drive[axis]
						  .reg[REGSPEC_VALVE_AIR + v]
						  .table != REGSPEC_NONE
					  ? 1u << v : 0;
			break;
		default:
			break;
		}
	}
	return valves;
}

/* The section and key that map valve V on AXIS' drive, into BUF. */
static void valve_key(const struct config *cfg, int axis, int v, char *buf,
		      size_t size)
{
	static const char *const valve_names[CONFIG_VALVES] = {
		"air", "water", "suction",
	};

	if (config_axis_backend(cfg, axis) == CONFIG_DRIVE_EPOS4_USB) {
		snprintf(buf, size, "[epos4.%s] valve_%s_bit", names_axis(axis),
			 valve_names[v]);
	} else {
		snprintf(buf, size, "[modbus.%s] valve_%s", names_axis(axis),
			 valve_names[v]);
	}
}

/* The bit of 0x60FD that switch S (a valve's or the pedal's regspec
 * signal) is on, on AXIS' EPOS4. */
static int epos4_bit(const struct config *cfg, int axis, int s)
{
	return s == REGSPEC_TOOL_PEDAL
		       ? cfg->epos4[axis].tool_pedal_bit
		       : cfg->epos4[axis].valve_bit[s - REGSPEC_VALVE_AIR];
}

/* Switches S and T (valves', the pedal's regspec signals) read the same
 * input of AXIS' drive. */
static bool same_input(const struct config *cfg, int axis, int s, int t)
{
	const struct regspec *reg = cfg->modbus_drive[axis].reg;

	if (config_axis_backend(cfg, axis) == CONFIG_DRIVE_EPOS4_USB) {
		return epos4_bit(cfg, axis, s) == epos4_bit(cfg, axis, t);
	}
	return reg[s].table == reg[t].table && reg[s].address == reg[t].address;
}

/* Valve V of axis A's drive and valve W of axis B's on one input (A and B
 * the same) or one valve on two drives: refused naming both keys. */
static int valve_clash(const struct config *cfg, int a, int v, int b, int w,
		       char *err, size_t size)
{
	char key[80], other[80];

	valve_key(cfg, a, v, key, sizeof(key));
	valve_key(cfg, b, w, other, sizeof(other));
	snprintf(err, size, a == b ? "%s: the input of %s (one input per "
				     "valve)"
				   : "%s: %s reads that valve already (one "
				     "input per valve)", key, other);
	return -EINVAL;
}

/* On AXIS' drive, each valve on an input of its own. */
static int check_axis_valves(const struct config *cfg, int axis, char *err,
			     size_t size)
{
	uint32_t mapped = config_axis_valves(cfg, axis);

	for (int v = 0; v < CONFIG_VALVES; v++) {
		for (int w = 0; w < v; w++) {
			if ((mapped & 1u << v) && (mapped & 1u << w) &&
			    same_input(cfg, axis, REGSPEC_VALVE_AIR + v,
				       REGSPEC_VALVE_AIR + w)) {
				return valve_clash(cfg, axis, v, axis, w, err,
						   size);
			}
		}
	}
	return 0;
}

/* Each valve is read from one input, of one drive, at most. */
static int check_valves(const struct config *cfg, char *err, size_t size)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		if (check_axis_valves(cfg, a, err, size)) {
			return -EINVAL;
		}
		for (int b = 0; b < a; b++) {
			uint32_t both = config_axis_valves(cfg, a) &
					config_axis_valves(cfg, b);

			if (both) {
				return valve_clash(cfg, a, __builtin_ctz(both),
						   b, __builtin_ctz(both), err,
						   size);
			}
		}
	}
	return 0;
}

uint32_t config_axis_tool(const struct config *cfg, int axis)
{
	const struct config_epos4 *e = &cfg->epos4[axis];
	const struct regspec *reg = cfg->modbus_drive[axis].reg;
	uint32_t tool = 0;

	switch (config_axis_backend(cfg, axis)) {
	case CONFIG_DRIVE_EPOS4_USB:
		tool |= e->tool_depth_sensor > 0 ? CONFIG_TOOL_DEPTH : 0;
		tool |= e->tool_opening_input > 0 ? CONFIG_TOOL_OPENING : 0;
		tool |= e->tool_pedal_bit >= 0 ? CONFIG_TOOL_PEDAL : 0;
		break;
	case CONFIG_DRIVE_MODBUS:
		for (int s = 0; s < CONFIG_TOOL_SIGNALS; s++) {
			tool |= reg[REGSPEC_TOOL_DEPTH + s].table !=
						REGSPEC_NONE
					? 1u << s : 0;
		}
		break;
	default:
		break;
	}
	return tool;
}

/* The section and key that map the tool's signal S (the bit number of
 * enum config_tool_signal) on AXIS' drive, into BUF. */
static void tool_key(const struct config *cfg, int axis, int s, char *buf,
		     size_t size)
{
	static const char *const epos4_keys[CONFIG_TOOL_SIGNALS] = {
		"tool_depth_sensor", "tool_opening_input", "tool_pedal_bit",
	};

	if (config_axis_backend(cfg, axis) == CONFIG_DRIVE_EPOS4_USB) {
		snprintf(buf, size, "[epos4.%s] %s", names_axis(axis),
			 epos4_keys[s]);
	} else {
		snprintf(buf, size, "[modbus.%s] %s", names_axis(axis),
			 regspec_signal_name(REGSPEC_TOOL_DEPTH + s));
	}
}

/* On AXIS' drive, the pedal on an input of its own, and the handle's
 * voltages apart. */
static int check_axis_tool(const struct config *cfg, int axis, char *err,
			   size_t size)
{
	uint32_t valves = config_axis_valves(cfg, axis);
	const struct config_epos4 *e = &cfg->epos4[axis];
	char key[80], other[80];

	for (int v = 0; v < CONFIG_VALVES; v++) {
		if ((config_axis_tool(cfg, axis) & CONFIG_TOOL_PEDAL) &&
		    (valves & 1u << v) &&
		    same_input(cfg, axis, REGSPEC_TOOL_PEDAL,
			       REGSPEC_VALVE_AIR + v)) {
			tool_key(cfg, axis, 2, key, sizeof(key));
			valve_key(cfg, axis, v, other, sizeof(other));
			snprintf(err, size, "%s: the input of %s (one input "
				 "per switch)", key, other);
			return -EINVAL;
		}
	}
	if ((config_axis_tool(cfg, axis) & CONFIG_TOOL_OPENING) &&
	    config_axis_backend(cfg, axis) == CONFIG_DRIVE_EPOS4_USB &&
	    e->tool_open_mv == e->tool_closed_mv) {
		snprintf(err, size, "[epos4.%s] tool_open_mv: %g mV, the same "
			 "as tool_closed_mv: the handle's travel reads nothing",
			 names_axis(axis), e->tool_open_mv);
		return -EINVAL;
	}
	return 0;
}

/* The tool's first signal in MAPPED (enum config_tool_signal bits), its
 * key into BUF. */
static int first_tool_key(const struct config *cfg, uint32_t mapped,
			  char *buf, size_t size)
{
	int s = __builtin_ctz(mapped);

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		if (config_axis_tool(cfg, a) & 1u << s) {
			tool_key(cfg, a, s, buf, size);
			return s;
		}
	}
	return s;
}

/* Each of the tool's signals read from one drive at most. */
static int check_tool(const struct config *cfg, char *err, size_t size)
{
	uint32_t all = 0;
	char key[80], other[80];

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		uint32_t t = config_axis_tool(cfg, a);

		if (check_axis_tool(cfg, a, err, size)) {
			return -EINVAL;
		}
		if (t & all) {
			int s = first_tool_key(cfg, t & all, other,
					       sizeof(other));

			tool_key(cfg, a, s, key, sizeof(key));
			snprintf(err, size, "%s: %s reads it already (one "
				 "drive per signal)", key, other);
			return -EINVAL;
		}
		all |= t;
	}
	return 0;
}

/* The tool's depth and its opening both read from drives or neither (the
 * model moves the tool on both, tool.h); the pedal as the rig builder
 * wires it. */
static int check_tool_pair(const struct config *cfg, char *err, size_t size)
{
	uint32_t all = 0, pair = CONFIG_TOOL_DEPTH | CONFIG_TOOL_OPENING;
	char key[80];

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		all |= config_axis_tool(cfg, a);
	}
	if ((all & pair) && (all & pair) != pair) {
		first_tool_key(cfg, all & pair, key, sizeof(key));
		snprintf(err, size, "%s: the tool's %s is on no drive: its "
			 "depth and its opening are read together", key,
			 all & CONFIG_TOOL_DEPTH ? "opening" : "depth");
		return -EINVAL;
	}
	return 0;
}

int config_check_whole(const struct config *cfg, char *err, size_t errsize)
{
	return config_check(cfg, err, errsize) ||
			       check_tool_pair(cfg, err, errsize)
		       ? -EINVAL
		       : 0;
}

/* Two EPOS4 axes must not be able to find the same drive. */
static int check_epos4(const struct config *cfg, char *err, size_t size)
{
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		const struct config_epos4 *e = &cfg->epos4[a];

		for (int b = 0; b < a; b++) {
			const struct config_epos4 *o = &cfg->epos4[b];

			if (config_axis_backend(cfg, a) !=
				    CONFIG_DRIVE_EPOS4_USB ||
			    config_axis_backend(cfg, b) !=
				    CONFIG_DRIVE_EPOS4_USB ||
			    e->vid != o->vid || e->pid != o->pid ||
			    strcmp(e->serial, o->serial)) {
				continue;
			}
			snprintf(err, size, "[epos4.%s] serial: '%s' names the "
				 "same drive as [epos4.%s]; two EPOS4 need their "
				 "serial numbers", names_axis(a), e->serial,
				 names_axis(b));
			return -EINVAL;
		}
	}
	return 0;
}

/* Speeds libmodbus knows (it silently takes 9600 for any other). */
static bool standard_baud(int baud)
{
	static const int bauds[] = {
		1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200, 230400,
		460800, 500000, 576000, 921600, 1000000, 1152000, 1500000,
		2000000, 2500000, 3000000, 3500000, 4000000,
	};

	for (size_t i = 0; i < sizeof(bauds) / sizeof(bauds[0]); i++) {
		if (bauds[i] == baud) {
			return true;
		}
	}
	return false;
}

static int check_modbus_bus(const struct config_modbus *m, char *err,
			    size_t size)
{
	if (m->transport == CONFIG_MODBUS_TCP) {
		if (!m->host[0]) {
			snprintf(err, size, "[modbus] host: empty");
			return -EINVAL;
		}
		return 0;
	}
	if (!m->device[0]) {
		snprintf(err, size, "[modbus] device: empty");
		return -EINVAL;
	}
	if (!standard_baud(m->baud)) {
		snprintf(err, size, "[modbus] baud: %d is not a standard line "
			 "speed (e.g. 9600, 115200, 1000000)", m->baud);
		return -EINVAL;
	}
	return 0;
}

/* The feedback registers of D, read with 0x17, fit one holding block. */
static int check_combined(const struct config_modbus_drive *d,
			  const char *axis, char *err, size_t size)
{
	static const int reads[] = { REGSPEC_POSITION, REGSPEC_VELOCITY,
				     REGSPEC_FAULT };
	int lo = 0xFFFF, hi = 0;

	if (d->reg[REGSPEC_TORQUE].table != REGSPEC_HOLDING) {
		snprintf(err, size, "[modbus.%s] combined_0x17: torque must "
			 "be a holding register", axis);
		return -EINVAL;
	}
	for (size_t i = 0; i < sizeof(reads) / sizeof(reads[0]); i++) {
		const struct regspec *r = &d->reg[reads[i]];

		if (r->table == REGSPEC_NONE) {
			continue;
		}
		if (r->table != REGSPEC_HOLDING) {
			snprintf(err, size, "[modbus.%s] %s: 0x17 reads holding "
				 "registers only", axis,
				 regspec_signal_name(reads[i]));
			return -EINVAL;
		}
		lo = r->address < lo ? r->address : lo;
		hi = r->address + regspec_words(r) > hi
			     ? r->address + regspec_words(r) : hi;
	}
	if (hi - lo > 125) {
		snprintf(err, size, "[modbus.%s] combined_0x17: the feedback "
			 "registers span %d, more than one 0x17 reads (125)",
			 axis, hi - lo);
		return -EINVAL;
	}
	return 0;
}

static int check_modbus_drive(const struct config_modbus_drive *d,
			      const char *axis, char *err, size_t size)
{
	static const int needed[] = { REGSPEC_TORQUE, REGSPEC_POSITION };
	static const int writes[] = { REGSPEC_TORQUE, REGSPEC_ENABLE,
				      REGSPEC_FAULT_RESET, REGSPEC_WATCHDOG };

	for (size_t i = 0; i < sizeof(needed) / sizeof(needed[0]); i++) {
		if (d->reg[needed[i]].table == REGSPEC_NONE) {
			snprintf(err, size, "[modbus.%s] %s: a modbus axis needs "
				 "it", axis, regspec_signal_name(needed[i]));
			return -EINVAL;
		}
	}
	for (size_t i = 0; i < sizeof(writes) / sizeof(writes[0]); i++) {
		const struct regspec *r = &d->reg[writes[i]];

		if (r->table != REGSPEC_NONE && !regspec_writable(r)) {
			snprintf(err, size, "[modbus.%s] %s: is written: it must "
				 "be a coil or a holding register", axis,
				 regspec_signal_name(writes[i]));
			return -EINVAL;
		}
	}
	return d->combined_0x17 ? check_combined(d, axis, err, size) : 0;
}

static int check_modbus(const struct config *cfg, char *err, size_t size)
{
	bool any = false;

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		const struct config_modbus_drive *d = &cfg->modbus_drive[a];

		if (config_axis_backend(cfg, a) != CONFIG_DRIVE_MODBUS) {
			continue;
		}
		any = true;
		if (check_modbus_drive(d, names_axis(a), err, size)) {
			return -EINVAL;
		}
		for (int b = 0; b < a; b++) {
			if (config_axis_backend(cfg, b) == CONFIG_DRIVE_MODBUS &&
			    cfg->modbus_drive[b].slave == d->slave) {
				snprintf(err, size, "[modbus.%s] slave: %d is "
					 "[modbus.%s]'s too", names_axis(a),
					 d->slave, names_axis(b));
				return -EINVAL;
			}
		}
	}
	return any ? check_modbus_bus(&cfg->modbus, err, size) : 0;
}

bool config_case_name_ok(const char *name)
{
	size_t n = strspn(name, "abcdefghijklmnopqrstuvwxyz"
			  "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-");

	return n && !name[n];
}

/* The assistant's usual press within her strongest. */
static int check_patient(const struct config_patient *p, char *err,
			 size_t size)
{
	if (p->hand_n > p->hand_max_n) {
		snprintf(err, size, "[patient] hand_n: %g N is above "
			 "hand_max_n (%g N): a press without a force would be "
			 "refused", p->hand_n, p->hand_max_n);
		return -EINVAL;
	}
	return 0;
}

int config_check(const struct config *cfg, char *err, size_t errsize)
{
	if (check_epos4(cfg, err, errsize) || check_modbus(cfg, err, errsize) ||
	    check_valves(cfg, err, errsize) || check_tool(cfg, err, errsize) ||
	    check_patient(&cfg->patient, err, errsize)) {
		return -EINVAL;
	}
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		if (cfg->rig.travel_min[a] >= cfg->rig.travel_max[a]) {
			snprintf(err, errsize,
				 "[rig] %s travel: minimum %g is not below "
				 "maximum %g", names_axis(a),
				 cfg->rig.travel_min[a],
				 cfg->rig.travel_max[a]);
			return -EINVAL;
		}
	}
	if (!config_case_name_ok(cfg->colon.name)) {
		snprintf(err, errsize, "[case] name: '%s' must be letters, "
			 "digits, '-' and '_'", cfg->colon.name);
		return -EINVAL;
	}
	if (cfg->shm.name[0] != '/' || strchr(cfg->shm.name + 1, '/') ||
	    !cfg->shm.name[1]) {
		snprintf(err, errsize, "[shm] name: '%s' must be '/' and a "
			 "name without further '/'", cfg->shm.name);
		return -EINVAL;
	}
	return 0;
}

void config_format(const struct config *cfg, const struct parse_key *k,
		   char *buf, size_t size)
{
	parse_format(k, cfg, buf, size);
}

void config_print(const struct config *cfg, FILE *out)
{
	const char *section = "";
	char value[CONFIG_STR + 32];
	int pad;

	for (size_t i = 0; i < table.n; i++) {
		const struct parse_key *k = &keys[i];

		if (strcmp(section, k->section)) {
			section = k->section;
			fprintf(out, "%s[%s]\n", i ? "\n" : "", section);
		}
		config_format(cfg, k, value, sizeof(value));
		pad = 40 - (int)(strlen(k->name) + strlen(value));
		fprintf(out, "%s = %s%*s ; %s%s%s%s%s\n", k->name, value,
			pad > 0 ? pad : 0, "", *k->unit ? "[" : "", k->unit,
			*k->unit ? "] " : "", k->help,
			k->flags & CONFIG_LIVE ? " (live)" : "");
	}
}
