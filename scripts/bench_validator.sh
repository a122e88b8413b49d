#!/usr/bin/env bash
# Validator report: what confirming the clearance between the validator's
# samples costs and finds on the planner benchmark's plants (`liftplan bench
# --validator-runs`, about 20 s on 2 cores), followed by the reading of the
# numbers in scripts/validator-notes.md as it stands:
#   scripts/bench_validator.sh [RUNS] > reports/validator.md
set -euo pipefail
runs=${1:-10}
cargo build --release -q
echo "# Validator"
target/release/liftplan -q bench --runs 0 --grid-runs 0 --t414-runs 0 --demo-seeds 0 --validator-runs "$runs" 2>/dev/null
echo
cat "$(dirname "$0")/validator-notes.md"
