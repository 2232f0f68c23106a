#!/bin/bash
# viewer_ab.sh ENDOVIEW... - two or more endoview binaries compared on one
# daemon (figures, not verdicts): the daemon on the simulated rig holds
# the scope 60 cm in, and each binary draws its frames in turn, ROUNDS
# times, so that a shared machine's drift falls on every binary alike.
# Build the one to compare with in a worktree of the older commit:
#
#   git worktree add /tmp/old HEAD~1 && make -C /tmp/old build/endoview
#   tests/bench/viewer_ab.sh /tmp/old/build/endoview build/endoview
#
# Prints each run's frame time (p50, p99 ms) and triangles drawn.
#
#   AB_ROUNDS   rounds (default 3)
#   AB_FRAMES   frames a run (default 300)
#   AB_VIEW     view (default endo)
#   AB_SIZE     window (default 1280x720)
#   AB_DAEMON   the daemon's extra arguments, e.g. the 2 million
#               triangles: "--set case.ring_vertices=672
#               --set case.step_m=0.001"
#   AB_VIEWER   endoview's extra arguments, e.g. --pass-times
set -u
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

if [ $# -lt 1 ]; then
	sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'
	exit 2
fi
for b in "$@"; do
	[ -x "$b" ] || { echo "$b: not an executable" >&2; exit 2; }
done
start_xvfb 1920x1080 || exit 1
# shellcheck disable=SC2086 # word splitting intended
hold_scope "$HOLD_AT" ${AB_DAEMON:-} || exit 1
echo "colon: $(ctl --json scene info 2>/dev/null | jq -r .triangles) triangles"
for r in $(seq "${AB_ROUNDS:-3}"); do
	for b in "$@"; do
		ENDOVIEW=$b
		# shellcheck disable=SC2086
		if ! view --view "${AB_VIEW:-endo}" --size "${AB_SIZE:-1280x720}" \
			--frames "${AB_FRAMES:-300}" ${AB_VIEWER:-}; then
			echo "$b: endoview failed:"
			sed 's/^/    /' "$VIEW_OUT"
			continue
		fi
		printf 'round %d  %-40s p50 %6.2f  p99 %6.2f  triangles %s\n' \
			"$r" "$b" "$(view_field frame_ms_p50)" \
			"$(view_field frame_ms_p99)" "$(view_field triangles)"
		sed -n 's/^endoview: passes_ms /    /p' "$VIEW_OUT"
	done
done
stop_daemon
