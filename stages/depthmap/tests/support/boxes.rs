//! Random crane-part boxes for the GPU query twin's tests and its soak run
//! (`examples/stress_gpu.rs` includes this file): shared so that both draw
//! the same kinds of box.

use liftplan_core::frame::{Point3, Vec3};
use liftplan_core::obb::Obb;
use rand::RngExt;

/// A random box centred within `spread` of `centre` (plan, m) at height `z`:
/// upright and turned about z, tilted any way, or a long thin boom at a
/// luffing angle.
pub fn random_box(rng: &mut rand_chacha::ChaCha8Rng, centre: [f64; 2], spread: [f64; 2], z: f64) -> Obb {
    use nalgebra::{Rotation3, Unit, Vector3};
    let center = Point3::new(
        centre[0] + rng.random_range(-spread[0]..spread[0]),
        centre[1] + rng.random_range(-spread[1]..spread[1]),
        z,
    );
    let yaw = Rotation3::from_axis_angle(&Vector3::z_axis(), rng.random_range(0.0..std::f64::consts::TAU));
    match rng.random_range(0..3) {
        0 => {
            let half = Vec3::new(rng.random_range(0.05..8.0), rng.random_range(0.05..8.0), rng.random_range(0.05..4.0));
            Obb::new(center, *yaw.matrix(), half)
        }
        1 => {
            let axis = Unit::new_normalize(Vector3::new(rng.random(), rng.random(), rng.random::<f64>() - 0.5));
            let turn = Rotation3::from_axis_angle(&axis, rng.random_range(0.0..3.0));
            let half = Vec3::new(rng.random_range(0.05..6.0), rng.random_range(0.05..6.0), rng.random_range(0.05..6.0));
            Obb::new(center, *(turn * yaw).matrix(), half)
        }
        _ => {
            let luff = Rotation3::from_axis_angle(&Vector3::y_axis(), -rng.random_range(0.0..1.5));
            let half = Vec3::new(rng.random_range(5.0..30.0), 0.8, 0.8);
            Obb::new(center, *(yaw * luff).matrix(), half)
        }
    }
}

/// An axis-aligned box whose faces lie on the 1/16 m lattice, within
/// `spread` of `centre`: with site heights on the same lattice, its faces
/// often touch an interval or a cell edge exactly, the case `f32` cannot
/// decide and the device must leave to the CPU.
pub fn lattice_box(rng: &mut rand_chacha::ChaCha8Rng, centre: [f64; 2], spread: [f64; 2], z: [i32; 2]) -> Obb {
    let on_lattice = |rng: &mut rand_chacha::ChaCha8Rng, c: f64, s: f64| {
        let lo = ((c - s) * 16.0).floor() as i64;
        let hi = ((c + s) * 16.0).ceil() as i64;
        rng.random_range(lo..=hi.max(lo + 1)) as f64 / 16.0
    };
    let x = on_lattice(rng, centre[0], spread[0]);
    let y = on_lattice(rng, centre[1], spread[1]);
    let zc = rng.random_range(z[0]..z[1]) as f64 / 16.0;
    let half = Vec3::new(
        rng.random_range(1..64) as f64 / 16.0,
        rng.random_range(1..64) as f64 / 16.0,
        rng.random_range(1..32) as f64 / 16.0,
    );
    Obb::axis_aligned(Point3::new(x, y, zc), half)
}
