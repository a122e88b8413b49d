//! `registration.json` as a later stage reads it back: which scans were
//! left out, which were merged with a warning, and how the reference was
//! levelled (the docs stage says all three on the plan's pages).
//!
//! Read typed, next to its writer ([`crate::ScanReport`]), so the two
//! shapes change together (a test writes one and reads it back): a file of
//! another shape is refused, not read as one of no scans, whose plan would
//! then say nothing of scans left out. What is read is words for the pages,
//! of any length ([`Registration::MAX_SCANS`] bounds how many); this module
//! must not decide anything about the plan.

use serde::Deserialize;

/// What a later stage reads of `registration.json`.
#[derive(Debug, Clone, Deserialize)]
pub struct Registration {
    pub scans: Vec<ScanRegistered>,
    /// What was passed by as holding no scan ([`crate::PassedBy`]); none
    /// in a file written before the stage passed files by.
    #[serde(default)]
    pub passed_by: Vec<PassedByRecorded>,
}

/// One file passed by, as [`crate::PassedBy`] writes it.
#[derive(Debug, Clone, Deserialize)]
pub struct PassedByRecorded {
    pub file: String,
    pub why: String,
}

/// One scan's entry, as [`crate::ScanReport`] writes it.
#[derive(Debug, Clone, Deserialize)]
pub struct ScanRegistered {
    pub name: String,
    /// Merged into the site cloud.
    pub registered: bool,
    /// How it was placed ("reference, levelled by ...", "plan-view
    /// correlation + ICP", ...).
    pub method: String,
    pub warning: Option<String>,
}

impl Registration {
    /// The most scans a `registration.json` read back may list: a survey
    /// is tens or hundreds of scans (registration, quadratic in them, takes
    /// minutes at a few tens), and each left out or warned of is a line on
    /// the plan's pages.
    pub const MAX_SCANS: usize = 100_000;

    /// Reads `registration.json`'s bytes, refusing a file of another shape
    /// or of more than [`Self::MAX_SCANS`] scans with serde's words (which
    /// say the line and column) or the count.
    pub fn from_json(bytes: &[u8]) -> Result<Registration, String> {
        let read: Registration = serde_json::from_slice(bytes).map_err(|e| e.to_string())?;
        if read.scans.len() > Self::MAX_SCANS {
            return Err(format!("{} scans, more than the {} liftplan reads", read.scans.len(), Self::MAX_SCANS));
        }
        if read.passed_by.len() > Self::MAX_SCANS {
            return Err(format!(
                "{} files passed by, more than the {} liftplan reads",
                read.passed_by.len(),
                Self::MAX_SCANS
            ));
        }
        Ok(read)
    }

    /// The scans left out unregistered, by name (what only they saw is
    /// missing from the site), and how many scans there were in all.
    pub fn left_out(&self) -> (Vec<String>, usize) {
        (self.scans.iter().filter(|s| !s.registered).map(|s| s.name.clone()).collect(), self.scans.len())
    }

    /// The files (or scans in them) passed by as holding no scan, each
    /// with why: "scans/readme.txt (holds no scan ...)".
    pub fn passed_by(&self) -> Vec<String> {
        self.passed_by.iter().map(|p| format!("{} ({})", p.file, p.why)).collect()
    }

    /// The reference scan and how it was levelled, where its vertical
    /// rests on its ground or on nothing (a scanner that did not level
    /// itself): every height in the plan rests on that frame.
    pub fn site_level_unconfirmed(&self) -> Option<(String, String)> {
        use crate::register::{LEVELLED_BY_GROUND, NOT_LEVELLED};
        let reference = self.scans.iter().find(|s| s.method.starts_with("reference"))?;
        let method = &reference.method;
        (method.contains(LEVELLED_BY_GROUND) || method.contains(NOT_LEVELLED))
            .then(|| (reference.name.clone(), method.clone()))
    }

    /// The scans merged with a warning from registration (placed with
    /// their station's help along a way what they share holds loosely,
    /// though points lie where another scanner saw through, or moved by the
    /// last alignment against all the others): each one's name and the
    /// warning. A scan left out is said as left out, not here.
    pub fn warned(&self) -> Vec<(String, String)> {
        self.scans
            .iter()
            .filter(|s| s.registered)
            .filter_map(|s| {
                let warning = s.warning.as_deref().filter(|w| !w.is_empty())?;
                Some((s.name.clone(), warning.to_string()))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::Registration;

    fn registration(json: serde_json::Value) -> Registration {
        Registration::from_json(json.to_string().as_bytes()).unwrap()
    }

    /// Only merged scans with a warning are named: a scan left out is
    /// named as left out, not as warned of.
    #[test]
    fn scans_merged_with_a_warning_are_named() {
        let method = "plan-view correlation + ICP";
        let scans = registration(serde_json::json!({ "scans": [
            { "name": "scan-1", "registered": true, "method": "reference", "warning": null },
            { "name": "scan-2", "registered": true, "method": method, "warning": "scan 'scan-2' was placed with its station's help: ..." },
            { "name": "scan-3", "registered": false, "method": "", "warning": "scan 'scan-3' is not merged: ..." },
            { "name": "scan-4", "registered": true, "method": method },
        ] }));
        assert_eq!(
            scans.warned(),
            [("scan-2".to_string(), "scan 'scan-2' was placed with its station's help: ...".to_string())]
        );
        assert_eq!(scans.left_out(), (vec!["scan-3".to_string()], 4));
        assert!(registration(serde_json::json!({ "scans": [] })).warned().is_empty());
    }

    /// A registration.json not of the shape the scans stage writes (no
    /// scans, a name not a string, whether merged not said) is refused, not
    /// read as one that says nothing of scans left out; nor is one listing
    /// more scans than liftplan reads.
    #[test]
    fn a_registration_of_another_shape_is_refused() {
        for wrong in [
            serde_json::json!([1, 2, 3]),
            serde_json::json!({}),
            serde_json::json!({ "scans": [{ "name": 5, "registered": false, "method": "" }] }),
            serde_json::json!({ "scans": [{ "name": "scan-3", "method": "" }] }),
            serde_json::json!({ "scans": [{ "name": "scan-3", "registered": "no", "method": "" }] }),
        ] {
            let e = Registration::from_json(wrong.to_string().as_bytes()).unwrap_err();
            assert!(e.contains(" at line 1 column "), "{wrong}: {e}");
        }
        let scan = r#"{"name":"s","registered":true,"method":"reference"}"#;
        let many = format!(r#"{{"scans":[{}]}}"#, vec![scan; Registration::MAX_SCANS + 1].join(","));
        let e = Registration::from_json(many.as_bytes()).unwrap_err();
        assert_eq!(e, "100001 scans, more than the 100000 liftplan reads");
    }

    /// What the scans stage writes reads back: the scan's name, whether
    /// merged, how and its warning.
    #[test]
    fn the_scans_stage_s_file_reads_back() {
        let report = crate::ScanReport {
            file: "scans/north.e57".into(),
            name: "north".into(),
            format: crate::read::Format::E57,
            points_read: 10,
            points_kept: 5,
            pose: [[0.0; 4]; 4],
            fitness: 0.9,
            rmse_m: 0.01,
            method: "plan-view correlation + ICP".into(),
            registered: true,
            warning: Some("moved 0.04 m by the last alignment".into()),
            hold_m: Some(0.02),
            refined_move_m: Some(0.04),
            unit: "metre".into(),
            to_m: [1.0; 3],
            date: None,
        };
        let left_out = crate::ScanReport { name: "south".into(), registered: false, warning: None, ..report.clone() };
        let passed = crate::PassedBy { file: "scans/readme.txt".into(), why: "holds no scan".into() };
        let written = crate::registration_json(crate::RegisterMode::None, &[report, left_out], &[passed]).to_string();
        let read = Registration::from_json(written.as_bytes()).unwrap();
        assert_eq!(read.left_out(), (vec!["south".to_string()], 2));
        assert_eq!(read.passed_by(), ["scans/readme.txt (holds no scan)"]);
        assert_eq!(read.warned(), [("north".to_string(), "moved 0.04 m by the last alignment".to_string())]);
        assert_eq!(read.scans[0].method, "plan-view correlation + ICP");
    }

    /// The demo's registration.json (the fuzz target `stage_records`'
    /// seed) reads: four scans, all merged, none warned of.
    #[test]
    fn the_demos_registration_json_is_read() {
        let demo = include_bytes!("../../../fuzz/seeds/stage_records/registration.json");
        let read = Registration::from_json(demo).unwrap();
        assert_eq!(read.left_out(), (vec![], 4));
        assert!(read.warned().is_empty() && read.site_level_unconfirmed().is_none());
        // Written before files were passed by: none.
        assert!(read.passed_by().is_empty());
        let e = Registration::from_json(&demo[..demo.len() / 2]).unwrap_err();
        assert!(e.contains(" at line "), "{e}");
    }

    #[test]
    fn a_reference_levelled_by_its_ground_or_not_at_all_is_named() {
        let with = |method: &str| {
            registration(serde_json::json!({ "scans": [
                { "name": "scan-2", "registered": true, "method": "levelled, plan-view correlation + ICP" },
                { "name": "scan-1", "registered": true, "method": method },
            ] }))
        };
        for unconfirmed in [
            format!("reference, levelled by {}", crate::register::LEVELLED_BY_GROUND),
            "reference, NOT LEVELLED: too few walls".to_string(),
        ] {
            assert_eq!(with(&unconfirmed).site_level_unconfirmed(), Some(("scan-1".into(), unconfirmed.clone())));
        }
        for confirmed in ["reference", "reference, levelled by its plumb surfaces (walls, columns, tanks)"] {
            assert_eq!(with(confirmed).site_level_unconfirmed(), None, "{confirmed}");
        }
    }
}
