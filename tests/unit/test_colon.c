/*
 * test_colon.c - the colon model against geometry: case files, the
 * centreline's length, frames and turning angle, the mesh's closure,
 * normals and folds, segments, deformation, OBJ import and export.
 *
 * Case files are read from $ENDOSIM_CASES (default config/cases: run from
 * the source tree); scratch files go to $TMPDIR.
 */
#include <dirent.h>
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "model/anatomy.h"
#include "model/centreline.h"
#include "model/colon.h"
#include "geom_assert.h"
#include "model/mesh.h"
#include "model/objio.h"
#include "model/rod.h"
#include "base/vec3.h"

static const char *cases_dir(void)
{
	const char *d = getenv("ENDOSIM_CASES");

	return d && *d ? d : "config/cases";
}

static void case_path(const char *name, char *out, size_t size)
{
	snprintf(out, size, "%s/%s.case", cases_dir(), name);
}

static struct colon *build(const char *name, double step, uint32_t ring)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	struct anatomy a;
	struct colon *c;
	char path[512], err[256];

	case_path(name, path, sizeof(path));
	if (anatomy_load(&a, path, err, sizeof(err))) {
		print_error("%s\n", err);
		fail();
	}
	p.step_m = step;
	p.ring_vertices = ring;
	c = colon_create(&a, &p, err, sizeof(err));
	if (!c) {
		print_error("%s\n", err);
		fail();
	}
	return c;
}

/* A scratch file with TEXT; its path in OUT. */
static void scratch(const char *tag, const char *text, char *out, size_t size)
{
	const char *tmp = getenv("TMPDIR");
	FILE *f;

	snprintf(out, size, "%s/endosim-test-%d-%s", tmp && *tmp ? tmp : "/tmp",
		 (int)getpid(), tag);
	f = fopen(out, "w");
	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

/* ERR starts "FILE:LINE: " ("FILE: " when LINE is 0) and says WORDS. */
static void assert_error_at(const char *err, const char *file, int line,
			    const char *words)
{
	char want[600];

	if (line) {
		snprintf(want, sizeof(want), "%s:%d: ", file, line);
	} else {
		snprintf(want, sizeof(want), "%s: ", file);
	}
	if (strncmp(err, want, strlen(want)) || !strstr(err, words)) {
		print_error("got '%s', want '%s' ... '%s'\n", err, want, words);
		fail();
	}
}

/* ---------------------------------------------------------------- cases */

static void test_every_case_loads(void **state)
{
	const char *want[] = { "normal", "redundant-sigmoid", "tight-flexures",
			       "polyps" };
	DIR *dir = opendir(cases_dir());
	struct dirent *e;
	int found = 0, wanted = 0;

	(void)state;
	assert_non_null(dir);
	while ((e = readdir(dir))) {
		size_t len = strlen(e->d_name);
		char path[512], err[256];
		struct anatomy a;

		if (len < 6 || strcmp(e->d_name + len - 5, ".case")) {
			continue;
		}
		snprintf(path, sizeof(path), "%s/%s", cases_dir(), e->d_name);
		if (anatomy_load(&a, path, err, sizeof(err))) {
			print_error("%s\n", err);
			fail();
		}
		/* the file is named after its case */
		assert_int_equal(strlen(a.name), len - 5);
		assert_memory_equal(a.name, e->d_name, len - 5);
		for (size_t i = 0; i < 4; i++) {
			wanted += !strcmp(a.name, want[i]);
		}
		found++;
	}
	closedir(dir);
	assert_true(found >= 4);
	assert_int_equal(wanted, 4);
}

static void test_normal_matches_brief(void **state)
{
	char path[512], err[256];
	struct anatomy a;

	(void)state;
	case_path("normal", path, sizeof(path));
	assert_int_equal(anatomy_load(&a, path, err, sizeof(err)), 0);
	assert_near(anatomy_length(&a), 1.5, 0.1);
	assert_near(a.seg[ANATOMY_RECTUM].length_m, 0.12, 0.01);
	assert_true(a.seg[ANATOMY_SIGMOID].mobile);
	assert_true(a.seg[ANATOMY_TRANSVERSE].mobile);
	assert_false(a.seg[ANATOMY_DESCENDING].mobile);
	assert_true(a.seg[ANATOMY_TRANSVERSE].length_m > 0.45 - 1e-9);
	assert_true(a.seg[ANATOMY_CECUM].diameter_m >
		    a.seg[ANATOMY_TRANSVERSE].diameter_m);
	case_path("polyps", path, sizeof(path));
	assert_int_equal(anatomy_load(&a, path, err, sizeof(err)), 0);
	assert_true(a.polyps >= 3);
}

/*
 * Every case can be finished: its cecum within the insertion tube's
 * reach. The model's colon does not shorten (a real sigmoid pleats onto a
 * straightened scope), so the tube needs the centreline's length to the
 * cecum and slack for the loops it cannot avoid: REACH_SLACK_M, what the
 * normal case's scripted expert has in beyond her tip there (1.60 m of
 * tube with the tip 1.50 m along; test_separation).
 */
#define REACH_SLACK_M 0.10

static void test_cecum_within_reach(void **state)
{
	const char *names[] = { "normal", "redundant-sigmoid",
				"tight-flexures", "polyps" };

	(void)state;
	for (size_t k = 0; k < 4; k++) {
		char path[512], err[256];
		struct anatomy a;

		case_path(names[k], path, sizeof(path));
		assert_int_equal(anatomy_load(&a, path, err, sizeof(err)), 0);
		if (anatomy_segment_start(&a, ANATOMY_CECUM) >
		    ROD_DEFAULT_LENGTH_M - REACH_SLACK_M) {
			fail_msg("%s: the cecum %.2f m in, beyond a %.1f m "
				 "tube's reach", names[k],
				 anatomy_segment_start(&a, ANATOMY_CECUM),
				 ROD_DEFAULT_LENGTH_M);
		}
	}
}

/* The redundant sigmoid is what it is for: longer than the normal case's
 * (by 10 cm or more) and held more laxly, its mesentery taller and
 * softer per length of colon (at most 60 %: a loop of a given size pulls
 * less). */
static void test_redundant_sigmoid_long_and_lax(void **state)
{
	char path[512], err[256];
	struct anatomy n, r;
	const struct anatomy_segment *ns, *rs;

	(void)state;
	case_path("normal", path, sizeof(path));
	assert_int_equal(anatomy_load(&n, path, err, sizeof(err)), 0);
	case_path("redundant-sigmoid", path, sizeof(path));
	assert_int_equal(anatomy_load(&r, path, err, sizeof(err)), 0);
	ns = &n.seg[ANATOMY_SIGMOID];
	rs = &r.seg[ANATOMY_SIGMOID];
	assert_true(rs->mobile);
	assert_true(rs->length_m >= ns->length_m + 0.10 - 1e-9);
	assert_true(rs->mesentery_height_m > ns->mesentery_height_m);
	assert_true(rs->mesentery_n_per_m / rs->length_m <=
		    0.6 * ns->mesentery_n_per_m / ns->length_m);
}

struct bad_case {
	const char *text;
	int line;
	const char *words; /* expected in the message after FILE:LINE: */
};

#define SEGS_AFTER_ANAL \
	"[segment rectum]\nlength_m = 0.12\ndiameter_m = 0.05\n" \
	"[segment sigmoid]\nlength_m = 0.37\ndiameter_m = 0.045\n" \
	"[segment descending]\nlength_m = 0.15\ndiameter_m = 0.045\n" \
	"[segment splenic_flexure]\nlength_m = 0.07\ndiameter_m = 0.05\n" \
	"[segment transverse]\nlength_m = 0.45\ndiameter_m = 0.055\n" \
	"[segment hepatic_flexure]\nlength_m = 0.06\ndiameter_m = 0.055\n" \
	"[segment ascending]\nlength_m = 0.2\ndiameter_m = 0.06\n" \
	"[segment cecum]\nlength_m = 0.06\ndiameter_m = 0.09\n"

/* Each of BAD refused with its line and words, the anatomy untouched. */
static void refused_with_line(const struct bad_case *bad, size_t n)
{
	for (size_t i = 0; i < n; i++) {
		char path[512], err[512];
		struct anatomy a, before;

		memset(&a, 0x5a, sizeof(a));
		before = a;
		scratch("bad.case", bad[i].text, path, sizeof(path));
		assert_int_equal(anatomy_load(&a, path, err, sizeof(err)),
				 -EINVAL);
		assert_error_at(err, path, bad[i].line, bad[i].words);
		assert_memory_equal(&a, &before, sizeof(a));
		unlink(path);
	}
}

static void test_bad_cases_refused_with_line(void **state)
{
	static const struct bad_case bad[] = {
		{ "[case]\nname = x\n[segment anal_canal]\nlength_m = 0.04\n"
		  "lenght_m = 3\n", 5, "lenght_m: unknown key" },
		{ "[case]\nname = x\n\n[segment anal_canal]\n"
		  "length_m = abc\n", 5, "length_m: 'abc' is not a number" },
		{ "[case]\nname = x\n[segment anal_canal]\nlength_m = 9\n", 4,
		  "out of range" },
		{ "[case]\nname = x\n[segment rectum]\n", 3,
		  "expected [segment anal_canal]" },
		{ "[case]\nname = x\n[segment anal_canal]\nlength_m = 0.04\n"
		  "diameter_m = 0.025\n", 5, "[segment rectum] is missing" },
		{ "[case]\nname = x\n[segment anal_canal]\nlength_m = 0.04\n"
		  "diameter_m = 0.025\nbend = 90 0.01 0\n" SEGS_AFTER_ANAL,
		  6, "below the lumen radius" },
		{ "[case]\nname = x\n[segment anal_canal]\nlength_m = 0.04\n"
		  "diameter_m = 0.025\nbend = 90 0.05 0\n" SEGS_AFTER_ANAL,
		  4, "shorter than the bends" },
		{ "[case]\nname = x\n[segment anal_canal]\nlength_m = 0.04\n"
		  "diameter_m = 0.025\nmobile = yes\n" SEGS_AFTER_ANAL,
		  6, "mobile: not allowed" },
		{ "[case]\nname = x\nname = y\n", 3, "duplicate key" },
		{ "name = x\n", 1, "before any [section]" },
		{ "[lumen]\n", 1, "must start with [case]" },
		{ "[case]\nname = a b\n", 2, "use letters" },
		{ "[case]\nname = x\n[segment anal_canal]\n"
		  "diameter_m = 0.02\n[polyp]\n", 3, "length_m is missing" },
		{ "[case]\n[segment anal_canal]\n", 1, "name is missing" },
		{ "[case]\nname = x\n[segment anal_canal]\nlength_m = 0.04\n"
		  "diameter_m = 0.025\n" SEGS_AFTER_ANAL "[polyp]\ns_m = 2.5\n"
		  "angle_deg = 0\ndiameter_m = 0.005\n", 30,
		  "not inside the colon" },
		{ "[case]\nname = x\n[segment anal_canal]\n"
		  "bend = 10 0.1\n", 4, "expected ANGLE_DEG RADIUS_M" },
		{ "", 0, "missing (empty file)" },
	};
	(void)state;
	refused_with_line(bad, sizeof(bad) / sizeof(bad[0]));
}

/* The patient's keys (issue 22): each wall law's, the fluid's, the
 * assistant's sites'. */
#define SEG_ANAL(extra) \
	"[case]\nname = x\n[segment anal_canal]\nlength_m = 0.04\n" \
	"diameter_m = 0.025\n" extra
#define WHOLE(extra) SEG_ANAL(extra) SEGS_AFTER_ANAL
#define SITE(keys) WHOLE("") "[site llq]\n" keys

static void test_bad_patient_keys_refused_with_line(void **state)
{
	static const struct bad_case bad[] = {
		{ SEG_ANAL("wall_collapsed = 0.05\n"), 6,
		  "wall_collapsed: 0.05 is out of range [0.1, 1]" },
		{ SEG_ANAL("wall_collapsed = 0.5x\n"), 6,
		  "wall_collapsed: '0.5x' is not a number" },
		{ WHOLE("wall_collapsed = 1\n"), 6,
		  "wall_collapsed: 1: the collapsed lumen must be narrower" },
		{ SEG_ANAL("wall_max = 2.5\n"), 6,
		  "wall_max: 2.5 is out of range [1, 2]" },
		{ WHOLE("wall_collapsed = 0.5\nwall_max = 1\n"), 7,
		  "wall_max: 1: the wall must stiffen towards a lumen wider" },
		{ SEG_ANAL("wall_nominal_pa = 50\n"), 6,
		  "wall_nominal_pa: 50 is out of range [200, 10000]" },
		{ SEG_ANAL("wall_nominal_pa = 2 kPa\n"), 6,
		  "wall_nominal_pa: '2 kPa' is not a number" },
		{ SEG_ANAL("wall_beta = 0\n"), 6,
		  "wall_beta: 0 is out of range [0.3, 5]" },
		{ SEG_ANAL("wall_beta = nan\n"), 6,
		  "wall_beta: 'nan' is not a number" },
		{ SEG_ANAL("fluid_m3 = -0.001\n"), 6,
		  "fluid_m3: -0.001 is out of range [0, 0.002]" },
		{ SEG_ANAL("fluid_m3 = inf\n"), 6,
		  "fluid_m3: 'inf' is not a number" },
		{ WHOLE("fluid_m3 = 0.0001\n"), 6, "fluid_m3: 0.0001 m^3 is "
		  "more than half the anal_canal's lumen" },
		{ SITE("position_m = 0.05 -0.2\n"), 31,
		  "position_m: '0.05 -0.2' is not three numbers X Y Z" },
		{ SITE("position_m = 0.05 -0.2 0.2 1\n"), 31,
		  "not three numbers" },
		{ SITE("position_m = 0 0 2\n"), 31,
		  "position_m: 2 is out of range [-1, 1] m" },
		{ SITE("position_m = 0 nan 0\n"), 31,
		  "position_m: 'nan' is not a number" },
		{ SITE("position_m = 0 0 0.2\ndirection = 0 0 0\n"), 30,
		  "direction: [site llq]: no direction" },
		{ SITE("position_m = 0 0 0.2\ndirection = 0 1.5 0\n"), 32,
		  "direction: 1.5 is out of range [-1, 1]" },
		{ SITE("position_m = 0 0 0.2\nradius_m = 0.5\n"), 32,
		  "radius_m: 0.5 is out of range [0.01, 0.2]" },
		{ SITE("radius_m = 0.05\n"), 30, "position_m is missing" },
		{ SITE("position_m = 0 0 0.2\n[site llq]\n"), 32,
		  "[site llq] appears twice" },
		{ WHOLE("") "[site]\nposition_m = 0 0 0.2\n", 30,
		  "unknown section" },
		{ WHOLE("") "[site l/q]\nposition_m = 0 0 0.2\n", 30,
		  "use letters, digits" },
		{ WHOLE("") "[site a]\nposition_m = 0 0 0\n[site b]\n"
		  "position_m = 0 0 0\n[site c]\nposition_m = 0 0 0\n"
		  "[site d]\nposition_m = 0 0 0\n[site e]\n"
		  "position_m = 0 0 0\n[site f]\nposition_m = 0 0 0\n"
		  "[site g]\nposition_m = 0 0 0\n[site h]\n"
		  "position_m = 0 0 0\n[site i]\n", 46, "more than 8 sites" },
	};
	(void)state;
	refused_with_line(bad, sizeof(bad) / sizeof(bad[0]));
}

/* A polyp 62 cm in (the sigmoid), 10 mm across, with KEYS (line 34 on). */
#define POLYP(keys) WHOLE("") "[polyp]\ns_m = 0.62\nangle_deg = 0\n" \
	"diameter_m = 0.01\n" keys

/* Issue 25's morphology: the Paris class and the shape agree whichever
 * the file names; a stalk on Ip only, its defaults the head's fractions;
 * the shipped cases' polyps take their class from their shape. */
static void test_polyp_morphology(void **state)
{
	static const struct {
		const char *keys;
		int shape, paris;
		double stalk_length_m, stalk_diameter_m;
	} good[] = {
		{ "", ANATOMY_POLYP_SESSILE, ANATOMY_PARIS_IS, 0, 0 },
		{ "shape = flat\n", ANATOMY_POLYP_FLAT, ANATOMY_PARIS_IIA, 0, 0 },
		{ "paris = IIb\n", ANATOMY_POLYP_FLAT, ANATOMY_PARIS_IIB, 0, 0 },
		{ "shape = pedunculated\n", ANATOMY_POLYP_PEDUNCULATED,
		  ANATOMY_PARIS_IP, 0.005, 0.0035 },
		{ "paris = Ip\nstalk_length_m = 0.012\n"
		  "stalk_diameter_m = 0.004\n", ANATOMY_POLYP_PEDUNCULATED,
		  ANATOMY_PARIS_IP, 0.012, 0.004 },
		{ "shape = sessile\nparis = Is\n", ANATOMY_POLYP_SESSILE,
		  ANATOMY_PARIS_IS, 0, 0 },
	};
	char path[512], err[512];
	struct anatomy a;

	(void)state;
	for (size_t i = 0; i < sizeof(good) / sizeof(good[0]); i++) {
		char text[4096];

		snprintf(text, sizeof(text), POLYP("%s"), good[i].keys);
		assert_int_equal(anatomy_parse(&a, text, "t.case", err,
					       sizeof(err)), 0);
		assert_int_equal(a.polyp[0].shape, good[i].shape);
		assert_int_equal(a.polyp[0].paris, good[i].paris);
		assert_near(a.polyp[0].stalk_length_m, good[i].stalk_length_m,
			    1e-12);
		assert_near(a.polyp[0].stalk_diameter_m,
			    good[i].stalk_diameter_m, 1e-12);
	}
	case_path("polyps", path, sizeof(path));
	assert_int_equal(anatomy_load(&a, path, err, sizeof(err)), 0);
	assert_int_equal(a.polyp[0].paris, ANATOMY_PARIS_IIA);
	assert_int_equal(a.polyp[1].paris, ANATOMY_PARIS_IS);
	assert_int_equal(a.polyp[3].paris, ANATOMY_PARIS_IP);
	assert_near(a.polyp[3].stalk_diameter_m, 0.35 * 0.015, 1e-12);
	assert_string_equal(anatomy_paris_name(a.polyp[0].paris), "IIa");
}

static void test_bad_polyp_keys_refused_with_line(void **state)
{
	static const struct bad_case bad[] = {
		{ POLYP("paris = III\n"), 34, "paris: 'III' is not a known" },
		{ POLYP("shape = sessile\nparis = Ip\n"), 35,
		  "paris: Ip is not a sessile polyp (shape on line 34)" },
		{ POLYP("paris = IIa\nshape = pedunculated\n"), 34,
		  "paris: IIa is not a pedunculated polyp" },
		{ POLYP("stalk_length_m = 0.01\n"), 34,
		  "only a pedunculated (Ip) polyp has a stalk" },
		{ POLYP("paris = IIb\nstalk_diameter_m = 0.002\n"), 35,
		  "only a pedunculated (Ip) polyp has a stalk" },
		{ POLYP("paris = Ip\nstalk_diameter_m = 0.012\n"), 35,
		  "stalk_diameter_m: 0.012 m is not thinner than the head" },
		{ POLYP("paris = Ip\nstalk_length_m = 0.05\n"), 35,
		  "stalk_length_m: 0.05 is out of range [0.001, 0.04]" },
	};
	(void)state;
	refused_with_line(bad, sizeof(bad) / sizeof(bad[0]));
}

/* ---------------------------------------------------------------- centreline */

static double polyline_length(const struct centreline *cl)
{
	double len = 0;

	for (size_t i = 1; i < centreline_count(cl); i++) {
		len += vec3_dist(centreline_sample(cl, i)->p,
				 centreline_sample(cl, i - 1)->p);
	}
	return len;
}

static void test_length_is_sum_of_segments(void **state)
{
	const char *names[] = { "normal", "redundant-sigmoid",
				"tight-flexures", "polyps" };

	(void)state;
	for (size_t k = 0; k < 4; k++) {
		struct colon *c = build(names[k], 0.002, 16);
		double want = anatomy_length(colon_anatomy(c));
		double got = polyline_length(colon_centreline(c));

		assert_near(got, want, 0.005 * want);
		assert_near(centreline_total_arclength(colon_centreline(c)),
			    got, 1e-9);
		colon_destroy(c);
	}
}

static void assert_orthonormal(const struct centreline_point *c)
{
	double x[3];

	assert_near(vec3_norm(c->t), 1, 1e-9);
	assert_near(vec3_norm(c->u), 1, 1e-9);
	assert_near(vec3_dot(c->t, c->u), 0, 1e-9);
	vec3_cross(x, c->t, c->u);
	assert_vec_near(c->v, x, 1e-9);
}

static void test_frames_orthonormal(void **state)
{
	struct colon *c = build("tight-flexures", 0.002, 16);
	const struct centreline *cl = colon_centreline(c);

	(void)state;
	for (size_t i = 0; i < centreline_count(cl); i++) {
		assert_orthonormal(centreline_sample(cl, i));
	}
	colon_destroy(c);
}

/* A planar S-curve in z = 0: a quarter circle, a straight, another back. */
static double (*planar_curve(size_t *n, double ds))[3]
{
	double (*p)[3] = malloc(2000 * sizeof(*p)), r = 0.1;
	size_t k = 0;

	for (double s = 0; s < M_PI / 2 * r; s += ds, k++) {
		vec3_set(p[k], r * sin(s / r), r * (1 - cos(s / r)), 0);
	}
	for (int i = 0; i < 50; i++, k++) {
		vec3_set(p[k], r, p[k - 1][1] + ds, 0);
	}
	for (double s = ds; s < M_PI / 2 * r; s += ds, k++) {
		double y0 = p[k - 1][1];

		vec3_set(p[k], r + r * (1 - cos(s / r)), y0 + r * sin(s / r) -
			 r * sin((s - ds) / r), 0);
	}
	*n = k;
	return p;
}

static void test_no_twist_on_planar_curve(void **state)
{
	const double z[3] = { 0, 0, 1 };
	size_t n;
	double (*p)[3] = planar_curve(&n, 0.002);
	char err[128];
	struct centreline *cl =
		centreline_create((const double(*)[3])p, n, 0.002, z, err,
				  sizeof(err));

	(void)state;
	assert_non_null(cl);
	for (size_t i = 0; i < n; i++) {
		assert_vec_near(centreline_sample(cl, i)->u, z, 1e-12);
	}
	centreline_destroy(cl);
	free(p);
}

/*
 * On the helix (a cos w, a sin w, b w), with c = |(a, b)|, s = c w and
 * torsion tau = b / c^2, a rotation-minimising frame turns against the
 * Frenet frame at the rate -tau: its angle from the principal normal N
 * towards the binormal B is theta0 - tau s.
 */
static void test_helix_rotation_minimising(void **state)
{
	const double a = 0.05, b = 0.03, ds = 0.001;
	double c = hypot(a, b), tau = b / (c * c), (*p)[3];
	size_t n = 1500;
	char err[128];
	struct centreline *cl;
	double theta0 = 0, last = 0, turned = 0, worst = 0;

	(void)state;
	p = malloc(n * sizeof(*p));
	for (size_t i = 0; i < n; i++) {
		double w = (double)i * ds / c;

		vec3_set(p[i], a * cos(w), a * sin(w), b * w);
	}
	cl = centreline_create((const double(*)[3])p, n, ds, NULL, err,
			       sizeof(err));
	assert_non_null(cl);
	for (size_t i = 1; i + 1 < n; i++) {
		double w = (double)i * ds / c, s = (double)i * ds;
		double nv[3] = { -cos(w), -sin(w), 0 };
		double bv[3] = { b * sin(w) / c, -b * cos(w) / c, a / c };
		const double *u = centreline_sample(cl, i)->u;
		double th = atan2(vec3_dot(u, bv), vec3_dot(u, nv));

		if (i == 1) {
			theta0 = th + tau * s;
		} else {
			turned += remainder(th - last, 2 * M_PI);
		}
		last = th;
		worst = fmax(worst, fabs(remainder(th - (theta0 - tau * s),
						   2 * M_PI)));
	}
	printf("# the helix: the frame turned %.3f rad against N over %.3f m "
	       "(-tau s: %.3f), %.1e rad from theta0 - tau s at most\n",
	       turned, (double)(n - 3) * ds, -tau * (double)(n - 3) * ds,
	       worst);
	/* the frame turned against Frenet's far beyond the tolerance: the
	 * test tells the two apart */
	assert_true(fabs(turned) > 1.0);
	assert_true(worst < 2e-3);
	centreline_destroy(cl);
	free(p);
}

/* The paper's sum is the turning angle: a quarter circle turns pi/2. */
static void test_turning_angle(void **state)
{
	size_t n;
	double (*p)[3] = planar_curve(&n, 0.002), acos_sum = 0, paper = 0;
	char err[128];
	struct centreline *cl =
		centreline_create((const double(*)[3])p, n, 0.002, NULL, err,
				  sizeof(err));

	(void)state;
	assert_non_null(cl);
	for (size_t i = 0; i + 2 < n; i++) {
		double d2[3], t0[3], t1[3];

		for (int d = 0; d < 3; d++) {
			d2[d] = p[i][d] - 2 * p[i + 1][d] + p[i + 2][d];
		}
		paper += vec3_norm(d2) / 0.002;
		vec3_sub(t0, p[i + 1], p[i]);
		vec3_sub(t1, p[i + 2], p[i + 1]);
		vec3_normalize(t0);
		vec3_normalize(t1);
		acos_sum += acos(fmin(1, vec3_dot(t0, t1)));
	}
	/* two quarter circles (the S turns there and back) */
	assert_near(centreline_turning(cl, n - 1), paper, 1e-9);
	assert_near(centreline_turning(cl, n - 1), M_PI, 0.01 * M_PI);
	assert_near(acos_sum, M_PI, 0.01 * M_PI);
	/* halfway along the straight only the first quarter has turned */
	assert_near(centreline_turning(cl, n / 2), M_PI / 2, 0.01 * M_PI);
	centreline_destroy(cl);
	free(p);
}

static void test_resample_keeps_ends_and_step(void **state)
{
	const double p[3][3] = { { 0, 0, 0 }, { 0.1, 0, 0 }, { 0.1, 0.05, 0 } };
	size_t n;
	double ds, (*q)[3] = centreline_resample(p, 3, 0.01, &n, &ds);

	(void)state;
	assert_non_null(q);
	assert_int_equal(n, 16);
	assert_near(ds, 0.01, 1e-12);
	assert_vec_near(q[0], p[0], 1e-12);
	assert_vec_near(q[15], p[2], 1e-12);
	assert_vec_near(q[10], p[1], 1e-12);
	free(q);
}

/* ---------------------------------------------------------------- mesh */

struct edge {
	uint32_t a, b;
};

static int edge_cmp(const void *x, const void *y)
{
	const struct edge *e = x, *f = y;

	if (e->a != f->a) {
		return e->a < f->a ? -1 : 1;
	}
	return e->b < f->b ? -1 : e->b > f->b;
}

static void test_mesh_closed_along_tube(void **state)
{
	struct colon *c = build("normal", 0.004, 24);
	const struct mesh *m = colon_mesh(c);
	struct edge *e = malloc(3 * m->triangles * sizeof(*e));
	size_t n = 3 * m->triangles, boundary = 0;

	(void)state;
	for (uint32_t k = 0; k < m->triangles; k++) {
		for (int j = 0; j < 3; j++) {
			uint32_t a = m->tri[k][j], b = m->tri[k][(j + 1) % 3];

			e[3 * k + j] = (struct edge){ a < b ? a : b,
						      a < b ? b : a };
		}
	}
	qsort(e, n, sizeof(*e), edge_cmp);
	for (size_t i = 0; i < n;) {
		size_t j = i;

		while (j < n && !edge_cmp(&e[i], &e[j])) {
			j++;
		}
		if (j - i == 1) {
			/* an open edge: only the anal verge's ring */
			assert_int_equal(m->sample[e[i].a], 0);
			assert_int_equal(m->sample[e[i].b], 0);
			boundary++;
		} else {
			assert_int_equal(j - i, 2);
		}
		i = j;
	}
	assert_int_equal(boundary, 24);
	free(e);
	colon_destroy(c);
}

static void test_normals_face_centreline(void **state)
{
	struct colon *c = build("tight-flexures", 0.002, 48);
	const struct mesh *m = colon_mesh(c);
	const struct centreline *cl = colon_centreline(c);

	(void)state;
	for (uint32_t k = 0; k < m->triangles; k++) {
		const uint32_t *t = m->tri[k];
		double p[3][3], ab[3], ac[3], n[3], mid[3] = { 0 }, in[3];
		struct centreline_point cp;
		double s = 0;

		for (int j = 0; j < 3; j++) {
			for (int d = 0; d < 3; d++) {
				p[j][d] = m->pos[t[j]][d];
				mid[d] += p[j][d] / 3;
			}
			s += m->sample[t[j]] * centreline_step(cl) / 3;
		}
		vec3_sub(ab, p[1], p[0]);
		vec3_sub(ac, p[2], p[0]);
		vec3_cross(n, ab, ac);
		centreline_at_s(cl, s, &cp);
		vec3_sub(in, cp.p, mid);
		assert_true(vec3_dot(n, in) > 0);
	}
	for (uint32_t j = 0; j + 1 < m->vertices; j++) {
		const double *cp = centreline_sample(cl, m->sample[j])->p;
		double x[3] = { cp[0] - m->pos[j][0], cp[1] - m->pos[j][1],
				cp[2] - m->pos[j][2] };
		double nv[3] = { m->nrm[j][0], m->nrm[j][1], m->nrm[j][2] };

		assert_true(vec3_dot(nv, x) > 0);
		assert_near(vec3_norm(nv), 1, 1e-5);
	}
	colon_destroy(c);
}

/* Moeller-Trumbore: does segment P0-P1 cross triangle ABC? */
static int segment_hits(const double p0[3], const double p1[3],
			const double a[3], const double b[3],
			const double c[3])
{
	double e1[3], e2[3], d[3], h[3], s[3], q[3], det, u, v, t;

	vec3_sub(e1, b, a);
	vec3_sub(e2, c, a);
	vec3_sub(d, p1, p0);
	vec3_cross(h, d, e2);
	det = vec3_dot(e1, h);
	if (fabs(det) < 1e-18) {
		return 0;
	}
	vec3_sub(s, p0, a);
	u = vec3_dot(s, h) / det;
	vec3_cross(q, s, e1);
	v = vec3_dot(d, q) / det;
	t = vec3_dot(e2, q) / det;
	return u > 1e-9 && v > 1e-9 && u + v < 1 - 1e-9 && t > 1e-9 &&
	       t < 1 - 1e-9;
}

static void vpos(const struct mesh *m, uint32_t j, double out[3])
{
	vec3_set(out, m->pos[j][0], m->pos[j][1], m->pos[j][2]);
}

static int shares_vertex(const uint32_t *t, uint32_t a, uint32_t b)
{
	for (int j = 0; j < 3; j++) {
		if (t[j] == a || t[j] == b) {
			return 1;
		}
	}
	return 0;
}

/* No edge in the window crosses a triangle it does not touch. */
static void assert_no_self_intersection(const struct mesh *m,
					uint32_t first, uint32_t count)
{
	for (uint32_t k = first; k < first + count; k++) {
		for (int j = 0; j < 3; j++) {
			uint32_t ea = m->tri[k][j], eb = m->tri[k][(j + 1) % 3];
			double p0[3], p1[3];

			vpos(m, ea, p0);
			vpos(m, eb, p1);
			for (uint32_t l = first; l < first + count; l++) {
				double a[3], b[3], c[3];

				if (shares_vertex(m->tri[l], ea, eb)) {
					continue;
				}
				vpos(m, m->tri[l][0], a);
				vpos(m, m->tri[l][1], b);
				vpos(m, m->tri[l][2], c);
				assert_false(segment_hits(p0, p1, a, b, c));
			}
		}
	}
}

/* The sample where the centreline bends most. */
static size_t tightest(const struct centreline *cl)
{
	size_t best = 0;

	for (size_t i = 1; i < centreline_count(cl); i++) {
		if (vec3_norm(centreline_sample(cl, i)->k) >
		    vec3_norm(centreline_sample(cl, best)->k)) {
			best = i;
		}
	}
	return best;
}

static double ring_distance(const struct mesh *m, size_t i, size_t j)
{
	double best = INFINITY;

	for (uint32_t a = m->sample_first[i]; a < m->sample_first[i + 1]; a++) {
		for (uint32_t b = m->sample_first[j]; b < m->sample_first[j + 1];
		     b++) {
			double pa[3], pb[3];

			vpos(m, a, pa);
			vpos(m, b, pb);
			best = fmin(best, vec3_dist(pa, pb));
		}
	}
	return best;
}

/*
 * At the tightest bend: every ring lies ahead of the one before along the
 * tangent (no fold), rings a lumen apart stay FRACTION of the lumen apart,
 * and no edge crosses a triangle there.
 */
static void assert_no_fold(const struct colon *c, uint32_t ring,
			   double fraction)
{
	const struct mesh *m = colon_mesh(c);
	const struct centreline *cl = colon_centreline(c);
	size_t i0 = tightest(cl), n = centreline_count(cl);
	double ds = centreline_step(cl);
	double lumen = 2 * colon_lumen_radius(c, i0 * ds, 0);
	size_t w = (size_t)(lumen / ds);
	uint32_t first, count;

	for (size_t i = i0 - w; i <= i0 + w && i + 2 < n; i++) {
		const double *t = centreline_sample(cl, i)->t;

		for (uint32_t j = 0; j < ring; j++) {
			double a[3], b[3], d[3];

			vpos(m, m->sample_first[i] + j, a);
			vpos(m, m->sample_first[i + 1] + j, b);
			vec3_sub(d, b, a);
			assert_true(vec3_dot(d, t) > 0);
		}
		for (size_t j = i + w; j <= i0 + w && j + 1 < n; j++) {
			assert_true(ring_distance(m, i, j) > fraction * lumen);
		}
	}
	mesh_range(m, (i0 - w / 2) * ds, (i0 + w / 2) * ds, &first, &count);
	assert_no_self_intersection(m, first, count);
}

static void test_no_fold_at_tightest_flexure(void **state)
{
	struct colon *c = build("tight-flexures", 0.002, 48);
	const struct centreline *cl = colon_centreline(c);
	size_t i0 = tightest(cl);

	(void)state;
	/* it is a tight flexure: the bend hugs the lumen */
	assert_true(1 / vec3_norm(centreline_sample(cl, i0)->k) <
		    1.2 * colon_lumen_radius(c, i0 * centreline_step(cl), 0));
	assert_no_fold(c, 48, 0.1);
	colon_destroy(c);
}

/* A bend tighter than the lumen (refused in case files, possible when a
 * bow tightens one): the wall inside the bend is held back, not folded. */
static void test_no_fold_inside_bend_tighter_than_lumen(void **state)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	char path[512], err[256];
	struct anatomy a;
	struct colon *c;
	const struct centreline *cl;
	size_t i0;

	(void)state;
	case_path("tight-flexures", path, sizeof(path));
	assert_int_equal(anatomy_load(&a, path, err, sizeof(err)), 0);
	a.seg[ANATOMY_SPLENIC_FLEXURE].bend[0].radius_m = 0.012;
	a.seg[ANATOMY_SPLENIC_FLEXURE].bend[0].angle_rad = 120 * M_PI / 180;
	p.ring_vertices = 48;
	c = colon_create(&a, &p, err, sizeof(err));
	assert_non_null(c);
	cl = colon_centreline(c);
	i0 = tightest(cl);
	assert_true(1 / vec3_norm(centreline_sample(cl, i0)->k) <
		    0.6 * colon_lumen_radius(c, i0 * centreline_step(cl), 0));
	assert_no_fold(c, 48, 0.05);
	colon_destroy(c);
}

static void test_segments_cover_mesh(void **state)
{
	struct colon *c = build("polyps", 0.002, 32);
	const struct mesh *m = colon_mesh(c);
	double ds = centreline_step(colon_centreline(c));
	uint32_t next = 0, first, count;

	(void)state;
	assert_true(m->segments > 30);
	for (uint32_t k = 0; k < m->segments; k++) {
		const struct mesh_segment *sg = &m->seg[k];

		assert_int_equal(sg->first, next);
		assert_true(sg->count > 0);
		next += sg->count;
		for (uint32_t t = sg->first; t < sg->first + sg->count; t++) {
			uint32_t lo = UINT32_MAX;

			for (int j = 0; j < 3; j++) {
				const float *p = m->pos[m->tri[t][j]];

				lo = m->sample[m->tri[t][j]] < lo ?
					     m->sample[m->tri[t][j]] : lo;
				for (int d = 0; d < 3; d++) {
					assert_true(p[d] >= sg->min[d]);
					assert_true(p[d] <= sg->max[d]);
				}
			}
			assert_true(lo * ds >= sg->s0_m - 1e-9);
			assert_true(lo * ds < sg->s1_m + 1e-9);
		}
		assert_int_equal(mesh_segment_at(m, 0.5 * (sg->s0_m + sg->s1_m)),
				 k);
	}
	assert_int_equal(next, m->triangles);
	mesh_range(m, m->seg[3].s0_m + 0.001, m->seg[5].s0_m + 0.001, &first,
		   &count);
	assert_int_equal(first, m->seg[3].first);
	assert_int_equal(count,
			 m->seg[3].count + m->seg[4].count + m->seg[5].count);
	colon_destroy(c);
}

/* The lumen's cross-section: folds, taeniae, the cecum; its rings. */
static void test_lumen_shape(void **state)
{
	struct colon *c = build("normal", 0.004, 16);
	const struct anatomy *a = colon_anatomy(c);
	double s = anatomy_segment_start(a, ANATOMY_DESCENDING) + 0.06;
	double taenia = a->taenia_angle_rad, mid = taenia + M_PI / 3;
	double end = anatomy_length(a);
	double fold_max = 0, fold_min = INFINITY;

	(void)state;
	/* haustral folds: the radius midway between taeniae dips every
	 * fold spacing by about the fold depth */
	for (double x = s; x < s + a->fold_spacing_m; x += 0.0005) {
		double r = colon_lumen_radius(c, x, mid);

		fold_max = fmax(fold_max, r);
		fold_min = fmin(fold_min, r);
	}
	assert_near(fold_min / fold_max,
		    1 - a->seg[ANATOMY_DESCENDING].fold_depth, 0.02);
	/* three taeniae: the section repeats every 120 deg, pulled in by
	 * the taenia depth (where no fold is, between them) */
	assert_near(colon_lumen_radius(c, s, taenia + 2 * M_PI / 3),
		    colon_lumen_radius(c, s, taenia), 1e-12);
	assert_near(colon_lumen_radius(c, s, taenia) / fold_max,
		    1 - a->seg[ANATOMY_DESCENDING].taenia_depth, 0.01);
	/* the cecum is wider, and its end closes */
	assert_true(colon_lumen_radius(c, end - 0.05, mid) >
		    colon_lumen_radius(c, s, mid));
	assert_true(colon_lumen_radius(c, end - 0.0005, mid) < 0.01);
	/* a ring found once gives the same radius all round it, folds,
	   taeniae, the segments' blends and the dome */
	for (double x = 0; x < end; x += 0.0137) {
		struct colon_ring ring;

		colon_ring_at(c, x, &ring);
		for (int k = 0; k < 24; k++) {
			double th = 2 * M_PI * k / 24 - 1;

			assert_true(colon_ring_radius(c, &ring, th) ==
				    colon_lumen_radius(c, x, th));
		}
	}
	colon_destroy(c);
}

/* ---------------------------------------------------------------- deformation */

static double kink(const struct centreline *cl, size_t i)
{
	double a[3], b[3];

	vec3_sub(a, centreline_sample(cl, i)->p, centreline_sample(cl, i - 1)->p);
	vec3_sub(b, centreline_sample(cl, i + 1)->p, centreline_sample(cl, i)->p);
	vec3_normalize(a);
	vec3_normalize(b);
	return acos(fmin(1, vec3_dot(a, b)));
}

static void test_bow_is_local_and_c1(void **state)
{
	struct colon *c = build("normal", 0.002, 32);
	struct centreline *cl = colon_centreline(c);
	const struct colon_region *sig = colon_region(c, ANATOMY_SIGMOID);
	double ds = centreline_step(cl), s0, s1, e[3], mid[3];
	size_t n = centreline_count(cl), a, b, im;
	double k_end = centreline_turning(cl, n - 1), len = polyline_length(cl);
	double turn_before_b, kink0_a, kink0_b;

	(void)state;
	assert_int_equal(sig->span, 0);
	centreline_span_range(cl, 0, &s0, &s1);
	a = (size_t)lround(s0 / ds);
	b = (size_t)lround(s1 / ds);
	im = (a + b) / 2;
	kink0_a = kink(cl, a);
	kink0_b = kink(cl, b);
	turn_before_b = centreline_turning(cl, a - 1);
	assert_int_equal(colon_bow(c, 0, 0.05, true), 0);
	/* nothing outside the span moved, bit for bit */
	for (size_t i = 0; i < n; i++) {
		if (i <= a || i >= b) {
			assert_memory_equal(centreline_sample(cl, i)->p,
					    centreline_base(cl, i)->p,
					    sizeof(double[3]));
		}
		if (i < a || i > b) {
			assert_memory_equal(centreline_sample(cl, i),
					    centreline_base(cl, i),
					    sizeof(struct centreline_point));
		}
		assert_orthonormal(centreline_sample(cl, i));
	}
	assert_near(centreline_turning(cl, a - 1), turn_before_b, 0);
	/* the middle moved by the amplitude, across the span */
	centreline_bow_direction(cl, 0, e);
	vec3_axpy(mid, centreline_base(cl, im)->p, 0.05, e);
	assert_vec_near(centreline_sample(cl, im)->p, mid, 1e-3);
	/* C1 at both ends: no kink beyond the curve's own bending */
	assert_near(kink(cl, a), kink0_a, 0.01);
	assert_near(kink(cl, b), kink0_b, 0.01);
	assert_near(kink(cl, a + 1), kink0_a, 0.02);
	/* frames continuous where the span hands back to the fixed colon */
	assert_vec_near(centreline_sample(cl, b)->u, centreline_sample(cl,
								       b + 1)->u,
			0.02);
	/* the bowed colon is longer and turns more; later samples shift */
	assert_true(polyline_length(cl) > len + 0.005);
	assert_near(centreline_total_arclength(cl), polyline_length(cl), 1e-9);
	assert_true(centreline_turning(cl, n - 1) > k_end + 0.1);
	/* the mesh followed: a vertex of the middle ring moved ~A along e */
	{
		uint32_t j = colon_mesh(c)->sample_first[im];
		const float *p = colon_mesh(c)->pos[j];
		double d[3] = { p[0] - centreline_base(cl, im)->p[0],
				p[1] - centreline_base(cl, im)->p[1],
				p[2] - centreline_base(cl, im)->p[2] };

		assert_true(vec3_dot(d, e) > 0.02);
	}
	/* and back: bowing to 0 restores the undeformed centreline */
	assert_int_equal(colon_bow(c, 0, 0, true), 0);
	for (size_t i = 0; i < n; i++) {
		assert_vec_near(centreline_sample(cl, i)->p,
				centreline_base(cl, i)->p, 1e-12);
		assert_vec_near(centreline_sample(cl, i)->u,
				centreline_base(cl, i)->u, 1e-9);
	}
	assert_near(centreline_turning(cl, n - 1), k_end, 1e-9);
	assert_int_equal(colon_bow(c, 2, 0.01, false), -EINVAL);
	assert_int_equal(colon_bow(c, 0, NAN, false), -EINVAL);
	colon_destroy(c);
}

/* ---------------------------------------------------------------- OBJ */

/* A triangle as its corners' coordinates, for comparing meshes. */
struct corners {
	float x[9];
};

static int corners_cmp(const void *a, const void *b)
{
	return memcmp(a, b, sizeof(struct corners));
}

static struct corners *sorted_corners(const struct mesh *m)
{
	struct corners *c = malloc(m->triangles * sizeof(*c));

	for (uint32_t k = 0; k < m->triangles; k++) {
		for (int j = 0; j < 3; j++) {
			memcpy(&c[k].x[3 * j], m->pos[m->tri[k][j]],
			       3 * sizeof(float));
		}
	}
	qsort(c, m->triangles, sizeof(*c), corners_cmp);
	return c;
}

/* The same triangles, corner for corner in the same winding, whatever
 * their order in the index buffer. */
static void assert_same_triangles(const struct mesh *a, const struct mesh *b)
{
	struct corners *ca = sorted_corners(a), *cb = sorted_corners(b);

	assert_int_equal(a->triangles, b->triangles);
	assert_memory_equal(ca, cb, a->triangles * sizeof(*ca));
	free(ca);
	free(cb);
}

static void test_export_import_round_trip(void **state)
{
	struct colon *c = build("redundant-sigmoid", 0.002, 24), *d;
	struct colon_params p = COLON_PARAMS_DEFAULT;
	const struct mesh *m = colon_mesh(c), *mi;
	const struct centreline *cl = colon_centreline(c), *cli;
	char path[512], err[256];

	(void)state;
	scratch("round.obj", "", path, sizeof(path));
	assert_int_equal(colon_export(c, path, err, sizeof(err)), 0);
	d = colon_import(path, NULL, &p, err, sizeof(err));
	if (!d) {
		print_error("%s\n", err);
		fail();
	}
	mi = colon_mesh(d);
	cli = colon_centreline(d);
	assert_int_equal(mi->vertices, m->vertices);
	assert_int_equal(mi->triangles, m->triangles);
	assert_int_equal(mi->segments, m->segments);
	assert_int_equal(centreline_count(cli), centreline_count(cl));
	for (size_t i = 0; i < centreline_count(cl); i++) {
		assert_vec_near(centreline_sample(cli, i)->p,
				centreline_sample(cl, i)->p, 1e-4);
	}
	assert_same_triangles(m, mi);
	for (uint32_t k = 0; k < m->segments; k++) {
		assert_int_equal(mi->seg[k].first, m->seg[k].first);
		assert_int_equal(mi->seg[k].count, m->seg[k].count);
	}
	unlink(path);
	colon_destroy(d);
	colon_destroy(c);
}

static void test_import_with_centreline_file(void **state)
{
	struct colon *c = build("normal", 0.004, 16), *d;
	struct colon_params p = COLON_PARAMS_DEFAULT;
	const struct centreline *cl = colon_centreline(c);
	char obj[512], pts[512], err[256];
	FILE *f;

	(void)state;
	scratch("cl.obj", "", obj, sizeof(obj));
	assert_int_equal(colon_export(c, obj, err, sizeof(err)), 0);
	scratch("cl.txt", "# centreline\n", pts, sizeof(pts));
	f = fopen(pts, "a");
	for (size_t i = 0; i < centreline_count(cl); i += 3) {
		const double *q = centreline_sample(cl, i)->p;

		fprintf(f, "%.9g %.9g %.9g\n\n", q[0], q[1], q[2]);
	}
	fclose(f);
	d = colon_import(obj, pts, &p, err, sizeof(err));
	if (!d) {
		print_error("%s\n", err);
		fail();
	}
	assert_int_equal(colon_mesh(d)->triangles, colon_mesh(c)->triangles);
	assert_near(centreline_length(colon_centreline(d)),
		    polyline_length(cl), 0.01);
	colon_destroy(d);
	colon_destroy(c);
	unlink(obj);
	unlink(pts);
}

struct bad_obj {
	const char *obj, *cl; /* cl NULL: the OBJ's polyline */
	int line;             /* 0: no line in the message */
	const char *words;
};

#define CL_LINE "l 4 5 6 7 8 9 10 11\n"
#define CL_VERTS "v 0 0 0\nv 0 0 0.1\nv 0 0 0.2\nv 0 0 0.3\nv 0 0 0.4\n" \
		 "v 0 0 0.5\nv 0 0 0.6\nv 0 0 0.7\n"

static void test_bad_obj_refused_with_line(void **state)
{
	static const struct bad_obj bad[] = {
		{ "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", NULL, 4,
		  "vertex index 4 is out of range" },
		{ "v 0 0 0\nv 1 0 nan\n", NULL, 2, "not a finite number" },
		{ "v 0 0 0\nv 1 0\n", NULL, 2, "expected 3 coordinates" },
		{ "v 0 0 0\nv 1 0 0 1\n", NULL, 2, "expected 3 coordinates" },
		{ "# c\nv 0 0 0\nv 1 0 0\nf 1 2\n", NULL, 4, "at least 3" },
		{ "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n", NULL, 4,
		  "repeats vertex" },
		{ "v 0 0 0\nv 1 0 0\nv 0 1 0\nfoo 1\n", NULL, 4,
		  "unknown statement 'foo'" },
		{ "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", NULL, 4,
		  "not a vertex index" },
		{ "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", NULL, 0,
		  "no centreline" },
		{ "v 0 0 0\n", NULL, 0, "no faces" },
		{ "v 0 0.01 0\nv 0.01 0 0\nv 0 -0.01 0.001\nf 1 2 3\n",
		  "0 0 0\n0 0 0.1\n0 0 zz\n", 3, "not a finite number" },
		{ "v 0 10 0\nv 0.01 0 0\nv 0 -0.01 0.001\nf 1 2 3\n" CL_VERTS
		  CL_LINE, NULL, 0, "more than" },
		{ "v 0 10 0\nv 0.01 0 0\nv 0 -0.01 0.001\nf 1 2 3\n"
		  "v 0 0 0\nv 0 0 100\nv 0 0 200\nv 0 0 300\nv 0 0 400\n"
		  "v 0 0 500\nv 0 0 600\nv 0 0 700\n" CL_LINE, NULL, 0,
		  "must be in metres" },
	};
	struct colon_params p = COLON_PARAMS_DEFAULT;

	(void)state;
	for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		char obj[512], cl[512], err[512];
		struct colon *c;

		scratch("bad.obj", bad[i].obj, obj, sizeof(obj));
		if (bad[i].cl) {
			scratch("bad.txt", bad[i].cl, cl, sizeof(cl));
		}
		c = colon_import(obj, bad[i].cl ? cl : NULL, &p, err,
				 sizeof(err));
		assert_null(c);
		assert_error_at(err, bad[i].cl ? cl : obj, bad[i].line,
				bad[i].words);
		unlink(obj);
		if (bad[i].cl) {
			unlink(cl);
		}
	}
}

static void test_bad_params_refused(void **state)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	char path[512], err[256];
	struct anatomy a;

	(void)state;
	case_path("normal", path, sizeof(path));
	assert_int_equal(anatomy_load(&a, path, err, sizeof(err)), 0);
	p.ring_vertices = 3;
	assert_null(colon_create(&a, &p, err, sizeof(err)));
	assert_non_null(strstr(err, "out of range"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_every_case_loads),
		cmocka_unit_test(test_normal_matches_brief),
		cmocka_unit_test(test_cecum_within_reach),
		cmocka_unit_test(test_redundant_sigmoid_long_and_lax),
		cmocka_unit_test(test_bad_cases_refused_with_line),
		cmocka_unit_test(test_bad_patient_keys_refused_with_line),
		cmocka_unit_test(test_polyp_morphology),
		cmocka_unit_test(test_bad_polyp_keys_refused_with_line),
		cmocka_unit_test(test_length_is_sum_of_segments),
		cmocka_unit_test(test_frames_orthonormal),
		cmocka_unit_test(test_no_twist_on_planar_curve),
		cmocka_unit_test(test_helix_rotation_minimising),
		cmocka_unit_test(test_turning_angle),
		cmocka_unit_test(test_resample_keeps_ends_and_step),
		cmocka_unit_test(test_mesh_closed_along_tube),
		cmocka_unit_test(test_normals_face_centreline),
		cmocka_unit_test(test_no_fold_at_tightest_flexure),
		cmocka_unit_test(test_no_fold_inside_bend_tighter_than_lumen),
		cmocka_unit_test(test_segments_cover_mesh),
		cmocka_unit_test(test_lumen_shape),
		cmocka_unit_test(test_bow_is_local_and_c1),
		cmocka_unit_test(test_export_import_round_trip),
		cmocka_unit_test(test_import_with_centreline_file),
		cmocka_unit_test(test_bad_obj_refused_with_line),
		cmocka_unit_test(test_bad_params_refused),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
