//! Helpers shared by the end-to-end tests.

use liftplan_core::cloud::PointCloud;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn bin() -> PathBuf {
    std::env::var("LIFTPLAN_BIN").map(PathBuf::from).unwrap_or_else(|_| PathBuf::from(env!("CARGO_BIN_EXE_liftplan")))
}

pub fn liftplan(args: &[&str]) -> Output {
    Command::new(bin()).args(args).output().expect("run liftplan")
}

pub fn ok(args: &[&str]) -> Output {
    let o = liftplan(args);
    assert!(
        o.status.success(),
        "liftplan {args:?} failed:\n{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

pub fn run_json(dir: &Path) -> serde_json::Value {
    let o = ok(&["run", dir.to_str().unwrap(), "--json", "-q"]);
    serde_json::from_slice(&o.stdout).expect("run --json prints JSON")
}

pub fn stage<'a>(report: &'a serde_json::Value, name: &str) -> &'a serde_json::Value {
    report["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == name)
        .unwrap_or_else(|| panic!("no stage {name} in {report}"))
}

/// A small synthetic scan: a sloped ground patch with a box on it, in a scanner
/// frame, `n` points per square metre-ish, deterministic.
pub fn small_scan(seed: u64, n_side: usize) -> PointCloud {
    let mut rng = liftplan_core::rng::seeded(seed, "small-scan");
    let mut c = PointCloud::default();
    for i in 0..n_side {
        for j in 0..n_side {
            let x = -15.0 + 30.0 * i as f64 / n_side as f64 + 0.01 * liftplan_core::rng::unit(&mut rng);
            let y = -15.0 + 30.0 * j as f64 / n_side as f64 + 0.01 * liftplan_core::rng::unit(&mut rng);
            let inside = x.abs() < 3.0 && y.abs() < 2.0;
            let z = if inside { 2.5 } else { -1.6 + 0.01 * x };
            c.xyz.push([x, y, z]);
            c.intensity.push((i * 31 + j * 7) as u16);
        }
    }
    c
}

pub fn write_scan(path: &Path, c: &PointCloud) {
    liftplan_scans::write::write_las(path, c).unwrap();
}

pub fn read_las_count(path: &Path) -> u64 {
    let r = las::Reader::from_path(path).unwrap();
    r.header().number_of_points()
}

/// Voxel count by the documented definition, for comparing with the stage.
pub fn voxel_count(points: &[[f64; 3]], v: f64) -> usize {
    let mut keys: Vec<(i64, i64, i64)> = points
        .iter()
        .map(|p| ((p[0] / v).floor() as i64, (p[1] / v).floor() as i64, (p[2] / v).floor() as i64))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    keys.len()
}

/// A new project with one scan dropped in.
pub fn project_with_scan(dir: &Path, n_side: usize) -> PointCloud {
    ok(&["init", dir.to_str().unwrap()]);
    let c = small_scan(1, n_side);
    write_scan(&dir.join("scans").join("north.laz"), &c);
    c
}

pub fn set_toml(dir: &Path, from: &str, to: &str) {
    let f = dir.join("liftplan.toml");
    let t = std::fs::read_to_string(&f).unwrap();
    assert!(t.contains(from), "{from} not in liftplan.toml");
    std::fs::write(&f, t.replacen(from, to, 1)).unwrap();
}

/// (inode, mtime) of every file in out/, to prove nothing was rewritten.
pub fn out_stamps(dir: &Path) -> Vec<(String, u64, i64, i64)> {
    use std::os::unix::fs::MetadataExt;
    let mut v: Vec<_> = std::fs::read_dir(dir.join("out"))
        .unwrap()
        .flatten()
        .map(|e| {
            let m = e.metadata().unwrap();
            (e.file_name().to_string_lossy().into_owned(), m.ino(), m.mtime(), m.mtime_nsec())
        })
        .collect();
    v.sort();
    v
}
