/* lensfx.c - see lensfx.h. */
#include "viewer/lensfx.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "base/log.h"
#include "viewer/gfx.h"

#define NOISE_PX 128      /* the lens's pattern, tiled once across it */
#define NOISE_CELLS 8     /* its coarsest octave's cells across */
#define NOISE_OCTAVES 4
#define NOISE_SEED 0x9e3779b9u
#define SHRINK 4          /* each blurred copy a quarter of the last */
#define SOFT 2            /* blurred copies: 1/4 and 1/16 of the image */

enum uniform {
	U_IMAGE, U_SOFT1, U_SOFT2, U_NOISE, U_VIEWPORT, U_MASK, U_SMEAR,
	U_MURK, U_REDOUT, U_WATER, U_TIME, U_EDGE, UNIFORMS
};

static const char *const uniform_name[UNIFORMS] = {
	"u_image", "u_soft1", "u_soft2", "u_noise", "u_viewport", "u_mask",
	"u_smear", "u_murk", "u_redout", "u_water", "u_time", "u_edge",
};

struct lensfx {
	GLuint program, shrink, noise, vao;
	GLint u[UNIFORMS];
	GLint shrink_source, shrink_ratio;
	struct gfx_target image;      /* the image as drawn (a texture) */
	struct gfx_target soft[SOFT]; /* its blurred copies */
	bool failed; /* a target could not be made: said, no lens since */
};

/*
 * 1 / u_ratio of the source each way (u_ratio 4 or 2): the mean of each
 * 4 x 4 (2 x 2) of its texels, four bilinear taps between them (4: each
 * tap the mean of 2 x 2; 2: each on one texel), a box filter.
 */
static const char *shrink_src =
	"#version 330 core\n"
	"uniform sampler2D u_source;\n"
	"uniform float u_ratio;\n"
	"out vec4 frag;\n"
	"void main() {\n"
	"	vec2 texel = 1.0 / vec2(textureSize(u_source, 0));\n"
	"	vec2 at = gl_FragCoord.xy * u_ratio * texel;\n"
	"	texel *= 0.25 * u_ratio;\n"
	"	vec2 x = vec2(texel.x, -texel.y);\n"
	"	frag = 0.25 * (texture(u_source, at - texel) +\n"
	"		texture(u_source, at + x) +\n"
	"		texture(u_source, at - x) +\n"
	"		texture(u_source, at + texel));\n"
	"}\n";

/*
 * The blur: the sharp image, its copy a quarter as wide (a blur of a few
 * pixels) and a sixteenth (a heavy blur, two taps to hide its texels),
 * mixed by the amount: the same look at any size. Blurring by copies
 * (rather than mipmaps, which llvmpipe builds slowly) keeps the pass at
 * a few milliseconds.
 * How much of the sharp image shows (1.6 smear at 0.45 of it where the
 * noise leaves no patch, 1.2 murk) is lensfx_rules.c's too: keep them
 * together. The veils glow evenly: what the smear or the haze scatters
 * back into the lens is the light the walls return, which the light's
 * automatic level (endo.h) keeps about even. The noise's red is the smear's
 * patches, green its finer texture, blue the red-out's folds.
 */
static const char *fragment_src =
	"#version 330 core\n"
	"uniform sampler2D u_image;\n"
	"uniform sampler2D u_soft1;\n"
	"uniform sampler2D u_soft2;\n"
	"uniform sampler2D u_noise;\n"
	"uniform vec4 u_viewport;\n"
	"uniform float u_mask;\n"
	"uniform float u_smear;\n"
	"uniform float u_murk;\n"
	"uniform float u_redout;\n"
	"uniform float u_water;\n"
	"uniform float u_time;\n"
	"uniform float u_edge;\n"
	"out vec4 frag;\n"
	ENDO_MASK_GLSL
	"void main() {\n"
	"	vec2 uv = (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw;\n"
	"	vec4 n = texture(u_noise, uv);\n"
	"	vec2 ripple = vec2(\n"
	"		sin(31.0 * uv.y + 11.0 * u_time + 6.0 * n.g),\n"
	"		sin(27.0 * uv.x - 9.0 * u_time + 6.0 * n.r));\n"
	"	uv += u_water * 0.008 * ripple;\n"
	"	float patch = smoothstep(0.35, 0.65, n.r);\n"
	"	float smear = u_smear * (0.45 + 0.55 * patch);\n"
	"	float blur = clamp(1.6 * smear + 1.2 * u_murk, 0.0, 1.0);\n"
	"	vec3 sharp = texture(u_image, uv).rgb;\n"
	"	vec3 soft1 = texture(u_soft1, uv).rgb;\n"
	"	vec2 o = 0.6 / vec2(textureSize(u_soft2, 0));\n"
	"	vec3 soft2 = 0.5 * (texture(u_soft2, uv + o).rgb +\n"
	"		texture(u_soft2, uv - o).rgb);\n"
	"	vec3 soft = mix(soft1, soft2,\n"
	"		clamp(2.0 * blur - 1.0, 0.0, 1.0));\n"
	"	vec3 c = mix(sharp, soft, clamp(2.0 * blur, 0.0, 1.0));\n"
	"	vec3 veil = vec3(0.80, 0.16, 0.10) * 0.54 *\n"
	"		    (0.7 + 0.6 * n.g);\n"
	"	c = mix(c, c * vec3(1.0, 0.55, 0.5) + veil, 0.8 * smear);\n"
	"	vec3 haze = vec3(0.50, 0.40, 0.14) * 0.46;\n"
	"	c = mix(c, c * vec3(0.85, 0.75, 0.40) + haze, 0.6 * u_murk);\n"
	"	vec3 mucosa = vec3(0.55, 0.07, 0.05) * (0.8 + 0.4 * n.b);\n"
	"	c = mix(c, mucosa, 0.95 * u_redout);\n"
	"	c += u_water * 0.06 * max(ripple.x * ripple.y, 0.0);\n"
	"	frag = vec4(c * endo_mask_px(u_viewport, u_mask, u_edge), 1.0);\n"
	"}\n";

static uint32_t hash(uint32_t x, uint32_t y, uint32_t octave)
{
	uint32_t h = x * 0x85ebca6bu ^ y * 0xc2b2ae35u ^ octave * 0x27d4eb2fu ^
		     NOISE_SEED;

	h ^= h >> 15;
	h *= 0x2c1b3c6du;
	h ^= h >> 12;
	return h;
}

static double smooth(double t)
{
	return t * t * (3 - 2 * t);
}

/* Value noise at (X, Y) pixels, CELLS cells across, tiling; 0..1. */
static double value(int x, int y, int cells, uint32_t channel)
{
	double fx = (double)x * cells / NOISE_PX, fy = (double)y * cells /
						      NOISE_PX;
	int x0 = (int)fx, y0 = (int)fy;
	double tx = smooth(fx - x0), ty = smooth(fy - y0), v[4];

	for (int k = 0; k < 4; k++) {
		uint32_t cx = (uint32_t)((x0 + (k & 1)) % cells);
		uint32_t cy = (uint32_t)((y0 + (k >> 1)) % cells);

		v[k] = (hash(cx, cy, (uint32_t)cells * 4 + channel) & 0xffff) /
		       65535.0;
	}
	return (v[0] * (1 - tx) + v[1] * tx) * (1 - ty) +
	       (v[2] * (1 - tx) + v[3] * tx) * ty;
}

/* Octaves of value noise, each half the last's weight; 0..1. */
static double fbm(int x, int y, int cells, uint32_t channel)
{
	double sum = 0, weight = 0.5, total = 0;

	for (int o = 0; o < NOISE_OCTAVES; o++) {
		sum += weight * value(x, y, cells << o, channel);
		total += weight;
		weight /= 2;
	}
	return sum / total;
}

static GLuint make_noise(void)
{
	static uint8_t px[NOISE_PX * NOISE_PX * 4];
	static const int cells[3] = { NOISE_CELLS / 2, NOISE_CELLS * 2,
				      NOISE_CELLS };

	for (int y = 0; y < NOISE_PX; y++) {
		for (int x = 0; x < NOISE_PX; x++) {
			uint8_t *p = &px[4 * (y * NOISE_PX + x)];

			for (int c = 0; c < 3; c++) {
				p[c] = (uint8_t)lround(
					255 * fbm(x, y, cells[c], (uint32_t)c));
			}
			p[3] = 255;
		}
	}
	return gfx_texture(NOISE_PX, NOISE_PX, 4, px, true, false);
}

struct lensfx *lensfx_create(void)
{
	struct lensfx *fx = calloc(1, sizeof(*fx));

	if (!fx) {
		return NULL;
	}
	fx->program = gfx_program("lens", gfx_viewport_vertex_src,
				  fragment_src);
	fx->shrink = fx->program ? gfx_program("lens's blur",
					       gfx_viewport_vertex_src,
					       shrink_src) : 0;
	fx->noise = fx->shrink ? make_noise() : 0;
	if (!fx->noise) {
		log_err("lens: cannot make its programs or texture");
		lensfx_destroy(fx);
		return NULL;
	}
	for (int k = 0; k < UNIFORMS; k++) {
		fx->u[k] = glGetUniformLocation(fx->program, uniform_name[k]);
	}
	fx->shrink_source = glGetUniformLocation(fx->shrink, "u_source");
	fx->shrink_ratio = glGetUniformLocation(fx->shrink, "u_ratio");
	glGenVertexArrays(1, &fx->vao);
	return fx;
}

void lensfx_destroy(struct lensfx *fx)
{
	if (!fx) {
		return;
	}
	gfx_target_drop(&fx->image);
	for (int k = 0; k < SOFT; k++) {
		gfx_target_drop(&fx->soft[k]);
	}
	glDeleteTextures(1, &fx->noise);
	glDeleteVertexArrays(1, &fx->vao);
	glDeleteProgram(fx->shrink);
	glDeleteProgram(fx->program);
	free(fx);
}

/* The image in R of the framebuffer bound into its texture, and its
 * blurred copies, the first a quarter of the image's side at FACTOR 1
 * (at FACTOR 0.5, the image drawn at half its side: a half); that
 * framebuffer bound again. False when a target could not be made. */
static bool copy_image(struct lensfx *fx, struct endo_rect r, double factor)
{
	const struct gfx_target *from = &fx->image;
	GLint bound = 0;

	glGetIntegerv(GL_FRAMEBUFFER_BINDING, &bound);

	glActiveTexture(GL_TEXTURE0);
	if (!gfx_target(&fx->image, r.w, r.h, GFX_TARGET_TEXTURE)) {
		return false;
	}
	glBindTexture(GL_TEXTURE_2D, fx->image.texture);
	glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, r.x, r.y, r.w, r.h);
	glUseProgram(fx->shrink);
	glUniform1i(fx->shrink_source, 0);
	glBindVertexArray(fx->vao);
	for (int k = 0; k < SOFT; k++) {
		struct gfx_target *to = &fx->soft[k];
		int ratio = k == 0 ? (int)lround(SHRINK * factor) : SHRINK;

		glUniform1f(fx->shrink_ratio, (float)ratio);
		if (!gfx_target(to, from->w / ratio > 0 ? from->w / ratio : 1,
				from->h / ratio > 0 ? from->h / ratio : 1,
				GFX_TARGET_COLOUR)) {
			glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)bound);
			return false;
		}
		glBindFramebuffer(GL_FRAMEBUFFER, to->fbo);
		glViewport(0, 0, to->w, to->h);
		glBindTexture(GL_TEXTURE_2D, from->texture);
		glDrawArrays(GL_TRIANGLES, 0, 3);
		from = to;
	}
	glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)bound);
	return true;
}

void lensfx_draw(struct lensfx *fx, const struct endosim_patient_state *p,
		 struct endo_rect r, double factor, double t_s)
{
	if (fx->failed || !lensfx_visible(p) || r.w <= 0 || r.h <= 0) {
		return;
	}
	if (!copy_image(fx, r, factor)) {
		log_warn("lens: no offscreen target of %dx%d: the image "
			 "drawn without the lens from now on", r.w, r.h);
		fx->failed = true;
		return;
	}
	glViewport(r.x, r.y, r.w, r.h);
	glUseProgram(fx->program);
	glUniform1i(fx->u[U_IMAGE], 0);
	glUniform1i(fx->u[U_SOFT1], 1);
	glUniform1i(fx->u[U_SOFT2], 2);
	glUniform1i(fx->u[U_NOISE], 3);
	glUniform4f(fx->u[U_VIEWPORT], (float)r.x, (float)r.y, (float)r.w,
		    (float)r.h);
	glUniform1f(fx->u[U_MASK], (float)ENDO_MASK_RADIUS);
	glUniform1f(fx->u[U_SMEAR], lensfx_amount(p->lens_smear));
	glUniform1f(fx->u[U_MURK], lensfx_amount(p->lens_murk));
	glUniform1f(fx->u[U_REDOUT], lensfx_amount(p->lens_redout));
	glUniform1f(fx->u[U_WATER], p->valves & ENDOSIM_VALVE_WATER ? 1 : 0);
	glUniform1f(fx->u[U_TIME], (float)fmod(t_s, 1000));
	/* the circle's edge as wide on the screen at any FACTOR */
	glUniform1f(fx->u[U_EDGE], (float)(1 / factor));
	glBindTexture(GL_TEXTURE_2D, fx->image.texture);
	for (int k = 0; k < SOFT; k++) {
		glActiveTexture((GLenum)(GL_TEXTURE1 + k));
		glBindTexture(GL_TEXTURE_2D, fx->soft[k].texture);
	}
	glActiveTexture(GL_TEXTURE3);
	glBindTexture(GL_TEXTURE_2D, fx->noise);
	glBindVertexArray(fx->vao);
	glDrawArrays(GL_TRIANGLES, 0, 3);
	glBindVertexArray(0);
	glActiveTexture(GL_TEXTURE0);
}
