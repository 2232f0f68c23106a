/* vessels.c - see vessels.h. */
#include "viewer/vessels.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#define STEP_PX 1.0        /* along a vessel */
#define TRUNKS_PER_MPX 14  /* vessel trees per million pixels */

struct canvas {
	int size;
	float *deep;   /* 0..1: broad submucosal vessels */
	float *fine;   /* 0..1: fine superficial vessels */
	uint32_t rng;
};

static uint32_t next(uint32_t *s)
{
	*s ^= *s << 13;
	*s ^= *s >> 17;
	*s ^= *s << 5;
	return *s;
}

/* Uniform in [0, 1). */
static float rnd(uint32_t *s)
{
	return (float)(next(s) >> 8) / 16777216.0f;
}

static float hash2(int x, int y, uint32_t seed)
{
	uint32_t h = (uint32_t)x * 374761393u + (uint32_t)y * 668265263u +
		     seed * 2246822519u;

	h = (h ^ (h >> 13)) * 1274126177u;
	return (float)((h ^ (h >> 16)) & 0xffffff) / 16777216.0f;
}

static float smooth(float t)
{
	return t * t * (3 - 2 * t);
}

/* Value noise on a lattice of PERIOD cells across the tile, in [0, 1). */
static float noise(float x, float y, int period, uint32_t seed)
{
	int x0 = (int)floorf(x), y0 = (int)floorf(y);
	float fx = smooth(x - (float)x0), fy = smooth(y - (float)y0);
	int xa = ((x0 % period) + period) % period, xb = (xa + 1) % period;
	int ya = ((y0 % period) + period) % period, yb = (ya + 1) % period;
	float a = hash2(xa, ya, seed), b = hash2(xb, ya, seed);
	float c = hash2(xa, yb, seed), d = hash2(xb, yb, seed);

	return (a + (b - a) * fx) * (1 - fy) + (c + (d - c) * fx) * fy;
}

/* Octaves from PERIOD cells up, at U, V in [0, 1): tileable. */
static float fbm(float u, float v, int period, int octaves, uint32_t seed)
{
	float sum = 0, amp = 0.5f, norm = 0;

	for (int k = 0; k < octaves; k++) {
		sum += amp * noise(u * (float)period, v * (float)period, period,
				   seed + (uint32_t)k);
		norm += amp;
		amp *= 0.5f;
		period *= 2;
	}
	return sum / norm;
}

static int wrap(int i, int n)
{
	return (i % n + n) % n;
}

/* A soft disc of radius W at (X, Y), kept as the maximum, wrapped. */
static void stamp(struct canvas *c, float *map, float x, float y, float w)
{
	int r = (int)ceilf(2 * w), n = c->size;

	for (int dy = -r; dy <= r; dy++) {
		for (int dx = -r; dx <= r; dx++) {
			float ex = (float)dx - (x - floorf(x));
			float ey = (float)dy - (y - floorf(y));
			float v = expf(-(ex * ex + ey * ey) / (w * w));
			float *p = &map[wrap((int)floorf(y) + dy, n) * n +
					wrap((int)floorf(x) + dx, n)];

			*p = v > *p ? v : *p;
		}
	}
}

/* One vessel from (X, Y) heading ANGLE, branching as it thins. */
static void grow(struct canvas *c, float *map, float x, float y, float angle,
		 float width, float length, int depth)
{
	float turn = 0;

	for (float run = 0; run < length && width > 0.3f; run += STEP_PX) {
		turn += (rnd(&c->rng) - 0.5f) * 0.016f;
		turn *= 0.93f;
		angle += turn;
		x += cosf(angle) * STEP_PX;
		y += sinf(angle) * STEP_PX;
		stamp(c, map, x, y, width);
		width *= 0.999f;
		if (depth < 5 && rnd(&c->rng) < 0.007f) {
			float side = rnd(&c->rng) < 0.5f ? -1.0f : 1.0f;

			grow(c, map, x, y,
			     angle + side * (0.4f + 0.6f * rnd(&c->rng)),
			     width * 0.7f, (length - run) * 0.6f, depth + 1);
			width *= 0.9f;
			angle -= side * 0.15f;
		}
	}
}

static void grow_all(struct canvas *c)
{
	int n = c->size;
	int trees = (int)((double)n * n * TRUNKS_PER_MPX / 1e6) + 4;
	float scale = (float)n / 1024.0f;

	for (int k = 0; k < trees; k++) {
		float x = rnd(&c->rng) * (float)n, y = rnd(&c->rng) * (float)n;
		float a = rnd(&c->rng) * 6.2831853f;

		if (k % 2 == 0) {
			grow(c, c->deep, x, y, a, 4.0f * scale, 900 * scale, 1);
		} else {
			grow(c, c->fine, x, y, a, 2.2f * scale, 600 * scale, 0);
		}
	}
}

/* The mean of the 2 R + 1 pixels around (X, Y) along a row or a column. */
static float box(const float *map, int n, int x, int y, int r, bool column)
{
	float sum = 0;

	for (int k = -r; k <= r; k++) {
		sum += column ? map[wrap(y + k, n) * n + x] :
				map[y * n + wrap(x + k, n)];
	}
	return sum / (float)(2 * r + 1);
}

/* Softens MAP by a box of 2 R + 1 pixels along the rows, then the
 * columns, wrapped (TMP: room for a map). */
static void blur(float *map, float *tmp, int n, int r)
{
	for (int pass = 0; pass < 2; pass++) {
		for (int y = 0; y < n; y++) {
			for (int x = 0; x < n; x++) {
				tmp[y * n + x] = box(map, n, x, y, r, pass);
			}
		}
		memcpy(map, tmp, (size_t)n * n * sizeof(*map));
	}
}

static uint8_t byte(float v)
{
	v = v < 0 ? 0 : v > 1 ? 1 : v;
	return (uint8_t)lrintf(v * 255.0f);
}

static void shade(const struct canvas *c, uint8_t *out, uint32_t seed)
{
	int n = c->size;

	for (int y = 0; y < n; y++) {
		for (int x = 0; x < n; x++) {
			float u = (float)x / (float)n, v = (float)y / (float)n;
			float m = fbm(u, v, 4, 3, seed);
			float g = fbm(u, v, 64, 3, seed + 17);
			float d = c->deep[y * n + x], f = c->fine[y * n + x];
			float rgb[3] = { 0.90f - 0.10f * m, 0.46f - 0.10f * m,
					 0.34f - 0.08f * m };
			const float deep[3] = { 0.78f, 0.60f, 0.78f };
			const float fine[3] = { 0.62f, 0.22f, 0.24f };
			uint8_t *p = &out[4 * (y * n + x)];

			for (int k = 0; k < 3; k++) {
				rgb[k] *= 1 + 0.45f * d * (deep[k] - 1);
				rgb[k] *= 1 + 0.75f * f * (fine[k] - 1);
				p[k] = byte(rgb[k]);
			}
			p[3] = byte(0.45f + 0.35f * (g - 0.5f) + 0.3f * f +
				    0.15f * d);
		}
	}
}

uint8_t *vessels_create(int size, uint32_t seed)
{
	struct canvas c = { .size = size, .rng = seed | 1 };
	uint8_t *img = NULL;
	float *tmp = NULL;

	if (size < 64 || size > 4096 || (size & (size - 1))) {
		return NULL;
	}
	c.deep = calloc((size_t)size * size, sizeof(float));
	c.fine = calloc((size_t)size * size, sizeof(float));
	if (c.deep && c.fine) {
		tmp = malloc((size_t)size * size * sizeof(float));
		img = tmp ? malloc((size_t)size * size * 4) : NULL;
	}
	if (img) {
		grow_all(&c);
		blur(c.deep, tmp, size, size / 512);
		blur(c.fine, tmp, size, size / 1024);
		shade(&c, img, seed);
	}
	free(tmp);
	free(c.deep);
	free(c.fine);
	return img;
}
