#!/bin/bash
# The source tree runs: with [case] directory left at its compiled-in
# default, which a checkout has not installed, endosimd finds the shipped
# cases in cases/ beside the configuration file (config/cases); where they
# are not there either, the error names the option that says where they are.
. "$(dirname "$0")/../common.sh"

# the tests' daemon arguments without their case.directory
args=()
for ((i = 0; i < ${#DAEMON_ARGS[@]}; i++)); do
	if [[ ${DAEMON_ARGS[i + 1]:-} = case.directory=* ]]; then
		i=$((i + 1)) # --set and its value
	else
		args+=("${DAEMON_ARGS[i]}")
	fi
done
DAEMON_ARGS=("${args[@]}")

printf '[loop]\nrate_hz = 1000\n' >"$TMP/bare.conf"
default=$("$ENDOSIMD" --config "$TMP/bare.conf" --print-config |
	sed -n 's/^directory = \([^ ]*\) .*case files.*/\1/p')
check "the compiled-in case directory is known ($default)" test -n "$default"
if [ -e "$default/normal.case" ]; then
	skip "the cases are installed in $default: found there first"
	finish
fi

check_status "from the checkout: config/endosimd.conf validates" 0 \
	sh -c 'cd "$1" && "$2" --config config/endosimd.conf --check-config' \
	_ "$TOP" "$ENDOSIMD"
start_daemon || finish
check "it runs the shipped case" test "$(status_field .case)" = normal
check "from config/cases" \
	test "$(ctl get case.directory)" = "$TOP/config/cases"
check "which case list reads" sh -c "'$ENDOCTL' --socket '$SOCK' case list |
	grep -q polyps"
stop_daemon

cp "$TOP/config/endosimd.conf" "$TMP/endosimd.conf"
check_status "a configuration with no cases beside it: exit 78" 78 \
	endosimd --config "$TMP/endosimd.conf" --check-config
check "names the file it looked for" \
	grep -q "$default/normal.case: cannot open" "$OUT"
check "and the option to set" \
	grep -q "\[case\] directory or --set case.directory=DIR" "$OUT"
check_status "a directory set without the case: exit 78, no fallback" 78 \
	endosimd --config "$TOP/config/endosimd.conf" --check-config \
	--set "case.directory=$TMP"
check "naming that directory and the option" \
	grep -q "no normal.case in $TMP: .*--set case.directory=DIR" "$OUT"
finish
