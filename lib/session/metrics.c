/*
 * metrics.c - the training metrics (metrics.h; for people: docs/METRICS.md).
 *
 * Times t count from the first record's stamp_ns. A record stands for the
 * instant of its stamp: a condition that holds from record j to the record
 * before k lasts t_k - t_j, so a 1 kHz stream gives every time to 1 ms.
 *
 *   cecum_s          t of the first record with tip_s_m >= colon_cecum_s()
 *   insertion_s      cecum_s, or duration_s while the cecum is not reached
 *   withdrawal_s     from cecum_s to the first later record with the tip
 *                    out (tip_s_m below the rectum's start, or depth_m <=
 *                    0), or to the last record
 *   insertion force  F = |limited[0]| (N): peak over all records, mean over
 *                    the records with depth_m > 0
 *   episodes         start: the first record with x > threshold; end: the
 *                    first record after it with x < METRICS_HYSTERESIS x
 *                    threshold; kept when end - start >= min_episode_s;
 *                    peak: the largest x in between. Force: x = F, loops:
 *                    x = max over the spans of |bow_m[k]|; pain: x = pain,
 *                    starting at x >= pain_level (at or above), with the
 *                    cause and place of its provocation: the record with
 *                    the largest stimulus from when the pain was last
 *                    below an episode's end to the episode's first
 *                    record (records without a stimulus: the
 *                    cause and place of the first record at the peak)
 *   pain_share       time with pain >= pain_level over duration_s (a
 *                    record's pain holds until the next record)
 *   pain_cause_s[c]  that time by the record's cause c; a record without a
 *                    cause (the stimulus gone, the pain fading) counts for
 *                    the last cause before it: the ache it left
 *   gloucester       0 without a responding patient (no record with the
 *                    patient enabled and a heart rate); else, from the
 *                    pain episodes (n), those peaking at or above
 *                    METRICS_GLOUCESTER_SEVERE_PAIN (n7, among the kept)
 *                    and pain_share (p):
 *                      5  p >= METRICS_GLOUCESTER_PROLONGED_SHARE
 *                      4  p >= METRICS_GLOUCESTER_FREQUENT_SHARE or n7 >= 2
 *                      3  n > 2 or n7 == 1
 *                      2  n = 1 or 2
 *                      1  n = 0
 *                    (the scale: 1 comfortable, 2 minimal: 1-2 episodes of
 *                    mild discomfort, 3 mild: more than 2, 4 moderate:
 *                    significant discomfort several times, 5 severe:
 *                    frequent and prolonged). An estimate from the model's
 *                    pain, not a nurse's observation.
 *   gas_used_l       the sum of gas_in_m3's rises from record to record
 *                    (it restarts at 0 when a case is loaded), x 1000
 *   position_changes records whose patient_position differs from the
 *                    previous record's (a turn towards it started)
 *   hand_uses        records with a hand_site >= 0 other than the
 *                    previous record's
 *   perforations     records whose burst_segment or torn_segment became
 *                    >= 0 (or another segment) since the previous record
 *   (the patient's measures count records with the patient enabled only;
 *   the first such record's hand, burst and tear count against none)
 *   lumen lost, mucosa seen, polyps seen: the view's (metricsview.c)
 *   the therapy      the tools' records (therapy.c)
 *   along the colon  segment i of a record: colon_region_at() its tip_s_m
 *                    (the first whose far end is beyond it, the cecum past
 *                    them all); none while not inserted. The
 *                    previous record's segment gains the time since it
 *                    (in pain and looped as that record was); a record's
 *                    pain and F raise its own segment's peaks
 */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "session/metrics.h"
#include "session/metricsview.h"
#include "session/therapy.h"

struct episodes {
	double on, off, min_s;
	bool at_on;               /* starts at x >= on, not x > on */
	bool active;              /* above the threshold now */
	bool counted;             /* ... and for at least min_s */
	double start_s, peak;
	uint32_t cause;           /* at the peak: pain episodes */
	int32_t place;
	uint32_t count, kept;
	double total_s, longest_s, largest;
	struct metrics_episode ep[METRICS_MAX_EPISODES];
};

struct metrics {
	struct metrics_params p;
	const struct colon *colon;
	double cecum_s_m, exit_s_m;
	struct metricsview *view; /* NULL without a colon */
	uint64_t first_ns;
	double last_s, prev_s;
	uint64_t records, inserted;
	uint64_t drops;
	double cecum_s, out_s;    /* < 0: not yet */
	double max_tip_s_m;
	double peak_n, sum_n;
	double lumen_lost_s;
	bool lost;                /* the previous record's */
	bool prev_in;             /* the previous record was inserted */
	struct episodes force, loop, pain;
	/* the patient: the previous record's, the sums */
	struct session_record prev; /* valid when records > 0 */
	bool responding;          /* a record with the patient's vitals */
	uint32_t cause;           /* the last cause seen, and its place */
	int32_t place;
	double stim_peak;         /* the largest stimulus from when the pain
				     was last below an episode's end to the
				     episode's start, its cause and place:
				     the provocation */
	uint32_t stim_cause;
	int32_t stim_place;
	double pain_s[ENDOSIM_PAIN_CAUSES];
	double pain_time_s;
	double peak_pain, gas_in_m3, peak_pa;
	uint32_t positions, hands, perforations;
	double inserted_s;        /* time with the tube in */
	uint32_t lost_views;
	/* the handling: the last sample, the sums */
	bool shape_have;
	double shape_t, shape_depth, shape_tip;
	double shaft_in, tip_in, shaft_idle, shaft_out, tip_out;
	double loop_in;           /* s with a loop on the way in */
	/* along the colon: each segment's measures */
	bool segments;            /* the colon is a case's (its regions are
				     the anatomy's segments) */
	struct metrics_segment along[ANATOMY_SEGMENTS];
	struct therapy therapy;   /* the working channel's */
};

void metrics_params_default(struct metrics_params *p)
{
	*p = (struct metrics_params){
		.force_threshold_n = METRICS_DEFAULT_FORCE_THRESHOLD_N,
		.loop_threshold_m = METRICS_DEFAULT_LOOP_THRESHOLD_M,
		.view_distance_m = METRICS_DEFAULT_VIEW_DISTANCE_M,
		.fov_rad = METRICS_DEFAULT_FOV_DEG * M_PI / 180,
		.view_rate_hz = METRICS_DEFAULT_VIEW_RATE_HZ,
		.min_episode_s = 0.2,
		.lumen_angle_rad = 70 * M_PI / 180,
		.pain_level = METRICS_DEFAULT_PAIN_LEVEL,
		.seen_dwell_s = 0.5,
		.polyp_dwell_s = 2.5,
	};
}

/* ------------------------------------------------------------ episodes */

static void episodes_init(struct episodes *e, double threshold, double min_s)
{
	memset(e, 0, sizeof(*e));
	e->on = threshold;
	e->off = METRICS_HYSTERESIS * threshold;
	e->min_s = min_s;
}

static void episodes_confirm(struct episodes *e)
{
	e->counted = true;
	e->count++;
	if (e->kept < METRICS_MAX_EPISODES) {
		e->ep[e->kept++] = (struct metrics_episode){
			.start_s = e->start_s, .end_s = -1, .peak = e->peak,
			.cause = e->cause, .place = e->place,
		};
	}
}

/* The current episode's entry, NULL when it is not kept. */
static struct metrics_episode *episodes_current(struct episodes *e)
{
	if (!e->counted || e->kept == 0 ||
	    e->ep[e->kept - 1].start_s != e->start_s) {
		return NULL;
	}
	return &e->ep[e->kept - 1];
}

static void episodes_close(struct episodes *e, double t)
{
	struct metrics_episode *cur;
	double d = t - e->start_s;

	if (!e->counted && d >= e->min_s) {
		episodes_confirm(e);
	}
	if (e->counted) {
		cur = episodes_current(e);
		if (cur) {
			cur->end_s = t;
			cur->peak = e->peak;
			cur->cause = e->cause;
			cur->place = e->place;
		}
		e->total_s += d;
		e->longest_s = fmax(e->longest_s, d);
		e->largest = fmax(e->largest, e->peak);
	}
	e->active = false;
	e->counted = false;
}

/* The peak so far: X at T, with CAUSE and PLACE when it is a new one. */
static void episodes_peak(struct episodes *e, double x, uint32_t cause,
			  int32_t place)
{
	if (x > e->peak) {
		e->peak = x;
		e->cause = cause;
		e->place = place;
	}
}

/* X at T; CAUSE and PLACE: the pain's (0 and -1 for the others). */
static void episodes_update(struct episodes *e, double t, double x,
			    uint32_t cause, int32_t place)
{
	struct metrics_episode *cur;

	if (!e->active) {
		if (x > e->on || (e->at_on && x == e->on)) {
			e->active = true;
			e->counted = false;
			e->start_s = t;
			e->peak = x;
			e->cause = cause;
			e->place = place;
		}
		return;
	}
	if (x < e->off) {
		episodes_close(e, t);
		return;
	}
	episodes_peak(e, x, cause, place);
	if (!e->counted && t - e->start_s >= e->min_s) {
		episodes_confirm(e);
	}
	cur = episodes_current(e);
	if (cur) {
		cur->peak = e->peak;
		cur->cause = e->cause;
		cur->place = e->place;
	}
}

/* The episodes as they stand at time NOW (one still going counts so far). */
static void episodes_result(const struct episodes *e, double now,
			    uint32_t *count, double *total_s,
			    double *longest_s, double *largest,
			    uint32_t *kept, struct metrics_episode *out)
{
	double d = now - e->start_s;

	*count = e->count;
	*total_s = e->total_s;
	*longest_s = e->longest_s;
	*largest = e->largest;
	*kept = e->kept;
	memcpy(out, e->ep, sizeof(e->ep));
	if (e->active && e->counted) {
		*total_s += d;
		*longest_s = fmax(*longest_s, d);
		*largest = fmax(*largest, e->peak);
	}
}

/* -------------------------------------------------------------- public */

struct metrics *metrics_create(const struct colon *colon,
			       const struct metrics_params *p)
{
	struct metrics *m = calloc(1, sizeof(*m));

	if (!m) {
		return NULL;
	}
	m->p = *p;
	m->colon = colon;
	m->cecum_s = -1;
	m->out_s = -1;
	m->exit_s_m = METRICS_EXIT_S_M;
	episodes_init(&m->force, p->force_threshold_n, p->min_episode_s);
	episodes_init(&m->loop, p->loop_threshold_m, p->min_episode_s);
	episodes_init(&m->pain, p->pain_level, p->min_episode_s);
	m->pain.at_on = true;
	m->place = -1;
	therapy_init(&m->therapy);
	if (!colon) {
		return m;
	}
	m->cecum_s_m = colon_cecum_s(colon);
	if (colon_anatomy(colon)) {
		const struct anatomy *a = colon_anatomy(colon);

		m->exit_s_m = anatomy_segment_start(a, ANATOMY_RECTUM);
		m->segments = true;
	}
	m->view = metricsview_create(colon, p);
	if (!m->view) {
		metrics_destroy(m);
		return NULL;
	}
	return m;
}

void metrics_destroy(struct metrics *m)
{
	if (!m) {
		return;
	}
	metricsview_destroy(m->view);
	free(m);
}

static double record_bow(const struct session_record *r)
{
	double b = 0;

	for (uint32_t k = 0; k < r->spans && k < ENDOSIM_SPANS; k++) {
		if (isfinite(r->bow_m[k])) {
			b = fmax(b, fabs(r->bow_m[k]));
		}
	}
	return b;
}

/* The cecum, then the way out. */
static void record_progress(struct metrics *m, const struct session_record *r,
			    double t)
{
	if (!m->colon) {
		return;
	}
	if (m->cecum_s < 0 && r->tip_s_m >= m->cecum_s_m) {
		m->cecum_s = t;
	} else if (m->cecum_s >= 0 && m->out_s < 0 &&
		   (r->tip_s_m < m->exit_s_m || r->depth_m <= 0)) {
		m->out_s = t;
	}
}

/*
 * The handling, every METRICS_SHAPE_STEP_S: the depth's and the tip's
 * moves since the last sample, summed by direction, on the way in (until
 * the cecum) or out (from it until the tip is out).
 */
static void record_shape(struct metrics *m, const struct session_record *r,
			 double t)
{
	double dd, ds;
	bool out;

	if (!isfinite(r->depth_m) || !isfinite(r->tip_s_m)) {
		return;
	}
	if (m->shape_have && t - m->shape_t < METRICS_SHAPE_STEP_S - 1e-9) {
		return;
	}
	dd = r->depth_m - m->shape_depth;
	ds = r->tip_s_m - m->shape_tip;
	out = m->cecum_s >= 0 && t > m->cecum_s;
	if (m->shape_have && !out) {
		if (record_bow(r) > m->loop.on) {
			m->loop_in += t - m->shape_t;
		}
		m->shaft_in += fmax(dd, 0);
		m->tip_in += fmax(ds, 0);
		if (dd > 0 && ds < METRICS_IDLE_SHARE * dd) {
			m->shaft_idle += dd;
		}
	} else if (m->shape_have && (m->out_s < 0 || t <= m->out_s)) {
		m->shaft_out += fmax(-dd, 0);
		m->tip_out += fmax(-ds, 0);
	}
	m->shape_have = true;
	m->shape_t = t;
	m->shape_depth = r->depth_m;
	m->shape_tip = r->tip_s_m;
}

/* The segment R's tip is in, -1: out (or no anatomy). */
static int tip_segment(const struct metrics *m, const struct session_record *r)
{
	if (!m->segments || !(r->depth_m > 0) || !isfinite(r->tip_s_m)) {
		return -1;
	}
	return colon_region_at(m->colon, r->tip_s_m);
}

/* Along the colon: Q's state (the previous record, NULL at the first)
 * held for DT where Q's tip was; R's pain and insertion force F where its
 * tip is. */
static void record_along(struct metrics *m, const struct session_record *r,
			 const struct session_record *q, double dt, double f)
{
	int i = q ? tip_segment(m, q) : -1;
	struct metrics_segment *s;

	if (i >= 0) {
		s = &m->along[i];
		s->time_s += dt;
		s->pain_s += q->patient && q->pain >= m->p.pain_level ? dt : 0;
		s->loop_s += record_bow(q) > m->loop.on ? dt : 0;
	}
	i = tip_segment(m, r);
	if (i >= 0) {
		s = &m->along[i];
		if (r->patient && isfinite(r->pain)) {
			s->peak_pain = fmax(s->peak_pain, r->pain);
		}
		s->peak_force_n = fmax(s->peak_force_n, f);
	}
}

/* SITE taken now, other than BEFORE (-1: none). */
static bool taken(int32_t site, int32_t before)
{
	return site >= 0 && site != before;
}

/* The provocation of the pain now at R: the largest stimulus (with a
 * cause) from when the pain was last below an episode's end up to the
 * record where the episode began: what brought the pain on, not what
 * came while it lasted. */
static void provocation(struct metrics *m, const struct session_record *r,
			double pain)
{
	if (!m->pain.active && pain < m->pain.off) {
		m->stim_peak = 0;
		m->stim_cause = ENDOSIM_PAIN_NONE;
		m->stim_place = -1;
	}
	if (!m->pain.active && isfinite(r->pain_stimulus) &&
	    r->pain_stimulus > m->stim_peak &&
	    r->pain_cause != ENDOSIM_PAIN_NONE &&
	    r->pain_cause < ENDOSIM_PAIN_CAUSES) {
		m->stim_peak = r->pain_stimulus;
		m->stim_cause = r->pain_cause;
		m->stim_place = r->pain_place;
	}
}

/* The patient's measures at R (T), the previous record's state held for
 * DT; Q: the previous record with the patient, or NULL. */
static void record_patient(struct metrics *m, const struct session_record *r,
			   const struct session_record *q, double t,
			   double dt)
{
	double pain = isfinite(r->pain) ? r->pain : 0;

	if (q && q->pain >= m->p.pain_level) {
		m->pain_time_s += dt;
		m->pain_s[m->cause] += dt;
	}
	if (!r->patient) {
		episodes_update(&m->pain, t, 0, 0, -1);
		return;
	}
	if (r->pain_cause != ENDOSIM_PAIN_NONE &&
	    r->pain_cause < ENDOSIM_PAIN_CAUSES) {
		m->cause = r->pain_cause;
		m->place = r->pain_place;
	}
	m->responding |= r->heart_rate_bpm > 0;
	m->peak_pain = fmax(m->peak_pain, pain);
	provocation(m, r, pain);
	episodes_update(&m->pain, t, pain, m->cause, m->place);
	if (m->pain.active && m->stim_cause != ENDOSIM_PAIN_NONE) {
		struct metrics_episode *cur = episodes_current(&m->pain);

		m->pain.cause = m->stim_cause;
		m->pain.place = m->stim_place;
		if (cur) {
			cur->cause = m->stim_cause;
			cur->place = m->stim_place;
		}
	}
	if (q && r->gas_in_m3 > q->gas_in_m3 && isfinite(r->gas_in_m3)) {
		m->gas_in_m3 += r->gas_in_m3 - q->gas_in_m3;
	}
	if (isfinite(r->gas_pressure_pa)) {
		m->peak_pa = fmax(m->peak_pa, r->gas_pressure_pa);
	}
	m->positions += q && r->patient_position != q->patient_position;
	m->hands += taken(r->hand_site, q ? q->hand_site : -1);
	m->perforations += taken(r->burst_segment, q ? q->burst_segment : -1);
	m->perforations += taken(r->torn_segment, q ? q->torn_segment : -1);
}

void metrics_record(struct metrics *m, const struct session_record *r)
{
	double t, dt, f = fabs(r->limited[0]);
	bool inserted = r->depth_m > 0, was_lost;

	if (m->records == 0) {
		m->first_ns = r->stamp_ns;
	}
	t = (double)(int64_t)(r->stamp_ns - m->first_ns) * ENDOSIM_S_PER_NS;
	dt = m->records ? t - m->last_s : 0;
	/* the previous record's state holds until this one */
	record_patient(m, r, m->records && m->prev.patient ? &m->prev : NULL,
		       t, dt);
	m->lumen_lost_s += m->lost ? dt : 0;
	m->inserted_s += m->records && m->prev_in ? dt : 0;
	m->records++;
	m->last_s = t;
	f = isfinite(f) ? f : 0;
	m->peak_n = fmax(m->peak_n, f);
	if (inserted) {
		m->inserted++;
		m->sum_n += f;
		m->max_tip_s_m = fmax(m->max_tip_s_m, r->tip_s_m);
	}
	record_progress(m, r, t);
	record_shape(m, r, t);
	episodes_update(&m->force, t, f, 0, -1);
	episodes_update(&m->loop, t, record_bow(r), 0, -1);
	record_along(m, r, m->records > 1 ? &m->prev : NULL, dt, f);
	therapy_record(&m->therapy, r, t, dt);
	m->prev = *r;
	was_lost = m->lost;
	m->lost = m->view && inserted && metricsview_lumen_lost(m->view, r);
	m->lost_views += m->lost && !was_lost;
	m->prev_in = inserted;
	if (m->view && inserted) {
		metricsview_record(m->view, r, t);
	}
}

void metrics_event(struct metrics *m, const struct session_event *ev,
		   const char *text)
{
	(void)text;
	if (ev->kind == SESSION_EVENT_DROPS && ev->value > (double)m->drops) {
		m->drops = (uint64_t)ev->value;
	}
}

static uint32_t popcount32(uint32_t x)
{
	uint32_t n = 0;

	for (; x; x &= x - 1) {
		n++;
	}
	return n;
}

/* The estimated Gloucester comfort score of OUT's pain (metrics.c's
 * head: the mapping). */
static uint32_t gloucester(const struct metrics_result *out)
{
	uint32_t severe = 0;

	for (uint32_t i = 0; i < out->n_pain; i++) {
		severe += out->pain[i].peak >= METRICS_GLOUCESTER_SEVERE_PAIN;
	}
	if (out->pain_share >= METRICS_GLOUCESTER_PROLONGED_SHARE) {
		return 5;
	}
	if (out->pain_share >= METRICS_GLOUCESTER_FREQUENT_SHARE ||
	    severe >= 2) {
		return 4;
	}
	if (out->pain_episodes > 2 || severe == 1) {
		return 3;
	}
	return out->pain_episodes ? 2 : 1;
}

static void patient_result(const struct metrics *m, double now,
			   struct metrics_result *out)
{
	episodes_result(&m->pain, now, &out->pain_episodes, &(double){ 0 },
			&(double){ 0 }, &(double){ 0 }, &out->n_pain,
			out->pain);
	out->pain_share = now > 0 ? m->pain_time_s / now : 0;
	out->peak_pain = m->peak_pain;
	memcpy(out->pain_cause_s, m->pain_s, sizeof(out->pain_cause_s));
	out->gloucester = m->responding ? gloucester(out) : 0;
	out->gas_used_l = m->gas_in_m3 * 1000;
	out->peak_gas_pressure_pa = m->peak_pa;
	out->position_changes = m->positions;
	out->hand_uses = m->hands;
	out->perforations = m->perforations;
}

void metrics_result(const struct metrics *m, struct metrics_result *out)
{
	double now = m->last_s;

	memset(out, 0, sizeof(*out));
	out->duration_s = now;
	out->records = m->records;
	out->drops = m->drops;
	out->cecum_s = m->cecum_s;
	out->insertion_s = m->cecum_s >= 0 ? m->cecum_s : now;
	if (m->cecum_s >= 0) {
		out->withdrawal_s = (m->out_s >= 0 ? m->out_s : now) -
				    m->cecum_s;
	}
	out->max_tip_s_m = m->max_tip_s_m;
	out->peak_insertion_n = m->peak_n;
	out->mean_insertion_n = m->inserted ? m->sum_n / (double)m->inserted : 0;
	episodes_result(&m->force, now, &out->force_episodes,
			&out->force_episode_s, &(double){ 0 },
			&(double){ 0 }, &out->n_force, out->force);
	episodes_result(&m->loop, now, &out->loop_episodes, &(double){ 0 },
			&out->longest_loop_s, &out->largest_loop_m,
			&out->n_loop, out->loop);
	out->loop_s = m->loop_in;
	out->shaft_in_m = m->shaft_in;
	out->tip_in_m = m->tip_in;
	out->chase_efficiency = m->shaft_in > 0 ? m->tip_in / m->shaft_in : 0;
	out->shaft_idle_m = m->shaft_idle;
	out->retraction_m = m->shaft_out;
	out->tip_retraction_m = m->tip_out;
	out->retraction_efficiency = m->shaft_out > 0 ?
				     m->tip_out / m->shaft_out : 0;
	out->clear_view = m->inserted_s > 0 ?
			  fmax(0, 1 - m->lumen_lost_s / m->inserted_s) : 0;
	out->lost_views = m->lost_views;
	patient_result(m, now, out);
	out->lumen_lost_s = m->lumen_lost_s;
	out->mucosa_seen = metricsview_seen(m->view);
	out->mucosa_per_min = now > 0 ? out->mucosa_seen * 100 / (now / 60)
				      : 0;
	for (int i = 0; m->colon && colon_anatomy(m->colon) &&
			i < ANATOMY_SEGMENTS; i++) {
		const struct anatomy *a = colon_anatomy(m->colon);
		double s0 = anatomy_segment_start(a, i);

		out->mucosa_segment[i] = metrics_mucosa_seen_between(
			m, s0, s0 + a->seg[i].length_m);
	}
	out->polyps_seen_mask = metricsview_found(m->view);
	out->polyps_seen = popcount32(out->polyps_seen_mask);
	out->polyps_total = (uint32_t)metricsview_polyps(m->view);
	therapy_result(&m->therapy, out->polyps_total, out);
}

bool metrics_has_patient(const struct metrics_result *r)
{
	return r->gloucester || r->peak_pain > 0 || r->gas_used_l > 0 ||
	       r->peak_gas_pressure_pa > 0 || r->position_changes ||
	       r->hand_uses || r->perforations;
}

void metrics_along(const struct metrics *m, struct metrics_along *out)
{
	out->segments = m->segments;
	memcpy(out->seg, m->along, sizeof(out->seg));
}

double metrics_mucosa_seen_in(const struct metrics *m, double s0_m,
			      double s1_m, double a0_rad, double a1_rad)
{
	return metricsview_seen_in(m->view, s0_m, s1_m, a0_rad, a1_rad);
}

double metrics_mucosa_seen_between(const struct metrics *m, double s0_m,
				   double s1_m)
{
	return metrics_mucosa_seen_in(m, s0_m, s1_m, 0, 2 * M_PI);
}

void metrics_map(const struct metrics *m, struct metrics_map *out)
{
	metricsview_map(m->view, out);
}

