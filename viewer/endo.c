/* endo.c - see endo.h. */
#include "viewer/endo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cglm/cglm.h>

#include "viewer/gfx.h"
#include "base/log.h"
#include "viewer/portal.h"
#include "viewer/shapes.h"
#include "base/vec3.h"
#include "viewer/vessels.h"

#define TEXTURE_PX 1024
#define TEXTURE_SEED 20020101u
#define EXPOSURE_M2 0.0007  /* a white wall facing the lens at 2.6 cm: 1 */
#define ALC_AROUND 8        /* rays on each cone */
#define ALC_CONE_RAD 0.4    /* the inner cone's half-angle */
#define ALC_STEP_M 0.002
#define ALC_REACH_M 0.08
#define GLOSS 0.8           /* the wettest mucosa's highlight */
/* the pools (shader text): the light's e-fold path in the murky liquid;
 * the liquid lit around the lens when the eye is under it as a wall this
 * far away squared */
#define MURK_M_TEXT "0.006"
#define NEAR_M2_TEXT "4.0e-4"
#define SEGMENTS_TEXT "9"
#define BUBBLE_CELL_M_TEXT "0.003" /* a bubble in some cells this wide */
#define BUBBLES_TEXT "0.2"         /* the share of cells with one */
_Static_assert(ENDOSIM_SEGMENTS == 9, "SEGMENTS_TEXT");

static const float mucosa_tint[3] = { 1.0f, 1.0f, 1.0f };
static const float polyp_tint[3] = { 1.02f, 0.80f, 0.78f };

enum uniform {
	U_VIEW, U_MODEL, U_NORMAL, U_THETA_MAX, U_FAR, U_EXPOSURE, U_TINT,
	U_GLOSS, U_VIEWPORT, U_MASK, U_BLOOD,
	/* the pools */
	U_LEVEL, U_SEG_END, U_S_PER_TEX, U_DRAW_LEVEL, U_UP, U_EYE,
	U_EYE_LEVEL, U_AXIS, U_AXIS_P, U_LUMEN_R, UNIFORMS
};

static const char *const uniform_name[UNIFORMS] = {
	"u_view", "u_model", "u_normal", "u_theta_max", "u_far", "u_exposure",
	"u_tint", "u_gloss", "u_viewport", "u_mask", "u_blood",
	"u_level", "u_seg_end", "u_s_per_tex", "u_draw_level",
	"u_up", "u_eye", "u_eye_level", "u_axis", "u_axis_p", "u_lumen_r",
};

/*
 * The programs, one source: dry (no pool in reach), pools (the eye above
 * the surfaces: a surface, the wall under it, the wet line) and under
 * (the eye under its segment's surface). llvmpipe runs both sides of a
 * branch for every pixel, so a branch on a uniform would cost the dry
 * walls the pools' shading: each draw takes the program it needs.
 */
enum program_kind { PROG_DRY, PROG_POOLS, PROG_UNDER, PROGRAMS };

static const char *const program_head[PROGRAMS] = {
	"#version 330 core\n#define POOLS 0\n#define UNDER 0\n",
	"#version 330 core\n#define POOLS 1\n#define UNDER 0\n",
	"#version 330 core\n#define POOLS 1\n#define UNDER 1\n",
};

struct program {
	GLuint id;
	GLint u[UNIFORMS];
};

struct endo {
	struct program prog[PROGRAMS];
	const struct program *in_use;
	GLuint texture;
	GLuint sphere_vao, sphere_buf[2];
	GLuint plain;              /* one white texel: the tool's surface */
	GLuint tool_vao, tool_buf[2];
};

/*
 * The pools (POOLS): each vertex' world position and its segment's
 * surface level, the segment found from its s (the texture's coordinate
 * along the colon) on the colon, given (u_draw_level) for a polyp.
 */
static const char *vertex_src =
	"uniform mat4 u_view;\n"
	"uniform mat4 u_model;\n"
	"uniform mat3 u_normal;\n"
	"uniform float u_theta_max;\n"
	"uniform float u_far;\n"
	"#if POOLS\n"
	"uniform float u_level[" SEGMENTS_TEXT "];\n"
	"uniform float u_seg_end[" SEGMENTS_TEXT " - 1];\n"
	"uniform float u_s_per_tex;\n"
	"uniform float u_draw_level;\n"
	"out vec3 v_world;\n"
	"out float v_level;\n"
	"#endif\n"
	"in vec3 a_position;\n"
	"in vec3 a_normal;\n"
	"in vec2 a_texcoord;\n"
	"out vec3 v_pos;\n"
	"out vec3 v_nrm;\n"
	"out vec2 v_tex;\n"
	"void main() {\n"
	"	vec4 p = u_view * u_model * vec4(a_position, 1.0);\n"
	"#if POOLS\n"
	"	float s = a_texcoord.x * u_s_per_tex;\n"
	"	int k = 0;\n"
	"	for (int i = 0; i < " SEGMENTS_TEXT " - 1; i++)\n"
	"		k += s >= u_seg_end[i] ? 1 : 0;\n"
	"	v_level = u_s_per_tex > 0.0 ? u_level[k] : u_draw_level;\n"
	"	v_world = (u_model * vec4(a_position, 1.0)).xyz;\n"
	"#endif\n"
	"	v_pos = p.xyz;\n"
	"	v_nrm = mat3(u_view) * u_normal * a_normal;\n"
	"	v_tex = a_texcoord;\n"
	"	float d = length(p.xyz);\n"
	"	vec3 r = p.xyz / max(d, 1e-7);\n"
	"	float theta = acos(clamp(-r.z, -1.0, 1.0));\n"
	"	float l = length(r.xy);\n"
	"	vec2 az = l > 1e-7 ? r.xy / l : vec2(0.0, 1.0);\n"
	/* behind the lens: far off the image and beyond the far plane */
	"	if (theta > 1.95) {\n"
	"		gl_Position = vec4(4.0 * az, 2.0, 1.0);\n"
	"		return;\n"
	"	}\n"
	"	gl_Position = vec4(az * theta / u_theta_max,\n"
	"			   2.0 * d / u_far - 1.0, 1.0);\n"
	"}\n";

/*
 * Light at the lens: 1/d^2; diffuse with a wrap that lets red light round
 * the folds (scattered in tissue); a specular term (the light and the
 * eye coincide, so the half vector is L) x^128, its strength the texture's
 * moisture (alpha), which breaks the highlights into glints.
 */
/*
 * The pools: a wall point under its segment's surface, the eye above it:
 * the ray enters the liquid where it meets the plane; the light's path in
 * it (the wall's light and the ray's) dims the wall e-fold every MURK_M
 * and the liquid's own scattered colour takes its place; the surface
 * reflects (Schlick's Fresnel term) the lens's light as a glint, broken
 * by faint ripples. A wall point just above the waterline glistens. The
 * eye under its segment's surface: the ray's path in the liquid up to
 * the surface or the wall, the liquid lit close to the lens.
 */
static const char *fragment_src =
	"uniform sampler2D u_texture;\n"
	"uniform float u_exposure;\n"
	"uniform vec3 u_tint;\n"
	"uniform float u_gloss;\n"
	"uniform vec4 u_viewport;\n"
	"uniform float u_mask;\n"
	"uniform float u_blood;\n"
	"in vec3 v_pos;\n"
	"in vec3 v_nrm;\n"
	"in vec2 v_tex;\n"
	"out vec4 frag;\n"
	ENDO_MASK_GLSL
	"#if POOLS\n"
	"uniform vec3 u_up;\n"
	"uniform vec3 u_eye;\n"
	"uniform float u_eye_level;\n"
	"uniform vec3 u_axis;\n"
	"uniform vec3 u_axis_p;\n"
	"uniform float u_lumen_r;\n"
	"in vec3 v_world;\n"
	"in float v_level;\n"
	"const vec3 liquid = vec3(0.36, 0.28, 0.08);\n"
	"const vec3 mirrored = vec3(0.55, 0.26, 0.20);\n"
	"const float murk_m = " MURK_M_TEXT ";\n"
	"vec3 under_eye(vec3 c, float d, float he, float hw) {\n"
	"	float path = hw < v_level ? d :\n"
	"		d * clamp((u_eye_level - he) / max(hw - he, 1e-6),\n"
	"			  0.0, 1.0);\n"
	"	float k = exp(-path / murk_m);\n"
	"	return c * k + liquid * u_exposure / " NEAR_M2_TEXT " *\n"
	"		(1.0 - k);\n"
	"}\n"
	"vec3 mirror(vec3 sp, vec3 m) {\n"
	"	vec3 o = sp - u_axis_p;\n"
	"	vec3 op = o - dot(o, u_axis) * u_axis;\n"
	"	vec3 mp = m - dot(m, u_axis) * u_axis;\n"
	"	float a = max(dot(mp, mp), 1e-6), b = dot(op, mp);\n"
	"	float cc = dot(op, op) - u_lumen_r * u_lumen_r;\n"
	"	vec3 q = sp + m * (sqrt(max(b * b - a * cc, 0.0)) - b) / a;\n"
	"	vec3 to_eye = u_eye - q;\n"
	"	float dq = length(to_eye);\n"
	"	vec3 x = q - u_axis_p;\n"
	"	vec3 nq = normalize(dot(x, u_axis) * u_axis - x);\n"
	"	float ndl = max(dot(nq, to_eye / dq), 0.0);\n"
	"	return mirrored * (0.3 + 0.7 * ndl) * u_exposure /\n"
	"		(dq * dq + 1e-6);\n"
	"}\n"
	"vec3 bubble(vec3 sp, vec3 n) {\n"
	"	vec3 a = normalize(cross(u_up, u_axis)), b = cross(u_up, a);\n"
	"	vec2 q = vec2(dot(sp, a), dot(sp, b)) /\n"
	"		" BUBBLE_CELL_M_TEXT ";\n"
	"	vec2 cell = floor(q), f = fract(q) - 0.5;\n"
	"	float h = fract(sin(dot(cell, vec2(127.1, 311.7))) *\n"
	"		43758.5);\n"
	"	float rb = 0.10 + 0.16 * fract(h * 7.13);\n"
	"	vec2 o = (f - (vec2(fract(h * 13.7), fract(h * 29.1)) -\n"
	"		0.5) *\n"
	"		  (0.9 - 2.0 * rb)) / rb;\n"
	"	float rr = dot(o, o);\n"
	"	if (h > " BUBBLES_TEXT " || rr >= 1.0)\n"
	"		return n;\n"
	"	return normalize(a * o.x + b * o.y + u_up * sqrt(1.0 - rr));\n"
	"}\n"
	"vec3 surface(vec3 c, float d, float he, float hw) {\n"
	"	vec3 r = (v_world - u_eye) / d;\n"
	"	float at = d * (v_level - he) / (hw - he);\n"
	"	vec3 sp = u_eye + at * r;\n"
	"	vec3 n = bubble(sp, normalize(u_up + 0.04 * vec3(\n"
	"		sin(dot(sp, vec3(900.0, 410.0, 130.0))),\n"
	"		sin(dot(sp, vec3(170.0, 830.0, 520.0))),\n"
	"		sin(dot(sp, vec3(610.0, 240.0, 760.0))))));\n"
	"	float cn = max(dot(n, -r), 0.0);\n"
	"	float fresnel = 0.02 + 0.98 * pow(1.0 - cn, 5.0);\n"
	"	float light = u_exposure / (at * at + 1e-6);\n"
	"	float k = exp(-2.0 * (d - at) / murk_m);\n"
	"	float cloud = 0.75 + 0.25 *\n"
	"		sin(dot(sp, vec3(210.0, 90.0, 150.0))) *\n"
	"		sin(dot(sp, vec3(70.0, 260.0, 120.0)));\n"
	"	vec3 body = c * k + liquid * light * cloud *\n"
	"		(0.15 + 0.85 * cn) * (1.0 - k);\n"
	"	return body * (1.0 - fresnel) +\n"
	"		fresnel * mirror(sp, reflect(r, n)) +\n"
	"		light * (0.25 * pow(cn, 30.0) +\n"
	"		3.0 * pow(cn, 300.0));\n"
	"}\n"
	"vec3 in_liquid(vec3 c, float d) {\n"
	"	float he = dot(u_eye, u_up), hw = dot(v_world, u_up);\n"
	"#if UNDER\n"
	"	return under_eye(c, d, he, hw);\n"
	"#else\n"
	"	if (hw >= v_level)\n"
	"		return c * (1.0 + 0.8 * (1.0 - smoothstep(0.0, 8e-4,\n"
	"						    hw - v_level)));\n"
	"	if (he > v_level)\n"
	"		return surface(c, d, he, hw);\n"
	"	return under_eye(c, d, he, hw);\n"
	"#endif\n"
	"}\n"
	"#endif\n"
	"void main() {\n"
	"	float d = length(v_pos);\n"
	"	vec4 t = texture(u_texture, v_tex);\n"
	"	float ndl = dot(normalize(v_nrm), -v_pos / d);\n"
	"	vec3 wrap = vec3(0.45, 0.25, 0.2);\n"
	"	vec3 diffuse = max((vec3(ndl) + wrap) / (1.0 + wrap), 0.0);\n"
	"	float s = max(ndl, 0.0);\n"
	"	s *= s; s *= s; s *= s; s *= s; s *= s; s *= s; s *= s;\n"
	"	vec3 c = t.rgb * u_tint * diffuse + u_gloss * t.a * t.a * s;\n"
	"	c *= u_exposure / (d * d + 1e-6);\n"
	"#if POOLS\n"
	"	c = in_liquid(c, d);\n"
	"#endif\n"
	"	c = mix(c, c * vec3(1.05, 0.22, 0.18), u_blood);\n"
	"	c = 1.0 - exp(-c);\n"
	"	frag = vec4(c * endo_mask(u_viewport, u_mask), 1.0);\n"
	"}\n";

/* A VAO with its vertex buffer (VBYTES of V, 9 floats a vertex: position,
 * normal, texture coordinates; V NULL: room only) and index buffer. */
static void make_shape(GLuint *vao, GLuint buf[2], GLsizeiptr vbytes,
		       const void *v, GLenum usage, GLsizeiptr ibytes,
		       const uint32_t *idx)
{
	const GLsizei stride = 9 * sizeof(float);

	glGenVertexArrays(1, vao);
	glBindVertexArray(*vao);
	glGenBuffers(2, buf);
	glBindBuffer(GL_ARRAY_BUFFER, buf[0]);
	glBufferData(GL_ARRAY_BUFFER, vbytes, v, usage);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buf[1]);
	glBufferData(GL_ELEMENT_ARRAY_BUFFER, ibytes, idx, GL_STATIC_DRAW);
	for (int a = 0; a < 3; a++) {
		glEnableVertexAttribArray((GLuint)a);
		uintptr_t at = 3 * (uintptr_t)a * sizeof(float);

		glVertexAttribPointer((GLuint)a, a < 2 ? 3 : 2, GL_FLOAT,
				      GL_FALSE, stride, (void *)at);
	}
	glBindVertexArray(0);
}

static void make_sphere(struct endo *e)
{
	static float v[SHAPES_SPHERE_VERTICES][9];
	static uint32_t idx[SHAPES_SPHERE_INDICES];

	shapes_sphere(v, idx);
	make_shape(&e->sphere_vao, e->sphere_buf, sizeof(v), v, GL_STATIC_DRAW,
		   sizeof(idx), idx);
}

/* The tool's tubes: a stream buffer for the longest, one index list. */
static void make_tool(struct endo *e)
{
	static uint32_t idx[6 * (TOOLVIEW_POINTS - 1) * SHAPES_TUBE_SIDES];
	static const uint8_t white[4] = { 255, 255, 255, 255 };

	e->plain = gfx_texture(1, 1, 4, white, false, false);
	shapes_tube_index(TOOLVIEW_POINTS, idx);
	make_shape(&e->tool_vao, e->tool_buf,
		   (GLsizeiptr)(shapes_tube_vertices(TOOLVIEW_POINTS) * 9 *
				sizeof(float)), NULL, GL_STREAM_DRAW,
		   sizeof(idx), idx);
}

static GLuint make_texture(void)
{
	uint8_t *img = vessels_create(TEXTURE_PX, TEXTURE_SEED);
	GLuint t;

	if (!img) {
		log_err("vessel texture: out of memory");
		return 0;
	}
	t = gfx_texture(TEXTURE_PX, TEXTURE_PX, 4, img, true, true);
	free(img);
	return t;
}

/* Program K from the one source. 0 on failure (logged). */
static int make_program(struct program *p, enum program_kind k)
{
	static const char *const name[PROGRAMS] = {
		"endoscopic view", "endoscopic view, pools",
		"endoscopic view, under a pool",
	};
	char *vs = NULL, *fs = NULL;

	if (asprintf(&vs, "%s%s", program_head[k], vertex_src) < 0) {
		vs = NULL;
	}
	if (asprintf(&fs, "%s%s", program_head[k], fragment_src) < 0) {
		fs = NULL;
	}
	p->id = vs && fs ? gfx_program(name[k], vs, fs) : 0;
	free(vs);
	free(fs);
	for (int u = 0; p->id && u < UNIFORMS; u++) {
		p->u[u] = glGetUniformLocation(p->id, uniform_name[u]);
	}
	return p->id ? 0 : -1;
}

struct endo *endo_create(void)
{
	struct endo *e = calloc(1, sizeof(*e));
	int bad = 0;

	if (!e) {
		return NULL;
	}
	for (int k = 0; k < PROGRAMS; k++) {
		bad |= make_program(&e->prog[k], (enum program_kind)k);
	}
	e->texture = bad ? 0 : make_texture();
	if (!e->texture) {
		endo_destroy(e);
		return NULL;
	}
	make_sphere(e);
	make_tool(e);
	return e;
}

void endo_destroy(struct endo *e)
{
	if (!e) {
		return;
	}
	glDeleteBuffers(2, e->sphere_buf);
	glDeleteVertexArrays(1, &e->sphere_vao);
	glDeleteBuffers(2, e->tool_buf);
	glDeleteVertexArrays(1, &e->tool_vao);
	glDeleteTextures(1, &e->plain);
	glDeleteTextures(1, &e->texture);
	for (int k = 0; k < PROGRAMS; k++) {
		glDeleteProgram(e->prog[k].id);
	}
	free(e);
}

/* Along RAY from the camera, the distance to the wall (up to REACH_M). */
static double march(const struct model *m, const struct endo_camera *cam,
		    const double ray[3])
{
	size_t i = model_sample_at(m, cam->s_m);
	double p[3], d[3];

	for (double t = ALC_STEP_M; t < ALC_REACH_M; t += ALC_STEP_M) {
		vec3_axpy(p, cam->eye, t, ray);
		if (model_wall_gap(m, &i, p, d) < 0) {
			return t;
		}
	}
	return ALC_REACH_M;
}

/*
 * How far the walls in the middle of the view are, as the light meter of a
 * video processor would weigh them: rays along the view direction and on
 * two cones around it; the distance whose inverse square is the rays'
 * mean (a near wall counts much, as it is much brighter).
 */
static double wall_ahead(const struct model *m, const struct endo_camera *cam)
{
	double right[3], d = march(m, cam, cam->dir), sum = 1 / (d * d);

	vec3_cross(right, cam->dir, cam->up);
	for (int k = 0; k < 2 * ALC_AROUND; k++) {
		double a = 2 * M_PI * k / ALC_AROUND, ray[3];
		double cone = k < ALC_AROUND ? ALC_CONE_RAD : 2 * ALC_CONE_RAD;

		vec3_scale(ray, cam->dir, cos(cone));
		vec3_axpy(ray, ray, sin(cone) * cos(a), cam->up);
		vec3_axpy(ray, ray, sin(cone) * sin(a), right);
		d = march(m, cam, ray);
		sum += 1 / (d * d);
	}
	return sqrt((2 * ALC_AROUND + 1) / sum);
}

/* The light's level for walls WALL_M away (endo.h). */
static double light_level(double wall_m)
{
	double r = wall_m / ENDO_ALC_REF_M;

	return fmax(ENDO_ALC_MIN, fmin(1, r * r));
}

/* Segment I's pool's level in P, or ENDO_DRY_M. */
static double level_of(const struct endosim_patient_state *p, int i)
{
	return p->fluid_m3[i] > 0 && isfinite(p->fluid_level_m[i]) ?
		       p->fluid_level_m[i] : ENDO_DRY_M;
}

/* The lumen around CAM on M, as a straight tube, for what the pools
 * mirror. */
static void lumen_around(const struct model *m, const struct endo_camera *cam,
			 struct endo_liquid *l)
{
	size_t i = model_sample_at(m, cam->s_m);
	const struct centreline_point *c = centreline_sample(m->cl, i);

	vec3_copy(l->axis_p, c->p);
	vec3_copy(l->axis, centreline_sample(m->cl, model_sample_at(
				 m, cam->s_m + ENDO_AXIS_AHEAD_M))->t);
	l->lumen_m = ENDO_LUMEN_SHARE * m->mesh->sample_rho[i] *
		     m->mesh->radial[i];
}

/* The pools of P seen from CAM on M (none without a patient, or on a
 * colon without the nine segments). */
static void liquid_of(const struct model *m,
		      const struct endosim_patient_state *p,
		      struct endo_camera *cam)
{
	struct endo_liquid *l = &cam->liquid;
	int eye = (int)(model_region_at(m, cam->s_m) - m->region);

	memset(l, 0, sizeof(*l));
	l->eye_level_m = ENDO_DRY_M;
	if (!p->enabled || m->regions != ENDOSIM_SEGMENTS ||
	    !(vec3_norm(p->fluid_up) > 0.5)) {
		return;
	}
	vec3_copy(l->up, p->fluid_up);
	vec3_normalize(l->up);
	lumen_around(m, cam, l);
	for (int i = 0; i < ENDOSIM_SEGMENTS; i++) {
		l->level_m[i] = level_of(p, i);
		l->on |= l->level_m[i] != ENDO_DRY_M;
	}
	l->eye_level_m = l->level_m[eye];
	l->under = vec3_dot(cam->eye, l->up) < l->eye_level_m;
}

void endo_camera(const struct model *m, const struct endosim_state *st,
		 struct endo_camera *cam)
{
	const struct endosim_scope_state *sc = &st->scope;
	const struct endosim_haptics_state *h = &st->haptics;
	double shift[3];

	vec3_copy(cam->eye, h->contact ? h->proxy : sc->tip);
	vec3_copy(cam->dir, sc->dir);
	vec3_copy(cam->up, sc->up);
	cam->s_m = sc->tip_s_m;
	cam->pulled_in_m = model_keep_inside(m, model_sample_at(m, sc->tip_s_m),
					     cam->eye, ENDO_WALL_MARGIN_M);
	cam->wall_m = wall_ahead(m, cam);
	cam->exposure = light_level(cam->wall_m);
	liquid_of(m, &st->patient, cam);
	vec3_sub(shift, cam->eye, sc->tip);
	toolview_build(&st->tool, sc, shift, &cam->tool);
	toolview_build_ghost(&st->guide, sc, shift, &cam->expert);
}

static void set_uniforms(const struct program *p,
			 const struct endo_camera *cam, struct endo_rect r)
{
	vec3 eye, centre, up;
	mat4 view;

	for (int k = 0; k < 3; k++) {
		eye[k] = (float)cam->eye[k];
		centre[k] = (float)(cam->eye[k] + cam->dir[k]);
		up[k] = (float)cam->up[k];
	}
	glm_lookat(eye, centre, up, view);
	glUniformMatrix4fv(p->u[U_VIEW], 1, GL_FALSE, view[0]);
	glUniform1f(p->u[U_THETA_MAX], (float)(ENDO_FOV_DEG / 2 * M_PI / 180));
	glUniform1f(p->u[U_FAR], (float)ENDO_FAR_M);
	glUniform1f(p->u[U_EXPOSURE], (float)(EXPOSURE_M2 * cam->exposure));
	glUniform1f(p->u[U_GLOSS], (float)GLOSS);
	glUniform4f(p->u[U_VIEWPORT], (float)r.x, (float)r.y, (float)r.w,
		    (float)r.h);
	glUniform1f(p->u[U_MASK], (float)ENDO_MASK_RADIUS);
	glUniform1f(p->u[U_BLOOD], cam->tool.blood);
}

/* The pools' uniforms: their levels, the segments' ends along the colon
 * of M, the eye's (the dry program has none of them: ignored). */
static void set_liquid(const struct program *p, const struct model *m,
		       const struct endo_camera *cam)
{
	const struct endo_liquid *l = &cam->liquid;
	float level[ENDOSIM_SEGMENTS], end[ENDOSIM_SEGMENTS - 1];

	if (!l->on) {
		return;
	}
	for (int i = 0; i < ENDOSIM_SEGMENTS; i++) {
		level[i] = (float)l->level_m[i];
		if (i + 1 < ENDOSIM_SEGMENTS) {
			end[i] = (float)m->region[i].s1_m;
		}
	}
	glUniform1fv(p->u[U_LEVEL], ENDOSIM_SEGMENTS, level);
	glUniform1fv(p->u[U_SEG_END], ENDOSIM_SEGMENTS - 1, end);
	glUniform3f(p->u[U_UP], (float)l->up[0], (float)l->up[1],
		    (float)l->up[2]);
	glUniform3f(p->u[U_EYE], (float)cam->eye[0], (float)cam->eye[1],
		    (float)cam->eye[2]);
	glUniform1f(p->u[U_EYE_LEVEL], (float)l->eye_level_m);
	glUniform3f(p->u[U_AXIS], (float)l->axis[0], (float)l->axis[1],
		    (float)l->axis[2]);
	glUniform3f(p->u[U_AXIS_P], (float)l->axis_p[0], (float)l->axis_p[1],
		    (float)l->axis_p[2]);
	glUniform1f(p->u[U_LUMEN_R], (float)l->lumen_m);
}

/* The pool a draw's vertices lie in: the colon's own by their s (LEVEL
 * unused), or LEVEL (a polyp's segment's). */
static void set_level(const struct program *p, bool colon, double level)
{
	glUniform1f(p->u[U_S_PER_TEX], colon ? (float)VESSELS_TILE_M : 0);
	glUniform1f(p->u[U_DRAW_LEVEL], (float)level);
}

/* Object to world: frame columns X, Y, Z scaled by S, at P. */
static void set_model(const struct program *p, const double x[3],
		      const double y[3], const double z[3],
		      const double s[3], const double at[3], const float *tint)
{
	mat4 model = GLM_MAT4_IDENTITY_INIT;
	mat3 normal;
	const double *axis[3] = { x, y, z };

	for (int c = 0; c < 3; c++) {
		for (int k = 0; k < 3; k++) {
			model[c][k] = (float)(axis[c][k] * s[c]);
			normal[c][k] = (float)(axis[c][k] / s[c]);
		}
		model[3][c] = (float)at[c];
	}
	glUniformMatrix4fv(p->u[U_MODEL], 1, GL_FALSE, model[0]);
	glUniformMatrix3fv(p->u[U_NORMAL], 1, GL_FALSE, normal[0]);
	glUniform3fv(p->u[U_TINT], 1, tint);
}

static void set_identity(const struct program *p)
{
	static const double x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 },
			    z[3] = { 0, 0, 1 }, one[3] = { 1, 1, 1 },
			    o[3] = { 0, 0, 0 };

	set_model(p, x, y, z, one, o, mucosa_tint);
}

/* Every program's uniforms for CAM's frame in R on M, the colon's model
 * (the identity) set. */
static void set_programs(struct endo *e, const struct model *m,
			 const struct endo_camera *cam, struct endo_rect r)
{
	for (int k = 0; k < PROGRAMS; k++) {
		const struct program *p = &e->prog[k];

		glUseProgram(p->id);
		set_uniforms(p, cam, r);
		set_liquid(p, m, cam);
		set_identity(p);
		set_level(p, true, 0);
	}
	e->in_use = &e->prog[PROGRAMS - 1];
}

/* Program K in use from now on; it. */
static const struct program *use(struct endo *e, enum program_kind k)
{
	if (e->in_use != &e->prog[k]) {
		e->in_use = &e->prog[k];
		glUseProgram(e->in_use->id);
	}
	return e->in_use;
}

/* The lowest point of box MIN..MAX along UP. */
static double lowest(const float min[3], const float max[3],
		     const double up[3])
{
	double h = 0;

	for (int a = 0; a < 3; a++) {
		h += fmin(min[a] * up[a], max[a] * up[a]);
	}
	return h;
}

/* What draws the walls in S0_M..S1_M, whose lowest point along the
 * surfaces' normal is LOW (m): pools where a segment's surface there
 * lies above it (or a wet line's width below). */
static enum program_kind program_for(const struct model *m,
				 const struct endo_liquid *l, double s0_m,
				 double s1_m, double low)
{
	if (!l->on) {
		return PROG_DRY;
	}
	if (l->under) {
		return PROG_UNDER;
	}
	for (int i = 0; i < m->regions && i < ENDOSIM_SEGMENTS; i++) {
		if (m->region[i].s1_m >= s0_m && m->region[i].s0_m <= s1_m &&
		    l->level_m[i] + ENDO_WET_M > low) {
			return PROG_POOLS;
		}
	}
	return PROG_DRY;
}

static uint32_t draw_colon(struct endo *e, const struct model *m,
			   const struct lod *l, const struct gpumesh *g,
			   const struct endo_camera *cam,
			   const struct portal_view *v, struct endo_stats *st)
{
	struct portal_item seen[PORTAL_MAX];
	int n = portal_find(m, v, cam->s_m, seen);
	uint32_t tris = 0;

	gpumesh_bind(g);
	for (int k = 0; k < n; k++) {
		const struct mesh_segment *sg = &m->mesh->seg[seen[k].segment];

		use(e, program_for(m, &cam->liquid, sg->s0_m, sg->s1_m,
				   lowest(sg->min, sg->max, cam->liquid.up)));
		tris += gpumesh_draw(g, lod_segment(l, seen[k].level,
						    seen[k].segment));
	}
	st->segments = (uint32_t)n;
	return tris;
}

/* One ellipsoid of a polyp: centre OFFSET radii along the normal, RADII. */
struct blob {
	double offset;
	double radii[3];
};

static const struct blob polyp_blobs[][2] = {
	[MODEL_POLYP_SESSILE] = { { 0.25, { 1, 1, 0.85 } } },
	[MODEL_POLYP_PEDUNCULATED] = { { 0.8, { 0.35, 0.35, 1.0 } },
				       { 2.0, { 1, 1, 0.95 } } },
	[MODEL_POLYP_FLAT] = { { 0.0, { 1, 1, 0.3 } } },
};

/* A cut polyp, lying free: its body alone, flattened on the wall. */
static const struct blob lying_blob[2] = { { 0.0, { 1, 1, 0.85 } } };

/*
 * Polyp P's blobs BL (offsets along N, in its radii) from AT on the wall
 * (N out of it, unit): what is not out of sight, in its segment's pools'
 * program. The triangles drawn.
 */
static uint32_t draw_blobs(struct endo *e, const struct model *m,
			   const struct model_polyp *p, const struct blob *bl,
			   const double at[3], const double n[3],
			   const struct endo_liquid *l,
			   const struct portal_view *v)
{
	double r = p->diameter_m / 2, x[3], y[3], c[3], s[3];
	int seg = (int)(model_region_at(m, p->s_m) - m->region);
	const struct program *prog;
	uint32_t tris = 0;

	if (!portal_sphere_visible(v, at, 3 * r)) {
		return 0;
	}
	prog = use(e, program_for(m, l, p->s_m, p->s_m,
				  vec3_dot(at, l->up) - 3 * r));
	set_level(prog, false, seg < ENDOSIM_SEGMENTS ? l->level_m[seg] :
							ENDO_DRY_M);
	vec3_copy(x, centreline_sample(m->cl, model_sample_at(m, p->s_m))->t);
	vec3_axpy(x, x, -vec3_dot(x, n), n);
	vec3_normalize(x);
	vec3_cross(y, n, x);
	for (int b = 0; b < 2 && bl[b].radii[0] > 0; b++) {
		vec3_axpy(c, at, bl[b].offset * r, n);
		vec3_scale(s, bl[b].radii, r);
		set_model(prog, x, y, n, s, c, polyp_tint);
		glDrawElements(GL_TRIANGLES, SHAPES_SPHERE_INDICES,
			       GL_UNSIGNED_INT, NULL);
		tris += SHAPES_SPHERE_INDICES / 3;
	}
	return tris;
}

/* Polyp P where the case put it, standing on the wall. */
static uint32_t draw_polyp(struct endo *e, const struct model *m,
			   const struct model_polyp *p,
			   const struct endo_liquid *l,
			   const struct portal_view *v)
{
	double at[3], n[3];

	model_wall(m, model_sample_at(m, p->s_m), p->angle_rad, at, n);
	return draw_blobs(e, m, p, polyp_blobs[p->shape], at, n, l, v);
}

/* Polyp P cut, lying at LIE (its body's centre): flattened towards the
 * wall, away from its ring's centre. */
static uint32_t draw_lying(struct endo *e, const struct model *m,
			   const struct model_polyp *p, const float lie[3],
			   const struct endo_liquid *l,
			   const struct portal_view *v)
{
	const double *o =
		centreline_sample(m->cl, model_sample_at(m, p->s_m))->p;
	double at[3] = { lie[0], lie[1], lie[2] }, n[3];

	vec3_sub(n, o, at); /* out of the wall: towards the lumen's axis */
	if (!(vec3_normalize(n) > 0)) {
		return 0;
	}
	return draw_blobs(e, m, p, lying_blob, at, n, l, v);
}

/* The case's polyps: those cut where they lie, those retrieved not at
 * all (CAM's tool: lying, gone), the rest where they stand. */
static uint32_t draw_polyps(struct endo *e, const struct model *m,
			    const struct endo_camera *cam,
			    const struct portal_view *v)
{
	const struct toolview *tv = &cam->tool;
	uint32_t tris = 0;

	glBindVertexArray(e->sphere_vao);
	for (int k = 0; k < m->polyps; k++) {
		bool mine = k < ENDOSIM_POLYPS;

		if (mine && (tv->gone >> k & 1u)) {
			continue;
		}
		tris += mine && (tv->lying >> k & 1u) ?
				draw_lying(e, m, &m->polyp[k], tv->lie[k],
					   &cam->liquid, v) :
				draw_polyp(e, m, &m->polyp[k], &cam->liquid,
					   v);
	}
	return tris;
}

/*
 * A tool (TV's parts): each a tube through its points on the plain
 * texture in its colour, the steel glossier than the plastic; with the
 * dry walls' program (a tool under a pool's surface is drawn clear). A
 * ghost (the expert's) translucent over what is drawn, writing no depth.
 */
static uint32_t draw_tool(struct endo *e, const struct toolview *tv)
{
	static float v[TOOLVIEW_POINTS * (SHAPES_TUBE_SIDES + 1)][9];
	const struct program *p;
	uint32_t tris = 0;

	if (!tv->parts) {
		return 0;
	}
	if (tv->ghost) {
		glEnable(GL_BLEND);
		glBlendColor(0, 0, 0, TOOLVIEW_GHOST_ALPHA);
		glBlendFunc(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA);
		glDepthMask(GL_FALSE);
	}
	p = use(e, PROG_DRY);
	set_identity(p); /* a polyp's may be set */
	glBindTexture(GL_TEXTURE_2D, e->plain);
	glBindVertexArray(e->tool_vao);
	glBindBuffer(GL_ARRAY_BUFFER, e->tool_buf[0]);
	for (int k = 0; k < tv->parts; k++) {
		const struct toolview_part *pt = &tv->part[k];
		size_t n = (size_t)pt->points;

		shapes_tube((const float(*)[3])pt->p, n, pt->radius_m, v);
		glBufferSubData(GL_ARRAY_BUFFER, 0,
				(GLsizeiptr)(shapes_tube_vertices(n) *
					     sizeof(v[0])), v);
		glUniform3fv(p->u[U_TINT], 1, pt->rgb);
		glUniform1f(p->u[U_GLOSS], pt->metal ? 2 * GLOSS : GLOSS / 4);
		glDrawElements(GL_TRIANGLES,
			       (GLsizei)(6 * (n - 1) * SHAPES_TUBE_SIDES),
			       GL_UNSIGNED_INT, NULL);
		tris += (uint32_t)(2 * (n - 1) * SHAPES_TUBE_SIDES);
	}
	glDisable(GL_BLEND);
	glDepthMask(GL_TRUE);
	return tris; /* set_programs() sets the gloss again next frame */
}

static void begin(struct endo_rect r)
{
	glViewport(r.x, r.y, r.w, r.h);
	glEnable(GL_SCISSOR_TEST);
	glScissor(r.x, r.y, r.w, r.h);
	glClearColor(0, 0, 0, 1);
	glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
	glEnable(GL_DEPTH_TEST);
	glDepthFunc(GL_LESS);
	glEnable(GL_CULL_FACE);
	glCullFace(GL_BACK);
	glFrontFace(GL_CCW);
}

static void end(void)
{
	glBindVertexArray(0);
	glDisable(GL_CULL_FACE);
	glDisable(GL_DEPTH_TEST);
	glDisable(GL_SCISSOR_TEST);
}

bool endo_project(const struct endo_camera *cam, struct endo_rect r,
		  const double x[3], double px[2])
{
	double d[3], right[3], up[3], v[3], len, th, l;

	vec3_sub(d, x, cam->eye);
	vec3_cross(right, cam->dir, cam->up);
	if (!(vec3_normalize(right) > 0) || !((len = vec3_norm(d)) > 0)) {
		return false;
	}
	vec3_cross(up, right, cam->dir);
	vec3_set(v, vec3_dot(d, right), vec3_dot(d, up), -vec3_dot(d, cam->dir));
	th = acos(fmax(-1, fmin(1, -v[2] / len)));
	l = hypot(v[0], v[1]);
	if (th > 1.95) { /* behind the lens (the shader's) */
		return false;
	}
	th /= ENDO_FOV_DEG / 2 * M_PI / 180;
	px[0] = r.x + (1 + (l > 0 ? v[0] / l : 0) * th) / 2 * r.w;
	px[1] = r.y + (1 + (l > 0 ? v[1] / l : 1) * th) / 2 * r.h;
	return true;
}

void endo_draw(struct endo *e, const struct model *m, const struct lod *l,
	       const struct gpumesh *g, const struct endo_camera *cam,
	       struct endo_rect r, struct endo_stats *st)
{
	struct portal_view v = {
		.half_angle = ENDO_HALF_ANGLE_RAD,
		.far_m = ENDO_FAR_M,
		.level_m = { ENDO_LEVEL_M },
	};

	vec3_copy(v.eye, cam->eye);
	vec3_copy(v.dir, cam->dir);
	memset(st, 0, sizeof(*st));
	begin(r);
	set_programs(e, m, cam, r);
	glActiveTexture(GL_TEXTURE0);
	glBindTexture(GL_TEXTURE_2D, e->texture);
	st->triangles = draw_colon(e, m, l, g, cam, &v, st);
	st->triangles += draw_polyps(e, m, cam, &v);
	st->triangles += draw_tool(e, &cam->tool);
	st->triangles += draw_tool(e, &cam->expert);
	end();
}
