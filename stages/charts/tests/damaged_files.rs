//! The load-chart reader on damaged copies of real workbooks
//! ([`liftplan_core::testing::damaged`]): the demo's chart as written (.xlsx)
//! and the .xls and .xlsb kept in `fixtures/charts/`. Each copy must read or
//! give an error naming the file, never panic. A few hundred deterministic
//! copies of each on every test run (`PROPTEST_CASES` for more), beside the
//! fuzz target (`fuzz/fuzz_targets/chart_workbook.rs`), which needs a nightly
//! toolchain and so does not run in CI.

use liftplan_core::testing::{damaged, hide_panics_from, proptest_cases};
use std::path::Path;

#[test]
fn damaged_load_charts_read_or_give_an_error() {
    // calamine panics on some damaged workbooks; the reader catches those
    // panics (`liftplan_core::guard`) and reports an error. Keep them out of
    // the test's output, and every other panic in it.
    hide_panics_from("/calamine-");
    let dir = tempfile::tempdir().unwrap();
    let original = dir.path().join("chart.xlsx");
    liftplan_fixtures::chart::write_demo_chart(&original).unwrap();
    let bytes = std::fs::read(&original).unwrap();
    let mut kept = vec![("chart.xlsx".to_string(), bytes)];
    let charts = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/charts");
    for name in ["chart.xls", "chart.xlsb"] {
        kept.push((name.to_string(), std::fs::read(charts.join(name)).unwrap()));
    }
    let copies = u64::from(proptest_cases(300));
    for (name, bytes) in &kept {
        let (mut read, mut refused) = (0, 0);
        for k in 0..copies {
            let path = dir.path().join(format!("damaged-{k}-{name}"));
            std::fs::write(&path, damaged(bytes, k)).unwrap();
            match liftplan_charts::inspect(&path) {
                Ok(_) => read += 1,
                Err(e) => {
                    let (e, file) = (e.to_string(), path.file_name().unwrap().to_string_lossy());
                    assert!(e.contains(&*file), "copy {k} of {name}: the error names the file: {e}");
                    refused += 1;
                }
            }
            std::fs::remove_file(&path).unwrap();
        }
        eprintln!("{name}: {read} read, {refused} refused");
    }
}
