/* metricstext.c - see metricstext.h. */
#include "session/metricstext.h"

#include <errno.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FIELD(name, kind) { #name, offsetof(struct metrics_result, name), kind }
#define FIELD_D(name) FIELD(name, FIELDS_DOUBLE)
#define FIELD_U(name) FIELD(name, FIELDS_UINT)
#define FIELD_L(name) FIELD(name, FIELDS_UINT64)

static const struct metricstext_field fields[] = {
	FIELD_D(duration_s), FIELD_L(records), FIELD_L(drops),
	FIELD_D(cecum_s), FIELD_D(insertion_s), FIELD_D(withdrawal_s),
	FIELD_D(max_tip_s_m), FIELD_D(peak_insertion_n),
	FIELD_D(mean_insertion_n), FIELD_U(force_episodes),
	FIELD_D(force_episode_s), FIELD_U(loop_episodes),
	FIELD_D(longest_loop_s), FIELD_D(largest_loop_m),
	/* the patient, in place of format 4's discomfort index */
	FIELD_D(pain_share), FIELD_D(peak_pain), FIELD_U(pain_episodes),
#define FIELD_CAUSE(i, name)                                                 \
	{ "pain_s_" name,                                                    \
	  offsetof(struct metrics_result, pain_cause_s) +                    \
		  (i) * sizeof(double), FIELDS_DOUBLE }
	FIELD_CAUSE(ENDOSIM_PAIN_LOOPING, "looping"),
	FIELD_CAUSE(ENDOSIM_PAIN_STRAIGHTENING, "straightening"),
	FIELD_CAUSE(ENDOSIM_PAIN_INSUFFLATION, "insufflation"),
	FIELD_CAUSE(ENDOSIM_PAIN_TIP, "tip"),
#undef FIELD_CAUSE
	FIELD_U(gloucester), FIELD_D(gas_used_l), FIELD_D(peak_gas_pressure_pa),
	FIELD_U(position_changes), FIELD_U(hand_uses), FIELD_U(perforations),
	FIELD_D(lumen_lost_s), FIELD_D(mucosa_seen), FIELD_U(polyps_seen),
	FIELD_U(polyps_total), FIELD_U(polyps_seen_mask),
	FIELD_D(shaft_in_m), FIELD_D(tip_in_m), FIELD_D(chase_efficiency),
	FIELD_D(shaft_idle_m), FIELD_D(loop_s), FIELD_D(retraction_m),
	FIELD_D(tip_retraction_m), FIELD_D(retraction_efficiency),
	FIELD_D(clear_view), FIELD_U(lost_views), FIELD_D(mucosa_per_min),
#define FIELD_SEGMENT(i, name)                                               \
	{ "mucosa_seen_" name,                                               \
	  offsetof(struct metrics_result, mucosa_segment) +                  \
		  (i) * sizeof(double), FIELDS_DOUBLE }
	FIELD_SEGMENT(0, "anal_canal"), FIELD_SEGMENT(1, "rectum"),
	FIELD_SEGMENT(2, "sigmoid"), FIELD_SEGMENT(3, "descending"),
	FIELD_SEGMENT(4, "splenic_flexure"), FIELD_SEGMENT(5, "transverse"),
	FIELD_SEGMENT(6, "hepatic_flexure"), FIELD_SEGMENT(7, "ascending"),
	FIELD_SEGMENT(8, "cecum"),
#undef FIELD_SEGMENT
	/* the therapy through the working channel (therapy.h) */
	FIELD_U(polyps_resected), FIELD_U(polyps_partly),
	FIELD_U(polyps_retrieved), FIELD_D(resection_s), FIELD_D(cautery_s),
	FIELD_U(tool_injuries), FIELD_U(biopsies), FIELD_U(clips),
	FIELD_U(bleeds), FIELD_U(bleeds_clipped), FIELD_D(bleed_control_s),
};
_Static_assert(ANATOMY_SEGMENTS == 9, "metrics: a mucosa field a segment");
_Static_assert(ENDOSIM_PAIN_CAUSES == 5, "metrics: a field a pain cause");

#define NFIELDS (sizeof(fields) / sizeof(fields[0]))

size_t metricstext_fields(const struct metricstext_field **out)
{
	*out = fields;
	return NFIELDS;
}

double metricstext_field_value(const struct metrics_result *r,
			      const struct metricstext_field *f)
{
	const unsigned char *at = (const unsigned char *)r + f->offset;
	uint64_t l;
	uint32_t u;
	double d;

	switch (f->kind) {
	case FIELDS_UINT:
		memcpy(&u, at, sizeof(u));
		return u;
	case FIELDS_UINT64:
		memcpy(&l, at, sizeof(l));
		return (double)l;
	default:
		memcpy(&d, at, sizeof(d));
		return d;
	}
}

static int put(char *buf, size_t size, size_t *used, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

static int put(char *buf, size_t size, size_t *used, const char *fmt, ...)
{
	va_list ap;
	int n;

	va_start(ap, fmt);
	n = vsnprintf(buf + *used, size > *used ? size - *used : 0, fmt, ap);
	va_end(ap);
	if (n < 0 || *used + (size_t)n >= size) {
		return -ENOSPC;
	}
	*used += (size_t)n;
	return 0;
}

static int put_field(const struct metrics_result *r,
		     const struct metricstext_field *f, char *buf, size_t size,
		     size_t *used)
{
	const char *at = (const char *)r + f->offset;

	switch (f->kind) {
	case FIELDS_DOUBLE:
		return put(buf, size, used, "%s=%.9g\n", f->key,
			   *(const double *)at);
	case FIELDS_UINT:
		return put(buf, size, used, "%s=%u\n", f->key,
			   *(const uint32_t *)at);
	default:
		return put(buf, size, used, "%s=%llu\n", f->key,
			   (unsigned long long)*(const uint64_t *)at);
	}
}

static int put_episodes(const char *kind, const struct metrics_episode *ep,
			uint32_t n, char *buf, size_t size, size_t *used)
{
	bool pain = !strcmp(kind, "pain");

	for (uint32_t i = 0; i < n; i++) {
		if (put(buf, size, used, "%s_episode.%u=%.9g,%.9g,%.9g", kind,
			i, ep[i].start_s, ep[i].end_s, ep[i].peak) ||
		    (pain && put(buf, size, used, ",%u,%d", ep[i].cause,
				 ep[i].place)) ||
		    put(buf, size, used, "\n")) {
			return -ENOSPC;
		}
	}
	return 0;
}

static int put_polyps(const struct metrics_result *r, char *buf, size_t size,
		     size_t *used)
{
	for (uint32_t i = 0; i < r->n_polyp && i < METRICS_MAX_POLYPS; i++) {
		const struct metrics_polyp *p = &r->polyp[i];

		if (put(buf, size, used, "polyp.%u=%u,%.9g,%.9g,%.9g,%u\n", i,
			p->fate, p->start_s, p->cut_s, p->cautery_s,
			p->bites)) {
			return -ENOSPC;
		}
	}
	return 0;
}

int metricstext_format(const struct metrics_result *result, char *buf,
		      size_t size)
{
	size_t used = 0;

	if (size) {
		buf[0] = '\0';
	}
	for (size_t i = 0; i < NFIELDS; i++) {
		if (put_field(result, &fields[i], buf, size, &used)) {
			return -ENOSPC;
		}
	}
	if (put_episodes("force", result->force, result->n_force, buf, size,
			 &used) ||
	    put_episodes("loop", result->loop, result->n_loop, buf, size,
			 &used) ||
	    put_episodes("pain", result->pain, result->n_pain, buf, size,
			 &used) ||
	    put_polyps(result, buf, size, &used)) {
		return -ENOSPC;
	}
	return (int)used;
}

static int parse_number(const char *v, enum fields_kind kind, void *at)
{
	char *end;

	errno = 0;
	if (kind == FIELDS_DOUBLE) {
		*(double *)at = strtod(v, &end);
	} else {
		unsigned long long x = strtoull(v, &end, 10);

		if (kind == FIELDS_UINT && x > UINT32_MAX) {
			return -EINVAL;
		}
		if (kind == FIELDS_UINT) {
			*(uint32_t *)at = (uint32_t)x;
		} else {
			*(uint64_t *)at = x;
		}
	}
	return errno || end == v || *end ? -EINVAL : 0;
}

/* "KIND_episode.N=start,end,peak" (a pain episode's: ",cause,place"
 * after it, PAIN) into LIST (N < METRICS_MAX_EPISODES). */
static int parse_episode(const char *index, const char *v, bool pain,
			 struct metrics_episode *list, uint32_t *n)
{
	struct metrics_episode e = { .place = -1 };
	char *end;
	unsigned long i = strtoul(index, &end, 10);
	int used = 0;

	if (end == index || *end || i >= METRICS_MAX_EPISODES ||
	    sscanf(v, "%lf,%lf,%lf%n", &e.start_s, &e.end_s, &e.peak,
		   &used) != 3) {
		return -EINVAL;
	}
	v += used;
	used = 0;
	if (pain && (sscanf(v, ",%u,%d%n", &e.cause, &e.place, &used) != 2 ||
		     e.cause >= ENDOSIM_PAIN_CAUSES)) {
		return -EINVAL;
	}
	if (v[used]) {
		return -EINVAL;
	}
	list[i] = e;
	*n = *n > i + 1 ? *n : (uint32_t)i + 1;
	return 0;
}

/* "polyp.N=fate,start,cut,cautery,bites" into OUT's polyp[N]. */
static int parse_polyp(const char *index, const char *v,
		       struct metrics_result *out)
{
	struct metrics_polyp p;
	char *end;
	unsigned long i = strtoul(index, &end, 10);
	int used = 0;

	if (end == index || *end || i >= METRICS_MAX_POLYPS ||
	    sscanf(v, "%u,%lf,%lf,%lf,%u%n", &p.fate, &p.start_s, &p.cut_s,
		   &p.cautery_s, &p.bites, &used) != 5 || v[used] ||
	    p.fate >= METRICS_FATES) {
		return -EINVAL;
	}
	out->polyp[i] = p;
	out->n_polyp = out->n_polyp > i + 1 ? out->n_polyp : (uint32_t)i + 1;
	return 0;
}

static int parse_line(char *line, struct metrics_result *out)
{
	char *v = strchr(line, '=');

	if (!v) {
		return -EINVAL;
	}
	*v++ = '\0';
	if (!strncmp(line, "force_episode.", 14)) {
		return parse_episode(line + 14, v, false, out->force,
				     &out->n_force);
	}
	if (!strncmp(line, "loop_episode.", 13)) {
		return parse_episode(line + 13, v, false, out->loop,
				     &out->n_loop);
	}
	if (!strncmp(line, "pain_episode.", 13)) {
		return parse_episode(line + 13, v, true, out->pain,
				     &out->n_pain);
	}
	if (!strncmp(line, "polyp.", 6)) {
		return parse_polyp(line + 6, v, out);
	}
	for (size_t i = 0; i < NFIELDS; i++) {
		if (!strcmp(line, fields[i].key)) {
			return parse_number(v, fields[i].kind,
					    (char *)out + fields[i].offset);
		}
	}
	return 0; /* a later version's key */
}

int metricstext_parse(const char *text, struct metrics_result *out)
{
	char line[256];

	memset(out, 0, sizeof(*out));
	out->cecum_s = -1;
	while (*text) {
		size_t n = strcspn(text, "\n");

		if (n >= sizeof(line)) {
			return -EINVAL;
		}
		memcpy(line, text, n);
		line[n] = '\0';
		text += n + (text[n] == '\n');
		if (n && parse_line(line, out)) {
			return -EINVAL;
		}
	}
	return 0;
}
