//! The pictures of a lift: site overview (top view), one perspective view per
//! step, and the load chart plot. Built as [`render::Scene`]s and drawn by the
//! renderer; the chart plot is drawn directly on an image.

use crate::render::{self, Camera, PointBatch, Polyline, Scene, TriangleBatch};
use liftplan_core::capacity::ChartConfig;
use liftplan_core::crane::{Config, PartKind};
use liftplan_core::image::{Image, Rgb};
use liftplan_core::lift::LiftTask;
use liftplan_core::mesh::TriMesh;
use liftplan_core::obb::Obb;
use liftplan_plan::LiftPlan;

const PLANT: Rgb = [150, 160, 175];
const CRANE: Rgb = [235, 170, 30];
const BOOM: Rgb = [220, 120, 20];
const LOAD: Rgb = [40, 110, 200];
const PATH: Rgb = [200, 30, 60];
const HOT_SPOT: Rgb = [235, 20, 20];
/// Other lifts' loads where they stand during this lift.
pub const OTHER_LOAD: Rgb = [150, 90, 190];

/// The site as the pictures show it: plant mesh and a thinned cloud.
pub struct SiteView {
    pub renderer: render::Renderer,
    pub mesh: TriMesh,
    pub points: Vec<[f32; 3]>,
    pub colors: Vec<Rgb>,
}

impl SiteView {
    /// Keeps at most `max_points` cloud points (every k-th), coloured by height.
    pub fn new(renderer: render::Renderer, mesh: TriMesh, points: &[[f64; 3]], max_points: usize) -> SiteView {
        let k = points.len().div_ceil(max_points.max(1)).max(1);
        let kept: Vec<[f32; 3]> = points.iter().step_by(k).map(|p| [p[0] as f32, p[1] as f32, p[2] as f32]).collect();
        let (lo, hi) = kept.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), p| (a.min(p[2]), b.max(p[2])));
        let colors = kept
            .iter()
            .map(|p| {
                let t = if hi > lo { ((p[2] - lo) / (hi - lo)) as f64 } else { 0.0 };
                let c = liftplan_core::image::ramp(t.powf(0.6));
                [(c[0] as f64 * 0.8 + 40.0) as u8, (c[1] as f64 * 0.8 + 40.0) as u8, (c[2] as f64 * 0.8 + 40.0) as u8]
            })
            .collect();
        SiteView { renderer, mesh, points: kept, colors }
    }

    fn base_scene(&self, point_px: f32) -> Scene {
        let mut s = Scene::default();
        if !self.mesh.triangles.is_empty() {
            s.triangles.push(render::mesh_batch(&self.mesh, PLANT));
        }
        if !self.points.is_empty() {
            s.points.push(PointBatch {
                positions: self.points.clone(),
                colors: self.colors.clone(),
                color: [120; 3],
                size_px: point_px,
            });
        }
        s
    }
}

fn crane_batches(task: &LiftTask, c: &Config) -> Vec<TriangleBatch> {
    task.crane
        .pose(c, &task.load)
        .parts
        .iter()
        .map(|(k, b)| {
            let color = match k {
                PartKind::Load => LOAD,
                PartKind::Boom | PartKind::Jib => BOOM,
                PartKind::Rope => [40, 40, 40],
                _ => CRANE,
            };
            render::obb_batch(b, color)
        })
        .collect()
}

/// Hook path (load centre) through the moves, sampled along each.
pub fn load_path(task: &LiftTask, plan: &LiftPlan, upto: usize) -> Vec<[f32; 3]> {
    let mut pts = Vec::new();
    for m in plan.moves.iter().take(upto) {
        let (a, b) = (m.from.to_array(), m.to.to_array());
        let n = 24;
        for s in 0..=n {
            let mut v = a;
            let j = m.joint.index();
            v[j] = a[j] + (b[j] - a[j]) * s as f64 / n as f64;
            let o = task.crane.load_obb(&Config::from_array(v), &task.load);
            pts.push([o.center.x as f32, o.center.y as f32, o.center.z as f32]);
        }
    }
    pts
}

/// Top view of the whole site with the crane at pick, the load at set (ghost)
/// and the load path.
pub fn overview(site: &SiteView, task: &LiftTask, plan: &LiftPlan, others: &[Obb], w: u32, h: u32) -> Image {
    let mut s = site.base_scene(2.0);
    s.triangles.extend(others.iter().map(|b| render::obb_batch(b, OTHER_LOAD)));
    s.triangles.extend(crane_batches(task, &plan.start));
    s.triangles.push(render::obb_batch(&task.crane.load_obb(&plan.set, &task.load), [90, 160, 230]));
    s.lines.push(Polyline {
        points: load_path(task, plan, plan.moves.len()),
        color: PATH,
        width_px: 3.0,
        on_top: true,
    });
    let (lo, hi) = s.bounds();
    let cam = Camera::top(lo, hi, w as f32 / h as f32);
    site.renderer.render(&s, &cam, w, h, 2)
}

/// Perspective view at the end of step `n` (1-based) with the path so far.
pub fn step_view(site: &SiteView, task: &LiftTask, plan: &LiftPlan, others: &[Obb], n: usize, w: u32, h: u32) -> Image {
    let mut s = site.base_scene(1.5);
    s.triangles.extend(others.iter().map(|b| render::obb_batch(b, OTHER_LOAD)));
    let end = plan.moves[n - 1].to;
    s.triangles.extend(crane_batches(task, &end));
    let done = load_path(task, plan, n);
    let all = load_path(task, plan, plan.moves.len());
    s.lines.push(Polyline { points: all, color: [230, 170, 180], width_px: 2.0, on_top: true });
    s.lines.push(Polyline { points: done, color: PATH, width_px: 3.5, on_top: true });
    // Hot spot: where the validator measured this step's smallest clearance, as
    // a red block on the obstacle with a flag pole drawn over everything, so it
    // is found even when the obstacle hides it.
    if let Some(at) = plan.steps.get(n - 1).and_then(|st| st.clearance_at) {
        let c = nalgebra::Point3::new(at[0], at[1], at[2]);
        s.triangles.push(render::obb_batch(
            &liftplan_core::obb::Obb::axis_aligned(c, nalgebra::Vector3::new(0.3, 0.3, 0.3)),
            HOT_SPOT,
        ));
        let (x, y, z) = (at[0] as f32, at[1] as f32, at[2] as f32);
        s.lines.push(Polyline {
            points: vec![[x, y, z], [x, y, z + 4.0]],
            color: HOT_SPOT,
            width_px: 2.5,
            on_top: true,
        });
    }
    // Frame the crane and the path, not the whole cloud.
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for c in [plan.start, end, plan.set] {
        for (_, b) in task.crane.pose(&c, &task.load).parts {
            for p in b.corners() {
                for i in 0..3 {
                    lo[i] = lo[i].min(p[i] as f32);
                    hi[i] = hi[i].max(p[i] as f32);
                }
            }
        }
    }
    lo[2] = lo[2].min(0.0);
    // Look from behind-left of the crane towards the work area.
    let mid_swing = 0.5 * (plan.start.swing_rad + plan.set.swing_rad) + task.crane.placement.heading_rad;
    let az = (mid_swing + std::f64::consts::PI + 0.6).to_degrees() as f32;
    let cam = Camera::framing(lo, hi, az, 28.0, 40.0, w as f32 / h as f32);
    site.renderer.render(&s, &cam, w, h, 2)
}

/// Capacity against radius for the lift's boom, the gross load, and the
/// radius of every step.
pub fn chart_plot(chart: &ChartConfig, task: &LiftTask, plan: &LiftPlan, w: u32, h: u32) -> Image {
    let mut img = Image::new(w, h, [255, 255, 255]);
    let (ml, mr, mt, mb) = (80.0, 20.0, 20.0, 50.0);
    let boom = if task.crane.model.is_tower() { 0.0 } else { task.crane.placement.boom_length_m };
    let rmax = chart.radii_m.last().copied().unwrap_or(50.0).max(1.0);
    let pts: Vec<(f64, f64)> = (0..=400)
        .filter_map(|i| {
            let r = rmax * i as f64 / 400.0;
            chart.lookup(boom, r).ok().map(|c| (r, task.effective_capacity_kg(c.capacity_kg)))
        })
        .collect();
    let cmax = pts.iter().map(|p| p.1).fold(task.gross_kg(), f64::max) * 1.1;
    let x_of = |r: f64| ml + r / rmax * (w as f64 - ml - mr);
    let y_of = |c: f64| h as f64 - mb - c / cmax * (h as f64 - mt - mb);
    img.rect_outline(ml, mt, w as f64 - mr, h as f64 - mb, 1.0, [60, 60, 60]);
    for q in 0..=5 {
        let c = cmax * q as f64 / 5.0;
        let t = format!("{:.0}", c / 1000.0);
        img.text((ml - 8.0) as i64 - Image::text_width(&t, 2), y_of(c) as i64 - 7, &t, 2, [40, 40, 40]);
        img.line(ml, y_of(c), w as f64 - mr, y_of(c), 1.0, [225, 225, 225]);
    }
    for q in 0..=5 {
        let r = rmax * q as f64 / 5.0;
        let t = format!("{r:.0}");
        img.text(x_of(r) as i64 - Image::text_width(&t, 2) / 2, (h as f64 - mb + 8.0) as i64, &t, 2, [40, 40, 40]);
    }
    img.text((w as f64 / 2.0 - 60.0) as i64, (h as f64 - 22.0) as i64, "RADIUS (M)", 2, [40, 40, 40]);
    img.text(4, 4, "CAPACITY (T)", 2, [40, 40, 40]);
    for p in pts.windows(2) {
        img.line(x_of(p[0].0), y_of(p[0].1), x_of(p[1].0), y_of(p[0].1), 2.0, [30, 90, 170]);
        img.line(x_of(p[1].0), y_of(p[0].1), x_of(p[1].0), y_of(p[1].1), 2.0, [30, 90, 170]);
    }
    let g = task.gross_kg();
    img.line(ml, y_of(g), w as f64 - mr, y_of(g), 2.0, [200, 40, 40]);
    img.text((w as f64 - mr - 150.0) as i64, y_of(g) as i64 - 18, "GROSS LOAD", 2, [200, 40, 40]);
    for st in &plan.steps {
        img.disc(x_of(st.radius_m), y_of(g), 5.0, [200, 40, 40]);
    }
    img
}
