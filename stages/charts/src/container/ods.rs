//! An ODS workbook's `content.xml`, checked before calamine reads it:
//! well-formed, and the cells and text its repeat attributes make within
//! bounds (see [the container module](super)).

use super::MAX_UNPACKED_BYTES;
use crate::sheet::MAX_CELLS;
use quick_xml::events::{BytesStart, Event};

/// calamine's caps on an ODS sheet's columns and rows (its `ods.rs`).
const ODS_MAX_COLUMNS: u64 = 16_384;
const ODS_MAX_ROWS: u64 = 1_048_576;

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
pub(super) fn check_content(
    xml: &mut impl std::io::BufRead,
) -> std::result::Result<std::result::Result<(), String>, ()> {
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
    use super::super::ods_of;
    use std::path::Path;

    /// `content.xml` of one sheet "Chart" whose rows are `rows` (XML).
    fn content(rows: &str) -> String {
        format!(
            r#"<?xml version="1.0" encoding="UTF-8"?>
<office:document-content xmlns:office="urn:oasis:names:tc:opendocument:xmlns:office:1.0" xmlns:table="urn:oasis:names:tc:opendocument:xmlns:table:1.0" xmlns:text="urn:oasis:names:tc:opendocument:xmlns:text:1.0" office:version="1.2"><office:body><office:spreadsheet><table:table table:name="Chart">{rows}</table:table></office:spreadsheet></office:body></office:document-content>"#
        )
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
            ..Default::default()
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

    /// A sheet's name holding a line break (XML's `&#10;`) is kept without
    /// it: it names the sheet's configuration in the run's lines.
    #[test]
    fn a_sheet_name_with_a_line_break_is_kept_on_one_line() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("chart.ods");
        ods_of(&path, &content(&libreoffice_chart()).replace(r#"table:name="Chart""#, r#"table:name="Main&#10;boom""#));
        let sheets = crate::sheet::read_workbook(&path).unwrap();
        assert_eq!(sheets[0].name, "Main\u{FFFD}boom");
        // A table naming the sheet as the file does meets it.
        let table = crate::TableMapping {
            file: "chart.ods".into(),
            sheet: "Main\nboom".into(),
            config: "mapped".into(),
            across: "B3:C3".into(),
            down: "A4:A6".into(),
            transposed: false,
            length_unit: None,
            capacity_unit: None,
        };
        let s = crate::Settings { table: vec![table], ..Default::default() };
        let (configs, _) = crate::read_chart(&path, &s).unwrap();
        assert_eq!(configs.iter().map(|c| c.name.as_str()).collect::<Vec<_>>(), ["mapped"]);
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
}
