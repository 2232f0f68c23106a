/* reporttherapy.c - see reporttherapy.h. */
#include "session/reporttherapy.h"

#include <stdbool.h>

#include "session/htmlpage.h"
#include "session/therapy.h"

static void measures(FILE *o, const struct metrics_result *m)
{
	uint32_t left = m->n_polyp - m->polyps_resected - m->polyps_partly;
	char note[160];

	fputs("<table class=\"metrics\">\n", o);
	htmlpage_row_begin(o, "Polyps resected",
			   m->polyps_resected == m->n_polyp ? "good" : "bad");
	fprintf(o, "%u of %u, %u partly, %u left, %u retrieved",
		m->polyps_resected, m->n_polyp, m->polyps_partly, left,
		m->polyps_retrieved);
	htmlpage_row_end(o, "cut free whole; partly: bitten or burnt, in "
			 "place");
	htmlpage_row_begin(o, "Time per resection", "");
	htmlpage_duration(o, m->polyps_resected ? m->resection_s : -1);
	snprintf(note, sizeof(note), "first touch of a tool to the polyp "
		 "free; published: %.0f &plusmn; %.0f s (rotary snare), "
		 "%.0f &plusmn; %.0f s (standard)", REPORTTHERAPY_ROTARY_S,
		 REPORTTHERAPY_ROTARY_SD_S, REPORTTHERAPY_STANDARD_S,
		 REPORTTHERAPY_STANDARD_SD_S);
	htmlpage_row_end(o, note);
	htmlpage_row_begin(o, "Cautery", "");
	htmlpage_duration(o, m->cautery_s);
	htmlpage_row_end(o, "the pedal down");
	htmlpage_row_begin(o, "Wall injured",
			   m->tool_injuries ? "bad" : "good");
	fprintf(o, "%u", m->tool_injuries);
	htmlpage_row_end(o, "current into the wall (a perforation with the "
			 "patient)");
	htmlpage_row_begin(o, "Biopsies, clips", "");
	fprintf(o, "%u bite%s, %u clip%s", m->biopsies,
		m->biopsies == 1 ? "" : "s", m->clips,
		m->clips == 1 ? "" : "s");
	htmlpage_row_end(o, "the forceps' samples; the clips placed");
	htmlpage_row_begin(o, "Bleeding",
			   m->bleeds > m->bleeds_clipped ? "warn" : "");
	fprintf(o, "%u point%s, %u clipped", m->bleeds,
		m->bleeds == 1 ? "" : "s", m->bleeds_clipped);
	if (m->bleed_control_s > 0) {
		fputs(", stopped after ", o);
		htmlpage_duration(o, m->bleed_control_s);
	}
	htmlpage_row_end(o, "cut stalks bleeding; the mean time to stop, by "
			 "a clip or by itself (the hemostasis trainer: a "
			 "clip in 20 s, experts; 73 s, beginners)");
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
	fputs("<table class=\"metrics\" id=\"polyp-fates\"><tr><th>#</th>"
	      "<th>fate</th><th>where</th><th>first touch</th>"
	      "<th>resection</th><th>cautery</th><th>bites</th></tr>\n", o);
	for (uint32_t i = 0; i < m->n_polyp; i++) {
		const struct metrics_polyp *p = &m->polyp[i];
		bool cut = p->cut_s >= 0 && p->start_s >= 0;

		fprintf(o, "<tr id=\"polyp-%u\" class=\"%s\"><th>%u</th>"
			"<td>%s</td><td>", i + 1, fate_mark(p->fate), i + 1,
			therapy_fate_name(p->fate));
		where(o, a, i);
		fputs("</td><td>", o);
		htmlpage_duration(o, p->start_s);
		fputs("</td><td>", o);
		htmlpage_duration(o, cut ? p->cut_s - p->start_s : -1);
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
