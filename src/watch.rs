//! `liftplan watch`: rerun the affected stages when inputs change.
//!
//! A burst of changes is gathered until the project has been quiet for
//! `[watch] settle_ms`; a changed file must also keep its size between two looks
//! and, for scans, parse its header, before a run starts (a copy in progress is
//! waited for up to `parse_wait_s`). A failing run is logged and reported; the
//! last good outputs stay in `out/` and the watcher keeps going. Ctrl-C stops it
//! between runs.

use crate::pipeline::{self, RunOptions, Status};
use crate::progress::Progress;
use crate::project::Project;
use anyhow::{Context, Result};
use notify::event::{AccessKind, AccessMode, ModifyKind};
use notify::{EventKind, RecursiveMode, Watcher};
use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Writes `msg` to the watch log and the terminal, through
/// [`crate::progress::for_terminal`]: it names files others dropped in the
/// folder (a scan's file name may hold a terminal's escape). Paths in it
/// are said with [`liftplan_core::location::in_words`], so a line break in
/// a file's name does not print a line of its own.
fn log(dir: &Path, msg: &str) {
    let msg = crate::progress::for_terminal(msg);
    let logdir = dir.join(".liftplan").join("log");
    let _ = std::fs::create_dir_all(&logdir);
    let t = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_secs_f64()).unwrap_or(0.0);
    if let Ok(mut f) = std::fs::OpenOptions::new().create(true).append(true).open(logdir.join("watch.log")) {
        let _ = writeln!(f, "{t:.3} {msg}");
    }
    eprintln!("[watch] {msg}");
}

fn relevant(dir: &Path, p: &Path) -> bool {
    let Ok(rel) = p.strip_prefix(dir) else {
        return false;
    };
    let first = rel.components().next().map(|c| c.as_os_str().to_string_lossy().into_owned()).unwrap_or_default();
    if first == ".liftplan" || first == "out" {
        return false;
    }
    let name = p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    // As the project's folders are listed ([`Project::files`]), and not
    // editors' backups.
    !crate::project::is_hidden_or_office_owner(&name) && !name.ends_with('~')
}

fn run_once(dir: &Path, progress: &Progress) {
    let project = match Project::load(dir) {
        Ok(p) => p,
        Err(e) => {
            log(dir, &format!("project file error, keeping the last outputs: {e}"));
            return;
        }
    };
    // As `liftplan run` does, before the run writes the plans it reads.
    for c in crate::resume::check_resumed(&project).iter().filter(|c| !c.agrees) {
        log(dir, &format!("warning: {}", c.said));
    }
    match pipeline::run(&project, &RunOptions { until: None, force: vec![] }, progress) {
        Ok(rep) => {
            for f in &rep.inputs_not_read {
                log(dir, &format!("warning: {}", crate::stages::not_read_said(f)));
            }
            let s: Vec<String> =
                rep.stages.iter().map(|s| format!("{}={:?}", s.name, s.status).to_lowercase()).collect();
            if rep.ok {
                log(dir, &format!("run ok: {}", s.join(" ")));
            } else {
                let err = rep
                    .stages
                    .iter()
                    .find(|s| s.status == Status::Failed)
                    .and_then(|s| s.error.clone())
                    .unwrap_or_default();
                log(dir, &format!("run failed, last good outputs kept in out/: {} | {err}", s.join(" ")));
            }
        }
        Err(e) => log(dir, &format!("run failed, last good outputs kept in out/: {e:#}")),
    }
}

/// How long a changed file's size must stay the same before it is used.
const SIZE_LOOK_GAP: Duration = Duration::from_millis(150);

/// The changed files that are not complete enough to use yet, with why: a file
/// must keep its size between two looks, one before `wait` and one after it,
/// and a scan's header must parse. Every file shares the one wait, so a drop
/// of thousands of scans costs one wait, not one each.
fn not_ready(paths: &[&Path], wait: impl FnOnce()) -> Vec<(PathBuf, String)> {
    let size = |p: &Path| std::fs::metadata(p).map(|m| m.len()).map_err(|e| e.to_string());
    let first: Vec<Result<u64, String>> = paths.iter().map(|p| size(p)).collect();
    if first.iter().any(|s| s.is_ok()) {
        wait();
    }
    let mut out = Vec::new();
    for (p, s1) in paths.iter().zip(first) {
        let verdict = s1.and_then(|s1| {
            if size(p)? != s1 {
                return Err("still growing".to_string());
            }
            header_parses(p)
        });
        if let Err(e) = verdict {
            out.push((p.to_path_buf(), e));
        }
    }
    out
}

/// Whether a scan's header parses (files that are not scans pass).
fn header_parses(p: &Path) -> Result<(), String> {
    let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if crate::stages::SCAN_EXTS.contains(&ext.as_str()) {
        liftplan_scans::read::list_scans(p).map_err(|e| e.to_string())?;
        if matches!(ext.as_str(), "las" | "laz") {
            liftplan_scans::read::las_precheck(p).map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}

pub fn watch(dir: &Path, progress: &Progress, stop: Arc<AtomicBool>) -> Result<()> {
    // Events arrive with absolute, resolved paths.
    let dir = &std::fs::canonicalize(dir).with_context(|| format!("resolving {}", dir.display()))?;
    let project = Project::load(dir).map_err(|e| anyhow::anyhow!("{e}"))?;
    let settle = Duration::from_millis(project.raw.watch.settle_ms.max(50));
    let parse_wait = Duration::from_secs(project.raw.watch.parse_wait_s);
    let (tx, rx) = std::sync::mpsc::channel();
    let mut watcher = notify::recommended_watcher(move |res: notify::Result<notify::Event>| {
        if let Ok(ev) = res {
            let _ = tx.send(ev);
        }
    })
    .context("starting the file watcher")?;
    watcher.watch(dir, RecursiveMode::Recursive).with_context(|| format!("watching {}", dir.display()))?;
    log(dir, &format!("watching {} (Ctrl-C to stop)", dir.display()));
    run_once(dir, progress);
    let mut changed: BTreeSet<PathBuf> = BTreeSet::new();
    let mut last_event = Instant::now();
    let mut waiting_since: Option<Instant> = None;
    while !stop.load(Ordering::SeqCst) {
        match rx.recv_timeout(Duration::from_millis(100)) {
            Ok(ev) => {
                // Our own runs read the inputs; only writes, creations, renames and
                // removals are changes.
                let write = match ev.kind {
                    EventKind::Create(_) | EventKind::Remove(_) => true,
                    EventKind::Modify(ModifyKind::Metadata(_)) => false,
                    EventKind::Modify(_) => true,
                    EventKind::Access(AccessKind::Close(AccessMode::Write)) => true,
                    _ => false,
                };
                if write {
                    for p in ev.paths {
                        if relevant(dir, &p) {
                            changed.insert(p);
                            last_event = Instant::now();
                        }
                    }
                }
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break,
        }
        if changed.is_empty() || last_event.elapsed() < settle {
            continue;
        }
        let files: Vec<&Path> = changed.iter().map(PathBuf::as_path).filter(|p| p.is_file()).collect();
        let not_ready = not_ready(&files, || std::thread::sleep(SIZE_LOOK_GAP));
        if !not_ready.is_empty() {
            let since = *waiting_since.get_or_insert_with(Instant::now);
            if since.elapsed() < parse_wait {
                if since.elapsed() < Duration::from_millis(200) {
                    for (p, e) in &not_ready {
                        log(dir, &format!("waiting for {}: {e}", liftplan_core::location::in_words(p)));
                    }
                }
                continue;
            }
            for (p, e) in &not_ready {
                log(
                    dir,
                    &format!(
                        "{} is still not readable after {:?}: {e}; running anyway so the problem is reported",
                        liftplan_core::location::in_words(p),
                        parse_wait
                    ),
                );
            }
        }
        waiting_since = None;
        let names: Vec<String> =
            changed.iter().map(|p| liftplan_core::location::in_words(p.strip_prefix(dir).unwrap_or(p))).collect();
        log(dir, &format!("changed: {}", names.join(", ")));
        changed.clear();
        run_once(dir, progress);
    }
    log(dir, "stopped");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file's name dropped in the folder is logged without its control
    /// characters: an escape shown as U+FFFD, a line break in a path too.
    #[test]
    fn the_watch_log_says_names_without_control_characters() {
        let d = tempfile::tempdir().unwrap();
        let name = liftplan_core::location::in_words(Path::new("scans/s1\nerror: x\x1b]0;t\x07.laz"));
        log(d.path(), &format!("changed: {name}"));
        let logged = std::fs::read_to_string(d.path().join(".liftplan/log/watch.log")).unwrap();
        assert!(logged.ends_with(" changed: scans/s1\u{FFFD}error: x\u{FFFD}]0;t\u{FFFD}.laz\n"), "{logged:?}");
    }

    #[test]
    fn files_share_one_wait_and_each_is_judged() {
        let t = tempfile::tempdir().unwrap();
        let scan = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/scans/gps-switches-1.laz");
        let bytes = std::fs::read(&scan).unwrap();
        let path = |name: &str| t.path().join(name);
        std::fs::write(path("done.laz"), &bytes).unwrap();
        std::fs::write(path("growing.laz"), &bytes[..bytes.len() / 2]).unwrap();
        std::fs::write(path("cut.laz"), &bytes[..100]).unwrap();
        std::fs::write(path("notes.txt"), "not a scan").unwrap();
        let names = ["done.laz", "growing.laz", "cut.laz", "notes.txt", "gone.laz"];
        let paths: Vec<PathBuf> = names.iter().map(|n| path(n)).collect();
        let refs: Vec<&Path> = paths.iter().map(PathBuf::as_path).collect();
        // The copy of growing.laz goes on while the watcher waits (and ends
        // before it looks again, so only the size tells).
        let waits = std::cell::Cell::new(0);
        let verdicts = not_ready(&refs, || {
            waits.set(waits.get() + 1);
            std::fs::write(path("growing.laz"), &bytes).unwrap();
        });
        assert_eq!(waits.get(), 1);
        let why = |name: &str| verdicts.iter().find(|(p, _)| p == &path(name)).map(|(_, e)| e.clone());
        assert_eq!(why("done.laz"), None);
        assert_eq!(why("notes.txt"), None);
        assert_eq!(why("growing.laz").as_deref(), Some("still growing"));
        assert!(why("cut.laz").is_some_and(|e| e.contains("cut.laz")), "{verdicts:?}");
        assert!(why("gone.laz").is_some(), "{verdicts:?}");
        assert_eq!(verdicts.len(), 3, "{verdicts:?}");
    }

    #[test]
    fn no_wait_when_no_file_is_there() {
        let t = tempfile::tempdir().unwrap();
        let gone = t.path().join("gone.laz");
        let verdicts = not_ready(&[gone.as_path()], || panic!("waited for files that are not there"));
        assert_eq!(verdicts.len(), 1);
    }
}
