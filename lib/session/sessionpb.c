/* sessionpb.c - see sessionpb.h. */
#include "session/sessionpb.h"

#include <string.h>

static size_t episodes_out(Endosim__MetricsEpisode *ep,
			   Endosim__MetricsEpisode **p,
			   const struct metrics_episode *in, uint32_t n)
{
	size_t k = n < METRICS_MAX_EPISODES ? n : METRICS_MAX_EPISODES;

	for (size_t i = 0; i < k; i++) {
		endosim__metrics_episode__init(&ep[i]);
		ep[i].start_s = in[i].start_s;
		ep[i].end_s = in[i].end_s;
		ep[i].peak = in[i].peak;
		ep[i].cause = in[i].cause;
		ep[i].place = in[i].place;
		p[i] = &ep[i];
	}
	return k;
}

/* The measures on the wire (SessionMetrics' name, metrics_result's). */
#define METRICS_ON_WIRE(X)                                                   \
	X(duration_s, duration_s) X(records, records) X(drops, drops)        \
	X(cecum_s, cecum_s) X(insertion_s, insertion_s)                      \
	X(withdrawal_s, withdrawal_s) X(max_tip_s_m, max_tip_s_m)            \
	X(peak_insertion_n, peak_insertion_n)                                \
	X(mean_insertion_n, mean_insertion_n)                                \
	X(force_episodes, force_episodes) X(force_time_s, force_episode_s)   \
	X(loop_episodes, loop_episodes) X(longest_loop_s, longest_loop_s)    \
	X(largest_loop_m, largest_loop_m)                                    \
	X(lumen_lost_s, lumen_lost_s) X(mucosa_seen, mucosa_seen)            \
	X(polyps_seen, polyps_seen) X(polyps_total, polyps_total)            \
	X(shaft_in_m, shaft_in_m) X(tip_in_m, tip_in_m)                      \
	X(chase_efficiency, chase_efficiency) X(shaft_idle_m, shaft_idle_m)  \
	X(looped_s, loop_s) X(retraction_m, retraction_m)                      \
	X(tip_retraction_m, tip_retraction_m)                                \
	X(retraction_efficiency, retraction_efficiency)                      \
	X(clear_view, clear_view) X(lost_views, lost_views)                  \
	X(mucosa_per_min, mucosa_per_min)                                    \
	X(pain_share, pain_share) X(peak_pain, peak_pain)                    \
	X(pain_episodes, pain_episodes) X(gloucester, gloucester)            \
	X(gas_used_l, gas_used_l)                                            \
	X(peak_gas_pressure_pa, peak_gas_pressure_pa)                        \
	X(position_changes, position_changes) X(hand_uses, hand_uses)        \
	X(perforations, perforations)                                        \
	X(polyps_resected, polyps_resected) X(polyps_partly, polyps_partly)  \
	X(polyps_retrieved, polyps_retrieved) X(resection_s, resection_s)    \
	X(cautery_s, cautery_s) X(tool_injuries, tool_injuries)              \
	X(biopsies, biopsies) X(clips, clips)                                \
	X(bleeds, bleeds) X(bleeds_clipped, bleeds_clipped)                  \
	X(bleed_control_s, bleed_control_s)

/* R's measures into M, its segments' into SEGMENT, its time in pain by
 * cause into CAUSE; no episodes. */
static void scalars_out(Endosim__SessionMetrics *m, double *segment,
			double *cause, const struct metrics_result *r)
{
	endosim__session_metrics__init(m);
#define TO_PB(pb, c) m->pb = r->c;
	METRICS_ON_WIRE(TO_PB)
#undef TO_PB
	memcpy(segment, r->mucosa_segment, ANATOMY_SEGMENTS * sizeof(double));
	m->n_mucosa_segment = ANATOMY_SEGMENTS;
	m->mucosa_segment = segment;
	memcpy(cause, r->pain_cause_s, ENDOSIM_PAIN_CAUSES * sizeof(double));
	m->n_pain_cause_s = ENDOSIM_PAIN_CAUSES;
	m->pain_cause_s = cause;
}

static size_t polyps_out(Endosim__PolypFate *pf, Endosim__PolypFate **p,
			 const struct metrics_result *r)
{
	size_t k = r->n_polyp < METRICS_MAX_POLYPS ? r->n_polyp
						   : METRICS_MAX_POLYPS;

	for (size_t i = 0; i < k; i++) {
		endosim__polyp_fate__init(&pf[i]);
		pf[i].fate = r->polyp[i].fate;
		pf[i].start_s = r->polyp[i].start_s;
		pf[i].cut_s = r->polyp[i].cut_s;
		pf[i].cautery_s = r->polyp[i].cautery_s;
		pf[i].bites = r->polyp[i].bites;
		p[i] = &pf[i];
	}
	return k;
}

void sessionpb_from_metrics(struct sessionpb_metrics *out,
			    const struct metrics_result *r)
{
	Endosim__SessionMetrics *m = &out->msg;

	scalars_out(m, out->segment, out->cause, r);
	m->n_force = episodes_out(out->force, out->force_p, r->force,
				  r->n_force);
	m->force = out->force_p;
	m->n_loops = episodes_out(out->loop, out->loop_p, r->loop, r->n_loop);
	m->loops = out->loop_p;
	m->n_pain = episodes_out(out->pain, out->pain_p, r->pain, r->n_pain);
	m->pain = out->pain_p;
	m->n_polyps = polyps_out(out->polyp, out->polyp_p, r);
	m->polyps = out->polyp_p;
}

void sessionpb_from_scalars(struct sessionpb_scalars *out,
			    const struct metrics_result *r)
{
	scalars_out(&out->msg, out->segment, out->cause, r);
}

static uint32_t episodes_in(struct metrics_episode *out,
			    Endosim__MetricsEpisode *const *in, size_t n)
{
	size_t k = n < METRICS_MAX_EPISODES ? n : METRICS_MAX_EPISODES;

	for (size_t i = 0; i < k; i++) {
		out[i].start_s = in[i]->start_s;
		out[i].end_s = in[i]->end_s;
		out[i].peak = in[i]->peak;
		out[i].cause = in[i]->cause;
		out[i].place = in[i]->place;
	}
	return (uint32_t)k;
}

void sessionpb_to_metrics(const Endosim__SessionMetrics *in,
			  struct metrics_result *out)
{
	memset(out, 0, sizeof(*out));
#define FROM_PB(pb, c) out->c = in->pb;
	METRICS_ON_WIRE(FROM_PB)
#undef FROM_PB
	out->n_force = episodes_in(out->force, in->force, in->n_force);
	out->n_loop = episodes_in(out->loop, in->loops, in->n_loops);
	out->n_pain = episodes_in(out->pain, in->pain, in->n_pain);
	for (size_t i = 0; i < in->n_polyps && i < METRICS_MAX_POLYPS; i++) {
		const Endosim__PolypFate *p = in->polyps[i];

		out->polyp[i] = (struct metrics_polyp){
			.fate = p->fate < METRICS_FATES ? p->fate : 0,
			.start_s = p->start_s, .cut_s = p->cut_s,
			.cautery_s = p->cautery_s, .bites = p->bites };
		out->n_polyp = (uint32_t)i + 1;
	}
	for (size_t i = 0; i < in->n_pain_cause_s && i < ENDOSIM_PAIN_CAUSES;
	     i++) {
		out->pain_cause_s[i] = in->pain_cause_s[i];
	}
	for (size_t i = 0; i < in->n_mucosa_segment && i < ANATOMY_SEGMENTS;
	     i++) {
		out->mucosa_segment[i] = in->mucosa_segment[i];
	}
}

void sessionpb_from_entry(Endosim__SessionInfo *out,
			  struct sessiondir_entry *e)
{
	endosim__session_info__init(out);
	out->id = e->id;
	out->trainee = e->trainee;
	out->case_name = e->case_name;
	out->started = e->started;
	out->bytes = e->bytes;
	out->ended = e->ended;
}
