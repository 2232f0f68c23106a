/*
 * session_report - the report of a session file, until endoctl's
 * `session report` does the same (report.h):
 *
 *   session_report FILE.endoses DIR
 *
 * recomputes the metrics from the records (sessionmetrics_compute()) with
 * the parameters the file was recorded with (sessioninputs.h), prints
 * them as key=value lines and writes DIR/index.html.
 */
#include <stdio.h>
#include <string.h>

#include "session/metricstext.h"
#include "session/report.h"
#include "session/sessioninputs.h"
#include "session/sessionmetrics.h"

int main(int argc, char **argv)
{
	static char text[1 << 14];
	struct session_file f = { 0 };
	struct metrics_params p;
	struct metrics_result m;
	char err[256] = "";
	int r;

	if (argc != 3) {
		fprintf(stderr, "usage: session_report FILE DIR\n");
		return 2;
	}
	r = session_file_read(argv[1], &f);
	if (r) {
		fprintf(stderr, "session_report: %s: %s\n", argv[1], strerror(-r));
		return 1;
	}
	sessioninputs_file_metrics_params(&f, &p);
	r = sessionmetrics_compute(&f, &p, &m, err, sizeof(err));
	if (err[0]) {
		fprintf(stderr, "session_report: %s\n", err);
	}
	if (!r && metricstext_format(&m, text, sizeof(text)) > 0) {
		fputs(text, stdout);
	}
	r = r ? r : report_write(&f, &m, NULL, argv[2]);
	if (r) {
		fprintf(stderr, "session_report: %s: %s\n", argv[2], strerror(-r));
	}
	session_file_close(&f);
	return r ? 1 : 0;
}
