#!/bin/bash
# Fault: the force loop's overrun budget exceeded ([loop] overrun_budget
# periods skipped within overrun_window_s). The loop is stalled by the test
# command: on the simulated rig, the first cycle after the stall latches
# the fault with torque zero on every axis; on the Modbus line the bus
# thread does not wait for that: commands older than the bus' allowed age
# bring the drives down while the loop is still stalled. The daemon answers
# throughout; reset is refused until the window has passed.
#
# The budget: the 1000 periods (the most) that common.sh gives every test,
# more than the stalls of a busy VM add up to (a budget of 200 was reached
# by a VM that skipped 140 periods a second on a bad day); the stalls, 1.5
# s and 4 s, exceed it. The window is widened to 3 s on the simulated rig so
# that "refused within the window" does not depend on how fast a loaded
# machine runs the checks. The Modbus stall outlasts the wait for the
# drives to stop however slowly the emulator answers.
. "$(dirname "$0")/fault_lib.sh"

window_s=3
check "simulated rig up, enabled, every axis moving" \
	start_sim --set loop.overrun_window_s=$window_s
budget=$(ctl get loop.overrun_budget)
watch_fault 0x10
check "the loop stalled for 1.5 s" ctl debug stall 1.5
check "the daemon answers while its loop is stalled" ctl status
check "sim stall: FAULT once the loop runs again" wait_for state_is FAULT
check "sim stall: reset refused within the ${window_s} s window" reset_refused
expect_fault "sim stall" overrun-budget none "skipped" "budget of $budget"
check "sim stall: about 1500 periods counted ($(watched fault_value))" \
	awk -v v="$(watched fault_value)" -v b="$budget" \
	'BEGIN { exit !(v > b && v >= 1400 && v <= 3000) }'
recovers "sim stall"
stop_daemon

check "Modbus rig up, enabled" start_mb_rig
watch_fault 0x10
check "the loop stalled for 4 s" ctl debug stall 4
cycle=$(status_field .cycle)
check "Modbus stall: the wheel drives stop while the loop is stalled" \
	wait_for wheels_off
check "Modbus stall: ... the loop had not run meanwhile" \
	[ "$(status_field .cycle)" = "$cycle" ]
expect_fault "Modbus stall" overrun-budget none "skipped"
check "Modbus stall: the bus says why it stopped" \
	grep -q "no command from the force loop" "$LOG"
recovers "Modbus stall"
check "Modbus stall: the wheels run again" wait_for wheels_on
finish
