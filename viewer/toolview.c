/* toolview.c - see toolview.h. */
#include "viewer/toolview.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"
#include "model/tool.h"

/* The sheaths' colours: the forceps' blue coat, the snare's white
 * sheath, the needle's clear catheter, the clip's blue one. */
static const float sheath_rgb[ENDOSIM_TOOLS][3] = {
	[ENDOSIM_TOOL_FORCEPS] = { 0.18f, 0.30f, 0.75f },
	[ENDOSIM_TOOL_SNARE] = { 0.90f, 0.90f, 0.86f },
	[ENDOSIM_TOOL_NEEDLE] = { 0.80f, 0.84f, 0.86f },
	[ENDOSIM_TOOL_CLIP] = { 0.30f, 0.50f, 0.85f },
};
static const float steel_rgb[3] = { 0.78f, 0.78f, 0.80f };

/* The frame the tool lies in: the exit, dir, and side = dir x radial
 * (tool.h), all moved by SHIFT. False when there is none to draw. */
struct frame {
	double exit[3], tip[3], dir[3], side[3];
};

static bool frame_of(const struct endosim_tool_state *t,
		     const struct endosim_scope_state *sc,
		     const double shift[3], struct frame *f)
{
	double radial[3];

	if (!(t->depth_m > 0) || !isfinite(vec3_dot(t->tip, t->tip)) ||
	    !isfinite(vec3_dot(sc->tip, sc->tip))) {
		return false;
	}
	vec3_copy(f->dir, sc->dir);
	vec3_axpy(f->exit, t->tip, -t->depth_m, f->dir);
	vec3_sub(radial, f->exit, sc->tip);
	vec3_axpy(radial, radial, -vec3_dot(radial, f->dir), f->dir);
	if (!(vec3_norm(radial) > 0)) {
		return false; /* a channel on the axis: no side */
	}
	vec3_normalize(radial);
	vec3_cross(f->side, f->dir, radial);
	vec3_add(f->exit, f->exit, shift);
	vec3_add(f->tip, t->tip, shift);
	return true;
}

static void put(struct toolview_part *p, const double x[3])
{
	for (int k = 0; k < 3; k++) {
		p->p[p->points][k] = (float)x[k];
	}
	p->points++;
}

static struct toolview_part *part(struct toolview *v, double radius_m,
				  const float rgb[3], bool metal)
{
	struct toolview_part *p = &v->part[v->parts++];

	p->points = 0;
	p->radius_m = (float)radius_m;
	memcpy(p->rgb, rgb, sizeof(p->rgb));
	p->metal = metal;
	return p;
}

/* A straight piece LEN_M long from the tool's tip, turned by ANGLE_RAD
 * from dir towards side. */
static void piece(struct toolview *v, const struct frame *f, double angle_rad,
		  double len_m, double radius_m)
{
	struct toolview_part *p = part(v, radius_m, steel_rgb, true);
	double to[3];

	put(p, f->tip);
	vec3_axpy(to, f->tip, len_m * cos(angle_rad), f->dir);
	vec3_axpy(to, to, len_m * sin(angle_rad), f->side);
	put(p, to);
}

/* The snare's ring round the published centre (moved by SHIFT). */
static void loop(struct toolview *v, const struct frame *f,
		 const struct endosim_tool_state *t, const double shift[3])
{
	struct toolview_part *p;
	double c[3], r = t->loop_m / 2;

	if (!(r > 0) || !isfinite(vec3_dot(t->loop_centre, t->loop_centre))) {
		return;
	}
	vec3_add(c, t->loop_centre, shift);
	p = part(v, TOOLVIEW_WIRE_M / 2, steel_rgb, true);
	for (int k = 0; k < TOOLVIEW_POINTS; k++) {
		/* from the sheath's tip (behind the centre) round and back */
		double phi = M_PI + 2 * M_PI * k / (TOOLVIEW_POINTS - 1), x[3];

		vec3_axpy(x, c, r * cos(phi), f->dir);
		vec3_axpy(x, x, r * sin(phi), f->side);
		put(p, x);
	}
}

void toolview_build(const struct endosim_tool_state *t,
		    const struct endosim_scope_state *sc,
		    const double shift[3], struct toolview *out)
{
	double open = isfinite(t->opening) ? fmax(0, fmin(1, t->opening)) : 0;
	struct toolview_part *sheath;
	struct frame f;

	out->parts = 0;
	if (t->kind <= ENDOSIM_TOOL_NONE || t->kind >= ENDOSIM_TOOLS ||
	    !frame_of(t, sc, shift, &f)) {
		return;
	}
	sheath = part(out, TOOLVIEW_SHEATH_M / 2, sheath_rgb[t->kind], false);
	put(sheath, f.exit);
	put(sheath, f.tip);
	switch (t->kind) {
	case ENDOSIM_TOOL_SNARE:
		loop(out, &f, t, shift);
		break;
	case ENDOSIM_TOOL_FORCEPS:
		for (int s = -1; s <= 1; s += 2) {
			piece(out, &f, s * open * TOOLVIEW_JAWS_RAD,
			      TOOL_DEFAULT_JAW_M, TOOLVIEW_SHEATH_M * 0.35);
		}
		break;
	case ENDOSIM_TOOL_NEEDLE:
		if (open > 0.5) {
			piece(out, &f, 0, TOOL_DEFAULT_NEEDLE_M,
			      TOOLVIEW_WIRE_M * 0.6);
		}
		break;
	case ENDOSIM_TOOL_CLIP:
		for (int s = -1; s <= 1; s += 2) {
			piece(out, &f, s * open * TOOLVIEW_PRONGS_RAD,
			      TOOL_DEFAULT_CLIP_M, TOOLVIEW_WIRE_M);
		}
		break;
	default:
		break;
	}
}
