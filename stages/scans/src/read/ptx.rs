//! Leica PTX, the text export of Cyclone, Register 360 and FARO Scene: one
//! or more scans one after another, each a header of ten lines and then one
//! line per cell of the scanner's grid.
//!
//! ```text
//! columns
//! rows
//! st1 st2 st3          scanner's position, registered
//! sx1 sx2 sx3          scanner's axes, registered
//! sy1 sy2 sy3
//! sz1 sz2 sz3
//! r11 r12 r13 0        4 x 4 transform, applied to a point as a row vector:
//! r21 r22 r23 0        [x y z 1] times it is the point registered
//! r31 r32 r33 0
//! tr1 tr2 tr3 1
//! x y z intensity [r g b]     columns x rows lines, in the scanner's frame
//! ```
//!
//! Points come out in the scanner's own frame, as the file holds them, and
//! the transform is the scan's [`ScanInfo::pose`], which registration takes as
//! its start (as an E57 scan's stored pose): it is never applied silently.
//! A cell the scanner got no return for is written `0 0 0`, and left out.
//! Intensity is 0..1; colour 0..255.
//!
//! The header gives no scan's length in bytes, so listing the scans reads the
//! whole file once, counting lines (the points are not parsed), and keeps
//! where each scan's points start; a file that ends before a scan's
//! `columns x rows` lines is refused then, as a copy still in progress or an
//! export that did not finish. The scanner's position and axes (lines 3 to
//! 6) are shown by `liftplan inspect`, not used: they are the registered
//! pose in the registration's own frame, which the transform equals unless
//! the export was made in another coordinate system (Cyclone's UCS).

use super::text::TakeLine;
use super::{CHUNK_POINTS, Format, ScanInfo};
use crate::error::{Result, ScanError};
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use liftplan_core::frame::Pose;
use nalgebra as na;
use serde_json::json;
use std::io::{BufRead, BufReader, Seek, SeekFrom};
use std::path::Path;

/// The most columns or rows a scan's grid may declare: a scanner's finest
/// grid is tens of thousands a side; a count beyond this is not a PTX
/// header.
const MOST_PER_SIDE: u64 = 1_000_000;

/// The most scans one file may hold: the scans stage takes at most this many
/// in all (a point's scan is a 16-bit number), and a survey has hundreds;
/// each scan listed is kept in memory with its details.
const MOST_SCANS: usize = u16::MAX as usize;

/// How far the transform's 3 x 3 part may be from a rotation (largest
/// entry of RᵀR - I): exporters print six decimals, which leave it 1e-6
/// off; a scale or a shear (a coordinate system in millimetres) is further
/// than this, and would distort the scan.
const ROTATION_TOLERANCE: f64 = 1e-3;

/// One scan's header.
struct Header {
    columns: u64,
    rows: u64,
    scanner: [[f64; 3]; 4],
    pose: Pose,
}

/// Reads lines, counting them and the bytes they take.
struct Lines<R: BufRead> {
    r: R,
    path: std::path::PathBuf,
    line: String,
    /// Lines read so far (the number of the last one read).
    lineno: u64,
    /// Bytes read so far.
    offset: u64,
}

impl<R: BufRead> Lines<R> {
    /// Reads the next line into `line`; false at the end of the file.
    fn advance(&mut self) -> Result<bool> {
        let n = self.r.take_line(&mut self.line, &self.path)?;
        if n == 0 {
            return Ok(false);
        }
        self.lineno += 1;
        self.offset += n as u64;
        Ok(true)
    }

    fn here(&self) -> Location {
        Location::line(&self.path, self.lineno, None)
    }

    /// The next line as exactly `N` numbers, `what` naming it in the error.
    fn numbers<const N: usize>(&mut self, what: &str) -> Result<[f64; N]> {
        if !self.advance()? {
            return Err(ScanError::format(
                Location::line(&self.path, self.lineno + 1, None),
                format!("the file ends inside a scan's header, where {what} belongs (truncated file)"),
            ));
        }
        // A byte order mark, where a Windows tool wrote one, starts the file.
        let text = self.line.trim().trim_start_matches(liftplan_core::byte_order_mark::CHAR);
        let shown: String = text.chars().take(60).collect();
        let vals: Vec<f64> = text.split_whitespace().map_while(|t| t.parse::<f64>().ok()).collect();
        if vals.len() != N || text.split_whitespace().count() != N || !vals.iter().all(|v| v.is_finite()) {
            return Err(ScanError::format(self.here(), format!("expected {what}: {N} numbers, found '{shown}'")));
        }
        let mut out = [0.0; N];
        out.copy_from_slice(&vals);
        Ok(out)
    }

    /// A header's first lines: the grid's columns or rows.
    fn count(&mut self, what: &str) -> Result<u64> {
        let [n] = self.numbers::<1>(what)?;
        if !(n >= 1.0 && n.fract() == 0.0 && n <= MOST_PER_SIDE as f64) {
            return Err(ScanError::format(
                self.here(),
                format!("expected {what}: a whole number from 1 to {MOST_PER_SIDE}, found {n}"),
            ));
        }
        Ok(n as u64)
    }

    /// The next scan's header, or `None` where the file has nothing more
    /// (blank lines at its end).
    fn header(&mut self) -> Result<Option<Header>> {
        // The first line, blank lines before it passed over (a file's last
        // line break written twice).
        loop {
            let buf = self.r.fill_buf().map_err(|e| ScanError::Io(Location::file(&self.path), e))?;
            match buf.first() {
                None => return Ok(None),
                Some(b) if b.is_ascii_whitespace() => {
                    if *b == b'\n' {
                        self.lineno += 1;
                    }
                    self.r.consume(1);
                    self.offset += 1;
                }
                Some(_) => break,
            }
        }
        let columns = self.count("the number of columns of the scan's grid")?;
        let rows = self.count("the number of rows of the scan's grid")?;
        let mut scanner = [[0.0; 3]; 4];
        for (k, s) in scanner.iter_mut().enumerate() {
            *s = self.numbers::<3>(["the scanner's position", "its X axis", "its Y axis", "its Z axis"][k])?;
        }
        let mut m = [[0.0; 4]; 4];
        for (k, row) in m.iter_mut().enumerate() {
            *row = self.numbers::<4>(&format!("row {} of the 4 x 4 transform", k + 1))?;
            let want = if k == 3 { 1.0 } else { 0.0 };
            if (row[3] - want).abs() > 1e-9 {
                return Err(ScanError::format(
                    self.here(),
                    format!(
                        "row {} of the 4 x 4 transform ends in {}, not {want}: not a rigid transform",
                        k + 1,
                        row[3]
                    ),
                ));
            }
        }
        // Applied to a row vector: the rotation's columns are the rows written.
        let r = na::Matrix3::from_fn(|i, j| m[j][i]);
        let off = (r.transpose() * r - na::Matrix3::identity()).abs().max();
        if off > ROTATION_TOLERANCE || r.determinant() <= 0.0 {
            return Err(ScanError::format(
                self.here(),
                format!(
                    "the 4 x 4 transform's first three rows are not a rotation (off by {off:.2e}, determinant {:.4}): \
                     a scale, a shear or a mirror would distort the scan; export it in metres without one",
                    r.determinant()
                ),
            ));
        }
        // The transform as a column vector takes it: the matrix transposed.
        let pose = liftplan_core::frame::pose_from_rows(&std::array::from_fn(|i| std::array::from_fn(|j| m[j][i])));
        Ok(Some(Header { columns, rows, scanner, pose }))
    }

    /// Passes over `count` lines without parsing them; the lines passed
    /// over, fewer where the file ends first.
    fn skip(&mut self, count: u64) -> Result<u64> {
        let mut passed = 0;
        // Bytes of a line begun but not ended in what was read so far.
        let mut open = false;
        while passed < count {
            let buf = self.r.fill_buf().map_err(|e| ScanError::Io(Location::file(&self.path), e))?;
            if buf.is_empty() {
                // A last line without its line break counts.
                if open {
                    passed += 1;
                    self.lineno += 1;
                }
                break;
            }
            let mut used = buf.len();
            for (i, &b) in buf.iter().enumerate() {
                if b == b'\n' {
                    passed += 1;
                    self.lineno += 1;
                    open = false;
                    if passed == count {
                        used = i + 1;
                        break;
                    }
                } else {
                    open = true;
                }
            }
            self.r.consume(used);
            self.offset += used as u64;
        }
        Ok(passed)
    }
}

fn open(path: &Path) -> Result<Lines<BufReader<std::fs::File>>> {
    let file = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    Ok(Lines {
        r: BufReader::with_capacity(1 << 20, file),
        path: path.into(),
        line: String::new(),
        lineno: 0,
        offset: 0,
    })
}

pub(super) fn list(path: &Path) -> Result<Vec<ScanInfo>> {
    let mut lines = open(path)?;
    let mut found: Vec<(Header, u64, u64)> = Vec::new();
    while let Some(h) = lines.header()? {
        if found.len() == MOST_SCANS {
            return Err(ScanError::format(
                Location::line(path, lines.lineno - 9, None),
                format!("the file holds more than {MOST_SCANS} scans, more than liftplan takes"),
            ));
        }
        let first_line = lines.lineno + 1;
        let at = lines.offset;
        let count = h.columns * h.rows;
        let passed = lines.skip(count)?;
        if passed < count {
            return Err(ScanError::format(
                Location::line(path, first_line - 10, None),
                format!(
                    "this scan's header declares {} x {} = {count} points, but the file ends after {passed} of them \
                     (truncated file, or a copy still in progress)",
                    h.columns, h.rows
                ),
            ));
        }
        found.push((h, at, first_line));
    }
    if found.is_empty() {
        return Err(ScanError::format(Location::file(path), "the file holds no scan (no PTX header)"));
    }
    let stem = super::stem(path);
    let several = found.len() > 1;
    Ok(found
        .into_iter()
        .enumerate()
        .map(|(i, (h, at, first_line))| {
            let mut details = serde_json::Map::new();
            details.insert("columns".into(), json!(h.columns));
            details.insert("rows".into(), json!(h.rows));
            details.insert("first_point_line".into(), json!(first_line));
            details.insert("scanner_position".into(), json!(h.scanner[0]));
            details.insert("scanner_axes".into(), json!(&h.scanner[1..]));
            ScanInfo {
                path: path.to_path_buf(),
                format: Format::Ptx,
                index: i,
                name: if several { format!("{stem}#{i}") } else { stem.clone() },
                declared_points: Some(h.columns * h.rows),
                pose: Some(h.pose),
                bbox: None,
                details,
                unit: super::CrsUnit::None,
                date: None,
                to_m: [1.0; 3],
                read_in: String::new(),
                points_at: Some((at, first_line)),
            }
        })
        .collect())
}

pub(super) fn stream(info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
    let path = &info.path;
    let (Some((at, first_line)), Some(count)) = (info.points_at, info.declared_points) else {
        return Err(ScanError::format(Location::item(path, &info.name), "not listed as a PTX scan"));
    };
    let mut lines = open(path)?;
    lines.r.seek(SeekFrom::Start(at)).map_err(|e| ScanError::Io(Location::file(path), e))?;
    lines.lineno = first_line - 1;
    let mut chunk = PointCloud::default();
    let mut delivered = 0u64;
    let mut columns: Option<usize> = None;
    let mut vals: Vec<f64> = Vec::with_capacity(8);
    for k in 0..count {
        if !lines.advance()? {
            return Err(ScanError::format(
                Location::line(path, lines.lineno + 1, None),
                format!(
                    "{}: the file ends after {k} of the scan's {count} points (it changed since it was listed)",
                    info.name
                ),
            ));
        }
        let text = lines.line.trim();
        vals.clear();
        vals.extend(text.split_whitespace().map_while(|t| t.parse::<f64>().ok()));
        let shown = || text.chars().take(60).collect::<String>();
        let all_numbers = vals.len() == text.split_whitespace().count();
        if !all_numbers || !(vals.len() == 4 || vals.len() == 7) {
            return Err(ScanError::format(
                lines.here(),
                format!("expected a point 'x y z intensity' or 'x y z intensity r g b', found '{}'", shown()),
            ));
        }
        match columns {
            None => columns = Some(vals.len()),
            Some(c) if c != vals.len() => {
                return Err(ScanError::format(
                    lines.here(),
                    format!("expected {c} values like the scan's points before, found {}", vals.len()),
                ));
            }
            _ => {}
        }
        if !vals.iter().all(|v| v.is_finite()) {
            return Err(ScanError::format(lines.here(), format!("a value is not a finite number: '{}'", shown())));
        }
        if vals[..3] == [0.0; 3] {
            continue; // no return for this cell of the grid
        }
        chunk.xyz.push([vals[0], vals[1], vals[2]]);
        chunk.intensity.push((vals[3] * 65535.0).clamp(0.0, 65535.0) as u16);
        if vals.len() == 7 {
            let c = |v: f64| (v.clamp(0.0, 255.0) * 257.0) as u16;
            chunk.rgb.push([c(vals[4]), c(vals[5]), c(vals[6])]);
        }
        if chunk.len() >= CHUNK_POINTS {
            delivered += chunk.len() as u64;
            f(&chunk)?;
            chunk = PointCloud::default();
        }
    }
    if !chunk.is_empty() {
        delivered += chunk.len() as u64;
        f(&chunk)?;
    }
    if delivered == 0 {
        return Err(ScanError::format(
            Location::item(path, &info.name),
            format!("no points: each of the scan's {count} cells is 0 0 0 (no return)"),
        ));
    }
    Ok(delivered)
}

#[cfg(test)]
mod tests {
    use crate::read::{ScanStreamer, list_scans, read_all};
    use liftplan_core::frame::Pose;
    use nalgebra as na;

    const IDENTITY: &str = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";

    /// A header for a scan of `columns` x `rows` at `pose` (its transform
    /// written as PTX writes it, and its position and axes the same).
    fn header(columns: u64, rows: u64, pose: &Pose) -> String {
        let r = pose.rotation.to_rotation_matrix();
        let t = pose.translation.vector;
        let mut s = format!("{columns}\n{rows}\n{} {} {}\n", t.x, t.y, t.z);
        for j in 0..3 {
            s += &format!("{} {} {}\n", r[(0, j)], r[(1, j)], r[(2, j)]);
        }
        for j in 0..3 {
            s += &format!("{} {} {} 0\n", r[(0, j)], r[(1, j)], r[(2, j)]);
        }
        s + &format!("{} {} {} 1\n", t.x, t.y, t.z)
    }

    fn write(name: &str, text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        (dir, path)
    }

    /// Two scans in one file: each listed with its grid, pose and name,
    /// read in its own frame with the no-return cells left out; the pose
    /// read back is the one written (row-vector convention), and a point
    /// moved by it lands where [x y z 1] times the matrix puts it.
    #[test]
    fn scans_are_listed_with_their_poses_and_read_in_their_own_frames() {
        let pose = Pose::from_parts(
            na::Translation3::new(558312.218127, 5240857.469093, 76.298415),
            na::UnitQuaternion::from_euler_angles(0.001, -0.002, 0.7),
        );
        let mut text = header(2, 2, &pose);
        text += "1 2 3 0.5 10 20 30\n0 0 0 0.5 0 0 0\n-4 5.5 6 1 255 0 0\n7 8 9 0 0 0 0\n";
        text += &header(1, 3, &Pose::identity());
        text += "1 1 1 0.25\n2 2 2 0.25\n3 3 3 0.25\n\n";
        let (_dir, path) = write("site.ptx", &text);
        let scans = list_scans(&path).unwrap();
        assert_eq!(scans.len(), 2);
        assert_eq!((scans[0].name.as_str(), scans[1].name.as_str()), ("site#0", "site#1"));
        assert_eq!((scans[0].declared_points, scans[1].declared_points), (Some(4), Some(3)));
        let read = scans[0].pose.unwrap();
        assert!((read.translation.vector - pose.translation.vector).norm() < 1e-9);
        assert!(read.rotation.angle_to(&pose.rotation) < 1e-9);
        // [x y z 1] times the matrix as written, by hand, for the first point.
        let r = pose.rotation.to_rotation_matrix();
        let rows: Vec<[f64; 3]> = (0..3).map(|j| [r[(0, j)], r[(1, j)], r[(2, j)]]).collect();
        let p = [1.0, 2.0, 3.0];
        let by_hand: Vec<f64> = (0..3).map(|k| p[0] * rows[0][k] + p[1] * rows[1][k] + p[2] * rows[2][k]).collect();
        let moved = read * na::Point3::new(1.0, 2.0, 3.0);
        let t = pose.translation.vector;
        for k in 0..3 {
            assert!((moved[k] - (by_hand[k] + t[k])).abs() < 1e-6, "{k}: {moved} {by_hand:?}");
        }
        let mut streamer = ScanStreamer::default();
        let mut first = liftplan_core::cloud::PointCloud::default();
        streamer
            .stream(&scans[0], &mut |c| {
                first.append(c);
                Ok(())
            })
            .unwrap();
        assert_eq!(first.xyz, [[1.0, 2.0, 3.0], [-4.0, 5.5, 6.0], [7.0, 8.0, 9.0]]);
        assert_eq!(first.intensity, [32767, 65535, 0]);
        assert_eq!(first.rgb[1], [65535, 0, 0]);
        let second = read_all(&scans[1]).unwrap();
        assert_eq!(second.xyz, [[1.0, 1.0, 1.0], [2.0, 2.0, 2.0], [3.0, 3.0, 3.0]]);
        // One scan alone is named by its file.
        let (_d, one) = write("station-7.PTX", &format!("{}{}", header(1, 1, &Pose::identity()), "1 2 3 0.5\n"));
        assert_eq!(list_scans(&one).unwrap()[0].name, "station-7");
    }

    /// What a file cut short, a header that is not one, a transform that
    /// is not rigid and a bad point say: the file, the line, what was
    /// expected.
    #[test]
    fn bad_files_are_refused_naming_the_line() {
        let err = |name: &str, text: &str| -> String {
            let (_d, path) = write(name, text);
            match list_scans(&path) {
                Err(e) => e.to_string(),
                Ok(scans) => {
                    read_all(&scans[0]).map(|c| format!("read {} points", c.len())).unwrap_or_else(|e| e.to_string())
                }
            }
        };
        let e = err("cut.ptx", &format!("2\n2\n{IDENTITY}1 1 1 0.5\n2 2 2 0.5\n3 3 3 0.5"));
        assert!(e.contains("cut.ptx:1") && e.contains("declares 2 x 2 = 4 points, but the file ends after 3"), "{e}");
        let e = err("head.ptx", "2\n2\n0 0 0\n1 0 0\n");
        assert!(e.contains("head.ptx:5") && e.contains("the file ends inside a scan's header"), "{e}");
        let e = err("cols.ptx", &format!("2.5\n2\n{IDENTITY}"));
        assert!(e.contains("cols.ptx:1") && e.contains("a whole number from 1"), "{e}");
        let e = err("huge.ptx", &format!("100000000\n100000000\n{IDENTITY}"));
        assert!(e.contains("huge.ptx:1") && e.contains("a whole number from 1 to 1000000"), "{e}");
        let scaled = IDENTITY.replace("1 0 0 0\n0 1 0 0\n0 0 1 0", "1000 0 0 0\n0 1000 0 0\n0 0 1000 0");
        let e = err("mm.ptx", &format!("1\n1\n{scaled}1 1 1 0.5\n"));
        assert!(e.contains("mm.ptx:10") && e.contains("not a rotation"), "{e}");
        let mirror = IDENTITY.replace("0 0 1 0\n", "0 0 -1 0\n");
        assert!(err("mirror.ptx", &format!("1\n1\n{mirror}1 1 1 0.5\n")).contains("not a rotation"));
        let sheared = IDENTITY.replace("0 0 0 1\n", "0 0 0 2\n");
        let e = err("w.ptx", &format!("1\n1\n{sheared}1 1 1 0.5\n"));
        assert!(e.contains("w.ptx:10") && e.contains("ends in 2, not 1"), "{e}");
        let e = err("axis.ptx", "1\n1\n0 0 0\n1 0\n");
        assert!(e.contains("axis.ptx:4") && e.contains("expected its X axis: 3 numbers, found '1 0'"), "{e}");
        let e = err("pt.ptx", &format!("1\n2\n{IDENTITY}1 1 1 0.5\n1 1 1\n"));
        assert!(e.contains("pt.ptx:12") && e.contains("expected a point 'x y z intensity'"), "{e}");
        let e = err("mixed.ptx", &format!("1\n2\n{IDENTITY}1 1 1 0.5\n1 1 1 0.5 1 2 3\n"));
        assert!(e.contains("mixed.ptx:12") && e.contains("expected 4 values"), "{e}");
        let e = err("nan.ptx", &format!("1\n1\n{IDENTITY}1 NaN 1 0.5\n"));
        assert!(e.contains("nan.ptx:11") && e.contains("not a finite number"), "{e}");
        let e = err("none.ptx", &format!("1\n2\n{IDENTITY}0 0 0 0.5\n0 0 0 0.5\n"));
        assert!(e.contains("none.ptx") && e.contains("each of the scan's 2 cells is 0 0 0"), "{e}");
        assert!(err("empty.ptx", "\n\n").contains("holds no scan"));
        // A second scan cut short is refused at its own header's line.
        let two = format!("1\n1\n{IDENTITY}1 1 1 0.5\n1\n2\n{IDENTITY}1 1 1 0.5\n");
        let e = err("two.ptx", &two);
        assert!(e.contains("two.ptx:12") && e.contains("ends after 1 of them"), "{e}");
        // A file of more scans than the stage takes is refused at the first
        // scan past them, before its listing grows further.
        let one = format!("1\n1\n{IDENTITY}1 1 1 0.5\n");
        let e = err("many.ptx", &one.repeat(65_536));
        assert!(e.contains(&format!("many.ptx:{}", 65_535 * 11 + 1)) && e.contains("more than 65535 scans"), "{e}");
        // Windows line breaks, and a byte order mark, read as well.
        assert_eq!(err("bom.ptx", &format!("\u{feff}1\n1\n{IDENTITY}1 1 1 0.5\n")), "read 1 points");
        assert_eq!(err("crlf.ptx", &format!("1\n1\n{IDENTITY}1 1 1 0.5\n").replace('\n', "\r\n")), "read 1 points");
    }
}
