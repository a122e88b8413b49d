//! Crane model files, lift requests and scanner station files (TOML) through
//! parsing and resolution (on a mobile crane that weighs its hoist rope, and
//! a tower crane whose rope's length is given too), and a resolved lift's
//! sling and reeving checks.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let _ = liftplan_core::crane::CraneModel::from_toml(std::path::Path::new("fuzz.toml"), text);
    if let Ok(spec) = toml::from_str::<liftplan_core::lift::LiftSpec>(text) {
        for name in ["ac-700", "tower-hh-60"] {
            let Ok(mut model) = liftplan_core::crane::builtin(name) else { continue };
            model.hook.rope_kg_per_m = Some(3.9);
            if model.is_tower() {
                (model.hook.rope_m, model.hook.rope_lead_m) = (Some(150.0), Some(10.0));
            }
            if let Ok(task) = spec.clone().resolve(model) {
                let _ = liftplan_core::reeving::Reeving::of(&task).map(|r| (r.said(), r.refused()));
                let _ = task.check_slings().map(|c| c.map(|c| (c.said(), c.over_limit())));
            }
        }
    }
    let _ = liftplan_scans::parse_stations(std::path::Path::new("stations.toml"), text);
});
