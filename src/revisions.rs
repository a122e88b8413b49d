//! Every plan a run has made, kept by its revision in
//! `out/revisions/<lift>/`: the plan (`<revision>.plan.json`, that lift's
//! entry as plan.json holds it), its steps (`<revision>.steps.csv`) and its
//! PDF (`<revision>.pdf`, the first made of it).
//!
//! A crew follows a printed plan, named by the revision on the foot of its
//! pages. `liftplan resume` and the resume check before each run must read
//! that plan however many runs ago it was made: the plan stage's cache keeps
//! only the last `[cache] keep` runs, and a site whose scans arrive one by
//! one re-plans at every scan. The engineer who signed it must be able to
//! find the document again as it was issued.
//!
//! It only adds files: a revision already kept is not written again (the
//! same revision is the same plan), and nothing is removed here, nor by
//! `liftplan clean`, which removes the rest of out/. A plan and its steps
//! take about 70 kB, its PDF 3-4 MB (the demo's): a site re-planned at each
//! of a hundred scans keeps some 400 MB.

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
    let mut kept = Vec::new();
    for (plan, lift, revision) in plans_in(plan_dir)? {
        let to = plan_file(out_dir, &lift, &revision);
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

/// Keeps each lift's PDF in the docs stage's output folder `docs_dir`,
/// made from the plans in `plan_dir` in the same run, as
/// `<revision>.pdf` beside its plan, where out/revisions/ holds none for
/// that revision yet: the first made of a plan is the one kept (one made
/// later of the same plan, by other `[docs]` settings or a newer liftplan,
/// is in out/ but not kept again). Says which it kept.
pub fn keep_documents(out_dir: &Path, plan_dir: &Path, docs_dir: &Path) -> Result<Vec<String>> {
    let mut kept = Vec::new();
    for (_, lift, revision) in plans_in(plan_dir)? {
        let pdf = docs_dir.join(format!("{lift}.pdf"));
        let to = out_dir.join(DIR).join(&lift).join(format!("{revision}.pdf"));
        if to.exists() || !pdf.is_file() {
            continue;
        }
        let bytes = std::fs::read(&pdf).with_context(|| format!("{}", pdf.display()))?;
        liftplan_core::artifact::write_atomic(&to, &bytes).with_context(|| format!("{}", to.display()))?;
        kept.push(format!("{lift} plan {revision}'s PDF"));
    }
    Ok(kept)
}

/// The lifts' plans in `plan_dir`'s plan.json with their ids and
/// revisions, those whose names could be a kept plan's
/// ([`names_a_file`]; a plan of no revision, made by an older liftplan, is
/// left out).
fn plans_in(plan_dir: &Path) -> Result<Vec<(serde_json::Value, String, String)>> {
    let file = plan_dir.join("plan.json");
    let text = std::fs::read_to_string(&file).with_context(|| format!("{}", file.display()))?;
    let mut plans: serde_json::Value = serde_json::from_str(&text).with_context(|| format!("{}", file.display()))?;
    let lifts = plans.get_mut("lifts").and_then(|l| l.as_array_mut()).map(std::mem::take).unwrap_or_default();
    Ok(lifts
        .into_iter()
        .filter_map(|plan| {
            let lift = plan["lift"].as_str()?.to_string();
            let revision = plan["summary"]["revision"].as_str()?.to_string();
            names_a_file(&lift, &revision).then_some((plan, lift, revision))
        })
        .collect())
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

    /// A lift's PDF is kept beside its plan, the first made of each
    /// revision: a later one of the same plan does not replace it; a lift
    /// without a PDF keeps none.
    #[test]
    fn the_first_pdf_of_each_revision_is_kept() {
        let d = tempfile::tempdir().unwrap();
        let (plans, docs, out) = (d.path().join("plans"), d.path().join("docs"), d.path().join("out"));
        std::fs::create_dir_all(&plans).unwrap();
        std::fs::create_dir_all(&docs).unwrap();
        std::fs::write(plans.join("plan.json"), plan_json(&[("V-101", "0fb8698c"), ("V-102", "1234abcd")])).unwrap();
        std::fs::write(docs.join("V-101.pdf"), "issued first").unwrap();
        assert_eq!(keep_documents(&out, &plans, &docs).unwrap(), ["V-101 plan 0fb8698c's PDF"]);
        let kept = out.join(DIR).join("V-101").join("0fb8698c.pdf");
        std::fs::write(docs.join("V-101.pdf"), "made again").unwrap();
        assert!(keep_documents(&out, &plans, &docs).unwrap().is_empty());
        assert_eq!(std::fs::read_to_string(&kept).unwrap(), "issued first");
        assert!(!out.join(DIR).join("V-102").exists());
    }
}
