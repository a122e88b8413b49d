//! The GPU point pass gives the same map as the CPU one. Runs where wgpu finds
//! an adapter (a GPU, or Mesa's lavapipe); says so plainly and passes otherwise.

use liftplan_depthmap::{Inputs, Settings, build, build_cpu, gpu};
use rand::{RngExt, SeedableRng};

fn cloud(n: usize, seed: u64) -> Inputs {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut inp = Inputs::default();
    for _ in 0..n {
        let (x, y) = (rng.random::<f64>() * 80.0 - 40.0, rng.random::<f64>() * 60.0 - 30.0);
        let z = if rng.random::<f64>() < 0.6 { 0.02 * x } else { rng.random::<f64>() * 25.0 };
        inp.points.push([x + 1000.0, y + 2000.0, z]);
        inp.ground.push(z < 0.02 * x + 0.01);
    }
    inp
}

#[test]
fn gpu_and_cpu_maps_are_equal() {
    let g = match gpu::open(true) {
        Ok(g) => g,
        Err(e) => {
            eprintln!("SKIPPED gpu_and_cpu_maps_are_equal: {e}");
            return;
        }
    };
    eprintln!("GPU twin test on {}", g.name());
    for (n, cell, radius) in [(50_000, 0.25, 0.05), (20_000, 0.1, 0.12), (1, 0.5, 0.0)] {
        let inp = cloud(n, n as u64);
        let s = Settings { cell_m: cell, point_radius_m: radius, ..Settings::default() };
        let (cpu, _) = build_cpu(&inp, &s).unwrap();
        let (gpu, _) = build(&inp, &s, Some(&g)).unwrap();
        assert_eq!(cpu, gpu, "maps differ for {n} points, cell {cell}, radius {radius}");
    }
}
