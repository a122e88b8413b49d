//! `liftplan resume`: where a lift stopped part way stands, read off its
//! last plan, as the `resume_from` line its `[[lift]]` takes to be planned
//! again from there.
//!
//! It only reads (`out/plan.json` and the project file) and prints; it does
//! not edit the project file or run anything.

use crate::project::Project;
use anyhow::{Context, Result, bail};
use liftplan_cspace::Joint;

/// The `resume_from` line for lift `lift` of the project in `dir`, stopped
/// after step `after_step` of its last plan, or during the next step where
/// that is a swing and `swing_deg` says where it stopped; a comment line
/// above it says whence.
pub fn line(dir: &std::path::Path, lift: &str, after_step: usize, swing_deg: Option<f64>) -> Result<String> {
    let p = Project::load(dir)?;
    let task = p
        .lifts()?
        .into_iter()
        .find(|t| t.id == lift)
        .with_context(|| format!("the project in {} has no lift '{lift}'", dir.display()))?;
    let file = p.out_dir().join("plan.json");
    let text = std::fs::read_to_string(&file)
        .with_context(|| format!("{}: no plan to resume (run the project first)", file.display()))?;
    #[derive(serde::Deserialize)]
    struct PlanFile {
        lifts: Vec<liftplan_plan::LiftPlan>,
    }
    let plans: PlanFile = serde_json::from_str(&text).with_context(|| format!("{}", file.display()))?;
    let Some(plan) = plans.lifts.iter().find(|l| l.lift == lift) else {
        bail!("{}: no plan of lift '{lift}' (run the project first)", file.display());
    };
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
    Ok(format!(
        "# lift {lift} {whence}, from {}: check it against the plan the crew follows and the crane's display\nresume_from = {{ swing_deg = {:.3}, {radial}, hoist_m = {:.3}, yaw_deg = {:.3} }}",
        file.display(),
        at.swing_rad.to_degrees(),
        at.hoist_m,
        at.load_yaw_rad.to_degrees()
    ))
}
