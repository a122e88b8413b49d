//! The content-addressed stage cache under `.liftplan/`.
//!
//! ```text
//! .liftplan/
//!   cache/<stage>/<key>/     outputs of one stage run + manifest.json
//!   cache/<stage>/.tmp-*     a run in progress (never trusted, swept)
//!   last/<stage>.json        manifest of the stage's last successful run
//!   runs/<n>.json            one record per `run` (keys, timings, versions)
//!   hashes.json              file hashes by (size, mtime, inode): saves rehashing
//!   log/                     watch-mode log
//! out/.manifest.json         which output file in out/ has which hash
//! ```
//!
//! A stage's outputs appear under `<key>/` by one atomic rename of a complete
//! folder, so a killed run leaves at most a `.tmp-*` folder that nothing reads.

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

/// Copies outputs into `out/` where their content changed; `out/` is touched
/// only after a stage succeeded, one file at a time by atomic rename.
pub fn publish(out_dir: &Path, entry_dir: &Path, m: &Manifest) -> Result<Vec<String>> {
    std::fs::create_dir_all(out_dir)?;
    let man_path = out_dir.join(".manifest.json");
    let mut man: BTreeMap<String, String> =
        std::fs::read_to_string(&man_path).ok().and_then(|t| serde_json::from_str(&t).ok()).unwrap_or_default();
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
    if !written.is_empty() {
        liftplan_core::artifact::write_atomic(&man_path, serde_json::to_string_pretty(&man)?.as_bytes())?;
    }
    Ok(written)
}
