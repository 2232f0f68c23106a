/* test_config.c - the configuration table: every class of bad input gives
 * one line naming the file, the line and the key; good input round-trips;
 * its defaults are the model's and the metrics' own. */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "conf/cases.h"
#include "conf/config.h"
#include "session/metrics.h"
#include "session/records.h"
#include "session/sessioninputs.h"

static char path[64];
static char err[512];

static void write_file(const char *text)
{
	FILE *f = fopen(path, "w");

	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

static int setup(void **state)
{
	(void)state;
	snprintf(path, sizeof(path), "/tmp/test_config.%d.conf", (int)getpid());
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	unlink(path);
	return 0;
}

/* Loads TEXT over the defaults; returns config_load()'s result. */
static int load(const char *text, struct config *cfg)
{
	write_file(text);
	config_defaults(cfg);
	return config_load(cfg, path, err, sizeof(err));
}

/* ERR names the file, LINE, and contains WHAT. */
static void assert_error(int line, const char *what)
{
	char where[96];

	snprintf(where, sizeof(where), "%s:%d:", path, line);
	assert_non_null(strstr(err, where));
	assert_non_null(strstr(err, what));
}

static void test_defaults_are_valid(void **state)
{
	struct config cfg;

	(void)state;
	config_defaults(&cfg);
	assert_int_equal(config_check(&cfg, err, sizeof(err)), 0);
	assert_int_equal(cfg.loop.rate_hz, 1000);
	assert_int_equal(cfg.loop.priority, 80);
	assert_int_equal(cfg.rig.backend, CONFIG_BACKEND_SIM);
	assert_string_equal(cfg.socket.directory, "/run/endosim");
	assert_string_equal(cfg.shm.name, "/endosim");
}

static void test_good_file(void **state)
{
	struct config cfg;

	(void)state;
	assert_int_equal(load("; comment\n[loop]\nrate_hz = 500\n"
			      "priority = 70 ; inline comment\n"
			      "[limits]\ninsertion_max_force_n = 20.5\n"
			      "[socket]\ndirectory = /tmp/x\n"
			      "[log]\nlevel = debug\n", &cfg), 0);
	assert_int_equal(cfg.loop.rate_hz, 500);
	assert_int_equal(cfg.loop.priority, 70);
	assert_true(cfg.limits.max[ENDOSIM_AXIS_INSERTION] == 20.5);
	assert_string_equal(cfg.socket.directory, "/tmp/x");
	assert_int_equal(cfg.log.level, 7);
	/* keys not in the file keep their defaults */
	assert_int_equal(cfg.loop.cpu, -1);
}

static void test_unknown_key(void **state)
{
	struct config cfg;

	(void)state;
	assert_int_equal(load("[loop]\nrate_hz = 500\nrate = 3\n", &cfg),
			 -EINVAL);
	assert_error(3, "[loop] rate: unknown key");
}

static void test_unknown_section(void **state)
{
	struct config cfg;

	(void)state;
	assert_int_equal(load("[loop]\nrate_hz = 500\n\n[lop]\nrate_hz = 1\n",
			      &cfg), -EINVAL);
	assert_error(5, "[lop] rate_hz: unknown key");
}

static void test_out_of_range(void **state)
{
	struct config cfg;

	(void)state;
	assert_int_equal(load("[loop]\npriority = 100\n", &cfg), -EINVAL);
	assert_error(2, "[loop] priority: 100 is out of range [1, 99]");
	assert_int_equal(load("[limits]\nroll_max_torque_n_m = -1\n", &cfg),
			 -EINVAL);
	assert_error(2, "out of range");
}

static void test_wrong_type(void **state)
{
	struct config cfg;

	(void)state;
	assert_int_equal(load("[loop]\nrate_hz = fast\n", &cfg), -EINVAL);
	assert_error(2, "'fast' is not an integer");
	assert_int_equal(load("[loop]\nrate_hz = 1000.5\n", &cfg), -EINVAL);
	assert_error(2, "not an integer");
	assert_int_equal(load("[limits]\n\ninsertion_max_force_n = 4x\n", &cfg),
			 -EINVAL);
	assert_error(3, "'4x' is not a number");
	assert_int_equal(load("[limits]\ninsertion_max_force_n = nan\n", &cfg),
			 -EINVAL);
	assert_error(2, "not a number");
	assert_int_equal(load("[rig]\nbackend = usb\n", &cfg), -EINVAL);
	assert_error(2, "[rig] backend: 'usb' is not a known choice");
	assert_int_equal(load("[log]\nlevel = loud\n", &cfg), -EINVAL);
	assert_error(2, "[log] level");
	assert_int_equal(load("[loop]\nrate_hz =\n", &cfg), -EINVAL);
	assert_error(2, "not an integer");
}

static void test_duplicate(void **state)
{
	struct config cfg;

	(void)state;
	assert_int_equal(load("[loop]\nrate_hz = 500\n[limits]\n[loop]\n"
			      "rate_hz = 600\n", &cfg), -EINVAL);
	assert_error(5, "duplicate key (first set on line 2)");
}

static void test_missing_file(void **state)
{
	struct config cfg;

	(void)state;
	config_defaults(&cfg);
	assert_int_equal(config_load(&cfg, "/nonexistent/endosimd.conf", err,
				     sizeof(err)), -ENOENT);
	assert_non_null(strstr(err, "/nonexistent/endosimd.conf: cannot open"));
}

static void test_empty_file(void **state)
{
	struct config cfg;

	(void)state;
	assert_int_equal(load("", &cfg), -EINVAL);
	assert_non_null(strstr(err, "empty"));
	assert_int_equal(load("; only comments\n\n[loop]\n", &cfg), -EINVAL);
	assert_non_null(strstr(err, "empty"));
}

static void test_syntax_error(void **state)
{
	struct config cfg;

	(void)state;
	assert_int_equal(load("[loop]\nrate_hz = 500\n[limits\n", &cfg),
			 -EINVAL);
	assert_error(3, "syntax error");
	assert_int_equal(load("[loop]\nrate_hz 500\n", &cfg), -EINVAL);
	assert_error(2, "syntax error");
}

static void test_cross_checks(void **state)
{
	struct config cfg;

	(void)state;
	assert_int_equal(load("[rig]\ninsertion_min_m = 2\n", &cfg), -EINVAL);
	assert_non_null(strstr(err, "insertion travel"));
	assert_int_equal(load("[shm]\nname = no-slash\n", &cfg), -EINVAL);
	assert_non_null(strstr(err, "[shm] name"));
}

/* TEXT's load refused at LINE with WHAT, the configuration untouched. */
static void refused_at(const char *text, int line, const char *what)
{
	struct config cfg, before;

	config_defaults(&before);
	write_file(text);
	config_defaults(&cfg);
	if (config_load(&cfg, path, err, sizeof(err)) != -EINVAL) {
		fail_msg("'%s' was taken", text);
	}
	if (line) {
		assert_error(line, what);
	} else { /* "FILE: ": the file does not set the key named */
		assert_int_equal(strncmp(err, path, strlen(path)), 0);
		assert_int_equal(strncmp(err + strlen(path), ": [", 3), 0);
		assert_non_null(strstr(err, what));
	}
	assert_memory_equal(&cfg, &before, sizeof(cfg));
}

/* The patient's keys (issue 22) and the tools' (issue 25): every [patient]
 * and [tool] key and [rod]
 * colon_mass_per_m_kg beyond either end of its range, malformed, or not
 * one of its choices, refused with its file, line and key. */
static void test_patient_keys(void **state)
{
	char text[256], what[160];

	(void)state;
	for (size_t i = 0; i < config_key_count(); i++) {
		const struct parse_key *k = config_key_at(i);
		double out[2] = { k->min - fabs(k->min) - 1,
				  k->max + fabs(k->max) + 1 };

		if (strcmp(k->section, "patient") &&
		    strcmp(k->section, "tool") &&
		    strcmp(k->name, "colon_mass_per_m_kg")) {
			continue;
		}
		if (k->type == PARSE_CHOICE) {
			snprintf(text, sizeof(text), "[%s]\n\n%s = bogus\n",
				 k->section, k->name);
			snprintf(what, sizeof(what), "[%s] %s: 'bogus' is not "
				 "a known choice", k->section, k->name);
			refused_at(text, 3, what);
			continue;
		}
		assert_int_equal(k->type, PARSE_DOUBLE);
		for (int e = 0; e < 2; e++) {
			snprintf(text, sizeof(text), "[%s]\n%s = %.17g\n",
				 k->section, k->name, out[e]);
			snprintf(what, sizeof(what), "[%s] %s: %.17g is out "
				 "of range", k->section, k->name, out[e]);
			refused_at(text, 2, what);
		}
		snprintf(text, sizeof(text), "[%s]\n%s = 1 x\n", k->section,
			 k->name);
		snprintf(what, sizeof(what), "[%s] %s: '1 x' is not a number",
			 k->section, k->name);
		refused_at(text, 2, what);
		snprintf(text, sizeof(text), "[%s]\n%s = nan\n", k->section,
			 k->name);
		refused_at(text, 2, "'nan' is not a number");
	}
	/* across keys: the usual press within the strongest */
	refused_at("[loop]\nrate_hz = 1000\n[patient]\nhand_max_n = 30\n"
		   "hand_n = 40\n", 5, "[patient] hand_n: 40 N is above "
		   "hand_max_n (30 N)");
	refused_at("[patient]\nhand_max_n = 10\n", 0, "[patient] hand_n: "
		   "20 N is above hand_max_n (10 N)");
}

static void test_set_live_only(void **state)
{
	struct config cfg;

	(void)state;
	config_defaults(&cfg);
	assert_int_equal(config_set(&cfg, "limits.insertion_max_force_n", "30",
				    true, err, sizeof(err)), 0);
	assert_true(cfg.limits.max[ENDOSIM_AXIS_INSERTION] == 30);
	assert_int_equal(config_set(&cfg, "loop.rate_hz", "500", true, err,
				    sizeof(err)), -EPERM);
	assert_int_equal(cfg.loop.rate_hz, 1000);
	assert_int_equal(config_set(&cfg, "loop.rate_hz", "500", false, err,
				    sizeof(err)), 0);
	assert_int_equal(cfg.loop.rate_hz, 500);
	assert_int_equal(config_set(&cfg, "loop.nope", "1", false, err,
				    sizeof(err)), -ENOENT);
	assert_int_equal(config_set(&cfg, "nodot", "1", false, err,
				    sizeof(err)), -ENOENT);
	assert_int_equal(config_set(&cfg, "limits.roll_max_torque_n_m", "9",
				    true, err, sizeof(err)), -EINVAL);
	assert_true(cfg.limits.max[ENDOSIM_AXIS_ROLL] == 1.0);
	/* a cross-key violation leaves the configuration unchanged */
	assert_int_equal(config_set(&cfg, "rig.wheel_ud_min_rad", "2", false,
				    err, sizeof(err)), -EINVAL);
	assert_true(cfg.rig.travel_min[ENDOSIM_AXIS_WHEEL_UD] == -1.75);
}

/* --print-config writes a file that loads back to the same values. */
static void test_print_round_trip(void **state)
{
	struct config a, b;
	FILE *f;

	(void)state;
	config_defaults(&a);
	assert_int_equal(config_set(&a, "limits.wheel_lr_max_torque_n_m",
				    "0.05", false, err, sizeof(err)), 0);
	assert_int_equal(config_set(&a, "socket.group", "video", false, err,
				    sizeof(err)), 0);
	f = fopen(path, "w");
	assert_non_null(f);
	config_print(&a, f);
	fclose(f);
	config_defaults(&b);
	assert_int_equal(config_load(&b, path, err, sizeof(err)), 0);
	for (size_t i = 0; i < config_key_count(); i++) {
		char va[200], vb[200];

		config_format(&a, config_key_at(i), va, sizeof(va));
		config_format(&b, config_key_at(i), vb, sizeof(vb));
		assert_string_equal(va, vb);
	}
}

/* Every key in the table has a unit or is dimensionless on purpose, help,
 * a default inside its range, and a unique name. */
static void test_table_sane(void **state)
{
	(void)state;
	for (size_t i = 0; i < config_key_count(); i++) {
		const struct parse_key *k = config_key_at(i);
		char name[160];

		assert_non_null(k->help);
		assert_true(strlen(k->help) > 5);
		if (k->type == PARSE_INT || k->type == PARSE_DOUBLE) {
			assert_true(k->def >= k->min && k->def <= k->max);
		}
		snprintf(name, sizeof(name), "%s.%s", k->section, k->name);
		assert_ptr_equal(config_key_find(name), k);
	}
}

/* ----------------------------------------- the owners' defaults, once */

static int mismatches;

/* One parameter: the configuration's GOT against its owner's WANT. */
static void same(const char *name, double got, double want)
{
	if (got != want) {
		print_error("%s: the configuration gives %.17g, its owner "
			    "%.17g\n", name, got, want);
		mismatches++;
	}
}

#define SAME(got, want, field) \
	same(#field, (double)(got).field, (double)(want).field)

static void same_rodscope(const struct rodscope_params *c)
{
	const struct rodscope_params m = RODSCOPE_PARAMS_DEFAULT;

	SAME(*c, m, rod.segments);
	SAME(*c, m, rod.length_m);
	SAME(*c, m, rod.radius_m);
	SAME(*c, m, rod.mass_per_m_kg);
	SAME(*c, m, rod.bending_n_m2);
	SAME(*c, m, rod.torsion_n_m2);
	SAME(*c, m, rod.damping_s);
	SAME(*c, m, rod.drag_n_s_per_m2);
	SAME(*c, m, rod.iterations);
	SAME(*c, m, bending_length_m);
	SAME(*c, m, tip_bending_n_m2);
	SAME(*c, m, lumen.wall_n_per_m2);
	SAME(*c, m, lumen.wall_damping_s);
	SAME(*c, m, lumen.friction);
	SAME(*c, m, lumen.slip_m_per_s);
	SAME(*c, m, lumen.pipe_n_per_m2);
	SAME(*c, m, lumen.tube_radius_m);
	SAME(*c, m, flex.node_spacing_m);
	SAME(*c, m, flex.damping_n_s_per_m);
	SAME(*c, m, flex.chain_n_per_m);
	SAME(*c, m, flex.bending_n_per_m);
	SAME(*c, m, flex.mass_per_m_kg);
	SAME(*c, m, coupling_n_per_m);
	SAME(*c, m, coupling_n_s_per_m);
	SAME(*c, m, roll_n_m_per_rad);
	SAME(*c, m, roll_n_m_s_per_rad);
	SAME(*c, m, stop_n_per_m);
	SAME(*c, m, wire_spacing_m);
}

static void same_patient(const struct patient_params *c)
{
	const struct patient_params m = PATIENT_PARAMS_DEFAULT;

	SAME(*c, m, enabled);
	SAME(*c, m, gas.kind);
	SAME(*c, m, gas.pump_m3_per_s);
	SAME(*c, m, gas.suction_m3_per_s);
	SAME(*c, m, gas.leak_m3_per_s_pa);
	SAME(*c, m, gas.leak_pa);
	SAME(*c, m, gas.absorb_air_per_s);
	SAME(*c, m, gas.absorb_co2_per_s);
	SAME(*c, m, gas.relief_pa);
	SAME(*c, m, gas.wall_strength_n_per_m);
	SAME(*c, m, gas.hydrostatic_pa_per_m);
	SAME(*c, m, fluid.suction_m3_per_s);
	SAME(*c, m, fluid.settle_s);
	SAME(*c, m, lens.contact_n);
	SAME(*c, m, lens.smear_n_s);
	SAME(*c, m, lens.dip_s);
	SAME(*c, m, lens.wash_s);
	SAME(*c, m, lens.redout_gap_m);
	SAME(*c, m, lens.redout_s);
	SAME(*c, m, start_position);
	SAME(*c, m, turn_s);
	SAME(*c, m, gravity_m_s2);
	SAME(*c, m, hand_n);
	SAME(*c, m, hand_max_n);
	SAME(*c, m, abdomen_n_per_m);
	SAME(*c, m, pain.stretch_threshold_n);
	SAME(*c, m, pain.stretch_gain_per_n);
	SAME(*c, m, pain.wall_threshold_n_per_m);
	SAME(*c, m, pain.wall_gain_per_n_per_m);
	SAME(*c, m, pain.tip_threshold_n);
	SAME(*c, m, pain.tip_gain_per_n);
	SAME(*c, m, pain.rise_s);
	SAME(*c, m, pain.fade_s);
	SAME(*c, m, pain.moving_m_s);
	SAME(*c, m, pain.turning_rad_s);
	SAME(*c, m, pain.sedation);
	SAME(*c, m, perforation.straight_n);
	SAME(*c, m, perforation.bent_n);
	SAME(*c, m, perforation.hold_s);
}

static void same_haptics(const struct haptics_params *c)
{
	const struct haptics_gains m = HAPTICS_GAINS_DEFAULT;
	const struct scope_params s = SCOPE_PARAMS_DEFAULT;

	SAME(c->gains, m, model);
	SAME(c->gains, m, scope_radius_m);
	SAME(c->gains, m, wall_stiffness_n_per_m);
	SAME(c->gains, m, wall_damping_n_s_per_m);
	SAME(c->gains, m, tip_lateral_stiffness_n_per_m);
	SAME(c->gains, m, force_shading);
	SAME(c->gains, m, contact_reach_m);
	SAME(c->gains, m, entry_depth_m);
	SAME(c->gains, m, friction_n_s_per_m_rad);
	SAME(c->gains, m, torsion_n_m_s_per_rad2);
	SAME(c->gains, m, wire_spacing_m);
	SAME(c->gains, m, wire_tension_n_m_per_m);
	SAME(c->gains, m, bending_stiffness_n_m_per_rad);
	SAME(c->gains, m, stop_stiffness_n_m_per_rad);
	SAME(c->gains, m, stop_damping_n_m_s_per_rad);
	SAME(c->gains, m, wheel_delay_s);
	SAME(c->gains, m, loop_relax_s);
	SAME(c->gains, m, damping[ENDOSIM_AXIS_INSERTION]);
	SAME(c->gains, m, damping[ENDOSIM_AXIS_ROLL]);
	SAME(c->gains, m, damping[ENDOSIM_AXIS_WHEEL_UD]);
	SAME(c->gains, m, damping[ENDOSIM_AXIS_WHEEL_LR]);
	SAME(c->gains, m, passivity);
	same("bending_length_m", c->bending_length_m, s.bending_length_m);
	same("wheel_gain[0]", c->wheel_gain[0], s.ud_gain);
	same("wheel_gain[1]", c->wheel_gain[1], s.lr_gain);
	same("wheel_limit_rad[0]", c->wheel_limit_rad[0], s.ud_limit_rad);
	same("wheel_limit_rad[1]", c->wheel_limit_rad[1], s.lr_limit_rad);
	same_rodscope(&c->rod);
	same_patient(&c->patient);
}

/* The metrics' thresholds, with the loop's by the paper model (0 in the
 * configuration: by the model; the metrics' default is the paper's). */
static void same_metrics(const struct config *cfg)
{
	struct config paper = *cfg;
	struct metrics_params c, m;

	paper.haptics.model = HAPTICS_MODEL_PAPER;
	sessioninputs_metrics_params(&paper, &c);
	metrics_params_default(&m);
	SAME(c, m, force_threshold_n);
	SAME(c, m, loop_threshold_m);
	SAME(c, m, view_distance_m);
	SAME(c, m, fov_rad);
	SAME(c, m, view_rate_hz);
	SAME(c, m, pain_level);
}

/* The tools' ([tool]), and the snare's size the control thread takes. */
static void same_tool(const struct config *cfg)
{
	const struct tool_params m = TOOL_PARAMS_DEFAULT;
	struct tool_params c;

	cases_tool_params(cfg, &c);
	SAME(c, m, channel_angle_rad);
	SAME(c, m, channel_offset_m);
	SAME(c, m, cut_j_per_m2);
	SAME(c, m, hot_power_w);
	SAME(c, m, cold_max_m);
	SAME(c, m, coag_j_per_m3);
	SAME(c, m, bleed_min_m);
	SAME(c, m, bleed_m_per_s);
	SAME(c, m, bleed_stop_s);
	SAME(c, m, retrieve_max_m);
	SAME(c, m, retrieve_reach_m);
	SAME(c, m, fall_drag_s);
	same("snare_size_m", cfg->tool.snare_size_m, TOOL_DEFAULT_SNARE_M);
}

/* CFG's model parameters (cases.h) field by field against the owners'. */
static void same_as_owners(const struct config *cfg)
{
	const struct colon_params mc = COLON_PARAMS_DEFAULT;
	const struct scope_params ms = SCOPE_PARAMS_DEFAULT;
	struct colon_params cc;
	struct scope_params cs;
	struct rodscope_params cr;
	struct haptics_params ch;

	cases_colon_params(cfg, &cc);
	SAME(cc, mc, step_m);
	SAME(cc, mc, ring_vertices);
	SAME(cc, mc, segment_m);
	SAME(cc, mc, contact_radius_m);
	cases_scope_params(cfg, &cs);
	SAME(cs, ms, bending_length_m);
	SAME(cs, ms, ud_gain);
	SAME(cs, ms, lr_gain);
	SAME(cs, ms, ud_limit_rad);
	SAME(cs, ms, lr_limit_rad);
	cases_rod_params(cfg, &cr);
	same_rodscope(&cr);
	cases_haptics_params(cfg, &ch);
	same_haptics(&ch);
	same_metrics(cfg);
	same_tool(cfg);
	if (strcmp(cfg->records.database, RECORDS_DEFAULT_NAME)) {
		print_message("records.database: %s, records.h: %s\n",
			      cfg->records.database, RECORDS_DEFAULT_NAME);
		mismatches++;
	}
}

/*
 * Each [tool] key set to a value in its range other than its default
 * reaches the model's parameters (cases_tool_params()): a key the table
 * has but the model never takes fails.
 */
static void test_tool_keys_reach_model(void **state)
{
	static const struct {
		const char *key, *value;
		size_t at;   /* in struct tool_params */
		double want; /* there */
	} k[] = {
#define TOOL_KEY(name, text, field, v)                                      \
	{ "tool." name, text, offsetof(struct tool_params, field), v }
		TOOL_KEY("channel_angle_deg", "90", channel_angle_rad,
			 90 * TOOL_RAD_PER_DEG),
		TOOL_KEY("channel_offset_m", "0.003", channel_offset_m, 0.003),
		TOOL_KEY("hot_power_w", "40", hot_power_w, 40),
		TOOL_KEY("cut_j_per_m2", "3e6", cut_j_per_m2, 3e6),
		TOOL_KEY("cold_max_m", "0.008", cold_max_m, 0.008),
		TOOL_KEY("coag_j_per_m3", "3e8", coag_j_per_m3, 3e8),
		TOOL_KEY("bleed_min_m", "0.004", bleed_min_m, 0.004),
		TOOL_KEY("bleed_m_per_s", "0.002", bleed_m_per_s, 0.002),
		TOOL_KEY("bleed_stop_s", "60", bleed_stop_s, 60),
		TOOL_KEY("retrieve_max_m", "0.008", retrieve_max_m, 0.008),
		TOOL_KEY("retrieve_reach_m", "0.004", retrieve_reach_m, 0.004),
		TOOL_KEY("fall_drag_s", "0.05", fall_drag_s, 0.05),
#undef TOOL_KEY
	};
	const struct tool_params def = TOOL_PARAMS_DEFAULT;

	(void)state;
	for (size_t i = 0; i < sizeof(k) / sizeof(k[0]); i++) {
		struct config cfg;
		struct tool_params p;
		double got, was;

		config_defaults(&cfg);
		assert_int_equal(config_set(&cfg, k[i].key, k[i].value, true,
					    err, sizeof(err)), 0);
		cases_tool_params(&cfg, &p);
		memcpy(&got, (const char *)&p + k[i].at, sizeof(got));
		memcpy(&was, (const char *)&def + k[i].at, sizeof(was));
		print_message("%s = %s: %g (default %g)\n", k[i].key,
			      k[i].value, got, was);
		assert_true(fabs(got - k[i].want) <= 1e-12 * fabs(k[i].want));
		assert_true(got != was);
	}
}

/*
 * Each default is written once, in the module that owns it (scope.h,
 * colon.h, rod.h, lumen.h, flex.h, rodscope.h, haptics.h, gas.h, fluid.h,
 * lens.h, patient.h, tool.h), and the
 * table refers to it; the metrics' thresholds and the records' file name
 * twice (metrics.h, records.h and the table). The configuration's defaults, as config_defaults() sets them
 * and as --print-config writes them and a file reads them back, make the
 * owners' parameters exactly: a default typed into the table, or edited
 * in one place only, or printed with less precision than it has, fails.
 */
static void test_defaults_are_the_owners(void **state)
{
	struct config cfg, printed;
	char *text = NULL;
	size_t size = 0;
	FILE *f;

	(void)state;
	mismatches = 0;
	config_defaults(&cfg);
	same_as_owners(&cfg);
	f = open_memstream(&text, &size);
	assert_non_null(f);
	config_print(&cfg, f);
	fclose(f);
	f = fmemopen(text, size, "r");
	assert_non_null(f);
	config_defaults(&printed);
	assert_int_equal(config_load_stream(&printed, f, "printed", err,
					    sizeof(err)), 0);
	fclose(f);
	free(text);
	same_as_owners(&printed);
	assert_int_equal(mismatches, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_defaults_are_valid),
		cmocka_unit_test(test_good_file),
		cmocka_unit_test(test_unknown_key),
		cmocka_unit_test(test_unknown_section),
		cmocka_unit_test(test_out_of_range),
		cmocka_unit_test(test_wrong_type),
		cmocka_unit_test(test_duplicate),
		cmocka_unit_test(test_missing_file),
		cmocka_unit_test(test_empty_file),
		cmocka_unit_test(test_syntax_error),
		cmocka_unit_test(test_cross_checks),
		cmocka_unit_test(test_patient_keys),
		cmocka_unit_test(test_set_live_only),
		cmocka_unit_test(test_print_round_trip),
		cmocka_unit_test(test_table_sane),
		cmocka_unit_test(test_defaults_are_the_owners),
		cmocka_unit_test(test_tool_keys_reach_model),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
