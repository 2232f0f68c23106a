/*
 * frame.h - length-prefixed framing of protocol messages on a byte stream.
 *
 * On the wire: a 4-byte little-endian length, then that many bytes. The
 * receiver below reassembles messages from reads of any size (one message
 * split over many reads, many messages in one read) into a buffer allocated
 * once, and refuses a length above its limit before reading the body.
 *
 * Not thread-safe: one receiver per connection, used by one thread.
 */
#ifndef ENDOSIM_FRAME_H
#define ENDOSIM_FRAME_H

#include <stddef.h>
#include <stdint.h>

#define FRAME_HEADER_BYTES 4

struct frame_rx {
	uint8_t *buf;     /* FRAME_HEADER_BYTES + max_msg bytes */
	size_t max_msg;   /* largest message body accepted, bytes */
	size_t start;     /* first byte not yet consumed */
	size_t len;       /* bytes held, from buf[0] */
};

/* Allocates the buffer. Returns 0 or -ENOMEM. */
int frame_rx_init(struct frame_rx *rx, size_t max_msg);

/* Frees the buffer; safe on a zeroed or already freed receiver. */
void frame_rx_free(struct frame_rx *rx);

/*
 * Where the next read() may write, and how much room there is (0 only when a
 * complete message is waiting to be taken with frame_rx_next()).
 */
uint8_t *frame_rx_space(struct frame_rx *rx, size_t *room);

/* Records that N bytes were written at frame_rx_space(). */
void frame_rx_commit(struct frame_rx *rx, size_t n);

/*
 * Takes the next complete message. Returns 1 with *MSG and *LEN set (valid
 * until the next call on RX), 0 when more bytes are needed, or -EMSGSIZE when
 * the announced length exceeds max_msg (the stream cannot be resynchronised:
 * close it).
 */
int frame_rx_next(struct frame_rx *rx, const uint8_t **msg, size_t *len);

/* Bytes received but not yet returned as a message (a truncated tail at EOF). */
size_t frame_rx_pending(const struct frame_rx *rx);

/* Writes the 4-byte header for a message of LEN bytes. */
void frame_put_header(uint8_t hdr[FRAME_HEADER_BYTES], uint32_t len);

/* Reads a 4-byte header. */
uint32_t frame_get_header(const uint8_t hdr[FRAME_HEADER_BYTES]);

#endif
