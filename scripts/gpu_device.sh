#!/usr/bin/env bash
# The GPU twin tests and the GPU benchmarks on a machine with a GPU, in one
# call of the device tool (which has no network and no cargo), from binaries
# built here.
#
#   scripts/gpu_device.sh prepare
#       Here: builds the release binaries (liftplan; the GPU twin tests of
#       core, depthmap, cspace and docs; bench_depthmap; bench_cspace;
#       stress_gpu) into .devbin/, stripped and packed, and fetches the
#       Vulkan loader's packages into .gl/ (both ignored by git).
#
#   scripts/gpu_device.sh run [soak-seconds]
#       There, from the repository root, with `.devbin` and `.gl` carried:
#       unpacks the loader, says which GPU is there, runs the twin tests, the
#       demo project end to end twice (`[gpu] use = "never"` and "require")
#       and compares their depth maps and plans byte for byte, then
#       `bench_depthmap` (maps), `bench_depthmap queries` and `bench_cspace
#       hybrid`, then the soak test for soak-seconds (default 120). Logs and
#       the three reports go to $OUT (./gpu-out where OUT is unset); the
#       reports' tables take the place of those in reports/depthmap.md,
#       reports/queries.md and reports/cspace.md.
#       The GPU run's PDF comes back too. Exits non-zero if a test fails,
#       the two demo runs differ, or the soak finds a difference.
#
#   scripts/gpu_device.sh repeat
#       There: `bench_depthmap repeat` at 21 M points with the GPU's clocks
#       sampled beside it (clocks.csv), for the run-to-run spread.
#
# The device tool's call. Run on 2026-12-04 on an H200: 133-163 s there with
# a soak of 30-60 s, and about 35 s to start the machine (reports/depthmap.md).
# .devbin holds the binaries stripped and packed with xz, small enough for
# the 64 MiB the working tree and carried paths may take; the 8 files written
# to $OUT are the most that come back:
#   run(command="scripts/gpu_device.sh run 45", carry=[".devbin", ".gl"], timeout_s=300)
set -euo pipefail
cd "$(dirname "$0")/.."

prepare() {
    local bins=.devbin
    rm -rf "$bins"
    mkdir -p "$bins"
    # Test executables are named by cargo's JSON messages, not guessable paths.
    local built
    built=$(cargo test --release --no-run --message-format=json \
        -p liftplan-core --test gpu_errors \
        -p liftplan-depthmap --test gpu_twin \
        -p liftplan-cspace --test gpu_twin \
        -p liftplan-docs --test gpu_twin |
        python3 -c '
import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["target"]["kind"] == ["test"]:
        pkg = m["package_id"].split("#")[-1].split("@")[0].split("/")[-1]
        print(pkg, m["target"]["name"], m["executable"])
')
    while read -r pkg name exe; do
        cp "$exe" "$bins/test-$pkg-$name"
    done <<<"$built"
    cargo build --release -p liftplan-depthmap --example bench_depthmap --example stress_gpu
    cargo build --release -p liftplan-cspace --example bench_cspace
    cargo build --release -p liftplan
    cp target/release/examples/{bench_depthmap,stress_gpu,bench_cspace} target/release/liftplan "$bins/"
    strip "$bins"/*
    ls -l "$bins"
    # Packed: the binaries share most of their code (wgpu, naga), which xz finds.
    local packed
    packed=$(mktemp)
    tar -C "$bins" -cJf "$packed" .
    rm -rf "${bins:?}"/*
    mv "$packed" "$bins/bins.tar.xz"
    chmod 644 "$bins/bins.tar.xz"
    du -sh "$bins"

    mkdir -p .gl /tmp/amd64/partial
    local o=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64)
    apt-get "${o[@]}" update >/dev/null
    (cd .gl && apt-get "${o[@]}" download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
    ls .gl
}

# There: the binaries unpacked into $bin and the Vulkan loader installed.
unpack() {
    [[ -f .devbin/bins.tar.xz ]] || { echo "no .devbin: run 'scripts/gpu_device.sh prepare' here and carry .devbin and .gl" >&2; exit 2; }
    # Unpacked outside .devbin, which stays small enough to carry again.
    bin=$(mktemp -d)
    tar -C "$bin" -xJf .devbin/bins.tar.xz
    if ! ldconfig -p | grep -q libvulkan; then
        for f in .gl/*.deb; do dpkg -x "$f" /; done
        ldconfig
    fi
    local icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
    [[ -f $icd ]] && export VK_DRIVER_FILES=$icd
    # Vulkan only: OpenGL through NVIDIA's EGL, where its vendor file is
    # named, offers an adapter there whose device does not open ("Parent
    # device is lost", 2026-12-04, an H200), which fails every twin test;
    # liftplan itself takes the Vulkan adapter there either way.
    export WGPU_BACKEND=vulkan
}

# There: `bench_depthmap repeat` at 21 M points (each cloud's GPU build eight
# times back to back) with the GPU's clocks sampled every 50 ms beside it.
repeat() {
    local bin out=${OUT:-gpu-out}
    mkdir -p "$out"
    unpack
    nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,utilization.gpu,power.draw --format=csv -lms 50 >"$out/clocks.csv" 2>&1 &
    local smi=$!
    timeout 200 "$bin"/bench_depthmap repeat 21000716 >"$out/repeat.md" 2>"$out/repeat.log" || echo "bench_depthmap repeat failed (exit $?)"
    kill "$smi" || true
    cat "$out/repeat.md"
    awk -F', ' 'NR > 1 { n[$2]++ } END { for (c in n) print c, n[c] }' "$out/clocks.csv" | sort -n | tail -n 12
}

run() {
    local soak=${1:-120} bin
    local out=${OUT:-gpu-out}
    mkdir -p "$out"
    unpack
    # The GPU's name heads the test log (8 files are all that come back).
    if command -v nvidia-smi >/dev/null; then
        nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv >"$out/tests.log" 2>&1 || true
    else
        echo "no nvidia-smi" >"$out/tests.log"
    fi
    cat "$out/tests.log"

    # Each step has its own limit, so that one hung on the device leaves the
    # others their time; the benchmarks come first, being what only this
    # machine can measure. Each step's wall time goes to bench_depthmap.log.
    local failed=0 t0
    step() {
        local limit=$1 what=$2
        shift 2
        echo "== $what"
        t0=$(date +%s.%N)
        # A shell function cannot run under timeout(1): its own commands have limits.
        if [[ $(type -t "$1") == function ]]; then
            "$@" || { echo "$what: failed"; failed=1; }
        else
            timeout "$limit" "$@" || { echo "$what: failed or over ${limit} s (exit $?)"; failed=1; }
        fi
        awk -v w="$what" -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "step %s: %.1f s\n", w, b - a }' | tee -a "$out/bench_depthmap.log"
    }
    run_twin_tests() {
        local t pkg
        for t in "$bin"/test-*; do
            # Tests run where cargo runs them: their package's directory.
            pkg=${t#"$bin"/test-liftplan-}
            pkg=${pkg%-gpu_*}
            echo "== $t"
            (cd "stages/$pkg" && timeout 120 "$t" --test-threads=1 --nocapture) >"$out/test.log" 2>&1 || failed=1
            grep -E "^test |test result|GPU twin test on|SKIPPED" "$out/test.log" | sort -u || true
            cat "$out/test.log" >>"$out/tests.log"
            rm "$out/test.log"
        done
    }
    step - "twin tests" run_twin_tests
    # The SM clock while the depth maps are built, as a count of samples per
    # clock (the driver lowers it when the device idles between bursts).
    local clocks
    clocks=$(mktemp)
    nvidia-smi --query-gpu=clocks.sm --format=csv,noheader -lms 50 >"$clocks" 2>/dev/null &
    local smi=$!
    step 150 "bench_depthmap" sh -c '"$0" >"$1/depthmap.md" 2>>"$1/bench_depthmap.log"' "$bin/bench_depthmap" "$out"
    kill "$smi" 2>/dev/null || true
    { echo "SM clock while bench_depthmap ran (samples every 50 ms):"; sort "$clocks" | uniq -c | sort -k2 -n; } >>"$out/bench_depthmap.log"
    step 100 "bench_cspace hybrid" sh -c '"$0" hybrid >"$1/cspace.md" 2>>"$1/bench_depthmap.log"' "$bin/bench_cspace" "$out"
    step 100 "bench_depthmap queries" sh -c '"$0" queries >"$1/queries.md" 2>>"$1/bench_depthmap.log"' "$bin/bench_depthmap" "$out"
    step - "demo, CPU and GPU" demo_twice "$out"
    step $((soak + 30)) "stress_gpu $soak" sh -c '"$0" "$1" >"$2/stress_gpu.log" 2>&1' "$bin/stress_gpu" "$soak" "$out"
    tail -n 1 "$out/stress_gpu.log" || true
    head -n 20 "$out/depthmap.md" "$out/queries.md" "$out/cspace.md" || true
    exit "$failed"
}

# The demo project run on the CPU and on the GPU (depth map and pictures):
# the depth map, the plan and its steps must be the same bytes (the pictures
# agree within a tolerance, which tests/gpu_twin.rs of the docs checks).
demo_twice() {
    local out=$1 d mode f t0 differ=0
    d=$(mktemp -d)
    timeout 60 "$bin"/liftplan -q demo "$d/base" >"$out/demo.log" 2>&1 || return 1
    for mode in never require; do
        cp -r "$d/base" "$d/$mode"
        printf '\n[gpu]\nuse = "%s"\n' "$mode" >>"$d/$mode/liftplan.toml"
        "$bin"/liftplan -q clean "$d/$mode" >>"$out/demo.log" 2>&1
        echo "== [gpu] use = \"$mode\"" >>"$out/demo.log"
        t0=$(date +%s.%N)
        timeout 90 "$bin"/liftplan run "$d/$mode" >>"$out/demo.log" 2>&1 || return 1
        awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "whole run: %.2f s\n", b - a }' >>"$out/demo.log"
    done
    cp "$d/require/out/V-101.pdf" "$out/V-101-gpu.pdf"
    # plan.json also records how long each part took: compared without those lines.
    for m in never require; do
        grep -vE '"[a-z_]*_ms":|"seconds":' "$d/$m/out/plan.json" >"$d/$m/out/plan-untimed.json"
    done
    for f in site.mdm plan-untimed.json V-101.steps.csv; do
        if cmp "$d/never/out/$f" "$d/require/out/$f" >>"$out/demo.log" 2>&1; then
            echo "demo: $f is the same on the CPU and the GPU" | tee -a "$out/demo.log"
        else
            echo "demo: $f DIFFERS between the CPU and the GPU" | tee -a "$out/demo.log"
            differ=1
        fi
    done
    grep -E "^== |depthmap|docs|whole run" "$out/demo.log" || true
    rm -rf "$d"
    return "$differ"
}

case "${1:-}" in
    prepare) prepare ;;
    run) shift; run "$@" ;;
    repeat) repeat ;;
    *) echo "usage: scripts/gpu_device.sh prepare | run [soak-seconds] | repeat" >&2; exit 2 ;;
esac
