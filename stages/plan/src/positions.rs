//! Where else a mobile crane could stand, for a lift refused where the lift
//! sets it up (the chart does not carry the load at the pick or the set,
//! the carrier or outriggers meet something, the boom meets something at
//! the pick or the set, or no path is found): the
//! nearest position from which its chart configuration carries the gross
//! load at both, the crane stands clear on level ground, and the whole lift
//! plans and passes the validator.
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
//! Words only: nothing here moves a lift's crane. The engineer puts the
//! position in the lift file and the lift is planned and checked anew. What
//! the site holds beyond the scans and the plant model (access, the ground's
//! strength, what is buried) is not known here, and is said to be checked.

use crate::{Settings, Site};
use liftplan_core::capacity::ChartConfig;
use liftplan_core::crane::Placement;
use liftplan_core::lift::LiftTask;

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
    /// The planned lift's steps, or why it was refused there.
    pub outcome: Result<usize, String>,
}

impl Tried {
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
    /// (how many were looked at).
    NoClearSetUp { looked_at: usize },
    /// The positions planned in full, in the order tried; the last planned,
    /// if any did.
    Tried(Vec<Tried>),
}

impl Found {
    /// The words appended to the refusal.
    pub fn said(&self, chart_name: &str) -> String {
        match self {
            Found::NotSearched => String::new(),
            Found::OutOfReach { farthest_m: None } => String::new(),
            Found::OutOfReach { farthest_m: Some(r) } => format!(
                "; no crane position carries it at both: the pick and the set lie more than twice {r:.2} m apart"
            ),
            Found::NoClearSetUp { looked_at } => format!(
                "; of the {looked_at} crane positions nearest the lift's within the reach of '{}' of both the pick and the set, none stands clear (its carrier and outriggers on ground level within {:.2} m, the boom and the load clear at the lift-off and the set-down)",
                chart_name,
                crate::validate::SET_UP_LEVEL_TOLERANCE_M
            ),
            Found::Tried(tried) => {
                let refused: Vec<String> = tried
                    .iter()
                    .filter_map(|t| {
                        t.outcome.as_ref().err().map(|why| format!("at {}: {}", t.where_said(), first_clause(why)))
                    })
                    .collect();
                match tried.iter().find(|t| t.outcome.is_ok()) {
                    Some(t) => format!(
                        "; the crane set up at {} carries it at both ({}), and there the lift plans and passes the validator in {} steps{}: a position to CHECK on site (access, the ground's strength, what lies under the pads) before it is given to the lift",
                        t.where_said(),
                        t.carries_said(),
                        t.outcome.as_ref().map_or(0, |n| *n),
                        if refused.is_empty() {
                            String::new()
                        } else {
                            format!(
                                " (nearer, {}, the lift is refused {})",
                                if refused.len() == 1 { "one" } else { "others" },
                                refused.join("; ")
                            )
                        }
                    ),
                    None => format!(
                        "; at the {} crane position(s) nearest the lift's where it carries the load at both and stands clear, the lift is refused too: {}",
                        tried.len(),
                        refused.join("; ")
                    ),
                }
            }
        }
    }
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
pub fn search(task: &LiftTask, site: &Site, chart: &ChartConfig, s: &Settings, seed: u64) -> Found {
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
    let mut clear: Vec<(Tried, LiftTask)> = Vec::new();
    let mut looked_at = 0;
    for &(_, moved_m, at, ..) in &carried {
        if clear.len() >= MOST_PLANNED || looked_at >= MOST_LOOKED_AT {
            break;
        }
        // The lift's own position was refused, and one near it is most
        // often refused for the same.
        if moved_m < APART_M || clear.iter().any(|(t, _)| (t.x_m - at[0]).hypot(t.y_m - at[1]) < APART_M) {
            continue;
        }
        looked_at += 1;
        if let Some(found) = headings.iter().find_map(|turn| set_up_at(task, site, chart, s, at, *turn, moved_m)) {
            clear.push(found);
        }
    }
    if clear.is_empty() {
        return Found::NoClearSetUp { looked_at };
    }
    let mut tried = Vec::new();
    for (mut t, moved) in clear {
        t.outcome = crate::plan_lift_hinting(&moved, site, s, seed, false)
            .map(|(plan, _)| plan.steps.len())
            .map_err(|e| e.to_string());
        let planned = t.outcome.is_ok();
        tried.push(t);
        if planned {
            break;
        }
    }
    Found::Tried(tried)
}

/// The lift with its crane at `at`, turned `turn_deg` from the lift's
/// heading, at the height of the ground scanned there, where the crane holds
/// the pick and the set, its chart carries the load at both, its set-up is
/// clear and level, and the lift-off, the set-down and where the search
/// starts and ends are clear.
fn set_up_at(
    task: &LiftTask,
    site: &Site,
    chart: &ChartConfig,
    s: &Settings,
    at: [f64; 2],
    turn_deg: f64,
    moved_m: f64,
) -> Option<(Tried, LiftTask)> {
    let heading_deg = (task.crane.placement.heading_rad.to_degrees() + turn_deg).rem_euclid(360.0).round();
    let placement = Placement { x_m: at[0], y_m: at[1], heading_rad: heading_deg.to_radians(), ..task.crane.placement };
    let moved = task.moved_to(placement).ok()?;
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
    let rules = crate::validate_rules(&moved, s, zones.iter().map(|z| z.polygon.clone()).collect());
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
        outcome: Ok(0),
    };
    Some((tried, moved))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tried(x_m: f64, outcome: Result<usize, String>) -> Tried {
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
        let found = Found::Tried(vec![tried(3.0, Err(refused.into())), tried(6.5, Ok(9))]);
        assert_eq!(
            found.said("Main"),
            "; the crane set up at position_m = [6.5, -2.5], heading_deg = 90, ground_z_m = 0.12 (the ground scanned there; 6.5 m from the lift's position) carries it at both (pick 72 % at 16.00 m, set 98 % at 21.79 m: a critical lift there, above its critical_pct), and there the lift plans and passes the validator in 9 steps (nearer, one, the lift is refused at position_m = [3.0, -2.5], heading_deg = 90, ground_z_m = 0.12 (the ground scanned there; 3.0 m from the lift's position): no collision-free, chart-compliant path found (1 run(s))): a position to CHECK on site (access, the ground's strength, what lies under the pads) before it is given to the lift"
        );
        let none = Found::Tried(vec![
            tried(3.0, Err(refused.into())),
            tried(6.5, Err("lift 'V-101': crane set-up: x".into())),
        ]);
        let said = none.said("Main");
        assert!(said.starts_with("; at the 2 crane position(s) nearest the lift's where it carries the load at both and stands clear, the lift is refused too: at position_m = [3.0"), "{said}");
        assert!(said.ends_with("3.0 m from the lift's position): no collision-free, chart-compliant path found (1 run(s)); at position_m = [6.5, -2.5], heading_deg = 90, ground_z_m = 0.12 (the ground scanned there; 6.5 m from the lift's position): crane set-up: x"), "{said}");
        assert_eq!(Found::NotSearched.said("Main"), "");
    }
}
