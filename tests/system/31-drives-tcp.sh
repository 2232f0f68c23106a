#!/usr/bin/env bash
# 31-drives-tcp.sh - both wheels on Modbus TCP (the emulator on loopback),
# insertion and roll simulated beside them. Comes up, renders torque the
# drives get, reads positions that move; a drive that stops answering is a
# bus error (and its own watchdog stops it); a killed server is a FAULT
# naming host:port with torque off on every axis, refused reset until it
# is back, then recovered.
. "$(dirname "$0")/drives_lib.sh"

PORT=$((20000 + $$ % 20000))
cat >"$TMP/rig.conf" <<EOF
[rig]
backend = drives
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
; the paper's model: with the tip off the wall, only the damping renders,
; a steady torque to find in the drive's register (the rod's tip bent
; against the wall would add a contact torque only_damping leaves on)
model = paper
[axis.wheel_ud]
backend = modbus
[axis.wheel_lr]
backend = modbus
[modbus]
transport = tcp
host = 127.0.0.1
port = $PORT
response_timeout_s = 0.3
feedback_max_age_s = 1
[modbus.wheel_ud]
slave = 1
torque = holding 0x0000 f32 dcba
enable = holding 0x0002
position = input 0x0000 i32
velocity = input 0x0002 i32
[modbus.wheel_lr]
slave = 2
torque = holding 0x0000 i16 scale=1e-5
enable = coil 0x0000
fault_reset = coil 0x0001
watchdog = holding 0x0001 u16 scale=0.001
watchdog_s = 0.2
position = input 0x0000 i32 badc
fault = discrete 0x0000
EOF

wheels_enabled() {
	state_is ENABLED && [ "$(mb_get 1 enabled)$(mb_get 2 enabled)" = 11 ]
}

torque_off() {
	for a in insertion roll wheel_ud wheel_lr; do
		[ "$(status_field ".axes.$a.limited")" = 0 ] || return 1
	done
	[ -z "$MODBUS_PID" ] && return 0
	[ "$(mb_get 1 torque_nm)" = 0 ] && [ "$(mb_get 2 torque_nm)" = 0 ]
}

others_off() {
	[ "$(status_field .axes.wheel_ud.limited)$(mb_get 1 torque_nm)" = 00 ]
}

watchdog_stopped() {
	[ "$(mb_get 2 torque_nm)" = 0 ] && [ "$(mb_get 2 fault)" = 0x8130 ]
}

check "Modbus TCP emulator up" start_modbus "$TMP/rig.conf" --listen "$PORT"
check "endosimd up, connected" start_on "$TMP/rig.conf"
check "IDLE, wheels present" \
	[ "$(status_field .state)/$(status_field .axes.wheel_ud.drive_status)" = IDLE/1 ]

mb "move 1 30"
mb "hand 2 0.002 1"
check "only the damping renders" only_damping
ctl set haptics.wheel_ud_damping_n_m_s_per_rad 0.01 >/dev/null
ctl enable >/dev/null; for i in $(seq 8); do echo "# $(ctl --json status | jq -c "[.axes.wheel_ud.limited, .axes.wheel_ud.position, .haptics.wheel_contact_nm, .haptics.wheel_tension_nm, .haptics.wheel_elastic_nm, .haptics.damping, .haptics.passivity_damping, .axes.wheel_ud.commanded]")"; done
check "enabled: both drives" wait_for wheels_enabled
check "forces in full once the enable ramp is over" wait_for status_true '.ramp == 1'
# torque_rendered: the damping's torque on wheel_ud, turned at pi rad/s
torque_rendered() { nonzero "$(status_field .axes.wheel_ud.limited)" 0.005; }
check "wheel_ud torque rendered" wait_for torque_rendered
lim=$(status_field .axes.wheel_ud.limited)
check "the f32 dcba torque register gets it" \
	approx "$(mb_get 1 torque_nm)" "$lim" 0.03 1e-6
check "wheel_ud velocity pi rad/s (i32 counts/s)" \
	approx "$(status_field .axes.wheel_ud.velocity)" 3.14159265 0.01 0
p1=$(status_field .axes.wheel_lr.position)
# moved_from P: wheel_lr is more than 1 mrad away from P
moved_from() {
	nonzero "$(awk -v a="$1" -v b="$(status_field .axes.wheel_lr.position)" \
		'BEGIN { print b - a }')" 0.001
}
check "wheel_lr position (i32 badc) moves (from $p1 rad)" wait_for moved_from "$p1"

# a drive that stops answering
mb "mute 2 on"
check "silent drive: FAULT" wait_for state_is FAULT
check "silent drive: a bus error on wheel_lr" \
	fault_says "bus-error on wheel_lr"
check "silent drive: ... naming slave 2" fault_says "slave 2"
check "silent drive: ... timed out" fault_says "timed out"
check "silent drive: torque off on the other axes" wait_for others_off
check "silent drive: its own watchdog stops it" wait_for watchdog_stopped
mb "mute 2 off"
check "answering again: reset" wait_for reset_ok
ctl enable >/dev/null
check "answering again: enabled" wait_for wheels_enabled

# the server goes away
since=$(daemon_time)
kill_modbus
check "server killed: FAULT" wait_for state_is FAULT
check "server killed: torque off on every axis" wait_for torque_off
check "server killed: drive-gone" fault_says "drive-gone on wheel_ud"
check "server killed: ... naming modbus tcp 127.0.0.1:$PORT" \
	fault_says "modbus tcp 127.0.0.1:$PORT"
sleep 0.3
check "server killed: one log line" [ "$(faults_since "$since")" -eq 1 ]
check "server gone: reset refused" reset_refused
check "server restarted" start_modbus "$TMP/rig.conf" --listen "$PORT"
check "server back: reset" wait_for reset_ok
check "server back: IDLE" state_is IDLE
ctl enable >/dev/null
check "server back: enabled" wait_for wheels_enabled

finish
