//! Precompute time of the three C-space strategies on a ~376k-triangle plant
//! (the thesis' Table 4.14 size), one process, this machine's CPU:
//!
//!   cargo run --release -p liftplan-cspace --example bench_cspace > reports/cspace.md

use liftplan_core::crane::builtin;
use liftplan_core::lift::LiftSpec;
use liftplan_core::mesh::TriMesh;
use liftplan_cspace::{CSpace, Problem, Settings, Strategy};
use rand::{RngExt, SeedableRng};
use rayon::prelude::*;
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
    // The boom table as the previous build made it: one box query per cell.
    if only.is_empty() || only.iter().any(|o| o == "hybrid") {
        let cs = CSpace::build(&Problem { task: &task, chart: None, map: &map }, &Settings::default());
        let problem = Problem { task: &task, chart: None, map: &map };
        let t = Instant::now();
        let by_query: Vec<_> = (0..cs.nr * cs.ns)
            .into_par_iter()
            .map(|idx| cs.radial_cell_by_query(&problem, idx % cs.ns, idx / cs.ns))
            .collect();
        let query_ms = t.elapsed().as_secs_f64() * 1e3;
        let (mut both, mut only_query, mut only_marked) = (0, 0, 0);
        for (a, b) in by_query.iter().zip(&cs.cell_hits) {
            match (a.is_some(), b.is_some()) {
                (true, true) => both += 1,
                (true, false) => only_query += 1,
                (false, true) => only_marked += 1,
                _ => {}
            }
        }
        println!(
            "\nBoom rows, same run: one box query per cell (grown by the clearance and the cell's motion) {query_ms:.0} ms, \
             {} cells blocked; marked obstacle by obstacle (the hybrid build above) {:.0} ms, {} blocked. \
             Blocked by both {both}, only by the box queries {only_query}, only by the marking {only_marked}.",
            both + only_query,
            cs.timings.radial_ms,
            both + only_marked
        );
    }
    println!(
        "\n`online` precomputes only the per-row chart and internal-clearance limits; it pays at query time instead (see reports/planner.md)."
    );
}
