/* test_config.c - the configuration table: every class of bad input gives
 * one line naming the file, the line and the key; good input round-trips. */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "conf/config.h"

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
		const struct config_key *k = config_key_at(i);
		char name[160];

		assert_non_null(k->help);
		assert_true(strlen(k->help) > 5);
		if (k->type == CONFIG_INT || k->type == CONFIG_DOUBLE) {
			assert_true(k->def >= k->min && k->def <= k->max);
		}
		snprintf(name, sizeof(name), "%s.%s", k->section, k->name);
		assert_ptr_equal(config_key_find(name), k);
	}
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
		cmocka_unit_test(test_set_live_only),
		cmocka_unit_test(test_print_round_trip),
		cmocka_unit_test(test_table_sane),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
