#!/bin/bash
# Fault: a force held beyond its limit for longer than [limits]
# saturation_s (0.5 s here) while torque is on. A constant command far
# beyond an up/down wheel's limit (the test command), the wheel held by
# the hand: the drive gets the limit, no more, for 0.5 s; then FAULT with
# torque zero on every axis. Torque off ends the saturation, so reset works
# at once; enabled again with the command still there, it faults again;
# gone, it does not.
. "$(dirname "$0")/fault_lib.sh"

# On the simulated rig saturation is a fault only when asked for
# ([limits] saturation_fault = yes: with auto it warns, no motor to
# protect; on the Modbus rig below auto makes it a fault, as on a rig).
# 10 mN m: the scripted hand (its grip 0.05 N m/rad) holds the wheel
# against it 0.2 rad off its target, not far off, never fast. The force
# model's own wheel torques (the paper model's: the wall's contact, wire
# tension, the bending spring) are off: they would saturate so small a
# limit by themselves.
check "simulated rig up, enabled, every axis moving" \
	start_sim --set limits.saturation_s=0.5 \
	--set limits.saturation_fault=yes \
	--set limits.wheel_ud_max_torque_n_m=0.01 --set haptics.model=paper \
	--set haptics.wall_stiffness_n_per_m=0 \
	--set haptics.wall_damping_n_s_per_m=0 \
	--set haptics.wire_tension_n_m_per_m=0 \
	--set haptics.bending_stiffness_n_m_per_rad=0
watch_fault 0x80
debug force wheel_ud 0.5
expect_fault "sim saturation" saturation wheel_ud "held beyond the limit 0.01"
# held_at_limit CSV: the records up to the fault's had wheel_ud's torque at
# its 10 mN m limit (how many: printed), never beyond it
held_at_limit() {
	ctl session export "$SESSION_FILE" --csv --out "$1" >/dev/null &&
		awk -F, '
		NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
		int($col["fault_bits"] / 128) % 2 { exit }
		{ v = $col["wheel_ud_limited_nm"]; v = v < 0 ? -v : v
		  at += v > 0.01 - 1e-9 && v < 0.01 + 1e-9; most = v > most ? v : most }
		END { print at " records at the limit, largest " most
		      exit !(at > 0 && most <= 0.01 + 1e-9) }' "$1"
}
check "sim saturation: the drive got the limit, no more ($(held_at_limit "$TMP/held.csv"))" \
	held_at_limit "$TMP/held.csv"
held_ms=$(awk -v ns="$(($(watched fault_ns) - $(watched watch_ns)))" 'BEGIN { print ns / 1e6 }')
check "sim saturation: not before 0.5 s ($held_ms ms after the watch began, held $(watched fault_detail) ms)" \
	awk -v t="$held_ms" -v d="$(watched fault_detail)" \
	'BEGIN { exit !(t >= 500 && d >= 500 && d < 2000) }'
recovers "sim saturation"
check "sim saturation: with the command still there, it faults again" \
	wait_for state_is FAULT
check "sim saturation: ... saturation again" fault_says "saturation on wheel_ud"
debug clear wheel_ud
recovers "sim saturation gone"
sleep 1
check "sim saturation gone: no fault for 1 s" state_is ENABLED
stop_daemon

# the emulated wheel's spring-hand holds it 0.4 rad off against 20 mN m
check "Modbus rig up, enabled" start_mb_rig --set limits.saturation_s=0.5 \
	--set limits.wheel_lr_max_torque_n_m=0.02
watch_fault 0x80
debug force wheel_lr -1
wheel_at_limit() {
	approx "$(mb_get 2 torque_nm)" -0.02 0.01 0
}
check "Modbus saturation: the drive applies the limit, no more" \
	wait_for wheel_at_limit
expect_fault "Modbus saturation" saturation wheel_lr "held beyond the limit"
check "Modbus saturation: both wheel drives disabled, no torque" \
	wait_for wheels_off
debug clear
recovers "Modbus saturation"
finish
