#!/usr/bin/env bash
# Planner report: `liftplan bench` (the thesis' Tables 4.11-4.18 on
# thesis-like plants, then MSPGA against the baselines and the C-space
# strategies on the demo lift, all in one run on this machine), followed by
# the reading of the numbers in scripts/planner-notes.md as it stands:
#   scripts/bench_planner.sh [RUNS] [GRID_RUNS] [T414_RUNS] [DEMO_SEEDS] > reports/planner.md
# Defaults 50 50 3 3: about 40 minutes on 2 cores.
set -euo pipefail
runs=${1:-50}; grid=${2:-50}; t414=${3:-3}; seeds=${4:-3}
cargo build --release -q
target/release/liftplan -q bench --runs "$runs" --grid-runs "$grid" --t414-runs "$t414" --demo-seeds "$seeds" 2>/dev/null
echo
cat "$(dirname "$0")/planner-notes.md"
