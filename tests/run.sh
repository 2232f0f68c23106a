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
# The system tests run one at a time: they measure the force loop's timing
# and talk to emulated drives whose serial framing is a matter of
# microseconds (tried: two streams at once on two CPUs saved no time and
# broke the Modbus RTU tests). A system test leaves most of a CPU idle, so
# the sanitizers' unit tests run meanwhile under SCHED_IDLE (chrt --idle):
# a task of that class runs only on a CPU that nothing else wants, and is
# preempted at once when anything does, so the system tests see an idle
# machine (their daemon's loop and emulators are SCHED_FIFO where the run
# is root) while the queue uses what they leave (it saved the queue's
# 100 s of wall time). The sanitizers' unit tests that wait on the clock
# (CLOCK_UNITS: a bus thread's answer within 3 s, readers' counts in a
# second) run first, with the plain build's.
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

# The unit tests that take longest (over 10 s on this 2-CPU VM, in either
# build), the longest first: they start first, so that none of them starts
# last and runs alone while the other CPU idles (the queue's 405 s of CPU
# took 222 s in the tests' order, 204 s so).
LONG_UNITS="test_separation test_rodcourse test_clinic test_hand test_lod
	test_patient test_haptics test_metrics"

# The unit tests that count on the clock (above): never starved.
CLOCK_UNITS="test_valves test_seqlock test_centre"

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

# unit_queue DIR ONLY SKIP BUILD_DIR:PREFIX...: the unit tests of each
# build, as many at once as there are CPUs from one queue (LONG_UNITS
# first, the longest first, then the rest in order), each into its own
# files in DIR (output, exit status, seconds); ONLY: the names to run
# ("": all), SKIP: names not to run.
unit_queue() {
	local dir=$1 only=" $(echo $2) " skip=" $(echo $3) " pair prefix t
	local name long=" $(echo $LONG_UNITS) "
	shift 3
	mkdir -p "$dir"
	# wanted NAME: on the queue
	wanted() {
		[[ "$skip" != *" $1 "* ]] &&
			{ [ "$only" = "  " ] || [[ "$only" == *" $1 "* ]]; }
	}
	{
		for name in $LONG_UNITS; do
			wanted "$name" || continue
			for pair in "$@"; do
				t=${pair%%:*}/tests/$name
				prefix=${pair#*:}
				[ -x "$t" ] && printf '%s\0%s\0' "$t" \
					"${prefix//\//-}"
			done
		done
		for pair in "$@"; do
			prefix=${pair#*:}
			for t in "${pair%%:*}"/tests/test_*; do
				case "$t" in *.d) continue ;; esac
				name=${t##*/}
				[[ "$long" == *" $name "* ]] && continue
				wanted "$name" || continue
				[ -x "$t" ] && printf '%s\0%s\0' "$t" \
					"${prefix//\//-}"
			done
		done
	} | xargs -0 -r -n 2 -P "$(nproc)" sh -c \
		'n=$3$(basename "$2"); s=$(date +%s); "$2" >"$1/$n.out" 2>&1
		 echo $? >"$1/$n.rc"; echo $(($(date +%s) - s)) >"$1/$n.s"' \
		_ "$dir"
}

# unit_record DIR PREFIX: records, in order, what unit_queue left in DIR
# for the build of PREFIX.
unit_record() {
	local dir=$1 prefix=$2 t name
	for t in "$dir/${prefix//\//-}"test_*.out; do
		[ -e "$t" ] || continue
		name=$(basename "$t" .out)
		name=${name#"${prefix//\//-}"}
		record "${prefix}unit/$name" "$t" \
			"$(cat "${t%.out}.rc")" "$(cat "${t%.out}.s")"
	done
}

# system_tests BUILD_DIR PREFIX SANITIZED [NAME...]: in order, one at a
# time; every one, or those NAMEs only.
system_tests() {
	local build=$1 prefix=$2 sanitized=$3 t started rc
	shift 3
	for t in tests/system/[0-9]*.sh; do
		[ -e "$t" ] || continue
		if [ $# -gt 0 ] && ! [[ " $* " == *" $(basename "$t" .sh) "* ]]; then
			continue
		fi
		started=$SECONDS
		BUILD="$build" SANITIZED=$sanitized timeout -k 20 300 bash "$t" \
			>"$work/system.out" 2>&1
		rc=$?
		if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
			echo "not ok - $(basename "$t") ran out of its 300 s" \
				>>"$work/system.out"
		fi
		record "${prefix}system/$(basename "$t" .sh)" "$work/system.out" \
			$rc $((SECONDS - started))
	done
}

started=$SECONDS
tests/layers.sh >"$work/layers.out" 2>&1
record "layers" "$work/layers.out" $? $((SECONDS - started))
started=$SECONDS
tests/commits.sh >"$work/commits.out" 2>&1
record "commits" "$work/commits.out" $? $((SECONDS - started))
asan=
[ -d "$BUILD/asan/tests" ] && asan=$BUILD/asan
if [ -n "$asan" ]; then
	unit_queue "$work/units" "$CLOCK_UNITS" "" "$asan:asan/"
fi
unit_queue "$work/units" "" "" "$BUILD:"
unit_record "$work/units" ""
if [ -n "$asan" ]; then
	# SCHED_IDLE where the kernel allows it, else the lowest niceness
	(chrt --idle -p 0 $BASHPID 2>/dev/null || renice -n 19 $BASHPID
		unit_queue "$work/units" "" "$CLOCK_UNITS" "$asan:asan/"
	) >/dev/null 2>&1 &
	idle_units=$!
fi
system_tests "$BUILD" "" ""
if [ -n "$asan" ]; then
	wait "$idle_units"
	unit_record "$work/units" "asan/"
	# a name that names no test (renamed, mistyped) fails, not skips
	for name in $ASAN_SYSTEM; do
		if [ ! -e "tests/system/$name.sh" ]; then
			echo "not ok - ASAN_SYSTEM names $name: no such test" \
				>"$work/system.out"
			record "asan/system/$name" "$work/system.out" 1 0
		fi
	done
	# a system test may shorten what only checks timing there
	# shellcheck disable=SC2086 # the list's words are the names
	system_tests "$BUILD/asan" "asan/" 1 $ASAN_SYSTEM
fi
if [ -d "$BUILD/fuzz" ]; then
	started=$SECONDS
	FUZZ_SECONDS=${FUZZ_SECONDS:-2} tests/fuzz/run.sh "$BUILD/fuzz" \
		>"$work/fuzz.out" 2>&1
	record "fuzz" "$work/fuzz.out" $? $((SECONDS - started))
	grep -v "passed, .* failed$" "$work/fuzz.out" | sed 's/^/    /'
fi
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
