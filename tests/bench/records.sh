#!/bin/bash
# records.sh - the rig's records at scale (issue 24; make bench runs it;
# figures, not verdicts): 10 000 sessions of 50 trainees made by
# records_gen (a HEADER and an END frame each, what the records read),
# then endosimd started on them (its start-up builds the database from
# the files: timed, from its start to its first answer), then each of
# `endoctl trainee list`, `trainee report NAME`, `session list` and
# `records check` timed RUNS times from endoctl's start to its exit:
# the median and the slowest, next to the issue's 0.2 s (the trainee's)
# and 0.1 s (the session list).
#
#   RECORDS_SESSIONS  sessions (default 10000)
#   RECORDS_TRAINEES  trainees (default 50)
#   RECORDS_RUNS      runs of each command (default 5)
set -u
. "$(dirname "$0")/../common.sh"

N=${RECORDS_SESSIONS:-10000}
T=${RECORDS_TRAINEES:-50}
RUNS=${RECORDS_RUNS:-5}
SESS="$TMP/sessions"

now_ms() { echo $(($(date +%s%N) / 1000000)); }

# timed NAME GOAL_S CMD...: CMD RUNS times; its median and slowest
timed() {
	local name=$1 goal=$2 t0 k
	shift 2
	: >"$TMP/times"
	for ((k = 0; k < RUNS; k++)); do
		t0=$(now_ms)
		"$@" >/dev/null 2>"$TMP/err" || {
			echo "  $name: failed: $(head -n 1 "$TMP/err")"
			return 1
		}
		echo $(($(now_ms) - t0)) >>"$TMP/times"
	done
	sort -n "$TMP/times" | awk -v name="$name" -v goal="$goal" '
		{ t[NR] = $1 } END {
		printf "  %-34s median %5d ms, slowest %5d ms%s\n", name,
			t[int((NR + 1) / 2)], t[NR],
			goal == "-" ? "" : " (goal " goal " s)" }'
}

echo "=== the records at scale: $N sessions of $T trainees ==="
t0=$(now_ms)
"$TOOLS/records_gen" "$SESS" "$N" "$T" || exit 1
echo "  the session files written (records_gen): $(($(now_ms) - t0)) ms," \
	"$(du -sh "$SESS" | cut -f1)"
t0=$(now_ms)
start_daemon --session-dir "$SESS" || exit 1
echo "  endosimd's start-up, the database built from the files:" \
	"$(($(now_ms) - t0)) ms ($(du -h "$SESS/records.sqlite" | cut -f1))"
timed "endoctl trainee list" 0.2 ctl trainee list
timed "endoctl trainee report trainee-07" 0.2 \
	ctl trainee report trainee-07 --out "$TMP/report"
timed "endoctl session list" 0.1 ctl session list
timed "endoctl records check (every file)" - ctl records check
echo "  (endoctl's whole run, connect to exit; the trainee's report" \
	"writes its page and $(($(ls "$TMP/report" | wc -l))) files)"
stop_daemon
