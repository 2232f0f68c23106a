#!/bin/bash
# run.sh - runs every test suite and sums them up in one closing line,
# "N passed, N failed"; exits non-zero when anything failed. Called by
# `make check` (and so `make test`).
#
# Suites: the cmocka unit tests and the numbered system tests of the build
# in $BUILD; the same again for the AddressSanitizer/UBSan build in
# $BUILD/asan when it exists (with SANITIZED=1: a long test may shorten
# what checks only timing, not memory, there); a short run of each fuzz
# target in $BUILD/fuzz when they exist ($FUZZ_SECONDS each, default 5).
set -u

TOP=$(cd "$(dirname "$0")/.." && pwd)
cd "$TOP" || exit 1
: "${BUILD:=build}"
passed=0
failed=0
failed_suites=""
out=$(mktemp)
trap 'rm -f "$out"' EXIT

# count SUITE EXIT_STATUS: adds the tally the suite printed in $out.
count() {
	local suite=$1 rc=$2 p f line
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
	[ "$f" -eq 0 ] || failed_suites="$failed_suites $suite"
	printf '%-34s %4d passed, %d failed  (%d s)\n' "$suite" "$p" "$f" \
		$((SECONDS - started))
}

# run_suites BUILD_DIR PREFIX: unit and system tests of one build.
run_suites() {
	local build=$1 prefix=$2 t rc name units
	# the unit tests need no real time: as many at once as there are CPUs,
	# each into its own files (output, exit status, seconds), then counted
	units=$(mktemp -d)
	for t in "$build"/tests/test_*; do
		case "$t" in *.d) continue ;; esac
		[ -x "$t" ] && printf '%s\0' "$t"
	done | xargs -0 -r -P "$(nproc)" -I{} sh -c \
		'n=$(basename "$1"); s=$(date +%s); "$1" >"$2/$n.out" 2>&1
		 echo $? >"$2/$n.rc"; echo $(($(date +%s) - s)) >"$2/$n.s"' \
		_ {} "$units"
	for t in "$units"/*.out; do
		[ -e "$t" ] || continue
		name=$(basename "$t" .out)
		cp "$t" "$out"
		rc=$(cat "$units/$name.rc")
		started=$((SECONDS - $(cat "$units/$name.s")))
		count "${prefix}unit/$name" "$rc"
		[ "$rc" -eq 0 ] || grep -vE 'OK \]|RUN  ' "$out" | tail -n 20 | sed 's/^/    /'
	done
	rm -rf "$units"
	for t in tests/system/[0-9]*.sh; do
		[ -e "$t" ] || continue
		started=$SECONDS
		BUILD="$build" SANITIZED=$sanitized timeout 300 bash "$t" \
			>"$out" 2>&1
		rc=$?
		count "${prefix}system/$(basename "$t" .sh)" $rc
		[ $rc -eq 0 ] || tail -n 40 "$out" | sed 's/^/    /'
	done
}

sanitized=
run_suites "$BUILD" ""
if [ -d "$BUILD/asan/tests" ]; then
	sanitized=1 # a system test may shorten what only checks timing
	run_suites "$BUILD/asan" "asan/"
fi
if [ -d "$BUILD/fuzz" ]; then
	started=$SECONDS
	FUZZ_SECONDS=${FUZZ_SECONDS:-5} tests/fuzz/run.sh "$BUILD/fuzz" >"$out" 2>&1
	count "fuzz" $?
	grep -v "passed, .* failed$" "$out" | sed 's/^/    /'
fi
if [ -n "$failed_suites" ]; then
	echo "failed:$failed_suites"
fi
echo "(the suites took $((SECONDS / 60)) min $((SECONDS % 60)) s)"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
