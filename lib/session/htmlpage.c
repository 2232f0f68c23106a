/* htmlpage.c - see htmlpage.h. */
#include "session/htmlpage.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *const palette[] = { "#1f5fa8", "#c0392b", "#2e8b57",
				       "#8e44ad", "#d4760a", "#6d4c41" };

/* ---------------------------------------------------------------- page */

const char htmlpage_style[] =
	"body{font-family:'DejaVu Sans',system-ui,sans-serif;margin:24px auto;"
	"max-width:1080px;color:#222;background:#f4f5f7}\n"
	"header,section{background:#fff;border-radius:8px;padding:16px 20px;"
	"margin-bottom:16px;box-shadow:0 1px 3px rgba(0,0,0,.12)}\n"
	"h1{margin:0 0 8px;font-size:24px}h2{font-size:18px;margin:0 0 10px}"
	"h3{font-size:15px;margin:14px 0 6px}\n"
	"dl{display:grid;grid-template-columns:repeat(3,auto 1fr);gap:4px 12px;"
	"margin:0}dt{color:#666}dd{margin:0;font-weight:600}\n"
	"table{border-collapse:collapse;width:100%}th,td{text-align:left;"
	"padding:5px 8px;border-bottom:1px solid #e4e4e4;font-size:14px}\n"
	"table.metrics th{width:200px}td.note{color:#777;font-size:12px}\n"
	"tr.good td:first-of-type{color:#1e7d32;font-weight:700}"
	"tr.bad td:first-of-type{color:#c62828;font-weight:700}"
	"tr.warn td:first-of-type{color:#b26a00;font-weight:700}\n"
	"tr.good th{border-left:5px solid #2e7d32}tr.bad th{border-left:5px "
	"solid #c62828}tr.warn th{border-left:5px solid #ef8f00}"
	"tr th{border-left:5px solid transparent}\n"
	"figure{margin:0 0 14px}figcaption{font-weight:600;margin:4px 0}\n"
	"svg.plot{display:block;max-width:100%;height:auto}\n"
	"svg .grid{stroke:#e6e6e6;stroke-width:1}svg .frame{fill:none;"
	"stroke:#999}\nsvg .tick,svg .legend,svg .seglabel,svg .evlabel,"
	"svg .thlabel{font-size:11px;fill:#555}svg .label{font-size:12px;"
	"fill:#333}\nsvg .series{fill:none;stroke-width:1.4;"
	"stroke-linejoin:round}svg .key{stroke-width:3}\n"
	"svg rect.force{fill:#e53935;fill-opacity:.16}svg rect.loop{"
	"fill:#fb8c00;fill-opacity:.18}\n"
	"svg .segment.s0{fill:#eef3fa}svg .segment.s1{fill:#fbfcfe}"
	"svg .seglabel{text-anchor:end;fill:#6a7b90}\n"
	"svg .event.fault{stroke:#c62828;stroke-width:1.5;stroke-dasharray:4 2}"
	"svg .event.state{stroke:#888;stroke-dasharray:2 3}\n"
	"svg .cecum{stroke:#2e7d32;stroke-width:1.5}svg .cecumlabel{"
	"font-size:11px;fill:#2e7d32}\n"
	"svg .threshold{stroke:#c62828;stroke-dasharray:6 4}"
	"svg .thlabel{fill:#c62828}\n"
	"p.none{color:#888;margin:2px 0}footer{color:#888;font-size:12px}\n";

FILE *htmlpage_create(const char *dir, char *tmp, size_t size)
{
	if (mkdir(dir, 0755) && errno != EEXIST) {
		return NULL;
	}
	if ((size_t)snprintf(tmp, size, "%s/index.html.tmp", dir) >= size) {
		errno = ENAMETOOLONG;
		return NULL;
	}
	return fopen(tmp, "w");
}

int htmlpage_commit(FILE *o, const char *tmp, const char *dir)
{
	char path[4096];
	int r = ferror(o) ? -EIO : 0;

	if (fclose(o) && !r) {
		r = -errno;
	}
	if (!r && (size_t)snprintf(path, sizeof(path), "%s/index.html", dir) >=
			  sizeof(path)) {
		r = -ENAMETOOLONG;
	}
	if (!r && rename(tmp, path)) {
		r = -errno;
	}
	if (r) {
		unlink(tmp);
	}
	return r;
}

/* ---------------------------------------------------------------- text */

void htmlpage_escape(FILE *out, const char *text)
{
	for (const char *c = text ? text : ""; *c; c++) {
		switch (*c) {
		case '&': fputs("&amp;", out); break;
		case '<': fputs("&lt;", out); break;
		case '>': fputs("&gt;", out); break;
		case '"': fputs("&quot;", out); break;
		case '\'': fputs("&#39;", out); break;
		default: fputc(*c, out);
		}
	}
}

void htmlpage_row_begin(FILE *o, const char *what, const char *mark)
{
	fprintf(o, "<tr class=\"%s\"><th>%s</th><td>", mark, what);
}

void htmlpage_row_end(FILE *o, const char *note)
{
	fprintf(o, "</td><td class=\"note\">%s</td></tr>\n", note);
}

void htmlpage_duration(FILE *out, double s)
{
	if (s < 0 || !isfinite(s)) {
		fputs("&ndash;", out);
	} else if (s < 60) {
		fprintf(out, "%.1f s", s);
	} else {
		fprintf(out, "%d min %02d s", (int)(s / 60), (int)fmod(s, 60));
	}
}

const char *htmlpage_color(int i)
{
	return palette[(unsigned)i % (sizeof(palette) / sizeof(palette[0]))];
}

/* ---------------------------------------------------------------- axes */

static double nice_step(double range, int ticks)
{
	double raw = range / ticks, mag = pow(10, floor(log10(raw)));
	double f = raw / mag;

	return (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * mag;
}

struct htmlpage_axis htmlpage_axis(double lo, double hi, int ticks)
{
	struct htmlpage_axis a;

	if (!(hi > lo)) {
		hi = lo + 1;
	}
	a.step = nice_step(hi - lo, ticks);
	a.lo = floor(lo / a.step + 1e-9) * a.step;
	a.hi = ceil(hi / a.step - 1e-9) * a.step;
	return a;
}

double htmlpage_px_x(const struct htmlpage_plot *p, double t_s)
{
	double u = (t_s / p->xscale - p->x.lo) / (p->x.hi - p->x.lo);

	return HTMLPAGE_PLOT_X + fmin(1, fmax(0, u)) * HTMLPAGE_PLOT_W;
}

double htmlpage_px_band(const struct htmlpage_axis *y, double v, double top,
			double height)
{
	double u = (v - y->lo) / (y->hi - y->lo);

	return top + height - fmin(1, fmax(0, u)) * height;
}

double htmlpage_px_y(const struct htmlpage_plot *p, double v)
{
	return htmlpage_px_band(&p->y, v, HTMLPAGE_PLOT_Y, HTMLPAGE_PLOT_H);
}

void htmlpage_yticks(FILE *o, const struct htmlpage_axis *y, double top,
		     double height)
{
	for (double v = y->lo; v <= y->hi + y->step / 2; v += y->step) {
		double py = htmlpage_px_band(y, v, top, height);

		fprintf(o, "<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" "
			"x2=\"%.1f\" y2=\"%.1f\"/><text class=\"tick\" "
			"x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n",
			HTMLPAGE_PLOT_X, py, HTMLPAGE_PLOT_X + HTMLPAGE_PLOT_W,
			py, HTMLPAGE_PLOT_X - 6, py + 4,
			fabs(v) < y->step / 1e6 ? 0 : v);
	}
}

static void plot_ticks(const struct htmlpage_plot *p, const char *xlabel,
		       const char *ylabel)
{
	FILE *o = p->out;

	htmlpage_yticks(o, &p->y, HTMLPAGE_PLOT_Y, HTMLPAGE_PLOT_H);
	for (double v = p->x.lo; v <= p->x.hi + p->x.step / 2; v += p->x.step) {
		double x = HTMLPAGE_PLOT_X + (v - p->x.lo) /
			   (p->x.hi - p->x.lo) * HTMLPAGE_PLOT_W;

		fprintf(o, "<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" "
			"x2=\"%.1f\" y2=\"%.1f\"/><text class=\"tick\" "
			"x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>\n",
			x, HTMLPAGE_PLOT_Y, x,
			HTMLPAGE_PLOT_Y + HTMLPAGE_PLOT_H, x,
			HTMLPAGE_PLOT_Y + HTMLPAGE_PLOT_H + 16, v);
	}
	fprintf(o, "<rect class=\"frame\" x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" "
		"height=\"%.1f\"/>\n", HTMLPAGE_PLOT_X, HTMLPAGE_PLOT_Y,
		HTMLPAGE_PLOT_W, HTMLPAGE_PLOT_H);
	fprintf(o, "<text class=\"label\" x=\"%.1f\" y=\"%d\" "
		"text-anchor=\"middle\">%s</text>\n",
		HTMLPAGE_PLOT_X + HTMLPAGE_PLOT_W / 2,
		HTMLPAGE_SVG_H - 4, xlabel);
	fprintf(o, "<text class=\"label\" transform=\"translate(16 %.1f) "
		"rotate(-90)\" text-anchor=\"middle\">%s</text>\n",
		HTMLPAGE_PLOT_Y + HTMLPAGE_PLOT_H / 2, ylabel);
}

void htmlpage_plot_begin(struct htmlpage_plot *p, const char *id,
			 const char *title, double ylo, double yhi,
			 const char *xlabel, const char *ylabel)
{
	p->y = htmlpage_axis(ylo, yhi, 5);
	fprintf(p->out, "<figure id=\"%s\"><figcaption>%s</figcaption>\n"
		"<svg class=\"plot\" xmlns=\"http://www.w3.org/2000/svg\" "
		"viewBox=\"0 0 %d %d\" width=\"%d\" height=\"%d\" role=\"img\" "
		"aria-label=\"%s\">\n", id, title, HTMLPAGE_SVG_W,
		HTMLPAGE_SVG_H, HTMLPAGE_SVG_W, HTMLPAGE_SVG_H,
		title);
	plot_ticks(p, xlabel, ylabel);
}

void htmlpage_plot_end(struct htmlpage_plot *p)
{
	fputs("</svg></figure>\n", p->out);
}

void htmlpage_plot_hline(const struct htmlpage_plot *p, double v,
			 const char *label)
{
	double y = htmlpage_px_y(p, v);

	fprintf(p->out, "<line class=\"threshold\" x1=\"%.1f\" y1=\"%.1f\" "
		"x2=\"%.1f\" y2=\"%.1f\"/><text class=\"thlabel\" x=\"%.1f\" "
		"y=\"%.1f\" text-anchor=\"end\">%s</text>\n", HTMLPAGE_PLOT_X,
		y, HTMLPAGE_PLOT_X + HTMLPAGE_PLOT_W, y,
		HTMLPAGE_PLOT_X + HTMLPAGE_PLOT_W - 4, y - 4, label);
}

