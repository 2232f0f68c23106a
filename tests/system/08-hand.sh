#!/bin/bash
# The simulated rig: the scripted hand inserts, twists and steers; live
# hand input through the socket takes over while it holds, clamped to the
# hand's strength, and expires. Every check waits on a state. How fast the
# strongest push moves the carriage is behaviour over cycles: checked in
# lockstep by tests/unit/test_course.c (test_hand_top_speed).
. "$(dirname "$0")/../common.sh"

# A quick hand that stays in the straight anal canal, short of the
# rectal wall, so that its own push never reaches hand_insertion_max_n.
# The paper's model: its rectal wall holds the tip where the live push
# below ends (the rod model's tube slides on along the wall, deep).
printf '%s\n' '# a quick hand: insert, twist, steer' \
	'0 insertion target 0.04 2' '0 roll target 0.5 1' \
	'0 wheel_ud target 0.5 1' '30 end' >"$TMP/hand.scn"
start_daemon --scenario "$TMP/hand.scn" --set haptics.model=paper || finish
ctl enable >/dev/null
check "the scenario runs" wait_for status_true '.scenario_time_s > 1'
check "the hand inserts the scope" wait_for status_true '.axes.insertion.position > 0.03'
check "the hand twists the tube" wait_for status_true '.axes.roll.position > 0.2'
check "the hand steers up" wait_for status_true '.axes.wheel_ud.position > 0.2' 
check "live input" ctl hand 0 0 0 0.1 --hold-ms 800
check "live input shows as the hand's torque (at most 0.1 N m)" \
	wait_for status_true '.axes.wheel_lr.hand > 0 and .axes.wheel_lr.hand <= 0.1'
check "live input moves the wheel" wait_for status_true '.axes.wheel_lr.position > 0.1' 
check "live input clamped to the hand's strength" ctl hand 1000 0 0 0 --hold-ms 1500
check "clamped to hand_insertion_max_n (40 N; the scenario's stays under 30)" \
	wait_for status_true '.axes.insertion.hand > 30 and .axes.insertion.hand <= 40'
# the push carries the carriage to the rectal wall (0.26 m) and holds it
# there; once it expires, the scenario's hand takes it back to 0.04 m
check "the push carries the carriage in (past 0.1 m)" \
	wait_for status_true '.axes.insertion.position > 0.1'
check "live input expires: the scenario's hand takes it back (under 0.05 m)" \
	wait_for status_true '.axes.insertion.position < 0.05'
check_status "wrong number of forces: usage" 2 ctl hand 1 2 3
check_status "non-finite force refused" 1 ctl hand nan 0 0 0
finish
