/*
 * voice.h - what the patient says (issue 23): which clip to play, from
 * the pain level the daemon publishes (struct endosim_patient_state pain,
 * 0..10) as it changes over time.
 *
 * Four steps, each a clip, said when the level rises across it:
 *
 *   VOICE_GROAN_AT  4.0  a breath and a groan (the assessment's "in
 *                        pain" from 4)
 *   VOICE_OW_AT     5.5  "ow"
 *   VOICE_HURTS_AT  7.0  "that hurts"
 *   VOICE_STOP_AT   8.5  "please stop"
 *
 * and a cry when a wall is perforated (burst_segment or torn_segment
 * becomes >= 0), at once and once. A level that jumps across several
 * steps says only the highest. Hysteresis: a step once said stays said
 * until the level falls VOICE_REARM_DROP below it (a level held, or
 * wavering about a step, says nothing more), and no clip follows another
 * within VOICE_MIN_INTERVAL_S (a step crossed meanwhile is said when the
 * interval is over, if the level is still above it).
 *
 * Deep sedation (ENDOSIM_SEDATION_DEEP) makes the patient quiet: no
 * words, no cry; only a groan at the highest step (VOICE_STOP_AT) or at a
 * perforation. The lighter sedations change the level itself (the
 * daemon's pain model), not what the voice does with it.
 *
 * Muted, the voice follows the level as ever but says nothing: unmuted
 * later, it does not say what it kept back. The first state, a state
 * without the patient, and a jump in time (backwards, or more than
 * VOICE_JUMP_S on: a replay's seek, a stalled viewer) are taken as they
 * are, silently: the steps already crossed count as said.
 *
 * Pure computation, no allocation; any thread, one voice per thread.
 */
#ifndef ENDOVIEW_VOICE_H
#define ENDOVIEW_VOICE_H

#include <stdbool.h>

#include "proto/endosim_shm.h"

#define VOICE_GROAN_AT 4.0
#define VOICE_OW_AT 5.5
#define VOICE_HURTS_AT 7.0
#define VOICE_STOP_AT 8.5
#define VOICE_REARM_DROP 2.0     /* below a step, to say it again */
#define VOICE_MIN_INTERVAL_S 4.0 /* between two clips */
#define VOICE_JUMP_S 1.0         /* a longer step in time: taken as is */

enum voice_clip {
	VOICE_NONE = -1,
	VOICE_GROAN = 0,
	VOICE_OW,
	VOICE_HURTS,
	VOICE_STOP,
	VOICE_CRY,
	VOICE_CLIPS,
};

struct voice {
	int said;        /* the steps said (0..4), until the level falls */
	bool perforated; /* a perforation was cried out */
	bool started;
	bool muted;
	double t_s;      /* the last step's time */
	double last_s;   /* the last clip's */
};

/* A new voice (unmuted): all zero but for what voice_init() sets. */
void voice_init(struct voice *v);

/* Mute (true) or unmute V. */
void voice_set_muted(struct voice *v, bool muted);

/*
 * The clip to say now, at T_S (s, any clock that runs on: monotonic live,
 * the replay's clock in a replay), for the patient P; VOICE_NONE for
 * none.
 */
enum voice_clip voice_step(struct voice *v,
			   const struct endosim_patient_state *p, double t_s);

/* The clip's name, its file's without ".wav" ("groan", "ow", "hurts",
 * "stop", "cry"); "none" for VOICE_NONE or out of range. */
const char *voice_clip_name(enum voice_clip c);

#endif
