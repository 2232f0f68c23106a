#!/bin/bash
# Fault: a drive reports a fault of its own. On the simulated rig (the roll
# axis' drive, by the test command) and on the Modbus emulator (a wheel
# drive's fault register): FAULT within the cycle that sees it, torque zero
# on every axis in that cycle, the drives disabled, the daemon answering;
# reset refused while the drive stays faulted, recovered once it clears.
. "$(dirname "$0")/fault_lib.sh"

check "simulated rig up, enabled, every axis moving" start_sim
watch_fault 0x1
debug drive-fault roll 0x2310
expect_fault "sim drive fault" drive roll "drive fault 0x2310"
refused_while "sim drive fault"
debug clear roll
recovers "sim drive fault"
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
