//! The planner's reproduction benchmarks, run by `liftplan bench` (Markdown
//! on stdout, progress and failures on stderr): the thesis' experiments on
//! synthetic plants built like its figures (Cai 2016, §4.5) and MSPGA against
//! the baselines on the demo lift. Not used by the pipeline.
//!
//! - Table 4.11/4.12: success rate and solution quality over RUNS seeds, Ali et
//!   al.'s fitness vs MSPGA's, on three plants: (1) process units between pick
//!   and set, (2) the set position on a structure higher than the obstacles
//!   between, (3) obstacles much higher than pick and set.
//! - Tables 4.15-4.18: success rate and mean fitness of feasible results over
//!   GRID_RUNS seeds for the thesis' 6 x 6 grid of crossover (rc) and mutation
//!   (rm) rates on plant 3 (Experiment 4.3.1) and on plant 3 with its columns
//!   lowered to 14 m (Experiment 4.3.2), next to the thesis' values.
//! - Table 4.14: the three C-space strategies on a 376k-triangle plant.
//! - The demo lift: MSPGA, Ali et al.'s fitness, RRT-Connect and PRM on the
//!   same checker and validator, then the three C-space strategies.
//! - The validator between its samples: what confirming the clearance along
//!   the whole motion costs on the plants above (reports/validator.md).
//!
//! Every run is the product's own `plan_lift`: the planner both ways round,
//! shortcut, and the independent validator; a run succeeds when a validated
//! plan comes back. The thesis rows run the GA once each way (`restarts = 0`);
//! a third row per plant is the planner as shipped (up to 2 restarts). The
//! plants are described in the code; they are built like the thesis' figures,
//! not copied from its models (which are not published).

use crate::validate::World;
use crate::{LiftPlan, Planner, Settings, Site, plan_lift};
use liftplan_core::capacity::CapacityTable;
use liftplan_core::crane::builtin;
use liftplan_core::lift::{LiftSpec, LiftTask};
use liftplan_core::mesh::TriMesh;
use liftplan_cspace::Joint;
use liftplan_depthmap::mdm::Mdm;
use std::path::Path;
use std::time::Instant;

struct Plant {
    name: &'static str,
    what: &'static str,
    mesh: TriMesh,
    task: LiftTask,
    /// The thesis' Table 4.11 success rates (Ali, MSPGA), %.
    published: Option<(f64, f64)>,
}

fn add_box(m: &mut TriMesh, name: &str, lo: [f64; 3], hi: [f64; 3]) {
    let g = m.group_id(name);
    m.add_box(g, lo, hi);
}

/// Box `[x0, x1] x [y0, y1] x [0, top]` placed at bearing `deg` and radius `r`
/// from the crane (its centre), axis-aligned.
fn unit_at(m: &mut TriMesh, name: &str, deg: f64, r: f64, half: [f64; 2], bottom: f64, top: f64) {
    let (x, y) = (r * deg.to_radians().cos(), r * deg.to_radians().sin());
    add_box(m, name, [x - half[0], y - half[1], bottom], [x + half[0], y + half[1], top]);
}

/// A lift from bearing/radius/height `pick` to `set` (degrees, m, m), the
/// slewing range limited to the short way round as in the thesis' experiments.
fn task(id: &str, pick: (f64, f64, f64), set: (f64, f64, f64)) -> LiftTask {
    let at = |deg: f64, r: f64| (r * deg.to_radians().cos(), r * deg.to_radians().sin());
    let (px, py) = at(pick.0, pick.1);
    let (sx, sy) = at(set.0, set.1);
    // The carrier stands along y (heading 90°), clear of the rows along x;
    // the slewing range is relative to it.
    let (lo, hi) = (pick.0.min(set.0) - 15.0 - 90.0, pick.0.max(set.0) + 15.0 - 90.0);
    let text = format!(
        r#"
id = "{id}"
load = {{ name = "skid", mass_t = 8.0, size_m = [6.0, 3.0, 2.5], cog_m = [0.0, 0.0, 0.0] }}
rigging = {{ mass_t = 0.3, height_m = 3.0 }}
crane = {{ model = "ac-700", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 90.0, boom_m = 62.4, chart_config = "none" }}
pick = {{ x_m = {px}, y_m = {py}, z_m = {}, yaw_deg = {} }}
set = {{ x_m = {sx}, y_m = {sy}, z_m = {}, yaw_deg = {} }}
clearance_m = 1.0
liftoff_m = 0.5
swing_range_deg = [{lo}, {hi}]
"#,
        pick.2, pick.0, set.2, set.0
    );
    let spec: LiftSpec = toml::from_str(&text).expect("lift");
    spec.resolve(builtin("ac-700").expect("ac-700")).expect("lift resolves")
}

fn slab(m: &mut TriMesh) {
    add_box(m, "GRADE", [-80.0, -80.0, -0.3], [80.0, 80.0, 0.0]);
}

/// Plant 1: a row of process units along the +x axis, from 8 m to 62 m out,
/// between pick (bearing -45°) and set (48°): the load goes over a unit.
fn plant1() -> Plant {
    let mut m = TriMesh::default();
    slab(&mut m);
    for (k, top) in [12.0, 15.0, 18.0, 21.0, 16.0, 14.0].iter().enumerate() {
        let x0 = 8.0 + 9.0 * k as f64;
        add_box(&mut m, &format!("UNIT-{}", k + 1), [x0, -3.5, 0.0], [x0 + 9.0, 3.5, *top]);
    }
    unit_at(&mut m, "SHELTER", -20.0, 34.0, [3.0, 3.0], 0.0, 6.0);
    unit_at(&mut m, "PIPE-RACK", 25.0, 30.0, [1.5, 6.0], 6.0, 8.0);
    Plant {
        name: "Plant 1",
        what: "a row of six process units 12-21 m high from 8 to 62 m out between pick and set, a pipe rack \
               and a shelter; 93° swing, pick and set at grade",
        mesh: m,
        task: task("P1", (-45.0, 24.0, 0.5), (48.0, 24.0, 0.5)),
        published: Some((8.0, 100.0)),
    }
}

/// Plant 2: the set position on a structure higher than the obstacles between.
fn plant2() -> Plant {
    let mut m = TriMesh::default();
    slab(&mut m);
    add_box(&mut m, "PIPE-RACK", [8.0, -1.5, 0.0], [62.0, 1.5, 14.0]);
    unit_at(&mut m, "VESSEL-1", -30.0, 25.0, [3.0, 3.0], 0.0, 14.0);
    unit_at(&mut m, "VESSEL-2", 35.0, 25.0, [3.0, 3.0], 0.0, 14.0);
    unit_at(&mut m, "STRUCTURE", 71.0, 26.0, [5.0, 5.0], 0.0, 18.0);
    Plant {
        name: "Plant 2",
        what: "a 14 m pipe rack from 8 to 62 m out and two 14 m vessels between pick and set; the set is \
               on top of an 18 m structure; 131° swing",
        mesh: m,
        task: task("P2", (-60.0, 24.0, 0.5), (71.0, 26.0, 18.0)),
        published: Some((88.0, 100.0)),
    }
}

/// Plant 3: obstacles much higher than pick and set.
fn plant3() -> Plant {
    plant3_with_columns(32.0)
}

/// Plant 3 with its columns `top` metres high (Experiment 4.3.2 lowers them
/// so that the crane need not raise its boom over them).
fn plant3_with_columns(top: f64) -> Plant {
    let mut m = TriMesh::default();
    slab(&mut m);
    for k in 0..6 {
        let x0 = 8.0 + 9.0 * k as f64;
        add_box(&mut m, &format!("COLUMN-{}", k + 1), [x0, -2.5, 0.0], [x0 + 9.0, 2.5, top]);
    }
    unit_at(&mut m, "BRIDGE", -20.0, 16.0, [1.0, 5.0], 10.0, 11.0);
    Plant {
        name: if top >= 30.0 { "Plant 3" } else { "Plant 3, lower columns" },
        what: if top >= 30.0 {
            "a row of 32 m columns from 8 to 62 m out between pick and set, and a pipe bridge; 83° swing, \
             pick and set at grade"
        } else {
            "plant 3 with its columns 14 m high (Experiment 4.3.2)"
        },
        mesh: m,
        task: task("P3", (-40.0, 22.0, 0.5), (43.0, 24.0, 0.5)),
        published: if top >= 30.0 { Some((0.0, 96.0)) } else { None },
    }
}

/// The Table 4.14 plant: ~376k triangles (31,334 boxes) in a ring 14-60 m
/// around the crane, up to 25 m high, with pick and set pads kept clear.
fn plant_414() -> Plant {
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(376);
    let mut m = TriMesh::default();
    slab(&mut m);
    let t = task("P4", (-45.0, 24.0, 0.5), (45.0, 24.0, 0.5));
    let pad = |c: &liftplan_core::crane::Config| {
        let b = t.crane.load_obb(c, &t.load);
        ([b.center.x, b.center.y], 8.0)
    };
    let pads = [pad(&t.pick), pad(&t.set)];
    let mut placed = 0;
    while placed < 31_333 {
        let (r, a) = (14.0 + rng.random::<f64>() * 46.0, rng.random::<f64>() * std::f64::consts::TAU);
        let c = [r * a.cos(), r * a.sin(), rng.random::<f64>() * 25.0];
        // The crane's carrier (20.5 m) and outriggers stand along y.
        if c[0].abs() < 8.0 && c[1].abs() < 16.0 {
            continue;
        }
        if pads.iter().any(|(p, d)| (c[0] - p[0]).hypot(c[1] - p[1]) < *d) {
            continue;
        }
        let h = [0.2 + rng.random::<f64>() * 1.5, 0.2 + rng.random::<f64>() * 1.5, 0.2 + rng.random::<f64>() * 1.5];
        let g = m.group_id(&format!("ITEM-{}", placed / 100));
        m.add_box(g, [c[0] - h[0], c[1] - h[1], (c[2] - h[2]).max(0.0)], [c[0] + h[0], c[1] + h[1], c[2] + h[2]]);
        placed += 1;
    }
    Plant {
        name: "Table 4.14 plant",
        what: "31,333 boxes in a ring 14-60 m around the crane, up to 26.5 m high, the crane's set-up area and pick and set pads (8 m) clear; 90° swing",
        mesh: m,
        task: t,
        published: None,
    }
}

fn map(mesh: &TriMesh) -> Mdm {
    let inp = liftplan_depthmap::Inputs { points: vec![], ground: vec![], mesh: mesh.clone() };
    liftplan_depthmap::build_cpu(&inp, &liftplan_depthmap::Settings::default()).expect("depth map").0
}

/// Motion units of a plan (swing deg, luff deg, hoist m, rotation deg) and its steps.
fn units(p: &LiftPlan) -> ([f64; 4], usize) {
    let mut u = [0.0; 4];
    for mv in &p.moves {
        let d = mv.delta().abs();
        match mv.joint {
            Joint::Swing => u[0] += d.to_degrees(),
            Joint::Radial => u[1] += d.to_degrees(),
            Joint::Hoist => u[2] += d,
            Joint::Rotate => u[3] += d.to_degrees(),
        }
    }
    (u, p.steps.len())
}

struct Tally {
    ok: usize,
    runs: usize,
    units: [f64; 4],
    steps: f64,
    fitness: f64,
    seconds: f64,
}

fn run_many(plant: &Plant, map: &Mdm, world: &World, s: &Settings, runs: u64) -> Tally {
    let site = Site { map, world, charts: None };
    let mut t = Tally { ok: 0, runs: runs as usize, units: [0.0; 4], steps: 0.0, fitness: 0.0, seconds: 0.0 };
    for seed in 0..runs {
        let t0 = Instant::now();
        let r = plan_lift(&plant.task, &site, s, seed);
        t.seconds += t0.elapsed().as_secs_f64();
        if let Err(e) = &r {
            eprintln!("{} seed {seed}: {e}", plant.name);
        }
        if let Ok((p, _)) = r {
            t.ok += 1;
            let (u, n) = units(&p);
            for k in 0..4 {
                t.units[k] += u[k];
            }
            t.steps += n as f64;
            // The thesis reports eq. 4.21's value for feasible strings.
            t.fitness += crate::mspga::feasible_fitness(&s.ga, p.planning.fitness);
        }
    }
    t
}

fn pct(t: &Tally) -> f64 {
    100.0 * t.ok as f64 / t.runs.max(1) as f64
}

/// Tables 4.11/4.12 (`runs` seeds per row) and the rate grids of Tables
/// 4.15-4.18 (`grid_runs` seeds per cell; 0 skips them).
pub fn thesis_tables(runs: u64, grid_runs: u64) {
    let plants = [plant1(), plant2(), plant3()];
    println!("# Planner: the thesis' experiments (Tables 4.11-4.18) and the baselines\n");
    println!(
        "Machine: {} threads. AC 700 with a 62.4 m boom (the thesis' boom length), 8 t skid 6 x 3 x 2.5 m, \
         1 m clearance, no load chart (geometry only). GA parameters of Table 4.10: population 100, string \
         length 6, rc 0.15, rm 0.75, at most 400 generations (stopping after 120 without improvement). \
         A run succeeds when `plan_lift` returns a plan the independent validator accepted.\n",
        rayon::current_num_threads()
    );
    for p in &plants {
        println!("- {}: {} ({} triangles)", p.name, p.what, p.mesh.triangle_count());
    }
    println!(
        "- Plant 3, lower columns: plant 3 with its columns 14 m high instead of 32 m (Experiment 4.3.2: the crane need not raise its boom over them)"
    );
    if runs > 0 {
        println!("\n## Table 4.11 / 4.12: Ali et al.'s fitness vs MSPGA, {runs} runs each\n");
        println!(
            "| plant | fitness | success | published | swing ° | luff ° | hoist m | rotation ° | steps | s per run |"
        );
        println!("|---|---|---|---|---|---|---|---|---|---|");
    }
    let mut built = Vec::new();
    for p in &plants {
        let m = map(&p.mesh);
        let world = World::new(&p.mesh, &[], &[]).expect("world");
        let rows = [
            (Planner::AliGa, "Ali et al.", p.published.map(|v| v.0), 0),
            (Planner::Mspga, "MSPGA", p.published.map(|v| v.1), 0),
            (Planner::Mspga, "MSPGA + 2 restarts (shipped)", None, 2),
        ];
        for (planner, label, published, restarts) in rows {
            if runs == 0 {
                continue;
            }
            let mut s = Settings { planner, ..Settings::default() };
            s.ga.restarts = restarts;
            let published = published.map(|v| format!("{v:.0} %")).unwrap_or_else(|| "-".into());
            let t = run_many(p, &m, &world, &s, runs);
            let n = t.ok.max(1) as f64;
            let q = |v: f64| if t.ok == 0 { "-".to_string() } else { format!("{:.1}", v / n) };
            println!(
                "| {} | {label} | {:.0} % ({}/{}) | {published} | {} | {} | {} | {} | {} | {:.1} |",
                p.name,
                pct(&t),
                t.ok,
                t.runs,
                q(t.units[0]),
                q(t.units[1]),
                q(t.units[2]),
                q(t.units[3]),
                q(t.steps),
                t.seconds / t.runs as f64
            );
        }
        built.push((m, world));
    }
    if grid_runs == 0 {
        return;
    }
    let low = plant3_with_columns(14.0);
    let built_low = (map(&low.mesh), World::new(&low.mesh, &[], &[]).expect("world"));
    // Tables 4.15-4.18: the thesis' grid of rates on plant 3 (Experiment 4.3.1)
    // and on plant 3 with lower columns (4.3.2), one GA run each way per plan.
    let experiments = [
        ("4.15 / 4.16", "Experiment 4.3.1, plant 3", &plants[2], &built[2], &THESIS_4_15, &THESIS_4_16),
        ("4.17 / 4.18", "Experiment 4.3.2, plant 3 with 14 m columns", &low, &built_low, &THESIS_4_17, &THESIS_4_18),
    ];
    for (tables, what, plant, (m, world), thesis_success, thesis_fitness) in experiments {
        let mut success = [[0.0; 6]; 6];
        let mut fitness = [[f64::NAN; 6]; 6];
        for (a, &rc) in RATES.iter().enumerate() {
            for (b, &rm) in RATES.iter().enumerate() {
                let mut s = Settings::default();
                s.ga.restarts = 0;
                s.ga.crossover_rate = rc;
                s.ga.mutation_rate = rm;
                let t = run_many(plant, m, world, &s, grid_runs);
                success[a][b] = t.ok as f64 / t.runs as f64;
                if t.ok > 0 {
                    fitness[a][b] = t.fitness / t.ok as f64;
                }
            }
        }
        println!("\n## Tables {tables}: crossover and mutation rates, {what}, {grid_runs} runs per cell");
        println!("\nEach cell: ours (thesis, 50 runs on its own plant).");
        grid_table("Probability of a feasible (validated) plan:", &success, thesis_success, 2);
        grid_table("Mean fitness (eq. 4.21) of the feasible plans:", &fitness, thesis_fitness, 1);
    }
}

/// The thesis' crossover and mutation rates (Tables 4.15-4.18).
const RATES: [f64; 6] = [0.05, 0.15, 0.25, 0.40, 0.55, 0.75];

/// Cai 2016 Tables 4.15-4.18, rows rc, columns rm, in the order of `RATES`.
const THESIS_4_15: [[f64; 6]; 6] = [
    [0.18, 0.42, 0.62, 0.68, 0.86, 0.94],
    [0.12, 0.32, 0.56, 0.76, 0.9, 0.92],
    [0.2, 0.38, 0.72, 0.7, 0.82, 1.0],
    [0.2, 0.36, 0.72, 0.66, 0.88, 0.88],
    [0.18, 0.46, 0.6, 0.74, 0.76, 0.72],
    [0.12, 0.12, 0.32, 0.32, 0.5, 0.54],
];
const THESIS_4_16: [[f64; 6]; 6] = [
    [2621.57, 2641.26, 2697.87, 2695.51, 2669.43, 2687.2],
    [2583.56, 2689.6, 2690.29, 2695.53, 2661.03, 2680.24],
    [2671.82, 2691.26, 2690.43, 2680.13, 2698.68, 2695.71],
    [2690.81, 2698.15, 2693.12, 2683.36, 2687.22, 2693.53],
    [2676.43, 2688.1, 2683.17, 2668.07, 2673.2, 2678.88],
    [2692.9, 2659.97, 2673.0, 2684.72, 2673.45, 2677.55],
];
const THESIS_4_17: [[f64; 6]; 6] = [
    [0.26, 0.46, 0.64, 0.7, 0.82, 0.86],
    [0.14, 0.42, 0.7, 0.82, 0.84, 0.94],
    [0.26, 0.64, 0.58, 0.84, 0.96, 0.96],
    [0.24, 0.54, 0.7, 0.78, 0.9, 0.98],
    [0.26, 0.38, 0.56, 0.66, 0.88, 0.86],
    [0.08, 0.44, 0.54, 0.42, 0.46, 0.6],
];
const THESIS_4_18: [[f64; 6]; 6] = [
    [2732.36, 2816.53, 2878.26, 2894.7, 2852.79, 2898.74],
    [2873.98, 2884.97, 2889.7, 2912.74, 2892.72, 2887.05],
    [2792.33, 2876.66, 2872.2, 2887.83, 2892.21, 2888.91],
    [2845.68, 2844.28, 2875.95, 2885.69, 2879.5, 2871.27],
    [2797.59, 2748.11, 2808.0, 2870.67, 2871.94, 2874.16],
    [2841.87, 2839.74, 2834.0, 2846.18, 2832.1, 2862.73],
];

/// One rc x rm table, ours next to the thesis'.
fn grid_table(title: &str, ours: &[[f64; 6]; 6], thesis: &[[f64; 6]; 6], digits: usize) {
    println!("\n{title}\n");
    print!("| |");
    for rm in RATES {
        print!(" rm = {rm:.2} |");
    }
    println!();
    println!("|---|{}", "---|".repeat(RATES.len()));
    for (a, rc) in RATES.iter().enumerate() {
        print!("| rc = {rc:.2} |");
        for b in 0..RATES.len() {
            let v = ours[a][b];
            let mine = if v.is_nan() { "-".to_string() } else { format!("{v:.digits$}") };
            print!(" {mine} ({:.digits$}) |", thesis[a][b]);
        }
        println!();
    }
}

/// Table 4.14: the three C-space strategies under MSPGA with 200 generations.
pub fn table_414(runs: u64) {
    use liftplan_cspace::Strategy;
    let p = plant_414();
    let t0 = Instant::now();
    let m = map(&p.mesh);
    let map_ms = t0.elapsed().as_secs_f64() * 1e3;
    let world = World::new(&p.mesh, &[], &[]).expect("world");
    let site = Site { map: &m, world: &world, charts: None };
    println!("## Table 4.14: C-space strategies, {runs} runs each\n");
    println!(
        "{} ({} triangles; depth map {map_ms:.0} ms). MSPGA, population 100, 200 generations (no early stop), \
         one GA run each way (restarts 0); plan ms is both swing directions, the shortcut and the planner's own \
         check, without the validator; a run succeeds when the validator accepts the plan. {} threads.\n",
        p.what,
        p.mesh.triangle_count(),
        rayon::current_num_threads()
    );
    println!(
        "| strategy | prep ms | plan ms | success | mean fitness (eq. 4.21) | mean motion cost | table lookups per plan | box queries per plan | thesis prep ms | thesis plan ms | thesis success | thesis fitness |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    // Strategy, and the thesis' prep ms, plan ms, success and mean fitness (its "C-space" is our `full`).
    let rows = [
        (Strategy::Full, "10,535", "789", "66 %", "3611.1"),
        (Strategy::Online, "0", "3,999", "93 %", "3943.7"),
        (Strategy::Hybrid, "1,034", "2,134", "92 %", "3965.8"),
    ];
    for (strategy, tp, tl, ts, tf) in rows {
        let mut s = Settings::default();
        s.cspace.strategy = strategy;
        s.ga.max_generations = 200;
        s.ga.stall_generations = 200;
        s.ga.restarts = 0;
        let (mut ok, mut prep, mut plan, mut cost, mut fitness) = (0, 0.0, 0.0, 0.0, 0.0);
        let (mut lookups, mut queries) = (0, 0);
        for seed in 0..runs {
            match plan_lift(&p.task, &site, &s, seed) {
                Ok((lp, cs)) => {
                    ok += 1;
                    cost += lp.planning.motion_cost;
                    // `planning.fitness` is eq. 4.21's motion term m.
                    fitness += crate::mspga::feasible_fitness(&s.ga, lp.planning.fitness);
                    prep += cs.build_ms;
                    plan += lp.planning.plan_ms - cs.build_ms;
                    lookups += lp.planning.table_lookups;
                    queries += lp.planning.box_queries;
                }
                Err(e) => eprintln!("{strategy:?} seed {seed}: {e}"),
            }
        }
        let k = ok.max(1) as f64;
        println!(
            "| {strategy:?} | {:.0} | {:.0} | {:.0} % ({ok}/{runs}) | {:.1} | {:.1} | {:.2e} | {:.2e} | {tp} | {tl} | {ts} | {tf} |",
            prep / k,
            plan / k,
            100.0 * ok as f64 / runs as f64,
            fitness / k,
            cost / k,
            lookups as f64 / k,
            queries as f64 / k,
        );
    }
}

/// What the validator's check between samples costs and finds: the planner
/// as shipped, `runs` seeds on each plant; for every validated plan, its
/// samples (evenly spaced, and added where two neighbours left room for a
/// part to come closer than its clearance between them), the validator's
/// time and the smallest clearance margin.
pub fn validator_table(runs: u64) {
    let plants = [plant1(), plant2(), plant3(), plant3_with_columns(14.0), plant_414()];
    let s = Settings::default();
    println!("## The validator between its samples, {runs} runs per plant\n");
    println!(
        "MSPGA as shipped, 1 m clearance, validator samples {} m of movement apart. Added: samples the validator \
         put between two neighbours whose distances left room for a part to come closer than its clearance \
         between them, halving the gap until the bound holds or the gap is 2 mm. Margin: the smallest \
         clearance less the requirement over every sample of every validated plan (the lift-off and set-down \
         steps require none). {} threads.\n",
        s.validator_sample_m,
        rayon::current_num_threads()
    );
    println!(
        "| plant | triangles | validated | samples per plan | added per plan | plans with samples added | most added in a plan | validator s per plan | slowest validation s | smallest margin mm |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for p in &plants {
        let m = map(&p.mesh);
        let world = World::new(&p.mesh, &[], &[]).expect("world");
        let site = Site { map: &m, world: &world, charts: None };
        let (mut ok, mut samples, mut added, mut with_added, mut most) = (0usize, 0usize, 0usize, 0usize, 0usize);
        let (mut seconds, mut slowest, mut margin) = (0.0, 0.0f64, f64::INFINITY);
        for seed in 0..runs {
            match plan_lift(&p.task, &site, &s, seed) {
                Ok((lp, _)) => {
                    let v = &lp.validator;
                    ok += 1;
                    samples += v.samples;
                    added += v.refined_samples;
                    with_added += usize::from(v.refined_samples > 0);
                    most = most.max(v.refined_samples);
                    seconds += v.seconds;
                    slowest = slowest.max(v.seconds);
                    for st in &lp.steps {
                        margin = margin.min(st.min_clearance_m - st.required_clearance_m);
                    }
                }
                Err(e) => eprintln!("{} seed {seed}: {e}", p.name),
            }
        }
        let k = ok.max(1) as f64;
        println!(
            "| {} | {} | {ok}/{runs} | {:.0} | {:.0} | {with_added} | {most} | {:.3} | {slowest:.3} | {:.0} |",
            p.name,
            p.mesh.triangle_count(),
            samples as f64 / k,
            added as f64 / k,
            seconds / k,
            margin * 1e3,
        );
    }
}

/// The first lift of a project that has been run once, and what planning it
/// reads: its map, the validator's world, its charts.
fn first_lift_of(dir: &Path) -> Result<(LiftTask, Mdm, World, Option<CapacityTable>), String> {
    let out = dir.join("out");
    let file = dir.join("liftplan.toml");
    let text = std::fs::read_to_string(&file).map_err(|e| format!("{}: {e}", file.display()))?;
    let v: toml::Value = toml::from_str(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    let lift = v
        .get("lift")
        .and_then(|l| l.as_array())
        .and_then(|l| l.first())
        .cloned()
        .ok_or_else(|| format!("{}: no [[lift]]", file.display()))?;
    let spec: LiftSpec = lift.try_into().map_err(|e| format!("{}: [[lift]]: {e}", file.display()))?;
    let model = liftplan_core::crane::builtin(&spec.crane.model)
        .map_err(|e| format!("{}: crane {}: {e}", file.display(), spec.crane.model))?;
    let task = spec.resolve(model).map_err(|e| format!("{}: {e}", file.display()))?;
    let map = Mdm::read(&out.join("site.mdm")).map_err(|e| e.to_string())?;
    let mesh = TriMesh::read_artifact(&out.join("plant.mesh")).unwrap_or_default();
    let excl = crate::load_exclusions(std::slice::from_ref(&task), crate::Settings::default().load_cutout_m);
    let (pts, ground, _) = crate::read_points(&out.join("site.laz"), &excl).map_err(|e| e.to_string())?;
    let world = World::new(&mesh, &pts, &ground)?;
    let charts = CapacityTable::read_csv(&out.join("capacity.csv")).ok();
    Ok((task, map, world, charts))
}

/// MSPGA against Ali et al.'s fitness, RRT-Connect and PRM (`seeds` each), then
/// the three C-space strategies, on the first lift of a project that has been
/// run once (the demo project: `liftplan demo DIR`).
pub fn demo_lift(dir: &Path, seeds: u64) -> Result<(), String> {
    let (task, map, world, charts) = first_lift_of(dir)?;
    let site = Site { map: &map, world: &world, charts: charts.as_ref() };
    println!("## Demo lift: MSPGA and the baselines (lift {})\n", task.id);
    println!(
        "Machine: {} threads. Same inputs, same checker (hybrid C-space), same validator; {seeds} seeds each. \
         Motion cost is the thesis' weighted units (swing 1/deg, luff 1.5/deg, hoist 0.06/cm, rotate 1/deg); \
         joint switches are the changes of moving joint along the path (the thesis' sc); time includes validation.\n",
        rayon::current_num_threads()
    );
    println!("| planner | success | mean cost | mean steps | mean joint switches | mean time s | validator ok |");
    println!("|---|---|---|---|---|---|---|");
    for planner in [Planner::Mspga, Planner::AliGa, Planner::RrtConnect, Planner::Prm] {
        let mut s = Settings { planner, ..Settings::default() };
        s.ga.max_generations = 400;
        let (mut ok, mut cost, mut steps, mut switches, mut time, mut valid) = (0, 0.0, 0.0, 0.0, 0.0, 0);
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
                    switches += p.planning.switches as f64;
                    valid += usize::from(p.validator.ok);
                }
                Err(e) => eprintln!("{planner:?} seed {seed}: {e}"),
            }
        }
        let k = ok.max(1) as f64;
        println!(
            "| {planner:?} | {ok}/{seeds} | {:.1} | {:.1} | {:.1} | {:.2} | {valid}/{ok} |",
            cost / k,
            steps / k,
            switches / k,
            time / seeds as f64
        );
    }
    println!("\n## Demo lift: C-space strategies (MSPGA, seed 0)\n");
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
    Ok(())
}

/// Re-planning when the site changes part way through a lift (Zhang &
/// Hammad 2012, §5.2), on the first lift of a project that has been run once
/// (the demo project), `seeds` times: the lift is planned (seed s); a tower
/// is put where the load is half way through the plan's longest swing, from
/// the ground to 2 m above the load's top (3 x 3 m, an obstacle placed by
/// hand); the lift is resumed from where that swing starts, the crane
/// stopped there. Timed side by side in one run: the first plan, the re-plan
/// from where the load hangs, and a plan from the pick with the tower. Each
/// is the product's `plan_lift` (C-space build, search, validation).
pub fn replanning(dir: &Path, seeds: u64) -> Result<(), String> {
    let (task, map, mut world, charts) = first_lift_of(dir)?;
    let s = Settings::default();
    println!("## Re-planning part way through the demo lift (lift {})\n", task.id);
    println!(
        "Machine: {} threads. Per seed: the lift planned from its pick; a 3 x 3 m tower put where the load is half way \
         through that plan's longest swing (from the ground to 2 m above the load's top); the lift resumed from where \
         that swing starts, with the tower (`resume_from` and `[[obstacle]]`); and, for comparison, planned from its \
         pick with the tower. Times are `plan_lift`'s: the C-space for the changed site, the search both ways round, \
         the shortcut and the independent validator. Zhang & Hammad 2012 (Table 5) report 1.47 s on average for their \
         DRRT-Con-Con-Mod re-planning (5.98 s for DRRT), on another site (a 596-element steel structure, a second \
         crane as the obstacle) and a 1.83 GHz dual-core: a figure to set beside, not the same question.\n",
        rayon::current_num_threads()
    );
    println!(
        "| seed | first plan s | tower on its path | re-plan from where the load hangs s | steps | from the pick with the tower s | steps | re-plan / from the pick |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let (mut replans, mut replan_s, mut replan_max_s, mut full_s, mut full_ok) = (0, 0.0, 0.0f64, 0.0, 0);
    let timed = |t: &LiftTask, site: &Site, seed: u64| {
        let t0 = Instant::now();
        let r = plan_lift(t, site, &s, seed);
        (r, t0.elapsed().as_secs_f64())
    };
    for seed in 0..seeds {
        world.others.clear();
        let (first, first_s) = timed(&task, &Site { map: &map, world: &world, charts: charts.as_ref() }, seed);
        let first = match first {
            Ok((p, _)) => p,
            Err(e) => {
                println!("| {seed} | {first_s:.2} (failed) | - | - | - | - | - | - |");
                eprintln!("seed {seed}: first plan: {e}");
                continue;
            }
        };
        let Some(swing) = first.moves.iter().filter(|m| m.joint == Joint::Swing).max_by(|a, b| {
            (a.to.swing_rad - a.from.swing_rad).abs().total_cmp(&(b.to.swing_rad - b.from.swing_rad).abs())
        }) else {
            println!("| {seed} | {first_s:.2} | no swing | - | - | - | - | - |");
            continue;
        };
        let half_way = {
            let (a, b) = (swing.from.to_array(), swing.to.to_array());
            liftplan_core::crane::Config::from_array(std::array::from_fn(|k| (a[k] + b[k]) / 2.0))
        };
        let load = task.crane.load_obb(&half_way, &task.load).aabb();
        let (cx, cy) = ((load.min[0] + load.max[0]) / 2.0, (load.min[1] + load.max[1]) / 2.0);
        let ground = task.crane.placement.z_m;
        let tower = liftplan_core::obstacle::Obstacle {
            name: "tower".into(),
            center_m: [cx, cy],
            base_z_m: ground,
            size_m: [3.0, 3.0, load.max[2] + 2.0 - ground],
            yaw_deg: 0.0,
            lifts: vec![],
        };
        let boxes = liftplan_core::obstacle::boxes_during(std::slice::from_ref(&tower), &task.id);
        let with_tower = map.with_boxes(&boxes);
        world.others = boxes;
        let site_with = Site { map: &with_tower, world: &world, charts: charts.as_ref() };
        // The first plan must meet the tower: else it stands nowhere on its path.
        let landing = crate::landing_moves(&task, first.moves.len());
        let rules = crate::validate_rules(&task, &s, &crate::landing_zones(&task, &s));
        let meets = crate::validate::validate_lift(&task, None, &world, &rules, &first.moves, &landing)
            .problems
            .iter()
            .any(|p| p.contains("obstacle 'tower'"));
        let resumed =
            LiftTask { resume_from: Some((swing.from, task.crane.load_pose(&swing.from, &task.load))), ..task.clone() };
        let (re, re_s) = timed(&resumed, &site_with, seed);
        let (full, f_s) = timed(&task, &site_with, seed);
        let said = |r: &crate::Result<(LiftPlan, liftplan_cspace::CSpace)>| match r {
            Ok((p, _)) => p.steps.len().to_string(),
            Err(_) => "failed".to_string(),
        };
        if re.is_ok() {
            replans += 1;
            replan_s += re_s;
            replan_max_s = replan_max_s.max(re_s);
        }
        if full.is_ok() {
            full_ok += 1;
            full_s += f_s;
        }
        for (what, r) in [("re-plan", &re), ("from the pick", &full)] {
            if let Err(e) = r {
                eprintln!("seed {seed}: {what}: {e}");
            }
        }
        println!(
            "| {seed} | {first_s:.2} | {} | {re_s:.2} | {} | {f_s:.2} | {} | {:.2} |",
            if meets { "yes" } else { "no" },
            said(&re),
            said(&full),
            re_s / f_s.max(1e-9)
        );
    }
    println!(
        "\nRe-planned {replans}/{seeds} (mean {:.2} s, at most {replan_max_s:.2} s); planned from the pick with the tower {full_ok}/{seeds} (mean {:.2} s). \
         Mean re-plan against Zhang & Hammad's 1.47 s: {:.2}.",
        replan_s / replans.max(1) as f64,
        full_s / full_ok.max(1) as f64,
        replan_s / replans.max(1) as f64 / 1.47
    );
    Ok(())
}
