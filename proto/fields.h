/*
 * fields.h - one description of the published state's fields: for each
 * struct of the shared-memory state (endosim_shm.h) that the wire carries,
 * a table of its fields, each with its kind, its name, its place in the
 * struct, in the protobuf message (endosim.proto) and in the session
 * record (session_file.h). Made of these tables alone:
 *
 *   - the status reply from the state: fields_to_pb(), by the control
 *     thread, table by table (the daemon fills the wire's own fields);
 *   - the session record from the state and back: fields_to_record() and
 *     fields_from_record(), under session_record_from_state() and
 *     session_record_to_state();
 *   - the CSV columns of `endoctl session export`: fields_columns();
 *   - `endoctl --json status`: endoctl walks the tables (endoctl_print.c).
 *
 * The tables: fields_status (struct endosim_state's own fields and the
 * safety monitors' that the wire carries: StatusReply), and, reached from
 * it by its sub-message rows, fields_fault (a latched fault's cause:
 * Fault), fields_scope (ScopeStatus), fields_haptics (HapticsStatus),
 * fields_rod (RodStatus), fields_guide (GuideStatus), fields_patient
 * (PatientStatus), fields_tool (ToolStatus) with fields_tool_polyp (each
 * of the case's polyps: ToolPolyp) and fields_axis (each axis:
 * AxisStatus). A table's
 * rows are in the order of the message's JSON.
 *
 * Adding a field to the published state:
 *   1. the field in its struct in endosim_shm.h (bump ENDOSIM_SHM_VERSION);
 *   2. the field in its message in endosim.proto, under a new number;
 *   3. ONE row in its struct's table in fields.c, where its JSON key goes
 *      (the macros there: a value, a vector, ...);
 *   and, only for a field sessions keep, the field in struct
 *   session_record (at its end: the record's layout is the file format,
 *   whose files already written read with it zero; the CSV's columns are
 *   in the record's order) and the row's record offset (with its columns
 *   for a vector or an axis' field).
 * That is all: the reply, endoctl's JSON, the record and the CSV follow.
 * A field of the state that the wire does not carry and no session keeps
 * is named in tests/unit/test_fields.c's list of such fields, with why:
 * that test fails on any byte of the published structs, of StatusReply's
 * messages or of the record that no row (or that list) accounts for.
 */
#ifndef ENDOSIM_FIELDS_H
#define ENDOSIM_FIELDS_H

#include <stddef.h>
#include <stdint.h>

#include "proto/endosim.pb-c.h"
#include "proto/endosim_shm.h"

/* A field's kind: how the state, the wire, the record and the JSON hold it. */
enum fields_kind {
	/* a value of the state (or, without SHM, the wire's own) */
	FIELDS_DOUBLE,  /* double; a float in the record */
	FIELDS_UINT,    /* uint32_t */
	FIELDS_UINT64,  /* uint64_t */
	FIELDS_BOOL,    /* uint32_t 0/1 in the state and record, a bool */
	FIELDS_NAMED,   /* uint32_t in the state and record, a uint32 or an
			   enum on the wire; the JSON writes NAMES(value) */
	FIELDS_VECTOR,  /* double[N] in the state, repeated double, N floats
			   in the record */
	FIELDS_INT,     /* int32_t (or, without SHM, the wire's own) */
	/* the wire's own: never in the state, the daemon fills them */
	FIELDS_STRING,  /* char * */
	FIELDS_KEY,     /* char *: the message's key in its FIELDS_MAP */
	/* sub-messages, described by SUB */
	FIELDS_MESSAGE, /* one, a pointer (NULL: absent): a JSON object */
	FIELDS_LIST,    /* repeated: a JSON array of objects */
	FIELDS_MAP,     /* repeated: a JSON object of objects by their KEY */
};

#define FIELDS_NONE ((size_t)-1) /* an offset: not there */

struct fields_field {
	const char *name;   /* its JSON key; a scalar's CSV column */
	enum fields_kind kind;
	size_t n;           /* FIELDS_VECTOR: its length in the state; else 1 */
	size_t shm;         /* offset in the table's struct; FIELDS_NONE: the
			       wire's own */
	size_t shm_n;       /* FIELDS_VECTOR: a uint32_t of the struct that
			       counts the elements in use (at most N; the
			       record keeps all N); FIELDS_NONE: all N are */
	size_t pb;          /* offset in the message; FIELDS_NONE: not on the
			       wire (a recorded field) */
	size_t pb_n;        /* a repeated field's n_ count in the message */
	size_t record;      /* offset in struct session_record of the first
			       element (of the first axis); FIELDS_NONE: not
			       recorded */
	const char *const *columns; /* recorded: its CSV columns, one per
				       element (per axis), NULL-terminated;
				       NULL: a scalar's name */
	const char *(*names)(uint32_t value); /* FIELDS_NAMED */
	const struct fields_table *sub; /* the sub-message kinds */
};

struct fields_table {
	const ProtobufCMessageDescriptor *pb; /* its message */
	const struct fields_field *fields;
	size_t n_fields;
	size_t shm;         /* where its (first) struct is in endosim_state */
	size_t size;        /* the struct's size: the step to the next one */
	size_t count;       /* how many: 1, ENDOSIM_AXES, ENDOSIM_FAULT_BITS */
};

extern const struct fields_table fields_status; /* the root */
extern const struct fields_table fields_fault;
extern const struct fields_table fields_scope;
extern const struct fields_table fields_haptics;
extern const struct fields_table fields_rod;
extern const struct fields_table fields_guide;
extern const struct fields_table fields_patient;
extern const struct fields_table fields_tool;
extern const struct fields_table fields_tool_polyp;
extern const struct fields_table fields_axis;

/*
 * Initialises MSG, a message of T's, and fills it from SHM, one struct of
 * T's: the values of the state. The wire's own fields and the
 * sub-messages are left to the caller. MSG's repeated fields point into
 * SHM, which must outlive it (the message never writes through them). Any
 * thread; never allocates.
 */
void fields_to_pb(const struct fields_table *t, void *msg, const void *shm);

/*
 * Copies the recorded fields of T and of the tables below it between the
 * published state ST and the session record REC (a struct session_record,
 * filled or read at the fields' offsets only: the caller zeroes the rest).
 * Any thread; never allocates.
 */
void fields_to_record(const struct fields_table *t,
		      const struct endosim_state *st, void *rec);
void fields_from_record(const struct fields_table *t, const void *rec,
			struct endosim_state *st);

/* How a record holds a recorded value. */
enum fields_stored {
	FIELDS_STORED_U64,
	FIELDS_STORED_U32,
	FIELDS_STORED_F32,
	FIELDS_STORED_I32,
};

/* One CSV column: a recorded value. */
struct fields_column {
	const char *name;   /* its unit as a suffix: insertion_position_m */
	enum fields_stored stored;
	size_t record;      /* offset in struct session_record */
};

/*
 * The CSV columns of a session's records, in the record's order: every
 * recorded value of the tables from fields_status but the time stamp (the
 * CSV gives it as t_s). Returns how many there are; OUT (MAX long) holds
 * them when that is at most MAX.
 */
size_t fields_columns(struct fields_column *out, size_t max);

#endif
