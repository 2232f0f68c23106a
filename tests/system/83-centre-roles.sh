#!/bin/bash
# Who sees what at a training centre (issue 24): the rules held by the
# centre's PostgreSQL itself (config/centre-roles.sql: roles, grants,
# row-level security) on a cluster of the test's own (pg_lib.sh). A rig
# records sessions of Ann, Bo and Cy, which arrive at the centre; the
# script is run (twice: it changes nothing the second time); Ann and Bo
# are trainees of the group 2026, which Dr Ives manages, Ada the centre's
# administrator, each with a login of their own. With Ann's credentials
# only her sessions are read, by endoctl and by queries written to read
# another's rows, which return none; she cannot delete, change or read
# the people; Dr Ives reads his group's, not Cy's; a login with no person
# reads nothing; Ada reads all and deletes one; the rig writes on, and
# Ann's new session is hers to read.
. "$(dirname "$0")/../common.sh"
. "$(dirname "$0")/pg_lib.sh"
pg_make

at_centre() { [ "$(sql 'SELECT COUNT(*) FROM sessions')" = "$1" ]; }
# centre SQL: as the superuser in the centre's database
centre() { psql -X -q -At -v ON_ERROR_STOP=1 \
	"host=$PGSOCK user=admin dbname=endosim" "$@"; }
# as LOGIN SQL: a query with LOGIN's credentials
as() { psql -X -q -At -v ON_ERROR_STOP=1 \
	"host=$PGSOCK user=$1 dbname=endosim" -c "$2"; }
url_of() { echo "postgresql:///endosim?host=$PGSOCK&user=$1"; }

start_daemon --set "records.centre=$URL" --set records.rig=rig-a \
	--set records.centre_retry_s=0.1 || finish
check "sessions of Ann, Bo and Cy recorded" eval \
	'record_session Ann && record_session Bo && record_session Cy'
check "... at the centre" wait_for at_centre 3

check "centre-roles.sql run" centre -f "$TOP/config/centre-roles.sql"
check "... and again: it changes nothing twice" \
	centre -f "$TOP/config/centre-roles.sql"
# person LOGIN NAME ROLE GROUPROLE: a login of their own, and their row
person() {
	centre -c "CREATE ROLE $1 LOGIN PASSWORD '$1-pw' IN ROLE $4" \
		-c "INSERT INTO endosim_people VALUES ('$1', '$2', '$3')" &&
		printf '*:*:endosim:%s:%s-pw\n' "$1" "$1" >>"$PGPASSFILE"
}
check "the people: Ann, Bo, Dr Ives, Ada, a stranger" eval \
	"person ann Ann trainee endosim_trainee &&
	 person bo Bo trainee endosim_trainee &&
	 person ives 'Dr Ives' instructor endosim_instructor &&
	 person ada Ada administrator endosim_admin &&
	 centre -c 'CREATE ROLE stranger LOGIN PASSWORD '\''stranger-pw'\'' \
	 IN ROLE endosim_trainee' &&
	 printf '*:*:endosim:stranger:stranger-pw\n' >>\"\$PGPASSFILE\""
check "group 2026 of Ann and Bo, managed by Dr Ives" centre \
	-c "INSERT INTO endosim_groups VALUES ('2026', 'Dr Ives')" \
	-c "INSERT INTO endosim_members VALUES ('2026', 'Ann'), ('2026', 'Bo')"

# the trainee
check "Ann: every session she can read is hers" test \
	"$(as ann 'SELECT string_agg(trainee, $$,$$) FROM sessions')" = Ann
check "Ann: a query for Bo's rows returns none" test \
	"$(as ann "SELECT COUNT(*) FROM sessions WHERE trainee = 'Bo'")" = 0
check "Ann: a query for anyone else's returns none" test \
	"$(as ann "SELECT COUNT(*) FROM sessions WHERE trainee <> 'Ann'
	OR trainee IS NULL")" = 0
BO_UUID=$(sql "SELECT uuid FROM sessions WHERE trainee = 'Bo'")
check "Ann: Bo's report page by its UUID: none" test \
	"$(as ann "SELECT COUNT(report) FROM sessions
	WHERE uuid = '$BO_UUID'")" = 0
check_status "Ann: DELETE: refused" 1 as ann "DELETE FROM sessions"
check "... in words" grep -q "permission denied for table sessions" "$OUT"
check_status "Ann: UPDATE her own: refused" 1 \
	as ann "UPDATE sessions SET trainee = 'Bo'"
check_status "Ann: the people: refused" 1 \
	as ann "SELECT * FROM endosim_people"
check_status "Ann: SET ROLE rig, the owner the rules do not bind: refused" 1 \
	as ann "SET ROLE rig"
check "... nothing changed: three sessions, Ann's hers" test \
	"$(sql "SELECT string_agg(trainee, ',' ORDER BY trainee)
	FROM sessions")" = "Ann,Bo,Cy"
check_status "Ann: endoctl trainee list --centre" 0 \
	ctl --json trainee list --centre "$(url_of ann)"
check "... herself only" jq -e '[.trainees[].trainee] == ["Ann"]' "$OUT"

# the instructor, a login with no person, the administrator
check "Dr Ives: his group's sessions, Ann's and Bo's" test \
	"$(as ives 'SELECT string_agg(trainee, $$,$$ ORDER BY trainee)
	FROM sessions')" = "Ann,Bo"
check "Dr Ives: a query for Cy's rows returns none" test \
	"$(as ives "SELECT COUNT(*) FROM sessions WHERE trainee = 'Cy'")" = 0
check_status "Dr Ives: DELETE: refused" 1 as ives "DELETE FROM sessions"
check_status "Dr Ives: endoctl trainee list --centre" 0 \
	ctl --json trainee list --centre "$(url_of ives)"
check "... Ann and Bo" jq -e '[.trainees[].trainee] | sort == ["Ann", "Bo"]' \
	"$OUT"
check "a login with no person: nothing" test \
	"$(as stranger 'SELECT COUNT(*) FROM sessions')" = 0
check "Ada: every session" test \
	"$(as ada 'SELECT COUNT(*) FROM sessions')" = 3
check "Ada: Cy's deleted" test \
	"$(as ada "DELETE FROM sessions WHERE trainee = 'Cy' RETURNING 1")" = 1

# the rig writes on under the policies
check "the rig: another session of Ann" record_session Ann
check "... at the centre" wait_for at_centre 3
check "... and Ann's to read" test \
	"$(as ann 'SELECT COUNT(*) FROM sessions')" = 2

finish
