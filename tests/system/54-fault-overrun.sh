#!/bin/bash
# Fault: the force loop's overrun budget exceeded ([loop] overrun_budget
# periods skipped within overrun_window_s). The loop is stalled by the test
# command. On the simulated rig a missed budget is only a warning by
# default ([loop] overrun_fault = auto): torque stays on, the cause is
# published as present while the window holds it, the journal says so.
# Told to fault (overrun_fault = yes), the first cycle after the stall
# latches the fault with torque zero on every axis; with a real drive
# (the Modbus wheels) auto makes it a fault: on the Modbus line the bus
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
# overrun_warned: the status publishes the overrun cause as present
overrun_warned() {
	status_true '(.active_faults / 16 | floor) % 2 == 1'
}

# The two simulated rigs run at once, each in a slot of its own (common.sh):
# each one's window passes while the other is checked, and the rig told to
# fault recovers while the Modbus rig's loop is stalled, instead of the
# test waiting for each window in turn. Every check that must fall within
# a window or a stall still comes right after its stall.
use_slot auto
check "simulated rig up, overrun_fault auto, enabled, every axis moving" \
	start_sim --set loop.overrun_window_s=$window_s
use_slot yes
check "simulated rig up, overrun_fault yes, enabled, every axis moving" \
	start_sim --set loop.overrun_window_s=$window_s \
	--set loop.overrun_fault=yes
budget=$(ctl get loop.overrun_budget)

use_slot auto
check "auto, all simulated: the journal says a miss is a warning" \
	grep -q "missing it is a warning" "$LOG"
check "auto: the loop stalled for 1.5 s" ctl debug stall 1.5
check "auto: the missed budget is published while the window holds it" \
	wait_for overrun_warned
check "auto: ... not latched, still ENABLED, torque on" status_true \
	'.state == "ENABLED" and .fault_bits == 0 and .ramp == 1'
check "auto: the journal warns" \
	wait_for grep -q "warning: force loop over its overrun budget" "$LOG"
check "auto: no FAULT in the journal" [ "$(fault_lines)" = 0 ]

use_slot yes
watch_fault 0x10
check "the loop stalled for 1.5 s" ctl debug stall 1.5
check "the daemon answers while its loop is stalled" ctl status
check "sim stall: FAULT once the loop runs again" wait_for state_is FAULT
check "sim stall: reset refused within the ${window_s} s window" reset_refused
expect_fault "sim stall" overrun-budget none "skipped" "budget of $budget"
check "sim stall: about 1500 periods counted ($(watched fault_value))" \
	awk -v v="$(watched fault_value)" -v b="$budget" \
	'BEGIN { exit !(v > b && v >= 1400 && v <= 3000) }'

use_slot auto
check "auto: the warning clears once the window has passed" \
	wait_for eval '! overrun_warned'
stop_daemon

use_slot main
check "Modbus rig up, overrun_fault auto, enabled" start_mb_rig
check "auto, a real drive: the journal says a miss is a fault" \
	grep -q "missing it is a fault" "$LOG"
watch_fault 0x10
check "the loop stalled for 4 s" ctl debug stall 4
cycle=$(status_field .cycle)
check "Modbus stall: the wheel drives stop while the loop is stalled" \
	wait_for wheels_off
check "Modbus stall: ... the loop had not run meanwhile" \
	[ "$(status_field .cycle)" = "$cycle" ]
use_slot yes
recovers "sim stall"
stop_daemon
use_slot main
expect_fault "Modbus stall" overrun-budget none "skipped"
check "Modbus stall: the bus says why it stopped" \
	grep -q "no command from the force loop" "$LOG"
recovers "Modbus stall"
check "Modbus stall: the wheels run again" wait_for wheels_on
finish
