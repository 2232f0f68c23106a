/* viewstats.c - see viewstats.h. */
#include "viewer/viewstats.h"

#include "viewer/mapview.h"

/* --pass-times' names, in timing.h's order */
static const char *const pass_name[] = { "update", "image", "lens",
					 "scale", "overview", "panel",
					 "swap" };

static void print_rect(FILE *out, const char *name, struct endo_rect r,
		       int fb_h)
{
	fprintf(out, " %s=%d,%d,%d,%d", name, r.x, fb_h - r.y - r.h, r.w,
		r.h);
}

void viewstats_print(FILE *out, const struct viewstats *s)
{
	const struct timing *t = s->timing;
	struct mapview_rect map;
	struct hud_layout lay;

	fprintf(out, "endoview: frames=%ld seconds=%.2f fps=%.1f "
		"frame_ms_p50=%.2f frame_ms_p99=%.2f age_ms_p50=%.2f "
		"age_ms_p99=%.2f triangles=%u triangles_max=%u gl_errors=%lu "
		"daemon=%s colon=%s\n", s->frames, s->seconds,
		s->seconds > 0 ? (double)s->frames / s->seconds : 0,
		timing_quantile(t, TIMING_FRAME, 0.5),
		timing_quantile(t, TIMING_FRAME, 0.99),
		timing_quantile(t, TIMING_AGE, 0.5),
		timing_quantile(t, TIMING_AGE, 0.99), s->triangles,
		s->triangles_max, s->gl_errors, s->daemon, s->colon);
	hud_layout(s->view, s->width, s->height, &lay);
	fprintf(out, "endoview: layout");
	print_rect(out, "endo", lay.endo, s->height);
	print_rect(out, "overview", lay.overview, s->height);
	print_rect(out, "panel", lay.panel, s->height);
	print_rect(out, "timeline", lay.timeline, s->height);
	map = s->map_shown ? mapview_box(s->width, s->height)
			   : (struct mapview_rect){ 0 };
	fprintf(out, " map=%d,%d,%d,%d\n", (int)map.x, (int)map.y,
		(int)map.w, (int)map.h);
	if (timing_count(t, TIMING_PASS_SWAP) == 0) {
		return; /* no --pass-times */
	}
	fprintf(out, "endoview: passes_ms");
	for (int k = TIMING_PASS_UPDATE; k <= TIMING_PASS_SWAP; k++) {
		fprintf(out, " %s=%.2f/%.2f", pass_name[k - TIMING_PASS_UPDATE],
			timing_quantile(t, (enum timing_kind)k, 0.5),
			timing_quantile(t, (enum timing_kind)k, 0.99));
	}
	fputc('\n', out);
}
