/*
 * endoctl_print.c - how endoctl prints the daemon's replies, as text or
 * JSON (endoctl.h).
 */
#include "endoctl/endoctl.h"

/* ------------------------------------------------------------ printing */

static void json_vector(struct json *j, const char *key, const double *v,
			size_t n)
{
	json_array_begin(j, key);
	for (size_t i = 0; i < n; i++) {
		json_double(j, NULL, v[i]);
	}
	json_array_end(j);
}

static void json_message(struct json *j, const char *key,
			 const struct fields_table *t, const void *msg);

/* The repeated sub-message D of MSG: its messages and their count. */
static size_t sub_messages(const struct fields_field *d, const void *msg,
			   const void *const **out)
{
	size_t n;

	memcpy(out, (const unsigned char *)msg + d->pb, sizeof(*out));
	memcpy(&n, (const unsigned char *)msg + d->pb_n, sizeof(n));
	return n;
}

/* The key of MSG, a message of T, in its FIELDS_MAP. */
static const char *map_key(const struct fields_table *t, const void *msg)
{
	const char *key = "";

	for (size_t i = 0; i < t->n_fields; i++) {
		if (t->fields[i].kind == FIELDS_KEY) {
			memcpy(&key, (const unsigned char *)msg +
					     t->fields[i].pb, sizeof(key));
		}
	}
	return key;
}

/* Sub-message field D of MSG (one, a list or a map) under its name. */
static void json_sub(struct json *j, const struct fields_field *d,
		     const void *msg)
{
	const void *one, *const *many;
	size_t n;

	if (d->kind == FIELDS_MESSAGE) {
		memcpy(&one, (const unsigned char *)msg + d->pb, sizeof(one));
		if (one) {
			json_message(j, d->name, d->sub, one);
		}
		return;
	}
	n = sub_messages(d, msg, &many);
	if (d->kind == FIELDS_LIST) {
		json_array_begin(j, d->name);
	} else {
		json_object_begin(j, d->name);
	}
	for (size_t k = 0; k < n; k++) {
		json_message(j, d->kind == FIELDS_MAP ? map_key(d->sub, many[k])
						      : NULL,
			     d->sub, many[k]);
	}
	if (d->kind == FIELDS_LIST) {
		json_array_end(j);
	} else {
		json_object_end(j);
	}
}

/* Field D of MSG under its name (fields.h). */
static void json_field(struct json *j, const struct fields_field *d,
		       const void *msg)
{
	const unsigned char *v = (const unsigned char *)msg + d->pb;
	const double *vec;
	const char *str;
	protobuf_c_boolean b;
	uint64_t u64;
	uint32_t u;
	int32_t i;
	double x;
	size_t n;

	switch (d->kind) {
	case FIELDS_DOUBLE:
		memcpy(&x, v, sizeof(x));
		json_double(j, d->name, x);
		break;
	case FIELDS_UINT:
		memcpy(&u, v, sizeof(u));
		json_uint(j, d->name, u);
		break;
	case FIELDS_UINT64:
		memcpy(&u64, v, sizeof(u64));
		json_uint(j, d->name, u64);
		break;
	case FIELDS_BOOL:
		memcpy(&b, v, sizeof(b));
		json_bool(j, d->name, b);
		break;
	case FIELDS_NAMED:
		memcpy(&u, v, sizeof(u));
		json_string(j, d->name, d->names(u));
		break;
	case FIELDS_VECTOR:
		memcpy(&vec, v, sizeof(vec));
		memcpy(&n, (const unsigned char *)msg + d->pb_n, sizeof(n));
		json_vector(j, d->name, vec, n);
		break;
	case FIELDS_INT:
		memcpy(&i, v, sizeof(i));
		json_int(j, d->name, i);
		break;
	case FIELDS_STRING:
		memcpy(&str, v, sizeof(str));
		json_string(j, d->name, str);
		break;
	case FIELDS_KEY:
		break; /* the key of this message's object in its map */
	case FIELDS_MESSAGE:
	case FIELDS_LIST:
	case FIELDS_MAP:
		json_sub(j, d, msg);
		break;
	}
}

/* MSG, a message of T, as an object under KEY, its fields in T's order. */
static void json_message(struct json *j, const char *key,
			 const struct fields_table *t, const void *msg)
{
	json_object_begin(j, key);
	for (size_t i = 0; i < t->n_fields; i++) {
		if (t->fields[i].pb != FIELDS_NONE) {
			json_field(j, &t->fields[i], msg);
		}
	}
	json_object_end(j);
}

void ctl_json_part(const struct fields_table *t, const void *msg)
{
	struct json j;

	json_init(&j, stdout);
	json_message(&j, NULL, t, msg);
}

void ctl_json_patient(const Endosim__PatientStatus *p)
{
	ctl_json_part(&fields_patient, p);
}

void ctl_json_status(const Endosim__StatusReply *s)
{
	struct json j;

	json_init(&j, stdout);
	json_message(&j, NULL, &fields_status, s);
}

static void print_haptics(const Endosim__HapticsStatus *h,
			  const Endosim__ScopeStatus *sc)
{
	printf("contact   %s, %.1f mm into the wall, %u plane(s); tube turning "
	       "%.2f rad\n", h->contact ? "yes" : "no",
	       h->penetration_m * 1e3, h->constraints, h->curvature_rad);
	printf("insertion contact %+.2f N, friction %+.2f N, loop %+.2f N\n",
	       h->trans_contact_n, h->trans_friction_n, h->trans_loop_n);
	printf("wheels    contact %+.3f/%+.3f, tension %+.3f/%+.3f, elastic "
	       "%+.3f/%+.3f N m\n", h->wheel_contact_nm[0],
	       h->wheel_contact_nm[1], h->wheel_tension_nm[0],
	       h->wheel_tension_nm[1], h->wheel_elastic_nm[0],
	       h->wheel_elastic_nm[1]);
	printf("tube      contact %+.3f N m, friction %+.3f N m; loops",
	       h->tube_contact_nm, h->tube_friction_nm);
	for (size_t i = 0; i < sc->n_bow_m; i++) {
		printf(" %.1f mm", sc->bow_m[i] * 1e3);
	}
	printf("\n");
}

/* The rod model's line (its loops are the tube line's); none in the
 * paper's. */
static void print_rod(const Endosim__RodStatus *r,
		      const Endosim__HapticsStatus *h)
{
	if (r->model != ENDOSIM__HAPTICS_MODEL__HAPTICS_MODEL_ROD) {
		return;
	}
	printf("rod       model %s: %u contacts, wall %.2f N, friction %.2f "
	       "N; at the carriage %+.2f N, %+.3f N m\n", names_model(r->model),
	       r->contacts, r->wall_n, r->friction_n, h->trans_rod_n,
	       h->tube_rod_nm);
}

/* The patient's line, when there is one (ctl_patient_summary()). */
static void print_patient(const Endosim__PatientStatus *p)
{
	char line[256];

	if (!p || !p->enabled) {
		return;
	}
	ctl_patient_summary(p, line, sizeof(line));
	printf("patient   %s\n", line);
}

void ctl_patient_summary(const Endosim__PatientStatus *p, char *out,
			 size_t size)
{
	int torn = p->burst_segment >= 0 ? p->burst_segment : p->torn_segment;
	int n = snprintf(out, size, "%s%s, gas %.2f L at %.1f mmHg, hand ",
			 p->turning ? "turning to " : "",
			 names_position(p->position), p->gas_m3 * 1e3,
			 p->pressure_pa / GAS_PA_PER_MMHG);

	if (n >= 0 && (size_t)n < size) {
		n += snprintf(out + n, size - (size_t)n, *p->site ?
			      "%s %.0f N" : "off", p->site, p->hand_n);
	}
	if (n >= 0 && (size_t)n < size) {
		n += snprintf(out + n, size - (size_t)n, ", valves %s, pain "
			      "%.1f%s%s, %s sedation%s%s",
			      names_valves(p->valves), p->pain,
			      p->pain_cause ? " " : "",
			      p->pain_cause ? names_pain_cause(p->pain_cause)
					    : "",
			      names_sedation(p->sedation),
			      torn >= 0 ? ", PERFORATED: " : "",
			      torn >= 0 ? anatomy_segment_name(torn) : "");
	}
}

void ctl_print_status(const Endosim__StatusReply *s)
{
	printf("state     %s\n", names_state((uint32_t)s->state));
	printf("fault     %s\n", *s->fault_text ? s->fault_text : "none");
	for (size_t i = 0; i < s->n_faults; i++) {
		const Endosim__Fault *f = s->faults[i];

		printf("%s %s%s\n", i ? "          " : "  latched",
		       f->text, f->active ? "  [still present]" : "");
	}
	if (s->active_faults & ~s->fault_bits & ENDOSIM_FAULT_OVERRUN) {
		printf("warning   %s: more periods skipped than the budget "
		       "allows, not a fault here ([loop] overrun_fault)\n",
		       names_fault(ENDOSIM_FAULT_OVERRUN));
	}
	if (s->state == ENDOSIM__DAEMON_STATE__DAEMON_STATE_ENABLED &&
	    s->ramp < 1.0) {
		printf("ramp      forces at %.0f%% (rising after enable)\n",
		       s->ramp * 100.0);
	}
	printf("rig       %s, %s priority %d, %.1f Hz (configured %.0f), "
	       "overruns %llu\n", s->rig, s->rt_policy, s->rt_priority,
	       s->loop_hz, s->loop_rate_hz, (unsigned long long)s->overruns);
	printf("cycle     %llu, uptime %.1f s, scenario %.1f s%s\n",
	       (unsigned long long)s->cycle, s->uptime_s, s->scenario_time_s,
	       s->scenario_done ? " (ended)" : "");
	if (*s->trainee || s->asks_trainee) {
		printf("trainee   %s\n", *s->trainee ? s->trainee :
		       "nobody logged in (endoview asks who is training)");
	}
	if (s->scope && s->scope->n_tip == 3 && s->scope->n_bend_rad == 2) {
		const Endosim__ScopeStatus *sc = s->scope;

		printf("case      %s\n", s->case_name);
		printf("scope     inserted %.3f m, tip at s %.3f m "
		       "(%.3f %.3f %.3f) m, bent %+.2f/%+.2f rad, turning "
		       "%.2f rad\n", sc->depth_m, sc->tip_s_m, sc->tip[0],
		       sc->tip[1], sc->tip[2], sc->bend_rad[0], sc->bend_rad[1],
		       sc->turning_rad);
	}
	if (s->haptics && s->haptics->n_wheel_contact_nm == 2 &&
	    s->haptics->n_wheel_tension_nm == 2 && s->scope &&
	    s->scope->n_bow_m <= 4) {
		print_haptics(s->haptics, s->scope);
	}
	if (s->rod && s->haptics) {
		print_rod(s->rod, s->haptics);
	}
	print_patient(s->patient);
	printf("%-10s %16s %16s %12s %12s %12s  %s\n", "axis", "position",
	       "velocity", "hand", "command", "limited", "drive");
	for (size_t i = 0; i < s->n_axes; i++) {
		const Endosim__AxisStatus *a = s->axes[i];
		char pos[32], vel[32], hand[32], cmd[32], lim[32];

		snprintf(pos, sizeof(pos), "%+.4f %s", a->position,
			 a->position_unit);
		snprintf(vel, sizeof(vel), "%+.4f %s/s", a->velocity,
			 a->position_unit);
		snprintf(hand, sizeof(hand), "%+.3f %s", a->hand, a->force_unit);
		snprintf(cmd, sizeof(cmd), "%+.3f %s", a->command,
			 a->force_unit);
		snprintf(lim, sizeof(lim), "%+.3f %s", a->limited,
			 a->force_unit);
		printf("%-10s %16s %16s %12s %12s %12s  %s\n", a->name, pos,
		       vel, hand, cmd, lim,
		       names_drive_status(a->drive_status));
	}
}

static void json_histogram(struct json *j, const char *key,
			   const Endosim__Histogram *h)
{
	json_object_begin(j, key);
	json_double(j, "p50_us", h->p50_us);
	json_double(j, "p99_us", h->p99_us);
	json_double(j, "p999_us", h->p999_us);
	json_double(j, "max_us", h->max_us);
	json_double(j, "mean_us", h->mean_us);
	json_uint(j, "count", h->count);
	json_object_end(j);
}

static void json_buses(struct json *j, const Endosim__StatsReply *s)
{
	json_array_begin(j, "buses");
	for (size_t i = 0; i < s->n_buses; i++) {
		const Endosim__BusStats *b = s->buses[i];

		json_object_begin(j, NULL);
		json_string(j, "name", b->name);
		json_double(j, "rate_hz", b->rate_hz);
		json_uint(j, "exchanges", b->exchanges);
		json_histogram(j, "exchange", b->exchange);
		json_histogram(j, "transaction", b->transaction);
		json_object_end(j);
	}
	json_array_end(j);
}

static void print_buses(const Endosim__StatsReply *s)
{
	for (size_t i = 0; i < s->n_buses; i++) {
		const Endosim__BusStats *b = s->buses[i];

		printf("bus       %s: %.0f exchanges/s; exchange p50 %.0f p99 "
		       "%.0f us; transaction p50 %.0f p99 %.0f us\n", b->name,
		       b->rate_hz, b->exchange->p50_us, b->exchange->p99_us,
		       b->transaction->p50_us, b->transaction->p99_us);
	}
}

void ctl_print_stats(const Endosim__StatsReply *s, bool json)
{
	if (json) {
		struct json j;

		json_init(&j, stdout);
		json_object_begin(&j, NULL);
		json_uint(&j, "cycles", s->cycles);
		json_uint(&j, "overruns", s->overruns);
		json_string(&j, "rt_policy", s->rt_policy);
		json_int(&j, "rt_priority", s->rt_priority);
		json_double(&j, "period_us", s->period_us);
		json_histogram(&j, "latency", s->latency);
		json_histogram(&j, "compute", s->compute);
		json_buses(&j, s);
		json_object_end(&j);
		return;
	}
	printf("cycles %llu, overruns %llu, %s priority %d, period %.0f us\n",
	       (unsigned long long)s->cycles, (unsigned long long)s->overruns,
	       s->rt_policy, s->rt_priority, s->period_us);
	printf("%-9s %8s %8s %8s %8s %8s   (us)\n", "", "p50", "p99",
	       "p99.9", "max", "mean");
	printf("%-9s %8.0f %8.0f %8.0f %8.1f %8.1f\n", "latency",
	       s->latency->p50_us, s->latency->p99_us, s->latency->p999_us,
	       s->latency->max_us, s->latency->mean_us);
	printf("%-9s %8.0f %8.0f %8.0f %8.1f %8.1f\n", "compute",
	       s->compute->p50_us, s->compute->p99_us, s->compute->p999_us,
	       s->compute->max_us, s->compute->mean_us);
	print_buses(s);
}
