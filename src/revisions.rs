//! Every plan a run has made, kept by its revision in
//! `out/revisions/<lift>/`: the plan (`<revision>.plan.json`, that lift's
//! entry as plan.json holds it) and its steps (`<revision>.steps.csv`).
//!
//! A crew follows a printed plan, named by the revision on the foot of its
//! pages. `liftplan resume` and the resume check before each run must read
//! that plan however many runs ago it was made: the plan stage's cache keeps
//! only the last `[cache] keep` runs, and a site whose scans arrive one by
//! one re-plans at every scan.
//!
//! It only adds files: a revision already kept is not written again (the
//! same revision is the same plan), and nothing is removed here, nor by
//! `liftplan clean`, which removes the rest of out/. The PDFs are not kept
//! by revision (3-4 MB each, where a plan and its steps take about 70 kB).

use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// The folder under out/.
pub const DIR: &str = "revisions";

/// Where lift `lift`'s plan of revision `revision` is kept.
pub fn plan_file(out_dir: &Path, lift: &str, revision: &str) -> PathBuf {
    out_dir.join(DIR).join(lift).join(format!("{revision}.plan.json"))
}

/// Lift `lift`'s plan of revision `revision`, where it is kept: none where
/// it is not, or where the names could not be a kept plan's (a revision in
/// a project file is the engineer's typing).
pub fn kept_plan_file(out_dir: &Path, lift: &str, revision: &str) -> Option<PathBuf> {
    Some(plan_file(out_dir, lift, revision)).filter(|f| names_a_file(lift, revision) && f.is_file())
}

/// Whether `revision` is one [`liftplan_plan::revision`] makes (8 lower-case
/// hex digits) and `lift` an id a project allows (it names files): a
/// plan.json edited by hand must not write outside the folder.
fn names_a_file(lift: &str, revision: &str) -> bool {
    revision.len() == 8
        && revision.bytes().all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f'))
        && !lift.is_empty()
        && lift.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_')
}

/// Keeps each lift's plan in `plan_dir` (its plan.json and
/// `<lift>.steps.csv`: the plan stage's output folder, a cache entry of it
/// or out/) that out/revisions/ does not hold yet; says which it kept
/// ("V-101 plan 3f9a2c1b"). A plan of no revision (made by an older
/// liftplan) is not kept.
pub fn keep(out_dir: &Path, plan_dir: &Path) -> Result<Vec<String>> {
    let file = plan_dir.join("plan.json");
    let text = std::fs::read_to_string(&file).with_context(|| format!("{}", file.display()))?;
    let plans: serde_json::Value = serde_json::from_str(&text).with_context(|| format!("{}", file.display()))?;
    let mut kept = Vec::new();
    for plan in plans["lifts"].as_array().into_iter().flatten() {
        let (Some(lift), Some(revision)) = (plan["lift"].as_str(), plan["summary"]["revision"].as_str()) else {
            continue;
        };
        if !names_a_file(lift, revision) {
            continue;
        }
        let to = plan_file(out_dir, lift, revision);
        if to.exists() {
            continue;
        }
        // The steps first: a plan file kept is one whose steps are too.
        let steps = plan_dir.join(format!("{lift}.steps.csv"));
        if steps.exists() {
            let bytes = std::fs::read(&steps).with_context(|| format!("{}", steps.display()))?;
            let steps_to = to.with_file_name(format!("{revision}.steps.csv"));
            liftplan_core::artifact::write_atomic(&steps_to, &bytes)
                .with_context(|| format!("{}", steps_to.display()))?;
        }
        let one = serde_json::json!({ "lifts": [plan] });
        liftplan_core::artifact::write_atomic(&to, serde_json::to_string_pretty(&one)?.as_bytes())
            .with_context(|| format!("{}", to.display()))?;
        kept.push(format!("{lift} plan {revision}"));
    }
    Ok(kept)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan_json(lifts: &[(&str, &str)]) -> String {
        let lifts: Vec<serde_json::Value> = lifts
            .iter()
            .map(|(lift, revision)| serde_json::json!({ "lift": lift, "summary": { "revision": revision }, "moves": [] }))
            .collect();
        serde_json::json!({ "lifts": lifts }).to_string()
    }

    /// Each revision is kept once, with its steps; a later plan of the same
    /// lift is kept beside it, not over it; a name that would leave the
    /// folder, or no revision, is not kept.
    #[test]
    fn each_revision_is_kept_once_beside_the_others() {
        let d = tempfile::tempdir().unwrap();
        let (entry, out) = (d.path().join("entry"), d.path().join("out"));
        std::fs::create_dir_all(&entry).unwrap();
        std::fs::write(entry.join("plan.json"), plan_json(&[("V-101", "0fb8698c"), ("V-102", "")])).unwrap();
        std::fs::write(entry.join("V-101.steps.csv"), "step,operation\n1,Hoist up\n").unwrap();
        assert_eq!(keep(&out, &entry).unwrap(), ["V-101 plan 0fb8698c"]);
        let kept = plan_file(&out, "V-101", "0fb8698c");
        let read: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&kept).unwrap()).unwrap();
        assert_eq!(read["lifts"][0]["lift"], "V-101");
        assert_eq!(read["lifts"].as_array().unwrap().len(), 1);
        let steps = out.join(DIR).join("V-101").join("0fb8698c.steps.csv");
        assert_eq!(std::fs::read_to_string(&steps).unwrap(), "step,operation\n1,Hoist up\n");
        // Kept already: not written again.
        assert!(keep(&out, &entry).unwrap().is_empty());
        // The next plan of the lift beside it.
        std::fs::write(entry.join("plan.json"), plan_json(&[("V-101", "1234abcd")])).unwrap();
        assert_eq!(keep(&out, &entry).unwrap(), ["V-101 plan 1234abcd"]);
        assert!(kept.exists() && plan_file(&out, "V-101", "1234abcd").exists());
        // Edited by hand to name a file elsewhere.
        for (lift, revision) in [("../x", "1234abcd"), ("V-101", "../../ab"), ("V-101", "1234ABCD"), ("", "1234abcd")] {
            std::fs::write(entry.join("plan.json"), plan_json(&[(lift, revision)])).unwrap();
            assert!(keep(&out, &entry).unwrap().is_empty(), "{lift} {revision}");
        }
        assert_eq!(std::fs::read_dir(out.join(DIR)).unwrap().count(), 1);
        // A plan.json that does not read is an error naming it.
        std::fs::write(entry.join("plan.json"), "{").unwrap();
        let e = format!("{:#}", keep(&out, &entry).unwrap_err());
        assert!(e.contains("plan.json"), "{e}");
    }
}
