/*
 * shm_probe - a separate process reading endosimd's shared memory, as the
 * viewer does: checks that every copy is consistent and that the state
 * advances. Used by the system tests.
 *
 *   shm_probe NAME [COUNT [INTERVAL_US]]   read COUNT states (default 200)
 *   shm_probe NAME --once                  print one state as key=value
 *   shm_probe NAME --valves MASK VALUE TIMEOUT_S
 *                                          read every state (every 50 us)
 *                                          until the patient's valves & MASK
 *                                          are VALUE; print that first state
 *                                          as --once does, and the state
 *                                          before it as before.KEY=VALUE
 *                                          (they must not be so at first:
 *                                          "watching" once it has read
 *                                          the first state, to wait for)
 *   shm_probe NAME --tool DEPTH_MM OPENING_PC PEDAL TIMEOUT_S
 *                                          the same until the tool in the
 *                                          working channel reads DEPTH_MM
 *                                          mm deep, OPENING_PC % open
 *                                          (rounded) and PEDAL (0, 1)
 *
 * Exit 0 when every read was consistent and the cycle advanced (--valves,
 * --tool: when the state came so in time), 1 otherwise.
 */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "proto/names.h"
#include "proto/shm_reader.h"

/* The patient's valves and gas, the tool in the working channel, the
 * axes' drives: what --valves and --tool wait on. */
static void print_valves(const char *pre, const struct endosim_state *st)
{
	const struct endosim_patient_state *p = &st->patient;

	printf("%sstamp_ns=%llu\n%spatient.valves=%u\n%spatient.gas_m3=%.9g\n"
	       "%spatient.gas_in_m3=%.9g\n%spatient.pressure_pa=%.9g\n", pre,
	       (unsigned long long)st->stamp_ns, pre, p->valves, pre,
	       p->gas_m3, pre, p->gas_in_m3, pre, p->pressure_pa);
	printf("%stool.depth_m=%.9g\n%stool.opening=%.9g\n%stool.pedal=%u\n",
	       pre, st->tool.depth_m, pre, st->tool.opening, pre,
	       st->tool.pedal);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		printf("%s%s.drive_status=%u\n", pre, names_axis(a),
		       st->axis[a].drive_status);
	}
}

static void print_once(const struct endosim_state *st)
{
	printf("cycle=%llu\nstate=%s\nfault_bits=%u\n",
	       (unsigned long long)st->cycle, names_state(st->state),
	       st->fault_bits);
	print_valves("", st);
	for (int a = 0; a < ENDOSIM_AXES; a++) {
		printf("%s.position=%.9g\n%s.limited=%.9g\n", names_axis(a),
		       st->axis[a].position, names_axis(a),
		       st->axis[a].limited);
	}
	printf("tool.loop_m=%.9g\ntool.tip=%.9g,%.9g,%.9g\n"
	       "tool.loop_centre=%.9g,%.9g,%.9g\n", st->tool.loop_m,
	       st->tool.tip[0], st->tool.tip[1], st->tool.tip[2],
	       st->tool.loop_centre[0], st->tool.loop_centre[1],
	       st->tool.loop_centre[2]);
	printf("guide.phase=%s\nguide.expert_kind=%s\n"
	       "guide.expert_depth_m=%.9g\nguide.expert_opening=%.9g\n"
	       "guide.expert_pedal=%u\nguide.expert_tip=%.9g,%.9g,%.9g\n",
	       names_guide_phase(st->guide.phase),
	       names_tool(st->guide.expert_kind), st->guide.expert_depth_m,
	       st->guide.expert_opening, st->guide.expert_pedal,
	       st->guide.expert_tip[0], st->guide.expert_tip[1],
	       st->guide.expert_tip[2]);
	printf("scope.depth_m=%.9g\nscope.tip_s_m=%.9g\nscope.spans=%u\n",
	       st->scope.depth_m, st->scope.tip_s_m, st->scope.spans);
	printf("scope.tip=%.6f,%.6f,%.6f\n", st->scope.tip[0],
	       st->scope.tip[1], st->scope.tip[2]);
	/* the tube's last point is the tip, its first the anal verge */
	printf("scope.tube_last=%.6f,%.6f,%.6f\n",
	       st->scope.tube[ENDOSIM_TUBE_POINTS - 1][0],
	       st->scope.tube[ENDOSIM_TUBE_POINTS - 1][1],
	       st->scope.tube[ENDOSIM_TUBE_POINTS - 1][2]);
	printf("scope.tube_first=%.6f,%.6f,%.6f\n", st->scope.tube[0][0],
	       st->scope.tube[0][1], st->scope.tube[0][2]);
}

/* Checks a copy against its own invariants and against the previous one. */
static const char *check(const struct endosim_state *st,
			 const struct endosim_state *prev)
{
	if (st->publish_ns < st->stamp_ns) {
		return "published before its own cycle";
	}
	if (st->state > ENDOSIM_STATE_FAULT) {
		return "unknown state";
	}
	if (prev && (st->cycle < prev->cycle || st->stamp_ns < prev->stamp_ns)) {
		return "went backwards";
	}
	if (prev && st->cycle == prev->cycle &&
	    memcmp(st, prev, sizeof(*st)) != 0) {
		return "same cycle, different contents";
	}
	return NULL;
}

/* What a watch waits for: the state is so. */
struct watch {
	bool (*there)(const struct watch *w, const struct endosim_state *st);
	char *const *arg; /* the command line's, after the option */
};

/* --valves MASK VALUE */
static bool valves_there(const struct watch *w, const struct endosim_state *st)
{
	uint32_t mask = (uint32_t)strtoul(w->arg[0], NULL, 0);

	return (st->patient.valves & mask) ==
	       (uint32_t)strtoul(w->arg[1], NULL, 0);
}

/* One of --tool's readings: WANT is SCALE times the published VALUE,
 * rounded. */
static bool tool_reads(const char *want, double value, double scale)
{
	return isfinite(value) && lround(value * scale) == atol(want);
}

/* --tool DEPTH_MM OPENING_PC PEDAL */
static bool tool_there(const struct watch *w, const struct endosim_state *st)
{
	return tool_reads(w->arg[0], st->tool.depth_m, 1e3) &&
	       tool_reads(w->arg[1], st->tool.opening, 1e2) &&
	       st->tool.pedal == (uint32_t)atoi(w->arg[2]);
}

/* The first state that is as W waits for, and the one before it. */
static int watch(struct shm_reader *r, const struct watch *w,
		 const char *timeout_s)
{
	struct timespec nap = { .tv_nsec = 50000 }, now;
	struct endosim_state st, prev = { 0 };
	bool have_prev = false;
	double end_s;

	clock_gettime(CLOCK_MONOTONIC, &now);
	end_s = (double)now.tv_sec + now.tv_nsec * 1e-9 + atof(timeout_s);
	do {
		if (!shm_reader_read(r, &st, 1000)) {
			bool there = w->there(w, &st);

			if (there && !have_prev) {
				fprintf(stderr, "shm_probe: the state was so "
					"before the watch began\n");
				return 1;
			}
			if (there) {
				print_once(&st);
				print_valves("before.", &prev);
				return 0;
			}
			if (!have_prev) {
				printf("watching\n");
				fflush(stdout);
			}
			prev = st;
			have_prev = true;
		}
		nanosleep(&nap, NULL);
		clock_gettime(CLOCK_MONOTONIC, &now);
	} while ((double)now.tv_sec + now.tv_nsec * 1e-9 < end_s);
	fprintf(stderr, "shm_probe: not so in time: valves %u, tool %g m "
		"deep, %g open, pedal %u\n", prev.patient.valves,
		prev.tool.depth_m, prev.tool.opening, prev.tool.pedal);
	return 1;
}

int main(int argc, char **argv)
{
	struct endosim_state st, prev;
	struct shm_reader *r;
	long count = 200, interval_us = 1000;
	const char *why;

	if (argc < 2) {
		fprintf(stderr, "usage: shm_probe NAME [COUNT [INTERVAL_US]] | "
			"NAME --once | NAME --valves MASK VALUE TIMEOUT_S | "
			"NAME --tool DEPTH_MM OPENING_PC PEDAL TIMEOUT_S\n");
		return 2;
	}
	r = shm_reader_open(argv[1]);
	if (!r) {
		fprintf(stderr, "shm_probe: %s: %s\n", argv[1], strerror(errno));
		return 1;
	}
	if ((argc > 5 && !strcmp(argv[2], "--valves")) ||
	    (argc > 6 && !strcmp(argv[2], "--tool"))) {
		bool valves = !strcmp(argv[2], "--valves");
		struct watch w = { valves ? valves_there : tool_there,
				   argv + 3 };
		int rc = watch(r, &w, argv[valves ? 5 : 6]);

		shm_reader_close(r);
		return rc;
	}
	if (argc > 2 && !strcmp(argv[2], "--once")) {
		int err = shm_reader_read(r, &st, 1000);

		if (!err) {
			print_once(&st);
		}
		shm_reader_close(r);
		return err ? 1 : 0;
	}
	if (argc > 2) {
		count = atol(argv[2]);
	}
	if (argc > 3) {
		interval_us = atol(argv[3]);
	}
	struct timespec nap = { .tv_nsec = interval_us * 1000 };
	uint64_t first = 0;

	for (long i = 0; i < count; i++) {
		why = shm_reader_read(r, &st, 1000) ? "no consistent copy"
						     : check(&st, i ? &prev : NULL);
		if (why) {
			fprintf(stderr, "shm_probe: read %ld: %s\n", i, why);
			shm_reader_close(r);
			return 1;
		}
		first = i ? first : st.cycle;
		prev = st;
		nanosleep(&nap, NULL);
	}
	printf("reads %ld, cycles %llu..%llu, writer pid %d\n", count,
	       (unsigned long long)first, (unsigned long long)st.cycle,
	       shm_reader_header(r)->writer_pid);
	shm_reader_close(r);
	return st.cycle > first ? 0 : 1;
}
