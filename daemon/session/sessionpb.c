/* sessionpb.c - see sessionpb.h. */
#include "sessionpb.h"

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
		p[i] = &ep[i];
	}
	return k;
}

void sessionpb_from_metrics(struct sessionpb_metrics *out,
			    const struct metrics_result *r)
{
	Endosim__SessionMetrics *m = &out->msg;

	endosim__session_metrics__init(m);
	m->duration_s = r->duration_s;
	m->records = r->records;
	m->drops = r->drops;
	m->cecum_s = r->cecum_s;
	m->insertion_s = r->insertion_s;
	m->withdrawal_s = r->withdrawal_s;
	m->max_tip_s_m = r->max_tip_s_m;
	m->peak_insertion_n = r->peak_insertion_n;
	m->mean_insertion_n = r->mean_insertion_n;
	m->force_episodes = r->force_episodes;
	m->force_time_s = r->force_episode_s;
	m->loop_episodes = r->loop_episodes;
	m->longest_loop_s = r->longest_loop_s;
	m->largest_loop_m = r->largest_loop_m;
	m->discomfort = r->discomfort;
	m->lumen_lost_s = r->lumen_lost_s;
	m->mucosa_seen = r->mucosa_seen;
	m->polyps_seen = r->polyps_seen;
	m->polyps_total = r->polyps_total;
	m->n_force = episodes_out(out->force, out->force_p, r->force,
				  r->n_force);
	m->force = out->force_p;
	m->n_loops = episodes_out(out->loop, out->loop_p, r->loop, r->n_loop);
	m->loops = out->loop_p;
}

static uint32_t episodes_in(struct metrics_episode *out,
			    Endosim__MetricsEpisode *const *in, size_t n)
{
	size_t k = n < METRICS_MAX_EPISODES ? n : METRICS_MAX_EPISODES;

	for (size_t i = 0; i < k; i++) {
		out[i].start_s = in[i]->start_s;
		out[i].end_s = in[i]->end_s;
		out[i].peak = in[i]->peak;
	}
	return (uint32_t)k;
}

void sessionpb_to_metrics(const Endosim__SessionMetrics *in,
			  struct metrics_result *out)
{
	memset(out, 0, sizeof(*out));
	out->duration_s = in->duration_s;
	out->records = in->records;
	out->drops = in->drops;
	out->cecum_s = in->cecum_s;
	out->insertion_s = in->insertion_s;
	out->withdrawal_s = in->withdrawal_s;
	out->max_tip_s_m = in->max_tip_s_m;
	out->peak_insertion_n = in->peak_insertion_n;
	out->mean_insertion_n = in->mean_insertion_n;
	out->force_episodes = in->force_episodes;
	out->force_episode_s = in->force_time_s;
	out->loop_episodes = in->loop_episodes;
	out->longest_loop_s = in->longest_loop_s;
	out->largest_loop_m = in->largest_loop_m;
	out->discomfort = in->discomfort;
	out->lumen_lost_s = in->lumen_lost_s;
	out->mucosa_seen = in->mucosa_seen;
	out->polyps_seen = in->polyps_seen;
	out->polyps_total = in->polyps_total;
	out->n_force = episodes_in(out->force, in->force, in->n_force);
	out->n_loop = episodes_in(out->loop, in->loops, in->n_loops);
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
