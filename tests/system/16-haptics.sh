#!/bin/bash
# The shipped demo scenario on the simulated rig (its first 32 s: inserting
# through the rectum and sigmoid, then pushing a straight tip into the
# splenic flexure): contact, friction, wire tension and a loop all happen,
# in the published state, and each axis' parts add up to its command.
. "$(dirname "$0")/../common.sh"

start_daemon --scenario "$TOP/config/scenarios/demo.scn" || finish
ctl enable >/dev/null
# 32 s of the course on its own clock: the simulated rig steps it once per
# force-loop cycle, so a stall of this machine that skips periods slows it
"$ENDOCTL" --socket "$SOCK" --json watch --rate 50 >"$TMP/trace.json" &
watch_pid=$!
WAIT_S=90 wait_for status_true '.scenario_time_s >= 32'
kill -TERM "$watch_pid"
wait "$watch_pid"
n=$(wc -l <"$TMP/trace.json")
check "the trace was recorded ($n states)" test "$n" -gt 500
q() { jq -s "$1" "$TMP/trace.json"; }
check "the tip touched the wall" test "$(q 'map(select(.haptics.contact)) | length > 10')" = true
check "the wall pushed back (F_static above 1 N)" \
	test "$(q 'map(.haptics.f_static | map(. * .) | add | sqrt) | max > 1')" = true
check "insertion friction, growing with the tube's turning" \
	test "$(q '[.[] | select(.scope.depth_m > 0.4)] | map(.haptics.trans_friction_n | fabs) | max > 0.5')" = true
check "curvature integral above 2 rad deep in" \
	test "$(q 'map(.haptics.curvature_rad) | max > 2')" = true
check "wire tension on the wheels" \
	test "$(q 'map(.haptics.wheel_tension_nm[] | fabs) | max > 0.002')" = true
check "a loop formed (the sigmoid bowed over 10 mm)" \
	test "$(q 'map(.scope.bow_m[0]) | max > 0.01')" = true
check "the loop carried insertion force" \
	test "$(q 'map(.haptics.trans_loop_n) | min < -1')" = true
check "withdrawing reduced it again" \
	test "$(q '.[-1].scope.bow_m[0] < 0.005')" = true
check "the parts of the insertion force add up to its command" \
	test "$(q 'map(.haptics.trans_contact_n + .haptics.trans_friction_n + .haptics.trans_loop_n + .haptics.damping[0] - .axes.insertion.command | fabs) | max < 1e-6')" = true
check "the parts of each wheel's torque add up to its command" \
	test "$(q 'map(. as $s | [0, 1] | map($s.haptics.wheel_contact_nm[.] + $s.haptics.wheel_tension_nm[.] + $s.haptics.wheel_elastic_nm[.] + $s.haptics.damping[2 + .]) as $sum | [$s.axes.wheel_ud.command - $sum[0], $s.axes.wheel_lr.command - $sum[1]] | map(fabs) | max) | max < 1e-6')" = true
check "nothing beyond the limits reached the drives" \
	test "$(q 'map(.axes.insertion.limited | fabs) | max <= 45')" = true
check "no fault" test "$(q 'map(.fault_bits) | max')" = 0
finish
