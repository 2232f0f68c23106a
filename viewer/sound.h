/*
 * sound.h - the patient's voice played (voice.h says which clip): short
 * clips from WAV files through OpenAL (Debian's libopenal, OpenAL Soft),
 * one at a time.
 *
 * The clips are the build's (the Makefile's voice rule: espeak-ng
 * speaking a line of text into DIR/NAME.wav), read by wav.h. A new
 * clip cuts the one playing short. OpenAL Soft mixes in a
 * thread of its own: playing never blocks the frame.
 *
 * Where there is no audio device (a headless machine, a container)
 * sound_create() fails and says why: the caller goes on silent. Under
 * test, OpenAL Soft's wave-file backend (ALSOFT_DRIVERS=wave, and
 * ALSOFT_CONF naming a file with "[wave]" "file = OUT.wav") records what
 * was played, in real time from the device's opening.
 *
 * Main thread.
 */
#ifndef ENDOVIEW_SOUND_H
#define ENDOVIEW_SOUND_H

#include <stddef.h>

struct sound;

/*
 * Opens the default audio device and loads DIR/NAMES[k].wav for k below
 * N as clip k. NULL, with why in ERR (SIZE bytes): no device, no memory,
 * a clip missing or not a WAV file of PCM.
 */
struct sound *sound_create(const char *dir, const char *const names[], int n,
			   char *err, size_t size);

/* NULL is fine; closes the device (the wave backend then completes its
 * file). */
void sound_destroy(struct sound *s);

/* Plays clip K (as sound_create() numbered them), cutting the one
 * playing short; any other K, or S NULL: nothing. */
void sound_play(struct sound *s, int k);

/* Seconds since the device opened (the wave file's time); 0 for NULL. */
double sound_time_s(const struct sound *s);

#endif
