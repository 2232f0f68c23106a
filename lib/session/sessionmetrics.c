/* sessionmetrics.c - see sessionmetrics.h. */
#include "session/sessionmetrics.h"

#include <errno.h>
#include <stdio.h>

#include "model/colon.h"
#include "session/sessioninputs.h"

/* The colon of F's CASE frame, its configuration, its header. */
static struct colon *session_colon(const struct session_file *f, char *err,
				   size_t errsize)
{
	struct config cfg;

	sessioninputs_config(f, &cfg, err, errsize);
	return sessioninputs_colon(f, &cfg, err, errsize);
}

/*
 * F's records, with its events in time order, through new metrics with P
 * on F's colon (*C, the caller's to destroy after the metrics; NULL
 * without a case, ERR saying why). NULL on ENOMEM, with ERR.
 */
static struct metrics *metrics_of(const struct session_file *f,
				  const struct metrics_params *p,
				  struct colon **c, char *err, size_t errsize)
{
	struct metrics *m;
	size_t e = 0;

	*c = f->header ? session_colon(f, err, errsize) : NULL;
	if (errsize && f->header && !*c) {
		/* the line says why; the metrics go on without the colon */
	} else if (errsize) {
		err[0] = '\0';
	}
	m = metrics_create(*c, p);
	if (!m) {
		colon_destroy(*c);
		*c = NULL;
		snprintf(err, errsize, "metrics: out of memory");
		return NULL;
	}
	for (size_t i = 0; i < f->n_records; i++) {
		for (; e < f->n_events &&
		       f->events[e].ev.stamp_ns <= f->records[i].stamp_ns; e++) {
			metrics_event(m, &f->events[e].ev, f->events[e].text);
		}
		metrics_record(m, &f->records[i]);
	}
	for (; e < f->n_events; e++) {
		metrics_event(m, &f->events[e].ev, f->events[e].text);
	}
	return m;
}

int sessionmetrics_compute(const struct session_file *f,
			   const struct metrics_params *p,
			   struct metrics_result *out, char *err,
			   size_t errsize)
{
	struct colon *c;
	struct metrics *m = metrics_of(f, p, &c, err, errsize);

	if (!m) {
		return -ENOMEM;
	}
	metrics_result(m, out);
	metrics_destroy(m);
	colon_destroy(c);
	return 0;
}

int sessionmetrics_map(const struct session_file *f, struct metrics_map *map,
		       struct metrics_along *along)
{
	struct metrics_params p;
	struct colon *c;
	struct metrics *m;
	char err[256];

	sessioninputs_file_metrics_params(f, &p);
	m = metrics_of(f, &p, &c, err, sizeof(err));
	if (!m) {
		return -ENOMEM;
	}
	if (map) {
		metrics_map(m, map);
	}
	if (along) {
		metrics_along(m, along);
	}
	metrics_destroy(m);
	colon_destroy(c);
	return 0;
}
