//! The GPU twin of the box queries ([`Mdm::hit_where`]) and the vertical
//! clearances ([`Mdm::clearance_where`]): the device answers
//! what it can prove in `f32`, the CPU's exact test the rest.
//!
//! The exact per-cell test ([`liftplan_core::obb::Obb::z_range_over_rect`]) is
//! `f64` geometry, which WGSL lacks, and an `f32` copy of it would not give
//! the CPU's answers bit for bit on every driver (GPU compilers may fuse
//! multiply-adds and divide to 2.5 ulp). So the device works like a filtered
//! geometric predicate. Each box goes up twice over: grown by a margin larger
//! than the `f32` rounding of the shader's few operations, by the accounting
//! at [`MARGIN_REL`] (the
//! *outer* box, which holds every point within the margin of the queried
//! one), and shrunk by it (the *inner* box, inside the queried one). The
//! shader walks the max-height pyramid and the cells exactly as the CPU's
//! walk does, in the same order, and decides each interval it meets:
//!
//! - outside the outer box's heights over the cell (a relaxation: each box
//!   axis alone bounds them; when the next test fails, the exact range, by
//!   duality: a bound on the heights that holds for any multipliers of the
//!   column's sides, so `f32` rounding only needs a room added, and whose
//!   best value, at one of ten multipliers, is the exact range): the CPU's
//!   exact test misses it too;
//! - meeting heights the inner box surely has over the cell (its height
//!   range over the cell pulled in by a margin, from the corners of that
//!   convex piece: the box's corners in the column, its edges' crossings
//!   with the column's sides, its segments on the column's edges; for an
//!   upright box, its height range wherever its footprint meets the cell):
//!   the CPU's exact test meets it too, and as nothing before it in the walk
//!   met the box, it is the CPU's answer, cell and interval;
//! - anything else: the device gives the box up, and the CPU answers it.
//!
//! A box the walk passes whole without a contact is free on both paths. So
//! every answer is the CPU's answer, `Hit` for `Hit` (the tests compare them
//! on random sites and boxes); how many boxes the device answers itself is a
//! matter of speed only (`ScreenCounts`).
//!
//! The vertical clearances ([`Mdm::clearance_where`], [`Gpu::clearances_where`])
//! work the same way with bounds instead of a yes or no. A cell's gap is an
//! `f32` subtraction from the box's exact heights over the cell; the device
//! bounds it from below with the outer box's heights (less a slack of 2^-20
//! of the heights, sixteen times the rounding of the subtraction on either
//! path) and from above with the inner box's, where those surely meet an
//! interval. It walks the box's cells, keeps the least upper bound found and
//! its cell, and keeps every cell whose lower bound does not lose to it in
//! the CPU's order (the smaller gap, then the lower cell index). Every cell
//! it drops has a larger gap than that cell, or an equal one later in that
//! order, so the CPU's answer lies in the cells it keeps (at most
//! [`CELLS`]), which the CPU then measures with its own per-cell test and
//! tie rule. For an upright box the heights are the CPU's own (the same over
//! every column it reaches), so its gaps are exact where it surely reaches a
//! cell, and over level ground the device settles the tie itself and keeps
//! one cell. More cells than that, or a walk past its budget: the CPU
//! answers the box whole.
//!
//! Must not: guess. A box it cannot place in `f32` safely (coordinates over
//! [`MAX_COORD_M`] from the grid origin), or whose walk runs past its loop
//! budget (a device that cuts loops short, [`Gpu::loop_cap`], gets half that
//! cap, and an answer goes out only when every loop of the walk, and the
//! one writing the answer, ended by itself),
//! goes to the CPU; so do all clearances on a map with heights beyond
//! [`MAX_HEIGHT_M`].

use super::{Gpu, words_from_bytes, words_to_bytes};
use crate::mdm::{Interval, Mdm};
use crate::query::{Clearance, Hit, LeaveOut, Vertical};
use liftplan_core::obb::Obb;
use rayon::prelude::*;

/// The shader.
pub(super) const SHADER: &str = include_str!("screen.wgsl");

/// Words a box takes on the device (the shader's layout).
const BOX_WORDS: usize = 33;
const SCREEN_GROUP: u32 = 64;
/// The shader's flag (in a box's word 31) for a box turned about z only.
const UPRIGHT: u32 = 0x100;
/// Boxes farther than this from the grid origin (m) are left to the CPU: the
/// margin that covers `f32` rounding grows with the coordinates.
pub const MAX_COORD_M: f64 = 1e6;
/// The margin's fixed part (m) and its part relative to the box's reach `F`
/// (its centre's largest grid-local coordinate, plus its size and two
/// cells): 2^-18 is 64 u, with u = 2^-24 the unit roundoff of `f32`.
///
/// The accounting (in u F, worst cases; the division is WGSL's, within
/// 2.5 ulps, 5 u):
/// - The `f32` box as written (centre within u F, axes within u, half sizes
///   rounded outward or inward), with the `f32` cell edges (within 2 u F),
///   holds the queried box over the true cell to within 9 u F: left over,
///   55.
/// - `outer_axis` errs by at most 10 in its numerator, 12.5 more once
///   divided by the axis' height (divided too, as is the margin) and 3.5
///   when the centre is added: 26, inside 55.
/// - `inner_range`'s points lie within 5 of the `f32` inner box (corners and
///   edges), 12 more across a side for a crossing, and a segment's ends
///   within 33 of its slabs (the division's error is an error along the
///   axis, not in height): at most 42, inside 64, so a point of the queried
///   box has that height over the cell.
/// - `outer_exact` is exact up to a room it adds for its own rounding.
///
/// The fixed part covers the CPU's own tolerances (1e-9 m, and its `f64`
/// rounding) with room to spare. At the twelfth stop the margin was 1 mm
/// plus 2^-16 (256 u): five times as many of the C-space test's boxes went
/// to the CPU, all at contacts within a few margins.
const MARGIN_M: f64 = 1e-4;
const MARGIN_REL: f64 = 1.0 / 262144.0;
/// Answer words per box of the clearance walk: verdict, number of cells,
/// and up to [`CELLS`] cells (the shader's `CLEAR_WORDS`).
const CLEAR_WORDS: usize = 12;
/// Cells the clearance walk may hand the CPU for one box (the shader's
/// `CELLS`); a box with more undecided cells is left to the CPU whole.
const CELLS: usize = 10;
/// Maps with heights farther than this from zero (m) take no clearances on
/// the device: the shader's gaps and their bounds must stay far from
/// `f32`'s largest number.
const MAX_HEIGHT_M: f32 = 1e30;
/// Loop iterations one box may take on a device that runs loops to the end:
/// a box over more cells and intervals than that is left to the CPU.
const BUDGET: u32 = 1 << 20;

/// A depth map on the device, for [`Gpu::hits_where`].
pub struct GpuMap {
    offsets: wgpu::Buffer,
    intervals: wgpu::Buffer,
    tops: wgpu::Buffer,
    levels: wgpu::Buffer,
    /// What the buffers were made from, to refuse a different map.
    spec: crate::mdm::GridSpec,
    intervals_len: usize,
    levels_len: usize,
    /// The largest height in the map, by magnitude (m).
    height_bound: f32,
}

impl GpuMap {
    /// Refuses a query of `map` against a different map on the device.
    fn check_is(&self, map: &Mdm) -> Result<(), String> {
        if self.spec != map.spec || self.intervals_len != map.intervals.len() || self.levels_len != map.pyramid.len() {
            return Err("the depth map on the GPU is not the one queried".into());
        }
        Ok(())
    }
}

/// How a batch of boxes was answered, and where the time went.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ScreenCounts {
    /// Answered "free" by the device (clearances: nothing lies that way).
    pub free_on_gpu: usize,
    /// Answered with their first contact by the device (clearances: the
    /// device proved the answer lies in a few cells, `cells_measured` in
    /// all, which the CPU then measured exactly).
    pub hit_on_gpu: usize,
    /// Answered by the CPU's exact query: a contact the device could not
    /// decide in `f32`, a walk over its loop budget, or a box too far from
    /// the grid origin.
    pub left_to_cpu: usize,
    /// Preparing the boxes, the device's walk and its answers read back (ms,
    /// wall clock on the host).
    pub screen_ms: f64,
    /// Of `screen_ms`, preparing the boxes on the host (ms).
    pub prepare_ms: f64,
    /// Of `screen_ms`, the host's share of moving boxes and answers: filling
    /// the device's buffers with the boxes and decoding the answers read
    /// back (ms). What is left of `screen_ms` after this and `prepare_ms`
    /// is the device's walk, the copies and the wait for them.
    pub transfer_ms: f64,
    /// The CPU's exact queries of the boxes left to it, and for clearances
    /// its measuring of the device's cells (ms).
    pub exact_ms: f64,
    /// Clearances: the cells the CPU measured for the boxes the device
    /// narrowed down (`hit_on_gpu`).
    pub cells_measured: usize,
}

impl ScreenCounts {
    /// Boxes answered, by the device or the CPU.
    pub fn boxes(&self) -> usize {
        self.free_on_gpu + self.hit_on_gpu + self.left_to_cpu
    }

    /// No boxes yet, and the times of a batch begun at `t0` whose device
    /// part ended at `t_exact` and whose CPU part ends now.
    fn timed(t0: std::time::Instant, t_exact: std::time::Instant, host: HostMs) -> ScreenCounts {
        ScreenCounts {
            screen_ms: (t_exact - t0).as_secs_f64() * 1e3,
            prepare_ms: host.prepare,
            transfer_ms: host.transfer,
            exact_ms: t_exact.elapsed().as_secs_f64() * 1e3,
            ..ScreenCounts::default()
        }
    }

    /// Adds another batch's counts and times to these.
    pub fn add(&mut self, o: &ScreenCounts) {
        self.free_on_gpu += o.free_on_gpu;
        self.hit_on_gpu += o.hit_on_gpu;
        self.left_to_cpu += o.left_to_cpu;
        self.screen_ms += o.screen_ms;
        self.prepare_ms += o.prepare_ms;
        self.transfer_ms += o.transfer_ms;
        self.exact_ms += o.exact_ms;
        self.cells_measured += o.cells_measured;
    }
}

/// Where the host's own time went in a batch (ms).
#[derive(Clone, Copy, Default)]
struct HostMs {
    prepare: f64,
    transfer: f64,
}

/// The device's answer for one box.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Verdict {
    Free,
    Hit(Hit),
    LeftToCpu,
}

impl Gpu {
    /// Puts a depth map on the device for box queries.
    pub fn upload_map(&self, map: &Mdm) -> Result<GpuMap, String> {
        let spec = map.spec;
        let consistent = map.offsets.len() == spec.cells() + 1
            && crate::mdm::offsets_describe(&map.offsets, map.intervals.len())
            && map.pyramid.first().is_some_and(|l| l.2.len() == spec.cells());
        if !consistent {
            return Err("depth map is not consistent (offsets or pyramid do not match its grid)".into());
        }
        if map.intervals.iter().any(|iv| iv.obj == u32::MAX) {
            // The shader reads u32::MAX as "no object left out".
            return Err("depth map has an interval of object id 4294967295, which the GPU queries reserve".into());
        }
        let mut tops = Vec::new();
        let mut levels = Vec::new();
        for (w, h, data) in &map.pyramid {
            levels.extend([tops.len() as u32, *w, *h, 0]);
            // WGSL may assume no infinities: an empty cell's -inf goes up as
            // the lowest finite height, which compares the same way.
            tops.extend(data.iter().map(|t| t.max(f32::MIN).to_bits()));
        }
        let mut intervals: Vec<u32> =
            map.intervals.iter().flat_map(|iv| [iv.zlo.to_bits(), iv.zhi.to_bits(), iv.obj]).collect();
        // A buffer is never empty.
        intervals.resize(intervals.len().max(4), 0);
        for (what, words) in [("offsets", map.offsets.len()), ("intervals", intervals.len()), ("pyramid", tops.len())] {
            if 4 * words as u64 > self.buffer_limit {
                return Err(format!(
                    "the depth map's {what} take {} bytes, more than one GPU buffer holds ({} bytes)",
                    4 * words,
                    self.buffer_limit
                ));
            }
        }
        let usage = wgpu::BufferUsages::STORAGE;
        liftplan_core::gpu::catching_errors(&self.dev, || {
            Ok(GpuMap {
                offsets: self.upload("map offsets", &words_to_bytes(&map.offsets), usage),
                intervals: self.upload("map intervals", &words_to_bytes(&intervals), usage),
                tops: self.upload("map pyramid", &words_to_bytes(&tops), usage),
                levels: self.upload("map levels", &words_to_bytes(&levels), usage),
                spec,
                intervals_len: map.intervals.len(),
                levels_len: map.pyramid.len(),
                height_bound: map.intervals.iter().fold(0.0f32, |m, iv| m.max(iv.zlo.abs()).max(iv.zhi.abs())),
            })
        })
    }

    /// [`Mdm::hit_where`] for every box, with `counts` "all but what `leave`
    /// leaves out" ([`LeaveOut::counts`]): the device answers what it can
    /// prove, the CPU the rest (see the module doc). `gpu_map` must be `map`
    /// uploaded.
    pub fn hits_where(
        &self,
        gpu_map: &GpuMap,
        map: &Mdm,
        boxes: &[Obb],
        leave: Option<LeaveOut>,
    ) -> Result<(Vec<Option<Hit>>, ScreenCounts), String> {
        gpu_map.check_is(map)?;
        let t0 = std::time::Instant::now();
        let (verdicts, host) = self.screen(gpu_map, map, boxes, leave)?;
        let t_exact = std::time::Instant::now();
        let counts_obj = |iv: &Interval| LeaveOut::counts(leave, iv);
        let hits = boxes
            .par_iter()
            .zip(&verdicts)
            .map(|(b, v)| match v {
                Verdict::Free => None,
                Verdict::Hit(h) => Some(*h),
                Verdict::LeftToCpu => map.hit_where(b, counts_obj),
            })
            .collect();
        let mut counts = ScreenCounts::timed(t0, t_exact, host);
        for v in &verdicts {
            match v {
                Verdict::Free => counts.free_on_gpu += 1,
                Verdict::Hit(_) => counts.hit_on_gpu += 1,
                Verdict::LeftToCpu => counts.left_to_cpu += 1,
            }
        }
        Ok((hits, counts))
    }

    /// The device's answer for every box, and where the host's own time
    /// went.
    fn screen(
        &self,
        gpu_map: &GpuMap,
        map: &Mdm,
        boxes: &[Obb],
        leave: Option<LeaveOut>,
    ) -> Result<(Vec<Verdict>, HostMs), String> {
        let batch = prepare_batch(map, boxes, leave);
        let mut verdicts: Vec<Verdict> =
            batch.outside.iter().map(|&out| if out { Verdict::Free } else { Verdict::LeftToCpu }).collect();
        let run = Dispatch { pipeline: &self.screen_boxes, way: 0, exact: None, out_binding: 6, out_words: 4 };
        let transfer = self.dispatch(gpu_map, map, &batch, &run, |k, a| verdicts[k] = verdict(map, a))?;
        Ok((verdicts, HostMs { prepare: batch.prepare_ms, transfer }))
    }

    /// Runs `run` over the boxes of `batch` that go up, in batches that fit
    /// the device's buffers, and hands each box's answer words to `take`
    /// with the box's place in the caller's list. Returns the host's time
    /// filling the buffers and decoding the answers (ms).
    fn dispatch(
        &self,
        gpu_map: &GpuMap,
        map: &Mdm,
        batch: &Batch,
        run: &Dispatch,
        mut take: impl FnMut(usize, &[u32]),
    ) -> Result<f64, String> {
        let budget = self.loop_cap.map_or(BUDGET, |cap| cap / 2);
        let spec = map.spec;
        // The inner test's lines stand this far inside a cell, clear of the
        // rounding of the cell's edges (a few ulps of the grid's size).
        let size = spec.nx.max(spec.ny) as f64 * spec.cell;
        let margin = 1e-4 + size / (1u64 << 20) as f64;
        let margin = if margin < spec.cell / 4.0 { margin as f32 } else { -1.0 };
        let per_box = (BOX_WORDS + 2 + run.out_words) as u64 * 4;
        let per_batch = ((self.buffer_limit / (4 * per_box)) as usize).max(1);
        let mut transfer = std::time::Duration::ZERO;
        liftplan_core::gpu::catching_errors(&self.dev, || {
            for (n, chunk) in batch.sent.chunks(per_batch).enumerate() {
                let first = n * per_batch;
                let t_fill = std::time::Instant::now();
                let words = batch.words[first..first + chunk.len()].as_flattened();
                let boxes_buf = self.upload("query boxes", &words_to_bytes(words), wgpu::BufferUsages::STORAGE);
                let out = self.storage("query answers", 4 * (run.out_words * chunk.len()) as u64);
                let params = [
                    chunk.len() as u32,
                    spec.nx,
                    spec.ny,
                    budget,
                    (spec.cell as f32).to_bits(),
                    margin.to_bits(),
                    run.way,
                    0,
                ];
                let p = self.upload("query params", &words_to_bytes(&params), wgpu::BufferUsages::UNIFORM);
                let mut binds = vec![
                    (0, &p),
                    (1, &boxes_buf),
                    (2, &gpu_map.offsets),
                    (3, &gpu_map.intervals),
                    (4, &gpu_map.tops),
                    (5, &gpu_map.levels),
                    (run.out_binding, &out),
                ];
                let exact_buf;
                if let Some(exact) = run.exact {
                    let words = &exact[2 * first..2 * (first + chunk.len())];
                    exact_buf = self.upload("query exact heights", &words_to_bytes(words), wgpu::BufferUsages::STORAGE);
                    binds.push((7, &exact_buf));
                }
                transfer += t_fill.elapsed();
                let mut enc = self.dev.device.create_command_encoder(&Default::default());
                self.pass(&mut enc, run.pipeline, &binds, chunk.len() as u32, SCREEN_GROUP);
                self.submit(enc);
                let bytes =
                    liftplan_core::gpu::read_back(&self.dev, &out, 0, 4 * (run.out_words * chunk.len()) as u64)?;
                let t_decode = std::time::Instant::now();
                let answers = words_from_bytes(&bytes);
                for (k, a) in chunk.iter().zip(answers.chunks_exact(run.out_words)) {
                    take(*k, a);
                }
                transfer += t_decode.elapsed();
            }
            Ok(())
        })?;
        Ok(transfer.as_secs_f64() * 1e3)
    }

    /// [`Mdm::clearance_where`] for every box, with `counts` "all but what
    /// `leave` leaves out" ([`LeaveOut::counts`]): the device narrows each
    /// box's answer down to a few cells, the CPU measures those exactly (see
    /// the module doc). `gpu_map` must be `map` uploaded.
    pub fn clearances_where(
        &self,
        gpu_map: &GpuMap,
        map: &Mdm,
        boxes: &[Obb],
        way: Vertical,
        leave: Option<LeaveOut>,
    ) -> Result<(Vec<Option<Clearance>>, ScreenCounts), String> {
        gpu_map.check_is(map)?;
        let t0 = std::time::Instant::now();
        let mut batch = prepare_batch(map, boxes, leave);
        let mut answers: Vec<Narrowed> =
            batch.outside.iter().map(|&out| if out { Narrowed::Nothing } else { Narrowed::LeftToCpu }).collect();
        if gpu_map.height_bound > MAX_HEIGHT_M {
            // Gaps and their bounds could overflow `f32` on the device.
            batch.sent.clear();
        }
        // An upright box's heights are the same over every column it
        // reaches: the CPU's, rounded as it rounds them, go up with it.
        let exact: Vec<u32> = batch
            .sent
            .iter()
            .flat_map(|&k| {
                let b = &boxes[k];
                [((b.center.z - b.half.z) as f32).to_bits(), ((b.center.z + b.half.z) as f32).to_bits()]
            })
            .collect();
        let prepare_ms = t0.elapsed().as_secs_f64() * 1e3;
        let way_word = match way {
            Vertical::Down => 0,
            Vertical::Up => 1,
        };
        let run = Dispatch {
            pipeline: &self.clear_boxes,
            way: way_word,
            exact: Some(&exact),
            out_binding: 8,
            out_words: CLEAR_WORDS,
        };
        let transfer = self.dispatch(gpu_map, map, &batch, &run, |k, a| answers[k] = narrowed(map, a))?;
        let t_exact = std::time::Instant::now();
        let counts_obj = |iv: &Interval| LeaveOut::counts(leave, iv);
        let found = boxes
            .par_iter()
            .zip(&answers)
            .map(|(b, a)| match a {
                Narrowed::Nothing => None,
                Narrowed::Cells(n, cells) => map.clearance_in_cells(b, way, counts_obj, &cells[..*n]),
                Narrowed::LeftToCpu => map.clearance_where(b, way, counts_obj),
            })
            .collect();
        let mut counts = ScreenCounts::timed(t0, t_exact, HostMs { prepare: prepare_ms, transfer });
        for a in &answers {
            match a {
                Narrowed::Nothing => counts.free_on_gpu += 1,
                Narrowed::Cells(n, _) => {
                    counts.hit_on_gpu += 1;
                    counts.cells_measured += n;
                }
                Narrowed::LeftToCpu => counts.left_to_cpu += 1,
            }
        }
        Ok((found, counts))
    }
}

/// One kind of device walk over a batch of boxes.
struct Dispatch<'a> {
    pipeline: &'a wgpu::ComputePipeline,
    /// The params' word 6 (clearances: 0 down, 1 up).
    way: u32,
    /// Two words per box that goes up, bound at 7, if the walk reads them.
    exact: Option<&'a [u32]>,
    out_binding: u32,
    /// Answer words per box.
    out_words: usize,
}

/// The boxes made ready for the device.
struct Batch {
    /// Per box: its bounding box misses the grid (no answer to look for, on
    /// both paths).
    outside: Vec<bool>,
    /// The boxes that go up, by their place in the caller's list, and their
    /// words, one slot of `BOX_WORDS` each. A box neither outside nor sent is left to
    /// the CPU (too far out, or not finite).
    sent: Vec<usize>,
    words: Vec<[u32; BOX_WORDS]>,
    /// Time spent preparing (ms).
    prepare_ms: f64,
}

/// Every box made ready in parallel, straight into its slot of one buffer;
/// the slots of boxes that do not go up are then closed up in place. One
/// buffer, written once and in parallel: a buffer per box gathered into
/// another took as long again as preparing the boxes (measured on the
/// C-space's 118,080 boom boxes).
fn prepare_batch(map: &Mdm, boxes: &[Obb], leave: Option<LeaveOut>) -> Batch {
    let t = std::time::Instant::now();
    let mut words = vec![[0u32; BOX_WORDS]; boxes.len()];
    let kinds: Vec<Prepared> =
        words.par_iter_mut().zip(boxes.par_iter()).map(|(w, b)| prepare(b, map, leave, w)).collect();
    let mut batch =
        Batch { outside: vec![false; boxes.len()], sent: Vec::with_capacity(boxes.len()), words, prepare_ms: 0.0 };
    for (k, kind) in kinds.into_iter().enumerate() {
        match kind {
            Prepared::Outside => batch.outside[k] = true,
            Prepared::Unsafe => {}
            Prepared::Sent => {
                let to = batch.sent.len();
                batch.words[to] = batch.words[k];
                batch.sent.push(k);
            }
        }
    }
    batch.words.truncate(batch.sent.len());
    batch.prepare_ms = t.elapsed().as_secs_f64() * 1e3;
    batch
}

/// One box's answer from the device, `[verdict, cell, interval, 0]`. A hit
/// whose interval is not in its cell is not trusted: the CPU answers.
fn verdict(map: &Mdm, a: &[u32]) -> Verdict {
    match a[0] {
        0 => Verdict::Free,
        1 => {
            let (cell, k) = (a[1] as usize, a[2]);
            let inside = cell < map.spec.cells() && (map.offsets[cell]..map.offsets[cell + 1]).contains(&k);
            if !inside {
                return Verdict::LeftToCpu;
            }
            let nx = map.spec.nx as usize;
            Verdict::Hit(Hit { i: (cell % nx) as u32, j: (cell / nx) as u32, interval: map.intervals[k as usize] })
        }
        _ => Verdict::LeftToCpu,
    }
}

/// The clearance walk's answer for one box.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Narrowed {
    /// Nothing it could meet lies that way, in any cell.
    Nothing,
    /// The answer lies in one of these cells (the first `.0`).
    Cells(usize, [u32; CELLS]),
    LeftToCpu,
}

/// One box's clearance answer from the device, `[verdict, n, cells...]`.
/// Cells off the grid, or a count out of range, are not trusted: the CPU
/// answers.
fn narrowed(map: &Mdm, a: &[u32]) -> Narrowed {
    match a[0] {
        0 => Narrowed::Nothing,
        1 => {
            let n = a[1] as usize;
            let cells = map.spec.cells();
            if n == 0 || n > CELLS || a[2..2 + n].iter().any(|&c| c as usize >= cells) {
                return Narrowed::LeftToCpu;
            }
            let mut out = [0u32; CELLS];
            out[..n].copy_from_slice(&a[2..2 + n]);
            Narrowed::Cells(n, out)
        }
        _ => Narrowed::LeftToCpu,
    }
}

/// What became of a box made ready for the device.
enum Prepared {
    /// Its bounding box misses the grid: free on both paths.
    Outside,
    /// Too far out, or not finite, to take to `f32` safely.
    Unsafe,
    /// Its words are written: it goes up.
    Sent,
}

/// The box in grid-local `f32` (the shader's layout): centre and axes
/// rounded, the outer half sizes (grown by the margin) and z range rounded
/// outward, the inner ones (shrunk by it) inward, the outer box's cells, and
/// where the CPU's walk starts ([`Mdm::hit_where`]), written into `out`
/// where the box goes up.
fn prepare(b: &Obb, map: &Mdm, leave: Option<LeaveOut>, out: &mut [u32; BOX_WORDS]) -> Prepared {
    let s = map.spec;
    let local = [b.center.x - s.x0, b.center.y - s.y0, b.center.z];
    let size = b.half.norm();
    let far = local.iter().fold(0.0f64, |m, v| m.max(v.abs())) + size + 2.0 * s.cell;
    let finite = local.iter().chain(b.half.iter()).chain(b.axes.iter()).all(|v| v.is_finite());
    if !finite || far > MAX_COORD_M {
        return Prepared::Unsafe;
    }
    // The CPU's walk: its start tiles.
    let Some(start) = map.start_tiles(&b.aabb()) else { return Prepared::Outside };
    let margin = MARGIN_M + MARGIN_REL * far;
    let outer = b.expanded(margin);
    let outer_box = outer.aabb();
    let (oi, oj) =
        (s.cols_between(outer_box.min[0], outer_box.max[0]), s.rows_between(outer_box.min[1], outer_box.max[1]));
    let mut w = [0u32; BOX_WORDS];
    for (k, v) in local.iter().enumerate() {
        w[k] = (*v as f32).to_bits();
    }
    w[3] = leave.map_or(u32::MAX, |l| l.obj);
    // WGSL may assume no infinities: the whole object goes up as "at or
    // below the largest finite height", which leaves out the same intervals.
    w[32] = leave.map_or(f32::MAX, |l| l.up_to_m().clamp(f32::MIN, f32::MAX)).to_bits();
    let inner = [b.half[0] - margin, b.half[1] - margin, b.half[2] - margin];
    let inner_ok = inner.iter().all(|h| *h > 0.0);
    for k in 0..3 {
        for r in 0..3 {
            w[4 + 4 * k + r] = (b.axes[(r, k)] as f32).to_bits();
        }
        w[7 + 4 * k] = f32_up(outer.half[k]).to_bits();
        w[24 + k] = f32_down(inner[k].max(0.0)).to_bits();
    }
    w[16..20].copy_from_slice(&[oi.start, oi.end - 1, oj.start, oj.end - 1]);
    w[20] = f32_down(outer_box.min[2]).to_bits();
    w[21] = f32_up(outer_box.max[2]).to_bits();
    w[22] = start.lvl as u32;
    // A negative radius empties every inner segment: no inner box.
    let radius = if inner_ok { f32_up(inner.iter().map(|h| h * h).sum::<f64>().sqrt()) } else { -1.0 };
    w[23] = radius.to_bits();
    w[27..31].copy_from_slice(&[*start.cols.start(), *start.cols.end(), *start.rows.start(), *start.rows.end()]);
    if b.is_upright() {
        w[31] = UPRIGHT;
    }
    *out = w;
    Prepared::Sent
}

/// The nearest `f32` at or above `x`.
fn f32_up(x: f64) -> f32 {
    let y = x as f32;
    if (y as f64) < x { y.next_up() } else { y }
}

/// The nearest `f32` at or below `x`.
fn f32_down(x: f64) -> f32 {
    let y = x as f32;
    if (y as f64) > x { y.next_down() } else { y }
}
