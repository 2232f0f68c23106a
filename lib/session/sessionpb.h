/*
 * sessionpb.h - the training metrics (metrics.h struct metrics_result) on
 * the wire (endosim.proto SessionMetrics), both ways: endosimd fills
 * replies with it, endoctl reads them back into the same struct it fills
 * from a session file, so that both print alike. Likewise a session's
 * facts (sessiondir.h's entry as a SessionInfo), which endosimd lists and
 * endoctl reads from a file named by its path.
 *
 * No allocation: the message and its episodes live in struct
 * sessionpb_metrics, whose arrays the message points into. Any thread but
 * the force loop.
 */
#ifndef ENDOSIM_SESSIONPB_H
#define ENDOSIM_SESSIONPB_H

#include "proto/endosim.pb-c.h"
#include "session/metrics.h"
#include "session/sessiondir.h"

struct sessionpb_metrics {
	Endosim__SessionMetrics msg;
	Endosim__MetricsEpisode force[METRICS_MAX_EPISODES];
	Endosim__MetricsEpisode loop[METRICS_MAX_EPISODES];
	Endosim__MetricsEpisode pain[METRICS_MAX_EPISODES];
	Endosim__MetricsEpisode *force_p[METRICS_MAX_EPISODES];
	Endosim__MetricsEpisode *loop_p[METRICS_MAX_EPISODES];
	Endosim__MetricsEpisode *pain_p[METRICS_MAX_EPISODES];
	Endosim__PolypFate polyp[METRICS_MAX_POLYPS];
	Endosim__PolypFate *polyp_p[METRICS_MAX_POLYPS];
	double segment[ANATOMY_SEGMENTS];
	double cause[ENDOSIM_PAIN_CAUSES];
};

/* OUT->msg becomes R on the wire (its episodes and its polyps' fates);
 * it points into OUT. */
void sessionpb_from_metrics(struct sessionpb_metrics *out,
			    const struct metrics_result *r);

/* The measures alone, without their episodes (a listing of many
 * sessions: TraineeSessions), a tenth of the size. */
struct sessionpb_scalars {
	Endosim__SessionMetrics msg;
	double segment[ANATOMY_SEGMENTS];
	double cause[ENDOSIM_PAIN_CAUSES];
};

/* OUT->msg becomes R on the wire without its episodes; it points into
 * OUT. */
void sessionpb_from_scalars(struct sessionpb_scalars *out,
			    const struct metrics_result *r);

/* The inverse (episodes beyond METRICS_MAX_EPISODES are left out, and
 * polyps beyond METRICS_MAX_POLYPS). */
void sessionpb_to_metrics(const Endosim__SessionMetrics *in,
			  struct metrics_result *out);

/*
 * OUT, initialised, becomes what a listing knows of the session E (id,
 * trainee, case, start, size, ended); its strings point into E.
 */
void sessionpb_from_entry(Endosim__SessionInfo *out,
			  struct sessiondir_entry *e);

#endif
