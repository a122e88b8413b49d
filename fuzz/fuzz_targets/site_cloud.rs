//! The scans stage's `site.laz` as the depth map, plan and docs stages read
//! it back (`liftplan_depthmap::read_cloud`), of any content: a file on disk
//! proves nothing of what it asks for. Reading it, with a box of points left
//! out as the plan stage leaves the load out, must give the points or an
//! error, never panic, hang or allocate what a header field says.
#![no_main]
use libfuzzer_sys::fuzz_target;

static PANIC_HOOK: std::sync::Once = std::sync::Once::new();

fuzz_target!(|data: &[u8]| {
    // The reader turns a panic inside the `las` and `laz` crates into an
    // error (through `liftplan_core::guard`), but libfuzzer-sys's panic hook
    // aborts before it can be caught: put the default hook back (a panic that
    // escapes the reader still fails the run).
    PANIC_HOOK.call_once(|| drop(std::panic::take_hook()));
    let Ok(dir) = tempfile::tempdir() else { return };
    let path = dir.path().join("site.laz");
    if std::fs::write(&path, data).is_err() {
        return;
    }
    use liftplan_core::frame::{Point3, Vec3};
    let load = liftplan_core::obb::Obb::axis_aligned(Point3::new(5.0, 5.0, 1.0), Vec3::new(2.0, 2.0, 1.0));
    let _ = liftplan_depthmap::read_cloud(&path, &[load], &mut liftplan_depthmap::Inputs::default());
});
