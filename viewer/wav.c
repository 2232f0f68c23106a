/* wav.c - see wav.h. */
#include "viewer/wav.h"

#include <errno.h>
#include <stdbool.h>
#include <string.h>

static uint32_t le32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	       (uint32_t)p[3] << 24;
}

static uint16_t le16(const unsigned char *p)
{
	return (uint16_t)(p[0] | p[1] << 8);
}

/* The fmt chunk of SIZE bytes at P into OUT; 0 or -EINVAL. */
static int wav_format(const unsigned char *p, uint32_t size,
		      struct wav_pcm *out)
{
	if (size < 16 || le16(p) != 1) {
		return -EINVAL; /* not PCM */
	}
	out->channels = le16(p + 2);
	out->rate_hz = le32(p + 4);
	out->bits = le16(p + 14);
	if ((out->channels != 1 && out->channels != 2) ||
	    (out->bits != 8 && out->bits != 16) || out->rate_hz == 0) {
		return -EINVAL;
	}
	return 0;
}

/* wav_parse() but for zeroing OUT on a failure. */
static int parse(const unsigned char *buf, size_t n, struct wav_pcm *out)
{
	size_t at = 12, frame;
	bool format = false;

	if (n < 12 || memcmp(buf, "RIFF", 4) || memcmp(buf + 8, "WAVE", 4)) {
		return -EINVAL;
	}
	while (at + 8 <= n) {
		const unsigned char *id = buf + at;
		size_t size = le32(buf + at + 4), left = n - at - 8;

		if (!memcmp(id, "fmt ", 4)) {
			if (size > left || wav_format(id + 8, (uint32_t)size,
						      out)) {
				return -EINVAL;
			}
			format = true;
		} else if (!memcmp(id, "data", 4) && format) {
			frame = out->channels * out->bits / 8;
			out->data = id + 8;
			out->bytes = (size < left ? size : left) / frame *
				     frame;
			return out->bytes ? 0 : -EINVAL;
		}
		at += 8 + size + (size & 1);
	}
	return -EINVAL;
}

int wav_parse(const unsigned char *buf, size_t n, struct wav_pcm *out)
{
	int r = parse(buf, n, out);

	if (r) {
		memset(out, 0, sizeof(*out));
	}
	return r;
}
