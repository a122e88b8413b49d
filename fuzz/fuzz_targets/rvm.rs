//! The RVM reader and the tessellation of whatever it accepts, under the
//! plant stage's triangle budget.
#![no_main]
use libfuzzer_sys::fuzz_target;

/// Room for triangles in one run: the stage's own check with a smaller room
/// than `MAX_TRIANGLES`, so that a model the check lets through fits the
/// fuzzer's memory limit.
const ROOM: u64 = 2_000_000;

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.rvm");
    let Ok(file) = liftplan_plant::rvm::parse(path, data) else { return };
    let settings = liftplan_plant::Settings::default();
    let mut summary = liftplan_plant::Summary::default();
    if let Ok(mesh) = liftplan_plant::rvm_to_mesh(path, &file, None, &settings, &mut summary, ROOM) {
        assert!(mesh.triangle_count() as u64 <= ROOM);
    }
});
