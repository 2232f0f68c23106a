/* voice.c - see voice.h. */
#include "viewer/voice.h"

#include <math.h>

static const double step_at[] = {
	VOICE_GROAN_AT, VOICE_OW_AT, VOICE_HURTS_AT, VOICE_STOP_AT,
};
#define STEPS ((int)(sizeof(step_at) / sizeof(step_at[0])))

static const char *const clip_name[VOICE_CLIPS] = {
	[VOICE_GROAN] = "groan", [VOICE_OW] = "ow", [VOICE_HURTS] = "hurts",
	[VOICE_STOP] = "stop", [VOICE_CRY] = "cry",
};

/* The steps LEVEL has reached, less DROP: 0..STEPS (NaN: 0). */
static int steps_of(double level, double drop)
{
	int n = 0;

	while (n < STEPS && level >= step_at[n] - drop) {
		n++;
	}
	return n;
}

void voice_init(struct voice *v)
{
	*v = (struct voice){ .last_s = -INFINITY };
}

void voice_set_muted(struct voice *v, bool muted)
{
	v->muted = muted;
}

/* CLIP said at T_S (VOICE_NONE: nothing), unless muted. */
static enum voice_clip say(struct voice *v, enum voice_clip clip, double t_s)
{
	if (clip == VOICE_NONE) {
		return VOICE_NONE;
	}
	v->last_s = t_s;
	return v->muted ? VOICE_NONE : clip;
}

enum voice_clip voice_step(struct voice *v,
			   const struct endosim_patient_state *p, double t_s)
{
	bool perforated = p->burst_segment >= 0 || p->torn_segment >= 0;
	bool deep = p->sedation == ENDOSIM_SEDATION_DEEP;
	int steps = steps_of(p->pain, 0), armed;
	bool fresh = !v->started || !(t_s >= v->t_s) ||
		     t_s - v->t_s > VOICE_JUMP_S;

	v->started = p->enabled;
	v->t_s = t_s;
	if (fresh || !p->enabled) {
		v->said = steps;
		v->perforated = perforated;
		v->last_s = -INFINITY;
		return VOICE_NONE;
	}
	armed = steps_of(p->pain, VOICE_REARM_DROP);
	v->said = v->said < armed ? v->said : armed;
	if (perforated && !v->perforated) {
		v->perforated = true;
		v->said = STEPS;
		return say(v, deep ? VOICE_GROAN : VOICE_CRY, t_s);
	}
	v->perforated = perforated;
	if (steps <= v->said || t_s - v->last_s < VOICE_MIN_INTERVAL_S) {
		return VOICE_NONE;
	}
	v->said = steps;
	if (deep) {
		return say(v, steps == STEPS ? VOICE_GROAN : VOICE_NONE, t_s);
	}
	return say(v, (enum voice_clip)(VOICE_GROAN + steps - 1), t_s);
}

const char *voice_clip_name(enum voice_clip c)
{
	return c >= 0 && c < VOICE_CLIPS ? clip_name[c] : "none";
}
