/* hud.c - see hud.h. */
#include "viewer/hud.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/anatomy.h"
#include "proto/names.h"
#include "viewer/burstmark.h"
#include "viewer/painview.h"
#include "viewer/patientview.h"
#include "viewer/toolview.h"

#define CHART_SAMPLES 512
#define CHART_DRAWN 240 /* samples across the chart */
#define PANEL_MIN_PX 220
#define PANEL_SHARE 0.30
#define MARGIN_PX 12
#define INSET_SHARE 0.45 /* of the height, the overview's inset at most */

const char *const hud_keys[] = {
	"Up/W  Down/S\tinsert, withdraw (Shift: faster)",
	"Left/A  Right/D\ttwist the tube",
	"I  K\ttip up, down (up/down wheel)",
	"J  L\ttip left, right (left/right wheel)",
	"mouse\tdrag the image to steer, right-drag",
	"\tto twist, scroll to insert",
	"gamepad\tleft stick insert, twist;",
	"\tright stick steer",
	"Z\thands off: the hand lets go of all",
	"E  X\tenable, disable the motors",
	"Space  R\temergency stop, reset",
	"1  2  3\tvalves, held: air, water, suction",
	"T  N\tturn the patient; the hand on the",
	"\tnext site, then off",
	"G  F  B\tguided: take over, follow again,",
	"\tback to the path",
	"V  O\tview, overview's orbit back",
	"M\tthe unseen-mucosa map (recording)",
	"U\tthe patient's voice off, on",
	"P\tsave a picture (PNG, here)",
	"C\tlog out: another trainee logs in",
	"H  Q\tthis help, quit",
	NULL,
};

const char *const hud_replay_keys[] = {
	"Space\tpause, play",
	"+  -  ]  [\tfaster, slower (x0.25 to x8)",
	"Left  Right\tseek 5 s back, on (Shift: 30 s)",
	"Home  End\tthe start, the end",
	"mouse\tclick the timeline to seek;",
	"\tdrag the overview to turn it",
	"V  O\tview, overview's orbit back",
	"U\tthe patient's voice off, on",
	"P\tsave a picture (PNG, here)",
	"H  Q\tthis help, quit",
	NULL,
};

static const float white[4] = { 0.90f, 0.92f, 0.95f, 1 };
static const float dim[4] = { 0.55f, 0.58f, 0.66f, 1 };
static const float green[4] = { 0.30f, 0.90f, 0.42f, 1 };
static const float amber[4] = { 1.00f, 0.70f, 0.15f, 1 };
static const float red[4] = { 1.00f, 0.27f, 0.22f, 1 };
static const float ghost[4] = { 0.35f, 0.70f, 1.00f, 1 }; /* the expert's */
static const float track[4] = { 1, 1, 1, 0.09f };
static const float shade[4] = { 0, 0, 0, 0.72f };
static const float black[4] = { 0, 0, 0, 1 };
static const float perforated_rgb[4] = { 0.85f, 0.07f, 0.07f, 1 };
static const float axis_rgb[ENDOSIM_AXES][4] = {
	{ 0.35f, 0.75f, 1.00f, 1 }, { 0.85f, 0.55f, 1.00f, 1 },
	{ 1.00f, 0.80f, 0.30f, 1 }, { 0.40f, 1.00f, 0.70f, 1 },
};
/* bar and chart scale per axis: N, N m */
static const double axis_scale[ENDOSIM_AXES] = { 40, 1.0, 0.15, 0.15 };
static const char *const axis_label[ENDOSIM_AXES] = {
	"insertion", "roll", "wheel U/D", "wheel L/R",
};

struct sample {
	double t_s;
	float force[ENDOSIM_AXES]; /* limited, as share of axis_scale */
};

struct hud {
	struct sample chart[CHART_SAMPLES];
	unsigned int next, count;
	char said[HUD_LINES][HUD_LINE]; /* the last panel's lines */
	int lines;
	int hidden;   /* the last panel's lines that found no room */
	float end_px; /* where its text ended, from the framebuffer's top */
};

/* Where the next line goes. */
struct pen {
	struct draw2d *d;
	struct hud *h;    /* keeps what it says */
	float x, y, w;    /* left, top of the next line, width */
	float small, large;
	float limit;      /* the lines end here: room for the note below */
	int hidden;       /* lines not drawn for want of room */
};

void hud_font_px(int h, float *small_px, float *large_px)
{
	*small_px = fmaxf(10, (float)h / 46);
	*large_px = fmaxf(14, (float)h / 26);
}

/* Under the panel's first lines: name, state, and a replay's two. */
static void timeline_rect(struct hud_layout *out, int h)
{
	float small, large, top;
	struct endo_rect p = out->panel;

	hud_font_px(h, &small, &large);
	top = MARGIN_PX + 1.35f * (3 * small + large) + small * 0.3f;
	out->timeline = (struct endo_rect){
		p.x + MARGIN_PX, p.y + p.h - (int)(top + small),
		p.w - 2 * MARGIN_PX, (int)small,
	};
}

void hud_layout(enum hud_view view, int w, int h, struct hud_layout *out)
{
	int panel = (int)fmax(PANEL_MIN_PX, PANEL_SHARE * w);
	int side = w - panel < h ? w - panel : h;
	int inset;

	side = side > 0 ? side : 0;
	panel = w - side;
	memset(out, 0, sizeof(*out));
	out->panel = (struct endo_rect){ 0, 0, panel, h };
	if (view == HUD_VIEW_OVERVIEW) {
		out->overview = (struct endo_rect){ panel, 0, side, h };
		timeline_rect(out, h);
		return;
	}
	out->endo = (struct endo_rect){ panel, (h - side) / 2, side, side };
	if (view == HUD_VIEW_BOTH) {
		inset = (int)fmin(panel, INSET_SHARE * h);
		out->overview = (struct endo_rect){ 0, 0, panel, inset };
		out->panel.y = inset;
		out->panel.h = h - inset;
	}
	timeline_rect(out, h);
}

struct hud *hud_create(void)
{
	return calloc(1, sizeof(struct hud));
}

void hud_destroy(struct hud *h)
{
	free(h);
}

void hud_chart_clear(struct hud *h)
{
	h->next = h->count = 0;
}

void hud_record(struct hud *h, const struct endosim_state *st, double t_s)
{
	const struct sample *last = &h->chart[(h->next + CHART_SAMPLES - 1) %
					      CHART_SAMPLES];
	struct sample *s = &h->chart[h->next];

	if (h->count && t_s - last->t_s < HUD_CHART_S / CHART_DRAWN) {
		return; /* a point every few pixels is enough */
	}
	s->t_s = t_s;
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		s->force[a] = (float)(st->axis[a].limited / axis_scale[a]);
	}
	h->next = (h->next + 1) % CHART_SAMPLES;
	h->count += h->count < CHART_SAMPLES;
}

/*
 * Whether what comes next, H px high, has room above the footer (and
 * the note that says what had none). Once something has not, nothing
 * after it has: the panel keeps its order, the least needed last.
 */
static bool room(struct pen *p, float h)
{
	if (p->hidden || p->y + h > p->limit) {
		p->hidden++;
		return false;
	}
	return true;
}

/* TEXT on the next line, cut short where the panel ends, wherever the
 * line falls. */
static void put(struct pen *p, enum font_size size, const float rgb[4],
		const char *text)
{
	float px = size == FONT_LARGE ? p->large : p->small;
	char cut[256];
	size_t n = (size_t)snprintf(cut, sizeof(cut), "%s", text);

	while (n > 1 && draw2d_text_width(p->d, size, cut) > p->w) {
		cut[--n] = '\0';
	}
	draw2d_text(p->d, size, p->x, p->y + px, rgb, cut);
	if (p->h->lines < HUD_LINES) {
		snprintf(p->h->said[p->h->lines++], HUD_LINE, "%s", cut);
	}
	p->y += px * 1.35f;
}

/* TEXT on the next line where there is room. */
static void line(struct pen *p, enum font_size size, const float rgb[4],
		 const char *text)
{
	if (room(p, (size == FONT_LARGE ? p->large : p->small) * 1.35f)) {
		put(p, size, rgb, text);
	}
}

static void gap(struct pen *p)
{
	p->y += p->small * 0.6f;
}

/* The rod model rendered ST (NULL: no state). */
static bool rod(const struct endosim_state *st)
{
	return st && st->rod.model == ENDOSIM_MODEL_ROD;
}

/* "FAULT: stale-feedback (wheel_ud)" and the like. */
static void state_words(const struct endosim_state *st, char *buf,
			size_t size, const float **rgb)
{
	char faults[96];

	switch (st->state) {
	case ENDOSIM_STATE_ENABLED:
		snprintf(buf, size, "ENABLED");
		*rgb = green;
		return;
	case ENDOSIM_STATE_FAULT:
		names_faults(st->fault_first ? st->fault_first : st->fault_bits,
			     faults, sizeof(faults));
		snprintf(buf, size, "FAULT: %s%s%s%s", faults,
			 st->fault_axis >= 0 ? " (" : "",
			 st->fault_axis >= 0 ? names_axis(st->fault_axis) : "",
			 st->fault_axis >= 0 ? ")" : "");
		*rgb = red;
		return;
	case ENDOSIM_STATE_ESTOP:
		snprintf(buf, size, "EMERGENCY STOP");
		*rgb = red;
		return;
	default:
		snprintf(buf, size, "%s", names_state(st->state));
		*rgb = dim;
	}
}

static const char *state_hint(const struct endosim_state *st)
{
	switch (st->state) {
	case ENDOSIM_STATE_IDLE:
		return "motors off (E: enable)";
	case ENDOSIM_STATE_ENABLED:
		return "forces on (X: off, Space: stop)";
	default:
		return "torque off (R: reset once clear)";
	}
}

static void draw_state(struct pen *p, const struct hud_info *in)
{
	const float *rgb = dim;
	char text[160];

	snprintf(text, sizeof(text), "endosim  %s%s", in->m ? in->m->name : "",
		 rod(in->st) ? "  rod model" : "");
	line(p, FONT_SMALL, dim, text);
	if (in->trainee && *in->trainee) {
		snprintf(text, sizeof(text), "trainee %s  (C: log out)",
			 in->trainee);
		line(p, FONT_SMALL, green, text);
	}
	if (!in->st || in->link == LINK_NO_DAEMON) {
		line(p, FONT_LARGE, red, "NO DAEMON");
		line(p, FONT_SMALL, dim, in->link_problem);
		return;
	}
	state_words(in->st, text, sizeof(text), &rgb);
	line(p, FONT_LARGE, in->link == LINK_STALE ? amber : rgb, text);
	if (!in->replay) {
		line(p, FONT_SMALL, dim, state_hint(in->st));
	}
}

/*
 * Guided replay, while it runs or the trainee has taken over: GUIDED (the
 * session, the playhead, the speed) and the tracking error, or TAKEN OVER
 * with the keys that give it back.
 */
static void draw_guide(struct pen *p, const struct endosim_guide_state *g)
{
	static const char *const title[] = {
		[ENDOSIM_GUIDE_MOVING] = "GUIDED: TO THE PATH",
		[ENDOSIM_GUIDE_GUIDING] = "GUIDED",
		[ENDOSIM_GUIDE_HOLDING] = "GUIDED: HELD ON THE PATH",
		[ENDOSIM_GUIDE_FADING] = "TAKING OVER",
		[ENDOSIM_GUIDE_FREE] = "TAKEN OVER",
	};
	bool free = g->phase == ENDOSIM_GUIDE_FREE ||
		    g->phase == ENDOSIM_GUIDE_FADING;
	char text[160];

	if (g->phase == ENDOSIM_GUIDE_OFF ||
	    g->phase >= sizeof(title) / sizeof(title[0])) {
		return;
	}
	gap(p);
	line(p, FONT_LARGE, free ? amber : green, title[g->phase]);
	if (g->length_s > 0) {
		snprintf(text, sizeof(text), "session %llu  %.1f / %.1f s  "
			 "x%.2f", (unsigned long long)g->source_id, g->time_s,
			 g->length_s, g->speed);
	} else { /* a replay: the record keeps the playhead only */
		snprintf(text, sizeof(text), "%.1f s into the expert's",
			 g->time_s);
	}
	line(p, FONT_SMALL, white, text);
	if (free) {
		line(p, FONT_SMALL, dim, "F: follow again, B: back to the path");
		return;
	}
	snprintf(text, sizeof(text), "off the path: ins %+.1f mm, roll %+.1f "
		 "deg (G: take over)", -g->error[0] * 1e3,
		 -g->error[1] * 180 / M_PI);
	line(p, FONT_SMALL, dim, text);
}

/* REPLAY, who and what; the clock; the timeline at LAY's. */
static void draw_replay(struct pen *p, const struct hud_replay *r,
			const struct hud_layout *lay, int fb_h)
{
	struct endo_rect tl = lay->timeline;
	float top = (float)(fb_h - tl.y - tl.h);
	float at = r->duration_s > 0 ? (float)(r->t_s / r->duration_s) : 0;
	char text[192];

	snprintf(text, sizeof(text), "REPLAY  %s%s%s", r->trainee,
		 *r->trainee ? ", " : "", r->case_name);
	line(p, FONT_SMALL, amber, text);
	snprintf(text, sizeof(text), "%.1f / %.1f s   x%g%s", r->t_s,
		 r->duration_s, r->speed, r->paused ? "   PAUSED" : "");
	line(p, FONT_SMALL, r->paused ? amber : white, text);
	draw2d_rect(p->d, (float)tl.x, top, (float)tl.w, (float)tl.h, track);
	draw2d_rect(p->d, (float)tl.x, top + tl.h * 0.25f, at * tl.w,
		    tl.h * 0.5f, axis_rgb[0]);
	for (double s = 10; s < r->duration_s; s += 10) {
		draw2d_rect(p->d, tl.x + (float)(s / r->duration_s) * tl.w,
			    top + tl.h * 0.7f, 1, tl.h * 0.3f, dim);
	}
	draw2d_rect(p->d, tl.x + at * tl.w - 1.5f, top - 2, 3,
		    (float)tl.h + 4, white);
	p->y = fmaxf(p->y, top + (float)tl.h) + p->small * 0.3f;
}

/* NAME ("left-lateral", "splenic_flexure") in words: "left lateral". */
static void spaced(const char *name, char *buf, size_t size)
{
	size_t n = (size_t)snprintf(buf, size, "%s", name);

	for (size_t k = 0; k < n && k < size; k++) {
		buf[k] = buf[k] == '-' || buf[k] == '_' ? ' ' : buf[k];
	}
}

/* Region RG's name in words ("splenic flexure"). */
static void region_name(const struct model_region *rg, char *buf, size_t size)
{
	spaced(rg->name, buf, size);
}

static void draw_where(struct pen *p, const struct hud_info *in)
{
	const struct endosim_scope_state *sc = &in->st->scope;
	char where[MODEL_NAME], text[160];

	snprintf(text, sizeof(text), "insertion %.1f cm", sc->depth_m * 100);
	line(p, FONT_LARGE, white, text);
	if (!in->m) {
		line(p, FONT_SMALL, dim, in->loading ? "loading the colon..." :
						       "no colon yet");
		return;
	}
	region_name(model_region_at(in->m, sc->tip_s_m), where, sizeof(where));
	snprintf(text, sizeof(text), "tip: %s, %.1f cm in", where,
		 sc->tip_s_m * 100);
	line(p, FONT_SMALL, white, text);
	snprintf(text, sizeof(text), "roll %+.0f, tip %+.0f up %+.0f right, "
		 "turns %.0f deg", sc->roll_rad * 180 / M_PI,
		 sc->bend_rad[0] * 180 / M_PI, sc->bend_rad[1] * 180 / M_PI,
		 sc->turning_rad * 180 / M_PI);
	line(p, FONT_SMALL, dim, text);
}

/* Tool T in words after LEAD ("tool", "expert"): which, how far out, the
 * handle, the snare's loop, a polyp held, the pedal. */
static void tool_words(const char *lead, const struct endosim_tool_state *t,
		       char *text, size_t size)
{
	int n = snprintf(text, size, "%s: %s", lead, names_tool(t->kind));

	if (t->kind == ENDOSIM_TOOL_SNARE) {
		n += snprintf(text + n, size - (size_t)n, " %.0f mm",
			      t->snare_m * 1000);
	}
	n += snprintf(text + n, size - (size_t)n,
		      t->depth_m > 0 ? ", %.0f mm out" : ", in the channel",
		      t->depth_m * 1000);
	n += snprintf(text + n, size - (size_t)n, ", handle %.0f %%",
		      t->opening * 100);
	if (t->kind == ENDOSIM_TOOL_SNARE && t->loop_m > 0) {
		n += snprintf(text + n, size - (size_t)n, ", loop %.0f mm",
			      t->loop_m * 1000);
	}
	if (t->captured >= 0) {
		n += snprintf(text + n, size - (size_t)n, ", holding polyp %d",
			      t->captured + 1);
	}
	if (t->pedal) {
		snprintf(text + n, size - (size_t)n, ", pedal down");
	}
}

/* The tool in the channel, as published (amber while the pedal is
 * down); guided replay's expert's under it, in its ghost's light blue
 * (toolview.h), amber likewise. */
static void draw_tool(struct pen *p, const struct endosim_state *st)
{
	char text[256]; /* the longest is under 130 */
	struct endosim_tool_state expert;

	if (st->tool.kind != ENDOSIM_TOOL_NONE &&
	    st->tool.kind < ENDOSIM_TOOLS) {
		tool_words("tool", &st->tool, text, sizeof(text));
		line(p, FONT_SMALL, st->tool.pedal ? amber : dim, text);
	}
	toolview_expert(&st->guide, &expert);
	if (expert.kind != ENDOSIM_TOOL_NONE && expert.kind < ENDOSIM_TOOLS) {
		tool_words("expert", &expert, text, sizeof(text));
		line(p, FONT_SMALL, expert.pedal ? amber : ghost, text);
	}
}

/* While a point bleeds (the tools' doing: tool.h), in red: how many, the
 * flow, the blood shed. */
static void draw_bleeding(struct pen *p, const struct endosim_tool_state *t)
{
	char text[128];

	if (t->bleeding == 0) {
		return;
	}
	snprintf(text, sizeof(text), "bleeding: %u point%s, %.1f mL/min, "
		 "%.1f mL shed", t->bleeding, t->bleeding == 1 ? "" : "s",
		 t->bleed_m3_s * ENDOSIM_ML_PER_MIN_PER_M3_S,
		 t->blood_m3 * ENDOSIM_ML_PER_M3);
	line(p, FONT_SMALL, red, text);
}

/* The largest bow of a mobile segment, and its span (-1: none). */
static double worst_loop(const struct endosim_scope_state *sc, int *span)
{
	double worst = 0;

	*span = -1;
	for (uint32_t k = 0; k < sc->spans && k < ENDOSIM_SPANS; k++) {
		if (fabs(sc->bow_m[k]) > worst) {
			worst = fabs(sc->bow_m[k]);
			*span = (int)k;
		}
	}
	return worst;
}

/* The warning of the largest bow, if it is a loop. */
static void draw_loop(struct pen *p, const struct hud_info *in, double t_s)
{
	int span;
	double worst = worst_loop(&in->st->scope, &span);
	char text[160];

	if (worst <= in->loop_threshold_m || !in->m) {
		return;
	}
	for (int i = 0; i < in->m->regions; i++) {
		if (in->m->region[i].span == span) {
			snprintf(text, sizeof(text),
				 "LOOP: the %s %s %.1f cm",
				 in->m->region[i].name,
				 rod(in->st) ? "moved" : "bows", worst * 100);
			line(p, FONT_LARGE, fmod(t_s, 1.0) < 0.6 ? amber : red,
			     text);
		}
	}
}

/* The rod model: how far each mobile segment has moved (its loop); in a
 * compact panel only while there is no loop, whose warning says it. */
static void draw_moved(struct pen *p, const struct hud_info *in)
{
	const struct endosim_scope_state *sc = &in->st->scope;
	char text[160] = "loop:", name[MODEL_NAME];
	const char *sep = "";
	size_t n = strlen(text);
	int span;

	if (in->compact && worst_loop(sc, &span) > in->loop_threshold_m) {
		return;
	}
	for (int i = 0; in->m && i < in->m->regions && n < sizeof(text);
	     i++) {
		const struct model_region *rg = &in->m->region[i];

		if (rg->span < 0 || rg->span >= (int)sc->spans ||
		    rg->span >= ENDOSIM_SPANS) {
			continue;
		}
		region_name(rg, name, sizeof(name));
		n += (size_t)snprintf(text + n, sizeof(text) - n,
				      "%s %s %.1f cm", sep, name,
				      fabs(sc->bow_m[rg->span]) * 100);
		sep = ",";
	}
	line(p, FONT_SMALL, dim, text);
}

/* The position, and the turn in progress, into TEXT; its colour. */
static const float *position_words(const struct endosim_patient_state *pt,
				   char *text, size_t size)
{
	char name[32];

	spaced(names_position(pt->position), name, sizeof(name));
	if (pt->turning) {
		snprintf(text, size, "turning to %s, %.0f %%", name,
			 fmin(1, fmax(0, pt->turn)) * 100);
	} else {
		snprintf(text, size, "patient %s", name);
	}
	return pt->turning ? amber : white;
}

/* The gas, its relief and where the first wall would burst, into TEXT;
 * its colour. */
static const float *gas_words(const struct hud_info *in, double burst,
			      char *text, size_t size)
{
	const struct endosim_patient_state *pt = &in->st->patient;
	double mmhg = pt->pressure_pa / BURSTMARK_PA_PER_MMHG;
	int n;

	n = snprintf(text, size, "gas %.1f mmHg, %.2f L", mmhg,
		     pt->gas_m3 * 1e3);
	if (in->relief_pa > 0 && n > 0 && (size_t)n < size) {
		n += snprintf(text + n, size - (size_t)n, ", relief %.0f",
			      in->relief_pa / BURSTMARK_PA_PER_MMHG);
	}
	if (!isnan(burst) && n > 0 && (size_t)n < size) {
		snprintf(text + n, size - (size_t)n, ", bursts ~%.0f",
			 burst / BURSTMARK_PA_PER_MMHG);
	}
	return mmhg > PATIENTVIEW_HIGH_MMHG ? amber : white;
}

/* The position and the gas: a line each, or in a compact panel one
 * where it fits the panel's width (amber when either is). */
static void draw_position_gas(struct pen *p, const struct hud_info *in,
			      double burst)
{
	char where[96], gas[160], both[260];
	const float *where_rgb = position_words(&in->st->patient, where,
						sizeof(where));
	const float *gas_rgb = gas_words(in, burst, gas, sizeof(gas));

	snprintf(both, sizeof(both), "%s; %s", where, gas);
	if (in->compact &&
	    draw2d_text_width(p->d, FONT_SMALL, both) <= p->w) {
		line(p, FONT_SMALL, where_rgb == amber ? amber : gas_rgb,
		     both);
		return;
	}
	line(p, FONT_SMALL, where_rgb, where);
	line(p, FONT_SMALL, gas_rgb, gas);
}

/* The assistant's hand and the handle's valves. */
static void draw_hand_valves(struct pen *p, const struct hud_info *in)
{
	const struct endosim_patient_state *pt = &in->st->patient;
	const char *site = in->m && pt->hand_site >= 0 &&
			   pt->hand_site < in->m->sites ?
			   in->m->site[pt->hand_site].name : "?";
	char text[160];

	if (pt->hand_site >= 0) {
		snprintf(text, sizeof(text), "hand on %s, %.0f N; valves %s",
			 site, pt->hand_n, names_valves(pt->valves));
	} else {
		snprintf(text, sizeof(text), "hand off; valves %s",
			 names_valves(pt->valves));
	}
	line(p, FONT_SMALL, pt->hand_site >= 0 || pt->valves ? white : dim,
	     text);
}

/* What covers the lens, when anything does. */
static void draw_lens(struct pen *p, const struct endosim_patient_state *pt)
{
	char text[128];

	if (!(pt->lens_smear > 0.01 || pt->lens_murk > 0.01 ||
	      pt->lens_redout > 0.01)) {
		return;
	}
	snprintf(text, sizeof(text), "lens: smear %.0f %%, murk %.0f %%, "
		 "red-out %.0f %%", pt->lens_smear * 100, pt->lens_murk * 100,
		 pt->lens_redout * 100);
	line(p, FONT_SMALL, amber, text);
}

/* Segment I in words: the colon's region, else the anatomy's name. */
static void segment_name(const struct model *m, int i, char *buf,
			 size_t size)
{
	if (m && i < m->regions) {
		region_name(&m->region[i], buf, size);
	} else {
		spaced(anatomy_segment_name(i), buf, size);
	}
}

/* The segment perforated (the gas's burst first, else the tip's tear)
 * in words into BUF and what did it into HOW; false: none. */
static bool perforation(const struct hud_info *in, char *buf, size_t size,
			const char **how)
{
	const struct endosim_patient_state *pt = &in->st->patient;
	int i = pt->burst_segment >= 0 ? pt->burst_segment : pt->torn_segment;

	if (!pt->enabled || i < 0) {
		return false;
	}
	segment_name(in->m, i, buf, size);
	*how = pt->burst_segment >= 0 ? "the gas's pressure burst the wall" :
					"the tip tore the wall";
	return true;
}

/* A torn wall, in red. */
static void draw_burst(struct pen *p, const struct hud_info *in)
{
	char name[MODEL_NAME], text[96];
	const char *how;

	if (!perforation(in, name, sizeof(name), &how)) {
		return;
	}
	snprintf(text, sizeof(text), "PERFORATED: %s", name);
	line(p, FONT_LARGE, red, text);
}

/* The level's words: "pain 6.3 grimace: looping, sigmoid". */
static void draw_pain_words(struct pen *p,
			    const struct endosim_patient_state *pt,
			    const struct model *m)
{
	char place[MODEL_NAME] = "", text[160];

	if (pt->pain_place >= 0) {
		segment_name(m, pt->pain_place, place, sizeof(place));
	}
	snprintf(text, sizeof(text), "pain %.1f %s%s%s%s%s", pt->pain,
		 painview_mood_name(painview_mood(pt->pain)),
		 pt->pain_cause ? ": " : "",
		 pt->pain_cause ? names_pain_cause(pt->pain_cause) : "",
		 pt->pain_cause && *place ? ", " : "",
		 pt->pain_cause ? place : "");
	line(p, FONT_SMALL, painview_rgb(pt->pain), text);
}

/* The vital signs: heart rate, oxygen saturation, sedation; amber or
 * red past the simple alarms' limits (a bedside monitor's defaults). */
static void draw_vitals(struct pen *p, const struct endosim_patient_state *pt)
{
	const float *rgb = white;
	char text[128];

	if (pt->heart_rate_bpm > 120 || pt->spo2 < 0.90) {
		rgb = red;
	} else if (pt->heart_rate_bpm > 100 || pt->spo2 < 0.94) {
		rgb = amber;
	}
	snprintf(text, sizeof(text), "HR %.0f/min  SpO2 %.0f %%  %s sedation",
		 pt->heart_rate_bpm, pt->spo2 * 100,
		 names_sedation(pt->sedation));
	line(p, FONT_SMALL, rgb, text);
}

/*
 * The patient panel: the figure, the gauge and the face side by side, the
 * pain's bar under them, then the lines: the level's words, the vital
 * signs, the position, the gas, the hand and the valves, the lens; in a
 * compact panel the lines alone, the position and the gas on one.
 */
static void draw_patient(struct pen *p, const struct hud_info *in)
{
	const struct endosim_patient_state *pt = &in->st->patient;
	double burst = burstmark_pa(pt, in->strength_n_per_m);
	float size = p->small * 6.5f, x = p->x, top;

	if (!pt->enabled) {
		return;
	}
	draw_burst(p, in);
	if (!in->compact && room(p, size + p->small * 1.4f)) {
		top = p->y;
		patientview_figure(p->d, x + size / 2, top + size / 2, size,
				   pt, in->m);
		patientview_gauge(p->d, x + size * 1.6f, top + size * 0.48f,
				  size * 0.42f, pt->pressure_pa, in->relief_pa,
				  burst);
		painview_face(p->d, x + size * 2.7f, top + size * 0.46f,
			      size * 0.4f, pt->pain);
		p->y = top + size + p->small * 0.2f;
		painview_bar(p->d, x, p->y, p->w, p->small * 0.7f, pt->pain);
		p->y += p->small * 1.2f;
	}
	draw_pain_words(p, pt, in->m);
	draw_vitals(p, pt);
	draw_position_gas(p, in, burst);
	draw_hand_valves(p, in);
	draw_lens(p, pt);
}

/* V, shown with DIGITS decimals: no "-0.0" for a hair below zero. */
static double tidy(double v, int digits)
{
	return fabs(v) < 0.5 * pow(10, -digits) ? 0 : v;
}

static float bar_x(float x0, float w, double v)
{
	return x0 + w / 2 + (float)(fmax(-1, fmin(1, v)) * w / 2);
}

/* A column of bars: from X, W px wide, its labels' and values' room. */
struct bar_column {
	float x, w, label_w, value_w;
};

/* One axis in column C on the pen's line: label, a bar of what the
 * drive gets (the force model's ask as a line, the hand's push as a
 * tick), the value. */
static void draw_bar(struct pen *p, const struct endosim_axis_state *ax,
		     int a, struct bar_column c)
{
	float x0 = c.x + c.label_w, w = c.w - c.label_w - c.value_w;
	float h = p->small * 0.8f, y = p->y + p->small * 0.25f;
	float v = bar_x(x0, w, ax->limited / axis_scale[a]);
	float asked = bar_x(x0, w, ax->command / axis_scale[a]);
	float hand = bar_x(x0, w, ax->hand / axis_scale[a]);
	float mid = x0 + w / 2;

	draw2d_text(p->d, FONT_SMALL, c.x, p->y + p->small, dim,
		    axis_label[a]);
	draw2d_rect(p->d, x0, y, w, h, track);
	draw2d_rect(p->d, fminf(mid, v), y, fabsf(v - mid), h, axis_rgb[a]);
	draw2d_rect(p->d, asked - 1, y - 2, 2, h + 4, white);
	draw2d_rect(p->d, hand - 1, y + h, 3, 4, amber);
	draw2d_printf(p->d, FONT_SMALL, x0 + w + 8, p->y + p->small, white,
		      a == ENDOSIM_AXIS_INSERTION ? "%+.1f N" : "%+.3f N m",
		      tidy(ax->limited, a == ENDOSIM_AXIS_INSERTION ? 1 : 3));
}

/* The axes' bars, a row each; in a compact panel wide enough for bars
 * of BAR_MIN_SMALLS, two to a row. */
#define BAR_MIN_SMALLS 4.0f
static void draw_bars(struct pen *p, const struct hud_info *in)
{
	struct bar_column c = {
		.x = p->x,
		.label_w = draw2d_text_width(p->d, FONT_SMALL, "wheel U/D  "),
		.value_w = draw2d_text_width(p->d, FONT_SMALL, " +0.000 N m"),
	};
	float gutter = p->small * 1.5f;
	int per_row;

	c.w = (p->w - gutter) / 2;
	per_row = in->compact &&
		  c.w - c.label_w - c.value_w >= BAR_MIN_SMALLS * p->small
		  ? 2 : 1;
	if (per_row == 1) {
		c.w = p->w;
	}
	for (int a = 0; a < ENDOSIM_AXES; a += per_row) {
		if (!room(p, p->small * 1.5f)) {
			continue;
		}
		for (int k = 0; k < per_row && a + k < ENDOSIM_AXES; k++) {
			c.x = p->x + (float)k * (c.w + gutter);
			draw_bar(p, &in->st->axis[a + k], a + k, c);
		}
		p->y += p->small * 1.5f;
	}
}

/* The rod model's tube: its pull at the carriage, the wall along it. */
static void draw_tube(struct pen *p, const struct endosim_state *st)
{
	const struct endosim_rod_state *r = &st->rod;
	char text[192];

	snprintf(text, sizeof(text), "tube at the carriage: %+.1f N, "
		 "%+.3f N m", st->haptics.trans_rod_n, st->haptics.tube_rod_nm);
	line(p, FONT_SMALL, dim, text);
	snprintf(text, sizeof(text), "tube on the wall: %u contact%s, %.1f N, "
		 "friction %.1f N", r->contacts, r->contacts == 1 ? "" : "s",
		 r->wall_n, r->friction_n);
	line(p, FONT_SMALL, r->contacts ? white : dim, text);
}

static void draw_parts(struct pen *p, const struct endosim_state *st)
{
	const struct endosim_haptics_state *h = &st->haptics;
	char text[192];

	if (rod(st)) {
		draw_tube(p, st);
	} else {
		snprintf(text, sizeof(text), "push: contact %+.1f, friction "
			 "%+.1f, loop %+.1f N", h->trans_contact_n,
			 h->trans_friction_n, h->trans_loop_n);
		line(p, FONT_SMALL, dim, text);
	}
	for (int k = 0; k < 2; k++) {
		snprintf(text, sizeof(text), "%s: contact %+.3f, wire %+.3f, "
			 "spring %+.3f N m",
			 axis_label[ENDOSIM_AXIS_WHEEL_UD + k],
			 h->wheel_contact_nm[k], h->wheel_tension_nm[k],
			 h->wheel_elastic_nm[k]);
		line(p, FONT_SMALL, dim, text);
	}
	snprintf(text, sizeof(text), "%s: %s, %.1f mm in, %u constraint%s",
		 rod(st) ? "tip on the wall" : "wall",
		 h->contact ? "touching" : "clear", h->penetration_m * 1000,
		 h->constraints, h->constraints == 1 ? "" : "s");
	line(p, FONT_SMALL, h->contact ? amber : dim, text);
}

static void draw_chart(struct pen *p, const struct hud *h, double t_s)
{
	float ch = p->small * 5, x0 = p->x, w = p->w;
	float mid = p->y + ch / 2;

	if (!room(p, ch + p->small * 0.5f)) {
		return;
	}
	draw2d_rect(p->d, x0, p->y, w, ch, track);
	draw2d_rect(p->d, x0, mid, w, 1, track);
	for (unsigned int k = 1; k < h->count; k++) {
		const struct sample *a = &h->chart[(h->next + CHART_SAMPLES -
						    k) % CHART_SAMPLES];
		const struct sample *b = &h->chart[(h->next + CHART_SAMPLES -
						    k - 1) % CHART_SAMPLES];
		float xa = x0 + w - (float)((t_s - a->t_s) / HUD_CHART_S) * w;
		float xb = x0 + w - (float)((t_s - b->t_s) / HUD_CHART_S) * w;

		if (xb < x0) {
			break;
		}
		for (int ax = 0; ax < ENDOSIM_AXES; ax++) {
			draw2d_line(p->d, xb, mid - b->force[ax] * ch / 2, xa,
				    mid - a->force[ax] * ch / 2, 1.5f,
				    axis_rgb[ax]);
		}
	}
	p->y += ch + p->small * 0.5f;
}

static void draw_help(struct pen *p, const char *const *keys)
{
	for (int k = 0; keys[k]; k++) {
		const char *tab = strchr(keys[k], '\t');
		char key[48];

		if (!room(p, p->small * 1.3f)) {
			continue;
		}
		snprintf(key, sizeof(key), "%.*s", (int)(tab - keys[k]),
			 keys[k]);
		draw2d_text(p->d, FONT_SMALL, p->x, p->y + p->small, amber,
			    key);
		draw2d_text(p->d, FONT_SMALL, p->x + p->w * 0.32f,
			    p->y + p->small, white, tab + 1);
		p->y += p->small * 1.3f;
	}
}

/* The footer's two lines end at BOTTOM; the gap and the note above
 * them. */
#define FOOTER_SMALLS 2.9f
#define ABOVE_FOOTER_SMALLS (0.6f + 1.35f)

/* What found no room, in a line of its own. */
static void draw_hidden(struct pen *p)
{
	char text[96];

	if (!p->hidden) {
		return;
	}
	snprintf(text, sizeof(text), "+ %d more line%s: no room here",
		 p->hidden, p->hidden == 1 ? "" : "s");
	put(p, FONT_SMALL, dim, text);
}

static void draw_footer(struct pen *p, const struct hud_info *in,
			float bottom)
{
	char text[192];

	p->y = fmaxf(p->y + p->small * 0.6f,
		     bottom - p->small * FOOTER_SMALLS);
	if (*in->rig_problem) {
		put(p, FONT_SMALL, amber, in->rig_problem);
	} else {
		put(p, FONT_SMALL, dim, *in->rig_said ? in->rig_said :
				in->driving ? "your hand drives the rig" :
					      "H: keys");
	}
	if (in->replay) {
		snprintf(text, sizeof(text), "%.0f fps, %u triangles, cycle "
			 "%llu", in->fps, in->triangles,
			 in->st ? (unsigned long long)in->st->cycle : 0ull);
	} else {
		snprintf(text, sizeof(text), "%.0f fps, %u triangles, state "
			 "%.1f ms old", in->fps, in->triangles, in->age_ms);
	}
	put(p, FONT_SMALL, dim, text);
}

static void draw_panel(struct hud *h, struct pen *p, const struct hud_info *in,
		       const struct hud_layout *lay, int fb_h, double t_s)
{
	const char *const *keys = in->replay ? hud_replay_keys : hud_keys;
	bool patient = in->st && in->st->patient.enabled;

	draw_state(p, in);
	if (in->replay && in->st) {
		draw_replay(p, in->replay, lay, fb_h);
	}
	if (in->st && in->link != LINK_NO_DAEMON) {
		draw_guide(p, &in->st->guide);
	}
	gap(p);
	if (in->st && in->link != LINK_NO_DAEMON) {
		draw_where(p, in);
		if (rod(in->st)) {
			draw_moved(p, in);
		}
		draw_loop(p, in, t_s);
		draw_tool(p, in->st);
		draw_bleeding(p, &in->st->tool);
		gap(p);
		if (in->help) {
			draw_help(p, keys);
			return;
		}
		if (patient && in->compact) {
			/* little room: the patient before the forces */
			draw_patient(p, in);
			gap(p);
			draw_bars(p, in);
		} else {
			draw_bars(p, in);
			if (patient) {
				draw_patient(p, in);
			} else if (!in->compact) {
				draw_parts(p, in->st);
				gap(p);
				draw_chart(p, h, t_s);
			}
		}
		if (patient && in->voice) {
			line(p, FONT_SMALL, dim, in->voice);
		}
	} else if (in->help) {
		draw_help(p, keys);
	}
}

/* A banner across the middle of R (GL's origin) in a framebuffer FB_H high. */
static void banner(struct draw2d *d, struct endo_rect r, int fb_h,
		   const char *title, const char *text, const float rgb[4])
{
	float large = draw2d_px(d, FONT_LARGE);
	float small = draw2d_px(d, FONT_SMALL);
	float bh = large * 1.6f + small * 2.2f;
	float top = (float)(fb_h - r.y - r.h) + ((float)r.h - bh) / 2;
	float tw = draw2d_text_width(d, FONT_LARGE, title);
	float sw = draw2d_text_width(d, FONT_SMALL, text);

	draw2d_rect(d, (float)r.x, top, (float)r.w, bh, shade);
	draw2d_rect(d, (float)r.x, top, (float)r.w, 3, rgb);
	draw2d_text(d, FONT_LARGE, (float)r.x + ((float)r.w - tw) / 2,
		    top + large * 1.3f, rgb, title);
	draw2d_text(d, FONT_SMALL, (float)r.x + ((float)r.w - sw) / 2,
		    top + large * 1.5f + small * 1.2f, white, text);
}

/* A perforation, plainly: a red banner across the top of R. */
static void perforation_banner(struct draw2d *d, struct endo_rect r,
			       int fb_h, const struct hud_info *in)
{
	char name[MODEL_NAME], title[96];
	const char *how;
	float large = draw2d_px(d, FONT_LARGE);
	float small = draw2d_px(d, FONT_SMALL);
	float top = (float)(fb_h - r.y - r.h), bh = large * 1.5f + small * 1.6f;
	float tw, sw;

	if (in->link == LINK_NO_DAEMON || !in->st ||
	    !perforation(in, name, sizeof(name), &how)) {
		return;
	}
	snprintf(title, sizeof(title), "PERFORATION: %s", name);
	tw = draw2d_text_width(d, FONT_LARGE, title);
	sw = draw2d_text_width(d, FONT_SMALL, how);
	draw2d_rect(d, (float)r.x, top, (float)r.w, bh, perforated_rgb);
	draw2d_text(d, FONT_LARGE, (float)r.x + ((float)r.w - tw) / 2,
		    top + large * 1.2f, white, title);
	draw2d_text(d, FONT_SMALL, (float)r.x + ((float)r.w - sw) / 2,
		    top + large * 1.3f + small * 1.1f, white, how);
}

static void banners(struct draw2d *d, const struct hud_layout *lay,
		    const struct hud_info *in, int fb_h)
{
	struct endo_rect r = lay->endo.w ? lay->endo : lay->overview;
	char text[192];

	perforation_banner(d, r, fb_h, in);
	if (in->link == LINK_NO_DAEMON) {
		banner(d, r, fb_h, "NO DAEMON", *in->link_problem ?
			in->link_problem : "waiting for endosimd", red);
	} else if (in->link == LINK_STALE) {
		snprintf(text, sizeof(text), "no new state for %.1f s: the "
			 "force loop has stopped publishing", in->stale_s);
		banner(d, r, fb_h, "DAEMON STALE", text, amber);
	} else if (in->loading || !in->m) {
		banner(d, r, fb_h, "LOADING THE COLON", in->link_problem,
		       amber);
	}
}

void hud_draw(struct hud *h, struct draw2d *d, const struct hud_layout *lay,
	      const struct hud_info *in, int w, int hgt, double t_s)
{
	struct endo_rect r = lay->panel, o = lay->overview;
	float top, bottom, small = draw2d_px(d, FONT_SMALL);
	struct pen p = {
		.d = d, .h = h, .x = (float)r.x + MARGIN_PX,
		.w = (float)r.w - 2 * MARGIN_PX,
		.small = small,
		.large = draw2d_px(d, FONT_LARGE),
	};

	(void)w;
	if (in->help && lay->endo.w && o.w && o.y + o.h <= r.y) {
		/* the keys asked for with both views: the panel takes the
		 * overview's inset below it too */
		draw2d_rect(d, (float)o.x, (float)(hgt - o.y - o.h),
			    (float)o.w, (float)o.h, black);
		r.h += r.y - o.y;
		r.y = o.y;
	}
	top = (float)(hgt - r.y - r.h);
	bottom = top + (float)r.h - MARGIN_PX;
	p.y = top + MARGIN_PX;
	p.limit = bottom - small * (FOOTER_SMALLS + ABOVE_FOOTER_SMALLS);
	h->lines = 0;
	draw_panel(h, &p, in, lay, hgt, t_s);
	draw_hidden(&p);
	h->hidden = p.hidden;
	draw_footer(&p, in, bottom);
	h->end_px = p.y;
	banners(d, lay, in, hgt);
}

const char *hud_said(const struct hud *h, int i)
{
	return i >= 0 && i < h->lines ? h->said[i] : NULL;
}

int hud_hidden(const struct hud *h)
{
	return h->hidden;
}

float hud_end_px(const struct hud *h)
{
	return h->end_px;
}
