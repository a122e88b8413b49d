//! The crane model reader on damaged copies of the built-in crane files, and
//! the capacity table's on damaged copies of a `capacity.csv`
//! ([`liftplan_core::testing::damaged`]): each copy must read or give an
//! error naming the file, never panic. (Lift requests are read from the
//! project file, whose damaged copies `tests/damaged_files.rs` of the
//! `liftplan` crate reads and resolves.) A few hundred deterministic copies
//! of each on every test run (`PROPTEST_CASES` for more), beside the fuzz
//! targets (`fuzz/fuzz_targets/crane_and_lift_toml.rs`, `capacity_csv.rs`),
//! which need a nightly toolchain and so do not run in CI.

use liftplan_core::capacity::{CapacityTable, ChartCell, ChartConfig};
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

#[test]
fn damaged_capacity_tables_read_or_give_an_error_naming_the_file() {
    let cell = |kg: f64, at: &str| Some(ChartCell { capacity_kg: kg, cell: format!("chart.xlsx [Main, 360!{at}]") });
    let table = CapacityTable {
        configs: vec![ChartConfig {
            name: "Main boom 360".into(),
            boom_lengths_m: vec![12.0, 20.0, 28.5],
            radii_m: vec![3.0, 4.0, 6.0, 8.0],
            cells: vec![
                cell(50000.0, "B2"),
                None,
                None,
                cell(40000.0, "B3"),
                cell(35000.0, "C3"),
                None,
                cell(30000.0, "B4"),
                cell(28000.0, "C4"),
                cell(21000.0, "D4"),
                cell(22000.0, "B5"),
                cell(20500.0, "C5"),
                cell(17000.0, "D5"),
            ],
        }],
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("capacity.csv");
    table.write_csv(&path).unwrap();
    let original = std::fs::read(&path).unwrap();
    assert_eq!(CapacityTable::from_csv_bytes(&path, &original).unwrap(), table);
    let (mut read, mut refused) = (0, 0);
    for k in 0..u64::from(proptest_cases(300)) {
        match CapacityTable::from_csv_bytes(&path, &damaged(&original, k)) {
            Ok(t) => {
                assert!(t.grid_cells() <= liftplan_core::capacity::MAX_GRID_CELLS);
                read += 1;
            }
            Err(e) => {
                assert!(e.starts_with(&path.display().to_string()), "copy {k}: the error names the file: {e}");
                refused += 1;
            }
        }
    }
    eprintln!("capacity.csv: {read} read, {refused} refused");
    assert!(refused > 0 && read > 0);
}
