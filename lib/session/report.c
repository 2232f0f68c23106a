/*
 * report.c - the instructor's HTML report (report.h).
 */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/colon.h"
#include "session/htmlpage.h"
#include "session/livemap.h"
#include "proto/names.h"
#include "session/report.h"
#include "session/reportalong.h"
#include "session/reportcompare.h"
#include "session/reportplot.h"
#include "session/reporttherapy.h"
#include "session/sessioninputs.h"
#include "session/sessionmetrics.h"

#define WITHDRAWAL_MARK_S 360.0
#define MAX_EVENT_ROWS 200

/* ---------------------------------------------------------------- text */

/* The header's KEY, escaped, or a dash. */
static void put_header(FILE *out, const struct session_file *f,
		       const char *key)
{
	char v[256];

	if (f->header && !session_text_get(f->header, key, v, sizeof(v)) &&
	    v[0]) {
		htmlpage_escape(out, v);
	} else {
		fputs("&ndash;", out);
	}
}

/* ---------------------------------------------------------------- axes */

/* Episodes as shaded bands of CLASS, from 0 to the plot's top. */
static void plot_bands(const struct htmlpage_plot *p,
		       const struct metrics_episode *ep,
		       uint32_t n, double end_s, const char *cls)
{
	for (uint32_t i = 0; i < n; i++) {
		double x0 = htmlpage_px_x(p, ep[i].start_s);
		double x1 = htmlpage_px_x(p,
					  ep[i].end_s >= 0 ? ep[i].end_s : end_s);

		fprintf(p->out, "<rect class=\"band %s\" x=\"%.1f\" y=\"%.1f\" "
			"width=\"%.1f\" height=\"%.1f\"><title>%s %u</title>"
			"</rect>\n", cls, x0, HTMLPAGE_PLOT_Y,
			fmax(x1 - x0, 1.5), HTMLPAGE_PLOT_H,
			strcmp(cls, "force") ? "loop episode" : "force episode",
			i + 1);
	}
}

/* Faults (red) and state changes (grey) as vertical marks. */
static void plot_events(const struct htmlpage_plot *p,
			const struct session_file *f)
{
	double last_x = -1e9;
	int row = 0;

	for (size_t i = 0; i < f->n_events; i++) {
		const struct session_event *ev = &f->events[i].ev;
		double t = (double)(int64_t)(ev->stamp_ns - p->t0_ns) *
			   ENDOSIM_S_PER_NS;
		double x = htmlpage_px_x(p, t);

		if (ev->kind == SESSION_EVENT_FAULT) {
			fprintf(p->out,
				"<line class=\"event fault\" x1=\"%.1f\" "
				"y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"><title>"
				"fault: %s</title></line>\n", x,
				HTMLPAGE_PLOT_Y, x,
				HTMLPAGE_PLOT_Y + HTMLPAGE_PLOT_H,
				names_fault(ev->detail));
		} else if (ev->kind == SESSION_EVENT_STATE) {
			const char *s = names_state((uint32_t)ev->value);

			/* labels close together go one under the other */
			row = x - last_x < 50 ? (row + 1) % 3 : 0;
			last_x = x;

			fprintf(p->out,
				"<line class=\"event state\" x1=\"%.1f\" "
				"y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/><text "
				"class=\"evlabel\" x=\"%.1f\" y=\"%.1f\">%s"
				"</text>\n", x, HTMLPAGE_PLOT_Y, x,
				HTMLPAGE_PLOT_Y + HTMLPAGE_PLOT_H, x + 3,
				HTMLPAGE_PLOT_Y + 10 + 11 * row, s);
		}
	}
}

static void plot_legend(const struct htmlpage_plot *p,
			const struct reportplot_series *s, int n, bool bands)
{
	double x = HTMLPAGE_PLOT_X + 4;

	for (int i = 0; i < n; i++) {
		fprintf(p->out, "<line class=\"key\" stroke=\"%s\" x1=\"%.1f\" "
			"y1=\"14\" x2=\"%.1f\" y2=\"14\"/><text class=\"legend\" "
			"x=\"%.1f\" y=\"18\">%s</text>\n", htmlpage_color(i), x,
			x + 18, x + 22, s[i].name);
		x += 34 + 7.0 * (double)strlen(s[i].name);
	}
	if (bands) {
		fprintf(p->out,
			"<rect class=\"swatch force\" x=\"%.1f\" y=\"8\" "
			"width=\"14\" height=\"12\"/><text class=\"legend\" "
			"x=\"%.1f\" y=\"18\">excessive force</text>\n"
			"<rect class=\"swatch loop\" x=\"%.1f\" y=\"8\" width=\"14\" "
			"height=\"12\"/><text class=\"legend\" x=\"%.1f\" y=\"18\">"
			"loop</text>\n", x, x + 18, x + 130, x + 148);
	}
}

/* ---------------------------------------------------------- the values */

static double get_limited(const struct session_record *r, int axis)
{
	return axis == 0 ? fabs(r->limited[0]) : r->limited[axis];
}

static double get_bow(const struct session_record *r, int k)
{
	return (uint32_t)k < r->spans ? fabs(r->bow_m[k]) : NAN;
}

/* A plot of N series with the episodes and events marked. */
static void plot_series_figure(struct htmlpage_plot *p,
			       const struct session_file *f,
			       const struct metrics_result *m, const char *id,
			       const char *title, const char *ylabel,
			       const struct reportplot_series *s, int n,
			       double lo, double hi)
{
	reportplot_range(f, s, n, &lo, &hi);
	reportplot_begin(p, id, title, lo, hi, ylabel);
	plot_bands(p, m->force, m->n_force, m->duration_s, "force");
	plot_bands(p, m->loop, m->n_loop, m->duration_s, "loop");
	plot_events(p, f);
	for (int k = 0; k < n; k++) {
		reportplot_series(p, f, &s[k], htmlpage_color(k));
	}
	plot_legend(p, s, n, true);
}

/* ----------------------------------------------------------- the plots */

/* One series S up to at least HI with a line at LEVEL, LABEL. */
static void plot_level_figure(struct htmlpage_plot *p,
			      const struct session_file *f,
			      const struct metrics_result *m, const char *id,
			      const char *title, const char *ylabel,
			      const struct reportplot_series *s, double hi,
			      double level, const char *label)
{
	plot_series_figure(p, f, m, id, title, ylabel, s, 1, 0, hi);
	htmlpage_plot_hline(p, level, label);
	htmlpage_plot_end(p);
}

static void plot_force(struct htmlpage_plot *p, const struct session_file *f,
		       const struct metrics_result *m)
{
	const struct reportplot_series s[] = {
		{ "insertion |F|", get_limited, 0 },
	};
	struct metrics_params mp;
	char label[64];

	sessioninputs_file_metrics_params(f, &mp); /* the session's threshold */
	snprintf(label, sizeof(label), "threshold %g N", mp.force_threshold_n);
	plot_level_figure(p, f, m, "plot-force", "Insertion force",
			  "force (N)", s, mp.force_threshold_n * 1.1,
			  mp.force_threshold_n, label);
}

static void plot_torques(struct htmlpage_plot *p, const struct session_file *f,
			 const struct metrics_result *m)
{
	const struct reportplot_series s[] = {
		{ "roll", get_limited, 1 },
		{ "wheel up/down", get_limited, 2 },
		{ "wheel left/right", get_limited, 3 },
	};

	plot_series_figure(p, f, m, "plot-torque", "Roll and wheel torques",
			   "torque (N m)", s, 3, 0, 0);
	htmlpage_plot_end(p);
}

static double get_pain(const struct session_record *r, int arg)
{
	(void)arg;
	return r->patient ? r->pain : NAN;
}

/* The patient's pain over time, the level of "in pain" marked. */
static void plot_pain(struct htmlpage_plot *p, const struct session_file *f,
		      const struct metrics_result *m)
{
	const struct reportplot_series s[] = {
		{ "pain", get_pain, 0 },
	};
	struct metrics_params mp;
	char label[64];

	sessioninputs_file_metrics_params(f, &mp);
	snprintf(label, sizeof(label), "in pain from %g", mp.pain_level);
	plot_level_figure(p, f, m, "plot-pain", "The patient's pain",
			  "pain (0-10)", s, 10, mp.pain_level, label);
}

/* The segments as horizontal bands, named. */
static void plot_segments(const struct htmlpage_plot *p,
			  const struct anatomy *a)
{
	for (int i = 0; i < ANATOMY_SEGMENTS; i++) {
		double s0 = anatomy_segment_start(a, i);
		double s1 = s0 + a->seg[i].length_m;
		double y0 = htmlpage_px_y(p, s1), y1 = htmlpage_px_y(p, s0);

		fprintf(p->out, "<rect class=\"segment s%d\" x=\"%.1f\" "
			"y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"><title>%s"
			"</title></rect>\n", i % 2, HTMLPAGE_PLOT_X, y0,
			HTMLPAGE_PLOT_W, y1 - y0,
			anatomy_segment_name(i));
		if (y1 - y0 >= 9) { /* room for its name */
			fprintf(p->out, "<text class=\"seglabel\" x=\"%.1f\" "
				"y=\"%.1f\">%s</text>\n",
				HTMLPAGE_PLOT_X + HTMLPAGE_PLOT_W - 6,
				(y0 + y1) / 2 + 4, anatomy_segment_name(i));
		}
	}
}

static void plot_tip(struct htmlpage_plot *p, const struct session_file *f,
		     const struct metrics_result *m, const struct anatomy *a)
{
	const struct reportplot_series s[] = {
		{ "tip along the colon", reportplot_tip_s, 0 },
	};
	double len = a ? anatomy_length(a) : 0;

	reportplot_range(f, s, 1, &(double){ 0 }, &len);
	reportplot_begin(p, "plot-tip", "The tip's progress along the colon",
			 0, len, "distance from the anal verge (m)");
	if (a) {
		plot_segments(p, a);
	}
	plot_bands(p, m->force, m->n_force, m->duration_s, "force");
	plot_bands(p, m->loop, m->n_loop, m->duration_s, "loop");
	plot_events(p, f);
	if (m->cecum_s >= 0) {
		double x = htmlpage_px_x(p, m->cecum_s);

		fprintf(p->out, "<line class=\"cecum\" x1=\"%.1f\" y1=\"%.1f\" "
			"x2=\"%.1f\" y2=\"%.1f\"/><text class=\"cecumlabel\" "
			"x=\"%.1f\" y=\"%.1f\">cecum reached</text>\n", x,
			HTMLPAGE_PLOT_Y, x, HTMLPAGE_PLOT_Y + HTMLPAGE_PLOT_H,
			x + 4, HTMLPAGE_PLOT_Y + HTMLPAGE_PLOT_H - 6);
	}
	reportplot_series(p, f, &s[0], htmlpage_color(0));
	plot_legend(p, s, 1, true);
	htmlpage_plot_end(p);
}

/* The loop threshold F's metrics counted from (sessioninputs.h), m. */
static double loop_threshold_m(const struct session_file *f)
{
	struct metrics_params mp;

	sessioninputs_file_metrics_params(f, &mp);
	return mp.loop_threshold_m;
}

static void plot_bows(struct htmlpage_plot *p, const struct session_file *f,
		      const struct metrics_result *m, const struct anatomy *a)
{
	struct reportplot_series s[ENDOSIM_SPANS];
	double loop_m = loop_threshold_m(f);
	int n = 0;

	for (int i = 0; a && i < ANATOMY_SEGMENTS && n < ENDOSIM_SPANS; i++) {
		if (a->seg[i].mobile) {
			s[n] = (struct reportplot_series){
				anatomy_segment_name(i), get_bow, n };
			n++;
		}
	}
	for (; n == 0 && f->n_records && n < (int)f->records[0].spans &&
	       n < ENDOSIM_SPANS; n++) {
		s[n] = (struct reportplot_series){ "mobile segment", get_bow,
						   n };
	}
	plot_series_figure(p, f, m, "plot-bow", "Loops: the bow of each mobile "
			   "segment", "bow amplitude (m)", s, n, 0, loop_m * 1.5);
	htmlpage_plot_hline(p, loop_m, "loop threshold");
	htmlpage_plot_end(p);
}

/* ---------------------------------------------------------- the tables */

static void row_begin(FILE *o, const char *what, const char *mark)
{
	htmlpage_row_begin(o, what, mark);
}

static void row_end(FILE *o, const char *note)
{
	htmlpage_row_end(o, note);
}

static void metrics_rows_times(FILE *o, const struct metrics_result *m)
{
	bool reached = m->cecum_s >= 0;

	row_begin(o, "Cecum reached", reached ? "good" : "bad");
	if (reached) {
		fputs("yes, after ", o);
		htmlpage_duration(o, m->cecum_s);
	} else {
		fputs("no", o);
	}
	row_end(o, "the tip inside the cecum");
	row_begin(o, "Insertion time", "");
	htmlpage_duration(o, m->insertion_s);
	row_end(o, reached ? "start to cecum" : "so far: cecum not reached");
	row_begin(o, "Withdrawal time", !reached ? "bad" :
		  m->withdrawal_s >= WITHDRAWAL_MARK_S ? "good" : "bad");
	if (reached) {
		htmlpage_duration(o, m->withdrawal_s);
	} else {
		fputs("&ndash;", o);
	}
	row_end(o, "cecum to out; at least 6 min is the quality mark");
	row_begin(o, "Deepest point", "");
	fprintf(o, "%.2f m", m->max_tip_s_m);
	row_end(o, "from the anal verge along the colon");
}

static void metrics_rows_forces(FILE *o, const struct session_file *f,
				const struct metrics_result *m)
{
	struct metrics_params mp;
	char note[96];

	metrics_params_default(&mp);
	row_begin(o, "Insertion force", "");
	fprintf(o, "peak %.1f N, mean %.1f N", m->peak_insertion_n,
		m->mean_insertion_n);
	row_end(o, "what the tube pushed back against the hand");
	row_begin(o, "Excessive force", m->force_episodes ? "warn" : "good");
	fprintf(o, "%u episode%s, ", m->force_episodes,
		m->force_episodes == 1 ? "" : "s");
	htmlpage_duration(o, m->force_episode_s);
	snprintf(note, sizeof(note), "above %g N for at least %g s",
		 mp.force_threshold_n, mp.min_episode_s);
	row_end(o, note);
	row_begin(o, "Loops", m->loop_episodes ? "warn" : "good");
	fprintf(o, "%u, longest ", m->loop_episodes);
	htmlpage_duration(o, m->longest_loop_s);
	fprintf(o, ", largest %.1f cm", m->largest_loop_m * 100);
	snprintf(note, sizeof(note), "a mobile segment bowed more than %g cm",
		 loop_threshold_m(f) * 100);
	row_end(o, note);
}

/* The Gloucester score's words (docs/METRICS.md). */
static const char *gloucester_words(uint32_t score)
{
	static const char *const words[] = {
		"not assessed (no responding patient)",
		"1, comfortable", "2, minimal discomfort",
		"3, mild discomfort", "4, moderate discomfort",
		"5, severe discomfort",
	};

	return score < 6 ? words[score] : "?";
}

static void metrics_rows_patient(FILE *o, const struct session_file *f,
				 const struct metrics_result *m)
{
	struct metrics_params mp;
	char note[96];

	if (!metrics_has_patient(m)) {
		row_begin(o, "Patient", "");
		fputs("none", o);
		row_end(o, "the session ran without the patient's model");
		return;
	}
	sessioninputs_file_metrics_params(f, &mp);
	row_begin(o, "Time in pain", m->pain_episodes ? "warn" : "good");
	fprintf(o, "%.1f %%, peak %.1f, %u episode%s", 100 * m->pain_share,
		m->peak_pain, m->pain_episodes,
		m->pain_episodes == 1 ? "" : "s");
	snprintf(note, sizeof(note), "pain (0-10) at %g or above; episodes of "
		 "at least %g s", mp.pain_level, mp.min_episode_s);
	row_end(o, note);
	row_begin(o, "Time in pain by cause", "");
	for (int c = ENDOSIM_PAIN_LOOPING; c < ENDOSIM_PAIN_CAUSES; c++) {
		fprintf(o, "%s%s %.1f s", c > ENDOSIM_PAIN_LOOPING ? ", " : "",
			names_pain_cause((uint32_t)c), m->pain_cause_s[c]);
	}
	row_end(o, "what hurt most while in pain");
	row_begin(o, "Comfort (Gloucester)", m->gloucester > 3 ? "bad" :
		  m->gloucester > 2 ? "warn" : "");
	fputs(gloucester_words(m->gloucester), o);
	row_end(o, "an estimate from the pain episodes and the time in pain");
	row_begin(o, "Insufflation", "");
	fprintf(o, "%.2f L in, peak %.0f mmHg (%.0f Pa)", m->gas_used_l,
		m->peak_gas_pressure_pa / METRICS_PA_PER_MMHG,
		m->peak_gas_pressure_pa);
	row_end(o, "the gas pumped in and its largest pressure");
	row_begin(o, "Patient turned, assistant's hand", "");
	fprintf(o, "%u position change%s, %u press%s", m->position_changes,
		m->position_changes == 1 ? "" : "s", m->hand_uses,
		m->hand_uses == 1 ? "" : "es");
	row_end(o, "the patient's turns and the assistant's presses");
	row_begin(o, "Perforations", m->perforations ? "bad" : "good");
	fprintf(o, "%u", m->perforations);
	row_end(o, "bursts by pressure and tears by the tip");
}

static void metrics_rows_view(FILE *o, const struct metrics_result *m)
{
	row_begin(o, "Lumen lost from view", "");
	htmlpage_duration(o, m->lumen_lost_s);
	if (m->duration_s > 0) {
		fprintf(o, " (%.0f %%)", 100 * m->lumen_lost_s / m->duration_s);
	}
	row_end(o, "the tip facing the wall");
	row_begin(o, "Mucosa seen", "");
	fprintf(o, "%.0f %%", 100 * m->mucosa_seen);
	row_end(o, "share of the wall in view within 6 cm for 0.5 s");
	row_begin(o, "... by segment", "");
	for (int i = 1; i < ANATOMY_SEGMENTS; i++) { /* rectum .. cecum */
		fprintf(o, "%s%s %.0f %%", i > 1 ? ", " : "",
			anatomy_segment_name(i), 100 * m->mucosa_segment[i]);
	}
	row_end(o, "where the trainee looked, and where not");
	if (m->polyps_total) {
		row_begin(o, "Polyps seen", m->polyps_seen == m->polyps_total ?
			  "good" : "bad");
		fprintf(o, "%u of %u", m->polyps_seen, m->polyps_total);
		row_end(o, "in the camera's view for 2.5 s");
	}
	row_begin(o, "Lumen in view", "");
	fprintf(o, "%.0f %% of the time in, lost %u time%s",
		100 * m->clear_view, m->lost_views,
		m->lost_views == 1 ? "" : "s");
	row_end(o, "clear-view share and lost-view count");
	row_begin(o, "Scope handling, in", m->chase_efficiency >= 0.7 ?
		  "good" : "warn");
	fprintf(o, "chase efficiency %.2f (tip %.2f m for %.2f m of shaft), "
		"idle push %.2f m", m->chase_efficiency, m->tip_in_m,
		m->shaft_in_m, m->shaft_idle_m);
	row_end(o, "how much of the push reached the tip (docs/METRICS.md)");
	if (m->retraction_m > 0) {
		row_begin(o, "Scope handling, out", "");
		fprintf(o, "retraction efficiency %.2f (tip %.2f m for %.2f m "
			"of shaft)", m->retraction_efficiency,
			m->tip_retraction_m, m->retraction_m);
		row_end(o, "how much of the withdrawal moved the tip");
	}
	if (m->drops) {
		row_begin(o, "Records dropped", "warn");
		fprintf(o, "%llu", (unsigned long long)m->drops);
		row_end(o, "the recording has gaps");
	}
}

static void episode_table(FILE *o, const char *title,
			  const struct metrics_episode *ep, uint32_t n,
			  uint32_t count, const char *unit, double scale)
{
	fprintf(o, "<h3>%s</h3>\n", title);
	if (!n) {
		fputs("<p class=\"none\">none</p>\n", o);
		return;
	}
	fprintf(o, "<table class=\"episodes\"><tr><th>#</th><th>start</th>"
		"<th>end</th><th>duration</th><th>peak (%s)</th></tr>\n", unit);
	for (uint32_t i = 0; i < n; i++) {
		fprintf(o, "<tr><td>%u</td><td>", i + 1);
		htmlpage_duration(o, ep[i].start_s);
		fputs("</td><td>", o);
		if (ep[i].end_s >= 0) {
			htmlpage_duration(o, ep[i].end_s);
			fputs("</td><td>", o);
			htmlpage_duration(o, ep[i].end_s - ep[i].start_s);
		} else {
			fputs("still going</td><td>&ndash;", o);
		}
		fprintf(o, "</td><td>%.1f</td></tr>\n", ep[i].peak * scale);
	}
	fputs("</table>\n", o);
	if (count > n) {
		fprintf(o, "<p class=\"none\">and %u more</p>\n", count - n);
	}
}

/* The pain episodes: when, how long, how bad, why and where. */
static void pain_table(FILE *o, const struct metrics_result *m)
{
	fputs("<h3>Pain</h3>\n", o);
	if (!m->n_pain) {
		fputs("<p class=\"none\">none</p>\n", o);
		return;
	}
	fputs("<table class=\"episodes\" id=\"pain-episodes\"><tr><th>#</th>"
	      "<th>start</th><th>duration</th><th>peak (0-10)</th>"
	      "<th>cause</th><th>place</th></tr>\n", o);
	for (uint32_t i = 0; i < m->n_pain; i++) {
		const struct metrics_episode *e = &m->pain[i];

		fprintf(o, "<tr><td>%u</td><td>", i + 1);
		htmlpage_duration(o, e->start_s);
		fputs("</td><td>", o);
		if (e->end_s >= 0) {
			htmlpage_duration(o, e->end_s - e->start_s);
		} else {
			fputs("still going", o);
		}
		fprintf(o, "</td><td>%.1f</td><td>%s</td><td>%s</td></tr>\n",
			e->peak, names_pain_cause(e->cause),
			e->place >= 0 ? anatomy_segment_name(e->place)
				      : "&ndash;");
	}
	fputs("</table>\n", o);
	if (m->pain_episodes > m->n_pain) {
		fprintf(o, "<p class=\"none\">and %u more</p>\n",
			m->pain_episodes - m->n_pain);
	}
}

/* The CSV's word for an event's kind (names.h), a parameter's in full. */
static const char *event_kind(uint32_t kind)
{
	return kind == SESSION_EVENT_PARAM ? "parameter" : names_event(kind);
}

static void event_table(FILE *o, const struct session_file *f, uint64_t t0)
{
	fputs("<h3>Events</h3>\n", o);
	if (!f->n_events) {
		fputs("<p class=\"none\">none</p>\n", o);
		return;
	}
	fputs("<table class=\"events\"><tr><th>time</th><th>event</th>"
	      "<th>what</th></tr>\n", o);
	for (size_t i = 0; i < f->n_events && i < MAX_EVENT_ROWS; i++) {
		const struct session_event *ev = &f->events[i].ev;

		fprintf(o, "<tr class=\"%s\"><td>", event_kind(ev->kind));
		htmlpage_duration(o, (double)(int64_t)(ev->stamp_ns - t0) *
					     ENDOSIM_S_PER_NS);
		fprintf(o, "</td><td>%s</td><td>", event_kind(ev->kind));
		if (ev->kind == SESSION_EVENT_STATE) {
			fputs(names_state((uint32_t)ev->value), o);
		} else if (ev->kind == SESSION_EVENT_FAULT) {
			fprintf(o, "%s (axis %s) ", names_fault(ev->detail),
				ev->axis >= 0 ? names_axis(ev->axis) : "none");
		} else if (ev->kind == SESSION_EVENT_DROPS) {
			fprintf(o, "%.0f records dropped so far ", ev->value);
		}
		htmlpage_escape(o, f->events[i].text);
		fputs("</td></tr>\n", o);
	}
	fputs("</table>\n", o);
	if (f->n_events > MAX_EVENT_ROWS) {
		fprintf(o, "<p class=\"none\">and %zu more</p>\n",
			f->n_events - MAX_EVENT_ROWS);
	}
}

/* ------------------------------------------------------------ the page */

static void page_header(FILE *o, const struct session_file *f,
			const struct metrics_result *m)
{
	fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
	      "<title>Colonoscopy training report ", o);
	put_header(o, f, "id");
	fprintf(o, "</title>\n<style>\n%s</style></head><body>\n<header>"
		"<h1>Colonoscopy training report</h1>\n<dl>", htmlpage_style);
	fputs("<dt>Trainee</dt><dd id=\"trainee\">", o);
	put_header(o, f, "trainee");
	fputs("</dd><dt>Case</dt><dd>", o);
	put_header(o, f, "case");
	fputs("</dd><dt>Date</dt><dd>", o);
	put_header(o, f, "started");
	fputs("</dd>\n<dt>Duration</dt><dd>", o);
	htmlpage_duration(o, m->duration_s);
	fputs("</dd><dt>Session</dt><dd>", o);
	put_header(o, f, "id");
	fprintf(o, "</dd><dt>Records</dt><dd>%llu%s</dd></dl></header>\n",
		(unsigned long long)m->records, f->end ? "" :
		" (recording cut short)");
}

static void page_map(FILE *o, const struct metrics_map *map,
		     const struct anatomy *a, uint32_t found);

/* Where it hurt: the pain along the colon, next to the force and the
 * loop (reportalong.h), from ALONG (NULL: not computed). */
static void page_along(FILE *o, const struct session_file *f,
		       const struct metrics_result *m,
		       const struct metrics_along *along)
{
	struct metrics_params mp;

	if (!along || !f->n_records) {
		return;
	}
	sessioninputs_file_metrics_params(f, &mp);
	fputs("<section id=\"along\"><h2>Along the colon</h2>\n", o);
	reportalong_write(o, along, &mp, metrics_has_patient(m));
	fputs("</section>\n", o);
}

static void page_metrics(FILE *o, const struct session_file *f,
			 const struct metrics_result *m,
			 const struct anatomy *a, const struct metrics_map *map,
			 const struct metrics_along *along)
{
	struct htmlpage_plot p = { .out = o };

	fputs("<section><h2>Metrics</h2><table class=\"metrics\">\n", o);
	metrics_rows_times(o, m);
	metrics_rows_forces(o, f, m);
	metrics_rows_patient(o, f, m);
	metrics_rows_view(o, m);
	fputs("</table></section>\n<section><h2>Over time</h2>\n", o);
	if (f->n_records) {
		p.t0_ns = f->records[0].stamp_ns;
		p.xscale = m->duration_s > 300 ? 60 : 1;
		p.x = htmlpage_axis(0, fmax(m->duration_s, 1e-3) / p.xscale,
				    10);
		plot_force(&p, f, m);
		plot_torques(&p, f, m);
		plot_tip(&p, f, m, a);
		plot_bows(&p, f, m, a);
		if (m->peak_pain > 0) {
			plot_pain(&p, f, m);
		}
		if (map && map->length_m > 0) {
			page_map(o, map, a, m->polyps_seen_mask);
		}
	} else {
		fputs("<p class=\"none\">no records</p>\n", o);
	}
	fputs("</section>\n", o);
	page_along(o, f, m, along);
	reporttherapy_write(o, m, a);
	fputs("<section><h2>Episodes and events</h2>\n", o);
	episode_table(o, "Excessive force", m->force, m->n_force,
		      m->force_episodes, "N", 1);
	episode_table(o, "Loops", m->loop, m->n_loop, m->loop_episodes, "cm",
		      100);
	if (metrics_has_patient(m)) {
		pain_table(o, m);
	}
	event_table(o, f, p.t0_ns);
	fputs("</section>\n<footer>endosim ", o);
	put_header(o, f, "version");
	fputs(" &middot; the metrics are defined in docs/METRICS.md</footer>\n"
	      "</body></html>\n", o);
}

/* ------------------------------------------- compared with a reference */

static void page_compare(FILE *o, const struct session_file *f,
			 const struct metrics_result *m,
			 const struct report_reference *ref,
			 const struct anatomy *a)
{
	fputs("<section id=\"compare\"><h2>Compared with the reference: "
	      "session ", o);
	put_header(o, ref->f, "id");
	fputs(" (", o);
	put_header(o, ref->f, "trainee");
	fputs(")</h2>\n", o);
	reportcompare_write(o, f, m, ref, a);
	fputs("</section>\n", o);
}

/* The unseen-mucosa map: the colon unrolled, each cell's share seen from
 * red (none) to pale green (all) on the map's ramp (livemap_colour()), the
 * segments' ends, the polyps (found: filled, missed: a ring). */
static void page_map(FILE *o, const struct metrics_map *map,
		     const struct anatomy *a, uint32_t found)
{
	const double x0 = HTMLPAGE_PLOT_X, y0 = HTMLPAGE_PLOT_Y,
	w = HTMLPAGE_PLOT_W, h = HTMLPAGE_PLOT_H;
	const double cw = w / METRICS_MAP_S, ch = h / METRICS_MAP_A;

	fprintf(o, "<figure id=\"mucosa-map\"><figcaption>The mucosa "
		"unrolled: seen (green) and unseen (red), polyps found "
		"(filled) and missed (rings)</figcaption>\n<svg class=\"plot\" "
		"xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 %d %d\" "
		"width=\"%d\" height=\"%d\" role=\"img\">\n", HTMLPAGE_SVG_W,
		HTMLPAGE_SVG_H,
		HTMLPAGE_SVG_W, HTMLPAGE_SVG_H);
	for (int i = 0; i < METRICS_MAP_S; i++) {
		for (int k = 0; k < METRICS_MAP_A; k++) {
			double v = map->seen[i][k], rgb[3];

			if (v < 0) {
				continue;
			}
			livemap_colour(LIVEMAP_ON_PAGE, v, rgb);
			fprintf(o, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.2f\" "
				"height=\"%.2f\" fill=\"rgb(%d,%d,%d)\"/>\n",
				x0 + i * cw, y0 + k * ch, cw + 0.05, ch + 0.05,
				(int)lround(rgb[0]), (int)lround(rgb[1]),
				(int)lround(rgb[2]));
		}
	}
	for (int i = 0; a && i < ANATOMY_SEGMENTS && map->length_m > 0; i++) {
		double x = x0 + anatomy_segment_start(a, i) / map->length_m * w;

		fprintf(o, "<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" "
			"x2=\"%.1f\" y2=\"%.1f\"/><text class=\"tick\" "
			"x=\"%.1f\" y=\"%.1f\">%s</text>\n", x, y0, x, y0 + h,
			x + 2, y0 + h + 14 + 10 * (i % 2),
			anatomy_segment_name(i));
	}
	for (int p = 0; a && p < a->polyps && map->length_m > 0; p++) {
		double an = fmod(a->polyp[p].angle_rad, 2 * M_PI);

		an = an < 0 ? an + 2 * M_PI : an;
		fprintf(o, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5\" "
			"stroke=\"#1a1a1a\" stroke-width=\"2\" fill=\"%s\">"
			"<title>polyp %d: %s</title></circle>\n",
			x0 + a->polyp[p].s_m / map->length_m * w,
			y0 + an / (2 * M_PI) * h,
			found >> p & 1 ? "#1a1a1a" : "none", p + 1,
			found >> p & 1 ? "found" : "missed");
	}
	fprintf(o, "<text class=\"label\" transform=\"translate(16 %.1f) "
		"rotate(-90)\" text-anchor=\"middle\">around (0-360 deg)"
		"</text>\n", y0 + h / 2);
	htmlpage_plot_end(&(struct htmlpage_plot){ .out = o });
}

void report_print(FILE *o, const struct session_file *f,
		  const struct metrics_result *m,
		  const struct report_reference *ref)
{
	struct metrics_map *map = malloc(sizeof(*map));
	struct metrics_along along;
	struct anatomy a;
	char err[256];
	bool have_a, have_along;

	have_along = sessionmetrics_map(f, map, &along) == 0;
	if (!map || !have_along) {
		free(map);
		map = NULL; /* the report without its map */
	}
	have_a = sessioninputs_anatomy(f, &a, err, sizeof(err)) == 0;
	page_header(o, f, m);
	if (ref) {
		page_compare(o, f, m, ref, have_a ? &a : NULL);
	}
	page_metrics(o, f, m, have_a ? &a : NULL, map,
		     have_along ? &along : NULL);
	free(map);
}

int report_write(const struct session_file *f, const struct metrics_result *m,
		 const struct report_reference *ref, const char *dir)
{
	char tmp[4200];
	FILE *o = htmlpage_create(dir, tmp, sizeof(tmp));

	if (!o) {
		return -errno;
	}
	report_print(o, f, m, ref);
	return htmlpage_commit(o, tmp, dir);
}
