/*
 * gfx.h - the few OpenGL helpers endoview's renderers share: shader
 * programs, textures, and the error check that runs every frame.
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
