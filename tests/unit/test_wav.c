/*
 * test_wav.c - the voice's clips read (viewer/wav.h): a PCM file's
 * format and samples; chunks before the samples skipped, a pad byte
 * after an odd one; a data size past the end cut to the whole frames
 * there; what is not PCM of 8 or 16 bits, 1 or 2 channels refused, as
 * are samples before their format; no truncation read past its end.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "viewer/wav.h"

#define MAX_FILE 256

/* A file being made. */
struct file {
	unsigned char b[MAX_FILE];
	size_t n;
};

static void put(struct file *f, const void *p, size_t n)
{
	assert_true(f->n + n <= MAX_FILE);
	memcpy(f->b + f->n, p, n);
	f->n += n;
}

static void put32(struct file *f, uint32_t v)
{
	unsigned char b[4] = { v & 0xff, v >> 8 & 0xff, v >> 16 & 0xff,
			       v >> 24 };

	put(f, b, 4);
}

static void put16(struct file *f, uint16_t v)
{
	unsigned char b[2] = { v & 0xff, v >> 8 };

	put(f, b, 2);
}

/* The header and a fmt chunk of FORMAT, CHANNELS, BITS at 22050 Hz. */
static void head(struct file *f, uint16_t format, uint16_t channels,
		 uint16_t bits)
{
	f->n = 0;
	put(f, "RIFF", 4);
	put32(f, 0); /* the writers' own sizes are not read */
	put(f, "WAVE", 4);
	put(f, "fmt ", 4);
	put32(f, 16);
	put16(f, format);
	put16(f, channels);
	put32(f, 22050);
	put32(f, 22050u * channels * bits / 8);
	put16(f, (uint16_t)(channels * bits / 8));
	put16(f, bits);
}

/* A data chunk saying SIZE bytes, holding N of them (0, 1, 2, ...). */
static void data(struct file *f, uint32_t size, size_t n)
{
	put(f, "data", 4);
	put32(f, size);
	for (size_t k = 0; k < n; k++) {
		unsigned char c = (unsigned char)k;

		put(f, &c, 1);
	}
}

static void mono16(void **state)
{
	struct file f;
	struct wav_pcm p;

	(void)state;
	head(&f, 1, 1, 16);
	data(&f, 20, 20);
	assert_int_equal(wav_parse(f.b, f.n, &p), 0);
	assert_int_equal(p.channels, 1);
	assert_int_equal(p.bits, 16);
	assert_int_equal(p.rate_hz, 22050);
	assert_ptr_equal(p.data, f.b + 44);
	assert_int_equal(p.bytes, 20);
}

/* A LIST chunk of 3 bytes and its pad before the samples: skipped. */
static void other_chunk_skipped(void **state)
{
	struct file f;
	struct wav_pcm p;

	(void)state;
	head(&f, 1, 2, 8);
	put(&f, "LIST", 4);
	put32(&f, 3);
	put(&f, "abc\0", 4);
	data(&f, 6, 6);
	assert_int_equal(wav_parse(f.b, f.n, &p), 0);
	assert_int_equal(p.channels, 2);
	assert_int_equal(p.bits, 8);
	assert_ptr_equal(p.data, f.b + 56);
	assert_int_equal(p.bytes, 6);
}

/* A size never filled in: the whole frames there (4-byte frames). */
static void size_past_the_end_cut(void **state)
{
	struct file f;
	struct wav_pcm p;

	(void)state;
	head(&f, 1, 2, 16);
	data(&f, 0xffffffffu, 23);
	assert_int_equal(wav_parse(f.b, f.n, &p), 0);
	assert_int_equal(p.bytes, 20);
}

static void refused(struct file *f)
{
	struct wav_pcm p;

	assert_int_equal(wav_parse(f->b, f->n, &p), -EINVAL);
	assert_null(p.data);
	assert_int_equal(p.bytes, 0);
}

static void not_pcm_refused(void **state)
{
	struct file f;

	(void)state;
	head(&f, 3, 1, 32); /* float */
	data(&f, 8, 8);
	refused(&f);
	head(&f, 1, 1, 24);
	data(&f, 6, 6);
	refused(&f);
	head(&f, 1, 3, 16);
	data(&f, 6, 6);
	refused(&f);
	head(&f, 1, 1, 16);
	data(&f, 1, 1); /* less than a frame */
	refused(&f);
	head(&f, 1, 1, 16);
	memcpy(f.b + 8, "AVI ", 4);
	data(&f, 2, 2);
	refused(&f);
	f.n = 0; /* the samples before their format */
	put(&f, "RIFF\0\0\0\0WAVE", 12);
	data(&f, 2, 2);
	refused(&f);
}

/* Each of a file's beginnings, in a buffer of its own size (ASan's
 * build: a byte read past it is caught): the samples there, or none. */
static void truncations(void **state)
{
	struct file f;
	struct wav_pcm p;

	(void)state;
	head(&f, 1, 1, 16);
	data(&f, 40, 40);
	for (size_t n = 0; n <= f.n; n++) {
		unsigned char *b = malloc(n ? n : 1);

		assert_non_null(b);
		memcpy(b, f.b, n);
		if (wav_parse(b, n, &p) == 0) {
			assert_true(n >= 46);
			assert_int_equal(p.bytes, (n - 44) / 2 * 2);
		} else {
			assert_true(n < 46);
		}
		free(b);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(mono16),
		cmocka_unit_test(other_chunk_skipped),
		cmocka_unit_test(size_past_the_end_cut),
		cmocka_unit_test(not_pcm_refused),
		cmocka_unit_test(truncations),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
