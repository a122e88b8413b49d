//! The CPU assembly against a plain reference.
//!
//! The CPU rasterises points inside the assembly (8-byte point records, merged
//! by height) while the GPU twin hands the same points over as raw intervals
//! (16-byte keys, merged by bottom and top). Both must give the map a plain
//! per-cell reference gives: every raw interval of a cell sorted by (object,
//! part, bottom, top), runs of one object merged (a convex part whole, other
//! intervals when less than the gap apart), then sorted by (bottom, top,
//! object), or one interval in single-level mode.

use liftplan_core::mesh::TriMesh;
use liftplan_depthmap::mdm::{self, GridSpec, Interval, Mdm, Mode, PointSource, Raw};
use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn key(v: f32) -> u32 {
    mdm::f32_key(v)
}

/// The map of `raws` cell by cell, written as plainly as possible.
fn reference(raws: &[Raw], spec: GridSpec, mode: Mode, gap: f32) -> (Vec<u32>, Vec<Interval>) {
    let mut cells: Vec<Vec<Raw>> = vec![Vec::new(); spec.cells()];
    for r in raws {
        cells[r.cell as usize].push(*r);
    }
    let mut offsets = vec![0u32];
    let mut intervals = Vec::new();
    for mut c in cells {
        c.sort_by_key(|r| (r.obj, r.part, key(r.zlo), key(r.zhi)));
        let mut merged: Vec<(Raw, f32)> = Vec::new();
        for r in c {
            match merged.last_mut() {
                Some((m, hi)) if m.obj == r.obj && m.part == r.part && (r.part != 0 || r.zlo <= *hi + gap) => {
                    *hi = hi.max(r.zhi)
                }
                _ => merged.push((r, r.zhi)),
            }
        }
        let mut out: Vec<Interval> =
            merged.iter().map(|(m, hi)| Interval { zlo: m.zlo, zhi: *hi, obj: m.obj }).collect();
        out.sort_by_key(|i| (key(i.zlo), key(i.zhi), i.obj));
        if mode == Mode::Single && !out.is_empty() {
            let lo = out.iter().map(|i| i.zlo).min_by_key(|z| key(*z)).unwrap();
            let top = *out.iter().rev().max_by_key(|i| key(i.zhi)).unwrap();
            out = vec![Interval { zlo: lo, zhi: top.zhi, obj: top.obj }];
        }
        intervals.extend(out);
        offsets.push(intervals.len() as u32);
    }
    (offsets, intervals)
}

struct Scene {
    xyz: Vec<[f64; 3]>,
    ground: Vec<bool>,
    mesh: TriMesh,
}

/// Points around (and a few outside) the grid, many at equal heights (a
/// ground plane and a quantised set) so ties and merges are common, some
/// triangles and boxes (convex parts) across cells.
fn scene(seed: u64, spec: &GridSpec, n: usize) -> Scene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (w, h) = (spec.nx as f64 * spec.cell, spec.ny as f64 * spec.cell);
    let mut s = Scene { xyz: vec![], ground: vec![], mesh: TriMesh::default() };
    for _ in 0..n {
        let x = spec.x0 + rng.random::<f64>() * (w + 2.0) - 1.0;
        let y = spec.y0 + rng.random::<f64>() * (h + 2.0) - 1.0;
        let (z, g) = match rng.random_range(0..4) {
            0 => (0.0, true),
            // Multiples of 1/16 m: with the radii and gaps below, exact
            // touching (bottom = top + gap) happens.
            1 => (rng.random_range(0..24) as f64 * 0.0625, false),
            2 => (rng.random::<f64>() * 3.0, rng.random::<bool>()),
            _ => (-rng.random::<f64>(), false),
        };
        s.xyz.push([x, y, z]);
        s.ground.push(g);
    }
    let g = s.mesh.group_id("pipe");
    let q = s.mesh.group_id("rack");
    for _ in 0..6 {
        let c = [spec.x0 + rng.random::<f64>() * w, spec.y0 + rng.random::<f64>() * h, rng.random::<f64>() * 2.0];
        let t: Vec<[f64; 3]> = (0..3)
            .map(|_| [c[0] + rng.random::<f64>() - 0.5, c[1] + rng.random::<f64>() - 0.5, c[2] + rng.random::<f64>()])
            .collect();
        s.mesh.add_part(g, false, &t, &[[0, 1, 2]]);
        let lo = [c[0], c[1], c[2]];
        s.mesh.add_box(q, lo, [lo[0] + 0.4, lo[1] + 0.3, lo[2] + 0.5]);
    }
    s
}

fn check(seed: u64, spec: GridSpec, radius: f32, gap: f32, mode: Mode, n: usize) -> Result<(), TestCaseError> {
    let s = scene(seed, &spec, n);
    let points = PointSource { xyz: &s.xyz, ground: &s.ground, radius };
    let tris: Vec<Raw> = mdm::mesh_raws(&s.mesh, &spec, 2).concat();
    let mut all = Vec::new();
    mdm::point_raws(&points, &spec, &mut all);
    // The counts the build's memory budget is checked with bound what is made.
    let (from_points, from_mesh) = (all.len() as u64, tris.len() as u64);
    prop_assert_eq!(mdm::point_cells(&points, &spec), from_points);
    prop_assert!(mdm::point_cells_bound(&points, &spec) >= from_points);
    let mesh_cells = mdm::mesh_cells(&s.mesh, &spec);
    prop_assert!(mesh_cells >= from_mesh && mdm::mesh_cells_bound(&s.mesh, &spec) >= mesh_cells);
    all.extend_from_slice(&tris);
    let objects = vec!["g".to_string(), "s".into(), "pipe".into(), "rack".into()];
    // The mesh rasterised into the assembly's jobs, and everything as raws.
    let mesh_jobs = mdm::mesh_jobs(&s.mesh, &spec, 2);
    prop_assert_eq!(mesh_jobs.iter().map(mdm::RawJob::len).sum::<usize>(), tris.len());
    let fused: Mdm = mdm::assemble_sources(Some(points), &mesh_jobs, spec, mode, gap, objects.clone());
    let mut jobs = mdm::raw_jobs(&all[..all.len() / 2], &spec);
    jobs.extend(mdm::raw_jobs(&all[all.len() / 2..], &spec));
    let as_raws: Mdm = mdm::assemble_sources(None, &jobs, spec, mode, gap, objects);
    let (offsets, intervals) = reference(&all, spec, mode, gap);
    prop_assert!(fused.offsets == offsets && fused.intervals == intervals, "points rasterised in the assembly differ");
    prop_assert!(as_raws.offsets == offsets && as_raws.intervals == intervals, "points as raw intervals differ");
    let mut read_back = fused.clone();
    read_back.build_pyramid();
    prop_assert!(read_back.pyramid == fused.pyramid, "the pyramid differs from one built from the intervals");
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(64)))]
    #[test]
    fn assembly_matches_the_reference(
        seed in any::<u64>(),
        nx in 1u32..60,
        ny in 1u32..40,
        cell in prop::sample::select(vec![0.1, 0.25, 0.5]),
        radius in prop::sample::select(vec![0.0f32, 0.05, 0.0625, 0.12, 0.3]),
        gap in prop::sample::select(vec![0.0f32, 0.1, 0.125]),
        single in any::<bool>(),
    ) {
        let spec = GridSpec { x0: 1000.0, y0: -500.0, cell, nx, ny };
        check(seed, spec, radius, gap, if single { Mode::Single } else { Mode::Multi }, 400)?;
    }
}

/// Grids wider than a band (one row per band), narrow ones (many rows), and
/// tiny ones whose cells hold thousands of points (sorted by radix).
#[test]
fn assembly_matches_the_reference_on_wide_narrow_and_crowded_grids() {
    for (nx, ny) in [(3000, 3), (2049, 2), (2, 3000), (700, 9), (2, 2), (4, 1)] {
        let spec = GridSpec { x0: 0.0, y0: 0.0, cell: 0.25, nx, ny };
        check(11, spec, 0.0625, 0.125, Mode::Multi, 20_000).unwrap();
    }
}

/// One crowded cell whose points sit at heights exactly one "touching"
/// distance apart (2 radius + gap) or further, in random order: the merge
/// must join the touching ones and only those, however many there are.
#[test]
fn crowded_cell_joins_exactly_touching_points() {
    let spec = GridSpec { x0: 0.0, y0: 0.0, cell: 1.0, nx: 1, ny: 1 };
    let (radius, gap) = (0.0625f32, 0.125f32);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let levels = [0.0, 0.25, 0.5, 1.5, 1.75, 3.0, 3.3125, 5.0];
    for n in [70, 300, 2000] {
        let xyz: Vec<[f64; 3]> = (0..n).map(|_| [0.5, 0.5, levels[rng.random_range(0..levels.len())]]).collect();
        let ground: Vec<bool> = (0..n).map(|_| rng.random_range(0..4) == 0).collect();
        let points = PointSource { xyz: &xyz, ground: &ground, radius };
        let mut raws = Vec::new();
        mdm::point_raws(&points, &spec, &mut raws);
        let fused = mdm::assemble_sources(Some(points), &[], spec, Mode::Multi, gap, vec!["g".into(), "s".into()]);
        let (offsets, intervals) = reference(&raws, spec, Mode::Multi, gap);
        assert_eq!((fused.offsets, fused.intervals), (offsets, intervals), "{n} points");
    }
}

/// Settings that would make the build's work or memory blow up are refused
/// with a message naming the setting, before anything is rasterised.
#[test]
fn oversized_point_radius_is_refused() {
    use liftplan_depthmap::{Inputs, Settings, build_cpu};
    let inp = Inputs { points: vec![[0.0, 0.0, 0.0]], ground: vec![false], ..Inputs::default() };
    let s = Settings { cell_m: 0.05, point_radius_m: 5.0, ..Settings::default() };
    let err = build_cpu(&inp, &s).expect_err("a 100-cell radius must be refused").to_string();
    assert!(err.contains("point_radius_m"), "{err}");
    let ok = Settings { cell_m: 0.05, point_radius_m: 0.4, ..Settings::default() };
    assert!(build_cpu(&inp, &ok).is_ok());
}

/// A map that would be built from more raw intervals than the budget
/// (`MAX_RAW_INTERVALS`) is refused before anything is rasterised: here ten
/// floor slabs of 79 x 79 m at 1 cm cells, 624 M raw intervals (about 20 GB
/// to assemble). The same slabs at 25 cm build.
#[test]
fn a_map_too_large_to_assemble_is_refused() {
    use liftplan_depthmap::{Inputs, MAX_RAW_INTERVALS, Settings, build_cpu};
    let mut mesh = TriMesh::default();
    let g = mesh.group_id("floors");
    for k in 0..10 {
        let z = 3.0 * k as f64;
        let v = [[0.0, 0.0, z], [79.0, 0.0, z], [79.0, 79.0, z], [0.0, 79.0, z]];
        mesh.add_part(g, false, &v, &[[0, 1, 2], [0, 2, 3]]);
    }
    let inp = Inputs { mesh, ..Inputs::default() };
    let extent = vec![0.0, 0.0, 79.0, 79.0];
    let fine = Settings { cell_m: 0.01, extent: extent.clone(), ..Settings::default() };
    let bound = mdm::mesh_cells(&inp.mesh, &fine.grid([0.0, 0.0, 79.0, 79.0]).unwrap());
    assert!(bound > MAX_RAW_INTERVALS, "{bound}");
    let err = build_cpu(&inp, &fine).expect_err("624 M raw intervals must be refused").to_string();
    assert!(
        err.contains("raw intervals (0 from scan points") && err.contains("use a larger cell_m (now 0.01 m)"),
        "{err}"
    );
    let coarse = Settings { cell_m: 0.25, extent, ..Settings::default() };
    let (m, _) = build_cpu(&inp, &coarse).unwrap();
    assert_eq!(m.intervals.len(), 10 * 316 * 316);
}
