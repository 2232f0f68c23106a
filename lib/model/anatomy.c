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

#include "base/parse.h"

#define DEG (M_PI / 180.0)
#define BEND_MARGIN 1.0 /* a bend's radius over the lumen radius, at least */

static const char *const segment_names[ANATOMY_SEGMENTS] = {
	"anal_canal", "rectum", "sigmoid", "descending", "splenic_flexure",
	"transverse", "hepatic_flexure", "ascending", "cecum",
};

static const char *const shape_names[] = { "sessile", "pedunculated",
					   "flat", NULL };
static const char *const paris_names[] = { "Ip", "Is", "IIa", "IIb", NULL };

/* Each Paris class's shape (the viewer draws shapes). */
static const int paris_shape[] = {
	[ANATOMY_PARIS_IP] = ANATOMY_POLYP_PEDUNCULATED,
	[ANATOMY_PARIS_IS] = ANATOMY_POLYP_SESSILE,
	[ANATOMY_PARIS_IIA] = ANATOMY_POLYP_FLAT,
	[ANATOMY_PARIS_IIB] = ANATOMY_POLYP_FLAT,
};

/* A shape's class when the file names none. */
static const int shape_paris[] = {
	[ANATOMY_POLYP_SESSILE] = ANATOMY_PARIS_IS,
	[ANATOMY_POLYP_PEDUNCULATED] = ANATOMY_PARIS_IP,
	[ANATOMY_POLYP_FLAT] = ANATOMY_PARIS_IIA,
};

/* The lines a polyp's keys were set on (0: not set), for its checks. */
struct polyp_lines {
	int section, shape, paris, stalk;
};

/* The state of one case file being read (parse_file_user()): the anatomy
 * as it grows, and the lines its checks name. */
struct reader {
	struct anatomy a;
	const char *path;
	char *err;
	size_t errsize;
	double taenia_depth, fold_depth; /* [lumen]'s, for segments without */
	bool seen_case, seen_lumen;
	bool in_segment, in_polyp;       /* the current section's kind */
	int segments;                    /* [segment] sections read */
	int lines;                       /* in the file */
	int bend_line[ANATOMY_SEGMENTS][ANATOMY_MAX_BENDS];
	int length_line[ANATOMY_SEGMENTS];
	int mobile_line[ANATOMY_SEGMENTS];
	int collapsed_line[ANATOMY_SEGMENTS], max_line[ANATOMY_SEGMENTS];
	int fluid_line[ANATOMY_SEGMENTS];
	bool seg_set_taenia[ANATOMY_SEGMENTS], seg_set_fold[ANATOMY_SEGMENTS];
	struct polyp_lines polyp_line[ANATOMY_MAX_POLYPS];
	int site_line[ANATOMY_MAX_SITES];
};

static int fail(struct reader *r, int line, const char *what, const char *fmt,
		...) __attribute__((format(printf, 4, 5)));

/* "FILE:LINE: WHAT: message"; always returns -EINVAL. */
static int fail(struct reader *r, int line, const char *what, const char *fmt,
		...)
{
	va_list ap;

	va_start(ap, fmt);
	parse_verror(r->err, r->errsize, r->path, line, what, fmt, ap);
	va_end(ap);
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

const char *anatomy_paris_name(int paris)
{
	return paris >= 0 && paris < 4 ? paris_names[paris] : "?";
}

double anatomy_segment_start(const struct anatomy *a, int id)
{
	double s = 0;

	for (int k = 0; k < id && k < ANATOMY_SEGMENTS; k++) {
		s += a->seg[k].length_m;
	}
	return s;
}

int anatomy_site_find(const struct anatomy *a, const char *name)
{
	for (int i = 0; i < a->sites; i++) {
		if (!strcmp(a->site[i].name, name)) {
			return i;
		}
	}
	return -1;
}

double anatomy_length(const struct anatomy *a)
{
	return anatomy_segment_start(a, ANATOMY_SEGMENTS);
}

/* ------------------------------------------------- the keys' own types */

/* A name: [A-Za-z0-9_-]+ in the key's size. */
static int name_parse(const struct parse_key *k, const char *text,
		      void *field, struct parse_file *pf, char *why,
		      size_t size)
{
	(void)pf;
	if (strlen(text) >= k->size) {
		snprintf(why, size, "longer than %zu characters", k->size - 1);
		return -EINVAL;
	}
	for (const char *c = text; *c; c++) {
		if (!isalnum((unsigned char)*c) && *c != '-' && *c != '_') {
			snprintf(why, size, "'%s': use letters, digits, '-' "
				 "and '_'", text);
			return -EINVAL;
		}
	}
	if (!*text) {
		snprintf(why, size, "empty");
		return -EINVAL;
	}
	strcpy(field, text);
	return 0;
}

/* Degrees in the file, radians in the struct. */
static int deg_parse(const struct parse_key *k, const char *text, void *field,
		     struct parse_file *pf, char *why, size_t size)
{
	double deg;

	(void)pf;
	if (parse_number(text, k->min, k->max, k->unit, &deg, why, size)) {
		return -EINVAL;
	}
	*(double *)field = deg * DEG;
	return 0;
}

/* yes or no, into a bool. */
static int bool_parse(const struct parse_key *k, const char *text,
		      void *field, struct parse_file *pf, char *why,
		      size_t size)
{
	(void)k;
	(void)pf;
	if (strcmp(text, "yes") && strcmp(text, "no")) {
		snprintf(why, size, "'%s' is not a known choice", text);
		return -EINVAL;
	}
	*(bool *)field = !strcmp(text, "yes");
	return 0;
}

/* ANGLE_DEG RADIUS_M PLANE_DEG: the segment's next bend. */
static int bend_parse(const struct parse_key *k, const char *text,
		      void *field, struct parse_file *pf, char *why,
		      size_t size)
{
	struct reader *r = parse_file_user(pf);
	struct anatomy_segment *seg = field;
	char copy[PARSE_MAX_LINE + 1], *tok[4], *save = NULL;
	double v[3];
	int n = 0;

	(void)k;
	snprintf(copy, sizeof(copy), "%s", text);
	for (char *t = strtok_r(copy, " \t", &save); t && n < 4;
	     t = strtok_r(NULL, " \t", &save)) {
		tok[n++] = t;
	}
	if (n != 3 || parse_double(tok[0], &v[0]) ||
	    parse_double(tok[1], &v[1]) || parse_double(tok[2], &v[2])) {
		snprintf(why, size, "expected ANGLE_DEG RADIUS_M PLANE_DEG");
		return -EINVAL;
	}
	if (v[0] <= 0 || v[0] > 180 || v[1] <= 0 || v[1] > 2 ||
	    fabs(v[2]) > 360) {
		snprintf(why, size, "angle must be in (0, 180] deg, radius in "
			 "(0, 2] m, plane in [-360, 360] deg");
		return -EINVAL;
	}
	if (seg->bends == ANATOMY_MAX_BENDS) {
		snprintf(why, size, "more than %d bends", ANATOMY_MAX_BENDS);
		return -EINVAL;
	}
	seg->bend[seg->bends] = (struct anatomy_bend){
		.angle_rad = v[0] * DEG, .radius_m = v[1],
		.plane_rad = v[2] * DEG,
	};
	r->bend_line[r->segments - 1][seg->bends++] = parse_file_line(pf);
	return 0;
}

/* "X Y Z": three numbers into a double[3] (position_m, direction). */
static int vec_parse(const struct parse_key *k, const char *text,
		     void *field, struct parse_file *pf, char *why,
		     size_t size)
{
	char copy[PARSE_MAX_LINE + 1], *tok[4], *save = NULL;
	double out[3];
	int n = 0;

	(void)pf;
	snprintf(copy, sizeof(copy), "%s", text);
	for (char *t = strtok_r(copy, " \t", &save); t && n < 4;
	     t = strtok_r(NULL, " \t", &save)) {
		tok[n++] = t;
	}
	if (n != 3) {
		snprintf(why, size, "'%s' is not three numbers X Y Z", text);
		return -EINVAL;
	}
	for (int i = 0; i < 3; i++) {
		if (parse_number(tok[i], k->min, k->max, k->unit, &out[i], why,
				 size)) {
			return -EINVAL;
		}
	}
	memcpy(field, out, sizeof(out));
	return 0;
}

static const struct parse_ops name_ops = { name_parse, NULL };
static const struct parse_ops vec_ops = { vec_parse, NULL };
static const struct parse_ops deg_ops = { deg_parse, NULL };
static const struct parse_ops bool_ops = { bool_parse, NULL };
static const struct parse_ops bend_ops = { bend_parse, NULL };

/* ------------------------------------------------------------ the keys */

#define R(f) offsetof(struct reader, f) /* [case], [lumen] */
#define S(f) offsetof(struct anatomy_segment, f)
#define P(f) offsetof(struct anatomy_polyp, f)
#define T(f) offsetof(struct anatomy_site, f)
#define NUM(sec, key, off, lo, hi, fl) \
	{ .section = sec, .name = key, .type = PARSE_DOUBLE, .offset = off, \
	  .min = lo, .max = hi, .unit = "", .flags = fl }
#define DEG_KEY(sec, key, off, fl) \
	{ .section = sec, .name = key, .type = PARSE_CUSTOM, .offset = off, \
	  .ops = &deg_ops, .min = -360, .max = 360, .unit = "", .flags = fl }
#define REQ PARSE_REQUIRED

static const struct parse_key keys[] = {
	{ .section = "case", .name = "name", .type = PARSE_CUSTOM,
	  .offset = R(a.name), .size = ANATOMY_NAME, .ops = &name_ops,
	  .unit = "", .flags = REQ },
	{ .section = "case", .name = "description", .type = PARSE_STRING,
	  .offset = R(a.description), .size = ANATOMY_TEXT, .unit = "" },
	DEG_KEY("lumen", "taenia_angle_deg", R(a.taenia_angle_rad), 0),
	NUM("lumen", "taenia_depth", R(taenia_depth), 0, 0.4, 0),
	NUM("lumen", "fold_depth", R(fold_depth), 0, 0.5, 0),
	NUM("lumen", "fold_spacing_m", R(a.fold_spacing_m), 0.005, 0.2, 0),
	NUM("lumen", "fold_width_m", R(a.fold_width_m), 0.001, 0.05, 0),
	NUM("segment", "length_m", S(length_m), 0.01, 2.0, REQ),
	NUM("segment", "diameter_m", S(diameter_m), 0.01, 0.12, REQ),
	NUM("segment", "taenia_depth", S(taenia_depth), 0, 0.4, 0),
	NUM("segment", "fold_depth", S(fold_depth), 0, 0.5, 0),
	{ .section = "segment", .name = "mobile", .type = PARSE_CUSTOM,
	  .offset = S(mobile), .ops = &bool_ops, .unit = "" },
	NUM("segment", "mesentery_n_per_m", S(mesentery_n_per_m), 1, 1e5, 0),
	NUM("segment", "mesentery_height_m", S(mesentery_height_m), 0.005,
	    0.2, 0),
	NUM("segment", "wall_collapsed", S(wall_collapsed), 0.1, 1, 0),
	NUM("segment", "wall_max", S(wall_max), 1, 2, 0),
	NUM("segment", "wall_nominal_pa", S(wall_nominal_pa), 200, 10000, 0),
	NUM("segment", "wall_beta", S(wall_beta), 0.3, 5, 0),
	NUM("segment", "fluid_m3", S(fluid_m3), 0, 0.002, 0),
	{ .section = "segment", .name = "bend", .type = PARSE_CUSTOM,
	  .offset = 0, .ops = &bend_ops, .unit = "",
	  .flags = PARSE_REPEATS },
	NUM("polyp", "s_m", P(s_m), 0, 3, REQ),
	DEG_KEY("polyp", "angle_deg", P(angle_rad), REQ),
	NUM("polyp", "diameter_m", P(diameter_m), 0.001, 0.06, REQ),
	{ .section = "polyp", .name = "shape", .type = PARSE_CHOICE,
	  .offset = P(shape), .choices = shape_names, .unit = "" },
	{ .section = "polyp", .name = "paris", .type = PARSE_CHOICE,
	  .offset = P(paris), .choices = paris_names, .unit = "" },
	NUM("polyp", "stalk_length_m", P(stalk_length_m), 0.001, 0.04, 0),
	NUM("polyp", "stalk_diameter_m", P(stalk_diameter_m), 0.001, 0.02,
	    0),
	{ .section = "site", .name = "position_m", .type = PARSE_CUSTOM,
	  .offset = T(position_m), .ops = &vec_ops, .min = -1, .max = 1,
	  .unit = "m", .flags = REQ },
	{ .section = "site", .name = "direction", .type = PARSE_CUSTOM,
	  .offset = T(direction), .ops = &vec_ops, .min = -1, .max = 1,
	  .unit = "" },
	NUM("site", "radius_m", T(radius_m), 0.01, 0.2, 0),
};

/* ------------------------------------------------------- the sections */

static int open_segment(struct reader *r, const char *name, void **base,
			char *why, size_t size)
{
	struct anatomy_segment *seg;

	if (r->segments == ANATOMY_SEGMENTS) {
		snprintf(why, size, "all %d segments are already there",
			 ANATOMY_SEGMENTS);
		return -EINVAL;
	}
	if (strcmp(name, segment_names[r->segments])) {
		snprintf(why, size, "expected [segment %s] next (segments run "
			 "from the anal verge in order: anal_canal ... cecum)",
			 segment_names[r->segments]);
		return -EINVAL;
	}
	seg = &r->a.seg[r->segments++];
	seg->mesentery_n_per_m = 150;
	seg->mesentery_height_m = 0.06;
	seg->wall_collapsed = ANATOMY_DEFAULT_WALL_COLLAPSED;
	seg->wall_max = ANATOMY_DEFAULT_WALL_MAX;
	seg->wall_nominal_pa = ANATOMY_DEFAULT_WALL_NOMINAL_PA;
	seg->wall_beta = ANATOMY_DEFAULT_WALL_BETA;
	r->in_segment = true;
	*base = seg;
	return 0;
}

static int open_polyp(struct reader *r, int line, void **base, char *why,
		      size_t size)
{
	if (r->a.polyps == ANATOMY_MAX_POLYPS) {
		snprintf(why, size, "more than %d polyps", ANATOMY_MAX_POLYPS);
		return -EINVAL;
	}
	r->polyp_line[r->a.polyps].section = line;
	r->in_polyp = true;
	*base = &r->a.polyp[r->a.polyps++];
	return 0;
}

/* A site's name: as a case's. */
static const struct parse_key site_name = { .size = ANATOMY_NAME };

static int open_site(struct reader *r, const char *name, int line,
		     void **base, char *why, size_t size)
{
	struct anatomy_site *t;

	if (r->a.sites == ANATOMY_MAX_SITES) {
		snprintf(why, size, "more than %d sites", ANATOMY_MAX_SITES);
		return -EINVAL;
	}
	t = &r->a.site[r->a.sites];
	if (name_parse(&site_name, name, t->name, NULL, why, size)) {
		return -EINVAL;
	}
	if (anatomy_site_find(&r->a, name) >= 0) {
		snprintf(why, size, "[site %s] appears twice", name);
		return -EINVAL;
	}
	r->site_line[r->a.sites++] = line;
	t->direction[1] = 1;
	t->radius_m = ANATOMY_DEFAULT_SITE_RADIUS_M;
	*base = t;
	return 0;
}

/* "[case]", "[lumen]", "[segment NAME]", "[site NAME]" or "[polyp]"
 * begins. */
static int begin(struct parse_file *pf, const char *kind, const char *arg,
		 void **base, char *why, size_t size)
{
	struct reader *r = parse_file_user(pf);
	bool is_case = !strcmp(kind, "case"), is_lumen = !strcmp(kind, "lumen");

	r->in_segment = false;
	r->in_polyp = false;
	if (!r->seen_case && !is_case) {
		snprintf(why, size, "the file must start with [case]");
		return -EINVAL;
	}
	if (!strcmp(kind, "segment") && arg) {
		return open_segment(r, arg, base, why, size);
	}
	if (!strcmp(kind, "site") && arg) {
		return open_site(r, arg, parse_file_line(pf), base, why, size);
	}
	if (arg) {
		snprintf(why, size, "unknown section");
		return -EINVAL;
	}
	if (!strcmp(kind, "polyp")) {
		return open_polyp(r, parse_file_line(pf), base, why, size);
	}
	if ((is_case && !r->seen_case) || (is_lumen && !r->seen_lumen)) {
		r->seen_case = true;
		r->seen_lumen |= is_lumen;
		*base = r;
		return 0;
	}
	snprintf(why, size, "%s", is_case || is_lumen ? "appears twice" :
		 "unknown section (case, lumen, segment NAME, site NAME, "
		 "polyp)");
	return -EINVAL;
}

static const struct parse_table table;

/* The line SECTION's key NAME was set on (SET_ON: the kit's), 0 if not. */
static int key_line(const int *set_on, const char *section, const char *name)
{
	return set_on[parse_find(&table, section, name) - keys];
}

static int segment_line(const int *set_on, const char *name)
{
	return key_line(set_on, "segment", name);
}

/* A polyp's lines: its shape's, its class's, its stalk's (either key). */
static void polyp_end(struct reader *r, const int *set_on)
{
	struct polyp_lines *l = &r->polyp_line[r->a.polyps - 1];
	int length = key_line(set_on, "polyp", "stalk_length_m");

	l->shape = key_line(set_on, "polyp", "shape");
	l->paris = key_line(set_on, "polyp", "paris");
	l->stalk = length ? length :
		   key_line(set_on, "polyp", "stalk_diameter_m");
}

/* A section ends: a segment's lines for the checks after the file. */
static void end(struct parse_file *pf, const int *set_on)
{
	struct reader *r = parse_file_user(pf);
	int id = r->segments - 1;

	r->lines = parse_file_line(pf);
	if (r->in_polyp) {
		polyp_end(r, set_on);
	}
	if (!r->in_segment) {
		return;
	}
	r->length_line[id] = segment_line(set_on, "length_m");
	r->mobile_line[id] = segment_line(set_on, "mobile");
	r->collapsed_line[id] = segment_line(set_on, "wall_collapsed");
	r->max_line[id] = segment_line(set_on, "wall_max");
	r->fluid_line[id] = segment_line(set_on, "fluid_m3");
	r->seg_set_taenia[id] = segment_line(set_on, "taenia_depth") != 0;
	r->seg_set_fold[id] = segment_line(set_on, "fold_depth") != 0;
}

static const struct parse_table table = {
	.keys = keys,
	.n = sizeof(keys) / sizeof(keys[0]),
	.flags = PARSE_HASH_COMMENTS | PARSE_KIND_ARG | PARSE_PER_SECTION,
	.begin = begin,
	.end = end,
};

/* ------------------------------------------------- after the file */

/* The wall's law (gas.h) reaches the case's radius at its nominal
 * pressure only from a narrower collapsed lumen towards a wider one; the
 * fluid leaves the lumen half open at least. */
static int check_wall(struct reader *r, int id)
{
	const struct anatomy_segment *seg = &r->a.seg[id];
	double lumen = M_PI * seg->diameter_m * seg->diameter_m / 4 *
		       seg->length_m;

	if (seg->wall_collapsed >= 1) {
		return fail(r, r->collapsed_line[id], "wall_collapsed", "%g: "
			    "the collapsed lumen must be narrower than the "
			    "case's (below 1)", seg->wall_collapsed);
	}
	if (seg->wall_max <= 1) {
		return fail(r, r->max_line[id], "wall_max", "%g: the wall must "
			    "stiffen towards a lumen wider than the case's "
			    "(above 1)", seg->wall_max);
	}
	if (seg->fluid_m3 > lumen / 2) {
		return fail(r, r->fluid_line[id], "fluid_m3", "%g m^3 is more "
			    "than half the %s's lumen (%g m^3)", seg->fluid_m3,
			    segment_names[id], lumen);
	}
	return 0;
}

static int check_segment(struct reader *r, int id)
{
	const struct anatomy_segment *seg = &r->a.seg[id];
	double arc = 0;

	for (int b = 0; b < seg->bends; b++) {
		arc += seg->bend[b].angle_rad * seg->bend[b].radius_m;
		if (seg->bend[b].radius_m <
		    BEND_MARGIN * seg->diameter_m / 2) {
			return fail(r, r->bend_line[id][b], "bend", "radius "
				    "%g m is below the lumen radius %g m: the "
				    "wall would fold inside the bend",
				    seg->bend[b].radius_m, seg->diameter_m / 2);
		}
	}
	if (arc > seg->length_m) {
		return fail(r, r->length_line[id], "length_m", "%g m is "
			    "shorter than the bends' arcs (%g m)",
			    seg->length_m, arc);
	}
	if (seg->mobile && (id == 0 || id == ANATOMY_SEGMENTS - 1 ||
			    r->a.seg[id - 1].mobile)) {
		return fail(r, r->mobile_line[id], "mobile", "not allowed on "
			    "the first or last segment or beside another "
			    "mobile segment");
	}
	return check_wall(r, id);
}

/* A polyp's shape and class made to agree, its stalk given its
 * defaults (anatomy.h). */
static int check_morphology(struct reader *r, int i)
{
	struct anatomy_polyp *po = &r->a.polyp[i];
	const struct polyp_lines *l = &r->polyp_line[i];

	if (!l->paris) {
		po->paris = shape_paris[po->shape];
	} else if (l->shape && paris_shape[po->paris] != po->shape) {
		return fail(r, l->paris, "paris", "%s is not a %s polyp (shape "
			    "on line %d)", paris_names[po->paris],
			    shape_names[po->shape], l->shape);
	}
	po->shape = paris_shape[po->paris];
	if (po->paris != ANATOMY_PARIS_IP) {
		return l->stalk ? fail(r, l->stalk, "[polyp]", "only a "
				       "pedunculated (Ip) polyp has a stalk") :
				  0;
	}
	if (po->stalk_length_m == 0) {
		po->stalk_length_m = ANATOMY_DEFAULT_STALK_LENGTH *
				     po->diameter_m;
	}
	if (po->stalk_diameter_m == 0) {
		po->stalk_diameter_m = ANATOMY_DEFAULT_STALK_DIAMETER *
				       po->diameter_m;
	}
	if (po->stalk_diameter_m >= po->diameter_m) {
		return fail(r, l->stalk ? l->stalk : l->section,
			    "stalk_diameter_m", "%g m is not "
			    "thinner than the head (%g m)",
			    po->stalk_diameter_m, po->diameter_m);
	}
	return 0;
}

static int check_polyp(struct reader *r, int i)
{
	const struct anatomy_polyp *po = &r->a.polyp[i];
	double len = anatomy_length(&r->a);
	int id = 0;

	if (po->s_m <= 0 || po->s_m >= len) {
		return fail(r, r->polyp_line[i].section, "[polyp]", "s_m %g m "
			    "is not inside the colon (0, %g) m", po->s_m, len);
	}
	while (id < ANATOMY_SEGMENTS - 1 &&
	       po->s_m >= anatomy_segment_start(&r->a, id + 1)) {
		id++;
	}
	if (po->diameter_m >= r->a.seg[id].diameter_m / 2) {
		return fail(r, r->polyp_line[i].section, "[polyp]", "diameter_m "
			    "%g m is too large for the %s lumen (%g m)",
			    po->diameter_m, segment_names[id],
			    r->a.seg[id].diameter_m);
	}
	return check_morphology(r, i);
}

/* A site's direction made a unit vector (it must have one). */
static int check_site(struct reader *r, int i)
{
	struct anatomy_site *t = &r->a.site[i];
	double n = sqrt(t->direction[0] * t->direction[0] +
			t->direction[1] * t->direction[1] +
			t->direction[2] * t->direction[2]);

	if (!(n > 1e-6)) {
		return fail(r, r->site_line[i], "direction", "[site %s]: no "
			    "direction", t->name);
	}
	for (int d = 0; d < 3; d++) {
		t->direction[d] /= n;
	}
	return 0;
}

static int check(struct reader *r)
{
	int e;

	if (r->segments < ANATOMY_SEGMENTS) {
		return fail(r, r->lines, "[segment]", "[segment %s] is missing",
			    segment_names[r->segments]);
	}
	for (int id = 0; id < ANATOMY_SEGMENTS; id++) {
		struct anatomy_segment *seg = &r->a.seg[id];

		if (!r->seg_set_taenia[id]) {
			seg->taenia_depth = r->taenia_depth;
		}
		if (!r->seg_set_fold[id]) {
			seg->fold_depth = r->fold_depth;
		}
		e = check_segment(r, id);
		if (e) {
			return e;
		}
	}
	for (int i = 0; i < r->a.polyps; i++) {
		e = check_polyp(r, i);
		if (e) {
			return e;
		}
	}
	for (int i = 0; i < r->a.sites; i++) {
		e = check_site(r, i);
		if (e) {
			return e;
		}
	}
	return 0;
}

/* Reads the open stream F (the file PATH) into A. */
static int load_stream(struct anatomy *a, FILE *f, const char *path,
		       char *err, size_t errsize)
{
	struct reader *r = calloc(1, sizeof(*r));
	int n;

	if (!r) {
		snprintf(err, errsize, "%s: out of memory", path);
		return -ENOMEM;
	}
	*r = (struct reader){ .path = path, .err = err, .errsize = errsize,
			      .taenia_depth = 0.10, .fold_depth = 0.15 };
	r->a.fold_spacing_m = 0.03;
	r->a.fold_width_m = 0.005;
	n = parse_ini(&table, f, path, r, r, err, errsize);
	if (n >= 0 && !r->seen_case) {
		snprintf(err, errsize, "%s: [case]: missing (empty file)",
			 path);
		n = -EINVAL;
	}
	n = n < 0 ? n : check(r);
	if (n >= 0) {
		*a = r->a;
	}
	free(r);
	return n;
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
