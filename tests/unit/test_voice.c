/*
 * test_voice.c - what the patient says (viewer/voice.h): each step's clip
 * as the level rises across it, the highest only when it jumps, none
 * again while a level is held or wavers, again once it fell well below,
 * no two clips within the interval, the cry at a perforation, quiet in
 * deep sedation, nothing while muted.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "viewer/voice.h"

#define FRAME_S (1.0 / 60)
#define MAX_SAID 16

/* What a run said: each clip and when. */
struct said {
	enum voice_clip clip[MAX_SAID];
	double at_s[MAX_SAID];
	int n;
};

static struct endosim_patient_state patient(void)
{
	return (struct endosim_patient_state){
		.enabled = 1, .sedation = ENDOSIM_SEDATION_MODERATE,
		.burst_segment = -1, .torn_segment = -1, .pain_place = -1,
	};
}

/* Frames from T0 to T1 s with the level going linearly from L0 to L1;
 * what V said into S. */
static void run(struct voice *v, struct endosim_patient_state *p, double t0,
		double t1, double l0, double l1, struct said *s)
{
	for (double t = t0; t < t1 - 1e-9; t += FRAME_S) {
		enum voice_clip c;

		p->pain = l0 + (l1 - l0) * (t - t0) / (t1 - t0);
		c = voice_step(v, p, t);
		if (c != VOICE_NONE && s->n < MAX_SAID) {
			s->clip[s->n] = c;
			s->at_s[s->n++] = t;
		}
	}
}

static void said_at(const struct said *s, int i, enum voice_clip clip,
		    double at_s)
{
	assert_true(i < s->n);
	assert_string_equal(voice_clip_name(s->clip[i]),
			    voice_clip_name(clip));
	assert_true(fabs(s->at_s[i] - at_s) < 1.5 * FRAME_S);
}

/* A slow rise (0.25 a second, steps 6 s apart): each step's clip as the
 * level crosses it. */
static void each_step_at_its_crossing(void **state)
{
	struct endosim_patient_state p = patient();
	struct voice v;
	struct said s = { 0 };

	(void)state;
	voice_init(&v);
	run(&v, &p, 0, 40, 0, 10, &s);
	assert_int_equal(s.n, 4);
	said_at(&s, 0, VOICE_GROAN, VOICE_GROAN_AT / 0.25);
	said_at(&s, 1, VOICE_OW, VOICE_OW_AT / 0.25);
	said_at(&s, 2, VOICE_HURTS, VOICE_HURTS_AT / 0.25);
	said_at(&s, 3, VOICE_STOP, VOICE_STOP_AT / 0.25);
}

/* A jump across three steps says the highest only; held, or wavering
 * about a step, nothing more for a minute. */
static void held_level_does_not_repeat(void **state)
{
	struct endosim_patient_state p = patient();
	struct voice v;
	struct said s = { 0 };

	(void)state;
	voice_init(&v);
	run(&v, &p, 0, 1, 0, 0, &s);
	run(&v, &p, 1, 61, 7.5, 7.5, &s);
	assert_int_equal(s.n, 1);
	said_at(&s, 0, VOICE_HURTS, 1);
	for (int k = 0; k < 30; k++) { /* 6.9 to 7.1 and back, each 2 s */
		run(&v, &p, 61 + 2 * k, 62 + 2 * k, 7.1, 6.9, &s);
		run(&v, &p, 62 + 2 * k, 63 + 2 * k, 6.9, 7.1, &s);
	}
	assert_int_equal(s.n, 1);
}

/* Said again only once the level fell VOICE_REARM_DROP below the step. */
static void rearmed_only_well_below(void **state)
{
	struct endosim_patient_state p = patient();
	struct voice v;
	struct said s = { 0 };

	(void)state;
	voice_init(&v);
	run(&v, &p, 0, 1, 0, 0, &s);
	run(&v, &p, 1, 10, 6, 6, &s); /* ow */
	run(&v, &p, 10, 20, VOICE_OW_AT - VOICE_REARM_DROP + 0.1,
	    VOICE_OW_AT - VOICE_REARM_DROP + 0.1, &s);
	run(&v, &p, 20, 30, 6, 6, &s); /* not well below: nothing */
	assert_int_equal(s.n, 1);
	run(&v, &p, 30, 40, VOICE_OW_AT - VOICE_REARM_DROP - 0.1,
	    VOICE_OW_AT - VOICE_REARM_DROP - 0.1, &s);
	run(&v, &p, 40, 50, 6, 6, &s); /* ow again */
	assert_int_equal(s.n, 2);
	said_at(&s, 0, VOICE_OW, 1);
	said_at(&s, 1, VOICE_OW, 40);
}

/* A step crossed within the interval waits for its end; one the level
 * left meanwhile is not said. */
static void interval_between_clips(void **state)
{
	struct endosim_patient_state p = patient();
	struct voice v;
	struct said s = { 0 };

	(void)state;
	voice_init(&v);
	run(&v, &p, 0, 1, 0, 0, &s);
	run(&v, &p, 1, 2, 4.5, 4.5, &s);  /* groan */
	run(&v, &p, 2, 10, 9, 9, &s);     /* please stop, at 1 + 4 s */
	assert_int_equal(s.n, 2);
	said_at(&s, 0, VOICE_GROAN, 1);
	said_at(&s, 1, VOICE_STOP, 1 + VOICE_MIN_INTERVAL_S);
	run(&v, &p, 10, 20, 0, 0, &s);
	run(&v, &p, 20, 21, 6, 6, &s);    /* ow */
	run(&v, &p, 21, 22, 0, 0, &s);    /* gone before the interval ends */
	run(&v, &p, 22, 23, 0, 0, &s);
	run(&v, &p, 23, 30, 4.8, 4.8, &s); /* 4.8: groan re-armed at 2.0,
					      said at 24 s */
	assert_int_equal(s.n, 4);
	said_at(&s, 2, VOICE_OW, 20);
	said_at(&s, 3, VOICE_GROAN, 20 + VOICE_MIN_INTERVAL_S);
}

/* The cry at once (within the interval), once; by the tip's tear too. */
static void cry_at_perforation(void **state)
{
	struct endosim_patient_state p = patient();
	struct voice v;
	struct said s = { 0 };

	(void)state;
	voice_init(&v);
	run(&v, &p, 0, 1, 0, 0, &s);
	run(&v, &p, 1, 2, 6, 6, &s);      /* ow */
	p.burst_segment = 2;
	run(&v, &p, 2, 20, 10, 10, &s);   /* the cry, and no please-stop */
	assert_int_equal(s.n, 2);
	said_at(&s, 0, VOICE_OW, 1);
	said_at(&s, 1, VOICE_CRY, 2);
	voice_init(&v);
	s.n = 0;
	p.burst_segment = -1;
	run(&v, &p, 0, 1, 1, 1, &s);
	p.torn_segment = 1;
	run(&v, &p, 1, 5, 1, 1, &s);
	assert_int_equal(s.n, 1);
	said_at(&s, 0, VOICE_CRY, 1);
}

/* Deep sedation: the rise says a groan at the highest step only; the
 * perforation a groan. */
static void quiet_when_deeply_sedated(void **state)
{
	struct endosim_patient_state p = patient();
	struct voice v;
	struct said s = { 0 };

	(void)state;
	p.sedation = ENDOSIM_SEDATION_DEEP;
	voice_init(&v);
	run(&v, &p, 0, 40, 0, 10, &s);
	assert_int_equal(s.n, 1);
	said_at(&s, 0, VOICE_GROAN, VOICE_STOP_AT / 0.25);
	p.torn_segment = 3;
	run(&v, &p, 40, 50, 10, 10, &s);
	assert_int_equal(s.n, 2);
	said_at(&s, 1, VOICE_GROAN, 40);
}

/* Muted: nothing, the perforation's cry neither; unmuted at the level
 * held, nothing kept back is said; the next crossing is. */
static void mute_mutes(void **state)
{
	struct endosim_patient_state p = patient();
	struct voice v;
	struct said s = { 0 };

	(void)state;
	voice_init(&v);
	voice_set_muted(&v, true);
	run(&v, &p, 0, 40, 0, 10, &s);
	p.burst_segment = 1;
	run(&v, &p, 40, 45, 10, 10, &s);
	assert_int_equal(s.n, 0);
	voice_set_muted(&v, false);
	p.burst_segment = -1;
	run(&v, &p, 45, 60, 4.5, 4.5, &s); /* above the groan's step */
	assert_int_equal(s.n, 0);
	run(&v, &p, 60, 70, 7.5, 7.5, &s);
	assert_int_equal(s.n, 1);
	said_at(&s, 0, VOICE_HURTS, 60);
}

/* The first state, a jump back or on in time (a replay's seek) and a
 * patient coming back are taken silently; without the patient, nothing. */
static void taken_as_is(void **state)
{
	struct endosim_patient_state p = patient();
	struct voice v;
	struct said s = { 0 };

	(void)state;
	voice_init(&v);
	p.burst_segment = 1;
	run(&v, &p, 0, 5, 9, 9, &s);      /* started in pain, perforated */
	p.burst_segment = -1;
	run(&v, &p, 5, 6, 0, 0, &s);
	run(&v, &p, 2, 3, 9, 9, &s);      /* back in time */
	run(&v, &p, 3, 4, 0, 0, &s);
	run(&v, &p, 10, 11, 9, 9, &s);    /* on by 6 s */
	p.enabled = 0;
	run(&v, &p, 11, 12, 0, 0, &s);
	p.enabled = 1;
	run(&v, &p, 12, 13, 9, 9, &s);
	assert_int_equal(s.n, 0);
	p.enabled = 0;
	run(&v, &p, 13, 30, 0, 10, &s);
	assert_int_equal(s.n, 0);
}

static void clip_names(void **state)
{
	(void)state;
	assert_string_equal(voice_clip_name(VOICE_GROAN), "groan");
	assert_string_equal(voice_clip_name(VOICE_OW), "ow");
	assert_string_equal(voice_clip_name(VOICE_HURTS), "hurts");
	assert_string_equal(voice_clip_name(VOICE_STOP), "stop");
	assert_string_equal(voice_clip_name(VOICE_CRY), "cry");
	assert_string_equal(voice_clip_name(VOICE_NONE), "none");
	assert_string_equal(voice_clip_name(VOICE_CLIPS), "none");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(each_step_at_its_crossing),
		cmocka_unit_test(held_level_does_not_repeat),
		cmocka_unit_test(rearmed_only_well_below),
		cmocka_unit_test(interval_between_clips),
		cmocka_unit_test(cry_at_perforation),
		cmocka_unit_test(quiet_when_deeply_sedated),
		cmocka_unit_test(mute_mutes),
		cmocka_unit_test(taken_as_is),
		cmocka_unit_test(clip_names),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
