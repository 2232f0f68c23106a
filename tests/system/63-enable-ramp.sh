#!/bin/bash
# No step of force when a session starts: after enable, a constant command
# comes through as command x t / T over [limits] enable_ramp_s (T), then in
# full. Checked against that line on every published state a 200 Hz
# subscription sees: limited = command x ramp, and the ramp's slope in the
# states' own time stamps is 1 / T. Disabling drops the force at once; the
# next enable ramps again from nothing; T is live. (endoctl prints nine
# significant digits: the tolerances are that, not the daemon's.)
. "$(dirname "$0")/fault_lib.sh"

# the carriage pushed into its withdrawn end stop by a constant 10 N (the
# test command): it stays put, the command stays constant
check "simulated rig up, IDLE" start_daemon --set debug.test_commands=yes
check "a constant command of -10 N on the carriage" ctl debug force insertion -10

# ramp_run T: enable during a subscription, once it has seen a state
# (IDLE), then check its states; the subscription lasts 1.5 s past the
# ramp's T, however late the enable comes after the first state
ramp_run() {
	local T=$1 n
	rm -f "$TMP/ramp.json" # not the last run's IDLE
	ctl --json watch --rate 200 --duration $(awk -v t="$T" 'BEGIN { print t + 1.5 }') \
		>"$TMP/ramp.json" &
	local sub=$!
	wait_for grep -q IDLE "$TMP/ramp.json"
	ctl enable >/dev/null
	wait "$sub"
	jq -c '{s: .stamp_ns, st: .state, r: .ramp, c: .axes.insertion.command,
		l: .axes.insertion.limited}' "$TMP/ramp.json" >"$TMP/ramp.txt"
	check "T=$T s: IDLE before enable: no force" \
		jq -se 'map(select(.st == "IDLE")) | length > 0 and all(.l == 0)' "$TMP/ramp.txt"
	check "T=$T s: every state: limited = command x ramp" \
		jq -se 'all(.l - .c * .r | fabs < 1e-6)' "$TMP/ramp.txt"
	check "T=$T s: the ramp never falls" \
		jq -se 'map(select(.st == "ENABLED") | .r) | . == sort' "$TMP/ramp.txt"
	check "T=$T s: it starts from nothing (first state $(jq -s 'map(select(.st == "ENABLED"))[0].l' "$TMP/ramp.txt") N)" \
		jq -se 'map(select(.st == "ENABLED"))[0].r < 0.05' "$TMP/ramp.txt"
	n=$(jq -s 'map(select(.r > 0 and .r < 1)) | length' "$TMP/ramp.txt")
	check "T=$T s: gradual: $n states between nothing and full" \
		[ "$n" -ge "$(awk -v t="$T" 'BEGIN { print int(t * 100) }')" ]
	check "T=$T s: slope 1/T in the states' own time" \
		jq -se --argjson T "$T" '[.[] | select(.r > 0 and .r < 1)] |
			[range(1; length) as $i | [.[$i - 1], .[$i]] |
			 select(.[1].s > .[0].s) |
			 (.[1].r - .[0].r) / ((.[1].s - .[0].s) / 1e9) * $T - 1 | fabs]
			| length > 10 and all(. < 1e-5)' "$TMP/ramp.txt"
	check "T=$T s: then in full: -10 N" \
		jq -se 'last | .r == 1 and .l == -10' "$TMP/ramp.txt"
}

ramp_run "$(ctl get limits.enable_ramp_s)"
check "disable: the force drops at once" ctl disable
check "... zero" status_true '.axes.insertion.limited == 0'
check "the ramp time is live" ctl set limits.enable_ramp_s 0.4
ramp_run 0.4
check "no fault throughout" [ "$(status_field .fault_bits)" = 0 ]
finish
