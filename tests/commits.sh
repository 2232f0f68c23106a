#!/bin/bash
# commits.sh - commit messages in git's own form: a subject of at most 72
# characters, then a blank line and a body that says why (merges may keep
# git's one-line "Merge branch ..."). Prints "N passed, N failed".
#
#   tests/commits.sh              every commit since the form was adopted
#   tests/commits.sh --message F  one message (the commit-msg hook's)
#
# The form was adopted after b34ccd0; older subjects are history and stay
# as they are. A checkout without git or without that commit (a shallow
# clone, a tarball) skips the check and says so.
set -u

SINCE=b34ccd01ec9208a352d8b319649f7fd58fbd4f3c
SUBJECT_MAX=72

# check_messages [hook]: reads records separated by NUL, each a line "ID
# PARENT..." (a merge has two parents or more) and the message below it;
# prints "not ok - ID SUBJECT: WHY" for each message out of form and the
# tally "N passed, N failed" (the hook: the why alone, on stderr); exits
# non-zero when any failed.
check_messages() {
	awk -v max="$SUBJECT_MAX" -v hook="${1:-}" 'BEGIN { RS = "\0" }
	NF == 0 { next }
	{
		n = split($0, line, "\n")
		merge = split(line[1], head, " ") > 2
		subject = line[2]
		body = 0
		for (i = 4; i <= n; i++) {
			body = body || line[i] ~ /[^[:space:]]/
		}
		why = ""
		if (subject == "") {
			why = "no subject"
		} else if (length(subject) > max) {
			why = "subject of " length(subject) " characters (at most " max ")"
		} else if (line[3] != "") {
			why = "no blank line after the subject"
		} else if (!merge && !body) {
			why = "no body: say why"
		}
		if (why == "") {
			passed++
		} else if (hook) {
			failed++
			printf "commit message: %s (see README, Contributing)\n", why > "/dev/stderr"
		} else {
			failed++
			printf "not ok - %s %s: %s\n", head[1], substr(subject, 1, 50), why
		}
	}
	END {
		if (!hook) {
			printf "%d passed, %d failed\n", passed, failed
		}
		exit failed > 0
	}'
}

if [ "${1:-}" = --message ]; then
	# the hook: comments and everything below the scissors line are git's
	parents=one
	git rev-parse -q --verify MERGE_HEAD >/dev/null 2>&1 && parents="one two"
	{
		echo "message $parents"
		sed -e '/^# -\{8,\} >8 -\{8,\}/,$d' -e '/^#/d' "$2"
	} | check_messages hook
	exit
fi

TOP=$(cd "$(dirname "$0")/.." && pwd)
cd "$TOP" || exit 1
if ! command -v git >/dev/null 2>&1 ||
	! git rev-parse -q --verify "$SINCE^{commit}" >/dev/null 2>&1; then
	echo "skip - commit messages: no git history here (a shallow clone?)"
	echo "0 passed, 0 failed, 1 skipped"
	exit 0
fi
git log --reverse -z --format='%h %p%n%B' "$SINCE..HEAD" | check_messages
