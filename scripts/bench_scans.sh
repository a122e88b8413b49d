#!/usr/bin/env bash
# Scans-stage benchmark: liftplan beside Open3D and laspy (and PDAL when a `pdal`
# binary is on PATH), in one run, on the same generated files. Numbers for
# reports/scans.md. Takes ~10 minutes and ~12 GB of memory (Open3D holds the
# 100 M point set in memory; liftplan streams it) on a 2-core machine.
#
#   scripts/bench_scans.sh [WORKDIR]      (default target/bench-scans)
#
# Writes WORKDIR/results.jsonl (one JSON object per measurement) and
# WORKDIR/summary.md (the tables).
set -euo pipefail
cd "$(dirname "$0")/.."
W=${1:-target/bench-scans}
mkdir -p "$W"
PEERS=scripts/bench_scans_peers.py

# Peers. Open3D's wheel needs libusb and libgomp at import time.
if ! python3 -c "import open3d, laspy, lazrs" 2>/dev/null; then
  if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
    apt-get install -y -qq --no-install-recommends libusb-1.0-0 libgomp1 >/dev/null || true
  fi
  python3 -m pip install -q open3d laspy lazrs
fi
python3 -c "import open3d, laspy, lazrs"

cargo build --release -q -p liftplan --bin liftplan
cargo build --release -q -p liftplan-fixtures --example bench_scans
B=target/release/examples/bench_scans
LP=target/release/liftplan

[ -f "$W/site_20M.laz" ] || $B generate "$W" --points 20000000 >/dev/null
[ -f "$W/site_100M_stacked.laz" ] || $B generate "$W" --points 100000000 --stacked >/dev/null
$B generate "$W" --points 1000 >/dev/null   # refreshes the ICP pair and icp.json only

R="$W/results.jsonl"
: >"$R"
echo "decode"
$B decode "$W/site_20M.laz" >>"$R"
python3 $PEERS decode "$W/site_20M.laz" >>"$R"
echo "voxel"
$B voxel "$W/site_20M.laz" 0.05 >>"$R"
python3 $PEERS voxel "$W/site_20M.laz" 0.05 >>"$R"
$B voxel "$W/site_100M_stacked.laz" 0.05 >>"$R"
echo "icp"
$B icp "$W" >>"$R"
python3 $PEERS icp "$W" >>"$R"

if command -v pdal >/dev/null 2>&1; then
  echo "pdal"
  python3 $PEERS pdal "$W/site_20M.laz" 0.05 >>"$R"
else
  echo "pdal: no pdal binary on PATH (Debian bookworm, trixie and sid and PyPI had none when this was written); skipped"
fi

echo "peak memory, 100 M points thinned at 0.05 m (whole stage / decode + voxel in memory)"
mem() { # label, command...
  local label=$1
  shift
  /usr/bin/time -f "%M %e" -o "$W/time.txt" "$@" >/dev/null
  read -r kb secs <"$W/time.txt"
  printf '{"tool": "%s", "op": "memory_100M", "peak_rss_mb": %s, "seconds": %s}\n' "$label" "$((kb / 1024))" "$secs" >>"$R"
}
mem "liftplan scans (stream, voxel, ground, write)" \
  $LP scans "$W/site_100M_stacked.laz" -o "$W/thin_100M.laz" --voxel 0.05 --register none -q
mem "laspy read + Open3D voxel_down_sample" python3 $PEERS voxel "$W/site_100M_stacked.laz" 0.05

python3 $PEERS summary "$R" | tee "$W/summary.md"
