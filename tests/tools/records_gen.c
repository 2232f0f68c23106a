/*
 * records_gen - a session directory for the records' scale bench
 * (tests/bench/records.sh, issue 24): SESSIONS session files of TRAINEES
 * trainees in DIR, each a HEADER (its ID, the trainee "trainee-NN" in
 * turn, the normal or the polyps case in turn, a start a minute after the
 * one before) and an END frame of measures that vary from session to
 * session, as the recorder writes them; no records between (the records
 * read a session's header and END frame, not its cycles).
 *
 *   records_gen DIR SESSIONS TRAINEES
 */
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "proto/session_file.h"
#include "session/metricstext.h"

/* Session ID's END frame: measures that move with the session's place in
 * its trainee's course (a learning curve of sorts). */
static void measures(unsigned long id, unsigned long trainees,
		     struct metrics_result *m)
{
	double k = (double)(id / trainees); /* the trainee's k-th session */

	*m = (struct metrics_result){
		.cecum_s = 300 + 600 / (1 + k / 10) + (double)(id % 7),
		.withdrawal_s = 240 + (double)(id % 180),
		.duration_s = 900,
		.mucosa_seen = 0.6 + 0.35 * k / (k + 20),
		.records = 900000,
		.force_episodes = (uint32_t)(id % 4),
		.loop_episodes = (uint32_t)(id % 3),
		.pain_share = 0.2 / (1 + k / 5),
		.polyps_seen = (uint32_t)(id % 6),
	};
}

static int write_session(const char *dir, unsigned long id,
			 unsigned long trainees)
{
	char path[4200], header[256], end[4096];
	struct metrics_result m;
	int fd, n, e;

	snprintf(path, sizeof(path), "%s/%lu.endoses", dir, id);
	n = snprintf(header, sizeof(header), "format=1\nid=%lu\n"
		     "trainee=trainee-%02lu\ncase=%s\n"
		     "started=2026-%02lu-%02luT%02lu:%02lu:00Z\n", id,
		     id % trainees, id % 2 ? "polyps" : "normal",
		     1 + id / 44640 % 12, 1 + id / 1440 % 28, id / 60 % 24,
		     id % 60);
	measures(id, trainees, &m);
	fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
	if (fd < 0) {
		perror(path);
		return -1;
	}
	e = session_file_write_magic(fd);
	e = e ? e : session_file_write_frame(fd, SESSION_FRAME_HEADER, header,
					     (uint32_t)n);
	n = metricstext_format(&m, end, sizeof(end));
	e = e || n <= 0 ? -1 : session_file_write_frame(fd, SESSION_FRAME_END,
							 end, (uint32_t)n);
	if (close(fd) || e) {
		fprintf(stderr, "records_gen: %s: cannot write it\n", path);
		return -1;
	}
	return 0;
}

int main(int argc, char **argv)
{
	unsigned long sessions, trainees;

	if (argc != 4 || !(sessions = strtoul(argv[2], NULL, 10)) ||
	    !(trainees = strtoul(argv[3], NULL, 10))) {
		fprintf(stderr, "usage: records_gen DIR SESSIONS TRAINEES\n");
		return 2;
	}
	if (mkdir(argv[1], 0755) && access(argv[1], W_OK)) {
		perror(argv[1]);
		return 1;
	}
	for (unsigned long id = 1; id <= sessions; id++) {
		if (write_session(argv[1], id, trainees)) {
			return 1;
		}
	}
	return 0;
}
