//! The crane model reader on damaged copies of the built-in crane files
//! ([`liftplan_core::testing::damaged`]), and the lift request on damaged
//! copies of the demo's: each copy must read or give an error naming the
//! file, never panic; a lift that reads must then resolve against its crane
//! or give an error. A few hundred deterministic copies of each on every test
//! run (`PROPTEST_CASES` for more), beside the fuzz target
//! (`fuzz/fuzz_targets/crane_and_lift_toml.rs`), which needs a nightly
//! toolchain and so does not run in CI.

use liftplan_core::crane::{CraneModel, builtin, builtin_names, builtin_text};
use liftplan_core::lift::LiftSpec;
use liftplan_core::testing::{damaged, proptest_cases};
use std::path::Path;

#[test]
fn damaged_crane_files_read_or_give_an_error_naming_the_file() {
    for name in builtin_names() {
        let original = builtin_text(name).unwrap();
        let file = format!("{name}.toml");
        let (mut read, mut refused) = (0, 0);
        for k in 0..u64::from(proptest_cases(300)) {
            let bytes = damaged(original.as_bytes(), k);
            let Ok(text) = std::str::from_utf8(&bytes) else { continue };
            match CraneModel::from_toml(Path::new(&file), text) {
                Ok(_) => read += 1,
                Err(e) => {
                    let e = e.to_string();
                    assert!(e.contains(&file), "copy {k} of {file}: the error names the file: {e}");
                    refused += 1;
                }
            }
        }
        eprintln!("{file}: {read} read, {refused} refused");
        assert!(refused > 0);
    }
}

#[test]
fn damaged_lift_requests_resolve_or_give_an_error() {
    let original = r#"id = "V-101"
load = { name = "vessel V-101", mass_t = 12.0, size_m = [8.0, 3.0, 3.0], cog_m = [0.2, 0.0, -0.1] }
rigging = { mass_t = 0.5, height_m = 4.0 }
crane = { model = "ac-700", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 0.0, boom_m = 40.0, chart_config = "Main boom 360" }
pick = { x_m = 6.0, y_m = -16.0, z_m = 1.2, yaw_deg = 90.0 }
set = { x_m = 30.0, y_m = 2.0, z_m = 1.2, yaw_deg = 0.0 }
clearance_m = 1.0
"#;
    let model = builtin("ac-700").unwrap();
    let original_spec: LiftSpec = toml::from_str(original).unwrap();
    original_spec.resolve(model.clone()).unwrap();
    let (mut resolved, mut refused) = (0, 0);
    for k in 0..u64::from(proptest_cases(400)) {
        let bytes = damaged(original.as_bytes(), k);
        let Ok(text) = std::str::from_utf8(&bytes) else { continue };
        let Ok(spec) = toml::from_str::<LiftSpec>(text) else {
            refused += 1;
            continue;
        };
        match spec.resolve(model.clone()) {
            Ok(_) => resolved += 1,
            Err(_) => refused += 1,
        }
    }
    eprintln!("lift request: {resolved} resolved, {refused} refused");
    assert!(resolved > 0 && refused > 0);
}
