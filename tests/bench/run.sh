#!/bin/bash
# run.sh - `make bench`: the figures the issues ask for. Benchmarks, not
# tests: they print numbers and judge nothing.
#
#   BENCH_SECONDS   duration of the loop-latency runs (default 30)
#   SOAK_SECONDS    duration of the soak run (default 600)
#   FUZZ_SECONDS    each fuzz target's run (default 60)
#
# 1. Force-loop wake-up latency next to cyclictest's, both at SCHED_FIFO 80
#    and 1 kHz, run at the same time on the same machine, their
#    percentiles computed the same way (1 us histogram bins), with the rod
#    model and with the paper's; the loop's compute time; the
#    shared-memory publish-to-read latency seen by a reader process.
# 2. The colon model: build time, memory, query and kinematics cost
#    (bench_colon). The training metrics' occlusion-aware coverage
#    (bench_metrics): a 10-minute 1 kHz session replayed, per evaluated
#    pose and per second of session; and `endoctl session report` of a
#    scripted session at 1 kHz (session_script) end to end.
# 3. The force loop's cycle over the demo scenario on the normal case: the
#    rod model at 80, 160 and 320 segments (and at 160 with the
#    patient's body: the gas, gravity, fluid, lens and the hand, and
#    then the patient's response alone per cycle, pain_step() and with
#    the vital signs and the tear, next to its 5 us), the
#    paper's model on its own demo, and the rod at about 2 million
#    triangles; the forces the hand feels next to Appleyard's; the tip's
#    contact force's change per cycle while it slides (bench_haptics).
#    The patient on the demo course (the scripted trainee's,
#    test_rodcourse: its line of figures): the gas
#    used a minute next to Bretthauer's 0.25 L/min, the pressure's range
#    with the tip free next to Kozarek's 9-57 mmHg. The patient's pain
#    (test_separation, all four cases): the time in pain and the peak of
#    the scripted expert, the novice and the novice deeply sedated, and
#    the pain episodes' split by place and cause next to Shah et al.'s. Not at SCHED_FIFO: a
#    process that never sleeps is throttled there by the kernel's
#    real-time bandwidth limit (50 ms of every second,
#    sched_rt_runtime_us), which is not the daemon's case (it sleeps
#    between cycles).
#    The tools' model (bench_tool): tool_step()'s cost per cycle, a
#    snare on the polyps case's tip withdrawn along its centreline and
#    the most a step does (32 stalks in the loop), next to its 10 us.
#    The scripted resection of the polyps case (test_resection): each
#    polyp's times as she aims the tools herself (found, aimed, lifted,
#    cut: found to free; a small one's retrieval by suction from its
#    cut) and from the first touch to free, the mean, the cautery, the
#    injections' and the stump's clip's times, next to the published
#    resection, clip and injection times.
# 4. The drives: exchange rates and transaction latency against the
#    emulators (drives.sh).
# 5. The viewer's frame times and the age of the state it shows
#    (tests/bench/viewer.sh).
# 6. The rig's records at scale: 10 000 sessions of 50 trainees, endoctl's
#    trainee list, trainee report and session list timed
#    (tests/bench/records.sh).
set -u
. "$(dirname "$0")/../common.sh"

SECONDS_RUN=${BENCH_SECONDS:-30}
PRIO=80

# percentiles of a cyclictest histogram ("bin count" lines, 1 us bins)
cyclictest_percentiles() {
	awk '/^[0-9]+ +[0-9]+/ { n[$1 + 0] = $2; total += $2; if ($1 + 0 > top) top = $1 + 0 }
	     /^# Max Latencies:/ { max = $4 + 0 }
	     END {
		split("0.50 0.99 0.999", q, " ");
		for (k = 1; k <= 3; k++) {
			need = int(total * q[k] + 0.5); if (need < 1) need = 1;
			seen = 0;
			for (i = 0; i <= top; i++) { seen += n[i]; if (seen >= need) { p[k] = i; break } }
		}
		printf "%d %d %d %d %d\n", p[1], p[2], p[3], max, total
	     }' "$1"
}

# loop_vs_cyclictest MODEL: one run of each at the same time
loop_vs_cyclictest() {
	local model=$1
	echo "=== force loop ($model model) vs cyclictest: ${SECONDS_RUN} s each, at the same time, SCHED_FIFO $PRIO, 1 kHz ==="
	start_daemon --set loop.priority=$PRIO --set haptics.model="$model" ||
		exit 1
	cyclictest -m -p $PRIO -i 1000 -D "$SECONDS_RUN" -h 10000 -q >"$TMP/cyclictest.out" 2>&1 &
	ct=$!
	sleep "$SECONDS_RUN"
	wait $ct
	ctl --json stats >"$TMP/stats.json"
	read -r c50 c99 c999 cmax ctotal < <(cyclictest_percentiles "$TMP/cyclictest.out")
	read -r cycles overruns policy prio l50 l99 l999 lmax lcount k50 k99 k999 kmax < <(
		jq -r '[.cycles, .overruns, .rt_policy, .rt_priority,
			.latency.p50_us, .latency.p99_us, .latency.p999_us, .latency.max_us,
			.latency.count, .compute.p50_us, .compute.p99_us,
			.compute.p999_us, .compute.max_us] | @tsv' "$TMP/stats.json")
	ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.2f", a / b; else printf "n/a" }'; }
	echo "policy $policy $prio; loop cycles $cycles, overruns $overruns"
	printf '%-22s %7s %7s %7s %9s %9s\n' "wake-up latency (us)" p50 p99 p99.9 max samples
	printf '%-22s %7.0f %7.0f %7.0f %9.1f %9d\n' "  endosimd" "$l50" "$l99" "$l999" "$lmax" "$lcount"
	printf '%-22s %7d %7d %7d %9d %9d\n' "  cyclictest" "$c50" "$c99" "$c999" "$cmax" "$ctotal"
	printf '%-22s %7s %7s %7s %9s   (goal: p99 <= 1.20)\n' "  ratio ours/theirs" \
		"$(ratio "$l50" "$c50")" "$(ratio "$l99" "$c99")" \
		"$(ratio "$l999" "$c999")" "$(ratio "$lmax" "$cmax")"
	printf 'loop compute time (us): p50 %.0f, p99 %.0f, p99.9 %.0f, max %.1f\n' \
		"$k50" "$k99" "$k999" "$kmax"
	echo "(endosimd's figures cover the whole daemon run, start-up included; 1 us bins, a percentile is the bin it falls in)"
	[ "$model" = rod ] && "$TOOLS/shm_latency" "$SHM" 5
	stop_daemon
}
loop_vs_cyclictest rod
echo
loop_vs_cyclictest paper

echo
echo "=== colon model and kinematics ==="
"$BUILD/tests/bench_colon" "$TOP/config/cases"

echo
echo "=== the metrics' occlusion-aware coverage (the depth test on the CPU) ==="
"$BUILD/tests/bench_metrics" "$TOP/config/cases/normal.case"
"$BUILD/tests/session_script" --rate 1000 --ring 192 \
	"$TOP/config/cases/polyps.case" "$TMP/long.endoses" >/dev/null
dur=$("$ENDOCTL" session show "$TMP/long.endoses" | awk '/^duration/ { print $2 }')
t0=$EPOCHREALTIME
"$ENDOCTL" session report "$TMP/long.endoses" --out "$TMP/long-report" >/dev/null
awk -v a="$t0" -v b="$EPOCHREALTIME" -v d="$dur" 'BEGIN {
	printf "endoctl session report of a scripted %.0f s session at 1 kHz (polyps case, 192 a ring): %.2f s (%.2f s per 10 minutes of session)\n", d, b - a, (b - a) / d * 600 }'
rm -f "$TMP/long.endoses"

CASE=$TOP/config/cases/normal.case
for segments in 80 160 320; do
	echo
	echo "=== the loop's cycle on the demo: the rod model, $segments segments ==="
	"$BUILD/tests/bench_haptics" --segments $segments "$CASE" \
		"$TOP/config/scenarios/demo.scn"
done
echo
echo "=== the loop's cycle on the demo: the rod, 160 segments, the patient (goal: p99 <= 250 us); the pain model's (goal: p99 <= 5 us) ==="
"$BUILD/tests/bench_haptics" --segments 160 --patient "$CASE" \
	"$TOP/config/scenarios/demo.scn"
echo
echo "=== the patient on the demo course: the gas used, the pressure (test_rodcourse) ==="
ENDOSIM_TOP=$TOP "$BUILD/tests/test_rodcourse" 2>&1 | grep '^the patient: '
echo "=== the patient's pain: expert and novice on every case, the split next to Shah's (test_separation) ==="
ENDOSIM_TOP=$TOP ENDOSIM_PAINRUN_FULL=1 "$BUILD/tests/test_separation" \
	2>&1 | grep -E '^# (config/|  |pain episodes|by cause)'
echo
echo "=== the tools' model: a snare on the polyps case, and 32 stalks in its loop (goal: p99 <= 10 us) ==="
"$BUILD/tests/bench_tool" "$TOP/config/cases/polyps.case"
echo
echo "=== the scripted resection of the polyps case (test_resection): each polyp's times (aimed; found to free; first touch to free), next to the published ==="
echo "published: resection 24 +/- 18 s (rotary snare), 30 +/- 26 s (standard snare); the hemostasis trainer's experts and beginners: clip 20 vs 73 s, injection 36 vs 92 s"
ENDOSIM_TOP=$TOP "$BUILD/tests/test_resection" 2>&1 |
	grep -E '^(polyp [0-9]+:|the expert:|the stalk|the channel)'
echo
echo "=== the loop's cycle on the paper model's demo, force shading on and off ==="
"$BUILD/tests/bench_haptics" --model paper "$CASE" \
	"$TOP/config/scenarios/demo-paper.scn"
"$BUILD/tests/bench_haptics" --model paper --no-shading "$CASE" \
	"$TOP/config/scenarios/demo-paper.scn"
echo
echo "=== the rod at about 2 million triangles (ring 1360, step 0.002 m) ==="
"$BUILD/tests/bench_haptics" --ring 1360 --step 0.002 "$CASE" \
	"$TOP/config/scenarios/demo.scn"

echo
echo "=== drives against the emulators ==="
BUILD=$BUILD "$TOP/tests/bench/drives.sh"

echo
BUILD="$BUILD" bash "$TOP/tests/bench/viewer.sh"

echo
BUILD="$BUILD" bash "$TOP/tests/bench/records.sh"

# The soak: the loop and the daemon's memory over a long run with the
# scenario looping and clients subscribed (tests/bench/soak.sh).
echo
"$TOP/tests/bench/soak.sh"

# The fuzzers: executions and coverage of each target in its time.
echo
echo "=== fuzzers: ${FUZZ_SECONDS:-60} s each (make fuzz) ==="
FUZZ_SECONDS=${FUZZ_SECONDS:-60} "$TOP/tests/fuzz/run.sh" "$BUILD/fuzz"
