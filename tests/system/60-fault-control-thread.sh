#!/bin/bash
# A dead control thread: nobody can command the daemon any more. The force
# loop latches an internal fault (torque zero on every axis in the cycle
# that takes it), the drives are brought down and disabled, and endosimd
# stops with exit status 70 so that systemd restarts it (Restart=
# on-failure). The thread is made to end by a test command.
. "$(dirname "$0")/fault_lib.sh"

check "rig up (wheels on Modbus, the rest simulated), enabled" start_mb_rig
watch_fault 0x200
check "the control thread told to end" ctl debug end-control
witnessed "control thread ended" internal none
wait "$DAEMON_PID"
rc=$?
DAEMON_PID=""
check "endosimd stopped with exit status 70 (EX_SOFTWARE)" [ "$rc" = 70 ]
check "the journal: the fault" \
	journal_says internal "the control thread ended"
check "the journal: why it stops" \
	grep -q "control thread ended: torque off; stopping (exit 70)" "$LOG"
check "both wheel drives disabled, no torque" wait_for wheels_off
check "sockets removed" test ! -e "$SOCK/control.sock" -a ! -e "$SOCK/status.sock"
grep -q "Restart=on-failure" "$TOP/systemd/endosimd.service" &&
	! grep -q "RestartPreventExitStatus=.*70" "$TOP/systemd/endosimd.service"
check "the unit restarts it on that exit status" [ $? = 0 ]
finish
