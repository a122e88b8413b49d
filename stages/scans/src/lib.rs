//! # liftplan-scans: stage 1, survey scans to one site cloud
//!
//! Reads every scan the survey team dropped in `scans/` (LAS 1.0–1.4, LAZ, PLY,
//! E57 with several scans per file, Leica PTX (several per file, each with
//! its registration's transform), PTS/XYZ text), places them in one frame
//! ([`register`]), thins them ([`subsample`]), classifies the ground
//! ([`ground`]) and writes, everything in metres (a file's coordinates in
//! the unit its CRS states, else in `[scans] unit`: [`read::units`]):
//!
//! | file | what |
//! |---|---|
//! | `site.laz` | LAS 1.4, millimetre scale, class 2 = ground, scan id in `point_source_id` |
//! | `registration.json` | per scan: 4x4 pose, fitness, inlier RMSE, method, warnings; the files passed by as holding no scan (read back by [`recorded`]) |
//! | `scans.png` | top view coloured by scan |
//! | `ground.asc` | ground-height grid (ESRI ASCII) |
//!
//! The stage reads each scan in chunks and never holds a raw survey in memory:
//! registration works on voxel-thinned copies, and the final thinning streams the
//! scans a second time through the chosen filter.
//!
//! Given a memo file ([`RunOptions::memo`]), registration keeps what it works
//! out there and looks it up on the next run ([`memo`]): a rerun whose scans,
//! poses and registration settings did not change gives the same result
//! without working it out again.
//!
//! It must not know about the cache, the project folder or the CLI: it gets file
//! paths and settings and writes into the folder it is given.
//!
//! ```no_run
//! use liftplan_scans::{run, RunOptions, Settings};
//! let inputs = vec![std::path::PathBuf::from("scans/north.laz")];
//! let summary = run(&inputs, &Settings::default(), &RunOptions::default(), std::path::Path::new("out")).unwrap();
//! println!("{} points", summary.points_out);
//! ```

pub mod coarse2d;
pub mod error;
pub mod features;
pub mod grid;
pub mod ground;
pub mod kdtree;
pub mod memo;
pub mod picture;
pub mod read;
pub mod recorded;
pub mod register;
pub mod subsample;
pub mod write;

use error::{Result, ScanError};
use liftplan_core::Location;
use liftplan_core::cloud::{PointCloud, class};
use liftplan_core::frame::{Aabb, Pose, pose_to_rows};
use read::ScanInfo;
use register::{FeatureCloud, RegCloud, RegInput, RegistrationSettings};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

pub use ground::GroundSettings;

/// Stage name, as in `liftplan options` and the cache.
pub const NAME: &str = "scans";
/// Part of the cache key: bump when the output for the same input changes.
pub const VERSION: u32 = 1;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RegisterMode {
    /// Use file/station poses as a start when present, else features; refine by ICP.
    Auto,
    /// Take coordinates as they are (scans already share a frame).
    None,
    /// Use the poses the files or the station file carry, without refinement.
    Poses,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SubsampleMethod {
    Voxel,
    Spacing,
    Nth,
    None,
}

/// The unit of scan files that state none (`[scans] unit`). A unit a file
/// states (a LAS/LAZ CRS, E57's metres) is that file's, whatever this says;
/// a file that names a CRS without stating its unit needs this set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ScanUnit {
    #[serde(rename = "m")]
    Metre,
    #[serde(rename = "ft")]
    Foot,
    #[serde(rename = "us-ft")]
    UsSurveyFoot,
}

impl ScanUnit {
    fn name_and_metres(self) -> (&'static str, f64) {
        match self {
            ScanUnit::Metre => ("metre", 1.0),
            ScanUnit::Foot => ("foot", 0.3048),
            ScanUnit::UsSurveyFoot => ("US survey foot", 1200.0 / 3937.0),
        }
    }
}

/// The unit `info`'s coordinates are read in: the one its file states, else
/// the project's (`[scans] unit`, metres where unset). A file that names a
/// CRS without stating its unit (an EPSG code alone) is refused where the
/// project does not say the unit: a State Plane survey in US feet read as
/// metres would put every obstacle 3.28 times too far from the crane.
fn unit_for(project: Option<ScanUnit>, info: &ScanInfo) -> Result<read::StatedUnit> {
    match (&info.unit, project) {
        (read::CrsUnit::Stated(u), _) => Ok(u.clone()),
        (read::CrsUnit::None, Some(p)) => {
            let (name, m) = p.name_and_metres();
            Ok(read::StatedUnit {
                horizontal_m: m,
                vertical_m: m,
                what: format!("{name} ([scans] unit; the file states none)"),
            })
        }
        (read::CrsUnit::None, None) => {
            Ok(read::StatedUnit::metres("metre (the default: the file states none and [scans] unit is not set)"))
        }
        (read::CrsUnit::Unstated { crs, heights }, Some(p)) => {
            let (name, m) = p.name_and_metres();
            let (v, heights) = match heights {
                Some((vname, v)) => (*v, format!("heights in {vname}, as the file states")),
                None => (m, "heights too".into()),
            };
            Ok(read::StatedUnit {
                horizontal_m: m,
                vertical_m: v,
                what: format!("{name} ([scans] unit, {heights}; the file's CRS, {crs}, states none)"),
            })
        }
        (read::CrsUnit::Unstated { crs, .. }, None) => Err(ScanError::format(
            Location::file(&info.path),
            format!(
                "its CRS is {crs}, which does not state its unit, and liftplan holds no EPSG registry to look it up (State Plane CRSs are often in US survey feet): set [scans] unit to the CRS's unit, \"m\", \"ft\" or \"us-ft\""
            ),
        )),
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum VoxelPoint {
    Centroid,
    Nearest,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum OnUnregistered {
    /// Fail the stage: a missing scan means missing obstacles.
    Fail,
    /// Leave the scan out and say so in the report.
    Exclude,
}

/// `[scans]` in `liftplan.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// auto | none | poses
    pub register: RegisterMode,
    /// voxel | spacing | nth | none
    pub subsample: SubsampleMethod,
    /// Voxel edge for `subsample = "voxel"` (m).
    pub voxel: f64,
    /// centroid | nearest (the input point nearest the voxel centroid)
    pub voxel_point: VoxelPoint,
    /// Minimum point spacing for `subsample = "spacing"` (m).
    pub spacing: f64,
    /// Keep every Nth point for `subsample = "nth"` (the thesis uses 9).
    pub every_nth: u64,
    /// Unit of the coordinates of scan files that state none: m | ft |
    /// us-ft; metres where unset. A LAS/LAZ file whose CRS states its unit,
    /// and every E57 file (metres by its standard), is read in its own,
    /// converted to metres; one whose CRS is named without its unit (an
    /// EPSG code alone) is read in this and refused where it is unset.
    pub unit: Option<ScanUnit>,
    /// Station file with initial poses, relative to the project folder.
    pub stations: Option<PathBuf>,
    /// fail | exclude
    pub on_unregistered: OnUnregistered,
    pub ground: GroundSettings,
    pub registration: RegistrationSettings,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            register: RegisterMode::Auto,
            subsample: SubsampleMethod::Voxel,
            voxel: 0.05,
            voxel_point: VoxelPoint::Centroid,
            spacing: 0.05,
            every_nth: 9,
            unit: None,
            stations: None,
            on_unregistered: OnUnregistered::Fail,
            ground: GroundSettings::default(),
            registration: RegistrationSettings::default(),
        }
    }
}

impl Settings {
    pub fn check(&self) -> std::result::Result<(), String> {
        match self.subsample {
            SubsampleMethod::Voxel if !(self.voxel.is_finite() && self.voxel > 0.0) => {
                return Err(format!("voxel must be a positive number of metres, found {}", self.voxel));
            }
            SubsampleMethod::Spacing if !(self.spacing.is_finite() && self.spacing > 0.0) => {
                return Err(format!("spacing must be a positive number of metres, found {}", self.spacing));
            }
            SubsampleMethod::Nth if self.every_nth == 0 => {
                return Err("every_nth must be 1 or more".into());
            }
            _ => {}
        }
        self.ground.check()?;
        self.registration.check()
    }
}

/// What `run` needs besides settings.
pub struct RunOptions<'a> {
    /// Project seed (registration's RANSAC is seeded from it).
    pub seed: u64,
    /// Reports progress: (what, done, total).
    pub progress: &'a (dyn Fn(&str, u64, u64) + Sync),
    /// The project folder: registration.json names the scans relative to it.
    pub root: Option<&'a Path>,
    /// Where registration keeps its answers between runs, if anywhere.
    pub memo: Option<MemoFile<'a>>,
}

/// A file registration's answers are kept in between runs ([`memo`]): they
/// save time, never change a result.
#[derive(Debug, Clone, Copy)]
pub struct MemoFile<'a> {
    pub path: &'a Path,
    /// Names the build of this crate: answers of another build are not used.
    pub build: &'a str,
    /// False to start from an empty memo (a rerun the user forced); the file
    /// is written afresh either way.
    pub reuse: bool,
}

impl Default for RunOptions<'_> {
    fn default() -> Self {
        RunOptions { seed: 0, progress: &|_, _, _| {}, root: None, memo: None }
    }
}

/// `registration.json`: the registration mode, every scan's report and the
/// files passed by (read back by [`recorded::Registration`]).
pub fn registration_json(register: RegisterMode, scans: &[ScanReport], passed_by: &[PassedBy]) -> serde_json::Value {
    serde_json::json!({ "register": register, "scans": scans, "passed_by": passed_by })
}

/// A file among the scans, or a scan in one, that the stage passed by as
/// holding no scan: a survey's report (`readme.txt`), an empty tile. It may
/// as well be a scan whose export failed, so the plan's pages name it.
#[derive(Debug, Clone, Serialize)]
pub struct PassedBy {
    /// The file as shown ([`liftplan_core::location::shown`]), with `#` and
    /// the scan's name for a scan in a file of several.
    pub file: String,
    pub why: String,
}

/// One line of the run output per scan.
#[derive(Debug, Clone, Serialize)]
pub struct ScanReport {
    pub file: String,
    pub name: String,
    pub format: read::Format,
    pub points_read: u64,
    pub points_kept: u64,
    /// Scan frame to site frame, row-major 4x4.
    pub pose: [[f64; 4]; 4],
    pub fitness: f64,
    pub rmse_m: f64,
    pub method: String,
    pub registered: bool,
    pub warning: Option<String>,
    /// How firmly what it shares with the scans placed before it held it
    /// in plan ([`register::RegResult::hold_m`], m).
    pub hold_m: Option<f64>,
    /// How far its last alignment, against all the other scans, moved its
    /// points ([`register::RegResult::refined_move_m`], m).
    pub refined_move_m: Option<f64>,
    /// The unit its coordinates were read in, and where that came from.
    pub unit: String,
    /// Metres per coordinate unit of x, y and z ([`ScanInfo::to_m`]).
    pub to_m: [f64; 3],
    /// The date its file gives ([`read::ScanDate`]; "2026-10-02
    /// (acquired)" or "... (file created)" in JSON).
    pub date: Option<read::ScanDate>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    pub scans: Vec<ScanReport>,
    /// What was passed by as holding no scan ([`PassedBy`]).
    pub passed_by: Vec<PassedBy>,
    pub points_read: u64,
    pub points_out: u64,
    pub ground_points: u64,
    pub bbox: [f64; 6],
    pub register: RegisterMode,
    pub subsample: String,
    /// Registration's answers (trials, placements, refinement) found in the
    /// memo (of earlier runs, or of this one where a scan taken out and
    /// placed again repeats a round), and those worked out in this one.
    pub registration_answers_reused: u64,
    pub registration_answers_worked_out: u64,
    /// What "fitness" means in the lines: a point overlaps the other scans
    /// within these (m), and a scan needs this share to register.
    pub fit_distance_m: f64,
    pub fit_residual_m: f64,
    pub min_fitness: f64,
}

impl Summary {
    /// One line per scan for the run output.
    pub fn lines(&self) -> Vec<String> {
        self.scans
            .iter()
            .flat_map(|s| {
                let state = if s.registered {
                    format!("fitness {:.0} %, rmse {:.1} mm ({})", 100.0 * s.fitness, 1000.0 * s.rmse_m, s.method)
                } else {
                    "NOT REGISTERED".into()
                };
                let unit = if s.to_m == [1.0; 3] {
                    String::new()
                } else {
                    format!("; coordinates in {}, converted to metres", s.unit)
                };
                let line =
                    format!("{}: {} points read, {} kept, {}{unit}", s.name, s.points_read, s.points_kept, state);
                // A scan merged with something to check (registration's
                // warning) says it on a line of its own.
                std::iter::once(line).chain(s.warning.clone().filter(|_| s.registered))
            })
            .chain(self.passed_by.iter().map(|p| format!("passed by: {}: {}", p.file, p.why)))
            .chain(self.fitness_line())
            .chain(self.unit_line())
            .chain(std::iter::once(self.date_line()))
            .collect()
    }

    /// What the scans' fitness and rmse mean, where registration ran: a
    /// fitness of 18 % reads as a failure to someone who takes it for a
    /// score; it is the scan's overlap with the others.
    fn fitness_line(&self) -> Option<String> {
        (self.register == RegisterMode::Auto && self.scans.len() > 1).then(|| {
            format!(
                "registration: a scan's fitness is the share of its points that overlap the scans placed with it (another scan's point within {:.2} m and its surface within {:.2} m): how much of its view the others share, not a score; it needs {:.0} % to register. rmse: the spread of those points' distances to the others' surfaces. The reference scan fixes the site frame.",
                self.fit_distance_m,
                self.fit_residual_m,
                100.0 * self.min_fitness
            )
        })
    }

    /// When the scans were taken, as their files say: the signer confirms
    /// that nothing on site has changed since, so the line says how old
    /// the survey is and where the dates come from (a LAS file's creation
    /// date may be its export's, not the survey's).
    fn date_line(&self) -> String {
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        let range = |acquired: bool| {
            let dates: Vec<read::ScanDate> =
                self.scans.iter().filter_map(|s| s.date).filter(|d| d.acquired == acquired).collect();
            let (lo, hi) = (dates.iter().min()?, dates.iter().max()?);
            let span = if lo == hi { lo.date.to_string() } else { format!("{} to {}", lo.date, hi.date) };
            Some((span, dates.len()))
        };
        let mut said = Vec::new();
        if let Some((span, n)) = range(true) {
            said.push(format!("taken {span} ({n} scan{}, as the files record their acquisition)", plural(n)));
        }
        if let Some((span, n)) = range(false) {
            said.push(format!(
                "files created {span} ({n} scan{}: the LAS files' creation date, which may be the export's, not the survey's)",
                plural(n)
            ));
        }
        let none = self.scans.iter().filter(|s| s.date.is_none()).count();
        if none > 0 {
            said.push(format!("no date in the file for {none} scan{}", plural(none)));
        }
        format!("scan dates: {}: ask the survey team when the site was scanned if unsure", said.join("; "))
    }

    /// The units the scans' coordinates were read in, with how many scans
    /// each: the lift plan's signer must see where they came from.
    fn unit_line(&self) -> Option<String> {
        let mut units: Vec<(&str, usize)> = Vec::new();
        for s in &self.scans {
            match units.iter_mut().find(|u| u.0 == s.unit) {
                Some(u) => u.1 += 1,
                None => units.push((&s.unit, 1)),
            }
        }
        let shown: Vec<String> =
            units.iter().map(|(u, n)| format!("{u}: {n} scan{}", if *n == 1 { "" } else { "s" })).collect();
        (!shown.is_empty()).then(|| format!("coordinate units: {}", shown.join("; ")))
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StationFile {
    /// Tolerances of every station that gives none of its own.
    tolerance_m: Option<toml::Spanned<f64>>,
    yaw_tolerance_deg: Option<toml::Spanned<f64>>,
    station: Vec<Station>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Station {
    scan: toml::Spanned<String>,
    x_m: toml::Spanned<f64>,
    y_m: toml::Spanned<f64>,
    z_m: Option<toml::Spanned<f64>>,
    yaw_deg: Option<toml::Spanned<f64>>,
    tolerance_m: Option<toml::Spanned<f64>>,
    yaw_tolerance_deg: Option<toml::Spanned<f64>>,
}

/// How far registration may place a scan from its station, in plan and in
/// height, unless the station file says otherwise (m): a surveyed station is
/// good to centimetres; a position read off a site plan needs its own.
pub const DEFAULT_STATION_TOLERANCE_M: f64 = 0.5;
/// The same for yaw (degrees).
pub const DEFAULT_STATION_YAW_TOLERANCE_DEG: f64 = 3.0;

/// A surveyed station: the scan it belongs to, its pose in the site frame,
/// how far registration may place the scan from it, and the line of the
/// station file that names the scan.
#[derive(Debug)]
pub struct SurveyedStation {
    /// The scan's name, as the scans' are kept ([`read::scan_name_kept`]).
    pub scan: String,
    /// Scanner frame to site frame.
    pub pose: Pose,
    /// Height and yaw are held only where the station gives them.
    pub tolerance: register::StationTolerance,
    /// The line of the file that names the scan.
    pub line: u64,
}

/// Reads a station file (see [`parse_stations`]).
fn read_stations(path: &Path) -> Result<Vec<SurveyedStation>> {
    let text = liftplan_core::location::read_text(path).map_err(|e| match e {
        liftplan_core::location::TextReadError::Io(e) => ScanError::Io(Location::file(path), e),
        liftplan_core::location::TextReadError::NotUtf8(at, why) => ScanError::format(at, why),
    })?;
    parse_stations(path, &text)
}

/// Parses the text of the station file at `path`. Each value must be a finite
/// number (TOML also writes `nan` and `inf`); an error names the file, line
/// and column.
pub fn parse_stations(path: &Path, text: &str) -> Result<Vec<SurveyedStation>> {
    let f: StationFile = toml::from_str(text).map_err(|e| {
        let (loc, msg) = liftplan_core::location::toml_error(path, text, &e);
        ScanError::format(loc, msg)
    })?;
    let tolerance = |name: &str, v: &toml::Spanned<f64>| -> Result<f64> {
        let x = *v.get_ref();
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(ScanError::format(
                Location::in_text(path, text, v.span().start),
                format!("{name} = {x}: a tolerance must be a positive number"),
            ))
        }
    };
    let file_plan_m = f.tolerance_m.as_ref().map(|v| tolerance("tolerance_m", v)).transpose()?;
    let file_yaw_deg = f.yaw_tolerance_deg.as_ref().map(|v| tolerance("yaw_tolerance_deg", v)).transpose()?;
    let mut out = Vec::with_capacity(f.station.len());
    for st in f.station {
        let given = [
            ("x_m", Some(&st.x_m)),
            ("y_m", Some(&st.y_m)),
            ("z_m", st.z_m.as_ref()),
            ("yaw_deg", st.yaw_deg.as_ref()),
        ];
        for (name, v) in given.into_iter().filter_map(|(n, v)| Some((n, v?))) {
            if !v.get_ref().is_finite() {
                return Err(ScanError::format(
                    Location::in_text(path, text, v.span().start),
                    format!("{name} = {} is not a finite number", v.get_ref()),
                ));
            }
        }
        let plan_m = match &st.tolerance_m {
            Some(v) => tolerance("tolerance_m", v)?,
            None => file_plan_m.unwrap_or(DEFAULT_STATION_TOLERANCE_M),
        };
        let yaw_deg = match &st.yaw_tolerance_deg {
            Some(v) => tolerance("yaw_tolerance_deg", v)?,
            None => file_yaw_deg.unwrap_or(DEFAULT_STATION_YAW_TOLERANCE_DEG),
        };
        out.push(SurveyedStation {
            tolerance: register::StationTolerance {
                plan_m,
                height_m: st.z_m.is_some().then_some(plan_m),
                yaw_deg: st.yaw_deg.is_some().then_some(yaw_deg),
            },
            line: liftplan_core::location::line_col(text, st.scan.span().start).0,
            pose: liftplan_core::frame::pose_xyz_yaw(
                *st.x_m.get_ref(),
                *st.y_m.get_ref(),
                st.z_m.as_ref().map_or(0.0, |v| *v.get_ref()),
                st.yaw_deg.as_ref().map_or(0.0, |v| *v.get_ref()).to_radians(),
            ),
            // Kept as the scans' names are, which it is matched with.
            scan: read::scan_name_kept(st.scan.get_ref()),
        });
    }
    Ok(out)
}

/// At least one station must name a scan given, and no scan may have two.
/// A station file that places no scan is a mistake (a misspelt name would
/// otherwise drop the surveyed pose without a word, and the site would be
/// placed by another scan's frame); a station for a scan not delivered yet is
/// not, so it is only warned of.
fn check_stations(path: &Path, stations: &[SurveyedStation], scans: &[ScanInfo]) -> Result<()> {
    let given = |st: &SurveyedStation| scans.iter().any(|s| s.name == st.scan);
    if let Some(st) = stations.iter().find(|st| !given(st)) {
        let names: Vec<&str> = scans.iter().map(|s| s.name.as_str()).collect();
        let what = format!("station for scan \"{}\" names no scan given (the scans are {})", st.scan, names.join(", "));
        if !stations.iter().any(given) {
            return Err(ScanError::format(
                Location::line(path, st.line, None),
                format!("{what}, and no other station names one: the file places no scan"),
            ));
        }
        for st in stations.iter().filter(|st| !given(st)) {
            tracing::warn!(
                "{}:{}: station for scan \"{}\" names no scan given; ignored",
                path.display(),
                st.line,
                st.scan
            );
        }
    }
    for (k, st) in stations.iter().enumerate() {
        if let Some(first) = stations[..k].iter().find(|o| o.scan == st.scan) {
            return Err(ScanError::format(
                Location::line(path, st.line, None),
                format!("scan \"{}\" has a second station (the first is on line {})", st.scan, first.line),
            ));
        }
    }
    Ok(())
}

/// Lists every scan in `inputs` (files in the given order, scans in file
/// order), each to be read in metres: in the unit its file states, else in
/// `unit` ([`ScanInfo::to_m`]; see [`unit_for`]).
pub fn list_all(inputs: &[PathBuf], unit: Option<ScanUnit>) -> Result<Vec<ScanInfo>> {
    let mut all = Vec::new();
    for p in inputs {
        for mut info in read::list_scans(p)? {
            let u = unit_for(unit, &info)?;
            info.to_m = [u.horizontal_m, u.horizontal_m, u.vertical_m];
            info.read_in = u.what;
            if let Some(b) = &mut info.bbox
                && !b.is_empty()
            {
                for k in 0..3 {
                    (b.min[k], b.max[k]) = (b.min[k] * info.to_m[k], b.max[k] * info.to_m[k]);
                }
            }
            all.push(info);
        }
    }
    if all.len() > u16::MAX as usize {
        return Err(ScanError::Settings(format!("{} scans: at most {} are supported", all.len(), u16::MAX)));
    }
    Ok(all)
}

pub fn thin_for_registration(
    files: &mut read::ScanStreamer,
    info: &ScanInfo,
    s: &RegistrationSettings,
    progress: &(dyn Fn(&str, u64, u64) + Sync),
) -> Result<(RegCloud, FeatureCloud, u64)> {
    let mut g = subsample::VoxelGrid::new(s.icp_voxel_m).map_err(ScanError::Settings)?;
    let total = info.declared_points.unwrap_or(0);
    let mut seen = 0u64;
    let n = files.stream(info, &mut |c| {
        g.add(c, 0).map_err(|e| ScanError::format(Location::item(&info.path, &info.name), e))?;
        seen += c.len() as u64;
        progress(&format!("read {}", info.name), seen, total);
        Ok(())
    })?;
    let fine = g.finish();
    let normals = features::normals(&fine.xyz, 16, 1.0, 5.0 * s.icp_voxel_m, [0.0; 3]);
    // Descriptors only serve scans that are not levelled.
    let coarse = if s.leveled {
        FeatureCloud::default()
    } else {
        let coarse = subsample::voxel_centroids(&fine, s.feature_voxel_m).map_err(ScanError::Settings)?;
        let cn = features::normals(&coarse.xyz, 16, 3.0 * s.feature_voxel_m, s.feature_voxel_m, [0.0; 3]);
        let f = features::fpfh(&coarse.xyz, &cn, s.feature_radius_m);
        FeatureCloud { pts: coarse.xyz, fpfh: f }
    };
    Ok((RegCloud { pts: fine.xyz, normals }, coarse, n))
}

/// Runs the stage; see the crate docs for what it writes into `out_dir`.
pub fn run(inputs: &[PathBuf], s: &Settings, opts: &RunOptions, out_dir: &Path) -> Result<Summary> {
    s.check().map_err(ScanError::Settings)?;
    let scans = list_all(inputs, s.unit)?;
    if scans.is_empty() {
        return Err(ScanError::Settings("no scan files given".into()));
    }
    // Files listing no scan (a report among the scans, read::list_scans
    // says why in the log), and a tiled delivery's empty tile: nothing to
    // place or merge (registering the tile failed the run as a scan that
    // overlaps nothing).
    let mut passed_by: Vec<PassedBy> = inputs
        .iter()
        .filter(|p| !scans.iter().any(|info| &info.path == *p))
        .map(|p| PassedBy {
            file: liftplan_core::location::shown(p, opts.root),
            why: "holds no scan: no line of numbers x y z, or empty".into(),
        })
        .collect();
    let (empty, scans): (Vec<ScanInfo>, Vec<ScanInfo>) =
        scans.into_iter().partition(|info| info.declared_points == Some(0));
    for info in &empty {
        let file = liftplan_core::location::shown(&info.path, opts.root);
        tracing::warn!("{file}: scan '{}' holds no points (its header declares none): passed by", info.name);
        let file = if info.name == read::stem(&info.path) { file } else { format!("{file}#{}", info.name) };
        passed_by.push(PassedBy { file, why: "its header declares no points".into() });
    }
    if scans.is_empty() {
        return Err(ScanError::Settings("every scan file given holds no points".into()));
    }
    let stations = match &s.stations {
        Some(p) => {
            let stations = read_stations(p)?;
            check_stations(p, &stations, &scans)?;
            stations
        }
        None => vec![],
    };
    let station_of = |info: &ScanInfo| stations.iter().find(|st| st.scan == info.name);
    let initial = |info: &ScanInfo| -> Option<Pose> { station_of(info).map(|st| st.pose).or(info.pose) };
    let names: Vec<String> = scans.iter().map(|x| x.name.clone()).collect();
    let mut read_counts = vec![0u64; scans.len()];
    let mut memo_counts = (0, 0);

    let results: Vec<register::RegResult> = match s.register {
        RegisterMode::None => scans
            .iter()
            .map(|x| {
                let mut r = plain_result(Pose::identity(), "none (coordinates as given)");
                r.warning = x.pose.filter(|p| !pose_is_identity(p)).map(|p| {
                    let t = p.translation.vector;
                    format!(
                        "scan '{}': its file gives it a pose ({:.3}, {:.3}, {:.3}) m, turned {:.2}°, which register = \"none\" does not apply: \
                         its points are merged as the file holds them; register = \"poses\" (or \"auto\") applies it",
                        x.name,
                        t.x,
                        t.y,
                        t.z,
                        p.rotation.angle().to_degrees()
                    )
                });
                r
            })
            .collect(),
        RegisterMode::Poses => scans
            .iter()
            .map(|x| match initial(x) {
                Some(p) => plain_result(p, "file or station pose"),
                None => plain_result(Pose::identity(), "no pose given: coordinates as given"),
            })
            .collect(),
        RegisterMode::Auto => {
            // The reference is the first scan with a station, so that the
            // scans are placed in the station file's frame; else the first.
            let first = scans.iter().position(|x| station_of(x).is_some()).unwrap_or(0);
            let order: Vec<usize> = std::iter::once(first).chain((0..scans.len()).filter(|&k| k != first)).collect();
            let mut regs = Vec::with_capacity(scans.len());
            let mut files = read::ScanStreamer::default();
            for &k in &order {
                let info = &scans[k];
                let (fine, coarse, n) = thin_for_registration(&mut files, info, &s.registration, opts.progress)?;
                read_counts[k] = n;
                let held = station_of(info).map(|st| st.tolerance);
                regs.push(RegInput { name: info.name.clone(), fine, coarse, initial: initial(info), held });
            }
            (opts.progress)("register", 0, 1);
            let mut memo = match opts.memo {
                Some(m) if m.reuse => memo::Memo::load(m.path, m.build),
                Some(m) => memo::Memo::new(m.build),
                None => memo::Memo::new(""),
            };
            let r = register::register_all_memo(&regs, &s.registration, opts.seed, &mut memo);
            memo_counts = (memo.hits, memo.misses);
            // Logged, not one of the summary's lines: those go into the
            // PDF, which must not depend on what an earlier run left behind.
            tracing::info!(
                "registration: {} of {} answers reused (the same as working them out)",
                memo.hits,
                memo.hits + memo.misses
            );
            if let Some(m) = opts.memo
                && let Err(e) = memo.save(m.path)
            {
                // The memo only saves time: the stage's result does not depend on it.
                tracing::warn!("{}: registration memo not written: {e}", m.path.display());
            }
            (opts.progress)("register", 1, 1);
            // Back in the scans' order.
            let mut by_scan: Vec<Option<register::RegResult>> = (0..scans.len()).map(|_| None).collect();
            for (&k, res) in order.iter().zip(r) {
                by_scan[k] = Some(res);
            }
            by_scan.into_iter().flatten().collect()
        }
    };

    let unregistered: Vec<(String, String)> = (scans.iter().zip(&results))
        .filter(|(_, r)| !r.registered)
        .map(|(info, r)| {
            let why = r.warning.clone().unwrap_or_else(|| format!("scan '{}' does not register", info.name));
            (info.name.clone(), why)
        })
        .collect();
    let mut reports: Vec<ScanReport> = scans
        .iter()
        .zip(&results)
        .map(|(info, r)| ScanReport {
            file: liftplan_core::location::shown(&info.path, opts.root),
            name: info.name.clone(),
            format: info.format,
            points_read: 0,
            points_kept: 0,
            pose: pose_to_rows(&r.pose),
            fitness: r.fitness,
            rmse_m: r.rmse_m,
            method: r.method.clone(),
            registered: r.registered,
            warning: r.warning.clone(),
            hold_m: r.hold_m,
            refined_move_m: r.refined_move_m,
            unit: info.read_in.clone(),
            to_m: info.to_m,
            date: info.date,
        })
        .collect();
    std::fs::create_dir_all(out_dir).map_err(|e| ScanError::Io(Location::file(out_dir), e))?;
    write_json(&out_dir.join("registration.json"), &registration_json(s.register, &reports, &passed_by))?;
    if !unregistered.is_empty() && s.on_unregistered == OnUnregistered::Fail {
        return Err(ScanError::Registration(unregistered_error(&unregistered, &out_dir.join("registration.json"))));
    }

    // Second pass: every registered scan through the thinning filter.
    let mut cloud = thin(&scans, &results, s, opts, &mut read_counts)?;
    // One count over the cloud for all scans (a count per scan read the
    // whole cloud once per scan).
    let mut kept = vec![0u64; reports.len()];
    for &sc in &cloud.scan {
        if let Some(n) = kept.get_mut(sc as usize) {
            *n += 1;
        }
    }
    for (k, r) in reports.iter_mut().enumerate() {
        r.points_read = read_counts[k];
        r.points_kept = kept[k];
    }
    let grid = if s.ground.enabled {
        (opts.progress)("ground", 0, 1);
        let g = ground::classify(&mut cloud, &s.ground).map_err(ScanError::Settings)?;
        (opts.progress)("ground", 1, 1);
        g
    } else {
        cloud.class = vec![class::UNCLASSIFIED; cloud.len()];
        None
    };
    (opts.progress)("write site.laz", 0, 1);
    write::write_las(&out_dir.join("site.laz"), &cloud)?;
    if let Some(g) = &grid {
        g.write_asc(&out_dir.join("ground.asc"))
            .map_err(|e| ScanError::Io(Location::file(out_dir.join("ground.asc")), e))?;
    }
    picture::top_view(&cloud, &names, 1200)
        .write_png(&out_dir.join("scans.png"))
        .map_err(|e| ScanError::Io(Location::file(out_dir.join("scans.png")), e))?;
    write_json(&out_dir.join("registration.json"), &registration_json(s.register, &reports, &passed_by))?;
    (opts.progress)("write site.laz", 1, 1);
    let bbox = cloud.bbox();
    Ok(Summary {
        points_read: read_counts.iter().sum(),
        points_out: cloud.len() as u64,
        ground_points: cloud.class.iter().filter(|&&c| c == class::GROUND).count() as u64,
        bbox: if bbox.is_empty() { [0.0; 6] } else { bbox.to_array() },
        register: s.register,
        subsample: match s.subsample {
            SubsampleMethod::Voxel => format!("voxel {} m ({:?})", s.voxel, s.voxel_point).to_lowercase(),
            SubsampleMethod::Spacing => format!("spacing {} m", s.spacing),
            SubsampleMethod::Nth => format!("every {}th point", s.every_nth),
            SubsampleMethod::None => "none".into(),
        },
        registration_answers_reused: memo_counts.0,
        registration_answers_worked_out: memo_counts.1,
        fit_distance_m: s.registration.fit_distance_m,
        fit_residual_m: s.registration.fit_residual_m,
        min_fitness: s.registration.min_fitness,
        scans: reports,
        passed_by,
    })
}

/// Whether a file's pose moves nothing (a PTX export already in the site's
/// frame writes the identity).
fn pose_is_identity(p: &Pose) -> bool {
    p.translation.vector.norm() < 1e-9 && p.rotation.angle() < 1e-12
}

fn plain_result(pose: Pose, method: &str) -> register::RegResult {
    register::RegResult {
        pose,
        fitness: 1.0,
        rmse_m: 0.0,
        method: method.into(),
        registered: true,
        warning: None,
        hold_m: None,
        refined_move_m: None,
    }
}

fn write_json(path: &Path, v: &serde_json::Value) -> Result<()> {
    let text = serde_json::to_string_pretty(v).unwrap_or_default();
    liftplan_core::artifact::write_atomic(path, text.as_bytes()).map_err(|e| ScanError::Io(Location::file(path), e))
}

fn thin(
    scans: &[ScanInfo],
    results: &[register::RegResult],
    s: &Settings,
    opts: &RunOptions,
    read_counts: &mut [u64],
) -> Result<PointCloud> {
    enum Filter {
        Voxel(subsample::VoxelGrid),
        Spacing(subsample::SpacingFilter),
        Nth(subsample::EveryNth),
        All(PointCloud),
    }
    let mk = || -> Result<Filter> {
        Ok(match s.subsample {
            SubsampleMethod::Voxel => Filter::Voxel(subsample::VoxelGrid::new(s.voxel).map_err(ScanError::Settings)?),
            SubsampleMethod::Spacing => {
                Filter::Spacing(subsample::SpacingFilter::new(s.spacing).map_err(ScanError::Settings)?)
            }
            SubsampleMethod::Nth => Filter::Nth(subsample::EveryNth::new(s.every_nth).map_err(ScanError::Settings)?),
            SubsampleMethod::None => Filter::All(PointCloud::default()),
        })
    };
    let pass =
        |filter: &mut Filter, nearest: Option<&mut subsample::NearestPicker>, read_counts: &mut [u64]| -> Result<()> {
            let mut nearest = nearest;
            let mut files = read::ScanStreamer::default();
            for (k, (info, r)) in scans.iter().zip(results).enumerate() {
                if !r.registered {
                    continue;
                }
                if let Filter::Nth(f) = filter {
                    f.next_scan();
                }
                let total = info.declared_points.unwrap_or(0);
                let mut seen = 0u64;
                let n = files.stream(info, &mut |c| {
                    let mut c = c.clone();
                    c.transform(&r.pose);
                    c.scan = vec![k as u16; c.len()];
                    c.class.clear();
                    let at = |e: String| ScanError::format(Location::item(&info.path, &info.name), e);
                    match (&mut *filter, nearest.as_deref_mut()) {
                        (_, Some(p)) => p.add(&c, k as u16),
                        (Filter::Voxel(g), None) => g.add(&c, k as u16).map_err(at)?,
                        (Filter::Spacing(g), None) => g.add(&c, k as u16).map_err(at)?,
                        (Filter::Nth(g), None) => g.add(&c, k as u16),
                        (Filter::All(all), None) => all.append(&c),
                    }
                    seen += c.len() as u64;
                    (opts.progress)(&format!("thin {}", info.name), seen, total);
                    Ok(())
                })?;
                read_counts[k] = n;
            }
            Ok(())
        };
    let mut f = mk()?;
    pass(&mut f, None, read_counts)?;
    Ok(match f {
        Filter::Voxel(g) if s.voxel_point == VoxelPoint::Nearest => {
            let mut picker = g.into_nearest_picker();
            let mut dummy = Filter::All(PointCloud::default());
            pass(&mut dummy, Some(&mut picker), read_counts)?;
            picker.finish()
        }
        Filter::Voxel(g) => g.finish(),
        Filter::Spacing(g) => g.finish(),
        Filter::Nth(g) => g.finish(),
        Filter::All(c) => c,
    })
}

/// Reasons an unregistered-scans error spells out; the rest are counted (a
/// survey of hundreds of scans that do not register would otherwise make an
/// error of hundreds of lines).
const UNREGISTERED_LISTED: usize = 5;

/// The error for scans that do not register, from each scan's name and
/// reason (which starts "scan '<name>' "). Scans refused for the same reason
/// (all those placed against a reference that disagrees with them) share one
/// entry that names them all, instead of the reason said once per scan.
fn unregistered_error(reasons: &[(String, String)], report: &Path) -> String {
    // (first scan's reason, the other scans with the same reason)
    let mut groups: Vec<(&str, &str, Vec<&str>)> = Vec::new();
    for (name, reason) in reasons {
        let rest = reason.strip_prefix(&format!("scan '{name}' ")).unwrap_or(reason);
        match groups.iter_mut().find(|g| g.1 == rest) {
            Some(g) => g.2.push(name),
            None => groups.push((reason, rest, vec![])),
        }
    }
    let listed = groups.iter().take(UNREGISTERED_LISTED).map(|(reason, _, same)| match same.as_slice() {
        [] => reason.to_string(),
        names => format!(
            "{reason} (the same for {} {})",
            if names.len() == 1 { "scan" } else { "scans" },
            names.iter().map(|n| format!("'{n}'")).collect::<Vec<_>>().join(", ")
        ),
    });
    let mut text = listed.collect::<Vec<_>>().join("; ");
    let unlisted: usize = groups.iter().skip(UNREGISTERED_LISTED).map(|g| 1 + g.2.len()).sum();
    if unlisted > 0 {
        text +=
            &format!("; and {unlisted} more scans do not register ({} gives every scan's fitness)", report.display());
    }
    // Files already in one frame (a registered survey exported in tiles
    // that barely overlap) fail to register against each other too, and
    // leaving them out would lose what they hold.
    text + " (where the files are already in one frame, a registered survey exported in parts, set [scans] \
            register = \"none\" to take their coordinates as they are; otherwise set [scans] on_unregistered = \
            \"exclude\" to leave such scans out, knowing their obstacles will be missing)"
}

/// A summary of a scan file for `liftplan inspect`, from headers where they
/// suffice and by streaming the points where they do not.
pub fn inspect(path: &Path) -> Result<serde_json::Value> {
    let scans = read::list_scans(path)?;
    // A text file of another kind, which a run passes by.
    if scans.is_empty() {
        return Err(ScanError::format(Location::file(path), "holds no scan (no line of numbers x y z ...)"));
    }
    let mut total = 0u64;
    let mut bbox = Aabb::empty();
    let mut per = Vec::new();
    let mut files = read::ScanStreamer::default();
    for info in &scans {
        let (n, b) = match (info.declared_points, info.bbox) {
            (Some(n), Some(b)) => (n, b),
            _ => {
                let mut b = Aabb::empty();
                let n = files.stream(info, &mut |c| {
                    b = b.union(&c.bbox());
                    Ok(())
                })?;
                (n, b)
            }
        };
        total += n;
        let site_b = match info.pose {
            Some(p) if !b.is_empty() => {
                let mut t = Aabb::empty();
                for k in 0..8 {
                    let c = [
                        if k & 1 == 0 { b.min[0] } else { b.max[0] },
                        if k & 2 == 0 { b.min[1] } else { b.max[1] },
                        if k & 4 == 0 { b.min[2] } else { b.max[2] },
                    ];
                    let q = p * nalgebra::Point3::new(c[0], c[1], c[2]);
                    t.grow([q.x, q.y, q.z]);
                }
                t
            }
            _ => b,
        };
        bbox = bbox.union(&site_b);
        per.push(serde_json::json!({
            "name": info.name,
            "points": n,
            "bbox": if b.is_empty() { serde_json::Value::Null } else { serde_json::json!(b.to_array()) },
            "pose": info.pose.map(|p| pose_to_rows(&p)),
            "date": info.date.map(|d| d.to_string()),
            "details": info.details,
        }));
    }
    Ok(serde_json::json!({
        "kind": "scan",
        "format": scans.first().map(|s| s.format.name()).unwrap_or("unknown"),
        "file": path.display().to_string(),
        "points": total,
        "bbox": if bbox.is_empty() { serde_json::Value::Null } else { serde_json::json!(bbox.to_array()) },
        "scans": per,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan(name: &str) -> ScanInfo {
        ScanInfo {
            path: PathBuf::from(format!("{name}.laz")),
            format: read::Format::Laz,
            index: 0,
            name: name.into(),
            declared_points: None,
            pose: None,
            bbox: None,
            details: Default::default(),
            unit: read::CrsUnit::None,
            date: None,
            to_m: [1.0; 3],
            read_in: String::new(),
            points_at: None,
        }
    }

    /// The stage opens an E57 file once per pass over its scans: once to
    /// thin them at centroids, twice to pick the points nearest them.
    #[test]
    fn the_stage_opens_a_multi_scan_file_once_per_pass() {
        let e57 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scans/two-scans.e57");
        let opens = || read::E57_OPENS.with(|n| n.get());
        for (voxel_point, passes) in [(VoxelPoint::Centroid, 1), (VoxelPoint::Nearest, 2)] {
            let out = tempfile::tempdir().unwrap();
            let s = Settings { register: RegisterMode::None, voxel_point, ..Default::default() };
            let before = opens();
            let summary = run(std::slice::from_ref(&e57), &s, &RunOptions::default(), out.path()).unwrap();
            assert_eq!(opens() - before, passes, "{voxel_point:?}");
            let counts: Vec<(u64, u64)> = summary.scans.iter().map(|r| (r.points_read, r.points_kept)).collect();
            assert_eq!(counts, [(30, 30), (20, 20)]);
        }
    }

    /// A scan whose header declares no points (a tiled delivery's empty
    /// tile) is passed by: registering it failed the run, as a scan that
    /// overlaps nothing. Scans all empty are refused.
    #[test]
    fn a_scan_of_no_points_is_passed_by() {
        let d = tempfile::tempdir().unwrap();
        let empty = d.path().join("tile-empty.las");
        las::Writer::from_path(&empty, las::Header::default()).unwrap().close().unwrap();
        let e57 = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scans/two-scans.e57");
        let s = Settings { register: RegisterMode::None, ..Default::default() };
        let out = tempfile::tempdir().unwrap();
        let readme = d.path().join("readme.txt");
        std::fs::write(&readme, "Survey of site A\n").unwrap();
        let summary = run(&[empty.clone(), e57, readme], &s, &RunOptions::default(), out.path()).unwrap();
        let names: Vec<&str> = summary.scans.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names.len(), 2, "{names:?}");
        assert!(!names.contains(&"tile-empty"), "{names:?}");
        // Both named in the run's lines and registration.json, for the
        // plan's pages (either may be a scan whose export failed).
        let passed: Vec<String> = summary.passed_by.iter().map(|p| format!("{}: {}", p.file, p.why)).collect();
        assert_eq!(passed.len(), 2, "{passed:?}");
        assert!(passed[0].ends_with("readme.txt: holds no scan: no line of numbers x y z, or empty"), "{passed:?}");
        assert!(passed[1].ends_with("tile-empty.las: its header declares no points"), "{passed:?}");
        assert!(
            summary
                .lines()
                .iter()
                .any(|l| l.starts_with("passed by: ") && l.ends_with("its header declares no points"))
        );
        let recorded = std::fs::read(out.path().join("registration.json")).unwrap();
        assert_eq!(recorded::Registration::from_json(&recorded).unwrap().passed_by().len(), 2);
        let e = run(&[empty], &s, &RunOptions::default(), out.path()).unwrap_err().to_string();
        assert!(e.contains("every scan file given holds no points"), "{e}");
    }

    #[test]
    fn many_unregistered_scans_make_a_short_error() {
        let report = Path::new("out/registration.json");
        let reasons: Vec<(String, String)> =
            (0..7).map(|k| (format!("s{k}"), format!("scan 's{k}' does not register (fitness {k} %)"))).collect();
        let e = unregistered_error(&reasons[..2], report);
        assert!(
            e.starts_with(
                "scan 's0' does not register (fitness 0 %); scan 's1' does not register (fitness 1 %) (where the files are already in one frame, a registered survey exported in parts, set [scans] register = \"none\""
            ),
            "{e}"
        );
        let e = unregistered_error(&reasons, report);
        assert!(
            e.contains("'s4' does not register (fitness 4 %); and 2 more scans do not register (out/registration.json"),
            "{e}"
        );
        assert!(!e.contains("'s5'") && e.ends_with("will be missing)"), "{e}");
    }

    #[test]
    fn scans_refused_for_one_reason_share_it() {
        let report = Path::new("out/registration.json");
        let why = "is not merged: the scans placed against the reference scan 'r' do not agree with it";
        let mut reasons: Vec<(String, String)> =
            ["a", "b", "c"].iter().map(|n| (n.to_string(), format!("scan '{n}' {why}"))).collect();
        reasons.insert(1, ("d".into(), "scan 'd' does not register".into()));
        let e = unregistered_error(&reasons, report);
        assert_eq!(
            e.split(" (where the files are already in one frame").next().unwrap(),
            format!("scan 'a' {why} (the same for scans 'b', 'c'); scan 'd' does not register")
        );
        assert_eq!(e.matches("do not agree").count(), 1, "{e}");
        // Counted past the listed reasons by scan, not by reason.
        let mut many: Vec<(String, String)> =
            (0..5).map(|k| (format!("s{k}"), format!("scan 's{k}' does not register ({k})"))).collect();
        many.extend(reasons);
        let e = unregistered_error(&many, report);
        assert!(e.contains("; and 4 more scans do not register"), "{e}");
    }

    fn stations(text: &str) -> (tempfile::TempDir, PathBuf) {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("stations.toml");
        std::fs::write(&p, text).unwrap();
        (d, p)
    }

    #[test]
    fn station_values_are_finite_numbers() {
        let (_d, p) = stations("[[station]]\nscan = \"scan-1\"\nx_m = nan\ny_m = 2.0\n");
        let e = read_stations(&p).unwrap_err().to_string();
        assert!(e.contains("stations.toml:3:7") && e.contains("x_m = NaN is not a finite number"), "{e}");

        let (_d, p) = stations("[[station]]\nscan = \"scan-1\"\nx_m = 1.0\ny_m = 2.0\nyaw_deg = inf\n");
        let e = read_stations(&p).unwrap_err().to_string();
        assert!(e.contains("yaw_deg = inf is not a finite number"), "{e}");

        // Height and heading may be left out.
        let (_d, p) = stations("[[station]]\nscan = \"scan-1\"\nx_m = 1.0\ny_m = 2.0\n");
        let st = read_stations(&p).unwrap();
        assert_eq!((st[0].scan.as_str(), st[0].line), ("scan-1", 2));
        let t = st[0].pose.translation.vector;
        assert!((t.x - 1.0).abs() < 1e-12 && (t.y - 2.0).abs() < 1e-12 && t.z == 0.0, "{t:?}");
    }

    #[test]
    fn station_tolerances_come_from_the_station_the_file_or_the_default() {
        use register::StationTolerance;
        let text = "tolerance_m = 0.05\n\n[[station]]\nscan = \"a\"\nx_m = 1.0\ny_m = 2.0\nz_m = 3.0\nyaw_deg = 4.0\nyaw_tolerance_deg = 0.5\n\n[[station]]\nscan = \"b\"\nx_m = 1.0\ny_m = 2.0\ntolerance_m = 2.0\n";
        let (_d, p) = stations(text);
        let st = read_stations(&p).unwrap();
        // Height and yaw are held only where the station gives them.
        assert_eq!(st[0].tolerance, StationTolerance { plan_m: 0.05, height_m: Some(0.05), yaw_deg: Some(0.5) });
        assert_eq!(st[1].tolerance, StationTolerance { plan_m: 2.0, height_m: None, yaw_deg: None });
        let (_d, p) = stations("[[station]]\nscan = \"a\"\nx_m = 1.0\ny_m = 2.0\nyaw_deg = 4.0\n");
        let t = read_stations(&p).unwrap()[0].tolerance;
        assert_eq!(
            t,
            StationTolerance {
                plan_m: DEFAULT_STATION_TOLERANCE_M,
                height_m: None,
                yaw_deg: Some(DEFAULT_STATION_YAW_TOLERANCE_DEG)
            }
        );

        for (text, at, what) in [
            (
                "tolerance_m = 0.0\n[[station]]\nscan = \"a\"\nx_m = 1.0\ny_m = 2.0\n",
                "stations.toml:1:15",
                "tolerance_m = 0",
            ),
            (
                "[[station]]\nscan = \"a\"\nx_m = 1.0\ny_m = 2.0\nyaw_tolerance_deg = -1.0\n",
                "stations.toml:5:21",
                "yaw_tolerance_deg = -1",
            ),
            (
                "[[station]]\nscan = \"a\"\nx_m = 1.0\ny_m = 2.0\ntolerance_m = nan\n",
                "stations.toml:5:15",
                "tolerance_m = NaN",
            ),
        ] {
            let (_d, p) = stations(text);
            let e = read_stations(&p).unwrap_err().to_string();
            assert!(e.contains(at) && e.contains(what) && e.contains("a tolerance must be a positive number"), "{e}");
        }
    }

    #[test]
    fn station_file_places_some_scan_and_no_scan_twice() {
        let scans = [scan("scan-1"), scan("scan-2")];
        let (_d, p) = stations("[[station]]\nscan = \"scan1\"\nx_m = 1.0\ny_m = 2.0\n");
        let e = check_stations(&p, &read_stations(&p).unwrap(), &scans).unwrap_err().to_string();
        assert!(
            e.contains("stations.toml:2")
                && e.contains("\"scan1\" names no scan given")
                && e.contains("scan-1, scan-2"),
            "{e}"
        );

        let two = "[[station]]\nscan = \"scan-2\"\nx_m = 1.0\ny_m = 2.0\n\n[[station]]\nscan = \"scan-2\"\nx_m = 3.0\ny_m = 4.0\n";
        let (_d, p) = stations(two);
        let e = check_stations(&p, &read_stations(&p).unwrap(), &scans).unwrap_err().to_string();
        assert!(e.contains("\"scan-2\" has a second station (the first is on line 2)"), "{e}");

        // A station for a scan not delivered yet, beside one that places a scan.
        let later = "[[station]]\nscan = \"scan-2\"\nx_m = 1.0\ny_m = 2.0\n\n[[station]]\nscan = \"scan-9\"\nx_m = 3.0\ny_m = 4.0\n";
        let (_d, p) = stations(later);
        check_stations(&p, &read_stations(&p).unwrap(), &scans).unwrap();
    }

    /// A scan's name, from its file's name, is kept without control
    /// characters (a line break in a file's name printed a line of its own
    /// in the run's output) and to its first 200 characters and a tag; a
    /// station naming the scan as its file does still places it.
    #[test]
    fn scan_names_are_kept_without_control_characters_and_short() {
        let name = read::stem(Path::new("scans/scan-3\nerror: evil\x1b[2J.laz"));
        assert_eq!(name, "scan-3\u{FFFD}error: evil\u{FFFD}[2J");
        let long = "s".repeat(300);
        let name = read::stem(Path::new(&format!("scans/{long}.e57")));
        assert_eq!(name, liftplan_core::names::kept(&long, read::MAX_SCAN_NAME_CHARS));
        assert_eq!(name.chars().count(), 200 + liftplan_core::names::TAG_CHARS);
        let (_d, p) = stations(&format!("[[station]]\nscan = \"{long}\"\nx_m = 1.0\ny_m = 2.0\n"));
        let st = read_stations(&p).unwrap();
        assert_eq!(st[0].scan, name);
        check_stations(&p, &st, &[scan(&name), scan("scan-2")]).unwrap();
    }

    /// The scans' dates are said with where they come from: E57's
    /// acquisition (GPS seconds since 1980-01-06, a time no scan could
    /// have refused), a LAS file's creation date, or none.
    #[test]
    fn scan_dates_say_where_they_come_from() {
        let gps = |s: f64| read::ScanDate::from_gps_seconds(s).map(|d| d.date.to_string());
        assert_eq!(gps(0.0).as_deref(), Some("1980-01-06"));
        assert_eq!(gps(1.4e9).as_deref(), Some("2024-05-17"));
        for bad in [f64::NAN, -1.0, 1e20, f64::INFINITY] {
            assert_eq!(gps(bad), None, "{bad}");
        }
        let day =
            |d: u32, acquired| read::ScanDate { date: chrono::NaiveDate::from_ymd_opt(2026, 10, d).unwrap(), acquired };
        let report = |date: Option<read::ScanDate>| ScanReport {
            file: String::new(),
            name: String::new(),
            format: read::Format::E57,
            points_read: 0,
            points_kept: 0,
            pose: [[0.0; 4]; 4],
            fitness: 1.0,
            rmse_m: 0.0,
            method: String::new(),
            registered: true,
            warning: None,
            hold_m: None,
            refined_move_m: None,
            unit: String::new(),
            to_m: [1.0; 3],
            date,
        };
        let summary = |dates: Vec<Option<read::ScanDate>>| Summary {
            scans: dates.into_iter().map(report).collect(),
            passed_by: Vec::new(),
            points_read: 0,
            points_out: 0,
            ground_points: 0,
            bbox: [0.0; 6],
            register: RegisterMode::None,
            subsample: String::new(),
            registration_answers_reused: 0,
            registration_answers_worked_out: 0,
            fit_distance_m: 0.25,
            fit_residual_m: 0.03,
            min_fitness: 0.02,
        };
        let line = summary(vec![Some(day(3, true)), Some(day(2, true)), Some(day(20, false)), None]).date_line();
        assert_eq!(
            line,
            "scan dates: taken 2026-10-02 to 2026-10-03 (2 scans, as the files record their acquisition); files created 2026-10-20 (1 scan: the LAS files' creation date, which may be the export's, not the survey's); no date in the file for 1 scan: ask the survey team when the site was scanned if unsure"
        );
        assert!(
            summary(vec![None]).lines().iter().any(|l| l.starts_with("scan dates: no date in the file for 1 scan"))
        );
        // Registration's fitness is explained where it ran on several scans.
        let mut two = summary(vec![None, None]);
        assert!(!two.lines().iter().any(|l| l.starts_with("registration:")));
        two.register = RegisterMode::Auto;
        let lines = two.lines().join("\n");
        assert!(
            lines.contains("within 0.25 m and its surface within 0.03 m") && lines.contains("needs 2 % to register"),
            "{lines}"
        );
    }
}
