//! Where else a mobile crane could stand, for a lift refused where the lift
//! sets it up (the chart does not carry the load at the pick or the set,
//! the carrier or outriggers meet something, the boom meets something at
//! the pick or the set, or no path is found): the
//! nearest position from which its chart configuration carries the gross
//! load at both, the crane stands clear on level ground, and the whole lift
//! plans and passes the validator. For a lift that plans but above its
//! `critical_pct`, the same search names the nearest position where it
//! would not be critical ([`Sought::NotCritical`]): the chart within
//! `critical_pct` at the pick and the set, the planned lift within it
//! throughout (positions a grid step from the lift's own are tried too).
//!
//! Positions are tried on a grid of [`GRID_M`] within the configuration's
//! farthest carrying radius of both the pick and the set, nearest to the
//! lift's own position first (those within the lift's `critical_pct` before
//! those above it), at the lift's heading first and then turned in steps of
//! 45° (not where the lift gives a swing range, which turns with it). Each
//! is checked, at the height of the ground scanned there, as the planner
//! checks the lift before it searches: the set-up (level ground,
//! carrier and outriggers clear), the lift-off and the set-down by the
//! validator, and where the search would start and end by the planner's
//! checker (online, no tables built). The first few that pass, [`APART_M`]
//! or more apart, are planned in full with the lift's seed and settings
//! ([`crate::plan_lift`]), so that one said to plan plans again, the same,
//! when the lift file is given it; a refusal there searches no further.
//!
//! What the outrigger pads bear on is looked at too, as for the lift's own
//! position: what the plant model or the scans hold in the ground under
//! them ([`crate::validate::under_pads`]) and the pressure under their mats
//! against the lift's `ground.allowable_kpa` (at the pick and the set as a
//! position is looked at, through the whole lift once planned). A position
//! where either is to be checked is passed over for one where neither is,
//! and named with it only where none such plans (the few nearest looked
//! at, as many as are planned in full).
//!
//! Words only: nothing here moves a lift's crane. The engineer puts the
//! position in the lift file and the lift is planned and checked anew. What
//! the site holds beyond the scans and the plant model (access, the ground's
//! strength, what is buried that neither holds) is not known here, and is
//! said to be checked.

use crate::steps::{StepPads, pads_at};
use crate::validate::UnderPad;
use crate::{Settings, Site};
use liftplan_core::capacity::ChartConfig;
use liftplan_core::crane::Placement;
use liftplan_core::lift::{GroundSpec, LiftTask};

/// The grid positions are tried on (m).
pub const GRID_M: f64 = 0.5;
/// The most grid positions looked at, each at up to [`HEADINGS`] headings:
/// a site crowded around the pick and the set is not searched for ever.
pub const MOST_LOOKED_AT: usize = 5000;
/// How many positions whose set-up is clear are planned in full, at most.
pub const MOST_PLANNED: usize = 3;
/// How far apart positions planned in full stand, at least, and from the
/// lift's own (m): the next position along a wall that refused the last is
/// refused for it too.
pub const APART_M: f64 = 3.0;
/// The carrier's headings tried at each position, from the lift's (°);
/// the lift's alone where it gives a permitted swing range.
pub const HEADINGS: [f64; 8] = [0.0, 90.0, 180.0, 270.0, 45.0, 135.0, 225.0, 315.0];

/// A position the crane was tried at.
#[derive(Debug, Clone, PartialEq)]
pub struct Tried {
    pub x_m: f64,
    pub y_m: f64,
    /// Carrier heading, as the lift file gives it (°).
    pub heading_deg: f64,
    pub ground_z_m: f64,
    /// Whether `ground_z_m` is the ground scanned there (else the lift's).
    pub ground_scanned: bool,
    /// From the lift's own position (m).
    pub moved_m: f64,
    /// Utilisation and working radius at the pick and at the set.
    pub pick: (f64, f64),
    pub set: (f64, f64),
    /// Above the lift's `critical_pct` at either.
    pub critical: bool,
    /// The most loaded pad: at the pick and the set as the position is
    /// looked at, through the whole lift once it is planned there (none
    /// where the crane file gives no outrigger geometry or masses).
    pub pads: Option<StepPads>,
    /// The lift's mats and ground, for the pads' pressure.
    pub ground: Option<GroundSpec>,
    /// What the plant model or the scans hold in the ground under its pads.
    pub under_pads: Vec<UnderPad>,
    pub outcome: Outcome,
}

/// What came of a position whose set-up is clear.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// The lift plans there and passes the validator, in so many steps, at
    /// most so much of the chart's capacity (%).
    Planned { steps: usize, most_pct: f64 },
    /// Sought where the lift is not critical: it plans there, but above its
    /// `critical_pct` (its most, %, and in which step).
    Critical { most_pct: f64, step: usize },
    /// Why the lift was refused there.
    Refused(String),
    /// Not planned: another position planned before it with nothing of its
    /// pads to check.
    NotPlanned,
}

impl Tried {
    /// The planned lift's steps, where it plans there.
    pub fn planned_steps(&self) -> Option<usize> {
        match self.outcome {
            Outcome::Planned { steps, .. } => Some(steps),
            _ => None,
        }
    }

    /// Whether what its pads bear on is to be checked: something in the
    /// ground under them, more pressure under a mat than the ground may
    /// bear, or the crane file's masses tipping the crane.
    pub fn pads_to_check(&self) -> bool {
        !self.under_pads.is_empty() || self.pads.is_some_and(|p| p.needs_checking(self.ground.as_ref()))
    }

    /// What is to be checked of its pads, in brief: "IN THE GROUND UNDER
    /// ITS PADS: DUCT 0.30 m below ...; 230 kPa UNDER THE REAR RIGHT PAD'S
    /// 2.50 x 2.50 m MAT, MORE THAN THE 200 kPa THE GROUND MAY BEAR".
    fn pads_to_check_said(&self) -> String {
        let mut said = Vec::new();
        if !self.under_pads.is_empty() {
            said.push(format!(
                "IN THE GROUND UNDER ITS PADS: {}",
                self.under_pads.iter().map(|u| u.said()).collect::<Vec<_>>().join("; ")
            ));
        }
        if let Some(p) = self.pads {
            if let (Some(g), Some((kpa, allowed, m))) = (self.ground, p.over_allowable(self.ground.as_ref())) {
                said.push(format!(
                        "{kpa:.0} kPa UNDER THE {} PAD'S {:.2} x {:.2} m MAT ({:.1} t, an estimate), MORE THAN THE {allowed:.0} kPa THE GROUND MAY BEAR (a mat of at least {:.2} x {:.2} m)",
                        p.pad.name().to_uppercase(),
                        g.mat_m[0],
                        g.mat_m[1],
                        p.load_kg / 1000.0,
                        m[0],
                        m[1]
                    ));
            }
            if p.tips {
                said.push("THE CRANE FILE'S MASSES PUT THE CENTRE OF GRAVITY OUTSIDE THE PADS".into());
            }
        }
        said.join("; ")
    }

    /// Where it was refused, and the first clause of why.
    fn refused_said(&self) -> Option<String> {
        match &self.outcome {
            Outcome::Refused(why) => Some(format!("at {}: {}", self.where_said(), first_clause(why))),
            _ => None,
        }
    }

    fn where_said(&self) -> String {
        format!(
            "position_m = [{:.1}, {:.1}], heading_deg = {:.0}, ground_z_m = {:.2} ({}; {:.1} m from the lift's position)",
            self.x_m,
            self.y_m,
            self.heading_deg,
            self.ground_z_m,
            if self.ground_scanned { "the ground scanned there" } else { "the lift's: no ground is scanned there" },
            self.moved_m
        )
    }

    fn carries_said(&self) -> String {
        format!(
            "pick {:.0} % at {:.2} m, set {:.0} % at {:.2} m{}",
            self.pick.0,
            self.pick.1,
            self.set.0,
            self.set.1,
            if self.critical { ": a critical lift there, above its critical_pct" } else { "" }
        )
    }
}

/// What a search seeks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sought {
    /// For a lift refused where its crane stands: a position where it plans.
    Plans,
    /// For a lift that plans above its `critical_pct`: a position where it
    /// plans within it, at both ends and through the whole lift.
    NotCritical,
}

/// What the search found.
#[derive(Debug, Clone, PartialEq)]
pub enum Found {
    /// The lift gives its pick or set as a crane configuration, or its crane
    /// is a tower crane: no position is searched.
    NotSearched,
    /// The configuration carries the gross load at no radius, or at none
    /// that reaches both the pick and the set (the farthest, m).
    OutOfReach { farthest_m: Option<f64> },
    /// Positions carry it at both, but none of those looked at stands clear
    /// (how many were looked at; whether the lift gives areas the crane
    /// may stand in, `crane_stands_in`).
    NoClearSetUp { looked_at: usize, in_areas: bool },
    /// The positions planned in full, in the order tried; the last planned,
    /// if any did.
    Tried(Vec<Tried>),
}

impl Found {
    /// The position named: the first where the lift plans and its pads are
    /// not to be checked, else the first where it plans (its index among
    /// those tried).
    pub fn chosen(&self) -> Option<usize> {
        let Found::Tried(tried) = self else { return None };
        let planned = |t: &&Tried| t.planned_steps().is_some();
        let first = |clean: bool| tried.iter().position(|t| planned(&t) && (!clean || !t.pads_to_check()));
        first(true).or_else(|| first(false))
    }

    /// The words appended to the refusal.
    pub fn said(&self, chart_name: &str) -> String {
        match self {
            Found::NotSearched => String::new(),
            Found::OutOfReach { farthest_m: None } => String::new(),
            Found::OutOfReach { farthest_m: Some(r) } => format!(
                "; no crane position carries it at both: the pick and the set lie more than twice {r:.2} m apart"
            ),
            Found::NoClearSetUp { looked_at, in_areas } => format!(
                "; of the {looked_at} crane positions nearest the lift's within the reach of '{}' of both the pick and the set, none stands clear (its carrier and outriggers {}on ground level within {:.2} m, the boom and the load clear at the lift-off and the set-down)",
                chart_name,
                if *in_areas { "within an area it may stand in (crane_stands_in), " } else { "" },
                crate::validate::SET_UP_LEVEL_TOLERANCE_M
            ),
            Found::Tried(tried) => match self.chosen() {
                Some(k) => format!(
                    "; the crane set up at {} carries it at both ({}), and there {}",
                    tried[k].where_said(),
                    tried[k].carries_said(),
                    planned_said(tried, k)
                ),
                None => {
                    let refused: Vec<String> = tried.iter().filter_map(Tried::refused_said).collect();
                    format!(
                        "; at the {} crane position(s) nearest the lift's where it carries the load at both and stands clear, the lift is refused too: {}",
                        refused.len(),
                        refused.join("; ")
                    )
                }
            },
        }
    }

    /// For a critical lift searched [`Sought::NotCritical`]: where it is
    /// not, or at how many positions looked at it is critical or refused
    /// too.
    pub fn not_critical_said(&self, critical_pct: f64) -> Option<String> {
        match self {
            Found::NotSearched | Found::OutOfReach { .. } => None,
            Found::NoClearSetUp { looked_at: 0, .. } => Some(format!(
                "its chart carries the load within {critical_pct:.0} % at both the pick and the set from no crane position"
            )),
            Found::NoClearSetUp { looked_at, .. } => Some(format!(
                "of the {looked_at} crane positions nearest the lift's where its chart carries the load within {critical_pct:.0} % at the pick and the set, none stands clear"
            )),
            Found::Tried(tried) => Some(match self.chosen() {
                Some(k) => format!(
                    "not critical with the crane set up at {}: {}; there {}",
                    tried[k].where_said(),
                    tried[k].carries_said(),
                    planned_said(tried, k)
                ),
                None => format!(
                    "at the {} crane position(s) nearest the lift's where its chart carries the load within {critical_pct:.0} % at the pick and the set and it stands clear, the lift is critical or refused too",
                    tried.len()
                ),
            }),
        }
    }
}

/// The words for the position named (`tried[k]`): it plans there, in so
/// many steps; what its pads bear on; those tried before it; what to check.
fn planned_said(tried: &[Tried], k: usize) -> String {
    let t = &tried[k];
    // Those refused or critical before it, and those nearer passed over
    // for what their pads bear on.
    let before: Vec<String> = tried
        .iter()
        .enumerate()
        .filter_map(|(i, o)| match &o.outcome {
            Outcome::Refused(_) if i < k => o.refused_said().map(|r| format!("refused {r}")),
            Outcome::Critical { most_pct, step } if i < k => {
                Some(format!("critical at {} ({most_pct:.1} % in step {step})", o.where_said()))
            }
            Outcome::Planned { .. } | Outcome::NotPlanned if i != k && o.pads_to_check() && o.moved_m < t.moved_m => {
                Some(format!("passed over at {}: {}", o.where_said(), o.pads_to_check_said()))
            }
            _ => None,
        })
        .collect();
    let pads = if t.pads_to_check() {
        format!(", BUT {}", t.pads_to_check_said())
    } else {
        let most = t
            .pads
            .map(|p| format!(", its outrigger pads at their most {} (an estimate)", p.said_briefly(t.ground.as_ref())));
        format!("{}, nothing of the plant model or the scans in the ground under them", most.unwrap_or_default())
    };
    let (steps, most_pct) = match t.outcome {
        Outcome::Planned { steps, most_pct } => (steps, most_pct),
        _ => (0, 0.0),
    };
    format!(
        "the lift plans and passes the validator in {steps} steps (at most {most_pct:.1} % of the chart's capacity){pads}{}: a position to CHECK on site (access, the ground's strength, what is buried that neither the plant model nor the scans hold) before it is given to the lift",
        if before.is_empty() { String::new() } else { format!(" (tried before it: {})", before.join("; ")) }
    )
}

/// A refusal's first clause, the lift's name left out: up to its first
/// ": " where what comes before says what refused it ("no collision-free,
/// chart-compliant path found (...)", "the validator rejected the plan"),
/// else up to its first "; " ("crane set-up: the carrier meets ..."). The
/// rest (why, hints) would bury the positions among them.
fn first_clause(why: &str) -> String {
    let why = why.split_once(": ").map_or(why, |(lift, rest)| if lift.starts_with("lift '") { rest } else { why });
    let colon = why.match_indices(':').map(|(at, _)| at).find(|&at| why[at + 1..].starts_with(char::is_whitespace));
    let cut = match colon {
        Some(at) if at >= 25 => at,
        _ => why.find("; ").unwrap_or(why.len()),
    };
    why[..cut].trim_end_matches(',').to_string()
}

/// The farthest working radius (m) at which `chart` carries the lift's
/// gross load on its boom, as the lift reads the chart.
fn farthest_carried_m(task: &LiftTask, chart: &ChartConfig) -> Option<f64> {
    let boom = task.chart_boom_m();
    chart
        .radii_m
        .iter()
        .rev()
        .map(|&row| row - task.radius_allowance_m)
        .find(|&r| r > 0.0 && utilisation_at(task, chart, boom, r).is_some())
}

/// The utilisation (%) at working radius `r_m`, where the chart carries the
/// gross load there.
fn utilisation_at(task: &LiftTask, chart: &ChartConfig, boom_m: f64, r_m: f64) -> Option<f64> {
    let k = chart.lookup(boom_m, r_m + task.radius_allowance_m).ok()?;
    Some(task.utilisation_pct(k.capacity_kg)).filter(|u| *u <= 100.0)
}

/// Where else the lift's crane could stand (the module's docs).
pub fn search(task: &LiftTask, site: &Site, chart: &ChartConfig, s: &Settings, seed: u64, sought: Sought) -> Found {
    if task.crane.model.is_tower() || task.by_configuration.iter().any(|b| *b) {
        return Found::NotSearched;
    }
    let Some(reach_m) = farthest_carried_m(task, chart) else { return Found::OutOfReach { farthest_m: None } };
    let (hp, hs) = (task.crane.sheave(&task.pick), task.crane.sheave(&task.set));
    if (hp - hs).xy().norm() > 2.0 * reach_m {
        return Found::OutOfReach { farthest_m: Some(reach_m) };
    }
    let boom = task.chart_boom_m();
    let home = task.crane.placement;
    // The grid over the two discs' common box, on multiples of GRID_M so a
    // position said is one the lift file takes as it is.
    let lo = [hp.x.max(hs.x) - reach_m, hp.y.max(hs.y) - reach_m].map(|v| (v / GRID_M).ceil() as i64);
    let hi = [hp.x.min(hs.x) + reach_m, hp.y.min(hs.y) + reach_m].map(|v| (v / GRID_M).floor() as i64);
    let mut carried: Vec<(bool, f64, [f64; 2], (f64, f64), (f64, f64))> = Vec::new();
    for i in lo[0]..=hi[0] {
        for j in lo[1]..=hi[1] {
            let at = [i as f64 * GRID_M, j as f64 * GRID_M];
            let radius = |h: &liftplan_core::frame::Point3| (h.x - at[0]).hypot(h.y - at[1]);
            let (rp, rs) = (radius(&hp), radius(&hs));
            let (Some(up), Some(us)) = (utilisation_at(task, chart, boom, rp), utilisation_at(task, chart, boom, rs))
            else {
                continue;
            };
            let critical = up.max(us) > task.critical_pct;
            if critical && sought == Sought::NotCritical {
                continue;
            }
            carried.push((critical, (at[0] - home.x_m).hypot(at[1] - home.y_m), at, (up, rp), (us, rs)));
        }
    }
    carried.sort_by(|a, b| {
        a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2[0].total_cmp(&b.2[0])).then(a.2[1].total_cmp(&b.2[1]))
    });
    // A permitted swing range turns with the carrier: whether it stands
    // for the chart's sector or for where the site lets the load go, only
    // at the lift's heading does it mean what the lift says.
    let headings: &[f64] = if task.swing_range_rad.is_some() { &HEADINGS[..1] } else { &HEADINGS };
    // Those whose pads' ground is to be checked apart: passed over for
    // those where it is not, kept (the nearest few) where none such plans.
    let (mut clear, mut to_check): (Vec<(Tried, LiftTask)>, Vec<(Tried, LiftTask)>) = (Vec::new(), Vec::new());
    let near = |kept: &[(Tried, LiftTask)], at: [f64; 2]| {
        kept.iter().any(|(t, _)| (t.x_m - at[0]).hypot(t.y_m - at[1]) < APART_M)
    };
    let mut looked_at = 0;
    for &(_, moved_m, at, ..) in &carried {
        if clear.len() >= MOST_PLANNED || looked_at >= MOST_LOOKED_AT {
            break;
        }
        // The lift's own position was refused, and one near it is most
        // often refused for the same; where it was critical, a step nearer
        // the pick or the set may be all it takes.
        let off_own_m = if sought == Sought::Plans { APART_M } else { GRID_M / 2.0 };
        if moved_m < off_own_m || near(&clear, at) {
            continue;
        }
        looked_at += 1;
        // At each position, the first heading whose set-up is clear and
        // whose pads' ground is not to be checked (turning the carrier
        // moves the pads), else the first whose set-up is clear.
        // What lies under the pads is looked for (it walks the model's
        // triangles) only where their pressure does not already pass the
        // position over, and where one passed over is kept.
        let mut checked = None;
        for turn in headings {
            // One whose pads' pressure is to be checked is of use only as
            // the first such here, and while fewer are kept than are planned
            // none near: otherwise it is passed by before its costly checks.
            let flagged_wanted = checked.is_none() && to_check.len() < MOST_PLANNED && !near(&to_check, at);
            let Some(mut found) = set_up_at(task, site, chart, s, at, *turn, moved_m, flagged_wanted) else {
                continue;
            };
            if !found.0.pads_to_check() {
                found.0.under_pads = crate::validate::under_pads(&found.1, site.world);
                if !found.0.pads_to_check() {
                    clear.push(found);
                    checked = None;
                    break;
                }
            }
            checked = checked.or(Some(found));
        }
        if let Some(mut found) = checked.filter(|_| to_check.len() < MOST_PLANNED && !near(&to_check, at)) {
            if found.0.under_pads.is_empty() {
                found.0.under_pads = crate::validate::under_pads(&found.1, site.world);
            }
            to_check.push(found);
        }
    }
    if clear.is_empty() && to_check.is_empty() {
        return Found::NoClearSetUp { looked_at, in_areas: !task.crane_stands_in.is_empty() };
    }
    // Planned in turn until one plans whose pads are not to be checked,
    // through the whole lift; those left are not planned. One passed over
    // for its pads stays so however it plans (the planned lift's most
    // loaded pad is at least its ends'), so once one has planned, those
    // after it could never be named and are not planned either.
    let mut tried = Vec::new();
    let (mut found_clean, mut planned_any) = (false, false);
    let flagged_from = clear.len();
    for (i, (mut t, moved)) in clear.into_iter().chain(to_check).enumerate() {
        if found_clean || (planned_any && i >= flagged_from) {
            t.outcome = Outcome::NotPlanned;
        } else {
            t.outcome = match crate::plan_lift_hinting(&moved, site, s, seed, false) {
                Ok((plan, _)) => {
                    t.pads = plan.summary.highest_pad.map(|(_, p)| p).or(t.pads);
                    let most_pct = plan.summary.max_utilisation_pct;
                    // Critical through the lift, not at its ends alone.
                    t.critical |= plan.summary.critical;
                    if sought == Sought::NotCritical && plan.summary.critical {
                        Outcome::Critical { most_pct, step: plan.summary.max_utilisation_step }
                    } else {
                        Outcome::Planned { steps: plan.steps.len(), most_pct }
                    }
                }
                Err(e) => Outcome::Refused(e.to_string()),
            };
            planned_any |= t.planned_steps().is_some();
            found_clean = t.planned_steps().is_some() && !t.pads_to_check();
        }
        tried.push(t);
    }
    Found::Tried(tried)
}

/// The lift with its crane at `at`, turned `turn_deg` from the lift's
/// heading, at the height of the ground scanned there, where the crane holds
/// the pick and the set, its chart carries the load at both, its set-up is
/// clear and level, and the lift-off, the set-down and where the search
/// starts and ends are clear; not where its most loaded pad at the pick or
/// the set is to be checked (more pressure than the ground may bear, or the
/// crane file's masses tipping it) unless `flagged_wanted`, which is found
/// before the costly checks.
#[allow(clippy::too_many_arguments)]
fn set_up_at(
    task: &LiftTask,
    site: &Site,
    chart: &ChartConfig,
    s: &Settings,
    at: [f64; 2],
    turn_deg: f64,
    moved_m: f64,
    flagged_wanted: bool,
) -> Option<(Tried, LiftTask)> {
    let heading_deg = (task.crane.placement.heading_rad.to_degrees() + turn_deg).rem_euclid(360.0).round();
    let placement = Placement { x_m: at[0], y_m: at[1], heading_rad: heading_deg.to_radians(), ..task.crane.placement };
    let moved = task.moved_to(placement).ok()?;
    // The most loaded pad at the pick and the set (the planned lift's most
    // replaces it; the ground's height below does not change it); what lies
    // under the pads is the caller's to look for.
    let pads = [moved.start(), moved.goal()]
        .iter()
        .filter_map(|c| pads_at(&moved, c))
        .max_by(|a, b| a.load_kg.total_cmp(&b.load_kg));
    if !flagged_wanted && pads.is_some_and(|p| p.needs_checking(moved.ground.as_ref())) {
        return None;
    }
    // The ground there: the lift's level where none is scanned; else its
    // median, to the centimetre the lift file is given in, and no dip under
    // the carrier and outriggers deeper than the set-up check's tolerance.
    let ground = crate::validate::set_up_ground_heights(&moved, site.world);
    let (moved, ground_scanned) = if ground.is_empty() {
        (moved, false)
    } else {
        let z = (ground[ground.len() / 2] * 100.0).round() / 100.0;
        let dip = z - ground[ground.len() / 20];
        if dip > crate::validate::SET_UP_LEVEL_TOLERANCE_M {
            return None;
        }
        (task.moved_to(Placement { z_m: z, ..placement }).ok()?, true)
    };
    let pick = moved.check_capacity(chart, moved.pick.radial).ok().filter(|k| k.effective_kg >= moved.gross_kg())?;
    let set = moved.check_capacity(chart, moved.set.radial).ok().filter(|k| k.effective_kg >= moved.gross_kg())?;
    // Its level is the ground's there (the planner's level check cannot
    // fail at the median it checks against): what it stands on is not.
    if crate::set_up_blocked(&moved, site, s).is_some() {
        return None;
    }
    // The lift-off and the set-down there, as the validator sees them: a
    // boom that meets what stands between the crane and the pick or the set
    // refuses the lift there whatever path is searched.
    let zones = crate::landing_zones(&moved, s);
    let rules = crate::validate_rules(&moved, s, &zones);
    for mv in [crate::lift_off(&moved), crate::set_down(&moved)] {
        if !crate::validate::validate(&moved, Some(chart), site.world, &rules, &[mv], &[true]).ok {
            return None;
        }
    }
    // And the planner's own check of where its search starts and ends,
    // online (no tables built): a boom too near a wall between the crane
    // and the set refuses the lift there before any search.
    let online = liftplan_cspace::Settings { strategy: liftplan_cspace::Strategy::Online, ..s.cspace.clone() };
    let cs = liftplan_cspace::CSpace::build(
        &liftplan_cspace::Problem { task: &moved, chart: Some(chart), map: site.map },
        &online,
    );
    let ck = liftplan_cspace::Checker::new(&cs, site.map, &moved, zones, s.cspace.sample_m);
    if ck.config(&moved.start()).is_err() || ck.config(&moved.goal()).is_err() {
        return None;
    }
    let tried = Tried {
        x_m: at[0],
        y_m: at[1],
        heading_deg,
        ground_z_m: moved.crane.placement.z_m,
        ground_scanned,
        moved_m,
        pick: (pick.utilisation_pct, pick.radius_m),
        set: (set.utilisation_pct, set.radius_m),
        critical: pick.utilisation_pct.max(set.utilisation_pct) > task.critical_pct,
        pads,
        ground: moved.ground,
        under_pads: Vec::new(),
        outcome: Outcome::NotPlanned,
    };
    Some((tried, moved))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tried(x_m: f64, outcome: Outcome) -> Tried {
        Tried {
            x_m,
            y_m: -2.5,
            heading_deg: 90.0,
            ground_z_m: 0.12,
            ground_scanned: true,
            moved_m: x_m,
            pick: (72.4, 16.0),
            set: (98.1, 21.79),
            critical: true,
            pads: None,
            ground: None,
            under_pads: Vec::new(),
            outcome,
        }
    }

    /// The positions refused before the one that plans are said with the
    /// first clause of why, the lift's name and hints left out; one that
    /// plans with its utilisation, whether critical, and what to check.
    #[test]
    fn the_positions_tried_are_said() {
        let refused =
            "lift 'V-101': no collision-free, chart-compliant path found (1 run(s)): the boom meets RACK; more";
        let found = Found::Tried(vec![
            tried(3.0, Outcome::Refused(refused.into())),
            tried(6.5, Outcome::Planned { steps: 9, most_pct: 98.1 }),
        ]);
        assert_eq!(
            found.said("Main"),
            "; the crane set up at position_m = [6.5, -2.5], heading_deg = 90, ground_z_m = 0.12 (the ground scanned there; 6.5 m from the lift's position) carries it at both (pick 72 % at 16.00 m, set 98 % at 21.79 m: a critical lift there, above its critical_pct), and there the lift plans and passes the validator in 9 steps (at most 98.1 % of the chart's capacity), nothing of the plant model or the scans in the ground under them (tried before it: refused at position_m = [3.0, -2.5], heading_deg = 90, ground_z_m = 0.12 (the ground scanned there; 3.0 m from the lift's position): no collision-free, chart-compliant path found (1 run(s))): a position to CHECK on site (access, the ground's strength, what is buried that neither the plant model nor the scans hold) before it is given to the lift"
        );
        assert_eq!(found.chosen(), Some(1));
        // The pads' most and the pressure under their mats; a nearer
        // position with a duct under a pad, passed over, and one farther
        // whose mats the ground would not bear, not planned.
        let ground = GroundSpec { mat_m: [2.5, 2.5], allowable_kpa: Some(200.0) };
        let pads = |load_kg: f64| StepPads {
            pad: liftplan_core::outriggers::Pad::RearRight,
            load_kg,
            at_m: [14.25, -3.25],
            pad_lifts: false,
            tips: false,
        };
        let duct = UnderPad {
            pad: liftplan_core::outriggers::Pad::FrontLeft,
            object: "DUCT".into(),
            depth_m: 0.3,
            zone_half_m: 2.75,
            zone_depth_m: 5.0,
        };
        let with = |mut t: Tried, load_kg: f64, under: Vec<UnderPad>| {
            (t.pads, t.ground, t.under_pads) = (Some(pads(load_kg)), Some(ground), under);
            t
        };
        let found = Found::Tried(vec![
            with(tried(6.5, Outcome::Planned { steps: 9, most_pct: 98.1 }), 118_600.0, vec![]),
            with(tried(4.0, Outcome::NotPlanned), 100_000.0, vec![duct.clone()]),
            with(tried(9.0, Outcome::NotPlanned), 140_000.0, vec![]),
        ]);
        assert_eq!(found.chosen(), Some(0));
        let said = found.said("Main");
        assert!(said.contains("in 9 steps (at most 98.1 % of the chart's capacity), its outrigger pads at their most 118.6 t on the rear right pad; 186 kPa under its 2.50 x 2.50 m mat, allowable 200 kPa (an estimate), nothing of the plant model or the scans in the ground under them (tried before it: passed over at position_m = [4.0, -2.5], heading_deg = 90, ground_z_m = 0.12 (the ground scanned there; 4.0 m from the lift's position): IN THE GROUND UNDER ITS PADS: DUCT 0.30 m below the set-up level under the front left pad (within 2.8 m of its centre and 5.0 m deep)): a position"), "{said}");
        assert!(!said.contains("[9.0"), "{said}");
        // Where only positions to check plan, the first is named with what
        // is to be checked.
        let found = Found::Tried(vec![
            with(tried(6.5, Outcome::Planned { steps: 9, most_pct: 98.1 }), 140_000.0, vec![duct.clone()]),
            with(tried(9.0, Outcome::Planned { steps: 8, most_pct: 98.1 }), 140_000.0, vec![]),
        ]);
        assert_eq!(found.chosen(), Some(0));
        let said = found.said("Main");
        assert!(said.contains("in 9 steps (at most 98.1 % of the chart's capacity), BUT IN THE GROUND UNDER ITS PADS: DUCT 0.30 m below the set-up level under the front left pad (within 2.8 m of its centre and 5.0 m deep); 220 kPa UNDER THE REAR RIGHT PAD'S 2.50 x 2.50 m MAT (140.0 t, an estimate), MORE THAN THE 200 kPa THE GROUND MAY BEAR (a mat of at least 2.70 x 2.70 m): a position"), "{said}");
        let none = Found::Tried(vec![
            tried(3.0, Outcome::Refused(refused.into())),
            tried(6.5, Outcome::Refused("lift 'V-101': crane set-up: x".into())),
        ]);
        let said = none.said("Main");
        assert!(said.starts_with("; at the 2 crane position(s) nearest the lift's where it carries the load at both and stands clear, the lift is refused too: at position_m = [3.0"), "{said}");
        assert!(said.ends_with("3.0 m from the lift's position): no collision-free, chart-compliant path found (1 run(s)); at position_m = [6.5, -2.5], heading_deg = 90, ground_z_m = 0.12 (the ground scanned there; 6.5 m from the lift's position): crane set-up: x"), "{said}");
        assert_eq!(Found::NotSearched.said("Main"), "");
        // Sought where a critical lift is not: one critical through the
        // lift (its ends within critical_pct) before the one named.
        let calm = |mut t: Tried, outcome| {
            (t.critical, t.pick, t.set, t.outcome) = (false, (45.0, 16.18), (73.0, 27.77), outcome);
            t
        };
        let found = Found::Tried(vec![
            calm(tried(2.5, Outcome::Refused("x".into())), Outcome::Critical { most_pct: 78.2, step: 6 }),
            calm(tried(4.0, Outcome::NotPlanned), Outcome::Planned { steps: 13, most_pct: 72.8 }),
        ]);
        assert_eq!(
            found.not_critical_said(75.0).unwrap(),
            "not critical with the crane set up at position_m = [4.0, -2.5], heading_deg = 90, ground_z_m = 0.12 (the ground scanned there; 4.0 m from the lift's position): pick 45 % at 16.18 m, set 73 % at 27.77 m; there the lift plans and passes the validator in 13 steps (at most 72.8 % of the chart's capacity), nothing of the plant model or the scans in the ground under them (tried before it: critical at position_m = [2.5, -2.5], heading_deg = 90, ground_z_m = 0.12 (the ground scanned there; 2.5 m from the lift's position) (78.2 % in step 6)): a position to CHECK on site (access, the ground's strength, what is buried that neither the plant model nor the scans hold) before it is given to the lift"
        );
        let none =
            Found::Tried(vec![calm(tried(2.5, Outcome::NotPlanned), Outcome::Critical { most_pct: 78.2, step: 6 })]);
        assert_eq!(
            none.not_critical_said(75.0).unwrap(),
            "at the 1 crane position(s) nearest the lift's where its chart carries the load within 75 % at the pick and the set and it stands clear, the lift is critical or refused too"
        );
        assert_eq!(Found::NotSearched.not_critical_said(75.0), None);
    }
}
