//! The containers of workbooks, checked before calamine reads them: the zip
//! archive of xlsx, xlsm, xlsb and ods files, and the compound file (CFB) of
//! xls files.
//!
//! A workbook's size on disk does not bound what calamine makes of it, and a
//! damaged one can stop it for ever:
//! - its parts are deflated, and calamine reads some of them whole (the
//!   shared strings, an ODS file's `content.xml`), so a part that unpacks to
//!   gigabytes is held in memory;
//! - an ODS cell's `table:number-columns-repeated` and a row's
//!   `table:number-rows-repeated` are expanded into a dense range of up to
//!   calamine's own limit of 100 M cells (about 3 GB), and the cell's text is
//!   copied into each: an 813-byte file took 6.3 GB and 17 s before the sheet
//!   reader's [`MAX_CELLS`](crate::sheet::MAX_CELLS) could refuse it;
//! - calamine waits for an ODS sheet's end tag until the end of the file, and
//!   past it: a `content.xml` cut short or with a damaged end tag made it loop
//!   for ever (found by the chart_workbook fuzz target);
//! - an xls file is a compound file whose streams are chains of sectors
//!   linked by a table in the file. calamine follows a chain until it ends:
//!   a 1,536-byte xls file whose directory's sector names itself as the next
//!   one made it grow a buffer until the allocation failed, and a file cut
//!   short inside a sector did the same (found by the fuzz target);
//! - calamine reserves the cells an xls sheet's used range (DIMENSIONS
//!   record) claims before reading any: one whose last row came before its
//!   first asked for 687 GB (found by the fuzz target);
//! - calamine makes an xls sheet one dense range spanning all its cells,
//!   whose rows and columns are any 16-bit numbers: two cells at A1 and at
//!   row and column 65,536 asked for 137 GB;
//! - calamine reserves room for as many shared strings as an xlsx file's
//!   table says it holds, before reading any: ten billion asked for 240 GB;
//! - calamine reads each xls sheet from where its BoundSheet8 record places
//!   it to the sheet's EOF record, so many sheets placed at one spot with no
//!   EOF cost the whole stream once per sheet: `liftplan chart` took 51 s on
//!   a 1.3 MB file of 20,000 such sheets.
//!
//! So every part is unpacked once here, counting bytes, and an ODS
//! `content.xml` must be well-formed XML whose cells and text, counted from
//! the repeat attributes the way calamine expands them, stay within bounds;
//! an xls file must be whole sectors, its sector tables must link every chain
//! to an end inside the file, its sheets must not overlap, and their used
//! ranges and the span of their cells must stay within bounds; an xlsx
//! file's shared strings table must not claim more strings than it could
//! hold. All before calamine opens the file. A file that is text (a CSV,
//! a web page or an Excel 2003 XML sheet saved with a workbook's name, as
//! web portals export "xls" files) is refused saying so, not as a damaged
//! archive. This module does not read
//! values or judge whether a file is a valid workbook: an archive or part it
//! cannot unpack is left to calamine, which reports it.
//!
//! The zip parts are checked here; `container/ods.rs` checks an ODS file's
//! `content.xml`, `container/xlsx.rs` an xlsx file's shared strings and
//! `container/cfb.rs` a compound file.

mod cfb;
mod ods;
mod xlsx;

use crate::error::{ChartError, Result};
use liftplan_core::Location;
use std::io::{BufReader, Read};
use std::path::Path;

/// The most bytes a workbook's parts may unpack to, all together. A
/// manufacturer's load chart workbook unpacks to a few megabytes.
pub const MAX_UNPACKED_BYTES: u64 = 256 << 20;

/// Checks the workbook at `path` if it is a zip container (xlsx, xlsm, xlsb,
/// ods) or a compound file; other files pass unchecked. A compound file is
/// checked whatever its name: calamine opens one named xlsx or xlsb too, to
/// see whether it is an encrypted workbook (found by the fuzz target).
pub fn check(path: &Path) -> Result<Checked> {
    let mut head = [0u8; 8];
    let compound =
        std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut head)).is_ok() && head == cfb::SIGNATURE;
    if compound {
        let bytes = std::fs::read(path).map_err(|e| ChartError::Io(Location::file(path), e))?;
        cfb::check(&bytes).map_err(|m| ChartError::Format(Location::file(path), m))?;
        return Ok(Checked::default());
    }
    if let Some(what) = text_not_workbook(path) {
        return Err(ChartError::Format(Location::file(path), what));
    }
    check_within(path, MAX_UNPACKED_BYTES)
}

/// How much of a file is looked at to tell text from a workbook.
const TEXT_LOOKED_AT: usize = 4096;

/// Where the file at `path` is text, not a workbook (no zip archive, no
/// compound file, and its first bytes are UTF-8 text without control
/// characters but line ends and tabs), what it seems to be and what to do.
fn text_not_workbook(path: &Path) -> Option<String> {
    let mut head = Vec::with_capacity(TEXT_LOOKED_AT);
    std::fs::File::open(path).ok()?.take(TEXT_LOOKED_AT as u64).read_to_end(&mut head).ok()?;
    if head.is_empty() || head.starts_with(b"PK") || head.starts_with(&cfb::SIGNATURE) {
        return None;
    }
    let head = liftplan_core::byte_order_mark::strip(&head);
    // Text in UTF-8 (a character cut at the end of what was looked at is
    // still text) or in a Windows code page, as a CSV saved on Windows is.
    let text = match std::str::from_utf8(head) {
        Ok(t) => std::borrow::Cow::Borrowed(t),
        Err(e) if e.error_len().is_none() => {
            std::borrow::Cow::Borrowed(std::str::from_utf8(&head[..e.valid_up_to()]).ok()?)
        }
        Err(_) => liftplan_core::names::utf8_or_latin1(head),
    };
    if text.chars().any(|c| c.is_control() && !matches!(c, '\n' | '\r' | '\t')) {
        return None;
    }
    let first_line = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("").trim();
    let kind = if first_line.starts_with('<') {
        "markup (a web page, or an Excel 2003 XML spreadsheet)"
    } else if first_line.contains([',', ';', '\t']) {
        "text in columns (a CSV or tab-separated file)"
    } else {
        "text"
    };
    let begins: String = first_line.chars().take(40).collect();
    let cut = if begins.len() < first_line.len() { "..." } else { "" };
    Some(format!(
        "is not a workbook but {kind} saved with a workbook's name (it begins '{begins}{cut}'): open it in Excel or \
         LibreOffice and save it as a workbook (.xlsx), then check the chart it shows against the maker's"
    ))
}

/// What the check saw of a workbook that its reader must know.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Checked {
    /// The xlsx workbook asks for its formulas to be calculated when it is
    /// opened: the values it stores for them are not to be trusted
    /// (`xlsx::asks_full_calculation_on_open`).
    pub calculated_on_open: bool,
}

fn check_within(path: &Path, max_unpacked_bytes: u64) -> Result<Checked> {
    let bad = |msg: String| ChartError::Format(Location::file(path), msg);
    let ods = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("ods"));
    let Ok(file) = std::fs::File::open(path) else { return Ok(Checked::default()) };
    let Ok(mut zip) = zip::ZipArchive::new(BufReader::new(file)) else { return Ok(Checked::default()) };
    let mut unpacked = 0u64;
    let mut seen = Checked::default();
    for i in 0..zip.len() {
        let Ok(part) = zip.by_index(i) else { continue };
        let name = part.name().map(|n| n.into_owned()).unwrap_or_default();
        let room = max_unpacked_bytes - unpacked;
        let mut counted = Counted { inner: part.take(room + 1), bytes: 0 };
        let checked = if ods && name == "content.xml" {
            ods::check_content(&mut BufReader::new(&mut counted))
        } else if !ods && xlsx::is_shared_strings(&name) {
            xlsx::check_shared_strings(&mut BufReader::new(&mut counted))
        } else if !ods && xlsx::is_workbook(&name) {
            xlsx::asks_full_calculation_on_open(&mut BufReader::new(&mut counted)).map(|asks| {
                seen.calculated_on_open = asks;
                Ok(())
            })
        } else {
            Ok(Ok(()))
        };
        // What a check did not read is still unpacked, and counted.
        let verdict = match checked {
            Ok(Ok(())) => std::io::copy(&mut counted, &mut std::io::sink()).map(|_| Ok(())).map_err(|_| ()),
            other => other,
        };
        unpacked += counted.bytes;
        if unpacked > max_unpacked_bytes {
            return Err(bad(format!(
                "the workbook's parts unpack to more than {max_unpacked_bytes} bytes (at part {name}); a load chart \
                 workbook never does"
            )));
        }
        match verdict {
            Ok(Ok(())) => {}
            Ok(Err(refusal)) => return Err(bad(refusal)),
            // A part that does not unpack is calamine's to report.
            Err(()) => return Ok(seen),
        }
    }
    Ok(seen)
}

/// Counts the bytes read through it.
struct Counted<R> {
    inner: R,
    bytes: u64,
}

impl<R: Read> Read for Counted<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.bytes += n as u64;
        Ok(n)
    }
}

/// An ODS workbook of `content` (its `content.xml`), for tests.
#[cfg(test)]
pub(crate) fn ods_of(path: &Path, content: &str) {
    let manifest = r#"<?xml version="1.0" encoding="UTF-8"?><manifest:manifest xmlns:manifest="urn:oasis:names:tc:opendocument:xmlns:manifest:1.0" manifest:version="1.2"><manifest:file-entry manifest:full-path="/" manifest:media-type="application/vnd.oasis.opendocument.spreadsheet"/><manifest:file-entry manifest:full-path="content.xml" manifest:media-type="text/xml"/></manifest:manifest>"#;
    zip_file(
        path,
        &[
            ("mimetype", "application/vnd.oasis.opendocument.spreadsheet"),
            ("META-INF/manifest.xml", manifest),
            ("content.xml", content),
        ],
    );
}

/// A zip file of `parts` (name, text), deflated, for the tests here and in
/// [`ods`].
#[cfg(test)]
pub(crate) fn zip_file(path: &Path, parts: &[(&str, &str)]) {
    use std::io::Write;
    let mut w = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
    for (name, text) in parts {
        let method =
            if *name == "mimetype" { zip::CompressionMethod::Stored } else { zip::CompressionMethod::Deflated };
        w.start_file(*name, zip::write::SimpleFileOptions::default().compression_method(method)).unwrap();
        w.write_all(text.as_bytes()).unwrap();
    }
    w.finish().unwrap();
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A CSV, a web page or an XML sheet saved as a workbook is refused as
    /// text, saying what it seems to be; a damaged archive or binary data
    /// is left to the readers.
    #[test]
    fn text_saved_as_a_workbook_is_refused_as_such() {
        let d = tempfile::tempdir().unwrap();
        let said = |name: &str, bytes: &[u8]| {
            let path = d.path().join(name);
            std::fs::write(&path, bytes).unwrap();
            text_not_workbook(&path)
        };
        let csv = said("chart.xlsx", b"\xef\xbb\xbfRadius;20;30\r\n3;49;39\r\n").unwrap();
        assert!(
            csv.starts_with("is not a workbook but text in columns (a CSV or tab-separated file) saved with a workbook's name (it begins 'Radius;20;30')"),
            "{csv}"
        );
        let html = said("page.xls", b"\n<html><body><table><tr><td>Radius</td></tr></table></body></html>").unwrap();
        assert!(html.contains("markup (a web page, or an Excel 2003 XML spreadsheet)"), "{html}");
        // Saved on Windows: a Latin-1 'ä'.
        let latin1 = said("latin1.xls", b"Ausladung\tL\xe4nge 20\r\n3\t49\r\n").unwrap();
        assert!(latin1.contains("(it begins 'Ausladung\tLänge 20')"), "{latin1}");
        assert!(said("chart.xlsx", b"PK\x03\x04 damaged").is_none());
        assert!(said("chart.xls", &[0xd0, 0xcf, 0x11, 0xe0, 0xa1, 0xb1, 0x1a, 0xe1, 0, 0]).is_none());
        assert!(said("chart.xlsx", b"Radius\x00\x01\x02").is_none());
        assert!(said("chart.xlsx", b"").is_none());
        let e = check(&d.path().join("page.xls")).unwrap_err().to_string();
        assert!(e.contains("page.xls: is not a workbook but markup"), "{e}");
    }

    /// A part that unpacks past the limit is refused before calamine reads it.
    #[test]
    fn a_workbook_unpacking_past_the_limit_is_refused() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.xlsx");
        let zeros = "0".repeat(1 << 20);
        zip_file(&path, &[("[Content_Types].xml", "<Types/>"), ("xl/sharedStrings.xml", &zeros)]);
        assert!(std::fs::metadata(&path).unwrap().len() < 10_000);
        let e = check_within(&path, 64 << 10).unwrap_err().to_string();
        assert!(
            e.contains(
                "chart.xlsx: the workbook's parts unpack to more than 65536 bytes (at part xl/sharedStrings.xml)"
            ),
            "{e}"
        );
        check_within(&path, 2 << 20).unwrap();
    }

    /// A chart workbook whose shared strings table says it holds ten billion
    /// strings: calamine reserved room for them (240 GB) and liftplan
    /// aborted. Refused before calamine opens it; the same workbook with its
    /// own count reads.
    #[test]
    fn a_workbook_claiming_billions_of_shared_strings_is_refused() {
        use std::io::{Read, Write};
        let d = tempfile::tempdir().unwrap();
        let good = d.path().join("good.xlsx");
        let mut wb = rust_xlsxwriter::Workbook::new();
        let ws = wb.add_worksheet().set_name("Chart").unwrap();
        ws.write_string(0, 0, "Main boom, capacities in t").unwrap();
        ws.write_string(1, 0, "Radius (m)").unwrap();
        ws.write_number(1, 1, 10.0).unwrap();
        wb.save(&good).unwrap();
        assert_eq!(crate::sheet::read_workbook(&good).unwrap()[0].text(1, 0), Some("Radius (m)"));

        let bad = d.path().join("bad.xlsx");
        let mut from = zip::ZipArchive::new(std::fs::File::open(&good).unwrap()).unwrap();
        let mut to = zip::ZipWriter::new(std::fs::File::create(&bad).unwrap());
        for i in 0..from.len() {
            let mut part = from.by_index(i).unwrap();
            let name = part.name().unwrap().into_owned();
            let mut text = String::new();
            part.read_to_string(&mut text).unwrap();
            if name == "xl/sharedStrings.xml" {
                assert!(text.contains("uniqueCount=\"2\""), "{text}");
                text = text.replace("uniqueCount=\"2\"", "uniqueCount=\"10000000000\"");
            }
            to.start_file(name, zip::write::SimpleFileOptions::default()).unwrap();
            to.write_all(text.as_bytes()).unwrap();
        }
        to.finish().unwrap();
        let e = crate::sheet::read_workbook(&bad).unwrap_err().to_string();
        assert!(
            e.contains(
                "bad.xlsx: its shared strings table says it holds 10000000000 strings (uniqueCount) but holds 2"
            ),
            "{e}"
        );
    }
}
