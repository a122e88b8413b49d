//! A compound file (the container of xls files, and of encrypted xlsx and
//! xlsb ones), checked before calamine reads it: whole sectors, sector tables
//! whose every chain ends inside the file, and sheets' used ranges and cells
//! within bounds (see [the container module](super)).

use crate::sheet::MAX_CELLS;

pub(super) const SIGNATURE: [u8; 8] = [0xD0, 0xCF, 0x11, 0xE0, 0xA1, 0xB1, 0x1A, 0xE1];

/// CFB sector ids from here up are markers (free, end of chain, table
/// sectors), not links.
const CFB_MAX_LINK: u32 = 0xFFFF_FFFA;
const CFB_END_OF_CHAIN: u32 = 0xFFFF_FFFE;

fn le_u16(b: &[u8], o: usize) -> u16 {
    u16::from_le_bytes([b[o], b[o + 1]])
}

fn le_u32(b: &[u8], o: usize) -> u32 {
    u32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]])
}

/// The 4-byte little-endian entries of a sector of a table.
fn entries(sector: &[u8]) -> impl Iterator<Item = u32> + '_ {
    sector.chunks_exact(4).map(|c| le_u32(c, 0))
}

/// Checks a compound file's sector table (FAT) and mini sector table: every
/// link must stay inside its table and every chain must end, so that calamine,
/// which follows a chain as long as it goes on, reads at most the file.
/// A file that is not a compound file passes (calamine reports it).
pub(super) fn check(bytes: &[u8]) -> std::result::Result<(), String> {
    if bytes.len() < 512 || bytes[..8] != SIGNATURE {
        return Ok(());
    }
    let sector_size = match le_u16(bytes, 30) {
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
    let mut file = CompoundFile { bytes, sector_size, fat: Vec::new(), mini: Vec::new() };
    // The table's own sectors: 109 in the header, then a chain of DIFAT
    // sectors (each a list and a link to the next), bounded by the file.
    let mut fat_sectors: Vec<u32> = entries(&bytes[76..76 + 4 * 109]).collect();
    let mut difat = le_u32(bytes, 68);
    let mut walked = 0;
    while difat < CFB_MAX_LINK {
        walked += 1;
        let Some(s) = file.sector(difat).filter(|_| walked <= sectors) else {
            return Err("its DIFAT chain loops or leaves the file; the workbook is damaged".into());
        };
        let n = sector_size / 4;
        fat_sectors.extend(entries(s).take(n - 1));
        difat = le_u32(s, 4 * (n - 1));
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
    file.fat = fat_sectors.iter().filter_map(|id| file.sector(*id)).flat_map(entries).collect();
    check_chains(&file.fat).map_err(|m| format!("its sector table {m}; the workbook is damaged"))?;
    // The mini sector table is a stream itself, a chain in the table above.
    let mut mini = Vec::new();
    let mut at = le_u32(bytes, 60);
    while at < CFB_MAX_LINK {
        let Some(s) = file.sector(at) else { break };
        mini.extend(entries(s));
        at = file.fat.get(at as usize).copied().unwrap_or(CFB_END_OF_CHAIN);
    }
    check_chains(&mini).map_err(|m| format!("its mini sector table {m}; the workbook is damaged"))?;
    file.mini = mini;
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
        follow(start, len, &self.fat, |at| {
            self.sector(at).ok_or_else(|| format!("a stream runs into sector {at}, past the file's end"))
        })
    }

    /// The same for a chain of mini sectors in `mini_stream`.
    fn mini_chain(&self, mini_stream: &[u8], start: u32, len: usize) -> std::result::Result<Vec<u8>, String> {
        follow(start, len, &self.mini, |at| {
            let from = at as usize * Self::MINI_SECTOR;
            mini_stream
                .get(from..from + Self::MINI_SECTOR)
                .ok_or_else(|| format!("a stream runs into mini sector {at}, past the mini stream's end"))
        })
    }

    /// A directory entry's stream: its first sector and its length, read as
    /// calamine reads them (a 64-bit length in files of 4096-byte sectors).
    fn start_and_len(&self, entry: &[u8]) -> (u32, usize) {
        let len = if self.sector_size == 512 {
            le_u32(entry, 120) as usize
        } else {
            u64::from_le_bytes(entry[120..128].try_into().unwrap_or([0; 8])) as usize
        };
        (le_u32(entry, 116), len)
    }

    /// The stream named `name` (ASCII, any case), as calamine finds it: the
    /// first directory entry of that name.
    fn stream(&self, dir: &[u8], name: &str) -> std::result::Result<Option<Vec<u8>>, String> {
        let dir_entries: Vec<&[u8]> = dir.chunks_exact(128).collect();
        let entry_name = |e: &[u8]| -> Vec<u8> {
            let units: Vec<u16> = e[..64].chunks_exact(2).map(|c| le_u16(c, 0)).collect();
            String::from_utf16_lossy(&units).bytes().take_while(|b| *b != 0).collect()
        };
        let Some(e) = dir_entries.iter().find(|e| entry_name(e).eq_ignore_ascii_case(name.as_bytes())) else {
            return Ok(None);
        };
        let (start, len) = self.start_and_len(e);
        if len >= Self::MINI_CUTOFF {
            return self.chain(start, len).map(Some);
        }
        // The mini stream is the root entry's stream.
        let (root_start, root_len) = self.start_and_len(dir_entries[0]);
        let mini_stream = self.chain(root_start, root_len)?;
        self.mini_chain(&mini_stream, start, len).map(Some)
    }
}

/// The first `len` bytes of the chain from `start` through `table` (entry k:
/// the sector after k), each sector's bytes from `sector`. A link past the
/// table ends the chain here; it panics calamine, whose guard reports that.
fn follow<'a>(
    start: u32,
    len: usize,
    table: &[u32],
    sector: impl Fn(u32) -> std::result::Result<&'a [u8], String>,
) -> std::result::Result<Vec<u8>, String> {
    let mut out = Vec::new();
    let mut at = start;
    while at != CFB_END_OF_CHAIN && out.len() < len {
        let s = sector(at)?;
        out.extend_from_slice(&s[..s.len().min(len - out.len())]);
        at = table.get(at as usize).copied().unwrap_or(CFB_END_OF_CHAIN);
    }
    Ok(out)
}

/// The used ranges (DIMENSIONS records) of an xls file's sheets, which
/// calamine reserves cells for before it reads any: a DIMENSIONS record of
/// 14 bytes claiming four billion rows made it ask for 687 GB (found by the
/// chart_workbook fuzz target). Each must be within [`MAX_CELLS`] cells, as
/// calamine computes them (wrapping, as its release build does). The records
/// are looked for where calamine reads them: the workbook globals, and each
/// sheet from the position its BoundSheet8 record gives.
///
/// Then the cells themselves: calamine makes each sheet one dense range
/// spanning every cell record it read, and a cell's row and column are any
/// 16-bit numbers, so two cells of a 5 kB file, at A1 and at row 65,536 of
/// column 65,536, made it ask for 137 GB. Each sheet's cells must span at
/// most [`MAX_CELLS`] cells.
fn check_xls_used_ranges(file: &CompoundFile) -> std::result::Result<(), String> {
    let dir_start = le_u32(file.bytes, 48);
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
    check_workbook_stream(&stream)
}

/// [`check_xls_used_ranges`] on the workbook stream: the globals from its
/// start, then each sheet from its BoundSheet8 position.
fn check_workbook_stream(stream: &[u8]) -> std::result::Result<(), String> {
    let sheets = check_globals(stream)?;
    // calamine reads every sheet when it opens the file, and keeps them all.
    let (mut all, mut read) = (0u64, 0usize);
    for (k, (pos, name)) in sheets.iter().enumerate() {
        let sheet = match name {
            Some(name) => format!("sheet '{name}'"),
            None => format!("sheet {}", k + 1),
        };
        let (cells, bytes) = check_sheet(stream, *pos, &sheet)?;
        // Each sheet is read from its position to its EOF record, here and
        // by calamine; sheets that overlap would cost the stream's length
        // once per sheet.
        read += bytes;
        if read > 2 * stream.len() {
            return Err(format!(
                "{sheet} starts at offset {pos} of the {}-byte workbook stream, and its first {} sheets' records \
                 add up to more than twice the stream: its sheets overlap",
                stream.len(),
                k + 1
            ));
        }
        all += cells;
        if all > MAX_CELLS as u64 {
            return Err(format!(
                "its first {} sheets' cells span {all} cells in all, more than the {MAX_CELLS} cells a load chart \
                 workbook may have",
                k + 1
            ));
        }
    }
    Ok(())
}

/// Walks the workbook stream's records from its start: refuses a used range
/// over [`MAX_CELLS`] cells anywhere on the way ([`check_used_range`]) and
/// returns the BoundSheet8 records (position and, where it reads as one,
/// name).
fn check_globals(stream: &[u8]) -> std::result::Result<Vec<(usize, Option<String>)>, String> {
    let mut sheets = Vec::new();
    for (typ, data) in records(stream, 0) {
        match (typ, data.len()) {
            (0x0085, 4..) => sheets.push((le_u32(data, 0) as usize, bound_sheet_name(data))),
            (0x0200, _) => check_used_range(data)?,
            _ => {}
        }
    }
    Ok(sheets)
}

/// A DIMENSIONS record's used range, which calamine reserves cells for, must
/// be within [`MAX_CELLS`] cells as calamine computes them (wrapping, as its
/// release build does). Records of other lengths calamine refuses.
fn check_used_range(data: &[u8]) -> std::result::Result<(), String> {
    let u16_at = |o: usize| le_u16(data, o) as u32;
    let (rf, rl, cf, cl) = match data.len() {
        10 => (u16_at(0), u16_at(2), u16_at(4), u16_at(6)),
        14 | 16 => (le_u32(data, 0), le_u32(data, 4), u16_at(8), u16_at(10)),
        _ => return Ok(()),
    };
    let cf = if 0xFF < cf || cl < cf { 0 } else { cf };
    let (rows, cols) = if rl >= 1 && cl >= 1 {
        ((rl - 1).wrapping_sub(rf).wrapping_add(1), (cl - 1).wrapping_sub(cf).wrapping_add(1))
    } else {
        (1, 1)
    };
    if rows as u64 * cols as u64 > MAX_CELLS as u64 {
        return Err(format!(
            "a sheet's used range (its DIMENSIONS record) spans {rows} rows x {cols} columns, more than the \
             {MAX_CELLS} cells a load chart may have"
        ));
    }
    Ok(())
}

/// The BIFF records (type, data) of `stream` from `pos`, as calamine splits
/// them; a CONTINUE record is one of its own here (calamine appends it to the
/// record before, whose data, read here, it leaves as it is).
fn records(stream: &[u8], pos: usize) -> impl Iterator<Item = (u16, &[u8])> {
    let mut rest = stream.get(pos..).unwrap_or_default();
    std::iter::from_fn(move || {
        if rest.len() < 4 {
            return None;
        }
        let (typ, len) = (le_u16(rest, 0), le_u16(rest, 2) as usize);
        let data = rest.get(4..4 + len)?;
        rest = &rest[4 + len..];
        Some((typ, data))
    })
}

/// A BoundSheet8 record's sheet name, if it reads as a BIFF8 short string
/// (a count, a flag byte of 0 or 1, the characters).
fn bound_sheet_name(data: &[u8]) -> Option<String> {
    let (&chars, &flags) = (data.get(6)?, data.get(7)?);
    if flags > 1 {
        return None;
    }
    let name = if flags == 0 {
        data.get(8..8 + chars as usize)?.iter().map(|&b| b as char).collect()
    } else {
        let units: Vec<u16> = data.get(8..8 + 2 * chars as usize)?.chunks_exact(2).map(|c| le_u16(c, 0)).collect();
        String::from_utf16(&units).ok()?
    };
    Some(name)
}

/// Walks the records of `sheet` (a name for messages) from `pos` to its EOF
/// record, as calamine reads them: the cells it reads must span at most
/// [`MAX_CELLS`] cells, and the used ranges it reads are checked
/// ([`check_used_range`]). Returns how many cells the sheet's cells span (the
/// dense range calamine makes of them) and how many bytes of the stream the
/// walk read.
///
/// Nested substreams (an embedded chart) are skipped, the sheet's EOF record
/// ends the walk, and every record calamine makes a cell (or a formula) of
/// counts, at the row and columns it reads. A record too short for its cell
/// counts where its first four bytes place it (calamine refuses it; counting
/// it only refuses more).
fn check_sheet(stream: &[u8], pos: usize, sheet: &str) -> std::result::Result<(u64, usize), String> {
    let (mut rows, mut cols) = ((u32::MAX, 0u32), (u32::MAX, 0u32));
    let mut span = |row: u32, first: u32, last: u32| {
        rows = (rows.0.min(row), rows.1.max(row));
        cols = (cols.0.min(first), cols.1.max(last));
    };
    let (mut seen_bof, mut depth) = (false, 0usize);
    let mut formula_at = (0u32, 0u32);
    let mut read = 0;
    for (typ, data) in records(stream, pos) {
        read += 4 + data.len();
        if depth > 0 {
            match typ {
                0x0809 => depth += 1,
                0x000A => depth -= 1,
                _ => {}
            }
            continue;
        }
        let at = || (data.len() >= 4).then(|| (le_u16(data, 0) as u32, le_u16(data, 2) as u32));
        match typ {
            0x0809 if seen_bof => depth += 1,
            0x0809 => seen_bof = true,
            0x000A => break,
            0x0200 => check_used_range(data)?,
            // Number, Label, RString, BoolErr, Rk, LabelSst.
            0x0203 | 0x0204 | 0x00D6 | 0x0205 | 0x027E | 0x00FD => {
                if let Some((row, col)) = at() {
                    span(row, col, col);
                }
            }
            // Formula: a formula cell, and the place of a String record after it.
            0x0006 => {
                if let Some(place) = at() {
                    formula_at = place;
                    span(place.0, place.1, place.1);
                }
            }
            0x0207 => span(formula_at.0, formula_at.1, formula_at.1),
            // MulRk: a row of cells from the first column, six bytes each.
            0x00BD => {
                if let (Some((row, first)), true) = (at(), data.len() >= 12) {
                    span(row, first, first + (data.len() as u32 - 6) / 6 - 1);
                }
            }
            _ => {}
        }
    }
    if rows.0 > rows.1 {
        return Ok((0, read));
    }
    let (height, width) = ((rows.1 - rows.0 + 1) as u64, (cols.1 - cols.0 + 1) as u64);
    if height * width > MAX_CELLS as u64 {
        return Err(format!(
            "{sheet} has cells from {} to {}: {height} rows x {width} columns, more than the {MAX_CELLS} cells a \
             load chart may have",
            liftplan_core::location::cell_ref(rows.0, cols.0),
            liftplan_core::location::cell_ref(rows.1, cols.1),
        ));
    }
    Ok((height * width, read))
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

#[cfg(test)]
mod tests {
    use super::{check_sheet, check_workbook_stream};
    use std::path::Path;

    fn chart_fixture(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/charts").join(name)
    }

    /// `fixtures/charts/chart.xls` (xlwt's BIFF8 in a compound file).
    fn xls_fixture() -> Vec<u8> {
        std::fs::read(chart_fixture("chart.xls")).unwrap()
    }

    /// The error of reading `bytes` as a workbook named `chart.xls`.
    fn refusal(bytes: &[u8]) -> String {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.xls");
        std::fs::write(&path, bytes).unwrap();
        crate::sheet::read_workbook(&path).unwrap_err().to_string()
    }

    /// The xls fixture with its directory's link (the sector after the
    /// directory's first, in the sector table) set to `next`; and the first
    /// sector of the table.
    fn xls_with_directory_link(next: impl FnOnce(u32) -> u32) -> (Vec<u8>, u32) {
        let mut bytes = xls_fixture();
        assert_eq!(super::le_u16(&bytes, 30), 9, "512-byte sectors");
        let (fat0, dir) = (super::le_u32(&bytes, 76), super::le_u32(&bytes, 48));
        let entry = (fat0 as usize + 1) * 512 + 4 * dir as usize;
        bytes[entry..entry + 4].copy_from_slice(&next(dir).to_le_bytes());
        (bytes, fat0)
    }

    #[test]
    fn an_xls_chart_is_read() {
        let (configs, _) = crate::read_chart(&chart_fixture("chart.xls"), &crate::Settings::default()).unwrap();
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
        let mut bad = xls_fixture();
        // DIMENSIONS: type 0x0200, 14 bytes: first row, last row + 1 (u32),
        // first column, last column + 1 (u16).
        let at = bad.windows(4).position(|w| w == [0x00, 0x02, 0x0E, 0x00]).unwrap() + 4;
        bad[at + 4..at + 8].copy_from_slice(&1_000_000u32.to_le_bytes());
        let e = refusal(&bad);
        assert!(e.contains("spans 1000000 rows x 4 columns, more than the 2000000 cells"), "{e}");
    }

    /// Two cells of the 5.6 kB fixture, at A1 and at row 65,536 of column
    /// 65,536 (one LabelSst record's row and column changed): calamine made
    /// its sheet one dense range of 2^32 cells and asked for 137 GB, which
    /// aborted liftplan. Refused, naming the sheet and the cells' span.
    #[test]
    fn an_xls_sheet_whose_cells_lie_far_apart_is_refused() {
        let mut bad = xls_fixture();
        // LabelSst: type 0x00FD, 10 bytes: row, column (u16), format, string.
        let at = bad.windows(4).rposition(|w| w == [0xFD, 0x00, 0x0A, 0x00]).unwrap() + 4;
        bad[at..at + 4].copy_from_slice(&[0xFF; 4]);
        let e = refusal(&bad);
        assert!(
            e.contains(
                "chart.xls: sheet 'Main boom' has cells from A1 to CRXP65536: 65536 rows x 65536 columns, more than \
                 the 2000000 cells"
            ),
            "{e}"
        );
    }

    /// BIFF records as bytes: (type, data) each.
    fn biff(records: &[(u16, Vec<u8>)]) -> Vec<u8> {
        let mut out = Vec::new();
        for (typ, data) in records {
            out.extend_from_slice(&typ.to_le_bytes());
            out.extend_from_slice(&(data.len() as u16).to_le_bytes());
            out.extend_from_slice(data);
        }
        out
    }

    /// A cell record's data: row, column, then `rest` zero bytes.
    fn cell(row: u16, col: u16, rest: usize) -> Vec<u8> {
        let mut d = [row.to_le_bytes(), col.to_le_bytes()].concat();
        d.resize(4 + rest, 0);
        d
    }

    /// A BoundSheet8 record: the sheet's position, state, type, then its name
    /// (a count, a flag byte: 8-bit characters, the characters).
    fn bound_sheet(pos: u32, name: &str) -> (u16, Vec<u8>) {
        let mut d = pos.to_le_bytes().to_vec();
        d.extend_from_slice(&[0, 0, name.len() as u8, 0]);
        d.extend_from_slice(name.as_bytes());
        (0x0085, d)
    }

    /// A workbook stream: the globals list a sheet per name, and the sheets,
    /// each `sheet`, follow one after another.
    fn workbook(sheet: &[u8], names: &[String]) -> Vec<u8> {
        let (bof, eof) = ((0x0809u16, vec![0u8; 16]), (0x000Au16, vec![]));
        let start = biff(&[bof.clone(), eof.clone()]).len() + names.iter().map(|n| 4 + 8 + n.len()).sum::<usize>();
        let mut records = vec![bof];
        let mut at = start;
        for name in names {
            records.push(bound_sheet(at as u32, name));
            at += sheet.len();
        }
        records.push(eof);
        let mut stream = biff(&records);
        assert_eq!(stream.len(), start);
        stream.extend(sheet.repeat(names.len()));
        stream
    }

    /// The sheet walk counts what calamine reads and nothing else: cells in
    /// an embedded chart's substream and after the sheet's EOF record do not
    /// count; a MulRk row counts every column it fills; a String record
    /// counts at the formula before it.
    #[test]
    fn an_xls_sheet_s_cells_are_counted_as_calamine_reads_them() {
        let (bof, eof) = ((0x0809u16, vec![0u8; 16]), (0x000Au16, vec![]));
        let far = (0x0203u16, cell(60_000, 200, 10));
        let sheet = |cells: Vec<(u16, Vec<u8>)>| {
            let mut r = vec![bof.clone(), (0x0203, cell(0, 0, 10))];
            r.extend(cells);
            r.push(eof.clone());
            r.push(far.clone());
            biff(&r)
        };
        // An embedded chart holding a far cell, skipped as calamine skips it.
        let nested = sheet(vec![bof.clone(), far.clone(), bof.clone(), eof.clone(), far.clone(), eof.clone()]);
        assert_eq!(check_sheet(&nested, 0, "sheet").map(|(cells, _)| cells), Ok(1));
        let near = sheet(vec![(0x00FD, cell(1999, 999, 6))]);
        assert_eq!(check_sheet(&near, 0, "sheet").map(|(cells, _)| cells), Ok(2000 * 1000));
        let e = check_sheet(&sheet(vec![far.clone()]), 0, "sheet").unwrap_err();
        assert!(e.starts_with("sheet has cells from A1 to GS60001: 60001 rows x 201 columns"), "{e}");
        // MulRk of three cells from column 700 (the last two bytes name the
        // last column).
        let mul_rk = (0x00BD, cell(2999, 700, 3 * 6 + 2));
        let e = check_sheet(&sheet(vec![mul_rk]), 0, "sheet").unwrap_err();
        assert!(e.contains("3000 rows x 703 columns"), "{e}");
        let string_after_formula = vec![(0x0006, cell(4000, 600, 20)), (0x0207, vec![0; 4])];
        let e = check_sheet(&sheet(string_after_formula), 0, "sheet").unwrap_err();
        assert!(e.contains("4001 rows x 601 columns"), "{e}");
    }

    /// calamine keeps every sheet's dense range once it has opened the file:
    /// two sheets of 1.2 M cells each pass one by one but not together.
    #[test]
    fn an_xls_workbook_s_sheets_count_together() {
        let (bof, eof) = ((0x0809u16, vec![0u8; 16]), (0x000Au16, vec![]));
        let sheet = biff(&[bof.clone(), (0x0203, cell(0, 0, 10)), (0x0203, cell(1199, 999, 10)), eof.clone()]);
        let booms = |n: usize| (0..n).map(|k| format!("Boom{k}")).collect::<Vec<_>>();
        assert_eq!(check_workbook_stream(&workbook(&sheet, &booms(1))), Ok(()));
        let e = check_workbook_stream(&workbook(&sheet, &booms(2))).unwrap_err();
        assert!(e.contains("its first 2 sheets' cells span 2400000 cells in all, more than the 2000000"), "{e}");
        // One sheet over the limit is named.
        let wide = biff(&[bof.clone(), (0x0203, cell(0, 0, 10)), (0x0203, cell(2000, 999, 10)), eof.clone()]);
        let e = check_workbook_stream(&workbook(&wide, &["Main boom".to_string()])).unwrap_err();
        assert!(e.starts_with("sheet 'Main boom' has cells from A1 to ALL2001"), "{e}");
    }

    /// Every sheet's records are read from its BoundSheet8 position to its
    /// EOF record, by this check and then by calamine. A workbook whose many
    /// sheets all start at one place and never end made both read the whole
    /// stream once per sheet: 20,000 sheets over a 1 MB stream are 20 GB of
    /// records. Refused once the sheets' records add up to more than twice
    /// the stream (a workbook's sheets lie one after another).
    #[test]
    fn an_xls_workbook_whose_sheets_overlap_is_refused() {
        let bof = (0x0809u16, vec![0u8; 16]);
        // No EOF anywhere: every sheet, at the stream's start, reads to its end.
        let mut records = vec![bof.clone()];
        records.extend((0..20_000).map(|_| bound_sheet(0, "S")));
        records.extend((0..100_000).map(|_| (0x0001u16, vec![0u8; 6])));
        let stream = biff(&records);
        let e = check_workbook_stream(&stream).unwrap_err();
        assert!(
            e.starts_with(
                "sheet 'S' starts at offset 0 of the 1260020-byte workbook stream, and its first 3 sheets' records \
                 add up to more than twice the stream: its sheets overlap"
            ),
            "{e}"
        );
        // Sheets one after another, each with an EOF, pass however many.
        let sheet = biff(&[bof, (0x0203, cell(0, 0, 10)), (0x000A, vec![])]);
        assert_eq!(check_workbook_stream(&workbook(&sheet, &vec!["S".to_string(); 5_000])), Ok(()));
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
        let mut bad = xls_fixture();
        // The fixture's BoundSheet8 record (type 0x0085, 17 bytes: the sheet's
        // position, then its state, type and name).
        let at = bad.windows(4).position(|w| w == [0x85, 0x00, 0x11, 0x00]).unwrap() + 4;
        assert_eq!(bad[at..at + 4], 1024u32.to_le_bytes());
        bad[at..at + 4].copy_from_slice(&0x00FF_FFFFu32.to_le_bytes());
        let e = refusal(&bad);
        assert!(e.contains("chart.xls: the workbook reader (calamine) failed on damaged data"), "{e}");
    }
}
