#!/bin/bash
# layers.sh - the wings of docs/ARCHITECTURE.md, checked on the sources and
# on the Makefile. One check per source file: every #include "WING/NAME.h"
# names its wing, and the file's wing may include it (the table below,
# with base's logging kept out of the model). One check per program: the
# wings the Makefile links into it are those it may link. Prints "N passed,
# N failed".
#
# A file's wing is its folder: proto/, lib/WING/, daemon/WING/ (daemon/
# itself is endosimd's main), endoctl/, viewer/. An include that names no
# wing ("foo.h") is one of the file's own folder, or of the tests'.
set -u

TOP=$(cd "$(dirname "$0")/.." && pwd)
cd "$TOP" || exit 1

# wing: the wings it may include (itself always)
declare -A MAY=(
	[proto]=""
	[base]="proto"
	[model]="base proto"
	[conf]="model base proto"
	[session]="conf model base proto"
	[rig]="conf model base proto"
	[loop]="rig conf model base proto"
	[recorder]="loop rig session conf model base proto"
	[control]="recorder loop rig session conf model base proto"
	[endosimd]="control recorder loop rig session conf model base proto"
	[endoctl]="session model base proto"
	[viewer]="session model base proto"
)
# headers of a wing it may otherwise include that stay out: the model knows
# nothing of logging (a model function reports through its return value)
declare -A NEVER_HEADER=(
	[model]="base/log.h"
)
# program: the wings it may link
declare -A LINKS=(
	[endosimd]="control recorder loop rig session conf model base proto"
	[endoctl]="session conf model base proto"
	[endoview]="viewer session conf model base proto"
)

wing_of() {
	case "$1" in
	proto/*) echo proto ;;
	lib/*/*) echo "${1#lib/}" | cut -d/ -f1 ;;
	daemon/*/*) echo "${1#daemon/}" | cut -d/ -f1 ;;
	daemon/*) echo endosimd ;;
	endoctl/*) echo endoctl ;;
	viewer/*) echo viewer ;;
	esac
}

passed=0
failed=0
for f in proto/*.[ch] lib/*/*.[ch] daemon/*.[ch] daemon/*/*.[ch] \
	endoctl/*.[ch] viewer/*.[ch]; do
	[ -e "$f" ] || continue
	wing=$(wing_of "$f")
	may=" $wing ${MAY[$wing]} "
	never=" ${NEVER_HEADER[$wing]:-} "
	bad=0
	while IFS=: read -r line header; do
		case "$header" in
		*/*) to=${header%%/*} ;;
		*)
			if [ -e "$(dirname "$f")/$header" ]; then
				continue
			fi
			echo "not ok - $f:$line: \"$header\" names no wing"
			bad=1
			continue
			;;
		esac
		[ "$to" = endoctl ] && to=endoctl
		case "$may" in
		*" $to "*) ;;
		*)
			echo "not ok - $f:$line: $wing includes $header: $to is" \
				"not among what $wing may include"
			bad=1
			continue
			;;
		esac
		case "$never" in
		*" $header "*)
			echo "not ok - $f:$line: $wing includes $header: a never"
			bad=1
			;;
		esac
	done < <(awk '/^[ \t]*#[ \t]*include[ \t]*"/ {
		h = $0; sub(/^[^"]*"/, "", h); sub(/".*/, "", h)
		print FNR ":" h }' "$f")
	if [ "$bad" -eq 0 ]; then
		passed=$((passed + 1))
	else
		failed=$((failed + 1))
	fi
done

# the wings each program links, as the Makefile says (make -p prints the
# variables without building anything)
vars=$(make -pn -f Makefile BUILD=/nonexistent 2>/dev/null)
for p in "${!LINKS[@]}"; do
	linked=$(printf '%s\n' "$vars" | sed -n "s/^${p}_WINGS = //p" | head -n 1)
	bad=""
	for w in $linked; do
		case " ${LINKS[$p]} " in
		*" $w "*) ;;
		*) bad="$bad $w" ;;
		esac
	done
	if [ -z "$linked" ]; then
		echo "not ok - $p: the Makefile names no wings for it"
		failed=$((failed + 1))
	elif [ -n "$bad" ]; then
		echo "not ok - $p links$bad: not among what it may link"
		failed=$((failed + 1))
	else
		passed=$((passed + 1))
	fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
