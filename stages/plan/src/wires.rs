//! Scan points that look like an overhead line no `[[power_line]]` gives:
//! thin, free-hanging runs of points some metres above the ground.
//!
//! Power lines are given by hand ([`liftplan_core::power_line`]): their
//! voltage is nowhere in the scans, and a conductor 12 mm across gives a
//! scanner a few points or none. But where a scanner did catch one (or a
//! guy wire, a telephone or lighting cable strung between poles), the
//! points show it, and a line the engineer did not know of is the hazard
//! that kills most people round cranes. This looks for it, and the plan
//! asks for it to be checked first: it is a warning, not an obstacle
//! beyond what its points already are (the planner keeps the lift's
//! clearance off them, as off every scan point, not a power line's
//! approach distance: it cannot know the line's voltage or sag).
//!
//! A point counts as part of such a line where it is at least
//! [`ABOVE_GROUND_M`] above the ground under it and what the scans show
//! within [`ISOLATED_M`] of it (ground left out) lies within [`THIN_M`] of
//! one straight line through it, no steeper than [`STEEPEST_DEG`], but
//! for a stray point or two ([`MOST_OFF_SHARE`]): a pipe or a beam is too
//! thick, a handrail has its knee rail and walkway near, a post stands
//! upright. Only points in a cell of half [`ISOLATED_M`] holding
//! [`LEAST_IN_CELL`] points or more that lie along a line, with no more
//! than [`MOST_CELLS_OFF_LINE`] of the cells round it holding points off
//! that line, are looked at so (a wire scanned with up to about 0.2 m
//! between its points). Such points within [`LINK_M`]
//! of each other are one run (a scan misses stretches of a wire); a run of
//! [`LEAST_LENGTH_M`] or more in plan is reported, unless it lies along a
//! line the project gives.
//!
//! What this module must not do: plan round what it finds, or say what it
//! is: a run of points is "line-like", for the engineer to identify on
//! site. Its bounds are heuristics: a line the scans saw nothing of, or
//! saw among other things, is not found, and a thin bar standing free may
//! be reported.

use liftplan_core::frame::{Mat3, Vec3};
use liftplan_core::obb::point_segment_distance_2d;
use liftplan_core::power_line::PowerLine;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::{HashMap, HashSet};

/// The least height above the ground under it (m) at which a run is looked
/// for: below it, fences, kerbs and parked vehicles' edges.
pub const ABOVE_GROUND_M: f64 = 3.0;
/// How far round a point (m) nothing but the line may lie.
pub const ISOLATED_M: f64 = 1.0;
/// How far off the line (m) its points may scatter: a conductor's
/// thickness and the scans' noise.
pub const THIN_M: f64 = 0.05;
/// The steepest a line may run from the horizontal (degrees): steeper is a
/// post or a mast's edge (a guy wire runs at 45 to 60 degrees).
pub const STEEPEST_DEG: f64 = 65.0;
/// The widest gap (m) between a run's points: a scan misses stretches.
pub const LINK_M: f64 = 1.5;
/// The shortest run (m, in plan) reported.
pub const LEAST_LENGTH_M: f64 = 10.0;
/// The fewest points round a point (within [`ISOLATED_M`]) to tell a line
/// by; fewer is noise.
const LEAST_AROUND: usize = 5;
/// The fewest points a cell of half [`ISOLATED_M`] must hold for its
/// points to be looked at: a wire scanned at up to about 0.2 m between
/// points.
pub const LEAST_IN_CELL: usize = 3;
/// The most of a cell's 26 neighbours (cells of half [`ISOLATED_M`]) that
/// may hold points though the line along the cell's own points does not
/// cross them, for its points to be looked at: stray points.
pub const MOST_CELLS_OFF_LINE: usize = 2;
/// The share of the points within [`ISOLATED_M`] of a point of a line that
/// may lie off it: stray points, not a pipe's surface (most of which lies
/// off any one line along it) nor a handrail's knee rail (half of what is
/// near).
pub const MOST_OFF_SHARE: f64 = 0.1;
/// The fewest points of a run reported.
const LEAST_POINTS: usize = 15;
/// The most points within [`ISOLATED_M`] of a point of a line: a wire
/// through that sphere, 2 m of it, thinned to 1 cm, holds 200; more is a
/// surface (and a point beside a dense surface is passed by without
/// gathering all of it).
const MOST_AROUND: usize = 400;
/// The most `[plan] found_lines_approach_m` may be (m): OSHA 1926.1409's
/// 50 feet for lines over 350 kV, with room.
pub const MOST_APPROACH_M: f64 = 30.0;
/// How far from a given power line (m, beyond its sag) a run lies along it.
const ALONG_GIVEN_M: f64 = 3.0;
/// How far from its middle (m, in plan) a given line not along a run is
/// named with it.
pub const NEAR_GIVEN_M: f64 = 30.0;

/// A run of line-like scan points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LineLike {
    /// Its two ends, the points farthest apart along it (m).
    pub from_m: [f64; 3],
    pub to_m: [f64; 3],
    /// Its length in plan (m).
    pub length_m: f64,
    /// The lowest and highest of its points (m).
    pub lowest_z_m: f64,
    pub highest_z_m: f64,
    /// The least height of its points above the ground under them (m).
    pub above_ground_m: f64,
    /// How many scan points it holds.
    pub points: usize,
    /// The given power line nearest its middle in plan, within
    /// [`NEAR_GIVEN_M`], and how far (m): a line given with its supports
    /// off may be this one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub near_given: Option<(String, f64)>,
}

impl LineLike {
    /// In words, for the plan's row and the sign-off page.
    pub fn said(&self) -> String {
        let near = match &self.near_given {
            Some((name, m)) => format!(
                " ({m:.1} m in plan from power line '{name}', which does not run along it: if it is that line, where the line is given is wrong)"
            ),
            None => String::new(),
        };
        format!(
            "{:.0} m of line-like scan points ({} points) from ({:.1}, {:.1}) to ({:.1}, {:.1}) m in plan, at z {:.1} to {:.1} m ({:.1} m or more above the ground under it){near}",
            self.length_m,
            self.points,
            self.from_m[0],
            self.from_m[1],
            self.to_m[0],
            self.to_m[1],
            self.lowest_z_m,
            self.highest_z_m,
            self.above_ground_m
        )
    }

    /// The run as a power line of unknown voltage kept `approach_m` off
    /// (`[plan] found_lines_approach_m`), named by its number `n` near the
    /// lift: held at its ends, sagging from their chord (least) down to its
    /// lowest point (most), hanging plumb. Where the scans did not see it,
    /// beyond its ends, it is not.
    pub fn as_power_line(&self, n: usize, approach_m: f64) -> PowerLine {
        let chord_mid_z = (self.from_m[2] + self.to_m[2]) / 2.0;
        PowerLine {
            name: format!("line-like run {n} found in the scans"),
            points_m: vec![self.from_m, self.to_m],
            sag_m: (chord_mid_z - self.lowest_z_m).max(0.0),
            least_sag_m: Some(0.0),
            swing_deg: None,
            // Unknown: the approach distance is the project's.
            voltage_kv: f64::NAN,
            approach_m: Some(approach_m),
            lifts: Vec::new(),
        }
    }

    /// A box round the run's straight line between its ends, `half_m`
    /// either side of it, for the pictures.
    pub fn obb(&self, half_m: f64) -> liftplan_core::obb::Obb {
        use liftplan_core::frame::Point3;
        let (a, b) = (Vec3::from(self.from_m), Vec3::from(self.to_m));
        let along = b - a;
        let len = along.norm();
        let x = if len > 0.0 { along / len } else { Vec3::x() };
        let across = Vec3::new(-x.y, x.x, 0.0);
        let y = if across.norm() > 1e-9 { across.normalize() } else { Vec3::y() };
        let z = x.cross(&y);
        let c = (a + b) / 2.0;
        liftplan_core::obb::Obb::new(
            Point3::new(c.x, c.y, c.z),
            Mat3::from_columns(&[x, y, z]),
            Vec3::new(len / 2.0 + half_m, half_m, half_m),
        )
    }

    /// The least plan distance (m) from `at` to the run's straight line
    /// between its ends.
    pub fn plan_distance_m(&self, at: [f64; 2]) -> f64 {
        point_segment_distance_2d(at, [self.from_m[0], self.from_m[1]], [self.to_m[0], self.to_m[1]])
    }
}

/// The runs of line-like points among `points` (`ground` flags the ground
/// points) within `within` (plan discs: centre and radius, m), but those
/// along a line of `given`.
pub fn find(points: &[[f64; 3]], ground: &[bool], within: &[([f64; 2], f64)], given: &[PowerLine]) -> Vec<LineLike> {
    // (A point not finite is in no disc: the eigen solver below is not fed one.)
    let inside = |p: &[f64; 3]| {
        p.iter().all(|v| v.is_finite())
            && within.iter().any(|(c, r)| (p[0] - c[0]).hypot(p[1] - c[1]) <= *r + ISOLATED_M)
    };
    let Some(ground_under) = GroundGrid::new(points, ground) else { return Vec::new() };
    // Everything but the ground near the lifts.
    let standing: Vec<[f64; 3]> =
        points.iter().zip(ground).filter(|(p, g)| !**g && inside(p)).map(|(p, _)| *p).collect();
    // The points by cells of half ISOLATED_M. A cell whose points lie
    // farther from their own best line than THIN_M, as a root mean square,
    // lie farther from any line, and each of its points has the whole cell
    // within ISOLATED_M: none is looked at (a wire's cell holding a stray
    // point is lost, a gap of half a metre its run bridges). Most of a
    // site's points (surfaces) are passed by so, a cell at a time, and so are cells of fewer than
    // LEAST_IN_CELL (stray points, leaves), which would each cost a search,
    // and cells more than MOST_CELLS_OFF_LINE of whose 26 neighbours hold
    // points though the cell's own line does not cross them (a sparse
    // wall's cells, whose few points may happen to lie along a line).
    let half = ISOLATED_M / 2.0;
    let keys: Vec<[i64; 3]> = standing.iter().map(|p| Grid::key(p, half)).collect();
    let mut order: Vec<usize> = (0..standing.len()).collect();
    order.par_sort_unstable_by_key(|&k| (keys[k], k));
    let cells: Vec<&[usize]> = order.chunk_by(|a, b| keys[*a] == keys[*b]).collect();
    let occupied: HashSet<[i64; 3]> = cells.iter().map(|c| keys[c[0]]).collect();
    // A cell a line crosses has its centre within half its diagonal of it.
    let crossed_within_m = half * 3f64.sqrt() / 2.0 + THIN_M;
    let held_off_line = |key: [i64; 3], mean: Vec3, axis: Vec3| {
        block_round(key)
            .filter(|c| *c != key && occupied.contains(c))
            .filter(|c| {
                let centre = Vec3::new(c[0] as f64 + 0.5, c[1] as f64 + 0.5, c[2] as f64 + 0.5) * half;
                let d = centre - mean;
                (d - axis * d.dot(&axis)).norm() > crossed_within_m
            })
            .count()
    };
    let mut candidates: Vec<usize> = cells
        .par_iter()
        .filter(|cell| cell.len() >= LEAST_IN_CELL)
        .filter(|cell| {
            let pts: Vec<Vec3> = cell.iter().map(|&k| Vec3::from(standing[k])).collect();
            best_line(&pts).is_some_and(|l| {
                l.rms_off_m <= THIN_M && held_off_line(keys[cell[0]], l.mean, l.axis) <= MOST_CELLS_OFF_LINE
            })
        })
        .flat_map_iter(|cell| {
            cell.iter().copied().filter(|&k| {
                let p = standing[k];
                p[2] - ground_under.at([p[0], p[1]]) >= ABOVE_GROUND_M
            })
        })
        .collect();
    if candidates.is_empty() {
        return Vec::new();
    }
    candidates.sort_unstable();
    // What lies round them, by cells of ISOLATED_M.
    let round: HashSet<[i64; 3]> =
        candidates.iter().flat_map(|&k| block_round(Grid::key(&standing[k], ISOLATED_M))).collect();
    let near: Vec<[f64; 3]> = standing.iter().filter(|p| round.contains(&Grid::key(p, ISOLATED_M))).copied().collect();
    let grid = Grid::new(&near, ISOLATED_M);
    let thin: Vec<usize> =
        candidates.into_par_iter().filter(|&k| line_like_around(&near, &grid, standing[k])).collect();
    let mut runs = link(&standing, &thin);
    runs.sort_by_key(|run| std::cmp::Reverse(run.len()));
    runs.into_iter()
        .filter(|run| run.len() >= LEAST_POINTS)
        .filter_map(|run| {
            let pts: Vec<[f64; 3]> = run.iter().map(|&k| standing[k]).collect();
            let mut line = run_of(&pts, &ground_under)?;
            if line.length_m < LEAST_LENGTH_M || given.iter().any(|l| along(&line, l)) {
                return None;
            }
            let mid = [(line.from_m[0] + line.to_m[0]) / 2.0, (line.from_m[1] + line.to_m[1]) / 2.0];
            line.near_given = given
                .iter()
                .filter_map(|l| {
                    let m = l
                        .points_m
                        .windows(2)
                        .map(|s| point_segment_distance_2d(mid, [s[0][0], s[0][1]], [s[1][0], s[1][1]]))
                        .fold(f64::INFINITY, f64::min);
                    (m <= NEAR_GIVEN_M).then(|| (l.name.clone(), m))
                })
                .min_by(|a, b| a.1.total_cmp(&b.1));
            Some(line)
        })
        .collect()
}

/// Whether what lies within [`ISOLATED_M`] of `p` lies within [`THIN_M`] of
/// one line through it, not too steep, and reaches along it.
fn line_like_around(pts: &[[f64; 3]], grid: &Grid, p: [f64; 3]) -> bool {
    let around: Vec<Vec3> = grid
        .near(p, ISOLATED_M)
        .map(|k| pts[k])
        .filter(|q| dist2(q, &p) <= ISOLATED_M * ISOLATED_M)
        .map(|q| Vec3::new(q[0], q[1], q[2]))
        .take(MOST_AROUND + 1)
        .collect();
    if around.len() < LEAST_AROUND || around.len() > MOST_AROUND {
        return false;
    }
    let at = Vec3::new(p[0], p[1], p[2]);
    let off_line = |axis: &Vec3, q: &Vec3| {
        let d = q - at;
        (d - axis * d.dot(axis)).norm()
    };
    // The line through p: first along what lies within half the distance
    // (a stray point farther off does not tilt it), then along what lies
    // within THIN_M of that.
    let close: Vec<Vec3> = around.iter().filter(|q| (*q - at).norm() <= ISOLATED_M / 2.0).copied().collect();
    let Some(first) = principal_axis(&close) else { return false };
    let on_first: Vec<Vec3> = around.iter().filter(|q| off_line(&first, q) <= THIN_M).copied().collect();
    let Some(axis) = principal_axis(&on_first) else { return false };
    let on_line: Vec<&Vec3> = around.iter().filter(|q| off_line(&axis, q) <= THIN_M).collect();
    let (lo, hi) =
        on_line.iter().map(|q| (*q - at).dot(&axis)).fold((0.0f64, 0.0f64), |(l, h), t| (l.min(t), h.max(t)));
    let steep = axis.z.abs().asin().to_degrees();
    // At a run's end, or a gap in it, the points lie to one side; a stray
    // point or two (dust, a bird, a mixed pixel) may lie off it.
    let off = around.len() - on_line.len();
    steep <= STEEPEST_DEG
        && hi - lo >= ISOLATED_M / 2.0
        && on_line.len() >= LEAST_AROUND
        && off as f64 <= MOST_OFF_SHARE * around.len() as f64
}

/// The points' mean (m) and covariance (m²).
fn mean_and_covariance(pts: &[Vec3]) -> (Vec3, Mat3) {
    let n = pts.len().max(1) as f64;
    let mean = pts.iter().fold(Vec3::zeros(), |a, p| a + p) / n;
    let cov = pts.iter().fold(Mat3::zeros(), |a, p| {
        let d = p - mean;
        a + d * d.transpose()
    }) / n;
    (mean, cov)
}

/// The straight line points lie nearest to, as a least-squares fit: through
/// their mean, along the direction they spread most along.
struct BestLine {
    mean: Vec3,
    /// Unit.
    axis: Vec3,
    /// The points' root mean square distance from it (m): no line has them
    /// nearer.
    rms_off_m: f64,
}

/// The points' [`BestLine`], where they spread.
fn best_line(pts: &[Vec3]) -> Option<BestLine> {
    let (mean, cov) = mean_and_covariance(pts);
    let eig = cov.symmetric_eigen();
    let k = (0..3).max_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]))?;
    let axis: Vec3 = eig.eigenvectors.column(k).into();
    let rms_off_m = (eig.eigenvalues.sum() - eig.eigenvalues[k]).max(0.0).sqrt();
    (eig.eigenvalues[k] > 0.0 && axis.norm() > 0.0).then(|| BestLine { mean, axis: axis.normalize(), rms_off_m })
}

/// The direction the points spread most along (unit), where they spread.
fn principal_axis(pts: &[Vec3]) -> Option<Vec3> {
    best_line(pts).map(|l| l.axis)
}

/// The cells of the block of 3 x 3 x 3 round `key`, its own among them.
fn block_round([x, y, z]: [i64; 3]) -> impl Iterator<Item = [i64; 3]> {
    (-1..=1i64).flat_map(move |dx| {
        (-1..=1i64).flat_map(move |dy| {
            (-1..=1i64).map(move |dz| [x.saturating_add(dx), y.saturating_add(dy), z.saturating_add(dz)])
        })
    })
}

/// The runs: line-like points (`members`, indices into `pts`) within
/// [`LINK_M`] of each other, joined.
fn link(pts: &[[f64; 3]], members: &[usize]) -> Vec<Vec<usize>> {
    let own: Vec<[f64; 3]> = members.iter().map(|&k| pts[k]).collect();
    let grid = Grid::new(&own, LINK_M);
    let mut parent: Vec<usize> = (0..own.len()).collect();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    for a in 0..own.len() {
        for b in grid.near(own[a], LINK_M).filter(|&b| b > a && dist2(&own[a], &own[b]) <= LINK_M * LINK_M) {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            if ra != rb {
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    let mut runs: HashMap<usize, Vec<usize>> = HashMap::new();
    for a in 0..own.len() {
        let r = root(&mut parent, a);
        runs.entry(r).or_default().push(members[a]);
    }
    let mut runs: Vec<Vec<usize>> = runs.into_values().collect();
    // In the order of their first point, whatever the map's order.
    runs.sort_by_key(|run| run[0]);
    runs
}

/// A run's ends, length and heights.
fn run_of(pts: &[[f64; 3]], ground_under: &GroundGrid) -> Option<LineLike> {
    let v: Vec<Vec3> = pts.iter().map(|p| Vec3::new(p[0], p[1], p[2])).collect();
    let axis = principal_axis(&v)?;
    let t = |p: &[f64; 3]| Vec3::new(p[0], p[1], p[2]).dot(&axis);
    let from = *pts.iter().min_by(|a, b| t(a).total_cmp(&t(b)))?;
    let to = *pts.iter().max_by(|a, b| t(a).total_cmp(&t(b)))?;
    let (lowest, highest) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p[2]), h.max(p[2])));
    let above = pts.iter().map(|p| p[2] - ground_under.at([p[0], p[1]])).fold(f64::INFINITY, f64::min);
    Some(LineLike {
        from_m: from,
        to_m: to,
        length_m: (to[0] - from[0]).hypot(to[1] - from[1]),
        lowest_z_m: lowest,
        highest_z_m: highest,
        above_ground_m: above,
        points: pts.len(),
        near_given: None,
    })
}

/// Whether a run lies along a given line: its ends and middle each within
/// [`ALONG_GIVEN_M`] of a span's straight line, or below it by no more
/// than the line's sag.
fn along(run: &LineLike, line: &PowerLine) -> bool {
    let mid = [0, 1, 2].map(|k| (run.from_m[k] + run.to_m[k]) / 2.0);
    [run.from_m, mid, run.to_m].iter().all(|p| {
        line.points_m.windows(2).any(|span| {
            let (a, b) = (Vec3::from(span[0]), Vec3::from(span[1]));
            let p = Vec3::from(*p);
            let ab = b - a;
            let t = if ab.norm_squared() > 0.0 { ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0) } else { 0.0 };
            let on = a + ab * t;
            let below = (on.z - p.z).clamp(0.0, line.sag_m);
            (p + Vec3::new(0.0, 0.0, below) - on).norm() <= ALONG_GIVEN_M
        })
    })
}

fn dist2(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}

/// Points by cubic cells, for their neighbours.
struct Grid {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<usize>>,
}

impl Grid {
    fn new(pts: &[[f64; 3]], cell: f64) -> Grid {
        let mut cells: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (k, p) in pts.iter().enumerate() {
            cells.entry(Self::key(p, cell)).or_default().push(k);
        }
        Grid { cell, cells }
    }

    fn key(p: &[f64; 3], cell: f64) -> [i64; 3] {
        p.map(|v| (v / cell).floor() as i64)
    }

    /// The points of the cells within `r` of `p` (more than those within `r`).
    fn near(&self, p: [f64; 3], r: f64) -> impl Iterator<Item = usize> + '_ {
        let (lo, hi) = (Self::key(&p.map(|v| v - r), self.cell), Self::key(&p.map(|v| v + r), self.cell));
        (lo[0]..=hi[0]).flat_map(move |x| {
            (lo[1]..=hi[1]).flat_map(move |y| {
                (lo[2]..=hi[2]).flat_map(move |z| self.cells.get(&[x, y, z]).into_iter().flatten().copied())
            })
        })
    }
}

/// The ground's height under a point: the lowest ground point of its plan
/// cell ([`GroundGrid::CELL_M`]), else of the nearest cells round it that
/// hold one, else the lowest ground point of all.
struct GroundGrid {
    lowest: HashMap<[i64; 2], f64>,
    everywhere: f64,
}

impl GroundGrid {
    const CELL_M: f64 = 5.0;
    /// How many cells round a cell without ground are looked in.
    const REACH: i64 = 2;

    fn new(points: &[[f64; 3]], ground: &[bool]) -> Option<GroundGrid> {
        let mut lowest: HashMap<[i64; 2], f64> = HashMap::new();
        let mut everywhere = f64::INFINITY;
        for (p, _) in points.iter().zip(ground).filter(|(p, g)| **g && p.iter().all(|v| v.is_finite())) {
            let z = lowest.entry(Self::key([p[0], p[1]])).or_insert(f64::INFINITY);
            *z = z.min(p[2]);
            everywhere = everywhere.min(p[2]);
        }
        everywhere.is_finite().then_some(GroundGrid { lowest, everywhere })
    }

    fn key(p: [f64; 2]) -> [i64; 2] {
        p.map(|v| (v / Self::CELL_M).floor() as i64)
    }

    fn at(&self, p: [f64; 2]) -> f64 {
        let [x, y] = Self::key(p);
        (0..=Self::REACH)
            .find_map(|ring| {
                (-ring..=ring)
                    .flat_map(|dx| (-ring..=ring).map(move |dy| (dx, dy)))
                    .filter(|(dx, dy)| dx.abs() == ring || dy.abs() == ring)
                    .filter_map(|(dx, dy)| self.lowest.get(&[x.saturating_add(dx), y.saturating_add(dy)]).copied())
                    .reduce(f64::min)
            })
            .unwrap_or(self.everywhere)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A site of flat ground, a pipe on a rack, a handrail over a walkway,
    /// a thin post and a wire hanging 12 m up between poles 50 m apart
    /// (sagging 1 m), scanned with a few millimetres of noise and a metre
    /// of it missed: only the wire is found, along its whole length.
    fn site(with_wire: bool) -> (Vec<[f64; 3]>, Vec<bool>) {
        let mut rng = liftplan_core::rng::seeded(7, "wires test");
        let mut noise = || liftplan_core::rng::uniform(&mut rng, -0.004, 0.004);
        let (mut pts, mut ground) = (Vec::new(), Vec::new());
        let mut put = |p: [f64; 3], g: bool| {
            pts.push(p);
            ground.push(g);
        };
        for i in -60..=60 {
            for j in -60..=60 {
                put([i as f64 * 0.5, j as f64 * 0.5, 0.0], true);
            }
        }
        let steps = |from: f64, to: f64, by: f64| {
            let n = ((to - from) / by).round() as usize;
            (0..=n).map(move |k| from + k as f64 * by).collect::<Vec<f64>>()
        };
        // A pipe 0.3 m across on a rack, 6 m up, along x.
        for x in steps(-20.0, 20.0, 0.05) {
            for a in 0..12 {
                let t = a as f64 * std::f64::consts::TAU / 12.0;
                put([x, -10.0 + 0.15 * t.cos(), 6.0 + 0.15 * t.sin()], false);
            }
        }
        // A handrail 1.1 m over a walkway 4 m up, along y, with its knee
        // rail half way.
        for y in steps(-15.0, 15.0, 0.05) {
            put([15.0 + noise(), y, 5.1 + noise()], false);
            put([15.0 + noise(), y, 4.55 + noise()], false);
            for w in steps(14.0, 16.0, 0.1) {
                put([w, y, 4.0], false);
            }
        }
        // A post 8 m tall, 0.03 m across.
        for z in steps(0.1, 8.0, 0.05) {
            put([-15.0 + noise(), 15.0 + noise(), z], false);
        }
        if with_wire {
            for x in steps(-25.0, 25.0, 0.05) {
                if (4.0..5.0).contains(&x) {
                    continue;
                }
                let sag = 1.0 * (1.0 - (x / 25.0).powi(2));
                put([x + noise(), 10.0 + noise(), 12.0 - sag + noise()], false);
            }
            // Stray points beside it (dust, a bird, a mixed pixel).
            for x in [-12.0f64, 3.0, 18.0] {
                let sag = 1.0 * (1.0 - (x / 25.0).powi(2));
                put([x, 10.6, 12.0 - sag + 0.3], false);
            }
        }
        (pts, ground)
    }

    #[test]
    fn a_wire_strung_between_poles_is_found_and_nothing_else_is() {
        let everywhere = [([0.0, 0.0], 100.0)];
        let (pts, ground) = site(true);
        let found = find(&pts, &ground, &everywhere, &[]);
        assert_eq!(found.len(), 1, "{found:?}");
        let w = &found[0];
        assert!(w.length_m > 45.0 && w.length_m <= 50.1, "{w:?}");
        assert!((w.from_m[1] - 10.0).abs() < 0.1 && (w.to_m[1] - 10.0).abs() < 0.1, "{w:?}");
        assert!(w.lowest_z_m > 10.9 && w.highest_z_m < 12.1 && w.above_ground_m > 10.9, "{w:?}");
        assert!(w.said().starts_with("50 m of line-like scan points ("), "{}", w.said());
        assert!(w.plan_distance_m([0.0, 0.0]) > 9.9 && w.plan_distance_m([0.0, 10.0]) < 0.1);
        // Without the wire: nothing (the pipe is thick, the handrail has its
        // walkway under it, the post stands upright).
        let (pts, ground) = site(false);
        assert_eq!(find(&pts, &ground, &everywhere, &[]), vec![]);
        // Only near the lifts.
        let (pts, ground) = site(true);
        assert_eq!(find(&pts, &ground, &[([0.0, -40.0], 20.0)], &[]), vec![]);
        // Along a line the project gives, it is that line.
        let given = PowerLine {
            name: "11 kV".into(),
            points_m: vec![[-25.0, 10.0, 12.0], [25.0, 10.0, 12.0]],
            sag_m: 1.0,
            least_sag_m: None,
            swing_deg: None,
            voltage_kv: 11.0,
            approach_m: None,
            lifts: vec![],
        };
        assert_eq!(find(&pts, &ground, &everywhere, std::slice::from_ref(&given)), vec![]);
        // A line given 10 m away is another, and is named with it.
        let elsewhere = PowerLine { points_m: vec![[-25.0, 20.0, 12.0], [25.0, 20.0, 12.0]], ..given };
        let found = find(&pts, &ground, &everywhere, &[elsewhere]);
        assert_eq!(found.len(), 1);
        let (name, m) = found[0].near_given.clone().unwrap();
        assert!(name == "11 kV" && (m - 10.0).abs() < 0.1, "{name} {m}");
        assert!(
            found[0].said().ends_with(&format!(
                " ({m:.1} m in plan from power line '11 kV', which does not run along it: if it is that line, where the line is given is wrong)"
            )),
            "{}",
            found[0].said()
        );
        assert_eq!(find(&pts, &ground, &everywhere, &[]).first().and_then(|l| l.near_given.clone()), None);
        // Kept off as a line of unknown voltage: held at the run's ends,
        // sagging from their chord to its lowest point; its boxes grown by
        // the approach distance hold what is that far from where the scans
        // saw it, and not what is farther.
        let line = w.as_power_line(1, 6.1);
        assert_eq!((line.approach(), line.points_m.clone()), (Some((6.1, "approach_m")), vec![w.from_m, w.to_m]));
        assert!((line.sag_m - ((w.from_m[2] + w.to_m[2]) / 2.0 - w.lowest_z_m)).abs() < 1e-12 && line.sag_m > 0.9);
        let boxes = line.boxes(6.1);
        let inside = |p: [f64; 3]| boxes.iter().any(|b| b.contains(&liftplan_core::frame::Point3::from(p)));
        let lowest = w.lowest_z_m;
        assert!(inside([0.0, 10.0 + 6.0, lowest]) && inside([0.0, 10.0, lowest - 6.0]) && inside([-20.0, 10.0, 12.0]));
        assert!(!inside([0.0, 10.0 + 6.5, lowest]) && !inside([0.0, 10.0, 12.0 + 6.5]));
        // Points not finite, or far off, change nothing and break nothing.
        let (mut pts, mut ground) = site(true);
        for p in [[f64::NAN, 0.0, 12.0], [0.0, f64::INFINITY, 12.0], [1e300, -1e300, 12.0], [0.0, 10.0, f64::NAN]] {
            pts.push(p);
            ground.push(false);
            pts.push(p);
            ground.push(true);
        }
        assert_eq!(find(&pts, &ground, &everywhere, &[]).len(), 1);
    }
}
