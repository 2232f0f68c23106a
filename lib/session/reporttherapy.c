/* reporttherapy.c - see reporttherapy.h. */
#include "session/reporttherapy.h"

#include "session/htmlpage.h"
#include "session/therapy.h"

static void row(FILE *o, const char *what, const char *mark)
{
	fprintf(o, "<tr><th>%s</th><td class=\"%s\">", what, mark);
}

static void row_end(FILE *o, const char *note)
{
	fprintf(o, "</td><td class=\"note\">%s</td></tr>\n", note);
}

static void measures(FILE *o, const struct metrics_result *m)
{
	uint32_t left = m->n_polyp - m->polyps_resected - m->polyps_partly;

	fputs("<table class=\"metrics\">\n", o);
	row(o, "Polyps resected", m->polyps_resected == m->n_polyp ? "good"
								  : "bad");
	fprintf(o, "%u of %u, %u partly, %u left, %u retrieved",
		m->polyps_resected, m->n_polyp, m->polyps_partly, left,
		m->polyps_retrieved);
	row_end(o, "cut free whole; partly: bitten or burnt, in place");
	row(o, "Time per resection", "");
	if (m->polyps_resected) {
		htmlpage_duration(o, m->resection_s);
	} else {
		fputs("&ndash;", o);
	}
	row_end(o, "first touch of a tool to the polyp free; published: "
		"24 &plusmn; 18 s (rotary snare), 30 &plusmn; 26 s "
		"(standard)");
	row(o, "Cautery", "");
	htmlpage_duration(o, m->cautery_s);
	row_end(o, "the pedal down");
	row(o, "Wall injured", m->tool_injuries ? "bad" : "good");
	fprintf(o, "%u", m->tool_injuries);
	row_end(o, "current into the wall (a perforation with the patient)");
	row(o, "Biopsies, clips", "");
	fprintf(o, "%u bite%s, %u clip%s", m->biopsies,
		m->biopsies == 1 ? "" : "s", m->clips, m->clips == 1 ? "" : "s");
	row_end(o, "the forceps' samples; the clips placed");
	fputs("</table>\n", o);
}

/* Polyp I's place and kind from A, "&ndash;" without it. */
static void where(FILE *o, const struct anatomy *a, uint32_t i)
{
	const struct anatomy_polyp *p;
	int seg = 0;

	if (!a || i >= (uint32_t)a->polyps) {
		fputs("&ndash;", o);
		return;
	}
	p = &a->polyp[i];
	while (seg + 1 < ANATOMY_SEGMENTS &&
	       anatomy_segment_start(a, seg + 1) <= p->s_m) {
		seg++;
	}
	fprintf(o, "%s, %.0f cm, %.0f mm %s", anatomy_segment_name(seg),
		p->s_m * 100, p->diameter_m * 1e3,
		anatomy_paris_name(p->paris));
}

static const char *fate_mark(uint32_t fate)
{
	return fate >= METRICS_FATE_COMPLETE ? "good" :
	       fate == METRICS_FATE_PARTLY ? "warn" : "bad";
}

static void fates(FILE *o, const struct metrics_result *m,
		  const struct anatomy *a)
{
	fputs("<table class=\"episodes\" id=\"polyp-fates\"><tr><th>#</th>"
	      "<th>where</th><th>fate</th><th>first touch</th>"
	      "<th>resection</th><th>cautery</th><th>bites</th></tr>\n", o);
	for (uint32_t i = 0; i < m->n_polyp; i++) {
		const struct metrics_polyp *p = &m->polyp[i];

		fprintf(o, "<tr id=\"polyp-%u\"><td>%u</td><td>", i + 1, i + 1);
		where(o, a, i);
		fprintf(o, "</td><td class=\"%s\">%s</td><td>",
			fate_mark(p->fate), therapy_fate_name(p->fate));
		if (p->start_s >= 0) {
			htmlpage_duration(o, p->start_s);
		} else {
			fputs("&ndash;", o);
		}
		fputs("</td><td>", o);
		if (p->cut_s >= 0 && p->start_s >= 0) {
			htmlpage_duration(o, p->cut_s - p->start_s);
		} else {
			fputs("&ndash;", o);
		}
		fputs("</td><td>", o);
		htmlpage_duration(o, p->cautery_s);
		fprintf(o, "</td><td>%u</td></tr>\n", p->bites);
	}
	fputs("</table>\n", o);
}

void reporttherapy_write(FILE *o, const struct metrics_result *m,
			 const struct anatomy *a)
{
	if (!m->n_polyp) {
		return;
	}
	fputs("<section id=\"therapy\"><h2>Therapy</h2>\n", o);
	measures(o, m);
	fates(o, m, a);
	fputs("</section>\n", o);
}
