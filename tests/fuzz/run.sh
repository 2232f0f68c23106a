#!/bin/bash
# run.sh DIR - runs every libFuzzer target in DIR for $FUZZ_SECONDS (default
# 60) from its seed corpus tests/fuzz/NAME/ (new inputs go to a scratch
# copy, not into the repository). Prints executions and coverage per
# target, then "N passed, N failed": a target fails when it crashes, leaks
# or trips a sanitizer (its exit status, or any sanitizer or libFuzzer
# report in its output: a report that did not stop it still fails it); the
# crashing input is kept in tests/fuzz/crash-*.
# Runs $FUZZ_JOBS targets at once (default: as many as there are CPUs).
set -u
dir=${1:?usage: run.sh BUILD_DIR_OF_FUZZERS}
here=$(cd "$(dirname "$0")" && pwd)
seconds=${FUZZ_SECONDS:-60}
passed=0
failed=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
jobs=${FUZZ_JOBS:-$(nproc)}
# what a sanitizer or libFuzzer prints when it finds something
REPORTS='runtime error:|ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)'

# fuzz BIN: one target; its verdict in $tmp/NAME.result, its status in .rc
fuzz() {
	local bin=$1 name seeds rc execs cov why
	name=$(basename "$bin")
	seeds="$here/${name#fuzz_}"
	mkdir -p "$tmp/$name"
	"$bin" -max_total_time="$seconds" -print_final_stats=1 \
		-artifact_prefix="$here/crash-$name-" "$tmp/$name" "$seeds" \
		>"$tmp/$name.log" 2>&1
	rc=$?
	why="exit $rc"
	if [ $rc -eq 0 ] && grep -qE "$REPORTS" "$tmp/$name.log"; then
		rc=1
		why="exit 0, but a sanitizer report"
	fi
	execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$tmp/$name.log")
	cov=$(grep -oE 'cov: [0-9]+' "$tmp/$name.log" | tail -n 1)
	if [ $rc -eq 0 ]; then
		echo "ok - $name: ${execs:-?} executions in ${seconds} s, ${cov:-cov: ?} edges"
	else
		echo "not ok - $name ($why)"
		grep -E "$REPORTS|ERROR|SUMMARY" "$tmp/$name.log" | head -n 5 | sed 's/^/#   /'
	fi >"$tmp/$name.result"
	echo $rc >"$tmp/$name.rc"
}

# $FUZZ_JOBS targets at once (default: one per CPU), reported in order
for bin in "$dir"/fuzz_*; do
	[ -x "$bin" ] || continue
	while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do
		wait -n
	done
	fuzz "$bin" &
done
wait
for bin in "$dir"/fuzz_*; do
	name=$(basename "$bin")
	[ -e "$tmp/$name.rc" ] || continue
	cat "$tmp/$name.result"
	if [ "$(cat "$tmp/$name.rc")" -eq 0 ]; then
		passed=$((passed + 1))
	else
		failed=$((failed + 1))
	fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
