/* mapview.c - see mapview.h. */
#include "viewer/mapview.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "session/livemap.h"
#include "viewer/hud.h"
#include "viewer/reconnect.h"

#define MAX_REGIONS 16
#define MAX_FOUND 32
#define MARGIN_PX 12.0f
#define PAD_PX 10.0f

struct map_region {
	char name[32];
	double s0_m, s1_m;
};

struct mapview {
	struct reconnect *rc; /* the read-only socket; its problem: why there
				 is no map, "": there is one */
	bool offline;
	uint64_t next_poll_ns;
	bool have_map;
	uint64_t session_id;
	double time_s, length_m, mucosa_seen, tip_s_m;
	uint8_t cells[LIVEMAP_CELLS];
	struct map_region region[MAX_REGIONS];
	int regions;
	double found_s_m[MAX_FOUND], found_angle_rad[MAX_FOUND];
	int found;
	char said[256];
};

static const float back_rgb[4] = { 0.05f, 0.06f, 0.08f, 0.96f };
static const float wall_rgb[4] = { 0.16f, 0.17f, 0.20f, 1 };
static const float white[4] = { 0.92f, 0.94f, 0.97f, 1 };
static const float dim[4] = { 0.60f, 0.63f, 0.70f, 1 };
static const float line_rgb[4] = { 1, 1, 1, 0.55f };
static const float black[4] = { 0, 0, 0, 1 };
static const float polyp_rgb[4] = { 1.00f, 0.86f, 0.25f, 1 };

struct mapview *mapview_create(const char *socket, bool offline)
{
	struct mapview *v = calloc(1, sizeof(*v));

	if (!v) {
		return NULL;
	}
	/* no delay: the map is asked for every MAPVIEW_POLL_S */
	v->rc = reconnect_create(socket, false, 0, LOG_INFO, "mucosa map: ");
	if (!v->rc) {
		free(v);
		return NULL;
	}
	v->offline = offline;
	return v;
}

void mapview_destroy(struct mapview *v)
{
	if (!v) {
		return;
	}
	reconnect_destroy(v->rc);
	free(v);
}

/* ------------------------------------------------------------ asking */

static void no_map(struct mapview *v, const char *why)
{
	reconnect_say(v->rc, "%s", why);
	v->have_map = false;
}

/* The reply's map kept, if it is one of the size drawn here. */
static void take(struct mapview *v, const Endosim__MapReply *m)
{
	if (m->along != METRICS_MAP_S || m->around != METRICS_MAP_A ||
	    m->cells.len != LIVEMAP_CELLS) {
		no_map(v, "a map of another size: another endosimd version");
		return;
	}
	memcpy(v->cells, m->cells.data, LIVEMAP_CELLS);
	v->session_id = m->session_id;
	v->time_s = m->time_s;
	v->length_m = m->length_m;
	v->mucosa_seen = m->mucosa_seen;
	v->tip_s_m = m->tip_s_m;
	v->regions = 0;
	for (size_t i = 0; i < m->n_regions && i < MAX_REGIONS; i++) {
		struct map_region *r = &v->region[v->regions++];

		snprintf(r->name, sizeof(r->name), "%s", m->regions[i]->name);
		r->s0_m = m->regions[i]->s0_m;
		r->s1_m = m->regions[i]->s1_m;
	}
	v->found = 0;
	for (size_t i = 0; i < m->n_found && i < MAX_FOUND; i++) {
		v->found_s_m[v->found] = m->found[i]->s_m;
		v->found_angle_rad[v->found++] = m->found[i]->angle_rad;
	}
	reconnect_clear(v->rc);
	v->have_map = m->length_m > 0;
	if (!v->have_map) {
		no_map(v, "the colon has no geometry to map");
	}
}

static void ask(struct mapview *v, uint64_t now_ns)
{
	Endosim__SessionMap body = ENDOSIM__SESSION_MAP__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	char why[RECONNECT_PROBLEM];
	int err = reconnect_connect(v->rc, now_ns);

	if (err < 0) {
		snprintf(why, sizeof(why), "no endosimd: %s: %s",
			 reconnect_path(v->rc), strerror(-err));
		no_map(v, why);
		return;
	}
	req.body_case = ENDOSIM__REQUEST__BODY_SESSION_MAP;
	req.session_map = &body;
	err = reconnect_request(v->rc, &req, &rep, MAPVIEW_TIMEOUT_MS);
	if (err) {
		snprintf(why, sizeof(why), "no answer from endosimd: %s",
			 strerror(-err));
		no_map(v, why);
		return;
	}
	if (rep->status != ENDOSIM__STATUS__STATUS_OK) {
		no_map(v, rep->error && *rep->error ? rep->error :
			  client_status_text(rep->status));
	} else if (rep->body_case == ENDOSIM__REPLY__BODY_MAP) {
		take(v, rep->map);
	} else {
		no_map(v, "an endosimd without the map");
	}
	endosim__reply__free_unpacked(rep, NULL);
}

static void say(struct mapview *v)
{
	if (!v->have_map) {
		snprintf(v->said, sizeof(v->said), "%s",
			 reconnect_problem(v->rc));
		return;
	}
	snprintf(v->said, sizeof(v->said), "session %llu at %.1f s: %.1f %% "
		 "seen, %d x %d cells, %d polyp%s found",
		 (unsigned long long)v->session_id, v->time_s,
		 100 * v->mucosa_seen, METRICS_MAP_S, METRICS_MAP_A, v->found,
		 v->found == 1 ? "" : "s");
}

void mapview_update(struct mapview *v, bool shown, uint64_t now_ns)
{
	if (!shown) {
		reconnect_close(v->rc);
		reconnect_clear(v->rc);
		v->have_map = false;
		v->next_poll_ns = 0;
		return;
	}
	if (v->offline) {
		no_map(v, "no live map in a replay: the session's report has "
			  "it (endoctl session report)");
	} else if (now_ns >= v->next_poll_ns) {
		v->next_poll_ns =
			now_ns + (uint64_t)(MAPVIEW_POLL_S * ENDOSIM_NS_PER_S);
		ask(v, now_ns);
	}
	say(v);
}

const char *mapview_said(const struct mapview *v)
{
	return v->said;
}

/* ------------------------------------------------------------ drawing */

/* The map's cells in the box (top-left origin pixels). */
struct grid {
	float x, y, w, h;  /* the cells' area */
	float cw, ch;      /* one cell */
	float small, large; /* the fonts' pixel heights */
};

struct mapview_rect mapview_box(int w, int h)
{
	float small, large, map_w = (float)w - 2 * MARGIN_PX - 2 * PAD_PX;
	float map_h = fminf(map_w / METRICS_MAP_S * METRICS_MAP_A,
			    0.32f * (float)h);
	float box_h;

	hud_font_px(h, &small, &large);
	box_h = PAD_PX + 1.6f * large + map_h + 2.8f * small + PAD_PX;
	return (struct mapview_rect){ .x = MARGIN_PX,
				      .y = (float)h - MARGIN_PX - box_h,
				      .w = (float)w - 2 * MARGIN_PX,
				      .h = box_h };
}

static struct grid grid_of(struct mapview_rect box, int h)
{
	struct grid g;

	hud_font_px(h, &g.small, &g.large);
	g.x = box.x + PAD_PX;
	g.y = box.y + PAD_PX + 1.6f * g.large;
	g.w = box.w - 2 * PAD_PX;
	g.h = box.h - 2 * PAD_PX - 1.6f * g.large - 2.8f * g.small;
	g.cw = g.w / METRICS_MAP_S;
	g.ch = g.h / METRICS_MAP_A;
	return g;
}

/* X of S_M along the colon. */
static float along_x(const struct mapview *v, const struct grid *g,
		     double s_m)
{
	double f = v->length_m > 0 ? s_m / v->length_m : 0;

	return g->x + (float)fmin(fmax(f, 0), 1) * g->w;
}

/* A share seen 0..1 as a colour: unseen red to seen green (the map's
 * ramp, livemap_colour()). */
static void share_rgb(double s, float rgba[4])
{
	double rgb[3];

	livemap_colour(LIVEMAP_ON_SCREEN, s, rgb);
	for (int c = 0; c < 3; c++) {
		rgba[c] = (float)(rgb[c] / 255);
	}
	rgba[3] = 1;
}

static void draw_cells(const struct mapview *v, struct draw2d *d,
		       const struct grid *g)
{
	draw2d_rect(d, g->x, g->y, g->w, g->h, wall_rgb);
	for (int i = 0; i < METRICS_MAP_S; i++) {
		for (int k = 0; k < METRICS_MAP_A; k++) {
			const uint8_t *cell = &v->cells[i * METRICS_MAP_A + k];
			float rgba[4];

			if (*cell == LIVEMAP_NO_WALL) {
				continue;
			}
			share_rgb(livemap_share(*cell), rgba);
			/* a hair's overlap: no seams between cells */
			draw2d_rect(d, g->x + i * g->cw, g->y + k * g->ch,
				    g->cw + 0.5f, g->ch + 0.5f, rgba);
		}
	}
}

/* "splenic_flexure" as "splenic flexure", or its initials "SF" where the
 * name does not fit into WIDTH pixels. */
static void region_label(const struct draw2d *d, const char *name,
			 float width, char *out, size_t size)
{
	size_t n = 0;

	snprintf(out, size, "%s", name);
	for (char *p = out; *p; p++) {
		*p = *p == '_' ? ' ' : *p;
	}
	if (draw2d_text_width(d, FONT_SMALL, out) <= width - 4) {
		return;
	}
	for (const char *p = name; *p && n + 1 < size; p++) {
		if (p == name || p[-1] == '_') {
			out[n++] = (char)toupper((unsigned char)*p);
		}
	}
	out[n] = '\0';
}

static void draw_regions(const struct mapview *v, struct draw2d *d,
			 const struct grid *g)
{
	char label[32];

	for (int i = 0; i < v->regions; i++) {
		const struct map_region *r = &v->region[i];
		float x0 = along_x(v, g, r->s0_m), x1 = along_x(v, g, r->s1_m);

		if (i > 0) {
			draw2d_line(d, x0, g->y, x0,
				    g->y + g->h + 0.4f * g->small, 1.5f,
				    line_rgb);
		}
		region_label(d, r->name, x1 - x0, label, sizeof(label));
		draw2d_text(d, FONT_SMALL,
			    x0 + (x1 - x0 - draw2d_text_width(d, FONT_SMALL,
							      label)) / 2,
			    g->y + g->h + 1.3f * g->small, dim, label);
	}
}

/* A disc of radius R at (X, Y), as a fan of triangles. */
static void draw_polyps(const struct mapview *v, struct draw2d *d,
			const struct grid *g)
{
	float r = fmaxf(4, fminf(g->ch * 0.8f, 9));

	for (int i = 0; i < v->found; i++) {
		double a = fmod(v->found_angle_rad[i], 2 * M_PI);
		float x = along_x(v, g, v->found_s_m[i]);
		float y = g->y + (float)((a < 0 ? a + 2 * M_PI : a) /
					 (2 * M_PI)) * g->h;

		draw2d_disc(d, x, y, r + 2, black);
		draw2d_disc(d, x, y, r, polyp_rgb);
	}
}

/* The tip: a line across the map, a pointer above it. */
static void draw_tip(const struct mapview *v, struct draw2d *d,
		     const struct grid *g, double tip_s_m)
{
	float x = along_x(v, g, tip_s_m), t = 0.45f * g->small;
	float xy[6] = { x - t, g->y - 1.3f * t, x + t, g->y - 1.3f * t, x,
			g->y };

	draw2d_rect(d, x - 2, g->y, 4, g->h, black);
	draw2d_rect(d, x - 1, g->y, 2, g->h, white);
	draw2d_triangle(d, xy, white);
}

/* A swatch and its word, from X on the baseline Y; returns the next X. */
static float legend(struct draw2d *d, float x, float y, float px,
		    const float rgba[4], const char *word)
{
	draw2d_rect(d, x, y - 0.8f * px, 0.8f * px, 0.8f * px, rgba);
	return x + px + draw2d_text(d, FONT_SMALL, x + px, y, dim, word) +
	       px;
}

static void draw_title(const struct mapview *v, struct draw2d *d,
		       const struct mapview_rect *box, const struct grid *g)
{
	float base = box->y + PAD_PX + 1.1f * g->large;
	float x = box->x + PAD_PX, unseen[4], seen[4];

	x += draw2d_text(d, FONT_LARGE, x, base, white, "UNSEEN MUCOSA");
	if (v->have_map) {
		x += draw2d_printf(d, FONT_SMALL, x + g->small, base, white,
				   "   session %llu   %.0f %% seen   %d "
				   "polyp%s found", (unsigned long long)
				   v->session_id, 100 * v->mucosa_seen,
				   v->found, v->found == 1 ? "" : "s");
		x += 3 * g->small;
		share_rgb(0, unseen);
		share_rgb(1, seen);
		x = legend(d, x, base, g->small, unseen, "unseen");
		legend(d, x, base, g->small, seen, "seen");
	}
	draw2d_text(d, FONT_SMALL, box->x + box->w - PAD_PX -
		    draw2d_text_width(d, FONT_SMALL, "M: hide"), base, dim,
		    "M: hide");
}

void mapview_draw(const struct mapview *v, struct draw2d *d, int w, int h,
		  const struct endosim_state *st)
{
	struct mapview_rect box = mapview_box(w, h);
	struct grid g = grid_of(box, h);

	draw2d_rect(d, box.x, box.y, box.w, box.h, back_rgb);
	draw_title(v, d, &box, &g);
	if (!v->have_map) {
		draw2d_text(d, FONT_LARGE, g.x, g.y + g.h / 2, dim,
			    *reconnect_problem(v->rc) ? reconnect_problem(v->rc)
						       : "asking endosimd");
		draw2d_text(d, FONT_SMALL, g.x, g.y + g.h / 2 + 1.6f * g.large,
			    dim, v->offline ? "" : "the map fills in while a "
			    "training session records (endoctl session "
			    "start)");
		return;
	}
	draw_cells(v, d, &g);
	draw_regions(v, d, &g);
	draw_polyps(v, d, &g);
	draw_tip(v, d, &g, st && st->scope.depth_m > 0 ? st->scope.tip_s_m :
							v->tip_s_m);
	draw2d_text(d, FONT_SMALL, g.x, g.y + g.h + 2.6f * g.small, dim,
		    "along: anal verge to cecum, the tip white;  around "
		    "(down): a full turn from the frame's u;  yellow: "
		    "polyps found");
}
