//! # liftplan-depthmap: stage 4a, the site as multi-level depth maps
//!
//! Rasterises the registered site cloud (points) and the plant mesh (triangles)
//! into one [`mdm::Mdm`] and answers box queries against it ([`query`]): does
//! a box meet an obstacle, and how far can it move straight down or up.
//!
//! | file | what |
//! |---|---|
//! | `site.mdm` | the depth map (liftplan artifact: grid, objects, CSR intervals) |
//! | `depthmap.png` | top view: height of the highest obstacle per cell |
//! | `depthmap.json` | grid, counts, timings |

pub mod dilate;
pub mod gpu;
pub mod mdm;
pub mod picture;
pub mod query;

use liftplan_core::Location;
use liftplan_core::cloud::class;
use liftplan_core::frame::Aabb;
use liftplan_core::mesh::TriMesh;
use liftplan_core::obb::Obb;
use mdm::{GridSpec, Mdm, Mode, Raw};
use serde::{Deserialize, Serialize};
use std::path::Path;

pub const NAME: &str = "depthmap";
pub const VERSION: u32 = 1;

#[derive(Debug, thiserror::Error)]
pub enum DepthError {
    #[error("{0}: {1}")]
    Input(Location, String),
    #[error("[depthmap] {0}")]
    Settings(String),
    #[error("{0}")]
    Gpu(String),
}

pub type Result<T> = std::result::Result<T, DepthError>;

impl From<liftplan_core::las_file::LasFileError> for DepthError {
    fn from(e: liftplan_core::las_file::LasFileError) -> Self {
        use liftplan_core::las_file::LasFileError;
        match e {
            LasFileError::Format(at, why) => DepthError::Input(at, why),
            LasFileError::Io(at, e) => DepthError::Input(at, e.to_string()),
        }
    }
}

/// `[depthmap]` in `liftplan.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// Cell edge (m).
    pub cell_m: f64,
    /// multi | single (2.5D: everything below the top of a cell is occupied).
    pub mode: Mode,
    /// Half height and plan radius each scan point occupies (m).
    pub point_radius_m: f64,
    /// Surface intervals of one object closer than this merge (m).
    pub merge_gap_m: f64,
    /// Plan extent [xmin, ymin, xmax, ymax] (m); empty: all inputs plus `margin_m`.
    pub extent: Vec<f64>,
    pub margin_m: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            cell_m: 0.25,
            mode: Mode::Multi,
            point_radius_m: 0.05,
            merge_gap_m: 0.1,
            extent: vec![],
            margin_m: 10.0,
        }
    }
}

/// Point radii above this many cells are refused: the work per point grows
/// with the square of it.
pub const MAX_POINT_RADIUS_CELLS: f64 = 8.0;

/// Grids above this many cells are refused (a typo in the cell size).
pub const MAX_CELLS: u64 = 64_000_000;

/// The most raw intervals (one for each cell a scan point or a plant
/// triangle covers) a depth map is built from. Assembly holds about 32 bytes
/// for each, so this is about 8 GB; past it the build is refused, naming what
/// to change, instead of running out of memory. A site's raw intervals grow
/// with the square of 1 / `cell_m` (a floor slab covers its area's cells)
/// and with `point_radius_m`; the thesis' largest site (21 M points and a
/// 376k-triangle plant) makes about 36 M.
pub const MAX_RAW_INTERVALS: u64 = 1 << 28;

impl Settings {
    pub fn check(&self) -> std::result::Result<(), String> {
        if !(self.cell_m.is_finite() && self.cell_m >= 0.01) {
            return Err(format!("cell_m must be at least 0.01 m, found {}", self.cell_m));
        }
        if !(self.point_radius_m.is_finite()
            && self.point_radius_m >= 0.0
            && self.merge_gap_m.is_finite()
            && self.merge_gap_m >= 0.0
            && self.margin_m.is_finite()
            && self.margin_m >= 0.0)
        {
            return Err("point_radius_m, merge_gap_m and margin_m must be zero or positive (and finite)".into());
        }
        if self.point_radius_m > MAX_POINT_RADIUS_CELLS * self.cell_m {
            return Err(format!(
                "point_radius_m {} is more than {MAX_POINT_RADIUS_CELLS} cells of {} m: a scan point covering \
                 hundreds of cells is a typo (each point is rasterised into every cell it covers)",
                self.point_radius_m, self.cell_m
            ));
        }
        if !(self.extent.is_empty()
            || (self.extent.len() == 4
                && self.extent.iter().all(|v| v.is_finite())
                && self.extent[0] < self.extent[2]
                && self.extent[1] < self.extent[3]))
        {
            return Err("extent must be [xmin, ymin, xmax, ymax], finite, with min < max".into());
        }
        Ok(())
    }

    /// The grid over `bbox` (site [xmin, ymin, xmax, ymax]) or the configured extent.
    pub fn grid(&self, bbox: [f64; 4]) -> Result<GridSpec> {
        let e = if self.extent.len() == 4 {
            [self.extent[0], self.extent[1], self.extent[2], self.extent[3]]
        } else {
            [bbox[0] - self.margin_m, bbox[1] - self.margin_m, bbox[2] + self.margin_m, bbox[3] + self.margin_m]
        };
        let c = self.cell_m;
        let x0 = (e[0] / c).floor() * c;
        let y0 = (e[1] / c).floor() * c;
        let nx = ((e[2] - x0) / c).ceil().max(1.0);
        let ny = ((e[3] - y0) / c).ceil().max(1.0);
        if !(nx * ny <= MAX_CELLS as f64) {
            return Err(DepthError::Settings(format!(
                "a {nx} x {ny} grid is too large (at most {MAX_CELLS} cells): use a larger cell_m or a smaller extent"
            )));
        }
        Ok(GridSpec { x0, y0, cell: c, nx: nx as u32, ny: ny as u32 })
    }
}

/// The inputs of a depth map, in site coordinates.
#[derive(Default)]
pub struct Inputs {
    pub points: Vec<[f64; 3]>,
    pub ground: Vec<bool>,
    pub mesh: TriMesh,
}

/// Reads the site cloud, dropping points inside `exclude` (e.g. the load at its
/// pick position, which the survey scanned but which must not block its own
/// lift). Returns how many were dropped per box of `exclude` (a point in
/// several counts for the first).
pub fn read_cloud(path: &Path, exclude: &[Obb], into: &mut Inputs) -> Result<Vec<usize>> {
    let mut dropped = vec![0; exclude.len()];
    read_cloud_with(path, exclude, into, |k, _| dropped[k] += 1)?;
    Ok(dropped)
}

/// [`read_cloud`], handing each dropped point to `dropped` with the index of
/// the box of `exclude` that took it (the first that holds it).
pub fn read_cloud_with(
    path: &Path,
    exclude: &[Obb],
    into: &mut Inputs,
    mut dropped: impl FnMut(usize, [f64; 3]),
) -> Result<()> {
    // The scans stage wrote it, but a file on disk proves nothing of what it
    // asks for: it is read as a survey's scan is, its structure checked
    // before the `las` and `laz` crates trust it (they panic, or allocate
    // what a header field says, on a damaged file), each call into them
    // guarded, every coordinate finite and every point the header declares
    // there (a cloud cut short would leave obstacles out unsaid).
    let declared = liftplan_core::las_file::precheck(path)?.points;
    let mut r = guarded(Location::file(path), "the LAS/LAZ reader", || {
        las::Reader::from_path(path)
            .map_err(|e| DepthError::Input(Location::file(path), format!("cannot read LAS header: {e}")))
    })?;
    let mut data = las::PointDataBuilder::new().for_header(r.header()).build();
    let mut seen = 0u64;
    loop {
        let place = || Location::item(path, format!("point {seen}"));
        let n = guarded(place(), "the LAS/LAZ point reader", || {
            r.fill_points(1 << 20, &mut data).map_err(|e| {
                DepthError::Input(
                    place(),
                    format!("cannot decode points after {seen} of the {declared} the header declares: {e}"),
                )
            })
        })?;
        if n == 0 {
            break;
        }
        for (i, ((x, y), (z, c))) in data.x().zip(data.y()).zip(data.z().zip(data.classification())).enumerate() {
            if !(x.is_finite() && y.is_finite() && z.is_finite()) {
                return Err(DepthError::Input(
                    Location::item(path, format!("point {}", seen + i as u64)),
                    format!("coordinate is not a finite number: {:?}", [x, y, z]),
                ));
            }
            let p = liftplan_core::frame::Point3::new(x, y, z);
            if let Some(k) = exclude.iter().position(|b| b.contains(&p)) {
                dropped(k, [x, y, z]);
                continue;
            }
            into.points.push([x, y, z]);
            into.ground.push(c == class::GROUND);
        }
        seen += n;
    }
    if seen < declared {
        return Err(DepthError::Input(
            Location::file(path),
            format!("header declares {declared} points but the data ends after {seen} (truncated file)"),
        ));
    }
    Ok(())
}

/// Runs a call into the `las` and `laz` crates through the guard: a panic
/// inside them is an error at `place`.
fn guarded<T>(place: Location, what: &str, read: impl FnOnce() -> Result<T>) -> Result<T> {
    liftplan_core::guard::run_reader(what, read).unwrap_or_else(|why| Err(DepthError::Input(place, why)))
}

/// Builds the depth map on the CPU.
pub fn build_cpu(inp: &Inputs, s: &Settings) -> Result<(Mdm, Timings)> {
    build(inp, s, None)
}

/// Builds the depth map, assembled on `gpu` when given (the triangles are
/// clipped to cells on the CPU either way).
pub fn build(inp: &Inputs, s: &Settings, gpu: Option<&gpu::Gpu>) -> Result<(Mdm, Timings)> {
    let t0 = std::time::Instant::now();
    s.check().map_err(DepthError::Settings)?;
    if inp.ground.len() != inp.points.len() {
        return Err(DepthError::Settings(format!(
            "{} points but {} ground flags: each point needs one",
            inp.points.len(),
            inp.ground.len()
        )));
    }
    let bb = points_bbox(&inp.points)
        .map_err(|k| {
            DepthError::Settings(format!(
                "site point {k} has a coordinate that is not a finite number: {:?}",
                inp.points[k]
            ))
        })?
        .union(&inp.mesh.bbox());
    if bb.is_empty() {
        return Err(DepthError::Settings("nothing to rasterise: no site cloud and no plant mesh".into()));
    }
    let spec = s.grid([bb.min[0], bb.min[1], bb.max[0], bb.max[1]])?;
    let mut objects = vec!["ground (scan)".to_string(), "scanned structure".to_string()];
    objects.extend(inp.mesh.groups.iter().cloned());
    let points = mdm::PointSource { xyz: &inp.points, ground: &inp.ground, radius: s.point_radius_m as f32 };
    check_raw_intervals(&points, &inp.mesh, &spec, s)?;
    let t_prep = t0.elapsed();
    let gap = s.merge_gap_m as f32;
    if let Some(g) = gpu {
        // Triangles are clipped on the CPU (in f64); the device takes their
        // raw intervals through the same passes as the points.
        let mesh: Vec<Raw> = mdm::mesh_raws(&inp.mesh, &spec, 2).into_iter().flatten().collect();
        let t_gen = t0.elapsed();
        let cells = g.assemble(Some(&points), &mesh, &spec, s.mode, gap).map_err(DepthError::Gpu)?;
        let m = Mdm::from_cells(spec, s.mode, &cells.counts, cells.intervals, cells.tops, objects);
        let t_all = t0.elapsed();
        let timings = Timings {
            prepare_ms: ms(t_prep),
            points_ms: 0.0,
            triangles_ms: ms(t_gen - t_prep),
            assemble_ms: ms(t_all - t_gen),
            total_ms: ms(t_all),
            raw_intervals: cells.raws,
            gpu: Some(cells.timings),
        };
        return Ok((m, timings));
    }
    // On the CPU the point pass is fused into the assembly (no raw intervals
    // are stored for points).
    let t_points = t0.elapsed();
    let raws = mdm::mesh_jobs(&inp.mesh, &spec, 2);
    let t_gen = t0.elapsed();
    let m = mdm::assemble_sources(Some(points), &raws, spec, s.mode, gap, objects);
    let t_all = t0.elapsed();
    Ok((
        m,
        Timings {
            prepare_ms: ms(t_prep),
            points_ms: ms(t_points - t_prep),
            triangles_ms: ms(t_gen - t_points),
            assemble_ms: ms(t_all - t_gen),
            total_ms: ms(t_all),
            raw_intervals: raws.iter().map(mdm::RawJob::len).sum(),
            gpu: None,
        },
    ))
}

/// Refuses a map that would be built from more than [`MAX_RAW_INTERVALS`]
/// raw intervals. Cheap bounds first; the counts only when they do not
/// settle it.
fn check_raw_intervals(points: &mdm::PointSource, mesh: &TriMesh, spec: &GridSpec, s: &Settings) -> Result<()> {
    let bounds = mdm::point_cells_bound(points, spec).saturating_add(mdm::mesh_cells_bound(mesh, spec));
    if bounds <= MAX_RAW_INTERVALS {
        return Ok(());
    }
    let (from_points, from_mesh) = (mdm::point_cells(points, spec), mdm::mesh_cells(mesh, spec));
    if from_points + from_mesh <= MAX_RAW_INTERVALS {
        return Ok(());
    }
    Err(DepthError::Settings(format!(
        "the depth map would be built from {} raw intervals ({from_points} from scan points, {from_mesh} from plant \
         triangles), more than it may hold ({MAX_RAW_INTERVALS}, about 8 GB): use a larger cell_m (now {} m){}",
        from_points + from_mesh,
        s.cell_m,
        if from_points > from_mesh {
            format!(" or a smaller point_radius_m (now {} m)", s.point_radius_m)
        } else {
            String::new()
        }
    )))
}

/// The points' bounding box, computed in parallel (it is a pass over every
/// point); or the index of the first point with a coordinate that is not a
/// finite number, which no grid cell can hold.
fn points_bbox(points: &[[f64; 3]]) -> std::result::Result<Aabb, usize> {
    use rayon::prelude::*;
    const CHUNK: usize = 1 << 16;
    points
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut b = Aabb::empty();
            for (k, p) in chunk.iter().enumerate() {
                if !(p[0].is_finite() && p[1].is_finite() && p[2].is_finite()) {
                    return Err(c * CHUNK + k);
                }
                b.grow(*p);
            }
            Ok(b)
        })
        .reduce(
            || Ok(Aabb::empty()),
            |a, b| match (a, b) {
                (Err(x), Err(y)) => Err(x.min(y)),
                (Err(x), _) | (_, Err(x)) => Err(x),
                (Ok(a), Ok(b)) => Ok(a.union(&b)),
            },
        )
}

fn ms(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1000.0
}

#[derive(Debug, Clone, Default, Serialize)]
pub struct Timings {
    pub prepare_ms: f64,
    pub points_ms: f64,
    pub triangles_ms: f64,
    pub assemble_ms: f64,
    pub total_ms: f64,
    pub raw_intervals: usize,
    /// The GPU assembly's parts, when it ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gpu: Option<gpu::GpuTimings>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    pub grid: GridSpec,
    pub mode: Mode,
    pub points: usize,
    pub points_excluded: usize,
    pub triangles: usize,
    pub intervals: usize,
    pub occupied_cells: usize,
    pub objects: usize,
    pub backend: String,
    pub timings: Timings,
}

impl Summary {
    pub fn lines(&self) -> Vec<String> {
        let mut lines = vec![format!(
            "{} x {} cells of {} m ({:?}), {} intervals in {} cells from {} points and {} triangles ({} ms on {})",
            self.grid.nx,
            self.grid.ny,
            self.grid.cell,
            self.mode,
            self.intervals,
            self.occupied_cells,
            self.points,
            self.triangles,
            self.timings.total_ms.round(),
            self.backend
        )];
        if self.points_excluded > 0 {
            lines.push(format!(
                "{} scan points taken for the loads at their pick positions, left out",
                self.points_excluded
            ));
        }
        lines
    }
}

pub use liftplan_core::gpu::GpuUse;

/// Runs the stage: `cloud` (site.laz) and `mesh` (plant.mesh) may each be absent.
pub fn run(
    cloud: Option<&Path>,
    mesh: Option<&Path>,
    exclude: &[Obb],
    s: &Settings,
    gpu_use: GpuUse,
    out_dir: &Path,
) -> Result<Summary> {
    s.check().map_err(DepthError::Settings)?;
    let mut inp = Inputs::default();
    let mut excluded = 0;
    if let Some(c) = cloud {
        excluded = read_cloud(c, exclude, &mut inp)?.iter().sum();
    }
    if let Some(m) = mesh {
        inp.mesh = TriMesh::read_artifact(m).map_err(|e| DepthError::Input(Location::file(m), e.to_string()))?;
    }
    // `auto` means "the GPU where it can": a device that does not start, or a
    // map it refuses (a row over its buffers), leaves the map to the CPU,
    // which builds the same one.
    let on_gpu = |d| -> Result<(Mdm, Timings, String)> {
        let g = gpu::Gpu::new(d).map_err(DepthError::Gpu)?;
        let (m, timings) = build(&inp, s, Some(&g))?;
        Ok((m, timings, format!("gpu: {}", g.name())))
    };
    let on_cpu = || build(&inp, s, None).map(|(m, timings)| (m, timings, "cpu".to_string()));
    let (m, timings, backend) = match liftplan_core::gpu::open_for(gpu_use, "depth map").map_err(DepthError::Gpu)? {
        None => on_cpu()?,
        Some(d) => match on_gpu(d) {
            Err(DepthError::Gpu(why)) if gpu_use == GpuUse::Auto => {
                tracing::warn!("depth map on the CPU: the GPU could not build it: {why}");
                on_cpu()?
            }
            built => built?,
        },
    };
    std::fs::create_dir_all(out_dir).map_err(|e| DepthError::Input(Location::file(out_dir), e.to_string()))?;
    m.write(&out_dir.join("site.mdm"))
        .map_err(|e| DepthError::Input(Location::file(out_dir.join("site.mdm")), e.to_string()))?;
    picture::top_view(&m, 1400)
        .write_png(&out_dir.join("depthmap.png"))
        .map_err(|e| DepthError::Input(Location::file(out_dir.join("depthmap.png")), e.to_string()))?;
    let summary = Summary {
        grid: m.spec,
        mode: m.mode,
        points: inp.points.len(),
        points_excluded: excluded,
        triangles: inp.mesh.triangle_count(),
        intervals: m.intervals.len(),
        occupied_cells: m.offsets.windows(2).filter(|w| w[1] > w[0]).count(),
        objects: m.objects.len(),
        backend,
        timings,
    };
    let json = serde_json::to_string_pretty(&summary).unwrap_or_default();
    liftplan_core::artifact::write_atomic(&out_dir.join("depthmap.json"), json.as_bytes())
        .map_err(|e| DepthError::Input(Location::file(out_dir), e.to_string()))?;
    Ok(summary)
}

/// `liftplan inspect` of an MDM file.
pub fn inspect(path: &Path) -> Result<serde_json::Value> {
    let m = Mdm::read(path).map_err(|e| DepthError::Input(Location::file(path), e.to_string()))?;
    let tops: Vec<f32> = m.pyramid[0].2.iter().copied().filter(|v| v.is_finite()).collect();
    Ok(serde_json::json!({
        "kind": "depthmap",
        "format": "mdm",
        "file": path.display().to_string(),
        "grid": m.spec,
        "mode": m.mode,
        "intervals": m.intervals.len(),
        "occupied_cells": tops.len(),
        "max_intervals_per_cell": m.offsets.windows(2).map(|w| w[1] - w[0]).max().unwrap_or(0),
        "highest_m": tops.iter().copied().fold(f32::NEG_INFINITY, f32::max),
        "objects": m.objects.len(),
        "bbox": [m.spec.x0, m.spec.y0, m.spec.x0 + m.spec.cell * m.spec.nx as f64, m.spec.y0 + m.spec.cell * m.spec.ny as f64],
    }))
}
