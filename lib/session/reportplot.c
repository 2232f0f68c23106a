/* reportplot.c - see reportplot.h. */
#include "session/reportplot.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

static double rec_t(const struct htmlpage_plot *p,
		    const struct session_record *r)
{
	return (double)(int64_t)(r->stamp_ns - p->t0_ns) * ENDOSIM_S_PER_NS;
}

void reportplot_begin(struct htmlpage_plot *p, const char *id,
		      const char *title, double ylo, double yhi,
		      const char *ylabel)
{
	htmlpage_plot_begin(p, id, title, ylo, yhi,
			    p->xscale > 1 ? "time (min)" : "time (s)", ylabel);
}

/* The column's extremes in the order they came (peaks survive). */
static void path_column(FILE *o, bool *first, double x, double a, double b)
{
	fprintf(o, "%s%.1f,%.1f", *first ? "M" : " L", x, a);
	*first = false;
	if (fabs(a - b) >= 0.05) {
		fprintf(o, " L%.1f,%.1f", x, b);
	}
}

void reportplot_series(const struct htmlpage_plot *p,
		       const struct session_file *f,
		       const struct reportplot_series *s, const char *color)
{
	bool first = true, have = false;
	long col = -1;
	double lo = 0, hi = 0;
	size_t ilo = 0, ihi = 0;

	fprintf(p->out, "<path class=\"series\" stroke=\"%s\" d=\"", color);
	for (size_t i = 0; i <= f->n_records; i++) {
		const struct session_record *r = &f->records[i < f->n_records ?
							   i : i - 1];
		long c = i < f->n_records
				 ? lround(htmlpage_px_x(p, rec_t(p, r)))
				 : -2;
		double v = i < f->n_records ? s->get(r, s->arg) : NAN;

		if (c != col && have) {
			path_column(p->out, &first, (double)col,
				    htmlpage_px_y(p, ilo < ihi ? lo : hi),
				    htmlpage_px_y(p, ilo < ihi ? hi : lo));
			have = false;
		}
		col = c;
		if (!isfinite(v)) {
			continue;
		}
		if (!have || v < lo) {
			lo = v;
			ilo = i;
		}
		if (!have || v > hi) {
			hi = v;
			ihi = i;
		}
		have = true;
	}
	fputs("\"/>\n", p->out);
}

void reportplot_range(const struct session_file *f,
		      const struct reportplot_series *s, int n, double *lo,
		      double *hi)
{
	for (size_t i = 0; i < f->n_records; i++) {
		for (int k = 0; k < n; k++) {
			double v = s[k].get(&f->records[i], s[k].arg);

			if (isfinite(v)) {
				*lo = fmin(*lo, v);
				*hi = fmax(*hi, v);
			}
		}
	}
}

double reportplot_tip_s(const struct session_record *r, int arg)
{
	(void)arg;
	return r->depth_m > 0 ? r->tip_s_m : NAN;
}
