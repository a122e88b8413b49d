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
# The device tool's call (estimated at 6 to 8 minutes there, from this
# machine's times; not yet run on one). .devbin holds the binaries stripped
# and packed with xz, small enough for the 64 MiB the working tree and
# carried paths may take; the 8 files written to $OUT are the most that
# come back:
#   run(command="scripts/gpu_device.sh run 120", carry=[".devbin", ".gl"], timeout_s=600)
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

run() {
    local soak=${1:-120} bin
    local out=${OUT:-gpu-out}
    mkdir -p "$out"
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
    # The GPU's name heads the test log (8 files are all that come back).
    if command -v nvidia-smi >/dev/null; then
        nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv >"$out/tests.log" 2>&1 || true
    else
        echo "no nvidia-smi" >"$out/tests.log"
    fi
    cat "$out/tests.log"

    local failed=0
    for t in "$bin"/test-*; do
        # Tests run where cargo runs them: their package's directory.
        local pkg=${t#"$bin"/test-liftplan-}
        pkg=${pkg%-gpu_*}
        echo "== $t"
        (cd "stages/$pkg" && "$t" --test-threads=1 --nocapture) >"$out/test.log" 2>&1 || failed=1
        grep -E "^test |test result|GPU twin test on|SKIPPED" "$out/test.log" | sort -u || true
        cat "$out/test.log" >>"$out/tests.log"
        rm "$out/test.log"
    done
    echo "== demo, CPU and GPU"
    demo_twice "$out" || failed=1
    echo "== bench_depthmap"
    "$bin"/bench_depthmap >"$out/depthmap.md" 2>"$out/bench_depthmap.log" || failed=1
    echo "== bench_depthmap queries"
    "$bin"/bench_depthmap queries >"$out/queries.md" 2>>"$out/bench_depthmap.log" || failed=1
    echo "== bench_cspace hybrid"
    "$bin"/bench_cspace hybrid >"$out/cspace.md" 2>>"$out/bench_depthmap.log" || failed=1
    echo "== stress_gpu $soak"
    "$bin"/stress_gpu "$soak" >"$out/stress_gpu.log" 2>&1 || failed=1
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
    "$bin"/liftplan -q demo "$d/base" >"$out/demo.log" 2>&1 || return 1
    for mode in never require; do
        cp -r "$d/base" "$d/$mode"
        printf '\n[gpu]\nuse = "%s"\n' "$mode" >>"$d/$mode/liftplan.toml"
        "$bin"/liftplan -q clean "$d/$mode" >>"$out/demo.log" 2>&1
        echo "== [gpu] use = \"$mode\"" >>"$out/demo.log"
        t0=$(date +%s.%N)
        "$bin"/liftplan run "$d/$mode" >>"$out/demo.log" 2>&1 || return 1
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
    *) echo "usage: scripts/gpu_device.sh prepare | run [soak-seconds]" >&2; exit 2 ;;
esac
