#!/usr/bin/env bash
# 30-drives-rtu.sh - all four axes on real drive code against emulated
# devices: insertion and roll on two EPOS4 under umockdev (libusb), both
# wheels on one Modbus RTU line over a pty (libmodbus). The rig comes up,
# enables, renders torque the emulators see in the right units, reads back
# positions that move; an error reply, a drive fault (sticky and not), a
# CRC error, an unplug and a killed Modbus emulator each end in FAULT with
# torque off on every axis and one log line naming the device and the
# cause; `endoctl reset` is refused while the cause persists and recovers
# once the device is back.
. "$(dirname "$0")/drives_lib.sh"

R=0.015 # the pinion, m

# Generous timeouts (and drive watchdogs): the emulators are ordinary
# processes on a shared machine; these tests are about what happens, not
# how fast.
cat >"$TMP/rig.conf" <<EOF
[rig]
backend = drives
; the free emulated roll motor (5e-4 kg m^2) must not meet the end brakes,
; whose 1 N m, late on a slow bus, would kick it into a runaway
roll_min_rad = -100
roll_max_rad = 100
[limits]
; the emulated motors turn on and on, far past the rig's travel: a bench,
; not a rig (tests/system/55-fault-travel.sh checks the travel), turned
; at a set speed however hard the end brakes push back at their limit
travel_margin_fraction = 100
saturation_s = 3600
; forces in full a tenth of a second after enable, not a second: the
; ramp itself is 63-enable-ramp's
enable_ramp_s = 0.1
[haptics]
; the paper's model: with the tube on the centreline and the tip off the
; wall, only the damping renders, a steady force to find in each drive
model = paper
[axis.insertion]
backend = epos4-usb
gear_radius_m = $R
counts_per_rev = 2048
[axis.roll]
backend = epos4-usb
[axis.wheel_ud]
backend = modbus
counts_per_rev = 4096
[axis.wheel_lr]
backend = modbus
gear_ratio = 3.5
direction = reversed
[epos4.insertion]
serial = EMU-INS
timeout_s = 0.5
feedback_max_age_s = 1
watchdog_s = 1
[epos4.roll]
serial = EMU-ROLL
timeout_s = 0.5
feedback_max_age_s = 1
watchdog_s = 1
[modbus]
device = $TMP/tty
response_timeout_s = 0.5
feedback_max_age_s = 1
[modbus.wheel_ud]
slave = 1
torque = holding 0x0000 i16 scale=1e-5
enable = coil 0x0000
fault_reset = coil 0x0001
position = input 0x0000 i32 cdab
velocity = input 0x0002 f32 cdab
fault = input 0x0004 u16
[modbus.wheel_lr]
slave = 2
combined_0x17 = yes
torque = holding 0x0010 i32 scale=1e-6
enable = holding 0x0012 u16
fault_reset = holding 0x0013 u16
position = holding 0x0020 i32
velocity = holding 0x0022 i32
fault = holding 0x0024 u16
EOF

AXES="insertion roll wheel_ud wheel_lr"

# every axis: bit set (or clear) in drive_status
all_status() {
	local a
	for a in $AXES; do
		if [ "$2" = set ]; then
			[ $(($(status_field ".axes.$a.drive_status") & $1)) -ne 0 ] || return 1
		else
			[ $(($(status_field ".axes.$a.drive_status") & $1)) -eq 0 ] || return 1
		fi
	done
}

# torque off everywhere: nothing sent, no drive enabled or producing it
torque_off() {
	local a
	for a in $AXES; do
		[ "$(status_field ".axes.$a.limited")" = 0 ] || return 1
	done
	for s in EMU-INS EMU-ROLL; do
		[ "$(usb_get $s present)" = 0 ] && continue
		[ "$(usb_get $s torque_nm)" = 0 ] || return 1
		[ "$(usb_get $s state)" != operation_enabled ] || return 1
	done
	[ -z "$MODBUS_PID" ] && return 0
	for s in 1 2; do
		[ "$(mb_get $s torque_nm)" = 0 ] || return 1
		[ "$(mb_get $s enabled)" = 0 ] || return 1
	done
}

enabled_everywhere() {
	state_is ENABLED && all_status 2 set &&
		[ "$(usb_get EMU-INS state)" = operation_enabled ] &&
		[ "$(usb_get EMU-ROLL state)" = operation_enabled ] &&
		[ "$(mb_get 1 enabled)" = 1 ] && [ "$(mb_get 2 enabled)" = 1 ]
}

enable_all() {
	ctl enable >/dev/null && wait_for enabled_everywhere
}

# --- start-up ---------------------------------------------------------------

check "USB emulator up" start_epos4 EMU-INS EMU-ROLL
check "Modbus emulator up on a pty" start_modbus "$TMP/rig.conf" --pty "$TMP/tty"
check "endosimd up on the emulated drives" start_on "$TMP/rig.conf"
check "IDLE" state_is IDLE
check "every drive present, none faulted" all_status 1 set
check "no fault bits" all_status 12 clear
check "the rig names its backend" [ "$(status_field .rig)" = drives ]

# --- motion, torque and units ---------------------------------------------------

# positions at rest: counts to metres and radians
at_rest() {
	approx "$(status_field .axes.insertion.position)" 0.9 0.001 0 &&
		approx "$(status_field .axes.wheel_lr.position)" -1.5707963 0.001 0
}
usb "place EMU-INS 19557" # 19557 / 2048 turns of a 1.5 cm pinion: 0.9 m
mb "place 2 1792"         # 2048 counts a turn: a quarter after 3.5:1, reversed
check "positions from counts: insertion 0.9 m, wheel_lr -pi/2 rad" \
	wait_for at_rest

# the hands: the carriage pushed at 60 rpm of the motor from mid travel,
# the wheels turned at 30 rpm, the tube twisted back and forth
usb "move EMU-INS 60"
usb "hand EMU-ROLL 0.01 0.5"
mb "move 1 30"
mb "move 2 30"
check "only the damping renders" only_damping
ctl set haptics.insertion_damping_n_s_per_m 20 >/dev/null
ctl set haptics.wheel_ud_damping_n_m_s_per_rad 0.01 >/dev/null
ctl set haptics.wheel_lr_damping_n_m_s_per_rad 0.02 >/dev/null

check "enable: every drive in torque mode" enable_all
check "EPOS4 in cyclic synchronous torque (mode 10)" \
	[ "$(usb_get EMU-INS mode)" = 10 ]
check "forces in full once the enable ramp is over" wait_for status_true '.ramp == 1'
sleep 0.5

# 60 rpm at the motor: 2 pi rad/s on a 1.5 cm pinion
V=$(awk -v r=$R 'BEGIN { print 2 * 3.14159265358979 * r }')
check "insertion velocity from rpm: $V m/s" \
	approx "$(status_field .axes.insertion.velocity)" "$V" 0.01 0
# position and the daemon's own clock in one reply: speed from positions
s1=$(status_field '"\(.axes.insertion.position) \(.stamp_ns)"')
sleep 0.4
s2=$(status_field '"\(.axes.insertion.position) \(.stamp_ns)"')
dpdt=$(echo "$s1 $s2" | awk '{ print ($3 - $1) / (($4 - $2) / 1e9) }')
check "insertion position from counts moves at $dpdt m/s" \
	approx "$dpdt" "$V" 0.2 0
check "wheel_ud velocity from counts/s: pi rad/s" \
	approx "$(status_field .axes.wheel_ud.velocity)" 3.14159265 0.01 0
check "wheel_lr velocity, geared 3.5 and reversed: -pi/3.5 rad/s" \
	approx "$(status_field .axes.wheel_lr.velocity)" -0.8975979 0.01 0
r1=$(status_field .axes.roll.position)
sleep 0.5
r2=$(status_field .axes.roll.position)
check "roll position moves with the hand ($r1 -> $r2 rad)" \
	nonzero "$(awk -v a="$r1" -v b="$r2" 'BEGIN { print b - a }')" 0.001

# what endosimd sent against what each emulated motor gets
lim=$(status_field .axes.insertion.limited)
check "insertion force rendered ($lim N)" nonzero "$lim" 0.5
check "EPOS4 motor torque = force x radius, via per-mille of 0x6076" \
	approx "$(usb_get EMU-INS torque_nm)" \
	"$(awk -v f="$lim" -v r=$R 'BEGIN { print f * r }')" 0.03 3e-4
lim=$(status_field .axes.wheel_ud.limited)
check "wheel_ud torque rendered ($lim N m)" nonzero "$lim" 0.005
check "Modbus drive torque register = wheel_ud torque" \
	approx "$(mb_get 1 torque_nm)" "$lim" 0.03 2e-5
lim=$(status_field .axes.wheel_lr.limited)
check "wheel_lr torque rendered ($lim N m)" nonzero "$lim" 0.005
check "Modbus drive torque (0x17) = -wheel_lr torque / 3.5" \
	approx "$(mb_get 2 torque_nm)" \
	"$(awk -v t="$lim" 'BEGIN { print -t / 3.5 }')" 0.03 2e-6

# --- faults ------------------------------------------------------------------

# fault NAME INJECT TEXT...: injects, expects the FAULT, resets, re-enables
fault_case() {
	local name=$1 inject=$2 since
	shift 2
	since=$(daemon_time)
	eval "$inject"
	check "$name: FAULT" wait_for state_is FAULT
	check "$name: torque off on every axis" wait_for torque_off
	sleep 0.3 # a further FAULT line would come now
	check "$name: one log line" [ "$(faults_since "$since")" -eq 1 ]
	for t in "$@"; do
		check "$name: status says '$t'" fault_says "$t"
		check "$name: log says '$t'" log_says "$t"
	done
}

recover() {
	check "$1: reset" wait_for reset_ok
	check "$1: IDLE" state_is IDLE
	check "$1: enabled again" enable_all
}

fault_case "error reply" "usb 'error EMU-ROLL'" "bus-error on roll" \
	"serial 'EMU-ROLL' node 1" "abort code 0x08000020"
recover "error reply"

fault_case "Modbus drive fault" "mb 'fault 2 0x42'" "drive on wheel_lr" \
	"slave 2" "drive fault 0x0042"
recover "Modbus drive fault"

fault_case "EPOS4 drive fault" "usb 'fault EMU-INS 0x4210 sticky'" \
	"drive on insertion" "drive fault 0x4210 (excess temperature"
sleep 0.6
check "sticky drive fault: reset refused while it persists" reset_refused
check "sticky drive fault: still FAULT" state_is FAULT
usb "clear EMU-INS"
recover "EPOS4 drive fault"

fault_case "CRC error" "usb 'crc EMU-INS'" "bus-error on insertion" \
	"failed its CRC"
recover "CRC error"

fault_case "USB unplug" "usb 'unplug EMU-INS'" "drive-gone on insertion" \
	"epos4-usb 24e7:3b01 serial 'EMU-INS'" "device gone"
sleep 0.6
check "unplugged: reset refused" reset_refused
check "unplugged: insertion not present" \
	[ $(($(status_field .axes.insertion.drive_status) & 1)) -eq 0 ]
usb "plug EMU-INS"
usb "move EMU-INS 60"
recover "USB replug"

fault_case "Modbus emulator killed" "kill_modbus" "drive-gone on wheel" \
	"modbus rtu $TMP/tty" "device gone"
sleep 0.6
check "Modbus gone: reset refused" reset_refused
check "Modbus emulator restarted" start_modbus "$TMP/rig.conf" --pty "$TMP/tty"
mb "move 1 30"
recover "Modbus back"
wheel_torque() {
	nonzero "$(mb_get 1 torque_nm)" 0.001
}
check "wheel torque reaches the new emulator" wait_for wheel_torque

# --- on the way down ----------------------------------------------------------

epos4_disabled() {
	[ "$(usb_get EMU-INS state)" = switch_on_disabled ] &&
		[ "$(usb_get EMU-ROLL state)" = switch_on_disabled ]
}

modbus_disabled() {
	[ "$(mb_get 1 enabled)$(mb_get 2 enabled)" = 00 ]
}

check "before stopping: enabled" enabled_everywhere
check "endosimd exits cleanly on SIGTERM" stop_daemon
check "stopping: EPOS4 drives disabled" wait_for epos4_disabled
check "stopping: Modbus drives disabled" wait_for modbus_disabled
check "stopping: no torque left on the motors" \
	test "$(usb_get EMU-INS torque_nm)$(mb_get 1 torque_nm)" = 00

finish
