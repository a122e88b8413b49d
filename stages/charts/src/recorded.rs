//! `lifts.json` as a later stage reads it back: which lifts are on a
//! chart of one capacity column, and the boom it is said for (the docs
//! stage puts it on the cover: the chart does not say which boom its
//! column is for).
//!
//! Read typed, next to its writer ([`crate::LiftReport`]), so the two
//! shapes change together (a test writes one and reads it back): a file of
//! another shape is refused, not read as one of no such lifts. This module
//! must not read the capacities back: the plan takes them from
//! `capacity.csv`.

use liftplan_core::lift::LiftTask;
use serde::Deserialize;

/// What a later stage reads of `lifts.json`.
#[derive(Debug, Clone, Deserialize)]
pub struct LiftsCharted {
    pub lifts: Vec<LiftCharted>,
}

/// One lift's entry, as [`crate::LiftReport`] writes it.
#[derive(Debug, Clone, Deserialize)]
pub struct LiftCharted {
    pub id: String,
    pub one_column_for_boom_m: Option<f64>,
}

impl LiftsCharted {
    /// Reads `lifts.json`'s bytes, refusing a file of another shape with
    /// serde's words (which say the line and column).
    pub fn from_json(bytes: &[u8]) -> Result<LiftsCharted, String> {
        serde_json::from_slice(bytes).map_err(|e| e.to_string())
    }

    /// Each lift on a chart of one column and the boom it is said for,
    /// which the charts stage writes as the lift's own crane's: a lift not
    /// among `tasks`, or a boom not its crane's, is refused naming the
    /// entry (the cover would name a boom the crane is not set up with);
    /// the caller names the file and the stage to rerun.
    pub fn one_column_booms(&self, tasks: &[LiftTask]) -> Result<Vec<(String, f64)>, String> {
        let mut booms = Vec::new();
        for (k, l) in self.lifts.iter().enumerate() {
            let Some(boom) = l.one_column_for_boom_m else { continue };
            // Said short: an id read may be of any length.
            let id: String = l.id.chars().take(liftplan_core::lift::MAX_LIFT_ID_CHARS).collect();
            let Some(task) = tasks.iter().find(|t| t.id == l.id) else {
                return Err(format!("lifts[{k}]: lift '{id}' is not one of the project's lifts"));
            };
            let own = task.crane.placement.boom_length_m;
            if boom.to_bits() != own.to_bits() {
                return Err(format!(
                    "lifts[{k}] ('{id}'): one_column_for_boom_m {boom} is not the {own} m boom its crane is set up with"
                ));
            }
            booms.push((l.id.clone(), boom));
        }
        Ok(booms)
    }
}

#[cfg(test)]
mod tests {
    use super::LiftsCharted;

    /// A lift on a chart of one column is said with its crane's own boom;
    /// lifts.json naming another boom, or a lift the project has not, is
    /// refused naming the entry; a file of another shape is refused.
    #[test]
    fn a_one_column_charts_boom_is_the_lifts_own() {
        let task = liftplan_fixtures::demo::lift();
        let boom = task.crane.placement.boom_length_m;
        let charted = |id: &str, boom: f64| -> LiftsCharted {
            let json = serde_json::json!({ "lifts": [
                { "id": "other", "one_column_for_boom_m": null },
                { "id": id, "one_column_for_boom_m": boom },
            ] });
            LiftsCharted::from_json(json.to_string().as_bytes()).unwrap()
        };
        let tasks = std::slice::from_ref(&task);
        assert_eq!(charted("V-101", boom).one_column_booms(tasks).unwrap(), [("V-101".to_string(), boom)]);
        let e = charted("V-101", 1e300).one_column_booms(tasks).unwrap_err();
        assert!(e.starts_with("lifts[1] ('V-101'): one_column_for_boom_m 1000000"), "{e}");
        assert!(e.contains(&format!("is not the {boom} m boom its crane is set up with")), "{e}");
        let e = charted("V-102", boom).one_column_booms(tasks).unwrap_err();
        assert!(e.starts_with("lifts[1]: lift 'V-102' is not one of the project's lifts"), "{e}");
        let e = charted(&"V".repeat(5_000), boom).one_column_booms(tasks).unwrap_err();
        assert!(e.starts_with(&format!("lifts[1]: lift '{}' is not", "V".repeat(100))), "{}", &e[..200]);
        // The demo's lifts.json (the fuzz target `stage_records`' seed):
        // its lift on a chart by boom length.
        let demo = include_bytes!("../../../fuzz/seeds/stage_records/lifts.json");
        assert_eq!(LiftsCharted::from_json(demo).unwrap().one_column_booms(tasks).unwrap(), []);
        for wrong in
            [r#"[1]"#, r#"{}"#, r#"{"lifts":[{"id":5}]}"#, r#"{"lifts":[{"id":"L","one_column_for_boom_m":"40"}]}"#]
        {
            let e = LiftsCharted::from_json(wrong.as_bytes()).unwrap_err();
            assert!(e.contains(" at line 1 column "), "{wrong}: {e}");
        }
    }
}
