//! # liftplan-docs: stage 6, pictures and the lift plan PDF
//!
//! For each planned lift: a site overview (top view), one perspective picture
//! per step, the load chart plot and the C-space picture from the plan stage,
//! laid out in `<lift>.pdf` for the engineer who signs it and the crew who
//! executes it. Reads `plan.json`; plans nothing and checks nothing itself.
//!
//! | file | what |
//! |---|---|
//! | `<lift>.pdf` | the lift plan document |
//! | `<lift>.overview.png` | top view of the site, crane, load path |
//! | `<lift>.chart.png` | capacity against radius with the lift's radii |

pub mod gpu;
pub mod pdf;
pub mod pictures;
pub mod render;
mod report;
pub mod rigging;

use liftplan_core::Location;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

pub const NAME: &str = "docs";
pub const VERSION: u32 = 1;

#[derive(Debug, thiserror::Error)]
pub enum DocsError {
    #[error("{0}: {1}")]
    Input(Location, String),
    #[error("[docs] {0}")]
    Other(String),
}

pub type Result<T> = std::result::Result<T, DocsError>;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Paper {
    #[default]
    A4,
    Letter,
}

/// `[docs]` in `liftplan.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    pub paper: Paper,
    /// One page per step with its picture.
    pub step_pictures: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings { paper: Paper::A4, step_pictures: true }
    }
}

/// What the documents are made from.
pub struct Inputs {
    pub project: String,
    /// Issue date, YYYY-MM-DD.
    pub date: String,
    pub tasks: Vec<liftplan_core::lift::LiftTask>,
    pub plan_json: PathBuf,
    pub mesh: Option<PathBuf>,
    pub cloud: Option<PathBuf>,
    pub capacity_csv: Option<PathBuf>,
    /// Folder holding `<lift>.cspace.png` from the plan stage.
    pub plan_dir: PathBuf,
    /// Lines describing the inputs (scans and registration, plant, chart).
    pub input_lines: Vec<String>,
    /// Input files and their blake3 hashes (short).
    pub input_hashes: Vec<(String, String)>,
    /// Scans that did not register and were left out of the site cloud
    /// (`[scans] on_unregistered = "exclude"`), by name, and how many scans
    /// there were in all.
    pub scans_left_out: (Vec<String>, usize),
    /// Scans merged with a warning from registration: each one's name and
    /// the warning's words (its line on the inputs page and the sign-off
    /// page give them).
    pub scans_warned: Vec<(String, String)>,
    /// Files among the scans (or scans in them) passed by as holding no
    /// scan, each with why, as the scans stage's `registration.json` lists
    /// them.
    pub scans_passed_by: Vec<String>,
    /// Files in the scans, plant and charts folders that no stage reads,
    /// each with why (a scan or a model in a format not read, a chart as a
    /// PDF); the last may count those not named ("and 4 more files").
    pub inputs_not_read: Vec<String>,
    /// Where the scanner did not level itself (`[scans.registration]
    /// leveled = false`) and the reference scan was levelled by its ground
    /// or not at all: its name and how its line says it was levelled.
    pub site_level_unconfirmed: Option<(String, String)>,
    /// Lifts of a luffing crane whose chart configuration has one capacity
    /// column, not one per boom length, with the boom length the chart must
    /// be for (the charts stage's `one_column_for_boom_m`).
    pub one_column_charts: Vec<(String, f64)>,
    /// What reading each chart configuration warned of (a value read from
    /// text, a footnote mark dropped, a column broken between two
    /// capacities), by configuration name.
    pub chart_warnings: Vec<(String, Vec<String>)>,
    /// The wind speeds each chart configuration's sheet states, by name.
    pub chart_wind: Vec<(String, Vec<liftplan_core::capacity::StatedOnChart>)>,
    /// The obstacles placed by hand in the project file, which the plan
    /// was made against.
    pub obstacles: Vec<liftplan_core::obstacle::Obstacle>,
    /// The overhead power lines the project gives, which the plan kept its
    /// approach distance off.
    pub power_lines: Vec<liftplan_core::power_line::PowerLine>,
    /// For each lift that resumes a plan it names (`resumes_plan`), by id:
    /// whether `resume_from` is where that plan has the load, for the
    /// cover.
    pub resume_checks: Vec<(String, liftplan_plan::resumed::Agreement)>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    pub documents: Vec<String>,
    pub pages: Vec<usize>,
    pub seconds: f64,
    /// Which rasteriser drew the pictures ("cpu" or "gpu: <adapter>").
    pub renderer: String,
}

impl Summary {
    pub fn lines(&self) -> Vec<String> {
        let mut lines: Vec<String> =
            self.documents.iter().zip(&self.pages).map(|(d, p)| format!("{d}: {p} pages")).collect();
        lines.push(format!("pictures drawn by the {} renderer", self.renderer));
        lines
    }
}

/// Today's date (UTC) as YYYY-MM-DD.
pub fn today() -> String {
    let days =
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_secs() / 86_400).unwrap_or(0)
            as i64;
    day(days)
}

/// A time given in seconds since 1970 (UTC) as YYYY-MM-DD HH:MM UTC.
pub fn date_utc(unix_s: u64) -> String {
    let minutes = unix_s % 86_400 / 60;
    format!("{} {:02}:{:02} UTC", day((unix_s / 86_400) as i64), minutes / 60, minutes % 60)
}

/// Day `days` since 1970-01-01 as YYYY-MM-DD.
fn day(days: i64) -> String {
    // Civil from days (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}

fn io(p: &Path, e: impl std::fmt::Display) -> DocsError {
    DocsError::Input(Location::file(p), e.to_string())
}

/// Renders every lift's document.
/// Pictures use the GPU twin of the rasteriser as `gpu_use` says.
pub fn run(inp: &Inputs, s: &Settings, gpu_use: liftplan_core::gpu::GpuUse, out_dir: &Path) -> Result<Summary> {
    let t0 = std::time::Instant::now();
    let text = std::fs::read_to_string(&inp.plan_json).map_err(|e| io(&inp.plan_json, e))?;
    #[derive(Deserialize)]
    struct PlanFile {
        lifts: Vec<liftplan_plan::LiftPlan>,
    }
    let plans: PlanFile = serde_json::from_str(&text).map_err(|e| io(&inp.plan_json, e))?;
    let mesh = match &inp.mesh {
        Some(p) => liftplan_core::mesh::TriMesh::read_artifact(p).map_err(|e| io(p, e))?,
        None => liftplan_core::mesh::TriMesh::default(),
    };
    let points = match &inp.cloud {
        Some(p) => read_points(p)?,
        None => vec![],
    };
    let renderer = render::Renderer::choose(gpu_use).map_err(DocsError::Other)?;
    let renderer_name = renderer.name();
    let site = pictures::SiteView::new(renderer, mesh, &points, 300_000);
    let charts = match &inp.capacity_csv {
        Some(p) => Some(liftplan_core::capacity::CapacityTable::read_csv(p).map_err(|e| io(p, e))?),
        None => None,
    };
    std::fs::create_dir_all(out_dir).map_err(|e| io(out_dir, e))?;
    let mut summary = Summary { documents: vec![], pages: vec![], seconds: 0.0, renderer: renderer_name };
    for plan in &plans.lifts {
        let Some(task) = inp.tasks.iter().find(|t| t.id == plan.lift) else {
            return Err(DocsError::Other(format!(
                "plan.json has lift '{}' which the project no longer defines; rerun the plan stage",
                plan.lift
            )));
        };
        // Step n is drawn with move n, under its words: a plan whose steps
        // are not one a move in order, each in its move's words, is not
        // drawn at all.
        if let Some(problem) = plan.steps_not_as_written(task) {
            return Err(io(&inp.plan_json, format!("lift '{}': {problem}; rerun the plan stage", plan.lift)));
        }
        let chart = charts.as_ref().and_then(|c| c.config(&task.chart_config).ok());
        let cspace_png = inp.plan_dir.join(format!("{}.cspace.png", task.id));
        // No picture where the plan stage drew none; one it cannot read is
        // an error naming it, not a page left without it unsaid.
        let cspace = match std::fs::read(&cspace_png) {
            Ok(b) => Some(liftplan_core::image::Image::decode_png(&b).map_err(|e| io(&cspace_png, e))?),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
            Err(e) => return Err(io(&cspace_png, e)),
        };
        let (bytes, pages, overview, chart_img) = report::document(inp, s, &site, task, plan, chart, cspace.as_ref())?;
        let name = format!("{}.pdf", task.id);
        liftplan_core::artifact::write_atomic(&out_dir.join(&name), &bytes).map_err(|e| io(&out_dir.join(&name), e))?;
        overview.write_png(&out_dir.join(format!("{}.overview.png", task.id))).map_err(|e| io(out_dir, e))?;
        if let Some(c) = chart_img {
            c.write_png(&out_dir.join(format!("{}.chart.png", task.id))).map_err(|e| io(out_dir, e))?;
        }
        summary.documents.push(name);
        summary.pages.push(pages);
    }
    summary.seconds = t0.elapsed().as_secs_f64();
    Ok(summary)
}

fn read_points(path: &Path) -> Result<Vec<[f64; 3]>> {
    liftplan_plan::read_points(path, &[]).map(|(p, _, _)| p).map_err(|e| io(path, e))
}
