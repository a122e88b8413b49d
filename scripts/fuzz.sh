#!/usr/bin/env bash
# Fuzzes the parsers: scripts/fuzz.sh [SECONDS [TARGET...]]
#
# Installs what it needs (cargo-fuzz, a nightly toolchain, the Python writers
# of the seed files), writes seeds into fuzz/corpus/ (scripts/fuzz_seeds.py),
# then runs each target (default: all) for SECONDS (default 300) under
# AddressSanitizer with a 2 GiB memory limit, optimised but with overflow
# checks and debug assertions on (`-O -a`: `-O` alone turns them off, and the
# fuzzers then missed an arithmetic overflow and the PDF layout's own checks,
# which a damaged plan.json and chart.json set off). It stops at the first crash,
# out-of-memory or timeout; the input that caused it is in
# fuzz/artifacts/<target>/, and `cargo +nightly fuzz run <target> <file>`
# replays it. Not part of CI (nightly, and minutes per target); CI's clippy
# checks that the targets build (fuzz/ is a workspace member).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(rvm att plant_mesh scan_file chart_workbook crane_and_lift_toml project_toml artifacts registration_memo kept_plans capacity_csv plan_document site_cloud chart_json plant_json stage_records)
fi
rustup toolchain list | grep -q '^nightly' || rustup toolchain install nightly --profile minimal
command -v cargo-fuzz > /dev/null || cargo install cargo-fuzz --locked
python3 -m pip install --quiet laspy lazrs pye57 openpyxl odfpy numpy
python3 scripts/fuzz_seeds.py fuzz/corpus
for t in "${targets[@]}"; do
  echo "== fuzzing $t for ${seconds} s"
  cargo +nightly fuzz run -O -a "$t" -- -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=20
done
