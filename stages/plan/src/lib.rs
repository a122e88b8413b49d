//! # liftplan-plan: stage 5, lift paths
//!
//! For each lift: build the hybrid C-space ([`liftplan_cspace`]), plan from the
//! lifted-off pick configuration to the configuration above the set position
//! with MSPGA ([`mspga`]; both swing directions), shorten the path, turn it into
//! single-joint operator steps ([`path`], [`steps`]), and check the whole lift,
//! lift-off and set-down included, with the independent [`validate`]or. A lift
//! the validator rejects fails the stage: no plan is written for it.
//!
//! | file | what |
//! |---|---|
//! | `plan.json` | every lift: verdict, summary, steps, node and move configurations (the export for crane control) |
//! | `<lift>.steps.csv` | the operator steps (Table 6.1 style) |
//! | `<lift>.cspace.png` | the C-space with the path |
//!
//! Baselines for the benchmarks live in [`baselines`].

pub mod baselines;
pub mod bench;
pub mod coverage;
mod hints;
pub mod load_scan;
pub mod model_copy;
pub mod mspga;
pub mod path;
pub mod positions;
pub mod resumed;
pub mod steps;
pub mod validate;
pub mod wires;

use liftplan_core::Location;
use liftplan_core::capacity::{CapacityTable, ChartConfig};
use liftplan_core::crane::{Config, Placement};
use liftplan_core::lift::LiftTask;
use liftplan_core::mesh::TriMesh;
use liftplan_core::obb::Obb;
use liftplan_core::obstacle::Obstacle;
use liftplan_core::power_line::PowerLine;
use liftplan_cspace::{CSpace, Checker, Joint, LandingZone, Problem};
use liftplan_depthmap::mdm::Mdm;
use liftplan_depthmap::query::LeaveOut;
use path::Move;
use serde::{Deserialize, Serialize};
use std::path::Path;

pub const NAME: &str = "plan";
pub const VERSION: u32 = 1;

#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    #[error("{0}: {1}")]
    Input(Location, String),
    #[error("[plan] {0}")]
    Settings(String),
    #[error("lift '{lift}': {message}")]
    Lift { lift: String, message: String },
    #[error("{0}")]
    ModelOffScans(String),
}

pub type Result<T> = std::result::Result<T, PlanError>;

/// Which planner produces the plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Planner {
    #[default]
    Mspga,
    AliGa,
    RrtConnect,
    Prm,
}

/// `[plan]` in `liftplan.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    pub planner: Planner,
    pub ga: mspga::GaSettings,
    pub cspace: liftplan_cspace::Settings,
    pub baselines: baselines::BaselineSettings,
    /// Landing zones: the load's footprint at pick and set grown by this (m).
    pub landing_margin_m: f64,
    /// Clearance of the hanging parts while the load is over a landing zone (m).
    pub landing_clearance_m: f64,
    /// Obstacles this close under the load at pick/set are its supports (m).
    pub support_m: f64,
    /// Validator: largest displacement of any crane point between samples (m).
    pub validator_sample_m: f64,
    /// Scan points this close to the load's box at pick (and up to
    /// [`LOAD_CUTOUT_ABOVE_M`] above it) are taken for the load and left out (m).
    pub load_cutout_m: f64,
    /// What a plant model that lies on the scans only when moved does to
    /// the plan ([`validate::model_offset_to_scans`]).
    pub model_off_scans: ModelOffScans,
    /// How far every part of the crane, its rope and its load is kept off
    /// each run of line-like scan points found near a lift ([`wires`]), as
    /// off a power line of unknown voltage (m); 0: the runs are named and
    /// asked about, and kept off by the lift's clearance only, as every scan
    /// point is.
    pub found_lines_approach_m: f64,
}

/// `[plan] model_off_scans`: a plant model placed off the scans puts its
/// obstacles where they are not, and leaves those only it shows (what the
/// scans did not see) out of where they are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ModelOffScans {
    /// No plan: the move that puts it on the scans is said.
    #[default]
    Refuse,
    /// Plan with the model where it is; the run and the PDF say it is off.
    Warn,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            planner: Planner::Mspga,
            ga: mspga::GaSettings::default(),
            cspace: liftplan_cspace::Settings::default(),
            baselines: baselines::BaselineSettings::default(),
            landing_margin_m: 0.5,
            landing_clearance_m: 0.2,
            support_m: 0.05,
            validator_sample_m: 0.05,
            load_cutout_m: LOAD_CUTOUT_GROW_M,
            model_off_scans: ModelOffScans::Refuse,
            found_lines_approach_m: 0.0,
        }
    }
}

impl Settings {
    pub fn check(&self) -> std::result::Result<(), String> {
        self.ga.check()?;
        self.cspace.check()?;
        self.baselines.check()?;
        let ok = |v: f64, lo: f64, hi: f64| v.is_finite() && v >= lo && v <= hi;
        if !ok(self.landing_margin_m, 0.0, 5.0)
            || !ok(self.landing_clearance_m, 0.0, 5.0)
            || !ok(self.support_m, 0.0, 0.5)
        {
            return Err("[plan] landing_margin_m and landing_clearance_m must be 0..5 m, support_m 0..0.5 m".into());
        }
        if !ok(self.validator_sample_m, 0.001, 0.5) {
            return Err("[plan] validator_sample_m must be between 0.001 and 0.5 m".into());
        }
        if !ok(self.load_cutout_m, 0.0, 1.0) {
            return Err("[plan] load_cutout_m must be between 0 and 1 m".into());
        }
        if !ok(self.found_lines_approach_m, 0.0, wires::MOST_APPROACH_M) {
            return Err(format!(
                "[plan] found_lines_approach_m must be between 0 (off) and {} m, found {}",
                wires::MOST_APPROACH_M,
                self.found_lines_approach_m
            ));
        }
        Ok(())
    }
}

/// How far the cut-out around a scanned load reaches beyond its box by
/// default (m, `[plan] load_cutout_m`): scan noise and a few centimetres of
/// error in the pick pose. Whatever else stands that close to the load at
/// pick is not seen, so it is kept small; it was 0.3 m, more than the
/// landing clearance (0.2 m) a part beside the load at pick must keep.
pub const LOAD_CUTOUT_GROW_M: f64 = 0.1;
/// How far above the load's box the cut-out reaches at least (m): the slings
/// lying on the load before the lift.
pub const LOAD_CUTOUT_ABOVE_M: f64 = 0.3;

/// How far above the load's box the cut-out of `grow_m` reaches (m).
pub fn cutout_above_m(grow_m: f64) -> f64 {
    grow_m.max(LOAD_CUTOUT_ABOVE_M)
}

/// The scan points taken for a lift's load at its pick position and left out
/// of every check ([`load_exclusions`]).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct LoadCutout {
    /// How far beyond the load's box at pick, sideways and below (m).
    pub grow_m: f64,
    /// How far above it (m).
    pub above_m: f64,
    /// How many scan points that left out.
    pub points: usize,
    /// The earlier lift that sets the load down where this one picks it up
    /// ([`lift_that_set_the_pick`]): then the load was not there when
    /// scanned, and the points taken are its support's top.
    #[serde(default)]
    pub set_by: Option<String>,
}

/// The other lifts' loads where they stand while lift `k` of `tasks` is made,
/// as named boxes: lifts are made in the order the project lists them, so a
/// load lifted before this one stands at its set position, and one lifted
/// after it still at its pick position. Their scan points at pick are cut
/// out of the site cloud for every lift ([`load_exclusions`]); the box
/// stands for a load not yet lifted whether or not it was scanned. A load
/// that is this lift's own (set down by an earlier lift where this one picks
/// it up, or picked up by a later lift where this one sets it down: the same
/// box in the same place, to 1 cm) is not another.
pub fn other_loads(tasks: &[LiftTask], k: usize) -> Vec<(Obb, String)> {
    let this = &tasks[k];
    tasks
        .iter()
        .enumerate()
        .filter(|&(j, _)| j != k)
        .filter_map(|(j, t)| {
            let (at, whence, own) = if j < k {
                (&t.set, "set position", hands_on(t, this))
            } else {
                (&t.pick, "pick position", hands_on(this, t))
            };
            (!own).then(|| (t.crane.load_obb(at, &t.load), format!("load of lift {} at its {whence}", t.id)))
        })
        .collect()
}

/// Whether `later` picks up the load `earlier` sets down: the same box in
/// the same place, to 1 cm.
fn hands_on(earlier: &LiftTask, later: &LiftTask) -> bool {
    same_box(&earlier.crane.load_obb(&earlier.set, &earlier.load), &later.crane.load_obb(&later.pick, &later.load))
}

/// The last earlier lift that sets down where lift `k` of `tasks` picks up
/// (the same box in the same place, to 1 cm), if one does: then the load
/// was not there when the site was scanned, its pick position cannot be
/// compared with the scans, and the points its cut-out takes are its
/// support's, not the load's.
pub fn lift_that_set_the_pick(tasks: &[LiftTask], k: usize) -> Option<&LiftTask> {
    tasks[..k].iter().rev().find(|e| hands_on(e, &tasks[k]))
}

/// Whether two boxes are one in place: each corner of one within 1 cm of a
/// corner of the other.
fn same_box(a: &Obb, b: &Obb) -> bool {
    let cb = b.corners();
    a.corners().iter().all(|p| cb.iter().any(|q| (p - q).norm() <= 0.01))
        && cb.iter().all(|q| a.corners().iter().any(|p| (p - q).norm() <= 0.01))
}

/// The scanned load at its pick position is in the site cloud; these boxes
/// (the load at pick, grown by `grow_m`, and above it by at least
/// [`LOAD_CUTOUT_ABOVE_M`]) are cut out of it so the load does not block its
/// own lift. The depth map and the validator use the same boxes.
pub fn load_exclusions(tasks: &[LiftTask], grow_m: f64) -> Vec<Obb> {
    tasks
        .iter()
        .map(|t| {
            let b = t.crane.load_obb(&t.pick, &t.load).expanded(grow_m);
            let up = cutout_above_m(grow_m) - grow_m;
            if b.is_upright() { b.with_top_raised(up) } else { b.expanded(up) }
        })
        .collect()
}

/// Everything a planned lift carries into `plan.json`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LiftPlan {
    pub lift: String,
    pub description: String,
    pub planner: Planner,
    pub crane_model: String,
    pub chart_config: String,
    pub gross_kg: f64,
    pub clearance_m: f64,
    pub landing_clearance_m: f64,
    /// How far a sudden gust at the permissible wind can swing what hangs,
    /// per metre below the boom head, as the plan keeps its clearance with
    /// it ([`LiftTask::gust_swing_per_m`]); 0: the lift was not planned for
    /// the wind, and its clearances are those of the load hanging plumb.
    #[serde(default)]
    pub gust_swing_per_m: f64,
    pub critical_pct: f64,
    pub pick: Config,
    pub set: Config,
    pub start: Config,
    pub goal: Config,
    /// Node configurations from start to goal (after shortening).
    pub nodes: Vec<Config>,
    pub moves: Vec<Move>,
    pub steps: Vec<steps::Step>,
    pub summary: steps::Summary,
    pub validator: ValidatorReport,
    pub planning: PlanningStats,
    /// Where the crane stood for the plan (`None` in a plan.json older than
    /// the field): `liftplan resume` checks that the project still sets it
    /// up there, as a crane stopped part way through its lift has not moved.
    #[serde(default)]
    pub crane_placement: Option<Placement>,
    /// Scan points taken for the load at pick (set by [`run`]).
    #[serde(default)]
    pub load_cutout: LoadCutout,
    /// How well the plant model and the scans agree (set by [`run`]; `None`
    /// where they barely overlap).
    #[serde(default)]
    pub model_vs_scans: Option<validate::ModelScanAgreement>,
}

impl LiftPlan {
    /// What is wrong with the steps of a plan read back (a plan.json cut
    /// short, edited by hand, or not one liftplan wrote) where they are not
    /// as [`run`] writes them for `task`: one a move, numbered from 1 in
    /// order, each in the words its move is said in ([`steps::describe`]).
    /// A document draws step n with move n, and heads its page with the
    /// step's words, so it reads none other: words edited to say another
    /// move, or run on past a page's width, are refused.
    pub fn steps_not_as_written(&self, task: &LiftTask) -> Option<String> {
        if self.steps.len() != self.moves.len() {
            return Some(format!(
                "{} steps for {} moves (the plan stage writes a step for each move)",
                self.steps.len(),
                self.moves.len()
            ));
        }
        if let Some((k, step)) = self.steps.iter().enumerate().find(|(k, step)| step.n != k + 1) {
            return Some(format!(
                "its step {} is numbered {} (the plan stage numbers them from 1 in order)",
                k + 1,
                step.n
            ));
        }
        let named = self.steps.iter().find_map(|step| {
            [("clearance_part", &step.clearance_part), ("clearance_to", &step.clearance_to)]
                .into_iter()
                .chain(step.chart_cell.as_ref().map(|c| ("chart_cell", c)))
                .find(|(_, said)| said.chars().count() > MAX_STEP_NAME_CHARS)
                .map(|(key, said)| {
                    format!(
                        "its step {}'s {key} is {} characters long, longer than any the plan stage writes (at most {MAX_STEP_NAME_CHARS}): \"{}\"",
                        step.n,
                        said.chars().count(),
                        shortened_said(said)
                    )
                })
        });
        if named.is_some() {
            return named;
        }
        let tower = task.crane.model.is_tower();
        self.steps.iter().zip(&self.moves).find_map(|(step, m)| {
            let (operation, amount, unit, text) = steps::describe(tower, m);
            let as_written = step.operation == operation
                && step.amount.to_bits() == amount.to_bits()
                && step.unit == unit
                && step.text == text;
            (!as_written).then(|| {
                format!(
                    "its step {} is not in the words its move is said in (\"{text}\", the plan stage's; \"{}\" read)",
                    step.n,
                    shortened_said(&step.text)
                )
            })
        })
    }
}

/// The most characters of what a step names (the crane part, what it comes
/// closest to, the chart's cell) the plan stage writes: the names it is
/// made of are bounded (plant groups' at
/// [`liftplan_core::mesh::MAX_GROUP_NAME_CHARS`], obstacles' and power
/// lines' at 100, lift ids at [`liftplan_core::lift::MAX_LIFT_ID_CHARS`]);
/// a step's row naming this many runs over pages of the document's steps
/// table.
pub const MAX_STEP_NAME_CHARS: usize = 1000;

/// Words read from a file, for an error saying them: whole up to 80
/// characters, else their first 80 and how many there were (words run on
/// for pages would bury the message).
fn shortened_said(s: &str) -> String {
    const SAID: usize = 80;
    match s.char_indices().nth(SAID) {
        None => s.to_string(),
        Some((cut, _)) => format!("{}... ({} characters)", &s[..cut], s.chars().count()),
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ValidatorReport {
    pub ok: bool,
    pub samples: usize,
    /// Of `samples`, those added where two neighbours' distances did not rule
    /// out a part coming closer than its requirement between them.
    #[serde(default)]
    pub refined_samples: usize,
    pub seconds: f64,
    pub problems: Vec<String>,
    /// The scanned ground under a mobile crane's carrier and outriggers,
    /// which must lie at the level the lift sets it up at, or within 3 m of
    /// a tower crane's mast (said, not checked); `None` where no ground was
    /// scanned there (the level is then as the lift gives it).
    #[serde(default)]
    pub set_up_ground: Option<validate::SetUpGround>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PlanningStats {
    pub seed: u64,
    pub generations: usize,
    pub evaluations: usize,
    pub first_feasible_generation: Option<usize>,
    pub fitness: f64,
    pub motion_cost: f64,
    pub switches: usize,
    pub cspace_ms: f64,
    pub plan_ms: f64,
    pub swing_direction: String,
    /// GA runs each way round until a feasible path appeared (1 + restarts used).
    pub attempts: usize,
    pub table_lookups: u64,
    pub box_queries: u64,
    pub convergence_best: Vec<f64>,
    pub convergence_mean: Vec<f64>,
}

/// Inputs shared by all lifts.
pub struct Site<'a> {
    pub map: &'a Mdm,
    pub world: &'a validate::World,
    pub charts: Option<&'a CapacityTable>,
}

fn lift_err(task: &LiftTask, message: impl Into<String>) -> PlanError {
    PlanError::Lift { lift: task.id.clone(), message: message.into() }
}

/// Why the search found no path, as far as the planner's tables tell. Each
/// way round, the swing x radius grid between the pick and the set is walked
/// from the pick's cell with the load on the shortest rope each cell allows
/// (hung highest), at the pick's or the set's load yaw: where the set's cell
/// cannot be reached, it says how far the load gets and what blocks the next
/// swing (the body or boom, the chart, or the load too close to something);
/// where it can, that the search failed to find the way. The tables are
/// conservative for whole cells, so a way finer than a cell is not seen.
fn why_no_path(ck: &Checker, start: &Config, goal: &Config, ways: &[(&str, f64)]) -> String {
    use rayon::prelude::*;
    let cs = ck.cs;
    let nr = cs.nr as usize;
    let cell = |swing: f64, k: usize| -> std::result::Result<(), liftplan_cspace::Blocked> {
        let mut first = None;
        for yaw in [start.load_yaw_rad, goal.load_yaw_rad] {
            let c = Config {
                swing_rad: swing,
                radial: cs.row_center(k as u32),
                hoist_m: cs.row_min_hoist[k],
                load_yaw_rad: yaw,
            };
            match ck.config(&c) {
                Ok(()) => return Ok(()),
                Err(b) => {
                    first.get_or_insert(b);
                }
            }
        }
        Err(first.expect("two yaws tried"))
    };
    let what_blocks = |b: &liftplan_cspace::Blocked| match (b.part, &b.object) {
        (Some(part), Some(o)) => format!("{} and {o}", part.name()),
        (Some(part), None) => format!("{} ({})", part.name(), b.reason),
        _ => b.reason.clone(),
    };
    // Where the load is what meets something, how high it hangs there at
    // most: what the engineer weighs against the rigging and the boom.
    let load_height = |blocked: &[&liftplan_cspace::Blocked]| {
        blocked
            .iter()
            .filter(|b| b.part == Some(liftplan_core::crane::PartKind::Load))
            .map(|b| ck.task.crane.load_obb(&b.at, &ck.task.load).aabb().min[2])
            .reduce(f64::max)
            .map(|z| format!(" (the load's underside no higher than z = {z:.2} m there, on the shortest rope)"))
            .unwrap_or_default()
    };
    let (Some(k0), Some(k1)) = (cs.row(start.radial), cs.row(goal.radial)) else {
        return "the pick or the set lies outside the crane's radial range".into();
    };
    let deg = |swing: f64| liftplan_core::units::wrap_pi(swing).to_degrees();
    let mut said = Vec::new();
    for (label, gs) in ways {
        let n = ((gs - start.swing_rad).abs() / cs.swing_step).ceil().max(1.0) as usize;
        let at = |j: usize| start.swing_rad + (gs - start.swing_rad) * j as f64 / n as f64;
        let grid: Vec<Vec<std::result::Result<(), liftplan_cspace::Blocked>>> =
            (0..=n).into_par_iter().map(|j| (0..nr).map(|k| cell(at(j), k)).collect()).collect();
        // Cells reached from the pick's, moving one joint a cell at a time.
        let mut reached = vec![vec![false; nr]; n + 1];
        let mut todo = vec![(0usize, k0 as usize)];
        if grid[0][k0 as usize].is_ok() {
            reached[0][k0 as usize] = true;
        } else {
            todo.clear();
        }
        while let Some((j, k)) = todo.pop() {
            let next = [(j + 1, k), (j.wrapping_sub(1), k), (j, k + 1), (j, k.wrapping_sub(1))];
            for (a, b) in next {
                if a <= n && b < nr && !reached[a][b] && grid[a][b].is_ok() {
                    reached[a][b] = true;
                    todo.push((a, b));
                }
            }
        }
        let line = if reached[n][k1 as usize] {
            "the planner's tables show a way at the shortest rope, cell by cell, which the search did not find"
                .to_string()
        } else if let Err(b) = &grid[0][k0 as usize] {
            format!("at the pick the load on the shortest rope is not clear: {}", what_blocks(b))
        } else if let Err(b) = &grid[n][k1 as usize] {
            format!("above the set position the load on the shortest rope is not clear: {}", what_blocks(b))
        } else if reached[n].iter().any(|&r| r) {
            // Between the radii it reaches there and the set's.
            let k1 = k1 as usize;
            let near = (0..nr).filter(|&k| reached[n][k]).min_by_key(|&k| k.abs_diff(k1)).unwrap_or(k1);
            let between = if near < k1 { near..k1 } else { k1..near };
            let blocked: Vec<&liftplan_cspace::Blocked> = between.filter_map(|k| grid[n][k].as_ref().err()).collect();
            format!(
                "the load reaches the set's swing on the shortest rope, but not its radius: in between, {}{}",
                dedup_counted(blocked.iter().map(|b| what_blocks(b)), None).join(", "),
                load_height(&blocked)
            )
        } else {
            let far = (0..=n).rev().find(|&j| reached[j].iter().any(|&r| r)).unwrap_or(0);
            // What blocks the next swing's rows, most often first.
            let blocked: Vec<&liftplan_cspace::Blocked> =
                grid.get(far + 1).into_iter().flatten().filter_map(|c| c.as_ref().err()).collect();
            let what = dedup_counted(blocked.iter().map(|b| what_blocks(b)), Some(nr));
            format!(
                "the load gets no farther than swing {:.1}° from the crane's heading (the pick is at {:.1}°, the set at {:.1}°), even on the shortest rope: at {:.1}° {}{}",
                deg(at(far)),
                deg(start.swing_rad),
                deg(*gs),
                deg(at(far + 1)),
                if what.is_empty() { "no radius joins on".to_string() } else { what.join(", ") },
                load_height(&blocked)
            )
        };
        said.push((*label, line));
    }
    let said: Vec<String> = match said.as_slice() {
        [] => return "the permitted swing range holds neither way round".into(),
        [(_, a), (_, b)] if a == b => vec![format!("both ways round, {a}")],
        _ => said.iter().map(|(label, line)| format!("{label}, {line}")).collect(),
    };
    format!(
        "{}; try another crane position, a longer boom, shorter rigging, or a larger population or more generations",
        said.join("; ")
    )
}

/// The three most frequent of `said`, most often first, each with how many
/// of `of` radii it blocks where that is given.
fn dedup_counted(said: impl Iterator<Item = String>, of: Option<usize>) -> Vec<String> {
    let mut counted: Vec<(String, usize)> = Vec::new();
    for w in said {
        match counted.iter_mut().find(|(x, _)| *x == w) {
            Some(e) => e.1 += 1,
            None => counted.push((w, 1)),
        }
    }
    counted.sort_by_key(|e| std::cmp::Reverse(e.1));
    counted
        .iter()
        .take(3)
        .map(|(w, c)| match of {
            Some(of) => format!("{w} at {c} of {of} radii"),
            None => w.clone(),
        })
        .collect()
}

/// Whether swinging from `from` to `to` (rad, as numbers: the way round is
/// in their difference) stays within the lift's permitted swing range.
fn way_permitted(task: &LiftTask, from: f64, to: f64) -> bool {
    task.swing_range_rad.is_none_or(|(a, b)| from.min(to) >= a && from.max(to) <= b)
}

/// The landing zones of a lift: at the pick and the set, or only the set
/// for a lift resumed part way (its load is not lifted off the pick, so
/// nothing hanging over it may come closer than the full clearance).
pub fn landing_zones(task: &LiftTask, s: &Settings) -> Vec<LandingZone> {
    let ends: &[Config] = if task.resumes() { &[task.set] } else { &[task.pick, task.set] };
    ends.iter()
        .map(|c| LandingZone::around(&task.crane.load_obb(c, &task.load), s.landing_margin_m, s.landing_clearance_m))
        .collect()
}

/// One planner run from `start` to `goal`: the node path if it found a
/// feasible one, and its statistics.
fn search(
    ck: &Checker,
    start: &Config,
    goal: &Config,
    s: &Settings,
    seed: u64,
    purpose: &str,
) -> (Option<Vec<Config>>, mspga::GaResult) {
    match s.planner {
        Planner::Mspga | Planner::AliGa => {
            let kind = if s.planner == Planner::Mspga { mspga::Fitness::Mspga } else { mspga::Fitness::Ali };
            let r = mspga::run(ck, start, goal, &s.ga, kind, seed, purpose);
            match r.best.clone() {
                Some(b) if b.n == 0 => (Some(b.genes), r),
                Some(b) => {
                    let why = mspga::first_problem(ck, &b.genes).map(|p| p.to_string()).unwrap_or_default();
                    tracing::info!("{purpose}: no feasible path ({why})");
                    (None, r)
                }
                None => (None, r),
            }
        }
        Planner::RrtConnect | Planner::Prm => {
            let r = if s.planner == Planner::RrtConnect {
                baselines::rrt_connect(ck, start, goal, &s.baselines, &s.ga.weights, seed)
            } else {
                baselines::prm(ck, start, goal, &s.baselines, &s.ga.weights, seed)
            };
            let stats = mspga::GaResult {
                best: None,
                generations: r.iterations,
                evaluations: r.edge_checks,
                first_feasible: None,
                best_fitness: vec![],
                mean_fitness: vec![],
            };
            (r.found.then_some(r.nodes), stats)
        }
    }
}

/// What the lift's carrier and outriggers (or mast) meet where it sets the
/// crane up, if anything: they stand on the ground, and anything else where
/// they stand (a bank higher than half a metre above it among them) is a
/// bad request. Whether that ground lies at the lift's level is
/// [`validate::crane_set_up_level_problem`]'s.
fn set_up_blocked(task: &LiftTask, site: &Site, s: &Settings) -> Option<String> {
    let standing = LeaveOut::up_to(liftplan_depthmap::mdm::OBJ_GROUND, task.crane.standing_ground_top_z());
    for &kind in task.crane.part_kinds() {
        if kind.dependence() != liftplan_core::crane::Dependence::Fixed {
            continue;
        }
        if let Some(b) = task.crane.part(kind, &task.pick, &task.load) {
            let b = b.with_underside_raised(s.support_m);
            if let Some(h) = site.map.hit_where(&b, |iv| LeaveOut::counts(Some(standing), iv)) {
                // Where, so the engineer can find it on the drawings or on site.
                let r = site.map.spec.rect(h.i, h.j);
                let name = kind.name();
                return Some(format!(
                    "crane set-up: the {name} {} {} in the cell at x {:.2} to {:.2} m, y {:.2} to {:.2} m, where it reaches from z = {:.2} to {:.2} m (the crane is set up at z = {:.2} m); move the crane or clear its footprint",
                    if name.ends_with('s') { "meet" } else { "meets" },
                    site.map.object_name(&h.interval),
                    r[0],
                    r[1],
                    r[2],
                    r[3],
                    h.interval.zlo,
                    h.interval.zhi,
                    task.crane.placement.z_m
                ));
            }
        }
    }
    None
}

/// The validator's rules for `task`, with its landing zones' outlines.
fn validate_rules(task: &LiftTask, s: &Settings, zones: &[LandingZone]) -> validate::Rules {
    validate::Rules {
        clearance_m: task.clearance_m,
        landing: zones.iter().map(|z| z.polygon.clone()).collect(),
        landing_clearance_m: s.landing_clearance_m,
        sample_m: s.validator_sample_m,
        support_m: s.support_m,
    }
}

/// Which of a lift's `n` moves, from the first to the set-down, are the
/// landing moves the validator lets the load touch its support in: the
/// lift-off (none for a lift resumed part way) and the set-down.
fn landing_moves(task: &LiftTask, n: usize) -> Vec<bool> {
    (0..n).map(|i| (i == 0 && !task.resumes()) || i + 1 == n).collect()
}

/// The lift-off: the hook raises the load `liftoff_m` off its pick support.
fn lift_off(task: &LiftTask) -> Move {
    Move { joint: Joint::Hoist, from: task.pick, to: task.start() }
}

/// The set-down, as checked before the search: from `liftoff_m` above the
/// set position onto it, at the set's own swing.
fn set_down(task: &LiftTask) -> Move {
    Move { joint: Joint::Hoist, from: task.goal(), to: task.set }
}

/// Plans, shortens, validates one lift.
pub fn plan_lift(task: &LiftTask, site: &Site, s: &Settings, seed: u64) -> Result<(LiftPlan, CSpace)> {
    plan_lift_hinting(task, site, s, seed, true)
}

/// [`plan_lift`]; where `positions` is false, a refusal does not search
/// for another crane position ([`positions::search`] plans at those it
/// tries with this, and a refusal there must not search again).
pub(crate) fn plan_lift_hinting(
    task: &LiftTask,
    site: &Site,
    s: &Settings,
    seed: u64,
    positions: bool,
) -> Result<(LiftPlan, CSpace)> {
    let t0 = std::time::Instant::now();
    if task.wind_swing_unknown() {
        return Err(lift_err(
            task,
            "the load's swing in the wind is not worked out (its chart's speed is to be read from the chart's sheet, and none was given to the planner): give wind chart_ms, or set wind plan_for_swing = false".to_string(),
        ));
    }
    // The planned path starts lifted off and ends above the set position:
    // there the load must keep the landing zone's clearance from what it
    // stands on, or the search would start inside it (it was refused as
    // "the lifted-off pick configuration is not allowed: closer than the
    // clearance allows: load and scanned structure", naming no key).
    if task.liftoff_m + 1e-9 < s.landing_clearance_m {
        return Err(lift_err(
            task,
            format!(
                "liftoff_m {:.2} m is less than the clearance the load keeps over its pick and set positions ([plan] landing_clearance_m, {:.2} m): lifted off, it would still be within it of what it stands on; set liftoff_m to {:.2} m or more",
                task.liftoff_m, s.landing_clearance_m, s.landing_clearance_m
            ),
        ));
    }
    // The sling legs do not depend on the path: checked first.
    let slings = match task.check_slings() {
        Some(c) => {
            let c = c.map_err(|e| lift_err(task, e))?;
            if let Some(over) = c.over_limit() {
                return Err(lift_err(task, over));
            }
            Some(c)
        }
        None => None,
    };
    // So is the reeving: the hook load is the same all along the path.
    let reeving = liftplan_core::reeving::Reeving::of(task);
    if let Some(why) = reeving.as_ref().and_then(|r| r.refused()) {
        return Err(lift_err(task, why));
    }
    let chart: Option<&ChartConfig> = match site.charts {
        Some(t) => Some(t.config(&task.chart_config).map_err(|e| lift_err(task, e.to_string()))?),
        None => None,
    };
    // Where else the crane could stand, for a refusal that moving it may
    // answer (not for a lift resumed part way: its crane holds the load).
    let elsewhere = |chart: Option<&ChartConfig>| match chart.filter(|_| positions && !task.resumes()) {
        Some(ch) => positions::search(task, site, ch, s, seed, positions::Sought::Plans).said(&ch.name),
        None => String::new(),
    };
    // (A lift resumed part way was lifted off its pick: where it hangs, the
    // checker and the validator read the chart.)
    let ends = if task.resumes() { &[("set", &task.set)][..] } else { &[("pick", &task.pick), ("set", &task.set)][..] };
    for &(what, c) in ends {
        if let Some(ch) = chart {
            match task.check_capacity(ch, c.radial) {
                Ok(k) if k.effective_kg >= task.gross_kg() => {}
                Ok(k) => {
                    return Err(lift_err(
                        task,
                        format!(
                            "{what} is over capacity: gross {:.0} kg at radius {:.2} m, chart {} gives {:.0} kg ({:.0} kg after the reduction){}{}",
                            task.gross_kg(),
                            k.radius_m,
                            k.capacity.cell,
                            k.capacity.capacity_kg,
                            k.effective_kg,
                            site.charts
                                .map(|t| hints::over_capacity(task, t, ch, what, k.radius_m))
                                .unwrap_or_default(),
                            elsewhere(Some(ch))
                        ),
                    ));
                }
                Err(e) => return Err(lift_err(task, format!("{what}: {e}"))),
            }
        }
    }
    // The crane's set-up: at the level of the ground scanned under it, and
    // standing clear on it.
    if let Some(problem) = validate::crane_set_up_level_problem(task, site.world) {
        return Err(lift_err(task, problem));
    }
    if let Some(problem) = set_up_blocked(task, site, s) {
        return Err(lift_err(task, format!("{problem}{}", elsewhere(chart))));
    }
    let cs = CSpace::build(&Problem { task, chart, map: site.map }, &s.cspace);
    let zones = landing_zones(task, s);
    let rules = validate_rules(task, s, &zones);
    let ck = Checker::new(&cs, site.map, task, zones, s.cspace.sample_m);
    let start = task.start();
    let goal0 = task.goal();
    // A box query's refusal is a clearance, not a collision: say which.
    // What hangs is swung by a gust where the lift is planned for the wind,
    // and off by its centre of gravity's tolerance where the lift gives one.
    let gust = (task.gust_swing_per_m > 0.0).then(|| {
        format!(
            "what hangs swung {:.1} cm per metre it hangs below the boom head, as far as a sudden gust at the permissible wind can swing it (wind plan_for_swing)",
            100.0 * task.gust_swing_per_m
        )
    });
    let cog = (task.cog_tolerance_m > 0.0).then(|| {
        format!(
            "the load and its rigging {:.2} m off along the load's x and y, as far as its centre of gravity may lie off (load cog_tolerance_m)",
            task.cog_tolerance_m
        )
    });
    let swung =
        (gust.is_some() || cog.is_some()).then(|| gust.into_iter().chain(cog).collect::<Vec<_>>().join(", and "));
    let why = |b: &liftplan_cspace::Blocked| {
        let hanging = b.part.is_some_and(|k| k.dependence() == liftplan_core::crane::Dependence::Full);
        let swung = swung.as_ref().filter(|_| hanging);
        if b.reason == liftplan_cspace::TOO_CLOSE {
            format!(
                "{b} (clearance_m {:.2} m, {:.2} m in a landing zone{})",
                task.clearance_m,
                s.landing_clearance_m,
                swung.map(|w| format!(", {w}")).unwrap_or_default()
            )
        } else if b.reason == liftplan_cspace::OVER_NOT_OVER && hanging && (swung.is_some() || task.fall_zone_m > 0.0) {
            let fall_zone = (task.fall_zone_m > 0.0)
                .then(|| format!("its fall zone, fall_zone_m {} m, kept off it", task.fall_zone_m));
            let said: Vec<String> = swung.map(|w| w.to_string()).into_iter().chain(fall_zone).collect();
            format!("{b} ({})", said.join("; "))
        } else {
            b.to_string()
        }
    };
    // Where the crane's own structure (its boom, its superstructure) meets
    // something there, another position may clear it; what the load meets
    // at its pick or set moves with it.
    let structure = |b: &liftplan_cspace::Blocked| {
        use liftplan_core::crane::PartKind;
        b.part.is_some_and(|k| !matches!(k, PartKind::Load | PartKind::Rigging | PartKind::HookBlock | PartKind::Rope))
    };
    if let Err(b) = ck.config(&start) {
        if task.resumes() {
            return Err(lift_err(
                task,
                format!(
                    "where the load hangs now (resume_from) is not clear: {}; no path from there is planned: make it clear by hand (hoist, or lower the load where it is safe), then give where it hangs then",
                    why(&b)
                ),
            ));
        }
        let hint = hints::for_load(task, site, &b, &task.pick, &start, task.height_key(true), true);
        let elsewhere = if structure(&b) { elsewhere(chart) } else { String::new() };
        return Err(lift_err(
            task,
            format!("the lifted-off pick configuration is not allowed: {}{hint}{elsewhere}", why(&b)),
        ));
    }
    if let Err(b) = ck.config(&goal0) {
        let hint = hints::for_load(task, site, &b, &task.set, &goal0, task.height_key(false), false);
        let elsewhere = if structure(&b) { elsewhere(chart) } else { String::new() };
        return Err(lift_err(
            task,
            format!("the configuration above the set position is not allowed: {}{hint}{elsewhere}", why(&b)),
        ));
    }
    // The lift-off and the set-down are the same whatever path is found: the
    // validator's verdict on them now, before the search, says what blocks
    // them instead of rejecting every plan at the end.
    // (A lift resumed part way has no lift-off: its load hangs.)
    let lift_off_check = (!task.resumes()).then(|| ("lift-off", lift_off(task), &task.pick, task.height_key(true)));
    for (what, mv, at, key) in
        lift_off_check.into_iter().chain([("set-down", set_down(task), &task.set, task.height_key(false))])
    {
        let v = validate::validate(task, chart, site.world, &rules, &[mv], &[true]);
        if !v.ok {
            // The move's own problems under its name; any other (the crane's
            // set-up, checked with the first move) as the validator says it.
            let problems: Vec<String> = v
                .problems
                .iter()
                .map(|p| match p.strip_prefix("move 1 (Hoist): ") {
                    Some(own) => format!("the {what} is not clear: {own}"),
                    None => p.clone(),
                })
                .collect();
            let hint = if v.problems.iter().any(|p| p.starts_with("move 1 (Hoist): load ")) {
                hints::itself_in_the_model(task, site, at, what == "lift-off")
                    .unwrap_or_else(|| hints::sunk(task, site, at, key))
            } else {
                String::new()
            };
            return Err(lift_err(task, format!("{}{hint}", problems.join("; "))));
        }
    }
    // Both ways round.
    let short = start.swing_rad + liftplan_core::units::wrap_pi(goal0.swing_rad - start.swing_rad);
    let long = if short >= start.swing_rad { short - std::f64::consts::TAU } else { short + std::f64::consts::TAU };
    let mut candidates = vec![];
    let mut attempts = 0;
    for attempt in 0..=s.ga.restarts {
        if !candidates.is_empty() {
            break;
        }
        attempts = attempt + 1;
        // Attempt 0 uses the project seed as it is; restarts draw new strings.
        let (seed, restart) = if attempt == 0 {
            (seed, String::new())
        } else {
            (seed ^ (attempt as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15), format!("/restart {attempt}"))
        };
        for (label, gs) in [("short way", short), ("long way", long)] {
            let goal = Config { swing_rad: gs, ..goal0 };
            if !way_permitted(task, start.swing_rad, gs) {
                continue;
            }
            let purpose = format!("plan/{}/{label}{restart}", task.id);
            let (nodes, stats) = search(&ck, &start, &goal, s, seed, &purpose);
            if let Some(nodes) = nodes {
                let nodes = path::shortcut(&ck, &nodes, &s.ga.weights);
                let moves = path::path_moves(&ck, &nodes);
                let (d, sc) = path::cost(&moves, &s.ga.weights, task.crane.model.is_tower());
                candidates.push((d + s.ga.lambda2 * (1.0 + sc as f64), label, nodes, moves, d, sc, stats));
            }
        }
    }
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
    let Some((m, label, nodes, moves, d, sc, stats)) = candidates.into_iter().next() else {
        let ways: Vec<(&str, f64)> = [("the short way round", short), ("the long way round", long)]
            .into_iter()
            .filter(|(_, gs)| way_permitted(task, start.swing_rad, *gs))
            .collect();
        return Err(lift_err(
            task,
            format!(
                "no collision-free, chart-compliant path found ({} run(s) of up to {} generations of {} strings each way): {}{}",
                attempts,
                s.ga.max_generations,
                s.ga.population,
                why_no_path(&ck, &start, &goal0, &ways),
                elsewhere(chart)
            ),
        ));
    };
    // The planner's own continuous check of the final path, edge by edge: the
    // moves the operator gets merge consecutive moves of one joint across
    // edges, the same motion, but sub-stepped differently, and the grown-box
    // checks are conservative for any sub-stepping without giving the same
    // answer near contact for all of them. The validator checks the merged moves.
    if let Some(b) = nodes.windows(2).find_map(|w| path::check_edge(&ck, &w[0], &w[1]).err()) {
        return Err(lift_err(task, format!("internal error: the shortened path fails the planner's own check: {b}")));
    }
    let plan_ms = t0.elapsed().as_secs_f64() * 1e3;
    // Lift-off and set-down.
    let mut all = Vec::with_capacity(moves.len() + 2);
    if !task.resumes() {
        all.push(Move { joint: Joint::Hoist, from: task.pick, to: start });
    }
    all.extend(moves.iter().copied());
    all.push(Move {
        joint: Joint::Hoist,
        from: nodes.last().copied().unwrap_or(goal0),
        to: Config { swing_rad: nodes.last().map(|n| n.swing_rad).unwrap_or(goal0.swing_rad), ..task.set },
    });
    let verdict = validate::validate_lift(task, chart, site.world, &rules, &all, &landing_moves(task, all.len()));
    if !verdict.ok {
        return Err(lift_err(
            task,
            format!("the validator rejected the plan, so none is written:\n  {}", verdict.problems.join("\n  ")),
        ));
    }
    let steps = steps::steps(task, &all, &verdict);
    let mut summary = steps::summary(task, &steps, &verdict);
    summary.slings = slings;
    summary.reeving = reeving;
    summary.set_on = validate::set_support(task, site.world, &task.set, s.support_m);
    summary.support_m = s.support_m;
    let plan = LiftPlan {
        lift: task.id.clone(),
        description: task.description.clone(),
        planner: s.planner,
        crane_model: task.crane.model.name.clone(),
        chart_config: task.chart_config.clone(),
        gross_kg: task.gross_kg(),
        clearance_m: task.clearance_m,
        landing_clearance_m: s.landing_clearance_m,
        gust_swing_per_m: task.gust_swing_per_m,
        critical_pct: task.critical_pct,
        pick: task.pick,
        set: task.set,
        start,
        goal: nodes.last().copied().unwrap_or(goal0),
        nodes,
        moves: all,
        steps,
        summary,
        validator: ValidatorReport {
            ok: verdict.ok,
            samples: verdict.samples,
            refined_samples: verdict.refined_samples,
            seconds: verdict.seconds,
            problems: verdict.problems,
            set_up_ground: verdict.set_up_ground,
        },
        planning: PlanningStats {
            seed,
            generations: stats.generations,
            evaluations: stats.evaluations,
            first_feasible_generation: stats.first_feasible,
            fitness: m,
            motion_cost: d,
            switches: sc,
            cspace_ms: cs.build_ms,
            plan_ms,
            swing_direction: label.to_string(),
            attempts,
            table_lookups: ck.counters.lookups(),
            box_queries: ck.counters.box_queries(),
            convergence_best: stats.best_fitness,
            convergence_mean: stats.mean_fitness,
        },
        crane_placement: Some(task.crane.placement),
        // What was cut out of the cloud for the load, and how the model and
        // the scans agree, are known to `run`.
        load_cutout: LoadCutout::default(),
        model_vs_scans: None,
    };
    Ok((plan, cs))
}

/// Reads the site points (dropping the `exclude` boxes) for the validator.
pub fn read_points(path: &Path, exclude: &[Obb]) -> Result<(Vec<[f64; 3]>, Vec<bool>, Vec<Vec<[f64; 3]>>)> {
    let mut inp = liftplan_depthmap::Inputs::default();
    let mut taken = vec![Vec::new(); exclude.len()];
    liftplan_depthmap::read_cloud_with(path, exclude, &mut inp, |k, p| taken[k].push(p))
        .map_err(|e| PlanError::Input(Location::file(path), e.to_string()))?;
    Ok((inp.points, inp.ground, taken))
}

/// The groups the plant stage left out of the model, as plant.json has them
/// (none in a plant.json written before it had them).
fn excluded_boxes(path: &Path) -> Result<Vec<liftplan_core::mesh::ModelBox>> {
    let bytes = std::fs::read(path).map_err(|e| PlanError::Input(Location::file(path), e.to_string()))?;
    liftplan_core::mesh::ModelBox::left_out_in_plant_json(&bytes)
        .map_err(|problem| PlanError::Input(Location::file(path), problem))
}

/// What the stage reports.
#[derive(Debug, Clone, Serialize)]
pub struct RunSummary {
    pub lifts: Vec<steps::Summary>,
    pub model_vs_scans: Option<validate::ModelScanAgreement>,
}

impl RunSummary {
    pub fn lines(&self) -> Vec<String> {
        self.model_vs_scans
            .iter()
            .map(|a| a.line())
            .chain(self.lifts.iter().flat_map(|s| {
                std::iter::once(s.line())
                    .chain(s.slings_line())
                    .chain(s.reeving_line())
                    .chain(s.pads_line())
                    .chain(s.not_critical_line())
                    .chain(s.under_pads_line())
                    .chain(s.other_loads_line())
                    .chain(s.other_cranes_line())
                    .chain(s.obstacles_line())
                    .chain(s.power_lines_line())
                    .chain(s.line_like_line())
                    .chain(s.coverage_line())
                    .chain(s.load_as_scanned_line())
                    .chain(s.against_model_lines())
            }))
            .collect()
    }
}

/// A plan's revision: the first 8 hex digits of a blake3 hash of the plan
/// as plan.json carries it (less its timings and the revision itself) and of
/// the crane, load and rigging it was made for. It is printed on every page
/// of the plan's PDF, so that the copy a crew follows can be told from
/// another plan of the same lift made the same day (a re-plan round a truck
/// parked since), and `liftplan resume` reads the plan the crew follows, not
/// whichever was made last. The same inputs and seed give the same revision
/// (nothing in it depends on the thread count or the time taken); a change
/// to anything the plan says gives another (but for a 1 in 4 billion
/// collision of the hash's first 32 bits, between the plans of one lift).
pub fn revision(plan: &LiftPlan, task: &LiftTask) -> String {
    let mut p = plan.clone();
    p.planning.cspace_ms = 0.0;
    p.planning.plan_ms = 0.0;
    p.validator.seconds = 0.0;
    p.summary.revision.clear();
    let mut h = blake3::Hasher::new();
    h.update(b"liftplan plan revision 2\n");
    // serde_json writes an f64 as its shortest round-trip digits: the
    // same plan gives the same bytes.
    h.update(&serde_json::to_vec(&p).unwrap_or_default());
    // The crane's parts, the load's shape and the plan a resumed lift
    // continues (said on its cover) are not in plan.json. Hashed as JSON,
    // whose optional keys are left out where not given: a crane file key,
    // or a rigging one, that a later version learns to read leaves the
    // revisions of plans that do not give it as they were.
    let made_for = serde_json::json!({
        "crane": task.crane.model,
        "placement": task.crane.placement,
        "load": task.load,
        "load_mass_kg": task.load_mass_kg,
        "rigging_mass_kg": task.rigging_mass_kg,
        "deductions_kg": task.deductions_kg,
        "counterweight_kg": task.counterweight_kg,
        "resumes_plan": task.resumes_plan,
        "slings": task.slings,
    });
    h.update(b"\n");
    h.update(&serde_json::to_vec(&made_for).unwrap_or_default());
    // Only where given, likewise.
    if task.cog_tolerance_m != 0.0 {
        h.update(format!("\ncog tolerance {:?}", task.cog_tolerance_m).as_bytes());
    }
    if task.cog_tolerance_z_m != 0.0 {
        h.update(format!("\ncog tolerance z {:?}", task.cog_tolerance_z_m).as_bytes());
    }
    h.finalize().to_hex()[..8].to_string()
}

/// A plan as plan.json carries it, less what its [`revision`] leaves out
/// (the times its C-space, search and validation took): two plans of one
/// revision are equal so, but for a collision of the hash. The JSON twin
/// of what [`revision`] clears, beside it so that the two stay alike.
pub fn but_for_timings(plan: &serde_json::Value) -> serde_json::Value {
    let mut p = plan.clone();
    for (section, key) in [("planning", "cspace_ms"), ("planning", "plan_ms"), ("validator", "seconds")] {
        if let Some(v) = p.get_mut(section).and_then(|s| s.get_mut(key)) {
            *v = serde_json::Value::from(0.0);
        }
    }
    p
}

/// The power lines there during `task`, as boxes round their conductors
/// grown so far that a part the validator passes keeps the approach
/// distance off the conductor even in the lift-off and set-down, where what
/// hangs need only not touch a box ([`validate::box_reach_for_m`]); in the
/// rest of the lift the parts keep the lift's clearance beyond it
/// ([`liftplan_core::power_line`]). The task is not used beyond its id: the
/// growth is the same for every lift. Each is named "power line 'NAME'
/// (beyond its 3.05 m approach distance)" where the validator meets it: a
/// step's clearance to it is measured to its box, beyond that distance from
/// the conductor, and a signer reading the steps must not take it for the
/// distance to the wire. Refused where they would cover more of the
/// map than [`MAX_OBSTACLE_CELLS`].
pub fn power_line_boxes(lines: &[PowerLine], task: &LiftTask, s: &Settings, cell_m: f64) -> Result<Vec<(Obb, String)>> {
    let mut out = Vec::new();
    for l in lines.iter().filter(|l| l.during(&task.id)) {
        // A line the project took has an approach distance.
        let Some((approach, _)) = l.approach() else { continue };
        let name = format!("power line '{}' (beyond its {approach:.2} m approach distance)", l.name);
        out.extend(l.boxes(validate::box_reach_for_m(approach, s.support_m)).into_iter().map(|b| (b, name.clone())));
    }
    let cells = cells_covered(out.iter().map(|(b, _)| *b), cell_m);
    if cells > MAX_OBSTACLE_CELLS {
        return Err(PlanError::Settings(format!(
            "the power lines ([[power_line]]) and their approach distances cover about {cells:.0} cells of the {cell_m} m depth map, more than the {MAX_OBSTACLE_CELLS:.0} liftplan takes: give the spans near the lifts only, or a coarser [depthmap] cell_m"
        )));
    }
    Ok(out)
}

/// The other lifts' cranes that lift `k`'s crane could meet, in words:
/// those set up elsewhere (another place, heading, boom or model than lift
/// `k`'s) whose slewing axis stands nearer lift `k`'s than the two cranes'
/// reach together: what of lift `k`'s crane swings and its load's plan
/// half-diagonal, its clearance, and what of the other crane swings
/// ([`liftplan_core::crane::CraneSetup::swinging_reach_m`], an upper bound at
/// any swing, which the other crane's carrier and outriggers, a few metres
/// from its axis, lie within for any boom or jib). No lift
/// is planned against another's crane (they may not stand on site at
/// once): the plan says so, and the engineer settles it.
pub fn other_cranes(tasks: &[LiftTask], k: usize) -> Vec<String> {
    let this = &tasks[k];
    let own = &this.crane.placement;
    let own_reach =
        this.crane.swinging_reach_m() + 0.5 * this.load.size_m[0].hypot(this.load.size_m[1]) + this.clearance_m;
    let same_crane = |t: &LiftTask| {
        let a = &t.crane.placement;
        t.crane.model.name == this.crane.model.name
            && (a.x_m - own.x_m).hypot(a.y_m - own.y_m) < SAME_PLACE_M
            && (a.z_m - own.z_m).abs() < SAME_PLACE_M
            && (a.heading_rad - own.heading_rad).abs() < 1e-9
            && (a.boom_length_m - own.boom_length_m).abs() < 1e-9
    };
    tasks
        .iter()
        .enumerate()
        .filter(|&(j, t)| j != k && !same_crane(t))
        .filter_map(|(_, t)| {
            let (x, y) = (t.crane.placement.x_m, t.crane.placement.y_m);
            let apart = (x - own.x_m).hypot(y - own.y_m);
            let together = own_reach + t.crane.swinging_reach_m();
            (apart < together).then(|| {
                format!(
                    "lift {}'s {} at ({x:.2}, {y:.2}) m, {apart:.1} m from this lift's crane (the two reach {together:.1} m together)",
                    t.id, t.crane.model.name
                )
            })
        })
        .collect()
}

/// Two lifts' cranes of one model set up within this of each other (m), at
/// the same heading and boom, are taken for the same crane.
const SAME_PLACE_M: f64 = 0.5;

/// How far round its crane (m, in plan) a lift looks for a line no one gave
/// ([`wires`]): the farthest its hook reaches, and the clearance and
/// [`WORKING_MARGIN_M`] beyond.
fn working_area(task: &LiftTask) -> ([f64; 2], f64) {
    let (lo, hi) = task.crane.limits().radial;
    let reach = task.crane.radius_m(lo).max(task.crane.radius_m(hi));
    ([task.crane.placement.x_m, task.crane.placement.y_m], reach + task.clearance_m + WORKING_MARGIN_M)
}

/// Past the hook's reach, how far a line no one gave is still named (m):
/// the load's size, its swing, the boom's head beyond the hook.
pub const WORKING_MARGIN_M: f64 = 15.0;

/// What a power line's words say of a support given where neither the
/// scans nor the plant model show one, though the site around it is
/// scanned: the docs stage asks for its position to be checked first.
pub const SUPPORT_NOT_SEEN: &str = "NOT SEEN, where the scans show the site around";

/// What the scans and the plant model show where `line` is held
/// ([`validate::support_seen`]), to follow its words: "; its 2 supports
/// seen in the scans or the plant model", or which are not and why,
/// numbered as `points_m` gives them from 1.
pub fn supports_said(line: &PowerLine, world: &validate::World) -> String {
    use validate::SupportSeen;
    let seen: Vec<SupportSeen> = line.points_m.iter().map(|&p| validate::support_seen(world, p)).collect();
    let numbers = |which: SupportSeen| -> Vec<usize> {
        seen.iter().enumerate().filter(|(_, s)| **s == which).map(|(k, _)| k + 1).collect()
    };
    let list = |n: &[usize]| n.iter().map(usize::to_string).collect::<Vec<_>>().join(", ");
    let (seen_n, not_seen, unscanned) =
        (numbers(SupportSeen::Seen), numbers(SupportSeen::NotSeen), numbers(SupportSeen::NotScanned));
    let all = line.points_m.len();
    let mut said = Vec::new();
    if seen_n.len() == all {
        said.push(format!("its {all} supports seen in the scans or the plant model"));
    } else if !seen_n.is_empty() {
        said.push(format!("supports seen in the scans or the plant model: {}", list(&seen_n)));
    }
    if !not_seen.is_empty() {
        // The first few where: a line of a hundred supports must fit its row.
        const NAMED: usize = 5;
        let mut at: Vec<String> = not_seen
            .iter()
            .take(NAMED)
            .map(|&k| {
                let p = line.points_m[k - 1];
                format!("{k} at ({:.2}, {:.2}, {:.2}) m", p[0], p[1], p[2])
            })
            .collect();
        if not_seen.len() > NAMED {
            at.push(format!("and {} more ({})", not_seen.len() - NAMED, list(&not_seen[NAMED..])));
        }
        said.push(format!(
            "support{} {} {SUPPORT_NOT_SEEN} (nothing within {:.0} m of it in plan): CHECK WHERE THE LINE RUNS",
            if not_seen.len() == 1 { "" } else { "s" },
            at.join(", "),
            validate::SUPPORT_SEEN_M
        ));
    }
    if unscanned.len() == all {
        said.push("its supports outside the scans (where it runs is as given)".to_string());
    } else if !unscanned.is_empty() {
        said.push(format!(
            "outside the scans: support{} {}",
            if unscanned.len() == 1 { "" } else { "s" },
            list(&unscanned)
        ));
    }
    format!("; {}", said.join("; "))
}

/// The most depth-map cells the obstacles placed by hand may cover together:
/// each lift's map copy holds an interval for every one (16 bytes), so a
/// project file cannot make that unbounded.
pub const MAX_OBSTACLE_CELLS: f64 = 16_000_000.0;

/// Whether the obstacles' plan extents, on a map of `cell_m` cells, are
/// within [`MAX_OBSTACLE_CELLS`]; if not, what to change.
fn obstacles_fit(obstacles: &[Obstacle], cell_m: f64) -> std::result::Result<(), String> {
    let cells = cells_covered(obstacles.iter().map(Obstacle::obb), cell_m);
    if cells > MAX_OBSTACLE_CELLS {
        return Err(format!(
            "the obstacles placed by hand ([[obstacle]]) cover about {cells:.0} cells of the {cell_m} m depth map together, more than the {MAX_OBSTACLE_CELLS:.0} liftplan takes: give fewer or smaller boxes, or a coarser [depthmap] cell_m"
        ));
    }
    Ok(())
}

/// How many cells of `cell_m` the boxes' plan extents cover at most,
/// together (each a cell beyond its extent on every side).
fn cells_covered(boxes: impl Iterator<Item = Obb>, cell_m: f64) -> f64 {
    boxes
        .map(|b| {
            let a = b.aabb();
            ((a.max[0] - a.min[0]) / cell_m + 2.0) * ((a.max[1] - a.min[1]) / cell_m + 2.0)
        })
        .sum()
}

/// Runs the stage over every lift; fails on the first lift that cannot be planned and validated.
pub fn run(
    tasks: &[LiftTask],
    map_path: &Path,
    mesh_path: Option<&Path>,
    plant_json: Option<&Path>,
    cloud_path: Option<&Path>,
    capacity_csv: Option<&Path>,
    obstacles: &[Obstacle],
    power_lines: &[PowerLine],
    s: &Settings,
    seed: u64,
    out_dir: &Path,
) -> Result<RunSummary> {
    s.check().map_err(PlanError::Settings)?;
    // A plan whose capacity was never checked must not read as validated:
    // without a chart there is nothing to check it against.
    let Some(capacity_csv) = capacity_csv else {
        return Err(PlanError::Lift {
            lift: tasks.first().map(|t| t.id.clone()).unwrap_or_default(),
            message: "no load chart was read (the charts folder holds no workbook liftplan reads), so the crane's capacity cannot be checked and no plan is made: put the crane's load chart (.xlsx, .xlsm, .xlsb, .xls or .ods) in the charts folder and name its configuration in chart_config".into(),
        });
    };
    let charts =
        CapacityTable::read_csv(capacity_csv).map_err(|e| PlanError::Input(Location::file(capacity_csv), e))?;
    let map = Mdm::read(map_path).map_err(|e| PlanError::Input(Location::file(map_path), e.to_string()))?;
    obstacles_fit(obstacles, map.spec.cell).map_err(PlanError::Settings)?;
    let mesh = match mesh_path {
        Some(p) => TriMesh::read_artifact(p).map_err(|e| PlanError::Input(Location::file(p), e.to_string()))?,
        None => TriMesh::default(),
    };
    let left_out = match plant_json {
        Some(p) => excluded_boxes(p)?,
        None => Vec::new(),
    };
    // Each lift's pick and set against the groups left out, and those that
    // are some lift's load.
    let against_model: Vec<Vec<model_copy::AgainstModel>> =
        tasks.iter().map(|t| model_copy::of_lift(t, &left_out)).collect();
    let loads: Vec<String> = against_model.iter().flatten().map(|a| a.object.clone()).collect();
    let exclusions = load_exclusions(tasks, s.load_cutout_m);
    let (points, ground, taken_for_loads) = match cloud_path {
        Some(p) => read_points(p, &exclusions)?,
        None => (vec![], vec![], vec![Vec::new(); tasks.len()]),
    };
    let mut world = validate::World::new(&mesh, &points, &ground).map_err(PlanError::Settings)?;
    let model_vs_scans = validate::model_scan_agreement(&world);
    if let Some(a) = &model_vs_scans
        && let (true, Some(_), ModelOffScans::Refuse) = (a.disagrees(), a.fits_moved_by, s.model_off_scans)
    {
        return Err(PlanError::ModelOffScans(format!(
            "no plan is made: {}; correct [plant] translate_m by that move (or rotate_z_deg), or set [plan] model_off_scans = \"warn\" to plan with the model where it is",
            a.line()
        )));
    }
    // Where a load was scanned at its pick position, its cut-out was seen.
    let scanned_loads: Vec<Obb> =
        exclusions.iter().zip(&taken_for_loads).filter(|(_, t)| !t.is_empty()).map(|(b, _)| *b).collect();
    std::fs::create_dir_all(out_dir).map_err(|e| PlanError::Input(Location::file(out_dir), e.to_string()))?;
    // Each line in words with what the scans and the model show of its
    // supports: the same for every lift it is there during.
    let power_lines_said: Vec<String> =
        power_lines.iter().map(|l| format!("{}{}", l.said(), supports_said(l, &world))).collect();
    // Lines in the scans that no one gave, looked for once round every
    // lift's crane.
    let working_areas: Vec<([f64; 2], f64)> = tasks.iter().map(working_area).collect();
    let line_like = wires::find(&points, &ground, &working_areas, power_lines);
    let mut plans = Vec::new();
    for (k, (task, taken)) in tasks.iter().zip(&taken_for_loads).enumerate() {
        // The other lifts' loads where they stand during this one, in the
        // validator's view and in the planner's map alike.
        world.others = other_loads(tasks, k);
        let lifts_loads = world.others.len();
        world.others.extend(liftplan_core::obstacle::boxes_during(obstacles, &task.id));
        let lines = power_line_boxes(power_lines, task, s, map.spec.cell)?;
        world.others.extend(lines);
        // The runs of line-like points near it, kept off as lines of unknown
        // voltage where the project asks.
        let (crane_at, reach_m) = working_areas[k];
        let near_runs: Vec<wires::LineLike> =
            line_like.iter().filter(|l| l.plan_distance_m(crane_at) <= reach_m).cloned().collect();
        if s.found_lines_approach_m > 0.0 {
            let found: Vec<PowerLine> =
                near_runs.iter().enumerate().map(|(n, l)| l.as_power_line(n + 1, s.found_lines_approach_m)).collect();
            world.others.extend(power_line_boxes(&found, task, s, map.spec.cell)?);
        }
        let with_others = (!world.others.is_empty()).then(|| map.with_boxes(&world.others));
        let site = Site { map: with_others.as_ref().unwrap_or(&map), world: &world, charts: Some(&charts) };
        let above_m = cutout_above_m(s.load_cutout_m);
        let set_by = lift_that_set_the_pick(tasks, k).map(|e| e.id.clone());
        let as_scanned = cloud_path.filter(|_| set_by.is_none()).map(|_| load_scan::of_pick(task, taken, above_m));
        // A lift refused where the scans contradict the load's box is most
        // often refused for it (the load's own points beyond the cut-out
        // read as "scanned structure"): say what the scans show.
        let (mut plan, cs) = plan_lift(task, &site, s, seed).map_err(|e| match (e, &as_scanned) {
            (PlanError::Lift { lift, message }, Some(l)) if l.points > 0 && l.needs_checking() => {
                PlanError::Lift { lift, message: format!("{message}; {}", l.said()) }
            }
            (e, _) => e,
        })?;
        plan.summary.coverage = Some(coverage::of_lift(task, &plan.moves, &world, &scanned_loads));
        plan.summary.under_pads = validate::under_pads(task, &world);
        // A critical lift: where its crane could stand for it not to be.
        if plan.summary.critical
            && !task.resumes()
            && let Ok(chart) = charts.config(&task.chart_config)
        {
            let found = positions::search(task, &site, chart, s, seed, positions::Sought::NotCritical);
            plan.summary.not_critical_at = found.not_critical_said(task.critical_pct);
        }
        // The support's top under a set position inside a load's cut-out
        // went with the scanned load.
        let set_box = task.crane.load_obb(&task.set, &task.load).expanded(s.support_m);
        if scanned_loads.iter().any(|b| b.intersects(&set_box)) {
            plan.summary.set_in_cutout_m = s.load_cutout_m;
        }
        // Where the load comes to rest, whether what holds it is under its
        // centre of gravity (unknown where the support's top went with a
        // load's cut-out).
        if let Some(on) = plan.summary.set_on.as_mut().filter(|_| plan.summary.set_in_cutout_m == 0.0) {
            on.cog_inside_m =
                Some(validate::cog_over_support_m(task, &world, &task.set, on.gap_m, s.support_m, s.support_m));
            on.cog_tolerance_m = task.cog_tolerance_m;
        }
        plan.summary.other_loads = world.others[..lifts_loads].iter().map(|(_, name)| name.clone()).collect();
        plan.summary.other_cranes = other_cranes(tasks, k);
        plan.summary.obstacles = obstacles.iter().filter(|o| o.during(&task.id)).map(|o| o.said()).collect();
        plan.summary.power_lines = power_lines
            .iter()
            .zip(&power_lines_said)
            .filter(|(l, _)| l.during(&task.id))
            .map(|(_, said)| said.clone())
            .collect();
        plan.summary.line_like = near_runs;
        plan.summary.line_like_kept_off_m = s.found_lines_approach_m;
        plan.summary.load_as_scanned = as_scanned;
        plan.summary.against_model = against_model[k].clone();
        plan.summary.passes_left_out = model_copy::passes_left_out(task, &plan.moves, &left_out, &loads, &world);
        plan.load_cutout = LoadCutout { grow_m: s.load_cutout_m, above_m, points: taken.len(), set_by };
        plan.model_vs_scans = model_vs_scans.clone();
        plan.summary.revision = revision(&plan, task);
        let io = |p: &Path, e: std::io::Error| PlanError::Input(Location::file(p), e.to_string());
        let csv = out_dir.join(format!("{}.steps.csv", task.id));
        liftplan_core::artifact::write_atomic(
            &csv,
            steps::to_csv(&plan.steps, task.crane.model.is_tower(), &plan.summary.revision).as_bytes(),
        )
        .map_err(|e| io(&csv, e))?;
        let png = out_dir.join(format!("{}.cspace.png", task.id));
        let pts: Vec<(f64, f64)> = std::iter::once(&plan.moves[0].from)
            .chain(plan.moves.iter().map(|m| &m.to))
            .map(|c| (c.swing_rad, c.radial))
            .collect();
        let marks = [("PICK", task.pick.swing_rad, task.pick.radial), ("SET", task.set.swing_rad, task.set.radial)];
        liftplan_cspace::picture::draw(
            &cs,
            task.gross_kg(),
            task.capacity_reduction_pct,
            task.swing_range_rad,
            &pts,
            &marks,
        )
        .write_png(&png)
        .map_err(|e| io(&png, e))?;
        plans.push(plan);
    }
    let json = serde_json::to_string_pretty(&serde_json::json!({ "lifts": plans })).unwrap_or_default();
    let pj = out_dir.join("plan.json");
    liftplan_core::artifact::write_atomic(&pj, json.as_bytes())
        .map_err(|e| PlanError::Input(Location::file(&pj), e.to_string()))?;
    Ok(RunSummary { lifts: plans.iter().map(|p| p.summary.clone()).collect(), model_vs_scans })
}

/// A lift for the unit tests: a 6 x 3 x 2.5 m skid with its centre of
/// gravity off the box's centre, on one of the built-in cranes (a 40 m boom
/// where it luffs), heading 20°.
#[cfg(test)]
pub(crate) fn test_lift(crane: &str) -> LiftTask {
    let text = format!(
        r#"
id = "L"
load = {{ name = "skid", mass_t = 5.0, size_m = [6.0, 3.0, 2.5], cog_m = [0.8, -0.4, 0.0] }}
rigging = {{ mass_t = 0.2, height_m = 3.0 }}
crane = {{ model = "{crane}", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 20.0, boom_m = 40.0, chart_config = "none" }}
pick = {{ x_m = 22.0, y_m = -14.0, z_m = 0.5, yaw_deg = 0.0 }}
set = {{ x_m = 22.0, y_m = 14.0, z_m = 0.5, yaw_deg = 90.0 }}
"#
    );
    let spec: liftplan_core::lift::LiftSpec = toml::from_str(&text).unwrap();
    spec.resolve(liftplan_core::crane::builtin(crane).unwrap()).unwrap()
}

/// The configuration of `task`'s crane at fractions `at` (each in [0, 1]) of
/// a turn of swing, of its radial range, of its rope range (no more than
/// `rope_span_m` of it) and of a turn of load yaw: random configurations for
/// the unit tests' property tests.
#[cfg(test)]
pub(crate) fn test_config(task: &LiftTask, at: [f64; 4], rope_span_m: f64) -> liftplan_core::crane::Config {
    let lim = task.crane.limits();
    liftplan_core::crane::Config {
        swing_rad: at[0] * std::f64::consts::TAU,
        radial: lim.radial.0 + at[1] * (lim.radial.1 - lim.radial.0),
        hoist_m: lim.hoist_m.0 + at[2] * (lim.hoist_m.1 - lim.hoist_m.0).min(rope_span_m),
        load_yaw_rad: at[3] * std::f64::consts::TAU,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// plant.json's boxes of the groups left out are read as the plant stage
    /// writes them; one it never writes (a negative size, edited or
    /// damaged) is refused naming the file and the box.
    #[test]
    fn boxes_left_out_are_read_as_the_plant_stage_writes_them() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("plant.json");
        let plant = |half: &str| {
            format!(
                r#"{{"files": [], "excluded_boxes": [{{"name": "/V-101", "center_m": [30.0, 2.0, 2.7], "half_m": {half}, "yaw_deg": -0.0}}]}}"#
            )
        };
        std::fs::write(&file, plant("[4.0, 1.5, 1.5]")).unwrap();
        let boxes = excluded_boxes(&file).unwrap();
        assert_eq!((boxes.len(), boxes[0].name.as_str(), boxes[0].half_m), (1, "/V-101", [4.0, 1.5, 1.5]));
        std::fs::write(&file, plant("[4.0, -1.5, 1.5]")).unwrap();
        let e = excluded_boxes(&file).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("{}: excluded_boxes[0] ('/V-101'): half_m [4.0, -1.5, 1.5]", file.display())),
            "{e}"
        );
        assert!(e.ends_with("rerun the plant stage (liftplan run --force plant)"), "{e}");
    }

    /// Another lift's crane is named where it is set up elsewhere within the
    /// two cranes' reach, and only then: not the same crane set up again
    /// for the next lift, nor one too far off to meet, whichever is listed
    /// first.
    #[test]
    fn other_lifts_cranes_within_reach_are_named() {
        let at = |id: &str, model: &str, x: f64, boom_m: f64| {
            let mut t = test_lift(model);
            t.id = id.into();
            t.crane.placement.x_m = x;
            t.crane.placement.boom_length_m = boom_m;
            t
        };
        let a = at("A", "ac-700", 0.0, 40.0);
        let same = at("B", "ac-700", 0.2, 40.0);
        let reach = a.crane.swinging_reach_m();
        let half_diagonal = 0.5 * 6.0f64.hypot(3.0);
        assert!(reach > 40.0 && reach < 60.0, "{reach}");
        let together = 2.0 * reach + half_diagonal + a.clearance_m;
        let near = at("C", "ac-700", together - 0.5, 40.0);
        let far = at("D", "ac-700", together + 0.5, 40.0);
        let longer_boom = at("E", "ac-700", 0.0, 50.0);
        let tasks = [a.clone(), same, near, far, longer_boom];
        let named = other_cranes(&tasks, 0);
        assert_eq!(named.len(), 2, "{named:?}");
        let model = &a.crane.model.name;
        assert!(named[0].starts_with(&format!("lift C's {model} at (")), "{}", named[0]);
        assert!(named[0].contains(&format!("{:.1} m from this lift's crane", together - 0.5)), "{}", named[0]);
        assert!(named[1].starts_with(&format!("lift E's {model} at (0.00, 0.00) m, 0.0 m from")), "{}", named[1]);
        // As D's crane sees it, C's is near and A's too far.
        let from_far = other_cranes(&tasks, 3);
        assert_eq!(from_far.len(), 2, "{from_far:?}");
        assert!(from_far[0].starts_with("lift C's"), "{from_far:?}");
        assert!(from_far[1].starts_with("lift E's"), "{from_far:?}");
        assert!(other_cranes(&tasks[..2], 0).is_empty());
    }

    /// Lifts are made in the order listed: during B, A (before it) stands
    /// where A sets it and C (after it) where C picks it up; a lift that
    /// picks up what an earlier one set down (D takes B's load on) does
    /// not meet its own load as another.
    #[test]
    fn other_lifts_loads_stand_where_the_order_puts_them() {
        let lift = |id: &str, pick_turn: f64, set_turn: f64| {
            let mut t = test_lift("ac-700");
            t.id = id.into();
            t.pick = Config { swing_rad: t.pick.swing_rad + pick_turn, ..t.pick };
            t.set = Config { swing_rad: t.set.swing_rad + set_turn, ..t.set };
            t
        };
        let (a, b, c) = (lift("A", 0.0, 0.0), lift("B", 0.3, 0.3), lift("C", 0.6, 0.6));
        let mut d = lift("D", 0.3, 0.9);
        d.pick = b.set;
        let tasks = [a.clone(), b.clone(), c.clone(), d];
        let during_b = other_loads(&tasks, 1);
        let names: Vec<&str> = during_b.iter().map(|(_, n)| n.as_str()).collect();
        // B sets down the load D picks up: D's load is B's own.
        assert_eq!(names, ["load of lift A at its set position", "load of lift C at its pick position"]);
        assert!(same_box(&during_b[0].0, &a.crane.load_obb(&a.set, &a.load)));
        assert!(same_box(&during_b[1].0, &c.crane.load_obb(&c.pick, &c.load)));
        let during_d: Vec<String> = other_loads(&tasks, 3).into_iter().map(|(_, n)| n).collect();
        assert_eq!(during_d, ["load of lift A at its set position", "load of lift C at its set position"]);
        assert!(other_loads(&tasks[..1], 0).is_empty());
        // D takes on what B set down: its load was not there when scanned.
        let set_by: Vec<Option<&str>> =
            (0..tasks.len()).map(|k| lift_that_set_the_pick(&tasks, k).map(|e| e.id.as_str())).collect();
        assert_eq!(set_by, [None, None, None, Some("B")]);
    }

    #[test]
    fn obstacles_that_would_fill_memory_are_refused() {
        let o = |side: f64| Obstacle {
            name: format!("{side} m box"),
            center_m: [0.0, 0.0],
            base_z_m: 0.0,
            size_m: [side, side, 3.0],
            yaw_deg: 45.0,
            lifts: vec![],
        };
        assert_eq!(obstacles_fit(&[o(10.0), o(20.0)], 0.25), Ok(()));
        // 200 boxes of 500 m at 0.25 m cells would be 16 G intervals.
        let many: Vec<Obstacle> = (0..200).map(|_| o(500.0)).collect();
        let why = obstacles_fit(&many, 0.25).unwrap_err();
        assert!(why.contains("give fewer or smaller boxes"), "{why}");
        // Turned 45°, one spans 707 m either way: 8 M cells.
        assert_eq!(obstacles_fit(&many[..1], 0.25), Ok(()));
        assert!(obstacles_fit(&many[..3], 0.25).is_err());
        assert_eq!(obstacles_fit(&many[..3], 0.5), Ok(()));
    }
}
