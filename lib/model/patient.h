/*
 * patient.h - the patient's body around the colon, as the haptics need
 * it each cycle: the gas that holds the lumen open (gas.h), the position
 * on the table and gravity (posture.h), the fluid pooled in the colon
 * (fluid.h), the assistant's hand on the abdomen at one of the case's
 * sites (a pad, flex.h), the lens (lens.h) and the handle's valves.
 *
 * The valves: the air/water valve covered lets the pump's air (or CO2)
 * in; pressed, it sends water onto the lens (the jet); the suction valve
 * takes gas out while the tip is in gas, fluid while it is under a pool's
 * surface.
 *
 * The hand: the assistant presses at site I with F newtons (the default
 * hand_n, at most hand_max_n): the pad sits on the abdominal wall at the
 * site's position, pushed in along its direction by F / abdomen_n_per_m
 * (the belly gives way), and holds the mobile colon within the site's
 * radius of its axis between the hand and the back, with at most F in
 * all (flex_set_pad(): the pad's grip); pad_n is what it holds.
 *
 * The patient responds (pain.h, vitals.h, perforation.h): the pain from
 * the mesentery's stretch (the haptics give each mobile span's tension),
 * the wall's distension (the gas's Laplace tension per segment) and the
 * tip's force; the heart rate and saturation; the tip's force tearing the
 * wall. Sedation is the patient's own (patient_sedate(): the session's),
 * not a live parameter; pain.sedation is where it starts.
 *
 * Gravity (gravity_m_s2 along posture's direction) acts on the mobile
 * colon's nodes, the rod and the fluid; the abdomen's hydrostatic
 * pressure on the gas (gas.h).
 *
 * Disabled (enabled false): every lumen factor 1, no gravity, no gas,
 * fluid or hand: the colon as it was before the patient, which the
 * scope's own tests keep.
 *
 * Units SI. No allocation anywhere (a struct patient is plain data, the
 * haptics hold it): the force loop steps it, fixed work a cycle (the
 * gas's Newton iterations, one segment's pool). One writer.
 */
#ifndef ENDOSIM_PATIENT_H
#define ENDOSIM_PATIENT_H

#include <stdbool.h>
#include <stdint.h>

#include "model/colon.h"
#include "model/flex.h"
#include "model/fluid.h"
#include "model/gas.h"
#include "model/lens.h"
#include "model/pain.h"
#include "model/perforation.h"
#include "model/posture.h"
#include "model/vitals.h"
#include "proto/endosim_shm.h"

#define PATIENT_GRAVITY_M_S2 9.81

struct patient_params {
	bool enabled;
	struct gas_params gas;
	struct fluid_params fluid;
	struct lens_params lens;
	struct pain_params pain;
	struct perforation_params perforation;
	struct vitals_params vitals;
	int start_position;         /* enum posture_position */
	double turn_s;              /* a change of position takes */
	double gravity_m_s2;
	double hand_n;              /* the assistant's press unless told */
	double hand_max_n;          /* the most she presses with */
	double abdomen_n_per_m;     /* the belly's give under the pad */
};

/* Off until every part of the rig shows and uses it (endoview's picture,
 * the scripted trainee's course): then on. */
#define PATIENT_DEFAULT_ENABLED false
#define PATIENT_DEFAULT_TURN_S 10.0
#define PATIENT_DEFAULT_HAND_N 20.0
#define PATIENT_DEFAULT_HAND_MAX_N 60.0
#define PATIENT_DEFAULT_ABDOMEN_N_PER_M 1000.0 /* 20 N: 2 cm in */

#define PATIENT_PARAMS_DEFAULT { .enabled = PATIENT_DEFAULT_ENABLED, \
		.gas = GAS_PARAMS_DEFAULT, .fluid = FLUID_PARAMS_DEFAULT, \
		.lens = LENS_PARAMS_DEFAULT, .pain = PAIN_PARAMS_DEFAULT, \
		.perforation = PERFORATION_PARAMS_DEFAULT, \
		.vitals = VITALS_PARAMS_DEFAULT, \
		.start_position = POSTURE_LEFT_LATERAL, \
		.turn_s = PATIENT_DEFAULT_TURN_S, \
		.gravity_m_s2 = PATIENT_GRAVITY_M_S2, \
		.hand_n = PATIENT_DEFAULT_HAND_N, \
		.hand_max_n = PATIENT_DEFAULT_HAND_MAX_N, \
		.abdomen_n_per_m = PATIENT_DEFAULT_ABDOMEN_N_PER_M }

/* This cycle's inputs from the scope and the handle. */
struct patient_input {
	uint32_t valves;         /* enum endosim_valve bits */
	double tip[3];           /* the tip's place, body frame, m */
	double tip_s_m;          /* its material s */
	double tip_force_n;      /* the wall's force on the tip */
	double wall_gap_m;       /* the tip's clearance to the wall */
	double tip_bend_rad;     /* the bending section's angle, either way */
	double insertion_m_s;    /* the tube pushed in (> 0) */
	double roll_rad_s;       /* and turned */
	const double *span_tension_n; /* each mobile span's mesentery
					 (flex_span_tension()), N; NULL:
					 none */
};

struct patient {
	struct patient_params p;
	const struct colon *colon;
	struct gas gas;
	struct posture posture;
	struct fluid fluid;
	struct lens lens;
	double factor[GAS_SEGMENTS]; /* this cycle's; 1 when disabled */
	uint32_t valves;
	bool tip_in_fluid;
	int site;                /* the site pressed, -1: none */
	double hand_n;
	double pad_n;            /* what the pad held (flex_pad_force()) */
	int torn;                /* a segment torn in the last step, -1 */
	int sedation;            /* enum endosim_sedation */
	struct pain pain;
	struct perforation perforation; /* by the tip */
	struct vitals vitals;
	int span_segment[ENDOSIM_SPANS]; /* each mobile span's segment */
	int spans;
};

/* Plain data, nothing attached, disabled parameters P kept. */
void patient_init(struct patient *pt, const struct patient_params *p);

/* COLON (a new case): everything anew at the start position, the gas at
 * its nominal distension, the case's fluid, the hand off. */
void patient_attach(struct patient *pt, const struct colon *colon);

/* Live parameters (flows, rates, the hand's force and reach; enabled and
 * the start position take effect at the next attach). */
void patient_set_params(struct patient *pt, const struct patient_params *p);

/* Turns the patient to POSITION over turn_s. 0, or -EINVAL (no such
 * position, disabled). */
int patient_turn(struct patient *pt, int position);

/* The assistant presses at SITE (the case's order) with FORCE_N (<= 0:
 * hand_n). 0, or -EINVAL (no such site, a force beyond hand_max_n,
 * disabled). */
int patient_press(struct patient *pt, int site, double force_n);

/* She lets go. */
void patient_release(struct patient *pt);

/* The patient sedated as SEDATION says (enum endosim_sedation), from now
 * until told again (a new case keeps it). 0, or -EINVAL (no such level;
 * nothing changed). Not for a disabled patient either. */
int patient_sedate(struct patient *pt, int sedation);

/*
 * One cycle of DT_S. Returns the segment torn in it (by the gas's
 * pressure or the tip's force), or -1. A state no
 * longer finite (patient_finite(); the loop's non-finite fault latched on
 * the cycle that broke it) is laid anew first, lying where it lies: the
 * gas at its nominal distension, the case's fluid, the hand off, the lens
 * clean (as the rod lays the tube anew).
 */
int patient_step(struct patient *pt, const struct patient_input *in,
		 double dt_s);

/*
 * The wall torn through where the scope's tip is, at material S_M, by
 * something other than the tip's force (a tool's current, tool.h): the
 * perforation as the tip's would be (torn_segment, once). Returns the
 * segment torn, or -1 (disabled, or torn already). Fixed work.
 */
int patient_perforate(struct patient *pt, double s_m);

/*
 * BLOOD_M3 shed into the lumen at material S_M (a bleeding point,
 * tool.h): into that segment's pool, where gravity takes it (fluid.h).
 * Nothing when disabled. Fixed work.
 */
void patient_bleed(struct patient *pt, double s_m, double blood_m3);

/*
 * The values the force loop's non-finite check watches, into V: the
 * gas's volume and pressure, each segment's radius factor, the fluid's
 * volume and level in each segment, the lens' smear, murk and red-out,
 * the pad's force, the pain, the heart rate and the saturation. Any of
 * them not finite is a fault.
 */
#define PATIENT_WATCHED (2 + 3 * GAS_SEGMENTS + 4 + 3)
void patient_watched(const struct patient *pt, double v[PATIENT_WATCHED]);

/* Every watched value finite. */
bool patient_finite(const struct patient *pt);

/* Gravity's acceleration now (m/s^2, body frame); zeros when disabled. */
void patient_gravity(const struct patient *pt, double g[3]);

/*
 * Gravity's acceleration (m/s^2, body frame) on what lies loose in the
 * lumen (a cut polyp, tool.h): the posture's gravity_m_s2, whether the
 * body is modelled or not (a disabled patient lies settled in its start
 * position, and a polyp cut free still falls).
 */
void patient_loose_gravity(const struct patient *pt, double g[3]);

/* The pad as it presses now (out->on false: none). */
void patient_pad(const struct patient *pt, struct flex_pad *out);

/* The lumen's radius factor at material S_M (gas_factor_at()). */
double patient_factor_at(const struct patient *pt, double s_m);

/* The lumen's GAS_SEGMENTS radius factors now (gas_factor_at()'s: for
 * what lies on the wall, tool_fall()); NULL while disabled (the lumen
 * as the case draws it). Valid until the next step. */
const double *patient_factors(const struct patient *pt);

/* The published state. */
void patient_publish(const struct patient *pt,
		     struct endosim_patient_state *out);

#endif
