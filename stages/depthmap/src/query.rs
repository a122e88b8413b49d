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

use crate::mdm::{Interval, Mdm};
use liftplan_core::obb::{Obb, strip_x_range};
use rayon::prelude::*;

/// Where a box meets the map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    pub i: u32,
    pub j: u32,
    pub interval: Interval,
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
    pub(crate) fn cover_level(&self, ci: &std::ops::Range<u32>, cj: &std::ops::Range<u32>) -> usize {
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
        let s = self.spec;
        let (ci, cj) = (s.cols_between(aabb.min[0], aabb.max[0]), s.rows_between(aabb.min[1], aabb.max[1]));
        if ci.is_empty() || cj.is_empty() || self.pyramid.is_empty() {
            return None;
        }
        let lvl = self.cover_level(&ci, &cj);
        for tj in (cj.start >> lvl)..=((cj.end - 1) >> lvl) {
            for ti in (ci.start >> lvl)..=((ci.end - 1) >> lvl) {
                if let Some(h) = self.descend(b, zmin, &counts, lvl, ti, tj) {
                    return Some(h);
                }
            }
        }
        None
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
        let (w, h, tops) = &self.pyramid[lvl];
        if ti >= *w || tj >= *h {
            return None;
        }
        let top = tops[(tj * w + ti) as usize];
        if top < zmin {
            return None;
        }
        let s = self.spec;
        let (i0, j0) = (ti << lvl, tj << lvl);
        let (i1, j1) = (((ti + 1) << lvl).min(s.nx), ((tj + 1) << lvl).min(s.ny));
        let c = s.cell;
        let (x0, x1) = (s.x0 + i0 as f64 * c, s.x0 + i1 as f64 * c);
        let (y0, y1) = (s.y0 + j0 as f64 * c, s.y0 + j1 as f64 * c);
        let (lo, hi) = b.z_range_over_rect(x0, x1, y0, y1)?;
        let (lo, hi) = (lo as f32, hi as f32);
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

    /// Smallest vertical gap between the box and the obstacles in the cells under
    /// it (negative: overlap), with the obstacle; `None` if there is nothing under
    /// or over it.
    pub fn vertical_clearance(&self, b: &Obb) -> Option<(f32, Interval)> {
        let mut best: Option<(f32, Interval)> = None;
        self.for_cells_under(b, |i, j| {
            let r = self.spec.rect(i, j);
            let Some((lo, hi)) = b.z_range_over_rect(r[0], r[1], r[2], r[3]) else { return true };
            let (lo, hi) = (lo as f32, hi as f32);
            for iv in self.cell(i, j) {
                let gap = if iv.zhi < lo {
                    lo - iv.zhi
                } else if iv.zlo > hi {
                    iv.zlo - hi
                } else {
                    -(iv.zhi.min(hi) - iv.zlo.max(lo))
                };
                if best.is_none_or(|(g, _)| gap < g) {
                    best = Some((gap, *iv));
                }
            }
            true
        });
        best
    }

    /// Name of an interval's object.
    pub fn object_name(&self, iv: &Interval) -> &str {
        self.objects.get(iv.obj as usize).map(|s| s.as_str()).unwrap_or("unknown object")
    }
}
