#!/bin/bash
# Load on the control thread does not reach the force loop: twenty clients
# subscribed at 200 Hz while commands keep arriving leave the loop's
# overruns and wake-up latency within noise of a quiet run, and every
# command is answered.
#
# "Within noise" on a shared VM: a starved or blocked loop shows up as
# millisecond latencies and hundreds of overruns in a 3 s window; the
# bounds (p99 at most twice the quiet one plus 250 us, at most 30 more
# overruns) tell that apart from the tens to hundreds of microseconds this
# machine's scheduling jitter adds between two windows. Under the
# sanitizers (SANITIZED=1) the twenty clients are instrumented processes
# that load both CPUs far more than real ones would, so there the loaded
# window's numbers are printed but not checked (and no quiet window is
# measured to compare them with): that run is for memory errors, and the
# plain build checks the timing. A stall of the VM that falls in a loaded
# window looks like load, so there are up to three rounds (below).
. "$(dirname "$0")/../common.sh"

window=3
start_daemon --scenario "$TOP/config/scenarios/demo.scn" || finish
ctl enable >/dev/null
measure() { # -> "p99_us overruns" over the next $window seconds
	local o0 o1
	ctl stats --reset >/dev/null
	o0=$(status_field .overruns)
	sleep "$window"
	o1=$(status_field .overruns)
	echo "$(ctl --json stats | jq .latency.p99_us) $((o1 - o0))"
}
# load: the twenty subscribers and the commands, for one window
load() {
	local pids="" i
	for i in $(seq 1 20); do
		ctl --json watch --rate 200 --duration $((window + 1)) \
			>"$TMP/sub$i" &
		pids="$pids $!"
	done
	(
		ok=0
		for i in $(seq 1 60); do
			ctl set limits.insertion_max_force_n $((30 + i % 10)) >/dev/null && ok=$((ok + 1))
			ctl status >/dev/null && ok=$((ok + 1))
		done
		echo "$ok" >"$TMP/answered"
	) &
	pids="$pids $!"
	read -r load_p99 load_over < <(measure)
	# shellcheck disable=SC2086
	wait $pids
}
p99_within() {
	awk -v l="$load_p99" -v q="$quiet_p99" 'BEGIN { exit !(l <= 2 * q + 250) }'
}
overruns_within() {
	[ "$load_over" -le $((quiet_over + 30)) ]
}
# A stall of the VM (steal from a busy host: 100-150 ms, seen every ~10 s
# on a bad day) in one window looks like load. A loop that load reaches
# fails every round; a stall rarely falls in three loaded windows running,
# so up to three rounds of a quiet window and a loaded one, each printed.
for round in 1 2 3; do
	if [ -n "${SANITIZED:-}" ]; then
		quiet_p99=- quiet_over=- # nothing to compare
	else
		read -r quiet_p99 quiet_over < <(measure)
	fi
	load
	echo "# round $round: quiet: p99 ${quiet_p99} us, ${quiet_over} overruns; loaded: p99 ${load_p99} us, ${load_over} overruns"
	if [ -n "${SANITIZED:-}" ] || { p99_within && overruns_within; }; then
		break
	fi
done
check "every command answered (120 of 120)" test "$(cat "$TMP/answered")" = 120
check "every subscriber got its pushes" test "$(for i in $(seq 1 20); do wc -l <"$TMP/sub$i"; done | sort -n | head -n 1)" -ge 100
if [ -z "${SANITIZED:-}" ]; then
	check "loop latency p99 within noise (${load_p99} us vs ${quiet_p99} us quiet, round $round)" \
		p99_within
	check "overruns within noise (${load_over} vs ${quiet_over} quiet, round $round)" \
		overruns_within
else
	echo "# sanitized build: the timing bounds are checked in the plain build"
fi
check "no fault" test "$(status_field .fault_bits)" = 0
finish
