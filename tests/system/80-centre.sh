#!/bin/bash
# A training centre's rigs together (issue 24): a PostgreSQL cluster of
# the test's own (initdb and pg_ctl in its temporary directory, as an
# unprivileged user, on a private Unix socket, a password for the rigs'
# role in a libpq password file) and two daemons as two rigs, each
# pointed at it with [records] centre. Sessions of one trainee recorded
# on both arrive at the centre with their rig, report page and
# measures; the server is stopped in the middle: the rigs go on
# recording, their sessions wait in each rig's SQLite queue, and arrive
# when it is started again, each once, in each rig's order; a rig whose
# own database is rebuilt (everything queued again) adds nothing twice.
# `endoctl trainee list|report --centre` read the centre directly: the
# trainee's sessions from both rigs, each with its rig. A malformed URL,
# a URL with a password and an unreachable centre are refused in words.
# The people: trainees, an instructor and his group made on rig-a reach
# the centre and rig-b, where Ann logs in with the PIN she was given on
# rig-a; a change of the group made on rig-a while the server is stopped
# waits in rig-a's accounts and arrives once when it is back, reaching
# rig-b and the instructor's login at the centre, which then reads his
# group's sessions only; the same change sent again (as after a lost
# acknowledgement) is not applied twice. A trainee training on rig-b and
# removed on rig-a no longer trains on rig-b once the centre's people
# reach it.
# Skipped (never passed) where Debian's postgresql is not installed.
. "$(dirname "$0")/../common.sh"

. "$(dirname "$0")/pg_lib.sh"
pg_make

# rig NAME: the daemons of the two rigs, each in its slot, at the centre
rig() {
	use_slot "$1"
	start_daemon --set "records.centre=$URL" --set "records.rig=$1" \
		--set records.centre_retry_s=0.1
}
# queued: how many sessions wait in the slot's rig's own queue
sessions_dir() { [ "$SLOT" = main ] && echo "$TMP/sessions" ||
	echo "$TMP/slot-$SLOT/sessions"; }
queued() { sqlite3 -readonly "$(sessions_dir)/records.sqlite" \
	'SELECT COUNT(*) FROM centre_queue'; }
drained() { [ "$(queued)" = 0 ]; }
at_centre() { [ "$(sql 'SELECT COUNT(*) FROM sessions')" = "$1" ]; }

# changes_queued: how many changes of its accounts wait in the slot's rig
changes_queued() { sqlite3 -readonly "$(sessions_dir)/accounts.sqlite" \
	'SELECT COUNT(*) FROM centre_queue'; }
changes_sent() { [ "$(changes_queued)" = 0 ]; }
# group_is NAME TRAINEES: the slot's rig's group NAME, its trainees a JSON
# array
group_is() { ctl --json group list | jq -e --arg g "$1" --argjson t "$2" \
	'.groups | map(select(.name == $g)) | .[0].trainees == $t'; }
members_are() { [ "$(sql "SELECT string_agg(trainee, ',' ORDER BY trainee)
	FROM endosim_members WHERE group_name = '2026'")" = "$1" ]; }

rig rig-a || finish
rig rig-b || finish
use_slot rig-a
check "rig-a: Ann and Bo, Dr Ives, his group 2026 of them" eval \
	'ENDOSIM_NEW_PIN=48213579 ctl user add Ann --role trainee &&
	 ENDOSIM_NEW_PIN=27182818 ctl user add Bo --role trainee &&
	 ENDOSIM_NEW_PIN=16180339 ctl user add "Dr Ives" --role instructor &&
	 ctl group add 2026 --instructor "Dr Ives" &&
	 ctl group join 2026 Ann Bo'
use_slot rig-b
check "rig-b: the group, from the centre" wait_for group_is 2026 '["Ann","Bo"]'
check "... its trainees: endoview on rig-b asks who is training" \
	wait_for status_true '.asks_trainee'
check_status "rig-b: Ann logs in with her PIN from rig-a" 0 \
	env ENDOSIM_PIN=48213579 "$ENDOCTL" --socket "$SOCK" --as Ann whoami
check "... as a trainee" grep -qx "Ann (trainee)" "$OUT"
use_slot rig-a
check "rig-a: a session of Ann" record Ann 100
use_slot rig-b
check "rig-b: a session of Ann" record Ann 100
check "both at the centre" wait_for at_centre 2
check "centre-roles.sql run; Dr Ives's login at the centre" eval \
	'centre -f "$TOP/config/centre-roles.sql" &&
	 login "Dr Ives" endosim_instructor'

check "the server stopped in the middle" pg_stop
use_slot rig-a
check_status "rig-a: Bo leaves 2026 while the centre is away" 0 \
	ctl group leave 2026 Bo
check "... the change waits in rig-a's accounts" test "$(changes_queued)" = 1
check "rig-a records on: Ann, Ann" eval 'record Ann 100 && record Ann 100'
use_slot rig-b
check "rig-b records on: Bo, Ann" eval 'record Bo 100 && record Ann 100'
for s in rig-a rig-b; do
	use_slot "$s"
	check "$s: its two wait in its own queue" test "$(queued)" = 2
	check "$s: its records have all its sessions" eval \
		'ctl --json session list | jq -e ".sessions | length == 3"'
	check "$s: the log says the centre is unreachable" wait_for grep -q \
		"cannot connect.*sessions wait in the rig's records" "$LOG"
done

check "the server started again" pg_start
check "every session arrives" wait_for at_centre 6
check "... each once" test "$(sql 'SELECT COUNT(DISTINCT (rig, rig_session))
	FROM sessions')" = 6
check "... three of each rig, in the rig's order" test "$(sql "SELECT
	rig || ':' || string_agg(rig_session::text, ',' ORDER BY arrival)
	FROM sessions GROUP BY rig ORDER BY rig")" = \
	"$(printf 'rig-a:1,2,3\nrig-b:1,2,3')"
check "... with the trainees as recorded" test "$(sql "SELECT
	string_agg(trainee, ',' ORDER BY rig, rig_session) FROM sessions")" = \
	"Ann,Ann,Ann,Ann,Bo,Ann"
check "... each with its report page and measures" test "$(sql "SELECT
	COUNT(*) FROM sessions WHERE ended AND has_measures AND
	report LIKE '%<html%' AND length(report) > 10000 AND
	duration_s > 0")" = 6
for s in rig-a:1 rig-b:0; do
	use_slot "${s%:*}"
	check "${s%:*}: its queue drained" wait_for drained
	check "${s%:*}: the log says the centre came back" grep -q \
		"centre reachable again: 2 sessions sent, ${s#*:} changes" \
		"$LOG"
done
check "the change arrived: 2026 of Ann alone" wait_for members_are Ann
check "... once" test "$(sql "SELECT COUNT(*) FROM endosim_changes
	WHERE op = 'group_leave' AND name = 'Bo'")" = 1
use_slot rig-b
check "... and reached rig-b" wait_for group_is 2026 '["Ann"]'
check "Dr Ives at the centre: his group's sessions, Ann's five" test \
	"$(as "Dr Ives" "SELECT trainee || ':' || COUNT(*) FROM sessions
	GROUP BY trainee")" = "Ann:5"
check "... Bo's none" test "$(as "Dr Ives" "SELECT COUNT(*) FROM sessions
	WHERE trainee = 'Bo'")" = 0
# Bo's join sent again with its ID, as if its acknowledgement was lost;
# the same session twice: rig-a's own database rebuilt from its files,
# every one of its sessions queued again (which sends the join too)
use_slot rig-a
BO_JOIN=$(sql "SELECT replace(id::text, '-', '') FROM endosim_changes
	WHERE op = 'group_join' AND name = 'Bo'")
check "rig-a: Bo's join queued again" \
	sqlite3 "$(sessions_dir)/accounts.sqlite" "INSERT INTO centre_queue
	(id, op, name, role, pin, group_name, course)
	VALUES ('$BO_JOIN', 'group_join', 'Bo', '', '', '2026', '')"
check_status "rig-a: records rebuild" 0 ctl records rebuild
check "... the join sent" wait_for changes_sent
check "... and not taken twice: 2026 of Ann alone still" members_are Ann
check "... the join noted once" test "$(sql "SELECT COUNT(*) FROM
	endosim_changes WHERE op = 'group_join' AND name = 'Bo'")" = 1

check "... its queue of sessions drains again" wait_for drained
check "... and the centre has each session still once" at_centre 6

check_status "trainee list --centre" 0 ctl --json trainee list --centre "$URL"
check "... Ann's five sessions from both rigs, Bo's one" jq -e \
	'.trainees | map({(.trainee): [.sessions, .rigs]}) | add ==
	 {"Ann": [5, ["rig-a", "rig-b"]], "Bo": [1, ["rig-b"]]}' "$OUT"
check_status "trainee list --centre (text)" 0 ctl trainee list --centre "$URL"
check "... a RIGS column" grep -q "^Ann .*rig-a, rig-b$" "$OUT"
check_status "trainee report Ann --centre" 0 \
	ctl trainee report Ann --out "$TMP/ann" --centre "$URL"
check "... her page lists five sessions, each with its rig" test \
	"$(grep -c '<tr id="session-rig-[ab]-[0-9]*"><td><a href="[0-9a-f-]*.html">[0-9]*</a></td><td>rig-[ab]</td>' \
	"$TMP/ann/index.html")" = 5
# pages_linked: each session's page that Ann's page links to is there
pages_linked() {
	local f n=0
	for f in $(grep -o '[0-9a-f-]\{36\}\.html' "$TMP/ann/index.html"); do
		grep -q "<html" "$TMP/ann/$f" || return 1
		n=$((n + 1))
	done
	[ "$n" = 5 ]
}
check "... and links each session's report page, from the centre" \
	pages_linked

# a trainee removed on one rig no longer trains on another
has_user() { ctl --json user list | jq -e --arg u "$1" \
	'.users | map(.name) | index($u) != null'; }
use_slot rig-b
check "rig-b: Cy added, and trains at the rig" eval \
	'ENDOSIM_NEW_PIN=31415926 ctl user add Cy --role trainee &&
	 ENDOSIM_PIN=31415926 ctl login Cy && status_true ".trainee == \"Cy\""'
use_slot rig-a
check "rig-a: Cy, from the centre" wait_for has_user Cy
check_status "rig-a: Cy removed" 0 ctl user remove Cy
use_slot rig-b
check "rig-b: Cy gone from the accounts" wait_for eval '! has_user Cy'
check "... and no longer trains there" wait_for status_true '.trainee == ""'
check "... the log says why" grep -q \
	"Cy no longer trains at the rig: no such trainee in the accounts" "$LOG"

check_status "a malformed URL: refused" 2 \
	ctl trainee list --centre "postgresql://[bad"
check "... in words" grep -q "not a PostgreSQL connection URL" "$OUT"
check_status "an unreachable centre: refused" 4 \
	ctl trainee list --centre "postgresql:///endosim?host=$TMP/none"
check "... in words" grep -q "centre: cannot connect" "$OUT"
# no_start VALUE: endosimd with [records] centre = VALUE refuses to
# start (EX_CONFIG), before it builds the colon
no_start() {
	timeout 20 "$ENDOSIMD" "${DAEMON_ARGS[@]}" --config \
		"$TOP/config/endosimd.conf" --set "records.centre=$1" \
		>"$OUT" 2>&1
	[ $? = 78 ] && ! grep -q "triangles" "$OUT"
}
use_slot bad
check "endosimd with a password in the URL: does not start" \
	no_start "postgresql://rig:rig-secret@localhost/endosim"
check "... in words" grep -q "holds a password: put it in libpq's password" \
	"$OUT"
check "endosimd with a malformed URL: does not start" no_start "endosim"
check "... in words" grep -q "not a PostgreSQL connection URL" "$OUT"

finish
