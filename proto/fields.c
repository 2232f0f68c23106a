/* fields.c - see fields.h. */
#include "proto/fields.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "proto/names.h"
#include "proto/session_file.h"

#define NONE FIELDS_NONE
#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* Offsets in the record, and in the struct (STRUCT) and the message
 * (MESSAGE) of the table being written. */
#define R(f) offsetof(struct session_record, f)
#define S(f) offsetof(STRUCT, f)
#define P(f) offsetof(MESSAGE, f)
#define LEN(f) (sizeof(((STRUCT *)0)->f) / sizeof(double))

/* a value NAME: in the struct at SHM, on the wire at PB, recorded at REC */
#define ROW(name, kind, shm, pb, rec)                                        \
	{ name, kind, 1, shm, NONE, pb, NONE, rec, NULL, NULL, NULL }
/* value F: in the struct and on the wire (and recorded), named alike */
#define VAL(f, kind) ROW(#f, kind, S(f), P(f), NONE)
#define REC(f, kind) ROW(#f, kind, S(f), P(f), R(f))
/* the wire's own F */
#define WIRE(f, kind) ROW(#f, kind, NONE, P(f), NONE)
/* F recorded, not on the wire */
#define KEPT(f, kind) ROW(#f, kind, S(f), NONE, R(f))
/* vector F, on the wire (and recorded, in COLUMNS) */
#define VEC(f)                                                               \
	{ #f, FIELDS_VECTOR, LEN(f), S(f), NONE, P(f), P(n_##f), NONE, NULL, \
	  NULL, NULL }
#define VEC_REC(f, columns)                                                  \
	{ #f, FIELDS_VECTOR, LEN(f), S(f), NONE, P(f), P(n_##f), R(f),       \
	  columns, NULL, NULL }
/* sub-message F, of table T: one, or many (KIND) */
#define ONE(f, t)                                                            \
	{ #f, FIELDS_MESSAGE, 1, NONE, NONE, P(f), NONE, NONE, NULL, NULL, t }
#define MANY(f, kind, t)                                                     \
	{ #f, kind, 1, NONE, NONE, P(f), P(n_##f), NONE, NULL, NULL, t }

/* A recorded vector's CSV columns, its unit as a suffix. */
#define COLUMNS(...) ((const char *const[]){ __VA_ARGS__, NULL })
#define XYZ(stem, unit)                                                      \
	COLUMNS(stem "_x_" unit, stem "_y_" unit, stem "_z_" unit)
#define UD_LR(stem, unit) COLUMNS(stem "_ud_" unit, stem "_lr_" unit)
#define SPANS(stem, unit)                                                    \
	COLUMNS(stem "0_" unit, stem "1_" unit, stem "2_" unit, stem "3_" unit)
#define NO_COLUMN ((const char *const[]){ NULL })

#define TABLE(rows, descriptor, where, how_many)                             \
	{ &descriptor, rows, COUNT(rows),                                    \
	  offsetof(struct endosim_state, where), sizeof(STRUCT), how_many }

_Static_assert(ENDOSIM_SPANS == 4, "fields: a bow column per span");
_Static_assert(ENDOSIM_AXES == 4, "fields: an axis' columns per axis");
_Static_assert(sizeof(Endosim__DaemonState) == sizeof(uint32_t),
	       "fields: the state is a uint32_t on the wire too");
_Static_assert(sizeof(Endosim__HapticsModel) == sizeof(uint32_t),
	       "fields: the model is a uint32_t on the wire too");
_Static_assert(sizeof(Endosim__PatientPosition) == sizeof(uint32_t),
	       "fields: the position is a uint32_t on the wire too");
_Static_assert(ENDOSIM_SEGMENTS == 9, "fields: a column per segment");

/* --- one latched fault: its cause's values; the daemon says the rest -- */
#define STRUCT struct endosim_fault_cause
#define MESSAGE Endosim__Fault
static const struct fields_field fault[] = {
	WIRE(code, FIELDS_UINT),
	WIRE(name, FIELDS_STRING),
	WIRE(axis, FIELDS_STRING),
	WIRE(time_s, FIELDS_DOUBLE),
	WIRE(text, FIELDS_STRING),
	WIRE(active, FIELDS_BOOL),
	VAL(value, FIELDS_DOUBLE),
	VAL(limit, FIELDS_DOUBLE),
	VAL(detail, FIELDS_UINT),
};
const struct fields_table fields_fault =
	TABLE(fault, endosim__fault__descriptor, safety.cause,
	      ENDOSIM_FAULT_BITS);
#undef STRUCT
#undef MESSAGE

/* --- an axis: the JSON keys it by its name; CSV columns per axis ------- */
#define STRUCT struct endosim_axis_state
#define MESSAGE Endosim__AxisStatus
#define AXES(f, lin, rot)                                                    \
	COLUMNS("insertion_" #f "_" lin, "roll_" #f "_" rot,                 \
		"wheel_ud_" #f "_" rot, "wheel_lr_" #f "_" rot)
#define AX(f, lin, rot)                                                      \
	{ #f, FIELDS_DOUBLE, 1, S(f), NONE, P(f), NONE, R(f),                \
	  AXES(f, lin, rot), NULL, NULL }
static const struct fields_field axis[] = {
	WIRE(name, FIELDS_KEY),
	AX(position, "m", "rad"),
	AX(velocity, "m_per_s", "rad_per_s"),
	AX(hand, "n", "nm"),
	AX(command, "n", "nm"),
	AX(limited, "n", "nm"),
	WIRE(position_unit, FIELDS_STRING),
	WIRE(force_unit, FIELDS_STRING),
	VAL(drive_status, FIELDS_UINT),
	/* the JSON's word for it */
	{ "drive", FIELDS_NAMED, 1, NONE, NONE, P(drive_status), NONE, NONE,
	  NULL, names_drive_status, NULL },
};
const struct fields_table fields_axis =
	TABLE(axis, endosim__axis_status__descriptor, axis, ENDOSIM_AXES);
#undef STRUCT
#undef MESSAGE

/* --- the scope --------------------------------------------------------- */
#define STRUCT struct endosim_scope_state
#define MESSAGE Endosim__ScopeStatus
static const struct fields_field scope[] = {
	REC(depth_m, FIELDS_DOUBLE),
	REC(tip_s_m, FIELDS_DOUBLE),
	REC(base_s_m, FIELDS_DOUBLE),
	REC(turning_rad, FIELDS_DOUBLE),
	VEC_REC(bend_rad, UD_LR("bend", "rad")),
	VEC_REC(tip, XYZ("tip", "m")),
	VEC_REC(dir, XYZ("dir", "1")),
	VEC_REC(up, XYZ("up", "1")),
	/* as many on the wire as spans says */
	{ "bow_m", FIELDS_VECTOR, LEN(bow_m), S(bow_m), S(spans), P(bow_m),
	  P(n_bow_m), R(bow_m), SPANS("bow", "m"), NULL, NULL },
	VAL(scene_id, FIELDS_UINT64),
	/* recorded, not on the wire */
	KEPT(roll_rad, FIELDS_DOUBLE),
	KEPT(spans, FIELDS_UINT),
};
const struct fields_table fields_scope =
	TABLE(scope, endosim__scope_status__descriptor, scope, 1);
#undef STRUCT
#undef MESSAGE

/* --- the haptic rendering's parts -------------------------------------- */
#define STRUCT struct endosim_haptics_state
#define MESSAGE Endosim__HapticsStatus
static const struct fields_field haptics[] = {
	REC(contact, FIELDS_BOOL),
	VAL(constraints, FIELDS_UINT),
	VEC_REC(proxy, XYZ("proxy", "m")),
	VEC_REC(normal, XYZ("normal", "1")),
	VEC_REC(f_static, XYZ("f_static", "n")),
	REC(penetration_m, FIELDS_DOUBLE),
	REC(curvature_rad, FIELDS_DOUBLE),
	REC(trans_contact_n, FIELDS_DOUBLE),
	REC(trans_friction_n, FIELDS_DOUBLE),
	REC(trans_loop_n, FIELDS_DOUBLE),
	REC(trans_rod_n, FIELDS_DOUBLE),
	VEC_REC(wheel_contact_nm, UD_LR("wheel_contact", "nm")),
	VEC_REC(wheel_tension_nm, UD_LR("wheel_tension", "nm")),
	VEC_REC(wheel_elastic_nm, UD_LR("wheel_elastic", "nm")),
	VEC(wire_dl_m),
	REC(tube_contact_nm, FIELDS_DOUBLE),
	REC(tube_friction_nm, FIELDS_DOUBLE),
	REC(tube_rod_nm, FIELDS_DOUBLE),
	VEC(damping),
	VAL(passivity_energy_j, FIELDS_DOUBLE),
	VAL(passivity_damping, FIELDS_DOUBLE),
};
const struct fields_table fields_haptics =
	TABLE(haptics, endosim__haptics_status__descriptor, haptics, 1);
#undef STRUCT
#undef MESSAGE

/* --- the rod model: its contacts and counts; the shape stays in the shm */
#define STRUCT struct endosim_rod_state
#define MESSAGE Endosim__RodStatus
/* recorded F, its CSV column said to be the rod's */
#define ROD(f, kind, names)                                                  \
	{ #f, kind, 1, S(f), NONE, P(f), NONE, R(f), COLUMNS("rod_" #f),     \
	  names, NULL }
static const struct fields_field rod[] = {
	ROD(model, FIELDS_NAMED, names_model),
	ROD(contacts, FIELDS_UINT, NULL),
	ROD(wall_n, FIELDS_DOUBLE, NULL),
	ROD(friction_n, FIELDS_DOUBLE, NULL),
	VAL(points, FIELDS_UINT),
	VAL(nodes, FIELDS_UINT),
};
const struct fields_table fields_rod =
	TABLE(rod, endosim__rod_status__descriptor, rod, 1);
#undef ROD
#undef STRUCT
#undef MESSAGE

/* --- guided replay: recorded with its reference and force per axis ---- */
#define STRUCT struct endosim_guide_state
#define MESSAGE Endosim__GuideStatus
#define GUIDE_AXES(stem, lin, rot)                                           \
	COLUMNS("guide_" stem "_insertion_" lin, "guide_" stem "_roll_" rot, \
		"guide_" stem "_wheel_ud_" rot, "guide_" stem "_wheel_lr_" rot)
static const struct fields_field guide[] = {
	{ "phase", FIELDS_NAMED, 1, S(phase), NONE, P(phase), NONE,
	  R(guide_phase), COLUMNS("guide_phase"), names_guide_phase, NULL },
	{ "ended", FIELDS_NAMED, 1, S(ended), NONE, P(ended), NONE, NONE,
	  NULL, names_guide_end, NULL },
	VAL(source_id, FIELDS_UINT64),
	{ "time_s", FIELDS_DOUBLE, 1, S(time_s), NONE, P(time_s), NONE,
	  R(guide_time_s), COLUMNS("guide_time_s"), NULL, NULL },
	VAL(length_s, FIELDS_DOUBLE),
	VAL(speed, FIELDS_DOUBLE),
	VAL(fade, FIELDS_DOUBLE),
	VAL(takeovers, FIELDS_UINT),
	{ "lost_axis", FIELDS_NAMED, 1, S(lost_axis), NONE, P(lost_axis),
	  NONE, NONE, NULL, names_guide_axis, NULL },
	{ "reference", FIELDS_VECTOR, LEN(reference), S(reference), NONE,
	  P(reference), P(n_reference), R(guide_reference),
	  GUIDE_AXES("reference", "m", "rad"), NULL, NULL },
	{ "force", FIELDS_VECTOR, LEN(force), S(force), NONE, P(force),
	  P(n_force), R(guide_force), GUIDE_AXES("force", "n", "nm"), NULL,
	  NULL },
	VEC(error),
	VEC(hand),
	{ "expert_kind", FIELDS_NAMED, 1, S(expert_kind), NONE,
	  P(expert_kind), NONE, NONE, NULL, names_tool, NULL },
	VAL(expert_pedal, FIELDS_BOOL),
	VAL(expert_snare_m, FIELDS_DOUBLE),
	VAL(expert_depth_m, FIELDS_DOUBLE),
	VAL(expert_opening, FIELDS_DOUBLE),
	VAL(expert_loop_m, FIELDS_DOUBLE),
	VEC(expert_tip),
	VEC(expert_loop_centre),
};
const struct fields_table fields_guide =
	TABLE(guide, endosim__guide_status__descriptor, guide, 1);
#undef GUIDE_AXES
#undef STRUCT
#undef MESSAGE

/* --- the patient's body: recorded as the list has it --------- */
#define STRUCT struct endosim_patient_state
#define MESSAGE Endosim__PatientStatus
#define SEGS(stem, unit)                                                     \
	COLUMNS(stem "anal_canal_" unit, stem "rectum_" unit,                \
		stem "sigmoid_" unit, stem "descending_" unit,               \
		stem "splenic_flexure_" unit, stem "transverse_" unit,       \
		stem "hepatic_flexure_" unit, stem "ascending_" unit,        \
		stem "cecum_" unit)
/* F recorded at the record's RF, its CSV column COLUMN */
#define PAT(f, kind, rf, column, names)                                      \
	{ #f, kind, 1, S(f), NONE, P(f), NONE, R(rf), COLUMNS(column),       \
	  names, NULL }
static const struct fields_field patient[] = {
	PAT(enabled, FIELDS_BOOL, patient, "patient_enabled", NULL),
	PAT(valves, FIELDS_NAMED, valves, "patient_valves", names_valves),
	PAT(position, FIELDS_NAMED, patient_position, "patient_position",
	    names_position),
	PAT(turning, FIELDS_BOOL, patient_turning, "patient_turning", NULL),
	PAT(turn, FIELDS_DOUBLE, patient_turn, "patient_turn_1", NULL),
	VEC(down),
	PAT(gas_m3, FIELDS_DOUBLE, gas_m3, "patient_gas_m3", NULL),
	PAT(pressure_pa, FIELDS_DOUBLE, gas_pressure_pa,
	    "patient_pressure_pa", NULL),
	PAT(gas_in_m3, FIELDS_DOUBLE, gas_in_m3, "patient_gas_in_m3", NULL),
	{ "factor", FIELDS_VECTOR, LEN(factor), S(factor), NONE, P(factor),
	  P(n_factor), R(lumen_factor), SEGS("patient_factor_", "1"), NULL,
	  NULL },
	VEC(transmural_pa),
	VEC(tension_n_per_m),
	VEC_REC(fluid_m3, SEGS("patient_fluid_", "m3")),
	VEC(fluid_level_m),
	VEC(fluid_up),
	PAT(hand_site, FIELDS_INT, hand_site, "patient_hand_site", NULL),
	WIRE(site, FIELDS_STRING),
	VAL(tip_in_fluid, FIELDS_BOOL),
	PAT(hand_n, FIELDS_DOUBLE, hand_n, "patient_hand_n", NULL),
	VAL(pad_n, FIELDS_DOUBLE),
	PAT(lens_smear, FIELDS_DOUBLE, lens_smear, "patient_lens_smear_1",
	    NULL),
	PAT(lens_murk, FIELDS_DOUBLE, lens_murk, "patient_lens_murk_1", NULL),
	PAT(lens_redout, FIELDS_DOUBLE, lens_redout, "patient_lens_redout_1",
	    NULL),
	PAT(burst_segment, FIELDS_INT, burst_segment, "patient_burst_segment",
	    NULL),
	PAT(sedation, FIELDS_NAMED, sedation, "patient_sedation",
	    names_sedation),
	PAT(pain, FIELDS_DOUBLE, pain, "patient_pain", NULL),
	PAT(pain_stimulus, FIELDS_DOUBLE, pain_stimulus,
	    "patient_pain_stimulus", NULL),
	PAT(pain_cause, FIELDS_NAMED, pain_cause, "patient_pain_cause",
	    names_pain_cause),
	PAT(pain_place, FIELDS_INT, pain_place, "patient_pain_place", NULL),
	PAT(heart_rate_bpm, FIELDS_DOUBLE, heart_rate_bpm,
	    "patient_heart_rate_bpm", NULL),
	PAT(spo2, FIELDS_DOUBLE, spo2, "patient_spo2_1", NULL),
	PAT(torn_segment, FIELDS_INT, torn_segment, "patient_torn_segment",
	    NULL),
};
const struct fields_table fields_patient =
	TABLE(patient, endosim__patient_status__descriptor, patient, 1);
#undef PAT
#undef SEGS
#undef STRUCT
#undef MESSAGE

/* --- the tool in the working channel: its sensing and events recorded - */
#define STRUCT struct endosim_tool_polyp
#define MESSAGE Endosim__ToolPolyp
static const struct fields_field tool_polyp[] = {
	{ "state", FIELDS_NAMED, 1, S(state), NONE, P(state), NONE, NONE,
	  NULL, names_polyp_state, NULL },
	VAL(lifted, FIELDS_BOOL),
	VAL(energy_j, FIELDS_DOUBLE),
	VAL(bites, FIELDS_UINT),
	{ "bleed", FIELDS_NAMED, 1, S(bleed), NONE, P(bleed), NONE, NONE,
	  NULL, names_bleed, NULL },
	VAL(bleed_m3_s, FIELDS_DOUBLE),
	VAL(blood_m3, FIELDS_DOUBLE),
	VEC(at),
};
const struct fields_table fields_tool_polyp =
	TABLE(tool_polyp, endosim__tool_polyp__descriptor, tool.polyp,
	      ENDOSIM_POLYPS);
#undef STRUCT
#undef MESSAGE

#define STRUCT struct endosim_tool_state
#define MESSAGE Endosim__ToolStatus
/* F recorded at the record's tool_F, its CSV column COLUMN */
#define TOOL(f, kind, column, names)                                         \
	{ #f, kind, 1, S(f), NONE, P(f), NONE, R(tool_##f), COLUMNS(column), \
	  names, NULL }
static const struct fields_field tool[] = {
	TOOL(kind, FIELDS_NAMED, "tool_kind", names_tool),
	TOOL(pedal, FIELDS_BOOL, "tool_pedal", NULL),
	TOOL(snare_m, FIELDS_DOUBLE, "tool_snare_m", NULL),
	TOOL(depth_m, FIELDS_DOUBLE, "tool_depth_m", NULL),
	TOOL(opening, FIELDS_DOUBLE, "tool_opening_1", NULL),
	VAL(loop_m, FIELDS_DOUBLE),
	VEC(tip),
	VEC(loop_centre),
	TOOL(captured, FIELDS_INT, "tool_captured", NULL),
	TOOL(events, FIELDS_UINT, "tool_events", NULL),
	TOOL(event_polyp, FIELDS_INT, "tool_event_polyp", NULL),
	VAL(clips, FIELDS_UINT),
	VAL(polyps, FIELDS_UINT),
	MANY(polyp, FIELDS_LIST, &fields_tool_polyp),
	VAL(bleeding, FIELDS_UINT),
	TOOL(bleed_m3_s, FIELDS_DOUBLE, "tool_bleed_m3_s", NULL),
	VAL(blood_m3, FIELDS_DOUBLE),
	VEC(bleed_at),
	VEC(clip_at),
	TOOL(lying_polyp, FIELDS_INT, "tool_lying_polyp", NULL),
	{ "lying_at", FIELDS_VECTOR, LEN(lying_at), S(lying_at), NONE,
	  P(lying_at), P(n_lying_at), R(tool_lying_at),
	  XYZ("tool_lying", "m"), NULL, NULL },
};
const struct fields_table fields_tool =
	TABLE(tool, endosim__tool_status__descriptor, tool, 1);
#undef TOOL
#undef STRUCT
#undef MESSAGE

/* --- the state's own fields, the safety monitors', the parts ---------- */
#define STRUCT struct endosim_state
#define MESSAGE Endosim__StatusReply
static const struct fields_field status[] = {
	{ "state", FIELDS_NAMED, 1, S(state), NONE, P(state), NONE, R(state),
	  NULL, names_state, NULL },
	REC(fault_bits, FIELDS_UINT),
	ROW("fault", FIELDS_STRING, NONE, P(fault_text), NONE),
	MANY(faults, FIELDS_LIST, &fields_fault),
	ROW("active_faults", FIELDS_UINT, S(safety.active), P(active_faults),
	    NONE),
	ROW("ramp", FIELDS_DOUBLE, S(safety.ramp), P(ramp), R(ramp)),
	REC(cycle, FIELDS_UINT64),
	/* the CSV's t_s */
	{ "stamp_ns", FIELDS_UINT64, 1, S(stamp_ns), NONE, P(stamp_ns), NONE,
	  R(stamp_ns), NO_COLUMN, NULL, NULL },
	WIRE(rt_policy, FIELDS_STRING),
	WIRE(rt_priority, FIELDS_INT),
	WIRE(loop_hz, FIELDS_DOUBLE),
	WIRE(loop_rate_hz, FIELDS_DOUBLE),
	VAL(overruns, FIELDS_UINT64),
	WIRE(rig, FIELDS_STRING),
	WIRE(version, FIELDS_STRING),
	WIRE(uptime_s, FIELDS_DOUBLE),
	REC(scenario_time_s, FIELDS_DOUBLE),
	VAL(scenario_done, FIELDS_BOOL),
	ROW("case", FIELDS_STRING, NONE, P(case_name), NONE),
	WIRE(trainee, FIELDS_STRING),
	WIRE(asks_trainee, FIELDS_BOOL),
	ONE(scope, &fields_scope),
	ONE(haptics, &fields_haptics),
	ONE(rod, &fields_rod),
	ONE(guide, &fields_guide),
	ONE(patient, &fields_patient),
	ONE(tool, &fields_tool),
	MANY(axes, FIELDS_MAP, &fields_axis),
	/* recorded, not on the wire */
	KEPT(latency_ns, FIELDS_UINT),
	KEPT(compute_ns, FIELDS_UINT),
};
const struct fields_table fields_status = {
	&endosim__status_reply__descriptor, status, COUNT(status), 0,
	sizeof(struct endosim_state), 1,
};
#undef STRUCT
#undef MESSAGE

/* ----------------------------------------------------------- the wire */

static void field_to_pb(const struct fields_field *d, unsigned char *msg,
			const unsigned char *shm)
{
	const unsigned char *src = shm + d->shm;
	unsigned char *dst = msg + d->pb;
	protobuf_c_boolean b;
	uint32_t u;
	size_t n = d->n;

	switch (d->kind) {
	case FIELDS_DOUBLE:
	case FIELDS_UINT64:
		memcpy(dst, src, 8);
		break;
	case FIELDS_UINT:
	case FIELDS_NAMED:
	case FIELDS_INT:
		memcpy(dst, src, sizeof(uint32_t));
		break;
	case FIELDS_BOOL:
		memcpy(&u, src, sizeof(u));
		b = (protobuf_c_boolean)u;
		memcpy(dst, &b, sizeof(b));
		break;
	case FIELDS_VECTOR:
		if (d->shm_n != NONE) {
			memcpy(&u, shm + d->shm_n, sizeof(u));
			n = u < n ? u : n;
		}
		memcpy(dst, &src, sizeof(src));
		memcpy(msg + d->pb_n, &n, sizeof(n));
		break;
	default:
		break; /* the wire's own, the sub-messages: the caller's */
	}
}

void fields_to_pb(const struct fields_table *t, void *msg, const void *shm)
{
	protobuf_c_message_init(t->pb, msg);
	for (size_t i = 0; i < t->n_fields; i++) {
		const struct fields_field *d = &t->fields[i];

		if (d->shm != NONE && d->pb != NONE) {
			field_to_pb(d, msg, shm);
		}
	}
}

/* -------------------------------------------------------- the record */

static enum fields_stored stored(enum fields_kind kind)
{
	switch (kind) {
	case FIELDS_UINT64:
		return FIELDS_STORED_U64;
	case FIELDS_DOUBLE:
	case FIELDS_VECTOR:
		return FIELDS_STORED_F32;
	case FIELDS_INT:
		return FIELDS_STORED_I32;
	default:
		return FIELDS_STORED_U32;
	}
}

/* The bytes of one element of KIND in the state and in the record. */
static size_t state_size(enum fields_kind kind)
{
	enum fields_stored how = stored(kind);

	return how == FIELDS_STORED_U64 || how == FIELDS_STORED_F32 ? 8 : 4;
}

static size_t record_size(enum fields_kind kind)
{
	return stored(kind) == FIELDS_STORED_U64 ? 8 : 4;
}

/* One element of D between the state's SHM and the record's REC. */
static void copy_element(const struct fields_field *d, unsigned char *shm,
			 unsigned char *rec, bool to_record)
{
	double v;
	float f;

	if (stored(d->kind) != FIELDS_STORED_F32) {
		memcpy(to_record ? rec : shm, to_record ? shm : rec,
		       record_size(d->kind));
	} else if (to_record) {
		memcpy(&v, shm, sizeof(v));
		f = (float)v;
		memcpy(rec, &f, sizeof(f));
	} else {
		memcpy(&f, rec, sizeof(f));
		v = f;
		memcpy(shm, &v, sizeof(v));
	}
}

/* The recorded fields of T and below between the state ST and REC. */
static void copy_table(const struct fields_table *t, unsigned char *st,
		       unsigned char *rec, bool to_record)
{
	for (size_t i = 0; i < t->n_fields; i++) {
		const struct fields_field *d = &t->fields[i];
		size_t in_state = state_size(d->kind);
		size_t in_rec = record_size(d->kind);

		if (d->sub) {
			copy_table(d->sub, st, rec, to_record);
		}
		if (d->record == NONE) {
			continue;
		}
		for (size_t k = 0; k < t->count; k++) {
			for (size_t e = 0; e < d->n; e++) {
				copy_element(d, st + t->shm + k * t->size +
						 d->shm + e * in_state,
					     rec + d->record +
						 (k * d->n + e) * in_rec,
					     to_record);
			}
		}
	}
}

void fields_to_record(const struct fields_table *t,
		      const struct endosim_state *st, void *rec)
{
	copy_table(t, (unsigned char *)st, rec, true);
}

void fields_from_record(const struct fields_table *t, const void *rec,
			struct endosim_state *st)
{
	copy_table(t, (unsigned char *)st, (unsigned char *)rec, false);
}

/* ------------------------------------------------------- the columns */

/* Column N, when OUT (MAX long) has room for it. */
static void put_column(struct fields_column *out, size_t max, size_t n,
		       const char *name, enum fields_stored how, size_t rec)
{
	if (n < max) {
		out[n].name = name;
		out[n].stored = how;
		out[n].record = rec;
	}
}

/* The columns of T and below into OUT from N on; the count so far. */
static size_t table_columns(const struct fields_table *t,
			    struct fields_column *out, size_t max, size_t n)
{
	for (size_t i = 0; i < t->n_fields; i++) {
		const struct fields_field *d = &t->fields[i];
		enum fields_stored how = stored(d->kind);

		if (d->sub) {
			n = table_columns(d->sub, out, max, n);
		}
		if (d->record == NONE) {
			continue;
		}
		if (!d->columns) {
			put_column(out, max, n++, d->name, how, d->record);
			continue;
		}
		for (size_t c = 0; d->columns[c]; c++) {
			put_column(out, max, n++, d->columns[c], how,
				   d->record + c * record_size(d->kind));
		}
	}
	return n;
}

static int by_record(const void *a, const void *b)
{
	const struct fields_column *x = a, *y = b;

	return (x->record > y->record) - (x->record < y->record);
}

size_t fields_columns(struct fields_column *out, size_t max)
{
	size_t n = table_columns(&fields_status, out, max, 0);

	if (n <= max) {
		qsort(out, n, sizeof(*out), by_record);
	}
	return n;
}
