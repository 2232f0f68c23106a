#!/bin/bash
# The docs say what runs: README.md and docs/*.md, checked against the
# programs they describe (issue 26).
#
# The convention the docs follow (docs/ENGINEER.md, "Tests"): a fenced
# block tagged sh is run, one command a line (a line ending in \ goes on
# to the next; comments and blank lines skipped), in order, file by file
# (README.md first, then docs/ by name), against one daemon on the
# simulated rig with the patient. Each command must exit 0, or N where
# its line ends in a comment "# exit N". The commands run in a scratch
# directory that has the source tree's config/ (--config
# config/endosimd.conf works there; what they write stays there), with
# endoctl, endosimd and endoview of $BUILD first on the PATH: endoctl
# finds the daemon through $ENDOSIM_SOCKET, endoview is given the
# daemon's shm name (and a virtual screen, only when a block runs it).
# A block tagged console or text is shown, not run (a real rig, root, a
# daemon of the reader's own, a long run, a listing), and counted; a
# fenced block with no tag or another one fails: a reader must be able to
# tell which is which. A command in an indented block fails too.
#
# The pictures: every image the docs show is in docs/, is kept by a named
# system test (`keep_picture FILE NAME` in tests/system/*.sh, NAME written
# out) and, where this build's run of that test kept it
# ($BUILD/pictures/NAME.png), that is a PNG of a plausible size; every
# picture in docs/ is shown somewhere. Links between the docs lead to a
# file that is there and, with a #fragment, to a heading it has. The
# README fits on two screens (under 120 lines) and keeps the two
# commands CI relies on.
. "$(dirname "$0")/../common.sh"

DOCS=("$TOP/README.md" "$TOP"/docs/*.md)
WORK=$TMP/work
BIN=$TMP/bin
mkdir -p "$WORK" "$BIN"
ln -s "$TOP/config" "$WORK/config"

# --- what the docs hold ----------------------------------------------------
# blocks FILE: one line per command of a fenced block, "LINE<TAB>TAG<TAB>
# COMMAND" (TAG sh, console or text; a text block's lines are not
# commands: one line for the block, COMMAND empty), and "LINE<TAB>bad<TAB>
# WHAT" for a fence without a known tag or a command in an indented block.
blocks() {
	awk '
	function flush() {
		if (cmd != "") { printf "%d\t%s\t%s\n", at, tag, cmd }
		cmd = ""
	}
	/^ *```/ {
		if (!inside) {
			inside = 1
			tag = $0
			sub(/^ *```/, "", tag)
			if (tag != "sh" && tag != "console" && tag != "text") {
				printf "%d\tbad\ta fence tagged \"%s\" (sh, console or text)\n", NR, tag
				tag = "text"
			}
			if (tag == "text") { printf "%d\ttext\t\n", NR }
		} else {
			flush()
			inside = 0
		}
		blank = 0
		next
	}
	inside && tag != "text" {
		line = $0
		if (cmd == "") {
			if (line ~ /^[ \t]*(#.*)?$/) { next }
			at = NR
		}
		if (line ~ /\\$/) {
			sub(/\\$/, "", line)
			cmd = cmd line " "
			next
		}
		cmd = cmd line
		flush()
		next
	}
	!inside && blank && /^    +(build\/)?endo(ctl|simd|view) / {
		printf "%d\tbad\ta command in an indented block: %s\n", NR, $0
	}
	{ blank = ($0 ~ /^$/) || (blank && /^    /) }
	' "$1"
}

# want CMD: the exit status CMD documents ("# exit N" at its end), else 0
want() {
	if [[ $1 =~ \#[[:space:]]*exit[[:space:]]+([0-9]+) ]]; then
		echo "${BASH_REMATCH[1]}"
	else
		echo 0
	fi
}

: >"$TMP/all"
for f in "${DOCS[@]}"; do
	blocks "$f" | sed "s|^|${f#"$TOP"/}:|" >>"$TMP/all"
done
RUN=$(grep -c $'\tsh\t' "$TMP/all")
SHOWN=$(grep -c $'\tconsole\t' "$TMP/all")
LISTINGS=$(grep -c $'\ttext\t' "$TMP/all")
while IFS=$'\t' read -r where _ what; do
	fail "$where: $what"
done < <(grep $'\tbad\t' "$TMP/all")
check "the docs have commands to run ($RUN) and to show ($SHOWN)" \
	test "$RUN" -gt 20 -a "$SHOWN" -gt 5

# --- the commands ------------------------------------------------------------
for p in endoctl endosimd; do
	ln -s "$BUILD/$p" "$BIN/$p"
done
printf '#!/bin/sh\nexec "%s" --shm-name "%s" --no-vsync "$@"\n' \
	"$BUILD/endoview" "$SHM" >"$BIN/endoview"
chmod +x "$BIN/endoview"
if grep $'\tsh\t' "$TMP/all" | cut -f3 | grep -qw endoview; then
	. "$TOP/tests/viewer_lib.sh"
	start_xvfb || fail "a virtual screen for endoview"
fi
start_daemon --set patient.enabled=yes || finish

# run CMD: CMD in the scratch directory, the docs' environment
run() {
	(cd "$WORK" && PATH="$BIN:$PATH" ENDOSIM_SOCKET="$SOCK" \
		timeout 30 bash -c "$1")
}
while IFS=$'\t' read -r where _ cmd; do
	check_status "$where: $cmd" "$(want "$cmd")" run "$cmd"
done < <(grep $'\tsh\t' "$TMP/all")
echo "# $RUN commands run, $SHOWN shown (console), $LISTINGS listings (text)"

# --- the pictures ------------------------------------------------------------
# (few processes a picture or a link: a shared VM forks slowly)
# KEPT[NAME]: the system test that keeps the picture NAME
declare -A KEPT
while read -r name test; do
	KEPT[$name]=$test
done < <(grep -o 'keep_picture "[^"]*" [a-z0-9-]*' "$TOP"/tests/system/*.sh |
	sed 's|^.*/\([^/]*\)\.sh:keep_picture "[^"]*" \(.*\)|\2 \1|')
# normal PATH: PATH without its "dir/../" and "./" parts
normal() {
	local p=$1
	p=${p//\/.\//\/}
	while [[ $p =~ ^(.*)/[^/.][^/]*/\.\./(.*)$ ]]; do
		p=${BASH_REMATCH[1]}/${BASH_REMATCH[2]}
	done
	echo "$p"
}
# png_size FILE: "WIDTH HEIGHT" of a PNG (its signature and IHDR), else
# nothing
png_size() {
	local b
	read -r -a b < <(od -An -tu1 -N24 -w24 "$1")
	[ "${#b[@]}" = 24 ] &&
		[ "${b[*]:0:8}" = "137 80 78 71 13 10 26 10" ] &&
		[ "${b[*]:12:4}" = "73 72 68 82" ] &&
		echo $(((b[16] << 24) + (b[17] << 16) + (b[18] << 8) + b[19])) \
			$(((b[20] << 24) + (b[21] << 16) + (b[22] << 8) + b[23]))
}
# plausible FILE: a PNG from 200x100 to 4000x4000 pixels, over 5 kB
plausible() {
	local w h
	read -r w h < <(png_size "$1")
	[ -n "${w:-}" ] && [ "$w" -ge 200 ] && [ "$w" -le 4000 ] &&
		[ "$h" -ge 100 ] && [ "$h" -le 4000 ] &&
		[ "$(stat -c %s "$1")" -gt 5000 ]
}
# the docs' images and links: "FILE image|link TARGET" a line
awk '/^ *```/ { code = !code } !code {
	line = $0
	while (match(line, /!?\[[^]]*\]\([^) ]*\)/)) {
		m = substr(line, RSTART, RLENGTH)
		line = substr(line, RSTART + RLENGTH)
		kind = m ~ /^!/ ? "image" : "link"
		sub(/^.*\]\(/, "", m)
		sub(/\)$/, "", m)
		print FILENAME, kind, m
	}
}' "${DOCS[@]}" >"$TMP/refs"
declare -A SHOWN
while read -r f kind ref; do
	[ "$kind" = image ] || continue
	img=$(normal "${f%/*}/$ref")
	SHOWN[$img]=1
	name=${img##*/}
	name=${name%.png}
	test=${KEPT[$name]:-}
	check "${f#"$TOP"/} shows ${img#"$TOP"/}: in the tree" test -s "$img"
	check "${f#"$TOP"/} shows $name.png: kept by a test (${test:-none})" \
		test -n "$test"
	if [ -e "$BUILD/pictures/$name.png" ]; then
		check "$name.png as $test kept it: a PNG of a plausible size ($(png_size "$BUILD/pictures/$name.png"))" \
			plausible "$BUILD/pictures/$name.png"
	fi
done <"$TMP/refs"
for img in "$TOP"/docs/*.png; do
	check "${img#"$TOP"/} is shown in the docs" test -n "${SHOWN[$img]:-}"
done

# --- the links between the docs -----------------------------------------------
# ANCHOR[FILE#FRAGMENT]: a heading of a doc, as GitHub makes its fragment
declare -A ANCHOR
while read -r f frag; do
	ANCHOR[$f#$frag]=1
done < <(awk '/^ *```/ { code = !code }
	!code && /^#+ / { h = tolower($0); sub(/^#+ /, "", h)
		gsub(/[^a-z0-9 _-]/, "", h); gsub(/ /, "-", h)
		print FILENAME, h }' "${DOCS[@]}" "$TOP/tests/README.md")
broken=()
while read -r f kind ref; do
	[ "$kind" = link ] || continue
	case $ref in http:* | https:* | mailto:*) continue ;; esac
	file=${ref%%#*}
	frag=${ref#"$file"}
	target=$f
	[ -z "$file" ] || target=$(normal "${f%/*}/$file")
	if [ ! -e "$target" ]; then
		broken+=("${f#"$TOP"/}: $ref: no such file")
	elif [ -n "$frag" ] && [ -z "${ANCHOR[$target$frag]:-}" ]; then
		broken+=("${f#"$TOP"/}: $ref: no such heading")
	fi
done <"$TMP/refs"
check "every link between the docs leads somewhere (${#broken[@]} broken)" \
	test "${#broken[@]}" = 0
[ "${#broken[@]}" = 0 ] || printf '#   %s\n' "${broken[@]}"

# --- the README ----------------------------------------------------------------
lines=$(wc -l <"$TOP/README.md")
check "README.md fits on two screens ($lines lines, under 120)" \
	test "$lines" -lt 120
check "README.md keeps the two commands (make demo, make test)" eval \
	'grep -q "^make demo " "$TOP/README.md" &&
	 grep -q "^make test " "$TOP/README.md"'
finish
