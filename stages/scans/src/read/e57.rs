//! ASTM E57 through the `e57` crate: several scans per file, structured
//! (gridded, with invalid no-return cells) or unstructured, cartesian or
//! spherical coordinates, each scan with its stored pose.
//!
//! Points are delivered in the scan's own frame and the stored pose is returned
//! separately so registration can use it as the initial guess. Pages with a bad
//! CRC are refused by the `e57` crate's paged reader; we report which scan and
//! how many points were read before it.

use super::{CHUNK_POINTS, Format, ScanInfo, check_finite, guard_decoder};
use crate::error::{Result, ScanError};
use e57::{CartesianCoordinate, E57Reader};
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use liftplan_core::frame::{Aabb, Pose};
use nalgebra as na;
use serde_json::json;
use std::path::{Path, PathBuf};

/// The E57 reader's calls go through the guard, as the LAS, LAZ and PLY
/// readers' do: none has panicked under the fuzzer yet, but a panic on a
/// damaged file should be that file's error, not a crash.
fn open(path: &Path) -> Result<E57Reader<std::io::BufReader<std::fs::File>>> {
    guard_decoder(
        || Location::file(path),
        "the E57 reader",
        || {
            E57Reader::from_file(path)
                .map_err(|e| ScanError::format(Location::file(path), format!("cannot read E57 structure: {e}")))
        },
    )
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
                name: pc.name.as_deref().map(super::scan_name_kept).unwrap_or_else(|| format!("{stem}#{i}")),
                declared_points: Some(pc.records),
                pose: pose_of(pc),
                bbox,
                details,
                unit: super::CrsUnit::Stated(super::StatedUnit::metres(
                    "metre (E57 coordinates are metres by its standard)",
                )),
                date: pc.acquisition_start.as_ref().and_then(|t| super::ScanDate::from_gps_seconds(t.gps_time)),
                to_m: [1.0; 3],
                read_in: String::new(),
                points_at: None,
            }
        })
        .collect())
}

/// An E57 file opened for all its scans. Opening one parses its XML section,
/// which grows with the number of scans, so a file opened once per scan cost
/// the square of its scans: 2,000 scans of three points each (4.5 MB) took
/// `liftplan scans` 155 s (0.31 s opened once).
pub(super) struct OpenE57 {
    path: PathBuf,
    reader: E57Reader<std::io::BufReader<std::fs::File>>,
    /// The scans' descriptions, taken once (`E57Reader::pointclouds` copies them all).
    clouds: Vec<e57::PointCloud>,
}

impl OpenE57 {
    pub(super) fn open(path: &Path) -> Result<Self> {
        #[cfg(test)]
        super::E57_OPENS.with(|n| n.set(n.get() + 1));
        let reader = open(path)?;
        let clouds = reader.pointclouds();
        Ok(OpenE57 { path: path.to_path_buf(), reader, clouds })
    }

    pub(super) fn path(&self) -> &Path {
        &self.path
    }

    pub(super) fn stream(&mut self, info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
        let path = &info.path;
        let Some(pc) = self.clouds.get(info.index) else {
            return Err(ScanError::format(Location::item(path, &info.name), "scan no longer present in the file"));
        };
        let r = &mut self.reader;
        let has_rgb = pc.has_color();
        let has_int = pc.has_intensity();
        let mut it = guard_decoder(
            || Location::item(path, &info.name),
            "the E57 reader",
            || {
                r.pointcloud_simple(pc)
                    .map_err(|e| ScanError::format(Location::item(path, &info.name), format!("cannot open scan: {e}")))
            },
        )?;
        it.apply_pose(false);
        it.spherical_to_cartesian(true);
        let mut chunk = PointCloud::default();
        let mut seen = 0u64;
        let mut records = 0u64;
        let place = |records: u64| Location::item(path, format!("{}, record {records}", info.name));
        // Points are decoded a batch at a time inside the guard, so that our own
        // handling of them (and the callback) stays outside it.
        let mut batch = Vec::with_capacity(4096);
        loop {
            batch.clear();
            guard_decoder(
                || place(records),
                "the E57 reader",
                || {
                    batch.extend(it.by_ref().take(4096));
                    Ok(())
                },
            )?;
            if batch.is_empty() {
                break;
            }
            for p in batch.drain(..) {
                let p = p.map_err(|e| ScanError::format(place(records), format!("cannot read point data: {e}")))?;
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::read::{E57_OPENS, ScanStreamer, list_scans, read_all};

    fn two_scans() -> Vec<ScanInfo> {
        list_scans(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scans/two-scans.e57")).unwrap()
    }

    /// Scans streamed one after another open their file once, and read as
    /// they do each on its own.
    #[test]
    fn a_file_is_opened_once_for_its_scans() {
        let scans = two_scans();
        let opens = || E57_OPENS.with(|n| n.get());
        let before = opens();
        let alone: Vec<PointCloud> = scans.iter().map(|s| read_all(s).unwrap()).collect();
        assert_eq!(opens() - before, 2);

        let before = opens();
        let mut files = ScanStreamer::default();
        for (s, want) in scans.iter().zip(&alone) {
            let mut got = PointCloud::default();
            let n = files
                .stream(s, &mut |c| {
                    got.append(c);
                    Ok(())
                })
                .unwrap();
            assert_eq!(n, want.len() as u64);
            assert_eq!((&got.xyz, &got.intensity, &got.rgb), (&want.xyz, &want.intensity, &want.rgb));
        }
        // Again from the first scan: the file stays open, and reads the same.
        let again = files.stream(&scans[0], &mut |c| {
            assert_eq!(c.xyz, alone[0].xyz);
            Ok(())
        });
        assert_eq!(again.unwrap(), 30);
        assert_eq!(opens() - before, 1);
    }

    /// `fixtures/scans/two-scans.e57`, written by pye57 (`make_e57.py` there):
    /// two scans, one with a pose and one with intensity and colour.
    #[test]
    fn two_scans_with_pose_intensity_and_colour() {
        let scans = two_scans();
        assert_eq!(scans.len(), 2);
        assert_eq!((scans[0].name.as_str(), scans[0].declared_points), ("scan-a", Some(30)));
        assert_eq!((scans[1].name.as_str(), scans[1].declared_points), ("scan-b", Some(20)));
        let pose = liftplan_core::frame::pose_to_rows(scans[0].pose.as_ref().unwrap());
        assert_eq!([pose[0][3], pose[1][3], pose[2][3]], [1.0, 2.0, 0.5]);
        // Points come in the scan's own frame (pye57 stores them as f32).
        let a = read_all(&scans[0]).unwrap();
        assert_eq!(a.len(), 30);
        for (k, p) in a.xyz.iter().enumerate() {
            let want = [0.1 * k as f64, 2.0, 0.05 * k as f64];
            assert!((0..3).all(|i| (p[i] - want[i]).abs() < 1e-6), "{k}: {p:?}");
        }
        assert!(a.intensity.is_empty() && a.rgb.is_empty());
        let b = read_all(&scans[1]).unwrap();
        assert_eq!(b.len(), 20);
        // Intensity and colour are scaled to 0..65535 over the limits the file
        // states: pye57 states the intensities' own range (0..0.95) and the
        // colours' full one (0..255).
        for k in 0..20 {
            let full = |v: f64| (v * 65535.0) as i64;
            assert!((b.intensity[k] as i64 - full(k as f64 / 19.0)).abs() <= 1, "{k}: {}", b.intensity[k]);
            assert!(
                b.rgb[k].iter().all(|c| (*c as i64 - full(10.0 * k as f64 / 255.0)).abs() <= 1),
                "{k}: {:?}",
                b.rgb[k]
            );
        }
    }

    /// An E57 scan's acquisition start (GPS seconds) is its date, as taken.
    #[test]
    fn an_e57_scans_acquisition_is_its_date() {
        use e57::{E57Writer, Record, RecordValue};
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("dated.e57");
        let mut w = E57Writer::from_file(&path, "liftplan-test").unwrap();
        for (k, start) in [Some(1.4e9), None].into_iter().enumerate() {
            let prototype = vec![Record::CARTESIAN_X_F64, Record::CARTESIAN_Y_F64, Record::CARTESIAN_Z_F64];
            let mut pc = w.add_pointcloud(&format!("scan-{k}"), prototype).unwrap();
            pc.set_acquisition_start(start.map(|gps_time| e57::DateTime { gps_time, atomic_reference: true }));
            pc.add_point(vec![RecordValue::Double(0.0), RecordValue::Double(0.0), RecordValue::Double(0.0)]).unwrap();
            pc.finalize().unwrap();
        }
        w.finalize().unwrap();
        let scans = super::super::list_scans(&path).unwrap();
        let dates: Vec<Option<String>> = scans.iter().map(|s| s.date.map(|d| d.to_string())).collect();
        assert_eq!(dates, [Some("2024-05-17 (acquired)".to_string()), None]);
    }
}
