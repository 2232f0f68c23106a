#!/usr/bin/env bash
# 32-drives-startup.sh - a missing or wrong device stops endosimd at
# start-up, before the force loop runs, with one line naming what it looked
# for: a wrong VID:PID, a wrong serial number, a tty that is not there, a
# TCP port nobody listens on, a slave id nobody answers to. A register map
# a modbus axis cannot use is a configuration error (exit 78).
. "$(dirname "$0")/drives_lib.sh"

EX_UNAVAILABLE=69
EX_CONFIG=78

cat >"$TMP/usb.conf" <<EOF
[rig]
backend = drives
[axis.insertion]
backend = epos4-usb
[axis.roll]
backend = epos4-usb
[epos4.insertion]
serial = EMU-INS
[epos4.roll]
serial = EMU-ROLL
EOF

cat >"$TMP/mb.conf" <<EOF
[rig]
backend = drives
[axis.wheel_ud]
backend = modbus
[modbus]
device = $TMP/tty
response_timeout_s = 0.2
[modbus.wheel_ud]
slave = 1
torque = holding 0 i16 scale=1e-5
position = input 0 i32
EOF

check "USB emulator up" start_epos4 EMU-INS EMU-ROLL
check "the right ids start (the setup is sound)" start_on "$TMP/usb.conf"
check "... and stop cleanly" stop_daemon

check "wrong VID:PID: refused, naming it" refused_at_start "$TMP/usb.conf" $EX_UNAVAILABLE \
	"epos4-usb 1234:3b01 serial 'EMU-INS': no USB device 1234:3b01 with serial 'EMU-INS' found" \
	--set epos4.insertion.vid=0x1234
check "wrong serial: refused, naming it" \
	refused_at_start "$TMP/usb.conf" $EX_UNAVAILABLE \
	"no USB device 24e7:3b01 with serial 'NOPE' found; there are serials" \
	--set epos4.roll.serial=NOPE
both_serials() {
	grep -q "there are serials.*'EMU-INS'" "$TMP/failed.log" &&
		grep -q "there are serials.*'EMU-ROLL'" "$TMP/failed.log"
}
check "... and the serials there are" both_serials

ENDOSIMD="$BUILD/endosimd" # no USB from here on

check "Modbus emulator up" start_modbus "$TMP/mb.conf" --pty "$TMP/tty"
check "the right tty starts (the setup is sound)" start_on "$TMP/mb.conf"
check "... and stop cleanly" stop_daemon

check "wrong tty: refused, naming it" \
	refused_at_start "$TMP/mb.conf" $EX_UNAVAILABLE \
	"modbus rtu $TMP/nope 115200 8N1: cannot open the line: No such file or directory" \
	--set "modbus.device=$TMP/nope"
check "nobody answers to slave 9: refused, naming it" \
	refused_at_start "$TMP/mb.conf" $EX_UNAVAILABLE \
	"slave 9: writing 0x0000: Connection timed out (does the drive for wheel_ud answer?)" \
	--set modbus.wheel_ud.slave=9
check "TCP port nobody listens on: refused, naming it" \
	refused_at_start "$TMP/mb.conf" $EX_UNAVAILABLE \
	"modbus tcp 127.0.0.1:9: cannot connect: Connection refused" \
	--set modbus.transport=tcp --set modbus.port=9

check "a modbus axis without position: a configuration error, naming it" \
	refused_at_start "$TMP/mb.conf" $EX_CONFIG \
	"[modbus.wheel_ud] position: a modbus axis needs it" \
	--set "modbus.wheel_ud.position=none"

finish
