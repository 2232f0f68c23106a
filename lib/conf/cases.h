/*
 * cases.h - which colon the daemon runs: the case the configuration names
 * ([case] file, or [case] directory/name.case) or one loaded by name, and
 * the list of case files in [case] directory; the model's parameters as the
 * configuration sets them (the model itself knows nothing of it).
 *
 * A case name is letters, digits, '-' and '_' (config_case_name_ok()), so
 * a name never leaves the directory; NAME.case must call itself NAME. A [case] file ending in ".obj" is an
 * imported mesh (colon_import()) with [case] centreline_file.
 *
 * The loaders read files and build the model (~50 ms at the default
 * resolution, ~0.5 s at 2 million triangles): any thread but the force
 * loop (endosimd's main and control threads, the viewer's replay, the
 * tools). Thread-safe (no shared state).
 */
#ifndef ENDOSIM_CASES_H
#define ENDOSIM_CASES_H

#include <stddef.h>

#include "model/anatomy.h"
#include "model/colon.h"
#include "conf/config.h"
#include "model/haptics.h"
#include "model/scope.h"

struct cases_entry {
	char name[ANATOMY_NAME];
	char description[ANATOMY_TEXT];
};

/*
 * The model as the configuration sets it: the colon's resolution and
 * contact radius; the scope's [scope]; the haptics' [haptics], with the
 * scope's and the wheels' limits and which axes are drives'. Any thread.
 */
void cases_colon_params(const struct config *cfg, struct colon_params *p);
void cases_scope_params(const struct config *cfg, struct scope_params *p);
void cases_haptics_params(const struct config *cfg,
			  struct haptics_params *p);
void cases_rod_params(const struct config *cfg, struct rodscope_params *p);
void cases_patient_params(const struct config *cfg,
			  struct patient_params *p);
/* The tools' ([tool]; the rest tool.h's defaults). */
void cases_tool_params(const struct config *cfg, struct tool_params *p);

/*
 * Builds the colon of case NAME in cfg->colon.directory, or, when NAME is
 * NULL, the configured one. NULL with one line in ERR ("FILE:LINE: ..."
 * for a broken file).
 */
struct colon *cases_load(const struct config *cfg, const char *name,
			 char *err, size_t errsize);

/*
 * The file cases_load(CFG, NAME, ...) reads, into BUF: DIRECTORY/NAME.case,
 * or the configured [case] file (a .case, or an .obj mesh) when NAME is
 * NULL. 0, or -EINVAL for a NAME that is not a case name, -ENAMETOOLONG.
 */
int cases_path(const struct config *cfg, const char *name, char *buf,
	       size_t size);

/*
 * The cases in DIR (files NAME.case that parse), sorted by name: a
 * malloc'd array of *N entries in *OUT (free() it). A file that does not
 * parse is left out and the first such error put in ERR (else ""). Returns
 * 0 or a negative errno (DIR unreadable, ENOMEM) with ERR set.
 */
int cases_list(const char *dir, struct cases_entry **out, size_t *n,
	       char *err, size_t errsize);

#endif
