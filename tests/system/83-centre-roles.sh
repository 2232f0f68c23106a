#!/bin/bash
# Who sees what at a training centre (issue 24): the rules held by the
# centre's PostgreSQL itself (config/centre-roles.sql: roles, grants,
# row-level security) on a cluster of the test's own (pg_lib.sh). The
# people come from the rig: Ann, Bo and Cy trainees, Dr Ives an
# instructor, Ada an administrator, the group 2026 of Ann and Bo that
# Dr Ives manages, all made with endoctl, reach the centre with their
# PINs as Argon2id strings; the rig records sessions of Ann, Bo and Cy,
# which arrive too. The script is run (twice: it changes nothing the
# second time); the centre gives each person a login named as they are
# at the rig. With Ann's credentials only her sessions are read, by
# endoctl and by queries written to read another's rows, which return
# none; she cannot delete, change or read the people; Dr Ives reads his
# group's, not Cy's, and nothing more while the centre grants him a
# trainee's role only; a login with no person reads nothing; Ada reads
# all, deletes one, reads the people's names but not their PINs' hashes
# and cannot add a person; the rig writes on, and Ann's new session is
# hers to read.
. "$(dirname "$0")/../common.sh"
. "$(dirname "$0")/pg_lib.sh"
pg_make

at_centre() { [ "$(sql 'SELECT COUNT(*) FROM sessions')" = "$1" ]; }
url_of() { echo "postgresql:///endosim?host=$PGSOCK&user=${1// /%20}"; }
# add NAME ROLE PIN: a user made on the rig by its staff
add() { ENDOSIM_NEW_PIN=$3 ctl user add "$1" --role "$2"; }
people_are() { [ "$(sql "SELECT string_agg(name || ':' || role, ','
	ORDER BY name) FROM endosim_people")" = "$1" ]; }
members_are() { [ "$(sql "SELECT string_agg(group_name || ':' || trainee,
	',' ORDER BY trainee) FROM endosim_members")" = "$1" ]; }

start_daemon --set "records.centre=$URL" --set records.rig=rig-a \
	--set records.centre_retry_s=0.1 || finish
check "on the rig: Ann, Bo, Cy, Dr Ives, Ada; 2026 of Ann and Bo" eval \
	'add Ann trainee 48213579 && add Bo trainee 27182818 &&
	 add Cy trainee 31415926 && add "Dr Ives" instructor 16180339 &&
	 add Ada administrator 90210777 &&
	 ctl group add 2026 --instructor "Dr Ives" &&
	 ctl group join 2026 Ann Bo'
check "... the people at the centre, with their roles" wait_for people_are \
	"Ada:administrator,Ann:trainee,Bo:trainee,Cy:trainee,Dr Ives:instructor"
check "... and the group" wait_for members_are "2026:Ann,2026:Bo"
check "... their PINs as Argon2id strings" test "$(sql "SELECT COUNT(*)
	FROM endosim_people WHERE pin LIKE '\$argon2id\$%'")" = 5
check "... the PINs nowhere in clear" eval "! sql 'SELECT pin FROM
	endosim_people' | grep -q -e 48213579 -e 27182818 -e 16180339"
check "sessions of Ann, Bo and Cy recorded" eval \
	'record Ann 100 && record Bo 100 && record Cy 100'
check "... at the centre" wait_for at_centre 3

check "centre-roles.sql run" centre -f "$TOP/config/centre-roles.sql"
check "... and again: it changes nothing twice" \
	centre -f "$TOP/config/centre-roles.sql"
check "logins: Ann, Bo, Dr Ives, Ada, a stranger" eval \
	"login Ann endosim_trainee && login Bo endosim_trainee &&
	 login 'Dr Ives' endosim_instructor && login Ada endosim_admin &&
	 login stranger endosim_trainee"

# the trainee
check "Ann: every session she can read is hers" test \
	"$(as Ann 'SELECT string_agg(trainee, $$,$$) FROM sessions')" = Ann
check "Ann: a query for Bo's rows returns none" test \
	"$(as Ann "SELECT COUNT(*) FROM sessions WHERE trainee = 'Bo'")" = 0
check "Ann: a query for anyone else's returns none" test \
	"$(as Ann "SELECT COUNT(*) FROM sessions WHERE trainee <> 'Ann'
	OR trainee IS NULL")" = 0
BO_UUID=$(sql "SELECT uuid FROM sessions WHERE trainee = 'Bo'")
check "Ann: Bo's report page by its UUID: none" test \
	"$(as Ann "SELECT COUNT(report) FROM sessions
	WHERE uuid = '$BO_UUID'")" = 0
check_status "Ann: DELETE: refused" 1 as Ann "DELETE FROM sessions"
check "... in words" grep -q "permission denied for table sessions" "$OUT"
check_status "Ann: UPDATE her own: refused" 1 \
	as Ann "UPDATE sessions SET trainee = 'Bo'"
check_status "Ann: the people: refused" 1 \
	as Ann "SELECT * FROM endosim_people"
check_status "Ann: SET ROLE rig, the owner the rules do not bind: refused" 1 \
	as Ann "SET ROLE rig"
check "... nothing changed: three sessions, Ann's hers" test \
	"$(sql "SELECT string_agg(trainee, ',' ORDER BY trainee)
	FROM sessions")" = "Ann,Bo,Cy"
check_status "Ann: endoctl trainee list --centre" 0 \
	ctl --json trainee list --centre "$(url_of Ann)"
check "... herself only" jq -e '[.trainees[].trainee] == ["Ann"]' "$OUT"

# the instructor, a login with no person, the administrator
check "Dr Ives: his group's sessions, Ann's and Bo's" test \
	"$(as "Dr Ives" 'SELECT string_agg(trainee, $$,$$ ORDER BY trainee)
	FROM sessions')" = "Ann,Bo"
check "Dr Ives: a query for Cy's rows returns none" test \
	"$(as "Dr Ives" "SELECT COUNT(*) FROM sessions
	WHERE trainee = 'Cy'")" = 0
check_status "Dr Ives: DELETE: refused" 1 as "Dr Ives" "DELETE FROM sessions"
check_status "Dr Ives: endoctl trainee list --centre" 0 \
	ctl --json trainee list --centre "$(url_of "Dr Ives")"
check "... Ann and Bo" jq -e '[.trainees[].trainee] | sort == ["Ann", "Bo"]' \
	"$OUT"
check "a login with no person: nothing" test \
	"$(as stranger 'SELECT COUNT(*) FROM sessions')" = 0
check "Ada: every session" test \
	"$(as Ada 'SELECT COUNT(*) FROM sessions')" = 3
check "Ada: Cy's deleted" test \
	"$(as Ada "DELETE FROM sessions WHERE trainee = 'Cy' RETURNING 1")" = 1
check "Ada: the people's names" test "$(as Ada "SELECT string_agg(name,
	',' ORDER BY name) FROM endosim_people")" = "Ada,Ann,Bo,Cy,Dr Ives"
check_status "Ada: their PINs' hashes: refused" 1 \
	as Ada "SELECT pin FROM endosim_people"
check_status "Ada: a person added by SQL: refused (the rigs' to add)" 1 \
	as Ada "INSERT INTO endosim_people VALUES ('Eve', 'trainee', 'x')"
check "Dr Ives granted a trainee's role only: none of his group's rows" \
	eval "centre -c 'REVOKE endosim_instructor FROM \"Dr Ives\"' \
	-c 'GRANT endosim_trainee TO \"Dr Ives\"' &&
	test \"\$(as 'Dr Ives' 'SELECT COUNT(*) FROM sessions')\" = 0"

# the rig writes on under the policies
check "the rig: another session of Ann" record Ann 100
check "... at the centre" wait_for at_centre 3
check "... and Ann's to read" test \
	"$(as Ann 'SELECT COUNT(*) FROM sessions')" = 2

finish
