//! The project folder and `liftplan.toml`.
//!
//! The file is parsed raw with serde (`deny_unknown_fields` everywhere, so a typo
//! is an error with line and column, not a silently ignored setting), then
//! validated: paths must stay inside the project folder unless
//! `[paths] allow_outside = true`, stage settings must be in range, lifts must
//! name a crane that exists.

use anyhow::{Context, Result, anyhow, bail};
use liftplan_core::lift::LiftSpec;
use liftplan_core::location::{Location, toml_error};
use serde::{Deserialize, Serialize};
use std::path::{Component, Path, PathBuf};

pub const FILE: &str = "liftplan.toml";

/// A project-file error: where, and what. Exit code 2.
#[derive(Debug)]
pub struct ProjectError {
    pub location: Location,
    pub message: String,
}

impl std::fmt::Display for ProjectError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.location, self.message)
    }
}

impl std::error::Error for ProjectError {}

#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProjectMeta {
    pub name: String,
    /// Seed of every random stream (registration, planner).
    pub seed: u64,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Paths {
    /// Allow paths outside the project folder (absolute or with `..`).
    pub allow_outside: bool,
    pub scans: PathBuf,
    pub plant: PathBuf,
    pub charts: PathBuf,
    pub cranes: PathBuf,
}

impl Default for Paths {
    fn default() -> Self {
        Paths {
            allow_outside: false,
            scans: "scans".into(),
            plant: "plant".into(),
            charts: "charts".into(),
            cranes: "cranes".into(),
        }
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WatchSettings {
    /// Quiet time after the last change before a run starts (ms).
    pub settle_ms: u64,
    /// How long to wait for a file that does not parse yet to be completed (s).
    pub parse_wait_s: u64,
}

impl Default for WatchSettings {
    fn default() -> Self {
        WatchSettings { settle_ms: 1000, parse_wait_s: 10 }
    }
}

/// `[cache]`: how many runs' outputs each stage keeps in `.liftplan/cache/`.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CacheSettings {
    /// Cache entries kept per stage, the last run's included (1 to 100).
    pub keep: usize,
}

impl Default for CacheSettings {
    fn default() -> Self {
        CacheSettings { keep: 3 }
    }
}

pub use liftplan_depthmap::GpuUse;

#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GpuSettings {
    /// auto | never | require
    #[serde(rename = "use")]
    pub use_: GpuUse,
}

/// `liftplan.toml` as written.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawProject {
    #[serde(default)]
    pub project: ProjectMeta,
    #[serde(default)]
    pub paths: Paths,
    #[serde(default)]
    pub scans: liftplan_scans::Settings,
    #[serde(default)]
    pub plant: liftplan_plant::Settings,
    #[serde(default)]
    pub charts: liftplan_charts::Settings,
    #[serde(default)]
    pub depthmap: liftplan_depthmap::Settings,
    #[serde(default)]
    pub plan: liftplan_plan::Settings,
    #[serde(default)]
    pub docs: liftplan_docs::Settings,
    #[serde(default)]
    pub gpu: GpuSettings,
    #[serde(default)]
    pub watch: WatchSettings,
    #[serde(default)]
    pub cache: CacheSettings,
    #[serde(default)]
    pub lift: Vec<LiftSpec>,
    /// What is on site now that neither the scans nor the model hold,
    /// placed by hand ([`liftplan_core::obstacle`]).
    #[serde(default)]
    pub obstacle: Vec<liftplan_core::obstacle::Obstacle>,
    /// Overhead power lines, given by hand ([`liftplan_core::power_line`]).
    #[serde(default)]
    pub power_line: Vec<liftplan_core::power_line::PowerLine>,
}

/// A validated project.
#[derive(Debug, Clone)]
pub struct Project {
    pub dir: PathBuf,
    pub file: PathBuf,
    pub raw: RawProject,
}

impl Project {
    pub fn load(dir: &Path) -> std::result::Result<Project, ProjectError> {
        let file = dir.join(FILE);
        let text = liftplan_core::location::read_text(&file).map_err(|e| match e {
            liftplan_core::location::TextReadError::Io(e) => ProjectError {
                location: Location::file(&file),
                message: if e.kind() == std::io::ErrorKind::NotFound {
                    format!("no {FILE} here (run `liftplan init {}` to create a project)", dir.display())
                } else {
                    e.to_string()
                },
            },
            liftplan_core::location::TextReadError::NotUtf8(location, message) => ProjectError { location, message },
        })?;
        let raw: RawProject = toml::from_str(&text).map_err(|e| {
            let (location, message) = toml_error(&file, &text, &e);
            ProjectError { location, message }
        })?;
        let p = Project { dir: dir.to_path_buf(), file: file.clone(), raw };
        p.validate(&text)?;
        Ok(p)
    }

    /// Line of the first occurrence of `needle` in the file, for error places.
    /// The `k`-th `header` table (`[[obstacle]]`), else (the list given
    /// inline) where `name` is first quoted.
    fn table_location(&self, text: &str, header: &str, k: usize, name: &str) -> Location {
        match text.match_indices(header).nth(k) {
            Some((off, _)) => Location::in_text(&self.file, text, off),
            None => self.locate(text, &format!("\"{name}\"")),
        }
    }

    fn locate(&self, text: &str, needle: &str) -> Location {
        match text.find(needle) {
            Some(off) => Location::in_text(&self.file, text, off),
            None => Location::file(&self.file),
        }
    }

    fn validate(&self, text: &str) -> std::result::Result<(), ProjectError> {
        let err = |needle: &str, message: String| ProjectError { location: self.locate(text, needle), message };
        let p = &self.raw.paths;
        for (key, path) in [("scans", &p.scans), ("plant", &p.plant), ("charts", &p.charts), ("cranes", &p.cranes)] {
            self.check_inside(path).map_err(|m| err(&format!("{key} ="), format!("[paths] {key}: {m}")))?;
            let full = self.dir.join(path);
            if !full.is_dir() {
                return Err(err(
                    &format!("{key} ="),
                    format!("[paths] {key}: folder {} does not exist{}", full.display(), windows_separators(path)),
                ));
            }
        }
        if let Some(st) = &self.raw.scans.stations {
            self.check_inside(st).map_err(|m| err("stations", format!("[scans] stations: {m}")))?;
            if !self.dir.join(st).is_file() {
                return Err(err(
                    "stations",
                    format!(
                        "[scans] stations: file {} does not exist{}",
                        self.dir.join(st).display(),
                        windows_separators(st)
                    ),
                ));
            }
        }
        // On every page's foot and the cover, as a lift's names are bounded.
        let name_chars = self.raw.project.name.chars().count();
        if name_chars > liftplan_core::lift::MAX_NAME_CHARS {
            return Err(err(
                "[project]",
                format!(
                    "[project] name is longer than {} characters ({name_chars}): shorten it",
                    liftplan_core::lift::MAX_NAME_CHARS
                ),
            ));
        }
        self.raw.scans.check().map_err(|m| err("[scans]", format!("[scans] {m}")))?;
        self.raw.plant.check().map_err(|m| err("[plant]", format!("[plant] {m}")))?;
        self.raw.depthmap.check().map_err(|m| err("[depthmap]", format!("[depthmap] {m}")))?;
        self.raw.plan.check().map_err(|m| {
            // The message starts with its table ("[plan.ga] ..."): point there.
            let table = m.strip_prefix('[').and_then(|r| r.split_once(']')).map(|(t, _)| format!("[{t}]"));
            let needle = table.filter(|t| text.contains(t.as_str())).unwrap_or_else(|| "[plan]".into());
            err(&needle, m)
        })?;
        if !(1..=100).contains(&self.raw.cache.keep) {
            return Err(err(
                "[cache]",
                format!(
                    "[cache] keep = {}: each stage keeps 1 to 100 runs' outputs (the last run's included)",
                    self.raw.cache.keep
                ),
            ));
        }
        let lift_ids: Vec<&str> = self.raw.lift.iter().map(|l| l.id.as_str()).collect();
        if let Some((k, m)) = liftplan_core::obstacle::problem_of(&self.raw.obstacle, &lift_ids) {
            let name = self.raw.obstacle.get(k).map_or("", |o| o.name.as_str());
            return Err(ProjectError { location: self.table_location(text, "[[obstacle]]", k, name), message: m });
        }
        if let Some((k, m)) = liftplan_core::power_line::problem_of(&self.raw.power_line, &lift_ids) {
            let name = self.raw.power_line.get(k).map_or("", |l| l.name.as_str());
            return Err(ProjectError { location: self.table_location(text, "[[power_line]]", k, name), message: m });
        }
        let mut ids = std::collections::HashSet::new();
        for l in &self.raw.lift {
            if !ids.insert(l.id.clone()) {
                return Err(err(&format!("\"{}\"", l.id), format!("lift id '{}' is used twice", l.id)));
            }
            let model =
                self.crane_model(&l.crane.model).map_err(|e| err(&l.crane.model, format!("lift '{}': {e:#}", l.id)))?;
            l.resolve(model).map_err(|m| err(&format!("\"{}\"", l.id), m))?;
        }
        Ok(())
    }

    /// Every lift, validated against its crane model.
    pub fn lifts(&self) -> Result<Vec<liftplan_core::lift::LiftTask>> {
        self.raw.lift.iter().map(|l| l.resolve(self.crane_model(&l.crane.model)?).map_err(anyhow::Error::msg)).collect()
    }

    /// Crane files the lifts use (for the stages' inputs).
    pub fn crane_files(&self) -> Vec<PathBuf> {
        let mut v: Vec<PathBuf> = self
            .raw
            .lift
            .iter()
            .map(|l| self.path(&self.raw.paths.cranes).join(format!("{}.toml", l.crane.model)))
            .filter(|p| p.is_file())
            .collect();
        v.sort();
        v.dedup();
        v
    }

    /// Refuses absolute paths and `..` unless `allow_outside`.
    pub fn check_inside(&self, p: &Path) -> std::result::Result<(), String> {
        if self.raw.paths.allow_outside {
            return Ok(());
        }
        if p.is_absolute()
            || p.components().any(|c| matches!(c, Component::ParentDir | Component::Prefix(_) | Component::RootDir))
        {
            return Err(format!(
                "'{}' leaves the project folder; write it relative to the project, or set [paths] allow_outside = true",
                p.display()
            ));
        }
        Ok(())
    }

    pub fn path(&self, rel: &Path) -> PathBuf {
        self.dir.join(rel)
    }

    /// A crane model: a file `cranes/<name>.toml` if present, else a built-in.
    pub fn crane_model(&self, name: &str) -> Result<liftplan_core::crane::CraneModel> {
        if name.contains(['/', '\\']) || name.contains("..") {
            bail!("crane model '{name}' must be a built-in name or a file name in the cranes folder");
        }
        let file = self.path(&self.raw.paths.cranes).join(format!("{name}.toml"));
        if file.is_file() {
            return liftplan_core::crane::CraneModel::from_file(&file).map_err(|e| anyhow!("{e}"));
        }
        liftplan_core::crane::builtin(name).map_err(|e| anyhow!("{e}; no file {} either", file.display()))
    }

    /// Files in a project folder with one of `exts`, sorted by name.
    pub fn files(&self, folder: &Path, exts: &[&str]) -> Result<Vec<PathBuf>> {
        let dir = self.path(folder);
        let mut out = Vec::new();
        let rd = std::fs::read_dir(&dir).with_context(|| format!("reading {}", dir.display()))?;
        for e in rd {
            let e = e?;
            let p = e.path();
            let name = e.file_name().to_string_lossy().into_owned();
            if is_hidden_or_office_owner(&name) || !p.is_file() {
                continue;
            }
            let ext = p.extension().and_then(|x| x.to_str()).unwrap_or("").to_ascii_lowercase();
            if exts.contains(&ext.as_str()) {
                out.push(p);
            }
        }
        out.sort();
        Ok(out)
    }

    pub fn state_dir(&self) -> PathBuf {
        state_dir_of(&self.dir)
    }

    pub fn out_dir(&self) -> PathBuf {
        out_dir_of(&self.dir)
    }
}

/// The cache, memos and logs of the project in `dir`, whether or not its
/// file reads.
pub fn state_dir_of(dir: &Path) -> PathBuf {
    dir.join(".liftplan")
}

/// The outputs of the project in `dir`, whether or not its file reads.
pub fn out_dir_of(dir: &Path) -> PathBuf {
    dir.join("out")
}

/// The commented `liftplan.toml` that `init` writes.
pub const TEMPLATE: &str = r#"# liftplan project file. Paths are relative to this folder.
# Every section is optional; the values shown are the defaults.

[project]
name = "my site"
seed = 1                  # seed of every random stream: same inputs + seed = same plan

[paths]
allow_outside = false     # allow paths outside this folder (absolute, or with ..)
scans = "scans"           # *.las *.laz *.ply *.e57 *.ptx *.pts *.xyz *.txt *.csv from the survey team
plant = "plant"           # *.rvm (+ .att) plant exports, *.ifc, *.obj *.ply *.stl *.gltf *.glb meshes
charts = "charts"         # *.xlsx *.xlsm *.xls *.xlsb *.ods load charts
cranes = "cranes"         # crane geometry files (<name>.toml); built in: ltm-1100, ac-700, tower-hh-60

[scans]
register = "auto"         # auto: register, from a file's or station's pose where given;
                          # poses: take the poses E57 and PTX files or stations give;
                          # none: coordinates as they are (a survey registered already)
subsample = "voxel"       # voxel | spacing | nth | none
voxel = 0.05              # voxel edge, m
voxel_point = "centroid"  # centroid | nearest
spacing = 0.05            # minimum point spacing for subsample = "spacing", m
every_nth = 9             # keep every Nth point for subsample = "nth"
# unit = "m"              # m | ft | us-ft: unit of scan files that state none (metres where
                          # unset; a LAS/LAZ CRS's unit, and E57's metres, are applied whatever
                          # this says); needed for a LAS/LAZ CRS named by an EPSG code alone
# stations = "stations.toml"   # surveyed scanner poses: [[station]] scan, x_m, y_m, z_m, yaw_deg;
#                              # registration keeps each scan within tolerance_m (plan and height,
#                              # default 0.5) and yaw_tolerance_deg (default 3) of its station,
#                              # set per station or, at the top of the file, for all; the first
#                              # scan with a station is the reference (the station file's frame);
#                              # give the survey's real tolerance: where what a scan shares with
#                              # the others holds it loosely (a corridor), only a station within
#                              # 0.18 m pins it down
on_unregistered = "fail"  # fail | exclude
# [scans.registration]
# leveled = true          # false for scanners that did not level themselves (no compensator):
                          # each scan is levelled by its walls and tanks (else its ground, and
                          # on a slope the site frame slopes with it); the run's lines say which

[scans.ground]
enabled = true
cell_m = 1.0
slope = 0.15
window_m = 18.0
threshold_m = 0.5
scalar = 1.25

[plant]
tolerance = 0.01          # RVM tessellation: how far outside a primitive its mesh may lie (never inside), m
cull_caps = true          # leave out end caps hidden inside connected primitives
# unit = "mm"             # m | mm | cm | ft | in: unit of OBJ/PLY/STL files, which state none
# up_axis = "z"            # z | y: their up axis; both must be set where there are such files
                          # (glTF is always metres and Y-up, RVM millimetres and Z-up)
include = []              # keep only groups matching these names (* and ? wildcards)
exclude = []              # leave out groups, e.g. the item being lifted: ["/V-101*"]
exclude_where = []        # leave out by attribute, e.g. ["Purpose=TEMP*"]
insulation = true         # keep insulation volumes
obstructions = true       # keep obstruction volumes
translate_m = [0.0, 0.0, 0.0]   # place the model in the site frame: rotate about Z, then translate
rotate_z_deg = 0.0

[charts]
# length_unit = "m"         # unit of chart grids whose labels name none: m | ft
# capacity_unit = "t"       # t | kg | lb | kips | shortton | kN | daN (a weight's); such a grid is refused unless these say

# [[charts.table]]         # describe a chart grid that detection gets wrong
# file = "chart.xlsx"
# sheet = "Main boom"
# config = "main boom 360"  # the name lifts use in crane.chart_config
# across = "C6:P6"          # boom lengths (radii if transposed = true)
# down = "B7:B45"           # radii (boom lengths if transposed = true)
# length_unit = "m"         # m | ft
# capacity_unit = "t"       # t | kg | lb | kips

[depthmap]
cell_m = 0.25             # plan cell of the multi-level depth map, m
mode = "multi"            # multi | single (2.5D: everything under a cell's top is solid)
point_radius_m = 0.05     # space each scan point occupies, m
merge_gap_m = 0.1         # surfaces of one object closer than this merge, m
extent = []               # [xmin, ymin, xmax, ymax]; empty: all inputs + margin_m
margin_m = 10.0

[plan]
planner = "mspga"         # mspga | ali-ga | rrt-connect | prm
landing_margin_m = 0.5    # landing zones: load footprint at pick/set grown by this, m
landing_clearance_m = 0.2 # clearance of hook and load over a landing zone, m
support_m = 0.05          # obstacles this close under the load at pick/set are its supports, m
validator_sample_m = 0.05 # validator: largest crane-point movement between evenly spaced samples, m (finer where needed)
load_cutout_m = 0.1       # scan points this close to the load at pick (0.3 m above it: slings) are taken for the load and not checked, m
model_off_scans = "refuse" # refuse | warn: a plant model that lies on the scans only when moved
found_lines_approach_m = 0.0 # keep this far off each run of line-like scan points near a lift (a line no
                          # [[power_line]] gives), as off a power line of unknown voltage, m; 0: name them only

[plan.ga]                 # Cai 2016, Table 4.10
population = 100
string_length = 6
crossover_rate = 0.15
mutation_rate = 0.75
small_scale = 0.016
large_scale = 0.16
max_generations = 400
stall_generations = 120
lambda1 = 1000.0
lambda2 = 10.0
swing_margin_deg = 20.0
restarts = 2              # no feasible path either way: start again from new strings, up to this many times

[plan.ga.weights]         # motion cost per unit (Cai Table 4.13)
swing_per_deg = 1.0
luff_per_deg = 1.5
hoist_per_cm = 0.06
rotate_per_deg = 1.0

[plan.cspace]
swing_step_deg = 0.5
luff_step_deg = 0.5
trolley_step_m = 0.25
strategy = "hybrid"       # hybrid | online | full
sample_m = 0.3            # online checks: largest hook/load movement per exactly checked piece, m
full_hoist_step_m = 0.5

[docs]
paper = "a4"              # a4 | letter
step_pictures = true      # one page per step with its picture

[gpu]
use = "auto"              # auto | never | require

[watch]
settle_ms = 1000          # quiet time after the last change before a rerun
parse_wait_s = 10         # how long to wait for a dropped file to become readable

[cache]
keep = 3                  # runs' outputs each stage keeps in .liftplan/cache (the last included)

# Something on site that neither the scans nor the model hold (a truck parked
# since the survey, a scaffold, stacked materials): a box the planner and the
# validator keep the crane and the load clearance_m off. Add one and run again
# to re-plan: only the plan and its document are made again. Uncomment and edit.
# [[obstacle]]
# name = "delivery truck"
# center_m = [12.0, -4.0]      # its centre in plan, m (the frame of the pick and set)
# base_z_m = 0.0               # its underside: the ground's height where it stands, m
# size_m = [10.0, 2.5, 4.0]    # length (along yaw_deg), width, height, m
# yaw_deg = 30.0               # its length's direction, anticlockwise from x, degrees
# lifts = ["V-101"]            # only during these lifts (leave it out: every lift)

# An overhead power line (scans show thin wires poorly, and never their voltage):
# every part of the crane, its rope and its load is kept approach_m off its
# conductor (leave it out: OSHA 1926.1408 Table A's for the voltage, 3.05 m up
# to 50 kV). Give each conductor, or the outermost on each side. Where the scans
# caught a line that none of these runs along, the plan names it (NOT A GIVEN
# POWER LINE) and its cover asks what it is first. Uncomment and edit.
# [[power_line]]
# name = "11 kV feeder"
# points_m = [[-30.0, 40.0, 9.0], [45.0, 38.0, 9.5]]   # where it is held (pole tops), in order, m
# sag_m = 1.0                  # the most it hangs below the straight line at mid-span, m
# least_sag_m = 0.6            # the least (cold, carrying little), m (leave it out: sag_m)
# swing_deg = 30.0             # how far the wind may swing it sideways, degrees (leave it out: plumb)
# voltage_kv = 11.0
# approach_m = 6.0             # the distance kept, m (a rule stricter than Table A's)

# A lift: uncomment and edit.
# [[lift]]
# id = "V-101"
# description = "Vessel from trailer onto its foundation"
# load = { name = "vessel V-101", mass_t = 12.0, size_m = [8.0, 3.0, 3.0], cog_m = [0.0, 0.0, 0.0] }
# # load: cog_m from the box's centre, m; add cog_tolerance_m = 0.1 where it is known only to so
# # many metres either way along x and y: the legs and the load's balance where it is set are
# # then checked at the worst within it; cog_tolerance_z_m = 0.2 likewise in height, for
# # the load not to turn over on one or two legs with its centre of gravity at its highest.
# rigging = { mass_t = 0.4, height_m = 4.0, legs = 2, leg_wll_t = 10.0 }
# # rigging: height_m from the hook block's underside to the load's top; legs 1, 2 or
# # 4 (the top's centre, the middles of its short edges, its corners) or lift_points_m
# # = [[x, y, z], ...] from the box's centre, and each leg's working load limit: the
# # legs' angles and the most one carries are checked (leave leg_wll_t out: not checked);
# # hitch = "choked" rates legs choked round the load at 0.8 of leg_wll_t; shackle_wll_t
# # and lift_point_wll_t check the shackle and the lug at each lift point against its pull.
# # pin_axes = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]] gives each shackle's pin direction (its
# # lug's hole, load frame, one per lift point): the shackles are then taken at the makers'
# # side-loading share for how far the legs pull out of line (else taken in line).
# # Two legs hanging plumb from a beam: add spreader = { length_m = 8.0, below_hook_m =
# # 2.0, wll_t = 20.0, mass_t = 0.3, top_leg_wll_t = 12.0 } to rigging (its pins over the
# # lift points, below_hook_m under the hook block; leave top_leg_wll_t out for a lifting
# # beam hung by its lug; mass_t is part of rigging's); it must lie within the footprint.
# # With width_m = 2.5 in spreader it is a frame over four lift points (legs = 4).
# # top_shackle_wll_t = 12.0 in spreader checks the shackles at its top lugs, and
# # top_pin_axes = [[0.0, 1.0, 0.0], ...] (one per top leg) their side loading.
# crane = { model = "ltm-1100", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 0.0, boom_m = 40.0, chart_config = "main boom, 360 deg" }
# # crane: add falls = 4 (the parts of line the hoist rope is reeved with) to have them
# # checked against the crane file's [hook] line_pull_t (per fall) and rated_t, and, where
# # it gives rope_m and rope_lead_m, how far the hoist rope lets the hook down on them.
# # Where the crane file weighs the rope ([hook] rope_kg_per_m), the rope below the boom
# # head is part of the gross load, on every fall, at the longest rope the lift is planned
# # with: add longest_rope_m = 30.0 to crane to keep the hook within that much rope below
# # the head and count no more (left out: the hook's whole travel).
# pick = { x_m = 6.0, y_m = -16.0, z_m = 1.2, yaw_deg = 90.0 }
# set = { x_m = 30.0, y_m = 2.0, z_m = 1.2, yaw_deg = 0.0 }
# # pick and set: the load's centre x, y and its underside's z (m), its yaw (degrees);
# # or a crane configuration: swing_deg, luff_deg (or trolley_m), hoist_m, yaw_deg.
# # crane may also give deductions_t: what the chart's notes deduct (a stowed jib), t.
# # To re-plan a lift stopped part way (the site changed: add an [[obstacle]]), give
# # where the load hangs now, as the crane shows it or the plan's steps give it:
# # resume_from = { swing_deg = -60.0, luff_deg = 49.0, hoist_m = 13.0, yaw_deg = 22.5 }
# # resumes_plan = { revision = "3f9a2c1b", after_step = 4 }   # the crew's plan (optional)
# # the plan then starts there, with no lift-off, and its cover says so; `liftplan
# # resume DIR LIFT --plan REVISION --after-step N` prints both lines.
# clearance_m = 1.0            # kept by every part from everything, m
# liftoff_m = 0.5              # vertical lift-off at the pick and set-down at the set, m
# critical_pct = 75.0          # utilisation over which the lift is flagged critical, %
# capacity_reduction_pct = 0.0 # taken off every chart value (site rules, wind), %
# radius_allowance_m = 0.0     # added to every radius before the chart is read
#                              # (the boom bending under load), m
# fall_zone_m = 0.0            # people kept this far round the ground under the load too,
#                              # and the load planned this far off not_over areas, m
# swing_range_deg = [-120.0, 120.0] # permitted slewing sector from the crane's heading;
#                                   # leave it out for a crane free to slew
# ground = { mat_m = [2.5, 2.5], allowable_kpa = 200.0 } # each outrigger pad's mat (m) and
#                              # what the ground may bear (kPa), for the pressure under
#                              # the pads: estimated from the crane file's [masses]; crane
#                              # may also give counterweight_t, the counterweight rigged
# wind = { chart_ms = 9.8, cw = 1.2 } # the chart's permissible wind speed (m/s; else the
#                              # one its sheet states) and the load's drag
#                              # coefficient, for the wind speed it may be
#                              # lifted in (mobile cranes); area_m2: its area facing the
#                              # wind, else its box's largest side; the plan keeps its
#                              # clearance with the load swung as far as a gust at that
#                              # speed can swing it (plan_for_swing = false: plumb), the
#                              # wind on the hoist rope's falls too where the crane file
#                              # gives [hook] rope_diameter_mm (or rope_kg_per_m)
# not_over = [{ name = "control room", corners_m = [[40.0, -10.0], [52.0, -10.0], [52.0, 4.0], [40.0, 4.0]] },
#             { name = "railway", corners_m = [[-20.0, -30.0], [-14.0, -30.0], [-14.0, 30.0], [-20.0, 30.0]], crane_too = true }]
#                              # areas the load must never be over (their corners in
#                              # plan, in order around them, m); the planner keeps the
#                              # load's footprint 0.25 m off them; crane_too: the crane's
#                              # boom, counterweight, rope and hook may not be over it
#                              # either (no oversailing)
# crane_stands_in = [{ name = "hardstanding", corners_m = [[-12.0, -9.0], [16.0, -9.0], [16.0, 9.0], [-12.0, 9.0]] }]
#                              # where the crane may be set up (its carrier and outriggers
#                              # within one of these, in plan, m): the lift's set-up is
#                              # checked against them and other positions are sought
#                              # only there (leave it out: anywhere)
"#;

/// Creates a project folder with the template and the input folders.
pub fn init(dir: &Path) -> Result<()> {
    let file = dir.join(FILE);
    if file.exists() {
        bail!("{} already exists; not overwriting it", file.display());
    }
    for sub in ["scans", "plant", "charts", "cranes"] {
        std::fs::create_dir_all(dir.join(sub)).with_context(|| format!("creating {}", dir.join(sub).display()))?;
    }
    liftplan_core::artifact::write_atomic(&file, TEMPLATE.as_bytes())
        .with_context(|| format!("writing {}", file.display()))?;
    let example = dir.join("cranes").join("example-ltm-1100.toml");
    if let Some(text) = liftplan_core::crane::builtin_text("ltm-1100") {
        liftplan_core::artifact::write_atomic(&example, text.as_bytes())?;
    }
    Ok(())
}

/// Whether a file in a project folder is hidden (a dot file, or the files
/// Windows keeps hidden in a folder it has shown: `Thumbs.db`,
/// `desktop.ini`), or the owner file Microsoft Office keeps beside a
/// workbook while it is open ("~$chart.xlsx", a few bytes, no workbook: read
/// as a chart it failed the run while the chart was open in Excel). None is
/// an input, nor a file not read worth naming.
pub fn is_hidden_or_office_owner(name: &str) -> bool {
    name.starts_with('.')
        || name.starts_with("~$")
        || name.eq_ignore_ascii_case("thumbs.db")
        || name.eq_ignore_ascii_case("desktop.ini")
}

/// What to add to "does not exist" for a path written with Windows'
/// separators, which are none here.
fn windows_separators(path: &Path) -> &'static str {
    if cfg!(windows) || !path.to_string_lossy().contains('\\') {
        ""
    } else {
        " ('\\' separates no folders here: write the path with '/', which serves on Windows too)"
    }
}

#[cfg(test)]
mod tests {
    /// The template's example lift, uncommented as its comment says, is a
    /// lift liftplan takes, every key it shows included.
    #[test]
    fn the_templates_example_lift_uncommented_resolves() {
        let lift: String = super::TEMPLATE
            .split("# A lift: uncomment and edit.\n")
            .nth(1)
            .expect("the template has an example lift")
            .lines()
            .map(|l| l.strip_prefix("# ").unwrap_or(l))
            .collect::<Vec<_>>()
            .join("\n");
        let v: toml::Value = toml::from_str(&lift).unwrap_or_else(|e| panic!("{e}\n{lift}"));
        let spec: liftplan_core::lift::LiftSpec = v["lift"][0].clone().try_into().unwrap();
        for key in [
            "liftoff_m",
            "critical_pct",
            "capacity_reduction_pct",
            "radius_allowance_m",
            "swing_range_deg",
            "ground",
            "wind",
            "not_over",
            "crane_stands_in",
        ] {
            assert!(v["lift"][0].get(key).is_some(), "{key} is not shown");
        }
        let task = spec.resolve(liftplan_core::crane::builtin("ltm-1100").unwrap()).unwrap();
        assert_eq!(task.id, "V-101");
        assert!(task.permissible_wind(&[]).is_ok());
        assert_eq!(task.not_over[0].name, "control room");
        assert!(!task.not_over[0].crane_too && task.not_over[1].crane_too);
        assert_eq!(task.crane_stands_in[0].name, "hardstanding");
        assert_eq!(task.stands_outside_its_areas(), None);
    }

    /// A project folder's files leave out hidden files and the owner file
    /// Excel keeps beside a workbook while it is open ("~$chart.xlsx"): read
    /// as a chart, it failed the run ("invalid Zip archive") while the
    /// chart was open.
    #[test]
    fn office_owner_files_are_no_inputs() {
        let d = tempfile::tempdir().unwrap();
        super::init(d.path()).unwrap();
        let p = super::Project::load(d.path()).unwrap();
        let charts = d.path().join(&p.raw.paths.charts);
        for name in ["ac700.xlsx", "~$ac700.xlsx", ".~lock.ac700.xlsx#", ".hidden.xlsx"] {
            std::fs::write(charts.join(name), b"x").unwrap();
        }
        let files = p.files(&p.raw.paths.charts, &["xlsx"]).unwrap();
        assert_eq!(files, [charts.join("ac700.xlsx")]);
    }

    /// A project file saved in the system's code page (Notepad's "ANSI") is
    /// refused at its first byte that is not UTF-8 (it was refused as
    /// "stream did not contain valid UTF-8", no place, nothing to do); one
    /// in UTF-8 with a byte order mark loads.
    #[test]
    fn a_project_file_not_in_utf8_is_refused_where_it_is() {
        let d = tempfile::tempdir().unwrap();
        super::init(d.path()).unwrap();
        let file = d.path().join(super::FILE);
        let template = std::fs::read(&file).unwrap();
        std::fs::write(&file, [&b"# Kranstellfl\xe4che S\xfcd\n"[..], &template].concat()).unwrap();
        let e = super::Project::load(d.path()).unwrap_err().to_string();
        assert!(e.contains("liftplan.toml:1:14: not UTF-8 text (byte 0xE4): save the file as UTF-8"), "{e}");
        std::fs::write(&file, [&b"\xef\xbb\xbf# Kranstellfl\xc3\xa4che\n"[..], &template].concat()).unwrap();
        assert!(super::Project::load(d.path()).is_ok());
    }

    /// The template's commented `[scans.registration]`, uncommented with
    /// `leveled = false`, is a setting liftplan takes.
    #[test]
    fn the_templates_registration_setting_uncommented_is_taken() {
        let part: String = super::TEMPLATE
            .split("# [scans.registration]\n")
            .nth(1)
            .and_then(|rest| rest.split("\n\n").next())
            .expect("the template shows [scans.registration]")
            .lines()
            .map(|l| l.strip_prefix("# ").unwrap_or(l))
            .collect::<Vec<_>>()
            .join("\n");
        assert!(part.contains("leveled = true"), "{part}");
        let raw: super::RawProject =
            toml::from_str(&format!("[scans.registration]\n{}", part.replace("leveled = true", "leveled = false")))
                .unwrap();
        assert!(!raw.scans.registration.leveled);
    }

    /// The template's commented example table `[[table]]`, uncommented, as
    /// a project file holding only it.
    fn templates_example(table: &str) -> super::RawProject {
        let example: String = super::TEMPLATE
            .split(&format!("# [[{table}]]\n"))
            .nth(1)
            .and_then(|rest| rest.split("\n\n").next())
            .unwrap_or_else(|| panic!("the template has no example [[{table}]]"))
            .lines()
            .map(|l| l.strip_prefix("# ").unwrap_or(l))
            .collect::<Vec<_>>()
            .join("\n");
        toml::from_str(&format!("[[{table}]]\n{example}")).unwrap()
    }

    /// The template's example obstacle, uncommented, is one liftplan takes.
    #[test]
    fn the_templates_example_obstacle_uncommented_is_taken() {
        let raw = templates_example("obstacle");
        // For the template's example lift.
        assert_eq!(liftplan_core::obstacle::problem_of(&raw.obstacle, &["V-101"]), None);
        assert_eq!(raw.obstacle[0].lifts, ["V-101"]);
        assert_eq!(
            raw.obstacle[0].said(),
            "delivery truck, 10.00 x 2.50 x 4.00 m at x 12.00, y -4.00 m, underside at z 0.00 m, turned 30.0°"
        );
    }

    /// The template's example power line, uncommented, is one liftplan
    /// takes.
    #[test]
    fn the_templates_example_power_line_uncommented_is_taken() {
        let raw = templates_example("power_line");
        assert_eq!(liftplan_core::power_line::problem_of(&raw.power_line, &["V-101"]), None);
        let said = raw.power_line[0].said();
        assert!(said.ends_with("kept 6.00 m off (approach_m)"), "{said}");
        assert!(said.contains("sagging 0.60 to 1.00 m at mid-span, swinging up to 30 degrees either way"), "{said}");
    }
}
