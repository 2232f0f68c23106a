#!/bin/bash
# When endosimd itself dies (SIGKILL: nothing of it runs any more), the
# drives' own communication watchdogs stop them: the EPOS4's heartbeat
# consumer (0x1016, [epos4.NAME] watchdog_s) and the Modbus drives'
# watchdog register ([modbus.NAME] watchdog_s), both set at bring-up. On
# the emulators: while the daemon lives they never trip; killed, every
# drive faults (0x8130) and drops its torque within its watchdog time.
. "$(dirname "$0")/fault_lib.sh"

conf=$(mb_rig_conf)
cat >>"$conf" <<CONF
[axis.insertion]
backend = epos4-usb
gear_radius_m = 0.015
[epos4.insertion]
serial = EMU-INS
timeout_s = 0.5
feedback_max_age_s = 1
watchdog_s = 0.3
CONF
check "USB emulator up" start_epos4 EMU-INS
check "Modbus emulator up" start_modbus "$conf" --pty "$TMP/tty" "${MB_MOTOR[@]}"
check "endosimd up on both" start_on "$conf" --scenario "$SOAK"
usb "place EMU-INS 19557" # 0.9 m
usb "move EMU-INS 6"      # the hand inserts slowly
mb "hand 1 0.004 1"
mb "hand 2 0.004 1.3"

all_on() {
	state_is ENABLED && [ "$(usb_get EMU-INS state)" = operation_enabled ] &&
		[ "$(mb_get 1 enabled)$(mb_get 2 enabled)" = 11 ]
}
check "enabled: every drive follows torque" sh -c "'$ENDOCTL' --socket '$SOCK' enable >/dev/null"
check "... every drive on" wait_for all_on
check "the EPOS4's heartbeat consumer set to 300 ms" \
	[ "$(usb_get EMU-INS heartbeat_ms)" = 300 ]
sleep 1
check "alive, the daemon keeps every watchdog fed (1 s later all on)" all_on
check "torque on the EPOS4's motor" nonzero "$(usb_get EMU-INS torque_nm)" 1e-6

all_stopped() {
	[ "$(usb_get EMU-INS state)" = fault ] &&
		[ "$(usb_get EMU-INS error)" = 0x8130 ] &&
		[ "$(usb_get EMU-INS torque_nm)" = 0 ] &&
		[ "$(mb_get 1 fault)$(mb_get 2 fault)" = 0x81300x8130 ] && wheels_off
}
t0=$(date +%s%N)
kill -KILL "$DAEMON_PID"
wait "$DAEMON_PID" 2>/dev/null
DAEMON_PID=""
check "SIGKILL: every drive stops itself (heartbeat error 0x8130)" \
	wait_for all_stopped
ms=$((($(date +%s%N) - t0) / 1000000))
sed 's/^/# /' "$TMP/usb.state" "$TMP/mb.state"
check "... within 1.5 s of the kill ($ms ms; watchdogs 300 and 500 ms)" [ "$ms" -lt 1500 ]
finish
