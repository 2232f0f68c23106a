#!/bin/bash
# Fault: a NaN or infinity anywhere in the force pipeline. On the simulated
# rig a NaN put by the test command into each stage in turn: the rig's
# feedback, the scope's pose (kinematics), the haptic rendering's parts,
# the force command; on the Modbus line a wheel drive's velocity register
# (a float) reading NaN, through the real decoding. Each: FAULT naming the
# stage, torque zero on every axis in the cycle that sees it; reset refused
# while it persists, recovered once it is gone.
. "$(dirname "$0")/fault_lib.sh"

check "simulated rig up, enabled, every axis moving" start_sim
stage_name=("" "rig's feedback" "scope's pose" "haptic rendering" "force command")
stage_axis=("" insertion none none roll)
for stage in 1 2 3 4; do
	what="sim NaN in the ${stage_name[$stage]}"
	axis=${stage_axis[$stage]}
	watch_fault 0x100
	debug nan "$([ "$axis" = none ] && echo wheel_ud || echo "$axis")" "$stage"
	expect_fault "$what" non-finite "$axis" "nan in the ${stage_name[$stage]}"
	check "$what: its stage" [ "$(watched fault_detail)" = "$stage" ]
	refused_while "$what"
	debug clear
	recovers "$what"
	check "$what: forces in full" wait_for status_true '.ramp == 1'
done
stop_daemon

check "Modbus rig up, enabled" start_mb_rig
watch_fault 0x100
mb "nan 1 on"
expect_fault "Modbus NaN" non-finite wheel_ud "nan in the rig's feedback"
check "Modbus NaN: both wheel drives disabled, no torque" wait_for wheels_off
refused_while "Modbus NaN"
mb "nan 1 off"
recovers "Modbus NaN"
finish
