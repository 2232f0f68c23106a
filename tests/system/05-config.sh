#!/bin/bash
# Bad configuration exits 78 (EX_CONFIG) naming file, line and key, before
# anything else happens; good configuration validates and round-trips.
. "$(dirname "$0")/../common.sh"

conf="$TMP/test.conf"
run() { endosimd "$@"; }

check "the shipped configuration validates" \
	endosimd --check-config --config "$TOP/config/endosimd.conf"
printf '[loop]\nrate_hz = 1000\n\n[limits]\nroll_max_torque_n_m = 7\n' >"$conf"
check_status "out of range: exit 78" 78 run --config "$conf"
check "names file, line and key" grep -q "$conf:5: \[limits\] roll_max_torque_n_m: 7 is out of range" "$OUT"
check "nothing was created before the check" test ! -e "$SOCK"
printf '[loop]\nrate_hz = 1000\nspeed = 3\n' >"$conf"
check_status "unknown key: exit 78" 78 run --config "$conf"
check "names the unknown key" grep -q "$conf:3: \[loop\] speed: unknown key" "$OUT"
printf '[loop]\npriority = high\n' >"$conf"
check_status "wrong type: exit 78" 78 run --config "$conf"
printf '[loop]\npriority = 50\npriority = 60\n' >"$conf"
check_status "duplicate: exit 78" 78 run --config "$conf"
check "names the duplicate" grep -q "duplicate key (first set on line 2)" "$OUT"
: >"$conf"
check_status "empty file: exit 78" 78 run --config "$conf"
check_status "missing file: exit 78" 78 run --config "$TMP/nope.conf"
check "names the missing file" grep -q "$TMP/nope.conf: cannot open" "$OUT"
check_status "bad override: exit 78" 78 run --set loop.rate_hz=1
printf '0 elbow free\n' >"$TMP/bad.scn"
check_status "bad scenario: exit 78" 78 run --scenario "$TMP/bad.scn"
check "names the scenario line" grep -q "bad.scn:1: unknown axis" "$OUT"
check_status "unknown option: usage (64)" 64 run --frobnicate
"$ENDOSIMD" --config "$TOP/config/endosimd.conf" --set limits.insertion_max_force_n=12.5 --print-config >"$conf"
check "--print-config shows units" grep -q '^insertion_max_force_n = 12.5 .*\[N\]' "$conf"
check "--print-config output validates" endosimd --check-config --config "$conf"
check "and keeps the override" sh -c "'$ENDOSIMD' --config '$conf' --print-config | grep -q '^insertion_max_force_n = 12.5 '"
check "command line overrides the file" sh -c "'$ENDOSIMD' --config '$conf' --shm-name /other --print-config | grep -q '^name = /other '"
finish
