/* endo.c - see endo.h. */
#include "viewer/endo.h"

#include <math.h>
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

static const float mucosa_tint[3] = { 1.0f, 1.0f, 1.0f };
static const float polyp_tint[3] = { 1.02f, 0.80f, 0.78f };

enum uniform {
	U_VIEW, U_MODEL, U_NORMAL, U_THETA_MAX, U_FAR, U_EXPOSURE, U_TINT,
	U_GLOSS, U_VIEWPORT, U_MASK, UNIFORMS
};

static const char *const uniform_name[UNIFORMS] = {
	"u_view", "u_model", "u_normal", "u_theta_max", "u_far", "u_exposure",
	"u_tint", "u_gloss", "u_viewport", "u_mask",
};

struct endo {
	GLuint program, texture;
	GLint u[UNIFORMS];
	GLuint sphere_vao, sphere_buf[2];
};

static const char *vertex_src =
	"#version 330 core\n"
	"uniform mat4 u_view;\n"
	"uniform mat4 u_model;\n"
	"uniform mat3 u_normal;\n"
	"uniform float u_theta_max;\n"
	"uniform float u_far;\n"
	"in vec3 a_position;\n"
	"in vec3 a_normal;\n"
	"in vec2 a_texcoord;\n"
	"out vec3 v_pos;\n"
	"out vec3 v_nrm;\n"
	"out vec2 v_tex;\n"
	"void main() {\n"
	"	vec4 p = u_view * u_model * vec4(a_position, 1.0);\n"
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
static const char *fragment_src =
	"#version 330 core\n"
	"uniform sampler2D u_texture;\n"
	"uniform float u_exposure;\n"
	"uniform vec3 u_tint;\n"
	"uniform float u_gloss;\n"
	"uniform vec4 u_viewport;\n"
	"uniform float u_mask;\n"
	"in vec3 v_pos;\n"
	"in vec3 v_nrm;\n"
	"in vec2 v_tex;\n"
	"out vec4 frag;\n"
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
	"	c = 1.0 - exp(-c);\n"
	"	vec2 hs = 0.5 * u_viewport.zw;\n"
	"	vec2 q = (gl_FragCoord.xy - u_viewport.xy - hs) / hs.y;\n"
	"	float edge = 2.0 / u_viewport.w;\n"
	"	c *= 1.0 - smoothstep(u_mask - edge, u_mask, length(q));\n"
	"	frag = vec4(c, 1.0);\n"
	"}\n";

static void make_sphere(struct endo *e)
{
	static float v[SHAPES_SPHERE_VERTICES][9];
	static uint32_t idx[SHAPES_SPHERE_INDICES];
	const GLsizei stride = sizeof(v[0]);

	shapes_sphere(v, idx);
	glGenVertexArrays(1, &e->sphere_vao);
	glBindVertexArray(e->sphere_vao);
	glGenBuffers(2, e->sphere_buf);
	glBindBuffer(GL_ARRAY_BUFFER, e->sphere_buf[0]);
	glBufferData(GL_ARRAY_BUFFER, sizeof(v), v, GL_STATIC_DRAW);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, e->sphere_buf[1]);
	glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof(idx), idx,
		     GL_STATIC_DRAW);
	for (int a = 0; a < 3; a++) {
		glEnableVertexAttribArray((GLuint)a);
		uintptr_t at = 3 * (uintptr_t)a * sizeof(float);

		glVertexAttribPointer((GLuint)a, a < 2 ? 3 : 2, GL_FLOAT,
				      GL_FALSE, stride, (void *)at);
	}
	glBindVertexArray(0);
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

struct endo *endo_create(void)
{
	struct endo *e = calloc(1, sizeof(*e));

	if (!e) {
		return NULL;
	}
	e->program = gfx_program("endoscopic view", vertex_src, fragment_src);
	e->texture = e->program ? make_texture() : 0;
	if (!e->texture) {
		endo_destroy(e);
		return NULL;
	}
	for (int k = 0; k < UNIFORMS; k++) {
		e->u[k] = glGetUniformLocation(e->program, uniform_name[k]);
	}
	make_sphere(e);
	return e;
}

void endo_destroy(struct endo *e)
{
	if (!e) {
		return;
	}
	glDeleteBuffers(2, e->sphere_buf);
	glDeleteVertexArrays(1, &e->sphere_vao);
	glDeleteTextures(1, &e->texture);
	glDeleteProgram(e->program);
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

void endo_camera(const struct model *m, const struct endosim_state *st,
		 struct endo_camera *cam)
{
	const struct endosim_scope_state *sc = &st->scope;
	const struct endosim_haptics_state *h = &st->haptics;

	vec3_copy(cam->eye, h->contact ? h->proxy : sc->tip);
	vec3_copy(cam->dir, sc->dir);
	vec3_copy(cam->up, sc->up);
	cam->s_m = sc->tip_s_m;
	cam->pulled_in_m = model_keep_inside(m, model_sample_at(m, sc->tip_s_m),
					     cam->eye, ENDO_WALL_MARGIN_M);
	cam->wall_m = wall_ahead(m, cam);
	cam->exposure = light_level(cam->wall_m);
}

static void set_uniforms(const struct endo *e, const struct endo_camera *cam,
			 struct endo_rect r)
{
	vec3 eye, centre, up;
	mat4 view;

	for (int k = 0; k < 3; k++) {
		eye[k] = (float)cam->eye[k];
		centre[k] = (float)(cam->eye[k] + cam->dir[k]);
		up[k] = (float)cam->up[k];
	}
	glm_lookat(eye, centre, up, view);
	glUseProgram(e->program);
	glUniformMatrix4fv(e->u[U_VIEW], 1, GL_FALSE, view[0]);
	glUniform1f(e->u[U_THETA_MAX], (float)(ENDO_FOV_DEG / 2 * M_PI / 180));
	glUniform1f(e->u[U_FAR], (float)ENDO_FAR_M);
	glUniform1f(e->u[U_EXPOSURE], (float)(EXPOSURE_M2 * cam->exposure));
	glUniform1f(e->u[U_GLOSS], (float)GLOSS);
	glUniform4f(e->u[U_VIEWPORT], (float)r.x, (float)r.y, (float)r.w,
		    (float)r.h);
	glUniform1f(e->u[U_MASK], (float)ENDO_MASK_RADIUS);
}

/* Object to world: frame columns X, Y, Z scaled by S, at P. */
static void set_model(const struct endo *e, const double x[3],
		      const double y[3], const double z[3],
		      const double s[3], const double p[3], const float *tint)
{
	mat4 model = GLM_MAT4_IDENTITY_INIT;
	mat3 normal;
	const double *axis[3] = { x, y, z };

	for (int c = 0; c < 3; c++) {
		for (int k = 0; k < 3; k++) {
			model[c][k] = (float)(axis[c][k] * s[c]);
			normal[c][k] = (float)(axis[c][k] / s[c]);
		}
		model[3][c] = (float)p[c];
	}
	glUniformMatrix4fv(e->u[U_MODEL], 1, GL_FALSE, model[0]);
	glUniformMatrix3fv(e->u[U_NORMAL], 1, GL_FALSE, normal[0]);
	glUniform3fv(e->u[U_TINT], 1, tint);
}

static void set_identity(const struct endo *e)
{
	static const double x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 },
			    z[3] = { 0, 0, 1 }, one[3] = { 1, 1, 1 },
			    o[3] = { 0, 0, 0 };

	set_model(e, x, y, z, one, o, mucosa_tint);
}

static uint32_t draw_colon(const struct endo *e, const struct model *m,
			   const struct lod *l, const struct gpumesh *g,
			   const struct portal_view *v, struct endo_stats *st,
			   double s_m)
{
	struct portal_item seen[PORTAL_MAX];
	int n = portal_find(m, v, s_m, seen);
	uint32_t tris = 0;

	set_identity(e);
	gpumesh_bind(g);
	for (int k = 0; k < n; k++) {
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

static uint32_t draw_polyp(const struct endo *e, const struct model *m,
			   const struct model_polyp *p,
			   const struct portal_view *v)
{
	size_t i = model_sample_at(m, p->s_m);
	double r = p->diameter_m / 2, at[3], n[3], x[3], y[3], c[3], s[3];
	uint32_t tris = 0;

	model_wall(m, i, p->angle_rad, at, n);
	if (!portal_sphere_visible(v, at, 3 * r)) {
		return 0;
	}
	vec3_copy(x, centreline_sample(m->cl, i)->t);
	vec3_axpy(x, x, -vec3_dot(x, n), n);
	vec3_normalize(x);
	vec3_cross(y, n, x);
	for (int b = 0; b < 2 && polyp_blobs[p->shape][b].radii[0] > 0; b++) {
		const struct blob *bl = &polyp_blobs[p->shape][b];

		vec3_axpy(c, at, bl->offset * r, n);
		vec3_scale(s, bl->radii, r);
		set_model(e, x, y, n, s, c, polyp_tint);
		glDrawElements(GL_TRIANGLES, SHAPES_SPHERE_INDICES,
			       GL_UNSIGNED_INT, NULL);
		tris += SHAPES_SPHERE_INDICES / 3;
	}
	return tris;
}

static uint32_t draw_polyps(const struct endo *e, const struct model *m,
			    const struct portal_view *v)
{
	uint32_t tris = 0;

	glBindVertexArray(e->sphere_vao);
	for (int k = 0; k < m->polyps; k++) {
		tris += draw_polyp(e, m, &m->polyp[k], v);
	}
	return tris;
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
	set_uniforms(e, cam, r);
	glActiveTexture(GL_TEXTURE0);
	glBindTexture(GL_TEXTURE_2D, e->texture);
	st->triangles = draw_colon(e, m, l, g, &v, st, cam->s_m);
	st->triangles += draw_polyps(e, m, &v);
	end();
}
