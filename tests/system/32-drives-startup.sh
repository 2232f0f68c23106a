#!/usr/bin/env bash
# 32-drives-startup.sh - a missing or wrong device stops endosimd at
# start-up, before the force loop runs, with one line naming what it looked
# for: a wrong VID:PID, a wrong serial number, a tty that is not there, a
# TCP port nobody listens on, a slave id nobody answers to. A register map
# a modbus axis cannot use is a configuration error (exit 78).
set -u
cd "$(dirname "$0")/../.." || exit 1
. tests/system/drives_lib.sh

EX_UNAVAILABLE=69
EX_CONFIG=78

cat >"$T/usb.conf" <<EOF
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

cat >"$T/mb.conf" <<EOF
[rig]
backend = drives
[axis.wheel_ud]
backend = modbus
[modbus]
device = $T/tty
response_timeout_s = 0.2
[modbus.wheel_ud]
slave = 1
torque = holding 0 i16 scale=1e-5
position = input 0 i32
EOF

# refused CONF WHAT [ARGS...]: exits EX_UNAVAILABLE before the force loop,
# saying WHAT
refused_at_start() {
	local conf=$1 what=$2 rc
	shift 2
	rc=$(run_daemon_expecting_failure "$conf" "$@")
	[ "$rc" = "$EX_UNAVAILABLE" ] || { echo "# exit $rc"; return 1; }
	grep -qF -- "$what" "$T/failed.log" ||
		{ echo "# log:"; sed 's/^/#   /' "$T/failed.log"; return 1; }
	! grep -q "force loop:" "$T/failed.log"
}

check "USB emulator up" start_epos4 EMU-INS EMU-ROLL
check "the right ids start (the setup is sound)" start_daemon "$T/usb.conf"
stop_daemon

check "wrong VID:PID: refused, naming it" refused_at_start "$T/usb.conf" \
	"epos4-usb 1234:3b01 serial 'EMU-INS': no USB device 1234:3b01 with serial 'EMU-INS' found" \
	--set epos4.insertion.vid=0x1234
check "wrong serial: refused, naming it" refused_at_start "$T/usb.conf" \
	"no USB device 24e7:3b01 with serial 'NOPE' found; there are serials" \
	--set epos4.roll.serial=NOPE
both_serials() {
	grep -q "there are serials.*'EMU-INS'" "$T/failed.log" &&
		grep -q "there are serials.*'EMU-ROLL'" "$T/failed.log"
}
check "... and the serials there are" both_serials

UMOCKDEV_ROOT= # no USB from here on

check "Modbus emulator up" start_modbus "$T/mb.conf" --pty "$T/tty"
check "the right tty starts (the setup is sound)" start_daemon "$T/mb.conf"
stop_daemon

check "wrong tty: refused, naming it" refused_at_start "$T/mb.conf" \
	"modbus rtu $T/nope 115200 8N1: cannot open the line: No such file or directory" \
	--set "modbus.device=$T/nope"
check "nobody answers to slave 9: refused, naming it" \
	refused_at_start "$T/mb.conf" \
	"slave 9: writing 0x0000: Connection timed out (does the drive for wheel_ud answer?)" \
	--set modbus.wheel_ud.slave=9
check "TCP port nobody listens on: refused, naming it" \
	refused_at_start "$T/mb.conf" \
	"modbus tcp 127.0.0.1:9: cannot connect: Connection refused" \
	--set modbus.transport=tcp --set modbus.port=9

rc=$(run_daemon_expecting_failure "$T/mb.conf" \
	--set "modbus.wheel_ud.position=none")
check "a modbus axis without position: configuration error" \
	[ "$rc" = "$EX_CONFIG" ]
check "... naming the section and key" \
	grep -qF "[modbus.wheel_ud] position: a modbus axis needs it" \
	"$T/failed.log"

finish
