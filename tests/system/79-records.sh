#!/bin/bash
# The rig's records (issue 24): endosimd writes each session's row to its
# SQLite database when the session stops, and `session list` is served
# from it; the session files stay the truth. Three short sessions on the
# simulated rig (one trainee named like an SQL injection), then: the
# database deleted (records check says it is missing, records rebuild
# writes every session once), its first byte damaged and a byte of a
# trainee's name changed (check says so: SQLite's integrity check finds
# the name no longer matches its index; rebuild recovers), the daemon
# killed (-9) right after a session stop and again while one records (on
# restart the records equal the files, the cut session among them), and
# stopped with its database damaged (made again at start-up). After
# each, every session is in the database once, its measures equal to
# `session show`'s (read with the sqlite3 program, not through endosimd).
. "$(dirname "$0")/../common.sh"

if ! command -v sqlite3 >/dev/null; then
	skip "the records" "no sqlite3 program (Debian's sqlite3)"
	tally
fi

SESS="$TMP/sessions"
DB="$SESS/records.sqlite"
BOBBY="Robert'); DROP TABLE sessions;--"

start_daemon --session-dir "$SESS" || finish

# record NAME: a session of NAME, a few hundred records long
live_status() { ctl --json session status | jq -e "$1"; }
record() {
	ctl session start --trainee "$1" >/dev/null &&
		wait_for live_status '.records > 300' &&
		ctl session stop >/dev/null
}
# sql QUERY: the database's answer, read beside the daemon
sql() { sqlite3 -readonly "$DB" "$1"; }
# measures_equal ID: the database's measures of session ID are those
# `session show ID` reads from its file (to %.9g; a NaN is null in both)
measures_equal() {
	ctl --json session show "$1" | jq -c .metrics >"$TMP/show.json" &&
		sqlite3 -readonly -json "$DB" "SELECT * FROM measures WHERE
			session_id = $1" | jq -c '.[0] | del(.session_id)' \
			>"$TMP/db.json" &&
		jq -e -n --slurpfile s "$TMP/show.json" \
			--slurpfile d "$TMP/db.json" '$d[0] | to_entries | length
			> 40 and all(.[]; . as $e | $s[0][$e.key] as $v |
			($e.value == null and $v == null) or
			(($e.value - $v) | fabs) <= 1e-8 * ([1, ($v | fabs)] |
			max))' >/dev/null
}
# records_equal N: every one of the N sessions in the database once, its
# trainee and measures the file's; a check finds nothing
records_equal() {
	local id
	[ "$(sql 'SELECT COUNT(*), COUNT(DISTINCT id) FROM sessions')" = \
		"$1|$1" ] || return 1
	[ "$(sql 'SELECT name FROM trainees t JOIN sessions s ON
		s.trainee_id = t.id WHERE s.id = 2')" = "$BOBBY" ] || return 1
	for id in $(sql 'SELECT id FROM measures'); do
		measures_equal "$id" || return 1
	done
	ctl --json records check | jq -e ".differ == 0 and .files == $1 and
		.rows == $1 and (.missing | not) and (.damaged | not)" \
		>/dev/null
}
# check_found JQ: `records check` finds what JQ says
check_found() { ctl --json records check | tee "$TMP/found.json" |
	jq -e "$1" >/dev/null; }

three() { record Ann && record "$BOBBY" && record Ann; }
check "three sessions recorded" three
check_status "session list" 0 ctl --json session list
check "... the three, from the records, the trainees as given" \
	jq -e '[.sessions[] | .trainee] == ["Ann", $b, "Ann"] and
	       all(.sessions[]; .ended)' --arg b "$BOBBY" "$OUT"
check "the database: each session once, measures as session show's" \
	records_equal 3
check "the measures: a column each" test \
	"$(sql 'SELECT COUNT(*) FROM pragma_table_info("measures")')" -gt 50

rm -f "$DB" "$DB-wal" "$DB-shm"
check "the database deleted: records check says it is missing" \
	check_found '.missing and .differ == 3 and
		     (.found | test("is missing"))'
check_status "records rebuild" 0 ctl records rebuild
check "... says what it did" grep -q "rebuilt: 3 sessions written" "$OUT"
check "... each session back once, as its file" records_equal 3

printf 'X' | dd of="$DB" bs=1 seek=0 conv=notrunc 2>/dev/null
check "its first byte damaged: records check says so" \
	check_found '.damaged and (.found | test("damaged"))'
check_status "records rebuild" 0 ctl records rebuild
check "... each session back once, as its file" records_equal 3
check "... the damaged one kept aside" test -s "$DB.damaged"

off=$(grep -abo "Robert'); DROP" "$DB" | head -n 1 | cut -d: -f1)
printf 'Z' | dd of="$DB" bs=1 seek="$off" conv=notrunc 2>/dev/null
check "a byte of a trainee's name changed: records check finds it" \
	check_found '.damaged or
		     (.found | test("session 2: .* differs .*trainee"))'
ctl records rebuild >/dev/null
check "... rebuilt: as the files" records_equal 3

record Bo
kill -KILL "$DAEMON_PID"
wait "$DAEMON_PID" 2>/dev/null
DAEMON_PID=""
start_daemon --session-dir "$SESS" || finish
check "killed (-9) right after a session stop: the records equal the files" \
	records_equal 4

ctl session start --trainee Cut >/dev/null
wait_for live_status '.records > 300' >/dev/null
kill -KILL "$DAEMON_PID"
wait "$DAEMON_PID" 2>/dev/null
DAEMON_PID=""
rm -f "$DB" "$DB-wal" "$DB-shm"
start_daemon --session-dir "$SESS" || finish
check "killed while recording, the database gone: made again at start-up" \
	records_equal 5
check "... the cut session in it without an END" \
	test "$(sql 'SELECT ended, (SELECT COUNT(*) FROM measures WHERE
		session_id = 5) FROM sessions WHERE id = 5')" = "0|0"
check "the daemon's log says it made the records" \
	grep -q "records $DB: made: 5 of 5 sessions written" "$LOG"
check_status "session list" 0 ctl --json session list
check "... the five" jq -e '.sessions | length == 5' "$OUT"

stop_daemon
printf 'X' | dd of="$DB" bs=1 seek=0 conv=notrunc 2>/dev/null
start_daemon --session-dir "$SESS" || finish
check "a damaged database at start-up: made again from the files" \
	records_equal 5
check "... the log says so" \
	grep -q "records $DB: damaged: 5 of 5 sessions written" "$LOG"

finish
