/* patient.c - see patient.h. */
#include "model/patient.h"

#include <errno.h>
#include <math.h>
#include <string.h>

#include "base/vec3.h"

static void factors_one(struct patient *pt)
{
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		pt->factor[i] = 1;
	}
}

void patient_init(struct patient *pt, const struct patient_params *p)
{
	struct patient_params keep = *p; /* P may be PT's own */

	memset(pt, 0, sizeof(*pt));
	pt->p = keep;
	pt->site = -1;
	pt->torn = -1;
	pt->gas.burst_segment = -1;
	posture_reset(&pt->posture, keep.start_position);
	lens_reset(&pt->lens);
	factors_one(pt);
	pt->sedation = keep.pain.sedation;
	pain_reset(&pt->pain);
	perforation_reset(&pt->perforation);
	vitals_reset(&pt->vitals, &keep.vitals, pt->sedation);
}

/* Which segment each of COLON's mobile spans lies in (a region of a
 * case is its segment; an imported colon's span has none, -1). */
static void map_spans(struct patient *pt, const struct colon *colon)
{
	pt->spans = 0;
	for (int i = 0; i < colon_regions(colon); i++) {
		int span = colon_region(colon, i)->span;

		if (span >= 0 && span < ENDOSIM_SPANS) {
			pt->span_segment[span] = colon_anatomy(colon) ? i : -1;
			pt->spans = span + 1 > pt->spans ? span + 1 : pt->spans;
		}
	}
}

/* The gas's inputs this cycle. */
static void gas_input(const struct patient *pt, bool suction_gas,
		      struct gas_input *in)
{
	memset(in, 0, sizeof(*in));
	in->air = pt->valves & ENDOSIM_VALVE_AIR;
	in->suction = suction_gas;
	vec3_copy(in->down, pt->posture.down);
	fluid_volumes(&pt->fluid, in->fluid_m3);
}

static void take_factors(struct patient *pt)
{
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		pt->factor[i] = i < pt->gas.segments ? pt->gas.seg[i].factor : 1;
	}
}

void patient_attach(struct patient *pt, const struct colon *colon)
{
	const struct anatomy *a = colon_anatomy(colon);
	double fluid[FLUID_SEGMENTS] = { 0 };
	struct gas_input in;
	int sedation = pt->sedation;

	patient_init(pt, &pt->p);
	pt->sedation = sedation;
	vitals_reset(&pt->vitals, &pt->p.vitals, sedation);
	pt->colon = colon;
	if (!pt->p.enabled) {
		return;
	}
	map_spans(pt, colon);
	for (int i = 0; a && i < FLUID_SEGMENTS; i++) {
		fluid[i] = a->seg[i].fluid_m3;
	}
	gas_attach(&pt->gas, &pt->p.gas, colon, NULL, pt->posture.down);
	fluid_attach(&pt->fluid, &pt->p.fluid, colon, fluid,
		     pt->posture.down, NULL);
	gas_input(pt, false, &in);
	gas_set_volume(&pt->gas, pt->gas.volume_m3, &in); /* with the fluid */
	take_factors(pt);
	fluid_settle(&pt->fluid, pt->factor);
}

void patient_set_params(struct patient *pt, const struct patient_params *p)
{
	bool enabled = pt->p.enabled;
	int start = pt->p.start_position;

	pt->p = *p;
	pt->p.enabled = enabled;
	pt->p.start_position = start;
	gas_set_params(&pt->gas, &p->gas);
	fluid_set_params(&pt->fluid, &p->fluid);
	if (pt->site >= 0 && pt->hand_n > p->hand_max_n) {
		pt->hand_n = p->hand_max_n;
	}
}

int patient_turn(struct patient *pt, int position)
{
	if (!pt->p.enabled) {
		return -EINVAL;
	}
	return posture_turn(&pt->posture, position, pt->p.turn_s);
}

int patient_press(struct patient *pt, int site, double force_n)
{
	const struct anatomy *a = pt->colon ? colon_anatomy(pt->colon) : NULL;
	double f = force_n > 0 ? force_n : pt->p.hand_n;

	if (!pt->p.enabled || !a || site < 0 || site >= a->sites ||
	    !(f <= pt->p.hand_max_n)) {
		return -EINVAL;
	}
	pt->site = site;
	pt->hand_n = f;
	return 0;
}

void patient_release(struct patient *pt)
{
	pt->site = -1;
	pt->hand_n = 0;
	pt->pad_n = 0;
}

int patient_sedate(struct patient *pt, int sedation)
{
	if (!pt->p.enabled || sedation < 0 || sedation >= ENDOSIM_SEDATIONS) {
		return -EINVAL;
	}
	pt->sedation = sedation;
	return 0;
}

void patient_watched(const struct patient *pt, double v[PATIENT_WATCHED])
{
	int n = 0;

	v[n++] = pt->gas.volume_m3;
	v[n++] = pt->gas.pressure_pa;
	for (int i = 0; i < GAS_SEGMENTS; i++) {
		v[n++] = pt->factor[i];
		v[n++] = pt->fluid.seg[i].volume_m3;
		v[n++] = pt->fluid.seg[i].level_m;
	}
	v[n++] = pt->lens.smear;
	v[n++] = pt->lens.murk;
	v[n++] = pt->lens.redout;
	v[n++] = pt->pad_n;
	v[n++] = pt->pain.level;
	v[n++] = pt->vitals.heart_rate_bpm;
	v[n++] = pt->vitals.spo2;
}

bool patient_finite(const struct patient *pt)
{
	double v[PATIENT_WATCHED];

	patient_watched(pt, v);
	for (int i = 0; i < PATIENT_WATCHED; i++) {
		if (!isfinite(v[i])) {
			return false;
		}
	}
	return true;
}

/* The body anew as the case starts it, but lying where it lies. */
static void lay_anew(struct patient *pt)
{
	int start = pt->p.start_position;

	pt->p.start_position = pt->posture.position;
	patient_attach(pt, pt->colon);
	pt->p.start_position = start;
}

/* The patient's response this cycle: pain, vital signs, a tear by the
 * tip in segment TIP_SEGMENT. */
static void respond(struct patient *pt, const struct patient_input *in,
		    int tip_segment, double dt_s)
{
	double wall[GAS_SEGMENTS];
	struct pain_params par = pt->p.pain;
	struct pain_input pi = {
		.spans = in->span_tension_n ? pt->spans : 0,
		.span_tension_n = in->span_tension_n,
		.span_segment = pt->span_segment,
		.segments = pt->gas.segments,
		.wall_n_per_m = wall,
		.tip_force_n = in->tip_force_n,
		.tip_segment = tip_segment,
		.insertion_m_s = in->insertion_m_s,
		.roll_rad_s = in->roll_rad_s,
	};

	for (int i = 0; i < pt->gas.segments; i++) {
		wall[i] = pt->gas.seg[i].tension_n_per_m;
	}
	par.sedation = pt->sedation;
	pain_step(&pt->pain, &par, &pi, dt_s);
	vitals_step(&pt->vitals, &pt->p.vitals, pt->pain.level, pt->sedation,
		    dt_s);
	if (perforation_step(&pt->perforation, &pt->p.perforation,
			     in->tip_force_n, in->tip_bend_rad, tip_segment,
			     dt_s) && pt->torn < 0) {
		pt->torn = tip_segment;
	}
}

int patient_step(struct patient *pt, const struct patient_input *in,
		 double dt_s)
{
	struct gas_input gi;
	struct lens_input li;
	int seg;

	pt->valves = in->valves;
	pt->torn = -1;
	if (!pt->p.enabled || !pt->colon) {
		return -1;
	}
	if (!patient_finite(pt)) {
		lay_anew(pt);
	}
	posture_step(&pt->posture, dt_s);
	seg = fluid_segment_at(&pt->fluid, in->tip_s_m);
	pt->tip_in_fluid = fluid_step(&pt->fluid, pt->posture.down, pt->factor,
				      in->valves & ENDOSIM_VALVE_SUCTION,
				      in->tip, seg, dt_s);
	gas_input(pt, (in->valves & ENDOSIM_VALVE_SUCTION) &&
			      !pt->tip_in_fluid, &gi);
	pt->torn = gas_step(&pt->gas, &gi, dt_s);
	take_factors(pt);
	li = (struct lens_input){
		.tip_force_n = in->tip_force_n,
		.under_fluid = pt->tip_in_fluid,
		.water = in->valves & ENDOSIM_VALVE_WATER,
		.suction = in->valves & ENDOSIM_VALVE_SUCTION,
		.wall_gap_m = in->wall_gap_m,
	};
	lens_step(&pt->lens, &pt->p.lens, &li, dt_s);
	respond(pt, in, seg, dt_s);
	return pt->torn;
}

int patient_perforate(struct patient *pt, double s_m)
{
	int seg;

	if (!pt->p.enabled || !pt->colon || pt->perforation.torn) {
		return -1;
	}
	seg = fluid_segment_at(&pt->fluid, s_m);
	pt->perforation.torn = true;
	pt->perforation.segment = seg;
	return seg;
}

void patient_bleed(struct patient *pt, double s_m, double blood_m3)
{
	if (pt->p.enabled && pt->colon) {
		fluid_add(&pt->fluid, fluid_segment_at(&pt->fluid, s_m),
			  blood_m3);
	}
}

void patient_gravity(const struct patient *pt, double g[3])
{
	if (!pt->p.enabled) {
		vec3_set(g, 0, 0, 0);
		return;
	}
	vec3_scale(g, pt->posture.down, pt->p.gravity_m_s2);
}

void patient_loose_gravity(const struct patient *pt, double g[3])
{
	vec3_scale(g, pt->posture.down, pt->p.gravity_m_s2);
}

void patient_pad(const struct patient *pt, struct flex_pad *out)
{
	const struct anatomy *a = pt->colon ? colon_anatomy(pt->colon) : NULL;
	const struct anatomy_site *s;
	double in;

	memset(out, 0, sizeof(*out));
	if (!pt->p.enabled || !a || pt->site < 0 || pt->site >= a->sites) {
		return;
	}
	s = &a->site[pt->site];
	in = pt->p.abdomen_n_per_m > 0 ? pt->hand_n / pt->p.abdomen_n_per_m
				       : 0;
	out->on = true;
	vec3_copy(out->in, s->direction);
	vec3_axpy(out->point, s->position_m, in, s->direction);
	out->radius_m = s->radius_m;
	out->force_n = pt->hand_n;
}

double patient_factor_at(const struct patient *pt, double s_m)
{
	if (!pt->p.enabled || !pt->colon) {
		return 1;
	}
	return gas_factor_at(pt->colon, pt->factor, s_m);
}

const double *patient_factors(const struct patient *pt)
{
	return pt->p.enabled && pt->colon ? pt->factor : NULL;
}

void patient_publish(const struct patient *pt,
		     struct endosim_patient_state *out)
{
	memset(out, 0, sizeof(*out));
	out->hand_site = -1;
	out->burst_segment = -1;
	out->pain_place = -1;
	out->torn_segment = -1;
	out->valves = pt->valves;
	for (int i = 0; i < ENDOSIM_SEGMENTS; i++) {
		out->factor[i] = 1;
	}
	if (!pt->p.enabled) {
		return;
	}
	out->enabled = 1;
	out->position = (uint32_t)pt->posture.position;
	out->turning = posture_turning(&pt->posture);
	out->turn = posture_progress(&pt->posture);
	vec3_copy(out->down, pt->posture.down);
	out->gas_m3 = pt->gas.volume_m3;
	out->pressure_pa = pt->gas.pressure_pa;
	out->gas_in_m3 = pt->gas.flow_in_m3;
	for (int i = 0; i < ENDOSIM_SEGMENTS && i < GAS_SEGMENTS; i++) {
		out->factor[i] = pt->factor[i];
		if (i < pt->gas.segments) {
			out->transmural_pa[i] = pt->gas.seg[i].transmural_pa;
			out->tension_n_per_m[i] =
				pt->gas.seg[i].tension_n_per_m;
		}
		if (i < pt->fluid.segments) {
			out->fluid_m3[i] = pt->fluid.seg[i].volume_m3;
			out->fluid_level_m[i] = pt->fluid.seg[i].level_m;
		}
	}
	vec3_copy(out->fluid_up, pt->fluid.up);
	out->hand_site = pt->site;
	out->tip_in_fluid = pt->tip_in_fluid;
	out->hand_n = pt->hand_n;
	out->pad_n = pt->pad_n;
	out->lens_smear = pt->lens.smear;
	out->lens_murk = pt->lens.murk;
	out->lens_redout = pt->lens.redout;
	out->burst_segment = pt->gas.burst_segment;
	out->sedation = (uint32_t)pt->sedation;
	out->pain = pt->pain.level;
	out->pain_stimulus = pt->pain.stimulus;
	out->pain_cause = (uint32_t)pt->pain.cause;
	out->pain_place = pt->pain.place;
	out->heart_rate_bpm = pt->vitals.heart_rate_bpm;
	out->spo2 = pt->vitals.spo2;
	out->torn_segment = pt->perforation.torn ? pt->perforation.segment : -1;
}
