/* sound.c - see sound.h. */
#include "viewer/sound.h"

#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <AL/al.h>
#include <AL/alc.h>

#include "base/mono.h"
#include "viewer/wav.h"

#define MAX_CLIPS 16
#define MAX_WAV_BYTES (8u << 20)

struct sound {
	ALCdevice *device;
	ALCcontext *context;
	ALuint source;
	ALuint buffer[MAX_CLIPS];
	int clips;
	uint64_t open_ns;
};

/* PATH mapped read-only, its size in N; NULL with errno. */
static unsigned char *map_file(const char *path, size_t *n)
{
	int fd = open(path, O_RDONLY | O_CLOEXEC);
	struct stat sb;
	void *p = MAP_FAILED;

	if (fd < 0) {
		return NULL;
	}
	if (fstat(fd, &sb) == 0 && sb.st_size > 0 &&
	    (size_t)sb.st_size <= MAX_WAV_BYTES) {
		*n = (size_t)sb.st_size;
		p = mmap(NULL, *n, PROT_READ, MAP_PRIVATE, fd, 0);
	} else {
		errno = EFBIG;
	}
	close(fd);
	return p == MAP_FAILED ? NULL : p;
}

static ALenum al_format(const struct wav_pcm *pcm)
{
	if (pcm->channels == 1) {
		return pcm->bits == 8 ? AL_FORMAT_MONO8 : AL_FORMAT_MONO16;
	}
	return pcm->bits == 8 ? AL_FORMAT_STEREO8 : AL_FORMAT_STEREO16;
}

/* DIR/NAME.wav into buffer B; 0 or -1 with ERR said. */
static int load_clip(ALuint b, const char *dir, const char *name, char *err,
		     size_t size)
{
	char path[4096];
	struct wav_pcm pcm;
	unsigned char *buf;
	size_t n = 0;
	int r;

	snprintf(path, sizeof(path), "%s/%s.wav", dir, name);
	buf = map_file(path, &n);
	if (!buf) {
		snprintf(err, size, "%s: %s", path, strerror(errno));
		return -1;
	}
	r = wav_parse(buf, n, &pcm);
	if (r) {
		snprintf(err, size, "%s: not a WAV file of PCM", path);
	} else {
		alBufferData(b, al_format(&pcm), pcm.data, (ALsizei)pcm.bytes,
			     (ALsizei)pcm.rate_hz);
		r = alGetError() == AL_NO_ERROR ? 0 : -1;
		if (r) {
			snprintf(err, size, "%s: OpenAL took no buffer", path);
		}
	}
	munmap(buf, n);
	return r ? -1 : 0;
}

/* The device, its context and the source into S; 0 or -1. */
static int open_device(struct sound *s, char *err, size_t size)
{
	s->device = alcOpenDevice(NULL);
	if (!s->device) {
		snprintf(err, size, "no audio device");
		return -1;
	}
	s->open_ns = mono_ns();
	s->context = alcCreateContext(s->device, NULL);
	if (!s->context || !alcMakeContextCurrent(s->context)) {
		snprintf(err, size, "no OpenAL context on the audio device");
		return -1;
	}
	alGetError();
	alGenSources(1, &s->source);
	alGenBuffers(s->clips, s->buffer);
	if (alGetError() != AL_NO_ERROR) {
		snprintf(err, size, "no OpenAL source or buffers");
		s->clips = 0;
		return -1;
	}
	return 0;
}

struct sound *sound_create(const char *dir, const char *const names[], int n,
			   char *err, size_t size)
{
	struct sound *s = calloc(1, sizeof(*s));

	if (!s || n < 0 || n > MAX_CLIPS) {
		snprintf(err, size, "%s", s ? "too many clips" :
					      strerror(ENOMEM));
		free(s);
		return NULL;
	}
	s->clips = n;
	if (open_device(s, err, size)) {
		goto fail;
	}
	for (int k = 0; k < n; k++) {
		if (load_clip(s->buffer[k], dir, names[k], err, size)) {
			goto fail;
		}
	}
	return s;
fail:
	sound_destroy(s);
	return NULL;
}

void sound_destroy(struct sound *s)
{
	if (!s) {
		return;
	}
	if (s->context) {
		if (s->source) {
			alSourceStop(s->source);
			alSourcei(s->source, AL_BUFFER, 0);
			alDeleteSources(1, &s->source);
		}
		if (s->clips) {
			alDeleteBuffers(s->clips, s->buffer);
		}
		alcMakeContextCurrent(NULL);
		alcDestroyContext(s->context);
	}
	if (s->device) {
		alcCloseDevice(s->device);
	}
	free(s);
}

void sound_play(struct sound *s, int k)
{
	if (!s || k < 0 || k >= s->clips) {
		return;
	}
	alSourceStop(s->source);
	alSourcei(s->source, AL_BUFFER, (ALint)s->buffer[k]);
	alSourcePlay(s->source);
}

double sound_time_s(const struct sound *s)
{
	return s ? (double)(mono_ns() - s->open_ns) / 1e9 : 0;
}
