//! Watch mode: slow copies, corrupt drops, recovery.

use crate::util::*;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Finished runs: `N.json` records only, not a record still being written under a temporary name.
fn runs(dir: &Path) -> usize {
    let Ok(entries) = std::fs::read_dir(dir.join(".liftplan/runs")) else {
        return 0;
    };
    entries
        .filter_map(|e| e.ok())
        .filter(|e| {
            let name = e.file_name();
            let name = name.to_string_lossy();
            name.strip_suffix(".json").is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
        })
        .count()
}

fn wait_runs(dir: &Path, n: usize, timeout: Duration) -> bool {
    let t = Instant::now();
    while t.elapsed() < timeout {
        if runs(dir) >= n {
            return true;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    false
}

fn logs(dir: &Path) -> String {
    let w = std::fs::read_to_string(dir.join(".liftplan/log/watch.log")).unwrap_or_default();
    let e = std::fs::read_to_string(dir.parent().unwrap().join("watch.err")).unwrap_or_default();
    format!("watch.log:\n{w}\nstderr:\n{e}")
}

fn last_run(dir: &Path) -> serde_json::Value {
    let n = runs(dir);
    serde_json::from_str(&std::fs::read_to_string(dir.join(format!(".liftplan/runs/{n}.json"))).unwrap()).unwrap()
}

#[test]
fn watch_slow_copy_corrupt_drop_and_fix() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("w");
    ok(&["init", dir.to_str().unwrap()]);
    set_toml(&dir, "settle_ms = 1000", "settle_ms = 600");
    set_toml(&dir, "parse_wait_s = 10", "parse_wait_s = 2");
    // The test scans share one frame already (a flat patch cannot be registered).
    set_toml(&dir, "register = \"auto\"", "register = \"none\"");
    let src = t.path().join("scan.laz");
    write_scan(&src, &small_scan(5, 300));
    let bytes = std::fs::read(&src).unwrap();

    let log = std::fs::File::create(t.path().join("watch.err")).unwrap();
    let child = Command::new(bin())
        .args(["watch", dir.to_str().unwrap(), "-q"])
        .stdout(Stdio::null())
        .stderr(log)
        .spawn()
        .unwrap();
    // Kill the watcher whatever happens to this test.
    struct Guard(std::process::Child);
    impl Drop for Guard {
        fn drop(&mut self) {
            let _ = self.0.kill();
            let _ = self.0.wait();
        }
    }
    let mut guard = Guard(child);
    let child = &mut guard.0;
    assert!(wait_runs(&dir, 1, Duration::from_secs(30)), "no initial run");

    // A slow copy in chunks, pauses shorter than the settle time: one run.
    {
        let mut f = std::fs::File::create(dir.join("scans/north.laz")).unwrap();
        for chunk in bytes.chunks(bytes.len() / 6 + 1) {
            f.write_all(chunk).unwrap();
            f.flush().unwrap();
            std::thread::sleep(Duration::from_millis(200));
        }
    }
    assert!(wait_runs(&dir, 2, Duration::from_secs(60)), "the copy did not trigger a run\n{}", logs(&dir));
    std::thread::sleep(Duration::from_secs(3));
    assert_eq!(runs(&dir), 2, "a slow copy must trigger exactly one run\n{}", logs(&dir));
    assert_eq!(last_run(&dir)["report"]["ok"], true);
    let good = std::fs::read(dir.join("out/site.laz")).unwrap();

    // A corrupt scan: reported, watcher stays up, out/ unchanged.
    std::fs::write(dir.join("scans/south.laz"), &bytes[..bytes.len() / 3]).unwrap();
    assert!(wait_runs(&dir, 3, Duration::from_secs(60)), "the corrupt drop was not reported\n{}", logs(&dir));
    assert_eq!(last_run(&dir)["report"]["ok"], false);
    assert!(child.try_wait().unwrap().is_none(), "watcher exited after a bad file");
    assert_eq!(std::fs::read(dir.join("out/site.laz")).unwrap(), good);
    let wlog = std::fs::read_to_string(dir.join(".liftplan/log/watch.log")).unwrap();
    assert!(wlog.contains("south.laz") && wlog.contains("last good outputs kept"), "{wlog}");

    // Fixing the file triggers a good run.
    std::fs::write(dir.join("scans/south.laz"), &bytes).unwrap();
    assert!(wait_runs(&dir, 4, Duration::from_secs(60)), "fixing the file did not trigger a run\n{}", logs(&dir));
    assert_eq!(last_run(&dir)["report"]["ok"], true, "{}", logs(&dir));

    // Ctrl-C exits cleanly.
    unsafe {
        libc::kill(child.id() as i32, libc::SIGINT);
    }
    let t0 = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(t0.elapsed() < Duration::from_secs(20), "watcher did not stop on Ctrl-C");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(status.success());
}
