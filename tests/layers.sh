#!/bin/bash
# layers.sh - the nevers of docs/ARCHITECTURE.md ("The wings"), checked on
# the sources: every #include "..." of a wing's files is looked up by name
# to the wing that holds the header, and one a wing must never include fails
# with its file and line. One check per file; prints "N passed, N failed".
#
# A header's wing is its folder: proto/ (and the generated endosim.pb-c.h),
# daemon/base/, daemon/model/, daemon/rig/, daemon/session/, daemon/ (the
# service), daemon/ctl/ (endoctl), viewer/. Two of base's modules are named
# on their own: the model may use base but never its configuration or its
# logging.
set -u

TOP=$(cd "$(dirname "$0")/.." && pwd)
cd "$TOP" || exit 1

# wing: what it never includes (wings, or base's config.h and log.h)
declare -A NEVER=(
	[proto]="base model rig session service ctl viewer"
	[base]="model rig session service ctl viewer"
	[model]="config.h log.h rig session service ctl viewer"
	[rig]="session service ctl viewer"
	[session]="rig service ctl viewer"
	[viewer]="rig service ctl"
)

declare -A WING # header name -> its wing
wing_of_dir() {
	case "$1" in
	proto) echo proto ;;
	daemon/base) echo base ;;
	daemon/model) echo model ;;
	daemon/rig) echo rig ;;
	daemon/session) echo session ;;
	daemon) echo service ;;
	daemon/ctl) echo ctl ;;
	viewer) echo viewer ;;
	esac
}
for f in proto/*.h daemon/*.h daemon/*/*.h viewer/*.h; do
	[ -e "$f" ] || continue
	WING[$(basename "$f")]=$(wing_of_dir "$(dirname "$f")")
done
WING[endosim.pb-c.h]=proto

passed=0
failed=0
for f in proto/*.[ch] daemon/*.[ch] daemon/*/*.[ch] viewer/*.[ch]; do
	[ -e "$f" ] || continue
	wing=$(wing_of_dir "$(dirname "$f")")
	never=" ${NEVER[$wing]:-} "
	bad=0
	while IFS=: read -r line header; do
		name=$(basename "$header")
		to=${WING[$name]:-}
		[ -n "$to" ] || continue
		case "$never" in
		*" $to "* | *" $name "*) ;;
		*) continue ;;
		esac
		echo "not ok - $f:$line: $wing includes $name ($to): a never"
		bad=1
	done < <(awk '/^[ \t]*#[ \t]*include[ \t]*"/ {
		h = $0; sub(/^[^"]*"/, "", h); sub(/".*/, "", h)
		print FNR ":" h }' "$f")
	if [ "$bad" -eq 0 ]; then
		passed=$((passed + 1))
	else
		failed=$((failed + 1))
	fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
