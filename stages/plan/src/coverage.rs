//! What a planned lift passes over that neither the scans nor the plant
//! model show.
//!
//! The planner and the validator take the site to be what the scans and the
//! model hold: where neither holds anything, the lift is clear because
//! nothing was seen there, not because nothing is there. A scan's shadow
//! behind a building, a rooftop no station saw, or a site beyond the
//! scanners' range looks free. This module works out, in plan view on a grid
//! of [`CELL_M`] cells, which cells the lift's parts pass over and which of
//! those lie farther than [`SEEN_WITHIN_M`] from any scan point (and, of
//! them, which the plant model does not
//! reach either), for the load and what hangs with it (which comes low) and
//! for the rest of the moving crane (the boom and superstructure, high up)
//! apart, so that the engineer signing the plan knows where to look on site.
//!
//! What this module must not do: change what the planner or the validator
//! sees (an unseen cell is neither an obstacle nor free space to them), or
//! refuse a plan: a survey rarely sees every square metre, and only the
//! people on site can say what stands where it did not look.

use crate::path::Move;
use crate::validate::{World, configs_along, in_polygon, plan_bounds, to_edge_m};
use liftplan_core::crane::{Dependence, PartKind};
use liftplan_core::lift::LiftTask;
use liftplan_core::obb::Obb;
use serde::{Deserialize, Serialize};
use std::collections::{HashMap, HashSet};

/// The plan-view cell (m): the validator's point voxels' width, so a cell
/// holds a scan point exactly when a voxel column is occupied.
pub const CELL_M: f64 = crate::validate::VOXEL_M;

/// A cell within this distance (m, in whole cells) of a cell holding a scan
/// point counts as scanned. Far from a station a scanner's rings on open
/// ground lie a metre or more apart, and the rays to the farther ring pass
/// a few centimetres over the gap: anything standing in it would have been
/// hit and left points in its own cell. What no ray reached (the shadow of
/// a tank, a site beyond the scanners' range) is wider.
pub const SEEN_WITHIN_M: f64 = 2.0;

/// How far apart (m of any part's movement) the poses are that the swept
/// area is made of; each footprint is grown by half of it.
const SWEEP_SAMPLE_M: f64 = 0.5;

/// The plan area some parts pass over, and how much of it is unseen.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Area {
    /// Cells passed over (m²).
    pub passed_m2: f64,
    /// Of them, cells farther than [`SEEN_WITHIN_M`] from any scan point
    /// (m²).
    pub unscanned_m2: f64,
    /// Of those, cells the plant model does not reach either (m²).
    pub unknown_m2: f64,
    /// The plan extent of the unscanned cells, [xmin, ymin, xmax, ymax]
    /// (m), if there are any.
    pub unscanned_within: Option<[f64; 4]>,
    /// The lowest the parts come over the unscanned cells (site z, m): a
    /// thing standing there reaches them only if it is that tall.
    pub unscanned_lowest_z_m: Option<f64>,
    /// The unscanned cells (indices of [`CELL_M`] cells: cell (i, j) spans
    /// x from i·CELL_M, y from j·CELL_M), in order, at most
    /// [`MAX_CELLS_LISTED`], for the pictures.
    #[serde(default)]
    pub unscanned_cells: Vec<[i32; 2]>,
    /// Every cell passed over, the same way, at most [`MAX_CELLS_LISTED`]:
    /// listed under the load only, for the picture of the ground people are
    /// kept off while it moves.
    #[serde(default)]
    pub passed_cells: Vec<[i32; 2]>,
}

/// The most unscanned cells an [`Area`] lists.
pub const MAX_CELLS_LISTED: usize = 20_000;

/// The ground people are kept off while the load moves, where the lift
/// gives a fall zone ([`LiftTask::fall_zone_m`]): the cells under the load
/// and what hangs with it, grown by it.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct KeptOut {
    /// The fall zone round the ground under the load (m).
    pub fall_zone_m: f64,
    /// The cells' area (m²).
    pub area_m2: f64,
    /// The cells, as [`Area::passed_cells`] lists them, at most
    /// [`MAX_CELLS_LISTED`].
    pub cells: Vec<[i32; 2]>,
}

/// What one lift passes over ([`of_lift`]).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Coverage {
    /// The grid's cell (m).
    pub cell_m: f64,
    /// Whether the project has scans at all.
    pub scans: bool,
    /// Under the load, its rigging, the hook block and the rope.
    pub under_load: Area,
    /// Under the rest of the crane that moves (boom, superstructure,
    /// counterweight; a tower crane's jib and trolley).
    pub under_crane: Area,
    /// What [`Coverage::under_crane`] is under, in words ("boom and
    /// superstructure"; "jib, counter-jib and trolley").
    pub crane_parts: String,
    /// The ground under the load with the lift's fall zone round it; `None`
    /// where it gives none (the ground under the load is then the ground
    /// people are kept off).
    #[serde(default)]
    pub kept_out: Option<KeptOut>,
}

impl Coverage {
    /// Whether the load passes over cells no scan saw (where the project has
    /// scans).
    pub fn load_passes_unscanned(&self) -> bool {
        self.scans && self.under_load.unscanned_m2 > 0.0
    }

    /// Whether the load passes over cells neither a scan (where the project
    /// has none) nor the plant model tells anything of.
    pub fn load_passes_unknown(&self) -> bool {
        !self.scans && self.under_load.unknown_m2 > 0.0
    }

    /// One line for the run's output and the PDF.
    pub fn line(&self) -> String {
        let where_ = |a: &Area| match (a.unscanned_within, a.unscanned_lowest_z_m) {
            (Some(e), Some(z)) => {
                format!(
                    " (x {:.0} to {:.0} m, y {:.0} to {:.0} m; no lower than z = {z:.2} m there)",
                    e[0], e[2], e[1], e[3]
                )
            }
            _ => String::new(),
        };
        if !self.scans {
            return format!(
                "what the lift passes over: no scans; the load passes over {:.0} m², {:.0} m² of it outside the plant model, where nothing is known{}; the crane's {} {:.0} m², {:.0} m² outside the model: check them on site",
                self.under_load.passed_m2,
                self.under_load.unknown_m2,
                where_(&self.under_load),
                self.crane_parts,
                self.under_crane.passed_m2,
                self.under_crane.unknown_m2
            );
        }
        // What the load passes over unseen asks for a look on site; what
        // only the boom does, high up, is said.
        let part = |who: &str, a: &Area, loud: bool| {
            if a.unscanned_m2 > 0.0 {
                let unseen = if loud { "WITH NO SCAN POINT WITHIN" } else { "with no scan point within" };
                let unseen = format!("{unseen} {SEEN_WITHIN_M:.0} m");
                // "(0 m² not in the plant model either)" read oddly.
                let model = if a.unknown_m2 < 0.5 {
                    "the plant model covers all of it".to_string()
                } else {
                    format!("{:.0} m² not in the plant model either", a.unknown_m2)
                };
                format!(
                    "{who} {:.0} m², {:.0} m² of it {}{} ({model}){}",
                    a.passed_m2,
                    a.unscanned_m2,
                    unseen,
                    where_(a),
                    if loud { ": CHECK ON SITE what stands there" } else { "" }
                )
            } else {
                format!("{who} {:.0} m², all of it scanned", a.passed_m2)
            }
        };
        let load = part("the load passes over", &self.under_load, true);
        let crane = part(&format!("the crane's {} over", self.crane_parts), &self.under_crane, false);
        format!("what the lift passes over: {load}; {crane}")
    }
}

type Cell = (i32, i32);

fn cell_of(x: f64, y: f64) -> Cell {
    ((x / CELL_M).floor() as i32, (y / CELL_M).floor() as i32)
}

/// The cells a convex plan polygon grown by `grow_m` reaches: those whose
/// centre lies within `grow_m` plus half a cell's diagonal of it, so that a
/// cell the grown polygon touches anywhere is among them.
fn cells_under(poly: &[[f64; 2]], grow_m: f64, mut each: impl FnMut(Cell)) {
    let Some((lo, hi)) = plan_bounds(poly) else { return };
    let reach = grow_m + CELL_M * std::f64::consts::FRAC_1_SQRT_2;
    let (c0, c1) = (cell_of(lo[0] - reach, lo[1] - reach), cell_of(hi[0] + reach, hi[1] + reach));
    for i in c0.0..=c1.0 {
        for j in c0.1..=c1.1 {
            let centre = [(i as f64 + 0.5) * CELL_M, (j as f64 + 0.5) * CELL_M];
            if in_polygon(poly, centre) || to_edge_m(poly, centre) <= reach {
                each((i, j));
            }
        }
    }
}

/// The cells of `window` (the least and greatest cell, inclusive) that the
/// plant model's triangles reach in plan view. Only the window's cells are
/// tried, so a model in the wrong unit (a kilometre-wide triangle) costs no
/// more than one that fits.
fn modelled_cells(world: &World, window: (Cell, Cell)) -> HashSet<Cell> {
    let mut cells = HashSet::new();
    let Some(mesh) = &world.mesh else { return cells };
    let v = mesh.vertices();
    for t in mesh.indices() {
        let tri: Vec<[f64; 2]> = t.iter().map(|&k| [v[k as usize].x, v[k as usize].y]).collect();
        let Some((lo, hi)) = plan_bounds(&tri) else { continue };
        let (lo, hi) = (cell_of(lo[0], lo[1]), cell_of(hi[0], hi[1]));
        for i in lo.0.max(window.0.0)..=hi.0.min(window.1.0) {
            for j in lo.1.max(window.0.1)..=hi.1.min(window.1.1) {
                let square = [i as f64 * CELL_M, j as f64 * CELL_M, (i + 1) as f64 * CELL_M, (j + 1) as f64 * CELL_M];
                if triangle_meets_square(&tri, square) {
                    cells.insert((i, j));
                }
            }
        }
    }
    cells
}

/// Whether a plan triangle and a square [x0, y0, x1, y1] share a point
/// (separating axes: the square's two and the triangle's three edge
/// normals).
fn triangle_meets_square(t: &[[f64; 2]], sq: [f64; 4]) -> bool {
    let corners = [[sq[0], sq[1]], [sq[2], sq[1]], [sq[2], sq[3]], [sq[0], sq[3]]];
    let apart_along = |axis: [f64; 2]| {
        let along = |p: &[f64; 2]| p[0] * axis[0] + p[1] * axis[1];
        let (tl, th) = t.iter().map(along).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| (l.min(x), h.max(x)));
        let (sl, sh) =
            corners.iter().map(along).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| (l.min(x), h.max(x)));
        th < sl || sh < tl
    };
    let edges = (0..3).map(|e| {
        let (a, b) = (t[e], t[(e + 1) % 3]);
        [a[1] - b[1], b[0] - a[0]]
    });
    !([[1.0, 0.0], [0.0, 1.0]].into_iter().chain(edges).any(apart_along))
}

/// The plan cells the lift's `moves` pass over, the hanging parts' and the
/// rest of the moving crane's, each with the lowest those parts come over
/// it (site z), from poses no more than [`SWEEP_SAMPLE_M`] of movement
/// apart. Where the lift is planned for the wind, what hangs is swung as
/// the planner and the validator swing it ([`LiftTask::hanging_swept`]; not
/// in the lift-off and set-down): the ground it may swing over is under
/// it too.
fn swept_cells(task: &LiftTask, moves: &[Move]) -> (HashMap<Cell, f64>, HashMap<Cell, f64>, HashSet<Cell>) {
    let (mut load, mut crane, mut fall_zone) = (HashMap::new(), HashMap::new(), HashSet::new());
    let hanging = |k: PartKind| matches!(k, PartKind::Load | PartKind::Rigging | PartKind::HookBlock | PartKind::Rope);
    for (m, landing) in moves.iter().zip(crate::landing_moves(task, moves.len())) {
        for c in configs_along(task, m, SWEEP_SAMPLE_M) {
            for (kind, part) in task.pose_hanging_swept(&c, !landing).parts.iter() {
                if kind.dependence() == Dependence::Fixed {
                    continue;
                }
                let into = if hanging(*kind) { &mut load } else { &mut crane };
                let bottom = part.corners().iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
                let footprint = part.footprint();
                cells_under(&footprint, SWEEP_SAMPLE_M / 2.0, |c| {
                    let z = into.entry(c).or_insert(f64::INFINITY);
                    *z = z.min(bottom);
                });
                if hanging(*kind) && task.fall_zone_m > 0.0 {
                    cells_under(&footprint, SWEEP_SAMPLE_M / 2.0 + task.fall_zone_m, |c| {
                        fall_zone.insert(c);
                    });
                }
            }
        }
    }
    (load, crane, fall_zone)
}

/// What `task`'s planned `moves` pass over in `world`. Cells under the
/// `also_seen` boxes count as scanned (the load at its pick position, whose
/// scan points were taken for the load and left out of `world`).
pub fn of_lift(task: &LiftTask, moves: &[Move], world: &World, also_seen: &[Obb]) -> Coverage {
    let mut scanned: HashSet<Cell> = HashSet::new();
    let reach = (SEEN_WITHIN_M / CELL_M).round() as i32;
    for (i, j) in world.points.columns() {
        for di in -reach..=reach {
            for dj in -reach..=reach {
                if di * di + dj * dj <= reach * reach {
                    scanned.insert((i + di, j + dj));
                }
            }
        }
    }
    let scans = world.points.count > 0;
    for b in also_seen {
        cells_under(&b.footprint(), -CELL_M * std::f64::consts::FRAC_1_SQRT_2, |c| {
            scanned.insert(c);
        });
    }
    let (load, crane, fall_zone) = swept_cells(task, moves);
    let mut window = ((i32::MAX, i32::MAX), (i32::MIN, i32::MIN));
    for &(i, j) in load.keys().chain(crane.keys()) {
        window = ((window.0.0.min(i), window.0.1.min(j)), (window.1.0.max(i), window.1.1.max(j)));
    }
    let modelled = modelled_cells(world, window);
    let area = |cells: &HashMap<Cell, f64>, list_passed: bool| {
        let cell2 = CELL_M * CELL_M;
        let unscanned: Vec<(&Cell, &f64)> = cells.iter().filter(|(c, _)| !scanned.contains(c)).collect();
        let unknown = unscanned.iter().filter(|(c, _)| !modelled.contains(c)).count();
        let lowest = unscanned.iter().map(|(_, z)| **z).reduce(f64::min);
        let within = (!unscanned.is_empty()).then(|| {
            let (mut e, f) = ([f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY], CELL_M);
            for &(&(i, j), _) in &unscanned {
                e = [
                    e[0].min(i as f64 * f),
                    e[1].min(j as f64 * f),
                    e[2].max((i + 1) as f64 * f),
                    e[3].max((j + 1) as f64 * f),
                ];
            }
            e
        });
        let listed = |cells: &mut dyn Iterator<Item = &Cell>| {
            let mut v: Vec<[i32; 2]> = cells.map(|c| [c.0, c.1]).collect();
            v.sort_unstable();
            v.truncate(MAX_CELLS_LISTED);
            v
        };
        Area {
            passed_m2: cells.len() as f64 * cell2,
            unscanned_m2: unscanned.len() as f64 * cell2,
            unknown_m2: unknown as f64 * cell2,
            unscanned_within: within,
            unscanned_lowest_z_m: lowest,
            unscanned_cells: listed(&mut unscanned.iter().map(|(c, _)| *c)),
            passed_cells: if list_passed { listed(&mut cells.keys()) } else { Vec::new() },
        }
    };
    Coverage {
        cell_m: CELL_M,
        scans,
        under_load: area(&load, true),
        under_crane: area(&crane, false),
        crane_parts: task.crane.model.words().moving_structure.to_string(),
        kept_out: (task.fall_zone_m > 0.0).then(|| {
            let mut cells: Vec<[i32; 2]> = fall_zone.iter().map(|c| [c.0, c.1]).collect();
            cells.sort_unstable();
            cells.truncate(MAX_CELLS_LISTED);
            KeptOut { fall_zone_m: task.fall_zone_m, area_m2: fall_zone.len() as f64 * CELL_M * CELL_M, cells }
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use liftplan_core::crane::Config;
    use liftplan_core::frame::{Point3, Vec3};
    use liftplan_core::mesh::TriMesh;

    /// Ground points every 0.5 m over the site, on lines `every_m` apart in
    /// x, none inside `hole` ([xmin, ymin, xmax, ymax]).
    fn ground(every_m: f64, hole: Option<[f64; 4]>) -> (Vec<[f64; 3]>, Vec<bool>) {
        let mut pts = Vec::new();
        let lines = (140.0 / every_m) as i32;
        for i in 0..=lines {
            for j in 0..=280 {
                let (x, y) = (-70.0 + i as f64 * every_m, -70.0 + j as f64 * 0.5);
                if hole.is_some_and(|h| h[0] <= x && x <= h[2] && h[1] <= y && y <= h[3]) {
                    continue;
                }
                pts.push([x, y, 0.0]);
            }
        }
        let flags = vec![true; pts.len()];
        (pts, flags)
    }

    /// The test lift's load swung at its pick radius to its set bearing:
    /// it passes over (26, 0), 26 m from the crane, on its way.
    fn swing() -> (LiftTask, Vec<Move>) {
        let task = crate::test_lift("ac-700");
        let to = Config { swing_rad: task.set.swing_rad, ..task.pick };
        let moves = vec![Move { joint: liftplan_cspace::Joint::Swing, from: task.pick, to }];
        (task, moves)
    }

    fn coverage(pts: &(Vec<[f64; 3]>, Vec<bool>), mesh: &TriMesh, also_seen: &[Obb]) -> Coverage {
        let (task, moves) = swing();
        let world = World::new(mesh, &pts.0, &pts.1).unwrap();
        of_lift(&task, &moves, &world, also_seen)
    }

    /// A hole in the scans under the load's path is found where it is, a
    /// plant model over it makes it known but not scanned, and scan rings
    /// a few metres apart leave nothing unseen.
    #[test]
    fn what_no_scan_saw_under_the_load_is_found() {
        let none = TriMesh::default();
        let full = coverage(&ground(0.5, None), &none, &[]);
        assert!(full.scans && full.under_load.passed_m2 > 50.0, "{full:?}");
        assert_eq!((full.under_load.unscanned_m2, full.under_crane.unscanned_m2), (0.0, 0.0), "{full:?}");
        assert!(!full.load_passes_unscanned() && full.line().contains("all of it scanned"), "{}", full.line());
        // Rings 2.5 m apart: the rays to the next ring passed over the gap.
        let rings = coverage(&ground(2.5, None), &none, &[]);
        assert_eq!(rings.under_load.unscanned_m2, 0.0, "{rings:?}");

        let hole = [21.0, -5.0, 31.0, 5.0];
        let holed = coverage(&ground(0.5, Some(hole)), &none, &[]);
        let a = &holed.under_load;
        assert!(holed.load_passes_unscanned() && a.unscanned_m2 >= 10.0, "{holed:?}");
        assert_eq!(a.unknown_m2, a.unscanned_m2);
        let e = a.unscanned_within.unwrap();
        assert!(e[0] >= hole[0] && e[1] >= hole[1] && e[2] <= hole[2] && e[3] <= hole[3], "{e:?}");
        // Listed, in order, for the pictures: every one inside the hole.
        assert_eq!(a.unscanned_cells.len() as f64, a.unscanned_m2);
        assert!(a.unscanned_cells.windows(2).all(|w| w[0] < w[1]));
        assert!(a.unscanned_cells.iter().all(|c| hole[0] <= c[0] as f64 && (c[0] + 1) as f64 <= hole[2]));
        // Every cell passed over is listed under the load (in order, the
        // unscanned among them), none under the crane.
        assert_eq!(a.passed_cells.len() as f64, a.passed_m2);
        assert!(a.passed_cells.windows(2).all(|w| w[0] < w[1]));
        assert!(a.unscanned_cells.iter().all(|c| a.passed_cells.binary_search(c).is_ok()));
        assert!(holed.under_crane.passed_m2 > 0.0 && holed.under_crane.passed_cells.is_empty());
        // The load hangs from a 40 m boom at its pick rope: well above ground.
        let z = a.unscanned_lowest_z_m.unwrap();
        assert!(z > 0.0 && z < 30.0, "{z}");
        assert!(holed.line().contains("WITH NO SCAN POINT WITHIN 2 m"), "{}", holed.line());

        // A slab in the plant model over the hole: known, though not scanned.
        let mut slab = TriMesh::default();
        let g = slab.group_id("SLAB");
        slab.add_box(g, [20.0, -6.0, 0.0], [32.0, 6.0, 0.3]);
        let modelled = coverage(&ground(0.5, Some(hole)), &slab, &[]);
        assert_eq!(modelled.under_load.unscanned_m2, a.unscanned_m2);
        assert_eq!(modelled.under_load.unknown_m2, 0.0, "{modelled:?}");
        assert!(modelled.line().contains("(the plant model covers all of it)"), "{}", modelled.line());
        assert!(holed.line().contains(" m² not in the plant model either"), "{}", holed.line());

        // The load's scan points, taken out at pick, were seen there.
        let cut = Obb::axis_aligned(Point3::new(26.0, 0.0, 1.0), Vec3::new(6.0, 6.0, 1.0));
        let seen = coverage(&ground(0.5, Some(hole)), &none, &[cut]);
        assert_eq!(seen.under_load.unscanned_m2, 0.0, "{seen:?}");
    }

    /// Planned for the wind, the ground a gust may swing what hangs over is
    /// under the load too: the swing's strip widens; not in a lift-off or
    /// set-down (a lift's first and last moves), and not under the crane.
    #[test]
    fn the_ground_a_gust_may_swing_the_load_over_is_under_it() {
        let (mut task, one) = swing();
        let at = |f: f64| Config {
            swing_rad: task.pick.swing_rad + f * (task.set.swing_rad - task.pick.swing_rad),
            ..task.pick
        };
        let thirds: Vec<Move> = (0..3)
            .map(|k| Move {
                joint: liftplan_cspace::Joint::Swing,
                from: at(k as f64 / 3.0),
                to: at((k + 1) as f64 / 3.0),
            })
            .collect();
        let world = World::new(&TriMesh::default(), &[], &[]).unwrap();
        let plumb = (of_lift(&task, &one, &world, &[]), of_lift(&task, &thirds, &world, &[]));
        task.gust_swing_per_m = 0.03;
        let swung = (of_lift(&task, &one, &world, &[]), of_lift(&task, &thirds, &world, &[]));
        // The one swing is the lift's first and last move: held, not swung.
        assert_eq!(swung.0, plumb.0);
        let (p, s) = (&plumb.1, &swung.1);
        assert!(
            s.under_load.passed_m2 > p.under_load.passed_m2 + 20.0,
            "{} against {}",
            s.under_load.passed_m2,
            p.under_load.passed_m2
        );
        assert!(p.under_load.passed_cells.iter().all(|c| s.under_load.passed_cells.binary_search(c).is_ok()));
        assert_eq!(s.under_crane, p.under_crane);
    }

    /// A fall zone grows the ground people are kept off round the ground
    /// under the load, by about its perimeter times the zone (a strip 3 m
    /// wide along both sides of a swing's arc); without one there is none,
    /// and nothing else changes.
    #[test]
    fn a_fall_zone_grows_the_ground_kept_off_round_the_load() {
        let (mut task, one) = swing();
        let world = World::new(&TriMesh::default(), &[], &[]).unwrap();
        let plain = of_lift(&task, &one, &world, &[]);
        assert_eq!(plain.kept_out, None);
        task.fall_zone_m = 3.0;
        let zoned = of_lift(&task, &one, &world, &[]);
        let k = zoned.kept_out.clone().expect("a fall zone is kept out");
        assert_eq!(k.fall_zone_m, 3.0);
        assert_eq!(Coverage { kept_out: None, ..zoned }, plain);
        let under = &plain.under_load;
        assert!(under.passed_cells.iter().all(|c| k.cells.binary_search(c).is_ok()));
        assert_eq!(k.cells.len() as f64, k.area_m2);
        // The swing's arc is long and narrow: the zone adds 3 m on both
        // sides of most of its length, and at most that round all of it.
        let (length, width) = (under.passed_m2 / 8.0, 8.0);
        assert!(k.area_m2 > under.passed_m2 + 2.0 * 3.0 * length * 0.8, "{} against {}", k.area_m2, under.passed_m2);
        let most = under.passed_m2 + 2.0 * (length + width) * (3.0 + 1.5) + std::f64::consts::PI * 4.5 * 4.5;
        assert!(k.area_m2 < most, "{} against {most}", k.area_m2);
    }

    /// A triangle meets a cell wherever they share a point: a sliver across
    /// it with no corner in it and missing its centre (a pipe's long side),
    /// one touching its edge; not one beside it.
    #[test]
    fn triangles_meet_the_cells_they_cross() {
        let cell = [0.0, 0.0, 1.0, 1.0];
        let sliver = [[-5.0, 0.1], [6.0, 0.12], [6.0, 0.14]];
        assert!(triangle_meets_square(&sliver, cell));
        assert!(triangle_meets_square(&[[1.0, 0.5], [3.0, 0.5], [3.0, 2.0]], cell));
        assert!(!triangle_meets_square(&[[1.1, 0.5], [3.0, 0.5], [3.0, 2.0]], cell));
        // Beside the cell's corner: its bounding box overlaps the cell, its
        // long edge's normal parts them.
        assert!(!triangle_meets_square(&[[0.8, 1.9], [1.9, 0.8], [3.0, 3.0]], cell));
    }

    /// Without scans, what the plant model does not reach is said.
    #[test]
    fn without_scans_what_the_model_does_not_reach_is_said() {
        let c = coverage(&(vec![], vec![]), &TriMesh::default(), &[]);
        assert!(!c.scans && !c.load_passes_unscanned(), "{c:?}");
        assert_eq!(c.under_load.unknown_m2, c.under_load.passed_m2);
        assert!(c.line().contains("no scans") && c.line().contains("outside the plant model"), "{}", c.line());
    }
}
