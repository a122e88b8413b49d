//! Every scan reader on hostile bytes: the first byte picks the format.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&sel, body)) = data.split_first() else { return };
    let ext = ["las", "laz", "ply", "e57", "pts", "xyz"][sel as usize % 6];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("scan.{ext}"));
    std::fs::write(&path, body).unwrap();
    if let Ok(scans) = liftplan_scans::read::list_scans(&path) {
        for s in &scans {
            let _ = liftplan_scans::read::read_all(s);
        }
    }
});
