#!/usr/bin/env bash
# Times `liftplan watch` from the moment N scans have been copied into a
# project's scans/ folder (all at once, as a survey team's drop) to the moment
# the watcher has checked them and starts its run ("changed: ..." in
# watch.log), for each liftplan binary given, one after the other in one run.
#
#   scripts/bench_watch_drop.sh N BINARY...
#
# The project waits 200 ms of quiet after the last change (settle_ms); the
# rest of the time is the watcher's check that each file is complete.
set -euo pipefail
n=$1
shift
here=$(cd "$(dirname "$0")/.." && pwd)
scan="$here/fixtures/scans/gps-switches-1.laz"
echo "| binary | scans dropped | drop to run start s |"
echo "|---|---|---|"
for bin in "$@"; do
    t=$(mktemp -d)
    "$bin" init "$t/w" >/dev/null
    sed -i 's/^settle_ms = 1000/settle_ms = 200/; s/^parse_wait_s = 10/parse_wait_s = 600/; s/^register = "auto"/register = "none"/' "$t/w/liftplan.toml"
    mkdir -p "$t/stage"
    for i in $(seq 1 "$n"); do cp "$scan" "$t/stage/s$i.laz"; done
    "$bin" watch "$t/w" -q 2>"$t/watch.err" &
    pid=$!
    log="$t/w/.liftplan/log/watch.log"
    until grep -qE "run (ok|failed)" "$log" 2>/dev/null; do sleep 0.05; done
    cp "$t"/stage/*.laz "$t/w/scans/"
    start=$(date +%s.%N)
    until grep -q "changed:" "$log" 2>/dev/null; do sleep 0.02; done
    end=$(date +%s.%N)
    kill "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    echo "| $bin | $n | $(echo "$end - $start" | bc -l | xargs printf '%.2f') |"
    rm -rf "$t"
done
