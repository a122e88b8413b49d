//! PLY point clouds (ascii and binary) through `ply-rs`: x, y, z with optional
//! intensity (`intensity`, `scalar_intensity`, `reflectance`) and colour
//! (`red`/`green`/`blue`, 8 or 16 bit), their names in any case (`X`,
//! `scalar_Intensity`, as tools write them). Normals are accepted and
//! ignored.

use super::{CHUNK_POINTS, Format, ScanInfo, check_finite, guard_decoder, stem};
use crate::error::{Result, ScanError};
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use ply_rs::parser::Parser;
use ply_rs::ply::{DefaultElement, Header, Property, PropertyAccess, PropertyDef, PropertyType, ScalarType};
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

/// What a vertex property is, by its name in any case.
#[derive(Clone, Copy, PartialEq)]
enum Role {
    Axis(usize),
    Intensity,
    Colour(usize),
}

const INTENSITY_NAMES: [&str; 3] = ["intensity", "scalar_intensity", "reflectance"];
const COLOUR_NAMES: [[&str; 3]; 3] =
    [["red", "r", "diffuse_red"], ["green", "g", "diffuse_green"], ["blue", "b", "diffuse_blue"]];

fn role(key: &str) -> Option<Role> {
    let is = |names: &[&str]| names.iter().any(|n| key.eq_ignore_ascii_case(n));
    if let Some(axis) = ["x", "y", "z"].iter().position(|a| key.eq_ignore_ascii_case(a)) {
        return Some(Role::Axis(axis));
    }
    if is(&INTENSITY_NAMES) {
        return Some(Role::Intensity);
    }
    COLOUR_NAMES.iter().position(|names| is(names)).map(Role::Colour)
}

/// The vertex property in `role`: the first so named in the header.
fn property_in(properties: &ply_rs::ply::KeyMap<PropertyDef>, wanted: Role) -> Option<(&String, &PropertyDef)> {
    properties.iter().find(|(name, _)| role(name) == Some(wanted))
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
        match role(&key) {
            Some(Role::Axis(i)) => self.xyz[i] = v,
            Some(Role::Intensity) => self.intensity = v,
            Some(Role::Colour(i)) => self.rgb[i] = colour(v),
            None => {}
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
    for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
        match property_in(&v.properties, Role::Axis(i)) {
            Some((_, p)) if matches!(p.data_type, PropertyType::Scalar(_)) => {}
            Some((axis, _)) => {
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
    let intensity = property_in(&v.properties, Role::Intensity).map(|(_, p)| p);
    let has_rgb = property_in(&v.properties, Role::Colour(0)).is_some();
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

    /// Property names in capitals, as some tools write them, read as
    /// lower-case ones (a scan with `X`, `Y`, `Z` was refused: "no property
    /// 'x'"); intensity and colour too.
    #[test]
    fn property_names_in_any_case() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("capitals.ply");
        let text = "ply\nformat ascii 1.0\nelement vertex 2\nproperty double X\nproperty double Y\nproperty double Z\nproperty float Intensity\nproperty uchar Red\nproperty uchar Green\nproperty uchar Blue\nend_header\n1 2 3 0.5 255 0 0\n4 5 6 0.25 0 255 0\n";
        std::fs::write(&path, text).unwrap();
        let scans = list(&path).unwrap();
        let cloud = crate::read::read_all(&scans[0]).unwrap();
        assert_eq!(cloud.xyz, [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
        assert!(cloud.intensity.len() == 2 && cloud.intensity[0] > cloud.intensity[1], "{:?}", cloud.intensity);
        assert_eq!(cloud.rgb, [[65535, 0, 0], [0, 65535, 0]]);
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
