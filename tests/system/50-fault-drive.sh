#!/bin/bash
# Fault: a drive reports a fault of its own. On the simulated rig (the roll
# axis' drive, by the test command) and on the Modbus emulator (a wheel
# drive's fault register): FAULT within the cycle that sees it, torque zero
# on every axis in that cycle, the drives disabled, the daemon answering;
# reset refused while the drive stays faulted, recovered once it clears.
# The journal line of a fault that keeps coming back is rate-limited.
. "$(dirname "$0")/fault_lib.sh"

check "simulated rig up, enabled, every axis moving" start_sim
watch_fault 0x1
debug drive-fault roll 0x2310
expect_fault "sim drive fault" drive roll "drive fault 0x2310"
refused_while "sim drive fault"
debug clear roll
recovers "sim drive fault"

# a drive that keeps faulting again after each reset: one journal line per
# fault, at most five a minute for the same cause, then a count of the rest
for i in 1 2 3 4 5 6 7; do
	debug drive-fault wheel_lr 0x3210
	wait_for state_is FAULT
	debug clear wheel_lr
	wait_for reset_ok
	ctl enable >/dev/null
done
check "a repeating fault: five journal lines in its minute, not more" \
	[ "$(grep -c "error: FAULT drive on " "$LOG")" = 5 ]
stop_daemon

check "Modbus rig up, enabled" start_mb_rig
watch_fault 0x1
mb "fault 2 0x42 sticky"
expect_fault "Modbus drive fault" drive wheel_lr "slave 2" "drive fault 0x0042"
check "Modbus drive fault: both wheel drives disabled, no torque" wait_for wheels_off
refused_while "Modbus drive fault"
mb "clear 2"
recovers "Modbus drive fault"
check "Modbus drive fault: the wheels run again" wait_for wheels_on
finish
