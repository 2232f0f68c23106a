#!/bin/bash
# Fault: a position outside the travel ([rig] travel by more than [limits]
# travel_margin_fraction of it). On the simulated rig (the carriage's
# encoder made to read beyond the inserted end) and on the Modbus line (a
# wheel motor put past its end): FAULT with torque zero on every axis in
# the cycle that sees it; reset refused while outside, recovered back
# inside.
. "$(dirname "$0")/fault_lib.sh"

check "simulated rig up, enabled, every axis moving" start_sim
margin=$(ctl get limits.travel_margin_fraction)
end=$(awk -v m="$margin" 'BEGIN { print 1.8 + m * 1.8 }')
watch_fault 0x20
debug position insertion 2.0
expect_fault "sim travel" travel insertion "position 2 m" "end of travel $end m"
check "sim travel: the limit passed is the end plus the margin" \
	approx "$(watched fault_limit)" "$end" 1e-9 0
refused_while "sim travel"
debug clear insertion
recovers "sim travel"
stop_daemon

check "Modbus rig up, enabled" start_mb_rig
watch_fault 0x20
mb "place 1 652" # 652 / 2048 turns: 2.0 rad, past 1.75 rad and the margin
mb "move 1 0"     # and held there
expect_fault "Modbus travel" travel wheel_ud "beyond the end of travel"
check "Modbus travel: both wheel drives disabled, no torque" wait_for wheels_off
refused_while "Modbus travel"
mb "place 1 0"
mb "hand 1 0.004 1"
recovers "Modbus travel"
finish
