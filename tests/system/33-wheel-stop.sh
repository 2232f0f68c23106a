#!/usr/bin/env bash
# 33-wheel-stop.sh - issue 12: both wheels on Modbus TCP drives turning a
# light, nearly frictionless knob (2e-5 kg m^2, 1e-4 N m s/rad), the tube
# held in the sigmoid, nobody's thumb on the wheels, torque on. The wire
# tension and the bending section's spring move each wheel; where they
# would carry it past the tip's angulation limit, the knob's stop (haptics.h)
# holds it. 20 s of the course: no fault (no runaway, no saturation), and
# each wheel at rest (to its encoder's counts) within its limit (bend limit
# / gain), give or take what the stop yields under the wheel's whole torque
# limit. The wall's stiffness on a wheel is limited to what the drive's lag
# allows (haptics.h): unlimited, it ran a wheel away at ~0.15 rad.
. "$(dirname "$0")/drives_lib.sh"

PORT=$((20000 + ($$ + 7) % 20000))
cat >"$TMP/rig.conf" <<EOF
[rig]
backend = drives
[limits]
; the emulated motors have no end of travel: a bench, not a rig (55 checks
; the travel); the runaway and saturation faults stay as shipped
travel_margin_fraction = 100
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
torque = holding 0x0000 f32
enable = holding 0x0002
position = input 0x0000 i32
velocity = input 0x0002 i32
[modbus.wheel_lr]
slave = 2
torque = holding 0x0000 f32
enable = holding 0x0002
position = input 0x0000 i32
velocity = input 0x0002 i32
EOF

# the hand inserts into the sigmoid (0.16-0.53 m of the normal colon) at
# 30 mm/s and holds the tube there, roll at 0; it never touches the wheels
cat >"$TMP/sigmoid.scn" <<EOF
0 insertion target 0.40 13
0 roll target 0
EOF

# limit_rad WHEEL: the wheel angle at the tip's angulation limit (ud, lr)
limit_rad() {
	awk -v l="$(ctl get "scope.${1}_limit_rad")" \
		-v g="$(ctl get "scope.${1}_gain_rad_per_rad")" \
		'BEGIN { print (g > 0 ? l / g : 1e9) }'
}

# 20 s of the course (the tube stops in the sigmoid within 10, the wheels
# come to rest after it); under the sanitizers (SANITIZED=1, a run for
# memory errors: the plain pass has checked the 20 s) the first 15
if [ -n "${SANITIZED:-}" ]; then course_s=15; else course_s=20; fi
# course_over_or_fault: the course has run its time, or a fault ended it
course_over_or_fault() {
	state_is FAULT || status_true ".scenario_time_s >= $course_s"
}

check "Modbus TCP emulator up (light free wheels)" start_modbus \
	"$TMP/rig.conf" --listen "$PORT" -o inertia=2e-5 -o viscous=1e-4
check "endosimd up on it, the hand on the sigmoid course" \
	start_on "$TMP/rig.conf" --scenario "$TMP/sigmoid.scn"
ctl enable >/dev/null
check "enabled" wait_for state_is ENABLED
"$ENDOCTL" --socket "$SOCK" --json watch --rate 50 >"$TMP/trace.json" &
watch_pid=$!
WAIT_S=120 wait_for course_over_or_fault
kill -TERM "$watch_pid"
wait "$watch_pid"

check "no fault in $course_s s of the course (no runaway, no saturation)" \
	test "$(status_field .state)/$(status_field .fault_bits)" = ENABLED/0
# the hand heads for 0.40 m; the straight tip meets the sigmoid's wall on
# the way (at ~0.26 m, the hand at its 40 N; the simulated wheels stop it
# there too) and stays in the sigmoid
check "the tube in the sigmoid" approx "$(status_field .axes.insertion.position)" 0.345 0 0.185
q() { jq -s "$1" "$TMP/trace.json"; }
n=$(q 'length')
check "the course was recorded ($n states)" test "$n" -gt 500
check "the wire tension worked on the wheels" \
	test "$(q 'map(.haptics.wheel_tension_nm[] | fabs) | max > 0.002')" = true
k=$(ctl get haptics.wheel_stop_stiffness_n_m_per_rad 2>/dev/null)
for w in ud lr; do
	lim=$(limit_rad $w)
	max=$(ctl get limits.wheel_${w}_max_torque_n_m)
	# the stop yields at most the wheel's whole torque limit over its
	# stiffness (none without the stop's key)
	give=$(awk -v m="$max" -v k="${k:-0}" 'BEGIN { print (k > 0 ? m / k : 0) }')
	last=$(q "[.[] | select(.scenario_time_s >= $course_s - 2)]
		| map(.axes.wheel_$w.position) | {x: (map(fabs) | max),
		  s: (max - min)} | \"\(.x) \(.s)\"" | tr -d '"')
	x=${last% *}
	spread=${last#* }
	# at rest: a frictionless wheel whose balance lies between two of the
	# encoder's counts (2048 a turn: 3.1 mrad) hunts about them, a few
	# counts at a few tenths of a rad/s behind a bus whose lag varies; a
	# wheel still turning (30 rad/s at a runaway, a swing of tenths of a
	# rad) spans hundreds: at rest is within 8 counts (1.4 deg)
	check "wheel_$w at rest in the last 2 s (moved $spread rad)" \
		awk -v s="$spread" \
		'BEGIN { exit !(s != "" && s <= 8 * 2 * 3.14159265 / 2048 + 1e-9) }'
	check "wheel_$w within its limit $lim rad (+ $give) (|x| $x rad)" \
		awk -v x="$x" -v l="$lim" -v g="$give" \
		'BEGIN { exit !(x != "" && x <= l + g) }'
	check "wheel_$w torque within [limits] ($max N m)" \
		test "$(q "map(.axes.wheel_$w.limited | fabs) | max <= $max + 1e-9")" = true
done
check "the parts of each wheel's torque add up to its command" \
	test "$(q 'map(. as $s | [0, 1] | map($s.haptics.wheel_contact_nm[.] + $s.haptics.wheel_tension_nm[.] + $s.haptics.wheel_elastic_nm[.] + $s.haptics.damping[2 + .]) as $sum | [$s.axes.wheel_ud.command - $sum[0], $s.axes.wheel_lr.command - $sum[1]] | map(fabs) | max) | max < 1e-6')" = true

finish
