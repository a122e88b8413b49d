//! MDM box queries against brute force (parry3d exact geometry) on random scenes.
//!
//! Contract: the map never answers "free" for a box that touches a triangle or a
//! point's occupied cube; it may answer "hit" for a free box only when a real
//! obstacle lies within one cell diagonal (plus the merge gap) of the box.
//! Likewise its vertical clearance never gives a box more room than it has
//! (parry3d's shape cast straight down or up), and where the room it gives
//! ends, a real obstacle lies within that slack.

use liftplan_core::frame::{Mat3, Point3, Vec3};
use liftplan_core::mesh::TriMesh;
use liftplan_core::obb::Obb;
use liftplan_depthmap::mdm::{Mdm, Mode};
use liftplan_depthmap::query::Vertical;
use liftplan_depthmap::{Inputs, Settings, build_cpu};
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query;
use parry3d_f64::query::ShapeCastOptions;
use parry3d_f64::shape::{Cuboid, Shape, Triangle};
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

/// Calls `f` with every obstacle of the scene as parry3d sees it: each
/// triangle, and each point's occupied cube of half side `point_half`.
fn for_each_obstacle(s: &Scene, point_half: f64, mut f: impl FnMut(&Pose, &dyn Shape)) {
    let id = Pose::identity();
    for t in &s.tris {
        f(&id, &Triangle::new(Vector::from(t[0]), Vector::from(t[1]), Vector::from(t[2])));
    }
    let pc = Cuboid::new(Vector::splat(point_half));
    for p in &s.points {
        f(&Pose::from_translation(Vector::from(*p)), &pc);
    }
}

/// Exact distance from the box to the nearest obstacle (0 when touching).
fn brute_distance(s: &Scene, b: &Obb, point_half: f64) -> f64 {
    let (pose, cub) = parry_pose(b);
    let mut best = f64::INFINITY;
    for_each_obstacle(s, point_half, |pos, shape| {
        best = best.min(query::distance(&pose, &cub, pos, shape).unwrap().distance);
    });
    best
}

/// Exact distance the box can move straight down or up before it touches an
/// obstacle (0 when touching now), or `None` if it never does.
fn brute_travel(s: &Scene, b: &Obb, point_half: f64, way: Vertical) -> Option<f64> {
    let (pose, cub) = parry_pose(b);
    let vel = Vector::new(0.0, 0.0, if way == Vertical::Down { -1.0 } else { 1.0 });
    let opts = ShapeCastOptions {
        max_time_of_impact: 1e3,
        target_distance: 0.0,
        stop_at_penetration: true,
        compute_impact_geometry_on_penetration: false,
    };
    let mut best: Option<f64> = None;
    for_each_obstacle(s, point_half, |pos, shape| {
        let hit = query::cast_shapes(&pose, vel, &cub, pos, Vector::ZERO, shape, opts).unwrap();
        if let Some(t) = hit.map(|h| h.time_of_impact) {
            best = Some(best.map_or(t, |b| b.min(t)));
        }
    });
    best
}

/// A random box turned and sized as [`random_box`]'s, centred over one of the
/// scene's points and lifted 0.5 to 2 m clear of everything: going down it
/// must meet that point, with room to spare. In a single-level map a crowded
/// scene can leave no random box any room (each column runs from its lowest
/// obstacle to its highest), so these make sure the room is tested at all.
fn box_over_a_point(rng: &mut ChaCha8Rng, s: &Scene) -> Obb {
    let b = random_box(rng);
    let p = s.points[rng.random_range(0..s.points.len())];
    let top = s.tris.iter().flatten().chain(&s.points).map(|v| v[2]).fold(f64::NEG_INFINITY, f64::max);
    let below_centre: f64 = (0..3).map(|k| b.axes[(2, k)].abs() * b.half[k]).sum();
    let z = top + rng.random_range(0.5..2.0) + below_centre;
    Obb::new(Point3::new(p[0], p[1], z), b.axes, b.half)
}

/// `b` moved `m` metres straight down or up.
fn moved(b: &Obb, way: Vertical, m: f64) -> Obb {
    let dz = if way == Vertical::Down { -m } else { m };
    Obb::new(Point3::new(b.center.x, b.center.y, b.center.z + dz), b.axes, b.half)
}

fn scene_inputs(s: &Scene) -> Inputs {
    let mut mesh = TriMesh::default();
    let g = mesh.group_id("soup");
    for t in &s.tris {
        mesh.add_part(g, false, t, &[[0, 1, 2]]);
    }
    Inputs { ground: vec![false; s.points.len()], points: s.points.clone(), mesh }
}

/// A random scene of `seed`, its map with `cell` m cells in `mode`, and the
/// generator left where the scene ends, to draw boxes from.
struct Site {
    rng: ChaCha8Rng,
    scene: Scene,
    settings: Settings,
    map: Mdm,
    /// How far from a real obstacle the map may put one: a cell diagonal
    /// plus the merge gap.
    slack: f64,
}

fn site(seed: u64, cell: f64, mode: Mode) -> Site {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scene = random_scene(&mut rng, 25, 40);
    let settings =
        Settings { cell_m: cell, mode, point_radius_m: 0.05, merge_gap_m: 0.1, extent: vec![], margin_m: 2.0 };
    let (map, _) = build_cpu(&scene_inputs(&scene), &settings).unwrap();
    let slack = cell * 2f64.sqrt() + settings.merge_gap_m + 1e-4;
    Site { rng, scene, settings, map, slack }
}

fn check(seed: u64, cell: f64, mode: Mode) -> Result<(), TestCaseError> {
    let Site { mut rng, scene, settings, map, slack } = site(seed, cell, mode);
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

/// The map's vertical clearance of random boxes against the exact travel,
/// the map's own box query, and the box moved by the clearance.
fn check_clearance(seed: u64, cell: f64, mode: Mode) -> Result<(), TestCaseError> {
    let Site { mut rng, scene, settings, map, slack } = site(seed, cell, mode);
    // f32 heights of a few metres round by under a micrometre; parry's casts
    // stop within its own tolerance.
    let tol = 1e-4;
    let (mut met, mut roomy) = (0, 0);
    for k in 0..48 {
        let b = if k < 40 { random_box(&mut rng) } else { box_over_a_point(&mut rng, &scene) };
        let hit = map.collides(&b);
        for way in [Vertical::Down, Vertical::Up] {
            let c = map.clearance(&b, way);
            prop_assert_eq!(hit, c.is_some_and(|c| c.gap_m <= 0.0), "clearance {:?} disagrees with the box query", c);
            if let Some(t) = brute_travel(&scene, &b, settings.point_radius_m, way) {
                met += 1;
                let c = c.ok_or_else(|| {
                    TestCaseError::fail(format!(
                        "{way:?}: the box meets an obstacle after {t} m, but the map sees none"
                    ))
                })?;
                prop_assert!(
                    c.gap_m as f64 <= t + tol,
                    "{way:?}: the map gives {} m of room, the box has {t} m",
                    c.gap_m
                );
            }
            let Some(c) = c else { continue };
            let gap = c.gap_m as f64;
            if gap > 2e-3 {
                roomy += 1;
                prop_assert!(
                    !map.collides(&moved(&b, way, gap - 1e-3)),
                    "{way:?}: moved {} m of its {gap} m, the box meets the map",
                    gap - 1e-3
                );
            }
            if gap <= 0.0 {
                // In contact now (checked against the box query above).
                continue;
            }
            let past = moved(&b, way, gap + 1e-3);
            prop_assert!(map.collides(&past), "{way:?}: moved past its {gap} m of room, the box meets nothing");
            if mode == Mode::Multi {
                let d = brute_distance(&scene, &past, settings.point_radius_m);
                prop_assert!(
                    d <= slack,
                    "{way:?}: where its {gap} m of room ends, the nearest obstacle is {d} m away (allowed {slack})"
                );
            }
        }
    }
    // The boxes over a point meet it on the way down with room to spare, so
    // this holds on every scene; it fails only if the checks above were skipped.
    prop_assert!(met > 0 && roomy > 0, "no box met an obstacle ({met}) or had room ({roomy})");
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(24)))]
    #[test]
    fn multi_level_map_is_conservative_and_tight(seed in any::<u64>(), cell in 0.1f64..0.6) {
        check(seed, cell, Mode::Multi)?;
    }

    #[test]
    fn single_level_map_is_conservative(seed in any::<u64>(), cell in 0.1f64..0.6) {
        check(seed, cell, Mode::Single)?;
    }

    #[test]
    fn multi_level_clearance_is_conservative_and_tight(seed in any::<u64>(), cell in 0.1f64..0.6) {
        check_clearance(seed, cell, Mode::Multi)?;
    }

    #[test]
    fn single_level_clearance_is_conservative(seed in any::<u64>(), cell in 0.1f64..0.6) {
        check_clearance(seed, cell, Mode::Single)?;
    }
}

/// A box 2 m over a slab and 1.5 m under a roof: the clearances name both,
/// and leaving out the roof's object leaves nothing overhead.
#[test]
fn clearance_under_a_roof_and_over_a_slab() {
    let mut mesh = TriMesh::default();
    let (slab, roof) = (mesh.group_id("SLAB-1"), mesh.group_id("ROOF-2"));
    mesh.add_box(slab, [0.0, 0.0, 0.0], [6.0, 6.0, 1.0]);
    mesh.add_box(roof, [0.0, 0.0, 6.5], [6.0, 6.0, 7.0]);
    let inp = Inputs { points: vec![], ground: vec![], mesh };
    let (map, _) = build_cpu(&inp, &Settings { margin_m: 1.0, ..Settings::default() }).unwrap();
    let b = Obb::axis_aligned(Point3::new(3.0, 3.0, 4.0), Vec3::new(1.0, 0.5, 1.0));
    let name = |m: &Mdm, c: &liftplan_depthmap::query::Clearance| m.object_name(&c.at.interval).to_string();
    let down = map.clearance(&b, Vertical::Down).unwrap();
    assert!((down.gap_m - 2.0).abs() < 1e-4 && name(&map, &down) == "SLAB-1", "{down:?}");
    // The slab is level, so every cell under the box ties: the first cell
    // under it in row order is named, whatever order the walk took.
    let s = map.spec;
    let first = (0..s.ny)
        .flat_map(|j| (0..s.nx).map(move |i| (j, i)))
        .find(|&(j, i)| {
            let r = s.rect(i, j);
            !map.cell(i, j).is_empty() && b.z_range_over_rect(r[0], r[1], r[2], r[3]).is_some()
        })
        .unwrap();
    assert_eq!((down.at.j, down.at.i), first);
    let up = map.clearance(&b, Vertical::Up).unwrap();
    assert!((up.gap_m - 1.5).abs() < 1e-4 && name(&map, &up) == "ROOF-2", "{up:?}");
    let not_roof = |iv: &liftplan_depthmap::mdm::Interval| map.object_name(iv) != "ROOF-2";
    assert_eq!(map.clearance_where(&b, Vertical::Up, not_roof), None);
    // Sunk 0.25 m into the slab: in contact, and 0.25 m up clears it.
    let sunk = moved(&b, Vertical::Down, 2.25);
    let c = map.clearance(&sunk, Vertical::Down).unwrap();
    assert!((c.gap_m + 0.25).abs() < 1e-4 && map.collides(&sunk), "{c:?}");
    let many = map.clearances(&[b, sunk], Vertical::Down);
    assert_eq!(many, vec![Some(down), Some(c)]);
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
