/*
 * session_file.h - the training session file: what endosimd records, what
 * endoctl (show, export, report) and endoview (--replay) read.
 *
 * The layout is documented for people in docs/SESSION_FORMAT.md; this
 * header is the contract for code. In short:
 *
 *   file   = magic "ENDOSES1" (8 bytes), then frames, nothing else
 *   frame  = u32 type, u32 length, LENGTH bytes of payload,
 *            u32 CRC-32 (IEEE, as zlib's crc32) of type, length and payload
 *
 * all little-endian. A reader stops at the first frame that is cut short
 * or whose CRC does not match: a file cut by a crash or a full disk reads
 * up to its last complete frame. Types never change meaning; a reader
 * skips types it does not know.
 *
 * Frame types, in the order a writer puts them:
 *   HEADER  (1)  once, first: "key=value\n" lines (UTF-8), see below
 *   CONFIG  (2)  once: the effective configuration, as --print-config
 *   CASE    (3)  once: the case file's text (the colon recorded on)
 *   RECORD  (4)  one per force-loop cycle: struct session_record
 *   EVENT   (5)  faults, enables, parameter changes, drops: struct
 *                session_event and its text
 *   END     (6)  once, last, when the session stopped cleanly: the final
 *                metrics as "key=value\n" lines
 *   SHAPE   (7)  the rod model only, every session_shape_every() cycles
 *                (>= 30 Hz), among the records: struct session_shape
 *
 * Header keys: format (8; 7 before the cut polyps' places, 6 before the
 * bleeding, 5 before the tool in
 * the working channel, 4
 * before the patient's pain, 3 before the
 * patient's body, 2 before guided replay, 1 before the rod model), id,
 * trainee, case,
 * started (UTC, ISO 8601), start_ns (CLOCK_MONOTONIC of the first
 * record's clock), period_ns, version (endosimd's), record_size
 * (sizeof(struct session_record)), and the case's resolution: step_m,
 * ring_vertices, segment_m.
 *
 * Threads: the file's functions are not for the force loop:
 * session_file_write_*() calls write(2) and may block; the reader
 * allocates. Neither keeps state between calls beyond its own struct.
 * The conversions between a state and a record or a shape (and
 * session_shape_due()) are the force loop's too: they never allocate.
 */
#ifndef ENDOSIM_SESSION_FILE_H
#define ENDOSIM_SESSION_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "proto/endosim_shm.h"

#define SESSION_FILE_MAGIC "ENDOSES1"
#define SESSION_FILE_FORMAT 8u

enum session_frame_type {
	SESSION_FRAME_HEADER = 1,
	SESSION_FRAME_CONFIG = 2,
	SESSION_FRAME_CASE = 3,
	SESSION_FRAME_RECORD = 4,
	SESSION_FRAME_EVENT = 5,
	SESSION_FRAME_END = 6,
	SESSION_FRAME_SHAPE = 7,
};

/* Largest payload a reader accepts (a case file, the configuration). */
#define SESSION_FRAME_MAX (4u << 20)

/*
 * One force-loop cycle as published (struct endosim_state), compact:
 * floats for the physical values (a float's 7 digits are far below the
 * rig's resolution), SI units as in endosim_shm.h. 572 bytes. Which field
 * of the state each holds, and its CSV column, is said once, in
 * fields.h's tables; a field added goes at the end (the CSV's columns are
 * in this order), the header's record_size says how long a file's records
 * are, and a reader takes the fields it knows: a shorter record's missing
 * fields read as zero, a longer one's are ignored.
 */
struct session_record {
	uint64_t cycle;
	uint64_t stamp_ns;        /* CLOCK_MONOTONIC of the cycle's wake-up */
	uint32_t state;           /* enum endosim_state_id */
	uint32_t fault_bits;      /* enum endosim_fault, latched */
	float position[ENDOSIM_AXES]; /* m, rad */
	float velocity[ENDOSIM_AXES]; /* m/s, rad/s */
	float hand[ENDOSIM_AXES];     /* N, N m: the simulated hand */
	float command[ENDOSIM_AXES];  /* N, N m: rendered */
	float limited[ENDOSIM_AXES];  /* N, N m: sent to the drives */
	float ramp;               /* enable ramp, 0..1 */
	/* the scope (struct endosim_scope_state) */
	float depth_m;
	float roll_rad;
	float bend_rad[2];
	float base_s_m;
	float tip_s_m;
	float turning_rad;
	float tip[3];
	float dir[3];
	float up[3];
	float bow_m[ENDOSIM_SPANS];
	/* the haptics (struct endosim_haptics_state) */
	float proxy[3];
	float normal[3];
	float f_static[3];        /* N */
	float penetration_m;
	uint32_t contact;         /* 1 while the wall holds the tip */
	uint32_t spans;           /* mobile segments in bow_m */
	float curvature_rad;
	float trans_contact_n;
	float trans_friction_n;
	float trans_loop_n;
	float wheel_contact_nm[2];
	float wheel_tension_nm[2];
	float wheel_elastic_nm[2];
	float tube_contact_nm;
	float tube_friction_nm;
	float scenario_time_s;
	uint32_t latency_ns;
	uint32_t compute_ns;
	/* format 2: the rod model (the haptics', struct endosim_rod_state);
	   where format 1 had two reserved zero words, then its end */
	float trans_rod_n;        /* N: the tube's reaction at the carriage */
	float tube_rod_nm;        /* N m: its twisting moment there */
	uint32_t model;           /* enum endosim_model */
	uint32_t contacts;        /* tube segments the wall presses */
	float wall_n;             /* N: the wall's normal forces, summed */
	float friction_n;         /* N: the friction's, sizes summed */
	/* format 3: guided replay (struct endosim_guide_state) */
	uint32_t guide_phase;     /* enum endosim_guide_phase */
	float guide_time_s;       /* the playhead, s of the recording */
	float guide_reference[ENDOSIM_AXES]; /* m, rad */
	float guide_force[ENDOSIM_AXES];     /* N, N m */
	/* format 4: the patient's body (struct endosim_patient_state); an
	   older record reads with patient 0: session_record_to_state() gives
	   the disabled patient's state then (factors 1, no site, no burst) */
	uint32_t patient;         /* 1: enabled */
	uint32_t valves;          /* enum endosim_valve bits */
	uint32_t patient_position; /* enum endosim_position, or turning to */
	uint32_t patient_turning; /* 1 while being turned */
	float patient_turn;       /* the turn's progress 0..1 */
	float gas_m3;             /* the gas in the colon */
	float gas_pressure_pa;    /* its pressure above the atmosphere */
	float gas_in_m3;          /* pumped in since the case was loaded */
	float lumen_factor[ENDOSIM_SEGMENTS]; /* each segment's radius factor */
	float fluid_m3[ENDOSIM_SEGMENTS];     /* fluid pooled in each */
	int32_t hand_site;        /* the site pressed (the case's), -1 none */
	float hand_n;             /* the assistant's press, N */
	float lens_smear;         /* 0..1 */
	float lens_murk;
	float lens_redout;
	int32_t burst_segment;    /* the first segment torn, -1: none */
	/* format 5: the patient responds; an older record reads with
	   sedation none, no pain, torn_segment -1 (as for burst_segment) */
	uint32_t sedation;        /* enum endosim_sedation */
	float pain;               /* 0..10 */
	float pain_stimulus;      /* 0..10 */
	uint32_t pain_cause;      /* enum endosim_pain_cause */
	int32_t pain_place;       /* the cause's segment, -1: none */
	float heart_rate_bpm;
	float spo2;               /* 0..1 */
	int32_t torn_segment;     /* where the tip tore the wall, -1: none */
	/* format 6: the tool in the working channel (struct
	   endosim_tool_state): what the rig sensed, the polyp held and what
	   happened, from which the rest follows (the loop, the clips); an
	   older record reads with no tool, nothing held (-1) */
	uint32_t tool_kind;       /* enum endosim_tool */
	float tool_snare_m;       /* the snare's size */
	float tool_depth_m;       /* beyond the channel's exit */
	float tool_opening;       /* the handle, 0..1 */
	uint32_t tool_pedal;      /* 1: down */
	int32_t tool_captured;    /* the polyp the loop holds, -1: none */
	uint32_t tool_events;     /* this cycle's enum endosim_tool_event */
	int32_t tool_event_polyp; /* the polyp they concern, -1: none */
	/* format 7: the bleeding points' flow, all together (m^3/s), from
	   which the blood shed follows; an older record reads with none */
	float tool_bleed_m3_s;
	/* format 8: one cut polyp's place a cycle, in turn (tool.h: the one
	   that moved, else the next lying), from which a replay draws each
	   where it lies; an older record reads with none (-1) */
	int32_t tool_lying_polyp; /* the case's order, -1: none */
	float tool_lying_at[3];   /* its body's centre, m */
} __attribute__((packed, aligned(4))); /* no tail padding: 4 bytes, not 8 */

_Static_assert(sizeof(struct session_record) == 572,
	       "session_record: its size is part of the file format");

/* Format 1's record: the fields up to compute_ns and two zero words. */
#define SESSION_RECORD_SIZE_1 304u
/* Format 7's: up to tool_bleed_m3_s. A shorter record reads with no
 * polyp lying (tool_lying_polyp -1). */
#define SESSION_RECORD_SIZE_7 556u
/* Format 6's: up to tool_event_polyp. A shorter record reads with no
 * bleeding. */
#define SESSION_RECORD_SIZE_6 552u
/* Format 5's: up to torn_segment. A shorter record reads with no tool,
 * tool_captured and tool_event_polyp -1 (none). */
#define SESSION_RECORD_SIZE_5 520u
/* Format 4's: up to burst_segment. A shorter record reads with
 * torn_segment and pain_place -1 (none), as no_patient() gives. */
#define SESSION_RECORD_SIZE_4 488u
/* Format 3's: up to guide_force. The CSV of a file of format 3 or older
 * has format 3's columns (the later ones appear where records hold them). */
#define SESSION_RECORD_SIZE_3 360u

/* What a session's event is (struct session_event.kind). */
enum session_event_kind {
	SESSION_EVENT_STATE = 1,   /* value: the new enum endosim_state_id */
	SESSION_EVENT_FAULT = 2,   /* axis, detail: the cause's bit number */
	SESSION_EVENT_PARAM = 3,   /* text: "section.key=value" */
	SESSION_EVENT_DROPS = 4,   /* value: records dropped so far */
	SESSION_EVENT_NOTE = 5,    /* text: anything else worth keeping */
	/* format 4: the patient's body, from the records' changes */
	SESSION_EVENT_POSITION = 6, /* value: the enum endosim_position;
				      detail 1: a turn towards it started,
				      0: settled in it */
	SESSION_EVENT_HAND = 7,    /* axis: the site pressed (the case's),
				      -1: released; value: the force, N */
	SESSION_EVENT_VALVE = 8,   /* detail: the enum endosim_valve bit;
				      value 1: on, 0: off */
	SESSION_EVENT_PERFORATION = 9, /* detail: the segment torn; value:
					  the gas pressure, Pa */
	/* format 5: the patient responds */
	SESSION_EVENT_TEAR = 10,   /* the tip tore the wall: a perforation;
				      detail: the segment; value: the tip's
				      force on the wall, N */
	SESSION_EVENT_SEDATION = 11, /* value: the enum endosim_sedation */
	/* format 6: the tool in the working channel */
	SESSION_EVENT_TOOL = 12,   /* a tool handed over (detail 0, axis
				      its enum endosim_tool, value a
				      snare's size, m) or one of its events
				      (detail its enum endosim_tool_event
				      bit, axis the polyp concerned or -1,
				      value the handle's opening; format
				      7: for bleed, clipped and stopped the
				      bleeding points' flow after it,
				      m^3/s) */
};

/* An event's fixed part; its text (not NUL-terminated) follows it. */
struct session_event {
	uint64_t stamp_ns;        /* CLOCK_MONOTONIC */
	uint32_t kind;            /* enum session_event_kind */
	int32_t axis;             /* -1: none or global */
	uint32_t detail;
	uint32_t reserved;
	double value;
};

_Static_assert(sizeof(struct session_event) == 32,
	       "session_event: its size is part of the file format");

/*
 * Fills OUT from one published state: the fields that fields.h's tables
 * say a record keeps, the rest zero. Never allocates; any thread.
 */
void session_record_from_state(const struct endosim_state *in,
			       struct session_record *out);

/*
 * The inverse, for a replay: fills the fields of OUT that a record holds
 * and zeroes the rest (the scope's tube is not recorded: rebuild it with
 * the scope's kinematics on the recorded case). A record without the
 * patient (disabled, or of format 3 or older) gives the disabled
 * patient's state: every lumen factor 1, no site, no burst; one without
 * a tool (none, or of format 5 or older) holds nothing (-1).
 */
void session_record_to_state(const struct session_record *in,
			     struct endosim_state *out);

/*
 * The rod's shape at one cycle (a SHAPE frame), as the rod model published
 * it (struct endosim_rod_state): the whole tube base to tip, its roll at
 * each point, and the mobile colon's nodes, each span's in order (span
 * 0's first). In the file its payload is the fields up to point (40
 * bytes), then point[POINTS], roll[POINTS] and node[NODES]: 40 + 16
 * POINTS + 12 NODES bytes, at most 5944; a later format may append to it.
 * The records keep the rest (the contacts, the forces, bow_m).
 */
struct session_shape {
	uint64_t cycle;           /* the record's it belongs to */
	uint64_t stamp_ns;        /* that record's stamp_ns */
	uint32_t points;          /* of point[] and roll[] */
	uint32_t nodes;           /* of node[] */
	uint32_t span_nodes[ENDOSIM_SPANS]; /* nodes per mobile span */
	float point[ENDOSIM_ROD_POINTS][3]; /* m, base to tip */
	float roll[ENDOSIM_ROD_POINTS];     /* rad */
	float node[ENDOSIM_COLON_NODES][3]; /* m, each node's from rest */
};

#define SESSION_SHAPE_HZ 30 /* the least rate of SHAPE frames */

/*
 * The cycles from one SHAPE frame to the next for a force loop of
 * PERIOD_NS: the most that keeps them at SESSION_SHAPE_HZ or more (33 at
 * 1 kHz: 30.3 Hz), 1 for a loop slower than that.
 */
uint32_t session_shape_every(uint64_t period_ns);

/*
 * Whether the cycle ST published has a SHAPE frame: the rod model's every
 * EVERY-th cycle (cycle 0 first; EVERY: session_shape_every()'s, 1 or
 * more). Never allocates; any thread.
 */
bool session_shape_due(const struct endosim_state *st, uint32_t every);

/*
 * OUT from one published state's rod (the counts capped at the arrays);
 * only the elements in use are written. Never allocates; any thread.
 */
void session_shape_from_state(const struct endosim_state *in,
			      struct session_shape *out);

/*
 * The inverse, for a replay: OUT's rod shape (points, roll, nodes, span
 * nodes; the arrays' unused elements zero) and its scope.bow_m, each
 * mobile span's largest node displacement, as the rod model publishes
 * it. The rest of OUT is left as it was (a record's).
 */
void session_shape_to_state(const struct session_shape *in,
			    struct endosim_state *out);

/*
 * S as a SHAPE frame's payload into OUT (sizeof(struct session_shape)
 * bytes at least). Returns its length.
 */
uint32_t session_shape_pack(const struct session_shape *s, void *out);

/* --- writing ---------------------------------------------------------- */

/* What the HEADER frame says (see the keys above). */
struct session_header {
	uint64_t id;
	const char *trainee;
	const char *case_name;
	const char *started;      /* UTC, ISO 8601 */
	uint64_t start_ns;
	uint64_t period_ns;
	const char *version;
	double step_m;
	int ring_vertices;
	double segment_m;
};

/*
 * H as the HEADER frame's text into BUF (SIZE bytes, NUL-terminated), with
 * the format and the record size. Returns its length, or -ENAMETOOLONG
 * when it does not fit.
 */
int session_header_text(const struct session_header *h, char *buf,
			size_t size);

/* Writes the magic to FD (a new, empty file). 0 or -errno. */
int session_file_write_magic(int fd);

/* Writes one frame to FD. 0 or -errno (a short write is -EIO). */
int session_file_write_frame(int fd, uint32_t type, const void *payload,
			     uint32_t length);

/*
 * Frames are also built in memory, so that a writer can gather many
 * records into one write(2): appends one frame to BUF (of SIZE bytes,
 * USED of them filled). Returns the bytes it took, or 0 when it does not
 * fit (BUF unchanged).
 */
size_t session_frame_put(unsigned char *buf, size_t size, size_t used,
			 uint32_t type, const void *payload, uint32_t length);

/* --- reading ---------------------------------------------------------- */

/*
 * A session file in memory. The arrays point into one allocation;
 * session_file_close() frees it. HEADER, CONFIG, CASE and END are
 * NUL-terminated copies of their frames' text (NULL when absent: END is
 * absent from a file cut short).
 */
struct session_file {
	char *header;
	char *config;
	char *case_text;
	char *end;
	struct session_record *records;
	size_t n_records;
	size_t record_size;       /* the records' length in the file (0:
				     none): what their format holds */
	struct session_file_event {
		struct session_event ev;
		char *text;           /* NUL-terminated, maybe empty */
	} *events;
	size_t n_events;
	struct session_file_shape {
		uint64_t stamp_ns;
		const unsigned char *payload; /* the SHAPE frame's */
		uint32_t length;
	} *shapes;                /* in the file's order: by time */
	size_t n_shapes;
	size_t bytes_read;        /* up to the end of the last good frame */
	size_t bytes_ignored;     /* after it: a cut or damaged tail */
	void *storage;
};

/*
 * Reads PATH. 0, or -errno: -ENOENT, -EACCES, ... ; -EBADMSG when it is
 * not a session file (no magic or no header frame), -EPROTO when its
 * records are shorter than format 1's, of two sizes, or not the size its
 * header says. A format-1 file's records read with the later fields
 * zero; a later format's longer ones by their first fields. Logs nothing:
 * the caller says it.
 */
int session_file_read(const char *path, struct session_file *out);

/* Frees what session_file_read() allocated; safe on a zeroed struct. */
void session_file_close(struct session_file *f);

/*
 * The value of KEY in "key=value\n" TEXT (a header or an end frame),
 * copied into OUT (SIZE bytes, NUL-terminated). 0, or -ENOENT.
 */
int session_text_get(const char *text, const char *key, char *out,
		     size_t size);

/* The index of the last record at or before STAMP_NS (0 if none is). */
size_t session_file_seek(const struct session_file *f, uint64_t stamp_ns);

/* The same among the SHAPE frames (0 if none is; none if no shapes). */
size_t session_file_seek_shape(const struct session_file *f,
			       uint64_t stamp_ns);

/* SHAPE frame I of F (below n_shapes) into OUT. */
void session_file_shape(const struct session_file *f, size_t i,
			struct session_shape *out);

/* CRC-32 (IEEE 802.3, reflected) of N bytes: zlib's crc32_z(). */
uint32_t session_crc32(uint32_t crc, const void *data, size_t n);

#endif
