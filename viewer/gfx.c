/* gfx.c - see gfx.h. */
#include "viewer/gfx.h"

#include <stdio.h>

#include "base/log.h"

static unsigned int debug_errors; /* since the last gfx_check() */
static unsigned long errors_total;

static bool compiled(GLuint shader, const char *name, const char *stage)
{
	GLint ok = 0;
	char text[2048];

	glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
	if (ok) {
		return true;
	}
	glGetShaderInfoLog(shader, sizeof(text), NULL, text);
	log_err("%s: %s shader: %s", name, stage, text);
	return false;
}

static GLuint stage(GLenum type, const char *src, const char *name)
{
	GLuint s = glCreateShader(type);

	glShaderSource(s, 1, &src, NULL);
	glCompileShader(s);
	if (!compiled(s, name, type == GL_VERTEX_SHADER ? "vertex" :
							  "fragment")) {
		glDeleteShader(s);
		return 0;
	}
	return s;
}

static bool linked(GLuint p, const char *name)
{
	GLint ok = 0;
	char text[2048];

	glGetProgramiv(p, GL_LINK_STATUS, &ok);
	if (ok) {
		return true;
	}
	glGetProgramInfoLog(p, sizeof(text), NULL, text);
	log_err("%s: link: %s", name, text);
	return false;
}

GLuint gfx_program(const char *name, const char *vertex_src,
		   const char *fragment_src)
{
	GLuint vs = stage(GL_VERTEX_SHADER, vertex_src, name);
	GLuint fs = vs ? stage(GL_FRAGMENT_SHADER, fragment_src, name) : 0;
	GLuint p = 0;

	if (!fs) {
		goto delete_shaders;
	}
	p = glCreateProgram();
	glAttachShader(p, vs);
	glAttachShader(p, fs);
	glBindAttribLocation(p, GFX_ATTR_POSITION, "a_position");
	glBindAttribLocation(p, GFX_ATTR_NORMAL, "a_normal");
	glBindAttribLocation(p, GFX_ATTR_TEXCOORD, "a_texcoord");
	glBindAttribLocation(p, GFX_ATTR_COLOR, "a_color");
	glLinkProgram(p);
	if (!linked(p, name)) {
		glDeleteProgram(p);
		p = 0;
	}
delete_shaders:
	glDeleteShader(fs);
	glDeleteShader(vs);
	return p;
}

GLuint gfx_texture(int w, int h, int channels, const uint8_t *pixels,
		   bool repeat, bool mipmap)
{
	GLenum format = channels == 4 ? GL_RGBA : GL_RED;
	GLint wrap = repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
	GLuint t;

	glGenTextures(1, &t);
	glBindTexture(GL_TEXTURE_2D, t);
	glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
	glTexImage2D(GL_TEXTURE_2D, 0, channels == 4 ? GL_RGBA8 : GL_R8, w, h,
		     0, format, GL_UNSIGNED_BYTE, pixels);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
	if (mipmap) {
		glGenerateMipmap(GL_TEXTURE_2D);
		glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
				GL_LINEAR_MIPMAP_NEAREST);
	} else {
		glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
				GL_LINEAR);
	}
	if (gfx_check("texture")) {
		glDeleteTextures(1, &t);
		return 0;
	}
	return t;
}

void gfx_target_drop(struct gfx_target *t)
{
	glDeleteFramebuffers(1, &t->fbo);
	glDeleteRenderbuffers(1, &t->depth);
	glDeleteTextures(1, &t->texture);
	*t = (struct gfx_target){ 0 };
}

bool gfx_target(struct gfx_target *t, int w, int h,
		enum gfx_target_kind kind)
{
	bool complete;

	if (t->texture && t->w == w && t->h == h) {
		return true;
	}
	gfx_target_drop(t);
	t->texture = gfx_texture(w, h, 4, NULL, false, false);
	glBindTexture(GL_TEXTURE_2D, 0);
	if (!t->texture) {
		return false;
	}
	t->w = w;
	t->h = h;
	if (kind == GFX_TARGET_TEXTURE) {
		return true;
	}
	glGenFramebuffers(1, &t->fbo);
	glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
	glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
			       GL_TEXTURE_2D, t->texture, 0);
	if (kind == GFX_TARGET_DEPTH) {
		glGenRenderbuffers(1, &t->depth);
		glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
		glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w,
				      h);
		glBindRenderbuffer(GL_RENDERBUFFER, 0);
		glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
					  GL_RENDERBUFFER, t->depth);
	}
	complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) ==
		   GL_FRAMEBUFFER_COMPLETE;
	glBindFramebuffer(GL_FRAMEBUFFER, 0);
	if (!complete) {
		gfx_target_drop(t);
	}
	return complete;
}

const char *const gfx_viewport_vertex_src =
	"#version 330 core\n"
	"uniform vec4 u_texrect;\n"
	"out vec2 v_uv;\n"
	"void main() {\n"
	"	vec2 p = vec2((gl_VertexID & 1) * 4 - 1,\n"
	"		      (gl_VertexID & 2) * 2 - 1);\n"
	"	v_uv = u_texrect.xy + (0.5 * p + 0.5) * u_texrect.zw;\n"
	"	gl_Position = vec4(p, 0.0, 1.0);\n"
	"}\n";

static void GLAPIENTRY on_debug(GLenum source, GLenum type, GLuint id,
				GLenum severity, GLsizei length,
				const GLchar *message, const void *user)
{
	(void)source;
	(void)id;
	(void)length;
	(void)user;
	if (type == GL_DEBUG_TYPE_ERROR) {
		debug_errors++;
		log_err("GL: %s", message);
	} else if (severity == GL_DEBUG_SEVERITY_HIGH) {
		log_warn("GL: %s", message);
	}
}

void gfx_debug_init(void)
{
	GLint flags = 0;

	glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
	if (!(flags & GL_CONTEXT_FLAG_DEBUG_BIT) ||
	    !epoxy_has_gl_extension("GL_KHR_debug")) {
		return;
	}
	glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
	glDebugMessageCallback(on_debug, NULL);
}

static const char *error_name(GLenum e)
{
	switch (e) {
	case GL_INVALID_ENUM:
		return "invalid enum";
	case GL_INVALID_VALUE:
		return "invalid value";
	case GL_INVALID_OPERATION:
		return "invalid operation";
	case GL_INVALID_FRAMEBUFFER_OPERATION:
		return "invalid framebuffer operation";
	case GL_OUT_OF_MEMORY:
		return "out of memory";
	default:
		return "unknown error";
	}
}

unsigned int gfx_check(const char *where)
{
	unsigned int n = debug_errors;
	GLenum e;

	debug_errors = 0;
	while ((e = glGetError()) != GL_NO_ERROR) {
		log_err("GL error in %s: %s (0x%x)", where, error_name(e), e);
		n++;
	}
	errors_total += n;
	return n;
}

unsigned long gfx_errors_total(void)
{
	return errors_total;
}
