//! Every scan reader on hostile bytes: the first byte picks the format.
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
    let ext = FORMATS[sel as usize % FORMATS.len()];
    let mut body = body.to_vec();
    if ext == "e57" && (sel as usize / FORMATS.len()) % 2 == 1 {
        write_page_checksums(&mut body);
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

/// Writes the CRC-32C of each whole 1024-byte page's first 1020 bytes into
/// its last four, big-endian, as E57 stores them.
fn write_page_checksums(body: &mut [u8]) {
    for page in body.chunks_exact_mut(1024) {
        let crc = crc32c(&page[..1020]);
        page[1020..].copy_from_slice(&crc.to_be_bytes());
    }
}

/// CRC-32C (Castagnoli), bit by bit: fuzz inputs are small.
fn crc32c(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0x82F6_3B78 } else { crc >> 1 };
        }
    }
    !crc
}
