//! `liftplan inspect FILE`: a summary of any input file, picked by extension,
//! like `pdal info`.

use anyhow::{Result, bail};
use std::path::Path;

pub fn inspect(path: &Path) -> Result<serde_json::Value> {
    if !path.exists() {
        bail!("{}: no such file", path.display());
    }
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if crate::stages::SCAN_EXTS.contains(&ext.as_str()) {
        return Ok(liftplan_scans::inspect(path)?);
    }
    if liftplan_charts::EXTS.contains(&ext.as_str()) {
        return Ok(liftplan_charts::inspect(path)?);
    }
    if liftplan_plant::EXTS.contains(&ext.as_str()) {
        return Ok(liftplan_plant::inspect(path, &liftplan_plant::Settings::default())?);
    }
    if ext == "mdm" {
        return Ok(liftplan_depthmap::inspect(path)?);
    }
    if ext == "toml" {
        return inspect_toml(path);
    }
    bail!(
        "{}: liftplan does not read .{ext} files (scans: {}; plant: {}; charts: {}; depth maps: mdm; crane models and station files: toml)",
        path.display(),
        crate::stages::SCAN_EXTS.join(", "),
        liftplan_plant::EXTS.join(", "),
        liftplan_charts::EXTS.join(", ")
    )
}

/// The .toml files liftplan reads besides the project file: crane models
/// (`cranes/*.toml`) and scanner station files.
fn inspect_toml(path: &Path) -> Result<serde_json::Value> {
    let text = liftplan_core::location::read_text(path).map_err(|e| match e {
        liftplan_core::location::TextReadError::Io(e) => anyhow::anyhow!("{}: {e}", path.display()),
        liftplan_core::location::TextReadError::NotUtf8(at, why) => anyhow::anyhow!("{at}: {why}"),
    })?;
    if path.file_name().is_some_and(|n| n == crate::project::FILE) {
        bail!(
            "{}: a project file; `liftplan status` shows what it asks for and `liftplan options` every setting",
            path.display()
        );
    }
    let table: toml::Table = text.parse().map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    if table.contains_key("station") {
        let stations = liftplan_scans::parse_stations(path, &text)?;
        return Ok(serde_json::json!({
            "file": path.display().to_string(),
            "kind": "scanner stations",
            "stations": stations.iter().map(|s| {
                let t = s.pose.translation;
                serde_json::json!({ "scan": s.scan, "line": s.line, "x_m": t.x, "y_m": t.y, "z_m": t.z })
            }).collect::<Vec<_>>(),
        }));
    }
    let m = liftplan_core::crane::CraneModel::from_toml(path, &text).map_err(|e| anyhow::anyhow!("{e}"))?;
    let mut v = serde_json::json!({ "file": path.display().to_string(), "kind": "crane model" });
    if let (Some(o), serde_json::Value::Object(model)) = (v.as_object_mut(), serde_json::to_value(&m)?) {
        o.extend(model.into_iter().map(|(k, x)| (if k == "kind" { "crane".to_string() } else { k }, x)));
    }
    Ok(v)
}

/// A few readable lines for the terminal.
pub fn human(v: &serde_json::Value) -> String {
    let mut s = String::new();
    if let Some(obj) = v.as_object() {
        for (k, val) in obj {
            match val {
                serde_json::Value::Array(a) if a.iter().all(|x| x.is_number()) => {
                    s.push_str(&format!("{k}: [{}]\n", a.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", ")));
                }
                serde_json::Value::Array(a) => {
                    s.push_str(&format!("{k}:\n"));
                    for item in a {
                        s.push_str(&format!("  - {}\n", serde_json::to_string(item).unwrap_or_default()));
                    }
                }
                serde_json::Value::Object(_) => {
                    s.push_str(&format!("{k}: {}\n", serde_json::to_string(val).unwrap_or_default()))
                }
                other => s.push_str(&format!(
                    "{k}: {}\n",
                    other.as_str().map(String::from).unwrap_or_else(|| other.to_string())
                )),
            }
        }
    }
    s
}
