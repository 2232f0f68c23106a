#!/bin/bash
# Who sees what on the rig (issue 24): users made by the rig's staff (root
# or the endosim group, an administrator while not logged in), a group of
# two trainees managed by an instructor, a trainee outside it; sessions of
# each. Logged in (endoctl --as NAME, the PIN from $ENDOSIM_PIN), a trainee
# lists only their own sessions and is refused, in words, another's by
# name, a session of another shown, the records' maintenance and the
# accounts' changes, which change nothing; the instructor lists their
# group's trainees' only, and manages his group: a trainee of his own
# added with a first PIN, who logs in; trainees joined and left, courses
# assigned and unassigned; refused, in words and changing nothing, an
# instructor added, a user removed, another instructor's group or trainee
# touched. The administrator sees every
# session. Without a login an
# unprivileged user (nobody) sees no records, with one their own. Wrong
# PINs: a few refused, then a try waits, even with the right PIN, a wait
# that grows; after it the right PIN logs in. (The waits are the rule's
# own seconds: the test sleeps them out, and the one check made inside a
# wait has 4 s to spare.) The PINs are nowhere in
# clear: not in the accounts' database, the records' or the log.
#
# Who trains at the rig (endoview's login screen, on a virtual screen,
# xdotool typing into it): a rig without a trainee's account does not
# ask; with one, the screen asks; a wrong PIN is refused on it and
# changes nothing; the right one makes Ann the rig's trainee (the
# status says so, a session started without --trainee is hers, Bo's is
# refused); C logs her out and the screen asks again; Bo logs in there
# and is logged out as endoview quits; --trainee with $ENDOSIM_PIN logs
# in without the screen, the HUD naming her (with a wrong one the screen
# says so: the docs' picture).
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

SESS="$TMP/sessions"
ACCOUNTS="$SESS/accounts.sqlite"
start_daemon || finish
check "no trainee's account: nobody trains, endoview is not asked to" \
	status_true '.trainee == "" and .asks_trainee == false'

# as NAME PIN ARGS...: endoctl logged in as NAME
as() {
	local name=$1 pin=$2
	shift 2
	ENDOSIM_PIN=$pin ctl --as "$name" "$@"
}
# add NAME ROLE PIN: a user made by the staff
add() { ENDOSIM_NEW_PIN=$3 ctl user add "$1" --role "$2"; }
# trainees_of: the trainees of the sessions the last --json list gave
trainees_of() { jq -c '[.sessions[].trainee] | sort' "$OUT"; }

check "staff: an administrator, two instructors, three trainees" eval \
	'add Ada administrator 90210777 && add "Dr Ives" instructor 16180339 &&
	 add "Dr Jay" instructor 14142135 && add Ann trainee 48213579 &&
	 add Bo trainee 27182818 && add Cy trainee 31415926'
check_status "a PIN too short: refused" 1 \
	env ENDOSIM_NEW_PIN=12 "$ENDOCTL" --socket "$SOCK" user add Di \
	--role trainee
check "... in words" grep -q "a PIN: 4 to 64 characters" "$OUT"
check_status "a second Ann: refused" 1 add Ann trainee 44440000
check "... in words" grep -q "there is a user Ann already" "$OUT"
check "group 2026 of Ann and Bo, managed by Dr Ives" eval \
	'ctl group add 2026 --instructor "Dr Ives" &&
	 ctl group join 2026 Ann Bo && ctl group assign 2026 basic.course'
check "group 2025 of Cy, managed by Dr Jay" eval \
	'ctl group add 2025 --instructor "Dr Jay" && ctl group join 2025 Cy'
check_status "group list" 0 ctl --json group list
check "... as made" jq -e '.groups | map(select(.name == "2026")) == [{
	"name": "2026", "instructor": "Dr Ives", "trainees": ["Ann", "Bo"],
	"courses": ["basic.course"]}]' "$OUT"
check "sessions of Ann, Ann, Bo and Cy" eval \
	'record Ann 100 && record Ann 100 && record Bo 100 &&
	 record Cy 100'

# the trainee
check_status "Ann: whoami" 0 as Ann 48213579 whoami
check "... Ann (trainee)" grep -qx "Ann (trainee)" "$OUT"
check_status "Ann: session list" 0 as Ann 48213579 --json session list
check "... her own two only" test "$(trainees_of)" = '["Ann","Ann"]'
check_status "Ann: trainee list" 0 as Ann 48213579 --json trainee list
check "... herself only" jq -e '[.trainees[].trainee] == ["Ann"]' "$OUT"
check "... judged by her group's course" jq -e \
	'.trainees[0].courses | map(.name + " of " + .group) == ["basic of 2026"]' \
	"$OUT"
printf '[course]\nname = c\nconsecutive = 1\n[case normal]\ncecum_s <= 480\n' \
	>"$TMP/c.course"
check "Cy's group 2027 and its course" eval 'ctl group add 2027 \
	--instructor "Dr Ives" && ctl group join 2027 Cy &&
	ctl group assign 2027 "$TMP/c.course"'
echo garbage >"$TMP/c.course"
check_status "... gone bad: the staff's list refused" 1 ctl trainee list
check "... in words" grep -q "group 2027's course $TMP/c.course: $TMP/c.course:1:" \
	"$OUT"
check_status "... Ann's, which it does not judge, is not" 0 \
	as Ann 48213579 trainee list
ctl group remove 2027 >/dev/null
check_status "Ann: Bo's page: refused" 1 \
	as Ann 48213579 trainee report Bo --out "$TMP/bo"
check "... in words" grep -q "Bo's sessions: a trainee sees only their own \
(you are logged in as Ann (trainee))" "$OUT"
check_status "Ann: Cy's session 4 shown: refused" 1 as Ann 48213579 session show 4
check "... in words" grep -q "that session is another trainee's" "$OUT"
check_status "Ann: her session 1 shown" 0 as Ann 48213579 session show 1
check_status "Ann: Cy's session 4 exported: refused" 1 \
	as Ann 48213579 session export 4 --csv --out "$TMP/cy.csv"
check "... nothing written" test ! -e "$TMP/cy.csv"
check_status "Ann: her session 1 exported" 0 \
	as Ann 48213579 session export 1 --csv --out "$TMP/ann.csv"
for what in "records check" "records rebuild" "records backup $TMP/b.sqlite"; do
	check_status "Ann: $what: refused" 1 as Ann 48213579 $what
	check "... in words" grep -q "only an administrator checks, rebuilds" \
		"$OUT"
done
check "... no backup made" test ! -e "$TMP/b.sqlite"
check_status "Ann: a session of Bo started: refused" 1 \
	as Ann 48213579 session start --trainee Bo
check "... in words" grep -q "Bo's sessions: a trainee sees only their own" \
	"$OUT"
check "... none recording" live_status '.recording == false'
check_status "Ann: user remove Bo: refused" 1 as Ann 48213579 user remove Bo
check "... in words" grep -q "only an administrator, or an instructor in \
the groups they manage, changes the accounts" "$OUT"
check_status "Ann: group leave 2026 Ann: refused" 1 \
	as Ann 48213579 group leave 2026 Ann
check_status "... nothing changed" 0 ctl --json group list
check "... (the group as it was)" jq -e '.groups | map(select(.name ==
	"2026"))[0].trainees == ["Ann", "Bo"]' "$OUT"
check_status "... (the users as they were)" 0 ctl --json user list
check "... (six)" jq -e '.users | length == 6' "$OUT"

# the instructor
check_status "Dr Ives: session list" 0 as "Dr Ives" 16180339 --json session list
check "... his group's: Ann's two and Bo's" test "$(trainees_of)" = \
	'["Ann","Ann","Bo"]'
check_status "Dr Ives: Cy's page: refused" 1 \
	as "Dr Ives" 16180339 trainee report Cy --out "$TMP/cy"
check "... in words" grep -q "Cy's sessions: not a trainee of your groups" \
	"$OUT"
check "... no page written" test ! -e "$TMP/cy"
check_status "Dr Ives: group list" 0 as "Dr Ives" 16180339 --json group list
check "... his group, the users he acts on: himself and its trainees" \
	jq -e '(.groups | map(.name)) == ["2026"] and ([.users[].name] ==
	["Ann", "Bo", "Dr Ives"])' "$OUT"

# the instructor manages his group: a trainee of his own, who logs in
# with her first PIN (each command below logs in anew: a hash each, so
# the rest of the rule is test_accounts')
ives() { as "Dr Ives" 16180339 "$@"; }
# ives_new PIN ARGS...: the same, a new PIN with it
ives_new() {
	local pin=$1
	shift
	ENDOSIM_NEW_PIN=$pin ives "$@"
}
check_status "Dr Ives: a trainee Di added, with a first PIN" 0 \
	ives_new 11235813 user add Di --role trainee
check_status "Dr Ives: Di, in no group, joins 2026" 0 ives group join 2026 Di
check_status "Dr Ives: Bo leaves 2026" 0 ives group leave 2026 Bo
check_status "Dr Ives: a course assigned to 2026" 0 \
	ives group assign 2026 polypectomy.course
check_status "Dr Ives: one unassigned" 0 ives group unassign 2026 basic.course
check_status "Di: logs in with her first PIN" 0 as Di 11235813 whoami
check "... as a trainee" grep -qx "Di (trainee)" "$OUT"
# refused: each in words, nothing changed
check_status "Dr Ives: an instructor added: refused" 1 \
	ives_new 55556666 user add Eve --role instructor
check "... in words" grep -q "an instructor adds trainees only" "$OUT"
check_status "Dr Ives: Di into Dr Jay's 2025: refused" 1 \
	ives group join 2025 Di
check "... in words" grep -q "group 2025 is Dr Jay's: an instructor changes \
only the groups they manage (you are logged in as Dr Ives (instructor))" \
	"$OUT"
check_status "Dr Ives: Cy, Dr Jay's trainee, into 2026: refused" 1 \
	ives group join 2026 Cy
check "... in words" grep -q "Cy is a trainee of group 2025, Dr Jay's" "$OUT"
check_status "Dr Ives: user remove Di: refused" 1 ives user remove Di
check "... in words" grep -q "only an administrator removes a user" "$OUT"
check_status "... the groups as he left them" 0 ctl --json group list
check "... (2026 his, 2025 untouched)" jq -e '.groups == [{"name": "2025",
	"instructor": "Dr Jay", "trainees": ["Cy"], "courses": []}, {"name":
	"2026", "instructor": "Dr Ives", "trainees": ["Ann", "Di"], "courses":
	["polypectomy.course"]}]' "$OUT"
check_status "... the users" 0 ctl --json user list
check "... (Di added, no Eve)" jq -e '[.users[].name] == ["Ada", "Ann", "Bo",
	"Cy", "Di", "Dr Ives", "Dr Jay"]' "$OUT"
check_status "... Dr Ives's user list" 0 ives --json user list
check "... (his group's, Bo in no group now, not Dr Jay's Cy)" jq -e \
	'[.users[].name] == ["Ann", "Bo", "Di", "Dr Ives"]' "$OUT"

# the administrator
check_status "Ada: session list" 0 as Ada 90210777 --json session list
check "... every one" test "$(trainees_of)" = '["Ann","Ann","Bo","Cy"]'
check_status "Ada: records check" 0 as Ada 90210777 records check

# who trains at the rig: endoview's login screen
# type TEXT: xdotool types TEXT into the viewer, then Enter
type() { xdotool type --delay 20 "$1" && xdotool key Return; }
# said N RE: the live viewer's log has N lines matching RE (grep -E)
said() { test "$(grep -cE "$2" "$TMP/live.out")" -ge "$1"; }
start_xvfb || finish
check "the accounts hold trainees: endoview is asked to" \
	status_true '.asks_trainee and .trainee == ""'
live_view normal --size 640x480 --max-fps 30
check "endoview asks who is training" \
	wait_for said 1 "login: who is training\?"
type Ann && type 00000000
check "a wrong PIN: refused on the screen" \
	wait_for said 1 "login of Ann refused: wrong name or PIN"
check "... nobody trains" status_true '.trainee == ""'
type 48213579
check "the right PIN: Ann trains at the rig" \
	wait_for said 1 "login: Ann trains at the rig"
check "... the status says so" status_true '.trainee == "Ann"'
check_status "... endoctl status too" 0 ctl status
check "... (its line)" grep -qx "trainee   Ann" "$OUT"
check_status "a session started without --trainee" 0 ctl --json session start
check "... is Ann's" jq -e '.trainee == "Ann"' "$OUT"
ctl session stop >/dev/null
check_status "Bo's session while Ann trains: refused" 1 \
	ctl session start --trainee Bo
check "... in words" grep -q "Ann is training at the rig: a session of Bo \
needs Ann to log out first" "$OUT"
xdotool key c
check "C: Ann logs out, the screen asks again" \
	wait_for said 2 "login: who is training\?"
check "... nobody trains" status_true '.trainee == ""'
type Bo && type 27182818
check "Bo logs in on it" wait_for status_true '.trainee == "Bo"'
check_status "Bo removed while he trains" 0 ctl user remove Bo
check "... nobody trains" status_true '.trainee == ""'
check "... endoview's login as Bo ended" grep -q \
	"logged out: Bo (trainee) is no longer a user" "$LOG"
check "... and it asks who is training again" \
	wait_for said 3 "login: who is training\?"
check_status "Bo added again, his PIN as before" 0 \
	env ENDOSIM_NEW_PIN=27182818 "$ENDOCTL" --socket "$SOCK" user add Bo \
	--role trainee
type Bo && type 27182818
check "... and logs in on it" wait_for status_true '.trainee == "Bo"'
xdotool key q
check "Q: endoview quits" wait_for eval '! kill -0 "$VIEWER" 2>/dev/null'
kill "$VIEWER" 2>/dev/null
wait "$VIEWER"
check "... and logs Bo out" said 1 "Bo logged out as endoview quits"
check "... nobody trains" status_true '.trainee == ""'
ENDOSIM_PIN=00000000 view --size 640x480 --frames 4 --trainee Ann \
	--screenshot "$TMP/login.png" --print-state
check "--trainee Ann with a wrong PIN: the screen says so" grep -qx \
	"login: asking: name 'Ann', PIN 0 characters, focus PIN: wrong name or PIN" \
	"$VIEW_OUT"
keep_picture "$TMP/login.png" endoview-login
ENDOSIM_PIN=48213579 view --frames 1 --trainee Ann --print-state
check "--trainee Ann, the PIN from \$ENDOSIM_PIN: in without the screen" \
	grep -qx "login: Ann trains" "$VIEW_OUT"
check "... the HUD names her" grep -q "^hud: trainee Ann  (C: log out)" \
	"$VIEW_OUT"
check "... and she is logged out as it quits" status_true '.trainee == ""'
check "the session list: Ann's session, recorded as she trained" \
	eval 'ctl --json session list | jq -e ".sessions[-1].trainee == \"Ann\""'

# an unprivileged user: the read-only socket, no records without a login
if [ "$(id -u)" = 0 ]; then
	chmod 711 "$TMP"
	nobody() { runuser -u nobody -- env "$@"; }
	check_status "nobody, not logged in: session list: refused" 1 \
		nobody "$ENDOCTL" --socket "$SOCK" session list
	check "... in words" grep -q "the records need a login" "$OUT"
	check_status "nobody, as Bo: trainee list" 0 nobody ENDOSIM_PIN=27182818 \
		"$ENDOCTL" --socket "$SOCK" --as Bo --json trainee list
	check "... Bo's only" jq -e '[.trainees[].trainee] == ["Bo"]' "$OUT"
	check_status "nobody, as Bo: his own PIN changed" 0 nobody \
		ENDOSIM_PIN=27182818 ENDOSIM_NEW_PIN=55443322 "$ENDOCTL" --socket \
		"$SOCK" --as Bo user pin Bo
	check_status "... the new one logs in" 0 as Bo 55443322 whoami
	check_status "nobody, as Ada: user add: the control socket is not \
theirs" 3 nobody ENDOSIM_PIN=90210777 ENDOSIM_NEW_PIN=55550000 "$ENDOCTL" \
		--socket "$SOCK" --as Ada user add Eve --role trainee
else
	skip "an unprivileged user: the test runs as one (no root to be nobody)"
fi

# wrong PINs: three in a row, then each makes the next try wait, 1 s, 2 s,
# 4 s; each sleep below starts after the refusal, so it outlasts the wait
for i in 1 2 3; do
	check_status "Ann, a wrong PIN ($i): refused" 1 as Ann 00000000 whoami
	check "... in words" grep -q "wrong name or PIN" "$OUT"
done
check "... the third: the next try waits" grep -q "the next try waits" "$OUT"
sleep 1.1
check_status "after the wait, a wrong PIN (4): refused" 1 as Ann 00000000 whoami
sleep 2.1
check_status "after the wait, a wrong PIN (5): refused" 1 as Ann 00000000 whoami
check_status "the right PIN at once: refused, she waits" 1 as Ann 48213579 whoami
check "... a wait grown to 4 s, in words" grep -q \
	"too many wrong PINs for Ann: try again in [34] s" "$OUT"
sleep 4.1
check_status "after it, the right PIN: in" 0 as Ann 48213579 whoami
check "... as Ann" grep -qx "Ann (trainee)" "$OUT"
check_status "a wrong PIN again: refused, no wait (the count cleared)" 1 \
	as Ann 00000000 whoami
check "... in words" grep -qx "endoctl: permission denied: wrong name or PIN" \
	"$OUT"
check_status "an unknown name: refused" 1 as Zed 48213579 whoami
check "... in the same words" grep -q "wrong name or PIN" "$OUT"

# the PINs in clear: nowhere
for f in "$ACCOUNTS" "$SESS/records.sqlite" "$LOG"; do
	check "no PIN in clear in $(basename "$f")" eval \
		"! grep -a -q -e 90210777 -e 16180339 -e 48213579 -e 55443322 -e 31415926 \
		-e 11235813 '$f'"
done
check "the accounts' database holds Argon2id hashes" test \
	"$(grep -a -o '\$argon2id\$' "$ACCOUNTS" | wc -l)" -ge 7
check "... and only its owner reads it" test \
	"$(stat -c %a "$ACCOUNTS")" = 600

finish
