/*
 * bench_colon.c - what the colon model and the scope's kinematics cost.
 *
 *   build/tests/bench_colon [CASES_DIR]     (default config/cases)
 *
 * For every case: the time to build it at the default resolution and at
 * about 2 million triangles, and the memory the model holds. Then, on the
 * normal case at the default resolution: one "triangles near s" query
 * (mesh_range over +-2 cm, timed in batches of 1000 because one query is
 * shorter than the clock's resolution), one kinematics update
 * (scope_update: tip, Jacobian, 128-point tube) and one bow of the sigmoid
 * with and without moving its mesh; p50 and p99 in ns.
 */
#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "model/colon.h"
#include "model/scope.h"

#define RUNS 20000
#define BATCH 1000

static uint64_t now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * ENDOSIM_NS_PER_S + (uint64_t)ts.tv_nsec;
}

static int cmp_u64(const void *a, const void *b)
{
	uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;

	return x < y ? -1 : x > y;
}

static void report(const char *what, uint64_t *ns, size_t n, double per)
{
	qsort(ns, n, sizeof(*ns), cmp_u64);
	printf("%-40s p50 %8.0f ns   p99 %8.0f ns\n", what,
	       (double)ns[n / 2] / per, (double)ns[n * 99 / 100] / per);
}

static struct colon *build(const struct anatomy *a, double step,
			   uint32_t ring, double *ms)
{
	struct colon_params p = COLON_PARAMS_DEFAULT;
	char err[256];
	uint64_t t0 = now_ns();
	struct colon *c;

	p.step_m = step;
	p.ring_vertices = ring;
	c = colon_create(a, &p, err, sizeof(err));
	*ms = (double)(now_ns() - t0) / 1e6;
	if (!c) {
		fprintf(stderr, "bench_colon: %s\n", err);
	}
	return c;
}

static void bench_builds(const char *dir)
{
	DIR *d = opendir(dir);
	struct dirent *e;

	if (!d) {
		perror(dir);
		exit(1);
	}
	printf("%-20s %12s %10s %10s\n", "case", "triangles", "build ms",
	       "MiB");
	while ((e = readdir(d))) {
		const double step[2] = { 0.002, 0.001 };
		const uint32_t ring[2] = { 192, 672 };
		size_t len = strlen(e->d_name);
		char path[1024], err[256];
		struct anatomy a;

		if (len < 6 || strcmp(e->d_name + len - 5, ".case")) {
			continue;
		}
		snprintf(path, sizeof(path), "%s/%s", dir, e->d_name);
		if (anatomy_load(&a, path, err, sizeof(err))) {
			fprintf(stderr, "bench_colon: %s\n", err);
			exit(1);
		}
		for (int r = 0; r < 2; r++) {
			double ms;
			struct colon *c = build(&a, step[r], ring[r], &ms);

			if (!c) {
				exit(1);
			}
			printf("%-20s %12u %10.1f %10.1f\n", a.name,
			       colon_mesh(c)->triangles, ms,
			       (double)colon_bytes(c) / (1 << 20));
			colon_destroy(c);
		}
	}
	closedir(d);
}

static void bench_queries(const struct colon *c, uint64_t *ns)
{
	const struct mesh *m = colon_mesh(c);
	double len = centreline_length(colon_centreline(c));
	volatile uint64_t sink = 0;

	for (int r = 0; r < RUNS / 10; r++) {
		uint64_t t0 = now_ns();

		for (int k = 0; k < BATCH; k++) {
			double s = len * ((k * 7919 + r) % 1000) / 1000.0;
			uint32_t first, count;

			mesh_range(m, s - 0.02, s + 0.02, &first, &count);
			sink += count;
		}
		ns[r] = now_ns() - t0;
	}
	report("triangles near s (mesh_range)", ns, RUNS / 10, BATCH);
	printf("%-40s %u triangles on average\n", "",
	       (unsigned)(sink / (RUNS / 10 * BATCH)));
}

static void bench_scope(const struct colon *c, uint64_t *ns)
{
	const struct scope_params p = SCOPE_PARAMS_DEFAULT;
	struct scope_pose *pose = malloc(sizeof(*pose));
	double len = centreline_total_arclength(colon_centreline(c));

	for (int r = 0; r < RUNS; r++) {
		struct scope_input in = { len * (r % 997) / 997.0,
					  0.001 * (r % 3000),
					  0.5 * sin(r * 0.01),
					  0.4 * cos(r * 0.013) };
		uint64_t t0 = now_ns();

		scope_update(&p, colon_centreline(c), &in, pose);
		ns[r] = now_ns() - t0;
	}
	report("kinematics update (scope_update)", ns, RUNS, 1);
	free(pose);
}

static void bench_bow(struct colon *c, uint64_t *ns, bool place)
{
	for (int r = 0; r < RUNS / 10; r++) {
		uint64_t t0 = now_ns();

		colon_bow(c, 0, 0.06 * (r % 100) / 100.0, place);
		ns[r] = now_ns() - t0;
	}
	report(place ? "bow sigmoid + move its mesh" : "bow sigmoid (centreline)",
	       ns, RUNS / 10, 1);
	colon_bow(c, 0, 0, true);
}

int main(int argc, char **argv)
{
	const char *dir = argc > 1 ? argv[1] : "config/cases";
	uint64_t *ns = malloc(RUNS * sizeof(*ns));
	char path[1024], err[256];
	struct anatomy a;
	struct colon *c;
	double ms;

	bench_builds(dir);
	snprintf(path, sizeof(path), "%s/normal.case", dir);
	if (anatomy_load(&a, path, err, sizeof(err))) {
		fprintf(stderr, "bench_colon: %s\n", err);
		return 1;
	}
	c = build(&a, 0.002, 192, &ms);
	if (!c) {
		return 1;
	}
	printf("\nnormal, %u triangles, %u segments of %.0f mm:\n",
	       colon_mesh(c)->triangles, colon_mesh(c)->segments,
	       colon_mesh(c)->segment_m * 1000);
	bench_queries(c, ns);
	bench_scope(c, ns);
	bench_bow(c, ns, false);
	bench_bow(c, ns, true);
	colon_destroy(c);
	free(ns);
	return 0;
}
