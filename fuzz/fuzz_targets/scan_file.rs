//! Every scan reader on hostile bytes: the first byte picks the format
//! (252 and above PTX, the reader added last: the others keep the
//! selectors the corpus was grown with).
//!
//! E57 files checksum every 1024-byte page (CRC-32C), so nearly every mutated
//! E57 file fails at its first page and the XML and binary sections behind
//! the checksums go untested. With the selector's second bit set, the target
//! writes each page's checksum for the mutated bytes first.
#![no_main]
use libfuzzer_sys::fuzz_target;

static PANIC_HOOK: std::sync::Once = std::sync::Once::new();

const FORMATS: [&str; 6] = ["las", "laz", "ply", "e57", "pts", "xyz"];

fuzz_target!(|data: &[u8]| {
    // The readers turn a panic inside a third-party decoder into an error
    // (`guard_decoder` in liftplan-scans), but libfuzzer-sys's panic hook
    // aborts before the panic can be caught. Put the default hook back: a
    // panic that escapes the readers still fails the run, since libfuzzer-sys
    // catches it and aborts.
    PANIC_HOOK.call_once(|| drop(std::panic::take_hook()));
    let Some((&sel, body)) = data.split_first() else { return };
    let ext = if sel >= 252 { "ptx" } else { FORMATS[sel as usize % FORMATS.len()] };
    let mut body = body.to_vec();
    if ext == "e57" && (sel as usize / FORMATS.len()) % 2 == 1 {
        liftplan_core::testing::e57_page_checksums(&mut body);
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("scan.{ext}"));
    std::fs::write(&path, body).unwrap();
    if let Ok(scans) = liftplan_scans::read::list_scans(&path) {
        let mut files = liftplan_scans::read::ScanStreamer::default();
        for s in &scans {
            let _ = files.stream(s, &mut |_| Ok(()));
        }
    }
});
