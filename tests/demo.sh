#!/bin/bash
# demo.sh - `make demo`: endosimd on the simulated rig with the shipped demo
# scenario (the simulated hand inserts, twists, steers and withdraws), a live
# status line while it runs, and a summary at the end. With a display, the
# viewer (endoview) opens beside it and the demo lasts until its window is
# closed: its keys take the simulated hand over from the scenario. Without
# one, the viewer draws on a virtual screen (Xvfb) and leaves two
# screenshots, mid-way and at the deepest. The run is recorded as a
# training session: its metrics and the instructor's report
# ($BUILD/demo-report/index.html) come at the end, and
# `endoview --replay` plays it again.
#
# The machine is taken for a development machine, not a rig: every axis
# simulated, a missed overrun budget a warning ([loop] overrun_fault = no;
# the budget stays the rig's), the viewer below the daemon (nice) and at
# most $DEMO_FPS frames a second, so that a VM or a viewer drawing in
# software beside the loop does not end the demo in FAULT. The summary says
# what the loop met: the overruns, against what a rig allows.
set -u
. "$(dirname "$0")/common.sh"
. "$TOP/tests/viewer_lib.sh"

# a display the viewer can open
has_display() {
	[ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] &&
		endoview --view empty --size 160x120 --frames 1 >/dev/null 2>&1
}

# shot SECONDS FILE: a screenshot of both views SECONDS into the scenario.
shot() {
	below_loop
	sleep "$1"
	view --view both --frames 30 --max-fps "$DEMO_FPS" --screenshot "$2" &&
		echo "  screenshot: $2"
}

# real_time TRACE: what the force loop met, from the trace of the run
# (`endoctl --json watch`): the periods it skipped, the worst second, how
# long it was over the budget, against what a rig allows
real_time() {
	local budget window
	budget=$(ctl get loop.overrun_budget)
	window=$(ctl get loop.overrun_window_s)
	ctl --json status | jq -r '"state \(.state), " +
	  (if .fault_bits == 0 then "no FAULT" else "FAULT: \(.fault)" end) +
	  "; the force loop ran \(.rt_policy) at \(.loop_hz * 10 | round / 10) Hz"'
	jq -rs --argjson budget "$budget" --arg window "$window" '
	  (.[-1].overruns - .[0].overruns) as $n |
	  ((.[-1].stamp_ns - .[0].stamp_ns) / 1e9) as $secs |
	  ([range(1; length) as $i |
	    { s: ((.[$i].stamp_ns - .[0].stamp_ns) / 1e9 | floor),
	      n: (.[$i].overruns - .[$i - 1].overruns) }] |
	   group_by(.s) | map(map(.n) | add) | max // 0) as $worst |
	  (map(select((.active_faults / 16 | floor) % 2 == 1)) | length) as $over |
	  "overruns: \($n) periods skipped in \($secs | round) s " +
	  "(\($n / ($secs * 10) | . * 1000 | round / 1000) % of the periods), " +
	  "\($worst) in the worst second; over the budget (\($budget) in " +
	  "\($window) s) \($over * 100 / length | round) % of the time: " +
	  (if $over > 0 or $worst > $budget
	   then "on a rig with real drives, a FAULT"
	   else "within a rig'"'"'s budget" end)
	' "$1"
	echo "this machine ran as a development machine: [loop] overrun_fault = no,"
	echo "  a missed budget a warning in the journal. A rig keeps the default,"
	echo "  auto (with real drives a missed budget is a FAULT, torque off), and"
	echo "  needs what keeps its loop within $budget periods in $window s:"
	echo "  isolated CPUs (isolcpus=, nohz_full=, [loop] cpu), a PREEMPT_RT"
	echo "  kernel, SCHED_FIFO (root or CAP_SYS_NICE) and the viewer on other"
	echo "  CPUs; \`endoctl stats\` shows its latency"
}

DEMO_FPS=30

# below_loop: this (sub)shell and what it starts run at nice 10, below the
# daemon, whose force loop a viewer drawing in software must not starve
below_loop() {
	renice -n 10 -p "$BASHPID" >/dev/null
}

SCENARIO="$TOP/config/scenarios/demo.scn"
LENGTH=$(awk '$2 == "end" || $2 == "repeat" { print $1 }' "$SCENARIO")
: "${LENGTH:=90}"

echo "endosim demo: endosimd on the simulated rig, scenario $(basename "$SCENARIO") (${LENGTH} s)"
SESSIONS="$BUILD/demo-sessions"
# the demo is the trainee's course with the patient (scenario_gen's):
# played so, it goes as she played it
start_daemon --scenario "$SCENARIO" --session-dir "$SESSIONS" \
	--set rig.backend=sim --set loop.overrun_fault=no \
	--set patient.enabled=yes || exit 1
echo "daemon pid $DAEMON_PID, sockets in $SOCK, shared memory $SHM"
echo "  in another terminal: $ENDOCTL --socket $SOCK status"
ctl enable
ctl session start --trainee "demo (the scripted hand)"
viewer=""
shots=""
if has_display; then
	(below_loop && endoview --socket "$SOCK" --shm-name "$SHM" \
		--view both --max-fps "$DEMO_FPS" >"$TMP/endoview.log" 2>&1) &
	viewer=$!
	echo "endoview is open (pid $viewer): the scenario drives the"
	echo "  simulated hand; take over with its keys (Up/Down insert,"
	echo "  Left/Right twist, I/K J/L steer, E enable, Space stop, R reset,"
	echo "  V view, H help); close its window or press Q to end the demo"
elif start_xvfb; then
	echo "no display: endoview draws on a virtual screen"
	shot 9 "$BUILD/demo-1.png" &
	shots="$!"
	shot 16 "$BUILD/demo-2.png" &
	shots="$shots $!"
else
	echo "no display and no Xvfb: the daemon alone"
fi
ctl --json watch --rate 50 --duration "$LENGTH" >"$TMP/trace.json" &
tracer=$!
if [ -t 1 ]; then rate=10; else rate=1; fi
ctl watch --rate $rate --duration "$LENGTH"
wait "$tracer"
if [ -n "$viewer" ]; then
	echo "the scenario is over: the hand is yours until the viewer closes"
	wait "$viewer"
fi
for pid in $shots; do
	wait "$pid"
done

echo
# what the model in use computed: the paper's (the tip's wall force, the
# friction, the mesentery's pull) or the rod's (the wall along the tube,
# the tube's reaction at the carriage, how far the mobile colon moved)
echo "=== summary ==="
ctl status | sed -n '1,4p'
ctl stats
jq -rs '
  def peak(f): map(f | fabs) | max;
  "peak |force| sent to the drives: insertion \(peak(.axes.insertion.limited) * 100 | round / 100) N, " +
  "roll \(peak(.axes.roll.limited) * 1000 | round / 1000) N m, " +
  "wheels \(peak(.axes.wheel_ud.limited) * 1000 | round / 1000) / \(peak(.axes.wheel_lr.limited) * 1000 | round / 1000) N m",
  "deepest insertion: \(map(.axes.insertion.position) | max * 1000 | round / 1000) m; " +
  "largest roll: \(peak(.axes.roll.position) * 100 | round / 100) rad; " +
  "largest tip steer: up/down \(peak(.axes.wheel_ud.position) * 100 | round / 100) rad, left/right \(peak(.axes.wheel_lr.position) * 100 | round / 100) rad",
  "the tip reached \(map(.scope.tip_s_m) | max * 100 | round / 100) m along the colon (case \(.[0].case)); " +
  "in contact with the wall \((map(select(.haptics.contact)) | length) * 100 / length | round) % of the time",
  if .[0].rod.model == "rod" then
    "the rod model: largest wall force on the tube \(map(.rod.wall_n) | max * 10 | round / 10) N " +
    "(at most \(map(.rod.contacts) | max) contacts, friction \(map(.rod.friction_n) | max * 10 | round / 10) N), " +
    "on the tip \(map(.haptics.f_static | map(. * .) | add | sqrt) | max * 10 | round / 10) N; " +
    "largest insertion reaction \(peak(.haptics.trans_rod_n) * 10 | round / 10) N at \(map(.haptics.curvature_rad) | max * 10 | round / 10) rad of turning; " +
    "largest loop \(map(.scope.bow_m | max) | max * 1000 | round) mm (the mobile colon moved)"
  else
  "largest wall force \(map(.haptics.f_static | map(. * .) | add | sqrt) | max * 10 | round / 10) N; " +
  "largest insertion friction \(peak(.haptics.trans_friction_n) * 10 | round / 10) N at \(map(.haptics.curvature_rad) | max * 10 | round / 10) rad of turning; " +
  "largest loop \(map(.scope.bow_m | max) | max * 1000 | round) mm, its force \(peak(.haptics.trans_loop_n) * 10 | round / 10) N"
  end,
  "states seen: \(map(.state) | unique | join(", ")); faults: \(map(.fault_bits) | max)"
' "$TMP/trace.json"

echo
echo "=== real time ==="
real_time "$TMP/trace.json"

echo
echo "=== the training session ==="
ctl session stop
id=$(ctl --json session list | jq -r '.sessions | max_by(.id) | .id')
file=$(ctl --json session show "$id" | jq -r '.path')
ctl session report "$id" --out "$BUILD/demo-report" &&
	echo "the instructor's report: $BUILD/demo-report/index.html"
echo "replay it: $BUILD/endoview --replay $file"
if stop_daemon; then
	echo "endosimd stopped cleanly (torque off, exit 0)"
else
	echo "endosimd exited with an error; its log:"
	cat "$LOG"
	exit 1
fi
