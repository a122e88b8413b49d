//! `chart.json`, the charts stage's summary that the plan and docs stages
//! read back for what each chart configuration's sheet states: damaged or
//! hostile bytes give an error naming the file, never a panic; and what is
//! read keeps the plan's numbers finite (a wind speed of 1e300 m/s read as
//! trusted swung the load to infinity and panicked building the C-space):
//! the demo's lift, planned for its swing in each stated wind speed, swings
//! a finite distance per metre it hangs, and takes each stated
//! counterweight as a finite mass.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;

fn lift() -> &'static liftplan_core::lift::LiftTask {
    static TASK: OnceLock<liftplan_core::lift::LiftTask> = OnceLock::new();
    TASK.get_or_init(liftplan_fixtures::demo::lift)
}

fuzz_target!(|data: &[u8]| {
    let Ok(configs) = liftplan_core::chart_json::from_bytes(std::path::Path::new("chart.json"), data) else { return };
    let winds = liftplan_core::chart_json::stated(&configs, |c| &c.wind_ms);
    let counterweights = liftplan_core::chart_json::stated(&configs, |c| &c.counterweight_kg);
    for (_, stated) in winds.iter().take(4) {
        for one in stated.iter().take(4) {
            let mut t = lift().clone();
            // As the plan stage plans a lift whose chart's sheet states one speed.
            if t.plan_for_wind(std::slice::from_ref(one)).is_ok() {
                assert!(t.gust_swing_per_m.is_finite(), "{} m/s: swing {} per m", one.value, t.gust_swing_per_m);
            }
        }
        let _ = lift().permissible_wind(stated);
    }
    for (_, stated) in counterweights.iter().take(4) {
        for one in stated.iter().take(4) {
            let mut t = lift().clone();
            t.chart_sheet_counterweight = Some(one.clone());
            if let Some((kg, _)) = t.chart_counterweight_kg() {
                assert!(kg.is_finite() && kg > 0.0, "{kg} kg");
            }
            let _ = t.counterweight_disagrees_kg();
        }
    }
});
