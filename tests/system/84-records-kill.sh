#!/bin/bash
# The rig's records killed while the daemon writes them (issue 24: the
# database against the files): 3000 sessions (records_gen), a `records
# rebuild` under way (its new database beside the old one: the write is
# in flight while that file is there), then kill -9 of endosimd. Started
# again: the old database is whole (start-up, which logs each row it
# writes from the files, writes none), `records check` finds the
# database and the files equal, every session once, measures as `session
# show` reads them from the file. A cut rebuild leaves nothing the next
# one trips on. (79-records kills the daemon after a session's stop and
# while one records.)
. "$(dirname "$0")/../common.sh"

if ! command -v sqlite3 >/dev/null; then
	skip "the records killed" "no sqlite3 program (Debian's sqlite3)"
	tally
fi

N=3000
SESS="$TMP/sessions"
DB="$SESS/records.sqlite"
"$TOOLS/records_gen" "$SESS" "$N" 7 || exit 1
start_daemon --session-dir "$SESS" || finish

sql() { sqlite3 -readonly "$DB" "$1"; }
# same_measure ID KEY: the database's KEY of session ID is session show's
same_measure() {
	local shown
	shown=$(ctl --json session show "$1" | jq ".metrics.$2") &&
		jq -e -n "($(sql "SELECT $2 FROM measures WHERE session_id = $1")
			- $shown) | fabs < 1e-9" >/dev/null
}
# records_equal: every session once, sampled measures the files', and
# records check finds nothing
records_equal() {
	local id
	[ "$(sql 'SELECT COUNT(*), COUNT(DISTINCT id), MIN(id), MAX(id)
		FROM sessions')" = "$N|$N|1|$N" ] || return 1
	for id in 1 1234 $N; do
		same_measure "$id" cecum_s && same_measure "$id" withdrawal_s ||
			return 1
	done
	CTL_TIMEOUT_MS=60000 ctl --json records check |
		jq -e ".differ == 0 and .files == $N and
		.rows == $N and (.missing | not) and (.damaged | not)" \
		>/dev/null
}
check "the records made at start-up equal the files" records_equal

ctl records rebuild >/dev/null 2>&1 &
CTL_PID=$!
if wait_for test -e "$DB.new"; then
	kill -KILL "$DAEMON_PID"
	check "killed (-9) while a rebuild writes the new database" true
else
	skip "killed while a rebuild writes" "the rebuild ended before it was seen"
	kill -KILL "$DAEMON_PID"
fi
wait "$DAEMON_PID" 2>/dev/null
wait "$CTL_PID" 2>/dev/null
DAEMON_PID=""
start_daemon --session-dir "$SESS" || finish
check "started again: the records equal the files" records_equal
check "... the old database whole: start-up wrote no row again" test \
	"$(grep -c "sessions written from their files" "$LOG")" = 1
CTL_TIMEOUT_MS=60000 check_status "records rebuild" 0 ctl records rebuild
check "... says what it did" grep -q "rebuilt: $N sessions written" "$OUT"
check "... the records equal the files" records_equal
check "... nothing of the cut one left" test ! -e "$DB.new"

finish
