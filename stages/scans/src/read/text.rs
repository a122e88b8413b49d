//! PTS and XYZ text exports of common scanner software.
//!
//! * PTS: an optional first line with the point count, then `x y z [intensity [r g b]]`
//!   (Leica Cyclone; intensity -2048..2047 is shifted to 0..4095); a
//!   multi-scan export repeats the count line before each scan. A block that
//!   ends before the count it declares (a file cut short, two spliced) is
//!   refused.
//! * XYZ/TXT/CSV: `x y z [r g b]` or `x y z intensity [r g b]`, separated by spaces,
//!   tabs, commas or semicolons; lines starting with `#` or `//` and a header line
//!   of words are skipped. Where the last of them names the columns (`Point,
//!   Easting, Northing, Height`; CloudCompare's `//X,Y,Z,R,G,B`), the columns
//!   are read as it names them ([`Columns::named`]); one naming coordinates
//!   that cannot be followed is refused. Exporters write intensity as 0..1, 12-bit or 16-bit
//!   values, and the file does not say which: the range of the first chunk's
//!   intensities decides, once for the whole file ([`intensity_scale`]).
//!
//! Lines stream through a buffered reader; a bad line is refused with its number.

use super::{CHUNK_POINTS, Format, ScanInfo, stem};
use crate::error::{Result, ScanError};
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use std::io::{BufRead, BufReader};
use std::path::Path;

/// Whether a file's extension is one that text other than points shares
/// (a report's `.txt`, a table's `.csv`, an `.asc` grid).
pub(super) fn may_be_other_text(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or_default().to_ascii_lowercase();
    matches!(ext.as_str(), "txt" | "csv" | "asc")
}

/// Whether a text file holds a line of three numbers or more (x y z), read
/// up to the first; a line of more than 64 KiB before it (no text point
/// file's) says it holds none.
fn holds_a_line_of_numbers(path: &Path) -> Result<bool> {
    let f = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    let mut r = BufReader::new(f);
    let (mut line, mut vals) = (String::new(), Vec::new());
    loop {
        match r.take_line(&mut line, path) {
            Ok(0) => return Ok(false),
            Ok(_) => {}
            Err(ScanError::Format(..)) => return Ok(false),
            Err(e) => return Err(e),
        }
        let t = line.trim().trim_start_matches(BOM);
        if Separation::of(t).numbers(t, &mut vals) && vals.len() >= 3 {
            return Ok(true);
        }
    }
}

pub(super) fn list(path: &Path, format: Format) -> Result<Vec<ScanInfo>> {
    if format == Format::Xyz && may_be_other_text(path) && !holds_a_line_of_numbers(path)? {
        tracing::warn!("{}: holds no line of numbers (x y z ...): not a scan, passed by", path.display());
        return Ok(Vec::new());
    }
    let f = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    let mut first = String::new();
    BufReader::new(f).take_line(&mut first, path)?;
    // An ESRI ASCII grid (a terrain model's `.asc`, as this program writes
    // its ground): its rows read as lines of points, each a wild point.
    if first.trim_start_matches(BOM).trim_start().get(..5).is_some_and(|w| w.eq_ignore_ascii_case("ncols")) {
        return Err(ScanError::format(
            Location::line(path, 1, None),
            "an ESRI ASCII grid (its first line 'ncols ...'), not a file of points: give the scanned points (the \
             ground is found from them)",
        ));
    }
    let declared = if format == Format::Pts { first.trim().trim_start_matches(BOM).parse::<u64>().ok() } else { None };
    let mut details = serde_json::Map::new();
    details.insert("first_line".into(), serde_json::json!(first.trim_end().chars().take(80).collect::<String>()));
    Ok(vec![ScanInfo {
        path: path.to_path_buf(),
        format,
        index: 0,
        name: stem(path),
        declared_points: declared,
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

pub(super) trait TakeLine {
    fn take_line(&mut self, s: &mut String, path: &Path) -> Result<usize>;
}

impl<R: BufRead> TakeLine for R {
    /// Reads one line, refusing lines over 64 KiB (binary data fed as text).
    fn take_line(&mut self, s: &mut String, path: &Path) -> Result<usize> {
        s.clear();
        let mut buf = Vec::new();
        let n = self
            .by_ref()
            .take(65_536)
            .read_until(b'\n', &mut buf)
            .map_err(|e| ScanError::Io(Location::file(path), e))?;
        if n == 65_536 && buf.last() != Some(&b'\n') {
            return Err(ScanError::format(Location::file(path), "a line is longer than 64 KiB: not a text point file"));
        }
        // Exporters write a header's words in the system's code page (a
        // German "Intensität" in Windows-1252): read as words all the same.
        // Numbers are ASCII, so a line of points is read whatever its bytes
        // outside them, and binary data fails as numbers, at its line.
        *s = match String::from_utf8(buf) {
            Ok(text) => text,
            Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
        };
        Ok(n)
    }
}

use liftplan_core::byte_order_mark::CHAR as BOM;
use std::io::Read as _;

/// How a text file's numbers are separated: decided by its first line of
/// numbers ([`Separation::of`]) and held for the file. A spreadsheet or a
/// scanner's software in a locale that writes decimal commas exports
/// `12,345;6,789;1,234` (or with blanks between): split at every comma, as
/// the reader did, that line read as six numbers, the point 12, 345, 6 with
/// a colour, and the next line alike, without a word.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Separation {
    /// Commas (and blanks) between numbers: `1.5,2.5,3.5`, `1, 2, 3`.
    Commas,
    /// Semicolons between numbers, a comma in one its decimal comma.
    Semicolons,
    /// Blanks (spaces, tabs) between numbers, a comma in one its decimal comma.
    Blanks,
}

impl Separation {
    /// For a line of numbers: semicolons where it holds one; commas where
    /// every piece between its commas is a number; else blanks.
    fn of(t: &str) -> Separation {
        if t.contains(';') {
            Separation::Semicolons
        } else if t.contains(',') && t.split(',').all(|p| p.trim().parse::<f64>().is_ok()) {
            Separation::Commas
        } else {
            Separation::Blanks
        }
    }

    /// The numbers of line `t` into `vals`; false where a field is not one
    /// (a header's words, or a line that does not follow the file's way).
    fn numbers(self, t: &str, vals: &mut Vec<f64>) -> bool {
        vals.clear();
        let split = |c: char| match self {
            Separation::Commas => c.is_whitespace() || c == ',',
            Separation::Semicolons => c == ';',
            Separation::Blanks => c.is_whitespace(),
        };
        for field in t.split(split).map(str::trim).filter(|f| !f.is_empty()) {
            let read = if self != Separation::Commas && field.contains(',') {
                field.replace(',', ".").parse::<f64>()
            } else {
                field.parse::<f64>()
            };
            match read {
                Ok(v) => vals.push(v),
                Err(_) => return false,
            }
        }
        true
    }
}

/// Which column holds what: by the header line's names where it names x, y
/// and z ([`Columns::named`]), else by the count of numbers on a line
/// ([`Columns::by_count`]).
#[derive(Clone, Copy, PartialEq, Debug)]
struct Columns {
    xyz: [usize; 3],
    intensity: Option<usize>,
    rgb: Option<[usize; 3]>,
}

/// What a header's column name says the column holds.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Named {
    Axis(usize),
    Intensity,
    Colour(usize),
}

impl Columns {
    /// By count: 4 = intensity, 6 = rgb, 7 = intensity + rgb.
    fn by_count(count: usize) -> Columns {
        Columns {
            xyz: [0, 1, 2],
            intensity: matches!(count, 4 | 7).then_some(3),
            rgb: match count {
                6 => Some([3, 4, 5]),
                7 => Some([4, 5, 6]),
                _ => None,
            },
        }
    }

    /// What a header's column name says: "X", "Easting", "E [m]",
    /// "Northing", "Elevation", "Intensity", "R", "scalar_Intensity", in any
    /// case; `None` for others (a point's number or name, normals, a class).
    fn name_says(name: &str) -> Option<Named> {
        let name = name.trim().trim_matches(['"', '\'']);
        // "X [m]", "E(m)": the name before its unit.
        let name = name.split(['[', '(']).next().unwrap_or_default().trim();
        let name = name.to_lowercase();
        let name = name.strip_prefix("scalar_").unwrap_or(&name);
        Some(match name {
            "x" | "e" | "east" | "easting" | "eastings" | "rechtswert" => Named::Axis(0),
            "y" | "n" | "north" | "northing" | "northings" | "hochwert" => Named::Axis(1),
            "z" | "h" | "height" | "elevation" | "elev" | "alt" | "altitude" | "höhe" | "hoehe" | "rl" => {
                Named::Axis(2)
            }
            "i" | "intensity" | "reflectance" => Named::Intensity,
            "r" | "red" => Named::Colour(0),
            "g" | "green" => Named::Colour(1),
            "b" | "blue" => Named::Colour(2),
            _ => return None,
        })
    }

    /// By the header line `header`, split as the file's lines of numbers
    /// are, where it names each of x, y and z once: where a survey's export
    /// puts its columns otherwise than x y z first ("Point, Easting,
    /// Northing, Height"; "Northing Easting Elevation"), read by count its
    /// points would be placed wrong, mirrored or shifted, without a word.
    /// Where it names more or fewer columns than the lines hold (`count`),
    /// it is followed only if it puts x, y and z first, as the count does.
    fn named(header: &str, separation: Separation, count: usize) -> HeaderSays {
        let header = header.trim_start_matches(['/', '#']).trim();
        let names: Vec<&str> = header
            .split(|c: char| match separation {
                Separation::Commas => c == ',',
                Separation::Semicolons => c == ';',
                Separation::Blanks => c.is_whitespace(),
            })
            .map(str::trim)
            .filter(|n| !n.is_empty())
            .collect();
        let said: Vec<Option<Named>> = names.iter().map(|n| Columns::name_says(n)).collect();
        let position = |what: Named| {
            let mut at = said.iter().enumerate().filter(|(_, s)| **s == Some(what)).map(|(i, _)| i);
            match (at.next(), at.next()) {
                (Some(i), None) => Ok(Some(i)),
                (None, _) => Ok(None),
                (Some(_), Some(_)) => Err(()),
            }
        };
        let axes = [0, 1, 2].map(|a| position(Named::Axis(a)));
        if axes.iter().all(|a| matches!(a, Ok(None))) {
            return HeaderSays::Nothing;
        }
        let quoted = format!("'{}'", header.chars().take(80).collect::<String>());
        let [Ok(Some(x)), Ok(Some(y)), Ok(Some(z))] = axes else {
            return HeaderSays::NotEachAxis(format!("its header {quoted} does not name each of x, y and z once"));
        };
        if names.len() != count {
            return if [x, y, z] == [0, 1, 2] {
                HeaderSays::Columns(Columns::by_count(count))
            } else {
                HeaderSays::Mismatch(format!(
                    "its header {quoted} names {} columns, x, y and z not first, and its lines hold {count} numbers",
                    names.len()
                ))
            };
        }
        let intensity = position(Named::Intensity).ok().flatten();
        let rgb = match [0, 1, 2].map(|c| position(Named::Colour(c)).ok().flatten()) {
            [Some(r), Some(g), Some(b)] => Some([r, g, b]),
            _ => None,
        };
        HeaderSays::Columns(Columns { xyz: [x, y, z], intensity, rgb })
    }
}

/// What a header line says of the columns ([`Columns::named`]).
#[derive(Debug, PartialEq)]
enum HeaderSays {
    /// It names no coordinate: not a header of columns, or none to follow.
    Nothing,
    Columns(Columns),
    /// It names some coordinates, but not each of x, y and z once.
    NotEachAxis(String),
    /// It names x, y and z, not first, over another count of columns than
    /// the lines hold.
    Mismatch(String),
}

/// The factor that takes an XYZ file's intensities to 0..65535, from the
/// first chunk's: 0..1 (CloudCompare's and many exporters' floats), up to
/// 4095 (12-bit, as PTS after its shift), else 16-bit. Decided once per file:
/// deciding point by point, as the reader did, took an intensity of 1 to
/// 65535 and one of 2 to 32 in the same file.
fn intensity_scale(first: &[f64]) -> f64 {
    let max = first.iter().copied().fold(0.0, f64::max);
    if max <= 1.0 {
        65535.0
    } else if max <= 4095.0 {
        16.0
    } else {
        1.0
    }
}

pub(super) fn stream(info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
    let path = &info.path;
    let file = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    let mut r = BufReader::with_capacity(1 << 20, file);
    let mut line = String::new();
    let mut lineno = 0u64;
    let mut chunk = PointCloud::default();
    let mut seen = 0u64;
    let mut columns: Option<usize> = None;
    // PTS: the current block's count line (points it declares, points read
    // before it, its line). Cyclone writes one per scan of a multi-scan file.
    let mut block: Option<(u64, u64, u64)> = None;
    let pts = info.format == Format::Pts;
    let mut vals: Vec<f64> = Vec::with_capacity(8);
    let mut separation: Option<Separation> = None;
    // The last line before the first line of points that was not one (a
    // header of column names, as a line of words or a `//` comment), and
    // what the columns hold, once the first line of points is read.
    let mut header: Option<(String, u64)> = None;
    let mut layout: Option<Columns> = None;
    // Intensities as read, turned into 0..65535 when their chunk is handed on.
    let mut raw_intensity: Vec<f64> = Vec::new();
    let mut scale: Option<f64> = pts.then_some(16.0);
    let mut hand_on = |chunk: &mut PointCloud, raw: &mut Vec<f64>| -> Result<()> {
        if !raw.is_empty() {
            let scale = *scale.get_or_insert_with(|| intensity_scale(raw));
            chunk.intensity = raw.iter().map(|&i| (i * scale).clamp(0.0, 65535.0) as u16).collect();
            raw.clear();
        }
        f(chunk)
    };
    loop {
        let n = r.take_line(&mut line, path)?;
        if n == 0 {
            break;
        }
        lineno += 1;
        // A byte order mark (a Windows tool's) starts the first line: the
        // point or count there is read.
        let t = line.trim().trim_start_matches(BOM);
        if t.is_empty() {
            continue;
        }
        if t.starts_with('#') || t.starts_with("//") {
            if columns.is_none() {
                header = Some((t.to_string(), lineno));
            }
            continue;
        }
        let ok = match separation {
            Some(s) => s.numbers(t, &mut vals),
            None => {
                // Decided by the first line of three numbers or more (a
                // PTS count line holds one) and held for the file.
                let s = Separation::of(t);
                let ok = s.numbers(t, &mut vals);
                if ok && vals.len() >= 3 {
                    separation = Some(s);
                }
                ok
            }
        };
        if !ok {
            if seen == 0 && columns.is_none() {
                // A header line of column names.
                header = Some((t.to_string(), lineno));
                continue;
            }
            return Err(ScanError::format(
                Location::line(path, lineno, None),
                format!("expected numbers 'x y z ...', found '{}'", t.chars().take(60).collect::<String>()),
            ));
        }
        if pts && vals.len() == 1 {
            let read = seen + chunk.len() as u64;
            block_holds(path, block, read, Some(lineno))?;
            let n = vals[0];
            if !(n >= 0.0 && n.fract() == 0.0 && n < 1e18) {
                return Err(ScanError::format(
                    Location::line(path, lineno, None),
                    format!("expected a point count (a whole number) or 'x y z ...', found '{}'", t),
                ));
            }
            block = Some((n as u64, read, lineno));
            continue;
        }
        if vals.len() < 3 {
            return Err(ScanError::format(
                Location::line(path, lineno, None),
                format!("expected at least 3 numbers (x y z), found {}", vals.len()),
            ));
        }
        match columns {
            None => {
                columns = Some(vals.len());
                // A comment line naming no column of each coordinate is a
                // comment ("# scanned 2026-03-02, heights above datum");
                // a line of words doing so, or any line naming them over
                // another count of columns, is a header that cannot be
                // followed.
                let says = match (&header, separation) {
                    (Some((h, _)), Some(s)) => Columns::named(h, s, vals.len()),
                    _ => HeaderSays::Nothing,
                };
                let header_line = header.as_ref().map_or(0, |h| h.1);
                let commented = header.as_ref().is_some_and(|h| h.0.starts_with(['#', '/']));
                layout = Some(match says {
                    HeaderSays::Columns(named) => {
                        if named.xyz != [0, 1, 2] {
                            tracing::warn!(
                                "{}: x, y and z read from columns {}, {} and {} as its header (line {header_line}) names them",
                                path.display(),
                                named.xyz[0] + 1,
                                named.xyz[1] + 1,
                                named.xyz[2] + 1,
                            );
                        }
                        named
                    }
                    HeaderSays::Nothing => Columns::by_count(vals.len()),
                    HeaderSays::NotEachAxis(_) if commented => Columns::by_count(vals.len()),
                    HeaderSays::NotEachAxis(why) | HeaderSays::Mismatch(why) => {
                        return Err(ScanError::format(
                            Location::line(path, header_line, None),
                            format!(
                                "{why}: which columns hold x, y and z cannot be told (a survey's export may put a point's \
                                 number first, or northing before easting); name them in the header (x, y, z or \
                                 easting, northing, height; one name a column) or leave the header out for x y z first"
                            ),
                        ));
                    }
                });
            }
            Some(c) if c != vals.len() => {
                return Err(ScanError::format(
                    Location::line(path, lineno, None),
                    format!("expected {c} values like the lines before, found {}", vals.len()),
                ));
            }
            _ => {}
        }
        if !layout.is_some_and(|l| l.xyz.iter().all(|&i| vals[i].is_finite())) {
            return Err(ScanError::format(
                Location::line(path, lineno, None),
                format!("coordinate is not a finite number: '{}'", t.chars().take(60).collect::<String>()),
            ));
        }
        let Some(Columns { xyz: [x, y, z], intensity, rgb }) = layout else { continue };
        chunk.xyz.push([vals[x], vals[y], vals[z]]);
        if let Some(i) = intensity {
            raw_intensity.push(if pts { vals[i] + 2048.0 } else { vals[i] });
        }
        if let Some([r, g, b]) = rgb {
            chunk.rgb.push([(vals[r] * 257.0) as u16, (vals[g] * 257.0) as u16, (vals[b] * 257.0) as u16]);
        }
        if chunk.len() >= CHUNK_POINTS {
            seen += chunk.len() as u64;
            hand_on(&mut chunk, &mut raw_intensity)?;
            chunk = PointCloud::default();
        }
    }
    if !chunk.is_empty() {
        seen += chunk.len() as u64;
        hand_on(&mut chunk, &mut raw_intensity)?;
    }
    if seen == 0 {
        return Err(ScanError::format(Location::file(path), "no points found"));
    }
    block_holds(path, block, seen, None)?;
    Ok(seen)
}

/// Whether a PTS block (its count line's (declared, points read before it,
/// line)) holds the points it declares, now that `read` points are read and
/// the next count line (at `next_line`) or the end of the file is reached.
/// Fewer: the file was cut short (a copy or an export that did not finish)
/// or two were spliced, and what it lost may be an obstacle. More: the
/// count is wrong, nothing is missing.
fn block_holds(path: &Path, block: Option<(u64, u64, u64)>, read: u64, next_line: Option<u64>) -> Result<()> {
    let Some((declared, start, line)) = block else { return Ok(()) };
    let held = read - start;
    if held < declared {
        let ends = match next_line {
            Some(n) => format!("the next count line (line {n}) comes after {held} of them"),
            None => format!("the file ends after {held} of them (truncated file)"),
        };
        return Err(ScanError::format(
            Location::line(path, line, None),
            format!("this count line declares {declared} points but {ends}"),
        ));
    }
    if held > declared {
        tracing::warn!("{}:{line}: count line declares {declared} points, {held} follow", path.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::read::{list_scans, read_all};

    /// Writes `text` to `name` in a temporary folder and reads its one scan.
    fn read(name: &str, text: &str) -> Result<liftplan_core::cloud::PointCloud, String> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let scans = list_scans(&path).map_err(|e| e.to_string())?;
        read_all(&scans[0]).map_err(|e| e.to_string())
    }

    /// A survey's report or notes dropped among the scans (`.txt`, `.csv`,
    /// `.asc`: no line of numbers, or empty) is no scan: it lists none (the
    /// run failed: "no points found"). An `.xyz` or `.pts` file is a scan
    /// and is refused so; an ESRI ASCII grid is refused at its first line.
    #[test]
    fn text_that_holds_no_points_is_passed_by_where_its_extension_is_shared() {
        let d = tempfile::tempdir().unwrap();
        let report = "Survey of site A, 2 March 2026\nScanner: RTC360, 12 stations\nRegistered, RMS 3 mm\n";
        let long_line = "x".repeat(70_000);
        for (name, text) in [
            ("readme.txt", report),
            ("notes.csv", "Station;Note\nS1;by the gate\n"),
            ("empty.txt", ""),
            ("one-line.txt", long_line.as_str()),
        ] {
            let path = d.path().join(name);
            std::fs::write(&path, text).unwrap();
            assert!(list_scans(&path).unwrap().is_empty(), "{name}");
        }
        let path = d.path().join("readme.xyz");
        std::fs::write(&path, report).unwrap();
        let e = read_all(&list_scans(&path).unwrap()[0]).unwrap_err().to_string();
        assert!(e.contains("no points found"), "{e}");
        let path = d.path().join("ground.asc");
        std::fs::write(&path, "ncols 3\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1.0 2.0 3.0\n").unwrap();
        let e = list_scans(&path).unwrap_err().to_string();
        assert!(e.contains("ground.asc:1") && e.contains("an ESRI ASCII grid"), "{e}");
    }

    /// A header naming the columns is followed: a survey's export with a
    /// point's number first, or northing before easting, was read by count
    /// (x the point's number, or the site mirrored) without a word. A
    /// header that names some coordinates but not each once, or names
    /// them, not first, over another count of columns, is refused at its
    /// line; comments and headers naming no coordinate change nothing.
    #[test]
    fn columns_are_read_as_the_header_names_them() {
        let xyz = |c: &liftplan_core::cloud::PointCloud| c.xyz.clone();
        let p = read(
            "survey.csv",
            "Point,Easting,Northing,Height\n1,500010.5,5700020.25,101.5\n2,500011.5,5700021.25,102.5\n",
        )
        .unwrap();
        assert_eq!(xyz(&p), [[500010.5, 5700020.25, 101.5], [500011.5, 5700021.25, 102.5]]);
        let p = read("ne.txt", "N E H\n5700020.25 500010.5 101.5\n").unwrap();
        assert_eq!(xyz(&p), [[500010.5, 5700020.25, 101.5]]);
        // CloudCompare's header, as a comment; its colours and intensity
        // where it puts them; names in capitals, with units, quoted.
        let p = read("cc.txt", "//X,Y,Z,R,G,B,Intensity\n1,2,3,255,0,0,0.5\n").unwrap();
        assert_eq!(
            (xyz(&p), p.rgb.clone(), p.intensity.clone()),
            (vec![[1.0, 2.0, 3.0]], vec![[65535, 0, 0]], vec![32767])
        );
        let p = read("units.csv", "\"Y [m]\";\"X [m]\";\"Z [m]\"\n2,0;1,0;3,0\n").unwrap();
        assert_eq!(xyz(&p), [[1.0, 2.0, 3.0]]);
        // x y z first over another count of columns: read by count.
        let p = read("more.xyz", "X Y Z\n1 2 3 0.5\n").unwrap();
        assert_eq!((xyz(&p), p.intensity.len()), (vec![[1.0, 2.0, 3.0]], 1));
        // Comments and words naming no coordinate.
        for text in ["# exported 2026-03-02 by scanner B, heights above datum\n1 2 3\n", "# scan 7\nA B C\n1 2 3\n"] {
            assert_eq!(xyz(&read("c.xyz", text).unwrap()), [[1.0, 2.0, 3.0]], "{text}");
        }
        for (text, why) in [
            ("Latitude Longitude Height\n52.1 13.2 40\n", "does not name each of x, y and z once"),
            ("x y z x\n1 2 3 4\n", "does not name each of x, y and z once"),
            (
                "Point ID Easting Northing Height\n1 500010.5 5700020.25 101.5\n",
                "names 5 columns, x, y and z not first, and its lines hold 4 numbers",
            ),
        ] {
            let e = read("h.xyz", text).unwrap_err();
            assert!(
                e.contains("h.xyz:1") && e.contains(why) && e.contains("which columns hold x, y and z cannot be told"),
                "{text}: {e}"
            );
        }
    }

    /// A PTS file that ends before the points its first line declares is
    /// cut short, and refused; one holding more reads (its count is wrong).
    #[test]
    fn a_pts_file_with_fewer_points_than_declared_is_refused() {
        let e = read("cut.pts", "3\n0 0 0 10\n1 0 0 10\n").unwrap_err();
        assert!(e.contains("cut.pts:1") && e.contains("declares 3 points but the file ends after 2"), "{e}");
        // A multi-scan file (a count line before each scan) reads whole; a
        // short block before the next count line is refused.
        let two = "2\n0 0 0 10\n1 0 0 10\n1\n5 5 5 10\n";
        assert_eq!(read("two.pts", two).unwrap().xyz, [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [5.0, 5.0, 5.0]]);
        let e = read("short.pts", "3\n0 0 0 10\n1 0 0 10\n1\n5 5 5 10\n").unwrap_err();
        assert!(e.contains("short.pts:1") && e.contains("the next count line (line 4) comes after 2"), "{e}");
        let e = read("half.pts", "2.5\n0 0 0 10\n").unwrap_err();
        assert!(e.contains("half.pts:1") && e.contains("expected a point count"), "{e}");
        assert_eq!(read("more.pts", "1\n0 0 0 10\n1 0 0 10\n").unwrap().len(), 2);
        assert_eq!(read("exact.pts", "2\n0 0 0 10\n1 0 0 10\n").unwrap().len(), 2);
    }

    #[test]
    fn a_file_s_intensities_are_scaled_alike() {
        // 8- or 12-bit values: 1 and 2 are one step apart, as in the file
        // (deciding point by point made 1 a full-scale 65535 and 2 a 32).
        let c = read("a.xyz", "X Y Z Intensity\n# exported\n0 0 0 0\n1 0 0 1\n2 0 0 2\n3 0 0 255\n").unwrap();
        assert_eq!(c.intensity, [0, 16, 32, 4080]);
        assert_eq!(c.xyz[3], [3.0, 0.0, 0.0]);
        // 0..1 floats.
        let c = read("b.csv", "0,0,0,0\n1,0,0,0.5\n2,0,0,1\n").unwrap();
        assert_eq!(c.intensity, [0, 32767, 65535]);
        // 16-bit values are kept (they saturated at 65535 before).
        let c = read("c.txt", "0;0;0;0\n1;0;0;1\n2;0;0;60000\n").unwrap();
        assert_eq!(c.intensity, [0, 1, 60000]);
        // Intensity and colour; colour is 8-bit.
        let c = read("d.xyz", "0 0 0 0.25 10 20 30\n").unwrap();
        assert_eq!((c.intensity[0], c.rgb[0]), (16383, [2570, 5140, 7710]));
    }

    /// The first chunk decides for the chunks after it.
    #[test]
    fn the_first_chunk_s_range_holds_for_the_file() {
        let mut text = "0 0 0 200\n".repeat(crate::read::CHUNK_POINTS);
        text += "1 0 0 1\n";
        let c = read("a.xyz", &text).unwrap();
        assert_eq!(
            (c.len(), c.intensity[0], c.intensity[crate::read::CHUNK_POINTS]),
            (crate::read::CHUNK_POINTS + 1, 3200, 16)
        );
    }

    #[test]
    fn pts_files_shift_their_intensities_and_may_count_their_points() {
        let c = read("a.pts", "3\n0 0 0 -2048 1 2 3\n1 0 0 0 1 2 3\n2 0 0 2047 1 2 3\n").unwrap();
        assert_eq!(c.intensity, [0, 32768, 65520]);
        assert_eq!(c.rgb[2], [257, 514, 771]);
        // A count below what the file holds is a warning, not an error (one
        // above it is a file cut short: refused, below).
        assert_eq!(read("b.pts", "1\n0 0 0\n1 1 1\n").unwrap().len(), 2);
    }

    /// A header line in Windows-1252 (not UTF-8) is a header all the same;
    /// bytes that are not text on a line of points are refused at the line.
    #[test]
    fn a_header_in_another_code_page_is_passed_over() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("de.xyz");
        std::fs::write(&path, b"X;Y;Z;Intensit\xe4t\n1;2;3;0.5\n").unwrap();
        let c = read_all(&list_scans(&path).unwrap()[0]).unwrap();
        assert_eq!(c.xyz, [[1.0, 2.0, 3.0]]);
        std::fs::write(&path, b"1 2 3\n4 5 \xff\xfe\n").unwrap();
        let e = read_all(&list_scans(&path).unwrap()[0]).unwrap_err().to_string();
        assert!(e.contains("de.xyz:2") && e.contains("expected numbers"), "{e}");
    }

    /// Decimal commas, with semicolons or blanks between the numbers, are
    /// read as decimals (a German export's "12,345;6,789;1,234" was read as
    /// the six numbers 12, 345, 6, 789, 1, 234: a point 12, 345, 6 with a
    /// colour); commas between numbers with decimal points are separators,
    /// as before; a line that does not follow the file's first is refused.
    #[test]
    fn decimal_commas_are_read_as_decimals() {
        let want = [[12.345, 6.789, 1.234], [13.5, 7.25, 1.0]];
        assert_eq!(read("a.xyz", "12,345;6,789;1,234\n13,5;7,25;1,0\n").unwrap().xyz, want);
        assert_eq!(read("b.txt", "X;Y;Z\n12,345 ; 6,789 ; 1,234\n13,5;7,25;1\n").unwrap().xyz, want);
        assert_eq!(read("c.xyz", "12,345 6,789 1,234\n13,5\t7,25\t1,0\n").unwrap().xyz, want);
        let c = read("d.csv", "12.345,6.789,1.234\n13.5, 7.25, 1\n").unwrap();
        assert_eq!(c.xyz, want);
        let c = read("e.pts", "2\n12,345 6,789 1,234 100\n13,5 7,25 1,0 100\n").unwrap();
        assert_eq!(c.xyz, want);
        let e = read("f.xyz", "12,345;6,789;1,234\n13.5,7.25,1.0\n").unwrap_err();
        assert!(e.contains("f.xyz:2") && e.contains("expected numbers"), "{e}");
    }

    /// A byte order mark at the start (Windows' Notepad, Excel's "CSV UTF-8")
    /// does not cost the first point, nor a PTS file its count.
    #[test]
    fn a_byte_order_mark_is_passed_over() {
        assert_eq!(read("a.xyz", "\u{feff}1 2 3\n4 5 6\n").unwrap().xyz, [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
        let e = read("cut.pts", "\u{feff}3\n0 0 0 10\n1 0 0 10\n").unwrap_err();
        assert!(e.contains("declares 3 points but the file ends after 2"), "{e}");
    }

    #[test]
    fn bad_lines_are_refused_with_their_number() {
        let e = read("a.xyz", "0 0 0\n1 1 1\nx y z\n").unwrap_err();
        assert!(e.contains("a.xyz:3") && e.contains("expected numbers 'x y z ...', found 'x y z'"), "{e}");
        let e = read("b.xyz", "# header\n0 0 0\n1 1 1 7\n").unwrap_err();
        assert!(e.contains("b.xyz:3") && e.contains("expected 3 values like the lines before, found 4"), "{e}");
        let e = read("c.xyz", "0 0\n").unwrap_err();
        assert!(e.contains("c.xyz:1") && e.contains("at least 3 numbers"), "{e}");
        let e = read("d.xyz", "0 0 0\n1 NaN 1\n").unwrap_err();
        assert!(e.contains("d.xyz:2") && e.contains("not a finite number"), "{e}");
        let e = read("e.xyz", "# nothing here\n\n").unwrap_err();
        assert!(e.contains("no points found"), "{e}");
        let e = read("f.xyz", &"1".repeat(70_000)).unwrap_err();
        assert!(e.contains("longer than 64 KiB"), "{e}");
    }
}
