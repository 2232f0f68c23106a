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
_Static_assert(ENDOSIM_POLYPS <= 32, "toolview: gone holds every polyp");
static const float blood_rgb[3] = { 0.50f, 0.02f, 0.02f };
/* the expert's ghost: a blue near the overview's reference scope's, with
 * little red, so that its hue stays where the light near the lens
 * saturates (endo.c's tone curve); its snare's wire amber while its pedal
 * is down (the HUD's amber) */
static const float ghost_rgb[3] = { 0.05f, 0.45f, 1.00f };
static const float ghost_hot_rgb[3] = { 1.00f, 0.70f, 0.15f };

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

double toolview_redness(double bleed_m3_s)
{
	return bleed_m3_s > 0 && isfinite(bleed_m3_s) ?
		       bleed_m3_s / (bleed_m3_s + TOOLVIEW_BLOOD_M3_S) : 0;
}

/* A short piece LEN_M long from AT (moved by SHIFT) towards the scope's
 * tip: what stands on the wall there. */
static void on_wall(struct toolview *v, const double at[3],
		    const struct endosim_scope_state *sc,
		    const double shift[3], double len_m, double radius_m,
		    const float rgb[3], bool metal)
{
	struct toolview_part *p;
	double from[3], to[3];

	if (!isfinite(vec3_dot(at, at)) || !(vec3_norm(at) > 0) ||
	    !isfinite(vec3_dot(sc->tip, sc->tip))) {
		return;
	}
	vec3_sub(to, sc->tip, at);
	if (!(vec3_normalize(to) > 0)) {
		return;
	}
	vec3_add(from, at, shift);
	vec3_axpy(to, from, len_m, to);
	p = part(v, radius_m, rgb, metal);
	put(p, from);
	put(p, to);
}

/* The tool in hand, out of the channel, into OUT (after its parts). */
static void in_hand(const struct endosim_tool_state *t,
		    const struct endosim_scope_state *sc,
		    const double shift[3], struct toolview *out)
{
	double open = isfinite(t->opening) ? fmax(0, fmin(1, t->opening)) : 0;
	struct toolview_part *sheath;
	struct frame f;

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

void toolview_expert(const struct endosim_guide_state *g,
		     struct endosim_tool_state *out)
{
	memset(out, 0, sizeof(*out));
	out->kind = g->expert_kind;
	out->pedal = g->expert_pedal;
	out->snare_m = g->expert_snare_m;
	out->depth_m = g->expert_depth_m;
	out->opening = g->expert_opening;
	out->loop_m = g->expert_loop_m;
	vec3_copy(out->tip, g->expert_tip);
	vec3_copy(out->loop_centre, g->expert_loop_centre);
	out->captured = -1;
	out->event_polyp = -1;
}

void toolview_build_ghost(const struct endosim_guide_state *g,
			  const struct endosim_scope_state *sc,
			  const double shift[3], struct toolview *out)
{
	struct endosim_tool_state t;

	toolview_expert(g, &t);
	out->ghost = true;
	out->parts = 0;
	out->blood = 0;
	out->gone = 0;
	out->lying = 0;
	in_hand(&t, sc, shift, out);
	for (int k = 0; k < out->parts; k++) {
		/* the snare's wire is its second part (in_hand()) */
		bool hot = t.pedal && t.kind == ENDOSIM_TOOL_SNARE && k == 1;

		memcpy(out->part[k].rgb, hot ? ghost_hot_rgb : ghost_rgb,
		       sizeof(out->part[k].rgb));
	}
}

/* The polyps cut: where each lies (a place not finite: not drawn). */
static void lying(const struct endosim_tool_state *t, struct toolview *out)
{
	out->lying = 0;
	for (uint32_t i = 0; i < t->polyps && i < ENDOSIM_POLYPS; i++) {
		const double *at = t->polyp[i].at;

		if (t->polyp[i].state != ENDOSIM_POLYP_CUT ||
		    !isfinite(vec3_dot(at, at))) {
			continue;
		}
		out->lying |= 1u << i;
		for (int k = 0; k < 3; k++) {
			out->lie[i][k] = (float)at[k];
		}
	}
}

void toolview_build(const struct endosim_tool_state *t,
		    const struct endosim_scope_state *sc,
		    const double shift[3], struct toolview *out)
{
	out->ghost = false;
	out->parts = 0;
	out->blood = (float)toolview_redness(t->bleed_m3_s);
	out->gone = 0;
	for (uint32_t i = 0; i < t->polyps && i < ENDOSIM_POLYPS; i++) {
		out->gone |= (uint32_t)(t->polyp[i].state ==
					ENDOSIM_POLYP_RETRIEVED) << i;
	}
	lying(t, out);
	in_hand(t, sc, shift, out);
	if (t->bleeding > 0) {
		on_wall(out, t->bleed_at, sc, shift, TOOLVIEW_WELL_M,
			TOOLVIEW_WELL_M * (0.6 + 0.8 * out->blood),
			blood_rgb, false);
	}
	if (t->clips > 0) {
		on_wall(out, t->clip_at, sc, shift, TOOLVIEW_CLIP_M,
			TOOLVIEW_WIRE_M * 1.5, steel_rgb, true);
	}
}
