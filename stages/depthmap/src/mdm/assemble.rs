//! Passes 2 to 5 of the depth map on the CPU: raw intervals grouped by band
//! of grid rows and by cell, each cell sorted and merged, the map assembled.
//!
//! The points' pass 1 is fused in (8-byte records per band, never a stored
//! raw interval per cell), and so is the triangles' ([`mesh_jobs`]). What a
//! cell's intervals are is fixed by the merge rule (`merge_sorted`,
//! `finish_cell`), which the GPU twin repeats; this module must not change
//! it without the twin, and `tests/assembly.rs` holds both to a plain
//! per-cell reference.

use super::raster::{point_span, triangle_raws};
use super::{
    GridSpec, Interval, Mdm, Mode, OBJ_GROUND, OBJ_SCAN, PointSource, Raw, cell_top, f32_from_key, f32_key,
    local_point, point_obj,
};
use liftplan_core::mesh::TriMesh;
use rayon::prelude::*;

/// Pass 1 for a mesh fused with the grouping by band: [`mesh_raws`](super::mesh_raws)' raw
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

/// Raw intervals made elsewhere (e.g. points by [`point_raws`](super::point_raws)) grouped by
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
/// in the operations [`point_raws`](super::point_raws) uses, so 8 bytes carry what a 16-byte raw
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
    let (xyz, ground) = (&p.xyz[range.clone()], &p.ground[range]);
    // `made[..n]` are the records; the rest is room, written before it is
    // counted, so that the common point costs no branch on its flags.
    let make_room = |made: &mut Vec<(u32, u64)>, len: usize| {
        if made.len() < len {
            made.resize(len.max(2 * made.len()), (0, 0));
        }
    };
    let mut n = 0usize;
    let mut cells = 0usize;
    let mut spans = [[0i32; 4]; BATCH];
    let mut heights = [0f32; BATCH];
    for (xyz, ground) in xyz.chunks(BATCH).zip(ground.chunks(BATCH)) {
        // The spans first, in a loop of arithmetic alone.
        for ((span, z), pt) in spans.iter_mut().zip(heights.iter_mut()).zip(xyz) {
            let q = local_point(pt, spec);
            let (i0, i1, j0, j1) = point_span(&q, p.radius, inv, nx as i64, ny as i64);
            *span = [i0 as i32, i1 as i32, j0 as i32, j1 as i32];
            *z = q[2];
        }
        // Two records a point at most, but for the points handled below.
        make_room(made, n + 2 * BATCH);
        for ((&[i0, i1, j0, j1], &z), &g) in spans.iter().zip(&heights).zip(ground) {
            if i1 < i0 || j1 < j0 {
                continue;
            }
            let obj = point_obj(g);
            if i1 - i0 > 1 || j1 - j0 > 1 {
                // Wider or taller than two cells: a record per cell.
                let (i0, i1, j0, j1) = (i0 as u32, i1 as u32, j0 as u32, j1 as u32);
                let need = (i1 - i0 + 1) as usize * (j1 - j0 + 1) as usize;
                cells += need;
                make_room(made, n + need + 2 * BATCH);
                for j in j0..=j1 {
                    for i in i0..=i1 {
                        made[n] = (j >> band_shift, point_record((j & mask) * nx + i, 0, obj, z));
                        n += 1;
                    }
                }
                continue;
            }
            let (i0, i1, j0, j1) = (i0 as u32, i1 as u32, j0 as u32, j1 as u32);
            cells += (i1 - i0 + 1) as usize * (j1 - j0 + 1) as usize;
            let (b0, b1) = (j0 >> band_shift, j1 >> band_shift);
            let wide = if i1 > i0 { WIDE } else { 0 };
            // Taller than a row: in one band a flag, across two a second
            // record (written always, kept only then).
            let across = (b0 != b1) as usize;
            let tall = if j1 > j0 && across == 0 { TALL } else { 0 };
            made[n] = (b0, point_record((j0 & mask) * nx + i0, wide | tall, obj, z));
            made[n + 1] = (b1, point_record((j1 & mask) * nx + i0, wide, obj, z));
            n += 1 + across;
        }
    }
    let (recs, starts) = group_by_band(&made[..n], bands.count);
    PointJob { recs, starts, cells }
}

/// Points a job takes at a time: their spans first, then their records.
const BATCH: usize = 256;

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
/// where each band's start. Public for the benchmark's yardstick, which
/// groups its records the way the build does.
pub fn group_by_band<T: Copy + Default>(made: &[(u32, T)], bands: usize) -> (Vec<T>, Vec<u32>) {
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
