//! The project file and the station file on damaged copies of the demo's
//! ([`liftplan_core::testing::damaged`]): each copy must load or give an
//! error naming the file, never panic; a project that loads must then give
//! its lifts or such an error. A few hundred deterministic
//! copies on every test run (`PROPTEST_CASES` for more), beside the fuzz
//! targets (`fuzz/fuzz_targets/project_toml.rs`, `crane_and_lift_toml.rs`),
//! which need a nightly toolchain and so do not run in CI.

use liftplan::project::{FILE, Project};
use liftplan_core::testing::{damaged, proptest_cases};

#[test]
fn damaged_project_files_load_or_give_an_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    for folder in ["scans", "plant", "charts", "cranes"] {
        std::fs::create_dir(dir.path().join(folder)).unwrap();
    }
    let original = liftplan_fixtures::demo::PROJECT_TOML.as_bytes();
    let names_it = |e: String, k: u64| assert!(e.contains(FILE), "copy {k}: the error names {FILE}: {e}");
    let (mut loaded, mut refused) = (0, 0);
    for k in 0..u64::from(proptest_cases(400)) {
        std::fs::write(dir.path().join(FILE), damaged(original, k)).unwrap();
        match Project::load(dir.path()) {
            Ok(p) => {
                loaded += 1;
                if let Err(e) = p.lifts() {
                    names_it(e.to_string(), k);
                }
                let _ = p.crane_files();
            }
            Err(e) => {
                refused += 1;
                names_it(e.to_string(), k);
            }
        }
    }
    eprintln!("project file: {loaded} loaded, {refused} refused");
    assert!(loaded > 0 && refused > 0);
}

#[test]
fn damaged_station_files_read_or_give_an_error_naming_the_file() {
    let original = "# Surveyed pose of the first scanner station (site frame).\n[[station]]\nscan = \"scan-1\"\nx_m = -30.0000\ny_m = -25.0000\nz_m = 1.6000\nyaw_deg = 12.500000\ntolerance_m = 0.5\n";
    let path = std::path::Path::new("stations.toml");
    let (mut read, mut refused) = (0, 0);
    for k in 0..u64::from(proptest_cases(400)) {
        let bytes = damaged(original.as_bytes(), k);
        let Ok(text) = std::str::from_utf8(&bytes) else { continue };
        match liftplan_scans::parse_stations(path, text) {
            Ok(_) => read += 1,
            Err(e) => {
                refused += 1;
                let e = e.to_string();
                assert!(e.contains("stations.toml"), "copy {k}: the error names the file: {e}");
            }
        }
    }
    eprintln!("station file: {read} read, {refused} refused");
    assert!(read > 0 && refused > 0);
}
