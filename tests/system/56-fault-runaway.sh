#!/bin/bash
# Fault: a runaway, speed above [limits] *_max_speed. On the simulated rig
# (the roll's speed made to read 40 rad/s) and on the Modbus line (a wheel
# motor spun at 400 rpm, 42 rad/s, by the emulated hand): FAULT with torque
# zero on every axis in the cycle that sees it, the drives disabled;
# reset refused while it spins, recovered once it has stopped.
. "$(dirname "$0")/fault_lib.sh"

check "simulated rig up, enabled, every axis moving" start_sim
watch_fault 0x40
debug speed roll 40
expect_fault "sim runaway" runaway roll "speed 40 rad/s" "limit 30 rad/s"
refused_while "sim runaway"
debug clear roll
recovers "sim runaway"
stop_daemon

check "Modbus rig up, enabled" start_mb_rig
mb "place 2 -554" # -1.7 rad: room to spin before the other end
mb "move 2 0"
watch_fault 0x40
mb "move 2 400"
expect_fault "Modbus runaway" runaway wheel_lr "a runaway"
check "Modbus runaway: measured above 30 rad/s ($(watched fault_value))" \
	awk -v v="$(watched fault_value)" 'BEGIN { exit !(v > 30 && v < 50) }'
check "Modbus runaway: both wheel drives disabled, no torque" \
	wait_for wheels_off
refused_while "Modbus runaway"
mb "move 2 0"
mb "place 2 0"
mb "hand 2 0.004 1.3"
recovers "Modbus runaway"
finish
