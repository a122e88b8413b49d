//! The BIM mesh readers (OBJ, PLY, STL, glTF and GLB) through `read_file`,
//! as the plant stage calls them: the first byte picks the format.
#![no_main]
use libfuzzer_sys::fuzz_target;

static PANIC_HOOK: std::sync::Once = std::sync::Once::new();

fuzz_target!(|data: &[u8]| {
    // The glTF reader turns a panic inside the gltf crate into an error
    // (`liftplan_core::guard`); put the default panic hook back so such a
    // caught panic is not reported as a crash (see scan_file.rs).
    PANIC_HOOK.call_once(|| drop(std::panic::take_hook()));
    let Some((&sel, body)) = data.split_first() else { return };
    let ext = ["obj", "ply", "stl", "gltf", "glb"][sel as usize % 5];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("plant.{ext}"));
    std::fs::write(&path, body).unwrap();
    // OBJ, PLY and STL need their unit and up axis said; these make the
    // readers scale and turn every vertex.
    let settings = liftplan_plant::Settings {
        unit: Some(liftplan_core::units::LengthUnit::Mm),
        up_axis: Some(liftplan_plant::UpAxis::Y),
        ..Default::default()
    };
    // The budget's room is what `MAX_TRIANGLES` leaves over earlier files:
    // leave 2 M triangles, so that what the check lets through fits the
    // fuzzer's memory limit.
    let before = liftplan_plant::MAX_TRIANGLES as usize - 2_000_000;
    let mut summary = liftplan_plant::Summary { triangles: before, ..Default::default() };
    if liftplan_plant::read_file(&path, &settings, &mut summary).is_ok() {
        assert!(summary.triangles <= liftplan_plant::MAX_TRIANGLES as usize);
    }
});
