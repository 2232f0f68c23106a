#!/bin/bash
# The simulated rig: the scripted hand inserts, twists and steers; live
# hand input through the socket takes over while it holds, clamped to the
# hand's strength and fading to nothing at the hand's top speed.
. "$(dirname "$0")/../common.sh"

# A quick hand that stays in the straight anal canal, short of the
# rectal wall, so that its own push never reaches hand_insertion_max_n.
printf '%s\n' '# a quick hand: insert, twist, steer' \
	'0 insertion target 0.04 2' '0 roll target 0.5 1' \
	'0 wheel_ud target 0.5 1' '30 end' >"$TMP/hand.scn"
start_daemon --scenario "$TMP/hand.scn" || finish
ctl enable >/dev/null
check "the scenario runs" wait_for status_true '.scenario_time_s > 1'
check "the hand inserts the scope" wait_for status_true '.axes.insertion.position > 0.03'
check "the hand twists the tube" wait_for status_true '.axes.roll.position > 0.2'
check "the hand steers up" wait_for status_true '.axes.wheel_ud.position > 0.2' 
check "live input" ctl hand 0 0 0 0.1 --hold-ms 800
check "live input shows as the hand's torque (at most 0.1 N m)" \
	status_true '.axes.wheel_lr.hand > 0 and .axes.wheel_lr.hand <= 0.1' 
check "live input moves the wheel" wait_for status_true '.axes.wheel_lr.position > 0.1' 
check "live input clamped to the hand's strength" ctl hand 1000 0 0 0 --hold-ms 500
check "clamped to hand_insertion_max_n" \
	status_true '.axes.insertion.hand > 0 and .axes.insertion.hand <= 40' 
sleep 0.7
check "live input expires: the scenario's hand is back" \
	test "$(status_field '.axes.insertion.hand != 40')" = true
# the strongest push the socket allows never makes the carriage faster
# than the hand's top speed (then the push has faded to nothing)
top=$(ctl get sim.hand_insertion_max_speed_m_s)
ctl hand 1000 0 0 0 --hold-ms 1500 >/dev/null
ctl --json watch --rate 200 --duration 1 >"$TMP/push.json"
fastest=$(jq -s 'map(.axes.insertion.velocity) | max' "$TMP/push.json")
check "pushed as hard as allowed: $fastest m/s, top speed $top m/s" \
	awk -v v="$fastest" -v top="$top" 'BEGIN { exit !(v > 0.3 && v <= top) }'
check_status "wrong number of forces: usage" 2 ctl hand 1 2 3
check_status "non-finite force refused" 1 ctl hand nan 0 0 0
finish
