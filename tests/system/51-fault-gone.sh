#!/bin/bash
# Fault: a drive vanishes. On the simulated rig (the up/down wheel's drive,
# by the test command) and on the Modbus line (the emulator killed: the
# pty closes as when a USB-serial adapter is pulled): FAULT with torque zero
# on every axis in the cycle that sees it, the daemon answering; reset
# refused while the drive is away, recovered once it is back.
. "$(dirname "$0")/fault_lib.sh"

check "simulated rig up, enabled, every axis moving" start_sim
watch_fault 0x2
debug drive-gone wheel_ud
expect_fault "sim drive gone" drive-gone wheel_ud "device gone"
check "sim drive gone: the status shows it gone" \
	[ "$(status_field .axes.wheel_ud.drive)" = gone ]
refused_while "sim drive gone"
debug clear wheel_ud
recovers "sim drive gone"
stop_daemon

check "Modbus rig up, enabled" start_mb_rig
watch_fault 0x2
kill_modbus
expect_fault "Modbus line gone" drive-gone wheel_ud "modbus rtu $TMP/tty" \
	"device gone"
refused_while "Modbus line gone"
check "Modbus line back" start_modbus "$TMP/mb-rig.conf" --pty "$TMP/tty" \
	"${MB_MOTOR[@]}"
mb "hand 1 0.004 1"
recovers "Modbus line gone"
check "Modbus line gone: the wheels run again" wait_for wheels_on
finish
