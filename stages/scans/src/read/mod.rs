//! Scan readers. Each format lists the scans a file holds from its header alone
//! ([`list_scans`], cheap, for `liftplan inspect`; a PTX file, whose scans
//! follow one another with no index, by counting its lines) and streams their points in
//! chunks ([`stream`]) so no reader ever holds a whole survey in memory.
//!
//! Points come out in the file's own frame; a pose the file carries (E57, PTX) is
//! returned in [`ScanInfo::pose`] and applied by registration, never silently.
//! Readers refuse non-finite coordinates and counts the file cannot hold, naming
//! the file and the place.

mod e57;
mod las;
mod ply;
mod ptx;
mod text;
pub mod units;

use crate::error::{Result, ScanError};
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use liftplan_core::frame::{Aabb, Pose};
use std::path::{Path, PathBuf};

pub use las::precheck as las_precheck;
pub use units::{CrsUnit, StatedUnit};

#[cfg(test)]
thread_local! {
    /// E57 files opened for streaming on this thread, for the tests that
    /// check a file is opened once per pass over its scans.
    pub(crate) static E57_OPENS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Points per chunk handed to a stream callback.
pub const CHUNK_POINTS: usize = 500_000;

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    Las,
    Laz,
    Ply,
    E57,
    Pts,
    Xyz,
    Ptx,
}

impl Format {
    /// Format from a file extension (case-insensitive); `None` if not a scan.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "las" => Format::Las,
            "laz" => Format::Laz,
            "ply" => Format::Ply,
            "e57" => Format::E57,
            "pts" => Format::Pts,
            "xyz" | "txt" | "asc" | "csv" => Format::Xyz,
            "ptx" => Format::Ptx,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            Format::Las => "las",
            Format::Laz => "laz",
            Format::Ply => "ply",
            Format::E57 => "e57",
            Format::Pts => "pts",
            Format::Xyz => "xyz",
            Format::Ptx => "ptx",
        }
    }
}

/// A date a scan file gives: when the scan was taken (E57's acquisition
/// start) or only when the file was written (a LAS header's creation date,
/// which may be the export's, not the survey's).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct ScanDate {
    pub date: chrono::NaiveDate,
    pub acquired: bool,
}

/// As its display: "2026-10-02 (acquired)".
impl serde::Serialize for ScanDate {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl std::fmt::Display for ScanDate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({})", self.date, if self.acquired { "acquired" } else { "file created" })
    }
}

impl ScanDate {
    /// The date of a GPS time (seconds since 1980-01-06 00:00 UTC, leap
    /// seconds aside: a few seconds cannot move a survey's date much), if it
    /// is a time a scan could have been taken at (1980 to 2200).
    pub fn from_gps_seconds(s: f64) -> Option<ScanDate> {
        if !(s.is_finite() && (0.0..=7.0e9).contains(&s)) {
            return None;
        }
        let epoch = chrono::NaiveDate::from_ymd_opt(1980, 1, 6)?;
        let date = epoch.checked_add_days(chrono::Days::new((s / 86_400.0).floor() as u64))?;
        Some(ScanDate { date, acquired: true })
    }
}

/// One scan inside a file, as its header describes it.
#[derive(Debug, Clone)]
pub struct ScanInfo {
    pub path: PathBuf,
    pub format: Format,
    /// Index of the scan within the file (E57 holds several).
    pub index: usize,
    pub name: String,
    /// Point count the header declares, if it declares one.
    pub declared_points: Option<u64>,
    /// Pose from the scan's frame to the file's common frame, if the file has one.
    pub pose: Option<Pose>,
    /// Bounding box from the header, if it has one (in the scan's own frame).
    pub bbox: Option<Aabb>,
    /// Format details for `inspect` (version, point format, scale, properties...).
    pub details: serde_json::Map<String, serde_json::Value>,
    /// What the file states of its coordinates' unit ([`units`]).
    pub unit: CrsUnit,
    /// When the scan was taken, as far as its file says.
    pub date: Option<ScanDate>,
    /// Metres per coordinate unit of x, y and z, which [`stream`] applies:
    /// ones as listed (the file's own numbers, as `inspect` shows them),
    /// set by `liftplan_scans::list_all` from the stated unit or the
    /// project's.
    pub to_m: [f64; 3],
    /// The unit `to_m` is for and where it came from, for the run's lines
    /// (set with it).
    pub read_in: String,
    /// Where the scan's first point is in its file, as (byte offset, line),
    /// for a format whose scans follow one another with nothing to find
    /// them by but reading (PTX); `None` for the others.
    pub points_at: Option<(u64, u64)>,
}

/// Lists the scans in a file from its header, reading no points. A text
/// file whose extension other files share (`.txt`, `.csv`, `.asc`: a
/// survey's report or notes dropped among the scans) that holds no line of
/// numbers is no scan: it lists none, with a warning.
pub fn list_scans(path: &Path) -> Result<Vec<ScanInfo>> {
    let format = Format::from_path(path).ok_or_else(|| {
        ScanError::format(Location::file(path), "not a scan file (expected .las, .laz, .ply, .e57, .ptx, .pts or .xyz)")
    })?;
    let meta = std::fs::metadata(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    if meta.len() == 0 {
        if text::may_be_other_text(path) {
            tracing::warn!("{}: empty: not a scan, passed by", path.display());
            return Ok(Vec::new());
        }
        return Err(ScanError::format(Location::file(path), "the file is empty"));
    }
    match format {
        Format::Las | Format::Laz => las::list(path, format),
        Format::Ply => ply::list(path),
        Format::E57 => e57::list(path),
        Format::Pts | Format::Xyz => text::list(path, format),
        Format::Ptx => ptx::list(path),
    }
}

/// Streams the points of one scan in chunks of at most [`CHUNK_POINTS`], in the
/// scan's own frame, in metres where [`ScanInfo::to_m`] says how. Returns
/// the number of points delivered.
pub fn stream(info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
    if info.to_m != [1.0; 3] {
        let mut scaled = PointCloud::default();
        return stream_as_read(info, &mut |c| {
            scaled.clone_from(c);
            for p in &mut scaled.xyz {
                for (v, m) in p.iter_mut().zip(info.to_m) {
                    *v *= m;
                }
            }
            f(&scaled)
        });
    }
    stream_as_read(info, f)
}

/// [`stream`] in the file's own numbers.
fn stream_as_read(info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
    match info.format {
        Format::Las | Format::Laz => las::stream(info, f),
        Format::Ply => ply::stream(info, f),
        Format::E57 => e57::OpenE57::open(&info.path)?.stream(info, f),
        Format::Pts | Format::Xyz => text::stream(info, f),
        Format::Ptx => ptx::stream(info, f),
    }
}

/// Streams scans one after another as [`stream`] does, keeping a file that
/// holds several scans (E57) open from one of its scans to the next, so that
/// it is opened once per pass over the scans, not once per scan. Give it the
/// scans in file order, as [`list_scans`] lists them.
#[derive(Default)]
pub struct ScanStreamer {
    e57: Option<e57::OpenE57>,
}

impl ScanStreamer {
    pub fn stream(&mut self, info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
        if info.format != Format::E57 || info.to_m != [1.0; 3] {
            return stream(info, f);
        }
        let mut open = match self.e57.take() {
            Some(open) if open.path() == info.path => open,
            _ => e57::OpenE57::open(&info.path)?,
        };
        let n = open.stream(info, f)?;
        // Kept only after a scan read to its end: a failed read may have left
        // the reader anywhere.
        self.e57 = Some(open);
        Ok(n)
    }
}

/// Reads one scan entirely (for small files and tests).
pub fn read_all(info: &ScanInfo) -> Result<PointCloud> {
    let mut all = PointCloud::default();
    stream(info, &mut |c| {
        all.append(c);
        Ok(())
    })?;
    Ok(all)
}

/// Runs a third-party decoder on a file's bytes, turning a panic inside it
/// into an error at `place` (see [`liftplan_core::guard::run_reader`]).
pub(crate) fn guard_decoder<T>(
    place: impl FnOnce() -> Location,
    what: &str,
    f: impl FnOnce() -> Result<T>,
) -> Result<T> {
    liftplan_core::guard::run_reader(what, f).unwrap_or_else(|why| Err(ScanError::format(place(), why)))
}

/// Checks a chunk's coordinates; `first_index` is the index of its first point
/// in the scan, for the error message.
pub(crate) fn check_finite(info: &ScanInfo, chunk: &PointCloud, first_index: u64) -> Result<()> {
    if let Some(i) = chunk.xyz.iter().position(|p| !(p[0].is_finite() && p[1].is_finite() && p[2].is_finite())) {
        return Err(ScanError::format(
            Location::item(&info.path, format!("{}, point {}", info.name, first_index + i as u64)),
            format!("coordinate is not a finite number: {:?}", chunk.xyz[i]),
        ));
    }
    Ok(())
}

/// Scan name from the file stem, as scans' names are kept.
pub(crate) fn stem(path: &Path) -> String {
    path.file_stem().map(|s| scan_name_kept(&s.to_string_lossy())).unwrap_or_else(|| "scan".into())
}

/// The most characters of a scan's name kept: a name is words in the run's
/// lines and on the plan's pages (scans left out, warned of), and an E57
/// file can name a scan in any number.
pub const MAX_SCAN_NAME_CHARS: usize = 200;

/// A scan's name (its file's stem, or the name its E57 file gives it) as
/// the scans stage keeps it ([`liftplan_core::names::kept`]): at most
/// [`MAX_SCAN_NAME_CHARS`] characters and a tag, no control characters (a
/// line break in a file's name printed a line of its own in the run's
/// output).
pub fn scan_name_kept(name: &str) -> String {
    liftplan_core::names::kept(name, MAX_SCAN_NAME_CHARS).into_owned()
}
