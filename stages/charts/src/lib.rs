//! # liftplan-charts: stage 3, load charts to capacity tables
//!
//! Reads the crane rental's load charts (xlsx, xlsm, xlsb, xls, ods) with
//! `calamine`, finds the chart grids in them ([`detect`]) or follows an explicit
//! mapping, and writes:
//!
//! | file | what |
//! |---|---|
//! | `capacity.csv` | config, boom_m, radius_m, capacity_kg, cell: every permitted chart cell in kg and m |
//! | `chart.json` | per configuration: file, sheet, range, grid size, units found, warnings |
//! | `lifts.json` | per lift: gross load, capacity and utilisation at pick and set, the radial ranges the chart permits, critical flag (read back by [`recorded`]) |
//!
//! Numbers a chart holds as text are read with the decimal mark their grid
//! shows ([`decimals`]); a radius or boom length may carry its unit in the
//! cell ("3,0 m", [`sheet::length_and_unit`]), which names the axis' unit
//! where the labels do not and must agree with it where they do. A cell
//! whose value the workbook does not truly hold is refused, not read as
//! empty: an xlsx formula with no value stored, or any formula of a workbook
//! that asks to be calculated when opened (programs that write workbooks
//! without calculating them store 0); a capacity showing a broken formula's
//! error (`#REF!`). Every value keeps the `sheet!cell` it came from, so
//! the lift plan can quote the chart row it relied on. The capacity rule itself (never interpolate upwards)
//! lives in `liftplan_core::capacity`.
//!
//! `capacity.csv` depends only on the charts; `lifts.json` also on the lifts, so
//! a changed load mass changes `lifts.json` and leaves stages that read only the
//! capacity table fresh.

pub mod container;
pub mod decimals;
pub mod detect;
pub mod error;
pub mod recorded;
pub mod sheet;
pub mod stated;

use error::{ChartError, Result};
use liftplan_core::Location;
use liftplan_core::capacity::{CapacityTable, ChartConfig};
use liftplan_core::lift::{CapacityCheck, ChartLimits, LiftTask};
use liftplan_core::location::cell_ref;
use liftplan_core::units::{LengthUnit, MassUnit};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

pub const NAME: &str = "charts";
pub const VERSION: u32 = 1;
pub const EXTS: &[&str] = &["xlsx", "xlsm", "xlsb", "xls", "ods"];

/// An explicit description of one chart grid, for layouts detection gets wrong.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableMapping {
    /// Workbook file name in the charts folder.
    pub file: String,
    pub sheet: String,
    /// Configuration name lifts refer to.
    pub config: String,
    /// Cells holding the values across, e.g. "C6:P6" (boom lengths, or radii
    /// when `transposed`).
    pub across: String,
    /// Cells holding the values down, e.g. "B7:B45".
    pub down: String,
    #[serde(default)]
    pub transposed: bool,
    pub length_unit: Option<LengthUnit>,
    pub capacity_unit: Option<MassUnit>,
}

/// `[charts]` in `liftplan.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// Explicit grids; a sheet named here is not searched automatically.
    pub table: Vec<TableMapping>,
    /// Length unit of the grids whose labels name none (and whose mapping
    /// does not say). Without it such a grid is refused.
    pub length_unit: Option<LengthUnit>,
    /// Capacity unit of the grids whose labels name none (and whose mapping
    /// does not say). Without it such a grid is refused.
    pub capacity_unit: Option<MassUnit>,
}

/// Parses "C6:P6" into ((row0, col0), (row1, col1)).
pub use liftplan_core::location::parse_cell_range as parse_range;

/// One configuration found, for `chart.json`.
#[derive(Debug, Clone, Serialize)]
pub struct ConfigReport {
    pub name: String,
    pub file: String,
    pub sheet: String,
    pub range: String,
    pub transposed: bool,
    pub boom_lengths: usize,
    /// One capacity column that holds for any boom (a tower crane's jib).
    pub any_boom: bool,
    pub radii: usize,
    pub permitted_cells: usize,
    pub units: detect::Units,
    pub title: String,
    pub warnings: Vec<String>,
    /// The wind speeds (m/s) and counterweights (kg) its sheet states in
    /// words beside the grid ([`stated`]); the wind speeds, where it states
    /// none, those the workbook's sheets of notes (sheets without a grid)
    /// state.
    pub wind_ms: Vec<liftplan_core::capacity::StatedOnChart>,
    pub counterweight_kg: Vec<liftplan_core::capacity::StatedOnChart>,
}

impl ConfigReport {
    /// What its sheet states in words, for the run's line: "; states wind
    /// 9.8 m/s (A51), counterweight 140 t (A3)", cells on its own sheet
    /// without its name ("Notes!A4" on a sheet of notes); empty where it
    /// states neither.
    pub fn stated_said(&self) -> String {
        let own = format!("{}!", self.sheet);
        let cell = |c: &str| c.strip_prefix(&own).unwrap_or(c).to_string();
        let wind = self.wind_ms.iter().map(|w| format!("wind {:.1} m/s ({})", w.value, cell(&w.cell)));
        let cw =
            self.counterweight_kg.iter().map(|c| format!("counterweight {} t ({})", c.value / 1000.0, cell(&c.cell)));
        let all: Vec<String> = wind.chain(cw).collect();
        if all.is_empty() { String::new() } else { format!("; states {}", all.join(", ")) }
    }

    /// The chart's columns: "12 booms", or one column for any boom or jib.
    pub fn columns_said(&self) -> String {
        if self.any_boom { "one column (any boom or jib)".to_string() } else { format!("{} booms", self.boom_lengths) }
    }
}

fn grid_from_mapping(path: &Path, m: &TableMapping) -> Result<detect::Grid> {
    let bad = |what: &str| {
        ChartError::Format(Location::cell(path, &m.sheet, what), format!("not a cell range like 'C6:P6': '{what}'"))
    };
    let (a0, a1) = parse_range(&m.across).ok_or_else(|| bad(&m.across))?;
    let (d0, d1) = parse_range(&m.down).ok_or_else(|| bad(&m.down))?;
    if a0.0 != a1.0 {
        return Err(ChartError::Format(
            Location::cell(path, &m.sheet, &m.across),
            "the 'across' range must be one row".into(),
        ));
    }
    if d0.1 != d1.1 {
        return Err(ChartError::Format(
            Location::cell(path, &m.sheet, &m.down),
            "the 'down' range must be one column".into(),
        ));
    }
    Ok(detect::Grid {
        header_row: a0.0,
        value_cols: (a0.1..=a1.1).collect(),
        label_col: d0.1,
        rows: (d0.0..=d1.0).collect(),
        transposed: m.transposed,
        boom_independent: false,
        title: m.config.clone(),
    })
}

/// Reads one workbook: its configurations and what was found.
pub fn read_chart(path: &Path, s: &Settings) -> Result<(Vec<ChartConfig>, Vec<ConfigReport>)> {
    read_chart_with(path, s, Unnamed::Refuse)
}

/// What [`read_chart_with`] does with a grid whose labels name no unit
/// (and which neither its mapping nor `[charts]` gives one).
#[derive(Clone, Copy, PartialEq)]
enum Unnamed {
    /// Refuse it: what a plan reads.
    Refuse,
    /// Read it as metres and tonnes, saying so: what `inspect` shows
    /// (`[charts]` units are not applied).
    Show,
}

fn read_chart_with(path: &Path, s: &Settings, unnamed: Unnamed) -> Result<(Vec<ChartConfig>, Vec<ConfigReport>)> {
    let sheets = sheet::read_workbook(path)?;
    let file_name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    // A table naming a sheet the workbook does not have (a typo) would be
    // passed by without a word, and the sheet it meant searched instead:
    // the layout the engineer described, and its units, not taken.
    let names_a_sheet = |t: &TableMapping| sheets.iter().any(|sh| sh.name == sheet::sheet_name_kept(&t.sheet));
    if let Some(m) = s.table.iter().find(|t| t.file == file_name && !names_a_sheet(t)) {
        let names: Vec<String> = sheets.iter().map(|sh| format!("'{}'", sh.name)).collect();
        return Err(ChartError::Format(
            Location::file(path),
            format!(
                "[[charts.table]] '{}' names sheet '{}', which this workbook does not have (its sheets: {})",
                m.config,
                m.sheet,
                names.join(", ")
            ),
        ));
    }
    let mut configs = Vec::new();
    let mut reports = Vec::new();
    let mut not_searched = Vec::new();
    // The grids of every sheet first, so that a footnote can be looked for
    // on the sheets that hold none (a sheet of notes).
    let mut sheet_grids: Vec<Vec<(detect::Grid, Option<&TableMapping>)>> = Vec::with_capacity(sheets.len());
    for sh in &sheets {
        let mapped: Vec<&TableMapping> =
            s.table.iter().filter(|t| t.file == file_name && sheet::sheet_name_kept(&t.sheet) == sh.name).collect();
        let mut grids: Vec<(detect::Grid, Option<&TableMapping>)> = Vec::new();
        if mapped.is_empty() && sh.cells.len() > detect::MAX_SEARCHED_CELLS {
            tracing::warn!(
                "{}: sheet '{}' has {} cells, more than a chart grid is searched in ({}); describe its grid with \
                 [[charts.table]] if it holds one",
                path.display(),
                sh.name,
                sh.cells.len(),
                detect::MAX_SEARCHED_CELLS
            );
            not_searched.push(format!("'{}' ({} cells)", sh.name, sh.cells.len()));
        } else if mapped.is_empty() {
            let found = detect::find_grids(sh)
                .map_err(|(cell, msg)| ChartError::Format(Location::cell(path, &sh.name, &cell), msg))?;
            grids.extend(found.into_iter().map(|g| (g, None)));
        } else {
            for m in mapped {
                grids.push((grid_from_mapping(path, m)?, Some(m)));
            }
        }
        sheet_grids.push(grids);
    }
    let notes: Vec<&sheet::Sheet> = sheets
        .iter()
        .zip(&sheet_grids)
        .filter(|(sh, grids)| grids.is_empty() && sh.cells.len() <= detect::MAX_SEARCHED_CELLS)
        .map(|(sh, _)| sh)
        .collect();
    let note_sheets = detect::NoteSheets::new(notes.iter().copied());
    // The wind speeds the sheets of notes state, each once, for the grids
    // whose own region states none.
    let mut notes_wind: Vec<liftplan_core::capacity::StatedOnChart> = Vec::new();
    for sh in &notes {
        for w in stated::on_sheet(sh, 0..=u32::MAX, 0..=u32::MAX).wind_ms {
            stated::keep_once(&mut notes_wind, w);
        }
    }
    for (sh, grids) in sheets.iter().zip(&sheet_grids) {
        let own_notes = detect::LazyNotes::new(sh);
        let single = grids.len() == 1;
        for (k, (g, mapping)) in grids.iter().enumerate() {
            let (rows, cols) = stated_region(grids, k);
            let stated = stated::on_sheet(sh, rows, cols);
            let name = match mapping {
                Some(m) => m.config.clone(),
                None if single => sh.name.clone(),
                None if !g.title.is_empty() => format!("{} / {}", sh.name, g.title),
                None => format!("{} #{}", sh.name, k + 1),
            };
            let mut units = detect::units(sh, g)
                .map_err(|(cell, msg)| ChartError::Format(Location::cell(path, &sh.name, &cell), msg))?;
            if let Some(m) = mapping {
                if let Some(l) = m.length_unit {
                    units.radius = l;
                    units.boom = l;
                    units.length_named = true;
                }
                if let Some(c) = m.capacity_unit {
                    units.capacity = c;
                    units.capacity_named = true;
                }
            }
            if unnamed == Unnamed::Show {
                show_unnamed(&mut units);
            } else {
                units_from_settings(&mut units, s).map_err(|what| {
                    ChartError::Format(
                        Location::cell(path, &sh.name, &cell_ref(g.header_row, g.label_col)),
                        format!(
                            "no {what} unit found around the chart grid at {}: its labels must name it, or say it \
                         with [charts] {}",
                            g.range(),
                            if what == "length" {
                                "length_unit = \"m\" (or \"ft\")"
                            } else {
                                "capacity_unit = \"t\" (or \"kg\", \"lb\", \"kips\", \"shortton\", \"kN\", \"daN\")"
                            }
                        ),
                    )
                })?;
            }
            let mut warnings = Vec::new();
            let c = detect::read_grid(sh, g, &units, &file_name, &name, (&own_notes, &note_sheets), &mut warnings)
                .map_err(|(cell, msg)| {
                    let cell = cell.split_once('!').map(|x| x.1.to_string()).unwrap_or(cell);
                    ChartError::Format(Location::cell(path, &sh.name, &cell), msg)
                })?;
            reports.push(ConfigReport {
                name: name.clone(),
                file: file_name.clone(),
                sheet: sh.name.clone(),
                range: g.range(),
                transposed: g.transposed,
                boom_lengths: c.boom_lengths_m.len(),
                any_boom: c.boom_independent(),
                radii: c.radii_m.len(),
                permitted_cells: c.cells.iter().filter(|x| x.is_some()).count(),
                units,
                title: g.title.clone(),
                warnings,
                wind_ms: if stated.wind_ms.is_empty() { notes_wind.clone() } else { stated.wind_ms },
                counterweight_kg: stated.counterweight_kg,
            });
            configs.push(c);
        }
    }
    if configs.is_empty() {
        let skipped = if not_searched.is_empty() {
            String::new()
        } else {
            format!(
                "; not searched, as larger than any chart (over {} cells): sheet {}",
                detect::MAX_SEARCHED_CELLS,
                not_searched.join(", ")
            )
        };
        return Err(ChartError::Format(
            Location::file(path),
            format!(
                "no load-chart grid found: expected boom lengths across a row and radii down the column left of \
                 them (or describe the grid with [[charts.table]]){skipped}"
            ),
        ));
    }
    Ok((configs, reports))
}

/// The last row of a grid (its header's where it has no rows).
fn grid_last_row(g: &detect::Grid) -> u32 {
    *g.rows.last().unwrap_or(&g.header_row)
}

fn grid_last_col(g: &detect::Grid) -> u32 {
    *g.value_cols.last().unwrap_or(&g.label_col)
}

/// The rows and columns of a sheet whose words are the `k`th grid's own
/// ([`stated::on_sheet`]). Its rows: its title's just above its header
/// ([`TITLE_ROWS`]), its own, and the notes under it down to the title of
/// the next grid below it (from the sheet's top where none is above it, to
/// its end where none is below). Its columns: from the column after the
/// grid beside it on its left (its title and labels lie left of its
/// numbers) to its own last column where another stands beside it on its
/// right, else the whole sheet's width. Side by side, each grid's title and
/// notes are then its own, not also its neighbour's.
fn stated_region(
    grids: &[(detect::Grid, Option<&TableMapping>)],
    k: usize,
) -> (std::ops::RangeInclusive<u32>, std::ops::RangeInclusive<u32>) {
    let g = &grids[k].0;
    // Beside it: sharing rows, in other columns.
    let beside = |o: &detect::Grid| {
        title_from(o) <= grid_last_row(g)
            && title_from(g) <= grid_last_row(o)
            && (o.label_col > grid_last_col(g) || grid_last_col(o) < g.label_col)
    };
    let others = || grids.iter().enumerate().filter(|(i, _)| *i != k).map(|(_, (o, _))| o);
    let (mut col_from, mut col_to) = (0, u32::MAX);
    for o in others().filter(|o| beside(o)) {
        if o.label_col > grid_last_col(g) {
            col_to = grid_last_col(g);
        } else {
            col_from = col_from.max(grid_last_col(o) + 1);
        }
    }
    // Above and below it: the others in its columns.
    let (mut row_from, mut row_to) = (0, u32::MAX);
    for o in others().filter(|o| !beside(o) && o.label_col <= col_to && grid_last_col(o) >= col_from) {
        if o.header_row < g.header_row {
            row_from = row_from.max(title_from(g)).max(grid_last_row(o) + 1);
        } else {
            row_to = row_to.min(title_from(o).saturating_sub(1));
        }
    }
    (row_from..=row_to.max(grid_last_row(g)), col_from..=col_to)
}

/// The rows just above a grid's header that are its own (its title, its
/// configuration line, its labels) rather than the notes of the grid above.
const TITLE_ROWS: u32 = 3;

/// The first of a grid's own rows above its header.
fn title_from(g: &detect::Grid) -> u32 {
    g.header_row.saturating_sub(TITLE_ROWS)
}

/// Fills the units a grid's labels do not name from `[charts]`, saying so
/// in `found`; the unit still unnamed (`"length"` or `"capacity"`) is an
/// error.
fn units_from_settings(units: &mut detect::Units, s: &Settings) -> std::result::Result<(), &'static str> {
    if !units.length_named {
        let l = s.length_unit.ok_or("length")?;
        units.radius = l;
        units.boom = l;
        units.length_named = true;
        units.found.push(format!("radius in {} (as [charts] length_unit says)", l.name()));
    }
    if !units.capacity_named {
        let c = s.capacity_unit.ok_or("capacity")?;
        units.capacity = c;
        units.capacity_named = true;
        units.found.push(format!("capacity in {} (as [charts] capacity_unit says)", c.name()));
    }
    Ok(())
}

/// Takes the units a grid's labels do not name as metres and tonnes, and
/// says so in `found` (the `*_named` flags stay false): for showing what a
/// file holds, never for a plan.
fn show_unnamed(units: &mut detect::Units) {
    let unnamed = match (units.length_named, units.capacity_named) {
        (true, true) => return,
        (false, false) => "length or capacity",
        (false, true) => "length",
        (true, false) => "capacity",
    };
    if !units.length_named {
        (units.radius, units.boom) = (LengthUnit::M, LengthUnit::M);
    }
    if !units.capacity_named {
        units.capacity = MassUnit::T;
    }
    units.found.push(format!(
        "NO {} UNIT NAMED: shown as {} and {}; a project must say its units",
        unnamed.to_uppercase(),
        units.radius.name(),
        units.capacity.name()
    ));
}

/// `lifts.json`: every lift's report (read back by
/// [`recorded::LiftsCharted`]).
pub fn lifts_json(lifts: &[LiftReport]) -> serde_json::Value {
    serde_json::json!({ "lifts": lifts })
}

/// A lift as the chart sees it, for `lifts.json`.
#[derive(Debug, Clone, Serialize)]
pub struct LiftReport {
    pub id: String,
    pub chart_config: String,
    pub gross_kg: f64,
    pub capacity_reduction_pct: f64,
    /// Added to every radius before the chart was read (m).
    pub radius_allowance_m: f64,
    pub pick: Option<CapacityCheck>,
    pub set: Option<CapacityCheck>,
    pub pick_error: Option<String>,
    pub set_error: Option<String>,
    pub limits: ChartLimits,
    /// The same intervals in degrees of luff (luffing) or metres of trolley (tower).
    pub intervals_display: Vec<(f64, f64)>,
    pub max_utilisation_pct: f64,
    pub critical: bool,
    pub critical_pct: f64,
    /// A luffing crane's chart configuration of one capacity column, not
    /// one per boom length: the boom length it was made for is not known
    /// here (a sheet per boom length is a common layout), so it is said.
    pub one_column_for_boom_m: Option<f64>,
}

/// Radial resolution of the chart limits: 0.05 degrees of luff, or 5 cm of trolley.
pub fn limit_step(task: &LiftTask) -> f64 {
    if task.crane.model.is_tower() { 0.05 } else { 0.05f64.to_radians() }
}

pub fn lift_report(task: &LiftTask, table: &CapacityTable) -> Result<LiftReport> {
    let cfg = table.config(&task.chart_config).map_err(|e| ChartError::Lift(task.id.clone(), e.to_string()))?;
    let pick = task.check_capacity(cfg, task.pick.radial);
    let set = task.check_capacity(cfg, task.set.radial);
    let limits = task.chart_limits(cfg, limit_step(task));
    let tower = task.crane.model.is_tower();
    let disp = |x: f64| if tower { x } else { x.to_degrees() };
    let utils: Vec<f64> = [&pick, &set].iter().filter_map(|r| r.as_ref().ok().map(|c| c.utilisation_pct)).collect();
    let max_u = utils.iter().copied().fold(0.0, f64::max);
    Ok(LiftReport {
        id: task.id.clone(),
        chart_config: task.chart_config.clone(),
        gross_kg: task.gross_kg(),
        capacity_reduction_pct: task.capacity_reduction_pct,
        radius_allowance_m: task.radius_allowance_m,
        pick_error: pick.as_ref().err().map(|e| e.to_string()),
        set_error: set.as_ref().err().map(|e| e.to_string()),
        pick: pick.ok(),
        set: set.ok(),
        intervals_display: limits.intervals.iter().map(|(a, b)| (disp(*a), disp(*b))).collect(),
        limits,
        max_utilisation_pct: max_u,
        critical: max_u > task.critical_pct,
        critical_pct: task.critical_pct,
        one_column_for_boom_m: (!tower && cfg.boom_independent()).then_some(task.crane.placement.boom_length_m),
    })
}

#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    pub files: Vec<String>,
    pub configs: Vec<ConfigReport>,
    pub rows: usize,
    pub lifts: Vec<LiftReport>,
}

impl Summary {
    pub fn lines(&self) -> Vec<String> {
        let mut v: Vec<String> = self
            .configs
            .iter()
            .map(|c| {
                format!(
                    "'{}': {} x {} radii from {} [{}!{}] ({}){}",
                    c.name,
                    c.columns_said(),
                    c.radii,
                    c.file,
                    c.sheet,
                    c.range,
                    c.units.found.join(", "),
                    c.stated_said()
                )
            })
            .collect();
        for c in &self.configs {
            v.extend(c.warnings.iter().map(|w| format!("warning: {w}")));
        }
        for l in &self.lifts {
            let pick = l
                .pick
                .as_ref()
                .map(|c| format!("{:.0} % at {:.1} m", c.utilisation_pct, c.radius_m))
                .unwrap_or_else(|| format!("NOT PERMITTED ({})", l.pick_error.clone().unwrap_or_default()));
            let set = l
                .set
                .as_ref()
                .map(|c| format!("{:.0} % at {:.1} m", c.utilisation_pct, c.radius_m))
                .unwrap_or_else(|| format!("NOT PERMITTED ({})", l.set_error.clone().unwrap_or_default()));
            // Over 100 % is more than critical: the lift cannot be made so.
            let over: Vec<&str> = [("pick", &l.pick), ("set", &l.set)]
                .into_iter()
                .filter(|(_, c)| c.as_ref().is_some_and(|c| c.utilisation_pct > 100.0))
                .map(|(at, _)| at)
                .collect();
            let flag = if !over.is_empty() {
                format!(" - OVER CAPACITY AT {}", over.join(" AND ").to_uppercase())
            } else if l.critical {
                " - CRITICAL LIFT".to_string()
            } else {
                String::new()
            };
            let farther = if l.radius_allowance_m > 0.0 {
                format!(" (the chart read {:.2} m farther out, radius_allowance_m)", l.radius_allowance_m)
            } else {
                String::new()
            };
            v.push(format!("lift {}: gross {:.2} t, pick {pick}, set {set}{farther}{flag}", l.id, l.gross_kg / 1000.0));
            if let Some(boom) = l.one_column_for_boom_m {
                v.push(format!(
                    "lift {}: chart configuration '{}' has one capacity column, not one per boom length: CHECK THAT IT IS THE CHART FOR THE {boom:.1} m BOOM the lift sets up",
                    l.id, l.chart_config
                ));
            }
        }
        v
    }
}

/// Runs the stage: reads the charts in `inputs` and checks `lifts` against them, writing into
/// `out_dir`; chart.json names the files relative to `root` (the project
/// folder) where given.
pub fn run(
    inputs: &[PathBuf],
    s: &Settings,
    lifts: &[LiftTask],
    out_dir: &Path,
    root: Option<&Path>,
) -> Result<Summary> {
    let mut table = CapacityTable::default();
    let mut reports = Vec::new();
    for (k, p) in inputs.iter().enumerate() {
        let (configs, reps) = read_chart(p, s)?;
        for c in configs {
            if table.configs.iter().any(|o| o.name == c.name) {
                return Err(ChartError::Format(
                    Location::file(p),
                    format!(
                        "configuration '{}' is defined twice; rename a sheet or use [[charts.table]] names",
                        c.name
                    ),
                ));
            }
            table.configs.push(c);
        }
        // What capacity.csv could not be read back with (the plan and docs
        // stages read it), refused here, naming the chart that went over.
        table.check_grid_cells().map_err(|e| {
            let with = if k > 0 { "with the charts before it, " } else { "" };
            ChartError::Format(Location::file(p), format!("{with}{e}"))
        })?;
        reports.extend(reps);
    }
    for m in &s.table {
        if !inputs.iter().any(|p| p.file_name().is_some_and(|n| n.to_string_lossy() == m.file)) {
            return Err(ChartError::Settings(format!(
                "table '{}' names file '{}', which is not in the charts folder",
                m.config, m.file
            )));
        }
    }
    let lift_reports = lifts.iter().map(|t| lift_report(t, &table)).collect::<Result<Vec<_>>>()?;
    std::fs::create_dir_all(out_dir).map_err(|e| ChartError::Io(Location::file(out_dir), e))?;
    table
        .write_csv(&out_dir.join("capacity.csv"))
        .map_err(|e| ChartError::Io(Location::file(out_dir.join("capacity.csv")), e))?;
    let summary = Summary {
        files: inputs.iter().map(|p| liftplan_core::location::shown(p, root)).collect(),
        rows: table.rows().len(),
        configs: reports,
        lifts: lift_reports,
    };
    let write = |name: &str, v: serde_json::Value| -> Result<()> {
        let p = out_dir.join(name);
        liftplan_core::artifact::write_atomic(&p, serde_json::to_string_pretty(&v).unwrap_or_default().as_bytes())
            .map_err(|e| ChartError::Io(Location::file(&p), e))
    };
    write("chart.json", serde_json::json!({ "files": summary.files, "configs": summary.configs }))?;
    write("lifts.json", lifts_json(&summary.lifts))?;
    Ok(summary)
}

/// `liftplan inspect` of a chart workbook.
pub fn inspect(path: &Path) -> Result<serde_json::Value> {
    let (configs, reports) = read_chart_with(path, &Settings::default(), Unnamed::Show)?;
    Ok(serde_json::json!({
        "kind": "chart",
        "format": path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase(),
        "file": path.display().to_string(),
        "configs": reports.iter().zip(&configs).map(|(r, c)| serde_json::json!({
            "name": r.name,
            "sheet": r.sheet,
            "range": r.range,
            "booms": r.boom_lengths,
            "radii": r.radii,
            "boom_lengths_m": c.boom_lengths_m,
            "radius_range_m": [c.radii_m.first(), c.radii_m.last()],
            "units": r.units,
            "warnings": r.warnings,
            "wind_ms": r.wind_ms,
            "counterweight_kg": r.counterweight_kg,
        })).collect::<Vec<_>>(),
    }))
}
