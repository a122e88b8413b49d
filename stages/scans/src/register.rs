//! Registration of N scans into one frame.
//!
//! 1. **Initial guess**: a pose the file carries (E57) or the station file, else
//!    none.
//! 2. **Coarse, pose-free**: terrestrial scanners level themselves (dual-axis
//!    compensators), so by default (`leveled = true`) two scans differ by a yaw and
//!    a translation, found by correlating plan views of their vertical structure
//!    ([`crate::coarse2d`]). For scans that are not levelled (`leveled = false`):
//!    each scan, and the model, is levelled by the direction its walls, columns
//!    and tanks are square to (else by its ground), and the plan views compared
//!    as above; FPFH descriptors on a thinned copy, mutual nearest neighbours in
//!    descriptor space, and RANSAC over 3-point Kabsch hypotheses with an
//!    edge-length check, add their candidates (alone, they placed none of the
//!    demo's scans). The reference scan is levelled the same way: it fixes the
//!    site frame.
//! 3. **Fine**: robust (Huber) point-to-plane ICP, coarse-to-fine correspondence
//!    distances, full 6 DOF.
//! 4. **Many scans**: the first scan is the reference. The others join the
//!    growing model greedily (scans held by a station first, then best fitness
//!    first), each aligned against the union of all scans placed so far; then
//!    all of them are aligned at once, each against all the others, the
//!    reference held where it is ([`align_all_as_one`]), so errors do not
//!    chain from scan to scan (aligned one at a time, scans placed off
//!    together stayed off). That last alignment is a small correction where
//!    the scans agree: one that moves a scan's points more than
//!    [`REFINED_MOVE_WARN_M`] merges it with a warning, more than
//!    [`LOOSE_HOLD_SLIDE_M`] does not merge it ([`refined_move_said`]).
//!
//! **Stations**: a scan with a surveyed station pose ([`RegInput::held`]) is
//! never placed outside its station's tolerance ([`StationTolerance`]): a
//! plan-view guess that fits the other scans better does not override a
//! survey (a van beside the reference once placed a scan 7.7 m and 61 degrees
//! from its station that way). Such a scan is reported not registered instead.
//! Where no scan fits those placed so far well enough to be placed (a van
//! beside the reference leaves the others too little of its view), a held
//! scan that puts no more than `max_violation` of its points where a placed
//! scanner saw through is placed at its station as surveyed, so that the
//! others can be placed against it. It is merged only if the scans placed
//! before it (the reference first), aligned as one with it and the scans
//! placed after it, stay where they are ([`SURVEY_AGREEMENT_M`],
//! [`SURVEY_AGREEMENT_DEG`]): otherwise their place relative to the
//! reference rests on the survey alone, and a survey 0.3 m off put them all
//! 0.3 m off. Each scan placed by its survey is checked so, in the order
//! placed. It must also, aligned with all the scans, overlap them by
//! `min_fitness` and stay within its tolerance. If it is not merged,
//! neither are the scans placed after it.
//!
//! A scan whose best alignment overlaps the model less than `min_fitness` is
//! reported as not registered; the stage never merges it silently.
//!
//! **Seen-through space**: an alignment may not put more than `max_violation`
//! of a scan's points where a placed scanner looked straight through
//! ([`free_space_violations`]); wrong alignments of repetitive plant fail
//! there. A scanner's steps far off pass both sides of a post or a wire
//! another scanner sees, and each such scanner adds to the share a right
//! alignment is refused for (24 stations refuse one): an alignment that
//! overlaps the others by [`NARROW_LEAST_FIT`] or more may still be placed
//! where no more than `max_violation` of its points lie where one of those
//! scanners' rays passed within half the width of what the point lies on
//! ([`half_widths_m`]), and says so; or where no more than that share lie so
//! beyond [`NEAR_SCANNER_M`] of its own scanner (a person or a van beside the
//! scanner, there for that scan alone, fills a large share of its points),
//! and says so. The first rounds check a scan against one
//! or two others, where a wrong pose's evidence is thin, so once every scan
//! is placed each is checked again against all the others
//! ([`FINAL_VIOLATION_FACTOR`]): a scan that disagrees with them is not
//! merged (unless it overlaps them by [`NARROW_LEAST_FIT`] and no more than
//! `max_violation` of its points lie so beyond [`NEAR_SCANNER_M`] of its
//! scanner, any ray counting: merged with a warning), and if the reference
//! disagrees, none of the scans placed against it is. The reference is also placed
//! again against all the others, as a trial places a scan but with what
//! stands beside its scanner left out of its plan view: if it fits them
//! clearly better elsewhere ([`REFERENCE_ELSEWHERE_MARGIN`]), they were
//! placed against a partial view of it (a van beside it), and none of them
//! is merged either. Neither check moves a scan; both only refuse.
//!
//! **Order**: placed one after another, the scan placed first of two that
//! cannot both be right is the one kept. Where no scan can be placed and a
//! scan's alignment passes but for one placed scan (not the reference, nor
//! one held by its station), that scan is taken out, with the scans placed
//! after it, and placed again once no other scan can be; each scan is
//! taken out once at most. Then: where the scan taken out cannot be placed
//! again, none of the scans placed while it was out (the other among them)
//! is merged; where it was placed again elsewhere
//! ([`ELSEWHERE_M`], [`ELSEWHERE_DEG`]), the others do not pin it down and
//! it is not merged (a van beside a scanner left its scan a view of the far
//! side of a tank and the rack, which fitted the two scans placed first 30
//! m off); where it was placed again where it was, and still stands in the
//! other's way, neither is merged (where the other could not be placed
//! even without it, the two stay as before).
//!
//! **Two places**: a scan whose trial passes at two places elsewhere from
//! each other, the second nearly as good ([`AMBIGUOUS_FIT_SHARE`]), is not
//! pinned down by the scans placed so far (like tanks in a row, like bays of
//! a rack, each scan seeing one or two): it waits while a scan they pin
//! down can be placed, as more scans may then rule one place out, and if it
//! still fits at two places when none can, it is not merged.
//!
//! **Loose hold**: ground overlaps under any plan move, and a scan whose
//! walls, columns and tanks share with the others only what turns or
//! slides onto itself (one tank's side, parallel walls) is held by them no
//! better: ICP drifts along that way. A scan whose alignment moves more
//! than [`LOOSE_HOLD_SLIDE_M`] its weakest way before its shared structure
//! lies 1 cm RMS further off ([`plan_hold`]) is not pinned down either: it
//! waits as above, and is not merged if it is still held so when no other
//! scan can be placed. A station pins that way down only where its
//! tolerance lets the scan lie no farther off it than that
//! ([`PlanHold::within_station_m`]): ICP, which holds nothing that way,
//! leaves a held scan where its station puts it, so with the default 0.5 m
//! a scan in a corridor whose station was 0.3 m off along it was merged
//! 0.3 m wrong with no word. A held scan so pinned waits too, but is
//! placed before the scans nothing pins down, with a warning that its place
//! that way is its station's. Of one scan's
//! alignments, a firmly held one ranks above a loosely held one that
//! scores higher (the first scan placed against a reference a van stood
//! beside fitted it 61 degrees turned, loosely, and where it stood,
//! firmly); a held scan held loosely ranks with the scans without a
//! station.
//!
//! Every reduction is summed in fixed-size blocks in a fixed order, so the result
//! does not depend on the number of threads.

use crate::features::{FPFH_BINS, Fpfh};
use crate::memo::{Key, Memo};
use liftplan_core::artifact::{ByteReader, ByteWriter};
use liftplan_core::frame::{Pose, Vec3};
use liftplan_core::rng;
use nalgebra as na;
use rayon::prelude::*;

/// A scan thinned for registration, in its own frame.
#[derive(Debug, Clone, Default)]
pub struct RegCloud {
    pub pts: Vec<[f64; 3]>,
    pub normals: Vec<[f64; 3]>,
}

/// A coarser copy with descriptors for pose-free alignment.
#[derive(Debug, Clone, Default)]
pub struct FeatureCloud {
    pub pts: Vec<[f64; 3]>,
    pub fpfh: Vec<Fpfh>,
}

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RegistrationSettings {
    /// Voxel of the copy ICP aligns (m).
    pub icp_voxel_m: f64,
    /// Voxel of the copy descriptors are computed on (m).
    pub feature_voxel_m: f64,
    /// Descriptor radius (m).
    pub feature_radius_m: f64,
    /// Most source points ICP uses per iteration.
    pub icp_source_points: usize,
    /// Correspondence distances of the coarse-to-fine ICP schedule (m).
    pub icp_distances_m: Vec<f64>,
    /// A point overlaps the model when its nearest model point is within
    /// `fit_distance_m` and its distance to that point's plane within
    /// `fit_residual_m`.
    pub fit_distance_m: f64,
    pub fit_residual_m: f64,
    /// Overlap below which a scan counts as not registered (0..1).
    pub min_fitness: f64,
    /// Largest share of a scan's points allowed where another scanner looked
    /// straight through (0..1); wrong alignments of repetitive plant fail here.
    pub max_violation: f64,
    /// Scanners levelled themselves (a dual-axis compensator): two scans
    /// differ by a yaw and a shift. Where not (`false`), each scan is
    /// levelled by its walls and tanks, or its ground, before the plan-view
    /// guesses (FPFH feature matches are tried too), ICP is 6-DOF either
    /// way, and the reference is levelled so, since it fixes the site frame
    /// whose z the later stages take for up.
    pub leveled: bool,
    pub ransac_iterations: usize,
}

impl Default for RegistrationSettings {
    fn default() -> Self {
        RegistrationSettings {
            icp_voxel_m: 0.05,
            feature_voxel_m: 0.3,
            feature_radius_m: 1.5,
            icp_source_points: 60_000,
            icp_distances_m: vec![1.0, 0.5, 0.25, 0.1],
            fit_distance_m: 0.25,
            fit_residual_m: 0.03,
            min_fitness: 0.02,
            max_violation: 0.005,
            leveled: true,
            ransac_iterations: 20_000,
        }
    }
}

impl RegistrationSettings {
    pub fn check(&self) -> Result<(), String> {
        let pos = |n: &str, v: f64| {
            if v.is_finite() && v > 0.0 { Ok(()) } else { Err(format!("registration.{n} must be positive, found {v}")) }
        };
        pos("icp_voxel_m", self.icp_voxel_m)?;
        pos("feature_voxel_m", self.feature_voxel_m)?;
        pos("feature_radius_m", self.feature_radius_m)?;
        pos("fit_residual_m", self.fit_residual_m)?;
        pos("fit_distance_m", self.fit_distance_m)?;
        if self.icp_distances_m.is_empty() || self.icp_distances_m.iter().any(|d| !(d.is_finite() && *d > 0.0)) {
            return Err("registration.icp_distances_m must be a non-empty list of positive distances".into());
        }
        if !(0.0..=1.0).contains(&self.max_violation) {
            return Err(format!("registration.max_violation must be in 0..1, found {}", self.max_violation));
        }
        if !(0.0..=1.0).contains(&self.min_fitness) {
            return Err(format!("registration.min_fitness must be in 0..1, found {}", self.min_fitness));
        }
        if self.icp_source_points < 100 || self.ransac_iterations == 0 {
            return Err("registration.icp_source_points must be >= 100 and ransac_iterations >= 1".into());
        }
        Ok(())
    }
}

/// How one scan was placed.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RegResult {
    #[serde(serialize_with = "ser_pose")]
    pub pose: Pose,
    /// Share of the scan's points with a model point within the fitness distance.
    pub fitness: f64,
    /// Point-to-plane RMS distance of those points (m).
    pub rmse_m: f64,
    pub method: String,
    pub registered: bool,
    pub warning: Option<String>,
    /// How far (m) its alignment, as tried against the scans placed before
    /// it, moves in plan its weakest way before what they share lies 1 cm
    /// RMS further off ([`PlanHold::slide_per_cm_m`]; over
    /// [`LOOSE_HOLD_SLIDE_M`] a scan is not merged, but where its station's
    /// tolerance pins that way down ([`PlanHold::within_station_m`])). None
    /// for the reference, a scan placed at its station as surveyed, and one
    /// never placed; kept for a scan placed and refused by a later check.
    pub hold_m: Option<f64>,
    /// How far (m) its last alignment, against all the other scans, moved
    /// its points from where the scans placed before it put them (the most
    /// over its points; [`REFINED_MOVE_WARN_M`]). None for the reference, a
    /// scan placed at its station as surveyed, and one never placed.
    pub refined_move_m: Option<f64>,
}

impl RegResult {
    /// Adds `warning` to what the scan is merged with (after any it has,
    /// joined by "; ").
    fn warn_also(&mut self, warning: String) {
        self.warning = Some(match self.warning.take() {
            Some(before) => format!("{before}; {warning}"),
            None => warning,
        });
    }
}

fn ser_pose<S: serde::Serializer>(p: &Pose, s: S) -> Result<S::Ok, S::Error> {
    use serde::Serialize;
    liftplan_core::frame::pose_to_rows(p).serialize(s)
}

#[inline]
fn tf(p: &Pose, x: &[f64; 3]) -> [f64; 3] {
    let q = p * na::Point3::new(x[0], x[1], x[2]);
    [q.x, q.y, q.z]
}

/// Mutual nearest neighbours in descriptor space, from at most `max_src` source
/// points chosen at a fixed stride.
pub fn match_features(src: &FeatureCloud, tgt: &FeatureCloud, max_src: usize) -> Vec<(usize, usize)> {
    let valid = |f: &Fpfh| f.iter().any(|v| *v != 0.0);
    let stride = (src.pts.len() / max_src.max(1)).max(1);
    let src_idx: Vec<usize> = (0..src.pts.len()).step_by(stride).filter(|&i| valid(&src.fpfh[i])).collect();
    let tgt_idx: Vec<usize> = (0..tgt.pts.len()).filter(|&i| valid(&tgt.fpfh[i])).collect();
    if src_idx.is_empty() || tgt_idx.is_empty() {
        return vec![];
    }
    let d2 = |a: &Fpfh, b: &Fpfh| -> f32 {
        let mut s = 0.0f32;
        for k in 0..FPFH_BINS {
            let d = a[k] - b[k];
            s += d * d;
        }
        s
    };
    let nearest = |q: &Fpfh, among: &[usize], set: &[Fpfh]| -> usize {
        let mut best = (f32::INFINITY, 0usize);
        for &j in among {
            let d = d2(q, &set[j]);
            if d < best.0 {
                best = (d, j);
            }
        }
        best.1
    };
    let fwd: Vec<usize> = src_idx.par_iter().map(|&i| nearest(&src.fpfh[i], &tgt_idx, &tgt.fpfh)).collect();
    // Reverse check only for the targets that were chosen.
    let mut chosen: Vec<usize> = fwd.clone();
    chosen.sort_unstable();
    chosen.dedup();
    let back: Vec<(usize, usize)> =
        chosen.par_iter().map(|&t| (t, nearest(&tgt.fpfh[t], &src_idx, &src.fpfh))).collect();
    let back_of = |t: usize| back.binary_search_by_key(&t, |x| x.0).ok().map(|k| back[k].1);
    src_idx.iter().zip(&fwd).filter(|(s, t)| back_of(**t) == Some(**s)).map(|(s, t)| (*s, *t)).collect()
}

/// Least-squares rigid transform taking `a` onto `b` (Kabsch), or a yaw-only
/// rotation when `leveled`.
pub fn fit_rigid(a: &[[f64; 3]], b: &[[f64; 3]], leveled: bool) -> Option<Pose> {
    let n = a.len();
    if n < 2 {
        return None;
    }
    let ca = a.iter().fold(Vec3::zeros(), |s, p| s + Vec3::new(p[0], p[1], p[2])) / n as f64;
    let cb = b.iter().fold(Vec3::zeros(), |s, p| s + Vec3::new(p[0], p[1], p[2])) / n as f64;
    let rot = if leveled {
        let (mut sxx, mut sxy) = (0.0, 0.0);
        for (p, q) in a.iter().zip(b) {
            let (ax, ay) = (p[0] - ca.x, p[1] - ca.y);
            let (bx, by) = (q[0] - cb.x, q[1] - cb.y);
            sxx += ax * bx + ay * by;
            sxy += ax * by - ay * bx;
        }
        na::UnitQuaternion::from_axis_angle(&Vec3::z_axis(), sxy.atan2(sxx))
    } else {
        if n < 3 {
            return None;
        }
        let mut h = na::Matrix3::zeros();
        for (p, q) in a.iter().zip(b) {
            h += (Vec3::new(p[0], p[1], p[2]) - ca) * (Vec3::new(q[0], q[1], q[2]) - cb).transpose();
        }
        let svd = h.svd(true, true);
        let (u, vt) = (svd.u?, svd.v_t?);
        let mut d = na::Matrix3::identity();
        if (vt.transpose() * u.transpose()).determinant() < 0.0 {
            d[(2, 2)] = -1.0;
        }
        let r = vt.transpose() * d * u.transpose();
        na::UnitQuaternion::from_matrix(&r)
    };
    let t = cb - rot * ca;
    Some(Pose::from_parts(na::Translation3::from(t), rot))
}

/// RANSAC over feature correspondences: the pose (source to target) with most
/// correspondences within `eps`, refined on its inliers, and the inlier count.
pub fn ransac(
    src: &[[f64; 3]],
    tgt: &[[f64; 3]],
    corr: &[(usize, usize)],
    leveled: bool,
    eps: f64,
    iterations: usize,
    seed: u64,
) -> Option<(Pose, usize)> {
    if corr.len() < 3 {
        return None;
    }
    let mut rng = rng::seeded(seed, "ransac");
    let count =
        |p: &Pose| corr.iter().filter(|(s, t)| super::grid::dist2(&tf(p, &src[*s]), &tgt[*t]) < eps * eps).count();
    let mut best: Option<(Pose, usize)> = None;
    // Hypotheses in fixed-size batches so results are independent of threads.
    let batch = 256;
    let mut done = 0;
    while done < iterations {
        let m = batch.min(iterations - done);
        let samples: Vec<[usize; 3]> = (0..m)
            .map(|_| {
                [rng::index(&mut rng, corr.len()), rng::index(&mut rng, corr.len()), rng::index(&mut rng, corr.len())]
            })
            .collect();
        let scored: Vec<Option<(Pose, usize)>> = samples
            .par_iter()
            .map(|s| {
                let k = if leveled { 2 } else { 3 };
                let ids = &s[..k];
                if ids.iter().enumerate().any(|(i, a)| ids[..i].contains(a)) {
                    return None;
                }
                let a: Vec<[f64; 3]> = ids.iter().map(|&i| src[corr[i].0]).collect();
                let b: Vec<[f64; 3]> = ids.iter().map(|&i| tgt[corr[i].1]).collect();
                // Consistency: rigid motions keep distances (and heights when levelled).
                for i in 0..k {
                    for j in (i + 1)..k {
                        let da = super::grid::dist2(&a[i], &a[j]).sqrt();
                        let db = super::grid::dist2(&b[i], &b[j]).sqrt();
                        if da < 2.0 * eps || (da - db).abs() > eps.max(0.1 * da) {
                            return None;
                        }
                        if leveled && ((a[i][2] - a[j][2]) - (b[i][2] - b[j][2])).abs() > eps {
                            return None;
                        }
                    }
                }
                let p = fit_rigid(&a, &b, leveled)?;
                Some((p, count(&p)))
            })
            .collect();
        for (p, c) in scored.into_iter().flatten() {
            if best.as_ref().is_none_or(|b| c > b.1) {
                best = Some((p, c));
            }
        }
        done += m;
    }
    let (p, _) = best?;
    let inl: Vec<(usize, usize)> =
        corr.iter().copied().filter(|(s, t)| super::grid::dist2(&tf(&p, &src[*s]), &tgt[*t]) < eps * eps).collect();
    let a: Vec<[f64; 3]> = inl.iter().map(|c| src[c.0]).collect();
    let b: Vec<[f64; 3]> = inl.iter().map(|c| tgt[c.1]).collect();
    let refined = fit_rigid(&a, &b, leveled).unwrap_or(p);
    let c = count(&refined);
    Some((refined, c))
}

/// The model ICP aligns against: points, normals and a k-d tree.
pub struct Target {
    pub pts: Vec<[f64; 3]>,
    pub normals: Vec<[f64; 3]>,
    grid: crate::kdtree::KdTree,
}

impl Target {
    pub fn new(pts: Vec<[f64; 3]>, normals: Vec<[f64; 3]>) -> Target {
        let grid = crate::kdtree::KdTree::new(&pts);
        Target { pts, normals, grid }
    }
}

const BLOCK: usize = 4096;

/// Robust point-to-plane ICP from `init`; returns the refined pose.
///
/// A pair counts only if the two normals agree (within about 45 degrees): the
/// front and back faces of a thin column or wall, seen from opposite sides, must
/// not be pulled together.
pub fn icp(src: &RegCloud, target: &Target, init: Pose, distances: &[f64]) -> Pose {
    let mut pose = init;
    // Each source point's nearest model point at the last step: the next
    // step's search starts from it (the same answer, found sooner).
    let mut last: Vec<u32> = vec![u32::MAX; src.pts.len()];
    for &d in distances {
        let grid = &target.grid;
        let huber = (d / 20.0).max(0.01);
        for _ in 0..50 {
            let m = pivot(src, &pose);
            let blocks: Vec<(na::Matrix6<f64>, na::Vector6<f64>, usize)> = last
                .par_chunks_mut(BLOCK)
                .enumerate()
                .map(|(b, last)| {
                    // Each pair's `w·j·jᵀ` and `w·r·j` summed in plain
                    // arrays, term for term as nalgebra forms them (the same
                    // bits), not a matrix built per pair.
                    let mut h = [[0.0f64; 6]; 6];
                    let mut g = [0.0f64; 6];
                    let mut n = 0;
                    for (k, last) in (b * BLOCK..).zip(last.iter_mut()) {
                        let p = tf(&pose, &src.pts[k]);
                        let hint = (*last != u32::MAX)
                            .then(|| (*last, crate::kdtree::distance2(&target.pts[*last as usize], &p)));
                        let Some((j, _)) = grid.nearest_from(&p, d, hint) else {
                            continue;
                        };
                        *last = j;
                        let nq = target.normals[j as usize];
                        if nq == [0.0; 3] || !compatible(&pose, &src.normals[k], &nq) {
                            continue;
                        }
                        let q = target.pts[j as usize];
                        let nv = Vec3::new(nq[0], nq[1], nq[2]);
                        let pv = Vec3::new(p[0], p[1], p[2]);
                        let r = (pv - Vec3::new(q[0], q[1], q[2])).dot(&nv);
                        let w = if r.abs() <= huber { 1.0 } else { huber / r.abs() };
                        let c = (pv - m).cross(&nv);
                        let jrow = [c.x, c.y, c.z, nv.x, nv.y, nv.z];
                        let (wj, wr) = (jrow.map(|v| w * v), w * r);
                        for i in 0..6 {
                            for k in 0..6 {
                                h[i][k] += wj[i] * jrow[k];
                            }
                            g[i] += wr * jrow[i];
                        }
                        n += 1;
                    }
                    (na::Matrix6::from_fn(|i, k| h[i][k]), na::Vector6::from(g), n)
                })
                .collect();
            let (mut h, mut g, mut n) = (na::Matrix6::zeros(), na::Vector6::zeros(), 0usize);
            for b in &blocks {
                h += b.0;
                g += b.1;
                n += b.2;
            }
            if n < 6 {
                break;
            }
            for i in 0..6 {
                h[(i, i)] += 1e-9 * (1.0 + h[(i, i)]);
            }
            let Some(x) = h.cholesky().map(|c| c.solve(&(-g))) else {
                break;
            };
            // The step turns about the pivot, then translates.
            let rot = na::UnitQuaternion::from_scaled_axis(Vec3::new(x[0], x[1], x[2]));
            let t = m - rot * m + Vec3::new(x[3], x[4], x[5]);
            let step = Pose::from_parts(na::Translation3::from(t), rot);
            pose = step * pose;
            if settled(&x, d) {
                break;
            }
        }
    }
    pose
}

/// The point of `src` at `pose` that an ICP step turns it about, rounded to
/// the metre. Rotations are linearised about a point of the scan where it
/// stands, not about the site's origin: with survey coordinates (a
/// northing of 5,000 km) a rotation about the origin is almost a
/// translation, and the normal equations lose the difference.
fn pivot(src: &RegCloud, pose: &Pose) -> Vec3 {
    match src.pts.first() {
        Some(p) => {
            let q = tf(pose, p);
            Vec3::new(q[0].round(), q[1].round(), q[2].round())
        }
        None => Vec3::zeros(),
    }
}

/// Whether an ICP step `x` (turn in radians about the pivot, then shift in
/// m) at correspondence distance `distance_m` ends the level: one that
/// moves under a 500th of the distance (0.2 mm at 0.1 m) and turns a point
/// 50 m off by no more. Measured: a third of the levels never came under
/// the tight limit that stood alone before (0.1 µrad, 1 µm), the
/// correspondences flipping back and forth at steps of a millimetre, and
/// spent 50 steps each, two thirds of all ICP steps (8 stations all round).
fn settled(x: &na::Vector6<f64>, distance_m: f64) -> bool {
    let (turn, shift) = (Vec3::new(x[0], x[1], x[2]).norm(), Vec3::new(x[3], x[4], x[5]).norm());
    let scale = distance_m / 0.1;
    (turn < 1e-7 && shift < 1e-6) || (turn < 4e-6 * scale && shift < 2e-4 * scale)
}

/// The sums one scan's points add to the normal equations of its pairs with
/// one other scan: the 12x12 matrix and the gradient over both scans' steps
/// (the scan's own six first), and how many pairs.
#[derive(Clone)]
struct PairSums {
    h: na::SMatrix<f64, 12, 12>,
    g: na::SVector<f64, 12>,
    pairs: usize,
}

/// Overlap and residual of a pose: the share of source points whose nearest
/// model point lies within `d` and whose distance to that point's plane is under
/// `max_residual`, and the RMS plane distance of those points. Measured along
/// normals, so it does not depend on how densely either scan sampled a surface.
pub fn evaluate(src: &RegCloud, target: &Target, pose: &Pose, d: f64, max_residual: f64) -> (f64, f64) {
    if src.pts.is_empty() {
        return (0.0, 0.0);
    }
    let blocks: Vec<(usize, f64)> = (0..src.pts.len().div_ceil(BLOCK))
        .into_par_iter()
        .map(|b| {
            let mut n = 0;
            let mut s2 = 0.0;
            for k in b * BLOCK..((b + 1) * BLOCK).min(src.pts.len()) {
                if let Some((_, _, r)) = overlapping(target, pose, &src.pts[k], &src.normals[k], d, max_residual) {
                    n += 1;
                    s2 += r * r;
                }
            }
            (n, s2)
        })
        .collect();
    let n: usize = blocks.iter().map(|b| b.0).sum();
    let s2: f64 = blocks.iter().map(|b| b.1).sum();
    (n as f64 / src.pts.len() as f64, if n > 0 { (s2 / n as f64).sqrt() } else { 0.0 })
}

/// How firmly an alignment's walls, columns and tanks hold it in plan,
/// where they overlap the model ([`plan_hold`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanHold {
    /// Structure pairs counted.
    pub pairs: usize,
    /// The mean square plane distance (m²) a move of one metre in plan
    /// gives those pairs, least over all moves.
    pub least: f64,
    /// The least's move: (turn, east, north), a turn in metres where the
    /// pairs lie.
    pub weakest: [f64; 3],
    /// The pairs' middle in plan (site frame, m), which the turn is about.
    pub middle: [f64; 2],
    /// Their RMS distance from it in plan (m), which scales the turn.
    pub spread_m: f64,
}

impl PlanHold {
    /// How far (m) the alignment moves in plan, its weakest way, before its
    /// shared structure lies 1 cm RMS off the model's (to first order):
    /// infinite where nothing holds it.
    pub fn slide_per_cm_m(&self) -> f64 {
        if self.least > 0.0 { 0.01 / self.least.sqrt() } else { f64::INFINITY }
    }

    /// How far (m) the alignment `pose` may lie from where it is, its
    /// weakest way, with its scanner (the scan frame's origin) within a
    /// station's `tolerance` of the surveyed `station`: a shift moves the
    /// scanner, and a turn about the pairs' middle moves it as well as
    /// turning it. Counted from where the scan is placed, either way, as
    /// far as the tolerance reaches that way: a scan placed 0.08 m off its
    /// station along the way, with 0.1 m surveyed, may lie 0.18 m off the
    /// other way, not 0.1 m. Infinite where the station does not bound
    /// that way (a turn about the scanner itself, with no yaw surveyed), or
    /// where the scan is placed outside the tolerance and no move that way
    /// brings it in.
    pub fn within_station_m(&self, pose: &Pose, station: &Pose, tolerance: &StationTolerance) -> f64 {
        let [turn, east, north] = self.weakest;
        let rad_per_m = turn / self.spread_m.max(1e-9);
        let (sx, sy) = (pose.translation.x - self.middle[0], pose.translation.y - self.middle[1]);
        // The scanner's move in plan per metre along the weakest way.
        let (dx, dy) = (east - rad_per_m * sy, north + rad_per_m * sx);
        // The moves `t` (m along the weakest way) that keep the scanner
        // within `plan_m` of its station: |o + t·d| <= plan_m, with `o`
        // where it stands off the station now.
        let (ox, oy) = (pose.translation.x - station.translation.x, pose.translation.y - station.translation.y);
        let (a, b, c) = (dx * dx + dy * dy, ox * dx + oy * dy, ox * ox + oy * oy - tolerance.plan_m * tolerance.plan_m);
        let unbounded = (f64::NEG_INFINITY, f64::INFINITY);
        let by_plan = if a > 0.0 {
            let disc = b * b - a * c;
            if disc < 0.0 {
                return f64::INFINITY;
            }
            let root = disc.sqrt();
            ((-b - root) / a, (-b + root) / a)
        } else if c <= 0.0 {
            unbounded
        } else {
            return f64::INFINITY;
        };
        // And its yaw within `yaw_deg` of the station's: |yaw + t·rad_per_m| <= limit.
        let by_yaw = match tolerance.yaw_deg {
            None => unbounded,
            Some(deg) => {
                let limit = deg.to_radians();
                let x = (station.rotation.inverse() * pose.rotation) * Vec3::x();
                let yaw = x.y.atan2(x.x);
                if rad_per_m != 0.0 {
                    let (t0, t1) = ((-limit - yaw) / rad_per_m, (limit - yaw) / rad_per_m);
                    (t0.min(t1), t0.max(t1))
                } else if yaw.abs() <= limit {
                    unbounded
                } else {
                    return f64::INFINITY;
                }
            }
        };
        let (lo, hi) = (by_plan.0.max(by_yaw.0), by_plan.1.min(by_yaw.1));
        if lo > hi {
            return f64::INFINITY;
        }
        lo.abs().max(hi.abs())
    }
}

/// How firmly the structure of `src` at `pose` holds it in plan against
/// the model: over the pairs of its points whose normal is not near
/// vertical (as [`structure`]) that overlap the model ([`evaluate`]'s
/// test, with the model point's normal not near vertical either), how a
/// plan move changes their plane distances. A move is a shift east and
/// north and a turn about the pairs' centroid, the turn scaled by their
/// RMS distance from it, so that its metres are metres where they lie.
///
/// Ground overlaps under any plan move, so it is left out: with it, the
/// weakest direction's share of the strongest did not tell a scan whose
/// overlap turns onto itself (one tank's side) from right placements
/// (reports/scans.md). A cylinder's side holds no turn about its axis (each
/// pair's change is then a fixed mix of its normal's east and north), two
/// parallel walls no slide along them: in both the least is near zero.
pub fn plan_hold(src: &RegCloud, target: &Target, pose: &Pose, d: f64, max_residual: f64) -> PlanHold {
    let near_vertical = |n: &[f64; 3]| *n == [0.0; 3] || n[2].abs() >= 0.9;
    let mut pairs: Vec<([f64; 3], [f64; 3])> = Vec::new();
    for (x, ns) in src.pts.iter().zip(&src.normals) {
        if near_vertical(ns) {
            continue;
        }
        let Some((p, j, _)) = overlapping(target, pose, x, ns, d, max_residual) else { continue };
        if !near_vertical(&target.normals[j]) {
            pairs.push((p, target.normals[j]));
        }
    }
    if pairs.len() < 3 {
        return PlanHold { pairs: pairs.len(), least: 0.0, weakest: [0.0, 1.0, 0.0], middle: [0.0; 2], spread_m: 0.0 };
    }
    let n = pairs.len() as f64;
    let (cx, cy) = pairs.iter().fold((0.0, 0.0), |(x, y), (p, _)| (x + p[0] / n, y + p[1] / n));
    let spread = (pairs.iter().map(|(p, _)| (p[0] - cx).powi(2) + (p[1] - cy).powi(2)).sum::<f64>() / n).sqrt();
    let mut h = na::Matrix3::<f64>::zeros();
    for (p, nq) in &pairs {
        let turn = ((p[0] - cx) * nq[1] - (p[1] - cy) * nq[0]) / spread.max(1e-9);
        let row = na::Vector3::new(turn, nq[0], nq[1]);
        h += row * row.transpose();
    }
    let e = na::SymmetricEigen::new(h / n);
    let lo = e.eigenvalues.imin();
    let v = e.eigenvectors.column(lo);
    PlanHold {
        pairs: pairs.len(),
        least: e.eigenvalues[lo].max(0.0),
        weakest: [v[0], v[1], v[2]],
        middle: [cx, cy],
        spread_m: spread,
    }
}

/// Where the source point `x` (normal `ns`) at `pose` overlaps the model,
/// as [`evaluate`] counts it: its nearest model point within `d`, normals
/// agreeing, and its distance to that point's plane (to the point, where
/// the model point has no normal) within `max_residual`. Gives the point
/// placed, the model point's index and that distance.
fn overlapping(
    target: &Target,
    pose: &Pose,
    x: &[f64; 3],
    ns: &[f64; 3],
    d: f64,
    max_residual: f64,
) -> Option<([f64; 3], usize, f64)> {
    let p = tf(pose, x);
    let (j, d2) = target.grid.nearest(&p, d)?;
    let j = j as usize;
    let nq = target.normals[j];
    if nq != [0.0; 3] && !compatible(pose, ns, &nq) {
        return None;
    }
    let q = target.pts[j];
    let r =
        if nq == [0.0; 3] { d2.sqrt() } else { (p[0] - q[0]) * nq[0] + (p[1] - q[1]) * nq[1] + (p[2] - q[2]) * nq[2] };
    (r.abs() <= max_residual).then_some((p, j, r))
}

/// Whether a source normal (rotated by `pose`) and a target normal agree.
#[inline]
fn compatible(pose: &Pose, ns: &[f64; 3], nt: &[f64; 3]) -> bool {
    if *ns == [0.0; 3] {
        return true;
    }
    let r = pose.rotation * Vec3::new(ns[0], ns[1], ns[2]);
    r.x * nt[0] + r.y * nt[1] + r.z * nt[2] > 0.7
}

/// One scan as registration sees it.
pub struct RegInput {
    pub name: String,
    pub fine: RegCloud,
    pub coarse: FeatureCloud,
    /// Pose the file or station file gives, if any.
    pub initial: Option<Pose>,
    /// Set when `initial` is a surveyed station pose the scan must be placed
    /// near. Honoured only when the reference (the first scan) has one too:
    /// only then are the scans placed in the station file's frame.
    pub held: Option<StationTolerance>,
}

/// How far registration may place a scan from its surveyed station pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StationTolerance {
    /// Largest distance in plan between the surveyed and the placed scanner (m).
    pub plan_m: f64,
    /// Largest height difference (m); `None` when the station gives no height.
    pub height_m: Option<f64>,
    /// Largest yaw difference (degrees); `None` when the station gives no yaw.
    pub yaw_deg: Option<f64>,
}

/// Where a placed scanner is relative to its surveyed station.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StationOffset {
    /// Distance in plan (m).
    pub plan_m: f64,
    /// Height difference (m, absolute).
    pub height_m: f64,
    /// Yaw difference (degrees, absolute, 0..180).
    pub yaw_deg: f64,
}

impl StationOffset {
    /// Whether the two poses are far enough apart to count as elsewhere
    /// ([`ELSEWHERE_M`], [`ELSEWHERE_DEG`]).
    fn is_elsewhere(&self) -> bool {
        self.plan_m.max(self.height_m) > ELSEWHERE_M || self.yaw_deg > ELSEWHERE_DEG
    }

    /// `placed` (scanner to site) against the surveyed `station` pose.
    pub fn between(station: &Pose, placed: &Pose) -> StationOffset {
        let d = placed.translation.vector - station.translation.vector;
        let x = (station.rotation.inverse() * placed.rotation) * Vec3::x();
        StationOffset { plan_m: d.x.hypot(d.y), height_m: d.z.abs(), yaw_deg: x.y.atan2(x.x).to_degrees().abs() }
    }

    pub fn within(&self, t: &StationTolerance) -> bool {
        self.plan_m <= t.plan_m
            && t.height_m.is_none_or(|h| self.height_m <= h)
            && t.yaw_deg.is_none_or(|y| self.yaw_deg <= y)
    }

    /// "7.7 m in plan, 0.0 m in height and 61.3 degrees" with the limits.
    fn describe(&self, t: &StationTolerance) -> String {
        let limit =
            |v: Option<f64>, unit: &str| v.map_or("not surveyed".to_string(), |v| format!("at most {v} {unit}"));
        format!(
            "{:.2} m in plan (at most {} m), {:.2} m in height ({}) and {:.1} degrees in yaw ({})",
            self.plan_m,
            t.plan_m,
            self.height_m,
            limit(t.height_m, "m"),
            self.yaw_deg,
            limit(t.yaw_deg, "degrees")
        )
    }
}

/// Whether a scan's own frame has the scanner at its origin (true for scans
/// exported in scanner coordinates, false for georeferenced exports): only then
/// can its points say where the scanner looked through.
fn scanner_at_origin(c: &RegCloud) -> bool {
    let b = liftplan_core::frame::Aabb::from_points(&c.pts);
    !b.is_empty()
        && b.min[0] < 0.0
        && b.max[0] > 0.0
        && b.min[1] < 0.0
        && b.max[1] > 0.0
        && b.min[2] < 0.0
        && b.max[2] > 0.0
}

fn subset(c: &RegCloud, idx: &[usize], max: usize) -> RegCloud {
    let stride = (idx.len() / max.max(1)).max(1);
    let pick: Vec<usize> = idx.iter().step_by(stride).copied().collect();
    RegCloud { pts: pick.iter().map(|&i| c.pts[i]).collect(), normals: pick.iter().map(|&i| c.normals[i]).collect() }
}

/// At most `max` points, spread evenly over normal directions (normal-space
/// sampling, Rusinkiewicz & Levoy 2001): the few walls and columns that pin a
/// scan along a long rack weigh as much as the acres of ground that only pin its
/// height. Points without a normal come last.
pub fn sample(c: &RegCloud, max: usize) -> RegCloud {
    let mut bins: Vec<Vec<usize>> = vec![Vec::new(); 12 * 5 + 1];
    for (i, n) in c.normals.iter().enumerate() {
        let b = if *n == [0.0; 3] {
            60
        } else {
            let az = n[1].atan2(n[0]).rem_euclid(std::f64::consts::TAU);
            let el = n[2].clamp(-1.0, 1.0).asin() + std::f64::consts::FRAC_PI_2;
            let ia = ((az / std::f64::consts::TAU * 12.0) as usize).min(11);
            let ie = ((el / std::f64::consts::PI * 5.0) as usize).min(4);
            ie * 12 + ia
        };
        bins[b].push(i);
    }
    let mut pick = Vec::with_capacity(max.min(c.pts.len()));
    let mut cursor = vec![0usize; bins.len()];
    // Within a bin, walk at a stride so picks spread over the scan.
    let strides: Vec<usize> = bins.iter().map(|b| (b.len() / (max / 60).max(1)).max(1)).collect();
    'fill: while pick.len() < max {
        let mut any = false;
        for b in 0..60 {
            let k = cursor[b];
            let len = bins[b].len();
            if k / strides[b] < len && k < len * strides[b] {
                let idx = (k * strides[b]) % len + (k * strides[b]) / len;
                if idx < len {
                    pick.push(bins[b][idx]);
                    any = true;
                    if pick.len() >= max {
                        break 'fill;
                    }
                }
                cursor[b] += 1;
            }
        }
        if !any {
            break;
        }
    }
    let mut k = 0;
    while pick.len() < max && k < bins[60].len() {
        pick.push(bins[60][k]);
        k += 1;
    }
    pick.sort_unstable();
    pick.dedup();
    RegCloud { pts: pick.iter().map(|&i| c.pts[i]).collect(), normals: pick.iter().map(|&i| c.normals[i]).collect() }
}

/// The points that pin a pose down: those whose normal is not near vertical.
/// Flat ground overlaps under any in-plane shift, so a fitness measured on all
/// points cannot tell a right alignment from a wrong one on a flat site.
pub fn structure(c: &RegCloud, max: usize) -> RegCloud {
    let idx: Vec<usize> =
        (0..c.pts.len()).filter(|&i| c.normals[i] != [0.0; 3] && c.normals[i][2].abs() < 0.9).collect();
    if idx.len() < 200 {
        return sample(c, max);
    }
    subset(c, &idx, max)
}

fn model_of(inputs: &[RegInput], poses: &[Option<Pose>], except: Option<usize>) -> Target {
    let placed = inputs
        .iter()
        .enumerate()
        .filter(|&(i, _)| Some(i) != except)
        .filter_map(|(i, inp)| Some((&inp.fine, poses[i]?)));
    let c = placed_cloud(placed);
    Target::new(c.pts, c.normals)
}

/// Clouds at their poses, as one cloud in the frame they are placed in.
fn placed_cloud<'a>(placed: impl Iterator<Item = (&'a RegCloud, Pose)>) -> RegCloud {
    let mut out = RegCloud::default();
    for (c, p) in placed {
        out.pts.extend(c.pts.iter().map(|x| tf(&p, x)));
        out.normals.extend(c.normals.iter().map(|n| {
            let v = p.rotation * Vec3::new(n[0], n[1], n[2]);
            [v.x, v.y, v.z]
        }));
    }
    out
}

/// The last alignment of the `placed` scans (indices into `inputs`, `srcs`
/// and `checks`, the reference not among them), all at once against each
/// other and the reference ([`align_all_as_one`]) from `poses` (updated):
/// (pose, fitness, RMSE) of each, in the order of `placed`.
fn refine(
    inputs: &[RegInput],
    srcs: &[RegCloud],
    checks: &[RegCloud],
    poses: &mut [Option<Pose>],
    placed: &[usize],
    s: &RegistrationSettings,
) -> Vec<(Pose, f64, f64)> {
    let fine = &s.icp_distances_m[s.icp_distances_m.len().saturating_sub(2)..];
    align_all_as_one(inputs, srcs, poses, placed, fine);
    placed
        .iter()
        .map(|&j| {
            let p = poses[j].unwrap_or_else(Pose::identity);
            let others = model_of(inputs, poses, Some(j));
            let (fit, rmse) = evaluate(&checks[j], &others, &p, s.fit_distance_m, s.fit_residual_m);
            (p, fit, rmse)
        })
        .collect()
}

/// Robust point-to-plane ICP of every scan at once: each of the `moving`
/// scans (indices into `inputs` and `srcs`, placed in `poses`; the
/// reference, index 0, is not among them and does not move) and the
/// reference are aligned against all the other placed scans, and each step
/// moves every moving scan by the one least-squares solution of all those
/// pairs together. Scans aligned one at a time against the others drift
/// back from a shared error only a fraction of it per pass: where two scans
/// placed against little overlap of the reference were 2 cm off and the
/// scans placed after them followed, one pass left 24 mm, twenty passes
/// 12 mm.
///
/// Each source point pairs with the nearest point of any other placed scan
/// (ties to the lower scan, then the lower point), as [`icp`] pairs it with
/// the nearest point of the other scans put together, and counts only
/// where the two normals agree. Each scan's tree is built once, in its own
/// frame; a point is taken into each scan's frame to search it. Where the
/// reference is not placed, nothing holds the frame and no scan is moved.
fn align_all_as_one(
    inputs: &[RegInput],
    srcs: &[RegCloud],
    poses: &mut [Option<Pose>],
    moving: &[usize],
    distances: &[f64],
) {
    // The scans in the alignment: the reference first (it holds the frame:
    // without it nothing is aligned), then the moving ones placed, their
    // unknowns in this order.
    if poses[0].is_none() {
        return;
    }
    let scans: Vec<usize> =
        std::iter::once(0).chain(moving.iter().copied().filter(|&j| j != 0 && poses[j].is_some())).collect();
    let unknowns = scans.len() - 1;
    if unknowns == 0 {
        return;
    }
    let trees: Vec<Target> =
        scans.iter().map(|&j| Target::new(inputs[j].fine.pts.clone(), inputs[j].fine.normals.clone())).collect();
    // Unknown block of scan `scans[a]` (None for the reference).
    let block = |a: usize| a.checked_sub(1);
    // Each source point's last pair (scan in `scans`, point): where the next
    // step's search starts.
    let mut last: Vec<Vec<(u32, u32)>> = scans.iter().map(|&j| vec![(u32::MAX, u32::MAX); srcs[j].pts.len()]).collect();
    let size = 6 * unknowns;
    for &d in distances {
        let huber = (d / 20.0).max(0.01);
        for _ in 0..50 {
            let at: Vec<Pose> = scans.iter().map(|&j| poses[j].unwrap_or_else(Pose::identity)).collect();
            let into: Vec<Pose> = at.iter().map(Pose::inverse).collect();
            let pivots: Vec<Vec3> = scans.iter().zip(&at).map(|(&j, p)| pivot(&srcs[j], p)).collect();
            let mut h = na::DMatrix::<f64>::zeros(size, size);
            let mut g = na::DVector::<f64>::zeros(size);
            let mut pairs = 0usize;
            for (a, last) in last.iter_mut().enumerate() {
                let src = &srcs[scans[a]];
                let ba = block(a);
                // Per block of points, the sums of their pairs with each scan.
                let zero = PairSums { h: na::SMatrix::zeros(), g: na::SVector::zeros(), pairs: 0 };
                let sums: Vec<Vec<PairSums>> = last
                    .par_chunks_mut(BLOCK)
                    .enumerate()
                    .map(|(c, last)| {
                        let mut with = vec![zero.clone(); scans.len()];
                        for (k, last) in (c * BLOCK..).zip(last.iter_mut()) {
                            let w = tf(&at[a], &src.pts[k]);
                            // (distance², scan, point) of the nearest point of the others.
                            let mut best: Option<(f64, usize, u32)> = None;
                            let mut radius = d;
                            let hinted = last.0 as usize;
                            let order = std::iter::once(hinted)
                                .filter(|&b| b < scans.len() && b != a)
                                .chain((0..scans.len()).filter(|&b| b != a && b != hinted));
                            for b in order {
                                let q = tf(&into[b], &w);
                                let hint = (b == hinted && last.1 != u32::MAX)
                                    .then(|| (last.1, crate::kdtree::distance2(&trees[b].pts[last.1 as usize], &q)));
                                let Some((i, d2)) = trees[b].grid.nearest_from(&q, radius, hint) else { continue };
                                if best.is_none_or(|(bd, bb, bi)| (d2, b, i) < (bd, bb, bi)) {
                                    best = Some((d2, b, i));
                                    radius = d2.sqrt();
                                }
                            }
                            let Some((_, b, i)) = best else { continue };
                            *last = (b as u32, i);
                            let nq = trees[b].normals[i as usize];
                            if nq == [0.0; 3] || !compatible(&(into[b] * at[a]), &src.normals[k], &nq) {
                                continue;
                            }
                            let q = tf(&at[b], &trees[b].pts[i as usize]);
                            let nv = at[b].rotation * Vec3::new(nq[0], nq[1], nq[2]);
                            let (pv, qv) = (Vec3::new(w[0], w[1], w[2]), Vec3::new(q[0], q[1], q[2]));
                            let r = (pv - qv).dot(&nv);
                            let wt = if r.abs() <= huber { 1.0 } else { huber / r.abs() };
                            let (ca, cb) = ((pv - pivots[a]).cross(&nv), (qv - pivots[b]).cross(&nv));
                            let row = na::SVector::<f64, 12>::from_column_slice(&[
                                ca.x, ca.y, ca.z, nv.x, nv.y, nv.z, -cb.x, -cb.y, -cb.z, -nv.x, -nv.y, -nv.z,
                            ]);
                            let e = &mut with[b];
                            e.h += wt * row * row.transpose();
                            e.g += wt * r * row;
                            e.pairs += 1;
                        }
                        with
                    })
                    .collect();
                for with in sums {
                    for (b, e) in with.iter().enumerate().filter(|(_, e)| e.pairs > 0) {
                        pairs += e.pairs;
                        // The two scans' rows and columns in the whole system.
                        let (ra, rb) = (ba.map(|x| 6 * x), block(b).map(|x| 6 * x));
                        for (u, ru) in [(0, ra), (6, rb)] {
                            let Some(ru) = ru else { continue };
                            for i in 0..6 {
                                g[ru + i] += e.g[u + i];
                            }
                            for (v, rv) in [(0, ra), (6, rb)] {
                                let Some(rv) = rv else { continue };
                                for i in 0..6 {
                                    for j in 0..6 {
                                        h[(ru + i, rv + j)] += e.h[(u + i, v + j)];
                                    }
                                }
                            }
                        }
                    }
                }
            }
            if pairs < size {
                return;
            }
            for i in 0..size {
                h[(i, i)] += 1e-9 * (1.0 + h[(i, i)]);
            }
            let Some(x) = h.cholesky().map(|c| c.solve(&(-g))) else {
                return;
            };
            let mut all_settled = true;
            for (a, &j) in scans.iter().enumerate() {
                let Some(u) = block(a) else { continue };
                let x: na::Vector6<f64> = x.fixed_rows::<6>(6 * u).into_owned();
                let rot = na::UnitQuaternion::from_scaled_axis(Vec3::new(x[0], x[1], x[2]));
                let t = pivots[a] - rot * pivots[a] + Vec3::new(x[3], x[4], x[5]);
                poses[j] = Some(Pose::from_parts(na::Translation3::from(t), rot) * at[a]);
                all_settled &= settled(&x, d);
            }
            if all_settled {
                break;
            }
        }
    }
}

/// Places every scan in the frame of the first; see the module docs.
pub fn register_all(inputs: &[RegInput], s: &RegistrationSettings, seed: u64) -> Vec<RegResult> {
    register_all_memo(inputs, s, seed, &mut Memo::new(""))
}

/// Reads back an answer kept in the memo.
fn answer(bytes: &[u8]) -> ByteReader<'_> {
    ByteReader::new(std::path::Path::new("registration memo"), bytes, 0)
}

/// Bits of a pose, in the order [`read_pose`] reads them back.
fn pose_numbers(p: &Pose) -> [f64; 7] {
    let (q, t) = (p.rotation.coords, p.translation.vector);
    [q[0], q[1], q[2], q[3], t.x, t.y, t.z]
}

fn hash_pose(h: &mut blake3::Hasher, p: &Pose) {
    for v in pose_numbers(p) {
        h.update(&v.to_bits().to_le_bytes());
    }
}

fn write_pose(w: &mut ByteWriter, p: &Pose) {
    for v in pose_numbers(p) {
        w.f64(v);
    }
}

/// The pose [`write_pose`] wrote, bit for bit (the quaternion is taken as
/// written, not normalised again).
fn read_pose(r: &mut ByteReader) -> Option<Pose> {
    let mut v = [0.0; 7];
    for x in &mut v {
        *x = r.f64().ok()?;
    }
    let q = na::UnitQuaternion::new_unchecked(na::Quaternion::from(na::Vector4::new(v[0], v[1], v[2], v[3])));
    Some(Pose::from_parts(na::Translation3::new(v[4], v[5], v[6]), q))
}

fn hash_points(h: &mut blake3::Hasher, pts: &[[f64; 3]]) {
    h.update(&(pts.len() as u64).to_le_bytes());
    for p in pts {
        for v in p {
            h.update(&v.to_bits().to_le_bytes());
        }
    }
}

/// Everything of a scan that registration reads.
fn scan_key(inp: &RegInput) -> Key {
    let mut h = blake3::Hasher::new();
    h.update(&(inp.name.len() as u64).to_le_bytes());
    h.update(inp.name.as_bytes());
    match &inp.initial {
        Some(p) => {
            h.update(&[1]);
            hash_pose(&mut h, p);
        }
        None => {
            h.update(&[0]);
        }
    }
    if let Some(t) = &inp.held {
        h.update(b"held");
        for v in [Some(t.plan_m), t.height_m, t.yaw_deg] {
            h.update(&v.map_or(u64::MAX, f64::to_bits).to_le_bytes());
        }
    }
    hash_points(&mut h, &inp.fine.pts);
    hash_points(&mut h, &inp.fine.normals);
    hash_points(&mut h, &inp.coarse.pts);
    h.update(&(inp.coarse.fpfh.len() as u64).to_le_bytes());
    for f in &inp.coarse.fpfh {
        for v in f {
            h.update(&v.to_bits().to_le_bytes());
        }
    }
    *h.finalize().as_bytes()
}

/// Placed scans' (pose, fitness, RMSE), as a placement or the refinement
/// keeps them.
fn encode_placed(placed: &[(Pose, f64, f64)]) -> Vec<u8> {
    let mut w = ByteWriter::new();
    for (p, fit, rmse) in placed {
        write_pose(&mut w, p);
        w.f64(*fit);
        w.f64(*rmse);
    }
    w.buf
}

/// What [`encode_placed`] wrote for `count` scans, if that is what `bytes` hold.
fn decode_placed(bytes: &[u8], count: usize) -> Option<Vec<(Pose, f64, f64)>> {
    let mut r = answer(bytes);
    let mut placed = Vec::with_capacity(count);
    for _ in 0..count {
        placed.push((read_pose(&mut r)?, r.f64().ok()?, r.f64().ok()?));
    }
    r.finish().is_ok().then_some(placed)
}

/// Reads `bytes` as each kind of answer the memo keeps: a trial, the
/// placement of `count` scans (one placed, or the refinement of them all),
/// the reference placed again; whether each read. For the fuzz target
/// `registration_memo`: an answer damaged inside a sound memo file must
/// read as nothing (worked out again), with no panic and no allocation its
/// bytes do not pay for.
#[doc(hidden)]
pub fn read_memo_answers(bytes: &[u8], count: usize) -> [bool; 3] {
    [Trial::decode(bytes).is_some(), decode_placed(bytes, count).is_some(), ReferenceAgain::decode(bytes).is_some()]
}

/// A trial of one scan in one round: what each candidate pose gave after ICP,
/// in the order they were tried.
struct Trial {
    /// (pose, fitness, violation, method) of the candidates that pass.
    passing: Vec<Passed>,
    /// The best (fitness, violation) of any candidate, passing or not.
    closest: (f64, f64),
    /// For a scan held by a station: (fitness, violation) of its station
    /// pose after ICP.
    at_station: Option<(f64, f64)>,
    /// The best-scoring candidate that passed but lies outside its station's
    /// tolerance: its (fitness, violation) and offset.
    held_back: Option<(f64, f64, StationOffset)>,
    /// The candidates that overlap enough and lie within their station's
    /// tolerance but put too many points where a placed scanner saw
    /// through: (pose, fitness).
    near_misses: Vec<(Pose, f64)>,
}

/// A candidate of a trial that passes.
#[derive(Debug, Clone)]
struct Passed {
    pose: Pose,
    fit: f64,
    viol: f64,
    method: String,
    /// How firmly what it shares with the scans placed holds it ([`plan_hold`]).
    hold: PlanHold,
}

impl Trial {
    fn encode(&self) -> Vec<u8> {
        let mut w = ByteWriter::new();
        w.f64(self.closest.0);
        w.f64(self.closest.1);
        w.u32(self.passing.len() as u32);
        for c in &self.passing {
            write_pose(&mut w, &c.pose);
            w.f64(c.fit);
            w.f64(c.viol);
            w.str(&c.method);
            w.u64(c.hold.pairs as u64);
            w.f64(c.hold.least);
            w.f64s(&c.hold.weakest);
            w.f64s(&c.hold.middle);
            w.f64(c.hold.spread_m);
        }
        w.f64s(&self.at_station.map_or(vec![], |(fit, viol)| vec![fit, viol]));
        w.f64s(&self.held_back.map_or(vec![], |(fit, viol, o)| vec![fit, viol, o.plan_m, o.height_m, o.yaw_deg]));
        w.u32(self.near_misses.len() as u32);
        for (p, fit) in &self.near_misses {
            write_pose(&mut w, p);
            w.f64(*fit);
        }
        w.buf
    }

    fn decode(bytes: &[u8]) -> Option<Trial> {
        let mut r = answer(bytes);
        let closest = (r.f64().ok()?, r.f64().ok()?);
        let n = r.u32().ok()?;
        let mut passing = Vec::new();
        for _ in 0..n {
            let (pose, fit, viol, method) = (read_pose(&mut r)?, r.f64().ok()?, r.f64().ok()?, r.str().ok()?);
            let hold = PlanHold {
                pairs: usize::try_from(r.u64().ok()?).ok()?,
                least: r.f64().ok()?,
                weakest: r.f64s().ok()?.try_into().ok()?,
                middle: r.f64s().ok()?.try_into().ok()?,
                spread_m: r.f64().ok()?,
            };
            passing.push(Passed { pose, fit, viol, method, hold });
        }
        let at_station = match r.f64s().ok()?.as_slice() {
            [] => None,
            &[fit, viol] => Some((fit, viol)),
            _ => return None,
        };
        let held_back = match r.f64s().ok()?.as_slice() {
            [] => None,
            &[fit, viol, plan_m, height_m, yaw_deg] => Some((fit, viol, StationOffset { plan_m, height_m, yaw_deg })),
            _ => return None,
        };
        let n = r.u32().ok()?;
        let mut near_misses = Vec::new();
        for _ in 0..n {
            near_misses.push((read_pose(&mut r)?, r.f64().ok()?));
        }
        r.finish().is_ok().then_some(Trial { passing, closest, at_station, held_back, near_misses })
    }
}

/// Two places a scan's trial passes at ([`AMBIGUOUS_FIT_SHARE`]): its best,
/// and the best of those elsewhere from it.
#[derive(Debug, Clone, Copy)]
struct TwoPlaces {
    /// The two overlaps (0..1), the best's first.
    fit: [f64; 2],
    /// How far apart they are.
    apart: StationOffset,
}

impl TwoPlaces {
    /// From a trial's passing candidates: where one [`ELSEWHERE_M`] or
    /// [`ELSEWHERE_DEG`] from the best-scoring overlaps the others by
    /// [`AMBIGUOUS_FIT_SHARE`] of its overlap or more.
    fn of(passing: &[Passed]) -> Option<TwoPlaces> {
        let best = passing.iter().reduce(|a, b| if score(b.fit, b.viol) > score(a.fit, a.viol) { b } else { a })?;
        passing
            .iter()
            .map(|c| (c.fit, StationOffset::between(&best.pose, &c.pose)))
            .filter(|(fit, apart)| apart.is_elsewhere() && *fit >= AMBIGUOUS_FIT_SHARE * best.fit)
            .reduce(|a, b| if b.0 > a.0 { b } else { a })
            .map(|(fit, apart)| TwoPlaces { fit: [best.fit, fit], apart })
    }
}

/// The farthest (m) an alignment of a scan may move in plan, its weakest
/// way, before the walls, columns and tanks it shares with the scans
/// placed so far lie 1 cm RMS further off each other
/// ([`PlanHold::slide_per_cm_m`]); one held more loosely is not pinned
/// down by them, and a station pins it down only where its tolerance lets
/// the scan lie no farther off that way than this
/// ([`PlanHold::within_station_m`]). Measured over 98 right placements (8, 16 and 24 stations
/// all round, 9 and 12 over three quarters, 6 over a half, the demo's 4
/// with and without a person beside a scanner, 8 all round with a person
/// beside the reference, 8 and 10 with a van beside it): at most 0.114 m
/// (`s6` of 16 all round, its weakest way a shift along the site's long
/// axis). Wrong placements: 0.25 m (`s1` of 4 all round with a van beside
/// the reference), 0.27 m (the demo's `scan-3` with a van beside it, 30 m
/// and 154 degrees off), 0.50 m (`s1` of 8 all round with the van) and
/// 0.72 m (`s1` of 12 all round with the van, overlapping the reference by
/// 86.5 %: all 12 scans were merged 28 degrees wrong, no other check
/// refusing them). Scans held by stations at their true poses (default
/// tolerance, 22 layouts, 176 placements): at most 0.169 m, a thin margin;
/// before held scans were held to it, `s3` of 8 all round, tried third,
/// was placed right at 0.190 and 0.266 m (with a van beside the
/// reference), and now waits and is placed later at 0.137 and 0.149 m. See
/// reports/scans.md.
pub const LOOSE_HOLD_SLIDE_M: f64 = 0.18;

/// How far the last alignment of a scan against all the others may move
/// its points (m) from where the scans placed before it put them, before
/// registration warns that they do not quite agree where it lies; past
/// [`LOOSE_HOLD_SLIDE_M`] it is not merged ([`refined_move_said`]). Right
/// registrations measured at most 22.0 mm (210 scans over the 29 layouts
/// of the bench that merge, a van or a person beside a scanner and stations
/// 0.3 m off among them), but for 34.7 mm where two scans placed first were
/// 2 cm off and the others followed them (reports/scans.md); 8.3 mm when
/// the scans were aligned one at a time, which left such an error in place.
/// Scans placed at their stations because they overlapped the others too
/// little to be aligned by them are left out: their own alignment is that
/// last one, and their surveys are checked against the scans instead.
pub const REFINED_MOVE_WARN_M: f64 = 0.05;

/// The farthest any point of `c` lies at `to` from where it lies at `from` (m).
fn moved_up_to_m(c: &RegCloud, from: &Pose, to: &Pose) -> f64 {
    c.pts.iter().map(|x| crate::kdtree::distance2(&tf(from, x), &tf(to, x))).fold(0.0, f64::max).sqrt()
}

/// What the last alignment of scan `name` against all the others, moving
/// its points up to `moved_m` (m), says of it: nothing, a warning
/// (`Ok`), or why it is not merged (`Err`), the remedy as the scan is
/// `held` by a station or not.
fn refined_move_said(name: &str, moved_m: f64, held: bool) -> Option<Result<String, String>> {
    if moved_m > LOOSE_HOLD_SLIDE_M {
        let remedy = if held {
            "check its station's survey and the others', or rescan from where more of the site is in view"
        } else {
            "give the surveyed poses of the stations in the station file, or rescan from where more of the site is in view"
        };
        Some(Err(format!(
            "scan '{name}' is not merged: aligned against all the other scans at the end, it moved up to {moved_m:.2} m from where the scans placed before it put it (at most {LOOSE_HOLD_SLIDE_M:.2} m allowed): the scans do not agree where it lies; {remedy}"
        )))
    } else if moved_m > REFINED_MOVE_WARN_M {
        Some(Ok(format!(
            "scan '{name}' moved up to {moved_m:.2} m when aligned against all the other scans at the end, from where the scans placed before it put it (up to {REFINED_MOVE_WARN_M:.2} m expected where they agree): check what it shows against what the other scans show there"
        )))
    } else {
        None
    }
}

/// How loosely an alignment is held ([`PlanHold::slide_per_cm_m`]), in
/// words: "moved 0.25 m its weakest way (...), they lie only 1 cm RMS
/// further off each other".
fn loose_hold_said(c: &Passed) -> String {
    let slide_m = c.hold.slide_per_cm_m();
    let way = weakest_way_said(c);
    if slide_m.is_finite() {
        format!("moved {slide_m:.2} m its weakest way ({way}), they lie only 1 cm RMS further off each other")
    } else {
        format!("moved any distance its weakest way ({way}), they lie no further off each other")
    }
}

/// A loose hold's weakest way in words: how much of it is a turn, and
/// along which bearing the rest shifts.
fn weakest_way_said(c: &Passed) -> String {
    let [turn, east, north] = c.hold.weakest;
    let bearing = east.atan2(north).to_degrees().rem_euclid(180.0);
    format!(
        "{:.0} % a turn about the shared structure's middle, the rest a shift along bearing {:.0}/{:.0} degrees",
        100.0 * turn * turn,
        bearing,
        bearing + 180.0
    )
}

/// Why scan `name` was placed though `share` of its points lie where
/// another scanner saw through (over `allowed[0]`): they lie within
/// [`NEAR_SCANNER_M`] of its own scanner but for `beyond` of its points
/// (within `allowed[1]`), its alignment overlapping the others by `fit`;
/// with `every_scan_placed`, as the check against all the others found it.
fn beside_scanner_said(
    name: &str,
    share: f64,
    beyond: f64,
    fit: f64,
    allowed: [f64; 2],
    every_scan_placed: bool,
) -> String {
    format!(
        "scan '{name}' was placed though{} {:.1} % of its points lie where another scanner saw through (at most {:.1} % allowed): they lie within {:.0} m of its own scanner but for {:.2} % of its points (at most {:.1} % allowed beyond), something that stood beside it for this scan alone (a person, a vehicle) or was moved before the others were scanned; its alignment overlaps the others by {:.1} % ({:.0} % or more needed to place it so). What it shows there is kept as an obstacle: check whether it still stands there",
        if every_scan_placed { ", with every scan placed," } else { "" },
        100.0 * share,
        100.0 * allowed[0],
        NEAR_SCANNER_M,
        100.0 * beyond,
        100.0 * allowed[1],
        100.0 * fit,
        100.0 * NARROW_LEAST_FIT
    )
}

/// With every scan placed, a scan may have at most this many times
/// `max_violation` of its points where the other scanners saw through.
/// Right poses measured at most 0.9 % against all other scans (a van or a
/// person beside one scanner, a lamp post a far scanner missed); a wrong
/// one at least 1.3 % as a candidate and 4.4 % in the case that made this
/// check (reports/scans.md). A wrong result the others agree with (the
/// same van with eight stations) passes it. A scan over it that overlaps
/// the others by [`NARROW_LEAST_FIT`] or more, and puts no more than
/// `max_violation` of its points so beyond [`NEAR_SCANNER_M`] of its own
/// scanner, is merged with a warning (a person 4 m from a scanner put 3.0 %
/// of its points there, nearly all within that reach).
pub const FINAL_VIOLATION_FACTOR: f64 = 4.0;

/// The least overlap (0..1) at which an alignment that puts more than
/// `max_violation` of its points where a placed scanner saw through may
/// still be placed, where no more than that share lies where a ray of that
/// scanner passed within half the width of what the point lies on
/// ([`half_widths_m`]). Right alignments refused so overlapped the others by
/// 87.9 % (a lamp post a scanner 57 m off missed, nine stations over three
/// quarters of the ellipse) and 91.4 % (24 stations all round); a wrong
/// alignment of a scan a van stood beside overlapped them by 55 % and
/// passed the seen-through check whichever way it was counted
/// (reports/scans.md).
pub const NARROW_LEAST_FIT: f64 = 0.6;

/// How registration ranks an alignment: its overlap (0..1) less ten times
/// the share of its points where a placed scanner saw through.
fn score(fit: f64, viol: f64) -> f64 {
    fit - 10.0 * viol
}

/// An alignment's seen-through check against the placed scanners: its
/// share of points where one saw through (any ray), and where the
/// alignment overlaps the others well enough for them to count, the share
/// where a ray passed within half the width of what a point lies on, and
/// of that, the share beyond [`NEAR_SCANNER_M`] from its own scanner.
struct SeenCheck {
    fit: f64,
    any: f64,
    narrow: Option<f64>,
    beyond: Option<f64>,
}

impl SeenCheck {
    /// The check of scan `src` at `p` (overlapping the others by `fit`)
    /// against the scanners `seen`, its share with any ray `any` (where it
    /// is known already) or counted; its share counted within half the
    /// width (`reach_m`, [`half_widths_m`]), and beyond [`NEAR_SCANNER_M`]
    /// where its frame is its scanner's (`scanner_at_origin`), only where
    /// that can pass it.
    #[allow(clippy::too_many_arguments)]
    fn of<'a>(
        src: &RegCloud,
        reach_m: impl FnOnce() -> &'a [f64],
        scanner_at_origin: bool,
        p: &Pose,
        fit: f64,
        any: Option<f64>,
        seen: &[(&RangeImage, Pose)],
        max_violation: f64,
    ) -> SeenCheck {
        let any = any.unwrap_or_else(|| free_space_violations(src, p, seen));
        let mut check = SeenCheck { fit, any, narrow: None, beyond: None };
        if fit >= NARROW_LEAST_FIT && any > max_violation {
            let reach_m = reach_m();
            let narrow = free_space_violations_within(src, reach_m, p, seen);
            check.narrow = Some(narrow);
            if narrow > max_violation && scanner_at_origin {
                check.beyond = Some(free_space_violations_beyond(src, Some(reach_m), p, seen));
            }
        }
        check
    }

    /// Whether the alignment passes: its share within `max_violation`, or
    /// where it overlaps the others by [`NARROW_LEAST_FIT`] or more, its
    /// share with rays within half the width, or that share beyond
    /// [`NEAR_SCANNER_M`] from its scanner (what stood beside the scanner
    /// for that scan alone is not held against it).
    fn passes(&self, max_violation: f64) -> bool {
        self.any <= max_violation
            || (self.fit >= NARROW_LEAST_FIT
                && (self.narrow.is_some_and(|v| v <= max_violation) || self.beyond.is_some_and(|v| v <= max_violation)))
    }
}

/// The placed scans (other than `j`) whose scanners a check of scan `j`
/// counts against, and their range images at their poses.
fn scanners_but<'a>(
    j: usize,
    poses: &[Option<Pose>],
    images: &'a [Option<RangeImage>],
) -> (Vec<usize>, Vec<(&'a RangeImage, Pose)>) {
    (0..poses.len()).filter(|&i| i != j).filter_map(|i| Some((i, (images[i].as_ref()?, poses[i]?)))).unzip()
}

/// The placed scans that alone keep scan `j` at `p` from passing the
/// seen-through check (each, left out, lets it pass), among `eligible`.
#[allow(clippy::too_many_arguments)]
fn standing_in_the_way<'a>(
    j: usize,
    p: &Pose,
    fit: f64,
    eligible: &[usize],
    poses: &[Option<Pose>],
    quick: &[RegCloud],
    images: &[Option<RangeImage>],
    half_widths_of: &(impl Fn(usize) -> &'a [f64] + Sync),
    max_violation: f64,
) -> Vec<usize> {
    let (by, seen) = scanners_but(j, poses, images);
    let any = seen_through_counts(&quick[j], None, p, &seen);
    let narrow = (fit >= NARROW_LEAST_FIT).then(|| seen_through_counts(&quick[j], Some(half_widths_of(j)), p, &seen));
    eligible
        .iter()
        .copied()
        .filter(|k| {
            let Some(at) = by.iter().position(|i| i == k) else { return false };
            any.share_without(Some(at)) <= max_violation
                || narrow.as_ref().is_some_and(|c| c.share_without(Some(at)) <= max_violation)
        })
        .collect()
}

/// Scan `j` has just been placed: noted for each scan taken out
/// (`deferred`) and not placed again yet.
fn note_placed_while_out(j: usize, poses: &[Option<Pose>], deferred: &[bool], placed_while_out: &mut [Vec<usize>]) {
    for (k, while_out) in placed_while_out.iter_mut().enumerate() {
        if deferred[k] && poses[k].is_none() && k != j {
            while_out.push(j);
        }
    }
}

/// The model of the placed scans, built only when a round has a trial or a
/// placement the memo does not hold.
struct Round {
    model: Target,
    model_cloud: RegCloud,
}

impl Round {
    fn new(inputs: &[RegInput], poses: &[Option<Pose>], except: Option<usize>) -> Round {
        let model = model_of(inputs, poses, except);
        let model_cloud = RegCloud { pts: model.pts.clone(), normals: model.normals.clone() };
        Round { model, model_cloud }
    }
}

/// [`register_all`], with the answers of trials, placements and the final
/// refinement looked up in and added to `memo` ([`crate::memo`]). The result
/// is the same with any memo, bit for bit; only the time differs.
pub fn register_all_memo(inputs: &[RegInput], s: &RegistrationSettings, seed: u64, memo: &mut Memo) -> Vec<RegResult> {
    let n = inputs.len();
    if n == 0 {
        return vec![];
    }
    // What every answer depends on besides the scans: the build and the
    // platform (its maths library), the settings and, for feature matching,
    // the seed and the scans' places in the list (its RANSAC is seeded from
    // them).
    let mut context = blake3::Hasher::new();
    context.update(b"liftplan registration v7\0");
    context.update(memo.build().as_bytes());
    context.update(b"\0");
    context.update(std::env::consts::ARCH.as_bytes());
    context.update(std::env::consts::OS.as_bytes());
    context.update(b"\0");
    context.update(serde_json::to_string(s).unwrap_or_default().as_bytes());
    if !s.leveled {
        context.update(&seed.to_le_bytes());
    }
    let by_place = !s.leveled;
    let scan_keys: Vec<Key> = inputs.par_iter().map(scan_key).collect();
    // The placed scans, their order and poses.
    let state_of = |poses: &[Option<Pose>], what: &[u8]| -> blake3::Hasher {
        let mut h = context.clone();
        h.update(what);
        for (i, p) in poses.iter().enumerate() {
            if let Some(p) = p {
                if by_place {
                    h.update(&(i as u64).to_le_bytes());
                }
                h.update(&scan_keys[i]);
                hash_pose(&mut h, p);
            }
        }
        h.update(b"\0end");
        h
    };
    // A station's tolerance holds in the station file's frame, which is the
    // frame scans are placed in only when the reference has a station too.
    let held = |j: usize| -> Option<(Pose, StationTolerance)> {
        inputs[0].held?;
        Some((inputs[j].initial?, inputs[j].held?))
    };
    // What the others share with a scan holds its alignment loosely where
    // it moves more than LOOSE_HOLD_SLIDE_M its weakest way for 1 cm
    // (`held_loosely_by_overlap`); a station pins that way down where its
    // tolerance lets the scan lie no farther off it than that. Not pinned
    // down either way: `loosely_held`.
    let held_loosely_by_overlap = |c: &Passed| c.hold.slide_per_cm_m() > LOOSE_HOLD_SLIDE_M;
    let loosely_held = |j: usize, c: &Passed| {
        held_loosely_by_overlap(c)
            && held(j)
                .is_none_or(|(station, tol)| c.hold.within_station_m(&c.pose, &station, &tol) > LOOSE_HOLD_SLIDE_M)
    };
    let mut poses: Vec<Option<Pose>> = vec![None; n];
    let mut results: Vec<Option<RegResult>> = vec![None; n];
    let fit_d = s.fit_distance_m;
    let fit_r = s.fit_residual_m;
    // The reference fixes the site frame, whose z the later stages take for
    // up: a scanner that did not level itself leaves that to be found.
    // A station gives a position and a yaw, no tilt; a file's pose (E57)
    // gives the whole rotation. Each scan is levelled once ([`levelling`]):
    // the reference by it, and every trial's plan view of the scan.
    let levels: Vec<Option<(Pose, &'static str)>> =
        if s.leveled { vec![None; n] } else { inputs.par_iter().map(|i| levelling(&i.fine)).collect() };
    let (reference_pose, reference_method) = match (inputs[0].initial, s.leveled) {
        (at, true) => (at.unwrap_or_else(Pose::identity), "reference".to_string()),
        (Some(p), false) if inputs[0].held.is_none() => (p, "reference".to_string()),
        (at, false) => {
            let at = at.unwrap_or_else(Pose::identity);
            match levels[0] {
                Some((level, by)) => (at * level, format!("reference, levelled by {by}")),
                None => (
                    at,
                    format!(
                        "reference, {}{NOT_LEVELLED}: too few walls or level ground to find its vertical, so the site frame tilts as its scanner did",
                        if inputs[0].held.is_some() { "at its station but " } else { "" }
                    ),
                ),
            }
        }
    };
    poses[0] = Some(reference_pose);
    results[0] = Some(RegResult {
        pose: reference_pose,
        fitness: 1.0,
        rmse_m: 0.0,
        method: reference_method,
        registered: true,
        hold_m: None,
        refined_move_m: None,
        warning: None,
    });
    let srcs: Vec<RegCloud> = inputs.iter().map(|i| sample(&i.fine, s.icp_source_points)).collect();
    let quick: Vec<RegCloud> = inputs.iter().map(|i| sample(&i.fine, s.icp_source_points / 4)).collect();
    let checks: Vec<RegCloud> = inputs.iter().map(|i| structure(&i.fine, s.icp_source_points / 4)).collect();
    // The half widths of the quick points, worked out for a scan only where
    // one of its alignments needs them (overlapping well, over the share).
    let half_widths: Vec<std::sync::OnceLock<Vec<f64>>> = (0..n).map(|_| std::sync::OnceLock::new()).collect();
    let half_widths_of = |j: usize| half_widths[j].get_or_init(|| half_widths_m(&quick[j], &inputs[j].fine)).as_slice();
    let images: Vec<Option<RangeImage>> =
        inputs.iter().map(|i| scanner_at_origin(&i.fine).then(|| RangeImage::new(&i.fine.pts, 0.5))).collect();
    // The seen-through check of scan `j` at `p`, overlapping the others by
    // `fit`, against the scanners `seen` ([`SeenCheck::of`]).
    let seen_check = |j: usize, p: &Pose, fit: f64, any: Option<f64>, seen: &[(&RangeImage, Pose)]| {
        SeenCheck::of(&quick[j], || half_widths_of(j), images[j].is_some(), p, fit, any, seen, s.max_violation)
    };
    let quick_levels = &s.icp_distances_m[..s.icp_distances_m.len().min(2)];
    // Pairwise coarse transforms (scan j's frame to scan i's frame) with their
    // RANSAC inlier counts, computed once per pair (scans that are not levelled).
    let mut coarse: std::collections::HashMap<(usize, usize), Option<(Pose, usize)>> = std::collections::HashMap::new();
    let eps = 1.5 * s.feature_voxel_m;
    // The scans in the order they were placed, after the reference.
    let mut order: Vec<usize> = Vec::new();
    // Held scans placed at their station as surveyed, with their overlap then.
    let mut surveyed_only: Vec<Option<f64>> = vec![None; n];
    // Per placed scan, whether it was placed for what stood beside its
    // scanner, and said so ([`beside_scanner_said`]).
    let mut said_beside_scanner: Vec<bool> = vec![false; n];
    let names: Vec<&str> = inputs.iter().map(|i| i.name.as_str()).collect();
    // Per scan, its last trial's near misses ([`Trial::near_misses`]).
    let mut near_misses: Vec<Vec<(Pose, f64)>> = vec![vec![]; n];
    // Scans taken out and placed again later, for standing in the way of
    // another's alignment, and each such contest: (the scan whose
    // alignment was kept from passing, the scan taken out, that
    // alignment's overlap, and where the scan taken out had been placed).
    let mut deferred = vec![false; n];
    let mut contests: Vec<(usize, usize, f64, Pose)> = Vec::new();
    // Per scan taken out, the scans placed while it was out.
    let mut placed_while_out: Vec<Vec<usize>> = vec![vec![]; n];
    // Scans refused for fitting the placed ones at two places.
    let mut not_pinned = vec![false; n];
    loop {
        let pending: Vec<usize> = (0..n).filter(|&j| poses[j].is_none() && !not_pinned[j]).collect();
        if pending.is_empty() {
            break;
        }
        let state = state_of(&poses, b"round");
        let mut round: Option<Round> = None;
        let seen: Vec<(&RangeImage, Pose)> = (0..n).filter_map(|i| Some((images[i].as_ref()?, poses[i]?))).collect();
        // (scan, pose, fitness, violation, method)
        let mut best: Option<(usize, Passed)> = None;
        let mut closest: Vec<(f64, f64)> = vec![(0.0, 1.0); n];
        let mut held_back: Vec<Option<(f64, f64, StationOffset)>> = vec![None; n];
        let mut at_station: Vec<Option<(f64, f64)>> = vec![None; n];
        // Each pending scan's trial against the scans placed so far: looked
        // up, or worked out, those not known all at once (they do not depend
        // on each other, and one trial's ICP runs on a few blocks of points,
        // too few to keep many cores busy). Each trial's answer does not
        // depend on what runs beside it.
        let keys: Vec<Key> = pending
            .iter()
            .map(|&j| {
                let mut key = state.clone();
                key.update(b"trial");
                key.update(&scan_keys[j]);
                if by_place {
                    key.update(&(j as u64).to_le_bytes());
                }
                *key.finalize().as_bytes()
            })
            .collect();
        let mut trials: Vec<Option<Trial>> = keys.iter().map(|key| memo.get(key).and_then(Trial::decode)).collect();
        let unknown: Vec<usize> = (0..pending.len()).filter(|&k| trials[k].is_none()).collect();
        if !unknown.is_empty() {
            let Round { model, model_cloud } = round.get_or_insert_with(|| Round::new(inputs, &poses, None));
            let (model, model_cloud) = (&*model, &*model_cloud);
            if !s.leveled {
                // Feature alignments of each pair, worked out once.
                let pairs: Vec<(usize, usize)> = unknown
                    .iter()
                    .flat_map(|&k| {
                        let j = pending[k];
                        (0..n).filter(|&i| poses[i].is_some()).map(move |i| (j, i))
                    })
                    .filter(|pair| !coarse.contains_key(pair))
                    .collect();
                let found: Vec<Option<(Pose, usize)>> = pairs
                    .par_iter()
                    .map(|&(j, i)| {
                        let corr = match_features(&inputs[j].coarse, &inputs[i].coarse, 4000);
                        ransac(
                            &inputs[j].coarse.pts,
                            &inputs[i].coarse.pts,
                            &corr,
                            false,
                            eps,
                            s.ransac_iterations,
                            seed ^ ((j as u64) << 32 | i as u64),
                        )
                    })
                    .collect();
                coarse.extend(pairs.into_iter().zip(found));
            }
            let coarse = &coarse;
            // The model levelled once for the round's trials ([`levelling`]).
            let levelled_model = (!s.leveled).then(|| {
                let up = levelling(model_cloud).map_or_else(Pose::identity, |l| l.0);
                (up, rotated(model_cloud, &up))
            });
            let worked_out: Vec<Trial> = unknown
                .par_iter()
                .map(|&k| {
                    let j = pending[k];
                    let mut candidates: Vec<(Pose, String)> = Vec::new();
                    if let Some(p) = inputs[j].initial {
                        candidates.push((p, "file pose + ICP".into()));
                    }
                    if s.leveled {
                        let guesses = plan_view_guesses(
                            &inputs[j].fine,
                            &checks[j],
                            &quick[j],
                            model,
                            model_cloud,
                            &seen,
                            4,
                            |g| g,
                        );
                        for p in guesses {
                            candidates.push((p, "plan-view correlation + ICP".into()));
                        }
                    } else if let Some((up_model, plan_model)) = &levelled_model {
                        // Each levelled, the scan and the model differ by a
                        // yaw and a shift again, up to the error of that
                        // levelling (ICP is 6-DOF).
                        let up_scan = levels[j].map_or_else(Pose::identity, |l| l.0);
                        let guesses = plan_view_guesses(
                            &rotated(&inputs[j].fine, &up_scan),
                            &checks[j],
                            &quick[j],
                            model,
                            plan_model,
                            &seen,
                            4,
                            |g| up_model.inverse() * g * up_scan,
                        );
                        for p in guesses {
                            candidates.push((p, "levelled, plan-view correlation + ICP".into()));
                        }
                        for i in 0..n {
                            let Some(pi) = poses[i] else { continue };
                            if let Some(Some((t, _))) = coarse.get(&(j, i)) {
                                candidates.push((pi * *t, format!("features (to {}) + ICP", inputs[i].name)));
                            }
                        }
                    }
                    let t = std::time::Instant::now();
                    let mut trial = Trial {
                        passing: vec![],
                        closest: (0.0, 1.0),
                        at_station: None,
                        held_back: None,
                        near_misses: vec![],
                    };
                    for (c, (init, method)) in candidates.into_iter().enumerate() {
                        let p = icp(&quick[j], model, init, quick_levels);
                        let (fit, _) = evaluate(&checks[j], model, &p, fit_d, fit_r);
                        let checked = seen_check(j, &p, fit, None, &seen);
                        let viol = checked.any;
                        // The station pose is the first candidate.
                        if c == 0 && held(j).is_some() {
                            trial.at_station = Some((fit, viol));
                        }
                        if score(fit, viol) > score(trial.closest.0, trial.closest.1) {
                            trial.closest = (fit, viol);
                        }
                        // Where an alignment overlaps the others well, the
                        // points a scanner's rays passed beside (a post its
                        // steps went both sides of) are not held against it.
                        let passes = checked.passes(s.max_violation);
                        if fit >= s.min_fitness
                            && !passes
                            && held(j).is_none_or(|(station, tol)| StationOffset::between(&station, &p).within(&tol))
                        {
                            trial.near_misses.push((p, fit));
                        }
                        if fit >= s.min_fitness && passes {
                            // A guess that scores higher must not move a scan
                            // away from where its station was surveyed.
                            let off = held(j).map(|(station, tol)| (StationOffset::between(&station, &p), tol));
                            match off.filter(|(o, tol)| !o.within(tol)) {
                                Some((o, _)) => {
                                    if trial.held_back.is_none_or(|(f, v, _)| score(fit, viol) > score(f, v)) {
                                        trial.held_back = Some((fit, viol, o));
                                    }
                                }
                                None => {
                                    let hold = plan_hold(&checks[j], model, &p, fit_d, fit_r);
                                    trial.passing.push(Passed { pose: p, fit, viol, method, hold });
                                }
                            }
                        }
                    }
                    tracing::debug!("candidates {j}: {:?}", t.elapsed());
                    trial
                })
                .collect();
            for (k, trial) in unknown.into_iter().zip(worked_out) {
                memo.put(keys[k], trial.encode());
                trials[k] = Some(trial);
            }
        }
        // Per scan, a second place its trial passes at ([`AMBIGUOUS_FIT_SHARE`]).
        let mut two_places: Vec<Option<TwoPlaces>> = vec![None; n];
        for (&j, trial) in pending.iter().zip(trials) {
            let Some(trial) = trial else { continue };
            closest[j] = trial.closest;
            held_back[j] = trial.held_back;
            at_station[j] = trial.at_station;
            near_misses[j] = trial.near_misses;
            two_places[j] = TwoPlaces::of(&trial.passing);
            // Scans held by a station go first: their place does not rest on
            // the scans placed before them, and theirs pins the others'
            // (not where what they share holds them loosely: then they wait
            // as a scan without a station does). A scan taken out for
            // standing in another's way waits until no other scan can be
            // placed, and one the others do not pin down until no other can
            // be placed by them, as does an alignment its shared structure
            // holds loosely ([`LOOSE_HOLD_SLIDE_M`]); of those, one its
            // station pins down goes first (it is placed, with a warning),
            // and one that nothing pins down last (it is refused). So a
            // held scan placed with its station's help is one whose shared
            // structure stayed loose while every scan held firmly was placed.
            for c in trial.passing {
                let rank = |j: usize, c: &Passed| {
                    (
                        held(j).is_some() && !held_loosely_by_overlap(c),
                        !deferred[j],
                        two_places[j].is_none(),
                        !loosely_held(j, c),
                        !held_loosely_by_overlap(c),
                        score(c.fit, c.viol),
                    )
                };
                if best.as_ref().is_none_or(|b| rank(j, &c).partial_cmp(&rank(b.0, &b.1)).is_some_and(|o| o.is_gt())) {
                    best = Some((j, c));
                }
            }
        }
        // The best scan the others do not pin down (it fits them at two
        // places, or what it shares with them holds it loosely): none that
        // they do can be placed. It is not merged; the next round tries the
        // rest.
        let unpinned = best.as_ref().and_then(|(j, c)| {
            let (fitness, why) = match (&two_places[*j], loosely_held(*j, c)) {
                (Some(two), _) => (two.fit[0], format!(
                    "scan '{}' is not merged: it fits the scans placed so far at two places {:.2} m in plan, {:.2} m in height and {:.1} degrees in yaw apart, overlapping them by {:.1} % at one and {:.1} % at the other (a second place at {:.0} % of the first's overlap or more refuses it): the other scans do not pin it down (it may see little of what they saw: like parts repeated, as tanks in a row or the bays of a rack, or a view hidden in part by something beside its scanner); give the surveyed poses of the stations in the station file, or rescan from where more of the site is in view",
                    names[*j],
                    two.apart.plan_m,
                    two.apart.height_m,
                    two.apart.yaw_deg,
                    100.0 * two.fit[0],
                    100.0 * two.fit[1],
                    100.0 * AMBIGUOUS_FIT_SHARE
                )),
                (None, true) => {
                    let (station, remedy) = match held(*j) {
                        Some((station, tol)) => (
                            format!(
                                ", and its station's tolerance (tolerance_m = {}{}) lets it lie up to {:.2} m off that way",
                                tol.plan_m,
                                tol.yaw_deg.map_or(String::new(), |deg| format!(", yaw_tolerance_deg = {deg}")),
                                c.hold.within_station_m(&c.pose, &station, &tol)
                            ),
                            "neither pins it down (what it shares may turn onto itself, as one tank's side, or slide along itself, as parallel walls); where its station was surveyed more closely than that, give its tolerance in the station file; or rescan from where more of the site is in view",
                        ),
                        None => (
                            String::new(),
                            "the other scans do not pin it down (what they share may turn onto itself, as one tank's side, or slide along itself, as parallel walls); give the surveyed poses of the stations in the station file, or rescan from where more of the site is in view",
                        ),
                    };
                    (c.fit, format!(
                        "scan '{}' is not merged: where it fits the scans placed so far best (overlapping them by {:.1} %), the walls, columns and tanks it shares with them hold it loosely in plan: {} (at most {:.2} m allowed){station}: {remedy}",
                        names[*j],
                        100.0 * c.fit,
                        loose_hold_said(c),
                        LOOSE_HOLD_SLIDE_M
                    ))
                }
                (None, false) => return None,
            };
            Some((*j, fitness, why))
        });
        if let Some((j, fitness, why)) = unpinned {
            not_pinned[j] = true;
            results[j] = Some(RegResult {
                pose: inputs[j].initial.unwrap_or_else(Pose::identity),
                fitness,
                rmse_m: 0.0,
                method: "none".into(),
                registered: false,
                hold_m: None,
                refined_move_m: None,
                warning: Some(why),
            });
            continue;
        }
        match best {
            Some((j, c)) => {
                let (p, trial_fit, viol) = (c.pose, c.fit, c.viol);
                // A held scan its shared structure holds loosely, its station
                // pinning that way down (else it is refused above).
                let station_pins = held(j)
                    .filter(|_| held_loosely_by_overlap(&c))
                    .map(|(station, tol)| c.hold.within_station_m(&c.pose, &station, &tol));
                // Placed though the share is over (at the trial's pose, which
                // passed): how much of it lies where a ray passed within half
                // the width, and of that, beyond what stood beside its scanner.
                let SeenCheck { narrow: narrow_share, beyond: beyond_share, .. } =
                    seen_check(j, &p, trial_fit, Some(viol), &seen);
                let mut key = state.clone();
                key.update(b"place");
                key.update(&scan_keys[j]);
                hash_pose(&mut key, &p);
                let key: Key = *key.finalize().as_bytes();
                let placed = memo.get(&key).and_then(|b| decode_placed(b, 1)).map(|v| v[0]);
                let (p, fit, rmse) = placed.unwrap_or_else(|| {
                    let model = &round.get_or_insert_with(|| Round::new(inputs, &poses, None)).model;
                    let p = icp(&srcs[j], model, p, &s.icp_distances_m);
                    let (fit, rmse) = evaluate(&checks[j], model, &p, fit_d, fit_r);
                    memo.put(key, encode_placed(&[(p, fit, rmse)]));
                    (p, fit, rmse)
                });
                poses[j] = Some(p);
                order.push(j);
                note_placed_while_out(j, &poses, &deferred, &mut placed_while_out);
                said_beside_scanner[j] = beyond_share.is_some();
                let narrow = narrow_share.map(|narrow_share| match beyond_share {
                    Some(beyond) => beside_scanner_said(&inputs[j].name, viol, beyond, trial_fit, [s.max_violation; 2], false),
                    None => format!(
                        "scan '{}' was placed though {:.1} % of its points lie where another scanner saw through (at most {:.1} % allowed): there, but for {:.2} % of its points, that scanner's rays passed farther off than half the width of what the point lies on (a post or a wire its steps went both sides of), and its alignment overlaps the others by {:.1} % ({:.0} % or more needed to place it so); check the thin structure it shows where another scan shows nothing",
                        inputs[j].name,
                        100.0 * viol,
                        100.0 * s.max_violation,
                        100.0 * narrow_share,
                        100.0 * trial_fit,
                        100.0 * NARROW_LEAST_FIT
                    ),
                });
                let by_station = station_pins.map(|within_m| {
                    format!(
                        "scan '{}' was placed with its station's help: the walls, columns and tanks it shares with the scans placed before it hold it loosely in plan (at most {:.2} m allowed: {}), so that way its place is its station's, within {:.2} m; check that station's survey",
                        inputs[j].name,
                        LOOSE_HOLD_SLIDE_M,
                        loose_hold_said(&c),
                        within_m
                    )
                });
                let warning = [narrow, by_station].into_iter().flatten().reduce(|a, b| a + "; " + &b);
                results[j] = Some(RegResult {
                    pose: p,
                    fitness: fit,
                    rmse_m: rmse,
                    method: c.method,
                    registered: true,
                    warning,
                    hold_m: Some(c.hold.slide_per_cm_m()),
                    refined_move_m: None,
                });
            }
            None => {
                // No scan fits those placed so far well enough to be placed
                // by them. A held scan that, at its surveyed pose, puts no
                // more than the allowed share of its points where a placed
                // scanner saw through is placed there as surveyed, so that
                // the others can be placed against it too (a van beside the
                // reference leaves the others too little of its view). Its
                // own alignment comes with the refinement, and the survey is
                // checked against the scans (those placed before it aligned
                // with it and those after it, and `confirm_surveys`).
                let by_survey = pending
                    .iter()
                    .copied()
                    .filter_map(|j| Some((j, at_station[j]?)))
                    .filter(|(_, (_, viol))| *viol <= s.max_violation)
                    .max_by(|a, b| score(a.1.0, a.1.1).total_cmp(&score(b.1.0, b.1.1)).then(b.0.cmp(&a.0)));
                if let Some((j, (station, _))) = by_survey.and_then(|(j, _)| Some((j, held(j)?))) {
                    let model = &round.get_or_insert_with(|| Round::new(inputs, &poses, None)).model;
                    let (fit, rmse) = evaluate(&checks[j], model, &station, fit_d, fit_r);
                    poses[j] = Some(station);
                    order.push(j);
                    note_placed_while_out(j, &poses, &deferred, &mut placed_while_out);
                    surveyed_only[j] = Some(fit);
                    results[j] = Some(RegResult {
                        pose: station,
                        fitness: fit,
                        rmse_m: rmse,
                        method: "station pose (overlap too small to align by) + refinement".into(),
                        registered: true,
                        hold_m: None,
                        refined_move_m: None,
                        warning: None,
                    });
                    continue;
                }
                // A scan whose alignment passes but for one placed scan: that
                // scan is taken out (with those placed after it, which were
                // placed against it) and placed again once no other scan can
                // be, so that the two are tried in the other order too. Each
                // scan is taken out once at most. How it ends is settled once
                // every scan is placed or refused (below).
                let eligible: Vec<usize> =
                    order.iter().rev().copied().filter(|&k| held(k).is_none() && !deferred[k]).collect();
                let mut misses: Vec<(usize, Pose, f64)> =
                    pending.iter().flat_map(|&j| near_misses[j].iter().map(move |&(p, fit)| (j, p, fit))).collect();
                // Best overlap first; the scan placed last of those in the
                // way (the fewest to place again).
                misses.sort_by(|a, b| b.2.total_cmp(&a.2).then(a.0.cmp(&b.0)));
                let contest = misses.iter().find_map(|&(j, p, fit)| {
                    let by = standing_in_the_way(
                        j,
                        &p,
                        fit,
                        &eligible,
                        &poses,
                        &quick,
                        &images,
                        &half_widths_of,
                        s.max_violation,
                    );
                    Some((j, *by.first()?, fit))
                });
                if let Some((j, k, fit)) = contest {
                    tracing::info!(
                        "registration: scan '{}' stands in the way of an alignment of scan '{}' (overlap {:.1} %); placing '{}' again after the others",
                        names[k],
                        names[j],
                        100.0 * fit,
                        names[k]
                    );
                    let first = poses[k].unwrap_or_else(Pose::identity);
                    let from = order.iter().position(|&x| x == k).unwrap_or(order.len());
                    for x in order.drain(from..) {
                        poses[x] = None;
                        results[x] = None;
                        surveyed_only[x] = None;
                        said_beside_scanner[x] = false;
                    }
                    deferred[k] = true;
                    contests.push((j, k, fit, first));
                    continue;
                }
                for &j in &pending {
                    let (fit, viol) = closest[j];
                    let warning = match (at_station[j], held(j)) {
                        (Some((fit, viol)), Some((_, tol))) => format!(
                            "scan '{}' does not register near its station: aligned from the pose the station file gives, it overlaps the scans placed so far by {:.1} % (at least {:.1} % required) and puts {:.1} % of its points where another scanner saw through (at most {:.1} % allowed){}; check that station's pose, or give its real uncertainty (tolerance_m, yaw_tolerance_deg); it is not merged",
                            inputs[j].name,
                            100.0 * fit,
                            100.0 * s.min_fitness,
                            100.0 * viol,
                            100.0 * s.max_violation,
                            match held_back[j] {
                                Some((fit, _, o)) => format!(
                                    "; the alignments that fit them (the best overlaps them by {:.1} %) place it {} from its station",
                                    100.0 * fit,
                                    o.describe(&tol)
                                ),
                                None => String::new(),
                            }
                        ),
                        _ => format!(
                            "scan '{}' does not register: its best alignment overlaps the other scans by {:.1} % (at least {:.1} % required) and puts {:.1} % of its points where another scanner saw through (at most {:.1} % allowed); it is not merged",
                            inputs[j].name,
                            100.0 * fit,
                            100.0 * s.min_fitness,
                            100.0 * viol,
                            100.0 * s.max_violation
                        ),
                    };
                    results[j] = Some(RegResult {
                        pose: inputs[j].initial.unwrap_or_else(Pose::identity),
                        fitness: fit,
                        rmse_m: 0.0,
                        method: "none".into(),
                        registered: false,
                        hold_m: None,
                        refined_move_m: None,
                        warning: Some(warning),
                    });
                }
                break;
            }
        }
    }
    // Each contest settled: scan `k` stood in the way of an alignment of
    // scan `j` and was placed again after the others.
    // - Where placed again it fitted at two places, the others do not pin
    //   it down: it is not merged, as it refused itself.
    // - Where `k` is not merged, the scans placed while it was out (`j`
    //   among them) may be what it could not be placed beside: none of
    //   them is merged.
    // - Where `k` was placed again elsewhere, the scans do not pin it: where
    //   it went rested on the order the scans were placed in (a van beside
    //   a scanner left its scan a partial view of the tank's far side and
    //   the rack, which fitted the two scans placed first turned 154
    //   degrees; placed again after the fourth, it fitted 1.6 m and 6
    //   degrees from there): it is not.
    // - Where it was placed again where it was, `j`, if placed, is checked
    //   against all the scans as placed; where `k` still stands in its way,
    //   neither is merged. Where `j` could not be placed even without `k`,
    //   the two stay as they were before `k` was taken out.
    for &(j, k, fit, first) in &contests {
        let merged = |x: usize| results[x].as_ref().filter(|r| r.registered).map(|r| r.pose);
        let (unmerge, why): (Vec<usize>, String) = match (merged(j), merged(k)) {
            // Placed again, it fitted at two places: as where it is placed
            // again elsewhere, the others do not pin it down, and its own
            // refusal says so.
            (_, None) if not_pinned[k] => continue,
            (_, None) => {
                // The scans placed while it was out, `j` among them, may be
                // what it could not then be placed beside.
                let mut without: Vec<usize> =
                    placed_while_out[k].iter().copied().filter(|&x| merged(x).is_some()).collect();
                without.sort_unstable();
                without.dedup();
                if without.is_empty() {
                    continue;
                }
                let listed = without.iter().map(|&x| format!("'{}'", names[x])).collect::<Vec<_>>().join(", ");
                if let Some(r) = results[k].as_mut() {
                    let said = r.warning.take().unwrap_or_else(|| format!("scan '{}' is not merged", names[k]));
                    r.warning = Some(format!(
                        "{said}; it had stood in the way of an alignment of scan '{}' and was taken out, and the scans placed while it was out ({listed}) are not merged either",
                        names[j]
                    ));
                }
                (
                    without,
                    format!(
                        "it was placed while scan '{}' was taken out (that scan stood in the way of an alignment of '{}' overlapping the others by {:.1} %), and '{}' could not then be placed beside the scans placed so; which of them are right is not known",
                        names[k],
                        names[j],
                        100.0 * fit,
                        names[k]
                    ),
                )
            }
            (pj, Some(pk)) => {
                let moved = StationOffset::between(&first, &pk);
                if moved.is_elsewhere() {
                    (
                        vec![k],
                        format!(
                            "it stood in the way of an alignment of scan '{}' overlapping the others by {:.1} %; taken out and placed again after the others, it fitted them {:.2} m in plan, {:.2} m in height and {:.1} degrees in yaw from where it had been: the other scans do not pin it down, and where it goes rests on the order they are placed in (it may see little of what they saw)",
                            names[j],
                            100.0 * fit,
                            moved.plan_m,
                            moved.height_m,
                            moved.yaw_deg
                        ),
                    )
                } else {
                    // Where `j` could not be placed even so, the two are as
                    // they were before `k` was taken out.
                    let Some(pj) = pj else { continue };
                    let others = model_of(inputs, &poses, Some(j));
                    let fit_now = evaluate(&checks[j], &others, &pj, fit_d, fit_r).0;
                    let (_, seen) = scanners_but(j, &poses, &images);
                    let now = seen_check(j, &pj, fit_now, None, &seen);
                    if now.passes(s.max_violation) {
                        continue;
                    }
                    (
                        vec![j, k],
                        format!(
                            "scans '{}' and '{}' cannot both be placed: placed where it was first, '{}' still stands in the way of the alignment of '{}' ({:.1} % of points where a scanner saw through, at most {:.1} % allowed), and which of the two is right is not known",
                            names[j],
                            names[k],
                            names[k],
                            names[j],
                            100.0 * now.any,
                            100.0 * s.max_violation
                        ),
                    )
                }
            }
        };
        for x in unmerge {
            poses[x] = None;
            if let Some(r) = results[x].as_mut() {
                r.registered = false;
                r.warning = Some(format!(
                    "scan '{}' is not merged: {why}; something beside a scanner (a vehicle, a skip) may have hidden part of its view: rescan that station with its view clear, or give the surveyed poses of the stations in the station file",
                    names[x]
                ));
            }
        }
    }
    // The last alignment: all placed scans as one, the reference held.
    let key: Key = *state_of(&poses, b"all aligned as one").finalize().as_bytes();
    // (pose, fitness, RMSE) of every placed scan after the first, in order.
    let placed: Vec<usize> = (1..n).filter(|&j| poses[j].is_some()).collect();
    // Where the scans placed before each put it, for how far the refinement moves it.
    let placed_at = poses.clone();
    let refined = memo.get(&key).and_then(|b| decode_placed(b, placed.len()));
    let refined = refined.unwrap_or_else(|| {
        let refined = refine(inputs, &srcs, &checks, &mut poses, &placed, s);
        memo.put(key, encode_placed(&refined));
        refined
    });
    for (&j, (p, fit, rmse)) in placed.iter().zip(refined) {
        if let Some(r) = results[j].as_mut() {
            let moved_m = placed_at[j]
                .filter(|_| surveyed_only[j].is_none() && r.registered)
                .map(|from| moved_up_to_m(&inputs[j].fine, &from, &p));
            r.refined_move_m = moved_m;
            let moved = moved_m.and_then(|m| refined_move_said(&inputs[j].name, m, held(j).is_some()));
            r.pose = p;
            r.fitness = fit;
            r.rmse_m = rmse;
            match moved {
                Some(Err(why)) => {
                    r.registered = false;
                    r.warning = Some(why);
                }
                Some(Ok(warning)) => r.warn_also(warning),
                None => {}
            }
        }
    }
    // The fine alignment and the refinement may still move a held scan.
    for (j, r) in results.iter_mut().enumerate() {
        let (Some(r), Some((station, tol))) = (r.as_mut().filter(|r| r.registered && j > 0), held(j)) else {
            continue;
        };
        let o = StationOffset::between(&station, &r.pose);
        if !o.within(&tol) {
            r.registered = false;
            r.warning = Some(format!(
                "scan '{}' is not merged: aligned with the other scans it lies {} from the pose the station file gives; check that station's pose, or give its real uncertainty (tolerance_m, yaw_tolerance_deg)",
                inputs[j].name,
                o.describe(&tol)
            ));
        }
    }
    // A scan placed by its survey and those placed after it agree with each
    // other; whether they agree with the scans placed before it (the
    // reference first) rests on the survey alone unless those, aligned with
    // them as one, stay where they are. A station surveyed 0.3 m or 2.5
    // degrees off (within the default tolerance) otherwise put every scan
    // after it that far off, and the reference, aligned with them, moved by
    // just that. Every such scan is checked, in the order placed; once one is
    // not merged, neither is any scan after it (`confirm_surveys`).
    for k in (0..order.len()).filter(|&k| surveyed_only[order[k]].is_some()) {
        let merged = |i: usize| results[i].as_ref().filter(|r| r.registered).map(|r| r.pose);
        let j = order[k];
        if merged(j).is_none() {
            break;
        }
        let mut before: Vec<Option<Pose>> = vec![None; n];
        let mut after: Vec<Option<Pose>> = vec![None; n];
        for i in std::iter::once(0).chain(order[..k].iter().copied()) {
            before[i] = merged(i);
        }
        for &i in &order[k..] {
            after[i] = merged(i);
        }
        let mut key = state_of(&before, b"survey check");
        key.update(state_of(&after, b"against").finalize().as_bytes());
        let key: Key = *key.finalize().as_bytes();
        let kept = memo.get(&key).and_then(|b| decode_placed(b, 1)).map(|v| (v[0].0, v[0].1));
        let (correction, fit) = kept.unwrap_or_else(|| {
            let (correction, fit) = align_as_one(inputs, &srcs, &checks, &before, &after, s);
            memo.put(key, encode_placed(&[(correction, fit, 0.0)]));
            (correction, fit)
        });
        let Some(why) = survey_disagreement(inputs, &before, &correction, fit, s.min_fitness) else {
            continue;
        };
        if let Some(r) = results[j].as_mut() {
            r.registered = false;
            r.warning = Some(format!(
                "scan '{}' is not merged: it overlapped the scans placed before it too little to be aligned by them, so it was placed at the pose the station file gives, and the scans placed after it against it; {why}",
                inputs[j].name,
            ));
        }
        break;
    }
    confirm_surveys(&order, &surveyed_only, &mut results, inputs, s.min_fitness);
    // Every registered scan against all the others, in the final poses. The
    // first rounds place scans against one or two others, where a wrong pose
    // can pass the seen-through check (a van beside the reference scan made
    // the three others agree on a frame turned 74 degrees from it); with all
    // scans placed, a wrong pose stands in what many scanners saw through.
    let final_poses: Vec<Option<Pose>> =
        results.iter().map(|r| r.as_ref().filter(|r| r.registered).map(|r| r.pose)).collect();
    let registered: Vec<(usize, Pose)> = final_poses.iter().enumerate().filter_map(|(j, p)| Some((j, (*p)?))).collect();
    let key: Key = *state_of(&final_poses, b"final check").finalize().as_bytes();
    // One share per registered scan, in order.
    let kept = memo.get(&key).and_then(|b| {
        let mut r = answer(b);
        let shares = r.f64s().ok()?;
        (r.finish().is_ok() && shares.len() == registered.len()).then_some(shares)
    });
    let shares = kept.unwrap_or_else(|| {
        let shares: Vec<f64> = registered
            .iter()
            .map(|&(j, p)| {
                let (_, seen) = scanners_but(j, &final_poses, &images);
                free_space_violations(&quick[j], &p, &seen)
            })
            .collect();
        let mut w = ByteWriter::new();
        w.f64s(&shares);
        memo.put(key, w.buf);
        shares
    });
    let limit = FINAL_VIOLATION_FACTOR * s.max_violation;
    let reference_share = registered.iter().zip(&shares).find(|((j, _), _)| *j == 0).map(|(_, v)| *v);
    // The reference placed again against all the others (scans that are
    // levelled: plan-view guesses): where a van beside it left it a partial
    // view, the first rounds placed the others against that view turned 61
    // degrees, and it fits them as they are better elsewhere. Not needed
    // where its share has already shown the others wrong.
    let again = (s.leveled && registered.len() > 1 && reference_share.is_some_and(|v| v <= limit)).then(|| {
        let key: Key = *state_of(&final_poses, b"reference again").finalize().as_bytes();
        memo.get(&key).and_then(ReferenceAgain::decode).unwrap_or_else(|| {
            let at = final_poses[0].unwrap_or(reference_pose);
            let Round { model, model_cloud } = Round::new(inputs, &final_poses, Some(0));
            let seen: Vec<(&RangeImage, Pose)> =
                (1..n).filter_map(|i| Some((images[i].as_ref()?, final_poses[i]?))).collect();
            let scored = |p: &Pose| {
                let fit = evaluate(&checks[0], &model, p, fit_d, fit_r).0;
                let viol = free_space_violations(&quick[0], p, &seen);
                [score(fit, viol), fit, viol]
            };
            let here = scored(&at);
            // Leave out what stands beside the scanner (a van fills its
            // plan view with structure no other scanner saw), where the
            // scan's frame says where its scanner stood.
            let far = images[0].is_some().then(|| {
                let pts = &inputs[0].fine.pts;
                let idx: Vec<usize> = (0..pts.len()).filter(|&i| pts[i][0].hypot(pts[i][1]) > NEAR_SCANNER_M).collect();
                subset(&inputs[0].fine, &idx, usize::MAX)
            });
            let plan_view = far.as_ref().unwrap_or(&inputs[0].fine);
            let guesses = plan_view_guesses(plan_view, &checks[0], &quick[0], &model, &model_cloud, &seen, 4, |g| g);
            let elsewhere = guesses
                .into_iter()
                .map(|g| icp(&quick[0], &model, g, quick_levels))
                .map(|p| (scored(&p), StationOffset::between(&at, &p)))
                .filter(|(_, o)| o.is_elsewhere())
                .max_by(|a, b| a.0[0].total_cmp(&b.0[0]));
            let again = ReferenceAgain { here, elsewhere };
            memo.put(key, again.encode());
            again
        })
    });
    // Where the reference fits the others clearly better than where it is.
    let better = again.as_ref().and_then(|a| {
        let (e, o) = a.elsewhere.as_ref()?;
        (e[0] > a.here[0] + REFERENCE_ELSEWHERE_MARGIN).then_some((a.here, *e, *o))
    });
    let disagreement = match (reference_share.filter(|v| *v > limit), better) {
        (Some(share), _) => Some(format!(
            "{:.1} % of the reference's points lie where they saw through (at most {:.1} %)",
            100.0 * share,
            100.0 * limit
        )),
        (None, Some((here, e, o))) => Some(format!(
            "placed again against all of them, it fits them better {:.1} m and {:.1} degrees from where they put it (overlap {:.1} %, {:.2} % of its points where they saw through; where it is: {:.1} %, {:.2} %)",
            o.plan_m,
            o.yaw_deg,
            100.0 * e[1],
            100.0 * e[2],
            100.0 * here[1],
            100.0 * here[2]
        )),
        (None, None) => None,
    };
    if let Some(why) = disagreement {
        // The others were placed, one after another, against the reference.
        for &(j, _) in registered.iter().filter(|(j, _)| *j != 0) {
            if let Some(r) = results[j].as_mut() {
                r.registered = false;
                r.warning = Some(format!(
                    "scan '{}' is not merged: the scans placed against the reference scan '{}' do not agree with it: {why}; something beside its scanner (a vehicle, a skip) may have hidden part of its view and misled the first alignments: rescan that station with its view clear, or give the surveyed poses of more stations in the station file",
                    inputs[j].name, inputs[0].name,
                ));
            }
        }
    } else {
        for (&(j, p), &share) in registered.iter().zip(&shares) {
            // Over the limit for what stood beside its scanner alone (not
            // the reference, whose overlap with the others is not its own).
            let beside = (share > limit && j > 0 && images[j].is_some())
                .then(|| results[j].as_ref().map_or(0.0, |r| r.fitness))
                .filter(|fit| *fit >= NARROW_LEAST_FIT)
                .and_then(|fit| {
                    let (_, seen) = scanners_but(j, &final_poses, &images);
                    let beyond = free_space_violations_beyond(&quick[j], None, &p, &seen);
                    (beyond <= s.max_violation).then_some((fit, beyond))
                });
            if let (Some((fit, beyond)), Some(r)) = (beside, results[j].as_mut()) {
                if !said_beside_scanner[j] {
                    r.warn_also(beside_scanner_said(
                        &inputs[j].name,
                        share,
                        beyond,
                        fit,
                        [limit, s.max_violation],
                        true,
                    ));
                }
                continue;
            }
            if let Some(r) = results[j].as_mut().filter(|_| share > limit) {
                r.registered = false;
                r.warning = Some(format!(
                    "scan '{}' is not merged: with every scan placed, {:.1} % of its points lie where other scanners saw through (at most {:.1} %): the scans do not agree where it is",
                    inputs[j].name,
                    100.0 * share,
                    100.0 * limit
                ));
            }
        }
    }
    confirm_surveys(&order, &surveyed_only, &mut results, inputs, s.min_fitness);
    results
        .into_iter()
        .map(|r| {
            r.unwrap_or(RegResult {
                pose: Pose::identity(),
                fitness: 0.0,
                rmse_m: 0.0,
                method: "none".into(),
                registered: false,
                hold_m: None,
                refined_move_m: None,
                warning: None,
            })
        })
        .collect()
}

/// The scans at `before`, moved as one, aligned (full ICP schedule) with
/// those at `after`: the correction that moves them, and how much of them
/// (their structure points, `checks`) then overlaps those.
fn align_as_one(
    inputs: &[RegInput],
    srcs: &[RegCloud],
    checks: &[RegCloud],
    before: &[Option<Pose>],
    after: &[Option<Pose>],
    s: &RegistrationSettings,
) -> (Pose, f64) {
    let model = model_of(inputs, after, None);
    let placed = |clouds: &[RegCloud]| placed_cloud(clouds.iter().zip(before).filter_map(|(c, p)| Some((c, (*p)?))));
    let correction = icp(&placed(srcs), &model, Pose::identity(), &s.icp_distances_m);
    let (fit, _) = evaluate(&placed(checks), &model, &correction, s.fit_distance_m, s.fit_residual_m);
    (correction, fit)
}

/// Why the scans at `before`, aligned as one with a scan placed by its
/// survey and those placed after it ([`align_as_one`]: `correction`, `fit`),
/// show the survey wrong: they overlap those too little for the alignment
/// to say anything, or the correction moves one of them beyond
/// [`SURVEY_AGREEMENT_M`] or [`SURVEY_AGREEMENT_DEG`]. `None` if they agree.
fn survey_disagreement(
    inputs: &[RegInput],
    before: &[Option<Pose>],
    correction: &Pose,
    fit: f64,
    min_fitness: f64,
) -> Option<String> {
    let agreement = StationTolerance {
        plan_m: SURVEY_AGREEMENT_M,
        height_m: Some(SURVEY_AGREEMENT_M),
        yaw_deg: Some(SURVEY_AGREEMENT_DEG),
    };
    // The first that moves too far is the one told; a NaN offset fails
    // `within`, and so refuses.
    let too_far =
        before.iter().flatten().map(|p| StationOffset::between(p, &(correction * p))).find(|o| !o.within(&agreement));
    if too_far.is_none() && fit >= min_fitness {
        return None;
    }
    let names: Vec<String> =
        inputs.iter().zip(before).filter(|(_, p)| p.is_some()).map(|(i, _)| format!("'{}'", i.name)).collect();
    let (those, verb_s) = match names.as_slice() {
        [one] => (format!("the reference scan {one}, aligned with them,"), "s"),
        _ => (format!("the scans placed before it ({}), aligned with them as one,", names.join(", ")), ""),
    };
    Some(match too_far {
        Some(o) => format!(
            "{those} move{verb_s} {:.3} m in plan, {:.3} m in height and {:.3} degrees in yaw (at most {} m and {} degrees; overlapping them by {:.1} % there): the survey of that station and the scans do not agree; check the stations' poses, and if they are right, the scans overlap too little to pin them (a vehicle beside a scanner can hide much of its view): scan again with the view clear, or add a station between them",
            o.plan_m,
            o.height_m,
            o.yaw_deg,
            SURVEY_AGREEMENT_M,
            SURVEY_AGREEMENT_DEG,
            100.0 * fit
        ),
        None => format!(
            "{those} overlap{verb_s} them by {:.1} % (at least {:.1} % required): too little to confirm the survey of that station; add a station between them, or leave the scan out",
            100.0 * fit,
            100.0 * min_fitness
        ),
    })
}

/// How far the scans placed before a scan placed by its survey (the
/// reference first) may move, aligned as one with it and the scans placed
/// after it, for the survey and the scans to agree. Measured in the
/// four-station van case with the second station surveyed: 0.0009 m and
/// 0.005 degrees with the right survey; 0.020 m and 0.023 degrees with the
/// survey 0.1 m off across (the scans pin that direction weakly), 0.28 m
/// with it 0.3 m off along, 0.42 m and 0.55 degrees with it 0.5 degrees off.
/// One layout's evidence (reports/scans.md has more).
pub const SURVEY_AGREEMENT_M: f64 = 0.01;
/// The yaw counterpart of [`SURVEY_AGREEMENT_M`] (degrees).
pub const SURVEY_AGREEMENT_DEG: f64 = 0.05;

/// Scans placed at their station as surveyed (`surveyed_only`, with their
/// overlap then) must, aligned with all the scans, overlap them as any placed
/// scan must (`min_fitness`). Where such a scan is not merged (for that or
/// any other reason), the survey alone placed it, wrongly or without
/// confirmation, and the scans placed after it (`order`), perhaps against
/// it, are not merged either.
fn confirm_surveys(
    order: &[usize],
    surveyed_only: &[Option<f64>],
    results: &mut [Option<RegResult>],
    inputs: &[RegInput],
    min_fitness: f64,
) {
    for &j in order {
        let (Some(at_survey), Some(r)) = (surveyed_only[j], results[j].as_mut()) else { continue };
        if r.registered && r.fitness < min_fitness {
            r.registered = false;
            r.warning = Some(format!(
                "scan '{}' is not merged: it overlapped the scans placed before it too little to be aligned by them ({:.1} %, at least {:.1} % required), so it was placed at the pose the station file gives; aligned with all the scans, it overlaps them by {:.1} %, still too little to confirm that pose",
                inputs[j].name,
                100.0 * at_survey,
                100.0 * min_fitness,
                100.0 * r.fitness
            ));
        }
    }
    let unconfirmed =
        order.iter().position(|&j| surveyed_only[j].is_some() && results[j].as_ref().is_some_and(|r| !r.registered));
    let Some(k) = unconfirmed else { return };
    for &later in &order[k + 1..] {
        if let Some(r) = results[later].as_mut().filter(|r| r.registered) {
            r.registered = false;
            r.warning = Some(format!(
                "scan '{}' is not merged: it was placed while scan '{}' stood at the pose the station file gives, which the scans did not confirm (see that scan)",
                inputs[later].name, inputs[order[k]].name
            ));
        }
    }
}

/// The reference scan placed again, against all the other registered scans
/// in their final poses, as a trial places a scan.
struct ReferenceAgain {
    /// (score, fitness, seen-through share) where the reference is.
    here: [f64; 3],
    /// The best-scoring candidate more than [`ELSEWHERE_M`] or
    /// [`ELSEWHERE_DEG`] from it: its (score, fitness, share) and offset.
    elsewhere: Option<([f64; 3], StationOffset)>,
}

/// A scan whose trial passes at two places [`ELSEWHERE_M`] or
/// [`ELSEWHERE_DEG`] apart, the second overlapping the scans placed so far
/// by at least this share of what the first does, is not pinned down by
/// them: it waits while any scan that is can be placed, and if it is still
/// so when none can, it is not merged. A row of like tanks (each scan seeing
/// one or two of them) put two scans a tank along, overlapping the others
/// by 98 % and 99 % there against 84 % and 73 % where they stood; right
/// alignments of the ellipse's layouts passed a second place at 57 % of the
/// first at most (reports/scans.md).
pub const AMBIGUOUS_FIT_SHARE: f64 = 0.5;

/// How far a pose must be from another to count as elsewhere (m in plan or
/// height, degrees in yaw).
pub const ELSEWHERE_M: f64 = 0.5;
/// See [`ELSEWHERE_M`].
pub const ELSEWHERE_DEG: f64 = 2.0;
/// What stands nearer its scanner than this in plan (m) may have been there
/// for that scan alone (a person, a van 4 m off): it is left out of the plan
/// view when the reference is placed again, and out of the seen-through
/// share of an alignment that overlaps the others by [`NARROW_LEAST_FIT`] or
/// more ([`SeenCheck::passes`]). Right alignments of scans a person or a van
/// stood beside put no more than 0.02 % of their points beyond it where
/// another scanner saw through; wrong ones that overlap the others that well
/// at least 1.79 % (within half the width; reports/scans.md).
pub const NEAR_SCANNER_M: f64 = 8.0;
/// By how much (fitness less 10 x seen-through share) the reference must fit
/// the others better elsewhere for them to count as placed wrongly. In the
/// van case it fitted them 0.25 better elsewhere; where the others were right
/// (4, 8, 16 stations all round, 9 over three quarters, a person beside the
/// reference) no candidate elsewhere scored higher than where it was, the
/// nearest 0.59 below (reports/scans.md).
pub const REFERENCE_ELSEWHERE_MARGIN: f64 = 0.1;

impl ReferenceAgain {
    fn encode(&self) -> Vec<u8> {
        let mut v = self.here.to_vec();
        if let Some((e, o)) = &self.elsewhere {
            v.extend_from_slice(e);
            v.extend_from_slice(&[o.plan_m, o.height_m, o.yaw_deg]);
        }
        let mut w = ByteWriter::new();
        w.f64s(&v);
        w.buf
    }

    fn decode(bytes: &[u8]) -> Option<ReferenceAgain> {
        let mut r = answer(bytes);
        let v = r.f64s().ok()?;
        r.finish().ok()?;
        let here = [*v.first()?, *v.get(1)?, *v.get(2)?];
        let elsewhere = match v.len() {
            3 => None,
            9 => Some(([v[3], v[4], v[5]], StationOffset { plan_m: v[6], height_m: v[7], yaw_deg: v[8] })),
            _ => return None,
        };
        Some(ReferenceAgain { here, elsewhere })
    }
}

/// Candidates for a scan against `model`: plan-view guesses (of
/// `plan_scan` onto `plan_model`, levelled clouds, taken to poses of the
/// scan in the model's frame by `to_pose`), ranked in 3D by overlap of
/// structure less seen-through space (heights and visibility tell apart
/// shifts that look alike from above), the best `keep`.
#[allow(clippy::too_many_arguments)]
fn plan_view_guesses(
    plan_scan: &RegCloud,
    check: &RegCloud,
    quick: &RegCloud,
    model: &Target,
    plan_model: &RegCloud,
    seen: &[(&RangeImage, Pose)],
    keep: usize,
    to_pose: impl Fn(Pose) -> Pose,
) -> Vec<Pose> {
    let guesses: Vec<(Pose, f32)> =
        crate::coarse2d::align(plan_scan, plan_model, 30_000).into_iter().map(|(g, s)| (to_pose(g), s)).collect();
    let scores: Vec<f64> = guesses
        .par_iter()
        .map(|(p, _)| score(evaluate(check, model, p, 0.5, 0.25).0, free_space_violations(quick, p, seen)))
        .collect();
    let mut order: Vec<usize> = (0..guesses.len()).collect();
    order.sort_by(|&a, &b| scores[b].total_cmp(&scores[a]));
    order.iter().take(keep).map(|&k| guesses[k].0).collect()
}

/// What a reference scan's method says where its vertical rests on its
/// ground, or on nothing (the docs stage names these among what to check).
pub const LEVELLED_BY_GROUND: &str = "its ground (where that slopes, the site frame slopes with it)";
pub const NOT_LEVELLED: &str = "NOT LEVELLED";

/// The rotation that levels a cloud (turns its vertical onto z), for scans
/// whose scanner did not level itself, tilted up to about 30 degrees.
///
/// The vertical is taken from the walls, columns and tanks the cloud holds
/// where it can be (the direction their normals are all square to: plant
/// and buildings stand plumb, where ground slopes), which needs such
/// surfaces facing at least two ways; else from the ground and other level
/// surfaces (their mean normal), which tilts the cloud by the ground's
/// slope. With the rotation, what it was taken from. `None` where the
/// cloud holds too few of either (a hundred normals) to tell.
fn levelling(c: &RegCloud) -> Option<(Pose, &'static str)> {
    let unit = |n: &[f64; 3]| {
        let v = Vec3::new(n[0], n[1], n[2]);
        (v.norm() > 0.5).then(|| v.normalize())
    };
    // The direction square to the normals within `band` (sine) of square
    // to `up`, where they face two ways or more. Narrowed in steps (30, 6
    // and 1.7 degrees): roofs, edges and railings with a slope left in the
    // band tilted it by 0.04 degrees on the demo's scans, 0.005 without.
    let square_to = |up: Vec3, band: f64| -> Option<Vec3> {
        let mut scatter = na::Matrix3::zeros();
        let mut count = 0usize;
        for v in c.normals.iter().filter_map(unit).filter(|v| v.dot(&up).abs() < band) {
            scatter += v * v.transpose();
            count += 1;
        }
        let eig = na::SymmetricEigen::new(scatter);
        let mut order = [0, 1, 2];
        order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        let [least, middle, _] = order.map(|k| eig.eigenvalues[k]);
        // Facing two ways: the second direction holds a fair share of them,
        // and the vertical far less.
        let two_ways = middle >= 0.1 * count as f64 && least <= 0.05 * middle;
        (count >= 100 && two_ways).then(|| {
            let v = eig.eigenvectors.column(order[0]).into_owned();
            if v.dot(&up) < 0.0 { -v } else { v }
        })
    };
    let mean_up = |within_deg: f64, about: Vec3| -> Option<Vec3> {
        let mut sum = Vec3::zeros();
        let mut count = 0usize;
        for v in c.normals.iter().filter_map(unit) {
            let v = if v.dot(&about) < 0.0 { -v } else { v };
            if v.dot(&about) >= within_deg.to_radians().cos() {
                sum += v;
                count += 1;
            }
        }
        (count >= 100).then(|| sum.normalize())
    };
    // A narrower band that holds too few keeps the wider one's answer.
    let narrowed = |u: Vec3, band: f64| square_to(u, band).unwrap_or(u);
    let (up, by) = match square_to(Vec3::z(), 0.5).map(|u| narrowed(narrowed(u, 0.1), 0.03)) {
        Some(u) => (u, "its plumb surfaces (walls, columns, tanks)"),
        None => (mean_up(30.0, Vec3::z()).and_then(|u| mean_up(5.0, u))?, LEVELLED_BY_GROUND),
    };
    let turn = na::UnitQuaternion::rotation_between(&up, &Vec3::z())?;
    Some((Pose::from_parts(na::Translation3::identity(), turn), by))
}

/// A cloud turned by a rotation (`turn`'s translation is ignored).
fn rotated(c: &RegCloud, turn: &Pose) -> RegCloud {
    let r = turn.rotation;
    let apply = |p: &[f64; 3]| {
        let v = r * Vec3::new(p[0], p[1], p[2]);
        [v.x, v.y, v.z]
    };
    RegCloud { pts: c.pts.iter().map(apply).collect(), normals: c.normals.iter().map(apply).collect() }
}

/// What a scanner saw, as the nearest range per direction bin, in the scan's
/// own frame (scanner at the origin), and the directions of its rays in each
/// bin. Used to reject alignments that put points where the scanner looked
/// straight through: a wrong alignment of repetitive geometry can overlap
/// well, but it cannot avoid floating in seen-through space.
pub struct RangeImage {
    bin_rad: f64,
    naz: usize,
    nel: usize,
    /// Per bin, the nearest range the scanner saw in it and its eight
    /// neighbours (worked out once: each check asks it).
    nearest_around: Vec<f32>,
    /// The unit directions of the scanner's points bin by bin: those of bin
    /// `k` are `rays[ray_start[k]..ray_start[k + 1]]`.
    ray_start: Vec<u32>,
    rays: Vec<[f32; 3]>,
}

impl RangeImage {
    pub fn new(pts: &[[f64; 3]], bin_deg: f64) -> RangeImage {
        let bin_rad = bin_deg.to_radians();
        let naz = (std::f64::consts::TAU / bin_rad).ceil() as usize;
        let nel = (std::f64::consts::PI / bin_rad).ceil() as usize + 1;
        let mut near = vec![f32::INFINITY; naz * nel];
        let mut im = RangeImage { bin_rad, naz, nel, nearest_around: vec![], ray_start: vec![], rays: vec![] };
        let binned: Vec<Option<(usize, f64)>> = pts.iter().map(|p| im.bin(p)).collect();
        let mut ray_start = vec![0u32; naz * nel + 1];
        for &(k, r) in binned.iter().flatten() {
            near[k] = near[k].min(r as f32);
            ray_start[k + 1] += 1;
        }
        for k in 0..naz * nel {
            ray_start[k + 1] += ray_start[k];
        }
        let mut filled = ray_start.clone();
        let mut rays = vec![[0.0f32; 3]; binned.iter().flatten().count()];
        for (p, b) in pts.iter().zip(&binned) {
            if let Some((k, r)) = *b {
                rays[filled[k] as usize] = [(p[0] / r) as f32, (p[1] / r) as f32, (p[2] / r) as f32];
                filled[k] += 1;
            }
        }
        im.nearest_around = (0..naz * nel)
            .map(|k| {
                let mut nearest = f32::INFINITY;
                im.around(k, |b| nearest = nearest.min(near[b]));
                nearest
            })
            .collect();
        im.ray_start = ray_start;
        im.rays = rays;
        im
    }

    #[inline]
    fn bin(&self, p: &[f64; 3]) -> Option<(usize, f64)> {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        if r < 0.5 {
            return None;
        }
        let az = p[1].atan2(p[0]).rem_euclid(std::f64::consts::TAU);
        let el = (p[2] / r).clamp(-1.0, 1.0).asin() + std::f64::consts::FRAC_PI_2;
        let i = ((az / self.bin_rad) as usize).min(self.naz - 1);
        let j = ((el / self.bin_rad) as usize).min(self.nel - 1);
        Some((j * self.naz + i, r))
    }

    /// The bins round the one `k` is in (its own and its eight neighbours,
    /// those that exist), passed to `f`.
    #[inline]
    fn around(&self, k: usize, mut f: impl FnMut(usize)) {
        let (i, j) = (k % self.naz, k / self.naz);
        for dj in -1i64..=1 {
            let jj = j as i64 + dj;
            if jj < 0 || jj >= self.nel as i64 {
                continue;
            }
            for di in -1i64..=1 {
                let ii = (i as i64 + di).rem_euclid(self.naz as i64) as usize;
                f(jj as usize * self.naz + ii);
            }
        }
    }

    /// Whether a point (in this scan's frame) lies clearly in front of everything
    /// the scanner saw around its direction, with one of the scanner's rays
    /// there passing within `reach_m` of it. A ray that passed farther off
    /// than half the width of what the point lies on may have passed beside
    /// it: a far scanner's coarse steps go both sides of a lamp post another
    /// scanner sees (infinite `reach_m`: any ray round its direction).
    #[inline]
    pub fn sees_through(&self, p: &[f64; 3], reach_m: f64) -> bool {
        let Some((k, r)) = self.bin(p) else {
            return false;
        };
        let nearest = self.nearest_around[k];
        if !(nearest.is_finite() && (r as f32) < nearest - (0.3 + 0.02 * r as f32)) {
            return false;
        }
        if reach_m.is_infinite() {
            return true;
        }
        let mut passed_by = false;
        self.around(k, |b| {
            passed_by = passed_by
                || self.rays[self.ray_start[b] as usize..self.ray_start[b + 1] as usize].iter().any(|d| {
                    let d = [f64::from(d[0]), f64::from(d[1]), f64::from(d[2])];
                    // The distance from p to the ray's line, |p × d|.
                    let c = [p[1] * d[2] - p[2] * d[1], p[2] * d[0] - p[0] * d[2], p[0] * d[1] - p[1] * d[0]];
                    c[0] * c[0] + c[1] * c[1] + c[2] * c[2] <= reach_m * reach_m
                })
        });
        passed_by
    }
}

/// How far round each point the seen-through check looks for its width (m).
pub const WIDTH_RADIUS_M: f64 = 0.5;

/// Half the width (m) across what each point of `checked` lies on: how
/// near another scanner's ray must pass it to count as having seen through
/// where it is ([`free_space_violations_within`]). From the points of
/// `cloud` (the same scan, in the same frame) within [`WIDTH_RADIUS_M`]:
/// the spread along their middle principal axis taken as a uniform width,
/// √(12 λ₂). A wire, a post or a pipe is narrow across its length, a wall
/// or the ground as wide as the radius allows. With fewer than five points
/// round a point its width is not known (infinite: any ray counts).
pub fn half_widths_m(checked: &RegCloud, cloud: &RegCloud) -> Vec<f64> {
    let grid = crate::grid::Grid::new(&cloud.pts, WIDTH_RADIUS_M);
    checked
        .pts
        .par_iter()
        .map(|p| {
            let mut around: Vec<[f64; 3]> = Vec::new();
            grid.for_each_within(p, WIDTH_RADIUS_M, |j, _| around.push(grid.points()[j as usize]));
            if around.len() < 5 {
                return f64::INFINITY;
            }
            let n = around.len() as f64;
            let mut mean = nalgebra::Vector3::zeros();
            for q in &around {
                mean += nalgebra::Vector3::from(*q);
            }
            mean /= n;
            let mut cov = nalgebra::Matrix3::zeros();
            for q in &around {
                let d = nalgebra::Vector3::from(*q) - mean;
                cov += d * d.transpose();
            }
            let mut l: Vec<f64> = nalgebra::SymmetricEigen::new(cov / n).eigenvalues.iter().copied().collect();
            l.sort_by(f64::total_cmp);
            (12.0 * l[1].max(0.0)).sqrt() / 2.0
        })
        .collect()
}

/// Share of `src` points (placed by `pose`) that some scan in `seen` (its range
/// image and its pose) saw straight through.
pub fn free_space_violations(src: &RegCloud, pose: &Pose, seen: &[(&RangeImage, Pose)]) -> f64 {
    seen_through_share(src, None, 0.0, pose, seen)
}

/// [`free_space_violations`], counting point `k` only where a ray of that
/// scanner passed within `reach_m[k]` of it ([`half_widths_m`]).
pub fn free_space_violations_within(src: &RegCloud, reach_m: &[f64], pose: &Pose, seen: &[(&RangeImage, Pose)]) -> f64 {
    seen_through_share(src, Some(reach_m), 0.0, pose, seen)
}

/// [`free_space_violations`] (`reach_m` `None`) or
/// [`free_space_violations_within`], counting only the points farther than
/// [`NEAR_SCANNER_M`] in plan from the scan's own scanner (its frame's
/// origin: scans in scanner coordinates), as a share of all its points.
pub fn free_space_violations_beyond(
    src: &RegCloud,
    reach_m: Option<&[f64]>,
    pose: &Pose,
    seen: &[(&RangeImage, Pose)],
) -> f64 {
    seen_through_share(src, reach_m, NEAR_SCANNER_M, pose, seen)
}

/// The share of `src`'s points some scanner of `seen` saw through, those
/// within `beyond_m` in plan of `src`'s frame's origin not counted.
fn seen_through_share(
    src: &RegCloud,
    reach_m: Option<&[f64]>,
    beyond_m: f64,
    pose: &Pose,
    seen: &[(&RangeImage, Pose)],
) -> f64 {
    if src.pts.is_empty() || seen.is_empty() {
        return 0.0;
    }
    let inv: Vec<(&RangeImage, Pose)> = seen.iter().map(|(im, p)| (*im, p.inverse())).collect();
    let bad: usize = (0..src.pts.len().div_ceil(BLOCK))
        .into_par_iter()
        .map(|b| {
            let mut n = 0;
            for k in b * BLOCK..((b + 1) * BLOCK).min(src.pts.len()) {
                if beyond_m > 0.0 && src.pts[k][0].hypot(src.pts[k][1]) <= beyond_m {
                    continue;
                }
                let q = tf(pose, &src.pts[k]);
                let reach = reach_m.map_or(f64::INFINITY, |r| r[k]);
                if inv.iter().any(|(im, pi)| im.sees_through(&tf(pi, &q), reach)) {
                    n += 1;
                }
            }
            n
        })
        .collect::<Vec<_>>()
        .iter()
        .sum();
    bad as f64 / src.pts.len() as f64
}

/// How many of a scan's points the scanners of a list saw through: in all,
/// and, scanner by scanner, those no other scanner of the list saw through
/// (so that the share without one scanner is known without counting again).
#[derive(Debug, Clone, PartialEq)]
pub struct SeenThrough {
    pub points: usize,
    pub any: usize,
    /// Per scanner of the list: the points only it saw through.
    pub only: Vec<usize>,
}

impl SeenThrough {
    /// The share (0..1) of the points some scanner saw through.
    pub fn share(&self) -> f64 {
        if self.points == 0 { 0.0 } else { self.any as f64 / self.points as f64 }
    }

    /// The share some scanner saw through, scanner `left_out` of the list
    /// left out.
    pub fn share_without(&self, left_out: Option<usize>) -> f64 {
        let any = self.any - left_out.map_or(0, |k| self.only[k]);
        if self.points == 0 { 0.0 } else { any as f64 / self.points as f64 }
    }
}

/// [`free_space_violations`] (infinite `reach_m`) or
/// [`free_space_violations_within`], as counts per scanner of `seen`.
pub fn seen_through_counts(
    src: &RegCloud,
    reach_m: Option<&[f64]>,
    pose: &Pose,
    seen: &[(&RangeImage, Pose)],
) -> SeenThrough {
    let inv: Vec<(&RangeImage, Pose)> = seen.iter().map(|(im, p)| (*im, p.inverse())).collect();
    let blocks: Vec<(usize, Vec<usize>)> = (0..src.pts.len().div_ceil(BLOCK))
        .into_par_iter()
        .map(|b| {
            let (mut any, mut only) = (0, vec![0; inv.len()]);
            for k in b * BLOCK..((b + 1) * BLOCK).min(src.pts.len()) {
                let q = tf(pose, &src.pts[k]);
                let reach = reach_m.map_or(f64::INFINITY, |r| r[k]);
                let mut by = inv.iter().enumerate().filter(|(_, (im, pi))| im.sees_through(&tf(pi, &q), reach));
                if let Some((first, _)) = by.next() {
                    any += 1;
                    if by.next().is_none() {
                        only[first] += 1;
                    }
                }
            }
            (any, only)
        })
        .collect();
    let mut counts = SeenThrough { points: src.pts.len(), any: 0, only: vec![0; seen.len()] };
    for (any, only) in blocks {
        counts.any += any;
        for (total, n) in counts.only.iter_mut().zip(only) {
            *total += n;
        }
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn station_offset_in_plan_height_and_yaw() {
        let station = liftplan_core::frame::pose_xyz_yaw(10.0, 20.0, 1.5, 350f64.to_radians());
        let placed = liftplan_core::frame::pose_xyz_yaw(13.0, 24.0, 1.0, 10f64.to_radians());
        let o = StationOffset::between(&station, &placed);
        // 20 degrees across north, not 340.
        assert!((o.plan_m - 5.0).abs() < 1e-12 && (o.height_m - 0.5).abs() < 1e-12 && (o.yaw_deg - 20.0).abs() < 1e-9);
        let held = |plan_m, height_m, yaw_deg| StationTolerance { plan_m, height_m, yaw_deg };
        assert!(o.within(&held(5.0, Some(0.5), Some(20.0 + 1e-6))));
        assert!(!o.within(&held(4.9, None, None)));
        assert!(!o.within(&held(5.0, Some(0.4), None)));
        assert!(!o.within(&held(5.0, None, Some(19.0))));
        // What the station does not give is not held.
        assert!(o.within(&held(5.0, None, None)));
    }

    #[test]
    fn scans_placed_after_an_unconfirmed_survey_are_not_merged() {
        let inputs: Vec<RegInput> = (0..4)
            .map(|k| RegInput {
                name: format!("s{k}"),
                fine: RegCloud::default(),
                coarse: FeatureCloud::default(),
                initial: None,
                held: None,
            })
            .collect();
        let placed = |registered| {
            Some(RegResult {
                pose: Pose::identity(),
                fitness: 0.5,
                rmse_m: 0.0,
                method: "m".into(),
                registered,
                hold_m: None,
                refined_move_m: None,
                warning: None,
            })
        };
        // s2, then s1 at its station, then s3.
        let order = [2, 1, 3];
        let surveyed_only = [None, Some(0.01), None, None];
        let mut results = vec![placed(true), placed(true), placed(true), placed(true)];
        confirm_surveys(&order, &surveyed_only, &mut results, &inputs, 0.02);
        assert!(results.iter().all(|r| r.as_ref().unwrap().registered), "a confirmed survey refuses nothing");
        let registered = |results: &[Option<RegResult>]| -> Vec<bool> {
            results.iter().map(|r| r.as_ref().unwrap().registered).collect()
        };
        // Refused for another reason (e.g. too far from its station).
        results[1] = placed(false);
        confirm_surveys(&order, &surveyed_only, &mut results, &inputs, 0.02);
        assert_eq!(
            registered(&results),
            [true, false, true, false],
            "only the scan placed after s1 is refused with it"
        );
        let why = results[3].as_ref().unwrap().warning.as_deref().unwrap();
        assert!(why.starts_with("scan 's3' is not merged: it was placed while scan 's1' stood"), "{why}");
        // Overlapping the others too little even when aligned with them all.
        let mut results = vec![placed(true), placed(true), placed(true), placed(true)];
        results[1].as_mut().unwrap().fitness = 0.015;
        confirm_surveys(&order, &surveyed_only, &mut results, &inputs, 0.02);
        assert_eq!(registered(&results), [true, false, true, false]);
        let own = results[1].as_ref().unwrap().warning.as_deref().unwrap();
        assert!(own.contains("(1.0 %, at least 2.0 % required)") && own.contains("overlaps them by 1.5 %"), "{own}");
    }

    /// Points 0.1 m apart on the faces of the box `lo`..`hi` whose outward
    /// normal is among `faces` (axis, sign), starting `phase` into the grid.
    fn box_faces(lo: [f64; 3], hi: [f64; 3], faces: &[(usize, f64)], phase: f64) -> RegCloud {
        let mut c = RegCloud::default();
        for &(axis, sign) in faces {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let steps = |a: usize| ((hi[a] - lo[a] - phase) / 0.1) as usize;
            for i in 0..=steps(u) {
                for k in 0..=steps(v) {
                    let mut p = [0.0; 3];
                    p[axis] = if sign > 0.0 { hi[axis] } else { lo[axis] };
                    p[u] = lo[u] + phase + 0.1 * i as f64;
                    p[v] = lo[v] + phase + 0.1 * k as f64;
                    let mut n = [0.0; 3];
                    n[axis] = sign;
                    c.pts.push(p);
                    c.normals.push(n);
                }
            }
        }
        c
    }

    /// Scans `s0`, `s1`... of `clouds`, none held by a station.
    fn unheld_inputs(clouds: &[RegCloud]) -> Vec<RegInput> {
        clouds
            .iter()
            .enumerate()
            .map(|(k, c)| RegInput {
                name: format!("s{k}"),
                fine: c.clone(),
                coarse: FeatureCloud::default(),
                initial: None,
                held: None,
            })
            .collect()
    }

    #[test]
    fn scans_placed_before_a_survey_are_checked_as_one() {
        // Two scans placed before a scan placed by its survey, each seeing
        // one wall and the roof of a shed (neither alone pins it in plan),
        // and that scan seeing all of it.
        let shed = ([0.0, 0.0, 0.0], [4.0, 3.0, 2.5]);
        let all_faces = [(0, -1.0), (0, 1.0), (1, -1.0), (1, 1.0), (2, 1.0)];
        let clouds = [
            box_faces(shed.0, shed.1, &[(0, -1.0), (2, 1.0)], 0.0),
            box_faces(shed.0, shed.1, &[(1, 1.0), (2, 1.0)], 0.0),
            box_faces(shed.0, shed.1, &all_faces, 0.05),
        ];
        let inputs = unheld_inputs(&clouds);
        let s = RegistrationSettings::default();
        let before = [Some(Pose::identity()), Some(Pose::identity()), None];
        let verdict = |survey_error: Pose| {
            let after = [None, None, Some(survey_error)];
            let (correction, fit) = align_as_one(&inputs, &clouds, &clouds, &before, &after, &s);
            (correction, survey_disagreement(&inputs, &before, &correction, fit, s.min_fitness))
        };
        let (correction, why) = verdict(Pose::identity());
        assert!(why.is_none(), "a right survey: {why:?} ({correction:?})");
        // Along the wall the reference sees: only the other scan pins that.
        let (correction, why) = verdict(liftplan_core::frame::pose_xyz_yaw(0.0, 0.3, 0.0, 0.0));
        assert!((correction.translation.y - 0.3).abs() < 0.01, "{correction:?}");
        let why = why.expect("a survey 0.3 m off is refused");
        assert!(
            why.starts_with("the scans placed before it ('s0', 's1'), aligned with them as one, move 0.3")
                && why.contains("overlapping them by"),
            "{why}"
        );
        let (_, why) = verdict(liftplan_core::frame::pose_xyz_yaw(0.0, 0.0, 0.0, 0.5_f64.to_radians()));
        assert!(why.is_some_and(|w| w.contains("degrees in yaw")), "a survey turned 0.5 degrees is refused");
        // Far from them: nothing to align by, so nothing confirms the survey.
        let (_, why) = verdict(liftplan_core::frame::pose_xyz_yaw(30.0, 0.0, 0.0, 0.0));
        assert!(why.is_some_and(|w| w.contains("overlap them by 0.0 %")), "no overlap is refused");
    }

    /// The last alignment of a scan against all the others brings one the
    /// scans before it placed off back, and how far it moved the scan's
    /// points is said: a warning past 0.05 m, not merged past 0.18 m.
    #[test]
    fn a_scan_the_last_alignment_moves_far_is_warned_of_or_not_merged() {
        let shed = ([0.0, 0.0, 0.0], [4.0, 3.0, 2.5]);
        let all_faces = [(0, -1.0), (0, 1.0), (1, -1.0), (1, 1.0), (2, 1.0)];
        let clouds = [box_faces(shed.0, shed.1, &all_faces, 0.0), box_faces(shed.0, shed.1, &all_faces, 0.05)];
        let inputs = unheld_inputs(&clouds);
        let s = RegistrationSettings::default();
        let moved = |off: Pose| {
            let mut poses = [Some(Pose::identity()), Some(off)];
            let refined = refine(&inputs, &clouds, &clouds, &mut poses, &[1], &s);
            let back = refined[0].0;
            assert!(back.translation.vector.norm() < 0.005, "placed {off:?}, refined to {back:?}");
            moved_up_to_m(&clouds[1], &off, &back)
        };
        let off = |x: f64| liftplan_core::frame::pose_xyz_yaw(x, 0.0, 0.0, 0.0);
        let m = moved(off(0.01));
        assert!((m - 0.01).abs() < 0.005 && refined_move_said("s1", m, false).is_none(), "{m}");
        let m = moved(off(0.08));
        assert!((m - 0.08).abs() < 0.005, "{m}");
        let warned = refined_move_said("s1", m, false).unwrap().unwrap();
        assert!(
            warned.starts_with("scan 's1' moved up to 0.08 m when aligned against all the other scans at the end"),
            "{warned}"
        );
        let m = moved(off(0.2));
        assert!((m - 0.2).abs() < 0.005, "{m}");
        let refused = refined_move_said("s1", m, false).unwrap().unwrap_err();
        assert!(refused.starts_with("scan 's1' is not merged: aligned against all the other scans at the end, it moved up to 0.20 m from where the scans placed before it put it (at most 0.18 m allowed)") && refused.ends_with("give the surveyed poses of the stations in the station file, or rescan from where more of the site is in view"), "{refused}");
        let held = refined_move_said("s1", m, true).unwrap().unwrap_err();
        assert!(
            held.ends_with(
                "; check its station's survey and the others', or rescan from where more of the site is in view"
            ),
            "{held}"
        );
        // A turn moves the points far from where it turns about the most.
        let turned = liftplan_core::frame::pose_xyz_yaw(0.0, 0.0, 0.0, 1f64.to_radians());
        let reach = clouds[1].pts.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
        let far = 2.0 * reach * 0.5f64.to_radians().sin();
        assert!(reach > 4.9 && (moved_up_to_m(&clouds[1], &Pose::identity(), &turned) - far).abs() < 1e-9);
    }

    /// Two scans placed off together, overlapping the reference little and
    /// each other much, come back when all are aligned as one; aligned one
    /// at a time against the others, each follows the other's error.
    #[test]
    fn scans_off_together_come_back_when_all_are_aligned_as_one() {
        let shed = |x: f64| ([x, 0.0, 0.0], [x + 4.0, 3.0, 2.5]);
        let all_faces = [(0, -1.0), (0, 1.0), (1, -1.0), (1, 1.0), (2, 1.0)];
        let (a, b, c) = (shed(0.0), shed(6.0), shed(12.0));
        // The reference sees the second shed's west and south walls and roof.
        let reference = joined(&[
            box_faces(a.0, a.1, &all_faces, 0.0),
            box_faces(b.0, b.1, &[(0, -1.0), (1, -1.0), (2, 1.0)], 0.0),
        ]);
        let other =
            |phase: f64| joined(&[box_faces(b.0, b.1, &all_faces, phase), box_faces(c.0, c.1, &all_faces, phase)]);
        let clouds = [reference, other(0.03), other(0.06)];
        let inputs = unheld_inputs(&clouds);
        let fine = [0.25, 0.1];
        let off = liftplan_core::frame::pose_xyz_yaw(0.02, -0.02, 0.01, 0.001);
        let worst = |poses: &[Option<Pose>]| {
            (1..3).map(|j| moved_up_to_m(&clouds[j], &Pose::identity(), &poses[j].unwrap())).fold(0.0, f64::max)
        };
        let start = [Some(Pose::identity()), Some(off), Some(off)];
        assert!(worst(&start) > 0.02, "{}", worst(&start));
        let mut one_at_a_time = start;
        for j in [1, 2] {
            let others = model_of(&inputs, &one_at_a_time, Some(j));
            one_at_a_time[j] = Some(icp(&clouds[j], &others, one_at_a_time[j].unwrap(), &fine));
        }
        assert!(worst(&one_at_a_time) > 0.005, "one at a time: {}", worst(&one_at_a_time));
        let mut as_one = start;
        align_all_as_one(&inputs, &clouds, &mut as_one, &[1, 2], &fine);
        assert!(worst(&as_one) < 0.001, "as one: {}", worst(&as_one));
        assert_eq!(as_one[0], Some(Pose::identity()), "the reference does not move");
    }

    /// ICP finds the same pose for a scan of a room's corner whether the
    /// site frame is near the corner or in survey coordinates 5,400 km away
    /// (where rotations about the site's origin, as it linearised them
    /// before, are all but translations and the scans did not register).
    #[test]
    fn icp_finds_the_pose_as_well_in_survey_coordinates() {
        let mut site: Vec<([f64; 3], [f64; 3])> = Vec::new();
        for i in 0..40 {
            for j in 0..40 {
                let (a, b) = (0.5 + 0.25 * i as f64, 0.5 + 0.25 * j as f64);
                site.push(([a, b, 0.0], [0.0, 0.0, 1.0]));
                if b < 5.0 {
                    site.push(([0.0, a, b], [1.0, 0.0, 0.0]));
                    site.push(([a, 0.0, b], [0.0, 1.0, 0.0]));
                }
            }
        }
        let scanner = liftplan_core::frame::pose_xyz_yaw(4.0, 3.0, 1.5, 0.7);
        let to_scan = scanner.inverse();
        let src = RegCloud {
            pts: site.iter().map(|(p, _)| tf(&to_scan, p)).collect(),
            normals: site
                .iter()
                .map(|(_, n)| {
                    let m = to_scan.rotation * Vec3::new(n[0], n[1], n[2]);
                    [m.x, m.y, m.z]
                })
                .collect(),
        };
        let nudge = Pose::from_parts(
            na::Translation3::new(0.25, -0.2, 0.1),
            na::UnitQuaternion::from_euler_angles(0.01, -0.01, 0.05),
        );
        for offset in [[0.0; 3], [512_345.0, 5_412_345.0, 102.0]] {
            let shift = Pose::from_parts(
                na::Translation3::new(offset[0], offset[1], offset[2]),
                na::UnitQuaternion::identity(),
            );
            let target = Target::new(
                site.iter().map(|(p, _)| [p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]]).collect(),
                site.iter().map(|(_, n)| *n).collect(),
            );
            let truth = shift * scanner;
            let found = icp(&src, &target, shift * nudge * scanner, &[1.0, 0.5, 0.25, 0.1]);
            let off_m = (found.translation.vector - truth.translation.vector).norm();
            let off_rad = found.rotation.angle_to(&truth.rotation);
            assert!(off_m < 1e-4 && off_rad < 1e-6, "offset {offset:?}: {off_m} m, {off_rad} rad from the truth");
        }
    }

    #[test]
    fn kabsch_recovers_a_transform() {
        let t = liftplan_core::frame::pose_xyz_yaw(3.0, -2.0, 0.5, 1.1);
        let a: Vec<[f64; 3]> = (0..20)
            .map(|i| {
                let x = i as f64;
                [x.sin() * 4.0, (x * 1.7).cos() * 3.0, (x * 0.3).sin()]
            })
            .collect();
        let b: Vec<[f64; 3]> = a.iter().map(|p| tf(&t, p)).collect();
        for leveled in [true, false] {
            let p = fit_rigid(&a, &b, leveled).unwrap();
            assert!((p.translation.vector - t.translation.vector).norm() < 1e-9);
            assert!(p.rotation.angle_to(&t.rotation) < 1e-9);
        }
    }

    /// A site on a 5 % slope with walls facing two ways, seen by a scanner
    /// tilted 4 and -3 degrees: levelled by the walls, to within 0.05
    /// degrees of true, where the ground would leave it on the slope; walls
    /// facing one way only leave it to the ground.
    #[test]
    fn levelling_takes_the_vertical_from_plumb_surfaces_before_the_ground() {
        let slope = 0.05f64;
        let ground_n = Vec3::new(-slope, 0.0, 1.0).normalize();
        let mut true_cloud = RegCloud::default();
        for i in 0..400 {
            let (x, y) = ((i % 20) as f64, (i / 20) as f64);
            true_cloud.pts.push([x, y, slope * x]);
            true_cloud.normals.push([ground_n.x, ground_n.y, ground_n.z]);
        }
        let walls = |cloud: &mut RegCloud, normals: &[[f64; 3]]| {
            for (k, n) in normals.iter().enumerate() {
                for i in 0..150 {
                    cloud.pts.push([k as f64 * 10.0, i as f64 * 0.1, 1.0 + (i % 7) as f64]);
                    cloud.normals.push(*n);
                }
            }
        };
        let mut one_way = true_cloud.clone();
        walls(&mut true_cloud, &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-0.6, 0.8, 0.0]]);
        walls(&mut one_way, &[[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]]);
        let tilt = na::UnitQuaternion::from_euler_angles(4f64.to_radians(), -3f64.to_radians(), 0.0);
        let tilted = |c: &RegCloud| rotated(c, &Pose::from_parts(na::Translation3::identity(), tilt));
        let error_deg = |c: &RegCloud| {
            let (level, by) = levelling(&tilted(c)).expect("levelled");
            ((level.rotation * tilt) * Vec3::z()).angle(&Vec3::z()).to_degrees()
                + if by.starts_with("its plumb") { 0.0 } else { 1000.0 }
        };
        assert!(error_deg(&true_cloud) < 0.05, "{}", error_deg(&true_cloud));
        let (level, by) = levelling(&tilted(&one_way)).expect("levelled by the ground");
        assert!(by.starts_with("its ground"), "{by}");
        let off = ((level.rotation * tilt) * Vec3::z()).angle(&Vec3::z()).to_degrees();
        assert!((off - slope.atan().to_degrees()).abs() < 0.05, "on the slope: {off} degrees");
        assert!(levelling(&RegCloud::default()).is_none());
    }

    /// A scanner whose 0.4 degree steps hit a wall 50 m off passes both
    /// sides of a post 0.15 m wide at 40 m (its rays there 0.28 m apart):
    /// a point on the post is seen through only by a ray passing within
    /// half the post's width of it, as one on a wall floating there is by
    /// any ray near it.
    #[test]
    fn a_ray_counts_as_seeing_through_a_point_only_where_it_passes_within_half_its_width() {
        let step = 0.4f64.to_radians();
        let mut wall = Vec::new();
        for i in -40..=40 {
            for k in -20..=20 {
                let (az, el) = (f64::from(i) * step, f64::from(k) * step);
                let r = 50.0 / (az.cos() * el.cos());
                wall.push([r * el.cos() * az.cos(), r * el.cos() * az.sin(), r * el.sin()]);
            }
        }
        let image = RangeImage::new(&wall, 0.5);
        // Half-way between two columns of rays, 0.14 m from each.
        let between = {
            let az = 2.5 * step;
            [40.0 * az.cos(), 40.0 * az.sin(), 0.0]
        };
        let on_a_ray = {
            let az = 2.0 * step;
            [40.0 * az.cos(), 40.0 * az.sin(), 0.0]
        };
        assert!(image.sees_through(&between, f64::INFINITY), "any ray round its direction");
        assert!(!image.sees_through(&between, 0.075), "a post 0.15 m wide the rays passed beside");
        assert!(image.sees_through(&between, 0.15), "something 0.3 m wide a ray would have hit");
        assert!(image.sees_through(&on_a_ray, 0.001), "a ray through the point itself");
        assert!(!image.sees_through(&[55.0, 0.0, 0.0], f64::INFINITY), "behind the wall");
        assert!(!image.sees_through(&[-40.0, 0.0, 0.0], f64::INFINITY), "where the scanner saw nothing");

        // Widths: a post (a column of points 0.15 m across), a wall, and a
        // point alone.
        let mut cloud = RegCloud::default();
        for i in 0..200 {
            let z = f64::from(i) * 0.01;
            for dx in [-0.075, -0.05, -0.025, 0.0, 0.025, 0.05, 0.075] {
                cloud.pts.push([10.0 + dx, 0.0, z]);
            }
        }
        for i in 0..40 {
            for k in 0..40 {
                cloud.pts.push([20.0, f64::from(i) * 0.05, f64::from(k) * 0.05]);
            }
        }
        cloud.pts.push([30.0, 0.0, 0.0]);
        cloud.normals = vec![[0.0; 3]; cloud.pts.len()];
        let reach_m = half_widths_m(
            &RegCloud { pts: vec![[10.0, 0.0, 1.0], [20.0, 1.0, 1.0], [30.0, 0.0, 0.0]], normals: vec![[0.0; 3]; 3] },
            &cloud,
        );
        assert!((reach_m[0] - 0.075).abs() < 0.02, "the post's half width: {}", reach_m[0]);
        assert!(reach_m[1] > 0.35, "a wall's is the radius': {}", reach_m[1]);
        assert!(reach_m[2].is_infinite(), "a point alone: not known, any ray counts");

        // The shares: any ray round a point counts, or only one within its
        // reach; infinite reaches count as any ray does.
        let checked = RegCloud { pts: vec![between, on_a_ray], normals: vec![[0.0; 3]; 2] };
        let seen = [(&image, Pose::identity())];
        let at = Pose::identity();
        assert_eq!(free_space_violations(&checked, &at, &seen), 1.0);
        assert_eq!(free_space_violations_within(&checked, &[f64::INFINITY; 2], &at, &seen), 1.0);
        assert_eq!(free_space_violations_within(&checked, &[0.075, 0.075], &at, &seen), 0.5);
    }

    /// A trial kept in the memo reads back as written, its near misses
    /// included; cut short anywhere, it reads as nothing (worked out again).
    #[test]
    fn a_trial_reads_back_as_written_and_not_at_all_when_cut_short() {
        let at = liftplan_core::frame::pose_xyz_yaw(51.7, 10.2, 0.1, 77.3f64.to_radians());
        let trial = Trial {
            passing: vec![Passed {
                pose: at,
                fit: 0.514,
                viol: 0.0,
                method: "plan-view correlation + ICP".into(),
                hold: PlanHold {
                    pairs: 4321,
                    least: 0.027,
                    weakest: [0.6, -0.8, 0.0],
                    middle: [50.2, 12.0],
                    spread_m: 7.5,
                },
            }],
            closest: (0.514, 0.0),
            at_station: Some((0.2, 0.001)),
            held_back: Some((0.3, 0.002, StationOffset { plan_m: 7.7, height_m: 0.1, yaw_deg: 61.0 })),
            near_misses: vec![(at, 0.252), (Pose::identity(), 0.03)],
        };
        let bytes = trial.encode();
        let back = Trial::decode(&bytes).expect("read back");
        assert_eq!(back.encode(), bytes);
        assert_eq!(back.near_misses.len(), 2);
        for cut in 0..bytes.len() {
            assert!(Trial::decode(&bytes[..cut]).is_none(), "cut at {cut}");
        }
    }

    /// The counts per scanner say what share is left with one scanner left
    /// out: a point two scanners saw through stays counted without either.
    #[test]
    fn a_share_without_one_scanner_counts_the_points_only_it_saw_through() {
        // Two scanners, 10 m apart along y, each seeing a wall 50 m off along
        // x over +-16 degrees.
        let wall = || {
            let mut pts = Vec::new();
            for i in -40..=40 {
                for k in -20..=20 {
                    let (az, el) = (f64::from(i) * 0.4f64.to_radians(), f64::from(k) * 0.4f64.to_radians());
                    let r = 50.0 / (az.cos() * el.cos());
                    pts.push([r * el.cos() * az.cos(), r * el.cos() * az.sin(), r * el.sin()]);
                }
            }
            pts
        };
        let (a, b) = (RangeImage::new(&wall(), 0.5), RangeImage::new(&wall(), 0.5));
        let seen = [(&a, Pose::identity()), (&b, liftplan_core::frame::pose_xyz_yaw(0.0, 10.0, 0.0, 0.0))];
        // In the site frame: one point in front of both walls' views, one
        // only scanner `a` sees past (outside `b`'s 16 degrees), one behind
        // the wall, one off to the side neither saw.
        let pts = vec![[40.0, 5.0, 0.0], [40.0, -8.0, 0.0], [55.0, 5.0, 0.0], [0.0, -40.0, 0.0]];
        let cloud = RegCloud { normals: vec![[0.0; 3]; pts.len()], pts };
        let counts = seen_through_counts(&cloud, None, &Pose::identity(), &seen);
        assert_eq!(counts, SeenThrough { points: 4, any: 2, only: vec![1, 0] });
        assert_eq!(counts.share(), free_space_violations(&cloud, &Pose::identity(), &seen));
        assert_eq!(counts.share_without(None), 0.5);
        assert_eq!(counts.share_without(Some(0)), 0.25, "the point both saw through stays");
        assert_eq!(counts.share_without(Some(1)), 0.5);
    }

    #[test]
    fn what_stood_beside_a_scanner_is_left_out_of_the_share_beyond_it() {
        // Another scanner 30 m off along x looks back at a wall 5 m behind
        // the checked scan's scanner (at x = -5): it saw through everything
        // in front of the wall.
        let mut wall = Vec::new();
        for i in -40..=40 {
            for k in -20..=20 {
                let (az, el) = (f64::from(i) * 0.4f64.to_radians(), f64::from(k) * 0.4f64.to_radians());
                let r = 35.0 / (az.cos() * el.cos());
                wall.push([-r * el.cos() * az.cos(), -r * el.cos() * az.sin(), r * el.sin()]);
            }
        }
        let image = RangeImage::new(&wall, 0.5);
        let seen = [(&image, liftplan_core::frame::pose_xyz_yaw(30.0, 0.0, 0.0, 0.0))];
        // The checked scan, in its own frame (its scanner at the origin): a
        // person 4 m off, where the other scanner saw through; the wall
        // behind it; a point 12 m off where the other saw through too.
        let mut pts: Vec<[f64; 3]> = (0..18).map(|k| [4.0, 0.0, -1.5 + 0.1 * f64::from(k)]).collect();
        pts.extend((0..80).map(|k| [-5.0, -4.0 + 0.1 * f64::from(k), 0.0]));
        let person_only = RegCloud { normals: vec![[0.0; 3]; pts.len()], pts: pts.clone() };
        let all = free_space_violations(&person_only, &Pose::identity(), &seen);
        assert_eq!(all, 18.0 / 98.0, "the person is where the other scanner saw through");
        assert_eq!(free_space_violations_beyond(&person_only, None, &Pose::identity(), &seen), 0.0);
        pts.push([12.0, 0.0, 0.0]);
        let also_far = RegCloud { normals: vec![[0.0; 3]; pts.len()], pts };
        assert_eq!(free_space_violations_beyond(&also_far, None, &Pose::identity(), &seen), 1.0 / 99.0);
        // Within half the width: the rays pass 0.01 m from a point 12 m off.
        let reach = vec![0.01; also_far.pts.len()];
        assert_eq!(free_space_violations_beyond(&also_far, Some(&reach), &Pose::identity(), &seen), 1.0 / 99.0);
        // Placed elsewhere, the scan's points are counted where they lie,
        // but which lie beyond is still measured from its own scanner.
        let moved = liftplan_core::frame::pose_xyz_yaw(0.0, 0.0, 0.5, 0.0);
        assert_eq!(free_space_violations_beyond(&person_only, None, &moved, &seen), 0.0);
        // The check: over the share, overlapping well, nothing beyond: passes;
        // overlapping less than NARROW_LEAST_FIT, or with its frame not its
        // scanner's, it does not.
        let check = |fit: f64, at_origin: bool| {
            SeenCheck::of(&person_only, || &reach[..98], at_origin, &Pose::identity(), fit, None, &seen, 0.005)
        };
        let well = check(0.8, true);
        assert_eq!((well.any, well.beyond), (18.0 / 98.0, Some(0.0)));
        assert!(well.passes(0.005));
        assert!(!check(0.5, true).passes(0.005));
        assert!(!check(0.8, false).passes(0.005));
        let far = SeenCheck::of(&also_far, || &reach, true, &Pose::identity(), 0.8, None, &seen, 0.005);
        assert_eq!(far.beyond, Some(1.0 / 99.0));
        assert!(!far.passes(0.005), "1 % beyond 8 m is over the 0.5 % allowed");
    }

    /// Points every 0.1 m over surfaces, with their normals: a wall from
    /// `a` to `b` in plan (normal to its left), 6 m high; a tank's side,
    /// radius 3 m about (cx, cy), between two bearings; ground over a
    /// square.
    fn wall(a: [f64; 2], b: [f64; 2]) -> RegCloud {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        let normal = [-dy / len, dx / len, 0.0];
        let mut c = RegCloud::default();
        for i in 0..=(len * 10.0) as usize {
            for k in 0..60 {
                let t = i as f64 / (len * 10.0);
                c.pts.push([a[0] + t * dx, a[1] + t * dy, 0.1 * k as f64]);
                c.normals.push(normal);
            }
        }
        c
    }

    fn tank_side(cx: f64, cy: f64, from_deg: f64, to_deg: f64) -> RegCloud {
        let mut c = RegCloud::default();
        let steps = ((to_deg - from_deg).to_radians() * 3.0 * 10.0) as usize;
        for i in 0..=steps {
            let a = (from_deg + (to_deg - from_deg) * i as f64 / steps as f64).to_radians();
            for k in 0..60 {
                c.pts.push([cx + 3.0 * a.cos(), cy + 3.0 * a.sin(), 0.1 * k as f64]);
                c.normals.push([a.cos(), a.sin(), 0.0]);
            }
        }
        c
    }

    fn ground(half_m: f64) -> RegCloud {
        let mut c = RegCloud::default();
        let n = (half_m * 10.0) as i64;
        for i in -n..=n {
            for k in -n..=n {
                c.pts.push([0.1 * i as f64, 0.1 * k as f64, 0.0]);
                c.normals.push([0.0, 0.0, 1.0]);
            }
        }
        c
    }

    fn joined(parts: &[RegCloud]) -> RegCloud {
        let mut c = RegCloud::default();
        for p in parts {
            c.pts.extend(&p.pts);
            c.normals.extend(&p.normals);
        }
        c
    }

    /// What a scan shares with the model holds it firmly in plan where its
    /// walls face several ways, and not along a way they leave free: a
    /// tank's side turns onto itself about its axis, parallel walls slide
    /// along themselves, ground holds nothing in plan.
    #[test]
    fn a_tank_s_side_or_parallel_walls_hold_a_scan_loosely() {
        let hold = |c: &RegCloud| {
            let model = Target::new(c.pts.clone(), c.normals.clone());
            // The scan a centimetre off where it fits: the pairs are the same.
            plan_hold(c, &model, &liftplan_core::frame::pose_xyz_yaw(0.01, 0.0, 0.0, 0.0), 0.25, 0.03)
        };
        let corner = hold(&joined(&[ground(10.0), wall([-8.0, -8.0], [8.0, -8.0]), wall([-8.0, 8.0], [-8.0, -8.0])]));
        assert!(corner.slide_per_cm_m() < 0.05, "{corner:?}");

        // Open on the far side (a bearing of 30 to 150 degrees seen): the
        // weakest way turns about the axis, a shift of the pairs' middle.
        let tank = hold(&joined(&[ground(10.0), tank_side(2.0, -1.0, 30.0, 150.0)]));
        assert!(tank.slide_per_cm_m() > 10.0 * LOOSE_HOLD_SLIDE_M, "{tank:?}");
        // The side's middle lies north of the axis: a turn about the axis
        // is a turn about the middle with a shift east, none north.
        assert!(tank.weakest[0].abs() > 0.5 && tank.weakest[2].abs() < 0.01, "{tank:?}");
        // With a wall across the open side, the turn is held.
        let tank_and_wall =
            hold(&joined(&[ground(10.0), tank_side(2.0, -1.0, 30.0, 150.0), wall([-6.0, 6.0], [8.0, 8.0])]));
        assert!(tank_and_wall.slide_per_cm_m() < LOOSE_HOLD_SLIDE_M, "{tank_and_wall:?}");

        let corridor = hold(&joined(&[ground(10.0), wall([-9.0, -4.0], [9.0, -4.0]), wall([9.0, 4.0], [-9.0, 4.0])]));
        assert!(corridor.slide_per_cm_m() > 100.0, "{corridor:?}");
        assert!((corridor.weakest[1].abs() - 1.0).abs() < 1e-6, "a slide east: {corridor:?}");

        let flat = hold(&ground(10.0));
        assert_eq!(flat.pairs, 0);
        assert!(flat.slide_per_cm_m().is_infinite());
    }

    /// A station pins down the way what a scan shares holds loosely only
    /// as closely as its tolerance: a shift moves the scanner, and a turn
    /// about the shared structure's middle both moves and turns it. The
    /// room is counted from where the scan is placed, either way.
    #[test]
    fn a_station_pins_a_loose_way_down_to_its_tolerance() {
        let tolerance = |plan_m, yaw_deg| StationTolerance { plan_m, height_m: None, yaw_deg };
        let slide_east = PlanHold { pairs: 100, least: 0.0, weakest: [0.0, 1.0, 0.0], middle: [0.0; 2], spread_m: 5.0 };
        let at = |x: f64, y: f64| liftplan_core::frame::pose_xyz_yaw(x, y, 0.0, 0.0);
        let turned = |x: f64, y: f64, deg: f64| liftplan_core::frame::pose_xyz_yaw(x, y, 0.0, deg.to_radians());
        let station = at(10.0, 0.0);
        let room = |hold: &PlanHold, placed: &Pose, t: &StationTolerance| hold.within_station_m(placed, &station, t);
        assert!((room(&slide_east, &at(10.0, 0.0), &tolerance(0.5, Some(2.0))) - 0.5).abs() < 1e-12);
        // Placed 0.3 m east of its station: it may lie 0.8 m west of there.
        assert!((room(&slide_east, &at(10.3, 0.0), &tolerance(0.5, Some(2.0))) - 0.8).abs() < 1e-12);
        assert!((room(&slide_east, &at(9.7, 0.0), &tolerance(0.5, Some(2.0))) - 0.8).abs() < 1e-12);
        // 0.3 m north of it: the chord east and west of there, 0.4 m each way.
        assert!((room(&slide_east, &at(10.0, 0.3), &tolerance(0.5, Some(2.0))) - 0.4).abs() < 1e-12);
        // As on the bench (`--station-error=0.08 --tolerance=0.1`): 0.08 m
        // off along the way, surveyed to 0.1 m, it may lie 0.18 m off, not 0.1 m.
        assert!((room(&slide_east, &at(10.08, 0.0), &tolerance(0.1, None)) - 0.18).abs() < 1e-12);
        // Outside the tolerance, with no move that way bringing it in: not pinned.
        assert!(room(&slide_east, &at(10.0, 0.6), &tolerance(0.5, None)).is_infinite());
        // A turn, 0.2 rad a metre where the pairs lie 5 m from their middle.
        let turn = PlanHold { weakest: [1.0, 0.0, 0.0], ..slide_east };
        let rad = 2f64.to_radians();
        // A scanner 10 m off the middle moves 2 m a metre: 0.25 m; the yaw
        // surveyed to 2 degrees gives 0.175 m.
        assert!((room(&turn, &at(10.0, 0.0), &tolerance(0.5, None)) - 0.25).abs() < 1e-12);
        assert!((room(&turn, &at(10.0, 0.0), &tolerance(0.5, Some(2.0))) - rad / 0.2).abs() < 1e-12);
        // Turned 1 degree from its station already: 3 degrees the other way.
        let three = 3f64.to_radians() / 0.2;
        assert!((room(&turn, &turned(10.0, 0.0, 1.0), &tolerance(2.0, Some(2.0))) - three).abs() < 1e-12);
        assert!((room(&turn, &turned(10.0, 0.0, -1.0), &tolerance(2.0, Some(2.0))) - three).abs() < 1e-12);
        // At the middle it does not move: only a surveyed yaw bounds the turn.
        let middle = |t: &StationTolerance| turn.within_station_m(&at(0.0, 0.0), &at(0.0, 0.0), t);
        assert!((middle(&tolerance(0.5, Some(2.0))) - rad / 0.2).abs() < 1e-12);
        assert!(middle(&tolerance(0.5, None)).is_infinite());
        // Outside the yaw surveyed where the turn cannot bring it in: not pinned.
        let slide_turned = slide_east.within_station_m(&turned(10.0, 0.0, 3.0), &station, &tolerance(0.5, Some(2.0)));
        assert!(slide_turned.is_infinite());
    }

    /// Two scans of a corridor, both held by stations, the second's 0.3 m
    /// off along it: what they share holds nothing along the corridor, so
    /// ICP leaves the second where its station put it. With the default
    /// tolerance (0.5 m) that is not pinned down and it is not merged
    /// (it was merged 0.3 m off, with no word, before); surveyed to 0.1 m,
    /// it is merged where its station is, and said to be.
    #[test]
    fn a_held_scan_its_station_alone_pins_along_a_corridor() {
        // Two walls along x at y = -5 and 5, 4 m high, and the ground.
        let corridor = |x0: f64, x1: f64, phase: f64| {
            joined(&[
                box_faces([x0, -5.2, 0.0], [x1, -5.0, 4.0], &[(1, 1.0)], phase),
                box_faces([x0, 5.0, 0.0], [x1, 5.2, 4.0], &[(1, -1.0)], phase),
                box_faces([x0, -5.0, -0.1], [x1, 5.0, 0.0], &[(2, 1.0)], phase),
            ])
        };
        let clouds = [corridor(-20.0, 20.0, 0.0), corridor(-15.0, 15.0, 0.05)];
        let register = |plan_m: f64, off_m: f64| {
            let tolerance = StationTolerance { plan_m, height_m: None, yaw_deg: Some(2.0) };
            let stations = [Pose::identity(), liftplan_core::frame::pose_xyz_yaw(off_m, 0.0, 0.0, 0.0)];
            let inputs: Vec<RegInput> = clouds
                .iter()
                .zip(stations)
                .enumerate()
                .map(|(k, (c, st))| RegInput {
                    name: format!("s{k}"),
                    fine: c.clone(),
                    coarse: FeatureCloud::default(),
                    initial: Some(st),
                    held: Some(tolerance),
                })
                .collect();
            register_all(&inputs, &RegistrationSettings::default(), 7).remove(1)
        };
        let refused = register(0.5, 0.3);
        let why = refused.warning.as_deref().unwrap_or_default();
        assert!(!refused.registered, "{refused:?}");
        assert!(
            why.starts_with("scan 's1' is not merged: where it fits the scans placed so far best")
                && why.contains("moved any distance its weakest way (0 % a turn about the shared structure's middle, the rest a shift along bearing 90/270 degrees), they lie no further off each other (at most 0.18 m allowed), and its station's tolerance (tolerance_m = 0.5, yaw_tolerance_deg = 2) lets it lie up to 0.50 m off that way"),
            "{why}"
        );
        let placed = register(0.1, 0.05);
        assert!(placed.registered, "{placed:?}");
        assert!(
            (placed.pose.translation.x - 0.05).abs() < 1e-3 && placed.pose.translation.y.abs() < 1e-3,
            "{placed:?}"
        );
        assert!(placed.hold_m.is_some_and(|m| m > LOOSE_HOLD_SLIDE_M), "{placed:?}");
        let said = placed.warning.as_deref().unwrap_or_default();
        assert!(
            said.starts_with("scan 's1' was placed with its station's help")
                && said.ends_with("so that way its place is its station's, within 0.10 m; check that station's survey"),
            "{said}"
        );
    }
}
