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

# message_ok TEXT MERGE: 0 when TEXT has the form; the fault on stdout.
message_ok() {
	local text=$1 merge=$2 subject second body
	subject=$(printf '%s\n' "$text" | sed -n 1p)
	second=$(printf '%s\n' "$text" | sed -n 2p)
	body=$(printf '%s\n' "$text" | sed -n '3,$p' | grep -v '^[[:space:]]*$')
	if [ -z "$subject" ]; then
		echo "no subject"
	elif [ "${#subject}" -gt "$SUBJECT_MAX" ]; then
		echo "subject of ${#subject} characters (at most $SUBJECT_MAX)"
	elif [ -n "$second" ]; then
		echo "no blank line after the subject"
	elif [ "$merge" = no ] && [ -z "$body" ]; then
		echo "no body: say why"
	else
		return 0
	fi
	return 1
}

if [ "${1:-}" = --message ]; then
	# the hook: comments and everything below the scissors line are git's
	text=$(sed -e '/^# -\{8,\} >8 -\{8,\}/,$d' -e '/^#/d' "$2")
	merge=no
	git rev-parse -q --verify MERGE_HEAD >/dev/null 2>&1 && merge=yes
	if ! why=$(message_ok "$text" "$merge"); then
		echo "commit message: $why (see README, Contributing)" >&2
		exit 1
	fi
	exit 0
fi

TOP=$(cd "$(dirname "$0")/.." && pwd)
cd "$TOP" || exit 1
if ! command -v git >/dev/null 2>&1 ||
	! git rev-parse -q --verify "$SINCE^{commit}" >/dev/null 2>&1; then
	echo "skip - commit messages: no git history here (a shallow clone?)"
	echo "0 passed, 0 failed, 1 skipped"
	exit 0
fi
passed=0
failed=0
for c in $(git rev-list --reverse "$SINCE..HEAD"); do
	merge=no
	[ "$(git rev-list --parents -n 1 "$c" | wc -w)" -gt 2 ] && merge=yes
	if why=$(message_ok "$(git log -1 --format=%B "$c")" "$merge"); then
		passed=$((passed + 1))
	else
		echo "not ok - $(git log -1 --format='%h %s' "$c" | cut -c1-60): $why"
		failed=$((failed + 1))
	fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
