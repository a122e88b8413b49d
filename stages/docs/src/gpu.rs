//! The GPU twin of the CPU rasteriser (wgpu render pipelines).
//!
//! It draws the same [`Projected`] scene the CPU path draws: triangles shaded on
//! the host, square sprites, capsule-shaped polyline segments whose coverage and
//! depth the fragment shader computes with the CPU's formula, in the same order
//! (triangles, sprites, then segments in scene order; on-top segments without a
//! depth test). The sample image is read back and box-filtered by the same
//! [`downsample`], so pictures differ only where the two rasterisers' edge rules
//! disagree about a sample on a shared edge (the tests bound that).
//!
//! This module must not change what a picture shows: any new scene element goes
//! into [`Projected`] first and is drawn by both paths.

use crate::render::{Camera, Projected, Rgb, SKY, Scene, downsample, project};
use liftplan_core::image::Image;
use wgpu::util::DeviceExt;

const SHADER: &str = r#"
struct U { size: vec2<f32>, pad: vec2<f32> }
@group(0) @binding(0) var<uniform> u: U;

fn to_clip(p: vec3<f32>) -> vec4<f32> {
    return vec4<f32>(p.x / u.size.x * 2.0 - 1.0, 1.0 - p.y / u.size.y * 2.0, p.z * 0.5 + 0.5, 1.0);
}

struct Flat { @builtin(position) pos: vec4<f32>, @location(0) @interpolate(flat) color: vec4<f32> }

@vertex fn tri_vs(@location(0) p: vec3<f32>, @location(1) c: u32) -> Flat {
    return Flat(to_clip(p), unpack4x8unorm(c));
}

@fragment fn flat_fs(i: Flat) -> @location(0) vec4<f32> { return i.color; }

const CORNERS = array<vec2<f32>, 6>(
    vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0),
    vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, 1.0), vec2<f32>(-1.0, 1.0));

@vertex fn sprite_vs(@builtin(vertex_index) v: u32, @location(0) at: vec3<f32>, @location(1) half: f32,
                     @location(2) c: u32) -> Flat {
    let k = CORNERS[v];
    return Flat(to_clip(vec3<f32>(at.x + k.x * half, at.y + k.y * half, at.z)), unpack4x8unorm(c));
}

struct Seg {
    @builtin(position) pos: vec4<f32>,
    @location(0) @interpolate(flat) color: vec4<f32>,
    @location(1) @interpolate(flat) a: vec3<f32>,
    @location(2) @interpolate(flat) b: vec3<f32>,
    @location(3) @interpolate(flat) r: f32,
}

@vertex fn seg_vs(@builtin(vertex_index) v: u32, @location(0) a: vec3<f32>, @location(1) b: vec3<f32>,
                  @location(2) r: f32, @location(3) c: u32) -> Seg {
    let lo = floor(min(a.xy, b.xy) - vec2<f32>(r));
    let hi = ceil(max(a.xy, b.xy) + vec2<f32>(r));
    let k = CORNERS[v] * 0.5 + vec2<f32>(0.5);
    let xy = lo + k * (hi - lo);
    // Depth comes from the fragment shader; any value inside the clip range here.
    return Seg(to_clip(vec3<f32>(xy, 0.0)), unpack4x8unorm(c), a, b, r);
}

struct SegOut { @location(0) color: vec4<f32>, @builtin(frag_depth) depth: f32 }

@fragment fn seg_fs(i: Seg) -> SegOut {
    let p = i.pos.xy;
    let d = i.b.xy - i.a.xy;
    let len2 = max(d.x * d.x + d.y * d.y, 1e-12);
    let t = clamp(((p.x - i.a.x) * d.x + (p.y - i.a.y) * d.y) / len2, 0.0, 1.0);
    let q = i.a.xy + t * d;
    let e = p - q;
    if (e.x * e.x + e.y * e.y > i.r * i.r) { discard; }
    let z = i.a.z + t * (i.b.z - i.a.z) - 1e-4;
    if (z < -1.0 || z > 1.0) { discard; }
    return SegOut(i.color, z * 0.5 + 0.5);
}
"#;

const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// An open GPU with the picture pipelines.
pub struct GpuRenderer {
    dev: liftplan_core::gpu::Device,
    layout: wgpu::BindGroupLayout,
    triangles: wgpu::RenderPipeline,
    sprites: wgpu::RenderPipeline,
    segments: wgpu::RenderPipeline,
    segments_on_top: wgpu::RenderPipeline,
}

fn pack(c: Rgb) -> u32 {
    u32::from_le_bytes([c[0], c[1], c[2], 255])
}

fn f32s(v: &[f32]) -> impl Iterator<Item = u8> + '_ {
    v.iter().flat_map(|x| x.to_le_bytes())
}

/// Opens a device ([`liftplan_core::gpu::open_device`]) and builds the pipelines.
pub fn open(allow_software: bool) -> Result<GpuRenderer, String> {
    Ok(GpuRenderer::new(liftplan_core::gpu::open_device(allow_software)?))
}

/// [`open`] on each backend that has an adapter
/// ([`liftplan_core::gpu::open_each_backend`]), for the twin test: the
/// backends' shader compilers and rasterisers differ.
pub fn open_each_backend(allow_software: bool) -> Vec<(wgpu::Backend, Result<GpuRenderer, String>)> {
    liftplan_core::gpu::open_each_backend(allow_software)
        .into_iter()
        .map(|(b, dev)| (b, dev.map(GpuRenderer::new)))
        .collect()
}

/// Builds the picture pipelines on an open device.
fn pipelines(dev: liftplan_core::gpu::Device) -> GpuRenderer {
    let d = &dev.device;
    let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("docs render"),
        source: wgpu::ShaderSource::Wgsl(SHADER.into()),
    });
    let layout = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("size"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    });
    let pl = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = |vs: &str,
                    fs: &str,
                    attrs: &[wgpu::VertexAttribute],
                    stride: u64,
                    step: wgpu::VertexStepMode,
                    compare: wgpu::CompareFunction,
                    write: bool| {
        d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(vs),
            layout: Some(&pl),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(vs),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout { array_stride: stride, step_mode: step, attributes: attrs })],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH,
                depth_write_enabled: Some(write),
                depth_compare: Some(compare),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(fs),
                compilation_options: Default::default(),
                targets: &[Some(COLOR.into())],
            }),
            multiview_mask: None,
            cache: None,
        })
    };
    use wgpu::CompareFunction::{Always, Less};
    use wgpu::VertexStepMode::{Instance, Vertex};
    let tri_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Uint32];
    let sprite_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32, 2 => Uint32];
    let seg_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32, 3 => Uint32];
    let triangles = pipeline("tri_vs", "flat_fs", &tri_attrs, 16, Vertex, Less, true);
    let sprites = pipeline("sprite_vs", "flat_fs", &sprite_attrs, 20, Instance, Less, true);
    let segments = pipeline("seg_vs", "seg_fs", &seg_attrs, 32, Instance, Less, true);
    let segments_on_top = pipeline("seg_vs", "seg_fs", &seg_attrs, 32, Instance, Always, false);
    GpuRenderer { dev, layout, triangles, sprites, segments, segments_on_top }
}

impl GpuRenderer {
    pub fn new(dev: liftplan_core::gpu::Device) -> GpuRenderer {
        pipelines(dev)
    }

    /// Adapter name and backend, for reports.
    pub fn name(&self) -> &str {
        &self.dev.name
    }

    fn buffer(&self, label: &str, bytes: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
        self.dev.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage,
        })
    }

    /// Renders like [`crate::render::render_cpu`]; device errors (out of
    /// memory, a texture it cannot make) come back as `Err`.
    pub fn render(&self, scene: &Scene, cam: &Camera, width: u32, height: u32, ss: u32) -> Result<Image, String> {
        liftplan_core::gpu::catching_errors(&self.dev, || self.render_caught(scene, cam, width, height, ss))
    }

    fn render_caught(&self, scene: &Scene, cam: &Camera, width: u32, height: u32, ss: u32) -> Result<Image, String> {
        let ss = ss.clamp(1, 4) as usize;
        let pr: Projected = project(scene, cam, width, height, ss);
        let (w, h) = (pr.w as u32, pr.h as u32);
        let max = self.dev.device.limits().max_texture_dimension_2d;
        if w > max || h > max {
            return Err(format!("{w} x {h} samples exceed the GPU's {max} pixel texture limit"));
        }
        let d = &self.dev.device;
        let size = wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 };
        let texture = |format, usage| {
            d.create_texture(&wgpu::TextureDescriptor {
                label: None,
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let color = texture(COLOR, wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC);
        let depth = texture(DEPTH, wgpu::TextureUsages::RENDER_ATTACHMENT);
        let ubuf = self.buffer(
            "size",
            &f32s(&[w as f32, h as f32, 0.0, 0.0]).collect::<Vec<_>>(),
            wgpu::BufferUsages::UNIFORM,
        );
        let bind = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: ubuf.as_entire_binding() }],
        });

        let mut tri_bytes = Vec::with_capacity(pr.triangles.len() * 48);
        for (v, c) in &pr.triangles {
            for p in v {
                tri_bytes.extend(f32s(p));
                tri_bytes.extend(pack(*c).to_le_bytes());
            }
        }
        let mut sprite_bytes = Vec::with_capacity(pr.sprites.len() * 20);
        for s in &pr.sprites {
            sprite_bytes.extend(f32s(&s.at));
            sprite_bytes.extend(s.half.to_le_bytes());
            sprite_bytes.extend(pack(s.color).to_le_bytes());
        }
        let mut seg_bytes = Vec::with_capacity(pr.segments.len() * 32);
        for s in &pr.segments {
            seg_bytes.extend(f32s(&s.a));
            seg_bytes.extend(f32s(&s.b));
            seg_bytes.extend(s.radius.to_le_bytes());
            seg_bytes.extend(pack(s.color).to_le_bytes());
        }
        let vb = wgpu::BufferUsages::VERTEX;
        let tri_buf = (!tri_bytes.is_empty()).then(|| self.buffer("triangles", &tri_bytes, vb));
        let sprite_buf = (!sprite_bytes.is_empty()).then(|| self.buffer("sprites", &sprite_bytes, vb));
        let seg_buf = (!seg_bytes.is_empty()).then(|| self.buffer("segments", &seg_bytes, vb));

        let mut enc = d.create_command_encoder(&Default::default());
        {
            let sky = |k: usize| SKY[k] as f64 / 255.0;
            let color_view = color.create_view(&Default::default());
            let depth_view = depth.create_view(&Default::default());
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("picture"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &color_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color { r: sky(0), g: sky(1), b: sky(2), a: 1.0 }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &bind, &[]);
            if let Some(b) = &tri_buf {
                pass.set_pipeline(&self.triangles);
                pass.set_vertex_buffer(0, b.slice(..));
                pass.draw(0..(pr.triangles.len() * 3) as u32, 0..1);
            }
            if let Some(b) = &sprite_buf {
                pass.set_pipeline(&self.sprites);
                pass.set_vertex_buffer(0, b.slice(..));
                pass.draw(0..6, 0..pr.sprites.len() as u32);
            }
            if let Some(b) = &seg_buf {
                pass.set_vertex_buffer(0, b.slice(..));
                // Runs of segments with the same depth rule, in scene order.
                let mut i = 0;
                while i < pr.segments.len() {
                    let top = pr.segments[i].on_top;
                    let j = pr.segments[i..].iter().position(|s| s.on_top != top).map_or(pr.segments.len(), |k| i + k);
                    pass.set_pipeline(if top { &self.segments_on_top } else { &self.segments });
                    pass.draw(0..6, i as u32..j as u32);
                    i = j;
                }
            }
        }
        let row = (w * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let staging = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("picture read back"),
            size: row as u64 * h as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        enc.copy_texture_to_buffer(
            color.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &staging,
                layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: Some(h) },
            },
            size,
        );
        self.dev.queue.submit([enc.finish()]);
        let data = liftplan_core::gpu::map_read(&self.dev, &staging, row as u64 * h as u64)?;
        let mut samples = Vec::with_capacity((w * h) as usize);
        for y in 0..h as usize {
            let r = &data[y * row as usize..y * row as usize + w as usize * 4];
            samples.extend(r.chunks_exact(4).map(|p| [p[0], p[1], p[2]]));
        }
        Ok(downsample(&samples, w as usize, ss, width, height))
    }
}
