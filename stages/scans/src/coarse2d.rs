//! Pose-free coarse alignment of levelled scans by correlating top views.
//!
//! Terrestrial scanners level themselves, so two scans differ by a yaw and a
//! translation. Vertical surfaces (walls, columns, tank shells: points whose normal
//! is near horizontal) seen from above form a plan of the site that both scans
//! share, whatever the viewpoint. For each yaw on a 2° grid the source plan is
//! rotated and cross-correlated with the target plan (FFT; binary occupancy, so
//! dense near-scanner areas do not dominate); the best yaws are refined on a finer
//! grid, and the height offset is the median difference of the two scans' lowest
//! points per plan cell. ICP then takes this guess to millimetres.
//!
//! On repetitive industrial geometry this is far more reliable than local
//! descriptors, which see the same beam or pipe everywhere.

use crate::register::RegCloud;
use liftplan_core::frame::{Pose, Vec3};
use nalgebra as na;
use rayon::prelude::*;
use rustfft::num_complex::Complex32;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Plan-view points of vertical structure, at most `max` (fixed stride).
pub fn vertical_structure(c: &RegCloud, max: usize) -> Vec<[f64; 2]> {
    let idx: Vec<usize> =
        (0..c.pts.len()).filter(|&i| c.normals[i] != [0.0; 3] && c.normals[i][2].abs() < 0.5).collect();
    let stride = (idx.len() / max.max(1)).max(1);
    idx.iter().step_by(stride).map(|&i| [c.pts[i][0], c.pts[i][1]]).collect()
}

struct Plan {
    n: usize,
    origin: [f64; 2],
    cell: f64,
    spectrum: Vec<Complex32>,
}

struct Fft2 {
    n: usize,
    fwd: Arc<dyn Fft<f32>>,
    inv: Arc<dyn Fft<f32>>,
}

impl Fft2 {
    fn new(n: usize) -> Fft2 {
        let mut p = FftPlanner::new();
        Fft2 { n, fwd: p.plan_fft_forward(n), inv: p.plan_fft_inverse(n) }
    }

    /// The 2-D transform of the `n` x `n` image `data` (row-major): every
    /// row, then every column as a row of the transposed image, with one
    /// scratch buffer for all (each column gathered and scattered on its own
    /// was a cache miss a value, and each transform allocated its scratch).
    fn run(&self, data: &mut [Complex32], inverse: bool) {
        let f = if inverse { &self.inv } else { &self.fwd };
        let mut scratch = vec![Complex32::new(0.0, 0.0); f.get_inplace_scratch_len()];
        f.process_with_scratch(data, &mut scratch);
        transpose(data, self.n);
        f.process_with_scratch(data, &mut scratch);
        transpose(data, self.n);
    }
}

/// Transposes the `n` x `n` row-major image in place, in tiles that stay in
/// cache.
fn transpose(data: &mut [Complex32], n: usize) {
    const TILE: usize = 32;
    for bi in (0..n).step_by(TILE) {
        for bj in (bi..n).step_by(TILE) {
            for i in bi..(bi + TILE).min(n) {
                for j in bj.max(i + 1)..(bj + TILE).min(n) {
                    data.swap(i * n + j, j * n + i);
                }
            }
        }
    }
}

fn raster(pts: &[[f64; 2]], origin: [f64; 2], cell: f64, n: usize, dilate: bool) -> Vec<Complex32> {
    let mut img = vec![Complex32::new(0.0, 0.0); n * n];
    let r: i64 = if dilate { 1 } else { 0 };
    for p in pts {
        let i = ((p[0] - origin[0]) / cell).floor() as i64;
        let j = ((p[1] - origin[1]) / cell).floor() as i64;
        for dj in -r..=r {
            for di in -r..=r {
                let (a, b) = (i + di, j + dj);
                if a >= 0 && b >= 0 && (a as usize) < n && (b as usize) < n {
                    img[b as usize * n + a as usize] = Complex32::new(1.0, 0.0);
                }
            }
        }
    }
    img
}

fn bbox2(pts: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in pts {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

fn rotate(pts: &[[f64; 2]], yaw: f64) -> Vec<[f64; 2]> {
    let (s, c) = yaw.sin_cos();
    pts.iter().map(|p| [c * p[0] - s * p[1], s * p[0] + c * p[1]]).collect()
}

/// The most cells a side of the coarse and of the fine correlation images
/// may have. The images cover the target's plan and the source's reach
/// around it, so a few far returns (a distant building, a long-range
/// scanner) widen them: at 0.4 m cells a 4 km plan would be 10,000 cells a
/// side, 800 MB an image and minutes a transform. Past these sides the cell
/// grows instead (a coarser first guess, which ICP refines as it does any).
const COARSE_SIDE: usize = 1024;
const FINE_SIDE: usize = 2048;

/// Size and origin shared by both images at one resolution: cells of `cell`
/// metres, or larger where the plan needs more than `max_side` of them.
fn plan_for(target: &[[f64; 2]], source_radius: f64, cell: f64, max_side: usize, fft: &mut Option<Fft2>) -> Plan {
    let (lo, hi) = bbox2(target);
    let extent_m = (hi[0] - lo[0]).max(hi[1] - lo[1]) + 2.0 * source_radius;
    // Room for the rounding below: 4 cells of margin and up to 15 to a
    // multiple of 16.
    let cell = cell.max(extent_m / (max_side - 20) as f64);
    let w = extent_m / cell;
    let n = ((w.ceil() as usize + 4).div_ceil(16)) * 16;
    let f = Fft2::new(n);
    let mut spec = raster(target, lo, cell, n, true);
    f.run(&mut spec, false);
    *fft = Some(f);
    Plan { n, origin: lo, cell, spectrum: spec }
}

/// The `k` strongest correlation peaks (shift in metres, source to target, and
/// overlap in cells) for one yaw, at least 3 cells apart.
fn correlate(plan: &Plan, f: &Fft2, src: &[[f64; 2]], k: usize) -> Vec<([f64; 2], f32)> {
    let n = plan.n;
    let (slo, _) = bbox2(src);
    let mut s = raster(src, slo, plan.cell, n, false);
    f.run(&mut s, false);
    for (a, b) in s.iter_mut().zip(&plan.spectrum) {
        *a = b * a.conj();
    }
    f.run(&mut s, true);
    let norm = (n * n) as f32;
    let mut peaks: Vec<(usize, f32)> = Vec::with_capacity(k + 1);
    for (i, v) in s.iter().enumerate() {
        let v = v.re / norm;
        if peaks.len() == k && v <= peaks[k - 1].1 {
            continue;
        }
        let (x, y) = ((i % n) as i64, (i / n) as i64);
        let near = |j: usize| {
            let (a, b) = ((j % n) as i64, (j / n) as i64);
            let dx = (x - a).rem_euclid(n as i64).min((a - x).rem_euclid(n as i64));
            let dy = (y - b).rem_euclid(n as i64).min((b - y).rem_euclid(n as i64));
            dx <= 3 && dy <= 3
        };
        if let Some(p) = peaks.iter().position(|p| near(p.0)) {
            if v > peaks[p].1 {
                peaks[p] = (i, v);
            } else {
                continue;
            }
        } else {
            peaks.push((i, v));
        }
        peaks.sort_by(|a, b| b.1.total_cmp(&a.1));
        peaks.truncate(k);
    }
    peaks
        .into_iter()
        .map(|(i, v)| {
            let (mut tx, mut ty) = ((i % n) as i64, (i / n) as i64);
            if tx > n as i64 / 2 {
                tx -= n as i64;
            }
            if ty > n as i64 / 2 {
                ty -= n as i64;
            }
            ([plan.origin[0] - slo[0] + tx as f64 * plan.cell, plan.origin[1] - slo[1] + ty as f64 * plan.cell], v)
        })
        .collect()
}

/// Candidate poses (source frame to target frame), best first, with their
/// correlation scores. `source` and `target` are levelled clouds with normals.
pub fn align(source: &RegCloud, target: &RegCloud, max_points: usize) -> Vec<(Pose, f32)> {
    align_within(source, target, max_points, COARSE_SIDE, FINE_SIDE)
}

/// [`align`] with images of at most `coarse_side` and `fine_side` cells a
/// side.
fn align_within(
    source: &RegCloud,
    target: &RegCloud,
    max_points: usize,
    coarse_side: usize,
    fine_side: usize,
) -> Vec<(Pose, f32)> {
    let src = vertical_structure(source, max_points);
    let tgt = vertical_structure(target, max_points);
    if src.len() < 50 || tgt.len() < 50 {
        return vec![];
    }
    // Centre the source on its own centroid so rotation keeps it compact.
    let c = src.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
    let c = [c[0] / src.len() as f64, c[1] / src.len() as f64];
    let src_c: Vec<[f64; 2]> = src.iter().map(|p| [p[0] - c[0], p[1] - c[1]]).collect();
    let r_c = src_c.iter().map(|p| (p[0] * p[0] + p[1] * p[1]).sqrt()).fold(0.0, f64::max);

    let mut f1 = None;
    let coarse = plan_for(&tgt, r_c, 1.0, coarse_side, &mut f1);
    let f1 = f1.unwrap_or_else(|| Fft2::new(coarse.n));
    let yaws: Vec<f64> = (0..180).map(|k| (k as f64 * 2.0).to_radians()).collect();
    let scored: Vec<(f64, [f64; 2], f32)> = yaws
        .par_iter()
        .map(|&y| {
            let best = correlate(&coarse, &f1, &rotate(&src_c, y), 1);
            let (t, s) = best.first().copied().unwrap_or(([0.0; 2], 0.0));
            (y, t, s)
        })
        .collect();
    // Local maxima over yaw, best first.
    let mut peaks: Vec<&(f64, [f64; 2], f32)> = (0..scored.len())
        .filter(|&k| {
            let prev = scored[(k + scored.len() - 1) % scored.len()].2;
            let next = scored[(k + 1) % scored.len()].2;
            scored[k].2 >= prev && scored[k].2 >= next
        })
        .map(|k| &scored[k])
        .collect();
    peaks.sort_by(|a, b| b.2.total_cmp(&a.2));
    peaks.truncate(6);

    let mut f2 = None;
    let fine = plan_for(&tgt, r_c, 0.4, fine_side, &mut f2);
    let f2 = f2.unwrap_or_else(|| Fft2::new(fine.n));
    let lowest = LowestPerCell::of(target);
    let mut out: Vec<(Pose, f32)> = peaks
        .par_iter()
        .flat_map_iter(|p| {
            // Best yaw near the peak, then several shifts at that yaw: periodic
            // structures (rack bays) give several plausible shifts, which the
            // caller tells apart in 3D.
            // Each yaw's five peaks are kept: the best yaw's are the shifts
            // (the first peak is the image's highest, whatever the count).
            let mut best = (p.0, f32::NEG_INFINITY, Vec::new());
            for k in -3..=3 {
                let y = p.0 + (k as f64 * 0.5).to_radians();
                let peaks = correlate(&fine, &f2, &rotate(&src_c, y), 5);
                let s = peaks.first().map(|x| x.1).unwrap_or(0.0);
                if s > best.1 {
                    best = (y, s, peaks);
                }
            }
            let (yaw, _, shifts) = best;
            let rot = na::UnitQuaternion::from_axis_angle(&Vec3::z_axis(), yaw);
            let rc = rot * Vec3::new(c[0], c[1], 0.0);
            shifts
                .into_iter()
                .map(move |(shift, score)| {
                    // First subtract the centroid, rotate, then shift.
                    let t = Vec3::new(shift[0] - rc.x, shift[1] - rc.y, 0.0);
                    (Pose::from_parts(na::Translation3::from(t), rot), score)
                })
                .collect::<Vec<_>>()
        })
        .map(|(p, sc)| (with_height(source, &lowest, p), sc))
        .collect();
    out.sort_by(|a, b| b.1.total_cmp(&a.1));
    out
}

/// Plan cells (m) over which [`with_height`] compares the lowest points.
const HEIGHT_CELL_M: f64 = 1.0;

fn height_cell(x: f64, y: f64) -> (i64, i64) {
    ((x / HEIGHT_CELL_M).floor() as i64, (y / HEIGHT_CELL_M).floor() as i64)
}

/// The target's lowest point per plan cell, worked out once for all the
/// guesses of an alignment (each guess used to hash the whole target again).
struct LowestPerCell {
    index: rustc_hash::FxHashMap<(i64, i64), u32>,
    low: Vec<f64>,
}

impl LowestPerCell {
    fn of(target: &RegCloud) -> LowestPerCell {
        let mut index: rustc_hash::FxHashMap<(i64, i64), u32> = rustc_hash::FxHashMap::default();
        let mut low: Vec<f64> = Vec::new();
        for p in &target.pts {
            let next = low.len() as u32;
            let i = *index.entry(height_cell(p[0], p[1])).or_insert(next) as usize;
            if i == low.len() {
                low.push(f64::INFINITY);
            }
            low[i] = low[i].min(p[2]);
        }
        LowestPerCell { index, low }
    }
}

/// Adds the vertical offset: the median, over plan cells both scans see, of the
/// difference between their lowest points.
fn with_height(source: &RegCloud, target: &LowestPerCell, pose: Pose) -> Pose {
    // Only the cells the target has count, so the source's lowest is kept
    // for those alone, by the target's index.
    let mut slow: Vec<Option<f64>> = vec![None; target.low.len()];
    for p in &source.pts {
        let q = pose * na::Point3::new(p[0], p[1], p[2]);
        if let Some(&i) = target.index.get(&height_cell(q.x, q.y)) {
            let e = &mut slow[i as usize];
            *e = Some(e.unwrap_or(f64::INFINITY).min(q.z));
        }
    }
    let mut d: Vec<f64> = slow.iter().zip(&target.low).filter_map(|(z, t)| Some(t - (*z)?)).collect();
    if d.is_empty() {
        return pose;
    }
    d.sort_by(f64::total_cmp);
    let dz = d[d.len() / 2];
    Pose::from_parts(
        na::Translation3::new(pose.translation.x, pose.translation.y, pose.translation.z + dz),
        pose.rotation,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 2-D transform is each row's then each column's 1-D transform,
    /// value for value, at sides that fill the transpose's tiles and that
    /// do not.
    #[test]
    fn the_image_transform_is_the_rows_then_the_columns() {
        for n in [1, 5, 32, 48, 80] {
            let f = Fft2::new(n);
            let image: Vec<Complex32> =
                (0..n * n).map(|k| Complex32::new(((k * 7919) % 13) as f32 - 6.0, ((k * 31) % 5) as f32)).collect();
            for inverse in [false, true] {
                let mut want = image.clone();
                let one = if inverse { &f.inv } else { &f.fwd };
                for row in want.chunks_mut(n) {
                    one.process(row);
                }
                for x in 0..n {
                    let mut col: Vec<Complex32> = (0..n).map(|y| want[y * n + x]).collect();
                    one.process(&mut col);
                    for (y, v) in col.into_iter().enumerate() {
                        want[y * n + x] = v;
                    }
                }
                let mut got = image.clone();
                f.run(&mut got, inverse);
                let bits = |v: &[Complex32]| v.iter().map(|c| (c.re.to_bits(), c.im.to_bits())).collect::<Vec<_>>();
                assert_eq!(bits(&got), bits(&want), "side {n}, inverse {inverse}");
            }
        }
    }

    /// Walls of a few buildings (points with level normals), 5 m tall, on an
    /// 80 m plot, and, if `far_m` is given, one more wall that far away.
    fn walls(far_m: Option<f64>) -> RegCloud {
        let mut c = RegCloud::default();
        let mut wall = |a: [f64; 2], b: [f64; 2]| {
            let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            let normal = [(b[1] - a[1]) / len, (a[0] - b[0]) / len, 0.0];
            for k in 0..(len / 0.25) as usize {
                let t = k as f64 * 0.25 / len;
                for h in 0..5 {
                    c.pts.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), h as f64]);
                    c.normals.push(normal);
                }
            }
        };
        for &(x, y, w, d) in
            &[(0.0, 0.0, 20.0, 12.0), (30.0, 5.0, 8.0, 30.0), (10.0, 40.0, 35.0, 9.0), (55.0, 60.0, 20.0, 20.0)]
        {
            wall([x, y], [x + w, y]);
            wall([x + w, y], [x + w, y + d]);
            wall([x + w, y + d], [x, y + d]);
            wall([x, y + d], [x, y]);
        }
        if let Some(far) = far_m {
            wall([far, 0.0], [far, 30.0]);
        }
        c
    }

    /// The source: the same site seen from a scanner turned by `yaw` and
    /// moved, in its own frame.
    fn seen_from(site: &RegCloud, pose: &Pose) -> RegCloud {
        let inv = pose.inverse();
        let moved = |p: &[f64; 3]| {
            let q = inv * na::Point3::new(p[0], p[1], p[2]);
            [q.x, q.y, q.z]
        };
        let turned = |n: &[f64; 3]| {
            let m = inv.rotation * Vec3::new(n[0], n[1], n[2]);
            [m.x, m.y, m.z]
        };
        RegCloud { pts: site.pts.iter().map(moved).collect(), normals: site.normals.iter().map(turned).collect() }
    }

    /// The fine stage takes a yaw's score from its five strongest peaks:
    /// the first of them is the image's highest, as the one peak asked for
    /// alone is, at every yaw tried.
    #[test]
    fn the_first_of_five_peaks_is_the_highest() {
        let site = walls(None);
        let tgt = vertical_structure(&site, 30_000);
        let src: Vec<[f64; 2]> = tgt.iter().filter(|p| p[0] < 40.0).map(|p| [p[0] - 3.0, p[1] + 2.0]).collect();
        let mut f = None;
        let plan = plan_for(&tgt, 40.0, 0.4, FINE_SIDE, &mut f);
        let f = f.unwrap();
        for k in -6..=6 {
            let turned = rotate(&src, (k as f64 * 0.5).to_radians());
            let one = correlate(&plan, &f, &turned, 1);
            let five = correlate(&plan, &f, &turned, 5);
            assert_eq!(one.len(), 1);
            assert!(five.len() > 1, "yaw step {k}: {five:?}");
            assert_eq!(five[0].1.to_bits(), one[0].1.to_bits(), "yaw step {k}");
            assert!(five.windows(2).all(|w| w[0].1 >= w[1].1), "yaw step {k}: {five:?}");
        }
    }

    /// A wall 800 m away widens the plan past the images' sides: the cells
    /// grow (here about 4 and 2 m) instead of the images, and the first guess
    /// still lands within a few cells of the true pose.
    #[test]
    fn a_far_wall_grows_the_cells_not_the_images() {
        let truth = Pose::from_parts(
            na::Translation3::new(6.0, -4.0, 0.0),
            na::UnitQuaternion::from_axis_angle(&Vec3::z_axis(), 30f64.to_radians()),
        );
        let site = walls(None);
        let target = walls(Some(800.0));
        let source = seen_from(&site, &truth);
        let tgt = vertical_structure(&target, 30_000);
        let plan = plan_for(&tgt, 60.0, 0.4, 256, &mut None);
        assert!(plan.n <= 256 && plan.cell > 3.0, "{} cells of {} m", plan.n, plan.cell);
        let poses = align_within(&source, &target, 30_000, 256, 512);
        let (best, _) = poses.first().expect("a pose");
        let miss = (best.translation.vector - truth.translation.vector).xy().norm();
        let turn = best.rotation.angle_to(&truth.rotation).to_degrees();
        assert!(miss < 5.0 && turn < 2.0, "{miss} m and {turn} deg off");
    }
}
