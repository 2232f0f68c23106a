/*
 * fuzz_course - libFuzzer target: the course-file parser (coursefile.c) on
 * arbitrary file contents, then judging a session against whatever it
 * accepts (every requirement, every case: the progress over a few
 * sessions).
 */
#include <stdint.h>

#include "session/coursefile.h"
#include "fuzz_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct coursefile c;
	struct metrics_result m = { .cecum_s = 300, .withdrawal_s = 400,
				    .mucosa_seen = 0.95 };
	const struct metrics_result *ms[3] = { &m, NULL, &m };
	const char *cases[3];
	struct coursefile_progress p[COURSEFILE_MAX_CASES];
	char err[512], text[128];

	if (coursefile_load(&c, fuzz_file(data, size), err, sizeof(err))) {
		return 0;
	}
	for (size_t k = 0; k < c.n_cases; k++) {
		for (size_t i = 0; i < c.cases[k].n_reqs; i++) {
			coursefile_req_text(&c.cases[k].req[i], text,
					    sizeof(text));
		}
		(void)coursefile_passed(&c.cases[k], &m);
	}
	cases[0] = cases[1] = c.cases[0].name;
	cases[2] = c.cases[c.n_cases - 1].name;
	coursefile_progress(&c, cases, ms, 3, p);
	(void)coursefile_complete(&c, p);
	return 0;
}
