/* anatomy.c - see anatomy.h. */
#include "model/anatomy.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/text.h"

#define DEG (M_PI / 180.0)
#define BEND_MARGIN 1.0 /* a bend's radius over the lumen radius, at least */

static const char *const segment_names[ANATOMY_SEGMENTS] = {
	"anal_canal", "rectum", "sigmoid", "descending", "splenic_flexure",
	"transverse", "hepatic_flexure", "ascending", "cecum",
};

static const char *const shape_names[] = { "sessile", "pedunculated",
					   "flat", NULL };

enum section { SEC_NONE, SEC_CASE, SEC_LUMEN, SEC_SEGMENT, SEC_POLYP };

enum key_type {
	KEY_DOUBLE, /* a number in the key's unit */
	KEY_DEG,    /* degrees in the file, radians in the struct */
	KEY_BOOL,   /* yes or no */
	KEY_NAME,   /* [A-Za-z0-9_-]+, ANATOMY_NAME */
	KEY_TEXT,   /* free text, ANATOMY_TEXT */
	KEY_SHAPE,  /* a polyp shape */
	KEY_BEND,   /* ANGLE_DEG RADIUS_M PLANE_DEG, repeatable */
};

struct key {
	enum section sec;
	const char *name;
	enum key_type type;
	size_t off; /* into struct anatomy, anatomy_segment or anatomy_polyp */
	double min, max;
	bool required;
};

#define A(f) offsetof(struct anatomy, f)
#define S(f) offsetof(struct anatomy_segment, f)
#define P(f) offsetof(struct anatomy_polyp, f)

static const struct key keys[] = {
	{ SEC_CASE, "name", KEY_NAME, A(name), 0, 0, true },
	{ SEC_CASE, "description", KEY_TEXT, A(description), 0, 0, false },
	{ SEC_LUMEN, "taenia_angle_deg", KEY_DEG, A(taenia_angle_rad), -360,
	  360, false },
	{ SEC_LUMEN, "taenia_depth", KEY_DOUBLE, 0, 0, 0.4, false },
	{ SEC_LUMEN, "fold_depth", KEY_DOUBLE, 0, 0, 0.5, false },
	{ SEC_LUMEN, "fold_spacing_m", KEY_DOUBLE, A(fold_spacing_m), 0.005,
	  0.2, false },
	{ SEC_LUMEN, "fold_width_m", KEY_DOUBLE, A(fold_width_m), 0.001, 0.05,
	  false },
	{ SEC_SEGMENT, "length_m", KEY_DOUBLE, S(length_m), 0.01, 2.0, true },
	{ SEC_SEGMENT, "diameter_m", KEY_DOUBLE, S(diameter_m), 0.01, 0.12,
	  true },
	{ SEC_SEGMENT, "taenia_depth", KEY_DOUBLE, S(taenia_depth), 0, 0.4,
	  false },
	{ SEC_SEGMENT, "fold_depth", KEY_DOUBLE, S(fold_depth), 0, 0.5, false },
	{ SEC_SEGMENT, "mobile", KEY_BOOL, S(mobile), 0, 0, false },
	{ SEC_SEGMENT, "mesentery_n_per_m", KEY_DOUBLE, S(mesentery_n_per_m),
	  1, 1e5, false },
	{ SEC_SEGMENT, "mesentery_height_m", KEY_DOUBLE,
	  S(mesentery_height_m), 0.005, 0.2, false },
	{ SEC_SEGMENT, "bend", KEY_BEND, 0, 0, 0, false },
	{ SEC_POLYP, "s_m", KEY_DOUBLE, P(s_m), 0, 3, true },
	{ SEC_POLYP, "angle_deg", KEY_DEG, P(angle_rad), -360, 360, true },
	{ SEC_POLYP, "diameter_m", KEY_DOUBLE, P(diameter_m), 0.001, 0.06,
	  true },
	{ SEC_POLYP, "shape", KEY_SHAPE, P(shape), 0, 0, false },
};

#define KEY_COUNT (sizeof(keys) / sizeof(keys[0]))

/* The state of one file being read. */
struct parser {
	struct anatomy *a;
	const char *path;
	char *err;
	size_t errsize;
	int line;
	enum section sec;
	int sec_line;        /* the current section's header */
	char sec_name[64];   /* for messages: "segment rectum", "polyp" */
	void *target;        /* the struct the section's keys land in */
	int key_line[KEY_COUNT]; /* in this section, 0: not seen */
	int segments;        /* [segment] sections read */
	bool seen_case, seen_lumen;
	double taenia_depth, fold_depth;   /* [lumen] defaults */
	int seg_line[ANATOMY_SEGMENTS];    /* header lines */
	int bend_line[ANATOMY_SEGMENTS][ANATOMY_MAX_BENDS];
	int length_line[ANATOMY_SEGMENTS];
	int mobile_line[ANATOMY_SEGMENTS];
	bool seg_set_taenia[ANATOMY_SEGMENTS], seg_set_fold[ANATOMY_SEGMENTS];
	int polyp_line[ANATOMY_MAX_POLYPS];
};

static int fail(struct parser *p, int line, const char *what, const char *fmt,
		...) __attribute__((format(printf, 4, 5)));

/* "FILE:LINE: WHAT: message"; always returns -EINVAL. */
static int fail(struct parser *p, int line, const char *what, const char *fmt,
		...)
{
	char msg[160];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(msg, sizeof(msg), fmt, ap);
	va_end(ap);
	snprintf(p->err, p->errsize, "%s:%d: %s: %s", p->path, line, what,
		 msg);
	return -EINVAL;
}

const char *anatomy_segment_name(int id)
{
	return id >= 0 && id < ANATOMY_SEGMENTS ? segment_names[id] : "?";
}

const char *anatomy_polyp_shape_name(int shape)
{
	return shape >= 0 && shape < 3 ? shape_names[shape] : "?";
}

double anatomy_segment_start(const struct anatomy *a, int id)
{
	double s = 0;

	for (int k = 0; k < id && k < ANATOMY_SEGMENTS; k++) {
		s += a->seg[k].length_m;
	}
	return s;
}

double anatomy_length(const struct anatomy *a)
{
	return anatomy_segment_start(a, ANATOMY_SEGMENTS);
}

static int parse_double(const char *text, double *out)
{
	char *end;

	errno = 0;
	*out = strtod(text, &end);
	return !*text || *end || errno || !isfinite(*out) ? -EINVAL : 0;
}

static int parse_number(struct parser *p, const struct key *k,
			const char *text, double *out)
{
	if (parse_double(text, out)) {
		return fail(p, p->line, k->name, "'%s' is not a number", text);
	}
	if (*out < k->min || *out > k->max) {
		return fail(p, p->line, k->name, "%s is out of range [%g, %g]",
			    text, k->min, k->max);
	}
	return 0;
}

static int parse_bend(struct parser *p, const struct key *k, char *text)
{
	struct anatomy_segment *seg = p->target;
	struct anatomy_bend *b = &seg->bend[seg->bends];
	char *tok[4], *save = NULL;
	double v[3];
	int n = 0;

	for (char *t = strtok_r(text, " \t", &save); t && n < 4;
	     t = strtok_r(NULL, " \t", &save)) {
		tok[n++] = t;
	}
	if (n != 3 || parse_double(tok[0], &v[0]) ||
	    parse_double(tok[1], &v[1]) || parse_double(tok[2], &v[2])) {
		return fail(p, p->line, k->name,
			    "expected ANGLE_DEG RADIUS_M PLANE_DEG");
	}
	if (v[0] <= 0 || v[0] > 180 || v[1] <= 0 || v[1] > 2 ||
	    fabs(v[2]) > 360) {
		return fail(p, p->line, k->name, "angle must be in (0, 180] "
			    "deg, radius in (0, 2] m, plane in [-360, 360] "
			    "deg");
	}
	if (seg->bends == ANATOMY_MAX_BENDS) {
		return fail(p, p->line, k->name, "more than %d bends",
			    ANATOMY_MAX_BENDS);
	}
	b->angle_rad = v[0] * DEG;
	b->radius_m = v[1];
	b->plane_rad = v[2] * DEG;
	p->bend_line[p->segments - 1][seg->bends++] = p->line;
	return 0;
}

static int parse_choice(struct parser *p, const struct key *k,
			const char *text, const char *const *choices, int *out)
{
	for (int i = 0; choices[i]; i++) {
		if (!strcmp(text, choices[i])) {
			*out = i;
			return 0;
		}
	}
	return fail(p, p->line, k->name, "'%s' is not a known choice", text);
}

static int parse_text(struct parser *p, const struct key *k, const char *text,
		      char *out, size_t size, bool name)
{
	if (strlen(text) >= size) {
		return fail(p, p->line, k->name, "longer than %zu characters",
			    size - 1);
	}
	for (const char *c = text; name && *c; c++) {
		if (!isalnum((unsigned char)*c) && *c != '-' && *c != '_') {
			return fail(p, p->line, k->name, "'%s': use letters, "
				    "digits, '-' and '_'", text);
		}
	}
	if (name && !*text) {
		return fail(p, p->line, k->name, "empty");
	}
	strcpy(out, text);
	return 0;
}

/* Stores VALUE for K; [lumen]'s depths go to the parser's defaults. */
static int apply(struct parser *p, const struct key *k, char *value)
{
	static const char *const bools[] = { "no", "yes", NULL };
	char *dst = (char *)p->target + k->off;
	double num;
	int choice = 0, r;

	switch (k->type) {
	case KEY_DOUBLE:
	case KEY_DEG:
		r = parse_number(p, k, value, &num);
		if (r) {
			return r;
		}
		if (p->sec == SEC_LUMEN && !strcmp(k->name, "taenia_depth")) {
			p->taenia_depth = num;
		} else if (p->sec == SEC_LUMEN &&
			   !strcmp(k->name, "fold_depth")) {
			p->fold_depth = num;
		} else {
			*(double *)dst = k->type == KEY_DEG ? num * DEG : num;
		}
		return 0;
	case KEY_BOOL:
		r = parse_choice(p, k, value, bools, &choice);
		if (!r) {
			*(bool *)dst = choice;
		}
		return r;
	case KEY_SHAPE:
		return parse_choice(p, k, value, shape_names, (int *)dst);
	case KEY_NAME:
		return parse_text(p, k, value, dst, ANATOMY_NAME, true);
	case KEY_TEXT:
		return parse_text(p, k, value, dst, ANATOMY_TEXT, false);
	case KEY_BEND:
		return parse_bend(p, k, value);
	}
	return -EINVAL;
}

static const struct key *find_key(enum section sec, const char *name)
{
	for (size_t i = 0; i < KEY_COUNT; i++) {
		if (keys[i].sec == sec && !strcmp(keys[i].name, name)) {
			return &keys[i];
		}
	}
	return NULL;
}

static int parse_key(struct parser *p, char *line)
{
	char *eq = strchr(line, '='), *name, *value;
	const struct key *k;
	size_t idx;

	if (!eq) {
		return fail(p, p->line, text_trim(line), "expected 'key = value'");
	}
	*eq = '\0';
	name = text_trim(line);
	value = text_trim(eq + 1);
	if (p->sec == SEC_NONE) {
		return fail(p, p->line, name, "before any [section]");
	}
	k = find_key(p->sec, name);
	if (!k) {
		return fail(p, p->line, name, "unknown key in [%s]",
			    p->sec_name);
	}
	idx = (size_t)(k - keys);
	if (p->key_line[idx] && k->type != KEY_BEND) {
		return fail(p, p->line, name, "duplicate key (first set on "
			    "line %d)", p->key_line[idx]);
	}
	p->key_line[idx] = p->line;
	return apply(p, k, value);
}

/* The line KEY of the current section was set on, 0 if not. */
static int line_of(const struct parser *p, const char *key)
{
	const struct key *k = find_key(p->sec, key);

	return k ? p->key_line[k - keys] : 0;
}

/* Checks what a section needs once all its keys are read. */
static int finish_section(struct parser *p)
{
	for (size_t i = 0; i < KEY_COUNT; i++) {
		if (keys[i].sec == p->sec && keys[i].required &&
		    !p->key_line[i]) {
			return fail(p, p->sec_line, p->sec_name,
				    "%s is missing", keys[i].name);
		}
	}
	if (p->sec == SEC_SEGMENT) {
		int id = p->segments - 1;

		p->length_line[id] = line_of(p, "length_m");
		p->mobile_line[id] = line_of(p, "mobile");
		p->seg_set_taenia[id] = line_of(p, "taenia_depth") != 0;
		p->seg_set_fold[id] = line_of(p, "fold_depth") != 0;
	}
	return 0;
}

static int open_segment(struct parser *p, const char *name)
{
	struct anatomy_segment *seg;

	if (p->segments == ANATOMY_SEGMENTS) {
		return fail(p, p->line, p->sec_name, "all %d segments are "
			    "already there", ANATOMY_SEGMENTS);
	}
	if (strcmp(name, segment_names[p->segments])) {
		return fail(p, p->line, p->sec_name, "expected [segment %s] "
			    "next (segments run from the anal verge in order: "
			    "anal_canal ... cecum)", segment_names[p->segments]);
	}
	seg = &p->a->seg[p->segments];
	seg->mesentery_n_per_m = 150;
	seg->mesentery_height_m = 0.06;
	p->seg_line[p->segments] = p->line;
	p->target = seg;
	p->segments++;
	return 0;
}

static int open_polyp(struct parser *p)
{
	if (p->a->polyps == ANATOMY_MAX_POLYPS) {
		return fail(p, p->line, "[polyp]", "more than %d polyps",
			    ANATOMY_MAX_POLYPS);
	}
	p->polyp_line[p->a->polyps] = p->line;
	p->target = &p->a->polyp[p->a->polyps++];
	return 0;
}

/* "[name]" or "[segment NAME]": ends the previous section, opens one. */
static int parse_header(struct parser *p, char *line)
{
	char *close = strchr(line, ']'), *name, *arg;
	int r;

	if (!close || *text_trim(close + 1)) {
		return fail(p, p->line, text_trim(line), "expected '[section]'");
	}
	*close = '\0';
	name = text_trim(line + 1);
	arg = strpbrk(name, " \t");
	if (arg) {
		*arg++ = '\0';
		arg = text_trim(arg);
	}
	if (p->sec != SEC_NONE && (r = finish_section(p))) {
		return r;
	}
	snprintf(p->sec_name, sizeof(p->sec_name), "[%s%s%s]", name,
		 arg ? " " : "", arg ? arg : "");
	memset(p->key_line, 0, sizeof(p->key_line));
	p->sec_line = p->line;
	if (!p->seen_case && strcmp(name, "case")) {
		return fail(p, p->line, p->sec_name, "the file must start "
			    "with [case]");
	}
	if (!strcmp(name, "segment") && arg) {
		p->sec = SEC_SEGMENT;
		return open_segment(p, arg);
	}
	if (arg) {
		return fail(p, p->line, p->sec_name, "unknown section");
	}
	if (!strcmp(name, "polyp")) {
		p->sec = SEC_POLYP;
		return open_polyp(p);
	}
	if ((!strcmp(name, "case") && !p->seen_case) ||
	    (!strcmp(name, "lumen") && !p->seen_lumen)) {
		p->sec = !strcmp(name, "case") ? SEC_CASE : SEC_LUMEN;
		p->seen_case = true;
		p->seen_lumen |= p->sec == SEC_LUMEN;
		p->target = p->a;
		return 0;
	}
	return fail(p, p->line, p->sec_name, !strcmp(name, "case") ||
		    !strcmp(name, "lumen") ? "appears twice" :
		    "unknown section (case, lumen, segment NAME, polyp)");
}

static int parse_stream(struct parser *p, FILE *f)
{
	char buf[512], *line;
	int r;

	while (fgets(buf, sizeof(buf), f)) {
		p->line++;
		if (!strchr(buf, '\n') && !feof(f)) {
			return fail(p, p->line, "line", "longer than %zu "
				    "characters", sizeof(buf) - 2);
		}
		buf[strcspn(buf, "#")] = '\0';
		line = text_trim(buf);
		if (!*line) {
			continue;
		}
		r = *line == '[' ? parse_header(p, line) : parse_key(p, line);
		if (r) {
			return r;
		}
	}
	if (p->sec == SEC_NONE) {
		snprintf(p->err, p->errsize, "%s: [case]: missing (empty "
			 "file)", p->path);
		return -EINVAL;
	}
	return finish_section(p);
}

static int check_segment(struct parser *p, int id)
{
	const struct anatomy_segment *seg = &p->a->seg[id];
	double arc = 0;

	for (int b = 0; b < seg->bends; b++) {
		arc += seg->bend[b].angle_rad * seg->bend[b].radius_m;
		if (seg->bend[b].radius_m <
		    BEND_MARGIN * seg->diameter_m / 2) {
			return fail(p, p->bend_line[id][b], "bend", "radius "
				    "%g m is below the lumen radius %g m: the "
				    "wall would fold inside the bend",
				    seg->bend[b].radius_m, seg->diameter_m / 2);
		}
	}
	if (arc > seg->length_m) {
		return fail(p, p->length_line[id], "length_m", "%g m is "
			    "shorter than the bends' arcs (%g m)",
			    seg->length_m, arc);
	}
	if (seg->mobile && (id == 0 || id == ANATOMY_SEGMENTS - 1 ||
			    p->a->seg[id - 1].mobile)) {
		return fail(p, p->mobile_line[id], "mobile", "not allowed on "
			    "the first or last segment or beside another "
			    "mobile segment");
	}
	return 0;
}

static int check_polyp(struct parser *p, int i)
{
	const struct anatomy_polyp *po = &p->a->polyp[i];
	double len = anatomy_length(p->a);
	int id = 0;

	if (po->s_m <= 0 || po->s_m >= len) {
		return fail(p, p->polyp_line[i], "[polyp]", "s_m %g m is not "
			    "inside the colon (0, %g) m", po->s_m, len);
	}
	while (id < ANATOMY_SEGMENTS - 1 &&
	       po->s_m >= anatomy_segment_start(p->a, id + 1)) {
		id++;
	}
	if (po->diameter_m >= p->a->seg[id].diameter_m / 2) {
		return fail(p, p->polyp_line[i], "[polyp]", "diameter_m %g m "
			    "is too large for the %s lumen (%g m)",
			    po->diameter_m, segment_names[id],
			    p->a->seg[id].diameter_m);
	}
	return 0;
}

static int check(struct parser *p)
{
	int r;

	if (p->segments < ANATOMY_SEGMENTS) {
		return fail(p, p->line, "[segment]", "[segment %s] is missing",
			    segment_names[p->segments]);
	}
	for (int id = 0; id < ANATOMY_SEGMENTS; id++) {
		struct anatomy_segment *seg = &p->a->seg[id];

		if (!p->seg_set_taenia[id]) {
			seg->taenia_depth = p->taenia_depth;
		}
		if (!p->seg_set_fold[id]) {
			seg->fold_depth = p->fold_depth;
		}
		r = check_segment(p, id);
		if (r) {
			return r;
		}
	}
	for (int i = 0; i < p->a->polyps; i++) {
		r = check_polyp(p, i);
		if (r) {
			return r;
		}
	}
	return 0;
}

/* Reads the open stream F (the file PATH) into A. */
static int load_stream(struct anatomy *a, FILE *f, const char *path,
		       char *err, size_t errsize)
{
	struct parser *p = calloc(1, sizeof(*p));
	int r;

	if (!p) {
		snprintf(err, errsize, "%s: out of memory", path);
		return -ENOMEM;
	}
	memset(a, 0, sizeof(*a));
	a->fold_spacing_m = 0.03;
	a->fold_width_m = 0.005;
	*p = (struct parser){ .a = a, .path = path, .err = err,
			      .errsize = errsize, .taenia_depth = 0.10,
			      .fold_depth = 0.15 };
	r = parse_stream(p, f);
	if (!r) {
		r = check(p);
	}
	free(p);
	return r;
}

static int cannot_open(const char *path, char *err, size_t errsize)
{
	int r = -errno;

	snprintf(err, errsize, "%s: cannot open: %s", path, strerror(-r));
	return r;
}

int anatomy_load(struct anatomy *a, const char *path, char *err,
		 size_t errsize)
{
	FILE *f = fopen(path, "r");
	int r;

	if (!f) {
		return cannot_open(path, err, errsize);
	}
	r = load_stream(a, f, path, err, errsize);
	fclose(f);
	return r;
}

int anatomy_parse(struct anatomy *a, const char *text, const char *name,
		  char *err, size_t errsize)
{
	FILE *f = fmemopen((void *)text, strlen(text), "r");
	int r;

	if (!f) {
		return cannot_open(name, err, errsize);
	}
	r = load_stream(a, f, name, err, errsize);
	fclose(f);
	return r;
}
