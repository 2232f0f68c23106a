/*
 * test_patient.c - the patient's position and the fluid in the colon
 * (posture.h, fluid.h), on simulated time:
 *  - a turn from left lateral to right lateral goes over the back
 *    (through supine halfway) in the turn's time, gravity a unit vector
 *    that never jumps; every position's gravity as documented;
 *  - fluid in a straight round tube lying across gravity: the pool's
 *    depth is the circular segment's that holds the volume, within 1 %;
 *  - fluid in the normal colon: its level holds each segment's volume
 *    (against an independent sum over every sample within 5 %: the
 *    model's rings stand 4 mm apart), the volume conserved
 *    within 0.1 % through four position changes, the surface
 *    perpendicular to gravity within 1 degree at rest (and lagging during
 *    a turn), and suction under the surface empties it at the configured
 *    rate, none above it;
 *  - the lens: pressed into the wall it smears in proportion to the
 *    force above contact and the time, dipped into fluid it clouds, the
 *    water jet clears either in its wash time, suction near the wall
 *    reds it out with its time constant and lets go as fast;
 *  - gravity on the colon, through the force loop (rod model, in
 *    lockstep): the mobile segments' nodes sag along gravity, supine
 *    towards the back and prone towards the front;
 *  - the patient responds through its step: a held loop in the sigmoid
 *    hurts as pain.h defines it under the patient's own sedation (deep:
 *    less), looping in the sigmoid; the heart rate follows the pain and
 *    the saturation the sedation; the tip held into the wall above 14.1
 *    N tears it after 0.5 s, published; a sedation that does not exist
 *    is refused;
 *  - a perforation end to end, through the force loop's own cycle in
 *    lockstep (offline.h), the rig kept safe: the hand pushing a
 *    straight tip at its strongest (40 N) until the tip, held into the
 *    wall above 14.1 N, tears it (torn_segment; with the thresholds out of
 *    reach, the same push tears nothing); the air valve held, the anus
 *    shut around the tube, until the gas bursts the widest segment, the
 *    cecum (burst_segment, as Kozarek found); either way the loop stays
 *    enabled without a fault bit and every force stays finite. (Their
 *    events in a recorded session: tests/system/78-patient.sh.)
 *
 * Under the sanitizers (sanitized.h) the pump runs four times as fast
 * until the gas bursts, and the push with the thresholds out of reach
 * ends a second after the first push tore (not at its scenario's end).
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "base/vec3.h"
#include "model/anatomy.h"
#include "model/colon.h"
#include "model/fluid.h"
#include "model/lens.h"
#include "model/patient.h"
#include "model/posture.h"
#include "offline.h"
#include "plain_anatomy.h"
#include "rig_loop.h"
#include "sanitized.h"

#define DT 0.001
#define ML 1e-6

static struct colon *normal;

static int setup(void **state)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	struct anatomy a;
	char err[256];

	(void)state;
	if (anatomy_load(&a, "config/cases/normal.case", err, sizeof(err))) {
		fprintf(stderr, "%s\n", err);
		return -1;
	}
	p.ring_vertices = 64;
	normal = colon_create(&a, &p, err, sizeof(err));
	return normal ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	colon_destroy(normal);
	return 0;
}

static double angle_deg(const double a[3], const double b[3])
{
	return acos(fmax(-1, fmin(1, vec3_dot(a, b) /
					  (vec3_norm(a) * vec3_norm(b))))) *
	       180 / M_PI;
}

static void positions(void **state)
{
	const double want[POSTURE_POSITIONS][3] = {
		{ 1, 0, 0 }, { 0, 1, 0 }, { -1, 0, 0 }, { 0, -1, 0 },
	};
	const double supine[3] = { 0, 1, 0 };
	struct posture p;
	double last[3], most_step = 0;

	(void)state;
	for (int i = 0; i < POSTURE_POSITIONS; i++) {
		posture_reset(&p, i);
		assert_true(angle_deg(p.down, want[i]) < 1e-9);
		assert_int_equal(posture_find(posture_name(i)), i);
	}
	assert_int_equal(posture_find("sitting"), -1);
	assert_int_equal(posture_turn(&p, 7, 1), -EINVAL);

	posture_reset(&p, POSTURE_LEFT_LATERAL);
	assert_int_equal(posture_turn(&p, POSTURE_RIGHT_LATERAL, 10), 0);
	vec3_copy(last, p.down);
	for (int k = 1; k <= 10000; k++) {
		posture_step(&p, DT);
		most_step = fmax(most_step, angle_deg(last, p.down));
		vec3_copy(last, p.down);
		assert_true(fabs(vec3_norm(p.down) - 1) < 1e-12);
		if (k == 5000) { /* halfway: on the back */
			assert_true(angle_deg(p.down, supine) < 1e-6);
			assert_true(posture_turning(&p));
		}
	}
	assert_false(posture_turning(&p));
	assert_true(angle_deg(p.down, want[POSTURE_RIGHT_LATERAL]) < 1e-6);
	/* eased: never more than 1.5 x the mean rate of 18 deg/s */
	assert_true(most_step < 1.5 * 180.0 / 10 * DT);
	/* and back over the back again */
	posture_turn(&p, POSTURE_LEFT_LATERAL, 10);
	for (int k = 1; k <= 5000; k++) {
		posture_step(&p, DT);
	}
	assert_true(angle_deg(p.down, supine) < 1e-6);
}

/* Segment I's pool, summed over every sample of the colon: the same
 * geometry as fluid.c's, an independent sum. */
static double pool_sum(const struct fluid *f, int i)
{
	const struct centreline *cl = colon_centreline(normal);
	const struct fluid_segment *s = &f->seg[i];
	double v = 0, ds = centreline_step(cl);

	for (size_t k = s->first; k < s->first + s->count; k++) {
		const struct centreline_point *c = centreline_sample(cl, k);
		double r = colon_tube_radius(normal, k);
		double tn = vec3_dot(c->t, f->up);
		double e = r * sqrt(fmax(0, 1 - tn * tn)) + ds * fabs(tn) / 2;
		double x = fmax(-1, fmin(1, (s->level_m - vec3_dot(c->p, f->up)) /
						   e));

		v += ds * r * r * (acos(-x) + x * sqrt(1 - x * x));
	}
	return v;
}

static void fluid_pools(void **state)
{
	struct fluid_params fp = FLUID_PARAMS_DEFAULT;
	double vol[FLUID_SEGMENTS] = { 0 };
	struct posture p;
	struct fluid f;
	const int order[] = { POSTURE_SUPINE, POSTURE_RIGHT_LATERAL,
			      POSTURE_PRONE, POSTURE_LEFT_LATERAL };
	double total0 = 0, lag = 0, none[3] = { 0 };

	(void)state;
	vol[ANATOMY_SIGMOID] = 40 * ML;
	vol[ANATOMY_TRANSVERSE] = 60 * ML;
	vol[ANATOMY_CECUM] = 30 * ML;
	posture_reset(&p, POSTURE_LEFT_LATERAL);
	fluid_attach(&f, &fp, normal, vol, p.down, NULL);
	for (int i = 0; i < FLUID_SEGMENTS; i++) {
		total0 += f.seg[i].volume_m3;
	}
	for (size_t n = 0; n < sizeof(order) / sizeof(order[0]); n++) {
		double total = 0, up[3];

		posture_turn(&p, order[n], 10);
		for (int k = 0; k < 12000; k++) { /* the turn, then 2 s */
			posture_step(&p, DT);
			fluid_step(&f, p.down, NULL, false, none, -1, DT);
			vec3_scale(up, p.down, -1);
			lag = fmax(lag, angle_deg(f.up, up));
		}
		vec3_scale(up, p.down, -1);
		printf("# %s: the surface %.4f deg from level;", posture_name(
			       order[n]), angle_deg(f.up, up));
		assert_true(angle_deg(f.up, up) < 1);
		for (int i = 0; i < FLUID_SEGMENTS; i++) {
			total += f.seg[i].volume_m3;
			if (vol[i] > 0) {
				double v = pool_sum(&f, i);

				printf(" %s %.2f mL (level's %.2f), %.1f mm "
				       "deep;", anatomy_segment_name(i),
				       f.seg[i].volume_m3 / ML, v / ML,
				       f.seg[i].depth_m * 1e3);
				assert_true(fabs(v - vol[i]) < 0.05 * vol[i]);
				assert_true(f.seg[i].depth_m > 0.002);
			}
		}
		printf("\n");
		assert_true(fabs(total - total0) < 0.001 * total0);
	}
	printf("# the surface lagged gravity by %.1f deg at most in a turn\n",
	       lag);
	assert_true(lag > 1);
}

/* A round straight tube of radius R across gravity: the depth D of a
 * pool holding V in length L: L R^2 A(D / R - 1) = V. */
static double analytic_depth(double v, double l, double r)
{
	double lo = 0, hi = 2 * r;

	for (int k = 0; k < 200; k++) {
		double d = (lo + hi) / 2, x = d / r - 1;

		if (l * r * r * (acos(-x) + x * sqrt(1 - x * x)) > v) {
			hi = d;
		} else {
			lo = d;
		}
	}
	return lo;
}

static void straight_pool(void **state)
{
	struct colon_params cp = COLON_PARAMS_DEFAULT;
	struct fluid_params fp = FLUID_PARAMS_DEFAULT;
	double vol[FLUID_SEGMENTS] = { 0 }, down[3] = { 0, 1, 0 };
	struct anatomy a;
	struct colon *c;
	struct fluid f;
	char err[256];
	int i = ANATOMY_TRANSVERSE;

	(void)state;
	plain_anatomy(&a, 0.05);
	for (int k = 0; k < ANATOMY_SEGMENTS; k++) {
		a.seg[k].taenia_depth = 0;
		a.seg[k].fold_depth = 0;
	}
	cp.ring_vertices = 64;
	c = colon_create(&a, &cp, err, sizeof(err));
	assert_non_null(c);
	for (double ml = 10; ml <= 400; ml *= 2) {
		const struct fluid_segment *s = &f.seg[i];
		double r, l = a.seg[i].length_m, want;

		vol[i] = ml * ML;
		fluid_attach(&f, &fp, c, vol, down, NULL);
		r = colon_tube_radius(c, s->first + s->count / 2);
		want = analytic_depth(vol[i], l, r);
		printf("# a straight tube %.1f mm wide: %.0f mL pools %.3f mm "
		       "deep (analytic %.3f)\n", 2e3 * r, ml, s->depth_m * 1e3,
		       want * 1e3);
		assert_true(fabs(s->depth_m - want) < 0.01 * want);
	}
	colon_destroy(c);
}

static void suction(void **state)
{
	struct fluid_params fp = FLUID_PARAMS_DEFAULT;
	double vol[FLUID_SEGMENTS] = { 0 };
	struct posture p;
	struct fluid f;
	const struct centreline *cl = colon_centreline(normal);
	const struct fluid_segment *s;
	double bottom[3] = { 0 }, above[3], low = INFINITY, v0, t = 2;
	int i = ANATOMY_TRANSVERSE;

	(void)state;
	vol[i] = 50 * ML;
	posture_reset(&p, POSTURE_SUPINE);
	fluid_attach(&f, &fp, normal, vol, p.down, NULL);
	s = &f.seg[i];
	for (size_t k = s->first; k < s->first + s->count; k++) {
		const double *q = centreline_sample(cl, k)->p;

		if (vec3_dot(q, f.up) < low) { /* the segment's lowest */
			low = vec3_dot(q, f.up);
			vec3_copy(bottom, q);
		}
	}
	vec3_axpy(above, bottom, 0.05, f.up); /* 5 cm up: in the gas */
	assert_true(fluid_under(&f, i, bottom));
	assert_false(fluid_under(&f, i, above));
	v0 = s->volume_m3;
	for (int k = 0; k < (int)lround(t / DT); k++) {
		fluid_step(&f, p.down, NULL, true, above, i, DT);
	}
	assert_true(s->volume_m3 == v0);
	for (int k = 0; k < (int)lround(t / DT); k++) {
		fluid_step(&f, p.down, NULL, true, bottom, i, DT);
	}
	printf("# suction under the surface: %.3f mL in %.0f s (%.3f mL at "
	       "%.2f mL/s)\n", (v0 - s->volume_m3) / ML, t,
	       fp.suction_m3_per_s * t / ML, fp.suction_m3_per_s / ML);
	assert_true(fabs(v0 - s->volume_m3 - fp.suction_m3_per_s * t) <
		    1e-6 * fp.suction_m3_per_s * t);
	assert_true(fabs(f.sucked_m3 - fp.suction_m3_per_s * t) < 1e-12);
}

static void lens(void **state)
{
	const struct lens_params p = LENS_PARAMS_DEFAULT;
	struct lens_input in = { .wall_gap_m = 0.01 };
	struct lens l;
	double t;

	(void)state;
	lens_reset(&l);
	in.tip_force_n = 1.5; /* 1 N above contact: 4 N s to smear */
	for (t = 0; t < 2 - DT / 2; t += DT) {
		lens_step(&l, &p, &in, DT);
	}
	print_message("pressed at 1.5 N for 2 s: smear %.3f (want %.3f)\n",
		      l.smear, (1.5 - p.contact_n) * 2 / p.smear_n_s);
	assert_true(fabs(l.smear - (1.5 - p.contact_n) * 2 / p.smear_n_s) <
		    1e-6);
	in.tip_force_n = 0.4; /* below contact: nothing more */
	lens_step(&l, &p, &in, 1);
	assert_true(fabs(l.smear - 0.5) < 1e-6);
	/* dipped: murky in dip_s */
	in.under_fluid = true;
	for (t = 0; t < p.dip_s * 0.5 - DT / 2; t += DT) {
		lens_step(&l, &p, &in, DT);
	}
	assert_true(fabs(l.murk - 0.5) < 1e-6);
	in.under_fluid = false;
	/* washed: half a wash time takes half off each */
	in.water = true;
	for (t = 0; t < p.wash_s * 0.5 - DT / 2; t += DT) {
		lens_step(&l, &p, &in, DT);
	}
	assert_true(l.smear < 1e-6 && l.murk < 1e-6);
	in.water = false;
	/* red-out: suction within the gap */
	in.suction = true;
	in.wall_gap_m = p.redout_gap_m / 2;
	for (t = 0; t < p.redout_s - DT / 2; t += DT) {
		lens_step(&l, &p, &in, DT);
	}
	print_message("suction at the wall for %.1f s: red-out %.3f (1 - 1/e "
		      "= %.3f)\n", p.redout_s, l.redout, 1 - exp(-1));
	assert_true(fabs(l.redout - (1 - exp(-1))) < 1e-3);
	in.wall_gap_m = p.redout_gap_m * 2; /* away from the wall */
	for (t = 0; t < 5 * p.redout_s; t += DT) {
		lens_step(&l, &p, &in, DT);
	}
	assert_true(l.redout < 0.01);
}

/* The published nodes' mean displacement from rest along DOWN, m. */
static double sag_along(const struct endosim_state *st, const double down[3])
{
	double sum = 0;

	for (uint32_t k = 0; k < st->rod.nodes; k++) {
		for (int d = 0; d < 3; d++) {
			sum += st->rod.node[k][d] * down[d];
		}
	}
	return st->rod.nodes ? sum / st->rod.nodes : 0;
}

/* Turned to POSITION and settled: the nodes' mean sag along gravity. */
static double settled_sag(struct rig_loop *r, int position, double *y)
{
	const struct endosim_state *st = NULL;
	const double back[3] = { 0, 1, 0 };

	loop_patient_post(r->loop, &(struct loop_patient_command){
		LOOP_PATIENT_TURN, position, 0 });
	for (int k = 0; k < 2500; k++) {
		st = rig_loop_step(r);
	}
	assert_false(st->patient.turning);
	assert_true(st->rod.nodes > 10);
	*y = sag_along(st, back);
	return sag_along(st, st->patient.down);
}

/* The patient on the normal colon, enabled, sedated SEDATION, after
 * SECONDS of the sigmoid's mesentery holding TENSION_N and the tip
 * pressing TIP_N straight into the sigmoid's wall. */
static void respond(struct patient *pt, int sedation, double tension_n,
		    double tip_n, double seconds)
{
	struct patient_params p = PATIENT_PARAMS_DEFAULT;
	double spans[ENDOSIM_SPANS] = { tension_n };
	struct patient_input in = {
		.tip_s_m = anatomy_segment_start(colon_anatomy(normal),
						 ANATOMY_SIGMOID) + 0.05,
		.tip_force_n = tip_n,
		.wall_gap_m = 0.01,
		.insertion_m_s = 0.01,
		.span_tension_n = spans,
	};

	p.enabled = true;
	patient_init(pt, &p);
	assert_int_equal(patient_sedate(pt, sedation), 0);
	patient_attach(pt, normal); /* a new case keeps the sedation */
	assert_int_equal(pt->sedation, sedation);
	for (int k = 0; k < (int)lround(seconds / DT); k++) {
		int torn = patient_step(pt, &in, DT);

		if (torn >= 0) {
			assert_int_equal(torn, ANATOMY_SIGMOID);
			assert_int_equal(pt->torn, ANATOMY_SIGMOID);
		}
	}
}

static void responds(void **state)
{
	const struct pain_params d = PAIN_PARAMS_DEFAULT;
	const struct vitals_params v = VITALS_PARAMS_DEFAULT;
	struct endosim_patient_state out;
	static struct patient pt;
	double g, t, want, none, deep;

	(void)state;
	respond(&pt, ENDOSIM_SEDATION_NONE, 30, 0, 2);
	want = d.stretch_gain_per_n * (30 - d.stretch_threshold_n) *
	       (1 - exp(-2 / d.rise_s));
	none = pt.pain.level;
	print_message("a 30 N loop held 2 s, unsedated: pain %.3f (%.3f), "
		      "heart %.1f bpm\n", none, want, pt.vitals.heart_rate_bpm);
	assert_true(fabs(none - want) <= 0.02 * want);
	assert_int_equal(pt.pain.cause, ENDOSIM_PAIN_LOOPING);
	assert_int_equal(pt.pain.place, ANATOMY_SIGMOID);
	want = v.rest_bpm + v.bpm_per_pain * none; /* where it goes */
	assert_true(pt.vitals.heart_rate_bpm > v.rest_bpm &&
		    pt.vitals.heart_rate_bpm < want);
	patient_publish(&pt, &out);
	assert_true(out.pain == pt.pain.level && out.pain_cause ==
		    ENDOSIM_PAIN_LOOPING && out.sedation == ENDOSIM_SEDATION_NONE);
	assert_int_equal(out.torn_segment, -1);

	respond(&pt, ENDOSIM_SEDATION_DEEP, 30, 0, 2);
	pain_sedation_factors(ENDOSIM_SEDATION_DEEP, &g, &t);
	want = g * d.stretch_gain_per_n * (30 - t * d.stretch_threshold_n) *
	       (1 - exp(-2 / d.rise_s));
	deep = pt.pain.level;
	print_message("... deeply sedated: pain %.3f (%.3f), SpO2 %.4f\n",
		      deep, want, pt.vitals.spo2);
	assert_true(fabs(deep - want) <= 0.02 * want && deep < none);
	assert_true(pt.vitals.spo2 < v.spo2[ENDOSIM_SEDATION_NONE] &&
		    pt.vitals.spo2 >= v.spo2[ENDOSIM_SEDATION_DEEP]);

	/* the tip held into the wall at 20 N: torn after the hold */
	respond(&pt, ENDOSIM_SEDATION_MODERATE, 0, 20, 0.45);
	assert_false(pt.perforation.torn);
	respond(&pt, ENDOSIM_SEDATION_MODERATE, 0, 20, 0.6);
	assert_true(pt.perforation.torn);
	patient_publish(&pt, &out);
	assert_int_equal(out.torn_segment, ANATOMY_SIGMOID);
	assert_int_equal(out.pain_cause, ENDOSIM_PAIN_TIP);

	assert_int_equal(patient_sedate(&pt, ENDOSIM_SEDATIONS), -EINVAL);
	assert_int_equal(patient_sedate(&pt, -1), -EINVAL);
	assert_int_equal(pt.sedation, ENDOSIM_SEDATION_MODERATE);
}

static void colon_sags(void **state)
{
	struct rig_loop r;
	double supine, prone, y_supine, y_prone;

	(void)state;
	rig_loop_create(&r, true, HAPTICS_MODEL_ROD);
	supine = settled_sag(&r, POSTURE_SUPINE, &y_supine);
	prone = settled_sag(&r, POSTURE_PRONE, &y_prone);
	print_message("the mobile colon's nodes sag %.2f mm supine (towards "
		      "the back: %+.2f mm), %.2f mm prone (%+.2f mm)\n",
		      supine * 1e3, y_supine * 1e3, prone * 1e3,
		      y_prone * 1e3);
	assert_true(supine > 1e-4 && prone > 1e-4);
	assert_true(y_supine > 1e-4 && y_prone < -1e-4);
	rig_loop_destroy(&r);
}

/* The force loop in lockstep on the normal case with the patient and CFG
 * (its colon read here), the hand playing the scenario TEXT (its lines). */
static struct offline *patient_course(const struct config *cfg,
				      const char *text)
{
	FILE *f = fmemopen((void *)text, strlen(text), "r");
	struct scenario *scn;
	struct config c = *cfg;
	struct colon *colon;
	struct offline *o;
	char err[512];

	assert_non_null(f);
	scn = scenario_load_stream(f, "test", err, sizeof(err));
	fclose(f);
	if (!scn) {
		fail_msg("%s", err);
	}
	c.patient.enabled = true;
	snprintf(c.colon.file, sizeof(c.colon.file),
		 "config/cases/normal.case");
	colon = cases_load(&c, NULL, err, sizeof(err));
	if (!colon) {
		fail_msg("%s", err);
	}
	o = offline_create_with(&c, colon, scn, err, sizeof(err));
	if (!o) {
		fail_msg("%s", err);
	}
	return o;
}

/* The rig safe: enabled, no fault, every force finite. */
static bool safe(const struct endosim_state *st)
{
	bool finite = isfinite(st->haptics.f_static[0]) &&
		      isfinite(st->haptics.f_static[1]) &&
		      isfinite(st->haptics.f_static[2]);

	for (int a = 0; a < ENDOSIM_AXES; a++) {
		finite = finite && isfinite(st->axis[a].command) &&
			 isfinite(st->axis[a].limited);
	}
	return finite && st->state == ENDOSIM_STATE_ENABLED &&
	       !st->fault_bits;
}

struct tear {
	double t_s;      /* scenario time of the first torn cycle; -1 */
	double force_n;  /* the tip's force then */
	int torn, burst; /* as the last cycle published */
	double peak_pa;  /* the gas's highest pressure */
	double end_pa;   /* and its last */
	long unsafe;     /* cycles not safe() */
};

/* Plays O to its end or to END_S, whichever comes first (or 1 s after a
 * tear), what tore into T. */
static void play_tear(struct offline *o, double end_s, struct tear *t)
{
	long cycles = (long)(fmin(offline_length_s(o), end_s) * 1000);
	long after = -1;

	*t = (struct tear){ .t_s = -1 };
	for (long k = 0; k < cycles && after != 0; k++, after -= after > 0) {
		const struct endosim_state *st = offline_step(o);
		const struct endosim_patient_state *p = &st->patient;

		t->unsafe += !safe(st);
		t->peak_pa = fmax(t->peak_pa, p->pressure_pa);
		t->end_pa = p->pressure_pa;
		t->torn = p->torn_segment;
		t->burst = p->burst_segment;
		if (t->t_s < 0 && (t->torn >= 0 || t->burst >= 0)) {
			t->t_s = st->scenario_time_s;
			t->force_n = vec3_norm(st->haptics.f_static);
			after = 1000;
		}
	}
	offline_destroy(o);
}

/* The hand inserts 8 cm with the wheels held straight, then pushes at
 * its strongest; the rod model. */
static const char push_lines[] =
	"0 insertion target 0.08 2\n0 wheel_ud target 0\n"
	"0 wheel_lr target 0\n2.5 insertion force 40\n6 end\n";

static void tip_tears(void **state)
{
	struct config cfg;
	struct tear t, strong;

	(void)state;
	config_defaults(&cfg);
	play_tear(patient_course(&cfg, push_lines), INFINITY, &t);
	print_message("pushed at 40 N: segment %d torn by the tip at %.2f s, "
		      "its force %.1f N; %ld unsafe cycles\n", t.torn, t.t_s,
		      t.force_n, t.unsafe);
	assert_true(t.torn >= 0 && t.torn < ENDOSIM_SEGMENTS);
	assert_int_equal(t.burst, -1);
	assert_true(t.t_s > 2.5 + cfg.patient.perforation_hold_s);
	assert_true(t.force_n > cfg.patient.perforation_straight_n);
	assert_int_equal(t.unsafe, 0);
	/* the tip's force is what tore it: out of reach, nothing tears */
	cfg.patient.perforation_straight_n = 500;
	cfg.patient.perforation_bent_n = 500;
	play_tear(patient_course(&cfg, push_lines),
		  SANITIZED ? t.t_s + 1 : INFINITY, &strong);
	assert_int_equal(strong.torn, -1);
	assert_int_equal(strong.unsafe, 0);
}

static void gas_bursts(void **state)
{
	static const char lines[] = "0 valve air on\n100 end\n";
	struct config cfg;
	struct tear t;

	(void)state;
	config_defaults(&cfg);
	cfg.haptics.model = HAPTICS_MODEL_PAPER; /* the gas's alone: quick */
	cfg.patient.leak_m3_per_s_pa = 0;        /* the anus shut */
	if (SANITIZED) {
		cfg.patient.pump_m3_per_s *= 4;
	}
	play_tear(patient_course(&cfg, lines), INFINITY, &t);
	print_message("the air valve held: segment %d burst at %.2f s, at "
		      "%.1f mmHg, 1 s later %.1f mmHg; %ld unsafe cycles\n",
		      t.burst, t.t_s, t.peak_pa / GAS_PA_PER_MMHG,
		      t.end_pa / GAS_PA_PER_MMHG, t.unsafe);
	assert_int_equal(t.burst, ANATOMY_CECUM);
	assert_int_equal(t.torn, -1);
	assert_true(t.t_s > 0);
	assert_true(t.end_pa < 0.5 * t.peak_pa); /* its gas escaped */
	assert_int_equal(t.unsafe, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(positions),
		cmocka_unit_test(straight_pool),
		cmocka_unit_test(fluid_pools),
		cmocka_unit_test(suction),
		cmocka_unit_test(lens),
		cmocka_unit_test(colon_sags),
		cmocka_unit_test(responds),
		cmocka_unit_test(tip_tears),
		cmocka_unit_test(gas_bursts),
	};

	sanitized_leaves("the pump four times as fast to the burst, the push "
			 "out of reach ended a second after the tear; the "
			 "full runs are the plain build's");
	return cmocka_run_group_tests(tests, setup, teardown);
}
