/* draw2d.c - see draw2d.h. */
#include "viewer/draw2d.h"

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "viewer/gfx.h"
#include "base/log.h"

#define BATCH_VERTICES 24576 /* a multiple of 6 */

struct vertex {
	float x, y, s, t;
	uint8_t rgba[4];
};

struct draw2d {
	const struct font *font;
	GLuint program, vao, vbo, texture;
	GLint u_scale;
	float white_s, white_t;
	struct vertex v[BATCH_VERTICES];
	int n;
};

static const char *vertex_src =
	"#version 330 core\n"
	"uniform vec2 u_scale;\n"
	"in vec4 a_position;\n"
	"in vec4 a_color;\n"
	"out vec2 v_uv;\n"
	"out vec4 v_color;\n"
	"void main() {\n"
	"	v_uv = a_position.zw;\n"
	"	v_color = a_color;\n"
	"	gl_Position = vec4(a_position.xy * u_scale + vec2(-1, 1),"
	" 0, 1);\n"
	"}\n";

static const char *fragment_src =
	"#version 330 core\n"
	"uniform sampler2D u_atlas;\n"
	"in vec2 v_uv;\n"
	"in vec4 v_color;\n"
	"out vec4 frag;\n"
	"void main() {\n"
	"	float a = texture(u_atlas, v_uv).r;\n"
	"	frag = vec4(v_color.rgb, v_color.a * a);\n"
	"}\n";

static GLuint make_texture(struct draw2d *d)
{
	static const uint8_t white[16] = { 255, 255, 255, 255, 255, 255,
					   255, 255, 255, 255, 255, 255,
					   255, 255, 255, 255 };
	const unsigned char *atlas;
	int w, h;

	if (!d->font) {
		d->white_s = d->white_t = 0.5f;
		return gfx_texture(4, 4, 1, white, false, false);
	}
	atlas = font_atlas(d->font, &w, &h);
	font_white(d->font, &d->white_s, &d->white_t);
	return gfx_texture(w, h, 1, atlas, false, false);
}

static void make_buffers(struct draw2d *d)
{
	glGenVertexArrays(1, &d->vao);
	glBindVertexArray(d->vao);
	glGenBuffers(1, &d->vbo);
	glBindBuffer(GL_ARRAY_BUFFER, d->vbo);
	glBufferData(GL_ARRAY_BUFFER, sizeof(d->v), NULL, GL_STREAM_DRAW);
	glEnableVertexAttribArray(GFX_ATTR_POSITION);
	glVertexAttribPointer(GFX_ATTR_POSITION, 4, GL_FLOAT, GL_FALSE,
			      sizeof(struct vertex), (void *)0);
	glEnableVertexAttribArray(GFX_ATTR_COLOR);
	glVertexAttribPointer(GFX_ATTR_COLOR, 4, GL_UNSIGNED_BYTE, GL_TRUE,
			      sizeof(struct vertex),
			      (void *)offsetof(struct vertex, rgba));
	glBindVertexArray(0);
}

struct draw2d *draw2d_create(const struct font *f)
{
	struct draw2d *d = calloc(1, sizeof(*d));

	if (!d) {
		return NULL;
	}
	d->font = f;
	d->program = gfx_program("draw2d", vertex_src, fragment_src);
	d->texture = d->program ? make_texture(d) : 0;
	if (!d->texture) {
		draw2d_destroy(d);
		return NULL;
	}
	d->u_scale = glGetUniformLocation(d->program, "u_scale");
	make_buffers(d);
	return d;
}

void draw2d_destroy(struct draw2d *d)
{
	if (!d) {
		return;
	}
	glDeleteBuffers(1, &d->vbo);
	glDeleteVertexArrays(1, &d->vao);
	glDeleteTextures(1, &d->texture);
	glDeleteProgram(d->program);
	free(d);
}

void draw2d_begin(struct draw2d *d, int w, int h)
{
	d->n = 0;
	glViewport(0, 0, w, h);
	glUseProgram(d->program);
	glUniform2f(d->u_scale, 2.0f / (float)w, -2.0f / (float)h);
}

void draw2d_end(struct draw2d *d)
{
	if (!d->n) {
		return;
	}
	glDisable(GL_DEPTH_TEST);
	glDisable(GL_CULL_FACE);
	glEnable(GL_BLEND);
	glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
	glUseProgram(d->program);
	glActiveTexture(GL_TEXTURE0);
	glBindTexture(GL_TEXTURE_2D, d->texture);
	glBindVertexArray(d->vao);
	glBindBuffer(GL_ARRAY_BUFFER, d->vbo);
	glBufferSubData(GL_ARRAY_BUFFER, 0,
			(GLsizeiptr)d->n * sizeof(struct vertex), d->v);
	glDrawArrays(GL_TRIANGLES, 0, d->n);
	glBindVertexArray(0);
	glDisable(GL_BLEND);
	d->n = 0;
}

static uint8_t channel(float c)
{
	return (uint8_t)lrintf((c < 0 ? 0 : c > 1 ? 1 : c) * 255.0f);
}

static void put(struct draw2d *d, float x, float y, float s, float t,
		const float rgba[4])
{
	struct vertex *v = &d->v[d->n++];

	*v = (struct vertex){ .x = x, .y = y, .s = s, .t = t };
	for (int k = 0; k < 4; k++) {
		v->rgba[k] = channel(rgba[k]);
	}
}

/* Room for N more vertices, flushing the batch when full. */
static void room(struct draw2d *d, int n)
{
	if (d->n + n > BATCH_VERTICES) {
		draw2d_end(d);
	}
}

/* A textured quad: corners (x0, y0)-(x1, y1), texcoords likewise. */
static void quad(struct draw2d *d, const struct font_quad *q,
		 const float rgba[4])
{
	room(d, 6);
	put(d, q->x0, q->y0, q->s0, q->t0, rgba);
	put(d, q->x1, q->y0, q->s1, q->t0, rgba);
	put(d, q->x1, q->y1, q->s1, q->t1, rgba);
	put(d, q->x0, q->y0, q->s0, q->t0, rgba);
	put(d, q->x1, q->y1, q->s1, q->t1, rgba);
	put(d, q->x0, q->y1, q->s0, q->t1, rgba);
}

void draw2d_rect(struct draw2d *d, float x, float y, float w, float h,
		 const float rgba[4])
{
	struct font_quad q = { x, y, x + w, y + h, d->white_s, d->white_t,
			       d->white_s, d->white_t };

	quad(d, &q, rgba);
}

void draw2d_triangle(struct draw2d *d, const float xy[6],
		     const float rgba[4])
{
	room(d, 3);
	for (int k = 0; k < 3; k++) {
		put(d, xy[2 * k], xy[2 * k + 1], d->white_s, d->white_t, rgba);
	}
}

void draw2d_disc(struct draw2d *d, float x, float y, float r,
		 const float rgba[4])
{
	const int n = 16;

	for (int k = 0; k < n; k++) {
		float a0 = (float)(2 * M_PI * k / n);
		float a1 = (float)(2 * M_PI * (k + 1) / n);
		float xy[6] = { x, y, x + r * cosf(a0), y + r * sinf(a0),
				x + r * cosf(a1), y + r * sinf(a1) };

		draw2d_triangle(d, xy, rgba);
	}
}

void draw2d_line(struct draw2d *d, float x0, float y0, float x1, float y1,
		 float width, const float rgba[4])
{
	float dx = x1 - x0, dy = y1 - y0, len = hypotf(dx, dy);
	float nx, ny;

	if (len == 0) {
		return;
	}
	nx = -dy / len * width / 2;
	ny = dx / len * width / 2;
	draw2d_triangle(d, (const float[6]){ x0 + nx, y0 + ny, x1 + nx,
					     y1 + ny, x1 - nx, y1 - ny },
			rgba);
	draw2d_triangle(d, (const float[6]){ x0 + nx, y0 + ny, x1 - nx,
					     y1 - ny, x0 - nx, y0 - ny },
			rgba);
}

float draw2d_text(struct draw2d *d, enum font_size size, float x, float y,
		  const float rgba[4], const char *text)
{
	float x0 = x;
	struct font_quad q;

	if (!d->font) {
		return 0;
	}
	x = roundf(x);
	y = roundf(y);
	for (const char *p = text; *p; p++) {
		font_quad(d->font, size, (unsigned char)*p, &x, y, &q);
		quad(d, &q, rgba);
	}
	return x - x0;
}

float draw2d_printf(struct draw2d *d, enum font_size size, float x, float y,
		    const float rgba[4], const char *fmt, ...)
{
	char text[256];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(text, sizeof(text), fmt, ap);
	va_end(ap);
	return draw2d_text(d, size, x, y, rgba, text);
}

float draw2d_text_width(const struct draw2d *d, enum font_size size,
			const char *text)
{
	return d->font ? font_width(d->font, size, text) : 0;
}

float draw2d_px(const struct draw2d *d, enum font_size size)
{
	if (d->font) {
		return font_px(d->font, size);
	}
	return size == FONT_LARGE ? 28 : 14;
}
