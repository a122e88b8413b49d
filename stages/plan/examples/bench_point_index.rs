//! Times the validator's index of site points (`validate::PointIndex`, points
//! sorted by 1 m voxel) against the hash map of growing lists it replaced (one
//! push per point, copied here as it was), on the same points in one run.
//!
//! `cargo run --release -p liftplan-plan --example bench_point_index [N...]`
//! (millions of points; default 1 5 10). Two clouds per size: points spread
//! through a 200 x 200 x 30 m volume, and points on surfaces as a thinned scan
//! has them (a 200 x 200 m ground and 40 walls 15 m high).

use liftplan_plan::validate::PointIndex;
use std::collections::HashMap;

/// The index before: each point pushed onto its voxel's list.
fn hashed(points: &[[f64; 3]], ground: &[bool]) -> HashMap<[i32; 3], Vec<([f64; 3], bool)>> {
    let mut cells: HashMap<[i32; 3], Vec<([f64; 3], bool)>> = HashMap::new();
    for (p, g) in points.iter().zip(ground) {
        let key = [p[0].floor() as i32, p[1].floor() as i32, p[2].floor() as i32];
        cells.entry(key).or_default().push((*p, *g));
    }
    cells
}

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![1, 5, 10] } else { sizes };
    let mut s: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut u = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    println!("| cloud | points | voxels | hash map of lists s | sorted index s | ratio |");
    println!("|---|---|---|---|---|---|");
    for m in sizes {
        let n = m * 1_000_000;
        for cloud in ["volume", "surfaces"] {
            let points: Vec<[f64; 3]> = (0..n)
                .map(|k| match cloud {
                    "volume" => [u() * 200.0, u() * 200.0, u() * 30.0],
                    _ if k % 3 == 0 => [(k % 40) as f64 * 5.0 + 0.2 * u(), u() * 200.0, u() * 15.0],
                    _ => [u() * 200.0, u() * 200.0, 0.05 * u()],
                })
                .collect();
            let ground: Vec<bool> = points.iter().map(|p| p[2] < 0.1).collect();
            let t = std::time::Instant::now();
            let before = hashed(&points, &ground);
            let t_before = t.elapsed().as_secs_f64();
            let t = std::time::Instant::now();
            let now = PointIndex::new(&points, &ground).expect("the index");
            let t_now = t.elapsed().as_secs_f64();
            assert_eq!(now.voxels(), before.len());
            println!("| {cloud} | {n} | {} | {t_before:.2} | {t_now:.2} | {:.1} |", before.len(), t_before / t_now);
        }
    }
}
