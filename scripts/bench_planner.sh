#!/usr/bin/env bash
# Planner report: the thesis' Tables 4.11/4.12, 4.15/4.16 and 4.14 on
# thesis-like plants, then MSPGA against the baselines and the C-space
# strategies on the demo lift, all in one run on this machine:
#   scripts/bench_planner.sh [RUNS] [GRID_RUNS] [T414_RUNS] > reports/planner.md
# Defaults 50 10 3 (about an hour on 2 cores); the reading of the numbers in
# scripts/planner-notes.md is appended as it stands.
set -euo pipefail
runs=${1:-50}; grid=${2:-10}; t414=${3:-3}
cargo build --release -q -p liftplan-plan --example bench_thesis --example bench_planners
cargo build --release -q
demo=$(mktemp -d)
trap 'rm -rf "$demo"' EXIT
target/release/liftplan demo "$demo/demo" -q >/dev/null
target/release/examples/bench_thesis "$runs" "$grid" 2>/dev/null
echo
target/release/examples/bench_thesis 0 0 "t414=$t414" 2>/dev/null
echo
cat "$(dirname "$0")/planner-notes.md"
echo
target/release/examples/bench_planners "$demo/demo" 3 2>/dev/null \
  | sed -e 's/^# Planner benchmark/## Demo lift: MSPGA and the baselines/' -e 's/^# C-space strategies/## Demo lift: C-space strategies/'
