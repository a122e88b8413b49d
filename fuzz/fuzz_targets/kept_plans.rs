//! The plans kept by revision read back as `liftplan revisions` and a run
//! read them: kept plan files and records of what they were made from of
//! any content (a file cut short by a full disk, edited by hand, or not one
//! liftplan wrote), and an out/plan.json naming any lift and revision.
//! Listing them, setting two side by side (`--compare`, `last` too) and a
//! run's line for a plan that replaces the last must fail with an error or
//! say so, never panic. The input is five files' bytes, split at 0xFF
//! (which UTF-8 never holds): two plans of lift V-101, their records of
//! inputs, and out/plan.json.
#![no_main]
use libfuzzer_sys::fuzz_target;
use liftplan::revisions;

fuzz_target!(|data: &[u8]| {
    let mut parts = data.split(|&b| b == 0xff);
    let mut next = || parts.next().unwrap_or_default();
    let (plan_a, plan_b, inputs_a, inputs_b, last) = (next(), next(), next(), next(), next());
    let Ok(dir) = tempfile::tempdir() else { return };
    let out = dir.path();
    let (a, b) = ("0000000a", "0000000b");
    let Some(folder) = revisions::plan_file(out, "V-101", a).parent().map(std::path::Path::to_path_buf) else {
        return;
    };
    if std::fs::create_dir_all(&folder).is_err() {
        return;
    }
    for (file, bytes) in [
        (revisions::plan_file(out, "V-101", a), plan_a),
        (revisions::plan_file(out, "V-101", b), plan_b),
        (revisions::inputs_file(out, "V-101", a), inputs_a),
        (revisions::inputs_file(out, "V-101", b), inputs_b),
        (out.join("plan.json"), last),
    ] {
        if std::fs::write(file, bytes).is_err() {
            return;
        }
    }
    let _ = revisions::list(out);
    for (was, now) in [(a, b), (b, a), (a, revisions::LAST)] {
        if let Ok(c) = revisions::compare(out, None, was, now) {
            let _ = (c.said(), c.briefly());
        }
    }
    let before = revisions::last_plans(out);
    let _ = revisions::replaced(out, &[("V-101".to_string(), a.to_string())], out);
    let _ = revisions::replaced(out, &before, out);
});
