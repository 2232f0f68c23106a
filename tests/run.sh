#!/bin/bash
# run.sh - runs every test suite (the cmocka unit tests, then the numbered
# system tests) and sums them up in a closing line "N passed, N failed".
# Exits non-zero when anything failed. Called by `make check`/`make test`.
set -u

TOP=$(cd "$(dirname "$0")/.." && pwd)
cd "$TOP" || exit 1
: "${BUILD:=build}"
: "${SUITE_PREFIX:=}"
export BUILD
passed=0
failed=0
failed_suites=""

# count SUITE OUTPUT_FILE EXIT_STATUS: adds the suite's own tally.
count() {
	local suite=$1 out=$2 rc=$3 p f line
	line=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$out" | tail -n 1)
	if [ -n "$line" ]; then
		p=${line%% passed*}
		f=${line#*passed, }
		f=${f%% failed*}
	else
		# cmocka: "[  PASSED  ] N test(s)." and "[  FAILED  ] N test(s),"
		p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$out" | tail -n 1)
		f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test(s), .*/\1/p' "$out" | tail -n 1)
		p=${p:-0}
		f=${f:-0}
	fi
	# a suite that crashed or exited non-zero without saying so fails once
	if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
		f=1
	fi
	passed=$((passed + p))
	failed=$((failed + f))
	if [ "$f" -ne 0 ]; then
		failed_suites="$failed_suites $suite"
	fi
	printf '%-32s %4d passed, %d failed\n' "$suite" "$p" "$f"
}

out=$(mktemp)
for t in "$BUILD"/tests/test_*; do
	case "$t" in *.d) continue ;; esac
	[ -x "$t" ] || continue
	"$t" >"$out" 2>&1
	rc=$?
	count "${SUITE_PREFIX}unit/$(basename "$t")" "$out" $rc
	[ $rc -eq 0 ] || sed 's/^/    /' "$out" | grep -vE 'OK \]|RUN  ' | tail -n 20
done
for t in tests/system/[0-9]*.sh; do
	[ -e "$t" ] || continue
	timeout 300 bash "$t" >"$out" 2>&1
	rc=$?
	count "${SUITE_PREFIX}system/$(basename "$t" .sh)" "$out" $rc
	[ $rc -eq 0 ] || sed 's/^/    /' "$out" | tail -n 40
done
# a short run of each fuzz target (make fuzz runs them longer)
if [ -d "$BUILD/fuzz" ] && [ -z "$SUITE_PREFIX" ]; then
	FUZZ_SECONDS=${FUZZ_SECONDS:-5} tests/fuzz/run.sh "$BUILD/fuzz" >"$out" 2>&1
	rc=$?
	count "fuzz" "$out" $rc
	sed 's/^/    /' "$out" | grep -v "passed, .* failed$"
fi
rm -f "$out"
if [ -n "$failed_suites" ]; then
	echo "failed:$failed_suites"
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
