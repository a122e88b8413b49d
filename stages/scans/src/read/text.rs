//! PTS and XYZ text exports of common scanner software.
//!
//! * PTS: an optional first line with the point count, then `x y z [intensity [r g b]]`
//!   (Leica Cyclone; intensity -2048..2047 is shifted to 0..4095).
//! * XYZ/TXT/CSV: `x y z [r g b]` or `x y z intensity [r g b]`, separated by spaces,
//!   tabs, commas or semicolons; lines starting with `#` or `//` and a header line
//!   of words are skipped.
//!
//! Lines stream through a buffered reader; a bad line is refused with its number.

use super::{CHUNK_POINTS, Format, ScanInfo, stem};
use crate::error::{Result, ScanError};
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use std::io::{BufRead, BufReader};
use std::path::Path;

pub(super) fn list(path: &Path, format: Format) -> Result<Vec<ScanInfo>> {
    let f = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    let mut first = String::new();
    BufReader::new(f).take_line(&mut first, path)?;
    let declared = if format == Format::Pts { first.trim().parse::<u64>().ok() } else { None };
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
    }])
}

trait TakeLine {
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
        *s = String::from_utf8(buf).map_err(|_| ScanError::format(Location::file(path), "not UTF-8 text"))?;
        Ok(n)
    }
}

use std::io::Read as _;

pub(super) fn stream(info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
    let path = &info.path;
    let file = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    let mut r = BufReader::with_capacity(1 << 20, file);
    let mut line = String::new();
    let mut lineno = 0u64;
    let mut chunk = PointCloud::default();
    let mut seen = 0u64;
    let mut columns: Option<usize> = None;
    let mut declared: Option<u64> = None;
    let pts = info.format == Format::Pts;
    let mut vals: Vec<f64> = Vec::with_capacity(8);
    loop {
        let n = r.take_line(&mut line, path)?;
        if n == 0 {
            break;
        }
        lineno += 1;
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') || t.starts_with("//") {
            continue;
        }
        vals.clear();
        let mut ok = true;
        for tok in t.split(|c: char| c.is_whitespace() || c == ',' || c == ';').filter(|s| !s.is_empty()) {
            match tok.parse::<f64>() {
                Ok(v) => vals.push(v),
                Err(_) => {
                    ok = false;
                    break;
                }
            }
        }
        if !ok {
            if seen == 0 && columns.is_none() {
                continue; // a header line of column names
            }
            return Err(ScanError::format(
                Location::line(path, lineno, None),
                format!("expected numbers 'x y z ...', found '{}'", t.chars().take(60).collect::<String>()),
            ));
        }
        if pts && seen == 0 && columns.is_none() && vals.len() == 1 {
            declared = Some(vals[0] as u64);
            continue;
        }
        if vals.len() < 3 {
            return Err(ScanError::format(
                Location::line(path, lineno, None),
                format!("expected at least 3 numbers (x y z), found {}", vals.len()),
            ));
        }
        match columns {
            None => columns = Some(vals.len()),
            Some(c) if c != vals.len() => {
                return Err(ScanError::format(
                    Location::line(path, lineno, None),
                    format!("expected {c} values like the lines before, found {}", vals.len()),
                ));
            }
            _ => {}
        }
        if !vals[..3].iter().all(|v| v.is_finite()) {
            return Err(ScanError::format(
                Location::line(path, lineno, None),
                format!("coordinate is not a finite number: '{}'", t.chars().take(60).collect::<String>()),
            ));
        }
        let c = vals.len();
        chunk.xyz.push([vals[0], vals[1], vals[2]]);
        // Column meaning by count: 4 = intensity, 6 = rgb, 7 = intensity + rgb.
        match c {
            4 | 7 => {
                let i = if pts { vals[3] + 2048.0 } else { vals[3] };
                chunk
                    .intensity
                    .push((if i <= 1.0 && !pts { i * 65535.0 } else { i * 16.0 }).clamp(0.0, 65535.0) as u16);
                if c == 7 {
                    chunk.rgb.push([(vals[4] * 257.0) as u16, (vals[5] * 257.0) as u16, (vals[6] * 257.0) as u16]);
                }
            }
            6 => chunk.rgb.push([(vals[3] * 257.0) as u16, (vals[4] * 257.0) as u16, (vals[5] * 257.0) as u16]),
            _ => {}
        }
        if chunk.len() >= CHUNK_POINTS {
            seen += chunk.len() as u64;
            f(&chunk)?;
            chunk = PointCloud::default();
        }
    }
    if !chunk.is_empty() {
        seen += chunk.len() as u64;
        f(&chunk)?;
    }
    if seen == 0 {
        return Err(ScanError::format(Location::file(path), "no points found"));
    }
    if let Some(d) = declared
        && d != seen
    {
        tracing::warn!("{}: first line declares {d} points, file holds {seen}", path.display());
    }
    Ok(seen)
}
