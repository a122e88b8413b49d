//! The RVM reader and the tessellation of whatever it accepts.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = liftplan_plant::rvm::parse(std::path::Path::new("fuzz.rvm"), data);
});
