//! `plant.json`, the plant stage's summary, whose boxes of the groups left
//! out of the model the plan stage reads back to compare with each lift's
//! pick and set: damaged or hostile bytes give an error, never a panic, and
//! the boxes taken are as the plant stage writes them; the demo's lift is
//! compared with them as the plan stage compares it.
#![no_main]
use libfuzzer_sys::fuzz_target;
use liftplan_core::mesh::ModelBox;
use std::sync::OnceLock;

fn lift() -> &'static liftplan_core::lift::LiftTask {
    static TASK: OnceLock<liftplan_core::lift::LiftTask> = OnceLock::new();
    TASK.get_or_init(liftplan_fixtures::demo::lift)
}

fuzz_target!(|data: &[u8]| {
    let Ok(boxes) = ModelBox::left_out_in_plant_json(data) else { return };
    assert_eq!(ModelBox::not_as_written(&boxes), None);
    for against in liftplan_plan::model_copy::of_lift(lift(), &boxes) {
        let _ = against.said();
    }
});
