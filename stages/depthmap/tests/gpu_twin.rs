//! The GPU assembly gives the CPU's map, bit for bit. Runs where wgpu finds an
//! adapter (a GPU, or Mesa's lavapipe); says so plainly and passes otherwise.

use liftplan_core::frame::{Point3, Vec3};
use liftplan_core::obb::Obb;
use liftplan_depthmap::mdm::{self, Mode, PointSource, Raw};
use liftplan_depthmap::query::{LeaveOut, Vertical};
use liftplan_depthmap::{Inputs, Settings, build, build_cpu, gpu};
use rand::{RngExt, SeedableRng};

#[path = "support/boxes.rs"]
mod boxes;

/// A sloping ground and scattered structure, with (when `plant`) pipes as
/// loose triangles and racks as boxes (convex parts) among them. Heights are
/// often multiples of 1/16 m, so equal heights and exactly touching intervals
/// are common.
fn site(n: usize, seed: u64, plant: bool) -> Inputs {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut inp = Inputs::default();
    for _ in 0..n {
        let (x, y) = (rng.random::<f64>() * 80.0 - 40.0, rng.random::<f64>() * 60.0 - 30.0);
        let z = match rng.random_range(0..4) {
            0 | 1 => 0.02 * x,
            2 => rng.random_range(0..200) as f64 * 0.0625,
            _ => rng.random::<f64>() * 25.0,
        };
        inp.points.push([x + 1000.0, y + 2000.0, z]);
        // Some points off the ground plane are ground too (classification
        // is not geometry), so one cell can hold equal intervals of both.
        inp.ground.push(z < 0.02 * x + 0.01 || rng.random_range(0..8) == 0);
    }
    if plant {
        let pipe = inp.mesh.group_id("pipe");
        let rack = inp.mesh.group_id("rack");
        for _ in 0..300 {
            let c = [1000.0 + rng.random::<f64>() * 80.0 - 40.0, 2000.0 + rng.random::<f64>() * 60.0 - 30.0];
            let z = rng.random::<f64>() * 20.0;
            let t: Vec<[f64; 3]> = (0..3)
                .map(|_| [c[0] + rng.random::<f64>() * 3.0, c[1] + rng.random::<f64>() * 3.0, z + rng.random::<f64>()])
                .collect();
            inp.mesh.add_part(pipe, false, &t, &[[0, 1, 2]]);
            inp.mesh.add_box(rack, [c[0], c[1], z], [c[0] + 1.5, c[1] + 0.7, z + 0.5]);
        }
    }
    inp
}

/// Runs `check` on a device of each backend with an adapter (Vulkan and
/// OpenGL where Mesa's lavapipe and llvmpipe are installed, as CI has them:
/// the same adapter runs shaders differently through each), and says so;
/// says plainly when there is none. A backend whose adapter is found but
/// whose device does not open fails the test.
fn for_each_gpu(mut check: impl FnMut(gpu::Gpu)) {
    let devices = gpu::open_each_backend(true);
    if devices.is_empty() {
        eprintln!("SKIPPED: no GPU adapter, the GPU twin is not tested here");
    }
    for (backend, opened) in devices {
        let g = opened.unwrap_or_else(|e| panic!("{backend:?} has an adapter, but: {e}"));
        eprintln!("GPU twin test on {}", g.name());
        check(g);
    }
}

#[test]
fn gpu_and_cpu_maps_are_equal() {
    for_each_gpu(|g| {
        let cases = [
            (50_000, 0.25, 0.05, 0.1, Mode::Multi, true),
            (50_000, 0.25, 0.0625, 0.125, Mode::Single, true),
            (20_000, 0.1, 0.12, 0.0, Mode::Multi, false),
            (30_000, 0.5, 0.0, 0.0, Mode::Multi, true),
            (30_000, 1.0, 0.25, 0.5, Mode::Single, false),
            (1, 0.5, 0.0, 0.1, Mode::Multi, false),
            (0, 0.5, 0.05, 0.1, Mode::Multi, true),
        ];
        for (n, cell, radius, gap, mode, plant) in cases {
            let inp = site(n, n as u64 + 7, plant);
            let s = Settings { cell_m: cell, point_radius_m: radius, merge_gap_m: gap, mode, ..Settings::default() };
            let (cpu, _) = build_cpu(&inp, &s).unwrap();
            let (gpu, _) = build(&inp, &s, Some(&g)).unwrap();
            assert!(
                cpu == gpu,
                "maps differ: {n} points, cell {cell}, radius {radius}, gap {gap}, {mode:?}, plant {plant}"
            );
        }
    });
}

/// Under a small buffer limit the grid is cut into many slabs (some cut again
/// when they turn out too full) and the points and triangles go up in many
/// chunks; crowded cells take the heapsort. The map is the same.
#[test]
fn gpu_slabs_chunks_and_crowded_cells_give_the_same_map() {
    for_each_gpu(|mut g| {
        let cases = [
            (40_000, 0.5, Mode::Multi, 1 << 16),
            (40_000, 4.0, Mode::Single, 1 << 16),
            (60_000, 10.0, Mode::Multi, 1 << 18),
        ];
        for (n, cell, mode, limit) in cases {
            g.set_buffer_limit(limit);
            let inp = site(n, 3, true);
            let s = Settings { cell_m: cell, mode, ..Settings::default() };
            let (cpu, _) = build_cpu(&inp, &s).unwrap();
            let points = PointSource { xyz: &inp.points, ground: &inp.ground, radius: s.point_radius_m as f32 };
            let mesh: Vec<Raw> = mdm::mesh_raws(&inp.mesh, &cpu.spec, 2).concat();
            let cells = g.assemble(Some(&points), &mesh, &cpu.spec, mode, s.merge_gap_m as f32).unwrap();
            assert!(cells.slabs > 1, "expected several slabs, got {}", cells.slabs);
            let crowded = cpu.offsets.windows(2).map(|w| w[1] - w[0]).max().unwrap_or(0);
            let gpu =
                mdm::Mdm::from_cells(cpu.spec, mode, &cells.counts, cells.intervals, cells.tops, cpu.objects.clone());
            assert!(cpu == gpu, "maps differ: {n} points, cell {cell}, {mode:?} ({} slabs)", cells.slabs);
            eprintln!(
                "cell {cell}: {} slabs, {} raw intervals, up to {crowded} intervals a cell",
                cells.slabs, cells.raws
            );
        }
    });
}

/// A grid row with more raw intervals than one buffer holds is refused with
/// an error that says what to change; nothing is cut short silently.
#[test]
fn gpu_refuses_a_row_over_its_buffers() {
    for_each_gpu(|mut g| {
        g.set_buffer_limit(1 << 16);
        let inp = site(60_000, 3, false);
        let s = Settings { cell_m: 20.0, ..Settings::default() };
        let err = build(&inp, &s, Some(&g)).expect_err("a row of 60,000 points cannot fit 4096 keys").to_string();
        assert!(err.contains("grid row 0") && err.contains("cell_m"), "{err}");
        // A row of more cells than one buffer's words.
        g.set_buffer_limit(4096);
        let s = Settings { cell_m: 0.05, ..Settings::default() };
        let err = build(&inp, &s, Some(&g)).expect_err("a row of 2000 cells cannot fit 1024 words").to_string();
        assert!(err.contains("a grid row of") && err.contains("cell_m"), "{err}");
    });
}

/// Single cells of a few to thousands of points at random heights: cells of
/// up to `LARGE` (256) raw keys are sorted by one invocation (insertion sort
/// up to 16, heapsort above), larger ones by a workgroup's bitonic sort, on
/// both sides of each switch.
#[test]
fn gpu_crowded_single_cells_match_the_cpu() {
    for_each_gpu(|g| {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let sizes =
            [(16, 1.0), (17, 1.0), (64, 3.0), (256, 30.0), (257, 30.0), (1000, 100.0), (4600, 10.0), (7000, 400.0)];
        for (n, height) in sizes {
            let mut inp = Inputs::default();
            for _ in 0..n {
                inp.points.push([0.5 + rng.random::<f64>() * 0.1, 0.5, rng.random::<f64>() * height]);
                inp.ground.push(rng.random_range(0..3) == 0);
            }
            for mode in [Mode::Multi, Mode::Single] {
                let s = Settings { cell_m: 1.0, extent: vec![0.0, 0.0, 1.0, 1.0], mode, ..Settings::default() };
                let (cpu, _) = build_cpu(&inp, &s).unwrap();
                let (gpu, _) = build(&inp, &s, Some(&g)).unwrap();
                assert!(cpu == gpu, "maps differ: {n} points in one cell, {mode:?}");
            }
        }
    });
}

/// Where the device cuts shader loops short (lavapipe), a cell too crowded
/// for that is refused with an error, never rasterised wrong.
#[test]
fn gpu_loop_cap_refuses_what_it_cannot_finish() {
    for_each_gpu(|g| {
        let Some(cap) = g.loop_cap() else {
            eprintln!("SKIPPED: {} runs loops to their end", g.name());
            return;
        };
        let n = cap as usize;
        let inp = Inputs {
            points: (0..n).map(|k| [0.5, 0.5, k as f64 * 0.5]).collect(),
            ground: vec![false; n],
            ..Inputs::default()
        };
        let s = Settings { cell_m: 1.0, extent: vec![0.0, 0.0, 1.0, 1.0], ..Settings::default() };
        let err = build(&inp, &s, Some(&g)).expect_err("a cell of `cap` keys cannot finish under the cap").to_string();
        assert!(err.contains("loops") && err.contains("[gpu] use"), "{err}");
    });
}

/// With a configured extent, points off the grid (near it, and absurdly far)
/// are left out the same way on both paths.
#[test]
fn gpu_leaves_out_points_off_a_configured_extent_as_the_cpu_does() {
    for_each_gpu(|g| {
        let mut inp = site(20_000, 9, true);
        for far in [1.0e4, 1.0e8, -1.0e8, 3.0e9] {
            inp.points.push([1000.0 + far, 2000.0, 1.0]);
            inp.points.push([1000.0, 2000.0 - far, 2.0]);
            inp.ground.extend([false, true]);
        }
        let s = Settings { cell_m: 0.1, extent: vec![990.0, 1990.0, 1010.0, 2005.0], ..Settings::default() };
        let (cpu, _) = build_cpu(&inp, &s).unwrap();
        let (gpu, _) = build(&inp, &s, Some(&g)).unwrap();
        assert!(cpu == gpu, "maps differ with points off the extent");
    });
}

/// What the queries leave out: nothing, all the ground, and the ground up
/// to 5 m (`site` has ground points on the 1/16 m lattice up to 12.4 m, so
/// with a radius of 1/16 m some intervals' tops are exactly 5 m).
fn leave_outs() -> [Option<LeaveOut>; 3] {
    [None, Some(LeaveOut::object(mdm::OBJ_GROUND)), Some(LeaveOut::up_to(mdm::OBJ_GROUND, 5.0))]
}

/// A random box over (and around) `site`'s area, `z` its centre height.
fn random_box(rng: &mut rand_chacha::ChaCha8Rng, z: f64) -> Obb {
    boxes::random_box(rng, [1000.0, 2000.0], [50.0, 40.0], z)
}

/// The GPU's box queries (device screen, CPU exact test for the rest) give
/// the CPU's answer for every box, hit for hit, with and without the ground
/// (all of it, or up to a height) left out; and the device does clear boxes: every box above the whole site.
#[test]
fn gpu_and_cpu_box_queries_agree() {
    for_each_gpu(|g| {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        for (n, cell, mode) in [(40_000, 0.25, Mode::Multi), (20_000, 1.0, Mode::Single), (40_000, 0.1, Mode::Multi)] {
            let inp = site(n, n as u64, true);
            let s = Settings { cell_m: cell, mode, ..Settings::default() };
            let (map, _) = build_cpu(&inp, &s).unwrap();
            let on_gpu = g.upload_map(&map).unwrap();
            let mut boxes: Vec<Obb> = (0..3000)
                .map(|_| {
                    let z = rng.random_range(-5.0..40.0);
                    random_box(&mut rng, z)
                })
                .collect();
            // Above everything (the site's tops stay under 27 m).
            let above: Vec<Obb> = (0..300).map(|_| random_box(&mut rng, 70.0)).collect();
            boxes.extend(&above);
            // Off the grid, and too far out to screen in f32: first and in
            // the middle of the list, so that the boxes after them go up in
            // other slots than their places in the list.
            boxes.insert(0, Obb::axis_aligned(Point3::new(5000.0, 2000.0, 1.0), Vec3::new(1.0, 1.0, 1.0)));
            boxes.insert(1500, Obb::axis_aligned(Point3::new(1000.0, 2.0e6, 1.0), Vec3::new(3.0e6, 1.0, 1.0)));
            for leave in leave_outs() {
                let (hits, counts) = g.hits_where(&on_gpu, &map, &boxes, leave).unwrap();
                let mut free = 0;
                for (k, b) in boxes.iter().enumerate() {
                    let cpu = map.hit_where(b, |iv| LeaveOut::counts(leave, iv));
                    assert_eq!(hits[k], cpu, "box {k} ({b:?}), cell {cell}, {mode:?}, leaving out {leave:?}");
                    free += cpu.is_none() as usize;
                }
                eprintln!("cell {cell} {mode:?} leaving out {leave:?}: {} boxes, {free} free, {counts:?}", boxes.len());
                assert!(counts.left_to_cpu >= 1, "the far box must go to the CPU");
                // The boxes above the site, and the one off the grid.
                assert!(counts.free_on_gpu > above.len(), "the device must clear the boxes above the site");
                // The device's tests have margins of millimetres: it answers
                // most boxes itself (free 99 %, hits 95-97 % when written); weaker ones would
                // leave the work to the CPU.
                assert!(100 * counts.free_on_gpu >= 97 * free, "the device cleared {counts:?} of {free} free boxes");
                assert!(
                    100 * counts.hit_on_gpu >= 90 * (boxes.len() - free),
                    "the device answered {counts:?} of {} boxes that meet the map",
                    boxes.len() - free
                );
            }
        }
    });
}

/// Ground left out up to a height: an interval whose top is exactly that
/// height is left out, one a hair higher counts, on both paths, for box
/// queries and clearances both ways.
#[test]
fn gpu_leaves_out_ground_up_to_a_height_as_the_cpu_does() {
    for_each_gpu(|g| {
        let mut inp = Inputs::default();
        // A ground point whose interval is [4.875, 5.0] (radius 1/16 m), and
        // one 2 m away whose interval tops out at 5.0625.
        for (x, z) in [(1.1, 4.9375), (3.1, 5.0)] {
            inp.points.push([x, 1.1, z]);
            inp.ground.push(true);
        }
        // Lower, beside the first: what a box above the first finds below
        // it where that ground is left out. (A device that took that ground
        // for an obstacle would narrow the answer down to its cell.)
        inp.points.push([1.35, 1.1, 3.9375]);
        inp.ground.push(false);
        let s =
            Settings { cell_m: 0.25, point_radius_m: 0.0625, extent: vec![0.0, 0.0, 4.0, 2.0], ..Settings::default() };
        let (map, _) = build_cpu(&inp, &s).unwrap();
        let on_gpu = g.upload_map(&map).unwrap();
        let over = |x: f64, z: f64, half_z: f64| Obb::axis_aligned(Point3::new(x, 1.1, z), Vec3::new(0.3, 0.3, half_z));
        // Each box overlaps its point's interval; the last two hang above them.
        let boxes = [over(1.1, 5.5, 0.6), over(3.1, 5.5, 0.6), over(1.1, 6.5, 0.25), over(3.1, 6.5, 0.25)];
        let at = |z: f64| Some(LeaveOut::up_to(mdm::OBJ_GROUND, z));
        for (leave, hit) in [
            (None, [true, true]),
            (at(5.0), [false, true]),
            (at(4.999), [true, true]),
            (at(5.0625), [false, false]),
            (Some(LeaveOut::object(mdm::OBJ_GROUND)), [false, false]),
        ] {
            let cpu: Vec<_> = boxes.iter().map(|b| map.hit_where(b, |iv| LeaveOut::counts(leave, iv))).collect();
            assert_eq!([cpu[0].is_some(), cpu[1].is_some()], hit, "leaving out {leave:?}: {cpu:?}");
            assert!(cpu[2].is_none() && cpu[3].is_none());
            let (gpu, _) = g.hits_where(&on_gpu, &map, &boxes, leave).unwrap();
            assert_eq!(gpu, cpu, "leaving out {leave:?}");
            for way in [Vertical::Down, Vertical::Up] {
                let cpu: Vec<_> =
                    boxes.iter().map(|b| map.clearance_where(b, way, |iv| LeaveOut::counts(leave, iv))).collect();
                let (gpu, _) = g.clearances_where(&on_gpu, &map, &boxes, way, leave).unwrap();
                assert_eq!(gpu, cpu, "leaving out {leave:?}, {way:?}");
                if way == Vertical::Down {
                    // What hangs above a point that counts finds it below.
                    let first = cpu[2].map(|c| c.at.interval.obj);
                    let want = if hit[0] { mdm::OBJ_GROUND } else { mdm::OBJ_SCAN };
                    assert_eq!(first, Some(want), "leaving out {leave:?}: {cpu:?}");
                    assert_eq!(cpu[3].is_some(), hit[1], "leaving out {leave:?}: {cpu:?}");
                }
            }
        }
    });
}

/// A walk longer than the device's loop budget (lavapipe's loop cap would
/// otherwise end it silently, which reads as "free") is given up and answered
/// by the CPU. Here 40,000 cells hold left-out ground at the box's height, and
/// the one obstacle is in the last cell of the walk.
#[test]
fn gpu_box_query_longer_than_the_loop_budget_is_right() {
    for_each_gpu(|g| {
        let mut inp = Inputs::default();
        for j in 0..200 {
            for i in 0..200 {
                inp.points.push([i as f64 * 0.1 + 0.05, j as f64 * 0.1 + 0.05, 99.5]);
                inp.ground.push(true);
            }
        }
        inp.points.push([19.95, 19.95, 99.6]);
        inp.ground.push(false);
        let s = Settings { cell_m: 0.1, extent: vec![0.0, 0.0, 20.0, 20.0], ..Settings::default() };
        let (map, _) = build_cpu(&inp, &s).unwrap();
        let on_gpu = g.upload_map(&map).unwrap();
        let b = Obb::axis_aligned(Point3::new(10.0, 10.0, 99.5), Vec3::new(9.99, 9.99, 0.5));
        let cpu = map.hit_where(&b, |iv| iv.obj != mdm::OBJ_GROUND);
        assert!(cpu.is_some_and(|h| h.interval.obj == mdm::OBJ_SCAN), "{cpu:?}");
        let (hits, counts) = g.hits_where(&on_gpu, &map, &[b], Some(LeaveOut::object(mdm::OBJ_GROUND))).unwrap();
        eprintln!("{counts:?}");
        assert_eq!(hits[0], cpu);
        if g.loop_cap().is_some() {
            assert_eq!(counts.left_to_cpu, 1, "a walk of 40,000 cells is over lavapipe's budget");
        }
    });
}

/// Boxes whose faces lie on the 1/16 m lattice over a site whose point
/// intervals do too (heights on the lattice, radius 1/16 m, cells of 1/4 m),
/// and the same boxes a thousandth of a millimetre higher and lower: faces
/// touching an interval or a cell edge exactly, or missing it by less than
/// `f32` resolves, are where the device cannot decide, and the answers must
/// still be the CPU's.
#[test]
fn gpu_box_queries_touching_exactly_are_right() {
    for_each_gpu(|g| {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let inp = site(30_000, 5, false);
        let s = Settings { cell_m: 0.25, point_radius_m: 0.0625, ..Settings::default() };
        let (map, _) = build_cpu(&inp, &s).unwrap();
        let on_gpu = g.upload_map(&map).unwrap();
        let lattice: Vec<Obb> =
            (0..3000).map(|_| boxes::lattice_box(&mut rng, [1000.0, 2000.0], [40.0, 30.0], [-16, 420])).collect();
        let moved =
            |dz: f64| lattice.iter().map(move |b| Obb::axis_aligned(b.center + Vec3::new(0.0, 0.0, dz), b.half));
        let all: Vec<Obb> = lattice.iter().copied().chain(moved(1e-6)).chain(moved(-1e-6)).collect();
        for leave in leave_outs() {
            let (hits, counts) = g.hits_where(&on_gpu, &map, &all, leave).unwrap();
            let cpu: Vec<_> = all.iter().map(|b| map.hit_where(b, |iv| LeaveOut::counts(leave, iv))).collect();
            for (k, b) in all.iter().enumerate() {
                assert_eq!(hits[k], cpu[k], "box {k} ({b:?}), leaving out {leave:?}");
            }
            // A lattice box that meets the map but is free once moved touches it exactly.
            let n = lattice.len();
            let touching =
                (0..n).filter(|&k| cpu[k].is_some() && (cpu[n + k].is_none() || cpu[2 * n + k].is_none())).count();
            eprintln!("lattice boxes leaving out {leave:?}: {counts:?}, {touching} touch the map exactly");
            assert!(touching > 0, "no box touches exactly: the test does not test what it says");
        }
    });
}

/// Turned boxes moved onto a contact and a few `f32` roundings either side
/// of it, far from the grid's origin (about 1.6 km, where a rounding of a
/// coordinate is about 0.1 mm): the device's margin must cover its
/// rounding there, or it would call free a box the CPU finds a hit, or the
/// other way round. Box queries and clearances both ways must be the CPU's.
/// With no margin at all this fails; one a few times too small still passes
/// here (rounding seldom reaches its worst case), so the margin's size rests
/// on the accounting at `MARGIN_REL` in `gpu/screen.rs`.
#[test]
fn gpu_box_queries_within_roundings_of_a_contact_far_out_are_right() {
    for_each_gpu(|g| {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(31);
        let inp = site(20_000, 13, true);
        let s = Settings { cell_m: 2.0, extent: vec![-600.0, 500.0, 1050.0, 2040.0], ..Settings::default() };
        let (map, _) = build_cpu(&inp, &s).unwrap();
        let on_gpu = g.upload_map(&map).unwrap();
        // One unit roundoff of a coordinate this far from the grid origin.
        let u_far = 1700.0 / (1u64 << 24) as f64;
        let mut near = Vec::new();
        while near.len() < 7 * 400 {
            let z = rng.random_range(2.0..30.0);
            let b = boxes::random_box(&mut rng, [1000.0, 2000.0], [40.0, 30.0], z);
            if map.hit(&b).is_some() {
                continue;
            }
            let Some(c) = map.clearance(&b, Vertical::Down) else { continue };
            for k in [-16.0, -4.0, -1.0, 0.0, 1.0, 4.0, 16.0] {
                let dz = k * u_far - c.gap_m as f64;
                near.push(Obb::new(b.center + Vec3::new(0.0, 0.0, dz), b.axes, b.half));
            }
        }
        for leave in leave_outs() {
            let (hits, counts) = g.hits_where(&on_gpu, &map, &near, leave).unwrap();
            let cpu: Vec<_> = near.iter().map(|b| map.hit_where(b, |iv| LeaveOut::counts(leave, iv))).collect();
            for (k, b) in near.iter().enumerate() {
                assert_eq!(hits[k], cpu[k], "box {k} ({b:?}), leaving out {leave:?}");
            }
            let hit = cpu.iter().filter(|h| h.is_some()).count();
            eprintln!("{} boxes near a contact leaving out {leave:?}: {hit} hit, {counts:?}", near.len());
            if leave.is_none() {
                // Moved onto the contact or past it, a box hits; short of it,
                // by a rounding or more, it is free (but where f32 cannot
                // tell which).
                assert!(
                    hit > near.len() / 4 && hit < near.len() * 3 / 4,
                    "{hit} of {} hit: not near contacts",
                    near.len()
                );
            }
            for way in [Vertical::Down, Vertical::Up] {
                let (found, _) = g.clearances_where(&on_gpu, &map, &near, way, leave).unwrap();
                for (k, b) in near.iter().enumerate() {
                    let cpu = map.clearance_where(b, way, |iv| LeaveOut::counts(leave, iv));
                    assert_eq!(found[k], cpu, "box {k} ({b:?}), {way:?}, leaving out {leave:?}");
                }
            }
        }
    });
}

/// The GPU's clearances (device narrowing, CPU measuring the cells it
/// keeps) give the CPU's answer for every box, both ways, with and without
/// the ground left out (all, or up to a height): gap, cell and interval.
#[test]
fn gpu_and_cpu_clearances_agree() {
    for_each_gpu(|g| {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(29);
        for (n, cell, mode) in [(40_000, 0.25, Mode::Multi), (20_000, 1.0, Mode::Single), (40_000, 0.1, Mode::Multi)] {
            let inp = site(n, n as u64 + 1, true);
            let s = Settings { cell_m: cell, mode, ..Settings::default() };
            let (map, _) = build_cpu(&inp, &s).unwrap();
            let on_gpu = g.upload_map(&map).unwrap();
            let mut boxes: Vec<Obb> = (0..2000)
                .map(|_| {
                    let z = rng.random_range(-5.0..40.0);
                    random_box(&mut rng, z)
                })
                .collect();
            boxes.push(Obb::axis_aligned(Point3::new(5000.0, 2000.0, 1.0), Vec3::new(1.0, 1.0, 1.0)));
            boxes.push(Obb::axis_aligned(Point3::new(1000.0, 2.0e6, 1.0), Vec3::new(3.0e6, 1.0, 1.0)));
            for way in [Vertical::Down, Vertical::Up] {
                for leave in leave_outs() {
                    let (found, counts) = g.clearances_where(&on_gpu, &map, &boxes, way, leave).unwrap();
                    let mut some = 0;
                    for (k, b) in boxes.iter().enumerate() {
                        let cpu = map.clearance_where(b, way, |iv| LeaveOut::counts(leave, iv));
                        assert_eq!(
                            found[k], cpu,
                            "box {k} ({b:?}), cell {cell}, {mode:?}, {way:?}, leaving out {leave:?}"
                        );
                        some += cpu.is_some() as usize;
                    }
                    eprintln!(
                        "cell {cell} {mode:?} {way:?} leaving out {leave:?}: {some} of {} with a gap, {counts:?}",
                        boxes.len()
                    );
                    assert!(some > boxes.len() / 10, "too few boxes have anything {way:?} of them: {some}");
                    assert!(counts.left_to_cpu >= 1, "the far box must go to the CPU");
                    assert!(counts.free_on_gpu >= 1, "the box off the grid has nothing under or over it");
                    // The device narrows most boxes to a few cells; a weaker
                    // bound would leave the work to the CPU.
                    assert!(
                        100 * counts.hit_on_gpu >= 80 * some,
                        "the device narrowed {counts:?} of {some} boxes with a gap"
                    );
                }
            }
        }
    });
}

/// Over a level slab every cell under a box ties: the device must settle
/// the tie as the CPU does (the first cell in row order), from the upright
/// box's exact heights, and hand the CPU a single cell. Boxes turned out of
/// the upright only tie nearly, and still agree.
#[test]
fn gpu_clearance_ties_over_a_slab_are_the_cpus() {
    for_each_gpu(|g| {
        let mut inp = Inputs::default();
        let slab = inp.mesh.group_id("SLAB-1");
        inp.mesh.add_box(slab, [0.0, 0.0, 0.0], [40.0, 40.0, 0.3]);
        let roof = inp.mesh.group_id("ROOF-1");
        inp.mesh.add_box(roof, [0.0, 0.0, 12.0], [40.0, 40.0, 12.5]);
        let s = Settings { cell_m: 0.25, extent: vec![0.0, 0.0, 40.0, 40.0], ..Settings::default() };
        let (map, _) = build_cpu(&inp, &s).unwrap();
        let on_gpu = g.upload_map(&map).unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(31);
        let upright: Vec<Obb> =
            (0..500).map(|_| boxes::random_box(&mut rng, [20.0, 20.0], [15.0, 15.0], 5.0)).collect();
        let upright: Vec<Obb> = upright.into_iter().filter(|b| b.is_upright()).collect();
        assert!(upright.len() > 100, "{} upright boxes", upright.len());
        for way in [Vertical::Down, Vertical::Up] {
            let (found, counts) = g.clearances_where(&on_gpu, &map, &upright, way, None).unwrap();
            for (k, b) in upright.iter().enumerate() {
                assert_eq!(found[k], map.clearance(b, way), "box {k} ({b:?}), {way:?}");
            }
            eprintln!("slab, upright boxes {way:?}: {counts:?}");
            assert_eq!(counts.boxes(), upright.len());
            assert!(100 * counts.hit_on_gpu >= 95 * upright.len(), "{counts:?}");
            // One cell per box, but where the box's edge runs within a
            // millimetre of a cell's (the device cannot tell if it reaches).
            assert!(counts.cells_measured <= counts.hit_on_gpu + counts.hit_on_gpu / 10, "{counts:?}");
        }
        let turned: Vec<Obb> = (0..500).map(|_| boxes::random_box(&mut rng, [20.0, 20.0], [15.0, 15.0], 5.0)).collect();
        for way in [Vertical::Down, Vertical::Up] {
            let (found, counts) = g.clearances_where(&on_gpu, &map, &turned, way, None).unwrap();
            for (k, b) in turned.iter().enumerate() {
                assert_eq!(found[k], map.clearance(b, way), "box {k} ({b:?}), {way:?}");
            }
            eprintln!("slab, any boxes {way:?}: {counts:?}");
        }
    });
}

/// Lattice boxes over a lattice site (see the box queries' test of the
/// same name): faces touching intervals exactly give gaps of exactly zero,
/// the ties the device's bounds cannot split; the answers must still be the
/// CPU's, both ways.
#[test]
fn gpu_clearances_touching_exactly_are_right() {
    for_each_gpu(|g| {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(37);
        let inp = site(30_000, 6, false);
        let s = Settings { cell_m: 0.25, point_radius_m: 0.0625, ..Settings::default() };
        let (map, _) = build_cpu(&inp, &s).unwrap();
        let on_gpu = g.upload_map(&map).unwrap();
        let lattice: Vec<Obb> =
            (0..2000).map(|_| boxes::lattice_box(&mut rng, [1000.0, 2000.0], [40.0, 30.0], [-16, 420])).collect();
        for way in [Vertical::Down, Vertical::Up] {
            for leave in leave_outs() {
                let (found, counts) = g.clearances_where(&on_gpu, &map, &lattice, way, leave).unwrap();
                let mut touching = 0;
                for (k, b) in lattice.iter().enumerate() {
                    let cpu = map.clearance_where(b, way, |iv| LeaveOut::counts(leave, iv));
                    assert_eq!(found[k], cpu, "box {k} ({b:?}), {way:?}, leaving out {leave:?}");
                    touching += cpu.is_some_and(|c| c.gap_m == 0.0) as usize;
                }
                eprintln!("lattice boxes {way:?} leaving out {leave:?}: {counts:?}, {touching} touch the map exactly");
                assert!(touching > 0, "no box touches exactly: the test does not test what it says");
            }
        }
    });
}

/// A clearance walk longer than the device's loop budget is given up and
/// answered by the CPU (lavapipe would otherwise end it silently).
#[test]
fn gpu_clearance_longer_than_the_loop_budget_is_right() {
    for_each_gpu(|g| {
        let mut inp = Inputs::default();
        for j in 0..200 {
            for i in 0..200 {
                // Rising by 1/64 m a cell in the device walk's order (the
                // quadtree's, z-order): each tile holds a cell higher than any
                // before it, so no tile bound cuts the walk short.
                let z = 90.0 + z_order(i, j) as f64 / 64.0;
                inp.points.push([i as f64 * 0.1 + 0.05, j as f64 * 0.1 + 0.05, z]);
                inp.ground.push(false);
            }
        }
        // Each point in its own cell only: a neighbour's height in a cell's
        // top would let a tile bound skip tiles.
        let s =
            Settings { cell_m: 0.1, point_radius_m: 0.01, extent: vec![0.0, 0.0, 20.0, 20.0], ..Settings::default() };
        let (map, _) = build_cpu(&inp, &s).unwrap();
        let on_gpu = g.upload_map(&map).unwrap();
        let b = Obb::axis_aligned(Point3::new(10.0, 10.0, 2000.0), Vec3::new(9.99, 9.99, 0.5));
        let cpu = map.clearance(&b, Vertical::Up);
        assert!(cpu.is_none(), "{cpu:?}");
        let cpu = map.clearance(&b, Vertical::Down);
        assert!(cpu.is_some_and(|c| c.at.i >= 198 && c.at.j >= 198), "{cpu:?}");
        let (found, counts) = g.clearances_where(&on_gpu, &map, &[b], Vertical::Down, None).unwrap();
        eprintln!("{counts:?}");
        assert_eq!(found[0], cpu);
        if g.loop_cap().is_some() {
            assert_eq!(counts.left_to_cpu, 1, "a walk of 40,000 cells is over lavapipe's budget");
        }
    });
}

/// A clearance walk within the device's loop budget by the shader's own
/// count that Mesa's lavapipe still cut short: its count also takes the
/// iteration in which each loop ends, and this walk ends many short loops.
/// Read as finished, it gave a gap 6 cm larger than the CPU's. The walk's
/// `done` flag sends such a box to the CPU; on a GPU it is answered whole.
#[test]
fn gpu_clearance_walk_cut_short_by_the_device_goes_to_the_cpu() {
    for_each_gpu(|g| {
        let inp = site(40_000, 40_001, true);
        let s = Settings { cell_m: 0.1, mode: Mode::Multi, ..Settings::default() };
        let (map, _) = build_cpu(&inp, &s).unwrap();
        let on_gpu = g.upload_map(&map).unwrap();
        let (c, sn) = (0.872538559727929, 0.4885452505018458);
        let turn = nalgebra::Matrix3::new(c, -sn, 0.0, sn, c, 0.0, 0.0, 0.0, 1.0);
        let b = Obb::new(
            Point3::new(1019.720667928227, 2022.0937481368644, -1.7599987149763696),
            turn,
            Vec3::new(7.602656184928848, 7.664752076727674, 1.9150532673840082),
        );
        let cpu = map.clearance(&b, Vertical::Up);
        assert!(cpu.is_some_and(|c| c.gap_m < -0.2), "{cpu:?}");
        let (found, counts) = g.clearances_where(&on_gpu, &map, &[b], Vertical::Up, None).unwrap();
        eprintln!("{counts:?}");
        assert_eq!(found[0], cpu);
    });
}

/// Under lavapipe's loop cap a walk that ends in time can still lose what
/// it found: the cap counts the loops of eight invocations together, and
/// here the first box's walk (over 22,000 cells, more than the budget) uses
/// it up just as the second box's walk ends. The loop that wrote the second
/// box's cells was then cut after its first cell, the other read back as
/// cell 0, and the device's answer was 1.7 cm more room than the CPU's.
/// Every loop of the walk now shows that it ended by itself.
#[test]
fn gpu_clearance_cells_written_short_by_the_device_go_to_the_cpu() {
    for_each_gpu(|g| {
        let inp = site(40_000, 40_001, true);
        let s = Settings { cell_m: 0.1, mode: Mode::Multi, ..Settings::default() };
        let (map, _) = build_cpu(&inp, &s).unwrap();
        let on_gpu = g.upload_map(&map).unwrap();
        let turn = |a: [f64; 9]| nalgebra::Matrix3::from_column_slice(&a);
        let wide = Obb::new(
            Point3::new(985.2570507156843, 1975.6384068750572, -4.8151592921697715),
            turn([
                -0.05043509885880424,
                -0.9987273405705396,
                0.0,
                0.9987273405705396,
                -0.05043509885880424,
                0.0,
                0.0,
                0.0,
                1.0,
            ]),
            Vec3::new(7.6748469217053765, 7.316211397528752, 1.1919557097337385),
        );
        let tilted = Obb::new(
            Point3::new(1013.9135973466678, 1970.225357328579, -3.2476427001896546),
            turn([
                0.0016664175821087535,
                0.9603562382210256,
                0.27877072795112967,
                -0.8773110280179861,
                -0.13238382570417956,
                0.46130237676598834,
                0.4799193506939124,
                -0.2453373563114393,
                0.8423105118824337,
            ]),
            Vec3::new(2.3581336917866254, 2.677091779430861, 1.9916232327651597),
        );
        let leave = Some(LeaveOut::object(mdm::OBJ_GROUND));
        let cpu: Vec<_> = [wide, tilted]
            .iter()
            .map(|b| map.clearance_where(b, Vertical::Up, |iv| LeaveOut::counts(leave, iv)))
            .collect();
        assert!(cpu[1].is_some_and(|c| c.at.i == 626 && c.at.j == 116), "{cpu:?}");
        let (found, counts) = g.clearances_where(&on_gpu, &map, &[wide, tilted], Vertical::Up, leave).unwrap();
        eprintln!("{counts:?}");
        assert_eq!(found, cpu);
    });
}

/// The cell's place in z-order: the bits of `i` and `j` interleaved, `i`'s
/// first.
fn z_order(i: u32, j: u32) -> u32 {
    (0..16).map(|b| ((i >> b) & 1) << (2 * b) | ((j >> b) & 1) << (2 * b + 1)).sum()
}

/// The dilation's twin gives the CPU's bits: random grids with empty cells,
/// NaN, both zeros and equal values, windows from none to wider than the
/// grid, and a depth map's own cell tops.
#[test]
fn gpu_and_cpu_dilations_are_equal() {
    use liftplan_depthmap::dilate::window_max;
    for_each_gpu(|g| {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let mut grids: Vec<(Vec<f32>, usize, usize, usize)> = Vec::new();
        for &(nx, ny) in &[(1, 1), (1, 9), (9, 1), (17, 5), (64, 48), (300, 257)] {
            for &w in &[0usize, 1, 3, 8, 400] {
                let grid: Vec<f32> = (0..nx * ny)
                    .map(|_| match rng.random_range(0..10) {
                        0..=3 => f32::NEG_INFINITY,
                        4 => f32::NAN,
                        5 => -0.0,
                        6 => 0.0,
                        _ => rng.random_range(0..64) as f32 * 0.25 - 4.0,
                    })
                    .collect();
                grids.push((grid, nx, ny, w));
            }
        }
        let (map, _) = build_cpu(&site(20_000, 3, true), &Settings { cell_m: 0.5, ..Settings::default() }).unwrap();
        let tops = map.pyramid[0].2.clone();
        grids.push((tops, map.spec.nx as usize, map.spec.ny as usize, 9));
        for (grid, nx, ny, w) in &grids {
            let cpu = window_max(grid, *nx, *ny, *w);
            let dev = g.window_max(grid, *nx, *ny, *w).unwrap();
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<u32>>();
            assert_eq!(bits(&dev), bits(&cpu), "{nx} x {ny}, w = {w}");
        }
    });
}
