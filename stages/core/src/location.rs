//! Where in an input something was found: a file plus a byte offset, a line and
//! column, a spreadsheet cell or a named item.
//!
//! Every error about user input carries a [`Location`], so a survey team or a lift
//! engineer can open the file and go straight to the bad spot. This module only
//! formats places; it must not open files.

use std::fmt;
use std::path::{Path, PathBuf};

/// How a stage's summary names an input file: relative to `root` (the
/// project folder) when it lies inside it, else as given. A summary written
/// this way is the same however the project folder was named on the command
/// line and wherever it lies, as its cache key is.
pub fn shown(path: &Path, root: Option<&Path>) -> String {
    in_words(root.and_then(|r| path.strip_prefix(r).ok()).unwrap_or(path))
}

/// A path as liftplan says it in its lines, errors and pages: each control
/// character in it (a line break in a file's name, a terminal's escape)
/// shown as U+FFFD, so that naming a file never prints a line it does not
/// say.
pub fn in_words(path: &Path) -> String {
    crate::names::without_controls(&path.display().to_string()).into_owned()
}

/// A place inside a file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Place {
    /// The file as a whole (it is missing, empty, or of the wrong kind).
    Whole,
    /// A byte offset from the start of the file.
    Byte(u64),
    /// A 1-based line and optional 1-based column of a text file.
    Line { line: u64, column: Option<u64> },
    /// A spreadsheet cell, e.g. sheet `Main boom`, cell `C12`.
    Cell { sheet: String, cell: String },
    /// A named element, e.g. a scan inside an E57 file or a group of an RVM file.
    Item(String),
}

/// A file and a place inside it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    pub path: PathBuf,
    pub place: Place,
}

impl Location {
    pub fn file(path: impl AsRef<Path>) -> Self {
        Location { path: path.as_ref().to_path_buf(), place: Place::Whole }
    }
    pub fn byte(path: impl AsRef<Path>, offset: u64) -> Self {
        Location { path: path.as_ref().to_path_buf(), place: Place::Byte(offset) }
    }
    pub fn line(path: impl AsRef<Path>, line: u64, column: Option<u64>) -> Self {
        Location { path: path.as_ref().to_path_buf(), place: Place::Line { line, column } }
    }
    /// The line and column of byte `offset` of `text`, the contents of `path`.
    pub fn in_text(path: impl AsRef<Path>, text: &str, offset: usize) -> Self {
        let (line, column) = line_col(text, offset);
        Location::line(path, line, Some(column))
    }
    pub fn cell(path: impl AsRef<Path>, sheet: &str, cell: &str) -> Self {
        Location {
            path: path.as_ref().to_path_buf(),
            place: Place::Cell { sheet: sheet.to_string(), cell: cell.to_string() },
        }
    }
    pub fn item(path: impl AsRef<Path>, item: impl Into<String>) -> Self {
        Location { path: path.as_ref().to_path_buf(), place: Place::Item(item.into()) }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = in_words(&self.path);
        match &self.place {
            Place::Whole => write!(f, "{p}"),
            Place::Byte(o) => write!(f, "{p} at byte {o}"),
            Place::Line { line, column: Some(c) } => write!(f, "{p}:{line}:{c}"),
            Place::Line { line, column: None } => write!(f, "{p}:{line}"),
            Place::Cell { sheet, cell } => write!(f, "{p} [{sheet}!{cell}]"),
            Place::Item(name) => write!(f, "{p} ({name})"),
        }
    }
}

/// Spreadsheet column letters for a 0-based column index (0 -> `A`, 27 -> `AB`).
pub fn column_letters(mut col: u32) -> String {
    let mut out = Vec::new();
    loop {
        out.push(b'A' + (col % 26) as u8);
        if col < 26 {
            break;
        }
        col = col / 26 - 1;
    }
    out.reverse();
    String::from_utf8(out).unwrap_or_default()
}

/// `A1`-style reference for a 0-based (row, column).
pub fn cell_ref(row: u32, col: u32) -> String {
    format!("{}{}", column_letters(col), row + 1)
}

/// Parses an `A1`-style cell ("C6", "$C$6") or range ("C6:P6") into its
/// 0-based corners ((first row, first column), (last row, last column)), a
/// cell being a range of one.
pub fn parse_cell_range(s: &str) -> Option<((u32, u32), (u32, u32))> {
    fn cell(c: &str) -> Option<(u32, u32)> {
        let c = c.trim().trim_start_matches('$');
        let split = c.find(|ch: char| ch.is_ascii_digit())?;
        let (letters, digits) = c.split_at(split);
        let letters = letters.trim_end_matches('$');
        if letters.is_empty() || !letters.chars().all(|ch| ch.is_ascii_alphabetic()) {
            return None;
        }
        let mut col: u32 = 0;
        for ch in letters.to_ascii_uppercase().chars() {
            col = col.checked_mul(26)?.checked_add(ch as u32 - 'A' as u32 + 1)?;
        }
        let row: u32 = digits.parse().ok()?;
        (row >= 1 && col >= 1).then(|| (row - 1, col - 1))
    }
    let (a, b) = s.split_once(':').unwrap_or((s, s));
    let (a, b) = (cell(a)?, cell(b)?);
    Some(((a.0.min(b.0), a.1.min(b.1)), (a.0.max(b.0), a.1.max(b.1))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_are_shown_relative_to_the_project_folder() {
        let root = Path::new("/data/site-a");
        assert_eq!(shown(Path::new("/data/site-a/scans/s1.laz"), Some(root)), "scans/s1.laz");
        assert_eq!(shown(Path::new("site-a/scans/s1.laz"), Some(Path::new("site-a"))), "scans/s1.laz");
        assert_eq!(shown(Path::new("/elsewhere/s1.laz"), Some(root)), "/elsewhere/s1.laz");
        assert_eq!(shown(Path::new("/data/site-a/scans/s1.laz"), None), "/data/site-a/scans/s1.laz");
        // A line break or an escape in a file's name is not said as one.
        let odd = Path::new("/data/site-a/scans/s1\nerror: x\x1b[2J.laz");
        assert_eq!(shown(odd, Some(root)), "scans/s1\u{FFFD}error: x\u{FFFD}[2J.laz");
        let at = Location::line(odd, 3, Some(4)).to_string();
        assert_eq!(at, "/data/site-a/scans/s1\u{FFFD}error: x\u{FFFD}[2J.laz:3:4");
    }

    #[test]
    fn cell_refs() {
        assert_eq!(cell_ref(0, 0), "A1");
        assert_eq!(cell_ref(11, 2), "C12");
        assert_eq!(column_letters(25), "Z");
        assert_eq!(column_letters(26), "AA");
        assert_eq!(column_letters(27), "AB");
        assert_eq!(column_letters(701), "ZZ");
        assert_eq!(column_letters(702), "AAA");
        assert_eq!(parse_cell_range("C6:P6"), Some(((5, 2), (5, 15))));
        assert_eq!(parse_cell_range("$B$7"), Some(((6, 1), (6, 1))));
        assert_eq!(parse_cell_range("M44:A6"), Some(((5, 0), (43, 12))));
        for not in ["", "6C", "C0", "C", "C6:", "Ç6"] {
            assert_eq!(parse_cell_range(not), None, "{not}");
        }
    }

    #[test]
    fn display() {
        assert_eq!(Location::byte("a.laz", 12).to_string(), "a.laz at byte 12");
        assert_eq!(Location::line("p.toml", 3, Some(5)).to_string(), "p.toml:3:5");
        assert_eq!(Location::cell("c.xlsx", "Main", "B4").to_string(), "c.xlsx [Main!B4]");
    }
}

/// Why a text file people edit could not be read ([`read_text`]).
#[derive(Debug)]
pub enum TextReadError {
    Io(std::io::Error),
    /// Not UTF-8: the place of its first byte that is not, and what to do.
    NotUtf8(Location, String),
}

/// Reads a text file people edit (a project, station or crane file), a
/// UTF-8 byte order mark left out. One saved in the system's code page
/// ("Kranstellfläche" in Windows-1252, as Notepad saved "ANSI") is refused
/// at the line and column of its first byte that is not UTF-8, saying what
/// to do: its words are names on the plan's pages and are not guessed at.
pub fn read_text(path: impl AsRef<Path>) -> Result<String, TextReadError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(TextReadError::Io)?;
    let bytes = crate::byte_order_mark::strip(&bytes);
    match std::str::from_utf8(bytes) {
        Ok(text) => Ok(text.to_string()),
        Err(e) => {
            let valid = e.valid_up_to();
            let before = std::str::from_utf8(&bytes[..valid]).unwrap_or_default();
            let (line, column) = line_col(before, valid);
            Err(TextReadError::NotUtf8(
                Location::line(path, line, Some(column)),
                format!(
                    "not UTF-8 text (byte 0x{:02X}): save the file as UTF-8 (in Notepad: Save as, Encoding UTF-8)",
                    bytes[valid]
                ),
            ))
        }
    }
}

/// 1-based line and column of a byte offset in `text`.
pub fn line_col(text: &str, offset: usize) -> (u64, u64) {
    let offset = offset.min(text.len());
    let before = &text.as_bytes()[..offset];
    let line = before.iter().filter(|&&b| b == b'\n').count() as u64 + 1;
    let line_start = before.iter().rposition(|&b| b == b'\n').map(|p| p + 1).unwrap_or(0);
    let col = String::from_utf8_lossy(&before[line_start..]).chars().count() as u64 + 1;
    (line, col)
}

/// Location and message of a TOML parse or schema error, e.g.
/// `site/liftplan.toml:12:1: unknown field 'voxl', expected one of ...`.
///
/// A backslash in a double-quoted string (a Windows path,
/// `"scans\stations.toml"`) is an escape to TOML, refused as "missing
/// escaped value": the message then says how to write the path.
pub fn toml_error(path: impl AsRef<Path>, text: &str, err: &toml::de::Error) -> (Location, String) {
    let loc = match err.span() {
        Some(span) => Location::in_text(path, text, span.start),
        None => Location::file(path),
    };
    let message = err.message().trim();
    let at_backslash = err.span().is_some_and(|s| {
        text[..s.start.min(text.len())].ends_with('\\') || text.get(s.start..).is_some_and(|t| t.starts_with('\\'))
    });
    if at_backslash && message.contains("escape") {
        return (
            loc,
            format!(
                "{message}; a backslash in a \"...\" string starts an escape: write a path with '/' \
                 (\"scans/stations.toml\"), which serves on Windows too"
            ),
        );
    }
    (loc, message.to_string())
}

#[cfg(test)]
mod line_tests {
    use super::*;

    /// A Windows path in a double-quoted string is refused where its
    /// backslash is, saying how to write it.
    #[test]
    fn a_windows_path_is_refused_saying_how_to_write_it() {
        #[derive(serde::Deserialize, Debug)]
        #[allow(dead_code)]
        struct Paths {
            stations: String,
        }
        let text = "stations = \"scans\\stations.toml\"\n";
        let err = toml::from_str::<Paths>(text).unwrap_err();
        let (at, why) = toml_error("liftplan.toml", text, &err);
        assert!(at.to_string().starts_with("liftplan.toml:1:"), "{at}");
        assert!(why.contains("write a path with '/'"), "{why}");
    }

    #[test]
    fn line_col_counts() {
        assert_eq!(line_col("ab\ncd\nef", 4), (2, 2));
        assert_eq!(line_col("ab", 0), (1, 1));
        assert_eq!(line_col("ab", 99), (1, 3));
    }

    /// A file in Windows-1252 is refused at its first byte that is not
    /// UTF-8, by line and column; a byte order mark is left out.
    #[test]
    fn text_not_in_utf8_is_refused_where_it_is() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("liftplan.toml");
        std::fs::write(&path, b"[project]\n# Kranstellfl\xe4che\n").unwrap();
        match read_text(&path) {
            Err(TextReadError::NotUtf8(at, why)) => {
                assert!(at.to_string().ends_with("liftplan.toml:2:14"), "{at}");
                assert!(why.starts_with("not UTF-8 text (byte 0xE4): save the file as UTF-8"), "{why}");
            }
            other => panic!("{other:?}"),
        }
        std::fs::write(&path, b"\xef\xbb\xbf[project]\n# Kranstellfl\xc3\xa4che\n").unwrap();
        assert_eq!(read_text(&path).unwrap(), "[project]\n# Kranstellfläche\n");
        assert!(matches!(read_text(d.path().join("none.toml")), Err(TextReadError::Io(_))));
    }
}
