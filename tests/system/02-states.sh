#!/bin/bash
# IDLE -> ENABLED on enable, ESTOP latched, reset back to IDLE; torque only
# while ENABLED.
. "$(dirname "$0")/../common.sh"

start_daemon || finish
state() { status_field .state; }

# the simulated hand pushes the carriage gently (about 0.2 m/s, nowhere
# near the end of travel in this test), so the haptics render a force
# (the axis' damping, and the friction of the inserted tube)
check "hand input accepted" ctl hand 1 0 0 0 --hold-ms 5000
sleep 0.3
check "IDLE: a force is computed" test "$(status_field '.axes.insertion.command != 0')" = true
check "IDLE: but none reaches the drive" test "$(status_field '.axes.insertion.limited')" = 0
check "enable" ctl enable
check "-> ENABLED" test "$(state)" = ENABLED
sleep 0.1
check "ENABLED: the force reaches the drive" \
	test "$(status_field '.axes.insertion.limited != 0')" = true
check "disable" ctl disable
check "-> IDLE" test "$(state)" = IDLE
check "IDLE again: no torque" test "$(status_field '.axes.insertion.limited')" = 0
check "enable again" ctl enable
check "estop" ctl estop
check "-> ESTOP" test "$(state)" = ESTOP
check "ESTOP: no torque on any axis" \
	test "$(ctl --json status | jq '[.axes[].limited] | all(. == 0)')" = true
check_status "enable refused while ESTOP is latched" 1 ctl enable
check "disable does not clear ESTOP" sh -c "'$ENDOCTL' --socket '$SOCK' disable && test \"\$('$ENDOCTL' --socket '$SOCK' --json status | jq -r .state)\" = ESTOP"
check "reset" ctl reset
check "-> IDLE" test "$(state)" = IDLE
check "enable works after reset" ctl enable
check "-> ENABLED" test "$(state)" = ENABLED
check "transitions are logged" grep -q "state ENABLED -> ESTOP (emergency stop)" "$LOG"
finish
