/*
 * session_shapes - a session file's SHAPE frames, for the tests of the
 * rod model's recording:
 *
 *   session_shapes FILE
 *
 * prints "records N FIRST LAST FIRST_NS LAST_NS" (the RECORDs' count, the
 * first's and the last's cycle and time stamp), then one line per SHAPE
 * frame, in the file's order: "shape CYCLE
 * STAMP_NS POINTS NODES BYTES" (BYTES: its payload's length).
 *
 * Exit status: 0, 1 when the file does not read (said on stderr), 2 usage.
 */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "proto/session_file.h"

int main(int argc, char **argv)
{
	static struct session_shape s;
	const struct session_record *a, *b;
	struct session_file f;
	int r;

	if (argc != 2) {
		fprintf(stderr, "usage: session_shapes FILE\n");
		return 2;
	}
	r = session_file_read(argv[1], &f);
	if (r) {
		fprintf(stderr, "session_shapes: %s: %s\n", argv[1],
			strerror(-r));
		return 1;
	}
	if (!f.n_records) {
		fprintf(stderr, "session_shapes: %s: no record\n", argv[1]);
		session_file_close(&f);
		return 1;
	}
	a = f.records;
	b = f.records + f.n_records - 1;
	printf("records %zu %" PRIu64 " %" PRIu64 " %" PRIu64 " %" PRIu64
	       "\n", f.n_records, a->cycle, b->cycle, a->stamp_ns, b->stamp_ns);
	for (size_t i = 0; i < f.n_shapes; i++) {
		session_file_shape(&f, i, &s);
		printf("shape %" PRIu64 " %" PRIu64 " %u %u %u\n", s.cycle,
		       s.stamp_ns, s.points, s.nodes, f.shapes[i].length);
	}
	session_file_close(&f);
	return 0;
}
