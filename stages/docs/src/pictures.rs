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
/// Obstacles placed by hand in the project file.
pub const OBSTACLE: Rgb = [0, 128, 128];
/// An overhead power line's conductor, on the overview.
pub const POWER_LINE: Rgb = [235, 140, 0];
/// A run of line-like scan points no power line given runs along (a line
/// no one gave?), on the overview.
pub const LINE_LIKE: Rgb = [0, 200, 225];
/// Ground the load passes over that no scan saw.
pub const UNSEEN: Rgb = [25, 25, 25];
/// Ground only the crane's boom or superstructure passes over that no scan
/// saw, in the pictures.
pub const UNSEEN_UNDER_CRANE: Rgb = [130, 130, 130];
/// The outline of an area the load must never be over (`not_over`).
pub const NOT_OVER: Rgb = [20, 150, 60];
/// The outline of an area the crane may be set up in (`crane_stands_in`).
pub const CRANE_AREA: Rgb = [40, 90, 210];
/// The ground the load passes over.
pub const UNDER_LOAD: Rgb = [248, 205, 205];
/// The circle a mobile crane's superstructure sweeps as it slews.
pub const TAIL_SWING: Rgb = [200, 0, 150];

/// The site as the pictures show it: plant mesh and a thinned cloud, in
/// `f32` metres from [`SiteView::origin`].
pub struct SiteView {
    pub renderer: render::Renderer,
    pub mesh: TriMesh,
    pub points: Vec<[f32; 3]>,
    pub colors: Vec<Rgb>,
    /// The site point (whole metres in plan, height 0) the pictures are
    /// drawn from. A site in survey coordinates (UTM northings of 5,000 km)
    /// in `f32` would be drawn to the nearest half metre.
    pub origin: [f64; 3],
}

impl SiteView {
    /// Keeps at most `max_points` cloud points (every k-th), coloured by
    /// height; everything is drawn from the middle of the site's plan extent.
    pub fn new(renderer: render::Renderer, mut mesh: TriMesh, points: &[[f64; 3]], max_points: usize) -> SiteView {
        let site = liftplan_core::frame::Aabb::from_points(points.iter().chain(&mesh.vertices));
        let origin = if site.is_empty() {
            [0.0; 3]
        } else {
            let c = site.center();
            [c[0].round(), c[1].round(), 0.0]
        };
        for v in &mut mesh.vertices {
            *v = [v[0] - origin[0], v[1] - origin[1], v[2] - origin[2]];
        }
        let k = points.len().div_ceil(max_points.max(1)).max(1);
        let kept: Vec<[f32; 3]> = points.iter().step_by(k).map(|p| to_local(origin, *p)).collect();
        let (lo, hi) = kept.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), p| (a.min(p[2]), b.max(p[2])));
        let colors = kept
            .iter()
            .map(|p| {
                let t = if hi > lo { ((p[2] - lo) / (hi - lo)) as f64 } else { 0.0 };
                let c = liftplan_core::image::ramp(t.powf(0.6));
                [(c[0] as f64 * 0.8 + 40.0) as u8, (c[1] as f64 * 0.8 + 40.0) as u8, (c[2] as f64 * 0.8 + 40.0) as u8]
            })
            .collect();
        SiteView { renderer, mesh, points: kept, colors, origin }
    }

    /// A site point as the pictures draw it.
    pub fn local(&self, p: [f64; 3]) -> [f32; 3] {
        to_local(self.origin, p)
    }

    /// A box in the site as the pictures draw it.
    fn local_obb(&self, b: &Obb) -> Obb {
        let mut o = *b;
        o.center -= nalgebra::Vector3::new(self.origin[0], self.origin[1], self.origin[2]);
        o
    }

    fn obb_batch(&self, b: &Obb, color: Rgb) -> TriangleBatch {
        render::obb_batch(&self.local_obb(b), color)
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

/// Site point `p` in `f32` metres from `origin`.
fn to_local(origin: [f64; 3], p: [f64; 3]) -> [f32; 3] {
    [(p[0] - origin[0]) as f32, (p[1] - origin[1]) as f32, (p[2] - origin[2]) as f32]
}

fn crane_batches(site: &SiteView, task: &LiftTask, c: &Config) -> Vec<TriangleBatch> {
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
            site.obb_batch(b, color)
        })
        .collect()
}

/// Cells of `area` that no scan saw, as flat tiles of `color` just above
/// the crane's set-up level `z_m`, one batch.
fn cells_batch(
    site: &SiteView,
    c: &liftplan_plan::coverage::Coverage,
    cells: &[[i32; 2]],
    z_m: f64,
    color: [u8; 3],
) -> TriangleBatch {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for &[i, j] in cells {
        let (x0, y0) = (i as f64 * c.cell_m, j as f64 * c.cell_m);
        let n = positions.len() as u32;
        for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            positions.push(site.local([x0 + dx * c.cell_m, y0 + dy * c.cell_m, z_m + 0.05]));
        }
        triangles.push([n, n + 1, n + 2]);
        triangles.push([n, n + 2, n + 3]);
    }
    TriangleBatch { positions, triangles, color }
}

/// Hook path (load centre) through the moves, sampled along each.
pub fn load_path(site: &SiteView, task: &LiftTask, plan: &LiftPlan, upto: usize) -> Vec<[f32; 3]> {
    let mut pts = Vec::new();
    for m in plan.moves.iter().take(upto) {
        let (a, b) = (m.from.to_array(), m.to.to_array());
        let n = 24;
        for s in 0..=n {
            let mut v = a;
            let j = m.joint.index();
            v[j] = a[j] + (b[j] - a[j]) * s as f64 / n as f64;
            let o = task.crane.load_obb(&Config::from_array(v), &task.load);
            pts.push(site.local([o.center.x, o.center.y, o.center.z]));
        }
    }
    pts
}

/// Top view of the whole site with the crane where the plan starts (at the
/// pick, or where a resumed lift's load hangs), the load at set (ghost) and
/// the load path; `others`: what else stands on site that neither the
/// scans nor the model hold (the other lifts' loads, the obstacles placed by
/// hand), each in its colour.
pub fn overview(site: &SiteView, task: &LiftTask, plan: &LiftPlan, others: &[(Obb, Rgb)], w: u32, h: u32) -> Image {
    let mut s = site.base_scene(2.0);
    // What stands beyond the scans and the model by more than FRAME_M (a
    // power line's far spans) is left out: drawn, it would frame the picture
    // round it.
    const FRAME_M: f32 = 20.0;
    let (lo, hi) = s.bounds();
    let near = |b: &Obb| {
        let a = site.local_obb(b).aabb();
        !(lo[0].is_finite() && hi[0].is_finite())
            || (0..2).all(|k| a.min[k] as f32 <= hi[k] + FRAME_M && a.max[k] as f32 >= lo[k] - FRAME_M)
    };
    s.triangles.extend(others.iter().filter(|(b, _)| near(b)).map(|(b, colour)| site.obb_batch(b, *colour)));
    // What only the crane's boom or superstructure passes over unseen, in
    // grey under what the load does, in black.
    // The ground under the load's path, under both.
    if let Some(c) = &plan.summary.coverage {
        let z = task.crane.placement.z_m;
        // With the lift's fall zone round it, where it gives one.
        let kept_out = c.kept_out.as_ref().map_or(&c.under_load.passed_cells, |k| &k.cells);
        if !kept_out.is_empty() {
            s.triangles.push(cells_batch(site, c, kept_out, z - 0.01, UNDER_LOAD));
        }
        if !c.under_crane.unscanned_cells.is_empty() {
            s.triangles.push(cells_batch(site, c, &c.under_crane.unscanned_cells, z, UNSEEN_UNDER_CRANE));
        }
        if !c.under_load.unscanned_cells.is_empty() {
            s.triangles.push(cells_batch(site, c, &c.under_load.unscanned_cells, z + 0.01, UNSEEN));
        }
    }
    s.triangles.extend(crane_batches(site, task, &plan.start));
    s.triangles.push(site.obb_batch(&task.crane.load_obb(&plan.set, &task.load), [90, 160, 230]));
    s.lines.extend(area_outlines(site, task));
    s.lines.extend(tail_swing_circle(site, task));
    s.lines.push(Polyline {
        points: load_path(site, task, plan, plan.moves.len()),
        color: PATH,
        width_px: 3.0,
        on_top: true,
    });
    let (lo, hi) = s.bounds();
    let cam = Camera::top(lo, hi, w as f32 / h as f32);
    site.renderer.render(&s, &cam, w, h, 2)
}

/// The areas the load must never be over, outlined on the ground the crane
/// stands on, drawn over everything.
fn not_over_outlines(site: &SiteView, task: &LiftTask) -> Vec<Polyline> {
    task.not_over.iter().map(|a| outline(site, task, &a.corners_m, NOT_OVER)).collect()
}

/// The areas the load must never be over and those the crane may stand in,
/// outlined as [`not_over_outlines`] outlines the first.
fn area_outlines(site: &SiteView, task: &LiftTask) -> Vec<Polyline> {
    let mut lines = not_over_outlines(site, task);
    lines.extend(task.crane_stands_in.iter().map(|a| outline(site, task, &a.corners_m, CRANE_AREA)));
    lines
}

/// A plan polygon on the ground the crane stands on, closed, drawn over
/// everything.
fn outline(site: &SiteView, task: &LiftTask, corners_m: &[[f64; 2]], color: Rgb) -> Polyline {
    let z = task.crane.placement.z_m + 0.05;
    let mut points: Vec<[f32; 3]> = corners_m.iter().map(|c| site.local([c[0], c[1], z])).collect();
    points.extend(points.first().copied());
    Polyline { points, color, width_px: 2.5, on_top: true }
}

/// The circle a mobile crane's superstructure sweeps as it slews
/// ([`liftplan_core::crane::CraneSetup::tail_swing_m`]), on the ground it
/// stands on, drawn over everything.
fn tail_swing_circle(site: &SiteView, task: &LiftTask) -> Option<Polyline> {
    let (r, _) = task.crane.tail_swing_m()?;
    let o = task.crane.slew_center();
    let points = (0..=96)
        .map(|k| {
            let a = k as f64 / 96.0 * std::f64::consts::TAU;
            site.local([o.x + r * a.cos(), o.y + r * a.sin(), o.z + 0.05])
        })
        .collect();
    Some(Polyline { points, color: TAIL_SWING, width_px: 2.0, on_top: true })
}

/// Perspective view at the end of step `n` (1-based) with the path so far.
pub fn step_view(
    site: &SiteView,
    task: &LiftTask,
    plan: &LiftPlan,
    others: &[(Obb, Rgb)],
    n: usize,
    w: u32,
    h: u32,
) -> Image {
    let mut s = site.base_scene(1.5);
    s.triangles.extend(others.iter().map(|(b, colour)| site.obb_batch(b, *colour)));
    let end = plan.moves[n - 1].to;
    s.triangles.extend(crane_batches(site, task, &end));
    let done = load_path(site, task, plan, n);
    let all = load_path(site, task, plan, plan.moves.len());
    s.lines.extend(not_over_outlines(site, task));
    s.lines.push(Polyline { points: all, color: [230, 170, 180], width_px: 2.0, on_top: true });
    s.lines.push(Polyline { points: done, color: PATH, width_px: 3.5, on_top: true });
    // Hot spot: where the validator measured this step's smallest clearance, as
    // a red block on the obstacle with a flag pole drawn over everything, so it
    // is found even when the obstacle hides it.
    if let Some(at) = plan.steps.get(n - 1).and_then(|st| st.clearance_at) {
        let c = nalgebra::Point3::new(at[0], at[1], at[2]);
        s.triangles.push(
            site.obb_batch(&liftplan_core::obb::Obb::axis_aligned(c, nalgebra::Vector3::new(0.3, 0.3, 0.3)), HOT_SPOT),
        );
        let [x, y, z] = site.local(at);
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
                let q = site.local([p.x, p.y, p.z]);
                for i in 0..3 {
                    lo[i] = lo[i].min(q[i]);
                    hi[i] = hi[i].max(q[i]);
                }
            }
        }
    }
    // Down to the ground the crane stands on (a site in survey heights
    // stands far above 0).
    lo[2] = lo[2].min(site.local([0.0, 0.0, task.crane.placement.z_m])[2]);
    // Look from behind-left of the crane towards the work area.
    let mid_swing = 0.5 * (plan.start.swing_rad + plan.set.swing_rad) + task.crane.placement.heading_rad;
    let az = (mid_swing + std::f64::consts::PI + 0.6).to_degrees() as f32;
    let cam = Camera::framing(lo, hi, az, 28.0, 40.0, w as f32 / h as f32);
    site.renderer.render(&s, &cam, w, h, 2)
}

/// Capacity against radius for the lift's boom, the gross load, and the
/// radius every step reads the chart at.
pub fn chart_plot(chart: &ChartConfig, task: &LiftTask, plan: &LiftPlan, w: u32, h: u32) -> Image {
    let mut img = Image::new(w, h, [255, 255, 255]);
    let (ml, mr, mt, mb) = (80.0, 20.0, 20.0, 50.0);
    let boom = task.chart_boom_m();
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
    // Where the chart was read: the radius plus the lift's allowance.
    for st in &plan.steps {
        img.disc(x_of(st.radius_m + task.radius_allowance_m), y_of(g), 5.0, [200, 40, 40]);
    }
    img
}

#[cfg(test)]
mod tests {
    use super::*;
    use liftplan_core::frame::{Point3, Vec3, rot_z};

    /// A site in survey coordinates (a UTM easting and northing, heights
    /// above a datum) is drawn as the same site near the origin: its points
    /// and boxes to well under a millimetre, where `f32` site coordinates
    /// would round them to half a metre.
    #[test]
    fn a_site_in_survey_coordinates_is_drawn_as_finely_as_one_at_the_origin() {
        let near: Vec<[f64; 3]> =
            (0..2000).map(|k| [(k % 50) as f64 * 0.37, (k / 50) as f64 * 0.41, 0.013 * k as f64]).collect();
        let shift = [512_345.0, 5_412_345.0, 102.0];
        let far: Vec<[f64; 3]> = near.iter().map(|p| [p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]]).collect();
        let mut mesh = TriMesh::default();
        let g = mesh.group_id("SLAB");
        mesh.add_box(g, [0.0, 0.0, -0.3], [18.0, 16.0, 0.0]);
        let mut far_mesh = mesh.clone();
        for v in &mut far_mesh.vertices {
            *v = [v[0] + shift[0], v[1] + shift[1], v[2] + shift[2]];
        }
        let a = SiteView::new(render::Renderer::Cpu, mesh, &near, 10_000);
        let b = SiteView::new(render::Renderer::Cpu, far_mesh, &far, 10_000);
        let (da, db) = (a.origin, b.origin);
        assert_eq!([db[0] - da[0], db[1] - da[1], db[2] - da[2]], [shift[0], shift[1], 0.0]);
        let close = |p: [f32; 3], q: [f32; 3]| {
            (p[0] - q[0]).abs() < 1e-4 && (p[1] - q[1]).abs() < 1e-4 && (q[2] - p[2] - 102.0).abs() < 1e-4
        };
        for (p, q) in a.points.iter().zip(&b.points) {
            assert!(close(*p, *q), "{p:?} {q:?}");
        }
        for (p, q) in a.mesh.vertices.iter().zip(&b.mesh.vertices) {
            let f = |v: &[f64; 3]| [v[0] as f32, v[1] as f32, v[2] as f32];
            assert!(close(f(p), f(q)), "{p:?} {q:?}");
        }
        let load = Obb::new(Point3::new(6.3, 4.1, 2.0), rot_z(0.4), Vec3::new(2.0, 1.0, 1.0));
        let mut far_load = load;
        far_load.center += Vec3::new(shift[0], shift[1], shift[2]);
        let (pa, pb) = (a.obb_batch(&load, LOAD).positions, b.obb_batch(&far_load, LOAD).positions);
        for (p, q) in pa.iter().zip(&pb) {
            assert!(close(*p, *q), "{p:?} {q:?}");
        }
    }

    /// The ground no scan saw under the load is drawn as one tile per cell
    /// the plan lists, just above the crane's set-up level, where the cells
    /// are in the site.
    #[test]
    fn unseen_cells_are_tiles_where_the_plan_lists_them() {
        let site =
            SiteView::new(render::Renderer::Cpu, TriMesh::default(), &[[100.0, 200.0, 0.0], [140.0, 260.0, 1.0]], 10);
        let c = liftplan_plan::coverage::Coverage {
            cell_m: 1.0,
            scans: true,
            under_load: liftplan_plan::coverage::Area {
                unscanned_cells: vec![[118, 229], [119, 229]],
                ..Default::default()
            },
            ..Default::default()
        };
        let b = cells_batch(&site, &c, &c.under_load.unscanned_cells, 102.0, UNSEEN);
        assert_eq!((b.positions.len(), b.triangles.len(), b.color), (8, 4, UNSEEN));
        // Under the crane only: none listed here, no tile.
        assert!(cells_batch(&site, &c, &c.under_crane.unscanned_cells, 102.0, UNSEEN_UNDER_CRANE).triangles.is_empty());
        let o = site.origin;
        assert_eq!(b.positions[0], [(118.0 - o[0]) as f32, (229.0 - o[1]) as f32, 102.05]);
        assert_eq!(b.positions[6], [(120.0 - o[0]) as f32, (230.0 - o[1]) as f32, 102.05]);
    }
}
