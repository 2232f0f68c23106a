#!/bin/bash
# The haptics in the running daemon, the paper's model (the rod model's
# parts are checked in lockstep by tests/unit/test_rodcourse.c): on the
# shipped paper demo scenario the force
# loop publishes its haptic rendering (the god-object contact, each axis'
# force by its parts) in every state, and each axis' parts add up to the
# command it published. The behaviour of the rendering over the course
# (contact, friction, wire tension, the loop and its reduction, the clamp)
# depends on how many cycles ran: it is checked in lockstep, cycle for
# cycle, by tests/unit/test_course.c. Here every wait is on a state: the
# tip meets the rectal wall at 2.1 s of the course, on the scenario's own
# clock.
. "$(dirname "$0")/../common.sh"

# the insertion limited to 1 N (held beyond it as long as it likes), so
# that the wall's push in the rectum is clamped on its way to the rig
start_daemon --scenario "$TOP/config/scenarios/demo-paper.scn" \
	--set haptics.model=paper \
	--set limits.insertion_max_force_n=1 --set limits.saturation_s=60 ||
	finish
ctl enable >/dev/null
"$ENDOCTL" --socket "$SOCK" --json watch --rate 50 >"$TMP/trace.json" &
watch_pid=$!
check "the tip meets the wall (published contact)" \
	wait_for status_true '.haptics.contact'
WAIT_S=30 check "the course goes on to 4 s of its clock" \
	wait_for status_true '.scenario_time_s >= 4'
kill -TERM "$watch_pid"
wait "$watch_pid"
n=$(wc -l <"$TMP/trace.json")
check "the trace was recorded ($n states)" test "$n" -gt 50
q() { jq -s "$1" "$TMP/trace.json"; }
check "contact in the trace, with the wall pushing back" \
	test "$(q 'map(select(.haptics.contact and (.haptics.f_static | map(. * .) | add) > 0)) | length > 0')" = true
check "the parts of the insertion force add up to its command" \
	test "$(q 'map(.haptics.trans_contact_n + .haptics.trans_friction_n + .haptics.trans_loop_n + .haptics.damping[0] - .axes.insertion.command | fabs) | max < 1e-6')" = true
check "the parts of each wheel's torque add up to its command" \
	test "$(q 'map(. as $s | [0, 1] | map($s.haptics.wheel_contact_nm[.] + $s.haptics.wheel_tension_nm[.] + $s.haptics.wheel_elastic_nm[.] + $s.haptics.damping[2 + .]) as $sum | [$s.axes.wheel_ud.command - $sum[0], $s.axes.wheel_lr.command - $sum[1]] | map(fabs) | max) | max < 1e-6')" = true
check "commands beyond the 1 N limit, clamped to it on their way to the rig" \
	test "$(q 'map(select(.axes.insertion.command | fabs > 1.05)) | length > 0 and (map(.axes.insertion.limited | fabs) | max <= 1)')" = true
check "no fault" test "$(q 'map(.fault_bits) | max')" = 0
finish
