//! Multi-level depth maps (thesis ch. 3): per cell of a plan grid, the sorted
//! height intervals occupied by the site, each tagged with the object it belongs
//! to.
//!
//! Layout is CSR: `offsets[k]..offsets[k + 1]` index `intervals` for cell `k`
//! (row-major, row 0 at the grid's south edge). Intervals of one cell are sorted
//! by bottom, then top, then object.
//!
//! **Building** follows the thesis' passes, which the GPU twin repeats:
//! 1. *generate*: each point gives `[z - r, z + r]` in every cell its square of
//!    half side `r` touches; each triangle gives, in every cell it touches, a
//!    conservative range of its heights over that cell (see [`triangle_cells`]);
//! 2. *count* the raw intervals per cell, 3. *prefix-sum* the counts into
//!    offsets, 4. *fill* the raw intervals in, 5. *sort and merge* each cell.
//!
//! The CPU fuses pass 1 into a two-level grouping by band and cell
//! ([`assemble_sources`]); the GPU twin (`crate::gpu`) runs the passes as
//! written.
//!
//! **Merging** (identical on CPU and GPU): raw intervals sort by (object, part,
//! bottom, top); intervals of one convex solid (a part) become one interval from
//! its lowest bottom to its highest top, since a vertical line through a convex
//! solid meets it in one segment; surface intervals of the same object merge when
//! they overlap or are less than `merge_gap` apart. A *single-level* map keeps
//! one interval per cell, from the lowest bottom to the highest top (2.5D).
//!
//! All heights are `f32` metres in the site frame; plan coordinates are taken
//! relative to the grid origin before anything else, so the arithmetic is the
//! same single operations in both implementations.

use liftplan_core::artifact::{self, ArtifactError, ByteReader, ByteWriter};
use liftplan_core::mesh::TriMesh;
use rayon::prelude::*;
use std::path::Path;

pub const ARTIFACT_KIND: &str = "MDM";
pub const ARTIFACT_VERSION: u32 = 1;

/// Object id of ground points from the scans.
pub const OBJ_GROUND: u32 = 0;
/// Object id of other scanned points.
pub const OBJ_SCAN: u32 = 1;

/// A plan grid: `nx x ny` square cells of `cell` metres from `(x0, y0)`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GridSpec {
    pub x0: f64,
    pub y0: f64,
    pub cell: f64,
    pub nx: u32,
    pub ny: u32,
}

impl GridSpec {
    pub fn cells(&self) -> usize {
        self.nx as usize * self.ny as usize
    }

    /// Cell rectangle in grid-local metres.
    pub fn rect_local(&self, i: u32, j: u32) -> [f64; 4] {
        let c = self.cell;
        [i as f64 * c, (i + 1) as f64 * c, j as f64 * c, (j + 1) as f64 * c]
    }

    /// Cell rectangle in site coordinates: [x0, x1, y0, y1].
    pub fn rect(&self, i: u32, j: u32) -> [f64; 4] {
        let r = self.rect_local(i, j);
        [r[0] + self.x0, r[1] + self.x0, r[2] + self.y0, r[3] + self.y0]
    }

    /// Column of a site x, clamped into the grid, or `None` outside.
    pub fn col(&self, x: f64) -> Option<u32> {
        let i = ((x - self.x0) / self.cell).floor();
        (i >= 0.0 && i < self.nx as f64).then_some(i as u32)
    }

    pub fn row(&self, y: f64) -> Option<u32> {
        let j = ((y - self.y0) / self.cell).floor();
        (j >= 0.0 && j < self.ny as f64).then_some(j as u32)
    }

    /// Columns overlapping [xa, xb] (site), clamped; empty if none.
    pub fn cols_between(&self, xa: f64, xb: f64) -> std::ops::Range<u32> {
        let a = ((xa - self.x0) / self.cell).floor().max(0.0);
        let b = ((xb - self.x0) / self.cell).floor().min(self.nx as f64 - 1.0);
        if b < a || b < 0.0 || a >= self.nx as f64 { 0..0 } else { a as u32..b as u32 + 1 }
    }

    pub fn rows_between(&self, ya: f64, yb: f64) -> std::ops::Range<u32> {
        let a = ((ya - self.y0) / self.cell).floor().max(0.0);
        let b = ((yb - self.y0) / self.cell).floor().min(self.ny as f64 - 1.0);
        if b < a || b < 0.0 || a >= self.ny as f64 { 0..0 } else { a as u32..b as u32 + 1 }
    }
}

/// One occupied height range of a cell.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct Interval {
    pub zlo: f32,
    pub zhi: f32,
    pub obj: u32,
}

/// A raw interval before merging: `part` is 1 + the convex part's index, or 0
/// for surfaces and points.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct Raw {
    pub cell: u32,
    pub zlo: f32,
    pub zhi: f32,
    pub obj: u32,
    pub part: u32,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    Multi,
    Single,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Mdm {
    pub spec: GridSpec,
    pub mode: Mode,
    pub offsets: Vec<u32>,
    pub intervals: Vec<Interval>,
    /// Object names by id.
    pub objects: Vec<String>,
    /// Max-height pyramid: level 0 is the top of each cell (`-inf` if empty),
    /// level k+1 the max over 2x2 blocks of level k.
    pub pyramid: Vec<(u32, u32, Vec<f32>)>,
}

/// Scan points as the depth map reads them: site coordinates and, per point,
/// whether it is ground. Every pass takes them relative to the grid origin in
/// `f32` with [`local_point`] as it reads them, so no converted copy is stored.
#[derive(Clone, Copy)]
pub struct PointSource<'a> {
    pub xyz: &'a [[f64; 3]],
    /// One flag per point of `xyz`.
    pub ground: &'a [bool],
    /// Half side of the square and half height each point occupies (m).
    pub radius: f32,
}

impl PointSource<'_> {
    /// Object id of point `k`.
    #[inline]
    pub fn obj(&self, k: usize) -> u32 {
        if self.ground[k] { OBJ_GROUND } else { OBJ_SCAN }
    }
}

/// A site point in grid-local `f32` metres (x, y relative to the grid origin,
/// z absolute): the one conversion the CPU passes and the GPU upload share.
#[inline]
pub fn local_point(p: &[f64; 3], spec: &GridSpec) -> [f32; 3] {
    [(p[0] - spec.x0) as f32, (p[1] - spec.y0) as f32, p[2] as f32]
}

/// Order of f32 by value as an unsigned key (total order, -0 < +0).
#[inline]
pub fn f32_key(v: f32) -> u32 {
    let b = v.to_bits();
    if b & 0x8000_0000 != 0 { !b } else { b | 0x8000_0000 }
}

/// `floor(x)` clamped to `[-1, 2^30]`, which holds every grid index (grids are
/// far smaller), as an integer. Written out because the baseline x86-64 target
/// makes `floor` a library call and a plain `as` conversion checks for
/// overflow; after the clamp (which takes NaN to -1) the value is finite and
/// in range, so neither is needed. The clamp changes no index the caller
/// keeps: it clamps to `[0, n - 1]` after.
#[inline]
#[allow(clippy::manual_clamp)] // `clamp` would keep a NaN, which the conversion must not see
fn floor_index(x: f32) -> i64 {
    let c = x.max(-1.0).min(1_073_741_824.0);
    // SAFETY: `c` is finite and within the range of i32.
    let t: i32 = unsafe { c.to_int_unchecked() };
    (if (t as f32) > c { t - 1 } else { t }) as i64
}

/// The columns `i0..=i1` and rows `j0..=j1` of the cells a point's square of
/// half side `radius` touches, clamped to the grid (empty when `i1 < i0` or
/// `j1 < j0`): the one definition the CPU passes and the GPU shader follow.
#[inline]
fn point_span(q: &[f32; 3], radius: f32, inv: f32, nx: i64, ny: i64) -> (i64, i64, i64, i64) {
    let i0 = floor_index((q[0] - radius) * inv).max(0);
    let i1 = floor_index((q[0] + radius) * inv).min(nx - 1);
    let j0 = floor_index((q[1] - radius) * inv).max(0);
    let j1 = floor_index((q[1] + radius) * inv).min(ny - 1);
    (i0, i1, j0, j1)
}

/// The point pass as raw intervals, point by point and each point's cells in
/// row order: the cells and intervals the GPU twin's fill pass writes, and the
/// reference the fused CPU assembly is tested against.
pub fn point_raws(points: &PointSource, spec: &GridSpec, out: &mut Vec<Raw>) {
    let inv = (1.0 / spec.cell) as f32;
    let (nx, ny) = (spec.nx as i64, spec.ny as i64);
    for (k, p) in points.xyz.iter().enumerate() {
        let (obj, q) = (points.obj(k), local_point(p, spec));
        let (i0, i1, j0, j1) = point_span(&q, points.radius, inv, nx, ny);
        let (zlo, zhi) = (q[2] - points.radius, q[2] + points.radius);
        for j in j0..=j1 {
            for i in i0..=i1 {
                out.push(Raw { cell: j as u32 * spec.nx + i as u32, zlo, zhi, obj, part: 0 });
            }
        }
    }
}

/// A convex polygon of at most 12 vertices: a triangle clipped to a cell
/// rectangle has at most 7. `lossy` marks one that needed more (possible only
/// when rounding makes a nearly degenerate polygon non-convex): a vertex was
/// dropped, so its height range may be too small and must not be used.
#[derive(Clone, Copy)]
struct Poly {
    v: [[f64; 3]; 12],
    n: usize,
    lossy: bool,
}

impl Poly {
    fn vertices(&self) -> &[[f64; 3]] {
        &self.v[..self.n]
    }

    fn range(&self, axis: usize) -> (f64, f64) {
        let vs = self.vertices();
        (
            vs.iter().map(|p| p[axis]).fold(f64::INFINITY, f64::min),
            vs.iter().map(|p| p[axis]).fold(f64::NEG_INFINITY, f64::max),
        )
    }
}

/// Clips a convex polygon to `coord[axis] >= v` (`keep_above`) or `<= v`.
fn clip(poly: &Poly, axis: usize, v: f64, keep_above: bool) -> Poly {
    let mut out = Poly { v: [[0.0; 3]; 12], n: 0, lossy: poly.lossy };
    let mut push = |p: [f64; 3]| {
        if out.n < out.v.len() {
            out.v[out.n] = p;
            out.n += 1;
        } else {
            out.lossy = true;
        }
    };
    let vs = poly.vertices();
    for k in 0..vs.len() {
        clip_edge(vs[k], vs[(k + 1) % vs.len()], axis, v, keep_above, &mut push);
    }
    out
}

/// One edge `a -> b` of a Sutherland-Hodgman clip to `coord[axis] >= v`
/// (`keep_above`) or `<= v`: `a` if it is inside, then the crossing if the
/// edge crosses.
#[inline]
fn clip_edge(a: [f64; 3], b: [f64; 3], axis: usize, v: f64, keep_above: bool, mut emit: impl FnMut([f64; 3])) {
    let inside = |p: &[f64; 3]| if keep_above { p[axis] >= v } else { p[axis] <= v };
    let (ia, ib) = (inside(&a), inside(&b));
    if ia {
        emit(a);
    }
    if ia != ib {
        let t = (v - a[axis]) / (b[axis] - a[axis]);
        emit([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])]);
    }
}

/// The lowest and highest height of convex polygon `poly` clipped to
/// `xa <= x <= xb`, or `None` if nothing is left: the vertices that clipping
/// to `x >= xa` and then to `x <= xb` with [`clip`] would give, in the same
/// order and arithmetic, but passed from the first clip to the second one at
/// a time instead of stored (this runs once per cell of every triangle).
fn heights_between(poly: &[[f64; 3]], xa: f64, xb: f64) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut keep = |p: [f64; 3]| {
        lo = lo.min(p[2]);
        hi = hi.max(p[2]);
    };
    // The second clip's first and latest input vertex.
    let mut first: Option<[f64; 3]> = None;
    let mut prev = [0.0; 3];
    for k in 0..poly.len() {
        clip_edge(poly[k], poly[(k + 1) % poly.len()], 0, xa, true, |p| {
            if first.is_some() {
                clip_edge(prev, p, 0, xb, false, &mut keep);
            } else {
                first = Some(p);
            }
            prev = p;
        });
    }
    let first = first?;
    clip_edge(prev, first, 0, xb, false, &mut keep);
    (lo <= hi).then_some((lo, hi))
}

/// Pass 1 for one triangle (grid-local coordinates): for every cell it touches,
/// the height range of the triangle over that cell, widened outwards by one part
/// in 10^6 plus a micrometre so rounding never makes it too small.
pub fn triangle_cells(t: &[[f64; 3]; 3], spec: &GridSpec, mut emit: impl FnMut(u32, f32, f32)) {
    let c = spec.cell;
    let mut tri = Poly { v: [[0.0; 3]; 12], n: 3, lossy: false };
    tri.v[..3].copy_from_slice(t);
    let ((minx, maxx), (miny, maxy)) = (tri.range(0), tri.range(1));
    if !(maxx >= 0.0 && maxy >= 0.0 && minx <= spec.nx as f64 * c && maxy.is_finite() && miny <= spec.ny as f64 * c) {
        return;
    }
    let j0 = ((miny / c).floor().max(0.0)) as u32;
    let j1 = ((maxy / c).floor().min(spec.ny as f64 - 1.0)) as u32;
    let i0 = ((minx / c).floor().max(0.0)) as u32;
    let i1 = ((maxx / c).floor().min(spec.nx as f64 - 1.0)) as u32;
    for j in j0..=j1 {
        let (ya, yb) = (j as f64 * c, (j + 1) as f64 * c);
        let strip = clip(&clip(&tri, 1, ya, true), 1, yb, false);
        if strip.n == 0 && !strip.lossy {
            continue;
        }
        let (a, b) = if strip.lossy {
            (i0, i1)
        } else {
            let (sx0, sx1) = strip.range(0);
            (((sx0 / c).floor().max(i0 as f64)) as u32, ((sx1 / c).floor().min(i1 as f64)) as u32)
        };
        for i in a..=b {
            let (xa, xb) = (i as f64 * c, (i + 1) as f64 * c);
            let (lo, hi) = if strip.lossy {
                // Conservative: the whole triangle's heights.
                tri.range(2)
            } else {
                match heights_between(strip.vertices(), xa, xb) {
                    Some(range) => range,
                    None => continue,
                }
            };
            let pad = 1e-6 * lo.abs().max(hi.abs()) + 1e-6;
            emit(j * spec.nx + i, (lo - pad) as f32, (hi + pad) as f32);
        }
    }
}

/// Pass 1 for a mesh: raw intervals of every triangle (`triangle_raws`), in
/// chunks of triangles rasterised in parallel. The plain form, which the
/// tests use as reference; the build uses [`mesh_jobs`].
pub fn mesh_raws(m: &TriMesh, spec: &GridSpec, obj_base: u32) -> Vec<Vec<Raw>> {
    (0..m.triangles.len())
        .into_par_iter()
        .chunks(4096)
        .map(|ids| {
            let mut v = Vec::new();
            for t in ids {
                triangle_raws(m, t, spec, obj_base, |r| v.push(r));
            }
            v
        })
        .collect()
}

/// Pass 1 for triangle `t` of a mesh: its raw intervals, tagged with the group
/// (object id `obj_base + group`) and, for convex parts, the part.
#[inline]
fn triangle_raws(m: &TriMesh, t: usize, spec: &GridSpec, obj_base: u32, mut emit: impl FnMut(Raw)) {
    let tri = m.triangles[t];
    let pt = |k: usize| {
        let p = m.vertices[tri[k] as usize];
        [p[0] - spec.x0, p[1] - spec.y0, p[2]]
    };
    let part_idx = m.part_of[t] as usize;
    let part = &m.parts[part_idx];
    let obj = obj_base + part.group;
    let pk = if part.convex_solid { part_idx as u32 + 1 } else { 0 };
    triangle_cells(&[pt(0), pt(1), pt(2)], spec, |cell, zlo, zhi| emit(Raw { cell, zlo, zhi, obj, part: pk }));
}

/// Pass 1 for a mesh fused with the grouping by band: [`mesh_raws`]' raw
/// intervals, chunk by chunk of triangles, grouped by band in cache as they
/// are made, for [`assemble_sources`]. The same intervals, never stored
/// ungrouped.
pub fn mesh_jobs(m: &TriMesh, spec: &GridSpec, obj_base: u32) -> Vec<RawJob> {
    let bands = Bands::of(spec);
    (0..m.triangles.len())
        .into_par_iter()
        .chunks(4096)
        .map_init(Vec::new, |made, ids| {
            made.clear();
            for t in ids {
                triangle_raws(m, t, spec, obj_base, |r| made.push(bands.raw_record(&r)));
            }
            let (recs, starts) = group_by_band(made, bands.count);
            RawJob { recs, starts, band_cells: bands.cells }
        })
        .collect()
}

/// Raw intervals made elsewhere (e.g. points by [`point_raws`]) grouped by
/// band in jobs, for [`assemble_sources`].
pub fn raw_jobs(raws: &[Raw], spec: &GridSpec) -> Vec<RawJob> {
    let bands = Bands::of(spec);
    raws.par_chunks(JOB)
        .map_init(Vec::new, |made, chunk| {
            made.clear();
            made.extend(chunk.iter().map(|r| bands.raw_record(r)));
            let (recs, starts) = group_by_band(made, bands.count);
            RawJob { recs, starts, band_cells: bands.cells }
        })
        .collect()
}

/// Inverse of [`f32_key`].
#[inline]
fn f32_from_key(k: u32) -> f32 {
    f32::from_bits(if k & 0x8000_0000 != 0 { k & 0x7fff_ffff } else { !k })
}

/// A raw interval without its cell, as its sort key: the integer order is the
/// merge order (object, part, bottom, top), and nothing is lost.
#[inline]
fn raw_key(r: &[u32; 5]) -> u128 {
    (r[1] as u128) << 96 | (r[2] as u128) << 64 | (r[3] as u128) << 32 | r[4] as u128
}

/// A point's record in a band: the low 32 bits the key of its height, bit 32
/// its object (ground or scan), then [`WIDE`] and [`TALL`], and from bit
/// [`CELL_SHIFT`] up its first cell in the band. Below the flags, the integer
/// order is (object, height), the order a cell's points are merged in. Its
/// interval `[z - r, z + r]` is computed again from the height when merging,
/// in the operations [`point_raws`] uses, so 8 bytes carry what a 16-byte raw
/// key would, and one record stands for up to four cells.
#[inline]
fn point_record(local: u32, flags: u64, obj: u32, z: f32) -> u64 {
    (local as u64) << CELL_SHIFT | flags | (obj as u64) << 32 | f32_key(z) as u64
}

/// The point also covers the next column.
const WIDE: u64 = 1 << 33;
/// The point also covers the next row, in the same band.
const TALL: u64 = 1 << 34;
const CELL_SHIFT: u32 = 35;
/// Object and height: what a cell sorts and merges.
const POINT_KEY: u64 = (1 << 33) - 1;

const _: () = assert!(OBJ_GROUND == 0 && OBJ_SCAN == 1, "a point's object is one bit of its record");

/// Pass 5's merge for one cell: `sorted` gives its raw intervals as (object,
/// part, bottom, top) in that order. A convex part's intervals become one, and
/// surface intervals (part 0) of one object merge when they overlap or are
/// less than `gap` apart.
#[inline]
fn merge_sorted(mut sorted: impl Iterator<Item = (u32, u32, f32, f32)>, gap: f32, out: &mut Vec<Interval>) {
    let Some((mut obj, mut part, mut zlo, mut zhi)) = sorted.next() else { return };
    for (o, p, lo, hi) in sorted {
        if o == obj && p == part && (part != 0 || lo <= zhi + gap) {
            if hi > zhi {
                zhi = hi;
            }
        } else {
            out.push(Interval { zlo, zhi, obj });
            (obj, part, zlo, zhi) = (o, p, lo, hi);
        }
    }
    out.push(Interval { zlo, zhi, obj });
}

/// Pass 5 for one cell's points, `recs` sorted: appends the merged intervals,
/// ground first, and returns where the other points' intervals start.
///
/// Sorted by height, a cell's point intervals are also sorted by (bottom,
/// top), the order [`merge_raws`] sorts raw intervals into, so both give the
/// same intervals for the same points (as the GPU twin's, which merges points
/// as raw keys, must).
fn merge_points(recs: &[u64], radius: f32, gap: f32, out: &mut Vec<Interval>) -> usize {
    let start = out.len();
    let unpack = |&k: &u64| {
        let z = f32_from_key(k as u32);
        ((k >> 32) as u32 & 1, 0, z - radius, z + radius)
    };
    merge_sorted(recs.iter().map(unpack), gap, out);
    start + out[start..].iter().take_while(|i| i.obj == OBJ_GROUND).count()
}

/// Pass 5 for one cell's raw intervals: sorts their keys and appends the
/// merged intervals. Equal keys are equal raws, so the sorted order, hence the
/// map, does not depend on the order the raws arrived in.
fn merge_raws(keys: &mut [u128], gap: f32, out: &mut Vec<Interval>) {
    keys.sort_unstable();
    let unpack =
        |&k: &u128| ((k >> 96) as u32, (k >> 64) as u32, f32_from_key((k >> 32) as u32), f32_from_key(k as u32));
    merge_sorted(keys.iter().map(unpack), gap, out);
}

/// The end of pass 5 for one cell whose merged intervals are `out[start..]`:
/// sorts them by (bottom, top, object), keeps one in single-level mode, and
/// returns the cell's top (`-inf` if empty) for the pyramid.
///
/// `sorted_runs` says that `out[start..]` is at most two runs, each already in
/// that order, split at `mid` (a cell of scan points only: its ground run and
/// its other-points run), which are merged instead of sorted.
fn finish_cell(
    out: &mut Vec<Interval>,
    start: usize,
    sorted_runs: Option<usize>,
    mode: Mode,
    tmp: &mut Vec<Interval>,
) -> f32 {
    let order = |i: &Interval| (f32_key(i.zlo), f32_key(i.zhi), i.obj);
    match sorted_runs {
        Some(mid) if mid > start && mid < out.len() => {
            tmp.clear();
            tmp.extend_from_slice(&out[start..]);
            let (a, b) = tmp.split_at(mid - start);
            let (mut x, mut y) = (0, 0);
            for slot in &mut out[start..] {
                let take_a = y == b.len() || (x < a.len() && order(&a[x]) <= order(&b[y]));
                *slot = if take_a { a[x] } else { b[y] };
                if take_a {
                    x += 1;
                } else {
                    y += 1;
                }
            }
        }
        Some(_) => {}
        None => out[start..].sort_unstable_by_key(order),
    }
    let cell = &mut out[start..];
    if mode == Mode::Single && !cell.is_empty() {
        // Sorted, the first bottom is the lowest (in key order, which also
        // orders -0 below +0, so every path picks the same one).
        let lo = cell[0].zlo;
        let top = cell.iter().fold(cell[0], |a, i| if f32_key(i.zhi) > f32_key(a.zhi) { *i } else { a });
        out.truncate(start);
        out.push(Interval { zlo: lo, zhi: top.zhi, obj: top.obj });
    }
    cell_top(&out[start..])
}

/// The highest top of a cell's intervals, `-inf` if it has none: the greatest
/// in key order ([`f32_key`]), so that of a -0 and a +0 top every path picks
/// the same one (`f32::max` may return either).
pub fn cell_top(cell: &[Interval]) -> f32 {
    cell.iter().map(|i| f32_key(i.zhi)).max().map_or(f32::NEG_INFINITY, f32_from_key)
}

/// About this many cells make a band, a run of whole grid rows that passes 2
/// to 5 treat together: small enough that a band's records stay in cache while
/// they are sorted and merged.
const BAND_CELLS: u32 = 2048;
/// Points or raws per parallel job of the partition.
const JOB: usize = 1 << 16;

/// One job's points as records grouped by band: band `b`'s are
/// `recs[starts[b]..starts[b + 1]]`, in point order.
struct PointJob {
    recs: Vec<u64>,
    starts: Vec<u32>,
    /// Cells the records stand for.
    cells: usize,
}

/// Pass 1 for a job of points, fused into the partition: every point's cells
/// become one record per band it touches (or one per cell, for a point wider
/// or taller than two cells), made in cache-sized batches and grouped by band
/// there, so the points are read once and neither they nor their raw
/// intervals are stored again. `made` holds the records before grouping, a
/// buffer reused from job to job (fresh memory would be paged in every time).
fn point_job(
    p: &PointSource,
    range: std::ops::Range<usize>,
    spec: &GridSpec,
    bands: Bands,
    made: &mut Vec<(u32, u64)>,
) -> PointJob {
    let inv = (1.0 / spec.cell) as f32;
    let (nx, ny) = (spec.nx, spec.ny);
    let band_shift = bands.shift;
    let mask = (1u32 << band_shift) - 1;
    made.clear();
    let mut cells = 0usize;
    for k in range {
        let q = local_point(&p.xyz[k], spec);
        let (i0, i1, j0, j1) = point_span(&q, p.radius, inv, nx as i64, ny as i64);
        if i1 < i0 || j1 < j0 {
            continue;
        }
        let (i0, i1, j0, j1) = (i0 as u32, i1 as u32, j0 as u32, j1 as u32);
        cells += (i1 - i0 + 1) as usize * (j1 - j0 + 1) as usize;
        let obj = p.obj(k);
        let (b0, b1) = (j0 >> band_shift, j1 >> band_shift);
        if i1 - i0 <= 1 && j1 - j0 <= 1 {
            let wide = if i1 > i0 { WIDE } else { 0 };
            if b0 == b1 {
                let tall = if j1 > j0 { TALL } else { 0 };
                made.push((b0, point_record((j0 & mask) * nx + i0, wide | tall, obj, q[2])));
            } else {
                made.push((b0, point_record((j0 & mask) * nx + i0, wide, obj, q[2])));
                made.push((b1, point_record((j1 & mask) * nx + i0, wide, obj, q[2])));
            }
        } else {
            for j in j0..=j1 {
                for i in i0..=i1 {
                    made.push((j >> band_shift, point_record((j & mask) * nx + i, 0, obj, q[2])));
                }
            }
        }
    }
    let (recs, starts) = group_by_band(made, bands.count);
    PointJob { recs, starts, cells }
}

/// How the grid is cut into bands: `1 << shift` rows each (a power of two, so
/// a row's band is a shift), `cells` cells each, `count` of them.
#[derive(Clone, Copy)]
struct Bands {
    shift: u32,
    cells: u32,
    count: usize,
}

impl Bands {
    /// About [`BAND_CELLS`] cells per band. The grid must have at most
    /// [`crate::MAX_CELLS`] cells, as [`crate::Settings::grid`] makes sure (a
    /// band's cell must fit a point record).
    fn of(spec: &GridSpec) -> Bands {
        let (nx, ny) = (spec.nx, spec.ny);
        assert!(spec.cells() as u64 <= crate::MAX_CELLS, "a {nx} x {ny} grid is larger than the depth map allows");
        const _: () = assert!(crate::MAX_CELLS <= 1 << (64 - CELL_SHIFT), "a cell in a band must fit a point record");
        let shift = (BAND_CELLS / nx.max(1)).max(1).ilog2().min(ny.max(1).ilog2() + 1);
        Bands { shift, cells: (1 << shift) * nx, count: ny.div_ceil(1 << shift) as usize }
    }

    /// A raw interval as `(band, [cell in band, object, part, bottom key, top key])`.
    #[inline]
    fn raw_record(&self, r: &Raw) -> (u32, [u32; 5]) {
        (r.cell / self.cells, [r.cell % self.cells, r.obj, r.part, f32_key(r.zlo), f32_key(r.zhi)])
    }
}

/// One job's raw intervals grouped by band: band `b`'s are
/// `recs[starts[b]..starts[b + 1]]`, each `[cell in band, object, part,
/// bottom key, top key]`. Made by [`mesh_jobs`] and [`raw_jobs`].
pub struct RawJob {
    recs: Vec<[u32; 5]>,
    starts: Vec<u32>,
    /// Cells per band of the grid it was made for.
    band_cells: u32,
}

impl RawJob {
    /// Raw intervals in the job.
    pub fn len(&self) -> usize {
        self.recs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.recs.is_empty()
    }
}

/// A counting sort of `made` (band, record) pairs by band: the records and
/// where each band's start.
fn group_by_band<T: Copy + Default>(made: &[(u32, T)], bands: usize) -> (Vec<T>, Vec<u32>) {
    let mut starts = vec![0u32; bands + 1];
    for &(b, _) in made {
        starts[b as usize + 1] += 1;
    }
    for b in 1..=bands {
        starts[b] += starts[b - 1];
    }
    let mut cursor = starts.clone();
    let mut recs = vec![T::default(); made.len()];
    for &(b, r) in made {
        let at = &mut cursor[b as usize];
        recs[*at as usize] = r;
        *at += 1;
    }
    (recs, starts)
}

/// [`bucket_points`] for raw records: cell `l`'s keys are
/// `buf[ends[l - 1]..ends[l]]` (from 0 for `l = 0`).
fn bucket_raws(jobs: &[RawJob], band: usize, cells: usize, ends: &mut Vec<u32>, buf: &mut Vec<u128>) {
    let segments = || jobs.iter().map(|j| &j.recs[j.starts[band] as usize..j.starts[band + 1] as usize]);
    ends.clear();
    ends.resize(cells + 1, 0);
    for seg in segments() {
        for r in seg {
            ends[r[0] as usize + 1] += 1;
        }
    }
    for l in 1..=cells {
        ends[l] += ends[l - 1];
    }
    buf.clear();
    buf.resize(ends[cells] as usize, 0);
    for seg in segments() {
        for r in seg {
            let at = &mut ends[r[0] as usize];
            buf[*at as usize] = raw_key(r);
            *at += 1;
        }
    }
}

/// Counting sort by cell of one band's point records, gathered from every job
/// and each standing for up to four cells: cell `l`'s keys (object and
/// height) end up in `s.points[s.point_ends[l - 1]..s.point_ends[l]]` (from 0
/// for `l = 0`).
///
/// The records are first sorted by first cell and flags, one write each with
/// no branch on the flags (which are as good as random); a cell's keys are
/// then its own records, the wide ones of the cell to its left, the tall ones
/// of the cell below and those both wide and tall below left, copied together
/// run by run.
fn bucket_points(jobs: &[PointJob], band: usize, cells: usize, nx: usize, s: &mut Scratch) {
    let segments = || jobs.iter().map(|j| &j.recs[j.starts[band] as usize..j.starts[band + 1] as usize]);
    const _: () = assert!(WIDE == 1 << 33 && TALL == 1 << 34);
    let group = |r: u64| 4 * (r >> CELL_SHIFT) as usize + ((r >> 33) & 3) as usize;
    let (starts, grouped) = (&mut s.group_starts, &mut s.grouped);
    starts.clear();
    starts.resize(4 * cells + 1, 0);
    for seg in segments() {
        for &r in seg {
            starts[group(r) + 1] += 1;
        }
    }
    for g in 1..starts.len() {
        starts[g] += starts[g - 1];
    }
    grouped.clear();
    grouped.resize(starts[4 * cells] as usize, 0);
    let mut cursor = starts.clone();
    for seg in segments() {
        for &r in seg {
            let at = &mut cursor[group(r)];
            grouped[*at as usize] = r & POINT_KEY;
            *at += 1;
        }
    }
    // Runs of group g: grouped[starts[g]..starts[g + 1]]; flags 1 wide, 2 tall.
    let run = |g: usize| &grouped[starts[g] as usize..starts[g + 1] as usize];
    let (ends, buf) = (&mut s.point_ends, &mut s.points);
    ends.clear();
    buf.clear();
    for l in 0..cells {
        buf.extend_from_slice(&grouped[starts[4 * l] as usize..starts[4 * l + 4] as usize]);
        if l % nx > 0 {
            buf.extend_from_slice(run(4 * (l - 1) + 1));
            buf.extend_from_slice(run(4 * (l - 1) + 3));
        }
        if l >= nx {
            buf.extend_from_slice(run(4 * (l - nx) + 2));
            buf.extend_from_slice(run(4 * (l - nx) + 3));
            if l % nx > 0 {
                buf.extend_from_slice(run(4 * (l - nx - 1) + 3));
            }
        }
        ends.push(buf.len() as u32);
    }
}

/// Per-thread buffers of pass 5.
#[derive(Default)]
struct Scratch {
    point_ends: Vec<u32>,
    points: Vec<u64>,
    raw_ends: Vec<u32>,
    raws: Vec<u128>,
    out: Vec<Interval>,
    tmp: Vec<Interval>,
    group_starts: Vec<u32>,
    grouped: Vec<u64>,
}

/// Passes 2 to 5 on the CPU: count, prefix-sum, fill, sort and merge, for
/// `points` (pass 1 fused in, see `point_job`) and the raw intervals in
/// `raws` (from [`mesh_jobs`], where pass 1 is fused in too, or [`raw_jobs`]).
///
/// Two levels, so that every write stays in cache: records are first grouped
/// by band of whole grid rows (about `BAND_CELLS` cells), job by job, each
/// job's records in its own buffer. Then each band, in parallel, gathers its
/// records from every job, sorts them by cell in a local buffer, and every
/// cell is sorted and merged. The sorted keys of a cell are unique up to equal
/// raws, so the map does not depend on job or thread order.
///
/// The grid must have at most [`crate::MAX_CELLS`] cells, as
/// [`crate::Settings::grid`] makes sure (a band's cell must fit its record).
pub fn assemble_sources(
    points: Option<PointSource>,
    raws: &[RawJob],
    spec: GridSpec,
    mode: Mode,
    gap: f32,
    objects: Vec<String>,
) -> Mdm {
    let nx = spec.nx;
    let bands = Bands::of(&spec);
    assert!(
        raws.iter().all(|j| j.starts.len() == bands.count + 1 && j.band_cells == bands.cells),
        "depth map assembly: raw jobs made for another grid"
    );
    let radius = points.map(|p| p.radius).unwrap_or(0.0);
    let point_jobs: Vec<PointJob> = match points {
        Some(p) => (0..p.xyz.len().div_ceil(JOB))
            .into_par_iter()
            .map_init(Vec::new, |made, k| point_job(&p, k * JOB..((k + 1) * JOB).min(p.xyz.len()), &spec, bands, made))
            .collect(),
        None => vec![],
    };
    let n = spec.cells();
    // Bands are merged a few at a time, each into a buffer that is reused and
    // so stays in cache and paged in; once a group is done, where its
    // intervals go in the map is known and they are copied there. Each cell a
    // record stands for gives at most one interval, which bounds the map.
    let capacity = point_jobs.iter().map(|j| j.cells).sum::<usize>() + raws.iter().map(RawJob::len).sum::<usize>();
    let mut intervals: Vec<Interval> = Vec::with_capacity(capacity);
    let mut counts = vec![0u32; n];
    let mut tops = vec![0f32; n];
    let group = 4 * rayon::current_num_threads();
    let mut scratch: Vec<Scratch> = (0..group).map(|_| Scratch::default()).collect();
    let mut band_counts: Vec<&mut [u32]> = counts.chunks_mut(bands.cells as usize).collect();
    let mut band_tops: Vec<&mut [f32]> = tops.chunks_mut(bands.cells as usize).collect();
    for first in (0..bands.count).step_by(group) {
        let last = (first + group).min(bands.count);
        scratch[..last - first]
            .par_iter_mut()
            .zip(band_counts[first..last].par_iter_mut().zip(band_tops[first..last].par_iter_mut()))
            .enumerate()
            .for_each(|(k, (s, (counts, tops)))| {
                let b = first + k;
                bucket_points(&point_jobs, b, counts.len(), nx as usize, s);
                bucket_raws(raws, b, counts.len(), &mut s.raw_ends, &mut s.raws);
                merge_band(radius, gap, mode, s, counts, tops);
            });
        let mut rest = &mut intervals.spare_capacity_mut()[..];
        let mut dsts = Vec::with_capacity(last - first);
        for s in &scratch[..last - first] {
            let (d, r) = std::mem::take(&mut rest).split_at_mut(s.out.len());
            dsts.push(d);
            rest = r;
        }
        let added: usize = scratch[..last - first].iter().map(|s| s.out.len()).sum();
        dsts.into_par_iter().zip(&scratch[..last - first]).for_each(|(d, s)| {
            for (d, v) in d.iter_mut().zip(&s.out) {
                d.write(*v);
            }
        });
        // SAFETY: the `added` slots after the length were written just above.
        unsafe { intervals.set_len(intervals.len() + added) };
    }
    drop((point_jobs, band_counts, band_tops));
    intervals.shrink_to_fit();
    Mdm::from_cells(spec, mode, &counts, intervals, tops, objects)
}

/// Passes 2 (by cell) to 5 for one band whose points and raws are already in
/// `s.points` and `s.raws` by cell: its intervals into `s.out`, and per cell their number
/// and the top into `counts` and `tops`.
fn merge_band(radius: f32, gap: f32, mode: Mode, s: &mut Scratch, counts: &mut [u32], tops: &mut [f32]) {
    let cells = counts.len();
    let out = &mut s.out;
    out.clear();
    let (mut p0, mut r0) = (0usize, 0usize);
    for l in 0..cells {
        let (p1, r1) = (s.point_ends[l] as usize, s.raw_ends[l] as usize);
        let start = out.len();
        let cell_points = &mut s.points[p0..p1];
        cell_points.sort_unstable();
        let mid = merge_points(cell_points, radius, gap, out);
        let runs = (r1 == r0).then_some(mid);
        merge_raws(&mut s.raws[r0..r1], gap, out);
        tops[l] = finish_cell(out, start, runs, mode, &mut s.tmp);
        counts[l] = (out.len() - start) as u32;
        (p0, r0) = (p1, r1);
    }
}

impl Mdm {
    /// A map from its cells in row-major order: how many intervals each has
    /// (`intervals` holds them cell after cell) and its top (for the pyramid).
    pub fn from_cells(
        spec: GridSpec,
        mode: Mode,
        counts: &[u32],
        intervals: Vec<Interval>,
        tops: Vec<f32>,
        objects: Vec<String>,
    ) -> Mdm {
        assert_eq!(counts.len(), spec.cells(), "depth map: one count per cell");
        assert_eq!(tops.len(), spec.cells(), "depth map: one top per cell");
        let mut offsets = Vec::with_capacity(counts.len() + 1);
        offsets.push(0u32);
        let mut at = 0u32;
        for c in counts {
            at += c;
            offsets.push(at);
        }
        assert_eq!(at as usize, intervals.len(), "depth map: counts add up to the intervals");
        let pyramid = Mdm::pyramid_from(spec.nx, spec.ny, tops);
        Mdm { spec, mode, offsets, intervals, objects, pyramid }
    }

    pub fn cell(&self, i: u32, j: u32) -> &[Interval] {
        let k = (j * self.spec.nx + i) as usize;
        &self.intervals[self.offsets[k] as usize..self.offsets[k + 1] as usize]
    }

    /// Highest top in a cell, `-inf` if empty.
    pub fn top(&self, i: u32, j: u32) -> f32 {
        self.pyramid.first().map(|l| l.2[(j * self.spec.nx + i) as usize]).unwrap_or(f32::NEG_INFINITY)
    }

    pub fn build_pyramid(&mut self) {
        let (nx, ny) = (self.spec.nx, self.spec.ny);
        let base = self.offsets.windows(2).map(|w| cell_top(&self.intervals[w[0] as usize..w[1] as usize])).collect();
        self.pyramid = Self::pyramid_from(nx, ny, base);
    }

    /// The max-height pyramid over `base`, the top of each cell in row-major order.
    fn pyramid_from(nx: u32, ny: u32, base: Vec<f32>) -> Vec<(u32, u32, Vec<f32>)> {
        let mut levels = vec![(nx, ny, base)];
        while let Some((w, h, l)) = levels.last() {
            if *w <= 1 && *h <= 1 {
                break;
            }
            let (w2, h2) = (w.div_ceil(2), h.div_ceil(2));
            let mut next = vec![f32::NEG_INFINITY; (w2 * h2) as usize];
            for j in 0..*h {
                for i in 0..*w {
                    let v = l[(j * w + i) as usize];
                    let k = ((j / 2) * w2 + i / 2) as usize;
                    if v > next[k] {
                        next[k] = v;
                    }
                }
            }
            levels.push((w2, h2, next));
        }
        levels
    }

    pub fn to_bytes(&self) -> Vec<u8> {
        let mut w = ByteWriter::new();
        let s = &self.spec;
        w.f64(s.x0);
        w.f64(s.y0);
        w.f64(s.cell);
        w.u32(s.nx);
        w.u32(s.ny);
        w.u8(matches!(self.mode, Mode::Single) as u8);
        w.u64(self.objects.len() as u64);
        for o in &self.objects {
            w.str(o);
        }
        w.u32s(&self.offsets);
        w.u64(self.intervals.len() as u64);
        for iv in &self.intervals {
            w.f32(iv.zlo);
            w.f32(iv.zhi);
            w.u32(iv.obj);
        }
        artifact::encode(ARTIFACT_KIND, ARTIFACT_VERSION, &w.buf)
    }

    pub fn write(&self, path: &Path) -> Result<(), ArtifactError> {
        artifact::write_atomic(path, &self.to_bytes())
            .map_err(|e| ArtifactError::Io(liftplan_core::Location::file(path), e))
    }

    pub fn read(path: &Path) -> Result<Mdm, ArtifactError> {
        let bytes = std::fs::read(path).map_err(|e| ArtifactError::Io(liftplan_core::Location::file(path), e))?;
        Self::from_bytes(path, &bytes)
    }

    pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<Mdm, ArtifactError> {
        let payload = artifact::decode(path, bytes, ARTIFACT_KIND, ARTIFACT_VERSION)?;
        let mut r = ByteReader::new(path, payload, 32);
        let spec = GridSpec { x0: r.f64()?, y0: r.f64()?, cell: r.f64()?, nx: r.u32()?, ny: r.u32()? };
        if !(spec.cell.is_finite() && spec.cell > 0.0 && spec.x0.is_finite() && spec.y0.is_finite()) {
            return Err(r.error("grid origin and cell size must be finite, cell positive"));
        }
        let mode = if r.u8()? == 1 { Mode::Single } else { Mode::Multi };
        let no = r.count(4)?;
        let mut objects = Vec::with_capacity(no);
        for _ in 0..no {
            objects.push(r.str()?);
        }
        let offsets = r.u32s()?;
        let ncells = (spec.nx as u64).saturating_mul(spec.ny as u64);
        if offsets.len() as u64 != ncells + 1 {
            return Err(r.error(format!("{} offsets for a {} x {} grid", offsets.len(), spec.nx, spec.ny)));
        }
        let ni = r.count(12)?;
        let mut intervals = Vec::with_capacity(ni);
        for _ in 0..ni {
            intervals.push(Interval { zlo: r.f32()?, zhi: r.f32()?, obj: r.u32()? });
        }
        r.finish()?;
        if offsets.first() != Some(&0)
            || offsets.windows(2).any(|w| w[1] < w[0])
            || *offsets.last().unwrap_or(&0) as usize != ni
        {
            return Err(r.error("offsets do not describe the intervals"));
        }
        if intervals.iter().any(|iv| !(iv.zlo <= iv.zhi) || iv.obj as usize >= objects.len()) {
            return Err(r.error("an interval is inverted, not finite or names a missing object"));
        }
        let mut m = Mdm { spec, mode, offsets, intervals, objects, pyramid: vec![] };
        m.build_pyramid();
        Ok(m)
    }
}
