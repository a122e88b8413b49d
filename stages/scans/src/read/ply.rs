//! PLY point clouds (ascii and binary) through `ply-rs`: x, y, z with optional
//! intensity (`intensity`, `scalar_intensity`, `reflectance`) and colour
//! (`red`/`green`/`blue`, 8 or 16 bit). Normals are accepted and ignored.

use super::{CHUNK_POINTS, Format, ScanInfo, check_finite, guard_decoder, stem};
use crate::error::{Result, ScanError};
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use ply_rs::parser::Parser;
use ply_rs::ply::{DefaultElement, Header, Property, PropertyAccess, PropertyType, ScalarType};
use serde_json::json;
use std::io::BufReader;
use std::path::Path;

#[derive(Default)]
struct Vertex {
    xyz: [f64; 3],
    intensity: f64,
    rgb: [u16; 3],
}

fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => v as f64,
        Property::UChar(v) => v as f64,
        Property::Short(v) => v as f64,
        Property::UShort(v) => v as f64,
        Property::Int(v) => v as f64,
        Property::UInt(v) => v as f64,
        Property::Float(v) => v as f64,
        Property::Double(v) => v,
        _ => return None,
    })
}

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Vertex::default()
    }
    fn set_property(&mut self, key: String, p: Property) {
        let Some(v) = scalar(&p) else { return };
        let eight_bit = matches!(p, Property::UChar(_) | Property::Char(_));
        let colour = |v: f64| {
            if eight_bit { (v.clamp(0.0, 255.0) * 257.0) as u16 } else { v.clamp(0.0, 65535.0) as u16 }
        };
        match key.as_str() {
            "x" => self.xyz[0] = v,
            "y" => self.xyz[1] = v,
            "z" => self.xyz[2] = v,
            "intensity" | "scalar_intensity" | "reflectance" | "scalar_Intensity" => self.intensity = v,
            "red" | "r" | "diffuse_red" => self.rgb[0] = colour(v),
            "green" | "g" | "diffuse_green" => self.rgb[1] = colour(v),
            "blue" | "b" | "diffuse_blue" => self.rgb[2] = colour(v),
            _ => {}
        }
    }
}

fn header(path: &Path) -> Result<(Header, BufReader<std::fs::File>)> {
    let f = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    let mut r = BufReader::new(f);
    liftplan_core::byte_order_mark::skip(&mut r).map_err(|e| ScanError::Io(Location::file(path), e))?;
    // ply-rs unwraps numbers in the header and panics on one too large for
    // 64 bits (found by the scan_file fuzz target).
    let h = guard_decoder(
        || Location::file(path),
        "the PLY header reader",
        || {
            Parser::<DefaultElement>::new()
                .read_header(&mut r)
                .map_err(|e| ScanError::format(Location::file(path), format!("cannot read PLY header: {e}")))
        },
    )?;
    Ok((h, r))
}

struct Layout {
    has_intensity: bool,
    has_rgb: bool,
    intensity_is_float: bool,
}

fn layout(path: &Path, h: &Header) -> Result<Layout> {
    let Some(v) = h.elements.get("vertex") else {
        return Err(ScanError::format(Location::file(path), "PLY has no 'vertex' element"));
    };
    for axis in ["x", "y", "z"] {
        match v.properties.get(axis) {
            Some(p) if matches!(p.data_type, PropertyType::Scalar(_)) => {}
            Some(_) => {
                return Err(ScanError::format(
                    Location::file(path),
                    format!("PLY property '{axis}' of element 'vertex' is a list, expected a number"),
                ));
            }
            None => {
                return Err(ScanError::format(
                    Location::file(path),
                    format!("PLY element 'vertex' has no property '{axis}' (expected x, y and z)"),
                ));
            }
        }
    }
    let intensity =
        ["intensity", "scalar_intensity", "reflectance", "scalar_Intensity"].iter().find_map(|k| v.properties.get(*k));
    let has_rgb = ["red", "r", "diffuse_red"].iter().any(|k| v.properties.contains_key(*k));
    let intensity_is_float =
        matches!(intensity.map(|p| &p.data_type), Some(PropertyType::Scalar(ScalarType::Float | ScalarType::Double)));
    Ok(Layout { has_intensity: intensity.is_some(), has_rgb, intensity_is_float })
}

pub(super) fn list(path: &Path) -> Result<Vec<ScanInfo>> {
    let (h, _) = header(path)?;
    layout(path, &h)?;
    let v = &h.elements["vertex"];
    let mut details = serde_json::Map::new();
    details.insert("encoding".into(), json!(format!("{:?}", h.encoding)));
    details.insert("properties".into(), json!(v.properties.keys().cloned().collect::<Vec<_>>()));
    details.insert("elements".into(), json!(h.elements.keys().cloned().collect::<Vec<_>>()));
    Ok(vec![ScanInfo {
        path: path.to_path_buf(),
        format: Format::Ply,
        index: 0,
        name: stem(path),
        declared_points: Some(v.count as u64),
        pose: None,
        bbox: None,
        details,
        unit: super::CrsUnit::None,
        date: None,
        to_m: [1.0; 3],
        read_in: String::new(),
        points_at: None,
    }])
}

/// The vertices of a PLY file whose header `h` was read from `r`, skipping
/// the elements before them.
fn vertices(path: &Path, h: &Header, r: &mut BufReader<std::fs::File>) -> Result<Vec<Vertex>> {
    let mut verts: Vec<Vertex> = Vec::new();
    for (name, def) in &h.elements {
        if name == "vertex" {
            verts = Parser::<Vertex>::new().read_payload_for_element(r, def, h).map_err(|e| {
                ScanError::format(
                    Location::item(path, "element 'vertex'"),
                    format!("cannot read the {} vertices the header declares: {e}", def.count),
                )
            })?;
            break;
        }
        Parser::<DefaultElement>::new().read_payload_for_element(r, def, h).map_err(|e| {
            ScanError::format(Location::item(path, format!("element '{name}'")), format!("cannot read: {e}"))
        })?;
    }
    Ok(verts)
}

pub(super) fn stream(info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
    let path = &info.path;
    let (h, mut r) = header(path)?;
    let lay = layout(path, &h)?;
    let verts = guard_decoder(|| Location::file(path), "the PLY reader", || vertices(path, &h, &mut r))?;
    // Float intensities are usually 0..1; LAS wants 16 bits.
    let max_i = verts.iter().map(|v| v.intensity).fold(0.0f64, f64::max);
    let scale_i = if lay.intensity_is_float && max_i <= 1.0 { 65535.0 } else { 1.0 };
    let mut seen = 0u64;
    for part in verts.chunks(CHUNK_POINTS) {
        let chunk = PointCloud {
            xyz: part.iter().map(|v| v.xyz).collect(),
            intensity: if lay.has_intensity {
                part.iter().map(|v| (v.intensity * scale_i).clamp(0.0, 65535.0) as u16).collect()
            } else {
                vec![]
            },
            rgb: if lay.has_rgb { part.iter().map(|v| v.rgb).collect() } else { vec![] },
            class: vec![],
            scan: vec![],
        };
        check_finite(info, &chunk, seen)?;
        seen += part.len() as u64;
        f(&chunk)?;
    }
    Ok(seen)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A PLY scan saved with a UTF-8 byte order mark reads (it was refused:
    /// "Expected magic number 'ply'").
    #[test]
    fn a_byte_order_mark_is_passed_over() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("marked.ply");
        let text = "\u{feff}ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n4 5 6\n";
        std::fs::write(&path, text).unwrap();
        let scans = list(&path).unwrap();
        assert_eq!(crate::read::read_all(&scans[0]).unwrap().xyz, [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
    }

    /// Found by the scan_file fuzz target: ply-rs unwraps the header's
    /// numbers and panicked on one too large for 64 bits.
    #[test]
    fn a_header_number_too_large_is_an_error() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("huge.ply");
        let text = "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        std::fs::write(&path, text).unwrap();
        let e = list(&path).unwrap_err().to_string();
        assert!(e.contains("huge.ply") && e.contains("PLY header reader failed on damaged data"), "{e}");
    }
}
