#!/bin/bash
# A client's commands are never a fault cause on their own. With the test
# commands off (the default) they are refused, and cannot be switched on
# through the socket. Then, while ENABLED with every axis moving, a barrage
# of everything a client may send: the hand at its strongest in every
# direction, non-finite and out-of-range values, every live limit at its
# extremes for a moment, enable and disable in a burst, subscriptions at
# the highest rate, garbage on both sockets. The witness in shared memory
# sees no fault latched, and no state with torque where none is allowed.
. "$(dirname "$0")/fault_lib.sh"

check "simulated rig up (test commands off), every axis moving" \
	start_daemon "${FAULT_ARGS[@]}" --scenario "$SOAK"
check_status "test commands refused" 1 ctl debug stall 1
check "... saying why" grep -q "test_commands = no" "$OUT"
check_status "... on the read-only socket too" 1 \
	ctl --socket "$SOCK/status.sock" debug drive-gone roll
check_status "the switch is not live" 1 ctl set debug.test_commands yes
check "enabled" ctl enable
check "forces in full" wait_for status_true '.ramp == 1'

watch_fault 0xffff 60
for axis in 0 1 2 3; do
	for f in 1000 -1000; do
		force=(0 0 0 0)
		force[$axis]=$f
		ctl hand "${force[@]}" --hold-ms 250 >/dev/null
		sleep 0.3
	done
done
check_status "a NaN hand refused" 1 ctl hand nan 0 0 0
check_status "an infinite hand refused" 1 ctl hand 0 inf 0 0
check_status "a hold over 10 s refused" 1 ctl hand 1 0 0 0 --hold-ms 60000
for kv in limits.insertion_max_force_n:0:100 limits.roll_max_torque_n_m:0:5 \
	limits.wheel_ud_max_torque_n_m:0:1 limits.wheel_lr_max_torque_n_m:0:1 \
	limits.enable_ramp_s:0:10 scope.bending_length_m:0.01:0.3 \
	scope.ud_gain_rad_per_rad:0:20 scope.ud_limit_rad:0:3.1416 \
	haptics.wall_stiffness_n_per_m:0:20000 log.level:debug:err; do
	IFS=: read -r key lo hi <<<"$kv"
	was=$(ctl get "$key")
	for v in "$lo" "$hi"; do
		ctl set "$key" "$v" >/dev/null && sleep 0.1
	done
	ctl set "$key" "$was" >/dev/null
	check_status "$key: out of range refused" 1 ctl set "$key" 1e9
done
check_status "a key that is not live refused" 1 ctl set limits.saturation_s 0.001
for i in $(seq 1 20); do
	ctl disable >/dev/null
	ctl enable >/dev/null
done
pids=""
for i in 1 2 3 4 5; do
	ctl --json watch --rate 1000 --duration 1 >/dev/null &
	pids="$pids $!"
done
for s in control.sock status.sock; do
	head -c 5000 /dev/urandom | timeout 5 socat -t 1 - "UNIX-CONNECT:$SOCK/$s" >/dev/null 2>&1
	printf '\377\377\377\177' | timeout 5 socat -t 1 - "UNIX-CONNECT:$SOCK/$s" >/dev/null 2>&1
done
check_status "a case load while ENABLED refused" 1 ctl case load normal
wait $pids
sleep 0.5
kill -TERM "$WATCH_PID" 2>/dev/null # it reports what it saw, and ends
wait "$WATCH_PID"
check "the witness watched throughout ($(watched states) states)" \
	[ "$(watched states)" -gt 1000 ]
check "no fault latched" [ -z "$(watched fault_bit)" ]
check "no state with torque where none is allowed" \
	[ "$(watched torque_violations)" = 0 ]
check "still ENABLED, no fault bits" \
	[ "$(status_field .state)/$(status_field .fault_bits)" = ENABLED/0 ]
check "no FAULT in the journal" sh -c "! grep -q 'error: FAULT' '$LOG'"
finish
