//! The independent validator.
//!
//! It shares no collision code with the planner: no depth map, no C-space, no
//! grown boxes. It measures exact distances (parry3d, f64) from every crane part
//! to the original plant triangles and the site points, along every move
//! sampled so that no point of the crane moves more than `sample_m` (finer than
//! the planner) and more finely wherever two samples leave room for a part to
//! come closer than its requirement between them, so that the clearance holds
//! along the whole motion to within 2 mm; it keeps the load and its rigging
//! off the crane's own structure, re-reads the load chart at every sample, and
//! checks that the moves make one path from the load's pick pose to its set
//! pose. What it shares with the planner is the crane's forward kinematics
//! (the part boxes) and the lift's rules (clearance, landing zones, chart,
//! permitted swing range), which it applies itself.
//!
//! A plan it rejects is never written as a plan.

use crate::path::Move;
use liftplan_core::capacity::ChartConfig;
use liftplan_core::crane::{Config, CranePose, Dependence, PartKind};
use liftplan_core::lift::{LiftTask, NotOver};
use liftplan_core::mesh::TriMesh;
use liftplan_core::obb::Obb;
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::{self, PointQuery, PointQueryWithLocation};
use parry3d_f64::shape::{ConvexPolyhedron, Cuboid, Segment, TriMesh as ParryMesh, TrianglePointLocation};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::HashMap;

/// Site points grouped by 1 m voxel, with their ground flag.
///
/// The voxels are kept in ascending `(x, y, z)` order and a voxel's points in
/// input order, so a search that visits them in that order meets the points in
/// one fixed order, whatever the build: of two obstacles at the same distance
/// the validator names the same one on every run.
pub struct PointIndex {
    /// Occupied voxels, ascending.
    keys: Vec<[i32; 3]>,
    /// The points of voxel `k` are `points[starts[k]..starts[k + 1]]`.
    starts: Vec<usize>,
    points: Vec<([f64; 3], bool)>,
    /// Voxel to its place in `keys`.
    place: HashMap<[i32; 3], u32>,
    pub count: usize,
}

pub(crate) const VOXEL_M: f64 = 1.0;

fn voxel(p: &[f64; 3]) -> [i32; 3] {
    [(p[0] / VOXEL_M).floor() as i32, (p[1] / VOXEL_M).floor() as i32, (p[2] / VOXEL_M).floor() as i32]
}

impl PointIndex {
    /// Sorts the points by voxel, in parallel (a hash map of growing lists,
    /// one push per point, took 3.4 s for 10 M points where this takes 0.9 s:
    /// `examples/bench_point_index`).
    pub fn new(points: &[[f64; 3]], ground: &[bool]) -> Result<PointIndex, String> {
        if ground.len() != points.len() {
            return Err(format!(
                "{} site points but {} ground flags: each point needs one",
                points.len(),
                ground.len()
            ));
        }
        if points.len() > u32::MAX as usize {
            return Err(format!("{} site points: the validator indexes at most {}", points.len(), u32::MAX));
        }
        let mut order: Vec<([i32; 3], u32)> =
            points.par_iter().enumerate().map(|(i, p)| (voxel(p), i as u32)).collect();
        // (voxel, index) pairs are distinct, so the unstable sort's order is the one order.
        order.par_sort_unstable();
        let mut keys: Vec<[i32; 3]> = Vec::new();
        let mut starts: Vec<usize> = Vec::new();
        for (k, (key, _)) in order.iter().enumerate() {
            if keys.last() != Some(key) {
                keys.push(*key);
                starts.push(k);
            }
        }
        starts.push(order.len());
        let sorted = order.par_iter().map(|&(_, i)| (points[i as usize], ground[i as usize])).collect();
        let place = keys.iter().enumerate().map(|(k, key)| (*key, k as u32)).collect();
        Ok(PointIndex { keys, starts, points: sorted, place, count: points.len() })
    }

    /// Number of occupied voxels.
    pub fn voxels(&self) -> usize {
        self.keys.len()
    }

    /// The plan columns (x, y voxel indices) holding a point, each once.
    pub(crate) fn columns(&self) -> impl Iterator<Item = (i32, i32)> + '_ {
        // Keys ascend by x, then y: a column's voxels lie together.
        self.keys
            .iter()
            .map(|k| (k[0], k[1]))
            .enumerate()
            .filter_map(move |(n, c)| (n == 0 || (self.keys[n - 1][0], self.keys[n - 1][1]) != c).then_some(c))
    }

    fn voxel_points(&self, k: usize) -> &[([f64; 3], bool)] {
        &self.points[self.starts[k]..self.starts[k + 1]]
    }

    /// The occupied voxels of the range `lo ..= hi`, in ascending order.
    /// Voxels are sorted by x first: those of the range's x lie together.
    fn occupied_in(&self, lo: [i32; 3], hi: [i32; 3]) -> impl Iterator<Item = usize> + '_ {
        let first = self.keys.partition_point(|k| k[0] < lo[0]);
        let end = self.keys.partition_point(|k| k[0] <= hi[0]);
        (first..end).filter(move |&k| (1..3).all(|a| lo[a] <= self.keys[k][a] && self.keys[k][a] <= hi[a]))
    }

    /// Whether the range `lo ..= hi` has more voxels than are occupied in
    /// all: then walking the occupied ones is cheaper than looking up each
    /// voxel of the range.
    fn walk_occupied(&self, lo: [i32; 3], hi: [i32; 3]) -> bool {
        let n_vox = (0..3).map(|a| hi[a] as i64 - lo[a] as i64 + 1).fold(1i64, i64::saturating_mul);
        n_vox > self.keys.len() as i64
    }

    /// The occupied voxels of the range `lo ..= hi`, found the cheaper way
    /// ([`Self::walk_occupied`]).
    fn voxels_in(&self, lo: [i32; 3], hi: [i32; 3]) -> Box<dyn Iterator<Item = usize> + '_> {
        if self.walk_occupied(lo, hi) {
            Box::new(self.occupied_in(lo, hi))
        } else {
            Box::new((lo[0]..=hi[0]).flat_map(move |x| {
                (lo[1]..=hi[1]).flat_map(move |y| {
                    (lo[2]..=hi[2]).filter_map(move |z| self.place.get(&[x, y, z]).map(|&k| k as usize))
                })
            }))
        }
    }

    /// The highest point (ground or not) in the plan rectangle `lo ..= hi`
    /// lower than `below_z`; `None` where none is.
    pub fn highest_in(&self, lo: [f64; 2], hi: [f64; 2], below_z: f64) -> Option<f64> {
        let (vlo, vhi) = (voxel(&[lo[0], lo[1], 0.0]), voxel(&[hi[0], hi[1], below_z]));
        self.occupied_in([vlo[0], vlo[1], i32::MIN], [vhi[0], vhi[1], vhi[2]])
            .flat_map(|k| self.voxel_points(k))
            .map(|(p, _)| p)
            .filter(|p| (lo[0]..=hi[0]).contains(&p[0]) && (lo[1]..=hi[1]).contains(&p[1]) && p[2] < below_z)
            .map(|p| p[2])
            .max_by(f64::total_cmp)
    }

    /// Heights of the ground points inside any of the plan polygons
    /// `areas`, at any height.
    fn ground_heights_in(&self, areas: &[Vec<[f64; 2]>]) -> Vec<f64> {
        let Some((lo, hi)) = plan_bounds(areas.iter().flatten()) else { return Vec::new() };
        let (vlo, vhi) = (voxel(&[lo[0], lo[1], 0.0]), voxel(&[hi[0], hi[1], 0.0]));
        self.occupied_in([vlo[0], vlo[1], i32::MIN], [vhi[0], vhi[1], i32::MAX])
            .flat_map(|k| self.voxel_points(k))
            .filter(|(p, ground)| *ground && areas.iter().any(|a| in_polygon(a, [p[0], p[1]])))
            .map(|(p, _)| p[2])
            .collect()
    }
}

/// How well the plant model and the scans agree where both see the site:
/// of the scanned structure points (ground left out) within
/// [`AGREEMENT_NEAR_M`] of the model, how many lie within
/// [`AGREEMENT_CLOSE_M`] of its surface. Scan points lie on what the
/// scanners saw, so where the model is placed right the points of what it
/// models lie on it. A model placed wrong in the site frame (a PDMS origin,
/// a missed `[plant] translate_m`) puts its obstacles where they are not,
/// and where the scans did not see them nothing else would.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct ModelScanAgreement {
    /// Scan points within [`AGREEMENT_NEAR_M`] of the model, of those sampled.
    pub compared: usize,
    /// Of those, the share within [`AGREEMENT_CLOSE_M`] of it (%).
    pub close_pct: f64,
    /// Their median distance to the model (m).
    pub median_m: f64,
    /// Where the model disagrees: the move that puts it on the scans, where
    /// one is found ([`model_offset_to_scans`]).
    #[serde(default)]
    pub fits_moved_by: Option<ModelMove>,
}

/// A plant model's move onto the scans: turned by `turn_deg`
/// (counter-clockwise seen from above) about the site point `about_m`, then
/// moved by `by_m` in plan and `z_m` up.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct ModelMove {
    /// Site x and y (m).
    pub by_m: [f64; 2],
    /// Up (m).
    #[serde(default)]
    pub z_m: f64,
    pub turn_deg: f64,
    /// Site x and y (m).
    pub about_m: [f64; 2],
    /// The share of the scan points near the model within
    /// [`AGREEMENT_CLOSE_M`] of it once moved (%).
    pub close_pct: f64,
}

impl ModelMove {
    /// The move in words.
    pub fn said(&self) -> String {
        // No "-0.00 m" for a move that is none along an axis.
        let tidy = |v: f64, below: f64| if v.abs() < below { 0.0 } else { v };
        let (dx, dy) = (tidy(self.by_m[0], 0.005), tidy(self.by_m[1], 0.005));
        let dz = tidy(self.z_m, 0.005);
        let turn = tidy(self.turn_deg, 0.005);
        let shift = match (dx != 0.0 || dy != 0.0, dz != 0.0) {
            (true, false) => format!("moved by x {dx:+.2} m, y {dy:+.2} m"),
            (true, true) => format!("moved by x {dx:+.2} m, y {dy:+.2} m, z {dz:+.2} m"),
            (false, true) => format!("moved by z {dz:+.2} m"),
            // No move at all is said as one, not as nothing.
            (false, false) if turn == 0.0 => format!("moved by x {dx:+.2} m, y {dy:+.2} m"),
            (false, false) => String::new(),
        };
        match (turn != 0.0, shift.is_empty()) {
            (false, _) => shift,
            (true, true) => {
                format!("turned by {turn:+.2}° about x {:.1} m, y {:.1} m", self.about_m[0], self.about_m[1])
            }
            (true, false) => {
                format!(
                    "turned by {turn:+.2}° about x {:.1} m, y {:.1} m and {shift}",
                    self.about_m[0], self.about_m[1]
                )
            }
        }
    }
}

impl ModelScanAgreement {
    /// Whether fewer than half the scan points near the model lie on it, or
    /// a move puts many more of them on it.
    pub fn disagrees(&self) -> bool {
        !(self.median_m <= AGREEMENT_CLOSE_M) || self.fits_moved_by.is_some()
    }

    /// One line for the run's output and the PDF.
    pub fn line(&self) -> String {
        let verdict = match (self.disagrees(), self.fits_moved_by) {
            (true, Some(m)) => format!(
                "the model lies on the scans when {} ({:.0} % of the points within {AGREEMENT_CLOSE_M:.2} m of it then): CHECK [plant] translate_m and rotate_z_deg: as it is, its obstacles the scans did not see are elsewhere",
                m.said(),
                m.close_pct
            ),
            (true, None) => "CHECK [plant] translate_m and rotate_z_deg: the model may not be where the scans put the site, and its obstacles the scans did not see would then be elsewhere".to_string(),
            (false, _) => "they agree".to_string(),
        };
        format!(
            "plant model against the scans: of {} scanned points within {AGREEMENT_NEAR_M:.0} m of the model, {:.0} % lie within {AGREEMENT_CLOSE_M:.2} m of it (median {:.3} m): {verdict}",
            self.compared, self.close_pct, self.median_m
        )
    }
}

/// See [`ModelScanAgreement`] (m).
pub const AGREEMENT_NEAR_M: f64 = 1.0;
pub const AGREEMENT_CLOSE_M: f64 = 0.1;
/// Scan points sampled at most: every k-th structure point.
const AGREEMENT_SAMPLES: usize = 20_000;

/// [`ModelScanAgreement`] of the model and the scans in `world`; `None`
/// where fewer than 50 sampled scan points lie near the model (the two
/// barely overlap, or there is no scan or no model).
pub fn model_scan_agreement(world: &World) -> Option<ModelScanAgreement> {
    let mesh = world.mesh.as_ref()?;
    let structure: Vec<&[f64; 3]> = world.points.points.iter().filter(|(_, g)| !g).map(|(p, _)| p).collect();
    let stride = structure.len().div_ceil(AGREEMENT_SAMPLES).max(1);
    let mut d: Vec<f64> = structure
        .par_iter()
        .step_by(stride)
        .filter_map(|p| {
            let q = Vector::new(p[0], p[1], p[2]);
            let d = mesh.distance_to_point(&Pose::identity(), q, false);
            (d <= AGREEMENT_NEAR_M).then_some(d)
        })
        .collect();
    if d.len() < 50 {
        return None;
    }
    d.sort_by(f64::total_cmp);
    let close = d.partition_point(|&x| x <= AGREEMENT_CLOSE_M);
    let median_m = d[d.len() / 2];
    let sampled: Vec<[f64; 3]> = structure.iter().step_by(stride).map(|p| **p).collect();
    let fits_moved_by = model_offset_to_scans(mesh, &sampled);
    Some(ModelScanAgreement {
        compared: d.len(),
        close_pct: 100.0 * close as f64 / d.len() as f64,
        median_m,
        fits_moved_by,
    })
}

/// How far a model may be off for [`model_offset_to_scans`] to find it (m).
pub const OFFSET_SEARCH_M: f64 = 4.0;

/// The move of `mesh` (a turn about z and a shift in x, y and z) that puts
/// it on the scan points `points`, where the move is more than
/// [`AGREEMENT_CLOSE_M`] at the points (less is within what "on the model"
/// allows) and then more than half of those near the model lie within
/// [`AGREEMENT_CLOSE_M`] of it, among them at least half of those that were
/// not before and [`MOVE_GAIN_PCT`] of all: point-to-plane alignment of the
/// points within [`OFFSET_SEARCH_M`] of the model, each step trusting only
/// points closer than three times the last step's median distance. It
/// informs the engineer's `[plant] translate_m` and `rotate_z_deg`; the
/// model is not moved.
///
/// The height is sought only where at least 50 of the points lie on or off
/// level faces of the model (tops of foundations, slabs, equipment): walls and
/// columns alone do not say it. A model off by a height datum has its
/// walls and columns where the scans have them, so most points still lie
/// on it (the demo's model 1 m low: 78 % of them, median 6 mm): the gain
/// in points on it once moved says it, not their median.
pub fn model_offset_to_scans(mesh: &ParryMesh, points: &[[f64; 3]]) -> Option<ModelMove> {
    // The scan points in the model's frame, given the model's move so far
    // (turned by `w` about `c`, then shifted by `t`), and how far each lies
    // off the model: the offset from its nearest model point.
    let to_model = |p: &[f64; 3], t: [f64; 3], w: f64, c: [f64; 2]| {
        let (x, y) = (p[0] - c[0] - t[0], p[1] - c[1] - t[1]);
        let (sin, cos) = (-w).sin_cos();
        Vector::new(c[0] + x * cos - y * sin, c[1] + x * sin + y * cos, p[2] - t[2])
    };
    // Each near point: its nearest model point, the direction it lies off
    // the model (the face's normal where it projects onto a face's inside,
    // true point-to-plane; else from that point), how far along it, and its
    // distance.
    let near = |t: [f64; 3], w: f64, c: [f64; 2], within: f64| -> Vec<Off> {
        points
            .par_iter()
            .filter_map(|p| {
                let q = to_model(p, t, w, c);
                let (proj, (tri, at)) = mesh.project_local_point_and_get_location(q, false);
                let r = q - proj.point;
                let d = r.length();
                let face = match at {
                    TrianglePointLocation::OnFace(..) => mesh.triangle(tri).normal(),
                    _ => None,
                };
                let dir = face.or_else(|| (d >= 1e-6).then(|| r / d));
                (d <= within).then(|| Off { on: proj.point, dir, along: dir.map_or(0.0, |n| n.dot(r)), d })
            })
            .collect()
    };
    // Of the points at distances `ds`, the share within AGREEMENT_CLOSE_M (%).
    let close_share = |ds: &mut dyn Iterator<Item = f64>| {
        let (n, close) =
            ds.fold((0usize, 0usize), |(n, close), d| (n + 1, close + usize::from(d <= AGREEMENT_CLOSE_M)));
        100.0 * close as f64 / n.max(1) as f64
    };
    let first = near([0.0; 3], 0.0, [0.0, 0.0], OFFSET_SEARCH_M);
    // As the model is: the points near it among those within the search.
    let before_pct = close_share(&mut first.iter().map(|o| o.d).filter(|d| *d <= AGREEMENT_NEAR_M));
    if first.len() < 50 {
        return None;
    }
    // Turned about the points' centre, and weighed by their spread about it,
    // so that a turn and a shift are alike in size.
    let c = {
        let n = first.len() as f64;
        [first.iter().map(|o| o.on.x).sum::<f64>() / n, first.iter().map(|o| o.on.y).sum::<f64>() / n]
    };
    let spread = (first.iter().map(|o| (o.on.x - c[0]).powi(2) + (o.on.y - c[1]).powi(2)).sum::<f64>()
        / first.len() as f64)
        .sqrt()
        .max(1.0);
    // First in plan (x, y and the turn), then the height too: sought
    // together from the start, points beside a wall's foot were taken for
    // the slab's top, and a height found that nothing supports once the
    // wall is placed.
    let (mut t, mut w) = ([0.0f64; 3], 0.0f64);
    for seek_height in [false, true] {
        let mut within = OFFSET_SEARCH_M;
        for _ in 0..40 {
            let pairs = near(t, w, c, within);
            if pairs.len() < 50 {
                return None;
            }
            let mut ds: Vec<f64> = pairs.iter().map(|o| o.d).collect();
            ds.sort_by(f64::total_cmp);
            let median = ds[ds.len() / 2];
            // Each point off the model by `along` its direction: the model's
            // shift (x, y, z) and turn (about c, in metres at the spread) in
            // its own frame that best cancel them.
            let (mut a, mut b) = ([[0.0f64; 4]; 4], [0.0f64; 4]);
            let mut on_level_faces = 0;
            for o in &pairs {
                let Some(n) = o.dir else { continue };
                on_level_faces += usize::from(n.z.abs() > 0.7);
                let turn = (n.y * (o.on.x - c[0]) - n.x * (o.on.y - c[1])) / spread;
                let row = [n.x, n.y, n.z, turn];
                for i in 0..4 {
                    for j in 0..4 {
                        a[i][j] += row[i] * row[j];
                    }
                    b[i] += row[i] * o.along;
                }
            }
            let step = if !seek_height {
                let plan = [0, 1, 3];
                solve(plan.map(|i| plan.map(|j| a[i][j])), plan.map(|i| b[i])).map(|s| [s[0], s[1], 0.0, s[2]])
            } else if on_level_faces >= 50 {
                solve(a, b)
            } else {
                // Walls and columns alone: the height is not sought.
                break;
            };
            let Some(step) = step else {
                // On the model already, or faces of too few directions to
                // say (in plan: nothing to find; the height: as in plan).
                if median <= AGREEMENT_CLOSE_M || seek_height {
                    break;
                }
                return None;
            };
            // In the site frame: the shift turned by the turn so far.
            let (sin, cos) = w.sin_cos();
            t = [t[0] + step[0] * cos - step[1] * sin, t[1] + step[0] * sin + step[1] * cos, t[2] + step[2]];
            w += step[3] / spread;
            within = (3.0 * median).clamp(AGREEMENT_NEAR_M, OFFSET_SEARCH_M);
            if step[0].hypot(step[1]).max(step[2].abs()).max(step[3].abs()) < 1e-3 {
                break;
            }
        }
    }
    let after = near(t, w, c, AGREEMENT_NEAR_M);
    let close_pct = close_share(&mut after.iter().map(|o| o.d));
    let moved_m = t[0].hypot(t[1]).max(t[2].abs()).max(w.abs() * spread);
    // Of the points off the model, the move puts at least half on it, and
    // they are not a handful.
    let gain = close_pct - before_pct;
    if !(moved_m > AGREEMENT_CLOSE_M
        && after.len() >= 50
        && close_pct > 50.0
        && gain >= MOVE_GAIN_PCT
        && gain >= (100.0 - before_pct) / 2.0)
    {
        return None;
    }
    // A turn and a shift are one turn about another point, the one the
    // move leaves where it is (a model turned about its own origin by a
    // wrong rotate_z_deg is turned back about that origin); said so where
    // that point is near the site.
    let (sin, cos) = w.sin_cos();
    let det = 2.0 * (1.0 - cos);
    if w.abs().to_degrees() >= 0.05 && det > 0.0 {
        let f = [c[0] + ((1.0 - cos) * t[0] - sin * t[1]) / det, c[1] + (sin * t[0] + (1.0 - cos) * t[1]) / det];
        if (f[0] - c[0]).hypot(f[1] - c[1]) <= TURN_ABOUT_WITHIN_M {
            return Some(ModelMove { by_m: [0.0, 0.0], z_m: t[2], turn_deg: w.to_degrees(), about_m: f, close_pct });
        }
    }
    Some(ModelMove { by_m: [t[0], t[1]], z_m: t[2], turn_deg: w.to_degrees(), about_m: c, close_pct })
}

/// A scan point near the model, as [`model_offset_to_scans`] sees it.
struct Off {
    /// Its nearest model point.
    on: Vector,
    /// The direction it lies off the model along, where one is known.
    dir: Option<Vector>,
    /// How far along `dir` (m).
    along: f64,
    /// Its distance to the model (m).
    d: f64,
}

/// How many more of the points near the model (percentage points) must lie
/// on it once moved, at least, for [`model_offset_to_scans`] to say the
/// move: a handful is how a model and scans of a real plant differ (an
/// item moved since, scan noise), not a misplaced model.
pub const MOVE_GAIN_PCT: f64 = 2.0;

/// How far from the scan points a turn that moves a model onto them may be
/// said to be about, rather than a turn about them and a shift (m).
const TURN_ABOUT_WITHIN_M: f64 = 5_000.0;

/// `a x = b` by Gaussian elimination with partial pivoting; `None` where
/// `a` is near singular (faces of too few directions to fix every unknown).
fn solve<const N: usize>(mut a: [[f64; N]; N], mut b: [f64; N]) -> Option<[f64; N]> {
    let scale = (0..N).map(|i| a[i][i].abs()).sum::<f64>();
    for col in 0..N {
        let pivot = (col..N).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if !(a[pivot][col].abs() > 1e-7 * scale) {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..N {
            let f = a[row][col] / a[col][col];
            for k in col..N {
                a[row][k] -= f * a[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; N];
    for row in (0..N).rev() {
        let rest: f64 = (row + 1..N).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - rest) / a[row][row];
    }
    Some(x)
}

/// How far the scanned ground under a mobile crane's carrier and outriggers
/// may lie from the level the lift sets the crane up at (m): mats, cribbing,
/// uneven ground. Farther, the lift has the crane at the wrong height (a
/// site in survey heights with `ground_z_m = 0`, say), and every clearance
/// of the plan would be measured from a crane that is not where it stands.
pub const SET_UP_LEVEL_TOLERANCE_M: f64 = 0.5;

/// Why the crane does not stand within one of the areas the lift gives it
/// (`crane_stands_in`), in words; `None` where it does, or where the lift
/// gives none. The rule is the lift's: the hull of what stands on the
/// ground (`LiftTask::standing_corners`: its fixed parts' outlines and its
/// pads' mats), inside an area and clear of its edges. Core's
/// `LiftTask::stands_outside_its_areas` is how the planner applies it; the
/// test is written again here, by other means, so that a mistake in one is
/// not in both: the hull is parry3d's (as a slab 1 m deep), kept off each
/// of the area's edges by parry3d's distance, its corners inside the area
/// by their winding number.
pub fn crane_outside_its_areas(task: &LiftTask) -> Option<String> {
    if task.crane_stands_in.is_empty() {
        return None;
    }
    let corners = task.standing_corners();
    let slab_corners: Vec<Vector> =
        corners.iter().flat_map(|c| [Vector::new(c[0], c[1], 0.0), Vector::new(c[0], c[1], 1.0)]).collect();
    let slab = ConvexPolyhedron::from_convex_hull(&slab_corners);
    let within = |area: &liftplan_core::lift::CraneArea| {
        let Some(slab) = &slab else { return false };
        let poly = &area.corners_m;
        let n = poly.len();
        n >= 3
            && slab.points().iter().all(|p| winding_number(poly, [p.x, p.y]) != 0)
            && (0..n).all(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                let edge = Segment::new(Vector::new(a[0], a[1], 0.5), Vector::new(b[0], b[1], 0.5));
                query::distance(&Pose::identity(), slab, &Pose::identity(), &edge).is_ok_and(|d| d.distance > 0.0)
            })
    };
    if task.crane_stands_in.iter().any(within) {
        return None;
    }
    let names: Vec<String> = task.crane_stands_in.iter().map(|a| format!("'{}'", a.name)).collect();
    let p = &task.crane.placement;
    Some(format!(
        "the crane set up at position_m = [{:.2}, {:.2}], heading_deg = {:.0}: its carrier and outriggers{} do not stand within an area it may stand in, clear of its edges (crane_stands_in: {})",
        p.x_m,
        p.y_m,
        p.heading_rad.to_degrees(),
        if task.mat_half_m().is_some() { " with their mats" } else { "" },
        names.join(", ")
    ))
}

/// How many times the polygon `poly` winds round `p` (0: outside).
fn winding_number(poly: &[[f64; 2]], p: [f64; 2]) -> i32 {
    let n = poly.len();
    let mut wn = 0;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        // Which side of the edge a->b the point lies on (> 0: left).
        let side = (b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1]);
        if a[1] <= p[1] {
            if b[1] > p[1] && side > 0.0 {
                wn += 1;
            }
        } else if b[1] <= p[1] && side < 0.0 {
            wn -= 1;
        }
    }
    wn
}

/// How far around a tower crane's mast the scanned ground is read (m).
pub const TOWER_GROUND_AROUND_M: f64 = 3.0;

/// What the load comes to rest on at its set position: the nearest obstacle
/// under its footprint and how far below its underside.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct SetSupport {
    /// From the load's underside down to the obstacle (m, within 2 mm).
    pub gap_m: f64,
    pub object: String,
    /// How far inside the edge of what the load comes to rest on its centre
    /// of gravity lies, in plan (m; negative: beyond it, where nothing known
    /// holds it): [`cog_over_support_m`]. `None` where it was not measured
    /// (the support's top went with a load's cut-out).
    #[serde(default)]
    pub cog_inside_m: Option<f64>,
    /// The centre of gravity's tolerance (`load.cog_tolerance_m`) that
    /// `cog_inside_m` is the least over (m; 0: none given).
    #[serde(default, skip_serializing_if = "liftplan_core::is_zero")]
    pub cog_tolerance_m: f64,
}

impl SetSupport {
    /// The load's centre of gravity is not known to lie over what holds it
    /// ([`COG_INSIDE_SUPPORT_M`]).
    pub fn tips(&self) -> bool {
        self.cog_inside_m.is_some_and(|m| !(m >= COG_INSIDE_SUPPORT_M))
    }

    /// Where the load does not tip, how far inside its centre of gravity lies, in few words.
    pub fn cog_inside_said(&self) -> Option<String> {
        let m = self.cog_inside_m.filter(|_| !self.tips())?;
        Some(if self.cog_tolerance_m > 0.0 {
            format!(
                "its centre of gravity, anywhere within {:.2} m of where the lift gives it (load cog_tolerance_m), lies at least {m:.2} m inside the edge of what holds it",
                self.cog_tolerance_m
            )
        } else {
            format!("its centre of gravity lies {m:.2} m inside the edge of what holds it")
        })
    }

    /// [`SetSupport::cog_inside_m`] said, where it was measured.
    pub fn cog_said(&self) -> Option<String> {
        let m = self.cog_inside_m?;
        let shown = "(as the scans and the plant model show what is under it, in cells of 0.2 m)";
        let (lies, within) = if self.cog_tolerance_m > 0.0 {
            ("MAY LIE", format!(" WITHIN ITS {:.2} m TOLERANCE (load cog_tolerance_m)", self.cog_tolerance_m))
        } else {
            ("LIES", String::new())
        };
        Some(if let Some(inside) = self.cog_inside_said() {
            format!("{inside} {shown}")
        } else if m >= 0.0 {
            format!(
                "ITS CENTRE OF GRAVITY{within} {lies} ONLY {m:.2} m INSIDE THE EDGE OF WHAT HOLDS IT {shown}: it may tip when the slings slacken; CHECK the set position and cog_m"
            )
        } else if m.is_finite() {
            format!(
                "ITS CENTRE OF GRAVITY{within} {lies} {:.2} m BEYOND THE EDGE OF WHAT HOLDS IT {shown}: it tips when the slings slacken, unless more holds it than they show; CHECK the set position and cog_m",
                -m
            )
        } else {
            "NOTHING WAS FOUND TO HOLD IT under its footprint: CHECK the set position".to_string()
        })
    }
}

/// A load whose centre of gravity lies less than this inside the edge of
/// what it rests on (m) is said to tip: what holds it is known to a cell of
/// the contact search, its centre of gravity to what the lift gives.
pub const COG_INSIDE_SUPPORT_M: f64 = 0.1;

/// The contact search's cell under a load (m): its footprint in cells this
/// wide, at most [`SUPPORT_CELLS_MAX`] a side.
const SUPPORT_CELL_M: f64 = 0.2;
const SUPPORT_CELLS_MAX: usize = 60;

/// How far below the load's underside [`set_support`] looks (m).
pub const SUPPORT_SEARCH_M: f64 = 5.0;

/// What lies under the load at `c` (its set configuration): the highest
/// obstacle under its footprint within [`SUPPORT_SEARCH_M`] of its
/// underside, and the gap to it; `None` where nothing is there. A plan whose
/// set-down ends with a gap leaves the last of the lowering unplanned.
///
/// A support whose top lies up to `reach_up_m` above the underside (the
/// validator lets the load rest that far into its support, `[plan]
/// support_m`) is met at a gap of 0: a model's foundation whose top is a
/// rounding above the set level holds the load's underside inside its
/// solid, where no face of it is near, and was found only at its bottom.
pub fn set_support(task: &LiftTask, world: &World, c: &Config, reach_up_m: f64) -> Option<SetSupport> {
    let load = task.crane.load_obb(c, &task.load);
    let underside = load.center.z - load.half.z;
    // The slab under the footprint, from `reach_up_m` above the underside
    // to `h` below it.
    let slab = |h: f64| {
        let mut b = load;
        b.center.z = underside + (reach_up_m - h) / 2.0;
        b.half.z = (reach_up_m + h) / 2.0;
        b
    };
    let meets = |h: f64| touching(world, &slab(h), ALL_GROUND);
    meets(SUPPORT_SEARCH_M)?;
    let (_, hi) = bisect_mm(0.0, SUPPORT_SEARCH_M, |h| meets(h).is_none());
    let object = meets(hi)?;
    Some(SetSupport { gap_m: hi, object, cog_inside_m: None, cog_tolerance_m: 0.0 })
}

/// How far inside the edge of what the load at `c` rests on its centre of
/// gravity lies, in plan (m; negative beyond it), the load resting `gap_m`
/// lower than at `c` (the gap [`set_support`] found). What it rests on: the
/// cells of its footprint (`SUPPORT_CELL_M`, 0.2 m) under which an obstacle's top
/// lies within `band_m` below that level (or up to `reach_up_m` above it).
/// The answer is a lower bound: the hull of the touching cells' centres,
/// less a cell's half diagonal (each touching cell holds a point of the
/// support within that of its centre). A load set with its centre of
/// gravity beyond the edge of its foundation tips off it when the slings
/// slacken; nothing else checked that. Where the lift gives the centre of
/// gravity a tolerance (`load.cog_tolerance_m`), the least over it.
pub fn cog_over_support_m(task: &LiftTask, world: &World, c: &Config, gap_m: f64, band_m: f64, reach_up_m: f64) -> f64 {
    let load = task.crane.load_obb(c, &task.load);
    let rest = load.center.z - load.half.z - gap_m;
    let cells = |half: f64| ((2.0 * half / SUPPORT_CELL_M).ceil() as usize).clamp(1, SUPPORT_CELLS_MAX);
    let (nu, nv) = (cells(load.half.x), cells(load.half.y));
    let (du, dv) = (2.0 * load.half.x / nu as f64, 2.0 * load.half.y / nv as f64);
    let centres: Vec<liftplan_core::frame::Point3> = (0..nu)
        .flat_map(|i| (0..nv).map(move |j| (i, j)))
        .map(|(i, j)| {
            let (u, v) = (-load.half.x + (i as f64 + 0.5) * du, -load.half.y + (j as f64 + 0.5) * dv);
            load.center + load.axis(0) * u + load.axis(1) * v
        })
        .collect();
    let touching: Vec<[f64; 2]> = centres
        .par_iter()
        .filter(|p| {
            let column = Obb::new(
                liftplan_core::frame::Point3::new(p.x, p.y, rest + (reach_up_m - band_m) / 2.0),
                load.axes,
                liftplan_core::frame::Vec3::new(du / 2.0, dv / 2.0, (reach_up_m + band_m) / 2.0),
            );
            touching(world, &column, ALL_GROUND).is_some()
        })
        .map(|p| [p.x, p.y])
        .collect();
    let slack = 0.5 * du.hypot(dv);
    let hull = liftplan_core::obb::convex_hull_2d(&touching);
    // A hull of one or two points (a post, a rail) holds nothing inside it.
    let inside = |cog: [f64; 2]| match hull.len() {
        0 => f64::NEG_INFINITY,
        1 | 2 => -to_edge_m(&hull, cog),
        _ if in_polygon(&hull, cog) => to_edge_m(&hull, cog),
        _ => -to_edge_m(&hull, cog),
    };
    // Within the centre of gravity's tolerance, the least: how far inside a
    // convex hull a point lies (negative beyond it) is concave in the point,
    // so over the tolerance's square it is least at a corner.
    let tol = task.cog_tolerance_m;
    let corners: &[[f64; 2]] =
        if tol > 0.0 { &[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]] } else { &[[0.0, 0.0]] };
    corners
        .iter()
        .map(|[sx, sy]| {
            let (x, y) = (task.load.cog_m[0] + sx * tol, task.load.cog_m[1] + sy * tol);
            let cog = load.center + load.axis(0) * x + load.axis(1) * y;
            inside([cog.x, cog.y])
        })
        .fold(f64::INFINITY, f64::min)
        - slack
}

/// The scanned ground under a mobile crane's carrier and outriggers, or
/// within [`TOWER_GROUND_AROUND_M`] of a tower crane's mast.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct SetUpGround {
    pub points: usize,
    /// Median, lowest and highest height of those points (m).
    pub median_m: f64,
    pub lowest_m: f64,
    pub highest_m: f64,
}

/// The problem of [`set_up_ground`], for the planner to refuse such a lift
/// before anything else.
pub(crate) fn crane_set_up_level_problem(task: &LiftTask, world: &World) -> Option<String> {
    set_up_ground(task, world).1
}

/// The heights of the scanned ground under a mobile crane's carrier and
/// outriggers, or within [`TOWER_GROUND_AROUND_M`] of a tower crane's mast,
/// lowest first.
pub(crate) fn set_up_ground_heights(task: &LiftTask, world: &World) -> Vec<f64> {
    // They stand still whatever the configuration. A tower crane's mast
    // stands on a foundation (a block in the ground, a raised plinth, a
    // building's frame): the ground beside it, not under it, is what the
    // scans show, and its level is said, not checked.
    let footprints: Vec<Vec<[f64; 2]>> = if task.crane.model.is_tower() {
        task.crane
            .part(PartKind::Mast, &task.pick, &task.load)
            .map(|b| b.expanded(TOWER_GROUND_AROUND_M).footprint())
            .into_iter()
            .collect()
    } else {
        [PartKind::Carrier, PartKind::Outriggers]
            .into_iter()
            .filter_map(|kind| task.crane.part(kind, &task.pick, &task.load))
            .map(|b| b.footprint())
            .collect()
    };
    let mut z = world.points.ground_heights_in(&footprints);
    z.sort_by(f64::total_cmp);
    z
}

/// The scanned ground under a mobile crane's carrier and outriggers, if any
/// is scanned there, and the problem if it does not lie at the level the
/// lift sets the crane up at.
fn set_up_ground(task: &LiftTask, world: &World) -> (Option<SetUpGround>, Option<String>) {
    let tower = task.crane.model.is_tower();
    let z = set_up_ground_heights(task, world);
    if z.is_empty() {
        return (None, None);
    }
    let g = SetUpGround { points: z.len(), median_m: z[z.len() / 2], lowest_m: z[0], highest_m: z[z.len() - 1] };
    let level = task.crane.placement.z_m;
    let problem = (!tower && !((g.median_m - level).abs() <= SET_UP_LEVEL_TOLERANCE_M)).then(|| {
        format!(
            "crane set-up: the lift sets the crane up at z = {level:.2} m (ground_z_m), but the scanned ground under its carrier and outriggers is at {:.2} m (median of {} ground points, {:.2} to {:.2} m): set ground_z_m to the height of the ground it stands on",
            g.median_m, g.points, g.lowest_m, g.highest_m
        )
    });
    (Some(g), problem)
}

/// What stands in the ground under an outrigger pad: the plant model's
/// object or the scans' points (ground left out) in the pad's zone
/// ([`under_pads`]).
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct UnderPad {
    pub pad: liftplan_core::outriggers::Pad,
    /// The plant model's group, or "scanned structure".
    pub object: String,
    /// How far below the set-up level its highest part in the zone lies (m).
    pub depth_m: f64,
    /// The zone: how far it reaches from the pad's centre each way in plan,
    /// and how deep below the set-up level (m).
    pub zone_half_m: f64,
    pub zone_depth_m: f64,
}

impl UnderPad {
    pub fn said(&self) -> String {
        // Found at the top of the zone below the scanned ground's tolerance,
        // its top may lie higher: the scans' search starts there.
        let top = if self.depth_m <= BURIED_BELOW_M {
            "reaching up to the set-up level".to_string()
        } else if (self.depth_m - SET_UP_LEVEL_TOLERANCE_M).abs() <= 2e-3 {
            format!("reaching up to {SET_UP_LEVEL_TOLERANCE_M:.2} m below the set-up level or higher")
        } else {
            format!("{:.2} m below the set-up level", self.depth_m)
        };
        format!(
            "{} {top} under the {} pad (within {:.1} m of its centre and {:.1} m deep)",
            self.object,
            self.pad.name(),
            self.zone_half_m,
            self.zone_depth_m
        )
    }
}

/// Where a lift gives no mats, the pad's own float, as a square (m).
pub const PAD_FLOAT_M: f64 = 1.0;

/// What stands in the ground under each outrigger pad of a mobile crane: a
/// buried pipe, a duct, a culvert, a foundation's edge or a pit under a
/// loaded pad can give way or be crushed. The zone is where a pad's load
/// spreads in the ground, as the common rule has it: down to twice the
/// mat's larger side (at least 2 m), widening by one in two, as a box of
/// the width it reaches at its foot. In it, every plant model group whose
/// top lies more than [`BURIED_BELOW_M`] below the set-up level (nearer is
/// the surface it stands on) or that reaches from the surface down below
/// [`SET_UP_LEVEL_TOLERANCE_M`], and the nearest scanned structure or other
/// lift's load below that tolerance (the scanned ground lies within it),
/// each with the depth of its top, shallowest first per pad. A tower crane
/// stands on its foundation: nothing.
pub fn under_pads(task: &LiftTask, world: &World) -> Vec<UnderPad> {
    use liftplan_core::outriggers::{Pad, pad_at};
    if task.crane.model.is_tower() {
        return Vec::new();
    }
    let mat = task.ground.map_or([PAD_FLOAT_M; 2], |g| g.mat_m);
    let zone_depth_m = (2.0 * mat[0].max(mat[1])).max(2.0);
    let zone_half_m = mat[0].max(mat[1]) / 2.0 + zone_depth_m / 2.0;
    let level = task.crane.placement.z_m;
    let top = level - SET_UP_LEVEL_TOLERANCE_M;
    let bottom = level - zone_depth_m;
    // The zone from `from_z` up to its top.
    let zone = |at: [f64; 2], from_z: f64| {
        Obb::new(
            liftplan_core::frame::Point3::new(at[0], at[1], (top + from_z) / 2.0),
            liftplan_core::frame::Mat3::identity(),
            liftplan_core::frame::Vec3::new(zone_half_m, zone_half_m, (top - from_z) / 2.0),
        )
    };
    // What the model does not name: scanned structure (the ground left
    // out) and the other lifts' loads.
    let meets = |at: [f64; 2], from_z: f64| {
        let b = zone(at, from_z);
        if scanned_structure_in(world, &b) {
            return Some("scanned structure".to_string());
        }
        world.others.iter().find(|(o, _)| o.intersects(&b)).map(|(_, name)| name.clone())
    };
    let mut under = Vec::new();
    for pad in Pad::ALL {
        let Some(at) = pad_at(&task.crane, pad) else { continue };
        let said = |object: String, depth_m: f64| UnderPad { pad, object, depth_m, zone_half_m, zone_depth_m };
        // The plant model's groups, each with its own top over the zone:
        // those buried (their top more than BURIED_BELOW_M down), and those
        // from the surface down into the zone below the scanned ground's
        // tolerance (a foundation's edge).
        let column = [at[0] - zone_half_m, at[1] - zone_half_m, at[0] + zone_half_m, at[1] + zone_half_m];
        let mut here: Vec<UnderPad> = model_in_column(world, column, bottom)
            .into_iter()
            .filter(|(_, high, low)| *high > bottom && (*high <= level - BURIED_BELOW_M || *low < top))
            .map(|(group, high, _)| said(group, (level - high).max(0.0)))
            .collect();
        // The scans' structure and the other loads, nearest first: the top
        // of what is there, the highest foot of the zone that still meets it.
        if meets(at, bottom).is_some() {
            let (lo, _) = bisect_mm(bottom, top - 1e-3, |z| meets(at, z).is_some());
            if let Some(object) = meets(at, lo) {
                here.push(said(object, level - lo));
            }
        }
        here.sort_by(|a, b| a.depth_m.total_cmp(&b.depth_m).then(a.object.cmp(&b.object)));
        under.extend(here);
    }
    under
}

/// How far below the set-up level the top of a plant model's object must
/// lie to be buried (m): one whose top is nearer is the surface the crane
/// stands on (a slab, paving), as the load's support is within `[plan]
/// support_m` of it.
pub const BURIED_BELOW_M: f64 = 0.05;

/// The plant model's groups inside the vertical prism over the plan
/// rectangle `column` ([x0, y0, x1, y1]) above `from_z`, each with its
/// highest and lowest point there (each triangle clipped to the prism), in
/// the groups' order.
fn model_in_column(world: &World, column: [f64; 4], from_z: f64) -> Vec<(String, f64, f64)> {
    let Some(mesh) = world.mesh.as_ref() else { return Vec::new() };
    let v = mesh.vertices();
    let mut spans: std::collections::BTreeMap<&str, (f64, f64)> = std::collections::BTreeMap::new();
    for (t, idx) in mesh.indices().iter().enumerate() {
        let tri = idx.map(|k| [v[k as usize].x, v[k as usize].y, v[k as usize].z]);
        if tri.iter().all(|p| p[2] <= from_z)
            || tri.iter().all(|p| p[0] < column[0])
            || tri.iter().all(|p| p[0] > column[2])
            || tri.iter().all(|p| p[1] < column[1])
            || tri.iter().all(|p| p[1] > column[3])
        {
            continue;
        }
        let Some((low, high)) = span_in_rectangle(&tri, column) else { continue };
        let group = world.tri_group.get(t).map(String::as_str).unwrap_or_default();
        let span = spans.entry(group).or_insert((f64::NEG_INFINITY, f64::INFINITY));
        *span = (span.0.max(high), span.1.min(low));
    }
    spans.into_iter().map(|(g, (high, low))| (g.to_string(), high, low)).collect()
}

/// The lowest and highest point of a triangle inside the vertical prism
/// over the plan rectangle [x0, y0, x1, y1], if any part of it lies over
/// it: the triangle clipped to each side in turn (a plane's height is
/// linear, so they are corners of what is left).
fn span_in_rectangle(tri: &[[f64; 3]; 3], r: [f64; 4]) -> Option<(f64, f64)> {
    let mut poly: Vec<[f64; 3]> = tri.to_vec();
    // Each side as (axis, bound, keep the side above it).
    for (axis, bound, above) in [(0, r[0], true), (0, r[2], false), (1, r[1], true), (1, r[3], false)] {
        let inside = |p: &[f64; 3]| if above { p[axis] >= bound } else { p[axis] <= bound };
        let mut out = Vec::with_capacity(poly.len() + 2);
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            if inside(&a) {
                out.push(a);
            }
            if inside(&a) != inside(&b) {
                let f = (bound - a[axis]) / (b[axis] - a[axis]);
                out.push([a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])]);
            }
        }
        poly = out;
        if poly.is_empty() {
            return None;
        }
    }
    let z = poly.iter().map(|p| p[2]);
    Some((z.clone().fold(f64::INFINITY, f64::min), z.fold(f64::NEG_INFINITY, f64::max)))
}

/// The obstacles, as the validator sees them.
pub struct World {
    pub mesh: Option<ParryMesh>,
    /// Group name per parry triangle.
    pub tri_group: Vec<String>,
    pub points: PointIndex,
    /// Solid boxes known apart from the model and the scans, with their
    /// names: the other lifts' loads where they stand during this one
    /// ([`crate::other_loads`]).
    pub others: Vec<(Obb, String)>,
}

impl World {
    pub fn new(mesh: &TriMesh, points: &[[f64; 3]], ground: &[bool]) -> Result<World, String> {
        let parry = if mesh.triangles.is_empty() {
            None
        } else {
            let v = mesh.vertices.iter().map(|p| Vector::new(p[0], p[1], p[2])).collect();
            Some(
                ParryMesh::new(v, mesh.triangles.clone())
                    .map_err(|e| format!("plant mesh for the validator: {e:?}"))?,
            )
        };
        let tri_group = (0..mesh.triangles.len()).map(|t| mesh.group_of_triangle(t).to_string()).collect();
        Ok(World { mesh: parry, tri_group, points: PointIndex::new(points, ground)?, others: Vec::new() })
    }
}

/// A box as parry3d's pose and cuboid.
pub fn parry_box(b: &Obb) -> (Pose, Cuboid) {
    let col = |k: usize| Vector::new(b.axes[(0, k)], b.axes[(1, k)], b.axes[(2, k)]);
    let rot = parry3d_f64::glamx::DQuat::from_mat3(&parry3d_f64::glamx::DMat3::from_cols(col(0), col(1), col(2)));
    (
        Pose::from_parts(Vector::new(b.center.x, b.center.y, b.center.z), rot),
        Cuboid::new(Vector::new(b.half.x, b.half.y, b.half.z)),
    )
}

/// Distance from a box to the nearest obstacle, and which, searched up to `cutoff_m` for points.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Nearest {
    pub distance_m: f64,
    pub object: String,
    /// The obstacle point the distance was measured to (for a plant triangle:
    /// the triangle's point nearest the part's centre), for the pictures'
    /// hot-spot markers.
    pub at: Option<[f64; 3]>,
}

/// What `b` touches (the nearest obstacle at no distance), scanned ground
/// at or below `ground_below_z` left out ([`nearest`]).
fn touching(world: &World, b: &Obb, ground_below_z: f64) -> Option<String> {
    let n = nearest(world, b, ground_below_z, 0.0);
    (n.distance_m <= 1e-9).then_some(n.object)
}

/// Where a property that `holds` at `holds_at` and not at `fails_at` (m)
/// stops holding, to 1 mm: the last value it was seen to hold at and the
/// first it was seen to fail at (the gap and depth searches).
fn bisect_mm(mut holds_at: f64, mut fails_at: f64, holds: impl Fn(f64) -> bool) -> (f64, f64) {
    while (fails_at - holds_at).abs() > 1e-3 {
        let mid = 0.5 * (holds_at + fails_at);
        if holds(mid) { holds_at = mid } else { fails_at = mid }
    }
    (holds_at, fails_at)
}

/// [`nearest`] leaves out no scanned ground.
const ALL_GROUND: f64 = f64::NEG_INFINITY;

/// The nearest obstacle to `b`: plant triangles and scanned points, less the
/// scanned ground at or below `ground_below_z` ([`ALL_GROUND`]: none).
fn nearest(world: &World, b: &Obb, ground_below_z: f64, cutoff_m: f64) -> Nearest {
    let (pose, cub) = parry_box(b);
    let mut best = Nearest { distance_m: f64::INFINITY, object: String::new(), at: None };
    if let Some(m) = &world.mesh
        && let Some((distance_m, tri)) = mesh_nearest(m, b)
    {
        let c = b.center;
        let on_tri = m.triangle(tri).project_local_point(Vector::new(c.x, c.y, c.z), true).point;
        best = Nearest {
            distance_m,
            object: world.tri_group.get(tri as usize).cloned().unwrap_or_default(),
            at: Some([on_tri.x, on_tri.y, on_tri.z]),
        };
    }
    // The boxes' bounding boxes' gap is no more than their distance: a box
    // whose gap is no less than the nearest yet cannot be nearer, and is
    // not measured (a power line gives thousands of boxes, most far off).
    // The nanometre keeps a gap rounded up from skipping a box rounded down.
    let ba = b.aabb();
    for (other, name) in &world.others {
        let oa = other.aabb();
        let gap = (0..3).map(|d| (oa.min[d] - ba.max[d]).max(ba.min[d] - oa.max[d]).max(0.0)).fold(0.0, f64::hypot);
        if gap - 1e-9 >= best.distance_m {
            continue;
        }
        let (p2, c2) = parry_box(other);
        // Two boxes: parry's answers cannot fail; a NaN box would, and is
        // taken as touching.
        let d = query::distance(&pose, &cub, &p2, &c2).map(|d| d.distance).unwrap_or(0.0);
        if d < best.distance_m {
            let at = match query::closest_points(&pose, &cub, &p2, &c2, f64::MAX) {
                Ok(query::ClosestPoints::WithinMargin(_, q)) => [q.x, q.y, q.z],
                _ => [other.center.x, other.center.y, other.center.z],
            };
            best = Nearest { distance_m: d, object: name.clone(), at: Some(at) };
        }
    }
    nearer_scan_point(world, b, (&pose, &cub), cutoff_m, ground_below_z, &mut best);
    best
}

/// Improves `best` with the nearest scan point to `b` (as `pose`, `cub`)
/// within `cutoff_m` and nearer than `best` (ground points at or below
/// `ground_below_z` left out), reading the voxels around the box the
/// cheaper way.
fn nearer_scan_point(
    world: &World,
    b: &Obb,
    (pose, cub): (&Pose, &Cuboid),
    cutoff_m: f64,
    ground_below_z: f64,
    best: &mut Nearest,
) {
    let aabb = b.aabb().expanded(cutoff_m.min(best.distance_m));
    let (lo, hi) = (voxel(&aabb.min), voxel(&aabb.max));
    let walk_occupied = world.points.walk_occupied(lo, hi);
    nearest_point(&world.points, (pose, cub), (lo, hi), ground_below_z, walk_occupied, best);
}

/// The scanned point (ground or not) nearest `b` within `cutoff_m`, and its
/// distance; `None` where none is that near.
pub fn nearest_scanned_point(world: &World, b: &Obb, cutoff_m: f64) -> Option<([f64; 3], f64)> {
    nearest_scan(world, b, cutoff_m, ALL_GROUND)
}

/// What the site shows where a power line's conductor is held
/// ([`support_seen`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SupportSeen {
    /// Scanned structure (not ground) or the plant model within
    /// [`SUPPORT_SEEN_M`] of it in plan, from 2.5 m below it to 5 m above:
    /// a pole's top, a crossarm, the insulator string a tower's conductor
    /// hangs from.
    Seen,
    /// Nothing there, where the scans show the site around it.
    NotSeen,
    /// The scans show nothing within [`SUPPORT_AROUND_M`] of it in plan.
    NotScanned,
}

/// How far from a support, in plan, what the scans or the model show there
/// counts as holding it (m): a pole's top, a crossarm's end.
pub const SUPPORT_SEEN_M: f64 = 1.0;
/// How far round a support, in plan, scanned points say the site there was
/// scanned (m).
pub const SUPPORT_AROUND_M: f64 = 5.0;

/// Whether the scans or the plant model show something that could hold a
/// power line's conductor at `at` (where the line's `points_m` says it is
/// held), nothing where the site around it is scanned, or no scan there:
/// a support given a few metres off, or the wrong line's, is a line
/// planned round where it is not.
pub fn support_seen(world: &World, at: [f64; 3]) -> SupportSeen {
    let b = Obb::axis_aligned(
        liftplan_core::frame::Point3::new(at[0], at[1], at[2] + 1.25),
        liftplan_core::frame::Vec3::new(SUPPORT_SEEN_M, SUPPORT_SEEN_M, 3.75),
    );
    let in_model = world.mesh.as_ref().and_then(|m| mesh_nearest(m, &b)).is_some_and(|(d, _)| d <= 0.0);
    if in_model || scanned_structure_in(world, &b) {
        return SupportSeen::Seen;
    }
    let r = SUPPORT_AROUND_M;
    match world.points.highest_in([at[0] - r, at[1] - r], [at[0] + r, at[1] + r], at[2] + 5.0) {
        Some(_) => SupportSeen::NotSeen,
        None => SupportSeen::NotScanned,
    }
}

/// Whether a scan point other than ground lies in `b`: whether the scans
/// saw anything standing there (ground points lie in the foot of any box
/// standing on the ground).
pub fn scanned_structure_in(world: &World, b: &Obb) -> bool {
    nearest_scan(world, b, 1e-6, f64::INFINITY).is_some()
}

/// Whether a scan point other than ground lies in `inside` (grown by
/// `SCAN_ON_FACE_M`, as points on its faces scatter both ways) within
/// `within_m` of `near`: whether the scans saw something of `inside` near
/// where `near` is.
pub fn scanned_structure_near(world: &World, near: &Obb, within_m: f64, inside: &Obb) -> bool {
    let inside = inside.expanded(SCAN_ON_FACE_M);
    let (near_pose, near_cub) = parry_box(near);
    let (in_pose, in_cub) = parry_box(&inside);
    let (a, b) = (near.aabb().expanded(within_m), inside.aabb());
    let (min, max) = ([0, 1, 2].map(|k| a.min[k].max(b.min[k])), [0, 1, 2].map(|k| a.max[k].min(b.max[k])));
    if (0..3).any(|k| min[k] > max[k]) {
        return false;
    }
    let index = &world.points;
    index.voxels_in(voxel(&min), voxel(&max)).any(|k| {
        index.voxel_points(k).iter().any(|(p, ground)| {
            let v = Vector::new(p[0], p[1], p[2]);
            !*ground
                && in_cub.distance_to_point(&in_pose, v, true) <= 0.0
                && near_cub.distance_to_point(&near_pose, v, true) <= within_m
        })
    })
}

/// How far outside a model box's faces a scan point of what the box holds
/// may lie (m): scan noise and a model drawn to the nearest few centimetres.
const SCAN_ON_FACE_M: f64 = 0.1;

/// The scan point nearest `b` within `cutoff_m` and its distance, ground
/// points at or below `ground_below_z` left out.
fn nearest_scan(world: &World, b: &Obb, cutoff_m: f64, ground_below_z: f64) -> Option<([f64; 3], f64)> {
    let (pose, cub) = parry_box(b);
    let mut best = Nearest { distance_m: cutoff_m, object: String::new(), at: None };
    nearer_scan_point(world, b, (&pose, &cub), cutoff_m, ground_below_z, &mut best);
    best.at.map(|p| (p, best.distance_m))
}

/// A plant model group that fills a load's box as a copy of the load would
/// ([`model_group_filling`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ModelCopy {
    pub group: String,
    /// The share of the two boxes' union they have in common.
    pub share: f64,
    /// The copy stands turned a quarter turn from the box.
    pub turned: bool,
}

/// The plant model's group that fills the box `b` as a copy of what it
/// stands for would: in `b`'s own frame, the group's bounding box and `b`
/// share more than half their union, with `b` as it is or turned a quarter
/// turn about the vertical; `None` where none does. A plant model holds
/// the equipment a lift installs where it is installed: at the set
/// position the load meets itself (turned, where the set's yaw is a
/// quarter turn off).
pub fn model_group_filling(world: &World, b: &Obb) -> Option<ModelCopy> {
    let mesh = world.mesh.as_ref()?;
    // The groups near the box (a model's faces lie on it, a rounding in or out).
    let near = b.aabb().expanded(0.1);
    let mut groups: HashMap<&str, liftplan_core::frame::Aabb> = HashMap::new();
    for (t, group) in world.tri_group.iter().enumerate() {
        let tri = mesh.triangle(t as u32);
        let (lo, hi) = (tri.a.min(tri.b).min(tri.c), tri.a.max(tri.b).max(tri.c));
        if (0..3).any(|a| hi[a] < near.min[a] || lo[a] > near.max[a]) {
            continue;
        }
        groups.entry(group.as_str()).or_insert_with(liftplan_core::frame::Aabb::empty);
    }
    // Each of those groups' whole extent in the box's frame.
    for (t, group) in world.tri_group.iter().enumerate() {
        if let Some(e) = groups.get_mut(group.as_str()) {
            let tri = mesh.triangle(t as u32);
            for p in [tri.a, tri.b, tri.c] {
                let l = b.to_local(&liftplan_core::frame::Point3::new(p.x, p.y, p.z));
                e.grow([l.x, l.y, l.z]);
            }
        }
    }
    let volume = |a: &liftplan_core::frame::Aabb| (0..3).map(|i| (a.max[i] - a.min[i]).max(0.0)).product::<f64>();
    let share = |a: &liftplan_core::frame::Aabb, half: [f64; 3]| {
        let target = liftplan_core::frame::Aabb { min: half.map(|h| -h), max: half };
        let overlap = liftplan_core::frame::Aabb {
            min: std::array::from_fn(|i| a.min[i].max(target.min[i])),
            max: std::array::from_fn(|i| a.max[i].min(target.max[i])),
        };
        let shared = volume(&overlap);
        shared / (volume(a) + volume(&target) - shared).max(1e-12)
    };
    let half = [b.half.x, b.half.y, b.half.z];
    groups
        .into_iter()
        .map(|(name, a)| {
            let (as_is, turned) = (share(&a, half), share(&a, [half[1], half[0], half[2]]));
            let copy = ModelCopy { group: name.to_string(), share: as_is.max(turned), turned: turned > as_is };
            (name, copy)
        })
        .filter(|(_, c)| c.share > 0.5)
        // The best, and of equal shares the first by name: one answer.
        .max_by(|a, b| a.1.share.total_cmp(&b.1.share).then_with(|| b.0.cmp(a.0)))
        .map(|(_, c)| c)
}

/// Improves `best` with the nearest point to a box among the points of
/// voxels `lo ..= hi` (ground points at or below `ground_below_z` left out),
/// the first in the index's order where several are as near. Walks either the occupied voxels (`walk_occupied`, cheaper when the
/// range has more voxels than the cloud) or the range's voxels; both visit the
/// range's occupied voxels in ascending order, so both give the same answer.
fn nearest_point(
    index: &PointIndex,
    (pose, cub): (&Pose, &Cuboid),
    (lo, hi): ([i32; 3], [i32; 3]),
    ground_below_z: f64,
    walk_occupied: bool,
    best: &mut Nearest,
) {
    let check = |pts: &[([f64; 3], bool)], best: &mut Nearest| {
        for (p, g) in pts {
            if *g && p[2] <= ground_below_z {
                continue;
            }
            let d = cub.distance_to_point(pose, Vector::new(p[0], p[1], p[2]), true);
            if d < best.distance_m {
                *best = Nearest {
                    distance_m: d,
                    object: if *g { "ground (scan)".into() } else { "scanned structure".into() },
                    at: Some(*p),
                };
            }
        }
    };
    // A voxel whose centre is farther from the box than the best distance so
    // far plus its half diagonal holds no nearer point: skipped unread. The
    // result is the same as reading every voxel.
    let far = |key: &[i32; 3], best: f64| {
        let c = key.map(|k| (k as f64 + 0.5) * VOXEL_M);
        cub.distance_to_point(pose, Vector::new(c[0], c[1], c[2]), true) - VOXEL_HALF_DIAGONAL_M > best
    };
    if walk_occupied {
        for k in index.occupied_in(lo, hi) {
            if !far(&index.keys[k], best.distance_m) {
                check(index.voxel_points(k), best);
            }
        }
    } else {
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    if far(&[x, y, z], best.distance_m) {
                        continue;
                    }
                    if let Some(&k) = index.place.get(&[x, y, z]) {
                        check(index.voxel_points(k as usize), best);
                    }
                }
            }
        }
    }
}

/// Longest side of the pieces a box is cut into for the mesh search (m).
const PIECE_M: f64 = 4.0;

/// Exact distance from a box to the plant mesh, and the nearest triangle.
///
/// The mesh's BVH is searched best-first with a node's bound taken from the
/// query's axis-aligned box; an inclined 60 m boom's is tens of metres wide
/// and prunes almost nothing. So the box is cut into pieces at most
/// `PIECE_M` long (their union is the box, so the smallest piece distance is
/// the box's distance) and each piece is searched with its own tight bound and
/// the best distance so far as the cut-off.
fn mesh_nearest(m: &ParryMesh, b: &Obb) -> Option<(f64, u32)> {
    let mut best: Option<(f64, u32)> = None;
    for piece in pieces(b, PIECE_M) {
        let (pose, cub) = parry_box(&piece);
        let bb = piece.aabb();
        let gap = |lo: f64, hi: f64, a: f64, b: f64| (lo - b).max(a - hi).max(0.0);
        let node_bound = |node: &parry3d_f64::partitioning::BvhNode, _: f64| {
            let (lo, hi) = (node.mins(), node.maxs());
            let dx = gap(lo.x, hi.x, bb.min[0], bb.max[0]);
            let dy = gap(lo.y, hi.y, bb.min[1], bb.max[1]);
            let dz = gap(lo.z, hi.z, bb.min[2], bb.max[2]);
            (dx * dx + dy * dy + dz * dz).sqrt()
        };
        let tri_distance =
            |t: u32, _: f64| query::distance(&pose, &cub, &Pose::identity(), &m.triangle(t)).ok().map(|d| d.distance);
        let cutoff = best.map(|(d, _)| d).unwrap_or(f64::MAX);
        if let Some((t, d)) = m.bvh().find_best(cutoff, node_bound, tri_distance)
            && best.is_none_or(|(bd, _)| d < bd)
        {
            best = Some((d, t));
        }
    }
    best
}

/// `b` cut into equal pieces at most `max_m` long along each of its axes.
fn pieces(b: &Obb, max_m: f64) -> Vec<Obb> {
    let n = [0, 1, 2].map(|k| ((2.0 * b.half[k] / max_m).ceil() as usize).clamp(1, 64));
    let half = liftplan_core::frame::Vec3::new(b.half.x / n[0] as f64, b.half.y / n[1] as f64, b.half.z / n[2] as f64);
    let mut out = Vec::with_capacity(n[0] * n[1] * n[2]);
    for i in 0..n[0] {
        for j in 0..n[1] {
            for k in 0..n[2] {
                let at = |idx: usize, nk: usize, h: f64| (2.0 * idx as f64 + 1.0 - nk as f64) * h;
                let center = b.center
                    + b.axis(0) * at(i, n[0], half.x)
                    + b.axis(1) * at(j, n[1], half.y)
                    + b.axis(2) * at(k, n[2], half.z);
                out.push(Obb::new(center, b.axes, half));
            }
        }
    }
    out
}

const VOXEL_HALF_DIAGONAL_M: f64 = 0.866_025_404 * VOXEL_M;

/// The lift's rules, as the validator applies them.
#[derive(Debug, Clone, Serialize)]
pub struct Rules {
    pub clearance_m: f64,
    /// Landing zones (plan polygons) and the clearance the hanging parts need in them.
    pub landing: Vec<Vec<[f64; 2]>>,
    pub landing_clearance_m: f64,
    /// Largest displacement of any crane point between samples (m).
    pub sample_m: f64,
    /// Obstacles within this distance of the load's underside at pick/set are its supports.
    pub support_m: f64,
}

pub(crate) use liftplan_core::obb::plan_bounds;

/// Whether `p` lies in the polygon by the even-odd rule: independent of the
/// planner's convex test of its landing zones.
pub(crate) fn in_polygon(poly: &[[f64; 2]], p: [f64; 2]) -> bool {
    liftplan_core::obb::in_polygon_2d(poly, p)
}

/// What one sample found.
#[derive(Debug, Clone, Serialize)]
pub struct SampleCheck {
    pub config: Config,
    pub part: PartKind,
    pub nearest: Nearest,
    pub required_m: f64,
    pub radius_m: f64,
    pub capacity_kg: Option<f64>,
    pub chart_cell: Option<String>,
    pub utilisation_pct: Option<f64>,
}

/// The verdict on one move.
#[derive(Debug, Clone, Serialize)]
pub struct MoveCheck {
    pub samples: usize,
    /// The sample with the smallest clearance margin (distance less requirement).
    pub tightest: SampleCheck,
    /// The clearance a step reports: the tightest part's requirement plus the
    /// least margin every part keeps along the whole move, between the
    /// samples too (the tightest sample's margin less at most half the
    /// largest movement between two samples), so a distance no point of the
    /// move comes closer than; the tightest sample's distance where that is
    /// beyond the point search's cut-off, or infinite.
    pub clearance_m: f64,
    /// The sample with the highest utilisation.
    pub max_utilisation: SampleCheck,
    pub problems: Vec<String>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Verdict {
    pub ok: bool,
    pub moves: Vec<MoveCheck>,
    pub problems: Vec<String>,
    /// The scanned ground under a mobile crane's carrier and outriggers, if
    /// any was scanned there ([`SET_UP_LEVEL_TOLERANCE_M`]).
    pub set_up_ground: Option<SetUpGround>,
    /// Samples checked, those added between the evenly spaced ones included.
    pub samples: usize,
    /// Samples added where two neighbours' distances did not rule out a part
    /// coming closer than its requirement between them.
    pub refined_samples: usize,
    pub seconds: f64,
}

/// The farthest any point of any part (crane, rope, hook, load) moves per
/// unit of the move's joint (m per rad for swing, luff and load yaw, m per m
/// for trolley and hoist).
pub(crate) fn lever_for(task: &LiftTask, m: &Move) -> f64 {
    let crane = &task.crane;
    match m.joint {
        liftplan_cspace::Joint::Swing => {
            // Farthest point of any part from the slewing axis.
            let far = |c: &Config| {
                crane.pose(c, &task.load).parts.iter().map(|(_, b)| crane.plan_reach_m(b)).fold(0.0, f64::max)
            };
            far(&m.from).max(far(&m.to))
        }
        liftplan_cspace::Joint::Radial => {
            if crane.model.is_tower() {
                // The trolley and what hangs from it move with the radius.
                1.0
            } else {
                // The boom turns about its foot pin: each of its points moves
                // its distance from the pin's axis per radian, and the hanging
                // parts move as the sheave does.
                let far = |c: &Config| {
                    let Some(boom) = crane.part(PartKind::Boom, c, &task.load) else { return 0.0 };
                    let (along, pin_axis) = (boom.axis(0), boom.axis(1));
                    let pin = boom.center - along * boom.half.x;
                    let from_axis = |p: liftplan_core::frame::Point3| {
                        let v = p - pin;
                        (v - pin_axis * v.dot(&pin_axis)).norm()
                    };
                    boom.corners().into_iter().map(from_axis).fold(from_axis(crane.sheave(c)), f64::max)
                };
                far(&m.from).max(far(&m.to))
            }
        }
        liftplan_cspace::Joint::Hoist => 1.0,
        liftplan_cspace::Joint::Rotate => {
            // The load and its rigging turn about the hook line.
            let far = |c: &Config| {
                let s = crane.sheave(c);
                [PartKind::Load, PartKind::Rigging]
                    .into_iter()
                    .filter_map(|k| crane.part(k, c, &task.load))
                    .flat_map(|b| b.corners())
                    .map(|p| (p.x - s.x).hypot(p.y - s.y))
                    .fold(0.0, f64::max)
            };
            far(&m.from).max(far(&m.to))
        }
    }
}

/// The configurations evenly spaced along `m` so that no point of the crane
/// moves more than `sample_m` between two, from its start to its end. A
/// move too long to sample is refused by the validator; here it is drawn
/// at most 100,000 times. For the reports drawn from a plan (what it
/// passes over, what it passes through); the validator samples on its own.
pub(crate) fn configs_along(task: &LiftTask, m: &Move, sample_m: f64) -> impl Iterator<Item = Config> + use<> {
    let moved_m = m.delta().abs() * lever_for(task, m);
    let n = samples_for(moved_m.min(sample_m * 1e5), sample_m);
    let (a, b, j) = (m.from.to_array(), m.to.to_array(), m.joint.index());
    (0..n).map(move |s| {
        let mut v = a;
        v[j] = a[j] + (b[j] - a[j]) * s as f64 / (n - 1).max(1) as f64;
        Config::from_array(v)
    })
}

/// Samples evenly spaced along a move in which no point moves more than
/// `moved_m`, so that none moves more than `sample_m` between two.
pub(crate) fn samples_for(moved_m: f64, sample_m: f64) -> usize {
    ((moved_m / sample_m).ceil() as usize).max(1) + 1
}

/// The first of the lift's `not_over` areas the load comes over (or within
/// its fall zone of, [`LiftTask::fall_zone_m`]) during the move, or a part
/// of the crane that turns with the swing comes over where the crane may
/// not be over it either (`crane_too`), and which part: their
/// footprints at samples at most `sample_m` of travel apart (`moved_m` over
/// the move, the farthest any point of any part goes), each grown by half
/// the travel between two, so that every moment of the move is covered.
/// The planner keeps them farther off
/// ([`liftplan_core::lift::NOT_OVER_MARGIN_M`]).
fn over_not_over<'a>(
    task: &'a LiftTask,
    m: &Move,
    moved_m: f64,
    sample_m: f64,
    landing_move: bool,
) -> Option<(PartKind, &'a NotOver)> {
    if task.not_over.is_empty() {
        return None;
    }
    let k = samples_for(moved_m, sample_m) - 1;
    let grow_m = moved_m / k as f64 / 2.0;
    // A lift-off or set-down is held at its support; elsewhere what hangs
    // is swung by a gust where the lift is planned for the wind.
    let (a, b) = (m.from.to_array(), m.to.to_array());
    let j = m.joint.index();
    (0..=k).find_map(|i| {
        let mut v = a;
        v[j] = a[j] + (b[j] - a[j]) * i as f64 / k as f64;
        task.not_over_near(&Config::from_array(v), grow_m, !landing_move)
    })
}

/// Checks one configuration: every part's distance against its requirement and the chart.
fn check_config(
    task: &LiftTask,
    chart: Option<&ChartConfig>,
    world: &World,
    rules: &Rules,
    c: &Config,
    landing_move: bool,
) -> Sample {
    let crane = &task.crane;
    let mut problems = Vec::new();
    let lim = crane.limits();
    if !(c.radial >= lim.radial.0 - 1e-9
        && c.radial <= lim.radial.1 + 1e-9
        && c.hoist_m >= lim.hoist_m.0 - 1e-9
        && c.hoist_m <= lim.hoist_m.1 + 1e-9)
    {
        problems.push("outside the crane's joint limits".to_string());
    }
    if let Some((a, b)) = task.swing_range_rad {
        // Modulo a turn: the same place whatever the turn count, and a swing
        // sampled this densely cannot leave the range and come back unseen.
        let past_a = (c.swing_rad - a).rem_euclid(std::f64::consts::TAU);
        if !(past_a <= b - a + 1e-9 || past_a >= std::f64::consts::TAU - 1e-9) {
            problems.push(format!(
                "outside the permitted swing range ({:.1}° to {:.1}° from the crane's heading, heading_deg)",
                a.to_degrees(),
                b.to_degrees()
            ));
        }
    }
    let radius = crane.radius_m(c.radial);
    let (cap, cell, util) = match chart.map(|ch| task.check_capacity(ch, c.radial)) {
        Some(Ok(k)) => (Some(k.capacity.capacity_kg), Some(k.capacity.cell.clone()), Some(k.utilisation_pct)),
        Some(Err(e)) => {
            problems.push(format!("load chart: {e}"));
            (None, None, None)
        }
        None => (None, None, None),
    };
    if util.is_some_and(|u| u > 100.0 + 1e-9) {
        problems.push(format!("over capacity: {:.1} % at radius {radius:.2} m", util.unwrap_or(0.0)));
    }
    let footprint = crane.load_obb(c, &task.load).footprint();
    let in_landing = rules.landing.iter().any(|poly| footprint.iter().all(|p| in_polygon(poly, *p)));
    // A lift-off or set-down asks the same of the hanging parts in a zone or not.
    let zone_margin_m =
        if landing_move { f64::INFINITY } else { zone_margin_m(&rules.landing, &footprint, in_landing) };
    // Every part's box once, for the site and for the crane's own structure;
    // where the lift is planned for the wind, what hangs swung as far as a
    // gust can swing it, but in a lift-off or set-down, held at its support.
    let pose = task.pose_hanging_swept(c, !landing_move);
    let mut out = Vec::new();
    for &(kind, mut b) in &pose.parts {
        let dep = kind.dependence();
        if dep == Dependence::Fixed {
            continue; // checked once per plan
        }
        let hanging = dep == Dependence::Full;
        let mut required = if hanging && in_landing { rules.landing_clearance_m } else { rules.clearance_m };
        if landing_move && hanging {
            // Lift-off and set-down: touch nothing but the load's support.
            required = LANDING_GAP_M;
            if kind == PartKind::Load {
                // The load may rest on its support.
                b = b.with_underside_raised(rules.support_m);
            }
        }
        // The superstructure and what turns with it swing just above the
        // ground the crane is set up on: that ground does not count for them
        // (a bank higher up does); all of it counts for the boom, the trolley
        // and what hangs. The planner applies the same rule.
        let ground_below_z = if dep == Dependence::Swing { task.crane.standing_ground_top_z() } else { ALL_GROUND };
        let nearest = nearest(world, &b, ground_below_z, search_cutoff_m(rules.clearance_m));
        // Written so that a distance that is not a number fails too.
        if !(nearest.distance_m >= required - DISTANCE_TOLERANCE_M) {
            problems.push(if landing_move && hanging {
                format!(
                    "{} touches {} during the lift-off or set-down ({:.3} m apart; only the load's support may)",
                    kind.name(),
                    nearest.object,
                    nearest.distance_m
                )
            } else {
                format!(
                    "{} is {:.3} m from {} (needs {:.2} m)",
                    kind.name(),
                    nearest.distance_m,
                    nearest.object,
                    required
                )
            });
        }
        out.push(SampleCheck {
            config: *c,
            part: kind,
            nearest,
            required_m: required,
            radius_m: radius,
            capacity_kg: cap,
            chart_cell: cell.clone(),
            utilisation_pct: util,
        });
    }
    let own = own_distances(&pose);
    for (kind, d, what) in &own {
        if !(*d >= OWN_CLEARANCE_M - DISTANCE_TOLERANCE_M) {
            problems
                .push(format!("{} is {d:.3} m from the crane's {what} (needs {OWN_CLEARANCE_M:.2} m)", kind.name()));
        }
    }
    Sample { t: 0.0, checks: out, own, problems, zone_margin_m }
}

/// What the load and its rigging must keep from the crane's own structure
/// (m): they must not touch it. The site's clearance is for swinging past
/// obstacles; the planner keeps the load off the boom by a shortest rope per
/// luff row, which this checks independently.
const OWN_CLEARANCE_M: f64 = 0.01;

/// The distance from the load and from its rigging to the nearest part of the
/// crane (at `pose`) that does not hang (boom, superstructure, counterweight, carrier,
/// outriggers; mast, jib, counter-jib, cab, trolley), and which part that
/// is. The hook block and the rope hang from the sheave at the boom's head,
/// inside the boom's box: they are not checked against it.
///
/// Parts whose bounding spheres are more than [`OWN_EXACT_WITHIN_M`] apart get
/// the spheres' gap instead of the exact distance: never more than it, and
/// plenty for the check and the bound between samples, at a fraction of the
/// cost (most of the crane is far from the load most of the time).
fn own_distances(pose: &CranePose) -> Vec<(PartKind, f64, &'static str)> {
    let radius = |b: &Obb| b.half.norm();
    let structure: Vec<(PartKind, &Obb)> =
        pose.parts.iter().filter(|(k, _)| k.dependence() != Dependence::Full).map(|(k, b)| (*k, b)).collect();
    pose.parts
        .iter()
        .filter(|(k, _)| matches!(k, PartKind::Load | PartKind::Rigging))
        .map(|(k, b)| {
            let (p1, c1) = parry_box(b);
            let (d, what) = structure
                .iter()
                .map(|(sk, sb)| {
                    let apart = (sb.center - b.center).norm() - radius(sb) - radius(b);
                    let d = if apart > OWN_EXACT_WITHIN_M {
                        apart
                    } else {
                        let (p2, c2) = parry_box(sb);
                        // Two boxes: parry's distance cannot fail; a NaN box would.
                        query::distance(&p1, &c1, &p2, &c2).map(|d| d.distance).unwrap_or(f64::NAN)
                    };
                    (d, sk.name())
                })
                .fold((f64::INFINITY, ""), |best, x| if !(x.0 >= best.0) { x } else { best });
            (*k, d, what)
        })
        .collect()
}

/// Within this gap between their bounding spheres (m), [`own_distances`]
/// measures a part's exact distance.
const OWN_EXACT_WITHIN_M: f64 = 1.0;

/// Distance from `p` to the nearest edge of `poly` (m).
pub(crate) fn to_edge_m(poly: &[[f64; 2]], p: [f64; 2]) -> f64 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
            let len2 = ex * ex + ey * ey;
            let t = if len2 > 0.0 { (((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / len2).clamp(0.0, 1.0) } else { 0.0 };
            (p[0] - a[0] - t * ex).hypot(p[1] - a[1] - t * ey)
        })
        .fold(f64::INFINITY, f64::min)
}

/// How far the load's footprint (its corners) can move before the landing
/// zones can change what the hanging parts need (m). Inside a zone: its
/// corners' least distance to that zone's edges, in the zone where that is
/// largest. Outside every zone: for each zone, the farthest of the corners
/// outside it (the footprint is in the zone only once all are), the least of
/// these over the zones. Without zones, infinite.
fn zone_margin_m(zones: &[Vec<[f64; 2]>], footprint: &[[f64; 2]], inside: bool) -> f64 {
    if inside {
        zones
            .iter()
            .filter(|poly| footprint.iter().all(|p| in_polygon(poly, *p)))
            .map(|poly| footprint.iter().map(|p| to_edge_m(poly, *p)).fold(f64::INFINITY, f64::min))
            .fold(0.0, f64::max)
    } else {
        zones
            .iter()
            .map(|poly| {
                footprint.iter().filter(|p| !in_polygon(poly, **p)).map(|p| to_edge_m(poly, *p)).fold(0.0, f64::max)
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// Distances below the requirement by no more than this pass (m): the
/// samples' own tolerance.
const DISTANCE_TOLERANCE_M: f64 = 1e-3;

/// How far a box round something must reach beyond it (m) for every part to
/// stay `distance_m` off that thing along the whole motion: the least any
/// part keeps off a box is what hangs in the lift-off and the set-down
/// ([`LANDING_GAP_M`], the load's underside raised by `support_m` there),
/// less the validator's tolerance along the motion. Elsewhere the parts keep
/// the clearance beyond that. For power lines ([`crate::power_line_boxes`]).
pub fn box_reach_for_m(distance_m: f64, support_m: f64) -> f64 {
    distance_m - LANDING_GAP_M + support_m + DISTANCE_TOLERANCE_M + REFINED_GAP_M / 2.0
}

/// What the hanging parts keep from everything during the lift-off and the
/// set-down, the load's support aside (whatever lies within `support_m` under
/// the load): not a clearance, only "not touching". A distance cannot say by
/// how much two solids overlap, so a requirement of zero would pass a load
/// lowered through a beam.
const LANDING_GAP_M: f64 = 0.01;

/// Two samples whose points are at most this far apart are not split
/// further (m). Everywhere between them every part is then at least its
/// requirement less `DISTANCE_TOLERANCE_M + REFINED_GAP_M / 2` (2 mm) from
/// every obstacle.
const REFINED_GAP_M: f64 = 2e-3;

/// The most any point may move in one move (m): a crane's longest moves
/// are a few hundred metres. It bounds the samples, evenly spaced and added
/// (one per millimetre of movement at most).
const MAX_MOVED_M: f64 = 10_000.0;

/// How far the point search looks beyond a part (m): a part farther than
/// this from every scanned point is reported at its mesh distance or at
/// infinity, so this is the most its distance is known to be.
/// How far the validator looks for the nearest obstacle (m), for a lift of
/// `clearance_m`: beyond it a distance is reported as infinite.
pub fn search_cutoff_m(clearance_m: f64) -> f64 {
    (clearance_m * 3.0).max(3.0)
}

/// One configuration along a move, at fraction `t` of it, and what it found.
struct Sample {
    t: f64,
    checks: Vec<SampleCheck>,
    /// [`own_distances`] here.
    own: Vec<(PartKind, f64, &'static str)>,
    problems: Vec<String>,
    /// [`zone_margin_m`] here: while the load moves less than this, the
    /// hanging parts' requirement stays what it is here.
    zone_margin_m: f64,
}

/// Whether every part keeps its requirement (less the tolerance) everywhere
/// between samples `a` and `b`, between which no point moves more than
/// `gap_m`: each point of a part in between is within `x` of where it was at
/// `a` and within `gap_m - x` of where it is at `b`, so its distance is at
/// least `max(d_a - x, d_b - gap_m + x) >= (d_a + d_b - gap_m) / 2`.
///
/// `hanging_may_need_m`: what the hanging parts may need somewhere between
/// (the larger of the two clearances) where the load may enter or leave a
/// landing zone there, else zero.
fn gap_holds(a: &[SampleCheck], b: &[SampleCheck], gap_m: f64, cutoff_m: f64, hanging_may_need_m: f64) -> bool {
    gap_margin(a, b, gap_m, cutoff_m, hanging_may_need_m) >= -DISTANCE_TOLERANCE_M
}

/// The least any part can be beyond its requirement anywhere between samples
/// `a` and `b` (m; the bound of [`gap_holds`], with the same requirements).
fn gap_margin(a: &[SampleCheck], b: &[SampleCheck], gap_m: f64, cutoff_m: f64, hanging_may_need_m: f64) -> f64 {
    let known = |c: &SampleCheck| c.nearest.distance_m.min(cutoff_m);
    let need =
        |c: &SampleCheck, m: f64| if c.part.dependence() == Dependence::Full { m.max(hanging_may_need_m) } else { m };
    let from_one = |c: &SampleCheck| known(c) - gap_m - need(c, c.required_m);
    let from_a = a.iter().map(|ca| match b.iter().find(|cb| cb.part == ca.part) {
        Some(cb) => (known(ca) + known(cb) - gap_m) / 2.0 - need(ca, ca.required_m.max(cb.required_m)),
        None => from_one(ca),
    });
    let only_b = b.iter().filter(|cb| !a.iter().any(|ca| ca.part == cb.part)).map(from_one);
    // A margin that is not a number makes the whole one not a number.
    from_a.chain(only_b).fold(f64::INFINITY, |m, x| if m.is_nan() || x.is_nan() { f64::NAN } else { m.min(x) })
}

/// [`gap_holds`] for the load's and rigging's distances to the crane's own
/// structure, which moves too: each moves at most `gap_m`, so the distance
/// between them changes by at most twice that.
fn own_gap_holds(a: &[(PartKind, f64, &str)], b: &[(PartKind, f64, &str)], gap_m: f64) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|((ka, da, _), (kb, db, _))| {
            ka == kb && (da + db - 2.0 * gap_m) / 2.0 >= OWN_CLEARANCE_M - DISTANCE_TOLERANCE_M
        })
}

/// What [`between`] needs to know of a move and the lift.
struct Gaps {
    /// The most any point moves over the whole move (m).
    moved_m: f64,
    /// [`search_cutoff_m`].
    cutoff_m: f64,
    /// The larger of the clearance and the landing clearance (m).
    hanging_worst_m: f64,
}

/// The samples to add between `a` and `b` (in order along the move) so that
/// [`gap_holds`] between every two neighbours, or they are `REFINED_GAP_M`
/// apart; `at` checks the configuration at a fraction of the move. Not
/// below a sample that already found a problem: the move is rejected anyway.
fn between(a: &Sample, b: &Sample, g: &Gaps, at: &(impl Fn(f64) -> Sample + Sync)) -> Vec<Sample> {
    let gap_m = g.moved_m * (b.t - a.t);
    if gap_m <= REFINED_GAP_M
        || !a.problems.is_empty()
        || !b.problems.is_empty()
        || (gap_holds(&a.checks, &b.checks, gap_m, g.cutoff_m, hanging_may_need_m(a, b, gap_m, g))
            && own_gap_holds(&a.own, &b.own, gap_m))
    {
        return Vec::new();
    }
    let mid = at(0.5 * (a.t + b.t));
    let mut out = between(a, &mid, g, at);
    let after = between(&mid, b, g, at);
    out.push(mid);
    out.extend(after);
    out
}

/// What the hanging parts may need between `a` and `b`, `gap_m` apart: the
/// larger clearance where the load's footprint (which moves no more than the
/// gap either) may enter or leave a landing zone there, else nothing more.
fn hanging_may_need_m(a: &Sample, b: &Sample, gap_m: f64, g: &Gaps) -> f64 {
    let zones_steady = a.zone_margin_m > gap_m || b.zone_margin_m > gap_m;
    if zones_steady { 0.0 } else { g.hanging_worst_m }
}

/// `samples` with `added[k]` put after `samples[k]`.
fn interleave(samples: Vec<Sample>, added: Vec<Vec<Sample>>) -> Vec<Sample> {
    let mut out = Vec::with_capacity(samples.len() + added.iter().map(Vec::len).sum::<usize>());
    let mut added = added.into_iter();
    for s in samples {
        out.push(s);
        out.extend(added.next().unwrap_or_default());
    }
    out
}

/// Whether two configurations put the crane in the same place: equal joint
/// values, swing and load yaw modulo a turn. A value that is not a number is
/// never the same.
fn same_place(a: &Config, b: &Config) -> bool {
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * (1.0 + x.abs().max(y.abs()));
    let turn = |x: f64, y: f64| close(turn_apart(x, y), 0.0);
    turn(a.swing_rad, b.swing_rad)
        && close(a.radial, b.radial)
        && close(a.hoist_m, b.hoist_m)
        && turn(a.load_yaw_rad, b.load_yaw_rad)
}

/// How far apart two angles are (rad, in [0, π]), whatever turn each is on.
fn turn_apart(x: f64, y: f64) -> f64 {
    let d = (x - y).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

/// Where the moves do not make one path: a move that changes a joint other
/// than its own (the samples move only its own), or one that does not start
/// where the one before ends (the crane would jump, unchecked).
fn path_breaks(moves: &[Move]) -> Vec<String> {
    let mut out = Vec::new();
    for (i, m) in moves.iter().enumerate() {
        let (mut a, mut b) = (m.from.to_array(), m.to.to_array());
        let j = m.joint.index();
        (a[j], b[j]) = (0.0, 0.0);
        if !same_place(&Config::from_array(a), &Config::from_array(b)) {
            out.push(format!(
                "move {} ({:?}) changes more than its own joint: {:?} to {:?}",
                i + 1,
                m.joint,
                m.from,
                m.to
            ));
        }
        if let Some(next) = moves.get(i + 1)
            && !same_place(&m.to, &next.from)
        {
            out.push(format!(
                "move {} does not start where move {} ends: {:?}, then {:?}",
                i + 2,
                i + 1,
                m.to,
                next.from
            ));
        }
    }
    out
}

/// [`validate`] for a whole lift: also that the moves start with the load at
/// its pick pose and end with it at its set pose, as the lift asks them
/// (forward kinematics, to 1 mm and 0.001 rad: the pick and set
/// configurations come from the crane's inverse kinematics, which this checks
/// too).
pub fn validate_lift(
    task: &LiftTask,
    chart: Option<&ChartConfig>,
    world: &World,
    rules: &Rules,
    moves: &[Move],
    landing_moves: &[bool],
) -> Verdict {
    let mut v = validate(task, chart, world, rules, moves, landing_moves);
    let at = |c: &Config, want: &liftplan_core::crane::LoadPose, (verb, which): (&str, &str)| {
        let got = task.crane.load_pose(c, &task.load);
        let off_m = (got.x_m - want.x_m).hypot(got.y_m - want.y_m).hypot(got.z_m - want.z_m);
        (!(off_m <= 1e-3 && turn_apart(got.yaw_rad, want.yaw_rad) <= 1e-3)).then(|| {
            format!(
                "the path {verb} with the load at ({:.3}, {:.3}, {:.3}) m, yaw {:.2}°, not at its {which} pose ({:.3}, {:.3}, {:.3}) m, yaw {:.2}°",
                got.x_m,
                got.y_m,
                got.z_m,
                got.yaw_rad.to_degrees(),
                want.x_m,
                want.y_m,
                want.z_m,
                want.yaw_rad.to_degrees()
            )
        })
    };
    let starts_at = match &task.resume_from {
        Some((_, pose)) => (pose, "resume_from"),
        None => (&task.pick_pose, "pick"),
    };
    let ends = match (moves.first(), moves.last()) {
        (Some(first), Some(last)) => {
            [at(&first.from, starts_at.0, ("starts", starts_at.1)), at(&last.to, &task.set_pose, ("ends", "set"))]
                .into_iter()
                .flatten()
                .collect()
        }
        _ => vec!["the path has no moves".to_string()],
    };
    v.problems.extend(ends);
    v.ok = v.problems.is_empty();
    v
}

/// Validates a plan: the moves from pick to set, the first and last being the
/// lift-off and set-down moves (`landing_moves` marks which are).
pub fn validate(
    task: &LiftTask,
    chart: Option<&ChartConfig>,
    world: &World,
    rules: &Rules,
    moves: &[Move],
    landing_moves: &[bool],
) -> Verdict {
    let t0 = std::time::Instant::now();
    let mut problems = Vec::new();
    let mut set_up = None;
    // Fixed parts once: they stand on the ground, so only obstacles other
    // than the ground they stand on count (ground up to half a metre above
    // their level; a bank higher up, under the carrier or the outrigger
    // beams, is in the way).
    if let Some(first) = moves.first() {
        for &kind in task.crane.part_kinds() {
            if kind.dependence() != Dependence::Fixed {
                continue;
            }
            if let Some(b) = task.crane.part(kind, &first.from, &task.load) {
                // It stands on the ground.
                let standing = task.crane.standing_ground_top_z();
                let n = nearest(world, &b.with_underside_raised(rules.support_m), standing, 1.0);
                if n.distance_m <= 0.0 {
                    problems.push(format!("crane set-up: {} intersects {}", kind.name(), n.object));
                }
            }
        }
        problems.extend(crane_outside_its_areas(task).map(|why| format!("crane set-up: {why}")));
        let (ground, problem) = set_up_ground(task, world);
        set_up = ground;
        problems.extend(problem);
    }
    problems.extend(path_breaks(moves));
    let mut move_checks = Vec::new();
    let (mut total, mut refined) = (0, 0);
    let cutoff_m = search_cutoff_m(rules.clearance_m);
    for (mi, m) in moves.iter().enumerate() {
        let lever_m = lever_for(task, m);
        // Swung by a gust, a hanging part's box also widens as it hangs
        // lower: by the swing per metre for each metre the sheave rises or
        // the part sinks, each at most what the move moves a point.
        let moved_m = m.delta().abs() * lever_m * (1.0 + 2.0 * task.gust_swing_per_m);
        if !(moved_m <= MAX_MOVED_M) {
            problems.push(format!(
                "move {} ({:?}) moves a point {moved_m} m, more than the validator checks ({MAX_MOVED_M} m)",
                mi + 1,
                m.joint
            ));
            continue;
        }
        let n = samples_for(moved_m, rules.sample_m);
        let landing = landing_moves.get(mi).copied().unwrap_or(false);
        let at = |t: f64| {
            let (a, b) = (m.from.to_array(), m.to.to_array());
            let mut v = a;
            let j = m.joint.index();
            v[j] = a[j] + (b[j] - a[j]) * t;
            Sample { t, ..check_config(task, chart, world, rules, &Config::from_array(v), landing) }
        };
        let even: Vec<Sample> = (0..n).into_par_iter().map(|s| at(s as f64 / (n - 1).max(1) as f64)).collect();
        // Where two neighbours' distances do not rule out a part coming
        // closer than its requirement between them, more samples there.
        let gaps = Gaps { moved_m, cutoff_m, hanging_worst_m: rules.clearance_m.max(rules.landing_clearance_m) };
        let added: Vec<Vec<Sample>> = even.par_windows(2).map(|w| between(&w[0], &w[1], &gaps, &at)).collect();
        let extra: usize = added.iter().map(Vec::len).sum();
        let in_order = interleave(even, added);
        total += n + extra;
        refined += extra;
        // The least margin along the whole move, between the samples too:
        // what the steps report, a bound no part comes closer than.
        let margin = |c: &SampleCheck| c.nearest.distance_m.min(cutoff_m) - c.required_m;
        let least_at_samples_m = in_order.iter().flat_map(|s| &s.checks).map(margin).fold(f64::INFINITY, f64::min);
        let least_between_m = in_order
            .windows(2)
            .map(|w| {
                let gap_m = moved_m * (w[1].t - w[0].t);
                gap_margin(&w[0].checks, &w[1].checks, gap_m, cutoff_m, hanging_may_need_m(&w[0], &w[1], gap_m, &gaps))
            })
            .fold(f64::INFINITY, f64::min);
        let least_margin_m = least_at_samples_m.min(least_between_m);
        let mut move_problems: Vec<String> = Vec::new();
        if let Some((part, area)) = over_not_over(task, m, moved_m, rules.sample_m, landing) {
            let hanging = part.dependence() == liftplan_core::crane::Dependence::Full;
            move_problems.push(if hanging && task.fall_zone_m > 0.0 {
                format!(
                    "{} comes over not_over '{}' or within its fall zone of it (fall_zone_m = {} m)",
                    liftplan_core::lift::over_not_over_said(part),
                    area.name,
                    task.fall_zone_m
                )
            } else {
                format!("{} comes over not_over '{}'", liftplan_core::lift::over_not_over_said(part), area.name)
            });
        }
        let mut tight: Option<SampleCheck> = None;
        let mut util: Option<SampleCheck> = None;
        for Sample { checks, problems: probs, .. } in in_order {
            for p in probs {
                if !move_problems.contains(&p) && move_problems.len() < 5 {
                    move_problems.push(p);
                }
            }
            for c in checks {
                let margin = c.nearest.distance_m - c.required_m;
                if tight.as_ref().is_none_or(|t| margin < t.nearest.distance_m - t.required_m) {
                    tight = Some(c.clone());
                }
                if util.as_ref().is_none_or(|u| c.utilisation_pct.unwrap_or(0.0) > u.utilisation_pct.unwrap_or(0.0)) {
                    util = Some(c);
                }
            }
        }
        for p in &move_problems {
            problems.push(format!("move {} ({:?}): {p}", mi + 1, m.joint));
        }
        if let (Some(t), Some(u)) = (tight, util) {
            let clearance_m = if t.nearest.distance_m < cutoff_m {
                (t.required_m + least_margin_m).min(t.nearest.distance_m).max(0.0)
            } else {
                t.nearest.distance_m
            };
            move_checks.push(MoveCheck {
                samples: n + extra,
                clearance_m,
                tightest: t,
                max_utilisation: u,
                problems: move_problems,
            });
        }
    }
    Verdict {
        ok: problems.is_empty(),
        moves: move_checks,
        problems,
        set_up_ground: set_up,
        samples: total,
        refined_samples: refined,
        seconds: t0.elapsed().as_secs_f64(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use liftplan_core::frame::{Mat3, Point3, Vec3, rot_z};
    use liftplan_cspace::Joint;
    use proptest::prelude::*;

    use liftplan_core::testing::unit_stream;

    fn clutter(seed: u64) -> TriMesh {
        let mut mesh = TriMesh::default();
        let mut u = unit_stream(seed);
        for k in 0..40 {
            let g = mesh.group_id(&format!("B{k}"));
            let (x, y, z) = (u() * 80.0 - 40.0, u() * 80.0 - 40.0, u() * 20.0);
            let (hx, hy, hz) = (0.2 + u() * 3.0, 0.2 + u() * 3.0, 0.2 + u() * 6.0);
            mesh.add_box(g, [x - hx, y - hy, z], [x + hx, y + hy, z + 2.0 * hz]);
        }
        mesh
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(24)))]
        /// Cutting the box into pieces gives the distance of the whole box.
        #[test]
        fn pieces_give_the_box_distance(
            seed in any::<u64>(),
            centre in prop::array::uniform3(-30.0f64..30.0),
            half in prop::array::uniform3(0.05f64..35.0),
            yaw in -3.2f64..3.2,
            tilt in -1.5f64..1.5,
        ) {
            let mesh = clutter(seed);
            let world = World::new(&mesh, &[], &[]).unwrap();
            let m = world.mesh.as_ref().unwrap();
            let (st, ct) = tilt.sin_cos();
            let axes: Mat3 = rot_z(yaw) * Mat3::new(ct, 0.0, st, 0.0, 1.0, 0.0, -st, 0.0, ct);
            let b = Obb::new(Point3::new(centre[0], centre[1], centre[2] + 15.0), axes, Vec3::new(half[0], half[1], half[2]));
            let (pose, cub) = parry_box(&b);
            let whole = query::distance(&pose, &cub, &Pose::identity(), m).unwrap().distance;
            let (cut, _) = mesh_nearest(m, &b).unwrap();
            prop_assert!((cut - whole).abs() < 1e-6, "pieces {cut} vs whole box {whole}");
        }
    }

    /// The points of voxels `lo ..= hi` one by one in (voxel, input) order,
    /// the first of the nearest kept: what the index's search must answer.
    fn nearest_point_brute(
        points: &[[f64; 3]],
        ground: &[bool],
        b: &Obb,
        (lo, hi): ([i32; 3], [i32; 3]),
        ground_below_z: f64,
        mut best: Nearest,
    ) -> Nearest {
        let (pose, cub) = parry_box(b);
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by_key(|&i| (voxel(&points[i]), i));
        for i in order {
            let key = voxel(&points[i]);
            if !(0..3).all(|a| lo[a] <= key[a] && key[a] <= hi[a]) || (ground[i] && points[i][2] <= ground_below_z) {
                continue;
            }
            let p = points[i];
            let d = cub.distance_to_point(&pose, Vector::new(p[0], p[1], p[2]), true);
            if d < best.distance_m {
                let object = if ground[i] { "ground (scan)" } else { "scanned structure" };
                best = Nearest { distance_m: d, object: object.into(), at: Some(p) };
            }
        }
        best
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(500)))]
        /// Both walks of the point index find the brute force's point, ties
        /// included: coordinates on a 0.25 m lattice put many points at the
        /// same distance from a box, and on voxel boundaries.
        #[test]
        fn point_search_is_the_brute_force(
            seed in any::<u64>(),
            n in 0usize..300,
            spread in prop::sample::select(vec![2.0f64, 8.0, 40.0]),
            centre in prop::array::uniform3(-6.0f64..6.0),
            half in prop::array::uniform3(0.05f64..6.0),
            yaw in -3.2f64..3.2,
            tilt in -1.5f64..1.5,
            cutoff in 0.3f64..8.0,
            start in prop::option::of(0.0f64..5.0),
            ground_below_z in prop_oneof![Just(ALL_GROUND), Just(f64::INFINITY), -3.0f64..3.0],
        ) {
            let mut u = unit_stream(seed);
            let points: Vec<[f64; 3]> =
                (0..n).map(|_| [0, 1, 2].map(|_| ((u() - 0.5) * spread * 4.0).round() / 4.0)).collect();
            let ground: Vec<bool> = (0..n).map(|_| u() < 0.4).collect();
            let index = PointIndex::new(&points, &ground).unwrap();
            let (st, ct) = tilt.sin_cos();
            let axes: Mat3 = rot_z(yaw) * Mat3::new(ct, 0.0, st, 0.0, 1.0, 0.0, -st, 0.0, ct);
            let b = Obb::new(Point3::new(centre[0], centre[1], centre[2]), axes, Vec3::new(half[0], half[1], half[2]));
            let aabb = b.aabb().expanded(cutoff);
            let range = (voxel(&aabb.min), voxel(&aabb.max));
            let start = Nearest {
                distance_m: start.unwrap_or(f64::INFINITY),
                object: "mesh".into(),
                at: None,
            };
            let want = nearest_point_brute(&points, &ground, &b, range, ground_below_z, start.clone());
            let (pose, cub) = parry_box(&b);
            for walk_occupied in [false, true] {
                let mut got = start.clone();
                nearest_point(&index, (&pose, &cub), range, ground_below_z, walk_occupied, &mut got);
                prop_assert_eq!(&got, &want, "walk_occupied {}", walk_occupied);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(200)))]
        /// No corner of any part moves farther than the lever times the
        /// joint's change: the samples' spacing and the bound between them
        /// rest on it.
        #[test]
        fn no_point_moves_farther_than_the_lever(
            tower in any::<bool>(),
            joint in 0usize..4,
            at in prop::array::uniform4(0.0f64..1.0),
            delta in -0.3f64..0.3,
        ) {
            let task = crate::test_lift(if tower { "tower-hh-60" } else { "ac-700" });
            let from = crate::test_config(&task, at, f64::INFINITY);
            let joint = [Joint::Swing, Joint::Radial, Joint::Hoist, Joint::Rotate][joint];
            let mut to = from.to_array();
            to[joint.index()] += delta;
            let m = Move { joint, from, to: Config::from_array(to) };
            let lever = lever_for(&task, &m);
            let (a, b) = (task.crane.pose(&m.from, &task.load), task.crane.pose(&m.to, &task.load));
            for ((kind, pa), (_, pb)) in a.parts.iter().zip(&b.parts) {
                for (ca, cb) in pa.corners().iter().zip(pb.corners()) {
                    let moved = (cb - ca).norm();
                    prop_assert!(moved <= lever * delta.abs() * (1.0 + 1e-9) + 1e-9,
                        "{kind:?} corner moved {moved} m for {delta} of {joint:?}, lever {lever}");
                }
            }
        }
    }

    proptest! {
        #![proptest_config({
            let cases = liftplan_core::testing::proptest_cases(500);
            ProptestConfig { max_global_rejects: liftplan_core::testing::proptest_rejects(cases), ..ProptestConfig::with_cases(cases) }
        })]
        /// Moving the footprint's corners less than the zone margin never
        /// changes whether it is over a landing zone: star-shaped zones with
        /// notches, footprints in, out and across them.
        #[test]
        fn the_zone_margin_keeps_the_landing_rule(
            seed in any::<u64>(),
            zones in 1usize..3,
            centre in prop::array::uniform2(-3.0f64..3.0),
            half in prop::array::uniform2(0.2f64..3.0),
            yaw in -3.2f64..3.2,
        ) {
            let mut u = unit_stream(seed);
            let polys: Vec<Vec<[f64; 2]>> = (0..zones)
                .map(|_| {
                    let (cx, cy, k) = (u() * 4.0 - 2.0, u() * 4.0 - 2.0, 3 + (u() * 9.0) as usize);
                    (0..k)
                        .map(|i| {
                            let a = (i as f64 + 0.8 * u()) / k as f64 * std::f64::consts::TAU;
                            let r = 0.5 + u() * 6.0;
                            [cx + r * a.cos(), cy + r * a.sin()]
                        })
                        .collect()
                })
                .collect();
            let (sy, cyaw) = yaw.sin_cos();
            let footprint: Vec<[f64; 2]> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .iter()
                .map(|(a, b)| {
                    let (x, y) = (a * half[0], b * half[1]);
                    [centre[0] + x * cyaw - y * sy, centre[1] + x * sy + y * cyaw]
                })
                .collect();
            let over = |f: &[[f64; 2]]| polys.iter().any(|poly| f.iter().all(|p| in_polygon(poly, *p)));
            let inside = over(&footprint);
            let margin = zone_margin_m(&polys, &footprint, inside);
            prop_assume!(margin.is_finite() && margin > 1e-6);
            for _ in 0..20 {
                let moved: Vec<[f64; 2]> = footprint
                    .iter()
                    .map(|p| {
                        let (a, r) = (u() * std::f64::consts::TAU, margin * 0.999 * u().sqrt());
                        [p[0] + r * a.cos(), p[1] + r * a.sin()]
                    })
                    .collect();
                prop_assert_eq!(over(&moved), inside, "margin {} moved {:?} from {:?}", margin, moved, footprint);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(200)))]
        /// The load's and rigging's distances to the crane are never more than
        /// the exact distance to its nearest part, and are that distance
        /// wherever it is within a metre.
        #[test]
        fn own_distances_are_exact_near_and_never_more(
            tower in any::<bool>(),
            at in prop::array::uniform4(0.0f64..1.0),
        ) {
            let task = crate::test_lift(if tower { "tower-hh-60" } else { "ac-700" });
            let c = crate::test_config(&task, at, 30.0);
            let pose = task.crane.pose(&c, &task.load);
            for (kind, d, _) in own_distances(&pose) {
                let (_, hb) = pose.parts.iter().find(|(k, _)| *k == kind).unwrap();
                let (p1, c1) = parry_box(hb);
                let exact = pose
                    .parts
                    .iter()
                    .filter(|(k, _)| k.dependence() != Dependence::Full)
                    .map(|(_, b)| {
                        let (p2, c2) = parry_box(b);
                        query::distance(&p1, &c1, &p2, &c2).unwrap().distance
                    })
                    .fold(f64::INFINITY, f64::min);
                prop_assert!(d <= exact + 1e-12, "{kind:?}: {d} over the exact {exact}");
                if exact <= OWN_EXACT_WITHIN_M {
                    prop_assert!((d - exact).abs() <= 1e-12, "{kind:?}: {d}, exact {exact}");
                }
            }
        }
    }

    proptest! {
        #![proptest_config({
            let cases = liftplan_core::testing::proptest_cases(300);
            ProptestConfig { max_global_rejects: liftplan_core::testing::proptest_rejects(cases), ..ProptestConfig::with_cases(cases) }
        })]
        /// The planner's shortest rope per luff row keeps the load and its
        /// rigging off the boom by more than the validator asks, at any swing,
        /// load yaw and longer rope: the planner does not plan what the
        /// validator would refuse. (The load here hangs off its centre of
        /// gravity.) Also swung by a gust, up to 20 cm per metre it hangs
        /// (the permissible wind gives 1.5), and off by a centre of gravity
        /// known to up to 0.5 m.
        #[test]
        fn the_planners_shortest_rope_keeps_the_load_off_the_boom(
            luff_deg in 0.0f64..80.0,
            row_deg in 0.0f64..2.0,
            more_rope in 0.0f64..3.0,
            swing in 0.0f64..6.3,
            yaw in 0.0f64..6.3,
            gusty in prop_oneof![Just(0.0), 0.0f64..0.2],
            cog_tolerance_m in prop_oneof![Just(0.0), 0.0f64..0.5],
        ) {
            let luff = luff_deg.to_radians();
            let mut task = crate::test_lift("ac-700");
            task.gust_swing_per_m = gusty;
            task.cog_tolerance_m = cog_tolerance_m;
            let shortest = liftplan_cspace::min_hoist_for_internal_clearance(
                &task.crane, &task.load, (luff_deg + row_deg).to_radians(), gusty, cog_tolerance_m);
            // Swung far enough at a steep enough boom, no rope keeps it off.
            prop_assume!(shortest.is_finite());
            let lim = task.crane.limits();
            let c = Config { swing_rad: swing, radial: luff, hoist_m: shortest.max(lim.hoist_m.0) + more_rope, load_yaw_rad: yaw };
            let pose = task.crane.pose(&c, &task.load);
            let boom = pose.get(PartKind::Boom).unwrap();
            let (pb, cb) = parry_box(boom);
            let sheave_z = task.crane.sheave(&c).z;
            for kind in [PartKind::Load, PartKind::Rigging] {
                let (ph, ch) = parry_box(&task.hanging_swept(kind, pose.get(kind).unwrap(), sheave_z));
                let d = query::distance(&ph, &ch, &pb, &cb).unwrap().distance;
                prop_assert!(d >= OWN_CLEARANCE_M, "{kind:?} {d} m from the boom at {c:?}");
            }
        }
    }

    /// The validator's test of where the crane stands (parry3d's hull and
    /// distances, winding numbers) says what core's, which the planner
    /// applies, says, wherever the crane stands in and about an L-shaped
    /// yard, turned any way, with mats or without; both ways come up.
    #[test]
    fn the_validator_and_the_planner_agree_where_the_crane_may_stand() {
        use liftplan_core::crane::{CraneSetup, Placement};
        use liftplan_core::lift::{CraneArea, GroundSpec};
        let task = crate::test_lift("ac-700");
        let yard = vec![[-15.0, -15.0], [35.0, -15.0], [35.0, 10.0], [10.0, 10.0], [10.0, 35.0], [-15.0, 35.0]];
        let (mut within, mut outside) = (0, 0);
        for k in 0..24 * 24 * 6 {
            let (x, y) = (-20.0 + 2.37 * (k % 24) as f64, -20.0 + 2.41 * (k / 24 % 24) as f64);
            let heading = 0.37 + 1.1 * (k / (24 * 24)) as f64;
            let mut t = task.clone();
            let placement = Placement { x_m: x, y_m: y, heading_rad: heading, ..t.crane.placement };
            t.crane = CraneSetup::new(t.crane.model.clone(), placement).unwrap();
            t.ground = (k % 2 == 0).then_some(GroundSpec { mat_m: [2.5, 1.2], allowable_kpa: None });
            t.crane_stands_in = vec![CraneArea { name: "yard".into(), corners_m: yard.clone() }];
            let planner = t.stands_outside_its_areas();
            let ours = crane_outside_its_areas(&t);
            assert_eq!(planner.is_some(), ours.is_some(), "at ({x}, {y}), heading {heading}: {planner:?} {ours:?}");
            if ours.is_some() { outside += 1 } else { within += 1 }
        }
        assert!(within > 100 && outside > 100, "{within} within, {outside} outside");
        // Said naming the area, with the mats where there are some.
        let mut t = task.clone();
        t.crane_stands_in =
            vec![CraneArea { name: "far".into(), corners_m: vec![[90.0, 0.0], [99.0, 0.0], [99.0, 9.0]] }];
        assert_eq!(
            crane_outside_its_areas(&t).as_deref(),
            Some(
                "the crane set up at position_m = [0.00, 0.00], heading_deg = 20: its carrier and outriggers do not stand within an area it may stand in, clear of its edges (crane_stands_in: 'far')"
            )
        );
        t.crane_stands_in.clear();
        assert_eq!(crane_outside_its_areas(&t), None);
    }

    /// What lies in the ground under the outrigger pads: a pipe buried
    /// under one pad is named with the depth of its top, in the zone the
    /// pad's load spreads into; nothing within the set-up tolerance, beyond
    /// the zone or in the scanned ground is; a pit's scanned sides are; a
    /// tower crane has no pads.
    #[test]
    fn what_lies_in_the_ground_under_the_pads_is_named() {
        use liftplan_core::outriggers::{Pad, pad_at};
        let mut task = crate::test_lift("ac-700");
        task.ground = Some(liftplan_core::lift::GroundSpec { mat_m: [2.0, 2.0], allowable_kpa: None });
        let at = pad_at(&task.crane, Pad::RearLeft).unwrap();
        // The zone: 4 m deep, within 1 + 2 = 3 m of the pad's centre.
        let buried = |offset_m: f64, top_z: f64, height_m: f64| {
            let mut mesh = TriMesh::default();
            let g = mesh.group_id("/UG-DRAIN-1");
            let (x, y) = (at[0] + offset_m, at[1]);
            mesh.add_box(g, [x - 0.3, y - 1.0, top_z - height_m], [x + 0.3, y + 1.0, top_z]);
            World::new(&mesh, &[], &[]).unwrap()
        };
        let pipe = |offset_m: f64, top_z: f64| buried(offset_m, top_z, 0.6);
        let under = under_pads(&task, &pipe(1.0, -1.2));
        assert_eq!(under.len(), 1, "{under:?}");
        let u = &under[0];
        assert_eq!((u.pad, u.object.as_str()), (Pad::RearLeft, "/UG-DRAIN-1"));
        assert!((u.depth_m - 1.2).abs() < 2e-3 && u.zone_half_m == 3.0 && u.zone_depth_m == 4.0, "{u:?}");
        assert!(
            u.said().starts_with("/UG-DRAIN-1 1.20 m below the set-up level under the rear left pad"),
            "{}",
            u.said()
        );
        // A shallow duct, within the scanned ground's tolerance: the model's
        // is named with its top, however far down it reaches, its sloping
        // top's highest point over the zone found (a triangle clipped to it).
        let shallow = &under_pads(&task, &buried(1.0, -0.1, 0.35))[0];
        assert!((shallow.depth_m - 0.1).abs() < 1e-9 && shallow.object == "/UG-DRAIN-1", "{shallow:?}");
        assert!(shallow.said().starts_with("/UG-DRAIN-1 0.10 m below the set-up level under the rear left pad"));
        let high = &under_pads(&task, &pipe(1.0, -0.3))[0];
        assert!((high.depth_m - 0.3).abs() < 1e-9, "{high:?}");
        let mut mesh = TriMesh::default();
        let g = mesh.group_id("/DUCT-SLOPED");
        let corners = [[at[0] - 10.0, at[1], -0.45], [at[0] + 10.0, at[1], -0.05], [at[0], at[1] + 10.0, -0.25]];
        mesh.add_part(g, false, &corners, &[[0, 1, 2]]);
        let sloped = under_pads(&task, &World::new(&mesh, &[], &[]).unwrap());
        let sloped = sloped.iter().find(|u| u.pad == Pad::RearLeft).unwrap();
        // x at[0] + 3 is the zone's edge: 0.05 + 0.4 * 7 / 20 below it.
        assert!((sloped.depth_m - 0.19).abs() < 1e-9, "{sloped:?}");
        // The slab the crane stands on (its top within 5 cm of the set-up
        // level), with a duct under it: the duct is named, the slab not.
        let mut mesh = TriMesh::default();
        let slab = mesh.group_id("/SLAB");
        mesh.add_box(slab, [at[0] - 5.0, at[1] - 5.0, -0.25], [at[0] + 5.0, at[1] + 5.0, -0.02]);
        assert!(under_pads(&task, &World::new(&mesh, &[], &[]).unwrap()).is_empty());
        let duct = mesh.group_id("/DUCT-1");
        mesh.add_box(duct, [at[0] - 0.2, at[1] - 4.0, -0.6], [at[0] + 0.2, at[1] + 4.0, -0.3]);
        let under = under_pads(&task, &World::new(&mesh, &[], &[]).unwrap());
        assert!(under.len() == 1 && under[0].object == "/DUCT-1" && (under[0].depth_m - 0.3).abs() < 1e-9, "{under:?}");
        // Every thing under the pad, shallowest first: a drain under the
        // duct, and a foundation from the surface down past the tolerance.
        let drain = mesh.group_id("/UG-DRAIN-2");
        mesh.add_box(drain, [at[0] - 3.0, at[1] + 0.5, -2.0], [at[0] + 3.0, at[1] + 1.0, -1.5]);
        let foundation = mesh.group_id("/FDN-9");
        mesh.add_box(foundation, [at[0] + 2.0, at[1] - 2.0, -1.2], [at[0] + 6.0, at[1] + 2.0, 0.3]);
        let under = under_pads(&task, &World::new(&mesh, &[], &[]).unwrap());
        let named: Vec<(&str, f64)> = under.iter().map(|u| (u.object.as_str(), u.depth_m)).collect();
        assert_eq!(named, [("/FDN-9", 0.0), ("/DUCT-1", 0.3), ("/UG-DRAIN-2", 1.5)], "{under:?}");
        assert!(
            under[0].said().starts_with("/FDN-9 reaching up to the set-up level under the rear left pad"),
            "{}",
            under[0].said()
        );
        // Beyond the zone: not named.
        assert!(under_pads(&task, &pipe(3.5, -1.2)).is_empty());
        assert!(under_pads(&task, &pipe(1.0, -4.7)).is_empty());
        // A pit's scanned sides under the pad are; its scanned floor, ground,
        // is not.
        let pit = [[at[0], at[1], -1.5], [at[0] + 0.5, at[1], -0.8]];
        let seen = under_pads(&task, &World::new(&TriMesh::default(), &pit, &[true, false]).unwrap());
        assert_eq!(seen.len(), 1, "{seen:?}");
        assert!(seen[0].object == "scanned structure" && (seen[0].depth_m - 0.8).abs() < 2e-3, "{seen:?}");
        assert!(under_pads(&task, &World::new(&TriMesh::default(), &pit, &[true, true]).unwrap()).is_empty());
        // Without mats, the pad's float: a zone of 2 m, within 1.5 m.
        task.ground = None;
        assert!(under_pads(&task, &pipe(1.0, -1.2))[0].zone_half_m == 1.5);
        assert!(under_pads(&task, &pipe(2.0, -1.2)).is_empty());
        assert!(under_pads(&crate::test_lift("tower-hh-60"), &pipe(0.0, -1.2)).is_empty());
    }

    #[test]
    fn ties_name_the_same_obstacle_on_every_build() {
        // Three points 1 m under a long box's underside: the one in the lowest
        // voxel is named, however the index's hash maps are seeded.
        let points = [[0.5, 0.5, -1.0], [5.5, 0.5, -1.0], [-3.5, 0.5, -1.0]];
        let ground = [true, false, false];
        let b = Obb::new(Point3::new(0.0, 0.0, 1.0), Mat3::identity(), Vec3::new(10.0, 1.0, 1.0));
        for _ in 0..20 {
            let world = World::new(&TriMesh::default(), &points, &ground).unwrap();
            let n = nearest(&world, &b, ALL_GROUND, 3.0);
            assert_eq!((n.distance_m, n.object.as_str(), n.at), (1.0, "scanned structure", Some([-3.5, 0.5, -1.0])));
        }
    }

    #[test]
    fn points_without_their_ground_flags_are_refused() {
        let e = World::new(&TriMesh::default(), &[[0.0; 3], [1.0; 3]], &[true]).err().unwrap_or_default();
        assert!(e.contains("2 site points but 1 ground flags"), "{e}");
    }
}
