//! Every scan reader on hostile bytes: the first byte picks the format.
#![no_main]
use libfuzzer_sys::fuzz_target;

static PANIC_HOOK: std::sync::Once = std::sync::Once::new();

fuzz_target!(|data: &[u8]| {
    // The readers turn a panic inside a third-party decoder into an error
    // (`guard_decoder` in liftplan-scans), but libfuzzer-sys's panic hook
    // aborts before the panic can be caught. Put the default hook back: a
    // panic that escapes the readers still fails the run, since libfuzzer-sys
    // catches it and aborts.
    PANIC_HOOK.call_once(|| drop(std::panic::take_hook()));
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
