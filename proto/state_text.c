/* state_text.c - see state_text.h. */
#include "proto/state_text.h"

static void doubles(FILE *f, const char *prefix, const char *key,
		    const double *v, int n)
{
	fprintf(f, "%s%s=", prefix, key);
	for (int i = 0; i < n; i++) {
		fprintf(f, "%s%.9g", i ? "," : "", v[i]);
	}
	fputc('\n', f);
}

static void axes(FILE *f, const char *prefix, const struct endosim_state *st)
{
	static const char *const keys[] = { "position", "velocity", "hand",
					    "command", "limited" };
	double v[ENDOSIM_AXES];

	for (int k = 0; k < 5; k++) {
		for (int a = 0; a < ENDOSIM_AXES; a++) {
			const struct endosim_axis_state *ax = &st->axis[a];
			const double all[] = { ax->position, ax->velocity,
					       ax->hand, ax->command,
					       ax->limited };

			v[a] = all[k];
		}
		doubles(f, prefix, keys[k], v, ENDOSIM_AXES);
	}
}

static void scope(FILE *f, const char *prefix,
		  const struct endosim_scope_state *sc)
{
	fprintf(f, "%sdepth_m=%.9g\n%sroll_rad=%.9g\n", prefix, sc->depth_m,
		prefix, sc->roll_rad);
	doubles(f, prefix, "bend_rad", sc->bend_rad, 2);
	fprintf(f, "%sbase_s_m=%.9g\n%stip_s_m=%.9g\n%sturning_rad=%.9g\n",
		prefix, sc->base_s_m, prefix, sc->tip_s_m, prefix,
		sc->turning_rad);
	doubles(f, prefix, "tip", sc->tip, 3);
	doubles(f, prefix, "dir", sc->dir, 3);
	doubles(f, prefix, "up", sc->up, 3);
	doubles(f, prefix, "bow_m", sc->bow_m, ENDOSIM_SPANS);
	fprintf(f, "%sspans=%u\n", prefix, sc->spans);
}

static void haptics(FILE *f, const char *prefix,
		    const struct endosim_haptics_state *h)
{
	doubles(f, prefix, "proxy", h->proxy, 3);
	doubles(f, prefix, "normal", h->normal, 3);
	doubles(f, prefix, "f_static", h->f_static, 3);
	fprintf(f, "%spenetration_m=%.9g\n%scontact=%u\n", prefix,
		h->penetration_m, prefix, h->contact);
}

/* KEY=x,y,z;x,y,z... for N points. */
static void points(FILE *f, const char *prefix, const char *key,
		   const float (*p)[3], uint32_t n)
{
	fprintf(f, "%s%s=", prefix, key);
	for (uint32_t i = 0; i < n; i++) {
		fprintf(f, "%s%.9g,%.9g,%.9g", i ? ";" : "", p[i][0], p[i][1],
			p[i][2]);
	}
	fputc('\n', f);
}

static void rod(FILE *f, const char *prefix, const struct endosim_state *st)
{
	const struct endosim_rod_state *r = &st->rod;
	uint32_t n = r->points < ENDOSIM_ROD_POINTS ? r->points :
						      ENDOSIM_ROD_POINTS;

	fprintf(f, "%smodel=%u\n%scontacts=%u\n%swall_n=%.9g\n"
		"%sfriction_n=%.9g\n%strans_rod_n=%.9g\n%stube_rod_nm=%.9g\n"
		"%sspan_nodes=%u,%u,%u,%u\n", prefix, r->model, prefix,
		r->contacts, prefix, r->wall_n, prefix, r->friction_n, prefix,
		st->haptics.trans_rod_n, prefix, st->haptics.tube_rod_nm,
		prefix, r->span_nodes[0], r->span_nodes[1], r->span_nodes[2],
		r->span_nodes[3]);
	points(f, prefix, "rod_point", r->point, n);
	fprintf(f, "%srod_roll=", prefix);
	for (uint32_t i = 0; i < n; i++) {
		fprintf(f, "%s%.9g", i ? "," : "", r->roll[i]);
	}
	fputc('\n', f);
	points(f, prefix, "rod_node", r->node,
	       r->nodes < ENDOSIM_COLON_NODES ? r->nodes : ENDOSIM_COLON_NODES);
}

/* The tool in the working channel, when one is in hand. */
static void tool(FILE *f, const char *prefix,
		 const struct endosim_tool_state *t)
{
	if (t->kind == ENDOSIM_TOOL_NONE) {
		return;
	}
	fprintf(f, "%stool_kind=%u\n%stool_depth_m=%.9g\n%stool_opening=%.9g\n"
		"%stool_pedal=%u\n%stool_loop_m=%.9g\n", prefix, t->kind,
		prefix, t->depth_m, prefix, t->opening, prefix, t->pedal,
		prefix, t->loop_m);
	doubles(f, prefix, "tool_tip", t->tip, 3);
	doubles(f, prefix, "tool_loop_centre", t->loop_centre, 3);
}

/* Guided replay's expert's tool, while it shows one (guide.h). */
static void expert(FILE *f, const char *prefix,
		   const struct endosim_guide_state *g)
{
	if (g->expert_kind == ENDOSIM_TOOL_NONE) {
		return;
	}
	fprintf(f, "%sexpert_kind=%u\n%sexpert_depth_m=%.9g\n"
		"%sexpert_opening=%.9g\n%sexpert_pedal=%u\n"
		"%sexpert_loop_m=%.9g\n", prefix, g->expert_kind, prefix,
		g->expert_depth_m, prefix, g->expert_opening, prefix,
		g->expert_pedal, prefix, g->expert_loop_m);
	doubles(f, prefix, "expert_tip", g->expert_tip, 3);
}

/* What the tools left in the colon, whatever is in hand. */
static void left(FILE *f, const char *prefix,
		 const struct endosim_tool_state *t)
{
	const char *sep = "";

	if (t->bleeding > 0) {
		fprintf(f, "%stool_bleeding=%u\n", prefix, t->bleeding);
		doubles(f, prefix, "tool_bleed_at", t->bleed_at, 3);
	}
	if (t->clips > 0) {
		fprintf(f, "%stool_clips=%u\n", prefix, t->clips);
		doubles(f, prefix, "tool_clip_at", t->clip_at, 3);
	}
	for (uint32_t i = 0; i < t->polyps && i < ENDOSIM_POLYPS; i++) {
		const double *x = t->polyp[i].at;

		if (t->polyp[i].state != ENDOSIM_POLYP_CUT) {
			continue;
		}
		if (!*sep) {
			fprintf(f, "%stool_lying=", prefix);
		}
		fprintf(f, "%s%u:%.9g,%.9g,%.9g", sep, i, x[0], x[1], x[2]);
		sep = ";";
	}
	if (*sep) {
		fputc('\n', f);
	}
}

void state_text_print(FILE *f, const char *prefix,
		      const struct endosim_state *st)
{
	fprintf(f, "%scycle=%llu\n%sstamp_ns=%llu\n%sstate=%u\n"
		"%sfault_bits=%u\n%sscenario_time_s=%.9g\n", prefix,
		(unsigned long long)st->cycle, prefix,
		(unsigned long long)st->stamp_ns, prefix, st->state, prefix,
		st->fault_bits, prefix, st->scenario_time_s);
	axes(f, prefix, st);
	fprintf(f, "%sramp=%.9g\n", prefix, st->safety.ramp);
	scope(f, prefix, &st->scope);
	haptics(f, prefix, &st->haptics);
	rod(f, prefix, st);
	tool(f, prefix, &st->tool);
	left(f, prefix, &st->tool);
	expert(f, prefix, &st->guide);
	points(f, prefix, "tube", st->scope.tube, ENDOSIM_TUBE_POINTS);
}
