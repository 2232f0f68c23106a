#!/bin/bash
# The emergency stop: latched as its own cause in state ESTOP, torque zero
# on every axis in the cycle that takes it, the drives disabled, the daemon
# answering; enable refused until reset, which always works (its cause is
# the command).
. "$(dirname "$0")/fault_lib.sh"

EXPECT_STATE=ESTOP
check "simulated rig up, enabled, every axis moving" start_sim
watch_fault 0x400
check "estop" ctl estop
expect_fault "sim estop" estop none "emergency stop commanded"
check_status "sim estop: enable refused" 1 ctl enable
recovers "sim estop"
stop_daemon

check "Modbus rig up, enabled" start_mb_rig
watch_fault 0x400
check "estop" ctl estop
expect_fault "Modbus estop" estop none "emergency stop commanded"
check "Modbus estop: both wheel drives disabled, no torque" wait_for wheels_off
recovers "Modbus estop"
check "Modbus estop: the wheels run again" wait_for wheels_on
finish
