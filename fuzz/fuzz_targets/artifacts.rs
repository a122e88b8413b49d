//! liftplan's own binary artifacts (depth map, plant mesh) read back from damaged bytes.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let p = std::path::Path::new("fuzz.bin");
    let _ = liftplan_depthmap::mdm::Mdm::from_bytes(p, data);
    let _ = liftplan_core::mesh::TriMesh::from_artifact_bytes(p, data);
});
