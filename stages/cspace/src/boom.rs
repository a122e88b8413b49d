//! The boom rows of the hybrid C-space of a luffing crane, marked obstacle by
//! obstacle instead of by one box query per (swing, luff) cell.
//!
//! A box query per cell walks the ~160 depth-map cells under a 40 m boom for
//! each of ~10^5 cells. Here every depth-map interval near the crane is visited
//! once or a few times and turned into the block of swing columns and luff rows
//! in which the boom can touch it; the blocks are painted into the table.
//!
//! **The geometry.** At swing `s` and luff `θ` the boom grown by `g` is a box:
//! in the vertical plane through the slewing axis at `s`, with the boom foot pin
//! as origin, the strip `{t·u(θ) + n·u⊥(θ) : -g ≤ t ≤ L + g, |n| ≤ h}` (`h` the
//! half depth plus `g`); across the plane `|b| ≤ w/2 + g`. A point of the strip
//! farther than `√(g² + h²)` from the pin has `t > 0`, so it lies within
//! `asin(h / ρ)` of the direction `θ`: a plane rectangle whose nearest point is
//! `ρ_min` from the pin can meet the strip only for `θ` within `asin(h / ρ_min)`
//! of the rectangle's angular span seen from the pin. Nearer rectangles block
//! every row.
//!
//! **Far from the slewing axis** (most of the site) a depth-map cell at plan
//! distance `R ∈ [R_min, R_max]` from the axis is across-plane within reach only
//! for swings within `asin(lat / R_min)` of its bearing, and there its distance
//! along the plane is at least `√(R_min² - lat²)`: one plane rectangle per
//! interval serves every swing column the cell reaches, and the swing motion
//! within a column needs no growing because the bearing window is exact.
//! **Near the axis** that bound is loose, so each column projects the near cells
//! onto its centre plane exactly and grows the boom by how far a point within
//! `r_near` of the axis moves within half a column.
//!
//! Conservative like every table entry: a cell left free is free for every
//! configuration inside it with the boom grown by the clearance. What this
//! module must not do: mark anything but the boom (other radial parts use box
//! queries in `lib.rs`).

use crate::{CSpace, CellHit, Problem, left_out};
use liftplan_core::crane::{Boom, PartKind};
use liftplan_core::frame::{Mat3, Point3, Vec3};
use liftplan_core::obb::Obb;
use liftplan_depthmap::mdm::Interval;
use rayon::prelude::*;
use std::f64::consts::TAU;

/// Bound on the error of [`atan2_fast`] (rad), with room for rounding; every
/// angle below is widened by it.
const ANGLE_TOL: f64 = 1e-6;

/// `atan2` to within 2·10⁻⁸ rad (Abramowitz & Stegun 4.4.49 on [0, 1], then
/// the octant symmetries): a few multiplications instead of libm's call, on
/// the hottest line of the build.
pub(crate) fn atan2_fast(y: f64, x: f64) -> f64 {
    const A: [f64; 8] = [
        -0.333_331_452_8,
        0.199_935_508_5,
        -0.142_088_994_4,
        0.106_562_639_3,
        -0.075_289_640_0,
        0.042_909_613_8,
        -0.016_165_736_7,
        0.002_866_225_7,
    ];
    let (ax, ay) = (x.abs(), y.abs());
    let (num, den) = if ay <= ax { (ay, ax) } else { (ax, ay) };
    if den == 0.0 {
        return 0.0;
    }
    let z = num / den;
    let z2 = z * z;
    let mut poly = A[7];
    for a in A[..7].iter().rev() {
        poly = poly * z2 + *a;
    }
    let mut r = z * (poly * z2 + 1.0);
    if ay > ax {
        r = std::f64::consts::FRAC_PI_2 - r;
    }
    if x < 0.0 {
        r = std::f64::consts::PI - r;
    }
    if y < 0.0 { -r } else { r }
}

/// `x.floor()` for |x| < 10^15 (infinities clamp to ±10^15), inline: the
/// baseline x86-64 target has no rounding instruction, so `floor` is a call.
fn floor(x: f64) -> f64 {
    let c = x.clamp(-1e15, 1e15);
    let t = c as i64 as f64;
    if t > c { t - 1.0 } else { t }
}

/// The grown boom in its plane: length `len` from the pin (see [`Strip::new`]),
/// grown by `g` at both ends, half thickness `h` in the plane, half width `lat`
/// across it (m).
#[derive(Debug, Clone, Copy)]
struct Strip {
    g: f64,
    h: f64,
    lat: f64,
    /// Lowest and highest luff of the table (rad).
    luff_range: (f64, f64),
    /// Farthest point of the strip from the pin (a corner of its far end),
    /// `hypot(len + g, h)`: computed once, it is needed for every interval.
    reach: f64,
}

impl Strip {
    fn new(boom: &Boom, len: f64, g: f64, cs: &CSpace) -> Strip {
        let luff_range = (cs.radial0, cs.radial0 + cs.nr as f64 * cs.radial_step);
        let h = boom.depth_m / 2.0 + g;
        Strip { g, h, lat: boom.width_m / 2.0 + g, luff_range, reach: (len + g).hypot(h) }
    }

    /// Luff angles (rad) at which the strip may meet the plane rectangle
    /// `[x0, x1] x [y0, y1]` (pin at the origin), or `None` if at none.
    fn luff_interval(&self, x0: f64, x1: f64, y0: f64, y1: f64) -> Option<(f64, f64)> {
        let dx = if x0 > 0.0 {
            x0
        } else if x1 < 0.0 {
            -x1
        } else {
            0.0
        };
        let dy = if y0 > 0.0 {
            y0
        } else if y1 < 0.0 {
            -y1
        } else {
            0.0
        };
        let rho2 = dx * dx + dy * dy;
        let reach = self.reach;
        if rho2 > reach * reach {
            return None;
        }
        // Only the part within reach matters: clip to the bounding box of the
        // reach disc's part over [x0, ∞) (the disc is widest at x0 there).
        let ylim = if x0 > 0.0 { (reach * reach - x0 * x0).max(0.0).sqrt() } else { reach };
        let (x1, y0, y1) = (x1.min(reach), y0.max(-ylim), y1.min(ylim));
        if rho2 <= self.g * self.g + self.h * self.h {
            return Some((f64::NEG_INFINITY, f64::INFINITY));
        }
        // asin(h / ρ) as the direction (c, h) with c = √(ρ² − h²), here ρ > h.
        let c = (rho2 - self.h * self.h).sqrt();
        if x0 > 0.0 {
            // In front of the pin (the usual case). Cheap bounds: the lowest
            // bearing is at the bottom corner farthest out if the bottom is above
            // the pin, else nearest in; the highest symmetrically; each turned by
            // ∓asin(h/ρ_min) by rotating the corner (both stay inside (−π, π)).
            let (xa, ya) = (if y0 >= 0.0 { x1 } else { x0 }, y0);
            let (xb, yb) = (if y1 >= 0.0 { x0 } else { x1 }, y1);
            let mut f0 = atan2_fast(ya * c - xa * self.h, xa * c + ya * self.h) - ANGLE_TOL;
            let mut f1 = atan2_fast(yb * c + xb * self.h, xb * c - yb * self.h) + ANGLE_TOL;
            // Corner-wise bounds, tighter when those corners are much farther
            // than the nearest point (tall rectangles). A corner v is strictly
            // below the strip's lower edge for θ in (φ_v + a_v, φ_v + π − a_v),
            // a_v = asin(h/ρ_v), and strictly above its upper edge for θ in
            // (φ_v − π + a_v, φ_v − a_v). If all four corners, hence the whole
            // rectangle, are on one side, the strip misses it. So no θ of the
            // crane above max(φ_v + a_v) meets it as long as min(φ_v − a_v) + π
            // (at least the cheap lower bound + π) exceeds the highest luff; and
            // symmetrically below.
            let (lo_luff, hi_luff) = self.luff_range;
            let tilt = |x: f64, y: f64, up: bool| {
                let cv = (x * x + y * y - self.h * self.h).sqrt();
                if up {
                    atan2_fast(y * cv + x * self.h, x * cv - y * self.h)
                } else {
                    atan2_fast(y * cv - x * self.h, x * cv + y * self.h)
                }
            };
            if xb * xb + yb * yb > 1.1 * rho2 && f0 + std::f64::consts::PI > hi_luff + ANGLE_TOL {
                // Along an edge at or above the pin's height the near corner has
                // the larger bearing and the smaller distance: it dominates.
                let top_edge: &[(f64, f64)] = if y1 >= 0.0 { &[(x0, y1)] } else { &[(x0, y1), (x1, y1)] };
                let bottom_edge: &[(f64, f64)] = if y0 >= 0.0 { &[(x0, y0)] } else { &[(x0, y0), (x1, y0)] };
                let u = top_edge
                    .iter()
                    .chain(bottom_edge)
                    .map(|&(x, y)| tilt(x, y, true))
                    .fold(f64::NEG_INFINITY, f64::max);
                f1 = f1.min(u + ANGLE_TOL);
            }
            if xa * xa + ya * ya > 1.1 * rho2 && f1 - std::f64::consts::PI < lo_luff - ANGLE_TOL {
                // Along an edge at or below the pin's height the near corner has
                // the smaller bearing and the smaller distance: it dominates.
                let bottom_edge: &[(f64, f64)] = if y0 <= 0.0 { &[(x0, y0)] } else { &[(x0, y0), (x1, y0)] };
                let top_edge: &[(f64, f64)] = if y1 <= 0.0 { &[(x0, y1)] } else { &[(x0, y1), (x1, y1)] };
                let l =
                    bottom_edge.iter().chain(top_edge).map(|&(x, y)| tilt(x, y, false)).fold(f64::INFINITY, f64::min);
                f0 = f0.max(l - ANGLE_TOL);
            }
            return Some((f0, f1));
        }
        let alpha = atan2_fast(self.h, c) + ANGLE_TOL;
        // A rectangle behind the pin and across its height straddles ±π: take
        // its angles in [0, 2π) there so they are contiguous.
        let wrap = x1 < 0.0 && y0 <= 0.0 && y1 >= 0.0;
        let (mut f0, mut f1) = (f64::INFINITY, f64::NEG_INFINITY);
        for (x, y) in [(x0, y0), (x1, y0), (x0, y1), (x1, y1)] {
            let f = atan2_fast(y, x);
            let f = if wrap { f.rem_euclid(TAU) } else { f };
            f0 = f0.min(f);
            f1 = f1.max(f);
        }
        Some((f0 - alpha, f1 + alpha))
    }
}

/// Luff rows overlapping the luff interval `[lo, hi]` (also one turn lower,
/// for intervals taken in [0, 2π)).
fn rows_of(cs: &CSpace, lo: f64, hi: f64, mut emit: impl FnMut(u32, u32)) {
    // Not a number would be a bug upstream; block everything rather than nothing.
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (f64::NEG_INFINITY, f64::INFINITY) };
    let last = cs.nr as f64 - 1.0;
    for shift in [0.0, -TAU] {
        if hi + shift + ANGLE_TOL < cs.radial0 {
            continue;
        }
        let k0 = floor((lo + shift - ANGLE_TOL - cs.radial0) / cs.radial_step).max(0.0);
        let k1 = floor((hi + shift + ANGLE_TOL - cs.radial0) / cs.radial_step).min(last);
        if k0 <= k1 {
            emit(k0 as u32, k1 as u32);
        }
    }
}

/// The luff rows at which `strip` may meet each obstacle interval of a cell
/// whose extent along the boom's plane is `[x0, x1]` from the pin (at height
/// `pz`); intervals outside `[z_floor, z_ceil]` cannot be reached.
///
/// Intervals less than the strip's thickness `2h` apart are taken together:
/// wherever the strip has its full thickness, its vertical chord is at least
/// `2h` long, so it cannot meet the gap between them without meeting one of
/// them in the same column, and the rows are those of the two. Only at the
/// strip's ends can this block a row more (never less). Cluttered sites (pipe
/// racks, stacked steel) have many such intervals per cell.
fn cell_rows(
    cs: &CSpace,
    strip: &Strip,
    cell: &[Interval],
    (x0, x1): (f64, f64),
    pz: f64,
    (z_floor, z_ceil): (f64, f64),
    mut emit: impl FnMut(u32, u32, u32),
) {
    let mut flush = |(zlo, zhi, obj): (f64, f64, u32)| {
        if let Some((lo, hi)) = strip.luff_interval(x0, x1, zlo - pz, zhi - pz) {
            rows_of(cs, lo, hi, |k0, k1| emit(k0, k1, obj));
        }
    };
    let mut run: Option<(f64, f64, u32)> = None;
    for iv in cell {
        let (zlo, zhi) = (iv.zlo as f64, iv.zhi as f64);
        if zlo > z_ceil {
            break;
        }
        // Every interval counts for the boom ([`left_out`] leaves none out for it).
        if zhi < z_floor {
            continue;
        }
        run = match run {
            Some((lo, hi, obj)) if zlo - hi < 2.0 * strip.h => Some((lo, hi.max(zhi), obj)),
            Some(done) => {
                flush(done);
                Some((zlo, zhi, iv.obj))
            }
            None => Some((zlo, zhi, iv.obj)),
        };
    }
    if let Some(done) = run {
        flush(done);
    }
}

/// A block of the table blocked by one obstacle: swing columns `c0 ..= c0 + cn`
/// (modulo a turn, `c0` in `0..ns`) and luff rows `k0 ..= k1`.
#[derive(Debug, Clone, Copy)]
struct Span {
    c0: i64,
    cn: u32,
    k0: u32,
    k1: u32,
    obj: u32,
}

/// One column's rows, each painted once by the first obstacle that covers it.
struct Column {
    /// Bit k set once row k is painted.
    painted: Vec<u64>,
    hits: Vec<Option<u32>>,
}

impl Column {
    fn new(nr: u32) -> Column {
        Column { painted: vec![0; (nr as usize).div_ceil(64)], hits: vec![None; nr as usize] }
    }

    fn paint(&mut self, k0: u32, k1: u32, obj: u32) {
        if let Some(rows) = RowMask::within(k0, k1, self.hits.len() as u32) {
            self.paint_rows(&rows, obj);
        }
    }

    fn paint_rows(&mut self, rows: &RowMask, obj: u32) {
        for w in rows.w0..=rows.w1 {
            let mut mask = u64::MAX;
            if w == rows.w0 {
                mask &= rows.first;
            }
            if w == rows.w1 {
                mask &= rows.last;
            }
            let word = &mut self.painted[w as usize];
            let mut free = mask & !*word;
            *word |= mask;
            while free != 0 {
                self.hits[(w * 64 + free.trailing_zeros()) as usize] = Some(obj);
                free &= free - 1;
            }
        }
    }
}

/// Rows `k0 ..= k1` as bit masks over a column's 64-row words: words
/// `w0 ..= w1`, the first and last of them masked. Computed once per span and
/// applied to each of its ~20 columns.
struct RowMask {
    w0: u32,
    w1: u32,
    first: u64,
    last: u64,
}

impl RowMask {
    /// Rows `k0 ..= k1` of a column of `nr` rows (`k1` clipped to the last),
    /// `None` if that leaves none.
    fn within(k0: u32, k1: u32, nr: u32) -> Option<RowMask> {
        let k1 = k1.min(nr.checked_sub(1)?);
        (k0 <= k1).then(|| RowMask {
            w0: k0 / 64,
            w1: k1 / 64,
            first: u64::MAX << (k0 % 64),
            last: u64::MAX >> (63 - k1 % 64),
        })
    }
}

/// Nearest and farthest plan distance of a cell rectangle from `(ox, oy)`.
fn distance_range(r: &[f64; 4], ox: f64, oy: f64) -> (f64, f64) {
    let dx = (r[0] - ox).max(ox - r[1]).max(0.0);
    let dy = (r[2] - oy).max(oy - r[3]).max(0.0);
    let fx = (r[0] - ox).abs().max((r[1] - ox).abs());
    let fy = (r[2] - oy).abs().max((r[3] - oy).abs());
    ((dx * dx + dy * dy).sqrt(), (fx * fx + fy * fy).sqrt())
}

/// The boom's table entries, row-major (`k * ns + i`).
pub(crate) fn boom_hits(cs: &CSpace, p: &Problem, boom: &Boom, clearance: f64) -> Vec<Option<CellHit>> {
    let crane = &p.task.crane;
    debug_assert!(left_out(crane, PartKind::Boom).is_none(), "the boom marking counts every interval");
    let map = p.map;
    let spec = map.spec;
    let o = crane.slew_center();
    let heading = crane.placement.heading_rad;
    let len = crane.placement.boom_length_m + boom.head_length_m;
    let (pa, pz) = (boom.pivot_x_m, o.z + boom.pivot_z_m);
    let far = Strip::new(boom, len, clearance, cs);
    let diag = spec.cell * std::f64::consts::SQRT_2;
    // Beyond r_near every relevant point is in front of the pin (a > 0); the
    // 2 m margin keeps the far bound on the distance along the plane,
    // √(R² − lat²), within ~0.2 m of the truth.
    let r_near = (far.g + far.h - pa).max(0.0) + far.lat + 2.0;
    let near = Strip::new(boom, len, clearance + (r_near + diag) * cs.swing_step / 2.0, cs);
    let z_floor = pz - (len + near.g) * (-cs.radial0.sin()).max(0.0) - near.g - near.h;
    let z_ceil = pz + near.reach;
    let r_lim = (pa.abs() + far.reach).hypot(far.lat);

    // Far cells: one span per interval (per luff-row run), in cell order.
    let (ns, swing_step) = (cs.ns as i64, cs.swing_step);
    let rows: Vec<u32> = spec.rows_between(o.y - r_lim, o.y + r_lim).collect();
    let cols = spec.cols_between(o.x - r_lim, o.x + r_lim);
    let far_spans: Vec<Span> = rows
        .par_iter()
        .flat_map_iter(|&cj| {
            let mut out: Vec<Span> = Vec::new();
            let mut cell_runs: Vec<(u32, u32, u32)> = Vec::new();
            if cols.is_empty() {
                return out;
            }
            // Bearings of the row's grid corners from the axis, each computed
            // once for the two cells that share it: [bottom, top] per grid line.
            let first = spec.rect(cols.start, cj);
            let corner_bearings: Vec<[f64; 2]> = cols
                .clone()
                .map(|ci| spec.rect(ci, cj)[0])
                .chain([spec.rect(cols.end - 1, cj)[1]])
                .map(|x| [first[2], first[3]].map(|y| atan2_fast(y - o.y, x - o.x)))
                .collect();
            for ci in cols.clone() {
                if (map.top(ci, cj) as f64) < z_floor {
                    continue;
                }
                let r = spec.rect(ci, cj);
                let (r_min, r_max) = distance_range(&r, o.x, o.y);
                if r_min < r_near || r_min > r_lim {
                    continue;
                }
                // Bearing window of the cell from the axis.
                let wrap = r[1] < o.x && r[2] <= o.y && r[3] >= o.y;
                let (mut b0, mut b1) = (f64::INFINITY, f64::NEG_INFINITY);
                let k = (ci - cols.start) as usize;
                for b in corner_bearings[k].iter().chain(&corner_bearings[k + 1]) {
                    let b = if wrap { b.rem_euclid(TAU) } else { *b };
                    b0 = b0.min(b);
                    b1 = b1.max(b);
                }
                // Nearest the cell comes along any plane within reach across it.
                let a_min = (r_min * r_min - far.lat * far.lat).sqrt();
                // asin(lat / R_min), here R_min > lat.
                let delta = atan2_fast(far.lat, a_min) + ANGLE_TOL;
                let c0 = floor((b0 - heading - delta - ANGLE_TOL) / swing_step) as i64;
                let c1 = floor((b1 - heading + delta + ANGLE_TOL) / swing_step) as i64;
                let (c0, cn) =
                    if c1 - c0 >= ns - 1 { (0, ns as u32 - 1) } else { (c0.rem_euclid(ns), (c1 - c0) as u32) };
                cell_runs.clear();
                cell_rows(
                    cs,
                    &far,
                    map.cell(ci, cj),
                    (a_min - pa, r_max - pa),
                    pz,
                    (z_floor, z_ceil),
                    |k0, k1, obj| cell_runs.push((k0, k1, obj)),
                );
                // The cell's intervals share its columns: emit the union of
                // their rows once, each row with an obstacle that covers it.
                cell_runs.sort_unstable_by_key(|&(k0, k1, obj)| (k0, std::cmp::Reverse(k1), obj));
                let mut covered: i64 = -1;
                let first = out.len();
                for &(k0, k1, obj) in &cell_runs {
                    if (k1 as i64) <= covered {
                        continue;
                    }
                    let k0 = k0.max((covered + 1) as u32);
                    covered = k1 as i64;
                    let own = out.len() > first;
                    match out.last_mut() {
                        Some(last) if own && last.obj == obj && last.k1 + 1 == k0 => last.k1 = k1,
                        _ => out.push(Span { c0, cn, k0, k1, obj }),
                    }
                }
            }
            out
        })
        .collect();

    // Columns in blocks: near cells per column, then the far spans. Each
    // block gets the spans that reach it, in their order (the first obstacle
    // to cover a cell is the one reported, so the order must not change).
    const BLOCK: u32 = 120;
    let n_blocks = cs.ns.div_ceil(BLOCK) as usize;
    let mut block_spans: Vec<Vec<&Span>> = vec![Vec::new(); n_blocks];
    for s in &far_spans {
        // Columns c0 ..= c0 + cn (c0 < ns, cn < ns), past ns continuing from 0.
        let (c0, c1) = (s.c0 as u32, s.c0 as u32 + s.cn);
        let wrapped = (c1 >= cs.ns).then(|| (0, c1 - cs.ns));
        for (a, b) in [(c0, c1.min(cs.ns - 1))].into_iter().chain(wrapped) {
            for bk in (a / BLOCK) as usize..=(b / BLOCK) as usize {
                if block_spans[bk].last().is_none_or(|l| !std::ptr::eq(*l, s)) {
                    block_spans[bk].push(s);
                }
            }
        }
    }
    let columns: Vec<Vec<Column>> = block_spans
        .par_iter()
        .enumerate()
        .map(|(bk, spans)| {
            let (b0, b1) = (bk as u32 * BLOCK, ((bk as u32 + 1) * BLOCK).min(cs.ns));
            let mut block: Vec<Column> = (b0..b1).map(|_| Column::new(cs.nr)).collect();
            for (col, i) in block.iter_mut().zip(b0..b1) {
                near_column(cs, p, i, &near, (pa, pz), (r_near, z_floor, z_ceil), col);
            }
            let width = (b1 - b0) as i64;
            for s in spans {
                let Some(rows) = RowMask::within(s.k0, s.k1, cs.nr) else { continue };
                // Columns b0 + t with (b0 + t - c0) mod ns <= cn.
                let off = if b0 as i64 >= s.c0 { b0 as i64 - s.c0 } else { b0 as i64 - s.c0 + ns };
                let cn = s.cn as i64;
                let mut paint_range = |t0: i64, t1: i64| {
                    for t in t0.max(0)..=t1.min(width - 1) {
                        block[t as usize].paint_rows(&rows, s.obj);
                    }
                };
                if off <= cn {
                    paint_range(0, cn - off);
                }
                paint_range(ns - off, ns - off + cn);
            }
            block
        })
        .collect();
    let mut hits = vec![None; (cs.nr * cs.ns) as usize];
    for (i, col) in columns.iter().flatten().enumerate() {
        for (k, h) in col.hits.iter().enumerate() {
            hits[k * cs.ns as usize + i] = h.map(|obj| CellHit { part: PartKind::Boom, obj });
        }
    }
    hits
}

/// Near cells of column `i`: projected onto the column's centre plane exactly,
/// with the boom grown for the swing within the column.
fn near_column(
    cs: &CSpace,
    p: &Problem,
    i: u32,
    near: &Strip,
    (pa, pz): (f64, f64),
    (r_near, z_floor, z_ceil): (f64, f64, f64),
    col: &mut Column,
) {
    let crane = &p.task.crane;
    let map = p.map;
    let o = crane.slew_center();
    let d = crane.boom_dir(cs.swing_center(i));
    let side = Vec3::new(-d.y, d.x, 0.0);
    let (a_lo, a_hi) = (pa - near.g - near.h, r_near + map.spec.cell * 2.0);
    let mid = o + d * (0.5 * (a_lo + a_hi));
    let swath = Obb::new(
        Point3::new(mid.x, mid.y, 0.5 * (z_floor + z_ceil)),
        Mat3::from_columns(&[d, side, Vec3::z()]),
        Vec3::new(0.5 * (a_hi - a_lo), near.lat, 0.5 * (z_ceil - z_floor).max(0.0)),
    );
    map.for_cells_under(&swath, |ci, cj| {
        if (map.top(ci, cj) as f64) < z_floor {
            return true;
        }
        let r = map.spec.rect(ci, cj);
        if distance_range(&r, o.x, o.y).0 >= r_near {
            return true;
        }
        let (mut a0, mut a1, mut b0, mut b1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for (x, y) in [(r[0], r[2]), (r[1], r[2]), (r[0], r[3]), (r[1], r[3])] {
            let (dx, dy) = (x - o.x, y - o.y);
            let a = dx * d.x + dy * d.y;
            let b = dy * d.x - dx * d.y;
            a0 = a0.min(a);
            a1 = a1.max(a);
            b0 = b0.min(b);
            b1 = b1.max(b);
        }
        if b0 > near.lat || b1 < -near.lat {
            return true;
        }
        cell_rows(cs, near, map.cell(ci, cj), (a0 - pa, a1 - pa), pz, (z_floor, z_ceil), |k0, k1, obj| {
            col.paint(k0, k1, obj)
        });
        true
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_atan2_is_within_its_tolerance() {
        let mut worst: f64 = 0.0;
        for a in 0..2000 {
            for r in [1e-3, 0.7, 1.0, 13.0, 2e4] {
                let t = a as f64 / 2000.0 * TAU - std::f64::consts::PI + 1e-4;
                let (y, x) = (r * t.sin(), r * t.cos());
                worst = worst.max((atan2_fast(y, x) - y.atan2(x)).abs());
            }
        }
        for (y, x) in [(0.0, 1.0), (1.0, 0.0), (-1.0, 0.0), (1.0, 1.0), (-1.0, -1.0), (0.0, -1.0)] {
            worst = worst.max((atan2_fast(y, x) - f64::atan2(y, x)).abs());
        }
        assert!(worst < ANGLE_TOL / 10.0, "worst error {worst}");
    }

    #[test]
    fn inline_floor_matches() {
        for x in [-2.5, -2.0, -1e-300, -0.0, 0.0, 0.3, 1.0, 7.999_999, 1e14, -1e14] {
            assert_eq!(floor(x), x.floor(), "{x}");
        }
        assert_eq!(floor(f64::INFINITY), 1e15);
        assert_eq!(floor(f64::NEG_INFINITY), -1e15);
    }

    #[test]
    fn painting_keeps_the_first_obstacle() {
        let mut c = Column::new(10);
        c.paint(2, 5, 7);
        c.paint(0, 3, 8);
        c.paint(5, 9, 9);
        c.paint(9, 12, 1);
        let got: Vec<Option<u32>> = c.hits.clone();
        assert_eq!(got, vec![Some(8), Some(8), Some(7), Some(7), Some(7), Some(7), Some(9), Some(9), Some(9), Some(9)]);
    }
}
