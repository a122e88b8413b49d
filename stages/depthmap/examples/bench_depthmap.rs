//! Depth-map rasterisation time for 1, 5 and 21 M points and a plant-sized
//! triangle set, CPU (rayon) and GPU (wgpu, when an adapter exists), each as a
//! ratio to a plain streaming pass over the same points on every thread (the
//! memory floor), all in one run:
//!
//!   cargo run --release -p liftplan-depthmap --example bench_depthmap > reports/depthmap.md
//!
//! Two clouds of each size over a 200 x 200 m site, both deterministic:
//! *random* (60 % on a ground plane, the rest anywhere up to 30 m: almost
//! nothing merges, the worst case for the assembly) and *surface* (points on
//! ground, buildings, tanks and pipes, as a scan sees a plant). The map uses
//! the project defaults (0.25 m cells, 5 cm point radius).
//!
//! With `queries`, it times batched box queries instead, CPU against GPU
//! (the device's walk, the CPU's exact test for what it leaves), on one map of the plant and
//! 5 M surface points:
//!
//!   cargo run --release -p liftplan-depthmap --example bench_depthmap -- queries > reports/queries.md

use liftplan_core::mesh::TriMesh;
use liftplan_core::obb::Obb;
use liftplan_depthmap::mdm::Mdm;
use liftplan_depthmap::query::Vertical;
use liftplan_depthmap::{Inputs, Settings, build, build_cpu, gpu};
use rand::{RngExt, SeedableRng};
use std::time::Instant;

fn points(n: usize) -> Inputs {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(n as u64);
    let mut inp = Inputs::default();
    inp.points.reserve(n);
    inp.ground.reserve(n);
    for _ in 0..n {
        let (x, y) = (rng.random::<f64>() * 200.0, rng.random::<f64>() * 200.0);
        let g = rng.random::<f64>() < 0.6;
        inp.points.push([x, y, if g { 0.0 } else { rng.random::<f64>() * 30.0 }]);
        inp.ground.push(g);
    }
    inp
}

/// `n` points on surfaces, as a laser scan of a plant sees it: gently sloping
/// ground (half of them, classed ground), the walls and roofs of 12 buildings,
/// 8 storage tanks and 16 pipes on racks, over the same 200 x 200 m. Unlike
/// [`points`], most points of a cell lie on one or two surfaces, so they merge.
fn surface_points(n: usize) -> Inputs {
    use std::f64::consts::TAU;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(n as u64 ^ 0x5eed);
    let ground_z = |x: f64, y: f64| 0.01 * x + 0.4 * (y / 25.0).sin();
    let buildings: Vec<[f64; 5]> = (0..12)
        .map(|k| {
            let (x, y) = (10.0 + (k % 4) as f64 * 48.0, 15.0 + (k / 4) as f64 * 60.0);
            [x, y, 18.0 + (k % 3) as f64 * 6.0, 12.0 + (k % 2) as f64 * 8.0, 8.0 + (k % 5) as f64 * 3.0]
        })
        .collect();
    let tanks: Vec<[f64; 4]> = (0..8).map(|k| [30.0 + k as f64 * 20.0, 190.0, 4.0 + (k % 3) as f64, 12.0]).collect();
    let mut inp = Inputs::default();
    inp.points.reserve(n);
    inp.ground.reserve(n);
    for _ in 0..n {
        let u = rng.random::<f64>();
        let (p, g) = if u < 0.5 {
            let (x, y) = (rng.random::<f64>() * 200.0, rng.random::<f64>() * 200.0);
            ([x, y, ground_z(x, y)], true)
        } else if u < 0.8 {
            let [bx, by, w, d, h] = buildings[rng.random_range(0..buildings.len())];
            let z0 = ground_z(bx, by);
            let (a, b) = (rng.random::<f64>(), rng.random::<f64>());
            let p = match rng.random_range(0..5) {
                0 => [bx + a * w, by, z0 + b * h],
                1 => [bx + a * w, by + d, z0 + b * h],
                2 => [bx, by + a * d, z0 + b * h],
                3 => [bx + w, by + a * d, z0 + b * h],
                _ => [bx + a * w, by + b * d, z0 + h],
            };
            (p, false)
        } else if u < 0.9 {
            let [cx, cy, r, h] = tanks[rng.random_range(0..tanks.len())];
            let t = rng.random::<f64>() * TAU;
            ([cx + r * t.cos(), cy + r * t.sin(), ground_z(cx, cy) + rng.random::<f64>() * h], false)
        } else {
            let k = rng.random_range(0..16);
            let (y, z) = (100.0 + (k % 4) as f64 * 2.0, 6.0 + (k / 4) as f64 * 1.5);
            let t = rng.random::<f64>() * TAU;
            ([5.0 + rng.random::<f64>() * 190.0, y + 0.3 * t.cos(), z + 0.3 * t.sin()], false)
        };
        inp.points.push(p);
        inp.ground.push(g);
    }
    inp
}

/// ~376k triangles: 31,000 small boxes (12 triangles each) scattered over the site.
fn plant() -> TriMesh {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(376);
    let mut m = TriMesh::default();
    let g = m.group_id("plant");
    for _ in 0..31_334 {
        let c = [rng.random::<f64>() * 200.0, rng.random::<f64>() * 200.0, rng.random::<f64>() * 25.0];
        let h = [0.2 + rng.random::<f64>() * 2.0, 0.2 + rng.random::<f64>() * 2.0, 0.2 + rng.random::<f64>() * 2.0];
        m.add_box(g, [c[0] - h[0], c[1] - h[1], c[2] - h[2]], [c[0] + h[0], c[1] + h[1], c[2] + h[2]]);
    }
    m
}

/// CPU builds (and floor passes) per row: a shared 2-core machine's times
/// vary by 10-15 % from run to run, and a CPU build is quick, so it gets more
/// tries than the GPU (3) does.
const CPU_RUNS: usize = 5;

fn best_of(k: usize, mut f: impl FnMut() -> f64) -> f64 {
    (0..k).map(|_| f()).fold(f64::INFINITY, f64::min)
}

fn main() {
    let s = Settings::default();
    // Optional: `cpu` skips the GPU; numbers replace the point counts.
    let args: Vec<String> = std::env::args().skip(1).collect();
    let cpu_only = args.iter().any(|a| a == "cpu");
    let mut sizes: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes = vec![1_000_000, 5_000_000, 21_000_716];
    }
    let device = if cpu_only { Err("not asked for".to_string()) } else { gpu::open(true) };
    if args.iter().any(|a| a == "queries") {
        return queries(&s, &device);
    }
    if args.iter().any(|a| a == "repeat") {
        return repeat(&s, &device, &sizes);
    }
    println!("# Depth-map rasterisation\n");
    println!(
        "{} CPU threads; GPU: {}. Best of {CPU_RUNS} runs on the CPU, of 3 on the GPU. Floor = one streaming pass reading every point on every thread (sum of coordinates, four accumulators a thread). \
         The thesis' figure: 21,000,716 points in 584 ms on a Tesla K20c.\n",
        rayon::current_num_threads(),
        device
            .as_ref()
            .map(|g| match g.loop_cap() {
                Some(cap) => format!("{} (ends a shader's loops after {cap} iterations)", g.name()),
                None => g.name().to_string(),
            })
            .unwrap_or_else(|e| format!("none ({e})"))
    );
    println!(
        "| input | floor ms | plain count+fill ms | plain count+fill / floor | banded count+fill ms | banded count+fill / floor | CPU ms | CPU / floor | GPU ms | GPU / floor | GPU passes ms | GPU passes / floor | maps equal |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let clouds = sizes.iter().map(|&n| ("random", n)).chain(sizes.iter().map(|&n| ("surface", n)));
    let mut splits = Vec::new();
    for (kind, n) in clouds {
        let inp = if kind == "random" { points(n) } else { surface_points(n) };
        let floor = best_of(CPU_RUNS, || {
            let t = Instant::now();
            std::hint::black_box(stream(&inp.points));
            t.elapsed().as_secs_f64() * 1e3
        });
        let fill = count_and_fill(&inp.points, s.cell_m, CPU_RUNS);
        let banded = count_and_fill_banded(&inp.points, s.cell_m, CPU_RUNS);
        let (cpu, gpu) = compare(&inp, &s, &device, &format!("{n} {kind} points"));
        splits.extend(gpu.map(|g| (format!("{n} {kind} points"), g)));
        let ratio = |x: f64| format!("{:.1}", x / floor);
        println!(
            "| {n} {kind} points | {floor:.1} | {fill:.0} | {} | {banded:.0} | {} | {cpu:.0} | {} | {} | {} | {} | {} | {} |",
            ratio(fill),
            ratio(banded),
            ratio(cpu),
            gpu.map_or("-".into(), |g| format!("{:.0}", g.total_ms)),
            gpu.map_or("-".into(), |g| ratio(g.total_ms)),
            gpu.map_or("-".into(), |g| format!("{:.1}", g.passes_ms)),
            gpu.map_or("-".into(), |g| ratio(g.passes_ms)),
            gpu.map_or("-", |g| if g.equal { "yes" } else { "NO" }),
        );
    }
    let inp = Inputs { points: vec![], ground: vec![], mesh: plant() };
    let (cpu, gpu) = compare(&inp, &s, &device, "plant");
    println!(
        "| {} triangles | - | - | - | - | - | {cpu:.0} | - | {} | - | {} | - | {} |",
        inp.mesh.triangle_count(),
        gpu.map_or("-".into(), |g| format!("{:.0}", g.total_ms)),
        gpu.map_or("-".into(), |g| format!("{:.1}", g.passes_ms)),
        gpu.map_or("-", |g| if g.equal { "yes" } else { "NO" }),
    );
    splits.extend(gpu.map(|g| (format!("{} triangles", inp.mesh.triangle_count()), g)));
    println!(
        "\nBoth paths run every pass (count, prefix sum, fill, per-cell sort and merge). Triangles are clipped to \
         cells on the CPU for both (in f64); on the GPU path their raw intervals go up and through the device's \
         passes with the points. GPU ms is the whole build (conversion and upload of the points, the passes, \
         reading the map back); GPU passes ms is the device's part alone. Plain count+fill is the thesis' count and \
         fill passes alone, done plainly on the CPU threads (every point to the one cell under it, per-thread \
         counts, prefix sum, its height key written to its cell's slot; no radius, no sort, no merge, grid and \
         output buffer given). Banded count+fill is the same in two cache-sized levels, as the CPU build groups \
         its records (by band of grid rows in jobs of 65,536 points, then by cell band by band)."
    );
    if splits.is_empty() {
        return;
    }
    println!(
        "\nWhere the GPU build's time went, in its run of least passes' time (wall clock on the host; each pass \
         waits for the device at its end): the upload (packing and copying the points and triangle raws), the \
         passes (count with its prefix sum and lists of crowded cells; fill; sort and merge with the merged \
         counts' prefix sum; compaction) and the read-back of the map.\n"
    );
    println!(
        "| input | raw intervals | upload ms | count ms | fill ms | sort and merge ms | compact ms | read back ms |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (what, g) in splits {
        let t = g.split;
        println!(
            "| {what} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |",
            g.raws, t.upload_ms, t.count_ms, t.fill_ms, t.sort_ms, t.compact_ms, t.read_back_ms
        );
    }
}

/// The floor: one pass reading every point on every thread, as the builds
/// use them, summing the coordinates into four accumulators per thread (one
/// accumulator would make the pass wait on each addition instead of on
/// memory: a serial sum read 21 M points in ~35 ms here, this in ~22 ms).
fn stream(points: &[[f64; 3]]) -> f64 {
    use rayon::prelude::*;
    points
        .par_chunks(1 << 16)
        .map(|c| {
            let mut acc = [0f64; 4];
            for (k, p) in c.iter().enumerate() {
                acc[k & 3] += p[0] + p[1] + p[2];
            }
            acc.iter().sum::<f64>()
        })
        .sum()
}

/// The grid of the count-and-fill yardsticks: the points' bounding box in
/// cells of `cell` m, and the one cell under a point (no radius).
#[derive(Clone, Copy)]
struct PlainGrid {
    lo: [f64; 2],
    inv: f64,
    nx: usize,
    ny: usize,
}

impl PlainGrid {
    fn of(points: &[[f64; 3]], cell: f64) -> PlainGrid {
        let lo = points.iter().fold([f64::INFINITY; 2], |m, p| [m[0].min(p[0]), m[1].min(p[1])]);
        let hi = points.iter().fold([f64::NEG_INFINITY; 2], |m, p| [m[0].max(p[0]), m[1].max(p[1])]);
        let inv = 1.0 / cell;
        PlainGrid { lo, inv, nx: ((hi[0] - lo[0]) * inv) as usize + 1, ny: ((hi[1] - lo[1]) * inv) as usize + 1 }
    }

    #[inline]
    fn cell_of(&self, p: &[f64; 3]) -> usize {
        let i = (((p[0] - self.lo[0]) * self.inv) as usize).min(self.nx - 1);
        let j = (((p[1] - self.lo[1]) * self.inv) as usize).min(self.ny - 1);
        j * self.nx + i
    }
}

/// The thesis' count and fill passes alone, done plainly on the CPU, as a
/// yardstick for the goal: every point goes to the one cell under it (no
/// radius), per-thread counts per cell, their prefix sum, then each point's
/// height key is written to its cell's next slot; no sort, no merge, no map,
/// the grid and the output buffer given. Its writes land all over the output,
/// so it measures what scattering a cloud into cells costs here when done as
/// a GPU does it. Returns the time (ms) of the best of `runs`.
fn count_and_fill(points: &[[f64; 3]], cell: f64, runs: usize) -> f64 {
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
    let grid = PlainGrid::of(points, cell);
    let cells = grid.nx * grid.ny;
    let threads = rayon::current_num_threads();
    let chunk = points.len().div_ceil(threads).max(1);
    // Written by position, from several threads at once: relaxed atomic
    // stores are plain stores on x86-64.
    let out: Vec<AtomicU32> = (0..points.len()).map(|_| AtomicU32::new(0)).collect();
    best_of(runs, || {
        let t = Instant::now();
        let mut counts: Vec<Vec<u32>> = points
            .par_chunks(chunk)
            .map(|c| {
                let mut n = vec![0u32; cells];
                for p in c {
                    n[grid.cell_of(p)] += 1;
                }
                n
            })
            .collect();
        let mut at = 0u32;
        for c in 0..cells {
            for n in counts.iter_mut() {
                (n[c], at) = (at, at + n[c]);
            }
        }
        points.par_chunks(chunk).zip(counts.par_iter_mut()).for_each(|(c, next)| {
            for p in c {
                let slot = &mut next[grid.cell_of(p)];
                out[*slot as usize].store(liftplan_depthmap::mdm::f32_key(p[2] as f32), Relaxed);
                *slot += 1;
            }
        });
        std::hint::black_box(&out);
        t.elapsed().as_secs_f64() * 1e3
    })
}

/// [`count_and_fill`] in two cache-sized levels, as the CPU build groups its
/// records: jobs of 65,536 points group (cell, height key) pairs by band of
/// grid rows in cache; then each band, in parallel, counts its cells over
/// every job's part of it and writes the keys to their slots in its own part
/// of the output. The same output as the plain passes (up to the order of
/// a cell's keys), with every write but the last in cache; still no radius,
/// no sort, no merge. Returns the time (ms) of the best of `runs`.
fn count_and_fill_banded(points: &[[f64; 3]], cell: f64, runs: usize) -> f64 {
    use rayon::prelude::*;
    let grid = PlainGrid::of(points, cell);
    // Whole rows of about 2048 cells a band, a power of two of rows.
    let shift = (2048 / grid.nx).max(1).ilog2();
    let band_cells = grid.nx << shift;
    let bands = grid.ny.div_ceil(1 << shift);
    let mut out = vec![0u32; points.len()];
    best_of(runs, || {
        let t = Instant::now();
        let jobs: Vec<(Vec<u64>, Vec<u32>)> = points
            .par_chunks(1 << 16)
            .map_init(Vec::new, |made: &mut Vec<(u32, u64)>, c| {
                // Each point's band and record once, in cache; then grouped
                // by band as the build groups its own.
                made.clear();
                made.extend(c.iter().map(|p| {
                    let cell = grid.cell_of(p);
                    let key = liftplan_depthmap::mdm::f32_key(p[2] as f32);
                    ((cell / band_cells) as u32, ((cell % band_cells) as u64) << 32 | key as u64)
                }));
                liftplan_depthmap::mdm::group_by_band(made, bands)
            })
            .collect();
        let seg = |j: &(Vec<u64>, Vec<u32>), b: usize| (j.1[b] as usize, j.1[b + 1] as usize);
        let mut parts: Vec<&mut [u32]> = Vec::with_capacity(bands);
        let mut rest = &mut out[..];
        for b in 0..bands {
            let n: usize = jobs.iter().map(|j| seg(j, b)).map(|(s, e)| e - s).sum();
            let (part, r) = std::mem::take(&mut rest).split_at_mut(n);
            parts.push(part);
            rest = r;
        }
        parts.into_par_iter().enumerate().for_each_init(Vec::new, |next, (b, part)| {
            next.clear();
            next.resize(band_cells + 1, 0u32);
            for j in &jobs {
                let (s, e) = seg(j, b);
                for r in &j.0[s..e] {
                    next[(r >> 32) as usize + 1] += 1;
                }
            }
            for c in 1..=band_cells {
                next[c] += next[c - 1];
            }
            for j in &jobs {
                let (s, e) = seg(j, b);
                for r in &j.0[s..e] {
                    let at = &mut next[(r >> 32) as usize];
                    part[*at as usize] = *r as u32;
                    *at += 1;
                }
            }
        });
        std::hint::black_box(&out);
        t.elapsed().as_secs_f64() * 1e3
    })
}

#[derive(Clone, Copy)]
struct GpuRun {
    total_ms: f64,
    passes_ms: f64,
    /// The run with the least passes' time: where its time went.
    split: gpu::GpuTimings,
    raws: usize,
    equal: bool,
}

/// CPU time (best of [`CPU_RUNS`]) and, with a device, the GPU's (best of 3)
/// and whether its map is the CPU's.
fn compare(inp: &Inputs, s: &Settings, device: &Result<gpu::Gpu, String>, what: &str) -> (f64, Option<GpuRun>) {
    let mut cpu_map = None;
    let cpu = best_of(CPU_RUNS, || {
        let t = Instant::now();
        let (m, timings) = build_cpu(inp, s).unwrap();
        let dt = t.elapsed().as_secs_f64() * 1e3;
        eprintln!("{what}, CPU: {timings:?}, {} intervals", m.intervals.len());
        cpu_map = Some(m);
        dt
    });
    let Ok(g) = device else { return (cpu, None) };
    let mut best = GpuRun {
        total_ms: f64::INFINITY,
        passes_ms: f64::INFINITY,
        split: gpu::GpuTimings::default(),
        raws: 0,
        equal: true,
    };
    for _ in 0..3 {
        let t = Instant::now();
        let (m, timings) = build(inp, s, Some(g)).unwrap();
        let dt = t.elapsed().as_secs_f64() * 1e3;
        eprintln!("{what}, GPU: {timings:?}");
        best.total_ms = best.total_ms.min(dt);
        if let Some(g) = timings.gpu.filter(|g| g.passes_ms < best.passes_ms) {
            best.passes_ms = g.passes_ms;
            best.split = g;
            best.raws = timings.raw_intervals;
        }
        best.equal &= Some(m) == cpu_map;
    }
    (cpu, Some(best))
}

/// `bench_depthmap repeat [sizes]`: the GPU build of each cloud eight times
/// back to back, each run's split, after one CPU build to compare the maps
/// with: how much the device's time varies from run to run (its clocks rise
/// under load), which best-of-3 alone does not show.
fn repeat(s: &Settings, device: &Result<gpu::Gpu, String>, sizes: &[usize]) {
    let g = match device {
        Ok(g) => g,
        Err(e) => return println!("no GPU: {e}"),
    };
    println!("# GPU depth-map builds back to back\n\nGPU: {}. Each cloud's build eight times in a row.\n", g.name());
    println!(
        "| input | run | upload ms | count ms | fill ms | sort and merge ms | compact ms | passes ms | read back ms | whole ms | map equal |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for &n in sizes {
        for kind in ["random", "surface"] {
            let inp = if kind == "random" { points(n) } else { surface_points(n) };
            let (cpu_map, _) = build_cpu(&inp, s).unwrap();
            for run in 1..=8 {
                let t = Instant::now();
                let (m, timings) = build(&inp, s, Some(g)).unwrap();
                let whole = t.elapsed().as_secs_f64() * 1e3;
                let t = timings.gpu.unwrap_or_default();
                println!(
                    "| {n} {kind} points | {run} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {whole:.0} | {} |",
                    t.upload_ms,
                    t.count_ms,
                    t.fill_ms,
                    t.sort_ms,
                    t.compact_ms,
                    t.passes_ms,
                    t.read_back_ms,
                    if m == cpu_map { "yes" } else { "NO" }
                );
            }
        }
    }
}

/// Three sets of boxes over the site, as a planner asks them: loads and hooks
/// (upright), booms at a luffing angle, and boxes turned any way.
fn query_boxes(n: usize, kind: &str) -> Vec<Obb> {
    use liftplan_core::frame::{Point3, Vec3};
    use nalgebra::{Rotation3, Unit, Vector3};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(n as u64 ^ kind.len() as u64);
    (0..n)
        .map(|_| {
            let yaw = Rotation3::from_axis_angle(&Vector3::z_axis(), rng.random::<f64>() * std::f64::consts::TAU);
            let (x, y) = (rng.random::<f64>() * 200.0, rng.random::<f64>() * 200.0);
            match kind {
                "loads" => {
                    let half =
                        Vec3::new(rng.random_range(1.0..4.0), rng.random_range(1.0..4.0), rng.random_range(0.5..2.0));
                    Obb::new(Point3::new(x, y, rng.random_range(0.0..45.0)), *yaw.matrix(), half)
                }
                "booms" => {
                    let luff = Rotation3::from_axis_angle(&Vector3::y_axis(), -rng.random_range(0.0..1.4));
                    let half = Vec3::new(rng.random_range(10.0..30.0), 0.6, 0.6);
                    Obb::new(Point3::new(x, y, rng.random_range(10.0..50.0)), *(yaw * luff).matrix(), half)
                }
                _ => {
                    let axis = Unit::new_normalize(Vector3::new(rng.random(), rng.random(), rng.random::<f64>() - 0.5));
                    let turn = Rotation3::from_axis_angle(&axis, rng.random_range(0.0..3.0));
                    let half =
                        Vec3::new(rng.random_range(0.5..5.0), rng.random_range(0.5..5.0), rng.random_range(0.5..5.0));
                    Obb::new(Point3::new(x, y, rng.random_range(0.0..45.0)), *(turn * yaw).matrix(), half)
                }
            }
        })
        .collect()
}

/// Batched box queries on the CPU (`Mdm::hits`, rayon) and through the GPU
/// screen (`Gpu::hits_where`), same boxes, same map, answers compared.
fn queries(s: &Settings, device: &Result<gpu::Gpu, String>) {
    const N: usize = 100_000;
    let mut inp = surface_points(5_000_000);
    inp.mesh = plant();
    let (map, _) = build_cpu(&inp, s).unwrap();
    println!("# Box queries against the depth map\n");
    println!(
        "{} CPU threads; GPU: {}. Map: the plant of reports/depthmap.md ({} triangles) and 5 M surface points, \
         0.25 m cells, {} intervals. {N} boxes a set; best of 3 runs each.\n",
        rayon::current_num_threads(),
        device.as_ref().map(|g| g.name().to_string()).unwrap_or_else(|e| format!("none ({e})")),
        inp.mesh.triangle_count(),
        map.intervals.len()
    );
    let sets = ["loads", "booms", "turned"].map(|kind| (kind, query_boxes(N, kind)));
    let on_gpu = device.as_ref().ok().map(|g| {
        let t = Instant::now();
        let on_gpu = g.upload_map(&map).unwrap();
        println!("Map upload to the GPU: {:.0} ms.\n", t.elapsed().as_secs_f64() * 1e3);
        (g, on_gpu)
    });
    clearances(&map, &sets, on_gpu.as_ref());
    let Some((g, on_gpu)) = on_gpu else {
        println!("No GPU: nothing to compare.");
        return;
    };
    println!("Box queries (`Mdm::hits` on the CPU, `Gpu::hits_where` on the GPU) of the same boxes:\n");
    println!(
        "| boxes | hit (CPU) | CPU ms | GPU ms | CPU / GPU | free on the GPU | hit on the GPU | left to the CPU | GPU walk ms | of which host prep ms | of which host transfer ms | CPU rest ms | answers equal |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (kind, boxes) in &sets {
        let mut cpu_hits = Vec::new();
        let cpu = best_of(3, || {
            let t = Instant::now();
            cpu_hits = map.hits(boxes);
            t.elapsed().as_secs_f64() * 1e3
        });
        let (gpu_ms, c, equal) = best_gpu_run(kind, &cpu_hits, || g.hits_where(&on_gpu, &map, boxes, None));
        println!(
            "| {N} {kind} | {} | {cpu:.0} | {gpu_ms:.0} | {:.2} | {} | {} | {} | {:.0} | {:.0} | {:.0} | {:.0} | {} |",
            cpu_hits.iter().filter(|h| h.is_some()).count(),
            cpu / gpu_ms,
            c.free_on_gpu,
            c.hit_on_gpu,
            c.left_to_cpu,
            c.screen_ms,
            c.prepare_ms,
            c.transfer_ms,
            c.exact_ms,
            if equal { "yes" } else { "NO" }
        );
    }
}

/// Vertical clearances, down and up, of each set of boxes: on the CPU
/// (`Mdm::clearances`, rayon) and, where there is a GPU, through its twin
/// (`Gpu::clearances_where`), answers compared.
fn clearances(map: &Mdm, sets: &[(&str, Vec<Obb>)], device: Option<&(&gpu::Gpu, gpu::GpuMap)>) {
    println!(
        "Vertical clearance, down and up: on the CPU (`Mdm::clearances`) and on the GPU twin \
        (`Gpu::clearances_where`: the device narrows each box down to a few cells, the CPU measures those):\n"
    );
    println!(
        "| boxes | way | with something that way | CPU ms | GPU ms | CPU / GPU | nothing that way (GPU) | \
         narrowed on the GPU | cells measured | left to the CPU | GPU walk ms | CPU rest ms | answers equal |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (kind, boxes) in sets {
        for way in [Vertical::Down, Vertical::Up] {
            let mut on_cpu = Vec::new();
            let cpu = best_of(3, || {
                let t = Instant::now();
                on_cpu = map.clearances(boxes, way);
                t.elapsed().as_secs_f64() * 1e3
            });
            let found = on_cpu.iter().filter(|c| c.is_some()).count();
            let Some((g, on_gpu)) = device else {
                println!("| {} {kind} | {way:?} | {found} | {cpu:.0} | | | | | | | | | |", boxes.len());
                continue;
            };
            let label = format!("{kind} {way:?}");
            let (gpu_ms, c, equal) =
                best_gpu_run(&label, &on_cpu, || g.clearances_where(on_gpu, map, boxes, way, None));
            println!(
                "| {} {kind} | {way:?} | {found} | {cpu:.0} | {gpu_ms:.0} | {:.2} | {} | {} | {} | {} | {:.0} | {:.0} | {} |",
                boxes.len(),
                cpu / gpu_ms,
                c.free_on_gpu,
                c.hit_on_gpu,
                c.cells_measured,
                c.left_to_cpu,
                c.screen_ms,
                c.exact_ms,
                if equal { "yes" } else { "NO" }
            );
        }
    }
    println!();
}

/// Best of 3 runs of a GPU twin's batch: its time (ms, the whole call), that
/// run's counts, and whether every run gave the CPU's answers `want`.
fn best_gpu_run<T: PartialEq>(
    label: &str,
    want: &[T],
    mut run: impl FnMut() -> Result<(Vec<T>, gpu::ScreenCounts), String>,
) -> (f64, gpu::ScreenCounts, bool) {
    let mut best = (f64::INFINITY, gpu::ScreenCounts::default());
    let mut equal = true;
    for _ in 0..3 {
        let t = Instant::now();
        let (answers, counts) = run().unwrap();
        let dt = t.elapsed().as_secs_f64() * 1e3;
        eprintln!("{label}: GPU {dt:.0} ms, {counts:?}");
        equal &= answers == want;
        if dt < best.0 {
            best = (dt, counts);
        }
    }
    (best.0, best.1, equal)
}
