/*
 * png_stats - pixel statistics of a region of a PNG (endoview's
 * screenshots), for the viewer's system tests. Reads the file with
 * stb_image.
 *
 *   png_stats FILE.png [--diff OTHER.png] REGION...
 *
 * REGION is rect:X,Y,W,H, disc:CX,CY,R or ring:CX,CY,R0,R1 (pixels, the
 * image's top-left origin). For each, one line:
 *
 *   REGION n=PIXELS mean=LUMA lit=SHARE red=SHARE amber=SHARE yellow=SHARE
 *          scope=SHARE box=X0,Y0,X1,Y1 grey=SHARE blood=SHARE
 *          ghost=SHARE
 *
 * LUMA is the mean Rec. 601 luma (0..255); lit the share of pixels with
 * luma above 40; red the share of saturated red (a banner, an alarm, the
 * contact point); amber the share of amber (a warning, a bowed segment);
 * yellow the share of the dull brown-yellow of the patient's fluid (green
 * near red, blue far below both: not the mucosa's pink, whose blue is
 * near its green);
 * scope the share of the overview's scope green; box the bounding box of
 * the scope-green pixels (-1s when none); grey the share of light, nearly
 * colourless pixels (each channel above 80, within a quarter of red of
 * each other: a tool's white sheath and its steel, not the mucosa); blood
 * the share of deep red (red above 30, green and blue below a third of
 * it: blood over the mucosa, not its pink); ghost the share of the
 * blue of guided replay's expert's tool (blue above red by 40 or more,
 * green above red by half as much: the ghost over the mucosa or the dark
 * lumen, not the mucosa's pink, nor a forceps' blue, whose green is
 * little above its red). With --diff (OTHER.png of the same size), each
 * line ends in changed=SHARE: the share of the region's pixels where a
 * channel differs from OTHER's by more than PNG_CHANGED (two pictures of
 * one scene, something moved).
 *
 * Exit 0, 1 when the file cannot be read, 2 on usage.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#define PNG_CHANGED 24 /* of 255, in any channel: a pixel changed */

struct region {
	char kind;            /* 'r', 'd', 'g' (rect, disc, ring) */
	double a, b, c, d;
};

struct tally {
	long n, lit, red, amber, yellow, scope, grey, blood, ghost, changed;
	double luma;
	int box[4];
};

static int parse(const char *s, struct region *r)
{
	if (sscanf(s, "rect:%lf,%lf,%lf,%lf", &r->a, &r->b, &r->c, &r->d) ==
	    4) {
		r->kind = 'r';
	} else if (sscanf(s, "disc:%lf,%lf,%lf", &r->a, &r->b, &r->c) == 3) {
		r->kind = 'd';
	} else if (sscanf(s, "ring:%lf,%lf,%lf,%lf", &r->a, &r->b, &r->c,
			  &r->d) == 4) {
		r->kind = 'g';
	} else {
		return -1;
	}
	return 0;
}

static int inside(const struct region *r, int x, int y)
{
	double dx = x + 0.5 - r->a, dy = y + 0.5 - r->b, d = hypot(dx, dy);

	switch (r->kind) {
	case 'r':
		return x >= r->a && x < r->a + r->c && y >= r->b &&
		       y < r->b + r->d;
	case 'd':
		return d <= r->c;
	default:
		return d >= r->c && d <= r->d;
	}
}

static void count(struct tally *t, const unsigned char *p, int x, int y)
{
	int r = p[0], g = p[1], b = p[2];
	double luma = 0.299 * r + 0.587 * g + 0.114 * b;
	int scope = g > 120 && g > r + 50 && g > b + 50;

	t->n++;
	t->luma += luma;
	t->lit += luma > 40;
	t->red += r > 200 && g < 100 && b < 100;
	t->amber += r > 120 && g > 0.45 * r && g < 0.8 * r && b < 0.3 * r;
	t->yellow += r > 30 && g > 0.62 * r && g < 1.1 * r && b < 0.5 * g;
	t->scope += scope;
	t->blood += r > 30 && g < r / 3 && b < r / 3;
	t->ghost += b > r + 40 && g - r > 0.5 * (b - r);
	t->grey += r > 80 && g > 80 && b > 80 &&
		   abs(r - g) < 0.25 * r && abs(g - b) < 0.25 * r &&
		   abs(r - b) < 0.25 * r;
	if (scope) {
		t->box[0] = t->box[0] < 0 || x < t->box[0] ? x : t->box[0];
		t->box[1] = t->box[1] < 0 || y < t->box[1] ? y : t->box[1];
		t->box[2] = x > t->box[2] ? x : t->box[2];
		t->box[3] = y > t->box[3] ? y : t->box[3];
	}
}

/* Whether pixel P differs from Q by more than PNG_CHANGED. */
static int changed(const unsigned char *p, const unsigned char *q)
{
	return abs(p[0] - q[0]) > PNG_CHANGED ||
	       abs(p[1] - q[1]) > PNG_CHANGED || abs(p[2] - q[2]) > PNG_CHANGED;
}

static void report(const char *name, const unsigned char *img,
		   const unsigned char *other, int w, int h,
		   const struct region *r)
{
	struct tally t = { .box = { -1, -1, -1, -1 } };
	double n;

	for (int y = 0; y < h; y++) {
		for (int x = 0; x < w; x++) {
			size_t at = 3 * ((size_t)y * w + x);

			if (inside(r, x, y)) {
				count(&t, &img[at], x, y);
				t.changed += other && changed(&img[at],
							      &other[at]);
			}
		}
	}
	n = t.n ? (double)t.n : 1;
	printf("%s n=%ld mean=%.1f lit=%.4f red=%.4f amber=%.4f yellow=%.4f "
	       "scope=%.4f box=%d,%d,%d,%d grey=%.4f blood=%.4f ghost=%.4f",
	       name,
	       t.n, t.luma / n, t.lit / n, t.red / n, t.amber / n,
	       t.yellow / n, t.scope / n, t.box[0], t.box[1], t.box[2],
	       t.box[3], t.grey / n, t.blood / n, t.ghost / n);
	if (other) {
		printf(" changed=%.4f", t.changed / n);
	}
	putchar('\n');
}

/* FILE as RGB, W x H; NULL (said) when it cannot be read. */
static unsigned char *load(const char *file, int *w, int *h)
{
	int channels;
	unsigned char *img = stbi_load(file, w, h, &channels, 3);

	if (!img) {
		fprintf(stderr, "png_stats: %s: %s\n", file,
			stbi_failure_reason());
	}
	return img;
}

int main(int argc, char **argv)
{
	struct region r;
	unsigned char *img, *other = NULL;
	int w, h, ow, oh, first = 2, rc = 0;

	if (argc < 3 || (!strcmp(argv[2], "--diff") && argc < 5)) {
		fprintf(stderr, "usage: png_stats FILE.png [--diff OTHER.png] "
			"REGION...\n");
		return 2;
	}
	img = load(argv[1], &w, &h);
	if (img && !strcmp(argv[2], "--diff")) {
		first = 4;
		other = load(argv[3], &ow, &oh);
		if (other && (ow != w || oh != h)) {
			fprintf(stderr, "png_stats: %s: %dx%d, not %dx%d\n",
				argv[3], ow, oh, w, h);
			rc = 1;
		}
	}
	if (!img || (first == 4 && !other)) {
		rc = 1;
	}
	for (int k = first; !rc && k < argc; k++) {
		if (parse(argv[k], &r)) {
			fprintf(stderr, "png_stats: bad region %s\n", argv[k]);
			rc = 2;
			break;
		}
		report(argv[k], img, other, w, h, &r);
	}
	stbi_image_free(img);
	stbi_image_free(other);
	return rc;
}
