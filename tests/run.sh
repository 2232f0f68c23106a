#!/bin/bash
# run.sh - runs every test suite and sums them up in one closing line,
# "N passed, N failed, N skipped"; exits non-zero when anything failed.
# Called by `make check` (and so `make test`). A skipped check (one that
# cannot be made here: common.sh's skip) neither passes nor fails; the
# suites that skipped any are named at the end, with why.
#
# Suites: the include check of the wings (tests/layers.sh), the commit
# messages' form (tests/commits.sh), the cmocka
# unit tests and the numbered system tests of the build in $BUILD; for the
# AddressSanitizer/UBSan build in $BUILD/asan when it exists, every unit
# test again and the system tests in ASAN_SYSTEM (with SANITIZED=1: a test
# may shorten what checks only timing, not memory, there); a short run of
# each fuzz target in $BUILD/fuzz when they exist ($FUZZ_SECONDS each,
# default 2).
#
# The unit tests need no real time: as many run at once as there are CPUs.
# The system tests that time something, or talk to emulated drives whose
# framing is a matter of microseconds, or stall or starve the machine on
# purpose, run one at a time with nothing beside them (tried: two streams
# of every system test at once broke the Modbus RTU tests); the others,
# which wait on states and mostly wait for a course in real time, run two
# at a time (SYSTEM_POOL), with the sanitizers' and the fuzz targets'.
set -u

# The system tests the sanitizers' build runs: with the unit tests they
# take each wing of endosimd through ASan and UBSan: the published state
# and the status socket (01), the control socket's hostile input (04),
# the drives on Modbus TCP (31) and on EPOS4 over USB with the safety
# chain's faults (50), the recorder with a session and its inputs (73),
# the patient (78). The plain pass runs every system test; all of them
# again under the sanitizers took 11 minutes, more than the whole run may
# (tests/README.md).
ASAN_SYSTEM="01-status 04-hostile 31-drives-tcp 50-fault-drive
	73-session-input 78-patient"

# The system tests that may run beside another (two at a time, the
# longest first): each waits on states, never on elapsed time, reads and
# writes only its own temporary directory, sockets, shm name, X server
# (Xvfb -displayfd) and PostgreSQL cluster, and times nothing; each
# passed with the machine loaded to 8 by four builds. The rest run alone
# before them: the loop's rate and latency (01, 15), the slow disk's
# overruns (71), the drives on their emulators (30-33, the faults 50-66),
# valgrind's (13), and those that look at the machine itself: another
# daemon (10), systemd (11), a user (12), the source tree's defaults (18).
# A new test runs alone until it is put here. The sanitizers' in the pool:
# those of ASAN_SYSTEM named here too.
SYSTEM_POOL="43-viewer-voice 41-replay 40-viewer 42-viewer-patient
	76-trainee 80-centre 46-viewer-bleed 77-live-map 78-patient
	72-report 79-records 82-roles 44-viewer-tool 75-guide 83-centre-roles
	84-records-kill 73-session-input 70-session 74-session-rod 19-docs
	81-tool 14-case 16-haptics 45-replay-tool 85-record-names 02-states
	03-readonly 04-hostile 05-config 06-sigterm 07-shm 08-hand
	09-subscribe 17-socket-security"

# The unit tests that take longest (over 10 s on this 2-CPU VM, in either
# build), the longest first: they start first, so that none of them starts
# last and runs alone while the other CPU idles (the queue's 405 s of CPU
# took 222 s in the tests' order, 204 s so).
LONG_UNITS="test_separation test_rodcourse test_clinic test_hand test_lod
	test_patient test_haptics test_metrics"

TOP=$(cd "$(dirname "$0")/.." && pwd)
cd "$TOP" || exit 1
: "${BUILD:=build}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
: >"$work/results" # SUITE PASSED FAILED SKIPPED, one line per suite
: >"$work/why"     # the failed checks, repeated at the end for CI's tail
: >"$work/skips"   # SUITE: WHY, one line per skipped check

# record SUITE OUT RC SECONDS: counts the tally the suite printed in OUT,
# prints its line (and the end of its output when it failed).
record() {
	local suite=$1 out=$2 rc=$3 secs=$4 p f s=0 line
	line=$(grep -E '^[0-9]+ passed, [0-9]+ failed(, [0-9]+ skipped)?$' \
		"$out" | tail -n 1)
	if [ -n "$line" ]; then
		p=${line%% passed*}
		f=${line#*passed, }
		f=${f%% failed*}
		case "$line" in
		*skipped)
			s=${line##*failed, }
			s=${s% skipped}
			;;
		esac
	else
		# cmocka: "[  PASSED  ] N test(s)." and "[  FAILED  ] N test(s),"
		p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$out" | tail -n 1)
		f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test(s), .*/\1/p' "$out" | tail -n 1)
		s=$(sed -n 's/^\[  SKIPPED \] \([0-9]*\) test.*/\1/p' "$out" | tail -n 1)
		p=${p:-0}
		f=${f:-0}
		s=${s:-0}
	fi
	# a suite that crashed or exited non-zero without saying so fails once
	if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
		f=1
	fi
	echo "$suite $p $f $s" >>"$work/results"
	printf '%-34s %4d passed, %d failed%s  (%d s)\n' "$suite" "$p" "$f" \
		"$([ "$s" -eq 0 ] || echo ", $s skipped")" "$secs"
	sed -n "s|^skip - |$suite: |p" "$out" >>"$work/skips"
	if [ "$f" -ne 0 ]; then
		grep -vE '^\[ +(OK|RUN) +\]|^ok - ' "$out" | tail -n 60 |
			sed 's/^/    /'
		printf '%s:\n%s\n' "$suite" "$(grep -E -A1 \
			'^not ok|^\[  FAILED  \]|ERROR: AddressSanitizer|runtime error' \
			"$out" | grep -v '^--$' | head -n 12 | sed 's/^/  /')" \
			>>"$work/why"
	fi
}

# unit_tests BUILD_DIR:PREFIX...: the unit tests of each build, as many
# at once as there are CPUs from one queue (LONG_UNITS first, the
# longest first, then the rest in order), each into its own files (output, exit
# status, seconds), then recorded in order.
unit_tests() {
	local dir=$work/units pair build prefix t name long
	long=" $(echo $LONG_UNITS) "
	mkdir -p "$dir"
	{
		for name in $LONG_UNITS; do
			for pair in "$@"; do
				t=${pair%%:*}/tests/$name
				prefix=${pair#*:}
				[ -x "$t" ] && printf '%s\0%s\0' "$t" \
					"${prefix//\//-}"
			done
		done
		for pair in "$@"; do
			build=${pair%%:*}
			prefix=${pair#*:}
			for t in "$build"/tests/test_*; do
				case "$t" in *.d) continue ;; esac
				case "$long" in
				*" ${t##*/} "*) continue ;;
				esac
				[ -x "$t" ] && printf '%s\0%s\0' "$t" \
					"${prefix//\//-}"
			done
		done
	} | xargs -0 -r -n 2 -P "$(nproc)" sh -c \
		'n=$3$(basename "$2"); s=$(date +%s); "$2" >"$1/$n.out" 2>&1
		 echo $? >"$1/$n.rc"; echo $(($(date +%s) - s)) >"$1/$n.s"' \
		_ "$dir"
	for pair in "$@"; do
		prefix=${pair#*:}
		for t in "$dir/${prefix//\//-}"test_*.out; do
			[ -e "$t" ] || continue
			name=$(basename "$t" .out)
			name=${name#"${prefix//\//-}"}
			record "${prefix}unit/$name" "$t" \
				"$(cat "${t%.out}.rc")" "$(cat "${t%.out}.s")"
		done
	done
	rm -rf "$dir"
}

# in_list NAME LIST: whether the word NAME is in LIST
in_list() {
	[[ " $(echo $2) " == *" $1 "* ]]
}

# system_job OUT BUILD SANITIZED TEST: one system test into OUT.out, its
# exit status into OUT.rc and its seconds into OUT.s; a test that ran out
# of its 300 s says so as a failed check. (Run by xargs too: exported.)
system_job() {
	local out=$1 build=$2 sanitized=$3 t=$4 started=$SECONDS rc
	BUILD="$build" SANITIZED=$sanitized timeout -k 20 300 bash "$t" \
		>"$out.out" 2>&1
	rc=$?
	if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
		echo "not ok - $(basename "$t") ran out of its 300 s" \
			>>"$out.out"
	fi
	echo "$rc" >"$out.rc"
	echo $((SECONDS - started)) >"$out.s"
}
export -f system_job

# system_tests BUILD_DIR PREFIX SANITIZED NAMES: those of NAMES (a list)
# in order, one at a time.
system_tests() {
	local build=$1 prefix=$2 sanitized=$3 names=$4 t name
	for t in tests/system/[0-9]*.sh; do
		[ -e "$t" ] || continue
		name=$(basename "$t" .sh)
		in_list "$name" "$names" || continue
		system_job "$work/system" "$build" "$sanitized" "$t"
		record "${prefix}system/$name" "$work/system.out" \
			"$(cat "$work/system.rc")" "$(cat "$work/system.s")"
	done
}

# pool_tests BUILD:PREFIX:SANITIZED:NAMES...: the system tests NAMES of
# each build, in SYSTEM_POOL's order, two at a time, and the fuzz targets
# beside them (when $BUILD/fuzz holds them); recorded in order after.
pool_tests() {
	local dir=$work/pool spec build prefix sanitized names name n
	mkdir -p "$dir"
	{
		for spec in "$@"; do
			IFS=: read -r build prefix sanitized names <<<"$spec"
			for name in $SYSTEM_POOL; do
				in_list "$name" "$names" || continue
				printf '%s\0%s\0%s\0%s\0' \
					"$dir/${prefix//\//-}$name" "$build" \
					"$sanitized" "tests/system/$name.sh"
			done
		done
		if [ -d "$BUILD/fuzz" ]; then
			printf '%s\0%s\0%s\0%s\0' "$dir/zz-fuzz" "$BUILD/fuzz" \
				"" fuzz
		fi
	} | xargs -0 -r -n 4 -P 2 bash -c \
		'if [ "$4" = fuzz ]; then
			s=$SECONDS
			FUZZ_SECONDS=${FUZZ_SECONDS:-2} tests/fuzz/run.sh "$2" \
				>"$1.out" 2>&1
			echo $? >"$1.rc"; echo $((SECONDS - s)) >"$1.s"
		 else
			system_job "$@"
		 fi' _
	for spec in "$@"; do
		IFS=: read -r build prefix sanitized names <<<"$spec"
		for name in $SYSTEM_POOL; do
			in_list "$name" "$names" || continue
			n="$dir/${prefix//\//-}$name"
			record "${prefix}system/$name" "$n.out" \
				"$(cat "$n.rc")" "$(cat "$n.s")"
		done
	done
	if [ -e "$dir/zz-fuzz.out" ]; then
		record "fuzz" "$dir/zz-fuzz.out" "$(cat "$dir/zz-fuzz.rc")" \
			"$(cat "$dir/zz-fuzz.s")"
		grep -v "passed, .* failed$" "$dir/zz-fuzz.out" | sed 's/^/    /'
	fi
	rm -rf "$dir"
}

started=$SECONDS
tests/layers.sh >"$work/layers.out" 2>&1
record "layers" "$work/layers.out" $? $((SECONDS - started))
started=$SECONDS
tests/commits.sh >"$work/commits.out" 2>&1
record "commits" "$work/commits.out" $? $((SECONDS - started))
if [ -d "$BUILD/asan/tests" ]; then
	unit_tests "$BUILD/asan:asan/" "$BUILD:"
else
	unit_tests "$BUILD:"
fi
# a name that names no test (renamed, mistyped) fails, not skips
for name in $ASAN_SYSTEM $SYSTEM_POOL; do
	if [ ! -e "tests/system/$name.sh" ]; then
		echo "not ok - run.sh names $name: no such test" >"$work/system.out"
		record "system/$name" "$work/system.out" 1 0
	fi
done
# alone LIST: the system tests of LIST that are not in the pool
alone() {
	local t name out=""
	for t in $1; do
		name=$(basename "$t" .sh)
		in_list "$name" "$SYSTEM_POOL" || out="$out $name"
	done
	echo "$out"
}
system_tests "$BUILD" "" "" "$(alone "$(echo tests/system/[0-9]*.sh)")"
pool=("$BUILD:::$(echo $SYSTEM_POOL)")
if [ -d "$BUILD/asan/tests" ]; then
	# a system test may shorten what only checks timing there
	system_tests "$BUILD/asan" "asan/" 1 "$(alone "$ASAN_SYSTEM")"
	pool+=("$BUILD/asan:asan/:1:$(echo $ASAN_SYSTEM)")
fi
pool_tests "${pool[@]}"
passed=$(awk '{ s += $2 } END { print s + 0 }' "$work/results")
failed=$(awk '{ s += $3 } END { print s + 0 }' "$work/results")
skipped=$(awk '{ s += $4 } END { print s + 0 }' "$work/results")
if [ "$skipped" -ne 0 ]; then
	echo "skipped (not checked here):"
	sed 's/^/  /' "$work/skips"
	echo "skipped:$(awk '$4 > 0 { printf " %s", $1 }' "$work/results")"
fi
if [ "$failed" -ne 0 ]; then
	echo "what failed:"
	sed 's/^/  /' "$work/why"
	echo "failed:$(awk '$3 > 0 { printf " %s", $1 }' "$work/results")"
fi
echo "(the suites took $((SECONDS / 60)) min $((SECONDS % 60)) s)"
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
