//! The GPU twin of the point pass (wgpu compute).
//!
//! Points dominate a site (tens of millions against a few hundred thousand plant
//! triangles), so the point pass is what runs on the GPU: a count pass writes
//! how many cells each point touches, the host turns the counts into offsets
//! (an exclusive prefix sum), and a fill pass writes every point's raw intervals
//! at its offset. The arithmetic is the CPU pass's, in the same f32 operations
//! and the same cell order, so the raw intervals are identical and the map the
//! shared assemble step builds from them is identical too (the tests compare
//! them). Triangle intervals and assembly stay on the CPU.
//!
//! Points go up in chunks small enough for the default storage-binding limit.

use crate::mdm::{GridSpec, PointSource, Raw, local_point};
use wgpu::util::DeviceExt;

const SHADER: &str = r#"
struct Params { n: u32, nx: u32, ny: u32, inv_cell: f32, radius: f32, p0: u32, p1: u32, p2: u32 }
@group(0) @binding(0) var<uniform> P: Params;
@group(0) @binding(1) var<storage, read> pts: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> counts: array<u32>;
@group(0) @binding(3) var<storage, read> offsets: array<u32>;
@group(0) @binding(4) var<storage, read_write> raws: array<u32>;

fn cells(q: vec4<f32>) -> vec4<i32> {
    let i0 = max(i32(floor((q.x - P.radius) * P.inv_cell)), 0);
    let i1 = min(i32(floor((q.x + P.radius) * P.inv_cell)), i32(P.nx) - 1);
    let j0 = max(i32(floor((q.y - P.radius) * P.inv_cell)), 0);
    let j1 = min(i32(floor((q.y + P.radius) * P.inv_cell)), i32(P.ny) - 1);
    return vec4<i32>(i0, i1, j0, j1);
}

@compute @workgroup_size(256)
fn count(@builtin(global_invocation_id) g: vec3<u32>) {
    let p = g.x + g.y * 65535u * 256u;
    if (p >= P.n) { return; }
    let r = cells(pts[p]);
    var c = 0u;
    if (r.y >= r.x && r.w >= r.z) { c = u32(r.y - r.x + 1) * u32(r.w - r.z + 1); }
    counts[p] = c;
}

@compute @workgroup_size(256)
fn fill(@builtin(global_invocation_id) g: vec3<u32>) {
    let p = g.x + g.y * 65535u * 256u;
    if (p >= P.n) { return; }
    let q = pts[p];
    let r = cells(q);
    var o = offsets[p];
    let zlo = bitcast<u32>(q.z - P.radius);
    let zhi = bitcast<u32>(q.z + P.radius);
    for (var j = r.z; j <= r.w; j = j + 1) {
        for (var i = r.x; i <= r.y; i = i + 1) {
            let b = o * 5u;
            raws[b] = u32(j) * P.nx + u32(i);
            raws[b + 1u] = zlo;
            raws[b + 2u] = zhi;
            raws[b + 3u] = bitcast<u32>(q.w);
            raws[b + 4u] = 0u;
            o = o + 1u;
        }
    }
}
"#;

/// An open GPU with the point-pass pipelines.
pub struct Gpu {
    dev: liftplan_core::gpu::Device,
    count: wgpu::ComputePipeline,
    fill: wgpu::ComputePipeline,
}

/// Opens a device ([`liftplan_core::gpu::open_device`]) and builds the pipelines.
pub fn open(allow_software: bool) -> Result<Gpu, String> {
    Ok(Gpu::new(liftplan_core::gpu::open_device(allow_software)?))
}

impl Gpu {
    /// Builds the point-pass pipelines on an open device.
    pub fn new(dev: liftplan_core::gpu::Device) -> Gpu {
        let module = dev.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("depthmap points"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let pipeline = |entry: &str| {
            dev.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: None,
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let count = pipeline("count");
        let fill = pipeline("fill");
        Gpu { dev, count, fill }
    }

    /// Adapter name and backend, for reports.
    pub fn name(&self) -> &str {
        &self.dev.name
    }

    fn read_back(&self, src: &wgpu::Buffer, bytes: u64) -> Result<Vec<u32>, String> {
        let data = liftplan_core::gpu::read_back(&self.dev, src, bytes)?;
        Ok(data.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect())
    }

    /// A buffer holding `words`.
    fn upload(&self, label: &str, words: &[u32], usage: wgpu::BufferUsages) -> wgpu::Buffer {
        let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        self.dev.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: &bytes,
            usage,
        })
    }

    /// A buffer a shader writes and the host reads back.
    fn output(&self, label: &str, bytes: u64) -> wgpu::Buffer {
        self.dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        })
    }

    /// Binds buffers to a pipeline's group 0 by binding number.
    fn bind(&self, pipeline: &wgpu::ComputePipeline, buffers: &[(u32, &wgpu::Buffer)]) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .map(|(binding, b)| wgpu::BindGroupEntry { binding: *binding, resource: b.as_entire_binding() })
            .collect();
        self.dev.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        })
    }

    fn dispatch(&self, pipeline: &wgpu::ComputePipeline, bind: &wgpu::BindGroup, n: u32) {
        let groups = n.div_ceil(256);
        let (x, y) = if groups > 65_535 { (65_535, groups.div_ceil(65_535)) } else { (groups.max(1), 1) };
        let mut enc = self.dev.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(x, y, 1);
        }
        self.dev.queue.submit([enc.finish()]);
    }

    /// The point pass on the GPU: every point's raw interval in every cell its
    /// square touches, as the CPU assembly rasterises points
    /// (`mdm::point_span`, `mdm::point_raws`), in point order.
    pub fn point_raws(&self, p: &PointSource, spec: &GridSpec, out: &mut Vec<Raw>) -> Result<(), String> {
        let radius = p.radius;
        let inv = (1.0 / spec.cell) as f32;
        // Cells one point can touch, to size chunks under the binding limit.
        let span = ((2.0 * radius * inv).ceil() as u64 + 1).pow(2);
        let limit =
            self.dev.device.limits().max_storage_buffer_binding_size.min(self.dev.device.limits().max_buffer_size);
        let chunk = ((limit / (20 * span)) as usize).clamp(1, 1 << 22);
        for (ci, pts) in p.xyz.chunks(chunk).enumerate() {
            let n = pts.len() as u32;
            let mut packed: Vec<u32> = Vec::with_capacity(pts.len() * 4);
            for (k, site) in pts.iter().enumerate() {
                let q = local_point(site, spec);
                packed.extend_from_slice(&[q[0].to_bits(), q[1].to_bits(), q[2].to_bits(), p.obj(ci * chunk + k)]);
            }
            let params: [u32; 8] = [n, spec.nx, spec.ny, inv.to_bits(), radius.to_bits(), 0, 0, 0];
            let ubuf = self.upload("params", &params, wgpu::BufferUsages::UNIFORM);
            let pbuf = self.upload("points", &packed, wgpu::BufferUsages::STORAGE);
            let cbuf = self.output("counts", 4 * n as u64);
            let bind = self.bind(&self.count, &[(0, &ubuf), (1, &pbuf), (2, &cbuf)]);
            self.dispatch(&self.count, &bind, n);
            let counts = self.read_back(&cbuf, 4 * n as u64)?;
            let mut offsets = Vec::with_capacity(counts.len());
            let mut total: u64 = 0;
            for c in &counts {
                offsets.push(total as u32);
                total += *c as u64;
            }
            if total == 0 {
                continue;
            }
            let obuf = self.upload("offsets", &offsets, wgpu::BufferUsages::STORAGE);
            let rbuf = self.output("raws", 20 * total);
            let bind = self.bind(&self.fill, &[(0, &ubuf), (1, &pbuf), (3, &obuf), (4, &rbuf)]);
            self.dispatch(&self.fill, &bind, n);
            let words = self.read_back(&rbuf, 20 * total)?;
            out.reserve(total as usize);
            for w in words.chunks_exact(5) {
                out.push(Raw {
                    cell: w[0],
                    zlo: f32::from_bits(w[1]),
                    zhi: f32::from_bits(w[2]),
                    obj: w[3],
                    part: w[4],
                });
            }
        }
        Ok(())
    }
}
