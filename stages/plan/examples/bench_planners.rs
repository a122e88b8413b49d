//! Planner and C-space benchmark on a project that has been run once
//! (`liftplan demo DIR` first). Same checker, same inputs, one process:
//!
//!   cargo run --release -p liftplan-plan --example bench_planners -- DIR [SEEDS] > reports/planner.md
//!
//! Part 1 compares MSPGA with the baselines (Ali et al.'s GA fitness,
//! RRT-Connect, PRM): success rate over seeds, motion cost, steps, time, and
//! whether the independent validator accepts the result. Part 2 compares the
//! three C-space strategies (hybrid, full precomputation, fully online) under
//! MSPGA: build time, planning time, table lookups and box queries.

use liftplan_core::capacity::CapacityTable;
use liftplan_core::lift::LiftSpec;
use liftplan_depthmap::mdm::Mdm;
use liftplan_plan::{Planner, Settings, Site, plan_lift, validate};
use std::path::PathBuf;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = PathBuf::from(args.get(1).expect("usage: bench_planners DIR [SEEDS]"));
    let seeds: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);
    let out = dir.join("out");
    let text = std::fs::read_to_string(dir.join("liftplan.toml")).expect("liftplan.toml");
    let v: toml::Value = toml::from_str(&text).expect("toml");
    let lift = v["lift"].as_array().expect("[[lift]]")[0].clone();
    let spec: LiftSpec = lift.try_into().expect("lift");
    let task =
        spec.resolve(liftplan_core::crane::builtin(&spec.crane.model).expect("built-in crane")).expect("lift resolves");
    let map = Mdm::read(&out.join("site.mdm")).expect("site.mdm");
    let mesh = liftplan_core::mesh::TriMesh::read_artifact(&out.join("plant.mesh")).unwrap_or_default();
    let excl = liftplan_plan::load_exclusions(std::slice::from_ref(&task));
    let (pts, ground) = liftplan_plan::read_points(&out.join("site.laz"), &excl).expect("site.laz");
    let world = validate::World::new(&mesh, &pts, &ground).expect("world");
    let charts = CapacityTable::read_csv(&out.join("capacity.csv")).ok();
    let site = Site { map: &map, world: &world, charts: charts.as_ref() };
    println!("# Planner benchmark: lift {} on {}\n", task.id, dir.display());
    println!(
        "Machine: {} threads. Same inputs, same checker (hybrid C-space), same validator; {seeds} seeds each. \
         Motion cost is the thesis' weighted units (swing 1/deg, luff 1.5/deg, hoist 0.06/cm, rotate 1/deg).\n",
        rayon::current_num_threads()
    );
    println!("| planner | success | mean cost | mean steps | mean time s | validator ok |");
    println!("|---|---|---|---|---|---|");
    let mut mspga_time = 0.0;
    for planner in [Planner::Mspga, Planner::AliGa, Planner::RrtConnect, Planner::Prm] {
        let mut s = Settings { planner, ..Settings::default() };
        s.ga.max_generations = 400;
        let (mut ok, mut cost, mut steps, mut time, mut valid) = (0, 0.0, 0.0, 0.0, 0);
        for seed in 0..seeds {
            let t0 = Instant::now();
            let r = plan_lift(&task, &site, &s, seed);
            let dt = t0.elapsed().as_secs_f64();
            time += dt;
            match r {
                Ok((p, _)) => {
                    ok += 1;
                    cost += p.planning.motion_cost;
                    steps += p.steps.len() as f64;
                    valid += usize::from(p.validator.ok);
                }
                Err(e) => eprintln!("{planner:?} seed {seed}: {e}"),
            }
        }
        if planner == Planner::Mspga {
            mspga_time = time / seeds as f64;
        }
        let k = ok.max(1) as f64;
        println!(
            "| {planner:?} | {ok}/{seeds} | {:.1} | {:.1} | {:.2} | {valid}/{ok} |",
            cost / k,
            steps / k,
            time / seeds as f64
        );
    }
    println!("\n# C-space strategies (MSPGA, seed 0)\n");
    println!("| strategy | build ms | plan+validate s | ratio to hybrid | table lookups | box queries | result |");
    println!("|---|---|---|---|---|---|---|");
    let mut hybrid = 0.0;
    for strategy in
        [liftplan_cspace::Strategy::Hybrid, liftplan_cspace::Strategy::Full, liftplan_cspace::Strategy::Online]
    {
        let mut s = Settings::default();
        s.cspace.strategy = strategy;
        let t0 = Instant::now();
        let r = plan_lift(&task, &site, &s, 0);
        let dt = t0.elapsed().as_secs_f64();
        if strategy == liftplan_cspace::Strategy::Hybrid {
            hybrid = dt;
        }
        match r {
            Ok((p, cs)) => println!(
                "| {strategy:?} | {:.0} | {dt:.2} | {:.2} | {} | {} | {} steps, cost {:.1} |",
                cs.build_ms,
                dt / hybrid.max(1e-9),
                p.planning.table_lookups,
                p.planning.box_queries,
                p.steps.len(),
                p.planning.motion_cost
            ),
            Err(e) => println!("| {strategy:?} | - | {dt:.2} | {:.2} | - | - | failed: {e} |", dt / hybrid.max(1e-9)),
        }
    }
    eprintln!("mspga mean {mspga_time:.2} s");
}
