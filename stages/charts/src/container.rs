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
//!   reader's [`MAX_CELLS`] could refuse it;
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
//!   first asked for 687 GB (found by the fuzz target).
//!
//! So every part is unpacked once here, counting bytes, and an ODS
//! `content.xml` must be well-formed XML whose cells and text, counted from
//! the repeat attributes the way calamine expands them, stay within bounds;
//! an xls file must be whole sectors, its sector tables must link every chain
//! to an end inside the file, and its sheets' used ranges must stay within
//! bounds. All before calamine opens the file. This module does not read
//! values or judge whether a file is a valid workbook: an archive or part it
//! cannot unpack is left to calamine, which reports it.

use crate::error::{ChartError, Result};
use crate::sheet::MAX_CELLS;
use liftplan_core::Location;
use quick_xml::events::{BytesStart, Event};
use std::io::{BufReader, Read};
use std::path::Path;

/// The most bytes a workbook's parts may unpack to, all together. A
/// manufacturer's load chart workbook unpacks to a few megabytes.
pub const MAX_UNPACKED_BYTES: u64 = 256 << 20;

/// calamine's caps on an ODS sheet's columns and rows (`ods.rs`).
const ODS_MAX_COLUMNS: u64 = 16_384;
const ODS_MAX_ROWS: u64 = 1_048_576;

/// Checks the workbook at `path` if it is a zip container (xlsx, xlsm, xlsb,
/// ods) or a compound file; other files pass unchecked. A compound file is
/// checked whatever its name: calamine opens one named xlsx or xlsb too, to
/// see whether it is an encrypted workbook (found by the fuzz target).
pub fn check(path: &Path) -> Result<()> {
    let mut head = [0u8; 8];
    let compound = std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut head)).is_ok() && head == CFB_SIGNATURE;
    if compound {
        let bytes = std::fs::read(path).map_err(|e| ChartError::Io(Location::file(path), e))?;
        return check_compound_file(&bytes).map_err(|m| ChartError::Format(Location::file(path), m));
    }
    check_within(path, MAX_UNPACKED_BYTES)
}

const CFB_SIGNATURE: [u8; 8] = [0xD0, 0xCF, 0x11, 0xE0, 0xA1, 0xB1, 0x1A, 0xE1];

/// CFB sector ids from here up are markers (free, end of chain, table
/// sectors), not links.
const CFB_MAX_LINK: u32 = 0xFFFF_FFFA;
const CFB_END_OF_CHAIN: u32 = 0xFFFF_FFFE;

/// Checks a compound file's sector table (FAT) and mini sector table: every
/// link must stay inside its table and every chain must end, so that calamine,
/// which follows a chain as long as it goes on, reads at most the file.
/// A file that is not a compound file passes (calamine reports it).
fn check_compound_file(bytes: &[u8]) -> std::result::Result<(), String> {
    if bytes.len() < 512 || bytes[..8] != CFB_SIGNATURE {
        return Ok(());
    }
    let u16_at = |o: usize| u16::from_le_bytes([bytes[o], bytes[o + 1]]);
    let u32_at = |b: &[u8], o: usize| u32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]);
    let sector_size = match u16_at(30) {
        9 => 512,
        12 => 4096,
        // calamine refuses other sizes itself.
        _ => return Ok(()),
    };
    // calamine reads a sector cut short by the file's end as the bytes there
    // are, and the same sector read again as padded with zeros, so what it
    // makes of a file cut short inside a sector depends on the order it reads
    // things in (the chart_workbook fuzz target found such a file that made it
    // allocate without end). Whole sectors only.
    if !bytes.len().is_multiple_of(sector_size) {
        return Err(format!(
            "it is cut short: {} bytes is not a whole number of {sector_size}-byte sectors; the workbook is damaged",
            bytes.len()
        ));
    }
    // Sectors after the header.
    let sectors = (bytes.len() / sector_size).saturating_sub(1);
    let sector = |id: u32| -> Option<&[u8]> {
        let start = (id as usize).checked_add(1)?.checked_mul(sector_size)?;
        bytes.get(start..start + sector_size)
    };
    // The table's own sectors: 109 in the header, then a chain of DIFAT
    // sectors (each a list and a link to the next), bounded by the file.
    let mut fat_sectors: Vec<u32> = (0..109).map(|k| u32_at(bytes, 76 + 4 * k)).collect();
    let mut difat = u32_at(bytes, 68);
    let mut walked = 0;
    while difat < CFB_MAX_LINK {
        walked += 1;
        let Some(s) = sector(difat).filter(|_| walked <= sectors) else {
            return Err("its DIFAT chain loops or leaves the file; the workbook is damaged".into());
        };
        let n = sector_size / 4;
        fat_sectors.extend((0..n - 1).map(|k| u32_at(s, 4 * k)));
        difat = u32_at(s, 4 * (n - 1));
    }
    // calamine reads every sector listed, however often it is listed: a
    // table of more sectors than the file has would be made of repeats.
    fat_sectors.retain(|id| *id < CFB_MAX_LINK);
    if let Some(id) = fat_sectors.iter().find(|id| **id as usize >= sectors) {
        return Err(format!(
            "its sector table is said to lie in sector {id}, past the file's {sectors}; the workbook is damaged"
        ));
    }
    if fat_sectors.len() > sectors {
        return Err(format!(
            "it lists {} sectors of its sector table, more than the file's {sectors}; the workbook is damaged",
            fat_sectors.len()
        ));
    }
    let fat: Vec<u32> = fat_sectors
        .iter()
        .filter_map(|id| sector(*id))
        .flat_map(|s| (0..sector_size / 4).map(move |k| u32_at(s, 4 * k)))
        .collect();
    check_chains(&fat).map_err(|m| format!("its sector table {m}; the workbook is damaged"))?;
    // The mini sector table is a stream itself, a chain in the table above.
    let mut mini = Vec::new();
    let mut at = u32_at(bytes, 60);
    while at < CFB_MAX_LINK {
        let Some(s) = sector(at) else { break };
        mini.extend((0..sector_size / 4).map(|k| u32_at(s, 4 * k)));
        at = fat.get(at as usize).copied().unwrap_or(CFB_END_OF_CHAIN);
    }
    check_chains(&mini).map_err(|m| format!("its mini sector table {m}; the workbook is damaged"))?;
    let file = CompoundFile { bytes, sector_size, fat, mini };
    check_xls_used_ranges(&file).map_err(|m| format!("{m}; the workbook is damaged"))
}

/// A compound file whose sector tables were checked (no loops, no links past
/// them), so that every chain ends.
struct CompoundFile<'a> {
    bytes: &'a [u8],
    sector_size: usize,
    fat: Vec<u32>,
    mini: Vec<u32>,
}

impl CompoundFile<'_> {
    const MINI_SECTOR: usize = 64;
    /// Streams shorter than this lie in the mini stream (calamine's cut-off).
    const MINI_CUTOFF: usize = 4096;

    fn sector(&self, id: u32) -> Option<&[u8]> {
        let start = (id as usize).checked_add(1)?.checked_mul(self.sector_size)?;
        self.bytes.get(start..start + self.sector_size)
    }

    /// The first `len` bytes of the chain from `start`, read as calamine
    /// reads them. A chain that runs into a sector the file does not have is
    /// an error: calamine would read it as zeros or as whatever follows.
    fn chain(&self, start: u32, len: usize) -> std::result::Result<Vec<u8>, String> {
        let mut out = Vec::new();
        let mut at = start;
        while at != CFB_END_OF_CHAIN && out.len() < len {
            let s = self.sector(at).ok_or_else(|| format!("a stream runs into sector {at}, past the file's end"))?;
            out.extend_from_slice(&s[..s.len().min(len - out.len())]);
            // A link past the table panics calamine; its guard reports that.
            at = self.fat.get(at as usize).copied().unwrap_or(CFB_END_OF_CHAIN);
        }
        Ok(out)
    }

    /// The same for a chain of mini sectors in `mini_stream`.
    fn mini_chain(&self, mini_stream: &[u8], start: u32, len: usize) -> std::result::Result<Vec<u8>, String> {
        let mut out = Vec::new();
        let mut at = start;
        while at != CFB_END_OF_CHAIN && out.len() < len {
            let from = at as usize * Self::MINI_SECTOR;
            let s = mini_stream
                .get(from..from + Self::MINI_SECTOR)
                .ok_or_else(|| format!("a stream runs into mini sector {at}, past the mini stream's end"))?;
            out.extend_from_slice(&s[..s.len().min(len - out.len())]);
            at = self.mini.get(at as usize).copied().unwrap_or(CFB_END_OF_CHAIN);
        }
        Ok(out)
    }

    /// The stream named `name` (ASCII, any case), as calamine finds it: the
    /// first directory entry of that name.
    fn stream(&self, dir: &[u8], name: &str) -> std::result::Result<Option<Vec<u8>>, String> {
        let entries: Vec<&[u8]> = dir.chunks_exact(128).collect();
        let entry_name = |e: &[u8]| -> Vec<u8> {
            let units: Vec<u16> = e[..64].chunks_exact(2).map(|c| u16::from_le_bytes([c[0], c[1]])).collect();
            String::from_utf16_lossy(&units).bytes().take_while(|b| *b != 0).collect()
        };
        let Some(e) = entries.iter().find(|e| entry_name(e).eq_ignore_ascii_case(name.as_bytes())) else {
            return Ok(None);
        };
        let start = u32::from_le_bytes([e[116], e[117], e[118], e[119]]);
        let len = if self.sector_size == 512 {
            u32::from_le_bytes([e[120], e[121], e[122], e[123]]) as usize
        } else {
            u64::from_le_bytes(e[120..128].try_into().unwrap_or([0; 8])) as usize
        };
        if len >= Self::MINI_CUTOFF {
            return self.chain(start, len).map(Some);
        }
        // The mini stream is the root entry's stream.
        let root = entries[0];
        let root_start = u32::from_le_bytes([root[116], root[117], root[118], root[119]]);
        let root_len = u32::from_le_bytes([root[120], root[121], root[122], root[123]]) as usize;
        let mini_stream = self.chain(root_start, root_len)?;
        self.mini_chain(&mini_stream, start, len).map(Some)
    }
}

/// The used ranges (DIMENSIONS records) of an xls file's sheets, which
/// calamine reserves cells for before it reads any: a DIMENSIONS record of
/// 14 bytes claiming four billion rows made it ask for 687 GB (found by the
/// chart_workbook fuzz target). Each must be within [`MAX_CELLS`] cells, as
/// calamine computes them (wrapping, as its release build does). The records
/// are looked for where calamine reads them: the workbook globals, and each
/// sheet from the position its BoundSheet8 record gives.
fn check_xls_used_ranges(file: &CompoundFile) -> std::result::Result<(), String> {
    let dir_start = u32::from_le_bytes([file.bytes[48], file.bytes[49], file.bytes[50], file.bytes[51]]);
    let dir = file.chain(dir_start, usize::MAX)?;
    if dir.len() < 128 {
        return Ok(());
    }
    let stream = match file.stream(&dir, "Workbook")? {
        Some(s) => s,
        None => match file.stream(&dir, "Book")? {
            Some(s) => s,
            None => return Ok(()),
        },
    };
    let mut sheets = Vec::new();
    check_records(&stream, 0, &mut sheets)?;
    for pos in sheets {
        check_records(&stream, pos, &mut Vec::new())?;
    }
    Ok(())
}

/// Walks BIFF records from `pos`: refuses a used range over [`MAX_CELLS`]
/// cells and collects BoundSheet8 positions into `sheets`.
fn check_records(stream: &[u8], pos: usize, sheets: &mut Vec<usize>) -> std::result::Result<(), String> {
    let mut rest = stream.get(pos..).unwrap_or_default();
    let u16_at = |b: &[u8], o: usize| u16::from_le_bytes([b[o], b[o + 1]]) as u32;
    let u32_at = |b: &[u8], o: usize| u32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]);
    while rest.len() >= 4 {
        let (typ, len) = (u16_at(rest, 0), u16_at(rest, 2) as usize);
        let Some(data) = rest.get(4..4 + len) else { break };
        rest = &rest[4 + len..];
        match (typ, len) {
            (0x0085, 4..) => sheets.push(u32_at(data, 0) as usize),
            (0x0200, 10 | 14 | 16) => {
                let (rf, rl, cf, cl) = if len == 10 {
                    (u16_at(data, 0), u16_at(data, 2), u16_at(data, 4), u16_at(data, 6))
                } else {
                    (u32_at(data, 0), u32_at(data, 4), u16_at(data, 8), u16_at(data, 10))
                };
                let cf = if 0xFF < cf || cl < cf { 0 } else { cf };
                let (rows, cols) = if rl >= 1 && cl >= 1 {
                    ((rl - 1).wrapping_sub(rf).wrapping_add(1), (cl - 1).wrapping_sub(cf).wrapping_add(1))
                } else {
                    (1, 1)
                };
                let cells = rows as u64 * cols as u64;
                if cells > MAX_CELLS as u64 {
                    return Err(format!(
                        "a sheet's used range (its DIMENSIONS record) spans {rows} rows x {cols} columns, more than \
                         the {MAX_CELLS} cells a load chart may have"
                    ));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Every link of `table` (entry k: the sector after k) stays inside it and
/// no chain comes back on itself.
fn check_chains(table: &[u32]) -> std::result::Result<(), String> {
    // 0: not seen, 1: on the chain being walked, 2: leads to an end.
    let mut state = vec![0u8; table.len()];
    let mut path = Vec::new();
    for start in 0..table.len() {
        let mut at = start;
        while state[at] == 0 {
            state[at] = 1;
            path.push(at);
            let next = table[at];
            if next >= CFB_MAX_LINK {
                break;
            }
            if next as usize >= table.len() {
                return Err(format!("links sector {at} to {next}, past its {} entries", table.len()));
            }
            at = next as usize;
            if state[at] == 1 {
                return Err(format!("links sector {at} back into its own chain (a loop)"));
            }
        }
        for k in path.drain(..) {
            state[k] = 2;
        }
    }
    Ok(())
}

fn check_within(path: &Path, max_unpacked_bytes: u64) -> Result<()> {
    let bad = |msg: String| ChartError::Format(Location::file(path), msg);
    let ods = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("ods"));
    let Ok(file) = std::fs::File::open(path) else { return Ok(()) };
    let Ok(mut zip) = zip::ZipArchive::new(BufReader::new(file)) else { return Ok(()) };
    let mut unpacked = 0u64;
    for i in 0..zip.len() {
        let Ok(part) = zip.by_index(i) else { continue };
        let name = part.name().map(|n| n.into_owned()).unwrap_or_default();
        let room = max_unpacked_bytes - unpacked;
        let mut counted = Counted { inner: part.take(room + 1), bytes: 0 };
        let verdict = if ods && name == "content.xml" {
            ods_content(&mut BufReader::new(&mut counted))
        } else {
            std::io::copy(&mut counted, &mut std::io::sink()).map(|_| Ok(())).map_err(|_| ())
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
            Err(()) => return Ok(()),
        }
    }
    Ok(())
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

/// What calamine would make of an ODS `content.xml`: `Err(())` if the part
/// cannot be read (calamine reports it), `Ok(Err(message))` if it must not be
/// given to calamine.
///
/// Refused:
/// - XML that is not well-formed, or ends inside an element. calamine reads
///   leniently and waits for a sheet's end tag (or an annotation's) until
///   the end of the file, for ever: a truncated or damaged `content.xml`
///   hung it (found by the chart_workbook fuzz target).
/// - A sheet, or all sheets together, of more than [`MAX_CELLS`] cells.
///   calamine keeps each row element's cells up to its last non-empty one,
///   with the columns repeated, and then makes a dense range of the rectangle
///   from the first to the last non-empty row (rows repeated) and from the
///   leftmost to the rightmost non-empty column. Both are counted. A cell
///   counts as non-empty if it has a value type, a formula, or any content:
///   more than calamine keeps, never less.
/// - Text that the repeats (and `text:s` runs of spaces) would expand past
///   [`MAX_UNPACKED_BYTES`]: calamine copies a cell's text for every column
///   and row it is repeated over.
fn ods_content(xml: &mut impl std::io::BufRead) -> std::result::Result<std::result::Result<(), String>, ()> {
    let mut reader = quick_xml::Reader::from_reader(xml);
    let config = reader.config_mut();
    config.expand_empty_elements = true;
    config.check_end_names = true;
    let mut buf = Vec::new();
    let mut depth = 0usize;
    let mut table: Option<OdsTable> = None;
    let (mut cells, mut text) = (0u64, 0u64);
    loop {
        let event = match reader.read_event_into(&mut buf) {
            Ok(event) => event,
            Err(quick_xml::Error::Io(_)) => return Err(()),
            Err(e) => {
                return Ok(Err(format!(
                    "content.xml is not well-formed XML at byte {} ({e}); the workbook is damaged",
                    reader.error_position()
                )));
            }
        };
        match event {
            Event::Start(e) => {
                depth += 1;
                match &mut table {
                    None if e.name().as_ref() == "table:table" => {
                        let name = attr(&e, "table:name").unwrap_or_default();
                        table = Some(OdsTable { name, depth, ..Default::default() });
                    }
                    Some(t) => t.start(&e, depth),
                    None => {}
                }
            }
            Event::Text(t) => {
                if let Some(cell) = table.as_mut().and_then(|t| t.cell.as_mut()) {
                    cell.bytes += t.len() as u64;
                    cell.filled |= t.chars().any(|c| !c.is_whitespace());
                }
            }
            Event::GeneralRef(_) | Event::CData(_) => {
                if let Some(cell) = table.as_mut().and_then(|t| t.cell.as_mut()) {
                    cell.bytes += 4;
                    cell.filled = true;
                }
            }
            Event::End(_) => {
                if let Some(t) = &mut table
                    && t.end(depth)
                {
                    let (read, dense) = t.cells();
                    cells += dense;
                    text = text.saturating_add(t.text);
                    if read > MAX_CELLS as u64 || cells > MAX_CELLS as u64 {
                        return Ok(Err(format!(
                            "sheet '{}' repeats its cells into {} (the workbook's sheets {cells} in all); a load \
                             chart never has more than {MAX_CELLS}",
                            t.name,
                            if read > dense { format!("{read} cells") } else { t.span() },
                        )));
                    }
                    if text > MAX_UNPACKED_BYTES {
                        return Ok(Err(format!(
                            "sheet '{}' repeats its text into more than {MAX_UNPACKED_BYTES} bytes (the workbook's \
                             sheets {text} in all); a load chart never holds that much",
                            t.name
                        )));
                    }
                    table = None;
                }
                depth = depth.saturating_sub(1);
            }
            Event::Eof if depth > 0 => {
                return Ok(Err("content.xml ends inside an element; the workbook is truncated or damaged".into()));
            }
            Event::Eof => return Ok(Ok(())),
            _ => {}
        }
        buf.clear();
    }
}

/// One `table:table` being counted.
#[derive(Default)]
struct OdsTable {
    name: String,
    depth: usize,
    /// Rows so far, repeats included (capped as calamine caps them).
    rows: u64,
    row: Option<OdsRow>,
    cell: Option<OdsCell>,
    /// Cells of the row elements as calamine keeps them (columns repeated).
    read: u64,
    /// First and end rows (repeats included) that have a non-empty cell.
    span_rows: Option<(u64, u64)>,
    /// Leftmost and end non-empty columns.
    span_cols: Option<(u64, u64)>,
    /// Bytes of text and formulas, columns and rows repeated.
    text: u64,
}

/// A `table:table-row` being read.
struct OdsRow {
    depth: usize,
    repeats: u64,
    next_column: u64,
    /// First and end non-empty columns.
    filled: Option<(u64, u64)>,
    /// Bytes of text and formulas, columns repeated.
    text: u64,
}

/// A `table:table-cell` (or covered cell) being read.
struct OdsCell {
    depth: usize,
    repeats: u64,
    filled: bool,
    /// Bytes of its text and formula, `text:s` spaces expanded.
    bytes: u64,
}

impl OdsTable {
    fn start(&mut self, e: &BytesStart, depth: usize) {
        if let Some(cell) = &mut self.cell {
            cell.filled = true;
            if e.name().as_ref() == "text:s" {
                cell.bytes = cell.bytes.saturating_add(count_attr(e, "text:c"));
            }
            return;
        }
        let name = e.name();
        if self.row.is_none() && name.as_ref() == "table:table-row" {
            let room = ODS_MAX_ROWS - self.rows.min(ODS_MAX_ROWS);
            let repeats = count_attr(e, "table:number-rows-repeated").min(room);
            self.row = Some(OdsRow { depth, repeats, next_column: 0, filled: None, text: 0 });
        } else if self.row.is_some()
            && (name.as_ref() == "table:table-cell" || name.as_ref() == "table:covered-table-cell")
        {
            let repeats = count_attr(e, "table:number-columns-repeated");
            let formula = attr(e, "table:formula");
            let filled = attr(e, "office:value-type").is_some() || formula.is_some();
            let bytes = formula.map_or(0, |f| f.len() as u64);
            self.cell = Some(OdsCell { depth, repeats, filled, bytes });
        }
    }

    /// Ends the element at `depth`; true when it ends the table.
    fn end(&mut self, depth: usize) -> bool {
        if let Some(cell) = &self.cell {
            if depth != cell.depth {
                return false;
            }
            if let Some(row) = &mut self.row {
                let end = row.next_column.saturating_add(cell.repeats).min(ODS_MAX_COLUMNS);
                if cell.filled && end > row.next_column {
                    let first = row.filled.map_or(row.next_column, |(f, _)| f);
                    row.filled = Some((first, end));
                    row.text = row.text.saturating_add(cell.bytes.saturating_mul(end - row.next_column));
                }
                row.next_column = end;
            }
            self.cell = None;
        } else if let Some(row) = &self.row {
            if depth != row.depth {
                return false;
            }
            if let Some((first, end)) = row.filled {
                self.read += end;
                let rows_first = self.span_rows.map_or(self.rows, |(f, _)| f);
                self.span_rows = Some((rows_first, self.rows + row.repeats));
                let (l, r) = self.span_cols.unwrap_or((first, end));
                self.span_cols = Some((l.min(first), r.max(end)));
                self.text = self.text.saturating_add(row.text.saturating_mul(row.repeats));
            }
            self.rows += row.repeats;
            self.row = None;
        } else {
            return depth == self.depth;
        }
        false
    }

    /// Cells calamine keeps while reading the rows, and in its dense range.
    fn cells(&self) -> (u64, u64) {
        let (rows, cols) = self.extent();
        (self.read, rows.saturating_mul(cols))
    }

    fn extent(&self) -> (u64, u64) {
        match (self.span_rows, self.span_cols) {
            (Some((r0, r1)), Some((c0, c1))) => (r1 - r0, c1 - c0),
            _ => (0, 0),
        }
    }

    fn span(&self) -> String {
        let (rows, cols) = self.extent();
        format!("{rows} rows x {cols} columns")
    }
}

fn attr(e: &BytesStart, key: &str) -> Option<String> {
    e.attributes().flatten().find(|a| a.key.as_ref() == key).map(|a| a.value.into_owned())
}

/// A repeat count: 1 when absent or not a number (calamine refuses the
/// latter itself).
fn count_attr(e: &BytesStart, key: &str) -> u64 {
    attr(e, key).and_then(|v| v.trim().parse::<u64>().ok()).unwrap_or(1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    /// A zip file of `parts` (name, text), deflated.
    fn zip_file(path: &Path, parts: &[(&str, &str)]) {
        let mut w = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
        for (name, text) in parts {
            let method =
                if *name == "mimetype" { zip::CompressionMethod::Stored } else { zip::CompressionMethod::Deflated };
            w.start_file(*name, zip::write::SimpleFileOptions::default().compression_method(method)).unwrap();
            w.write_all(text.as_bytes()).unwrap();
        }
        w.finish().unwrap();
    }

    /// `content.xml` of one sheet "Chart" whose rows are `rows` (XML).
    fn content(rows: &str) -> String {
        format!(
            r#"<?xml version="1.0" encoding="UTF-8"?>
<office:document-content xmlns:office="urn:oasis:names:tc:opendocument:xmlns:office:1.0" xmlns:table="urn:oasis:names:tc:opendocument:xmlns:table:1.0" xmlns:text="urn:oasis:names:tc:opendocument:xmlns:text:1.0" office:version="1.2"><office:body><office:spreadsheet><table:table table:name="Chart">{rows}</table:table></office:spreadsheet></office:body></office:document-content>"#
        )
    }

    /// An ODS workbook of `content` (its `content.xml`).
    fn ods_of(path: &Path, content: &str) {
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

    /// An ODS workbook with one sheet "Chart" whose rows are `rows` (XML).
    fn ods(path: &Path, rows: &str) {
        ods_of(path, &content(rows));
    }

    fn cell(v: &str) -> String {
        match v.parse::<f64>() {
            Ok(_) => format!(
                r#"<table:table-cell office:value-type="float" office:value="{v}"><text:p>{v}</text:p></table:table-cell>"#
            ),
            Err(_) => {
                format!(r#"<table:table-cell office:value-type="string"><text:p>{v}</text:p></table:table-cell>"#)
            }
        }
    }

    /// A small load chart laid out as LibreOffice saves one: every row padded
    /// with an empty cell repeated to the last column, and the empty rows
    /// below repeated to the sheet's last row.
    fn libreoffice_chart() -> String {
        let empty_to_end =
            |used: usize| format!(r#"<table:table-cell table:number-columns-repeated="{}"/>"#, 16384 - used);
        let mut rows = String::new();
        let grid: [&[&str]; 6] = [
            &["Main boom, capacities in t"],
            &["Radius (m)", "Boom length (m)"],
            &["", "20", "30"],
            &["3", "50", "40"],
            &["5", "30", "25"],
            &["8", "15", "12"],
        ];
        for line in grid {
            rows.push_str("<table:table-row>");
            for v in line {
                rows.push_str(&if v.is_empty() { "<table:table-cell/>".to_string() } else { cell(v) });
            }
            rows.push_str(&empty_to_end(line.len()));
            rows.push_str("</table:table-row>");
        }
        rows.push_str(&format!(
            r#"<table:table-row table:number-rows-repeated="{}">{}</table:table-row>"#,
            1_048_576 - grid.len(),
            empty_to_end(0)
        ));
        rows
    }

    /// Found by hand after the fuzzers missed it (they cannot reach inside a
    /// deflated part): an 813-byte ODS file whose one row of one cell is
    /// repeated into 99,000 rows of 1000 columns. calamine would make a dense
    /// range of 99 M cells (6.3 GB) before the sheet reader could refuse it.
    #[test]
    fn an_ods_file_whose_repeats_make_millions_of_cells_is_refused() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("bomb.ods");
        let row = format!(
            r#"<table:table-row table:number-rows-repeated="99000">{}</table:table-row>"#,
            cell("1").replace("<table:table-cell ", r#"<table:table-cell table:number-columns-repeated="1000" "#)
        );
        ods(&path, &row);
        assert!(std::fs::metadata(&path).unwrap().len() < 2000);
        let e = crate::sheet::read_workbook(&path).unwrap_err().to_string();
        assert!(e.contains("bomb.ods: sheet 'Chart' repeats its cells into 99000 rows x 1000 columns"), "{e}");
        // Two cells far apart make calamine's range as large.
        let far = format!(
            r#"<table:table-row>{}</table:table-row><table:table-row table:number-rows-repeated="300"><table:table-cell/></table:table-row><table:table-row><table:table-cell table:number-columns-repeated="16000"/>{}</table:table-row>"#,
            cell("1"),
            cell("2")
        );
        ods(&path, &far);
        let e = crate::sheet::read_workbook(&path).unwrap_err().to_string();
        assert!(e.contains("repeats its cells into 302 rows x 16001 columns"), "{e}");
    }

    /// A chart saved the way LibreOffice saves it (empty cells and rows
    /// repeated to the sheet's edges) is read, and its grid found.
    #[test]
    fn an_ods_chart_padded_to_the_sheets_edges_is_read() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.ods");
        ods(&path, &libreoffice_chart());
        let sheets = crate::sheet::read_workbook(&path).unwrap();
        assert_eq!(sheets.len(), 1);
        assert_eq!(sheets[0].cells.len(), 14);
        assert_eq!(sheets[0].num(4, 2), Some(25.0));
        let (configs, _) = crate::read_chart(&path, &crate::Settings::default()).unwrap();
        assert_eq!(configs.len(), 1);
        assert_eq!(configs[0].boom_lengths_m, vec![20.0, 30.0]);
        assert_eq!(configs[0].radii_m, vec![3.0, 5.0, 8.0]);
        let c = configs[0].lookup(30.0, 4.0).unwrap();
        assert_eq!(c.capacity_kg, 25_000.0);
    }

    /// A sheet too large to search for grids (here a chart above a block of
    /// 202,500 numbers) is named in the error, and a `[[charts.table]]`
    /// mapping of its grid still reads it.
    #[test]
    fn a_sheet_too_large_to_search_is_named_and_can_be_mapped() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.ods");
        let block =
            cell("7").replace("<table:table-cell ", r#"<table:table-cell table:number-columns-repeated="450" "#);
        let rows = libreoffice_chart().replace(
            r#"<table:table-row table:number-rows-repeated="1048570">"#,
            &format!(r#"<table:table-row table:number-rows-repeated="450">{block}</table:table-row><table:table-row table:number-rows-repeated="1048120">"#),
        );
        assert_ne!(rows, libreoffice_chart());
        ods(&path, &rows);
        let e = crate::read_chart(&path, &crate::Settings::default()).unwrap_err().to_string();
        assert!(e.contains("no load-chart grid found") && e.contains("sheet 'Chart' (202514 cells)"), "{e}");
        let mapped = crate::Settings {
            table: vec![crate::TableMapping {
                file: "chart.ods".into(),
                sheet: "Chart".into(),
                config: "main".into(),
                across: "B3:C3".into(),
                down: "A4:A6".into(),
                transposed: false,
                length_unit: None,
                capacity_unit: None,
            }],
        };
        let (configs, _) = crate::read_chart(&path, &mapped).unwrap();
        assert_eq!(configs[0].boom_lengths_m, vec![20.0, 30.0]);
    }

    /// Found by the chart_workbook fuzz target: a sheet whose end tag is
    /// damaged (`</tible:table>`) made calamine read past the end of the file
    /// for ever. Damaged or truncated XML is refused before calamine sees it.
    #[test]
    fn a_content_xml_that_is_not_well_formed_is_refused() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.ods");
        let whole = content(&libreoffice_chart());
        // The fuzzer's case: the sheet's end tag misspelt.
        let misspelt = whole.replace("</table:table></office:spreadsheet>", "</tible:table></office:spreadsheet>");
        assert_ne!(misspelt, whole);
        for (bad, why) in [
            (misspelt, "not well-formed XML"),
            (whole[..whole.len() / 2].to_string(), "not well-formed XML"),
            (whole[..whole.rfind("</table:table>").unwrap()].to_string(), "ends inside an element"),
        ] {
            ods_of(&path, &bad);
            let e = crate::sheet::read_workbook(&path).unwrap_err().to_string();
            assert!(e.contains("chart.ods: content.xml") && e.contains(why), "{why}: {e}");
        }
    }

    /// Text is copied into every cell a repeat makes: a cell of a few hundred
    /// bytes over a million cells, or one run of four billion spaces
    /// (`text:s`), is refused.
    #[test]
    fn an_ods_file_whose_repeats_make_gigabytes_of_text_is_refused() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("text.ods");
        let long = "x".repeat(300);
        let row = format!(
            r#"<table:table-row table:number-rows-repeated="1000"><table:table-cell table:number-columns-repeated="1000" office:value-type="string"><text:p>{long}</text:p></table:table-cell></table:table-row>"#
        );
        ods(&path, &row);
        let e = crate::sheet::read_workbook(&path).unwrap_err().to_string();
        assert!(e.contains("sheet 'Chart' repeats its text into more than 268435456 bytes"), "{e}");
        let spaces = r#"<table:table-row><table:table-cell office:value-type="string"><text:p>a<text:s text:c="4000000000"/>b</text:p></table:table-cell></table:table-row>"#;
        ods(&path, spaces);
        let e = crate::sheet::read_workbook(&path).unwrap_err().to_string();
        assert!(e.contains("repeats its text into more than"), "{e}");
    }

    fn chart_fixture(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/charts").join(name)
    }

    /// `fixtures/charts/chart.xls` (xlwt's BIFF8 in a compound file).
    fn xls_fixture() -> Vec<u8> {
        std::fs::read(chart_fixture("chart.xls")).unwrap()
    }

    /// The xls fixture with its directory's link (the sector after the
    /// directory's first, in the sector table) set to `next`; and the first
    /// sector of the table.
    fn xls_with_directory_link(next: impl FnOnce(u32) -> u32) -> (Vec<u8>, u32) {
        let mut bytes = xls_fixture();
        assert_eq!(u16::from_le_bytes([bytes[30], bytes[31]]), 9, "512-byte sectors");
        let u32_at = |o: usize| u32::from_le_bytes(bytes[o..o + 4].try_into().unwrap());
        let (fat0, dir) = (u32_at(76), u32_at(48));
        let entry = (fat0 as usize + 1) * 512 + 4 * dir as usize;
        bytes[entry..entry + 4].copy_from_slice(&next(dir).to_le_bytes());
        (bytes, fat0)
    }

    #[test]
    fn an_xls_chart_is_read() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.xls");
        std::fs::write(&path, xls_fixture()).unwrap();
        let (configs, _) = crate::read_chart(&path, &crate::Settings::default()).unwrap();
        assert_eq!(configs[0].boom_lengths_m, vec![20.0, 30.0, 40.0]);
        assert_eq!(configs[0].radii_m, vec![3.0, 5.0, 8.0, 12.0]);
    }

    /// An xls file whose directory's sector names itself as the next one made
    /// calamine grow a buffer until the allocation failed (a 1,536-byte file
    /// asked for 4 GB), and so did one named xlsb; one whose chain links past
    /// the sector table would
    /// index past it; one listing a sector of its table many times makes
    /// calamine read it as many times. All are refused before calamine opens
    /// them.
    #[test]
    fn an_xls_file_whose_sector_chains_loop_or_leave_the_table_is_refused() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.xls");
        let refusal = |bytes: &[u8]| {
            std::fs::write(&path, bytes).unwrap();
            crate::sheet::read_workbook(&path).unwrap_err().to_string()
        };
        let (looped, fat0) = xls_with_directory_link(|dir| dir);
        let e = refusal(&looped);
        assert!(e.contains("chart.xls: its sector table links sector") && e.contains("back into its own chain"), "{e}");
        // calamine opens a compound file named xlsx or xlsb too, to see
        // whether it is an encrypted workbook (found by the fuzz target).
        for name in ["chart.xlsx", "chart.xlsb"] {
            let other = d.path().join(name);
            std::fs::write(&other, &looped).unwrap();
            let e = crate::sheet::read_workbook(&other).unwrap_err().to_string();
            assert!(e.contains(&format!("{name}: its sector table links sector")), "{e}");
        }
        let e = refusal(&xls_with_directory_link(|_| 100_000).0);
        assert!(e.contains("links sector") && e.contains("to 100000, past its 128 entries"), "{e}");
        // The table said to lie past the file's end, and a DIFAT chain leaving
        // the file.
        for (offset, why) in [
            (76, "its sector table is said to lie in sector 1000, past the file's 10"),
            (68, "its DIFAT chain loops or leaves the file"),
        ] {
            let mut bad = xls_fixture();
            bad[offset..offset + 4].copy_from_slice(&1000u32.to_le_bytes());
            let e = refusal(&bad);
            assert!(e.contains(why), "{e}");
        }
        // A table listing one sector 109 times: calamine reads each listing.
        let mut bad = xls_fixture();
        for k in 1..109 {
            bad[76 + 4 * k..80 + 4 * k].copy_from_slice(&fat0.to_le_bytes());
        }
        let e = refusal(&bad);
        assert!(e.contains("it lists 109 sectors of its sector table, more than the file's 10"), "{e}");
    }

    /// Found by the chart_workbook fuzz target: an xls sheet whose used range
    /// (DIMENSIONS record, 14 bytes) ends before it starts, which calamine's
    /// wrapping arithmetic turns into four billion rows, and reserves cells
    /// for: 687 GB, an allocation failure. And the fixture's own used range
    /// stretched to a million rows.
    #[test]
    fn an_xls_sheet_whose_used_range_is_too_large_is_refused() {
        let e = crate::sheet::read_workbook(&chart_fixture("damaged-dimensions.xls")).unwrap_err().to_string();
        assert!(
            e.contains("damaged-dimensions.xls: a sheet's used range (its DIMENSIONS record) spans 4294967150 rows"),
            "{e}"
        );
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.xls");
        let mut bad = xls_fixture();
        // DIMENSIONS: type 0x0200, 14 bytes: first row, last row + 1 (u32),
        // first column, last column + 1 (u16).
        let at = bad.windows(4).position(|w| w == [0x00, 0x02, 0x0E, 0x00]).unwrap() + 4;
        bad[at + 4..at + 8].copy_from_slice(&1_000_000u32.to_le_bytes());
        std::fs::write(&path, &bad).unwrap();
        let e = crate::sheet::read_workbook(&path).unwrap_err().to_string();
        assert!(e.contains("spans 1000000 rows x 4 columns, more than the 2000000 cells"), "{e}");
    }

    /// Found by the chart_workbook fuzz target:
    /// - a compound file cut short inside a sector (calamine panicked on it);
    /// - one whose sector table lies in its last sector, cut short: calamine
    ///   read the part there and, for sectors past the end, zeros, in a chain
    ///   that never ended, until the allocation failed.
    ///
    /// Both are refused by the container check. A sheet whose BoundSheet8
    /// record places it past the end of the workbook stream still makes
    /// calamine slice past it and panic; the guard around calamine turns that
    /// into an error naming the file.
    #[test]
    fn an_xls_file_cut_short_is_refused() {
        let e = crate::sheet::read_workbook(&chart_fixture("damaged-cut-short.xls")).unwrap_err().to_string();
        assert!(e.contains("damaged-cut-short.xls: it is cut short: 1897 bytes"), "{e}");
        let e = crate::sheet::read_workbook(&chart_fixture("damaged-partial-sector.xls")).unwrap_err().to_string();
        assert!(e.contains("damaged-partial-sector.xls: it is cut short: 5100 bytes"), "{e}");
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.xls");
        let mut bad = xls_fixture();
        // The fixture's BoundSheet8 record (type 0x0085, 17 bytes: the sheet's
        // position, then its state, type and name).
        let at = bad.windows(4).position(|w| w == [0x85, 0x00, 0x11, 0x00]).unwrap() + 4;
        assert_eq!(bad[at..at + 4], 1024u32.to_le_bytes());
        bad[at..at + 4].copy_from_slice(&0x00FF_FFFFu32.to_le_bytes());
        std::fs::write(&path, &bad).unwrap();
        let e = crate::sheet::read_workbook(&path).unwrap_err().to_string();
        assert!(e.contains("chart.xls: the workbook reader (calamine) failed on damaged data"), "{e}");
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
}
