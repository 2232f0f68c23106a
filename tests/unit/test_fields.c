/*
 * test_fields.c - fields.h's tables against the structs they describe, so
 * that a field added to the state, to a message or to the record without
 * its row fails here:
 *   - every byte of struct endosim_state is some row's (in every axis,
 *     every fault cause) or in the list below of what neither the wire nor
 *     a session carries, and none is twice;
 *   - every field of StatusReply and of its sub-messages is one row's, of
 *     the protobuf type, label and count the row's kind says;
 *   - every byte of struct session_record is one recorded row's;
 *   - names unique in a table, rows within their struct, a vector's count
 *     within it, a recorded field's columns one per element;
 *   - the CSV columns are the session format's, in the record's order;
 *   - the reply's values are the state's (a bool, a state's name, a vector
 *     counted by another field and capped at its length).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "proto/fields.h"
#include "proto/names.h"
#include "proto/session_file.h"

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))
#define NONE FIELDS_NONE

/*
 * What the wire does not carry and no session keeps, and why: in each
 * struct of the table (each axis, each cause).
 */
static const struct {
	const struct fields_table *t;
	size_t at, size;
	const char *why;
} not_carried[] = {
#define NOT(table, type, f, why)                                             \
	{ &table, offsetof(type, f), sizeof(((type *)0)->f), why }
#define STATE(f, why) NOT(fields_status, struct endosim_state, f, why)
#define CAUSE(f, why) NOT(fields_fault, struct endosim_fault_cause, f, why)
#define AXIS(f, why) NOT(fields_axis, struct endosim_axis_state, f, why)
#define SCOPE(f, why) NOT(fields_scope, struct endosim_scope_state, f, why)
#define ROD(f, why) NOT(fields_rod, struct endosim_rod_state, f, why)
#define PATIENT(f, why)                                                      \
	NOT(fields_patient, struct endosim_patient_state, f, why)
#define TOOL(f, why) NOT(fields_tool, struct endosim_tool_state, f, why)
	STATE(publish_ns, "the publisher's own clock, for shm readers"),
	STATE(fault_axis, "the first fault's: faults[0] says it"),
	STATE(fault_detail, "the first fault's: faults[0] says it"),
	STATE(fault_ns, "the first fault's: faults[0] says it"),
	STATE(fault_first, "which fault is faults[0]"),
	STATE(safety.overrun_periods, "the safety monitor's own"),
	STATE(safety.enabled_ns, "the safety monitor's own"),
	STATE(safety.saturated_s, "the safety monitor's own"),
	STATE(safety.faults_latched, "the safety monitor's own"),
	CAUSE(first_ns, "the daemon says it as time_s"),
	CAUSE(axis, "the daemon says it as the axis' name"),
	AXIS(feedback_ns, "the feedback's age: the safety monitor's"),
	AXIS(reserved, "padding"),
	SCOPE(reserved, "padding"),
	SCOPE(tube, "the shape (1.5 kB): the viewer's, from the shm"),
	ROD(point, "the shape (3.9 kB): the shm's, sessions' SHAPE frames"),
	ROD(roll, "the shape's roll: the shm's, sessions' SHAPE frames"),
	ROD(node, "the colon's nodes: the shm's, sessions' SHAPE frames"),
	ROD(span_nodes, "the nodes' spans: the shm's, SHAPE frames'"),
	PATIENT(reserved, "padding"),
	TOOL(reserved, "padding"),
#undef NOT
#undef STATE
#undef CAUSE
#undef AXIS
#undef SCOPE
#undef ROD
#undef PATIENT
#undef TOOL
};

/* Every table, from the root, each once. */
static size_t all_tables(const struct fields_table **out, size_t max)
{
	size_t n = 0;

	out[n++] = &fields_status;
	for (size_t k = 0; k < n; k++) {
		for (size_t i = 0; i < out[k]->n_fields; i++) {
			const struct fields_table *sub = out[k]->fields[i].sub;
			bool seen = false;

			for (size_t m = 0; m < n; m++) {
				seen = seen || out[m] == sub;
			}
			if (sub && !seen) {
				assert_true(n < max);
				out[n++] = sub;
			}
		}
	}
	return n;
}

/* The bytes of one element of D in the state and in the record, as
 * fields.h documents the kinds. */
static size_t state_bytes(const struct fields_field *d)
{
	switch (d->kind) {
	case FIELDS_UINT:
	case FIELDS_BOOL:
	case FIELDS_NAMED:
	case FIELDS_INT:
		return sizeof(uint32_t);
	case FIELDS_UINT64:
		return sizeof(uint64_t);
	default:
		return sizeof(double);
	}
}

static size_t record_bytes(const struct fields_field *d)
{
	return d->kind == FIELDS_UINT64 ? sizeof(uint64_t) : 4;
}

static void mark(unsigned char *map, size_t size, size_t at, size_t n)
{
	assert_true(at + n <= size);
	for (size_t i = at; i < at + n; i++) {
		map[i]++;
	}
}

/* Which table's struct holds byte AT of the state (the deepest). */
static const char *region(const struct fields_table **t, size_t n,
			  size_t at, size_t *within)
{
	const char *name = "StatusReply";

	*within = at;
	for (size_t k = 1; k < n; k++) {
		if (at >= t[k]->shm && at < t[k]->shm + t[k]->count * t[k]->size) {
			name = t[k]->pb->short_name;
			*within = (at - t[k]->shm) % t[k]->size;
		}
	}
	return name;
}

static void test_state_covered(void **state)
{
	static unsigned char map[sizeof(struct endosim_state)];
	const struct fields_table *t[16];
	size_t n = all_tables(t, COUNT(t)), bad = 0;

	(void)state;
	assert_int_equal(n, 10);
	for (size_t k = 0; k < n; k++) {
		for (size_t i = 0; i < t[k]->n_fields; i++) {
			const struct fields_field *d = &t[k]->fields[i];

			for (size_t c = 0; d->shm != NONE && c < t[k]->count;
			     c++) {
				mark(map, sizeof(map),
				     t[k]->shm + c * t[k]->size + d->shm,
				     d->n * state_bytes(d));
			}
		}
	}
	for (size_t i = 0; i < COUNT(not_carried); i++) {
		for (size_t c = 0; c < not_carried[i].t->count; c++) {
			mark(map, sizeof(map),
			     not_carried[i].t->shm + c * not_carried[i].t->size +
				     not_carried[i].at,
			     not_carried[i].size);
		}
	}
	for (size_t at = 0, end; at < sizeof(map); at = end) {
		size_t within;
		const char *in = region(t, n, at, &within);

		for (end = at + 1; end < sizeof(map) && map[end] == map[at];
		     end++) {
		}
		if (map[at] != 1 && bad++ < 8) {
			print_error("bytes %zu..%zu of the state (%s's struct "
				    "+ %zu): %s\n", at, end - 1, in, within,
				    map[at] ? "in two rows" :
				    "no row, and not in not_carried");
		}
	}
	assert_int_equal(bad, 0);
}

/* Whether D's kind is what protobuf field F is. */
static bool kind_fits(const struct fields_field *d,
		      const ProtobufCFieldDescriptor *f)
{
	bool many = f->label == PROTOBUF_C_LABEL_REPEATED;
	bool count = many && f->quantifier_offset == d->pb_n;

	switch (d->kind) {
	case FIELDS_DOUBLE:
		return f->type == PROTOBUF_C_TYPE_DOUBLE && !many;
	case FIELDS_UINT:
		return f->type == PROTOBUF_C_TYPE_UINT32 && !many;
	case FIELDS_UINT64:
		return f->type == PROTOBUF_C_TYPE_UINT64 && !many;
	case FIELDS_BOOL:
		return f->type == PROTOBUF_C_TYPE_BOOL && !many;
	case FIELDS_NAMED:
		return (f->type == PROTOBUF_C_TYPE_UINT32 ||
			f->type == PROTOBUF_C_TYPE_ENUM) && !many && d->names;
	case FIELDS_VECTOR:
		return f->type == PROTOBUF_C_TYPE_DOUBLE && count;
	case FIELDS_INT:
		return f->type == PROTOBUF_C_TYPE_INT32 && !many;
	case FIELDS_STRING:
	case FIELDS_KEY:
		return f->type == PROTOBUF_C_TYPE_STRING && !many;
	case FIELDS_MESSAGE:
		return f->type == PROTOBUF_C_TYPE_MESSAGE && !many &&
		       f->descriptor == d->sub->pb;
	case FIELDS_LIST:
	case FIELDS_MAP:
		return f->type == PROTOBUF_C_TYPE_MESSAGE && count &&
		       f->descriptor == d->sub->pb;
	}
	return false;
}

static void test_wire_covered(void **state)
{
	const struct fields_table *t[16];
	size_t n = all_tables(t, COUNT(t));

	(void)state;
	for (size_t k = 0; k < n; k++) {
		const ProtobufCMessageDescriptor *m = t[k]->pb;

		for (unsigned int f = 0; f < m->n_fields; f++) {
			const ProtobufCFieldDescriptor *fd = &m->fields[f];
			size_t rows = 0, derived = 0;

			for (size_t i = 0; i < t[k]->n_fields; i++) {
				const struct fields_field *d = &t[k]->fields[i];

				if (d->pb != fd->offset) {
					continue;
				}
				if (!kind_fits(d, fd)) {
					fail_msg("%s.%s: row %s of the wrong "
						 "kind", m->short_name,
						 fd->name, d->name);
				}
				/* a word for another row's value (drive) */
				if (d->kind == FIELDS_NAMED && d->shm == NONE) {
					derived++;
				} else {
					rows++;
				}
			}
			if (rows != 1) {
				fail_msg("%s.%s: in %zu rows (and %zu words "
					 "for it), not one", m->short_name,
					 fd->name, rows, derived);
			}
		}
		for (size_t i = 0; i < t[k]->n_fields; i++) {
			const struct fields_field *d = &t[k]->fields[i];
			bool found = d->pb == NONE;

			for (unsigned int f = 0; f < m->n_fields; f++) {
				found = found || d->pb == m->fields[f].offset;
			}
			if (!found) {
				fail_msg("%s: row %s is no field of it",
					 m->short_name, d->name);
			}
		}
	}
}

/* The columns of D: one per element, per struct of its table. */
static void check_columns(const struct fields_table *t,
			  const struct fields_field *d)
{
	size_t n = 0;

	if (!d->columns) {
		assert_int_equal(d->n * t->count, 1);
		return;
	}
	while (d->columns[n]) {
		n++;
	}
	/* none: the record's time stamp, the CSV's t_s */
	if (n == 0) {
		assert_string_equal(d->name, "stamp_ns");
		return;
	}
	if (n != d->n * t->count) {
		fail_msg("%s.%s: %zu columns for %zu values", t->pb->short_name,
			 d->name, n, d->n * t->count);
	}
}

static void check_row(const struct fields_table *t,
		      const struct fields_field *d)
{
	bool sub = d->kind == FIELDS_MESSAGE || d->kind == FIELDS_LIST ||
		   d->kind == FIELDS_MAP;
	bool own = d->kind == FIELDS_STRING || d->kind == FIELDS_KEY;

	assert_true(d->name && *d->name);
	assert_true(d->pb != NONE || d->record != NONE);
	assert_true(d->record == NONE || d->shm != NONE);
	assert_int_equal(d->sub != NULL, sub);
	assert_int_equal(d->names != NULL, d->kind == FIELDS_NAMED);
	if (sub || own) {
		assert_true(d->shm == NONE && d->record == NONE);
	}
	assert_true(d->kind == FIELDS_VECTOR ? d->n >= 1 : d->n == 1);
	if (d->shm != NONE) {
		assert_true(d->shm + d->n * state_bytes(d) <= t->size);
	}
	if (d->shm_n != NONE) {
		assert_int_equal(d->kind, FIELDS_VECTOR);
		assert_true(d->shm_n + sizeof(uint32_t) <= t->size);
	}
	if (d->record != NONE) {
		check_columns(t, d);
	}
}

static void test_rows(void **state)
{
	const struct fields_table *t[16];
	size_t n = all_tables(t, COUNT(t));

	(void)state;
	for (size_t k = 0; k < n; k++) {
		size_t keys = 0;

		for (size_t i = 0; i < t[k]->n_fields; i++) {
			const struct fields_field *d = &t[k]->fields[i];

			check_row(t[k], d);
			keys += d->kind == FIELDS_KEY;
			for (size_t j = 0; j < i; j++) {
				if (!strcmp(t[k]->fields[j].name, d->name)) {
					fail_msg("%s: two rows named %s",
						 t[k]->pb->short_name, d->name);
				}
			}
			if (d->kind == FIELDS_MAP) {
				size_t sub_keys = 0;

				for (size_t j = 0; j < d->sub->n_fields; j++) {
					sub_keys += d->sub->fields[j].kind ==
						    FIELDS_KEY;
				}
				assert_int_equal(sub_keys, 1);
			}
		}
		assert_true(keys <= 1);
		assert_true(t[k]->shm + t[k]->count * t[k]->size <=
			    sizeof(struct endosim_state));
	}
}

static void test_record_covered(void **state)
{
	static unsigned char map[sizeof(struct session_record)];
	const struct fields_table *t[16];
	size_t n = all_tables(t, COUNT(t));

	(void)state;
	for (size_t k = 0; k < n; k++) {
		for (size_t i = 0; i < t[k]->n_fields; i++) {
			const struct fields_field *d = &t[k]->fields[i];

			if (d->record != NONE) {
				mark(map, sizeof(map), d->record,
				     t[k]->count * d->n * record_bytes(d));
			}
		}
	}
	for (size_t at = 0; at < sizeof(map); at++) {
		if (map[at] != 1) {
			fail_msg("byte %zu of the record: in %d rows", at,
				 map[at]);
		}
	}
}

/* The CSV's columns, as docs/SESSION_FORMAT.md's format 6 has them. */
static const char csv_columns[] =
	"cycle,state,fault_bits,insertion_position_m,roll_position_rad,"
	"wheel_ud_position_rad,wheel_lr_position_rad,"
	"insertion_velocity_m_per_s,roll_velocity_rad_per_s,"
	"wheel_ud_velocity_rad_per_s,wheel_lr_velocity_rad_per_s,"
	"insertion_hand_n,roll_hand_nm,wheel_ud_hand_nm,wheel_lr_hand_nm,"
	"insertion_command_n,roll_command_nm,wheel_ud_command_nm,"
	"wheel_lr_command_nm,insertion_limited_n,roll_limited_nm,"
	"wheel_ud_limited_nm,wheel_lr_limited_nm,ramp,depth_m,roll_rad,"
	"bend_ud_rad,bend_lr_rad,base_s_m,tip_s_m,turning_rad,tip_x_m,"
	"tip_y_m,tip_z_m,dir_x_1,dir_y_1,dir_z_1,up_x_1,up_y_1,up_z_1,"
	"bow0_m,bow1_m,bow2_m,bow3_m,proxy_x_m,proxy_y_m,proxy_z_m,"
	"normal_x_1,normal_y_1,normal_z_1,f_static_x_n,f_static_y_n,"
	"f_static_z_n,penetration_m,contact,spans,curvature_rad,"
	"trans_contact_n,trans_friction_n,trans_loop_n,wheel_contact_ud_nm,"
	"wheel_contact_lr_nm,wheel_tension_ud_nm,wheel_tension_lr_nm,"
	"wheel_elastic_ud_nm,wheel_elastic_lr_nm,tube_contact_nm,"
	"tube_friction_nm,scenario_time_s,latency_ns,compute_ns,trans_rod_n,"
	"tube_rod_nm,rod_model,rod_contacts,rod_wall_n,rod_friction_n,"
	"guide_phase,guide_time_s,guide_reference_insertion_m,"
	"guide_reference_roll_rad,guide_reference_wheel_ud_rad,"
	"guide_reference_wheel_lr_rad,guide_force_insertion_n,"
	"guide_force_roll_nm,guide_force_wheel_ud_nm,guide_force_wheel_lr_nm,"
	/* format 4: the patient */
	"patient_enabled,patient_valves,patient_position,patient_turning,"
	"patient_turn_1,patient_gas_m3,patient_pressure_pa,patient_gas_in_m3,"
	"patient_factor_anal_canal_1,patient_factor_rectum_1,"
	"patient_factor_sigmoid_1,patient_factor_descending_1,"
	"patient_factor_splenic_flexure_1,patient_factor_transverse_1,"
	"patient_factor_hepatic_flexure_1,patient_factor_ascending_1,"
	"patient_factor_cecum_1,patient_fluid_anal_canal_m3,"
	"patient_fluid_rectum_m3,patient_fluid_sigmoid_m3,"
	"patient_fluid_descending_m3,patient_fluid_splenic_flexure_m3,"
	"patient_fluid_transverse_m3,patient_fluid_hepatic_flexure_m3,"
	"patient_fluid_ascending_m3,patient_fluid_cecum_m3,"
	"patient_hand_site,patient_hand_n,patient_lens_smear_1,"
	"patient_lens_murk_1,patient_lens_redout_1,patient_burst_segment,"
	/* format 5: the patient responds */
	"patient_sedation,patient_pain,patient_pain_stimulus,"
	"patient_pain_cause,patient_pain_place,patient_heart_rate_bpm,"
	"patient_spo2_1,patient_torn_segment,"
	/* format 6: the tool in the working channel */
	"tool_kind,tool_snare_m,tool_depth_m,tool_opening_1,tool_pedal,"
	"tool_captured,tool_events,tool_event_polyp,"
	/* format 7: the bleeding */
	"tool_bleed_m3_s,"
	/* format 8: a cut polyp lying */
	"tool_lying_polyp,tool_lying_x_m,tool_lying_y_m,tool_lying_z_m";

/* The column called NAME among C's N. */
static const struct fields_column *column(const struct fields_column *c,
					  size_t n, const char *name)
{
	for (size_t i = 0; i < n; i++) {
		if (!strcmp(c[i].name, name)) {
			return &c[i];
		}
	}
	fail_msg("no column %s", name);
	return NULL;
}

static void test_columns(void **state)
{
	struct fields_column c[160], few[3];
	size_t n = fields_columns(c, COUNT(c)), len = 0;
	char line[4096];

	(void)state;
	assert_true(n <= COUNT(c));
	for (size_t i = 0; i < n; i++) {
		assert_true(i == 0 || c[i].record > c[i - 1].record);
		len += (size_t)snprintf(line + len, sizeof(line) - len, "%s%s",
					i ? "," : "", c[i].name);
		assert_true(len < sizeof(line));
	}
	assert_string_equal(line, csv_columns);
	assert_int_equal(fields_columns(few, COUNT(few)), n); /* past MAX */
	assert_int_equal(c[0].record, offsetof(struct session_record, cycle));
	assert_int_equal(c[0].stored, FIELDS_STORED_U64);
	assert_int_equal(c[1].stored, FIELDS_STORED_U32);
	assert_int_equal(column(c, n, "rod_model")->stored, FIELDS_STORED_U32);
	assert_int_equal(column(c, n, "guide_phase")->stored,
			 FIELDS_STORED_U32);
	assert_int_equal(column(c, n, "guide_force_wheel_lr_nm")->stored,
			 FIELDS_STORED_F32);
	assert_int_equal(column(c, n, "guide_force_wheel_lr_nm")->record,
			 offsetof(struct session_record, guide_force) +
			 3 * sizeof(float));
	assert_int_equal(column(c, n, "patient_valves")->stored,
			 FIELDS_STORED_U32);
	assert_int_equal(column(c, n, "patient_fluid_cecum_m3")->record,
			 offsetof(struct session_record, fluid_m3) +
			 8 * sizeof(float));
	assert_int_equal(column(c, n, "patient_hand_site")->stored,
			 FIELDS_STORED_I32);
	assert_int_equal(column(c, n, "patient_torn_segment")->stored,
			 FIELDS_STORED_I32);
	assert_int_equal(column(c, n, "tool_events")->stored,
			 FIELDS_STORED_U32);
	assert_int_equal(column(c, n, "tool_opening_1")->stored,
			 FIELDS_STORED_F32);
	assert_int_equal(column(c, n, "tool_lying_polyp")->stored,
			 FIELDS_STORED_I32);
	assert_int_equal(c[n - 1].stored, FIELDS_STORED_F32);
	assert_int_equal(c[n - 1].record,
			 offsetof(struct session_record, tool_lying_at[2]));
}

/* A state whose every double and word differs. */
static void distinct(struct endosim_state *st)
{
	memset(st, 0, sizeof(*st));
	st->state = ENDOSIM_STATE_ESTOP;
	st->cycle = 1ull << 40;
	st->safety.active = 0x24;
	st->safety.ramp = 0.625;
	st->scenario_done = 7;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		st->axis[a].position = a + 0.5;
		st->axis[a].limited = -a - 0.25;
		st->axis[a].drive_status = ENDOSIM_DRIVE_PRESENT;
	}
	st->scope.bend_rad[1] = -0.75;
	st->scope.bow_m[1] = 0.02;
	st->scope.scene_id = 99;
	st->haptics.contact = 1;
	st->haptics.damping[3] = 4.5;
	st->haptics.trans_rod_n = -1.5;
	st->haptics.tube_rod_nm = 0.125;
	st->safety.cause[2].value = 3.25;
	st->safety.cause[2].detail = 17;
	st->rod.model = ENDOSIM_MODEL_ROD;
	st->rod.contacts = 12;
	st->rod.wall_n = 3.5;
	st->rod.friction_n = 0.375;
	st->rod.points = 161;
	st->rod.nodes = 40;
	st->patient.enabled = 1;
	st->patient.valves = ENDOSIM_VALVE_AIR | ENDOSIM_VALVE_SUCTION;
	st->patient.position = ENDOSIM_POSITION_SUPINE;
	st->patient.turning = 1;
	st->patient.turn = 0.25;
	st->patient.gas_m3 = 0.0015;
	st->patient.pressure_pa = 1250;
	st->patient.factor[8] = 1.125;
	st->patient.fluid_m3[2] = 5e-5;
	st->patient.fluid_up[1] = -1;
	st->patient.hand_site = 1;
	st->patient.hand_n = 30;
	st->patient.pad_n = 4.5;
	st->patient.lens_murk = 0.5;
	st->patient.burst_segment = -1;
}

static void test_to_pb(void **state)
{
	struct endosim_state st;
	Endosim__StatusReply s;
	Endosim__ScopeStatus sc;
	Endosim__HapticsStatus h;
	Endosim__AxisStatus ax;
	Endosim__RodStatus rod;
	Endosim__PatientStatus pat;
	Endosim__Fault f;

	(void)state;
	distinct(&st);
	fields_to_pb(&fields_status, &s, &st);
	assert_int_equal(s.state, ENDOSIM__DAEMON_STATE__DAEMON_STATE_ESTOP);
	assert_int_equal(s.cycle, 1ull << 40);
	assert_int_equal(s.active_faults, 0x24);
	assert_true(s.ramp == 0.625);
	assert_true(s.scenario_done);
	assert_null(s.scope);
	assert_int_equal(s.n_axes, 0);
	assert_string_equal(s.rig, ""); /* the daemon's own */
	fields_to_pb(&fields_axis, &ax, &st.axis[2]);
	assert_true(ax.position == 2.5 && ax.limited == -2.25);
	assert_int_equal(ax.drive_status, ENDOSIM_DRIVE_PRESENT);
	fields_to_pb(&fields_fault, &f, &st.safety.cause[2]);
	assert_true(f.value == 3.25);
	assert_int_equal(f.detail, 17);
	fields_to_pb(&fields_haptics, &h, &st.haptics);
	assert_true(h.contact);
	assert_int_equal(h.n_damping, ENDOSIM_AXES);
	assert_ptr_equal(h.damping, st.haptics.damping);
	st.scope.spans = 2;
	fields_to_pb(&fields_scope, &sc, &st.scope);
	assert_int_equal(sc.n_bend_rad, 2);
	assert_true(sc.bend_rad[1] == -0.75);
	assert_int_equal(sc.n_bow_m, 2);
	assert_true(sc.bow_m[1] == 0.02);
	assert_int_equal(sc.scene_id, 99);
	st.scope.spans = 1000; /* never past the array */
	fields_to_pb(&fields_scope, &sc, &st.scope);
	assert_int_equal(sc.n_bow_m, ENDOSIM_SPANS);
	assert_true(protobuf_c_message_check(&sc.base));
	assert_null(s.rod);
	fields_to_pb(&fields_rod, &rod, &st.rod);
	assert_int_equal(rod.model, ENDOSIM__HAPTICS_MODEL__HAPTICS_MODEL_ROD);
	assert_string_equal(names_model(rod.model), "rod");
	assert_int_equal(rod.contacts, 12);
	assert_true(rod.wall_n == 3.5 && rod.friction_n == 0.375);
	assert_int_equal(rod.points, 161);
	assert_int_equal(rod.nodes, 40);
	assert_true(protobuf_c_message_check(&rod.base));
	assert_null(s.patient);
	fields_to_pb(&fields_patient, &pat, &st.patient);
	assert_true(pat.enabled && pat.turning);
	assert_int_equal(pat.valves, 5);
	assert_string_equal(names_valves(pat.valves), "air,suction");
	assert_int_equal(pat.position,
			 ENDOSIM__PATIENT_POSITION__PATIENT_POSITION_SUPINE);
	assert_string_equal(names_position(pat.position), "supine");
	assert_true(pat.turn == 0.25 && pat.pressure_pa == 1250);
	assert_int_equal(pat.n_factor, ENDOSIM_SEGMENTS);
	assert_true(pat.factor[8] == 1.125);
	assert_true(pat.fluid_up[1] == -1);
	assert_int_equal(pat.hand_site, 1);
	assert_int_equal(pat.burst_segment, -1);
	assert_true(pat.pad_n == 4.5 && pat.lens_murk == 0.5);
	assert_string_equal(pat.site, ""); /* the daemon's own */
	pat.site = "llq";
	assert_true(protobuf_c_message_check(&pat.base));
}

/* The record keeps what the tables say, as floats, and gives it back. */
static void test_record(void **state)
{
	struct endosim_state st, back;
	struct session_record r;

	(void)state;
	distinct(&st);
	st.scope.spans = 3;
	st.latency_ns = 12345;
	session_record_from_state(&st, &r);
	assert_int_equal(r.state, ENDOSIM_STATE_ESTOP);
	assert_true(r.limited[3] == -3.25f);
	assert_true(r.bend_rad[1] == -0.75f);
	assert_true(r.bow_m[1] == 0.02f);
	assert_int_equal(r.spans, 3);
	assert_int_equal(r.latency_ns, 12345);
	assert_int_equal(r.model, ENDOSIM_MODEL_ROD);
	assert_int_equal(r.contacts, 12);
	assert_true(r.wall_n == 3.5f && r.friction_n == 0.375f);
	assert_true(r.trans_rod_n == -1.5f && r.tube_rod_nm == 0.125f);
	session_record_to_state(&r, &back);
	assert_true(back.axis[1].position == 1.5);
	assert_true(back.safety.ramp == 0.625);
	assert_true(back.scope.bow_m[1] == (double)0.02f);
	assert_int_equal(back.haptics.contact, 1);
	assert_true(back.haptics.damping[3] == 0); /* not recorded */
	assert_int_equal(back.scope.scene_id, 0);
	assert_int_equal(back.rod.model, ENDOSIM_MODEL_ROD);
	assert_int_equal(back.rod.contacts, 12);
	assert_true(back.rod.wall_n == 3.5 && back.rod.friction_n == 0.375);
	assert_true(back.haptics.trans_rod_n == -1.5);
	assert_true(back.haptics.tube_rod_nm == 0.125);
	assert_int_equal(back.rod.points, 0); /* a SHAPE frame's */
	assert_int_equal(r.patient, 1);
	assert_int_equal(r.valves, 5);
	assert_int_equal(r.patient_position, ENDOSIM_POSITION_SUPINE);
	assert_true(r.gas_m3 == 0.0015f && r.lumen_factor[8] == 1.125f);
	assert_int_equal(r.hand_site, 1);
	assert_int_equal(r.burst_segment, -1);
	assert_int_equal(back.patient.enabled, 1);
	assert_int_equal(back.patient.turning, 1);
	assert_true(back.patient.turn == 0.25);
	assert_true(back.patient.pressure_pa == 1250);
	assert_true(back.patient.fluid_m3[2] == (double)5e-5f);
	assert_int_equal(back.patient.hand_site, 1);
	assert_true(back.patient.hand_n == 30);
	assert_true(back.patient.lens_murk == 0.5);
	assert_int_equal(back.patient.burst_segment, -1);
	assert_true(back.patient.pad_n == 0); /* not recorded */
	assert_true(back.patient.fluid_up[1] == 0);
}

/* A record without the patient (disabled, or an older format's, whose
 * fields read zero) gives the disabled patient's state, not a colon
 * collapsed with the hand at site 0 and the anal canal torn. */
static void test_record_no_patient(void **state)
{
	struct session_record r;
	struct endosim_state back;

	(void)state;
	memset(&r, 0, sizeof(r));
	r.valves = ENDOSIM_VALVE_WATER;
	session_record_to_state(&r, &back);
	assert_int_equal(back.patient.enabled, 0);
	assert_int_equal(back.patient.hand_site, -1);
	assert_int_equal(back.patient.burst_segment, -1);
	for (int i = 0; i < ENDOSIM_SEGMENTS; i++) {
		assert_true(back.patient.factor[i] == 1);
	}
	assert_int_equal(back.patient.valves, ENDOSIM_VALVE_WATER);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_state_covered),
		cmocka_unit_test(test_wire_covered),
		cmocka_unit_test(test_rows),
		cmocka_unit_test(test_record_covered),
		cmocka_unit_test(test_columns),
		cmocka_unit_test(test_to_pb),
		cmocka_unit_test(test_record),
		cmocka_unit_test(test_record_no_patient),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
