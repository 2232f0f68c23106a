/*
 * fuzz_session - libFuzzer target: a session file on arbitrary contents,
 * as `endoctl session show/export/report` and `endoview --replay` meet a
 * damaged or hostile one: the reader (frames, CRCs, record sizes, the
 * SHAPE frames' counts), the header's keys, a seek, the shape shown then,
 * and the END frame's metrics parsed back.
 */
#include <stdint.h>

#include "fuzz_file.h"
#include "session/metrics.h"
#include "session/metricstext.h"
#include "proto/session_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct session_shape shape;
	static struct endosim_state st;
	struct metrics_result m;
	struct session_file f;
	char v[64];

	if (session_file_read(fuzz_file(data, size), &f) != 0) {
		return 0;
	}
	session_text_get(f.header, "record_size", v, sizeof(v));
	session_text_get(f.header, "trainee", v, sizeof(v));
	if (f.n_records) {
		session_file_seek(&f, f.records[f.n_records / 2].stamp_ns);
	}
	if (f.n_shapes) {
		session_file_shape(&f, session_file_seek_shape(&f, UINT64_MAX / 2),
				   &shape);
		session_shape_to_state(&shape, &st);
	}
	if (f.end) {
		metricstext_parse(f.end, &m);
	}
	session_file_close(&f);
	return 0;
}
