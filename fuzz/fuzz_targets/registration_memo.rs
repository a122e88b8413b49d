//! The registration memo (`.liftplan/memo/scans/registration.memo`) read
//! back from damaged bytes, and payloads of any content in a valid frame: a
//! file that fails must be ignored whole, without a panic or an allocation
//! its bytes do not pay for. The first byte picks which.
#![no_main]
use libfuzzer_sys::fuzz_target;
use liftplan_core::artifact;
use liftplan_scans::memo;

fuzz_target!(|data: &[u8]| {
    let p = std::path::Path::new("registration.memo");
    let Some((&sel, body)) = data.split_first() else { return };
    if sel % 2 == 0 {
        let _ = memo::from_bytes(p, body);
    } else {
        let _ = memo::from_bytes(p, &artifact::encode("REGMEMO", 1, body));
    }
});
