/* reportcompare.c - see reportcompare.h. */
#include "session/reportcompare.h"

#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "session/htmlpage.h"
#include "session/reportplot.h"

#define ALONG_BIN_M 0.01 /* the colon in 1 cm steps */
#define ALONG_BINS 400   /* up to 4 m */

/* What a session did at each place of the colon on its way in. */
struct along {
	double force[ALONG_BINS]; /* the largest |insertion force|, N */
	double loop[ALONG_BINS];  /* the largest bow of any segment, m */
	bool seen[ALONG_BINS];
};

/* F's records until the cecum (M's; all of them if never reached), by
 * the tip's place along the colon. */
static void along_colon(const struct session_file *f,
			const struct metrics_result *m, struct along *a)
{
	uint64_t t0 = f->n_records ? f->records[0].stamp_ns : 0;

	memset(a, 0, sizeof(*a));
	for (size_t i = 0; i < f->n_records; i++) {
		const struct session_record *r = &f->records[i];
		double t = (double)(r->stamp_ns - t0) * ENDOSIM_S_PER_NS,
		       bow = 0;
		long b = lround(r->tip_s_m / ALONG_BIN_M);

		if (m->cecum_s >= 0 && t > m->cecum_s) {
			break;
		}
		if (r->depth_m <= 0 || b < 0 || b >= ALONG_BINS) {
			continue;
		}
		for (uint32_t k = 0; k < r->spans && k < ENDOSIM_SPANS; k++) {
			bow = fmax(bow, fabs(r->bow_m[k]));
		}
		a->force[b] = fmax(a->force[b], fabs(r->limited[0]));
		a->loop[b] = fmax(a->loop[b], bow);
		a->seen[b] = true;
	}
}

/* One series of A (FORCE or LOOP) over the colon, dashed if DASH. */
static void along_series(const struct htmlpage_plot *p, const struct along *a,
			 bool force, const char *color, bool dash)
{
	bool first = true;

	fprintf(p->out, "<path class=\"series\" stroke=\"%s\"%s d=\"", color,
		dash ? " stroke-dasharray=\"6 3\"" : "");
	for (int b = 0; b < ALONG_BINS; b++) {
		double v = force ? a->force[b] : a->loop[b];

		if (!a->seen[b]) {
			continue;
		}
		fprintf(p->out, "%s%.1f,%.1f", first ? "M" : " L",
			htmlpage_px_x(p, b * ALONG_BIN_M), htmlpage_px_y(p, v));
		first = false;
	}
	fputs("\"/>\n", p->out);
}

/* A legend of the trainee's (solid) and the reference's (dashed). */
static void compare_legend(const struct htmlpage_plot *p)
{
	fprintf(p->out,
		"<line class=\"key\" stroke=\"%s\" x1=\"%.1f\" y1=\"14\" "
		"x2=\"%.1f\" y2=\"14\"/><text class=\"legend\" x=\"%.1f\" "
		"y=\"18\">this session</text><line class=\"key\" stroke=\"%s\" "
		"stroke-dasharray=\"6 3\" x1=\"%.1f\" y1=\"14\" x2=\"%.1f\" "
		"y2=\"14\"/><text class=\"legend\" x=\"%.1f\" y=\"18\">"
		"reference</text>\n", htmlpage_color(0), HTMLPAGE_PLOT_X + 4,
		HTMLPAGE_PLOT_X + 22,
		HTMLPAGE_PLOT_X + 26, htmlpage_color(2), HTMLPAGE_PLOT_X + 130,
		HTMLPAGE_PLOT_X + 148,
		HTMLPAGE_PLOT_X + 152);
}

/* A plot along the colon (x: the tip's place, m) of both sessions. */
static void along_plot(FILE *o, const struct along *mine,
		       const struct along *ref, const struct anatomy *a,
		       bool force)
{
	struct htmlpage_plot p = { .out = o, .xscale = 1 };
	double len = a ? anatomy_length(a) : 0, hi = force ? 10 : 0.02;

	for (int b = 0; b < ALONG_BINS; b++) {
		const struct along *s[2] = { mine, ref };

		for (int k = 0; k < 2; k++) {
			if (s[k]->seen[b]) {
				len = fmax(len, b * ALONG_BIN_M);
				hi = fmax(hi, force ? s[k]->force[b] :
						      s[k]->loop[b]);
			}
		}
	}
	p.x = htmlpage_axis(0, fmax(len, 0.1), 10);
	htmlpage_plot_begin(&p, force ? "compare-force" : "compare-loop",
			    force ? "Insertion force where the tip was, on "
				    "the way in"
				  : "The largest loop where the tip was, on the "
				    "way in",
			    0, hi, "the tip's place along the colon (m)",
			    force ? "force (N)" : "bow amplitude (m)");
	along_series(&p, ref, force, htmlpage_color(2), true);
	along_series(&p, mine, force, htmlpage_color(0), false);
	compare_legend(&p);
	htmlpage_plot_end(&p);
}

/* The tip's progress over time of both, on one time axis. */
static void compare_tip(FILE *o, const struct session_file *f,
			const struct metrics_result *m,
			const struct report_reference *ref)
{
	const struct reportplot_series s = { "tip along the colon",
					     reportplot_tip_s, 0 };
	struct htmlpage_plot p = { .out = o };
	double dur = fmax(m->duration_s, ref->m->duration_s), hi = 0.1;

	reportplot_range(f, &s, 1, &(double){ 0 }, &hi);
	reportplot_range(ref->f, &s, 1, &(double){ 0 }, &hi);
	p.xscale = dur > 300 ? 60 : 1;
	p.x = htmlpage_axis(0, fmax(dur, 1e-3) / p.xscale, 10);
	reportplot_begin(&p, "compare-tip", "The tip's progress: this session "
			 "and the reference", 0, hi,
			 "distance from the anal verge (m)");
	if (ref->f->n_records) {
		p.t0_ns = ref->f->records[0].stamp_ns;
		fprintf(o, "<g stroke-dasharray=\"6 3\">");
		reportplot_series(&p, ref->f, &s, htmlpage_color(2));
		fputs("</g>\n", o);
	}
	if (f->n_records) {
		p.t0_ns = f->records[0].stamp_ns;
		reportplot_series(&p, f, &s, htmlpage_color(0));
	}
	compare_legend(&p);
	htmlpage_plot_end(&p);
}

static void compare_row(FILE *o, const char *what, const char *fmt,
			double mine, double ref)
{
	fprintf(o, "<tr><th>%s</th><td>", what);
	fprintf(o, fmt, mine);
	fputs("</td><td>", o);
	fprintf(o, fmt, ref);
	fputs("</td></tr>\n", o);
}

/* Both sessions' main measures side by side. */
static void compare_table(FILE *o, const struct metrics_result *m,
			  const struct metrics_result *r)
{
	fputs("<table class=\"metrics\" id=\"compare-metrics\"><tr><th></th>"
	      "<th>this session</th><th>reference</th></tr>\n", o);
	compare_row(o, "duration (s)", "%.1f", m->duration_s, r->duration_s);
	compare_row(o, "time to the cecum (s; -1: not reached)", "%.1f",
		    m->cecum_s, r->cecum_s);
	compare_row(o, "withdrawal (s)", "%.1f", m->withdrawal_s,
		    r->withdrawal_s);
	compare_row(o, "deepest (m along the colon)", "%.2f", m->max_tip_s_m,
		    r->max_tip_s_m);
	compare_row(o, "peak insertion force (N)", "%.1f",
		    m->peak_insertion_n, r->peak_insertion_n);
	compare_row(o, "mean insertion force (N)", "%.1f",
		    m->mean_insertion_n, r->mean_insertion_n);
	compare_row(o, "excessive-force episodes", "%.0f",
		    m->force_episodes, r->force_episodes);
	compare_row(o, "... their time (s)", "%.1f", m->force_episode_s,
		    r->force_episode_s);
	compare_row(o, "loop episodes", "%.0f", m->loop_episodes,
		    r->loop_episodes);
	compare_row(o, "largest loop (cm)", "%.1f", m->largest_loop_m * 100,
		    r->largest_loop_m * 100);
	compare_row(o, "time in pain (%)", "%.1f", m->pain_share * 100,
		    r->pain_share * 100);
	compare_row(o, "peak pain (0-10)", "%.1f", m->peak_pain,
		    r->peak_pain);
	compare_row(o, "pain episodes", "%.0f", m->pain_episodes,
		    r->pain_episodes);
	compare_row(o, "Gloucester comfort (estimate)", "%.0f",
		    m->gloucester, r->gloucester);
	compare_row(o, "perforations", "%.0f", m->perforations,
		    r->perforations);
	compare_row(o, "lumen lost (s)", "%.1f", m->lumen_lost_s,
		    r->lumen_lost_s);
	compare_row(o, "mucosa seen (%)", "%.1f", m->mucosa_seen * 100,
		    r->mucosa_seen * 100);
	compare_row(o, "polyps seen", "%.0f", m->polyps_seen, r->polyps_seen);
	compare_row(o, "lumen in view (%)", "%.0f", m->clear_view * 100,
		    r->clear_view * 100);
	compare_row(o, "lumen lost (times)", "%.0f", m->lost_views,
		    r->lost_views);
	compare_row(o, "chase efficiency, in", "%.2f", m->chase_efficiency,
		    r->chase_efficiency);
	compare_row(o, "idle push, in (m)", "%.2f", m->shaft_idle_m,
		    r->shaft_idle_m);
	compare_row(o, "looped (s)", "%.1f", m->loop_s, r->loop_s);
	compare_row(o, "retraction efficiency, out", "%.2f",
		    m->retraction_efficiency, r->retraction_efficiency);
	fputs("</table>\n", o);
}

void reportcompare_write(FILE *o, const struct session_file *f,
			 const struct metrics_result *m,
			 const struct report_reference *ref,
			 const struct anatomy *a)
{
	static struct along mine, theirs;

	compare_table(o, m, ref->m);
	along_colon(f, m, &mine);
	along_colon(ref->f, ref->m, &theirs);
	compare_tip(o, f, m, ref);
	along_plot(o, &mine, &theirs, a, true);
	along_plot(o, &mine, &theirs, a, false);
}
