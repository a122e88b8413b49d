//! The RVM and ATT readers on damaged copies of the real PDMS sample export
//! (`fixtures/plant/`): bytes flipped, fields overwritten with extreme
//! values, the file cut short ([`liftplan_core::testing::damaged`]). Each
//! copy must give a mesh or an error naming the file, never a panic, and a
//! mesh within the triangle room it was given. A thousand deterministic
//! copies on every test run (`PROPTEST_CASES` for more), beside the fuzz
//! targets (`fuzz/fuzz_targets/rvm.rs`, `att.rs`), which need a nightly
//! toolchain and so do not run in CI.

use liftplan_core::testing::{damaged, proptest_cases};
use std::path::Path;

fn fixture(name: &str) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/plant").join(name);
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn damaged_rvm_files_give_a_mesh_or_an_error() {
    const ROOM: u64 = 2_000_000;
    let original = fixture("plm-sample_11072013.rvm");
    let path = Path::new("damaged.rvm");
    let (mut meshes, mut errors) = (0, 0);
    for k in 0..u64::from(proptest_cases(1000)) {
        let bytes = damaged(&original, k);
        let file = match liftplan_plant::rvm::parse(path, &bytes) {
            Ok(file) => file,
            Err(e) => {
                assert!(e.to_string().contains("damaged.rvm"), "copy {k}: the error names the file: {e}");
                errors += 1;
                continue;
            }
        };
        let mut summary = liftplan_plant::Summary::default();
        match liftplan_plant::rvm_to_mesh(path, &file, None, &liftplan_plant::Settings::default(), &mut summary, ROOM) {
            Ok(mesh) => {
                assert!(mesh.triangle_count() as u64 <= ROOM, "copy {k}: {} triangles", mesh.triangle_count());
                meshes += 1;
            }
            Err(e) => {
                assert!(e.to_string().contains("damaged.rvm"), "copy {k}: the error names the file: {e}");
                errors += 1;
            }
        }
    }
    eprintln!("{meshes} meshes, {errors} errors");
    assert!(meshes > 0 && errors > 0, "the damage should be caught sometimes and harmless sometimes");
}

#[test]
fn damaged_att_files_give_attributes_or_an_error() {
    let original = fixture("plm-sample_11072013.att");
    let (mut read, mut errors) = (0, 0);
    for k in 0..u64::from(proptest_cases(1000)) {
        match liftplan_plant::att::parse(Path::new("damaged.att"), &damaged(&original, k)) {
            Ok(_) => read += 1,
            Err(e) => {
                assert!(e.to_string().contains("damaged.att"), "copy {k}: the error names the file: {e}");
                errors += 1;
            }
        }
    }
    eprintln!("{read} read, {errors} errors");
    assert!(read > 0, "most damage to a text file still reads");
}
