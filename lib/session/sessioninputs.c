/* sessioninputs.c - see sessioninputs.h. */
#include "session/sessioninputs.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conf/cases.h"

int sessioninputs_config(const struct session_file *f, struct config *cfg,
			 char *err, size_t errsize)
{
	FILE *in;
	int r;

	config_defaults(cfg);
	if (!f->config || !*f->config) {
		return 0;
	}
	in = fmemopen(f->config, strlen(f->config), "r");
	if (!in) {
		snprintf(err, errsize, "%s", strerror(errno));
		return -EINVAL;
	}
	r = config_load_stream(cfg, in, "CONFIG", err, errsize);
	fclose(in);
	if (r) {
		config_defaults(cfg);
		return -EINVAL;
	}
	return 0;
}

double sessioninputs_loop_threshold_m(double configured_m, bool rod)
{
	if (configured_m > 0) {
		return configured_m;
	}
	return rod ? SESSION_LOOP_THRESHOLD_ROD_M
		   : SESSION_LOOP_THRESHOLD_PAPER_M;
}

void sessioninputs_metrics_params(const struct config *cfg,
				  struct metrics_params *p)
{
	metrics_params_default(p);
	p->force_threshold_n = cfg->session.force_threshold_n;
	p->loop_threshold_m = sessioninputs_loop_threshold_m(
		cfg->session.loop_threshold_m,
		cfg->haptics.model == HAPTICS_MODEL_ROD);
	p->view_distance_m = cfg->session.view_distance_m;
	p->fov_rad = cfg->session.fov_deg * M_PI / 180;
	p->view_rate_hz = cfg->session.view_rate_hz;
	p->pain_level = cfg->session.pain_level;
}

void sessioninputs_file_metrics_params(const struct session_file *f,
				       struct metrics_params *p)
{
	struct config cfg;
	char err[256];

	sessioninputs_config(f, &cfg, err, sizeof(err));
	if (f->n_records) {
		cfg.haptics.model = f->records[0].model == ENDOSIM_MODEL_ROD
					    ? HAPTICS_MODEL_ROD
					    : HAPTICS_MODEL_PAPER;
	}
	sessioninputs_metrics_params(&cfg, p);
}

int sessioninputs_colon_params(const struct session_file *f,
			       const struct config *cfg,
			       struct colon_params *p, char *err,
			       size_t errsize)
{
	char v[64];

	cases_colon_params(cfg, p);
	if (!session_text_get(f->header, "step_m", v, sizeof(v))) {
		p->step_m = strtod(v, NULL);
	}
	if (!session_text_get(f->header, "ring_vertices", v, sizeof(v))) {
		p->ring_vertices = (uint32_t)strtoul(v, NULL, 10);
	}
	if (!session_text_get(f->header, "segment_m", v, sizeof(v))) {
		p->segment_m = strtod(v, NULL);
	}
	if (!(p->step_m > 0) || !(p->segment_m > 0) || !p->ring_vertices) {
		snprintf(err, errsize, "its header's resolution does not add up");
		return -EINVAL;
	}
	return 0;
}

int sessioninputs_anatomy(const struct session_file *f, struct anatomy *a,
			  char *err, size_t errsize)
{
	if (!f->case_text || !*f->case_text) {
		snprintf(err, errsize, "the session has no case");
		return -ENOENT;
	}
	return anatomy_parse(a, f->case_text, "CASE", err, errsize);
}

struct colon *sessioninputs_colon(const struct session_file *f,
				  const struct config *cfg, char *err,
				  size_t errsize)
{
	struct colon_params p;
	struct anatomy a;

	if (sessioninputs_anatomy(f, &a, err, errsize) ||
	    sessioninputs_colon_params(f, cfg, &p, err, errsize)) {
		return NULL;
	}
	return colon_create(&a, &p, err, errsize);
}

struct colon *sessioninputs_file_colon(const struct session_file *f,
				       char *err, size_t errsize)
{
	struct config cfg;
	char why[256];

	sessioninputs_config(f, &cfg, why, sizeof(why));
	return sessioninputs_colon(f, &cfg, err, errsize);
}

int sessioninputs_scope(const struct session_file *f, struct scope_params *p,
			double *radius_m, char *err, size_t errsize)
{
	struct config cfg;
	int r = sessioninputs_config(f, &cfg, err, errsize);

	cases_scope_params(&cfg, p);
	*radius_m = cfg.haptics.scope_radius_m;
	return r;
}

void sessioninputs_tool(const struct session_file *f, struct tool_params *p)
{
	struct config cfg;
	char err[256];

	(void)sessioninputs_config(f, &cfg, err, sizeof(err));
	cases_tool_params(&cfg, p);
}
