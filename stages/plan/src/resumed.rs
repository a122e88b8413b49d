//! Whether a lift resumed part way starts where the plan it names has the
//! load: its `resume_from` against that plan's pose after the step its
//! `resumes_plan` names (or part way through the next step, where that is a
//! swing), for the crane that plan was made for, set up where it stood.
//!
//! `liftplan run` says the answer before each run, and the docs stage puts
//! it on the cover of the new plan. This module only compares: it does not
//! look for the plan (its callers say where they read it) and never
//! refuses, since a pose read off the crane's display is the one to plan
//! from and the check only asks for a look.

use crate::LiftPlan;
use liftplan_core::crane::{Config, Placement};
use liftplan_core::lift::LiftTask;
use liftplan_cspace::Joint;

/// What [`compare`] found.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Agreement {
    /// `resume_from` is the plan's pose after the step named (or on the
    /// next step's swing), for the same crane at the same place.
    pub agrees: bool,
    /// Said in a line, without the lift's id: what was compared and how it
    /// came out.
    pub said: String,
}

/// How far apart a printed pose may be from the plan's and still be the
/// same: `liftplan resume` prints 3 decimals (degrees and metres).
const PRINTED_DEG: f64 = 0.002;
const PRINTED_M: f64 = 0.002;

/// Where a crane is set up, in words.
pub fn placement_words(c: &Placement, tower: bool) -> String {
    format!(
        "({:.2}, {:.2}) m, ground z {:.2} m, heading {:.1}°{}",
        c.x_m,
        c.y_m,
        c.z_m,
        c.heading_rad.to_degrees(),
        if tower { String::new() } else { format!(", boom {:.1} m", c.boom_length_m) }
    )
}

/// Where the crane `plan` was made for is not the one `task` sets up: its
/// model, or where it stands; what differs, in words ("plan R was made for
/// the A; the project gives the B", "plan R had the crane at ...; the
/// project sets it up at ..."), for its callers to say what to do. A crane
/// stopped part way through its lift is the plan's, where it stood: a pose
/// compared or printed for another would be planned from at the wrong crane.
pub fn crane_differs(task: &LiftTask, plan: &LiftPlan, revision: &str) -> Option<String> {
    if plan.crane_model != task.crane.model.name {
        return Some(format!(
            "plan {revision} was made for the {}; the project gives the {}",
            plan.crane_model, task.crane.model.name
        ));
    }
    let tower = task.crane.model.is_tower();
    plan.crane_placement.filter(|was| *was != task.crane.placement).map(|was| {
        format!(
            "plan {revision} had the crane at {}; the project sets it up at {}",
            placement_words(&was, tower),
            placement_words(&task.crane.placement, tower)
        )
    })
}

/// `task`'s `resume_from` against `plan`, the plan its `resumes_plan`
/// names, read from `whence` (a file, in words); none where the lift does
/// not resume a named plan.
pub fn compare(task: &LiftTask, plan: &LiftPlan, whence: &str) -> Option<Agreement> {
    let (Some((resume, _)), Some(named)) = (&task.resume_from, &task.resumes_plan) else { return None };
    let (revision, after_step) = (named.revision.as_str(), named.after_step);
    let no = |said: String| Some(Agreement { agrees: false, said });
    if let Some(differs) = crane_differs(task, plan, revision) {
        return no(format!(
            "{differs}: the crane holding the load is the plan's, where it stood, and resume_from is not checked against another"
        ));
    }
    let tower = task.crane.model.is_tower();
    if !(1..plan.moves.len()).contains(&after_step) {
        return no(format!(
            "resumes_plan names step {after_step} of plan {revision}, which has {} steps (the last sets the load down)",
            plan.moves.len()
        ));
    }
    let there = plan.moves[after_step - 1].to;
    let next = &plan.moves[after_step];
    let apart = differences(&there, resume, tower);
    let on_next_swing = next.joint == Joint::Swing && {
        let (a, b) = (next.from.swing_rad.to_degrees(), next.to.swing_rad.to_degrees());
        let s = resume.swing_rad.to_degrees();
        s >= a.min(b) - PRINTED_DEG && s <= a.max(b) + PRINTED_DEG && apart.iter().all(|(name, _)| *name == "swing")
    };
    let whence = format!("plan {revision} (from {whence})");
    Some(if apart.is_empty() {
        Agreement { agrees: true, said: format!("resume_from is where {whence} has the load after step {after_step}") }
    } else if on_next_swing {
        Agreement {
            agrees: true,
            said: format!("resume_from is on step {}'s swing of {whence}, after step {after_step}", after_step + 1),
        }
    } else {
        let said: Vec<String> = apart.into_iter().map(|(_, s)| s).collect();
        Agreement {
            agrees: false,
            said: format!(
                "resume_from is not where {whence} has the load after step {after_step}: {}. The new plan starts from resume_from: check that it is where the load hangs (the crane's display) and that resumes_plan names the crew's plan and step",
                said.join(", ")
            ),
        }
    })
}

/// The joints in which `given` is not `plan` beyond what printing rounds
/// (name, and both values in words).
fn differences(plan: &Config, given: &Config, tower: bool) -> Vec<(&'static str, String)> {
    let mut out = Vec::new();
    let mut deg = |name: &'static str, words: &str, a: f64, b: f64| {
        let (a, b) = (a.to_degrees(), b.to_degrees());
        if (a - b).abs() > PRINTED_DEG {
            out.push((name, format!("{words} {b:.3}° given, {a:.3}° in the plan")));
        }
    };
    deg("swing", "swing", plan.swing_rad, given.swing_rad);
    if !tower {
        deg("luff", "luff", plan.radial, given.radial);
    }
    deg("yaw", "load yaw", plan.load_yaw_rad, given.load_yaw_rad);
    let mut metres = |name: &'static str, words: &str, a: f64, b: f64| {
        if (a - b).abs() > PRINTED_M {
            out.push((name, format!("{words} {b:.3} m given, {a:.3} m in the plan")));
        }
    };
    if tower {
        metres("trolley", "trolley", plan.radial, given.radial);
    }
    metres("hoist", "hoist", plan.hoist_m, given.hoist_m);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config(swing_deg: f64, luff_deg: f64, hoist_m: f64) -> Config {
        Config { swing_rad: swing_deg.to_radians(), radial: luff_deg.to_radians(), hoist_m, load_yaw_rad: 0.0 }
    }

    #[test]
    fn a_pose_as_printed_is_the_plans_and_a_moved_one_is_not() {
        let plan = config(31.234_567, 55.5, 12.345_678);
        // As `liftplan resume` prints it: 3 decimals.
        let printed = config(31.235, 55.5, 12.346);
        assert!(differences(&plan, &printed, false).is_empty());
        let moved = config(31.235, 55.5, 12.846);
        let apart = differences(&plan, &moved, false);
        assert_eq!(apart.len(), 1, "{apart:?}");
        assert_eq!(apart[0].0, "hoist");
        assert!(apart[0].1.contains("hoist 12.846 m given, 12.346 m in the plan"), "{apart:?}");
        let turned = config(33.0, 54.0, 12.346);
        let names: Vec<&str> = differences(&plan, &turned, false).into_iter().map(|(n, _)| n).collect();
        assert_eq!(names, ["swing", "luff"]);
        // A tower crane's radial joint is its trolley, in metres.
        let trolley = Config { radial: 20.0, ..plan };
        let apart = differences(&Config { radial: 20.5, ..plan }, &trolley, true);
        assert_eq!(apart.len(), 1, "{apart:?}");
        assert!(apart[0].1.contains("trolley 20.000 m given, 20.500 m in the plan"), "{apart:?}");
    }
}
