//! LAS 1.4 / LAZ output: point format 6 (7 with colour), millimetre scale,
//! classification, intensity, and the scan id in `point_source_id`.
//!
//! The file is written under a temporary name in the target folder and renamed
//! when complete, so a killed run never leaves a torn `site.laz`.

use crate::error::{Result, ScanError};
use las::{Builder, Point, Transform, Vector, Version, Writer};
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use std::io::BufWriter;
use std::path::Path;

pub fn write_las(path: &Path, cloud: &PointCloud) -> Result<()> {
    let loc = || Location::file(path);
    let compressed = path.extension().and_then(|e| e.to_str()).map(|e| e.eq_ignore_ascii_case("laz")).unwrap_or(false);
    let mut b = Builder::from((1, 4));
    b.version = Version::new(1, 4);
    b.point_format = las::point::Format::new(if cloud.rgb.is_empty() { 6 } else { 7 })
        .map_err(|e| ScanError::format(loc(), e.to_string()))?;
    b.point_format.is_compressed = compressed;
    b.generating_software = format!("liftplan {}", env!("CARGO_PKG_VERSION"));
    b.system_identifier = "liftplan scans stage".into();
    let bb = cloud.bbox();
    let off = |i: usize| {
        if bb.is_empty() { 0.0 } else { (bb.min[i]).floor() }
    };
    b.transforms = Vector {
        x: Transform { scale: 0.001, offset: off(0) },
        y: Transform { scale: 0.001, offset: off(1) },
        z: Transform { scale: 0.001, offset: off(2) },
    };
    let header = b.into_header().map_err(|e| ScanError::format(loc(), e.to_string()))?;
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| ScanError::Io(loc(), e))?;
    let tmp = dir.join(format!(
        ".{}.tmp-{}",
        path.file_name().map(|n| n.to_string_lossy()).unwrap_or_default(),
        std::process::id()
    ));
    let result = (|| -> std::result::Result<(), String> {
        let file = std::fs::File::create(&tmp).map_err(|e| e.to_string())?;
        let mut w = Writer::new(BufWriter::with_capacity(1 << 20, file), header).map_err(|e| e.to_string())?;
        for i in 0..cloud.len() {
            let p = cloud.xyz[i];
            let mut pt = Point { x: p[0], y: p[1], z: p[2], ..Default::default() };
            pt.intensity = cloud.intensity.get(i).copied().unwrap_or(0);
            pt.classification = las::point::Classification::new(cloud.class.get(i).copied().unwrap_or(1))
                .unwrap_or(las::point::Classification::Unclassified);
            pt.point_source_id = cloud.scan.get(i).copied().unwrap_or(0);
            pt.return_number = 1;
            pt.number_of_returns = 1;
            pt.gps_time = Some(0.0);
            if !cloud.rgb.is_empty() {
                let c = cloud.rgb[i];
                pt.color = Some(las::Color::new(c[0], c[1], c[2]));
            }
            w.write_point(pt).map_err(|e| e.to_string())?;
        }
        w.close().map_err(|e| e.to_string())?;
        let inner = w.into_inner().map_err(|e| e.to_string())?;
        let file = inner.into_inner().map_err(|e| e.to_string())?;
        file.sync_all().map_err(|e| e.to_string())?;
        Ok(())
    })();
    match result {
        Ok(()) => std::fs::rename(&tmp, path).map_err(|e| ScanError::Io(loc(), e)),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(ScanError::format(loc(), format!("cannot write LAS: {e}")))
        }
    }
}
