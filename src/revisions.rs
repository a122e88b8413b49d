//! Every plan a run has made, kept by its revision in
//! `out/revisions/<lift>/`: the plan (`<revision>.plan.json`, that lift's
//! entry as plan.json holds it), its steps (`<revision>.steps.csv`), what it
//! was made from (`<revision>.inputs.json`, the plan stage's inputs by their
//! hashes) and its PDF (`<revision>.pdf`, the first made of it).
//!
//! A crew follows a printed plan, named by the revision on the foot of its
//! pages. `liftplan resume` and the resume check before each run must read
//! that plan however many runs ago it was made: the plan stage's cache keeps
//! only the last `[cache] keep` runs, and a site whose scans arrive one by
//! one re-plans at every scan. The engineer who signed it must be able to
//! find the document again as it was issued.
//!
//! Keeping only adds files: a revision already kept is not written again
//! (the same revision is the same plan; one that is not, a kept file
//! changed by hand or a collision of the revision's hash, is said and
//! never written over), and `liftplan clean`, which
//! removes the rest of out/, leaves them. A plan and its steps take about
//! 70 kB, its PDF 3-4 MB (the demo's): a site re-planned at each of a
//! hundred scans keeps some 400 MB. `liftplan revisions` lists them
//! ([`list`]) and, asked to, removes those kept longer ago than a number
//! of days, or all but each lift's newest few ([`remove_older_than`]), but
//! never one a crew may hold or be given: each lift's newest, the last
//! plans (out/plan.json), those the plan stage's cache holds (a run would
//! keep them again) and those the project's lifts resume ([`held`]). Asked
//! to, it sets two of a lift's plans side by side for the engineer asked to
//! sign one that replaces the other ([`compare`]).

use anyhow::{Context, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The folder under out/.
pub const DIR: &str = "revisions";

/// Where lift `lift`'s plan of revision `revision` is kept.
pub fn plan_file(out_dir: &Path, lift: &str, revision: &str) -> PathBuf {
    out_dir.join(DIR).join(lift).join(format!("{revision}.plan.json"))
}

/// What lift `lift`'s plan of revision `revision` was made from, where it
/// is kept: the plan stage's inputs (its code, its settings, which hold
/// every lift's, and each upstream output it read) by their hashes.
pub fn inputs_file(out_dir: &Path, lift: &str, revision: &str) -> PathBuf {
    out_dir.join(DIR).join(lift).join(format!("{revision}.inputs.json"))
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
    keep_made_from(out_dir, plan_dir, None)
}

/// [`keep`], and, where the run knows the inputs of the stages before the
/// plan stage (`stages`: by stage, each input's name and hash as its
/// manifest has them: the scan, plant and chart files, their settings and
/// code), what each plan was made from ([`inputs_file`]: those and the plan
/// stage's own inputs), where none is kept beside it yet. A plan the run
/// found fresh was made from inputs that give the same stages' outputs, so
/// it may be written for a plan kept before; [`keep`] alone, before a run
/// (a plan an earlier one left), writes none.
pub fn keep_made_from(
    out_dir: &Path,
    plan_dir: &Path,
    stages: Option<&std::collections::BTreeMap<String, std::collections::BTreeMap<String, String>>>,
) -> Result<Vec<String>> {
    let mut kept = Vec::new();
    let mut another = Vec::new();
    // What the plans were made from: the plan stage's inputs, as its
    // manifest names them, and the stages' before it.
    let made_from = std::fs::read_to_string(plan_dir.join("manifest.json"))
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .and_then(|m| {
            let mut inputs: BTreeMap<String, String> = serde_json::from_value(m["inputs"].clone()).ok()?;
            add_lift_settings(&mut inputs, &m["settings"]);
            Some(inputs)
        })
        .zip(stages)
        .map(|(inputs, s)| serde_json::json!({ "inputs": inputs, "stages": s }));
    for (plan, lift, revision) in plans_in(plan_dir)? {
        let to = plan_file(out_dir, &lift, &revision);
        let inputs_to = inputs_file(out_dir, &lift, &revision);
        let write_inputs = |made_from: &Option<serde_json::Value>| -> Result<()> {
            if let Some(one) = made_from.as_ref().filter(|_| !inputs_to.exists()) {
                liftplan_core::artifact::write_atomic(&inputs_to, serde_json::to_string_pretty(one)?.as_bytes())
                    .with_context(|| format!("{}", inputs_to.display()))?;
            }
            Ok(())
        };
        if to.exists() {
            let kept_plan = std::fs::read_to_string(&to)
                .ok()
                .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
                .map(|v| v["lifts"][0].clone());
            let differs =
                |k: serde_json::Value| liftplan_plan::but_for_timings(&k) != liftplan_plan::but_for_timings(&plan);
            if kept_plan.is_some_and(differs) {
                another.push(format!("{lift} plan {revision}"));
            } else {
                // The same plan, kept before: what it was made from, where
                // that was not kept then.
                write_inputs(&made_from)?;
            }
            continue;
        }
        write_inputs(&made_from)?;
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
    if !another.is_empty() {
        anyhow::bail!(
            "{} not kept: out/{DIR}/ holds another plan of that revision (a file there changed by hand, or two plans whose revisions collide), so the revision on its pages does not tell it from that one: CHECK which plan the crew holds{}",
            another.join(", "),
            if kept.is_empty() { String::new() } else { format!("; kept {}", kept.join(", ")) }
        );
    }
    Ok(kept)
}

/// The name under which [`add_lift_settings`] keeps a lift's own settings.
const LIFT_SETTINGS: &str = "settings of lift ";
/// ... and a stage's settings besides the lifts.
const SETTINGS_BESIDES_LIFTS: &str = "settings besides the lifts";

/// Adds to a stage's `inputs` (as its manifest has them), where its
/// `settings` hold the project's lifts, a hash of each lift's own settings
/// (by its id) and one of the settings besides the lifts: kept in what a
/// plan was made from (not in the stage's key, which the whole settings'
/// hash makes), so that a comparison tells a change to the lift's own
/// settings from one to another lift's ([`compare`]).
pub fn add_lift_settings(inputs: &mut BTreeMap<String, String>, settings: &serde_json::Value) {
    let (Some(all), Some(lifts)) = (settings.as_object(), settings["lifts"].as_array()) else { return };
    let hash = |v: &serde_json::Value| blake3::hash(v.to_string().as_bytes()).to_hex().to_string();
    for lift in lifts {
        if let Some(id) = lift["id"].as_str() {
            inputs.insert(format!("{LIFT_SETTINGS}{id}"), hash(lift));
        }
    }
    let mut besides = all.clone();
    besides.remove("lifts");
    inputs.insert(SETTINGS_BESIDES_LIFTS.to_string(), hash(&serde_json::Value::Object(besides)));
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
        let to = plan_file(out_dir, &lift, &revision).with_file_name(format!("{revision}.pdf"));
        if to.exists() || !pdf.is_file() {
            continue;
        }
        let bytes = std::fs::read(&pdf).with_context(|| format!("{}", pdf.display()))?;
        liftplan_core::artifact::write_atomic(&to, &bytes).with_context(|| format!("{}", to.display()))?;
        kept.push(format!("{lift} plan {revision}'s PDF"));
    }
    Ok(kept)
}

/// One plan kept by revision, as `liftplan revisions` lists it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Kept {
    pub lift: String,
    pub revision: String,
    /// When it was kept: its plan file's modification time (seconds since
    /// 1970, UTC), where the file system gives it (none: never removed).
    pub kept_unix_s: Option<u64>,
    /// What its plan says, where its file reads as a plan: whether the
    /// validator passed it, its steps, the most of the chart it uses (%),
    /// its least clearance (m).
    pub validated: Option<bool>,
    pub steps: Option<u64>,
    pub max_utilisation_pct: Option<f64>,
    pub min_clearance_m: Option<f64>,
    /// Its PDF's size (bytes), where one is kept.
    pub pdf_bytes: Option<u64>,
    /// Its files' sizes together (bytes).
    pub bytes: u64,
}

impl Kept {
    /// Its files: the PDF, the steps and what it was made from (where
    /// kept), then the plan, the order they are removed in (a plan file
    /// kept is one whose steps are).
    fn files(&self, out_dir: &Path) -> [PathBuf; 4] {
        let plan = plan_file(out_dir, &self.lift, &self.revision);
        [
            plan.with_file_name(format!("{}.pdf", self.revision)),
            plan.with_file_name(format!("{}.steps.csv", self.revision)),
            inputs_file(out_dir, &self.lift, &self.revision),
            plan,
        ]
    }

    /// In one line, for the listing.
    pub fn said(&self) -> String {
        let mb = |b: u64| b as f64 / 1e6;
        let plan = match (self.validated, self.steps) {
            (Some(ok), Some(steps)) => format!(
                "{}, {steps} steps, {:.0} % of the chart, least clearance {:.2} m",
                if ok { "validated" } else { "NOT VALIDATED" },
                self.max_utilisation_pct.unwrap_or(f64::NAN),
                self.min_clearance_m.unwrap_or(f64::NAN)
            ),
            _ => "its plan file does not read as a plan".to_string(),
        };
        let pdf = self.pdf_bytes.map_or("no PDF kept".to_string(), |b| format!("PDF {:.1} MB", mb(b)));
        format!(
            "{} plan {}  kept {}  {plan}; {pdf}; {:.1} MB in all",
            self.lift,
            self.revision,
            self.kept_unix_s.map_or("at a time the file system does not give".to_string(), liftplan_docs::date_utc),
            mb(self.bytes)
        )
    }
}

/// The plans kept in `out_dir`'s revisions/, by lift, each lift's oldest
/// first (by when it was kept, then revision). Files there whose names
/// could not be a kept plan's are left out.
pub fn list(out_dir: &Path) -> Result<Vec<Kept>> {
    let root = out_dir.join(DIR);
    let mut kept = Vec::new();
    if !root.is_dir() {
        return Ok(kept);
    }
    let read_dir = |d: &Path| std::fs::read_dir(d).with_context(|| format!("reading {}", d.display()));
    for lift_dir in read_dir(&root)? {
        let lift_dir = lift_dir.with_context(|| format!("reading {}", root.display()))?.path();
        let Some(lift) = lift_dir.file_name().and_then(|n| n.to_str()).map(str::to_string) else { continue };
        if !lift_dir.is_dir() {
            continue;
        }
        for file in read_dir(&lift_dir)? {
            let file = file.with_context(|| format!("reading {}", lift_dir.display()))?.path();
            let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("");
            let Some(revision) = name.strip_suffix(".plan.json") else { continue };
            if !names_a_file(&lift, revision) {
                continue;
            }
            let size = |p: &Path| std::fs::metadata(p).ok().filter(|m| m.is_file()).map(|m| m.len());
            let meta = std::fs::metadata(&file).with_context(|| format!("{}", file.display()))?;
            let kept_unix_s =
                meta.modified().ok().and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok()).map(|d| d.as_secs());
            let summary = std::fs::read_to_string(&file)
                .ok()
                .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
                .map(|v| v["lifts"][0]["summary"].clone())
                .filter(|s| s.is_object());
            let field = |k: &str| summary.as_ref().map(|s| s[k].clone());
            let mut one = Kept {
                lift: lift.clone(),
                revision: revision.to_string(),
                kept_unix_s,
                validated: field("validated").and_then(|v| v.as_bool()),
                steps: field("steps").and_then(|v| v.as_u64()),
                max_utilisation_pct: field("max_utilisation_pct").and_then(|v| v.as_f64()),
                min_clearance_m: field("min_clearance_m").and_then(|v| v.as_f64()),
                pdf_bytes: None,
                bytes: 0,
            };
            // The plan file's size is in the metadata read above.
            let [pdf, steps, inputs, _] = one.files(out_dir);
            one.pdf_bytes = size(&pdf);
            let plan_bytes = if meta.is_file() { meta.len() } else { 0 };
            one.bytes =
                plan_bytes + one.pdf_bytes.unwrap_or(0) + size(&steps).unwrap_or(0) + size(&inputs).unwrap_or(0);
            kept.push(one);
        }
    }
    kept.sort_by(|a, b| (&a.lift, a.kept_unix_s, &a.revision).cmp(&(&b.lift, b.kept_unix_s, &b.revision)));
    Ok(kept)
}

/// Which of the `kept` plans may not be removed, and why: each lift's
/// newest kept, and its `newest` newest (`--keep-last`); those in the
/// plan.json files of `plan_dirs` (out/, where the last plans are, and the
/// plan stage's cache entries, from which a run would keep them again);
/// those `resumed` names (a lift's id and the revision its `resumes_plan`
/// gives).
pub fn held(
    kept: &[Kept],
    plan_dirs: &[PathBuf],
    resumed: &[(String, String)],
    newest: usize,
) -> std::collections::BTreeMap<(String, String), &'static str> {
    let mut held = std::collections::BTreeMap::new();
    for (lift, revision) in resumed {
        held.insert((lift.clone(), revision.clone()), "a lift of the project resumes it (resumes_plan)");
    }
    for dir in plan_dirs.iter().filter(|d| d.join("plan.json").is_file()) {
        // A plan.json that does not read holds nothing the listing can name.
        for (_, lift, revision) in plans_in(dir).unwrap_or_default() {
            held.entry((lift, revision)).or_insert("among the last plans or the plan stage's cache");
        }
    }
    // The list is each lift's oldest first: walked newest first, how many
    // of the lift's are newer is counted as it goes.
    let mut newer = 0;
    for (k, one) in kept.iter().enumerate().rev() {
        newer = if kept.get(k + 1).is_some_and(|next| next.lift == one.lift) { newer + 1 } else { 0 };
        let why = match newer {
            0 => "the lift's newest kept plan",
            n if n < newest => "among the lift's newest kept plans (--keep-last)",
            _ => continue,
        };
        held.entry((one.lift.clone(), one.revision.clone())).or_insert(why);
    }
    held
}

/// Removes the `kept` plans kept before `before_unix_s` (their PDF, steps
/// and plan files; `u64::MAX`: whenever) but those `held` names and those
/// kept at a time not known; says which it removed.
pub fn remove_older_than(
    out_dir: &Path,
    kept: &[Kept],
    held: &BTreeMap<(String, String), &'static str>,
    before_unix_s: u64,
) -> Result<Vec<String>> {
    remove(out_dir, &removable(kept, held, before_unix_s).collect::<Vec<_>>())
}

/// The plans to remove for what is kept to come to `most_bytes` or under
/// (`--keep-under`): of the `kept` plans [`removable`] before
/// `before_unix_s`, the oldest first, whatever their lift, as many as it
/// takes, or all of them where that is not enough (the rest is held).
pub fn to_fit<'a>(
    kept: &'a [Kept],
    held: &'a BTreeMap<(String, String), &'static str>,
    before_unix_s: u64,
    most_bytes: u64,
) -> Vec<&'a Kept> {
    let mut total: u64 = kept.iter().map(|k| k.bytes).sum();
    let mut oldest_first: Vec<&Kept> = removable(kept, held, before_unix_s).collect();
    oldest_first.sort_by(|a, b| (a.kept_unix_s, &a.lift, &a.revision).cmp(&(b.kept_unix_s, &b.lift, &b.revision)));
    oldest_first
        .into_iter()
        .take_while(|k| {
            let over = total > most_bytes;
            total = total.saturating_sub(k.bytes);
            over
        })
        .collect()
}

/// The `kept` plans that may be removed: kept before `before_unix_s`, at a
/// time known, and not `held`.
fn removable<'a>(
    kept: &'a [Kept],
    held: &'a BTreeMap<(String, String), &'static str>,
    before_unix_s: u64,
) -> impl Iterator<Item = &'a Kept> {
    kept.iter().filter(move |k| {
        k.kept_unix_s.is_some_and(|t| t < before_unix_s) && !held.contains_key(&(k.lift.clone(), k.revision.clone()))
    })
}

/// Removes `plans` (their PDF, steps, inputs and plan files, the plan
/// file last); says which it removed, with their sizes.
pub fn remove(out_dir: &Path, plans: &[&Kept]) -> Result<Vec<String>> {
    let mut removed = Vec::new();
    for one in plans {
        for file in one.files(out_dir).iter().filter(|f| f.is_file()) {
            std::fs::remove_file(file).with_context(|| format!("removing {}", file.display()))?;
        }
        removed.push(format!("{} plan {} ({:.1} MB)", one.lift, one.revision, one.bytes as f64 / 1e6));
    }
    Ok(removed)
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

/// One thing two kept plans of a lift differ in, in words: what, as it
/// was and as it is now.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Difference {
    pub what: String,
    pub was: String,
    pub now: String,
}

/// What differs between two kept plans of one lift (`liftplan revisions
/// --compare WAS NOW`): for the engineer asked to sign a plan that replaces
/// one signed before, or a crew handed a new revision.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Comparison {
    pub lift: String,
    pub was: String,
    pub now: String,
    /// What a signer reads first ([`SAID`]), in that order, where it differs.
    pub differences: Vec<Difference>,
    /// The first step that differs (1-based), and what it was and is now
    /// ("Luff down 11.26 °"; "none" past a plan's last step); `None` where
    /// the steps are the same.
    pub first_step_differing: Option<(usize, String, String)>,
    /// Every other value of the plans that differs, by where it is in the
    /// plan file (a JSON pointer; the planner's own search figures and
    /// timings left out).
    pub other_values: Vec<String>,
    /// What the plans were made from that differs ([`made_from`]); `None`
    /// where a plan's inputs are not kept (kept by an earlier liftplan), or
    /// their record does not read ([`Comparison::inputs_unread`]).
    pub inputs_differing: Option<Vec<InputDiffering>>,
    /// Each record of a plan's inputs that is there but does not read (a
    /// file cut short, edited, or not one liftplan wrote), with why: what
    /// the plans were made from is then not known, and the record is not
    /// to be taken for one that is missing.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub inputs_unread: Vec<String>,
}

/// One input two plans were made from that differs: what it is, in words
/// ("scans/a.laz changed", "the plan stage's settings"), and what more says
/// it (what it holds, its name in the stage's manifest).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct InputDiffering {
    pub what: String,
    pub more: Vec<String>,
}

impl InputDiffering {
    fn new(what: String, more: &[&str]) -> InputDiffering {
        InputDiffering { what, more: more.iter().map(|m| m.to_string()).collect() }
    }

    /// In words, what more says it in brackets.
    pub fn said(&self) -> String {
        self.more.iter().fold(self.what.clone(), |s, m| format!("{s} ({m})"))
    }
}

impl Comparison {
    /// In one line, for a run's output: what differs, by name, and the
    /// command that says how.
    pub fn briefly(&self) -> String {
        let mut what: Vec<String> = self.differences.iter().map(|d| d.what.to_lowercase()).collect();
        if let Some((n, _, _)) = &self.first_step_differing {
            what.push(format!("the path from step {n}"));
        }
        if what.is_empty() && !self.other_values.is_empty() {
            what.push(format!(
                "{} other value{} of the plan file",
                self.other_values.len(),
                if self.other_values.len() == 1 { "" } else { "s" }
            ));
        }
        let made_from = match &self.inputs_differing {
            Some(d) if !d.is_empty() => format!(
                "; what it was made from differs: {}",
                d.iter().map(|i| i.what.as_str()).collect::<Vec<_>>().join(", ")
            ),
            _ => String::new(),
        };
        format!(
            "{}: plan {} replaces plan {}: {} differ{made_from} (liftplan revisions --compare {} {})",
            self.lift,
            self.now,
            self.was,
            if what.is_empty() { "nothing but the time planning took".to_string() } else { what.join(", ") },
            self.was,
            self.now
        )
    }

    /// In lines, for the terminal.
    pub fn said(&self) -> String {
        let mut lines = vec![format!("{}: plan {} against plan {}:", self.lift, self.now, self.was)];
        for d in &self.differences {
            lines.push(format!("  {}: {}; now {}", d.what, d.was, d.now));
        }
        if let Some((n, was, now)) = &self.first_step_differing {
            lines.push(format!("  The path differs from step {n}: {was}; now {now}"));
        }
        if !self.other_values.is_empty() {
            const NAMED: usize = 8;
            let named: Vec<&str> = self.other_values.iter().take(NAMED).map(String::as_str).collect();
            let more = self.other_values.len().saturating_sub(NAMED);
            let more = if more > 0 { format!(" and {more} more") } else { String::new() };
            lines.push(format!(
                "  {} other value{} of the plan file differ{}: {}{more}",
                self.other_values.len(),
                if self.other_values.len() == 1 { "" } else { "s" },
                if self.other_values.len() == 1 { "s" } else { "" },
                named.join(", ")
            ));
        }
        if self.was == self.now {
            lines.push("  the same plan (one revision given twice)".to_string());
        } else if self.differences.is_empty() && self.first_step_differing.is_none() && self.other_values.is_empty() {
            lines.push("  no difference but for the time planning took".to_string());
        }
        lines.push(match &self.inputs_differing {
            None if !self.inputs_unread.is_empty() => {
                format!("  Made from: not known: {}", self.inputs_unread.join("; "))
            }
            None => "  Made from: not known (a plan kept by an earlier liftplan has no record of its inputs beside it)"
                .to_string(),
            Some(d) if d.is_empty() => "  Made from: the same inputs".to_string(),
            Some(d) => format!(
                "  Made from: {} differ{}",
                d.iter().map(InputDiffering::said).collect::<Vec<_>>().join("; "),
                if d.len() == 1 { "s" } else { "" }
            ),
        });
        lines.join("\n")
    }
}

/// What `--compare`'s second plan may be: the lift's last plan.
pub const LAST: &str = "last";

/// What a signer reads first, in words: each with the parts of the plan
/// file it says (JSON pointers into a lift's plan), which the rest of the
/// comparison leaves to it.
type Say = fn(&serde_json::Value) -> String;
const SAID: &[(&str, &[&str], Say)] = &[
    ("Validated", &["/summary/validated"], |p| flag(p, "/summary/validated", "yes", "NO")),
    ("Crane", &["/crane_model", "/chart_config"], |p| {
        format!("{}, chart configuration '{}'", text(p, "/crane_model"), text(p, "/chart_config"))
    }),
    ("Crane set up at", &["/crane_placement"], |p| {
        format!(
            "({}, {}, {}) m, heading {}°, boom {} m",
            number(p, "/crane_placement/x_m", 1.0, 2),
            number(p, "/crane_placement/y_m", 1.0, 2),
            number(p, "/crane_placement/z_m", 1.0, 2),
            number(p, "/crane_placement/heading_rad", 180.0 / std::f64::consts::PI, 1),
            number(p, "/crane_placement/boom_length_m", 1.0, 1),
        )
    }),
    ("Gross load", &["/gross_kg"], |p| format!("{} t", number(p, "/gross_kg", 1e-3, 2))),
    ("Clearance kept", &["/clearance_m", "/landing_clearance_m"], |p| {
        format!(
            "{} m, {} m over the landing zones",
            number(p, "/clearance_m", 1.0, 2),
            number(p, "/landing_clearance_m", 1.0, 2)
        )
    }),
    (
        "Most of the chart used",
        &["/summary/max_utilisation_pct", "/summary/max_utilisation_step", "/summary/max_utilisation_cell"],
        |p| {
            format!(
                "{} % at step {} ({})",
                number(p, "/summary/max_utilisation_pct", 1.0, 1),
                number(p, "/summary/max_utilisation_step", 1.0, 0),
                text(p, "/summary/max_utilisation_cell")
            )
        },
    ),
    ("Critical lift", &["/summary/critical"], |p| flag(p, "/summary/critical", "yes", "no")),
    (
        "Least clearance",
        &["/summary/min_clearance_m", "/summary/min_clearance_step", "/summary/min_clearance_what"],
        |p| {
            format!(
                "{} m at step {} ({})",
                number(p, "/summary/min_clearance_m", 1.0, 2),
                number(p, "/summary/min_clearance_step", 1.0, 0),
                text(p, "/summary/min_clearance_what")
            )
        },
    ),
    ("Steps", &["/summary/steps"], |p| number(p, "/summary/steps", 1.0, 0)),
    ("Slings", &["/summary/slings"], |p| match p.pointer("/summary/slings").filter(|s| s.is_object()) {
        None => "not checked".into(),
        Some(_) => {
            let lengths: Vec<String> = p
                .pointer("/summary/slings/leg_lengths_m")
                .and_then(|v| v.as_array())
                .map(|a| a.iter().filter_map(|l| l.as_f64()).map(|l| format!("{l:.2}")).collect())
                .unwrap_or_default();
            format!(
                "{} legs {} m long, the most on one {} t",
                number(p, "/summary/slings/legs", 1.0, 0),
                lengths.join(", "),
                number(p, "/summary/slings/max_leg_kg", 1e-3, 2)
            )
        }
    }),
    ("Reeving", &["/summary/reeving"], |p| match p.pointer("/summary/reeving").filter(|s| s.is_object()) {
        None => "not checked".into(),
        Some(_) => format!(
            "{} falls, hook load {} t",
            number(p, "/summary/reeving/falls", 1.0, 0),
            number(p, "/summary/reeving/hook_load_kg", 1e-3, 2)
        ),
    }),
    ("Outrigger pad at its most", &["/summary/highest_pad"], |p| match p.pointer("/summary/highest_pad/1") {
        None => "not worked out".into(),
        Some(_) => format!(
            "{} t on the {} pad at step {}",
            number(p, "/summary/highest_pad/1/load_kg", 1e-3, 1),
            words_of(&text(p, "/summary/highest_pad/1/pad")),
            number(p, "/summary/highest_pad/0", 1.0, 0)
        ),
    }),
    ("Power lines", &["/summary/power_lines"], |p| listed(p, "/summary/power_lines")),
    ("Obstacles placed by hand", &["/summary/obstacles"], |p| listed(p, "/summary/obstacles")),
];

/// A name as plan.json writes it ("RearLeft") in words ("rear left").
fn words_of(name: &str) -> String {
    let mut out = String::new();
    for (k, c) in name.chars().enumerate() {
        if c.is_uppercase() && k > 0 {
            out.push(' ');
        }
        out.extend(c.to_lowercase());
    }
    out
}

/// `yes` or `no` as the flag at `pointer` in `plan` is set, or "not said".
fn flag(plan: &serde_json::Value, pointer: &str, yes: &str, no: &str) -> String {
    match plan.pointer(pointer).and_then(|v| v.as_bool()) {
        Some(true) => yes.into(),
        Some(false) => no.into(),
        None => "not said".into(),
    }
}

/// The string at `pointer` in `plan`, or "not said".
fn text(plan: &serde_json::Value, pointer: &str) -> String {
    plan.pointer(pointer).and_then(|v| v.as_str()).unwrap_or("not said").to_string()
}

/// The number at `pointer` in `plan` times `scale`, to `digits` decimals,
/// or "not said".
fn number(plan: &serde_json::Value, pointer: &str, scale: f64, digits: usize) -> String {
    plan.pointer(pointer).and_then(|v| v.as_f64()).map_or("not said".into(), |v| format!("{:.digits$}", v * scale))
}

/// The strings of the list at `pointer` in `plan` joined, or "none".
fn listed(plan: &serde_json::Value, pointer: &str) -> String {
    let items: Vec<&str> = plan
        .pointer(pointer)
        .and_then(|v| v.as_array())
        .map(|a| a.iter().filter_map(|v| v.as_str()).collect())
        .unwrap_or_default();
    if items.is_empty() { "none".into() } else { items.join("; ") }
}

/// What a plan file's parts hold that the comparison does not set side by
/// side: the planner's search (its figures and timings), the path's own
/// nodes and moves (its steps say it), the plan's name, and the hook's
/// configurations (the steps and the summary say where the load goes).
const NOT_COMPARED: &[&str] =
    &["/planning", "/nodes", "/moves", "/summary/revision", "/validator/seconds", "/start", "/goal"];

/// Lift `lift`'s kept plans `was` and `now` set side by side ([`Comparison`]);
/// where `lift` is `None`, the lift that keeps both. `now` may be `last`:
/// the lift's last plan (out/plan.json's), else the one kept last. Refused, naming what is missing, where a plan
/// is not kept, two lifts keep both, or a file does not read as a plan.
pub fn compare(out_dir: &Path, lift: Option<&str>, was: &str, now: &str) -> Result<Comparison> {
    // What is kept, read once, where a lift or the last plan is to be found.
    let kept = if lift.is_none() || now == LAST { list(out_dir)? } else { Vec::new() };
    let newest;
    let now = if now == LAST {
        let lifts: Vec<&str> = match lift {
            Some(l) => vec![l],
            None => kept.iter().filter(|k| k.revision == was).map(|k| k.lift.as_str()).collect(),
        };
        let [one] = lifts[..] else {
            anyhow::bail!(match lifts.len() {
                0 => format!("no lift keeps plan {was} in {}", out_dir.join(DIR).display()),
                _ => format!("lifts {} each keep plan {was}: name one with --lift", lifts.join(", ")),
            });
        };
        // The lift's plan in out/plan.json (a run keeps each plan it
        // makes), else the one kept last (each lift's plans are listed
        // oldest first).
        let in_last_plans = last_plans(out_dir)
            .into_iter()
            .find(|(l, _)| l == one)
            .map(|(_, r)| r)
            .filter(|r| kept.iter().any(|k| k.lift == one && &k.revision == r));
        newest =
            match in_last_plans {
                Some(r) => r,
                None => kept.iter().rev().find(|k| k.lift == one).map(|k| k.revision.clone()).with_context(|| {
                    format!("lift '{one}' keeps no plan in {}", out_dir.join(DIR).join(one).display())
                })?,
            };
        newest.as_str()
    } else {
        now
    };
    let lift = match lift {
        Some(l) => l.to_string(),
        None => {
            let keeps = |l: &str, r: &str| kept.iter().any(|k| k.lift == l && k.revision == r);
            let mut lifts: Vec<&str> = kept.iter().map(|k| k.lift.as_str()).collect();
            lifts.dedup();
            let both: Vec<&str> = lifts.into_iter().filter(|l| keeps(l, was) && keeps(l, now)).collect();
            match both[..] {
                [one] => one.to_string(),
                [] => {
                    let missing = if kept.iter().any(|k| k.revision == was) { now } else { was };
                    anyhow::bail!(
                        "no lift keeps both plan {was} and plan {now} in {}: plan {missing} is not kept there (`liftplan revisions` lists those that are)",
                        out_dir.join(DIR).display()
                    );
                }
                _ => anyhow::bail!("lifts {} each keep plans {was} and {now}: name one with --lift", both.join(", ")),
            }
        }
    };
    let read = |revision: &str| -> Result<serde_json::Value> {
        let file = kept_plan_file(out_dir, &lift, revision).with_context(|| {
            format!("lift '{lift}' keeps no plan {revision} in {}", out_dir.join(DIR).join(&lift).display())
        })?;
        let text = std::fs::read_to_string(&file).with_context(|| format!("reading {}", file.display()))?;
        let plan: serde_json::Value =
            serde_json::from_str(&text).with_context(|| format!("{} does not read as JSON", file.display()))?;
        let one = plan["lifts"][0].clone();
        anyhow::ensure!(
            one["summary"].is_object(),
            "{} does not hold a lift's plan (lifts[0].summary)",
            file.display()
        );
        Ok(liftplan_plan::but_for_timings(&one))
    };
    let (a, b) = (read(was)?, read(now)?);
    let mut differences = Vec::new();
    for (what, _, say) in SAID {
        let (x, y) = (say(&a), say(&b));
        if x != y {
            differences.push(Difference { what: what.to_string(), was: x, now: y });
        }
    }
    let step = |plan: &serde_json::Value, k: usize| -> Option<String> {
        let s = plan.pointer(&format!("/steps/{k}"))?;
        Some(format!(
            "{} {:.2} {}",
            s["operation"].as_str().unwrap_or("?"),
            s["amount"].as_f64().unwrap_or(f64::NAN),
            s["unit"].as_str().unwrap_or("")
        ))
    };
    let steps = |plan: &serde_json::Value| plan["steps"].as_array().map_or(0, Vec::len);
    let first_step_differing = (0..steps(&a).max(steps(&b))).find_map(|k| {
        let (x, y) = (step(&a, k), step(&b, k));
        (x != y).then(|| (k + 1, x.unwrap_or_else(|| "none".into()), y.unwrap_or_else(|| "none".into())))
    });
    let mut covered: Vec<&str> = NOT_COMPARED.to_vec();
    covered.push("/steps");
    for (_, parts, _) in SAID {
        covered.extend_from_slice(parts);
    }
    let mut other_values = Vec::new();
    differing_leaves(&a, &b, &mut String::new(), &covered, &mut other_values);
    // A record that is missing is a plan kept without one; one that is there
    // and does not read is said as such.
    let mut inputs_unread = Vec::new();
    let mut inputs_of = |revision: &str| -> Option<serde_json::Value> {
        let file = inputs_file(out_dir, &lift, revision);
        let text = match std::fs::read_to_string(&file) {
            Ok(text) => text,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return None,
            Err(e) => {
                inputs_unread.push(format!("{} does not read ({e})", file.display()));
                return None;
            }
        };
        match serde_json::from_str::<serde_json::Value>(&text) {
            Ok(v) if v["inputs"].is_object() => Some(v),
            Ok(_) => {
                inputs_unread.push(format!("{} holds no record of inputs (an object \"inputs\")", file.display()));
                None
            }
            Err(e) => {
                inputs_unread.push(format!("{} does not read as JSON ({e})", file.display()));
                None
            }
        }
    };
    let (inputs_was, inputs_now) = (inputs_of(was), inputs_of(now));
    let inputs_differing = inputs_was.zip(inputs_now).map(|(x, y)| inputs_that_differ(&x, &y, &lift));
    Ok(Comparison {
        lift,
        was: was.to_string(),
        now: now.to_string(),
        differences,
        first_step_differing,
        other_values,
        inputs_differing,
        inputs_unread,
    })
}

/// The plans out/plan.json holds by lift ((lift, revision)), before a run
/// writes over it; none where it holds none.
pub fn last_plans(out_dir: &Path) -> Vec<(String, String)> {
    plans_in(out_dir).map(|p| p.into_iter().map(|(_, lift, revision)| (lift, revision)).collect()).unwrap_or_default()
}

/// For each lift whose plan in `plan_dir` replaces another of `before`
/// (the last plans before the run), both kept: a line saying what differs
/// ([`Comparison::briefly`]). A comparison that cannot be made (a plan not
/// kept) says nothing: the run's own lines say why a plan was not kept.
pub fn replaced(out_dir: &Path, before: &[(String, String)], plan_dir: &Path) -> Vec<String> {
    let Ok(now) = plans_in(plan_dir) else { return Vec::new() };
    now.iter()
        .filter_map(|(_, lift, revision)| {
            let (_, was) = before.iter().find(|(l, r)| l == lift && r != revision)?;
            compare(out_dir, Some(lift), was, revision).ok().map(|c| c.briefly())
        })
        .collect()
}

/// What differs between what two plans were made from (each as its
/// [`inputs_file`] holds it), in words: where both name the stages before
/// the plan stage, their files (changed, added, removed), settings and
/// code, then the plan stage's own settings and code; else the plan
/// stage's inputs ([`made_from`]). A stage's settings that hold the lifts
/// are said as what of them differs for `lift`, where both records have
/// the parts ([`add_lift_settings`]): its own, those besides the lifts, or
/// other lifts' only.
fn inputs_that_differ(was: &serde_json::Value, now: &serde_json::Value, lift: &str) -> Vec<InputDiffering> {
    let differing = |x: &serde_json::Value, y: &serde_json::Value| -> Vec<(String, &'static str)> {
        let (Some(x), Some(y)) = (x.as_object(), y.as_object()) else { return Vec::new() };
        let mut names: Vec<&String> = x.keys().chain(y.keys()).collect();
        names.sort_unstable();
        names.dedup();
        names
            .into_iter()
            .filter_map(|k| match (x.get(k), y.get(k)) {
                (Some(a), Some(b)) if a != b => Some((k.clone(), "changed")),
                (None, Some(_)) => Some((k.clone(), "added")),
                (Some(_), None) => Some((k.clone(), "removed")),
                _ => None,
            })
            .collect()
    };
    // The parts are said through "settings", not by themselves.
    let part = |n: &str| n.starts_with(LIFT_SETTINGS) || n == SETTINGS_BESIDES_LIFTS;
    let plan_stage: Vec<(String, &str)> =
        differing(&was["inputs"], &now["inputs"]).into_iter().filter(|(n, _)| !part(n)).collect();
    let plan_settings = |d: InputDiffering, n: &str| {
        let how = (n == "settings").then(|| settings_differing(&was["inputs"], &now["inputs"], lift)).flatten();
        match how {
            Some(how) => how.said_of(d),
            None => d,
        }
    };
    let (Some(a), Some(b)) = (was["stages"].as_object(), now["stages"].as_object()) else {
        return plan_stage.into_iter().map(|(n, _)| plan_settings(made_from(&n), &n)).collect();
    };
    let mut out = Vec::new();
    let mut stages: Vec<&String> = a.keys().chain(b.keys()).collect();
    stages.sort_unstable();
    stages.dedup();
    for stage in stages {
        let none = serde_json::Value::Null;
        let (x, y) = (a.get(stage).unwrap_or(&none), b.get(stage).unwrap_or(&none));
        for (name, how) in differing(x, y) {
            out.push(match name.as_str() {
                "code" => InputDiffering::new(format!("liftplan's {stage} stage"), &["its code"]),
                "settings" => {
                    let d = InputDiffering::new(format!("the {stage} stage's settings"), &[]);
                    match settings_differing(x, y, lift) {
                        Some(how) => how.said_of(d),
                        None => d,
                    }
                }
                n if part(n) => continue,
                n => match n.strip_prefix("file:") {
                    // Said without control characters: the key keeps the
                    // name as it is, which tells files apart.
                    Some(file) => {
                        InputDiffering::new(format!("{} {how}", liftplan_core::names::without_controls(file)), &[])
                    }
                    // Another stage's output it read: said where that stage's inputs differ.
                    None if n.starts_with("upstream:") => continue,
                    None => InputDiffering::new(format!("the {stage} stage's input '{n}'"), &[how]),
                },
            });
        }
    }
    // The plan stage's own; what it read of the stages before it is said
    // above, by what they were made from.
    out.extend(
        plan_stage
            .into_iter()
            .filter(|(n, _)| !n.starts_with("upstream:"))
            .map(|(n, _)| plan_settings(made_from(&n), &n)),
    );
    out
}

/// What of a stage's settings differs for one lift.
#[derive(Debug, Clone, Copy, PartialEq)]
struct SettingsDiffering<'a> {
    lift: &'a str,
    own: bool,
    besides: bool,
}

impl SettingsDiffering<'_> {
    /// `d` (a stage's settings differing) said so: "for other lifts" in
    /// what differs where neither the lift's own nor those besides the
    /// lifts do, else which of them does in what more says it.
    fn said_of(self, mut d: InputDiffering) -> InputDiffering {
        let lift = self.lift;
        match (self.own, self.besides) {
            (false, false) => {
                d.what.push_str(" for other lifts");
                d.more.insert(0, format!("not {lift}'s own, nor those besides the lifts"));
            }
            (true, false) => d.more.insert(0, format!("{lift}'s own")),
            (false, true) => d.more.insert(0, format!("those besides the lifts, not {lift}'s own")),
            (true, true) => d.more.insert(0, format!("{lift}'s own and those besides the lifts")),
        }
        d
    }
}

/// What of a stage's settings differs between two records of its inputs
/// for `lift`, where both hold the parts ([`add_lift_settings`]); `None`
/// where either does not.
fn settings_differing<'a>(
    x: &serde_json::Value,
    y: &serde_json::Value,
    lift: &'a str,
) -> Option<SettingsDiffering<'a>> {
    let besides = (x.get(SETTINGS_BESIDES_LIFTS)?, y.get(SETTINGS_BESIDES_LIFTS)?);
    let own = format!("{LIFT_SETTINGS}{lift}");
    Some(SettingsDiffering { lift, own: x.get(&own) != y.get(&own), besides: besides.0 != besides.1 })
}

/// One of the plan stage's inputs, as its manifest names it, in words.
pub fn made_from(name: &str) -> InputDiffering {
    let (what, holds) = match name {
        "code" => ("liftplan's plan stage", Some("its code")),
        "settings" => (
            "the plan stage's settings",
            Some("the project's lifts, any of them, power lines, obstacles and [plan], [cspace]"),
        ),
        "upstream:scans/site.laz" => ("the site cloud", Some("the scans, as registered and thinned")),
        "upstream:plant/plant.mesh" => ("the plant model's mesh", None),
        "upstream:plant/plant.json" => ("the plant model's groups", Some("those left out, their boxes")),
        "upstream:charts/capacity.csv" => ("the load charts' capacities", None),
        "upstream:charts/chart.json" => {
            ("what the load charts state", Some("their cells, wind, counterweight, warnings"))
        }
        "upstream:depthmap/site.mdm" => ("the depth map", Some("the site cloud and the plant model rasterised")),
        other => return InputDiffering::new(format!("the plan stage's input '{other}'"), &[]),
    };
    InputDiffering::new(what.to_string(), &[holds, Some(name)].into_iter().flatten().collect::<Vec<_>>())
}

/// Pushes onto `out` the JSON pointer of every value where `a` and `b`
/// differ below `at`, but those under `covered`; an object or a list that
/// one has and the other lacks, or of another length, counts as one.
fn differing_leaves(
    a: &serde_json::Value,
    b: &serde_json::Value,
    at: &mut String,
    covered: &[&str],
    out: &mut Vec<String>,
) {
    use serde_json::Value;
    if covered.iter().any(|c| at == c || at.starts_with(&format!("{c}/"))) {
        return;
    }
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
            keys.sort_unstable();
            keys.dedup();
            for k in keys {
                let len = at.len();
                at.push('/');
                at.push_str(&k.replace('~', "~0").replace('/', "~1"));
                differing_leaves(x.get(k).unwrap_or(&Value::Null), y.get(k).unwrap_or(&Value::Null), at, covered, out);
                at.truncate(len);
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (k, (u, v)) in x.iter().zip(y).enumerate() {
                let len = at.len();
                at.push_str(&format!("/{k}"));
                differing_leaves(u, v, at, covered, out);
                at.truncate(len);
            }
        }
        _ if a != b => out.push(at.clone()),
        _ => {}
    }
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
        let manifest = serde_json::json!({ "stage": "plan", "inputs": { "code": "31ee", "settings": "ecaa" } });
        std::fs::write(entry.join("manifest.json"), manifest.to_string()).unwrap();
        // Kept before a run: what it was made from is not known.
        assert_eq!(keep(&out, &entry).unwrap(), ["V-101 plan 0fb8698c"]);
        assert!(!inputs_file(&out, "V-101", "0fb8698c").exists());
        // Found fresh by a run, which knows the stages' inputs: written
        // beside it, once.
        let stages: std::collections::BTreeMap<String, std::collections::BTreeMap<String, String>> =
            [("scans".to_string(), [("file:scans/a.laz".to_string(), "aa".to_string())].into())].into();
        assert!(keep_made_from(&out, &entry, Some(&stages)).unwrap().is_empty());
        let read_inputs = || -> serde_json::Value {
            serde_json::from_str(&std::fs::read_to_string(inputs_file(&out, "V-101", "0fb8698c")).unwrap()).unwrap()
        };
        assert_eq!(read_inputs()["inputs"], manifest["inputs"]);
        assert_eq!(read_inputs()["stages"]["scans"]["file:scans/a.laz"], "aa");
        let other: std::collections::BTreeMap<String, std::collections::BTreeMap<String, String>> = Default::default();
        keep_made_from(&out, &entry, Some(&other)).unwrap();
        assert_eq!(read_inputs()["stages"]["scans"]["file:scans/a.laz"], "aa", "never written over");
        let kept = plan_file(&out, "V-101", "0fb8698c");
        let read: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&kept).unwrap()).unwrap();
        assert_eq!(read["lifts"][0]["lift"], "V-101");
        assert_eq!(read["lifts"].as_array().unwrap().len(), 1);
        let steps = out.join(DIR).join("V-101").join("0fb8698c.steps.csv");
        assert_eq!(std::fs::read_to_string(&steps).unwrap(), "step,operation\n1,Hoist up\n");
        // Kept already: not written again, nor for a plan of that revision
        // that took another time to make.
        assert!(keep(&out, &entry).unwrap().is_empty());
        let timed = |ms: f64, steps: u64| {
            serde_json::json!({ "lifts": [{
                "lift": "V-101", "summary": { "revision": "0fb8698c", "steps": steps }, "moves": [],
                "planning": { "plan_ms": ms, "cspace_ms": ms }, "validator": { "seconds": ms }
            }] })
            .to_string()
        };
        let other = d.path().join("other");
        std::fs::create_dir_all(&other).unwrap();
        std::fs::write(other.join("plan.json"), timed(1.0, 7)).unwrap();
        let elsewhere = d.path().join("elsewhere");
        assert_eq!(keep(&elsewhere, &other).unwrap(), ["V-101 plan 0fb8698c"]);
        std::fs::write(other.join("plan.json"), timed(2.5, 7)).unwrap();
        assert!(keep(&elsewhere, &other).unwrap().is_empty());
        // Another plan under a revision kept: said, and the kept one left.
        let before = std::fs::read_to_string(plan_file(&elsewhere, "V-101", "0fb8698c")).unwrap();
        std::fs::write(other.join("plan.json"), timed(1.0, 8)).unwrap();
        let e = format!("{:#}", keep(&elsewhere, &other).unwrap_err());
        assert!(
            e.starts_with("V-101 plan 0fb8698c not kept: out/revisions/ holds another plan of that revision"),
            "{e}"
        );
        assert_eq!(std::fs::read_to_string(plan_file(&elsewhere, "V-101", "0fb8698c")).unwrap(), before);
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

    /// Listed by lift, oldest first, with what each plan says; removing
    /// those kept before a time leaves each lift's newest, those in the
    /// plan folders given and those resumed, and removes the others' files.
    #[test]
    fn old_plans_are_removed_but_those_a_crew_may_hold() {
        let d = tempfile::tempdir().unwrap();
        let (entry, out) = (d.path().join("entry"), d.path().join("out"));
        std::fs::create_dir_all(&entry).unwrap();
        let day = 86_400u64;
        let t0 = 1_796_000_000u64;
        let plans = [
            ("V-101", "0000000a", t0),
            ("V-101", "0000000b", t0 + day),
            ("V-101", "0000000c", t0 + 2 * day),
            ("V-101", "0000000d", t0 + 3 * day),
            ("V-101", "0000000e", t0 + 9 * day),
            ("V-102", "0000000f", t0),
        ];
        for (lift, revision, at) in plans {
            std::fs::write(entry.join("plan.json"), plan_json(&[(lift, revision)])).unwrap();
            std::fs::write(entry.join(format!("{lift}.steps.csv")), "step\n").unwrap();
            keep(&out, &entry).unwrap();
            let plan = plan_file(&out, lift, revision);
            std::fs::write(plan.with_file_name(format!("{revision}.pdf")), "pdf").unwrap();
            let when = std::time::UNIX_EPOCH + std::time::Duration::from_secs(at);
            std::fs::File::options().write(true).open(&plan).unwrap().set_modified(when).unwrap();
        }
        // A file there that is no kept plan's, and a plan file that does not read.
        std::fs::write(out.join(DIR).join("V-101").join("notes.txt"), "mine").unwrap();
        std::fs::write(plan_file(&out, "V-101", "0000000b"), "{").unwrap();
        std::fs::File::options()
            .write(true)
            .open(plan_file(&out, "V-101", "0000000b"))
            .unwrap()
            .set_modified(std::time::UNIX_EPOCH + std::time::Duration::from_secs(t0 + day))
            .unwrap();
        let kept = list(&out).unwrap();
        let names: Vec<String> = kept.iter().map(|k| format!("{} {}", k.lift, k.revision)).collect();
        assert_eq!(
            names,
            [
                "V-101 0000000a",
                "V-101 0000000b",
                "V-101 0000000c",
                "V-101 0000000d",
                "V-101 0000000e",
                "V-102 0000000f"
            ]
        );
        assert_eq!(kept[0].pdf_bytes, Some(3));
        assert!(kept[1].validated.is_none() && kept[1].said().contains("its plan file does not read as a plan"));
        assert!(
            kept[0].said().starts_with("V-101 plan 0000000a  kept 2026-11-30 00:53 UTC  its plan file"),
            "{}",
            kept[0].said()
        );
        // The last plans hold c; a lift resumes a; e and f are their lifts' newest.
        std::fs::write(entry.join("plan.json"), plan_json(&[("V-101", "0000000c")])).unwrap();
        let resumed = [("V-101".to_string(), "0000000a".to_string())];
        let plan_dirs = [entry.clone(), d.path().join("no-such")];
        // Each lift's three newest held too (--keep-last 3): c is held
        // already, so d is the one more.
        let three = held(&kept, &plan_dirs, &resumed, 3);
        assert_eq!(three.len(), 5, "{three:?}");
        assert_eq!(
            three[&("V-101".to_string(), "0000000d".to_string())],
            "among the lift's newest kept plans (--keep-last)"
        );
        assert_eq!(
            three[&("V-101".to_string(), "0000000c".to_string())],
            "among the last plans or the plan stage's cache"
        );
        assert!(!three.contains_key(&("V-101".to_string(), "0000000b".to_string())));
        let held = held(&kept, &plan_dirs, &resumed, 1);
        assert_eq!(held.len(), 4, "{held:?}");
        assert_eq!(
            held[&("V-101".to_string(), "0000000a".to_string())],
            "a lift of the project resumes it (resumes_plan)"
        );
        // To come under a size: the oldest not held first, whatever the
        // lift, only as many as it takes (b is 1 byte over: b alone goes,
        // then d), and all that may go where that is not enough.
        let total: u64 = kept.iter().map(|k| k.bytes).sum();
        let names = |plans: Vec<&Kept>| plans.iter().map(|k| k.revision.clone()).collect::<Vec<_>>();
        assert!(names(to_fit(&kept, &held, u64::MAX, total)).is_empty());
        assert_eq!(names(to_fit(&kept, &held, u64::MAX, total - 1)), ["0000000b"]);
        assert_eq!(names(to_fit(&kept, &held, u64::MAX, total - kept[1].bytes - 1)), ["0000000b", "0000000d"]);
        assert_eq!(names(to_fit(&kept, &held, u64::MAX, 0)), ["0000000b", "0000000d"]);
        // Only those kept before the time given.
        assert_eq!(names(to_fit(&kept, &held, t0 + 2 * day, 0)), ["0000000b"]);
        let removed = remove_older_than(&out, &kept, &held, t0 + 5 * day).unwrap();
        assert_eq!(removed.len(), 2, "{removed:?}");
        assert!(removed[0].starts_with("V-101 plan 0000000b (") && removed[1].starts_with("V-101 plan 0000000d ("));
        let names: Vec<String> = list(&out).unwrap().iter().map(|k| k.revision.clone()).collect();
        assert_eq!(names, ["0000000a", "0000000c", "0000000e", "0000000f"]);
        let left: Vec<String> = std::fs::read_dir(out.join(DIR).join("V-101"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with("0000000b") || n.starts_with("0000000d"))
            .collect();
        assert!(left.is_empty(), "{left:?}");
        assert!(out.join(DIR).join("V-101").join("notes.txt").is_file());
        assert_eq!(liftplan_docs::date_utc(0), "1970-01-01 00:00 UTC");
        assert_eq!(liftplan_docs::date_utc(951_782_400 + 23 * 3600 + 59 * 60 + 30), "2000-02-29 23:59 UTC");
    }

    /// A kept plan as a test writes it: what the comparison reads.
    fn kept(out: &Path, lift: &str, revision: &str, gross_kg: f64, steps: &[(&str, f64)], extra: serde_json::Value) {
        let steps: Vec<serde_json::Value> = steps
            .iter()
            .map(|(op, amount)| serde_json::json!({ "operation": op, "amount": amount, "unit": "m" }))
            .collect();
        let mut plan = serde_json::json!({
            "lift": lift,
            "gross_kg": gross_kg,
            "crane_model": "AC 700",
            "steps": steps,
            "planning": { "plan_ms": gross_kg, "box_queries": gross_kg },
            "summary": {
                "revision": revision,
                "validated": true,
                "steps": steps.len(),
                "highest_pad": [1, { "load_kg": 104_200.0, "pad": "RearLeft" }],
                "obstacles": [],
            },
        });
        if let (Some(p), Some(e)) = (plan.as_object_mut(), extra.as_object()) {
            p.extend(e.clone());
        }
        let file = plan_file(out, lift, revision);
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        std::fs::write(file, serde_json::json!({ "lifts": [plan] }).to_string()).unwrap();
    }

    /// A stage's settings that hold the lifts are said by what of them
    /// differs for the lift compared, where both records hold the parts
    /// (`add_lift_settings`): another lift's change alone is not taken for
    /// this lift's.
    #[test]
    fn a_change_to_another_lift_s_settings_is_said_as_such() {
        let mut inputs = BTreeMap::new();
        let settings = |a_mass: f64, b_mass: f64, seed: u64| {
            serde_json::json!({ "plan": {}, "seed": seed, "lifts": [
                { "id": "V-101", "load": { "mass_t": a_mass } },
                { "id": "P-7", "load": { "mass_t": b_mass } },
            ]})
        };
        add_lift_settings(&mut inputs, &settings(12.0, 3.0, 7));
        assert_eq!(
            inputs.keys().collect::<Vec<_>>(),
            ["settings besides the lifts", "settings of lift P-7", "settings of lift V-101"]
        );
        let record = |s: serde_json::Value| {
            let mut i = BTreeMap::new();
            i.insert("code".to_string(), "31ee".to_string());
            i.insert("settings".to_string(), blake3::hash(s.to_string().as_bytes()).to_hex().to_string());
            add_lift_settings(&mut i, &s);
            let mut charts = i.clone();
            charts.insert("file:charts/c.xlsx".to_string(), "cc".to_string());
            serde_json::json!({ "inputs": i, "stages": { "charts": charts } })
        };
        let said = |was: serde_json::Value, now: serde_json::Value| -> Vec<String> {
            inputs_that_differ(&record(was), &record(now), "V-101").iter().map(InputDiffering::said).collect()
        };
        let holds = "(the project's lifts, any of them, power lines, obstacles and [plan], [cspace]) (settings)";
        assert_eq!(
            said(settings(12.0, 3.0, 7), settings(12.0, 3.5, 7)),
            [
                "the charts stage's settings for other lifts (not V-101's own, nor those besides the lifts)"
                    .to_string(),
                format!(
                    "the plan stage's settings for other lifts (not V-101's own, nor those besides the lifts) {holds}"
                ),
            ]
        );
        assert_eq!(
            said(settings(12.0, 3.0, 7), settings(12.5, 3.0, 7))[1],
            format!("the plan stage's settings (V-101's own) {holds}")
        );
        assert_eq!(
            said(settings(12.0, 3.0, 7), settings(12.0, 3.0, 8))[1],
            format!("the plan stage's settings (those besides the lifts, not V-101's own) {holds}")
        );
        assert_eq!(
            said(settings(12.0, 3.0, 7), settings(12.5, 3.0, 8))[1],
            format!("the plan stage's settings (V-101's own and those besides the lifts) {holds}")
        );
        // A record without the parts (kept before this was) says the settings alone.
        let mut bare = record(settings(12.0, 3.0, 7));
        for part in ["settings besides the lifts", "settings of lift V-101", "settings of lift P-7"] {
            bare["inputs"].as_object_mut().unwrap().remove(part);
        }
        let d = inputs_that_differ(&bare, &record(settings(12.0, 3.5, 7)), "V-101");
        assert_eq!(d.last().unwrap().said(), format!("the plan stage's settings {holds}"));
    }

    /// Two plans of a lift: what a signer reads first where it differs,
    /// rounded as the documents give it (a gross load 0.4 kg heavier is the
    /// same 16.82 t); the first step that differs; every other value that
    /// differs by where it is, the planner's own figures left out. The lift
    /// is found where one keeps both, and named where two do.
    #[test]
    fn two_kept_plans_are_set_side_by_side() {
        let d = tempfile::tempdir().unwrap();
        let out = d.path();
        let steps = [("Hoist up", 0.5), ("Swing", 30.0), ("Hoist down", 0.5)];
        kept(out, "V-101", "0000000a", 16_819.0, &steps, serde_json::json!({ "gust_swing_per_m": 0.01 }));
        let other_steps = [("Hoist up", 0.5), ("Swing", 31.0), ("Hoist down", 0.5), ("Rotate load", 5.0)];
        let obstacle = serde_json::json!({ "gust_swing_per_m": 0.02, "summary": {
            "revision": "0000000b",
            "validated": true,
            "steps": 4,
            "highest_pad": [2, { "load_kg": 104_200.0, "pad": "FrontRight" }],
            "obstacles": ["raised work platform"],
        }});
        kept(out, "V-101", "0000000b", 17_819.0, &other_steps, obstacle);
        let made_from = |revision: &str, settings: &str| {
            let inputs = serde_json::json!({ "inputs": { "code": "31ee", "settings": settings, "upstream:scans/site.laz": "1f90" } });
            std::fs::write(inputs_file(out, "V-101", revision), inputs.to_string()).unwrap();
        };
        let c = compare(out, None, "0000000a", "0000000b").unwrap();
        assert!(
            c.said().ends_with(
                "\n  Made from: not known (a plan kept by an earlier liftplan has no record of its inputs beside it)"
            ),
            "{}",
            c.said()
        );
        // A record there that does not read is said so, not taken for none.
        made_from("0000000a", "ecaa");
        let file = inputs_file(out, "V-101", "0000000b");
        std::fs::write(&file, "{\"inputs\": {\"code\": \"31").unwrap();
        let c = compare(out, None, "0000000a", "0000000b").unwrap();
        assert!(c.inputs_differing.is_none() && c.inputs_unread.len() == 1, "{c:?}");
        let said = c.said();
        let want = format!("\n  Made from: not known: {} does not read as JSON (EOF while parsing", file.display());
        assert!(said.contains(&want), "{said}");
        std::fs::write(&file, "[1, 2]").unwrap();
        let said = compare(out, None, "0000000a", "0000000b").unwrap().said();
        assert!(said.ends_with("0000000b.inputs.json holds no record of inputs (an object \"inputs\")"), "{said}");
        made_from("0000000b", "ecab");
        let c = compare(out, None, "0000000a", "0000000b").unwrap();
        let said = c.said();
        assert!(said.ends_with("\n  Made from: the plan stage's settings (the project's lifts, any of them, power lines, obstacles and [plan], [cspace]) (settings) differs"), "{said}");
        assert!(
            said.starts_with("V-101: plan 0000000b against plan 0000000a:\n  Gross load: 16.82 t; now 17.82 t\n"),
            "{said}"
        );
        assert!(said.contains("\n  Steps: 3; now 4\n"), "{said}");
        assert!(said.contains("\n  Outrigger pad at its most: 104.2 t on the rear left pad at step 1; now 104.2 t on the front right pad at step 2\n"), "{said}");
        assert!(said.contains("\n  Obstacles placed by hand: none; now raised work platform\n"), "{said}");
        assert!(said.contains("\n  The path differs from step 2: Swing 30.00 m; now Swing 31.00 m\n"), "{said}");
        assert_eq!(c.other_values, ["/gust_swing_per_m"]);
        assert!(said.contains("\n  1 other value of the plan file differs: /gust_swing_per_m\n"), "{said}");
        assert!(!said.contains("Validated") && !said.contains("planning"), "{said}");
        // Rounded as the documents give it, and the planner's figures left out.
        kept(out, "V-101", "0000000c", 16_819.4, &steps, serde_json::json!({ "gust_swing_per_m": 0.01 }));
        made_from("0000000c", "ecaa");
        let same = compare(out, None, "0000000a", "0000000c").unwrap();
        assert_eq!((same.differences.len(), same.first_step_differing.clone()), (0, None), "{same:?}");
        assert!(same.other_values.is_empty(), "{same:?}");
        assert!(
            same.said().ends_with("no difference but for the time planning took\n  Made from: the same inputs"),
            "{}",
            same.said()
        );
        let itself = compare(out, None, "0000000a", "0000000a").unwrap().said();
        assert!(
            itself.ends_with(":\n  the same plan (one revision given twice)\n  Made from: the same inputs"),
            "{itself}"
        );
        // The lift's plan kept last (its files' times may tie: then by
        // revision), or the one in out/plan.json, the last plans.
        let last = compare(out, None, "0000000a", LAST).unwrap();
        assert_eq!((last.lift.as_str(), last.now.as_str()), ("V-101", "0000000c"));
        std::fs::write(out.join("plan.json"), plan_json(&[("V-101", "0000000b")])).unwrap();
        assert_eq!(compare(out, None, "0000000a", LAST).unwrap().now, "0000000b");
        std::fs::remove_file(out.join("plan.json")).unwrap();
        // Where both name the stages before the plan stage: their files,
        // settings and code, and the plan stage's own, not what it read.
        let with_stages = |revision: &str, scans: serde_json::Value, site: &str| {
            let inputs = serde_json::json!({
                "inputs": { "code": "31ee", "settings": "ecaa", "upstream:scans/site.laz": site },
                "stages": { "scans": scans, "charts": { "file:charts/c.xlsx": "cc" } },
            });
            std::fs::write(inputs_file(out, "V-101", revision), inputs.to_string()).unwrap();
        };
        with_stages(
            "0000000a",
            serde_json::json!({ "file:scans/a.laz": "aa", "file:scans/b.laz": "bb", "settings": "s1" }),
            "1f90",
        );
        with_stages(
            "0000000b",
            serde_json::json!({ "file:scans/a.laz": "a2", "file:scans/c.laz": "cc", "settings": "s2" }),
            "2f90",
        );
        assert_eq!(
            compare(out, None, "0000000a", "0000000b")
                .unwrap()
                .inputs_differing
                .unwrap()
                .iter()
                .map(InputDiffering::said)
                .collect::<Vec<_>>(),
            ["scans/a.laz changed", "scans/b.laz removed", "scans/c.laz added", "the scans stage's settings"]
        );
        // The run's line names each whole, brackets in a file's name too,
        // and a line break in one as U+FFFD, not as a line of its own.
        with_stages(
            "0000000b",
            serde_json::json!({ "file:scans/a.laz": "aa", "file:scans/scan (1).laz": "dd", "file:scans/s\n2.laz": "ee" }),
            "1f90",
        );
        let brief = compare(out, None, "0000000a", "0000000b").unwrap().briefly();
        assert!(
            brief.contains("; what it was made from differs: scans/b.laz removed, scans/s\u{FFFD}2.laz added, scans/scan (1).laz added, the scans stage's settings ("),
            "{brief}"
        );
        made_from("0000000a", "ecaa");
        made_from("0000000b", "ecab");
        // A run's line for a plan that replaces the last (out/plan.json's
        // before the run): the names of what differs and the command.
        let entry = out.join("entry");
        std::fs::create_dir_all(&entry).unwrap();
        std::fs::write(entry.join("plan.json"), plan_json(&[("V-101", "0000000b")])).unwrap();
        let before = vec![("V-101".to_string(), "0000000a".to_string())];
        assert_eq!(
            replaced(out, &before, &entry),
            [
                "V-101: plan 0000000b replaces plan 0000000a: gross load, steps, outrigger pad at its most, obstacles placed by hand, the path from step 2 differ; what it was made from differs: the plan stage's settings (liftplan revisions --compare 0000000a 0000000b)"
            ]
        );
        assert!(replaced(out, &[("V-101".to_string(), "0000000b".to_string())], &entry).is_empty());
        assert!(replaced(out, &[("V-101".to_string(), "0000000f".to_string())], &entry).is_empty());
        // A plan past the other's last step.
        let shorter = compare(out, Some("V-101"), "0000000b", "0000000a").unwrap();
        assert!(
            shorter.said().contains("The path differs from step 2: Swing 31.00 m; now Swing 30.00 m"),
            "{}",
            shorter.said()
        );
        // What is not kept, a lift to name, a file that is no plan.
        let e = compare(out, None, "0000000a", "0000000f").unwrap_err().to_string();
        assert!(
            e.contains("no lift keeps both plan 0000000a and plan 0000000f")
                && e.contains("plan 0000000f is not kept there"),
            "{e}"
        );
        kept(out, "V-102", "0000000a", 1.0, &steps, serde_json::json!({}));
        kept(out, "V-102", "0000000b", 1.0, &steps, serde_json::json!({}));
        let e = compare(out, None, "0000000a", "0000000b").unwrap_err().to_string();
        assert!(e.contains("lifts V-101, V-102 each keep plans 0000000a and 0000000b: name one with --lift"), "{e}");
        assert!(compare(out, Some("V-102"), "0000000a", "0000000b").unwrap().differences.is_empty());
        let e = compare(out, None, "0000000a", LAST).unwrap_err().to_string();
        assert!(e.contains("lifts V-101, V-102 each keep plan 0000000a: name one with --lift"), "{e}");
        assert_eq!(compare(out, Some("V-102"), "0000000a", LAST).unwrap().now, "0000000b");
        let e = format!("{:#}", compare(out, Some("V-103"), "0000000a", "0000000b").unwrap_err());
        assert!(e.contains("lift 'V-103' keeps no plan 0000000a in "), "{e}");
        std::fs::write(plan_file(out, "V-102", "0000000b"), "{\"lifts\": [1]}").unwrap();
        let e = format!("{:#}", compare(out, Some("V-102"), "0000000a", "0000000b").unwrap_err());
        assert!(e.contains("0000000b.plan.json does not hold a lift's plan (lifts[0].summary)"), "{e}");
    }
}
