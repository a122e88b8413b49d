//! The registration memo (`.liftplan/memo/scans/registration.memo`) read
//! back from damaged bytes, and payloads of any content in a valid frame: a
//! file that fails must be ignored whole, without a panic or an allocation
//! its bytes do not pay for. The first byte picks which; or it reads the
//! bytes as each answer the memo keeps (a trial, a placement of up to 255
//! scans, the reference placed again), which must read as nothing where
//! damaged.
#![no_main]
use libfuzzer_sys::fuzz_target;
use liftplan_core::artifact;
use liftplan_scans::memo;

fuzz_target!(|data: &[u8]| {
    let p = std::path::Path::new("registration.memo");
    let Some((&sel, body)) = data.split_first() else { return };
    match sel % 3 {
        0 => {
            let _ = memo::from_bytes(p, body);
        }
        1 => {
            let _ = memo::from_bytes(p, &artifact::encode("REGMEMO", 1, body));
        }
        _ => {
            let Some((&count, answer)) = body.split_first() else { return };
            let _ = liftplan_scans::register::read_memo_answers(answer, usize::from(count));
        }
    }
});
