/* therapy.c - see therapy.h. */
#include "session/therapy.h"

#include <string.h>

void therapy_init(struct therapy *th)
{
	memset(th, 0, sizeof(*th));
	th->captured = -1;
	for (int i = 0; i < METRICS_MAX_POLYPS; i++) {
		th->polyp[i].start_s = -1;
		th->polyp[i].cut_s = -1;
		th->bleed_s[i] = -1;
	}
}

/* Polyp I's entry, NULL for none (-1) or beyond the case's most. */
static struct metrics_polyp *polyp_at(struct therapy *th, int32_t i)
{
	if (i < 0 || i >= METRICS_MAX_POLYPS) {
		return NULL;
	}
	if ((uint32_t)i >= th->polyps) {
		th->polyps = (uint32_t)i + 1;
	}
	return &th->polyp[i];
}

/* Polyp I's bleeding (EV: its BLEED, CLIPPED or STOPPED) at T. */
static void bleeding(struct therapy *th, int32_t i, uint32_t ev, double t)
{
	if (ev & ENDOSIM_TOOL_BLEED) {
		th->bleeds++;
		th->bleed_s[i] = t;
	}
	if ((ev & (ENDOSIM_TOOL_CLIPPED | ENDOSIM_TOOL_STOPPED)) &&
	    th->bleed_s[i] >= 0) {
		th->clipped += !!(ev & ENDOSIM_TOOL_CLIPPED);
		th->controlled++;
		th->control_s += t - th->bleed_s[i];
		th->bleed_s[i] = -1;
	}
}

/* R's events at T. */
static void events(struct therapy *th, const struct session_record *r,
		   double t)
{
	struct metrics_polyp *p = polyp_at(th, r->tool_event_polyp);
	uint32_t ev = r->tool_events;

	th->injuries += !!(ev & ENDOSIM_TOOL_INJURY);
	th->bites += !!(ev & ENDOSIM_TOOL_BITE);
	th->clips += !!(ev & ENDOSIM_TOOL_CLIP_PLACED);
	if (!p) {
		return;
	}
	if (p->start_s < 0 && (ev & (ENDOSIM_TOOL_LIFT | ENDOSIM_TOOL_CAPTURE |
				     ENDOSIM_TOOL_BITE | ENDOSIM_TOOL_CUT))) {
		p->start_s = t;
	}
	p->bites += !!(ev & ENDOSIM_TOOL_BITE);
	if ((ev & ENDOSIM_TOOL_CUT) && p->cut_s < 0) {
		p->cut_s = t;
	}
	th->retrieved[r->tool_event_polyp] |= !!(ev & ENDOSIM_TOOL_RETRIEVE);
	bleeding(th, r->tool_event_polyp, ev, t);
}

void therapy_record(struct therapy *th, const struct session_record *r,
		    double t, double dt)
{
	struct metrics_polyp *held;

	if (th->have_prev && th->pedal) {
		th->pedal_s += dt;
		held = polyp_at(th, th->captured);
		if (held) {
			held->cautery_s += dt;
		}
	}
	th->tooled |= r->tool_kind != ENDOSIM_TOOL_NONE;
	events(th, r, t);
	th->have_prev = true;
	th->pedal = r->tool_pedal != 0;
	th->captured = r->tool_captured;
}

/* P's fate at the end, RETRIEVED whether it was sucked out. */
static uint32_t fate(const struct metrics_polyp *p, bool retrieved)
{
	if (p->cut_s >= 0) {
		return retrieved ? METRICS_FATE_RETRIEVED
				 : METRICS_FATE_COMPLETE;
	}
	return p->bites || p->cautery_s > 0 ? METRICS_FATE_PARTLY
					    : METRICS_FATE_LEFT;
}

void therapy_result(const struct therapy *th, uint32_t polyps_total,
		    struct metrics_result *out)
{
	uint32_t n = th->polyps > polyps_total ? th->polyps : polyps_total;
	double sum_s = 0;

	out->cautery_s = th->pedal_s;
	out->tool_injuries = th->injuries;
	out->biopsies = th->bites;
	out->clips = th->clips;
	out->bleeds = th->bleeds;
	out->bleeds_clipped = th->clipped;
	out->bleed_control_s = th->controlled ? th->control_s / th->controlled
					      : 0;
	out->n_polyp = th->tooled || th->polyps ? n : 0;
	if (out->n_polyp > METRICS_MAX_POLYPS) {
		out->n_polyp = METRICS_MAX_POLYPS;
	}
	for (uint32_t i = 0; i < out->n_polyp; i++) {
		struct metrics_polyp *p = &out->polyp[i];

		*p = th->polyp[i];
		p->fate = fate(p, th->retrieved[i]);
		out->polyps_partly += p->fate == METRICS_FATE_PARTLY;
		out->polyps_retrieved += p->fate == METRICS_FATE_RETRIEVED;
		if (p->fate >= METRICS_FATE_COMPLETE) {
			out->polyps_resected++;
			sum_s += p->cut_s - p->start_s;
		}
	}
	out->resection_s = out->polyps_resected ?
			   sum_s / out->polyps_resected : 0;
}

const char *therapy_fate_name(uint32_t fate)
{
	static const char *const names[METRICS_FATES] = {
		"left", "partly", "complete", "retrieved",
	};

	return fate < METRICS_FATES ? names[fate] : "?";
}
