//! liftplan's own binary artifacts (depth map, plant mesh) read back from
//! damaged bytes, and payloads of any content in a valid frame: a checksum
//! proves a file whole, not that liftplan wrote it, so the payload readers
//! must hold against hostile content as well. The first byte picks which.
#![no_main]
use libfuzzer_sys::fuzz_target;
use liftplan_core::{artifact, mesh};
use liftplan_depthmap::mdm;

fuzz_target!(|data: &[u8]| {
    let p = std::path::Path::new("fuzz.bin");
    let Some((&sel, body)) = data.split_first() else { return };
    match sel % 3 {
        0 => {
            let _ = mdm::Mdm::from_bytes(p, body);
            let _ = mesh::TriMesh::from_artifact_bytes(p, body);
        }
        1 => {
            let framed = artifact::encode(mdm::ARTIFACT_KIND, mdm::ARTIFACT_VERSION, body);
            let _ = mdm::Mdm::from_bytes(p, &framed);
        }
        _ => {
            let framed = artifact::encode(mesh::ARTIFACT_KIND, mesh::ARTIFACT_VERSION, body);
            let _ = mesh::TriMesh::from_artifact_bytes(p, &framed);
        }
    }
});
