/* overview.c - see overview.h. */
#include "viewer/overview.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include <cglm/cglm.h>

#include "viewer/gfx.h"
#include "base/log.h"
#include "model/scope.h"
#include "viewer/shapes.h"
#include "base/vec3.h"

#define FOV_DEG 30.0
#define STRIPE_RADIUS_M 0.0016  /* the roll's line, on its surface */
#define OUTSIDE 0.45f           /* the tube outside the patient: dimmer */
#define TIP_RADIUS_M 0.006
#define CONTACT_RADIUS_M 0.012  /* larger than the tip: it shows round it */
#define ARROW_M 0.03
#define GHOST_GAIN 0.55f
#define REFERENCE_GAIN 2.5f /* guided replay's reference: a brighter ghost */
#define LUMEN_GIVE_M 0.005 /* a tube pressed into the wall (overview_print) */

static const float scope_rgb[3] = { OVERVIEW_SCOPE_RGB };
static const float outside_rgb[3] = { 0.20f * OUTSIDE, 0.95f * OUTSIDE,
				       0.30f * OUTSIDE };
static const float stripe_rgb[3] = { 0.95f, 0.97f, 1.0f };
static const float stripe_out_rgb[3] = { 0.95f * OUTSIDE, 0.97f * OUTSIDE,
					  OUTSIDE };
static const float tip_rgb[3] = { 1.0f, 1.0f, 0.85f };
static const float contact_rgb[3] = { 1.0f, 0.15f, 0.1f };
static const float colon_rgb[3] = { 0.95f, 0.55f, 0.50f };
static const float bowed_rgb[3] = { 1.0f, 0.62f, 0.08f };
static const float background[3] = { 0.035f, 0.045f, 0.07f };
static const float reference_rgb[3] = { 0.35f, 0.70f, 1.0f };

enum uniform { U_MVP, U_MODEL, U_COLOR, U_EYE, U_GHOST, UNIFORMS };

static const char *const uniform_name[UNIFORMS] = {
	"u_mvp", "u_model", "u_color", "u_eye", "u_ghost",
};

enum { SPHERE, TUBE, STRIPE, REFERENCE, ARROW, SHAPES };

struct overview {
	GLuint program;
	GLint u[UNIFORMS];
	GLuint vao[SHAPES], vbo[SHAPES], ebo[SHAPES];
	mat4 vp;             /* world to clip, the mirror included */
	struct endo_rect rect;
	uint64_t scene_id;   /* of the bounds below */
	double centre[3], radius;
};

static const char *vertex_src =
	"#version 330 core\n"
	"uniform mat4 u_mvp;\n"
	"uniform mat4 u_model;\n"
	"in vec3 a_position;\n"
	"in vec3 a_normal;\n"
	"out vec3 v_pos;\n"
	"out vec3 v_nrm;\n"
	"void main() {\n"
	"	v_pos = (u_model * vec4(a_position, 1.0)).xyz;\n"
	"	v_nrm = mat3(u_model) * a_normal;\n"
	"	gl_Position = u_mvp * vec4(a_position, 1.0);\n"
	"}\n";

static const char *fragment_src =
	"#version 330 core\n"
	"uniform vec3 u_color;\n"
	"uniform vec3 u_eye;\n"
	"uniform float u_ghost;\n"
	"in vec3 v_pos;\n"
	"in vec3 v_nrm;\n"
	"out vec4 frag;\n"
	"void main() {\n"
	"	vec3 V = normalize(u_eye - v_pos);\n"
	"	float f = abs(dot(normalize(v_nrm), V));\n"
	"	if (u_ghost > 0.0) {\n"
	"		float rim = 1.0 - f;\n"
	"		vec3 c = u_color * u_ghost * (0.04 + rim * rim);\n"
	"		frag = vec4(c, 1.0);\n"
	"	} else {\n"
	"		frag = vec4(u_color * (0.35 + 0.65 * f), 1.0);\n"
	"	}\n"
	"}\n";

static void shape_buffers(struct overview *o, int k, GLsizeiptr vbytes,
			  const void *v, GLsizeiptr ibytes, const void *idx,
			  GLenum usage)
{
	const GLsizei stride = 9 * sizeof(float);

	glBindVertexArray(o->vao[k]);
	glBindBuffer(GL_ARRAY_BUFFER, o->vbo[k]);
	glBufferData(GL_ARRAY_BUFFER, vbytes, v, usage);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, o->ebo[k]);
	glBufferData(GL_ELEMENT_ARRAY_BUFFER, ibytes, idx, GL_STATIC_DRAW);
	for (int a = 0; a < 2; a++) {
		glEnableVertexAttribArray((GLuint)a);
		uintptr_t at = 3 * (uintptr_t)a * sizeof(float);

		glVertexAttribPointer((GLuint)a, 3, GL_FLOAT, GL_FALSE, stride,
				      (void *)at);
	}
}

static void make_shapes(struct overview *o)
{
	static float sphere[SHAPES_SPHERE_VERTICES][9];
	static uint32_t sphere_idx[SHAPES_SPHERE_INDICES];
	static uint32_t tube_idx[6 * (ENDOSIM_ROD_POINTS - 1) *
				 SHAPES_TUBE_SIDES];
	static const float line[2][3] = { { 0, 0, 0 }, { 0, 0, 1 } };
	float arrow[2 * (SHAPES_TUBE_SIDES + 1)][9];
	uint32_t arrow_idx[6 * SHAPES_TUBE_SIDES];
	size_t tube_bytes = shapes_tube_vertices(ENDOSIM_ROD_POINTS) * 9 *
			    sizeof(float);

	glGenVertexArrays(SHAPES, o->vao);
	glGenBuffers(SHAPES, o->vbo);
	glGenBuffers(SHAPES, o->ebo);
	shapes_sphere(sphere, sphere_idx);
	shape_buffers(o, SPHERE, sizeof(sphere), sphere, sizeof(sphere_idx),
		      sphere_idx, GL_STATIC_DRAW);
	shapes_tube_index(ENDOSIM_ROD_POINTS, tube_idx);
	for (int k = TUBE; k <= REFERENCE; k++) {
		shape_buffers(o, k, (GLsizeiptr)tube_bytes, NULL,
			      sizeof(tube_idx), tube_idx, GL_STREAM_DRAW);
	}
	shapes_tube(line, 2, 1, arrow);
	shapes_tube_index(2, arrow_idx);
	shape_buffers(o, ARROW, sizeof(arrow), arrow, sizeof(arrow_idx),
		      arrow_idx, GL_STATIC_DRAW);
	glBindVertexArray(0);
}

struct overview *overview_create(void)
{
	struct overview *o = calloc(1, sizeof(*o));

	if (!o) {
		return NULL;
	}
	o->program = gfx_program("overview", vertex_src, fragment_src);
	if (!o->program) {
		free(o);
		return NULL;
	}
	for (int k = 0; k < UNIFORMS; k++) {
		o->u[k] = glGetUniformLocation(o->program, uniform_name[k]);
	}
	make_shapes(o);
	return o;
}

void overview_destroy(struct overview *o)
{
	if (!o) {
		return;
	}
	glDeleteBuffers(SHAPES, o->ebo);
	glDeleteBuffers(SHAPES, o->vbo);
	glDeleteVertexArrays(SHAPES, o->vao);
	glDeleteProgram(o->program);
	free(o);
}

/* The undeformed colon's middle and reach, once per scene. */
static void bounds(struct overview *o, const struct model *m)
{
	double lo[3], hi[3], rho = 0;
	size_t n = centreline_count(m->cl);

	if (o->scene_id == m->scene_id) {
		return;
	}
	vec3_copy(lo, centreline_base(m->cl, 0)->p);
	vec3_copy(hi, lo);
	for (size_t i = 0; i < n; i++) {
		const double *p = centreline_base(m->cl, i)->p;

		for (int k = 0; k < 3; k++) {
			lo[k] = fmin(lo[k], p[k]);
			hi[k] = fmax(hi[k], p[k]);
		}
		rho = fmax(rho, m->mesh->sample_rho[i]);
	}
	vec3_lerp(o->centre, lo, hi, 0.5);
	o->radius = 0.5 * vec3_dist(lo, hi) + rho;
	o->scene_id = m->scene_id;
}

/* World to clip: the mirror (the patient's left to the viewer's right
 * from the front), the orbit's camera, a perspective that fits the colon.
 * EYE: the camera in world coordinates. */
static void view_projection(struct overview *o,
			    const struct overview_orbit *orbit,
			    struct endo_rect r, double eye[3])
{
	double aspect = (double)r.w / (r.h > 0 ? r.h : 1);
	double half = FOV_DEG / 2 * M_PI / 180;
	double fit = fmin(half, atan(tan(half) * aspect));
	double dist = o->radius / sin(fit) / fmax(orbit->zoom, 0.1);
	double cp = cos(orbit->pitch_rad);
	vec3 at = { (float)-o->centre[0], (float)o->centre[1],
		    (float)o->centre[2] };
	vec3 from, up = { 0, 0, 1 };
	mat4 mirror = GLM_MAT4_IDENTITY_INIT, view, proj;

	from[0] = at[0] + (float)(dist * cp * sin(orbit->yaw_rad));
	from[1] = at[1] + (float)(dist * cp * cos(orbit->yaw_rad));
	from[2] = at[2] + (float)(dist * sin(orbit->pitch_rad));
	vec3_set(eye, -from[0], from[1], from[2]);
	mirror[0][0] = -1;
	glm_lookat(from, at, up, view);
	glm_perspective((float)(2 * half), (float)aspect,
			(float)(dist - 2 * o->radius > 0.01 ?
					dist - 2 * o->radius : 0.01),
			(float)(dist + 2 * o->radius), proj);
	glm_mat4_mul(proj, view, o->vp);
	glm_mat4_mul(o->vp, mirror, o->vp);
}

/* Draws the triangles of shape K from index FIRST, INDICES of them, with
 * MODEL, colour RGB; returns their number. */
static uint32_t draw_range(const struct overview *o, int k, mat4 model,
			   const float rgb[3], size_t first, GLsizei indices)
{
	mat4 mvp;

	glm_mat4_mul((vec4 *)o->vp, model, mvp);
	glUniformMatrix4fv(o->u[U_MVP], 1, GL_FALSE, mvp[0]);
	glUniformMatrix4fv(o->u[U_MODEL], 1, GL_FALSE, model[0]);
	glUniform3fv(o->u[U_COLOR], 1, rgb);
	glBindVertexArray(o->vao[k]);
	glDrawElements(GL_TRIANGLES, indices, GL_UNSIGNED_INT,
		       (void *)(first * sizeof(uint32_t)));
	return (uint32_t)indices / 3;
}

static uint32_t draw_shape(const struct overview *o, int k, mat4 model,
			   const float rgb[3], GLsizei indices)
{
	return draw_range(o, k, model, rgb, 0, indices);
}

static uint32_t sphere_at(const struct overview *o, const double p[3],
			  double radius, const float rgb[3])
{
	mat4 model = GLM_MAT4_IDENTITY_INIT;

	for (int k = 0; k < 3; k++) {
		model[k][k] = (float)radius;
		model[3][k] = (float)p[k];
	}
	return draw_shape(o, SPHERE, model, rgb, SHAPES_SPHERE_INDICES);
}

/* A thin rod from P along the unit D, LEN long. */
static uint32_t arrow_at(const struct overview *o, const double p[3],
			 const double d[3], double len, const float rgb[3])
{
	mat4 model = GLM_MAT4_IDENTITY_INIT;
	double a[3] = { d[1], -d[0], 0 }, b[3];

	if (vec3_normalize(a) == 0) {
		vec3_set(a, 1, 0, 0);
	}
	vec3_cross(b, d, a);
	for (int k = 0; k < 3; k++) {
		model[0][k] = (float)(a[k] * SCOPE_RADIUS_M * 0.3);
		model[1][k] = (float)(b[k] * SCOPE_RADIUS_M * 0.3);
		model[2][k] = (float)(d[k] * len);
		model[3][k] = (float)p[k];
	}
	return draw_shape(o, ARROW, model, rgb, 6 * SHAPES_TUBE_SIDES);
}

/* The rod's points published. */
static size_t rod_points(const struct endosim_rod_state *rod)
{
	return rod->points < ENDOSIM_ROD_POINTS ? rod->points :
						  ENDOSIM_ROD_POINTS;
}

/* Shape K, a tube of RADIUS through the N points P: its segments up to
 * point FROM in DIM, those after in RGB. Returns the triangles. */
static uint32_t draw_tube(const struct overview *o, int k,
			  const float (*p)[3], size_t n, double radius,
			  size_t from, const float dim[3], const float rgb[3])
{
	static float v[ENDOSIM_ROD_POINTS * (SHAPES_TUBE_SIDES + 1)][9];
	const size_t side = 6 * SHAPES_TUBE_SIDES;
	mat4 identity = GLM_MAT4_IDENTITY_INIT;
	uint32_t tris = 0;

	from = from < n - 1 ? from : n - 1;
	shapes_tube(p, n, (float)radius, v);
	glBindBuffer(GL_ARRAY_BUFFER, o->vbo[k]);
	glBufferSubData(GL_ARRAY_BUFFER, 0,
			(GLsizeiptr)(shapes_tube_vertices(n) * sizeof(v[0])),
			v);
	if (from > 0) {
		tris += draw_range(o, k, identity, dim, 0,
				   (GLsizei)(side * from));
	}
	if (from + 1 < n) {
		tris += draw_range(o, k, identity, rgb, side * from,
				   (GLsizei)(side * (n - 1 - from)));
	}
	return tris;
}

/* The rod model's whole tube, dimmer outside the patient, with the line
 * of its roll. */
static uint32_t draw_rod(const struct overview *o, const struct model *m,
			 const struct endosim_rod_state *rod)
{
	static float stripe[ENDOSIM_ROD_POINTS][3];
	const float(*p)[3] = (const float(*)[3])rod->point;
	size_t n = rod_points(rod), from = 0;

	if (n < 2) {
		return 0;
	}
	while (from < n && model_outside(m, p[from])) {
		from++;
	}
	shapes_stripe(p, rod->roll, n, centreline_base(m->cl, 0)->u,
		      (float)m->scope_radius_m, stripe);
	return draw_tube(o, TUBE, p, n, m->scope_radius_m, from, outside_rgb,
			 scope_rgb) +
	       draw_tube(o, STRIPE, (const float(*)[3])stripe, n,
			 STRIPE_RADIUS_M, from, stripe_out_rgb, stripe_rgb);
}

static uint32_t draw_scope(const struct overview *o, const struct model *m,
			   const struct endosim_state *st)
{
	const struct endosim_scope_state *sc = &st->scope;
	const struct endosim_haptics_state *h = &st->haptics;
	uint32_t tris;

	if (st->rod.model == ENDOSIM_MODEL_ROD) {
		tris = draw_rod(o, m, &st->rod);
	} else {
		tris = draw_tube(o, TUBE, (const float(*)[3])sc->tube,
				 ENDOSIM_TUBE_POINTS, m->scope_radius_m, 0,
				 scope_rgb, scope_rgb);
	}
	tris += sphere_at(o, sc->tip, TIP_RADIUS_M, tip_rgb);
	tris += arrow_at(o, sc->tip, sc->dir, ARROW_M, tip_rgb);
	if (h->contact) {
		tris += sphere_at(o, h->proxy, CONTACT_RADIUS_M, contact_rgb);
		tris += arrow_at(o, h->proxy, h->normal, ARROW_M, contact_rgb);
	}
	return tris;
}

/*
 * Guided replay's reference: the scope where the expert's recording had
 * it now (taken over: where the guidance left off), by the paper's
 * kinematics on the colon's centreline from the reference's axes (the
 * scope the daemon renders with: the scene's), drawn as a ghost beside the
 * real one.
 */
static uint32_t draw_reference(const struct overview *o,
			       const struct model *m,
			       const struct endosim_guide_state *g)
{
	static struct scope_pose pose;
	static float tube[SCOPE_TUBE_POINTS][3];
	const struct scope_input in = {
		.depth_m = g->reference[ENDOSIM_AXIS_INSERTION],
		.roll_rad = g->reference[ENDOSIM_AXIS_ROLL],
		.wheel_ud_rad = g->reference[ENDOSIM_AXIS_WHEEL_UD],
		.wheel_lr_rad = g->reference[ENDOSIM_AXIS_WHEEL_LR],
	};

	if (g->phase == ENDOSIM_GUIDE_OFF) {
		return 0;
	}
	scope_update(&m->scope, m->cl, &in, &pose);
	for (int p = 0; p < SCOPE_TUBE_POINTS; p++) {
		for (int d = 0; d < 3; d++) {
			tube[p][d] = (float)pose.tube[p][d];
		}
	}
	return draw_tube(o, REFERENCE, (const float(*)[3])tube,
			 SCOPE_TUBE_POINTS, m->scope_radius_m, 0, reference_rgb,
			 reference_rgb);
}

/* A region's colour: a mobile one turns amber as it bows or moves. */
static void region_rgb(const struct model *m, const struct model_region *rg,
		       float rgb[3])
{
	double f = 0;

	if (rg->span >= 0 && rg->max_bow_m > 0) {
		f = model_moved(m, rg->span, NULL) / rg->max_bow_m;
	}
	for (int k = 0; k < 3; k++) {
		rgb[k] = (float)(colon_rgb[k] +
				 fmin(1, f) * (bowed_rgb[k] - colon_rgb[k]));
	}
}

/* Region I's segments; one it shares with the region before is that
 * one's. Returns false when none is left. */
static bool region_segments(const struct model *m, int i, uint32_t *k0,
			    uint32_t *k1)
{
	const struct model_region *rg = &m->region[i];

	*k0 = mesh_segment_at(m->mesh, rg->s0_m);
	*k1 = mesh_segment_at(m->mesh, rg->s1_m - 1e-6);
	if (i > 0 && *k0 == mesh_segment_at(m->mesh,
					    m->region[i - 1].s1_m - 1e-6)) {
		++*k0;
	}
	return *k0 <= *k1;
}

static uint32_t draw_colon(const struct overview *o, const struct model *m,
			   const struct lod *l, const struct gpumesh *g)
{
	mat4 identity = GLM_MAT4_IDENTITY_INIT;
	uint32_t tris = 0, k0, k1;
	float rgb[3];

	glUniformMatrix4fv(o->u[U_MVP], 1, GL_FALSE, o->vp[0]);
	glUniformMatrix4fv(o->u[U_MODEL], 1, GL_FALSE, identity[0]);
	gpumesh_bind(g);
	for (int i = 0; i < m->regions; i++) {
		if (!region_segments(m, i, &k0, &k1)) {
			continue;
		}
		region_rgb(m, &m->region[i], rgb);
		glUniform3fv(o->u[U_COLOR], 1, rgb);
		tris += gpumesh_draw(g, lod_span(l, LOD_OVERVIEW, k0, k1));
	}
	return tris;
}

static void begin(struct endo_rect r)
{
	glViewport(r.x, r.y, r.w, r.h);
	glEnable(GL_SCISSOR_TEST);
	glScissor(r.x, r.y, r.w, r.h);
	glClearColor(background[0], background[1], background[2], 1);
	glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
	glEnable(GL_DEPTH_TEST);
	glDepthFunc(GL_LESS);
}

static void end(void)
{
	glBindVertexArray(0);
	glDepthMask(GL_TRUE);
	glDisable(GL_BLEND);
	glDisable(GL_DEPTH_TEST);
	glDisable(GL_SCISSOR_TEST);
}

uint32_t overview_draw(struct overview *o, const struct model *m,
		       const struct lod *l, const struct gpumesh *g,
		       const struct endosim_state *st,
		       const struct overview_orbit *orbit, struct endo_rect r)
{
	double eye[3];
	float eyef[3];
	uint32_t tris = 0;

	bounds(o, m);
	view_projection(o, orbit, r, eye);
	o->rect = r;
	for (int k = 0; k < 3; k++) {
		eyef[k] = (float)eye[k];
	}
	begin(r);
	glUseProgram(o->program);
	glUniform3fv(o->u[U_EYE], 1, eyef);
	glUniform1f(o->u[U_GHOST], 0);
	if (st) {
		tris += draw_scope(o, m, st);
	}
	/* the ghost: added light, no depth written, both walls */
	glDepthMask(GL_FALSE);
	glEnable(GL_BLEND);
	glBlendFunc(GL_ONE, GL_ONE);
	if (st) {
		glUniform1f(o->u[U_GHOST], REFERENCE_GAIN);
		tris += draw_reference(o, m, &st->guide);
	}
	glUniform1f(o->u[U_GHOST], GHOST_GAIN);
	tris += draw_colon(o, m, l, g);
	end();
	return tris;
}

bool overview_project(const struct overview *o, const double p[3], int fb_h,
		      float xy[2])
{
	vec4 w = { (float)p[0], (float)p[1], (float)p[2], 1 }, c;

	glm_mat4_mulv((vec4 *)o->vp, w, c);
	if (c[3] <= 0) {
		return false;
	}
	xy[0] = (float)o->rect.x + (c[0] / c[3] + 1) / 2 * (float)o->rect.w;
	xy[1] = (float)fb_h - ((float)o->rect.y +
			       (c[1] / c[3] + 1) / 2 * (float)o->rect.h);
	return true;
}

void overview_labels(const struct overview *o, const struct model *m,
		     struct draw2d *d, int fb_h)
{
	static const float grey[4] = { 0.75f, 0.78f, 0.85f, 0.85f };
	char name[MODEL_NAME];
	float xy[2];

	for (int i = 0; i < m->regions; i++) {
		const struct model_region *rg = &m->region[i];
		size_t k = model_sample_at(m, 0.5 * (rg->s0_m + rg->s1_m));

		if (!overview_project(o, centreline_sample(m->cl, k)->p, fb_h,
				      xy) ||
		    strcmp(rg->name, "anal_canal") == 0) {
			continue;
		}
		snprintf(name, sizeof(name), "%s", rg->name);
		for (char *q = name; *q; q++) {
			*q = *q == '_' ? ' ' : *q;
		}
		draw2d_text(d, FONT_SMALL, xy[0] + 14, xy[1], grey, name);
	}
}

/* "KEY=x,y;x,y..." where the last overview drew the rod's points that lie
 * OUTSIDE the patient, or inside. */
static void print_rod(const struct overview *o, const struct model *m,
		      const struct endosim_rod_state *rod, bool outside,
		      int fb_h, FILE *f)
{
	const char *sep = "";
	float xy[2];

	fprintf(f, "overview: rod_%s=", outside ? "out" : "in");
	for (size_t i = 0; i < rod_points(rod); i++) {
		const float *q = rod->point[i];
		double p[3] = { q[0], q[1], q[2] };

		if (model_outside(m, q) == outside &&
		    overview_project(o, p, fb_h, xy)) {
			fprintf(f, "%s%.1f,%.1f", sep, xy[0], xy[1]);
			sep = ";";
		}
	}
	fputc('\n', f);
}

/* The sample of M nearest P. */
static size_t nearest_sample(const struct model *m, const double p[3])
{
	size_t best = 0;
	double best_d = INFINITY;

	for (size_t i = 0; i < centreline_count(m->cl); i++) {
		double d = vec3_dist(p, centreline_sample(m->cl, i)->p);

		if (d < best_d) {
			best_d = d;
			best = i;
		}
	}
	return best;
}

/* The share of the rod's points inside the patient that lie within the
 * colon as placed, the wall's give (LUMEN_GIVE_M) allowed. */
static void print_in_lumen(const struct model *m,
			   const struct endosim_rod_state *rod, FILE *f)
{
	int in = 0, within = 0;

	for (size_t k = 0; k < rod_points(rod); k++) {
		const float *q = rod->point[k];
		double p[3] = { q[0], q[1], q[2] }, d[3];
		size_t i;

		if (!model_outside(m, q)) {
			i = nearest_sample(m, p);
			within += model_wall_gap(m, &i, p, d) > -LUMEN_GIVE_M;
			in++;
		}
	}
	fprintf(f, "overview: rod_in_lumen=%.3f\n",
		in ? (double)within / in : 0);
}

/* Span K's sample that moved most: where it is drawn, where it would be
 * at rest, and the lumen's radius there, in pixels. */
static void print_span(const struct overview *o, const struct model *m,
		       int k, int fb_h, FILE *f)
{
	size_t i;
	double moved = model_moved(m, k, &i), rim[3], r = 0;
	const struct centreline_point *c = centreline_sample(m->cl, i);
	float at[2] = { 0, 0 }, rest[2] = { 0, 0 }, xy[2];

	overview_project(o, c->p, fb_h, at);
	overview_project(o, centreline_base(m->cl, i)->p, fb_h, rest);
	for (int side = 0; side < 2; side++) {
		vec3_axpy(rim, c->p, m->mesh->sample_rho[i],
			  side ? c->v : c->u);
		if (overview_project(o, rim, fb_h, xy)) {
			r = fmax(r, hypot(xy[0] - at[0], xy[1] - at[1]));
		}
	}
	fprintf(f, "overview: span=%d moved_m=%.4f at=%.1f,%.1f "
		"rest=%.1f,%.1f lumen_px=%.1f\n", k, moved, at[0], at[1],
		rest[0], rest[1], r);
}

void overview_print(const struct overview *o, const struct model *m,
		    const struct endosim_state *st, int fb_h, FILE *f)
{
	if (st && st->rod.model == ENDOSIM_MODEL_ROD) {
		print_rod(o, m, &st->rod, false, fb_h, f);
		print_rod(o, m, &st->rod, true, fb_h, f);
		print_in_lumen(m, &st->rod, f);
	}
	for (int k = 0; k < centreline_spans(m->cl); k++) {
		print_span(o, m, k, fb_h, f);
	}
}
