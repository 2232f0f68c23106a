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
# backed up online and restored after rows were lost (the sessions as
# backed up, the one recorded since from its file; refused while a
# session records, over an existing file, on the read-only socket, from a
# file that is no records database), and stopped with its database
# damaged (made again at start-up). After
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

# --- backup and restore ------------------------------------------------------
# dump [MAX_ID]: the sessions (up to MAX_ID), their measures and
# trainees, row by row
dump() {
	local max=${1:-1000000}
	sqlite3 -readonly "$DB" "SELECT * FROM sessions WHERE id <= $max
			ORDER BY id;
		SELECT * FROM measures WHERE session_id <= $max
			ORDER BY session_id;
		SELECT * FROM trainees WHERE id IN (SELECT trainee_id FROM
			sessions WHERE id <= $max) ORDER BY id"
}
BACKUP="$TMP/monday.sqlite"
dump >"$TMP/before.txt"
check_status "records backup, online, into a new file" 0 \
	ctl records backup "$BACKUP"
check "... says how many sessions it holds" \
	grep -qx "backed up 5 sessions into $BACKUP" "$OUT"
check "... one file (no WAL beside it) of the database's rows" eval \
	'[ ! -e "$BACKUP-wal" ] && [ "$(DB=$BACKUP dump)" = \
		"$(cat "$TMP/before.txt")" ]'
check_status "... never over a file: refused (1)" 1 \
	ctl records backup "$BACKUP"
check "... saying so" grep -q "it exists" "$OUT"
check_status "... on the read-only socket: refused (1)" 1 \
	"$ENDOCTL" --socket "$SOCK/status.sock" records backup "$TMP/ro.sqlite"
check "... nothing written" test ! -e "$TMP/ro.sqlite"
check_status "... a relative path: the daemon writes it where endoctl is" 0 \
	sh -c "cd '$TMP' && '$ENDOCTL' --socket '$SOCK' records backup \
		rel.sqlite"
check "... there" test -s "$TMP/rel.sqlite"

record Dan # recorded since the backup
sqlite3 "$DB" "DELETE FROM measures; DELETE FROM sessions;"
check_status "rows lost: records restore from the backup" 0 \
	ctl records restore "$BACKUP"
check "... the sessions backed up as they were" eval \
	'[ "$(dump 5)" = "$(cat "$TMP/before.txt")" ]'
check "... the one recorded since, from its file: the records equal the \
files" records_equal 6

ctl session start --trainee Eve >/dev/null
check_status "restore while a session records: refused (1)" 1 \
	ctl records restore "$BACKUP"
check "... saying so" grep -q "a session is recording" "$OUT"
ctl session stop >/dev/null
printf 'not a database\n' >"$TMP/junk.sqlite"
check_status "restore from a file that is no records database: refused (1)" \
	1 ctl records restore "$TMP/junk.sqlite"
check "... saying so" grep -q "not a sound records database" "$OUT"
check "... the records as they were, with the session just stopped" \
	records_equal 7

stop_daemon
printf 'X' | dd of="$DB" bs=1 seek=0 conv=notrunc 2>/dev/null
start_daemon --session-dir "$SESS" || finish
check "a damaged database at start-up: made again from the files" \
	records_equal 7
check "... the log says so" \
	grep -q "records $DB: damaged: 7 of 7 sessions written" "$LOG"

finish
