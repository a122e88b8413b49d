//! Multi-level depth maps (thesis ch. 3): per cell of a plan grid, the sorted
//! height intervals occupied by the site, each tagged with the object it belongs
//! to.
//!
//! Layout is CSR: `offsets[k]..offsets[k + 1]` index `intervals` for cell `k`
//! (row-major, row 0 at the grid's south edge). Intervals of one cell are sorted
//! by bottom, then top, then object.
//!
//! **Building** follows the thesis' passes, which the GPU twin repeats:
//! 1. *generate*: each point gives `[z - r, z + r]` in every cell its disc of
//!    radius `r` touches; each triangle gives, in every cell it touches, a
//!    conservative range of its heights over that cell (see [`triangle_cells`]);
//! 2. *count* the raw intervals per cell, 3. *prefix-sum* the counts into
//!    offsets, 4. *fill* the raw intervals in, 5. *sort and merge* each cell.
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

/// Points in grid-local metres (x, y relative to the grid origin, z absolute).
pub struct LocalPoints {
    pub xyz: Vec<[f32; 3]>,
    pub obj: Vec<u32>,
}

/// Order of f32 by value as an unsigned key (total order, -0 < +0).
#[inline]
pub fn f32_key(v: f32) -> u32 {
    let b = v.to_bits();
    if b & 0x8000_0000 != 0 { !b } else { b | 0x8000_0000 }
}

/// `x.floor() as i64`, inline (the baseline x86-64 target has no rounding
/// instruction, so `floor` is a library call): the same value for every input.
#[inline]
fn floor_i64(x: f32) -> i64 {
    let t = x as i64;
    if (t as f32) > x { t.saturating_sub(1) } else { t }
}

/// The cells a point's square of half side `radius` touches, and its height
/// interval: the one definition the CPU passes and the GPU shader follow.
#[inline]
fn point_cells(q: &[f32; 3], radius: f32, inv: f32, nx: i64, ny: i64, mut cell: impl FnMut(u32)) -> (f32, f32) {
    let i0 = floor_i64((q[0] - radius) * inv);
    let i1 = floor_i64((q[0] + radius) * inv);
    let j0 = floor_i64((q[1] - radius) * inv);
    let j1 = floor_i64((q[1] + radius) * inv);
    for j in j0.max(0)..=j1.min(ny - 1) {
        for i in i0.max(0)..=i1.min(nx - 1) {
            cell((j * nx + i) as u32);
        }
    }
    (q[2] - radius, q[2] + radius)
}

/// Clips a convex polygon to `coord[axis] >= v` (`keep_above`) or `<= v`.
fn clip(poly: &[[f64; 3]], axis: usize, v: f64, keep_above: bool) -> Vec<[f64; 3]> {
    let inside = |p: &[f64; 3]| if keep_above { p[axis] >= v } else { p[axis] <= v };
    let mut out = Vec::with_capacity(poly.len() + 2);
    for k in 0..poly.len() {
        let a = poly[k];
        let b = poly[(k + 1) % poly.len()];
        let (ia, ib) = (inside(&a), inside(&b));
        if ia {
            out.push(a);
        }
        if ia != ib {
            let t = (v - a[axis]) / (b[axis] - a[axis]);
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])]);
        }
    }
    out
}

/// Pass 1 for one triangle (grid-local coordinates): for every cell it touches,
/// the height range of the triangle over that cell, widened outwards by one part
/// in 10^6 plus a micrometre so rounding never makes it too small.
pub fn triangle_cells(t: &[[f64; 3]; 3], spec: &GridSpec, mut emit: impl FnMut(u32, f32, f32)) {
    let c = spec.cell;
    let minx = t.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
    let maxx = t.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
    let miny = t.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let maxy = t.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
    if !(maxx >= 0.0 && maxy >= 0.0 && minx <= spec.nx as f64 * c && maxy.is_finite() && miny <= spec.ny as f64 * c) {
        return;
    }
    let j0 = ((miny / c).floor().max(0.0)) as u32;
    let j1 = ((maxy / c).floor().min(spec.ny as f64 - 1.0)) as u32;
    let i0 = ((minx / c).floor().max(0.0)) as u32;
    let i1 = ((maxx / c).floor().min(spec.nx as f64 - 1.0)) as u32;
    let tri = t.to_vec();
    for j in j0..=j1 {
        let (ya, yb) = (j as f64 * c, (j + 1) as f64 * c);
        let strip = clip(&clip(&tri, 1, ya, true), 1, yb, false);
        if strip.is_empty() {
            continue;
        }
        let sx0 = strip.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
        let sx1 = strip.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
        let a = ((sx0 / c).floor().max(i0 as f64)) as u32;
        let b = ((sx1 / c).floor().min(i1 as f64)) as u32;
        for i in a..=b {
            let (xa, xb) = (i as f64 * c, (i + 1) as f64 * c);
            let poly = clip(&clip(&strip, 0, xa, true), 0, xb, false);
            if poly.is_empty() {
                continue;
            }
            let lo = poly.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
            let hi = poly.iter().map(|p| p[2]).fold(f64::NEG_INFINITY, f64::max);
            let pad = 1e-6 * lo.abs().max(hi.abs()) + 1e-6;
            emit(j * spec.nx + i, (lo - pad) as f32, (hi + pad) as f32);
        }
    }
}

/// Pass 1 for a mesh: raw intervals of every triangle, tagged with the group
/// (object id `obj_base + group`) and, for convex parts, the part.
pub fn mesh_raws(m: &TriMesh, spec: &GridSpec, obj_base: u32, out: &mut Vec<Raw>) {
    let parts: Vec<Vec<Raw>> = (0..m.triangles.len())
        .into_par_iter()
        .chunks(4096)
        .map(|ids| {
            let mut v = Vec::new();
            for t in ids {
                let tri = m.triangles[t];
                let pt = |k: usize| {
                    let p = m.vertices[tri[k] as usize];
                    [p[0] - spec.x0, p[1] - spec.y0, p[2]]
                };
                let part_idx = m.part_of[t] as usize;
                let part = &m.parts[part_idx];
                let obj = obj_base + part.group;
                let pk = if part.convex_solid { part_idx as u32 + 1 } else { 0 };
                triangle_cells(&[pt(0), pt(1), pt(2)], spec, |cell, zlo, zhi| {
                    v.push(Raw { cell, zlo, zhi, obj, part: pk })
                });
            }
            v
        })
        .collect();
    for v in parts {
        out.extend_from_slice(&v);
    }
}

/// A raw interval without its cell, packed so that the integer order is the
/// merge order (object, part, bottom, top) and nothing is lost.
#[inline]
fn pack(obj: u32, part: u32, zlo: f32, zhi: f32) -> u128 {
    (obj as u128) << 96 | (part as u128) << 64 | (f32_key(zlo) as u128) << 32 | f32_key(zhi) as u128
}

/// Inverse of [`f32_key`].
#[inline]
fn f32_from_key(k: u32) -> f32 {
    f32::from_bits(if k & 0x8000_0000 != 0 { k & 0x7fff_ffff } else { !k })
}

/// Pass 5 for one cell: sorts the packed raws and appends the merged intervals.
fn merge_cell(raw: &mut [u128], gap: f32, mode: Mode, out: &mut Vec<Interval>) {
    if raw.is_empty() {
        return;
    }
    // Equal keys are equal raws: the sorted order, hence the map, does not
    // depend on the order the raws arrived in.
    raw.sort_unstable();
    let unpack = |k: u128| ((k >> 96) as u32, (k >> 64) as u32, f32_from_key((k >> 32) as u32), f32_from_key(k as u32));
    let start = out.len();
    let (mut obj, mut part, mut zlo, mut zhi) = unpack(raw[0]);
    for &k in &raw[1..] {
        let (o, p, lo, hi) = unpack(k);
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
    let cell = &mut out[start..];
    cell.sort_unstable_by_key(|i| (f32_key(i.zlo), f32_key(i.zhi), i.obj));
    if mode == Mode::Single {
        let lo = cell.iter().map(|i| i.zlo).fold(f32::INFINITY, f32::min);
        let top = cell.iter().fold(cell[0], |a, i| if f32_key(i.zhi) > f32_key(a.zhi) { *i } else { a });
        out.truncate(start);
        out.push(Interval { zlo: lo, zhi: top.zhi, obj: top.obj });
    }
}

/// Points rasterised straight into the assembly (no raw intervals stored).
pub struct PointSource<'a> {
    pub points: &'a LocalPoints,
    pub radius: f32,
}

/// Tiles of `TILE x TILE` cells group the work of passes 2 to 5.
const TILE: u32 = 64;
/// Points or raws per parallel job.
const JOB: usize = 1 << 16;

/// What the assembly reads: the points (rasterised on the fly) and raws.
struct Sources<'a> {
    points: Option<&'a PointSource<'a>>,
    raws: &'a [Raw],
    inv: f32,
    nx: i64,
    ny: i64,
}

impl Sources<'_> {
    /// Calls `f(cell, packed key)` for every raw interval of a job, in order.
    #[inline]
    fn visit(&self, job: Job, mut f: impl FnMut(u32, u128)) {
        match job {
            Job::Points(a, b) => {
                let Some(p) = self.points else { return };
                for k in a..b {
                    let q = &p.points.xyz[k];
                    let obj = p.points.obj[k];
                    let (mut cells, mut n) = ([0u32; 4], 0);
                    let (zlo, zhi) = point_cells(q, p.radius, self.inv, self.nx, self.ny, |c| {
                        if n < 4 {
                            cells[n] = c;
                        }
                        n += 1;
                    });
                    let key = pack(obj, 0, zlo, zhi);
                    if n <= 4 {
                        for &c in &cells[..n] {
                            f(c, key);
                        }
                    } else {
                        // A radius wider than a cell: rare, so recompute.
                        point_cells(q, p.radius, self.inv, self.nx, self.ny, |c| f(c, key));
                    }
                }
            }
            Job::Raws(a, b) => {
                for r in &self.raws[a..b] {
                    f(r.cell, pack(r.obj, r.part, r.zlo, r.zhi));
                }
            }
        }
    }
}

#[derive(Clone, Copy)]
enum Job {
    Points(usize, usize),
    Raws(usize, usize),
}

/// Passes 2 to 5 on the CPU: count, prefix-sum, fill, sort and merge, for the
/// points of `points` (pass 1 fused in: each point's cells are computed where
/// they are counted and where they are filled) and the raw intervals `raws`.
///
/// Two levels, so that every write stays in cache: the raws are first
/// partitioned by tile of 64 x 64 cells (count per tile, prefix, fill, per
/// job in parallel into disjoint slots, packed into 16-byte sort keys), then
/// each tile, in parallel, is counted, prefix-summed and filled by cell in a
/// local buffer and every cell sorted and merged. The sorted keys of a cell
/// are unique, so the map does not depend on job or thread order.
pub fn assemble_sources(
    points: Option<PointSource>,
    raws: &[Raw],
    spec: GridSpec,
    mode: Mode,
    gap: f32,
    objects: Vec<String>,
) -> Mdm {
    let (nx, ny) = (spec.nx, spec.ny);
    let (tx, ty) = (nx.div_ceil(TILE), ny.div_ceil(TILE));
    let ntiles = (tx * ty) as usize;
    let tile_of = |cell: u32| {
        let (i, j) = (cell % nx, cell / nx);
        ((j / TILE) * tx + i / TILE) as usize
    };
    let inv = (1.0 / spec.cell) as f32;
    let npts = points.as_ref().map(|p| p.points.xyz.len()).unwrap_or(0);
    let mut jobs: Vec<Job> = (0..npts.div_ceil(JOB)).map(|k| Job::Points(k * JOB, ((k + 1) * JOB).min(npts))).collect();
    jobs.extend((0..raws.len().div_ceil(JOB)).map(|k| Job::Raws(k * JOB, ((k + 1) * JOB).min(raws.len()))));
    let src = Sources { points: points.as_ref(), raws, inv, nx: nx as i64, ny: ny as i64 };
    // Level 1: partition by tile.
    let counts: Vec<Vec<u32>> = jobs
        .par_iter()
        .map(|&job| {
            let mut c = vec![0u32; ntiles];
            src.visit(job, |cell, _| c[tile_of(cell)] += 1);
            c
        })
        .collect();
    let mut tile_start = vec![0usize; ntiles + 1];
    let mut cursors: Vec<Vec<usize>> = vec![vec![0; ntiles]; jobs.len()];
    let mut at = 0usize;
    for t in 0..ntiles {
        tile_start[t] = at;
        for (j, c) in counts.iter().enumerate() {
            cursors[j][t] = at;
            at += c[t] as usize;
        }
    }
    tile_start[ntiles] = at;
    drop(counts);
    let mut cells = vec![0u32; at];
    let mut keys = vec![0u128; at];
    let (cell_ptr, key_ptr) = (SendPtr(cells.as_mut_ptr()), SendPtr(keys.as_mut_ptr()));
    jobs.par_iter().zip(cursors.par_iter_mut()).for_each(|(&job, cur)| {
        src.visit(job, |cell, key| {
            let c = &mut cur[tile_of(cell)];
            // SAFETY: each job owns the slots [its cursor start, + its count) of
            // every tile, disjoint from every other job's and within `at`.
            unsafe {
                *cell_ptr.get().add(*c) = cell;
                *key_ptr.get().add(*c) = key;
            }
            *c += 1;
        });
    });
    drop(cursors);
    // Level 2: per tile, by cell, then sort and merge.
    let tiles: Vec<(Vec<u32>, Vec<Interval>)> = (0..ntiles)
        .into_par_iter()
        .map(|t| {
            let (ti, tj) = (t as u32 % tx, t as u32 / tx);
            let (i0, j0) = (ti * TILE, tj * TILE);
            let (w, h) = ((nx - i0).min(TILE), (ny - j0).min(TILE));
            let local = |cell: u32| ((cell / nx - j0) * w + (cell % nx - i0)) as usize;
            let (a, b) = (tile_start[t], tile_start[t + 1]);
            let mut offs = vec![0u32; (w * h) as usize + 1];
            for &c in &cells[a..b] {
                offs[local(c) + 1] += 1;
            }
            for k in 1..offs.len() {
                offs[k] += offs[k - 1];
            }
            let mut sorted = vec![0u128; b - a];
            let mut cur = offs.clone();
            for (&c, &k) in cells[a..b].iter().zip(&keys[a..b]) {
                let l = local(c);
                sorted[cur[l] as usize] = k;
                cur[l] += 1;
            }
            // starts[l]..starts[l + 1]: the merged intervals of local cell l.
            let mut starts = Vec::with_capacity((w * h) as usize + 1);
            starts.push(0u32);
            let mut out = Vec::new();
            for l in 0..(w * h) as usize {
                merge_cell(&mut sorted[offs[l] as usize..offs[l + 1] as usize], gap, mode, &mut out);
                starts.push(out.len() as u32);
            }
            (starts, out)
        })
        .collect();
    drop((cells, keys));
    // Row-major CSR from the tiles.
    let n = spec.cells();
    let mut offsets = Vec::with_capacity(n + 1);
    offsets.push(0u32);
    let total: usize = tiles.iter().map(|t| t.1.len()).sum();
    let mut intervals = Vec::with_capacity(total);
    for j in 0..ny {
        let tj = j / TILE;
        for ti in 0..tx {
            let t = (tj * tx + ti) as usize;
            let (i0, j0) = (ti * TILE, tj * TILE);
            let w = (nx - i0).min(TILE);
            let row = ((j - j0) * w) as usize;
            let (s, out) = &tiles[t];
            let (a, b) = (s[row] as usize, s[row + w as usize] as usize);
            intervals.extend_from_slice(&out[a..b]);
            for l in row..row + w as usize {
                offsets.push(offsets.last().copied().unwrap_or(0) + (s[l + 1] - s[l]));
            }
        }
    }
    let mut m = Mdm { spec, mode, offsets, intervals, objects, pyramid: vec![] };
    m.build_pyramid();
    m
}

#[derive(Clone, Copy)]
struct SendPtr<T>(*mut T);
unsafe impl<T> Send for SendPtr<T> {}
unsafe impl<T> Sync for SendPtr<T> {}
impl<T> SendPtr<T> {
    fn get(self) -> *mut T {
        self.0
    }
}

impl Mdm {
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
        let base: Vec<f32> = (0..ny)
            .flat_map(|j| (0..nx).map(move |i| (i, j)))
            .map(|(i, j)| {
                let k = (j * nx + i) as usize;
                self.intervals[self.offsets[k] as usize..self.offsets[k + 1] as usize]
                    .iter()
                    .map(|iv| iv.zhi)
                    .fold(f32::NEG_INFINITY, f32::max)
            })
            .collect();
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
        self.pyramid = levels;
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
