#!/bin/bash
# Fault: a bus transaction fails. On the simulated rig (the left/right
# wheel's, by the test command) and on the Modbus line (an exception reply
# from a wheel drive): FAULT with torque zero on every axis in the cycle
# that sees it, the drives disabled, the daemon answering; reset refused
# while transactions keep failing, recovered once they succeed.
. "$(dirname "$0")/fault_lib.sh"

check "simulated rig up, enabled, every axis moving" start_sim
watch_fault 0x8
debug bus-error wheel_lr
expect_fault "sim bus error" bus-error wheel_lr "a transaction failed"
refused_while "sim bus error"
debug clear wheel_lr
recovers "sim bus error"
stop_daemon

check "Modbus rig up, enabled" start_mb_rig
watch_fault 0x8
mb "exception 1 4"
expect_fault "Modbus exception" bus-error wheel_ud "slave 1" \
	"Slave device or server failure"
check "Modbus exception: both wheel drives disabled, no torque" \
	wait_for wheels_off
recovers "Modbus exception"
check "Modbus exception: the wheels run again" wait_for wheels_on
finish
