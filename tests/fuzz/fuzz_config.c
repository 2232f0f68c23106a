/*
 * fuzz_config - libFuzzer target: the configuration file parser and the
 * table's validation, on arbitrary file contents; and a KEY=VALUE override
 * as given on the command line.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "conf/config.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct config cfg;
	char err[512], text[256];
	FILE *f;

	config_defaults(&cfg);
	f = fmemopen((void *)data, size, "r");
	if (f) {
		config_load_stream(&cfg, f, "fuzz.conf", err, sizeof(err));
		fclose(f);
	}
	if (size < sizeof(text)) {
		memcpy(text, data, size);
		text[size] = '\0';
		char *eq = strchr(text, '=');

		if (eq) {
			*eq = '\0';
			config_set(&cfg, text, eq + 1, false, err, sizeof(err));
		}
	}
	return 0;
}
