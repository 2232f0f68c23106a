#!/bin/bash
# Hostile names and course files in the rig's records (issue 24): a
# trainee named with quotes, semicolons and SQL is recorded and shown as
# given by session list, trainee list and the database itself; names of
# 10 kB and with control characters are refused at the socket, saying
# why; a name with a NUL byte inside its protobuf string (a hand-made
# request: endoctl's arguments cannot hold one), which protobuf-c would
# cut short silently, is refused on both sockets, nothing recorded; a
# course file with a NUL byte is refused with its file and line, one with
# quotes and semicolons in its name judges as given.
. "$(dirname "$0")/../common.sh"

SESS="$TMP/sessions"
DB="$SESS/records.sqlite"
HOSTILE="O'Neil \"x\"; DROP TABLE trainees;--"

start_daemon --session-dir "$SESS" || finish

sessions() { ctl --json session list | jq '.sessions | length'; }

check "a trainee named with quotes, semicolons and SQL recorded" \
	record "$HOSTILE"
check_status "session list" 0 ctl --json session list
check "... shows the name as given" \
	jq -e --arg n "$HOSTILE" '[.sessions[].trainee] == [$n]' "$OUT"
check_status "trainee list" 0 ctl --json trainee list
check "... shows the name as given" \
	jq -e --arg n "$HOSTILE" '[.trainees[].trainee] == [$n]' "$OUT"
if command -v sqlite3 >/dev/null; then
	check "... the database holds it as given, its tables whole" test \
		"$(sqlite3 -readonly "$DB" 'SELECT name FROM trainees')" = \
		"$HOSTILE"
fi

BIG=$(head -c 10240 /dev/zero | tr '\0' x)
check_status "a 10 kB name refused" 1 ctl session start --trainee "$BIG"
check "... saying why" grep -q "trainee: at most 63 bytes" "$OUT"
check_status "a name with a tab refused" 1 \
	ctl session start --trainee "$(printf 'Ann\tSmith')"
check "... saying why" grep -q "no control characters" "$OUT"
check_status "a 10 kB trainee to list: none such" 1 \
	ctl trainee report "$BIG" --out "$TMP/page"

# raw REQUEST_BYTES...: a request (printf's escapes) framed (its length,
# 4 bytes little-endian) to SOCKET; the reply's bytes on stdout
raw() {
	local sock=$1 body=$2 len
	len=$(printf "$body" | wc -c)
	{ printf "\\$(printf %03o "$len")\\000\\000\\000"; printf "$body"; } |
		timeout 5 socat -t 1 - "UNIX-CONNECT:$sock" 2>/dev/null
}
# SessionStart{trainee = "Ann\0Evil"}: Request field 25 (key 0xca 0x01),
# its field 1 (key 0x0a); version 1, seq 7
START='\010\001\020\007\312\001\012\012\010Ann\000Evil'
raw "$SOCK/control.sock" "$START" >"$TMP/reply"
check "a name with a NUL byte refused on the control socket" \
	grep -aq "a name holds a NUL byte" "$TMP/reply"
check "... nothing recorded" test "$(sessions)" = 1
check "... not recording" live_status '.recording | not'
# TraineeSessions{trainee = "Ann\0Evil"}: field 32 (key 0x82 0x02)
LIST='\010\001\020\007\202\002\012\012\010Ann\000Evil'
raw "$SOCK/status.sock" "$LIST" >"$TMP/reply"
check "... and in a trainee's request on the status socket" \
	grep -aq "a name holds a NUL byte" "$TMP/reply"
LIST='\010\001\020\007\202\002\010\012\006Ann;--'
raw "$SOCK/status.sock" "$LIST" >"$TMP/reply"
check "... where one without it is answered" \
	test -s "$TMP/reply" -a -z "$(grep -a "NUL byte" "$TMP/reply")"

printf '[course]\nname = t\0evil\nconsecutive = 1\n[case normal]\ncecum_s <= 1e9\n' \
	>"$TMP/nul.course"
check_status "a course file with a NUL byte refused" 1 \
	ctl trainee list --course "$TMP/nul.course"
check "... with its file and line" grep -q "nul.course:2: a NUL byte" "$OUT"
printf '[course]\nname = it'"'"'s; DROP TABLE x;--\nconsecutive = 1\n[case normal]\ncecum_s <= 1e9\n' \
	>"$TMP/quotes.course"
check_status "a course named with quotes and semicolons" 0 \
	ctl --json trainee list --course "$TMP/quotes.course"
check "... judges by its name as given" \
	jq -e '.course == "it'"'"'s; DROP TABLE x;--"' "$OUT"

finish
