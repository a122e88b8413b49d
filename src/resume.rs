//! `liftplan resume`: where a lift stopped part way stands, read off the
//! plan its crew follows, as the `resume_from` line its `[[lift]]` takes to
//! be planned again from there.
//!
//! The crew's plan is named by its revision, printed on every page of its
//! PDF: the last plan in `out/` may be a newer one (made after the crew's
//! copy was printed), and the pose after step 4 of another plan is not where
//! the load hangs. A plan made before the last is read from the plans kept
//! by revision (`out/revisions/`, [`crate::revisions`]) or, made by a
//! liftplan that did not keep them, from the plan stage's cache (the
//! `[cache] keep` most recent runs).
//!
//! It only reads (`out/plan.json`, `out/revisions/`, the plan stage's cache
//! and the project file) and prints; it does not edit the project file or
//! run anything.
//!
//! [`check_resumed`] is the other way round: before a run, whether a lift's
//! `resume_from` is where the plan its `resumes_plan` names has the load
//! after that step, for the crane the plan was made for, set up where it
//! stood. It reports and never refuses: the engineer is told to
//! check the printed pose against the crane's display, and a pose taken off
//! the display is the one to plan from. It runs outside the stages, so a
//! plan never depends on what the cache happens to hold.

use crate::cache::Cache;
use crate::project::Project;
use anyhow::{Context, Result, bail};
use liftplan_cspace::Joint;
use liftplan_plan::LiftPlan;
use std::path::{Path, PathBuf};

#[derive(serde::Deserialize)]
struct PlanFile {
    lifts: Vec<LiftPlan>,
}

/// Lift `lift`'s plan in a plan.json, if the file holds one.
fn plan_in(file: &Path, lift: &str) -> Result<Option<LiftPlan>> {
    let text = std::fs::read_to_string(file).with_context(|| format!("{}", file.display()))?;
    let plans: PlanFile = serde_json::from_str(&text).with_context(|| format!("{}", file.display()))?;
    Ok(plans.lifts.into_iter().find(|l| l.lift == lift))
}

/// The plan of lift `lift` whose revision is `revision` in the last plans
/// (`out/plan.json`), the plans kept by revision (out/revisions/) or, for
/// one made before liftplan kept them, the plan stage's cache, with the file
/// it was read from; or none. A file that cannot be read is one that does
/// not hold it.
fn plan_named(p: &Project, lift: &str, revision: &str, last: Option<&LiftPlan>) -> Option<(LiftPlan, PathBuf)> {
    if let Some(last) = last.filter(|l| l.summary.revision == revision) {
        return Some((last.clone(), p.out_dir().join("plan.json")));
    }
    let kept = crate::revisions::plan_file(&p.out_dir(), lift, revision);
    if let Ok(Some(plan)) = plan_in(&kept, lift).map(|o| o.filter(|plan| plan.summary.revision == revision)) {
        return Some((plan, kept));
    }
    Cache::new(&p.state_dir()).entries(liftplan_plan::NAME).into_iter().find_map(|entry| {
        let file = entry.join("plan.json");
        match plan_in(&file, lift) {
            Ok(Some(plan)) if plan.summary.revision == revision => Some((plan, file)),
            _ => None,
        }
    })
}

/// The plan of lift `lift` whose revision is `revision`: the last one
/// (`out/plan.json`), one kept by revision or one the plan stage's cache
/// still keeps, with the file it was read from and the last plan's revision.
fn find_plan(p: &Project, lift: &str, revision: &str) -> Result<(LiftPlan, PathBuf, String)> {
    let last_file = p.out_dir().join("plan.json");
    if !last_file.exists() {
        bail!("{}: no plan to resume (run the project first)", last_file.display());
    }
    let Some(last) = plan_in(&last_file, lift)? else {
        bail!("{}: no plan of lift '{lift}' (run the project first)", last_file.display());
    };
    let last_revision = last.summary.revision.clone();
    if let Some((plan, file)) = plan_named(p, lift, revision, Some(&last)) {
        return Ok((plan, file, last_revision));
    }
    bail!(
        "lift '{lift}' has no plan {revision}: its last plan ({}) is plan {}, and neither the plans kept by revision ({}) nor the plan stage's cache ({}) hold one of that revision. Check the revision on the foot of the crew's pages; if theirs was made by a liftplan that did not keep plans by revision, or out/ was cleaned since, read the swing, luff (or trolley) and hoist off the crane's display and give them as resume_from by hand",
        last_file.display(),
        if last_revision.is_empty() { "of no revision (made by an older liftplan)" } else { &last_revision },
        p.out_dir().join(crate::revisions::DIR).join(lift).display(),
        p.state_dir().join("cache").join(liftplan_plan::NAME).display(),
    )
}

/// Where a crane is set up, in words.
fn placement_words(c: &liftplan_core::crane::Placement, tower: bool) -> String {
    format!(
        "({:.2}, {:.2}) m, ground z {:.2} m, heading {:.1}°{}",
        c.x_m,
        c.y_m,
        c.z_m,
        c.heading_rad.to_degrees(),
        if tower { String::new() } else { format!(", boom {:.1} m", c.boom_length_m) }
    )
}

/// Whether `revision` reads as a plan's revision: the 8 hex digits after
/// "plan" on the foot of each page of its PDF.
fn revision_given(revision: &str) -> Result<String> {
    let r = revision.trim().to_ascii_lowercase();
    if r.len() != 8 || !r.bytes().all(|b| b.is_ascii_hexdigit()) {
        bail!(
            "--plan {revision:?}: give the plan's revision, the 8 hex digits after \"plan\" on the foot of each page of the crew's PDF (such as 3f9a2c1b)"
        );
    }
    Ok(r)
}

/// The `resumes_plan` and `resume_from` lines for lift `lift` of the
/// project in `dir`, stopped after step `after_step` of its plan `revision`
/// (the one its crew follows), or during the next step where that is a
/// swing and `swing_deg` says where it stopped; a comment line above them
/// says whence.
pub fn line(dir: &Path, lift: &str, revision: &str, after_step: usize, swing_deg: Option<f64>) -> Result<String> {
    let revision = revision_given(revision)?;
    let p = Project::load(dir)?;
    let task = p
        .lifts()?
        .into_iter()
        .find(|t| t.id == lift)
        .with_context(|| format!("the project in {} has no lift '{lift}'", dir.display()))?;
    let (plan, file, last_revision) = find_plan(&p, lift, &revision)?;
    if plan.crane_model != task.crane.model.name {
        bail!(
            "plan {revision} of lift '{lift}' was made for the {}; the project now gives the {}: the crane holding the load is the plan's, so give its model in {} before resuming",
            plan.crane_model,
            task.crane.model.name,
            p.dir.join("liftplan.toml").display()
        );
    }
    // A crane stopped part way through its lift stands where it stood: a
    // project that now sets it up elsewhere (a position searched again, an
    // edit) would plan from the right pose at the wrong place.
    if let Some(was) = plan.crane_placement
        && was != task.crane.placement
    {
        let tower = task.crane.model.is_tower();
        bail!(
            "plan {revision} of lift '{lift}' had the crane at {}; the project now sets it up at {}: a crane stopped part way has not moved, so set the lift's crane in {} back to where it stands before resuming",
            placement_words(&was, tower),
            placement_words(&task.crane.placement, tower),
            p.dir.join("liftplan.toml").display()
        );
    }
    let steps = plan.moves.len();
    // A plan.json edited by hand may have fewer steps than moves: say "?".
    let text = |n: usize| plan.steps.get(n).map_or("?", |s| s.text.as_str());
    if !(1..steps).contains(&after_step) {
        bail!(
            "--after-step must be 1 to {}: the plan of lift '{lift}' has {steps} steps, and the last sets the load down",
            steps.saturating_sub(1)
        );
    }
    let mut at = plan.moves[after_step - 1].to;
    let mut whence = format!("after step {after_step} ({})", text(after_step - 1));
    if let Some(deg) = swing_deg {
        let next = &plan.moves[after_step];
        let (a, b) = (next.from.swing_rad.to_degrees(), next.to.swing_rad.to_degrees());
        if next.joint != Joint::Swing {
            bail!(
                "step {} of the plan of lift '{lift}' is not a swing ({}): --swing-deg says where a swing stopped",
                after_step + 1,
                text(after_step)
            );
        }
        if !(deg.is_finite() && deg >= a.min(b) - 1e-6 && deg <= a.max(b) + 1e-6) {
            bail!("step {} swings from {a:.3}° to {b:.3}°: --swing-deg {deg} is not on the way", after_step + 1);
        }
        at.swing_rad = deg.to_radians();
        whence = format!("during step {} ({}), stopped at swing {deg:.3}°", after_step + 1, text(after_step));
    }
    let radial = if task.crane.model.is_tower() {
        format!("trolley_m = {:.3}", at.radial)
    } else {
        format!("luff_deg = {:.3}", at.radial.to_degrees())
    };
    let which = if revision == last_revision {
        format!("plan {revision}, the last")
    } else {
        format!("plan {revision}, not the last ({last_revision})")
    };
    Ok(format!(
        "# lift {lift} {whence}, {which}, from {}: check it against the crane's display\nresumes_plan = {{ revision = \"{revision}\", after_step = {after_step} }}\nresume_from = {{ swing_deg = {:.3}, {radial}, hoist_m = {:.3}, yaw_deg = {:.3} }}",
        file.display(),
        at.swing_rad.to_degrees(),
        at.hoist_m,
        at.load_yaw_rad.to_degrees()
    ))
}

/// What [`check_resumed`] found for one lift.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ResumeCheck {
    pub lift: String,
    /// The plan named was found and `resume_from` is its pose after the step
    /// named (or on the next step's swing).
    pub agrees: bool,
    /// Said in a line: what was compared, or why nothing was.
    pub said: String,
}

/// How far apart a printed pose may be from the plan's and still be the
/// same: `liftplan resume` prints 3 decimals (degrees and metres).
const PRINTED_DEG: f64 = 0.002;
const PRINTED_M: f64 = 0.002;

/// For each lift of the project that resumes part way through the plan its
/// `resumes_plan` names: whether its `resume_from` is where that plan has
/// the load after the step named, or part way through the next step where
/// that is a swing (`liftplan resume --swing-deg`). Read before a run, from
/// the last plans (`out/plan.json`), the plans kept by revision and the plan
/// stage's cache; a plan none holds is said, not refused. A project whose lifts do not read is
/// left to the run to refuse.
pub fn check_resumed(p: &Project) -> Vec<ResumeCheck> {
    // Most runs resume nothing: they read no crane file for this.
    if p.raw.lift.iter().all(|l| l.resumes_plan.is_none()) {
        return Vec::new();
    }
    let Ok(tasks) = p.lifts() else { return Vec::new() };
    let last_file = p.out_dir().join("plan.json");
    // The last plans, read once for every lift; none where there is no
    // readable file.
    let last_plans: Vec<LiftPlan> = std::fs::read_to_string(&last_file)
        .ok()
        .and_then(|text| serde_json::from_str::<PlanFile>(&text).ok())
        .map_or_else(Vec::new, |f| f.lifts);
    let mut out = Vec::new();
    for task in tasks {
        let (Some((resume, _)), Some(named)) = (&task.resume_from, &task.resumes_plan) else { continue };
        let lift = task.id.as_str();
        let (revision, after_step) = (named.revision.as_str(), named.after_step);
        let last = last_plans.iter().find(|l| l.lift == lift);
        let check = |agrees: bool, said: String| ResumeCheck { lift: lift.to_string(), agrees, said };
        let Some((plan, file)) = plan_named(p, lift, revision, last) else {
            out.push(check(
                false,
                format!(
                    "lift {lift}: resumes_plan names plan {revision}, which neither {}, the plans kept by revision ({}) nor the plan stage's cache hold: resume_from is not checked against it (check it against the crane's display)",
                    last_file.display(),
                    p.out_dir().join(crate::revisions::DIR).join(lift).display()
                ),
            ));
            continue;
        };
        // As `liftplan resume` refuses: a pose is compared only with a plan
        // made for the crane the project now gives.
        if plan.crane_model != task.crane.model.name {
            out.push(check(
                false,
                format!(
                    "lift {lift}: plan {revision} was made for the {}; the project gives the {}: the crane holding the load is the plan's, and resume_from is not checked against a plan for another crane",
                    plan.crane_model, task.crane.model.name
                ),
            ));
            continue;
        }
        let tower = task.crane.model.is_tower();
        if let Some(was) = plan.crane_placement
            && was != task.crane.placement
        {
            out.push(check(
                false,
                format!(
                    "lift {lift}: plan {revision} had the crane at {}; the project sets it up at {}: a crane stopped part way has not moved",
                    placement_words(&was, tower),
                    placement_words(&task.crane.placement, tower)
                ),
            ));
            continue;
        }
        if !(1..plan.moves.len()).contains(&after_step) {
            out.push(check(
                false,
                format!(
                    "lift {lift}: resumes_plan names step {after_step} of plan {revision}, which has {} steps (the last sets the load down)",
                    plan.moves.len()
                ),
            ));
            continue;
        }
        let there = plan.moves[after_step - 1].to;
        let next = &plan.moves[after_step];
        let apart = differences(&there, resume, tower);
        let on_next_swing = next.joint == Joint::Swing && {
            let (a, b) = (next.from.swing_rad.to_degrees(), next.to.swing_rad.to_degrees());
            let s = resume.swing_rad.to_degrees();
            s >= a.min(b) - PRINTED_DEG && s <= a.max(b) + PRINTED_DEG && apart.iter().all(|(name, _)| *name == "swing")
        };
        let whence = format!("plan {revision} (from {})", file.display());
        out.push(if apart.is_empty() {
            check(true, format!("lift {lift}: resume_from is where {whence} has the load after step {after_step}"))
        } else if on_next_swing {
            check(
                true,
                format!("lift {lift}: resume_from is on step {}'s swing of {whence}, after step {after_step}", after_step + 1),
            )
        } else {
            let said: Vec<String> = apart.into_iter().map(|(_, s)| s).collect();
            check(
                false,
                format!(
                    "lift {lift}: resume_from is not where {whence} has the load after step {after_step}: {}. The new plan starts from resume_from: check that it is where the load hangs (the crane's display) and that resumes_plan names the crew's plan and step",
                    said.join(", ")
                ),
            )
        });
    }
    out
}

/// The joints in which `given` is not `plan` beyond what printing rounds
/// (name, and both values in words).
fn differences(
    plan: &liftplan_core::crane::Config,
    given: &liftplan_core::crane::Config,
    tower: bool,
) -> Vec<(&'static str, String)> {
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
    use liftplan_core::crane::Config;

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
