#!/bin/bash
# A separate reader process sees consistent, advancing states in shared
# memory, and the same state endoctl reports.
. "$(dirname "$0")/../common.sh"

start_daemon --scenario "$TOP/config/scenarios/demo.scn" || finish
check "shm object exists, world-readable" test "$(stat -c %a "/dev/shm$SHM")" = 644
check "300 reads: consistent and advancing" "$TOOLS/shm_probe" "$SHM" 300 1000
check "shm says IDLE" sh -c "'$TOOLS/shm_probe' '$SHM' --once | grep -qx state=IDLE"
ctl enable >/dev/null
check "shm follows enable" sh -c "'$TOOLS/shm_probe' '$SHM' --once | grep -qx state=ENABLED"
check "consistent while the hand moves the rig" "$TOOLS/shm_probe" "$SHM" 300 500
check "a reader of another layout is refused" sh -c "! '$TOOLS/shm_probe' /endosim-none-$$ 1"
finish
