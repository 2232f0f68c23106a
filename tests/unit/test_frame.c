/* test_frame.c - length-prefixed framing: messages split and joined across
 * reads, truncation, oversize, garbage; and the protocol decoder's answer to
 * garbage. */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "proto/endosim.pb-c.h"
#include "proto/frame.h"

#define MAX_MSG 1024

/* Appends a frame holding LEN bytes of BODY to BUF at *AT. */
static void put_frame(uint8_t *buf, size_t *at, const void *body, size_t len)
{
	frame_put_header(buf + *at, (uint32_t)len);
	memcpy(buf + *at + FRAME_HEADER_BYTES, body, len);
	*at += FRAME_HEADER_BYTES + len;
}

/* Feeds LEN bytes of DATA in pieces of at most CHUNK bytes. */
static void feed(struct frame_rx *rx, const uint8_t *data, size_t len,
		 size_t chunk)
{
	while (len) {
		size_t room, n;
		uint8_t *dst = frame_rx_space(rx, &room);

		n = len < chunk ? len : chunk;
		assert_true(room >= n);
		memcpy(dst, data, n);
		frame_rx_commit(rx, n);
		data += n;
		len -= n;
	}
}

static void test_header_is_little_endian(void **state)
{
	uint8_t hdr[4];

	(void)state;
	frame_put_header(hdr, 0x12345678u);
	assert_int_equal(hdr[0], 0x78);
	assert_int_equal(hdr[1], 0x56);
	assert_int_equal(hdr[2], 0x34);
	assert_int_equal(hdr[3], 0x12);
	assert_int_equal(frame_get_header(hdr), 0x12345678u);
}

static void test_two_messages_in_one_read(void **state)
{
	struct frame_rx rx;
	uint8_t buf[64];
	size_t at = 0, len;
	const uint8_t *msg;

	(void)state;
	assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
	put_frame(buf, &at, "hello", 5);
	put_frame(buf, &at, "world!", 6);
	feed(&rx, buf, at, at);
	assert_int_equal(frame_rx_next(&rx, &msg, &len), 1);
	assert_int_equal(len, 5);
	assert_memory_equal(msg, "hello", 5);
	assert_int_equal(frame_rx_next(&rx, &msg, &len), 1);
	assert_int_equal(len, 6);
	assert_memory_equal(msg, "world!", 6);
	assert_int_equal(frame_rx_next(&rx, &msg, &len), 0);
	assert_int_equal(frame_rx_pending(&rx), 0);
	frame_rx_free(&rx);
}

static void test_one_message_in_many_reads(void **state)
{
	struct frame_rx rx;
	uint8_t buf[MAX_MSG + 8], body[MAX_MSG];
	size_t at = 0, len;
	const uint8_t *msg;

	(void)state;
	for (size_t i = 0; i < sizeof(body); i++) {
		body[i] = (uint8_t)(i * 7);
	}
	assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
	put_frame(buf, &at, body, sizeof(body));
	for (size_t i = 0; i < at; i++) {
		assert_int_equal(frame_rx_next(&rx, &msg, &len), 0);
		feed(&rx, buf + i, 1, 1);
	}
	assert_int_equal(frame_rx_next(&rx, &msg, &len), 1);
	assert_int_equal(len, sizeof(body));
	assert_memory_equal(msg, body, sizeof(body));
	frame_rx_free(&rx);
}

/* A stream of many messages read in odd-sized pieces comes out whole. */
static void test_many_messages_odd_chunks(void **state)
{
	struct frame_rx rx;
	static uint8_t buf[20000];
	size_t at = 0, len, got = 0;
	const uint8_t *msg;

	(void)state;
	assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
	for (int i = 0; i < 100; i++) {
		uint8_t body[150];

		memset(body, i, sizeof(body));
		put_frame(buf, &at, body, (size_t)(i % 150));
	}
	for (size_t off = 0; off < at;) {
		size_t n = at - off < 37 ? at - off : 37;

		feed(&rx, buf + off, n, n);
		off += n;
		while (frame_rx_next(&rx, &msg, &len) == 1) {
			assert_int_equal(len, got % 150);
			for (size_t k = 0; k < len; k++) {
				assert_int_equal(msg[k], (uint8_t)got);
			}
			got++;
		}
	}
	assert_int_equal(got, 100);
	frame_rx_free(&rx);
}

static void test_truncated(void **state)
{
	struct frame_rx rx;
	uint8_t buf[64];
	size_t at = 0, len;
	const uint8_t *msg;

	(void)state;
	assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
	put_frame(buf, &at, "truncated message", 17);
	feed(&rx, buf, at - 3, 64);
	assert_int_equal(frame_rx_next(&rx, &msg, &len), 0);
	assert_int_equal(frame_rx_pending(&rx), at - 3);
	/* a bare partial header too */
	frame_rx_free(&rx);
	assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
	feed(&rx, buf, 2, 2);
	assert_int_equal(frame_rx_next(&rx, &msg, &len), 0);
	assert_int_equal(frame_rx_pending(&rx), 2);
	frame_rx_free(&rx);
}

static void test_oversized(void **state)
{
	struct frame_rx rx;
	uint8_t hdr[4];
	size_t len;
	const uint8_t *msg;

	(void)state;
	assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
	frame_put_header(hdr, MAX_MSG + 1);
	feed(&rx, hdr, 4, 4);
	assert_int_equal(frame_rx_next(&rx, &msg, &len), -EMSGSIZE);
	frame_rx_free(&rx);
	assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
	frame_put_header(hdr, 0xffffffffu);
	feed(&rx, hdr, 4, 4);
	assert_int_equal(frame_rx_next(&rx, &msg, &len), -EMSGSIZE);
	frame_rx_free(&rx);
	/* exactly the limit is fine */
	assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
	frame_put_header(hdr, MAX_MSG);
	feed(&rx, hdr, 4, 4);
	assert_int_equal(frame_rx_next(&rx, &msg, &len), 0);
	frame_rx_free(&rx);
}

static void test_empty_message(void **state)
{
	struct frame_rx rx;
	uint8_t hdr[4];
	size_t len = 99;
	const uint8_t *msg;

	(void)state;
	assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
	frame_put_header(hdr, 0);
	feed(&rx, hdr, 4, 4);
	assert_int_equal(frame_rx_next(&rx, &msg, &len), 1);
	assert_int_equal(len, 0);
	frame_rx_free(&rx);
}

/* Random bytes never overrun the buffer: each header is either a message
 * the receiver hands out within bounds, or -EMSGSIZE. */
static void test_garbage(void **state)
{
	struct frame_rx rx;
	uint8_t junk[4096];
	size_t len;
	const uint8_t *msg;
	int r;

	(void)state;
	srand(42);
	for (int round = 0; round < 200; round++) {
		assert_int_equal(frame_rx_init(&rx, MAX_MSG), 0);
		for (size_t i = 0; i < sizeof(junk); i++) {
			junk[i] = (uint8_t)rand();
		}
		/* small lengths now and then, so some frames complete */
		junk[3] = junk[2] = 0;
		junk[1] &= 1;
		size_t off = 0;

		do {
			size_t room;
			uint8_t *dst = frame_rx_space(&rx, &room);
			size_t n = sizeof(junk) - off < room ? sizeof(junk) - off
							     : room;

			memcpy(dst, junk + off, n);
			frame_rx_commit(&rx, n);
			off += n;
			while ((r = frame_rx_next(&rx, &msg, &len)) == 1) {
				assert_true(len <= MAX_MSG);
				assert_true(msg >= rx.buf);
				assert_true(msg + len <= rx.buf + rx.len);
			}
		} while (r == 0 && off < sizeof(junk));
		assert_true(r == 0 || r == -EMSGSIZE);
		frame_rx_free(&rx);
	}
}

/* The request decoder refuses garbage and truncation (NULL), and decodes a
 * real request whole. */
static void test_request_decoder(void **state)
{
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__SetParam sp = ENDOSIM__SET_PARAM__INIT;
	Endosim__Request *out;
	uint8_t buf[256];
	size_t len;

	(void)state;
	req.version = 1;
	req.seq = 77;
	req.body_case = ENDOSIM__REQUEST__BODY_SET_PARAM;
	sp.key = "limits.insertion_max_force_n";
	sp.value = "30";
	req.set_param = &sp;
	len = endosim__request__pack(&req, buf);
	out = endosim__request__unpack(NULL, len, buf);
	assert_non_null(out);
	assert_int_equal(out->seq, 77);
	assert_string_equal(out->set_param->value, "30");
	endosim__request__free_unpacked(out, NULL);
	assert_null(endosim__request__unpack(NULL, len - 3, buf));
	memset(buf, 0xff, sizeof(buf));
	assert_null(endosim__request__unpack(NULL, sizeof(buf), buf));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_header_is_little_endian),
		cmocka_unit_test(test_two_messages_in_one_read),
		cmocka_unit_test(test_one_message_in_many_reads),
		cmocka_unit_test(test_many_messages_odd_chunks),
		cmocka_unit_test(test_truncated),
		cmocka_unit_test(test_oversized),
		cmocka_unit_test(test_empty_message),
		cmocka_unit_test(test_garbage),
		cmocka_unit_test(test_request_decoder),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
