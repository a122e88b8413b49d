//! Times the search for line-like scan points (`wires::find`, once a run of
//! the plan stage) on a site of walls, ground and stray points, with and
//! without a wire strung through it, and says what it found; beside it, in
//! the same run on the same points, the validator's index of the site
//! points (`validate::PointIndex`), which the plan stage builds anyway, as
//! the yardstick of the ratio.
//!
//! `cargo run --release -p liftplan-plan --example bench_wires [N...]`
//! (millions of points; default 1 4). Each cloud: a fifth of its points on
//! a 120 x 120 m ground, three quarters on 20 walls 100 m long and 20 m
//! high, a twentieth strewn through the volume up to 25 m (at 4 M points,
//! two within a metre of a point of the wire on average: strays that break
//! it into pieces); the wire, 50 m long at 12 m with 5 cm between its
//! points, is added to the second run of each size.

use liftplan_core::rng::{index, seeded, uniform};
use liftplan_plan::validate::PointIndex;
use liftplan_plan::wires::find;

fn site(millions: f64) -> (Vec<[f64; 3]>, Vec<bool>) {
    let n = (millions * 1e6) as usize;
    let mut rng = seeded(1, "bench_wires");
    let (mut pts, mut ground) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for _ in 0..n / 5 {
        pts.push([uniform(&mut rng, -60.0, 60.0), uniform(&mut rng, -60.0, 60.0), 0.0]);
        ground.push(true);
    }
    for _ in 0..n * 3 / 4 {
        let x = -50.0 + 5.0 * index(&mut rng, 20) as f64;
        pts.push([x, uniform(&mut rng, -50.0, 50.0), uniform(&mut rng, 0.0, 20.0)]);
        ground.push(false);
    }
    for _ in 0..n / 20 {
        pts.push([uniform(&mut rng, -60.0, 60.0), uniform(&mut rng, -60.0, 60.0), uniform(&mut rng, 0.0, 25.0)]);
        ground.push(false);
    }
    (pts, ground)
}

fn main() {
    let sizes: Vec<f64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![1.0, 4.0] } else { sizes };
    println!("| points | wire | find ms | runs found | PointIndex::new ms | find / index |");
    println!("|---|---|---|---|---|---|");
    for m in sizes {
        let (mut pts, mut ground) = site(m);
        for wire in [false, true] {
            if wire {
                // Between two walls (x -47.5), clear of them by 2.5 m.
                for k in 0..=1000 {
                    pts.push([-47.5, -25.0 + k as f64 * 0.05, 12.0]);
                    ground.push(false);
                }
            }
            let t = std::time::Instant::now();
            let found = find(&pts, &ground, &[([0.0, 0.0], 80.0)], &[]);
            let ms = t.elapsed().as_secs_f64() * 1e3;
            let t = std::time::Instant::now();
            let index = PointIndex::new(&pts, &ground).expect("index");
            let index_ms = t.elapsed().as_secs_f64() * 1e3;
            println!(
                "| {} | {} | {ms:.0} | {} | {index_ms:.0} | {:.2} |",
                pts.len(),
                if wire { "yes" } else { "no" },
                found.len(),
                ms / index_ms
            );
            drop(index);
        }
    }
}
