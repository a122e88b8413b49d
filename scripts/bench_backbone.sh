#!/usr/bin/env bash
# Backbone benchmark: no-op rerun time on a demo project, and content hashing
# (a rerun after touching every input, so every file is re-hashed) against
# reading the same bytes with `cat > /dev/null`, in the same run.
#   scripts/bench_backbone.sh DEMO_DIR > reports/backbone.md
set -euo pipefail
dir=${1:?usage: bench_backbone.sh DEMO_DIR}
bin=${LIFTPLAN_BIN:-target/release/liftplan}
"$bin" run "$dir" -q >/dev/null
ms() { python3 -c 'import sys,time,subprocess; t=time.perf_counter(); subprocess.run(sys.argv[1:],check=True,stdout=subprocess.DEVNULL,stderr=subprocess.DEVNULL); print("%.1f"%((time.perf_counter()-t)*1000))' "$@"; }
noop=(); for i in 1 2 3 4 5 6 7 8 9; do noop+=("$(ms "$bin" run "$dir" -q)"); done
files=$(find "$dir/scans" "$dir/plant" "$dir/charts" -type f | sort)
bytes=$(cat $files | wc -c)
hash=(); catt=()
for i in 1 2 3 4 5; do
  touch $files
  hash+=("$(ms "$bin" run "$dir" -q)")
  catt+=("$(ms sh -c "cat $(echo $files) > /dev/null")")
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
n=$(median "${noop[@]}"); h=$(median "${hash[@]}"); c=$(median "${catt[@]}")
echo "# Backbone benchmark"
echo
echo "Demo project \`$dir\` ($(echo $files | wc -w) input files, $bytes bytes); medians; $(nproc) cores."
echo
echo "| measurement | ms | note |"
echo "|---|---|---|"
echo "| no-op rerun (every stage fresh) | $n | goal under 50 ms |"
echo "| rerun after touching every input (all re-hashed, still fresh) | $h | includes process start and the no-op work |"
echo "| \`cat\` of the same files to /dev/null | $c | reading floor |"
echo "| ratio re-hash rerun / cat | $(python3 -c "print('%.2f' % ($h/$c))") | |"
echo
echo "Command: \`scripts/bench_backbone.sh $dir\`"
