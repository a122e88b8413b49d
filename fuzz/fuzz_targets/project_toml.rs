//! A project's `liftplan.toml` through parsing and validation, as
//! `liftplan run` loads it: every stage's settings checked, paths checked
//! against a project folder with the default input folders, and every lift
//! resolved against its crane.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;
use std::sync::OnceLock;

/// One project folder for the whole run; each input rewrites its file.
fn project_dir() -> &'static Path {
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = tempfile::tempdir().expect("a temporary folder");
        for folder in ["scans", "plant", "charts", "cranes"] {
            std::fs::create_dir(d.path().join(folder)).expect("an input folder");
        }
        d
    })
    .path()
}

fuzz_target!(|data: &[u8]| {
    let dir = project_dir();
    std::fs::write(dir.join(liftplan::project::FILE), data).expect("the project file written");
    if let Ok(p) = liftplan::project::Project::load(dir) {
        let _ = p.lifts();
        let _ = p.crane_files();
    }
});
