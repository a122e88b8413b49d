//! Load-chart workbooks (xlsx, xls, xlsb, ods) through reading and grid detection.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&sel, body)) = data.split_first() else { return };
    let ext = ["xlsx", "xls", "xlsb", "ods"][sel as usize % 4];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("chart.{ext}"));
    std::fs::write(&path, body).unwrap();
    let _ = liftplan_charts::inspect(&path);
});
