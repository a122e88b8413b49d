//! The off-screen renderer's scene description and its CPU rasteriser.
//!
//! A [`Scene`] is plain data: triangle batches (flat colour, Lambert shaded),
//! point sprites (square, screen-sized) and polylines, seen by a [`Camera`].
//! [`render_cpu`] draws it with a z-buffer at `ss x ss` samples per pixel and box-
//! filters down, which gives anti-aliased edges. The GPU twin draws the same scene
//! with the same shading formula and sampling, so pictures agree within a small
//! tolerance wherever a GPU exists.

use nalgebra::{Matrix4, Point3, Vector3};
use rayon::prelude::*;

pub type Rgb = [u8; 3];

#[derive(Debug, Clone)]
pub struct TriangleBatch {
    pub positions: Vec<[f32; 3]>,
    pub triangles: Vec<[u32; 3]>,
    pub color: Rgb,
}

#[derive(Debug, Clone)]
pub struct PointBatch {
    pub positions: Vec<[f32; 3]>,
    /// One colour per point, or empty for `color`.
    pub colors: Vec<Rgb>,
    pub color: Rgb,
    /// Side of the square sprite in output pixels.
    pub size_px: f32,
}

#[derive(Debug, Clone)]
pub struct Polyline {
    pub points: Vec<[f32; 3]>,
    pub color: Rgb,
    pub width_px: f32,
    /// Drawn over everything (e.g. the hook path), not depth tested.
    pub on_top: bool,
}

#[derive(Debug, Clone, Default)]
pub struct Scene {
    pub triangles: Vec<TriangleBatch>,
    pub points: Vec<PointBatch>,
    pub lines: Vec<Polyline>,
}

impl Scene {
    /// Bounding box of everything in the scene.
    pub fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        let mut grow = |p: &[f32; 3]| {
            for i in 0..3 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        };
        self.triangles.iter().flat_map(|b| b.positions.iter()).for_each(&mut grow);
        self.points.iter().flat_map(|b| b.positions.iter()).for_each(&mut grow);
        self.lines.iter().flat_map(|b| b.points.iter()).for_each(&mut grow);
        (lo, hi)
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Vertical field of view in degrees.
    Perspective { fov_y_deg: f32 },
    /// Height of the view in metres.
    Orthographic { height_m: f32 },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub up: [f32; 3],
    pub projection: Projection,
    pub near: f32,
    pub far: f32,
}

impl Camera {
    /// A camera looking at a box from the given azimuth and elevation (degrees),
    /// far enough to frame it.
    pub fn framing(
        lo: [f32; 3],
        hi: [f32; 3],
        azimuth_deg: f32,
        elevation_deg: f32,
        fov_y_deg: f32,
        aspect: f32,
    ) -> Camera {
        let c = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, (lo[2] + hi[2]) / 2.0];
        let r = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt().max(1.0) / 2.0;
        let half = (fov_y_deg.to_radians() / 2.0).tan().min((fov_y_deg.to_radians() / 2.0).tan() * aspect);
        let dist = r / half.atan().sin() * 1.05;
        let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
        let eye = [c[0] + dist * el.cos() * az.cos(), c[1] + dist * el.cos() * az.sin(), c[2] + dist * el.sin()];
        Camera {
            eye,
            target: c,
            up: [0.0, 0.0, 1.0],
            projection: Projection::Perspective { fov_y_deg },
            near: (dist - 2.0 * r).max(0.1),
            far: dist + 2.0 * r,
        }
    }

    /// A top view of a box (north up).
    pub fn top(lo: [f32; 3], hi: [f32; 3], aspect: f32) -> Camera {
        let c = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, hi[2] + 10.0];
        let h = ((hi[1] - lo[1]).max((hi[0] - lo[0]) / aspect) * 1.08).max(1.0);
        Camera {
            eye: c,
            target: [c[0], c[1], lo[2] - 1.0],
            up: [0.0, 1.0, 0.0],
            projection: Projection::Orthographic { height_m: h },
            near: 1.0,
            far: hi[2] - lo[2] + 20.0,
        }
    }

    /// World to clip space for an image of the given aspect (width / height).
    pub fn view_proj(&self, aspect: f32) -> Matrix4<f32> {
        let view = Matrix4::look_at_rh(&Point3::from(self.eye), &Point3::from(self.target), &Vector3::from(self.up));
        let proj = match self.projection {
            Projection::Perspective { fov_y_deg } => {
                Matrix4::new_perspective(aspect, fov_y_deg.to_radians(), self.near, self.far)
            }
            Projection::Orthographic { height_m } => {
                let h = height_m / 2.0;
                let w = h * aspect;
                Matrix4::new_orthographic(-w, w, -h, h, self.near, self.far)
            }
        };
        proj * view
    }

    pub fn view_dir(&self) -> Vector3<f32> {
        (Vector3::from(self.target) - Vector3::from(self.eye)).normalize()
    }
}

/// Shading shared by both renderers: ambient plus a key light from the upper
/// left behind the viewer, on the face normal (two-sided).
pub fn shade(color: Rgb, normal: Vector3<f32>, view_dir: Vector3<f32>) -> Rgb {
    let light = Vector3::new(-0.35, -0.45, 0.82).normalize();
    let mut n = normal;
    if n.dot(&view_dir) > 0.0 {
        n = -n;
    }
    let diffuse = n.dot(&light).max(0.0);
    let k = 0.42 + 0.58 * diffuse;
    [
        (color[0] as f32 * k).min(255.0) as u8,
        (color[1] as f32 * k).min(255.0) as u8,
        (color[2] as f32 * k).min(255.0) as u8,
    ]
}

pub const SKY: Rgb = [236, 241, 247];

/// Which rasteriser draws the pictures.
pub enum Renderer {
    Cpu,
    Gpu(crate::gpu::GpuRenderer),
}

impl Renderer {
    /// The GPU twin when `[gpu] use` asks for it and an adapter opens (`auto`:
    /// hardware adapters only), else the CPU rasteriser; `require` without an
    /// adapter is an error.
    pub fn choose(use_: liftplan_core::gpu::GpuUse) -> Result<Renderer, String> {
        Ok(match liftplan_core::gpu::open_for(use_, "pictures")? {
            Some(dev) => Renderer::Gpu(crate::gpu::GpuRenderer::new(dev)),
            None => Renderer::Cpu,
        })
    }

    pub fn name(&self) -> String {
        match self {
            Renderer::Cpu => "cpu".into(),
            Renderer::Gpu(g) => format!("gpu: {}", g.name()),
        }
    }

    /// Renders with this renderer; a GPU failure (lost device, a picture over
    /// its texture limit) falls back to the CPU twin with a warning, since the
    /// two draw the same picture.
    pub fn render(&self, scene: &Scene, cam: &Camera, width: u32, height: u32, ss: u32) -> liftplan_core::image::Image {
        if let Renderer::Gpu(g) = self {
            match g.render(scene, cam, width, height, ss) {
                Ok(im) => return im,
                Err(e) => tracing::warn!("GPU picture failed, drawing it on the CPU: {e}"),
            }
        }
        render_cpu(scene, cam, width, height, ss)
    }
}

struct Target {
    w: usize,
    color: Vec<Rgb>,
    depth: Vec<f32>,
}

/// A point sprite in sample space: centre (x, y in samples, z in NDC), half side.
pub(crate) struct Sprite {
    pub(crate) at: [f32; 3],
    pub(crate) half: f32,
    pub(crate) color: Rgb,
}

/// A polyline segment in sample space.
pub(crate) struct Segment {
    pub(crate) a: [f32; 3],
    pub(crate) b: [f32; 3],
    pub(crate) radius: f32,
    pub(crate) color: Rgb,
    pub(crate) on_top: bool,
}

/// The scene projected to sample space (x right, y down, in samples; z in NDC,
/// -1 near .. 1 far), triangles already shaded. Both renderers draw exactly this,
/// so they differ only in how they rasterise it.
pub(crate) struct Projected {
    pub(crate) w: usize,
    pub(crate) h: usize,
    pub(crate) triangles: Vec<([[f32; 3]; 3], Rgb)>,
    pub(crate) sprites: Vec<Sprite>,
    pub(crate) segments: Vec<Segment>,
}

pub(crate) fn project(scene: &Scene, cam: &Camera, width: u32, height: u32, ss: usize) -> Projected {
    let (w, h) = (width as usize * ss, height as usize * ss);
    let aspect = width as f32 / height as f32;
    let vp = cam.view_proj(aspect);
    let vd = cam.view_dir();
    let to_screen = |p: &[f32; 3]| -> Option<[f32; 3]> {
        let c = vp * nalgebra::Vector4::new(p[0], p[1], p[2], 1.0);
        if c.w <= 1e-6 {
            return None;
        }
        let n = c.xyz() / c.w;
        Some([(n.x * 0.5 + 0.5) * w as f32, (0.5 - n.y * 0.5) * h as f32, n.z])
    };
    let mut triangles = Vec::new();
    for b in &scene.triangles {
        for tri in &b.triangles {
            let (a, bb, c) = (b.positions[tri[0] as usize], b.positions[tri[1] as usize], b.positions[tri[2] as usize]);
            let (Some(sa), Some(sb), Some(sc)) = (to_screen(&a), to_screen(&bb), to_screen(&c)) else { continue };
            let n = (Vector3::from(bb) - Vector3::from(a)).cross(&(Vector3::from(c) - Vector3::from(a)));
            if n.norm_squared() == 0.0 {
                continue;
            }
            triangles.push(([sa, sb, sc], shade(b.color, n.normalize(), vd)));
        }
    }
    let mut sprites = Vec::new();
    for b in &scene.points {
        let half = b.size_px * ss as f32 / 2.0;
        for (i, p) in b.positions.iter().enumerate() {
            let Some(at) = to_screen(p) else { continue };
            if !(-1.0..=1.0).contains(&at[2]) {
                continue;
            }
            sprites.push(Sprite { at, half, color: b.colors.get(i).copied().unwrap_or(b.color) });
        }
    }
    let mut segments = Vec::new();
    for l in &scene.lines {
        let radius = l.width_px * ss as f32 / 2.0;
        for seg in l.points.windows(2) {
            let (Some(a), Some(b)) = (to_screen(&seg[0]), to_screen(&seg[1])) else { continue };
            segments.push(Segment { a, b, radius, color: l.color, on_top: l.on_top });
        }
    }
    Projected { w, h, triangles, sprites, segments }
}

/// Renders `scene` at `width x height` pixels with `ss x ss` samples per pixel.
pub fn render_cpu(scene: &Scene, cam: &Camera, width: u32, height: u32, ss: u32) -> liftplan_core::image::Image {
    let ss = ss.clamp(1, 4) as usize;
    let pr = project(scene, cam, width, height, ss);
    let (w, h) = (pr.w, pr.h);
    let mut t = Target { w, color: vec![SKY; w * h], depth: vec![f32::INFINITY; w * h] };
    // Triangles, rasterised in horizontal bands in parallel.
    const BAND: usize = 64;
    t.color.par_chunks_mut(w * BAND).zip(t.depth.par_chunks_mut(w * BAND)).enumerate().for_each(|(bi, (col, dep))| {
        let y0 = bi * BAND;
        let y1 = (y0 + BAND).min(h);
        for (s, c) in &pr.triangles {
            raster_tri(s, *c, w, y0, y1, col, dep);
        }
    });
    for sp in &pr.sprites {
        let (s, half) = (sp.at, sp.half);
        let (x0, x1) = ((s[0] - half).round().max(0.0) as usize, ((s[0] + half).round().max(0.0) as usize).min(w));
        let (y0, y1) = ((s[1] - half).round().max(0.0) as usize, ((s[1] + half).round().max(0.0) as usize).min(h));
        for y in y0..y1 {
            for x in x0..x1 {
                let k = y * w + x;
                if s[2] < t.depth[k] {
                    t.depth[k] = s[2];
                    t.color[k] = sp.color;
                }
            }
        }
    }
    for sg in &pr.segments {
        let (a, b, r) = (sg.a, sg.b, sg.radius);
        let (minx, maxx) =
            ((a[0].min(b[0]) - r).floor().max(0.0) as usize, ((a[0].max(b[0]) + r).ceil().max(0.0) as usize).min(w));
        let (miny, maxy) =
            ((a[1].min(b[1]) - r).floor().max(0.0) as usize, ((a[1].max(b[1]) + r).ceil().max(0.0) as usize).min(h));
        for y in miny..maxy {
            for x in minx..maxx {
                if let Some(z) = segment_depth(a, b, r, x as f32 + 0.5, y as f32 + 0.5) {
                    let k = y * w + x;
                    if sg.on_top || z < t.depth[k] {
                        if !sg.on_top {
                            t.depth[k] = z;
                        }
                        t.color[k] = sg.color;
                    }
                }
            }
        }
    }
    downsample(&t.color, t.w, ss, width, height)
}

/// Depth of a segment's capsule at a sample, or `None` outside it. The GPU
/// fragment shader computes the same thing.
fn segment_depth(a: [f32; 3], b: [f32; 3], r: f32, px: f32, py: f32) -> Option<f32> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = (dx * dx + dy * dy).max(1e-12);
    let u = (((px - a[0]) * dx + (py - a[1]) * dy) / len2).clamp(0.0, 1.0);
    let (qx, qy) = (a[0] + u * dx, a[1] + u * dy);
    ((px - qx).powi(2) + (py - qy).powi(2) <= r * r).then(|| a[2] + u * (b[2] - a[2]) - 1e-4)
}

fn edge(a: &[f32; 3], b: &[f32; 3], x: f32, y: f32) -> f32 {
    (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])
}

/// Fills the part of a screen triangle inside rows `y0..y1`, sampling pixel
/// centres (top-left fill rule by half-open bounds).
fn raster_tri(s: &[[f32; 3]; 3], c: Rgb, w: usize, y0: usize, y1: usize, col: &mut [Rgb], dep: &mut [f32]) {
    let [a, b, cc] = s;
    let area = edge(a, b, cc[0], cc[1]);
    if area.abs() < 1e-12 {
        return;
    }
    let minx = a[0].min(b[0]).min(cc[0]).floor().max(0.0) as usize;
    let maxx = (a[0].max(b[0]).max(cc[0]).ceil().max(0.0) as usize).min(w);
    let miny = (a[1].min(b[1]).min(cc[1]).floor().max(y0 as f32) as usize).max(y0);
    let maxy = (a[1].max(b[1]).max(cc[1]).ceil().max(0.0) as usize).min(y1);
    for y in miny..maxy {
        let py = y as f32 + 0.5;
        for x in minx..maxx {
            let px = x as f32 + 0.5;
            let w0 = edge(b, cc, px, py) / area;
            let w1 = edge(cc, a, px, py) / area;
            let w2 = 1.0 - w0 - w1;
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            let z = w0 * a[2] + w1 * b[2] + w2 * cc[2];
            if !(-1.0..=1.0).contains(&z) {
                continue;
            }
            let k = (y - y0) * w + x;
            if z < dep[k] {
                dep[k] = z;
                col[k] = c;
            }
        }
    }
}

/// Box-filters `ss x ss` samples (row-major, `sample_w` per row) to pixels.
pub(crate) fn downsample(
    samples: &[Rgb],
    sample_w: usize,
    ss: usize,
    width: u32,
    height: u32,
) -> liftplan_core::image::Image {
    let mut out = liftplan_core::image::Image::new(width, height, SKY);
    let n = (ss * ss) as u32;
    for y in 0..height as usize {
        for x in 0..width as usize {
            let mut acc = [0u32; 3];
            for sy in 0..ss {
                for sx in 0..ss {
                    let c = samples[(y * ss + sy) * sample_w + x * ss + sx];
                    for k in 0..3 {
                        acc[k] += c[k] as u32;
                    }
                }
            }
            out.set(
                x as i64,
                y as i64,
                [((acc[0] + n / 2) / n) as u8, ((acc[1] + n / 2) / n) as u8, ((acc[2] + n / 2) / n) as u8],
            );
        }
    }
    out
}

/// A triangle batch from a core mesh (site-frame coordinates) with one colour.
pub fn mesh_batch(m: &liftplan_core::mesh::TriMesh, color: Rgb) -> TriangleBatch {
    TriangleBatch {
        positions: m.vertices.iter().map(|v| [v[0] as f32, v[1] as f32, v[2] as f32]).collect(),
        triangles: m.triangles.clone(),
        color,
    }
}

/// The 12 triangles of an oriented box.
pub fn obb_batch(b: &liftplan_core::obb::Obb, color: Rgb) -> TriangleBatch {
    let c = b.corners();
    let positions: Vec<[f32; 3]> = c.iter().map(|p| [p.x as f32, p.y as f32, p.z as f32]).collect();
    let mut triangles = Vec::new();
    for q in [[0u32, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
        triangles.push([q[0], q[1], q[2]]);
        triangles.push([q[0], q[2], q[3]]);
    }
    TriangleBatch { positions, triangles, color }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grey ground square under a red box, seen from above at an angle.
    fn known_scene() -> (Scene, Camera) {
        let ground = TriangleBatch {
            positions: vec![[-20.0, -20.0, 0.0], [20.0, -20.0, 0.0], [20.0, 20.0, 0.0], [-20.0, 20.0, 0.0]],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            color: [128, 128, 128],
        };
        let b = liftplan_core::obb::Obb::axis_aligned(
            nalgebra::Point3::new(0.0, 0.0, 2.0),
            nalgebra::Vector3::new(2.0, 2.0, 2.0),
        );
        let scene = Scene { triangles: vec![ground, obb_batch(&b, [200, 30, 30])], ..Default::default() };
        let cam = Camera {
            eye: [0.0, -30.0, 30.0],
            target: [0.0, 0.0, 0.0],
            up: [0.0, 0.0, 1.0],
            projection: Projection::Perspective { fov_y_deg: 50.0 },
            near: 1.0,
            far: 200.0,
        };
        (scene, cam)
    }

    #[test]
    fn draws_sky_ground_and_box() {
        let (scene, cam) = known_scene();
        let im = render_cpu(&scene, &cam, 160, 120, 2);
        // Top rows look over the ground square into the sky.
        assert_eq!(im.get(80, 1), SKY);
        // Centre: the box (red dominant).
        let c = im.get(80, 60);
        assert!(c[0] > 100 && c[1] < 60 && c[2] < 60, "{c:?}");
        // Lower corner: ground (grey).
        let g = im.get(10, 110);
        assert!(g[0] == g[1] && g[1] == g[2] && g[0] > 40, "{g:?}");
    }

    #[test]
    fn framing_keeps_the_scene_in_view() {
        let (scene, _) = known_scene();
        let (lo, hi) = scene.bounds();
        let cam = Camera::framing(lo, hi, -60.0, 35.0, 40.0, 4.0 / 3.0);
        let im = render_cpu(&scene, &cam, 120, 90, 1);
        // Every border pixel is sky: nothing is cut off.
        for x in 0..120 {
            assert_eq!(im.get(x, 0), SKY);
            assert_eq!(im.get(x, 89), SKY);
        }
    }
}
