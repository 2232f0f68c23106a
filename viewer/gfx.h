/*
 * gfx.h - the few OpenGL helpers endoview's renderers share: shader
 * programs, textures, offscreen targets and the one-triangle pass over
 * the viewport that draws them, and the error check that runs every
 * frame.
 *
 * OpenGL 3.3 core through libepoxy; every call needs the window's context
 * current on the calling thread (endoview's main thread).
 */
#ifndef ENDOVIEW_GFX_H
#define ENDOVIEW_GFX_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

/* Vertex attribute locations, the same in every program. */
enum gfx_attrib {
	GFX_ATTR_POSITION = 0,
	GFX_ATTR_NORMAL = 1,
	GFX_ATTR_TEXCOORD = 2,
	GFX_ATTR_COLOR = 3,
};

/*
 * Compiles and links a program from GLSL 330 core sources, with the
 * attribute locations above. Returns 0 with the compiler's log on stderr
 * (naming NAME) when either stage or the link fails.
 */
GLuint gfx_program(const char *name, const char *vertex_src,
		   const char *fragment_src);

/*
 * An RGBA8 (CHANNELS 4) or R8 (CHANNELS 1) texture of W x H from PIXELS,
 * rows top first (NULL: undefined, one to draw into); REPEAT wraps, else
 * clamps; MIPMAP builds the chain and filters with it. Returns 0 on
 * failure.
 */
GLuint gfx_texture(int w, int h, int channels, const uint8_t *pixels,
		   bool repeat, bool mipmap);

/* A texture to draw into, with what draws into it (struct gfx_target). */
enum gfx_target_kind {
	GFX_TARGET_TEXTURE, /* the texture alone: glCopyTexSubImage2D() in */
	GFX_TARGET_COLOUR,  /* and a framebuffer with it as its colour */
	GFX_TARGET_DEPTH,   /* and a 24-bit depth buffer to that */
};

struct gfx_target {
	GLuint texture, fbo, depth; /* fbo, depth: 0 where not made */
	int w, h;                   /* px */
};

/*
 * T as an RGBA8 target of W x H of KIND, linearly filtered, clamped at
 * its edges; made anew (the old one deleted) only when its size changed.
 * Returns false, T empty, when the driver will not have it. Leaves
 * texture 0 and framebuffer 0 bound when it makes one.
 */
bool gfx_target(struct gfx_target *t, int w, int h,
		enum gfx_target_kind kind);

/* Deletes what T holds; T empty. An empty T is fine. */
void gfx_target_drop(struct gfx_target *t);

/*
 * A vertex shader that covers the viewport with one triangle made from
 * gl_VertexID alone (glDrawArrays(GL_TRIANGLES, 0, 3), an empty vertex
 * array bound). Its v_uv runs across the viewport over the rectangle
 * u_texrect of a texture (x, y, w, h in its 0..1); a program that finds
 * its place by gl_FragCoord leaves u_texrect unset. Interpolated, not
 * computed in the fragment shader: llvmpipe fetches a texel at a
 * computed coordinate slower (a 720x720 copy took 0.3 ms more).
 */
extern const char *const gfx_viewport_vertex_src;

/*
 * Asks the context for debug messages (KHR_debug, where the context has
 * it) so that errors are reported with their meaning as they happen.
 */
void gfx_debug_init(void);

/*
 * Takes every pending GL error and logs it with WHERE. Returns how many
 * errors (GL errors and debug messages of type error) were seen since the
 * previous call.
 */
unsigned int gfx_check(const char *where);

/* Errors seen since start-up. */
unsigned long gfx_errors_total(void);

#endif
