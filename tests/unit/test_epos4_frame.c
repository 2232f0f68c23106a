/*
 * test_epos4_frame.c - the EPOS4 frame codec: CRC against an independent
 * CRC-16/XMODEM, byte stuffing of 0x90 wherever it appears (length, data,
 * CRC), the services' layouts, and refusal of truncated, corrupted and
 * badly stuffed frames.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "rig/epos4_frame.h"

/* CRC-16/XMODEM (poly 0x1021, init 0, no reflection), byte-wise. */
static uint16_t xmodem(const uint8_t *p, size_t n)
{
	uint16_t crc = 0;

	for (size_t i = 0; i < n; i++) {
		crc ^= (uint16_t)(p[i] << 8);
		for (int b = 0; b < 8; b++) {
			crc = crc & 0x8000 ? (uint16_t)(crc << 1 ^ 0x1021)
					   : (uint16_t)(crc << 1);
		}
	}
	return crc;
}

/* The EPOS4 CRC by its definition: words high byte first, 0 appended. */
static uint16_t reference_crc(const struct epos4_frame *f)
{
	uint8_t seq[2 + EPOS4_FRAME_MAX_DATA];
	size_t n = 0;

	seq[n++] = f->len_words;
	seq[n++] = f->opcode;
	for (size_t i = 0; i < (size_t)f->len_words * 2; i += 2) {
		seq[n++] = f->data[i + 1];
		seq[n++] = f->data[i];
	}
	return xmodem(seq, n);
}

static void test_xmodem_check_value(void **state)
{
	(void)state;
	assert_int_equal(xmodem((const uint8_t *)"123456789", 9), 0x31C3);
}

static void test_crc_matches_definition(void **state)
{
	struct epos4_frame f;

	(void)state;
	epos4_read_request(&f, 1, 0x6041, 0);
	assert_int_equal(epos4_frame_crc(f.opcode, f.len_words, f.data),
			 reference_crc(&f));
	for (uint32_t v = 0; v < 5000; v += 7) {
		epos4_write_request(&f, 1, 0x6071, 0, v * 2654435761u);
		assert_int_equal(epos4_frame_crc(f.opcode, f.len_words,
						 f.data),
				 reference_crc(&f));
	}
}

static void test_read_request_layout(void **state)
{
	uint8_t buf[EPOS4_FRAME_MAX_BYTES];
	struct epos4_frame f;
	uint16_t crc;
	size_t n;

	(void)state;
	epos4_read_request(&f, 1, 0x6041, 0);
	n = epos4_frame_encode(&f, buf, sizeof(buf));
	crc = reference_crc(&f);
	assert_int_equal(n, 10);
	uint8_t want[] = { 0x90, 0x02, 0x60, 0x02, 0x01, 0x41, 0x60, 0x00,
			   (uint8_t)crc, (uint8_t)(crc >> 8) };
	assert_memory_equal(buf, want, sizeof(want));
}

static void test_write_request_layout(void **state)
{
	struct epos4_frame f;
	uint8_t op, node, sub;
	uint16_t index;
	uint32_t value;

	(void)state;
	epos4_write_request(&f, 3, 0x6071, 0, 0xFFFFFF9C);
	assert_int_equal(f.opcode, EPOS4_OP_WRITE_OBJECT);
	assert_int_equal(f.len_words, 4);
	uint8_t want[] = { 0x03, 0x71, 0x60, 0x00, 0x9C, 0xFF, 0xFF, 0xFF };
	assert_memory_equal(f.data, want, sizeof(want));
	assert_int_equal(epos4_parse_request(&f, &op, &node, &index, &sub,
					     &value), 0);
	assert_int_equal(op, EPOS4_OP_WRITE_OBJECT);
	assert_int_equal(node, 3);
	assert_int_equal(index, 0x6071);
	assert_int_equal(sub, 0);
	assert_int_equal(value, 0xFFFFFF9C);
}

/* Count of 0x90 bytes in the encoded body (after DLE STX). */
static int dles(const uint8_t *buf, size_t n)
{
	int c = 0;

	for (size_t i = 2; i < n; i++) {
		c += buf[i] == EPOS4_DLE;
	}
	return c;
}

static void roundtrip(const struct epos4_frame *f)
{
	uint8_t buf[EPOS4_FRAME_MAX_BYTES];
	struct epos4_frame out;
	size_t n = epos4_frame_encode(f, buf, sizeof(buf));

	assert_true(n > 0);
	assert_int_equal(epos4_frame_decode(buf, n, &out), 0);
	assert_int_equal(out.opcode, f->opcode);
	assert_int_equal(out.len_words, f->len_words);
	assert_memory_equal(out.data, f->data, (size_t)f->len_words * 2);
}

static void test_stuffing_in_data(void **state)
{
	uint8_t buf[EPOS4_FRAME_MAX_BYTES];
	struct epos4_frame f;
	size_t n;

	(void)state;
	epos4_write_request(&f, 0x90, 0x9090, 0x90, 0x90909090);
	n = epos4_frame_encode(&f, buf, sizeof(buf));
	/* 8 data bytes of 0x90 doubled; nothing else may be a lone DLE */
	assert_true(dles(buf, n) >= 16);
	assert_int_equal(dles(buf, n) % 2, 0);
	assert_int_equal(n, 2 + 2 + 16 + 2 + (size_t)(dles(buf, n) - 16) / 2);
	roundtrip(&f);
}

static void test_stuffing_in_length(void **state)
{
	uint8_t buf[EPOS4_FRAME_MAX_BYTES];
	struct epos4_frame f = { .opcode = 0x11, .len_words = 0x90 };
	size_t n;

	(void)state;
	for (size_t i = 0; i < 2 * 0x90; i++) {
		f.data[i] = (uint8_t)(i % 0x80);
	}
	n = epos4_frame_encode(&f, buf, sizeof(buf));
	assert_int_equal(buf[3], 0x90);
	assert_int_equal(buf[4], 0x90);
	assert_int_equal(buf[5], 0x00);
	roundtrip(&f);
	assert_true(n > 4 + 2 * 0x90);
}

static void test_stuffing_in_crc(void **state)
{
	uint8_t buf[EPOS4_FRAME_MAX_BYTES];
	struct epos4_frame f;
	uint16_t crc;
	int found = 0;
	size_t n;

	(void)state;
	for (uint32_t v = 0; v < 100000 && found < 2; v++) {
		epos4_write_request(&f, 1, 0x6071, 0, v);
		crc = epos4_frame_crc(f.opcode, f.len_words, f.data);
		if ((uint8_t)crc != 0x90 && (uint8_t)(crc >> 8) != 0x90) {
			continue;
		}
		found++;
		n = epos4_frame_encode(&f, buf, sizeof(buf));
		/* the CRC is last: its 0x90 byte(s) doubled there */
		assert_true(buf[n - 1] == 0x90 || buf[n - 2] == 0x90);
		assert_int_equal(n, 2 + 2 + 8 + 2 + (size_t)dles(buf, n) / 2);
		roundtrip(&f);
	}
	assert_int_equal(found, 2);
}

static void test_truncated_refused(void **state)
{
	uint8_t buf[EPOS4_FRAME_MAX_BYTES];
	struct epos4_frame f, out;
	size_t n;

	(void)state;
	epos4_write_request(&f, 1, 0x9090, 0x90, 0x12903490);
	n = epos4_frame_encode(&f, buf, sizeof(buf));
	for (size_t cut = 0; cut < n; cut++) {
		assert_int_equal(epos4_frame_decode(buf, cut, &out), -EAGAIN);
	}
	assert_int_equal(epos4_frame_decode(buf, n, &out), 0);
}

static void test_corrupted_refused(void **state)
{
	uint8_t buf[EPOS4_FRAME_MAX_BYTES];
	struct epos4_frame f, out;
	size_t n;

	(void)state;
	epos4_read_request(&f, 1, 0x6064, 0);
	n = epos4_frame_encode(&f, buf, sizeof(buf));
	for (size_t i = 2; i < n; i++) {
		for (int bit = 0; bit < 8; bit++) {
			uint8_t bad[EPOS4_FRAME_MAX_BYTES];
			int r;

			memcpy(bad, buf, n);
			bad[i] ^= (uint8_t)(1u << bit);
			r = epos4_frame_decode(bad, n, &out);
			/* never accepted; a changed Len may leave it short */
			assert_true(r == -EBADMSG || r == -EPROTO ||
				    r == -EAGAIN);
		}
	}
}

static void test_bad_stuffing_refused(void **state)
{
	const uint8_t bad[] = { 0x90, 0x02, 0x60, 0x02, 0x90, 0x33, 0x60, 0x00,
				0x00, 0x00, 0x00 };
	struct epos4_frame out;

	(void)state;
	assert_int_equal(epos4_frame_decode(bad, sizeof(bad), &out), -EPROTO);
}

static void test_resync(void **state)
{
	uint8_t buf[2 * EPOS4_FRAME_MAX_BYTES + 8];
	struct epos4_decoder d;
	struct epos4_frame f, g, out;
	size_t n = 0;
	int frames = 0, cut = 0;

	(void)state;
	epos4_read_request(&f, 1, 0x6041, 0);
	epos4_response(&g, 0, true, 0x0237);
	buf[n++] = 0x55; /* noise before the first frame */
	buf[n++] = 0x02;
	n += epos4_frame_encode(&f, buf + n, sizeof(buf) - n) - 3;
	/* ... that frame cut short by the start of the next */
	n += epos4_frame_encode(&g, buf + n, sizeof(buf) - n);
	epos4_decoder_reset(&d);
	for (size_t i = 0; i < n; i++) {
		int r = epos4_decoder_feed(&d, buf[i], &out);

		frames += r > 0;
		cut += r == -EPROTO;
	}
	assert_int_equal(cut, 1);
	assert_int_equal(frames, 1);
	assert_int_equal(out.opcode, EPOS4_OP_RESPONSE);
}

static void test_responses(void **state)
{
	struct epos4_frame f;
	uint32_t abort, value;

	(void)state;
	epos4_response(&f, 0, true, 0x00020192);
	assert_int_equal(epos4_parse_response(&f, EPOS4_OP_READ_OBJECT, &abort,
					      &value), 0);
	assert_int_equal(abort, 0);
	assert_int_equal(value, 0x00020192);
	/* a write's reply to a read is malformed, and the reverse */
	assert_int_equal(epos4_parse_response(&f, EPOS4_OP_WRITE_OBJECT,
					      &abort, &value), -EPROTO);
	epos4_response(&f, 0x06090030, false, 0);
	assert_int_equal(epos4_parse_response(&f, EPOS4_OP_WRITE_OBJECT,
					      &abort, &value), 0);
	assert_int_equal(abort, 0x06090030);
	/* a refused read may come without its value */
	assert_int_equal(epos4_parse_response(&f, EPOS4_OP_READ_OBJECT,
					      &abort, &value), 0);
	epos4_response(&f, 0, false, 0);
	assert_int_equal(epos4_parse_response(&f, EPOS4_OP_READ_OBJECT,
					      &abort, &value), -EPROTO);
	f.opcode = 0x60;
	assert_int_equal(epos4_parse_response(&f, EPOS4_OP_WRITE_OBJECT,
					      &abort, &value), -EPROTO);
}

static void test_unknown_request(void **state)
{
	struct epos4_frame f = { .opcode = 0x11, .len_words = 2 };
	uint8_t op, node, sub;
	uint16_t index;
	uint32_t value;

	(void)state;
	assert_int_equal(epos4_parse_request(&f, &op, &node, &index, &sub,
					     &value), -EPROTO);
	epos4_read_request(&f, 1, 0x6041, 0);
	f.len_words = 3;
	assert_int_equal(epos4_parse_request(&f, &op, &node, &index, &sub,
					     &value), -EPROTO);
}

static void test_encode_needs_room(void **state)
{
	uint8_t buf[9];
	struct epos4_frame f;

	(void)state;
	epos4_read_request(&f, 1, 0x6041, 0);
	assert_int_equal(epos4_frame_encode(&f, buf, sizeof(buf)), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_xmodem_check_value),
		cmocka_unit_test(test_crc_matches_definition),
		cmocka_unit_test(test_read_request_layout),
		cmocka_unit_test(test_write_request_layout),
		cmocka_unit_test(test_stuffing_in_data),
		cmocka_unit_test(test_stuffing_in_length),
		cmocka_unit_test(test_stuffing_in_crc),
		cmocka_unit_test(test_truncated_refused),
		cmocka_unit_test(test_corrupted_refused),
		cmocka_unit_test(test_bad_stuffing_refused),
		cmocka_unit_test(test_resync),
		cmocka_unit_test(test_responses),
		cmocka_unit_test(test_unknown_request),
		cmocka_unit_test(test_encode_needs_room),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
