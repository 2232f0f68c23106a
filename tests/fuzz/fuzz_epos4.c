/*
 * fuzz_epos4 - libFuzzer target: the EPOS4 frame decoder (epos4_frame.c)
 * on an arbitrary byte stream, as the USB pipe delivers it: byte by byte
 * through the stream decoder, each frame it completes parsed as a request
 * and as the response to either service, and re-encoded: decoding that
 * again must give the same frame. The whole input once more through the
 * one-frame decoder.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rig/epos4_frame.h"

/* Encoding a decoded frame and decoding it again changes nothing. */
static void round_trip(const struct epos4_frame *f)
{
	uint8_t buf[EPOS4_FRAME_MAX_BYTES];
	struct epos4_frame again;
	size_t n = epos4_frame_encode(f, buf, sizeof(buf));

	if (!n || epos4_frame_decode(buf, n, &again) != 0 ||
	    again.opcode != f->opcode || again.len_words != f->len_words ||
	    memcmp(again.data, f->data, (size_t)f->len_words * 2)) {
		abort();
	}
}

static void parse(const struct epos4_frame *f)
{
	uint32_t abort_code, value;
	uint16_t index;
	uint8_t op, node, sub;

	(void)epos4_parse_request(f, &op, &node, &index, &sub, &value);
	(void)epos4_parse_response(f, EPOS4_OP_READ_OBJECT, &abort_code,
				   &value);
	(void)epos4_parse_response(f, EPOS4_OP_WRITE_OBJECT, &abort_code,
				   &value);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct epos4_decoder dec;
	static struct epos4_frame f;

	epos4_decoder_reset(&dec);
	for (size_t i = 0; i < size; i++) {
		if (epos4_decoder_feed(&dec, data[i], &f) == 1) {
			parse(&f);
			round_trip(&f);
		}
	}
	if (epos4_frame_decode(data, size, &f) == 0) {
		parse(&f);
	}
	return 0;
}
