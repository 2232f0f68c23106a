#!/bin/bash
# Subscriptions push status at the requested rate until the client leaves;
# other clients are served meanwhile.
. "$(dirname "$0")/../common.sh"

start_daemon || finish
ctl --json watch --rate 50 --duration 1.5 >"$TMP/watch.json" &
watcher=$!
sleep 0.3
check "another client is served meanwhile" ctl status
wait $watcher
n=$(wc -l <"$TMP/watch.json")
check "pushes arrive ($n at 50 Hz in 1.5 s)" test "$n" -ge 20
check "each push is a status object" test "$(jq -s 'map(has("cycle")) | all' "$TMP/watch.json")" = true
check "cycles advance from push to push" test "$(jq -s '[.[].cycle] | . == sort' "$TMP/watch.json")" = true
check_status "a rate above 1000 Hz is refused" 1 ctl watch --rate 5000
check "the daemon goes on after the watcher left" ctl status
finish
