/* frame.c - see frame.h. */
#include "proto/frame.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

int frame_rx_init(struct frame_rx *rx, size_t max_msg)
{
	rx->buf = malloc(FRAME_HEADER_BYTES + max_msg);
	if (!rx->buf) {
		return -ENOMEM;
	}
	rx->max_msg = max_msg;
	rx->start = 0;
	rx->len = 0;
	return 0;
}

void frame_rx_free(struct frame_rx *rx)
{
	free(rx->buf);
	rx->buf = NULL;
	rx->start = 0;
	rx->len = 0;
}

/* Moves the unconsumed bytes to the front of the buffer. */
static void compact(struct frame_rx *rx)
{
	if (rx->start == 0) {
		return;
	}
	memmove(rx->buf, rx->buf + rx->start, rx->len - rx->start);
	rx->len -= rx->start;
	rx->start = 0;
}

uint8_t *frame_rx_space(struct frame_rx *rx, size_t *room)
{
	compact(rx);
	*room = FRAME_HEADER_BYTES + rx->max_msg - rx->len;
	return rx->buf + rx->len;
}

void frame_rx_commit(struct frame_rx *rx, size_t n)
{
	rx->len += n;
}

int frame_rx_next(struct frame_rx *rx, const uint8_t **msg, size_t *len)
{
	size_t held = rx->len - rx->start;
	uint32_t body;

	if (held < FRAME_HEADER_BYTES) {
		return 0;
	}
	body = frame_get_header(rx->buf + rx->start);
	if (body > rx->max_msg) {
		return -EMSGSIZE;
	}
	if (held < FRAME_HEADER_BYTES + (size_t)body) {
		return 0;
	}
	*msg = rx->buf + rx->start + FRAME_HEADER_BYTES;
	*len = body;
	rx->start += FRAME_HEADER_BYTES + (size_t)body;
	return 1;
}

size_t frame_rx_pending(const struct frame_rx *rx)
{
	return rx->len - rx->start;
}

void frame_put_header(uint8_t hdr[FRAME_HEADER_BYTES], uint32_t len)
{
	hdr[0] = (uint8_t)len;
	hdr[1] = (uint8_t)(len >> 8);
	hdr[2] = (uint8_t)(len >> 16);
	hdr[3] = (uint8_t)(len >> 24);
}

uint32_t frame_get_header(const uint8_t hdr[FRAME_HEADER_BYTES])
{
	return (uint32_t)hdr[0] | (uint32_t)hdr[1] << 8 |
	       (uint32_t)hdr[2] << 16 | (uint32_t)hdr[3] << 24;
}
