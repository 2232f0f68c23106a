/*
 * test_toolview.c - the tool as the endoscopic view draws it
 * (viewer/toolview.h) against the model's pose (lib/model/tool.h): the
 * sheath from the channel's exit to the published tip; the snare's ring
 * of the published diameter round the published centre, in the plane of
 * dir and dir x radial, starting at the sheath's tip; the forceps' cups
 * and the clip's prongs opening with the handle; the needle only past
 * half open; everything moved with the lens; nothing while the tool is in
 * the channel, for no tool, or for a state not finite; a bleeding point
 * welling from its place towards the tip, the view reddened by the flow,
 * and the clip placed standing on the wall, tool in hand or not; guided
 * replay's expert's tool as a ghost of its own colour.
 * and the clip placed standing on the wall, tool in hand or not; the
 * polyps cut drawn where they lie, those retrieved not at all.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "base/vec3.h"
#include "model/tool.h"
#include "viewer/toolview.h"

#define TOL 1e-6 /* m: floats of positions about 0.1 m from the origin */

static struct endosim_scope_state sc;
static struct endosim_tool_state tool;
static const double none[3] = { 0, 0, 0 };

/* A scope tip at (0.01, 0.02, 0.1) looking along +z, up +y, and the
 * model's pose of tool KIND DEPTH_M out, the handle at OPENING, a snare
 * of 20 mm. */
static void setup_tool(int kind, double depth_m, double opening)
{
	struct tool_params par = TOOL_PARAMS_DEFAULT;
	struct tool_pose pose;

	memset(&sc, 0, sizeof(sc));
	memset(&tool, 0, sizeof(tool));
	vec3_set(sc.tip, 0.01, 0.02, 0.1);
	vec3_set(sc.dir, 0, 0, 1);
	vec3_set(sc.up, 0, 1, 0);
	tool_pose(&par, &sc, depth_m, &pose);
	tool.kind = (uint32_t)kind;
	tool.depth_m = depth_m;
	tool.opening = opening;
	tool.snare_m = 0.020;
	vec3_copy(tool.tip, pose.tip);
	tool.loop_m = tool_loop_diameter(tool.snare_m, opening, depth_m);
	vec3_axpy(tool.loop_centre, pose.tip, tool.loop_m / 2, pose.dir);
}

static double dist_f(const float a[3], const double b[3])
{
	double d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };

	return vec3_norm(d);
}

/* The sheath: from the model's exit to its tip. */
static void sheath(void **state)
{
	struct tool_params par = TOOL_PARAMS_DEFAULT;
	struct tool_pose pose;
	struct toolview v;

	(void)state;
	setup_tool(ENDOSIM_TOOL_SNARE, 0.015, 1);
	tool_pose(&par, &sc, 0.015, &pose);
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 2);
	assert_int_equal(v.part[0].points, 2);
	assert_true(dist_f(v.part[0].p[0], pose.exit) < TOL);
	assert_true(dist_f(v.part[0].p[1], pose.tip) < TOL);
	assert_false(v.part[0].metal);
	assert_true(fabs(v.part[0].radius_m - TOOLVIEW_SHEATH_M / 2) < 1e-9);
}

/* The snare's ring: its points at half the loop from the centre, in the
 * plane that holds dir and is normal to the channel's radial direction,
 * starting and ending at the sheath's tip. */
static void snare_ring(void **state)
{
	struct tool_params par = TOOL_PARAMS_DEFAULT;
	struct tool_pose pose;
	struct toolview v;
	const struct toolview_part *r;

	(void)state;
	setup_tool(ENDOSIM_TOOL_SNARE, 0.010, 0.8);
	tool_pose(&par, &sc, 0.010, &pose);
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 2);
	r = &v.part[1];
	assert_int_equal(r->points, TOOLVIEW_POINTS);
	assert_true(r->metal);
	assert_true(tool.loop_m > 0.01);
	for (int k = 0; k < r->points; k++) {
		double x[3] = { r->p[k][0], r->p[k][1], r->p[k][2] };

		assert_true(fabs(dist_f(r->p[k], tool.loop_centre) -
				 tool.loop_m / 2) < TOL);
		vec3_sub(x, x, tool.loop_centre);
		assert_true(fabs(vec3_dot(x, pose.radial)) < TOL);
	}
	assert_true(dist_f(r->p[0], pose.tip) < TOL);
	assert_true(dist_f(r->p[r->points - 1], pose.tip) < TOL);
}

/* The angle (rad) of part P's piece from dir. */
static double angle_of(const struct toolview_part *p)
{
	double d[3];

	for (int k = 0; k < 3; k++) {
		d[k] = p->p[1][k] - p->p[0][k];
	}
	return acos(d[2] / vec3_norm(d));
}

/* The forceps' cups and the clip's prongs open with the handle, the
 * model's lengths; the needle is out only past half open. */
static void jaws(void **state)
{
	struct toolview v;

	(void)state;
	setup_tool(ENDOSIM_TOOL_FORCEPS, 0.010, 1);
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 3);
	for (int k = 1; k < 3; k++) {
		assert_true(fabs(angle_of(&v.part[k]) - TOOLVIEW_JAWS_RAD) <
			    1e-5);
		assert_true(fabs(dist_f(v.part[k].p[1], tool.tip) -
				 TOOL_DEFAULT_JAW_M) < TOL);
	}
	setup_tool(ENDOSIM_TOOL_FORCEPS, 0.010, 0);
	toolview_build(&tool, &sc, none, &v);
	assert_true(angle_of(&v.part[1]) < 1e-3);
	setup_tool(ENDOSIM_TOOL_CLIP, 0.010, 0.5);
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 3);
	assert_true(fabs(angle_of(&v.part[2]) - 0.5 * TOOLVIEW_PRONGS_RAD) <
		    1e-5);
	assert_true(fabs(dist_f(v.part[2].p[1], tool.tip) -
			 TOOL_DEFAULT_CLIP_M) < TOL);
	setup_tool(ENDOSIM_TOOL_NEEDLE, 0.010, 0.4);
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 1);
	setup_tool(ENDOSIM_TOOL_NEEDLE, 0.010, 0.6);
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 2);
	assert_true(fabs(dist_f(v.part[1].p[1], tool.tip) -
			 TOOL_DEFAULT_NEEDLE_M) < TOL);
}

/* The lens moved (the proxy): the tool goes with it. */
static void with_the_lens(void **state)
{
	static const double shift[3] = { 0.001, -0.002, 0.0005 };
	struct toolview a, b;

	(void)state;
	setup_tool(ENDOSIM_TOOL_SNARE, 0.012, 1);
	toolview_build(&tool, &sc, none, &a);
	toolview_build(&tool, &sc, shift, &b);
	assert_int_equal(a.parts, b.parts);
	for (int k = 0; k < a.parts; k++) {
		for (int j = 0; j < a.part[k].points; j++) {
			for (int x = 0; x < 3; x++) {
				assert_true(fabs(b.part[k].p[j][x] -
						 a.part[k].p[j][x] -
						 shift[x]) < TOL);
			}
		}
	}
}

/* Nothing to draw: in the channel, no tool, a tool not finite. */
static void nothing(void **state)
{
	struct toolview v;

	(void)state;
	setup_tool(ENDOSIM_TOOL_SNARE, -0.002, 1);
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 0);
	setup_tool(ENDOSIM_TOOL_NONE, 0.010, 1);
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 0);
	setup_tool(ENDOSIM_TOOL_SNARE, 0.010, 1);
	tool.tip[1] = NAN;
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 0);
	setup_tool(ENDOSIM_TOOL_SNARE, 0.010, 1);
	tool.loop_centre[0] = NAN;
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 1); /* the sheath, no ring */
}

/* What the tools left: no tool in hand, a point bleeding a 5 mm stalk's
 * flow (the view half red) welling from bleed_at towards the tip, and
 * the clip placed standing at clip_at; nothing of either without them. */
static void on_the_wall(void **unused)
{
	struct toolview v;
	double at[3], to_tip[3], d[3];

	(void)unused;
	setup_tool(ENDOSIM_TOOL_NONE, -0.01, 0);
	vec3_set(at, 0.02, 0.0, 0.13);
	vec3_copy(tool.bleed_at, at);
	tool.bleed_m3_s = TOOLVIEW_BLOOD_M3_S;
	tool.bleeding = 1;
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 1);
	assert_true(fabs(v.blood - 0.5) < 1e-6);
	assert_true(dist_f(v.part[0].p[0], at) < TOL);
	assert_true(v.part[0].rgb[0] > 4 * v.part[0].rgb[1]); /* red */
	vec3_sub(to_tip, sc.tip, at);
	vec3_normalize(to_tip);
	for (int k = 0; k < 3; k++) {
		d[k] = v.part[0].p[1][k] - v.part[0].p[0][k];
	}
	assert_true(fabs(vec3_dot(d, to_tip) - TOOLVIEW_WELL_M) < TOL);
	tool.clips = 1;
	vec3_set(tool.clip_at, 0.021, 0.0, 0.13);
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 2);
	assert_true(dist_f(v.part[1].p[0], tool.clip_at) < TOL);
	assert_true(v.part[1].metal);
	tool.bleeding = 0;
	tool.bleed_m3_s = 0;
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.parts, 1);
	assert_true(v.part[0].metal);
	assert_true(v.blood == 0);
	assert_true(toolview_redness(NAN) == 0);
	assert_true(fabs(toolview_redness(3 * TOOLVIEW_BLOOD_M3_S) - 0.75) <
		    1e-12);
	/* the polyps retrieved are gone from the view, no other */
	tool.polyps = 3;
	tool.polyp[0].state = ENDOSIM_POLYP_CUT;
	tool.polyp[2].state = ENDOSIM_POLYP_RETRIEVED;
	toolview_build(&tool, &sc, none, &v);
	assert_int_equal(v.gone, 1u << 2);
}

/* Guided replay's expert's tool: the published tool's fields as the
 * guide state's expert_* (toolview_expert()'s inverse). */
static void expert_of(const struct endosim_tool_state *t,
		      struct endosim_guide_state *g)
{
	memset(g, 0, sizeof(*g));
	g->phase = ENDOSIM_GUIDE_GUIDING;
	g->expert_kind = t->kind;
	g->expert_pedal = t->pedal;
	g->expert_snare_m = t->snare_m;
	g->expert_depth_m = t->depth_m;
	g->expert_opening = t->opening;
	g->expert_loop_m = t->loop_m;
	vec3_copy(g->expert_tip, t->tip);
	vec3_copy(g->expert_loop_centre, t->loop_centre);
}

/*
 * The expert's ghost: the parts of the same tool in hand, point for
 * point (with the lens too), every one in the ghost's light blue (blue
 * above red), marked a ghost; the snare's wire amber while its pedal is
 * down, the sheath still blue; nothing for none, in the channel, or not
 * finite; no blood, nothing gone; the trainee's own tool not a ghost.
 */
static void ghost(void **unused)
{
	static const double shift[3] = { 0.001, -0.002, 0.0005 };
	struct endosim_guide_state g;
	struct endosim_tool_state back;
	struct toolview mine, v;

	(void)unused;
	setup_tool(ENDOSIM_TOOL_SNARE, 0.012, 0.7);
	expert_of(&tool, &g);
	toolview_build(&tool, &sc, shift, &mine);
	toolview_build_ghost(&g, &sc, shift, &v);
	assert_false(mine.ghost);
	assert_true(v.ghost);
	assert_int_equal(v.parts, 2);
	assert_int_equal(v.parts, mine.parts);
	for (int k = 0; k < v.parts; k++) {
		const float *c = v.part[k].rgb;

		assert_int_equal(v.part[k].points, mine.part[k].points);
		for (int j = 0; j < v.part[k].points; j++) {
			for (int x = 0; x < 3; x++) {
				assert_true(v.part[k].p[j][x] ==
					    mine.part[k].p[j][x]);
			}
		}
		assert_true(c[2] > c[1] && c[1] > c[0] + 0.2f);
	}
	assert_true(v.blood == 0 && v.gone == 0);
	toolview_expert(&g, &back);
	assert_int_equal(back.kind, ENDOSIM_TOOL_SNARE);
	assert_true(back.depth_m == tool.depth_m &&
		    back.opening == tool.opening &&
		    back.loop_m == tool.loop_m);
	assert_int_equal(back.captured, -1);
	g.expert_pedal = 1;
	toolview_build_ghost(&g, &sc, none, &v);
	assert_true(v.part[1].rgb[0] > v.part[1].rgb[2]); /* the wire amber */
	assert_true(v.part[0].rgb[2] > v.part[0].rgb[0]); /* the sheath not */
	g.expert_kind = ENDOSIM_TOOL_NONE;
	toolview_build_ghost(&g, &sc, none, &v);
	assert_int_equal(v.parts, 0);
	setup_tool(ENDOSIM_TOOL_FORCEPS, -0.002, 1);
	expert_of(&tool, &g);
	toolview_build_ghost(&g, &sc, none, &v);
	assert_int_equal(v.parts, 0);
	setup_tool(ENDOSIM_TOOL_FORCEPS, 0.010, 1);
	expert_of(&tool, &g);
	toolview_build_ghost(&g, &sc, none, &v);
	assert_int_equal(v.parts, 3);
	g.expert_tip[0] = NAN;
	toolview_build_ghost(&g, &sc, none, &v);
	assert_int_equal(v.parts, 0);
}

/*
 * The polyps: one cut drawn where it lies (its published at, not moved
 * with the lens), one retrieved not at all, one in place where it
 * stands; a cut one whose place is not finite not drawn.
 */
static void lying_where_published(void **unused)
{
	const double shift[3] = { 0.001, 0.002, 0.003 };
	struct toolview v;

	(void)unused;
	setup_tool(ENDOSIM_TOOL_NONE, 0, 0);
	tool.polyps = 4;
	tool.polyp[0].state = ENDOSIM_POLYP_CUT;
	vec3_set(tool.polyp[0].at, 0.012, -0.02, 0.31);
	tool.polyp[1].state = ENDOSIM_POLYP_RETRIEVED;
	vec3_set(tool.polyp[1].at, 0.1, 0.1, 0.1);
	tool.polyp[2].state = ENDOSIM_POLYP_IN_PLACE;
	tool.polyp[3].state = ENDOSIM_POLYP_CUT;
	vec3_set(tool.polyp[3].at, NAN, 0, 0);
	toolview_build(&tool, &sc, shift, &v);
	assert_int_equal(v.lying, 1u << 0);
	assert_int_equal(v.gone, 1u << 1);
	assert_true(dist_f(v.lie[0], tool.polyp[0].at) < TOL);
	assert_int_equal(v.parts, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(sheath),
		cmocka_unit_test(snare_ring),
		cmocka_unit_test(jaws),
		cmocka_unit_test(with_the_lens),
		cmocka_unit_test(nothing),
		cmocka_unit_test(on_the_wall),
		cmocka_unit_test(ghost),
		cmocka_unit_test(lying_where_published),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
