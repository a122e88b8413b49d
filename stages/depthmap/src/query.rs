//! Queries of crane parts (OBBs) against a depth map.
//!
//! Every answer is conservative: a box that touches an obstacle in a cell is
//! always reported; a box may be reported in a cell next to a real obstacle
//! (intervals cover whole cells) but never "free" when it is not.
//!
//! Fast path: the max-height pyramid. If the box's lowest point is above the
//! highest obstacle of every pyramid tile under its footprint, it is free without
//! looking at a single interval. Otherwise each cell under the footprint whose top
//! reaches the box is tested exactly: the box's height range over that cell's
//! column ([`Obb::z_range_over_rect`]) against the cell's intervals.
//!
//! The GPU twin (`crate::gpu::Gpu::hits_where`) follows this walk, in this
//! order, and answers only what it can prove gives these answers; keep the two
//! in step when changing the walk (its tests compare them box for box).
//!
//! Vertical clearance ([`Mdm::clearance`]): how far a box can move straight
//! down or up before it meets an obstacle, from the same per-cell test. Its
//! GPU twin (`crate::gpu::Gpu::clearances_where`) narrows each box down to a
//! few cells and has `Mdm::clearance_in_cells` measure them: keep the
//! per-cell test (`Mdm::cell_clearance`) and the tie rule (`keep_first`)
//! the one both paths use.

use crate::mdm::{Interval, Mdm};
use liftplan_core::frame::Aabb;
use liftplan_core::obb::{Obb, strip_x_range};
use rayon::prelude::*;

/// Where a box meets the map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    pub i: u32,
    pub j: u32,
    pub interval: Interval,
}

/// Intervals a query leaves out: those of object `obj` whose top is at or
/// below `up_to_m` (m, site frame). The scanned ground the crane stands on,
/// for the parts that stand on it or swing just above it, while a bank
/// rising above that level still counts for them.
///
/// The same rule on the CPU ([`LeaveOut::counts`], for [`Mdm::hit_where`]
/// and [`Mdm::clearance_where`]) and on the GPU
/// ([`crate::gpu::Gpu::hits_where`], [`crate::gpu::Gpu::clearances_where`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeaveOut {
    pub obj: u32,
    /// Never NaN; `+inf` leaves out the whole object.
    up_to_m: f32,
}

impl LeaveOut {
    /// Leaves out every interval of `obj`.
    pub fn object(obj: u32) -> LeaveOut {
        LeaveOut { obj, up_to_m: f32::INFINITY }
    }

    /// Leaves out the intervals of `obj` whose top is at or below `z_m`:
    /// `z_m` is rounded down to `f32` (never more left out than asked); a
    /// NaN leaves nothing out.
    pub fn up_to(obj: u32, z_m: f64) -> LeaveOut {
        let mut z = z_m as f32;
        if (z as f64) > z_m {
            z = z.next_down();
        }
        LeaveOut { obj, up_to_m: if z.is_nan() { f32::NEG_INFINITY } else { z } }
    }

    /// The height at or below which the object is left out (m).
    pub fn up_to_m(&self) -> f32 {
        self.up_to_m
    }

    /// Whether `iv` counts for a query that leaves out `leave`.
    pub fn counts(leave: Option<LeaveOut>, iv: &Interval) -> bool {
        match leave {
            Some(l) => !(iv.obj == l.obj && iv.zhi <= l.up_to_m),
            None => true,
        }
    }
}

/// The pyramid tiles a walk over a box's cells starts from (level `lvl`;
/// columns and rows, inclusive), in row order.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct StartTiles {
    pub lvl: usize,
    pub cols: std::ops::RangeInclusive<u32>,
    pub rows: std::ops::RangeInclusive<u32>,
}

/// Which way [`Mdm::clearance`] moves a box: straight down (how high it
/// hangs over what is under it) or straight up (its headroom).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Vertical {
    Down,
    Up,
}

/// How far a box can move one way ([`Vertical`]) before it meets the map.
///
/// As conservative as the box queries: the map may put an obstacle nearer
/// than it is (intervals cover whole cells), never farther.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clearance {
    /// Metres the box can move before it touches the interval at `at` (with
    /// its heights over that cell). Zero or less: it meets that interval now,
    /// which reaches `-gap_m` metres past the box's bottom (moving down: the
    /// interval's top is that far above it) or top (moving up).
    pub gap_m: f32,
    /// The obstacle it meets first: the smallest gap, and of equal gaps the
    /// first in row order of the cells and in height order in a cell.
    pub at: Hit,
}

impl Mdm {
    /// Highest top over the cells of a plan rectangle, from the pyramid.
    pub fn max_top_in(&self, xa: f64, xb: f64, ya: f64, yb: f64) -> f32 {
        let s = &self.spec;
        let (ci, cj) = (s.cols_between(xa, xb), s.rows_between(ya, yb));
        if ci.is_empty() || cj.is_empty() {
            return f32::NEG_INFINITY;
        }
        let lvl = self.cover_level(&ci, &cj);
        let (w, _, data) = &self.pyramid[lvl];
        let mut m = f32::NEG_INFINITY;
        for j in (cj.start >> lvl)..=((cj.end - 1) >> lvl) {
            for i in (ci.start >> lvl)..=((ci.end - 1) >> lvl) {
                m = m.max(data[(j * w + i) as usize]);
            }
        }
        m
    }

    /// The coarsest pyramid level at which a block of cells spans at most
    /// 2 x 2 tiles (or whatever the pyramid has).
    fn cover_level(&self, ci: &std::ops::Range<u32>, cj: &std::ops::Range<u32>) -> usize {
        let span = (ci.end - ci.start).max(cj.end - cj.start);
        let mut lvl = 0usize;
        while lvl + 1 < self.pyramid.len() && (1u32 << (lvl + 1)) < span {
            lvl += 1;
        }
        lvl
    }

    /// Calls `f(i, j)` for every cell under the box's footprint, row by row.
    pub fn for_cells_under(&self, b: &Obb, mut f: impl FnMut(u32, u32) -> bool) {
        let s = self.spec;
        let poly = b.footprint();
        let aabb = b.aabb();
        for j in s.rows_between(aabb.min[1], aabb.max[1]) {
            let r = s.rect(0, j);
            let Some((xa, xb)) = strip_x_range(&poly, r[2], r[3]) else { continue };
            for i in s.cols_between(xa, xb) {
                if !f(i, j) {
                    return;
                }
            }
        }
    }

    /// First place where `b` meets an obstacle, if any.
    pub fn hit(&self, b: &Obb) -> Option<Hit> {
        self.hit_where(b, |_| true)
    }

    /// First place where `b` meets an obstacle that `counts` (e.g. everything but
    /// the ground under a crane's carrier), if any.
    ///
    /// Descends the max-height pyramid from tiles about the box's size: a tile
    /// whose highest top is below the box's lowest point over that tile (or that
    /// the box does not stand over) is skipped with everything in it, so a big
    /// box over mostly low ground costs a handful of tile tests instead of one
    /// test per cell. Cells are tested exactly as before; the answer (hit or
    /// not) is the same as testing every cell under the box.
    pub fn hit_where(&self, b: &Obb, counts: impl Fn(&Interval) -> bool) -> Option<Hit> {
        let aabb = b.aabb();
        let zmin = aabb.min[2] as f32;
        let start = self.start_tiles(&aabb)?;
        for tj in start.rows.clone() {
            for ti in start.cols.clone() {
                if let Some(h) = self.descend(b, zmin, &counts, start.lvl, ti, tj) {
                    return Some(h);
                }
            }
        }
        None
    }

    /// Where the walks over a box's cells start: the pyramid tiles about the
    /// box's size that cover the cells under its bounding box `aabb`; `None`
    /// when those miss the grid. The box query, the clearance and their GPU
    /// twin all start here.
    pub(crate) fn start_tiles(&self, aabb: &Aabb) -> Option<StartTiles> {
        let s = self.spec;
        let (ci, cj) = (s.cols_between(aabb.min[0], aabb.max[0]), s.rows_between(aabb.min[1], aabb.max[1]));
        if ci.is_empty() || cj.is_empty() || self.pyramid.is_empty() {
            return None;
        }
        let lvl = self.cover_level(&ci, &cj);
        Some(StartTiles {
            lvl,
            cols: (ci.start >> lvl)..=((ci.end - 1) >> lvl),
            rows: (cj.start >> lvl)..=((cj.end - 1) >> lvl),
        })
    }

    /// The highest top in pyramid tile (`ti`, `tj`) of level `lvl` (`-inf`
    /// if it is empty), or `None` past the level's edge.
    fn tile_top(&self, lvl: usize, ti: u32, tj: u32) -> Option<f32> {
        let (w, h, tops) = &self.pyramid[lvl];
        (ti < *w && tj < *h).then(|| tops[(tj * w + ti) as usize])
    }

    /// Orders tiles of level `lvl` highest top first (those past the edge
    /// last): the clearance's walk down, where the highest tile likely holds
    /// the smallest gap and the lower ones then fall to its bound.
    fn highest_first(&self, lvl: usize, tiles: &mut [(u32, u32)]) {
        let top = |&(i, j): &(u32, u32)| self.tile_top(lvl, i, j).unwrap_or(f32::NEG_INFINITY);
        tiles.sort_by(|a, b| top(b).total_cmp(&top(a)));
    }

    /// The box's height range over the column of pyramid tile (`ti`, `tj`)
    /// of level `lvl` (a cell at level 0), rounded to `f32` as the map is, or
    /// `None` if the box does not reach it: the one test both walks make, so
    /// that a box query and a clearance see the same cells.
    fn tile_z_range(&self, b: &Obb, lvl: usize, ti: u32, tj: u32) -> Option<(f32, f32)> {
        let s = self.spec;
        let (i0, j0) = (ti << lvl, tj << lvl);
        let (i1, j1) = (((ti + 1) << lvl).min(s.nx), ((tj + 1) << lvl).min(s.ny));
        let c = s.cell;
        let (x0, x1) = (s.x0 + i0 as f64 * c, s.x0 + i1 as f64 * c);
        let (y0, y1) = (s.y0 + j0 as f64 * c, s.y0 + j1 as f64 * c);
        let (lo, hi) = b.z_range_over_rect(x0, x1, y0, y1)?;
        Some((lo as f32, hi as f32))
    }

    fn descend(
        &self,
        b: &Obb,
        zmin: f32,
        counts: &impl Fn(&Interval) -> bool,
        lvl: usize,
        ti: u32,
        tj: u32,
    ) -> Option<Hit> {
        let top = self.tile_top(lvl, ti, tj)?;
        if top < zmin {
            return None;
        }
        let (lo, hi) = self.tile_z_range(b, lvl, ti, tj)?;
        if top < lo {
            return None;
        }
        if lvl == 0 {
            for iv in self.cell(ti, tj) {
                if iv.zlo > hi {
                    break;
                }
                if iv.zhi >= lo && counts(iv) {
                    return Some(Hit { i: ti, j: tj, interval: *iv });
                }
            }
            return None;
        }
        for (dj, di) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            if let Some(h) = self.descend(b, zmin, counts, lvl - 1, 2 * ti + di, 2 * tj + dj) {
                return Some(h);
            }
        }
        None
    }

    pub fn collides(&self, b: &Obb) -> bool {
        self.hit(b).is_some()
    }

    /// Many boxes at once, in parallel; answers in input order.
    pub fn hits(&self, boxes: &[Obb]) -> Vec<Option<Hit>> {
        boxes.par_iter().map(|b| self.hit(b)).collect()
    }

    /// How far `b` can move straight down or up before it meets an obstacle
    /// in the cells under it (see [`Clearance`]); `None` when nothing under
    /// or over it lies that way.
    pub fn clearance(&self, b: &Obb, way: Vertical) -> Option<Clearance> {
        self.clearance_where(b, way, |_| true)
    }

    /// [`Mdm::clearance`] to the obstacles that `counts` only (e.g. everything
    /// but the ground under a crane's carrier).
    ///
    /// Every cell under the box is tested as [`Mdm::hit_where`] tests it:
    /// the box's height range over the cell's column
    /// ([`Obb::z_range_over_rect`], rounded to `f32` as the map is) against
    /// the cell's intervals. So the box meets something (`hit_where` is
    /// `Some`) exactly when the gap is zero or less, either way. Moving down,
    /// the box meets every interval that starts no higher than its top over
    /// the cell, when its bottom reaches the interval's top; moving up,
    /// symmetrically.
    ///
    /// The walk descends the max-height pyramid as `hit_where` does, but
    /// cannot stop at the first contact: it skips a tile only when nothing in
    /// it can beat the gap found so far (moving down: the box's lowest point
    /// over the tile, less the tile's top, is larger by a millimetre and the
    /// rounding of the heights; moving up: everything in the tile lies below
    /// the box by as much). Of
    /// equal gaps it keeps the lowest row, then column, then the first in the
    /// cell's height order, so the answer does not depend on the walk's order.
    pub fn clearance_where(&self, b: &Obb, way: Vertical, counts: impl Fn(&Interval) -> bool) -> Option<Clearance> {
        let StartTiles { lvl, cols, rows } = self.start_tiles(&b.aabb())?;
        let mut tiles: Vec<(u32, u32)> = rows.flat_map(|tj| cols.clone().map(move |ti| (ti, tj))).collect();
        if way == Vertical::Down {
            self.highest_first(lvl, &mut tiles);
        }
        let mut best = None;
        for (ti, tj) in tiles {
            self.descend_clearance(b, way, &counts, (lvl, ti, tj), &mut best);
        }
        best
    }

    fn descend_clearance(
        &self,
        b: &Obb,
        way: Vertical,
        counts: &impl Fn(&Interval) -> bool,
        (lvl, ti, tj): (usize, u32, u32),
        best: &mut Option<Clearance>,
    ) {
        let Some(top) = self.tile_top(lvl, ti, tj) else { return };
        if top == f32::NEG_INFINITY {
            return;
        }
        let Some((lo, _)) = self.tile_z_range(b, lvl, ti, tj) else { return };
        let hopeless = match way {
            // Every gap in the tile is at least `lo - top`, less the rounding
            // of two `f32` subtractions (its and the cell's), which
            // `spare_m` covers many times over at any height.
            Vertical::Down => best.is_some_and(|b| lo - top > b.gap_m + spare_m(lo, top)),
            Vertical::Up => top < lo - spare_m(lo, top),
        };
        if hopeless {
            return;
        }
        if lvl > 0 {
            let mut children = [(0, 0), (0, 1), (1, 0), (1, 1)].map(|(dj, di)| (2 * ti + di, 2 * tj + dj));
            if way == Vertical::Down {
                self.highest_first(lvl - 1, &mut children);
            }
            for (i, j) in children {
                self.descend_clearance(b, way, counts, (lvl - 1, i, j), best);
            }
            return;
        }
        if let Some(found) = self.cell_clearance(b, way, counts, ti, tj) {
            keep_first(best, found);
        }
    }

    /// The smallest gap between `b`, moved `way`, and an interval of cell
    /// (`i`, `j`) that `counts`, with the box's heights over the cell's
    /// column; of equal gaps the first in height order. `None` when the box
    /// does not reach the cell's column or nothing in it lies that way.
    fn cell_clearance(
        &self,
        b: &Obb,
        way: Vertical,
        counts: &impl Fn(&Interval) -> bool,
        i: u32,
        j: u32,
    ) -> Option<Clearance> {
        let (lo, hi) = self.tile_z_range(b, 0, i, j)?;
        let mut found: Option<Clearance> = None;
        for iv in self.cell(i, j) {
            let gap = match way {
                // Sorted by bottom: the rest start above the box too.
                Vertical::Down if iv.zlo > hi => break,
                Vertical::Down => lo - iv.zhi,
                Vertical::Up if iv.zhi < lo => continue,
                Vertical::Up => iv.zlo - hi,
            };
            if counts(iv) && found.is_none_or(|f| gap < f.gap_m) {
                found = Some(Clearance { gap_m: gap, at: Hit { i, j, interval: *iv } });
            }
        }
        found
    }

    /// [`Mdm::clearance_where`] when the answer is known to lie in one of
    /// `cells` (indices `j * nx + i`, in any order): the GPU twin's last
    /// step, which has proved that every other cell's gap is larger.
    pub(crate) fn clearance_in_cells(
        &self,
        b: &Obb,
        way: Vertical,
        counts: impl Fn(&Interval) -> bool,
        cells: &[u32],
    ) -> Option<Clearance> {
        let nx = self.spec.nx;
        let mut best = None;
        for &c in cells {
            if let Some(found) = self.cell_clearance(b, way, &counts, c % nx, c / nx) {
                keep_first(&mut best, found);
            }
        }
        best
    }

    /// [`Mdm::clearance`] of many boxes at once, in parallel; answers in input order.
    pub fn clearances(&self, boxes: &[Obb], way: Vertical) -> Vec<Option<Clearance>> {
        boxes.par_iter().map(|b| self.clearance(b, way)).collect()
    }

    /// Name of an interval's object.
    pub fn object_name(&self, iv: &Interval) -> &str {
        self.objects.get(iv.obj as usize).map(|s| s.as_str()).unwrap_or("unknown object")
    }
}

/// Keeps in `best` the clearance the walk must answer: the smallest gap, and
/// of equal gaps the lowest row, then column (a cell's own ties are settled
/// by `Mdm::cell_clearance`); so the answer does not depend on the order
/// in which cells are tested.
fn keep_first(best: &mut Option<Clearance>, found: Clearance) {
    let first = |c: &Clearance| (c.at.j, c.at.i);
    if best.is_none_or(|b| found.gap_m < b.gap_m || (found.gap_m == b.gap_m && first(&found) < first(&b))) {
        *best = Some(found);
    }
}

/// Room for the rounding of the `f32` subtractions that give gaps and their
/// bounds from heights `a` and `b`: a millimetre, and 16 times the largest
/// rounding error of one subtraction (2^-24 of the operands), so that a
/// tile's bound never skips a cell whose own test would tie or win, at any
/// height.
fn spare_m(a: f32, b: f32) -> f32 {
    1e-3 + (a.abs() + b.abs()) * (1.0 / (1u32 << 20) as f32)
}
