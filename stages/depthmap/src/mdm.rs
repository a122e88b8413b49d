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
use std::path::Path;

mod assemble;
mod raster;

pub use assemble::{RawJob, assemble_sources, group_by_band, mesh_jobs, raw_jobs};
pub use raster::{
    mesh_cells, mesh_cells_bound, mesh_raws, point_cells, point_cells_bound, point_raws, triangle_cell_count,
    triangle_cells,
};

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

/// Whether CSR `offsets` describe `intervals` intervals: from 0, never
/// falling, ending at their count.
pub fn offsets_describe(offsets: &[u32], intervals: usize) -> bool {
    offsets.first() == Some(&0)
        && offsets.windows(2).all(|w| w[0] <= w[1])
        && offsets.last().is_some_and(|&n| n as usize == intervals)
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
        point_obj(self.ground[k])
    }
}

/// Object id of a point by its ground flag.
#[inline]
pub(crate) fn point_obj(ground: bool) -> u32 {
    if ground { OBJ_GROUND } else { OBJ_SCAN }
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

/// The greatest `f32` at most `v`.
fn f32_at_most(v: f64) -> f32 {
    let f = v as f32;
    if f as f64 > v { f.next_down() } else { f }
}

/// The least `f32` at least `v`.
fn f32_at_least(v: f64) -> f32 {
    let f = v as f32;
    if (f as f64) < v { f.next_up() } else { f }
}

/// Inverse of [`f32_key`].
#[inline]
pub(crate) fn f32_from_key(k: u32) -> f32 {
    f32::from_bits(if k & 0x8000_0000 != 0 { k & 0x7fff_ffff } else { !k })
}

/// The highest top of a cell's intervals, `-inf` if it has none: the greatest
/// in key order ([`f32_key`]), so that of a -0 and a +0 top every path picks
/// the same one (`f32::max` may return either).
pub fn cell_top(cell: &[Interval]) -> f32 {
    cell.iter().map(|i| f32_key(i.zhi)).max().map_or(f32::NEG_INFINITY, f32_from_key)
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

    /// This map with `boxes` added as solid objects (their names appended to
    /// the map's objects): in every cell a box reaches, the box's exact
    /// height range over the cell, widened to the next `f32` outwards, so a
    /// box query meets the box wherever it is. For obstacles that are known
    /// as boxes only after the map is built (another lift's load where it
    /// stands during this one); a map built with them as triangles would
    /// hold the same or tighter ranges.
    pub fn with_boxes(&self, boxes: &[(liftplan_core::obb::Obb, String)]) -> Mdm {
        let spec = self.spec;
        let first_obj = self.objects.len() as u32;
        // (cell, interval) for the cells the boxes reach, in cell order: no
        // per-cell list for a grid of millions of cells.
        let mut added: Vec<(usize, Interval)> = Vec::new();
        for (n, (b, _)) in boxes.iter().enumerate() {
            let a = b.aabb();
            for j in spec.rows_between(a.min[1], a.max[1]) {
                for i in spec.cols_between(a.min[0], a.max[0]) {
                    let r = spec.rect(i, j);
                    if let Some((lo, hi)) = b.z_range_over_rect(r[0], r[1], r[2], r[3]) {
                        let zlo = f32_at_most(lo);
                        let zhi = f32_at_least(hi);
                        added.push(((j * spec.nx + i) as usize, Interval { zlo, zhi, obj: first_obj + n as u32 }));
                    }
                }
            }
        }
        let order = |i: &Interval| (f32_key(i.zlo), f32_key(i.zhi), i.obj);
        let mut counts = Vec::with_capacity(spec.cells());
        let mut tops = Vec::with_capacity(spec.cells());
        let mut intervals = Vec::with_capacity(self.intervals.len());
        added.sort_by_key(|(k, iv)| (*k, order(iv)));
        let mut next = added.iter().peekable();
        for k in 0..spec.cells() {
            let start = intervals.len();
            intervals.extend_from_slice(&self.intervals[self.offsets[k] as usize..self.offsets[k + 1] as usize]);
            let mut more = false;
            while let Some((_, iv)) = next.next_if(|(c, _)| *c == k) {
                intervals.push(*iv);
                more = true;
            }
            if more {
                intervals[start..].sort_unstable_by_key(order);
                if self.mode == Mode::Single {
                    // One interval a cell, as the build keeps it: the lowest
                    // bottom to the highest top, named by the highest.
                    let cell = &intervals[start..];
                    let top = cell.iter().fold(cell[0], |a, i| if f32_key(i.zhi) > f32_key(a.zhi) { *i } else { a });
                    let lo = cell[0].zlo;
                    intervals.truncate(start);
                    intervals.push(Interval { zlo: lo, zhi: top.zhi, obj: top.obj });
                }
            }
            counts.push((intervals.len() - start) as u32);
            tops.push(cell_top(&intervals[start..]));
        }
        let mut objects = self.objects.clone();
        objects.extend(boxes.iter().map(|(_, name)| name.clone()));
        Mdm::from_cells(spec, self.mode, &counts, intervals, tops, objects)
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
        if !offsets_describe(&offsets, ni) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use liftplan_core::frame::{Point3, Vec3, rot_z};
    use liftplan_core::obb::Obb;

    /// A turned box added to a built map: the cells it stands over hold it,
    /// by name, from its lowest to its highest point over each, to the next
    /// `f32` outwards; a box query meets it and one beside it does not; the
    /// cells it misses are the map's own; a single-level map keeps one
    /// interval a cell.
    #[test]
    fn boxes_added_to_a_map_are_obstacles_there_and_nowhere_else() {
        let mut mesh = liftplan_core::mesh::TriMesh::default();
        let g = mesh.group_id("SLAB");
        mesh.add_box(g, [-10.0, -10.0, -0.3], [10.0, 10.0, 0.0]);
        for mode in [Mode::Multi, Mode::Single] {
            let s = crate::Settings { mode, ..Default::default() };
            let inp = crate::Inputs { points: vec![], ground: vec![], mesh: mesh.clone() };
            let map = crate::build_cpu(&inp, &s).unwrap().0;
            let load = Obb::new(Point3::new(2.0, 1.0, 2.5), rot_z(0.5), Vec3::new(2.0, 1.0, 1.0));
            let with = map.with_boxes(&[(load, "load of lift A at its set position".into())]);
            assert_eq!(with.objects.last().map(String::as_str), Some("load of lift A at its set position"));
            let obj = with.objects.len() as u32 - 1;
            let mut held = 0;
            for j in 0..map.spec.ny {
                for i in 0..map.spec.nx {
                    let r = map.spec.rect(i, j);
                    let cell = with.cell(i, j);
                    match load.z_range_over_rect(r[0], r[1], r[2], r[3]) {
                        Some((lo, hi)) => {
                            held += 1;
                            let top = cell.iter().map(|iv| iv.zhi).fold(f32::NEG_INFINITY, f32::max);
                            assert!(top as f64 >= hi && with.top(i, j) as f64 >= hi, "{i} {j}: {cell:?}");
                            if mode == Mode::Multi {
                                let iv = cell.iter().find(|iv| iv.obj == obj).unwrap();
                                assert!((iv.zlo as f64) <= lo && (iv.zlo as f64) > lo - 1e-6, "{iv:?} {lo}");
                                assert!((iv.zhi as f64) >= hi && (iv.zhi as f64) < hi + 1e-6, "{iv:?} {hi}");
                                assert_eq!(cell.len(), map.cell(i, j).len() + 1);
                            } else {
                                assert_eq!((cell.len(), cell[0].obj), (1, obj));
                            }
                        }
                        None => assert_eq!(cell, map.cell(i, j), "{i} {j}"),
                    }
                }
            }
            assert!(held > 20, "{held}");
            let probe = |x: f64| Obb::axis_aligned(Point3::new(x, 1.0, 2.5), Vec3::new(0.2, 0.2, 0.2));
            let hit = with.hit(&probe(2.0)).unwrap();
            assert_eq!(with.object_name(&hit.interval), "load of lift A at its set position");
            assert!(with.hit(&probe(6.0)).is_none() && map.hit(&probe(2.0)).is_none());
        }
    }
}
