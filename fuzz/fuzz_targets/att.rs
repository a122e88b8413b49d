//! The PDMS attribute (.att) parser.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = liftplan_plant::att::parse(std::path::Path::new("fuzz.att"), data);
});
