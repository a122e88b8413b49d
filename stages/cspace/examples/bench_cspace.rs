//! Precompute time of the three C-space strategies on a ~376k-triangle plant
//! (the thesis' Table 4.14 size), one process, this machine's CPU; then the
//! thesis' build (a box query per cell) on the CPU and on the GPU where wgpu
//! finds an adapter (lavapipe counts: the report names the device):
//!
//!   cargo run --release -p liftplan-cspace --example bench_cspace > reports/cspace.md

use liftplan_core::crane::builtin;
use liftplan_core::lift::LiftSpec;
use liftplan_core::mesh::TriMesh;
use liftplan_cspace::by_query::{Queries, QueryRows, rows_by_query};
use liftplan_cspace::{CSpace, Problem, Settings, Strategy};
use rand::{RngExt, SeedableRng};
use std::time::Instant;

fn plant() -> TriMesh {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(376);
    let mut m = TriMesh::default();
    for k in 0..31_334 {
        let g = m.group_id(&format!("ITEM-{}", k / 100));
        // A plant ring around the crane: 12..60 m out, up to 25 m high.
        let (r, a) = (12.0 + rng.random::<f64>() * 48.0, rng.random::<f64>() * std::f64::consts::TAU);
        let c = [r * a.cos(), r * a.sin(), rng.random::<f64>() * 25.0];
        let h = [0.2 + rng.random::<f64>() * 1.5, 0.2 + rng.random::<f64>() * 1.5, 0.2 + rng.random::<f64>() * 1.5];
        m.add_box(g, [c[0] - h[0], c[1] - h[1], c[2] - h[2]], [c[0] + h[0], c[1] + h[1], c[2] + h[2]]);
    }
    m
}

fn main() {
    // Optional arguments name the strategies to run (default: all three);
    // `runs=N` takes the best of N builds instead of 3.
    let args: Vec<String> = std::env::args().skip(1).map(|a| a.to_lowercase()).collect();
    let repeats: usize = args.iter().find_map(|a| a.strip_prefix("runs=")).and_then(|v| v.parse().ok()).unwrap_or(3);
    let only: Vec<String> = args.into_iter().filter(|a| !a.starts_with("runs=")).collect();
    let spec: LiftSpec = toml::from_str(
        r#"
id = "B"
load = { name = "skid", mass_t = 10.0, size_m = [6.0, 3.0, 3.0], cog_m = [0.0, 0.0, 0.0] }
rigging = { mass_t = 0.3, height_m = 3.0 }
crane = { model = "ac-700", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 0.0, boom_m = 40.0, chart_config = "none" }
pick = { x_m = 25.0, y_m = 0.0, z_m = 10.0, yaw_deg = 0.0 }
set = { x_m = 0.0, y_m = 25.0, z_m = 10.0, yaw_deg = 0.0 }
clearance_m = 1.0
"#,
    )
    .unwrap();
    let task = spec.resolve(builtin("ac-700").unwrap()).unwrap();
    let mesh = plant();
    let t0 = Instant::now();
    let inp = liftplan_depthmap::Inputs { points: vec![], ground: vec![], mesh };
    let (map, _) = liftplan_depthmap::build_cpu(&inp, &liftplan_depthmap::Settings::default()).unwrap();
    let map_ms = t0.elapsed().as_secs_f64() * 1e3;
    println!("# C-space precomputation\n");
    println!(
        "{} triangles (rasterised into the depth map in {map_ms:.0} ms), AC 700 with a 40 m boom in the middle of the plant, \
         0.5° x 0.5° swing x luff grid, {} CPU threads. Thesis Table 4.14: hybrid 1034 ms on its GPU. Best of {repeats}.\n",
        inp.mesh.triangle_count(),
        rayon::current_num_threads()
    );
    println!(
        "| strategy | cells | precompute ms | ratio to the thesis' 1034 ms | body ms | boom ms | max rope ms | rope bits ms | boom cells blocked |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for strategy in [Strategy::Hybrid, Strategy::Full, Strategy::Online] {
        if !only.is_empty() && !only.contains(&format!("{strategy:?}").to_lowercase()) {
            continue;
        }
        let s = Settings { strategy, ..Settings::default() };
        let mut best = f64::INFINITY;
        let mut cells = 0;
        let mut timings = liftplan_cspace::BuildTimings::default();
        let mut blocked = 0;
        for _ in 0..repeats.max(1) {
            let cs = CSpace::build(&Problem { task: &task, chart: None, map: &map }, &s);
            if cs.build_ms < best {
                best = cs.build_ms;
                timings = cs.timings;
            }
            cells = cs.ns * cs.nr;
            blocked = cs.cell_hits.iter().filter(|h| h.is_some()).count();
        }
        let t = timings;
        println!(
            "| {strategy:?} | {cells} | {best:.0} | {:.2} | {:.1} | {:.0} | {:.0} | {:.0} | {blocked} |",
            best / 1034.0,
            t.swing_ms,
            t.radial_ms,
            t.max_hoist_ms,
            t.hoist_bits_ms
        );
    }
    // The thesis' build: body and boom rows by one box query each, on the
    // CPU and on the GPU's box-query twin, against the hybrid build's marking.
    if only.is_empty() || only.iter().any(|o| o == "hybrid") {
        let problem = Problem { task: &task, chart: None, map: &map };
        let cs = CSpace::build(&problem, &Settings::default());
        let marking_ms = cs.timings.swing_ms + cs.timings.radial_ms;
        let timed = |on: Queries| {
            let mut best: Option<(f64, QueryRows)> = None;
            for _ in 0..repeats.max(1) {
                let t = Instant::now();
                let rows = rows_by_query(&cs, &problem, on).unwrap();
                let ms = t.elapsed().as_secs_f64() * 1e3;
                if best.as_ref().is_none_or(|b| ms < b.0) {
                    best = Some((ms, rows));
                }
            }
            best.unwrap()
        };
        let (cpu_ms, cpu) = timed(Queries::Cpu);
        let asked = cpu.swing_hits.len() + cpu.cell_hits.len();
        let blocked = |r: &[Option<liftplan_cspace::CellHit>]| r.iter().filter(|h| h.is_some()).count();
        println!(
            "\n## The thesis' build: one box query per cell, CPU and GPU\n\n\
             The body rows ({} swing columns) and boom rows ({} cells) by one box query each (grown by the clearance \
             and the cell's motion): the thesis' C-space build (§4.4), whose GPU figure is Table 4.14's. \
             The CPU row is the same as the hybrid build's body rows plus the box-query boom rows; the GPU row is \
             the same queries on the GPU's box-query twin, whose answers are the CPU's by construction \
             (`liftplan_depthmap::gpu`): the boxes it cannot decide in f32 go to the CPU's exact query, \
             inside the time shown. Best of {repeats}.\n",
            cs.ns,
            cs.ns * cs.nr
        );
        println!(
            "| path | device | body + boom rows ms | ratio to the thesis' 1034 ms | ratio to the CPU's box queries | boxes left to the CPU | rows equal to the CPU's |"
        );
        println!("|---|---|---|---|---|---|---|");
        let threads = format!("CPU, {} threads", rayon::current_num_threads());
        println!(
            "| hybrid build (body by box queries, boom marked obstacle by obstacle) | {threads} | {marking_ms:.0} | {:.3} | {:.2} | - | - |",
            marking_ms / 1034.0,
            marking_ms / cpu_ms
        );
        println!("| box queries | {threads} | {cpu_ms:.0} | {:.2} | 1.00 | - | yes |", cpu_ms / 1034.0);
        match liftplan_depthmap::gpu::open(true) {
            Ok(g) => {
                let t = Instant::now();
                let on = g.upload_map(&map).unwrap();
                let upload_ms = t.elapsed().as_secs_f64() * 1e3;
                let (gpu_ms, dev) = timed(Queries::Gpu(&g, &on));
                let equal = dev.swing_hits == cpu.swing_hits && dev.cell_hits == cpu.cell_hits;
                let sc = dev.screen;
                println!(
                    "| box queries on the GPU twin | {} | {gpu_ms:.0} | {:.2} | {:.2} | {} of {} ({:.1} %) | {} |",
                    g.name(),
                    gpu_ms / 1034.0,
                    gpu_ms / cpu_ms,
                    sc.left_to_cpu,
                    sc.boxes(),
                    100.0 * sc.left_to_cpu as f64 / sc.boxes().max(1) as f64,
                    if equal { "yes" } else { "**NO**" }
                );
                let (prepare_ms, transfer_ms, exact_ms) = (sc.prepare_ms, sc.transfer_ms, sc.exact_ms);
                let (host_ms, walk_ms) = (prepare_ms + transfer_ms + exact_ms, sc.screen_ms - prepare_ms - transfer_ms);
                println!(
                    "\nGPU: the depth map's upload took {upload_ms:.0} ms (once per map, not in the row). Of the best run, \
                     {:.0} ms went to the device's part: preparing the boxes on the host ({prepare_ms:.0} ms), filling \
                     the device's buffers with them and decoding its answers on the host ({transfer_ms:.0} ms), and the \
                     device's walk, its copies and the wait for them ({walk_ms:.0} ms); and {exact_ms:.0} ms to the \
                     CPU's exact queries of the boxes left to it. The host's own share, {host_ms:.0} ms \
                     ({prepare_ms:.0} + {transfer_ms:.0} + {exact_ms:.0}), is work on this host's cores that a faster \
                     device does not take off them: with this host, no device makes the row faster than that.",
                    sc.screen_ms
                );
                if !equal {
                    eprintln!("the GPU's rows differ from the CPU's");
                    std::process::exit(1);
                }
                // The longest-clear-rope table with its dilation on the device.
                let rope_ms = |gpu: Option<&liftplan_depthmap::gpu::Gpu>| {
                    (0..repeats.max(1))
                        .map(|_| CSpace::build_on(&problem, &Settings::default(), gpu))
                        .map(|b| (b.timings.max_hoist_ms, b))
                        .min_by(|a, b| a.0.total_cmp(&b.0))
                        .unwrap()
                };
                let (cpu_rope_ms, on_cpu) = rope_ms(None);
                let (gpu_rope_ms, on_gpu) = rope_ms(Some(&g));
                let same =
                    on_gpu.max_hoist.iter().map(|h| h.to_bits()).eq(on_cpu.max_hoist.iter().map(|h| h.to_bits()));
                println!(
                    "\nThe longest clear rope per cell (hybrid build), its dilation on {}: {gpu_rope_ms:.1} ms \
                     against {cpu_rope_ms:.1} ms with it on the CPU ({:.2}x; best of {repeats}, the upload and read-back \
                     inside); on the device: {}; the table equal to the CPU's bit for bit: {}.",
                    g.name(),
                    gpu_rope_ms / cpu_rope_ms,
                    on_gpu.timings.dilation_on_gpu,
                    if same { "yes" } else { "**NO**" }
                );
                if !same {
                    eprintln!("the GPU's rope table differs from the CPU's");
                    std::process::exit(1);
                }
            }
            Err(e) => println!("| box queries on the GPU twin | none: {e} | - | - | - | - | - |"),
        }
        let (mut both, mut only_query, mut only_marked) = (0, 0, 0);
        for (a, b) in cpu.cell_hits.iter().zip(&cs.cell_hits) {
            match (a.is_some(), b.is_some()) {
                (true, true) => both += 1,
                (true, false) => only_query += 1,
                (false, true) => only_marked += 1,
                _ => {}
            }
        }
        println!(
            "\nBoom cells blocked: {} by the box queries, {} by the marking; by both {both}, only by the box queries \
             {only_query}, only by the marking {only_marked}. Body columns blocked: {} of {} (the same rows in both builds). \
             {asked} table entries, each asking one box per part until one meets something.",
            blocked(&cpu.cell_hits),
            blocked(&cs.cell_hits),
            blocked(&cpu.swing_hits),
            cs.ns
        );
    }
    println!(
        "\n`online` precomputes only the per-row chart and internal-clearance limits; it pays at query time instead (see reports/planner.md)."
    );
}
