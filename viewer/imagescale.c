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
	GLuint program, vao; /* the copy into the window */
	GLint u_from;
	int w, h;          /* the target's, px */
	struct endo_rect from; /* what was drawn in it */
	bool window_depth; /* the window has a depth buffer */
	bool bound;        /* between begin and end */
	bool failed;       /* a target could not be made: said once */
};

/* The target's texture over the viewport, sampled through its filter: a
 * rectangle of two triangles made from the vertex' index (no buffer), an
 * affine texture coordinate over u_from (the drawn part, in the
 * texture's 0..1), no depth, no blending: with the window's depth gone,
 * a fifth to a seventh of the frame's work less than glBlitFramebuffer()
 * into a window with a depth buffer (docs/ENGINEER.md). */
static const char *vertex_src =
	"#version 330 core\n"
	"uniform vec4 u_from;\n"
	"out vec2 v_uv;\n"
	"void main() {\n"
	"	const vec2 corner[6] = vec2[](vec2(0, 0), vec2(1, 0),\n"
	"		vec2(0, 1), vec2(0, 1), vec2(1, 0), vec2(1, 1));\n"
	"	vec2 c = corner[gl_VertexID];\n"
	"	v_uv = u_from.xy + c * u_from.zw;\n"
	"	gl_Position = vec4(2.0 * c - 1.0, 0.0, 1.0);\n"
	"}\n";

static const char *fragment_src =
	"#version 330 core\n"
	"uniform sampler2D u_image;\n"
	"in vec2 v_uv;\n"
	"out vec4 frag;\n"
	"void main() {\n"
	"	frag = texture(u_image, v_uv);\n"
	"}\n";

/* Whether the window's framebuffer has a depth buffer. */
static bool window_depth(void)
{
	GLint type = GL_NONE;

	glBindFramebuffer(GL_FRAMEBUFFER, 0);
	glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_DEPTH,
					      GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE,
					      &type);
	return type != GL_NONE;
}

struct imagescale *imagescale_create(void)
{
	struct imagescale *s = calloc(1, sizeof(struct imagescale));

	if (!s) {
		return NULL;
	}
	s->window_depth = window_depth();
	s->program = gfx_program("imagescale", vertex_src, fragment_src);
	if (s->program) {
		s->u_from = glGetUniformLocation(s->program, "u_from");
		glGenVertexArrays(1, &s->vao);
	}
	return s;
}

/* The target, not the copy's program. */
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
	glDeleteProgram(s->program);
	glDeleteVertexArrays(1, &s->vao);
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
	s->colour = s->program ? gfx_texture(w, h, 4, NULL, false, false) : 0;
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
	bool full = !(scale < 1);
	int w = full ? r.x + r.w : (int)lround(r.w * scale);
	int h = full ? r.y + r.h : (int)lround(r.h * scale);

	s->bound = false;
	if ((full && s->window_depth) || s->failed || r.w < 1 || r.h < 1 ||
	    w < 1 || h < 1) {
		return r;
	}
	if (!make(s, w, h)) {
		log_warn("3-D view: no offscreen target of %dx%d: drawn in "
			 "the window, without a depth test", w, h);
		s->failed = true;
		return r;
	}
	glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
	s->bound = true;
	s->from = full ? r : (struct endo_rect){ 0, 0, w, h };
	return s->from;
}

void imagescale_end(struct imagescale *s, struct endo_rect r)
{
	GLint filter;

	if (!s->bound) {
		return;
	}
	filter = s->from.w == r.w && s->from.h == r.h ? GL_NEAREST : GL_LINEAR;
	glBindFramebuffer(GL_FRAMEBUFFER, 0);
	glViewport(r.x, r.y, r.w, r.h);
	glDisable(GL_BLEND);
	glUseProgram(s->program);
	glUniform4f(s->u_from, (float)s->from.x / (float)s->w,
		    (float)s->from.y / (float)s->h,
		    (float)s->from.w / (float)s->w,
		    (float)s->from.h / (float)s->h);
	glActiveTexture(GL_TEXTURE0);
	glBindTexture(GL_TEXTURE_2D, s->colour);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
	glBindVertexArray(s->vao);
	glDrawArrays(GL_TRIANGLES, 0, 6);
	glBindVertexArray(0);
	s->bound = false;
}
