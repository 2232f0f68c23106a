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

/* A test's patient, its voice and what it said. */
struct fixture {
	struct endosim_patient_state p;
	struct voice v;
	struct said s;
};

/* A fresh fixture: the patient enabled, moderately sedated, nothing
 * torn; the voice new. */
static int fresh(void **state)
{
	static struct fixture f;

	f = (struct fixture){
		.p = { .enabled = 1, .sedation = ENDOSIM_SEDATION_MODERATE,
		       .burst_segment = -1, .torn_segment = -1,
		       .pain_place = -1 },
	};
	voice_init(&f.v);
	*state = &f;
	return 0;
}

/* Frames from T0 to T1 s with the level going linearly from L0 to L1;
 * what the voice said into F's. */
static void run(struct fixture *f, double t0, double t1, double l0,
		double l1)
{
	struct said *s = &f->s;

	for (double t = t0; t < t1 - 1e-9; t += FRAME_S) {
		enum voice_clip c;

		f->p.pain = l0 + (l1 - l0) * (t - t0) / (t1 - t0);
		c = voice_step(&f->v, &f->p, t);
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
	struct fixture *f = *state;

	run(f, 0, 40, 0, 10);
	assert_int_equal(f->s.n, 4);
	said_at(&f->s, 0, VOICE_GROAN, VOICE_GROAN_AT / 0.25);
	said_at(&f->s, 1, VOICE_OW, VOICE_OW_AT / 0.25);
	said_at(&f->s, 2, VOICE_HURTS, VOICE_HURTS_AT / 0.25);
	said_at(&f->s, 3, VOICE_STOP, VOICE_STOP_AT / 0.25);
}

/* A jump across three steps says the highest only; held, or wavering
 * about a step, nothing more for a minute. */
static void held_level_does_not_repeat(void **state)
{
	struct fixture *f = *state;

	run(f, 0, 1, 0, 0);
	run(f, 1, 61, 7.5, 7.5);
	assert_int_equal(f->s.n, 1);
	said_at(&f->s, 0, VOICE_HURTS, 1);
	for (int k = 0; k < 30; k++) { /* 6.9 to 7.1 and back, each 2 s */
		run(f, 61 + 2 * k, 62 + 2 * k, 7.1, 6.9);
		run(f, 62 + 2 * k, 63 + 2 * k, 6.9, 7.1);
	}
	assert_int_equal(f->s.n, 1);
}

/* Said again only once the level fell VOICE_REARM_DROP below the step. */
static void rearmed_only_well_below(void **state)
{
	struct fixture *f = *state;

	run(f, 0, 1, 0, 0);
	run(f, 1, 10, 6, 6); /* ow */
	run(f, 10, 20, VOICE_OW_AT - VOICE_REARM_DROP + 0.1,
	    VOICE_OW_AT - VOICE_REARM_DROP + 0.1);
	run(f, 20, 30, 6, 6); /* not well below: nothing */
	assert_int_equal(f->s.n, 1);
	run(f, 30, 40, VOICE_OW_AT - VOICE_REARM_DROP - 0.1,
	    VOICE_OW_AT - VOICE_REARM_DROP - 0.1);
	run(f, 40, 50, 6, 6); /* ow again */
	assert_int_equal(f->s.n, 2);
	said_at(&f->s, 0, VOICE_OW, 1);
	said_at(&f->s, 1, VOICE_OW, 40);
}

/* A step crossed within the interval waits for its end; one the level
 * left meanwhile is not said. */
static void interval_between_clips(void **state)
{
	struct fixture *f = *state;

	run(f, 0, 1, 0, 0);
	run(f, 1, 2, 4.5, 4.5);  /* groan */
	run(f, 2, 10, 9, 9);     /* please stop, at 1 + 4 s */
	assert_int_equal(f->s.n, 2);
	said_at(&f->s, 0, VOICE_GROAN, 1);
	said_at(&f->s, 1, VOICE_STOP, 1 + VOICE_MIN_INTERVAL_S);
	run(f, 10, 20, 0, 0);
	run(f, 20, 21, 6, 6);    /* ow */
	run(f, 21, 22, 0, 0);    /* gone before the interval ends */
	run(f, 22, 23, 0, 0);
	run(f, 23, 30, 4.8, 4.8); /* 4.8: groan re-armed at 2.0,
					      said at 24 s */
	assert_int_equal(f->s.n, 4);
	said_at(&f->s, 2, VOICE_OW, 20);
	said_at(&f->s, 3, VOICE_GROAN, 20 + VOICE_MIN_INTERVAL_S);
}

/* The cry at once (within the interval), once; by the tip's tear too. */
static void cry_at_perforation(void **state)
{
	struct fixture *f = *state;

	run(f, 0, 1, 0, 0);
	run(f, 1, 2, 6, 6);      /* ow */
	f->p.burst_segment = 2;
	run(f, 2, 20, 10, 10);   /* the cry, and no please-stop */
	assert_int_equal(f->s.n, 2);
	said_at(&f->s, 0, VOICE_OW, 1);
	said_at(&f->s, 1, VOICE_CRY, 2);
	fresh(state); /* a new patient */
	f = *state;
	run(f, 0, 1, 1, 1);
	f->p.torn_segment = 1;
	run(f, 1, 5, 1, 1);
	assert_int_equal(f->s.n, 1);
	said_at(&f->s, 0, VOICE_CRY, 1);
}

/* Deep sedation: the rise says a groan at the highest step only; the
 * perforation a groan. */
static void quiet_when_deeply_sedated(void **state)
{
	struct fixture *f = *state;

	f->p.sedation = ENDOSIM_SEDATION_DEEP;
	run(f, 0, 40, 0, 10);
	assert_int_equal(f->s.n, 1);
	said_at(&f->s, 0, VOICE_GROAN, VOICE_STOP_AT / 0.25);
	f->p.torn_segment = 3;
	run(f, 40, 50, 10, 10);
	assert_int_equal(f->s.n, 2);
	said_at(&f->s, 1, VOICE_GROAN, 40);
}

/* Muted: nothing, the perforation's cry neither; unmuted at the level
 * held, nothing kept back is said; the next crossing is. */
static void mute_mutes(void **state)
{
	struct fixture *f = *state;

	voice_set_muted(&f->v, true);
	run(f, 0, 40, 0, 10);
	f->p.burst_segment = 1;
	run(f, 40, 45, 10, 10);
	assert_int_equal(f->s.n, 0);
	voice_set_muted(&f->v, false);
	f->p.burst_segment = -1;
	run(f, 45, 60, 4.5, 4.5); /* above the groan's step */
	assert_int_equal(f->s.n, 0);
	run(f, 60, 70, 7.5, 7.5);
	assert_int_equal(f->s.n, 1);
	said_at(&f->s, 0, VOICE_HURTS, 60);
}

/* The first state, a jump back or on in time (a replay's seek) and a
 * patient coming back are taken silently; without the patient, nothing. */
static void taken_as_is(void **state)
{
	struct fixture *f = *state;

	f->p.burst_segment = 1;
	run(f, 0, 5, 9, 9);      /* started in pain, perforated */
	f->p.burst_segment = -1;
	run(f, 5, 6, 0, 0);
	run(f, 2, 3, 9, 9);      /* back in time */
	run(f, 3, 4, 0, 0);
	run(f, 10, 11, 9, 9);    /* on by 6 s */
	f->p.enabled = 0;
	run(f, 11, 12, 0, 0);
	f->p.enabled = 1;
	run(f, 12, 13, 9, 9);
	assert_int_equal(f->s.n, 0);
	f->p.enabled = 0;
	run(f, 13, 30, 0, 10);
	assert_int_equal(f->s.n, 0);
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
		cmocka_unit_test_setup(each_step_at_its_crossing, fresh),
		cmocka_unit_test_setup(held_level_does_not_repeat, fresh),
		cmocka_unit_test_setup(rearmed_only_well_below, fresh),
		cmocka_unit_test_setup(interval_between_clips, fresh),
		cmocka_unit_test_setup(cry_at_perforation, fresh),
		cmocka_unit_test_setup(quiet_when_deeply_sedated, fresh),
		cmocka_unit_test_setup(mute_mutes, fresh),
		cmocka_unit_test_setup(taken_as_is, fresh),
		cmocka_unit_test(clip_names),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
