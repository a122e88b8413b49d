//! Operator steps (Cai Table 6.1 style): one joint at a time, with the crane's
//! configuration, radius, capacity, utilisation and the smallest clearance the
//! validator measured during the step.

use crate::path::Move;
use crate::validate::Verdict;
use liftplan_core::crane::Config;
use liftplan_core::lift::{CounterweightFrom, GroundSpec, LiftTask};
use liftplan_core::outriggers::{G_M_S2, Pad, pressure_kpa};
use liftplan_cspace::Joint;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Step {
    pub n: usize,
    /// e.g. "Swing", "Luff up", "Hoist up", "Lower", "Rotate load", "Trolley out".
    pub operation: String,
    /// Signed amount in `unit`.
    pub amount: f64,
    pub unit: String,
    /// Human text: "swing +58.0° (counter-clockwise)".
    pub text: String,
    pub end: Config,
    /// Working radius at the end of the step (m).
    pub radius_m: f64,
    /// Load underside height at the end (m).
    pub load_height_m: f64,
    /// Smallest chart capacity during the step (kg, before the reduction) and its cell.
    pub capacity_kg: Option<f64>,
    pub chart_cell: Option<String>,
    /// Highest utilisation during the step (%).
    pub utilisation_pct: Option<f64>,
    /// Smallest clearance during the step (m), which part, to what, and what
    /// was required; infinite where nothing lay within the validator's search.
    #[serde(with = "distance_json")]
    pub min_clearance_m: f64,
    pub clearance_part: String,
    pub clearance_to: String,
    /// Where on the obstacle the smallest clearance was measured (site frame).
    #[serde(default)]
    pub clearance_at: Option<[f64; 3]>,
    pub required_clearance_m: f64,
    /// The most an outrigger pad carries during the step; `None` for a
    /// tower crane or a crane file without masses.
    #[serde(default)]
    pub pads: Option<StepPads>,
}

/// The most an outrigger pad carries during a step, from the crane file's
/// masses ([`liftplan_core::outriggers`]): an estimate, for the ground
/// under the pads and its mats, not the manufacturer's figures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepPads {
    pub pad: Pad,
    pub load_kg: f64,
    /// The pad's centre (site frame, m).
    pub at_m: [f64; 2],
    /// Whether at some moment of the step a pad lifts off and three carry
    /// the crane.
    pub pad_lifts: bool,
    /// Whether at some moment the centre of gravity of crane and load lies
    /// outside the pads.
    pub tips: bool,
}

/// Swing and luff between the samples of [`pads_during`] (rad): a pad's
/// load changes with the cosine of the swing, so its most between two
/// samples half a degree apart exceeds theirs by at most 1 - cos 0.25°
/// (0.001 %) of its swing's share.
const PAD_SAMPLE_RAD: f64 = std::f64::consts::PI / 360.0;

/// The pads' most during a move: their loads at both ends and every half
/// degree of swing and luff between (hoisting and turning the load change
/// none of them), each the higher of the gross load on the hook and the
/// gross load less the chart's deductions
/// ([`LiftTask::pad_loads_hanging`]).
pub fn pads_during(task: &LiftTask, m: &Move) -> Option<StepPads> {
    let (a, b) = (m.from.to_array(), m.to.to_array());
    let turn = (b[0] - a[0]).abs() + if task.crane.model.is_tower() { 0.0 } else { (b[1] - a[1]).abs() };
    let n = ((turn / PAD_SAMPLE_RAD).ceil() as usize).clamp(1, 100_000);
    let mut most: Option<StepPads> = None;
    for i in 0..=n {
        let t = i as f64 / n as f64;
        let here = pads_at(task, &Config::from_array(std::array::from_fn(|k| a[k] + (b[k] - a[k]) * t)))?;
        most = Some(match most {
            Some(m) if m.load_kg >= here.load_kg => {
                StepPads { pad_lifts: m.pad_lifts || here.pad_lifts, tips: m.tips || here.tips, ..m }
            }
            Some(m) => StepPads { pad_lifts: m.pad_lifts || here.pad_lifts, tips: m.tips || here.tips, ..here },
            None => here,
        });
    }
    most
}

/// The pads at one configuration: the most loaded, the higher of the
/// gross load on the hook and the least that hangs (no deductions, no
/// hoist rope: [`LiftTask::least_hanging_kg`]).
pub fn pads_at(task: &LiftTask, c: &Config) -> Option<StepPads> {
    let mut loads = task.pad_loads(c)?;
    if task.gross_kg() > task.least_hanging_kg() {
        let without = task.pad_loads_hanging(c, task.least_hanging_kg())?;
        if without.highest().1 > loads.highest().1 {
            loads = without;
        }
    }
    let (pad, load_kg) = loads.highest();
    Some(StepPads {
        pad,
        load_kg,
        at_m: liftplan_core::outriggers::pad_at(&task.crane, pad)?,
        pad_lifts: loads.loads_kg.contains(&0.0),
        tips: loads.tips,
    })
}

impl StepPads {
    /// The pad's load in words, and the pressure under its mat where the
    /// lift gives one: "84.2 t (826 kN) on the front left pad (x 8.25 m,
    /// y 5.75 m); 206 kPa under its 2.00 x 2.00 m mat, allowable 250 kPa".
    pub fn said(&self, ground: Option<&GroundSpec>) -> String {
        self.said_as(ground, false)
    }

    /// [`StepPads::said`] without the force and the pad's place: "84.2 t on
    /// the front left pad; 206 kPa ...", for the sign-off page, where the
    /// cover and the step's page give them.
    pub fn said_briefly(&self, ground: Option<&GroundSpec>) -> String {
        self.said_as(ground, true)
    }

    fn said_as(&self, ground: Option<&GroundSpec>, brief: bool) -> String {
        let mut s = if brief {
            format!("{:.1} t on the {} pad", self.load_kg / 1000.0, self.pad.name())
        } else {
            format!(
                "{:.1} t ({:.0} kN) on the {} pad (x {:.2} m, y {:.2} m)",
                self.load_kg / 1000.0,
                self.load_kg * G_M_S2 / 1000.0,
                self.pad.name(),
                self.at_m[0],
                self.at_m[1]
            )
        };
        if let Some(g) = ground {
            let kpa = pressure_kpa(self.load_kg, g.mat_m);
            s += &format!("; {kpa:.0} kPa under its {:.2} x {:.2} m mat", g.mat_m[0], g.mat_m[1]);
            match (g.allowable_kpa, self.over_allowable(Some(g))) {
                (_, Some((_, allowed, m))) => {
                    s += &format!(
                        ", MORE THAN THE {allowed:.0} kPa THE GROUND MAY BEAR: a mat of at least {:.2} x {:.2} m (spreading it as evenly) or a ground check",
                        m[0], m[1]
                    )
                }
                (Some(allowed), None) => s += &format!(", allowable {allowed:.0} kPa"),
                (None, None) => s += " (no allowable pressure given: ground allowable_kpa)",
            }
        }
        if self.tips {
            s += "; THE CRANE FILE'S MASSES PUT THE CENTRE OF GRAVITY OUTSIDE THE PADS: the crane would tip, so its [masses] or the chart are wrong";
        } else if self.pad_lifts {
            s += "; a pad lifts off (three carry the crane)";
        }
        s
    }

    /// Whether the ground's allowable pressure is exceeded, or the crane
    /// would tip: what the signer must check first.
    pub fn needs_checking(&self, ground: Option<&GroundSpec>) -> bool {
        self.tips || self.over_allowable(ground).is_some()
    }

    /// Where the pressure under its mat is more than the ground may bear:
    /// that pressure and the allowable (kPa), and the mat that would bear
    /// it ([`liftplan_core::outriggers::mat_bearing_m`], m).
    pub fn over_allowable(&self, ground: Option<&GroundSpec>) -> Option<(f64, f64, [f64; 2])> {
        let g = ground?;
        let (kpa, allowed) = (pressure_kpa(self.load_kg, g.mat_m), g.allowable_kpa?);
        (kpa > allowed)
            .then(|| (kpa, allowed, liftplan_core::outriggers::mat_bearing_m(self.load_kg, g.mat_m, allowed)))
    }
}

/// A move in words: its operation, signed amount, unit and the step's text
/// (`tower`: the radial joint is a trolley, not a luff).
pub fn describe(tower: bool, m: &Move) -> (String, f64, String, String) {
    let d = m.delta();
    match m.joint {
        Joint::Swing => {
            let deg = d.to_degrees();
            let dir = if deg >= 0.0 { "counter-clockwise" } else { "clockwise" };
            ("Swing".into(), deg, "°".into(), format!("swing {deg:+.1}° ({dir})"))
        }
        Joint::Radial if tower => {
            let op = if d >= 0.0 { "Trolley out" } else { "Trolley in" };
            (op.into(), d, "m".into(), format!("trolley {d:+.2} m"))
        }
        Joint::Radial => {
            let deg = d.to_degrees();
            let op = if deg >= 0.0 { "Luff up" } else { "Luff down" };
            (op.into(), deg, "°".into(), format!("{} {:.1}°", op.to_lowercase(), deg.abs()))
        }
        Joint::Hoist => {
            // Shorter rope raises the load: report the load's rise.
            let rise = -d;
            let op = if rise >= 0.0 { "Hoist up" } else { "Lower" };
            (op.into(), rise, "m".into(), format!("{} {:.2} m", op.to_lowercase(), rise.abs()))
        }
        Joint::Rotate => {
            let deg = d.to_degrees();
            let dir = if deg >= 0.0 { "counter-clockwise" } else { "clockwise" };
            ("Rotate load".into(), deg, "°".into(), format!("rotate load {deg:+.1}° ({dir})"))
        }
    }
}

/// The steps of a validated move list.
pub fn steps(task: &LiftTask, moves: &[Move], verdict: &Verdict) -> Vec<Step> {
    moves
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let (operation, amount, unit, text) = describe(task.crane.model.is_tower(), m);
            let check = verdict.moves.get(i);
            let tight = check.map(|c| &c.tightest);
            let util = check.map(|c| &c.max_utilisation);
            Step {
                n: i + 1,
                operation,
                amount,
                unit,
                text,
                end: m.to,
                radius_m: task.crane.radius_m(m.to.radial),
                load_height_m: task.crane.load_bottom_z(&m.to, &task.load),
                capacity_kg: util.and_then(|u| u.capacity_kg),
                chart_cell: util.and_then(|u| u.chart_cell.clone()),
                utilisation_pct: util.and_then(|u| u.utilisation_pct),
                min_clearance_m: check.map(|c| c.clearance_m).unwrap_or(f64::INFINITY),
                clearance_part: tight.map(|t| t.part.name().to_string()).unwrap_or_default(),
                clearance_to: tight.map(|t| t.nearest.object.clone()).unwrap_or_default(),
                clearance_at: tight.and_then(|t| t.nearest.at),
                required_clearance_m: tight.map(|t| t.required_m).unwrap_or(0.0),
                pads: pads_during(task, m),
            }
        })
        .collect()
}

/// The lift at a glance.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Summary {
    pub lift: String,
    /// The plan's revision ([`crate::revision`]): printed on every page of
    /// its PDF, and what `liftplan resume` is told to know the plan the crew
    /// follows. Empty until [`crate::run`] has the whole plan.
    #[serde(default)]
    pub revision: String,
    pub validated: bool,
    pub steps: usize,
    pub max_utilisation_pct: f64,
    pub max_utilisation_step: usize,
    pub max_utilisation_cell: String,
    pub critical: bool,
    /// Least clearance of the steps between the lift-off and the set-down
    /// (m); infinite where there are none, or nothing lay within the
    /// validator's search in any.
    #[serde(with = "distance_json")]
    pub min_clearance_m: f64,
    pub min_clearance_step: usize,
    pub min_clearance_what: String,
    pub swing_deg: f64,
    pub luff_or_trolley: f64,
    pub hoist_m: f64,
    pub rotate_deg: f64,
    /// What the load rests on at its set position ([`crate::validate::set_support`]).
    #[serde(default)]
    pub set_on: Option<crate::validate::SetSupport>,
    /// How far above its support the load may end and still rest on it (m).
    #[serde(default)]
    pub support_m: f64,
    /// Where the set position lies in a load's cut-out at pick (a lift that
    /// sets its load back, or where a later lift picks it up), how far the
    /// cut-out reaches below the load (m): the support's top that far down
    /// was taken with the scanned load, so a gap up to it is the scans', not
    /// the plan's.
    #[serde(default)]
    pub set_in_cutout_m: f64,
    /// What the lift passes over that the scans and the model do not show
    /// ([`crate::coverage::of_lift`]).
    #[serde(default)]
    pub coverage: Option<crate::coverage::Coverage>,
    /// The other lifts' loads this lift was planned and checked against
    /// ([`crate::other_loads`]).
    #[serde(default)]
    pub other_loads: Vec<String>,
    /// The other lifts' cranes, set up elsewhere, that stand within this
    /// lift's crane's reach ([`crate::other_cranes`]): not checked against
    /// it. Each in words.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub other_cranes: Vec<String>,
    /// The obstacles placed by hand this lift was planned and checked
    /// against, each in words ([`liftplan_core::obstacle::Obstacle::said`]).
    #[serde(default)]
    pub obstacles: Vec<String>,
    /// What the scans show of the load at its pick position, against its box
    /// ([`crate::load_scan::of_pick`]; `None` without scans).
    #[serde(default)]
    pub load_as_scanned: Option<crate::load_scan::LoadAsScanned>,
    /// The pick and set against the plant model's copy of the load, where
    /// one was left out of the model there ([`crate::model_copy::of_lift`]).
    #[serde(default)]
    pub against_model: Vec<crate::model_copy::AgainstModel>,
    /// Groups left out of the plant model that the lift passes through,
    /// where the scans show nothing of them ([`crate::model_copy::passes_left_out`]).
    #[serde(default)]
    pub passes_left_out: Vec<crate::model_copy::PassesLeftOut>,
    /// The lift's clearance (m), for saying them.
    #[serde(default)]
    pub clearance_m: f64,
    /// The overhead power lines this lift was planned and checked against,
    /// each in words ([`liftplan_core::power_line::PowerLine::said`]).
    #[serde(default)]
    pub power_lines: Vec<String>,
    /// Runs of line-like scan points near the crane that no power line
    /// given lies along ([`crate::wires`]): a line no one told the planner
    /// of, to be checked first.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub line_like: Vec<crate::wires::LineLike>,
    /// How far the plan keeps off them (m, `[plan] found_lines_approach_m`);
    /// 0: the lift's clearance only.
    #[serde(default, skip_serializing_if = "liftplan_core::is_zero")]
    pub line_like_kept_off_m: f64,
    /// The sling legs, where the lift gives their working load limit
    /// ([`liftplan_core::slings::check`]).
    #[serde(default)]
    pub slings: Option<liftplan_core::slings::SlingCheck>,
    /// The hoist rope's falls and the hook block against the hook load,
    /// where the crane file or the lift gives them
    /// ([`liftplan_core::reeving`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reeving: Option<liftplan_core::reeving::Reeving>,
    /// The step in which an outrigger pad carries the most, and that most
    /// ([`Step::pads`]).
    #[serde(default)]
    pub highest_pad: Option<(usize, StepPads)>,
    /// The steps in which the crane file's masses would tip the crane.
    #[serde(default)]
    pub pads_tip_in: Vec<usize>,
    /// The counterweight the pads' loads were worked out with (kg), and
    /// whose it is ([`LiftTask::counterweight_used_kg`]).
    #[serde(default)]
    pub pads_counterweight: Option<(f64, CounterweightFrom)>,
    /// The lift's counterweight and the one its chart configuration's name
    /// states, where they differ ([`LiftTask::counterweight_disagrees_kg`]).
    #[serde(default)]
    pub counterweight_disagrees_kg: Option<[f64; 2]>,
    /// The lift's chart configuration, for saying whose counterweight.
    #[serde(default)]
    pub chart_config: String,
    /// The cell of the chart's sheet that states the counterweight the
    /// chart's is ([`CounterweightFrom::ChartSheet`]), for saying where.
    #[serde(default)]
    pub chart_counterweight_cell: Option<String>,
    /// What stands in the ground under the outrigger pads
    /// ([`crate::validate::under_pads`]).
    #[serde(default)]
    pub under_pads: Vec<crate::validate::UnderPad>,
    /// For a critical lift, where its crane could stand for it not to be
    /// ([`crate::positions::Found::not_critical_said`]), in words.
    #[serde(default)]
    pub not_critical_at: Option<String>,
    /// The lift's mats and ground, for saying the pressure.
    #[serde(default)]
    pub ground: Option<GroundSpec>,
}

/// Serde for a distance that may be infinite (nothing within the
/// validator's search): JSON has no infinity, so it is written as null and
/// read back as infinite (a plan whose distance was written so could not be
/// read by the docs stage).
mod distance_json {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        if v.is_finite() { s.serialize_f64(*v) } else { s.serialize_none() }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::INFINITY))
    }
}

/// Where the set-down ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SetDown<'a> {
    /// On its support: within `support_m` under the load.
    Rests(&'a crate::validate::SetSupport),
    /// Above the nearest thing under it: the rest of the lowering is not
    /// planned.
    Above(&'a crate::validate::SetSupport),
    /// Over nothing modelled within [`crate::validate::SUPPORT_SEARCH_M`].
    OverNothing,
}

impl Summary {
    /// Where the set-down ends ([`Summary::set_on`], [`Summary::support_m`];
    /// the support's gap is known to 2 mm).
    pub fn set_down(&self) -> SetDown<'_> {
        match &self.set_on {
            Some(s) if s.gap_m <= self.support_m + self.set_in_cutout_m + 2e-3 => SetDown::Rests(s),
            Some(s) => SetDown::Above(s),
            None => SetDown::OverNothing,
        }
    }

    /// [`Summary::set_down`] for the run's line.
    pub fn set_down_line(&self) -> String {
        let tips = |s: &crate::validate::SetSupport| match s.cog_said() {
            Some(said) if s.tips() => format!(", BUT {said}"),
            _ => String::new(),
        };
        match self.set_down() {
            SetDown::Rests(s) => format!("set down on {}{}", s.object, tips(s)),
            SetDown::Above(s) => format!(
                "SET-DOWN ENDS {:.2} m ABOVE {}: lowering it further is not part of this plan{}",
                s.gap_m,
                s.object,
                tips(s)
            ),
            SetDown::OverNothing => format!(
                "NOTHING MODELLED UNDER THE LOAD at its set position (within {:.0} m): check its support on site",
                crate::validate::SUPPORT_SEARCH_M
            ),
        }
    }

    /// [`Summary::other_loads`] said, if there are any.
    pub fn other_loads_said(&self) -> Option<String> {
        (!self.other_loads.is_empty()).then(|| {
            format!(
                "planned and checked with the other lifts' loads where they stand during this one (lifts are made in the order the project lists them): {}",
                self.other_loads.join("; ")
            )
        })
    }

    /// [`Summary::other_cranes`] said, if there are any.
    pub fn other_cranes_said(&self) -> Option<String> {
        (!self.other_cranes.is_empty()).then(|| {
            format!(
                "NOT CHECKED AGAINST THE OTHER LIFTS' CRANES, set up where this lift's could meet them: {}; each lift is planned with its own crane alone, so where such a crane stands on site during this lift, keep the two apart (a lift plan of both, the crews' own rules) or move it",
                self.other_cranes.join("; ")
            )
        })
    }

    /// [`Summary::other_cranes_said`] for the run's output.
    pub fn other_cranes_line(&self) -> Option<String> {
        self.other_cranes_said().map(|said| format!("lift {}: {said}", self.lift))
    }

    /// [`Summary::obstacles`] said, if there are any.
    pub fn obstacles_said(&self) -> Option<String> {
        (!self.obstacles.is_empty()).then(|| {
            format!(
                "planned and checked with the obstacles placed by hand in the project file (on site, not in the scans or the model): {}",
                self.obstacles.join("; ")
            )
        })
    }

    /// [`Summary::other_loads_said`] for the run's output.
    pub fn other_loads_line(&self) -> Option<String> {
        self.other_loads_said().map(|said| format!("lift {}: {said}", self.lift))
    }

    /// [`Summary::slings`] for the run's output.
    pub fn slings_line(&self) -> Option<String> {
        self.slings.as_ref().map(|c| format!("lift {}: sling legs: {}", self.lift, c.said()))
    }

    /// [`Summary::reeving`] for the run's output.
    pub fn reeving_line(&self) -> Option<String> {
        self.reeving.as_ref().map(|r| format!("lift {}: reeving: {}", self.lift, r.said()))
    }

    /// [`Summary::power_lines`] for the run's output, in one line.
    pub fn power_lines_line(&self) -> Option<String> {
        (!self.power_lines.is_empty()).then(|| format!("lift {}: {}", self.lift, self.power_lines.join("; ")))
    }

    /// [`Summary::line_like`] in words, for the run's output and the
    /// sign-off page.
    pub fn line_like_said(&self) -> Option<String> {
        (!self.line_like.is_empty()).then(|| {
            format!(
                "NOT A GIVEN POWER LINE: {}, near the crane, where no power line given runs: CHECK WHAT {} (an overhead conductor, a guy wire, a cable); {}",
                self.line_like.iter().map(crate::wires::LineLike::said).collect::<Vec<_>>().join("; "),
                if self.line_like.len() == 1 { "IT IS" } else { "EACH IS" },
                if self.line_like_kept_off_m > 0.0 {
                    format!(
                        "the plan keeps every part of the crane, its rope and its load {:.2} m off {}, as off a power line of unknown voltage ([plan] found_lines_approach_m), where the scans saw {} (from its ends' chord down to its lowest point, not beyond its ends): give a line as a [[power_line]] for its own approach distance, sag and swing",
                        self.line_like_kept_off_m,
                        if self.line_like.len() == 1 { "it" } else { "each" },
                        if self.line_like.len() == 1 { "it" } else { "them" }
                    )
                } else {
                    "the plan keeps the lift's clearance from those points, as from every scan point, not a power line's approach distance: give a line as a [[power_line]] for it to be kept off, or set [plan] found_lines_approach_m to keep off every such run".to_string()
                }
            )
        })
    }

    /// [`Summary::line_like_said`] for the run's output.
    pub fn line_like_line(&self) -> Option<String> {
        self.line_like_said().map(|said| format!("lift {}: {said}", self.lift))
    }

    /// [`Summary::obstacles_said`] for the run's output.
    pub fn obstacles_line(&self) -> Option<String> {
        self.obstacles_said().map(|said| format!("lift {}: {said}", self.lift))
    }

    /// [`Summary::load_as_scanned`]'s line, for the run's output.
    pub fn load_as_scanned_line(&self) -> Option<String> {
        self.load_as_scanned.as_ref().map(|l| format!("lift {}: {}", self.lift, l.said()))
    }

    /// [`Summary::against_model`], a line each, and
    /// [`Summary::passes_left_out`] in one.
    pub fn against_model_lines(&self) -> impl Iterator<Item = String> + '_ {
        self.against_model
            .iter()
            .map(|a| a.said())
            .chain(crate::model_copy::PassesLeftOut::said(&self.passes_left_out, self.clearance_m))
            .map(|said| format!("lift {}: {said}", self.lift))
    }

    /// [`Summary::highest_pad`] in words: the most a pad carries, in which
    /// step, and any step where the crane would tip.
    pub fn pads_said(&self) -> Option<String> {
        self.pads_said_as(false)
    }

    /// [`Summary::pads_said`] in brief ([`StepPads::said_briefly`]), for
    /// the sign-off page.
    pub fn pads_said_briefly(&self) -> Option<String> {
        self.pads_said_as(true)
    }

    fn pads_said_as(&self, brief: bool) -> Option<String> {
        let (n, p) = self.highest_pad?;
        let tips = match self.pads_tip_in.as_slice() {
            [] => String::new(),
            [one] => format!(" (the crane would tip in step {one})"),
            many => format!(" (the crane would tip in {} steps)", many.len()),
        };
        let ground = self.ground.as_ref();
        let counterweight = self.pads_counterweight_said().map(|c| format!(", with {c}")).unwrap_or_default();
        Some(if brief {
            // The counterweight only where it is to be checked (the cover
            // gives it always).
            let counterweight = if self.counterweight_disagrees_kg.is_some() { counterweight.as_str() } else { "" };
            format!(
                "outrigger pads at their most (an estimate from the crane file's masses{counterweight}): step {n}{tips}, {}",
                p.said_briefly(ground)
            )
        } else {
            format!(
                "outrigger pads (estimated from the crane file's masses{counterweight}) at their most: in step {n}{tips}, {}; the crane manufacturer's outrigger loads govern",
                p.said(ground)
            )
        })
    }

    /// The counterweight the pads' estimate used, and whose it is: "the
    /// lift's 70.0 t counterweight", or the crane file's, which the lift can
    /// change.
    pub fn pads_counterweight_said(&self) -> Option<String> {
        let (kg, from) = self.pads_counterweight?;
        let t = kg / 1000.0;
        // Whose the chart's counterweight is: its configuration's name's,
        // or its sheet's cell's.
        let charts = |upper: bool| match (&self.chart_counterweight_cell, upper) {
            (Some(cell), false) => format!("its chart's sheet states ({cell})"),
            (Some(cell), true) => format!("ITS CHART'S SHEET STATES ({cell})"),
            (None, false) => format!("its chart configuration '{}' names", self.chart_config),
            (None, true) => format!("ITS CHART CONFIGURATION '{}' NAMES", self.chart_config),
        };
        Some(match (from, self.counterweight_disagrees_kg) {
            (CounterweightFrom::Lift, Some([_, named])) => format!(
                "the lift's {t:.1} t counterweight, NOT THE {:.1} t {}: CHECK crane counterweight_t against what is rigged",
                named / 1000.0,
                charts(true)
            ),
            (CounterweightFrom::Lift, None) => format!("the lift's {t:.1} t counterweight"),
            (CounterweightFrom::ChartConfig | CounterweightFrom::ChartSheet, _) => {
                format!("the {t:.1} t counterweight {}", charts(false))
            }
            (CounterweightFrom::CraneFile, _) => {
                format!("the crane file's {t:.1} t counterweight (crane counterweight_t sets the one rigged)")
            }
        })
    }

    /// [`Summary::under_pads`] in words, where anything is there.
    pub fn under_pads_said(&self) -> Option<String> {
        (!self.under_pads.is_empty()).then(|| {
            format!(
                "IN THE GROUND UNDER THE OUTRIGGER PADS: {}: CHECK what it is and what it bears before the crane is set up (a buried pipe, duct, culvert, pit or foundation edge under a loaded pad can give way)",
                self.under_pads.iter().map(|u| u.said()).collect::<Vec<_>>().join("; ")
            )
        })
    }

    /// [`Summary::not_critical_at`] for the run's output.
    pub fn not_critical_line(&self) -> Option<String> {
        self.not_critical_at.as_ref().map(|said| format!("lift {}: critical; {said}", self.lift))
    }

    /// [`Summary::under_pads_said`] for the run's output.
    pub fn under_pads_line(&self) -> Option<String> {
        self.under_pads_said().map(|said| format!("lift {}: {said}", self.lift))
    }

    /// [`Summary::pads_said`] for the run's output.
    pub fn pads_line(&self) -> Option<String> {
        self.pads_said().map(|said| format!("lift {}: {said}", self.lift))
    }

    /// [`Summary::coverage`]'s line, for the run's output.
    pub fn coverage_line(&self) -> Option<String> {
        self.coverage.as_ref().map(|c| format!("lift {}: {}", self.lift, c.line()))
    }

    pub fn line(&self) -> String {
        format!(
            "lift {}: plan {}, {} steps, validated; max utilisation {:.0} % (step {}, {}){}; {}; {}",
            self.lift,
            self.revision,
            self.steps,
            self.max_utilisation_pct,
            self.max_utilisation_step,
            self.max_utilisation_cell,
            if self.critical { ", CRITICAL LIFT" } else { "" },
            if self.min_clearance_m.is_finite() {
                format!(
                    "min clearance {:.2} m (step {}, {})",
                    self.min_clearance_m, self.min_clearance_step, self.min_clearance_what
                )
            } else if self.steps <= 2 {
                "no step between the lift-off and the set-down".to_string()
            } else {
                "nothing within the validator's search in any step between the lift-off and the set-down".to_string()
            },
            self.set_down_line()
        )
    }
}

pub fn summary(task: &LiftTask, steps: &[Step], verdict: &Verdict) -> Summary {
    let mut s = Summary {
        lift: task.id.clone(),
        revision: String::new(),
        validated: verdict.ok,
        steps: steps.len(),
        max_utilisation_pct: 0.0,
        max_utilisation_step: 0,
        max_utilisation_cell: String::new(),
        critical: false,
        min_clearance_m: f64::INFINITY,
        min_clearance_step: 0,
        min_clearance_what: String::new(),
        swing_deg: 0.0,
        luff_or_trolley: 0.0,
        hoist_m: 0.0,
        rotate_deg: 0.0,
        set_on: None,
        support_m: 0.0,
        set_in_cutout_m: 0.0,
        coverage: None,
        load_as_scanned: None,
        other_loads: Vec::new(),
        other_cranes: Vec::new(),
        obstacles: Vec::new(),
        against_model: Vec::new(),
        passes_left_out: Vec::new(),
        clearance_m: task.clearance_m,
        power_lines: Vec::new(),
        line_like: Vec::new(),
        line_like_kept_off_m: 0.0,
        slings: None,
        reeving: None,
        highest_pad: None,
        pads_tip_in: Vec::new(),
        pads_counterweight: task.counterweight_used_kg(),
        counterweight_disagrees_kg: task.counterweight_disagrees_kg(),
        chart_config: task.chart_config.clone(),
        chart_counterweight_cell: task
            .chart_counterweight_kg()
            .filter(|(_, from)| *from == CounterweightFrom::ChartSheet)
            .and_then(|_| task.chart_sheet_counterweight.as_ref().map(|s| s.cell.clone())),
        under_pads: Vec::new(),
        not_critical_at: None,
        ground: task.ground,
    };
    // Lift-off and set-down touch the supports by design; report the travel.
    let landing = crate::landing_moves(task, steps.len());
    for (st, landing) in steps.iter().zip(landing) {
        if let Some(p) = st.pads
            && s.highest_pad.is_none_or(|(_, h)| p.load_kg > h.load_kg)
        {
            s.highest_pad = Some((st.n, p));
        }
        if st.pads.is_some_and(|p| p.tips) {
            s.pads_tip_in.push(st.n);
        }
        if let Some(u) = st.utilisation_pct
            && u > s.max_utilisation_pct
        {
            s.max_utilisation_pct = u;
            s.max_utilisation_step = st.n;
            s.max_utilisation_cell = st.chart_cell.clone().unwrap_or_default();
        }
        if !landing && st.min_clearance_m < s.min_clearance_m {
            s.min_clearance_m = st.min_clearance_m;
            s.min_clearance_step = st.n;
            s.min_clearance_what = format!("{} to {}", st.clearance_part, st.clearance_to);
        }
        match st.operation.as_str() {
            "Swing" => s.swing_deg += st.amount.abs(),
            "Rotate load" => s.rotate_deg += st.amount.abs(),
            "Hoist up" | "Lower" => s.hoist_m += st.amount.abs(),
            _ => s.luff_or_trolley += st.amount.abs(),
        }
    }
    s.critical = s.max_utilisation_pct > task.critical_pct;
    s
}

/// A text field of the steps' CSV as a spreadsheet opening the file is to
/// show it: quoted where it holds a comma, a quote or a line break, and,
/// where it starts as a formula does (`=`, `+`, `-`, `@`, a tab or a
/// carriage return), with an apostrophe before it, so that it is shown as
/// the words it is, not worked out (a plant model's group named
/// `=HYPERLINK(...)`, as a model's file may name one, would be a link in the
/// crew's spreadsheet, and `-2+3` a number).
fn csv_field(s: &str) -> String {
    let s = if s.starts_with(['=', '+', '-', '@', '\t', '\r']) { format!("'{s}") } else { s.to_string() };
    if s.contains([',', '"', '\n', '\r']) { format!("\"{}\"", s.replace('"', "\"\"")) } else { s }
}

/// The steps as CSV, each with the crane's configuration at its end under
/// the names a lift's `resume_from` takes (`swing_deg`, `luff_deg` or, for
/// a tower crane, `trolley_m`, `hoist_m`), so a lift stopped after a step
/// is resumed from that row. Every row ends with the plan's revision
/// ([`crate::revision`]), so that a row read on its own (into a crane's
/// control, a spreadsheet) still names the plan it belongs to.
pub fn to_csv(steps: &[Step], tower: bool, revision: &str) -> String {
    let mut out = format!(
        "step,operation,amount,unit,swing_deg,{},hoist_m,load_yaw_deg,radius_m,load_height_m,capacity_kg,chart_cell,utilisation_pct,min_clearance_m,clearance_part,clearance_to,max_pad_kg,max_pad,plan\n",
        if tower { "trolley_m" } else { "luff_deg" }
    );
    for s in steps {
        let radial = if tower { s.end.radial } else { s.end.radial.to_degrees() };
        let opt = |v: Option<f64>, p: usize| v.map(|x| format!("{x:.p$}")).unwrap_or_default();
        out.push_str(&format!(
            "{},{},{:.3},{},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{},{},{},{:.3},{},{},{},{},{}\n",
            s.n,
            csv_field(&s.operation),
            s.amount,
            s.unit,
            s.end.swing_rad.to_degrees(),
            radial,
            s.end.hoist_m,
            s.end.load_yaw_rad.to_degrees(),
            s.radius_m,
            s.load_height_m,
            opt(s.capacity_kg, 0),
            csv_field(s.chart_cell.as_deref().unwrap_or("")),
            opt(s.utilisation_pct, 1),
            s.min_clearance_m,
            csv_field(&s.clearance_part),
            csv_field(&s.clearance_to),
            opt(s.pads.map(|p| p.load_kg), 0),
            s.pads.map(|p| p.pad.name()).unwrap_or_default(),
            csv_field(revision),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A name in the steps' CSV reads back as one field, as written, where
    /// it holds commas, quotes or line breaks, and a spreadsheet shows one
    /// that starts as a formula does as words (an apostrophe before it).
    #[test]
    fn csv_fields_read_back_as_words() {
        let names = [
            ("/PIPE-RACK-2", "/PIPE-RACK-2"),
            ("rack, \"north\"\r\nbay", "rack, \"north\"\r\nbay"),
            ("=HYPERLINK(\"http://example.com\",\"x\")", "'=HYPERLINK(\"http://example.com\",\"x\")"),
            ("+1", "'+1"),
            ("-2+3", "'-2+3"),
            ("@SUM(A1)", "'@SUM(A1)"),
            ("\t=1", "'\t=1"),
            ("\r=1", "'\r=1"),
        ];
        let line: Vec<String> = names.iter().map(|(name, _)| csv_field(name)).collect();
        let csv = format!("{}\n", line.join(","));
        let mut reader = csv::ReaderBuilder::new().has_headers(false).from_reader(csv.as_bytes());
        let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
        assert_eq!(rows.len(), 1, "{csv}");
        let read: Vec<&str> = rows[0].iter().collect();
        assert_eq!(read, names.iter().map(|(_, shown)| *shown).collect::<Vec<_>>(), "{csv}");
    }

    /// The words "counter-clockwise" and "clockwise" say which way the boom
    /// and the load turn, seen from above, as the crane's kinematics turn
    /// them (a rigger reads the words, not the sign).
    #[test]
    fn turn_directions_are_the_kinematics_seen_from_above() {
        let task = crate::test_lift("ac-700");
        let c = task.start();
        for (joint, step) in [(Joint::Swing, 0.3), (Joint::Swing, -0.3), (Joint::Rotate, 0.3), (Joint::Rotate, -0.3)] {
            let mut to = c.to_array();
            to[joint.index()] += step;
            let m = Move { joint, from: c, to: Config::from_array(to) };
            let (_, _, _, text) = describe(task.crane.model.is_tower(), &m);
            // The boom's direction for a swing, the load's long axis for a rotation.
            let dir = |k: &Config| match joint {
                Joint::Swing => task.crane.boom_dir(k.swing_rad),
                _ => task.crane.load_obb(k, &task.load).axis(0),
            };
            let turn_z = dir(&m.from).cross(&dir(&m.to)).z;
            let want = if turn_z > 0.0 { "(counter-clockwise)" } else { "(clockwise)" };
            assert!(text.ends_with(want), "{joint:?} {step}: '{text}' but the turn's z is {turn_z}");
        }
    }

    /// A swing through the bearing at which a pad carries most: the most
    /// is found between the move's ends, to within the sampling's bound of
    /// a fine search; a hoist, which moves nothing that weighs on the pads
    /// but along the rope, reads its ends. How it is said, with mats the
    /// ground bears and mats it does not.
    #[test]
    fn the_pads_most_is_found_between_a_moves_ends_and_said() {
        let task = crate::test_lift("ac-700");
        // The crane weighs its hoist rope (3.9 kg/m), counted on the block's
        // 10 falls over its 110 m travel: the lift gives no falls.
        use liftplan_core::reeving::{LongestRope, RopeWeight};
        assert_eq!(task.rope_weight, Some(RopeWeight::new(3.9, 10, false, 110.0, LongestRope::Travel)));
        let at = |deg: f64| Config { swing_rad: deg.to_radians(), ..task.start() };
        // The rear-heavy crane's counterweight over the rear left pad of its
        // square spread: swing -45°.
        let m = Move { joint: Joint::Swing, from: at(-80.0), to: at(-10.0) };
        let most = pads_during(&task, &m).unwrap();
        assert_eq!(most.pad, Pad::RearLeft);
        let fine =
            (0..=70_000).map(|i| pads_at(&task, &at(-80.0 + i as f64 * 1e-3)).unwrap().load_kg).fold(0.0, f64::max);
        let ends = pads_at(&task, &m.from).unwrap().load_kg.max(pads_at(&task, &m.to).unwrap().load_kg);
        assert!(fine > ends + 1000.0, "{fine} {ends}");
        assert!(most.load_kg <= fine + 1e-6 && most.load_kg > fine * (1.0 - 1e-6), "{most:?} {fine}");
        // The rope is counted at its longest in the gross load: the rear pad
        // carries most with the least that may hang (no rope), not with the
        // gross.
        let gross = task.pad_loads(&at(-45.0)).unwrap().highest().1;
        let least = task.pad_loads_hanging(&at(-45.0), task.least_hanging_kg()).unwrap().highest().1;
        assert!(least > gross + 100.0 && pads_at(&task, &at(-45.0)).unwrap().load_kg == least, "{least} {gross}");
        // The chart's deductions (somewhere on the crane, the lift does not
        // say where) weigh least on a rear pad at the hook: its most is the
        // one without them.
        // (Without the rope, whose least is the same case.)
        let mut bare = task.clone();
        bare.rope_weight = None;
        let bare_most = pads_during(&bare, &m).unwrap();
        let mut deducting = bare.clone();
        deducting.deductions_kg = 8000.0;
        let rear = pads_during(&deducting, &m).unwrap();
        assert_eq!((rear.pad, rear.load_kg), (bare_most.pad, bare_most.load_kg));
        let at_hook = deducting.pad_loads(&at(-45.0)).unwrap().highest().1;
        assert!(at_hook < bare_most.load_kg - 1000.0, "{at_hook} {bare_most:?}");
        let mut up = m.from.to_array();
        up[Joint::Hoist.index()] -= 3.0;
        let hoist = Move { joint: Joint::Hoist, from: m.from, to: Config::from_array(up) };
        assert_eq!(pads_during(&task, &hoist).unwrap().load_kg, pads_at(&task, &m.from).unwrap().load_kg);
        // Said, with the pressure under mats the ground bears, or not.
        let kpa = pressure_kpa(most.load_kg, [3.0, 3.0]);
        let bears = GroundSpec { mat_m: [3.0, 3.0], allowable_kpa: Some(kpa + 1.0) };
        assert!(!most.needs_checking(Some(&bears)));
        assert!(
            most.said(Some(&bears))
                .ends_with(&format!("; {kpa:.0} kPa under its 3.00 x 3.00 m mat, allowable {:.0} kPa", kpa + 1.0))
        );
        let not = GroundSpec { allowable_kpa: Some(kpa - 1.0), ..bears };
        assert!(most.needs_checking(Some(&not)));
        let m = liftplan_core::outriggers::mat_bearing_m(most.load_kg, [3.0, 3.0], kpa - 1.0);
        assert!(m[0] > 3.0 && pressure_kpa(most.load_kg, m) <= kpa - 1.0, "{m:?}");
        assert!(
            most.said(Some(&not)).ends_with(&format!(
                ", MORE THAN THE {:.0} kPa THE GROUND MAY BEAR: a mat of at least {:.2} x {:.2} m (spreading it as evenly) or a ground check",
                kpa - 1.0,
                m[0],
                m[1]
            )),
            "{}",
            most.said(Some(&not))
        );
        let unknown = GroundSpec { allowable_kpa: None, ..bears };
        assert!(!most.needs_checking(Some(&unknown)) && !most.needs_checking(None));
        assert!(most.said(Some(&unknown)).ends_with("(no allowable pressure given: ground allowable_kpa)"));
        // A tower crane has no outriggers.
        let tower = crate::test_lift("tower-hh-60");
        let t = tower.start();
        assert!(
            pads_during(&tower, &Move { joint: Joint::Swing, from: t, to: Config { swing_rad: 1.0, ..t } }).is_none()
        );
    }
}
