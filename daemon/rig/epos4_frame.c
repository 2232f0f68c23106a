/* epos4_frame.c - see epos4_frame.h. */
#include "rig/epos4_frame.h"

#include <errno.h>
#include <string.h>

enum { WAIT_DLE, WAIT_STX, BODY };

static uint16_t crc_word(uint16_t crc, uint16_t word)
{
	for (uint16_t bit = 0x8000; bit; bit >>= 1) {
		uint16_t carry = crc & 0x8000;

		crc = (uint16_t)(crc << 1);
		if (word & bit) {
			crc++;
		}
		if (carry) {
			crc ^= 0x1021;
		}
	}
	return crc;
}

uint16_t epos4_frame_crc(uint8_t opcode, uint8_t len_words,
			 const uint8_t *data)
{
	uint16_t crc = crc_word(0, (uint16_t)(len_words << 8 | opcode));

	for (size_t i = 0; i < (size_t)len_words * 2; i += 2) {
		crc = crc_word(crc, (uint16_t)(data[i] | data[i + 1] << 8));
	}
	return crc_word(crc, 0);
}

/* Appends BYTE, doubled when it is a DLE. False when OUT is full. */
static bool put(uint8_t *out, size_t size, size_t *n, uint8_t byte)
{
	size_t need = byte == EPOS4_DLE ? 2 : 1;

	if (*n + need > size) {
		return false;
	}
	out[(*n)++] = byte;
	if (need == 2) {
		out[(*n)++] = byte;
	}
	return true;
}

size_t epos4_frame_encode(const struct epos4_frame *f, uint8_t *out,
			  size_t size)
{
	size_t len = (size_t)f->len_words * 2;
	uint16_t crc;
	size_t n = 2;
	bool ok;

	if (len > EPOS4_FRAME_MAX_DATA || size < 2) {
		return 0;
	}
	crc = epos4_frame_crc(f->opcode, f->len_words, f->data);
	out[0] = EPOS4_DLE;
	out[1] = EPOS4_STX;
	ok = put(out, size, &n, f->opcode) && put(out, size, &n, f->len_words);
	for (size_t i = 0; ok && i < len; i++) {
		ok = put(out, size, &n, f->data[i]);
	}
	ok = ok && put(out, size, &n, (uint8_t)crc) &&
	     put(out, size, &n, (uint8_t)(crc >> 8));
	return ok ? n : 0;
}

void epos4_decoder_reset(struct epos4_decoder *d)
{
	d->state = WAIT_DLE;
	d->dle = false;
	d->n = 0;
}

bool epos4_decoder_busy(const struct epos4_decoder *d)
{
	return d->state != WAIT_DLE;
}

/* A body byte, unstuffed. Returns 1 when the frame is complete. */
static int body_byte(struct epos4_decoder *d, uint8_t byte,
		     struct epos4_frame *f)
{
	size_t total;
	uint16_t crc;

	d->body[d->n++] = byte;
	total = d->n >= 2 ? 2 + (size_t)d->body[1] * 2 + 2 : SIZE_MAX;
	if (d->n < total) {
		return 0;
	}
	f->opcode = d->body[0];
	f->len_words = d->body[1];
	memcpy(f->data, d->body + 2, (size_t)f->len_words * 2);
	crc = (uint16_t)(d->body[total - 2] | d->body[total - 1] << 8);
	epos4_decoder_reset(d);
	return crc == epos4_frame_crc(f->opcode, f->len_words, f->data)
		       ? 1
		       : -EBADMSG;
}

/* A byte after an unpaired DLE inside a body. */
static int after_dle(struct epos4_decoder *d, uint8_t byte,
		     struct epos4_frame *f)
{
	d->dle = false;
	if (byte == EPOS4_DLE) {
		return body_byte(d, byte, f);
	}
	if (byte == EPOS4_STX) {
		/* a new frame starts: the one being read was cut short */
		d->n = 0;
		return -EPROTO;
	}
	epos4_decoder_reset(d);
	return -EPROTO;
}

int epos4_decoder_feed(struct epos4_decoder *d, uint8_t byte,
		       struct epos4_frame *f)
{
	switch (d->state) {
	case WAIT_DLE:
		if (byte == EPOS4_DLE) {
			d->state = WAIT_STX;
		}
		return 0;
	case WAIT_STX:
		d->state = byte == EPOS4_STX ? BODY
			   : byte == EPOS4_DLE ? WAIT_STX : WAIT_DLE;
		d->n = 0;
		return 0;
	default:
		if (d->dle) {
			return after_dle(d, byte, f);
		}
		if (byte == EPOS4_DLE) {
			d->dle = true;
			return 0;
		}
		return body_byte(d, byte, f);
	}
}

int epos4_frame_decode(const uint8_t *buf, size_t len, struct epos4_frame *f)
{
	struct epos4_decoder d;
	int r;

	epos4_decoder_reset(&d);
	for (size_t i = 0; i < len; i++) {
		r = epos4_decoder_feed(&d, buf[i], f);
		if (r) {
			return r > 0 ? 0 : r;
		}
	}
	return -EAGAIN;
}

/* --- the services ---------------------------------------------------- */

static void put_le(uint8_t *p, uint32_t v, int bytes)
{
	for (int i = 0; i < bytes; i++) {
		p[i] = (uint8_t)(v >> (8 * i));
	}
}

static uint32_t get_le(const uint8_t *p, int bytes)
{
	uint32_t v = 0;

	for (int i = 0; i < bytes; i++) {
		v |= (uint32_t)p[i] << (8 * i);
	}
	return v;
}

/* Node, index, subindex: the first 4 data bytes of both requests. */
static void address(struct epos4_frame *f, uint8_t node, uint16_t index,
		    uint8_t subindex)
{
	f->data[0] = node;
	put_le(f->data + 1, index, 2);
	f->data[3] = subindex;
}

void epos4_read_request(struct epos4_frame *f, uint8_t node, uint16_t index,
			uint8_t subindex)
{
	f->opcode = EPOS4_OP_READ_OBJECT;
	f->len_words = 2;
	address(f, node, index, subindex);
}

void epos4_write_request(struct epos4_frame *f, uint8_t node, uint16_t index,
			 uint8_t subindex, uint32_t value)
{
	f->opcode = EPOS4_OP_WRITE_OBJECT;
	f->len_words = 4;
	address(f, node, index, subindex);
	put_le(f->data + 4, value, 4);
}

void epos4_response(struct epos4_frame *f, uint32_t abort, bool with_value,
		    uint32_t value)
{
	f->opcode = EPOS4_OP_RESPONSE;
	f->len_words = with_value ? 4 : 2;
	put_le(f->data, abort, 4);
	if (with_value) {
		put_le(f->data + 4, value, 4);
	}
}

int epos4_parse_request(const struct epos4_frame *f, uint8_t *opcode,
			uint8_t *node, uint16_t *index, uint8_t *subindex,
			uint32_t *value)
{
	if (!((f->opcode == EPOS4_OP_READ_OBJECT && f->len_words == 2) ||
	      (f->opcode == EPOS4_OP_WRITE_OBJECT && f->len_words == 4))) {
		return -EPROTO;
	}
	*opcode = f->opcode;
	*node = f->data[0];
	*index = (uint16_t)get_le(f->data + 1, 2);
	*subindex = f->data[3];
	*value = f->opcode == EPOS4_OP_WRITE_OBJECT ? get_le(f->data + 4, 4)
						    : 0;
	return 0;
}

int epos4_parse_response(const struct epos4_frame *f, uint8_t request_op,
			 uint32_t *abort, uint32_t *value)
{
	bool with_value = request_op == EPOS4_OP_READ_OBJECT;
	bool full, refused;

	if (f->opcode != EPOS4_OP_RESPONSE || f->len_words < 2) {
		return -EPROTO;
	}
	*abort = get_le(f->data, 4);
	full = f->len_words == (with_value ? 4 : 2);
	/* a refused read may come back without its value */
	refused = with_value && *abort && f->len_words == 2;
	if (!full && !refused) {
		return -EPROTO;
	}
	*value = f->len_words == 4 ? get_le(f->data + 4, 4) : 0;
	return 0;
}
