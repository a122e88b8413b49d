//! Soak test of the GPU depth-map assembly and box queries against the
//! CPU's: random sites (points, loose triangles and boxes; heights often on a
//! 1/16 m lattice, so ties and exact touching are common), cell sizes, radii,
//! gaps, modes and buffer limits (so slabs are cut and uploads chunked), for
//! as long as asked:
//!
//!   cargo run --release -p liftplan-depthmap --example stress_gpu -- [seconds]
//!
//! On each map, random crane-part boxes and boxes on the 1/16 m lattice (and
//! those a thousandth of a millimetre higher and lower) are queried on the
//! device and on the CPU, with and without the ground left out (all of it, or up to a height): box queries,
//! and vertical clearances down and up.
//!
//! Prints each map and each query answer that differs and each map the device
//! refuses (a row over a small buffer limit, or lavapipe's loop cap), then a
//! summary; exits with an error when anything differs. The test suite's
//! `tests/gpu_twin.rs` covers the same ground in seconds; this is for a long
//! run on a device machine.

use liftplan_core::frame::Vec3;
use liftplan_core::obb::Obb;
use liftplan_depthmap::mdm::{self, Mode, PointSource, Raw};
use liftplan_depthmap::query::{LeaveOut, Vertical};
use liftplan_depthmap::{Inputs, Settings, build_cpu, gpu};
use rand::{RngExt, SeedableRng};

#[path = "../tests/support/boxes.rs"]
mod boxes;

/// What the queries leave out: nothing, all the ground, and the ground up
/// to 5 m (a lattice height, which some intervals' tops meet exactly).
fn leave_outs() -> [Option<LeaveOut>; 3] {
    [None, Some(LeaveOut::object(mdm::OBJ_GROUND)), Some(LeaveOut::up_to(mdm::OBJ_GROUND, 5.0))]
}

fn main() {
    let mut g = gpu::open(true).unwrap();
    let seconds: u64 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(300);
    let t0 = std::time::Instant::now();
    let (mut case, mut compared, mut refused, mut differ) = (0u64, 0u64, 0u64, 0u64);
    let (mut queries, mut queries_differ, mut left_to_cpu) = (0u64, 0u64, 0u64);
    let (mut clearances, mut clearances_differ, mut clearance_left) = (0u64, 0u64, 0u64);
    while t0.elapsed().as_secs() < seconds {
        case += 1;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(case);
        let n = rng.random_range(0..40_000usize);
        let w = rng.random_range(1.0..60.0f64);
        let h = rng.random_range(1.0..60.0f64);
        let mut inp = Inputs::default();
        let quant = rng.random_bool(0.5);
        for _ in 0..n {
            let x = 500.0 + rng.random::<f64>() * w;
            let y = -300.0 + rng.random::<f64>() * h;
            let z = if quant { rng.random_range(-20..200) as f64 * 0.0625 } else { rng.random::<f64>() * 30.0 - 5.0 };
            inp.points.push([x, y, z]);
            inp.ground.push(rng.random_bool(0.3));
        }
        let tris = rng.random_range(0..200);
        let a = inp.mesh.group_id("a");
        let b = inp.mesh.group_id("b");
        for _ in 0..tris {
            let c = [500.0 + rng.random::<f64>() * w, -300.0 + rng.random::<f64>() * h, rng.random::<f64>() * 20.0];
            if rng.random_bool(0.5) {
                let t: Vec<[f64; 3]> = (0..3)
                    .map(|_| {
                        [c[0] + rng.random::<f64>() * 2.0, c[1] + rng.random::<f64>() * 2.0, c[2] + rng.random::<f64>()]
                    })
                    .collect();
                inp.mesh.add_part(a, false, &t, &[[0, 1, 2]]);
            } else {
                inp.mesh.add_box(
                    b,
                    c,
                    [
                        c[0] + rng.random::<f64>() * 3.0,
                        c[1] + rng.random::<f64>() * 3.0,
                        c[2] + 0.1 + rng.random::<f64>(),
                    ],
                );
            }
        }
        let cell: f64 = [0.05, 0.1, 0.25, 0.5, 1.0, 2.0, 5.0][rng.random_range(0..7)];
        let radius: f64 = [0.0f64, 0.01, 0.05, 0.0625, 0.12, 0.3][rng.random_range(0..6)].min(8.0 * cell);
        let gap = [0.0, 0.05, 0.1, 0.125, 0.5][rng.random_range(0..5)];
        let mode = if rng.random_bool(0.3) { Mode::Single } else { Mode::Multi };
        let s = Settings {
            cell_m: cell,
            point_radius_m: radius,
            merge_gap_m: gap,
            mode,
            margin_m: rng.random_range(0.0..3.0),
            ..Settings::default()
        };
        let Ok((cpu, _)) = build_cpu(&inp, &s) else { continue };
        let limit = [1u64 << 16, 1 << 20, u64::MAX][rng.random_range(0..3)];
        g.set_buffer_limit(limit);
        let points = PointSource { xyz: &inp.points, ground: &inp.ground, radius: radius as f32 };
        let mesh: Vec<Raw> = mdm::mesh_raws(&inp.mesh, &cpu.spec, 2).concat();
        match g.assemble(Some(&points), &mesh, &cpu.spec, mode, gap as f32) {
            Ok(cells) => {
                let m = mdm::Mdm::from_cells(
                    cpu.spec,
                    mode,
                    &cells.counts,
                    cells.intervals,
                    cells.tops,
                    cpu.objects.clone(),
                );
                compared += 1;
                if m != cpu {
                    differ += 1;
                    println!(
                        "MISMATCH case {case}: n {n} tris {tris} cell {cell} radius {radius} gap {gap} {mode:?} limit {limit} slabs {}",
                        cells.slabs
                    );
                }
            }
            Err(e) => {
                refused += 1;
                println!("case {case} refused: {e}");
            }
        }
        let centre = [500.0 + w / 2.0, -300.0 + h / 2.0];
        let spread = [w / 2.0 + 5.0, h / 2.0 + 5.0];
        let mut boxes: Vec<Obb> = (0..200)
            .map(|_| {
                let z = rng.random_range(-5.0..35.0);
                boxes::random_box(&mut rng, centre, spread, z)
            })
            .collect();
        for _ in 0..100 {
            let b = boxes::lattice_box(&mut rng, centre, spread, [-40, 420]);
            let moved = |dz: f64| Obb::axis_aligned(b.center + Vec3::new(0.0, 0.0, dz), b.half);
            boxes.extend([b, moved(1e-6), moved(-1e-6)]);
        }
        // The map goes up whole (small limits are for the assembly's slabs);
        // the boxes go up in batches under this case's limit.
        g.set_buffer_limit(u64::MAX);
        let uploaded = g.upload_map(&cpu);
        g.set_buffer_limit(limit);
        let on_gpu = match uploaded {
            Ok(m) => m,
            Err(e) => {
                println!("case {case}: map not uploaded for queries: {e}");
                continue;
            }
        };
        for leave in leave_outs() {
            match g.hits_where(&on_gpu, &cpu, &boxes, leave) {
                Ok((hits, counts)) => {
                    left_to_cpu += counts.left_to_cpu as u64;
                    for (k, b) in boxes.iter().enumerate() {
                        queries += 1;
                        let want = cpu.hit_where(b, |iv| LeaveOut::counts(leave, iv));
                        if hits[k] != want {
                            queries_differ += 1;
                            println!(
                                "QUERY MISMATCH case {case} box {k} leaving out {leave:?}: GPU {:?}, CPU {want:?}, {b:?}",
                                hits[k]
                            );
                        }
                    }
                }
                Err(e) => println!("case {case}: queries refused: {e}"),
            }
            for way in [Vertical::Down, Vertical::Up] {
                match g.clearances_where(&on_gpu, &cpu, &boxes, way, leave) {
                    Ok((found, counts)) => {
                        clearance_left += counts.left_to_cpu as u64;
                        for (k, b) in boxes.iter().enumerate() {
                            clearances += 1;
                            let want = cpu.clearance_where(b, way, |iv| LeaveOut::counts(leave, iv));
                            if found[k] != want {
                                clearances_differ += 1;
                                println!(
                                    "CLEARANCE MISMATCH case {case} box {k} {way:?} leaving out {leave:?}: GPU {:?}, \
                                     CPU {want:?}, {b:?}",
                                    found[k]
                                );
                            }
                        }
                    }
                    Err(e) => println!("case {case}: clearances refused: {e}"),
                }
            }
        }
    }
    println!(
        "{case} cases in {} s on {}: {compared} maps compared, {differ} differ, {refused} refused; \
         {queries} box queries compared, {queries_differ} differ ({left_to_cpu} answered by the CPU's exact test); \
         {clearances} clearances compared, {clearances_differ} differ ({clearance_left} answered by the CPU whole)",
        t0.elapsed().as_secs(),
        g.name()
    );
    if differ > 0 || queries_differ > 0 || clearances_differ > 0 {
        std::process::exit(1);
    }
}
