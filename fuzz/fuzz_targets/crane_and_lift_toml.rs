//! Crane model files, lift requests and scanner station files (TOML) through
//! parsing and resolution (on a crane that weighs its hoist rope), and a
//! resolved lift's sling and reeving checks.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let _ = liftplan_core::crane::CraneModel::from_toml(std::path::Path::new("fuzz.toml"), text);
    if let Ok(spec) = toml::from_str::<liftplan_core::lift::LiftSpec>(text)
        && let Ok(mut model) = liftplan_core::crane::builtin("ac-700")
        && let Ok(task) = {
            model.hook.rope_kg_per_m = Some(3.9);
            spec.resolve(model)
        }
    {
        let _ = liftplan_core::reeving::Reeving::of(&task).map(|r| (r.said(), r.refused()));
        let _ = task.check_slings().map(|c| c.map(|c| (c.said(), c.over_limit())));
    }
    let _ = liftplan_scans::parse_stations(std::path::Path::new("stations.toml"), text);
});
