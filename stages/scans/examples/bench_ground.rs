//! Times ground classification (`liftplan_scans::ground::classify`) on
//! synthetic sites and prints a hash of its answer (every point's class and
//! the ground grid), so that a faster build can be checked to give the same.
//!
//! `cargo run --release -p liftplan-scans --example bench_ground [CELL_M]`

use liftplan_core::cloud::PointCloud;
use liftplan_scans::ground::{GroundSettings, classify};
use std::time::Instant;

/// A site of `side` metres: gently sloping ground with buildings and tanks
/// on it, `n` points, and, if `far` is given, a second patch of ground that
/// far away in x (two scans of one site taken far apart).
fn site(side: f64, n: usize, far: Option<f64>) -> PointCloud {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut xyz = Vec::with_capacity(n);
    for k in 0..n {
        let (mut x, y) = (rnd() * side, rnd() * side);
        if far.is_some() && k % 2 == 1 {
            x = x * 0.1 + far.unwrap_or(0.0);
        }
        let ground = 0.02 * x + 3.0 * (y / 80.0).sin();
        // Buildings on a 60 m pitch, 20 m across, 12 m tall; tanks between.
        let (bx, by) = (x.rem_euclid(60.0), y.rem_euclid(60.0));
        let z = if bx < 20.0 && by < 20.0 && rnd() < 0.6 {
            ground + 12.0 * rnd()
        } else if (bx - 40.0).hypot(by - 40.0) < 6.0 && rnd() < 0.5 {
            ground + 8.0 * rnd()
        } else {
            ground + 0.02 * rnd()
        };
        xyz.push([x, y, z]);
    }
    let len = xyz.len();
    PointCloud { xyz, intensity: vec![0; len], rgb: vec![[0; 3]; len], class: vec![0; len], scan: vec![0; len] }
}

fn main() {
    let cases: [(&str, f64, usize, Option<f64>, f64); 6] = [
        ("300 m site, 1 M points", 300.0, 1_000_000, None, 1.0),
        ("300 m site, 1 M points", 300.0, 1_000_000, None, 0.5),
        ("1 km site, 2 M points", 1000.0, 2_000_000, None, 1.0),
        ("1 km site, 2 M points", 1000.0, 2_000_000, None, 0.5),
        ("two 300 m patches 1.5 km apart, 1 M points", 300.0, 1_000_000, Some(1500.0), 1.0),
        ("1 km site, 8 M points", 1000.0, 8_000_000, None, 0.25),
    ];
    println!("| site | cell m | grid | seconds | ground points | answer hash |");
    println!("|---|---|---|---|---|---|");
    // An argument picks the cases whose cell size it names, e.g. `0.25`.
    let only: Option<f64> = std::env::args().nth(1).and_then(|a| a.parse().ok());
    for (name, side, n, far, cell_m) in cases {
        if only.is_some_and(|c| c != cell_m) {
            continue;
        }
        let mut cloud = site(side, n, far);
        let s = GroundSettings { cell_m, ..GroundSettings::default() };
        let t = Instant::now();
        let grid = classify(&mut cloud, &s).expect("within the grid bound");
        let secs = t.elapsed().as_secs_f64();
        let mut h = blake3::Hasher::new();
        h.update(&cloud.class);
        let size = match &grid {
            Some(g) => {
                for z in &g.z {
                    h.update(&z.to_bits().to_le_bytes());
                }
                format!("{} x {}", g.nx, g.ny)
            }
            None => "-".into(),
        };
        let ground = cloud.class.iter().filter(|&&c| c == 2).count();
        println!("| {name} | {cell_m} | {size} | {secs:.2} | {ground} | {} |", &h.finalize().to_hex()[..16]);
    }
}
