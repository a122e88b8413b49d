//! The crane model reader on damaged copies of the built-in crane files
//! ([`liftplan_core::testing::damaged`]): each copy must read or give an
//! error naming the file, never panic. (Lift requests are read from the
//! project file, whose damaged copies `tests/damaged_files.rs` of the
//! `liftplan` crate reads and resolves.) A few hundred deterministic copies
//! of each on every test run (`PROPTEST_CASES` for more), beside the fuzz
//! target (`fuzz/fuzz_targets/crane_and_lift_toml.rs`), which needs a
//! nightly toolchain and so does not run in CI.

use liftplan_core::crane::{CraneModel, builtin_names, builtin_text};
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
