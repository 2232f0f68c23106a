/*
 * wav.h - the samples of a WAV file (the voice's clips, sound.h), as
 * espeak-ng and most writers make them: RIFF, WAVE, a "fmt " chunk of
 * PCM (format 1) of 8 or 16 bits, 1 or 2 channels, then a "data" chunk;
 * other chunks are skipped. A data chunk whose size runs past the end
 * (a writer that never went back to fill it in) is cut to what is
 * there, in whole frames.
 *
 * Pure computation, no allocation; any thread.
 */
#ifndef ENDOVIEW_WAV_H
#define ENDOVIEW_WAV_H

#include <stddef.h>
#include <stdint.h>

/* A WAV file's samples, pointing into its bytes. */
struct wav_pcm {
	const unsigned char *data;
	size_t bytes;        /* whole frames, > 0 */
	unsigned int channels, bits, rate_hz;
};

/* The samples of the N bytes at BUF into OUT: 0, or -EINVAL for what is
 * not such a file (OUT then zero). */
int wav_parse(const unsigned char *buf, size_t n, struct wav_pcm *out);

#endif
