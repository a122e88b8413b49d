//! `liftplan resume`: where a lift stopped part way stands, read off the
//! plan its crew follows, as the `resume_from` line its `[[lift]]` takes to
//! be planned again from there.
//!
//! The crew's plan is named by its revision, printed on every page of its
//! PDF: the last plan in `out/` may be a newer one (made after the crew's
//! copy was printed), and the pose after step 4 of another plan is not where
//! the load hangs. A plan made before the last is read from the plans kept
//! by revision (`out/revisions/`, [`liftplan::revisions`]) or, made by a
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
//! the display is the one to plan from. It runs outside the stages and
//! reads the cache too (the docs stage makes the same comparison for the
//! cover, from out/revisions/ alone).

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
pub(crate) fn plan_in(file: &Path, lift: &str) -> Result<Option<LiftPlan>> {
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
    if let Some(kept) = liftplan::revisions::kept_plan_file(&p.out_dir(), lift, revision)
        && let Ok(Some(plan)) = plan_in(&kept, lift).map(|o| o.filter(|plan| plan.summary.revision == revision))
    {
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
        p.out_dir().join(liftplan::revisions::DIR).join(lift).display(),
        p.state_dir().join("cache").join(liftplan_plan::NAME).display(),
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
    // A crane stopped part way through its lift is the plan's, where it
    // stood: a project that now gives another, or sets it up elsewhere (a
    // position searched again, an edit), would plan from the right pose at
    // the wrong crane.
    if let Some(differs) = liftplan_plan::resumed::crane_differs(&task, &plan, &revision) {
        bail!(
            "lift '{lift}': {differs}: the crane holding the load is the plan's, where it stood, so give its model and where it stands in {} before resuming",
            p.dir.join("liftplan.toml").display()
        );
    }
    let steps = plan.moves.len();
    // A step is said in its move's own words, as the plan stage says it,
    // not in the words the file holds: the comment line is pasted into the
    // project file, and words edited into a kept plan (a line break and a
    // `resume_from` of their own) would be pasted with it.
    let tower = task.crane.model.is_tower();
    let text = |n: usize| liftplan_plan::steps::describe(tower, &plan.moves[n]).3;
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

/// For each lift of the project that resumes part way through the plan its
/// `resumes_plan` names: whether its `resume_from` is where that plan has
/// the load after the step named, or part way through the next step where
/// that is a swing (`liftplan resume --swing-deg`), as
/// [`liftplan_plan::resumed::compare`] finds. Read before a run, from the
/// last plans (`out/plan.json`), the plans kept by revision and the plan
/// stage's cache; a plan none holds is said, not refused. A project whose
/// lifts do not read is left to the run to refuse.
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
        let (Some(_), Some(named)) = (&task.resume_from, &task.resumes_plan) else { continue };
        let lift = task.id.as_str();
        let revision = named.revision.as_str();
        let last = last_plans.iter().find(|l| l.lift == lift);
        let check = |agrees: bool, said: String| ResumeCheck { lift: lift.to_string(), agrees, said };
        let Some((plan, file)) = plan_named(p, lift, revision, last) else {
            out.push(check(
                false,
                format!(
                    "lift {lift}: resumes_plan names plan {revision}, which neither {}, the plans kept by revision ({}) nor the plan stage's cache hold: resume_from is not checked against it (check it against the crane's display)",
                    last_file.display(),
                    p.out_dir().join(liftplan::revisions::DIR).join(lift).display()
                ),
            ));
            continue;
        };
        if let Some(a) = liftplan_plan::resumed::compare(&task, &plan, &file.display().to_string()) {
            out.push(check(a.agrees, format!("lift {lift}: {}", a.said)));
        }
    }
    out
}
