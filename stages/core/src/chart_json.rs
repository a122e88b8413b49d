//! The charts stage's `chart.json` as the plan and docs stages read it back:
//! for each chart configuration, what its sheet states beside its grid (the
//! permissible wind speed, the counterweight) and what reading it warned of.
//!
//! Read as a user's file is, not trusted: it lies in the project's cache,
//! where a disk, a copy or a hand can damage it, and its numbers go into the
//! plan (the load's swing in the wind, the outrigger pads' loads). So every
//! number is held to the bounds the charts stage held it to when it read it
//! off the sheet ([`crate::wind::MAX_CHART_WIND_MS`],
//! [`crate::lift::MAX_COUNTERWEIGHT_T`]); beyond them the plan's geometry
//! loses its meaning (a wind of 1e300 m/s swung the load to infinity and
//! overflowed the C-space's window), and the file is refused naming the
//! value's place.
//!
//! This module does not read the workbook, the capacity grids
//! ([`crate::capacity`]) or `lifts.json`; it does not decide which stated
//! value a lift takes ([`crate::lift::LiftTask::permissible_wind`] does).

use crate::capacity::StatedOnChart;
use std::path::Path;

/// One chart configuration as `chart.json` gives it: what its sheet states
/// and what reading it warned of.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
pub struct ConfigStated {
    pub name: String,
    /// Wind speeds its sheet states (m/s).
    pub wind_ms: Vec<StatedOnChart>,
    /// Counterweights its sheet states (kg).
    pub counterweight_kg: Vec<StatedOnChart>,
    pub warnings: Vec<String>,
}

#[derive(serde::Deserialize)]
struct ChartJson {
    configs: Vec<ConfigStated>,
}

/// Reads `chart.json` at `path` ([`from_bytes`]).
pub fn read(path: &Path) -> Result<Vec<ConfigStated>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    from_bytes(path, &bytes)
}

/// The configurations of a `chart.json` read from `path` (which names the
/// file in errors): refused where it is not JSON as the charts stage writes
/// it (with the line and column) or a number stated lies outside what a
/// chart's sheet is read to state (with the configuration and the entry).
pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<Vec<ConfigStated>, String> {
    let rerun = "rerun the charts stage (liftplan run --force charts)";
    let json: ChartJson = serde_json::from_slice(bytes)
        .map_err(|e| format!("{}: line {}, column {}: {e}; {rerun}", path.display(), e.line(), e.column()))?;
    let kg_max = crate::lift::MAX_COUNTERWEIGHT_T * crate::units::KG_PER_TONNE;
    for (i, c) in json.configs.iter().enumerate() {
        let lists = [
            ("wind_ms", &c.wind_ms, "m/s", crate::wind::MAX_CHART_WIND_MS, "a wind speed"),
            ("counterweight_kg", &c.counterweight_kg, "kg", kg_max, "a counterweight"),
        ];
        for (key, list, unit, max, what) in lists {
            for (j, s) in list.iter().enumerate() {
                if !(s.value > 0.0 && s.value <= max) {
                    return Err(format!(
                        "{}: configs[{i}] ('{}'), {key}[{j}] ({}): {} {unit} is not {what} a chart's sheet is read to state \
                         (above 0, at most {max} {unit}); {rerun}",
                        path.display(),
                        c.name,
                        s.cell,
                        // Not 301 digits for a value of 1e300.
                        if s.value.abs() < 1e9 { s.value.to_string() } else { format!("{:e}", s.value) }
                    ));
                }
            }
        }
    }
    Ok(json.configs)
}

/// What each configuration's sheet states in `list` (its wind speeds or
/// counterweights), by configuration name, for those that state any.
pub fn stated(
    configs: &[ConfigStated],
    list: fn(&ConfigStated) -> &Vec<StatedOnChart>,
) -> Vec<(String, Vec<StatedOnChart>)> {
    configs.iter().filter(|c| !list(c).is_empty()).map(|c| (c.name.clone(), list(c).clone())).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The demo's chart.json as the charts stage writes it, kept as the fuzz
    /// target `chart_json`'s seed: the fuzzer starts from a file this reads.
    const DEMO: &str = include_str!("../../../fuzz/seeds/chart_json/demo-chart.json");

    #[test]
    fn stated_values_and_warnings_read_back() {
        let configs = from_bytes(Path::new("chart.json"), DEMO.as_bytes()).unwrap();
        let names: Vec<&str> = configs.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["Main boom 360", "Main boom 360 CW 70t"]);
        let wind = stated(&configs, |c| &c.wind_ms);
        assert_eq!(
            (wind[0].0.as_str(), wind[0].1[0].value, wind[0].1[0].cell.as_str()),
            ("Main boom 360", 9.8, "Main boom 360!A51")
        );
        let counterweights: Vec<f64> =
            stated(&configs, |c| &c.counterweight_kg).iter().map(|(_, s)| s[0].value).collect();
        assert_eq!(counterweights, [140_000.0, 70_000.0]);
        assert!(configs.iter().all(|c| c.warnings.is_empty()));
        // A configuration that states nothing is not listed; its warnings are read.
        let warned = DEMO.replacen(r#""warnings": []"#, r#""warnings": ["row 7 read as radii"]"#, 1);
        let mut configs = from_bytes(Path::new("chart.json"), warned.as_bytes()).unwrap();
        assert_eq!(configs[0].warnings, ["row 7 read as radii"]);
        configs[1].wind_ms.clear();
        assert_eq!(stated(&configs, |c| &c.wind_ms).len(), 1);
    }

    #[test]
    fn values_beyond_what_a_sheet_is_read_to_state_are_refused_naming_their_place() {
        let path = Path::new("cache/charts/chart.json");
        for (from, to, says) in [
            (
                "9.8",
                "1e300",
                "configs[0] ('Main boom 360'), wind_ms[0] (Main boom 360!A51): 1e300 m/s is not a wind speed",
            ),
            ("9.8", "0.0", "wind_ms[0] (Main boom 360!A51): 0 m/s"),
            ("9.8", "100.5", "100.5 m/s"),
            ("140000.0", "-140000.0", "counterweight_kg[0] (Main boom 360!A3): -140000 kg is not a counterweight"),
            ("140000.0", "1e8", "100000000 kg"),
        ] {
            let damaged = DEMO.replacen(&format!("\"value\": {from}"), &format!("\"value\": {to}"), 1);
            let e = from_bytes(path, damaged.as_bytes()).unwrap_err();
            assert!(e.starts_with("cache/charts/chart.json: ") && e.contains(says), "{to}: {e}");
            assert!(e.ends_with("rerun the charts stage (liftplan run --force charts)"), "{e}");
        }
        // The bounds themselves are values a sheet may state.
        for (from, to) in [("9.8", "100.0"), ("140000.0", "1e7")] {
            let at_bound = DEMO.replacen(&format!("\"value\": {from}"), &format!("\"value\": {to}"), 1);
            assert!(from_bytes(path, at_bound.as_bytes()).is_ok(), "{to}");
        }
    }

    #[test]
    fn what_is_not_chart_json_is_refused_with_its_line_and_column() {
        let path = Path::new("chart.json");
        for (damaged, says) in [
            (DEMO.replacen("\"value\": 9.8", "\"value\": \"9.8\"", 1), "line 37, column"),
            (DEMO.replacen("\"warnings\": [],", "", 1), "missing field `warnings`"),
            (DEMO[..DEMO.len() / 2].to_string(), "EOF while parsing"),
            ("[".repeat(10_000), "invalid type"),
        ] {
            let e = from_bytes(path, damaged.as_bytes()).unwrap_err();
            assert!(e.starts_with("chart.json: line ") && e.contains(says), "{e}");
        }
    }
}
