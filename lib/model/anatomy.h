/*
 * anatomy.h - a colonoscopy case: the colon's anatomy by its segments from
 * the anal verge, and its pathologies, read from a case file.
 *
 * Case file format (config/cases/NAME.case): lines "key = value" under
 * section headers; '#' starts a comment anywhere, ';' at a line's start or
 * after a blank; blank lines are ignored. Read by the parsing kit over
 * libinih (base/parse.h has the grammar), from a file or a session's CASE
 * frame.
 *
 *   [case]                      once, first
 *   name = normal               required; letters, digits, '-', '_'
 *   description = free text     optional
 *
 *   [lumen]                     optional, defaults shown
 *   taenia_angle_deg = 0        where the first of the three taeniae runs,
 *                               around the centreline from the frame's u
 *   taenia_depth = 0.10         fraction of the radius the taeniae pull in
 *   fold_depth = 0.15           fraction of the radius a haustral fold
 *                               narrows the lumen (midway between taeniae)
 *   fold_spacing_m = 0.03       distance between folds along the colon
 *   fold_width_m = 0.005        half-width of a fold
 *
 *   [segment NAME]              all nine, in this order: anal_canal, rectum,
 *                               sigmoid, descending, splenic_flexure,
 *                               transverse, hepatic_flexure, ascending, cecum
 *   length_m = 0.37             required, along the centreline
 *   diameter_m = 0.045          required, lumen diameter
 *   taenia_depth = 0.1          optional, overrides [lumen] (0: round)
 *   fold_depth = 0.15           optional, overrides [lumen] (0: no folds)
 *   mobile = yes                optional (default no): on a mesentery, may
 *                               bow; not the first or last segment, and
 *                               never two mobile segments side by side
 *   mesentery_n_per_m = 150     stiffness of the mesentery (mobile only)
 *   mesentery_height_m = 0.06   largest bow of the segment (mobile only)
 *   wall_collapsed = 0.4        optional, the wall's pressure-volume law
 *   wall_max = 1.25             (gas.h): the radius factor collapsed
 *   wall_nominal_pa = 2000      (0.1..1, below 1) and the one it stiffens
 *   wall_beta = 1.5             towards (1..2, above 1), the transmural
 *                               pressure at the case's radius (200..10000
 *                               Pa) and the law's shape (0.3..5; defaults
 *                               below)
 *   fluid_m3 = 0                optional: residual fluid pooled in it
 *                               (0..0.002, at most half its lumen)
 *   bend = ANGLE_DEG RADIUS_M PLANE_DEG
 *                               repeatable, up to ANATOMY_MAX_BENDS: an arc
 *                               of ANGLE_DEG (0..180) with radius RADIUS_M;
 *                               PLANE_DEG turns the bending direction about
 *                               the tangent from the previous bend's (0:
 *                               the same sense, 180: back, an S; 90 and 270
 *                               out of that plane). The first bend of the
 *                               case counts from the patient's anterior.
 *                               A segment's straight remainder is shared
 *                               equally before, between and after its bends.
 *
 *   [site NAME]                 repeatable, up to ANATOMY_MAX_SITES: a
 *                               place where the assistant presses on the
 *                               abdomen (llq over the sigmoid, umbilical
 *                               under the transverse colon's apex, ...)
 *   position_m = X Y Z          required: the pad's centre on the
 *                               abdominal wall, m (each -1..1)
 *   direction = X Y Z           into the abdomen (default 0 1 0: from the
 *                               front towards the back; each -1..1, not
 *                               all 0; made a unit vector)
 *   radius_m = 0.08             the pad's reach about its axis (the
 *                               flat of a hand, 16 cm across; 0.01..0.2):
 *                               the mobile colon within it, at any depth,
 *                               is held (flex.h)
 *
 *   [polyp]                     repeatable, up to ANATOMY_MAX_POLYPS
 *   s_m = 0.62                  required: distance from the anal verge
 *   angle_deg = 45              required: around the lumen from the frame's u
 *   diameter_m = 0.008          required: its size (a stalked polyp's
 *                               head), 0.001..0.06
 *   shape = sessile             sessile (default), pedunculated or flat
 *   paris = Is                  optional, its Paris class (Endoscopy
 *                               2003;35:570): Ip (pedunculated: a head on
 *                               a stalk), Is (sessile), IIa (flat,
 *                               slightly elevated) or IIb (flat, level
 *                               with the mucosa); by default from shape
 *                               (pedunculated Ip, sessile Is, flat IIa),
 *                               and shape from it when only it is given;
 *                               the two must agree when both are
 *   stalk_length_m = 0.004      Ip only: from the wall to the head
 *                               (0.001..0.04; default half the diameter)
 *   stalk_diameter_m = 0.003    Ip only: its thickness, below the head's
 *                               diameter (0.001..0.02; default 0.35 of
 *                               it); the defaults are the proportions the
 *                               viewer draws a pedunculated polyp with.
 *                               What a snare needs of them: tool.h
 *
 * Coordinates (colon.h): metres, x to the patient's left, y posterior, z
 * cranial (DICOM's LPS: the mobile sigmoid and transverse colon hang
 * towards -y, the front, from the flexures on the back wall); the anal
 * verge at the origin, the colon starting cranially.
 *
 * Checks beyond each value's range: every segment present and in order,
 * bends fit in their segment, no bend tighter than the lumen radius (the
 * wall would fold on the inside of the bend), mobile segments as above,
 * each wall's law able to reach the case's radius (wall_collapsed below 1,
 * wall_max above 1), a segment's fluid at most half its lumen at the
 * case's diameter, polyps inside the colon and smaller than the lumen,
 * a polyp's shape and Paris class agreeing, a stalk only on Ip and
 * thinner than its head,
 * sites named once and with a direction.
 *
 * Errors are one line "FILE:LINE: [section] key: what", "FILE:LINE:
 * [section]: what" or, for the checks after the file, "FILE:LINE: key:
 * what", in the caller's buffer. Loading reads the file and allocates only
 * while it reads; struct anatomy is plain data (copy it freely). Any
 * thread.
 */
#ifndef ENDOSIM_ANATOMY_H
#define ENDOSIM_ANATOMY_H

#include <stdbool.h>
#include <stddef.h>

#define ANATOMY_SEGMENTS 9
#define ANATOMY_MAX_BENDS 8
#define ANATOMY_MAX_POLYPS 32
#define ANATOMY_MAX_SITES 8

/* The wall's law's defaults (gas.h, docs/PATIENT.md): folds meeting at 40
 * % of the radius, stiffening towards 125 %, the case's radius at 15 mmHg
 * (CT colonography's distension), beta 1.5 (barostat fits: 1-2). */
#define ANATOMY_DEFAULT_WALL_COLLAPSED 0.4
#define ANATOMY_DEFAULT_WALL_MAX 1.25
#define ANATOMY_DEFAULT_WALL_NOMINAL_PA 2000.0
#define ANATOMY_DEFAULT_WALL_BETA 1.5
#define ANATOMY_DEFAULT_SITE_RADIUS_M 0.08
#define ANATOMY_NAME 64
#define ANATOMY_TEXT 160

enum anatomy_segment_id {
	ANATOMY_ANAL_CANAL = 0,
	ANATOMY_RECTUM,
	ANATOMY_SIGMOID,
	ANATOMY_DESCENDING,
	ANATOMY_SPLENIC_FLEXURE,
	ANATOMY_TRANSVERSE,
	ANATOMY_HEPATIC_FLEXURE,
	ANATOMY_ASCENDING,
	ANATOMY_CECUM,
};

enum anatomy_polyp_shape {
	ANATOMY_POLYP_SESSILE = 0,
	ANATOMY_POLYP_PEDUNCULATED,
	ANATOMY_POLYP_FLAT,
};

/* The Paris classes of superficial lesions a snare removes (type 0). */
enum anatomy_paris {
	ANATOMY_PARIS_IP = 0, /* pedunculated */
	ANATOMY_PARIS_IS,     /* sessile */
	ANATOMY_PARIS_IIA,    /* flat, slightly elevated (< 2.5 mm) */
	ANATOMY_PARIS_IIB,    /* flat, level with the mucosa */
};

/* A stalk's defaults as fractions of the head's diameter. */
#define ANATOMY_DEFAULT_STALK_LENGTH 0.5
#define ANATOMY_DEFAULT_STALK_DIAMETER 0.35

struct anatomy_bend {
	double angle_rad;  /* 0..pi */
	double radius_m;   /* of the arc, > lumen radius */
	double plane_rad;  /* about the tangent, from the previous bend's */
};

struct anatomy_segment {
	double length_m;
	double diameter_m;
	double taenia_depth;       /* fraction of the radius, 0..0.4 */
	double fold_depth;         /* fraction of the radius, 0..0.5 */
	bool mobile;
	double mesentery_n_per_m;  /* mobile segments: N/m */
	double mesentery_height_m; /* mobile segments: largest bow, m */
	double wall_collapsed;     /* radius factor, 0.1..1, below 1 */
	double wall_max;           /* radius factor, 1..2, above 1 */
	double wall_nominal_pa;    /* Pa, 200..10000 */
	double wall_beta;          /* 0.3..5 */
	double fluid_m3;           /* residual fluid, 0..0.002 */
	struct anatomy_bend bend[ANATOMY_MAX_BENDS];
	int bends;
};

struct anatomy_site {
	char name[ANATOMY_NAME];
	double position_m[3];      /* on the abdominal wall, body frame */
	double direction[3];       /* unit, into the abdomen */
	double radius_m;
};

struct anatomy_polyp {
	double s_m;        /* from the anal verge along the centreline */
	double angle_rad;  /* around the lumen from the frame's u */
	double diameter_m; /* its size: a stalked polyp's head's */
	int shape;         /* enum anatomy_polyp_shape */
	int paris;         /* enum anatomy_paris, agreeing with shape */
	double stalk_length_m;   /* Ip: wall to head; 0 otherwise */
	double stalk_diameter_m; /* Ip: < diameter_m; 0 otherwise */
};

struct anatomy {
	char name[ANATOMY_NAME];
	char description[ANATOMY_TEXT];
	double taenia_angle_rad;
	double fold_spacing_m;
	double fold_width_m;
	struct anatomy_segment seg[ANATOMY_SEGMENTS];
	struct anatomy_polyp polyp[ANATOMY_MAX_POLYPS];
	int polyps;
	struct anatomy_site site[ANATOMY_MAX_SITES];
	int sites;
};

/* The site called NAME, or -1. */
int anatomy_site_find(const struct anatomy *a, const char *name);

/*
 * Reads the case file PATH into A. Returns 0, -ENOENT or another negative
 * errno when it cannot be read, or -EINVAL with one line in ERR (A then
 * as it was).
 */
int anatomy_load(struct anatomy *a, const char *path, char *err,
		 size_t errsize);

/*
 * The same for a case file's TEXT (NUL-terminated, e.g. a session file's
 * CASE frame); NAME stands for the file in ERR's "NAME:LINE: ...".
 */
int anatomy_parse(struct anatomy *a, const char *text, const char *name,
		  char *err, size_t errsize);

/* "anal_canal", ..., "cecum"; "?" when out of range. */
const char *anatomy_segment_name(int id);

/* "sessile", "pedunculated", "flat"; "?" when out of range. */
const char *anatomy_polyp_shape_name(int shape);

/* "Ip", "Is", "IIa", "IIb"; "?" when out of range. */
const char *anatomy_paris_name(int paris);

/* Sum of the segments' lengths, m. */
double anatomy_length(const struct anatomy *a);

/* Distance from the anal verge to the start of segment ID, m. */
double anatomy_segment_start(const struct anatomy *a, int id);

#endif
