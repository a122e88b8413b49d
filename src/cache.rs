//! The content-addressed stage cache under `.liftplan/`.
//!
//! ```text
//! .liftplan/
//!   cache/<stage>/<key>/     outputs of one stage run + manifest.json
//!                            (the `[cache] keep` most recently used per stage)
//!   cache/<stage>/.tmp-*     a run in progress (never trusted, swept)
//!   last/<stage>.json        manifest of the stage's last successful run
//!   memo/<stage>/            what a stage keeps to save time on its next run
//!                            (registration's trials); never changes an output
//!   runs/<n>.json            one record per `run` (keys, timings, versions)
//!   hashes.json              file hashes by (size, mtime, inode): saves rehashing
//!   log/                     watch-mode log
//! out/.manifest.json         which output file in out/ has which hash
//! ```
//!
//! A stage's outputs appear under `<key>/` by one atomic rename of a complete
//! folder, so a killed run leaves at most a `.tmp-*` folder that nothing reads.
//!
//! Entries are dropped past the `[cache] keep` most recently used per stage
//! ([`Cache::prune`]): a site whose scans arrive one by one in watch mode
//! would otherwise keep every version of its site cloud. A dropped entry only
//! costs a rerun if its inputs come back.

use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What a finished stage run left in its cache folder.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Manifest {
    pub stage: String,
    pub version: u32,
    pub key: String,
    /// Input name (project-relative path, `setting:<section>`, `upstream:<stage>/<file>`) to hash.
    pub inputs: BTreeMap<String, String>,
    /// The settings the stage ran with (for `status` to say which one changed).
    pub settings: serde_json::Value,
    /// Output file name to blake3 hash.
    pub outputs: BTreeMap<String, String>,
    pub summary: serde_json::Value,
    pub lines: Vec<String>,
    pub seconds: f64,
}

pub struct Cache {
    pub root: PathBuf,
}

impl Cache {
    pub fn new(state_dir: &Path) -> Cache {
        Cache { root: state_dir.to_path_buf() }
    }

    pub fn entry_dir(&self, stage: &str, key: &str) -> PathBuf {
        self.root.join("cache").join(stage).join(key)
    }

    /// The manifest of a complete cache entry, if there is one.
    pub fn lookup(&self, stage: &str, key: &str) -> Option<Manifest> {
        let dir = self.entry_dir(stage, key);
        let text = std::fs::read_to_string(dir.join("manifest.json")).ok()?;
        let m: Manifest = serde_json::from_str(&text).ok()?;
        // Every output must still be there with its size (cheap; hashes were
        // checked when the entry was made and entries are never edited).
        for name in m.outputs.keys() {
            if !dir.join(name).is_file() {
                return None;
            }
        }
        (m.key == key).then_some(m)
    }

    /// A fresh temporary folder for a stage run.
    pub fn temp_dir(&self, stage: &str) -> Result<PathBuf> {
        let base = self.root.join("cache").join(stage);
        std::fs::create_dir_all(&base).with_context(|| format!("creating {}", base.display()))?;
        let d = base.join(format!(".tmp-{}-{}", std::process::id(), nanos()));
        std::fs::create_dir_all(&d)?;
        Ok(d)
    }

    /// Seals a finished run: hashes outputs, writes the manifest, renames the
    /// folder into place.
    pub fn commit(&self, tmp: &Path, mut m: Manifest) -> Result<Manifest> {
        for name in m.outputs.clone().keys() {
            let h = liftplan_core::artifact::hash_file(&tmp.join(name))
                .with_context(|| format!("stage {} did not write {name}", m.stage))?;
            m.outputs.insert(name.clone(), h.to_hex().to_string());
        }
        liftplan_core::artifact::write_atomic(
            &tmp.join("manifest.json"),
            serde_json::to_string_pretty(&m)?.as_bytes(),
        )?;
        let dest = self.entry_dir(&m.stage, &m.key);
        if dest.exists() {
            // A forced rerun replaces the old entry.
            let old = dest.with_extension(format!("old-{}", nanos()));
            std::fs::rename(&dest, &old)?;
            let _ = std::fs::remove_dir_all(&old);
        }
        std::fs::rename(tmp, &dest).with_context(|| format!("moving {} into place", dest.display()))?;
        let last = self.root.join("last");
        std::fs::create_dir_all(&last)?;
        liftplan_core::artifact::write_atomic(
            &last.join(format!("{}.json", m.stage)),
            serde_json::to_string_pretty(&m)?.as_bytes(),
        )?;
        Ok(m)
    }

    /// The last successful run of a stage, for `status` to explain staleness.
    pub fn last(&self, stage: &str) -> Option<Manifest> {
        let text = std::fs::read_to_string(self.root.join("last").join(format!("{stage}.json"))).ok()?;
        serde_json::from_str(&text).ok()
    }

    /// The folders of the stage's complete entries, the most recently used
    /// first (of equal times, the larger key first).
    pub fn entries(&self, stage: &str) -> Vec<PathBuf> {
        self.by_use(stage)
            .into_iter()
            .map(|(_, key)| self.entry_dir(stage, &key))
            .filter(|e| e.join("manifest.json").is_file())
            .collect()
    }

    /// The stage's entry folders (not runs in progress or being dropped)
    /// with their manifest's time (the epoch where it has none), the most
    /// recently used first; of equal times, the larger key first, so that
    /// the order does not depend on the folder listing's.
    fn by_use(&self, stage: &str) -> Vec<(std::time::SystemTime, String)> {
        let Ok(dir) = std::fs::read_dir(self.root.join("cache").join(stage)) else {
            return vec![];
        };
        let mut found: Vec<(std::time::SystemTime, String)> = dir
            .flatten()
            .filter_map(|e| {
                let key = e.file_name().to_str()?.to_string();
                if key.starts_with('.') || key.contains(".old-") || !e.path().is_dir() {
                    return None;
                }
                let used = std::fs::metadata(e.path().join("manifest.json")).and_then(|m| m.modified());
                Some((used.unwrap_or(std::time::UNIX_EPOCH), key))
            })
            .collect();
        found.sort_by(|a, b| b.cmp(a));
        found
    }

    /// Removes folders left by killed runs.
    pub fn sweep(&self) {
        let Ok(stages) = std::fs::read_dir(self.root.join("cache")) else {
            return;
        };
        for s in stages.flatten() {
            let Ok(entries) = std::fs::read_dir(s.path()) else {
                continue;
            };
            for e in entries.flatten() {
                let n = e.file_name().to_string_lossy().into_owned();
                if n.starts_with(".tmp-") || n.contains(".old-") {
                    let _ = std::fs::remove_dir_all(e.path());
                }
            }
        }
    }

    /// Marks an entry as used now, for [`Cache::prune`] (best effort: an
    /// entry whose time cannot be set is only dropped sooner).
    pub fn touch(&self, stage: &str, key: &str) {
        let manifest = self.entry_dir(stage, key).join("manifest.json");
        if let Ok(f) = std::fs::File::options().append(true).open(manifest) {
            let _ = f.set_modified(std::time::SystemTime::now());
        }
    }

    /// Drops the stage's entries past the `keep` most recently used (by their
    /// manifest's time: made or [`Cache::touch`]ed), never `in_use`. Each is
    /// renamed out of the way (`.old-`) before it is removed, so a crash
    /// midway leaves nothing [`Cache::lookup`] trusts and [`Cache::sweep`]
    /// finishes it. Returns the keys dropped.
    pub fn prune(&self, stage: &str, in_use: &str, keep: usize) -> Vec<String> {
        let others = self.by_use(stage).into_iter().filter(|(_, key)| key != in_use);
        let mut dropped = Vec::new();
        for (_, key) in others.skip(keep.saturating_sub(1)) {
            let entry = self.entry_dir(stage, &key);
            let old = entry.with_extension(format!("old-{}", nanos()));
            if std::fs::rename(&entry, &old).is_ok() {
                let _ = std::fs::remove_dir_all(&old);
                dropped.push(key);
            }
        }
        dropped
    }

    /// Records a run as `.liftplan/runs/<n>.json`.
    pub fn record_run(&self, record: &serde_json::Value) -> Result<PathBuf> {
        let dir = self.root.join("runs");
        std::fs::create_dir_all(&dir)?;
        let n = std::fs::read_dir(&dir)?
            .flatten()
            .filter_map(|e| e.path().file_stem().and_then(|s| s.to_str()).and_then(|s| s.parse::<u64>().ok()))
            .max()
            .map(|m| m + 1)
            .unwrap_or(1);
        let p = dir.join(format!("{n}.json"));
        liftplan_core::artifact::write_atomic(&p, serde_json::to_string_pretty(record)?.as_bytes())?;
        Ok(p)
    }
}

fn nanos() -> u128 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_nanos()).unwrap_or(0)
}

/// Content hashes of input files, remembered by (size, mtime, ctime, inode) so a
/// no-op rerun does not read gigabytes of scans. A file whose metadata changed
/// (touched, copied over) is hashed again; the key always uses the content hash.
#[derive(Default, Serialize, Deserialize)]
pub struct FileHashes {
    entries: BTreeMap<String, (String, String)>,
    #[serde(skip)]
    dirty: bool,
}

fn stamp(meta: &std::fs::Metadata) -> String {
    use std::os::unix::fs::MetadataExt;
    format!(
        "{}:{}.{}:{}.{}:{}",
        meta.len(),
        meta.mtime(),
        meta.mtime_nsec(),
        meta.ctime(),
        meta.ctime_nsec(),
        meta.ino()
    )
}

impl FileHashes {
    pub fn load(state_dir: &Path) -> FileHashes {
        std::fs::read_to_string(state_dir.join("hashes.json"))
            .ok()
            .and_then(|t| serde_json::from_str(&t).ok())
            .unwrap_or_default()
    }

    pub fn save(&self, state_dir: &Path) -> Result<()> {
        if self.dirty {
            std::fs::create_dir_all(state_dir)?;
            liftplan_core::artifact::write_atomic(
                &state_dir.join("hashes.json"),
                serde_json::to_string(self)?.as_bytes(),
            )?;
        }
        Ok(())
    }

    /// The files written, replaced or removed since [`FileHashes::hash`] last
    /// looked at them (their stamp differs from the one their hash was taken
    /// at), and files never hashed.
    pub fn changed_since_hashed(&self, files: &[PathBuf]) -> Vec<PathBuf> {
        files
            .iter()
            .filter(|f| {
                let now = std::fs::metadata(f).ok().map(|m| stamp(&m));
                let then = self.entries.get(f.to_string_lossy().as_ref()).map(|(st, _)| st);
                now.is_none() || now.as_ref() != then
            })
            .cloned()
            .collect()
    }

    pub fn hash(&mut self, path: &Path) -> Result<String> {
        let meta = std::fs::metadata(path).with_context(|| format!("reading {}", path.display()))?;
        let s = stamp(&meta);
        let k = path.to_string_lossy().into_owned();
        if let Some((st, h)) = self.entries.get(&k)
            && *st == s
        {
            return Ok(h.clone());
        }
        let h = liftplan_core::artifact::hash_file(path)
            .with_context(|| format!("reading {}", path.display()))?
            .to_hex()
            .to_string();
        self.entries.insert(k, (s, h.clone()));
        self.dirty = true;
        Ok(h)
    }
}

/// The key of a stage run: blake3 over its name, code version and every input.
pub fn key(stage: &str, version: u32, inputs: &BTreeMap<String, String>) -> String {
    let mut h = blake3::Hasher::new();
    h.update(b"liftplan-stage-key-v1\0");
    h.update(stage.as_bytes());
    h.update(&version.to_le_bytes());
    for (k, v) in inputs {
        h.update(&(k.len() as u64).to_le_bytes());
        h.update(k.as_bytes());
        h.update(&(v.len() as u64).to_le_bytes());
        h.update(v.as_bytes());
    }
    h.finalize().to_hex()[..32].to_string()
}

/// What [`publish`] did in `out/`.
#[derive(Debug, Default)]
pub struct Published {
    /// Outputs rewritten.
    pub written: Vec<String>,
    /// Files the stage made before and no longer makes (a lift taken out of
    /// the project, or renamed), moved to `out/superseded/`.
    pub superseded: Vec<String>,
}

/// Where [`publish`] moves what a stage no longer makes.
pub const SUPERSEDED_DIR: &str = "superseded";

/// Copies outputs into `out/` where their content changed; `out/` is touched
/// only after a stage succeeded, one file at a time by atomic rename. What
/// the stage published before and no longer makes is moved to
/// `out/superseded/`: a lift's plan left in `out/` after the lift was taken
/// out of the project, or renamed, would read as current, VALIDATED.
pub fn publish(out_dir: &Path, entry_dir: &Path, m: &Manifest) -> Result<Published> {
    std::fs::create_dir_all(out_dir)?;
    let man_path = out_dir.join(".manifest.json");
    let mut man: BTreeMap<String, String> =
        std::fs::read_to_string(&man_path).ok().and_then(|t| serde_json::from_str(&t).ok()).unwrap_or_default();
    let by_path = out_dir.join(".published.json");
    let mut by_stage: BTreeMap<String, Vec<String>> =
        std::fs::read_to_string(&by_path).ok().and_then(|t| serde_json::from_str(&t).ok()).unwrap_or_default();
    let mut superseded = Vec::new();
    let before = by_stage.get(&m.stage).cloned().unwrap_or_default();
    // Only names of files in out/ itself or below it, as a stage writes them:
    // the list is a file in out/, which anyone may edit.
    let plain = |name: &str| {
        let p = Path::new(name);
        p.components().count() > 0 && p.components().all(|c| matches!(c, std::path::Component::Normal(_)))
    };
    for name in before.iter().filter(|n| !m.outputs.contains_key(*n) && plain(n)) {
        let from = out_dir.join(name);
        if from.is_file() {
            let to = unused_name(&out_dir.join(SUPERSEDED_DIR).join(name));
            if let Some(parent) = to.parent() {
                std::fs::create_dir_all(parent)?;
            }
            std::fs::rename(&from, &to).with_context(|| format!("moving {name} to {}", to.display()))?;
            superseded.push(name.clone());
        }
        man.remove(name);
    }
    let now: Vec<String> = m.outputs.keys().cloned().collect();
    let listed_changed = before != now;
    by_stage.insert(m.stage.clone(), now);
    let mut written = Vec::new();
    for (name, hash) in &m.outputs {
        let dest = out_dir.join(name);
        if man.get(name) == Some(hash) && dest.is_file() {
            continue;
        }
        if let Some(parent) = dest.parent() {
            std::fs::create_dir_all(parent)?;
        }
        let tmp = dest.with_file_name(format!(
            ".{}.tmp-{}",
            dest.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default(),
            std::process::id()
        ));
        std::fs::copy(entry_dir.join(name), &tmp)
            .with_context(|| format!("copying {name} to {}", out_dir.display()))?;
        std::fs::rename(&tmp, &dest)?;
        man.insert(name.clone(), hash.clone());
        written.push(name.clone());
    }
    if !written.is_empty() || !superseded.is_empty() {
        liftplan_core::artifact::write_atomic(&man_path, serde_json::to_string_pretty(&man)?.as_bytes())?;
    }
    if listed_changed {
        liftplan_core::artifact::write_atomic(&by_path, serde_json::to_string_pretty(&by_stage)?.as_bytes())?;
    }
    Ok(Published { written, superseded })
}

/// `path` where no file has that name, else the first of `stem.2.ext`,
/// `stem.3.ext`, ... that is free: a lift taken out twice (or renamed, then
/// renamed back and out again) leaves each plan it had, none renamed over
/// another. Past [`MAX_SUPERSEDED_COPIES`] the last is replaced.
fn unused_name(path: &Path) -> std::path::PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    // "V-101.steps.csv" numbers as "V-101.2.steps.csv": the extension a
    // viewer opens it by stays at the end.
    let (stem, ext) = match name.split_once('.') {
        Some((stem, ext)) if !stem.is_empty() => (stem.to_string(), format!(".{ext}")),
        _ => (name.clone(), String::new()),
    };
    std::iter::once(path.to_path_buf())
        .chain((2..=MAX_SUPERSEDED_COPIES).map(|k| path.with_file_name(format!("{stem}.{k}{ext}"))))
        .find(|p| !p.exists())
        .unwrap_or_else(|| path.with_file_name(format!("{stem}.{MAX_SUPERSEDED_COPIES}{ext}")))
}

/// How many copies of one name `out/superseded/` keeps.
pub const MAX_SUPERSEDED_COPIES: usize = 1000;

#[cfg(test)]
mod tests {
    use super::*;

    fn manifest(outputs: &[&str]) -> Manifest {
        Manifest {
            stage: "docs".into(),
            version: 1,
            key: "k".into(),
            inputs: BTreeMap::new(),
            settings: serde_json::Value::Null,
            outputs: outputs.iter().map(|o| (o.to_string(), format!("hash of {o}"))).collect(),
            summary: serde_json::Value::Null,
            lines: vec![],
            seconds: 0.0,
        }
    }

    /// A stage's entries, the most recently used first, without the
    /// folders of runs in progress or being dropped, or one with no
    /// manifest (never complete).
    #[test]
    fn a_stages_entries_most_recently_used_first() {
        let d = tempfile::tempdir().unwrap();
        let cache = Cache::new(d.path());
        assert!(cache.entries("plan").is_empty());
        let at = |secs: u64| std::time::UNIX_EPOCH + std::time::Duration::from_secs(secs);
        for (key, secs) in [("aaaa", 3000), ("bbbb", 1000), ("cccc", 2000), (".tmp-1", 4000), ("dddd.old-7", 5000)] {
            let e = cache.entry_dir("plan", key);
            std::fs::create_dir_all(&e).unwrap();
            let f = std::fs::File::create(e.join("manifest.json")).unwrap();
            f.set_modified(at(secs)).unwrap();
        }
        std::fs::create_dir_all(cache.entry_dir("plan", "eeee")).unwrap();
        let keys: Vec<String> =
            cache.entries("plan").iter().map(|e| e.file_name().unwrap().to_string_lossy().into_owned()).collect();
        assert_eq!(keys, ["aaaa", "cccc", "bbbb"]);
    }

    /// What a stage no longer makes moves to out/superseded/, and only
    /// that: not another stage's file, not a file outside out/ that an
    /// edited list names.
    #[test]
    fn what_a_stage_no_longer_makes_is_moved_aside() {
        let d = tempfile::tempdir().unwrap();
        let (entry, out) = (d.path().join("entry"), d.path().join("out"));
        std::fs::create_dir_all(&entry).unwrap();
        for f in ["A.pdf", "B.pdf"] {
            std::fs::write(entry.join(f), f).unwrap();
        }
        let p = publish(&out, &entry, &manifest(&["A.pdf", "B.pdf"])).unwrap();
        assert_eq!(p.written, ["A.pdf", "B.pdf"]);
        assert!(p.superseded.is_empty());
        std::fs::write(out.join("other-stage.json"), "x").unwrap();
        let p = publish(&out, &entry, &manifest(&["A.pdf"])).unwrap();
        assert_eq!(p.superseded, ["B.pdf"]);
        assert!(!out.join("B.pdf").exists() && out.join("superseded").join("B.pdf").is_file());
        assert!(out.join("A.pdf").is_file() && out.join("other-stage.json").is_file());
        // An edited list naming a file outside out/ moves nothing.
        std::fs::write(d.path().join("precious"), "keep").unwrap();
        std::fs::write(out.join(".published.json"), r#"{ "docs": ["A.pdf", "../precious", "/etc/hostname"] }"#)
            .unwrap();
        let p = publish(&out, &entry, &manifest(&["A.pdf"])).unwrap();
        assert!(p.superseded.is_empty(), "{p:?}");
        assert!(d.path().join("precious").is_file());
    }

    /// A plan superseded twice keeps both copies: the second was renamed
    /// over the first, which was lost.
    #[test]
    fn a_name_superseded_twice_keeps_both_copies() {
        let d = tempfile::tempdir().unwrap();
        let (entry, out) = (d.path().join("entry"), d.path().join("out"));
        std::fs::create_dir_all(&entry).unwrap();
        for version in ["first", "second"] {
            std::fs::write(entry.join("B.steps.csv"), version).unwrap();
            let mut with_b = manifest(&["B.steps.csv"]);
            with_b.outputs.insert("B.steps.csv".into(), format!("hash of {version}"));
            publish(&out, &entry, &with_b).unwrap();
            let p = publish(&out, &entry, &manifest(&[])).unwrap();
            assert_eq!(p.superseded, ["B.steps.csv"]);
        }
        let aside = out.join(SUPERSEDED_DIR);
        assert_eq!(std::fs::read_to_string(aside.join("B.steps.csv")).unwrap(), "first");
        assert_eq!(std::fs::read_to_string(aside.join("B.2.steps.csv")).unwrap(), "second");
        assert_eq!(unused_name(&aside.join("B.steps.csv")), aside.join("B.3.steps.csv"));
        assert_eq!(unused_name(&aside.join("README")), aside.join("README"));
    }
}
