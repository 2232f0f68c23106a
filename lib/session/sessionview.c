/* sessionview.c - see sessionview.h. */
#include "session/sessionview.h"

#include <assert.h>
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "proto/fields.h"
#include "model/anatomy.h"
#include "proto/names.h"
#include "session/metricstext.h"
#include "session/sessioninputs.h"
#include "session/sessionmetrics.h"
#include "session/therapy.h"

/* ------------------------------------------------------------ metrics */

int sessionview_metrics(const struct session_file *f,
			struct metrics_result *out, bool *recomputed)
{
	struct metrics_params p;
	char err[512];

	*recomputed = false;
	if (f->end && !metricstext_parse(f->end, out)) {
		return 0;
	}
	sessioninputs_file_metrics_params(f, &p);
	*recomputed = true;
	return sessionmetrics_compute(f, &p, out, err, sizeof(err));
}

static void print_episodes(FILE *out, const char *what,
			   const struct metrics_episode *ep, uint32_t n,
			   const char *unit)
{
	for (uint32_t i = 0; i < n; i++) {
		fprintf(out, "  %s %u: %.2f .. ", what, i + 1, ep[i].start_s);
		if (ep[i].end_s < 0) {
			fprintf(out, "(going)");
		} else {
			fprintf(out, "%.2f s", ep[i].end_s);
		}
		fprintf(out, ", peak %.3g %s\n", ep[i].peak, unit);
	}
}

/* The pain episodes, each with its cause and place. */
static void print_pain_episodes(FILE *out, const struct metrics_result *m)
{
	for (uint32_t i = 0; i < m->n_pain; i++) {
		const struct metrics_episode *e = &m->pain[i];

		fprintf(out, "  pain %u: %.2f .. ", i + 1, e->start_s);
		if (e->end_s < 0) {
			fprintf(out, "(going)");
		} else {
			fprintf(out, "%.2f s", e->end_s);
		}
		fprintf(out, ", peak %.1f, %s in the %s\n", e->peak,
			names_pain_cause(e->cause),
			e->place >= 0 ? anatomy_segment_name(e->place) : "-");
	}
}

static void print_patient(FILE *out, const struct metrics_result *m)
{
	if (!metrics_has_patient(m)) {
		fprintf(out, "patient           none\n");
		return;
	}
	fprintf(out, "time in pain      %.1f %% (pain >= the level), peak "
		"%.1f, %u episodes\n", 100 * m->pain_share, m->peak_pain,
		m->pain_episodes);
	print_pain_episodes(out, m);
	fprintf(out, "pain by cause     looping %.1f s, straightening %.1f s, "
		"insufflation %.1f s, tip %.1f s\n",
		m->pain_cause_s[ENDOSIM_PAIN_LOOPING],
		m->pain_cause_s[ENDOSIM_PAIN_STRAIGHTENING],
		m->pain_cause_s[ENDOSIM_PAIN_INSUFFLATION],
		m->pain_cause_s[ENDOSIM_PAIN_TIP]);
	if (m->gloucester) {
		fprintf(out, "comfort           Gloucester %u (an estimate "
			"from the pain)\n", m->gloucester);
	} else {
		fprintf(out, "comfort           not assessed (no responding "
			"patient)\n");
	}
	fprintf(out, "gas               %.2f L in, peak %.1f mmHg (%.0f Pa)\n",
		m->gas_used_l, m->peak_gas_pressure_pa / METRICS_PA_PER_MMHG,
		m->peak_gas_pressure_pa);
	fprintf(out, "patient           %u position changes, %u hand presses, "
		"%u perforations\n", m->position_changes, m->hand_uses,
		m->perforations);
}

/* The therapy through the working channel, a line a polyp (therapy.h);
 * nothing without a tool in hand. */
static void print_therapy(FILE *out, const struct metrics_result *m)
{
	if (!m->n_polyp) {
		return;
	}
	fprintf(out, "therapy           %u of %u polyps resected, %u partly, "
		"%u retrieved; %.2f s a resection, cautery %.2f s, %u wall "
		"injuries, %u biopsies, %u clips\n", m->polyps_resected,
		m->n_polyp, m->polyps_partly, m->polyps_retrieved,
		m->resection_s, m->cautery_s, m->tool_injuries, m->biopsies,
		m->clips);
	if (m->bleeds) {
		fprintf(out, "bleeding          %u points, %u clipped, stopped "
			"after %.2f s on average\n", m->bleeds,
			m->bleeds_clipped, m->bleed_control_s);
	}
	for (uint32_t i = 0; i < m->n_polyp; i++) {
		const struct metrics_polyp *p = &m->polyp[i];

		fprintf(out, "  polyp %u: %s", i + 1,
			therapy_fate_name(p->fate));
		if (p->start_s >= 0) {
			fprintf(out, ", touched at %.2f s", p->start_s);
		}
		if (p->cut_s >= 0 && p->start_s >= 0) {
			fprintf(out, ", free %.2f s later",
				p->cut_s - p->start_s);
		}
		fprintf(out, ", cautery %.2f s, %u bites\n", p->cautery_s,
			p->bites);
	}
}

void sessionview_print(FILE *out, const struct metrics_result *m)
{
	fprintf(out, "duration          %.2f s, %" PRIu64 " records, %" PRIu64
		" dropped\n", m->duration_s, m->records, m->drops);
	if (m->cecum_s >= 0) {
		fprintf(out, "cecum reached     at %.2f s\n", m->cecum_s);
	} else {
		fprintf(out, "cecum reached     no (deepest %.3f m)\n",
			m->max_tip_s_m);
	}
	fprintf(out, "insertion time    %.2f s\nwithdrawal time   %.2f s\n",
		m->insertion_s, m->withdrawal_s);
	fprintf(out, "insertion force   peak %.2f N, mean %.2f N\n",
		m->peak_insertion_n, m->mean_insertion_n);
	fprintf(out, "force episodes    %u, %.2f s in all\n", m->force_episodes,
		m->force_episode_s);
	print_episodes(out, "force", m->force, m->n_force, "N");
	fprintf(out, "loops             %u, longest %.2f s, largest %.3f m\n",
		m->loop_episodes, m->longest_loop_s, m->largest_loop_m);
	print_episodes(out, "loop", m->loop, m->n_loop, "m");
	print_patient(out, m);
	fprintf(out, "lumen lost        %.2f s\n", m->lumen_lost_s);
	fprintf(out, "mucosa seen       %.1f %%\npolyps seen       %u of %u\n",
		100 * m->mucosa_seen, m->polyps_seen, m->polyps_total);
	fprintf(out, "lumen in view     %.1f %% of the time in, lost %u times; "
		"mucosa %.1f %% a minute\n", 100 * m->clear_view,
		m->lost_views, m->mucosa_per_min);
	fprintf(out, "way in            shaft %.3f m, tip %.3f m (chase "
		"efficiency %.2f), idle push %.3f m, looped %.2f s\n",
		m->shaft_in_m, m->tip_in_m, m->chase_efficiency,
		m->shaft_idle_m, m->loop_s);
	fprintf(out, "way out           shaft %.3f m, tip %.3f m (retraction "
		"efficiency %.2f)\n", m->retraction_m, m->tip_retraction_m,
		m->retraction_efficiency);
	print_therapy(out, m);
}

static void json_episodes(struct json *j, const char *key,
			  const struct metrics_episode *ep, uint32_t n)
{
	bool pain = !strcmp(key, "pain");

	json_array_begin(j, key);
	for (uint32_t i = 0; i < n; i++) {
		json_object_begin(j, NULL);
		json_double(j, "start_s", ep[i].start_s);
		json_double(j, "end_s", ep[i].end_s);
		json_double(j, "peak", ep[i].peak);
		if (pain) {
			json_string(j, "cause", names_pain_cause(ep[i].cause));
			json_string(j, "place", ep[i].place >= 0 ?
				    anatomy_segment_name(ep[i].place) : "");
		}
		json_object_end(j);
	}
	json_array_end(j);
}

/* The therapy's polyps (none without a tool in hand: no key). */
static void json_polyps(struct json *j, const struct metrics_result *m)
{
	if (!m->n_polyp) {
		return;
	}
	json_array_begin(j, "polyps");
	for (uint32_t i = 0; i < m->n_polyp; i++) {
		const struct metrics_polyp *p = &m->polyp[i];

		json_object_begin(j, NULL);
		json_string(j, "fate", therapy_fate_name(p->fate));
		json_double(j, "start_s", p->start_s);
		json_double(j, "cut_s", p->cut_s);
		json_double(j, "cautery_s", p->cautery_s);
		json_uint(j, "bites", p->bites);
		json_object_end(j);
	}
	json_array_end(j);
}

void sessionview_json(struct json *j, const char *key,
		      const struct metrics_result *m)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);

	json_object_begin(j, key);
	for (size_t i = 0; i < n; i++) {
		if (f[i].kind == FIELDS_DOUBLE) {
			json_double(j, f[i].key,
				    metricstext_field_value(m, &f[i]));
		} else {
			json_uint(j, f[i].key,
				  (uint64_t)metricstext_field_value(m, &f[i]));
		}
	}
	json_episodes(j, "force", m->force, m->n_force);
	json_episodes(j, "loops", m->loop, m->n_loop);
	json_episodes(j, "pain", m->pain, m->n_pain);
	json_polyps(j, m);
	json_object_end(j);
}

/* The summary CSV's header: who, what, when, then every measure. */
int sessionview_summary_header(FILE *out)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);

	fputs("id,trainee,case,started", out);
	for (size_t i = 0; i < n; i++) {
		fprintf(out, ",%s", f[i].key);
	}
	fputc('\n', out);
	return ferror(out) ? -EIO : 0;
}

/* TEXT as a CSV field: quoted, its quotes doubled. */
static void csv_text(FILE *out, const char *text)
{
	fputc('"', out);
	for (; text && *text; text++) {
		if (*text == '"') {
			fputc('"', out);
		}
		fputc(*text, out);
	}
	fputc('"', out);
}

int sessionview_summary_row(FILE *out, const struct session_file *f,
			    const struct metrics_result *m)
{
	static const char *const keys[] = { "id", "trainee", "case",
					    "started" };
	const struct metricstext_field *fl;
	size_t n = metricstext_fields(&fl);
	char value[256];

	for (size_t k = 0; k < 4; k++) {
		if (session_text_get(f->header ? f->header : "", keys[k], value,
				     sizeof(value))) {
			value[0] = '\0';
		}
		if (k) {
			fputc(',', out);
		}
		if (k == 0) {
			fputs(value, out);
		} else {
			csv_text(out, value);
		}
	}
	for (size_t i = 0; i < n; i++) {
		fprintf(out, ",%.9g", metricstext_field_value(m, &fl[i]));
	}
	fputc('\n', out);
	return ferror(out) ? -EIO : 0;
}

/* ------------------------------------------------------------ CSV */

/* Column C (fields_columns) of record R. */
static void put_value(FILE *out, const struct session_record *r,
		      const struct fields_column *c)
{
	const unsigned char *p = (const unsigned char *)r + c->record;
	uint64_t u64;
	uint32_t u32;
	int32_t i32;
	float f;

	switch (c->stored) {
	case FIELDS_STORED_U64:
		memcpy(&u64, p, sizeof(u64));
		fprintf(out, ",%" PRIu64, u64);
		break;
	case FIELDS_STORED_U32:
		memcpy(&u32, p, sizeof(u32));
		fprintf(out, ",%" PRIu32, u32);
		break;
	case FIELDS_STORED_F32:
		memcpy(&f, p, sizeof(f));
		fprintf(out, ",%.7g", (double)f);
		break;
	case FIELDS_STORED_I32:
		memcpy(&i32, p, sizeof(i32));
		fprintf(out, ",%" PRId32, i32);
		break;
	}
}

uint64_t sessionview_start_ns(const struct session_file *f)
{
	char v[32];

	if (!session_text_get(f->header, "start_ns", v, sizeof(v))) {
		return strtoull(v, NULL, 10);
	}
	return f->n_records ? f->records[0].stamp_ns : 0;
}

static double since(uint64_t t0, uint64_t stamp_ns)
{
	return (double)(int64_t)(stamp_ns - t0) / ENDOSIM_NS_PER_S;
}

/*
 * How many of the N columns COLS (in the record's order) F's records
 * hold: format 3's at least, as its CSV always had them.
 */
static size_t held_columns(const struct session_file *f,
			   const struct fields_column *cols, size_t n)
{
	size_t end = f->record_size > SESSION_RECORD_SIZE_3 ?
			     f->record_size : SESSION_RECORD_SIZE_3;

	while (n && cols[n - 1].record >= end) {
		n--;
	}
	return n;
}

int sessionview_csv(FILE *out, const struct session_file *f)
{
	/* every column is at least a float of the record */
	struct fields_column cols[sizeof(struct session_record) /
				  sizeof(float)];
	size_t n = fields_columns(cols, sizeof(cols) / sizeof(cols[0]));
	uint64_t t0 = sessionview_start_ns(f);

	assert(n <= sizeof(cols) / sizeof(cols[0]));
	n = held_columns(f, cols, n);
	fprintf(out, "t_s");
	for (size_t c = 0; c < n; c++) {
		fprintf(out, ",%s", cols[c].name);
	}
	fputc('\n', out);
	for (size_t i = 0; i < f->n_records; i++) {
		const struct session_record *r = &f->records[i];

		fprintf(out, "%.6f", since(t0, r->stamp_ns));
		for (size_t c = 0; c < n; c++) {
			put_value(out, r, &cols[c]);
		}
		fputc('\n', out);
	}
	return ferror(out) ? -EIO : 0;
}

/* TEXT as a CSV field: quoted, its quotes doubled. */
static void put_quoted(FILE *out, const char *text)
{
	fputc('"', out);
	for (; *text; text++) {
		if (*text == '"') {
			fputc('"', out);
		}
		fputc(*text, out);
	}
	fputc('"', out);
}

int sessionview_events_csv(FILE *out, const struct session_file *f)
{
	uint64_t t0 = sessionview_start_ns(f);

	fprintf(out, "t_s,kind,axis,detail,value,text\n");
	for (size_t i = 0; i < f->n_events; i++) {
		const struct session_event *ev = &f->events[i].ev;

		fprintf(out, "%.6f,%s,%d,%u,%.9g,", since(t0, ev->stamp_ns),
			names_event(ev->kind), ev->axis, ev->detail, ev->value);
		put_quoted(out, f->events[i].text);
		fputc('\n', out);
	}
	return ferror(out) ? -EIO : 0;
}
