/* imagescale.c - see imagescale.h. */
#include "viewer/imagescale.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "viewer/gfx.h"

struct imagescale {
	struct gfx_target target;
	GLuint program, vao; /* the copy into the window */
	GLint u_texrect;
	struct endo_rect from; /* what was drawn in the target */
	bool window_depth; /* the window has a depth buffer */
	bool bound;        /* between begin and end */
	bool failed;       /* a target could not be made: said once */
};

/* The target's texture over the viewport (gfx_viewport_vertex_src, its
 * u_texrect the drawn part), sampled through its filter, no depth, no
 * blending: with the window's depth gone, a fifth to a seventh of the
 * frame's work less than glBlitFramebuffer() into a window with a depth
 * buffer (docs/ENGINEER.md). */
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
	s->program = gfx_program("imagescale", gfx_viewport_vertex_src,
				 fragment_src);
	if (s->program) {
		s->u_texrect = glGetUniformLocation(s->program, "u_texrect");
		glGenVertexArrays(1, &s->vao);
	}
	return s;
}

void imagescale_destroy(struct imagescale *s)
{
	if (!s) {
		return;
	}
	gfx_target_drop(&s->target);
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
	if (!s->program || !gfx_target(&s->target, w, h, GFX_TARGET_DEPTH)) {
		log_warn("3-D view: no offscreen target of %dx%d: drawn in "
			 "the window, without a depth test", w, h);
		s->failed = true;
		return r;
	}
	glBindFramebuffer(GL_FRAMEBUFFER, s->target.fbo);
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
	glUniform4f(s->u_texrect, (float)s->from.x / (float)s->target.w,
		    (float)s->from.y / (float)s->target.h,
		    (float)s->from.w / (float)s->target.w,
		    (float)s->from.h / (float)s->target.h);
	glActiveTexture(GL_TEXTURE0);
	glBindTexture(GL_TEXTURE_2D, s->target.texture);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
	glBindVertexArray(s->vao);
	glDrawArrays(GL_TRIANGLES, 0, 3);
	glBindVertexArray(0);
	s->bound = false;
}
