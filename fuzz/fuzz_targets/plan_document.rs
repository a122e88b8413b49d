//! A plan.json as the docs stage reads it back from the plan stage's cache
//! entry, of any content (cut short by a full disk, edited by hand, or not
//! one liftplan wrote): laying out the lift's document from it must write
//! the document or fail with an error, never panic, hang or allocate without
//! bound. The input is the plan.json; the lift (the demo's V-101 on the
//! built-in ac-700, from the demo's project file) and a capacity table are
//! fixed, the site empty. Every picture is drawn (step pictures on) by
//! the CPU rasteriser.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;

const CAPACITY: &str = "config,boom_m,radius_m,capacity_kg,cell
Main boom 360,16.0,3.0,482600.0,chart.xlsx [Main boom 360!B7]
Main boom 360,40.0,3.0,250000.0,chart.xlsx [Main boom 360!C7]
Main boom 360,16.0,12.0,120000.0,chart.xlsx [Main boom 360!B8]
Main boom 360,40.0,12.0,90000.0,chart.xlsx [Main boom 360!C8]
Main boom 360,40.0,36.0,14000.0,chart.xlsx [Main boom 360!C9]
";

fn lift() -> &'static liftplan_core::lift::LiftTask {
    static TASK: OnceLock<liftplan_core::lift::LiftTask> = OnceLock::new();
    TASK.get_or_init(liftplan_fixtures::demo::lift)
}

fuzz_target!(|data: &[u8]| {
    let Ok(dir) = tempfile::tempdir() else { return };
    let (plan_json, capacity_csv) = (dir.path().join("plan.json"), dir.path().join("capacity.csv"));
    if std::fs::write(&plan_json, data).is_err() || std::fs::write(&capacity_csv, CAPACITY).is_err() {
        return;
    }
    let inputs = liftplan_docs::Inputs {
        project: "fuzz".into(),
        date: "2026-12-07".into(),
        tasks: vec![lift().clone()],
        plan_json,
        mesh: None,
        cloud: None,
        capacity_csv: Some(capacity_csv),
        plan_dir: dir.path().to_path_buf(),
        input_lines: vec![],
        input_hashes: vec![],
        scans_left_out: (vec![], 0),
        scans_warned: vec![],
        scans_passed_by: vec![],
        inputs_not_read: vec![],
        site_level_unconfirmed: None,
        one_column_charts: vec![],
        chart_warnings: vec![],
        chart_wind: vec![],
        obstacles: vec![],
        power_lines: vec![],
        resume_checks: vec![],
    };
    let settings = liftplan_docs::Settings::default();
    let _ = liftplan_docs::run(&inputs, &settings, liftplan_core::gpu::GpuUse::Never, &dir.path().join("out"));
});
