//! LAS 1.0–1.4 and LAZ through the `las` and `laz` crates, after the header
//! pre-check of our own ([`liftplan_core::las_file::precheck`], which the
//! stages reading `site.laz` back share), each call into them guarded.

use super::{CHUNK_POINTS, Format, ScanInfo, check_finite, guard_decoder, stem};
use crate::error::{Result, ScanError};
use las::Reader;
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
pub use liftplan_core::las_file::RawLasHeader;
use serde_json::json;
use std::path::Path;

/// Checks the structure of a LAS/LAZ file without trusting any field (see
/// [`liftplan_core::las_file::precheck`]).
pub fn precheck(path: &Path) -> Result<RawLasHeader> {
    Ok(liftplan_core::las_file::precheck(path)?)
}

fn open(path: &Path) -> Result<Reader> {
    let file = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    let r = std::io::BufReader::with_capacity(1 << 20, file);
    guard_decoder(
        || Location::file(path),
        "the LAS/LAZ reader",
        || Reader::new(r).map_err(|e| ScanError::format(Location::file(path), format!("cannot read LAS header: {e}"))),
    )
}

pub(super) fn list(path: &Path, format: Format) -> Result<Vec<ScanInfo>> {
    let raw = precheck(path)?;
    let reader = open(path)?;
    let hdr = reader.header();
    let fmt = if raw.compressed { Format::Laz } else { Format::Las };
    if fmt != format {
        tracing::warn!("{}: extension says {} but the file is {}", path.display(), format.name(), fmt.name());
    }
    let mut details = serde_json::Map::new();
    details.insert("version".into(), json!(format!("{}.{}", raw.version.0, raw.version.1)));
    details.insert("point_format".into(), json!(raw.point_format));
    details.insert("compressed".into(), json!(raw.compressed));
    details.insert("record_length".into(), json!(raw.record_length));
    details.insert("scale".into(), json!(raw.scale));
    details.insert("offset".into(), json!(raw.offset));
    details.insert("vlrs".into(), json!(hdr.vlrs().len()));
    details.insert("evlrs".into(), json!(hdr.evlrs().len()));
    details.insert("crs".into(), json!(hdr.has_crs_vlrs()));
    let unit = crs_unit(path, hdr)?;
    let said = match &unit {
        super::CrsUnit::Stated(u) => u.what.clone(),
        super::CrsUnit::Unstated { crs, .. } => format!("NOT STATED by its CRS ({crs})"),
        super::CrsUnit::None => "none stated (no CRS)".into(),
    };
    details.insert("unit".into(), json!(said));
    details.insert("system_identifier".into(), json!(hdr.system_identifier()));
    details.insert("generating_software".into(), json!(hdr.generating_software()));
    Ok(vec![ScanInfo {
        path: path.to_path_buf(),
        format: fmt,
        index: 0,
        name: stem(path),
        declared_points: Some(raw.points),
        pose: None,
        bbox: Some(raw.bbox),
        details,
        unit,
        date: hdr.date().map(|date| super::ScanDate { date, acquired: false }),
        to_m: [1.0; 3],
        read_in: String::new(),
        points_at: None,
    }])
}

/// The unit the file's CRS (E)VLRs state: the WKT's where it has one (LAS
/// 1.4 makes it the CRS), else the GeoTIFF keys'.
fn crs_unit(path: &Path, hdr: &las::Header) -> Result<super::CrsUnit> {
    let projection =
        |id: u16| hdr.all_vlrs().find(|v| v.user_id.trim_end_matches('\0') == "LASF_Projection" && v.record_id == id);
    let (found, record) = if let Some(v) = projection(2112) {
        (super::units::from_wkt(&v.data), "WKT CRS (record 2112)")
    } else if let Some(v) = projection(34735) {
        (super::units::from_geokeys(&v.data), "GeoTIFF keys (record 34735)")
    } else {
        return Ok(super::CrsUnit::None);
    };
    match found.map_err(|why| ScanError::format(Location::item(path, record), why))? {
        super::CrsUnit::Unstated { crs, heights } => {
            Ok(super::CrsUnit::Unstated { crs: format!("{crs}, in its {record}"), heights })
        }
        unit => Ok(unit),
    }
}

pub(super) fn stream(info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
    let raw = precheck(&info.path)?;
    let mut reader = open(&info.path)?;
    let declared = raw.points;
    let mut data = las::PointDataBuilder::new().for_header(reader.header()).build();
    let has_rgb = reader.header().point_format().has_color;
    let mut chunk = PointCloud::default();
    let mut seen = 0u64;
    loop {
        let place = || Location::item(&info.path, format!("point {seen}"));
        let n = guard_decoder(place, "the LAS/LAZ point reader", || {
            reader.fill_points(CHUNK_POINTS as u64, &mut data).map_err(|e| {
                ScanError::format(
                    place(),
                    format!(
                        "cannot decode points after {seen} of the {declared} the header declares: {e} (truncated or corrupt file)"
                    ),
                )
            })
        })?;
        if n == 0 {
            break;
        }
        chunk.xyz.clear();
        chunk.intensity.clear();
        chunk.rgb.clear();
        chunk.class.clear();
        chunk.scan.clear();
        chunk.xyz.extend(data.x().zip(data.y()).zip(data.z()).map(|((x, y), z)| [x, y, z]));
        chunk.intensity.extend(data.intensity());
        chunk.class.extend(data.classification());
        if has_rgb && let Some(rgb) = data.rgb() {
            chunk.rgb.extend(rgb.map(|(r, g, b)| [r, g, b]));
        }
        check_finite(info, &chunk, seen)?;
        seen += n;
        f(&chunk)?;
    }
    if seen < declared {
        return Err(ScanError::format(
            Location::file(&info.path),
            format!("header declares {declared} points but the data ends after {seen} (truncated file)"),
        ));
    }
    Ok(seen)
}

#[cfg(test)]
mod tests {
    use super::*;
    use liftplan_core::cloud::PointCloud;

    /// A 1000-point LAZ written by liftplan, and where its laszip VLR's
    /// payload starts.
    fn small_laz(dir: &Path) -> (std::path::PathBuf, Vec<u8>, usize) {
        let mut c = PointCloud::default();
        for k in 0..1000 {
            c.xyz.push([k as f64 * 0.01, (k % 37) as f64 * 0.1, (k % 11) as f64 * 0.2]);
            c.intensity.push(k as u16);
        }
        let path = dir.join("a.laz");
        crate::write::write_las(&path, &c).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let user = bytes.windows(14).position(|w| w == b"laszip encoded").expect("a laszip VLR");
        // The user id starts 2 bytes into the 54-byte VLR header.
        (path, bytes, user - 2 + 54)
    }

    /// A file in `fixtures/scans/`.
    fn fixture(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scans").join(name)
    }

    fn damaged(path: &Path, bytes: &[u8], at: usize, value: &[u8]) -> String {
        let mut b = bytes.to_vec();
        b[at..at + value.len()].copy_from_slice(value);
        std::fs::write(path, &b).unwrap();
        let err = list(path, Format::Laz).and_then(|s| super::super::read_all(&s[0]));
        err.expect_err("a damaged file must be refused").to_string()
    }

    #[test]
    fn laz_fields_the_decompressor_trusts_are_checked() {
        let dir = tempfile::tempdir().unwrap();
        let (path, bytes, vlr) = small_laz(dir.path());
        let info = list(&path, Format::Laz).unwrap();
        assert_eq!(super::super::read_all(&info[0]).unwrap().len(), 1000, "the undamaged file reads whole");

        // Items that make a point other than the header's record length
        // (found by the scan_file fuzz target: the decompressor asserted).
        let record = u16::from_le_bytes([bytes[105], bytes[106]]);
        let e = damaged(&path, &bytes, 105, &(record + 1).to_le_bytes());
        assert!(e.contains("a.laz") && e.contains("record length"), "{e}");

        // An item whose size is not its type's.
        let e = damaged(&path, &bytes, vlr + 34 + 2, &(record + 1).to_le_bytes());
        assert!(e.contains("item 0 (type 10) is given as 31 bytes; that type is 30 bytes"), "{e}");

        // A POINT14 item (30 bytes) retyped as RGB14 (6 bytes): the
        // decompressor would read a 6-byte first point and take the next
        // bytes for layer sizes (found by the fuzz target: a 4 GB layer).
        let e = damaged(&path, &bytes, vlr + 34, &11u16.to_le_bytes());
        assert!(e.contains("item 0 (type 11) is given as 30 bytes; that type is 6 bytes"), "{e}");

        // Chunks too large to hold in memory at once.
        let e = damaged(&path, &bytes, vlr + 12, &0x7fff_fff0u32.to_le_bytes());
        assert!(e.contains("MiB") && e.contains(&format!("byte {}", vlr + 12)), "{e}");

        // Chunks too small for the points declared: the one chunk cannot hold them.
        let e = damaged(&path, &bytes, vlr + 12, &100u32.to_le_bytes());
        assert!(e.contains("fewer than the 1000 points"), "{e}");

        let e = damaged(&path, &bytes, vlr + 12, &0u32.to_le_bytes());
        assert!(e.contains("chunk size of 0"), "{e}");

        // A layer of the first chunk stated at 2 GiB (found by the fuzz
        // target: the decompressor allocated it before reading). The chunk
        // opens after the 8-byte table offset with its first point (30 bytes
        // in format 6) and its point count.
        let sizes = u32::from_le_bytes(bytes[96..100].try_into().unwrap()) as usize + 8 + 30 + 4;
        let e = damaged(&path, &bytes, sizes, &0x7fff_ffffu32.to_le_bytes());
        assert!(e.contains("chunk 0's layers") && e.contains(&format!("byte {sizes}")), "{e}");
    }
    /// The fixture's 250 points in variable-size chunks (100, 70, 80, then the
    /// empty one lazrs ends with), as COPC files are chunked.
    fn variable_chunks(dir: &Path) -> (std::path::PathBuf, Vec<u8>) {
        let fixture = fixture("variable-chunks.laz");
        let bytes = std::fs::read(fixture).unwrap();
        let path = dir.join("v.laz");
        std::fs::write(&path, &bytes).unwrap();
        (path, bytes)
    }

    #[test]
    fn variable_size_chunks_read_whole_and_their_counts_are_checked() {
        let dir = tempfile::tempdir().unwrap();
        let (path, bytes) = variable_chunks(dir.path());
        let info = list(&path, Format::Laz).unwrap();
        let c = super::super::read_all(&info[0]).unwrap();
        assert_eq!(c.len(), 250);
        let b = info[0].bbox.unwrap();
        assert!(
            c.xyz.iter().all(|p| (0..3).all(|k| p[k] >= b.min[k] && p[k] <= b.max[k])),
            "points inside the header's box"
        );

        // One point more in the header than in the chunks, in both counts.
        let mut more = bytes.clone();
        more[107..111].copy_from_slice(&251u32.to_le_bytes());
        more[247..255].copy_from_slice(&251u64.to_le_bytes());
        std::fs::write(&path, &more).unwrap();
        let e = list(&path, Format::Laz).unwrap_err().to_string();
        assert!(e.contains("v.laz") && e.contains("hold 250 points, but the header declares 251"), "{e}");

        // The legacy count apart from the LAS 1.4 one.
        let e = damaged(&path, &bytes, 107, &249u32.to_le_bytes());
        assert!(e.contains("byte 247") && e.contains("disagree"), "{e}");
    }
    /// Found by the scan_file fuzz target: a LAZ (LAS 1.4, format 7) whose
    /// compressed points make `laz`'s arithmetic decoder index past its table
    /// and panic. Its structure passes every check, so the panic is caught and
    /// becomes an error naming the file and the point.
    #[test]
    fn a_panic_in_the_decompressor_is_an_error() {
        let path = fixture("damaged-decoder-panic.laz");
        let info = list(&path, Format::Laz).unwrap();
        let e = super::super::read_all(&info[0]).unwrap_err().to_string();
        assert!(
            e.contains("damaged-decoder-panic.laz") && e.contains("point 0") && e.contains("failed on damaged data"),
            "{e}"
        );
    }
    /// Found by the scan_file fuzz target: a chunk table whose
    /// arithmetic-coded counts make the same decoder panic while `precheck`
    /// reads the table.
    #[test]
    fn a_panic_decoding_the_chunk_table_is_an_error() {
        let path = fixture("damaged-chunk-table.laz");
        let e = list(&path, Format::Laz).unwrap_err().to_string();
        assert!(e.contains("damaged-chunk-table.laz at byte") && e.contains("chunk table's decoder failed"), "{e}");
    }
    /// Found by the scan_file fuzz target: a LAZ (format 1) whose GPS times
    /// switch sequence without end. `laz` 0.13.0 recursed once per switch
    /// and overflowed the stack, aborting the process; the patched copy
    /// (third_party/laz) stops after four switches in one point.
    #[test]
    fn gps_times_that_switch_without_end_are_an_error() {
        let path = fixture("damaged-gps-recursion.laz");
        let info = list(&path, Format::Laz).unwrap();
        let e = super::super::read_all(&info[0]).unwrap_err().to_string();
        assert!(e.contains("damaged-gps-recursion.laz") && e.contains("switches sequence more than 4 times"), "{e}");
    }
    /// GPS times taking turns among three sequences (`make_gps_switches.py`):
    /// LASzip switches sequence at nearly every point, once per point, and
    /// the patched decoder reads every point, in formats 1 and 6.
    #[test]
    fn gps_times_that_switch_once_per_point_read_whole() {
        for name in ["gps-switches-1.laz", "gps-switches-6.laz"] {
            let info = list(&fixture(name), Format::Laz).unwrap();
            let c = super::super::read_all(&info[0]).unwrap();
            assert_eq!(c.len(), 600, "{name}");
            for (k, p) in c.xyz.iter().enumerate() {
                assert!((p[0] - k as f64 / 100.0).abs() < 1e-9 && p[1] == 2.0 && p[2] == 0.5, "{name} {k}: {p:?}");
            }
        }
    }

    /// A LAS file with `crs` as its projection record (`record_id`), points
    /// at (100, 200, 10), (110, 200, 12) in its own numbers.
    fn las_with_crs(dir: &Path, name: &str, crs: Option<(u16, Vec<u8>)>) -> std::path::PathBuf {
        let mut b = las::Builder::from((1, 4));
        b.point_format = las::point::Format::new(0).unwrap();
        if let Some((record_id, data)) = crs {
            b.vlrs.push(las::Vlr { user_id: "LASF_Projection".into(), record_id, description: String::new(), data });
        }
        let path = dir.join(name);
        let mut w = las::Writer::from_path(&path, b.into_header().unwrap()).unwrap();
        for (x, z) in [(100.0, 10.0), (110.0, 12.0)] {
            w.write_point(las::Point { x, y: 200.0, z, ..Default::default() }).unwrap();
        }
        w.close().unwrap();
        path
    }

    /// A survey in US survey feet (its GeoTIFF keys say so) is read in
    /// metres; one without a CRS in `[scans] unit`; one whose CRS is in
    /// degrees is refused, naming the file and the record; `inspect` shows
    /// the file's own numbers and the unit it states.
    #[test]
    fn coordinates_are_read_in_metres_whatever_unit_the_file_states() {
        let d = tempfile::tempdir().unwrap();
        let us_ft = 1200.0 / 3937.0;
        let feet = las_with_crs(
            d.path(),
            "ft.las",
            Some((34735, super::super::units::geokeys(&[(1024, 1), (3072, 2263), (3076, 9003)]))),
        );
        for unit in [None, Some(crate::ScanUnit::Metre), Some(crate::ScanUnit::Foot)] {
            let scans = crate::list_all(std::slice::from_ref(&feet), unit).unwrap();
            let c = super::super::read_all(&scans[0]).unwrap();
            assert!(
                (c.xyz[0][0] - 100.0 * us_ft).abs() < 1e-9 && (c.xyz[1][2] - 12.0 * us_ft).abs() < 1e-9,
                "{:?}",
                c.xyz
            );
            let b = scans[0].bbox.unwrap();
            assert!((b.max[0] - 110.0 * us_ft).abs() < 1e-6, "{b:?}");
            assert!(matches!(&scans[0].unit, super::super::CrsUnit::Stated(u) if u.what.contains("US survey foot")));
        }
        let bare = las_with_crs(d.path(), "bare.las", None);
        let c = super::super::read_all(&crate::list_all(std::slice::from_ref(&bare), None).unwrap()[0]).unwrap();
        assert_eq!(c.xyz[0], [100.0, 200.0, 10.0]);
        let c = super::super::read_all(
            &crate::list_all(std::slice::from_ref(&bare), Some(crate::ScanUnit::Foot)).unwrap()[0],
        )
        .unwrap();
        assert!((c.xyz[0][1] - 200.0 * 0.3048).abs() < 1e-9, "{:?}", c.xyz);
        let degrees = br#"GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],UNIT["degree",0.0174532925199433]]"#;
        let geo = las_with_crs(d.path(), "geo.las", Some((2112, degrees.to_vec())));
        let e = crate::list_all(&[geo], Some(crate::ScanUnit::Metre)).unwrap_err().to_string();
        assert!(e.contains("geo.las") && e.contains("record 2112") && e.contains("degrees"), "{e}");
        let shown = crate::inspect(&feet).unwrap().to_string();
        assert!(shown.contains("US survey foot") && shown.contains("110"), "{shown}");
    }

    /// A file whose CRS is only an EPSG code does not state its unit: it is
    /// refused unless `[scans] unit` says it (a State Plane survey in US
    /// feet read as metres puts every obstacle 3.28 times too far), and read
    /// in that unit when it does; a code of a family in metres by definition
    /// (UTM) reads in metres.
    #[test]
    fn a_crs_named_only_by_its_code_needs_the_project_to_say_its_unit() {
        let d = tempfile::tempdir().unwrap();
        let keys = |k: &[(u16, u16)]| Some((34735, super::super::units::geokeys(k)));
        let state_plane = las_with_crs(d.path(), "sp.las", keys(&[(1024, 1), (3072, 2263)]));
        let e = crate::list_all(std::slice::from_ref(&state_plane), None).unwrap_err().to_string();
        assert!(
            e.contains("sp.las") && e.contains("EPSG:2263") && e.contains("record 34735") && e.contains("[scans] unit"),
            "{e}"
        );
        let us_ft = 1200.0 / 3937.0;
        let scans = crate::list_all(std::slice::from_ref(&state_plane), Some(crate::ScanUnit::UsSurveyFoot)).unwrap();
        let c = super::super::read_all(&scans[0]).unwrap();
        assert!((c.xyz[1][0] - 110.0 * us_ft).abs() < 1e-9 && (c.xyz[1][2] - 12.0 * us_ft).abs() < 1e-9, "{:?}", c.xyz);
        let c = super::super::read_all(
            &crate::list_all(std::slice::from_ref(&state_plane), Some(crate::ScanUnit::Metre)).unwrap()[0],
        )
        .unwrap();
        assert_eq!(c.xyz[1], [110.0, 200.0, 12.0]);
        // Heights the file states stay its own.
        let with_heights = las_with_crs(d.path(), "sph.las", keys(&[(1024, 1), (3072, 2263), (4099, 9001)]));
        let c =
            super::super::read_all(&crate::list_all(&[with_heights], Some(crate::ScanUnit::UsSurveyFoot)).unwrap()[0])
                .unwrap();
        assert!((c.xyz[1][0] - 110.0 * us_ft).abs() < 1e-9 && c.xyz[1][2] == 12.0, "{:?}", c.xyz);
        let utm = las_with_crs(d.path(), "utm.las", keys(&[(1024, 1), (3072, 32632)]));
        let c = super::super::read_all(&crate::list_all(&[utm], None).unwrap()[0]).unwrap();
        assert_eq!(c.xyz[1], [110.0, 200.0, 12.0]);
        let shown = crate::inspect(&state_plane).unwrap().to_string();
        assert!(shown.contains("NOT STATED") && shown.contains("EPSG:2263"), "{shown}");
    }

    /// A LAS header's creation date is the scan's date as far as the file
    /// says, marked as the file's, not the survey's; a header without one
    /// (day and year 0, against the standard) has none.
    #[test]
    fn a_las_files_creation_date_is_read_as_such() {
        let d = tempfile::tempdir().unwrap();
        for (name, date) in [("dated.las", chrono::NaiveDate::from_ymd_opt(2026, 10, 2)), ("undated.las", None)] {
            let mut b = las::Builder::from((1, 4));
            b.date = date;
            let path = d.path().join(name);
            let mut w = las::Writer::from_path(&path, b.into_header().unwrap()).unwrap();
            w.write_point(las::Point::default()).unwrap();
            w.close().unwrap();
            let scans = super::super::list_scans(&path).unwrap();
            assert_eq!(scans[0].date, date.map(|date| super::super::ScanDate { date, acquired: false }), "{name}");
        }
        let shown = crate::inspect(&d.path().join("dated.las")).unwrap().to_string();
        assert!(shown.contains("2026-10-02 (file created)"), "{shown}");
    }
}
