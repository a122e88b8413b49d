//! ASTM E57 through the `e57` crate: several scans per file, structured
//! (gridded, with invalid no-return cells) or unstructured, cartesian or
//! spherical coordinates, each scan with its stored pose.
//!
//! Points are delivered in the scan's own frame and the stored pose is returned
//! separately so registration can use it as the initial guess. Pages with a bad
//! CRC are refused by the `e57` crate's paged reader; we report which scan and
//! how many points were read before it.

use super::{CHUNK_POINTS, Format, ScanInfo, check_finite};
use crate::error::{Result, ScanError};
use e57::{CartesianCoordinate, E57Reader};
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use liftplan_core::frame::{Aabb, Pose};
use nalgebra as na;
use serde_json::json;
use std::path::Path;

fn open(path: &Path) -> Result<E57Reader<std::io::BufReader<std::fs::File>>> {
    E57Reader::from_file(path)
        .map_err(|e| ScanError::format(Location::file(path), format!("cannot read E57 structure: {e}")))
}

fn pose_of(pc: &e57::PointCloud) -> Option<Pose> {
    let t = pc.transform.as_ref()?;
    let q = na::UnitQuaternion::from_quaternion(na::Quaternion::new(
        t.rotation.w,
        t.rotation.x,
        t.rotation.y,
        t.rotation.z,
    ));
    let tr = na::Translation3::new(t.translation.x, t.translation.y, t.translation.z);
    let all_finite =
        [t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z, t.translation.x, t.translation.y, t.translation.z]
            .iter()
            .all(|v| v.is_finite());
    all_finite.then(|| Pose::from_parts(tr, q))
}

pub(super) fn list(path: &Path) -> Result<Vec<ScanInfo>> {
    let r = open(path)?;
    let pcs = r.pointclouds();
    if pcs.is_empty() {
        return Err(ScanError::format(Location::file(path), "the E57 file holds no point clouds"));
    }
    let stem = super::stem(path);
    Ok(pcs
        .iter()
        .enumerate()
        .map(|(i, pc)| {
            let bbox = pc.cartesian_bounds.as_ref().and_then(|b| {
                match (b.x_min, b.y_min, b.z_min, b.x_max, b.y_max, b.z_max) {
                    (Some(a), Some(b_), Some(c), Some(d), Some(e), Some(f)) => {
                        Some(Aabb { min: [a, b_, c], max: [d, e, f] })
                    }
                    _ => None,
                }
            });
            let mut details = serde_json::Map::new();
            details.insert("guid".into(), json!(pc.guid));
            details.insert("structured".into(), json!(pc.index_bounds.is_some()));
            details.insert("has_pose".into(), json!(pc.transform.is_some()));
            details.insert("sensor".into(), json!(pc.sensor_model));
            details.insert(
                "attributes".into(),
                json!(pc.prototype.iter().map(|r| format!("{:?}", r.name)).collect::<Vec<_>>()),
            );
            ScanInfo {
                path: path.to_path_buf(),
                format: Format::E57,
                index: i,
                name: pc.name.clone().unwrap_or_else(|| format!("{stem}#{i}")),
                declared_points: Some(pc.records),
                pose: pose_of(pc),
                bbox,
                details,
            }
        })
        .collect())
}

pub(super) fn stream(info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
    let path = &info.path;
    let mut r = open(path)?;
    let pcs = r.pointclouds();
    let Some(pc) = pcs.get(info.index) else {
        return Err(ScanError::format(Location::item(path, &info.name), "scan no longer present in the file"));
    };
    let has_rgb = pc.has_color();
    let has_int = pc.has_intensity();
    let mut it = r
        .pointcloud_simple(pc)
        .map_err(|e| ScanError::format(Location::item(path, &info.name), format!("cannot open scan: {e}")))?;
    it.apply_pose(false);
    it.spherical_to_cartesian(true);
    let mut chunk = PointCloud::default();
    let mut seen = 0u64;
    let mut records = 0u64;
    for p in it {
        let p = p.map_err(|e| {
            ScanError::format(
                Location::item(path, format!("{}, record {records}", info.name)),
                format!("cannot read point data: {e}"),
            )
        })?;
        records += 1;
        let CartesianCoordinate::Valid { x, y, z } = p.cartesian else {
            continue;
        };
        chunk.xyz.push([x, y, z]);
        if has_int {
            chunk.intensity.push((p.intensity.unwrap_or(0.0).clamp(0.0, 1.0) * 65535.0) as u16);
        }
        if has_rgb {
            let c = p.color.map(|c| [c.red, c.green, c.blue]).unwrap_or([0.0; 3]);
            chunk.rgb.push([
                (c[0].clamp(0.0, 1.0) * 65535.0) as u16,
                (c[1].clamp(0.0, 1.0) * 65535.0) as u16,
                (c[2].clamp(0.0, 1.0) * 65535.0) as u16,
            ]);
        }
        if chunk.len() >= CHUNK_POINTS {
            check_finite(info, &chunk, seen)?;
            seen += chunk.len() as u64;
            f(&chunk)?;
            chunk = PointCloud::default();
        }
    }
    if !chunk.is_empty() {
        check_finite(info, &chunk, seen)?;
        seen += chunk.len() as u64;
        f(&chunk)?;
    }
    if records < pc.records {
        return Err(ScanError::format(
            Location::item(path, &info.name),
            format!("the scan declares {} records but only {records} could be read", pc.records),
        ));
    }
    Ok(seen)
}
