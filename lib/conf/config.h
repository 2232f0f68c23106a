/*
 * config.h - endosimd's configuration: one table declares every key once
 * (section, name, type, default, range, unit, whether it may change while
 * running, one line of help), the defaults of the model's parameters by
 * their owners' names (scope.h, haptics.h, rodscope.h, ...). The same table
 * parses the INI file (parse.h's kit, over Debian's libinih), applies
 * command-line overrides, prints the effective configuration and answers
 * GetConfig/SetParam.
 *
 * Errors are reported as one line, "FILE:LINE: [section] key: what" (the
 * kit's, parse.h), in the caller's buffer, before anything else happens;
 * the caller exits with EX_CONFIG (78).
 *
 * Not thread-safe: the main thread loads; afterwards the control thread owns
 * the master copy and hands copies to the force loop (loop.h).
 */
#ifndef ENDOSIM_CONFIG_H
#define ENDOSIM_CONFIG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "base/parse.h"
#include "proto/endosim_shm.h"
#include "model/haptics.h"
#include "model/tool.h"
#include "conf/regspec.h"

#define CONFIG_DEFAULT_PATH "/etc/endosim/endosimd.conf"
#ifndef CONFIG_CASE_DIR /* the Makefile sets it to $(DATADIR)/cases */
#define CONFIG_CASE_DIR "/usr/local/share/endosim/cases"
#endif
#define CONFIG_SESSION_DIR "/var/lib/endosim/sessions"
#define CONFIG_STR 128 /* longest string value, bytes with the NUL */
#define CONFIG_OVERRUN_BUDGET_MAX 1000 /* [loop] overrun_budget */

enum config_backend {
	CONFIG_BACKEND_SIM = 0,    /* every axis simulated */
	CONFIG_BACKEND_DRIVES = 1, /* each axis as its [axis.NAME] says */
};

/* What a missed overrun budget is ([loop] overrun_fault). */
enum config_overrun_fault {
	CONFIG_OVERRUN_WARN = 0,  /* no: a warning, counted and logged */
	CONFIG_OVERRUN_FAULT = 1, /* yes: a fault, latched */
	CONFIG_OVERRUN_AUTO = 2,  /* a fault unless every axis is simulated */
};

/* What moves one axis ([axis.NAME] backend). */
enum config_drive {
	CONFIG_DRIVE_SIM = 0,
	CONFIG_DRIVE_EPOS4_USB = 1,
	CONFIG_DRIVE_MODBUS = 2,
};

enum config_transport { CONFIG_MODBUS_RTU = 0, CONFIG_MODBUS_TCP = 1 };
enum config_parity {
	CONFIG_PARITY_NONE = 0,
	CONFIG_PARITY_EVEN,
	CONFIG_PARITY_ODD,
};

/* One axis' mechanics: how motor turns and encoder counts map to the axis. */
struct config_axis {
	int backend;          /* enum config_drive */
	double gear_ratio;    /* motor turns per turn of the output */
	double gear_radius_m; /* insertion only: pinion radius, m per rad */
	int counts_per_rev;   /* encoder counts per motor turn */
	int reversed;         /* 1: motor positive is axis negative */
};

/*
 * The handle's valves a real rig reads from its drives' digital inputs, in
 * enum endosim_valve's order (valve V is bit 1 << V): the air/water valve
 * covered (air), pressed (water), the suction valve.
 */
#define CONFIG_VALVES 3

/*
 * The tool in the working channel a real rig senses (model/tool.h's
 * input): its depth (an encoder), its handle's opening (an analogue
 * input) and the cautery's foot pedal (a digital input). The bits say
 * which of them a drive reads (config_axis_tool()).
 */
enum config_tool_signal {
	CONFIG_TOOL_DEPTH = 1u << 0,
	CONFIG_TOOL_OPENING = 1u << 1,
	CONFIG_TOOL_PEDAL = 1u << 2,
};
#define CONFIG_TOOL_SIGNALS 3

/* One maxon EPOS4 on USB ([epos4.NAME]). */
struct config_epos4 {
	int vid, pid;                 /* USB vendor and product id */
	char serial[CONFIG_STR];      /* USB serial number; "": any */
	int node_id;                  /* the drive's node-ID */
	double timeout_s;             /* per USB transfer */
	double feedback_max_age_s;    /* older feedback is a fault */
	double max_rate_hz;           /* the bus thread's exchange rate cap */
	double rated_torque_unit_n_m; /* SI value of one unit of 0x6076 */
	double watchdog_s;            /* heartbeat consumer time 0x1016 */
	int valve_bit[CONFIG_VALVES]; /* the bit of digital inputs 0x60FD
					 that is set while the valve is
					 pressed; -1: not on this drive */
	int tool_depth_sensor;        /* the subindex of 0x60E4 (additional
					 position actual values: 1..3, the
					 drive's sensors) that counts the
					 tool's depth; 0: not on this drive */
	double tool_m_per_count;      /* the depth one count is, m */
	double tool_depth_offset_m;   /* the depth at count 0, m */
	int tool_opening_input;       /* the analogue input (0x3160:N, mV)
					 the handle's opening is wired to,
					 1..2; 0: not on this drive */
	double tool_closed_mv;        /* its voltage closed, mV */
	double tool_open_mv;          /* its voltage open, mV */
	int tool_pedal_bit;           /* the bit of 0x60FD set while the
					 pedal is down; -1: not on it */
};

/* The Modbus line or connection all modbus axes share ([modbus]). */
struct config_modbus {
	int transport;                /* enum config_transport */
	char device[CONFIG_STR];      /* RTU: serial device */
	int baud;
	int parity;                   /* enum config_parity */
	int data_bits, stop_bits;
	int rs485;                    /* 1: switch the port to RS-485 mode */
	char host[CONFIG_STR];        /* TCP */
	int port;
	double response_timeout_s;
	double byte_timeout_s;
	double feedback_max_age_s;
	double max_rate_hz;
};

/* One Modbus wheel drive ([modbus.NAME]): its slave id and register map. */
struct config_modbus_drive {
	int slave;
	int combined_0x17;            /* 1: write and read in one transaction */
	double watchdog_s;            /* written to the watchdog register */
	struct regspec reg[REGSPEC_SIGNALS];
};

struct config {
	struct {
		int rate_hz;      /* force-loop rate, Hz */
		int priority;     /* SCHED_FIFO priority, 1..99 */
		int cpu;          /* CPU to pin the loop to, -1: any */
		int cpu_dma_latency_us; /* PM QoS held while running, -1: none */
		int overrun_budget;     /* periods skipped within ... */
		double overrun_window_s; /* ... this window: missed */
		int overrun_fault;      /* enum config_overrun_fault */
	} loop;
	struct {
		int backend;                   /* enum config_backend */
		double travel_min[ENDOSIM_AXES]; /* m or rad */
		double travel_max[ENDOSIM_AXES]; /* m or rad */
		double feedback_max_age_s;     /* older feedback is a fault */
	} rig;
	struct {
		double inertia[ENDOSIM_AXES];  /* kg or kg m^2 */
		double viscous[ENDOSIM_AXES];  /* N s/m or N m s/rad */
		double coulomb[ENDOSIM_AXES];  /* N or N m */
		double hand_stiffness[ENDOSIM_AXES]; /* N/m or N m/rad */
		double hand_damping[ENDOSIM_AXES];   /* N s/m or N m s/rad */
		double hand_max[ENDOSIM_AXES]; /* N or N m */
		double hand_max_speed[ENDOSIM_AXES]; /* m/s or rad/s */
		double hand_hold_s;            /* default hold of live input */
		double grip_max[ENDOSIM_AXES]; /* N or N m: the hand's hold
						  before the axis slips */
	} sim;
	struct {
		char directory[CONFIG_STR];
		char group[CONFIG_STR];        /* "" : the daemon's own group */
		int max_request_bytes;
		int max_clients;
		int max_queued_bytes;          /* unsent replies per client */
		double idle_timeout_s;         /* silent clients are closed */
		double partial_timeout_s;      /* unfinished requests too */
	} socket;
	struct {
		char name[CONFIG_STR];
	} shm;
	struct {
		double max[ENDOSIM_AXES];      /* N or N m, both directions */
		double slew[ENDOSIM_AXES];     /* N/s or N m/s */
		double enable_ramp_s;          /* torque rises over this */
		double max_speed[ENDOSIM_AXES]; /* m/s or rad/s: a runaway */
		double travel_margin;          /* fraction of the travel */
		double saturation_s;           /* longest hold at a limit */
		int saturation_fault;          /* enum config_overrun_fault:
						  no, yes, auto (a fault on
						  a drive's axis) */
	} limits;
	struct haptics_gains haptics;          /* haptics.h */
	struct {
		int level;                     /* syslog level */
	} log;
	struct config_axis axis[ENDOSIM_AXES];
	struct config_epos4 epos4[ENDOSIM_AXES];
	struct config_modbus modbus;
	struct config_modbus_drive modbus_drive[ENDOSIM_AXES];
	struct {                           /* [case] */
		char directory[CONFIG_STR];    /* holds NAME.case files */
		char name[CONFIG_STR];         /* the case at start-up */
		char file[CONFIG_STR];         /* "" or a .case or .obj path */
		char centreline_file[CONFIG_STR]; /* an .obj's points, "" */
		double step_m;                 /* centreline and ring spacing */
		int ring_vertices;
		double segment_m;              /* mesh segments along s */
	} colon;
	struct {
		int test_commands;   /* 1: DebugInject accepted (tests only) */
	} debug;
	struct {                           /* [session]: recorder.h */
		char directory[CONFIG_STR];    /* ID.endoses files */
		double ring_s;                 /* the record ring, s of cycles */
		double write_limit_bytes_per_s; /* tests: a slow disk; 0 none */
		double force_threshold_n;      /* metrics.h struct metrics_params */
		double loop_threshold_m;
		double view_distance_m;
		double fov_deg;
		double view_rate_hz;
		double pain_level;             /* 0..10 */
		char course[CONFIG_STR];       /* coursefile.h: endoctl trainee */
	} session;
	struct {                           /* [records]: records.h */
		char database[CONFIG_STR];     /* relative: under the sessions */
		char rig[CONFIG_STR];          /* "": the host's name */
		char centre[CONFIG_STR];       /* centre.h's URL; "": none */
		double centre_retry_s;         /* retry; the people looked at */
	} records;
	struct {
		double bending_length_m;
		double gain[2];      /* tip rad per wheel rad: ud, lr */
		double limit_rad[2]; /* largest tip bend: ud, lr */
	} scope;
	struct config_rod {      /* [rod]: the rod model (rodscope.h) */
		int segments;
		double length_m;
		double mass_per_m_kg;
		double bending_n_m2;
		double torsion_n_m2;
		double tip_bending_n_m2;
		double damping_s;
		double drag_n_s_per_m2;
		int iterations;
		double wall_n_per_m2;
		double wall_damping_s;
		double friction;
		double slip_m_per_s;
		double pipe_n_per_m2;
		double coupling_n_per_m;
		double coupling_n_s_per_m;
		double roll_n_m_per_rad;
		double roll_n_m_s_per_rad;
		double stop_n_per_m;
		double colon_node_spacing_m;
		double colon_damping_n_s_per_m;
		double colon_chain_n_per_m;
		double colon_bending_n_per_m;
		double colon_mass_per_m_kg;
	} rod;
	struct config_patient {  /* [patient]: the patient's body (patient.h) */
		int enabled;         /* 0 no, 1 yes */
		int gas;             /* enum gas_kind */
		int position;        /* enum posture_position: at the start */
		double turn_s;
		double pump_m3_per_s;
		double suction_m3_per_s;
		double suction_fluid_m3_per_s;
		double leak_pa;
		double leak_m3_per_s_pa;
		double absorb_air_per_s;
		double absorb_co2_per_s;
		double relief_pa;
		double wall_strength_n_per_m;
		double hydrostatic_pa_per_m;
		double fluid_settle_s;
		double hand_n;
		double hand_max_n;
		double abdomen_n_per_m;
		double lens_contact_n;
		double lens_smear_n_s;
		double lens_dip_s;
		double lens_wash_s;
		double lens_redout_gap_m;
		double lens_redout_s;
		double perforation_straight_n;
		double perforation_bent_n;
		double perforation_hold_s;
	} patient;
	struct pain_params pain; /* [pain]: the patient's pain (pain.h);
				    its sedation a session's unless it
				    says */
	struct config_guide {    /* [guide]: guided replay (guide.h); per
				    axis in enum endosim_axis order, N or
				    N m, m or rad */
		double stiffness[ENDOSIM_AXES];  /* N/m, N m/rad */
		double damping[ENDOSIM_AXES];    /* N s/m, N m s/rad */
		double force_max[ENDOSIM_AXES];  /* N, N m */
		double speed_max[ENDOSIM_AXES];  /* m/s, rad/s */
		double takeover[ENDOSIM_AXES];   /* N, N m: a hand's push */
		double error_max[ENDOSIM_AXES];  /* m, rad */
		double takeover_s;   /* the push held so long: taken over */
		double fade_s;       /* the force fades out over this */
		double error_s;      /* the error held so long: cannot follow */
		double hand_filter_hz; /* the hand's force estimate's low pass */
	} guide;
	struct config_tool {     /* [tool]: the working channel's (tool.h) */
		double channel_angle_deg; /* clockwise from 12 o'clock */
		double channel_offset_m;
		double snare_size_m;  /* a snare selected without a size */
		double hot_power_w;
		double cut_j_per_m2;
		double cold_max_m;
		double coag_j_per_m3; /* the bleeding's (tool.h) */
		double bleed_min_m;
		double bleed_m_per_s;
		double bleed_stop_s;
		double retrieve_max_m; /* retrieval's */
		double retrieve_reach_m;
		double fall_drag_s;   /* a cut polyp's fall */
	} tool;
};

/* The keys' own flags (struct parse_key flags). */
enum config_flags {
	CONFIG_LIVE = PARSE_USER, /* may change while running (SetParam) */
};

/* Fills CFG with every key's default. */
void config_defaults(struct config *cfg);

/*
 * Reads the INI file PATH over CFG. Returns 0, -ENOENT (cannot open),
 * -ENOMEM or -EINVAL (unknown key, bad value, duplicate, syntax error,
 * empty file, a cross-key check of config_check()), with one line in ERR,
 * "FILE:LINE: [SECTION] KEY: message" (a check's: the line of the key it
 * names, "FILE: " when the file does not set it). CFG is unchanged on
 * error.
 */
int config_load(struct config *cfg, const char *path, char *err,
		size_t errsize);

/* The same for an open stream; NAME stands for the file in messages. */
int config_load_stream(struct config *cfg, FILE *f, const char *name,
		       char *err, size_t errsize);

/*
 * Sets KEY ("section.name") from the text VALUE as if read from the file.
 * With LIVE_ONLY, keys without CONFIG_LIVE are refused. Returns 0, -ENOENT
 * (no such key), -EPERM (not live) or -EINVAL (bad value), with one line in
 * ERR. CFG is unchanged on error.
 */
int config_set(struct config *cfg, const char *key, const char *value,
	       bool live_only, char *err, size_t errsize);

/* True when NAME can name a case file: [A-Za-z0-9_-]+, no path. */
bool config_case_name_ok(const char *name);

/*
 * Cross-key checks (travel min below max, distinct devices, a usable
 * register map for each modbus axis, each of the handle's valves and the
 * tool's pedal on an input of its own, each of the tool's signals on one
 * drive, the assistant's hand_n within hand_max_n, a case name, ...):
 * what holds after every key (config_set()). Returns 0 or -EINVAL with
 * "[SECTION] KEY: message" in ERR.
 */
int config_check(const struct config *cfg, char *err, size_t errsize);

/*
 * config_check(), and what only a whole configuration must hold, since
 * one key set at a time cannot make it so: the tool's depth and opening
 * on drives both or neither. config_load() checks it; so must whoever
 * sets keys one by one (the command line's --set), after the last.
 */
int config_check_whole(const struct config *cfg, char *err, size_t errsize);

/* The backend that moves AXIS: CONFIG_DRIVE_SIM unless [rig] backend is
 * drives. */
int config_axis_backend(const struct config *cfg, int axis);

/*
 * True when a missed overrun budget latches a fault: [loop] overrun_fault
 * is yes, or auto with some axis on a real drive. Any thread, the force
 * loop included (no I/O, no allocation).
 */
bool config_overrun_faults(const struct config *cfg);

/*
 * True when AXIS held beyond its force limit for saturation_s latches a
 * fault: [limits] saturation_fault is yes, or auto and a real drive turns
 * the axis (a simulated axis has no motor to protect: a warning). Any
 * thread, the force loop included.
 */
bool config_saturation_faults(const struct config *cfg, int axis);

/*
 * The valves (enum endosim_valve bits) read from the drive of AXIS: those
 * its [epos4.NAME] valve_*_bit or [modbus.NAME] valve_* keys map, when
 * AXIS is on that backend; 0 for a simulated axis (whose valves, like
 * every unmapped one, come from the simulated hand). Any thread.
 */
uint32_t config_axis_valves(const struct config *cfg, int axis);

/*
 * The tool's signals (enum config_tool_signal bits) read from the drive
 * of AXIS: those its [epos4.NAME] tool_* or [modbus.NAME] tool_* keys
 * map, when AXIS is on that backend; 0 for a simulated axis (the tool's
 * unmapped signals come from the simulated hand). Any thread.
 */
uint32_t config_axis_tool(const struct config *cfg, int axis);

/* The feedback age beyond which AXIS is faulted, s: its bus's, or [rig]'s. */
double config_feedback_max_age_s(const struct config *cfg, int axis);

/* The table (parse.h's keys): config_key_count() entries. */
size_t config_key_count(void);
const struct parse_key *config_key_at(size_t i);

/* The key called "section.name", or NULL. */
const struct parse_key *config_key_find(const char *key);

/* Writes KEY's value in CFG as text, as it would appear in the file. */
void config_format(const struct config *cfg, const struct parse_key *key,
		   char *buf, size_t size);

/* Prints every key with its value, unit and help as a valid INI file. */
void config_print(const struct config *cfg, FILE *out);

#endif
