/* traineepage.c - see traineepage.h. */
#include "session/traineepage.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "session/htmlpage.h"
#include "session/metricstext.h"

/* A main measure: its key (metricstext_fields()), what it is (in the
 * table's head: short), its unit on the page, the factor from the
 * metric's unit to it, and whether it counts (its axis: whole steps). */
struct measure {
	const char *key;
	const char *title;
	const char *brief;
	const char *unit;
	double scale;
	bool count;
};

static const struct measure measures[] = {
	{ "cecum_s", "Time to the cecum", "Cecum", "min", 1.0 / 60, false },
	{ "withdrawal_s", "Withdrawal time", "Withdrawal", "min", 1.0 / 60,
	  false },
	{ "mucosa_seen", "Mucosa seen", "Mucosa", "%", 100, false },
	{ "force_episodes", "Excessive-force episodes", "Force ep.", "", 1,
	  true },
	{ "loop_episodes", "Loop episodes", "Loops", "", 1, true },
	{ "peak_insertion_n", "Peak insertion force", "Peak force", "N", 1,
	  false },
	{ "pain_share", "Time in pain", "Pain", "%", 100, false },
	{ "perforations", "Perforations", "Perf.", "", 1, true },
	{ "polyps_seen", "Polyps found", "Polyps", "", 1, true },
};

#define NMEASURES (sizeof(measures) / sizeof(measures[0]))

static const char page_style[] =
	"td.met{color:#1e7d32}td.missed{color:#c62828}"
	"span.met{color:#1e7d32}span.missed{color:#c62828}"
	"span.met,span.missed{display:block;font-size:11px;"
	"white-space:nowrap}\n"
	"table#sessions th,table#sessions td{font-size:12px;padding:4px 5px;"
	"vertical-align:top}div.wide{overflow-x:auto}\n"
	"svg circle.met{fill:#2e7d32}svg circle.missed{fill:#c62828}"
	"svg circle.unjudged{fill:#888}\n"
	"p.complete{color:#1e7d32;font-weight:700;font-size:18px}"
	"p.incomplete{color:#b26a00;font-weight:700;font-size:18px}\n";

/* The measure's value in M in its unit on the page; NAN: none (the cecum
 * never reached). */
static double measure_value(const struct measure *me,
			    const struct metrics_result *m)
{
	const struct metricstext_field *f;
	size_t n = metricstext_fields(&f);

	for (size_t i = 0; i < n; i++) {
		if (!strcmp(f[i].key, me->key)) {
			double v = metricstext_field_value(m, &f[i]);

			return !strcmp(me->key, "cecum_s") && v < 0
				       ? NAN : v * me->scale;
		}
	}
	return NAN;
}

static void put_value(FILE *o, double v)
{
	if (isfinite(v)) {
		fprintf(o, "%.3g", v);
	} else {
		fputs("&ndash;", o);
	}
}

/* ---------------------------------------------------------- the status */

static void status_case(FILE *o, const struct coursefile *c, size_t k,
			const struct coursefile_progress *p,
			const struct traineepage_session *s)
{
	fputs("<li>", o);
	htmlpage_escape(o, c->cases[k].name);
	if (p->completed) {
		fprintf(o, ": complete (session %llu, %u in a row)</li>\n",
			(unsigned long long)s[p->completed - 1].id,
			c->consecutive);
		return;
	}
	fprintf(o, ": %u of %u sessions in a row met every requirement (%u "
		"session%s on it); %u more needed</li>\n", p->run,
		c->consecutive, p->sessions, p->sessions == 1 ? "" : "s",
		c->consecutive - p->run);
}

/* The status of course C, the K-th of N_COURSES (one: the ids the page
 * always had; more: each id numbered from the second). */
static int page_status(FILE *o, const struct coursefile *c, size_t k,
		       size_t n_courses, const struct traineepage_session *s,
		       size_t n)
{
	char id[24] = "";
	const char **cases = malloc((n ? n : 1) * sizeof(*cases));
	const struct metrics_result **m = malloc((n ? n : 1) * sizeof(*m));
	struct coursefile_progress p[COURSEFILE_MAX_CASES];
	bool done;

	if (!cases || !m) {
		free(cases);
		free(m);
		return -ENOMEM;
	}
	for (size_t i = 0; i < n; i++) {
		cases[i] = s[i].case_name;
		m[i] = s[i].m;
	}
	coursefile_progress(c, cases, m, n, p);
	done = coursefile_complete(c, p);
	if (k) {
		snprintf(id, sizeof(id), "-%zu", k + 1);
	}
	fprintf(o, "<section id=\"course%s\"><h2>Course ", id);
	htmlpage_escape(o, c->name);
	fprintf(o, "%s</h2>\n<p id=\"course-status%s\" class=\"%s\">%s</p>\n"
		"<p>", n_courses > 1 ? " (one of the trainee's courses)" : "",
		id, done ? "complete" : "incomplete",
		done ? "course complete" : "course not complete yet");
	htmlpage_escape(o, c->description);
	fprintf(o, "</p>\n<p>Each case needs %u sessions in a row that meet "
		"all its requirements.</p>\n<ul>\n", c->consecutive);
	for (size_t i = 0; i < c->n_cases; i++) {
		status_case(o, c, i, &p[i], s);
	}
	fputs("</ul></section>\n", o);
	free(cases);
	free(m);
	return 0;
}

/* ---------------------------------------------------------- the table */

/* The courses that judge a trainee, as the page goes through them. */
struct courses {
	const struct coursefile *const *c;
	size_t n;
};

/* Each requirement of K met by M or not; each after COURSE's name unless
 * NULL. */
static void reqs(FILE *o, const struct coursefile_case *k,
		 const struct metrics_result *m, const char *course)
{
	char text[96];

	for (size_t i = 0; i < k->n_reqs; i++) {
		bool met = coursefile_met(&k->req[i], m);

		coursefile_req_text(&k->req[i], text, sizeof(text));
		fprintf(o, "<span class=\"%s\">%s ", met ? "met" : "missed",
			met ? "&#10003;" : "&#10007;");
		if (course) {
			htmlpage_escape(o, course);
			fputs(": ", o);
		}
		htmlpage_escape(o, text);
		fputs("</span>", o);
	}
}

/* Session S judged by several courses: each that names its case. */
static void session_courses(FILE *o, const struct courses *cs,
			    const struct traineepage_session *s)
{
	size_t named = 0;

	fputs("<td>", o);
	for (size_t j = 0; j < cs->n; j++) {
		const struct coursefile_case *k = coursefile_case(cs->c[j],
								  s->case_name);
		bool passed = k && coursefile_passed(k, s->m);

		if (!k) {
			continue;
		}
		named++;
		fprintf(o, "<span class=\"%s\">", passed ? "met" : "missed");
		htmlpage_escape(o, cs->c[j]->name);
		fprintf(o, ": %s</span>", passed ? "passed" : "failed");
	}
	fprintf(o, "%s</td><td>", named ? "" : "not in the courses");
	for (size_t j = 0; j < cs->n; j++) {
		const struct coursefile_case *k = coursefile_case(cs->c[j],
								  s->case_name);

		if (k) {
			reqs(o, k, s->m, cs->c[j]->name);
		}
	}
	fputs("</td>", o);
}

static void session_reqs(FILE *o, const struct courses *cs,
			 const struct traineepage_session *s)
{
	const struct coursefile_case *k = cs->n == 1 ?
		coursefile_case(cs->c[0], s->case_name) : NULL;
	bool passed;

	if (cs->n > 1 && s->m) {
		session_courses(o, cs, s);
		return;
	}
	if (!k || !s->m) {
		fprintf(o, "<td>%s</td><td></td>", !cs->n ? "" :
			cs->n > 1 || k ? "not known" : "not in the course");
		return;
	}
	passed = coursefile_passed(k, s->m);
	fprintf(o, "<td class=\"%s\">%s</td><td>", passed ? "met" : "missed",
		passed ? "passed" : "failed");
	reqs(o, k, s->m, NULL);
	fputs("</td>", o);
}

static void session_row(FILE *o, const struct courses *c,
			const struct traineepage_session *s)
{
	fputs("<tr id=\"session-", o);
	if (s->rig) { /* IDs are the rigs' own: one may repeat another's */
		htmlpage_escape(o, s->rig);
		fputc('-', o);
	}
	fprintf(o, "%llu\"><td>", (unsigned long long)s->id);
	if (s->href) {
		fputs("<a href=\"", o);
		htmlpage_escape(o, s->href);
		fputs("\">", o);
	}
	fprintf(o, "%llu%s</td><td>", (unsigned long long)s->id,
		s->href ? "</a>" : "");
	if (s->rig) {
		htmlpage_escape(o, s->rig);
		fputs("</td><td>", o);
	}
	htmlpage_escape(o, s->started);
	fputs("</td><td>", o);
	htmlpage_escape(o, s->case_name);
	fputs("</td><td>", o);
	htmlpage_duration(o, s->m ? s->m->duration_s : -1);
	if (s->recomputed) {
		fputs(" (cut short)", o);
	}
	fputs("</td>", o);
	for (size_t i = 0; i < NMEASURES; i++) {
		fputs("<td>", o);
		put_value(o, s->m ? measure_value(&measures[i], s->m) : NAN);
		fputs("</td>", o);
	}
	session_reqs(o, c, s);
	fputs("</tr>\n", o);
}

static void page_sessions(FILE *o, const struct courses *c,
			  const struct traineepage_session *s, size_t n)
{
	fprintf(o, "<section><h2>Sessions</h2>\n<div class=\"wide\"><table "
		"id=\"sessions\"><tr><th>Session</th>%s<th>Date</th>"
		"<th>Case</th><th>Duration</th>", n && s[0].rig ?
		"<th>Rig</th>" : "");
	for (size_t i = 0; i < NMEASURES; i++) {
		fprintf(o, "<th title=\"%s\">%s%s%s%s</th>", measures[i].title,
			measures[i].brief,
			*measures[i].unit ? " (" : "", measures[i].unit,
			*measures[i].unit ? ")" : "");
	}
	fputs("<th>Course</th><th>Requirements</th></tr>\n", o);
	for (size_t i = 0; i < n; i++) {
		session_row(o, c, &s[i]);
	}
	fputs("</table></div></section>\n", o);
}

/* ----------------------------------------------------- learning curves */

/* The sections of the courses that name one case. */
struct bounds {
	const struct coursefile_case *k[TRAINEEPAGE_MAX_COURSES];
	size_t n;
};

/* The courses' bounds on ME for one case (B), as lines. */
static void curve_bound(const struct htmlpage_plot *p, const struct bounds *b,
			const struct measure *me)
{
	static const char *const op_html[] = {
		[COURSEFILE_LE] = "&le;", [COURSEFILE_GE] = "&ge;",
		[COURSEFILE_LT] = "&lt;", [COURSEFILE_GT] = "&gt;",
		[COURSEFILE_EQ] = "=",
	};
	char label[96];

	for (size_t j = 0; j < b->n; j++) {
		for (size_t i = 0; i < b->k[j]->n_reqs; i++) {
			const struct coursefile_req *q = &b->k[j]->req[i];

			if (strcmp(q->field->key, me->key)) {
				continue;
			}
			snprintf(label, sizeof(label), "requirement %s %g%s%s",
				 op_html[q->op], q->value * me->scale,
				 *me->unit ? " " : "", me->unit);
			htmlpage_plot_hline(p, q->value * me->scale, label);
		}
	}
}

/* The y range of ME over the case's sessions and its bound. */
static void curve_range(const struct traineepage_session *const *cs,
			size_t n, const struct bounds *b,
			const struct measure *me, double *lo, double *hi)
{
	*lo = 0;
	*hi = 0;
	for (size_t i = 0; i < n; i++) {
		double v = measure_value(me, cs[i]->m);

		*lo = isfinite(v) ? fmin(*lo, v) : *lo;
		*hi = isfinite(v) ? fmax(*hi, v) : *hi;
	}
	for (size_t j = 0; j < b->n; j++) {
		const struct coursefile_case *k = b->k[j];

		for (size_t i = 0; i < k->n_reqs; i++) {
			if (!strcmp(k->req[i].field->key, me->key)) {
				*hi = fmax(*hi, k->req[i].value * me->scale);
				*lo = fmin(*lo, k->req[i].value * me->scale);
			}
		}
	}
	*hi = *hi > *lo ? *hi * 1.1 : *lo + 1;
	*hi = me->count ? fmax(*hi, *lo + 5) : *hi; /* steps of 1 */
}

/* Whether M meets every requirement of the courses (B) on ME: 1, 0, or
 * -1 (none). */
static int measure_met(const struct bounds *b, const struct measure *me,
		       const struct metrics_result *m)
{
	int met = -1;

	for (size_t j = 0; j < b->n; j++) {
		const struct coursefile_case *k = b->k[j];

		for (size_t i = 0; i < k->n_reqs; i++) {
			if (!strcmp(k->req[i].field->key, me->key)) {
				met = met != 0 && coursefile_met(&k->req[i], m);
			}
		}
	}
	return met;
}

/* The measure over the case's N sessions CS as a line with points, each
 * marked by whether it met the course's requirements on the measure. */
static void curve_points(const struct htmlpage_plot *p,
			 const struct traineepage_session *const *cs, size_t n,
			 const struct bounds *k, const struct measure *me)
{
	bool first = true;

	fprintf(p->out, "<path class=\"series\" stroke=\"%s\" d=\"",
		htmlpage_color(0));
	for (size_t i = 0; i < n; i++) {
		double v = measure_value(me, cs[i]->m);

		if (isfinite(v)) {
			fprintf(p->out, "%s%.1f %.1f", first ? "M" : " L",
				htmlpage_px_x(p, (double)(i + 1)),
				htmlpage_px_y(p, v));
			first = false;
		}
	}
	fputs("\"/>\n", p->out);
	for (size_t i = 0; i < n; i++) {
		double v = measure_value(me, cs[i]->m);
		int met = measure_met(k, me, cs[i]->m);

		if (!isfinite(v)) {
			continue;
		}
		fprintf(p->out, "<circle class=\"point %s\" cx=\"%.1f\" "
			"cy=\"%.1f\" r=\"4.5\"><title>session %llu: %.3g%s%s%s"
			"</title></circle>\n", met < 0 ? "unjudged" : met ?
			"met" : "missed", htmlpage_px_x(p, (double)(i + 1)),
			htmlpage_px_y(p, v), (unsigned long long)cs[i]->id, v,
			*me->unit ? " " : "", me->unit, met < 0 ? "" : met ?
			" (requirement met)" : " (requirement not met)");
	}
}

/* The plot of ME over the N sessions CS on the ORDINAL-th case. */
static void curve(FILE *o, size_t ordinal, const char *case_name,
		  const struct traineepage_session *const *cs, size_t n,
		  const struct bounds *k, const struct measure *me)
{
	struct htmlpage_plot p = { .out = o, .xscale = 1 };
	char id[160], ylabel[64];
	double lo, hi;

	snprintf(id, sizeof(id), "curve-%zu-%s", ordinal, me->key);
	snprintf(ylabel, sizeof(ylabel), "%s%s%s%s", me->title,
		 *me->unit ? " (" : "", me->unit, *me->unit ? ")" : "");
	curve_range(cs, n, k, me, &lo, &hi);
	p.x = htmlpage_axis(0, (double)n, n < 10 ? (int)n : 10);
	fprintf(o, "<div class=\"curve\" data-case=\"");
	htmlpage_escape(o, case_name);
	fputs("\">\n", o);
	htmlpage_plot_begin(&p, id, me->title, lo, hi,
			    "the trainee's session on this case", ylabel);
	curve_bound(&p, k, me);
	curve_points(&p, cs, n, k, me);
	htmlpage_plot_end(&p);
	fputs("</div>\n", o);
}

/* The curves of the sessions on CASE_NAME, the ORDINAL-th case (from 1),
 * with metrics (CS: room for N). */
static void case_curves(FILE *o, size_t ordinal, const char *case_name,
			const struct traineepage_session *s, size_t n,
			const struct courses *c,
			const struct traineepage_session **cs)
{
	struct bounds b = { .n = 0 };
	size_t m = 0;

	for (size_t j = 0; j < c->n; j++) {
		if ((b.k[b.n] = coursefile_case(c->c[j], case_name))) {
			b.n++;
		}
	}
	for (size_t i = 0; i < n; i++) {
		if (s[i].m && !strcmp(s[i].case_name, case_name)) {
			cs[m++] = &s[i];
		}
	}
	if (!m) {
		return;
	}
	fprintf(o, "<h3 id=\"case-%zu\">Case ", ordinal);
	htmlpage_escape(o, case_name);
	fprintf(o, " (%zu session%s)</h3>\n", m, m == 1 ? "" : "s");
	for (size_t i = 0; i < NMEASURES; i++) {
		curve(o, ordinal, case_name, cs, m, &b, &measures[i]);
	}
}

/* Whether CASE_NAME came earlier than session I. */
static bool case_seen_before(const struct traineepage_session *s, size_t i)
{
	for (size_t j = 0; j < i; j++) {
		if (!strcmp(s[j].case_name, s[i].case_name)) {
			return true;
		}
	}
	return false;
}

static int page_curves(FILE *o, const struct traineepage_session *s,
		       size_t n, const struct courses *c)
{
	const struct traineepage_session **cs = malloc((n ? n : 1) *
						       sizeof(*cs));
	size_t ordinal = 0;

	if (!cs) {
		return -ENOMEM;
	}
	fputs("<section id=\"curves\"><h2>Learning curves</h2>\n", o);
	for (size_t i = 0; i < n; i++) {
		if (!case_seen_before(s, i)) {
			case_curves(o, ++ordinal, s[i].case_name, s, n, c,
				    cs);
		}
	}
	fputs("</section>\n", o);
	free(cs);
	return 0;
}

/* ------------------------------------------------------------ the page */

static void page_header(FILE *o, const char *trainee, size_t n)
{
	fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
	      "<title>Colonoscopy training: ", o);
	htmlpage_escape(o, trainee);
	fprintf(o, "</title>\n<style>\n%s%s</style></head><body>\n<header>"
		"<h1>Colonoscopy training: a trainee's course</h1>\n<dl>"
		"<dt>Trainee</dt><dd id=\"trainee\">", htmlpage_style,
		page_style);
	htmlpage_escape(o, trainee);
	fprintf(o, "</dd><dt>Sessions</dt><dd>%zu</dd></dl></header>\n", n);
}

int traineepage_write(const char *trainee,
		      const struct traineepage_session *s, size_t n,
		      const struct coursefile *const *courses,
		      size_t n_courses, const char *dir)
{
	struct courses cs = { .c = courses, .n = n_courses };
	char tmp[4200];
	FILE *o;
	int r = 0;

	if (n_courses > TRAINEEPAGE_MAX_COURSES) {
		return -EINVAL;
	}
	if (!(o = htmlpage_create(dir, tmp, sizeof(tmp)))) {
		return -errno;
	}
	page_header(o, trainee, n);
	for (size_t k = 0; !r && k < n_courses; k++) {
		r = page_status(o, courses[k], k, n_courses, s, n);
	}
	page_sessions(o, &cs, s, n);
	r = r ? r : page_curves(o, s, n, &cs);
	fputs("<footer>endosim &middot; the metrics are defined in "
	      "docs/METRICS.md, the courses in config/courses/</footer>\n"
	      "</body></html>\n", o);
	if (r) {
		fclose(o);
		unlink(tmp);
		return r;
	}
	return htmlpage_commit(o, tmp, dir);
}
