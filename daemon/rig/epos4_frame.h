/*
 * epos4_frame.h - the maxon EPOS4 USB/RS-232 frame protocol (EPOS4
 * Communication Guide, "USB & RS232 communication"): framing, byte
 * stuffing, CRC, and the ReadObject/WriteObject services.
 *
 *   DLE 0x90 | STX 0x02 | OpCode | Len (16-bit words) | Data (Len words) | CRC
 *
 * Multi-byte values are little-endian. Every 0x90 after STX (in OpCode, Len,
 * Data and CRC) is sent twice. The CRC is CRC-CCITT (polynomial 0x1021,
 * initial value 0) over the words [(Len << 8) | OpCode, data words...,
 * 0x0000], each word fed high bit first, before stuffing.
 *
 * Both ends use this module: the daemon's epos4-usb backend (requests out,
 * responses in) and the EPOS4 emulator (the reverse). Pure computation: no
 * allocation, no I/O, safe in any thread.
 */
#ifndef ENDOSIM_EPOS4_FRAME_H
#define ENDOSIM_EPOS4_FRAME_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define EPOS4_DLE 0x90
#define EPOS4_STX 0x02

#define EPOS4_OP_RESPONSE 0x00
#define EPOS4_OP_READ_OBJECT 0x60
#define EPOS4_OP_WRITE_OBJECT 0x68

/* Longest data, bytes: Len is one byte of words (the services use 8). */
#define EPOS4_FRAME_MAX_DATA 510
/* Longest encoded frame: DLE STX, then every byte stuffed at worst. */
#define EPOS4_FRAME_MAX_BYTES (2 + 2 * (2 + EPOS4_FRAME_MAX_DATA + 2))

struct epos4_frame {
	uint8_t opcode;
	uint8_t len_words;                   /* data length in 16-bit words */
	uint8_t data[EPOS4_FRAME_MAX_DATA];  /* 2 * len_words bytes used */
};

/* The CRC of a frame's OpCode, Len and data (2 * LEN_WORDS bytes). */
uint16_t epos4_frame_crc(uint8_t opcode, uint8_t len_words,
			 const uint8_t *data);

/*
 * Encodes F into OUT (SIZE bytes; EPOS4_FRAME_MAX_BYTES always suffice).
 * Returns the number of bytes, or 0 when F is too long or OUT too small.
 */
size_t epos4_frame_encode(const struct epos4_frame *f, uint8_t *out,
			  size_t size);

/*
 * A byte-at-a-time decoder for a stream (a USB bulk IN pipe or a serial
 * line). Bytes before a DLE STX are skipped; a new DLE STX inside a frame
 * abandons the frame being read.
 */
struct epos4_decoder {
	int state;
	bool dle;        /* the previous body byte was an unpaired DLE */
	size_t n;        /* body bytes so far (OpCode, Len, data, CRC) */
	uint8_t body[2 + EPOS4_FRAME_MAX_DATA + 2];
};

void epos4_decoder_reset(struct epos4_decoder *d);

/* True when the decoder is inside a frame (some of it received). */
bool epos4_decoder_busy(const struct epos4_decoder *d);

/*
 * Feeds one byte. Returns 0 (more needed), 1 (a frame is complete and in F),
 * or a negative errno, after which the decoder waits for the next DLE STX:
 *   -EBADMSG   the CRC does not match
 *   -EPROTO    a DLE followed by anything but DLE or STX, or a frame cut
 *              short by a new DLE STX
 */
int epos4_decoder_feed(struct epos4_decoder *d, uint8_t byte,
		       struct epos4_frame *f);

/*
 * Decodes the one frame that BUF (LEN bytes) should hold. Returns 0 with F
 * filled, -EAGAIN when BUF ends before the frame does (truncated), or an
 * error of epos4_decoder_feed().
 */
int epos4_frame_decode(const uint8_t *buf, size_t len, struct epos4_frame *f);

/* --- the services ---------------------------------------------------- */

/* ReadObject request: NODE, INDEX, SUBINDEX. */
void epos4_read_request(struct epos4_frame *f, uint8_t node, uint16_t index,
			uint8_t subindex);

/* WriteObject request: NODE, INDEX, SUBINDEX, VALUE (4 bytes). */
void epos4_write_request(struct epos4_frame *f, uint8_t node, uint16_t index,
			 uint8_t subindex, uint32_t value);

/*
 * The response to a request: ABORT (a CiA 301 SDO abort code, 0: success)
 * and, for a ReadObject (WITH_VALUE), the 4-byte VALUE.
 */
void epos4_response(struct epos4_frame *f, uint32_t abort, bool with_value,
		    uint32_t value);

/*
 * Parses a request. Returns 0 with the fields filled (VALUE only for a
 * WriteObject), or -EPROTO for an unknown OpCode or a wrong Len.
 */
int epos4_parse_request(const struct epos4_frame *f, uint8_t *opcode,
			uint8_t *node, uint16_t *index, uint8_t *subindex,
			uint32_t *value);

/*
 * Parses the response to a request with opcode REQUEST_OP. Returns 0 with
 * ABORT and (for a ReadObject) VALUE filled, or -EPROTO when OpCode or Len
 * do not fit a response to that request (a refused ReadObject may come
 * with or without its 4 value bytes).
 */
int epos4_parse_response(const struct epos4_frame *f, uint8_t request_op,
			 uint32_t *abort, uint32_t *value);

#endif
