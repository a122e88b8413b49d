//! Pass 1 of the depth map, the geometry: which cells a scan point or a
//! plant triangle occupies, and over what heights.
//!
//! A point occupies its square of half side `r` and `[z - r, z + r]`; a
//! triangle, in every cell it touches, a conservative range of its heights
//! over that cell (it must never miss an obstacle). This module says nothing
//! about how the raw intervals are grouped, sorted or merged: that is
//! [`super::assemble`]'s job, and the GPU twin's.

use super::{GridSpec, PointSource, Raw, local_point};
use liftplan_core::mesh::TriMesh;
use rayon::prelude::*;

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
pub(crate) fn point_span(q: &[f32; 3], radius: f32, inv: f32, nx: i64, ny: i64) -> (i64, i64, i64, i64) {
    let i0 = floor_index((q[0] - radius) * inv).max(0);
    let i1 = floor_index((q[0] + radius) * inv).min(nx - 1);
    let j0 = floor_index((q[1] - radius) * inv).max(0);
    let j1 = floor_index((q[1] + radius) * inv).min(ny - 1);
    (i0, i1, j0, j1)
}

/// An upper bound on the raw intervals [`point_raws`] makes, without a pass:
/// the points times the most cells one can cover.
pub fn point_cells_bound(points: &PointSource, spec: &GridSpec) -> u64 {
    // A span of 2r starts in one cell and ends at most ceil(2r / cell) cells
    // later; one more for rounding in the f32 arithmetic of `point_span`.
    let side = (2.0 * points.radius as f64 / spec.cell).ceil() as u64 + 2;
    (points.xyz.len() as u64).saturating_mul(side * side)
}

/// The raw intervals [`point_raws`] makes: each point's cells, counted.
pub fn point_cells(points: &PointSource, spec: &GridSpec) -> u64 {
    let inv = (1.0 / spec.cell) as f32;
    let (nx, ny) = (spec.nx as i64, spec.ny as i64);
    points
        .xyz
        .par_iter()
        .map(|p| {
            let (i0, i1, j0, j1) = point_span(&local_point(p, spec), points.radius, inv, nx, ny);
            ((i1 - i0 + 1).max(0) * (j1 - j0 + 1).max(0)) as u64
        })
        .sum()
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
    triangle_rows(t, spec, |tri, j, (a, b), strip| {
        for i in a..=b {
            let (xa, xb) = (i as f64 * c, (i + 1) as f64 * c);
            let (lo, hi) = match strip {
                // Conservative: the whole triangle's heights.
                None => tri.range(2),
                Some(strip) => match heights_between(strip.vertices(), xa, xb) {
                    Some(range) => range,
                    None => continue,
                },
            };
            let pad = 1e-6 * lo.abs().max(hi.abs()) + 1e-6;
            emit(j * spec.nx + i, (lo - pad) as f32, (hi + pad) as f32);
        }
    });
}

/// How many cells [`triangle_cells`] visits for the triangle: an upper bound
/// on the raw intervals it makes (a cell its strip spans but the triangle
/// misses makes none), found without the per-cell clipping.
pub fn triangle_cell_count(t: &[[f64; 3]; 3], spec: &GridSpec) -> u64 {
    let mut n = 0u64;
    triangle_rows(t, spec, |_, _, (a, b), _| n += (b as u64 + 1).saturating_sub(a as u64));
    n
}

/// The grid rows a triangle crosses: for each, the row `j`, the columns
/// `(a, b)` its strip spans and the strip (the triangle clipped to the row),
/// or `None` where clipping lost precision and the row is taken across the
/// triangle's whole column range.
fn triangle_rows(t: &[[f64; 3]; 3], spec: &GridSpec, mut row: impl FnMut(&Poly, u32, (u32, u32), Option<&Poly>)) {
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
        if strip.lossy {
            row(&tri, j, (i0, i1), None);
        } else {
            let (sx0, sx1) = strip.range(0);
            let span = (((sx0 / c).floor().max(i0 as f64)) as u32, ((sx1 / c).floor().min(i1 as f64)) as u32);
            row(&tri, j, span, Some(&strip));
        }
    }
}

/// Triangle `t` of a mesh in grid-local coordinates.
fn local_triangle(m: &TriMesh, spec: &GridSpec, t: usize) -> [[f64; 3]; 3] {
    let p = |k: usize| {
        let v = m.vertices[m.triangles[t][k] as usize];
        [v[0] - spec.x0, v[1] - spec.y0, v[2]]
    };
    [p(0), p(1), p(2)]
}

/// An upper bound on the raw intervals [`mesh_raws`] makes, in one cheap
/// pass: the cells of each triangle's bounding box, summed.
pub fn mesh_cells_bound(m: &TriMesh, spec: &GridSpec) -> u64 {
    (0..m.triangles.len())
        .into_par_iter()
        .map(|t| {
            let v = local_triangle(m, spec, t);
            let span = |axis: usize, cells: u32| {
                let lo = v.iter().map(|p| p[axis]).fold(f64::INFINITY, f64::min) / spec.cell;
                let hi = v.iter().map(|p| p[axis]).fold(f64::NEG_INFINITY, f64::max) / spec.cell;
                let (lo, hi) = (lo.floor().max(0.0), hi.floor().min(cells as f64 - 1.0));
                if hi >= lo { (hi - lo) as u64 + 1 } else { 0 }
            };
            span(0, spec.nx) * span(1, spec.ny)
        })
        .sum()
}

/// A tighter upper bound than [`mesh_cells_bound`]: the cells
/// [`triangle_cell_count`] finds for each triangle (a long diagonal pipe
/// covers a few of its box's thousands of cells).
pub fn mesh_cells(m: &TriMesh, spec: &GridSpec) -> u64 {
    (0..m.triangles.len()).into_par_iter().map(|t| triangle_cell_count(&local_triangle(m, spec, t), spec)).sum()
}

/// Pass 1 for a mesh: raw intervals of every triangle (`triangle_raws`), in
/// chunks of triangles rasterised in parallel. The plain form, which the
/// tests use as reference; the build uses [`mesh_jobs`](super::mesh_jobs).
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
pub(crate) fn triangle_raws(m: &TriMesh, t: usize, spec: &GridSpec, obj_base: u32, mut emit: impl FnMut(Raw)) {
    let part_idx = m.part_of[t] as usize;
    let part = &m.parts[part_idx];
    let obj = obj_base + part.group;
    let pk = if part.convex_solid { part_idx as u32 + 1 } else { 0 };
    triangle_cells(&local_triangle(m, spec, t), spec, |cell, zlo, zhi| emit(Raw { cell, zlo, zhi, obj, part: pk }));
}
