/* imagescale.c - see imagescale.h. */
#include "viewer/imagescale.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "viewer/gfx.h"

struct imagescale {
	GLuint fbo, colour, depth;
	int w, h;          /* the target's, px */
	bool bound;        /* between begin and end */
	bool failed;       /* a target could not be made: said once */
};

struct imagescale *imagescale_create(void)
{
	return calloc(1, sizeof(struct imagescale));
}

static void drop(struct imagescale *s)
{
	glDeleteFramebuffers(1, &s->fbo);
	glDeleteTextures(1, &s->colour);
	glDeleteRenderbuffers(1, &s->depth);
	s->fbo = s->colour = s->depth = 0;
	s->w = s->h = 0;
}

void imagescale_destroy(struct imagescale *s)
{
	if (!s) {
		return;
	}
	drop(s);
	free(s);
}

double imagescale_for(const char *renderer)
{
	static const char *const software[] = { "llvmpipe", "softpipe",
						"swrast" };

	for (size_t k = 0;
	     renderer && k < sizeof(software) / sizeof(software[0]); k++) {
		if (strstr(renderer, software[k])) {
			return IMAGESCALE_SOFTWARE;
		}
	}
	return 1;
}

/* A target of W x H; false when the driver will not have it. */
static bool make(struct imagescale *s, int w, int h)
{
	if (s->fbo && s->w == w && s->h == h) {
		return true;
	}
	drop(s);
	s->colour = gfx_texture(w, h, 4, NULL, false, false);
	if (!s->colour) {
		return false;
	}
	glBindTexture(GL_TEXTURE_2D, 0);
	glGenRenderbuffers(1, &s->depth);
	glBindRenderbuffer(GL_RENDERBUFFER, s->depth);
	glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
	glBindRenderbuffer(GL_RENDERBUFFER, 0);
	glGenFramebuffers(1, &s->fbo);
	glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
	glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
			       GL_TEXTURE_2D, s->colour, 0);
	glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
				  GL_RENDERBUFFER, s->depth);
	if (glCheckFramebufferStatus(GL_FRAMEBUFFER) !=
	    GL_FRAMEBUFFER_COMPLETE) {
		glBindFramebuffer(GL_FRAMEBUFFER, 0);
		drop(s);
		return false;
	}
	glBindFramebuffer(GL_FRAMEBUFFER, 0);
	s->w = w;
	s->h = h;
	return true;
}

struct endo_rect imagescale_begin(struct imagescale *s, struct endo_rect r,
				  double scale)
{
	int w = (int)lround(r.w * scale), h = (int)lround(r.h * scale);

	s->bound = false;
	if (!(scale < 1) || s->failed || w < 1 || h < 1) {
		return r;
	}
	if (!make(s, w, h)) {
		log_warn("endoscopic image: no offscreen target of %dx%d: "
			 "drawn at full size", w, h);
		s->failed = true;
		return r;
	}
	glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
	s->bound = true;
	return (struct endo_rect){ 0, 0, w, h };
}

void imagescale_end(struct imagescale *s, struct endo_rect r)
{
	if (!s->bound) {
		return;
	}
	glBindFramebuffer(GL_READ_FRAMEBUFFER, s->fbo);
	glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
	glBlitFramebuffer(0, 0, s->w, s->h, r.x, r.y, r.x + r.w, r.y + r.h,
			  GL_COLOR_BUFFER_BIT, GL_LINEAR);
	glBindFramebuffer(GL_FRAMEBUFFER, 0);
	s->bound = false;
}
