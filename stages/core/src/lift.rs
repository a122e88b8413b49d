//! The lift request an engineer writes (`[[lift]]` in `liftplan.toml`) and its
//! validated form, [`LiftTask`], in SI units.
//!
//! Pick and set are given either as load poses (where the load rests: box-centre
//! plan position, underside height, yaw), solved by inverse kinematics, or as crane
//! configurations. The gross load the chart must carry is load + rigging + hook
//! block + configured deductions (ICE-Planner's "total load").

use crate::crane::{Config, CraneModel, CraneSetup, Dependence, LoadPose, LoadShape, PartKind, Placement};
use crate::units::KG_PER_TONNE;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    #[serde(default = "default_load_name")]
    pub name: String,
    pub mass_t: f64,
    /// Box size along the load's x, y, z.
    pub size_m: [f64; 3],
    /// Centre of gravity relative to the box centre.
    #[serde(default)]
    pub cog_m: [f64; 3],
    /// How far the centre of gravity may lie from `cog_m` along the load's
    /// x and y (m): where it is known only so well (a vendor's drawing, a
    /// load of unknown contents), the legs are checked for the worst within
    /// it ([`crate::slings::check_within`]) and so is the load's balance on
    /// what it is set on.
    #[serde(default, skip_serializing_if = "crate::is_zero")]
    pub cog_tolerance_m: f64,
    /// How far the centre of gravity may lie above or below `cog_m`'s
    /// height (m): on one or two legs the load turns about its lift points,
    /// and is checked not to turn over with the centre of gravity at the
    /// highest it may lie ([`LiftTask::check_slings`]).
    #[serde(default, skip_serializing_if = "crate::is_zero")]
    pub cog_tolerance_z_m: f64,
}

fn default_load_name() -> String {
    "load".into()
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RiggingSpec {
    #[serde(default)]
    pub mass_t: f64,
    /// Hook block underside to the top of the load.
    #[serde(default = "default_rigging_height")]
    pub height_m: f64,
    /// The sling legs' number (1, 2 or 4, at the default lift points:
    /// [`crate::slings::default_points`]), where `lift_points_m` does not
    /// give them.
    #[serde(default)]
    pub legs: Option<usize>,
    /// Each sling leg's working load limit (t, straight pull): the legs are
    /// checked against it ([`crate::slings`]); without it they are not.
    #[serde(default)]
    pub leg_wll_t: Option<f64>,
    /// Where each leg takes the load, from the centre of its box in the
    /// load's frame (m), one to four points.
    #[serde(default)]
    pub lift_points_m: Option<Vec<[f64; 3]>>,
    /// A beam the two legs hang plumb from ([`crate::slings::Spreader`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spreader: Option<SpreaderSpec>,
    /// How the legs hold the load: "straight" (to lift points) or
    /// "choked" (round it: [`crate::slings::CHOKE_FACTOR`]).
    #[serde(default, skip_serializing_if = "Hitch::is_straight")]
    pub hitch: Hitch,
    /// The working load limit of the shackle at each lift point (t, in line).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shackle_wll_t: Option<f64>,
    /// What each lift point (a lug, a trunnion) may carry in its leg's
    /// direction (t), as its rating for that angle gives it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lift_point_wll_t: Option<f64>,
    /// The direction of the shackle's pin at each lift point, in the
    /// points' order (the axis of its lug's hole, in the load's frame; any
    /// length): the shackles are then checked for side loading
    /// ([`crate::slings::side_loading`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_axes: Option<Vec<[f64; 3]>>,
}

/// `rigging.hitch`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Hitch {
    #[default]
    Straight,
    Choked,
}

impl Hitch {
    fn is_straight(&self) -> bool {
        *self == Hitch::Straight
    }
}

/// `rigging.spreader`: a spreader beam hung from the hook by two top legs
/// (`top_leg_wll_t` given) or a lifting beam hung by its lug (not given);
/// with `width_m`, a spreader or lifting frame over four lift points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpreaderSpec {
    /// End to end (m).
    pub length_m: f64,
    /// From the hook block's underside down to its pins (m).
    pub below_hook_m: f64,
    /// What it may carry below it (t).
    pub wll_t: f64,
    /// Its own mass (t), part of `rigging.mass_t`.
    #[serde(default)]
    pub mass_t: f64,
    /// Each top leg's working load limit (t, straight pull).
    #[serde(default)]
    pub top_leg_wll_t: Option<f64>,
    /// A spreader frame's width (m, along the load's y; `length_m` along
    /// its x), over four lift points ([`crate::slings::check_frame`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width_m: Option<f64>,
    /// Each top leg's shackle's working load limit (t, in line), at the
    /// spreader's lugs: checked against its top leg's pull.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub top_shackle_wll_t: Option<f64>,
    /// The direction of each top shackle's pin (the axis of the
    /// spreader's lug's hole, in the load's frame), one per top leg in the
    /// order of the lift points: the top shackles are then checked for
    /// side loading ([`crate::slings::TopShackles`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub top_pin_axes: Option<Vec<[f64; 3]>>,
}

impl Default for RiggingSpec {
    fn default() -> Self {
        RiggingSpec {
            mass_t: 0.0,
            height_m: default_rigging_height(),
            legs: None,
            leg_wll_t: None,
            lift_points_m: None,
            spreader: None,
            hitch: Hitch::Straight,
            shackle_wll_t: None,
            lift_point_wll_t: None,
            pin_axes: None,
        }
    }
}

fn default_rigging_height() -> f64 {
    2.0
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CraneSpec {
    /// A built-in model name or a file in `cranes/` (without `.toml`).
    pub model: String,
    /// Slewing axis in the site frame.
    pub position_m: [f64; 2],
    /// Ground level at the slewing axis.
    #[serde(default)]
    pub ground_z_m: f64,
    pub heading_deg: f64,
    /// Main boom length (luffing cranes).
    #[serde(default)]
    pub boom_m: Option<f64>,
    /// The chart configuration this set-up uses (counterweight, outriggers, sector).
    pub chart_config: String,
    /// Extra deductions the chart's notes require (e.g. stowed jib), tonnes.
    #[serde(default)]
    pub deductions_t: f64,
    /// The counterweight rigged (t), for the outrigger loads; the crane
    /// file's `[masses] counterweight_t` where left out.
    #[serde(default)]
    pub counterweight_t: Option<f64>,
    /// The falls (parts of line) the hoist rope is reeved with, checked
    /// against the crane file's line pull per fall ([`crate::reeving`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub falls: Option<u32>,
    /// The longest rope below the boom head (the trolley) this lift is
    /// planned with (m): the hook's travel for this lift, within the crane
    /// file's. Where the crane file weighs its hoist rope, the rope is
    /// counted in the hook load at this length ([`crate::reeving::RopeWeight`]);
    /// left out, at the crane's longest.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub longest_rope_m: Option<f64>,
}

/// The mats under the outrigger pads and what the ground may bear, for the
/// pressure each pad puts on it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundSpec {
    /// A pad's mat, length by width (m).
    pub mat_m: [f64; 2],
    /// The bearing pressure the ground may take (kPa = kN/m²), as the site's
    /// ground assessment gives it.
    #[serde(default)]
    pub allowable_kpa: Option<f64>,
}

/// Whose counterweight the outrigger loads are worked out with
/// ([`LiftTask::counterweight_used_kg`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum CounterweightFrom {
    /// The lift's `crane counterweight_t`.
    Lift,
    /// The one the lift's chart configuration's name states.
    ChartConfig,
    /// The one its chart's sheet states beside the grid
    /// ([`LiftTask::chart_sheet_counterweight`]).
    ChartSheet,
    /// The crane file's `[masses] counterweight_t`.
    CraneFile,
}

/// The heaviest counterweight a chart's configuration name or sheet is
/// read to state (t): more than any crane carries, so a number beyond it
/// is not one, and read back from `chart.json` it is refused
/// ([`crate::chart_json`]).
pub const MAX_COUNTERWEIGHT_T: f64 = 10_000.0;

/// The counterweight a chart configuration's name states, in kg: "Main
/// boom 360 CW 70t", "counterweight 42.5 t", "Ballast: 140 t",
/// "Gegengewicht 70 t". `None` where it states none, or two that differ.
pub fn counterweight_named_kg(name: &str) -> Option<f64> {
    let lower = name.to_lowercase();
    let mut found: Option<f64> = None;
    for key in ["counterweight", "counter-weight", "counter weight", "ballast", "gegengewicht", "cw"] {
        let mut from = 0;
        while let Some(i) = lower[from..].find(key).map(|i| i + from) {
            from = i + key.len();
            // A whole word: "cw" not inside "screw".
            if lower[..i].chars().next_back().is_some_and(char::is_alphanumeric) {
                continue;
            }
            let rest = lower[from..].trim_start_matches([' ', ':', '=', '\u{a0}']);
            let digits = rest.find(|c: char| !(c.is_ascii_digit() || c == '.' || c == ',')).unwrap_or(rest.len());
            let after = rest[digits..].trim_start();
            let is_tonnes = after.starts_with('t') && !after[1..].starts_with(char::is_alphanumeric);
            let Ok(t) = rest[..digits].replace(',', ".").parse::<f64>() else { continue };
            if !(is_tonnes && t.is_finite() && t > 0.0 && t <= MAX_COUNTERWEIGHT_T) {
                continue;
            }
            match found {
                Some(f) if (f - t * KG_PER_TONNE).abs() > 1e-6 => return None,
                _ => found = Some(t * KG_PER_TONNE),
            }
        }
    }
    found
}

/// Pick or set: a load pose (`x_m`, `y_m`, `z_m`, `yaw_deg`) or a configuration
/// (`swing_deg`, `luff_deg` or `trolley_m`, `hoist_m`, `yaw_deg`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoseSpec {
    pub x_m: Option<f64>,
    pub y_m: Option<f64>,
    /// Underside of the load.
    pub z_m: Option<f64>,
    pub swing_deg: Option<f64>,
    pub luff_deg: Option<f64>,
    pub trolley_m: Option<f64>,
    pub hoist_m: Option<f64>,
    #[serde(default)]
    pub yaw_deg: f64,
}

/// The plan a lift resumed part way continues ([`LiftSpec::resumes_plan`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResumesPlan {
    /// Its revision: the 8 hex digits after "plan" on the foot of each page
    /// of its PDF.
    pub revision: String,
    /// The last of its steps done (where the lift stopped during the next,
    /// `resume_from` says where).
    pub after_step: usize,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LiftSpec {
    pub id: String,
    #[serde(default)]
    pub description: String,
    pub load: LoadSpec,
    #[serde(default)]
    pub rigging: RiggingSpec,
    pub crane: CraneSpec,
    pub pick: PoseSpec,
    pub set: PoseSpec,
    /// Where the load hangs now, part way through the lift, to plan from
    /// there to the set instead of from the pick: re-planning when the site
    /// has changed during the lift. A configuration read off the crane
    /// (`swing_deg`, `luff_deg` or `trolley_m`, `hoist_m`, `yaw_deg`, as
    /// the plan's steps give them) or the load's pose.
    #[serde(default)]
    pub resume_from: Option<PoseSpec>,
    /// The plan a resumed lift continues and the last step of it done, as
    /// `liftplan resume` prints them beside `resume_from`: said on the new
    /// plan's cover, so that its record names the plan it follows on from.
    /// Only with `resume_from`.
    #[serde(default)]
    pub resumes_plan: Option<ResumesPlan>,
    /// Minimum clear distance from every crane part and the load to any obstacle.
    #[serde(default = "default_clearance")]
    pub clearance_m: f64,
    /// Vertical lift-off at the pick and set-down at the set, done hook-only with
    /// the support surface allowed to touch the load.
    #[serde(default = "default_liftoff")]
    pub liftoff_m: f64,
    /// Capacity reduction applied to every chart value (site rules, wind), percent.
    #[serde(default)]
    pub capacity_reduction_pct: f64,
    /// Added to every radius before the chart is read (m): an allowance for
    /// the boom bending under load, which lengthens the radius the rigid
    /// crane model plans with.
    #[serde(default)]
    pub radius_allowance_m: f64,
    /// How far round the ground under the load (and what hangs with it, as
    /// far as a gust may swing it) people are kept out while it moves, for
    /// what may fall from it and where it would land if it fell (m); drawn
    /// and measured, and kept off the areas the load must never be over
    /// (`not_over`: people there cannot be kept out), which the path is
    /// planned round by that much more. Elsewhere the ground is cleared by
    /// the crew, not planned round.
    #[serde(default)]
    pub fall_zone_m: f64,
    /// Utilisation above which the lift is flagged critical, percent.
    #[serde(default = "default_critical")]
    pub critical_pct: f64,
    /// Permitted slewing range relative to the carrier heading, degrees.
    #[serde(default)]
    pub swing_range_deg: Option<[f64; 2]>,
    /// The outrigger pads' mats and the ground's allowable bearing pressure.
    #[serde(default)]
    pub ground: Option<GroundSpec>,
    /// The chart's permissible wind speed and the load's drag, for the wind
    /// speed up to which this load may be lifted.
    #[serde(default)]
    pub wind: Option<crate::wind::WindSpec>,
    /// Areas the load must never be over (an occupied building, a road,
    /// live plant), in plan, in the frame of the pick and the set.
    #[serde(default)]
    pub not_over: Vec<NotOver>,
    /// Where the crane may be set up (a hardstanding, a road, a prepared
    /// pad), in plan: its carrier and outriggers (or a tower's mast) stand
    /// within one of these where any is given.
    #[serde(default)]
    pub crane_stands_in: Vec<CraneArea>,
}

/// An area the crane may be set up in: its carrier and outriggers (their
/// plan outlines' hull) lie within the polygon `corners_m` ([x, y] in
/// metres, in order around it), clear of its edges.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CraneArea {
    pub name: String,
    pub corners_m: Vec<[f64; 2]>,
}

/// An area the load must never be over: its footprint (the plan outline of
/// its box) keeps out of the polygon `corners_m` ([x, y] in metres, in
/// order around it) at every moment of the lift.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NotOver {
    pub name: String,
    pub corners_m: Vec<[f64; 2]>,
    /// The crane may not be over it either (may not oversail it: a
    /// railway, a neighbour's property): nothing that turns with its swing
    /// (superstructure, counterweight, boom or jib, rope, hook block) comes
    /// over it, as the load does not.
    #[serde(default)]
    pub crane_too: bool,
}

/// How far the planner keeps the footprints of what hangs from the crane
/// (and of the crane, where it may not be over it either) off a `not_over` area
/// (m): at least the validator's half spacing of its samples at its
/// coarsest setting, so that a path the planner finds clear the validator
/// finds clear too.
pub const NOT_OVER_MARGIN_M: f64 = 0.25;

/// The most `not_over` areas a lift may give, and corners an area may have:
/// the planner tests the load's footprint against them at every
/// configuration it checks, so a lift file cannot make that unbounded.
pub const MAX_NOT_OVER: usize = 50;
pub const MAX_NOT_OVER_CORNERS: usize = 200;
/// The longest name an area may have (characters): the PDF says it.
pub const MAX_NOT_OVER_NAME: usize = 100;

impl NotOver {
    /// Why it is not an area a lift can give, naming the key.
    fn problem(&self, k: usize) -> Option<String> {
        area_problem("not_over", "control room", k, &self.name, &self.corners_m)
    }
}

impl CraneArea {
    /// Why it is not an area a lift can give, naming the key.
    fn problem(&self, k: usize) -> Option<String> {
        area_problem("crane_stands_in", "hardstanding north of the rack", k, &self.name, &self.corners_m)
    }
}

/// Why a plan area of a lift's `key` list (its `k`th, from 0) is not one it
/// can give: a name, 3 to [`MAX_NOT_OVER_CORNERS`] finite corners, and an
/// area.
fn area_problem(key: &str, example: &str, k: usize, name: &str, corners_m: &[[f64; 2]]) -> Option<String> {
    let n = corners_m.len();
    if name.trim().is_empty() {
        return Some(format!("{key}[{k}] needs a name (what the area is: \"{example}\")"));
    }
    if name.chars().count() > MAX_NOT_OVER_NAME {
        return Some(format!("{key}[{k}]'s name is longer than {MAX_NOT_OVER_NAME} characters"));
    }
    if !(3..=MAX_NOT_OVER_CORNERS).contains(&n) {
        return Some(format!(
            "{key} '{name}' needs 3 to {MAX_NOT_OVER_CORNERS} corners_m ([x, y] in metres, in order around it), found {n}"
        ));
    }
    if let Some(c) = corners_m.iter().find(|c| !(c[0].is_finite() && c[1].is_finite())) {
        return Some(format!("{key} '{name}' has a corner that is not a finite [x, y] in metres: {c:?}"));
    }
    let twice_area: f64 = (0..n)
        .map(|i| {
            let (a, b) = (corners_m[i], corners_m[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum();
    if !(twice_area.abs() > 2e-4) {
        return Some(format!("{key} '{name}' encloses no area: give its corners_m in order around it"));
    }
    None
}

fn default_clearance() -> f64 {
    1.0
}
fn default_liftoff() -> f64 {
    0.5
}
fn default_critical() -> f64 {
    75.0
}

/// A validated lift: everything in SI, pick and set solved to configurations.
#[derive(Debug, Clone)]
pub struct LiftTask {
    pub id: String,
    pub description: String,
    pub crane: CraneSetup,
    pub chart_config: String,
    pub load_name: String,
    pub load: LoadShape,
    /// [`LoadSpec::cog_tolerance_m`] (m, along the load's x and y).
    pub cog_tolerance_m: f64,
    /// [`LoadSpec::cog_tolerance_z_m`] (m, along the load's z).
    pub cog_tolerance_z_m: f64,
    pub load_mass_kg: f64,
    pub rigging_mass_kg: f64,
    /// The sling legs to check, where the lift gives their working load
    /// limit ([`RiggingSpec::leg_wll_t`]).
    pub slings: Option<crate::slings::Slings>,
    /// The falls the hoist rope is reeved with (`crane.falls`).
    pub falls: Option<u32>,
    /// How far the falls let the hook hang below the boom head, where the
    /// crane file gives the hoist rope's length: where less than the hook's
    /// travel, the crane is set up with it as its longest rope
    /// ([`crate::reeving`]).
    pub rope_reach: Option<crate::reeving::RopeReach>,
    /// The hoist rope below the boom head, part of the hook load, where the
    /// crane file weighs it ([`crate::reeving::RopeWeight`]).
    pub rope_weight: Option<crate::reeving::RopeWeight>,
    /// The lift's own longest rope (m, [`CraneSpec::longest_rope_m`]): the
    /// crane is set up with it as its longest rope.
    pub longest_rope_m: Option<f64>,
    pub deductions_kg: f64,
    /// Configurations with the load resting at its pick and set positions.
    pub pick: Config,
    pub set: Config,
    pub pick_pose: LoadPose,
    pub set_pose: LoadPose,
    /// Where the load hangs when the lift resumes part way through
    /// ([`LiftSpec::resume_from`]): the plan starts there, with no lift-off.
    pub resume_from: Option<(Config, LoadPose)>,
    /// The plan it continues, where the lift says ([`LiftSpec::resumes_plan`]).
    pub resumes_plan: Option<ResumesPlan>,
    pub clearance_m: f64,
    pub liftoff_m: f64,
    pub capacity_reduction_pct: f64,
    /// Added to every radius before the chart is read (m).
    pub radius_allowance_m: f64,
    /// [`LiftSpec::fall_zone_m`].
    pub fall_zone_m: f64,
    pub critical_pct: f64,
    pub swing_range_rad: Option<(f64, f64)>,
    /// Whether the pick and the set were given as crane configurations
    /// (swing, luff or trolley, hoist) rather than load poses: which key
    /// sets their height.
    pub by_configuration: [bool; 2],
    /// The counterweight rigged (kg), where the lift says it.
    pub counterweight_kg: Option<f64>,
    pub ground: Option<GroundSpec>,
    pub wind: Option<crate::wind::WindSpec>,
    /// Areas the load must never be over ([`NotOver`]).
    pub not_over: Vec<NotOver>,
    /// Areas the crane may be set up in ([`CraneArea`]); none given: anywhere.
    pub crane_stands_in: Vec<CraneArea>,
    /// The counterweight the lift's chart configuration's sheet states in
    /// words beside its grid, where it states one ("Counterweight 140 t",
    /// its cell): set by the stage that has read the chart, none until then.
    pub chart_sheet_counterweight: Option<crate::capacity::StatedOnChart>,
    /// How far a sudden gust at the permissible wind can swing what hangs
    /// from the crane, per metre it hangs below the boom head's sheave
    /// ([`crate::wind::PermissibleWind::gust_swing_per_m`]): the planner and
    /// the validator keep the clearance with the hanging parts swung so
    /// ([`Self::hanging_swept`]). 0 where the lift is not planned for the wind;
    /// set by [`Self::plan_for_wind`].
    pub gust_swing_per_m: f64,
}

impl LiftTask {
    /// The key that sets the height of the pick (`at_pick`) or the set, as
    /// the lift gives it: `pick z_m`, or `pick hoist_m` for a position given
    /// as a crane configuration.
    pub fn height_key(&self, at_pick: bool) -> &'static str {
        match (at_pick, self.by_configuration[usize::from(!at_pick)]) {
            (true, false) => "pick z_m",
            (true, true) => "pick hoist_m",
            (false, false) => "set z_m",
            (false, true) => "set hoist_m",
        }
    }

    /// The sling legs' check ([`crate::slings::check_within`]), where the
    /// lift gives them: the centre of gravity anywhere within its tolerance
    /// in plan, and at the highest its height's tolerance lets it lie,
    /// which is the worst for turning over on one or two legs and for the
    /// tilt's bound (nothing else of the check depends on its height: the
    /// legs' pulls on a load hanging level depend on where it lies in
    /// plan).
    pub fn check_slings(&self) -> Option<Result<crate::slings::SlingCheck, String>> {
        let legs = self.slings.as_ref()?;
        let (l, tz) = (&self.load, self.cog_tolerance_z_m);
        let highest = [l.cog_m[0], l.cog_m[1], l.cog_m[2] + tz];
        let c = crate::slings::check_within(
            legs,
            self.load_mass_kg,
            l.size_m,
            highest,
            self.cog_tolerance_m,
            l.rigging_height_m,
        );
        Some(match c {
            Ok(c) => Ok(crate::slings::SlingCheck {
                cog_tolerance_z_m: tz,
                side_loading: crate::slings::side_loading(
                    legs,
                    l.size_m,
                    l.cog_m,
                    self.cog_tolerance_m,
                    tz,
                    l.rigging_height_m,
                ),
                ..c
            }),
            Err(e) if tz > 0.0 => Err(format!(
                "with the load's centre of gravity up to load cog_tolerance_z_m ({tz:.2} m) higher than given, at z {:.2} m from its box's centre: {e}",
                highest[2]
            )),
            Err(e) => Err(e),
        })
    }

    /// Load + rigging + hook block + the hoist rope where weighed
    /// ([`Self::hook_load_kg`]) + deductions, in kg.
    pub fn gross_kg(&self) -> f64 {
        self.hook_load_kg() + self.deductions_kg
    }

    /// What hangs from the boom head: load, rigging, hook block and the
    /// hoist rope below the head where the crane file weighs it (counted at
    /// the longest rope the lift is planned with), in kg (the chart's
    /// deductions, a stowed jib, do not).
    pub fn hook_load_kg(&self) -> f64 {
        self.least_hanging_kg() + self.rope_weight.as_ref().map_or(0.0, |w| w.kg)
    }

    /// The least that may hang from the boom head: load, rigging and hook
    /// block, without the rope (kg). Where less weight is the worse case
    /// (the wind the load may be lifted in, the pads behind the crane), it
    /// is worked out with this.
    pub fn least_hanging_kg(&self) -> f64 {
        self.load_mass_kg + self.rigging_mass_kg + self.crane.model.hook.mass_kg
    }

    /// The outrigger pads' loads at `c` ([`crate::outriggers::pad_loads`]),
    /// the gross load on the hook; `None` for a tower crane or a crane file
    /// without masses.
    pub fn pad_loads(&self, c: &Config) -> Option<crate::outriggers::PadLoads> {
        self.pad_loads_hanging(c, self.gross_kg())
    }

    /// [`LiftTask::pad_loads`] with `hanging_kg` on the hook. Where the chart's
    /// deductions weigh (a stowed jib on the boom, a heavier hook block) the
    /// lift does not say, and how much of the hoist rope hangs (it is
    /// counted at its longest): at the hook they load the pads in front of
    /// the crane more, and elsewhere those behind it, so a pad's most is the
    /// higher of the gross load and the least that hangs
    /// ([`Self::least_hanging_kg`]).
    pub fn pad_loads_hanging(&self, c: &Config, hanging_kg: f64) -> Option<crate::outriggers::PadLoads> {
        let (counterweight_kg, _) = self.counterweight_used_kg()?;
        crate::outriggers::pad_loads(&self.crane, c.swing_rad, c.radial, hanging_kg, counterweight_kg)
    }

    /// The counterweight the outrigger loads are worked out with (kg), and
    /// whose it is: the lift's (`crane counterweight_t`), else its chart's
    /// ([`Self::chart_counterweight_kg`]: the chart is read for what is
    /// rigged), else the crane file's; `None` where there are no masses.
    pub fn counterweight_used_kg(&self) -> Option<(f64, CounterweightFrom)> {
        let crate::crane::CraneKind::Luffing(l) = &self.crane.model.kind else { return None };
        let file = l.masses?.counterweight_t * KG_PER_TONNE;
        Some(match (self.counterweight_kg, self.chart_counterweight_kg()) {
            (Some(kg), _) => (kg, CounterweightFrom::Lift),
            (None, Some((kg, from))) => (kg, from),
            (None, None) => (file, CounterweightFrom::CraneFile),
        })
    }

    /// The counterweight the lift's chart states (kg): the one its
    /// configuration's name states ([`counterweight_named_kg`]), else the
    /// one its sheet states beside the grid.
    pub fn chart_counterweight_kg(&self) -> Option<(f64, CounterweightFrom)> {
        match (counterweight_named_kg(&self.chart_config), &self.chart_sheet_counterweight) {
            (Some(kg), _) => Some((kg, CounterweightFrom::ChartConfig)),
            (None, Some(stated)) => Some((stated.value, CounterweightFrom::ChartSheet)),
            (None, None) => None,
        }
    }

    /// Where the lift's `crane counterweight_t` is not what its chart states
    /// ([`Self::chart_counterweight_kg`]; more than 0.05 t apart): the two
    /// (kg).
    pub fn counterweight_disagrees_kg(&self) -> Option<[f64; 2]> {
        let (lift, (chart, _)) = (self.counterweight_kg?, self.chart_counterweight_kg()?);
        ((lift - chart).abs() > 50.0).then_some([lift, chart])
    }

    /// The wind speed up to which the load may be lifted: from the lift's
    /// `wind`, its chart's speed the lift's `chart_ms` or else the one its
    /// chart's sheet states (`stated`, each speed it states once); its hook
    /// load the load, the slings and the hook block (the chart's deductions
    /// do not hang in the wind). Err: why it is not worked out. With it, the
    /// speeds the sheet states where the lift's `chart_ms` is none of them.
    pub fn permissible_wind(
        &self,
        stated: &[crate::capacity::StatedOnChart],
    ) -> Result<(crate::wind::PermissibleWind, Vec<crate::capacity::StatedOnChart>), String> {
        let listed =
            || stated.iter().map(|s| format!("{:.1} m/s ({})", s.value, s.cell)).collect::<Vec<_>>().join(", ");
        let Some(spec) = &self.wind else {
            return Err(if stated.is_empty() {
                "the lift gives no wind = { chart_ms, cw } (the chart's permissible wind speed and the load's drag coefficient)".to_string()
            } else {
                format!(
                    "the lift gives no wind = {{ cw }}, the load's drag coefficient (its chart's sheet states {})",
                    listed()
                )
            });
        };
        let (chart_ms, cell) = match (spec.chart_ms, stated) {
            (Some(v), _) => (v, None),
            (None, [one]) => (one.value, Some(one.cell.clone())),
            (None, []) => {
                return Err("the lift's wind gives no chart_ms, and its chart's sheet states no wind speed".to_string());
            }
            (None, _) => {
                return Err(format!(
                    "the lift's wind gives no chart_ms, and its chart's sheet states several wind speeds, {}: give chart_ms",
                    listed()
                ));
            }
        };
        // A sheet may state several speeds (one for long booms): the lift's
        // is to be checked only where it is none of them.
        let stated_too = stated.iter().any(|s| (s.value - chart_ms).abs() <= 0.05);
        let other = if stated_too { Vec::new() } else { stated.to_vec() };
        let w = crate::wind::PermissibleWind::of(chart_ms, cell, spec, self.load.size_m, self.least_hanging_kg());
        Ok((w.with_rope(self.rope_in_wind()), other))
    }

    /// The hoist rope's falls in the wind ([`crate::wind::RopeInWind`]): the
    /// lift's falls, or where it gives none the most the hook block takes;
    /// the crane file's diameter, or where it gives none the widest a rope
    /// of its mass per metre is; at the longest rope the lift is planned
    /// with, whatever the path. Err: why it is not counted, naming what to
    /// give.
    pub fn rope_in_wind(&self) -> Result<crate::wind::RopeInWind, String> {
        let hook = &self.crane.model.hook;
        let Some((falls, falls_given)) = crate::reeving::falls_counted(self.falls, hook.max_falls) else {
            return Err(
                "the lift gives no falls (crane falls) and the crane file no most falls (hook.max_falls)".to_string()
            );
        };
        let (diameter_mm, diameter_given) = match (hook.rope_diameter_mm, hook.rope_kg_per_m) {
            (Some(d), _) => (d, true),
            (None, Some(kg_per_m)) => (crate::wind::RopeInWind::widest_diameter_mm(kg_per_m), false),
            (None, None) => {
                return Err(
                    "the crane file gives neither the rope's diameter nor its mass per metre (hook.rope_diameter_mm, hook.rope_kg_per_m)".to_string()
                );
            }
        };
        Ok(crate::wind::RopeInWind::new(falls, falls_given, diameter_mm, diameter_given, hook.max_rope_m))
    }

    /// Sets [`Self::gust_swing_per_m`] from the lift's `wind`, with the
    /// speeds its chart's sheet states (`stated`; see
    /// [`Self::permissible_wind`]), where it is planned for the load's swing
    /// (`wind plan_for_swing`, on unless turned off); 0 otherwise. Err: why
    /// the swing cannot be worked out, naming what to give.
    pub fn plan_for_wind(&mut self, stated: &[crate::capacity::StatedOnChart]) -> Result<(), String> {
        self.gust_swing_per_m = match &self.wind {
            Some(spec) if spec.plan_for_swing => match self.permissible_wind(stated) {
                Ok((w, _)) => w.gust_swing_per_m(),
                Err(why) => {
                    return Err(format!(
                        "lift '{}': the load's swing in the wind cannot be planned for: {why}; or set wind plan_for_swing = false (the plan then keeps its clearance with the load hanging plumb)",
                        self.id
                    ));
                }
            },
            _ => 0.0,
        };
        Ok(())
    }

    /// Whether the lift is to be planned for the load's swing in the wind and
    /// it is not worked out yet: its chart speed comes from the chart's sheet,
    /// which [`Self::plan_for_wind`] has not been given.
    pub fn wind_swing_unknown(&self) -> bool {
        self.wind.is_some_and(|w| w.plan_for_swing) && self.gust_swing_per_m <= 0.0
    }

    /// A hanging part's box `b` (a `kind` that hangs) at a configuration
    /// whose sheave is at height `sheave_z`, grown in plan by how far it may
    /// hang off where the crane holds it: by how far a sudden gust at the
    /// permissible wind can swing it, [`Self::gust_swing_per_m`] times how
    /// far its underside hangs below the sheave, on every side (the wind's
    /// direction is not known; a swinging load rises, never falls, so its
    /// underside stays); and, for the load and its rigging, by the centre
    /// of gravity's tolerance ([`Self::cog_tolerance_m`]) along the load's
    /// x and y: hanging level, as the plan takes it, the load has the hook
    /// over its centre of gravity wherever that lies, so it hangs off by as
    /// much as that lies off where the lift gives it (the rigging's box,
    /// over the load's footprint, with it). On legs left as made for the
    /// centre of gravity as given it hangs tilted instead: not planned, but
    /// bounded and said ([`crate::slings::tilt_bound_deg`]). `b` itself
    /// where neither applies. For upright boxes, as every hanging part's
    /// is, turned as the load is: then the growth is exact.
    pub fn hanging_swept(&self, kind: PartKind, b: &crate::obb::Obb, sheave_z: f64) -> crate::obb::Obb {
        let cog_m = if matches!(kind, PartKind::Load | PartKind::Rigging) { self.cog_tolerance_m } else { 0.0 };
        if self.gust_swing_per_m <= 0.0 && cog_m <= 0.0 {
            return *b;
        }
        let below_m = (sheave_z - b.aabb().min[2]).max(0.0);
        b.expanded_by_motion(self.gust_swing_per_m * below_m + cog_m, 0.0)
    }

    /// Whether what hangs may hang off where the crane holds it
    /// ([`Self::hanging_swept`]): planned for the wind, or a centre of
    /// gravity known only to a tolerance.
    pub fn hangs_swept(&self) -> bool {
        self.gust_swing_per_m > 0.0 || self.cog_tolerance_m > 0.0
    }

    /// The crane's parts at `c` ([`CraneSetup::pose`]), what hangs grown by
    /// how far it may hang off ([`Self::hanging_swept`]) where `free` (not
    /// in a lift-off or set-down, where the crew holds it at its support).
    pub fn pose_hanging_swept(&self, c: &Config, free: bool) -> crate::crane::CranePose {
        let mut pose = self.crane.pose(c, &self.load);
        if free && self.hangs_swept() {
            let sheave_z = self.crane.sheave(c).z;
            for (kind, b) in pose.parts.iter_mut() {
                if kind.dependence() == Dependence::Full {
                    *b = self.hanging_swept(*kind, b, sheave_z);
                }
            }
        }
        pose
    }

    /// The first of the lift's `not_over` areas something comes within
    /// `within_m` of at `c`, and what: what hangs from the crane (the load's
    /// footprint, the plan outline of its box, which its rigging's is too;
    /// the hook block's; the hoist rope's; each grown by how far it may hang
    /// off where `free`, [`Self::hanging_swept`]: not in a lift-off or
    /// set-down, nor resting at the pick or set), within `within_m` and its fall zone
    /// ([`Self::fall_zone_m`]: what falls from it lands there), against
    /// every area; then,
    /// against the areas the crane may not be over either (`crane_too`),
    /// the plan outline of each other part that turns with the swing, in
    /// the order of [`CraneSetup::part_kinds`]. The carrier, its outriggers
    /// and a tower's mast stand where the lift file puts them; they are not
    /// looked at.
    pub fn not_over_near(&self, c: &Config, within_m: f64, free: bool) -> Option<(PartKind, &NotOver)> {
        if self.not_over.is_empty() {
            return None;
        }
        // A part's outline is drawn only for an area its plan extent comes
        // near (the planner asks this at every configuration it checks);
        // the exact test repeats the bounds' test, so the first, a
        // nanometre wider, passes by nothing it would find.
        let near = |part: &crate::obb::Obb, crane_too_only: bool, within_m: f64| {
            let extent = part.plan_extent();
            let mut footprint = None;
            self.not_over.iter().filter(|a| a.crane_too || !crane_too_only).find(|a| {
                let Some(area) = crate::obb::plan_bounds(&a.corners_m) else { return false };
                if crate::obb::bounds_apart(extent, area, within_m + 1e-9) {
                    return false;
                }
                crate::obb::footprint_near_area(
                    footprint.get_or_insert_with(|| part.footprint()),
                    &a.corners_m,
                    within_m,
                )
            })
        };
        const HANGING: [PartKind; 3] = [PartKind::Load, PartKind::HookBlock, PartKind::Rope];
        let sheave_z = if free && self.hangs_swept() { Some(self.crane.sheave(c).z) } else { None };
        let hanging = HANGING.iter().find_map(|&kind| {
            let part = self.crane.part(kind, c, &self.load)?;
            let part = sheave_z.map_or(part, |z| self.hanging_swept(kind, &part, z));
            near(&part, false, within_m + self.fall_zone_m).map(|a| (kind, a))
        });
        // Areas out of the crane's reach are passed by before its parts are
        // placed (the planner asks this at every configuration it checks).
        let o = self.crane.slew_center();
        let reach_m = self.crane.swinging_reach_m() + within_m;
        let in_reach = |a: &NotOver| {
            crate::obb::plan_bounds(&a.corners_m).is_some_and(|(lo, hi)| {
                let d = |k: usize, p: f64| (lo[k] - p).max(p - hi[k]).max(0.0);
                d(0, o.x).hypot(d(1, o.y)) <= reach_m
            })
        };
        if hanging.is_some() || !self.not_over.iter().any(|a| a.crane_too && in_reach(a)) {
            return hanging;
        }
        self.crane
            .part_kinds()
            .iter()
            .filter(|k| k.dependence() != Dependence::Fixed && !HANGING.contains(k) && **k != PartKind::Rigging)
            .find_map(|&kind| {
                let part = self.crane.part(kind, c, &self.load)?;
                near(&part, true, within_m).map(|a| (kind, a))
            })
    }

    /// Capacity after the configured reduction.
    pub fn effective_capacity_kg(&self, chart_kg: f64) -> f64 {
        chart_kg * (1.0 - self.capacity_reduction_pct / 100.0)
    }

    /// Utilisation in percent of the reduced chart capacity.
    pub fn utilisation_pct(&self, chart_kg: f64) -> f64 {
        let cap = self.effective_capacity_kg(chart_kg);
        if cap <= 0.0 { f64::INFINITY } else { 100.0 * self.gross_kg() / cap }
    }

    /// Where the planned path starts: lifted `liftoff_m` clear of the pick
    /// support, or where the load hangs when the lift resumes part way.
    pub fn start(&self) -> Config {
        match self.resume_from {
            Some((c, _)) => c,
            None => Config { hoist_m: self.pick.hoist_m - self.liftoff_m, ..self.pick },
        }
    }

    /// Whether the lift resumes part way through ([`LiftSpec::resume_from`]):
    /// its path starts with the load hanging, not with the lift-off.
    pub fn resumes(&self) -> bool {
        self.resume_from.is_some()
    }

    /// The configuration `liftoff_m` above the set position.
    pub fn goal(&self) -> Config {
        Config { hoist_m: self.set.hoist_m - self.liftoff_m, ..self.set }
    }
}

/// The longest side of a load's box liftplan takes (m): more is a length
/// given in millimetres, not a load.
pub const MAX_LOAD_SIDE_M: f64 = 150.0;
/// The tallest rigging (m).
pub const MAX_RIGGING_HEIGHT_M: f64 = 100.0;
/// The largest clearance or lift-off (m).
pub const MAX_CLEARANCE_M: f64 = 20.0;
/// The largest radius allowance liftplan takes (m): a boom bending more
/// than this under its load is beyond what a chart read farther out stands
/// for.
pub const MAX_RADIUS_ALLOWANCE_M: f64 = 10.0;
/// The widest fall zone round the ground under the load (m).
pub const MAX_FALL_ZONE_M: f64 = 30.0;

/// The most characters a lift's id may have (ASCII, so bytes too).
pub const MAX_LIFT_ID_CHARS: usize = 100;

/// The most characters of a name a lift gives (its load's), as of an
/// obstacle's ([`crate::obstacle`]) and an area's ([`MAX_NOT_OVER_NAME`]).
pub const MAX_NAME_CHARS: usize = 100;

/// The most characters of a lift's description.
pub const MAX_DESCRIPTION_CHARS: usize = 1000;

impl LiftSpec {
    /// Checks the request against the crane model and solves pick and set.
    pub fn resolve(&self, model: CraneModel) -> Result<LiftTask, String> {
        let id = &self.id;
        if id.is_empty() || !id.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') {
            return Err(format!("lift id '{id}' must be letters, digits, '-' or '_' (it names output files)"));
        }
        // Said on every page of its plan, and in what other lifts' plans
        // come close to ("load of lift ..."), as obstacles' names are.
        if id.len() > MAX_LIFT_ID_CHARS {
            return Err(format!(
                "lift id '{}...' is longer than {MAX_LIFT_ID_CHARS} characters ({}): give it a shorter one",
                &id[..40],
                id.len()
            ));
        }
        // Words on the plan's pages, bounded as obstacles' and areas' names
        // are: a load named in thousands of characters ran the cover off
        // its page.
        let named =
            [("load.name", &self.load.name, MAX_NAME_CHARS), ("description", &self.description, MAX_DESCRIPTION_CHARS)];
        for (key, text, max) in named {
            let chars = text.chars().count();
            if chars > max {
                let start: String = text.chars().take(40).collect();
                return Err(format!(
                    "lift '{id}': {key} '{start}...' is longer than {max} characters ({chars}): shorten it"
                ));
            }
        }
        let pos = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!("lift '{id}': {name} must be positive, found {v}"))
            }
        };
        let nonneg = |name: &str, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(format!("lift '{id}': {name} must be zero or positive, found {v}"))
            }
        };
        // Lengths are in metres: one given in millimetres (a load 8000 m
        // long) read as "the load would need -2967.92 m of rope".
        let metres = |name: &str, v: f64, max_m: f64| {
            if v <= max_m {
                Ok(())
            } else {
                Err(format!(
                    "lift '{id}': {name} = {v} m is more than {max_m} m, beyond any lift liftplan plans: lengths are in metres (was it given in millimetres?)"
                ))
            }
        };
        pos("load.mass_t", self.load.mass_t)?;
        for (i, s) in self.load.size_m.iter().enumerate() {
            pos(&format!("load.size_m[{i}]"), *s)?;
            metres(&format!("load.size_m[{i}]"), *s, MAX_LOAD_SIDE_M)?;
        }
        for (i, c) in self.load.cog_m.iter().enumerate() {
            if !(c.abs() <= self.load.size_m[i] / 2.0) {
                return Err(format!("lift '{id}': load.cog_m[{i}] = {c} lies outside the load box"));
            }
        }
        nonneg("load.cog_tolerance_m", self.load.cog_tolerance_m)?;
        for (i, c) in self.load.cog_m[..2].iter().enumerate() {
            let tol = self.load.cog_tolerance_m;
            if !(c.abs() + tol <= self.load.size_m[i] / 2.0) {
                return Err(format!(
                    "lift '{id}': load.cog_m[{i}] = {c} give or take load.cog_tolerance_m = {tol} m reaches outside the load box ({} m along its {}): a centre of gravity lies within the load",
                    self.load.size_m[i],
                    ["x", "y"][i]
                ));
            }
        }
        nonneg("load.cog_tolerance_z_m", self.load.cog_tolerance_z_m)?;
        let (cz, tz) = (self.load.cog_m[2], self.load.cog_tolerance_z_m);
        if !(cz.abs() + tz <= self.load.size_m[2] / 2.0) {
            return Err(format!(
                "lift '{id}': load.cog_m[2] = {cz} give or take load.cog_tolerance_z_m = {tz} m reaches outside the load box ({} m high): a centre of gravity lies within the load",
                self.load.size_m[2]
            ));
        }
        nonneg("rigging.mass_t", self.rigging.mass_t)?;
        nonneg("rigging.height_m", self.rigging.height_m)?;
        nonneg("crane.deductions_t", self.crane.deductions_t)?;
        if let Some(n) = self.crane.falls {
            if !(1..=crate::reeving::MAX_FALLS).contains(&n) {
                return Err(format!("lift '{id}': crane.falls must be 1 to {}, found {n}", crate::reeving::MAX_FALLS));
            }
            if let Some(most) = model.hook.max_falls.filter(|most| n > *most) {
                return Err(format!(
                    "lift '{id}': crane.falls = {n} is more than the hook block's sheaves take (hook.max_falls = {most} in the crane file)"
                ));
            }
        }
        metres("rigging.height_m", self.rigging.height_m, MAX_RIGGING_HEIGHT_M)?;
        let r = &self.rigging;
        let slings = match (r.leg_wll_t, r.legs, &r.lift_points_m) {
            (None, _, _) if r.spreader.is_some() => {
                return Err(format!(
                    "lift '{id}': rigging gives a spreader but not the working load limit of the legs hanging from it: give rigging leg_wll_t (t, each leg's) with legs = 2 (a beam) or 4 (a frame), or their lift_points_m"
                ));
            }
            (None, _, _)
                if r.hitch != Hitch::Straight
                    || r.shackle_wll_t.is_some()
                    || r.lift_point_wll_t.is_some()
                    || r.pin_axes.is_some() =>
            {
                return Err(format!(
                    "lift '{id}': rigging gives the legs' hitch, their shackles or their lift points but not the legs' working load limit: give rigging leg_wll_t (t, each leg's, straight pull) with legs or lift_points_m to have them checked"
                ));
            }
            (None, None, None) => None,
            (None, _, _) => {
                return Err(format!(
                    "lift '{id}': rigging gives its sling legs (legs or lift_points_m) but not their working load limit: give rigging leg_wll_t (t, each leg's, straight pull) to have them checked"
                ));
            }
            (Some(wll_t), legs, points) => {
                pos("rigging.leg_wll_t", wll_t)?;
                let (lift_points_m, points_given) = match (legs, points) {
                    (_, Some(p)) if p.is_empty() || p.len() > 4 => {
                        return Err(format!(
                            "lift '{id}': rigging lift_points_m gives {} points: give one to four, one per sling leg",
                            p.len()
                        ));
                    }
                    (Some(n), Some(p)) if n != p.len() => {
                        return Err(format!(
                            "lift '{id}': rigging legs = {n} but lift_points_m gives {} points: give one point per leg",
                            p.len()
                        ));
                    }
                    (_, Some(p)) => {
                        for (k, q) in p.iter().enumerate() {
                            for (i, v) in q.iter().enumerate() {
                                if !v.is_finite() {
                                    return Err(format!(
                                        "lift '{id}': rigging lift_points_m[{k}][{i}] must be a number, found {v}"
                                    ));
                                }
                                metres(
                                    &format!("rigging lift_points_m[{k}][{i}] (its size)"),
                                    v.abs(),
                                    MAX_LOAD_SIDE_M,
                                )?;
                            }
                        }
                        (p.clone(), true)
                    }
                    (Some(n), None) => match crate::slings::default_points(n, self.load.size_m) {
                        Some(p) => (p, false),
                        None => {
                            return Err(format!(
                                "lift '{id}': rigging legs = {n}: liftplan places 1, 2 or 4 legs (the top's centre, the middles of its short edges, its corners); give another arrangement's points as lift_points_m"
                            ));
                        }
                    },
                    (None, None) => {
                        return Err(format!(
                            "lift '{id}': rigging leg_wll_t is given but not the legs: give rigging legs (1, 2 or 4) or lift_points_m"
                        ));
                    }
                };
                let spreader = match &r.spreader {
                    None => None,
                    Some(b) => {
                        pos("rigging.spreader.length_m", b.length_m)?;
                        metres("rigging.spreader.length_m", b.length_m, MAX_LOAD_SIDE_M)?;
                        nonneg("rigging.spreader.below_hook_m", b.below_hook_m)?;
                        metres("rigging.spreader.below_hook_m", b.below_hook_m, MAX_RIGGING_HEIGHT_M)?;
                        pos("rigging.spreader.wll_t", b.wll_t)?;
                        nonneg("rigging.spreader.mass_t", b.mass_t)?;
                        if b.mass_t > r.mass_t + 1e-9 {
                            return Err(format!(
                                "lift '{id}': rigging.spreader.mass_t ({} t) is more than rigging.mass_t ({} t), which must include it (the chart carries the load and all its rigging)",
                                b.mass_t, r.mass_t
                            ));
                        }
                        if let Some(t) = b.top_leg_wll_t {
                            pos("rigging.spreader.top_leg_wll_t", t)?;
                        }
                        if let Some(w) = b.width_m {
                            pos("rigging.spreader.width_m", w)?;
                            metres("rigging.spreader.width_m", w, MAX_LOAD_SIDE_M)?;
                        }
                        let top_shackles = match (b.top_shackle_wll_t, &b.top_pin_axes) {
                            (None, None) => None,
                            (None, Some(_)) => {
                                return Err(format!(
                                    "lift '{id}': rigging.spreader.top_pin_axes gives the directions of the top shackles' pins but not the shackles' working load limit: give rigging.spreader.top_shackle_wll_t (t, in line) for them to be checked for side loading"
                                ));
                            }
                            (Some(_), _) if b.top_leg_wll_t.is_none() => {
                                return Err(format!(
                                    "lift '{id}': rigging.spreader.top_shackle_wll_t gives the shackles of the spreader's top legs, but it has none (no top_leg_wll_t: a lifting beam or frame hung from the hook by its lug): give top_leg_wll_t for a spreader hung by top legs, or leave top_shackle_wll_t out"
                                ));
                            }
                            (Some(t), axes) => {
                                pos("rigging.spreader.top_shackle_wll_t", t)?;
                                let pin_axes = match axes {
                                    None => None,
                                    Some(axes) if axes.len() != lift_points_m.len() => {
                                        return Err(format!(
                                            "lift '{id}': rigging.spreader.top_pin_axes gives {} directions for {} top legs: give one per top leg, in the order of the lift points they stand over",
                                            axes.len(),
                                            lift_points_m.len()
                                        ));
                                    }
                                    Some(axes) => {
                                        Some(unit_directions(id, "rigging.spreader.top_pin_axes", axes, "top leg")?)
                                    }
                                };
                                Some(crate::slings::TopShackles { wll_kg: t * KG_PER_TONNE, pin_axes })
                            }
                        };
                        Some(crate::slings::Spreader {
                            length_m: b.length_m,
                            below_hook_m: b.below_hook_m,
                            wll_kg: b.wll_t * KG_PER_TONNE,
                            mass_kg: b.mass_t * KG_PER_TONNE,
                            top_leg_wll_kg: b.top_leg_wll_t.map(|t| t * KG_PER_TONNE),
                            width_m: b.width_m,
                            top_shackles,
                        })
                    }
                };
                if let Some(t) = r.shackle_wll_t {
                    pos("rigging.shackle_wll_t", t)?;
                }
                if let Some(t) = r.lift_point_wll_t {
                    pos("rigging.lift_point_wll_t", t)?;
                }
                let pin_axes = match &r.pin_axes {
                    None => None,
                    Some(_) if r.shackle_wll_t.is_none() => {
                        return Err(format!(
                            "lift '{id}': rigging pin_axes gives the directions of the shackles' pins but not the shackles' working load limit: give rigging shackle_wll_t (t, in line) for the shackles to be checked for side loading"
                        ));
                    }
                    Some(_) if r.hitch == Hitch::Choked => {
                        return Err(format!(
                            "lift '{id}': rigging pin_axes gives the directions of the shackles' pins at the lift points, but the legs are choked round the load (hitch = \"choked\"), not shackled to lugs: leave pin_axes out"
                        ));
                    }
                    Some(axes) if axes.len() != lift_points_m.len() => {
                        return Err(format!(
                            "lift '{id}': rigging pin_axes gives {} directions for {} lift points: give one per lift point, in their order",
                            axes.len(),
                            lift_points_m.len()
                        ));
                    }
                    Some(axes) => Some(unit_directions(id, "rigging pin_axes", axes, "lift point")?),
                };
                Some(crate::slings::Slings {
                    lift_points_m,
                    points_given,
                    ratings: crate::slings::Ratings {
                        leg_wll_kg: wll_t * KG_PER_TONNE,
                        choked: r.hitch == Hitch::Choked,
                        shackle_wll_kg: r.shackle_wll_t.map(|t| t * KG_PER_TONNE),
                        lift_point_wll_kg: r.lift_point_wll_t.map(|t| t * KG_PER_TONNE),
                    },
                    spreader,
                    pin_axes,
                })
            }
        };
        pos("clearance_m", self.clearance_m)?;
        metres("clearance_m", self.clearance_m, MAX_CLEARANCE_M)?;
        nonneg("liftoff_m", self.liftoff_m)?;
        metres("liftoff_m", self.liftoff_m, MAX_CLEARANCE_M)?;
        nonneg("radius_allowance_m", self.radius_allowance_m)?;
        metres("radius_allowance_m", self.radius_allowance_m, MAX_RADIUS_ALLOWANCE_M)?;
        nonneg("fall_zone_m", self.fall_zone_m)?;
        if self.fall_zone_m > MAX_FALL_ZONE_M {
            return Err(format!(
                "lift '{id}': fall_zone_m = {} m: liftplan draws a fall zone of up to {MAX_FALL_ZONE_M} m round the ground under the load (keep a wider one by hand)",
                self.fall_zone_m
            ));
        }
        if !(0.0..100.0).contains(&self.capacity_reduction_pct) {
            return Err(format!(
                "lift '{id}': capacity_reduction_pct must be in 0..100, found {}",
                self.capacity_reduction_pct
            ));
        }
        if !(self.critical_pct > 0.0 && self.critical_pct <= 100.0) {
            return Err(format!("lift '{id}': critical_pct must be in (0, 100], found {}", self.critical_pct));
        }
        let boom = match (&model.kind, self.crane.boom_m) {
            (crate::crane::CraneKind::Luffing(_), Some(b)) => b,
            (crate::crane::CraneKind::Luffing(_), None) => {
                return Err(format!("lift '{id}': crane.boom_m is required for a luffing crane"));
            }
            (crate::crane::CraneKind::Tower(_), _) => 0.0,
        };
        let placement = Placement {
            x_m: self.crane.position_m[0],
            y_m: self.crane.position_m[1],
            z_m: self.crane.ground_z_m,
            heading_rad: self.crane.heading_deg.to_radians(),
            boom_length_m: boom,
        };
        // The falls take rope: where the rope lets the hook down less than
        // its travel, that is the longest rope of this lift's crane. It
        // runs along the boom, or a tower crane's jib.
        let run_m = match &model.kind {
            crate::crane::CraneKind::Tower(t) => t.jib.length_m,
            crate::crane::CraneKind::Luffing(_) => boom,
        };
        let rope_reach = match (model.hook.rope_m, model.hook.rope_lead_m, self.crane.falls) {
            (Some(rope_m), Some(lead_m), Some(falls)) => Some(crate::reeving::RopeReach {
                rope_m,
                lead_m,
                boom_m: run_m,
                falls,
                reach_m: crate::reeving::rope_reach_m(rope_m, lead_m, run_m, falls),
                travel_m: model.hook.max_rope_m,
                trolley: model.is_tower(),
            }),
            _ => None,
        };
        let mut model = model;
        let mut longest_from = crate::reeving::LongestRope::Travel;
        if let Some(r) = rope_reach.as_ref().filter(|r| r.reach_m < r.travel_m) {
            if !(r.reach_m > model.hook.min_rope_m) {
                return Err(format!(
                    "lift '{id}': {}, not more than the {:.2} m the hook block keeps below it (hook.min_rope_m): reeve fewer falls (crane falls) or rig a longer rope",
                    r.reach_said(),
                    model.hook.min_rope_m
                ));
            }
            model.hook.max_rope_m = r.reach_m;
            longest_from = crate::reeving::LongestRope::Reach;
        }
        let below = crate::reeving::hangs_below(model.is_tower());
        if let Some(m) = self.crane.longest_rope_m {
            if !(m.is_finite() && m > model.hook.min_rope_m) {
                return Err(format!(
                    "lift '{id}': crane.longest_rope_m must be more than the {:.2} m of rope the hook block keeps {below} (hook.min_rope_m), found {m}",
                    model.hook.min_rope_m
                ));
            }
            if m > model.hook.max_rope_m {
                let why = match (longest_from, &rope_reach) {
                    (crate::reeving::LongestRope::Reach, Some(r)) => r.reach_said(),
                    _ => format!("the hook's travel is {:.2} m (hook.max_rope_m)", model.hook.max_rope_m),
                };
                return Err(format!(
                    "lift '{id}': crane.longest_rope_m {m:.2} m is more rope than the hook may hang on: {why}"
                ));
            }
            model.hook.max_rope_m = m;
            longest_from = crate::reeving::LongestRope::Lift;
        }
        let counted = crate::reeving::falls_counted(self.crane.falls, model.hook.max_falls);
        let rope_weight = match (model.hook.rope_kg_per_m, counted) {
            (None, _) => None,
            (Some(w), Some((falls, given))) => Some(crate::reeving::RopeWeight {
                trolley: model.is_tower(),
                ..crate::reeving::RopeWeight::new(w, falls, given, model.hook.max_rope_m, longest_from)
            }),
            (Some(_), None) => {
                return Err(format!(
                    "lift '{id}': the crane file weighs its hoist rope (hook.rope_kg_per_m), but the lift gives no falls (crane falls) and the file no most falls (hook.max_falls) to count it on: give crane falls"
                ));
            }
        };
        let crane = CraneSetup::new(model, placement).map_err(|e| format!("lift '{id}': {e}"))?;
        // A pick or set beyond the rope's reach or the lift's longest rope:
        // say why the rope is short.
        let rope_said = |e: String| match (longest_from, rope_reach.as_ref()) {
            (crate::reeving::LongestRope::Reach, Some(r)) => format!(
                "{e} (on {} falls the hoist rope lets the hook hang at most {:.2} m {below}, hook.rope_m: reeve fewer falls if the load allows)",
                r.falls, r.reach_m
            ),
            (crate::reeving::LongestRope::Lift, _) => format!(
                "{e} (the lift is planned with at most {:.2} m of rope {below}, crane.longest_rope_m)",
                crane.model.hook.max_rope_m
            ),
            _ => e,
        };
        let load =
            LoadShape { size_m: self.load.size_m, cog_m: self.load.cog_m, rigging_height_m: self.rigging.height_m };
        let solve = |which: &str, p: &PoseSpec| -> Result<(Config, LoadPose), String> {
            let given = [
                ("x_m", p.x_m),
                ("y_m", p.y_m),
                ("z_m", p.z_m),
                ("swing_deg", p.swing_deg),
                ("luff_deg", p.luff_deg),
                ("trolley_m", p.trolley_m),
                ("hoist_m", p.hoist_m),
                ("yaw_deg", Some(p.yaw_deg)),
            ];
            if let Some((key, v)) = given.iter().find(|(_, v)| v.is_some_and(|v| !v.is_finite())) {
                return Err(format!(
                    "lift '{id}': {which}.{key} must be a finite number, found {}",
                    v.unwrap_or_default()
                ));
            }
            let yaw = p.yaw_deg.to_radians();
            match (p.x_m, p.y_m, p.z_m, p.swing_deg, p.hoist_m) {
                (Some(x), Some(y), Some(z), None, None) if p.luff_deg.is_none() && p.trolley_m.is_none() => {
                    let pose = LoadPose { x_m: x, y_m: y, z_m: z, yaw_rad: yaw };
                    let c = crane
                        .inverse(&pose, &load)
                        .map_err(|e| format!("lift '{id}': {which} position cannot be reached: {e}"))?;
                    Ok((c, pose))
                }
                (None, None, None, Some(sw), Some(h)) => {
                    let radial = match (&crane.model.kind, p.luff_deg, p.trolley_m) {
                        (crate::crane::CraneKind::Luffing(_), Some(l), None) => l.to_radians(),
                        (crate::crane::CraneKind::Tower(_), None, Some(t)) => t,
                        (crate::crane::CraneKind::Luffing(_), _, _) => {
                            return Err(format!(
                                "lift '{id}': {which} needs luff_deg (and no trolley_m) for a luffing crane"
                            ));
                        }
                        (crate::crane::CraneKind::Tower(_), _, _) => {
                            return Err(format!(
                                "lift '{id}': {which} needs trolley_m (and no luff_deg) for a tower crane"
                            ));
                        }
                    };
                    let c = Config { swing_rad: sw.to_radians(), radial, hoist_m: h, load_yaw_rad: yaw };
                    if !c.to_array().iter().all(|v| v.is_finite()) {
                        return Err(format!("lift '{id}': {which} has a non-finite value"));
                    }
                    Ok((c, crane.load_pose(&c, &load)))
                }
                _ => Err(format!(
                    "lift '{id}': {which} must give either a load pose (x_m, y_m, z_m, yaw_deg) or a configuration (swing_deg, luff_deg or trolley_m, hoist_m, yaw_deg), not a mix"
                )),
            }
        };
        let (mut pick, pick_pose) = solve("pick", &self.pick).map_err(rope_said)?;
        let (mut set, set_pose) = solve("set", &self.set).map_err(rope_said)?;
        within_reach(id, &crane, self.liftoff_m, &pick, &set).map_err(rope_said)?;
        let mut resume_from = match &self.resume_from {
            Some(p) => {
                let (c, pose) = solve("resume_from", p).map_err(rope_said)?;
                let lim = crane.limits();
                if !(lim.radial.0 - 1e-9..=lim.radial.1 + 1e-9).contains(&c.radial)
                    || !(lim.hoist_m.0 - 1e-9..=lim.hoist_m.1 + 1e-9).contains(&c.hoist_m)
                {
                    return Err(format!(
                        "lift '{id}': resume_from is outside the crane's {} range or its rope's ({:.2}..{:.2} m): give where the load hangs now as the crane shows it",
                        crane.model.words().radial_axis,
                        lim.hoist_m.0,
                        lim.hoist_m.1
                    ));
                }
                Some((c, pose))
            }
            None => None,
        };
        let resumes_plan = match &self.resumes_plan {
            None => None,
            Some(_) if resume_from.is_none() => {
                return Err(format!(
                    "lift '{id}': resumes_plan names the plan a lift resumed part way continues; give resume_from too (where the load hangs now: `liftplan resume` prints both), or leave resumes_plan out"
                ));
            }
            Some(r) => {
                let revision = r.revision.trim().to_ascii_lowercase();
                if revision.len() != 8 || !revision.bytes().all(|b| b.is_ascii_hexdigit()) || r.after_step == 0 {
                    return Err(format!(
                        "lift '{id}': resumes_plan = {{ revision = {:?}, after_step = {} }}: the revision is the 8 hex digits after \"plan\" on the foot of each page of that plan's PDF (such as 3f9a2c1b), and after_step the last of its steps done (1 or more)",
                        r.revision, r.after_step
                    ));
                }
                Some(ResumesPlan { revision, after_step: r.after_step })
            }
        };
        let swing_range_rad = match self.swing_range_deg {
            Some([a_deg, b_deg]) if a_deg < b_deg && b_deg - a_deg <= 360.0 && a_deg >= -360.0 && b_deg <= 360.0 => {
                let range = (a_deg.to_radians(), b_deg.to_radians());
                let shown = format!("[{a_deg}, {b_deg}]");
                into_swing_range(id, range, &shown, &mut pick, &mut set)?;
                if let Some((c, _)) = resume_from.as_mut() {
                    c.swing_rad = crate::units::swing_into_range(c.swing_rad, range.0, range.1).ok_or_else(|| {
                        format!(
                            "lift '{id}': resume_from, at swing {:.1}° from the crane's heading, is outside swing_range_deg {shown}",
                            c.swing_rad.to_degrees()
                        )
                    })?;
                }
                Some(range)
            }
            Some(_) => {
                return Err(format!(
                    "lift '{id}': swing_range_deg must be [min, max] with min < max, within -360..360 and at most a full turn (leave it out for a crane free to slew)"
                ));
            }
            None => None,
        };
        let masses = match &crane.model.kind {
            crate::crane::CraneKind::Luffing(l) => l.masses,
            crate::crane::CraneKind::Tower(_) => None,
        };
        if masses.is_none() && (self.crane.counterweight_t.is_some() || self.ground.is_some()) {
            let key = if self.ground.is_some() { "ground" } else { "crane counterweight_t" };
            return Err(format!(
                "lift '{id}': {key} is for the outrigger loads, and the crane model {} gives no [masses] to work them out from{}",
                crane.model.name,
                if crane.model.is_tower() { " (a tower crane has no outriggers)" } else { "" }
            ));
        }
        if let Some(w) = &self.wind {
            if crane.model.is_tower() {
                return Err(format!(
                    "lift '{id}': wind is worked out as a mobile crane's chart gives it (EN 13000: its speed for up to 1.2 m² per tonne), and {} is a tower crane: its manufacturer's in-service wind rules apply",
                    crane.model.name
                ));
            }
            if let Some(problem) = w.problem() {
                return Err(format!("lift '{id}': {problem}"));
            }
        }
        if let Some(t) = self.crane.counterweight_t
            && !(t.is_finite() && (0.0..=10_000.0).contains(&t))
        {
            return Err(format!(
                "lift '{id}': crane counterweight_t must be a mass in tonnes from 0 to 10000, found {t}"
            ));
        }
        if let Some(g) = &self.ground {
            if !g.mat_m.iter().all(|v| v.is_finite() && *v > 0.0 && *v <= 100.0) {
                return Err(format!(
                    "lift '{id}': ground mat_m must be a mat's length and width, each above 0 and at most 100 m, found {:?}",
                    g.mat_m
                ));
            }
            if let Some(p) = g.allowable_kpa
                && !(p.is_finite() && p > 0.0)
            {
                return Err(format!("lift '{id}': ground allowable_kpa must be a positive pressure in kPa, found {p}"));
            }
        }
        if self.not_over.len() > MAX_NOT_OVER {
            return Err(format!("lift '{id}': at most {MAX_NOT_OVER} not_over areas, found {}", self.not_over.len()));
        }
        if let Some(why) = self.not_over.iter().enumerate().find_map(|(k, a)| a.problem(k)) {
            return Err(format!("lift '{id}': {why}"));
        }
        if self.crane_stands_in.len() > MAX_NOT_OVER {
            return Err(format!(
                "lift '{id}': at most {MAX_NOT_OVER} crane_stands_in areas, found {}",
                self.crane_stands_in.len()
            ));
        }
        if let Some(why) = self.crane_stands_in.iter().enumerate().find_map(|(k, a)| a.problem(k)) {
            return Err(format!("lift '{id}': {why}"));
        }
        let task = LiftTask {
            id: id.clone(),
            description: self.description.clone(),
            crane,
            chart_config: self.crane.chart_config.clone(),
            load_name: self.load.name.clone(),
            load,
            cog_tolerance_m: self.load.cog_tolerance_m,
            cog_tolerance_z_m: self.load.cog_tolerance_z_m,
            load_mass_kg: self.load.mass_t * KG_PER_TONNE,
            rigging_mass_kg: self.rigging.mass_t * KG_PER_TONNE,
            slings,
            falls: self.crane.falls,
            rope_reach,
            rope_weight,
            longest_rope_m: self.crane.longest_rope_m,
            deductions_kg: self.crane.deductions_t * KG_PER_TONNE,
            pick,
            set,
            pick_pose,
            set_pose,
            resume_from,
            resumes_plan,
            clearance_m: self.clearance_m,
            liftoff_m: self.liftoff_m,
            capacity_reduction_pct: self.capacity_reduction_pct,
            radius_allowance_m: self.radius_allowance_m,
            fall_zone_m: self.fall_zone_m,
            critical_pct: self.critical_pct,
            swing_range_rad,
            by_configuration: [self.pick.swing_deg.is_some(), self.set.swing_deg.is_some()],
            counterweight_kg: self.crane.counterweight_t.map(|t| t * KG_PER_TONNE),
            ground: self.ground,
            wind: self.wind,
            not_over: self.not_over.clone(),
            crane_stands_in: self.crane_stands_in.clone(),
            chart_sheet_counterweight: None,
            gust_swing_per_m: 0.0,
        };
        ends_off_not_over(&task)?;
        if let Some(why) = task.stands_outside_its_areas() {
            return Err(format!("lift '{id}': {why}: set it up within one, or give the area it stands in"));
        }
        // A chart speed the lift gives is known now; one its chart's sheet
        // states, once the chart is read (the plan stage sets it then).
        let mut task = task;
        if self.wind.is_some_and(|w| w.chart_ms.is_some()) {
            task.plan_for_wind(&[])?;
        }
        Ok(task)
    }
}

/// The pick and the set within the crane's radial range and its rope's,
/// the lift-off's rope included.
/// `axes` (directions of shackles' pins, `key` in lift `id`'s file, one per
/// `what`: "lift point", "top leg") made unit vectors, each scaled first so
/// that no square overflows; refused where one is not a direction.
fn unit_directions(id: &str, key: &str, axes: &[[f64; 3]], what: &str) -> Result<Vec<[f64; 3]>, String> {
    let mut unit = Vec::with_capacity(axes.len());
    for (k, a) in axes.iter().enumerate() {
        let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !a.iter().all(|v| v.is_finite()) || scale == 0.0 {
            return Err(format!(
                "lift '{id}': {key}[{k}] must be a direction (three numbers, not all zero: the axis of {what} {}'s lug's hole, in the load's frame), found {a:?}",
                k + 1
            ));
        }
        let s = a.map(|v| v / scale);
        let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
        unit.push(s.map(|v| v / n));
    }
    Ok(unit)
}

fn within_reach(id: &str, crane: &CraneSetup, liftoff_m: f64, pick: &Config, set: &Config) -> Result<(), String> {
    let lim = crane.limits();
    for (which, c) in [("pick", pick), ("set", set)] {
        if c.radial < lim.radial.0 - 1e-9 || c.radial > lim.radial.1 + 1e-9 {
            return Err(format!(
                "lift '{id}': {which} is outside the crane's {} range",
                crane.model.words().radial_axis
            ));
        }
        if c.hoist_m - liftoff_m < lim.hoist_m.0 - 1e-9 || c.hoist_m > lim.hoist_m.1 + 1e-9 {
            return Err(format!(
                "lift '{id}': {which} needs {:.2} m of rope and lift-off needs {:.2} m less; the crane allows {:.2}..{:.2} m",
                c.hoist_m, liftoff_m, lim.hoist_m.0, lim.hoist_m.1
            ));
        }
    }
    Ok(())
}

/// The pick's and the set's swing where the permitted range `(a, b)` (rad,
/// `shown` as the lift gives it) holds them: a range across ±180° ([90,
/// 270] behind the carrier) holds a pick solved at -160° as 200°, and the
/// planner and the validator compare swing with the range as numbers.
fn into_swing_range(
    id: &str,
    (a, b): (f64, f64),
    shown: &str,
    pick: &mut Config,
    set: &mut Config,
) -> Result<(), String> {
    for (which, c) in [("pick", pick), ("set", set)] {
        let Some(inside) = crate::units::swing_into_range(c.swing_rad, a, b) else {
            return Err(format!(
                "lift '{id}': the {which}, at swing {:.1}° from the crane's heading, is outside swing_range_deg {shown}",
                c.swing_rad.to_degrees(),
            ));
        };
        c.swing_rad = inside;
    }
    Ok(())
}

impl LiftTask {
    /// This lift with its crane set up at `placement` instead, the pick and
    /// the set solved again from their load poses, as [`LiftSpec::resolve`]
    /// solves them: where else the crane could stand. Err where the crane
    /// cannot hold either there (beyond its reach, its rope, or the lift's
    /// permitted swing range), or the placement is not one for it.
    pub fn moved_to(&self, placement: Placement) -> Result<LiftTask, String> {
        let id = &self.id;
        if self.resumes() {
            return Err(format!("lift '{id}' resumes part way through (resume_from): its crane stays where it stands"));
        }
        let crane = CraneSetup::new(self.crane.model.clone(), placement).map_err(|e| format!("lift '{id}': {e}"))?;
        let solve = |which: &str, pose: &LoadPose| {
            crane.inverse(pose, &self.load).map_err(|e| format!("lift '{id}': {which} position cannot be reached: {e}"))
        };
        let (mut pick, mut set) = (solve("pick", &self.pick_pose)?, solve("set", &self.set_pose)?);
        within_reach(id, &crane, self.liftoff_m, &pick, &set)?;
        if let Some((a, b)) = self.swing_range_rad {
            let shown = format!("[{:.1}, {:.1}]", a.to_degrees(), b.to_degrees());
            into_swing_range(id, (a, b), &shown, &mut pick, &mut set)?;
        }
        let moved = LiftTask { crane, pick, set, by_configuration: [false, false], ..self.clone() };
        ends_off_not_over(&moved)?;
        if let Some(why) = moved.stands_outside_its_areas() {
            return Err(format!("lift '{id}': {why}"));
        }
        Ok(moved)
    }
}

impl LiftTask {
    /// The plan corners of what stands on the ground the crane is set up
    /// in (`crane_stands_in`): its carrier and outriggers (a tower's mast),
    /// and the pads' mats where the lift gives them (`ground.mat_m`), each
    /// as a square of its longer side, square to the carrier (it holds the
    /// mat laid either way round). The planner's test of the areas
    /// ([`Self::stands_outside_its_areas`]) and the validator's own both
    /// take them.
    pub fn standing_corners(&self) -> Vec<[f64; 2]> {
        let mut corners: Vec<[f64; 2]> = self
            .crane
            .part_kinds()
            .iter()
            .filter(|k| k.dependence() == Dependence::Fixed)
            .filter_map(|&k| self.crane.part(k, &self.pick, &self.load))
            .flat_map(|b| b.footprint())
            .collect();
        if let Some(half) = self.mat_half_m() {
            let square_to_carrier = crate::frame::rot_z(self.crane.placement.heading_rad);
            for pad in crate::outriggers::Pad::ALL {
                let Some(at) = crate::outriggers::pad_at(&self.crane, pad) else { continue };
                let centre = crate::frame::Point3::new(at[0], at[1], 0.0);
                let mat = crate::obb::Obb::new(centre, square_to_carrier, crate::frame::Vec3::new(half, half, 0.0));
                corners.extend(mat.footprint());
            }
        }
        corners
    }

    /// Half the longer side of the pads' mats (m), where the lift gives them.
    pub fn mat_half_m(&self) -> Option<f64> {
        self.ground.map(|g| g.mat_m[0].max(g.mat_m[1]) / 2.0).filter(|h| *h > 0.0)
    }

    /// Where the lift gives areas the crane may be set up in and its
    /// carrier and outriggers (or a tower's mast) do not lie within one of
    /// them (the hull of their plan outlines, clear of the area's edges),
    /// why, in words.
    pub fn stands_outside_its_areas(&self) -> Option<String> {
        if self.crane_stands_in.is_empty() {
            return None;
        }
        let footprint = crate::obb::convex_hull_2d(&self.standing_corners());
        // An area whose extent does not hold the footprint's is passed by
        // before its edges are walked (the position search asks this at
        // thousands of positions).
        // (A crane of no fixed parts has no footprint, and is within none.)
        let extent = crate::obb::plan_bounds(&footprint);
        let holds = |a: &CraneArea| {
            extent
                .zip(crate::obb::plan_bounds(&a.corners_m))
                .is_some_and(|((flo, fhi), (lo, hi))| (0..2).all(|k| lo[k] <= flo[k] && fhi[k] <= hi[k]))
                && crate::obb::footprint_within_area(&footprint, &a.corners_m)
        };
        if self.crane_stands_in.iter().any(holds) {
            return None;
        }
        let p = &self.crane.placement;
        let names: Vec<String> = self.crane_stands_in.iter().map(|a| format!("'{}'", a.name)).collect();
        Some(format!(
            "the crane set up at position_m = [{:.2}, {:.2}], heading_deg = {:.0}: its {} not within an area it may stand in (crane_stands_in: {})",
            p.x_m,
            p.y_m,
            p.heading_rad.to_degrees(),
            match (self.crane.model.is_tower(), self.mat_half_m().is_some()) {
                (true, _) => "mast is",
                (false, true) => "carrier and outriggers, with their pads' mats, are",
                (false, false) => "carrier and outriggers are",
            },
            names.join(", ")
        ))
    }
}

/// The load is lifted from and set down outside the areas it must not be
/// over, by its fall zone and the planner's margin, and the crane stands
/// and reaches there outside those it may not be over either.
fn ends_off_not_over(task: &LiftTask) -> Result<(), String> {
    for (which, c) in [("pick", &task.pick), ("set", &task.set)] {
        match task.not_over_near(c, NOT_OVER_MARGIN_M, false) {
            None => {}
            Some((part, a)) if part.dependence() == Dependence::Full => {
                let within = if task.fall_zone_m > 0.0 {
                    format!(
                        "within {:.2} m of it (its fall zone, fall_zone_m = {} m, and the planner's {NOT_OVER_MARGIN_M} m)",
                        task.fall_zone_m + NOT_OVER_MARGIN_M,
                        task.fall_zone_m
                    )
                } else {
                    format!("within {NOT_OVER_MARGIN_M} m of it")
                };
                return Err(format!(
                    "lift '{}': {} at the {which} is over not_over '{}' or {within}: a load is lifted and set down outside the areas it must not be over{}",
                    task.id,
                    over_not_over_said(part),
                    a.name,
                    if task.fall_zone_m > 0.0 { ", and what may fall from it lands outside them" } else { "" }
                ));
            }
            Some((part, a)) => {
                return Err(format!(
                    "lift '{}': {} at the {which} is over not_over '{}' (crane_too) or within {NOT_OVER_MARGIN_M} m of it: the crane is set up where it reaches the pick and the set without being over it",
                    task.id,
                    over_not_over_said(part),
                    a.name
                ));
            }
        }
    }
    Ok(())
}

/// What [`LiftTask::not_over_near`] found over an area, in words: "the
/// load", "the hook block", "the crane's boom".
pub fn over_not_over_said(part: PartKind) -> String {
    match part {
        PartKind::Load | PartKind::HookBlock | PartKind::Rope | PartKind::Rigging => format!("the {}", part.name()),
        _ => format!("the crane's {}", part.name()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPEC: &str = r#"
id = "V-101"
load = { mass_t = 12.5, size_m = [6.0, 3.0, 3.0] }
rigging = { mass_t = 0.4, height_m = 3.0 }
crane = { model = "ltm-1100", position_m = [0.0, 0.0], heading_deg = 0.0, boom_m = 40.0, chart_config = "main" }
pick = { x_m = 20.0, y_m = 5.0, z_m = 0.0, yaw_deg = 0.0 }
set = { x_m = -10.0, y_m = 18.0, z_m = 2.0, yaw_deg = 90.0 }
"#;

    fn spec() -> LiftSpec {
        toml::from_str(SPEC).unwrap()
    }

    /// A lift's id names its files and is said on its plan's pages: ASCII
    /// letters, digits, '-' and '_', at most 100 of them.
    #[test]
    fn a_lift_id_is_a_short_file_name() {
        let with_id = |id: &str| {
            let mut s = spec();
            s.id = id.into();
            s.resolve(crate::crane::builtin("ac-700").unwrap()).map(|t| t.id)
        };
        let longest = "L".repeat(MAX_LIFT_ID_CHARS);
        assert_eq!(with_id(&longest).unwrap(), longest);
        assert_eq!(
            with_id(&format!("{longest}1")).unwrap_err(),
            format!("lift id '{}...' is longer than 100 characters (101): give it a shorter one", "L".repeat(40))
        );
        assert!(with_id("V/101").unwrap_err().contains("must be letters, digits, '-' or '_'"));
        assert!(with_id("").is_err());
    }

    /// The names and words a lift gives for its plan's pages are bounded.
    #[test]
    fn a_lift_names_things_in_few_words() {
        let resolve = |s: LiftSpec| s.resolve(crate::crane::builtin("ac-700").unwrap());
        let mut s = spec();
        s.load.name = "é".repeat(MAX_NAME_CHARS);
        s.description = "d".repeat(MAX_DESCRIPTION_CHARS);
        assert!(resolve(s.clone()).is_ok());
        let mut long_name = s.clone();
        long_name.load.name.push('x');
        assert_eq!(
            resolve(long_name).unwrap_err(),
            format!("lift 'V-101': load.name '{}...' is longer than 100 characters (101): shorten it", "é".repeat(40))
        );
        let mut long_description = s;
        long_description.description.push('x');
        assert!(resolve(long_description).unwrap_err().contains("description 'dddd"));
    }

    /// The falls a lift gives are within 1 to 64 and what the crane's hook
    /// block takes; its reeving is then checked against the hook load.
    #[test]
    fn the_falls_are_checked_against_the_hook_block() {
        let with_falls = |falls: u32| {
            let mut s = spec();
            s.crane.falls = Some(falls);
            s.resolve(crate::crane::builtin("ac-700").unwrap())
        };
        assert!(with_falls(0).unwrap_err().contains("crane.falls must be 1 to 64, found 0"));
        assert!(
            with_falls(12)
                .unwrap_err()
                .contains("crane.falls = 12 is more than the hook block's sheaves take (hook.max_falls = 10")
        );
        let task = with_falls(1).unwrap();
        assert_eq!(task.falls, Some(1));
        let r = crate::reeving::Reeving::of(&task).unwrap();
        assert_eq!((r.line_pull_kg, r.max_falls), (Some(10_000.0), Some(10)));
        assert!((r.hook_load_kg - task.hook_load_kg()).abs() < 1e-9);
        // On one fall the hook load (12.5 t, 0.4 t, the 3.5 t block and
        // 110 m of rope at 3.9 kg/m) is refused, naming the falls it needs.
        assert_eq!(
            r.refused().unwrap(),
            "the hook load (16.83 t: load, rigging, hook block and 0.43 t of hoist rope) is more than 1 fall of 10.00 t each carries (10.00 t): reeve at least 2 falls (crane falls)"
        );
        assert_eq!(crate::reeving::Reeving::of(&with_falls(2).unwrap()).unwrap().refused(), None);
        // A crane file of no line pull or rating and a lift of no falls: nothing.
        assert!(
            crate::reeving::Reeving::of(&spec().resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap()).is_none()
        );
    }

    /// The falls take rope: 300 m of it, 20 m to the boom's foot and the
    /// 40 m boom leave 240 m past the head, so the hook hangs at most 60 m
    /// below it on 4 falls (the crane's longest rope for the lift), 24 m on
    /// 10 (short of the pick, refused saying why); on 1 fall the hook's
    /// 110 m of travel holds; on 10 falls of 80 m of rope, the hook cannot
    /// leave the head.
    #[test]
    fn the_falls_take_rope() {
        let on = |rope_m: f64, falls: u32| {
            let mut model = crate::crane::builtin("ac-700").unwrap();
            (model.hook.rope_m, model.hook.rope_lead_m) = (Some(rope_m), Some(20.0));
            let mut s = spec();
            s.crane.falls = Some(falls);
            s.resolve(model)
        };
        let t = on(300.0, 4).unwrap();
        assert_eq!(t.crane.limits().hoist_m.1, 60.0);
        let r = t.rope_reach.clone().unwrap();
        assert_eq!((r.reach_m, r.travel_m), (60.0, 110.0));
        assert_eq!(
            r.said(None),
            "the hoist rope's 300 m (less 20.0 m to the boom's foot and the 40.0 m boom) on 4 falls lets the hook hang 60.00 m below the boom head: the longest rope planned with (hook travel 110.00 m)"
        );
        assert!(crate::reeving::Reeving::of(&t).unwrap().said().contains(&format!("; {};", r.said(None))));
        assert!(t.pick.hoist_m > 24.0, "{}", t.pick.hoist_m);
        let e = on(300.0, 10).unwrap_err();
        assert!(e.contains("lift 'V-101': pick"), "{e}");
        assert!(
            e.ends_with("(on 10 falls the hoist rope lets the hook hang at most 24.00 m below the boom head, hook.rope_m: reeve fewer falls if the load allows)"),
            "{e}"
        );
        let one = on(300.0, 1).unwrap();
        assert_eq!(one.crane.limits().hoist_m.1, 110.0);
        assert!(one.rope_reach.unwrap().said(None).ends_with(
            "lets the hook hang 240.00 m below the boom head, more than the hook's travel (110.00 m), which holds"
        ));
        let e = on(80.0, 10).unwrap_err();
        assert!(
            e.contains("on 10 falls lets the hook hang 2.00 m below the boom head, not more than the 2.00 m the hook block keeps below it (hook.min_rope_m): reeve fewer falls (crane falls) or rig a longer rope"),
            "{e}"
        );
        // Without falls, or without the rope in the crane file: not known.
        let mut s = spec();
        s.crane.model = "ac-700".into();
        assert_eq!(s.resolve(crate::crane::builtin("ac-700").unwrap()).unwrap().rope_reach, None);
    }

    /// Where the crane file weighs its hoist rope, every fall is counted in
    /// the hook load at the longest rope the lift is planned with: the
    /// rope's reach, the hook's travel or the lift's `longest_rope_m`,
    /// which is then the crane's joint limit for the lift.
    #[test]
    fn the_hoist_rope_below_the_head_is_counted_at_the_longest_rope() {
        use crate::reeving::LongestRope;
        let on = |rope_m: Option<f64>, falls: Option<u32>, longest: Option<f64>| {
            let mut model = crate::crane::builtin("ac-700").unwrap();
            model.hook.rope_kg_per_m = Some(3.9);
            (model.hook.rope_m, model.hook.rope_lead_m) = (rope_m, rope_m.map(|_| 20.0));
            let mut s = spec();
            (s.crane.falls, s.crane.longest_rope_m) = (falls, longest);
            s.resolve(model)
        };
        let mut unweighed = crate::crane::builtin("ac-700").unwrap();
        unweighed.hook.rope_kg_per_m = None;
        let bare = spec().resolve(unweighed).unwrap();
        assert_eq!(bare.rope_weight, None);
        assert_eq!(bare.hook_load_kg(), bare.least_hanging_kg());
        // 300 m of rope on 4 falls reaches 60 m below the head: 4 x 60 m.
        let t = on(Some(300.0), Some(4), None).unwrap();
        let w = t.rope_weight.clone().unwrap();
        assert_eq!((w.falls, w.falls_given, w.longest_m, w.longest_from), (4, true, 60.0, LongestRope::Reach));
        assert!((w.kg - 4.0 * 60.0 * 3.9).abs() < 1e-9);
        assert!((t.hook_load_kg() - (bare.least_hanging_kg() + 936.0)).abs() < 1e-9);
        assert!((t.gross_kg() - (bare.gross_kg() + 936.0)).abs() < 1e-9);
        assert_eq!(t.least_hanging_kg(), bare.least_hanging_kg());
        let r = crate::reeving::Reeving::of(&t).unwrap();
        assert_eq!(r.hook_load_kg, t.hook_load_kg());
        assert!(
            r.said().starts_with("hook load 17.34 t (load, rigging, hook block and 0.94 t of hoist rope)"),
            "{}",
            r.said()
        );
        // The lift's longest rope: the hook's travel for it, and the count.
        let pick = t.pick.hoist_m;
        let short = on(Some(300.0), Some(4), Some(pick + 1.0)).unwrap();
        assert_eq!(short.crane.limits().hoist_m.1, pick + 1.0);
        let w = short.rope_weight.unwrap();
        assert_eq!((w.longest_m, w.longest_from), (pick + 1.0, LongestRope::Lift));
        assert!((w.kg - 4.0 * (pick + 1.0) * 3.9).abs() < 1e-9);
        let e = on(Some(300.0), Some(4), Some(pick - 1.0)).unwrap_err();
        assert!(e.contains("lift 'V-101': pick"), "{e}");
        assert!(
            e.ends_with(&format!(
                "(the lift is planned with at most {:.2} m of rope below the boom head, crane.longest_rope_m)",
                pick - 1.0
            )),
            "{e}"
        );
        let e = on(Some(300.0), Some(4), Some(61.0)).unwrap_err();
        assert!(e.ends_with("crane.longest_rope_m 61.00 m is more rope than the hook may hang on: the hoist rope's 300 m (less 20.0 m to the boom's foot and the 40.0 m boom) on 4 falls lets the hook hang 60.00 m below the boom head"), "{e}");
        let e = on(None, Some(4), Some(111.0)).unwrap_err();
        assert!(e.ends_with("crane.longest_rope_m 111.00 m is more rope than the hook may hang on: the hook's travel is 110.00 m (hook.max_rope_m)"), "{e}");
        for bad in [2.0, f64::NAN, -5.0] {
            let e = on(None, Some(4), Some(bad)).unwrap_err();
            assert!(e.contains("crane.longest_rope_m must be more than the 2.00 m of rope the hook block keeps below the boom head (hook.min_rope_m)"), "{e}");
        }
        // No falls given: counted on the most the block takes, over the
        // hook's travel; without those either, refused.
        let w = on(None, None, None).unwrap().rope_weight.unwrap();
        assert_eq!((w.falls, w.falls_given, w.longest_m, w.longest_from), (10, false, 110.0, LongestRope::Travel));
        // With nothing else of the reeving to check, the row still says
        // what was counted.
        let mut quiet = crate::crane::builtin("ac-700").unwrap();
        (quiet.hook.line_pull_t, quiet.hook.rated_t) = (None, None);
        let r = crate::reeving::Reeving::of(&spec().resolve(quiet).unwrap()).expect("the rope's weight is said");
        assert!(
            r.said().contains("; the 4.29 t of hoist rope: 10 falls (the most the hook block takes"),
            "{}",
            r.said()
        );
        let mut model = crate::crane::builtin("ac-700").unwrap();
        (model.hook.rope_kg_per_m, model.hook.max_falls) = (Some(3.9), None);
        let e = spec().resolve(model).unwrap_err();
        assert!(e.ends_with("the lift gives no falls (crane falls) and the file no most falls (hook.max_falls) to count it on: give crane falls"), "{e}");
        // The wind the load may be lifted in is worked out without the rope:
        // the lighter what hangs, the less wind it takes.
        let mut windy = spec();
        windy.crane.falls = Some(4);
        windy.wind = Some(crate::wind::WindSpec { chart_ms: Some(9.8), cw: 1.2, area_m2: None, plan_for_swing: true });
        let mut model = crate::crane::builtin("ac-700").unwrap();
        model.hook.rope_kg_per_m = Some(3.9);
        let t = windy.resolve(model).unwrap();
        assert!(t.rope_weight.is_some());
        assert_eq!(t.permissible_wind(&[]).unwrap().0.hook_load_kg, t.least_hanging_kg());
        // A crane file with none of the rope's figures: the lift's longest
        // rope limits the hook all the same, and is said.
        let ltm = spec().resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap();
        assert!(crate::reeving::Reeving::of(&ltm).is_none());
        let mut s = spec();
        s.crane.longest_rope_m = Some(ltm.pick.hoist_m.max(ltm.set.hoist_m) + 1.0);
        let kept = s.resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap();
        assert_eq!(Some(kept.crane.limits().hoist_m.1), s.crane.longest_rope_m);
        let said = crate::reeving::Reeving::of(&kept).expect("the longest rope is said").said();
        assert!(
            said.ends_with(&format!(
                "; the hook kept within {:.2} m of rope below the boom head (crane longest_rope_m)",
                s.crane.longest_rope_m.unwrap()
            )),
            "{said}"
        );
        // A tower crane's rope hangs from its trolley, and is said so.
        let mut tower = crate::crane::builtin("tower-hh-60").unwrap();
        tower.hook.rope_kg_per_m = Some(1.6);
        let mut s = spec();
        (s.crane.model, s.crane.boom_m, s.crane.falls, s.crane.longest_rope_m) =
            ("tower-hh-60".into(), None, Some(2), Some(0.5));
        let e = s.clone().resolve(tower.clone()).unwrap_err();
        assert!(e.contains("of rope the hook block keeps below the trolley (hook.min_rope_m)"), "{e}");
        s.crane.longest_rope_m = None;
        let w = s.resolve(tower).unwrap().rope_weight.unwrap();
        assert!(w.trolley && w.said().contains("m below the trolley (the hook's travel"), "{}", w.said());
    }

    /// A tower crane's falls take rope too: 150 m of it, 10 m from the drum
    /// to the jib's root and the 60 m jib (out to the trolley and on to the
    /// jib's head past the falls, wherever the trolley stands) leave 80 m,
    /// so the hook hangs at most 40 m below the trolley on 2 falls, less
    /// than its 48 m of travel: the crane's longest rope for the lift; on 8
    /// falls, 10 m, short of the pick, refused saying why, below the
    /// trolley.
    #[test]
    fn a_tower_cranes_falls_take_rope_along_its_jib() {
        let on = |falls: u32| {
            let mut tower = crate::crane::builtin("tower-hh-60").unwrap();
            (tower.hook.rope_m, tower.hook.rope_lead_m) = (Some(150.0), Some(10.0));
            let mut s = spec();
            (s.crane.model, s.crane.boom_m, s.crane.falls) = ("tower-hh-60".into(), None, Some(falls));
            s.resolve(tower)
        };
        let t = on(2).unwrap();
        assert_eq!(t.crane.limits().hoist_m.1, 40.0);
        let r = t.rope_reach.clone().unwrap();
        assert_eq!((r.boom_m, r.reach_m, r.travel_m, r.trolley), (60.0, 40.0, 48.0, true));
        assert_eq!(
            r.said(None),
            "the hoist rope's 150 m (less 10.0 m to the jib's root and the 60.0 m jib) on 2 falls lets the hook hang 40.00 m below the trolley: the longest rope planned with (hook travel 48.00 m)"
        );
        assert!(crate::reeving::Reeving::of(&t).unwrap().said().contains(&r.said(None)));
        assert!(t.pick.hoist_m > 10.0 && t.set.hoist_m > 10.0, "{} {}", t.pick.hoist_m, t.set.hoist_m);
        let e = on(8).unwrap_err();
        assert!(
            e.ends_with("(on 8 falls the hoist rope lets the hook hang at most 10.00 m below the trolley, hook.rope_m: reeve fewer falls if the load allows)"),
            "{e}"
        );
        // The mobile crane's words are not a tower crane's.
        assert!(!e.contains("boom"), "{e}");
    }

    /// A centre of gravity known only so well in height: kept within the
    /// load; on trunnions 0.1 m above it, the load hangs on two legs with
    /// 0.05 m of tolerance and is refused with 0.1 m (it would turn over at
    /// the highest its centre of gravity may lie); the tilt's bound is taken
    /// there; on four legs to the hook nothing changes, and it is said.
    #[test]
    fn a_centre_of_gravity_known_only_so_well_in_height_is_checked_at_its_highest() {
        let with = |points: &str, tol: f64, tol_z: f64| {
            let mut s = spec();
            s.rigging = toml::from_str(&format!("mass_t = 0.4\nheight_m = 3.0\nleg_wll_t = 20.0\n{points}")).unwrap();
            (s.load.cog_m, s.load.cog_tolerance_m, s.load.cog_tolerance_z_m) = ([0.0, 0.0, -0.1], tol, tol_z);
            s.resolve(crate::crane::builtin("ltm-1100").unwrap())
        };
        let trunnions = "lift_points_m = [[-3.0, 0.0, 0.0], [3.0, 0.0, 0.0]]";
        let e = with(trunnions, 0.0, -0.1).unwrap_err();
        assert!(e.contains("load.cog_tolerance_z_m must be zero or positive, found -0.1"), "{e}");
        let e = with(trunnions, 0.0, 1.5).unwrap_err();
        assert!(e.contains("load.cog_m[2] = -0.1 give or take load.cog_tolerance_z_m = 1.5 m reaches outside the load box (3 m high)"), "{e}");
        let c = with(trunnions, 0.0, 0.0).unwrap().check_slings().unwrap().unwrap();
        assert_eq!(c.cog_tolerance_z_m, 0.0);
        let c = with(trunnions, 0.0, 0.05).unwrap().check_slings().unwrap().unwrap();
        assert!(c.said().ends_with("; its lift points above the centre of gravity even up to 0.05 m higher than given (load cog_tolerance_z_m)"), "{}", c.said());
        let e = with(trunnions, 0.0, 0.1).unwrap().check_slings().unwrap().unwrap_err();
        assert!(
            e.starts_with("with the load's centre of gravity up to load cog_tolerance_z_m (0.10 m) higher than given, at z 0.00 m from its box's centre: the load hangs on 2 legs from lift points as low as z 0.00 m"),
            "{e}"
        );
        // With a tolerance in plan too, the tilt's bound over the 0.05 m left:
        // atan(√2 x 0.02 / 0.05).
        let c = with(trunnions, 0.02, 0.05).unwrap().check_slings().unwrap().unwrap();
        let want = (std::f64::consts::SQRT_2 * 0.02f64).atan2(0.05).to_degrees();
        assert!((c.tilt_deg.unwrap() - want).abs() < 1e-9, "{:?} {want}", c.tilt_deg);
        assert!(
            c.said().ends_with("higher than given (load cog_tolerance_z_m), the tilt's bound taken there"),
            "{}",
            c.said()
        );
        let four = with("legs = 4", 0.0, 0.5).unwrap().check_slings().unwrap().unwrap();
        let plain = with("legs = 4", 0.0, 0.0).unwrap().check_slings().unwrap().unwrap();
        assert_eq!((four.max_leg_kg, four.max_angle_deg), (plain.max_leg_kg, plain.max_angle_deg));
        assert!(four.said().ends_with("; the centre of gravity's height, known to 0.50 m (load cog_tolerance_z_m), changes nothing of this on 4 legs"), "{}", four.said());
    }

    #[test]
    fn resolves_and_sums_gross_load() {
        let t = spec().resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap();
        assert!((t.gross_kg() - (12500.0 + 400.0 + 1100.0)).abs() < 1e-9);
        assert!((t.start().hoist_m - (t.pick.hoist_m - 0.5)).abs() < 1e-12);
        assert!((t.set_pose.yaw_rad - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!((t.utilisation_pct(14000.0) - 100.0 * 14000.0 / 14000.0).abs() < 1e-9);
    }

    /// A lift resumed part way starts where its load hangs, given as the
    /// crane's configuration or as the load's pose; one the crane cannot
    /// hold is refused naming the key, and such a lift's crane is not moved.
    #[test]
    fn a_lift_resumed_part_way_starts_where_the_load_hangs() {
        let model = || crate::crane::builtin("ltm-1100").unwrap();
        let resumed = |text: &str| {
            let mut s = spec();
            s.resume_from = Some(toml::from_str(text).unwrap());
            s.resolve(model())
        };
        let t = resumed("swing_deg = 40.0\nluff_deg = 60.0\nhoist_m = 12.0\nyaw_deg = 30.0").unwrap();
        assert!(t.resumes() && !spec().resolve(model()).unwrap().resumes());
        let want = Config {
            swing_rad: 40f64.to_radians(),
            radial: 60f64.to_radians(),
            hoist_m: 12.0,
            load_yaw_rad: 30f64.to_radians(),
        };
        assert_eq!(t.start(), want);
        let pose = t.resume_from.unwrap().1;
        assert!((pose.z_m - t.crane.load_pose(&want, &t.load).z_m).abs() < 1e-12);
        // The same place given as the load's pose.
        let by_pose =
            resumed(&format!("x_m = {}\ny_m = {}\nz_m = {}\nyaw_deg = 30.0", pose.x_m, pose.y_m, pose.z_m)).unwrap();
        let c = by_pose.start();
        assert!((c.swing_rad - want.swing_rad).abs() < 1e-6 && (c.radial - want.radial).abs() < 1e-6, "{c:?}");
        assert!((c.hoist_m - want.hoist_m).abs() < 1e-6);
        let far = resumed("swing_deg = 40.0\nluff_deg = 60.0\nhoist_m = 5000.0").unwrap_err();
        assert!(far.contains("resume_from is outside the crane's"), "{far}");
        let mixed = resumed("swing_deg = 40.0\nx_m = 3.0\nhoist_m = 12.0").unwrap_err();
        assert!(mixed.contains("resume_from must give either a load pose"), "{mixed}");
        let mut s = spec();
        s.resume_from = Some(toml::from_str("swing_deg = 150.0\nluff_deg = 60.0\nhoist_m = 12.0").unwrap());
        s.swing_range_deg = Some([-120.0, 120.0]);
        let outside = s.resolve(model()).unwrap_err();
        assert!(outside.contains("resume_from, at swing 150.0°") && outside.contains("swing_range_deg"), "{outside}");
        let moved = t.moved_to(Placement { x_m: 2.0, ..t.crane.placement }).unwrap_err();
        assert!(moved.contains("resumes part way through (resume_from): its crane stays where it stands"), "{moved}");
        // The plan it continues: kept (in lower case), refused without
        // resume_from or where it is no revision or step.
        let with_plan = |resume_from: Option<&str>, plan: &str| {
            let mut s = spec();
            s.resume_from = resume_from.map(|r| toml::from_str(r).unwrap());
            s.resumes_plan = Some(toml::from_str(plan).unwrap());
            s.resolve(model())
        };
        let hangs = Some("swing_deg = 40.0\nluff_deg = 60.0\nhoist_m = 12.0");
        let t = with_plan(hangs, "revision = \"3F9A2C1B\"\nafter_step = 4").unwrap();
        assert_eq!(t.resumes_plan, Some(ResumesPlan { revision: "3f9a2c1b".into(), after_step: 4 }));
        let alone = with_plan(None, "revision = \"3f9a2c1b\"\nafter_step = 4").unwrap_err();
        assert!(alone.contains("give resume_from too"), "{alone}");
        for bad in [
            "revision = \"3f9a2c1\"\nafter_step = 4",
            "revision = \"3f9a2c1g\"\nafter_step = 4",
            "revision = \"3f9a2c1b\"\nafter_step = 0",
        ] {
            let e = with_plan(hangs, bad).unwrap_err();
            assert!(e.contains("the 8 hex digits after \"plan\"") && e.contains("1 or more"), "{bad}: {e}");
        }
    }

    /// The sling legs: checked where their working load limit is given,
    /// at the default points for 1, 2 or 4 legs or at the points given;
    /// what cannot be checked is refused naming the key.
    #[test]
    fn sling_legs_are_given_with_their_working_load_limit() {
        let rigged = |text: &str| {
            let mut s = spec();
            s.rigging = toml::from_str(&format!("mass_t = 0.4\nheight_m = 3.0\n{text}")).unwrap();
            s.resolve(crate::crane::builtin("ltm-1100").unwrap())
        };
        assert!(rigged("").unwrap().slings.is_none());
        let four = rigged("legs = 4\nleg_wll_t = 8.0").unwrap().slings.unwrap();
        assert_eq!(four.lift_points_m.len(), 4);
        assert!(!four.points_given && four.ratings.leg_wll_kg == 8000.0);
        let given = rigged("leg_wll_t = 8.0\nlift_points_m = [[-2.0, 0.0, 1.5], [2.0, 0.0, 1.5], [0.0, 1.0, 1.5]]");
        assert!(given.unwrap().slings.unwrap().points_given);
        let beam = rigged(
            "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0, mass_t = 0.3, top_leg_wll_t = 12.0 }",
        )
        .unwrap()
        .slings
        .unwrap()
        .spreader
        .unwrap();
        assert_eq!(
            beam,
            crate::slings::Spreader {
                length_m: 6.0,
                below_hook_m: 2.0,
                wll_kg: 20_000.0,
                mass_kg: 300.0,
                top_leg_wll_kg: Some(12_000.0),
                width_m: None,
                top_shackles: None,
            }
        );
        assert!(
            toml::from_str::<RiggingSpec>(
                "spreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0, span_m = 5.0 }"
            )
            .is_err()
        );
        let choked =
            rigged("legs = 2\nleg_wll_t = 8.0\nhitch = \"choked\"\nshackle_wll_t = 8.5\nlift_point_wll_t = 9.0")
                .unwrap()
                .slings
                .unwrap();
        assert!(
            choked.ratings.choked
                && choked.ratings.shackle_wll_kg == Some(8500.0)
                && choked.ratings.lift_point_wll_kg == Some(9000.0),
            "{choked:?}"
        );
        assert!(!rigged("legs = 2\nleg_wll_t = 8.0\nhitch = \"straight\"").unwrap().slings.unwrap().ratings.choked);
        // The pins' directions, of any length (a huge one too), taken as
        // unit vectors; the check then says how far each leg pulls out of
        // line with its shackle.
        let pinned =
            rigged("legs = 2\nleg_wll_t = 8.0\nshackle_wll_t = 8.5\npin_axes = [[0.0, 2.0, 0.0], [1e300, 1e300, 0.0]]")
                .unwrap();
        let axes = pinned.slings.as_ref().unwrap().pin_axes.clone().unwrap();
        assert_eq!(axes[0], [0.0, 1.0, 0.0]);
        assert!(
            axes[1].iter().zip([1.0, 1.0, 0.0]).all(|(a, b)| (a - b * std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-15)
        );
        // A spreader beam's top shackles, their pins across the beam: the
        // top legs pull in the beam's plane, in line.
        let beam = rigged(
            "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0, top_leg_wll_t = 12.0, top_shackle_wll_t = 9.5, top_pin_axes = [[0.0, 2.0, 0.0], [0.0, -1.0, 0.0]] }",
        )
        .unwrap();
        let shackles = beam.slings.as_ref().unwrap().spreader.as_ref().unwrap().top_shackles.clone().unwrap();
        assert_eq!((shackles.wll_kg, shackles.pin_axes), (9500.0, Some(vec![[0.0, 1.0, 0.0], [0.0, -1.0, 0.0]])));
        let top = beam.check_slings().unwrap().unwrap().spreader.unwrap().top.unwrap();
        assert_eq!((top.shackle_wll_kg, top.out_of_line_deg.clone()), (Some(9500.0), vec![0.0, 0.0]), "{top:?}");
        let side = pinned.check_slings().unwrap().unwrap().side_loading.unwrap();
        assert_eq!(side.out_of_line_deg[0], 0.0);
        assert!(side.out_of_line_deg[1] > 0.0 && side.turn_deg == 0.0, "{side:?}");
        assert!(
            rigged("legs = 2\nleg_wll_t = 8.0\nshackle_wll_t = 8.5")
                .unwrap()
                .check_slings()
                .unwrap()
                .unwrap()
                .side_loading
                .is_none()
        );
        assert!(
            toml::from_str::<RiggingSpec>("hitch = \"basket\"").is_err(),
            "a basket hitch is not checked, so not taken"
        );
        for (text, said) in [
            ("legs = 4", "but not their working load limit: give rigging leg_wll_t"),
            ("leg_wll_t = 8.0", "give rigging legs (1, 2 or 4) or lift_points_m"),
            ("legs = 3\nleg_wll_t = 8.0", "liftplan places 1, 2 or 4 legs"),
            (
                "legs = 2\nleg_wll_t = 8.0\nlift_points_m = [[0.0, 0.0, 1.5]]",
                "legs = 2 but lift_points_m gives 1 points",
            ),
            ("leg_wll_t = 8.0\nlift_points_m = []", "gives 0 points: give one to four"),
            ("legs = 2\nleg_wll_t = -1.0", "rigging.leg_wll_t must be positive"),
            ("leg_wll_t = 8.0\nlift_points_m = [[0.0, 0.0, 1500.0]]", "lift_points_m[0][2] (its size) = 1500 m"),
            (
                "legs = 2\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0 }",
                "gives a spreader but not the working load limit of the legs hanging from it",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0, mass_t = 0.5 }",
                "rigging.spreader.mass_t (0.5 t) is more than rigging.mass_t (0.4 t), which must include it",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 0.0 }",
                "rigging.spreader.wll_t must be positive",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6000.0, below_hook_m = 2.0, wll_t = 20.0 }",
                "rigging.spreader.length_m = 6000 m",
            ),
            (
                "legs = 4\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, width_m = 0.0, below_hook_m = 2.0, wll_t = 20.0 }",
                "rigging.spreader.width_m must be positive",
            ),
            (
                "legs = 2\nhitch = \"choked\"",
                "gives the legs' hitch, their shackles or their lift points but not the legs' working load limit",
            ),
            (
                "legs = 2\nshackle_wll_t = 8.5",
                "gives the legs' hitch, their shackles or their lift points but not the legs' working load limit",
            ),
            ("legs = 2\nleg_wll_t = 8.0\nshackle_wll_t = 0.0", "rigging.shackle_wll_t must be positive"),
            (
                "legs = 2\nlift_point_wll_t = 9.0",
                "their shackles or their lift points but not the legs' working load limit",
            ),
            ("legs = 2\nleg_wll_t = 8.0\nlift_point_wll_t = -1.0", "rigging.lift_point_wll_t must be positive"),
            (
                "legs = 2\npin_axes = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]",
                "their shackles or their lift points but not the legs' working load limit",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\npin_axes = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]",
                "rigging pin_axes gives the directions of the shackles' pins but not the shackles' working load limit",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nshackle_wll_t = 8.5\nhitch = \"choked\"\npin_axes = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]",
                "the legs are choked round the load (hitch = \"choked\"), not shackled to lugs: leave pin_axes out",
            ),
            (
                "legs = 4\nleg_wll_t = 8.0\nshackle_wll_t = 8.5\npin_axes = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]",
                "rigging pin_axes gives 2 directions for 4 lift points: give one per lift point, in their order",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nshackle_wll_t = 8.5\npin_axes = [[0.0, 1.0, 0.0], [0.0, 0.0, 0.0]]",
                "rigging pin_axes[1] must be a direction (three numbers, not all zero: the axis of lift point 2's lug's hole",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nshackle_wll_t = 8.5\npin_axes = [[0.0, 1.0, 0.0], [nan, 1.0, 0.0]]",
                "rigging pin_axes[1] must be a direction",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nshackle_wll_t = 8.5\npin_axes = [[inf, 1.0, 0.0], [0.0, 1.0, 0.0]]",
                "rigging pin_axes[0] must be a direction",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0, top_leg_wll_t = 12.0, top_pin_axes = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]] }",
                "rigging.spreader.top_pin_axes gives the directions of the top shackles' pins but not the shackles' working load limit: give rigging.spreader.top_shackle_wll_t",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0, top_shackle_wll_t = 12.0 }",
                "rigging.spreader.top_shackle_wll_t gives the shackles of the spreader's top legs, but it has none (no top_leg_wll_t",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0, top_leg_wll_t = 12.0, top_shackle_wll_t = -1.0 }",
                "rigging.spreader.top_shackle_wll_t must be positive",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0, top_leg_wll_t = 12.0, top_shackle_wll_t = 12.0, top_pin_axes = [[0.0, 1.0, 0.0]] }",
                "rigging.spreader.top_pin_axes gives 1 directions for 2 top legs: give one per top leg",
            ),
            (
                "legs = 2\nleg_wll_t = 8.0\nspreader = { length_m = 6.0, below_hook_m = 2.0, wll_t = 20.0, top_leg_wll_t = 12.0, top_shackle_wll_t = 12.0, top_pin_axes = [[0.0, 1.0, 0.0], [0.0, 0.0, 0.0]] }",
                "rigging.spreader.top_pin_axes[1] must be a direction (three numbers, not all zero: the axis of top leg 2's lug's hole",
            ),
        ] {
            let e = rigged(text).unwrap_err();
            assert!(e.contains(said), "{text}: {e}");
        }
    }

    /// A fall zone is taken up to 30 m; a negative or wider one is refused
    /// naming the key.
    #[test]
    fn a_fall_zone_is_taken_within_its_bounds() {
        let model = || crate::crane::builtin("ltm-1100").unwrap();
        let zoned = |m: f64| {
            let mut s = spec();
            s.fall_zone_m = m;
            s.resolve(model())
        };
        assert_eq!(zoned(0.0).unwrap().fall_zone_m, 0.0);
        assert_eq!(zoned(30.0).unwrap().fall_zone_m, 30.0);
        assert!(zoned(-1.0).unwrap_err().contains("fall_zone_m must be zero or positive"));
        assert!(zoned(31.0).unwrap_err().contains("fall_zone_m = 31 m: liftplan draws a fall zone of up to 30 m"));
    }

    #[test]
    fn rejects_mixed_pose_and_bad_id() {
        let mut s = spec();
        s.pick.swing_deg = Some(3.0);
        assert!(s.resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap_err().contains("not a mix"));
        let mut s = spec();
        s.id = "a b".into();
        assert!(s.resolve(crate::crane::builtin("ltm-1100").unwrap()).is_err());
    }

    /// The areas the crane may stand in: taken as given, refused naming the
    /// key where one is no area, and where the crane's set-up is not within
    /// one.
    #[test]
    fn areas_the_crane_may_stand_in_are_checked_as_given() {
        let crane = || crate::crane::builtin("ltm-1100").unwrap();
        let with = |name: &str, corners_m: Vec<[f64; 2]>| {
            let mut sp = spec();
            sp.crane_stands_in = vec![CraneArea { name: name.into(), corners_m }];
            sp.resolve(crane())
        };
        let big = vec![[-30.0, -30.0], [30.0, -30.0], [30.0, 30.0], [-30.0, 30.0]];
        let t = with("yard", big.clone()).unwrap();
        assert_eq!(t.crane_stands_in[0].name, "yard");
        // An area 0.3 m round the carrier and outriggers holds them, and
        // not their pads' 2 m mats (1 m round each pad, 0.6 m beyond the
        // outriggers' outline, which is 0.4 m round the pads).
        let outline: Vec<[f64; 2]> = [PartKind::Carrier, PartKind::Outriggers]
            .iter()
            .flat_map(|&k| t.crane.part(k, &t.pick, &t.load).unwrap().footprint())
            .collect();
        let (lo, hi) = crate::obb::plan_bounds(&outline).unwrap();
        let snug = vec![
            [lo[0] - 0.3, lo[1] - 0.3],
            [hi[0] + 0.3, lo[1] - 0.3],
            [hi[0] + 0.3, hi[1] + 0.3],
            [lo[0] - 0.3, hi[1] + 0.3],
        ];
        assert!(with("pad", snug.clone()).is_ok());
        let mut sp = spec();
        sp.crane_stands_in = vec![CraneArea { name: "pad".into(), corners_m: snug }];
        sp.ground = Some(GroundSpec { mat_m: [2.0, 1.0], allowable_kpa: None });
        let e = sp.clone().resolve(crane()).unwrap_err();
        assert!(e.contains("its carrier and outriggers, with their pads' mats, are not within an area it may stand in (crane_stands_in: 'pad')"), "{e}");
        sp.ground = Some(GroundSpec { mat_m: [0.5, 0.5], allowable_kpa: None });
        assert!(sp.resolve(crane()).is_ok());
        for (name, corners, said) in [
            (
                " ",
                big.clone(),
                "crane_stands_in[0] needs a name (what the area is: \"hardstanding north of the rack\")",
            ),
            ("strip", big[..2].to_vec(), "crane_stands_in 'strip' needs 3 to 200 corners_m"),
            ("line", vec![[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]], "crane_stands_in 'line' encloses no area"),
            (
                "far",
                vec![[40.0, 0.0], [50.0, 0.0], [50.0, 10.0]],
                "its carrier and outriggers are not within an area it may stand in (crane_stands_in: 'far')",
            ),
        ] {
            let e = with(name, corners).unwrap_err();
            assert!(e.starts_with("lift 'V-101': ") && e.contains(said), "{e}");
        }
    }

    /// The areas a load must never be over: taken as given, refused naming
    /// the key where one is no area, and where the load stands over one (or
    /// within the planner's margin of it) at the pick or the set.
    #[test]
    fn areas_the_load_must_not_be_over_are_checked_as_given() {
        let crane = || crate::crane::builtin("ltm-1100").unwrap();
        let area = |name: &str, x0: f64, y0: f64, x1: f64, y1: f64| NotOver {
            name: name.into(),
            corners_m: vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]],
            crane_too: false,
        };
        let with = |areas: Vec<NotOver>| {
            let mut sp = spec();
            sp.not_over = areas;
            sp.resolve(crane())
        };
        let t = with(vec![area("road", 0.0, -30.0, 4.0, 30.0)]).unwrap();
        assert_eq!(t.not_over[0].name, "road");
        // The pick's load spans x 17 to 23 m, y 3.5 to 6.5 m.
        let e = with(vec![area("control room", 22.0, 0.0, 30.0, 4.0)]).unwrap_err();
        assert!(e.contains("the load at the pick is over not_over 'control room' or within 0.25 m of it"), "{e}");
        let e = with(vec![area("edge", 23.1, 0.0, 30.0, 4.0)]).unwrap_err();
        assert!(e.contains("the load at the pick is over not_over 'edge'"), "{e}");
        assert!(with(vec![area("off", 23.3, 0.0, 30.0, 4.0)]).is_ok());
        // A fall zone is kept off an area too: 2 m round the load puts the
        // same area within it (the load's end at 23 m, the area from 23.3),
        // and the area 2.3 m farther off clear of it; the margin beyond.
        let zoned = |areas: Vec<NotOver>| {
            let mut sp = spec();
            sp.fall_zone_m = 2.0;
            sp.not_over = areas;
            sp.resolve(crane())
        };
        let e = zoned(vec![area("off", 23.3, 0.0, 30.0, 4.0)]).unwrap_err();
        assert!(
            e.contains("the load at the pick is over not_over 'off' or within 2.25 m of it (its fall zone, fall_zone_m = 2 m, and the planner's 0.25 m)")
                && e.contains("what may fall from it lands outside them"),
            "{e}"
        );
        assert!(zoned(vec![area("off", 25.1, 0.0, 30.0, 4.0)]).is_err());
        let t = zoned(vec![area("off", 25.3, 0.0, 30.0, 4.0)]).unwrap();
        let c = t.pick;
        assert_eq!(t.not_over_near(&c, 0.0, false).map(|(k, _)| k), None);
        assert_eq!(t.not_over_near(&c, 0.35, false).map(|(k, _)| k), Some(PartKind::Load));
        // What hangs above the load is kept off too: with the centre of
        // gravity 2.9 m along the load from its middle, the hook block
        // (0.8 m wide) hangs over x = 22.9 m, past the load's end.
        let mut sp = spec();
        sp.load.cog_m = [2.9, 0.0, 0.0];
        sp.not_over = vec![area("beside", 23.3, 0.0, 30.0, 10.0)];
        assert!(with(sp.not_over.clone()).is_ok());
        let e = sp.resolve(crane()).unwrap_err();
        assert!(e.contains("the hook block at the pick is over not_over 'beside' or within 0.25 m of it"), "{e}");
        let mut two = area("line", 0.0, 0.0, 1.0, 1.0);
        two.corners_m.truncate(2);
        assert!(with(vec![two]).unwrap_err().contains("not_over 'line' needs 3 to 200 corners_m"));
        let flat =
            NotOver { name: "flat".into(), corners_m: vec![[0.0, 0.0], [5.0, 0.0], [10.0, 0.0]], crane_too: false };
        assert!(with(vec![flat]).unwrap_err().contains("not_over 'flat' encloses no area"));
        let long = area(&"x".repeat(MAX_NOT_OVER_NAME + 1), 0.0, 0.0, 1.0, 1.0);
        assert!(with(vec![long]).unwrap_err().contains("not_over[0]'s name is longer than 100 characters"));
        let unnamed = area(" ", 0.0, 0.0, 1.0, 1.0);
        assert!(with(vec![unnamed]).unwrap_err().contains("not_over[0] needs a name"));
        let nan = area("nan", 0.0, 0.0, f64::NAN, 1.0);
        assert!(with(vec![nan]).unwrap_err().contains("not_over 'nan' has a corner that is not a finite"));
        assert!(
            with(vec![area("a", 0.0, 0.0, 1.0, 1.0); MAX_NOT_OVER + 1]).unwrap_err().contains("at most 50 not_over")
        );
        // Areas the crane may not be over either: the crane standing in the
        // road, its boom over a pipe bridge at the pick (the boom runs from
        // the crane at the origin towards the pick's load at [20, 5]; at
        // x = 10 m its axis is at y = 2.5 m).
        let crane_too = |a: NotOver| NotOver { crane_too: true, ..a };
        let e = with(vec![crane_too(area("road", 0.0, -30.0, 4.0, 30.0))]).unwrap_err();
        assert!(e.contains("the crane's superstructure at the pick is over not_over 'road' (crane_too)"), "{e}");
        let bridge = area("pipe bridge", 9.0, 1.5, 11.0, 3.5);
        assert!(with(vec![bridge.clone()]).is_ok());
        let e = with(vec![crane_too(bridge)]).unwrap_err();
        assert!(e.contains("the crane's boom at the pick is over not_over 'pipe bridge' (crane_too)"), "{e}");
        // A crane moved to where its boom would reach over one is refused too.
        let t = with(vec![crane_too(area("cable tray", 9.0, -1.5, 11.0, -0.5))]).unwrap();
        let c = t.pick;
        assert_eq!(t.not_over_near(&c, 0.0, true), None);
        let moved = t.moved_to(Placement { y_m: -5.0, ..t.crane.placement }).unwrap_err();
        assert!(moved.contains("the crane's boom at the pick is over not_over 'cable tray' (crane_too)"), "{moved}");
        assert!(t.moved_to(Placement { y_m: 1.0, ..t.crane.placement }).is_ok());
    }

    /// TOML has `nan` and `inf`: a position given so is named, not solved.
    #[test]
    fn a_position_that_is_not_a_number_is_named() {
        let mut s = spec();
        s.pick.x_m = Some(f64::NAN);
        let e = s.resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap_err();
        assert!(e.contains("pick.x_m must be a finite number, found NaN"), "{e}");
        let mut s = spec();
        s.set.yaw_deg = f64::INFINITY;
        let e = s.resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap_err();
        assert!(e.contains("set.yaw_deg must be a finite number, found inf"), "{e}");
    }

    /// Lengths are metres: one given in millimetres is named as such, not
    /// solved (it read "the load would need -2967.92 m of rope").
    #[test]
    fn a_length_in_millimetres_is_named() {
        let crane = || crate::crane::builtin("ltm-1100").unwrap();
        let mut s = spec();
        s.load.size_m = [6000.0, 3000.0, 3000.0];
        let e = s.resolve(crane()).unwrap_err();
        assert!(e.contains("load.size_m[0] = 6000 m is more than 150 m"), "{e}");
        assert!(e.contains("was it given in millimetres?"), "{e}");
        let mut s = spec();
        s.clearance_m = 1000.0;
        assert!(s.resolve(crane()).unwrap_err().contains("clearance_m = 1000 m"));
        let mut s = spec();
        s.liftoff_m = 500.0;
        assert!(s.resolve(crane()).unwrap_err().contains("liftoff_m = 500 m"));
        let mut s = spec();
        s.rigging.height_m = 3000.0;
        assert!(s.resolve(crane()).unwrap_err().contains("rigging.height_m = 3000 m"));
        let mut s = spec();
        s.load.size_m = [MAX_LOAD_SIDE_M, 3.0, 3.0];
        assert!(s.resolve(crane()).is_ok());
    }

    /// A centre of gravity known to 0.4 m: the load and its rigging hang
    /// grown by that along the load's x and y wherever they hang free (the
    /// hook over the centre of gravity wherever it lies), the hook block and
    /// the rope not; on top of a gust's swing where there is one.
    #[test]
    fn what_hangs_is_grown_by_the_centre_of_gravitys_tolerance() {
        let mut sp = spec();
        sp.load.cog_tolerance_m = 0.4;
        let t = sp.resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap();
        assert!(t.hangs_swept());
        let c = t.start();
        let held = t.crane.pose(&c, &t.load);
        let free = t.pose_hanging_swept(&c, true);
        for (kind, b) in &held.parts {
            let grown = free.get(*kind).unwrap();
            let by = if matches!(kind, PartKind::Load | PartKind::Rigging) { 0.4 } else { 0.0 };
            assert!(
                (grown.half.x - b.half.x - by).abs() < 1e-12
                    && (grown.half.y - b.half.y - by).abs() < 1e-12
                    && (grown.half.z, grown.center, grown.axes) == (b.half.z, b.center, b.axes),
                "{kind:?}"
            );
        }
        // Held at its support in a lift-off or set-down: as it is.
        assert_eq!(t.pose_hanging_swept(&c, false).parts, held.parts);
        // With a gust's swing too: both.
        let mut windy = t.clone();
        windy.gust_swing_per_m = 0.02;
        let (load, sheave_z) = (windy.crane.load_obb(&c, &windy.load), windy.crane.sheave(&c).z);
        let swing_m = 0.02 * (sheave_z - windy.crane.load_bottom_z(&c, &windy.load));
        let grown = windy.hanging_swept(PartKind::Load, &load, sheave_z);
        assert!((grown.half.x - load.half.x - swing_m - 0.4).abs() < 1e-12);
    }

    /// A centre of gravity's tolerance is a length, and with it the centre
    /// of gravity stays within the load's box in plan.
    #[test]
    fn a_centre_of_gravitys_tolerance_stays_within_the_load() {
        let crane = || crate::crane::builtin("ltm-1100").unwrap();
        let with = |cog_m: [f64; 3], tol: f64| {
            let mut s = spec();
            (s.load.cog_m, s.load.cog_tolerance_m) = (cog_m, tol);
            s.resolve(crane())
        };
        assert_eq!(with([0.0; 3], 0.0).unwrap().cog_tolerance_m, 0.0);
        assert_eq!(with([2.5, 0.0, 0.0], 0.5).unwrap().cog_tolerance_m, 0.5);
        let e = with([2.5, 0.0, 0.0], 0.6).unwrap_err();
        assert!(
            e.contains("load.cog_m[0] = 2.5 give or take load.cog_tolerance_m = 0.6 m reaches outside the load box (6 m along its x)"),
            "{e}"
        );
        let e = with([0.0, 1.0, 0.0], 0.6).unwrap_err();
        assert!(e.contains("load.cog_m[1] = 1 give or take"), "{e}");
        assert!(
            with([0.0; 3], -0.1).unwrap_err().contains("load.cog_tolerance_m must be zero or positive, found -0.1")
        );
        assert!(with([0.0; 3], f64::NAN).unwrap_err().contains("load.cog_tolerance_m must be zero or positive"));
        // Read from the lift's file.
        let s: LiftSpec = toml::from_str(
            &SPEC.replace("size_m = [6.0, 3.0, 3.0] }", "size_m = [6.0, 3.0, 3.0], cog_tolerance_m = 0.2 }"),
        )
        .unwrap();
        assert_eq!(s.resolve(crane()).unwrap().cog_tolerance_m, 0.2);
    }

    /// One boom (40 m), rows every 2 m from 4 to 60 m: (100 - r) t, each
    /// cell named `r<radius>`.
    fn chart_every_2_m() -> crate::capacity::ChartConfig {
        let radii_m: Vec<f64> = (2..=30).map(|k| 2.0 * k as f64).collect();
        let cells = radii_m
            .iter()
            .map(|r| Some(crate::capacity::ChartCell { capacity_kg: (100.0 - r) * 1000.0, cell: format!("r{r}") }))
            .collect();
        crate::capacity::ChartConfig { name: "main".into(), boom_lengths_m: vec![40.0], radii_m, cells }
    }

    /// A radius allowance (for the boom bending under load) reads the chart
    /// that much farther out, in every capacity check the planner, the
    /// validator and the charts stage make; it is a length in metres.
    #[test]
    fn the_radius_allowance_reads_the_chart_farther_out() {
        let crane = || crate::crane::builtin("ltm-1100").unwrap();
        let chart = chart_every_2_m();
        let plain = spec().resolve(crane()).unwrap();
        let mut s = spec();
        s.radius_allowance_m = 3.0;
        let allowed = s.resolve(crane()).unwrap();
        let (a, b) = (
            plain.check_capacity(&chart, plain.pick.radial).unwrap(),
            allowed.check_capacity(&chart, allowed.pick.radial).unwrap(),
        );
        assert_eq!(a.radius_m, b.radius_m);
        let row = |r: f64| 2.0 * (r / 2.0).ceil();
        assert_eq!(a.capacity.cell, format!("r{}", row(a.radius_m)), "{a:?}");
        assert_eq!(b.capacity.cell, format!("r{}", row(a.radius_m + 3.0)), "{b:?}");
        assert!(b.utilisation_pct > a.utilisation_pct);
        let mut s = spec();
        s.radius_allowance_m = -0.5;
        assert!(s.resolve(crane()).unwrap_err().contains("radius_allowance_m"));
        s.radius_allowance_m = 500.0;
        assert!(s.resolve(crane()).unwrap_err().contains("radius_allowance_m = 500 m is more than 10 m"));
    }

    /// A motion between two radii reads the chart's cell at each end and at
    /// every row between, with the radius allowance, each once; the same
    /// cells a capacity check at each radius between would read.
    #[test]
    fn a_motion_reads_the_chart_cells_between_its_radii() {
        let chart = chart_every_2_m();
        let crane = || crate::crane::builtin("ltm-1100").unwrap();
        let plain = spec().resolve(crane()).unwrap();
        assert_eq!(plain.chart_cells_between(&chart, 9.0, 14.5), ["r10", "r12", "r14", "r16"]);
        assert_eq!(plain.chart_cells_between(&chart, 14.5, 9.0), ["r10", "r12", "r14", "r16"]);
        assert_eq!(plain.chart_cells_between(&chart, 10.0, 10.0), ["r10"]);
        // Beyond the chart's last row no cell is read.
        assert_eq!(plain.chart_cells_between(&chart, 58.5, 70.0), ["r60"]);
        let mut s = spec();
        s.radius_allowance_m = 1.0;
        let allowed = s.resolve(crane()).unwrap();
        assert_eq!(allowed.chart_cells_between(&chart, 9.0, 14.5), ["r10", "r12", "r14", "r16"]);
        assert_eq!(allowed.chart_cells_between(&chart, 9.5, 9.5), ["r12"]);
        // Every radius between reads one of them.
        for k in 0..=55 {
            let r = 9.0 + 0.1 * k as f64;
            let read = plain.chart_cells_between(&chart, r, r);
            assert!(plain.chart_cells_between(&chart, 9.0, 14.5).contains(&read[0]), "{r}");
        }
    }

    /// A permitted swing range holds the pick and the set as its numbers
    /// say, across ±180° too; outside it, the position is named.
    #[test]
    fn a_swing_range_holds_the_pick_and_set_or_names_them() {
        let crane = || crate::crane::builtin("ltm-1100").unwrap();
        let free = spec().resolve(crane()).unwrap();
        // The pick is at about 14°, the set at about 119°.
        let (p, s) = (free.pick.swing_rad.to_degrees(), free.set.swing_rad.to_degrees());
        assert!((10.0..20.0).contains(&p) && (115.0..125.0).contains(&s), "{p} {s}");
        let mut sp = spec();
        sp.swing_range_deg = Some([-350.0, 0.0]);
        let t = sp.resolve(crane()).unwrap();
        assert!((t.pick.swing_rad.to_degrees() - (p - 360.0)).abs() < 1e-9);
        assert!((t.set.swing_rad.to_degrees() - (s - 360.0)).abs() < 1e-9);
        let mut sp = spec();
        sp.swing_range_deg = Some([0.0, 90.0]);
        let e = sp.resolve(crane()).unwrap_err();
        assert!(e.contains("the set, at swing 11") && e.contains("is outside swing_range_deg [0, 90]"), "{e}");
        let mut sp = spec();
        sp.swing_range_deg = Some([-10.0, 400.0]);
        assert!(sp.resolve(crane()).unwrap_err().contains("at most a full turn"));
    }

    /// A lift moved to another crane position solves its pick and set as
    /// the lift file given that position would, its swing range held, and
    /// says where the crane there cannot hold them.
    #[test]
    fn a_lift_moved_elsewhere_solves_as_its_file_would() {
        let crane = || crate::crane::builtin("ltm-1100").unwrap();
        let mut sp = spec();
        sp.swing_range_deg = Some([-180.0, 180.0]);
        let t = sp.resolve(crane()).unwrap();
        let to = Placement { x_m: 5.0, y_m: 12.0, z_m: 0.3, heading_rad: 30f64.to_radians(), ..t.crane.placement };
        let moved = t.moved_to(to).unwrap();
        let mut there = sp.clone();
        there.crane.position_m = [5.0, 12.0];
        there.crane.ground_z_m = 0.3;
        there.crane.heading_deg = 30.0;
        let fresh = there.resolve(crane()).unwrap();
        for (a, b) in [(moved.pick, fresh.pick), (moved.set, fresh.set)] {
            assert!(a.to_array().iter().zip(b.to_array()).all(|(x, y)| (x - y).abs() < 1e-12), "{a:?} {b:?}");
        }
        assert_eq!(moved.crane.placement, fresh.crane.placement);
        assert_ne!(moved.pick, t.pick);
        // Beyond the crane's reach, outside the swing range, off the boom's range.
        let far = Placement { x_m: 200.0, ..to };
        assert!(
            t.moved_to(far).unwrap_err().contains("pick position cannot be reached"),
            "{:?}",
            t.moved_to(far).err()
        );
        let mut sp = spec();
        sp.swing_range_deg = Some([-60.0, 130.0]);
        let t = sp.resolve(crane()).unwrap();
        let turned = Placement { heading_rad: std::f64::consts::PI, ..t.crane.placement };
        let e = t.moved_to(turned).unwrap_err();
        assert!(e.contains("is outside swing_range_deg [-60.0, 130.0]"), "{e}");
        let e = t.moved_to(Placement { boom_length_m: 500.0, ..t.crane.placement }).unwrap_err();
        assert!(e.contains("boom length 500 m is outside"), "{e}");
    }

    /// A lift's wind: worked out on the hook load (load, slings and hook
    /// block, not the chart's deductions); refused for a tower crane and
    /// for values no lift has.
    #[test]
    fn the_wind_key_is_checked_and_worked_out_on_the_hook_load() {
        let mut sp = spec();
        sp.crane.deductions_t = 2.0;
        sp.wind = Some(crate::wind::WindSpec { chart_ms: Some(9.8), cw: 1.2, area_m2: None, plan_for_swing: true });
        let t = sp.resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap();
        let stated =
            |v: f64, cell: &str| crate::capacity::StatedOnChart { value: v, cell: cell.into(), text: String::new() };
        let (w, other) = t.permissible_wind(&[]).unwrap();
        assert!((w.hook_load_kg - (12500.0 + 400.0 + 1100.0)).abs() < 1e-9 && other.is_empty(), "{w:?}");
        assert_eq!((w.area_m2, w.chart_cell.as_deref()), (18.0, None));
        // The lift's speed governs; where the sheet states others and not
        // it, they are said.
        let (w, other) = t.permissible_wind(&[stated(9.8, "M!A1"), stated(7.0, "M!A2")]).unwrap();
        assert!(w.chart_ms == 9.8 && other.is_empty(), "{other:?}");
        let (_, other) = t.permissible_wind(&[stated(9.0, "M!A1"), stated(7.0, "M!A2")]).unwrap();
        assert_eq!(other, [stated(9.0, "M!A1"), stated(7.0, "M!A2")]);
        // Without chart_ms, the one speed the sheet states; of two, none.
        let mut from_chart = sp.clone();
        from_chart.wind = Some(crate::wind::WindSpec { chart_ms: None, cw: 1.2, area_m2: None, plan_for_swing: true });
        let t = from_chart.resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap();
        let (w, _) = t.permissible_wind(&[stated(9.0, "M!A1")]).unwrap();
        assert_eq!((w.chart_ms, w.chart_cell.as_deref()), (9.0, Some("M!A1")));
        let e = t.permissible_wind(&[stated(9.0, "M!A1"), stated(7.0, "M!A2")]).unwrap_err();
        assert!(e.contains("states several wind speeds, 9.0 m/s (M!A1), 7.0 m/s (M!A2): give chart_ms"), "{e}");
        assert!(t.permissible_wind(&[]).unwrap_err().contains("states no wind speed"));
        let none = spec().resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap();
        assert!(none.permissible_wind(&[stated(9.0, "M!A1")]).unwrap_err().contains("the lift gives no wind = { cw }"));
        let mut bad = sp.clone();
        bad.wind = Some(crate::wind::WindSpec { chart_ms: Some(98.0), cw: 1.2, area_m2: None, plan_for_swing: true });
        let e = bad.resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap_err();
        assert!(e.starts_with("lift 'V-101': wind chart_ms must be a wind speed in m/s"), "{e}");
        sp.crane.model = "tower-hh-60".into();
        sp.crane.boom_m = None;
        let e = sp.resolve(crate::crane::builtin("tower-hh-60").unwrap()).unwrap_err();
        assert!(e.contains("is a tower crane: its manufacturer's in-service wind rules apply"), "{e}");
    }

    /// The hoist rope's falls in the wind: the lift's falls or the block's
    /// most, the crane file's diameter or the widest for its mass, at the
    /// longest rope the lift is planned with; the swing planned for grows by
    /// half their area; not counted, and why, where the crane file cannot
    /// say how wide the rope is or the falls are not known.
    #[test]
    fn the_hoist_rope_s_falls_catch_the_wind_too() {
        let windy = |falls: Option<u32>, diameter_mm: Option<f64>, kg_per_m: Option<f64>, max_falls: Option<u32>| {
            let mut s = spec();
            s.crane.falls = falls;
            s.crane.longest_rope_m = Some(35.0);
            s.wind = Some(crate::wind::WindSpec { chart_ms: Some(9.8), cw: 1.2, area_m2: None, plan_for_swing: true });
            let mut model = crate::crane::builtin("ac-700").unwrap();
            (model.hook.rope_diameter_mm, model.hook.rope_kg_per_m, model.hook.max_falls) =
                (diameter_mm, kg_per_m, max_falls);
            s.resolve(model).unwrap()
        };
        let t = windy(Some(6), Some(28.0), Some(3.9), Some(10));
        let r = t.rope_in_wind().unwrap();
        assert_eq!((r.falls, r.falls_given, r.diameter_mm, r.diameter_given, r.longest_m), (6, true, 28.0, true, 35.0));
        let (w, _) = t.permissible_wind(&[]).unwrap();
        assert_eq!(w.rope, Some(r.clone()));
        assert_eq!(t.gust_swing_per_m, w.gust_swing_per_m());
        let bare = windy(Some(6), None, None, Some(10));
        let (plain, _) = bare.permissible_wind(&[]).unwrap();
        assert_eq!(plain.rope, None);
        let grown = t.gust_swing_per_m / bare.gust_swing_per_m;
        assert!((grown - (plain.wind_area_m2 + r.wind_area_m2 / 2.0) / plain.wind_area_m2).abs() < 1e-12, "{grown}");
        assert!(grown > 1.1, "{grown}");
        assert_eq!(
            plain.rope_not_counted.as_deref(),
            Some(
                "the crane file gives neither the rope's diameter nor its mass per metre (hook.rope_diameter_mm, hook.rope_kg_per_m)"
            )
        );
        let guessed = windy(None, None, Some(3.9), Some(10)).rope_in_wind().unwrap();
        assert_eq!((guessed.falls, guessed.falls_given, guessed.diameter_given), (10, false, false));
        assert!((guessed.diameter_mm - crate::wind::RopeInWind::widest_diameter_mm(3.9)).abs() < 1e-12);
        let e = windy(None, Some(28.0), None, None).rope_in_wind().unwrap_err();
        assert_eq!(e, "the lift gives no falls (crane falls) and the crane file no most falls (hook.max_falls)");
    }

    /// A lift that gives its wind is planned for the load's swing in a gust:
    /// what hangs is grown in plan by twice the steady push per metre it
    /// hangs below the sheave, its underside kept; not where turned off, and
    /// not before a chart speed the sheet states is known.
    #[test]
    fn a_lift_with_wind_is_planned_for_the_swing_a_gust_gives_the_load() {
        let crane = || crate::crane::builtin("ltm-1100").unwrap();
        let mut sp = spec();
        sp.wind = Some(crate::wind::WindSpec { chart_ms: Some(9.8), cw: 1.2, area_m2: None, plan_for_swing: true });
        let t = sp.resolve(crane()).unwrap();
        let (w, _) = t.permissible_wind(&[]).unwrap();
        // The load catches 21.6 m² on 14 t, more than the chart's 1.2 m²/t:
        // at its reduced speed it hangs as far off plumb as the chart's load.
        let chart_rate = 2.0 * 0.5 * 1.25 * 9.8f64.powi(2) * 1.2 / (1000.0 * 9.80665);
        assert!(w.reduced() && (t.gust_swing_per_m - chart_rate).abs() < 1e-12, "{}", t.gust_swing_per_m);
        assert!((t.gust_swing_per_m - 0.0147).abs() < 1e-4 && !t.wind_swing_unknown());
        let c = t.start();
        let (load, sheave_z) = (t.crane.load_obb(&c, &t.load), t.crane.sheave(&c).z);
        let swung = t.hanging_swept(PartKind::Load, &load, sheave_z);
        let below_m = sheave_z - t.crane.load_bottom_z(&c, &t.load);
        let swing_m = t.gust_swing_per_m * below_m;
        assert!(swing_m > 0.3, "{swing_m}");
        assert!(
            (swung.half.x - load.half.x - swing_m).abs() < 1e-12
                && (swung.half.y - load.half.y - swing_m).abs() < 1e-12
        );
        assert_eq!((swung.half.z, swung.center), (load.half.z, load.center));
        // A road beside the load's footprint, 0.3 m off: clear of the load
        // hanging plumb, not of the load a gust swings.
        let side = load.aabb().max[1] + 0.3;
        let mut near = spec();
        near.wind = sp.wind;
        near.not_over = vec![NotOver {
            name: "road".into(),
            corners_m: vec![[0.0, side], [40.0, side], [40.0, side + 5.0], [0.0, side + 5.0]],
            crane_too: false,
        }];
        let e = near.resolve(crane()).map(|t| t.not_over_near(&t.start(), 0.0, true).map(|(k, a)| (k, a.name.clone())));
        assert_eq!(e, Ok(Some((crate::crane::PartKind::Load, "road".to_string()))));
        let plumb = near.resolve(crane()).unwrap();
        assert_eq!(plumb.not_over_near(&plumb.start(), 0.0, false), None);
        // Turned off: the box as it hangs.
        let mut off = sp.clone();
        off.wind = Some(crate::wind::WindSpec { plan_for_swing: false, ..sp.wind.unwrap() });
        let t = off.resolve(crane()).unwrap();
        assert_eq!((t.gust_swing_per_m, t.hanging_swept(PartKind::Load, &load, sheave_z)), (0.0, load));
        assert!(!t.wind_swing_unknown());
        // The chart's speed from its sheet: not known until it is given.
        let mut sheet = sp.clone();
        sheet.wind = Some(crate::wind::WindSpec { chart_ms: None, ..sp.wind.unwrap() });
        let mut t = sheet.resolve(crane()).unwrap();
        assert!(t.wind_swing_unknown());
        let e = t.plan_for_wind(&[]).unwrap_err();
        assert!(e.starts_with("lift 'V-101': the load's swing in the wind cannot be planned for: the lift's wind gives no chart_ms, and its chart's sheet states no wind speed; or set wind plan_for_swing = false"), "{e}");
        let stated = crate::capacity::StatedOnChart { value: 9.8, cell: "M!A41".into(), text: String::new() };
        t.plan_for_wind(&[stated]).unwrap();
        assert!((t.gust_swing_per_m - chart_rate).abs() < 1e-12 && !t.wind_swing_unknown());
        // In the project file it is on unless turned off.
        let spec: crate::wind::WindSpec = toml::from_str("cw = 1.2").unwrap();
        assert!(spec.plan_for_swing);
        let spec: crate::wind::WindSpec = toml::from_str("cw = 1.2\nplan_for_swing = false").unwrap();
        assert!(!spec.plan_for_swing);
    }

    /// The outrigger keys need a crane file with masses, and sane values.
    #[test]
    fn the_outrigger_keys_need_masses_and_sane_values() {
        let with = |ground: &str, counterweight: &str, crane: &str| {
            let text = format!(
                "{}ground = {ground}\n",
                SPEC.replace("chart_config = \"main\"", &format!("chart_config = \"main\"{counterweight}"))
                    .replace("\"ltm-1100\"", &format!("\"{crane}\""))
            );
            let sp: LiftSpec = toml::from_str(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
            sp.resolve(crate::crane::builtin(crane).unwrap())
        };
        let t = with("{ mat_m = [2.0, 2.0], allowable_kpa = 250.0 }", ", counterweight_t = 20.0", "ltm-1100").unwrap();
        assert_eq!(t.counterweight_kg, Some(20_000.0));
        assert_eq!(t.counterweight_used_kg(), Some((20_000.0, CounterweightFrom::Lift)));
        assert_eq!(t.ground.unwrap().mat_m, [2.0, 2.0]);
        let light = t.pad_loads(&t.pick).unwrap().total_kg;
        let full = with("{ mat_m = [2.0, 2.0] }", "", "ltm-1100").unwrap();
        assert_eq!(full.counterweight_used_kg(), Some((37_000.0, CounterweightFrom::CraneFile)));
        assert!((full.pad_loads(&full.pick).unwrap().total_kg - light - 17_000.0).abs() < 1e-6);
        let e = with("{ mat_m = [0.0, 2.0] }", "", "ltm-1100").unwrap_err();
        assert!(e.contains("ground mat_m must be"), "{e}");
        let e = with("{ mat_m = [2.0, 2.0], allowable_kpa = -5.0 }", "", "ltm-1100").unwrap_err();
        assert!(e.contains("allowable_kpa must be a positive pressure"), "{e}");
        let e = with("{ mat_m = [2.0, 2.0] }", ", counterweight_t = -1.0", "ltm-1100").unwrap_err();
        assert!(e.contains("counterweight_t must be a mass"), "{e}");
        let e = with("{ mat_m = [2.0, 2.0] }", "", "tower-hh-60").unwrap_err();
        assert!(e.contains("gives no [masses]") && e.contains("a tower crane has no outriggers"), "{e}");
    }

    /// A chart configuration's name may state its counterweight: read so,
    /// and only so ("CW 70t", not "screw 70 t", "70 to 80 t" or two that
    /// differ).
    #[test]
    fn a_chart_configurations_counterweight_is_read_from_its_name() {
        for (name, kg) in [
            ("Main boom 360 CW 70t", Some(70_000.0)),
            ("Main boom, counterweight 42.5 t, 360°", Some(42_500.0)),
            ("Ballast: 140 t", Some(140_000.0)),
            ("Hauptausleger Gegengewicht 70 t", Some(70_000.0)),
            ("CW 70t (counterweight 70 t)", Some(70_000.0)),
            ("Main boom 360", None),
            ("screw 70 t", None),
            ("CW 70 to 80 t", None),
            ("CW 70t / CW 140t", None),
            ("CW 70 kg", None),
        ] {
            assert_eq!(counterweight_named_kg(name), kg, "{name}");
        }
        let with = |config: &str, counterweight: &str| {
            let text = SPEC.replace("chart_config = \"main\"", &format!("chart_config = \"{config}\"{counterweight}"));
            toml::from_str::<LiftSpec>(&text).unwrap().resolve(crate::crane::builtin("ltm-1100").unwrap()).unwrap()
        };
        let t = with("main CW 20t", "");
        assert_eq!(t.counterweight_used_kg(), Some((20_000.0, CounterweightFrom::ChartConfig)));
        // The pads are worked out with it: 17 t less than the file's 37 t.
        let file = with("main", "");
        let total = |t: &LiftTask| t.pad_loads(&t.pick).unwrap().total_kg;
        assert!((total(&file) - total(&t) - 17_000.0).abs() < 1e-6);
        assert_eq!(t.counterweight_disagrees_kg(), None);
        let t = with("main CW 20t", ", counterweight_t = 37.0");
        assert_eq!(t.counterweight_used_kg(), Some((37_000.0, CounterweightFrom::Lift)));
        assert_eq!(t.counterweight_disagrees_kg(), Some([37_000.0, 20_000.0]));
        assert_eq!(with("main CW 20t", ", counterweight_t = 20.0").counterweight_disagrees_kg(), None);
        // The one its chart's sheet states, where the name states none;
        // the name's where both do; the lift's over either.
        let sheet = crate::capacity::StatedOnChart { value: 25_000.0, cell: "main!A3".into(), text: "CW 25 t".into() };
        let mut t = with("main", "");
        t.chart_sheet_counterweight = Some(sheet.clone());
        assert_eq!(t.counterweight_used_kg(), Some((25_000.0, CounterweightFrom::ChartSheet)));
        assert!((total(&file) - total(&t) - 12_000.0).abs() < 1e-6);
        let mut t = with("main CW 20t", "");
        t.chart_sheet_counterweight = Some(sheet.clone());
        assert_eq!(t.counterweight_used_kg(), Some((20_000.0, CounterweightFrom::ChartConfig)));
        let mut t = with("main", ", counterweight_t = 37.0");
        t.chart_sheet_counterweight = Some(sheet);
        assert_eq!(t.counterweight_disagrees_kg(), Some([37_000.0, 25_000.0]));
    }

    #[test]
    fn unknown_field_is_refused() {
        let e = toml::from_str::<LiftSpec>("id='x'\nlod = 1\n").unwrap_err();
        assert!(e.to_string().contains("lod"), "{e}");
    }
}

/// Where the chart lets this lift go: the radial joint intervals (luff angle or
/// trolley radius) over which the reduced chart capacity at the working radius
/// carries the gross load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChartLimits {
    pub gross_kg: f64,
    /// Radial intervals, ascending, in the crane's radial unit (rad or m).
    pub intervals: Vec<(f64, f64)>,
    /// Step the intervals were resolved with (same unit).
    pub step: f64,
}

impl ChartLimits {
    pub fn contains(&self, radial: f64) -> bool {
        self.intervals.iter().any(|(a, b)| radial >= *a - 1e-12 && radial <= *b + 1e-12)
    }

    /// The interval holding `radial`, if any.
    pub fn interval_of(&self, radial: f64) -> Option<(f64, f64)> {
        self.intervals.iter().copied().find(|(a, b)| radial >= *a - 1e-12 && radial <= *b + 1e-12)
    }
}

/// The capacity of a lift's crane at a configuration's working radius, with
/// utilisation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CapacityCheck {
    /// The rigid crane's radius (m); the chart was read at this plus the
    /// lift's `radius_allowance_m`.
    pub radius_m: f64,
    pub capacity: crate::capacity::Capacity,
    /// Chart capacity after the configured reduction (kg).
    pub effective_kg: f64,
    pub utilisation_pct: f64,
}

impl LiftTask {
    /// Capacity and utilisation at a radial joint value, or why the chart forbids it.
    pub fn check_capacity(
        &self,
        chart: &crate::capacity::ChartConfig,
        radial: f64,
    ) -> Result<CapacityCheck, crate::capacity::CapacityError> {
        let r = self.crane.radius_m(radial);
        let tower = self.crane.model.is_tower();
        if tower && !chart.boom_independent() {
            let b = &chart.boom_lengths_m;
            return Err(crate::capacity::CapacityError::ByBoomForTower {
                min_m: b.first().copied().unwrap_or(0.0),
                max_m: b.last().copied().unwrap_or(0.0),
            });
        }
        let c = chart.lookup(self.chart_boom_m(), r + self.radius_allowance_m)?;
        let eff = self.effective_capacity_kg(c.capacity_kg);
        Ok(CapacityCheck {
            radius_m: r,
            utilisation_pct: self.utilisation_pct(c.capacity_kg),
            effective_kg: eff,
            capacity: c,
        })
    }

    /// The boom length the chart is read at: the lift's boom, or 0 for a
    /// tower crane, whose chart has one column for any jib.
    pub fn chart_boom_m(&self) -> f64 {
        if self.crane.model.is_tower() { 0.0 } else { self.crane.placement.boom_length_m }
    }

    /// The chart cells a motion between the working radii `from_m` and
    /// `to_m` reads, as [`Self::check_capacity`] reads them (with the radius
    /// allowance, by the chart's rule): the cell at each end and at every
    /// chart row between, each once, from the smaller radius out. A radius
    /// the chart gives no capacity at reads none.
    pub fn chart_cells_between(&self, chart: &crate::capacity::ChartConfig, from_m: f64, to_m: f64) -> Vec<String> {
        let boom = self.chart_boom_m();
        let (lo, hi) = (from_m.min(to_m) + self.radius_allowance_m, from_m.max(to_m) + self.radius_allowance_m);
        let rows = chart.radii_m.iter().copied().filter(|&r| r > lo && r < hi);
        let mut cells: Vec<String> = Vec::new();
        for r in std::iter::once(lo).chain(rows).chain(std::iter::once(hi)) {
            if let Ok(c) = chart.lookup(boom, r)
                && !cells.contains(&c.cell)
            {
                cells.push(c.cell);
            }
        }
        cells
    }

    /// The radial ranges where the chart carries the gross load, resolved at
    /// `step` (rad for luffing cranes, m for tower cranes) within the crane's own
    /// radial limits. Each interval's ends are sampled points that pass; between
    /// samples the next-larger-radius rule of the chart keeps the answer safe
    /// only if the chart rows are no further apart than the step in radius, so
    /// the planner re-checks capacity at every configuration it uses.
    pub fn chart_limits(&self, chart: &crate::capacity::ChartConfig, step: f64) -> ChartLimits {
        let (lo, hi) = self.crane.limits().radial;
        let n = (((hi - lo) / step).ceil() as usize).max(1);
        let gross = self.gross_kg();
        let mut intervals: Vec<(f64, f64)> = Vec::new();
        let mut open: Option<f64> = None;
        let mut last_ok = lo;
        for k in 0..=n {
            let x = (lo + step * k as f64).min(hi);
            let ok = self.check_capacity(chart, x).map(|c| c.effective_kg >= gross).unwrap_or(false);
            match (ok, open) {
                (true, None) => {
                    open = Some(x);
                    last_ok = x;
                }
                (true, Some(_)) => last_ok = x,
                (false, Some(a)) => {
                    intervals.push((a, last_ok));
                    open = None;
                }
                (false, None) => {}
            }
        }
        if let Some(a) = open {
            intervals.push((a, last_ok));
        }
        ChartLimits { gross_kg: gross, intervals, step }
    }
}
