//! The GPU twin of the depth-map assembly (wgpu compute).
//!
//! The thesis' passes (ch. 3), all on the device, slab after slab of grid
//! rows:
//!
//! 1. *count*: every point adds one to each cell its square touches (the cells
//!    of `mdm::point_span`), every triangle raw interval to its cell (atomics);
//! 2. *allocate*: an exclusive prefix sum of the counts gives each cell its
//!    start (a workgroup scan per 256 cells; the block sums scanned the same
//!    way and added back);
//! 3. *fill*: every raw interval's sort key `[object, part, key(bottom),
//!    key(top)]` goes to its cell's next free slot;
//! 4. *sort and merge*: a cell's keys sorted, merged as `mdm::merge_sorted`
//!    merges them, sorted by (bottom, top, object), cut to one in
//!    single-level mode, counted, and the cell's top written. A cell of up to
//!    256 keys takes one invocation (insertion sort when short, heapsort
//!    otherwise); a more crowded one (walls, poles, dense scans) takes a
//!    workgroup, which sorts with a bitonic network and merges with one
//!    invocation (a workgroup of 64 per cell of 17 to 512 keys, sorting in
//!    workgroup memory, was tried on an H200 and was slower: the merge is
//!    serial, and one invocation per cell runs 32 cells' merges at once);
//! 5. a prefix sum of the merged counts, and each cell's intervals copied to
//!    their place in the slab's part of the map.
//!
//! The fill order depends on thread timing, a cell's sorted keys do not (equal
//! keys are equal raw intervals), and the arithmetic is the CPU's: the same
//! `f32` operations for a point's cells and heights, comparisons in the
//! integer key order where the CPU uses it, and the merge's `bottom <= top +
//! gap` as the same `f32` sum. So the map is the CPU's bit for bit (the tests
//! compare them); the one way they could differ is a height within 1.2e-38 m
//! of zero that is not zero (a subnormal number, which a GPU may flush to
//! zero in arithmetic), which no survey or plant model holds. Triangles are
//! clipped to cells on the CPU (in `f64`, which WGSL lacks; a few hundred
//! thousand triangles against tens of millions of points), and their raw
//! intervals go up and through the same passes.
//!
//! Mesa's lavapipe (llvmpipe) silently leaves every loop of an invocation once
//! it has run 65535 iterations in all, which would give a wrong map for a
//! crowded cell. A one-invocation probe finds such a cap when the device
//! opens, and a slab whose most crowded cell could need more is refused with
//! an error instead; GPUs run loops to their end.
//!
//! Buffers stay under the device's storage-binding limit: points and triangle
//! raws go up in chunks, and a slab has as many rows as its raw intervals'
//! keys fit one buffer (a slab that turns out too full is cut and counted
//! again).
//!
//! The box queries' and clearances' twin, [`Gpu::upload_map`],
//! [`Gpu::hits_where`] and [`Gpu::clearances_where`], is in `gpu/screen.rs`;
//! the dilation's, [`Gpu::window_max`], in `gpu/dilate.rs`.

use crate::mdm::{GridSpec, Interval, Mode, PointSource, Raw, local_point};
use wgpu::util::DeviceExt;

mod dilate;
mod screen;
pub use screen::{GpuMap, MAX_COORD_M, ScreenCounts};

/// The passes, in WGSL, after what they share with the dilation's shader
/// (`common.wgsl`); `{LARGE}` is replaced by [`LARGE`] when compiled.
const SHADER: &str = concat!(include_str!("common.wgsl"), include_str!("assemble.wgsl"));

const GROUP: u32 = 256;
const MERGE_GROUP: u32 = 64;
/// Cells with more raw keys than this are sorted by a workgroup each, the
/// others by one invocation each (the shader's `LARGE`).
const LARGE: u64 = 256;
/// Iterations of the loop probe: more than any pass needs on a device that
/// does not cut loops short.
const PROBE_LOOPS: u32 = 1 << 20;
const MAX_DIM: u32 = 65_535;

/// An open GPU with the assembly pipelines.
pub struct Gpu {
    dev: liftplan_core::gpu::Device,
    count_points: wgpu::ComputePipeline,
    count_mesh: wgpu::ComputePipeline,
    fill_points: wgpu::ComputePipeline,
    fill_mesh: wgpu::ComputePipeline,
    scan_blocks: wgpu::ComputePipeline,
    add_blocks: wgpu::ComputePipeline,
    merge_cells: wgpu::ComputePipeline,
    compact: wgpu::ComputePipeline,
    find_large: wgpu::ComputePipeline,
    large_cells: wgpu::ComputePipeline,
    /// The box-query screen (`screen.rs`).
    screen_boxes: wgpu::ComputePipeline,
    clear_boxes: wgpu::ComputePipeline,
    /// The dilation's twin (`gpu/dilate.rs`).
    window_max: wgpu::ComputePipeline,
    /// Loop iterations one invocation may run, where the device cuts loops
    /// short (lavapipe: 65535); `None` where the probe ran to its end.
    loop_cap: Option<u32>,
    /// Largest buffer the passes use (bytes): the device's storage-binding
    /// limit, or less when asked ([`Gpu::set_buffer_limit`]).
    buffer_limit: u64,
}

/// Opens a device ([`liftplan_core::gpu::open_device`]) and builds the pipelines.
pub fn open(allow_software: bool) -> Result<Gpu, String> {
    Gpu::new(liftplan_core::gpu::open_device(allow_software)?)
}

/// [`open`] on each backend that has an adapter
/// ([`liftplan_core::gpu::open_each_backend`]), for the twin tests.
pub fn open_each_backend(allow_software: bool) -> Vec<(wgpu::Backend, Result<Gpu, String>)> {
    liftplan_core::gpu::open_each_backend(allow_software)
        .into_iter()
        .map(|(b, dev)| (b, dev.and_then(Gpu::new)))
        .collect()
}

/// The device's side of a depth map, cell by cell in row-major order: what
/// [`crate::mdm::Mdm::from_cells`] takes.
pub struct Cells {
    pub counts: Vec<u32>,
    pub intervals: Vec<Interval>,
    pub tops: Vec<f32>,
    /// Raw intervals before merging.
    pub raws: usize,
    /// Slabs of rows the grid was cut into.
    pub slabs: usize,
    pub timings: GpuTimings,
}

/// Where the GPU assembly's time went (ms, wall clock on the host).
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct GpuTimings {
    /// Converting and uploading points and triangle raws.
    pub upload_ms: f64,
    /// The passes on the device, each slab up to its last count read back:
    /// the sum of the four below (each waits for the device at its end), so
    /// the host's few microseconds between them are not counted.
    pub passes_ms: f64,
    /// Pass 1 and 2: counting raw intervals per cell, the prefix sum and the
    /// list of crowded cells.
    pub count_ms: f64,
    /// Pass 3: every raw interval's key to its cell's slot.
    pub fill_ms: f64,
    /// Pass 4 and the merged counts' prefix sum.
    pub sort_ms: f64,
    /// Pass 5: the merged intervals into the map's layout.
    pub compact_ms: f64,
    /// Reading the map back (counts, tops, intervals).
    pub read_back_ms: f64,
}

/// Uniform parameters of one dispatch (the shader's `Params`).
#[derive(Clone, Copy, Default)]
struct Params {
    n: u32,
    nx: u32,
    row0: u32,
    rows: u32,
    inv_cell: f32,
    radius: f32,
    gap: f32,
    single: bool,
}

impl Gpu {
    /// Builds the pipelines on an open device and probes how long its shader
    /// loops may run.
    pub fn new(dev: liftplan_core::gpu::Device) -> Result<Gpu, String> {
        let module = dev.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("depthmap assembly"),
            source: wgpu::ShaderSource::Wgsl(SHADER.replace("{LARGE}", &LARGE.to_string()).into()),
        });
        let screen = dev.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("box query screen"),
            source: wgpu::ShaderSource::Wgsl(screen::SHADER.into()),
        });
        let dilation = dev.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("dilation"),
            source: wgpu::ShaderSource::Wgsl(dilate::SHADER.into()),
        });
        let pipeline_with = |module: &wgpu::ShaderModule, entry: &str, zero_workgroup_memory: bool| {
            dev.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: None,
                module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions {
                    zero_initialize_workgroup_memory: zero_workgroup_memory,
                    ..Default::default()
                },
                cache: None,
            })
        };
        let pipeline_in = |module: &wgpu::ShaderModule, entry: &str| pipeline_with(module, entry, true);
        // The assembly's workgroups write each workgroup variable before they
        // read it (the scan's partial sums, the first lane's cell, counts and
        // list places): zeroing them first, in each of hundreds of thousands
        // of workgroups, is time for nothing.
        let pipeline = |entry: &str| pipeline_with(&module, entry, false);
        let probe = pipeline("probe_loops");
        let mut gpu = Gpu {
            count_points: pipeline("count_points"),
            count_mesh: pipeline("count_mesh"),
            fill_points: pipeline("fill_points"),
            fill_mesh: pipeline("fill_mesh"),
            scan_blocks: pipeline("scan_blocks"),
            add_blocks: pipeline("add_blocks"),
            merge_cells: pipeline("merge_cells"),
            compact: pipeline("compact"),
            find_large: pipeline("find_large"),
            large_cells: pipeline("large_cells"),
            screen_boxes: pipeline_in(&screen, "screen_boxes"),
            clear_boxes: pipeline_in(&screen, "clear_boxes"),
            window_max: pipeline_in(&dilation, "window_max"),
            buffer_limit: device_buffer_limit(&dev.device),
            loop_cap: None,
            dev,
        };
        gpu.loop_cap = liftplan_core::gpu::catching_errors(&gpu.dev, || gpu.probe_loops(&probe))?;
        Ok(gpu)
    }

    /// Runs one invocation of a loop of [`PROBE_LOOPS`] iterations and
    /// returns how many it ran, if fewer.
    fn probe_loops(&self, probe: &wgpu::ComputePipeline) -> Result<Option<u32>, String> {
        let out = self.storage("probe", 8);
        let p = self.uniform(Params { n: PROBE_LOOPS, ..Params::default() });
        let mut enc = self.dev.device.create_command_encoder(&Default::default());
        self.pass(&mut enc, probe, &[(0, &p), (5, &out)], 1, 1);
        self.submit(enc);
        let ran = self.read_words(&out, 0, 1)?[0];
        Ok((ran < PROBE_LOOPS).then_some(ran))
    }

    /// Keeps every buffer under `bytes` (at least 4 KiB) where the device
    /// allows more: more chunks and slabs, the same map. The tests use it to
    /// run the slab and chunk logic on small inputs.
    pub fn set_buffer_limit(&mut self, bytes: u64) {
        self.buffer_limit = device_buffer_limit(&self.dev.device).min(bytes.max(4096));
    }

    /// Loop iterations one shader invocation may run on this device, where
    /// it cuts loops short (Mesa's lavapipe: 65535); `None` elsewhere.
    pub fn loop_cap(&self) -> Option<u32> {
        self.loop_cap
    }

    /// Adapter name and backend, for reports.
    pub fn name(&self) -> &str {
        &self.dev.name
    }

    fn upload(&self, label: &str, bytes: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
        self.dev.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage,
        })
    }

    fn uniform(&self, p: Params) -> wgpu::Buffer {
        let words =
            [p.n, p.nx, p.row0, p.rows, p.inv_cell.to_bits(), p.radius.to_bits(), p.gap.to_bits(), p.single as u32];
        self.upload("params", &words_to_bytes(&words), wgpu::BufferUsages::UNIFORM)
    }

    /// A zeroed storage buffer (wgpu zeroes new buffers) of at least 16 bytes.
    fn storage(&self, label: &str, bytes: u64) -> wgpu::Buffer {
        self.dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: bytes.max(16).next_multiple_of(4),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Records `pipeline` over `n` items, `per_group` per workgroup.
    fn pass(
        &self,
        enc: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::ComputePipeline,
        buffers: &[(u32, &wgpu::Buffer)],
        n: u32,
        per_group: u32,
    ) {
        if n == 0 {
            return;
        }
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .map(|(binding, b)| wgpu::BindGroupEntry { binding: *binding, resource: b.as_entire_binding() })
            .collect();
        let bind = self.dev.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let groups = n.div_ceil(per_group);
        let (x, y) = if groups > MAX_DIM { (MAX_DIM, groups.div_ceil(MAX_DIM)) } else { (groups, 1) };
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(x, y, 1);
    }

    /// Records an exclusive, saturating prefix sum of `data[..n]` in place.
    fn scan(&self, enc: &mut wgpu::CommandEncoder, data: &wgpu::Buffer, n: u32, base: Params) {
        let blocks = n.div_ceil(GROUP);
        let sums = self.storage("scan sums", 4 * blocks as u64);
        let p = self.uniform(Params { n, ..base });
        // One workgroup per block: `pass` counts items, so blocks * GROUP.
        self.pass(enc, &self.scan_blocks, &[(0, &p), (5, data), (6, &sums)], blocks * GROUP, GROUP);
        if blocks > 1 {
            self.scan(enc, &sums, blocks, base);
            self.pass(enc, &self.add_blocks, &[(0, &p), (5, data), (6, &sums)], n, GROUP);
        }
    }

    fn submit(&self, enc: wgpu::CommandEncoder) {
        self.dev.queue.submit([enc.finish()]);
    }

    /// Waits until the device has done what was submitted.
    fn wait(&self) -> Result<(), String> {
        self.dev.device.poll(wgpu::PollType::wait_indefinitely()).map(|_| ()).map_err(|e| format!("GPU poll: {e}"))
    }

    /// `words` 32-bit words of `src` from word `at`.
    fn read_words(&self, src: &wgpu::Buffer, at: u64, words: u64) -> Result<Vec<u32>, String> {
        liftplan_core::gpu::read_back_with(&self.dev, src, 4 * at, 4 * words, words_from_bytes)
    }

    /// Passes 1 to 5 on the device for `points` and the triangles' raw
    /// intervals `mesh` (from `mdm::mesh_raws`): every cell's merged
    /// intervals, count and top, as `mdm::assemble_sources` makes them.
    ///
    /// Errors the device reports (out of memory, a buffer it cannot make) come
    /// back as `Err`, as do the refusals above; nothing panics.
    pub fn assemble(
        &self,
        points: Option<&PointSource>,
        mesh: &[Raw],
        spec: &GridSpec,
        mode: Mode,
        gap: f32,
    ) -> Result<Cells, String> {
        if 4 * (spec.nx as u64 + 1) > self.buffer_limit {
            return Err(format!(
                "a grid row of {} cells is more than one GPU buffer holds ({} bytes): use a larger cell_m, or the \
                 CPU ([gpu] use = \"never\")",
                spec.nx, self.buffer_limit
            ));
        }
        let base = Params {
            nx: spec.nx,
            inv_cell: (1.0 / spec.cell) as f32,
            radius: points.map_or(0.0, |p| p.radius),
            gap,
            single: mode == Mode::Single,
            ..Params::default()
        };
        liftplan_core::gpu::catching_errors(&self.dev, || {
            let t0 = std::time::Instant::now();
            let sources = self.upload_sources(points, mesh, spec)?;
            self.assemble_slabs(&sources, spec, base, t0.elapsed().as_secs_f64() * 1e3)
        })
    }

    /// Every slab of the grid, with the sources already on the device.
    fn assemble_slabs(
        &self,
        sources: &Sources,
        spec: &GridSpec,
        base: Params,
        upload_ms: f64,
    ) -> Result<Cells, String> {
        let ms = |t: std::time::Instant| t.elapsed().as_secs_f64() * 1e3;
        let mut cells = Cells {
            counts: Vec::with_capacity(spec.cells()),
            intervals: Vec::new(),
            tops: Vec::with_capacity(spec.cells()),
            raws: 0,
            slabs: 0,
            timings: GpuTimings { upload_ms, ..GpuTimings::default() },
        };
        // Rows per slab: as many as the per-cell buffers (one word a cell,
        // plus one) allow, cut when the keys do not fit.
        let max_rows = (((self.buffer_limit / 4).saturating_sub(1)) / spec.nx as u64).clamp(1, spec.ny as u64) as u32;
        let max_keys = self.buffer_limit / 16;
        let mut rows = max_rows;
        let mut row0 = 0u32;
        while row0 < spec.ny {
            rows = rows.min(spec.ny - row0);
            let slab = Params { row0, rows, ..base };
            let t_count = std::time::Instant::now();
            let (lists, counted) = self.count_slab(sources, slab)?;
            let total = counted.total;
            cells.timings.count_ms += ms(t_count);
            if let Some(cap) = self.loop_cap {
                let need = self.loop_need(counted.most, base.radius as f64 * base.inv_cell as f64);
                if need > cap as u64 / 2 {
                    return Err(format!(
                        "{} ends a shader's loops after {cap} iterations (Mesa's lavapipe does), and the most crowded \
                         cell of grid rows {row0}..{} ({} raw intervals) needs up to {need}: use the CPU ([gpu] use = \
                         \"never\"), or a GPU",
                        self.dev.name,
                        row0 + rows,
                        counted.most
                    ));
                }
            }
            if total > max_keys {
                if rows == 1 {
                    return Err(format!(
                        "grid row {row0} has {total} raw intervals or more, over what one GPU buffer holds \
                         ({max_keys}): use a larger cell_m, or the CPU ([gpu] use = \"never\")"
                    ));
                }
                // Cut to what should fit, with a margin for uneven rows.
                rows = (((rows as u64 * max_keys / total) as u32).clamp(1, rows - 1) * 7 / 8).max(1);
                continue;
            }
            self.merge_slab(sources, slab, &lists, counted, &mut cells)?;
            row0 += rows;
        }
        let t = &mut cells.timings;
        t.passes_ms = t.count_ms + t.fill_ms + t.sort_ms + t.compact_ms;
        Ok(cells)
    }

    /// Points as `[x, y, z, object]` (grid-local `f32`, the CPU's conversion)
    /// and triangle raws as `[cell, bottom, top, object, part]`, in chunks
    /// that fit a binding.
    fn upload_sources(&self, points: Option<&PointSource>, mesh: &[Raw], spec: &GridSpec) -> Result<Sources, String> {
        let mut sources = Sources::default();
        if let Some(p) = points {
            let per = (self.buffer_limit / 16).min(1 << 24) as usize;
            for (ci, chunk) in p.xyz.chunks(per).enumerate() {
                let buf = self.upload_items("points", chunk.len(), 4, |k| {
                    let q = local_point(&chunk[k], spec);
                    [q[0].to_bits(), q[1].to_bits(), q[2].to_bits(), p.obj(ci * per + k), 0]
                })?;
                sources.points.push((buf, chunk.len() as u32));
            }
        }
        for chunk in mesh.chunks((self.buffer_limit / 20).min(1 << 24) as usize) {
            let buf = self.upload_items("mesh raws", chunk.len(), 5, |k| {
                let r = &chunk[k];
                [r.cell, r.zlo.to_bits(), r.zhi.to_bits(), r.obj, r.part]
            })?;
            sources.mesh.push((buf, chunk.len() as u32));
        }
        Ok(sources)
    }

    /// A storage buffer of `n` items of `words` 32-bit words each (the first
    /// `words` of what `item` gives), packed in parallel: on one thread,
    /// packing 21 M points took most of a second on this project's 2-core
    /// machine.
    fn upload_items(
        &self,
        label: &str,
        n: usize,
        words: usize,
        item: impl Fn(usize) -> [u32; 5] + Sync,
    ) -> Result<wgpu::Buffer, String> {
        use rayon::prelude::*;
        const BLOCK: usize = 1 << 12;
        let stride = 4 * words;
        let bytes = stride * n;
        let buf = self.dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: bytes.max(16) as u64,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: true,
        });
        // Packed by the threads a chunk of about 16 MB at a time into one
        // buffer, reused, and copied into the mapped memory, which is written
        // only (it may be write-combining): no buffer of hundreds of megabytes
        // on the host, whose fresh pages cost more than the packing.
        let mut mapped = buf.slice(..).get_mapped_range_mut().map_err(|e| format!("GPU upload of {label}: {e:?}"))?;
        let per_chunk = 64 * BLOCK;
        let mut packed = vec![0u8; stride * per_chunk.min(n)];
        for first in (0..n).step_by(per_chunk) {
            let items = per_chunk.min(n - first);
            let chunk = &mut packed[..stride * items];
            chunk.par_chunks_mut(stride * BLOCK).enumerate().for_each(|(b, block)| {
                for (k, out) in block.chunks_exact_mut(stride).enumerate() {
                    for (o, w) in out.chunks_exact_mut(4).zip(&item(first + b * BLOCK + k)[..words]) {
                        o.copy_from_slice(&w.to_le_bytes());
                    }
                }
            });
            mapped.slice(stride * first..stride * (first + items)).copy_from_slice(chunk);
        }
        drop(mapped);
        buf.unmap();
        Ok(buf)
    }

    /// Passes 1 and 2 for one slab: each cell's start in the slab's keys
    /// (one more word, the total, at the end), the list of large cells, and
    /// [`SlabCounts`].
    fn count_slab(&self, src: &Sources, slab: Params) -> Result<(SlabLists, SlabCounts), String> {
        let cells = slab.rows * slab.nx;
        let starts = self.storage("starts", 4 * (cells as u64 + 1));
        let large = self.storage("large cells", 4 * cells as u64);
        let stats = self.storage("slab counts", 12);
        let mut enc = self.dev.device.create_command_encoder(&Default::default());
        for (buf, k) in &src.points {
            let p = self.uniform(Params { n: *k, ..slab });
            self.pass(&mut enc, &self.count_points, &[(0, &p), (1, buf), (3, &starts)], *k, GROUP);
        }
        for (buf, k) in &src.mesh {
            let p = self.uniform(Params { n: *k, ..slab });
            self.pass(&mut enc, &self.count_mesh, &[(0, &p), (2, buf), (3, &starts)], *k, GROUP);
        }
        self.scan(&mut enc, &starts, cells + 1, slab);
        let p = self.uniform(Params { n: cells, ..slab });
        self.pass(&mut enc, &self.find_large, &[(0, &p), (3, &stats), (7, &starts), (11, &large)], cells, GROUP);
        enc.copy_buffer_to_buffer(&starts, 4 * cells as u64, &stats, 8, 4);
        self.submit(enc);
        let w = self.read_words(&stats, 0, 3)?;
        Ok((SlabLists { starts, large }, SlabCounts { large: w[0], most: w[1] as u64, total: w[2] as u64 }))
    }

    /// The most loop iterations one invocation of a pass runs for a slab
    /// whose most crowded cell has `most` raw keys (an upper bound).
    fn loop_need(&self, most: u64, radius_cells: f64) -> u64 {
        let lg = |n: u64| 64 - n.max(1).leading_zeros() as u64;
        // One invocation's heapsort, merge, sort and finish of up to LARGE keys.
        let small = 2 * (LARGE / 2 + LARGE) * lg(LARGE) + 3 * LARGE;
        // A workgroup's bitonic sorts (each lane), and the first lane's merge
        // and finish; the compaction copies up to `most` intervals.
        let p = most.max(1).next_power_of_two();
        let stages = lg(p) * (lg(p) + 1) / 2;
        let large = 2 * stages * ((p / 2).div_ceil(GROUP as u64) + 1) + 3 * most + 2 * lg(p);
        let span = (2.0 * radius_cells).ceil() as u64 + 2;
        small.max(large).max(span * span)
    }

    /// Passes 3 to 5 for one slab whose cells start at `lists.starts` in
    /// `counted.total` keys; its cells appended to `out`.
    fn merge_slab(
        &self,
        src: &Sources,
        slab: Params,
        lists: &SlabLists,
        counted: SlabCounts,
        out: &mut Cells,
    ) -> Result<(), String> {
        let total = counted.total;
        let starts = &lists.starts;
        let t0 = std::time::Instant::now();
        let ms = |t: std::time::Instant| t.elapsed().as_secs_f64() * 1e3;
        let cells = slab.rows * slab.nx;
        let keys = self.storage("keys", 16 * total);
        let cursor = self.storage("cursor", 4 * (cells as u64 + 1));
        let merged = self.storage("merged counts", 4 * (cells as u64 + 1));
        let tops = self.storage("tops", 4 * cells as u64);
        let mut enc = self.dev.device.create_command_encoder(&Default::default());
        enc.copy_buffer_to_buffer(starts, 0, &cursor, 0, 4 * (cells as u64 + 1));
        for (buf, k) in &src.points {
            let p = self.uniform(Params { n: *k, ..slab });
            self.pass(&mut enc, &self.fill_points, &[(0, &p), (1, buf), (3, &cursor), (4, &keys)], *k, GROUP);
        }
        for (buf, k) in &src.mesh {
            let p = self.uniform(Params { n: *k, ..slab });
            self.pass(&mut enc, &self.fill_mesh, &[(0, &p), (2, buf), (3, &cursor), (4, &keys)], *k, GROUP);
        }
        // Waits between the passes, for their times: about 0.2 ms each on the
        // H200 measured (reports/depthmap.md), against passes of 1 to 100 ms.
        self.submit(enc);
        self.wait()?;
        out.timings.fill_ms += ms(t0);
        let t_sort = std::time::Instant::now();
        let mut enc = self.dev.device.create_command_encoder(&Default::default());
        let p = self.uniform(Params { n: cells, ..slab });
        let binds = [(0, &p), (4, &keys), (7, starts), (8, &merged), (9, &tops)];
        self.pass(&mut enc, &self.merge_cells, &binds, cells, MERGE_GROUP);
        // One workgroup per large cell: `pass` counts items.
        let pl = self.uniform(Params { n: counted.large, ..slab });
        let binds = [(0, &pl), (4, &keys), (7, starts), (8, &merged), (9, &tops), (11, &lists.large)];
        self.pass(&mut enc, &self.large_cells, &binds, counted.large * GROUP, GROUP);
        self.scan(&mut enc, &merged, cells + 1, slab);
        self.submit(enc);
        let kept = self.read_words(&merged, cells as u64, 1)?[0] as u64;
        out.timings.sort_ms += ms(t_sort);
        let t_compact = std::time::Instant::now();
        let intervals = self.storage("intervals", 12 * kept);
        let mut enc = self.dev.device.create_command_encoder(&Default::default());
        let binds = [(0, &p), (4, &keys), (7, starts), (8, &merged), (10, &intervals)];
        self.pass(&mut enc, &self.compact, &binds, cells, GROUP);
        self.submit(enc);
        self.wait()?;
        out.timings.compact_ms += ms(t_compact);
        let t_read = std::time::Instant::now();
        let ends = self.read_words(&merged, 0, cells as u64 + 1)?;
        // What comes back must be a map: a device that answers otherwise is
        // refused rather than trusted.
        if ends[0] != 0 || ends.windows(2).any(|w| w[1] < w[0]) || ends[cells as usize] as u64 != kept {
            return Err(format!(
                "GPU ({}) returned inconsistent interval counts for grid rows from {}",
                self.dev.name, slab.row0
            ));
        }
        out.counts.extend(ends.windows(2).map(|w| w[1] - w[0]));
        out.tops.extend(self.read_words(&tops, 0, cells as u64)?.into_iter().map(f32::from_bits));
        // Decoded where mapped: one copy of what may be hundreds of megabytes.
        out.intervals.reserve(kept as usize);
        liftplan_core::gpu::read_back_with(&self.dev, &intervals, 0, 12 * kept, |bytes| {
            let word = |b: &[u8]| u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            out.intervals.extend(bytes.chunks_exact(12).map(|b| Interval {
                zlo: f32::from_bits(word(&b[0..4])),
                zhi: f32::from_bits(word(&b[4..8])),
                obj: word(&b[8..12]),
            }));
        })?;
        out.timings.read_back_ms += ms(t_read);
        out.raws += total as usize;
        out.slabs += 1;
        Ok(())
    }
}

/// What the count of one slab found.
#[derive(Clone, Copy)]
struct SlabCounts {
    /// Cells of more than `LARGE` raw keys, sorted by a workgroup each.
    large: u32,
    /// Raw keys of the most crowded cell.
    most: u64,
    /// Raw keys in all (saturated at `u32::MAX`).
    total: u64,
}

/// One slab's cell starts and its list of large cells, from the count.
struct SlabLists {
    starts: wgpu::Buffer,
    large: wgpu::Buffer,
}

/// The inputs on the device, each chunk with its item count.
#[derive(Default)]
struct Sources {
    points: Vec<(wgpu::Buffer, u32)>,
    mesh: Vec<(wgpu::Buffer, u32)>,
}

/// The largest buffer a pass may bind on `device` (bytes), and at most 4 GiB,
/// so that every index a shader computes (in `u32` words) fits.
fn device_buffer_limit(device: &wgpu::Device) -> u64 {
    let limits = device.limits();
    limits.max_storage_buffer_binding_size.min(limits.max_buffer_size).min(u32::MAX as u64)
}

/// Words the device wrote (little-endian), as read back.
fn words_from_bytes(bytes: &[u8]) -> Vec<u32> {
    bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
}

/// The words as the device reads them (little-endian): on a little-endian
/// host, the same memory, not a copy (the boxes of a C-space build are 15 MB).
fn words_to_bytes(words: &[u32]) -> std::borrow::Cow<'_, [u8]> {
    if cfg!(target_endian = "little") {
        std::borrow::Cow::Borrowed(bytemuck::cast_slice(words))
    } else {
        std::borrow::Cow::Owned(words.iter().flat_map(|w| w.to_le_bytes()).collect())
    }
}
