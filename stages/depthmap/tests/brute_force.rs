//! MDM box queries against brute force (parry3d exact geometry) on random scenes.
//!
//! Contract: the map never answers "free" for a box that touches a triangle or a
//! point's occupied cube; it may answer "hit" for a free box only when a real
//! obstacle lies within one cell diagonal (plus the merge gap) of the box.

use liftplan_core::frame::{Mat3, Point3, Vec3};
use liftplan_core::mesh::TriMesh;
use liftplan_core::obb::Obb;
use liftplan_depthmap::mdm::Mode;
use liftplan_depthmap::{Inputs, Settings, build_cpu};
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query;
use parry3d_f64::shape::{Cuboid, Triangle};
use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn parry_pose(b: &Obb) -> (Pose, Cuboid) {
    let a = |k: usize| Vector::new(b.axes[(0, k)], b.axes[(1, k)], b.axes[(2, k)]);
    let rot = parry3d_f64::glamx::DQuat::from_mat3(&parry3d_f64::glamx::DMat3::from_cols(a(0), a(1), a(2)));
    let pose = Pose::from_parts(Vector::new(b.center.x, b.center.y, b.center.z), rot);
    (pose, Cuboid::new(Vector::new(b.half.x, b.half.y, b.half.z)))
}

struct Scene {
    tris: Vec<[[f64; 3]; 3]>,
    points: Vec<[f64; 3]>,
}

fn random_scene(rng: &mut ChaCha8Rng, n_tris: usize, n_points: usize) -> Scene {
    let mut r = |a: f64, b: f64| a + (b - a) * rng.random::<f64>();
    let mut tris = Vec::new();
    for _ in 0..n_tris {
        let c = [r(0.0, 10.0), r(0.0, 10.0), r(0.0, 6.0)];
        let mut t = [[0.0; 3]; 3];
        for v in &mut t {
            *v = [c[0] + r(-1.5, 1.5), c[1] + r(-1.5, 1.5), c[2] + r(-1.5, 1.5)];
        }
        tris.push(t);
    }
    let points = (0..n_points).map(|_| [r(0.0, 10.0), r(0.0, 10.0), r(0.0, 6.0)]).collect();
    Scene { tris, points }
}

fn random_box(rng: &mut ChaCha8Rng) -> Obb {
    let mut r = |a: f64, b: f64| a + (b - a) * rng.random::<f64>();
    let axis = Vec3::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0));
    let angle = r(0.0, std::f64::consts::PI);
    let rot: Mat3 = if axis.norm() > 1e-3 {
        *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).matrix()
    } else {
        Mat3::identity()
    };
    Obb::new(
        Point3::new(r(-1.0, 11.0), r(-1.0, 11.0), r(-1.0, 7.0)),
        rot,
        Vec3::new(r(0.05, 2.0), r(0.05, 2.0), r(0.05, 2.0)),
    )
}

/// Exact distance from the box to the nearest obstacle (0 when touching).
fn brute_distance(s: &Scene, b: &Obb, point_half: f64) -> f64 {
    let (pose, cub) = parry_pose(b);
    let id = Pose::identity();
    let mut best = f64::INFINITY;
    for t in &s.tris {
        let tri = Triangle::new(Vector::from(t[0]), Vector::from(t[1]), Vector::from(t[2]));
        best = best.min(query::distance(&pose, &cub, &id, &tri).unwrap().distance);
    }
    let pc = Cuboid::new(Vector::splat(point_half));
    for p in &s.points {
        best = best.min(query::distance(&pose, &cub, &Pose::from_translation(Vector::from(*p)), &pc).unwrap().distance);
    }
    best
}

fn scene_inputs(s: &Scene) -> Inputs {
    let mut mesh = TriMesh::default();
    let g = mesh.group_id("soup");
    for t in &s.tris {
        mesh.add_part(g, false, t, &[[0, 1, 2]]);
    }
    Inputs { ground: vec![false; s.points.len()], points: s.points.clone(), mesh }
}

fn check(seed: u64, cell: f64, mode: Mode) -> Result<(), TestCaseError> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scene = random_scene(&mut rng, 25, 40);
    let settings =
        Settings { cell_m: cell, mode, point_radius_m: 0.05, merge_gap_m: 0.1, extent: vec![], margin_m: 2.0 };
    let (map, _) = build_cpu(&scene_inputs(&scene), &settings).unwrap();
    let slack = cell * 2f64.sqrt() + settings.merge_gap_m + 1e-4;
    for _ in 0..60 {
        let b = random_box(&mut rng);
        let d = brute_distance(&scene, &b, settings.point_radius_m);
        let hit = map.collides(&b);
        prop_assert!(hit || d > 1e-6, "false free: box {:?} is {d} m from an obstacle but the map says free", b);
        if mode == Mode::Multi {
            prop_assert!(!hit || d <= slack, "false hit {d} m from the nearest obstacle (allowed {slack})");
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn multi_level_map_is_conservative_and_tight(seed in any::<u64>(), cell in 0.1f64..0.6) {
        check(seed, cell, Mode::Multi)?;
    }

    #[test]
    fn single_level_map_is_conservative(seed in any::<u64>(), cell in 0.1f64..0.6) {
        check(seed, cell, Mode::Single)?;
    }
}

/// The MDM artifact reads back identical to what was written.
#[test]
fn artifact_round_trip() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let scene = random_scene(&mut rng, 30, 100);
    let (map, _) = build_cpu(&scene_inputs(&scene), &Settings::default()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("x.mdm");
    map.write(&p).unwrap();
    let back = liftplan_depthmap::mdm::Mdm::read(&p).unwrap();
    assert_eq!(back, map);
}

/// A damaged artifact is an error, never a panic.
#[test]
fn truncated_artifact_is_an_error() {
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    let scene = random_scene(&mut rng, 10, 10);
    let (map, _) = build_cpu(&scene_inputs(&scene), &Settings::default()).unwrap();
    let bytes = map.to_bytes();
    for cut in [0, 10, bytes.len() / 2, bytes.len() - 1] {
        assert!(liftplan_depthmap::mdm::Mdm::from_bytes(std::path::Path::new("x.mdm"), &bytes[..cut]).is_err());
    }
}
