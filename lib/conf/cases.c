/* cases.c - see cases.h. */
#include "conf/cases.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void cases_colon_params(const struct config *cfg, struct colon_params *p)
{
	p->step_m = cfg->colon.step_m;
	p->ring_vertices = (uint32_t)cfg->colon.ring_vertices;
	p->segment_m = cfg->colon.segment_m;
	p->contact_radius_m = cfg->haptics.scope_radius_m;
}

void cases_scope_params(const struct config *cfg, struct scope_params *p)
{
	*p = (struct scope_params){
		.bending_length_m = cfg->scope.bending_length_m,
		.ud_gain = cfg->scope.gain[0],
		.lr_gain = cfg->scope.gain[1],
		.ud_limit_rad = cfg->scope.limit_rad[0],
		.lr_limit_rad = cfg->scope.limit_rad[1],
	};
}

void cases_haptics_params(const struct config *cfg, struct haptics_params *p)
{
	p->gains = cfg->haptics;
	p->bending_length_m = cfg->scope.bending_length_m;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		p->driven[a] = config_axis_backend(cfg, a) != CONFIG_DRIVE_SIM;
	}
	for (int w = 0; w < 2; w++) {
		p->wheel_gain[w] = cfg->scope.gain[w];
		p->wheel_limit_rad[w] = cfg->scope.limit_rad[w];
		p->wheel_max_n_m[w] = cfg->limits.max[ENDOSIM_AXIS_WHEEL_UD + w];
	}
	cases_rod_params(cfg, &p->rod);
	cases_patient_params(cfg, &p->patient);
}

void cases_patient_params(const struct config *cfg,
			  struct patient_params *p)
{
	const struct config_patient *c = &cfg->patient;

	*p = (struct patient_params){
		.enabled = c->enabled,
		.gas = {
			.kind = c->gas,
			.pump_m3_per_s = c->pump_m3_per_s,
			.suction_m3_per_s = c->suction_m3_per_s,
			.leak_m3_per_s_pa = c->leak_m3_per_s_pa,
			.leak_pa = c->leak_pa,
			.absorb_air_per_s = c->absorb_air_per_s,
			.absorb_co2_per_s = c->absorb_co2_per_s,
			.relief_pa = c->relief_pa,
			.wall_strength_n_per_m = c->wall_strength_n_per_m,
			.hydrostatic_pa_per_m = c->hydrostatic_pa_per_m,
		},
		.fluid = {
			.suction_m3_per_s = c->suction_fluid_m3_per_s,
			.settle_s = c->fluid_settle_s,
		},
		.lens = {
			.contact_n = c->lens_contact_n,
			.smear_n_s = c->lens_smear_n_s,
			.dip_s = c->lens_dip_s,
			.wash_s = c->lens_wash_s,
			.redout_gap_m = c->lens_redout_gap_m,
			.redout_s = c->lens_redout_s,
		},
		.start_position = c->position,
		.turn_s = c->turn_s,
		.gravity_m_s2 = PATIENT_GRAVITY_M_S2,
		.hand_n = c->hand_n,
		.hand_max_n = c->hand_max_n,
		.abdomen_n_per_m = c->abdomen_n_per_m,
		.pain = cfg->pain,
		.perforation = {
			.straight_n = c->perforation_straight_n,
			.bent_n = c->perforation_bent_n,
			.hold_s = c->perforation_hold_s,
		},
		.vitals = VITALS_PARAMS_DEFAULT,
	};
}

void cases_tool_params(const struct config *cfg, struct tool_params *p)
{
	const struct config_tool *c = &cfg->tool;

	*p = (struct tool_params)TOOL_PARAMS_DEFAULT;
	p->channel_angle_rad = c->channel_angle_deg * TOOL_RAD_PER_DEG;
	p->channel_offset_m = c->channel_offset_m;
	p->hot_power_w = c->hot_power_w;
	p->cut_j_per_m2 = c->cut_j_per_m2;
	p->cold_max_m = c->cold_max_m;
	p->coag_j_per_m3 = c->coag_j_per_m3;
	p->bleed_min_m = c->bleed_min_m;
	p->bleed_m_per_s = c->bleed_m_per_s;
	p->bleed_stop_s = c->bleed_stop_s;
	p->retrieve_max_m = c->retrieve_max_m;
	p->retrieve_reach_m = c->retrieve_reach_m;
	p->fall_drag_s = c->fall_drag_s;
}

void cases_rod_params(const struct config *cfg, struct rodscope_params *p)
{
	const struct config_rod *r = &cfg->rod;

	p->rod = (struct rod_params){
		.segments = r->segments, .length_m = r->length_m,
		.radius_m = cfg->haptics.scope_radius_m,
		.mass_per_m_kg = r->mass_per_m_kg,
		.bending_n_m2 = r->bending_n_m2,
		.torsion_n_m2 = r->torsion_n_m2, .damping_s = r->damping_s,
		.drag_n_s_per_m2 = r->drag_n_s_per_m2,
		.iterations = r->iterations,
	};
	p->bending_length_m = cfg->scope.bending_length_m;
	p->tip_bending_n_m2 = r->tip_bending_n_m2;
	p->lumen = (struct lumen_params){
		.wall_n_per_m2 = r->wall_n_per_m2,
		.wall_damping_s = r->wall_damping_s, .friction = r->friction,
		.slip_m_per_s = r->slip_m_per_s,
		.pipe_n_per_m2 = r->pipe_n_per_m2,
		.tube_radius_m = cfg->haptics.scope_radius_m,
	};
	p->flex = (struct flex_params){
		.node_spacing_m = r->colon_node_spacing_m,
		.damping_n_s_per_m = r->colon_damping_n_s_per_m,
		.chain_n_per_m = r->colon_chain_n_per_m,
		.mass_per_m_kg = r->colon_mass_per_m_kg,
		.bending_n_per_m = r->colon_bending_n_per_m,
	};
	p->coupling_n_per_m = r->coupling_n_per_m;
	p->coupling_n_s_per_m = r->coupling_n_s_per_m;
	p->roll_n_m_per_rad = r->roll_n_m_per_rad;
	p->roll_n_m_s_per_rad = r->roll_n_m_s_per_rad;
	p->stop_n_per_m = r->stop_n_per_m;
	p->wire_spacing_m = cfg->haptics.wire_spacing_m;
}

static bool ends_with(const char *s, const char *tail)
{
	size_t n = strlen(s), t = strlen(tail);

	return n >= t && !strcmp(s + n - t, tail);
}

/* Reads PATH; when NAME is given, the case must be called so. */
static int read_case(const char *path, const char *name, struct anatomy *a,
		     char *err, size_t errsize)
{
	int r = anatomy_load(a, path, err, errsize);

	if (!r && name && strcmp(a->name, name)) {
		snprintf(err, errsize, "%s: [case] name '%s' differs from the "
			 "file's name '%s'", path, a->name, name);
		r = -EINVAL;
	}
	return r;
}

static struct colon *load_case_file(const char *path, const char *name,
				    const struct colon_params *p, char *err,
				    size_t errsize)
{
	struct anatomy a;

	if (read_case(path, name, &a, err, errsize)) {
		return NULL;
	}
	return colon_create(&a, p, err, errsize);
}

struct colon *cases_load(const struct config *cfg, const char *name,
			 char *err, size_t errsize)
{
	const char *cl = cfg->colon.centreline_file;
	struct colon_params p;
	char path[2 * CONFIG_STR + 8];

	cases_colon_params(cfg, &p);
	if (!name && *cfg->colon.file) {
		if (ends_with(cfg->colon.file, ".obj")) {
			return colon_import(cfg->colon.file, *cl ? cl : NULL,
					    &p, err, errsize);
		}
		return load_case_file(cfg->colon.file, NULL, &p, err,
				      errsize);
	}
	name = name ? name : cfg->colon.name;
	if (!config_case_name_ok(name)) {
		snprintf(err, errsize, "'%s' is not a case name (letters, "
			 "digits, '-', '_')", name);
		return NULL;
	}
	snprintf(path, sizeof(path), "%s/%s.case", cfg->colon.directory, name);
	return load_case_file(path, name, &p, err, errsize);
}

int cases_path(const struct config *cfg, const char *name, char *buf,
	       size_t size)
{
	int n;

	if (!name && *cfg->colon.file) {
		n = snprintf(buf, size, "%s", cfg->colon.file);
	} else {
		name = name ? name : cfg->colon.name;
		if (!config_case_name_ok(name)) {
			return -EINVAL;
		}
		n = snprintf(buf, size, "%s/%s.case", cfg->colon.directory,
			     name);
	}
	return n < 0 || (size_t)n >= size ? -ENAMETOOLONG : 0;
}

static int by_name(const void *a, const void *b)
{
	return strcmp(((const struct cases_entry *)a)->name,
		      ((const struct cases_entry *)b)->name);
}

/* Adds DIR/FILE to *OUT if it parses; keeps the first error in ERR. */
static int add_case(const char *dir, const char *file,
		    struct cases_entry **out, size_t *n, size_t *cap,
		    char *err, size_t errsize)
{
	char path[4096], why[sizeof(path) + 256], name[ANATOMY_NAME];
	struct anatomy a;

	snprintf(path, sizeof(path), "%s/%s", dir, file);
	snprintf(name, sizeof(name), "%.*s", (int)(strlen(file) - 5), file);
	if (read_case(path, name, &a, why, sizeof(why))) {
		if (!*err) {
			snprintf(err, errsize, "%s", why);
		}
		return 0;
	}
	if (*n == *cap) {
		size_t c = *cap ? 2 * *cap : 16;
		struct cases_entry *bigger = realloc(*out, c * sizeof(**out));

		if (!bigger) {
			return -ENOMEM;
		}
		*out = bigger;
		*cap = c;
	}
	snprintf((*out)[*n].name, ANATOMY_NAME, "%s", a.name);
	snprintf((*out)[*n].description, ANATOMY_TEXT, "%s", a.description);
	(*n)++;
	return 0;
}

int cases_list(const char *dir, struct cases_entry **out, size_t *n,
	       char *err, size_t errsize)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	size_t cap = 0;
	int r = 0;

	*out = NULL;
	*n = 0;
	err[0] = '\0';
	if (!d) {
		r = -errno;
		snprintf(err, errsize, "%s: %s", dir, strerror(-r));
		return r;
	}
	while (!r && (e = readdir(d))) {
		if (e->d_name[0] != '.' && ends_with(e->d_name, ".case")) {
			r = add_case(dir, e->d_name, out, n, &cap, err,
				     errsize);
		}
	}
	closedir(d);
	if (r) {
		snprintf(err, errsize, "%s: out of memory", dir);
		free(*out);
		*out = NULL;
		*n = 0;
		return r;
	}
	qsort(*out, *n, sizeof(**out), by_name);
	return 0;
}
