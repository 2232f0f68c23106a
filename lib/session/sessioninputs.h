/*
 * sessioninputs.h - the one reader of what a session was recorded with:
 * its CONFIG frame (the configuration as --print-config printed it), its
 * CASE frame (the case file's text) and its header's colon resolution,
 * and what they make: the configuration, the colon's, the scope's and the
 * metrics' parameters, the colon. The recorder (the live configuration), the
 * report, endoctl's views and the viewer's replay all take them here.
 *
 * Any thread but the force loop; the colon is allocated (~50 ms).
 */
#ifndef ENDOSIM_SESSIONINPUTS_H
#define ENDOSIM_SESSIONINPUTS_H

#include <stdbool.h>
#include <stddef.h>

#include "model/anatomy.h"
#include "model/colon.h"
#include "model/scope.h"
#include "model/tool.h"
#include "conf/config.h"
#include "session/metrics.h"
#include "proto/session_file.h"

/*
 * F's configuration into CFG: the defaults overridden by its CONFIG frame.
 * 0 (also for a file without one: the defaults), or -EINVAL with the line
 * that does not parse in ERR and CFG the defaults.
 */
int sessioninputs_config(const struct session_file *f, struct config *cfg,
			 char *err, size_t errsize);

/* A loop, when [session] loop_threshold_m is 0: by the haptics' model. The
 * rod model moves the sigmoid a centimetre or two on an ordinary insertion
 * (the tube takes the outside of its bends); its loops are larger. */
#define SESSION_LOOP_THRESHOLD_PAPER_M METRICS_DEFAULT_LOOP_THRESHOLD_M
#define SESSION_LOOP_THRESHOLD_ROD_M 0.03

/*
 * The one home of the loop threshold (m) that the metrics count loops
 * from, and so the report, endoview's loop warning and docs/METRICS.md:
 * CONFIGURED_M ([session] loop_threshold_m) when above 0, else the
 * model's (ROD: the rod model ran, else the paper's).
 */
double sessioninputs_loop_threshold_m(double configured_m, bool rod);

/* The metrics' parameters ([session] thresholds) CFG sets, the loop's
 * by CFG's model. */
void sessioninputs_metrics_params(const struct config *cfg,
				  struct metrics_params *p);

/* The metrics' parameters the session F was recorded with: its CONFIG
 * frame's (the defaults where it has none), the loop's by the model its
 * records say ran (its CONFIG's without a record). */
void sessioninputs_file_metrics_params(const struct session_file *f,
				       struct metrics_params *p);

/*
 * The colon's parameters: CFG's ([case] resolution, the tip's radius),
 * the resolution in F's header over them. 0, or -EINVAL when the header's
 * resolution does not add up.
 */
int sessioninputs_colon_params(const struct session_file *f,
			       const struct config *cfg,
			       struct colon_params *p, char *err,
			       size_t errsize);

/*
 * The anatomy of F's CASE frame (anatomy_parse()): 0, -ENOENT when F has
 * no case, or -EINVAL with one line in ERR.
 */
int sessioninputs_anatomy(const struct session_file *f, struct anatomy *a,
			  char *err, size_t errsize);

/*
 * The colon of F's CASE frame with the parameters above; NULL with why in
 * ERR (no case recorded, a case or a resolution that does not parse).
 */
struct colon *sessioninputs_colon(const struct session_file *f,
				  const struct config *cfg, char *err,
				  size_t errsize);

/* The same with F's own configuration (sessioninputs_config()'s). */
struct colon *sessioninputs_file_colon(const struct session_file *f,
				       char *err, size_t errsize);

/*
 * The scope F was recorded with: its configuration's [scope] in P, and
 * [haptics] scope_radius_m in *RADIUS_M. 0, or -EINVAL with the line of its
 * CONFIG frame that does not parse in ERR and the defaults in P and
 * *RADIUS_M.
 */
int sessioninputs_scope(const struct session_file *f, struct scope_params *p,
			double *radius_m, char *err, size_t errsize);

/*
 * The tools F was recorded with: its configuration's [tool] (where the
 * working channel opens on the tip) in P; the defaults where its CONFIG
 * frame does not parse.
 */
void sessioninputs_tool(const struct session_file *f, struct tool_params *p);

#endif
