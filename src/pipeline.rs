//! The stage graph and the make-style runner.
//!
//! Each stage declares the project files it reads, the settings that affect it
//! and the upstream output files it reads. Its key is blake3 over its name, code
//! version and the content hashes of all of those; a key already in the cache is
//! `fresh` and nothing runs. Because downstream keys hash upstream *output files*,
//! a stage that reruns but writes the same bytes does not make its downstream
//! stale (early cut-off).

use crate::cache::{self, Cache, FileHashes, Manifest};
use crate::progress::Progress;
use crate::project::Project;
use anyhow::{Context, Result, anyhow};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What a stage run gets.
pub struct Ctx<'a> {
    pub project: &'a Project,
    /// Project files this stage reads, sorted.
    pub inputs: &'a [PathBuf],
    /// Cache folders of the upstream stages that produced output.
    #[allow(dead_code)]
    pub upstream: &'a BTreeMap<&'static str, (PathBuf, Manifest)>,
    /// Folder the stage writes its outputs into.
    pub out: &'a Path,
    /// Folder the stage may keep working data in from one run to the next
    /// (`.liftplan/memo/<stage>/`, made when first written). What it keeps
    /// there may only save time: its outputs must be the same without it.
    pub memo: &'a Path,
    /// The user forced this run (`--force`): the stage must not reuse what
    /// it kept in `memo`.
    pub forced: bool,
    /// The hash of the code behind the stage ([`StageDef::code`]): what it
    /// keeps in `memo` is valid for this build only.
    pub code: &'a str,
    pub progress: &'a Progress,
}

#[allow(dead_code)] // used by the stages that read upstream artifacts
impl Ctx<'_> {
    /// Path of an upstream output, if that stage produced it.
    pub fn upstream_file(&self, stage: &str, file: &str) -> Option<PathBuf> {
        let (dir, m) = self.upstream.get(stage)?;
        m.outputs.contains_key(file).then(|| dir.join(file))
    }

    /// An upstream stage's output read by `read` (its crate's reader of
    /// that file, which refuses one not of the shape the stage writes,
    /// saying where); a refusal is said naming the file and the stage to
    /// rerun; `None` where that stage did not write it.
    pub fn upstream_read<T>(
        &self,
        stage: &str,
        file: &str,
        read: impl FnOnce(&[u8]) -> std::result::Result<T, String>,
    ) -> Result<Option<T>> {
        let Some(f) = self.upstream_file(stage, file) else { return Ok(None) };
        let bytes = std::fs::read(&f).with_context(|| format!("reading {}", f.display()))?;
        let read = read(&bytes).map_err(|e| {
            anyhow::anyhow!("{}: {e}; rerun the {stage} stage (liftplan run --force {stage})", f.display())
        })?;
        Ok(Some(read))
    }

    pub fn report(&self, stage: &str) -> impl Fn(&str, u64, u64) + Sync + '_ {
        let stage = stage.to_string();
        move |what: &str, done: u64, total: u64| self.progress.report(&stage, what, done, total)
    }
}

/// What a stage run produced.
pub struct Produced {
    /// Output file names inside `Ctx::out`, published to `out/`.
    pub outputs: Vec<String>,
    pub summary: serde_json::Value,
    /// Human lines for the run output (one per scan, per lift...).
    pub lines: Vec<String>,
}

pub struct StageDef {
    pub name: &'static str,
    pub version: u32,
    /// Hash of the code behind the stage (`build.rs`): part of its key, so a
    /// new build whose code for the stage differs runs it again.
    pub code: &'static str,
    pub about: &'static str,
    /// Project files the stage reads.
    pub inputs: fn(&Project) -> Result<Vec<PathBuf>>,
    /// The settings that affect the stage, as JSON.
    pub settings: fn(&Project) -> serde_json::Value,
    /// Upstream outputs it reads: (stage, file name or "*").
    pub reads: &'static [(&'static str, &'static str)],
    /// Whether there is anything to do; otherwise the stage is skipped.
    pub applicable: fn(&Project, &[PathBuf], &BTreeMap<&'static str, (PathBuf, Manifest)>) -> bool,
    pub run: fn(&Ctx) -> Result<Produced>,
}

pub fn stages() -> Vec<StageDef> {
    vec![
        crate::stages::scans(),
        crate::stages::plant(),
        crate::stages::charts(),
        crate::stages::depthmap(),
        crate::stages::plan(),
        crate::stages::docs(),
    ]
}

pub fn stage_names() -> Vec<&'static str> {
    stages().iter().map(|s| s.name).collect()
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    Ran,
    Fresh,
    Failed,
    Skipped,
}

#[derive(Debug, Clone, Serialize)]
pub struct StageReport {
    pub name: String,
    pub status: Status,
    pub key: Option<String>,
    pub seconds: f64,
    pub outputs: Vec<String>,
    /// Output files rewritten in out/ by this run.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub published: Vec<String>,
    /// Files this stage made before and no longer makes, moved by this run
    /// to `out/superseded/` ([`cache::publish`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub superseded: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// For each lift whose plan this run's replaces another (the plan
    /// stage's), what differs, in a line ([`liftplan::revisions::replaced`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub replaced: Vec<String>,
    #[serde(skip)]
    pub lines: Vec<String>,
}

#[derive(Debug, Clone, Serialize)]
pub struct RunReport {
    pub stages: Vec<StageReport>,
    pub ok: bool,
    /// Lifts resumed part way: whether each `resume_from` is the pose of the
    /// plan it names (`resume::check_resumed`, before the run).
    pub resume_checks: Vec<crate::resume::ResumeCheck>,
    /// Files in the input folders that no stage reads, with why
    /// ([`crate::stages::inputs_not_read`]).
    pub inputs_not_read: Vec<String>,
}

pub struct RunOptions {
    pub until: Option<String>,
    pub force: Vec<String>,
}

fn matches(pattern: &str, name: &str) -> bool {
    pattern == "*" || pattern == name
}

/// The key inputs of a stage: files, settings, upstream outputs.
fn key_inputs(
    def: &StageDef,
    project: &Project,
    files: &[PathBuf],
    hashes: &mut FileHashes,
    upstream: &BTreeMap<&'static str, (PathBuf, Manifest)>,
) -> Result<(BTreeMap<String, String>, serde_json::Value)> {
    let mut inputs = BTreeMap::new();
    inputs.insert("code".to_string(), def.code.to_string());
    for f in files {
        let rel = f.strip_prefix(&project.dir).unwrap_or(f).to_string_lossy().into_owned();
        inputs.insert(format!("file:{rel}"), hashes.hash(f)?);
    }
    let settings = (def.settings)(project);
    inputs.insert("settings".into(), blake3::hash(settings.to_string().as_bytes()).to_hex().to_string());
    for (stage, pat) in def.reads {
        match upstream.get(stage) {
            Some((_, m)) => {
                let mut any = false;
                for (name, h) in &m.outputs {
                    if matches(pat, name) {
                        inputs.insert(format!("upstream:{stage}/{name}"), h.clone());
                        any = true;
                    }
                }
                if !any {
                    inputs.insert(format!("upstream:{stage}/{pat}"), "absent".into());
                }
            }
            None => {
                inputs.insert(format!("upstream:{stage}/{pat}"), "absent".into());
            }
        }
    }
    Ok((inputs, settings))
}

/// Runs the stages in order; see the module docs.
pub fn run(project: &Project, opts: &RunOptions, progress: &Progress) -> Result<RunReport> {
    let mut report = run_stages(project, &stages(), opts, progress)?;
    report.inputs_not_read = crate::stages::inputs_not_read(project);
    Ok(report)
}

fn run_stages(project: &Project, defs: &[StageDef], opts: &RunOptions, progress: &Progress) -> Result<RunReport> {
    let names: Vec<&str> = defs.iter().map(|d| d.name).collect();
    if let Some(u) = &opts.until
        && !names.contains(&u.as_str())
    {
        return Err(anyhow!("--until {u}: no such stage (stages: {})", names.join(", ")));
    }
    for f in &opts.force {
        if !names.contains(&f.as_str()) {
            return Err(anyhow!("--force {f}: no such stage (stages: {})", names.join(", ")));
        }
    }
    let cache = Cache::new(&project.state_dir());
    cache.sweep();
    keep_earlier_plans(project, &cache);
    let mut hashes = FileHashes::load(&project.state_dir());
    let mut upstream: BTreeMap<&'static str, (PathBuf, Manifest)> = BTreeMap::new();
    let mut reports = Vec::new();
    let mut failed = false;
    // Stages that failed, or were not run because one they read failed.
    let mut stopped: std::collections::BTreeSet<&'static str> = std::collections::BTreeSet::new();
    let mut past_until = false;
    for def in defs {
        let mut rep = StageReport {
            name: def.name.into(),
            status: Status::Skipped,
            key: None,
            seconds: 0.0,
            outputs: vec![],
            published: vec![],
            superseded: vec![],
            error: None,
            reason: None,
            replaced: vec![],
            lines: vec![],
        };
        // A failed stage stops only the stages that read it (and theirs):
        // the others still run, so that one run names every input's
        // problem (a damaged scan and a plant file in a unit not stated
        // were found one run apart), and their outputs stay current.
        if let Some(upstream_failed) = def.reads.iter().map(|(s, _)| *s).find(|s| stopped.contains(s)) {
            rep.reason = Some(format!("the {upstream_failed} stage it reads failed"));
            stopped.insert(def.name);
            reports.push(rep);
            continue;
        }
        if past_until {
            rep.reason = Some("after --until".into());
            reports.push(rep);
            continue;
        }
        let t0 = Instant::now();
        let outcome = (|| -> Result<()> {
            let files = (def.inputs)(project)?;
            if !(def.applicable)(project, &files, &upstream) {
                rep.reason = Some("nothing to do (no inputs)".into());
                return Ok(());
            }
            let (inputs, settings) = key_inputs(def, project, &files, &mut hashes, &upstream)?;
            let key = cache::key(def.name, def.version, &inputs);
            rep.key = Some(key.clone());
            let forced = opts.force.iter().any(|f| f == def.name);
            let m = match cache.lookup(def.name, &key).filter(|_| !forced) {
                Some(m) => {
                    rep.status = Status::Fresh;
                    cache.touch(def.name, &key);
                    m
                }
                None => {
                    let tmp = cache.temp_dir(def.name)?;
                    let memo = project.state_dir().join("memo").join(def.name);
                    let ctx = Ctx {
                        project,
                        inputs: &files,
                        upstream: &upstream,
                        out: &tmp,
                        memo: &memo,
                        forced,
                        code: def.code,
                        progress,
                    };
                    let produced = match (def.run)(&ctx) {
                        Ok(p) => p,
                        Err(e) => {
                            let _ = std::fs::remove_dir_all(&tmp);
                            return Err(e);
                        }
                    };
                    // The key names the files as they were hashed before the run.
                    // A file written during the run (a copy still going, a scan
                    // re-exported) may have been read half old, half new; kept
                    // under that key, such a result would be served as fresh
                    // once the file is back to what was hashed.
                    let changed = hashes.changed_since_hashed(&files);
                    if !changed.is_empty() {
                        let _ = std::fs::remove_dir_all(&tmp);
                        let names: Vec<String> =
                            changed.iter().map(|f| liftplan_core::location::shown(f, Some(&project.dir))).collect();
                        return Err(anyhow!(
                            "{} changed (written, replaced or removed) while the {} stage ran; its result was not kept: run again once the files are complete",
                            names.join(", "),
                            def.name
                        ));
                    }
                    let m = Manifest {
                        stage: def.name.into(),
                        version: def.version,
                        key: key.clone(),
                        inputs,
                        settings,
                        outputs: produced.outputs.iter().map(|o| (o.clone(), String::new())).collect(),
                        summary: produced.summary,
                        lines: produced.lines,
                        seconds: t0.elapsed().as_secs_f64(),
                    };
                    let m = cache.commit(&tmp, m).inspect_err(|_| {
                        let _ = std::fs::remove_dir_all(&tmp);
                    })?;
                    rep.status = Status::Ran;
                    m
                }
            };
            let dir = cache.entry_dir(def.name, &key);
            // The last plans, before this run's take their place.
            let last_plans = if def.name == liftplan_plan::NAME {
                liftplan::revisions::last_plans(&project.out_dir())
            } else {
                Vec::new()
            };
            let published = cache::publish(&project.out_dir(), &dir, &m)?;
            rep.published = published.written;
            rep.outputs = m.outputs.keys().map(|o| format!("out/{o}")).collect();
            rep.lines = m.lines.clone();
            // Kept as soon as made: a stage after it may read it by revision.
            if def.name == liftplan_plan::NAME {
                keep_revisions(project, &dir, &upstream, &mut rep.lines);
                rep.replaced = liftplan::revisions::replaced(&project.out_dir(), &last_plans, &dir);
                rep.lines.extend(rep.replaced.iter().cloned());
            }
            if def.name == liftplan_docs::NAME
                && let Some((plan_dir, _)) = upstream.get(liftplan_plan::NAME)
            {
                keep_documents(project, plan_dir, &dir, &mut rep.lines);
            }
            if !published.superseded.is_empty() {
                rep.lines.push(format!(
                    "no longer made (a lift taken out of the project or renamed), moved to out/{}/: {}",
                    cache::SUPERSEDED_DIR,
                    published.superseded.join(", ")
                ));
                rep.superseded = published.superseded;
            }
            upstream.insert(def.name, (dir, m));
            Ok(())
        })();
        rep.seconds = t0.elapsed().as_secs_f64();
        if let Err(e) = outcome {
            rep.status = Status::Failed;
            rep.error = Some(format!("{e:#}"));
            failed = true;
            stopped.insert(def.name);
        }
        if opts.until.as_deref() == Some(def.name) {
            past_until = true;
        }
        reports.push(rep);
    }
    hashes.save(&project.state_dir())?;
    // Only after every stage: a stage reads its upstream stages' entries.
    for rep in &reports {
        if let (Status::Fresh | Status::Ran, Some(key)) = (&rep.status, &rep.key) {
            for dropped in cache.prune(&rep.name, key, project.raw.cache.keep) {
                tracing::debug!("cache: dropped {} {dropped} (past [cache] keep)", rep.name);
            }
        }
    }
    let report = RunReport { ok: !failed, stages: reports, resume_checks: Vec::new(), inputs_not_read: Vec::new() };
    cache.record_run(&serde_json::json!({
        "liftplan": env!("CARGO_PKG_VERSION"),
        "finished_unix": std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_secs()).unwrap_or(0),
        "stage_versions": defs.iter().map(|d| (d.name, d.version)).collect::<BTreeMap<_, _>>(),
        "report": report,
    }))?;
    Ok(report)
}

/// Keeps the plan the plan stage made or found fresh (in `plan_dir`) in
/// out/revisions/ ([`liftplan::revisions`]), and says so in the stage's
/// lines. A plan that could not be kept is said there too and does not
/// fail the run: the plan in out/ is made and checked; only reading it by
/// revision later depends on this.
fn keep_revisions(
    project: &Project,
    plan_dir: &Path,
    upstream: &BTreeMap<&'static str, (PathBuf, Manifest)>,
    lines: &mut Vec<String>,
) {
    // What the stages before it were made from, kept with each plan.
    let stages: BTreeMap<String, BTreeMap<String, String>> = upstream
        .iter()
        .map(|(stage, (_, m))| {
            let mut inputs = m.inputs.clone();
            liftplan::revisions::add_lift_settings(&mut inputs, &m.settings);
            (stage.to_string(), inputs)
        })
        .collect();
    said_kept(
        liftplan::revisions::keep_made_from(&project.out_dir(), plan_dir, Some(&stages)),
        ": liftplan resume reads this plan only while out/ or the cache holds it",
        lines,
    );
}

/// Keeps the PDFs the docs stage made or found fresh (in `docs_dir`), of
/// the plans in `plan_dir`, by revision beside them
/// ([`liftplan::revisions::keep_documents`]), and says so as
/// [`keep_revisions`] does.
fn keep_documents(project: &Project, plan_dir: &Path, docs_dir: &Path, lines: &mut Vec<String>) {
    said_kept(liftplan::revisions::keep_documents(&project.out_dir(), plan_dir, docs_dir), "", lines);
}

/// What a keeping by revision kept, or why it did not (then `if_not` after
/// the error), as a line of the stage's; nothing where nothing was new.
fn said_kept(kept: Result<Vec<String>>, if_not: &str, lines: &mut Vec<String>) {
    let folder = format!("out/{}/", liftplan::revisions::DIR);
    match kept {
        Ok(kept) if kept.is_empty() => {}
        Ok(kept) => lines.push(format!("kept by revision in {folder}: {}", kept.join(", "))),
        Err(e) => lines.push(format!("warning: not kept by revision in {folder} ({e:#}){if_not}")),
    }
}

/// Keeps, before a run, the plans an earlier one left (out/ and the plan
/// stage's cache) that out/revisions/ does not hold: those made by a
/// liftplan that kept none, so that a crew's plan among them is read by
/// revision from the run that resumes it on. Nothing to keep, or a file
/// that does not read, is passed by.
fn keep_earlier_plans(project: &Project, cache: &Cache) {
    let out = project.out_dir();
    // The cache's first: out/plan.json may have been edited by hand, and
    // a revision is kept once.
    for dir in cache.entries(liftplan_plan::NAME).into_iter().chain([out.clone()]) {
        if dir.join("plan.json").is_file()
            && let Err(e) = liftplan::revisions::keep(&out, &dir)
        {
            tracing::debug!("not kept by revision: {e:#}");
        }
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct StageStatus {
    pub name: String,
    /// fresh | stale | skipped
    pub state: String,
    pub key: Option<String>,
    pub why: Vec<String>,
}

/// Each stage fresh or stale, and why; runs nothing.
pub fn status(project: &Project) -> Result<Vec<StageStatus>> {
    let cache = Cache::new(&project.state_dir());
    let mut hashes = FileHashes::load(&project.state_dir());
    let mut upstream: BTreeMap<&'static str, (PathBuf, Manifest)> = BTreeMap::new();
    let mut stale_upstream: Vec<&str> = Vec::new();
    let mut out = Vec::new();
    for def in stages() {
        let files = (def.inputs)(project)?;
        if !(def.applicable)(project, &files, &upstream) && stale_upstream.is_empty() {
            out.push(StageStatus {
                name: def.name.into(),
                state: "skipped".into(),
                key: None,
                why: vec!["nothing to do (no inputs)".into()],
            });
            continue;
        }
        let mut blocked: Vec<&str> = def.reads.iter().map(|r| r.0).filter(|s| stale_upstream.contains(s)).collect();
        // A stage may read several files of one upstream stage: name it once.
        blocked.dedup();
        if !blocked.is_empty() {
            out.push(StageStatus {
                name: def.name.into(),
                state: "stale".into(),
                key: None,
                why: blocked.iter().map(|s| format!("upstream stage {s} is stale")).collect(),
            });
            stale_upstream.push(def.name);
            continue;
        }
        let (inputs, settings) = key_inputs(&def, project, &files, &mut hashes, &upstream)?;
        let key = cache::key(def.name, def.version, &inputs);
        if let Some(m) = cache.lookup(def.name, &key) {
            upstream.insert(def.name, (cache.entry_dir(def.name, &key), m));
            out.push(StageStatus { name: def.name.into(), state: "fresh".into(), key: Some(key), why: vec![] });
            continue;
        }
        let why = match cache.last(def.name) {
            None => vec!["never ran".into()],
            Some(last) => explain(&last, def.version, &inputs, &settings),
        };
        stale_upstream.push(def.name);
        out.push(StageStatus { name: def.name.into(), state: "stale".into(), key: Some(key), why });
    }
    hashes.save(&project.state_dir())?;
    Ok(out)
}

fn explain(
    last: &Manifest,
    version: u32,
    inputs: &BTreeMap<String, String>,
    settings: &serde_json::Value,
) -> Vec<String> {
    let mut why = Vec::new();
    if last.version != version {
        why.push(format!("stage code changed (version {} -> {version})", last.version));
    }
    if last.inputs.get("code") != inputs.get("code") {
        why.push("liftplan's code for this stage changed (a new build)".into());
    }
    // An input file's name in words: one line, whatever it holds.
    let file = |k: &str| liftplan_core::names::without_controls(k.trim_start_matches("file:")).into_owned();
    for (k, v) in inputs {
        if k == "settings" || k == "code" {
            continue;
        }
        match last.inputs.get(k) {
            None => why.push(format!("{} added", file(k))),
            Some(old) if old != v => why.push(format!("{} changed", file(k))),
            _ => {}
        }
    }
    for k in last.inputs.keys() {
        if k != "settings" && k != "code" && !inputs.contains_key(k) {
            why.push(format!("{} removed", file(k)));
        }
    }
    diff_settings("", &last.settings, settings, &mut why);
    if why.is_empty() {
        why.push("its cached result is missing".into());
    }
    why
}

fn diff_settings(prefix: &str, a: &serde_json::Value, b: &serde_json::Value, why: &mut Vec<String>) {
    match (a, b) {
        (serde_json::Value::Object(x), serde_json::Value::Object(y)) => {
            for (k, vb) in y {
                let p = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                match x.get(k) {
                    Some(va) => diff_settings(&p, va, vb, why),
                    None => why.push(format!("setting {p} added")),
                }
            }
            for k in x.keys() {
                if !y.contains_key(k) {
                    why.push(format!("setting {prefix}.{k} removed"));
                }
            }
        }
        _ if a != b => why.push(format!("setting {prefix} changed ({a} -> {b})")),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan_files(p: &Project) -> Result<Vec<PathBuf>> {
        p.files(&p.raw.paths.scans, &["xyz"])
    }

    fn no_settings(_: &Project) -> serde_json::Value {
        serde_json::Value::Null
    }

    fn always(_: &Project, _: &[PathBuf], _: &BTreeMap<&'static str, (PathBuf, Manifest)>) -> bool {
        true
    }

    /// Copies its input to `copy.xyz`.
    fn copy(ctx: &Ctx) -> Result<Produced> {
        std::fs::copy(&ctx.inputs[0], ctx.out.join("copy.xyz"))?;
        Ok(Produced { outputs: vec!["copy.xyz".into()], summary: serde_json::Value::Null, lines: vec![] })
    }

    /// Copies its input while a survey copy of the same file starts over:
    /// the file is written again, with the same bytes in the end.
    fn copy_while_rewritten(ctx: &Ctx) -> Result<Produced> {
        let bytes = std::fs::read(&ctx.inputs[0])?;
        std::fs::write(&ctx.inputs[0], &bytes[..bytes.len() / 2])?;
        let produced = copy(ctx)?;
        std::fs::write(&ctx.inputs[0], &bytes)?;
        Ok(produced)
    }

    fn stage(run: fn(&Ctx) -> Result<Produced>) -> StageDef {
        built(run, "build-1")
    }

    fn built(run: fn(&Ctx) -> Result<Produced>, code: &'static str) -> StageDef {
        StageDef {
            name: "copy",
            version: 1,
            code,
            about: "copies a scan",
            inputs: scan_files,
            settings: no_settings,
            reads: &[],
            applicable: always,
            run,
        }
    }

    #[test]
    fn a_result_read_from_a_file_that_changed_during_the_run_is_not_kept() {
        let t = tempfile::tempdir().unwrap();
        crate::project::init(t.path()).unwrap();
        let scan = t.path().join("scans").join("a.xyz");
        let text: String = (0..1000).map(|k| format!("{k} 0 0\n")).collect();
        std::fs::write(&scan, &text).unwrap();
        let project = Project::load(t.path()).unwrap();
        let opts = RunOptions { until: None, force: vec![] };
        let progress = Progress::new(true);

        let first = run_stages(&project, &[stage(copy_while_rewritten)], &opts, &progress).unwrap();
        assert!(!first.ok);
        assert_eq!(first.stages[0].status, Status::Failed);
        let error = first.stages[0].error.clone().unwrap_or_default();
        assert!(
            error.contains("scans/a.xyz changed (written, replaced or removed) while the copy stage ran"),
            "{error}"
        );
        assert!(!project.out_dir().join("copy.xyz").exists());

        // The scan is as it was hashed, but the half copy was not kept: the
        // stage runs again and copies the whole file, then is fresh.
        assert_eq!(std::fs::read_to_string(&scan).unwrap(), text);
        let second = run_stages(&project, &[stage(copy)], &opts, &progress).unwrap();
        assert_eq!(second.stages[0].status, Status::Ran, "{:?}", second.stages[0]);
        assert_eq!(std::fs::read_to_string(project.out_dir().join("copy.xyz")).unwrap(), text);
        let third = run_stages(&project, &[stage(copy)], &opts, &progress).unwrap();
        assert_eq!(third.stages[0].status, Status::Fresh);
    }

    #[test]
    fn a_build_with_other_code_for_a_stage_runs_it_again() {
        let t = tempfile::tempdir().unwrap();
        crate::project::init(t.path()).unwrap();
        std::fs::write(t.path().join("scans").join("a.xyz"), "0 0 0\n1 0 0\n").unwrap();
        let project = Project::load(t.path()).unwrap();
        let opts = RunOptions { until: None, force: vec![] };
        let progress = Progress::new(true);
        let status = |code| run_stages(&project, &[built(copy, code)], &opts, &progress).unwrap().stages[0].status;
        assert_eq!(status("build-1"), Status::Ran);
        assert_eq!(status("build-1"), Status::Fresh);
        assert_eq!(status("build-2"), Status::Ran);
        let last = Cache::new(&project.state_dir()).last("copy").unwrap();
        let files = scan_files(&project).unwrap();
        let mut hashes = FileHashes::load(&project.state_dir());
        let (inputs, settings) =
            key_inputs(&built(copy, "build-3"), &project, &files, &mut hashes, &BTreeMap::new()).unwrap();
        assert_eq!(explain(&last, 1, &inputs, &settings), vec!["liftplan's code for this stage changed (a new build)"]);
    }
}
