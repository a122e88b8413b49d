//! `registration.json` and `lifts.json`, the scans and charts stages'
//! records, as the docs stage reads them back (`liftplan_scans::recorded`,
//! `liftplan_charts::recorded`): damaged or hostile bytes give an error,
//! never a panic, and what is read (scans left out or warned of, the
//! reference's levelling, the boom a chart of one column is said for) is
//! drawn on the demo lift's document as the docs stage draws it, without
//! step pictures (the records are words on the cover and the inputs page).
//!
//! The input is the registration.json's bytes, a NUL, then the
//! lifts.json's (JSON holds no raw NUL); without a NUL, no lifts.json.
//! The plan is the demo's (fuzz/seeds/plan_document).
#![no_main]
use libfuzzer_sys::fuzz_target;
use liftplan_charts::recorded::LiftsCharted;
use liftplan_scans::recorded::Registration;
use std::sync::OnceLock;

const PLAN: &[u8] = include_bytes!("../seeds/plan_document/demo-V-101.plan.json");

fn lift() -> &'static liftplan_core::lift::LiftTask {
    static TASK: OnceLock<liftplan_core::lift::LiftTask> = OnceLock::new();
    TASK.get_or_init(liftplan_fixtures::demo::lift)
}

fuzz_target!(|data: &[u8]| {
    let (registration, lifts) = match data.iter().position(|&b| b == 0) {
        Some(at) => (&data[..at], Some(&data[at + 1..])),
        None => (data, None),
    };
    let tasks = std::slice::from_ref(lift());
    let Ok(registration) = Registration::from_json(registration) else { return };
    let one_column_charts = match lifts.map(LiftsCharted::from_json) {
        Some(Ok(charted)) => match charted.one_column_booms(tasks) {
            Ok(booms) => booms,
            Err(_) => return,
        },
        Some(Err(_)) => return,
        None => vec![],
    };
    let Ok(dir) = tempfile::tempdir() else { return };
    let plan_json = dir.path().join("plan.json");
    if std::fs::write(&plan_json, PLAN).is_err() {
        return;
    }
    let inputs = liftplan_docs::Inputs {
        project: "fuzz".into(),
        date: "2026-12-07".into(),
        tasks: tasks.to_vec(),
        plan_json,
        mesh: None,
        cloud: None,
        capacity_csv: None,
        plan_dir: dir.path().to_path_buf(),
        input_lines: vec![],
        input_hashes: vec![],
        scans_left_out: registration.left_out(),
        scans_warned: registration.warned(),
        scans_passed_by: registration.passed_by(),
        inputs_not_read: vec![],
        site_level_unconfirmed: registration.site_level_unconfirmed(),
        one_column_charts,
        chart_warnings: vec![],
        chart_wind: vec![],
        obstacles: vec![],
        power_lines: vec![],
        resume_checks: vec![],
    };
    let settings = liftplan_docs::Settings { step_pictures: false, ..Default::default() };
    let drawn = liftplan_docs::run(&inputs, &settings, liftplan_core::gpu::GpuUse::Never, &dir.path().join("out"));
    // The demo's plan, read back as the docs stage reads it, is drawn
    // whatever the records say.
    assert!(drawn.is_ok(), "{:?}", drawn.err());
});
