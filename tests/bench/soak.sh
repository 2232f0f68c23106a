#!/bin/bash
# soak.sh - the soak run of `make bench`: endosimd on the simulated rig for
# SOAK_SECONDS (default 600) with the soak scenario looping (every axis
# moving, config/scenarios/soak.scn), torque on, and clients subscribed the
# whole time (SOAK_CLIENTS at 100 Hz and one at 1000 Hz). Prints the force
# loop's overruns and wake-up latency (p99.9, max) over the soak, the
# daemon's resident memory at the start and the end (and in between), and
# whether a fault latched. A benchmark: it prints figures, judges nothing
# but whether the run itself went through.
set -u
. "$(dirname "$0")/../common.sh"

secs=${SOAK_SECONDS:-600}
clients=${SOAK_CLIENTS:-8}
samples=10

rss_kib() {
	awk '/^VmRSS:/ { print $2 }' "/proc/$DAEMON_PID/status"
}

echo "=== soak: ${secs} s on the simulated rig, the soak scenario looping, $clients clients at 100 Hz and one at 1000 Hz ==="
start_daemon --scenario "$TOP/config/scenarios/soak.scn" || exit 1
ctl enable >/dev/null
wait_for status_true '.ramp == 1'
pids=""
# endoctl itself in the background (not the ctl function): $! is its pid
for i in $(seq 1 "$clients"); do
	"$ENDOCTL" --socket "$SOCK" --json watch --rate 100 \
		--duration "$((secs + 5))" >/dev/null &
	pids="$pids $!"
done
"$ENDOCTL" --socket "$SOCK" --json watch --rate 1000 \
	--duration "$((secs + 5))" >/dev/null &
pids="$pids $!"
sleep 2 # everyone connected, buffers grown to their working size
ctl stats --reset >/dev/null
o0=$(status_field .overruns)
rss0=$(rss_kib)
series="$rss0"
for i in $(seq 1 "$samples"); do
	sleep "$(awk -v s="$secs" -v n="$samples" 'BEGIN { print s / n }')"
	series="$series $(rss_kib)"
done
rss1=$(rss_kib)
o1=$(status_field .overruns)
ctl --json stats >"$TMP/soak-stats.json"
ctl --json status >"$TMP/soak-status.json"
hwm=$(awk '/^VmHWM:/ { print $2 }' "/proc/$DAEMON_PID/status")
kill $pids 2>/dev/null
wait $pids 2>/dev/null
read -r cycles p50 p99 p999 max < <(jq -r '[.cycles, .latency.p50_us,
	.latency.p99_us, .latency.p999_us, .latency.max_us] | @tsv' \
	"$TMP/soak-stats.json")
read -r state faults scn < <(jq -r '[.state, .fault_bits,
	.scenario_time_s] | @tsv' "$TMP/soak-status.json")
echo "loop: $cycles cycles since start, overruns during the soak: $((o1 - o0))"
printf 'wake-up latency over the soak (us): p50 %.0f, p99 %.0f, p99.9 %.0f, max %.1f\n' \
	"$p50" "$p99" "$p999" "$max"
echo "daemon RSS (KiB): start $rss0, end $rss1, growth $((rss1 - rss0)); peak $hwm"
echo "  every $((secs / samples)) s: $series"
echo "state at the end: $state, fault bits $faults, scenario at ${scn} s (looping)"
stop_daemon
