#!/bin/bash
# Training sessions, the edges: bad arguments, unknown ids, a second start,
# a stop without a session, start and stop on the read-only socket, a case
# load during a session: each a clear error that changes nothing. A file
# cut mid-record reads up to its last complete record (show recomputes its
# metrics, export gives the same records as before the cut; the records
# find it cut, and once rebuilt the list says so); SIGTERM during
# a session ends its file cleanly; SIGKILL leaves a file without END that
# still shows; ids count on across restarts; reports of both kinds; with
# endosimd stopped, a session file reads by its path.
. "$(dirname "$0")/../common.sh"

SESS="$TMP/sessions"
start_daemon --session-dir "$SESS" || finish

# --- nothing recorded yet ------------------------------------------------
check_status "status without a session: said, exit 0" 0 ctl session status
check "... in words" grep -q "no session" "$OUT"
check_status "stop without a session: refused" 1 ctl session stop
check "... saying so" grep -q "no session is recording" "$OUT"
check_status "show of an unknown id: refused" 1 ctl session show 99
check "... naming it" grep -q "no session 99" "$OUT"
check_status "show of a non-number: usage" 2 ctl session show abc
check_status "show 0: usage" 2 ctl session show 0
check_status "export without --csv: usage" 2 ctl session export 1
check_status "an unknown subcommand: usage" 2 ctl session frobnicate
check_status "start with an unknown option: usage" 2 ctl session start --bogus x
long=$(printf 'x%.0s' $(seq 1 64))
check_status "a trainee name of 64 bytes: refused" 1 \
	ctl session start --trainee "$long"
check_status "a trainee name with a newline: refused" 1 \
	ctl session start --trainee "$(printf 'a\nb')"
check_status "a case name with a path: refused" 1 \
	ctl session start --case ../normal
check_status "a case that does not exist: refused" 1 \
	ctl session start --case no-such-case
check_status "start on the read-only socket: refused" 1 \
	"$ENDOCTL" --socket "$SOCK/status.sock" session start
check "... as read-only" grep -q "read-only" "$OUT"
check "after all that, still no session and no file" \
	test "$(ctl session status)" = "no session since endosimd started" -a \
	-z "$(ls "$SESS" | grep -v '^records\.sqlite')"

# --- one session, and what is refused during it ---------------------------
check_status "start with a case while IDLE: loads it" 0 \
	ctl session start --trainee "Dr. Ada Lovelace" --case polyps
check "the daemon runs the case" test "$(status_field .case)" = polyps
check_status "a second start: refused" 1 ctl session start
check "... naming the running session" grep -q "session 1 is recording" "$OUT"
check_status "a case load during the session: refused" 1 ctl case load normal
check_status "stop on the read-only socket: refused" 1 \
	"$ENDOCTL" --socket "$SOCK/status.sock" session stop
check_status "status on the read-only socket: fine" 0 \
	"$ENDOCTL" --socket "$SOCK/status.sock" session status
check "... recording session 1" grep -q "session 1 (recording)" "$OUT"
# ~2 s of records, by the loop's own count: a slow machine's skipped
# cycles make the wait longer, not the session shorter
check "recording on: more than 1600 records" \
	wait_for live_status '.records > 1600'
check_status "stop" 0 ctl session stop
check "the daemon is fine: IDLE, no fault" \
	test "$(status_field '.state + "/" + (.fault_bits | tostring)')" = IDLE/0
check_status "list on the read-only socket" 0 \
	"$ENDOCTL" --socket "$SOCK/status.sock" --json session list
check "list: session 1, ended, the trainee and the case" \
	jq -e '.sessions | length == 1 and .[0].id == 1 and .[0].ended and
	       .[0].trainee == "Dr. Ada Lovelace" and .[0].case == "polyps"' "$OUT"

# --- a file cut mid-record -------------------------------------------------
f="$SESS/1.endoses"
ctl session export 1 --csv --out "$TMP/full.csv"
full=$(($(wc -l <"$TMP/full.csv") - 1))
check "the whole session exported ($full records, more than the 1600 seen live)" \
	test "$full" -gt 1600
cp "$f" "$TMP/1.whole"
truncate -s $(($(stat -c %s "$f") / 2 + 150)) "$f"
check_status "show of the cut file" 0 ctl --json session show 1
check "... recomputes the metrics: no END frame" \
	jq -e '(.note | test("no END frame")) and .ended == false' "$OUT"
cut_n=$(jq .metrics.records "$OUT")
check_status "export of the cut file" 0 ctl session export 1 --csv \
	--out "$TMP/cut.csv"
n=$(($(wc -l <"$TMP/cut.csv") - 1))
check "the cut file holds about half the records ($n of $full), as shown ($cut_n)" \
	test "$n" -gt $((full * 45 / 100)) -a "$n" -lt $((full * 55 / 100)) \
	-a "$n" = "$cut_n"
check "... and they are the first $n records, unchanged" \
	cmp -s "$TMP/cut.csv" <(head -n $((n + 1)) "$TMP/full.csv")
check "the records, which the list is served from, find the file cut" \
	sh -c '"$1" --socket "$2" records check | grep -q "^session 1: .*size"' \
	_ "$ENDOCTL" "$SOCK"
ctl records rebuild >/dev/null
check "the list says it is cut short" \
	bash -c "'$ENDOCTL' --socket '$SOCK' session list | grep -q ' cut short '"

# --- SIGTERM during a session: its END is written ---------------------------
ctl session start --trainee term >/dev/null
sleep 1
check "SIGTERM while recording: clean exit" stop_daemon
start_daemon --session-dir "$SESS" || finish
check_status "after a restart, session 2 shows" 0 ctl --json session show 2
check "... ended cleanly, with its metrics from END" \
	jq -e '.ended and (has("note") | not) and .metrics.records > 500' "$OUT"
check "... its length and end: the file's (not the recorder's any more)" \
	jq -e '.records == .metrics.records and .ended_at > .started and
	       ((.ended_at | fromdateiso8601) - (.started | fromdateiso8601) -
		.duration_s | fabs) <= 1' "$OUT"
cp "$OUT" "$TMP/show2.json"
ctl session export 2 --csv --out "$TMP/s2.csv"
check_status "its report" 0 ctl session report 2 --out "$TMP/report"
check "... an HTML page naming the trainee" grep -q "term" "$TMP/report/index.html"
check_status "the report of the cut file too" 0 ctl session report 1 --out "$TMP/cut"
check "... saying its metrics were recomputed" grep -q "recomputed" "$OUT"
check_status "report without --out: usage" 2 ctl session report 2

# --- SIGKILL during a session: no END, still readable -----------------------
ctl session start --trainee crash >/dev/null
check "the next session is 3" grep -q "^session 3 " <(ctl session status)
sleep 1.5
kill -KILL "$DAEMON_PID"
wait "$DAEMON_PID" 2>/dev/null
DAEMON_PID=""
start_daemon --session-dir "$SESS" || finish
check_status "the crashed session shows" 0 ctl --json session show 3
check "... recomputed from its records (at least the 0.5 s written)" \
	jq -e '(.note | test("no END")) and .metrics.records > 400' "$OUT"
ctl session start >/dev/null
check "ids count on: the next is 4" grep -q "^session 4 " <(ctl session status)
ctl session stop >/dev/null

# --- with endosimd stopped: a session file read by its path ----------------
stop_daemon
check_status "endosimd stopped: show by the file's path" 0 \
	ctl --json session show "$SESS/2.endoses"
check "... the same session and metrics as endosimd showed" \
	jq -e --slurpfile d "$TMP/show2.json" '.id == 2 and .ended and
	       .trainee == "term" and .path == "'"$SESS/2.endoses"'" and
	       .metrics == $d[0].metrics and .records == .metrics.records and
	       .ended_at == $d[0].ended_at' "$OUT"
check_status "... export by the path" 0 \
	ctl session export "$SESS/2.endoses" --csv --out "$TMP/s2-file.csv"
check "... the same records as exported through endosimd" \
	cmp -s "$TMP/s2.csv" "$TMP/s2-file.csv"
check_status "... the crashed one's report by its path" 0 \
	ctl session report "$SESS/3.endoses" --out "$TMP/report3"
check "... recomputed" grep -q "recomputed" "$OUT"
check_status "a path that is not a session file: refused" 1 \
	ctl session show "$TMP/s2.csv"
check "... saying so" grep -q "s2.csv: not a session file" "$OUT"
check_status "a path that does not exist: refused" 1 \
	ctl session export "$TMP/none.endoses" --csv
check "... saying so" grep -q "No such file" "$OUT"

# --- a session directory that cannot be made: the rig runs, sessions refused
check "a session directory that cannot be made: the daemon still comes up" \
	start_daemon --session-dir /proc/endosim-sessions
check "... saying so in its log" grep -q "no session can be recorded" "$LOG"
check_status "... a session start refused" 1 ctl session start
check "... saying why" grep -q "endosim-sessions" "$OUT"
check "... and the rig still enables" ctl enable
finish
